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
from dataclasses import dataclass

import numpy as np
import xarray as xr

from .simulation import recorded

__all__ = [
    "LUBRICATION_COLUMNS",
    "LUBRICATION_CONTACTS",
    "FilmData",
    "film_data",
    "in_contact",
    "lubrication_by_contact",
    "rolling_race_films",
]

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


def in_contact(ds: xr.Dataset, prefix: str, name: str, outputs: np.ndarray) -> np.ndarray:
    """The values of the lubrication output ``{prefix}_{name}`` (e.g. "flange",
    "specific_film_thickness") at the outputs ``outputs`` (a boolean mask of the time
    axis), flattened, of the contacts in contact there: a maximum pressure above 0."""
    touching = ds[f"{prefix}_max_pressure"].values[outputs] > 0.0
    return ds[f"{prefix}_{name}"].values[outputs][touching]


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
        pressure = in_contact(ds, prefix, "max_pressure", outputs)
        if not pressure.size:
            rows.append((name, [0.0] + [math.nan] * (len(LUBRICATION_COLUMNS) - 1)))
            continue
        lam = in_contact(ds, prefix, "specific_film_thickness", outputs)
        speed = in_contact(ds, prefix, "sliding_speed", outputs)
        most = int(np.argmax(pressure))
        rows.append(
            (
                name,
                [
                    float(pressure[most]) / 1e9,
                    float(lam[most]),
                    float(lam.min()),
                    float(np.median(lam)),
                    100.0 * float(np.mean(lam < 1.0)),
                    100.0 * float(np.mean((lam >= 1.0) & (lam < 3.0))),
                    100.0 * float(np.mean(lam >= 3.0)),
                    float(speed.max()),
                ],
            )
        )
    return rows


@dataclass(frozen=True)
class FilmData:
    """What the films of a configuration's race contacts need (SI): E' of the roller on
    the inner and on the outer ring, the ambient viscosity eta0, Blok's alpha* (eq. 31),
    the viscosity's temperature slope and the oil's thermal conductivity (eq. 48), at the
    operating temperature."""

    e_prime: dict[str, float]
    eta0: float
    alpha_star: float
    viscosity_slope: float
    thermal_conductivity: float


def film_data(cfg) -> FilmData:
    """:class:`FilmData` of the configuration ``cfg``."""
    from .model import Model
    from .tribology import effective_modulus

    m = cfg.materials
    roller = (m.roller.youngs_modulus, m.roller.poisson_ratio)
    model = Model(cfg)
    return FilmData(
        e_prime={
            race: effective_modulus(*roller, ring.youngs_modulus, ring.poisson_ratio)
            for race, ring in (("inner", m.inner_ring), ("outer", m.outer_ring))
        },
        eta0=model.eta0,
        alpha_star=model.alpha_star,
        viscosity_slope=model.viscosity_slope,
        thermal_conductivity=cfg.lubricant.thermal_conductivity,
    )


def rolling_race_films(
    cfg, data: FilmData, speed: float, slice_loads: dict[str, np.ndarray]
) -> dict[str, np.ndarray]:
    """The central film h_c [m] of each roller's most loaded slice at the inner and the
    outer race (``slice_loads[race]``: the slices' loads [N], shape (rollers, slices)),
    for an inner ring turning at ``speed`` [rad/s] with the outer ring fixed and the
    rollers rolling without slip (with the outer ring turning, ``speed`` is the inner
    ring's speed relative to it: the rolling speeds depend on that alone): the surfaces
    move at the entrainment speed (omega_i - omega_c) R_i at the inner race and
    omega_c R_o at the outer, omega_c the roller set's speed
    (``geometry.epicyclic_factor``).
    The film is the dynamic model's of a race slice that does not slide: Moes (eqs.
    33-38) with the thermal correction (eq. 47), the speed regularised as there
    (``surfaces.boundary_friction.smoothing_speed``). NaN where the slice carries nothing."""
    from .tribology import line_films, thermal_correction

    g = cfg.geometry
    r = g.roller_diameter / 2.0
    r_in, r_out = g.inner_raceway_diameter / 2.0, g.outer_raceway_diameter / 2.0
    omega_c = abs(speed) * g.epicyclic_factor
    v_s = cfg.surfaces.boundary_friction.smoothing_speed
    geometry = {
        "inner": ((abs(speed) - omega_c) * r_in, 1.0 / (1.0 / r + 1.0 / r_in)),
        "outer": (omega_c * r_out, 1.0 / (1.0 / r - 1.0 / r_out)),
    }
    films = {}
    for race, (u, r_eff) in geometry.items():
        q = np.asarray(slice_loads[race], dtype=float).max(axis=1) / g.roller.slice_width
        u0 = math.hypot(u, v_s)
        loaded = q > 0.0
        moes = line_films(
            r_eff, u0, u0, np.where(loaded, q, 1.0), data.e_prime[race], data.alpha_star, data.eta0
        )["moes"]
        phi = thermal_correction(u0, 0.0, data.viscosity_slope, data.thermal_conductivity)
        films[race] = np.where(loaded, np.asarray(moes) * phi, np.nan)
    return films
