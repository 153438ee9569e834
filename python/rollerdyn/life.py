"""Rating life of a radial cylindrical roller bearing: ISO 281:2007 (basic and modified
rating life from the load ratings) and ISO/TS 16281:2008 (reference rating life from the
loads of the roller slices, "laminae").

Pure numpy; nothing here imports the core, so the module is cheap to import. Arguments and
results are SI (N, m, m^2/s, rad; speeds in r/min as the standards give them; lives in
millions of revolutions). Where a standard's formula is written for millimetres (the load
ratings, the reference viscosity, the fatigue load limit) the conversion is made inside and
the doc string says so.

Sources (docs/life.md tells which was taken where they differ):

- ISO 281:2007, clause 7 (radial roller bearings: 7.1 basic dynamic radial load rating with
  the factor f_c of Table 7, 7.3 basic rating life), clause 9 (9.2 a_1 for reliability,
  Table 12; 9.3 a_ISO for the systems approach) and Annex B (fatigue load limit).
- ISO 76:2006 (basic static radial load rating of radial roller bearings, the static
  equivalent load and the static safety factor s_0 = C_0 / P_0; the 4 000 MPa at the
  centre of the most heavily loaded contact that defines C_0 for roller bearings).
- ISO/TS 16281:2008, clause 5.3 (roller bearings: eqs. (47)-(49) roller contact ratings
  from C_r, (56)-(57) lamina ratings, (61)-(64) dynamic equivalent lamina loads, (65) basic
  reference rating life) and clause 7 (a_ISO with the reference equivalent load). The TS
  equation numbers are those of two independent open implementations (see docs/life.md).

Every function checks its arguments and raises :class:`ValueError` naming the argument and
the rule it breaks.
"""

from __future__ import annotations

import math
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = [
    "BM_CYLINDRICAL",
    "FC_GAMMA",
    "FC_TABLE",
    "LAMBDA_NU_RADIAL",
    "RELIABILITY_FACTORS",
    "basic_rating_life",
    "dynamic_load_rating",
    "equivalent_lamina_loads",
    "fatigue_load_limit",
    "lamina_load_ratings",
    "life_modification_factor",
    "modified_reference_rating_life",
    "rating_factor",
    "reference_equivalent_load",
    "reference_rating_life",
    "reference_viscosity",
    "reliability_factor",
    "ROLLER_STATIC_PRESSURE",
    "static_load_rating",
    "static_safety_factor",
    "stress_static_safety",
    "viscosity_ratio",
]

MM = 1e3
"""Millimetres per metre: the ISO formulas take lengths in mm."""

BM_CYLINDRICAL = 1.1
"""Rating factor b_m for contemporary cylindrical roller bearings (ISO 281:2007, Table 1,
the values of b_m)."""

FC_GAMMA = np.round(np.arange(1, 31) * 0.01, 2)
"""D_we cos(alpha) / D_pw, the rows of ISO 281:2007 Table 7 (0.01 ... 0.30)."""

FC_TABLE = np.array(
    [
        52.1, 60.8, 66.5, 70.7, 74.1, 76.9, 79.2, 81.2, 82.8, 84.2,
        85.4, 86.4, 87.1, 87.7, 88.2, 88.5, 88.7, 88.8, 88.8, 88.7,
        88.5, 88.2, 87.9, 87.5, 87.0, 86.4, 85.8, 85.2, 84.5, 83.8,
    ]
)  # fmt: skip
"""Factor f_c of ISO 281:2007 Table 7 (radial roller bearings), one value per row of
:data:`FC_GAMMA`. Values equal the closed form behind the table (ISO/TR 1281-1,
f_c = 207.9 lambda nu gamma^(2/9) (1 - gamma)^(29/27) (1 + gamma)^(-1/4)
[1 + (1.04 ((1 - gamma)/(1 + gamma))^(143/108))^(9/2)]^(-2/9) with lambda nu = 0.83) to
their last digit; tests/test_life.py checks this."""

LAMBDA_NU_RADIAL = 0.83
"""Reduction factor lambda nu of radial roller bearings (ISO/TS 16281:2008 eq. (49); the
same 0.83 is built into f_c of ISO 281:2007 Table 7)."""

