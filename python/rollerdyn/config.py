"""Bearing configuration: the TOML schema, its validation and the derived quantities.

A configuration file (see ``examples/b1.toml`` and ``docs/configuration.md``) is read with
:func:`load_config`, a dict with :func:`parse_config`. Both return a frozen
:class:`BearingConfig` whose numeric fields are plain SI floats; dimensional values are
converted at the boundary by :mod:`rollerdyn.units`. Every problem found is reported at
once in a :class:`ConfigError`, one line per problem::

    geometry.roller.edge_radius: "3 mm" — must be < roller diameter/2 = 2.2475 mm

Derived quantities (roller diameter, pitch diameter, effective Vogel factor, end time,
roller mass properties, ...) are properties, never typed into the file.
"""

from __future__ import annotations

import difflib
import math
import re
import tomllib
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from functools import cached_property
from pathlib import Path
from typing import Annotated, Any, Literal, Union, get_args, get_origin

from pydantic import (
    BaseModel,
    BeforeValidator,
    ConfigDict,
    Discriminator,
    Field,
    PrivateAttr,
    Tag,
    ValidationError,
    create_model,
    model_validator,
)
from pydantic.fields import FieldInfo
from pydantic_core import PydanticCustomError

from .units import (
    SI_NUMBERS,
    Integer,
    IntegerSpec,
    Number,
    NumberSpec,
    Quantity,
    QuantitySpec,
    Vector,
    VectorSpec,
    format_si,
)

__all__ = [
    "BearingConfig",
    "ConfigError",
    "Problem",
    "TimeTable",
    "fit_roelands_z",
    "load_config",
    "parse_config",
    "problems_from",
]

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


# --------------------------------------------------------------------------- errors


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


# --------------------------------------------------------------------------- base types


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


def _ramp_factor(shape: str, x: float) -> float:
    x = min(1.0, max(0.0, x))
    return x if shape == "linear" else 0.5 * (1.0 - math.cos(math.pi * x))


# --------------------------------------------------------------------------- geometry


class RollerConfig(_Section):
    """``[geometry.roller]``: one roller (all rollers are equal)."""

    length: Quantity("length", positive=True, example="5 mm")
    edge_radius: Quantity("length", positive=True, example="0.5 mm")
    end_face_radius: Quantity("length", positive=True, example="5000 mm")
    profile: Literal["straight", "crowned"] = "straight"
    crown_drop: Quantity("length", nonnegative=True, example="2 um") = "0 um"
    crown_length: Quantity("length", positive=True, example="1 mm") | None = None
    slices: Integer(ge=1, le=MAX_SLICES) = 20

    @model_validator(mode="after")
    def _check(self) -> RollerConfig:
        cross = _Cross()
        straight = self.length - 2.0 * self.edge_radius
        if straight <= 0.0:
            cross.add(
                "edge_radius",
                _mm(self.edge_radius),
                f"must be < length/2 = {_mm(self.length / 2)} "
                "(the roller length must exceed 2*edge_radius)",
            )
        if self.profile == "straight":
            if self.crown_drop != 0.0:
                cross.add(
                    "crown_drop",
                    _mm(self.crown_drop),
                    'a crown drop needs profile = "crowned" (profile is "straight")',
                )
            if self.crown_length is not None:
                cross.add(
                    "crown_length",
                    _mm(self.crown_length),
                    'crown_length is only used with profile = "crowned"',
                )
        else:
            if self.crown_drop <= 0.0:
                cross.add("crown_drop", _mm(self.crown_drop), "must be > 0 for a crowned profile")
            if self.crown_length is None:
                cross.add("crown_length", "(missing)", "required for a crowned profile")
            elif straight > 0.0 and self.crown_length > straight / 2.0:
                cross.add(
                    "crown_length",
                    _mm(self.crown_length),
                    "must be <= (length - 2*edge_radius)/2 = "
                    f"{_mm(straight / 2)} (the crowned zone at each end)",
                )
        cross.raise_if_any()
        return self

    @property
    def effective_length(self) -> float:
        """Length of the generatrix between the edge tori, ``length - 2*edge_radius``, m."""
        return self.length - 2.0 * self.edge_radius

    @property
    def slice_width(self) -> float:
        """Width of one slice, ``effective_length / slices``, m."""
        return self.effective_length / self.slices


class FlangeConfig(_Section):
    """``[geometry.flange]``: a cone between a root torus (at the raceway) and a rim torus."""

    opening_angle: Quantity("angle", ge=0.0, lt="90 deg", example="0.11 deg")
    height: Quantity("length", positive=True, example="1.1 mm")
    root_radius: Quantity("length", positive=True, example="0.2 mm")
    rim_radius: Quantity("length", positive=True, example="0.3 mm")
    axial_play: Quantity("length", nonnegative=True, example="20 um")


_FLANGE_OVERRIDES = ("inner_ring_flange", "outer_ring_flange")


