"""How far two runs of the same bearing drift apart, output by output: the roller
positions (in the load zone and outside it, and split into axial, radial and
circumferential), tilts and skews at full speed, the roller end-flange normal forces and
the frictional torque (docs/dynamics.md, "Agreement of the two detectors in whole B1
runs").

Used on the semi-analytical and the gradient detector's runs of the paper study, and on the
semi-analytical run and its round-off twin (the same configuration with ``solver.atol``
changed in the tenth digit): the twin's error norms differ in their last digits, so sooner
or later one of its steps does, and from there it follows another sequence of steps within
the same tolerances. How far it then drifts is how far the integration at those
tolerances leaves the motion undetermined, a bound below which no comparison of two runs
can go."""

from __future__ import annotations

import math

import numpy as np
import xarray as xr

#: The speed ramp of B1 ends at 0.7 s; outputs from here on count as full speed [s]. Runs
#: whose speed ramp ends later use their own end (:func:`differences`).
FULL_SPEED = 0.75


def full_speed_time(ds: xr.Dataset, final_speed: float, share: float) -> float:
    """The first output time of ``ds`` at which the inner ring turns at ``share`` of its
    final speed ``final_speed`` [rad/s] or more (the ``full_speed`` of
    :func:`differences`); infinity if it never does."""
    final = abs(final_speed)
    turning = (np.abs(ds.ring_speed.values) >= share * final) & (final > 0)
    return float(ds.time.values[np.argmax(turning)]) if turning.any() else float("inf")


#: Half-width of the load zone about its centre (the roller azimuth pi: radial load along
#: -y, azimuth measured from +y towards +z) [rad].
LOAD_ZONE_HALF_WIDTH = np.radians(60.0)

#: What :func:`differences` needs in each file.
NEEDED = (
    "time",
    "azimuth",
    "position",
    "tilt",
    "skew",
    "flange_normal_force",
    "frictional_torque",
)

#: The measures of :func:`differences`: key -> (what, unit of the value).
MEASURES: dict[str, tuple[str, str]] = {
    "position_load_zone": ("roller position in the load zone (±60°), whole run", "m"),
    "position_outside": ("roller position outside the load zone, whole run", "m"),
    "position_load_zone_full_speed": ("roller position in the load zone, full speed", "m"),
    "position_outside_full_speed": ("roller position outside the load zone, full speed", "m"),
    "axial_full_speed": ("any roller's position along the axis, full speed", "m"),
    "radial_full_speed": ("any roller's position along the radius, full speed", "m"),
    "circumferential_full_speed": (
        "any roller's position along the circumference, full speed",
        "m",
    ),
    "tilt_full_speed": ("roller tilt, full speed", "rad"),
    "skew_full_speed": ("roller skew, full speed", "rad"),
    "flange_force": ("roller end-flange normal force, of the largest", "-"),
    "torque_mean_full_speed": ("mean frictional torque at full speed, relative", "-"),
    "torque_full_speed": ("frictional torque output by output at full speed, of the largest", "-"),
}


def _interval(ds: xr.Dataset) -> float:
    """A run's output interval [s]: the median spacing of its output times."""
    return float(np.median(np.diff(ds.time.values))) if ds.sizes["time"] > 1 else math.nan


def missing_variables(ds: xr.Dataset) -> list[str]:
    """The variables :func:`differences` needs that ``ds`` lacks."""
    return [name for name in NEEDED if name not in ds.variables]


def common_outputs(a: xr.Dataset, b: xr.Dataset) -> int:
    """How many leading outputs the two runs share (same times within 1e-12 s)."""
    n = min(a.sizes["time"], b.sizes["time"])
    same = np.isclose(a.time.values[:n], b.time.values[:n], rtol=0.0, atol=1e-12)
    return n if same.all() else int(np.argmin(same))


