"""The maps of ``rollerdyn study map`` (matplotlib, PNG and SVG): one figure per output
(friction torque, its ratio to the torque of steady rolling, roller-set speed loss, largest
flange force, the median Lambdas, the ring's vibration). With
two or more swept quantities (speed, radial and axial load, oil temperature), a colour map
over the two with the most values (one panel per value of the others); with one, a line
over it, the torque's with the quasi-static torque of steady rolling beside it. Points that
are not steady are marked with a cross;
points without a value (failed, or stopped before a whole window after the ramps) are
left blank and labelled with their status ("none" where a steady point has no value).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

#: The grid's axes: column, label.
AXES = (
    ("speed [rpm]", "speed of the turning ring [rpm]"),
    ("radial_load [N]", "radial load [N]"),
    ("axial_load [N]", "axial load [N]"),
    ("temperature [degC]", "oil temperature [degC]"),
)


def write_maps(frame, out: Path, name: str) -> list[Path]:
    """One figure per output of :data:`rollerdyn.study.maps.OUTPUTS` that has a value at
    some point (none: the flanges' Lambda of a map whose roller ends never touch, or a
    result without the lubrication outputs); returns the files."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from ..plots import save_figure
    from .estimates import STEADY_ROLLING
    from .maps import OUTPUTS, STEADY

    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    axes = [(col, label) for col, label in AXES if col in frame]  # a table of before
    sizes = {col: sorted(frame[col].unique()) for col, _ in axes}
    varying = sorted([col for col, _ in axes if len(sizes[col]) > 1], key=lambda c: -len(sizes[c]))
    labels = dict(axes)
    written = []
    for column, title, unit in OUTPUTS:
        if column not in frame or not np.isfinite(frame[column].astype(float)).any():
            continue
        short = column.split(" [")[0].replace(" ", "_")
        if len(varying) >= 2:
            x, y = varying[0], varying[1]
            rest = [c for c, _ in axes if c not in (x, y)]
            # one panel per combination of the other axes' values; titled by those that vary
            shown = [c for c in rest if len(sizes[c]) > 1] or rest[:1]
            panels = sorted({tuple(r) for r in frame[shown].itertuples(index=False)})
            cols = min(len(panels), 3)
            rows = -(-len(panels) // cols)
            fig, grid_axes = plt.subplots(
                rows, cols, figsize=(5.5 * cols, 4.2 * rows), squeeze=False, layout="constrained"
            )
            for ax in grid_axes.flat[len(panels) :]:  # the last row's empty places
                ax.set_visible(False)
            for ax, values in zip(grid_axes.flat, panels, strict=False):
                sub = frame
                for c, v in zip(shown, values, strict=True):
                    sub = sub[sub[c] == v]
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
                        ax.text(*at, _blank(row), ha="center", va="center", color="0.35")
                    elif row["status"] != STEADY:
                        ax.plot(*at, "rx", ms=10, mew=2)
                where = zip(shown, values, strict=True)
                panel_title = ", ".join(f"{labels[c]} = {v:g}" for c, v in where)
                ax.set(xlabel=labels[x], ylabel=labels[y], title=panel_title)
            fig.suptitle(f"{name}: {title} at steady state (x: not steady)")
        else:
            x = varying[0] if varying else axes[0][0]
            fig, ax = plt.subplots(figsize=(7, 4.2))
            rows = frame.sort_values(x)
            ax.plot(rows[x], rows[column], "o-", label="map point")
            if column == "torque [N*m]" and STEADY_ROLLING in rows:
                # the quasi-static estimate beside it (docs/study.md)
                label = "steady rolling (quasi-static, spins balanced)"
                ax.plot(rows[x], rows[STEADY_ROLLING], "s--", color="0.45", label=label)
            valued = np.isfinite(rows[column].astype(float))
            bad = rows[(rows["status"] != STEADY) & valued]
            if len(bad):
                ax.plot(bad[x], bad[column], "rx", ms=10, mew=2, label="not steady")
            for _, row in rows[~valued].iterrows():
                ax.axvline(row[x], color="0.6", ls=":")
                ax.annotate(
                    _blank(row),
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


def _blank(row) -> str:
    """The label of a point without a value: its status where it did not reach a steady
    state, "none" where it did and the quantity has none there (a flange's film without
    axial load: the cell said "steady")."""
    from .maps import STEADY

    return "none" if row["status"] == STEADY else str(row["status"])
