"""``rollerdyn compare``: how far two runs of the same bearing drift apart, output by output
(:func:`rollerdyn.study.agreement.differences`, what the paper study's detector comparison
uses)."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Annotated

import typer
from rich.table import Table

from .common import console, plain, refuse, say, time_option

#: How each unit of :data:`rollerdyn.study.agreement.MEASURES` is shown: unit, factor.
SHOWN_UNITS = {"m": ("µm", 1e6), "rad": ("mrad", 1e3), "-": ("%", 100.0)}

#: The solver statistics shown side by side: attribute, label.
STATISTICS = (
    ("stats_steps", "steps"),
    ("stats_rhs_evaluations", "right-hand sides"),
    ("stats_gradient_fallbacks", "gradient fallbacks"),
    ("stats_total_seconds", "wall [s]"),
)


def compare_command(
    first: Annotated[
        Path, typer.Argument(help="A result file (netCDF) of rollerdyn run.", metavar="A")
    ],
    second: Annotated[
        Path,
        typer.Argument(
            help="Another result of the same bearing, e.g. the other detector's.", metavar="B"
        ),
    ],
    full_speed: Annotated[
        str,
        typer.Option(
            "--full-speed",
            help="Simulated time from which the runs count as at full speed, with a unit "
            "(750 ms) or a bare number of seconds: B1's speed ramp ends at 0.7 s; for other "
            "ramps give their end and some settling time.",
            metavar="TIME",
        ),
    ] = "0.75 s",
) -> None:
    """Compare two runs of the same bearing output by output (e.g. the two contact
    detectors' runs, or a run and its round-off twin: docs/dynamics.md, "Agreement of the
    two detectors in whole B1 runs").

    Prints the largest differences over the outputs the two share: a roller's position
    [µm] in the load zone (within 60° of its centre) and outside it, over the whole run and
    at full speed (from --full-speed, by default 0.75 s; also split into axial, radial and
    circumferential), tilt and skew at full speed [mrad], the roller end-flange
    normal forces [% of the largest of either run] and the frictional torque at full speed
    (its mean, relative [%], and output by output [% of the largest]); n/a where no output
    qualifies (no full speed in a short run). Beside each roller's measure, where its
    largest difference lies: the output time, the roller and its azimuth in A (0° at +y,
    the load zone's centre at 180°). Then both runs' steps, right-hand sides,
    gradient fallbacks and wall time. A note first names the fields in which the two runs'
    bearings (geometry, materials, inner ring) differ, if they do, and a run that did not
    record its rollers or flanges (solver.outputs); their measures show n/a. A second
    note names what else differs: the loads and speeds, the oil or the surfaces' models
    (the solver's settings, which a comparison is usually about, are not named).

    Exits with status 2 if a file is missing or not a rollerdyn run's result, if the two
    runs share no output but their first or differ in their roller count, or for a bad
    --full-speed. Runs of two output intervals are compared at the times both have.
    """
    from ..report import ReportError, open_result
    from ..simulation import recorded
    from ..study.agreement import MEASURES, NEEDED, differences

    from_full_speed = time_option("--full-speed", full_speed, zero=True)
    runs = []
    for path in (first, second):
        try:
            needed = tuple(n for n in NEEDED if n != "time")
            runs.append(open_result(path, required=needed, recorded_only=True))
        except ReportError as err:
            raise refuse(err) from None
    a, b = runs
    try:
        found = differences(a, b, from_full_speed)
    except ValueError as err:
        raise refuse(f"{first} and {second}: {err}") from None
    _note_other_bearings(a.attrs, b.attrs, first, second)
    for path, run in ((first, a), (second, b)):
        lacking = [g for g in ("rollers", "flanges") if not recorded(run, g)]
        if lacking:
            what = " and ".join(lacking)
            say(f"{path}: the run did not record its {what} (solver.outputs): n/a below", "yellow")
    _print_differences(found, MEASURES, f"{first.name} against {second.name}")
    _print_statistics(runs, (first.name, second.name))


def _note_other_bearings(a: dict, b: dict, first: Path, second: Path) -> None:
    """A line when the two runs record bearings that differ (geometry, materials, inner
    ring): their differences are then not those of a method or of round-off."""
    from ..provenance import CASE_SECTIONS, bearing_differences, recorded_configuration

    ra, rb = recorded_configuration(a), recorded_configuration(b)
    if ra is None or rb is None:
        return
    differ = bearing_differences(ra, rb)
    if differ:
        say(
            f"note: {first.name} and {second.name} are runs of different bearings "
            f"({'; '.join(differ)}); the differences below include that",
            "yellow",
        )
    # another load, oil or flange law (a review: point against distributed law, no word)
    differ = bearing_differences(ra, rb, sections=CASE_SECTIONS)
    if differ:
        say(
            f"note: {first.name} and {second.name} differ in their case "
            f"({'; '.join(differ)}); the differences below include that",
            "yellow",
        )


def _print_differences(found: dict, measures: dict, title: str) -> None:
    """The table of :func:`rollerdyn.study.agreement.differences`, in µm, mrad and %, with
    where each roller's largest difference lies."""
    from ..study.agreement import where_text

    table = Table(
        title=plain(f"{title}: {found['outputs']} common outputs, 0 … {found['t_end']:.6g} s")
    )
    table.add_column("largest difference of", overflow="fold")
    table.add_column("value", justify="right")
    table.add_column("where (output, roller, its azimuth in A)", overflow="fold")
    for key, (what, unit) in measures.items():
        shown, factor = SHOWN_UNITS[unit]
        value = found[key]
        text = "n/a" if not math.isfinite(value) else f"{value * factor:.4g} {shown}"
        place = where_text(found["where"].get(key)) if math.isfinite(value) else ""
        table.add_row(plain(what), text, plain(place))
    console.print(table)


def _print_statistics(runs: list, names: tuple[str, str]) -> None:
    """Both runs' :data:`STATISTICS` side by side."""
    stats = Table(title="solver statistics")
    stats.add_column("", overflow="fold")
    for name in names:
        stats.add_column(plain(name), justify="right")
    for attr, label in STATISTICS:
        stats.add_row(label, *(_stat(run.attrs.get(attr)) for run in runs))
    console.print(stats)


def _stat(value) -> str:
    """A statistic as printed: n/a when the file has none."""
    if value is None:
        return "n/a"
    return f"{value:.4g}" if isinstance(value, float) else str(value)
