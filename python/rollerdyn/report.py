"""One self-contained HTML report of one or more result files (``rollerdyn report``).

The page holds the inputs of each run (its attributes and the load and speed histories
from the data), a summary table, the paper's figures 8-13 as interactive plotly plots and
an animated view of the roller set that can be scrubbed through time. Every script and
style is inline (plotly.js included once), so the file opens without network access.
All quantities are SI (lengths of the roller-set view in mm, angles of the azimuth plots
in degrees, as their axes say).
"""

from __future__ import annotations

import html
import json
import math
from pathlib import Path
from typing import Annotated

import numpy as np
import typer
import xarray as xr

from .simulation import FLANGES, PAIRINGS, carried_axial_force

MAX_FRAMES = 200
"""Most frames of the roller-set animation; longer runs are subsampled evenly."""

MAX_POINTS = 40_000
"""Most points per trace of the azimuth scatter plots (figs. 12, 13); evenly thinned."""

LAST_SHARE = 0.2
"""Share of the run (by time, at its end) over which the frictional torque is averaged."""

REQUIRED = (
    "frictional_torque",
    "radial_load",
    "axial_load",
    "ring_speed",
    "azimuth",
    "skew",
    "position",
    "srr_inner",
    "inner_normal_force",
    "outer_normal_force",
    "flange_pairing",
    "flange_normal_force",
    "flange_friction_force",
    "flange_axial_force",
)
"""Variables a rollerdyn result must hold for the report."""


class ReportError(ValueError):
    """A file that cannot be reported on: missing, unreadable or not a rollerdyn result."""


# --------------------------------------------------------------------------- reading


def open_result(path: Path, required: tuple[str, ...] = REQUIRED) -> xr.Dataset:
    """The result in ``path``, loaded into memory; :class:`ReportError` (one line naming
    the file and what is wrong) if it is missing, unreadable or not a rollerdyn result
    (one of the ``required`` variables or its final time missing, or no outputs)."""
    path = Path(path)
    if path.is_dir():
        raise ReportError(f"{path}: is a folder, not a result file")
    if not path.is_file():
        raise ReportError(f"{path}: result file not found")
    if path.stat().st_size == 0:
        raise ReportError(f"{path}: not a rollerdyn result (the file is empty)")
    try:
        with xr.open_dataset(path, engine="h5netcdf") as opened:
            ds = opened.load()
    except Exception as err:  # h5py/h5netcdf raise several kinds for non-HDF5 input
        reason = " ".join(str(err).split()) or type(err).__name__
        raise ReportError(
            f"{path}: not a rollerdyn result (cannot be read as netCDF: {reason})"
        ) from None
    missing = [v for v in required if v not in ds]
    if missing or "final_time_s" not in ds.attrs:
        what = _listed(missing) if missing else "attribute final_time_s"
        raise ReportError(f"{path}: not a rollerdyn result (missing {what})")
    if ds.sizes.get("time", 0) == 0:
        raise ReportError(f"{path}: the result holds no outputs (empty time axis)")
    return ds


def _listed(names: list[str], most: int = 4) -> str:
    """``a, b, c and 5 more``: the first ``most`` names and how many follow."""
    shown = ", ".join(names[:most])
    return shown + (f" and {len(names) - most} more" if len(names) > most else "")


def _labels(paths: list[Path], sets: list[xr.Dataset]) -> list[str]:
    stems = [p.stem for p in paths]
    names = stems if len(set(stems)) == len(stems) else [str(p) for p in paths]
    return [
        f"{n} (F_a = {float(ds.axial_load[-1]):.0f} N)" for n, ds in zip(names, sets, strict=True)
    ]


def _full_speed(ds: xr.Dataset) -> xr.Dataset:
    """The part of the run at (at least 99 % of) full inner ring speed (as plots.py)."""
    speed = np.abs(ds.ring_speed.values)
    if speed.max() <= 0:
        return ds
    return ds.isel(time=np.nonzero(speed >= 0.99 * speed.max())[0])


