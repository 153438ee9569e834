"""Reading a configuration: :func:`load_config` (a TOML file) and :func:`parse_config` (a
mapping), both returning a validated :class:`~rollerdyn.config.BearingConfig` or raising a
:class:`~rollerdyn.config.ConfigError` that lists every problem.
"""

from __future__ import annotations

import json
import math
import os
import re
import sys
import tomllib
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from pydantic import ValidationError

from ..units import SI_NUMBERS
from .errors import ConfigError, Problem, _show, problems_from
from .schema import BearingConfig


def load_config(path: str | Path, changes: Mapping[str, Any] | None = None) -> BearingConfig:
    """Read and validate a TOML configuration file; raise :class:`ConfigError` if invalid.

    ``changes`` maps dotted paths to values written as in the file (``{"surfaces.flange_law":
    "distributed", "operating.axial_load": "500 N"}``; the command line's ``--set``); they
    replace the file's values before validation, and the configuration's
    :attr:`~BearingConfig.toml_text` is then the changed table written as TOML, headed by a
    comment naming the file and the changes, so a result records what made it."""
    if not isinstance(path, str | os.PathLike) or isinstance(path, bytes):
        raise ConfigError(
            f"path = {path!r}: expected the configuration file's path (a str or a "
            f"pathlib.Path), got {type(path).__name__}"
        )
    if isinstance(path, str) and not path.strip():
        raise ConfigError("path = '': no configuration file named")
    from ..paths import printable

    p = Path(path)
    shown = printable(str(p)) if len(str(p)) <= 200 else printable(str(p)[:197]) + "..."
    if "\n" in str(path) and ("=" in str(path) or "[" in str(path)):
        # the file's text given instead of its path (a review: a raw OSError)
        raise ConfigError(
            f"path = {str(path)[:40]!r}...: this looks like a configuration's TOML text, not "
            "its file's path; pass the path, or parse the text with "
            "rollerdyn.parse_config(tomllib.loads(text))"
        )
    try:
        if not p.exists():
            raise ConfigError(f"{p}: configuration file not found", source=str(p))
        if not p.is_file():
            raise ConfigError(f"{p}: not a file", source=str(p))
    except OSError as exc:  # a name longer than the file system takes (255 bytes): a traceback
        raise ConfigError(f"{shown}: cannot be read ({exc.strerror})", source=str(p)) from None
    try:
        text = p.read_bytes().decode("utf-8-sig")  # a byte-order mark is not TOML
    except UnicodeDecodeError as exc:
        raise ConfigError(
            f"{p}: not UTF-8 text ({exc.reason} at byte {exc.start})", source=str(p)
        ) from None
    except OSError as exc:
        raise ConfigError(f"{p}: cannot read ({exc.strerror})", source=str(p)) from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        msg = str(exc)
        m = re.search(r"\(at line (\d+), column (\d+)\)", msg)
        where = f"{p}:{m.group(1)}:{m.group(2)}" if m else f"{p}"
        reason = re.sub(r"\s*\(at (line \d+, column \d+|end of document)\)", "", msg)
        raise ConfigError(f"{where}: malformed TOML — {reason}", source=str(p)) from None
    except RecursionError:  # tomllib reads nested arrays and tables recursively
        raise ConfigError(
            f"{p}: malformed TOML — arrays or tables nested too deeply", source=str(p)
        ) from None
    except ValueError as exc:  # Python's limit on the digits of an integer it reads
        reason = str(exc)
        if "integer string conversion" in reason:
            reason = f"an integer of more than {sys.get_int_max_str_digits()} digits"
        raise ConfigError(f"{p}: malformed TOML — {reason}", source=str(p)) from None
    if not changes:
        config = parse_config(data, source=str(p))
        config._toml = text
        return config
    from ..paths import printable
    from ..sweep import SweepError, changed

    try:
        plain_changes = _plain_changes(changes, str(p))
        data = changed(data, plain_changes)
    except SweepError as exc:
        raise ConfigError(f"invalid configuration {p}: {exc}", source=str(p)) from None
    except RecursionError:
        raise ConfigError(
            f"invalid configuration {p}: changes: a value nested too deeply", source=str(p)
        ) from None
    paths = list(plain_changes)
    named = ", ".join(paths[:5]) + (f" and {len(paths) - 5} more" if len(paths) > 5 else "")
    config = parse_config(data, source=f"{p} with --set {named}")
    shown = ", ".join(f"{k} = {_shown(v)}" for k, v in plain_changes.items())
    # the file's name as UTF-8 (a result file holds nothing else)
    config._toml = toml_text(data, header=f"{printable(p)}, changed: {shown}")
    return config


