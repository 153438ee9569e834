"""Sweeps on Dask (issue 5, item 3): the grid, its validation, the runs on worker processes
against the same runs in series, the summary and the command line.

The runs are short static B1 variants (loads ramped over 1 ms, 3 ms simulated) so that the
whole module takes well under a minute on two cores.
"""

from __future__ import annotations

import math
from functools import cache
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import xarray as xr
from b1 import B1, changed_b1
from typer.testing import CliRunner

import rollerdyn
from rollerdyn.cli import app
from rollerdyn.simulation import SimulationError
from rollerdyn.sweep import (
    SUMMARY_COLUMNS,
    SweepError,
    build_grid,
    parse_set,
    run_one,
    summarize,
    toml_value,
)

RUNNER = CliRunner()

SHORT = {
    "operating.gravity": "0 m/s^2",
    "operating.inner_ring_speed": "0 rpm",
    "operating.speed_ramp": None,
    "operating.load_ramp.end": "1 ms",
    "operating.end_time": "3 ms",
    "solver.output_interval": "0.25 ms",
}
AXIAL = ["0 N", "500 N"]


SHORT_DATA = changed_b1(SHORT)


@cache
def serial(axial: str) -> xr.Dataset:
    """The same run in this process, in series."""
    cfg = rollerdyn.parse_config(changed_b1({"operating.axial_load": axial}, SHORT_DATA))
    return rollerdyn.simulate(cfg)


@pytest.fixture(scope="module")
def swept(tmp_path_factory):
    out = tmp_path_factory.mktemp("sweep")
    calls = []
    frame = rollerdyn.sweep(
        SHORT_DATA,
        {"operating.axial_load": AXIAL},
        out,
        workers=2,
        progress=lambda done, total, row: calls.append((done, total, row)),
    )
    return out, frame, calls


# --------------------------------------------------------------------------- the grid


def test_set_values_are_read_as_in_toml():
    assert parse_set("operating.axial_load=0 N, 500 N") == ("operating.axial_load", AXIAL)
    assert parse_set("materials.roller.poisson_ratio=0.29,0.3")[1] == [0.29, 0.3]
    assert parse_set("solver.pruning=true,false")[1] == [True, False]
    assert parse_set("solver.detector=gradient")[1] == ["gradient"]
    assert toml_value('"17"') == "17" and toml_value("17") == 17
    path, values = parse_set('operating.axial_load={table = [[0, "0 N"], [1, "5 N"]]},"9 N"')
    assert values == [{"table": [[0, "0 N"], [1, "5 N"]]}, "9 N"]
    with pytest.raises(SweepError, match="PATH=VALUE"):
        parse_set("operating.axial_load")
    # bytes of the command line that are not UTF-8 (surrogates in Python): no result file
    # could record the value, so it is refused, shown with the byte escaped
    with pytest.raises(SweepError, match=r"--set name=B\\xff: not UTF-8 text"):
        parse_set("name=B\udcff")
    # a line break would let TOML read a second key, which the value's reading drops:
    # refused, whatever follows it
    for option in ("solver.rtol=1e-5\nsolver.atol=3", 'name="a"\nb=1', "solver.rtol=1e-5\t"):
        with pytest.raises(SweepError, match="line break or control character"):
            parse_set(option)


def test_set_takes_ranges_a_b_n():
    """A:B:N as `statics` and `study map` take it: N values from A to B in their unit."""
    assert parse_set("operating.axial_load=0 N:1000 N:3")[1] == ["0 N", "500 N", "1000 N"]
    assert parse_set("operating.axial_load=0.5 N:1.5 N:3")[1] == ["0.5 N", "1.0 N", "1.5 N"]
    assert parse_set("geometry.roller.slices=10:20:3")[1] == [10, 15, 20]
    assert parse_set("solver.rtol=1e-6:1e-5:2")[1] == [1e-6, 1e-5]
    for bad, rule in (
        ("operating.axial_load=0 N:1 kN:3", "same unit"),
        ("operating.axial_load=0 N:1000 N:0", "N must be 2"),
        ("operating.axial_load=0 N:1000 N:100000", "N must be 2"),
        # a negative or fractional count is a count, not a unit (was "unknown unit")
        ("operating.axial_load=0 N:1000 N:-1", "N must be 2"),
        ("operating.axial_load=0 N:1000 N:2.5", "N must be 2"),
        ("operating.axial_load=0 N:1e999 N:2", "finite"),
    ):
        with pytest.raises(SweepError, match=rule):
            parse_set(bad)


