"""Running the dynamic model: configuration -> Rust core -> xarray Dataset.

:func:`simulate` mirrors ``rollerdyn run``: it derives the model's parameters from a
validated configuration (:func:`model_parameters`, all SI), runs the core and returns an
:class:`xarray.Dataset` whose variables carry their units in ``attrs["units"]``. A run that
fails keeps everything computed until then: the Dataset holds those records and its
``attrs["error"]`` says when and where the run failed; :func:`simulate` then raises
:class:`SimulationError` carrying that partial Dataset.

Checkpoints: every ``solver.checkpoint_interval`` of simulated time
(from t = 0) the integration restarts its solver from the state reached, in every run. The
Dataset keeps the last checkpoint (``checkpoint_time``, ``checkpoint_step``,
``checkpoint_state``, counters in ``attrs["checkpoint_stats_*"]``); a run resumed from it
(``resume=``) takes the same path as the uninterrupted run and so equals it bit for bit in
every data variable. Attributes that measure wall time (``stats_*_seconds``,
``checkpoint_stats_*_seconds``) differ, and a resumed result has ``resumed_at_s``.

The names the result shares with the core (pairings, flanges, detectors) are those of
:mod:`rollerdyn.names`, re-exported here.
"""

from __future__ import annotations

import math
import numbers
import os
import threading
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import xarray as xr

from . import _core
from .config import BearingConfig, RampConfig, TimeTable
from .config.solver import OUTPUT_GROUPS
from .model import Model
from .names import DETECTORS, FLANGES, GRADIENT, PAIRINGS, flange_indices
from .provenance import check_same_configuration, record_attrs
from .tribology import effective_modulus
from .units import parse_time


def carried_axial_force(ds: xr.Dataset) -> xr.DataArray:
    """Axial force each roller carries from the inner ring to the outer ring [N] (paper
    fig. 12): the axial force of the inner ring's two flanges on it (the outer ring's
    flanges take it back, so the sum over all four is the roller's small net force)."""
    carried = ds.flange_axial_force.isel(flange=flange_indices("inner")).sum("flange")
    return carried.assign_attrs(units="N", long_name="axial force carried by the roller")


def ring_speeds(ds: xr.Dataset) -> tuple[np.ndarray, np.ndarray]:
    """The inner and the outer ring's speeds at every output [rad/s]; a result without
    ``outer_ring_speed``, recorded before the outer ring could turn, had it fixed (0)."""
    inner = np.asarray(ds.ring_speed.values, dtype=float)
    if "outer_ring_speed" not in ds:
        return inner, np.zeros_like(inner)
    return inner, np.asarray(ds.outer_ring_speed.values, dtype=float)


def full_speed(ds: xr.Dataset) -> xr.Dataset:
    """The part of a result at (at least 99 % of) full speed of each ring that turns, the
    outputs the azimuth figures use; the whole result if neither ring turns."""
    turning = [s for s in map(np.abs, ring_speeds(ds)) if s.max() > 0]
    if not turning:
        return ds
    full = np.logical_and.reduce([s >= 0.99 * s.max() for s in turning])
    return ds.isel(time=np.nonzero(full)[0])


class SimulationError(RuntimeError):
    """A run that stopped early; :attr:`dataset` holds everything computed until then."""

    def __init__(self, message: str, dataset: xr.Dataset):
        super().__init__(message)
        self.dataset = dataset


class SimulationInterrupted(SimulationError, KeyboardInterrupt):
    """A run stopped by Ctrl-C (or SIGTERM through the CLI's handler): a
    :class:`KeyboardInterrupt` that still carries everything computed (:attr:`dataset`)."""


#: Result size above which a run is refused unless forced [bytes].
MAX_RESULT_BYTES = 2e9
#: Least number of steps (t_end / dt_max) above which a run is refused unless forced
#: (B1's whole run takes about 50 000 steps).
MAX_MIN_STEPS = 1e8
#: Checkpoints (t_end / checkpoint_interval) above which a run is refused unless forced:
#: each restarts the integrator with a fresh step size (B1's whole run takes 13 at the
#: default 100 ms; at 1 ns a 2 ms run took 100 s of wall time to stall).
MAX_CHECKPOINTS = 1e5


def estimated_cost(config: BearingConfig, t_end: float, t_start: float = 0.0) -> dict:
    """What a run will at least cost: outputs, the result's size [bytes] (what
    ``solver.outputs`` keeps, uncompressed), the memory its outputs take while it runs
    [bytes] (:func:`recorded_groups`) and steps (the span over dt_max, a lower bound)."""
    span = max(t_end - t_start, 0.0)
    intervals = span / min(config.solver.output_interval, t_end)
    # exact while it is a count a run could make; a float (up to inf) past that
    outputs = math.ceil(intervals) + 1 if intervals < 2.0**53 else intervals + 1.0
    z = config.geometry.roller_count
    return {
        "outputs": outputs,
        "bytes": outputs * 8 * numbers_per_output(z, config.solver.outputs),
        "memory_bytes": outputs * 8 * numbers_per_output(z, recorded_groups(config)),
        "min_steps": span / config.solver.dt_max,
        "checkpoints": span / config.solver.checkpoint_interval,
    }


def recorded_groups(config: BearingConfig) -> tuple[str, ...]:
    """The output groups the core records while a run goes: every group when
    ``solver.outputs`` selects any (the per-roller records hold them all; the selection is
    made when the result is built), none when it selects none."""
    return OUTPUT_GROUPS if config.solver.outputs else ()


def numbers_per_output(z: int, groups: tuple[str, ...] = OUTPUT_GROUPS) -> int:
    """How many numbers a result of ``z`` rollers and the ``solver.outputs`` ``groups``
    holds per output time: the time, the scalars, the ring's position and tilt; per roller
    its variables (and position); per roller end and flange its variables (and contact
    location)."""
    per_roller, per_flange = output_variables(groups)
    per_roller_count = len(per_roller) + (3 if "rollers" in groups else 0)
    per_flange_count = len(per_flange) + (3 if "flanges" in groups else 0)
    return 1 + len(_SCALARS) + 3 + 2 + z * (per_roller_count + 4 * per_flange_count)


#: The most facets (``solver.mesh_around`` x ``solver.mesh_along``) of a figure that a
#: run with the mesh detector takes (:func:`check_cost`): at 1024 x 256 a run ignored
#: Ctrl-C for 12 minutes before its first step (a review).
MAX_MESH_FACETS = 128 * 32


