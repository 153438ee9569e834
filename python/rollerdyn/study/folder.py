"""The study folder: its manifest ``study.json`` (which study, of which configuration, and
the files it wrote), the checks made before any run (a folder of another study or
configuration is refused, naming the option; so is a folder without a manifest that holds
files a study writes), ``--overwrite`` (removes only the files the earlier study's manifest
lists) and the tables written beside the runs.
"""

from __future__ import annotations

import contextlib
import json
import math
import os
from pathlib import Path, PurePosixPath

from ..config import BearingConfig
from ..provenance import config_hash, differences, resolved
from .runs import StudyError, check_unlocked

MANIFEST = "study.json"

#: What a study writes at the top of its folder (a folder without a manifest that holds
#: one of these is refused).
WRITTEN = (
    MANIFEST,
    "report.html",
    "runs.csv",
    "findings.csv",
    "findings.json",
    "runtime_study.csv",
    "map.csv",
    "map.parquet",
    "thermal.csv",
    "thermal_speed.csv",
)
RUN_FOLDERS = ("runs", "points")
FIGURES = "figures"

#: The tables and the report each kind of study writes (listed in its manifest before
#: they are written).
OUTPUTS = {
    "paper": ("runs.csv", "findings.csv", "findings.json", "runtime_study.csv", "report.html"),
    "map": ("map.csv", "map.parquet", "thermal.csv", "thermal_speed.csv", "report.html"),
}


def _kind_of_file(rel: str) -> bool:
    """Whether ``rel`` (a path in the folder, as a manifest lists it) is of a kind a study
    writes: a name of :data:`WRITTEN`, a run file in a run folder or a figure; a manifest
    that lists anything else (``../x``, ``notes.txt``) never has it removed."""
    parts = PurePosixPath(rel).parts
    if not parts or ".." in parts or PurePosixPath(rel).is_absolute():
        return False
    if len(parts) == 1:
        return rel in WRITTEN and rel != MANIFEST
    if parts[0] in RUN_FOLDERS:
        return len(parts) == 2 and ".nc" in parts[1]
    return parts[0] == FIGURES and PurePosixPath(rel).suffix in (".png", ".svg")


def _study_files(out: Path) -> list[str]:
    """The files in ``out`` of the kinds a study writes (:func:`_kind_of_file`), relative."""
    found = [n for n in WRITTEN if n != MANIFEST and ((out / n).exists() or (out / n).is_symlink())]
    for sub in RUN_FOLDERS:
        found += [f"{sub}/{p.name}" for p in sorted((out / sub).glob("*.nc*"))]
    figures = out / FIGURES
    if figures.is_dir():
        pictures = [*figures.rglob("*.png"), *figures.rglob("*.svg")]
        found += sorted(p.relative_to(out).as_posix() for p in pictures)
    return found


def _shown(names: list[str]) -> str:
    return ", ".join(names[:3]) + (", ..." if len(names) > 3 else "")


def _read_manifest(out: Path) -> dict | None:
    """The manifest of the folder ``out`` (None without one); :class:`StudyError` for one
    that cannot be read or is not a study's (it does not say what a study wrote there)."""
    manifest = out / MANIFEST
    if not (manifest.exists() or manifest.is_symlink()):
        return None
    reason = ""
    try:
        old = json.loads(manifest.read_text(encoding="utf-8"))
    except (OSError, ValueError, RecursionError) as err:
        reason = str(err) or type(err).__name__
    else:
        kinds = {"study": str, "settings": dict, "config_resolved": dict, "files": list}
        if not isinstance(old, dict):
            reason = f"it holds a JSON {type(old).__name__}, not a study's manifest"
        elif old.get("study") not in OUTPUTS:
            reason = f"study = {old.get('study')!r}: not {' or '.join(map(repr, OUTPUTS))}"
        elif bad := [k for k, t in kinds.items() if k in old and not isinstance(old[k], t)]:
            reason = f"its {bad[0]!r} is not a JSON {kinds[bad[0]].__name__}"
        elif not all(isinstance(f, str) for f in old.get("files", [])):
            reason = "its 'files' is not a list of file names"
        else:
            return old
    raise StudyError(
        f"-o {out}: its {MANIFEST} cannot be read ({reason}); it does not say what an "
        "earlier study wrote there, so nothing in the folder is replaced or removed, not "
        "even with --overwrite: use another folder"
    )


def _listed(out: Path, old: dict) -> list[str]:
    """The files the manifest ``old`` lists that are in ``out`` and of a kind a study
    writes; a manifest of an earlier version, which lists none, owns the files of those
    kinds in its folder (:func:`_study_files`)."""
    if "files" not in old:
        return _study_files(out)
    return [
        f
        for f in old["files"]
        if _kind_of_file(f) and ((out / f).exists() or (out / f).is_symlink())
    ]


