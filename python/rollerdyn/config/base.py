"""Building blocks of the configuration schema: the limits it enforces, the base class of
every section, time tables and the load and speed histories (a value or a table), field
hints and the collector of cross-field problems.

:mod:`.schema` builds the sections from these; :mod:`.errors` renders what ``_Cross``
collects.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Annotated, Any, Union

from pydantic import (
    AfterValidator,
    BaseModel,
    ConfigDict,
    Discriminator,
    Field,
    Tag,
    create_model,
    model_validator,
)
from pydantic_core import PydanticCustomError

from ..units import Quantity

#: 0 degC in K: the Vogel and Dicke laws take the temperature in degC.
T0_CELSIUS = 273.15
#: Reference temperature of ``lubricant.density.rho_15`` (15 degC), K.
T_DENSITY_REF = 288.15

# Limits on what drives a run's cost or lies beyond any bearing (refused before any work).
#: Slices per roller: 500 slices of a 5 mm roller are 10 um wide; the cost grows with them.
MAX_SLICES = 500
#: Hertz pressure of the heaviest roller above which a load is refused [Pa] (2.5 times the
#: 4 GPa that ISO 76 allows a roller bearing statically).
MAX_HERTZ_PRESSURE = 10e9
#: Pitch-circle speed above which an inner ring speed is refused [m/s] (the fastest rolling
#: bearings, hybrid spindle bearings with n*d_m of about 3e6 mm/min, reach about 160 m/s).
MAX_PITCH_SPEED = 300.0

#: Largest prescribed inner ring misalignment, either way [deg].
MAX_MISALIGNMENT_DEG = 1.0


class _Cross:
    """Collects cross-field problems inside a model validator and raises them together.

    Each problem is (relative location, value shown if the raw input has none, rule).
    """

    def __init__(self) -> None:
        self.items: list[tuple[tuple[str | int, ...], str, str]] = []

    def add(self, loc: str | tuple[str | int, ...], shown: str, rule: str) -> None:
        loc = tuple(loc.split(".")) if isinstance(loc, str) else loc
        self.items.append((loc, shown, rule))

    def raise_if_any(self) -> None:
        if self.items:
            summary = "; ".join(f"{'.'.join(map(str, loc))}: {rule}" for loc, _, rule in self.items)
            raise PydanticCustomError(
                "cross_field", "{summary}", {"summary": summary, "problems": tuple(self.items)}
            )


def _mm(x: float) -> str:
    return f"{x * 1e3:.6g} mm"


class _Section(BaseModel):
    model_config = ConfigDict(
        extra="forbid", frozen=True, validate_default=True, allow_inf_nan=False
    )


def _table_type(value_type: Any, label: str) -> type[TimeTable]:
    return create_model(  # type: ignore[call-overload]
        f"{label}Table",
        __base__=TimeTable,
        table=(tuple[tuple[Quantity("time", ge=0.0), value_type], ...], ...),
    )


class TimeTable(_Section):
    """A time history: rows ``[time, value]``, linear in between, held beyond the ends."""

    table: tuple[tuple[float, float], ...]

    @model_validator(mode="after")
    def _check_rows(self) -> TimeTable:
        cross = _Cross()
        if len(self.table) < 2:
            cross.add(("table",), "", "a table needs at least 2 rows [time, value]")
        for i in range(1, len(self.table)):
            if self.table[i][0] <= self.table[i - 1][0]:
                cross.add(
                    ("table", i, 0),
                    f"{self.table[i][0]:g} s",
                    f"times must be strictly increasing: row {i} time "
                    f"{self.table[i][0]:g} s is not after row {i - 1} time "
                    f"{self.table[i - 1][0]:g} s",
                )
        cross.raise_if_any()
        return self

    @property
    def times(self) -> tuple[float, ...]:
        return tuple(r[0] for r in self.table)

    @property
    def values(self) -> tuple[float, ...]:
        return tuple(r[1] for r in self.table)

    @property
    def end(self) -> float:
        """Time of the last row, s."""
        return self.table[-1][0]

    @property
    def final(self) -> float:
        """Value held after the last row (SI)."""
        return self.table[-1][1]

    def value_at(self, t: float) -> float:
        """Linear interpolation in the table, constant before the first and after the last row."""
        rows = self.table
        if t <= rows[0][0]:
            return rows[0][1]
        for (t0, v0), (t1, v1) in zip(rows, rows[1:], strict=False):
            if t <= t1:
                return v0 + (v1 - v0) * (t - t0) / (t1 - t0)
        return rows[-1][1]


def _dispatch(value: Any) -> str:
    return "<table>" if isinstance(value, Mapping) or isinstance(value, TimeTable) else "<value>"


def QuantityOrTable(fam: str, label: str, **bounds: Any) -> Any:  # noqa: N802
    """A constant quantity ``"5000 N"`` or a time table ``{table = [["0 s", "0 N"], ...]}``."""
    value_type = Quantity(fam, **bounds)
    return Annotated[
        Union[  # noqa: UP007 - tags need the explicit form
            Annotated[value_type, Tag("<value>")],
            Annotated[_table_type(value_type, label), Tag("<table>")],
        ],
        Discriminator(_dispatch),
    ]


#: Load and speed histories: a constant (ramped) value or a time table.
ForceHistory = QuantityOrTable("force", "Force")
RadialHistory = QuantityOrTable("force", "RadialForce", ge=0.0)
SpeedHistory = QuantityOrTable("angular velocity", "AngularVelocity")


#: The control characters (C0 and DEL) a one-line text field refuses, and those a
#: free text refuses (it keeps tabs and line breaks).
_ONE_LINE_CONTROLS = re.compile(r"[\x00-\x1f\x7f]")
_FREE_TEXT_CONTROLS = re.compile(r"[\x00-\x08\x0b\x0c\x0e-\x1f\x7f]")


def control_character_rule(text: str, *, multiline: bool = False) -> str | None:
    """Why ``text`` cannot be a text field's value: the first control character it holds
    (a one-line text: any; a ``multiline`` one: any but tab, line feed and carriage
    return), or None. A result file stores the text (netCDF refuses a NUL), and names are
    printed in tables and comments."""
    found = (_FREE_TEXT_CONTROLS if multiline else _ONE_LINE_CONTROLS).search(text)
    if found is None:
        return None
    allowed = " (tabs and line breaks are allowed)" if multiline else ""
    return (
        f"must not hold control characters{allowed}: U+{ord(found.group()):04X} at "
        f"character {found.start() + 1}"
    )


def Text(*, multiline: bool = False, min_length: int = 0) -> Any:  # noqa: N802
    """A pydantic field type: a string without control characters
    (:func:`control_character_rule`), at least ``min_length`` characters long."""

    def check(value: str) -> str:
        rule = control_character_rule(value, multiline=multiline)
        if rule is not None:
            raise PydanticCustomError("quantity", "{rule}", {"rule": rule})
        return value

    return Annotated[str, Field(min_length=min_length), AfterValidator(check)]


@dataclass(frozen=True)
class Hint:
    """Field metadata: what the field expects, in words (for messages and docs)."""

    text: str

    def describe(self) -> str:
        return self.text