def test_grid_is_the_cartesian_product_validated_up_front():
    grid = build_grid(
        SHORT_DATA,
        {"operating.axial_load": AXIAL, "materials.roller.poisson_ratio": [0.29, 0.3, 0.31]},
    )
    assert len(grid) == 6 and [p.run for p in grid] == list(range(6))
    assert grid[4].values == {
        "operating.axial_load": "500 N",
        "materials.roller.poisson_ratio": 0.3,
    }
    assert grid[4].si_values == {
        "operating.axial_load": 500.0,
        "materials.roller.poisson_ratio": 0.3,
    }
    assert grid[4].file == "run_0004.nc"
    with pytest.raises(SweepError) as err:
        build_grid(SHORT_DATA, {"operating.axial_load": ["500 N", 0, "3 mm"]})
    text = str(err.value)
    assert "2 of 3 grid points fail" in text and "no run was started" in text
    assert "operating.axial_load: 0 — a bare number is ambiguous" in text
    assert 'operating.axial_load: "3 mm" — expected a force' in text


# --------------------------------------------------------------------------- runs on Dask


def test_sweep_on_two_workers_equals_the_runs_in_series(swept):
    out, frame, calls = swept
    assert list(frame["run"]) == [0, 1]
    assert list(frame["operating.axial_load"]) == AXIAL
    assert list(frame["operating.axial_load [N]"]) == [0.0, 500.0]
    assert set(SUMMARY_COLUMNS) <= set(frame.columns)
    assert list(frame["status"]) == ["completed", "completed"]
    assert list(frame["note"]) == ["", ""]  # neither crawled
    assert list(frame["file"]) == ["run_0000.nc", "run_0001.nc"]
    for i, axial in enumerate(AXIAL):
        ref = serial(axial)
        with xr.open_dataset(out / f"run_{i:04d}.nc", engine="h5netcdf") as opened:
            got = opened.load()
        assert got.attrs["final_time_s"] == ref.attrs["final_time_s"] == pytest.approx(3e-3)
        for name in (
            "time",
            "frictional_torque",
            "position",
            "flange_normal_force",
            "inner_normal_force",
            "srr_inner",
            "final_state",
        ):
            np.testing.assert_array_equal(got[name].values, ref[name].values, err_msg=name)
        assert got.attrs["stats_steps"] == ref.attrs["stats_steps"]
        expected = summarize(ref)
        for column, value in expected.items():
            assert frame[column][i] == value or (math.isnan(value) and math.isnan(frame[column][i]))
        # the summary's definitions, checked directly
        t = ref.time.values
        last = t >= 0.8 * t[-1]
        assert expected["mean_frictional_torque [N*m]"] == float(
            ref.frictional_torque.values[last].mean()
        )
        race = max(float(ref.inner_normal_force.max()), float(ref.outer_normal_force.max()))
        assert expected["max_race_load [N]"] == race > 0
        assert expected["max_flange_normal_force [N]"] == float(ref.flange_normal_force.max())
        # this sweep's ring never turns: the slide-to-roll ratio has no meaning yet
        assert float(ref.ring_speed.max()) == 0.0
        assert math.isnan(expected["max_abs_srr_inner [1]"])
    # progress: once at submission, then once per finished run
    assert calls[0] == (0, 2, None)
    assert [c[0] for c in calls[1:]] == [1, 2] and all(c[1] == 2 for c in calls)
    # the Parquet file holds the same table
    pd.testing.assert_frame_equal(pd.read_parquet(out / "summary.parquet"), frame)