def check_cost(
    config: BearingConfig,
    t_end: float,
    t_start: float = 0.0,
    remedy: str = ", or force the run (--force, force=True)",
    outputs_optional: bool = True,
    detector: str | None = None,
) -> None:
    """Raises ValueError, with the estimate, if a run would be far beyond a normal one
    (see :data:`MAX_RESULT_BYTES`, :data:`MAX_MIN_STEPS`, :data:`MAX_CHECKPOINTS`);
    ``force=True`` of
    :func:`simulate` skips this check (the core still refuses what it cannot hold).
    ``remedy`` ends the advice (where forcing is not offered, pass ""); where the caller
    needs every output group (a study), ``outputs_optional=False`` leaves out the advice
    to record none. ``detector``: the run's, if not the configuration's (the mesh
    detector's resolution is bounded, :data:`MAX_MESH_FACETS`)."""
    cost = estimated_cost(config, t_end, t_start)
    s = config.solver
    facets = s.mesh_around * s.mesh_along
    if (detector or s.detector) == "mesh" and facets > MAX_MESH_FACETS:
        raise ValueError(
            f"solver.mesh_around x solver.mesh_along = {s.mesh_around} x {s.mesh_along}: a "
            f"run with the mesh detector at more than {MAX_MESH_FACETS} facets a figure "
            "(128 x 32) takes minutes a step (a roller end's detection 10.7 ms at 64 x 16 "
            "and 56 ms at 128 x 32, growing with the facets, 68 of them a right-hand side), "
            "and Ctrl-C is taken only between steps; choose fewer facets (`rollerdyn bench "
            f"contact` compares the resolutions){remedy}"
        )
    if cost["memory_bytes"] > MAX_RESULT_BYTES:
        raise ValueError(
            f"solver.output_interval = {s.output_interval:g} s: {cost['outputs']:.3g} outputs "
            f"to t = {t_end:g} s would take {cost['memory_bytes'] / 1e9:.3g} GB of results "
            f"while the run goes (with any group in solver.outputs, every group is recorded "
            f"until the result is built: more than {MAX_RESULT_BYTES / 1e9:g} GB); choose a "
            f"longer interval{' or solver.outputs = []' if outputs_optional else ''}{remedy}"
        )
    if cost["min_steps"] > MAX_MIN_STEPS:
        raise ValueError(
            f"solver.dt_max = {s.dt_max:g} s: the run to t = {t_end:g} s takes at least "
            f"{cost['min_steps']:.3g} steps (more than {MAX_MIN_STEPS:.0e}; B1 takes about "
            f"5e4); choose a larger dt_max{remedy}"
        )
    if cost["checkpoints"] > MAX_CHECKPOINTS:
        raise ValueError(
            f"solver.checkpoint_interval = {s.checkpoint_interval:g} s: the run to "
            f"t = {t_end:g} s would stop for {cost['checkpoints']:.3g} checkpoints (more than "
            f"{MAX_CHECKPOINTS:.0e}; each restarts the integrator); choose a longer "
            f"interval{remedy}"
        )


def as_config(config: BearingConfig | str | os.PathLike) -> BearingConfig:
    """A validated configuration: a path is read with :func:`load_config`; a
    :class:`BearingConfig` is validated again (one changed with ``model_copy`` is not). It
    keeps the TOML text it was read from only while that text still gives its values (a
    result then records no text, only the resolved values)."""
    import tomllib

    from .config import ConfigError, load_config, parse_config

    if isinstance(config, str | os.PathLike):
        return load_config(config)
    if not isinstance(config, BearingConfig):
        raise TypeError(
            f"config: expected a BearingConfig or a path to a TOML file, got "
            f"{type(config).__name__}"
        )
    checked = parse_config(config.model_dump(), si_numbers=True)
    text = config.toml_text
    if text is not None:
        try:
            unchanged = parse_config(tomllib.loads(text)) == checked
        except (ConfigError, tomllib.TOMLDecodeError):
            unchanged = False
        checked._toml = text if unchanged else None
    return checked


def _history(value: float | TimeTable, ramp: RampConfig | None) -> dict:
    if isinstance(value, TimeTable):
        return {"kind": "table", "times": list(value.times), "values": list(value.values)}
    if ramp is None:
        return {"kind": "ramp", "value": float(value), "start": 0.0, "end": 0.0, "shape": "linear"}
    return {
        "kind": "ramp",
        "value": float(value),
        "start": ramp.start,
        "end": ramp.end,
        "shape": ramp.shape,
    }


def model_parameters(config: BearingConfig, detector: str | None = None) -> dict:
    """The SI parameters of the Rust model, derived from ``config``: a dict of sections
    (``geometry``, ``materials``, ``inner_ring``, ``lubricant``, ``surfaces``,
    ``operating``, ``cavity``: physical; ``solver``: numerical), each a dict of values or
    of nested sections. The core reads it into typed structs of the same shape
    (``crates/rollerdyn-py/src/params/schema.rs``) and refuses a missing or unknown key,
    naming its path (``tests/test_params_agree.py``)."""
    cfg, model = config, Model(config)
    g, m, s, op = cfg.geometry, cfg.materials, cfg.surfaces, cfg.operating
    laws = model.line_contacts
    roller = g.roller
    crowned = roller.profile == "crowned"

    def flange(f) -> dict:
        return {
            "opening_angle": f.opening_angle,
            "height": f.height,
            "root_radius": f.root_radius,
            "rim_radius": f.rim_radius,
            "axial_play": f.axial_play,
        }

    def line_contact(ring, law: str) -> dict:
        e_prime = effective_modulus(
            m.roller.youngs_modulus, m.roller.poisson_ratio, ring.youngs_modulus, ring.poisson_ratio
        )
        return {"e_prime": e_prime, "k1": laws[law].k1, "k2": laws[law].k2}

    def pair(p) -> dict:
        return {"roughness": p.roughness, "zh_b": p.zh_b, "zh_c": p.zh_c}

    sq, solver = s.squeeze_film, cfg.solver
    return {
        "geometry": {
            "roller_count": int(g.roller_count),
            "roller": {
                "radius": g.roller_diameter / 2.0,
                "length": roller.length,
                "edge_radius": roller.edge_radius,
                "end_face_radius": roller.end_face_radius,
                "slices": int(roller.slices),
                "crown_drop": roller.crown_drop if crowned else 0.0,
                "crown_length": (roller.crown_length or 0.0) if crowned else 0.0,
                "log_relief": g.log_relief,
            },
            "inner_raceway_radius": g.inner_raceway_diameter / 2.0,
            "outer_raceway_radius": g.outer_raceway_diameter / 2.0,
            "inner_flange": flange(g.inner_flange),
            "outer_flange": flange(g.outer_flange),
            "flanges": [name in g.flanges for name in FLANGES],
        },
        "materials": {
            "roller_density": m.roller.density,
            "inner_race": line_contact(m.inner_ring, "inner"),
            "outer_race": line_contact(m.outer_ring, "outer"),
            "roller_roller": line_contact(m.roller, "roller"),
        },
        "inner_ring": {
            "mass": cfg.inner_ring.mass,
            "axial_inertia": cfg.inner_ring_axial_inertia,
            "transverse_inertia": cfg.inner_ring_transverse_inertia,
            "tilt_free": cfg.inner_ring.tilt == "free",
            "misalignment": cfg.inner_ring.misalignment,
        },
        "lubricant": {
            "eta0": model.eta0,
            "viscosity_slope": model.viscosity_slope,
            "alpha_star": model.alpha_star,
            "thermal_conductivity": cfg.lubricant.thermal_conductivity,
            "density": cfg.lubricant.density_at(op.temperature),
        },
        "surfaces": {
            "raceway": pair(s.raceway),
            "flange": pair(s.flange),
            "flange_law": s.flange_law,
            "roller_roller": pair(s.roller_roller_pair),
            "boundary_friction": {
                "mu_b0": s.boundary_friction.mu_b0,
                "s0": s.boundary_friction.s0,
                "smoothing_speed": s.boundary_friction.smoothing_speed,
            },
            "hysteresis_coefficient": s.hysteresis_coefficient,
            "rolling_resistance": s.rolling_resistance,
            "damping_ratio": s.damping_ratio,
            "squeeze_film": {
                "enabled": bool(sq.enabled),
                "half_width": sq.half_width,
                "floor": sq.floor,
                "cutoff": sq.cutoff,
            },
            "race_film": {
                "enabled": bool(s.race_film.enabled),
                "cutoff": s.race_film.cutoff,
                "suction_limit": s.race_film.suction_limit,
            },
        },
        "operating": {
            "radial_load": _history(op.radial_load, op.load_ramp),
            "axial_load": _history(op.axial_load, op.load_ramp),
            "inner_ring_speed": _history(op.inner_ring_speed, op.speed_ramp),
            "outer_ring_speed": _history(op.outer_ring_speed, op.speed_ramp),
            "gravity": list(op.gravity),
            "carrier_speed": _history(op.carrier_speed, op.speed_ramp),
            "carrier_offset": list(op.carrier_offset),
        },
        "cavity": {
            "oil_fraction": cfg.cavity.oil_fraction,
            "air_density": cfg.cavity.air_density,
            "air_viscosity": cfg.cavity.air_viscosity,
        },
        "solver": {
            "detector": detector or solver.detector,
            "mesh_around": int(solver.mesh_around),
            "mesh_along": int(solver.mesh_along),
            "pruning": bool(solver.pruning),
            "border_band_roller": solver.border_band_roller,
            "border_band_flange": solver.border_band_flange,
            "friction": bool(solver.friction),
        },
    }


