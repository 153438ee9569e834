"""Preloaded into each worker process of the local Dask cluster that ``rollerdyn sweep``
and ``rollerdyn study`` start (:func:`rollerdyn.sweep.connect`): the worker ignores Ctrl-C.

A Ctrl-C in the terminal reaches the whole foreground process group, the workers too. The
command itself handles it (it writes its summary and closes the cluster, which ends the
workers); a worker that took it as well would print a KeyboardInterrupt traceback of
Dask's event loop.
"""

from __future__ import annotations

import signal
from typing import Any


def dask_setup(worker: Any) -> None:
    """Dask's preload hook, run in the worker process's main thread at its start."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