def _plain_changes(changes: Mapping[str, Any], source: str) -> dict[str, Any]:
    """``changes`` with numpy's scalars as Python's numbers, numpy's arrays and tuples as
    lists (what tomllib reads), so that their TOML text reads back as they are;
    ConfigError unless a mapping of dotted paths."""
    if not isinstance(changes, Mapping) or not all(
        isinstance(k, str) and k.strip() and all(part.strip() for part in k.split("."))
        for k in changes
    ):  # "a..b" made a table of an empty key (a review)
        raise ConfigError(
            f"changes = {changes!r}: expected a mapping of dotted paths to values written as "
            'in the file, e.g. {"surfaces.flange_law": "distributed"}',
            source=source,
        )

    def plain(value: Any) -> Any:
        if isinstance(value, Mapping):
            return {k: plain(v) for k, v in value.items()}
        if isinstance(value, list | tuple):
            return [plain(v) for v in value]
        if hasattr(value, "magnitude") and hasattr(value, "units"):
            # a pint Quantity: as text with its unit, as the file writes it (its magnitude
            # an int failed on tolist(); a review)
            return str(value)
        if not isinstance(value, str | bytes) and hasattr(value, "tolist"):
            # a numpy scalar or array: its Python values (an array as nested lists, which
            # the field's rules then judge: a vector has three components)
            return plain(value.tolist())
        return value

    return {k.strip(): plain(v) for k, v in changes.items()}


def toml_text(data: Mapping[str, Any], header: str = "") -> str | None:
    """``data`` written as TOML (:func:`dump_toml`) after ``header`` as a comment; None if
    it holds a value TOML lacks, or if the text would not read back as ``data`` exactly
    (a NaN)."""
    comment = "".join(f"# {_control_escaped(line)}\n" for line in header.splitlines())
    try:
        text = comment + dump_toml(data)
        same = tomllib.loads(text) == data
    except (TypeError, tomllib.TOMLDecodeError):
        return None
    return text if same else None


def dump_toml(data: Mapping[str, Any]) -> str:
    """A table as :mod:`tomllib` reads it (tables, arrays, strings, numbers, booleans)
    written as TOML: its values, then its sub-tables as ``[a.b]`` sections. TypeError for a
    value of another type."""
    lines: list[str] = []
    _table_lines(lines, [], data)
    return "\n".join(lines) + "\n"


def _table_lines(lines: list[str], where: list[str], table: Mapping[str, Any]) -> None:
    """Appends ``table``'s values, then its sub-tables as ``[a.b]`` sections."""
    for key, value in table.items():
        if not isinstance(value, Mapping):
            lines.append(f"{_key(key)} = {_inline(value)}")
    for key, value in table.items():
        if isinstance(value, Mapping):
            lines.extend(["", f"[{'.'.join(_key(k) for k in [*where, key])}]"])
            _table_lines(lines, [*where, key], value)


def _control_escaped(text: str) -> str:
    """``text`` with the characters a TOML comment must not hold (control characters but
    the tab, and DEL) as ``\\uXXXX``."""
    return re.sub(r"[\x00-\x08\x0a-\x1f\x7f]", lambda m: f"\\u{ord(m.group()):04x}", text)


def _key(key: str) -> str:
    """A TOML key: bare where it may be, else quoted."""
    return key if re.fullmatch(r"[A-Za-z0-9_-]+", key) else _string(key)


def _string(text: str) -> str:
    """A TOML basic string (JSON's escapes are TOML's; DEL must be escaped too)."""
    return json.dumps(text, ensure_ascii=False).replace("\x7f", "\\u007f")


def _shown(value: Any) -> str:
    """A changed value as a comment shows it: inline TOML where it is a TOML value."""
    if value is None:
        return "none (removed)"
    try:
        return _inline(value)
    except TypeError:
        return repr(value)


