"""The fastest and the unstable modes of the dynamic model at a run's state: the
eigenvalues of the Jacobian of the equations of motion (the matrix the integrator's Newton
iteration uses) and, for each, the states that carry it.

A mode with a positive real part λ grows as e^{λt}: the integrator must resolve it, and
the states that carry it name the body and the motion (a roller's tilt and skew rates, a
spin). Steps that shrink with no fast growing mode are held by the jumps of a force law
instead (docs/dynamics.md, "Free inner ring tilt"). ``rollerdyn modes``
prints them; ``changes`` evaluates the same state with switches of the configuration
changed (e.g. ``solver.friction = false``) to tell which force makes a mode: the way
docs/dynamics.md ("Hot oil at speed: the point law's radii") found what slows B1 with the
oil at 120 °C.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
import xarray as xr

from .config import BearingConfig, parse_config

#: A roller's 11 states (crates/rollerdyn-core/src/bearing/state.rs): centre, axis angles,
#: velocity, angular velocity (spin included), inertial components.
ROLLER_STATES = ("x", "y", "z", "theta_y", "theta_z", "vx", "vy", "vz", "wx", "wy", "wz")
#: The inner ring's states: position and velocity; with the tilt free also its axis angles
#: and transverse angular velocity.
RING_STATES = ("x", "y", "z", "vx", "vy", "vz")
RING_TILT_STATES = ("theta_y", "theta_z", "wx", "wy", "wz")


@dataclass(frozen=True)
class Mode:
    """One eigenvalue of the Jacobian and the states that carry its eigenvector."""

    #: The eigenvalue [1/s]: real part the growth rate (positive: unstable), imaginary
    #: part 2π times the frequency.
    eigenvalue: complex
    #: (body, state, share): the largest components of the eigenvector, each as a share of
    #: the largest (1 for the first); body "inner ring" or "roller i".
    states: tuple[tuple[str, str, float], ...]

    @property
    def growth_rate(self) -> float:
        """Re λ [1/s]."""
        return float(self.eigenvalue.real)

    @property
    def frequency(self) -> float:
        """|Im λ|/2π [Hz]."""
        return float(abs(self.eigenvalue.imag) / (2.0 * np.pi))

    @property
    def rollers(self) -> list[int]:
        """The rollers among the carrying states, in order of first appearance."""
        found: list[int] = []
        for body, _, _ in self.states:
            if body.startswith("roller "):
                i = int(body.split()[1])
                if i not in found:
                    found.append(i)
        return found


def state_names(rollers: int, tilt_free: bool) -> list[tuple[str, str]]:
    """(body, state) of every state of the model, in the state vector's order."""
    ring = RING_STATES + (RING_TILT_STATES if tilt_free else ())
    names = [("inner ring", s) for s in ring]
    for i in range(rollers):
        names += [(f"roller {i}", s) for s in ROLLER_STATES]
    return names


def changed_config(config: BearingConfig, changes: Mapping[str, Any] | None) -> BearingConfig:
    """``config`` with dotted-path ``changes`` (values as in a file or SI numbers), validated
    again; ConfigError (a ValueError) naming a bad one."""
    if not changes:
        return config
    from .sweep import changed

    return parse_config(changed(config.model_dump(), dict(changes)), si_numbers=True)


def names_of(core, config: BearingConfig) -> list[tuple[str, str]]:
    """:func:`state_names` of a core model built from ``config``."""
    return state_names(core.rollers, config.inner_ring.tilt == "free")


