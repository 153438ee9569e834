"""``rollerdyn report``: one self-contained HTML page about one or more result files
(:func:`rollerdyn.report.report`)."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from ..limits import MAX_FRAMES
from .common import checked, error, quiet_arithmetic, refuse, say


def report_command(
    results: Annotated[
        list[Path],
        typer.Argument(help="Result files (netCDF) written by rollerdyn run.", metavar="RESULT"),
    ],
    output: Annotated[
        Path,
        typer.Option(
            "--output",
            "-o",
            help="The HTML file to write. Its folder must exist; an existing file is "
            "replaced only if it is an earlier report (.html).",
        ),
    ] = Path("report.html"),
    max_frames: Annotated[
        int,
        typer.Option(
            "--max-frames",
            min=1,
            help="Most frames of the roller-set animation (outputs are evenly subsampled).",
        ),
    ] = MAX_FRAMES,
) -> None:
    """Write one self-contained HTML page about one or more results (default: report.html).

    The page needs no network access: plotly.js (about 5 MB) and every style are inline.
    Units are SI: forces in N, torques in N*m, time in s, speeds in rad/s; azimuths in
    degrees and the roller-set view in mm, as the axes say. The page shows:

    - inputs: each run's attributes (bearing, detector, solver settings, statistics) and
    its radial and axial load (N) and inner ring speed (rad/s) over time;

    - a summary table, one column per result: mean bearing frictional torque over the
    last 20 % of the run (N*m), largest roller-race load (N), largest flange normal force
    (N), largest |slide-to-roll ratio| at the inner race while the ring turns (n/a if it
    never does), final time (s), solver steps and wall time (s);

    - the paper's figures, interactive, every result in the same plot: fig. 10 frictional
    torque over time, fig. 11 flange friction force of roller 0 over time, fig. 12 axial
    force on a roller over its azimuth, fig. 13 inner slide-to-roll ratio over azimuth,
    figs. 8 and 9 share of time per roller end / flange pairing at each ring;

    - an animation of the roller set (orbit positions, skew, inner race load) with a
    slider through time, at most --max-frames frames (default 200).

    Exits with status 2 if a file is missing or is not a rollerdyn result, or if -o
    cannot take the report (checked before any work). The page is written through a
    temporary file renamed into place: a failed write (status 1) leaves an earlier report
    as it was.
    """
    from ..report import ReportError, check_report_output, report

    checked(check_report_output, results, output)
    try:
        with quiet_arithmetic():
            written = report(results, output, max_frames=max_frames)
    except ReportError as err:
        raise refuse(err) from None
    except OSError as err:  # written through a temporary file: an earlier report is intact
        kept = "an earlier report there is unchanged" if output.exists() else "nothing written"
        error(f"-o {output}: could not write the report ({err.strerror or err}); {kept}")
        raise typer.Exit(1) from None
    size = written.stat().st_size / 1e6
    if written != output:
        say(
            f"wrote {written} ({size:.1f} MB): {output} was created by another program "
            "meanwhile and is no report of rollerdyn; it is kept as it is",
            "yellow",
        )
        return
    say(f"wrote {written} ({size:.1f} MB)")
