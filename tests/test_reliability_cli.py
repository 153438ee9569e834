"""Issue 16 on the command line: no hang, no traceback, nothing overwritten, output a person
can follow.

A. every output path is checked before any work (exit status 2, one line naming the option,
   the path and the rule); an existing result is replaced only with --overwrite (or
   continued in place with --resume); stale ``*.tmp<pid>`` files of dead writers go.
B. text from files and options is printed as it is (never as rich markup); a file that is
   no rollerdyn result, an unreachable scheduler or an unwritable folder: one line, exit 2.
C. progress as plain lines without a terminal; help wrapped once; --t-end with units;
   no max |SRR| before the ring turns.
D. run --force reaches simulate.

The runs are 1-2 ms of B1 (a few seconds each).
"""

from __future__ import annotations

import math
import os
import re
import socket
import subprocess
import sys
import threading
import time
from functools import partial
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from b1 import B1, ROOT, b1_file_with, load_b1
from typer.testing import CliRunner

from rollerdyn.cli import app

RUNNER = CliRunner()
ROLLERDYN = Path(sys.executable).with_name("rollerdyn")
COMMANDS = ("validate", "check", "bench", "run", "plot", "sweep", "report")


def invoke(*args: str, code: int, says: tuple[str, ...] = (), env=None):
    """Runs the CLI in-process; checks the exit status, that no exception escaped (no
    traceback), and that the output holds each of ``says``."""
    result = RUNNER.invoke(app, [str(a) for a in args], env=env)
    assert result.exit_code == code, result.output
    escaped = result.exception
    assert escaped is None or isinstance(escaped, SystemExit), repr(escaped)
    assert "Traceback" not in result.output
    for text in says:
        assert text in result.output, (text, result.output)
    return result


def one_line_saying(output: str, *texts: str) -> str:
    """The one line of ``output`` that holds every one of ``texts``."""
    lines = [line for line in output.splitlines() if all(t in line for t in texts)]
    assert lines, (texts, output)
    return lines[0]


@pytest.fixture(scope="module")
def result(tmp_path_factory) -> Path:
    """A real 2 ms result of B1 (the inner ring does not turn yet)."""
    from rollerdyn.simulation import simulate, write

    path = tmp_path_factory.mktemp("result") / "b1.nc"
    write(simulate(load_b1(), t_end=0.002), path)
    return path


# --------------------------------------------------------------------------- A: output paths


def test_run_refuses_bad_output_paths_before_any_work(tmp_path):
    """Missing folder, a file where a folder is needed, a folder where a file is, the
    configuration itself (even with --overwrite), a device: exit 2 at once, nothing
    written."""
    regular = tmp_path / "regular.txt"
    regular.write_text("x")
    config = tmp_path / "b1.toml"
    config.write_bytes(B1.read_bytes())
    cases = [
        (tmp_path / "missing" / "r.nc", "does not exist"),
        (regular / "r.nc", "is a file, not a folder"),  # also how a read-only place looks to root
        (tmp_path, "is a folder"),
        (config, "is the configuration file"),
        (Path("/dev/null"), "not a regular file"),
    ]
    for out, rule in cases:
        started = time.monotonic()
        res = invoke("run", config, "-o", out, "--t-end", "0.001", "--overwrite", code=2)
        line = one_line_saying(res.output, "-o", str(out), rule)
        assert line.strip() == res.output.strip()  # one line, nothing else
        assert time.monotonic() - started < 5.0
    assert config.read_bytes() == B1.read_bytes()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["b1.toml", "regular.txt"]


@pytest.mark.skipif(os.geteuid() == 0, reason="root may write anywhere")
def test_read_only_folder_is_refused(tmp_path):
    folder = tmp_path / "ro"
    folder.mkdir()
    folder.chmod(0o500)
    try:
        res = invoke("run", B1, "-o", folder / "r.nc", "--t-end", "0.001", code=2)
        assert "not writable" in res.output
    finally:
        folder.chmod(0o700)


def test_a_place_os_access_calls_read_only_is_refused(tmp_path, monkeypatch):
    """The same as root: os.access says the folder (or the file) is not writable."""
    import rollerdyn.paths as paths

    folder = tmp_path / "ro"
    folder.mkdir()
    (folder / "old.html").write_text("<html></html>")
    real = os.access

    def access(path, mode, denied=folder):
        return not (Path(path) == denied and mode & os.W_OK) and real(path, mode)

    monkeypatch.setattr(paths.os, "access", access)  # os.access everywhere
    sweep = ("sweep", B1, "--set", "operating.axial_load=0 N", "--t-end", "0.001")
    for args in (
        ("run", B1, "-o", folder / "r.nc", "--t-end", "0.001"),
        (*sweep, "-o", folder),
        (*sweep, "-o", folder / "new"),
        ("plot", "x.nc", "-o", folder),
        ("report", "x.nc", "-o", folder / "r.html"),
    ):
        res = invoke(*args, code=2)
        one_line_saying(res.output, "-o", str(folder), "not writable")
    monkeypatch.setattr(paths.os, "access", partial(access, denied=folder / "old.html"))
    res = invoke("report", "x.nc", "-o", folder / "old.html", code=2)
    one_line_saying(res.output, "old.html", "not writable")
    assert [p.name for p in folder.iterdir()] == ["old.html"]


