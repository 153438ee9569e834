"""Studies: many runs of one configuration, on Dask, with what they show.

- :func:`paper` (``rollerdyn study paper``): the runs behind the paper's sect. 5 (figs.
  8-14), its findings checked on them (PASS / FAIL / NOT RUN with the numbers behind
  each), the figures and one HTML report.
- :func:`operating_map` (``rollerdyn study map``): a grid of speeds, loads and oil
  temperatures, each point run until its outputs are steady, with maps of friction
  torque, roller-set speed loss and largest flange force, and with a heat dissipation
  the thermal balance (:mod:`.thermal`).

Both are resumable: a run whose file holds it to its end is not run again, one stopped
(wall-time cap, killed worker, Ctrl-C) continues from its last checkpoint. Bad input
raises :class:`StudyError` (a ``ValueError``) naming the option, before any run. See
``docs/study.md``.

The modules: :mod:`.plan` (which runs), :mod:`.runs` (one run as a Dask task, its file's
state), :mod:`.schedule` (the runs on Dask, progress), :mod:`.folder` (the study folder),
:mod:`.findings` (the checks), :mod:`.figures` and :mod:`.report_page` (figures, report),
:mod:`.paper`, :mod:`.maps`, :mod:`.steady`, :mod:`.map_figures` and :mod:`.thermal`. The
names below are imported when first used, so that the command line starts before the heavy
libraries load.
"""

from __future__ import annotations

import importlib
import sys
import types
from typing import Any

#: Public name -> module that defines it.
_LAZY = {
    "FAIL": ".findings",
    "NOT_RUN": ".findings",
    "PASS": ".findings",
    "Finding": ".findings",
    "MapStudy": ".maps",
    "operating_map": ".maps",
    "parse_range": ".maps",
    "PaperStudy": ".paper",
    "paper": ".paper",
    "StudyError": ".runs",
}


def __getattr__(name: str) -> Any:
    if name in _LAZY:
        value = getattr(importlib.import_module(_LAZY[name], __name__), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'rollerdyn.study' has no attribute {name!r}")


class _Study(types.ModuleType):
    """``rollerdyn.study.paper`` stays the function, though the module ``paper`` exists:
    the import system's binding of a submodule over a public name of :data:`_LAZY` (by
    ``from .paper import ...`` in another module, or ``import rollerdyn.study.paper``) is
    ignored; the submodule stays in ``sys.modules``, where imports find it."""

    def __setattr__(self, name: str, value: Any) -> None:
        if name in _LAZY and isinstance(value, types.ModuleType):
            return
        super().__setattr__(name, value)


sys.modules[__name__].__class__ = _Study

__all__ = sorted(_LAZY)
