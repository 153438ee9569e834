"""Studies: many runs of one configuration, on Dask, with what they show.

- :func:`paper` (``rollerdyn study paper``): the runs behind the paper's sect. 5 (figs.
  8-14), its findings checked on them (PASS / FAIL / NOT RUN with the numbers behind
  each), the figures and one HTML report.
- :func:`operating_map` (``rollerdyn study map``): a grid of speeds and loads, each point
  run until its outputs are steady, with maps of friction torque, roller-set speed loss
  and largest flange force.

Both are resumable: a run whose file holds it to its end is not run again, one stopped
(wall-time cap, killed worker, Ctrl-C) continues from its last checkpoint. Bad input
raises :class:`StudyError` (a ``ValueError``) naming the option, before any run. See
``docs/study.md``.
"""

from __future__ import annotations

from .findings import FAIL, NOT_RUN, PASS, Finding
from .maps import MapStudy, operating_map, parse_range
from .paper import PaperStudy, paper
from .runs import StudyError

__all__ = [
    "FAIL",
    "NOT_RUN",
    "PASS",
    "Finding",
    "MapStudy",
    "PaperStudy",
    "StudyError",
    "operating_map",
    "paper",
    "parse_range",
]
