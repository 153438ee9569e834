"""``rollerdyn plot``: the paper's figures from result files (matplotlib, PNG and SVG)."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from ..paths import check_output_dir
from .common import checked, refuse, say


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
    ratio at the inner race over azimuth (fig. 13), roller loads over azimuth, the power
    taken at each roller and the races' sliding part of it over azimuth (W), the specific
    film thickness Lambda at the inner race and each roller's most loaded flange contact
    over azimuth (boundary, mixed or full-film lubrication), and the roller end / flange
    pairings in contact (figs. 8, 9). A figure is drawn from the
    results that recorded what it shows (solver.outputs; results written before the power
    losses have no power figures). A missing file or one that is not a rollerdyn result
    exits with status 2.
    """
    from ..plots import plot_results
    from ..report import ReportError

    checked(check_output_dir, out, "-o")
    try:
        written = plot_results(results, out)
    except ReportError as err:
        raise refuse(err) from None
    except OSError as err:
        raise refuse(f"-o {out}: could not write the figures ({err})", 1) from None
    for w in written:
        say(f"wrote {w}")
