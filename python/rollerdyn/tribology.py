"""The force laws of the reference paper (sect. 3.1.2 - 3.3) on numpy arrays.

Thin wrappers over ``rollerdyn._core``: every array argument is broadcast with numpy, the
core evaluates elementwise, and the result has the broadcast shape; the arguments after
the arrays (a law's constants) are single numbers. All quantities are SI numbers (m, N, Pa,
Pa*s, K, m/s, rad; text such as ``"1 GPa"`` is not read). A bad argument raises ValueError
naming it, its value and the rule. Equation numbers refer to the reference paper.
"""

from __future__ import annotations

import functools
import inspect
from collections.abc import Callable
from typing import Any

import numpy as np

from . import _core

__all__ = [
    "EhlTraction",
    "boundary_friction_coefficient",
    "boundary_share",
    "carreau_shear_stress",
    "chittenden_film",
    "dicke_viscosity",
    "ehl_rolling_force",
    "effective_modulus",
    "elliptic_integrals",
    "ellipticity",
    "hertz_line",
    "hertz_point",
    "hertz_point_force",
    "hysteresis_moment",
    "line_films",
    "line_power_law_force",
    "roelands_viscosity",
    "thermal_correction",
    "tripp_deflection",
    "vogel_viscosity",
]

EhlTraction = _core.EhlTraction


#: Argument name -> (rule, test on a float array). Names not listed must be finite.
_POSITIVE = (
    "must be positive and finite",
    lambda x: np.isfinite(x) & (x > 0.0),
)
_NONNEGATIVE = (
    "must be finite and >= 0",
    lambda x: np.isfinite(x) & (x >= 0.0),
)
_FINITE = ("must be finite (not NaN or infinite)", np.isfinite)
_RULES: dict[str, tuple[str, Callable[[np.ndarray], np.ndarray]]] = {
    **dict.fromkeys(
        (
            "r1", "r2", "rx", "ry", "r_eff", "length", "e_prime", "e1", "e2", "eta0",
            "viscosity", "radius_ratio", "roller_radius", "counter_radius",
            "temperature", "k", "eta_p", "tau0", "n", "half_width", "thermal_conductivity",
            "smoothing_speed", "s0", "k1", "k2", "b", "c",
        ),
        _POSITIVE,
    ),
    **dict.fromkeys(
        (
            "force", "load_per_length", "normal_force", "wall_thickness", "film_ratio",
            "alpha_star", "alpha", "alpha_v", "mu_b0", "z",
        ),
        _NONNEGATIVE,
    ),
    "m1": ("must lie in [0, 1]", lambda x: np.isfinite(x) & (x >= 0.0) & (x <= 1.0)),
    "p_p": ("must be negative and finite (eq. 19's pole)", lambda x: np.isfinite(x) & (x < 0.0)),
    "nu1": ("must lie in (-1, 0.5)", lambda x: (x > -1.0) & (x < 0.5)),
    "nu2": ("must lie in (-1, 0.5)", lambda x: (x > -1.0) & (x < 0.5)),
}  # fmt: skip


#: The arguments that name a variant of a law (strings), with what they may be.
_CHOICES = {
    "method_name": '"brewe_hamrock" or "exact"',
    "counterface": '"convex" or "outer_ring"',
}


def _shown(value: Any) -> str:
    """``value``'s repr, shortened to 60 characters."""
    text = repr(value)
    return text if len(text) <= 60 else text[:57] + "..."


def _check(name: str, value: Any, scalar: bool = False) -> np.ndarray | None:
    """``value`` as a float array (None for a variant's name, a string of
    :data:`_CHOICES`); ValueError naming ``name`` if it is not what the argument takes: a
    real number in SI units (an array of them unless ``scalar``, an argument that does not
    broadcast) that keeps its rule (:data:`_RULES`; finite for the others)."""
    if name in _CHOICES:
        if not isinstance(value, str):
            raise ValueError(f"{name} = {_shown(value)}: must be {_CHOICES[name]} (a string)")
        return None
    x = _numbers(name, value, scalar)
    rule, ok = _RULES.get(name, _FINITE)
    _refuse_where(name, x, ~ok(x), rule)
    return x


def _numbers(name: str, value: Any, scalar: bool = False) -> np.ndarray:
    """``value`` as a float array, or ValueError naming ``name``: None, text (a quantity
    with a unit, ``"1 GPa"``: these laws take SI numbers), booleans, complex numbers and
    (for a ``scalar`` argument) arrays are refused."""
    what = "a real number in SI units" + ("" if scalar else " or an array of them")
    if value is None or isinstance(value, str | bytes):
        unit = " (text is not read: these laws take SI numbers)" if isinstance(value, str) else ""
        raise ValueError(f"{name} = {_shown(value)}: must be {what}{unit}")

    def refused() -> ValueError:
        return ValueError(f"{name} = {_shown(value)}: must be {what}")

    try:
        raw = np.asarray(value)
    except (TypeError, ValueError, OverflowError):  # ragged nesting, an odd object
        raise refused() from None
    if raw.dtype.kind == "c":
        raise ValueError(f"{name} = {_shown(value)}: must be {what}, not complex")
    if raw.dtype.kind not in "iufO":  # booleans, text
        raise refused()
    try:  # an object array: Python's integers beyond int64, Fractions, Decimals ...
        x = raw.astype(float)
    except (TypeError, ValueError, OverflowError):
        raise refused() from None
    if scalar and x.ndim != 0:
        raise ValueError(
            f"{name} = {_shown(value)}: must be a single number (this argument does not "
            f"broadcast), got an array of shape {x.shape}"
        )
    return x