def test_existing_result_is_kept_unless_overwrite_or_resume(tmp_path):
    """A second run onto the same file is refused (the file untouched); --overwrite
    replaces it; --resume with the same file continues it in place. Stale temporary
    files of a killed writer go, those of a live process stay."""
    out = tmp_path / "r.nc"
    invoke("run", B1, "-o", out, "--t-end", "0.001", code=0, says=("wrote",))
    before = out.read_bytes()
    res = invoke("run", B1, "-o", out, "--t-end", "0.002", code=2, says=("--overwrite",))
    one_line_saying(res.output, "-o", str(out), "exists")
    assert out.read_bytes() == before
    dead = subprocess.Popen([sys.executable, "-c", "pass"])
    dead.wait()
    stale = tmp_path / f"r.nc.tmp{dead.pid}"
    live = tmp_path / f"r.nc.tmp{os.getppid()}"  # a live process (not ours)
    stale.write_bytes(b"half")
    live.write_bytes(b"mine")
    res = invoke("run", B1, "-o", out, "--t-end", "0.002", "--overwrite", code=0)
    assert "removed" in res.output and not stale.exists() and live.exists()
    with xr.open_dataset(out, engine="h5netcdf") as ds:
        assert float(ds.attrs["final_time_s"]) == pytest.approx(0.002)
    invoke("run", B1, "-o", out, "--resume", out, "--t-end", "0.003", code=0)
    with xr.open_dataset(out, engine="h5netcdf") as ds:
        assert float(ds.attrs["final_time_s"]) == pytest.approx(0.003)


def test_stale_temporaries_are_those_of_dead_processes(tmp_path):
    from rollerdyn.paths import remove_stale_temporaries

    dead = subprocess.Popen([sys.executable, "-c", "pass"])
    dead.wait()
    out = tmp_path / "r[1].nc"  # glob characters in the name are taken literally
    names = [f"r[1].nc.tmp{dead.pid}", f"r[1].nc.tmp{os.getppid()}", "r[1].nc.tmpx", "r1.nc.tmp7"]
    for name in names:
        (tmp_path / name).write_text("x")
    removed = remove_stale_temporaries(out)
    assert removed == [(tmp_path / names[0], dead.pid)]
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(names[1:])


def test_plot_report_sweep_check_their_outputs_first(tmp_path, result):
    regular = tmp_path / "regular.txt"
    regular.write_text("x")
    earlier = tmp_path / "earlier"
    earlier.mkdir()
    (earlier / "summary.parquet").write_bytes(b"x")
    sweep = ("sweep", B1, "--set", "operating.axial_load=0 N", "--t-end", "0.001")
    for args, texts in (
        (("plot", result, "-o", regular), ("is a file, not a folder",)),
        (("plot", result, "-o", tmp_path / "a" / "b"), ("does not exist",)),
        (("report", result, "-o", tmp_path), ("is a folder",)),
        (("report", result, "-o", result), ("an input",)),
        (("report", result, "-o", tmp_path / "a" / "r.html"), ("does not exist",)),
        (("report", result, "-o", regular), ("exists", "only an earlier report")),
        (("report", result, "-o", B1), ("exists",)),
        ((*sweep, "-o", regular), ("is a file, not a folder",)),
        ((*sweep, "-o", regular / "s"), ("is a file, not a folder",)),
        ((*sweep, "-o", tmp_path / "a" / "s"), ("does not exist",)),
        ((*sweep, "-o", earlier), ("summary.parquet", "--overwrite")),
        # a folder whose permissions allow writing but which takes no file (/proc): found
        # before the work, not when its result is written (a run's was lost)
        (("run", B1, "-o", Path("/proc/r.nc"), "--t-end", "0.001"), ("cannot create a file",)),
        (("statics", B1, "-o", Path("/proc/s.nc")), ("cannot create a file",)),
        (("study", "map", B1, "--speed", "3000", "-o", Path("/proc/m")), ("cannot create",)),
    ):
        res = invoke(*args, code=2)
        one_line_saying(res.output, "-o", *texts)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["earlier", "regular.txt"]
    assert [p.name for p in earlier.iterdir()] == ["summary.parquet"]


