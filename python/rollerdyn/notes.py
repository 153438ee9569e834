"""Notes on a configuration before it runs (``rollerdyn run`` and ``rollerdyn check`` print
them; :func:`configuration_notes` from Python): what is known to make a run creep with the
paper's point end-flange law, an equilibrium start whose loads have not begun, and loads
whose quasi-static equilibrium the flanges or the races cannot carry by ISO 76's static
limit. Advice only: a note never stops a run. ``rollerdyn check`` also prints, with
:func:`refusal_note`, the refusal ``rollerdyn run`` would give before its first step."""

from __future__ import annotations

import os

from .config import BearingConfig
from .config.base import TimeTable
from .names import RACES, SEMI_ANALYTICAL


def configuration_notes(
    config: BearingConfig | str | os.PathLike, t_end: float | None = None
) -> list[str]:
    """The notes on ``config`` (a configuration or its TOML file) for a run to ``t_end``
    [s] (default: the configuration's end time), one line each, in the order ``rollerdyn
    run`` prints them: :func:`slow_configuration_note`, :func:`carrier_note`,
    :func:`unloaded_start_note`, then :func:`capacity_note`. The configuration is
    validated and ``t_end`` read as :func:`rollerdyn.simulate` does (a time such as
    ``"50 ms"`` or a number of seconds; ValueError naming it otherwise)."""
    from .simulation import as_config
    from .units import parse_time

    cfg = as_config(config)
    t = cfg.end_time if t_end is None else parse_time(t_end, "t_end")
    notes = (
        slow_configuration_note(cfg),
        carrier_note(cfg),
        unloaded_start_note(cfg),
        capacity_note(cfg, t),
    )
    return [note for note in notes if note is not None]


def detector_note(detector: str) -> str | None:
    """A one-line note for a run with the mesh detector, the detection study's slow
    baseline (docs/contact.md: about 9 ms a roller end at its default resolution), or
    None: its progress lines come between steps that take seconds (B1's first step with it
    16 s on one thread)."""
    if detector != "mesh":
        return None
    return (
        "note: the mesh detector is the slow baseline of the detection study: about 9 ms a "
        "roller end against the semi-analytical detector's microsecond (docs/contact.md), "
        "so a run with it is for milliseconds of comparison, and its progress lines come "
        "between its long steps"
    )


#: The planet carrier's field [m/s^2] from which :func:`carrier_note` speaks: ten times
#: gravity, ten times the pushes on the unloaded rollers that B1's own run has.
CARRIER_FIELD_NOTED = 98.1


def carrier_note(cfg: BearingConfig) -> str | None:
    """A one-line note where a planet carrier's centrifugal field at the bearing (at its
    final speed) is more than :data:`CARRIER_FIELD_NOTED`: the field's part along the orbit
    pushes the unloaded rollers against each other, and such a run takes many small steps
    (B1 at 400 g: 18 times the steps; docs/dynamics.md, "A planet carrier")."""
    field = cfg.carrier_field
    if not field > CARRIER_FIELD_NOTED:
        return None
    return (
        f"note: the planet carrier's field at the bearing, {field:.4g} m/s^2 "
        f"({field / 9.81:.3g} g), pushes the unloaded rollers along their orbit against "
        f"each other ({cfg.roller_mass * field:.3g} N on each): expect roller-roller "
        "friction and many small steps (B1 at 400 g takes 18 times the steps of its run "
        'without the carrier; docs/dynamics.md, "A planet carrier")'
    )


def slow_configuration_note(cfg: BearingConfig) -> str | None:
    """A one-line note for a configuration known to stall or creep where B1 runs, or None,
    with the paper's point end-flange law (docs/dynamics.md, "Free inner ring tilt"):
    the free inner-ring tilt (B1 stalls in the load ramp, at t = 0.0226 s) and a
    prescribed tilt (B1 at 0.05 deg creeps from t = 0.39 s on, near the end of the load
    ramp, with its most loaded inner-flange ends on their end faces: to t = 0.55 s in 63 s
    on two cores, 64 232 steps)."""
    if cfg.surfaces.flange_law != "point":
        return None
    if cfg.inner_ring.tilt == "free":
        return (
            "note: inner_ring.tilt = free with surfaces.flange_law = point stalls in the load "
            "ramp (B1: the steps collapse at t = 0.023 s and the run stops); with "
            'surfaces.flange_law = "distributed" it takes less than the locked run with that '
            'law (docs/dynamics.md, "Free inner ring tilt")'
        )
    if cfg.inner_ring.misalignment != 0.0:
        return (
            "note: a prescribed inner_ring.misalignment with surfaces.flange_law = point "
            "creeps once the loads are up (B1 at 0.05 deg: steps of about 3 us from "
            "t = 0.39 s, to t = 0.55 s in a minute on two cores; the most loaded ends lie on "
            'their end faces); with surfaces.flange_law = "distributed" B1\'s whole run at '
            '0.05 deg takes about 29 s on one core (docs/dynamics.md, "Prescribed tilt '
            'instead")'
        )
    return None