def shared_outputs(a: xr.Dataset, b: xr.Dataset) -> tuple[np.ndarray, np.ndarray]:
    """The indices in ``a`` and in ``b`` of the outputs at the same times (within 1e-12 s),
    wherever they lie: two runs' leading outputs for runs of one output interval, the
    times both intervals hit for runs of two (every 7 ms for 0.7 and 1 ms)."""
    ta, tb = a.time.values, b.time.values
    if ta.size == 0 or tb.size == 0:
        return np.zeros(0, int), np.zeros(0, int)
    after = np.clip(np.searchsorted(tb, ta), 0, tb.size - 1)  # the nearest at or after
    before = np.clip(after - 1, 0, None)
    nearest = np.where(np.abs(tb[before] - ta) < np.abs(tb[after] - ta), before, after)
    same = np.abs(tb[nearest] - ta) <= 1e-12
    return np.flatnonzero(same), nearest[same]


def differences(a: xr.Dataset, b: xr.Dataset, full_speed: float = FULL_SPEED) -> dict:
    """The largest differences of :data:`MEASURES` between runs ``a`` and ``b`` over their
    common outputs (NaN where no output qualifies, e.g. no full speed in a short run), with
    ``"outputs"`` and ``"t_end"`` [s]: what was compared, and ``"flange_force_largest"``
    [N]: the largest roller end-flange normal force of either run, which ``"flange_force"``
    is relative to, and ``"where"``: for each measure of a roller's position, tilt or skew,
    the output time [s], roller and its azimuth [deg] in ``a`` at which its largest
    difference lies (:func:`where_largest`). Measures of what a run did not record
    (``solver.outputs``: its rollers, its flanges) are NaN. Raises ``ValueError`` if the
    runs have different roller counts or share no output but the one at their start
    (:func:`shared_outputs`; two runs of different output intervals are compared at the
    times both have)."""
    rollers = a.sizes.get("roller"), b.sizes.get("roller")
    if None not in rollers and rollers[0] != rollers[1]:
        raise ValueError(f"the runs have {rollers[0]} and {rollers[1]} rollers")
    ia, ib = shared_outputs(a, b)
    if ia.size == 0:
        raise ValueError("the runs share no output times")
    if ia.size == 1 and min(a.sizes["time"], b.sizes["time"]) > 1:
        # one output at t = 0 compared the starts only and showed 0 everywhere (a review)
        raise ValueError(
            f"the runs share only their output at t = {float(a.time[ia[0]]):.6g} s (outputs "
            f"every {_interval(a):.4g} s and every {_interval(b):.4g} s); compare runs "
            "with a common solver.output_interval"
        )
    n = int(ia.size)
    a, b = a.isel(time=ia), b.isel(time=ib)
    t = a.time.values
    full = t >= full_speed
    out: dict = {
        "outputs": n,
        "t_end": float(t[-1]),
        **{key: np.nan for key in ROLLER_MEASURES},
        "where": {},
        "flange_force": np.nan,
        "flange_force_largest": np.nan,
        "torque_mean_full_speed": np.nan,
        "torque_full_speed": np.nan,
    }
    # what a run did not record (solver.outputs) stays NaN
    from ..simulation import recorded

    if recorded(a, "rollers") and recorded(b, "rollers"):
        out.update(_roller_differences(a, b, full))
    if recorded(a, "flanges") and recorded(b, "flanges"):
        fa = np.nan_to_num(a.flange_normal_force.values)
        fb = np.nan_to_num(b.flange_normal_force.values)
        largest = max(float(np.abs(fa).max()), float(np.abs(fb).max()))
        out["flange_force"] = _largest(np.abs(fa - fb)) / largest if largest > 0 else np.nan
        out["flange_force_largest"] = largest
    ta, tb = a.frictional_torque.values, b.frictional_torque.values
    if full.any():
        ma, mb = float(ta[full].mean()), float(tb[full].mean())
        out["torque_mean_full_speed"] = abs(ma - mb) / abs(ma) if ma != 0 else np.nan
        out["torque_full_speed"] = _largest(np.abs(ta - tb)[full]) / float(np.abs(ta).max())
    return out


