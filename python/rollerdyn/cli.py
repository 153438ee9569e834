"""The ``rollerdyn`` command line.

Commands: ``validate`` (every model against published values), ``check`` (validate a
configuration file and show its derived quantities), ``bench`` (time the hot paths),
``run``, ``plot``, ``sweep`` and ``report``. All inputs and outputs are SI unless a column
says otherwise.

Bad input (an option value, a configuration, a file that is no result, an output path
that cannot or must not be written, see :mod:`rollerdyn.paths`) exits with status 2 and
one message naming the option or field, the value and the rule, before any work. Every
message is printed as plain text (:func:`say`, :func:`error`): text from files and
options is never read as rich markup.
"""

from __future__ import annotations

import contextlib
import math
import signal
import time
from pathlib import Path
from typing import Annotated

import typer
from rich.console import Console
from rich.table import Table
from rich.text import Text

from .config import ConfigError, load_config
from .paths import (
    OutputPathError,
    check_output_dir,
    check_output_file,
    remove_stale_temporaries,
)

# rich_markup_mode=None: help texts are plain text (a "[s]" or "[arrays]" stays as typed)
# and click wraps each paragraph once to the terminal's width.
app = typer.Typer(
    help="rollerdyn: dynamics of full-complement cylindrical roller bearings.",
    no_args_is_help=True,
    add_completion=False,
    rich_markup_mode=None,
)
# markup=False: text from files and options (a bearing named "B1 [/x]", a file
# "nope[/x].nc") is printed as it is, never read as rich markup; colours are set with
# Text styles.
console = Console(markup=False, width=200 if not Console().is_terminal else None)

ConfigOption = Annotated[
    Path | None,
    typer.Option(
        "--config",
        "-c",
        help="Bearing configuration (TOML) for the B1-specific cases; "
        "default: examples/b1.toml of the source tree.",
    ),
]


def plain(text: object) -> str:
    """``text`` as printable text: bytes of a file name that are not UTF-8 (kept by
    Python as surrogates) shown as ``\\xff`` instead of failing to print."""
    try:
        raw = str(text).encode("utf-8", "surrogateescape")
    except UnicodeEncodeError:  # a surrogate that is no escaped byte
        raw = str(text).encode("utf-8", "backslashreplace")
    return raw.decode("utf-8", "backslashreplace")


def say(text: object, style: str | None = None, out: Console | None = None) -> None:
    """Prints ``text`` as it is (never as markup), unwrapped: one message, one line."""
    (out or console).print(Text(plain(text), style=style or ""), soft_wrap=True)


def error(text: object, out: Console | None = None) -> None:
    """Prints an error message in red, as it is (never as markup)."""
    say(text, "red", out)


def refuse(text: object, code: int = 2) -> typer.Exit:
    """Prints ``text`` as an error and returns the exit to raise (status 2: bad input)."""
    error(text)
    return typer.Exit(code)


def checked(check, *args, **kwargs):
    """``check(*args, **kwargs)`` of :mod:`rollerdyn.paths`; its refusal exits with 2."""
    try:
        return check(*args, **kwargs)
    except OutputPathError as err:
        raise refuse(err) from None


def time_option(option: str, text: str | None) -> float | None:
    """The value of a time option (``--t-end``) in s: ``"50 ms"``, ``"0.05 s"`` or a bare
    number of seconds (``"0.05"``); None stays None. Exits with status 2 naming the
    option, the value and the rule for anything but a positive, finite time."""
    from .units import QuantityError, parse_quantity

    if text is None:
        return None
    rule = "must be a positive time, e.g. 50 ms, 0.05 s or 0.05 (seconds)"
    try:
        value = float(text)
    except ValueError:
        try:
            value = parse_quantity(text.strip(), "time")
        except QuantityError as err:  # its first clause says what is wrong, then a hint
            reason = str(err).split("; ")[0]
            raise refuse(f"{option} = {text!r}: {reason}; {rule}") from None
    if not (math.isfinite(value) and value > 0.0):
        raise refuse(f"{option} = {text!r}: {rule}")
    return value


def _load(path: Path):
    """The configuration in ``path``; exits with status 2 and its problems if invalid."""
    try:
        return load_config(path)
    except ConfigError as err:
        text = str(err)
        error(
            text if text.startswith("invalid configuration") else f"invalid configuration\n{text}"
        )
        raise typer.Exit(2) from None