def unloaded_start_note(cfg: BearingConfig) -> str | None:
    """A one-line note when ``solver.start = "equilibrium"`` meets loads that are still
    zero at t = 0 (a load ramp or table that starts from nothing) but not later, or None:
    the start is the equilibrium of the loads at t = 0 (docs/dynamics.md, "Start from
    equilibrium"), so such a run starts unloaded and takes its loads on afterwards, however
    fast the ramp (B1 with loads and speed ramped over 0.1 ms from such a start, at
    3000 rpm, fails at t = 0.48 ms with 18 roller ends on their end spheres)."""
    op = cfg.operating
    if cfg.solver.start != "equilibrium":
        return None
    at_start = abs(op.radial_load_at(0.0)) + abs(op.axial_load_at(0.0))
    later = abs(op.radial_load_at(cfg.end_time)) + abs(op.axial_load_at(cfg.end_time))
    if at_start > 0.0 or later == 0.0:
        return None
    return (
        'note: solver.start = "equilibrium" solves the equilibrium of the loads at t = 0, '
        "which are zero here (operating.load_ramp or a load table starts from nothing): the "
        "run starts unloaded; to start at full load, remove operating.load_ramp (and "
        'operating.speed_ramp) (docs/dynamics.md, "Start from equilibrium")'
    )


def refusal_note(cfg: BearingConfig, t_end: float | None = None) -> str | None:
    """The refusal ``rollerdyn run`` would give a run of ``cfg`` to ``t_end`` (default: its
    end time) before its first step, as a note, or None: the point end-flange law's load
    check (docs/dynamics.md, "The whole B1 run"), which ``--force`` skips. ``rollerdyn
    check`` prints it; ``rollerdyn run`` raises the refusal itself. The check is a
    quasi-static equilibrium, so it is made on the statics' core model (no traction
    table)."""
    refusal = point_law_refusal(cfg, cfg.end_time if t_end is None else float(t_end))
    if refusal is not None:
        return f"note: rollerdyn run refuses this configuration (--force runs it): {refusal}"
    refusal = start_refusal(cfg)
    if refusal is not None:
        return f"note: rollerdyn run refuses this configuration: {refusal}"
    return None


def start_refusal(cfg: BearingConfig) -> str | None:
    """Why a run of ``cfg`` has no state to start from (``solver.start``: at rest, bodies
    that overlap, e.g. B1's ring misaligned by 0.5°; from equilibrium, none found), as the
    core says it before the first step, or None. ``rollerdyn check`` passed such a
    configuration that ``rollerdyn run`` then refused (a review). Neither start
    evaluates the traction: its untabulated model serves. The contacts are found by the
    semi-analytical detector whatever the run's (they agree on the start; the mesh
    detector at its finest took minutes for it)."""
    from . import _core
    from .model import Model
    from .simulation import model_parameters

    try:
        params = model_parameters(cfg, SEMI_ANALYTICAL)
        traction = Model(cfg).traction_model(tabulated=False)
    except ValueError:
        return None  # no model to run at all: not this check's refusal (run names it)
    try:
        if cfg.solver.start == "equilibrium":
            _core.equilibrium_state(params, traction, 0.0)
        else:
            _core.initial_state(params, traction)
    except ValueError as refusal:
        text = str(refusal)
        if cfg.solver.start != "equilibrium" and 'solver.start = "equilibrium"' in text:
            # the advice checked: B1 misaligned 0.5 deg has no equilibrium either (a review)
            try:
                _core.equilibrium_state(params, traction, 0.0)
            except ValueError as none:
                text += f"; but that start finds none either ({str(none).split(': ', 1)[-1]})"
        return text
    return None


