"""The runs behind the paper's sect. 5 (figs. 8-14) for a configuration: which runs, what
each is for (its role), and their names and files.

- figs. 10, 11, 12, 13: one run per axial load (default 0, 500, 1000 and 2000 N; the
  configuration's own load is always one of them), inner ring tilt locked, the
  configuration's detector (semi-analytical for B1) and Δt_max. With the point law, the
  same loads once more with the distributed law (a second series): the point law refuses
  loads at which the loaded roller ends lie flat on the flanges (B1 at 2000 N;
  docs/dynamics.md), the distributed law runs them;
- figs. 8, 9: the configuration's own run (tilt locked) and the same with
  ``inner_ring.tilt = "free"`` (never a prescribed misalignment in its place). With the
  paper's point law (``surfaces.flange_law = "point"``) the pair is run with the
  distributed law instead: the point law's free tilt collapses its steps (B1 reached
  t = 0.066 s of 1.288 s in 600 s; docs/dynamics.md, "Free inner ring tilt"), and a
  locked run with the same law is what the free one is compared with;
- sect. 5.1 and 5.3: the configuration's own run with the gradient detector (the same
  contact points and penetrations? the MBS runtime of both methods), and its round-off
  twin: the own run with ``solver.atol`` changed in the tenth digit (:data:`ROUNDOFF`),
  which takes another sequence of steps within the same tolerances and so tells how far
  the integration leaves the motion undetermined, the yardstick of the two methods'
  differences in kinematics, forces and torque;
- issue 15's figures of the two methods (not in the paper): the pair once more at ten
  times tighter tolerances (``solver.rtol`` and ``solver.atol`` × :data:`TIGHT`), where
  the integration error of the weakly held rollers at full speed falls below 0.1 µm, so
  that the two methods' whole runs are judged against absolute bounds rather than the
  twin;
- fig. 14: both detectors at each Δt_max (default 0.2, 0.5 and 1 times the
  configuration's ``solver.dt_max``).

A run needed by several figures is run once: runs are identified by their configuration
hash and detector (:func:`rollerdyn.provenance.config_hash`), and the first name given to
a run is its name.
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from typing import Any

from ..config import BearingConfig, parse_config
from ..config.solver import OUTPUT_GROUPS
from ..names import GRADIENT, SEMI_ANALYTICAL
from ..provenance import config_hash, differences, resolved
from ..units import SHORTEST_TIME
from .runs import RunSpec, StudyError

#: Axial loads of figs. 10-13 [N] (paper sect. 5.2).
DEFAULT_LOADS: tuple[float, ...] = (0.0, 500.0, 1000.0, 2000.0)

#: Δt_max of fig. 14 as multiples of the configuration's solver.dt_max.
DEFAULT_DT_MAX_FACTORS: tuple[float, ...] = (0.2, 0.5, 1.0)

#: ``surfaces.flange_law``: the paper's point contact, and the distributed law that runs
#: the free tilt and the loads the point law refuses (module doc).
POINT_LAW, DISTRIBUTED_LAW = "point", "distributed"

#: The round-off twin's relative change of ``solver.atol``: it changes the error norms in
#: their last digits, as the two detectors' contact results differ in theirs, and so,
#: sooner or later, a step (docs/dynamics.md, "How far a run moves when only its steps
#: change").
ROUNDOFF = 1e-10

#: The tight pair's factor on ``solver.rtol`` and ``solver.atol``: at B1's tolerances the
#: unloaded rollers' integration error is about 1 µm, at ten times tighter ones below
#: 0.1 µm at full speed (docs/dynamics.md, "At tighter tolerances: within 0.1 µm at full
#: speed; over the whole run only by chance").
TIGHT = 0.1


@dataclass
class Plan:
    """The runs of a paper study and what each is for (values are run names)."""

    config: BearingConfig
    t_end: float
    specs: list[RunSpec] = field(default_factory=list)
    loads: dict[float, str] = field(default_factory=dict)  # F_a [N] -> run
    # the same loads with the distributed flange law, when the configuration's is the point law
    loads_distributed: dict[float, str] = field(default_factory=dict)
    reference: str = ""  # the configuration as it is (tilt locked, its detector)
    reference_gradient: str | None = None  # the same with the gradient detector
    reference_twin: str | None = None  # the same with solver.atol changed by ROUNDOFF
    # detector -> the reference with solver.rtol and solver.atol x TIGHT (the tight pair)
    tight: dict[str, str] = field(default_factory=dict)
    free_tilt: str | None = None  # the same with the inner ring free to tilt
    tilt_locked: str = ""  # the locked run of figs. 8, 9 (the free tilt's law)
    runtime: dict[float, dict[str, str]] = field(default_factory=dict)  # dt_max -> detector

    def spec(self, name: str) -> RunSpec:
        return next(s for s in self.specs if s.name == name)


#: The study's option behind each field its runs change.
_OPTIONS = {
    "operating.axial_load": "--loads",
    "solver.dt_max": "--dt-max",
    "solver.rtol": "--tight",
    "solver.atol": "--tight",
}


def _variant(cfg: BearingConfig, changes: dict) -> BearingConfig:
    """``cfg`` with dotted-path changes (SI numbers), validated again; a change the
    configuration's rules refuse raises :class:`StudyError` naming the option, the field,
    the value and the rule."""
    from ..config import ConfigError
    from ..sweep import changed

    try:
        return parse_config(changed(cfg.model_dump(), changes), si_numbers=True)
    except ConfigError as err:
        problem = next(iter(err.problems or ()), None)
        if problem is None:
            raise StudyError(str(err).splitlines()[-1].strip()) from None
        option = _OPTIONS.get(problem.path, "the study's change")
        raise StudyError(f"{option}: {' '.join(str(problem).split())}") from None


def _numbers(values: Any, option: str, what: str) -> list[float]:
    """``values`` (numbers) as floats; :class:`StudyError` naming ``option`` for anything
    else (None, a text, a list holding a text)."""
    if isinstance(values, str | bytes) or not isinstance(values, Iterable):
        raise StudyError(f"{option} = {values!r}: expected a list of {what} (empty: none)")
    values = list(values)
    for v in values:
        if isinstance(v, bool) or not isinstance(v, numbers.Real):
            raise StudyError(f"{option} = {values!r}: {v!r} is not a number; expected {what}")
    return [float(v) for v in values]


def _fmt(value: float) -> str:
    return f"{value:g}"


def _check_cost(name: str, variant: BearingConfig, end: float, det: str, given: bool) -> None:
    """Refuses, before any run, a run of the plan whose results, steps or checkpoints to
    ``end`` with the detector ``det`` would be far beyond a normal run's
    (:func:`rollerdyn.simulation.check_cost`; a study has no ``--force``): ``--t-end 1e9``
    started all 17 runs, each of which failed with that message. ``given``: whether
    ``--t-end`` was (the message leads with it then); a runtime run's dt_max is
    ``--dt-max``'s."""
    from ..simulation import check_cost

    own = " (its --dt-max)" if name.startswith("dt-max-") else " in the configuration"
    try:
        check_cost(
            variant,
            end,
            remedy=f"{own}, or a shorter --t-end",
            outputs_optional=False,
            detector=det,
        )
    except ValueError as err:
        lead = f"--t-end = {end:g} s: " if given else ""
        raise StudyError(f"{lead}the run {name}: {err}") from None


