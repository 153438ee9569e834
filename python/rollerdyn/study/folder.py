"""The study folder: its manifest ``study.json`` (which study, of which configuration),
the checks made before any run (a folder of another study or configuration is refused,
naming the option), ``--overwrite`` (removes only what a study writes) and the tables
written beside the runs.
"""

from __future__ import annotations

import json
import math
import os
from pathlib import Path

from ..config import BearingConfig
from ..provenance import config_hash, differences, resolved
from .runs import StudyError, check_unlocked

MANIFEST = "study.json"

#: What a study writes, relative to its folder (``--overwrite`` removes these only).
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


def _remove_written(out: Path) -> None:
    for name in WRITTEN:
        (out / name).unlink(missing_ok=True)
    for sub in RUN_FOLDERS:
        for f in (out / sub).glob("*.nc*"):
            f.unlink(missing_ok=True)
    figures = out / "figures"
    if figures.is_dir():
        for f in [*figures.rglob("*.png"), *figures.rglob("*.svg")]:
            f.unlink(missing_ok=True)


def _grid_text(grid: list) -> str:
    """A map's grid (speeds [rad/s], radial and axial loads [N], and the oil temperatures
    [K] where the map sets them) as its values, in rpm, N and degC."""
    try:
        speeds, radial, axial, *temperatures = grid
        rpm = [f"{v * 30 / math.pi:.6g}" for v in speeds]
        text = (
            f"speeds {', '.join(rpm)} rpm, radial loads {', '.join(f'{v:.6g}' for v in radial)}"
            f" N, axial loads {', '.join(f'{v:.6g}' for v in axial)} N"
        )
        for axis in temperatures[:1]:
            text += f", temperatures {', '.join(f'{v - 273.15:.6g}' for v in axis)} degC"
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
) -> Path:
    """Checks that ``outdir`` may hold the ``kind`` study ("paper" or "map") of ``cfg``
    and writes its manifest; returns the folder (created with its parents if missing).

    Refused with :class:`StudyError` (one line naming -o or CONFIG): a file in its place,
    a folder of another kind of study, of another configuration (the first fields that
    differ are named, SI values) or with other ``settings`` (e.g. the map's steadiness
    criterion), result files without a manifest, and a folder in which another study is
    running (its lock; checked before anything is removed or written). ``overwrite`` first
    removes what a study writes (:data:`WRITTEN`, the run files and figures) and nothing
    else."""
    out = Path(outdir)
    if out.exists() and not out.is_dir():
        raise StudyError(f"-o {out}: is a file, not a folder")
    manifest = out / MANIFEST
    if out.is_dir():  # never remove or rewrite the files of a study running in it
        check_unlocked(out)
    if overwrite and out.is_dir():
        _remove_written(out)
    now = resolved(cfg)
    digest = config_hash(cfg)
    settings = dict(settings or {})
    if manifest.is_file():
        try:
            old = json.loads(manifest.read_text(encoding="utf-8"))
        except (OSError, ValueError) as err:
            raise StudyError(
                f"-o {out}: its {MANIFEST} cannot be read ({err}); use another folder or "
                "--overwrite"
            ) from None
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
            raise StudyError(
                f"-o {out}: holds a map of another grid ({_grid_text(earlier['grid'])}; "
                f"now {_grid_text(settings['grid'])}); its points are numbered in their grid, "
                "so a map continues only its own grid: use another folder or --overwrite"
            )
        if changed:
            k = changed[0]
            raise StudyError(
                f"-o {out}: holds a {kind} study made with {k} = {old['settings'][k]!r}, not "
                f"{settings[k]!r}; use another folder or --overwrite"
            )
    elif out.is_dir():
        found = sorted(p.name for sub in ("", *RUN_FOLDERS) for p in (out / sub).glob("*.nc"))
        if found:
            raise StudyError(
                f"-o {out}: holds result files ({', '.join(found[:3])}"
                f"{', ...' if len(found) > 3 else ''}) but no {MANIFEST}: not a study folder; "
                "use another folder or --overwrite"
            )
    try:
        out.mkdir(parents=True, exist_ok=True)
        if not os.access(out, os.W_OK | os.X_OK):
            raise StudyError(f"-o {out}: the folder is not writable")
        data = {
            "study": kind,
            "config_name": cfg.name,
            "config_sha256": digest,
            "config_resolved": now,
            "settings": settings,
        }
        tmp = out / f".{MANIFEST}.{os.getpid()}.tmp"
        tmp.write_text(json.dumps(data, indent=1, sort_keys=True), encoding="utf-8")
        os.replace(tmp, manifest)
    except OSError as err:
        raise StudyError(
            f"-o {out}: cannot create the folder or write its manifest there "
            f"({err.strerror or err}); choose a folder you can write"
        ) from None
    return out
