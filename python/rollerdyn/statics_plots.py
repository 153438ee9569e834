"""Figures of a quasi-static result (:mod:`rollerdyn.statics`): the load distribution of
one case, or the heaviest roller, the ring's displacement and the rating lives over a
sweep."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr


def draw(ds: xr.Dataset, path: Path) -> None:
    """Draws ``ds`` (one case or a sweep) to the PNG file ``path``."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    if "case" not in ds.dims:
        fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4))
        azimuth = ds.roller_azimuth.values
        order = np.argsort(azimuth)
        a.plot(azimuth[order], ds.inner_race_load.values[order], "o-", label="inner race")
        a.plot(azimuth[order], ds.outer_race_load.values[order], "s--", label="outer race")
        a.set(xlabel="roller azimuth [deg] (load along 180 deg)", ylabel="roller load [N]")
        a.legend()
        heaviest = int(np.argmax(ds.inner_race_load.values))
        b.plot(ds.slice.values, ds.inner_slice_pressure.values[heaviest] / 1e9, "o-")
        b.set(xlabel="slice", ylabel="p0 [GPa]", title=f"heaviest roller ({heaviest}), inner race")
    else:
        x_name = ds.attrs["swept"].split(",")[0]
        x = ds[x_name].values
        unit = ds[x_name].attrs.get("units", "")
        x_name = f"{x_name} [{unit}]" if unit else x_name
        fig, (a, b, c) = plt.subplots(1, 3, figsize=(14, 4))
        a.plot(x, ds.max_roller_load.values)
        a.set(xlabel=x_name, ylabel="heaviest roller [N]")
        b.plot(x, ds.ring_displacement.sel(ring_dof="y").values * 1e6)
        b.set(xlabel=x_name, ylabel="ring displacement y [um]")
        for name, label in (
            ("l10", "L_10 (ISO 281)"),
            ("l10r", "L_10r (ISO/TS 16281)"),
            ("lnmr", "L_nmr"),
        ):
            c.plot(x, ds[name].values, label=label)
        c.set(xlabel=x_name, ylabel="life [1e6 rev]", yscale="log")
        c.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
