"""Error rendering of the configuration: :class:`Problem`, :class:`ConfigError` and
:func:`problems_from`, which turns pydantic's validation errors into one line per problem,
``<path>: <value as given> — <rule>``, with the value as written in the file.
"""

from __future__ import annotations

import difflib
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any, Literal, get_args, get_origin

from pydantic import BaseModel, ValidationError
from pydantic.fields import FieldInfo

from ..units import IntegerSpec, NumberSpec, QuantitySpec, VectorSpec
from .base import Hint, TimeTable
from .schema import _FLANGE_OVERRIDES, MOVED_FIELDS, BearingConfig


@dataclass(frozen=True)
class Problem:
    """One problem in a configuration: where, the value as given, and the rule broken."""

    path: str
    value: str
    rule: str

    def __str__(self) -> str:
        return f"{self.path}: {self.value} — {self.rule}"


class ConfigError(ValueError):
    """An invalid, unreadable or missing configuration.

    ``str(err)`` lists every problem on its own line as ``<path>: <value> — <rule>``;
    :attr:`problems` holds them as :class:`Problem` objects; :attr:`source` is the file.
    """

    def __init__(self, message: str, problems: Sequence[Problem] = (), source: str | None = None):
        super().__init__(message)
        self.problems: tuple[Problem, ...] = tuple(problems)
        self.source = source


# --------------------------------------------------------------------------- messages

_MISSING = object()


def _show(value: Any) -> str:
    """A value as it would be written in TOML (strings quoted), shortened if long."""
    if value is _MISSING:
        return "(missing)"
    if isinstance(value, str):
        s = '"' + _escaped(value.replace("\\", "\\\\").replace('"', '\\"')) + '"'
    elif isinstance(value, int) and not isinstance(value, bool) and value.bit_length() > 200:
        s = f"(an integer of about {int(value.bit_length() * 0.30103) + 1} digits)"
    elif isinstance(value, bool):
        s = "true" if value else "false"
    elif isinstance(value, Mapping):
        s = "{" + ", ".join(f"{k} = {_show(v)}" for k, v in value.items()) + "}"
    elif isinstance(value, list | tuple):
        s = "[" + ", ".join(_show(v) for v in value) + "]"
    else:
        s = repr(value)
    return s if len(s) <= 80 else s[:77] + "..."


_ESCAPES = {"\n": "\\n", "\t": "\\t", "\r": "\\r"}


def _escaped(text: str) -> str:
    """``text`` with its control characters escaped as TOML writes them (``\\n``,
    ``\\u0000``), so that a message shows them and holds none."""
    return re.sub(
        r"[\x00-\x1f\x7f]", lambda m: _ESCAPES.get(m.group(), f"\\u{ord(m.group()):04x}"), text
    )


def _raw(data: Any, loc: Sequence[str | int]) -> Any:
    cur = data
    for part in loc:
        if isinstance(cur, Mapping) and part in cur:
            cur = cur[part]
        elif isinstance(cur, list | tuple) and isinstance(part, int) and 0 <= part < len(cur):
            cur = cur[part]
        else:
            return _MISSING
    return cur


def _raw_or_inherited(data: Any, loc: tuple[str | int, ...]) -> tuple[Any, bool]:
    """Raw value at ``loc``; flange overrides fall back to ``geometry.flange`` (inherited)."""
    value = _raw(data, loc)
    if value is _MISSING and len(loc) >= 3 and loc[0] == "geometry" and loc[1] in _FLANGE_OVERRIDES:
        value = _raw(data, ("geometry", "flange", *loc[2:]))
        return value, value is not _MISSING
    return value, False


def _annotation_models(ann: Any) -> list[type[BaseModel]]:
    if isinstance(ann, type) and issubclass(ann, BaseModel):
        return [ann]
    out: list[type[BaseModel]] = []
    for arg in get_args(ann):
        out.extend(_annotation_models(arg))
    return out


def _field_at(loc: Sequence[str | int]) -> FieldInfo | None:
    """The field info of the (dotted) location ``loc``, or None."""
    cls: type[BaseModel] | None = BearingConfig
    info: FieldInfo | None = None
    for part in loc:
        if cls is None or not isinstance(part, str) or part not in cls.model_fields:
            return None
        info = cls.model_fields[part]
        models = _annotation_models(info.annotation)
        cls = models[0] if models else None
    return info


def _section_model(loc: Sequence[str | int]) -> type[BaseModel] | None:
    """The model class of the section at ``loc`` (``()`` is the top level)."""
    if not loc:
        return BearingConfig
    info = _field_at(loc)
    models = _annotation_models(info.annotation) if info is not None else []
    return models[0] if models else None


def _metadata(info: FieldInfo) -> list[Any]:
    found = list(info.metadata)
    stack = [info.annotation]
    while stack:
        ann = stack.pop()
        if hasattr(ann, "__metadata__"):
            found.extend(ann.__metadata__)
        stack.extend(get_args(ann))
    return found


