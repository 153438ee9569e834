"""``rollerdyn sweep``: a grid of variants of a configuration run on Dask
(:func:`rollerdyn.sweep.sweep`), its progress, and the summary printed as a table."""

from __future__ import annotations

import contextlib
import math
import time
from collections.abc import Callable
from pathlib import Path
from typing import Annotated, Any

import typer
from rich.table import Table
from rich.text import Text

from ..paths import check_output_dir
from .common import (
    check_detector,
    checked,
    console,
    detector_help,
    error,
    load,
    output_option,
    plain,
    refuse,
    refusing,
    say,
    terminated_as_interrupted,
    time_option,
)


def _fmt(value: Any, spec: str = ".6g") -> str:
    """A summary value as text; NaN (nothing to report) as n/a."""
    if isinstance(value, float):
        return "n/a" if math.isnan(value) else format(value, spec)
    return str(value)


def sweep_command(
    config: Annotated[
        Path, typer.Argument(help="Bearing configuration (TOML) to vary.", metavar="CONFIG")
    ],
    sets: Annotated[
        list[str],
        typer.Option(
            "--set",
            metavar="PATH=VALUES",
            help="PATH=VALUE[,VALUE...]: a dotted configuration path and the values it "
            'takes, e.g. --set operating.axial_load="0 N,500 N,1000 N". Each value is '
            "written as in the TOML file: with its unit for dimensional fields "
            '("500 N", "3000 rpm", "80 degC"); bare numbers (0.3, 20) and true/false '
            "are numbers and booleans, valid only for dimensionless fields (a bare 500 "
            "for a force is refused: no unit); anything else is a string. Commas inside "
            "quotes, [arrays] or {inline tables} do not split. A:B:N gives N values from "
            'A to B evenly, in their unit ("0 N:1000 N:5"; bare numbers stay numbers). '
            "Repeat --set for more paths: the runs are the full grid (cartesian product).",
        ),
    ],
    output: Annotated[
        Path,
        output_option(
            help="Output folder: run_0000.nc, run_0001.nc, ... (netCDF, SI units, as "
            "written by rollerdyn run) and summary.parquet. Created if missing (its parent "
            "must exist); a folder that holds an earlier sweep's results is refused unless "
            "--overwrite is given.",
        ),
    ] = Path("sweep"),
    overwrite: Annotated[
        bool,
        typer.Option(
            "--overwrite",
            help="Replace the results of an earlier sweep in the output folder (its "
            "run_XXXX.nc, summary and figure; a file of those names that is not a sweep's "
            "is refused, and nothing else is touched).",
        ),
    ] = False,
    resume: Annotated[
        bool,
        typer.Option(
            "--resume",
            help="Continue the sweep in the output folder that was interrupted (Ctrl-C, "
            "SIGTERM, a lost machine): the runs whose result files are there, of the same "
            "configuration, detector and end time, are kept and not run again (a failed "
            "run stays failed: it would fail again, bit for bit), the others run. Give the "
            "same CONFIG, --set values, --t-end and --detector; a run file of another "
            "sweep is refused (exit status 2). Without an earlier sweep it runs them all.",
        ),
    ] = False,
    scheduler: Annotated[
        str | None,
        typer.Option(
            "--scheduler",
            help="Address of a running Dask scheduler (e.g. tcp://10.0.0.5:8786); its "
            "workers need rollerdyn installed and must see the output folder. An address "
            "that cannot be reached within 10 s exits with status 2. Default: a local "
            "cluster of --workers processes.",
        ),
    ] = None,
    workers: Annotated[
        int,
        typer.Option(
            "--workers",
            min=1,
            help="Worker processes of the local cluster (one thread, so one run, each). "
            "Ignored with --scheduler.",
        ),
    ] = 2,
    t_end: Annotated[
        str | None,
        typer.Option(
            "--t-end",
            help="Simulated end time of every run, with a unit as in the configuration "
            "(50 ms, 0.05 s) or a bare number of seconds. Default: each configuration's "
            "end time (speed ramp end + two roller-set revolutions, about 1.288 s for B1).",
            metavar="TIME",
        ),
    ] = None,
    detector: Annotated[
        str | None,
        typer.Option(
            "--detector",
            help=detector_help("each configuration"),
        ),
    ] = None,
    force: Annotated[
        bool,
        typer.Option(
            "--force",
            help="Run every point as rollerdyn run --force would: also those whose estimated "
            "result size or cost is far beyond a normal run, and those the point end-flange "
            "law's load check refuses (a roller end pressed onto its end face, or a load the "
            "point law has no equilibrium for: the run's "
            "steps creep or collapse).",
        ),
    ] = False,
) -> None:
    """Run a grid of variants of a configuration on Dask and summarise them.

    Every grid point and the output folder are checked before any run starts; a bad one
    exits with status 2 naming the --set path (or option), the value and the rule. Each
    run writes its own result file. The summary (one row per run; units SI, given in the
    column names: run, each swept value as given and in SI, status, error, final time
    [s], mean frictional torque over the last 20 % of the run [N*m], maximum roller race
    load [N], maximum flange normal force [N], maximum |slide-to-roll ratio| at the inner
    race while the ring turns [1] (n/a if it never does), steps, a note (a run that
    crawled: its steps averaged under 1 µs of simulated time over 10 s of wall time, with
    its likely cause; printed below the table), wall time [s], file) is
    written to summary.parquet and printed, and drawn over the swept quantity with the most
    values, one line per combination of the others, in summary.png and summary.svg (when a
    numeric value takes two or more values). A failed run keeps its partial result and its
    error in the summary (a cross in the figure), and the sweep goes on; the command then
    exits with status 1. Ctrl-C or SIGTERM stops the sweep: the summary lists the runs that
    finished and the others as interrupted (exit status 130 or 143), and the same command
    with --resume runs the others, keeping the finished ones' files. --overwrite first
    removes the earlier sweep's result files, summary and figure (files of those names that
    are not a sweep's are refused: exit status 2, nothing removed).
    """
    from ..sweep import (
        RUN_FILES,
        SUMMARY_FILE,
        SweepError,
        _sigterm_deferred,
        build_grid,
        earlier_results,
        sweep,
    )
    from ..sweep_figures import FIGURE_NAME
    from ..sweep_resume import finished_runs

    parameters = _parameters(sets)
    end = time_option("--t-end", t_end)
    if overwrite and resume:
        raise refuse(
            "--overwrite and --resume: choose one (--resume keeps the earlier sweep's "
            "finished runs, --overwrite removes them)"
        )
    load(config)  # a bad file: the same message and exit status as rollerdyn run
    check_detector(detector)
    checked(
        check_output_dir,
        output,
        "-o",
        results=(RUN_FILES, SUMMARY_FILE),
        overwrite=overwrite or resume,
        hint="; pass --resume to continue that sweep or --overwrite to replace it, or "
        "choose another folder",
    )
    flag = "--resume" if resume else "--overwrite"
    with refusing(SweepError, output):  # --overwrite replaces a sweep's own files only
        earlier_results(output, overwrite or resume, f"-o {output}", flag, resume)

    def stopped(cause: str) -> str:
        if (output / SUMMARY_FILE).is_file():
            return (
                f"rollerdyn sweep: {cause}; {output / SUMMARY_FILE} lists the runs that "
                "finished and the others as interrupted; the same command with --resume "
                "runs the others"
            )
        return f"rollerdyn sweep: {cause} before any run started; nothing written"

    with (
        refusing(SweepError, output),
        _said_when_interrupted(lambda: stopped("interrupted")),
        terminated_as_interrupted(lambda: stopped("terminated (SIGTERM)")),
    ):
        with _sigterm_deferred():  # a stop within an import would fail it (not stop)
            import distributed  # noqa: F401
            import pandas  # noqa: F401
            import pyarrow.parquet  # noqa: F401
        runs = math.prod(len(v) for v in parameters.values())
        with console.status(f"checking the grid's {runs} configurations"):
            points = build_grid(config, parameters, end, detector)  # before the cluster
            if resume:  # another sweep's run files refused before the cluster starts
                finished_runs(output, points, end, detector)
        with _sweep_progress(console, scheduler, resume) as progress:
            frame = sweep(
                config,
                parameters,
                output,
                scheduler=scheduler,
                workers=workers,
                t_end=end,
                detector=detector,
                progress=progress,
                force=force,
                overwrite=overwrite,
                resume=resume,
            )
    failed = _print_summary(frame, config, output, list(parameters))
    figure = output / f"{FIGURE_NAME}.png"
    drawn = f", {figure} (and .svg)" if figure.is_file() else ""
    say(
        f"wrote {output / SUMMARY_FILE}{drawn} and {int((frame['file'] != '').sum())} result "
        f"files; {len(frame) - failed} completed, {failed} failed"
    )
    if failed:
        raise typer.Exit(1)