def _remove(out: Path, listed: list[str]) -> None:
    """Removes the files ``listed`` (relative to ``out``) and what a run killed while
    writing one of them left (``FILE.tmp<pid>``, :func:`rollerdyn.simulation.write`)."""
    for rel in listed:
        path = out / rel
        path.unlink(missing_ok=True)
        if path.parent.name in RUN_FOLDERS:
            prefix = f"{path.name}.tmp"
            for tmp in path.parent.iterdir():
                if tmp.name.startswith(prefix) and tmp.name[len(prefix) :].isdigit():
                    tmp.unlink(missing_ok=True)


def record_files(out: Path, files) -> None:
    """Adds ``files`` (paths in the study folder ``out``, e.g. the figures just written) to
    its manifest's list of what the study wrote, which ``--overwrite`` removes. A manifest
    that cannot be rewritten keeps its list (the files stay on disk)."""
    manifest = Path(out) / MANIFEST
    with contextlib.suppress(OSError, ValueError, AttributeError, TypeError):
        data = json.loads(manifest.read_text(encoding="utf-8"))
        names = {Path(f).resolve().relative_to(Path(out).resolve()).as_posix() for f in files}
        data["files"] = sorted(set(data.get("files", [])) | names)
        _write_manifest(Path(out), data)


def replace_figures(out: Path, written) -> None:
    """Records the figures just ``written`` (:func:`record_files`) and removes the figures
    an earlier study in ``out`` wrote that this one did not write again, with the figure
    folders that leaves empty: a rerun with fewer runs left the old plan's figures (fig.
    14, the tilt's, the distributed law's) beside a report without them. Only what the
    manifest lists as the study's figures is removed."""
    manifest = Path(out) / MANIFEST
    root = Path(out).resolve()
    with contextlib.suppress(OSError, ValueError, AttributeError, TypeError):
        listed = json.loads(manifest.read_text(encoding="utf-8")).get("files", [])
        now = {Path(f).resolve().relative_to(root).as_posix() for f in written}
        stale = [
            f
            for f in listed
            if _kind_of_file(f) and PurePosixPath(f).parts[0] == FIGURES and f not in now
        ]
        _remove(Path(out), stale)
        for folder in sorted({(Path(out) / f).parent for f in stale}, reverse=True):
            if folder != Path(out) / FIGURES:
                with contextlib.suppress(OSError):
                    folder.rmdir()  # only when empty
        data = json.loads(manifest.read_text(encoding="utf-8"))
        data["files"] = sorted(set(data.get("files", [])) - set(stale))
        _write_manifest(Path(out), data)
    record_files(out, written)


def _write_manifest(out: Path, data: dict) -> None:
    tmp = out / f".{MANIFEST}.{os.getpid()}.tmp"
    try:
        tmp.write_text(json.dumps(data, indent=1, sort_keys=True), encoding="utf-8")
        os.replace(tmp, out / MANIFEST)
    finally:
        tmp.unlink(missing_ok=True)


def _grid_texts(earlier: list, now: list) -> tuple[str, str]:
    """Two maps' grids as :func:`_grid_text` writes them, to six digits, or to all where
    six show no difference (150 rad/s against 1432.39448783 rpm read "1432.39 rpm" twice)."""
    texts = _grid_text(earlier), _grid_text(now)
    if texts[0] == texts[1]:
        texts = _grid_text(earlier, ".17g"), _grid_text(now, ".17g")
    return texts


def _grid_text(grid: list, digits: str = ".6g") -> str:
    """A map's grid (speeds [rad/s], radial and axial loads [N], and the oil temperatures
    [K] where the map sets them) as its values, in rpm, N and degC."""
    try:
        speeds, radial, axial, *temperatures = grid
        rpm = [f"{v * 30 / math.pi:{digits}}" for v in speeds]
        text = (
            f"speeds {', '.join(rpm)} rpm, radial loads "
            f"{', '.join(f'{v:{digits}}' for v in radial)} N, axial loads "
            f"{', '.join(f'{v:{digits}}' for v in axial)} N"
        )
        for axis in temperatures[:1]:
            text += f", temperatures {', '.join(f'{v - 273.15:{digits}}' for v in axis)} degC"
        return text
    except (TypeError, ValueError):
        return "unreadable"


