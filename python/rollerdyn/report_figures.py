"""The figures of the HTML report (:mod:`rollerdyn.report`), as plotly figures: the
paper's figures 8-13 over every result, the load and speed histories, and the animated
roller set. Quantities are SI (lengths of the roller-set view in mm, azimuths in degrees,
as the axes say)."""

from __future__ import annotations

import math

import numpy as np
import xarray as xr

from .limits import MAX_FRAMES
from .names import PAIRINGS, flange_indices
from .simulation import carried_axial_force, full_speed, recorded

MAX_POINTS = 40_000
"""Most points per trace of the azimuth scatter plots (figs. 12, 13); evenly thinned."""


def _time_weights(t: np.ndarray) -> np.ndarray:
    """Trapezoid weights of the outputs: the time each output stands for."""
    if t.size < 2:
        return np.ones_like(t, dtype=float)
    w = np.empty_like(t, dtype=float)
    w[0] = (t[1] - t[0]) / 2
    w[-1] = (t[-1] - t[-2]) / 2
    w[1:-1] = (t[2:] - t[:-2]) / 2
    return w


def nanmax(a) -> float:
    """Largest finite value of ``a`` (NaN if there is none)."""
    a = np.asarray(a, dtype=float)
    a = a[np.isfinite(a)]
    return float(a.max()) if a.size else float("nan")


#: The figures' layout (shared with the study's fig. 14, rollerdyn.study.figures).
LAYOUT = dict(
    template="plotly_white",
    height=420,
    margin=dict(l=70, r=30, t=60, b=60),
    legend=dict(orientation="h", yanchor="bottom", y=1.02, xanchor="left", x=0),
)


def having(labels, sets, *groups: str) -> tuple[list, list]:
    """The labels and results of ``labels``/``sets`` that recorded every output group
    ``groups`` (:func:`rollerdyn.simulation.recorded`)."""
    kept = [
        (lab, ds)
        for lab, ds in zip(labels, sets, strict=True)
        if all(recorded(ds, g) for g in groups)
    ]
    return [lab for lab, _ in kept], [ds for _, ds in kept]


def _thin(n: int, most: int) -> np.ndarray:
    """Indices of at most ``most`` of ``n`` items, evenly spread, first and last kept."""
    if n <= most:
        return np.arange(n)
    return np.unique(np.linspace(0, n - 1, most).round().astype(int))


def time_figures(labels, sets) -> list:
    """(key, figure) of figs. 10 and 11: frictional torque and roller 0's flange friction
    force over time, one trace per result."""
    import plotly.graph_objects as go

    figs = []
    fig = go.Figure()
    for label, ds in zip(labels, sets, strict=True):
        fig.add_scatter(x=ds.time.values, y=ds.frictional_torque.values, name=label)
    fig.update_layout(
        title="fig. 10: bearing frictional torque",
        xaxis_title="time t [s]",
        yaxis_title="bearing frictional torque [N·m]",
        **LAYOUT,
    )
    figs.append(("fig10", fig))
    labels, sets = having(labels, sets, "flanges")
    if not sets:
        return figs
    fig = go.Figure()
    for label, ds in zip(labels, sets, strict=True):
        f = ds.flange_friction_force.isel(roller=0).sum("flange").values
        fig.add_scatter(x=ds.time.values, y=f, name=label)
    fig.update_layout(
        title="fig. 11: flange friction force of roller 0 (sum over its four flange contacts)",
        xaxis_title="time t [s]",
        yaxis_title="flange friction force, roller 0 [N]",
        **LAYOUT,
    )
    figs.append(("fig11", fig))
    return figs


def azimuth_figures(labels, sets) -> list:
    """(key, figure) of figs. 12 and 13 and of the roller-inner race load, over the roller
    azimuth (rollers pooled; the outputs at full speed, see
    :func:`rollerdyn.simulation.full_speed`)."""
    import plotly.graph_objects as go

    figs: list = []
    all_labels, all_sets = labels, sets
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
        # the axial force needs the flanges' outputs as well (solver.outputs)
        needs = ("rollers", "flanges") if key == "fig12" else ("rollers",)
        labels, sets = having(all_labels, all_sets, *needs)
        if not sets:
            continue
        fig = go.Figure()
        for label, ds in zip(labels, sets, strict=True):
            d = full_speed(ds)
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
            **LAYOUT,
        )
        fig.update_xaxes(range=[0, 360], dtick=45)
        figs.append((key, fig))
    return figs


#: The contacts of :func:`lubrication_figures`: (key, variables' prefix, what it is).
LUBRICATION_FIGURES = (
    ("lambda_inner", "inner", "roller-inner race"),
    ("lambda_flange", "flange", "roller end / flange"),
)


