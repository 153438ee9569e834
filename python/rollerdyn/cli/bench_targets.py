"""The targets of ``rollerdyn bench``: EHL traction, roller end / flange detection, one
right-hand side and Jacobian of the model, and whole runs (both detectors, the runtime
study of the paper's fig. 14, the operating points of :mod:`rollerdyn.bench_cases`). Each
prints its tables; :mod:`.bench` parses the options and picks the target."""

from __future__ import annotations

from pathlib import Path

from rich.table import Table
from rich.text import Text

from ..names import GRADIENT, SEMI_ANALYTICAL
from .common import console, refuse, say

#: Most traction evaluations per contact type (about 40 ns each with B1's tabulated
#: traction: some 8 s for both types).
MAX_REPETITIONS = 100_000_000
#: Most trajectory steps of the contact benchmark (ten revolutions; about 0.35 ms a step
#: with its reference and mesh checks: some 20 s).
MAX_STEPS = 62_830


def _interruptible(call, *args, **kwargs):
    """``call(*args, **kwargs)`` (a core function that holds no Python lock while it runs)
    in a helper thread, the main thread waiting in short slices: Ctrl-C stops the command
    at once instead of when the call returns (the benchmark's timing loops have no point
    at which the core asks for signals); the abandoned call ends with the process."""
    import threading

    done: dict = {}

    def target() -> None:
        try:
            done["value"] = call(*args, **kwargs)
        except BaseException as err:  # handed to the main thread
            done["error"] = err

    worker = threading.Thread(target=target, daemon=True)
    worker.start()
    while worker.is_alive():
        worker.join(0.1)
    if "error" in done:
        raise done["error"]
    return done["value"]


def bench_traction(cfg, repetitions: int) -> None:
    """One line slice and one ellipse of the configuration's traction model, timed."""
    from ..model import Model

    traction = Model(cfg).traction
    traction.time_per_evaluation(10_000)  # warm-up
    line, ellipse = _interruptible(traction.time_per_evaluation, repetitions)
    table = Table(title="EHL traction evaluation (one core)")
    for col in ("contact", "time per evaluation [ns]", "scheme"):
        table.add_column(col)
    scheme = f"{cfg.solver.traction} ({cfg.solver.traction_nodes} nodes direct)"
    table.add_row("line slice", f"{line:.0f}", scheme)
    table.add_row("ellipse", f"{ellipse:.0f}", scheme)
    console.print(table)


def bench_model(cfg, state: Path | None, config_given: bool = False) -> None:
    """One right-hand side and one Jacobian of the model, timed at a state: the final state
    of the result ``state`` with the configuration it records (``cfg`` if
    ``config_given``), or the initial state of ``cfg``."""
    import numpy as np

    from .. import _core
    from ..model import Model
    from ..simulation import model_parameters

    if state is None:
        y = None
        where = "the initial state"
    else:
        from ..modes import run_config
        from ..report import ReportError, open_result

        try:
            ds = open_result(state, required=("final_state",))
        except ReportError as err:
            raise refuse(f"--state {err}") from None
        if not config_given:
            try:
                cfg = run_config(ds)
            except ValueError as err:
                raise refuse(f"--state {state}: {' '.join(str(err).split())}") from None
        y = np.asarray(ds["final_state"].values, dtype=float).tolist()
        t = float(ds.attrs["final_time_s"])
        where = f"the final state of {state} (t = {t:.6g} s)"
    model = _core.Model(model_parameters(cfg, cfg.solver.detector), Model(cfg).traction)
    if y is None:
        t, y = 0.0, model.initial_state()
    try:
        r = model.timing(t, y, 2000, 200)
    except ValueError as err:
        raise refuse(f"--state {state}: {err}") from None
    law = f"{cfg.surfaces.flange_law} end-flange law"
    table = Table(title=f"{cfg.name} ({law}): the model at {where}, one core")
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
    """(detector, attrs) of one whole run with each detector, each on one thread (the
    gradient detector's runs always are: ``simulate``), so that the two are compared as
    the paper compares them and as the tables say."""
    from ..simulation import SimulationError, SimulationInterrupted, simulate

    rows = []
    for detector in (SEMI_ANALYTICAL, GRADIENT):
        with console.status(Text(f"running {cfg.name}{label} with the {detector} detector...")):
            try:
                ds = simulate(cfg, t_end=t_end, detector=detector, threads=1)
            except SimulationInterrupted:
                raise  # Ctrl-C stops the benchmark, not only this run
            except SimulationError as err:
                ds = err.dataset
        rows.append((detector, ds))
    return rows