def test_a_worker_killed_mid_run_loses_no_run(tmp_path):
    """Issue 6, item 5: a worker process killed (SIGKILL) while it runs a sweep's task does
    not lose the sweep: the run is done again elsewhere, the summary has every run once,
    and the values and files equal the runs in series."""
    import os
    import signal
    import threading
    import time

    from distributed import Client, LocalCluster

    killed: list[tuple[str, list]] = []
    stop = threading.Event()
    with (
        LocalCluster(
            n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
        ) as cluster,
        Client(cluster) as client,
    ):
        pids = client.run(os.getpid)  # worker address -> process id, before any run

        def kill_a_busy_worker() -> None:
            # The scheduler knows which worker runs what; a worker busy in the Rust core
            # may not answer, so its pid was asked for up front.
            while not stop.is_set() and not killed:
                busy = {w: keys for w, keys in client.processing().items() if keys}
                if busy:
                    worker = sorted(busy)[0]
                    time.sleep(0.3)  # well into the run (parse, simulate, write)
                    if client.processing().get(worker):
                        os.kill(pids[worker], signal.SIGKILL)
                        killed.append((worker, list(busy[worker])))
                        return
                time.sleep(0.01)

        killer = threading.Thread(target=kill_a_busy_worker)
        killer.start()
        try:
            frame = rollerdyn.sweep(
                SHORT_DATA, {"operating.axial_load": AXIAL}, tmp_path, scheduler=client
            )
        finally:
            stop.set()
            killer.join()
    assert killed, "no worker was killed while it ran a task"
    assert list(frame["run"]) == [0, 1] and frame["run"].is_unique
    assert list(frame["status"]) == ["completed", "completed"], list(frame["error"])
    assert list(frame["file"]) == ["run_0000.nc", "run_0001.nc"]
    # no partial file of the killed attempt is left; the summary and its figure are there
    assert sorted(f.name for f in tmp_path.iterdir()) == [
        "run_0000.nc",
        "run_0001.nc",
        "summary.parquet",
        "summary.png",
        "summary.svg",
    ]
    for i, axial in enumerate(AXIAL):
        ref = serial(axial)
        for column, value in summarize(ref).items():
            assert frame[column][i] == value or (math.isnan(value) and math.isnan(frame[column][i]))
        with xr.open_dataset(tmp_path / f"run_{i:04d}.nc", engine="h5netcdf") as opened:
            got = opened.load()
        for name in ("time", "frictional_torque", "position", "final_state"):
            np.testing.assert_array_equal(got[name].values, ref[name].values, err_msg=name)
    pd.testing.assert_frame_equal(pd.read_parquet(tmp_path / "summary.parquet"), frame)


def test_a_run_writes_its_file_atomically(tmp_path, monkeypatch):
    """run_one writes under a temporary name and renames: a write that dies half way leaves
    no run file (and no temporary one); a second execution of the run replaces the first."""
    import rollerdyn.simulation as simulation

    written = serial("0 N").isel(time=slice(0, 3))
    monkeypatch.setattr(simulation, "simulate", lambda cfg, **kw: written)
    real_write = simulation.write

    def dying_write(ds, path):
        Path(path).write_bytes(b"half a file")
        raise OSError("disk gone")

    monkeypatch.setattr(simulation, "write", dying_write)
    result = run_one(SHORT_DATA, False, str(tmp_path), "run_0003.nc")
    assert result["status"] == "failed" and "disk gone" in result["error"]
    assert result["file"] == "" and list(tmp_path.iterdir()) == []
    monkeypatch.setattr(simulation, "write", real_write)
    for _ in range(2):  # a retry after a lost worker runs it again: one complete file
        result = run_one(SHORT_DATA, False, str(tmp_path), "run_0003.nc")
        assert result["status"] == "completed" and result["file"] == "run_0003.nc"
    assert [f.name for f in tmp_path.iterdir()] == ["run_0003.nc"]
    with xr.open_dataset(tmp_path / "run_0003.nc", engine="h5netcdf") as opened:
        np.testing.assert_array_equal(opened["time"].values, written["time"].values)


def test_a_failed_run_keeps_its_partial_file_and_its_error(tmp_path, monkeypatch):
    partial = serial("0 N").isel(time=slice(0, 3))

    def failing(cfg, t_end=None, detector=None, progress=None, resume=None, threads=None, **kw):
        raise SimulationError("step size too small at t = 0.5 ms", partial)

    monkeypatch.setattr("rollerdyn.simulation.simulate", failing)
    result = run_one(SHORT_DATA, False, str(tmp_path), "run_0007.nc")
    assert result["status"] == "failed" and "step size too small" in result["error"]
    assert result["file"] == "run_0007.nc" and (tmp_path / "run_0007.nc").is_file()
    assert result["steps"] == partial.attrs["stats_steps"]


