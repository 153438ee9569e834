"""``rollerdyn run``: a dynamic simulation written to a netCDF file, with its progress
(a live bar on a terminal, else plain lines), checkpoints, --resume, and Ctrl-C or SIGTERM
stopping the run with everything computed so far written."""

from __future__ import annotations

import contextlib
import math
import signal
import sys
import time
from pathlib import Path
from typing import Annotated

import typer

from ..paths import check_output_file, remove_stale_temporaries
from .common import (
    SET_HELP,
    check_detector,
    checked,
    console,
    detector_help,
    error,
    load,
    plain,
    refuse,
    say,
    set_options,
    time_option,
)


def run(
    config: Annotated[Path, typer.Argument(help="Bearing configuration (TOML).", metavar="CONFIG")],
    output: Annotated[
        Path,
        typer.Option(
            "--output",
            "-o",
            help="Result file (netCDF, xarray/h5netcdf). Its folder must exist; an existing "
            "file is refused unless --overwrite is given or --resume names the same file.",
        ),
    ] = Path("result.nc"),
    overwrite: Annotated[
        bool,
        typer.Option("--overwrite", help="Replace the file -o names if it exists."),
    ] = False,
    t_end: Annotated[
        str | None,
        typer.Option(
            "--t-end",
            help="Simulated end time, with a unit as in the configuration (50 ms, 0.05 s) "
            "or a bare number of seconds (0.05). Default: the configuration's end time "
            "(speed ramp end + two roller-set revolutions, about 1.288 s for B1).",
            metavar="TIME",
        ),
    ] = None,
    detector: Annotated[
        str | None,
        typer.Option(
            "--detector",
            help=detector_help("the configuration"),
        ),
    ] = None,
    resume: Annotated[
        Path | None,
        typer.Option(
            "--resume",
            help="Continue an unfinished run (interrupted, killed, failed, or stopped by "
            "--t-end) from the last checkpoint saved in its result file; the output holds "
            "both parts and equals an uninterrupted run bit for bit. Same configuration and "
            "detector required. -o may name the same file (the way to continue a run in "
            "place).",
        ),
    ] = None,
    checkpoint_interval: Annotated[
        str | None,
        typer.Option(
            "--checkpoint-interval",
            help="Checkpoint interval in simulated time (not wall-clock time), with a unit "
            "(100 ms) or a bare number of seconds (0.1): the solver restarts every TIME "
            "and the result file is rewritten there (at most once per --save-interval of "
            "wall time); after kill -9 the run continues from the last checkpoint "
            "written. Overrides solver.checkpoint_interval of the configuration "
            "(default 100 ms). With --resume the default is the earlier run's interval, "
            "which a bit-for-bit continuation needs (another interval changes the result "
            "within the tolerances).",
            metavar="TIME",
        ),
    ] = None,
    save_interval: Annotated[
        str,
        typer.Option(
            "--save-interval",
            help="Least wall-clock time between two checkpoint writes of the result file, "
            "with a unit (10 s) or a bare number of seconds; 0 writes it at every "
            "checkpoint. The first checkpoint is always written. Each write costs about "
            "the same whatever the result's size (0.3-0.5 s for B1 on a 2-core machine), "
            "so writing all of B1's 13 checkpoints takes about a tenth of the run. After "
            "kill -9 at most this plus one checkpoint interval of work is lost.",
            metavar="TIME",
        ),
    ] = "10 s",
    threads: Annotated[
        int | None,
        typer.Option(
            "--threads",
            min=1,
            help="Threads that evaluate the contacts and the Jacobian's columns (default: all "
            "cores; never more than the cores this process may use; the gradient detector "
            "always uses one). The result does not depend on it, bit for bit.",
        ),
    ] = None,
    settings: Annotated[
        list[str] | None,
        typer.Option(
            "--set",
            help=SET_HELP
            + " The result records the changed configuration (its TOML text, headed by the "
            "file and the changes); --resume needs the same --set.",
        ),
    ] = None,
    force: Annotated[
        bool,
        typer.Option(
            "--force",
            help="Run even when the estimated result size or cost is far beyond a normal "
            "run (the refusal prints the estimate), or when the point end-flange law's load "
            "check refuses it (a roller end pressed onto its end face, or a load the point "
            "law has no equilibrium for: the run's steps "
            "creep or collapse).",
        ),
    ] = False,
) -> None:
    """Run the dynamic simulation and write its results to a netCDF file.

    Units: SI throughout the file (every variable has a 'units' attribute; time in s,
    forces in N, torques in N*m, angles in rad, speeds in rad/s). Outputs are saved every
    solver.output_interval by interpolation.

    Progress: on a terminal a bar shows simulated time, solver steps, speed (simulated
    time per wall second) and the time left; otherwise (a log, a pipe) one line is
    printed at every 10 % of the simulated time and at least every 10 s (between steps:
    the mesh detector's can take longer). A run whose steps
    average less than 1 µs of simulated time over 10 s of wall time (from 30 s on) gets one
    note naming its likely cause (recorded as the result's crawl_note).

    The output is checked before the run: its folder must exist and be writable, and an
    existing file is only replaced with --overwrite (or continued with --resume naming
    it). If the run fails or is interrupted (Ctrl-C), everything computed until then is
    written and the command exits with status 1 (130 after Ctrl-C, 143 after SIGTERM).
    The result file is also written at checkpoints (every --checkpoint-interval of
    simulated time, by default solver.checkpoint_interval, 100 ms; atomically; at most one
    every --save-interval of wall time, 10 s), so after kill -9 or a crash it holds the run
    up to the last checkpoint written, and --resume finishes the run. A file that another
    program writes under that name during the run is kept: the run's file then goes to
    NAME-2.nc, and the command says so. Bad input exits with status 2 before any work.
    """
    check_detector(detector)
    interval = time_option("--checkpoint-interval", checkpoint_interval)
    save_every = time_option("--save-interval", save_interval, zero=True) or 0.0  # has a default
    end = time_option("--t-end", t_end)
    changes = set_options(settings)
    cfg = load(config, changes)
    # after the input checks: a bad option or file is refused before xarray and the
    # simulation's other libraries load (about 0.6 s)
    from ..notes import configuration_notes, detector_note
    from ..simulation import CheckpointSaver, SimulationError, resume_state, simulate

    end = cfg.end_time if end is None else end
    replace_existing = _check_run_output(output, config, resume, overwrite)
    previous = None if resume is None else _open_resume(resume, end)
    if interval is None and previous is not None:
        interval = _earlier_interval(previous, resume)
    if interval is not None:  # a change as --set makes it, so the result records its TOML
        changes["solver.checkpoint_interval"] = f"{float(interval)!r} s"
        cfg = load(config, changes)
    for note in configuration_notes(cfg, end):
        say(note, "yellow")
    mesh = detector_note(detector or cfg.solver.detector)
    if mesh is not None:
        say(mesh, "yellow")
    for tmp, pid in remove_stale_temporaries(output):
        say(f"removed {tmp}: a temporary file of process {pid}, which no longer runs")
    t_start = 0.0 if previous is None else float(resume_state(previous)[0])
    unsaved: list[OSError] = []  # a checkpoint that could not be written stops the run
    # Ctrl-C and SIGTERM (a batch system or `kill`) recorded from here until the result is
    # written: the run stops at its next progress report (every output time and 0.2 s of
    # wall time) and writes everything computed so far (exit status 130 or 143), and one
    # that comes after the last report or during the final write lets that write finish.
    # Raised where it lands, the exception could be swallowed by library code (pydantic's
    # serializer, during a checkpoint's write, warns and goes on) or cut the write. A
    # second Ctrl-C interrupts at once.
    received: list[int] = []

    def moved(old: Path, new: Path) -> None:
        error(
            f"-o {old}: another program put a file there during the run; it is kept, and "
            f"this run's checkpoints and result go to {new}"
        )

    # the checkpoints and the result replace only the file this run wrote last (or the
    # one --overwrite / --resume allowed at the start): never one that another program
    # wrote meanwhile
    saver = CheckpointSaver(output, save_every, replace_existing=replace_existing, moved=moved)

    def checkpoint(partial) -> None:
        try:
            saver(partial)
        except OSError as err:
            unsaved.append(err)

    status = 0

    def crawl_notice(note: str) -> None:
        modes = f"rollerdyn modes {saver.path} (also after Ctrl-C, which keeps the result)"
        say(f"note: {note}. For this run: {modes}", "yellow")

    with _signals_recorded(received):
        with _run_progress(cfg.name, t_start, end) as show:
            try:
                ds = simulate(
                    cfg,
                    t_end=end,
                    detector=detector,
                    progress=lambda p: _stop_if(received) or show(p) or bool(unsaved),
                    resume=previous,
                    checkpoint=checkpoint,
                    threads=threads,
                    notice=crawl_notice,
                    **({"force": True} if force else {}),
                )
            except ValueError as err:
                raise refuse(err) from None
            except SimulationError as err:
                ds = err.dataset
                status = _stop_status(err)
                error(f"run stopped: {err}")
        before_the_write = bool(received)
        written = _write_result(saver, ds, unsaved)
    say(_run_line(written, ds))
    if status and not unsaved and ds.sizes.get("time", 0) > 0:
        say(
            f"if its steps were small: rollerdyn modes {written} names the modes "
            "that grow at its last state"
        )
    if unsaved:
        status = status or 1
    if received and not status:  # after the last progress report
        when = "" if before_the_write else " while its result was written"
        error(f"run ended, then interrupted{when}; the result is whole")
        status = 143 if received[0] == signal.SIGTERM else 130
    if status:
        raise typer.Exit(status)