def _time_weights(t: np.ndarray) -> np.ndarray:
    """Trapezoid weights of the outputs: the time each output stands for."""
    if t.size < 2:
        return np.ones_like(t, dtype=float)
    w = np.empty_like(t, dtype=float)
    w[0] = (t[1] - t[0]) / 2
    w[-1] = (t[-1] - t[-2]) / 2
    w[1:-1] = (t[2:] - t[:-2]) / 2
    return w


def _nanmax(a) -> float:
    a = np.asarray(a, dtype=float)
    a = a[np.isfinite(a)]
    return float(a.max()) if a.size else float("nan")


def max_abs_srr_inner(ds: xr.Dataset) -> float:
    """Largest |slide-to-roll ratio| at the inner race over the outputs at which the inner
    ring turns (any roller; NaN outputs ignored); NaN if it never turns: before the ring
    turns the ratio has no meaning (it divides by a rolling speed that is not there)."""
    turning = np.abs(np.asarray(ds.ring_speed.values, dtype=float)) > 0.0
    if not turning.any():
        return float("nan")
    return _nanmax(np.abs(ds.srr_inner.values[turning]))


# --------------------------------------------------------------------------- summary

SUMMARY_ROWS = (
    ("mean_torque", "mean bearing frictional torque, last 20 % of the run", "N*m"),
    ("max_race_load", "max. roller-race load (inner and outer race)", "N"),
    ("max_flange_force", "max. roller end / flange normal force", "N"),
    ("max_srr_inner", "max. |slide-to-roll ratio| at the inner race", "-"),
    ("final_time", "final time", "s"),
    ("steps", "solver steps (rejected)", "-"),
    ("wall", "wall time", "s"),
    ("status", "status", ""),
)


#: Attributes that hold the configuration's text (shown as text, not in the table).
_CONFIG_TEXTS = ("config_toml", "config_resolved", "config")


def _pretty_json(text: str) -> str:
    """``text`` indented if it is JSON, else as it is."""
    import json

    try:
        return json.dumps(json.loads(text), indent=2)
    except ValueError:
        return text


def summary(ds: xr.Dataset) -> dict:
    """The summary quantities of one result (SI), keyed as :data:`SUMMARY_ROWS`."""
    t = ds.time.values
    t0, t1 = float(t[0]), float(t[-1])
    last = t >= t1 - LAST_SHARE * (t1 - t0)
    a = ds.attrs
    status = "completed" if int(a.get("completed", 0)) else "unfinished"
    if "error" in a:
        status += f": {a['error']}"
    return {
        "mean_torque": float(np.mean(ds.frictional_torque.values[last])),
        "max_race_load": max(
            _nanmax(ds.inner_normal_force.values), _nanmax(ds.outer_normal_force.values)
        ),
        "max_flange_force": _nanmax(ds.flange_normal_force.values),
        "max_srr_inner": max_abs_srr_inner(ds),
        "final_time": float(a["final_time_s"]),
        "steps": (int(a.get("stats_steps", -1)), int(a.get("stats_error_test_failures", 0))),
        "wall": float(a.get("stats_total_seconds", float("nan"))),
        "status": status,
    }


def _fmt(key: str, value) -> str:
    if key == "steps":
        return "n/a" if value[0] < 0 else f"{value[0]} ({value[1]})"
    if isinstance(value, str):
        return value
    if not math.isfinite(value):
        return "n/a"
    return f"{value:.4g}"


# --------------------------------------------------------------------------- figures

_LAYOUT = dict(
    template="plotly_white",
    height=420,
    margin=dict(l=70, r=30, t=60, b=60),
    legend=dict(orientation="h", yanchor="bottom", y=1.02, xanchor="left", x=0),
)


def _thin(n: int, most: int) -> np.ndarray:
    """Indices of at most ``most`` of ``n`` items, evenly spread, first and last kept."""
    if n <= most:
        return np.arange(n)
    return np.unique(np.linspace(0, n - 1, most).round().astype(int))


