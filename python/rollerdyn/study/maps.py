"""``rollerdyn study map``: operating maps beyond the paper. A grid of speeds (of the inner
ring, or of a turning outer ring about a still inner one: :func:`turning_ring`), radial and
axial loads and oil temperatures, each point run on Dask until its outputs are
steady (:mod:`.steady`), and maps of friction torque (with the quasi-static torque of steady
rolling beside it, :mod:`.estimates`), roller-set speed loss (skidding) and largest flange
force; over two or more temperatures, with a heat dissipation, the thermal
balance (:mod:`.thermal`): the temperature at which the bearing gives off the heat its
friction makes.

The folder (default ``results/map``) holds ``study.json``, ``points/point_XXXX.nc`` (one
result per grid point, written at its checkpoints), ``map.csv`` and ``map.parquet`` (one
row per point), ``thermal.csv`` (with a heat dissipation: one row per speed and loads),
``figures/`` (the maps, PNG and SVG) and ``report.html`` (:mod:`.map_page`). Invoked
again it runs only what is missing, as ``rollerdyn study paper`` does.
"""

from __future__ import annotations

import itertools
import math
import os
import time
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..config.base import T0_CELSIUS
from ..config.solver import OUTPUT_GROUPS
from ..provenance import config_hash
from ..units import QuantityError, parse_quantity
from .estimates import STEADY_ROLLING, TORQUE_RATIO, steady_rolling_torques
from .runs import FINISHED, RunSpec, StudyError, inspect_run, lock_folder, open_run, record
from .steady import LAMBDAS, VIBRATION, SteadyRule, window_length, window_outputs

RPM = 2.0 * math.pi / 60.0

#: How a grid point starts: "equilibrium" (full load and speed from t = 0, from the
#: quasi-static equilibrium, solver.start; the default), "short-ramps" (loads over 0 ...
#: --ramp, speed over --ramp ... 2 --ramp, cosine) or "config" (the configuration's own
#: ramps).
STARTS = ("equilibrium", "short-ramps", "config")

#: The configuration paths the grid sets, and their options.
OPTIONS = {
    "operating.inner_ring_speed": "--speed",
    "operating.radial_load": "--radial-load",
    "operating.axial_load": "--axial-load",
    "operating.temperature": "--temperature",
}

#: Map outputs: column, title, unit.
OUTPUTS = (
    ("torque [N*m]", "friction torque", "N·m"),
    (TORQUE_RATIO, "torque / quasi-static torque of steady rolling", "-"),
    ("speed loss [1]", "roller-set speed loss 1 - cage / epicyclic speed", "-"),
    ("max flange force [N]", "largest flange normal force", "N"),
    ("inner race Lambda [1]", "median specific film thickness, inner race", "-"),
    ("flange Lambda [1]", "median specific film thickness, roller ends / flanges", "-"),
    ("ring vibration [m]", "inner ring vibration along the radial load, peak to peak", "m"),
)


#: The map's table as printed and on its page: column, heading, number format.
MAP_COLUMNS = (
    ("point", "point", ""),
    ("speed [rpm]", "speed [rpm]", ".4g"),
    ("radial_load [N]", "F_r [N]", ".4g"),
    ("axial_load [N]", "F_a [N]", ".4g"),
    ("temperature [degC]", "T [degC]", ".4g"),
    ("status", "status", ""),
    ("steady at [s]", "steady at [s]", ".4g"),
    ("torque [N*m]", "torque [N*m]", ".4g"),
    (STEADY_ROLLING, "steady rolling [N*m]", ".4g"),
    ("speed loss [1]", "speed loss [-]", ".3g"),
    ("max flange force [N]", "max flange force [N]", ".4g"),
    ("inner race Lambda [1]", "Lambda inner race [-]", ".3g"),
    ("flange Lambda [1]", "Lambda flanges [-]", ".3g"),
    ("ring vibration [m]", "ring vibration p-p [m]", ".3g"),
    ("wall [s]", "wall [s]", ".1f"),
)