class GeometryConfig(_Section):
    """``[geometry]``: raceways, clearance, outer ring wall, roller and flanges."""

    roller_count: Integer(ge=3)
    inner_raceway_diameter: Quantity("length", positive=True, example="20 mm")
    outer_raceway_diameter: Quantity("length", positive=True, example="29 mm")
    diametral_clearance: Quantity("length", nonnegative=True, example="10 um")
    outer_ring_wall_thickness: Quantity("length", positive=True, example="2.5 mm")
    roller: RollerConfig
    flange: FlangeConfig
    inner_ring_flange: FlangeConfig | None = None
    outer_ring_flange: FlangeConfig | None = None

    @model_validator(mode="before")
    @classmethod
    def _merge_flange_overrides(cls, data: Any) -> Any:
        # geometry.inner_ring_flange / outer_ring_flange override single keys of geometry.flange
        if isinstance(data, Mapping) and isinstance(data.get("flange"), Mapping):
            data = dict(data)
            for key in _FLANGE_OVERRIDES:
                if isinstance(data.get(key), Mapping):
                    data[key] = {**data["flange"], **data[key]}
        return data

    @model_validator(mode="after")
    def _check(self) -> GeometryConfig:
        cross = _Cross()
        d_i, d_o, c = (
            self.inner_raceway_diameter,
            self.outer_raceway_diameter,
            self.diametral_clearance,
        )
        if d_o <= d_i:
            cross.add(
                "outer_raceway_diameter",
                _mm(d_o),
                f"must be > inner_raceway_diameter ({_mm(d_i)})",
            )
            cross.raise_if_any()
        dia = self.roller_diameter
        if dia <= 0.0:
            cross.add(
                "diametral_clearance",
                _mm(c),
                "leaves no room for rollers: roller diameter (D_o - D_i)/2 - clearance/2 = "
                f"{_mm(dia)} must be > 0",
            )
            cross.raise_if_any()
        gap = self.circumferential_gap
        if gap <= 0.0:
            z_max = math.ceil(math.pi / math.asin(min(1.0, dia / self.pitch_diameter))) - 1
            cross.add(
                "roller_count",
                str(self.roller_count),
                f"rollers do not fit: pitch_diameter*sin(pi/Z) - roller_diameter = {_mm(gap)} "
                f"must be > 0 (roller diameter {_mm(dia)}, pitch diameter "
                f"{_mm(self.pitch_diameter)}; at most {z_max} rollers fit)",
            )
        r = self.roller
        if r.edge_radius >= dia / 2.0:
            cross.add(
                "roller.edge_radius",
                _mm(r.edge_radius),
                f"must be < roller diameter/2 = {_mm(dia / 2)}",
            )
        if r.end_face_radius <= dia / 2.0:
            cross.add(
                "roller.end_face_radius",
                _mm(r.end_face_radius),
                f"must be > roller diameter/2 = {_mm(dia / 2)} (convex end face sphere)",
            )
        for key in ("flange", *_FLANGE_OVERRIDES):
            fl: FlangeConfig | None = getattr(self, key)
            if fl is None:
                continue
            if fl.height >= dia:
                cross.add(
                    f"{key}.height",
                    _mm(fl.height),
                    f"must be < roller diameter ({_mm(dia)}): the flange is taller than the roller",
                )
            if fl.height <= fl.root_radius + fl.rim_radius:
                cross.add(
                    f"{key}.height",
                    _mm(fl.height),
                    f"must be > root_radius + rim_radius = {_mm(fl.root_radius + fl.rim_radius)} "
                    "(room for the cone between the tori)",
                )
        cross.raise_if_any()
        return self

    @property
    def roller_diameter(self) -> float:
        """``(D_o - D_i)/2 - clearance/2``, m."""
        return (
            self.outer_raceway_diameter - self.inner_raceway_diameter
        ) / 2.0 - self.diametral_clearance / 2.0

    @property
    def pitch_diameter(self) -> float:
        """``(D_o + D_i)/2``, m."""
        return (self.outer_raceway_diameter + self.inner_raceway_diameter) / 2.0

    @property
    def circumferential_gap(self) -> float:
        """Gap between neighbouring rollers on the pitch circle, ``d_m*sin(pi/Z) - D``, m."""
        return self.pitch_diameter * math.sin(math.pi / self.roller_count) - self.roller_diameter

    @property
    def fill_ratio(self) -> float:
        """Share of the pitch circle covered by rollers, ``Z*D/(pi*d_m)``."""
        return self.roller_count * self.roller_diameter / (math.pi * self.pitch_diameter)

    @property
    def inner_flange(self) -> FlangeConfig:
        """Flange geometry of the inner ring (both sides)."""
        return self.inner_ring_flange or self.flange

    @property
    def outer_flange(self) -> FlangeConfig:
        """Flange geometry of the outer ring (both sides)."""
        return self.outer_ring_flange or self.flange


# --------------------------------------------------------------------------- materials


class MaterialConfig(_Section):
    """An isotropic elastic solid."""

    youngs_modulus: Quantity("pressure", positive=True, example="210 GPa")
    poisson_ratio: Number(gt=0.0, lt=0.5)
    density: Quantity("density", positive=True, example="7850 kg/m^3")


class MaterialsConfig(_Section):
    """``[materials.*]``: roller, inner ring and outer ring."""

    roller: MaterialConfig
    inner_ring: MaterialConfig
    outer_ring: MaterialConfig