def point_law_refusal(cfg: BearingConfig, t_end: float) -> str | None:
    """The point end-flange law's load check of a run of ``cfg`` to ``t_end`` [s], as the
    core makes it before a run's first step: its refusal, or None (also for the
    distributed law, which has no such check)."""
    from .statics import _core_model

    if cfg.surfaces.flange_law != "point":
        return None
    try:
        model = _core_model(cfg)
    except ValueError:
        return None  # no model to run at all: not this check's refusal (run names it)
    try:
        model.check_point_law(t_end)
    except ValueError as refusal:
        from .simulation import refusal_with_its_cause

        return refusal_with_its_cause(cfg, str(refusal))
    return None


#: Why a roller of one slice has no equilibrium once anything tilts it (the statics'
#: hint too).
ONE_SLICE = (
    "a roller of one slice (geometry.roller.slices = 1) has no tilting stiffness at its "
    "races, so nothing holds it against the moment its flange contacts (or a "
    "misalignment) put on it, with either flange law: give more slices (B1 has 20)"
)


def capacity_note(cfg: BearingConfig, t: float) -> str | None:
    """A one-line note when the loads of a run to time ``t`` are more than the bearing
    carries statically: their quasi-static equilibrium (``rollerdyn statics``, the
    configuration's end-flange law) presses a roller end on a flange, or a roller on a
    race, past ISO 76's static limit of 4 GPa, where the surfaces deform for good
    (docs/dynamics.md, "Distributed roller end-flange law": B1 from 2.8 kN axially, and
    its inner race from 11.6 kN radially). The loads are judged at ``t`` and at every row
    of a load table before it (the extremes of a piecewise-linear history; a ramp only
    rises), the earliest past the limit named. The run goes on: whether such a load is
    worth a run is the user's call, and its elastic contacts do not describe that
    deformation. None otherwise, also where the statics find no equilibrium for another
    reason (B1 with a prescribed tilt and the point law) or fail: the note is advice and
    never stops a run."""
    op = cfg.operating
    rows = {
        row_time
        for load in (op.radial_load, op.axial_load)
        if isinstance(load, TimeTable)
        for row_time in load.times
        if row_time < t
    }
    for time in sorted(rows) + [t]:
        note = _capacity_note_at(cfg, time)
        if note is not None:
            return note
    return None


def _capacity_note_at(cfg: BearingConfig, t: float) -> str | None:
    """:func:`capacity_note` for the loads at time ``t`` alone."""
    from .statics import statics

    op = cfg.operating
    loads = (op.radial_load_at(t), op.axial_load_at(t))
    try:
        ds = statics(
            cfg,
            radial_load=loads[0],
            axial_load=loads[1],
            speed=op.inner_ring_speed_at(t),
            outer_speed=op.outer_ring_speed_at(t),
            carrier_speed=op.carrier_speed_at(t),
        )
    except ValueError as error:
        if "cannot carry it" in str(error):
            return (
                f"note: at the loads of t = {t:.4g} s, {error}; a run goes on, but its "
                "elastic contacts do not describe flanges deformed past that limit"
            )
        return None
    except Exception:  # advice only: whatever the statics make of a case, the run goes on
        return None
    return _race_note(t, loads, ds)


def _race_note(t: float, loads: tuple[float, float], ds) -> str | None:
    """The note for a quasi-static equilibrium ``ds`` whose largest race contact pressure
    (its slices', crowning and edges included) exceeds ISO 76's 4 GPa (its static safety
    by stress ``s0_races`` below 1), naming that roller and race; else None."""
    import numpy as np

    if not float(ds.s0_races) < 1.0:
        return None
    per_roller = {race: ds[f"{race}_slice_pressure"].values.max(axis=1) for race in RACES}
    race = max(RACES, key=lambda r: per_roller[r].max())
    roller = int(np.argmax(per_roller[race]))
    return (
        f"note: at the loads of t = {t:.4g} s (radial {loads[0]:g} N, axial {loads[1]:g} N) "
        f"the races cannot carry them: at equilibrium roller {roller} presses the {race} "
        f"race at {float(ds.max_pressure) / 1e9:.1f} GPa, above the 4 GPa of ISO 76's static "
        "limit; a run goes on, but its elastic contacts do not describe races deformed past "
        "that limit"
    )
