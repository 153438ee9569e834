"""Whole runs of the operating points that decide how fast the dynamic model is
(``rollerdyn bench mbs --cases``): the B1 run as the paper defines it, B1 brought to full
speed quickly at 500 and 3000 rpm, with the inner ring free to tilt, at other axial loads,
and with the outer ring turning instead. Each is timed on the given threads with a
wall-time cap; the table gives steps, Newton failures, right-hand sides and the simulated
seconds per wall second."""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from .config import BearingConfig, parse_config
from .simulation import Progress, SimulationError, SimulationInterrupted, simulate
from .sweep import _changed

#: Loads over 0 ... 20 ms, speed over 20 ... 40 ms, end at 0.1 s: full speed fast.
_SHORT_RAMPS = {
    "operating.load_ramp": {"start": "0 s", "end": "20 ms", "shape": "cosine"},
    "operating.speed_ramp": {"start": "20 ms", "end": "40 ms", "shape": "cosine"},
    "operating.end_time": "0.1 s",
}

#: Full load and speed from t = 0, started from the quasi-static equilibrium, to 0.1 s.
_FROM_EQUILIBRIUM = {
    "operating.load_ramp": None,
    "operating.speed_ramp": None,
    "operating.end_time": "0.1 s",
    "solver.start": "equilibrium",
}

#: Name -> (what it is, dotted changes to the configuration; None removes a key).
CASES: dict[str, tuple[str, dict[str, Any]]] = {
    "whole": ("the configuration as it is (B1: the paper's run)", {}),
    "full-speed-500rpm": ("loads over 20 ms, 500 rpm over 20-40 ms, to 0.1 s", _SHORT_RAMPS),
    "full-speed-3000rpm": (
        "the same at 3000 rpm",
        {**_SHORT_RAMPS, "operating.inner_ring_speed": "3000 rpm"},
    ),
    "hot-3000rpm": (
        "full-speed-3000rpm with the oil at 120 degC (FVA 3: 6 mPa s against 16.5 at 80 degC)",
        {
            **_SHORT_RAMPS,
            "operating.inner_ring_speed": "3000 rpm",
            "operating.temperature": "120 degC",
        },
    ),
    "equilibrium-500rpm": (
        "full load and 500 rpm from an equilibrium start, to 0.1 s",
        _FROM_EQUILIBRIUM,
    ),
    "equilibrium-3000rpm": (
        "the same at 3000 rpm",
        {**_FROM_EQUILIBRIUM, "operating.inner_ring_speed": "3000 rpm"},
    ),
    "free-tilt": ("the whole run with inner_ring.tilt = free", {"inner_ring.tilt": "free"}),
    "tilt-0.05deg": (
        "the whole run with the locked ring tilted by 0.05 deg (inner_ring.misalignment)",
        {"inner_ring.misalignment": "0.05 deg"},
    ),
    "outer-ring": (
        "the whole run with the outer ring turning instead of the inner one (a planet gear's "
        "bearing): inner ring 0 rpm, outer ring 500 rpm",
        {"operating.inner_ring_speed": "0 rpm", "operating.outer_ring_speed": "500 rpm"},
    ),
    "planet-3000rpm": (
        "a planet gear's bearing: the outer ring at 500 rpm on a pin in a carrier at 3000 rpm, "
        "40 mm from the sun's axis, from an equilibrium start, to 0.1 s",
        {
            **_FROM_EQUILIBRIUM,
            "operating.inner_ring_speed": "0 rpm",
            "operating.outer_ring_speed": "500 rpm",
            "operating.carrier_speed": "3000 rpm",
            "operating.carrier_offset": "40 mm",
        },
    ),
    "axial-0N": ("the whole run with no axial load", {"operating.axial_load": "0 N"}),
    "axial-500N": ("the whole run with 500 N axial load", {"operating.axial_load": "500 N"}),
    "axial-2000N": ("the whole run with 2000 N axial load", {"operating.axial_load": "2000 N"}),
    "axial-3000N": ("the whole run with 3000 N axial load", {"operating.axial_load": "3000 N"}),
}

