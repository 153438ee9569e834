"""Continuing an interrupted sweep (`rollerdyn sweep --resume`, `sweep(..., resume=True)`,
`python/rollerdyn/sweep_resume.py`): the runs that finished are kept, file for file, and
only the others run; a run file of another sweep is refused by name before anything runs.

The reference for "kept" is the file itself (the same inode and modification time: not
written again) and for "the same sweep" a sweep run in one go: the simulator is
deterministic, so a resumed sweep's summary must equal it number for number.
"""

from __future__ import annotations

import math
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pandas as pd
import pytest
from b1 import B1, changed_b1
from typer.testing import CliRunner

import rollerdyn
from rollerdyn.cli import app
from rollerdyn.simulation import SimulationError
from rollerdyn.sweep import SweepError, build_grid, run_one

RUNNER = CliRunner()

SHORT_DATA = changed_b1(
    {
        "operating.gravity": "0 m/s^2",
        "operating.inner_ring_speed": "0 rpm",
        "operating.speed_ramp": None,
        "operating.load_ramp.end": "1 ms",
        "operating.end_time": "3 ms",
        "solver.output_interval": "0.25 ms",
    }
)
GRID = {"operating.axial_load": ["0 N", "250 N", "500 N"]}
#: The summary's columns a resumed sweep must reproduce exactly (the wall time is not one).
NUMBERS = ["run", "status", "final_time [s]", "mean_frictional_torque [N*m]", "steps", "file"]


def _stamps(folder: Path) -> dict[str, tuple[int, int]]:
    """Each run file's inode and modification time: changed by any write or replacement."""
    return {p.name: (p.stat().st_ino, p.stat().st_mtime_ns) for p in folder.glob("run_*.nc")}


def _interrupted_sweep(folder: Path, resume: bool = False) -> list[int]:
    """A sweep of GRID on one worker, interrupted as the main thread's Ctrl-C would be when
    its first run finishes; returns the runs reported before it."""
    reported: list[int] = []

    def interrupt(done, total, row):
        if row is not None:
            reported.append(row["run"])
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        rollerdyn.sweep(SHORT_DATA, GRID, folder, workers=1, progress=interrupt, resume=resume)
    return reported


def test_resume_runs_only_the_points_the_interrupted_sweep_left(tmp_path):
    # resume=True on an empty folder is a plain sweep (here interrupted after one run)
    _interrupted_sweep(tmp_path / "sw", resume=True)
    folder = tmp_path / "sw"
    before = _stamps(folder)
    interrupted = pd.read_parquet(folder / "summary.parquet")
    left = set(interrupted.loc[interrupted["status"] == "interrupted", "run"])
    assert before and left, interrupted  # one run kept at least, one left at least
    calls = []
    frame = rollerdyn.sweep(
        SHORT_DATA, GRID, folder, workers=1, resume=True, progress=lambda *c: calls.append(c)
    )
    # the first report counts the kept runs as done; only the others were run
    assert calls[0][:2] == (len(before), 3) and calls[0][2] is None
    assert {row["run"] for _, _, row in calls[1:]} == left
    assert all(_stamps(folder)[name] == stamp for name, stamp in before.items())
    assert list(frame["status"]) == ["completed"] * 3
    # a kept run's wall time is the earlier summary's
    for run in set(interrupted["run"]) - left:
        wall = interrupted.loc[interrupted["run"] == run, "wall [s]"].item()
        kept = frame.loc[frame["run"] == run, "wall [s]"].item()
        assert kept == wall or (math.isnan(kept) and math.isnan(wall))
    # the same numbers as the sweep run in one go (deterministic simulator)
    whole = rollerdyn.sweep(SHORT_DATA, GRID, tmp_path / "whole", workers=2)
    pd.testing.assert_frame_equal(frame[NUMBERS], whole[NUMBERS])
    assert pd.read_parquet(folder / "summary.parquet")[NUMBERS].equals(frame[NUMBERS])
    # resumed once more, nothing is left: no cluster, no run, every file kept
    stamps = _stamps(folder)
    again = rollerdyn.sweep(SHORT_DATA, GRID, folder, resume=True)
    assert _stamps(folder) == stamps
    pd.testing.assert_frame_equal(again[NUMBERS], frame[NUMBERS])