def run_options(config: BearingConfig, t_end: float, force: bool = False) -> dict:
    """The SI options of the core's run of ``config`` to ``t_end`` (``force`` as in
    :func:`simulate`: without the point law's load check), one flat section (the
    threads are the model's: :class:`rollerdyn._core.Model` is built with them; the core's
    ``RunSettings`` in ``crates/rollerdyn-py/src/params/schema.rs``)."""
    s = config.solver
    return {
        "t_end": t_end,
        "rtol": s.rtol,
        "atol": s.atol,
        "atol_time_scale": s.atol_time_scale,
        "dt_max": s.dt_max,
        "output_interval": min(s.output_interval, t_end),
        "method": s.method,
        "max_step_growth": s.max_step_growth,
        "step_gain": s.step_gain,
        "jacobian_after_newton_failure": s.jacobian_after_newton_failure,
        "jacobian_at_latest_iterate": s.jacobian_at_latest_iterate,
        "partial_jacobians": s.partial_jacobians,
        "checkpoint_interval": s.checkpoint_interval,
        "start": s.start,
        "min_mean_step": s.stall_step,
        # the point law's load check before the first step
        "check_flange_law": not force,
        # per-roller records only for a result that keeps some of them
        "roller_records": bool(recorded_groups(config)),
    }


@dataclass(frozen=True)
class Progress:
    """What a progress callback receives at every output time and every 0.2 s of wall
    time between them (``at_output`` False)."""

    time: float
    t_end: float
    steps: int
    rhs_evaluations: int
    jacobian_evaluations: int
    step_size: float
    at_output: bool = True


_SCALARS = {
    "ring_speed": ("rad/s", "inner ring angular velocity about +x"),
    "outer_ring_speed": ("rad/s", "outer ring angular velocity about +x"),
    "carrier_speed": (
        "rad/s",
        "planet carrier's angular velocity about +x (every other output is seen from the "
        "carrier; 0 where it stands)",
    ),
    "radial_load": ("N", "radial load on the inner ring (along -y)"),
    "axial_load": ("N", "axial load on the inner ring (along +x)"),
    "frictional_torque": (
        "N*m",
        "bearing frictional torque: moment of all contact forces on the inner ring about "
        "its axis, positive when it resists the rotation",
    ),
    "outer_ring_torque": ("N*m", "moment of the contact forces on the outer ring about +x"),
    "power_loss": (
        "W",
        "power taken from the bodies' motion by every contact (their motion relative to the "
        "outer ring) and the oil-air drag; its mean in steady running is the friction power, "
        "frictional_torque times the inner ring's speed relative to the outer ring "
        "(ring_speed - outer_ring_speed)",
    ),
    "sliding_power_loss": (
        "W",
        "of power_loss, the sliding's part over every contact (traction, boundary friction, "
        "the films' shear)",
    ),
    "normal_power_loss": (
        "W",
        "of power_loss, the normal forces' part over every contact (elastic energy stored, "
        "contact damping, the films' normal load; its mean in steady running: the damping and "
        "the films')",
    ),
    "rolling_power_loss": (
        "W",
        "of power_loss, the rolling resistance's part over every contact (its couples and "
        "forces); power_loss less these three is the drag's",
    ),
}
_PER_ROLLER = {
    "azimuth": ("rad", "roller azimuth, from +y towards +z (load zone centre at pi, -y)"),
    "tilt": ("rad", "roller tilt (axis towards radial, about the circumferential direction)"),
    "skew": ("rad", "roller skew (axis towards circumferential, about the radial direction)"),
    "spin_speed": ("rad/s", "roller angular velocity about its own axis"),
    "orbital_speed": ("rad/s", "roller orbital angular velocity about the bearing axis"),
    "srr_inner": ("1", "slide-to-roll ratio at the inner race, eq. 49 (1 = race, 2 = roller)"),
    "srr_outer": ("1", "slide-to-roll ratio at the outer race, eq. 49 (1 = race, 2 = roller)"),
    "inner_normal_force": ("N", "roller-inner race normal force (sum over slices)"),
    "outer_normal_force": ("N", "roller-outer race normal force (sum over slices)"),
    "inner_tangential_force": ("N", "roller-inner race tangential force on the roller"),
    "outer_tangential_force": ("N", "roller-outer race tangential force on the roller"),
    "roller_roller_normal_force": ("N", "normal force between this roller and the next"),
    "roller_roller_tangential_force": ("N", "tangential force between this roller and the next"),
}
#: Per roller, the ``power`` group of ``solver.outputs``.
_PER_ROLLER_POWER = {
    "inner_power_loss": (
        "W",
        "power the roller-inner race contact takes from the motion (friction, rolling "
        "resistance, damping, oil film; plus its rate of elastic energy, which averages out)",
    ),
    "outer_power_loss": ("W", "the same for the roller-outer race contact"),
    "roller_roller_power_loss": ("W", "the same for the contact between this roller and the next"),
    "inner_sliding_power_loss": (
        "W",
        "of inner_power_loss, the sliding's part (traction, boundary friction, film shear)",
    ),
    "outer_sliding_power_loss": ("W", "of outer_power_loss, the sliding's part"),
    "roller_roller_sliding_power_loss": ("W", "of roller_roller_power_loss, the sliding's part"),
    "inner_rolling_power_loss": (
        "W",
        "of inner_power_loss, the rolling resistance's part (the rest after the sliding and "
        "the normal forces)",
    ),
    "outer_rolling_power_loss": ("W", "of outer_power_loss, the rolling resistance's part"),
    "roller_roller_rolling_power_loss": (
        "W",
        "of roller_roller_power_loss, the rolling resistance's part (the film's rolling force)",
    ),
    "drag_power_loss": ("W", "power the oil-air drag takes from the roller's motion"),
}