#: Least number of outputs in a window W of the steadiness criterion: each point's
#: ``solver.output_interval`` is at most W / 100. The friction torque of an unloaded B1
#: (0 N axial) loses its correlation within 0.1-0.2 ms; sampled every 1 ms (B1's own
#: interval, 10 samples in a 10 ms window) its window means scattered by 6 % at 3000 rpm
#: and the point never became steady at --tol 0.02; sampled every 0.1 ms, by 1.1 %
#: (docs/study.md, "How often a point is sampled").
OUTPUTS_PER_WINDOW = 100

#: The output groups (``solver.outputs``) a map's points record at least: the steadiness
#: windows read the rollers' orbital speeds and the flange forces, the map's lubrication
#: columns the contacts' specific film thickness (:mod:`.steady`).
MAP_OUTPUTS = ("rollers", "flanges", "lubrication")

#: Most grid points of a map: each is a dynamic run of seconds to minutes (and the
#: points' folders are numbered with four digits).
MAX_MAP_POINTS = 10_000


def parse_range(
    text: str | Sequence[float] | float,
    option: str,
    family: str,
    unit: str,
    positive: bool = False,
) -> list[float]:
    """The values of a grid option, SI: ``"a:b:n"`` (n evenly spaced values from a to b,
    a < b, n >= 2; or n = 1 with a = b), a comma list ``"v1,v2"`` or one value. Each value
    is a number in ``unit`` (rpm, N) or has its own unit (``"5 kN"``). Raises
    :class:`StudyError` naming ``option`` for an empty, reversed or malformed range."""
    if isinstance(text, int | float) and not isinstance(text, bool):
        texts: list[Any] = [text]
    elif isinstance(text, str):
        texts = []
    elif isinstance(text, bytes | bool) or not isinstance(text, Iterable):
        raise StudyError(f"{option} {text!r}: give a:b:n, a list v1,v2,... or a value")
    else:
        texts = list(text)

    def value(v: Any) -> float:
        v = in_unit(v, unit)
        try:
            return parse_quantity(v, family)
        except QuantityError as err:
            raise StudyError(f"{option} {text!r}: {v!r}: {err}") from None

    if isinstance(text, str):
        body = text.strip()
        if not body:
            raise StudyError(f"{option} {text!r}: empty; give a:b:n, a list v1,v2,... or a value")
        if ":" in body:
            parts = body.split(":")
            if len(parts) != 3 or not all(p.strip() for p in parts):
                raise StudyError(f"{option} {text!r}: expected a:b:n (from a to b in n points)")
            try:
                n = int(parts[2])
            except ValueError:
                raise StudyError(
                    f"{option} {text!r}: n = {parts[2].strip()!r} must be a whole number of points"
                ) from None
            a, b = value(parts[0]), value(parts[1])
            if n < 1:
                raise StudyError(
                    f"{option} {text!r}: empty range ({n} points); n must be >= 2 (or 1 with a = b)"
                )
            if a > b:
                raise StudyError(
                    f"{option} {text!r}: reversed range (a = {parts[0].strip()} > b = "
                    f"{parts[1].strip()}); give it from low to high"
                )
            if n == 1 and a != b:
                raise StudyError(f"{option} {text!r}: one point needs a = b, or n >= 2")
            if n > 1 and a == b:
                raise StudyError(f"{option} {text!r}: empty range (a = b) with {n} points")
            values = [a + (b - a) * i / (n - 1) for i in range(n)] if n > 1 else [a]
        else:
            values = [value(v) for v in body.split(",") if v.strip()]
            if len(values) != len(body.split(",")):
                raise StudyError(f"{option} {text!r}: an empty value (two commas)")
    else:
        values = [value(v) for v in texts]
        if not values:
            raise StudyError(f"{option}: no values given")
    if len(set(values)) != len(values):
        raise StudyError(f"{option} {text!r}: a value is given twice")
    for v in values:
        if not math.isfinite(v) or v < 0 or (positive and v == 0):
            rule = "above 0" if positive else ">= 0"
            raise StudyError(f"{option} {text!r}: every value must be {rule}")
    return sorted(values)


