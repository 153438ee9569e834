"""Agreement of two whole B1 runs output by output, e.g. the semi-analytical and the
gradient detector's runs of `rollerdyn study paper` (docs/dynamics.md, "Agreement of the two
detectors in whole B1 runs"):

    .venv/bin/python scripts/compare_runs.py results/study/runs/axial-1000N.nc \\
        results/study/runs/axial-1000N-gradient.nc

Prints the largest difference of a roller's position in the load zone (within 60° of its
centre) and outside it, over the whole run and at full speed (t >= 0.75 s, split into axial,
radial and circumferential), of tilt and skew, of the roller end-flange normal forces
(relative to the largest) and of the frictional torque (mean at full speed, and output by
output).
"""

import signal
import sys

import numpy as np
import xarray as xr

FULL_SPEED = 0.75  # s: B1's speed ramp ends at 0.7 s
UM = 1e6


NEEDED = ("time", "azimuth", "position", "tilt", "skew", "flange_normal_force")


def open_run(path: str) -> xr.Dataset:
    """The result file at `path`, or exit with one line saying why it cannot be compared."""
    try:
        ds = xr.open_dataset(path)
    except FileNotFoundError:
        sys.exit(f"compare_runs: {path}: no such file")
    except (OSError, ValueError) as error:
        sys.exit(f"compare_runs: {path}: not a readable result file ({type(error).__name__})")
    missing = [name for name in NEEDED + ("frictional_torque",) if name not in ds.variables]
    if missing:
        sys.exit(f"compare_runs: {path}: not a run's result (no {', '.join(missing)})")
    return ds


def main(first: str, second: str) -> None:
    a, b = open_run(first), open_run(second)
    if a.sizes["roller"] != b.sizes["roller"]:
        sys.exit(f"compare_runs: the runs have {a.sizes['roller']} and {b.sizes['roller']} rollers")
    n = min(a.sizes["time"], b.sizes["time"])
    a, b = a.isel(time=slice(0, n)), b.isel(time=slice(0, n))
    if not np.allclose(a.time, b.time):
        sys.exit("the two runs have different output times")
    t = a.time.values
    azimuth = np.mod(a.azimuth.values, 2 * np.pi)  # from +y towards +z; load zone centre pi
    zone = np.abs(azimuth - np.pi) <= np.radians(60)
    d = a.position.values - b.position.values  # (time, roller, xyz)
    dist = np.linalg.norm(d, axis=2)
    full = t >= FULL_SPEED
    radial = np.stack([np.zeros_like(azimuth), np.cos(azimuth), np.sin(azimuth)], axis=2)
    around = np.stack([np.zeros_like(azimuth), -np.sin(azimuth), np.cos(azimuth)], axis=2)
    print(f"compared over 0 ... {t[-1]:.4f} s, {n} outputs")
    print(
        f"position: load zone {dist[zone].max() * UM:.3f} um, "
        f"outside {dist[~zone].max() * UM:.3f} um"
    )
    if full.any():
        fz, fo = zone & full[:, None], ~zone & full[:, None]
        print(
            f"at full speed: load zone {dist[fz].max() * UM:.3f} um, outside "
            f"{dist[fo].max() * UM:.3f} um; axial {np.abs(d[..., 0])[full].max() * UM:.3f}, "
            f"radial {np.abs((d * radial).sum(2))[full].max() * UM:.3f}, "
            f"circumferential {np.abs((d * around).sum(2))[full].max() * UM:.3f} um"
        )
        for name in ("tilt", "skew"):
            diff = np.abs(a[name].values - b[name].values)[full].max()
            print(f"{name} at full speed: {diff * 1e3:.3f} mrad")
    fa = np.nan_to_num(a.flange_normal_force.values)
    fb = np.nan_to_num(b.flange_normal_force.values)
    largest = max(fa.max(), fb.max())
    worst = np.abs(fa - fb).max()
    print(
        f"flange normal force: {worst:.4f} N of the largest {largest:.2f} N "
        f"({worst / largest * 100:.3f} %)"
    )
    ta, tb = a.frictional_torque.values, b.frictional_torque.values
    if full.any():
        ma, mb = ta[full].mean(), tb[full].mean()
        print(
            f"torque at full speed: mean {ma:.6f} against {mb:.6f} N m "
            f"(relative {abs(ma - mb) / abs(ma):.2e}); output by output "
            f"{np.abs(ta - tb)[full].max() / np.abs(ta).max() * 100:.3f} % of the largest"
        )
    for key in ("stats_steps", "stats_gradient_fallbacks", "stats_total_seconds"):
        print(f"{key}: {a.attrs.get(key)} against {b.attrs.get(key)}")


if __name__ == "__main__":
    signal.signal(signal.SIGPIPE, signal.SIG_DFL)  # `| head` ends the output quietly
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