_PER_FLANGE = {
    "flange_pairing": ("1", "active pairing index into the 'pairing' coordinate, -1 if none"),
    "flange_penetration": ("m", "penetration of the composite end/flange contact (<0: gap)"),
    "flange_normal_force": ("N", "roller end / flange normal force"),
    "flange_friction_force": ("N", "roller end / flange friction force"),
    "flange_axial_force": ("N", "axial (x) force of the flange contact on the roller"),
}
#: Per roller end and flange, the ``power`` group of ``solver.outputs``.
_PER_FLANGE_POWER = {
    "flange_power_loss": (
        "W",
        "power the roller end / flange contact takes from the motion (as inner_power_loss)",
    ),
    "flange_sliding_power_loss": (
        "W",
        "of flange_power_loss, the sliding's part (the rest is the normal forces': damping "
        "and squeeze film)",
    ),
}


#: The lubrication of a contact where its pressure is highest (the slice, or the flange
#: ellipse, of the largest maximum pressure; not in the paper's outputs): name suffix ->
#: (units, text). NaN where no slice or ellipse of the contact is in contact.
_LUBRICATION = {
    "max_pressure": (
        "Pa",
        "maximum (Hertz) pressure p0 of the contact's most loaded slice (eq. 17), or of the "
        "flange contact ellipse (3F/(2 pi a b))",
    ),
    "film_thickness": (
        "m",
        "central film thickness h_c there (Moes, the greater of Moes and ZEV between "
        "rollers, Chittenden at the flanges; thermally corrected, eq. 47)",
    ),
    "specific_film_thickness": (
        "1",
        "specific film thickness Lambda = h_c / sigma there, sigma the contact's composite "
        "roughness (< 1 boundary, 1-3 mixed, > 3 full film lubrication)",
    ),
    "sliding_speed": ("m/s", "sliding speed |u_B - u_A| there"),
}
#: Per roller, the ``lubrication`` group of ``solver.outputs``.
_PER_ROLLER_LUBRICATION = {
    f"{contact}_{name}": (units, f"{where}: {text}")
    for contact, where in (
        ("inner", "roller-inner race"),
        ("outer", "roller-outer race"),
        ("roller_roller", "this roller and the next"),
    )
    for name, (units, text) in _LUBRICATION.items()
}
#: Per roller end and flange, the ``lubrication`` group of ``solver.outputs``.
_PER_FLANGE_LUBRICATION = {
    f"flange_{name}": (units, f"roller end / flange: {text}")
    for name, (units, text) in _LUBRICATION.items()
}


def output_variables(groups: tuple[str, ...]) -> tuple[dict, dict]:
    """The per-roller and the per-flange variables (name: (units, text)) a result of the
    ``solver.outputs`` ``groups`` holds, besides the bearing's own (:data:`_SCALARS`, the
    ring's position and tilt) and, with "rollers" and "flanges", the roller positions and
    flange contact locations."""
    per_roller = {
        **(_PER_ROLLER if "rollers" in groups else {}),
        **(_PER_ROLLER_POWER if "power" in groups else {}),
        **(_PER_ROLLER_LUBRICATION if "lubrication" in groups else {}),
    }
    per_flange = {
        **(_PER_FLANGE if "flanges" in groups else {}),
        **(_PER_FLANGE_POWER if "power" in groups else {}),
        **(_PER_FLANGE_LUBRICATION if "lubrication" in groups else {}),
    }
    return per_roller, per_flange


def recorded(ds: xr.Dataset, group: str) -> bool:
    """Whether the result ``ds`` holds every variable of the output group ``group`` of
    ``solver.outputs`` (a run records only the groups it selects)."""
    per_roller, per_flange = output_variables((group,))
    located = {"rollers": ("position",), "flanges": ("flange_location",)}.get(group, ())
    return all(name in ds for name in (*per_roller, *per_flange, *located))


def output_group_of(name: str) -> str | None:
    """The group of ``solver.outputs`` that variable ``name`` belongs to (None: one every
    result holds, or no output at all)."""
    groups = {
        "rollers": (*_PER_ROLLER, "position"),
        "flanges": (*_PER_FLANGE, "flange_location"),
        "power": (*_PER_ROLLER_POWER, *_PER_FLANGE_POWER),
        "lubrication": (*_PER_ROLLER_LUBRICATION, *_PER_FLANGE_LUBRICATION),
    }
    return next((g for g, names in groups.items() if name in names), None)


def _no_contact_as_nan(data: dict) -> None:
    """The film, Lambda and sliding speed of a contact without a section in contact (a
    maximum pressure of 0; the core writes 0) as NaN: there is no such film; and the film
    and Lambda of a run without friction (``solver.friction = false``, which computes no
    film: 0) as well."""
    for contact in ("inner", "outer", "roller_roller", "flange"):
        touching = data[f"{contact}_max_pressure"].values > 0.0
        filmed = touching & (data[f"{contact}_film_thickness"].values > 0.0)
        for name, where in (
            ("film_thickness", filmed),
            ("specific_film_thickness", filmed),
            ("sliding_speed", touching),
        ):
            var = data[f"{contact}_{name}"]
            var.values = np.where(where, var.values, np.nan)


def to_dataset(raw: dict, config: BearingConfig, detector: str) -> xr.Dataset:
    """Builds the Dataset from the core's flat arrays."""
    time = np.asarray(raw["time"])
    nt, z = time.size, int(raw["rollers"])
    data = {}

    def var(name: str, dims: tuple, shape: tuple, units: str, text: str) -> None:
        arr = np.asarray(raw[name], dtype=float).reshape(shape)
        data[name] = xr.Variable(dims, arr, {"units": units, "long_name": text})

    for name, (units, text) in _SCALARS.items():
        var(name, ("time",), (nt,), units, text)
    var("ring_position", ("time", "xyz"), (nt, 3), "m", "inner ring centre")
    var(
        "ring_tilt",
        ("time", "tilt_axis"),
        (nt, 2),
        "rad",
        "inner ring axis angles (theta_y, theta_z)",
    )
    per_roller, per_flange = output_variables(config.solver.outputs)
    for name, (units, text) in per_roller.items():
        var(name, ("time", "roller"), (nt, z), units, text)
    if "rollers" in config.solver.outputs:
        var("position", ("time", "roller", "xyz"), (nt, z, 3), "m", "roller centre")
    for name, (units, text) in per_flange.items():
        var(name, ("time", "roller", "flange"), (nt, z, 4), units, text)
    if "lubrication" in config.solver.outputs:
        _no_contact_as_nan(data)
    if "flanges" in config.solver.outputs:
        var(
            "flange_location",
            ("time", "roller", "flange", "xyz"),
            (nt, z, 4, 3),
            "m",
            "roller end / flange contact location P_m (eq. 1)",
        )
        data["flange_pairing"] = data["flange_pairing"].astype(np.int8)
        data["flange_pairing"].attrs.update(
            {"units": "1", "long_name": _PER_FLANGE["flange_pairing"][1]}
        )
    coords = {
        "time": ("time", time, {"units": "s", "long_name": "simulated time"}),
        "roller": ("roller", np.arange(z)),
        "flange": ("flange", list(FLANGES)),
        "pairing": ("pairing", list(PAIRINGS)),
        "xyz": ("xyz", ["x", "y", "z"]),
        "tilt_axis": ("tilt_axis", ["theta_y", "theta_z"]),
    }
    stats = raw["stats"]
    attrs = {
        "title": f"rollerdyn run of {config.name}",
        "bearing": config.name,
        "detector": detector,
        "method": config.solver.method,
        "rtol": config.solver.rtol,
        "atol_m": config.solver.atol,
        "dt_max_s": config.solver.dt_max,
        "max_step_growth": config.solver.max_step_growth,
        "step_gain": config.solver.step_gain,
        "jacobian_after_newton_failure": int(config.solver.jacobian_after_newton_failure),
        "jacobian_at_latest_iterate": int(config.solver.jacobian_at_latest_iterate),
        "partial_jacobians": config.solver.partial_jacobians,
        "output_interval_s": config.solver.output_interval,
        "outputs": " ".join(config.solver.outputs),
        "checkpoint_interval_s": config.solver.checkpoint_interval,
        "final_time_s": float(raw["final_time"]),
        "completed": int(raw["error"] is None and not raw["interrupted"]),
        "conventions": "x = bearing axis; on the inner ring: radial load -y, axial load +x",
        # the flanges the rings have (geometry.flanges); the flange axis names all four
        "flanges": " ".join(config.geometry.flanges),
        **record_attrs(config),
    }
    for key, value in stats.items():
        attrs[f"stats_{key}"] = value
    if raw["error"] is not None:
        attrs["error"] = raw["error"]
    for key, value in raw["checkpoint_stats"].items():
        attrs[f"checkpoint_stats_{key}"] = value
    ds = xr.Dataset(data, coords=coords, attrs=attrs)
    ds["final_state"] = xr.Variable(("state",), np.asarray(raw["final_state"]), {"units": "SI"})
    ds["checkpoint_state"] = xr.Variable(
        ("state",),
        np.asarray(raw["checkpoint_state"], dtype=float),
        {"units": "SI", "long_name": "state at the last checkpoint (resume point)"},
    )
    ds["checkpoint_time"] = xr.Variable(
        (), float(raw["checkpoint_time"]), {"units": "s", "long_name": "last checkpoint time"}
    )
    ds["checkpoint_step"] = xr.Variable(
        (),
        float(raw["checkpoint_step"]),
        {"units": "s", "long_name": "next step size at the last checkpoint (NaN: fresh start)"},
    )
    return ds