@pytest.fixture(scope="module")
def finished(tmp_path_factory) -> Path:
    """A folder holding GRID's sweep, run whole (3 ms each)."""
    folder = tmp_path_factory.mktemp("finished")
    rollerdyn.sweep(SHORT_DATA, GRID, folder, workers=2)
    return folder


@pytest.mark.parametrize(
    ("grid", "kwargs", "match"),
    [
        (
            {"operating.axial_load": ["0 N", "300 N", "500 N"]},
            {},
            r"run_0001.nc \(run 1\) was run with another configuration \(SI values, earlier "
            r"-> now\): operating.axial_load: 250.0 -> 300.0",
        ),
        (
            {"operating.axial_load": ["0 N", "250 N"]},
            {},
            "run_0002.nc is a run of an earlier sweep with more points than this one's 2",
        ),
        (GRID, {"t_end": "2 ms"}, r"was run to t = 0.003 s, this sweep's end time is 0.002 s"),
        (GRID, {"detector": "gradient"}, "detector 'semi-analytical', this sweep's is 'gradient'"),
        (GRID, {"overwrite": True}, "overwrite = True and resume = True: choose one"),
        (GRID, {"resume": "yes"}, "resume = 'yes': must be True or False"),
    ],
)
def test_resume_refuses_another_sweeps_runs_and_touches_nothing(finished, grid, kwargs, match):
    stamps = _stamps(finished)
    summary = (finished / "summary.parquet").stat().st_mtime_ns
    kwargs = {"resume": True, **kwargs}
    with pytest.raises(SweepError, match=match):
        rollerdyn.sweep(SHORT_DATA, grid, finished, **kwargs)
    assert _stamps(finished) == stamps
    assert (finished / "summary.parquet").stat().st_mtime_ns == summary


def test_a_failed_run_is_kept_as_failed_and_an_interrupted_one_runs_again(tmp_path, monkeypatch):
    # A run that failed would fail again bit for bit: kept, with its error. A file whose
    # run was interrupted (its error says so; not what a sweep writes, but a file of its
    # name) is not finished: its point runs again.
    import rollerdyn.simulation as simulation

    (point,) = build_grid(SHORT_DATA, {"operating.axial_load": ["0 N"]})
    real = rollerdyn.simulate(rollerdyn.parse_config(point.data))
    for error, file in (("step size too small at t = 0.5 ms", "failed"), ("interrupted", "run")):
        partial = real.isel(time=slice(0, 3)).copy()
        partial.attrs.update(completed=0, error=error, final_time_s=5e-4)

        def failing(cfg, partial=partial, **kw):
            raise SimulationError(partial.attrs["error"], partial)

        monkeypatch.setattr(simulation, "simulate", failing)
        folder = tmp_path / file
        folder.mkdir()
        assert run_one(point.data, False, str(folder), point.file)["status"] == "failed"
        monkeypatch.undo()
        stamps = _stamps(folder)
        frame = rollerdyn.sweep(SHORT_DATA, {"operating.axial_load": ["0 N"]}, folder, resume=True)
        if file == "failed":
            assert _stamps(folder) == stamps
            assert frame["status"].item() == "failed" and error in frame["error"].item()
        else:
            assert _stamps(folder) != stamps
            assert frame["status"].item() == "completed"
            assert frame["final_time [s]"].item() == pytest.approx(3e-3, rel=1e-9)


