"""Checks of the paths a command writes, made before any work starts.

Every check raises :class:`OutputPathError`, whose message is one line naming the option,
the path and the rule broken, e.g. ``-o out/r.nc: the folder out does not exist (create it
first)``. The command line prints it and exits with status 2; nothing has been computed
or written then. :func:`remove_stale_temporaries` clears what a killed writer left behind.

:func:`write_atomically` writes a file through a temporary one beside it, renamed into
place only once it is whole: a failed write (a full disk) leaves an earlier file as it
was, and a file another program created meanwhile is not replaced unless asked.
"""

from __future__ import annotations

import errno
import os
from collections.abc import Callable, Iterable
from pathlib import Path

__all__ = [
    "NAME_MAX",
    "OutputPathError",
    "check_name",
    "check_output_dir",
    "check_output_file",
    "is_result_file",
    "name_problem",
    "place_file",
    "printable",
    "process_alive",
    "remove_stale_temporaries",
    "same_file",
    "temporary_path",
    "write_atomically",
]

#: The longest name of one file or folder (one part of a path) in bytes that the common
#: file systems take (ext4, xfs, btrfs, tmpfs; NAME_MAX); a part of a path longer than it
#: cannot be created or even looked up ("File name too long").
NAME_MAX = 255

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
    """True if ``a`` and ``b`` name the same file (existing or not). Never raises: a name
    that cannot be looked up (a symbolic link loop, a part over :data:`NAME_MAX` bytes) is
    compared as it is spelled, made absolute."""
    try:
        return os.path.samefile(a, b)
    except (OSError, ValueError):
        pass
    try:
        return Path(a).resolve() == Path(b).resolve()
    except (OSError, RuntimeError, ValueError):  # RuntimeError: a symbolic link loop
        return os.path.abspath(a) == os.path.abspath(b)


def repeated_file(paths) -> tuple[Path, Path] | None:
    """The first two of ``paths`` that name the same file (:func:`same_file`: ``b.nc`` and
    ``./b.nc``, a link and its target), or None."""
    paths = [Path(p) for p in paths]
    for i, a in enumerate(paths):
        for b in paths[i + 1 :]:
            if same_file(a, b):
                return a, b
    return None


def name_problem(path: Path) -> str | None:
    """What makes ``path`` impossible to look up or use, in a few words, or None: a part of
    its name longer than :data:`NAME_MAX` bytes, a symbolic link loop, a symbolic link to
    nothing, or another error of the system (its text). A path that does not exist (yet)
    is no problem."""
    path = Path(path)
    for part in path.parts:
        size = len(os.fsencode(part))
        if size > NAME_MAX:
            return (
                f"a part of the name is {size} bytes long; a file system takes at most "
                f"{NAME_MAX} bytes per file or folder name"
            )
    try:
        os.stat(path)
    except (FileNotFoundError, NotADirectoryError):
        if os.path.islink(path):
            return "is a symbolic link to something that does not exist"
        return None
    except OSError as err:
        if err.errno == errno.ELOOP:
            return "is a symbolic link loop (its links lead back to themselves)"
        if err.errno == errno.ENAMETOOLONG:
            return "the name is too long for the file system (File name too long)"
        return err.strerror or type(err).__name__
    except ValueError as err:  # a NUL byte in the name
        return str(err)
    return None


def check_name(path: Path, option: str = "-o") -> Path:
    """Raises :class:`OutputPathError` naming ``option``, ``path`` and the rule if ``path``
    cannot be looked up or used (:func:`name_problem`); returns it."""
    problem = name_problem(path)
    if problem is not None:
        raise OutputPathError(f"{option} {path}: {problem}")
    return Path(path)


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
    mount, /proc, a full quota); a run would find out only when it writes its result. The
    probe's name is short and its own (``.rdXXXXXXXX.probe``): one made of ``path``'s name
    would be refused for a long but valid name ("File name too long")."""
    import tempfile

    try:
        handle, name = tempfile.mkstemp(prefix=".rd", suffix=".probe", dir=parent)
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
    reserve: int | None = None,
) -> Path:
    """Checks that the file ``path`` may be written; returns it.

    Refused: a name that cannot be used (:func:`check_name`: a part over :data:`NAME_MAX`
    bytes, a symbolic link loop), a folder, a missing or read-only parent folder, one of
    ``inputs`` (pairs of what it is and its path, e.g. ``("the configuration file",
    cfg)``), something that is not a regular file (a device, a pipe), a read-only file, and
    an existing file unless ``overwrite`` (``hint`` then says how to replace it).
    ``reserve``: the bytes the writer adds to the file's name for its temporary file (by
    default those of ``NAME.tmp<pid>``, what :func:`rollerdyn.simulation.write` writes
    first; 0 for a writer that uses :func:`write_atomically`, which shortens it itself)."""
    path = Path(path)
    if str(path) == "-":  # a file named "-" was written (a review): "-" reads as stdout
        raise OutputPathError(
            f"{option} -: '-' (standard output) is not taken for a file here; give a file name"
        )
    check_name(path, option)
    _check_room(path, option, len(f".tmp{os.getpid()}") if reserve is None else reserve)
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
    ``overwrite`` (``hint`` says how to replace them). A name that cannot be used
    (:func:`check_name`) is refused."""
    path = Path(path)
    check_name(path, option)
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


