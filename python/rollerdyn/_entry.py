"""The ``rollerdyn`` command's entry point: imports the command line (and with it the
heavy libraries) inside the handler of Ctrl-C, so that an interruption at any phase,
even while Python starts, ends with one line and status 130, never a traceback. A run
interrupted later writes what it computed first and says so (``rollerdyn run``)."""

from __future__ import annotations

import signal
import sys

#: Set by a Ctrl-C during the imports. CPython drops a KeyboardInterrupt raised inside
#: some of its own callbacks (an import lock's weakref callback prints "Exception
#: ignored" and the command ran on to its end; seen at 50 ms after the start), so the
#: signal is also recorded here and checked once the imports are done.
_ctrl_c_seen = False


def _record_ctrl_c(signum: int, frame: object) -> None:
    global _ctrl_c_seen
    _ctrl_c_seen = True
    raise KeyboardInterrupt


def _from_ctrl_c(exit_: SystemExit) -> bool:
    """Whether typer ended the command because of a KeyboardInterrupt that no command
    handled itself (typer turns it silently into exit status 130)."""
    context = exit_.__context__
    return exit_.code == 130 and isinstance(getattr(context, "__cause__", None), KeyboardInterrupt)


def main() -> None:
    """Runs the command line; Ctrl-C outside the commands' own handlers exits 130 with one
    line."""
    signal.signal(signal.SIGINT, _record_ctrl_c)
    try:
        from .cli import app

        if _ctrl_c_seen:
            raise KeyboardInterrupt
        signal.signal(signal.SIGINT, signal.default_int_handler)
        app()
    except KeyboardInterrupt:
        print("rollerdyn: interrupted", file=sys.stderr)
        sys.exit(130)
    except SystemExit as exit_:
        if _from_ctrl_c(exit_):
            print("rollerdyn: interrupted", file=sys.stderr)
        raise
