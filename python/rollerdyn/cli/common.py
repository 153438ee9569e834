"""What every command of the command line shares: the console, printing text as it is,
refusing bad input with exit status 2, the ``--config``, ``--detector`` and ``--output``
options, time options and loading a configuration.

Every message is printed as plain text (:func:`say`, :func:`error`): text from files and
options is never read as rich markup.
"""

from __future__ import annotations

import contextlib
from collections.abc import Callable, Iterable
from pathlib import Path
from typing import Annotated, Any

import typer
from rich.console import Console
from rich.text import Text

from ..names import DETECTORS, SEMI_ANALYTICAL, one_of
from ..paths import OutputPathError
from ..paths import printable as plain  # text as printable (non-UTF-8 bytes escaped)

# markup=False: text from files and options (a bearing named "B1 [/x]", a file
# "nope[/x].nc") is printed as it is, never read as rich markup; colours are set with
# Text styles.
console = Console(markup=False, width=200 if not Console().is_terminal else None)

ConfigOption = Annotated[
    Path | None,
    typer.Option(
        "--config",
        "-c",
        help="Bearing configuration (TOML) for the B1-specific cases; "
        "default: examples/b1.toml of the source tree.",
    ),
]


def detector_help(default: str) -> str:
    """The help of a ``--detector`` option whose default is ``solver.detector`` of
    ``default`` (e.g. "the configuration")."""
    return (
        f"Roller end / flange detector: {one_of(DETECTORS)}. "
        f"Default: solver.detector of {default} ({SEMI_ANALYTICAL})."
    )


def say(text: object, style: str | None = None, out: Console | None = None) -> None:
    """Prints ``text`` as it is (never as markup), unwrapped: one message, one line."""
    (out or console).print(Text(plain(text), style=style or ""), soft_wrap=True)


def error(text: object, out: Console | None = None) -> None:
    """Prints an error message in red, as it is (never as markup)."""
    say(text, "red", out)


def refuse(text: object, code: int = 2) -> typer.Exit:
    """Prints ``text`` as an error and returns the exit to raise (status 2: bad input)."""
    error(text)
    return typer.Exit(code)


@contextlib.contextmanager
def refusing(bad_input: type[Exception] | tuple[type[Exception], ...], output: Path):
    """Runs the block of a command that writes to the folder ``output`` (``-o``):
    ``bad_input`` (e.g. :class:`rollerdyn.sweep.SweepError`) exits with status 2 and its
    message, an ``OSError`` (a folder that cannot be written) with status 1 naming -o."""
    try:
        yield
    except bad_input as err:
        raise refuse(err) from None
    except OSError as err:
        raise refuse(f"-o {output}: {err}", 1) from None


@contextlib.contextmanager
def quiet_arithmetic():
    """NumPy's warnings about NaN and infinite values (a result that holds them, whose
    numbers show as n/a) kept off the command's output: one line per problem, not
    RuntimeWarnings with source lines."""
    import warnings

    import numpy as np

    with warnings.catch_warnings(), np.errstate(all="ignore"):
        warnings.simplefilter("ignore", RuntimeWarning)
        yield


def output_option(help: str) -> Any:
    """The ``-o``/``--output`` option of a command, with its ``help``."""
    return typer.Option("--output", "-o", help=help)


def checked(check, *args, **kwargs):
    """``check(*args, **kwargs)`` of :mod:`rollerdyn.paths`; its refusal exits with 2."""
    try:
        return check(*args, **kwargs)
    except OutputPathError as err:
        raise refuse(err) from None


def time_option(option: str, text: str | None, zero: bool = False) -> float | None:
    """The value of a time option (``--t-end``) in s: ``"50 ms"``, ``"0.05 s"`` or a bare
    number of seconds (``"0.05"``); None stays None. Exits with status 2 naming the
    option, the value and the rule for anything but a finite time of at least 1 ns
    (``zero``: 0 s; :func:`rollerdyn.units.parse_time`)."""
    from ..units import parse_time

    if text is None:
        return None
    try:
        return parse_time(text, option, zero)
    except ValueError as err:
        raise refuse(err) from None