def test_path_checks_library():
    from rollerdyn.paths import OutputPathError, check_output_dir, check_output_file

    with pytest.raises(OutputPathError, match="--out x/y.nc: the folder x does not exist"):
        check_output_file(Path("x/y.nc"), "--out")
    assert check_output_file(B1, overwrite=True) == B1
    with pytest.raises(OutputPathError, match="exists; see"):
        check_output_file(B1, hint="; see")
    with pytest.raises(OutputPathError, match="is the configuration file"):
        check_output_file(B1, inputs=[("the configuration file", B1)], overwrite=True)
    assert check_output_dir(ROOT / "new-folder") == ROOT / "new-folder"
    with pytest.raises(OutputPathError, match="holds earlier results"):
        check_output_dir(ROOT / "examples", results=("*.toml",), overwrite=False)


# --------------------------------------------------------------------------- B: no markup


def test_bracketed_config_values_and_names_print_as_they_are(tmp_path):
    """A value "5000 [/x] N" (rich's closing tag) and a bearing "B1 [/x] [mass]": no
    MarkupError, and the brackets are not swallowed; in a real process too."""
    bad = b1_file_with(tmp_path, 'radial_load = "5000 N"', 'radial_load = "5000 [/x] N"', count=1)
    for args in (("check", bad), ("run", bad, "-o", tmp_path / "r.nc")):
        res = invoke(*args, code=2)
        one_line_saying(res.output, "operating.radial_load", "5000 [/x] N")
    done = subprocess.run(
        [str(ROLLERDYN), "check", str(bad)], capture_output=True, text=True, timeout=60
    )
    assert done.returncode == 2 and "5000 [/x] N" in done.stdout + done.stderr
    assert "Traceback" not in done.stdout + done.stderr
    named = b1_file_with(tmp_path, 'name = "B1"', 'name = "B1 [/x] [mass]"', "named.toml", count=1)
    invoke("check", named, code=0, says=("B1 [/x] [mass]: derived quantities", "roller mass"))
    res = invoke("run", named, "-o", tmp_path / "n.nc", "--t-end", "0.001", code=0)
    one_line_saying(res.output, "B1 [/x] [mass]: t = 0.001")


def test_bracketed_file_names_print_as_they_are(tmp_path):
    for args in (
        ("plot", "nope[/x].nc"),
        ("report", "nope[/x].nc"),
        ("run", B1, "--resume", "nope[/x].nc", "-o", tmp_path / "r.nc"),
        ("bench", "model", "--state", "nope[/x].nc"),
    ):
        res = invoke(*args, code=2)
        one_line_saying(res.output, "nope[/x].nc", "not found")


def test_help_keeps_brackets_and_is_wrapped_once():
    """Every command's help at 80 columns: bracketed text as typed, no line longer than
    80, and no paragraph broken twice (a short line inside a paragraph)."""
    for command in COMMANDS:
        res = invoke(command, "--help", code=0, env={"COLUMNS": "80"})
        lines = res.output.splitlines()
        assert all(len(line) <= 80 for line in lines), command
        head = res.output.split("\nArguments:")[0].split("\nOptions:")[0]
        for paragraph in head.split("\n\n")[1:]:
            body = paragraph.splitlines()[:-1]
            assert all(len(line) >= 55 for line in body), (command, paragraph)
    helps = {c: invoke(c, "--help", code=0, env={"COLUMNS": "80"}).output for c in COMMANDS}
    assert "wall time [s]" in helps["bench"]
    assert "[arrays]" in helps["sweep"] and "[N*m]" in helps["sweep"]
    assert "--force" in helps["run"] and "--overwrite" in helps["run"]


# --------------------------------------------------------------------------- B: bad files


def _bad_files(tmp_path: Path, good: Path) -> dict[str, tuple[Path, str]]:
    """Files that are no rollerdyn result, and what the message says about each."""
    text = tmp_path / "text.nc"
    text.write_text("this is not netCDF\n")
    empty = tmp_path / "empty.nc"
    empty.write_bytes(b"")
    truncated = tmp_path / "truncated.nc"
    truncated.write_bytes(good.read_bytes()[:3000])
    foreign = tmp_path / "foreign.nc"
    xr.Dataset({"a": ("x", np.arange(3.0))}).to_netcdf(foreign, engine="h5netcdf")
    folder = tmp_path / "folder.nc"
    folder.mkdir()
    return {
        "text": (text, "cannot be read as netCDF"),
        "empty": (empty, "empty"),
        "truncated": (truncated, "truncated"),
        "foreign": (foreign, "missing"),
        "folder": (folder, "is a folder"),
    }


