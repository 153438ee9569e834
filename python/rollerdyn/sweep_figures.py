"""The figure of a sweep's summary (``rollerdyn sweep``; matplotlib, PNG and SVG): its
summary numbers (mean frictional torque, largest race load, largest flange force, largest
|slide-to-roll ratio| at the inner race) over the swept quantity with the most values, one
line per combination of the other swept values. Failed runs are marked with a cross at
the numbers of their partial run, and are not joined into the lines.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

#: The figure's panels: summary column, title.
PANELS = (
    ("mean_frictional_torque [N*m]", "mean frictional torque, last 20 % [N·m]"),
    ("max_race_load [N]", "largest roller–race load [N]"),
    ("max_flange_normal_force [N]", "largest flange normal force [N]"),
    ("max_abs_srr_inner [1]", "largest |SRR| at the inner race [–]"),
)

#: The figure's files in the sweep's folder (with .png and .svg).
FIGURE_NAME = "summary"

#: Lines beyond which the legend is left out (it would hide the panels).
MOST_LABELLED_LINES = 10


def numeric_axis(frame, paths: list[str]) -> str | None:
    """The SI column (``"<path> [<unit>]"``) of the swept path with the most distinct finite
    values (the first given among equals), or None when no numeric path takes two."""
    best, most = None, 1
    for path in paths:
        column = next((c for c in frame.columns if c.startswith(f"{path} [")), None)
        if column is None:
            continue
        values = np.unique(frame[column].to_numpy(dtype=float))
        count = int(np.isfinite(values).sum())
        if count > most:
            best, most = column, count
    return best


def write_summary_figure(frame, paths: list[str], out: Path, name: str) -> list[Path]:
    """Writes ``out/summary.png`` and ``.svg`` for the summary ``frame`` of a sweep over
    ``paths`` (see the module doc) and returns the files; none when no numeric path takes
    two values (nothing to draw a line over)."""
    axis = numeric_axis(frame, paths)
    if axis is None:
        return []
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from .plots import save_figure

    x_path = axis.split(" [")[0]
    others = [p for p in paths if p != x_path]
    groups = list(frame.groupby(others, sort=False)) if others else [((), frame)]
    fig, axes = plt.subplots(2, 2, figsize=(11, 7.5), sharex=True)
    for ax, (column, title) in zip(axes.flat, PANELS, strict=True):
        for key, rows in groups:
            rows = rows.sort_values(axis)
            done = rows[rows["status"] == "completed"]
            label = _label(others, key)
            (line,) = ax.plot(done[axis], done[column], "o-", label=label)
            failed = rows[rows["status"] != "completed"]
            if len(failed):
                ax.plot(failed[axis], failed[column], "x", color=line.get_color(), ms=9, mew=2)
        ax.set_title(title, fontsize=10)
        ax.grid(alpha=0.3)
        _readable_range(ax, frame[column].to_numpy(dtype=float))
    for ax in axes[1]:
        ax.set_xlabel(axis)
    handles, labels = axes.flat[0].get_legend_handles_labels()
    if others and len(groups) <= MOST_LABELLED_LINES:
        fig.legend(handles, labels, loc="lower center", ncol=min(len(groups), 3), frameon=False)
    failed_any = bool((frame["status"] != "completed").any())
    note = " (x: failed run, its partial numbers)" if failed_any else ""
    fig.suptitle(f"{name}: sweep over {x_path}{note}")
    fig.tight_layout(rect=(0, 0.08 if others else 0, 1, 1))
    return save_figure(fig, Path(out), FIGURE_NAME)


def _readable_range(ax, values: np.ndarray) -> None:
    """Plain tick labels (no offset), and a range of at least ±5 % about values that
    barely change (matplotlib would spread round-off over the panel); "n/a" on a panel
    without any value (the slide-to-roll ratio of runs whose ring never turns)."""
    ax.ticklabel_format(axis="y", useOffset=False)
    finite = values[np.isfinite(values)]
    if not finite.size:
        ax.text(0.5, 0.5, "n/a", transform=ax.transAxes, ha="center", color="0.4")
        ax.set_yticks([])
        return
    low, high = float(finite.min()), float(finite.max())
    middle, scale = 0.5 * (low + high), max(abs(low), abs(high))
    if high - low < 0.1 * scale or scale == 0.0:
        half = 0.05 * scale if scale > 0.0 else 1.0
        ax.set_ylim(min(low, middle - half), max(high, middle + half))


def _label(others: list[str], key) -> str:
    """The legend text of one line: each other swept path with its value as given."""
    values = key if isinstance(key, tuple) else (key,)
    return ", ".join(f"{p} = {v}" for p, v in zip(others, values, strict=True)) or "runs"
