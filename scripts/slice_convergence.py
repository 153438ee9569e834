"""Slice convergence of the whole B1 run (docs/dynamics.md, "Slices per roller"): B1 as in
examples/b1.toml with `geometry.roller.slices` set to each count given, one thread each:

    .venv/bin/python scripts/slice_convergence.py 5 10 15 20 30 40

Prints per count the solver's work (steps, Newton failures, right-hand sides, wall time)
and the run's results at full speed, each the mean over the outputs at t >= 0.75 s of: the
frictional torque, the largest inner-race roller load, the largest roller end-flange normal
force, the largest roller-roller normal force, and the largest |tilt| and |skew| of a
roller. Each run takes about as long as `rollerdyn bench mbs --cases whole --threads 1`
(more slices, longer); run two at a time on two cores, their wall times compare only with
each other.
"""

import sys
from pathlib import Path

import numpy as np

from rollerdyn import load_config
from rollerdyn.config import parse_config
from rollerdyn.simulation import SimulationError, simulate
from rollerdyn.sweep import _changed

B1 = Path(__file__).resolve().parents[1] / "examples" / "b1.toml"


def results_at_full_speed(ds) -> dict[str, float]:
    """The compared quantities: means over the outputs at t >= 0.75 s."""
    late = ds.sel(time=slice(0.75, None))
    return {
        "torque [N m]": float(late.frictional_torque.mean()),
        "inner-race load max [N]": float(late.inner_normal_force.max("roller").mean()),
        "flange force max [N]": float(late.flange_normal_force.max(("roller", "flange")).mean()),
        "roller-roller max [N]": float(late.roller_roller_normal_force.max("roller").mean()),
        "tilt max [rad]": float(np.abs(late.tilt).max("roller").mean()),
        "skew max [rad]": float(np.abs(late.skew).max("roller").mean()),
    }


def main(counts: list[int]) -> None:
    base = load_config(B1)
    for n in counts:
        changed = _changed(base.model_dump(), {"geometry.roller.slices": n})
        ds = simulate(parse_config(changed, si_numbers=True), threads=1)
        a = ds.attrs
        work = (
            f"steps {a['stats_steps']}, Newton failures {a['stats_newton_failures']}, "
            f"right-hand sides {a['stats_rhs_evaluations']}, wall {a['stats_total_seconds']:.1f} s"
        )
        found = ", ".join(f"{k} {v:.6g}" for k, v in results_at_full_speed(ds).items())
        print(f"slices {n}: {work}; {found}", flush=True)


if __name__ == "__main__":
    try:
        main([int(n) for n in sys.argv[1:]] or [10, 20, 40])
    except (ValueError, SimulationError) as err:  # a bad count, or a run stopped (Ctrl-C)
        sys.exit(f"slice_convergence.py: {err}")
    except KeyboardInterrupt:
        sys.exit("slice_convergence.py: stopped")