def in_unit(value: Any, unit: str) -> str:
    """The text of a map option's value for :func:`parse_quantity`: a number, or a number
    given as text, in ``unit``; other text (with its own unit) as it is."""
    if isinstance(value, int | float) and not isinstance(value, bool):
        return f"{value!r} {unit}"
    text = str(value).strip()
    try:
        float(text)
    except ValueError:
        return text
    return f"{text} {unit}"


@dataclass
class MapStudy:
    """What :func:`operating_map` made: one row per grid point (a ``pandas.DataFrame``,
    see :func:`point_row`), the figures written and the study's folder."""

    outdir: Path
    points: Any
    figures: list[Path] = field(default_factory=list)
    timing: dict = field(default_factory=dict)
    #: The thermal balance (:func:`.thermal.balance_temperatures`; one row per speed and
    #: loads), with a heat dissipation only.
    thermal: Any = None
    #: The thermally permissible speeds (:func:`.thermal.permissible_speeds`; one row per
    #: loads), with a permissible temperature only.
    permissible: Any = None


def point_config(
    cfg,
    speed: float,
    radial: float,
    axial: float,
    start: str,
    ramp: float,
    temperature: float | None = None,
):
    """(configuration of a grid point, end of its ramps [s]): ``cfg`` with its turning
    ring (:func:`turning_ring`) at ``speed`` [rad/s], the loads [N] and the oil
    ``temperature`` [K] (default the configuration's), started as ``start`` says
    (:data:`STARTS`)."""
    from ..config import parse_config
    from ..sweep import changed

    data = cfg.model_dump()
    op = data["operating"]
    op.update(
        {f"{turning_ring(cfg)}_ring_speed": speed, "radial_load": radial, "axial_load": axial}
    )
    if temperature is not None:
        op["temperature"] = temperature
    op.pop("end_time", None)
    # the steadiness windows read the rollers' and flanges' outputs (study.steady)
    groups = set(data["solver"]["outputs"]) | set(MAP_OUTPUTS)
    changes: dict[str, Any] = {"solver.outputs": [g for g in OUTPUT_GROUPS if g in groups]}
    if start == "short-ramps":
        op["load_ramp"] = {"start": 0.0, "end": ramp, "shape": "cosine"}
        op["speed_ramp"] = {"start": ramp, "end": 2 * ramp, "shape": "cosine"}
    elif start == "equilibrium":
        op.pop("load_ramp", None)
        op.pop("speed_ramp", None)
        changes["solver.start"] = "equilibrium"
    variant = parse_config(changed(data, changes), si_numbers=True)
    op = variant.operating
    settle = max(op.speed_history_end, 0.0 if op.load_ramp is None else op.load_ramp.end)
    return variant, settle


def windowed(variant, window: float):
    """``variant`` with its checkpoints every ``window`` W [s] (the steadiness criterion's
    windows end at them) and its outputs at most every W / :data:`OUTPUTS_PER_WINDOW`
    (a finer ``solver.output_interval`` of the configuration is kept)."""
    sol = variant.solver.model_copy(
        update={
            "checkpoint_interval": window,
            "output_interval": min(variant.solver.output_interval, window / OUTPUTS_PER_WINDOW),
        }
    )
    return variant.model_copy(update={"solver": sol})