def test_a_run_the_point_law_refuses_runs_when_the_sweep_is_forced(tmp_path, monkeypatch):
    """A grid point the point law's load check refuses (B1 without radial load at 100 N
    axially: its most loaded roller end on its end face, docs/dynamics.md, "The whole B1
    run") is a failed run with the refusal as its error and no file; `force` (`sweep
    --force`) hands `force=True` to the run, which then skips the check as `rollerdyn run
    --force` does (that run itself: tests/test_oil_and_threads.py). Standing still with the
    load applied over 1 ms, as here, the forced run's steps collapse at t = 1.5 ms
    (measured 2026-11-30, 37 s): the refusal is right for this one."""
    data = changed_b1({"operating.radial_load": "0 N", "operating.axial_load": "100 N"}, SHORT_DATA)
    refused = run_one(data, False, str(tmp_path), "run_0000.nc")
    assert refused["status"] == "failed" and "lies on its end face" in refused["error"]
    assert refused["file"] == "" and refused["steps"] == 0
    calls = []
    written = serial("0 N")

    def recorded(cfg, **kw):
        calls.append(kw)
        return written

    monkeypatch.setattr("rollerdyn.simulation.simulate", recorded)
    forced = run_one(data, False, str(tmp_path), "run_0001.nc", force=True)
    assert forced["status"] == "completed" and calls[-1]["force"] is True
    run_one(data, False, str(tmp_path), "run_0002.nc")
    assert calls[-1]["force"] is False


# --------------------------------------------------------------------------- command line


def test_cli_bad_set_value_is_exit_2_naming_path_and_value(tmp_path):
    result = RUNNER.invoke(
        app,
        ["sweep", str(B1), "--set", "operating.axial_load=0,250", "-o", str(tmp_path / "s")],
    )
    assert result.exit_code == 2, result.output
    assert "operating.axial_load: 0 — a bare number is ambiguous (no unit)" in result.output
    assert "--set operating.axial_load" in result.output and "250" in result.output
    assert "Traceback" not in result.output
    assert not (tmp_path / "s").exists()  # nothing started
    bad = RUNNER.invoke(app, ["sweep", str(B1), "--set", "operating.axial_lod=5 N"])
    assert bad.exit_code == 2 and "did you mean 'axial_load'" in bad.output


def test_cli_sweep_writes_the_summary(tmp_path):
    out = tmp_path / "sweep"
    result = RUNNER.invoke(
        app,
        [
            "sweep",
            str(B1),
            "--set",
            "operating.load_ramp.end=1 ms",
            "--set",
            "operating.axial_load=500 N",
            "--t-end",
            "0.001",
            "--workers",
            "1",
            "-o",
            str(out),
        ],
    )
    assert result.exit_code == 0, result.output
    assert "1 completed, 0 failed" in result.output and "summary.parquet" in result.output
    frame = pd.read_parquet(out / "summary.parquet")
    assert list(frame["operating.axial_load"]) == ["500 N"]
    assert list(frame["operating.load_ramp.end [s]"]) == [0.001]
    assert frame["status"][0] == "completed" and frame["final_time [s]"][0] == 0.001
    assert (out / "run_0000.nc").is_file()
    assert not (out / "summary.png").exists()  # one value per path: no line to draw