def _inline(value: Any) -> str:
    """A value written inline; TypeError for a type TOML (as read by tomllib) lacks."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):  # float's own repr: numpy's shows its type
        return float.__repr__(value) if math.isfinite(value) else str(float(value))
    if isinstance(value, str):
        return _string(value)
    if isinstance(value, list | tuple):
        return "[" + ", ".join(_inline(v) for v in value) + "]"
    if isinstance(value, Mapping):
        return "{" + ", ".join(f"{_key(k)} = {_inline(v)}" for k, v in value.items()) + "}"
    raise TypeError(f"{type(value).__name__} is no TOML value")


def parse_config(
    data: Mapping[str, Any], *, source: str | None = None, si_numbers: bool = False
) -> BearingConfig:
    """Validate a configuration mapping (as read from TOML).

    ``si_numbers=True`` accepts bare numbers for dimensional fields and takes them as SI
    (for re-validating ``BearingConfig.model_dump()``); files never use it.
    """
    if not isinstance(data, Mapping):
        raise ConfigError(
            f"{source or 'configuration'}: expected a table of sections, got {type(data).__name__}",
            source=source,
        )
    head = f"invalid configuration{f' {source}' if source else ''}"
    try:
        huge = _huge_integers(data)
        if huge:
            # validated with each such integer as inf (refused by every field, but without
            # its OverflowError), its own problem in place of what the field says of inf
            data = _replaced(data, {loc for loc, _ in huge}, math.inf)
        try:
            config = BearingConfig.model_validate(dict(data), context={SI_NUMBERS: si_numbers})
        except ValidationError as exc:
            problems = problems_from(exc, data)
        else:
            problems = []
    except RecursionError:
        raise ConfigError(f"{head}: values nested too deeply", source=source) from None
    if huge:
        own = [Problem(".".join(map(str, loc)), _show(value), INTEGER_RULE) for loc, value in huge]
        problems = own + [
            pr for pr in problems if not any(_related(pr.path, mine.path) for mine in own)
        ]
    if problems:
        n = len(problems)
        # every problem stays in .problems; the message lists the first ones (200 000
        # unknown keys gave 200 000 lines; a review)
        lines = [f"{head} ({n} problem{'s' if n != 1 else ''}):", *map(str, problems[:SHOWN])]
        if n > SHOWN:
            lines.append(f"... and {n - SHOWN} more problems")
        raise ConfigError("\n".join(lines), problems, source)
    return config


#: The most problems a :class:`ConfigError`'s message lists (its ``problems`` hold all).
SHOWN = 20

#: The largest of TOML's integers (the TOML specification: 64-bit signed, -2^63 ... 2^63
#: - 1, read losslessly or refused; Python's tomllib reads any): far beyond them a number
#: field would overflow a float.
INTEGER_LIMIT = 2**63 - 1
INTEGER_RULE = (
    "an integer beyond TOML's 64-bit range (-2^63 ... 2^63 - 1); write a large value as "
    "a float (1e20) or with a unit"
)


def _huge_integers(data: Any) -> list[tuple[tuple[str | int, ...], int]]:
    """The places (key paths) and values of the integers in ``data`` (tables and arrays)
    beyond TOML's range (:data:`INTEGER_LIMIT`), found without recursion (a table may nest
    deeply)."""
    found = []
    stack: list[tuple[tuple[str | int, ...], Any]] = [((), data)]
    while stack:
        loc, value = stack.pop()
        if isinstance(value, Mapping):
            stack.extend(((*loc, k), v) for k, v in value.items())
        elif isinstance(value, list | tuple):
            stack.extend(((*loc, i), v) for i, v in enumerate(value))
        elif isinstance(value, int) and not -INTEGER_LIMIT - 1 <= value <= INTEGER_LIMIT:
            found.append((loc, value))
    return sorted(found, key=lambda item: [str(part) for part in item[0]])


def _replaced(data: Any, locs: set[tuple[str | int, ...]], by: Any, at: tuple = ()) -> Any:
    """``data`` with the values at ``locs`` replaced ``by`` (the rest shared)."""
    if at in locs:
        return by
    if not any(loc[: len(at)] == at for loc in locs):
        return data
    if isinstance(data, Mapping):
        return {k: _replaced(v, locs, by, (*at, k)) for k, v in data.items()}
    return [_replaced(v, locs, by, (*at, i)) for i, v in enumerate(data)]


def _related(a: str, b: str) -> bool:
    """Whether the dotted paths ``a`` and ``b`` are the same, or one lies inside the other."""
    return a == b or a.startswith(b + ".") or b.startswith(a + ".")