def result_size_refusal(variant, max_time: float, window: float) -> str | None:
    """Why a point's result file run to ``max_time`` [s] would be too large (its outputs
    every W / :data:`OUTPUTS_PER_WINDOW`, above ``simulation.MAX_RESULT_BYTES``), naming
    the map's options that decide it; None when it is not."""
    from ..simulation import MAX_RESULT_BYTES, estimated_cost

    cost = estimated_cost(variant, max_time)
    if cost["memory_bytes"] <= MAX_RESULT_BYTES:  # what the run holds while it goes
        return None
    interval = variant.solver.output_interval
    if interval < window / OUTPUTS_PER_WINDOW * (1 - 1e-9):  # the configuration's own
        why = "the configuration's solver.output_interval"
        remedy = f"choose a solver.output_interval of up to {window / OUTPUTS_PER_WINDOW:.3g} s"
    else:
        why = f"{OUTPUTS_PER_WINDOW} per window of {window:.4g} s"
        remedy = "choose a longer --window"
    return (
        f"{cost['outputs']:.3g} outputs (one every {interval:.3g} s: {why}) would take "
        f"{cost['memory_bytes'] / 1e9:.3g} GB of results while it runs (more than "
        f"{MAX_RESULT_BYTES / 1e9:g} GB); "
        f"{remedy} or a shorter --max-time"
    )


def equilibrium_refusal(variant, traction) -> str | None:
    """Why ``variant`` has no quasi-static equilibrium at t = 0 (the start of
    ``solver.start = "equilibrium"``: the core's message, without its prefix), or None if
    it has one. ``traction``: any traction model of the configuration (the equilibrium
    does not evaluate it)."""
    from .. import _core
    from ..simulation import model_parameters

    try:
        _core.equilibrium_state(model_parameters(variant, variant.solver.detector), traction, 0.0)
    except ValueError as err:
        return str(err).removeprefix("solver.start = equilibrium: ").strip()
    return None


#: The start a grid point falls back to when it has no equilibrium (column ``start``).
FALLBACK = "short-ramps: no equilibrium at t = 0"