def failure_note(err: BaseException) -> str:
    """Why a run failed, for its table: the message alone of a refusal of its input (a
    ``ValueError``, which the core and the configuration raise naming the field, the value
    and the rule), else the exception's class and message (a fault to be reported)."""
    return str(err) if isinstance(err, ValueError) else f"{type(err).__name__}: {err}"


def simulate(
    config: BearingConfig | str | os.PathLike,
    t_end: float | None = None,
    detector: str | None = None,
    progress: Callable[[Progress], bool | None] | None = None,
    resume: xr.Dataset | None = None,
    checkpoint: Callable[[xr.Dataset], None] | None = None,
    threads: int | None = None,
    force: bool = False,
    notice: Callable[[str], None] | None = None,
) -> xr.Dataset:
    """Runs ``config`` (a :class:`BearingConfig`, validated again, or the path of a TOML
    file) from its consistent start to ``t_end`` (default: the configuration's end time)
    and returns the Dataset. A run whose result or step count would be far beyond a
    normal run is refused with the estimate (:func:`check_cost`), and a run with the
    paper's point end-flange law whose loads press the most loaded roller end onto its end
    face is refused before its first step (its steps would creep or collapse:
    docs/dynamics.md, "The whole B1 run"), unless ``force``.
    Ctrl-C raises :class:`SimulationInterrupted`, a :class:`KeyboardInterrupt` that
    carries the Dataset so far.

    ``threads``: how many threads evaluate the contacts and the Jacobian's columns (default:
    all cores; at most the cores this process may use; the gradient detector always uses
    one). The result does not depend on it, bit for bit. ``progress(Progress)`` is called
    at every output time and every 0.2 s of wall time between them (``Progress.at_output``
    tells which); returning True stops the run (the Dataset then ends at the last output),
    any other value (None, False, a number, a list) lets it go on. Raises
    :class:`SimulationError` (with the partial Dataset) if the integration fails.

    ``checkpoint(ds)`` is called at every checkpoint (every ``solver.checkpoint_interval``
    of simulated time) with the Dataset so far (``completed`` = 0), e.g. to save it.

    A run that crawls (:class:`CrawlWatch`: its steps averaging less than 1 µs of simulated
    time over 10 s of wall time, from 30 s on) is noted once: ``notice(note)`` is called
    then, and the Dataset (also a checkpoint's, a stopped run's) records the note in
    ``attrs["crawl_note"]``.

    ``resume``: the Dataset of an earlier, unfinished run of the same configuration (an
    interrupted or failed run, or one stopped early by ``t_end``). The run continues from
    its last checkpoint (outputs after it are computed again) and the result holds both
    parts; it equals an uninterrupted run bit for bit in every data variable. (A Dataset
    without checkpoint, from an older version, continues from its final state with a fresh
    step-size history: equal to within the integration tolerance.)
    """
    config = as_config(config)
    det = config.solver.detector if detector is None else detector
    if det not in DETECTORS:
        raise ValueError(f"detector = {det!r}: must be one of {', '.join(DETECTORS)}")
    end = config.end_time if t_end is None else parse_time(t_end, "t_end")
    threads = default_threads() if threads is None else threads
    if isinstance(threads, bool) or not isinstance(threads, numbers.Integral) or threads < 1:
        raise ValueError(f"threads = {threads!r}: must be a whole number >= 1")
    threads = int(threads)
    for name, given in (("progress", progress), ("checkpoint", checkpoint), ("notice", notice)):
        if given is not None and not callable(given):
            raise ValueError(f"{name} = {given!r}: must be a function (or None)")
    if not isinstance(force, bool | np.bool_):
        raise ValueError(f"force = {force!r}: must be True or False")
    force = bool(force)
    start = None
    if resume is not None:
        start = _resume_point(resume, config, det, end)
    if not force:
        check_cost(config, end, 0.0 if start is None else start[0], detector=det)
    forced = _forced_past(config, end, force, resume)
    model = Model(config)
    params = model_parameters(config, det)
    # the point law's load check is made for a resumed run too (at its new end time),
    # unless its first part was forced past it
    options = run_options(config, end, force or forced is not None)

    crawl = CrawlWatch(
        config.surfaces.flange_law == "point",
        # the run stops at every checkpoint time, saved or not (a resumed run takes the
        # same path as the uninterrupted one)
        step_caps={
            "solver.checkpoint_interval": config.solver.checkpoint_interval,
            # a dt_max of 1 ns was blamed on the point law (a review)
            "solver.dt_max": config.solver.dt_max,
        },
    )

    def callback(t, t_end_, steps, rhs, jac, step, at_output):
        report = Progress(t, t_end_, steps, rhs, jac, step, at_output)
        note = crawl(report)
        if note is not None and notice is not None:
            notice(note)
        if progress is None:
            return False
        # Only True (Python's or numpy's) stops; any other value, e.g. a count a callback
        # returns by accident, lets the run go on.
        stop = progress(report)
        return isinstance(stop, (bool, np.bool_)) and bool(stop)

    saving = {"seconds": 0.0}

    def at_checkpoint(raw_partial: dict) -> bool:
        started = time.perf_counter()
        ds = to_dataset(raw_partial, config, det)
        if resume is not None:
            ds = _join(resume, ds)
        _stamp_forced(ds, forced)
        _stamp_crawl(ds, crawl.note, resume)
        checkpoint(ds)
        saving["seconds"] += time.perf_counter() - started
        return False

    # never more threads than the cores this process may use (as the core does; and a
    # number too large for the core's integers is no error)
    core = _core.Model(params, model.traction, min(threads, default_threads()))
    try:
        raw = core.run(options, callback, start, None if checkpoint is None else at_checkpoint)
    except ValueError as refusal:
        raise ValueError(refusal_with_its_cause(config, str(refusal))) from None
    raw["stats"]["checkpoint_seconds"] = saving["seconds"]
    ds = to_dataset(raw, config, det)
    ds.attrs["threads"] = min(threads, default_threads()) if det != GRADIENT else 1
    if resume is not None:
        ds = _join(resume, ds)
    _stamp_forced(ds, forced)
    _stamp_crawl(ds, crawl.note, resume)
    if "interruption" in raw:
        # the interruption's own words ("terminated by SIGTERM", "Ctrl-C" from the CLI),
        # or Ctrl-C for Python's bare KeyboardInterrupt
        cause = raw["interruption"].strip().removesuffix(":")
        if cause.startswith("KeyboardInterrupt"):
            cause = cause.removeprefix("KeyboardInterrupt").lstrip(": ") or "Ctrl-C"
        ds.attrs["error"] = f"interrupted at t = {raw['final_time']:.6g} s: {cause}"
        if raw["interruption"].startswith("KeyboardInterrupt"):
            raise SimulationInterrupted(ds.attrs["error"], ds)
        raise SimulationError(ds.attrs["error"], ds)
    if raw["error"] is not None:
        raise SimulationError(raw["error"], ds)
    return ds


