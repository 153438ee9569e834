"""Derived values of a configuration: the quantities computed from its fields (roller and
pitch diameters, the effective Vogel factor, the Roelands exponent fitted to Dicke, load
and speed histories, end time, masses and inertias, the load limit), never typed into the
file.

Each section's derived values are a mixin of its class in :mod:`.schema`
(``GeometryDerived`` of ``GeometryConfig``, ...), so that they read as properties of the
configuration (``cfg.geometry.roller_diameter``, ``cfg.end_time``).
"""

from __future__ import annotations

import math
from functools import cached_property
from typing import TYPE_CHECKING

from .. import _core
from ..tribology import effective_modulus
from .base import MAX_HERTZ_PRESSURE, T0_CELSIUS, T_DENSITY_REF, TimeTable

if TYPE_CHECKING:
    from .schema import DickeConfig, FlangeConfig, RampConfig, SurfacePairConfig

# --------------------------------------------------------------------------- geometry


class RollerDerived:
    """Derived values of ``[geometry.roller]``."""

    __slots__ = ()

    @property
    def effective_length(self) -> float:
        """Length of the generatrix between the edge tori, ``length - 2*edge_radius``, m."""
        return self.length - 2.0 * self.edge_radius

    @property
    def slice_width(self) -> float:
        """Width of one slice, ``effective_length / slices``, m."""
        return self.effective_length / self.slices

    @property
    def slice_centres(self) -> list[float]:
        """The slices' centres along the roller axis from its middle, m (the core's
        stations of the line contacts, ``bearing/line_contacts.rs``)."""
        half, width = 0.5 * self.effective_length, self.slice_width
        return [-half + (j + 0.5) * width for j in range(self.slices)]


#: The flanges an axial load on the inner ring presses, by its direction: along +x the
#: inner ring's -x flange pushes the rollers onto the outer ring's +x flange (the core's
#: ``BearingParams::axial_load_flanges``).
AXIAL_LOAD_FLANGES = {1.0: ("inner-x", "outer+x"), -1.0: ("inner+x", "outer-x")}


#: The factor k of the logarithmic roller profile's relief k D where the configuration
#: gives none: ISO/TS 16281:2008's for rollers whose profile is not known (MESYS's manual:
#: it corresponds to a contact stress of 3000 MPa in short cylindrical roller bearings).
ISO_RELIEF_FACTOR = 0.00035


class GeometryDerived:
    """Derived values of ``[geometry]``."""

    __slots__ = ()

    @property
    def log_relief(self) -> float:
        """The relief k D of the logarithmic roller profile, m: the profile's drop at s
        from the roller's centre is k D ln[1 / (1 - (2 s / L_we)^2)] (Lundberg's profile
        as ISO/TS 16281:2008 takes it; k = ``relief_factor``, by default
        :data:`ISO_RELIEF_FACTOR`); 0 for a straight or crowned roller."""
        roller = self.roller
        if roller.profile != "logarithmic":
            return 0.0
        k = ISO_RELIEF_FACTOR if roller.relief_factor is None else roller.relief_factor
        return k * self.roller_diameter

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
    def epicyclic_factor(self) -> float:
        """omega_c / omega_i of the roller set rolling without slip, the outer ring fixed:
        ``(1 - D/d_m)/2`` (Harris & Kotzalas, Rolling Bearing Analysis, vol. 1, ch. 8)."""
        return (1.0 - self.roller_diameter / self.pitch_diameter) / 2.0

    @property
    def outer_epicyclic_factor(self) -> float:
        """omega_c / omega_o of the roller set rolling without slip, the inner ring fixed:
        ``(1 + D/d_m)/2`` (Harris & Kotzalas, eq. 8.23)."""
        return (1.0 + self.roller_diameter / self.pitch_diameter) / 2.0

    @property
    def fill_ratio(self) -> float:
        """Share of the pitch circle covered by rollers, ``Z*D/(pi*d_m)``."""
        return self.roller_count * self.roller_diameter / (math.pi * self.pitch_diameter)

    @property
    def flange_arrangement(self) -> str:
        """The flanges present in words, with the type they make (ISO 15, DIN 5412-1;
        the full-complement variant after a semicolon), e.g. "the outer ring's two (type
        NU)"."""
        present = set(self.flanges)
        inner = sorted(f.removeprefix("inner") for f in present if f.startswith("inner"))
        outer = sorted(f.removeprefix("outer") for f in present if f.startswith("outer"))
        if len(inner) == 2 and len(outer) == 2:
            return "all four (type NUP)"
        if len(outer) == 2:
            return "the outer ring's two" + (
                f" and the inner ring's {inner[0]} (type NJ; NJG)" if inner else " (type NU)"
            )
        if len(inner) == 2:
            return "the inner ring's two" + (
                f" and the outer ring's {outer[0]} (type NF; NCF)" if outer else " (type N)"
            )
        return f"the inner ring's {inner[0]} and the outer ring's {outer[0]}"

    @property
    def axial_load_carried(self) -> str:
        """The directions of an axial load on the inner ring that the flanges carry
        (:data:`AXIAL_LOAD_FLANGES`): "both directions", "along +x only", "along -x only"
        or "none"."""
        carried = [
            along
            for along, direction in (("+x", 1.0), ("-x", -1.0))
            if set(AXIAL_LOAD_FLANGES[direction]) <= set(self.flanges)
        ]
        if len(carried) == 2:
            return "both directions"
        return f"along {carried[0]} only" if carried else "none"

    @property
    def inner_flange(self) -> FlangeConfig:
        """Flange geometry of the inner ring (both sides)."""
        return self.inner_ring_flange or self.flange

    @property
    def outer_flange(self) -> FlangeConfig:
        """Flange geometry of the outer ring (both sides)."""
        return self.outer_ring_flange or self.flange