def _write_result(saver, ds, unsaved: list[OSError]) -> Path:
    """Writes the run's result ``ds`` through ``saver``'s file; returns where it went. If
    it cannot be written there, keeps it in the system's temporary folder and exits with
    status 1 naming both (and the checkpoint that could not be written, if one stopped the
    run)."""
    from ..paths import keep_elsewhere
    from ..simulation import encode

    stop = f"could not write the checkpoint ({unsaved[0]}); run stopped; " if unsaved else ""
    try:
        written = saver.file.write(ds)
        if unsaved:
            error(f"-o {written}: {stop}the result is written whole")
        return written
    except OSError as err:
        why = f"could not write the result ({err.strerror or err})"
    except Exception as err:  # h5py: data it cannot encode
        why = f"could not encode the result ({' '.join(str(err).split())})"
    try:
        kept = keep_elsewhere(encode(ds), "rollerdyn-run-")
    except Exception as err:
        kept = f"it could not be encoded to keep it elsewhere ({err}): it is lost"
    raise refuse(f"-o {saver.path}: {stop}{why}; {kept}", 1) from None


@contextlib.contextmanager
def _signals_recorded(received: list[int]):
    """Ctrl-C and SIGTERM only recorded in ``received`` while the block runs (the run
    stops at its next progress report, :func:`_stop_if`; the result's write, about 1.5 s
    for B1, compressing, is not cut short, so nothing computed is lost); a second Ctrl-C
    raises KeyboardInterrupt at once. Nothing changes outside the main thread, where
    Python takes no signals."""
    import threading

    if threading.current_thread() is not threading.main_thread():
        yield
        return

    def record(signum, _frame) -> None:
        received.append(signum)
        if signum == signal.SIGINT and received.count(signal.SIGINT) > 1:
            raise KeyboardInterrupt

    handlers = {signum: signal.signal(signum, record) for signum in (signal.SIGINT, signal.SIGTERM)}
    try:
        yield
    finally:
        for signum, handler in handlers.items():
            signal.signal(signum, handler)