def test_cli_resume_after_ctrl_c_finishes_the_sweep(tmp_path):
    # Ctrl-C in the terminal (to the process group) while runs are out: one line that
    # names the summary and --resume, exit status 130; the same command with --resume
    # keeps what finished, runs the rest and exits with 0.
    command = Path(sys.executable).parent / "rollerdyn"
    folder = tmp_path / "sw"
    args = [str(command), "sweep", str(B1), "--set", "operating.axial_load=500 N,1000 N,1500 N"]
    args += ["--t-end", "0.2 s", "--workers", "1", "-o", str(folder)]
    proc = subprocess.Popen(
        args, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, start_new_session=True
    )
    lines = []
    for line in proc.stdout:  # until the first run finished
        lines.append(line)
        if "done" in line:
            break
    os.killpg(proc.pid, signal.SIGINT)
    out, _ = proc.communicate(timeout=60)
    out = "".join(lines) + out
    assert proc.returncode == 130, out
    assert "Traceback" not in out, out
    last = out.strip().splitlines()[-1]
    assert last.startswith("rollerdyn sweep: interrupted; ") and "with --resume" in last, out
    stamps = _stamps(folder)
    assert stamps, out
    start = time.monotonic()
    done = subprocess.run([*args, "--resume"], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stdout + done.stderr
    kept = len(stamps)
    said = f"{kept} of 3 runs kept" if kept < 3 else "all 3 runs kept"
    assert f"{said} from the earlier sweep" in done.stdout, done.stdout
    assert all(_stamps(folder)[name] == stamp for name, stamp in stamps.items())
    frame = pd.read_parquet(folder / "summary.parquet")
    assert list(frame["status"]) == ["completed"] * 3, (frame, time.monotonic() - start)


def test_cli_resume_and_overwrite_together_are_refused(tmp_path):
    result = RUNNER.invoke(
        app,
        ["sweep", str(B1), "--set", "operating.axial_load=0 N", "-o", str(tmp_path)]
        + ["--resume", "--overwrite"],
    )
    assert result.exit_code == 2
    assert "--overwrite and --resume: choose one" in result.output
    assert list(tmp_path.iterdir()) == []


def _copy(finished: Path, tmp_path: Path) -> Path:
    import shutil

    return Path(shutil.copytree(finished, tmp_path / "copy"))


def test_a_second_sweep_in_the_same_folder_is_refused_and_a_stale_lock_taken_over(
    finished, tmp_path
):
    """Two sweeps writing one folder replaced each other's run files and both said they
    completed (found by a review, 2026-12-02): a sweep holds the folder's lock
    (``.sweep.lock``, its process id) while it runs, another is refused in one line before
    it starts anything; a lock whose process is gone is taken over; none is left behind."""
    folder = _copy(finished, tmp_path)
    holder = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(60)"])
    try:
        (folder / ".sweep.lock").write_text(str(holder.pid))
        with pytest.raises(SweepError, match=rf"another sweep \(process {holder.pid}\) is running"):
            rollerdyn.sweep(SHORT_DATA, GRID, folder, resume=True)
    finally:
        holder.kill()
        holder.wait()
    frame = rollerdyn.sweep(SHORT_DATA, GRID, folder, resume=True)  # its process is gone
    assert list(frame["status"]) == ["completed"] * 3
    assert not (folder / ".sweep.lock").exists()


def test_resume_rewrites_a_summary_cut_short(finished, tmp_path):
    """A summary left empty or cut short (a sweep killed while an older version wrote it in
    place; it is now written through a temporary file) beside the sweep's own run files
    was refused as another program's; --resume takes it as the sweep's and writes it
    anew. Without run files of a sweep beside it, it is still refused."""
    folder = _copy(finished, tmp_path)
    whole = pd.read_parquet(folder / "summary.parquet")
    (folder / "summary.parquet").write_bytes(b"")
    frame = rollerdyn.sweep(SHORT_DATA, GRID, folder, resume=True)
    pd.testing.assert_frame_equal(frame[NUMBERS], whole[NUMBERS])
    assert pd.read_parquet(folder / "summary.parquet")[NUMBERS].equals(whole[NUMBERS])
    alone = tmp_path / "alone"
    alone.mkdir()
    (alone / "summary.parquet").write_bytes(b"")
    with pytest.raises(SweepError, match="summary.parquet is not a file an earlier sweep"):
        rollerdyn.sweep(SHORT_DATA, GRID, alone, resume=True)


def test_the_start_line_counts_what_the_sweep_kept():
    """The progress's first line gives the count the sweep itself kept (a run file whose
    data cannot be read is run again: 'no run left' was said before one was run)."""
    from rollerdyn.cli.sweep import _started

    assert _started(0, 3) == "3 runs submitted"
    assert _started(2, 3) == "2 of 3 runs kept from the earlier sweep, 1 run submitted"
    assert _started(3, 3) == "all 3 runs kept from the earlier sweep; writing the summary"