def test_the_summary_figure_draws_over_the_path_with_the_most_values(tmp_path):
    """The figure's x axis is the numeric path with the most values (here the axial load,
    3, against the radial load's 2; the detector is text), one line per combination of the
    others; a failed run is a cross at its partial numbers; without a numeric path of two
    values there is no figure."""
    from rollerdyn.sweep_figures import numeric_axis, write_summary_figure

    rows = []
    for radial in (1000.0, 5000.0):
        for detector in ("semi-analytical", "gradient"):
            for axial in (0.0, 500.0, 1000.0):
                rows.append(
                    {
                        "operating.radial_load": f"{radial:g} N",
                        "operating.radial_load [N]": radial,
                        "solver.detector": detector,
                        "operating.axial_load": f"{axial:g} N",
                        "operating.axial_load [N]": axial,
                        "status": "failed" if axial == 1000.0 and radial == 5000.0 else "completed",
                        "mean_frictional_torque [N*m]": 3e-4 * axial + 1e-6 * radial,
                        "max_race_load [N]": 0.3 * radial,
                        "max_flange_normal_force [N]": 0.14 * axial,
                        "max_abs_srr_inner [1]": math.nan,
                    }
                )
    frame = pd.DataFrame(rows)
    paths = ["operating.radial_load", "solver.detector", "operating.axial_load"]
    assert numeric_axis(frame, paths) == "operating.axial_load [N]"
    written = write_summary_figure(frame, paths, tmp_path, "b1.toml")
    assert [f.name for f in written] == ["summary.png", "summary.svg"]
    svg = (tmp_path / "summary.svg").read_text()
    # four lines (2 radial loads x 2 detectors), labelled, and the failed runs' crosses
    assert "operating.radial_load = 5000 N, solver.detector = gradient" in svg
    assert "sweep over operating.axial_load (x: failed run, its partial numbers)" in svg
    one = frame[frame["operating.axial_load [N]"] == 0.0]
    assert numeric_axis(one, paths) == "operating.radial_load [N]"
    assert numeric_axis(one[one["operating.radial_load [N]"] == 1000.0], paths) is None
    assert write_summary_figure(frame.iloc[:1], paths, tmp_path / "none", "b1.toml") == []


def test_cli_sweep_help_explains_units_and_defaults():
    result = RUNNER.invoke(app, ["sweep", "--help"])
    assert result.exit_code == 0
    for text in ("--set", "unit", "--workers", "--scheduler", "N*m", "summary.parquet"):
        assert text in result.output


def test_ctrl_c_keeps_the_summary_of_the_finished_runs(tmp_path):
    # Ctrl-C while runs are out (here raised by the progress report of the first finished
    # run, as the main thread would get it): summary.parquet lists that run as finished,
    # a run that finished while the worker stopped (up to 4 s; these runs take about one)
    # as finished from its file, and the others as interrupted, without a file; the
    # interrupt still ends the sweep.
    first: list[int] = []

    def interrupt(done, total, row):
        if row is not None:
            first.append(row["run"])
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        rollerdyn.sweep(
            SHORT_DATA,
            {"operating.axial_load": ["0 N", "500 N", "1000 N"]},
            tmp_path,
            workers=1,
            progress=interrupt,
        )
    frame = pd.read_parquet(tmp_path / "summary.parquet")
    assert list(frame["run"]) == [0, 1, 2]
    assert frame["status"].iloc[first[0]] == "completed"
    finished = frame[frame["status"] == "completed"]
    assert all((tmp_path / f).is_file() for f in finished["file"])
    assert finished["final_time [s]"].notna().all()
    rest = frame[frame["status"] != "completed"]
    assert set(rest["status"]) <= {"interrupted"}
    assert (rest["file"] == "").all() and rest["error"].str.contains("Ctrl-C").all()
    assert {p.name for p in tmp_path.glob("run_*.nc")} == set(finished["file"])


def _sweep_with_runs_out(folder: Path):
    """`rollerdyn sweep` of three runs of 0.2 s on two workers into ``folder``, in its own
    session, 2 s after its runs are out on the workers: the process and its lines so far."""
    import subprocess
    import sys
    import time

    command = Path(sys.executable).parent / "rollerdyn"
    args = [str(command), "sweep", str(B1), "--set", "operating.axial_load=500 N,1000 N,1500 N"]
    args += ["--t-end", "0.2 s", "--workers", "2", "-o", str(folder)]
    proc = subprocess.Popen(
        args, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, start_new_session=True
    )
    lines = []
    for line in proc.stdout:  # until the runs are out on the workers
        lines.append(line)
        if "submitted" in line:
            break
    time.sleep(2.0)
    return proc, lines