def lubrication_figures(labels, sets) -> list:
    """(key, figure) of the specific film thickness Lambda over the roller azimuth at the
    inner race and at the flanges (rollers and flanges pooled; the contacts in contact, at
    the outputs at full speed, :func:`rollerdyn.simulation.full_speed`), on a log scale
    with the regimes' bounds 1 and 3 marked."""
    import plotly.graph_objects as go

    labels, sets = having(labels, sets, "rollers", "lubrication")
    figs: list = []
    for key, prefix, what in LUBRICATION_FIGURES:
        fig = go.Figure()
        for label, ds in zip(labels, sets, strict=True):
            d = full_speed(ds)
            lam = d[f"{prefix}_specific_film_thickness"].values
            psi = np.mod(d.azimuth.values, 2 * np.pi)
            if lam.ndim == 3:  # per flange: every flange at its roller's azimuth
                psi = np.repeat(psi[..., None], lam.shape[2], axis=2)
            psi, lam = np.degrees(psi.ravel()), lam.ravel()
            on = np.isfinite(lam) & (lam > 0.0)
            psi, lam = psi[on], lam[on]
            keep = _thin(psi.size, MAX_POINTS)
            fig.add_scatter(
                x=psi[keep], y=lam[keep], mode="markers", marker=dict(size=3), name=label
            )
        for bound in (1.0, 3.0):
            fig.add_hline(y=bound, line=dict(color="#999", width=1, dash="dot"))
        fig.add_vline(x=180.0, line=dict(color="#999", width=1, dash="dash"))
        fig.update_layout(
            title=f"specific film thickness Lambda = h_c / sigma at the {what} contacts "
            "(in contact; 1 and 3: boundary / mixed / full film)",
            xaxis_title="roller azimuth ψ [deg] (load zone centre at 180 deg)",
            yaxis_title="Lambda [-]",
            yaxis_type="log",
            **LAYOUT,
        )
        fig.update_xaxes(range=[0, 360], dtick=45)
        figs.append((key, fig))
    return figs


def pairing_shares(ds: xr.Dataset, ring: str) -> dict:
    """Share of time per roller end / flange pairing at ``ring`` ('inner' or 'outer'),
    over every roller and both flanges of the ring, with 'none' for no contact (the
    shares add up to 1; each output weighted by the time it stands for)."""
    idx = flange_indices(ring)
    pairing = ds.flange_pairing.isel(flange=idx).values  # (time, roller, 2)
    w = _time_weights(ds.time.values)[:, None, None] * np.ones(pairing.shape)
    total = w.sum()
    shares = {name: float(w[pairing == k].sum() / total) for k, name in enumerate(PAIRINGS)}
    shares["none"] = float(w[pairing < 0].sum() / total)
    return shares


def pairing_figures(labels, sets) -> list:
    """(key, figure) of figs. 8 and 9: share of time per pairing at each ring."""
    import plotly.graph_objects as go

    figs: list = []
    labels, sets = having(labels, sets, "flanges")
    if not sets:
        return figs
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
            **LAYOUT,
        )
        figs.append((key, fig))
    return figs


def inputs_figure(labels, sets):
    """Radial and axial load and the rings' speeds over time, one row each (the outer
    ring's dashed where it turns, a planet carrier's dotted)."""
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
        for var, name, dash in (
            ("outer_ring_speed", "outer ring", "dash"),
            ("carrier_speed", "planet carrier", "dot"),
        ):
            if var in ds and np.any(ds[var].values != 0.0):
                fig.add_scatter(
                    x=ds.time.values,
                    y=ds[var].values,
                    name=f"{label}: {name}",
                    legendgroup=label,
                    line=dict(color=colour, dash=dash),
                    row=3,
                    col=1,
                )
    fig.update_yaxes(title_text="radial load [N]", row=1, col=1)
    fig.update_yaxes(title_text="axial load [N]", row=2, col=1)
    fig.update_yaxes(title_text="ring speed [rad/s]", row=3, col=1)
    fig.update_xaxes(title_text="time t [s]", row=3, col=1)
    fig.update_layout(title="loads and speed over time (from the data)", **LAYOUT)
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
    f_max = nanmax(force)
    f_max = f_max if f_max > 0 else 1.0
    s_max = nanmax(np.abs(skew))
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


def ripple_figures(labels, sets, ripples: list[dict]) -> list:
    """(key, figure) of the amplitude spectra at full speed (:func:`rollerdyn.ripple.spectra`)
    of the frictional torque and of the inner ring's displacement across and along the
    load, up to 4.5 times the roller pass frequency, with its harmonics marked (dotted,
    the first result's), of the results whose ``ripples`` have amplitudes (none: no
    figure)."""
    import plotly.graph_objects as go

    from .ripple import shown_spectra

    _, harmonics, shown = shown_spectra(zip(labels, sets, ripples, strict=True))
    if not shown:
        return []
    panels = (
        ("ripple_torque", "frictional torque", [("frictional_torque", "", 1.0)], "N·m"),
        (
            "ripple_ring",
            "inner ring displacement",
            [("ring_z", ", z (across the load)", 1e9), ("ring_y", ", y (along it)", 1e9)],
            "nm",
        ),
    )
    figs = []
    for key, what, signals, unit in panels:
        fig = go.Figure()
        for label, _, s in shown:
            for name, suffix, factor in signals:
                fig.add_scatter(x=s["frequency"], y=factor * s[name], name=label + suffix)
        for f in harmonics:
            fig.add_vline(x=f, line_dash="dot", line_color="#888")
        fig.update_layout(
            title=f"{what} at full speed: amplitude spectrum (dotted: k times the roller "
            "pass frequency)",
            xaxis_title="frequency [Hz]",
            yaxis_title=f"amplitude [{unit}]",
            yaxis_type="log",
            **LAYOUT,
        )
        figs.append((key, fig))
    return figs
