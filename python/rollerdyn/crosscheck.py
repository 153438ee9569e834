"""A run beside the quasi-static estimate at its final loads and speed: what the report
shows under "Beside the quasi-static estimate" (docs/report.md).

The estimate is :func:`rollerdyn.statics.statics` of the run's own configuration at the
loads and ring speeds of its final time (the equilibrium, its friction of steady rolling
with each roller's spin and skew balanced; docs/statics.md), in milliseconds. Side by side
with the run's means over its last outputs they show what the dynamics add (the ends'
positions under friction, the neighbours' friction, the unloaded rollers' skid) and catch a
run that went wrong, e.g. one that is not yet steady. B1 at 1000 N: the torque 0.3025
against 0.3039 N·m, the loaded rollers' slip at the load zone's centre -0.199 against
-0.209 % (docs/statics.md).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import xarray as xr

__all__ = ["Beside", "beside_statics"]

#: Half the width of the azimuth window around the load zone's centre (180 deg, the radial
#: load along -y) over which the run's slip is averaged [deg].
CENTRE_WINDOW = 10.0


@dataclass(frozen=True)
class Beside:
    """One quantity of the run and the estimate's: (label, unit, run, estimate)."""

    label: str
    unit: str
    run: float
    estimate: float


def beside_statics(ds: xr.Dataset, last: np.ndarray) -> list[Beside] | str:
    """The run ``ds`` (its outputs ``last`` averaged) beside the quasi-static estimate at
    its final loads and speed: friction torque, heaviest roller's load at the inner race,
    largest flange force and the slip of the rollers at the load zone's centre; NaN where
    the run did not record the output. A string says why there is no estimate (no
    configuration recorded, no equilibrium)."""
    from .modes import run_config
    from .report import power_summary
    from .statics import StaticsError, statics

    try:
        cfg = run_config(ds)
    except ValueError as err:
        return f"no estimate: {err}"
    op, t = cfg.operating, float(ds.attrs["final_time_s"])
    inner, outer = op.inner_ring_speed_at(t), op.outer_ring_speed_at(t)
    try:
        st = statics(
            cfg,
            radial_load=op.radial_load_at(t),
            axial_load=op.axial_load_at(t),
            speed=inner,
            outer_speed=outer,
            carrier_speed=op.carrier_speed_at(t),
        )
    except (StaticsError, ValueError) as err:
        return f"no estimate: {err}"
    rows = [
        Beside(
            "friction torque (mean power loss over the ring speed)",
            "N*m",
            power_summary(ds, last)["torque_from_power"],
            float(st.friction_torque),
        ),
        Beside(
            "heaviest roller's load at the inner race",
            "N",
            _mean_of_largest(ds, "inner_normal_force", last),
            float(st.max_roller_load),
        ),
        Beside(
            "largest roller end / flange force",
            "N",
            _mean_of_largest(ds, "flange_normal_force", last),
            float(st.max_flange_force),
        ),
    ]
    slip = _centre_slip(ds, cfg, last, inner, outer)
    heaviest = int(np.argmin(np.abs(st.roller_azimuth.values % 360.0 - 180.0)))
    rows.append(
        Beside(
            f"slip of the rollers within {CENTRE_WINDOW:g} deg of the load zone's centre",
            "%",
            100.0 * slip,
            100.0 * float(st.roller_slip[heaviest]),
        )
    )
    return rows


def _mean_of_largest(ds: xr.Dataset, name: str, last: np.ndarray) -> float:
    """The mean over the outputs ``last`` of the largest value of ``name`` at each."""
    if name not in ds:
        return math.nan
    values = np.asarray(ds[name].values[last], dtype=float)
    values = values.reshape(values.shape[0], -1)
    with np.errstate(all="ignore"):
        largest = np.nanmax(np.where(np.isfinite(values), values, -np.inf), axis=1)
    largest = largest[np.isfinite(largest)]
    return float(np.mean(largest)) if largest.size else math.nan


def _centre_slip(ds: xr.Dataset, cfg, last: np.ndarray, inner: float, outer: float) -> float:
    """The run's slip 1 - (spin - omega_c) / spin of rolling without slip of the rollers
    within :data:`CENTRE_WINDOW` of the load zone's centre over the outputs ``last``, the
    spins about the rollers' own axes taken relative to the roller set's frame at the
    epicyclic speed omega_c, as the statics' ``roller_slip`` (NaN if not recorded)."""
    from .config.derived import epicyclic_speed

    if "spin_speed" not in ds or "azimuth" not in ds:
        return math.nan
    g = cfg.geometry
    orbit = epicyclic_speed(inner, outer, g.epicyclic_factor)
    rolling = (orbit - inner) * g.inner_raceway_diameter / g.roller_diameter
    if rolling == 0.0:
        return math.nan
    azimuth = np.degrees(np.asarray(ds.azimuth.values[last], dtype=float)) % 360.0
    spin = np.asarray(ds.spin_speed.values[last], dtype=float)
    centre = np.abs(azimuth - 180.0) < CENTRE_WINDOW
    if not centre.any():
        return math.nan
    return float(1.0 - (np.mean(spin[centre]) - orbit) / rolling)
