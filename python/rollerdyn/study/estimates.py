"""The quasi-static estimate beside each point of an operating map: the friction torque of
steady rolling (:func:`rollerdyn.statics.statics_sweep`'s ``friction_torque``, the contacts
evaluated at the quasi-static equilibrium with each roller spinning where its friction
moments balance; docs/statics.md, "Friction of steady rolling"). It costs milliseconds a
point where the point's dynamic run costs seconds, and the two side by side show what the
dynamics add: the neighbours' friction on the unloaded rollers, the rollers' skew and the
roller ends' own positions on the flanges (docs/study.md, "The quasi-static estimate
beside each point").
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

#: The map's column of the estimate, and of the dynamic torque over it.
STEADY_ROLLING = "steady rolling torque [N*m]"
TORQUE_RATIO = "torque over steady rolling [1]"


def steady_rolling_torques(cfg: Any, axes: Sequence[Sequence[float]]) -> list[float]:
    """The friction torque of steady rolling [N*m] at every point of the map's grid
    ``axes`` (speeds [rad/s] of the turning ring, radial and axial loads [N], oil
    temperatures [K]; the points in the map's order, the temperature fastest), NaN where
    the statics find no equilibrium or give no friction estimate (their ``friction_note``:
    the point law's roller ends on their faces). ``cfg``: the map's configuration (its flange law,
    tilt and the rest as the points have them)."""
    from ..statics import StaticsError, statics_sweep
    from .maps import turning_ring

    speeds, radial, axial, temperatures = (list(a) for a in axes)
    grid = {
        f"operating.{turning_ring(cfg)}_ring_speed": speeds,
        "operating.radial_load": radial,
        "operating.axial_load": axial,
    }
    design = {}
    if temperatures != [cfg.operating.temperature]:
        design["operating.temperature"] = temperatures
    loads = len(speeds) * len(radial) * len(axial)
    try:
        ds = statics_sweep(cfg, grid, design=design, stiffness=False)
    except StaticsError:  # no point has an equilibrium
        return [math.nan] * (loads * len(temperatures))
    torque = ds["friction_torque"].values
    # the sweep's cases: the temperature slowest, then speed, radial and axial load
    return [float(torque[t * loads + i]) for i in range(loads) for t in range(len(temperatures))]


__all__ = ["STEADY_ROLLING", "TORQUE_RATIO", "steady_rolling_torques"]
