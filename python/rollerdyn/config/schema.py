"""The configuration's schema: one pydantic model per TOML section, with the rules of each
field (units, bounds) and the cross-field checks, up to :class:`BearingConfig`, the whole
file.

Every numeric field holds a plain SI float once validated (:mod:`rollerdyn.units` converts
at the boundary). The values derived from the fields are the sections' mixins in
:mod:`.derived`; problems found by the checks are rendered by :mod:`.errors`.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Mapping
from typing import Annotated, Any, Literal

from pydantic import BeforeValidator, Field, PrivateAttr, StrictBool, model_validator
from pydantic_core import PydanticCustomError

from ..names import FLANGES
from ..units import Integer, Number, Quantity, Vector, format_si
from .base import (
    MAX_HERTZ_PRESSURE,
    MAX_MISALIGNMENT_DEG,
    MAX_PITCH_SPEED,
    MAX_SLICES,
    ForceHistory,
    Hint,
    RadialHistory,
    SpeedHistory,
    Text,
    TimeTable,
    _Cross,
    _mm,
    _Section,
)
from .derived import (
    AXIAL_LOAD_FLANGES,
    SPEEDS,
    BearingDerived,
    DickeDerived,
    GeometryDerived,
    LubricantDensityDerived,
    LubricantDerived,
    OperatingDerived,
    RampDerived,
    RollerDerived,
    SurfacesDerived,
    VogelDerived,
    _history_peak,
)
from .solver import SolverConfig

# --------------------------------------------------------------------------- geometry


class RollerConfig(RollerDerived, _Section):
    """``[geometry.roller]``: one roller (all rollers are equal)."""

    length: Quantity("length", positive=True, le="1 m", example="5 mm")
    edge_radius: Quantity("length", positive=True, example="0.5 mm")
    end_face_radius: Quantity("length", positive=True, example="5000 mm")
    profile: Literal["straight", "crowned", "logarithmic"] = "straight"
    crown_drop: Quantity("length", nonnegative=True, example="2 um") = "0 um"
    crown_length: Quantity("length", positive=True, example="1 mm") | None = None
    relief_factor: Number(gt=0.0, le=0.01) | None = None
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
        if self.relief_factor is not None and self.profile != "logarithmic":
            cross.add(
                "relief_factor",
                repr(self.relief_factor),
                f'only used with profile = "logarithmic" (profile is "{self.profile}")',
            )
        if self.profile != "crowned":
            if self.crown_drop != 0.0:
                cross.add(
                    "crown_drop",
                    _mm(self.crown_drop),
                    f'a crown drop needs profile = "crowned" (profile is "{self.profile}")',
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


#: The largest crown drop, a share of the roller diameter (B1's 4.5 mm rollers: 45 µm;
#: crowns drop by micrometres).
MAX_CROWN_DROP = 0.01


class FlangeConfig(_Section):
    """``[geometry.flange]``: a cone between a root torus (at the raceway) and a rim torus."""

    opening_angle: Quantity("angle", ge=0.0, lt="10 deg", example="0.11 deg")
    height: Quantity("length", positive=True, example="1.1 mm")
    root_radius: Quantity("length", positive=True, example="0.2 mm")
    rim_radius: Quantity("length", positive=True, example="0.3 mm")
    axial_play: Quantity("length", nonnegative=True, example="20 um")


_FLANGE_OVERRIDES = ("inner_ring_flange", "outer_ring_flange")

#: The longest simulated time [s]: at B1's pace (25 s of wall time per simulated second)
#: a day of it; and at the default dt_max the least step count a run is refused beyond
#: (rollerdyn.simulation.MAX_MIN_STEPS) is reached at 1e5 s anyway.
MAX_END_TIME = 1e5


def axial_load_flange_rule(cfg: BearingConfig, axial_load: float) -> str | None:
    """Why ``axial_load`` on the inner ring [N] (with the ring's weight along the axis,
    its mass times the x part of ``operating.gravity``) cannot be carried: along +x the
    inner ring's -x flange pushes the rollers onto the outer ring's +x flange, along -x
    the other two (:data:`AXIAL_LOAD_FLANGES`), and one of the two is missing from
    ``geometry.flanges``; None where it can (the core's
    ``BearingParams::check_axial_load_path``)."""
    weight = cfg.inner_ring.mass * cfg.operating.gravity[0]
    along_axis = axial_load + weight
    if along_axis == 0.0:
        return None
    direction = 1.0 if along_axis > 0.0 else -1.0
    path = AXIAL_LOAD_FLANGES[direction]
    missing = [f for f in path if f not in cfg.geometry.flanges]
    if not missing:
        return None
    by_weight = f" with the ring's weight along the axis ({weight:g} N)" if weight else ""
    return (
        f"pushes the inner ring along {'+x' if direction > 0 else '-x'}{by_weight}, "
        f'which only the flanges "{path[0]}" and "{path[1]}" carry; '
        f'geometry.flanges has no "{missing[0]}"'
    )


class GeometryConfig(GeometryDerived, _Section):
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
    # Which flanges the rings have (B1, type NUP: all four; NU: the outer ring's two; NJ
    # and NJG: the outer ring's two and one of the inner ring's; NF and NCF: the inner
    # ring's two and one of the outer ring's). Absent flanges have no contact.
    flanges: tuple[Literal[FLANGES], ...] = FLANGES

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
        # a clearance equal to the gap left 4e-16 mm of roller by round-off, which passed
        # on to other rules' messages, or with them relaxed to a run of NaN fits (a review)
        if dia <= 1e-9 * (d_o - d_i):
            cross.add(
                "diametral_clearance",
                _mm(c),
                "leaves no room for rollers: roller diameter (D_o - D_i)/2 - clearance/2 = "
                f"{_mm(dia)} must be > 0"
                + (" (this is round-off of the raceways' difference)" if dia > 0.0 else ""),
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
        if r.crown_drop > MAX_CROWN_DROP * dia:
            # 10 mm on a 4.5 mm roller passed `check` silently (a review)
            cross.add(
                "roller.crown_drop",
                _mm(r.crown_drop),
                f"must be <= {MAX_CROWN_DROP:.0%} of the roller diameter "
                f"({_mm(MAX_CROWN_DROP * dia)}): a crown's drop is micrometres",
            )
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
        self._check_flanges(cross)
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
        self._check_flanges_face_each_other(cross)
        cross.raise_if_any()
        return self

    def _check_flanges_face_each_other(self, cross: _Cross) -> None:
        """The inner ring's and the outer ring's flanges stand on their raceways and face
        each other across the annulus (D_o - D_i)/2: together they must be lower than it
        (the core's ``BearingParams::check_fit``)."""
        annulus = (self.outer_raceway_diameter - self.inner_raceway_diameter) / 2.0
        inner, outer = self.inner_flange.height, self.outer_flange.height
        if inner + outer >= annulus:
            key = next(
                (k for k in reversed(_FLANGE_OVERRIDES) if getattr(self, k) is not None),
                "flange",
            )
            cross.add(
                f"{key}.height",
                f"{_mm(inner)} + {_mm(outer)}",
                f"the inner and outer flanges together must be lower than the annulus "
                f"between the raceways, (D_o - D_i)/2 = {_mm(annulus)}",
            )

    def _check_flanges(self, cross: _Cross) -> None:
        """Each flange once, and one on each side of the rollers: nothing else holds them
        along the axis (the core's ``BearingParams::check``)."""
        shown = "[" + ", ".join(f'"{f}"' for f in self.flanges) + "]"
        if len(set(self.flanges)) != len(self.flanges):
            cross.add("flanges", shown, "names each flange at most once")
        for side in ("-x", "+x"):
            if not any(f.endswith(side) for f in self.flanges):
                cross.add(
                    "flanges",
                    shown,
                    f'needs a flange on the rollers\' {side} side ("inner{side}" or '
                    f'"outer{side}"): nothing else holds them along the axis',
                )


# --------------------------------------------------------------------------- materials


class MaterialConfig(_Section):
    """An isotropic elastic solid. The bounds hold every engineering solid with a wide
    margin (rubber's modulus is about 10 MPa, diamond's 1.2 TPa; osmium, the densest
    element, 22 590 kg/m^3); beyond them the contact laws leave their range."""

    youngs_modulus: Quantity("pressure", ge="1 MPa", le="10 TPa", example="210 GPa")
    poisson_ratio: Number(gt=0.0, lt=0.5)
    density: Quantity("density", ge="1 kg/m^3", le="100000 kg/m^3", example="7850 kg/m^3")


class MaterialsConfig(_Section):
    """``[materials.*]``: roller, inner ring and outer ring."""

    roller: MaterialConfig
    inner_ring: MaterialConfig
    outer_ring: MaterialConfig


class InnerRingConfig(_Section):
    """``[inner_ring]``: the inner ring together with its (rigid) shaft."""

    mass: Quantity("mass", ge="1 g", le="100000 kg", example="0.1 kg")
    axial_inertia: Quantity("moment of inertia", positive=True) | None = None
    transverse_inertia: Quantity("moment of inertia", positive=True) | None = None
    tilt: Literal["locked", "free"] = "locked"
    # Prescribed tilt of a locked ring about z (perpendicular to the radial load along -y and
    # the axial load along +x, as the paper's tilt, sect. 5.2); the ring's axis is
    # (cos g, sin g, 0) for the whole run.
    misalignment: Quantity(
        "angle", ge=f"-{MAX_MISALIGNMENT_DEG:g} deg", le=f"{MAX_MISALIGNMENT_DEG:g} deg"
    ) = "0 deg"

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


class VogelConfig(VogelDerived, _Section):
    """Vogel law ``eta0 = k*exp(b/(theta + c))``, theta in degC."""

    k: Quantity("dynamic viscosity", positive=True, example="0.062 mPa*s")
    b: Quantity("temperature interval", positive=True, example="1021.7 K")
    c: Quantity("temperature interval", example="101.5517 K")


class ReferenceViscosityConfig(_Section):
    """A measured viscosity that rescales the Vogel factor ``k``."""

    temperature: Quantity("temperature", example="40 degC")
    viscosity: Quantity("dynamic viscosity", positive=True, le="1000 Pa*s", example="81 mPa*s")


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


class DickeConfig(DickeDerived, _Section):
    """Dicke law ``eta = eta0*exp(p/(a1 + a2*theta + (b1 + b2*theta)*p))``, theta in degC."""

    a1: Quantity("pressure", positive=True, example="327.7918 bar")
    a2: Quantity("pressure per temperature", example="2.9862 bar/K")
    b1: Number()
    b2: Quantity("inverse temperature", example="3.0115e-4 1/K")


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
    #: Lubricating oils decompose far below 1000 degC; the fit's exponentials overflow far
    #: above (1e6 degC made its least squares fail with NaN).
    t_max: Quantity("temperature", le="1000 degC") = "140 degC"

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


class LubricantDensityConfig(LubricantDensityDerived, _Section):
    """Density ``rho(T) = rho_15 + slope*(T - 15 degC)``."""

    rho_15: Quantity("density", positive=True, example="887.6 kg/m^3")
    slope: Quantity("density per temperature", example="-0.6 kg/m^3/K")


class LubricantConfig(LubricantDerived, _Section):
    """``[lubricant]``: rheology and thermal data of the oil."""

    name: Text(min_length=1)
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


# --------------------------------------------------------------------------- surfaces


class SurfacePairConfig(_Section):
    """Roughness and Zhou-Hoeprich load-sharing parameters (eq. 53) of one contact type."""

    roughness: Quantity("length", positive=True, example="0.16 um")
    zh_b: Number(gt=0.0)
    zh_c: Number(gt=0.0)


class BoundaryFrictionConfig(_Section):
    """Boundary friction (eqs. 51, 52) and its smoothing at small sliding speed."""

    mu_b0: Number(ge=0.0, le=1.0)  # dry steel on steel is about 0.6
    s0: Number(gt=0.0)
    smoothing_speed: Quantity("speed", positive=True) = "1 mm/s"


class SqueezeFilmConfig(_Section):
    """``[surfaces.squeeze_film]``: squeeze-film damping of the oil between roller ends and
    flanges (not in the paper; docs/dynamics.md)."""

    enabled: StrictBool = True
    half_width: Quantity("length", positive=True, le="10 mm") = "0.5 mm"
    floor: Quantity("length", positive=True, le="100 um") = "0.24 um"
    cutoff: Quantity("length", positive=True, le="1 mm") = "20 um"


class RaceFilmConfig(_Section):
    """``[surfaces.race_film]``: the rigid-isoviscous oil film in the roller-race and
    roller-roller gaps (Martin's load, squeeze, Couette shear; not in the paper;
    docs/dynamics.md). Its gap floor is each contact's composite roughness.
    ``suction_limit``: how far below ambient the film's pressure falls before it cavitates
    (0: the half-Sommerfeld condition, a separating film pulls with nothing)."""

    enabled: StrictBool = True
    cutoff: Quantity("length", positive=True, le="1 mm") = "100 um"
    suction_limit: Quantity("pressure", ge=0.0, le="10 MPa") = "0.1 MPa"


class SurfacesConfig(SurfacesDerived, _Section):
    """``[surfaces]``. ``flange_law``: how a roller end-flange contact carries its load:
    ``"point"`` (the paper's Hertz at the deepest point of the detected pairing) or
    ``"distributed"`` (not in the paper: the whole overlap over the roller end on a Winkler
    foundation with the surfaces' asperities, for ends that lie nearly flat on the flange;
    docs/dynamics.md). ``rolling_resistance``: how the rolling resistance of the race
    contacts (eqs. 55-57) and the films' rolling force in the line-contact gaps act on the two
    bodies: ``"balanced"`` (the default; not in the paper: in rolling the same moment about
    each body's axis and the force pair that keeps the oil film in equilibrium, so that the
    contact conserves angular momentum, the rolling force acting against the entrainment on
    both surfaces) or ``"paper"`` (eqs. 55-57: a pure moment against each
    body's rolling, which creates angular momentum; B1's example keeps it for the paper's
    study); docs/dynamics.md, "Torque balance of the rings"."""

    raceway: SurfacePairConfig
    flange: SurfacePairConfig
    flange_law: Literal["point", "distributed"] = "point"
    roller_roller: SurfacePairConfig | None = None
    boundary_friction: BoundaryFrictionConfig
    hysteresis_coefficient: Number(ge=0.0, le=1.0)  # a share of the rolling work
    rolling_resistance: Literal["paper", "balanced"] = "balanced"
    damping_ratio: Number(ge=0.0, le=2.0) = 0.1
    squeeze_film: SqueezeFilmConfig = Field(default_factory=SqueezeFilmConfig)
    race_film: RaceFilmConfig = Field(default_factory=RaceFilmConfig)


# --------------------------------------------------------------------------- operating


class CavityConfig(_Section):
    """``[cavity]``: the oil-air mixture in the bearing's cavity, whose drag acts on the
    rollers (Harris & Kotzalas; not in the paper; docs/dynamics.md). Air at 80 degC."""

    oil_fraction: Number(ge=0.0, le=1.0) = 0.03
    air_density: Quantity("density", ge=0.0, le="100 kg/m^3") = "1.0 kg/m^3"
    air_viscosity: Quantity("dynamic viscosity", ge=0.0, le="1 Pa*s") = "2.1e-5 Pa*s"


class RampConfig(RampDerived, _Section):
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


class OperatingConfig(OperatingDerived, _Section):
    """``[operating]``: loads on the inner ring, the rings' speeds, temperature, ramps, end
    time."""

    radial_load: RadialHistory
    axial_load: ForceHistory
    inner_ring_speed: SpeedHistory
    # Not in the paper (its outer ring is fixed): a planet gear turns its bearing's outer
    # ring about a fixed pin (inner_ring_speed = "0 rpm").
    outer_ring_speed: SpeedHistory = "0 rpm"
    temperature: Quantity("temperature", example="80 degC")
    load_ramp: RampConfig | None = None
    speed_ramp: RampConfig | None = None
    end_time: Quantity("time", positive=True, example="1.3 s") | None = None
    gravity: Vector(
        "acceleration", example='"9.81 m/s^2" or ["0 m/s^2", "-9.81 m/s^2", "0 m/s^2"]'
    ) = "9.81 m/s^2"
    # Not in the paper: a planet gear's bearing on the pin of a carrier turning about the
    # sun's axis; the speeds above are then relative to the carrier (docs/dynamics.md).
    carrier_speed: SpeedHistory = "0 rpm"
    carrier_offset: Vector(
        "length", example='"40 mm" or ["0 mm", "-40 mm", "0 mm"]', bound=10.0
    ) = "0 m"

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
        for ring in SPEEDS:
            if self.speed_ramp is not None and isinstance(getattr(self, ring), TimeTable):
                cross.add(
                    "speed_ramp",
                    "",
                    f"{ring} is a time table; a speed ramp only applies to a constant speed",
                )
        if self.end_time is not None and self.end_time <= self.speed_history_end:
            cross.add(
                "end_time",
                f"{self.end_time:g} s",
                f"must be > the end of the speed ramp/table ({self.speed_history_end:g} s)",
            )
        if self.carrier_offset[0] != 0.0:
            cross.add(
                "carrier_offset",
                f"{self.carrier_offset[0]:g} m along x",
                "must lie across the axis (x part 0): the carrier's axis is parallel to the "
                "bearing's",
            )
        cross.raise_if_any()
        return self


# --------------------------------------------------------------------------- top level

#: Fields that have moved: old dotted path -> (new dotted path, why). A configuration that
#: still has one at its old place is refused naming both (``config/errors.py``); a result
#: recorded with the old layout is read in the new one (``provenance.py``).
MOVED_FIELDS: dict[str, tuple[str, str]] = {
    "surfaces.border_band_roller": ("solver.border_band_roller", "a numerical setting"),
    "surfaces.border_band_flange": ("solver.border_band_flange", "a numerical setting"),
    "surfaces.friction": ("solver.friction", "a numerical setting"),
}


class BearingConfig(BearingDerived, _Section):
    """A complete bearing simulation: geometry, materials, lubricant, operation, solver."""

    name: Text(min_length=1)
    description: Text(multiline=True) | None = None
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
        """Equal field values, whatever text they were read from (the TOML text is a record)
        and whichever derived values were computed and cached already."""
        if not isinstance(other, BearingConfig):
            return NotImplemented
        fields = type(self).model_fields
        return all(self.__dict__.get(k) == other.__dict__.get(k) for k in fields)

    __hash__ = None  # type: ignore[assignment]  # mutable values, as pydantic's own

    def model_copy(self, *, update: Mapping[str, Any] | None = None, deep: bool = False):
        """A copy (pydantic's ``model_copy``) without the derived values this one has
        computed and cached (:attr:`roller_mass_properties`): a copy with ``update`` has
        other fields, and computes its own on first use. (Like pydantic's, the copy is not
        validated; ``rollerdyn.simulate`` and ``statics`` validate what they are given.)"""
        copy = super().model_copy(update=update, deep=deep)
        for name in _cached_properties(type(self)):
            copy.__dict__.pop(name, None)
        return copy

    @property
    def toml_text(self) -> str | None:
        """The TOML text this configuration was read from (:func:`load_config`): the file as
        read, or, with changes, the changed table written as TOML (comments dropped) after a
        comment naming the file and the changes; None for a configuration built in Python,
        or where the changed table has no TOML text that reads back as it (a NaN)."""
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
        if t > lub.vogel.pole():
            self._check_ambient_viscosity(cross, t_shown)
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
        self._check_axial_load_flanges(cross)
        if op.end_time is None and self.roller_set_speed == 0.0:
            cross.add(
                "operating.end_time",
                "(missing)",
                "required when the roller set does not orbit at the final ring speeds "
                "(no roller-set revolutions to count)",
            )
        elif self.end_time > MAX_END_TIME:
            derived = op.end_time is None
            cross.add(
                "operating.end_time",
                f"(derived: {self.end_time:.3g} s)" if derived else f"{self.end_time:.3g} s",
                f"must be <= {MAX_END_TIME:.0e} s"
                + (
                    ": the roller set orbits so slowly at the final ring speeds that two "
                    "revolutions take that long; give operating.end_time"
                    if derived
                    else ""
                ),
            )
        elif self.solver.output_interval >= self.end_time:
            cross.add(
                "solver.output_interval",
                f"{self.solver.output_interval:g} s",
                f"must be < the end time ({self.end_time:g} s)",
            )
        cross.raise_if_any()
        return self

    def _check_ambient_viscosity(self, cross: _Cross, t_shown: str) -> None:
        """The ambient viscosity eta0 at the operating temperature (Vogel, rescaled to the
        reference viscosity) must be finite and above Roelands' eta_p: eq. 19's
        ln(eta0/eta_p) is the pressure-viscosity's scale."""
        lub = self.lubricant
        eta0 = self.base_viscosity
        if not (math.isfinite(eta0) and eta0 > 0.0):
            cross.add(
                "lubricant.vogel",
                f"k = {format_si(lub.vogel.k, 'dynamic viscosity')}, "
                f"b = {format_si(lub.vogel.b, 'temperature interval')}, "
                f"c = {format_si(lub.vogel.c, 'temperature interval')}",
                f"gives an ambient viscosity of {eta0:g} Pa*s at the operating temperature "
                f"({t_shown}); it must be finite and > 0",
            )
        elif eta0 <= lub.roelands.eta_p:
            cross.add(
                "lubricant.roelands.eta_p",
                format_si(lub.roelands.eta_p, "dynamic viscosity"),
                f"must be below the ambient viscosity at the operating temperature "
                f"({format_si(eta0, 'dynamic viscosity')} at {t_shown}, from lubricant.vogel"
                + (" and reference_viscosity" if lub.reference_viscosity is not None else "")
                + ")",
            )

    def _check_axial_load_flanges(self, cross: _Cross) -> None:
        """An axial load on the inner ring (with the ring's weight along the axis) needs
        the two flanges it presses (:func:`axial_load_flange_rule`), for the least and the
        largest value of its history (a ramp from 0, as the core reads it)."""
        op = self.operating
        if isinstance(op.axial_load, TimeTable):
            values = op.axial_load.values
        else:
            values = (0.0, op.axial_load)
        for load in sorted({min(values), max(values)}):
            rule = axial_load_flange_rule(self, load)
            if rule is not None:
                cross.add("operating.axial_load", format_si(load, "force"), rule)

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
        for ring in SPEEDS:
            speed = _history_peak(getattr(op, ring))
            pitch_speed = speed * self.speed_radius(ring)
            if not pitch_speed <= MAX_PITCH_SPEED:
                cross.add(
                    f"operating.{ring}",
                    f"{speed * 30.0 / math.pi:.6g} rpm",
                    f"must give a pitch-circle speed of at most {MAX_PITCH_SPEED:g} m/s "
                    f"(here {pitch_speed:.3g} m/s), beyond the fastest rolling bearings",
                )


def _cached_properties(cls: type) -> list[str]:
    """The names of ``cls``'s cached derived values (its ``functools.cached_property``
    attributes, which keep their value in the instance's ``__dict__``)."""
    return [
        name
        for klass in cls.__mro__
        for name, attr in vars(klass).items()
        if isinstance(attr, functools.cached_property)
    ]
