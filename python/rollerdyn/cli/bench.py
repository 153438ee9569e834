"""``rollerdyn bench``: the command, its options and which target runs; the targets
themselves (tables of timings) are in :mod:`.bench_targets`."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Annotated

import typer

from ..names import GRADIENT, SEMI_ANALYTICAL
from ..paths import check_output_dir
from .bench_targets import (
    MAX_REPETITIONS,
    MAX_STEPS,
    bench_cases,
    bench_contact,
    bench_mbs,
    bench_model,
    bench_statics,
    bench_traction,
    runtime_study,
)
from .common import (
    SET_HELP,
    ConfigOption,
    checked,
    default_config,
    load,
    output_option,
    refuse,
    set_options,
    time_option,
)


def bench(
    target: Annotated[
        str,
        typer.Argument(
            help="What to time: 'traction' (EHL traction integral), 'contact' (roller "
            f"end/flange detection: {SEMI_ANALYTICAL}, pruned, {GRADIENT}), 'model' (one "
            "right-hand side and one Jacobian of the bearing model at a state), 'mbs' "
            f"(whole runs with the {SEMI_ANALYTICAL} and the {GRADIENT} detector), 'statics' "
            "(one quasi-static equilibrium and a load sweep) or 'all' (traction and contact)."
        ),
    ] = "all",
    repetitions: Annotated[
        int,
        typer.Option(
            min=1000,
            max=MAX_REPETITIONS,
            help="traction: evaluations timed per contact type (about 40 ns each with "
            "B1's tabulated traction: the default takes a few hundredths of a second, the "
            "most about 8 s).",
        ),
    ] = 200_000,
    steps: Annotated[
        int,
        typer.Option(
            min=10,
            max=MAX_STEPS,
            help="contact: trajectory steps of 1e-3 rad of roller-set azimuth (the default "
            "6283 is one revolution, about 2 s with the reference and mesh checks; the "
            "most, ten revolutions, about 20 s).",
        ),
    ] = 6283,
    t_end: Annotated[
        str | None,
        typer.Option(
            "--t-end",
            help="mbs: simulated end time, with a unit as in the configuration (50 ms, "
            "0.05 s) or a bare number of seconds (default: the configuration's, 1.288 s "
            "for B1). Not with --cases, whose cases run to their own ends.",
            metavar="TIME",
        ),
    ] = None,
    sweep_dt_max: Annotated[
        str | None,
        typer.Option(
            "--sweep-dt-max",
            help="mbs: the runtime study of the paper's fig. 14. Comma-separated maximum "
            "step sizes Δt_max in s (e.g. 1e-5,3e-5,1e-4); each is run with both detectors "
            "to --t-end, and the table and a plot (runtime over Δt_max) are written to "
            "--output.",
        ),
    ] = None,
    output: Annotated[
        str,
        output_option(
            help="mbs --sweep-dt-max: directory for table and plot; mbs --cases: directory "
            "for bench_cases.csv.",
        ),
    ] = "runtime-study",
    cases: Annotated[
        str | None,
        typer.Option(
            "--cases",
            help=f"mbs: comma-separated operating points to run with the {SEMI_ANALYTICAL} "
            "detector instead of the detector comparison: whole, full-speed-500rpm, "
            "full-speed-3000rpm, hot-3000rpm (the same with the oil at 120 degC), "
            "equilibrium-500rpm, equilibrium-3000rpm, free-tilt, "
            "tilt-0.05deg (inner_ring.misalignment), axial-0N, axial-500N, axial-2000N, "
            "axial-3000N, and distributed-NAME for NAME one of whole, hot-3000rpm, free-tilt, "
            "tilt-0.05deg and the axial-* (the distributed end-flange law); 'default' (whole, "
            "full-speed-500rpm, full-speed-3000rpm, free-tilt, axial-0N) or 'all'. Prints "
            "steps, Newton failures, right-hand sides, Jacobians (of them partial: "
            "solver.partial_jacobians), wall time [s] and simulated seconds per wall "
            "second, and writes "
            "bench_cases.csv to --output.",
        ),
    ] = None,
    threads: Annotated[
        str,
        typer.Option(
            "--threads",
            help="mbs --cases: thread counts to run each case on, comma-separated (e.g. 1,2); "
            "'all' for all cores; a count above the cores this process may use runs on "
            "those. Default 1.",
        ),
    ] = "1",
    max_wall: Annotated[
        float,
        typer.Option(
            "--max-wall",
            min=1.0,
            help="mbs --cases: wall time [s] after which a case is stopped and reported "
            "as far as it got.",
        ),
    ] = 300.0,
    state: Annotated[
        Path | None,
        typer.Option(
            "--state",
            help="model: a result file (netCDF from `rollerdyn run`) whose final state is "
            "timed, with the configuration the run records (its TOML text, --set changes "
            "included) unless --config names another of the same bearing (default: the "
            "consistent initial state of --config, where nothing is loaded yet).",
        ),
    ] = None,
    statics_cases: Annotated[
        int,
        typer.Option(
            "--statics-cases",
            min=2,
            max=100_000,
            help="statics: radial loads in the sweep, from half to twice the "
            "configuration's (its axial load kept).",
        ),
    ] = 1000,
    config: ConfigOption = None,
    settings: Annotated[
        list[str] | None,
        typer.Option(
            "--set",
            help=SET_HELP + " Changes the configuration of --config (or B1's) for every "
            "target, e.g. mbs with solver.rtol=1e-6 and solver.atol=1e-10.",
        ),
    ] = None,
) -> None:
    """Time the hot paths and print tables (times in ns per evaluation unless a column
    says otherwise).

    traction: one line slice and one elliptical contact with the configuration's
    traction model, on one core.

    contact: one roller end passing once around the bearing against an inner-ring flange
    of the configuration (steps of 1e-3 rad of roller-set azimuth), every method
    evaluating all six pairings; the gradient method warm-started from the previous step;
    accuracy against the reference solver every 100th step. For statistically careful
    numbers use "cargo bench -p rollerdyn-core".

    model: the mean time of one right-hand side (2 000 of them, each evaluating every
    contact) and one Jacobian (200, each taking its base evaluation from the one before at
    the same state, as a run's Jacobian takes the latest right-hand side's) at the final
    state of --state, in µs, and the right-hand side's split into detection, line contacts
    and flange forces. With the distributed end-flange law the overlaps start, as in a run,
    from the support frames a first evaluation at that state found.

    mbs: the whole run (to --t-end) on one core with each detector: wall time, steps,
    right-hand-side and Jacobian evaluations, and where the time goes: detection, line
    contacts and flange forces (summed over every contact evaluation, in right-hand sides
    and Jacobians alike), the time inside Jacobians, and the rest (linear algebra and the
    solver's own work); then how far the two runs agree (as `rollerdyn compare`), against
    0.1 µm for every roller's position, 1 % of the largest flange force and 0.1 % of the
    mean torque at full speed. With --sweep-dt-max: the runtime study of the paper's
    fig. 14; with --cases: whole runs of operating points.

    statics: one quasi-static equilibrium of the configuration's load case (ms, median of
    20) and a sweep of --statics-cases radial loads (s), in the core and with datasets.
    """
    if target not in ("traction", "contact", "model", "mbs", "statics", "all"):
        raise refuse(f"target = {target!r}: must be traction, contact, model, mbs, statics or all")
    _refuse_options_of_other_targets(
        target,
        {
            "--repetitions": repetitions != 200_000,
            "--steps": steps != 6283,
            "--t-end": t_end is not None,
            "--sweep-dt-max": sweep_dt_max is not None,
            "--cases": cases is not None,
            "--threads": threads != "1",
            "--max-wall": max_wall != 300.0,
            "--state": state is not None,
            "--statics-cases": statics_cases != 1000,
            "-o": output != "runtime-study",
        },
    )
    end = time_option("--t-end", t_end)
    dt_max_values = None if sweep_dt_max is None else _dt_max_values(sweep_dt_max)
    thread_counts = _thread_counts(threads)
    if cases is not None and t_end is not None:
        raise refuse(
            f"--t-end {t_end} with --cases: each case runs to its own end (the whole run, or "
            "0.1 s at full speed); --t-end sets the end of mbs's detector comparison and of "
            "--sweep-dt-max"
        )
    if target == "mbs" and (cases is not None or dt_max_values is not None):
        if not output.strip():  # an unset variable: the files would go to the current folder
            raise refuse(f"-o {output!r}: empty; give the folder for the files (. for this one)")
        checked(check_output_dir, Path(output), "-o")
    changes = set_options(settings)
    if changes and state is not None and config is None:
        raise refuse(
            "--set with --state: the state is timed with the configuration its run records; "
            "give --config as well to time it with a changed one"
        )
    cfg = load(config if config is not None else default_config(), changes)
    if target in ("traction", "all"):
        bench_traction(cfg, repetitions)
    if target in ("contact", "all"):
        bench_contact(cfg, steps)
    if target == "model":
        bench_model(cfg, state, config_given=config is not None)
    if target == "statics":
        bench_statics(cfg, statics_cases)
    if target == "mbs" and cases is not None:
        bench_cases(cfg, cases, thread_counts, max_wall, Path(output))
    elif target == "mbs" and dt_max_values is not None:
        path = config if config is not None else default_config()
        variants = [(v, _with_dt_max(path, changes, v)) for v in dt_max_values]
        runtime_study(variants, end, Path(output))
    elif target == "mbs":
        bench_mbs(cfg, end)


#: Where each option of ``bench`` applies (its target, or targets).
_APPLIES = {
    "--repetitions": ("traction", "all"),
    "--steps": ("contact", "all"),
    "--t-end": ("mbs",),
    "--sweep-dt-max": ("mbs",),
    "--cases": ("mbs",),
    "--threads": ("mbs",),
    "--max-wall": ("mbs",),
    "--state": ("model",),
    "--statics-cases": ("statics",),
    "-o": ("mbs",),
}


def _refuse_options_of_other_targets(target: str, given: dict[str, bool]) -> None:
    """Exits with status 2 naming an option given for a target it does not apply to (it
    was ignored without a word); also --threads, --max-wall and -o of mbs without
    --cases or --sweep-dt-max, which alone use them."""
    for option, was_given in given.items():
        if was_given and target not in _APPLIES[option]:
            where = " or ".join(t for t in _APPLIES[option] if t != "all")
            raise refuse(f"{option} applies to the target {where}, not to {target}")
    if target == "mbs" and given["--sweep-dt-max"] and given["--cases"]:
        raise refuse("--sweep-dt-max with --cases: give one (fig. 14's study, or the cases)")
    if target == "mbs" and not given["--cases"]:
        for option in ("--threads", "--max-wall"):
            if given[option]:
                raise refuse(f"{option} applies to mbs --cases only")
        if given["-o"] and not given["--sweep-dt-max"]:
            raise refuse("-o applies to mbs --cases and mbs --sweep-dt-max only (their files)")


def _with_dt_max(path: Path, changes: dict, dt_max: float):
    """The configuration with ``solver.dt_max`` set to a value of ``--sweep-dt-max``,
    checked by the configuration's rules (at least 1 ns, above solver.min_mean_step);
    exits with status 2 naming the option and the value otherwise."""
    from ..config import ConfigError, load_config

    try:
        return load_config(path, {**changes, "solver.dt_max": f"{dt_max!r} s"})
    except ConfigError as err:
        problems = "; ".join(str(p) for p in err.problems or ()) or str(err)
        raise refuse(f"--sweep-dt-max {dt_max:g}: {problems}") from None


def _dt_max_values(text: str) -> list[float]:
    """``--sweep-dt-max`` of ``bench``: comma-separated positive times in s, sorted, each
    once (a value given twice failed the study's table after every run)."""
    try:
        values = [float(v) for v in text.split(",") if v.strip()]
    except ValueError:
        values = []
    if not values or not all(v > 0.0 and math.isfinite(v) for v in values):
        raise refuse(
            f"--sweep-dt-max = {text!r}: must be comma-separated positive finite times in s, "
            "e.g. 1e-5,3e-5,1e-4"
        )
    return sorted(set(values))


def _thread_counts(text: str) -> list[int]:
    """``--threads`` of ``bench``: comma-separated counts or 'all', each capped at the cores
    this process may use (as the run caps them), without repeats; a capped count is named
    on stderr."""
    from ..simulation import default_threads

    cores = default_threads()
    counts: list[int] = []
    for part in text.split(","):
        part = part.strip()
        if part == "all":
            count = cores
        elif part.isdigit() and int(part) >= 1:
            count = int(part)
        else:
            raise refuse(
                f"--threads = {text!r}: must be comma-separated whole numbers >= 1 or 'all'"
            )
        if count > cores:
            typer.echo(
                f"--threads {count}: this process may use {cores} core(s); runs on {cores}",
                err=True,
            )
            count = cores
        if count not in counts:
            counts.append(count)
    return counts
