"""Physical quantities at the configuration boundary.

A dimensional value in a configuration file is a string ``"<number> <unit>"``, e.g.
``"20 mm"``, ``"500 rpm"``, ``"80 degC"`` or ``"81 mPa*s"``. It is parsed with pint (one
module-level :data:`ureg`), checked against the *unit family* the field declares (length,
force, pressure, ...) and converted to a plain SI float. Everything behind this boundary
works with SI floats only: m, kg, s, N, Pa, Pa*s, rad, rad/s, K, ...

The conversion is decimally exact: the result is the float nearest to
``number * factor (+ offset)`` evaluated in decimal arithmetic, where ``factor`` is pint's
conversion factor to SI. So ``"20 mm"`` gives exactly ``0.02``, ``"10 um"`` exactly ``1e-05``
and ``"80 degC"`` exactly ``353.15``.

Temperatures come in two families that must not be confused:

* ``"temperature"`` -- an absolute temperature: ``"80 degC"``, ``"°C"``, ``"353.15 K"``,
  ``"176 degF"``. A temperature difference unit (``delta_degC``) is refused.
* ``"temperature interval"`` -- a temperature difference: ``"20 K"`` or
  ``"20 delta_degC"``. An offset unit (``degC``, ``°C``, ``degF``) is refused, because
  ``"20 degC"`` is ambiguous for a difference.

In compound units an offset unit can only mean a difference (``"2.9862 bar/degC"`` is
``2.9862 bar/K``); pint reads it that way and so do we.

Angles are dimensionless in SI, but an angle field still needs an angle unit (``deg``,
``rad``, ``arcmin``, ...), and an angular velocity needs one too (``rpm``, ``rad/s``,
``deg/s``); ``"50 Hz"`` or ``"50 1/s"`` is refused as a frequency, since it does not say
whether cycles or radians are meant.

The pydantic type factories :func:`Quantity`, :func:`Number` and :func:`Integer` make each
configuration field one line::

    inner_raceway_diameter: Quantity("length", positive=True)
    opening_angle: Quantity("angle", ge=0, lt="90 deg")
    poisson_ratio: Number(gt=0, lt=0.5)
    roller_count: Integer(ge=3)
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from decimal import Decimal, InvalidOperation, localcontext
from typing import Annotated, Any

import pint
from pydantic import BeforeValidator, ValidationInfo
from pydantic_core import PydanticCustomError

__all__ = [
    "FAMILIES",
    "parse_time",
    "Family",
    "Integer",
    "Number",
    "Q_",
    "Quantity",
    "QuantityError",
    "Vector",
    "VectorSpec",
    "QuantitySpec",
    "NumberSpec",
    "IntegerSpec",
    "describe_unit",
    "format_si",
    "parse_quantity",
    "ureg",
]

#: The one unit registry of rollerdyn. Use it (or :data:`Q_`) for every pint object.
ureg = pint.UnitRegistry(autoconvert_offset_to_baseunit=False)
Q_ = ureg.Quantity

#: Context key: ``model_validate(data, context={SI_NUMBERS: True})`` accepts bare numbers
#: for dimensional fields and reads them as SI (used to re-validate dumped configurations).
SI_NUMBERS = "si_numbers"


class QuantityError(ValueError):
    """A value that cannot be read as a quantity of the expected family."""


@dataclass(frozen=True)
class Family:
    """A unit family: the dimension a field expects, its SI unit and an example."""

    name: str
    dims: str  # pint dimensionality, e.g. "[length]" or "[mass] / [length] ** 3"
    si_unit: str
    example: str
    radian: int = 0  # power of radian in the root units (angles, angular velocities)
    temperature: str = ""  # "absolute" | "interval" | "" (not a bare temperature)

    @property
    def article(self) -> str:
        return ("an " if self.name[0] in "aeiou" else "a ") + self.name


def _families(*items: Family) -> dict[str, Family]:
    return {f.name: f for f in items}


#: Unit families that configuration fields may declare.
FAMILIES: dict[str, Family] = _families(
    Family("length", "[length]", "m", "20 mm"),
    Family("mass", "[mass]", "kg", "0.1 kg"),
    Family("time", "[time]", "s", "0.5 s"),
    Family("force", "[force]", "N", "5000 N"),
    Family("force per length", "[force] / [length]", "N/m", "1000 N/mm"),
    Family("torque", "[energy]", "N*m", "0.1 N*m"),
    Family("pressure", "[pressure]", "Pa", "210 GPa"),
    Family("pressure per temperature", "[pressure] / [temperature]", "Pa/K", "2.9862 bar/K"),
    Family("inverse temperature", "1 / [temperature]", "1/K", "3.0115e-4 1/K"),
    Family("angle", "[]", "rad", "0.11 deg", radian=1),
    Family("angular velocity", "1 / [time]", "rad/s", "500 rpm", radian=1),
    Family("speed", "[length] / [time]", "m/s", "1 mm/s"),
    Family("acceleration", "[acceleration]", "m/s^2", "9.81 m/s^2"),
    Family("temperature", "[temperature]", "K", "80 degC", temperature="absolute"),
    Family("temperature interval", "[temperature]", "K", "20 K", temperature="interval"),
    Family("dynamic viscosity", "[viscosity]", "Pa*s", "81 mPa*s"),
    Family("density", "[density]", "kg/m^3", "7850 kg/m^3"),
    Family("density per temperature", "[density] / [temperature]", "kg/m^3/K", "-0.6 kg/m^3/K"),
    Family("moment of inertia", "[mass] * [length] ** 2", "kg*m^2", "5e-6 kg*m^2"),
    Family(
        "thermal conductivity", "[power] / [length] / [temperature]", "W/(m*K)", "0.134 W/(m*K)"
    ),
    Family("thermal conductance", "[power] / [temperature]", "W/K", "0.35 W/K"),
    Family("volume flow", "[volume] / [time]", "m^3/s", "0.5 l/min"),
)

# Further families, only used to name what was given instead ("got a frequency").
_KNOWN: dict[str, Family] = _families(
    Family("frequency", "1 / [time]", "Hz", "50 Hz"),
    Family("dimensionless number", "[]", "", "1"),
    Family("area", "[area]", "m^2", "1 mm^2"),
    Family("volume", "[volume]", "m^3", "1 mm^3"),
    Family("energy or torque", "[energy]", "J", "1 N*m"),
    Family("power", "[power]", "W", "1 W"),
    Family("angular acceleration", "1 / [time] ** 2", "rad/s^2", "1 rad/s^2", radian=1),
    Family("kinematic viscosity", "[length] ** 2 / [time]", "m^2/s", "100 mm^2/s"),
    Family("stiffness", "[force] / [length]", "N/m", "1 N/m"),
)

_DIMS = {name: ureg.get_dimensionality(f.dims) for name, f in {**FAMILIES, **_KNOWN}.items()}

_OFFSET_UNITS = frozenset(
    name for name, d in ureg._units.items() if not d.converter.is_multiplicative
)

_EXPONENT_RE = re.compile(r"(\*\*|\^)\s*(?P<exp>[+-]?\d{1,3}(?:\.\d{1,3})?)(?P<after>\s*\S?)")
_POWER_RE = re.compile(r"\*\*|\^")


def _plain_exponents(unit_text: str) -> bool:
    """True if every power in ``unit_text`` is raised to a plain number of at most three
    digits that is not itself raised to a power. pint evaluates the unit as an arithmetic
    expression with Python integers, so "m**9**9**9" would take forever (found by
    fuzzing the configuration loader)."""
    powers = [m.start() for m in _POWER_RE.finditer(unit_text)]
    for start in powers:
        m = _EXPONENT_RE.match(unit_text, start)
        if m is None:
            return False
        after = m.group("after").strip()
        if after and (
            after in "^.0123456789" or unit_text[m.end("exp") :].lstrip().startswith("**")
        ):
            return False
    return True


_NUMBER_RE = re.compile(
    r"""^\s*(?P<num>[+-]?(?:(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?|nan|inf(?:inity)?))
        (?P<unit>.*?)\s*$""",
    re.IGNORECASE | re.VERBOSE,
)


def _radian_power(unit: pint.Unit) -> float:
    return ureg.get_root_units(unit)[1]._units.get("radian", 0)


def _matches(unit: pint.Unit, fam: Family) -> bool:
    if unit.dimensionality != _DIMS[fam.name]:
        return False
    return _radian_power(unit) == fam.radian


def _is_offset_unit(unit: pint.Unit) -> bool:
    return any(name in _OFFSET_UNITS for name in unit._units)


def _is_delta_temperature(unit: pint.Unit) -> bool:
    return any(name.startswith("delta_") for name in unit._units)


def describe_unit(unit: pint.Unit | str) -> str:
    """Name the family of a unit, with its article: ``describe_unit("N") == "a force"``."""
    if isinstance(unit, str):
        unit = ureg.parse_units(unit)
    if unit.dimensionality == _DIMS["temperature"]:
        if _is_delta_temperature(unit):
            return "a temperature interval"
        return "an absolute temperature" if _is_offset_unit(unit) else "a temperature"
    for fam in (*FAMILIES.values(), *_KNOWN.values()):
        if _matches(unit, fam):
            if fam.name == "dimensionless number" and unit.dimensionless and str(unit):
                return f"a dimensionless ratio ({unit:~})"
            return fam.article
    return f"a quantity of dimension {unit.dimensionality}"


def family(name: str) -> Family:
    """Look up a unit family by name (``"length"``) or pint dimension (``"[length]"``)."""
    if name in FAMILIES:
        return FAMILIES[name]
    if name.startswith("["):
        dims = ureg.get_dimensionality(name)
        found = [f for f in FAMILIES.values() if _DIMS[f.name] == dims]
        if len(found) == 1:
            return found[0]
        if len(found) > 1:
            names = ", ".join(repr(f.name) for f in found)
            raise ValueError(f"dimension {name} is ambiguous; name the family: {names}")
    raise ValueError(f"unknown unit family {name!r}; known: {', '.join(FAMILIES)}")


def _decimal_si(text: str, unit: pint.Unit, fam: Family) -> float:
    """SI value of ``text`` (a decimal number) in ``unit``, rounded once to a float."""
    factor = Q_(1.0, unit).to(fam.si_unit).magnitude
    offset = 0.0
    if fam.temperature == "absolute":
        offset = Q_(0.0, unit).to(fam.si_unit).magnitude
        factor = factor - offset
    try:
        with localcontext() as ctx:
            ctx.prec = 40
            value = Decimal(text) * Decimal(repr(factor)) + Decimal(repr(offset))
        return float(value)
    except InvalidOperation:  # pragma: no cover - the regex only lets numbers through
        return float(text) * factor + offset


def _show(value: Any) -> str:
    if isinstance(value, str):
        return f'"{value}"'
    return repr(value)


#: Newton metres written without a product sign ("Nm", "kNm", "Nmm"), which pint does not
#: read as newton times metre.
_RUN_TOGETHER_NEWTON_METRE = re.compile(r"^[kKmM]?Nm{1,2}$")


def parse_quantity(value: Any, fam: str | Family, *, si_numbers: bool = False) -> float:
    """Convert ``value`` (``"20 mm"`` or a pint quantity) of family ``fam`` to an SI float.

    Raises :class:`QuantityError` whose message states the rule that was broken.
    With ``si_numbers=True`` a bare int/float is accepted and taken to be in SI already.
    """
    fam = fam if isinstance(fam, Family) else family(fam)
    hint = f'expected {fam.article} with a unit, e.g. "{fam.example}"'
    if isinstance(value, bool):
        raise QuantityError(f"got a boolean; {hint}")
    if isinstance(value, int | float):
        if not math.isfinite(value):
            raise QuantityError(f"must be finite; {hint}")
        if si_numbers:
            return float(value)
        raise QuantityError(f"a bare number is ambiguous (no unit); {hint}")
    if isinstance(value, pint.Quantity):
        mag = value.magnitude
        if not isinstance(mag, int | float) or isinstance(mag, bool):
            raise QuantityError(f"expected a scalar quantity; {hint}")
        text, unit = repr(float(mag)), ureg.parse_units(str(value.units))
    elif isinstance(value, str):
        m = _NUMBER_RE.match(value.replace("\u2212", "-"))
        if m is None:
            raise QuantityError(f'expected "<number> <unit>"; {hint}')
        text, unit_text = m.group("num"), m.group("unit").strip().replace("·", "*")
        if not unit_text:
            raise QuantityError(f"a number without a unit is ambiguous; {hint}")
        if "," in unit_text:
            raise QuantityError(
                f"{value.strip()!r}: one number and its unit (no thousands separators, no "
                f"lists); {hint}"
            )
        if _RUN_TOGETHER_NEWTON_METRE.match(unit_text):
            # pint reads "Nm" as one unknown-to-the-user unit, not newton times metre
            product = unit_text.replace("Nm", "N*m", 1)
            raise QuantityError(
                f"unit {unit_text!r}: write newton metres with a product, e.g. "
                f'"{text} {product}"; {hint}'
            )
        if not _plain_exponents(unit_text):
            raise QuantityError(
                f"unit {unit_text!r}: an exponent must be a plain number (at most three "
                f"digits, not itself raised to a power); {hint}"
            )
        try:
            unit = ureg.parse_units(unit_text)
        # pint evaluates the unit as an arithmetic expression of Python tokens and fails in
        # many ways besides its own errors (found by fuzzing the configuration loader:
        # tokenize.TokenError for "5''' MPa", ZeroDivisionError for "A/0", KeyError for
        # "m**-0"); any failure to parse is an unknown unit.
        except Exception as exc:
            # a unit of 200 000 characters was echoed whole (a review)
            shown = unit_text if len(unit_text) <= 60 else unit_text[:57] + "..."
            raise QuantityError(
                f"unknown unit {shown!r} ({_pint_reason(exc)[:200]}); {hint}"
            ) from None
    else:
        raise QuantityError(
            f'expected a string such as "{fam.example}", got {type(value).__name__}'
        )

    if not math.isfinite(float(text)):
        raise QuantityError(f"must be finite; {hint}")
    if not _matches(unit, fam):
        if str(unit) == "dimensionless":  # e.g. "20 m/m": no unit left
            raise QuantityError(f"a number without a unit is ambiguous; {hint}")
        got = describe_unit(unit)
        raise QuantityError(f'expected {fam.article} (e.g. "{fam.example}"), got {got}')
    if fam.temperature == "absolute" and _is_delta_temperature(unit):
        raise QuantityError(
            'expected an absolute temperature (e.g. "80 degC" or "353.15 K"), '
            "got a temperature difference"
        )
    if fam.temperature == "interval" and _is_offset_unit(unit):
        raise QuantityError(
            f"a temperature on an offset scale ({unit:~}) is ambiguous for a temperature "
            f'difference; use K or delta_degC, e.g. "{text} K"'
        )
    si = _decimal_si(text, unit, fam)
    if fam.temperature == "absolute" and si <= 0.0:
        raise QuantityError("an absolute temperature must be above 0 K")
    return si


#: The shortest time an option takes [s] (as the solver's dt_max and output interval): below
#: it a checkpoint or end time would not move the run's clock (1e-40 s past t = 0.01 s).
SHORTEST_TIME = 1e-9


def parse_time(value: Any, name: str, zero: bool = False) -> float:
    """A finite time of at least 1 ns (``zero``: at least 0 s), in s, from a number of
    seconds, a number's text (``"0.05"``) or a quantity (``"50 ms"``), for options such as
    ``--t-end`` and ``t_end=``; raises :class:`ValueError` naming ``name``, the value and
    the rule."""
    shown = repr(value) if len(repr(value)) <= 40 else repr(value)[:37] + "..."
    least = "0 s" if zero else "1 ns"
    rule = f"must be a finite time of at least {least}, e.g. 50 ms, 0.05 s or 0.05 (seconds)"
    if isinstance(value, bool) or type(value).__name__ == "bool_":
        raise ValueError(f"{name} = {shown}: {rule}")
    inner = value.strip(" \t\r\n") if isinstance(value, str) else ""  # str.strip() takes \x1f
    if any(ord(c) < 32 or ord(c) == 127 for c in inner):
        raise ValueError(f"{name} = {shown}: a control character in it; {rule}")  # "2 ms\x00"
    if not isinstance(value, int | float | str):
        if not _real_scalar(value):
            raise ValueError(f"{name} = {shown}: {rule}")
        try:  # numpy's scalars and 0-d arrays, Fraction, Decimal: their value
            value = float(value)
        except (OverflowError, ValueError, TypeError):
            raise ValueError(f"{name} = {shown}: is not finite; {rule}") from None
    try:
        seconds = float(value)
    except OverflowError:  # an int beyond any float
        seconds = math.inf
    except ValueError:
        try:
            seconds = parse_quantity(value.strip(), "time")
        except QuantityError as err:  # its first clause says what is wrong, then a hint
            reason = str(err).split("; ")[0]
            raise ValueError(f"{name} = {shown}: {reason}; {rule}") from None
    if not math.isfinite(seconds):
        raise ValueError(f"{name} = {shown}: is not finite; {rule}")
    if not seconds >= (0.0 if zero else SHORTEST_TIME):
        raise ValueError(f"{name} = {shown}: {rule}")
    return seconds


def _real_scalar(value: Any) -> bool:
    """Whether ``value`` is one real number of another type than int and float: numpy's
    integer and floating scalars and 0-d arrays, ``fractions.Fraction``,
    ``decimal.Decimal``."""
    import decimal
    import numbers

    if isinstance(value, numbers.Real | decimal.Decimal):
        return True
    dtype, shape = getattr(value, "dtype", None), getattr(value, "shape", None)
    return shape == () and getattr(dtype, "kind", "") in ("i", "u", "f")


def _pint_reason(exc: Exception) -> str:
    """Why a unit text failed: pint's own words for a name it does not know, else that the
    text is no unit expression (pint's other failures speak of its parser's internals)."""
    if isinstance(exc, pint.errors.UndefinedUnitError):
        msg = str(exc).strip().splitlines()[0] if str(exc).strip() else type(exc).__name__
        return msg[:120]
    return "not a product or quotient of units with plain exponents, e.g. N*m or m/s^2"


def format_si(value: float, fam: str | Family) -> str:
    """``format_si(0.02, "length") == "0.02 m"``; for messages about derived values."""
    fam = fam if isinstance(fam, Family) else family(fam)
    if fam.temperature == "absolute":
        return f"{value:.6g} K ({value - 273.15:.6g} degC)"
    return f"{value:.6g} {fam.si_unit}".rstrip()


# --------------------------------------------------------------------------- pydantic types


def _bound(value: float | str | None, fam: Family | None) -> tuple[float, str] | None:
    """A bound given as an SI number or (for quantities) as a string with unit."""
    if value is None:
        return None
    if isinstance(value, str):
        if fam is None:
            raise TypeError("string bounds need a unit family")
        return parse_quantity(value, fam), value
    label = f"{value:g}" if fam is None or value == 0 else format_si(value, fam)
    return float(value), label


@dataclass(frozen=True)
class _Bounds:
    gt: tuple[float, str] | None = None
    ge: tuple[float, str] | None = None
    lt: tuple[float, str] | None = None
    le: tuple[float, str] | None = None

    def check(self, v: float) -> None:
        parts = []
        ok = True
        if self.gt is not None:
            parts.append(f"> {self.gt[1]}")
            ok &= v > self.gt[0]
        if self.ge is not None:
            parts.append(f">= {self.ge[1]}")
            ok &= v >= self.ge[0]
        if self.lt is not None:
            parts.append(f"< {self.lt[1]}")
            ok &= v < self.lt[0]
        if self.le is not None:
            parts.append(f"<= {self.le[1]}")
            ok &= v <= self.le[0]
        if not ok:
            raise QuantityError("must be " + " and ".join(parts))

    def describe(self) -> str:
        parts = []
        for op, b in ((">", self.gt), (">=", self.ge), ("<", self.lt), ("<=", self.le)):
            if b is not None:
                parts.append(f"{op} {b[1]}")
        return " and ".join(parts)


def _make_bounds(fam, gt, ge, lt, le, positive, nonnegative) -> _Bounds:
    if positive:
        gt = 0.0 if gt is None else gt
    if nonnegative:
        ge = 0.0 if ge is None else ge
    return _Bounds(_bound(gt, fam), _bound(ge, fam), _bound(lt, fam), _bound(le, fam))


@dataclass(frozen=True)
class QuantitySpec:
    """Metadata attached to a :func:`Quantity` field (read by messages and docs)."""

    family: Family
    bounds: _Bounds
    example: str

    def describe(self) -> str:
        rule = self.bounds.describe()
        return f"{self.family.article} ({self.family.si_unit})" + (f", {rule}" if rule else "")


@dataclass(frozen=True)
class NumberSpec:
    bounds: _Bounds

    def describe(self) -> str:
        rule = self.bounds.describe()
        return "a plain number" + (f", {rule}" if rule else "")


@dataclass(frozen=True)
class IntegerSpec:
    bounds: _Bounds

    def describe(self) -> str:
        rule = self.bounds.describe()
        return "an integer" + (f", {rule}" if rule else "")


def _custom(exc: Exception) -> PydanticCustomError:
    return PydanticCustomError("quantity", "{rule}", {"rule": str(exc)})


def _si_numbers(info: ValidationInfo | None) -> bool:
    ctx = info.context if info is not None else None
    return bool(ctx and ctx.get(SI_NUMBERS))


def Quantity(  # noqa: N802 - a type factory, used like a type
    fam: str,
    *,
    gt: float | str | None = None,
    ge: float | str | None = None,
    lt: float | str | None = None,
    le: float | str | None = None,
    positive: bool = False,
    nonnegative: bool = False,
    example: str | None = None,
) -> Any:
    """A pydantic field type: a quantity string of family ``fam``, stored as an SI float.

    ``fam`` is a family name (``"length"``, ``"temperature interval"``, see
    :data:`FAMILIES`) or an unambiguous pint dimension (``"[length]"``). Numeric bounds
    are SI; string bounds carry a unit (``lt="90 deg"``).
    """
    f = family(fam)
    if example:
        f = Family(f.name, f.dims, f.si_unit, example, f.radian, f.temperature)
    spec = QuantitySpec(f, _make_bounds(f, gt, ge, lt, le, positive, nonnegative), f.example)

    def validate(value: Any, info: ValidationInfo) -> float:
        try:
            si = parse_quantity(value, f, si_numbers=_si_numbers(info))
            spec.bounds.check(si)
        except QuantityError as exc:
            raise _custom(exc) from None
        return si

    return Annotated[float, BeforeValidator(validate), spec]


@dataclass(frozen=True)
class VectorSpec:
    """Metadata of a :func:`Vector` field (for docs and error messages)."""

    family: Family
    example: str

    def describe(self) -> str:
        return (
            f"{self.family.name}: one quantity (along -y) or a list of three (x, y, z), "
            f"finite, magnitude <= {self.bound:g} {self.family.si_unit}"
        )

    bound: float = 1e4


def Vector(fam: str, *, example: str, bound: float = 1e4) -> Any:  # noqa: N802
    """A pydantic field type: a vector of quantities of family ``fam`` in SI, as a tuple
    (x, y, z). A single quantity is its magnitude along -y (down, with the radial load);
    a list gives the three components. Its magnitude must not exceed ``bound`` (SI)."""
    f = family(fam)
    spec = VectorSpec(f, example, bound)

    def validate(value: Any, info: ValidationInfo) -> tuple[float, float, float]:
        try:
            if isinstance(value, list | tuple):
                if len(value) != 3:
                    raise QuantityError(
                        f"a vector needs three components (x, y, z), got {len(value)}"
                    )
                parts = [parse_quantity(v, f, si_numbers=_si_numbers(info)) for v in value]
            else:
                parts = [0.0, -parse_quantity(value, f, si_numbers=_si_numbers(info)), 0.0]
            if not all(math.isfinite(v) for v in parts):
                raise QuantityError("every component must be finite")
            if math.hypot(*parts) > bound:
                raise QuantityError(f"magnitude must be <= {bound:g} {f.si_unit}")
        except QuantityError as exc:
            raise _custom(exc) from None
        return (parts[0], parts[1], parts[2])

    return Annotated[tuple[float, float, float], BeforeValidator(validate), spec]


def Number(  # noqa: N802
    *,
    gt: float | None = None,
    ge: float | None = None,
    lt: float | None = None,
    le: float | None = None,
    positive: bool = False,
    nonnegative: bool = False,
) -> Any:
    """A pydantic field type: a finite plain (dimensionless) number, int or float."""
    spec = NumberSpec(_make_bounds(None, gt, ge, lt, le, positive, nonnegative))

    def validate(value: Any) -> float:
        try:
            if isinstance(value, bool) or not isinstance(value, int | float):
                if isinstance(value, str | pint.Quantity):
                    raise QuantityError(
                        "expected a plain number without unit (this field is dimensionless)"
                    )
                raise QuantityError(f"expected a plain number, got {type(value).__name__}")
            if not math.isfinite(value):
                raise QuantityError("must be finite")
            spec.bounds.check(float(value))
        except QuantityError as exc:
            raise _custom(exc) from None
        return float(value)

    return Annotated[float, BeforeValidator(validate), spec]


def Integer(*, ge: int | None = None, le: int | None = None) -> Any:  # noqa: N802
    """A pydantic field type: an integer (a float such as ``20.0`` or a bool is refused)."""
    spec = IntegerSpec(_make_bounds(None, None, ge, None, le, False, False))

    def validate(value: Any) -> int:
        try:
            if isinstance(value, bool) or not isinstance(value, int):
                raise QuantityError("expected an integer")
            spec.bounds.check(value)
        except QuantityError as exc:
            raise _custom(exc) from None
        return value

    return Annotated[int, BeforeValidator(validate), spec]