def test_files_that_are_no_result_give_one_line(tmp_path, result):
    out = tmp_path / "out"
    out.mkdir()
    for path, what in _bad_files(tmp_path, result).values():
        for args in (
            ("plot", path, "-o", out / "plots"),
            ("report", path, "-o", out / "r.html"),
            ("run", B1, "--resume", path, "-o", out / "r.nc", "--t-end", "0.003"),
            ("bench", "model", "--state", path),
        ):
            res = invoke(*args, code=2)
            line = one_line_saying(res.output, str(path), what)
            assert line.strip() == res.output.strip(), res.output
    assert list(out.iterdir()) == []


# --------------------------------------------------------------------------- B: sweeps


def _closed_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def test_sweep_unreachable_scheduler_is_one_line(tmp_path):
    out = tmp_path / "s"
    base = ("sweep", B1, "--set", "operating.axial_load=0 N", "--t-end", "0.001", "-o", out)
    for address, what in (
        (f"tcp://127.0.0.1:{_closed_port()}", "cannot connect"),
        ("tcp://nohost.invalid:8786", "cannot connect"),
        ("nonsense", "not a scheduler address"),
    ):
        started = time.monotonic()
        res = invoke(*base, "--scheduler", address, code=2)
        one_line_saying(res.output, "scheduler", address, what)
        assert time.monotonic() - started < 15.0
    assert not out.exists()


def test_a_server_that_never_answers_is_no_hang():
    """Dask's own handshake waits forever on a server that accepts and stays silent."""
    from rollerdyn.sweep import SweepError, _check_reachable

    server = socket.socket()
    server.bind(("127.0.0.1", 0))
    server.listen(4)
    held = []
    thread = threading.Thread(target=lambda: held.append(server.accept()), daemon=True)
    thread.start()
    started = time.monotonic()
    try:
        with pytest.raises(SweepError, match="no answer within 1 s"):
            _check_reachable(f"tcp://127.0.0.1:{server.getsockname()[1]}", 1.0)
    finally:
        server.close()
    assert time.monotonic() - started < 5.0


# --------------------------------------------------------------------------- C: output


def test_progress_is_plain_lines_without_a_terminal(tmp_path):
    res = invoke("run", B1, "-o", tmp_path / "r.nc", "--t-end", "0.002", code=0)
    assert "━" not in res.output  # no bar
    one_line_saying(res.output, "B1: t = 0.001 / 0.002 s (50 %)", "steps", "ms/s")
    one_line_saying(res.output, "B1: t = 0.002 / 0.002 s (100 %)")
    one_line_saying(res.output, "wrote", "to t = 0.002 s")


def test_t_end_takes_units_and_refuses_other_quantities(tmp_path):
    out = tmp_path / "r.nc"
    invoke("run", B1, "-o", out, "--t-end", "1.5 ms", code=0, says=("to t = 0.0015 s",))
    for bad, rule in (
        ("5 N", "got a force"),
        ("-1 ms", "at least 1 ns"),
        ("0", "at least 1 ns"),
        ("nan", "at least 1 ns"),
        ("fast", "at least 1 ns"),
        # below 1 ns the run's clock would not move: it looped without end, deaf to Ctrl-C
        ("1e-40", "at least 1 ns"),
    ):
        for args in (
            ("run", B1, "-o", tmp_path / "x.nc"),
            ("bench", "mbs"),
            ("sweep", B1, "--set", "operating.axial_load=0 N", "-o", tmp_path / "s"),
        ):
            res = invoke(*args, "--t-end", bad, code=2)
            one_line_saying(res.output, "--t-end", repr(bad), rule)
    res = invoke("run", B1, "-o", tmp_path / "x.nc", "--checkpoint-interval", "1 kg", code=2)
    one_line_saying(res.output, "--checkpoint-interval", "got a mass")
    res = invoke("run", B1, "-o", tmp_path / "x.nc", "--checkpoint-interval", "1e-30", code=2)
    one_line_saying(res.output, "--checkpoint-interval", "at least 1 ns")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["r.nc"]


def test_no_slide_to_roll_ratio_before_the_ring_turns(result):
    from rollerdyn.report import _fmt, summary
    from rollerdyn.sweep import summarize

    with xr.open_dataset(result, engine="h5netcdf") as opened:
        ds = opened.load()
    assert not np.any(ds.ring_speed.values)
    assert np.nanmax(np.abs(ds.srr_inner.values)) > 1.0  # what used to be reported
    assert math.isnan(summary(ds)["max_srr_inner"]) and _fmt("max_srr_inner", math.nan) == "n/a"
    assert math.isnan(summarize(ds)["max_abs_srr_inner [1]"])
    turning = ds.assign(ring_speed=ds.ring_speed.copy(data=[0.0, 0.0, 10.0]))
    last = float(np.nanmax(np.abs(ds.srr_inner.values[-1])))
    assert summary(turning)["max_srr_inner"] == last
    assert summarize(turning)["max_abs_srr_inner [1]"] == last


# --------------------------------------------------------------------------- D and writes


