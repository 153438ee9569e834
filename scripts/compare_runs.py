"""Agreement of two whole B1 runs output by output, e.g. the semi-analytical and the
gradient detector's runs of `rollerdyn study paper` (docs/dynamics.md, "Agreement of the two
detectors in whole B1 runs"):

    .venv/bin/python scripts/compare_runs.py results/study/runs/axial-1000N.nc \\
        results/study/runs/axial-1000N-gradient.nc

Prints the largest difference of a roller's position in the load zone (within 60° of its
centre) and outside it, over the whole run and at full speed (t >= 0.75 s, split into axial,
radial and circumferential), of tilt and skew, of the roller end-flange normal forces
(relative to the largest) and of the frictional torque (mean at full speed, and output by
output): `rollerdyn.study.agreement.differences`, which the paper study's finding
`same_kinematics` uses too.
"""

import signal
import sys

import numpy as np
import xarray as xr

from rollerdyn.study.agreement import differences, missing_variables

UM = 1e6


def open_run(path: str) -> xr.Dataset:
    """The result file at `path`, or exit with one line saying why it cannot be compared."""
    try:
        ds = xr.open_dataset(path)
    except FileNotFoundError:
        sys.exit(f"compare_runs: {path}: no such file")
    except (OSError, ValueError) as error:
        sys.exit(f"compare_runs: {path}: not a readable result file ({type(error).__name__})")
    missing = missing_variables(ds)
    if missing:
        sys.exit(f"compare_runs: {path}: not a run's result (no {', '.join(missing)})")
    return ds


def main(first: str, second: str) -> None:
    a, b = open_run(first), open_run(second)
    try:
        d = differences(a, b)
    except ValueError as error:
        sys.exit(f"compare_runs: {error}")
    print(f"compared over 0 ... {d['t_end']:.4f} s, {d['outputs']} outputs")
    print(
        f"position: load zone {d['position_load_zone'] * UM:.3f} um, "
        f"outside {d['position_outside'] * UM:.3f} um"
    )
    if np.isfinite(d["tilt_full_speed"]):
        print(
            f"at full speed: load zone {d['position_load_zone_full_speed'] * UM:.3f} um, "
            f"outside {d['position_outside_full_speed'] * UM:.3f} um; "
            f"axial {d['axial_full_speed'] * UM:.3f}, radial {d['radial_full_speed'] * UM:.3f}, "
            f"circumferential {d['circumferential_full_speed'] * UM:.3f} um"
        )
        for name in ("tilt", "skew"):
            print(f"{name} at full speed: {d[name + '_full_speed'] * 1e3:.3f} mrad")
    print(f"flange normal force: {d['flange_force'] * 100:.3f} % of the largest")
    if np.isfinite(d["torque_full_speed"]):
        print(
            f"torque at full speed: mean relative {d['torque_mean_full_speed']:.2e}; output "
            f"by output {d['torque_full_speed'] * 100:.3f} % of the largest"
        )
    for key in ("stats_steps", "stats_gradient_fallbacks", "stats_total_seconds"):
        print(f"{key}: {a.attrs.get(key)} against {b.attrs.get(key)}")


if __name__ == "__main__":
    signal.signal(signal.SIGPIPE, signal.SIG_DFL)  # `| head` ends the output quietly
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