class InnerRingConfig(_Section):
    """``[inner_ring]``: the inner ring together with its (rigid) shaft."""

    mass: Quantity("mass", positive=True, example="0.1 kg")
    axial_inertia: Quantity("moment of inertia", positive=True) | None = None
    transverse_inertia: Quantity("moment of inertia", positive=True) | None = None
    tilt: Literal["locked", "free"] = "locked"
    # Prescribed tilt of a locked ring about z (perpendicular to the radial load along -y and
    # the axial load along +x, as the paper's tilt, sect. 5.2); the ring's axis is
    # (cos g, sin g, 0) for the whole run.
    misalignment: Quantity("angle", ge="-1 deg", le="1 deg") = "0 deg"

    @model_validator(mode="after")
    def _check(self) -> InnerRingConfig:
        if self.tilt == "free" and self.misalignment != 0.0:
            cross = _Cross()
            cross.add(
                "misalignment",
                f"{self.misalignment:.6g} rad",
                'a prescribed misalignment needs tilt = "locked" '
                "(the free ring finds its own tilt)",
            )
            cross.raise_if_any()
        return self


# --------------------------------------------------------------------------- lubricant


class VogelConfig(_Section):
    """Vogel law ``eta0 = k*exp(b/(theta + c))``, theta in degC."""

    k: Quantity("dynamic viscosity", positive=True, example="0.062 mPa*s")
    b: Quantity("temperature interval", positive=True, example="1021.7 K")
    c: Quantity("temperature interval", example="101.5517 K")

    def eta0(self, temperature: float, k: float | None = None) -> float:
        """Viscosity at ambient pressure, Pa*s, at absolute ``temperature`` (K): eq. 20,
        evaluated by the Rust core."""
        import numpy as np

        from rollerdyn import _core

        eta, _ = _core.vogel_viscosity(
            np.array([temperature]), self.k if k is None else k, self.b, self.c
        )
        return float(eta[0])

    def pole(self) -> float:
        """Absolute temperature (K) of the Vogel pole ``theta = -c``."""
        return T0_CELSIUS - self.c


class ReferenceViscosityConfig(_Section):
    """A measured viscosity that rescales the Vogel factor ``k``."""

    temperature: Quantity("temperature", example="40 degC")
    viscosity: Quantity("dynamic viscosity", positive=True, example="81 mPa*s")


@dataclass(frozen=True)
class Hint:
    """Field metadata: what the field expects, in words (for messages and docs)."""

    text: str

    def describe(self) -> str:
        return self.text


def _z_value(value: Any) -> Any:
    if value == "fit":
        return value
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise PydanticCustomError(
            "quantity", "{rule}", {"rule": 'expected a positive number or "fit"'}
        )
    if not math.isfinite(value) or value <= 0.0:
        raise PydanticCustomError("quantity", "{rule}", {"rule": "must be finite and > 0"})
    return float(value)


class RoelandsConfig(_Section):
    """Roelands pressure-viscosity law (eq. 19)."""

    eta_p: Quantity("dynamic viscosity", positive=True) = "0.0631 mPa*s"
    p_p: Quantity("pressure", lt=0.0, example="-196 MPa") = "-196 MPa"
    z: Annotated[
        float | Literal["fit"], BeforeValidator(_z_value), Hint('a positive number or "fit"')
    ]
    z_fit: Literal["initial_slope", "least_squares"] = "initial_slope"
    fit_pressure_max: Quantity("pressure", positive=True) = "1 GPa"

    @model_validator(mode="after")
    def _check(self) -> RoelandsConfig:
        cross = _Cross()
        if self.z != "fit":
            for key in ("z_fit", "fit_pressure_max"):
                if key in self.model_fields_set:
                    cross.add(key, "", f'only used with z = "fit" (z is {self.z:g})')
        cross.raise_if_any()
        return self


class DickeConfig(_Section):
    """Dicke law ``eta = eta0*exp(p/(a1 + a2*theta + (b1 + b2*theta)*p))``, theta in degC."""

    a1: Quantity("pressure", positive=True, example="327.7918 bar")
    a2: Quantity("pressure per temperature", example="2.9862 bar/K")
    b1: Number()
    b2: Quantity("inverse temperature", example="3.0115e-4 1/K")

    def denominator(self, pressure: float, temperature: float) -> float:
        theta = temperature - T0_CELSIUS
        return self.a1 + self.a2 * theta + (self.b1 + self.b2 * theta) * pressure


class CarreauConfig(_Section):
    """Carreau shear thinning (eq. 21)."""

    tau0: Quantity("pressure", positive=True, example="5 MPa")
    n: Number(gt=0.0, le=1.0)


class LimitingShearStressConfig(_Section):
    """Bilinear limiting shear stress of Wang (eq. 50)."""

    chi: Number(ge=0.0)
    p_star: Quantity("pressure", positive=True, example="1.5 GPa")
    tau_l0: Quantity("pressure", positive=True, example="0.12 GPa")

    @model_validator(mode="after")
    def _check(self) -> LimitingShearStressConfig:
        cross = _Cross()
        at_zero = self.tau_l0 - self.chi * self.p_star
        if at_zero < -1e-9 * self.tau_l0:
            cross.add(
                "tau_l0",
                format_si(self.tau_l0, "pressure"),
                f"must be >= chi*p_star = {format_si(self.chi * self.p_star, 'pressure')} "
                "(else the limiting shear stress is negative at p = 0)",
            )
        cross.raise_if_any()
        return self