def test_force_reaches_simulate_and_a_failed_write_is_one_line(tmp_path, result, monkeypatch):
    import rollerdyn.simulation as simulation

    with xr.open_dataset(result, engine="h5netcdf") as opened:
        ds = opened.load()
    seen = []

    def fake(cfg, **kwargs):
        seen.append(kwargs.get("force", False))
        if not kwargs.get("force", False):
            raise ValueError("solver.dt_max = 1e-12 s: takes 1e9 steps; force the run (--force)")
        kwargs["checkpoint"](ds)
        return ds

    monkeypatch.setattr(simulation, "simulate", fake)
    res = invoke("run", B1, "-o", tmp_path / "a.nc", code=2)
    one_line_saying(res.output, "solver.dt_max", "--force")
    invoke("run", B1, "-o", tmp_path / "a.nc", "--force", code=0, says=("wrote",))
    assert seen == [False, True]

    def failing(ds, path, compress=True, replace=True):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(simulation, "write", failing)
    res = invoke("run", B1, "-o", tmp_path / "b.nc", "--force", code=1)
    line = one_line_saying(res.output, "-o", "could not write", "No space", "kept in")
    assert line.strip() == res.output.strip()
    assert not (tmp_path / "b.nc").exists()
    kept = Path(line.split("the result was kept in ")[1].strip())
    with xr.open_dataset(kept, engine="h5netcdf") as back:  # nothing computed is lost
        assert back.sizes == ds.sizes
    kept.unlink()


def test_no_markup_left_in_the_commands():
    """The commands print through Text or plain strings: no rich markup tag in their
    source, and no escape() (which would print its backslashes now)."""
    package = ROOT / "python" / "rollerdyn"
    commands = sorted(package.glob("cli/*.py")) + [
        package / f"{name}.py"
        for name in ("report", "report_figures", "sweep", "plots", "bench_cases")
    ]
    assert len(commands) > 5
    for path in commands:
        source = path.read_text(encoding="utf-8")
        name = path.relative_to(package)
        assert not re.search(r"\[/?(red|green|bold)\]", source), name
        assert not re.search(r"(?<![.\w])escape\(", source), name  # html.escape is fine


# ------------------------------------------------- E: an adversarial pass (2026-11-28)


def test_statics_outputs_are_checked_before_the_work(tmp_path):
    """-o and --plot naming one file would leave only the plot (the netCDF lost); a --plot
    extension matplotlib cannot write failed with a traceback after the whole analysis."""
    same = tmp_path / "st.png"
    res = invoke("statics", B1, "-o", same, "--plot", same, code=2)
    one_line_saying(res.output, "-o", "--plot", "the same file")
    for name, what in (("st.txt", ".txt is not an image format"), ("st", "no extension")):
        res = invoke("statics", B1, "--plot", tmp_path / name, code=2)
        one_line_saying(res.output, "--plot", what, ".png")
    assert not any(tmp_path.iterdir())


def test_statics_moments_take_a_torque_unit():
    """--set moment_z takes "0.1 N*m" (the help promises units) and refuses a force."""
    from rollerdyn.statics import parse_range

    assert parse_range("moment_z", "0.1 N*m") == [pytest.approx(0.1)]
    assert parse_range("moment_z", "0:10 N*m:3") == [0.0, 5.0, 10.0]
    assert parse_range("moment_y", "0.25") == [0.25]
    res = invoke("statics", B1, "--set", "moment_z=1 N", code=2)
    one_line_saying(res.output, "moment_z", "expected a torque", "got a force")
    res = invoke("statics", B1, "--set", "operating.radial_load=3000,,7000", code=2)
    one_line_saying(res.output, "an empty value")
    # a path given twice replaced its first values without a word (run and sweep refuse)
    twice = ("--set", "operating.radial_load=1000 N,5 kN", "--set", "operating.radial_load=2 kN")
    res = invoke("statics", B1, *twice, code=2)
    one_line_saying(res.output, "operating.radial_load", "given twice")
    # a prescribed misalignment holds the tilt a moment would act on: the moment was
    # silently ignored
    both = ("--set", "inner_ring.misalignment=0.03 deg", "--set", "moment_y=5 N*m")
    res = invoke("statics", B1, *both, code=2)
    one_line_saying(res.output, "moment_y", "misalignment", "act on nothing")
    from rollerdyn.statics import StaticsError, statics

    with pytest.raises(StaticsError, match="would act on nothing"):
        statics(B1, misalignment=5e-4, moment=(5.0, 0.0))


def test_bench_cases_refuse_t_end(tmp_path):
    """The cases run to their own ends; --t-end with --cases was ignored without a word."""
    res = invoke("bench", "mbs", "--cases", "axial-0N", "--t-end", "1 ms", "-o", tmp_path, code=2)
    one_line_saying(res.output, "--t-end", "--cases", "own end")