RELIABILITY_FACTORS: dict[float, float] = {
    90.0: 1.0, 95.0: 0.64, 96.0: 0.55, 97.0: 0.47, 98.0: 0.37, 99.0: 0.25,
    99.2: 0.22, 99.4: 0.19, 99.6: 0.16, 99.8: 0.12, 99.9: 0.093,
    99.92: 0.087, 99.94: 0.08, 99.95: 0.077,
}  # fmt: skip
"""Life modification factor for reliability a_1 (ISO 281:2007, 9.2, Table 12), by
reliability in per cent."""

#: ISO/TS 16281:2008 eqs. (47), (48): Lundberg-Palmgren's ratios C / (Z Q_c) of the inner and
#: outer ring of a radial roller bearing, and the factor between the two rings' ratings.
_TS_INNER = 0.378
_TS_OUTER = 0.364
_TS_RING = 1.038

#: a_ISO for radial roller bearings (ISO 281:2007, 9.3): (kappa from, kappa to, d, e) in
#: a_ISO = 0.1 [1 - (1.5859 - d / kappa^e) (e_C C_u / P)^0.4]^-9.185.
_AISO_RANGES = (
    (0.1, 0.4, 1.3993, 0.054381),
    (0.4, 1.0, 1.2348, 0.19087),
    (1.0, 4.0, 1.2348, 0.071739),
)
_AISO_C = 1.5859
_AISO_POWER = 0.4
_AISO_EXPONENT = -9.185
_AISO_MAX = 50.0

Ring = Literal["inner", "outer"]


# --------------------------------------------------------------------------- checks


def _array(name: str, value: ArrayLike) -> NDArray[np.float64]:
    """``value`` as a float array; ValueError naming ``name`` if it is not numeric or not
    finite."""

    def refused() -> ValueError:
        shown = repr(value) if len(repr(value)) <= 60 else repr(value)[:57] + "..."
        return ValueError(f"{name}: must be a number or an array of numbers, got {shown}")

    if isinstance(value, str | bytes) or value is None:
        raise refused()
    try:
        raw = np.asarray(value)
    except (TypeError, ValueError, OverflowError):  # ragged nesting, an odd object
        raise refused() from None
    if raw.dtype.kind == "c":  # numpy would drop the imaginary part with a warning
        raise ValueError(f"{name}: must be real, got a complex {_shape_of(raw)}")
    if raw.dtype.kind not in "biufO":  # text
        raise refused()
    try:  # an object array: Python's integers beyond int64, Fractions, Decimals ...
        arr = raw.astype(np.float64)
    except (TypeError, ValueError, OverflowError):
        raise refused() from None
    if not np.all(np.isfinite(arr)):
        bad = tuple(int(i) for i in np.argwhere(~np.isfinite(arr))[0]) if arr.ndim else ()
        where = f" at index {bad}" if bad else ""
        raise ValueError(f"{name}: must be finite (not NaN or infinite){where}")
    return arr


def _shape_of(arr: np.ndarray) -> str:
    """The words for ``arr``'s shape: a number (0-d) or an array of its shape."""
    return "number" if arr.ndim == 0 else f"array of shape {arr.shape}"


def _broadcast(**arrays: NDArray[np.float64]) -> tuple[NDArray[np.float64], ...]:
    """The arrays broadcast together (numpy's rules); ValueError naming the arguments and
    their shapes where they do not broadcast."""
    try:
        return tuple(np.broadcast_arrays(*arrays.values()))
    except ValueError:
        shapes = ", ".join(f"{name} {a.shape}" for name, a in arrays.items())
        raise ValueError(
            f"{', '.join(arrays)}: their shapes must broadcast together (numpy's rules), "
            f"got {shapes}"
        ) from None


def _positive(name: str, value: ArrayLike) -> NDArray[np.float64]:
    arr = _array(name, value)
    if np.any(arr <= 0.0):
        raise ValueError(f"{name}: must be > 0, got {_first(arr, arr <= 0.0)}")
    return arr


def _nonnegative(name: str, value: ArrayLike) -> NDArray[np.float64]:
    arr = _array(name, value)
    if np.any(arr < 0.0):
        raise ValueError(f"{name}: must be >= 0, got {_first(arr, arr < 0.0)}")
    return arr