def operating_map(
    config: Any,
    outdir: str | os.PathLike = "results/map",
    *,
    speed: Any,
    radial_load: Any = None,
    axial_load: Any = None,
    temperature: Any = None,
    heat_dissipation: Any = None,
    ambient: Any = None,
    oil_flow: Any = None,
    oil_inlet: Any = None,
    permissible_temperature: Any = None,
    start: str = "equilibrium",
    ramp: float = 0.02,
    window: float = 0.01,
    tol: float = 0.02,
    max_time: float = 0.5,
    max_wall: float = 300.0,
    scheduler: Any = None,
    workers: int | None = None,
    overwrite: bool = False,
    progress: Callable[[dict], Any] | None = None,
    force: bool = False,
) -> MapStudy:
    """Runs the grid ``speed`` x ``radial_load`` x ``axial_load`` x ``temperature`` of
    ``config`` until each point is steady (see :mod:`.steady`) and draws the maps.

    ``speed`` [rpm], ``radial_load`` and ``axial_load`` [N], ``temperature`` [degC]:
    ``"a:b:n"``, ``"v1,v2"``, a number or a list (see :func:`parse_range`); loads and
    temperature default to the configuration's. ``heat_dissipation`` [W/K] (a number, or
    text with a unit: ``"0.35 W/K"``): the heat the bearing gives off per kelvin above
    ``ambient`` (default ``"20 degC"``, a number in degC or text with a unit); with it, and
    two or more temperatures, the thermal balance of each speed and loads
    (:func:`.thermal.balance_temperatures`) is written to ``thermal.csv`` and drawn;
    ``oil_flow`` [m^3/s] (a number, or text with a unit: ``"0.5 l/min"``) of a circulating
    oil entering at ``oil_inlet`` (default: ``ambient``) carries heat away too; and
    with ``permissible_temperature`` [degC] (a number, or text with a unit) the thermally
    permissible speed of each loads (:func:`.thermal.permissible_speeds`) to
    ``thermal_speed.csv``.
    ``start``: one of :data:`STARTS`; a point without a quasi-static equilibrium at t = 0
    (:func:`equilibrium_refusal`) starts from short ramps instead, and its row's ``start``
    says so and why (:data:`FALLBACK`). ``ramp`` [s]: the short ramps' length (read only
    with short ramps; the command line refuses ``--ramp`` otherwise). ``window``
    [s], ``tol`` [1]: the steadiness criterion; ``max_time`` [s]: simulated time at which
    a point that is not steady ends; ``max_wall`` [s]: wall-time cap per point and
    invocation. ``force``: run the points the point end-flange law's load check refuses
    (as ``rollerdyn run --force``; their rows' notes say so); without it such a point is a
    run that could not be run, and a later invocation with ``force`` runs it.
    ``progress`` hears ``{"kind": "prepare", "done", "total"}`` while the points are
    checked, then the runs' events (:func:`.schedule.run_all`). Other arguments as in
    :func:`rollerdyn.study.paper`."""
    from ..simulation import as_config
    from .paper import _source_name, check_arguments, default_workers
    from .schedule import Clock, check_scheduler, check_workers
    from .thermal import dissipation_from_options

    clock = Clock()
    check_arguments(progress, overwrite=overwrite, force=force)
    cfg = as_config(config)
    _check_map_settings(start, ramp, window, tol, max_time, max_wall)
    turning_ring(cfg)
    axes = _map_axes(cfg, speed, radial_load, axial_load, temperature)
    dissipation = dissipation_from_options(
        cfg,
        axes[3],
        {
            "--heat-dissipation": heat_dissipation,
            "--ambient": ambient,
            "--oil-flow": oil_flow,
            "--oil-inlet": oil_inlet,
            "--permissible-temperature": permissible_temperature,
        },
    )
    workers = default_workers() if workers is None else workers
    check_workers(workers)
    specs, rules = _map_points(cfg, axes, start, ramp, window, tol, max_time, progress)
    check_scheduler(scheduler)
    settings = {"start": start, "ramp": ramp, "window": window, "tol": tol, "max_time": max_time}
    # the points are files by number: a folder continues only the grid it was made with
    grid = axes if axes[3] != [cfg.operating.temperature] else axes[:3]
    settings["grid"] = [[float(v) for v in axis] for axis in grid]
    run = {
        "max_wall": float(max_wall),
        "scheduler": scheduler,
        "workers": workers,
        "force": force,
    }
    return _run_map(
        cfg,
        Path(outdir),
        specs,
        rules,
        settings,
        run,
        overwrite,
        progress,
        clock,
        source=_source_name(config),
        dissipation=dissipation,
        axes=axes,
    )


def _check_map_settings(
    start: str, ramp: float, window: float, tol: float, max_time: float, max_wall: float
) -> None:
    """Refuses a start that is not one of :data:`STARTS` and settings that are not positive
    numbers (``tol`` below 1; ``ramp`` read only with short ramps)."""
    if start not in STARTS:
        raise StudyError(f"--start = {start!r}: must be {', '.join(STARTS)}")
    for name, value, ok in (
        ("--ramp", ramp, start != "short-ramps" or value_ok(ramp)),
        ("--window", window, value_ok(window)),
        ("--tol", tol, value_ok(tol) and tol < 1),
        ("--max-time", max_time, value_ok(max_time)),
        ("--max-wall", max_wall, value_ok(max_wall)),
    ):
        if not ok:
            below = " below 1" if name == "--tol" else ""
            raise StudyError(f"{name} = {value!r}: must be a positive number{below}")


