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
import json
import math
import tomllib
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from rollerdyn.config import BearingConfig, load_config, parse_config

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


# --------------------------------------------------------------------------- TOML writer


def _string(text: str) -> str:
    """A TOML basic string: JSON's escapes plus DEL (TOML forbids it unescaped)."""
    return json.dumps(text, ensure_ascii=False).replace("\x7f", "\\u007f")


def _key(key: str) -> str:
    return _string(str(key))


def _toml_value(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if math.isnan(value):
            return "nan"
        if math.isinf(value):
            return "inf" if value > 0 else "-inf"
        return repr(value)
    if isinstance(value, str):
        return _string(value)
    if isinstance(value, list):
        return "[" + ", ".join(_toml_value(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{" + ", ".join(f"{_key(k)} = {_toml_value(v)}" for k, v in value.items()) + "}"
    raise TypeError(type(value))


def dump_toml(data: dict, prefix: tuple = ()) -> str:
    """TOML text of nested dicts (keys always quoted; tables as [headers])."""
    lines, tables = [], []
    for key, value in data.items():
        if isinstance(value, dict) and value:
            tables.append((key, value))
        else:
            lines.append(f"{_key(key)} = {_toml_value(value)}")
    out = "\n".join(lines) + "\n"
    for key, value in tables:
        name = (*prefix, key)
        out += "\n[" + ".".join(_key(k) for k in name) + "]\n" + dump_toml(value, name)
    return out