def _time_figures(labels, sets) -> list:
    import plotly.graph_objects as go

    figs = []
    fig = go.Figure()
    for label, ds in zip(labels, sets, strict=True):
        fig.add_scatter(x=ds.time.values, y=ds.frictional_torque.values, name=label)
    fig.update_layout(
        title="fig. 10: bearing frictional torque",
        xaxis_title="time t [s]",
        yaxis_title="bearing frictional torque [N·m]",
        **_LAYOUT,
    )
    figs.append(("fig10", fig))
    fig = go.Figure()
    for label, ds in zip(labels, sets, strict=True):
        f = ds.flange_friction_force.isel(roller=0).sum("flange").values
        fig.add_scatter(x=ds.time.values, y=f, name=label)
    fig.update_layout(
        title="fig. 11: flange friction force of roller 0 (sum over its four flange contacts)",
        xaxis_title="time t [s]",
        yaxis_title="flange friction force, roller 0 [N]",
        **_LAYOUT,
    )
    figs.append(("fig11", fig))
    return figs


def _azimuth_figures(labels, sets) -> list:
    import plotly.graph_objects as go

    figs = []
    for key, title, ylabel in (
        (
            "fig12",
            "fig. 12: axial force carried by a roller over its azimuth (from the inner ring's"
            " flanges, rollers pooled)",
            "axial force carried by the roller [N]",
        ),
        (
            "fig13",
            "fig. 13: slide-to-roll ratio at the inner race over azimuth (rollers pooled)",
            "slide-to-roll ratio, inner race [-]",
        ),
        (
            "loads",
            "roller-inner race load over azimuth (rollers pooled)",
            "roller-inner race load [N]",
        ),
    ):
        fig = go.Figure()
        for label, ds in zip(labels, sets, strict=True):
            d = _full_speed(ds)
            psi = np.degrees(np.mod(d.azimuth.values.ravel(), 2 * np.pi))
            if key == "fig12":
                v = carried_axial_force(d).values.ravel()
            elif key == "fig13":
                v = d.srr_inner.values.ravel()
            else:
                v = d.inner_normal_force.values.ravel()
            keep = _thin(psi.size, MAX_POINTS)
            fig.add_scatter(x=psi[keep], y=v[keep], mode="markers", marker=dict(size=3), name=label)
        fig.add_vline(x=180.0, line=dict(color="#999", width=1, dash="dash"))
        fig.update_layout(
            title=title,
            xaxis_title="roller azimuth ψ [deg] (load zone centre at 180 deg)",
            yaxis_title=ylabel,
            **_LAYOUT,
        )
        fig.update_xaxes(range=[0, 360], dtick=45)
        figs.append((key, fig))
    return figs


def pairing_shares(ds: xr.Dataset, ring: str) -> dict:
    """Share of time per roller end / flange pairing at ``ring`` ('inner' or 'outer'),
    over every roller and both flanges of the ring, with 'none' for no contact (the
    shares add up to 1; each output weighted by the time it stands for)."""
    idx = [k for k, f in enumerate(FLANGES) if f.startswith(ring)]
    pairing = ds.flange_pairing.isel(flange=idx).values  # (time, roller, 2)
    w = _time_weights(ds.time.values)[:, None, None] * np.ones(pairing.shape)
    total = w.sum()
    shares = {name: float(w[pairing == k].sum() / total) for k, name in enumerate(PAIRINGS)}
    shares["none"] = float(w[pairing < 0].sum() / total)
    return shares


def _pairing_figures(labels, sets) -> list:
    import plotly.graph_objects as go

    figs = []
    for ring, key in (("inner", "fig8"), ("outer", "fig9")):
        fig = go.Figure()
        for label, ds in zip(labels, sets, strict=True):
            shares = pairing_shares(ds, ring)
            fig.add_bar(x=list(shares), y=list(shares.values()), name=label)
        fig.update_layout(
            title=f"fig. {key[3:]}: roller end / flange pairings in contact at the {ring} ring",
            xaxis_title="pairing (roller end - flange; 'none': no contact)",
            yaxis_title="share of time, all rollers and both flanges [-]",
            barmode="group",
            **_LAYOUT,
        )
        figs.append((key, fig))
    return figs


