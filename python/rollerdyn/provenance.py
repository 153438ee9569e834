"""What made a result: the configuration (as read and resolved to SI), its hash, the
rollerdyn version and the git commit. Every result file records them
(:func:`record_attrs`), and ``--resume`` refuses to continue a run of another
configuration (:func:`check_same_configuration`), naming the first fields that differ.

The hash covers the resolved configuration except what may change between the parts of
a resumed run without changing its physics: the checkpoint interval (``--checkpoint-
interval``), the end time (a run may be extended) and the free-text description.
A result recorded before some fields moved to another section
(:data:`~rollerdyn.config.schema.MOVED_FIELDS`) is compared with its values at their new
places: a run of B1 made with ``surfaces.friction`` continues with ``solver.friction``.
A field added later (:data:`ADDED_FIELDS`) counts only where it differs from what every
earlier result did.
"""

from __future__ import annotations

import copy
import functools
import hashlib
import json
import math
import subprocess
from pathlib import Path
from typing import Any

from .config import BearingConfig
from .config.schema import MOVED_FIELDS

#: Dotted fields left out of the configuration hash (see the module's doc).
NOT_HASHED = ("solver.checkpoint_interval", "operating.end_time", "description")

#: How many differing fields a refusal names.
SHOWN_DIFFERENCES = 3


def resolved(config: BearingConfig) -> dict:
    """The configuration resolved to SI numbers (JSON types)."""
    return config.model_dump(mode="json")


def flatten(data: Any, prefix: str = "") -> dict[str, Any]:
    """Dotted paths to leaf values (lists are leaves)."""
    if not isinstance(data, dict):
        return {prefix: data}
    out: dict[str, Any] = {}
    for key, value in data.items():
        out.update(flatten(value, f"{prefix}.{key}" if prefix else str(key)))
    return out


#: Fields added since results began to record their configuration, with the value every
#: result recorded before had: left out of the hash (and of the differences) at that
#: value, so that a configuration that keeps it hashes as it did before the field existed.
#: (``solver.outputs``: the groups before "lubrication" joined them and the default.)
ADDED_FIELDS = {"solver.outputs": ["rollers", "flanges", "power"]}


def _hashed(flat: dict[str, Any]) -> dict[str, Any]:
    return {
        k: v
        for k, v in flat.items()
        if k not in NOT_HASHED and not (k in ADDED_FIELDS and v == ADDED_FIELDS[k])
    }


def _hash_of(values: dict) -> str:
    text = json.dumps(_hashed(flatten(values)), sort_keys=True)
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


def config_hash(config: BearingConfig) -> str:
    """SHA-256 of the resolved configuration without :data:`NOT_HASHED` (hex)."""
    return _hash_of(resolved(config))


def current_layout(values: dict) -> dict:
    """A resolved configuration recorded before some of its fields moved
    (:data:`~rollerdyn.config.schema.MOVED_FIELDS`), with them at their new places."""
    out = copy.deepcopy(values)
    for old, (new, _) in MOVED_FIELDS.items():
        *parents, key = old.split(".")
        section: Any = out
        for part in parents:
            section = section.get(part) if isinstance(section, dict) else None
        if not isinstance(section, dict) or key not in section:
            continue
        value = section.pop(key)
        *parents, key = new.split(".")
        target = out
        for part in parents:
            target = target.setdefault(part, {})
        target.setdefault(key, value)
    return out


@functools.cache
def git_commit() -> str:
    """The commit of the source tree rollerdyn runs from ('' when not a git checkout),
    with '+dirty' when it has uncommitted changes."""
    here = Path(__file__).resolve().parent
    try:
        head = subprocess.run(
            ["git", "rev-parse", "HEAD"], cwd=here, capture_output=True, text=True, timeout=5
        )
        if head.returncode != 0:
            return ""
        dirty = subprocess.run(
            ["git", "status", "--porcelain", "--untracked-files=no"],
            cwd=here,
            capture_output=True,
            text=True,
            timeout=5,
        )
    except (OSError, subprocess.SubprocessError):
        return ""
    return head.stdout.strip() + ("+dirty" if dirty.stdout.strip() else "")