def _stop_status(err: Exception) -> int:
    """Exit status of a run stopped by ``err``: 143 SIGTERM, 130 Ctrl-C, else 1."""
    from ..simulation import SimulationInterrupted

    if not isinstance(err, SimulationInterrupted):
        return 1
    return 143 if "SIGTERM" in str(err) else 130


def _check_run_output(output: Path, config: Path, resume: Path | None, overwrite: bool) -> bool:
    """Exits with status 2 unless ``run`` may write ``output`` (see :mod:`rollerdyn.paths`):
    an existing file only with --overwrite or as the --resume file. Returns whether a file
    there may be replaced."""
    from ..paths import same_file

    in_place = resume is not None and same_file(output, resume)
    checked(
        check_output_file,
        output,
        "-o",
        inputs=[("the configuration file", config)],
        overwrite=overwrite or in_place,
        hint="; pass --overwrite to replace it, or --resume with the same file to continue its run",
        reserve=0,  # simulation.write's temporary file keeps its name short
    )
    return overwrite or in_place


def _earlier_interval(previous, resume: Path) -> float | None:
    """The checkpoint interval [s] the earlier run of ``--resume`` recorded (None: none
    recorded); exits with status 2 if the record is no positive number."""
    earlier = previous.attrs.get("checkpoint_interval_s")
    if earlier is None:
        return None
    try:
        value = float(earlier)
    except (TypeError, ValueError):
        value = math.nan
    if not (math.isfinite(value) and value > 0.0):
        raise refuse(
            f"--resume {resume}: its checkpoint_interval_s = {earlier!r} is no positive "
            "number of seconds: the file was changed after its run"
        )
    return value


def _open_resume(resume: Path, end: float):
    """The earlier result of ``--resume``, loaded; exits with status 2 naming the file and
    what is wrong if it is no rollerdyn result or already reached ``end``."""
    from ..report import REQUIRED, ReportError, open_result

    try:
        previous = open_result(resume, required=(*REQUIRED, "final_state"), recorded_only=True)
    except ReportError as err:
        raise refuse(f"--resume {err}") from None
    t_prev = float(previous.attrs["final_time_s"])
    if not end > t_prev:
        raise refuse(
            f"--resume {resume}: the run already reached t = {t_prev} s; --t-end = {end} s "
            "must lie after it"
        )
    return previous