@app.command()
def validate(config: ConfigOption = None) -> None:
    """Check every model against published values and closed-form limits.

    Prints one row per case: group, case, source, expected and computed value (SI units),
    relative error, tolerance and pass/fail ("info" rows report a known model error and
    never fail). Exits with status 1 if any case fails.
    """
    from .validation import run

    cfg = _load(config) if config is not None else None
    table = Table(title="rollerdyn validation", show_lines=False)
    for col in ("group", "case", "source", "expected", "computed", "rel. error", "tol.", "pass"):
        table.add_column(col, overflow="fold")
    failures = 0
    with console.status(Text("running validation cases...")):
        results = list(run(cfg))
    for r in results:
        c = r.case
        verdict = (
            Text("info")
            if c.report_only
            else (Text("pass", style="green") if r.passed else Text("FAIL", style="red"))
        )
        failures += 0 if r.passed else 1
        table.add_row(
            c.group,
            c.name,
            c.source,
            f"{c.expected:.6g}",
            f"{r.computed:.6g}",
            f"{r.relative_error:.2e}",
            "-" if c.report_only else f"{c.rtol:.0e}",
            verdict,
        )
    console.print(table)
    total = len(results)
    console.print(f"{total - failures} passed, {failures} failed")
    if failures:
        raise typer.Exit(1)


@app.command()
def check(
    config: Annotated[Path, typer.Argument(help="Bearing configuration (TOML).", metavar="CONFIG")],
) -> None:
    """Validate a configuration file and print its derived quantities (SI units).

    Shows roller diameter, pitch diameter, gap between rollers, roller mass and inertias,
    end time, lubricant state at the run temperature (eta0, Roelands z, alpha*) and the
    line-contact power laws (eq. 11) fitted to Tripp with their errors.
    """
    from .model import Model

    cfg = _load(config)
    model = Model(cfg)
    g = cfg.geometry
    rows = [
        ("roller diameter", g.roller_diameter, "m"),
        ("pitch diameter", g.pitch_diameter, "m"),
        ("gap between neighbouring rollers", g.circumferential_gap, "m"),
        ("roller mass", cfg.roller_mass, "kg"),
        ("roller axial inertia", cfg.roller_axial_inertia, "kg m^2"),
        ("roller transverse inertia", cfg.roller_transverse_inertia, "kg m^2"),
        ("roller-set speed at full speed", cfg.roller_set_speed, "rad/s"),
        ("end time", cfg.end_time, "s"),
        ("eta0 at run temperature", model.eta0, "Pa s"),
        ("Roelands z", model.roelands_z, "-"),
        ("alpha* (eq. 32 fit)", model.alpha_star, "1/Pa"),
        ("alpha* fit max. relative error", model.alpha_star_fit["max_relative_error"], "-"),
    ]
    for name, law in model.line_contacts.items():
        rows.append((f"eq. 11 roller-{name}: k1", law.k1, "SI"))
        rows.append((f"eq. 11 roller-{name}: k2", law.k2, "-"))
        rows.append((f"eq. 11 roller-{name}: max force error vs Tripp", law.max_force_error, "-"))
    table = Table(title=f"{cfg.name}: derived quantities")
    for col in ("quantity", "value", "unit"):
        table.add_column(col)
    for name, value, unit in rows:
        table.add_row(name, f"{value:.6g}", unit)
    console.print(table)


