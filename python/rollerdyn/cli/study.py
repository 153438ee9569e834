"""``rollerdyn study``: ``paper`` (the paper's sect. 5 on Dask, its findings checked, one
report) and ``map`` (operating maps at steady state), with one progress display for the
whole study and the tables printed at the end (:mod:`rollerdyn.study`)."""

from __future__ import annotations

import contextlib
import math
import time
from pathlib import Path
from typing import Annotated, Any

import typer

from ..limits import DEFAULT_MAX_WALL
from .common import (
    console,
    default_config,
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
from .study_tables import (
    print_findings,
    print_frame,
    print_map,
    print_runs,
    print_timing,
    run_status,
    status_and_note,
)

app = typer.Typer(
    help="Studies of many runs on Dask: the paper's section 5 (paper) and operating maps (map).",
    no_args_is_help=True,
    add_completion=False,
    rich_markup_mode=None,
)


SchedulerOption = Annotated[
    str | None,
    typer.Option(
        "--scheduler",
        help="Address of a running Dask scheduler (e.g. tcp://10.0.0.5:8786); its workers "
        "need rollerdyn installed and must see the output folder. One that cannot be "
        "reached within 10 s exits with status 2. Default: a local cluster of --workers "
        "processes.",
    ),
]
WorkersOption = Annotated[
    int | None,
    typer.Option(
        "--workers",
        min=1,
        help="Worker processes of the local cluster, one run (one core) each. Default: all "
        "cores. Ignored with --scheduler.",
    ),
]
MaxWallOption = Annotated[
    float,
    typer.Option(
        "--max-wall",
        help="Wall-time cap of each run in this invocation [s]. A run that reaches it is "
        "stopped, reported as 'not finished (reached t = ...)' and continued from its "
        "last checkpoint by the next invocation.",
        metavar="SECONDS",
    ),
]
OverwriteOption = Annotated[
    bool,
    typer.Option(
        "--overwrite",
        help="Start afresh: remove what an earlier study wrote in the folder (the run "
        "files, tables, figures and report its study.json lists; nothing else). A folder "
        "without study.json that holds files a study writes is refused either way.",
    ),
]


#: The quantity each unit of :func:`_numbers` stands for (:mod:`rollerdyn.units`).
_FAMILIES = {"N": "force", "s": "time"}


def _numbers(text: str | None, option: str, unit: str) -> list[float] | None:
    """A comma list of numbers in ``unit``, each also with its own unit ("5 kN", "1 ms"),
    as ``study map`` takes them (None stays None; 'none' is empty)."""
    from ..units import QuantityError, parse_quantity

    if text is None:
        return None
    if text.strip().lower() == "none":
        return []

    def value(item: str) -> float:
        try:
            return float(item)
        except ValueError:
            return parse_quantity(item.strip(), _FAMILIES[unit])

    try:
        values = [value(v) for v in text.split(",")]
    except QuantityError:
        raise refuse(
            f"{option} = {text!r}: must be comma-separated numbers in {unit}, or values with "
            "their unit (or none)"
        ) from None
    if not values or not all(math.isfinite(v) for v in values):
        raise refuse(f"{option} = {text!r}: must be comma-separated finite numbers in {unit}")
    return values


def paper_command(
    config: Annotated[
        Path | None,
        typer.Argument(
            help="Bearing configuration (TOML). Default: examples/b1.toml of the source tree.",
            metavar="[CONFIG]",
        ),
    ] = None,
    output: Annotated[
        Path,
        output_option(
            help="Study folder (created with its parents if missing): study.json, runs/ "
            "(one netCDF result per run, SI units), runs.csv, findings.csv, findings.json, "
            "runtime_study.csv, figures/ (PNG, SVG) and report.html. A folder of an earlier "
            "study of the same configuration is continued: finished runs are reused, "
            "unfinished ones continue from their last checkpoint; one of another "
            "configuration is refused (exit status 2) unless --overwrite.",
        ),
    ] = Path("results/study"),
    t_end: Annotated[
        str | None,
        typer.Option(
            "--t-end",
            help="Simulated end time of every run, with a unit (20 ms, 0.02 s) or a bare "
            "number of seconds: a short version of the study. Default: the configuration's "
            "end time (speed ramp end + two roller-set revolutions, about 1.288 s for B1).",
            metavar="TIME",
        ),
    ] = None,
    max_wall: MaxWallOption = DEFAULT_MAX_WALL,
    loads: Annotated[
        str,
        typer.Option(
            "--loads",
            help="Axial loads of figs. 10-13 in N, comma-separated (each also with its "
            "unit: 0.5 kN), or 'none'; the configuration's own axial load is always one of "
            "them.",
            metavar="N,N,...",
        ),
    ] = "0,500,1000,2000",
    dt_max: Annotated[
        str | None,
        typer.Option(
            "--dt-max",
            help="Δt_max of fig. 14 in s, comma-separated (each also with its unit: "
            "0.5 ms; each run with both detectors), or 'none'. Default: 0.2, 0.5 and 1 "
            "times solver.dt_max (2e-4, 5e-4, 1e-3 s for B1).",
            metavar="S,S,...",
        ),
    ] = None,
    free_tilt: Annotated[
        bool,
        typer.Option(
            "--free-tilt/--no-free-tilt",
            help="Run the configuration with inner_ring.tilt = free for figs. 8, 9 and "
            "compare it with the locked ring. With surfaces.flange_law = point (the paper's, "
            "B1's) both runs of that pair use the distributed law, with which the free tilt "
            "runs (the point law's collapses; docs/dynamics.md). Capped by --max-wall, "
            "reported as not finished when it does not finish; never replaced by a "
            "prescribed misalignment.",
        ),
    ] = True,
    gradient: Annotated[
        bool,
        typer.Option(
            "--gradient/--no-gradient",
            help="Run the gradient detector too (sect. 5.1 contact points, sect. 5.3 MBS "
            "runtime, fig. 14), and the round-off twin of the configuration's run "
            "(solver.atol x (1 + 1e-10)) that its differences in kinematics are judged against.",
        ),
    ] = True,
    distributed: Annotated[
        bool,
        typer.Option(
            "--distributed/--no-distributed",
            help="With surfaces.flange_law = point (the paper's, B1's): run the axial loads "
            "once more with the distributed flange law, a second series of figs. 10-13 and "
            "its checks (the point law refuses loads at which the loaded roller ends lie "
            "flat on the flanges, B1 at 2000 N; docs/dynamics.md).",
        ),
    ] = True,
    tight: Annotated[
        bool,
        typer.Option(
            "--tight/--no-tight",
            help="With --gradient: run the configuration with both detectors once more at "
            "ten times tighter tolerances (solver.rtol and solver.atol x 0.1; for B1 1e-6 "
            "and 1e-10 m), where the two methods are judged against absolute bounds: every "
            "roller's position 0.1 µm, flange forces 1 % of the largest, mean torque 0.1 % "
            "(not in the paper; B1's pair took 36-68 s and 198-280 s on one core).",
        ),
    ] = True,
    scheduler: SchedulerOption = None,
    workers: WorkersOption = None,
    overwrite: OverwriteOption = False,
    run: Annotated[
        bool,
        typer.Option(
            "--run/--no-run",
            help="--no-run: run nothing; check the findings and write the tables, figures "
            "and report from what the folder holds.",
        ),
    ] = True,
) -> None:
    """Run the paper's whole study (sect. 5, figs. 8-14) on Dask, check its findings and
    write one report.

    The runs: the configuration at axial loads 0, 500, 1000 and 2000 N (figs. 10-13;
    with the point law also with the distributed flange law), with the inner ring free to
    tilt (figs. 8, 9; with the point law both runs of that pair with the distributed law),
    with the gradient detector (contact points and penetrations, MBS runtime, sect. 5.1
    and 5.3), its round-off twin (solver.atol changed in the tenth digit: how far a run
    moves when only its steps change, the yardstick of the detectors' differences), both
    detectors at ten times tighter tolerances (judged against 0.1 µm, 1 % and 0.1 %) and
    both detectors at each Δt_max (fig. 14). Each is one Dask task on one
    core; progress is shown for the whole study. The findings table gives each of the
    paper's statements PASS, FAIL or NOT RUN (nothing to judge) with the numbers behind
    it. Units: SI (s, N, N*m, m) unless a column says otherwise.

    Exit status: 0 when the study ran (runs that did not finish and findings that FAIL
    are results, in the tables); 1 when a run could not be run at all; 2 for bad input
    (nothing run); 130 after Ctrl-C, 143 after SIGTERM (finished runs and checkpoints stay
    on disk).
    """
    from ..study import paper

    end = time_option("--t-end", t_end)
    load_values = _numbers(loads, "--loads", "N") or []
    dt_values = _numbers(dt_max, "--dt-max", "s")
    path = config if config is not None else default_config()
    load(path)  # a bad file: the same message and exit status as rollerdyn run
    started = time.perf_counter()
    result = _run_study(
        "study paper",
        paper,
        path,
        output,
        t_end=end,
        loads=load_values,
        dt_max=dt_values,
        free_tilt=free_tilt,
        gradient=gradient,
        distributed=distributed,
        tight=tight,
        max_wall=max_wall,
        scheduler=scheduler,
        workers=workers,
        overwrite=overwrite,
        run=run,
    )
    print_runs(result.runs, f"{result.plan.config.name}: runs of the study in {output}")
    print_findings(result.findings)
    files = ("report.html", "findings.csv", "runs.csv")
    _finish(output, files, result.runs, result.figures, result.timing, started)


def map_command(
    config: Annotated[Path, typer.Argument(help="Bearing configuration (TOML).", metavar="CONFIG")],
    speed: Annotated[
        str,
        typer.Option(
            "--speed",
            help="Inner ring speeds in rpm: a:b:n (n evenly spaced from a to b, a < b), a "
            "list v1,v2,... or one value; a value may carry its own unit (3000 rpm, 50 "
            "rad/s). Above 0. Where the configuration turns the outer ring about a still "
            "inner ring (operating.inner_ring_speed = 0 rpm, a planet gear's bearing), "
            "the outer ring's speeds.",
            metavar="A:B:N",
        ),
    ],
    radial_load: Annotated[
        str | None,
        typer.Option(
            "--radial-load",
            help="Radial loads in N, as --speed (5 kN allowed). Default: the configuration's.",
            metavar="A:B:N",
        ),
    ] = None,
    axial_load: Annotated[
        str | None,
        typer.Option(
            "--axial-load",
            help="Axial loads in N, as --speed. Default: the configuration's.",
            metavar="A:B:N",
        ),
    ] = None,
    temperature: Annotated[
        str | None,
        typer.Option(
            "--temperature",
            help="Oil (and bearing) temperatures in degC, as --speed (353.15 K allowed); "
            "each point's viscosity, density and Roelands z follow it. Default: the "
            "configuration's operating.temperature.",
            metavar="A:B:N",
        ),
    ] = None,
    heat_dissipation: Annotated[
        str | None,
        typer.Option(
            "--heat-dissipation",
            help="The heat the bearing gives off per kelvin above --ambient, in W/K (a "
            "number, or with its unit). With two or more --temperature values the map "
            "finds, for each speed and loads, the temperature at which this equals the "
            "friction power (the thermal balance: thermal.csv and "
            "figures/thermal_balance; docs/study.md). Default: no balance.",
            metavar="W/K",
        ),
    ] = None,
    ambient: Annotated[
        str | None,
        typer.Option(
            "--ambient",
            help="Temperature of the surroundings of the thermal balance, in degC (or with "
            "its unit); with --heat-dissipation only. Default: 20 degC (ISO 15312's "
            "reference).",
            metavar="TEMPERATURE",
        ),
    ] = None,
    oil_flow: Annotated[
        str | None,
        typer.Option(
            "--oil-flow",
            help="With --heat-dissipation: a circulating oil's volume flow through the "
            "bearing (with its unit: 0.5 l/min; a bare number is m^3/s), which leaves at the "
            "bearing's temperature and so carries rho c_p V [W/K] per kelvin above its "
            "inlet away (rho from the configuration, c_p by Cragoe's formula). Default: none.",
            metavar="FLOW",
        ),
    ] = None,
    oil_inlet: Annotated[
        str | None,
        typer.Option(
            "--oil-inlet",
            help="With --oil-flow: the oil's inlet temperature in degC (or with its unit). "
            "Default: --ambient.",
            metavar="TEMPERATURE",
        ),
    ] = None,
    permissible_temperature: Annotated[
        str | None,
        typer.Option(
            "--permissible-temperature",
            help="With --heat-dissipation: the bearing's permissible temperature in degC "
            "(or with its unit); the map then finds, for each loads, the lowest speed at "
            "which the thermal balance reaches it (the thermally permissible speed: "
            "thermal_speed.csv and figures/thermal_speed). Default: none.",
            metavar="TEMPERATURE",
        ),
    ] = None,
    output: Annotated[
        Path,
        output_option(
            help="Map folder (created with its parents if missing): study.json, points/ "
            "(one netCDF result per grid point), map.csv, map.parquet, report.html (one "
            "page: tables and maps), thermal*.csv with a balance, and figures/. An "
            "earlier map of the same configuration, criterion and grid is continued; another "
            "is refused (exit status 2) unless --overwrite.",
        ),
    ] = Path("results/map"),
    start: Annotated[
        str,
        typer.Option(
            "--start",
            help="How each point starts: equilibrium (full load and speed from t = 0, from "
            "the quasi-static equilibrium: about half the wall time of short ramps for a "
            "loaded point), short-ramps (loads over 0 ... --ramp, speed over --ramp ... 2 "
            "--ramp) or config (the configuration's own ramps).",
        ),
    ] = "equilibrium",
    ramp: Annotated[
        str | None,
        typer.Option(
            "--ramp",
            help="Length of each short ramp, with --start short-ramps only. Default: 20 ms.",
            metavar="TIME",
        ),
    ] = None,
    window: Annotated[
        str,
        typer.Option(
            "--window",
            help="Least window W of the steadiness criterion; W is at least two roller "
            "passing periods, and each point writes an output at least every W/100 "
            "(docs/study.md).",
            metavar="TIME",
        ),
    ] = "10 ms",
    tol: Annotated[
        float,
        typer.Option(
            "--tol",
            help="Steady when the torque, speed loss and largest flange force, each over a "
            "window, changed by at most this share of their value over each of the last two "
            "windows (or by less than 1e-4 N*m, 0.005, 1 N).",
        ),
    ] = 0.02,
    max_time: Annotated[
        str,
        typer.Option(
            "--max-time",
            help="Simulated time at which a point that is not steady ends (reported as not "
            "steady).",
            metavar="TIME",
        ),
    ] = "0.5 s",
    max_wall: MaxWallOption = 300.0,
    scheduler: SchedulerOption = None,
    workers: WorkersOption = None,
    overwrite: OverwriteOption = False,
    force: Annotated[
        bool,
        typer.Option(
            "--force",
            help="Run the points the point end-flange law's load check refuses (a roller "
            "end pressed onto its end face, or a load the point law has no equilibrium for: "
            "the run's steps may creep or collapse), as "
            "rollerdyn run --force does; their rows' notes say so. Without it such a point "
            "is not run (exit status 1), and the map invoked again with --force runs it.",
        ),
    ] = False,
) -> None:
    """Run a grid of speeds, loads and oil temperatures to steady state on Dask and draw
    operating maps.

    Each grid point runs until its friction torque [N*m], roller-set speed loss (1 - mean
    roller orbital speed / epicyclic cage speed, skidding) [-] and largest flange normal
    force [N], averaged over windows of simulated time, stop changing (see --tol,
    --window; docs/study.md), or until --max-time. The table (one row per point: values,
    status, time steady, the three outputs and the median specific film thickness Lambda
    [-] of the inner race and of the flange contacts and the inner ring's vibration peak
    to peak along the load [m] over the last window, wall time) is
    printed and written; the maps go to figures/ (PNG, SVG), all onto report.html. With
    --heat-dissipation, the thermal balance of each speed and loads [degC, W] is printed
    and written too, and with --permissible-temperature the thermally permissible speed of
    each loads [rpm].

    Exit status: 0 when the map ran; 1 when a point could not be run at all; 2 for bad
    input (nothing run).
    """
    from ..study import operating_map
    from ..study.thermal import PERMISSIBLE_COLUMNS, THERMAL_COLUMNS

    if ramp is not None and start != "short-ramps":
        raise refuse(
            f"--ramp {ramp}: sets the short ramps of --start short-ramps; the points start "
            f"as --start {start} says (the default is equilibrium: full load and speed from "
            "t = 0)"
        )
    ramp_s = time_option("--ramp", "20 ms" if ramp is None else ramp)
    window_s = time_option("--window", window)
    max_time_s = time_option("--max-time", max_time)
    load(config)
    started = time.perf_counter()
    result = _run_study(
        "study map",
        operating_map,
        config,
        output,
        speed=speed,
        radial_load=radial_load,
        axial_load=axial_load,
        temperature=temperature,
        heat_dissipation=heat_dissipation,
        ambient=ambient,
        oil_flow=oil_flow,
        oil_inlet=oil_inlet,
        permissible_temperature=permissible_temperature,
        start=start,
        ramp=ramp_s,
        window=window_s,
        tol=tol,
        max_time=max_time_s,
        max_wall=max_wall,
        scheduler=scheduler,
        workers=workers,
        overwrite=overwrite,
        force=force,
    )
    print_map(result.points, f"operating map of {config.name} in {output}")
    files: tuple[str, ...] = ("report.html", "map.csv", "map.parquet")
    for table, title, columns, written in (
        (result.thermal, "thermal balance", THERMAL_COLUMNS, "thermal.csv"),
        (
            result.permissible,
            "thermally permissible speed",
            PERMISSIBLE_COLUMNS,
            "thermal_speed.csv",
        ),
    ):
        if table is not None:  # the note in the status cell
            print_frame(table, f"{title} of {config.name}", columns[:-1], status_and_note)
            files += (written,)
    _finish(output, files, result.points, result.figures, result.timing, started)


def _run_study(title: str, study, config: Path, output: Path, **options):
    """``study(config, output, **options)`` with the progress display of the whole study;
    bad input exits with status 2, a folder that cannot be written with 1."""
    from ..study import StudyError

    # after SIGTERM as after Ctrl-C: the workers closed, the runs' files as far as they got
    try:
        with (
            terminated_as_interrupted(lambda: _kept(output, "terminated (SIGTERM)")),
            refusing(StudyError, output),
            _progress(title, options.get("scheduler")) as show,
        ):
            return study(config, output, progress=show, **options)
    except KeyboardInterrupt:
        # Ctrl-C said only "rollerdyn: interrupted", less than SIGTERM's line (a review)
        error(_kept(output, "interrupted"))
        raise typer.Exit(130) from None


def _kept(output: Path, how: str) -> str:
    """The line of a study stopped ``how``: what its folder keeps."""
    if not output.is_dir():
        return f"rollerdyn study: {how}; nothing was run"
    return (
        f"rollerdyn study: {how}; {output} keeps the runs as far as they got, and the same "
        "command continues them"
    )


def _finish(output: Path, files, frame, figures: list, timing: dict, started: float) -> None:
    """The end of a study's command: its timing, the ``files`` it wrote in ``output``, and
    exit status 1 if a run (a row of ``frame``) could not be run at all (no file)."""
    print_timing(timing, time.perf_counter() - started, frame)
    wrote = ", ".join(str(output / name) for name in files)
    say(f"wrote {wrote} and {len(figures)} figure files in {output / 'figures'}")
    if len(frame[(frame["status"] == "failed") & (frame["file"] == "")]):
        raise typer.Exit(1)


app.command(
    "paper", short_help="The paper's sect. 5 (figs. 8-14) on Dask, findings checked, a report."
)(paper_command)
app.command(
    "map",
    short_help="Operating maps: speeds, loads and oil temperatures at steady state; the "
    "thermal balance.",
)(map_command)


# --------------------------------------------------------------------------- progress


class _Lines:
    """Progress as plain lines (no terminal): the plan, each run's end, and each run's
    time at most every ``every`` seconds."""

    def __init__(self, title: str, every: float = 10.0):
        self.title, self.every = title, every
        self.started = time.perf_counter()
        self.last: dict[str, float] = {}
        self.done = self.total = 0

    def __call__(self, event: dict) -> None:
        wall = time.perf_counter() - self.started
        kind = event["kind"]
        if kind == "prepare":
            if event["done"] == 0 or wall - self.last.get("", -math.inf) >= self.every:
                self.last[""] = wall
                say(
                    f"{self.title}: preparing {event['total']} points (each checked, with its "
                    f"start): {event['done']} done ({wall:.1f} s)"
                )
        elif kind == "plan":
            self.total, self.done = event["total"], len(event["reused"])
            n = event["total"]
            say(
                f"{self.title}: {n} run{'s' if n != 1 else ''}, {len(event['reused'])} already "
                f"done, {len(event['pending'])} to run ({wall:.1f} s)"
            )
        elif kind == "update":
            name = event["name"]
            if wall - self.last.get(name, -math.inf) >= self.every:
                self.last[name] = wall
                say(
                    f"{self.title}: {name} t = {event['t']:.4g} / {event['t_end']:.4g} s, "
                    f"{event['steps']} steps ({wall:.1f} s)"
                )
        elif kind == "done":
            self.done += 1
            rec = event["record"]
            say(
                f"{self.title}: {event['name']} {run_status(rec)}; "
                f"{self.done} of {self.total} done ({wall:.1f} s)"
            )


@contextlib.contextmanager
def _progress(title: str, scheduler: str | None):
    """The progress callback of a study: live bars on a terminal (the whole study and
    one per running run), else lines."""
    if not console.is_terminal:
        yield _Lines(title)
        return
    from rich.progress import (
        BarColumn,
        Progress,
        TextColumn,
        TimeElapsedColumn,
    )

    columns = (
        TextColumn("{task.description}", markup=False),
        BarColumn(),
        TextColumn("{task.fields[what]}", markup=False),
        TimeElapsedColumn(),
    )
    with Progress(*columns, console=console, transient=False) as bar:
        where = "local cluster" if scheduler is None else scheduler
        overall = bar.add_task(plain(f"{title} ({where})"), total=None, what="")
        tasks: dict[str, Any] = {}
        ends: dict[str, float] = {}

        def show(event: dict) -> None:
            kind = event["kind"]
            if kind == "prepare":
                what = f"preparing points: {event['done']}/{event['total']}"
                bar.update(overall, total=event["total"], completed=event["done"], what=what)
            elif kind == "plan":
                ends.update(event.get("t_end", {}))
                done, total = len(event["reused"]), event["total"]
                bar.update(overall, total=total, completed=done, what=f"{done}/{total} runs")
                for name in event["pending"]:
                    tasks[name] = bar.add_task(
                        plain(f"  {name}"), total=ends.get(name), what="waiting", start=False
                    )
            elif kind == "update" and event["name"] in tasks:
                task = tasks[event["name"]]
                bar.start_task(task)
                bar.update(
                    task,
                    completed=event["t"],
                    what=f"t = {event['t']:.4g} / {event['t_end']:.4g} s, {event['steps']} steps",
                )
            elif kind == "done":
                rec = event["record"]
                task = tasks.get(event["name"])
                if task is not None:
                    bar.update(
                        task,
                        completed=rec.get("reached [s]", 0.0),
                        what=plain(run_status(rec)),
                    )
                    bar.stop_task(task)
                bar.advance(overall)
                total = bar.tasks[overall].total or 0
                done = int(bar.tasks[overall].completed)
                bar.update(overall, what=f"{done}/{total} runs")

        yield show