def check_detector(detector: str | None) -> None:
    """Exits with status 2 unless ``--detector`` is None or names a detector."""
    if detector is not None and detector not in DETECTORS:
        raise refuse(f"--detector = {detector!r}: must be {one_of(DETECTORS)}")


def default_config() -> Path:
    """B1's configuration of the source tree, the commands' default; exits with status 2 and
    one line if the package was installed without it (``pip install`` of a copy)."""
    from ..validation import default_config_path

    try:
        return default_config_path()
    except FileNotFoundError as err:
        raise refuse(err) from None


def load(path: Path, changes: dict[str, Any] | None = None):
    """The configuration in ``path`` with the ``--set`` ``changes`` (:func:`set_options`);
    exits with status 2 and its problems if invalid."""
    from ..config import ConfigError, load_config

    try:
        return load_config(path, changes)
    except ConfigError as err:
        text = str(err)
        error(
            # a file-level error (not found, malformed TOML) on one line with its heading
            text if text.startswith("invalid configuration") else f"invalid configuration: {text}"
        )
        raise typer.Exit(2) from None


#: The help of a command's ``--set`` option that changes one value each.
SET_HELP = (
    "PATH=VALUE: a configuration value changed, written as in the file (e.g. "
    'surfaces.flange_law=distributed, operating.axial_load="500 N", solver.friction=false); '
    "PATH=none removes an optional value, leaving its default (operating.load_ramp=none: "
    "the loads from t = 0); repeat for more."
)


def set_options(options: list[str] | None) -> dict[str, Any]:
    """``--set PATH=VALUE`` options as ``{path: value}`` (values read as in a TOML file);
    exits with status 2 naming a malformed one, one with more than one value, a path given
    twice, or two paths of which one lies inside the other."""
    from ..sweep import SweepError, parse_set

    changes: dict[str, Any] = {}
    for option in options or []:
        try:
            path, values = parse_set(option, ranges=False)
        except SweepError as err:
            raise refuse(err) from None
        if len(values) != 1:
            raise refuse(
                f"--set {option}: one value per path (this is no sweep); a text that holds a "
                "comma is quoted: --set 'lubricant.name=\"a, b\"'"
            )
        if path in changes:
            raise refuse(f"--set {option}: {path} is set twice")
        refuse_overlap(option, path, changes)
        # a bare none (not "none" quoted) removes the value: its default, or no ramp
        removed = values == ["none"] and option.partition("=")[2].strip() == "none"
        changes[path] = None if removed else values[0]
    return changes


def refuse_overlap(option: str, path: str, others: Iterable[str]) -> None:
    """Exits with status 2 where ``--set option`` (at ``path``) and one of the ``others``
    paths lie one inside the other (a table and a key of it)."""
    for other in others:
        if path.startswith(f"{other}.") or other.startswith(f"{path}."):
            raise refuse(
                f"--set {option}: overlaps --set {other} (one sets a table, the other a "
                "key inside it); set the keys one by one"
            )


@contextlib.contextmanager
def sigterm_as_interrupt(received: list[int]):
    """SIGTERM (a batch system's stop, `kill`, `timeout`) within the block is Ctrl-C: a
    KeyboardInterrupt, so that what the block computes stops as after Ctrl-C and keeps what
    it has; ``received`` records it (a second SIGTERM meanwhile is only recorded). Nothing
    changes outside the main thread, where Python takes no signals."""
    import signal
    import threading

    if threading.current_thread() is not threading.main_thread():
        yield
        return

    def stop(signum, _frame):
        received.append(signum)
        if len(received) == 1:
            raise KeyboardInterrupt("terminated by SIGTERM")

    previous = signal.signal(signal.SIGTERM, stop)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)


@contextlib.contextmanager
def terminated_as_interrupted(message: str | Callable[[], str]):
    """SIGTERM within the block is Ctrl-C (:func:`sigterm_as_interrupt`), so that a sweep or
    a study closes its workers and keeps what they computed as it does after Ctrl-C; the
    command then prints ``message`` (or what it returns, asked then: what was kept) and
    exits with status 143. Ctrl-C itself passes on."""
    received: list[int] = []
    try:
        with sigterm_as_interrupt(received):
            yield
    except KeyboardInterrupt:
        if not received:
            raise
        error(message() if callable(message) else message)
        raise typer.Exit(143) from None
