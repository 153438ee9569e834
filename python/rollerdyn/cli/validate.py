"""``rollerdyn validate`` (every model against published values) and ``rollerdyn check``
(a configuration file and its derived quantities)."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer
from rich.table import Table
from rich.text import Text

from .common import SET_HELP, ConfigOption, console, default_config, load, say, set_options


def validate(config: ConfigOption = None) -> None:
    """Check every model against published values and closed-form limits.

    Prints one row per case: group, case, source, expected and computed value (SI units),
    relative error, tolerance and pass/fail (a known model error, such as the Brewe-Hamrock
    fit's at high ellipticity, has its measured size rounded up as its tolerance). Exits
    with status 1 if any case fails.
    """
    from ..validation import differs_from_b1, run

    cfg = load(config if config is not None else default_config())
    table = Table(title="rollerdyn validation", show_lines=False)
    for col in ("group", "case", "source", "expected", "computed", "rel. error", "tol.", "pass"):
        table.add_column(col, overflow="fold")
    failures = 0
    with console.status(Text("running validation cases...")):
        results = list(run(cfg))
    for r in results:
        c = r.case
        verdict = Text("pass", style="green") if r.passed else Text("FAIL", style="red")
        failures += 0 if r.passed else 1
        table.add_row(
            c.group,
            c.name,
            c.source,
            f"{c.expected:.6g}",
            f"{r.computed:.6g}",
            f"{r.relative_error:.2e}",
            f"{c.rtol:.2g}",
            verdict,
        )
    console.print(table)
    total = len(results)
    console.print(f"{total - failures} passed, {failures} failed")
    other = differs_from_b1(cfg)
    if other is not None:
        say(
            f"B1's own cases (eq. 11 at its races, its oil and traction, its roller) left out: "
            f"{cfg.name} is not B1 as published ({other} differs from examples/b1.toml's), "
            "and their expected values are B1's"
        )
    if failures:
        raise typer.Exit(1)


def check(
    config: Annotated[Path, typer.Argument(help="Bearing configuration (TOML).", metavar="CONFIG")],
    settings: Annotated[
        list[str] | None,
        typer.Option("--set", help=SET_HELP + " As `rollerdyn run --set` would run it."),
    ] = None,
) -> None:
    """Validate a configuration file and print its derived quantities (SI units).

    Shows roller diameter, pitch diameter, gap between rollers, roller mass and inertias,
    end time, the outputs to it and the result's size before compression (MB; what
    solver.outputs selects, every solver.output_interval), lubricant state at the run
    temperature (eta0, Roelands z, alpha*) and the line-contact power laws (eq. 11)
    fitted to Tripp with their errors; the flanges the rings have (geometry.flanges), the
    bearing type they make and the axial loads they carry; then whether `rollerdyn run`
    would refuse the run
    at its start (a run far beyond a normal one or the point end-flange law's load check,
    both of which --force skips; a start whose bodies overlap, or without equilibrium), and
    the
    notes it would print: a configuration known to creep with the point end-flange law (a
    free or prescribed ring tilt), an equilibrium start before the loads, and loads at
    the end time whose quasi-static equilibrium presses a flange or a race past ISO 76's
    4 GPa.
    """
    from ..model import Model
    from ..notes import configuration_notes, refusal_note
    from ..simulation import estimated_cost

    cfg = load(config, set_options(settings))
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
    ]
    field = cfg.carrier_field
    if field != 0.0:
        rows.append(("planet carrier's field at the bearing's axis, at full speed", field, "m/s^2"))
        rows.append(("  ... on one roller", cfg.roller_mass * field, "N"))
    rows += [
        ("eta0 at run temperature", model.eta0, "Pa s"),
        ("Roelands z", model.roelands_z, "-"),
        ("alpha* (eq. 32 fit)", model.alpha_star, "1/Pa"),
        ("alpha* fit max. relative error", model.alpha_star_fit["max_relative_error"], "-"),
    ]
    cost = estimated_cost(cfg, cfg.end_time)
    rows.append(("outputs to the end time", cost["outputs"], "-"))
    rows.append(("result size before compression (solver.outputs)", cost["bytes"] / 1e6, "MB"))
    rows.append(("outputs held while the run goes", cost["memory_bytes"] / 1e6, "MB"))
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
    g = cfg.geometry
    say(f"flanges: {g.flange_arrangement}; axial load carried: {g.axial_load_carried}")
    for note in [_cost_note(cfg), refusal_note(cfg), *configuration_notes(cfg)]:
        if note is not None:
            say(note, "yellow")


def _cost_note(cfg) -> str | None:
    """The refusal `rollerdyn run` gives a run far beyond a normal one (its outputs' size,
    its least step count, its checkpoints: :func:`rollerdyn.simulation.check_cost`), as a
    note, or None."""
    from ..simulation import check_cost

    try:
        check_cost(cfg, cfg.end_time)
    except ValueError as refusal:
        return f"note: rollerdyn run refuses this configuration: {refusal}"
    return None