def _check_room(path: Path, option: str, reserve: int) -> None:
    """Refuses a file name that leaves no room for the ``reserve`` bytes its writer adds
    for the temporary file it writes first."""
    size = len(os.fsencode(path.name))
    if reserve > 0 and size <= NAME_MAX < size + reserve:
        raise OutputPathError(
            f"{option} {path}: the file name is {size} bytes long; it is written first "
            f"under its name and {reserve} bytes more (a temporary file), so it may be at "
            f"most {NAME_MAX - reserve} bytes (a file system takes {NAME_MAX})"
        )


def temporary_path(path: Path) -> Path:
    """The temporary file beside ``path`` that :func:`write_atomically` writes first:
    ``NAME.tmp<pid>`` (which :func:`remove_stale_temporaries` clears once its process is
    gone), or ``.rollerdyn.tmp<pid>`` where that name would be longer than
    :data:`NAME_MAX` bytes."""
    path = Path(path)
    name = f"{path.name}.tmp{os.getpid()}"
    if len(os.fsencode(name)) > NAME_MAX:
        name = f".rollerdyn.tmp{os.getpid()}"
    return path.with_name(name)


def _free_name(path: Path, number: int) -> Path:
    """``path`` with ``-number`` before its extension: ``out/s-2.nc``; the stem shortened
    (by whole characters) where the name would be longer than :data:`NAME_MAX` bytes."""
    stem, tail = path.stem, f"-{number}{path.suffix}"
    while stem and len(os.fsencode(stem + tail)) > NAME_MAX:
        stem = stem[:-1]
    return path.with_name(stem + tail)


def keep_elsewhere(data: bytes | memoryview, prefix: str, suffix: str = ".nc") -> str:
    """Writes ``data`` (a result that could not be written where asked) to a new file in
    the system's temporary folder (another disk than the output's, often); says where, or
    that it is lost."""
    import tempfile

    try:
        handle, name = tempfile.mkstemp(prefix=prefix, suffix=suffix)
    except OSError as err:
        return f"the result could not be kept elsewhere either ({err.strerror or err}): it is lost"
    try:
        with os.fdopen(handle, "wb") as f:
            f.write(data)
    except OSError as err:
        Path(name).unlink(missing_ok=True)
        return f"the result could not be kept elsewhere either ({err.strerror or err}): it is lost"
    return f"the result was kept in {name}"


def _link_new(source: Path, target: Path) -> bool:
    """Makes ``target`` name the file ``source`` only if ``target`` does not exist (a hard
    link, which fails if it does: no other program's file created meanwhile is replaced);
    False if it exists. Where the file system has no hard links, checks and renames."""
    try:
        os.link(source, target)
        return True
    except FileExistsError:
        return False
    except OSError as err:
        if err.errno not in (errno.EPERM, errno.EOPNOTSUPP, errno.ENOTSUP, errno.EMLINK):
            raise
    if os.path.lexists(target):
        return False
    os.replace(source, target)
    return True