@pytest.mark.parametrize("presses", [1, 2])
def test_ctrl_c_in_the_terminal_stops_the_sweep_with_one_line(tmp_path, presses):
    # A terminal's Ctrl-C reaches the whole process group, the Dask workers too: the
    # workers ignore it (the command closes them), so the output is the command's one line,
    # no worker's KeyboardInterrupt traceback, no Dask message, and no "Exception ignored
    # in Client.__del__" of a client xarray opened in a worker. The summary is written
    # after the workers have stopped, also when Ctrl-C is pressed again meanwhile: it lists
    # each run with its file or as interrupted without one, and no partial file is left.
    # The closing takes about 5 s (Dask kills a busy worker after 4 s); 30 s allows for
    # a loaded machine.
    import os
    import signal
    import time

    proc, lines = _sweep_with_runs_out(tmp_path / "sw")
    os.killpg(proc.pid, signal.SIGINT)
    sent = time.monotonic()
    if presses == 2:
        time.sleep(0.5)
        os.killpg(proc.pid, signal.SIGINT)
    out, _ = proc.communicate(timeout=60)
    out = "".join(lines) + out
    assert time.monotonic() - sent < 30.0, out
    assert proc.returncode == 130, out
    for noise in ("Traceback", "WARNING", "Exception ignored"):
        assert noise not in out, out
    last = out.strip().splitlines()[-1]  # naming what was kept and how to go on
    assert last.startswith("rollerdyn sweep: interrupted; ") and "--resume" in last, out
    folder = tmp_path / "sw"
    frame = pd.read_parquet(folder / "summary.parquet")
    assert set(frame["status"]) <= {"interrupted", "completed"}, frame
    for status, file in zip(frame["status"], frame["file"], strict=True):
        assert (status == "completed") == (file != ""), frame
    listed = {f for f in frame["file"] if f}
    on_disk = {p.name for p in folder.glob("run_*.nc")}
    assert on_disk == listed, (on_disk, listed)
    assert not list(folder.glob(".run_*")), list(folder.iterdir())


def test_sigterm_stops_the_sweep_as_ctrl_c_does(tmp_path):
    # SIGTERM to the command alone (as `kill`, `timeout` or a batch system send it; the
    # workers are separate processes and get nothing): the command closes the workers and
    # writes the summary as after Ctrl-C, ends with one line naming it, exit status 143.
    import os
    import signal

    proc, lines = _sweep_with_runs_out(tmp_path / "sw")
    os.kill(proc.pid, signal.SIGTERM)
    out, _ = proc.communicate(timeout=60)
    out = "".join(lines) + out
    assert proc.returncode == 143, out
    for noise in ("Traceback", "WARNING", "Exception ignored"):
        assert noise not in out, out
    assert "terminated (SIGTERM)" in out.strip().splitlines()[-1], out
    frame = pd.read_parquet(tmp_path / "sw" / "summary.parquet")
    assert set(frame["status"]) <= {"interrupted", "completed"}, frame
    assert (frame["status"] == "interrupted").any(), frame


def test_a_sweep_removes_what_an_earlier_sweep_wrote(tmp_path):
    # An earlier, larger grid's run_0001.nc and run_0002.nc and its figure must not stay
    # beside the new sweep's summary of one run (which draws no figure: one value). They
    # are removed with overwrite=True only, and only as a sweep writes them (a result the
    # summary lists or that a sweep wrote under its name, the summary's columns, a figure
    # of matplotlib's beside that summary; tests/test_folders_refuse_foreign_files.py
    # refuses the others).
    import h5py

    for name in ("run_0000.nc", "run_0001.nc", "run_0002.nc"):
        with h5py.File(tmp_path / name, "w") as f:
            f.attrs.update(final_time_s=0.001, rollerdyn_version=rollerdyn.__version__)
            if name != "run_0000.nc":  # not in the summary: stamped as a sweep stamps them
                f.attrs["sweep_file"] = name
    for name in ("summary.png", "summary.svg"):
        (tmp_path / name).write_text("<!-- Created with matplotlib -->")
    earlier = {"run": [0], "status": ["completed"], "error": [""], "file": ["run_0000.nc"]}
    pd.DataFrame(earlier).to_parquet(tmp_path / "summary.parquet")
    frame = rollerdyn.sweep(
        SHORT_DATA, {"operating.axial_load": ["500 N"]}, tmp_path, workers=1, overwrite=True
    )
    assert list(frame["status"]) == ["completed"]
    assert [p.name for p in tmp_path.glob("run_*.nc")] == ["run_0000.nc"]
    assert not (tmp_path / "summary.png").exists() and not (tmp_path / "summary.svg").exists()