@contextlib.contextmanager
def _said_when_interrupted(message: Callable[[], str]):
    """Ctrl-C within the block ends the command with the one line ``message()`` (what the
    interrupted sweep kept, asked then) and exit status 130."""
    try:
        yield
    except KeyboardInterrupt:
        error(message())
        raise typer.Exit(130) from None


def _parameters(sets: list[str]) -> dict[str, list[Any]]:
    """The --set options as {path: values}; exits with status 2 on a malformed one."""
    from ..sweep import SweepError, parse_set

    parameters: dict[str, list[Any]] = {}
    try:
        for option in sets:
            path, values = parse_set(option)
            if path in parameters:
                raise SweepError(f"--set {path}: given twice; list all its values in one --set")
            parameters[path] = values
    except SweepError as err:
        raise refuse(err) from None
    return parameters


class _Lines:
    """The sweep's progress as plain lines (no terminal: a log, a pipe), one per run."""

    def __init__(self, say: Callable[[str], None]):
        self.say, self.started = say, time.perf_counter()

    def __call__(self, done: int, total: int, row: dict | None) -> None:
        wall = time.perf_counter() - self.started
        if row is None:
            self.say(f"sweep: {_started(done, total)} ({wall:.1f} s)")
        else:
            status = row["status"]
            self.say(f"sweep: run {row['run']} {status}; {done} of {total} done ({wall:.1f} s)")


