"""The study's HTML report (``report.html`` in the study folder): the findings table, every
run with its configuration and runtime, the study's timing and every figure (figs. 8-14,
interactive). The page is built like ``rollerdyn report``'s (:mod:`rollerdyn.report`):
its style, tables and figures, plotly.js inline once, so it opens without network access.
"""

from __future__ import annotations

import html
import json
import math
from pathlib import Path

from ..report import FigureEmbedder, html_page, table
from ..report_figures import azimuth_figures, pairing_figures, time_figures
from .figures import runtime_figures
from .findings import FAIL, PASS, Finding
from .plan import Plan
from .runs import COMPLETED

_STATUS_CSS = """
td.PASS { color: #0a7a0a; font-weight: bold; } td.FAIL { color: #b00000; font-weight: bold; }
td.NOT-RUN { color: #777; font-weight: bold; } td.wrap { max-width: 60em; }
"""


def number_text(value, spec: str = ".4g") -> str:
    """A table cell: ``value`` formatted by ``spec`` where it is a number, "n/a" where it
    is not finite, as text otherwise."""
    if isinstance(value, float) and not math.isfinite(value):
        return "n/a"
    return format(value, spec) if isinstance(value, int | float) else str(value)


def _label(plan: Plan, name: str, records: dict) -> str:
    rec = records.get(name, {})
    label = plan.spec(name).label
    if rec.get("status") not in (None, COMPLETED):
        label += f" [{rec['status']}, to t = {rec.get('reached [s]', math.nan):.4g} s]"
    return label


def _findings_table(findings: list[Finding]) -> str:
    out = ["<table><thead><tr><th>finding (paper)</th><th>check</th>"]
    out.append("<th>the numbers behind it</th></tr></thead><tbody>")
    for f in findings:
        cls = f.status.replace(" ", "-")
        out.append(
            f"<tr><td>{html.escape(f.statement)}</td><td class='{cls}'>"
            f"{html.escape(f.status)}</td><td class='wrap'>{html.escape(f.numbers)}</td></tr>"
        )
    out.append("</tbody></table>")
    return "".join(out)


def _runs_table(plan: Plan, records: dict) -> str:
    header = [
        "run",
        "what",
        "changes from the configuration (SI)",
        "detector",
        "status",
        "reached [s]",
        "end [s]",
        "wall [s]",
        "steps",
        "this invocation",
        "file",
    ]
    rows = []
    for spec in plan.specs:
        rec = records.get(spec.name, {})
        rows.append(
            [
                spec.name,
                spec.label,
                spec.meta.get("changes", ""),
                spec.detector,
                rec.get("note") or rec.get("status", "not run"),
                number_text(rec.get("reached [s]", math.nan)),
                number_text(spec.t_end),
                number_text(rec.get("wall [s]", math.nan), ".1f"),
                number_text(rec.get("steps", 0), "d"),
                rec.get("action", ""),
                f"runs/{spec.file}" if rec.get("file") else "",
            ]
        )
    return table(header, rows, numeric_from=5)


def configuration_details(cfg, whose: str, note: str) -> str:
    """``cfg`` as read (its TOML text) or, built in Python, resolved to SI, folded, with
    ``note`` below (``whose``: "the study's", "the map's")."""
    text = getattr(cfg, "toml_text", "")
    if text:
        body = f"<pre>{html.escape(text)}</pre>"
        what = "as read (TOML)"
    else:
        body = f"<pre>{html.escape(json.dumps(cfg.model_dump(mode='json'), indent=2))}</pre>"
        what = "resolved to SI (built in Python, no TOML text)"
    return (
        f"<details><summary>{whose} configuration, {what}</summary>{body}</details>"
        f"<p class='note'>{note}</p>"
    )


def _configuration(plan: Plan) -> str:
    return configuration_details(
        plan.config,
        "the study's",
        "Each run changes it as its line in the table above says (axial load, "
        "inner_ring.tilt, detector, solver.dt_max); every run's file records its resolved "
        "configuration and hash (attributes config_resolved, config_sha256).",
    )