def _inputs_figure(labels, sets):
    import plotly.io as pio
    from plotly.subplots import make_subplots

    fig = make_subplots(rows=3, cols=1, shared_xaxes=True, vertical_spacing=0.06)
    colours = pio.templates["plotly_white"].layout.colorway or ("#636efa",)
    for j, (label, ds) in enumerate(zip(labels, sets, strict=True)):
        colour = colours[j % len(colours)]
        for row, var in enumerate(("radial_load", "axial_load", "ring_speed"), start=1):
            fig.add_scatter(
                x=ds.time.values,
                y=ds[var].values,
                name=label,
                legendgroup=label,
                showlegend=row == 1,
                line=dict(color=colour),
                row=row,
                col=1,
            )
    fig.update_yaxes(title_text="radial load [N]", row=1, col=1)
    fig.update_yaxes(title_text="axial load [N]", row=2, col=1)
    fig.update_yaxes(title_text="inner ring speed [rad/s]", row=3, col=1)
    fig.update_xaxes(title_text="time t [s]", row=3, col=1)
    fig.update_layout(title="loads and speed over time (from the data)", **_LAYOUT)
    fig.update_layout(height=620)
    return fig


def animation_figure(ds: xr.Dataset, max_frames: int = MAX_FRAMES):
    """The roller set seen along the bearing axis, one frame per (subsampled) output:
    roller centres on their orbit (y up, z to the right, mm), marker size and colour =
    roller-inner race normal force, a short line along the orbit = skew."""
    import plotly.graph_objects as go

    nt, z = ds.sizes["time"], ds.sizes["roller"]
    frames_idx = _thin(nt, max(1, max_frames))
    t = ds.time.values
    pos = ds.position.values  # (time, roller, xyz) in m
    y, zc = pos[..., 1] * 1e3, pos[..., 2] * 1e3
    psi = ds.azimuth.values
    skew = ds.skew.values
    force = ds.inner_normal_force.values
    r_orbit = float(np.nanmean(np.hypot(y, zc)))
    if not (r_orbit > 0):
        r_orbit = 1.0
    f_max = _nanmax(force)
    f_max = f_max if f_max > 0 else 1.0
    s_max = _nanmax(np.abs(skew))
    s_max = s_max if s_max > 0 else 1.0
    line_len = 0.15 * r_orbit  # a skew of s_max draws a line this long (mm)
    symbols = ["diamond"] + ["circle"] * (z - 1)

    def traces(i: int):
        f = np.nan_to_num(force[i], nan=0.0)
        size = 8 + 22 * np.clip(f / f_max, 0.0, 1.0)
        # Direction of increasing azimuth in the (z, y) plot plane: (cos psi, -sin psi).
        ex, ey = np.cos(psi[i]), -np.sin(psi[i])
        length = line_len * np.nan_to_num(skew[i]) / s_max
        lx, ly = [], []
        for k in range(z):
            lx += [zc[i, k], zc[i, k] + length[k] * ex[k], None]
            ly += [y[i, k], y[i, k] + length[k] * ey[k], None]
        text = [
            f"roller {k}<br>ψ = {math.degrees(psi[i, k]) % 360:.1f} deg"
            f"<br>F_inner = {force[i, k]:.1f} N<br>skew = {skew[i, k] * 1e3:.3f} mrad"
            for k in range(z)
        ]
        markers = go.Scatter(
            x=zc[i],
            y=y[i],
            mode="markers",
            name="rollers (size, colour: inner race load)",
            text=text,
            hoverinfo="text",
            marker=dict(
                size=size,
                color=f,
                cmin=0.0,
                cmax=f_max,
                colorscale="Viridis",
                symbol=symbols,
                line=dict(color="#333", width=1),
                colorbar=dict(title=dict(text="inner race<br>load [N]")),
            ),
        )
        lines = go.Scatter(
            x=lx,
            y=ly,
            mode="lines",
            name=f"skew (full line = {s_max * 1e3:.3g} mrad)",
            line=dict(color="#d62728", width=3),
            hoverinfo="skip",
        )
        return [markers, lines]

    theta = np.linspace(0, 2 * np.pi, 181)
    orbit = go.Scatter(
        x=r_orbit * np.sin(theta),
        y=r_orbit * np.cos(theta),
        mode="lines",
        name="mean orbit",
        line=dict(color="#bbb", width=1, dash="dot"),
        hoverinfo="skip",
    )
    shown = len(frames_idx) - 1  # the page opens on the last frame
    frames = [
        go.Frame(data=traces(i), traces=[1, 2], name=f"{k}") for k, i in enumerate(frames_idx)
    ]
    steps = [
        dict(
            method="animate",
            label=f"{t[i] * 1e3:.4g}",
            args=[
                [f"{k}"],
                dict(
                    mode="immediate",
                    frame=dict(duration=0, redraw=False),
                    transition=dict(duration=0),
                ),
            ],
        )
        for k, i in enumerate(frames_idx)
    ]
    lim = 1.3 * r_orbit
    fig = go.Figure(data=[orbit, *traces(frames_idx[shown])], frames=frames)
    fig.update_layout(
        template="plotly_white",
        height=720,
        margin=dict(l=70, r=30, t=70, b=150),
        title="roller set seen along the bearing axis (roller 0: diamond); drag the slider "
        "to scrub through time",
        xaxis=dict(title="z [mm]", range=[-lim, lim], zeroline=False),
        yaxis=dict(
            title="y [mm] (radial load along -y)",
            range=[-lim, lim],
            scaleanchor="x",
            scaleratio=1,
            zeroline=False,
        ),
        legend=dict(orientation="h", yanchor="bottom", y=1.0, xanchor="left", x=0),
        sliders=[
            dict(
                active=shown,
                steps=steps,
                currentvalue=dict(prefix="time t [ms] = "),
                pad=dict(t=60),
                len=0.7,
                x=0.3,
            )
        ],
        updatemenus=[
            dict(
                type="buttons",
                direction="left",
                x=0.0,
                y=0.0,
                xanchor="left",
                yanchor="top",
                pad=dict(t=70, r=10),
                showactive=False,
                buttons=[
                    _animate_button("play from start", None, 60, fromcurrent=False),
                    _animate_button("play", None, 60, fromcurrent=True),
                    _animate_button("pause", [None], 0),
                ],
            )
        ],
    )
    return fig, len(frames_idx)