def _expectation(info: FieldInfo | None) -> str:
    """What a field expects, for 'required' messages and the docs."""
    if info is None:
        return ""
    ann = info.annotation
    for meta in _metadata(info):
        if isinstance(meta, VectorSpec):
            return f"{meta.describe()}, e.g. {meta.example}"
    if get_origin(ann) is tuple:
        return "an array of [time, value] rows"
    table = any(issubclass(m, TimeTable) for m in _annotation_models(ann))
    alt = " or a time table {table = [[time, value], ...]}" if table else ""
    for meta in _metadata(info):
        if isinstance(meta, QuantitySpec):
            return f'{meta.describe()}, e.g. "{meta.example}"{alt}'
        if isinstance(meta, NumberSpec | IntegerSpec | Hint):
            return meta.describe()
    if _annotation_models(ann):
        return "a [section] table"
    if get_origin(ann) is Literal:
        return "one of " + ", ".join(f'"{a}"' for a in get_args(ann))
    if ann is str:
        return "a string"
    return ""


def _rule_for(err: Mapping[str, Any], loc: tuple[str | int, ...]) -> str:
    typ, ctx = err["type"], err.get("ctx") or {}
    if typ == "quantity":
        return str(ctx["rule"])
    if typ in ("model_type", "model_attributes_type", "dict_type"):
        return "expected a table (a [section] or {inline table})"
    if typ == "literal_error":
        return f"must be one of {ctx.get('expected', '')}".replace("'", '"')
    if typ == "string_type":
        return "expected a string"
    if typ == "bool_type":
        return "expected true or false (a TOML boolean)"
    if typ == "string_too_short":
        return "must not be empty"
    if typ in ("tuple_type", "list_type"):
        return "expected an array"
    if typ == "too_short" and loc and isinstance(loc[-1], int):
        return "each row must be [time, value]"
    if typ == "too_long" and loc and isinstance(loc[-1], int):
        return "each row must be [time, value]"
    msg = str(err.get("msg", typ))
    return msg.removeprefix("Value error, ")


def problems_from(exc: ValidationError, data: Any) -> list[Problem]:
    """Turn a pydantic ``ValidationError`` into :class:`Problem` lines (values as given)."""
    out: list[Problem] = []
    seen: set[tuple[str, str]] = set()

    def add(loc: tuple[str | int, ...], value: str, rule: str, inherited: bool = False) -> None:
        path = ".".join(map(str, loc)) or "<top level>"
        if inherited:
            # the same inherited value failing the same rule at geometry.flange: say it once
            if (".".join(map(str, ("geometry", "flange", *loc[2:]))), rule) in seen:
                return
            value += " (inherited from geometry.flange)"
        if (path, rule) in seen:
            return
        seen.add((path, rule))
        out.append(Problem(path, value, rule))

    def user_part(p: str | int) -> bool:
        """Not one of pydantic's own location markers ("<wrapped>" and the like)."""
        return not (isinstance(p, str) and p.startswith("<"))

    for err in exc.errors(include_url=False):
        loc = tuple(filter(user_part, err["loc"]))
        typ = err["type"]
        if typ == "cross_field":
            for rel, shown, rule in err["ctx"]["problems"]:
                full = loc + tuple(rel)
                raw, inherited = _raw_or_inherited(data, full)
                value = _show(raw) if raw is not _MISSING else (shown or "(see rule)")
                add(full, value, rule, inherited)
            continue
        if typ == "extra_forbidden" and ".".join(map(str, loc)) in MOVED_FIELDS:
            new_place, why = MOVED_FIELDS[".".join(map(str, loc))]
            add(loc, _show(err.get("input")), f"has moved to {new_place} ({why})")
            continue
        if typ == "extra_forbidden":
            # the unknown key is the location's last part, even one that starts with "<"
            section, key = tuple(filter(user_part, err["loc"][:-1])), err["loc"][-1]
            loc = (*section, key)
            model = _section_model(section)
            name = ".".join(map(str, section)) or "<top level>"
            rule = f"unknown key '{key}' in section '{name}'"
            if model is not None:
                allowed = list(model.model_fields)
                close = difflib.get_close_matches(str(key), allowed, n=1)
                rule += f" (allowed: {', '.join(allowed)})"
                if close:
                    rule += f"; did you mean '{close[0]}'?"
            add(loc, _show(err.get("input")), rule)
            continue
        if typ == "missing" and loc and isinstance(loc[-1], int):  # short table row
            add(loc[:-1], _show(_raw(data, loc[:-1])), "each row must be [time, value]")
            continue
        if typ == "missing":
            info = _field_at(loc)
            expect = _expectation(info)
            add(loc, "(missing)", "required" + (f": {expect}" if expect else ""))
            continue
        raw, inherited = _raw_or_inherited(data, loc)
        value = _show(raw if raw is not _MISSING else err.get("input"))
        add(loc, value, _rule_for(err, loc), inherited)
    return out
