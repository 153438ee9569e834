"""The ``[solver]`` section: time integration and every numerical setting of the model
(the core's ``ModelOptions``), apart from the physical sections of :mod:`.schema`."""

from __future__ import annotations

from typing import Literal

from pydantic import Field, StrictBool, field_validator, model_validator
from pydantic_core import PydanticCustomError

from ..names import DETECTORS, SEMI_ANALYTICAL
from ..units import Integer, Number, Quantity, format_si
from .base import _Cross, _Section


class LineFitConfig(_Section):
    """Range of the fit of eq. 11 to Tripp's line-contact law (load per unit length).

    Without ``load_min``/``load_max`` the ranges follow from the radial load: with the
    Stribeck/Harris estimate of the heaviest roller, ``q_ref = 4.08 F_r / (Z l)`` (l the
    straight roller length), race contacts are fitted over ``[0.1, 2] q_ref`` and
    roller-roller contacts over ``[0.01, 0.2] q_ref`` (see :class:`rollerdyn.model.Model`).
    Given values apply to all three contact kinds.
    """

    load_min: Quantity("force per length", positive=True) | None = None
    load_max: Quantity("force per length", positive=True) | None = None
    samples: Integer(ge=2, le=10_000) = 64

    @model_validator(mode="after")
    def _check(self) -> LineFitConfig:
        cross = _Cross()
        if (self.load_min is None) != (self.load_max is None):
            cross.add(
                "load_max" if self.load_max is None else "load_min",
                "(missing)",
                "give both load_min and load_max, or neither (derived from the radial load)",
            )
        elif self.load_max is not None and self.load_max <= self.load_min:
            cross.add(
                "load_max",
                format_si(self.load_max, "force per length"),
                f"must be > load_min ({format_si(self.load_min, 'force per length')})",
            )
        cross.raise_if_any()
        return self


#: The groups of outputs a result can hold besides the bearing's own (``solver.outputs``):
#: per roller its kinematics and race and roller-roller forces; per roller end and flange
#: its pairing, penetration, forces and location; per contact its power loss and parts;
#: per contact its largest pressure and the film, specific film thickness and sliding
#: speed there.
OUTPUT_GROUPS = ("rollers", "flanges", "power", "lubrication")


#: A run whose steps average dt_max / STALL_FRACTION or less over 10 000 steps has stalled
#: (the default of ``solver.min_mean_step``).
STALL_FRACTION = 20000.0


class SolverConfig(_Section):
    """``[solver]``: time integration and every numerical setting of the model (the
    core's ``ModelOptions``: detector, pruning, mesh resolution, border bands, friction).
    ``min_mean_step``: a run stops with an error (its result so far kept) when 10 000
    steps in a row advance the time by less than this mean step: steps that have collapsed
    to nanoseconds (B1 at 2000 N axially, the free ring tilt with the point law;
    docs/dynamics.md) would take hours or days; by default ``dt_max`` / 20 000 (50 ns at
    B1's 1 ms; B1's whole runs average at least 35 µs per step over any 10 000 steps, a
    0.05° prescribed tilt with fast ramps 180 ns); 0 s: never."""

    rtol: Number(ge=1e-12, lt=1.0) = 1e-5
    atol: Number(ge=1e-15, le=1e-3) = 1e-9
    atol_time_scale: Quantity("time", positive=True, le="1 s") = "1e-5 s"
    dt_max: Quantity("time", ge="1 ns") = "1e-3 s"
    output_interval: Quantity("time", ge="1 ns") = "1e-4 s"
    outputs: tuple[Literal[OUTPUT_GROUPS], ...] = OUTPUT_GROUPS
    checkpoint_interval: Quantity("time", ge="1 ns") = "100 ms"
    detector: Literal[DETECTORS] = SEMI_ANALYTICAL
    start: Literal["rest", "equilibrium"] = "rest"
    method: Literal["tr-bdf2", "esdirk34"] = "tr-bdf2"
    min_mean_step: Quantity("time", ge=0.0, le="1 ms") | None = None
    max_step_growth: Number(gt=1.0, le=10.0) = 1.3
    step_gain: Number(gt=0.0, le=1.0) = 0.3
    jacobian_after_newton_failure: StrictBool = True
    jacobian_at_latest_iterate: StrictBool = True
    partial_jacobians: Integer(ge=0, le=1000) = 2
    pruning: StrictBool = True
    mesh_around: Integer(ge=8, le=1024) = 64
    mesh_along: Integer(ge=2, le=256) = 16
    border_band_roller: Quantity("angle", ge=0.0, le="1 deg") = "1.5e-4 rad"
    border_band_flange: Quantity("length", ge=0.0, le="1 mm") = "50 um"
    friction: StrictBool = True
    traction_nodes: Integer(ge=1, le=200) = 12
    traction: Literal["tabulated", "direct"] = "tabulated"
    line_fit: LineFitConfig = Field(default_factory=LineFitConfig)

    @property
    def stall_step(self) -> float:
        """The mean step [s] below which the run counts as stalled: ``min_mean_step``, or
        ``dt_max`` / :data:`STALL_FRACTION` if it is not set."""
        if self.min_mean_step is not None:
            return float(self.min_mean_step)
        return float(self.dt_max) / STALL_FRACTION

    @field_validator("outputs")
    @classmethod
    def _in_order(cls, value: tuple[str, ...]) -> tuple[str, ...]:
        """The groups in the order of :data:`OUTPUT_GROUPS`; each at most once."""
        if len(set(value)) != len(value):
            twice = next(g for g in value if value.count(g) > 1)
            raise PydanticCustomError(
                "quantity", "{rule}", {"rule": f'names each group at most once ("{twice}" twice)'}
            )
        return tuple(g for g in OUTPUT_GROUPS if g in value)

    @model_validator(mode="after")
    def _check(self) -> SolverConfig:
        cross = _Cross()
        if self.min_mean_step is not None and self.min_mean_step >= self.dt_max:
            cross.add(
                "min_mean_step",
                format_si(self.min_mean_step, "time"),
                f"must be below dt_max ({format_si(self.dt_max, 'time')}); 0 s turns the "
                "stall check off",
            )
        cross.raise_if_any()
        return self