def _animate_button(label: str, frames, duration_ms: int, fromcurrent: bool = True) -> dict:
    """A plotly updatemenu button that animates ``frames`` (None: all; [None]: stop)."""
    options = dict(
        frame=dict(duration=duration_ms, redraw=False),
        transition=dict(duration=0),
        mode="immediate",
    )
    if frames is None:
        options["fromcurrent"] = fromcurrent
    return dict(label=label, method="animate", args=[frames, options])


# --------------------------------------------------------------------------- page

_CSS = """
body { font-family: system-ui, -apple-system, "Segoe UI", Roboto, sans-serif; margin: 0;
       color: #222; background: #fafafa; }
main { max-width: 1200px; margin: 0 auto; padding: 1em 2em 4em; }
h1 { font-size: 1.6em; } h2 { border-bottom: 1px solid #ccc; padding-bottom: .2em;
       margin-top: 2em; } h3 { margin-top: 1.5em; }
table { border-collapse: collapse; margin: .5em 0 1em; background: #fff; }
th, td { border: 1px solid #ddd; padding: .3em .7em; text-align: left; vertical-align: top; }
th { background: #f0f0f0; } td.num { text-align: right; font-variant-numeric: tabular-nums; }
pre { background: #fff; border: 1px solid #ddd; padding: .8em; overflow-x: auto; }
.figure { background: #fff; border: 1px solid #e3e3e3; margin: 1em 0; padding: .3em; }
.note { color: #555; font-size: .92em; } .warn { color: #a40000; }
nav a { margin-right: 1em; }
"""


def _table(header: list[str], rows: list[list[str]], numeric_from: int = 1) -> str:
    out = ["<table><thead><tr>"]
    out += [f"<th>{html.escape(h)}</th>" for h in header]
    out.append("</tr></thead><tbody>")
    for row in rows:
        out.append("<tr>")
        for j, cell in enumerate(row):
            cls = ' class="num"' if j >= numeric_from else ""
            out.append(f"<td{cls}>{html.escape(str(cell))}</td>")
        out.append("</tr>")
    out.append("</tbody></table>")
    return "".join(out)