@app.command()
def bench(
    target: Annotated[
        str,
        typer.Argument(
            help="What to time: 'traction' (EHL traction integral), 'contact' (roller "
            "end/flange detection: semi-analytical, pruned, gradient), 'model' (one "
            "right-hand side and one Jacobian of the bearing model at a state), 'mbs' "
            "(whole runs with the semi-analytical and the gradient detector) or 'all' "
            "(traction and contact)."
        ),
    ] = "all",
    repetitions: Annotated[
        int, typer.Option(min=1000, help="Traction evaluations timed per contact type.")
    ] = 200_000,
    steps: Annotated[
        int, typer.Option(min=10, help="Trajectory steps of the contact benchmark.")
    ] = 6283,
    t_end: Annotated[
        str | None,
        typer.Option(
            "--t-end",
            help="mbs: simulated end time, with a unit as in the configuration (50 ms, "
            "0.05 s) or a bare number of seconds (default: the configuration's, 1.288 s "
            "for B1).",
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
        Path,
        typer.Option(
            "--output",
            "-o",
            help="mbs --sweep-dt-max: directory for table and plot; mbs --cases: directory "
            "for bench_cases.csv.",
        ),
    ] = Path("runtime-study"),
    cases: Annotated[
        str | None,
        typer.Option(
            "--cases",
            help="mbs: comma-separated operating points to run with the semi-analytical "
            "detector instead of the detector comparison: whole, full-speed-500rpm, "
            "full-speed-3000rpm, equilibrium-500rpm, equilibrium-3000rpm, free-tilt, axial-0N, "
            "axial-500N, axial-2000N, axial-3000N; "
            "'default' (the first five) or 'all'. Prints steps, Newton failures, right-hand "
            "sides, wall time [s] and simulated seconds per wall second, and writes "
            "bench_cases.csv to --output.",
        ),
    ] = None,
    threads: Annotated[
        str,
        typer.Option(
            "--threads",
            help="mbs --cases: thread counts to run each case on, comma-separated (e.g. 1,2); "
            "'all' for all cores. Default 1.",
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
            help="model: a result file (netCDF from `rollerdyn run`) of the same "
            "configuration whose final state is timed (default: the consistent initial "
            "state, where nothing is loaded yet).",
        ),
    ] = None,
    config: ConfigOption = None,
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

    model: the mean time of one right-hand side (2 000 of them) and one Jacobian (200) at
    the final state of --state, in µs, and the right-hand side's split into detection,
    line contacts and flange forces.

    mbs: the whole run (to --t-end) on one core with each detector: wall time, steps,
    right-hand-side and Jacobian evaluations, and where the time goes: detection, line
    contacts and flange forces (summed over every contact evaluation, in right-hand sides
    and Jacobians alike), the time inside Jacobians, and the rest (linear algebra and the
    solver's own work). With --sweep-dt-max: the runtime study of the paper's fig. 14;
    with --cases: whole runs of operating points.
    """
    from .validation import default_config_path

    if target not in ("traction", "contact", "model", "mbs", "all"):
        raise refuse(f"target = {target!r}: must be traction, contact, model, mbs or all")
    end = time_option("--t-end", t_end)
    dt_max_values = None if sweep_dt_max is None else _dt_max_values(sweep_dt_max)
    thread_counts = _thread_counts(threads)
    if target == "mbs" and (cases is not None or dt_max_values is not None):
        checked(check_output_dir, output, "-o")
    cfg = _load(config if config is not None else default_config_path())
    if target in ("traction", "all"):
        _bench_traction(cfg, repetitions)
    if target in ("contact", "all"):
        _bench_contact(cfg, steps)
    if target == "model":
        _bench_model(cfg, state)
    if target == "mbs" and cases is not None:
        _bench_cases(cfg, cases, thread_counts, max_wall, output)
    elif target == "mbs" and dt_max_values is not None:
        _runtime_study(cfg, end, dt_max_values, output)
    elif target == "mbs":
        _bench_mbs(cfg, end)


def _dt_max_values(text: str) -> list[float]:
    """``--sweep-dt-max`` of ``bench``: comma-separated positive times in s, sorted."""
    try:
        values = [float(v) for v in text.split(",") if v.strip()]
    except ValueError:
        values = []
    if not values or not all(v > 0.0 and math.isfinite(v) for v in values):
        raise refuse(
            f"--sweep-dt-max = {text!r}: must be comma-separated positive times in s, "
            "e.g. 1e-5,3e-5,1e-4"
        )
    return sorted(values)


def _bench_traction(cfg, repetitions: int) -> None:
    """One line slice and one ellipse of the configuration's traction model, timed."""
    from .model import Model

    traction = Model(cfg).traction
    traction.time_per_evaluation(10_000)  # warm-up
    line, ellipse = traction.time_per_evaluation(repetitions)
    table = Table(title="EHL traction evaluation (one core)")
    for col in ("contact", "time per evaluation [ns]", "scheme"):
        table.add_column(col)
    scheme = f"{cfg.solver.traction} ({cfg.solver.traction_nodes} nodes direct)"
    table.add_row("line slice", f"{line:.0f}", scheme)
    table.add_row("ellipse", f"{ellipse:.0f}", scheme)
    console.print(table)


def _bench_model(cfg, state: Path | None) -> None:
    """One right-hand side and one Jacobian of the model, timed at a state."""
    import numpy as np

    from . import _core
    from .model import Model
    from .simulation import model_parameters

    params = model_parameters(cfg, cfg.solver.detector)
    traction = Model(cfg).traction
    if state is None:
        t, y, where = 0.0, _core.initial_state(params, traction), "the initial state"
    else:
        from .report import ReportError, open_result

        try:
            ds = open_result(state, required=("final_state",))
        except ReportError as err:
            raise refuse(f"--state {err}") from None
        y = np.asarray(ds["final_state"].values, dtype=float).tolist()
        t = float(ds.attrs["final_time_s"])
        where = f"the final state of {state} (t = {t:.6g} s)"
    try:
        r = _core.model_timing(params, traction, t, y, 2000, 200)
    except ValueError as err:
        raise refuse(f"--state {state}: {err}") from None
    table = Table(title=f"{cfg.name}: the model at {where}, one core")
    for col in ("", "time [µs]"):
        table.add_column(col)
    table.add_row("right-hand side", f"{r['rhs_seconds'] * 1e6:.1f}")
    table.add_row("  roller end/flange detection", f"{r['detection_seconds'] * 1e6:.1f}")
    table.add_row("  line contacts (slices)", f"{r['line_contact_seconds'] * 1e6:.1f}")
    table.add_row("  roller end/flange forces", f"{r['flange_force_seconds'] * 1e6:.1f}")
    table.add_row("Jacobian", f"{r['jacobian_seconds'] * 1e6:.1f}")
    console.print(table)
    console.print(
        f"{r['states']} states; a Jacobian costs {r['jacobian_seconds'] / r['rhs_seconds']:.1f} "
        f"right-hand sides; {r['detections']:.0f} detections per right-hand side"
    )


def _mbs_runs(cfg, t_end: float | None, label: str = "") -> list:
    """(detector, attrs) of one whole run with each detector."""
    from .simulation import SimulationError, simulate

    rows = []
    for detector in ("semi-analytical", "gradient"):
        with console.status(Text(f"running {cfg.name}{label} with the {detector} detector...")):
            try:
                ds = simulate(cfg, t_end=t_end, detector=detector)
            except SimulationError as err:
                ds = err.dataset
        rows.append((detector, ds.attrs))
    return rows


def _runtime_study(cfg, t_end: float | None, dt_max_values: list, out: Path) -> None:
    """The paper's fig. 14: wall time of whole runs over Δt_max, both detectors."""
    import pandas as pd

    from .plots import plot_runtime_study

    records = []
    for dt_max in dt_max_values:
        solver = cfg.solver.model_copy(update={"dt_max": dt_max})
        variant = cfg.model_copy(update={"solver": solver})
        for detector, a in _mbs_runs(variant, t_end, f" (dt_max = {dt_max:g} s)"):
            records.append(
                {
                    "dt_max_s": dt_max,
                    "detector": detector,
                    "wall_s": a["stats_total_seconds"],
                    "t_reached_s": a["final_time_s"],
                    "completed": int(a["completed"]),
                    "steps": a["stats_steps"],
                    "rejected_steps": a.get("stats_error_test_failures", 0),
                    "rhs": a["stats_rhs_evaluations"],
                    "jacobians": a["stats_jacobian_evaluations"],
                    "gradient_fallbacks": a.get("stats_gradient_fallbacks", 0),
                }
            )
    frame = pd.DataFrame.from_records(records)
    out.mkdir(parents=True, exist_ok=True)
    frame.to_csv(out / "runtime_study.csv", index=False)
    paths = plot_runtime_study(frame, out, title=f"{cfg.name}: runtime over Δt_max")
    table = Table(title=f"{cfg.name}: runtime study (paper fig. 14), one core")
    cols = ("Δt_max [s]", "detector", "wall [s]", "t reached [s]", "steps", "rejected", "fallbacks")
    for col in cols:
        table.add_column(col)
    for r in records:
        table.add_row(
            f"{r['dt_max_s']:g}",
            r["detector"],
            f"{r['wall_s']:.2f}",
            f"{r['t_reached_s']:.4g}",
            str(r["steps"]),
            str(r["rejected_steps"]),
            str(r["gradient_fallbacks"]),
        )
    console.print(table)
    pivot = frame.pivot(index="dt_max_s", columns="detector", values=["wall_s", "t_reached_s"])
    for dt_max, row in pivot.iterrows():
        reached = row["t_reached_s"]
        if reached["semi-analytical"] != reached["gradient"]:
            console.print(f"Δt_max = {dt_max:g} s: the runs ended at different times")
            continue
        saving = 100 * (1 - row["wall_s"]["semi-analytical"] / row["wall_s"]["gradient"])
        console.print(f"Δt_max = {dt_max:g} s: semi-analytical {saving:.0f} % below gradient")
    say(f"wrote {out / 'runtime_study.csv'} and " + ", ".join(str(p) for p in paths))


def _thread_counts(text: str) -> list[int]:
    """``--threads`` of ``bench``: comma-separated counts or 'all'."""
    from .simulation import default_threads

    counts = []
    for part in text.split(","):
        part = part.strip()
        if part == "all":
            counts.append(default_threads())
        elif part.isdigit() and int(part) >= 1:
            counts.append(int(part))
        else:
            raise refuse(
                f"--threads = {text!r}: must be comma-separated whole numbers >= 1 or 'all'"
            )
    return counts


def _bench_cases(cfg, cases: str, thread_counts: list, max_wall: float, out: Path) -> None:
    """Whole runs of the operating points of :mod:`rollerdyn.bench_cases` on the given
    thread counts."""
    import pandas as pd

    from .bench_cases import CASES, DEFAULT_CASES, run_case

    if cases.strip() == "default":
        names = list(DEFAULT_CASES)
    elif cases.strip() == "all":
        names = list(CASES)
    else:
        names = [c.strip() for c in cases.split(",") if c.strip()]
    unknown = [n for n in names if n not in CASES]
    if not names or unknown:
        what = ", ".join(unknown) or "empty"
        raise refuse(
            f"--cases = {cases!r}: {what} not a case; choose from {', '.join(CASES)}, "
            "default or all"
        )
    results = []
    for name in names:
        for n in thread_counts:
            with console.status(Text(f"{cfg.name}: case {name} ({CASES[name][0]})...")) as status:

                def show(p, status=status, name=name, n=n) -> None:
                    status.update(
                        Text(
                            f"{cfg.name}: case {name} on {n} thread(s), t = {p.time:.4f} / "
                            f"{p.t_end:.4f} s, {p.steps} steps"
                        )
                    )

                results.append(run_case(cfg, name, max_wall, show, threads=n))
    table = Table(title=f"{cfg.name}: operating points, semi-analytical detector")
    cols = (
        "case",
        "threads",
        "simulated [s]",
        "wall [s]",
        "sim s / wall s",
        "steps",
        "rejected",
        "Newton failures",
        "rhs",
        "Jacobians",
        "torque [N m]",
        "note",
    )
    for col in cols:
        table.add_column(col)
    for r in results:
        table.add_row(
            r.name,
            str(r.threads),
            f"{r.reached:.4g} of {r.target:.4g}",
            f"{r.wall:.1f}",
            f"{r.sim_per_wall:.3g}",
            str(r.steps),
            str(r.rejected),
            str(r.newton_failures),
            str(r.rhs),
            str(r.jacobians),
            f"{r.torque:.4g}",
            r.message,
        )
    console.print(table)
    out.mkdir(parents=True, exist_ok=True)
    frame = pd.DataFrame.from_records(
        [{**r.__dict__, "sim_per_wall": r.sim_per_wall} for r in results]
    )
    frame.to_csv(out / "bench_cases.csv", index=False)
    say(f"wrote {out / 'bench_cases.csv'}")


def _bench_mbs(cfg, t_end: float | None) -> None:
    rows = _mbs_runs(cfg, t_end)
    reached = rows[0][1]["final_time_s"]
    table = Table(title=f"{cfg.name}: whole run to t = {reached:.4g} s, one core")
    cols = (
        "detector",
        "wall [s]",
        "steps",
        "rejected",
        "rhs",
        "Jacobians",
        "LU setups",
        "detection [s]",
        "line contacts [s]",
        "flange forces [s]",
        "in Jacobians [s]",
        "rest [s]",
        "gradient fallbacks",
    )
    for col in cols:
        table.add_column(col)
    for detector, a in rows:
        rest = a["stats_total_seconds"] - a["stats_rhs_seconds"] - a["stats_jacobian_seconds"]
        table.add_row(
            detector,
            f"{a['stats_total_seconds']:.2f}",
            str(a["stats_steps"]),
            str(a.get("stats_error_test_failures", 0)),
            str(a["stats_rhs_evaluations"]),
            str(a["stats_jacobian_evaluations"]),
            str(a.get("stats_linear_solver_setups", "")),
            f"{a['stats_detection_seconds']:.2f}",
            f"{a['stats_line_contact_seconds']:.2f}",
            f"{a['stats_flange_force_seconds']:.2f}",
            f"{a['stats_jacobian_seconds']:.2f}",
            f"{rest:.2f}",
            str(a.get("stats_gradient_fallbacks", 0)),
        )
    console.print(table)
    semi, grad = rows[0][1]["stats_total_seconds"], rows[1][1]["stats_total_seconds"]
    console.print(
        f"semi-analytical run time {100 * (1 - semi / grad):.0f} % below the gradient method's "
        "(paper sect. 5.3: 35 %)"
    )


def _bench_contact(cfg, steps: int) -> None:
    from . import _core

    g = cfg.geometry
    fl = g.inner_flange
    with console.status(Text("timing roller end / flange detection...")):
        r = _core.contact_benchmark(
            roller_diameter=g.roller_diameter,
            roller_length=g.roller.length,
            edge_radius=g.roller.edge_radius,
            end_face_radius=g.roller.end_face_radius,
            opening_angle=fl.opening_angle,
            flange_height=fl.height,
            root_radius=fl.root_radius,
            rim_radius=fl.rim_radius,
            raceway_radius=g.inner_raceway_diameter / 2,
            pitch_radius=g.pitch_diameter / 2,
            axial_play=fl.axial_play,
            steps=steps,
            mesh_every=max(1, steps // 8),
            mesh_resolutions=[(32, 8), (64, 16), (128, 32)],
        )
    table = Table(title=f"Roller end / flange detection, {r['evaluations']} trajectory steps")
    for col in (
        "method",
        "time per evaluation [ns]",
        "gradient (6 pairings) / this",
        "gradient, pruned / this",
    ):
        table.add_column(col)
    for name, key in (
        ("semi-analytical (6 pairings)", "semi_analytical_ns"),
        ("semi-analytical, pruned", "pruned_ns"),
        ("semi-analytical composite only (torus-torus when needed)", "composite_ns"),
        ("semi-analytical composite, pruned (overlap only)", "pruned_composite_ns"),
        ("gradient (Koch), warm-started, 6 pairings", "gradient_ns"),
        ("gradient (Koch), warm-started, pruned", "gradient_pruned_ns"),
    ):
        table.add_row(
            name,
            f"{r[key]:.0f}",
            f"{r['gradient_ns'] / r[key]:.1f}x",
            f"{r['gradient_pruned_ns'] / r[key]:.1f}x",
        )
    console.print(table)
    facts = Table(title="Detection details")
    facts.add_column("quantity")
    facts.add_column("value")
    facts.add_row("steps with overlap", str(r["steps_in_contact"]))
    facts.add_row(
        "gradient: mean Newton iterations per pairing", f"{r['gradient_mean_iterations']:.2f}"
    )
    solves = 6 * r["evaluations"]
    facts.add_row(
        "gradient: pairing solves not converged", f"{r['gradient_not_converged']} of {solves}"
    )
    facts.add_row(
        "gradient: converged to a wrong stationary point (normals not opposite)",
        f"{r['gradient_wrong_stationary']} of {solves}",
    )
    facts.add_row(
        "gradient: steps whose composite differs from semi-analytical",
        str(r["gradient_wrong_composite"]),
    )
    facts.add_row("pruning: pairings skipped", f"{r['pruned_pairings']} of {6 * r['evaluations']}")
    facts.add_row("pruning: whole flange skipped", f"{r['pruned_flanges']} of {r['evaluations']}")
    facts.add_row(
        "semi-analytical vs reference: max |dPm| [m]", f"{r['semi_max_location_error']:.2e}"
    )
    facts.add_row(
        "semi-analytical vs reference: max |d delta| [m]",
        f"{r['semi_max_penetration_error']:.2e} ({r['reference_checks']} checks)",
    )
    console.print(facts)
    mesh = Table(title="Mesh baseline (parry3d-f64 triangle meshes, meshing included)")
    for col in (
        "segments around x along",
        "time per evaluation [ms]",
        "max |d delta| [m]",
        "samples",
    ):
        mesh.add_column(col)
    for around, along, ns, error, samples in r.get("mesh", []):
        mesh.add_row(f"{around} x {along}", f"{ns / 1e6:.2f}", f"{error:.2e}", str(samples))
    console.print(mesh)


# --------------------------------------------------------------------------- runs


@app.command()
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
            help="Roller end / flange detector: semi-analytical, gradient or mesh. "
            "Default: solver.detector of the configuration (semi-analytical).",
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
            "(100 ms) or a bare number of seconds (0.1): the result file is rewritten and "
            "the solver restarted every TIME; at most this much simulated time is lost "
            "after kill -9. Overrides solver.checkpoint_interval of the configuration "
            "(default 100 ms). With --resume the default is the earlier run's interval, "
            "which a bit-for-bit continuation needs (another interval changes the result "
            "within the tolerances).",
            metavar="TIME",
        ),
    ] = None,
    threads: Annotated[
        int | None,
        typer.Option(
            "--threads",
            min=1,
            help="Threads that evaluate the contacts and the Jacobian's columns (default: all "
            "cores; the gradient detector always uses one). The result does not depend on "
            "it, bit for bit.",
        ),
    ] = None,
    force: Annotated[
        bool,
        typer.Option(
            "--force",
            help="Run even when the estimated result size or cost is far beyond a normal "
            "run (the refusal prints the estimate).",
        ),
    ] = False,
) -> None:
    """Run the dynamic simulation and write its results to a netCDF file.

    Units: SI throughout the file (every variable has a 'units' attribute; time in s,
    forces in N, torques in N*m, angles in rad, speeds in rad/s). Outputs are saved every
    solver.output_interval by interpolation.

    Progress: on a terminal a bar shows simulated time, solver steps, speed (simulated
    time per wall second) and the time left; otherwise (a log, a pipe) one line is
    printed at every 10 % of the simulated time and at least every 10 s.

    The output is checked before the run: its folder must exist and be writable, and an
    existing file is only replaced with --overwrite (or continued with --resume naming
    it). If the run fails or is interrupted (Ctrl-C), everything computed until then is
    written and the command exits with status 1 (130 after Ctrl-C, 143 after SIGTERM).
    The result file is also written at every checkpoint (every --checkpoint-interval of
    simulated time, by default solver.checkpoint_interval, 100 ms; atomically), so after
    kill -9 or a crash it holds the run up to the last checkpoint, and --resume finishes
    the run. Bad input exits with status 2 before any work.
    """
    from .simulation import SimulationError, resume_state, simulate, write

    if detector is not None and detector not in ("semi-analytical", "gradient", "mesh"):
        raise refuse(f"--detector = {detector!r}: must be semi-analytical, gradient or mesh")
    interval = time_option("--checkpoint-interval", checkpoint_interval)
    end = time_option("--t-end", t_end)
    cfg = _load(config)
    end = cfg.end_time if end is None else end
    _check_run_output(output, config, resume, overwrite)
    previous = None if resume is None else _open_resume(resume, end)
    if interval is None and previous is not None:
        earlier = previous.attrs.get("checkpoint_interval_s")
        if earlier is not None and math.isfinite(float(earlier)) and float(earlier) > 0.0:
            interval = float(earlier)
    if interval is not None:
        solver = cfg.solver.model_copy(update={"checkpoint_interval": float(interval)})
        cfg = cfg.model_copy(update={"solver": solver})
    for tmp, pid in remove_stale_temporaries(output):
        say(f"removed {tmp}: a temporary file of process {pid}, which no longer runs")
    t_start = 0.0 if previous is None else float(resume_state(previous)[0])
    unsaved: list[OSError] = []  # a checkpoint that could not be written stops the run

    def checkpoint(partial) -> None:
        try:
            write(partial, output)
        except OSError as err:
            unsaved.append(err)

    status = 0
    with _run_progress(cfg.name, t_start, end) as show:
        # SIGTERM (a batch system or `kill`) stops the run like Ctrl-C: at the next output
        # time, with everything computed so far written (exit status 143).
        previous_handler = signal.signal(signal.SIGTERM, _terminate)
        try:
            ds = simulate(
                cfg,
                t_end=end,
                detector=detector,
                progress=lambda p: show(p) or bool(unsaved),
                resume=previous,
                checkpoint=checkpoint,
                threads=threads,
                **({"force": True} if force else {}),
            )
        except ValueError as err:
            raise refuse(err) from None
        except SimulationError as err:
            ds = err.dataset
            status = _stop_status(str(err))
            error(f"run stopped: {err}")
        finally:
            signal.signal(signal.SIGTERM, previous_handler)
    if unsaved:
        raise refuse(f"-o {output}: could not write the checkpoint ({unsaved[0]}); run stopped", 1)
    try:
        write(ds, output)
    except OSError as err:
        raise refuse(f"-o {output}: could not write the result ({err})", 1) from None
    say(_run_line(output, ds))
    if status:
        raise typer.Exit(status)


def _stop_status(message: str) -> int:
    """Exit status of a run stopped by ``message``: 143 SIGTERM, 130 Ctrl-C, else 1."""
    if "SIGTERM" in message:
        return 143
    return 130 if "KeyboardInterrupt" in message else 1


def _check_run_output(output: Path, config: Path, resume: Path | None, overwrite: bool) -> None:
    """Exits with status 2 unless ``run`` may write ``output`` (see :mod:`rollerdyn.paths`):
    an existing file only with --overwrite or as the --resume file."""
    from .paths import same_file

    in_place = resume is not None and same_file(output, resume)
    checked(
        check_output_file,
        output,
        "-o",
        inputs=[("the configuration file", config)],
        overwrite=overwrite or in_place,
        hint="; pass --overwrite to replace it, or --resume with the same file to continue its run",
    )


def _open_resume(resume: Path, end: float):
    """The earlier result of ``--resume``, loaded; exits with status 2 naming the file and
    what is wrong if it is no rollerdyn result or already reached ``end``."""
    from .report import REQUIRED, ReportError, open_result

    try:
        previous = open_result(resume, required=(*REQUIRED, "final_state"))
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
        f"{st['stats_jacobian_evaluations']} Jacobians, {st['stats_total_seconds']:.1f} s wall "
        f"on {st.get('threads', 1)} thread(s)"
    )


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
        yield ProgressLines(name, t_start, t_end)
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


