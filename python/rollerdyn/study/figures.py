"""The study's figures: figs. 8-13 as PNG and SVG with :func:`rollerdyn.plots.plot_results`
(one line or bar group per run), fig. 14 with :func:`rollerdyn.plots.plot_runtime_study`,
and fig. 14 as plotly figures for the report.
"""

from __future__ import annotations

import math
from pathlib import Path

from ..names import GRADIENT, SEMI_ANALYTICAL
from .plan import Plan
from .runs import COMPLETED


def runtime_frame(plan: Plan, records: dict):
    """Fig. 14's table: one row per Δt_max and detector (columns as ``rollerdyn bench mbs
    --sweep-dt-max`` writes them: dt_max_s, detector, wall_s, t_reached_s, completed,
    steps, rejected_steps, status, run)."""
    import pandas as pd

    rows = []
    for dt, runs in plan.runtime.items():
        for det, name in runs.items():
            rec = records.get(name, {})
            rows.append(
                {
                    "dt_max_s": dt,
                    "detector": det,
                    "wall_s": rec.get("wall [s]", math.nan),
                    "t_reached_s": rec.get("reached [s]", math.nan),
                    "completed": int(rec.get("status") == COMPLETED),
                    "steps": rec.get("steps", 0),
                    "rejected_steps": rec.get("rejected", 0),
                    "status": rec.get("status", "not run"),
                    "run": name,
                }
            )
    columns = ["dt_max_s", "detector", "wall_s", "t_reached_s", "completed", "steps"]
    return pd.DataFrame(rows, columns=[*columns, "rejected_steps", "status", "run"])


def write_figures(plan: Plan, records: dict, outdir: Path) -> list[Path]:
    """Figs. 8-14 as PNG and SVG under ``outdir/figures``: ``axial-loads/`` (figs. 10-13
    and the roller loads, one line per load; ``axial-loads-distributed/`` the same with
    the distributed flange law, when the configuration has the point law), ``tilt/``
    (figs. 8, 9: locked and free tilt) and ``fig14_runtime_over_dt_max`` (completed runs
    only). Returns the files."""
    from ..plots import plot_results, plot_runtime_study

    runs = Path(outdir) / "runs"
    figures = Path(outdir) / "figures"
    written: list[Path] = []

    def existing(names) -> list[Path]:
        return [runs / f"{n}.nc" for n in names if n and (runs / f"{n}.nc").is_file()]

    loads = existing(plan.loads.values())
    if loads:
        written += plot_results(loads, figures / "axial-loads")
    loads = existing(plan.loads_distributed.values())
    if loads:
        written += plot_results(loads, figures / "axial-loads-distributed")
    tilt = existing(dict.fromkeys([plan.tilt_locked, plan.free_tilt]))  # a free ring: one run
    if plan.free_tilt is not None and len(tilt) == 2:
        written += plot_results(tilt, figures / "tilt")
    frame = runtime_frame(plan, records)
    done = frame[frame["completed"] == 1]
    if len(done):
        figures.mkdir(parents=True, exist_ok=True)
        title = f"{plan.config.name}, whole runs to t = {plan.t_end:.4g} s"
        written += plot_runtime_study(done, figures, title=title)
    return written


def runtime_figures(plan: Plan, records: dict) -> list:
    """(key, plotly figure) of fig. 14: wall time over Δt_max per detector, and the
    semi-analytical method's saving over Δt_max (only Δt_max with both runs completed)."""
    import plotly.graph_objects as go

    from ..report_figures import LAYOUT

    frame = runtime_frame(plan, records)
    if frame.empty:
        return []
    fig = go.Figure()
    for det, rows in frame.groupby("detector"):
        rows = rows.sort_values("dt_max_s")
        done = rows[rows["completed"] == 1]
        fig.add_scatter(x=done.dt_max_s, y=done.wall_s, mode="lines+markers", name=str(det))
        cut = rows[rows["completed"] == 0]
        if len(cut):
            fig.add_scatter(
                x=cut.dt_max_s,
                y=cut.wall_s,
                mode="markers",
                marker=dict(symbol="x", size=10),
                name=f"{det}: not finished (wall time until stopped)",
            )
    fig.update_layout(
        title="fig. 14 (runtime): wall time of the whole run over Δt_max, one core per run",
        xaxis_title="maximum step size Δt_max [s]",
        yaxis_title="wall time of the run [s]",
        **LAYOUT,
    )
    fig.update_xaxes(type="log")
    figs = [("fig14_wall", fig)]
    pivot = frame[frame["completed"] == 1].pivot(
        index="dt_max_s", columns="detector", values="wall_s"
    )
    if {SEMI_ANALYTICAL, GRADIENT} <= set(pivot.columns):
        pivot = pivot.dropna()
        saving = 100.0 * (1.0 - pivot[SEMI_ANALYTICAL] / pivot[GRADIENT])
        fig = go.Figure()
        fig.add_scatter(x=pivot.index, y=saving, mode="lines+markers", name="saving")
        fig.add_hline(y=35.0, line=dict(color="#999", dash="dash"))
        fig.update_layout(
            title="fig. 14: runtime saving of the semi-analytical method over Δt_max "
            "(dashed: the paper's 35 % at its Δt_max)",
            xaxis_title="maximum step size Δt_max [s]",
            yaxis_title="1 - wall(semi-analytical) / wall(gradient) [%]",
            **LAYOUT,
        )
        fig.update_xaxes(type="log")
        figs.append(("fig14_saving", fig))
    return figs