def _attr_text(value) -> str:
    if isinstance(value, np.ndarray):
        return json.dumps(value.tolist())
    if isinstance(value, np.generic):
        return str(value.item())
    return str(value)


def build_html(paths: list[Path], max_frames: int = MAX_FRAMES) -> str:
    """The report page for the results in ``paths`` (see :func:`report`)."""
    import plotly
    import plotly.io as pio

    paths = [Path(p) for p in paths]
    if not paths:
        raise ReportError("no result files given")
    sets = [open_result(p) for p in paths]
    labels = _labels(paths, sets)
    config = {"displaylogo": False, "responsive": True}
    js_included = False

    def embed(fig, div_id: str) -> str:
        nonlocal js_included
        snippet = pio.to_html(
            fig,
            config=config,
            auto_play=False,
            include_plotlyjs=not js_included,
            full_html=False,
            div_id=f"plot-{div_id}",
        )
        js_included = True
        return f'<div class="figure">{snippet}</div>'

    body = []
    names = ", ".join(html.escape(str(p)) for p in paths)
    body.append(f"<h1>rollerdyn report</h1><p>Results: {names}</p>")
    body.append(
        '<nav><a href="#summary">summary</a><a href="#inputs">inputs</a>'
        '<a href="#figures">figures</a><a href="#animation">roller set</a></nav>'
    )

    # Summary.
    body.append('<h2 id="summary">Summary</h2>')
    values = [summary(ds) for ds in sets]
    rows = []
    for key, text, unit in SUMMARY_ROWS:
        rows.append([text, unit] + [_fmt(key, v[key]) for v in values])
    body.append(_table(["quantity", "unit", *labels], rows, numeric_from=2))
    body.append(
        f'<p class="note">Mean torque over the last {LAST_SHARE:.0%} of each run\'s simulated '
        "time; maxima over every output, roller and contact. Slide-to-roll ratio: eq. 49 of "
        "the paper, over the outputs at which the inner ring turns ('n/a' if it never "
        "does: the ratio has no meaning before). Steps: accepted solver steps (rejected "
        "in brackets); wall time: the run's, on one core.</p>"
    )

    # Inputs.
    body.append('<h2 id="inputs">Inputs</h2>')
    for p, label, ds in zip(paths, labels, sets, strict=True):
        body.append(f"<h3>{html.escape(label)}: {html.escape(str(p))}</h3>")
        if "error" in ds.attrs:
            body.append(
                f'<p class="warn">The run stopped early: {html.escape(ds.attrs["error"])}</p>'
            )
        plain = [
            [k, _attr_text(v)]
            for k, v in ds.attrs.items()
            if not k.startswith("stats_") and k not in _CONFIG_TEXTS
        ]
        stats = [[k[6:], _attr_text(v)] for k, v in ds.attrs.items() if k.startswith("stats_")]
        body.append(_table(["attribute", "value"], plain, numeric_from=9))
        if stats:
            body.append("<details><summary>solver statistics</summary>")
            body.append(_table(["statistic", "value"], stats, numeric_from=1))
            body.append("</details>")
        text = next(
            (ds.attrs[k] for k in ("config_toml", "config") if isinstance(ds.attrs.get(k), str)),
            "",
        )
        resolved = ds.attrs.get("config_resolved")
        if text:
            body.append("<details open><summary>configuration (TOML, as read)</summary>")
            body.append(f"<pre>{html.escape(text)}</pre></details>")
        elif isinstance(resolved, str) and resolved:
            body.append(
                "<details open><summary>configuration (resolved to SI; built in Python, "
                "no TOML text)</summary>"
            )
            body.append(f"<pre>{html.escape(_pretty_json(resolved), quote=False)}</pre></details>")
        else:
            body.append(
                '<p class="note">The result file holds no configuration text; the '
                "attributes above and the load and speed histories below are what it "
                "records of the inputs.</p>"
            )
    body.append(embed(_inputs_figure(labels, sets), "inputs"))

    # Figures.
    body.append('<h2 id="figures">Figures of the paper (sect. 5.2)</h2>')
    body.append(
        '<p class="note">Interactive: zoom by dragging, double-click to reset, click a '
        "legend entry to hide a run. Azimuth plots use the outputs at (at least 99 % of) "
        "full inner ring speed, or the whole run if the ring never turns.</p>"
    )
    for key, fig in _time_figures(labels, sets):
        body.append(embed(fig, key))
    for key, fig in _pairing_figures(labels, sets):
        body.append(embed(fig, key))
    for key, fig in _azimuth_figures(labels, sets):
        body.append(embed(fig, key))

    # Animation.
    body.append('<h2 id="animation">Roller set over time</h2>')
    body.append(
        '<p class="note">Seen along the bearing axis: roller centres (marker size and colour: '
        "roller-inner race normal force), roller 0 as a diamond, a red line along the orbit "
        "for the skew (its length scaled to the largest skew of the run, pointing forward "
        "along increasing azimuth for positive skew). Drag the slider to scrub through time; "
        "frames are evenly subsampled outputs.</p>"
    )
    for j, (label, ds) in enumerate(zip(labels, sets, strict=True)):
        fig, n = animation_figure(ds, max_frames)
        body.append(f"<h3>{html.escape(label)} ({n} frames of {ds.sizes['time']} outputs)</h3>")
        body.append(embed(fig, f"animation{j}"))

    body.append(
        f'<p class="note">Made by rollerdyn with plotly {plotly.__version__} (plotly.js '
        "inline: the page needs no network access).</p>"
    )
    # Marks the page once every figure's script has run (used by the tests).
    body.append(
        "<script>document.body.setAttribute('data-plots', "
        "String(document.querySelectorAll('.js-plotly-plot').length));</script>"
    )
    return (
        '<!DOCTYPE html>\n<html lang="en"><head><meta charset="utf-8">'
        '<meta name="viewport" content="width=device-width, initial-scale=1">'
        f"<title>rollerdyn report: {names}</title><style>{_CSS}</style></head>"
        f"<body><main>{''.join(body)}</main></body></html>\n"
    )