def _refuse_where(name: str, x: np.ndarray, bad: np.ndarray, rule: str) -> None:
    """Raises ValueError naming ``name``, the first value of ``x`` where ``bad`` holds (the
    two broadcast together) and ``rule``; nothing if ``bad`` holds nowhere."""
    if np.any(bad):
        first = np.broadcast_to(x, np.shape(bad))[bad].flat[0] if np.ndim(bad) else x
        raise ValueError(f"{name} = {float(first)!r}: {rule}")


#: A rule across arguments (or on the result): the argument it names, the rule, and where
#: it is broken, from the arguments as float arrays (and the result).
_Across = tuple[str, str, Callable[..., np.ndarray]]


def _vectorize(
    core: Callable[..., Any], before: tuple[_Across, ...] = (), after: tuple[_Across, ...] = ()
) -> Callable[..., Any]:
    """Wrap an elementwise core function, whose first arguments (as many as the core's
    ``ARRAY_ARGUMENTS`` says) are equal-length 1-D arrays: the arguments are checked
    (:data:`_RULES`, by name, then the rules ``before`` across them), broadcast, and the
    result takes the broadcast shape (and is checked by the rules ``after``). The wrapper
    has the core function's signature and docstring."""
    n_arrays = _core.ARRAY_ARGUMENTS[core.__name__]
    signature = inspect.signature(core)
    names = list(signature.parameters)

    @functools.wraps(core)
    def wrapper(*args: Any, **kwargs: Any) -> Any:
        try:
            bound = signature.bind(*args, **kwargs)
        except TypeError as err:
            raise TypeError(f"{core.__name__}{signature}: {err}") from None
        numeric: dict[str, np.ndarray] = {}
        for i, name in enumerate(names):
            if name not in bound.arguments:
                continue
            x = _check(name, bound.arguments[name], scalar=i >= n_arrays)
            if x is not None:
                numeric[name] = x
        for name, rule, broken in before:
            with np.errstate(invalid="ignore"):
                _refuse_where(name, numeric[name], broken(**numeric), rule)
        broadcast = [n for n in names[:n_arrays] if n in numeric]
        try:
            arrays = np.broadcast_arrays(*(numeric[n] for n in broadcast))
        except ValueError:
            shapes = ", ".join(f"{n} {numeric[n].shape}" for n in broadcast)
            raise ValueError(
                f"{core.__name__}: the array arguments' shapes do not broadcast together ({shapes})"
            ) from None
        shape = arrays[0].shape
        flat = [np.ascontiguousarray(a.ravel()) for a in arrays]
        rest = [
            bound.arguments[n] if n in _CHOICES else float(numeric[n])
            for n in names[n_arrays:]
            if n in bound.arguments
        ]
        result = core(*flat, *rest)

        def reshape(x: Any) -> Any:
            if isinstance(x, np.ndarray):
                return x.reshape(shape) if shape else float(x[0])
            if isinstance(x, tuple):
                return tuple(reshape(v) for v in x)
            if isinstance(x, dict):
                return {k: reshape(v) for k, v in x.items()}
            return x

        out = reshape(result)
        for name, rule, broken in after:
            _refuse_where(name, numeric[name], broken(out, **numeric), rule)
        return out

    wrapper.__signature__ = signature
    return wrapper


def effective_modulus(e1: float, nu1: float, e2: float, nu2: float) -> float:
    """E' = 2/((1 - nu1^2)/E1 + (1 - nu2^2)/E2) (paper, nomenclature), Pa."""
    for name, value in (("e1", e1), ("nu1", nu1), ("e2", e2), ("nu2", nu2)):
        _check(name, value, scalar=True)
    return _core.effective_modulus(float(e1), float(nu1), float(e2), float(nu2))


elliptic_integrals = _vectorize(_core.elliptic_integrals)
ellipticity = _vectorize(_core.ellipticity)
hertz_point = _vectorize(_core.hertz_point)
hertz_point_force = _vectorize(_core.hertz_point_force)
hertz_line = _vectorize(_core.hertz_line)
tripp_deflection = _vectorize(
    _core.tripp_deflection,
    after=(
        (
            "load_per_length",
            "beyond the range of Tripp's solution (eqs. 9, 10; its logarithms turn the "
            "deflection negative where the contact's half-width nears the radii)",
            lambda deflection, load_per_length, **_: (
                (np.asarray(deflection) <= 0.0) & (load_per_length > 0.0)
            ),
        ),
    ),
)
line_power_law_force = _vectorize(_core.line_power_law_force)


vogel_viscosity = _vectorize(
    _core.vogel_viscosity,
    before=(
        (
            "temperature",
            "must lie above Vogel's pole, 273.15 K - c (eq. 20)",
            lambda temperature, c, **_: temperature - 273.15 + c <= 0.0,
        ),
    ),
)
roelands_viscosity = _vectorize(
    _core.roelands_viscosity,
    before=(
        (
            "pressure",
            "must lie above p_p, the pole of eq. 19",
            lambda pressure, p_p, **_: pressure <= p_p,
        ),
    ),
)
dicke_viscosity = _vectorize(_core.dicke_viscosity)
carreau_shear_stress = _vectorize(_core.carreau_shear_stress)
line_films = _vectorize(_core.line_films)
chittenden_film = _vectorize(_core.chittenden_film)
thermal_correction = _vectorize(_core.thermal_correction)
boundary_friction_coefficient = _vectorize(_core.boundary_friction_coefficient)
boundary_share = _vectorize(_core.boundary_share)
hysteresis_moment = _vectorize(_core.hysteresis_moment)
ehl_rolling_force = _vectorize(_core.ehl_rolling_force)