def build_plan(
    config: BearingConfig,
    t_end: float | None = None,
    loads: Sequence[float] = DEFAULT_LOADS,
    dt_max: Sequence[float] | None = None,
    free_tilt: bool = True,
    gradient: bool = True,
    distributed: bool = True,
    tight: bool = True,
) -> Plan:
    """The runs of the paper study of ``config`` to ``t_end`` [s] (default: the
    configuration's end time); ``loads`` [N], ``dt_max`` [s] (default: 0.2, 0.5 and 1
    times ``solver.dt_max``; empty: no fig. 14 runs). ``gradient=False``: no run with the
    gradient detector (so neither fig. 14 nor the comparison of the methods, nor its
    round-off twin, nor the tight pair). ``tight=False``: no pair of the two detectors at
    :data:`TIGHT` times the tolerances.
    ``distributed=False``: no second load series with the distributed law. Raises
    :class:`StudyError` for values that make no run. The runs record every output
    (``solver.outputs``): the study's figures and checks need them all."""
    cfg = config
    if tuple(cfg.solver.outputs) != OUTPUT_GROUPS:
        cfg = _variant(cfg, {"solver.outputs": list(OUTPUT_GROUPS)})
    end = float(cfg.end_time if t_end is None else t_end)
    if not (end >= SHORTEST_TIME and math.isfinite(end)):
        raise StudyError(f"--t-end = {t_end!r}: must be a time of at least 1 ns")
    loads = _numbers(loads, "--loads", "axial loads in N")
    if any(not (math.isfinite(v) and v >= 0.0) for v in loads):
        raise StudyError(f"--loads = {loads}: every axial load must be >= 0 N")
    if dt_max is None:
        dt_max = [cfg.solver.dt_max * f for f in DEFAULT_DT_MAX_FACTORS]
    dt_max = _numbers(dt_max, "--dt-max", "times in s")  # checked without gradient runs too
    dt_max = sorted(set(dt_max)) if gradient else []
    if any(not (math.isfinite(v) and v > 0.0) for v in dt_max):
        raise StudyError(f"--dt-max = {dt_max}: must be positive times in s")
    detector = cfg.solver.detector
    plan = Plan(config=cfg, t_end=end)
    seen: dict[tuple[str, str], str] = {}

    base = resolved(cfg)

    def add(name: str, variant: BearingConfig, det: str, label: str, meta: dict) -> str:
        key = (config_hash(variant), det)
        if key in seen:
            return seen[key]
        seen[key] = name
        _check_cost(name, variant, end, det, t_end is not None)
        changed = [d.replace("'", "") for d in differences(base, resolved(variant))]
        if det != detector:
            changed.append(f"detector: {detector} -> {det}")
        meta = {**meta, "changes": "; ".join(changed) or "none"}
        plan.specs.append(
            RunSpec(name, label, variant.model_dump(), det, end, key[0], meta=dict(meta))
        )
        return name

    def meta(fa: float | None, tilt: str, dt: float) -> dict:
        return {
            "axial_load [N]": math.nan if fa is None else fa,
            "tilt": tilt,
            "dt_max [s]": dt,
        }

    def add_load(fa: float) -> str:  # figs. 10-13: the configuration at another axial load
        return add(
            f"axial-{_fmt(fa)}N",
            _variant(cfg, {"operating.axial_load": fa}),
            detector,
            f"F_a = {_fmt(fa)} N, {tilt_text}",
            meta(fa, cfg.inner_ring.tilt, dt0),
        )

    law = {"surfaces.flange_law": DISTRIBUTED_LAW}

    def add_distributed(fa: float | None) -> str:  # the distributed law at load fa
        own_load = fa is None or fa == own_fa  # None: the configuration's own load
        fa = own_fa if own_load else fa
        return add(
            f"{plan.reference}-{DISTRIBUTED_LAW}"
            if own_load
            else f"axial-{_fmt(fa)}N-{DISTRIBUTED_LAW}",
            _variant(cfg, law if own_load else {**law, "operating.axial_load": fa}),
            detector,
            f"{_label_fa(fa)}, {tilt_text}, {DISTRIBUTED_LAW} flange law",
            meta(fa, cfg.inner_ring.tilt, dt0),
        )

    own = cfg.operating.axial_load
    own_fa = float(own) if isinstance(own, int | float) else None
    dt0 = cfg.solver.dt_max
    locked = cfg.inner_ring.tilt == "locked"
    point_law = cfg.surfaces.flange_law == POINT_LAW
    tilt_text = "tilt locked" if locked else "tilt free"
    if cfg.inner_ring.misalignment:
        tilt_text = f"misaligned {math.degrees(cfg.inner_ring.misalignment):g} deg"
    # The configuration's own run first: most figures and checks need it.
    ref_name = f"axial-{_fmt(own_fa)}N" if own_fa is not None else "reference"
    plan.reference = add(
        ref_name,
        cfg,
        detector,
        f"F_a = {_fmt(own_fa)} N, {tilt_text}" if own_fa is not None else "reference",
        meta(own_fa, cfg.inner_ring.tilt, dt0),
    )
    if gradient and detector != GRADIENT:
        plan.reference_gradient = add(
            f"{ref_name}-gradient",
            cfg,
            GRADIENT,
            f"{_label_fa(own_fa)}, {tilt_text}, gradient detector",
            meta(own_fa, cfg.inner_ring.tilt, dt0),
        )
        plan.reference_twin = add(
            f"{ref_name}-roundoff",
            _variant(cfg, {"solver.atol": cfg.solver.atol * (1.0 + ROUNDOFF)}),
            detector,
            f"{_label_fa(own_fa)}, {tilt_text}, round-off twin (solver.atol × (1 + {ROUNDOFF:g}))",
            meta(own_fa, cfg.inner_ring.tilt, dt0),
        )
    if gradient and tight and detector != GRADIENT:
        tightened = _variant(
            cfg,
            {"solver.rtol": _tighter(cfg.solver.rtol), "solver.atol": _tighter(cfg.solver.atol)},
        )
        for det, suffix in ((detector, "tight"), (GRADIENT, "gradient-tight")):
            plan.tight[det] = add(
                f"{ref_name}-{suffix}",
                tightened,
                det,
                f"{_label_fa(own_fa)}, {tilt_text}, {det}, solver.rtol and solver.atol × {TIGHT:g}",
                meta(own_fa, cfg.inner_ring.tilt, dt0),
            )
    plan.tilt_locked = plan.reference
    if free_tilt and not locked:
        plan.free_tilt = plan.reference
    elif free_tilt:  # figs. 8, 9: with the point law both runs with the distributed law
        tilt = {"inner_ring.tilt": "free", "inner_ring.misalignment": 0.0}
        suffix = law_text = ""
        if point_law:
            plan.tilt_locked = add_distributed(None)
            tilt, suffix = {**tilt, **law}, f"-{DISTRIBUTED_LAW}"
            law_text = f", {DISTRIBUTED_LAW} flange law"
        plan.free_tilt = add(
            f"free-tilt{suffix}",
            _variant(cfg, tilt),
            detector,
            f"{_label_fa(own_fa)}, inner ring free to tilt{law_text}",
            meta(own_fa, "free", dt0),
        )
    # figs. 10-13: the highest load early (it may be the slowest), the rest after fig. 14's.
    series = sorted(set(loads) | ({own_fa} if own_fa is not None else set()))
    later = []
    for fa in sorted(series, reverse=True):
        if fa == own_fa:
            plan.loads[fa] = plan.reference
            continue
        later.append(fa)
    if later:
        top = later.pop(0)
        plan.loads[top] = add_load(top)
    for dt in dt_max:
        plan.runtime[dt] = {}
        variant = _variant(cfg, {"solver.dt_max": dt})
        for det in (SEMI_ANALYTICAL, GRADIENT):
            plan.runtime[dt][det] = add(
                f"dt-max-{dt:.3g}s-{det}",
                variant,
                det,
                f"{_label_fa(own_fa)}, Δt_max = {dt:.3g} s, {det}",
                meta(own_fa, cfg.inner_ring.tilt, dt),
            )
    for fa in later:
        plan.loads[fa] = add_load(fa)
    plan.loads = dict(sorted(plan.loads.items()))
    if distributed and point_law:
        for fa in sorted(plan.loads, reverse=True):  # the highest (slowest) load first
            plan.loads_distributed[fa] = add_distributed(fa)
        plan.loads_distributed = dict(sorted(plan.loads_distributed.items()))
    return plan


def _tighter(tolerance: float) -> float:
    """``tolerance`` × :data:`TIGHT`, rounded to 12 digits (B1's 1e-5 gives 1e-6, not
    1.0000000000000002e-06)."""
    return float(f"{tolerance * TIGHT:.12g}")


def _label_fa(fa: float | None) -> str:
    return "reference" if fa is None else f"F_a = {_fmt(fa)} N"
