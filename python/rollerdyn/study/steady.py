"""When a grid point of ``rollerdyn study map`` is steady, and its outputs there.

The outputs, each averaged over a window of simulated time W:

- friction torque: the mean power loss over the mean speed of the rings relative to each
  other, mean(``power_loss``) / |mean(``ring_speed`` - ``outer_ring_speed``)| [N*m] (the
  mean of ``frictional_torque`` for a result without power losses over the whole window,
  or where the rings do not turn relative to each other): in steady running the
  two agree, but at light loads the torque's mean is pulled up by the velocity errors the
  tolerances allow (B1 without axial load: 15 % at its tolerances) and the power loss's
  is not (docs/dynamics.md, "Where the power goes");
- roller-set speed loss (skidding): ``1 - cage-equivalent speed / epicyclic speed``, where
  the cage-equivalent speed is the mean of every roller's ``orbital_speed`` and the
  epicyclic speed is ``omega_i (1 - D / d_m) / 2 + omega_o (1 + D / d_m) / 2`` of the
  mean ring speeds (no slip; ``omega_o`` = 0 where the outer ring is fixed) [1];
- largest flange force: the largest ``flange_normal_force`` of any roller and flange [N];
- the lubrication (a result that records it, ``solver.outputs`` "lubrication"; NaN
  otherwise): the median specific film thickness Lambda = h_c / sigma over the inner race
  contacts and over the roller end / flange contacts in contact in the window [1]
  (:mod:`rollerdyn.lubrication`; below 1 boundary, above 3 full-film lubrication);
- the inner ring's vibration: the peak-to-peak of its centre's y coordinate (along the
  radial load) over the window [m]. The window holds at least two roller passes (below),
  so this spans the ring's motion at the roller pass frequency as the rollers' varying
  compliance drives it (docs/dynamics.md, "Vibration and torque ripple at the roller pass
  frequency"); a drift within the window counts in it too.

The lubrication and the vibration are reported, not judged: the criterion compares the
three outputs above.

The criterion (:class:`SteadyRule`): from the end of the ramps on, the run is cut into
windows of length W that end at the checkpoints (``solver.checkpoint_interval`` = W, so
the check costs nothing between them); at each checkpoint t_k with
t_k - 3 W >= the ramps' end, the outputs over the last three windows [t_k - 3 W,
t_k - 2 W], [t_k - 2 W, t_k - W] and [t_k - W, t_k] are compared, each window with the
one before. The point is steady when in both comparisons every output changed by at most
``tol`` of its later value, or by at most its floor (:data:`FLOORS`) for values near
zero (two comparisons, so that one chance agreement of two windows does not end a run
that still drifts or swings). W is the larger of ``window`` and two roller passing
periods at the epicyclic speed (2 * 2 pi / (Z omega_c)), so each window averages over at
least two rollers passing a point. A point that is not steady at its maximum time ends
there and is reported as not steady, with its outputs over its last window.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..config.derived import epicyclic_speed
from ..simulation import ring_speeds

#: Changes below these count as steady whatever ``tol`` says (values near zero):
#: torque [N*m], speed loss [1], flange force [N]. The speed loss of a bearing that barely
#: skids is a small number whose window means swing by a few 1e-3 (B1 at 3000 rpm and
#: 1000 N: 0.0004 ... 0.005 from one 10 ms window to the next), so 0.5 % of the
#: epicyclic speed is its resolution.
FLOORS = {"torque [N*m]": 1e-4, "speed loss [1]": 5e-3, "max flange force [N]": 1.0}

#: The lubrication outputs (reported over the window, not part of the criterion): column
#: -> the contacts' variables' prefix.
LAMBDAS = {"inner race Lambda [1]": "inner", "flange Lambda [1]": "flange"}

#: The ring's vibration over the window (reported, not part of the criterion).
VIBRATION = "ring vibration [m]"


def window_length(window: float, speed: float, rollers: int, factor: float) -> float:
    """W [s]: ``window`` or two roller passing periods at ``speed`` [rad/s], the longer."""
    cage = abs(speed) * factor
    passing = 2.0 * math.pi / (rollers * cage) if cage > 0 else math.inf
    return max(window, 2.0 * passing)


def window_outputs(ds, t0: float, t1: float, factor: float) -> dict:
    """The outputs averaged over the outputs with t0 < t <= t1 (see the module's doc)."""
    t = np.asarray(ds.time.values, dtype=float)
    sel = (t > t0 + 1e-12) & (t <= t1 + 1e-12)
    if not sel.any():
        return {k: math.nan for k in (*FLOORS, *LAMBDAS, VIBRATION)}
    ring, outer = (float(np.mean(s[sel])) for s in ring_speeds(ds))
    orbital = float(np.nanmean(ds.orbital_speed.values[sel]))
    epicyclic = epicyclic_speed(ring, outer, factor)
    loss = 1.0 - orbital / epicyclic if epicyclic != 0 else math.nan
    relative = abs(ring - outer)
    flange = np.asarray(ds.flange_normal_force.values[sel], dtype=float)
    flange = flange[np.isfinite(flange)]
    torque = float(np.mean(ds.frictional_torque.values[sel]))
    power = np.asarray(ds.power_loss.values[sel], dtype=float) if "power_loss" in ds else []
    # a window reaching back into a result continued from one without power losses (NaN
    # there) keeps the torque's mean
    if len(power) and np.isfinite(power).all() and relative != 0.0:
        torque = float(np.mean(power)) / relative
    return {
        "torque [N*m]": torque,
        "speed loss [1]": loss,
        "max flange force [N]": float(flange.max()) if flange.size else 0.0,
        **{key: median_lambda(ds, prefix, sel) for key, prefix in LAMBDAS.items()},
        VIBRATION: ring_vibration(ds, sel),
    }


def ring_vibration(ds, sel: np.ndarray) -> float:
    """The peak-to-peak of the inner ring centre's y coordinate at the outputs ``sel``
    [m]; NaN for a result without the ring's position."""
    if "ring_position" not in ds:
        return math.nan
    return float(np.ptp(ds.ring_position.sel(xyz="y").values[sel]))


def median_lambda(ds, prefix: str, sel: np.ndarray) -> float:
    """The median specific film thickness of the ``prefix`` contacts in contact (a maximum
    pressure above 0) at the outputs ``sel``; NaN where none touches or the result did
    not record it."""
    from ..lubrication import in_contact

    if f"{prefix}_specific_film_thickness" not in ds or f"{prefix}_max_pressure" not in ds:
        return math.nan
    values = in_contact(ds, prefix, "specific_film_thickness", sel)
    return float(np.median(values)) if values.size else math.nan


def changes(before: dict, after: dict, tol: float) -> dict:
    """{output: (change, allowed)} between two windows' outputs."""
    out = {}
    for key, floor in FLOORS.items():
        a, b = before[key], after[key]
        out[key] = (abs(b - a), max(tol * abs(b), floor))
    return out


@dataclass(frozen=True)
class SteadyRule:
    """The stop rule of a map point (see the module's doc): called with the run so far at
    each checkpoint, returns ``"steady at t = ... s"`` once steady, else ''."""

    settle: float  # end of the ramps [s]
    window: float  # W [s]
    tol: float
    factor: float  # the inner ring's epicyclic factor, (1 - D/d_m)/2

    def verdict(self, ds) -> tuple[bool, float, dict]:
        """(steady, t_k, outputs over the last window) at the last multiple t_k of W
        that the run ``ds`` reached: its last checkpoint (``checkpoint_time``; the windows
        end at the checkpoints, which need not fall on output times) or its last output."""
        t_end = float(ds.time.values[-1])
        if "checkpoint_time" in ds:
            t_end = max(t_end, float(ds["checkpoint_time"]))
        w = self.window
        k = math.floor((t_end + 1e-12) / w)
        t_k = k * w
        last = window_outputs(ds, t_k - w, t_k, self.factor)
        if t_k - 3 * w < self.settle - 1e-12:
            return False, t_k, last
        windows = [window_outputs(ds, t_k - j * w, t_k - (j - 1) * w, self.factor) for j in (3, 2)]
        windows.append(last)
        ok = all(
            math.isfinite(c) and c <= allowed
            for before, after in zip(windows, windows[1:], strict=False)
            for c, allowed in changes(before, after, self.tol).values()
        )
        return ok, t_k, last

    def unmet(self, t_end: float) -> str:
        """What a run that ended at ``t_end`` without being steady is."""
        return f"not steady by its maximum time, t = {t_end:.6g} s"

    def __call__(self, ds) -> str:
        ok, t_k, _ = self.verdict(ds)
        return f"steady at t = {t_k:.6g} s" if ok else ""