def prepare_folder(
    outdir: Path,
    kind: str,
    cfg: BearingConfig,
    *,
    overwrite: bool = False,
    source: str | None = None,
    settings: dict | None = None,
    files: list[str] | tuple[str, ...] = (),
) -> Path:
    """Checks that ``outdir`` may hold the ``kind`` study ("paper" or "map") of ``cfg``
    and writes its manifest, which lists ``files`` (the run files the study writes,
    relative to the folder: ``runs/NAME.nc``) and its tables and report (:data:`OUTPUTS`);
    returns the folder (created with its parents if missing).

    Refused with :class:`StudyError` (one line naming -o or CONFIG): a file in its place,
    a folder in which another study is running (its lock), a manifest that cannot be read
    or is not a study's, a folder without a manifest that holds files a study writes
    (:data:`WRITTEN`, run files, figures) or result files, and, unless ``overwrite``, a
    folder of another kind of study, of another configuration (the first fields that
    differ are named, SI values) or with other ``settings`` (e.g. the map's steadiness
    criterion). ``overwrite`` removes the files the earlier manifest lists (one of an
    earlier version, which lists none: the files of the kinds a study writes) and nothing
    else; a file this study writes that the manifest does not list is refused. Nothing is
    removed or written before every check has passed."""
    out = Path(outdir)
    if out.exists() and not out.is_dir():
        raise StudyError(f"-o {out}: is a file, not a folder")
    old = None
    if out.is_dir():  # never remove or rewrite the files of a study running in it
        check_unlocked(out)
        old = _read_manifest(out)
    now = resolved(cfg)
    digest = config_hash(cfg)
    settings = dict(settings or {})
    files = sorted({*files, *OUTPUTS[kind]})
    listed: list[str] = []
    if old is None and out.is_dir():
        found = _study_files(out) + sorted(p.name for p in out.glob("*.nc"))
        if found:
            raise StudyError(
                f"-o {out}: holds {_shown(found)} but no {MANIFEST}: not a study folder, so "
                "nothing in it is replaced or removed, not even with --overwrite; use another "
                "folder or move those files"
            )
    elif old is not None and overwrite:
        listed = _listed(out, old)
        unlisted = [f for f in files if (out / f).exists() and f not in listed]
        if unlisted:
            raise StudyError(
                f"-o {out}: holds {_shown(unlisted)}, which its {MANIFEST} does not list as "
                "written by the earlier study; --overwrite removes only the files listed "
                "there: move them or use another folder"
            )
    elif old is not None:
        _check_same(out, old, kind, digest, now, settings, source)
        files = sorted({*files, *_listed(out, old)})
    if out.is_dir() and not os.access(out, os.W_OK | os.X_OK):
        raise StudyError(f"-o {out}: the folder is not writable")
    try:
        _remove(out, listed)
        out.mkdir(parents=True, exist_ok=True)
        if not os.access(out, os.W_OK | os.X_OK):
            raise StudyError(f"-o {out}: the folder is not writable")
        data = {
            "study": kind,
            "config_name": cfg.name,
            "config_sha256": digest,
            "config_resolved": now,
            "settings": settings,
            "files": files,
        }
        _write_manifest(out, data)
    except OSError as err:
        raise StudyError(
            f"-o {out}: cannot create the folder or write its manifest there "
            f"({err.strerror or err}); choose a folder you can write"
        ) from None
    return out


def _check_same(out: Path, old: dict, kind: str, digest, now, settings, source) -> None:
    """Refuses the folder ``out`` whose manifest ``old`` is of another kind of study, of
    another configuration or with other settings than this study's."""
    if old.get("study") != kind:
        raise StudyError(
            f"-o {out}: holds a {old.get('study')!r} study, not a {kind!r} study; use "
            "another folder or --overwrite"
        )
    if old.get("config_sha256") != digest:
        diff = differences(old.get("config_resolved") or {}, now)
        shown = "; ".join(diff[:3]) + (f" and {len(diff) - 3} more" if len(diff) > 3 else "")
        what = f"CONFIG {source}" if source else "the configuration"
        raise StudyError(
            f"-o {out}: holds runs of another configuration than {what} (SI values, "
            f"earlier -> now: {shown or 'unreadable'}); use another folder or --overwrite"
        )
    earlier = old.get("settings", {})
    changed = [k for k in settings if k in earlier and earlier[k] != settings[k]]
    if "grid" in changed:
        was, now = _grid_texts(earlier["grid"], settings["grid"])
        raise StudyError(
            f"-o {out}: holds a map of another grid ({was}; "
            f"now {now}); its points are numbered in their grid, "
            "so a map continues only its own grid: use another folder or --overwrite"
        )
    if changed:
        k = changed[0]
        raise StudyError(
            f"-o {out}: holds a {kind} study made with {k} = {earlier[k]!r}, not "
            f"{settings[k]!r}; use another folder or --overwrite"
        )