# --------------------------------------------------------------------------- lubricant


class VogelDerived:
    """The Vogel law evaluated."""

    __slots__ = ()

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


class DickeDerived:
    """The Dicke law's denominator."""

    __slots__ = ()

    def denominator(self, pressure: float, temperature: float) -> float:
        theta = temperature - T0_CELSIUS
        return self.a1 + self.a2 * theta + (self.b1 + self.b2 * theta) * pressure


class LubricantDensityDerived:
    """The oil's density at a temperature."""

    __slots__ = ()

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


class LubricantDerived:
    """Derived values of ``[lubricant]``."""

    __slots__ = ()

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


class SurfacesDerived:
    """Derived values of ``[surfaces]``."""

    __slots__ = ()

    @property
    def roller_roller_pair(self) -> SurfacePairConfig:
        """Surfaces of roller-roller contacts (``roller_roller``, else ``raceway``)."""
        return self.roller_roller or self.raceway


# --------------------------------------------------------------------------- operating


class RampDerived:
    """A ramp evaluated."""

    __slots__ = ()

    def factor(self, t: float) -> float:
        """0 before ``start``, 1 after ``end``; linear or ``(1 - cos(pi*x))/2`` in between."""
        return _core.ramp_factor(self.shape, (t - self.start) / (self.end - self.start))


def roller_set_speed(geometry, inner: float, outer: float) -> float:
    """The roller set's orbital speed [rad/s] rolling without slip at the inner and outer
    rings' speeds [rad/s] (Harris & Kotzalas, eq. 8.23; the core's ``rolling_speeds``)."""
    return epicyclic_speed(inner, outer, geometry.epicyclic_factor)


def epicyclic_speed(inner: float, outer: float, inner_factor: float) -> float:
    """The roller set's orbital speed [rad/s] rolling without slip at the inner and outer
    rings' speeds [rad/s], from the inner ring's epicyclic factor ``(1 - D/d_m)/2`` alone:
    the outer ring's, ``(1 + D/d_m)/2``, is 1 less it (Harris & Kotzalas, eq. 8.23)."""
    return inner * inner_factor + outer * (1.0 - inner_factor)


def _history_peak(value: float | TimeTable) -> float:
    """Largest magnitude a load or speed history reaches (NaN stays NaN)."""
    if isinstance(value, TimeTable):
        return max(abs(v) for v in value.values)
    return abs(value)


def _history_at(value: float | TimeTable, ramp: RampConfig | None, t: float) -> float:
    if isinstance(value, TimeTable):
        return value.value_at(t)
    return value * (1.0 if ramp is None else ramp.factor(t))


#: The speed histories of ``[operating]`` (the speed ramp takes each from 0).
SPEEDS = ("inner_ring_speed", "outer_ring_speed", "carrier_speed")


