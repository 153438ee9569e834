"""Checks of the paths a command writes, made before any work starts.

Every check raises :class:`OutputPathError`, whose message is one line naming the option,
the path and the rule broken, e.g. ``-o out/r.nc: the folder out does not exist (create it
first)``. The command line prints it and exits with status 2; nothing has been computed
or written then. :func:`remove_stale_temporaries` clears what a killed writer left behind.
"""

from __future__ import annotations

import os
from collections.abc import Iterable
from pathlib import Path

__all__ = [
    "OutputPathError",
    "check_output_dir",
    "check_output_file",
    "is_result_file",
    "printable",
    "process_alive",
    "remove_stale_temporaries",
    "same_file",
]

#: The first bytes of an HDF5 file (netCDF-4, what rollerdyn writes) and of classic netCDF.
_SIGNATURES = (b"\x89HDF\r\n\x1a\n", b"CDF\x01", b"CDF\x02")


def printable(text: object) -> str:
    """``text`` as UTF-8 text: bytes of a file name or an argument that are not UTF-8 (kept
    by Python as surrogates) shown as ``\\xff`` (any other surrogate as ``\\udXXX``), so it
    can be printed and recorded in a result file."""
    try:
        raw = str(text).encode("utf-8", "surrogateescape")
    except UnicodeEncodeError:  # a surrogate that is no escaped byte
        raw = str(text).encode("utf-8", "backslashreplace")
    return raw.decode("utf-8", "backslashreplace")


class OutputPathError(ValueError):
    """An output path that cannot or must not be written (one line: option, path, rule)."""


def same_file(a: Path, b: Path) -> bool:
    """True if ``a`` and ``b`` name the same file (existing or not)."""
    try:
        return os.path.samefile(a, b)
    except OSError:
        return a.resolve() == b.resolve()


def is_result_file(path: Path) -> bool:
    """True if ``path`` is a netCDF/HDF5 file (by its first bytes), as results are."""
    try:
        with open(path, "rb") as f:
            head = f.read(8)
    except OSError:
        return False
    return any(head.startswith(s) for s in _SIGNATURES)


def _check_parent(path: Path, option: str) -> None:
    """The folder that will hold ``path`` exists, is a folder and is writable."""
    parent = path.parent
    if not parent.exists():
        raise OutputPathError(
            f"{option} {path}: the folder {parent} does not exist (create it first)"
        )
    if not parent.is_dir():
        raise OutputPathError(f"{option} {path}: {parent} is a file, not a folder")
    if not os.access(parent, os.W_OK | os.X_OK):
        raise OutputPathError(f"{option} {path}: the folder {parent} is not writable")
    _probe(parent, path, option)


def _probe(parent: Path, path: Path, option: str) -> None:
    """Creates and removes a file in ``parent``: permissions alone do not tell (a read-only
    mount, /proc, a full quota); a run would find out only when it writes its result."""
    import tempfile

    try:
        handle, name = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".probe", dir=parent)
    except OSError as err:
        reason = err.strerror or type(err).__name__
        raise OutputPathError(
            f"{option} {path}: cannot create a file in the folder {parent} ({reason})"
        ) from None
    os.close(handle)
    os.unlink(name)


def check_output_file(
    path: Path,
    option: str = "-o",
    *,
    inputs: Iterable[tuple[str, Path]] = (),
    overwrite: bool = False,
    hint: str = "",
) -> Path:
    """Checks that the file ``path`` may be written; returns it.

    Refused: a folder, a missing or read-only parent folder, one of ``inputs`` (pairs of
    what it is and its path, e.g. ``("the configuration file", cfg)``), something that is
    not a regular file (a device, a pipe), a read-only file, and an existing file unless
    ``overwrite`` (``hint`` then says how to replace it)."""
    path = Path(path)
    if path.is_dir():
        raise OutputPathError(f"{option} {path}: is a folder; give a file name")
    _check_parent(path, option)
    for what, given in inputs:
        if same_file(path, Path(given)):
            raise OutputPathError(
                f"{option} {path}: is {what}, an input; writing would destroy it "
                "(choose another output)"
            )
    if not path.exists() and not path.is_symlink():
        return path
    if not path.is_file():
        raise OutputPathError(f"{option} {path}: exists and is not a regular file")
    if not os.access(path, os.W_OK):
        raise OutputPathError(f"{option} {path}: the file exists and is not writable")
    if not overwrite:
        raise OutputPathError(f"{option} {path}: the file exists{hint}")
    return path


def check_output_dir(
    path: Path,
    option: str = "-o",
    *,
    results: Iterable[str] = (),
    overwrite: bool = True,
    hint: str = "",
) -> Path:
    """Checks that the folder ``path`` may be created (its parent exists) or written to;
    returns it. ``results``: glob patterns of earlier results in it, refused unless
    ``overwrite`` (``hint`` says how to replace them)."""
    path = Path(path)
    if path.exists() and not path.is_dir():
        raise OutputPathError(f"{option} {path}: is a file, not a folder")
    if not path.exists():
        _check_parent(path, option)
        return path
    if not os.access(path, os.W_OK | os.X_OK):
        raise OutputPathError(f"{option} {path}: the folder is not writable")
    if not overwrite:
        found = sorted({p.name for pattern in results for p in path.glob(pattern)})
        if found:
            shown = ", ".join(found[:3]) + (", ..." if len(found) > 3 else "")
            raise OutputPathError(f"{option} {path}: holds earlier results ({shown}){hint}")
    return path


def process_alive(pid: int) -> bool:
    """True if process ``pid`` exists (possibly another user's); False for a number that
    is no process id. Also asked by the study folder's lock (:mod:`rollerdyn.study.runs`)."""
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    except (OverflowError, OSError):
        return False
    return True


def remove_stale_temporaries(path: Path) -> list[tuple[Path, int]]:
    """Removes the files ``PATH.tmp<pid>`` beside ``path`` (what
    :func:`rollerdyn.simulation.write` leaves when its process is killed while writing)
    whose process is no longer running; returns (file, pid) of each removed."""
    path = Path(path)
    prefix = f"{path.name}.tmp"
    removed = []
    try:
        candidates = list(path.parent.glob(f"{_glob_escape(prefix)}*"))
    except OSError:
        return removed
    for tmp in candidates:
        digits = tmp.name[len(prefix) :]
        if not digits.isdigit() or int(digits) <= 0 or not tmp.is_file():
            continue
        pid = int(digits)
        if pid == os.getpid() or process_alive(pid):
            continue
        try:
            tmp.unlink()
        except OSError:
            continue
        removed.append((tmp, pid))
    return removed


def _glob_escape(text: str) -> str:
    """``text`` with glob's special characters taken literally."""
    return "".join(f"[{c}]" if c in "*?[" else c for c in text)
