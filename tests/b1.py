"""B1, the reference paper's bearing (``examples/b1.toml``), for every test.

The one source of B1 in the tests: its file, bytes and TOML data, variants with dotted-path
changes (as data, :func:`changed_b1`, or validated, :func:`variant`), a copy of the file
with a text replaced (:func:`b1_file_with`) and a TOML writer for variants written to a
file (:func:`dump_toml`). Every variant starts from the file itself, so all tests see the
same lubricant, geometry and solver settings unless they change them.
``tests/conftest.py`` turns these into the fixtures ``b1`` and ``raw``.
"""

from __future__ import annotations

import copy
import tomllib
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from rollerdyn.config import BearingConfig, load_config, parse_config
from rollerdyn.config.loading import dump_toml  # noqa: F401 (the tests' TOML writer)

ROOT = Path(__file__).resolve().parents[1]
B1 = ROOT / "examples" / "b1.toml"
B1_BYTES = B1.read_bytes()
B1_TEXT = B1_BYTES.decode("utf-8")


def b1_data() -> dict:
    """B1's TOML data as read from the file (a fresh copy at each call)."""
    return tomllib.loads(B1_TEXT)


def load_b1() -> BearingConfig:
    """B1 read from its file (a fresh object: no derived value cached by other tests)."""
    return load_config(B1)


def changed_b1(changes: Mapping[str, Any], base: dict | None = None) -> dict:
    """B1's TOML data (or a deep copy of ``base``) with dotted-path changes, e.g.
    ``{"operating.axial_load": "0 N"}``; None removes a key."""
    data = copy.deepcopy(base) if base is not None else b1_data()
    for path, value in changes.items():
        section = data
        *parents, key = path.split(".")
        for p in parents:
            section = section.setdefault(p, {})
        if value is None:
            section.pop(key, None)
        else:
            section[key] = value
    return data


def variant(**changes: Any) -> BearingConfig:
    """B1 with dotted-path changes (see :func:`changed_b1`), validated."""
    return parse_config(changed_b1(changes))


def b1_file_with(
    tmp_path: Path, old: str, new: str, name: str = "variant.toml", count: int = -1
) -> Path:
    """B1's file with ``old`` (which must occur in it) replaced by ``new``, written to
    ``tmp_path / name``: every occurrence, or the first ``count``."""
    assert old in B1_TEXT, old
    path = tmp_path / name
    path.write_text(B1_TEXT.replace(old, new, count), encoding="utf-8")
    return path