def refusal_with_its_cause(config: BearingConfig, refusal: str) -> str:
    """The core's refusal of a run before its first step, with the point law's advice
    replaced where a roller of one slice is the cause (:data:`rollerdyn.notes.ONE_SLICE`)."""
    from .notes import ONE_SLICE

    if config.geometry.roller.slices == 1 and "no quasi-static equilibrium" in refusal:
        return refusal.split("; use surfaces.flange_law", 1)[0] + "; " + ONE_SLICE
    return refusal


#: How ``attrs["forced"]`` of a forced run begins (its refusal follows).
FORCED_MARK = "run with --force past the point law's load check"


def _forced_past(
    config: BearingConfig, end: float, force: bool, resume: xr.Dataset | None
) -> str | None:
    """What ``attrs["forced"]`` of a run of ``config`` to ``end`` says: :data:`FORCED_MARK`
    and the point end-flange law's refusal that ``force`` overrode, or None (no refusal,
    or not forced); a resumed run keeps its first part's."""
    if resume is not None:
        return resume.attrs.get("forced")
    if not force or config.surfaces.flange_law != "point":
        return None
    from .notes import point_law_refusal

    refusal = point_law_refusal(config, end)
    return None if refusal is None else f"{FORCED_MARK}: {refusal}"


#: What each of :class:`CrawlWatch`'s step caps does to a step.
_CAP_REASONS = {
    "solver.checkpoint_interval": "which ends a step at every multiple of it",
    "solver.dt_max": "the largest step the solver takes",
}


class CrawlWatch:
    """Notices once when a run crawls: when its steps over at least ``window`` seconds of
    wall time, ``after`` seconds into the run, average less than ``mean_step`` of simulated
    time (B1's whole run averages 69 µs, its full speed at 3000 rpm 12 µs; with the oil at
    120 °C there the point law averages 0.44 µs: docs/dynamics.md, "Hot oil at speed: the
    point law's radii"). Called with each :class:`Progress`; returns the note (one line:
    the pace, how to find the cause, and with the point end-flange law the law that avoids
    the known one) the first time, else None. ``step_caps``: the intervals that end a step
    wherever the physics would let it go on (the checkpoint interval); one below
    ``mean_step`` is named as the cause instead."""

    def __init__(
        self,
        point_law: bool,
        after: float = 30.0,
        window: float = 10.0,
        mean_step: float = 1e-6,
        clock: Callable[[], float] = time.perf_counter,
        step_caps: Mapping[str, float] | None = None,
    ):
        self.point_law, self.clock = point_law, clock
        self.step_caps = dict(step_caps or {})
        self.after, self.window, self.mean_step = after, window, mean_step
        self.started = clock()
        self.mark: tuple[float, float, int] | None = None  # (wall, time, steps)
        self.note: str | None = None

    def __call__(self, p: Progress) -> str | None:
        now = self.clock()
        if self.note is not None or now - self.started < self.after - self.window:
            return None
        if self.mark is None:
            self.mark = (now, p.time, p.steps)
            return None
        wall, t, steps = self.mark
        if now - wall < self.window or p.steps <= steps:
            return None
        mean = (p.time - t) / (p.steps - steps)
        self.mark = (now, p.time, p.steps)
        if mean >= self.mean_step:
            return None
        capped = [(name, cap) for name, cap in self.step_caps.items() if cap < self.mean_step]
        if capped:
            name, cap = min(capped, key=lambda item: item[1])
            why = _CAP_REASONS.get(name, "which ends a step at every multiple of it")
            self.note = (
                f"the run crawled: from t = {t:.6g} s its {p.steps - steps} steps averaged "
                f"{mean:.2g} s of simulated time each, held below {name} = {cap:.2g} s, "
                f"{why}; a longer one lets the steps grow"
            )
            return self.note
        law = (
            "; with the point end-flange law a known cause is a roller end nearly parallel "
            'to a flange, which surfaces.flange_law = "distributed" avoids (--set '
            'surfaces.flange_law=distributed; docs/dynamics.md, "Hot oil at speed: the point '
            "law's radii\")"
            if self.point_law
            else ""
        )
        self.note = (
            f"the run crawled: from t = {t:.6g} s its {p.steps - steps} steps averaged "
            f"{mean:.2g} s of simulated time each; rollerdyn modes on its result names the "
            f"modes that grow{law}"
        )
        return self.note


def _stamp_crawl(ds: xr.Dataset, note: str | None, resume: xr.Dataset | None) -> None:
    """Records in ``ds.attrs["crawl_note"]`` the note of a run that crawled
    (:class:`CrawlWatch`; an earlier part's, for a resumed run whose new part did not)."""
    earlier = None if resume is None else resume.attrs.get("crawl_note")
    if note or earlier:
        ds.attrs["crawl_note"] = note or earlier


def _stamp_forced(ds: xr.Dataset, forced: str | None) -> None:
    """Records in ``ds.attrs["forced"]`` the refusal a forced run went past
    (:func:`_forced_past`), so that its file, tables and report say so."""
    if forced:
        ds.attrs["forced"] = forced


def default_threads() -> int:
    """All the cores this process may use."""
    import os

    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # not on Linux
        return max(1, os.cpu_count() or 1)