class AlphaStarFitConfig(_Section):
    """Temperature range of the fit ``alpha*(T) = c1*exp(c2*T) + c3*exp(c4*T)`` (eq. 32)."""

    t_min: Quantity("temperature") = "20 degC"
    t_max: Quantity("temperature") = "140 degC"

    @model_validator(mode="after")
    def _check(self) -> AlphaStarFitConfig:
        cross = _Cross()
        if self.t_min >= self.t_max:
            cross.add(
                "t_max",
                format_si(self.t_max, "temperature"),
                f"must be > t_min ({format_si(self.t_min, 'temperature')})",
            )
        cross.raise_if_any()
        return self


class LubricantDensityConfig(_Section):
    """Density ``rho(T) = rho_15 + slope*(T - 15 degC)``."""

    rho_15: Quantity("density", positive=True, example="887.6 kg/m^3")
    slope: Quantity("density per temperature", example="-0.6 kg/m^3/K")

    def at(self, temperature: float) -> float:
        """Density, kg/m^3, at absolute ``temperature`` (K)."""
        return self.rho_15 + self.slope * (temperature - T_DENSITY_REF)


def fit_roelands_z(
    eta0: float,
    eta_p: float,
    p_p: float,
    dicke: DickeConfig,
    temperature: float,
    method: str = "initial_slope",
    pressure_max: float = 1e9,
) -> float:
    """Roelands exponent ``z`` (eq. 19) matched to the Dicke law at ``temperature`` (K),
    computed by the Rust core (``rollerdyn-core::tribology::lubricant::fit_roelands_z``).

    ``initial_slope``: equal slopes ``d ln(eta)/dp`` at ``p = 0``;
    ``least_squares``: least squares in ``ln(eta)`` over ``(0, pressure_max]``.
    """
    from rollerdyn import _core

    return _core.fit_roelands_z(
        eta0, temperature, eta_p, p_p, dicke.a1, dicke.a2, dicke.b1, dicke.b2, method, pressure_max
    )


class LubricantConfig(_Section):
    """``[lubricant]``: rheology and thermal data of the oil."""

    name: Annotated[str, Field(min_length=1)]
    vogel: VogelConfig
    reference_viscosity: ReferenceViscosityConfig | None = None
    roelands: RoelandsConfig
    dicke: DickeConfig | None = None
    carreau: CarreauConfig
    limiting_shear_stress: LimitingShearStressConfig
    alpha_star_fit: AlphaStarFitConfig = Field(default_factory=AlphaStarFitConfig)
    density: LubricantDensityConfig
    thermal_conductivity: Quantity("thermal conductivity", positive=True)

    @model_validator(mode="after")
    def _check(self) -> LubricantConfig:
        cross = _Cross()
        if self.roelands.z == "fit" and self.dicke is None:
            cross.add(
                "roelands.z",
                '"fit"',
                'z = "fit" needs a [lubricant.dicke] section to fit against',
            )
        pole = self.vogel.pole()
        checks = [("alpha_star_fit.t_min", self.alpha_star_fit.t_min)]
        if self.reference_viscosity is not None:
            checks.append(("reference_viscosity.temperature", self.reference_viscosity.temperature))
        for loc, t in checks:
            if t <= pole:
                cross.add(
                    loc,
                    format_si(t, "temperature"),
                    f"must be above the Vogel pole theta = -c ({format_si(pole, 'temperature')})",
                )
        cross.raise_if_any()
        return self

    @property
    def vogel_scale(self) -> float:
        """Factor on ``vogel.k`` so that eta0 matches ``reference_viscosity`` (1 if none)."""
        ref = self.reference_viscosity
        if ref is None:
            return 1.0
        return ref.viscosity / self.vogel.eta0(ref.temperature)

    @property
    def vogel_k(self) -> float:
        """Effective Vogel factor ``k``, Pa*s (``vogel.k`` times :attr:`vogel_scale`)."""
        return self.vogel.k * self.vogel_scale

    def eta0(self, temperature: float) -> float:
        """Viscosity at ambient pressure, Pa*s, with the effective ``k``; ``temperature`` in K."""
        return self.vogel.eta0(temperature, k=self.vogel_k)

    def density_at(self, temperature: float) -> float:
        """Density, kg/m^3, at ``temperature`` (K)."""
        return self.density.at(temperature)

    def roelands_z_at(self, temperature: float) -> float:
        """Roelands ``z``: the given number, or the Dicke fit at ``temperature`` (K)."""
        z = self.roelands.z
        if z != "fit":
            return float(z)
        assert self.dicke is not None  # enforced by the validator
        return fit_roelands_z(
            self.eta0(temperature),
            self.roelands.eta_p,
            self.roelands.p_p,
            self.dicke,
            temperature,
            self.roelands.z_fit,
            self.roelands.fit_pressure_max,
        )


# --------------------------------------------------------------------------- surfaces


class SurfacePairConfig(_Section):
    """Roughness and Zhou-Hoeprich load-sharing parameters (eq. 53) of one contact type."""

    roughness: Quantity("length", positive=True, example="0.16 um")
    zh_b: Number(gt=0.0)
    zh_c: Number(gt=0.0)


