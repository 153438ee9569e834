"""The lubrication of a result's contacts (not among the paper's outputs): per contact
kind, the largest maximum pressure and how thick the film is against the roughness.

A result's group "lubrication" of ``solver.outputs`` records, for every race, roller-roller
and roller end / flange contact at every output, the contact's largest maximum pressure p0
(of its most loaded slice, or of its flange ellipse) and the central film h_c, the
specific film thickness Lambda = h_c / sigma and the sliding speed there (sigma the
contact's composite roughness, ``surfaces.*.roughness``). Lambda sorts the contacts into
the usual regimes (Hamrock, Schmid & Jacobson, Fundamentals of Fluid Film Lubrication, 2nd
ed. 2004, the chapter on film thickness and surface roughness): below 1 the asperities carry
much of the load (boundary lubrication), from 1 to 3 they share it with the film (mixed),
above 3 the film carries it (full film). The model itself shares the load by Lambda (the
paper's eq. 53, Zhou & Hoeprich), so the regimes are those that set its friction.
"""

from __future__ import annotations

import math

import numpy as np
import xarray as xr

from .simulation import recorded

__all__ = ["LUBRICATION_COLUMNS", "LUBRICATION_CONTACTS", "lubrication_by_contact"]

#: The contact kinds of :func:`lubrication_by_contact`: (name, variables' prefix).
LUBRICATION_CONTACTS = (
    ("inner race", "inner"),
    ("outer race", "outer"),
    ("roller pairs", "roller_roller"),
    ("flanges", "flange"),
)

#: The columns of :func:`lubrication_by_contact`'s rows: (text, unit).
LUBRICATION_COLUMNS = (
    ("largest maximum pressure p0", "GPa"),
    ("Lambda there", "-"),
    ("smallest Lambda", "-"),
    ("median Lambda", "-"),
    ("boundary, Lambda < 1", "%"),
    ("mixed, 1 <= Lambda < 3", "%"),
    ("full film, Lambda >= 3", "%"),
    ("largest sliding speed", "m/s"),
)


def lubrication_by_contact(
    ds: xr.Dataset, outputs: np.ndarray
) -> list[tuple[str, list[float]]] | None:
    """Per contact kind (:data:`LUBRICATION_CONTACTS`), over the outputs ``outputs`` (a
    boolean mask of the time axis) and every roller (and flange) in contact there (a
    maximum pressure above 0): the values of :data:`LUBRICATION_COLUMNS`, the regimes'
    shares counting each contact at each output once. NaN where no such contact is in
    contact (its largest pressure 0). None for a result that did not record its
    lubrication (an older file, or ``solver.outputs`` without "lubrication")."""
    if not recorded(ds, "lubrication"):
        return None
    rows = []
    for name, prefix in LUBRICATION_CONTACTS:
        pressure = ds[f"{prefix}_max_pressure"].values[outputs].ravel()
        lam = ds[f"{prefix}_specific_film_thickness"].values[outputs].ravel()
        speed = ds[f"{prefix}_sliding_speed"].values[outputs].ravel()
        touching = pressure > 0.0
        if not touching.any():
            rows.append((name, [0.0] + [math.nan] * (len(LUBRICATION_COLUMNS) - 1)))
            continue
        most = int(np.argmax(pressure))
        lam_on = lam[touching]
        rows.append(
            (
                name,
                [
                    float(pressure[most]) / 1e9,
                    float(lam[most]),
                    float(lam_on.min()),
                    float(np.median(lam_on)),
                    100.0 * float(np.mean(lam_on < 1.0)),
                    100.0 * float(np.mean((lam_on >= 1.0) & (lam_on < 3.0))),
                    100.0 * float(np.mean(lam_on >= 3.0)),
                    float(speed[touching].max()),
                ],
            )
        )
    return rows