def report(paths, out, max_frames: int = MAX_FRAMES) -> Path:
    """Writes one self-contained HTML report of the result files ``paths`` (netCDF written
    by ``rollerdyn run``) to ``out`` and returns its path. Raises :class:`ReportError` for
    a missing file or one that is not a rollerdyn result, and for ``out`` naming one of
    them."""
    from .paths import same_file

    if isinstance(paths, str | Path):
        paths = [paths]
    paths, out = [Path(p) for p in paths], Path(out)
    for p in paths:
        if same_file(out, p):
            raise ReportError(f"-o {out}: is the result file {p}, an input; choose another")
    page = build_html(paths, max_frames=max_frames)
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(page, encoding="utf-8")
    return out


def check_report_output(results: list[Path], output: Path) -> Path:
    """Checks before any work that ``output`` may take the report (see
    :mod:`rollerdyn.paths`): not an input, its folder there and writable, and if it
    exists an earlier report (``.html``/``.htm``), not a result or any other file."""
    from .paths import check_output_file, is_result_file

    output = Path(output)
    replaceable = output.suffix.lower() in (".html", ".htm") and not is_result_file(output)
    return check_output_file(
        output,
        "-o",
        inputs=[(f"the result file {r}", r) for r in results],
        overwrite=replaceable,
        hint="; only an earlier report (.html) is replaced: choose another name",
    )


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
    cannot take the report (checked before any work).
    """
    from .cli import checked, error, refuse, say

    checked(check_report_output, results, output)
    try:
        written = report(results, output, max_frames=max_frames)
    except ReportError as err:
        raise refuse(err) from None
    except OSError as err:
        error(f"-o {output}: could not write the report ({err})")
        raise typer.Exit(1) from None
    size = written.stat().st_size / 1e6
    say(f"wrote {written} ({size:.1f} MB)")