def runtime_study(variants: list, t_end: float | None, out: Path) -> None:
    """The paper's fig. 14: wall time of whole runs over Δt_max, both detectors;
    ``variants``: (Δt_max [s], the configuration with it) in order."""
    import pandas as pd

    from ..plots import plot_runtime_study

    records = []
    for dt_max, variant in variants:
        for detector, ds in _mbs_runs(variant, t_end, f" (dt_max = {dt_max:g} s)"):
            a = ds.attrs
            records.append(
                {
                    "dt_max_s": dt_max,
                    "detector": detector,
                    "threads": a["threads"],
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
    name = variants[0][1].name
    paths = plot_runtime_study(frame, out, title=f"{name}: runtime over Δt_max")
    table = Table(title=f"{name}: runtime study (paper fig. 14), one core")
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
        if reached[SEMI_ANALYTICAL] != reached[GRADIENT]:
            console.print(f"Δt_max = {dt_max:g} s: the runs ended at different times")
            continue
        saving = 100 * (1 - row["wall_s"][SEMI_ANALYTICAL] / row["wall_s"][GRADIENT])
        console.print(f"Δt_max = {dt_max:g} s: {SEMI_ANALYTICAL} {saving:.0f} % below {GRADIENT}")
    say(f"wrote {out / 'runtime_study.csv'} and " + ", ".join(str(p) for p in paths))


def bench_cases(cfg, cases: str, thread_counts: list, max_wall: float, out: Path) -> None:
    """Whole runs of the operating points of :mod:`rollerdyn.bench_cases` on the given
    thread counts."""
    import pandas as pd

    from ..bench_cases import CASES, DEFAULT_CASES, run_case

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
    table = Table(title=f"{cfg.name}: operating points, {SEMI_ANALYTICAL} detector")
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
        "Jacobians (partial)",
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
            f"{r.jacobians} ({r.partial_jacobians})",
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


def bench_mbs(cfg, t_end: float | None) -> None:
    """Whole runs (to ``t_end``) with each detector on one core: where the time goes."""
    runs = _mbs_runs(cfg, t_end)
    rows = [(detector, ds.attrs) for detector, ds in runs]
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
        f"{SEMI_ANALYTICAL} run time {100 * (1 - semi / grad):.0f} % below the {GRADIENT} method's "
        "(paper sect. 5.3: 35 %)"
    )
    _detector_agreement(cfg, runs[0][1], runs[1][1])


def _detector_agreement(cfg, semi, grad) -> None:
    """How far the two detectors' runs agree (:func:`rollerdyn.study.agreement.differences`,
    as `rollerdyn compare` prints it), each against the issue's bounds that the study's
    check judges (:data:`rollerdyn.study.findings.TIGHT_MEASURES`); full speed
    from the first output at which the inner ring turns at 99 % of its final speed, as the
    study's detector check counts it."""
    import math

    from ..study.agreement import MEASURES, differences, full_speed_time
    from ..study.findings import FULL_SPEED, TIGHT_MEASURES
    from .compare import SHOWN_UNITS

    full_speed = full_speed_time(semi, cfg.operating.final_inner_ring_speed, FULL_SPEED)
    try:
        found = differences(semi, grad, full_speed)
    except ValueError as err:
        say(f"the two runs cannot be compared: {err}", "yellow")
        return
    speed = (
        f"full speed from {full_speed:.4g} s"
        if math.isfinite(full_speed)
        else "full speed not reached"
    )
    table = Table(title=f"agreement of the two runs over 0 … {found['t_end']:.4g} s ({speed})")
    for col in ("largest difference of", "value", "bound", "within"):
        table.add_column(col)
    for key, bound in TIGHT_MEASURES.items():
        what, unit = MEASURES[key]
        shown, factor = SHOWN_UNITS[unit]
        value = found[key]
        within = "n/a" if not math.isfinite(value) else ("yes" if value <= bound else "no")
        text = "n/a" if not math.isfinite(value) else f"{value * factor:.4g} {shown}"
        table.add_row(what, text, f"{bound * factor:g} {shown}", within)
    console.print(table)


def bench_contact(cfg, steps: int) -> None:
    """One roller end passing once around the bearing against an inner-ring flange: every
    detection method timed, with its accuracy against the reference solver."""
    from .. import _core

    g = cfg.geometry
    fl = g.inner_flange
    with console.status(Text("timing roller end / flange detection...")):
        r = _interruptible(
            _core.contact_benchmark,
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


def bench_statics(cfg, cases: int) -> None:
    """The quasi-static analysis on one core: one equilibrium of the configuration's load
    case from the cold start (median of 20, with its stiffness), and a sweep of ``cases``
    radial loads from half to twice the configuration's (its axial load kept), each from its
    neighbour, in the core and through :func:`rollerdyn.statics.statics_sweep` (datasets,
    lives)."""
    import statistics
    import time

    import numpy as np

    from .. import _core
    from ..statics import StaticsError, _case_with, _core_model, config_case, statics_sweep

    model = _core_model(cfg)
    base = config_case(cfg)

    def timed(case_list: list, chain: bool) -> tuple[float, list]:
        started = time.perf_counter()
        out = _core.statics(model, [c.core() for c in case_list], chain=chain, stiffness=True)
        return time.perf_counter() - started, out

    _, (first,) = timed([base], False)
    if isinstance(first, str):
        raise refuse(f"statics: {first}")
    single = statistics.median(timed([base], False)[0] for _ in range(20))
    radial = max(base.radial_load, 1.0)
    loads = np.linspace(0.5 * radial, 2.0 * radial, cases)
    sweep_cases = [_case_with(base, radial_load=float(f)) for f in loads]
    core_seconds, results = timed(sweep_cases, True)
    failed = sum(1 for r in results if isinstance(r, str))
    started = time.perf_counter()
    try:
        statics_sweep(cfg, {"operating.radial_load": loads.tolist()})
    except StaticsError as err:
        raise refuse(f"statics: {err}") from None
    datasets_seconds = time.perf_counter() - started
    table = Table(title=f"{cfg.name}: quasi-static analysis, one core")
    for col in ("what", "time", "note"):
        table.add_column(col)
    table.add_row(
        "one equilibrium",
        f"{single * 1e3:.2f} ms",
        f"radial {base.radial_load:g} N, axial {base.axial_load:g} N, cold start, "
        "with the 5x5 stiffness and the friction of steady rolling; median of 20",
    )
    table.add_row(
        f"{cases}-case radial sweep, core",
        f"{core_seconds:.2f} s",
        f"{loads[0]:g} ... {loads[-1]:g} N, each case from its neighbour; "
        f"{failed} without equilibrium",
    )
    table.add_row(
        f"{cases}-case radial sweep, statics_sweep",
        f"{datasets_seconds:.2f} s",
        "the same with one dataset per case (slice loads, lives)",
    )
    console.print(table)
