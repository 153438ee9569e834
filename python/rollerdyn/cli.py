"""The ``rollerdyn`` command line.

Commands: ``validate`` (every model against published values), ``check`` (validate a
configuration file and show its derived quantities), ``bench`` (time the hot path).
All inputs and outputs are SI unless a column says otherwise.
"""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer
from rich.console import Console
from rich.table import Table

from .config import ConfigError, load_config

app = typer.Typer(
    help="rollerdyn: dynamics of full-complement cylindrical roller bearings.",
    no_args_is_help=True,
    add_completion=False,
)
console = Console(width=200 if not Console().is_terminal else None)

ConfigOption = Annotated[
    Path | None,
    typer.Option(
        "--config",
        "-c",
        help="Bearing configuration (TOML) for the B1-specific cases; "
        "default: examples/b1.toml of the source tree.",
    ),
]


def _load(path: Path):
    try:
        return load_config(path)
    except ConfigError as err:
        console.print(f"[red]invalid configuration[/red]\n{err}")
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
    with console.status("running validation cases..."):
        results = list(run(cfg))
    for r in results:
        c = r.case
        verdict = (
            "info" if c.report_only else ("[green]pass[/green]" if r.passed else "[red]FAIL[/red]")
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
    config: Annotated[Path, typer.Argument(help="Bearing configuration (TOML).")],
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
    repetitions: Annotated[
        int, typer.Option(min=1000, help="Evaluations timed per contact type.")
    ] = 200_000,
    config: ConfigOption = None,
) -> None:
    """Time the EHL traction integral, the hot path of the dynamic model.

    Reports nanoseconds per line-slice and per elliptical-contact evaluation with the
    configuration's traction model (default: examples/b1.toml), single-threaded.
    For statistically careful numbers use ``cargo bench -p rollerdyn-core``.
    """
    from .model import Model
    from .validation import default_config_path

    cfg = _load(config if config is not None else default_config_path())
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


if __name__ == "__main__":  # pragma: no cover
    app()