def _resume_point(previous: xr.Dataset, config: BearingConfig, detector: str, end: float):
    """(t, y, h) to continue ``previous`` from, after checking that it fits ``config``: its
    last checkpoint (h None if that is the run's fresh start), else its final state."""
    if not isinstance(previous, xr.Dataset):
        raise TypeError(
            "resume: expected the xarray Dataset of an earlier run (what simulate returned, "
            f"or xarray.open_dataset of its file), got {type(previous).__name__}"
        )
    if "final_time_s" not in previous.attrs:
        raise ValueError("resume: the Dataset is not a rollerdyn result (no final_time_s)")
    for key, expected in (("bearing", config.name), ("detector", detector)):
        found = previous.attrs.get(key)
        if found != expected:
            raise ValueError(
                f"resume: the earlier run's {key} is {found!r}, this run's {expected!r}: "
                "a run can only be continued with the same configuration and detector"
            )
    check_same_configuration(previous.attrs, config)
    z = config.geometry.roller_count
    if previous.sizes.get("roller", z) != z:
        raise ValueError(
            f"resume: the earlier result holds {previous.sizes['roller']} rollers, its "
            f"configuration {z}: the file was changed after its run"
        )
    if "final_state" not in previous:
        raise ValueError("resume: the earlier result has no final_state to continue from")
    _check_resume_record(previous)
    t_final = float(previous.attrs["final_time_s"])
    if not end > t_final:
        raise ValueError(
            f"resume: t_end = {end} s must lie after the earlier run's end, t = {t_final} s"
        )
    t0, step, state = resume_state(previous)
    if not (math.isfinite(t0) and 0.0 <= t0 <= t_final):
        raise ValueError(
            f"resume: the earlier result's checkpoint time {t0} s must lie in [0, {t_final}] s"
        )
    _check_outputs_reach(previous, t0, config.solver.output_interval)
    if step is None and "checkpoint_state" in previous and t0 != 0.0:
        raise ValueError(
            f"resume: the earlier result's checkpoint at t = {t0} s has no step (the mark of "
            "the run's fresh start at t = 0): the file was changed after its run"
        )
    longest = max(t_final, config.solver.dt_max)
    if step is not None and not (math.isfinite(step) and 0.0 < step <= longest):
        raise ValueError(
            f"resume: the earlier result's checkpoint step {step} s must lie in (0, {longest}] s"
        )
    return t0, [float(v) for v in state], step


def _check_resume_record(previous: xr.Dataset) -> None:
    """Refuses (ValueError, naming what) an earlier result whose record of its checkpoint
    is incomplete or whose output times are not finite and increasing: a file changed
    after its run, from which no continuation equals the uninterrupted run."""
    present = [name for name in _STATE_VARS[1:] if name in previous]
    if present and len(present) < len(_STATE_VARS) - 1:
        missing = [name for name in _STATE_VARS[1:] if name not in previous]
        raise ValueError(
            f"resume: the earlier result has {', '.join(present)} but no {', '.join(missing)}: "
            "the file was changed after its run"
        )
    times = np.asarray(previous["time"].values, dtype=float) if "time" in previous.coords else []
    if len(times) and not (np.all(np.isfinite(times)) and np.all(np.diff(times) > 0)):
        raise ValueError(
            "resume: the earlier result's output times are not finite and increasing: the "
            "file was changed after its run"
        )


def _check_outputs_reach(previous: xr.Dataset, t0: float, interval: float) -> None:
    """Refuses (ValueError, naming the times) an earlier result that lacks an output of
    the output grid k * ``interval`` up to its resume point ``t0``: its time axis was cut
    after its run (``ds.isel(time=...)``), and the continued run, which computes the
    outputs after ``t0`` only, would leave that gap in the joined result."""
    if "time" not in previous.coords or not interval > 0.0:
        return
    times = np.atleast_1d(np.asarray(previous["time"].values, dtype=float))
    slack = _core.time_slack(t0)
    k = np.rint(times / interval)
    on_grid = (np.abs(times - k * interval) <= slack) & (times <= t0 + slack)
    present = np.unique(k[on_grid]).astype(np.int64)
    wanted = int(math.floor((t0 + slack) / interval)) + 1  # k = 0 ... wanted - 1
    gaps = np.flatnonzero(present[:wanted] != np.arange(min(len(present), wanted)))
    first = int(gaps[0]) if len(gaps) else len(present)
    if first >= wanted:
        return
    held = f"{times[0]:.6g} ... {times[-1]:.6g} s" if len(times) else "none"
    raise ValueError(
        f"resume: the earlier result has no output at t = {first * interval:.6g} s (solver."
        f"output_interval {interval:g} s), before its checkpoint at t = {t0:.6g} s, where "
        f"the run continues (its outputs: {len(times)}, {held}): its time axis was cut "
        "after its run (e.g. with isel), so the joined result would have a gap; resume "
        "from the whole result"
    )


def resume_state(previous: xr.Dataset) -> tuple[float, float | None, np.ndarray]:
    """Time, step (None: fresh start) and state to continue ``previous`` from."""
    if "checkpoint_state" in previous:
        step = float(previous["checkpoint_step"])
        return (
            float(previous["checkpoint_time"]),
            None if math.isnan(step) else step,
            previous["checkpoint_state"].values,
        )
    return float(previous.attrs["final_time_s"]), None, previous["final_state"].values


_STATE_VARS = ("final_state", "checkpoint_state", "checkpoint_time", "checkpoint_step")


def _join(previous: xr.Dataset, continued: xr.Dataset) -> xr.Dataset:
    """The earlier run's outputs up to its resume point followed by the continued run's
    (an output at the resume time, present in both, is kept once). Counters are summed:
    the continued run's plus the earlier run's at its last checkpoint (older results
    without checkpoint: at their end)."""
    t0, _, _ = resume_state(previous)
    earlier = previous.sel(time=previous.time <= t0 + _core.time_slack(t0))
    later = continued.sel(time=continued.time > t0 + _core.time_slack(t0))
    joined = xr.concat(
        [
            earlier.drop_vars(_STATE_VARS, errors="ignore"),
            later.drop_vars(_STATE_VARS, errors="ignore"),
        ],
        dim="time",
        data_vars="all",
        combine_attrs="override",
    )
    for name in _STATE_VARS:
        joined[name] = continued[name]
    joined.attrs = dict(continued.attrs)
    prefix = "checkpoint_stats_" if "checkpoint_state" in previous else "stats_"
    for key in list(joined.attrs):
        for kind in ("stats_", "checkpoint_stats_"):
            if not key.startswith(kind) or key.endswith("t_reached"):
                continue
            base = previous.attrs.get(prefix + key[len(kind) :])
            if base is not None:
                joined.attrs[key] = type(base)(joined.attrs[key] + base)
    joined.attrs["resumed_at_s"] = t0
    return joined


#: Lossless compression of a result's numeric arrays: HDF5's byte shuffle and gzip at level
#: 1. B1's whole run (1 289 outputs): 16.7 MB -> 9.4 MB, written in 0.41-0.65 s (2026-12-02,
#: with the checksums and every group of solver.outputs; before the lubrication outputs
#: 11.2 MB -> 7.0 MB in 0.35-0.53 s instead of 0.21 s uncompressed, read in 0.29 s instead
#: of 0.25 s; level 4 was 1 % smaller and 20 % slower when measured with fewer outputs).
#: Each compressed chunk carries HDF5's Fletcher-32 checksum: a damaged chunk is refused on
#: reading (HDF5's "filter returned failure") instead of read as numbers (a byte flipped in
#: a torque gave 6.3e268 N*m in a report).
COMPRESSION = {"compression": "gzip", "compression_opts": 1, "shuffle": True, "fletcher32": True}
#: Arrays smaller than this [bytes] are stored as they are: a compressed array is stored in
#: chunks, whose index costs a few kB per array (a result of 5 outputs: 113 kB plain,
#: 166 kB with every array compressed).
COMPRESS_FROM = 64 * 1024