def build_page(
    plan: Plan,
    sets: dict,
    records: dict,
    findings: list[Finding],
    timing: dict,
    title: str,
) -> str:
    """The study's page (see the module's doc)."""
    embed = FigureEmbedder()
    body = [f"<h1>{html.escape(title)}</h1>"]
    body.append(
        '<nav><a href="#findings">findings</a><a href="#runs">runs</a>'
        '<a href="#figures">figures</a><a href="#configuration">configuration</a></nav>'
    )
    passed = sum(f.status == PASS for f in findings)
    failed = sum(f.status == FAIL for f in findings)
    body.append('<h2 id="findings">The paper\'s findings, checked</h2>')
    body.append(
        f"<p>{passed} PASS, {failed} FAIL, {len(findings) - passed - failed} NOT RUN "
        f"(of {len(findings)}). A check is NOT RUN when its runs give nothing to judge (not "
        "run, not at full speed, no flange contact); runs that did not finish are used "
        "where their part is meaningful, and the numbers say so. Definitions: "
        "docs/study.md.</p>"
    )
    body.append(_findings_table(findings))
    body.append('<h2 id="runs">Runs</h2>')
    body.append(_runs_table(plan, records))
    eff = timing.get("parallel efficiency", math.nan)
    wall = number_text(timing.get("study wall [s]", math.nan), ".1f")
    walls = number_text(timing.get("sum of run walls [s]", math.nan), ".1f")
    body.append(
        f"<p>This invocation: {wall} s of wall "
        f"time for the study, {timing.get('runs run', 0)} run(s) run or continued, their wall "
        f"times summing to {walls} s on "
        f"{timing.get('workers', 0)} worker(s): parallel efficiency "
        f"{number_text(100 * eff, '.0f')} %. Runs reused from the "
        "study folder cost nothing. Wall [s] in the table is each run's own time (all its "
        "parts, one core).</p>"
    )

    body.append('<h2 id="figures">Figures of the paper (sect. 5)</h2>')
    body.append(
        '<p class="note">Interactive: zoom by dragging, double-click to reset, click a '
        "legend entry to hide a run. Azimuth plots use the outputs at (at least 99 % of) "
        "full inner ring speed, or the whole run if the ring never turns.</p>"
    )
    series = [("", "Axial loads: figs. 10-13", plan.loads)]
    if plan.loads_distributed:
        title = "Axial loads with the distributed flange law (not in the paper): figs. 10-13"
        series.append(("_distributed", title, plan.loads_distributed))
    for suffix, heading, loads in series:
        load_names = [n for n in loads.values() if sets.get(n) is not None]
        body.append(f"<h3>{heading}</h3>")
        if not load_names:
            body.append("<p class='warn'>No run of this axial-load series has a result.</p>")
            continue
        labels = [_label(plan, n, records) for n in load_names]
        data = [sets[n] for n in load_names]
        for key, fig in time_figures(labels, data):
            body.append(embed(fig, key + suffix))
        for key, fig in azimuth_figures(labels, data):
            body.append(embed(fig, key + suffix))
    body.append("<h3>Inner ring tilt locked and free: figs. 8, 9</h3>")
    # (a configuration whose inner ring is free to tilt is its own free-tilt run)
    pair = dict.fromkeys((plan.tilt_locked, plan.free_tilt))
    pair = [n for n in pair if n and sets.get(n) is not None]
    if plan.free_tilt is None:
        body.append("<p class='warn'>The free-tilt run is not part of this study.</p>")
    labels = [_label(plan, n, records) for n in pair]
    data = [sets[n] for n in pair]
    free = sets.get(plan.free_tilt) if plan.free_tilt != plan.reference else None
    if free is not None and records.get(plan.free_tilt, {}).get("status") != COMPLETED:
        t_free = float(free.attrs["final_time_s"])
        locked = sets[plan.tilt_locked]
        labels.append(f"{_label(plan, plan.tilt_locked, records)}, over 0 … {t_free:.4g} s")
        data.append(locked.sel(time=locked.time <= t_free + 1e-12))
        body.append(
            f"<p class='note'>The free-tilt run did not finish (t ≤ {t_free:.4g} s): the "
            "locked run over the same time is shown beside it.</p>"
        )
    if data:
        for key, fig in pairing_figures(labels, data):
            body.append(embed(fig, key))
    body.append("<h3>Runtime: fig. 14</h3>")
    figs = runtime_figures(plan, records)
    for key, fig in figs:
        body.append(embed(fig, key))
    if not figs:
        body.append("<p class='warn'>No fig. 14 runs in this study.</p>")
    body.append('<h2 id="configuration">Configuration</h2>')
    body.append(_configuration(plan))
    return html_page(title, body, _STATUS_CSS)


def write_page(path: Path, page: str) -> Path:
    """Writes ``page`` to ``path`` atomically (a temporary file renamed over it)."""
    import os

    path = Path(path)
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    try:
        tmp.write_text(page, encoding="utf-8")
        os.replace(tmp, path)
    finally:
        tmp.unlink(missing_ok=True)
    return path