def record_attrs(config: BearingConfig) -> dict[str, str]:
    """The Dataset attributes that record what made a result."""
    from . import __version__

    return {
        "config_toml": config.toml_text or "",
        "config_resolved": json.dumps(resolved(config), sort_keys=True),
        "config_sha256": config_hash(config),
        "rollerdyn_version": __version__,
        "git_commit": git_commit(),
    }


def _same(a: Any, b: Any) -> bool:
    if isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b):
        return True
    return a == b


def differences(earlier: dict, now: dict) -> list[str]:
    """'field: earlier -> now' for each hashed field that differs, in the schema's order."""
    old, new = _hashed(flatten(earlier)), _hashed(flatten(now))
    keys = list(new) + [k for k in old if k not in new]
    return [
        f"{k}: {old.get(k, '(absent)')!r} -> {new.get(k, '(absent)')!r}"
        for k in keys
        if not _same(old.get(k, "(absent)"), new.get(k, "(absent)"))
    ]


#: What makes the bearing itself (its run's operating point, oil, surfaces and solver
#: aside): the parts a comparison of two runs or a state evaluated with another
#: configuration assumes the same.
BEARING_SECTIONS = ("geometry", "materials", "inner_ring")


#: What makes a run's case besides its bearing: its loads and speeds, its oil and its
#: contact models (the solver aside, whose settings a comparison of two runs is about).
CASE_SECTIONS = ("operating", "lubricant", "surfaces")


def bearing_differences(
    a: dict, b: dict, shown: int = 3, sections: tuple[str, ...] = BEARING_SECTIONS
) -> list[str]:
    """'field: a -> b' for the first ``shown`` fields of ``sections`` (by default
    :data:`BEARING_SECTIONS`) in which the resolved configurations ``a`` and ``b``
    (:func:`resolved`, or a result's ``config_resolved``) differ; with more, a last entry
    says how many more."""
    found = differences(*({s: c.get(s) for s in sections} for c in (a, b)))
    more = len(found) - shown
    return found[:shown] + ([f"and {more} more"] if more > 0 else [])


def recorded_configuration(attrs: dict) -> dict | None:
    """A result's ``config_resolved`` (None if it records none, or not as JSON)."""
    text = attrs.get("config_resolved")
    if not isinstance(text, str) or not text.strip():
        return None
    try:
        data = json.loads(text)
    except ValueError:
        return None
    return current_layout(data) if isinstance(data, dict) else None


def check_same_configuration(attrs: dict, config: BearingConfig) -> None:
    """Raises ValueError unless the result with ``attrs`` was made by ``config`` (same
    hash, or the same values once moved fields are at their new places), naming the first
    fields that differ (SI values)."""
    stored = attrs.get("config_sha256")
    if not stored:
        raise ValueError(
            "resume: the earlier result records no configuration (config_sha256): it cannot "
            "be checked to be a run of this configuration; start a new run"
        )
    now = resolved(config)
    if stored == _hash_of(now):
        return
    try:
        earlier = json.loads(attrs.get("config_resolved", ""))
    except (TypeError, ValueError):
        earlier = {}
    if isinstance(earlier, dict):
        # a result recorded before fields moved: its values, at their new places
        moved = current_layout(earlier)
        if moved != earlier and _hash_of(earlier) == stored and _hash_of(moved) == _hash_of(now):
            return
        earlier = moved
    diff = differences(earlier, now) if isinstance(earlier, dict) else []
    shown = "; ".join(diff[:SHOWN_DIFFERENCES]) or "(the stored values are unreadable)"
    more = f" and {len(diff) - SHOWN_DIFFERENCES} more" if len(diff) > SHOWN_DIFFERENCES else ""
    raise ValueError(
        "resume: the earlier run was made with another configuration (SI values, earlier -> "
        f"now): {shown}{more}; a run can only be continued with its own configuration (the "
        "same file and --set options)"
    )
