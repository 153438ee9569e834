"""``rollerdyn modes``: the fastest growing modes of the model at a run's final state
(:mod:`rollerdyn.modes`), with the bodies and states that carry them."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Annotated

import typer
from rich.table import Table

from .common import console, load, refuse, say, set_options


def modes_command(
    run: Annotated[
        Path,
        typer.Argument(
            help="A result file (netCDF) of rollerdyn run; its final state is examined: "
            "where it ended (--t-end), or for a run stopped by Ctrl-C or an error, its last "
            "output (to look closer to a collapse, run again with --t-end just before it).",
            metavar="RUN",
        ),
    ],
    config: Annotated[
        Path | None,
        typer.Option(
            "--config",
            "-c",
            help="The configuration (TOML) to evaluate the state with. Default: the one "
            "the run records (its TOML text, or for a run built in Python, e.g. a sweep's, "
            "its values in SI).",
            metavar="CONFIG",
        ),
    ] = None,
    count: Annotated[
        int,
        typer.Option(
            "--count", "-n", help="How many modes to print, fastest growing first.", min=1
        ),
    ] = 6,
    by_force: Annotated[
        bool,
        typer.Option(
            "--by-force",
            help="Also print the fastest growing mode with each of friction, contact "
            "damping, the race film, the squeeze film and drag switched off in turn, and "
            "with all of them off (a growth that stays comes from the contacts' elastic "
            "laws and geometry).",
        ),
    ] = False,
    settings: Annotated[
        list[str] | None,
        typer.Option(
            "--set",
            help="PATH=VALUE: evaluate the same state with a configuration value changed, "
            "written as in the file (e.g. solver.friction=false, "
            'surfaces.damping_ratio=0, operating.temperature="80 degC"); repeat for more.',
        ),
    ] = None,
) -> None:
    """Print the modes of the equations of motion at the final state of RUN: the
    eigenvalues λ of their Jacobian (the matrix of the integrator's Newton iteration),
    fastest growing first. Re λ > 0 [1/s] is a mode that grows as exp(Re λ · t): the
    integrator must resolve it, so steps far below 1/Re λ follow it; steps that shrink
    with no fast growing mode are held by a force law's jumps instead. The table names the
    states that carry each (a share of the largest component: a roller's position x, y, z
    [m], axis angles theta_y, theta_z [rad], velocities vx, vy, vz [m/s]
    and angular velocities wx, wy, wz [rad/s], inertial components; the inner ring's
    likewise) and, for each roller among them, its azimuth [deg], contact loads [N] and
    flange pairings at the last output. With --set the same state is evaluated with the
    changed model, to tell which force makes a mode; --by-force does that for each damping
    and driving force in turn (docs/dynamics.md, "Hot oil at speed: the point law's
    radii").

    Exits with status 2 for a missing or unreadable file, a run without a configuration
    and no --config, a --config of another bearing (the state does not fit it) or a bad
    --set.
    """
    from ..modes import growth_by_force, modes_of_run, run_config
    from ..report import ReportError, open_result
    from ..sweep import SweepError

    try:
        ds = open_result(run, required=("final_state",))
    except ReportError as err:
        raise refuse(err) from None
    changes = set_options(settings)
    if config is not None:
        changed_cfg = cfg = load(config, changes)  # --set read as `run` reads it
        _note_another_bearing(ds.attrs, cfg, run)
    else:
        try:
            cfg = run_config(ds)
        except ValueError as err:
            raise refuse(f"{run}: {' '.join(str(err).split())}") from None
        try:
            changed_cfg = run_config(ds, changes)
        except (ValueError, SweepError) as err:
            raise refuse(f"--set: {' '.join(str(err).split())}") from None
    try:
        modes = modes_of_run(changed_cfg, ds)
    except ValueError as err:
        raise refuse(f"{run}: {' '.join(str(err).split())}") from None
    t = float(ds.attrs["final_time_s"])
    changed = ", ".join(f"{k} = {_shown(v)}" for k, v in changes.items())
    title = f"{cfg.name}: the fastest growing modes at t = {t:.6g} s of {run.name}"
    table = Table(title=title + (f" with {changed}" if changed else ""))
    for col in (
        "growth rate [1/s]",
        "frequency [Hz]",
        "states (share)",
        "rollers at the last output",
    ):
        table.add_column(col)
    last = ds.isel(time=-1) if "time" in ds.dims else None
    for mode in modes[:count]:
        table.add_row(
            f"{mode.growth_rate:.4g}",
            f"{mode.frequency:.4g}",
            _states_text(mode),
            "; ".join(_roller_note(last, i) for i in mode.rollers[:2]),
        )
    console.print(table)
    if last is not None and "azimuth" not in last:
        say(
            "the rollers' azimuths and loads: n/a, the result records no rollers "
            '(solver.outputs lacks "rollers")'
        )
    if by_force:
        _print_by_force(growth_by_force(changed_cfg, t, ds["final_state"].values))
    unstable = sum(1 for m in modes if m.growth_rate > 0)
    say(
        f"{len(modes)} modes, {unstable} with a positive growth rate; the largest size "
        f"{max(abs(m.eigenvalue) for m in modes):.3g} 1/s"
    )


def _note_another_bearing(attrs: dict, cfg, run: Path) -> None:
    """A line when --config describes another bearing than the one the run records (the
    state fits any of the same roller count; its modes are then those of that bearing)."""
    from ..provenance import bearing_differences, recorded_configuration, resolved

    recorded = recorded_configuration(attrs)
    if recorded is None:
        return
    differ = bearing_differences(recorded, resolved(cfg))
    if differ:
        say(
            f"note: --config describes another bearing than {run.name} records "
            f"({'; '.join(differ)}); its state is evaluated with the --config one",
            "yellow",
        )


def _print_by_force(rows) -> None:
    """The table of --by-force: what is off, the fastest growth rate and its states."""
    table = Table(title="the fastest growing mode with forces switched off")
    for col in ("switched off", "growth rate [1/s]", "frequency [Hz]", "states (share)"):
        table.add_column(col)
    for label, mode in rows:
        table.add_row(label, f"{mode.growth_rate:.4g}", f"{mode.frequency:.4g}", _states_text(mode))
    console.print(table)


def _states_text(mode) -> str:
    """A mode's carrying states, short: ``r7.wy 1.00, r7.wz 0.62, ring.x 0.01``."""
    return ", ".join(
        f"{body.replace('roller ', 'r').replace('inner ring', 'ring')}.{state} {share:.2f}"
        for body, state, share in mode.states
    )


def _shown(value: object) -> str:
    """A --set value as written in a file (true/false for booleans)."""
    return str(value).lower() if isinstance(value, bool) else str(value)


def _roller_note(last, i: int) -> str:
    """Roller i's azimuth and loads at the last output, in a few words."""
    if last is None or "roller" not in last.dims or i >= last.sizes["roller"]:
        return f"roller {i}"
    if "azimuth" not in last:
        return f"roller {i}"
    r = last.sel(roller=i)

    def value(name: str) -> float:
        return float(r[name].max()) if name in r else math.nan

    azimuth = math.degrees(float(r["azimuth"]) % (2 * math.pi)) if "azimuth" in r else math.nan
    return (
        f"roller {i}: {azimuth:.0f}°, races {value('inner_normal_force'):.3g}/"
        f"{value('outer_normal_force'):.3g} N, flanges up to {value('flange_normal_force'):.3g} N"
        f"{_pairings(r)}"
    )


def _pairings(r) -> str:
    """The pairings of a roller's flange contacts at an output, e.g. `` (TO-CO, TO-CO)``."""
    from ..names import PAIRINGS

    if "flange_pairing" not in r:
        return ""
    found = [PAIRINGS[k] for k in r["flange_pairing"].values.tolist() if 0 <= k < len(PAIRINGS)]
    return f" ({', '.join(found)})" if found else ""
