"""The tables that ``rollerdyn study`` prints at the end: the runs, the map's points, the
thermal balance, the paper's findings and the timing (rich tables on the console)."""

from __future__ import annotations

import math
from typing import Any

from rich.table import Table
from rich.text import Text

from .common import console, plain, say

_STYLE = {"PASS": "green", "FAIL": "red", "NOT RUN": "yellow"}
_RUN_STYLE = {
    "completed": "green",
    "failed": "red",
    "steady": "green",
    "balanced": "green",
    "found": "green",
}


def _fmt(value: Any, spec: str = ".4g") -> str:
    if isinstance(value, float):
        return "n/a" if math.isnan(value) else format(value, spec)
    return str(value)


#: The columns of the runs' table: column of the frame, heading, number format.
_RUN_COLUMNS = (
    ("name", "run", ""),
    ("label", "what", ""),
    ("status", "status", ""),
    ("reached [s]", "reached [s]", ".4g"),
    ("t_end [s]", "end [s]", ".4g"),
    ("wall [s]", "wall [s]", ".1f"),
    ("steps", "steps", ""),
    ("action", "this time", ""),
)


#: The longest status cell shown whole; a longer one (a failure's reason with the core's
#: whole message: about 900 characters, a cell 70 lines tall) is cut there.
LONGEST_STATUS = 240


def _shortened(text: str, longest: int = LONGEST_STATUS) -> str:
    """``text`` cut at ``longest`` characters, saying where it is whole."""
    if len(text) <= longest:
        return text
    return text[: longest - 1].rstrip() + "… (whole in the folder's CSV table)"


def print_frame(frame, title: str, columns, status_text) -> None:
    """One row per row of ``frame``: ``columns`` (column, heading, format), the status
    coloured and shown as ``status_text(row)`` says."""
    table = Table(title=plain(title))
    for _, head, _ in columns:
        table.add_column(head, overflow="fold")
    for _, row in frame.iterrows():
        cells = []
        for col, _, spec in columns:
            value = row.get(col, "")
            if col == "status":
                style = _RUN_STYLE.get(value, "yellow")
                cells.append(Text(_shortened(plain(status_text(row))), style=style))
            else:
                cells.append(Text(plain(_fmt(value, spec or ".4g"))))
        table.add_row(*cells)
    console.print(table)


def run_status(row) -> str:
    """A row's status cell: its note (a failure's reason is prefixed "failed: ") or its
    status."""
    note = row.get("note") or ""
    if row["status"] == "failed" and note:
        return f"failed: {note}"
    return note or row["status"]


def status_and_note(row) -> str:
    """A row's status cell: its status, and its note after a colon where it has one."""
    return f"{row['status']}: {row['note']}" if row["note"] else row["status"]


def print_runs(frame, title: str) -> None:
    print_frame(frame, title, _RUN_COLUMNS, run_status)


def print_map(frame, title: str) -> None:
    from ..simulation import FORCED_MARK
    from ..study.maps import FALLBACK, MAP_COLUMNS

    def status(row) -> str:
        steady = row["status"] in ("steady", "not steady")
        # a long reason cut before the marks are added, which the cut would drop
        text = row["status"] if steady else _shortened(run_status(row), LONGEST_STATUS - 130)
        if str(row.get("start", "")).startswith(FALLBACK):
            # no equilibrium at t = 0: the point ran from short ramps (docs/study.md)
            text = f"{text} (from short ramps: no equilibrium)"
        if FORCED_MARK in str(row.get("note", "")):
            text = f"{text} (--force: past the point law's load check)"
        return text

    print_frame(frame, title, MAP_COLUMNS, status)


def print_findings(findings) -> None:
    table = Table(title="the paper's findings, checked on the runs (docs/study.md)")
    for head in ("finding (paper)", "check", "the numbers behind it"):
        table.add_column(head, overflow="fold")
    for f in findings:
        table.add_row(
            Text(plain(f.statement)),
            Text(f.status, style=_STYLE.get(f.status, "")),
            Text(plain(f.numbers)),
        )
    console.print(table)


def print_timing(timing: dict, total: float, frame) -> None:
    eff = timing.get("parallel efficiency", math.nan)
    runs = timing.get("runs run", 0)
    if not runs:
        present, planned = int((frame["file"] != "").sum()), len(frame)
        if present == planned:
            say(f"nothing to run: every run was already in the folder ({total:.1f} s in all)")
        else:
            say(
                f"no run was run: {present} of the {planned} runs are in the "
                f"folder ({total:.1f} s in all)"
            )
        return
    say(
        f"runs: {timing['study wall [s]']:.1f} s of wall time for {runs} run(s) whose own "
        f"times sum to {timing['sum of run walls [s]']:.1f} s on {timing['workers'] or '?'} "
        f"worker(s): parallel efficiency {_fmt(100 * eff, '.0f')} %; {total:.1f} s in all "
        "with the figures and the report"
    )