def turning_ring(cfg: Any) -> str:
    """The ring whose speed a map sweeps, the other one standing: "inner" where the outer
    ring is fixed (B1), "outer" where the configuration turns the outer ring about a still
    inner ring (a planet gear's bearing). Both turning is refused, naming the values."""
    op = cfg.operating
    inner, outer = op.inner_ring_speed, op.outer_ring_speed
    if isinstance(outer, float) and outer == 0.0:
        return "inner"
    if isinstance(inner, float) and inner == 0.0:
        return "outer"
    raise StudyError(
        f"operating.inner_ring_speed = {op.final_inner_ring_speed / RPM:g} rpm with "
        f"operating.outer_ring_speed = {op.final_outer_ring_speed / RPM:g} rpm: a map sweeps "
        "the speed of one ring with the other standing (--speed turns the inner ring where "
        "the outer one is fixed, the outer ring where the inner one is at 0 rpm); map both "
        "turning with 'rollerdyn sweep'"
    )


def _map_axes(cfg: Any, speed: Any, radial_load: Any, axial_load: Any, temperature: Any = None):
    """The map's speeds [rad/s], radial and axial loads [N] and oil temperatures [K] (the
    loads by default the configuration's final ones, the temperature the configuration's),
    at most :data:`MAX_MAP_POINTS` points in all."""
    speeds = parse_range(speed, "--speed", "angular velocity", "rpm", positive=True)
    own = cfg.operating
    radial = parse_range(
        radial_load if radial_load is not None else [_final(own.radial_load)],
        "--radial-load",
        "force",
        "N",
    )
    axial = parse_range(
        axial_load if axial_load is not None else [_final(own.axial_load)],
        "--axial-load",
        "force",
        "N",
    )
    temperatures = parse_range(
        temperature if temperature is not None else [f"{own.temperature!r} K"],
        "--temperature",
        "temperature",
        "degC",
        positive=True,
    )
    total = len(speeds) * len(radial) * len(axial) * len(temperatures)
    if total > MAX_MAP_POINTS:
        raise StudyError(
            f"--speed, --radial-load, --axial-load, --temperature: {len(speeds)} x "
            f"{len(radial)} x {len(axial)} x {len(temperatures)} = {total} grid points; a "
            f"map has at most {MAX_MAP_POINTS} (each point is a dynamic run of seconds to "
            "minutes)"
        )
    return speeds, radial, axial, temperatures