def _first(arr: NDArray[np.float64], bad: NDArray[np.bool_]) -> str:
    """The first offending value of ``arr`` and, for arrays, where it is."""
    if arr.ndim == 0:
        return repr(float(arr))
    index = tuple(int(i) for i in np.argwhere(bad)[0])
    return f"{float(arr[index])!r} at index {index}"


def _scalar(name: str, value: ArrayLike) -> float:
    arr = _array(name, value)
    if arr.ndim != 0:
        raise ValueError(f"{name}: must be a single number, got an array of shape {arr.shape}")
    return float(arr)


def _positive_scalar(name: str, value: ArrayLike) -> float:
    x = _scalar(name, value)
    if x <= 0.0:
        raise ValueError(f"{name}: must be > 0, got {x!r}")
    return x


def _count(name: str, value: object) -> int:
    """A whole number >= 1 (an int, or a float with an integral value)."""
    if isinstance(value, bool) or not isinstance(value, int | float | np.integer | np.floating):
        raise ValueError(f"{name}: must be a whole number >= 1, got {value!r}")
    if not math.isfinite(float(value)) or float(value) != int(value) or int(value) < 1:
        raise ValueError(f"{name}: must be a whole number >= 1, got {value!r}")
    return int(value)


def _contact_angle(value: ArrayLike) -> float:
    alpha = _scalar("contact_angle", value)
    if not 0.0 <= alpha < math.pi / 4:
        raise ValueError(
            f"contact_angle: must lie in [0, pi/4) rad (a radial roller bearing, "
            f"ISO 281:2007 clause 7), got {alpha!r}"
        )
    return alpha


def _gamma(
    roller_diameter: ArrayLike, pitch_diameter: ArrayLike, contact_angle: ArrayLike
) -> float:
    """gamma = D_we cos(alpha) / D_pw, checked against the range of ISO 281 Table 7."""
    d = _positive_scalar("roller_diameter", roller_diameter)
    dpw = _positive_scalar("pitch_diameter", pitch_diameter)
    alpha = _contact_angle(contact_angle)
    gamma = d * math.cos(alpha) / dpw
    if not FC_GAMMA[0] - 1e-12 <= gamma <= FC_GAMMA[-1] + 1e-12:
        raise ValueError(
            f"roller_diameter, pitch_diameter: D_we cos(alpha) / D_pw = {gamma:.6g} must lie in "
            f"[{FC_GAMMA[0]}, {FC_GAMMA[-1]}], the range of ISO 281:2007 Table 7"
        )
    return gamma


def _out(arr: NDArray[np.float64]) -> float | NDArray[np.float64]:
    """A float for a 0-d result, else the array."""
    return float(arr) if arr.ndim == 0 else arr