def _terminate(signum, frame) -> None:
    """SIGTERM handler of `run`: raised inside the core's signal check, it stops the run."""
    raise KeyboardInterrupt("terminated by SIGTERM")


@app.command()
def plot(
    results: Annotated[
        list[Path],
        typer.Argument(help="Result files (netCDF) of rollerdyn run.", metavar="RESULT"),
    ],
    out: Annotated[
        Path,
        typer.Option(
            "--output",
            "-o",
            help="Folder for the figures; created if missing (its parent must exist). "
            "Figures of the same names in it are replaced.",
        ),
    ] = Path("plots"),
) -> None:
    """Draw the paper's figures from result files (PNG and SVG, axes in SI units).

    Bearing frictional torque over time (fig. 10), flange friction force of roller 0 over
    time (fig. 11), axial force of a roller over its azimuth (fig. 12), slide-to-roll
    ratio at the inner race over azimuth (fig. 13), roller loads over azimuth, and the
    roller end / flange pairings in contact (figs. 8, 9). A missing file or one that is
    not a rollerdyn result exits with status 2.
    """
    from .plots import plot_results
    from .report import ReportError

    checked(check_output_dir, out, "-o")
    try:
        written = plot_results(results, out)
    except ReportError as err:
        raise refuse(err) from None
    except OSError as err:
        raise refuse(f"-o {out}: could not write the figures ({err})", 1) from None
    for w in written:
        say(f"wrote {w}")


# --------------------------------------------------------------------------- sweeps

from .sweep import sweep_command  # noqa: E402

app.command("sweep")(sweep_command)


# --------------------------------------------------------------------------- report

from .report import report_command  # noqa: E402

app.command("report")(report_command)


if __name__ == "__main__":  # pragma: no cover
    app()
