"""The paper's figures (sect. 5.2) from result files, with matplotlib (PNG and SVG)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr

from .names import PAIRINGS, flange_indices
from .simulation import carried_axial_force, full_speed, recorded


def _label(ds: xr.Dataset, name: str) -> str:
    """The legend entry of a run: its name (:func:`report.run_names`), the axial load of its
    load case and its tilt, and where a study stopped it (its attribute ``study_stopped``),
    how far it got."""
    from .paths import printable
    from .report import configured_axial_load

    # printable: a file name's bytes that are not UTF-8 (\xe9) cannot be drawn as text
    label = f"{printable(name)} (F_a = {configured_axial_load(ds):.0f} N"
    tilt = np.degrees(float(np.abs(ds.ring_tilt.isel(time=-1)).max()))
    if tilt > 0:
        label += f", IR tilt {tilt:.3g} deg"
    label += ")"
    if "study_stopped" in ds.attrs:
        label += f" [not finished, to t = {float(ds.attrs['final_time_s']):.3g} s]"
    return label


def save_figure(fig, out: Path, name: str) -> list[Path]:
    """Writes ``fig`` as ``out/name.png`` and ``out/name.svg`` and closes it; returns the
    files. Each is drawn in memory and written through a temporary file renamed over the
    earlier figure (:func:`rollerdyn.paths.write_atomically`): a failed write (a full disk)
    leaves the earlier figure as it was, never a partial one."""
    import io

    import matplotlib.pyplot as plt

    from .paths import write_atomically

    written = []
    try:
        for ext in ("png", "svg"):
            drawn = io.BytesIO()
            fig.savefig(drawn, format=ext, dpi=120, bbox_inches="tight")
            written.append(write_atomically(Path(out) / f"{name}.{ext}", drawn.getbuffer(), True))
    finally:
        plt.close(fig)
    return written


def roller_power_loss(ds: xr.Dataset) -> xr.DataArray:
    """The power taken at each roller [W] (time, roller): its two race contacts, its four
    end-flange contacts, its contact with the next roller and its drag."""
    return (
        ds.inner_power_loss
        + ds.outer_power_loss
        + ds.flange_power_loss.sum("flange")
        + ds.roller_roller_power_loss
        + ds.drag_power_loss
    )


def plot_results(paths: list[Path], out: Path) -> list[Path]:
    """Writes every figure for the given results into ``out``; returns the files. Every
    file is read first: :class:`rollerdyn.report.ReportError` (naming the file and what
    is wrong) for one that is missing or not a rollerdyn result, before any figure."""
    import matplotlib

    from .report import REQUIRED, open_result, refuse_repeats, run_names

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    paths = [Path(p) for p in paths]
    refuse_repeats(paths)
    sets = [
        (n, open_result(p, required=(*REQUIRED, "ring_tilt"), recorded_only=True))
        for n, p in zip(run_names(paths), paths, strict=True)
    ]
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    written: list[Path] = []

    def save(fig, name: str) -> None:
        written.extend(save_figure(fig, out, name))

    fig, ax = plt.subplots(figsize=(7, 4))
    for p, ds in sets:
        ax.plot(ds.time, ds.frictional_torque, label=_label(ds, p))
    ax.set(xlabel="time t [s]", ylabel="bearing frictional torque [N m]", title="fig. 10")
    ax.legend()
    save(fig, "fig10_frictional_torque")

    # the figures of the rollers and flanges, from the results that recorded them
    # (solver.outputs)
    flanged = [(p, ds) for p, ds in sets if recorded(ds, "flanges")]
    rolled = [(p, ds) for p, ds in sets if recorded(ds, "rollers")]
    if flanged:
        fig, ax = plt.subplots(figsize=(7, 4))
        for p, ds in flanged:
            f = ds.flange_friction_force.isel(roller=0).sum("flange")
            ax.plot(ds.time, f, label=_label(ds, p))
        ax.set(xlabel="time t [s]", ylabel="flange friction force, roller 0 [N]", title="fig. 11")
        ax.legend()
        save(fig, "fig11_flange_friction")

    for name, var, ylabel, title in (
        (
            "fig12_axial_force_over_azimuth",
            "axial",
            "axial force carried by the roller [N]",
            "fig. 12",
        ),
        (
            "fig13_srr_inner_over_azimuth",
            "srr_inner",
            "slide-to-roll ratio, inner race [-]",
            "fig. 13",
        ),
        (
            "roller_load_over_azimuth",
            "inner_normal_force",
            "roller-inner race load [N]",
            "roller loads",
        ),
        (
            "roller_power_loss_over_azimuth",
            "power",
            "power taken at the roller [W]",
            "where the power goes: the roller's race, end and next-pair contacts and drag\n"
            "(instantaneous, with what the contacts store and give back; its mean is the loss)",
        ),
    ):
        # the axial force needs the flanges too; results written before power losses
        # were recorded, or without the power outputs, have no power figure
        over_azimuth(
            [
                (p, ds)
                for p, ds in rolled
                if (var != "axial" or recorded(ds, "flanges"))
                and (var != "power" or "inner_power_loss" in ds)
            ],
            lambda d, var=var: [("", ".", _per_roller(d, var))],
            ylabel,
            title,
            lambda fig, name=name: save(fig, name),
        )

    # where the rollers slip, in watts: the sliding's part of the race contacts' power
    over_azimuth(
        [(p, ds) for p, ds in rolled if "inner_sliding_power_loss" in ds],
        lambda d: [
            (f", {race} race", marker, d[f"{race}_sliding_power_loss"])
            for race, marker in (("inner", "."), ("outer", "x"))
        ],
        "power taken by sliding [W]",
        "where the rollers slip: the sliding's part of the race contacts' power",
        lambda fig: save(fig, "race_sliding_power_over_azimuth"),
    )

    # the lubrication regime: Lambda at the inner race and at each roller's most loaded
    # flange contact (rollerdyn.lubrication)
    over_azimuth(
        [(p, ds) for p, ds in rolled if recorded(ds, "lubrication")],
        lambda d: [
            (", inner race", ".", d.inner_specific_film_thickness),
            (", flanges", "x", most_loaded_flange(d, "flange_specific_film_thickness")),
        ],
        "specific film thickness Lambda = h_c / sigma [-]",
        "lubrication: Lambda < 1 boundary, 1-3 mixed, > 3 full film\n"
        "(inner race; each roller's most loaded flange contact)",
        lambda fig: save(fig, "lubrication_over_azimuth"),
        yscale="log",
    )

    ripple_spectra(sets, lambda fig: save(fig, "ripple_spectra"))

    for ring, title in (("inner", "fig. 8"), ("outer", "fig. 9")) if flanged else ():
        fig, ax = plt.subplots(figsize=(7, 4))
        width = 0.8 / max(1, len(flanged))
        for j, (p, ds) in enumerate(flanged):
            idx = flange_indices(ring)
            pairing = ds.flange_pairing.isel(flange=idx).values.ravel()
            counts = [(pairing == k).sum() for k in range(len(PAIRINGS))]
            total = max(1, (pairing >= 0).sum())
            x = np.arange(len(PAIRINGS)) + j * width
            ax.bar(x, np.array(counts) / total, width, label=_label(ds, p))
        ax.set_xticks(np.arange(len(PAIRINGS)) + 0.4 - width / 2, PAIRINGS)
        ax.set(ylabel="share of contact outputs [-]", title=f"{title}: pairings at the {ring} ring")
        ax.legend()
        save(fig, f"fig{8 if ring == 'inner' else 9}_pairings_{ring}")
    return written


def ripple_spectra(sets: list, save) -> None:
    """The amplitude spectra at full speed of the frictional torque and of the inner
    ring's displacement across the load (z), up to 4.5 times the roller pass frequency Z
    f_c, its harmonics dotted (:mod:`rollerdyn.ripple`); nothing where no result runs
    :data:`rollerdyn.ripple.MIN_PERIODS` roller passes at full speed."""
    import matplotlib.pyplot as plt

    from .ripple import ripple, shown_spectra

    passing, harmonics, shown = shown_spectra((p, ds, ripple(ds)) for p, ds in sets)
    if not shown:
        return
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(7, 6), sharex=True)
    for p, ds, s in shown:
        top.semilogy(s["frequency"], s["frictional_torque"], label=_label(ds, p))
        bottom.semilogy(s["frequency"], 1e9 * s["ring_z"], label=_label(ds, p))
    for ax in (top, bottom):
        for f in harmonics:
            ax.axvline(f, color="0.6", linestyle=":", linewidth=1)
    top.set(
        ylabel="torque amplitude [N m]",
        title=f"ripple at full speed (dotted: k x the roller pass frequency {passing:.4g} Hz)",
    )
    bottom.set(xlabel="frequency [Hz]", ylabel="inner ring amplitude along z [nm]")
    top.legend()
    save(fig)


def _per_roller(d: xr.Dataset, var: str) -> xr.DataArray:
    """Per roller and output: the axial force it carries ("axial"), the power taken at it
    ("power") or the variable ``var``."""
    if var == "axial":
        return carried_axial_force(d)
    if var == "power":
        return roller_power_loss(d)
    return d[var]


def most_loaded_flange(d: xr.Dataset, var: str) -> xr.DataArray:
    """Per roller and output, the per-flange variable ``var`` at the roller's flange
    contact of the largest maximum pressure (NaN where none of its ends touches)."""
    pressure = d.flange_max_pressure.values
    most = np.argmax(pressure, axis=2)[..., None]
    values = np.take_along_axis(d[var].values, most, axis=2)[..., 0]
    touching = np.take_along_axis(pressure, most, axis=2)[..., 0] > 0.0
    return xr.DataArray(np.where(touching, values, np.nan), dims=("time", "roller"))


def over_azimuth(
    pairs: list, series, ylabel: str, title: str, save, yscale: str = "linear"
) -> None:
    """A figure over the roller azimuth at full speed, rollers pooled: for each (name,
    result) of ``pairs`` the curves ``series(d)`` gives, (label suffix, marker, values of
    d, the outputs at full speed), on a ``yscale`` axis; ``save(fig)`` keeps it. Nothing
    without ``pairs``, or on a log scale without a positive value (a film where nothing
    touches yet)."""
    import matplotlib.pyplot as plt

    curves = []
    for p, ds in pairs:
        d = full_speed(ds)
        psi = np.degrees(d.azimuth.values.ravel())
        for suffix, marker, v in series(d):
            curves.append((psi, v.values.ravel(), marker, _label(ds, p) + suffix))
    if yscale == "log":  # a point to draw: a positive value at a finite azimuth
        curves = [
            (x, y, m, lab)
            for x, y, m, lab in curves
            if ((y > 0.0) & np.isfinite(y) & np.isfinite(x)).any()
        ]
    if not curves:
        return
    fig, ax = plt.subplots(figsize=(7, 4))
    for psi, values, marker, label in curves:
        ax.plot(psi, values, marker, ms=2, label=label)
    ax.axvline(180.0, color="0.6", lw=0.8, ls="--")
    ax.set(
        xlabel="roller azimuth psi [deg] (load zone centre at 180 deg)",
        ylabel=ylabel,
        title=title,
        yscale=yscale,
    )
    ax.legend(markerscale=5)
    save(fig)


def plot_runtime_study(frame, out: Path, title: str = "runtime over Δt_max") -> list[Path]:
    """The paper's fig. 14: wall time of whole runs over the maximum step size Δt_max, one
    line per detector (``frame``: columns dt_max_s, detector, wall_s); PNG and SVG."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 4))
    for detector, rows in frame.groupby("detector"):
        rows = rows.sort_values("dt_max_s")
        ax.plot(rows.dt_max_s, rows.wall_s, marker="o", label=detector)
    ax.set(
        xscale="log",
        xlabel="maximum step size Δt_max [s]",
        ylabel="wall time of the run [s]",
        title=f"fig. 14: {title}",
    )
    ax.legend()
    return save_figure(fig, out, "fig14_runtime_over_dt_max")