def _run_line(output: Path, ds) -> str:
    """The closing line of ``run``: what was written and what it cost."""
    st = ds.attrs
    return (
        f"wrote {output}: {ds.sizes['time']} outputs to t = {st['final_time_s']:.6g} s; "
        f"{st['stats_steps']} steps ({st.get('stats_error_test_failures', 0)} rejected), "
        f"{st['stats_rhs_evaluations']} right-hand sides, "
        f"{st['stats_jacobian_evaluations']} Jacobians, "
        f"{_seconds(st['stats_total_seconds'])} of wall time integrating "
        f"on {st.get('threads', 1)} thread(s)"
    )


def _seconds(wall: float) -> str:
    """A wall time as text: three significant digits below 10 s (a short run's 0.013 s
    is not "0.0 s"), tenths above."""
    return f"{wall:.3g} s" if wall < 10 else f"{wall:.1f} s"


def _rate(simulated: float, wall: float) -> str:
    """Simulated time per wall second, as text."""
    return f"{simulated / wall * 1e3:.3g} ms/s" if wall > 0 else ""


class ProgressLines:
    """Progress of a run as plain lines, for a log or a pipe (no terminal): one at every
    10 % of the simulated time and at least one every ``every`` seconds of wall time."""

    def __init__(self, name: str, t_start: float, t_end: float, every: float = 10.0):
        self.name, self.t_start, self.t_end, self.every = name, t_start, t_end, every
        self.started = self.last = time.perf_counter()
        self.next_share = 0.1

    def __call__(self, p) -> None:
        now = time.perf_counter()
        span = self.t_end - self.t_start
        share = (p.time - self.t_start) / span if span > 0 else 1.0
        if share < self.next_share - 1e-9 and now - self.last < self.every:
            return
        while self.next_share <= share + 1e-9:
            self.next_share += 0.1
        self.last = now
        wall = now - self.started
        say(
            f"{self.name}: t = {p.time:.6g} / {self.t_end:.6g} s ({100 * share:.0f} %), "
            f"{p.steps} steps, {_rate(p.time - self.t_start, wall)}, {wall:.1f} s wall"
        )


@contextlib.contextmanager
def _run_progress(name: str, t_start: float, t_end: float):
    """The progress callback of a run: rich's live bar on a terminal, else plain lines."""
    if not console.is_terminal:
        yield _going_on_without_stdout(ProgressLines(name, t_start, t_end))
        return
    from rich.progress import (
        BarColumn,
        Progress,
        TextColumn,
        TimeElapsedColumn,
        TimeRemainingColumn,
    )

    columns = (
        TextColumn("{task.description}", style="bold", markup=False),
        BarColumn(),
        TextColumn("t = {task.completed:.4f} / {task.total:.4f} s", markup=False),
        TextColumn("{task.fields[steps]} steps", markup=False),
        TextColumn("{task.fields[rate]}", markup=False),
        TimeElapsedColumn(),
        TimeRemainingColumn(),
    )
    start = time.perf_counter()
    with Progress(*columns, console=console, transient=False) as bar:
        task = bar.add_task(plain(name), total=t_end, steps=0, rate="")

        def show(p) -> None:
            rate = _rate(p.time - t_start, time.perf_counter() - start)
            bar.update(task, completed=p.time, steps=p.steps, rate=rate)

        yield show


def _going_on_without_stdout(show):
    """``show``, which a closed standard output does not stop: rich ends the process
    (SystemExit 1, standard output then sent to /dev/null) when the reader of a pipe has
    left (``rollerdyn run ... | head -1``), which stopped the run with no word on its
    standard error (a review). The run goes on without progress lines, says so once on
    standard error, and writes its result."""
    gone: list[bool] = []

    def guarded(p) -> None:
        if gone:
            return
        try:
            show(p)
        except SystemExit as stop:
            if not isinstance(stop.__context__, BrokenPipeError):
                raise
            gone.append(True)
            print(
                "rollerdyn run: standard output closed; the run goes on without progress lines",
                file=sys.stderr,
            )

    return guarded


def _stop_if(received: list[int]) -> None:
    """Stops the run from its progress report once Ctrl-C or SIGTERM has come
    (``received``)."""
    if received:
        raise KeyboardInterrupt(
            "terminated by SIGTERM" if received[0] == signal.SIGTERM else "Ctrl-C"
        )
