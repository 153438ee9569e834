"""The operating map's HTML report (``report.html`` in the map folder): the points with
their steady outputs, the thermal balance and the thermally permissible speeds where the
map has them, the maps (the PNG files of ``figures/``, embedded) and the configuration.
One self-contained file, styled as ``rollerdyn report``'s pages (:mod:`rollerdyn.report`).
"""

from __future__ import annotations

import base64
import html
import math
from pathlib import Path

from ..report import html_page, table
from .maps import MAP_COLUMNS
from .report_page import configuration_details, number_text
from .thermal import PERMISSIBLE_COLUMNS, THERMAL_COLUMNS


def frame_table(frame, columns) -> str:
    """``frame``'s rows as an HTML table of ``columns`` (column, heading, format); a column
    the frame lacks is left empty."""
    header = [head for _, head, _ in columns]
    rows = [
        [number_text(row.get(col, ""), spec) for col, _, spec in columns]
        for _, row in frame.iterrows()
    ]
    return table(header, rows, numeric_from=len(columns))


def _png(path: Path) -> str:
    data = base64.b64encode(Path(path).read_bytes()).decode("ascii")
    alt = html.escape(Path(path).stem)
    return f'<div class="figure"><img alt="{alt}" src="data:image/png;base64,{data}"></div>'


def build_map_page(
    frame,
    figures,
    *,
    title: str,
    config,
    thermal=None,
    permissible=None,
    dissipation=None,
    timing=None,
) -> str:
    """The map's page (see the module's doc). ``figures``: the files the map wrote (its
    PNG files are embedded); ``config``: the map's configuration; ``dissipation``: the
    balance's :class:`.thermal.Dissipation`, with ``thermal``."""
    body = [f"<h1>{html.escape(title)}</h1>"]
    steady = int((frame["status"] == "steady").sum())
    body.append('<h2 id="points">Points</h2>')
    body.append(
        f"<p>{steady} of {len(frame)} points steady. Each point ran from its start until its "
        "friction torque, roller-set speed loss and largest flange force, averaged over "
        'windows of simulated time, stopped changing (docs/study.md, "The outputs and the '
        'steady-state criterion"); the values are those of its last window. Λ is the median '
        "specific film thickness h_c/σ of the contacts in contact (below 1 boundary, above 3 "
        "full-film lubrication). Beside each point, the quasi-static estimate: the friction "
        "torque of steady rolling at its speed, loads and oil temperature (rollerdyn statics, "
        "each roller spinning where its friction moments balance; docs/statics.md), which "
        "the point's torque is divided by in the map torque_over_steady_rolling.</p>"
    )
    body.append(frame_table(frame, MAP_COLUMNS))
    if timing and not timing.get("runs run", 0):
        body.append("<p class='note'>This invocation ran nothing: every point was there.</p>")
    elif timing:
        eff = timing.get("parallel efficiency", math.nan)
        wall = number_text(timing.get("study wall [s]", math.nan), ".1f")
        body.append(
            f"<p class='note'>This invocation: {wall} s of wall time, "
            f"{timing.get('runs run', 0)} point(s) run or continued on "
            f"{timing.get('workers', 0) or '?'} worker(s) (parallel efficiency "
            f"{number_text(100 * eff, '.0f')} %); points already in the folder cost nothing.</p>"
        )
    if thermal is not None:
        body.append('<h2 id="thermal">Thermal balance</h2>')
        body.append(
            "<p>The temperature at which the friction power the map measured equals the heat "
            f"the bearing gives off, {html.escape(dissipation.describe())} (docs/study.md, "
            '"The thermal balance").</p>'
        )
        body.append(frame_table(thermal, THERMAL_COLUMNS))
    if permissible is not None:
        body.append('<h2 id="permissible">Thermally permissible speed</h2>')
        body.append(
            "<p>The lowest speed at which the thermal balance reaches the permissible "
            "temperature.</p>"
        )
        body.append(frame_table(permissible, PERMISSIBLE_COLUMNS))
    pngs = [Path(f) for f in figures if Path(f).suffix == ".png" and Path(f).is_file()]
    body.append('<h2 id="figures">Maps</h2>')
    if pngs:
        body.append(
            "<p class='note'>A cross marks a point that is not steady at its maximum time; a "
            "point without a value is labelled with its status. The same figures are in "
            "figures/ as PNG and SVG.</p>"
        )
        body += [_png(p) for p in pngs]
    else:
        body.append("<p class='warn'>No figure: no point has a value.</p>")
    body.append('<h2 id="configuration">Configuration</h2>')
    body.append(
        configuration_details(
            config,
            "the map's",
            "Each point sets its speed, loads and oil temperature and starts as the map says; "
            "its file records its resolved configuration and hash.",
        )
    )
    nav = ["points", "figures", "configuration"]
    if thermal is not None:
        nav.insert(1, "thermal")
    if permissible is not None:
        nav.insert(2, "permissible")
    links = "".join(f'<a href="#{n}">{n}</a>' for n in nav)
    body.insert(1, f"<nav>{links}</nav>")
    return html_page(title, body)


__all__ = ["build_map_page", "frame_table"]