def _map_points(cfg: Any, axes, start, ramp, window, tol, max_time, progress=None):
    """The runs of the grid ``axes`` (speeds, radial loads, axial loads) and the
    steadiness rule of each run by name. Every point is validated before any runs: the
    points that fail are named together. ``progress`` receives ``{"kind": "prepare",
    "done", "total"}`` before the first point, at most every 0.5 s after and when all are
    done (each point
    takes about 57 ms with its quasi-static start: a grid of 1000 points was silent for a
    minute)."""
    from ..config import ConfigError
    from ..model import Model

    g = cfg.geometry
    factor = g.epicyclic_factor
    # the roller set's speed per swept speed: of the inner ring, or of a turning outer one
    cage_factor = factor if turning_ring(cfg) == "inner" else g.outer_epicyclic_factor
    rules, specs, problems = {}, [], []
    # the equilibrium does not evaluate the traction: its untabulated model, built at once
    traction = Model(cfg).traction_model(tabulated=False) if start == "equilibrium" else None
    own_temperature = axes[3] == [cfg.operating.temperature]
    total = math.prod(len(axis) for axis in axes)
    said = -math.inf
    for i, (w, fr, fa, temp) in enumerate(itertools.product(*axes)):
        if progress is not None and (time.monotonic() - said >= 0.5 or i == 0):
            progress({"kind": "prepare", "done": i, "total": total})
            said = time.monotonic()
        label = f"{w / RPM:g} rpm, F_r = {fr:g} N, F_a = {fa:g} N"
        if not own_temperature:  # the map sets the oil temperature
            label += f", {temp - T0_CELSIUS:g} degC"
        try:
            variant, settle, started = _point_start(cfg, (w, fr, fa, temp), start, ramp, traction)
        except ConfigError as err:
            for prob in err.problems or ():
                option = OPTIONS.get(prob.path)
                # the point's label gives its values with their units (the configuration's
                # value is the map's SI number)
                said = f"point {i} ({label}): {prob.path} — {prob.rule}"
                problems.append(said + (f" ({option})" if option else ""))
            if not err.problems:
                problems.append(f"point {i} ({label}): {str(err).splitlines()[-1].strip()}")
            continue
        win = window_length(window, w, g.roller_count, cage_factor)
        if settle + 3 * win > max_time:
            longer = " (two roller passes, longer than --window)" if win > window else ""
            raise StudyError(
                f"--max-time = {max_time:g} s: too short for point {i} ({label}): the ramps "
                f"end at {settle:g} s and three windows of {win:.4g} s{longer} must follow"
            )
        variant = windowed(variant, win)
        size = result_size_refusal(variant, max_time, win)
        if size:
            raise StudyError(
                f"--max-time = {max_time:g} s: too long for point {i} ({label}): {size}"
            )
        meta = {
            "speed [rpm]": float(f"{w / RPM:.12g}"),  # 3000, not 3000.0000000000005
            "radial_load [N]": fr,
            "axial_load [N]": fa,
            "temperature [degC]": temp - T0_CELSIUS,
            "start": started,
        }
        name = f"point_{i:04d}"
        spec = RunSpec(
            name,
            label,
            variant.model_dump(),
            variant.solver.detector,
            max_time,
            config_hash(variant),
            meta=meta,
        )
        rules[name] = SteadyRule(settle, win, tol, factor)
        specs.append(spec)
    if progress is not None:
        progress({"kind": "prepare", "done": total, "total": total})
    if problems:
        failing = len({p.split(" (", 1)[0] for p in problems})  # "point i (...): ..."
        raise StudyError(
            f"invalid map: {failing} grid point(s) fail validation (no run was started): "
            + "; ".join(problems)
        )
    return specs, rules


def _point_start(cfg: Any, point, start: str, ramp: float, traction):
    """The configuration of one grid point (speed, radial load, axial load, temperature),
    its settling time and how it starts: from ``start``, or from short ramps
    (:data:`FALLBACK`, with the reason) where ``traction`` is given and the point has no
    quasi-static equilibrium (:func:`equilibrium_refusal`; e.g. the free tilt's, whose
    rollers the statics press past ISO 76)."""
    speed, radial, axial, temperature = point
    variant, settle = point_config(cfg, speed, radial, axial, start, ramp, temperature)
    if traction is not None:
        refusal = equilibrium_refusal(variant, traction)
        if refusal is not None:
            variant, settle = point_config(
                cfg, speed, radial, axial, "short-ramps", ramp, temperature
            )
            return variant, settle, f"{FALLBACK} ({refusal})"
    return variant, settle, start


