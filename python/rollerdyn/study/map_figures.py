"""The maps of ``rollerdyn study map`` (matplotlib, PNG and SVG): one figure per output
(friction torque, roller-set speed loss, largest flange force). With two or three swept
quantities, a colour map over the two with the most values (one panel per value of the
third); with one, a line over it. Points that are not steady are marked with a cross;
points without a value (failed, or stopped before a whole window after the ramps) are
left blank and labelled with their status.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

#: The grid's axes: column, label.
AXES = (
    ("speed [rpm]", "inner ring speed [rpm]"),
    ("radial_load [N]", "radial load [N]"),
    ("axial_load [N]", "axial load [N]"),
)


def write_maps(frame, out: Path, name: str) -> list[Path]:
    """One figure per output of :data:`rollerdyn.study.maps.OUTPUTS` that has a value at
    some point (none: the flanges' Lambda of a map whose roller ends never touch, or a
    result without the lubrication outputs); returns the files."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from ..plots import save_figure
    from .maps import OUTPUTS, STEADY

    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    sizes = {col: sorted(frame[col].unique()) for col, _ in AXES}
    varying = sorted([col for col, _ in AXES if len(sizes[col]) > 1], key=lambda c: -len(sizes[c]))
    labels = dict(AXES)
    written = []
    for column, title, unit in OUTPUTS:
        if column not in frame or not np.isfinite(frame[column].astype(float)).any():
            continue
        short = column.split(" [")[0].replace(" ", "_")
        if len(varying) >= 2:
            x, y = varying[0], varying[1]
            rest = [c for c, _ in AXES if c not in (x, y)]
            panel = rest[0]
            values = sizes[panel]
            fig, axes = plt.subplots(
                1, len(values), figsize=(5.5 * len(values), 4.2), squeeze=False
            )
            for ax, v in zip(axes[0], values, strict=True):
                sub = frame[frame[panel] == v]
                grid = sub.pivot_table(index=y, columns=x, values=column, aggfunc="first")
                grid = grid.reindex(index=sizes[y], columns=sizes[x])
                mesh = ax.pcolormesh(
                    np.arange(len(sizes[x]) + 1) - 0.5,
                    np.arange(len(sizes[y]) + 1) - 0.5,
                    grid.values.astype(float),
                    shading="flat",
                    cmap="viridis",
                )
                fig.colorbar(mesh, ax=ax, label=f"{title} [{unit}]")
                ax.set_xticks(range(len(sizes[x])), [f"{s:g}" for s in sizes[x]])
                ax.set_yticks(range(len(sizes[y])), [f"{s:g}" for s in sizes[y]])
                for _, row in sub.iterrows():
                    at = sizes[x].index(row[x]), sizes[y].index(row[y])
                    if not np.isfinite(float(row[column])):
                        # no value (failed, or stopped before a window after the ramps)
                        ax.text(*at, row["status"], ha="center", va="center", color="0.35")
                    elif row["status"] != STEADY:
                        ax.plot(*at, "rx", ms=10, mew=2)
                ax.set(xlabel=labels[x], ylabel=labels[y], title=f"{labels[panel]} = {v:g}")
            fig.suptitle(f"{name}: {title} at steady state (x: not steady)")
        else:
            x = varying[0] if varying else AXES[0][0]
            fig, ax = plt.subplots(figsize=(7, 4.2))
            rows = frame.sort_values(x)
            ax.plot(rows[x], rows[column], "o-", label="map point")
            valued = np.isfinite(rows[column].astype(float))
            bad = rows[(rows["status"] != STEADY) & valued]
            if len(bad):
                ax.plot(bad[x], bad[column], "rx", ms=10, mew=2, label="not steady")
            for _, row in rows[~valued].iterrows():
                ax.axvline(row[x], color="0.6", ls=":")
                ax.annotate(
                    row["status"],
                    (row[x], 0.02),
                    xycoords=("data", "axes fraction"),
                    rotation=90,
                    color="0.35",
                    ha="right",
                    va="bottom",
                )
            ax.set(xlabel=labels[x], ylabel=f"{title} [{unit}]", title=f"{name}: {title}")
            ax.legend()
        written += save_figure(fig, out, f"map_{short}")
    return written
