"""The ``rollerdyn`` command's entry point: Ctrl-C at any moment of the start ends the
command with one line, "rollerdyn: interrupted", and status 130, never a traceback. A run
interrupted later writes what it computed first and says so (``rollerdyn run``).

Ctrl-C in three phases:

1. From the start of :func:`main` until the command line is imported (typer and rich,
   about 0.2 s; the commands load the heavy libraries when they run), nothing has been
   done that would need undoing: the handler writes the line and ends the process at once
   (:func:`_exit_interrupted`). It raises nothing, because a KeyboardInterrupt raised at
   an arbitrary point of the imports can land in one of CPython's own callbacks (an import
   lock's weakref callback), where CPython prints it as "Exception ignored in ..." with a
   traceback and drops it (seen at 50 ms after the start).
2. From then on, while a command has no handler of its own (importing the libraries it
   needs, reading the configuration, building the model), Ctrl-C is Python's
   KeyboardInterrupt: typer ends with status 130 and :func:`main` prints the line. One
   that CPython drops in such a callback is not printed but raised again once the
   callback has returned (:func:`_redeliver`).
3. A command's own handling takes over where it has one (``rollerdyn run`` writes what
   the run computed).

SIGTERM (``kill``, ``timeout``, a batch system) where no command takes it as Ctrl-C ends
the process as Python's default would, at once, but with the line "rollerdyn: terminated"
and status 143 (:func:`_exit_terminated`): during the start, the same on a slow or a busy
machine.

Before :func:`main` runs (Python's own start, ``import rollerdyn`` and this module, about
30 ms), a Ctrl-C is Python's: a traceback, or none at all in its first milliseconds.
"""

from __future__ import annotations

import os
import sys

# The C module behind ``signal``: ``signal`` itself imports enum (about 10 ms of the start,
# in which a Ctrl-C would still be Python's own traceback). Type checkers read ``signal``.
TYPE_CHECKING = False
if TYPE_CHECKING:
    import signal
else:
    import _signal as signal

#: The hook that reports exceptions CPython cannot raise, as it was before :func:`main`.
_usual_unraisablehook = sys.unraisablehook


def _exit_interrupted(signum: int, frame: object) -> None:
    """Ctrl-C during the imports: the line, and the process ends (nothing to undo yet)."""
    os.write(2, b"rollerdyn: interrupted\n")
    os._exit(130)


def _exit_terminated(signum: int, frame: object) -> None:
    """SIGTERM where no command handles it: the line, and the process ends at once (as with
    Python's default, which ended it by the signal, status -15 to a caller and no word)."""
    os.write(2, b"rollerdyn: terminated\n")
    os._exit(143)


def _redeliver(unraisable: sys.UnraisableHookArgs) -> None:
    """``sys.unraisablehook`` while a command runs: a KeyboardInterrupt that CPython could
    not raise (it came in a weakref callback or a ``__del__``) is raised again in the main
    thread a moment later, once the callback has returned; anything else is reported as
    usual."""
    if not isinstance(unraisable.exc_value, KeyboardInterrupt):
        _usual_unraisablehook(unraisable)
        return
    import _thread
    import threading
    import time

    def interrupt_soon() -> None:
        time.sleep(0.005)
        _thread.interrupt_main()  # as a Ctrl-C: the main thread raises KeyboardInterrupt

    threading.Thread(target=interrupt_soon, daemon=True).start()


def _from_ctrl_c(exit_: SystemExit) -> bool:
    """Whether typer ended the command because of a KeyboardInterrupt that no command
    handled itself (typer turns it silently into exit status 130)."""
    context = exit_.__context__
    return exit_.code == 130 and isinstance(getattr(context, "__cause__", None), KeyboardInterrupt)


def main() -> None:
    """Runs the command line; Ctrl-C outside the commands' own handlers exits 130 with one
    line; SIGTERM outside the commands' own handlers exits 143 with one line."""
    signal.signal(signal.SIGINT, _exit_interrupted)
    signal.signal(signal.SIGTERM, _exit_terminated)
    from .cli import app

    sys.unraisablehook = _redeliver
    signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        app()
    except KeyboardInterrupt:
        print("rollerdyn: interrupted", file=sys.stderr)
        sys.exit(130)
    except SystemExit as exit_:
        if _from_ctrl_c(exit_):
            print("rollerdyn: interrupted", file=sys.stderr)
        raise