def _run_map(
    cfg, out, specs, rules, settings, run, overwrite, progress, clock, *, source, dissipation, axes
):
    """Runs the grid's points ``specs`` of the grid ``axes`` in the folder ``out``
    (prepared, and locked meanwhile; ``run``: max_wall, scheduler, workers and force),
    each beside its quasi-static estimate (:mod:`.estimates`), writes map.csv, map.parquet and
    the figures (and with ``dissipation``, a :class:`.thermal.Dissipation`, the thermal
    balance: thermal.csv, thermal_speed.csv and their figures), and returns the study."""
    import pandas as pd

    from .folder import prepare_folder, record_files
    from .map_figures import write_maps
    from .map_page import build_map_page
    from .report_page import write_page
    from .schedule import run_all, timing
    from .thermal import write_thermal

    files = [f"points/{spec.file}" for spec in specs]
    out = prepare_folder(
        out, "map", cfg, overwrite=overwrite, source=source, settings=settings, files=files
    )
    points_dir = out / "points"
    points_dir.mkdir(exist_ok=True)
    lock = lock_folder(out)
    try:
        # the quasi-static estimate of every point (milliseconds each), before any run
        torques = steady_rolling_torques(cfg, axes)
        estimates = dict(zip((spec.name for spec in specs), torques, strict=True))
        records = run_all(specs, points_dir, progress=progress, stop_rules=rules, **run)
        rows = []
        for spec in specs:
            ds = open_run(points_dir / spec.file)
            rec, rule = records[spec.name], rules[spec.name]
            rows.append(point_row(spec, ds, rec, rule, estimates[spec.name]))
        frame = pd.DataFrame(rows)
        frame.to_csv(out / "map.csv", index=False)
        frame.to_parquet(out / "map.parquet", engine="pyarrow", index=False)
        figures = write_maps(frame, out / "figures", cfg.name)
        thermal, permissible = write_thermal(frame, dissipation, out, cfg.name, figures)
        record_files(out, figures)  # what --overwrite may remove
        workers = run["workers"] if run["scheduler"] is None else 0
        study_timing = timing(records, clock(), workers)
        page = build_map_page(
            frame,
            figures,
            title=f"Operating map of {cfg.name}",
            config=cfg,
            thermal=thermal,
            permissible=permissible,
            dissipation=dissipation,
            timing=study_timing,
        )
        write_page(out / "report.html", page)
    finally:
        lock.unlink(missing_ok=True)
    return MapStudy(out, frame, figures, study_timing, thermal, permissible)


def value_ok(v: Any) -> bool:
    return isinstance(v, int | float) and not isinstance(v, bool) and math.isfinite(v) and v > 0


def _final(value) -> float:
    from ..config import TimeTable

    return value.final if isinstance(value, TimeTable) else float(value)


#: Point statuses of the map table.
STEADY, NOT_STEADY = "steady", "not steady"


def point_row(spec: RunSpec, ds, rec: dict, rule: SteadyRule, estimate: float = math.nan) -> dict:
    """One row of the map table: the point's values, its status (steady; not steady at
    its maximum time; not finished, with the time reached; failed), the time it became
    steady, its outputs over the last window, the quasi-static ``estimate`` (the friction
    torque of steady rolling, :mod:`.estimates`) and its wall time."""
    row = {
        "point": spec.name,
        **spec.meta,
        "status": rec["status"],
        "note": rec.get("note", ""),
        "steady at [s]": math.nan,
        "window [s]": rule.window,
        "reached [s]": rec.get("reached [s]", math.nan),
        "torque [N*m]": math.nan,
        STEADY_ROLLING: estimate,
        TORQUE_RATIO: math.nan,
        "speed loss [1]": math.nan,
        "max flange force [N]": math.nan,
        **dict.fromkeys((*LAMBDAS, VIBRATION), math.nan),
        "wall [s]": rec.get("wall [s]", math.nan),
        "file": rec.get("file", ""),
    }
    if ds is None:
        return row
    _, t_k, _ = rule.verdict(ds)
    state = inspect_run(spec, dict(ds.attrs))
    if state == FINISHED and ds.attrs.get("study_done"):
        row["status"], row["steady at [s]"] = STEADY, t_k
    elif state == FINISHED:
        row["status"] = NOT_STEADY
        row["note"] = rule.unmet(spec.t_end)
    if t_k - rule.window >= rule.settle - 1e-12:  # a whole window after the ramps
        row.update(window_outputs(ds, t_k - rule.window, t_k, rule.factor))
        row[TORQUE_RATIO] = row["torque [N*m]"] / estimate if estimate > 0 else math.nan
    forced = str(ds.attrs.get("forced", ""))
    if forced:  # run past the point law's load check
        row["note"] = f"{row['note']}; {forced}" if row["note"] else forced
    return row


__all__ = [
    "MapStudy",
    "equilibrium_refusal",
    "operating_map",
    "parse_range",
    "point_row",
    "record",
]
