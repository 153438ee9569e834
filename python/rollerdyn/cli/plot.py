"""``rollerdyn plot``: the paper's figures from result files (matplotlib, PNG and SVG)."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from ..paths import OutputPathError, check_name, check_output_dir
from .common import checked, quiet_arithmetic, refuse, say

#: Extensions of image files (matplotlib's formats): an -o named so is a figure's file name,
#: given where plot takes the folder of its figures.
IMAGE_EXTENSIONS = frozenset(
    ".eps .jpeg .jpg .pdf .pgf .png .ps .raw .rgba .svg .svgz .tif .tiff .webp".split()
)


def check_figure_folder(out: str) -> Path:
    """The folder ``-o`` of ``plot`` (:func:`rollerdyn.paths.check_output_dir`); refused:
    an empty name (an unset variable: the figures would go to the current folder) and, unless
    it is a folder already, a name with an image extension (``-o torque.png``: plot writes
    several figures, as PNG and SVG, into a folder)."""
    if not out.strip():
        raise OutputPathError(
            f"-o {out!r}: empty; give the folder for the figures (. for the current one)"
        )
    path = check_name(Path(out), "-o")
    if path.suffix.lower() in IMAGE_EXTENSIONS and not path.is_dir():
        raise OutputPathError(
            f"-o {out}: names an image file; plot writes several figures (PNG and SVG) "
            "into a folder: give the folder's name"
        )
    return check_output_dir(path, "-o")


def plot(
    results: Annotated[
        list[Path],
        typer.Argument(help="Result files (netCDF) of rollerdyn run.", metavar="RESULT"),
    ],
    out: Annotated[
        str,
        typer.Option(
            "--output",
            "-o",
            help="Folder for the figures; created if missing (its parent must exist). "
            "Figures of the same names in it are replaced.",
            metavar="PATH",
        ),
    ] = "plots",
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

    folder = checked(check_figure_folder, out)
    try:
        with quiet_arithmetic():
            written = plot_results(results, folder)
    except ReportError as err:
        raise refuse(err) from None
    except OSError as err:
        raise refuse(
            f"-o {out}: could not write the figures ({err.strerror or err}); figures there "
            "before are unchanged or replaced whole",
            1,
        ) from None
    for w in written:
        say(f"wrote {w}")