class OperatingDerived:
    """Derived values of ``[operating]``: the histories evaluated."""

    __slots__ = ()

    @property
    def speed_history_end(self) -> float:
        """Time from which the rings' (and the carrier's) speeds are constant, s."""
        speeds = [getattr(self, name) for name in SPEEDS]
        ends = [v.end if isinstance(v, TimeTable) else 0.0 for v in speeds]
        ramp = self.speed_ramp
        if ramp is not None and not all(isinstance(v, TimeTable) for v in speeds):
            ends.append(ramp.end)
        return max(ends)

    @property
    def final_inner_ring_speed(self) -> float:
        """Inner ring speed after the ramp/table, rad/s."""
        v = self.inner_ring_speed
        return v.final if isinstance(v, TimeTable) else v

    @property
    def final_outer_ring_speed(self) -> float:
        """Outer ring speed after the ramp/table, rad/s."""
        v = self.outer_ring_speed
        return v.final if isinstance(v, TimeTable) else v

    @property
    def final_carrier_speed(self) -> float:
        """The planet carrier's speed after the ramp/table, rad/s."""
        v = self.carrier_speed
        return v.final if isinstance(v, TimeTable) else v

    @property
    def final_relative_speed(self) -> float:
        """Inner ring speed relative to the outer ring after the ramp/table, rad/s: what
        sets the rolling (entrainment) speeds and the rating life's revolutions."""
        return self.final_inner_ring_speed - self.final_outer_ring_speed

    def radial_load_at(self, t: float) -> float:
        """Radial load (N, along -y) at time ``t`` (s)."""
        return _history_at(self.radial_load, self.load_ramp, t)

    def axial_load_at(self, t: float) -> float:
        """Axial load (N, along +x) at time ``t`` (s)."""
        return _history_at(self.axial_load, self.load_ramp, t)

    def inner_ring_speed_at(self, t: float) -> float:
        """Inner ring angular velocity (rad/s) at time ``t`` (s)."""
        return _history_at(self.inner_ring_speed, self.speed_ramp, t)

    def outer_ring_speed_at(self, t: float) -> float:
        """Outer ring angular velocity (rad/s) at time ``t`` (s)."""
        return _history_at(self.outer_ring_speed, self.speed_ramp, t)

    def carrier_speed_at(self, t: float) -> float:
        """The planet carrier's angular velocity (rad/s) at time ``t`` (s)."""
        return _history_at(self.carrier_speed, self.speed_ramp, t)


# --------------------------------------------------------------------------- top level


class BearingDerived:
    """Derived values of the whole configuration."""

    __slots__ = ()

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
        e_prime = effective_modulus(
            m.roller.youngs_modulus,
            m.roller.poisson_ratio,
            m.inner_ring.youngs_modulus,
            m.inner_ring.poisson_ratio,
        )
        q = MAX_HERTZ_PRESSURE**2 * 2.0 * math.pi * r_eff * straight / e_prime
        return q * g.roller_count / 4.08

    def speed_radius(self, speed: str) -> float:
        """The radius [m] at which the configuration bounds the speed ``speed`` (one of
        :data:`SPEEDS`) by the pitch-circle rule: the pitch circle's, and for the planet
        carrier's speed the bearing's farthest rollers from the carrier's axis."""
        radius = self.geometry.pitch_diameter / 2.0
        if speed == "carrier_speed":
            radius += math.hypot(*self.operating.carrier_offset)
        return radius

    @property
    def carrier_field(self) -> float:
        """The planet carrier's centrifugal field at the bearing's axis at full speed,
        Omega_c^2 |offset| [m/s^2] (0 without a carrier)."""
        op = self.operating
        return op.final_carrier_speed**2 * math.hypot(*op.carrier_offset)

    # ---- kinematics and run length

    @property
    def roller_set_speed(self) -> float:
        """Roller-set (cage) angular velocity at full speed, rad/s.

        Epicyclic kinematics without slip (Harris & Kotzalas, eq. 8.23):
        ``omega_c = omega_i*(1 - D/d_m)/2 + omega_o*(1 + D/d_m)/2``.
        """
        return roller_set_speed(
            self.geometry,
            self.operating.final_inner_ring_speed,
            self.operating.final_outer_ring_speed,
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