#: The distributed roller end-flange law (surfaces.flange_law) for each of the whole runs.
_DISTRIBUTED = {"surfaces.flange_law": "distributed"}
for _name in (
    "whole",
    "hot-3000rpm",
    "free-tilt",
    "tilt-0.05deg",
    "axial-0N",
    "axial-500N",
    "axial-2000N",
    "axial-3000N",
):
    _text, _changes = CASES[_name]
    CASES[f"distributed-{_name}"] = (
        f"{_text}, distributed flange law",
        {**_changes, **_DISTRIBUTED},
    )

#: The cases run when none are named.
DEFAULT_CASES = ("whole", "full-speed-500rpm", "full-speed-3000rpm", "free-tilt", "axial-0N")


@dataclass(frozen=True)
class CaseResult:
    """What one case's run did."""

    name: str
    threads: int
    target: float
    reached: float
    completed: bool
    wall: float
    steps: int
    rejected: int
    newton_failures: int
    rhs: int
    jacobians: int
    #: Of ``jacobians``, those renewed only in the failing rollers' columns
    #: (``solver.partial_jacobians``).
    partial_jacobians: int
    torque: float
    message: str = ""

    @property
    def sim_per_wall(self) -> float:
        """Simulated seconds per wall second."""
        return self.reached / self.wall if self.wall > 0 else float("nan")


def case_config(cfg: BearingConfig, name: str) -> BearingConfig:
    """``cfg`` changed as case ``name`` says (validated again)."""
    if name not in CASES:
        raise ValueError(f"case {name!r}: must be one of {', '.join(CASES)}")
    changes = CASES[name][1]
    if not changes:
        return cfg
    data = cfg.model_dump()
    for path in [p for p, v in changes.items() if v is None]:
        *parents, key = path.split(".")
        section = data
        for part in parents:
            section = section[part]
        section.pop(key, None)
    kept = {p: v for p, v in changes.items() if v is not None}
    return parse_config(_changed(data, kept), si_numbers=True)


def _refused(name: str, threads: int, target: float, start: float, err: Exception) -> CaseResult:
    """The result of a case that could not run, with the reason."""
    return CaseResult(
        name=name,
        threads=threads,
        target=target,
        reached=0.0,
        completed=False,
        wall=time.monotonic() - start,
        steps=0,
        rejected=0,
        newton_failures=0,
        rhs=0,
        jacobians=0,
        partial_jacobians=0,
        torque=float("nan"),
        message=" ".join(str(err).split()),
    )


def run_case(
    cfg: BearingConfig,
    name: str,
    max_wall: float,
    progress: Callable[[Progress], None] | None = None,
    threads: int = 1,
) -> CaseResult:
    """Runs case ``name`` of ``cfg`` on ``threads`` threads, stopped after ``max_wall``
    seconds of wall time from its first output (building the model comes before)."""
    start = time.monotonic()
    try:
        variant = case_config(cfg, name)
    except ValueError as err:  # the case does not apply to this configuration
        return _refused(name, threads, float(cfg.end_time), start, err)

    begun: list[float] = []  # the wall time of the first output: the cap counts from it

    def callback(p: Progress) -> bool:
        if progress is not None:
            progress(p)
        now = time.monotonic()
        if not begun:
            begun.append(now)
        return now - begun[0] > max_wall

    message = ""
    try:
        ds = simulate(variant, progress=callback, threads=threads)
    except SimulationInterrupted:
        raise  # Ctrl-C stops the benchmark, not only this case
    except SimulationError as err:
        ds, message = err.dataset, str(err).splitlines()[0]
    except ValueError as err:  # refused before the first step (e.g. no equilibrium)
        return _refused(name, threads, float(variant.end_time), start, err)
    a = ds.attrs
    late = ds.frictional_torque.sel(time=slice(0.9 * float(ds.time[-1]), None))
    return CaseResult(
        name=name,
        threads=int(a.get("threads", threads)),
        target=float(variant.end_time),
        reached=float(a["final_time_s"]),
        completed=bool(a["completed"]) and not message,
        wall=float(a["stats_total_seconds"]),
        steps=int(a["stats_steps"]),
        rejected=int(a.get("stats_error_test_failures", 0)),
        newton_failures=int(a.get("stats_newton_failures", 0)),
        rhs=int(a["stats_rhs_evaluations"]),
        jacobians=int(a["stats_jacobian_evaluations"]),
        partial_jacobians=int(a.get("stats_partial_jacobians", 0)),
        torque=float(late.mean()) if late.size else float("nan"),
        message=message or ("" if a["completed"] else f"stopped after {max_wall:g} s of wall time"),
    )