class BoundaryFrictionConfig(_Section):
    """Boundary friction (eqs. 51, 52) and its smoothing at small sliding speed."""

    mu_b0: Number(ge=0.0)
    s0: Number(gt=0.0)
    smoothing_speed: Quantity("speed", positive=True) = "1 mm/s"


class SqueezeFilmConfig(_Section):
    """``[surfaces.squeeze_film]``: squeeze-film damping of the oil between roller ends and
    flanges (not in the paper; docs/dynamics.md)."""

    enabled: bool = True
    half_width: Quantity("length", positive=True, le="10 mm") = "0.5 mm"
    floor: Quantity("length", positive=True, le="100 um") = "0.24 um"
    cutoff: Quantity("length", positive=True, le="1 mm") = "20 um"


class RaceFilmConfig(_Section):
    """``[surfaces.race_film]``: the rigid-isoviscous oil film in the roller-race and
    roller-roller gaps (Martin's load, squeeze, Couette shear; not in the paper;
    docs/dynamics.md). Its gap floor is each contact's composite roughness."""

    enabled: bool = True
    cutoff: Quantity("length", positive=True, le="1 mm") = "100 um"


class SurfacesConfig(_Section):
    """``[surfaces]``."""

    raceway: SurfacePairConfig
    flange: SurfacePairConfig
    roller_roller: SurfacePairConfig | None = None
    boundary_friction: BoundaryFrictionConfig
    hysteresis_coefficient: Number(ge=0.0)
    damping_ratio: Number(ge=0.0, le=2.0) = 0.1
    border_band_roller: Quantity("angle", ge=0.0, le="1 deg") = "1.5e-4 rad"
    border_band_flange: Quantity("length", ge=0.0, le="1 mm") = "50 um"
    squeeze_film: SqueezeFilmConfig = Field(default_factory=SqueezeFilmConfig)
    race_film: RaceFilmConfig = Field(default_factory=RaceFilmConfig)
    friction: bool = True

    @property
    def roller_roller_pair(self) -> SurfacePairConfig:
        """Surfaces of roller-roller contacts (``roller_roller``, else ``raceway``)."""
        return self.roller_roller or self.raceway


# --------------------------------------------------------------------------- operating


class CavityConfig(_Section):
    """``[cavity]``: the oil-air mixture in the bearing's cavity, whose drag acts on the
    rollers (Harris & Kotzalas; not in the paper; docs/dynamics.md). Air at 80 degC."""

    oil_fraction: Number(ge=0.0, le=1.0) = 0.03
    air_density: Quantity("density", ge=0.0, le="100 kg/m^3") = "1.0 kg/m^3"
    air_viscosity: Quantity("dynamic viscosity", ge=0.0, le="1 Pa*s") = "2.1e-5 Pa*s"


class RampConfig(_Section):
    """A ramp from 0 to the full value between ``start`` and ``end``."""

    start: Quantity("time", ge=0.0, example="0 s")
    end: Quantity("time", positive=True, example="0.5 s")
    shape: Literal["cosine", "linear"] = "cosine"

    @model_validator(mode="after")
    def _check(self) -> RampConfig:
        cross = _Cross()
        if self.end <= self.start:
            cross.add("end", f"{self.end:g} s", f"must be > start ({self.start:g} s)")
        cross.raise_if_any()
        return self

    def factor(self, t: float) -> float:
        """0 before ``start``, 1 after ``end``; linear or ``(1 - cos(pi*x))/2`` in between."""
        return _ramp_factor(self.shape, (t - self.start) / (self.end - self.start))


ForceHistory = QuantityOrTable("force", "Force")
RadialHistory = QuantityOrTable("force", "RadialForce", ge=0.0)
SpeedHistory = QuantityOrTable("angular velocity", "AngularVelocity")


def _history_peak(value: float | TimeTable) -> float:
    """Largest magnitude a load or speed history reaches (NaN stays NaN)."""
    if isinstance(value, TimeTable):
        return max(abs(v) for v in value.values)
    return abs(value)


def _history_at(value: float | TimeTable, ramp: RampConfig | None, t: float) -> float:
    if isinstance(value, TimeTable):
        return value.value_at(t)
    return value * (1.0 if ramp is None else ramp.factor(t))