@pytest.mark.parametrize(
    ("args", "says"),
    [
        # a billion steps asked the core for 144 GB and aborted it with a Rust backtrace
        (["contact", "--steps", "1000000000"], ("--steps", "62830")),
        (["traction", "--repetitions", "2000000000"], ("--repetitions", "100000000")),
        # options of another target were ignored without a word
        (["traction", "--t-end", "5"], ("--t-end", "mbs", "traction")),
        (["statics", "--state", "x.nc"], ("--state", "model", "statics")),
        (["mbs", "--threads", "2"], ("--threads", "mbs --cases")),
        # a dt_max the configuration refuses passed the option's own check and failed
        # after the first run with a 66-line traceback
        (["mbs", "--t-end", "2 ms", "--sweep-dt-max", "5e-10"], ("--sweep-dt-max 5e-10", "1 ns")),
        # -o without the cases or the study, which alone write files, was ignored
        (["mbs", "--t-end", "2 ms"], ("-o applies to mbs --cases and mbs --sweep-dt-max",)),
    ],
)
def test_bench_options_out_of_range_or_of_another_target_are_refused(tmp_path, args, says):
    res = invoke("bench", *args, "-o", tmp_path / "rs", code=2) if "mbs" in args else None
    res = res or invoke("bench", *args, code=2)
    assert "Traceback" not in res.output
    for text in says:
        assert text in res.output, res.output
    assert not (tmp_path / "rs").exists()


def test_a_dt_max_given_twice_is_run_once():
    """A Δt_max given twice ran twice and then failed the table with "Index contains
    duplicate entries" after every run."""
    from rollerdyn.cli.bench import _dt_max_values

    assert _dt_max_values("1e-4,3e-5,1e-4") == [3e-5, 1e-4]


@pytest.mark.parametrize(
    "args", [["contact", "--steps", "60000"], ["traction", "--repetitions", "100000000"]]
)
def test_ctrl_c_stops_a_core_benchmark_at_once(args):
    """The core's timing loops ask for no signals: Ctrl-C waited until they ended (a
    million contact steps: 292 s after the Ctrl-C). They now run in a helper thread while
    the command waits: these take 15–20 s (contact) and about 7 s (traction); the command
    must end within 5 s of the Ctrl-C with the one line and status 130."""
    import signal

    # after 3 s the core call has started (Python's start takes about 1 s)
    status, out = _signalled_bench(args, signal.SIGINT, 3.0)
    assert status == 130, out
    assert out.strip().splitlines()[-1] == "rollerdyn: interrupted", out


def _signalled_bench(args: list[str], signum: int, delay: float) -> tuple[int, str]:
    """(exit status, output) of ``rollerdyn bench ARGS`` sent ``signum`` after ``delay``
    seconds, which must end it within 5 s."""
    command = Path(sys.executable).parent / "rollerdyn"
    proc = subprocess.Popen(
        [str(command), "bench", *args], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True
    )
    time.sleep(delay)
    proc.send_signal(signum)
    sent = time.monotonic()
    out, _ = proc.communicate(timeout=60)
    assert time.monotonic() - sent < 5.0, out
    return proc.returncode, out


@pytest.mark.parametrize("delay", [0.15, 3.0])
def test_sigterm_where_no_command_takes_it_is_one_line(delay):
    """SIGTERM ended a command without a SIGTERM handler of its own (here a core benchmark,
    about 7 s) by Python's default: no word, status -15 to the caller; and a sweep's start
    on a busy machine the same way (its test expects 143). Now one line and status 143,
    during the imports (0.15 s) as in the core call (3 s)."""
    import signal

    args = ["traction", "--repetitions", "100000000"]
    status, out = _signalled_bench(args, signal.SIGTERM, delay)
    assert status == 143, out
    assert out.strip().splitlines()[-1] == "rollerdyn: terminated", out


def test_cost_checks_cover_checkpoints_and_every_sweep_point(tmp_path):
    """A checkpoint interval of 1 ns crawled for 100 s before it stalled; a sweep point's
    result size was refused only inside the cluster, advising a --force sweep lacks."""
    res = invoke(
        "run",
        B1,
        "-o",
        tmp_path / "r.nc",
        "--t-end",
        "2 ms",
        "--checkpoint-interval",
        "1 ns",
        code=2,
    )
    one_line_saying(res.output, "solver.checkpoint_interval", "checkpoints", "longer interval")
    res = invoke(
        "sweep",
        B1,
        "--set",
        "solver.output_interval=1 ns",
        "-o",
        tmp_path / "sw",
        "--t-end",
        "1 ms",
        code=2,
    )
    line = one_line_saying(res.output, "solver.output_interval", "GB")
    assert "--force" not in line
    assert not (tmp_path / "sw").exists()


