"""Continuing an interrupted sweep (``rollerdyn sweep --resume``, ``sweep(..., resume=True)``).

A sweep stopped by Ctrl-C, SIGTERM or a lost machine leaves the result files of the runs
that finished. Run again with ``resume``, the same sweep keeps each of those files whose
run is this grid point's (the same configuration, by its hash, the same detector and end
time) and runs only the other points. A run that failed is kept as failed: the simulator
is deterministic, so running it again would fail again, bit for bit (``--overwrite``
redoes every run). A run file of another configuration, detector or end time, or of a
point beyond this grid, is refused by name before any run starts: it belongs to another
sweep, which ``--resume`` must not mix into this one's summary.
"""

from __future__ import annotations

import math
from pathlib import Path

from .config import parse_config
from .provenance import check_same_configuration


def finished_runs(out: Path, points, t_end: float | None, detector: str | None) -> list:
    """The points of ``points`` whose runs an earlier sweep in the folder ``out`` finished
    (completed to the end time, or failed with the solver's error), judged from their
    files' attributes (fast). Raises :class:`~rollerdyn.sweep.SweepError` naming the file
    for a run file that is not this grid's (another configuration, detector or end time;
    a point beyond the grid)."""
    from .sweep import RUN_FILES, SweepError, run_attributes

    by_file = {p.file: p for p in points}
    where = f"-o {out}"
    hint = (
        "--resume continues the same sweep (the same file, --set values, --t-end and "
        "--detector); use --overwrite to replace the earlier sweep, or another folder"
    )
    finished = []
    for path in sorted(out.glob(RUN_FILES)):
        point = by_file.get(path.name)
        if point is None:
            raise SweepError(
                f"{where}: {path.name} is a run of an earlier sweep with more points than "
                f"this one's {len(points)}; {hint}"
            )
        attrs = run_attributes(path)
        if isinstance(attrs, str):
            raise SweepError(f"{where}: {path.name} cannot be continued ({attrs}); {hint}")
        why = _other_run(attrs, point, t_end, detector)
        if why:
            raise SweepError(f"{where}: {path.name} (run {point.run}) {why}; {hint}")
        error = str(attrs.get("error", ""))
        if int(attrs.get("completed", 0)) or (error and not error.startswith("interrupted")):
            finished.append(point)
    return finished


def kept_runs(out: Path, points, t_end: float | None, detector: str | None) -> dict[int, dict]:
    """The summary rows of the :func:`finished_runs`, read from their files, with the wall
    time the earlier summary lists; a file that cannot be read is left out (run again)."""
    from .sweep import row_from_file

    walls = _earlier_walls(out)
    rows: dict[int, dict] = {}
    for point in finished_runs(out, points, t_end, detector):
        row = row_from_file(out / point.file, point)
        if row is not None:
            row["wall [s]"] = walls.get(point.run, math.nan)
            rows[point.run] = row
    return rows


def _other_run(attrs: dict, point, t_end: float | None, detector: str | None) -> str:
    """Why the run with ``attrs`` is not the run of ``point`` ("" if it is)."""
    cfg = parse_config(point.data, si_numbers=point.si_numbers)
    try:
        check_same_configuration(attrs, cfg)
    except ValueError as err:
        head = "(SI values, earlier -> now): "
        if head not in str(err):
            return "records no configuration (config_sha256) to check it by"
        changed = str(err).split(head, 1)[1].split("; a run can only", 1)[0]
        return f"was run with another configuration {head}{changed}"
    wanted = detector or cfg.solver.detector
    if attrs.get("detector") != wanted:
        return f"was run with the detector {attrs.get('detector')!r}, this sweep's is {wanted!r}"
    end = cfg.end_time if t_end is None else t_end
    reached = float(attrs.get("final_time_s", math.nan))
    from .study.runs import time_slack

    slack = time_slack(end)
    completed = int(attrs.get("completed", 0)) == 1
    if reached > end + slack or (completed and reached < end - slack):
        return f"was run to t = {reached:.6g} s, this sweep's end time is {end:.6g} s"
    return ""


def _earlier_walls(out: Path) -> dict[int, float]:
    """Each run's wall time as the earlier sweep's summary lists it (none if there is no
    readable summary)."""
    import pyarrow.parquet as pq

    from .sweep import SUMMARY_FILE

    try:
        table = pq.read_table(out / SUMMARY_FILE, columns=["run", "wall [s]"]).to_pydict()
    except Exception:  # no summary (a sweep killed hard) or another program's file
        return {}
    walls = {}
    for run, wall in zip(table["run"], table["wall [s]"], strict=True):
        if isinstance(run, int) and isinstance(wall, float):
            walls[run] = wall
    return walls