class OperatingConfig(_Section):
    """``[operating]``: loads on the inner ring, its speed, temperature, ramps, end time."""

    radial_load: RadialHistory
    axial_load: ForceHistory
    inner_ring_speed: SpeedHistory
    temperature: Quantity("temperature", example="80 degC")
    load_ramp: RampConfig | None = None
    speed_ramp: RampConfig | None = None
    end_time: Quantity("time", positive=True, example="1.3 s") | None = None
    gravity: Vector(
        "acceleration", example='"9.81 m/s^2" or ["0 m/s^2", "-9.81 m/s^2", "0 m/s^2"]'
    ) = "9.81 m/s^2"

    @model_validator(mode="after")
    def _check(self) -> OperatingConfig:
        cross = _Cross()
        if self.load_ramp is not None and all(
            isinstance(v, TimeTable) for v in (self.radial_load, self.axial_load)
        ):
            cross.add(
                "load_ramp",
                "",
                "both loads are time tables; a load ramp only applies to constant loads",
            )
        if self.speed_ramp is not None and isinstance(self.inner_ring_speed, TimeTable):
            cross.add(
                "speed_ramp",
                "",
                "inner_ring_speed is a time table; a speed ramp only applies to a constant speed",
            )
        if self.end_time is not None and self.end_time <= self.speed_history_end:
            cross.add(
                "end_time",
                f"{self.end_time:g} s",
                f"must be > the end of the speed ramp/table ({self.speed_history_end:g} s)",
            )
        cross.raise_if_any()
        return self

    @property
    def speed_history_end(self) -> float:
        """Time from which the inner ring speed is constant, s."""
        v = self.inner_ring_speed
        if isinstance(v, TimeTable):
            return v.end
        return 0.0 if self.speed_ramp is None else self.speed_ramp.end

    @property
    def final_inner_ring_speed(self) -> float:
        """Inner ring speed after the ramp/table, rad/s."""
        v = self.inner_ring_speed
        return v.final if isinstance(v, TimeTable) else v

    def radial_load_at(self, t: float) -> float:
        """Radial load (N, along -y) at time ``t`` (s)."""
        return _history_at(self.radial_load, self.load_ramp, t)

    def axial_load_at(self, t: float) -> float:
        """Axial load (N, along +x) at time ``t`` (s)."""
        return _history_at(self.axial_load, self.load_ramp, t)

    def inner_ring_speed_at(self, t: float) -> float:
        """Inner ring angular velocity (rad/s) at time ``t`` (s)."""
        return _history_at(self.inner_ring_speed, self.speed_ramp, t)


# --------------------------------------------------------------------------- solver


class LineFitConfig(_Section):
    """Range of the fit of eq. 11 to Tripp's line-contact law (load per unit length).

    Without ``load_min``/``load_max`` the ranges follow from the radial load: with the
    Stribeck/Harris estimate of the heaviest roller, ``q_ref = 4.08 F_r / (Z l)`` (l the
    straight roller length), race contacts are fitted over ``[0.1, 2] q_ref`` and
    roller-roller contacts over ``[0.01, 0.2] q_ref`` (see :class:`rollerdyn.model.Model`).
    Given values apply to all three contact kinds.
    """

    load_min: Quantity("force per length", positive=True) | None = None
    load_max: Quantity("force per length", positive=True) | None = None
    samples: Integer(ge=2, le=10_000) = 64

    @model_validator(mode="after")
    def _check(self) -> LineFitConfig:
        cross = _Cross()
        if (self.load_min is None) != (self.load_max is None):
            cross.add(
                "load_max" if self.load_max is None else "load_min",
                "(missing)",
                "give both load_min and load_max, or neither (derived from the radial load)",
            )
        elif self.load_max is not None and self.load_max <= self.load_min:
            cross.add(
                "load_max",
                format_si(self.load_max, "force per length"),
                f"must be > load_min ({format_si(self.load_min, 'force per length')})",
            )
        cross.raise_if_any()
        return self


class SolverConfig(_Section):
    """``[solver]``: time integration and numerical settings."""

    rtol: Number(ge=1e-12, lt=1.0) = 1e-5
    atol: Number(ge=1e-15) = 1e-9
    atol_time_scale: Quantity("time", positive=True, le="1 s") = "1e-5 s"
    dt_max: Quantity("time", ge="1 ns") = "1e-4 s"
    output_interval: Quantity("time", ge="1 ns") = "1e-4 s"
    checkpoint_interval: Quantity("time", positive=True) = "100 ms"
    detector: Literal["semi-analytical", "gradient", "mesh"] = "semi-analytical"
    start: Literal["rest", "equilibrium"] = "rest"
    method: Literal["tr-bdf2", "esdirk34"] = "tr-bdf2"
    max_step_growth: Number(gt=1.0, le=10.0) = 1.3
    step_gain: Number(gt=0.0, le=1.0) = 0.3
    jacobian_after_newton_failure: bool = False
    pruning: bool = True
    mesh_around: Integer(ge=8, le=1024) = 64
    mesh_along: Integer(ge=2, le=256) = 16
    traction_nodes: Integer(ge=1, le=200) = 12
    traction: Literal["tabulated", "direct"] = "tabulated"
    line_fit: LineFitConfig = Field(default_factory=LineFitConfig)


# --------------------------------------------------------------------------- top level