def test_overwrite_refuses_a_result_no_sweep_wrote_under_its_name(tmp_path):
    # the adversarial review: a result of `rollerdyn run` copied in as run_0009.nc was
    # deleted by the next sweep's --overwrite (only "is a rollerdyn result" was asked);
    # now a run file must be listed by the summary or stamped by a sweep with its name
    import shutil

    rollerdyn.sweep(SHORT_DATA, {"operating.axial_load": ["0 N", "5 N"]}, tmp_path, workers=1)
    shutil.copy(tmp_path / "run_0000.nc", tmp_path / "run_0009.nc")  # renamed: not its own
    before = sorted(p.name for p in tmp_path.iterdir())
    with pytest.raises(SweepError, match="run_0009.nc is not a file an earlier sweep wrote"):
        rollerdyn.sweep(
            SHORT_DATA, {"operating.axial_load": ["0 N"]}, tmp_path, workers=1, overwrite=True
        )
    assert sorted(p.name for p in tmp_path.iterdir()) == before
    (tmp_path / "run_0009.nc").unlink()  # the sweep's own files, listed and stamped, go
    rollerdyn.sweep(
        SHORT_DATA, {"operating.axial_load": ["0 N"]}, tmp_path, workers=1, overwrite=True
    )
    assert [p.name for p in tmp_path.glob("run_*.nc")] == ["run_0000.nc"]


def test_a_sweep_runs_from_a_thread_other_than_the_main_one(tmp_path):
    # The local cluster's workers are spawned with Ctrl-C ignored, which Python can set
    # only in the main thread: from another thread (a notebook's or an application's
    # worker thread) the sweep runs as it is, and the main thread's handler stays as it was.
    import signal
    import threading

    before = signal.getsignal(signal.SIGINT)
    outcome: list = []

    def work():
        try:
            frame = rollerdyn.sweep(
                SHORT_DATA, {"operating.axial_load": ["0 N"]}, tmp_path, workers=1
            )
            outcome.append(list(frame["status"]))
        except Exception as err:  # reported below, with its type
            outcome.append(err)

    thread = threading.Thread(target=work)
    thread.start()
    thread.join(timeout=300)
    assert outcome == [["completed"]], outcome
    assert signal.getsignal(signal.SIGINT) is before


def test_the_summary_prints_a_runs_note_below_the_table(tmp_path, capsys):
    """A run that crawled (its result's crawl_note, the summary's note column) is named
    below the table with its note, as a failed run is with its error."""
    import pandas as pd

    from rollerdyn.cli.sweep import _print_summary

    row = {"run": 0, "status": "completed", "error": "", "wall [s]": 1.0, "file": "r.nc"}
    row |= {"final_time [s]": 0.1, "mean_frictional_torque [N*m]": 0.3, "steps": 9}
    row |= {"max_race_load [N]": 1.0, "max_flange_normal_force [N]": 1.0}
    row |= {"max_abs_srr_inner [1]": 0.1, "note": "the run crawled: from t = 0.05 s ..."}
    failed = _print_summary(pd.DataFrame([row]), tmp_path / "b1.toml", tmp_path, [])
    out = " ".join(capsys.readouterr().out.split())
    assert failed == 0 and "run 0: the run crawled: from t = 0.05 s" in out


def test_sigterm_while_the_summary_is_written_is_taken_after_it():
    # the command's SIGTERM handler raises KeyboardInterrupt; raised while summary.parquet
    # is written, it would leave half a file: within the block it is only recorded, and
    # its handler runs once the block is done
    import os
    import signal

    from rollerdyn.sweep import _sigterm_deferred

    calls: list[int] = []
    previous = signal.signal(signal.SIGTERM, lambda signum, _: calls.append(signum))
    try:
        with _sigterm_deferred():
            os.kill(os.getpid(), signal.SIGTERM)
            assert calls == []  # the summary would be written here
        assert calls == [signal.SIGTERM]
    finally:
        signal.signal(signal.SIGTERM, previous)


