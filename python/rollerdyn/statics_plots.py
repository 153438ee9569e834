"""Figures of a quasi-static result (:mod:`rollerdyn.statics`): the load distribution of
one case, or the heaviest roller, the ring's displacement, the rating lives and the
friction of steady rolling over a sweep."""

from __future__ import annotations

import textwrap
from pathlib import Path

import numpy as np
import xarray as xr

from .config.base import T0_CELSIUS


def draw(ds: xr.Dataset, path: Path) -> None:
    """Draws ``ds`` (one case or a sweep) to the PNG file ``path``."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    if "case" not in ds.dims:
        fig, (a, b, c) = plt.subplots(1, 3, figsize=(15, 4))
        # from the radial load's direction (180 deg), within -180 ... 180 deg
        azimuth = ds.roller_azimuth.values % 360.0 - 180.0
        order = np.argsort(azimuth)
        a.plot(azimuth[order], ds.inner_race_load.values[order], "o-", label="inner race")
        a.plot(azimuth[order], ds.outer_race_load.values[order], "s--", label="outer race")
        a.set(xlabel="roller azimuth from the radial load [deg]", ylabel="roller load [N]")
        a.legend()
        heaviest = int(np.argmax(ds.inner_race_load.values))
        along = ds.slice_position.values * 1e3  # mm
        for race, style in (("inner", "o-"), ("outer", "s--")):
            pressure = ds[f"{race}_slice_pressure"].values[heaviest] / 1e9
            b.plot(along, pressure, style, label=f"{race} race")
        b.set(
            xlabel="along the roller from its middle [mm]",
            ylabel="p0 [GPa]",
            title=f"heaviest roller ({heaviest}): contact pressure by slice",
        )
        b.legend()
        note = str(ds["friction_note"].values) if "friction_note" in ds else ""
        _draw_slip(c, azimuth[order], ds.roller_slip.values[order], note)
    else:
        fig = _draw_sweep(plt, ds)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def _draw_slip(ax, azimuth: np.ndarray, slip: np.ndarray, note: str = "") -> None:
    """The rollers' slip in steady rolling [%] over their azimuth from the radial load,
    on a symmetric log scale (the loaded rollers' fractions of a per cent beside the
    unloaded ones' tens); where there is none, why (``note``, or no relative speed)."""
    if not np.isfinite(slip).any():
        why = note.split(":")[0] if note else "no relative speed between the rings"
        text = "\n".join(textwrap.wrap(f"n/a: {why}", 40))
        ax.text(0.5, 0.5, text, ha="center", va="center", transform=ax.transAxes)
        ax.set(title="steady rolling: where the rollers slip", xticks=[], yticks=[])
        return
    ax.plot(azimuth, slip * 100.0, "o-")
    ax.axhline(0.0, color="0.6", lw=0.8)
    ax.set_yscale("symlog", linthresh=0.1)
    ax.set(
        xlabel="roller azimuth from the radial load [deg]",
        ylabel="slip, 1 - spin / rolling spin [%]",
        title="steady rolling: where the rollers slip",
    )


def _sweep_axes(ds: xr.Dataset) -> tuple[str | None, list[str]]:
    """The swept coordinate along the x axis (the first numeric one with more than one value;
    None: none is) and the others, one line for each combination of their values."""
    swept = [s for s in ds.attrs["swept"].split(",") if s]
    varying = [s for s in swept if np.unique(ds[s].values.astype(str)).size > 1]
    numeric = [s for s in varying if ds[s].dtype.kind in "fiu"]
    x = numeric[0] if numeric else None
    return x, [s for s in varying if s != x]


#: SI unit of a swept value -> the unit its axis is drawn in and the factor to it: angles
#: in degrees, as misalignments are given, speeds in rpm (temperatures and lengths in
#: :func:`shown_axis`).
_SHOWN = {"rad": ("deg", 180.0 / np.pi), "rad/s": ("rpm", 30.0 / np.pi)}


def shown_axis(values: np.ndarray, unit: str) -> tuple[np.ndarray, str]:
    """``values`` in SI ``unit`` converted to the unit an engineer reads them in (see
    :data:`_SHOWN`; metres below 1 mm in um, below 1 m in mm), with that unit."""
    values = np.asarray(values, dtype=float)
    if unit == "K":
        return values - T0_CELSIUS, "degC"
    if unit == "m":
        largest = float(np.nanmax(np.abs(values))) if values.size else 0.0
        return (values * 1e6, "um") if largest < 1e-3 else (values * 1e3, "mm")
    if unit in _SHOWN:
        shown, factor = _SHOWN[unit]
        return values * factor, shown
    return values, unit


def _label(ds: xr.Dataset, name: str, value) -> str:
    unit = ds[name].attrs.get("units", "")
    shown = f"{value:.4g}" if isinstance(value, float | np.floating) else str(value)
    return f"{name} = {shown} {unit}".strip()


def _draw_sweep(plt, ds: xr.Dataset):
    """The heaviest roller, the ring's displacement, the lives and the friction of steady
    rolling over the first numeric swept value, one line for each combination of the other
    swept values."""
    x_name, others = _sweep_axes(ds)
    cases = np.arange(ds.sizes["case"])
    unit = ds[x_name].attrs.get("units", "") if x_name else ""
    x, unit = shown_axis(ds[x_name].values, unit) if x_name else (cases, "")
    keys = [tuple(ds[o].values[i] for o in others) for i in cases]
    groups = list(dict.fromkeys(keys))
    fig, (a, b, c, d) = plt.subplots(1, 4, figsize=(18, 4.5))
    lives = (("l10", "L_10 (ISO 281)"), ("l10r", "L_10r (ISO/TS 16281)"), ("lnmr", "L_nmr"))
    for key in groups:
        rows = np.array([i for i in cases if keys[i] == key])
        name = ", ".join(_label(ds, o, v) for o, v in zip(others, key, strict=True))
        a.plot(x[rows], ds.max_roller_load.values[rows], "o-", ms=3, label=name or None)
        b.plot(x[rows], ds.ring_displacement.sel(ring_dof="y").values[rows] * 1e6, "o-", ms=3)
        d.plot(x[rows], ds.friction_torque.values[rows], "o-", ms=3)
        for var, label in lives if len(groups) == 1 else lives[1:2]:
            c.plot(x[rows], ds[var].values[rows], "o-", ms=3, label=label if not others else name)
    x_label = (f"{x_name} [{unit}]" if unit else x_name) if x_name else "case"
    a.set(xlabel=x_label, ylabel="heaviest roller [N]")
    b.set(xlabel=x_label, ylabel="ring displacement y [um]")
    life = "life [1e6 rev]" if len(groups) == 1 else "L_10r (ISO/TS 16281) [1e6 rev]"
    c.set(xlabel=x_label, ylabel=life, yscale="log")
    d.set(xlabel=x_label, ylabel="friction of steady rolling [N*m]")
    for ax in (a, b, d):  # plain numbers: no offset above a panel of nearly equal values
        ax.ticklabel_format(axis="y", useOffset=False)
    if others:
        a.legend(fontsize=7)
    c.legend(fontsize=7)
    return fig