class BearingConfig(_Section):
    """A complete bearing simulation: geometry, materials, lubricant, operation, solver."""

    name: Annotated[str, Field(min_length=1)]
    description: str | None = None
    geometry: GeometryConfig
    materials: MaterialsConfig
    inner_ring: InnerRingConfig
    lubricant: LubricantConfig
    surfaces: SurfacesConfig
    operating: OperatingConfig
    cavity: CavityConfig = Field(default_factory=CavityConfig)
    solver: SolverConfig = Field(default_factory=SolverConfig)
    #: The TOML text the configuration was read from (None if built in Python).
    _toml: str | None = PrivateAttr(default=None)

    def __eq__(self, other: object) -> bool:
        """Equal values, whatever text they were read from (the TOML text is a record)."""
        if not isinstance(other, BearingConfig):
            return NotImplemented
        return (
            self.__dict__ == other.__dict__ and self.__pydantic_extra__ == other.__pydantic_extra__
        )

    __hash__ = None  # type: ignore[assignment]  # mutable values, as pydantic's own

    @property
    def toml_text(self) -> str | None:
        """The TOML text this configuration was read from (:func:`load_config`), as read;
        None for a configuration built in Python."""
        return self._toml

    @model_validator(mode="after")
    def _check(self) -> BearingConfig:
        cross = _Cross()
        op, lub = self.operating, self.lubricant
        t = op.temperature
        t_shown = format_si(t, "temperature")
        fit = lub.alpha_star_fit
        if not fit.t_min <= t <= fit.t_max:
            cross.add(
                "operating.temperature",
                t_shown,
                "must lie within lubricant.alpha_star_fit "
                f"[{format_si(fit.t_min, 'temperature')}, {format_si(fit.t_max, 'temperature')}]",
            )
        if t <= lub.vogel.pole():
            cross.add(
                "operating.temperature",
                t_shown,
                "must be above the Vogel pole theta = -c "
                f"({format_si(lub.vogel.pole(), 'temperature')})",
            )
        if lub.roelands.z == "fit" and lub.dicke is not None and lub.dicke.denominator(0.0, t) <= 0:
            cross.add(
                "lubricant.dicke.a2",
                format_si(lub.dicke.a2, "pressure per temperature"),
                f"a1 + a2*theta must be > 0 at the operating temperature ({t_shown})",
            )
        if lub.density_at(t) <= 0.0:
            cross.add(
                "lubricant.density.slope",
                format_si(lub.density.slope, "density per temperature"),
                f"gives a density <= 0 at the operating temperature ({t_shown})",
            )
        self._check_operating_limits(cross)
        if op.end_time is None and op.final_inner_ring_speed == 0.0:
            cross.add(
                "operating.end_time",
                "(missing)",
                "required when the final inner ring speed is 0 "
                "(no roller-set revolutions to count)",
            )
        elif self.solver.output_interval >= self.end_time:
            cross.add(
                "solver.output_interval",
                f"{self.solver.output_interval:g} s",
                f"must be < the end time ({self.end_time:g} s)",
            )
        cross.raise_if_any()
        return self

    def _check_operating_limits(self, cross: _Cross) -> None:
        """Loads and speeds far beyond what any rolling bearing carries are refused before
        any work (they would only make the solver fail after a long time)."""
        op = self.operating
        limit = self.load_limit
        for field, value in (("radial_load", op.radial_load), ("axial_load", op.axial_load)):
            peak = _history_peak(value)
            if not peak <= limit:
                cross.add(
                    f"operating.{field}",
                    format_si(peak, "force"),
                    f"must be at most {format_si(limit, 'force')}: the heaviest roller "
                    f"(Stribeck, 4.08 F/Z) would see a Hertz pressure above "
                    f"{MAX_HERTZ_PRESSURE / 1e9:g} GPa, far beyond what bearing steel carries "
                    "(ISO 76 allows 4 GPa)",
                )
        speed = _history_peak(op.inner_ring_speed)
        pitch_speed = speed * self.geometry.pitch_diameter / 2.0
        if not pitch_speed <= MAX_PITCH_SPEED:
            cross.add(
                "operating.inner_ring_speed",
                f"{speed * 30.0 / math.pi:.6g} rpm",
                f"must give a pitch-circle speed of at most {MAX_PITCH_SPEED:g} m/s "
                f"(here {pitch_speed:.3g} m/s), beyond the fastest rolling bearings",
            )

    @property
    def load_limit(self) -> float:
        """Largest radial or axial load accepted [N]: the radial load whose heaviest roller
        (Stribeck: Q = 4.08 F_r/Z) presses the inner race with the Hertz line-contact pressure
        p0 = sqrt(Q E' / (2 pi R' l)) = :data:`MAX_HERTZ_PRESSURE`."""
        g, m = self.geometry, self.materials
        straight = g.roller.length - 2.0 * g.roller.edge_radius
        r_roller = g.roller_diameter / 2.0
        r_race = g.inner_raceway_diameter / 2.0
        r_eff = r_roller * r_race / (r_roller + r_race)
        e_prime = 2.0 / (
            (1.0 - m.roller.poisson_ratio**2) / m.roller.youngs_modulus
            + (1.0 - m.inner_ring.poisson_ratio**2) / m.inner_ring.youngs_modulus
        )
        q = MAX_HERTZ_PRESSURE**2 * 2.0 * math.pi * r_eff * straight / e_prime
        return q * g.roller_count / 4.08

    # ---- kinematics and run length

    @property
    def roller_set_speed(self) -> float:
        """Roller-set (cage) angular velocity at full speed, rad/s, outer ring fixed.

        Epicyclic kinematics without slip: ``omega_c = omega_i*(1 - D/d_m)/2``.
        """
        g = self.geometry
        return (
            self.operating.final_inner_ring_speed
            * (1.0 - g.roller_diameter / g.pitch_diameter)
            / 2.0
        )

    @property
    def end_time(self) -> float:
        """Simulated time, s: ``operating.end_time``, else the end of the speed ramp/table
        plus two roller-set revolutions at full speed (``2 * 2*pi/|omega_c|``)."""
        if self.operating.end_time is not None:
            return self.operating.end_time
        return self.operating.speed_history_end + 2.0 * 2.0 * math.pi / abs(self.roller_set_speed)

    # ---- lubricant at the operating temperature

    @property
    def base_viscosity(self) -> float:
        """eta0 at the operating temperature, Pa*s."""
        return self.lubricant.eta0(self.operating.temperature)

    @property
    def roelands_z(self) -> float:
        """Roelands exponent at the operating temperature (given, or fitted to Dicke)."""
        return self.lubricant.roelands_z_at(self.operating.temperature)

    # ---- masses and inertias

    @cached_property
    def roller_mass_properties(self) -> dict[str, float]:
        """``{"mass", "axial_inertia", "transverse_inertia"}`` of one roller (kg, kg*m^2),
        from the Rust core (``transverse_inertia`` about a diameter through the centre)."""
        from rollerdyn import _core

        g = self.geometry
        r = g.roller
        props = _core.roller_mass_properties(
            g.roller_diameter,
            r.length,
            r.edge_radius,
            r.end_face_radius,
            self.materials.roller.density,
        )
        return {k: float(props[k]) for k in ("mass", "axial_inertia", "transverse_inertia")}

    @property
    def roller_mass(self) -> float:
        """kg."""
        return self.roller_mass_properties["mass"]

    @property
    def roller_axial_inertia(self) -> float:
        """kg*m^2, about the roller axis."""
        return self.roller_mass_properties["axial_inertia"]

    @property
    def roller_transverse_inertia(self) -> float:
        """kg*m^2, about a diameter through the roller centre."""
        return self.roller_mass_properties["transverse_inertia"]

    @property
    def inner_ring_equivalent_length(self) -> float:
        """Length w of the solid steel cylinder of radius D_i/2 that has the inner ring's
        mass: ``w = m / (rho * pi * (D_i/2)^2)``, m (used for the default inertias)."""
        r = self.geometry.inner_raceway_diameter / 2.0
        return self.inner_ring.mass / (self.materials.inner_ring.density * math.pi * r * r)

    @property
    def inner_ring_axial_inertia(self) -> float:
        """``inner_ring.axial_inertia``, else ``m*r^2/2`` of the solid cylinder (r = D_i/2)."""
        if self.inner_ring.axial_inertia is not None:
            return self.inner_ring.axial_inertia
        r = self.geometry.inner_raceway_diameter / 2.0
        return self.inner_ring.mass * r * r / 2.0

    @property
    def inner_ring_transverse_inertia(self) -> float:
        """``inner_ring.transverse_inertia``, else ``m*(3r^2 + w^2)/12`` of the solid cylinder."""
        if self.inner_ring.transverse_inertia is not None:
            return self.inner_ring.transverse_inertia
        r = self.geometry.inner_raceway_diameter / 2.0
        w = self.inner_ring_equivalent_length
        return self.inner_ring.mass * (3.0 * r * r + w * w) / 12.0