#: The measures of :func:`_roller_differences`: a roller's position, tilt and skew.
ROLLER_MEASURES = (
    "position_load_zone",
    "position_outside",
    "position_load_zone_full_speed",
    "position_outside_full_speed",
    "axial_full_speed",
    "radial_full_speed",
    "circumferential_full_speed",
    "tilt_full_speed",
    "skew_full_speed",
)


def _roller_differences(a: xr.Dataset, b: xr.Dataset, full: np.ndarray) -> dict:
    """The measures of :data:`ROLLER_MEASURES` between ``a`` and ``b`` (the same outputs;
    ``full``: those at full speed), and ``"where"`` each largest lies."""
    t = a.time.values
    azimuth = np.mod(a.azimuth.values, 2 * np.pi)
    zone = np.abs(azimuth - np.pi) <= LOAD_ZONE_HALF_WIDTH
    d = a.position.values - b.position.values  # (time, roller, xyz)
    dist = np.linalg.norm(d, axis=2)
    radial = np.stack([np.zeros_like(azimuth), np.cos(azimuth), np.sin(azimuth)], axis=2)
    around = np.stack([np.zeros_like(azimuth), -np.sin(azimuth), np.cos(azimuth)], axis=2)
    fz, fo = zone & full[:, None], ~zone & full[:, None]
    full_rows = np.broadcast_to(full[:, None], dist.shape)
    per_roller = {  # measure -> (difference per output and roller, the outputs it is over)
        "position_load_zone": (dist, zone),
        "position_outside": (dist, ~zone),
        "position_load_zone_full_speed": (dist, fz),
        "position_outside_full_speed": (dist, fo),
        "axial_full_speed": (np.abs(d[..., 0]), full_rows),
        "radial_full_speed": (np.abs((d * radial).sum(2)), full_rows),
        "circumferential_full_speed": (np.abs((d * around).sum(2)), full_rows),
        "tilt_full_speed": (np.abs(a.tilt.values - b.tilt.values), full_rows),
        "skew_full_speed": (np.abs(a.skew.values - b.skew.values), full_rows),
    }
    return {
        **{key: _largest(values[mask]) for key, (values, mask) in per_roller.items()},
        "where": {
            key: where_largest(values, mask, t, azimuth)
            for key, (values, mask) in per_roller.items()
        },
    }


def where_largest(
    values: np.ndarray, mask: np.ndarray, time: np.ndarray, azimuth: np.ndarray
) -> dict | None:
    """Where the largest finite value of ``values`` (output, roller) within ``mask`` lies:
    ``{"time": [s], "roller": index, "azimuth_deg": [deg]}``; None if there is none."""
    chosen = np.where(mask & np.isfinite(values), values, -np.inf)
    if not np.isfinite(chosen).any():
        return None
    i, roller = np.unravel_index(int(np.argmax(chosen)), chosen.shape)
    return {
        "time": float(time[i]),
        "roller": int(roller),
        "azimuth_deg": float(np.degrees(azimuth[i, roller])),
    }


def where_text(place: dict | None) -> str:
    """``place`` of :func:`where_largest` as printed: 't = 0.62 s, roller 7 at 4.5°'."""
    if place is None:
        return ""
    return f"t = {place['time']:.4g} s, roller {place['roller']} at {place['azimuth_deg']:.1f}°"


def where_suffix(found: dict, key: str) -> str:
    """' (at t = …, roller … at …°)' for measure ``key`` of :func:`differences`' result
    ``found``, or '' where it is not known."""
    place = where_text(found.get("where", {}).get(key))
    return f" (at {place})" if place else ""


def measure_text(key: str, value: float) -> str:
    """The value of measure ``key`` of :data:`MEASURES` as the checks print it (µm, mrad
    or %; 'n/a' where not finite)."""
    unit = MEASURES[key][1]
    if not math.isfinite(value):
        return "n/a"
    if unit == "m":
        return f"{value * 1e6:.3g} µm"
    if unit == "rad":
        return f"{value * 1e3:.3g} mrad"
    return f"{100 * value:.3g} %"


def _largest(values: np.ndarray) -> float:
    """The largest finite value, NaN if there is none."""
    finite = values[np.isfinite(values)]
    return float(finite.max()) if finite.size else np.nan