#: Serialises :func:`write`'s global Dask setting between threads.
_WRITE_LOCK = threading.Lock()


def _check_free_space(ds: xr.Dataset, path: str | Path) -> None:
    """Raises OSError (ENOSPC) if the disk of ``path`` has less room than the dataset's
    uncompressed size and 256 KiB: HDF5 that runs out of space while writing prints
    tracebacks it cannot raise and can crash the process (seen with a full tmpfs)."""
    import errno
    import shutil

    need = sum(v.nbytes for v in ds.variables.values()) + 2**18
    free = shutil.disk_usage(os.path.dirname(os.path.abspath(path))).free
    if free < need:
        raise OSError(
            errno.ENOSPC,
            f"No space left on device ({free} bytes free, the file needs up to {need})",
            path,
        )


#: Least wall-clock time between two checkpoint writes of a run's result file [s]
#: (:class:`CheckpointSaver`; ``rollerdyn run --save-interval``).
SAVE_INTERVAL = 10.0


class ResultFile:
    """The file a run writes again and again (its checkpoints, then the whole result):
    each write goes through a temporary file and replaces only the file this object wrote
    last, as it left it, or at first an existing file at ``path`` if ``replace_existing``
    (``rollerdyn run --overwrite``, or ``--resume`` in place). A file that another program
    (or a second rollerdyn) put there or changed meanwhile is kept, and the result goes to
    the first free name beside it, ``NAME-2.nc``, ``NAME-3.nc``, ...
    (:func:`rollerdyn.paths.place_file`); ``path`` then names it, later writes go there,
    and ``moved`` (if given) is told the old and the new file at once."""

    def __init__(
        self,
        path,
        replace_existing: bool = True,
        moved: Callable[[Path, Path], None] | None = None,
    ):
        self.path = Path(path)
        self._own = _file_identity(self.path) if replace_existing else None
        self._moved = moved

    def _is_own(self, path: Path) -> bool:
        return self._own is not None and _file_identity(path) == self._own

    def write(self, ds: xr.Dataset, compress: bool = True) -> Path:
        """Writes ``ds`` (:func:`write`); returns the file written."""
        written = write(ds, self.path, compress, replace=self._is_own)
        if written != self.path and self._moved is not None:
            self._moved(self.path, written)
        self.path, self._own = written, _file_identity(written)
        return written


def _file_identity(path: Path) -> tuple[int, ...] | None:
    """What tells the file ``path`` names from any other and from itself rewritten: its
    device, inode, size and time of last change, not following a symbolic link; None if
    there is none."""
    try:
        st = os.lstat(path)
    except (OSError, ValueError):
        return None
    return (st.st_dev, st.st_ino, st.st_size, st.st_mtime_ns)


class CheckpointSaver:
    """Writes a run's checkpoints to ``path`` (uncompressed, atomically, each replacing only
    the checkpoint before it: :class:`ResultFile`, which ``file`` is; an existing file at
    ``path`` is replaced if ``replace_existing``; ``moved`` as there): the first at once, a
    later one only once ``every`` seconds of wall time (``clock``) have passed since the end
    of the last write; ``every`` = 0 writes each. A write costs about the same whatever the
    data, h5netcdf's creation of the result's variables (0.3–0.5 s for B1's on this
    machine): at every one of B1's 13 checkpoints, about a tenth of the run. After kill -9
    the file holds the run up to the last checkpoint written, so at most ``every`` plus one
    checkpoint interval of work is lost; an interruption or error that Python sees writes
    everything anyway. ``writes`` counts the writes."""

    def __init__(
        self,
        path,
        every: float = SAVE_INTERVAL,
        clock=time.monotonic,
        replace_existing: bool = True,
        moved: Callable[[Path, Path], None] | None = None,
    ):
        if not (math.isfinite(every) and every >= 0.0):
            raise ValueError(f"save interval = {every!r}: must be a time of at least 0 s")
        self.file = ResultFile(path, replace_existing, moved)
        self.every, self.clock = every, clock
        self.last: float | None = None
        self.writes = 0

    @property
    def path(self) -> Path:
        """The file the checkpoints go to (another name if a foreign file took ``path``)."""
        return self.file.path

    def __call__(self, ds: xr.Dataset) -> bool:
        """Writes ``ds`` if it is due; True if it was written."""
        if self.last is not None and self.clock() - self.last < self.every:
            return False
        self.file.write(ds, compress=False)  # the final write compresses
        self.last = self.clock()
        self.writes += 1
        return True


def write(
    ds: xr.Dataset,
    path,
    compress: bool = True,
    replace: bool | Callable[[Path], bool] = True,
) -> Path:
    """Writes a result to netCDF (h5netcdf engine) atomically: encoded in memory
    (:func:`encode`), written to a temporary file beside ``path``
    (:func:`rollerdyn.paths.temporary_path`) and flushed to the disk, then renamed over it
    (:func:`rollerdyn.paths.write_atomically`), so that ``path`` always holds a complete
    file (the previous checkpoint's, if the process is killed while writing), and a disk
    that fills meanwhile raises ``OSError`` (HDF5 writing a file itself then printed
    tracebacks and could crash the process). ``replace``: whether a file at ``path`` may be
    replaced, or a function of the path that says so at the rename; a file that may not is
    kept and the result goes to ``NAME-2.nc`` (:func:`rollerdyn.paths.place_file`). Returns
    the file written. ``compress=False`` for the checkpoints a run writes as it goes (B1
    writes 13: compressing each would add about 1.5 s to a 40 s run); the final file is
    compressed."""
    from .paths import write_atomically

    path = Path(os.fspath(path))
    _check_free_space(ds, path)
    return write_atomically(path, encode(ds, compress), replace)


def encode(ds: xr.Dataset, compress: bool = True) -> memoryview:
    """A result as the bytes of a netCDF file (h5netcdf engine), encoded in memory. Numeric
    arrays of at least :data:`COMPRESS_FROM` bytes are compressed without loss
    (:data:`COMPRESSION`) if ``compress``; values read back are bit for bit the ones
    written. Raises what h5py raises for data it cannot encode (``RuntimeError``,
    ``ValueError``, ``TypeError``)."""
    import io

    import dask

    # Every variable's encoding set here: one read back from a file would keep that file's
    # (its compression, chunks) otherwise.
    encoding = {
        name: dict(COMPRESSION)
        if compress and var.ndim > 0 and var.dtype.kind in "fiub" and var.nbytes >= COMPRESS_FROM
        else {}
        for name, var in ds.data_vars.items()
    }
    buffer = io.BytesIO()
    # The synchronous scheduler: in a Dask worker (a sweep's or a study's run), xarray
    # would otherwise ask for the worker's client and open one to the scheduler, a
    # connection that outlives the cluster ("Exception ignored in Client.__del__" once the
    # cluster is closed). A result is numpy data: nothing to schedule. The setting is
    # global: the lock keeps two threads' writes (a worker of several threads) from
    # restoring each other's setting out of order.
    with _WRITE_LOCK, dask.config.set(scheduler="synchronous"):
        ds.to_netcdf(buffer, engine="h5netcdf", encoding=encoding)
    return buffer.getbuffer()
