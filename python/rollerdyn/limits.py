"""Defaults that the command line shows in its options, in a module that imports nothing:
the command line reads them before it loads the heavy libraries (``rollerdyn --help``
takes a fraction of a second), and the modules that use them take them from here."""

from __future__ import annotations

MAX_FRAMES = 200
"""Most frames of the roller-set animation; longer runs are subsampled evenly."""

DEFAULT_MAX_WALL = 600.0
"""Wall-time cap of one run of a study [s] (per invocation of the study)."""