def _slice_loads(
    q_inner: ArrayLike, q_outer: ArrayLike
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The slice loads of both races: finite, >= 0, 2-D (rollers, slices), same shape."""
    qi = _nonnegative("q_inner", q_inner)
    qe = _nonnegative("q_outer", q_outer)
    for name, q in (("q_inner", qi), ("q_outer", qe)):
        if q.ndim != 2 or q.shape[0] < 1 or q.shape[1] < 1:
            raise ValueError(
                f"{name}: must be a 2-D array (rollers Z, slices n_s) with Z, n_s >= 1, "
                f"got shape {q.shape}"
            )
    if qi.shape != qe.shape:
        raise ValueError(
            f"q_outer: must have the shape of q_inner (Z, n_s) = {qi.shape}, got {qe.shape}"
        )
    return qi, qe


def _ring(rotating: str) -> Ring:
    if rotating not in ("inner", "outer"):
        raise ValueError(f'rotating: must be "inner" or "outer", got {rotating!r}')
    return rotating  # type: ignore[return-value]


# --------------------------------------------------------------------------- ISO 281 / ISO 76


def rating_factor(gamma: float) -> float:
    """Factor f_c of a radial roller bearing for gamma = D_we cos(alpha) / D_pw:
    ISO 281:2007, 7.1, Table 7, interpolated linearly between its rows as the table's note
    allows. Outside the table (gamma < 0.01 or > 0.30) a ValueError is raised."""
    g = _scalar("gamma", gamma)
    if not FC_GAMMA[0] - 1e-12 <= g <= FC_GAMMA[-1] + 1e-12:
        raise ValueError(
            f"gamma: must lie in [{FC_GAMMA[0]}, {FC_GAMMA[-1]}], the range of "
            f"ISO 281:2007 Table 7, got {g!r}"
        )
    return float(np.interp(g, FC_GAMMA, FC_TABLE))


def dynamic_load_rating(
    z: int,
    roller_diameter: float,
    effective_length: float,
    pitch_diameter: float,
    contact_angle: float = 0.0,
    rows: int = 1,
) -> float:
    """Basic dynamic radial load rating C_r [N] of a radial roller bearing,
    ISO 281:2007, 7.1:

        C_r = b_m f_c (i L_we cos(alpha))^(7/9) Z^(3/4) D_we^(29/27)

    with b_m = 1.1 (cylindrical roller bearings) and f_c from Table 7 by
    D_we cos(alpha) / D_pw, interpolated linearly (:func:`rating_factor`). The formula is
    for L_we and D_we in mm (C_r in N): the lengths given in m are converted inside.

    z: rollers per row Z; roller_diameter: D_we [m]; effective_length: L_we [m], the
    roller length that carries load (without chamfers / edge radii); pitch_diameter:
    D_pw [m]; contact_angle: alpha [rad], 0 for a cylindrical roller bearing; rows: i.
    """
    n = _count("z", z)
    i = _count("rows", rows)
    gamma = _gamma(roller_diameter, pitch_diameter, contact_angle)
    d = float(roller_diameter) * MM
    length = _positive_scalar("effective_length", effective_length) * MM
    cos_a = math.cos(float(contact_angle))
    fc = rating_factor(gamma)
    return BM_CYLINDRICAL * fc * (i * length * cos_a) ** (7 / 9) * n**0.75 * d ** (29 / 27)


def static_load_rating(
    z: int,
    roller_diameter: float,
    effective_length: float,
    pitch_diameter: float,
    contact_angle: float = 0.0,
    rows: int = 1,
) -> float:
    """Basic static radial load rating C_0r [N] of a radial roller bearing, ISO 76:2006
    (radial roller bearings):

        C_0r = 44 (1 - D_we cos(alpha) / D_pw) i Z L_we D_we cos(alpha)

    The factor 44 is in N/mm^2, so the lengths (given in m) are converted to mm inside.
    Arguments as for :func:`dynamic_load_rating`."""
    n = _count("z", z)
    i = _count("rows", rows)
    d = _positive_scalar("roller_diameter", roller_diameter)
    dpw = _positive_scalar("pitch_diameter", pitch_diameter)
    length = _positive_scalar("effective_length", effective_length)
    alpha = _contact_angle(contact_angle)
    cos_a = math.cos(alpha)
    gamma = d * cos_a / dpw
    if gamma >= 1.0:
        raise ValueError(
            f"roller_diameter, pitch_diameter: D_we cos(alpha) / D_pw must be < 1, got {gamma!r}"
        )
    return 44.0 * (1.0 - gamma) * i * n * (length * MM) * (d * MM) * cos_a


#: ISO 76:2006's contact stress at the basic static load rating of roller bearings [Pa]
#: (4 000 MPa at the centre of the most heavily loaded roller/raceway contact; a total
#: permanent deformation of about 1e-4 of the roller diameter).
ROLLER_STATIC_PRESSURE = 4.0e9


def static_safety_factor(c0: float, p0: float) -> float:
    """Static safety factor s_0 = C_0 / P_0 (ISO 76:2006). For a radial cylindrical roller
    bearing (contact angle 0) the static equivalent radial load is P_0r = F_r: the axial
    load, which its flanges carry, does not enter. c0 [N] > 0, p0 [N] >= 0 (infinite at
    0)."""
    c_0 = _positive_scalar("c0", c0)
    load = _scalar("p0", p0)
    if load < 0.0:
        raise ValueError(f"p0: must be >= 0, got {load!r}")
    return math.inf if load == 0.0 else c_0 / load


def stress_static_safety(
    pressure: float, contact: Literal["line", "point"], limit: float = ROLLER_STATIC_PRESSURE
) -> float:
    """Static safety from the largest Hertzian contact pressure p_0 of a load case: the
    factor by which its load may grow until p_0 reaches ``limit`` (ISO 76's 4 000 MPa for
    roller bearings), the contact held as it is. Hertz's p_0 grows with the square root of
    a line contact's load and the cube root of a point contact's, so the factor is
    (limit / p_0)^2 for ``"line"`` (roller/raceway) and (limit / p_0)^3 for ``"point"``
    (roller end/flange). Unlike C_0 / P_0 it sees the case's own load distribution,
    crowning and edges; it does not see the load zone widening with the load (B1: p_0
    reaches 4 GPa at 2.31 times its radial load, not 1.98). pressure [Pa] >= 0 (infinite at
    0), limit [Pa] > 0."""
    p = _scalar("pressure", pressure)
    if p < 0.0:
        raise ValueError(f"pressure: must be >= 0, got {p!r}")
    if contact not in ("line", "point"):
        raise ValueError(f"contact: must be 'line' or 'point', got {contact!r}")
    cap = _positive_scalar("limit", limit)
    return math.inf if p == 0.0 else (cap / p) ** (2 if contact == "line" else 3)


def fatigue_load_limit(c0: float, pitch_diameter: float) -> float:
    """Fatigue load limit C_u [N] of a roller bearing from its static rating, the
    approximation of ISO 281:2007 Annex B (B.3.2.2, roller bearings):

        C_u = C_0 / 8.2                        for D_pw <= 100 mm
        C_u = C_0 / 8.2 (100 / D_pw)^0.3       for D_pw >  100 mm  (D_pw in mm)

    c0: basic static load rating C_0 [N]; pitch_diameter: D_pw [m] (converted to mm
    inside)."""
    c_0 = _positive_scalar("c0", c0)
    dpw = _positive_scalar("pitch_diameter", pitch_diameter) * MM
    cu = c_0 / 8.2
    return cu if dpw <= 100.0 else cu * (100.0 / dpw) ** 0.3


def basic_rating_life(c: ArrayLike, p: ArrayLike) -> float | NDArray[np.float64]:
    """Basic rating life L_10 [10^6 revolutions] of a radial roller bearing,
    ISO 281:2007, 7.3: L_10 = (C_r / P_r)^(10/3). c: basic dynamic load rating C_r [N];
    p: dynamic equivalent radial load P_r [N]. Broadcasts like numpy."""
    cr, pr = _broadcast(c=_positive("c", c), p=_positive("p", p))
    return _out((cr / pr) ** (10 / 3))


def reference_viscosity(
    speed_rpm: ArrayLike, pitch_diameter: ArrayLike
) -> float | NDArray[np.float64]:
    """Reference kinematic viscosity nu_1 [m^2/s] (ISO 281:2007, 9.3, the equations of its
    reference viscosity diagram):

        nu_1 = 45000 n^-0.83 D_pw^-0.5    for n <  1000 r/min
        nu_1 =  4500 n^-0.5  D_pw^-0.5    for n >= 1000 r/min

    with n in r/min, D_pw in mm and nu_1 in mm^2/s; pitch_diameter is given in m and the
    result returned in m^2/s (conversions inside). Broadcasts like numpy."""
    n, dpw = _broadcast(
        speed_rpm=_positive("speed_rpm", speed_rpm),
        pitch_diameter=_positive("pitch_diameter", pitch_diameter) * MM,
    )
    nu1 = np.where(n < 1000.0, 45000.0 * n**-0.83, 4500.0 * n**-0.5) * dpw**-0.5
    return _out(np.asarray(nu1 * 1e-6))


def viscosity_ratio(
    nu: ArrayLike, speed_rpm: ArrayLike, pitch_diameter: ArrayLike
) -> float | NDArray[np.float64]:
    """Viscosity ratio kappa = nu / nu_1 (ISO 281:2007, 9.3): nu is the lubricant's
    kinematic viscosity at the operating temperature [m^2/s], nu_1 from
    :func:`reference_viscosity`. Broadcasts like numpy."""
    v, n, dpw = _broadcast(
        nu=_positive("nu", nu),
        speed_rpm=_positive("speed_rpm", speed_rpm),
        pitch_diameter=_positive("pitch_diameter", pitch_diameter),
    )
    return _out(np.asarray(v / reference_viscosity(n, dpw)))


def life_modification_factor(
    kappa: ArrayLike, ec_cu_over_p: ArrayLike
) -> float | NDArray[np.float64]:
    """Life modification factor a_ISO for radial roller bearings (ISO 281:2007, 9.3):

        a_ISO = 0.1 [1 - (1.5859 - 1.3993 / kappa^0.054381) (e_C C_u / P)^0.4]^-9.185
                                                          for 0.1 <= kappa < 0.4
        a_ISO = 0.1 [1 - (1.5859 - 1.2348 / kappa^0.19087 ) (e_C C_u / P)^0.4]^-9.185
                                                          for 0.4 <= kappa < 1
        a_ISO = 0.1 [1 - (1.5859 - 1.2348 / kappa^0.071739) (e_C C_u / P)^0.4]^-9.185
                                                          for 1 <= kappa <= 4

    kappa above 4 is taken as 4 (as the standard says); below 0.1, where the standard's
    equations stop, as 0.1 (a choice, docs/life.md). a_ISO is limited to 50, also where the
    bracket reaches 0. kappa: viscosity ratio; ec_cu_over_p: e_C C_u / P (>= 0).
    Broadcasts like numpy."""
    k = np.clip(_positive("kappa", kappa), 0.1, 4.0)
    x = _nonnegative("ec_cu_over_p", ec_cu_over_p)
    k, x = _broadcast(kappa=k, ec_cu_over_p=x)
    d = np.select([k < 0.4, k < 1.0], [_AISO_RANGES[0][2], _AISO_RANGES[1][2]], _AISO_RANGES[2][2])
    e = np.select([k < 0.4, k < 1.0], [_AISO_RANGES[0][3], _AISO_RANGES[1][3]], _AISO_RANGES[2][3])
    base = 1.0 - (_AISO_C - d / k**e) * x**_AISO_POWER
    with np.errstate(divide="ignore", over="ignore"):
        a = np.where(base > 0.0, 0.1 * np.maximum(base, 1e-300) ** _AISO_EXPONENT, _AISO_MAX)
    return _out(np.asarray(np.minimum(a, _AISO_MAX)))


def reliability_factor(reliability: float = 90.0) -> float:
    """Life modification factor for reliability a_1 (ISO 281:2007, 9.2, Table 12) for a
    reliability in per cent; only the table's values are accepted (90, 95, 96, 97, 98, 99,
    99.2, 99.4, 99.6, 99.8, 99.9, 99.92, 99.94, 99.95)."""
    r = _scalar("reliability", reliability)
    key = round(r, 2)
    if abs(key - r) > 1e-9 or key not in RELIABILITY_FACTORS:
        raise ValueError(
            f"reliability: must be one of the values of ISO 281:2007 Table 12 "
            f"({', '.join(f'{v:g}' for v in RELIABILITY_FACTORS)} per cent), got {r!r}"
        )
    return RELIABILITY_FACTORS[key]


# --------------------------------------------------------------------------- ISO/TS 16281


def lamina_load_ratings(
    dynamic_rating: float,
    z: int,
    roller_diameter: float,
    pitch_diameter: float,
    slices: int,
    contact_angle: float = 0.0,
    lambda_nu: float = LAMBDA_NU_RADIAL,
) -> tuple[float, float]:
    """Basic dynamic load ratings of a lamina at the inner and the outer raceway,
    (q_ci, q_ce) [N], of a single-row radial roller bearing (ISO/TS 16281:2008, 5.3):

        Q_ci = C_r / (lambda nu 0.378 Z cos(alpha)) [1 + (1.038 r)^(9/2)]^(2/9)    eq. (47)
        Q_ce = C_r / (lambda nu 0.364 Z cos(alpha)) [1 + (1.038 r)^(-9/2)]^(2/9)   eq. (48)
        r = ((1 - gamma) / (1 + gamma))^(143/108),  gamma = D_we cos(alpha) / D_pw
        q_ci = Q_ci (1 / n_s)^(7/9),  q_ce = Q_ce (1 / n_s)^(7/9)              eqs. (56), (57)

    with lambda nu = 0.83 (eq. (49)). The TS divides C_r by lambda nu because it models
    the edge stresses (the reduction ISO 281 lumps into lambda nu) through the slice
    loads; pass lambda_nu=1 to keep ISO 281's reduction in the ratings. Only ratios of
    lengths enter, so no unit conversion is needed.

    dynamic_rating: C_r [N] (ISO 281, :func:`dynamic_load_rating`, or the catalogue's);
    z: rollers Z; roller_diameter: D_we [m]; pitch_diameter: D_pw [m]; slices: n_s;
    contact_angle: alpha [rad]; lambda_nu: reduction factor (0 < lambda nu <= 1)."""
    cr = _positive_scalar("dynamic_rating", dynamic_rating)
    n = _count("z", z)
    ns = _count("slices", slices)
    d = _positive_scalar("roller_diameter", roller_diameter)
    dpw = _positive_scalar("pitch_diameter", pitch_diameter)
    alpha = _contact_angle(contact_angle)
    lv = _positive_scalar("lambda_nu", lambda_nu)
    if lv > 1.0:
        raise ValueError(f"lambda_nu: must lie in (0, 1], got {lv!r}")
    gamma = d * math.cos(alpha) / dpw
    if not 0.0 < gamma < 1.0:
        raise ValueError(
            f"roller_diameter, pitch_diameter: D_we cos(alpha) / D_pw must lie in (0, 1), "
            f"got {gamma!r}"
        )
    r = _TS_RING * ((1.0 - gamma) / (1.0 + gamma)) ** (143 / 108)
    common = cr / (lv * n * math.cos(alpha))
    q_ci = common / _TS_INNER * (1.0 + r**4.5) ** (2 / 9)
    q_ce = common / _TS_OUTER * (1.0 + r**-4.5) ** (2 / 9)
    lamina = ns ** (-7 / 9)
    return q_ci * lamina, q_ce * lamina


def _power_mean(q: NDArray[np.float64], p: float) -> NDArray[np.float64]:
    """(1/Z sum_j q_jk^p)^(1/p) over the rollers (axis 0), scaled by the largest load so
    that the powers cannot overflow."""
    scale = q.max(axis=0)
    safe = np.where(scale > 0.0, scale, 1.0)
    return scale * np.mean((q / safe) ** p, axis=0) ** (1.0 / p)


def equivalent_lamina_loads(
    q_inner: ArrayLike, q_outer: ArrayLike, rotating: Ring = "inner"
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Dynamic equivalent loads of the laminae, (q_ei, q_ee), each of shape (n_s,) [N]
    (ISO/TS 16281:2008, 5.3, eqs. (61)-(64)): for each slice k, over the Z rollers,

        ring rotating relative to the load:   q_e,k = (1/Z sum_j q_jk^4)^(1/4)
        ring stationary relative to the load: q_e,k = (1/Z sum_j q_jk^(9/2))^(2/9)

    q_inner, q_outer: slice loads at the inner and the outer raceway, shape (Z, n_s) [N],
    0 where there is no contact. rotating: the ring that rotates relative to the load,
    "inner" (the usual case: rotating inner ring, load and outer ring stationary) or
    "outer". The TS's stress-riser factors f_i, f_e (eqs. (58)-(60)) are taken as 1: the
    slice loads are expected to carry the edge effects (docs/life.md)."""
    qi, qe = _slice_loads(q_inner, q_outer)
    ring = _ring(rotating)
    p_inner, p_outer = (4.0, 4.5) if ring == "inner" else (4.5, 4.0)
    return _power_mean(qi, p_inner), _power_mean(qe, p_outer)


def reference_rating_life(
    q_inner: ArrayLike,
    q_outer: ArrayLike,
    dynamic_rating: float,
    roller_diameter: float,
    pitch_diameter: float,
    contact_angle: float = 0.0,
    rotating: Ring = "inner",
    lambda_nu: float = LAMBDA_NU_RADIAL,
) -> float:
    """Basic reference rating life L_10r [10^6 revolutions] of a single-row radial roller
    bearing from its slice loads (ISO/TS 16281:2008, 5.3, eq. (65)):

        L_10r = ( sum_k [ (q_ci / q_ei,k)^(-9/2) + (q_ce / q_ee,k)^(-9/2) ] )^(-8/9)

    with the lamina ratings q_ci, q_ce of :func:`lamina_load_ratings` (Z and n_s from the
    shape of the loads) and the equivalent lamina loads of :func:`equivalent_lamina_loads`.
    Infinite when no slice is loaded. For equal loads on all slices of each roller the
    result does not depend on n_s; it scales with the load as load^-4 (line contact),
    where ISO 281's L_10 scales as P^(-10/3).

    q_inner, q_outer: slice loads (Z, n_s) [N]; dynamic_rating: C_r [N]; roller_diameter:
    D_we [m]; pitch_diameter: D_pw [m]; contact_angle: alpha [rad]; rotating: "inner" or
    "outer"; lambda_nu: see :func:`lamina_load_ratings`."""
    qi, qe = _slice_loads(q_inner, q_outer)
    z, ns = qi.shape
    q_ci, q_ce = lamina_load_ratings(
        dynamic_rating, z, roller_diameter, pitch_diameter, ns, contact_angle, lambda_nu
    )
    q_ei, q_ee = equivalent_lamina_loads(qi, qe, rotating)
    total = float(np.sum((q_ei / q_ci) ** 4.5) + np.sum((q_ee / q_ce) ** 4.5))
    return math.inf if total == 0.0 else total ** (-8 / 9)


def reference_equivalent_load(l10r: float, dynamic_rating: float) -> float:
    """Dynamic equivalent reference load P_ref [N]: the load that gives the life l10r by
    ISO 281's law, P_ref = C_r / L_10r^(3/10) (ISO/TS 16281:2008, used for a_ISO in
    clause 7). l10r: L_10r [10^6 revolutions] (> 0, may be infinite: P_ref = 0);
    dynamic_rating: C_r [N]."""
    cr = _positive_scalar("dynamic_rating", dynamic_rating)
    if isinstance(l10r, str | bytes) or l10r is None or np.iscomplexobj(l10r) or np.ndim(l10r):
        raise ValueError(f"l10r: must be a number, got {l10r!r}")
    try:
        life = float(l10r)
    except (TypeError, ValueError, OverflowError):
        raise ValueError(f"l10r: must be a number, got {l10r!r}") from None
    if math.isnan(life) or life <= 0.0:
        raise ValueError(f"l10r: must be > 0 (infinite allowed), got {life!r}")
    return 0.0 if math.isinf(life) else cr / life**0.3


def modified_reference_rating_life(
    q_inner: ArrayLike,
    q_outer: ArrayLike,
    dynamic_rating: float,
    roller_diameter: float,
    pitch_diameter: float,
    *,
    kappa: float,
    contamination: float,
    fatigue_limit: float,
    reliability: float = 90.0,
    contact_angle: float = 0.0,
    rotating: Ring = "inner",
    lambda_nu: float = LAMBDA_NU_RADIAL,
) -> float:
    """Modified reference rating life L_nmr [10^6 revolutions] (ISO/TS 16281:2008,
    clause 7, with ISO 281:2007, 9.2 and 9.3):

        L_nmr = a_1 a_ISO(kappa, e_C C_u / P_ref) L_10r,   P_ref = C_r / L_10r^(3/10)

    This is the TS's way: one a_ISO for the bearing, from the reference equivalent load
    that gives L_10r (:func:`reference_equivalent_load`), not an a_ISO per lamina (that
    needs lamina fatigue limits the 2008 TS does not define; docs/life.md).

    q_inner, q_outer, dynamic_rating, roller_diameter, pitch_diameter, contact_angle,
    rotating, lambda_nu: as for :func:`reference_rating_life`; kappa: viscosity ratio
    (:func:`viscosity_ratio`); contamination: e_C in [0, 1]; fatigue_limit: C_u [N]
    (:func:`fatigue_load_limit`); reliability: per cent, a value of ISO 281 Table 12."""
    ec = _scalar("contamination", contamination)
    if not 0.0 <= ec <= 1.0:
        raise ValueError(f"contamination: must lie in [0, 1] (ISO 281 e_C), got {ec!r}")
    cu = _positive_scalar("fatigue_limit", fatigue_limit)
    k = _positive_scalar("kappa", kappa)
    a1 = reliability_factor(reliability)
    l10r = reference_rating_life(
        q_inner, q_outer, dynamic_rating, roller_diameter, pitch_diameter,
        contact_angle, rotating, lambda_nu,
    )  # fmt: skip
    if math.isinf(l10r):
        return math.inf
    p_ref = reference_equivalent_load(l10r, dynamic_rating)
    a_iso = float(life_modification_factor(k, ec * cu / p_ref))
    return a1 * a_iso * l10r