def test_map_grid_is_capped(tmp_path):
    """100 000 speeds validated silently for over a minute before any run."""
    res = invoke("study", "map", B1, "-o", tmp_path / "m", "--speed", "1000:3000:100000", code=2)
    one_line_saying(res.output, "--speed", "at most 10000")
    res = invoke(
        "study",
        "map",
        B1,
        "-o",
        tmp_path / "m",
        "--speed",
        "1000:3000:200",
        "--axial-load",
        "0:1000:100",
        code=2,
    )
    one_line_saying(res.output, "20000 grid points", "at most 10000")


def test_config_rules_match_the_core(tmp_path):
    """An opening angle of 15° passed `check` and failed every command after it (the core
    allows < 10°); a byte-order mark at the file's start was malformed TOML."""
    wide = b1_file_with(tmp_path, 'opening_angle = "0.11 deg"', 'opening_angle = "15 deg"')
    res = invoke("check", wide, code=2)
    one_line_saying(res.output, "geometry.flange.opening_angle", "< 10 deg")
    bom = tmp_path / "bom.toml"
    bom.write_bytes(b"\xef\xbb\xbf" + B1.read_bytes())
    invoke("check", bom, code=0)


def test_statics_result_is_named_as_such_by_plot(tmp_path):
    from rollerdyn.statics import statics

    path = tmp_path / "st.nc"
    statics(load_b1()).to_netcdf(path, engine="h5netcdf")
    for command in ("plot", "report"):
        res = invoke(command, path, "-o", tmp_path / f"out_{command}", code=2)
        one_line_saying(res.output, "quasi-static result", "rollerdyn run")


def test_resume_refuses_a_result_with_other_rollers(tmp_path, result):
    """A result cut to 5 of 17 rollers was continued and padded with NaN."""
    cut = tmp_path / "cut.nc"
    with xr.open_dataset(result, engine="h5netcdf") as ds:
        ds.load().isel(roller=slice(0, 5)).to_netcdf(cut, engine="h5netcdf")
    res = invoke("run", B1, "-o", cut, "--t-end", "3 ms", "--resume", cut, code=2)
    one_line_saying(res.output, "5 rollers", "17")


def test_resume_from_a_state_outside_the_bearing_fails_at_once(result):
    """A checkpoint state set to 1.0 throughout (the ring 1.7 m off centre) made the solver
    shrink its steps inside one attempt for ever, deaf to Ctrl-C; it is refused at the
    start, naming the body."""
    from rollerdyn.simulation import simulate

    with xr.open_dataset(result, engine="h5netcdf") as ds:
        tampered = ds.load()
    tampered["checkpoint_state"].values[:] = 1.0
    with pytest.raises(ValueError, match="inside the bearing: the inner ring left the bearing"):
        simulate(load_b1(), t_end=0.003, resume=tampered, threads=1)


def test_statics_says_when_the_races_are_pressed_past_iso_76():
    """B1 at 80 kN radially gave its whole table (10 GPa at the inner race, s_0 0.14)
    without a word, while `rollerdyn check` notes that the races cannot carry it (a
    review). The note names the static safety by stress below 1 (ISO 76's 4 GPa: 0.16 by
    the model's slices) and the pressure; a sweep counts such cases."""
    res = invoke("statics", B1, "--set", "operating.radial_load=80 kN", code=0)
    text = " ".join(res.output.split())
    assert "the races cannot carry this load" in text and "races 0.16 < 1" in text, text
    res = invoke("statics", B1, "--set", "operating.radial_load=5 kN,20 kN,80 kN", code=0)
    assert "2 cases past ISO 76's 4 GPa" in " ".join(res.output.split())
    res = invoke("statics", B1, code=0)
    assert "cannot carry" not in res.output
    # past at the flanges alone: their pressure named, not the races' (a review)
    import importlib

    from rollerdyn.cli.statics import _overload_text

    ds = importlib.import_module("rollerdyn.statics").statics(load_b1())
    ds["s0_flanges"] = 0.6
    text = _overload_text(ds)
    assert text.startswith("the flanges cannot carry this load") and "race pressure" not in text
    assert "largest flange pressure 1.95 GPa by Hertz's exact ellipse" in text