def test_dask_logs_are_held_back_while_the_cluster_closes(caplog):
    # A sweep stopped by SIGTERM to its process group printed Dask's "Batched Comm Closed"
    # (INFO, from the logger distributed.batched) with a CommClosedError traceback in 2 of
    # 11 tries, logged after the cluster had restored its own silenced handlers; with the
    # closing inside _dask_logs_silenced, 8 of 8 such stops printed only the one line.
    import logging

    from rollerdyn.sweep import _dask_logs_silenced

    dask_logger = logging.getLogger("distributed")
    client = logging.getLogger("distributed.client")  # a level of its own (a review)
    before = dask_logger.level
    client.setLevel(logging.WARNING)
    with caplog.at_level(logging.DEBUG):
        with _dask_logs_silenced():
            logging.getLogger("distributed.batched").info("Batched Comm Closed")
            logging.getLogger("distributed.worker").error("a worker's error")
            client.warning("a client's warning")
        assert caplog.records == []
        logging.getLogger("distributed.batched").critical("after the block")
    assert [r.getMessage() for r in caplog.records] == ["after the block"]
    assert dask_logger.level == before and client.level == logging.WARNING


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"progress": 5}, "progress = 5: must be a function"),
        ({"force": "yes"}, "force = 'yes': must be True or False"),
        ({"workers": "2"}, "workers = '2': must be a whole number"),
        ({"workers": 1.5}, "workers = 1.5: must be a whole number"),
        ({"t_end": "abc"}, "t_end = 'abc': must be a time"),
        ({"retries": "x"}, "retries = 'x': must be a whole number"),
        ({"workers": 100_000}, "workers = 100000: at most [0-9]+ on this machine"),
    ],
)
def test_bad_arguments_are_refused_before_an_earlier_sweep_is_touched(tmp_path, kwargs, match):
    """Also a worker count past 4 per core (100 000 filled the memory for minutes, deaf to
    Ctrl-C) and a grid of more than 10 000 points (10^8 was built silently)."""
    # a progress of 5 started the cluster, removed the earlier sweep's files and then
    # failed with "TypeError: 'int' object is not callable"
    earlier = ["run_0000.nc", "run_0001.nc", "summary.parquet"]
    for name in earlier:
        (tmp_path / name).write_text("an earlier sweep's")
    with pytest.raises(SweepError, match=match):
        rollerdyn.sweep(SHORT_DATA, {"operating.axial_load": ["0 N"]}, tmp_path, **kwargs)
    assert sorted(p.name for p in tmp_path.iterdir()) == earlier
    a_file = tmp_path / "run_0000.nc"
    with pytest.raises(SweepError, match="is a file, not a folder"):
        rollerdyn.sweep(SHORT_DATA, {"operating.axial_load": ["0 N"]}, a_file)
    huge = {"operating.axial_load": ["0 N"] * 200, "operating.radial_load": ["1 kN"] * 200}
    with pytest.raises(SweepError, match="200 x 200 = 40000 grid points; a sweep has at most"):
        rollerdyn.sweep(SHORT_DATA, huge, tmp_path)
    assert sorted(p.name for p in tmp_path.iterdir()) == earlier


@pytest.mark.parametrize("delay", [1.0, 1.4])
def test_sigterm_while_the_sweep_starts_is_one_true_line(tmp_path, delay):
    # SIGTERM while the grid is built or the workers start claimed a summary that was never
    # written, and Dask's exit then printed an assertion about a worker still starting (or
    # an import it cut gave an ImportError); now one line that says what was kept (the
    # summary when it exists, else nothing), no traceback, exit status 143. Which moment
    # the signal meets depends on the machine; either line must be true.
    import signal
    import subprocess
    import sys
    import time

    command = Path(sys.executable).parent / "rollerdyn"
    out = tmp_path / "sw"
    args = [str(command), "sweep", str(B1), "--workers", "1", "--t-end", "0.005", "-o", str(out)]
    proc = subprocess.Popen(
        [*args, "--set", "operating.axial_load=0 N,500 N"],
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
    )
    time.sleep(delay)
    proc.send_signal(signal.SIGTERM)
    text, _ = proc.communicate(timeout=120)
    assert proc.returncode == 143, text
    for noise in ("Traceback", "Exception ignored", "Error"):
        assert noise not in text, text
    lines = [line for line in text.splitlines() if line.startswith("rollerdyn sweep:")]
    if lines:  # none if it came before Python's handler was installed
        assert len(lines) == 1, text
        claims = "summary.parquet lists" in lines[0]
        assert claims == (out / "summary.parquet").is_file(), text