def place_file(tmp: Path, path: Path, replace: bool | Callable[[Path], bool] = False) -> Path:
    """Renames the whole file ``tmp`` to ``path`` (beside it, on the same file system);
    returns where it went. ``replace``: whether a file at ``path`` may be replaced, True or
    asked at the rename (a function of ``path``; e.g. "is it an earlier report"). A file
    there that may not be replaced (one that another program or a second rollerdyn wrote
    since the command checked its output) is kept, and ``tmp`` goes to the first free name
    ``STEM-2.EXT``, ``STEM-3.EXT``, ...: the caller says so. ``tmp`` is gone afterwards."""
    tmp, path = Path(tmp), Path(path)
    try:
        if replace is True:
            os.replace(tmp, path)
            return path
        target = path
        for number in range(2, 10_000):
            if _link_new(tmp, target):
                return target
            if target == path and callable(replace) and replace(path):
                os.replace(tmp, path)
                return path
            target = _free_name(path, number)
        raise FileExistsError(errno.EEXIST, "no free name beside it", str(path))
    finally:
        _remove_quietly(tmp)


def write_atomically(
    path: Path, data: bytes | memoryview | str, replace: bool | Callable[[Path], bool] = False
) -> Path:
    """Writes ``data`` (text as UTF-8) to ``path`` atomically: to a temporary file beside it
    (:func:`temporary_path`), flushed to the disk, then renamed into place
    (:func:`place_file`, which also says what ``replace`` means); returns the file
    written. Raises ``OSError`` if the write fails (a full disk, a folder gone); the
    temporary file is removed then, and a file that was at ``path`` is left as it was."""
    path = Path(path)
    raw = data.encode("utf-8", "surrogateescape") if isinstance(data, str) else data
    tmp = temporary_path(path)
    flags = os.O_WRONLY | os.O_CREAT | os.O_TRUNC | getattr(os, "O_NOFOLLOW", 0)
    try:
        handle = os.open(tmp, flags, 0o666)
        with os.fdopen(handle, "wb") as f:
            f.write(raw)
            f.flush()
            os.fsync(f.fileno())
        return place_file(tmp, path, replace)
    finally:
        _remove_quietly(tmp)


def _remove_quietly(path: Path) -> None:
    """Removes ``path`` if it is there; an error doing so is not the one to report."""
    try:
        if os.path.lexists(path):
            os.remove(path)
    except OSError:
        pass


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


def lock_holder(folder: Path, name: str) -> int | None:
    """The id of another living process that holds the lock file ``folder/name`` (it holds
    the holder's process id), else None (no lock, a stale one, or this process's)."""
    try:
        pid = int((Path(folder) / name).read_text().strip() or "0")
    except (OSError, ValueError):
        return None
    return pid if pid > 0 and pid != os.getpid() and process_alive(pid) else None


def check_unlocked(folder: Path, name: str, what: str, error: type[Exception]) -> None:
    """Raises ``error`` (``-o FOLDER: another WHAT (process N) is running in this folder;
    ...``) if another living process holds the lock ``folder/name``."""
    pid = lock_holder(folder, name)
    if pid is not None:
        raise error(
            f"-o {folder}: another {what} (process {pid}) is running in this folder; "
            "wait for it or choose another folder"
        )


def take_folder_lock(folder: Path, name: str, what: str, error: type[Exception]) -> Path:
    """Takes the lock file ``folder/name`` (created exclusively, holding this process's id)
    and returns it; a stale one (its process gone) is taken over. Raises ``error``
    (:func:`check_unlocked`) if another living process holds it: two studies or sweeps
    writing one folder replace each other's files."""
    lock = Path(folder) / name
    try:
        fd = os.open(lock, os.O_CREAT | os.O_EXCL | os.O_WRONLY, 0o644)
    except FileExistsError:
        check_unlocked(folder, name, what, error)
        lock.unlink(missing_ok=True)  # a stale lock (its process is gone) or our own
        fd = os.open(lock, os.O_CREAT | os.O_EXCL | os.O_WRONLY, 0o644)
    with os.fdopen(fd, "w") as f:
        f.write(str(os.getpid()))
    return lock


def remove_stale_temporaries(path: Path) -> list[tuple[Path, int]]:
    """Removes the files ``PATH.tmp<pid>`` beside ``path``, and ``.rollerdyn.tmp<pid>``
    there (:func:`temporary_path`: what :func:`rollerdyn.simulation.write` and
    :func:`write_atomically` leave when their process is killed while writing), whose
    process is no longer running; returns (file, pid) of each removed."""
    path = Path(path)
    removed = []
    candidates = []
    for prefix in (f"{path.name}.tmp", ".rollerdyn.tmp"):
        try:
            candidates += [(prefix, p) for p in path.parent.glob(f"{_glob_escape(prefix)}*")]
        except OSError:
            pass
    for prefix, tmp in candidates:
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