def _started(kept: int, total: int) -> str:
    """What a sweep of ``total`` runs started with, ``kept`` of them kept from the earlier
    sweep (``--resume``; the count :func:`rollerdyn.sweep.sweep` reports, which leaves
    out a run file that cannot be read)."""
    left = total - kept
    runs = f"{left} run" + ("" if left == 1 else "s")
    if not kept:
        return f"{runs} submitted"
    if not left:
        return f"all {total} runs kept from the earlier sweep; writing the summary"
    return f"{kept} of {total} runs kept from the earlier sweep, {runs} submitted"


@contextlib.contextmanager
def _sweep_progress(console, scheduler: str | None, resume: bool = False):
    """The progress callback of :func:`sweep`: a live bar on a terminal, else lines
    (``resume``: the earlier sweep's finished runs are read first)."""
    start = "starting Dask workers" if scheduler is None else f"connecting to {scheduler}"
    start = f"reading the earlier sweep's runs, {start} for the others" if resume else start
    if not console.is_terminal:
        say(f"sweep: {start}")
        yield _Lines(say)
        return
    from rich.progress import (
        BarColumn,
        MofNCompleteColumn,
        Progress,
        TextColumn,
        TimeElapsedColumn,
        TimeRemainingColumn,
    )

    columns = (
        TextColumn("{task.description}", style="bold", markup=False),
        BarColumn(),
        MofNCompleteColumn(),
        TextColumn("runs", markup=False),
        TimeElapsedColumn(),
        TimeRemainingColumn(),
        TextColumn("{task.fields[last]}", markup=False),
    )
    with Progress(*columns, console=console, transient=False) as bar:
        task = bar.add_task(plain(start), total=None, last="")

        def progress(done: int, total: int, row: dict | None) -> None:
            last = _started(done, total) if row is None else f"run {row['run']} {row['status']}"
            bar.update(task, description="sweep", completed=done, total=total, last=last)

        yield progress


def _print_summary(frame, config: Path, output: Path, swept: list[str]) -> int:
    """Prints the summary table and each failed run's error; returns how many failed."""
    table = Table(title=plain(f"sweep of {config.name}: {len(frame)} runs, in {output}"))
    headers = {
        "final_time [s]": "final t [s]",
        "mean_frictional_torque [N*m]": "mean torque, last 20 % [N*m]",
        "mean_power_loss [W]": "mean power loss [W]",
        "max_race_load [N]": "max race load [N]",
        "max_flange_normal_force [N]": "max flange force [N]",
        "max_abs_srr_inner [1]": "max |SRR| inner, ring turning",
        "steps": "steps",
        "wall [s]": "wall [s]",
        "file": "file",
    }
    # swept values as given (SI in the parquet); a column a summary lacks (one written
    # before it existed) is left out
    shown = [c for c in ["run", *swept, "status", *headers] if c in frame.columns]
    for col in shown:
        table.add_column(headers.get(col, col), overflow="fold")
    for _, row in frame.iterrows():
        cells = []
        for col in shown:
            value = row[col]
            if col == "status":
                ok = value == "completed"
                cells.append(Text(value, style="green" if ok else "red"))
                continue
            cells.append(Text(plain(_fmt(value, ".1f" if col == "wall [s]" else ".6g"))))
        table.add_row(*cells)
    console.print(table)
    for _, row in frame[frame["note"].astype(bool)].iterrows():
        say(f"run {row['run']}: {row['note']}", "yellow")
    failed = frame[frame["status"] != "completed"]
    for _, row in failed.iterrows():
        error(f"run {row['run']} failed: {row['error']}")
    return len(failed)