def modes_at(
    config: BearingConfig,
    t: float,
    state: np.ndarray,
    changes: Mapping[str, Any] | None = None,
    shown_states: int = 4,
) -> list[Mode]:
    """Every mode of ``config``'s model (with the dotted-path ``changes``) at time ``t`` [s]
    and ``state``, the fastest growing first (by real part, then by size). Raises
    ValueError for a state of the wrong length or a change the configuration refuses."""
    from . import _core
    from .model import Model
    from .simulation import model_parameters

    config = changed_config(config, changes)
    core = _core.Model(model_parameters(config, config.solver.detector), Model(config).traction)
    n = core.states
    y = np.asarray(state, dtype=float)
    if y.shape != (n,):
        raise ValueError(f"the state has {y.size} values; this model has {n} states")
    if not np.all(np.isfinite(y)):
        raise ValueError("the state holds values that are not finite numbers")
    jacobian = np.asarray(core.jacobian(float(t), y.tolist()), dtype=float).reshape(n, n)
    if not np.all(np.isfinite(jacobian)):
        bad = sorted({names_of(core, config)[k] for k in np.argwhere(~np.isfinite(jacobian))[:, 0]})
        raise ValueError(f"the Jacobian at this state is not finite in the rows of {bad[:4]}")
    values, vectors = np.linalg.eig(jacobian)
    names = names_of(core, config)
    order = sorted(range(n), key=lambda k: (-values[k].real, -abs(values[k])))
    modes = []
    for k in order:
        size = np.abs(vectors[:, k])
        top = np.argsort(-size)[:shown_states]
        largest = size[top[0]] if size[top[0]] > 0 else 1.0
        states = tuple((*names[j], float(size[j] / largest)) for j in top)
        modes.append(Mode(complex(values[k]), states))
    return modes


#: The forces `rollerdyn modes --by-force` switches off one at a time, then all together:
#: label -> dotted-path changes of the configuration.
FORCES_OFF: dict[str, dict[str, Any]] = {
    "friction (traction, boundary friction, rolling resistance)": {"solver.friction": False},
    "contact damping": {"surfaces.damping_ratio": 0.0},
    "race film (oil across the line-contact gaps)": {"surfaces.race_film.enabled": False},
    "squeeze film at the flanges": {"surfaces.squeeze_film.enabled": False},
    "drag of the oil-air mixture": {"cavity.oil_fraction": 0.0},
}


def growth_by_force(config: BearingConfig, t: float, state: np.ndarray) -> list[tuple[str, Mode]]:
    """The fastest growing mode at the state as the model is, with each force of
    :data:`FORCES_OFF` switched off in turn, and with all of them off: (what is off, the
    mode). A growth that stays with all of them off comes from the positions (the contacts'
    elastic laws and their geometry), not from friction, damping, films or drag."""
    cases = [("nothing (the model as configured)", {})] + list(FORCES_OFF.items())
    everything: dict[str, Any] = {}
    for changes in FORCES_OFF.values():
        everything.update(changes)
    cases.append(("all of these", everything))
    return [(label, modes_at(config, t, state, changes)[0]) for label, changes in cases]


def run_config(run: xr.Dataset, changes: Mapping[str, Any] | None = None) -> BearingConfig:
    """The configuration a run's result records: its TOML text, or, for a run
    built in Python (a sweep's), its values resolved to SI (``config_resolved``, moved
    fields at their present places); with ``changes`` (dotted paths, values written as in
    the file, as ``rollerdyn run --set`` takes them: a dimensional value needs its unit)
    applied. ValueError if it records neither, or they no longer validate."""
    import json
    import tomllib

    from .provenance import current_layout
    from .sweep import changed

    changes = dict(changes or {})
    text = run.attrs.get("config_toml")
    if isinstance(text, str) and text.strip():
        return parse_config(changed(tomllib.loads(text), changes))
    resolved = run.attrs.get("config_resolved")
    if isinstance(resolved, str) and resolved.strip():
        _refuse_bare_numbers(changes)
        data = changed(current_layout(json.loads(resolved)), changes)
        return parse_config(data, si_numbers=True)
    raise ValueError("the result records no configuration; give it with --config")


def _refuse_bare_numbers(changes: Mapping[str, Any]) -> None:
    """A bare number for a dimensional field is ambiguous, as in a file (the SI values of a
    sweep's record would take it as SI without a word)."""
    from .sweep import _si_unit

    for path, value in changes.items():
        unit = _si_unit(path)
        number = isinstance(value, int | float) and not isinstance(value, bool)
        if number and unit not in (None, "1", ""):
            raise ValueError(
                f"{path} = {value!r}: a bare number is ambiguous (no unit); write it with its "
                f'unit, e.g. "{value} {unit}"'
            )


def modes_of_run(
    config: BearingConfig, run: xr.Dataset, changes: Mapping[str, Any] | None = None
) -> list[Mode]:
    """:func:`modes_at` at the final state of a run's result ``run``."""
    if "final_state" not in run or "final_time_s" not in run.attrs:
        raise ValueError("the result holds no final state")
    return modes_at(config, float(run.attrs["final_time_s"]), run["final_state"].values, changes)