def test_a_mesh_run_too_fine_to_interrupt_is_refused_before_it_starts(tmp_path):
    """The mesh detector at 1024 x 256 facets (allowed by the configuration's bounds, for
    the detection study) ran for 12 minutes at full CPU before its first step, deaf to
    Ctrl-C and SIGTERM, and only kill -9 stopped it (a review). A run takes at most
    128 x 32 facets with it; --force still runs more."""
    from rollerdyn.simulation import MAX_MESH_FACETS, check_cost

    fine = ["--set", "solver.mesh_around=1024", "--set", "solver.mesh_along=256"]
    res = invoke("run", B1, "-o", tmp_path / "x.nc", "--detector", "mesh", *fine, code=2)
    one_line_saying(res.output, "solver.mesh_around x solver.mesh_along = 1024 x 256", "--force")
    assert not (tmp_path / "x.nc").exists()
    cfg = load_b1()
    assert MAX_MESH_FACETS == 128 * 32
    check_cost(cfg, 0.001, detector="mesh")  # the default 64 x 16
    fine_cfg = cfg.model_copy(
        update={"solver": cfg.solver.model_copy(update={"mesh_around": 256, "mesh_along": 32})}
    )
    with pytest.raises(ValueError, match="256 x 32"):
        check_cost(fine_cfg, 0.001, detector="mesh")
    check_cost(fine_cfg, 0.001)  # B1's own detector: no mesh
    res = invoke("check", B1, *fine, "--set", "solver.detector=mesh", code=0)
    assert "rollerdyn run refuses this configuration: solver.mesh_around" in " ".join(
        res.output.split()
    )


def test_check_names_a_start_that_run_refuses():
    """B1's ring misaligned by 0.5 deg: `check` passed it with a note on creeping, `run`
    refused it at once (the raceway overlaps the untilted rollers at rest; a review).
    `check` now says so, with the core's advice, the start from equilibrium, checked: at
    0.15 deg that start runs it (B1's doc comment), at 0.5 deg it finds none either."""
    res = invoke("check", B1, "--set", "inner_ring.misalignment=0.15 deg", code=0)
    text = " ".join(res.output.split())
    assert "rollerdyn run refuses this configuration: inner_ring.misalignment = 0.1500 deg" in text
    assert 'solver.start = "equilibrium"' in text and "none either" not in text
    res = invoke("check", B1, "--set", "inner_ring.misalignment=0.5 deg", code=0)
    text = " ".join(res.output.split())
    assert "overlap by 14.544 um" in text and "but that start finds none either" in text
    res = invoke("check", B1, code=0)
    assert "refuses" not in res.output


def test_a_run_goes_on_when_its_standard_output_is_closed(tmp_path):
    """`rollerdyn run ... | head -1`: rich ended the process (SystemExit 1) at the first
    progress line after the pipe's reader left, with no word on standard error and the
    result cut at 10 ms with the error "SystemExit: 1" (a review). The run now goes on
    without progress lines, says so once on standard error and writes its whole result."""
    import xarray as xr

    command = Path(sys.executable).parent / "rollerdyn"
    out = tmp_path / "p.nc"
    proc = subprocess.Popen(
        [str(command), "run", str(B1), "-o", str(out), "--t-end", "0.05"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    assert proc.stdout.readline()  # the first progress line, then the reader leaves
    proc.stdout.close()
    _, err = proc.communicate(timeout=120)
    assert proc.returncode == 0, err
    assert err.strip() == (
        "rollerdyn run: standard output closed; the run goes on without progress lines"
    )
    with xr.open_dataset(out) as ds:
        assert float(ds.time[-1]) == pytest.approx(0.05) and "error" not in ds.attrs


def test_run_and_check_take_a_text_with_colons_as_text():
    """--set on run and check read 'ratio 1:2:3' as a sweep's A:B:N and refused it with no
    field named (a review); they take one value, so it is text, and a range given there
    is refused by the field's own rule."""
    res = invoke("check", B1, "--set", "description=ratio 1:2:3", code=0)
    assert "A:B:N" not in res.output
    res = invoke("check", B1, "--set", "operating.radial_load=0 N:5000 N:1", code=2)
    one_line_saying(res.output, 'operating.radial_load: "0 N:5000 N:1"', "expected a force")


def test_dash_is_not_taken_for_a_result_file_name(tmp_path, monkeypatch):
    """`-o -` wrote a file named "-" in the current folder (a review)."""
    monkeypatch.chdir(tmp_path)
    res = invoke("run", B1, "-o", "-", "--t-end", "1 ms", code=2)
    one_line_saying(res.output, "-o -: '-' (standard output) is not taken for a file here")
    assert list(tmp_path.iterdir()) == []


def test_a_statics_sweep_shows_speeds_and_angles_as_given():
    """A sweep typed in rpm and degrees was shown in rad/s and rad (a review); the table
    shows rpm and degrees, the dataset keeps SI."""
    sets = ["--set", "operating.inner_ring_speed=1000 rpm,3000 rpm"]
    sets += ["--set", "roller_set_phase=0 deg,10 deg"]
    res = invoke("statics", B1, *sets, code=0)
    text = " ".join(res.output.split())
    assert "[rpm]" in text and "[deg]" in text and "[rad/s]" not in text, text
    assert "│ 3000 │ 10 │" in text, text