# --------------------------------------------------------------------------- loading


def load_config(path: str | Path) -> BearingConfig:
    """Read and validate a TOML configuration file; raise :class:`ConfigError` if invalid."""
    p = Path(path)
    if not p.exists():
        raise ConfigError(f"{p}: configuration file not found", source=str(p))
    if not p.is_file():
        raise ConfigError(f"{p}: not a file", source=str(p))
    try:
        text = p.read_bytes().decode("utf-8")
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
    config = parse_config(data, source=str(p))
    config._toml = text
    return config


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
    try:
        return BearingConfig.model_validate(dict(data), context={SI_NUMBERS: si_numbers})
    except ValidationError as exc:
        problems = problems_from(exc, data)
        head = f"invalid configuration{f' {source}' if source else ''}"
        n = len(problems)
        lines = [f"{head} ({n} problem{'s' if n != 1 else ''}):", *map(str, problems)]
        raise ConfigError("\n".join(lines), problems, source) from None


# --------------------------------------------------------------------------- messages

_MISSING = object()


def _show(value: Any) -> str:
    """A value as it would be written in TOML (strings quoted), shortened if long."""
    if value is _MISSING:
        return "(missing)"
    if isinstance(value, str):
        s = '"' + value.replace("\\", "\\\\").replace('"', '\\"') + '"'
    elif isinstance(value, bool):
        s = "true" if value else "false"
    elif isinstance(value, Mapping):
        s = "{" + ", ".join(f"{k} = {_show(v)}" for k, v in value.items()) + "}"
    elif isinstance(value, list | tuple):
        s = "[" + ", ".join(_show(v) for v in value) + "]"
    else:
        s = repr(value)
    return s if len(s) <= 80 else s[:77] + "..."


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

    for err in exc.errors(include_url=False):
        loc = tuple(p for p in err["loc"] if not (isinstance(p, str) and p.startswith("<")))
        typ = err["type"]
        if typ == "cross_field":
            for rel, shown, rule in err["ctx"]["problems"]:
                full = loc + tuple(rel)
                raw, inherited = _raw_or_inherited(data, full)
                value = _show(raw) if raw is not _MISSING else (shown or "(see rule)")
                add(full, value, rule, inherited)
            continue
        if typ == "extra_forbidden":
            section, key = loc[:-1], loc[-1]
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
