"""Quasi-static analysis: the equilibrium of the inner ring and the rollers under radial
load, axial load, tilting moment or a prescribed misalignment, at rest or at a speed, with
the dynamic model's contact laws (race slices, semi-analytical roller end / flange
detection); the bearing's 5x5 stiffness there; and the rating life from the slice loads
(ISO 281, ISO/TS 16281; :mod:`rollerdyn.life`). The solver is the core's
(``crates/rollerdyn-core/src/bearing/quasi_static``); docs/statics.md describes it.

:func:`statics` solves one case, :func:`statics_sweep` a grid of cases (and, with ``design``,
of bearings: configuration values such as the clearance or the oil temperature), each
returned as an :class:`xarray.Dataset` whose variables carry their units in
``attrs["units"]``.
"""

from __future__ import annotations

import itertools
import math
import os
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, replace
from typing import Any, NamedTuple

import numpy as np
import xarray as xr

from . import _core, life
from .config import BearingConfig
from .lubrication import FilmData, film_data, rolling_race_films
from .model import Model
from .names import FLANGES, PAIRINGS, RACES, SEMI_ANALYTICAL
from .provenance import record_attrs
from .simulation import as_config, model_parameters
from .units import QuantityError, family, parse_quantity

__all__ = [
    "STATIC_FIELDS",
    "StaticCase",
    "StaticsError",
    "StaticsInterrupted",
    "design_configs",
    "parse_range",
    "statics",
    "statics_sweep",
]

RING_DOF = ("x", "y", "z", "tilt_y", "tilt_z")
RING_UNITS = ("m", "m", "m", "rad", "rad")
RING_LOAD_UNITS = ("N", "N", "N", "N*m", "N*m")

STATIC_FIELDS: dict[str, tuple[str, str]] = {
    "operating.radial_load": ("radial_load", "force"),
    "operating.axial_load": ("axial_load", "force"),
    "operating.inner_ring_speed": ("speed", "angular velocity"),
    "operating.outer_ring_speed": ("outer_speed", "angular velocity"),
    "operating.carrier_speed": ("carrier_speed", "angular velocity"),
    "inner_ring.misalignment": ("misalignment", "angle"),
    "moment_y": ("moment_y", "torque"),
    "moment_z": ("moment_z", "torque"),
    "roller_set_phase": ("roller_set_phase", "angle"),
}
"""What a statics sweep can vary: the load case (path -> (case field, unit family)). Other
configuration values change the model; sweep them with ``rollerdyn sweep``."""

#: The loads of a load case, with the SI unit each is written in, that a configuration is
#: validated with (:func:`case_config_values`): the rules across sections that a load case
#: can break are the flanges' (an axial load needs a flange to carry it). The speeds and
#: the misalignment stay the file's: a case at rest would ask the file for an end time.
CASE_CONFIG_UNITS = {"operating.radial_load": "N", "operating.axial_load": "N"}


def case_config_values(grid: Mapping[str, Sequence[float]]) -> dict[str, float]:
    """The loads [N] of a load-case ``grid`` that a configuration is validated with, the
    largest in magnitude of each (the most demanding), so that a bearing of type NU swept
    at no axial load is not refused for its file's axial load."""
    return {
        path: float(max(values, key=abs))
        for path, values in grid.items()
        if path in CASE_CONFIG_UNITS and len(values)
    }


DEFAULT_CONTAMINATION = 0.5
"""ISO 281 contamination factor e_C by default: "normal cleanliness" (ISO 281:2007, table 15,
0.6 ... 0.5 for D_pw < 100 mm)."""


class StaticsError(ValueError):
    """A load case without equilibrium, or a bad statics option: the message names it."""


class StaticsInterrupted(KeyboardInterrupt):
    """A sweep stopped by Ctrl-C: a :class:`KeyboardInterrupt` that carries the cases solved
    until then (:attr:`dataset`, None where none was; its ``attrs["interrupted"]`` says how
    many of how many)."""

    def __init__(self, message: str, dataset: xr.Dataset | None):
        super().__init__(message)
        self.dataset = dataset


class _Stopped(KeyboardInterrupt):
    """Ctrl-C within :func:`_solve`, with the results of the cases solved before it."""

    def __init__(self, results: list[dict | str]):
        super().__init__("interrupted")
        self.results = results


@dataclass(frozen=True)
class StaticCase:
    """One load case (SI): loads on the inner ring (radial along -y, axial along +x), the
    tilting moment about y and z, the inner ring speed, the ring's misalignment about z
    (None: the ring's tilt is free and found from the moment), the roller set's phase
    [rad]: its turn from the place with roller 0 under the load (the ring's equilibrium
    repeats every roller pitch, 2 pi / Z: the varying compliance, docs/statics.md), the
    outer ring's speed, and a planet carrier's speed (the rings' speeds relative to it)."""

    radial_load: float
    axial_load: float
    speed: float
    misalignment: float | None
    moment_y: float = 0.0
    moment_z: float = 0.0
    roller_set_phase: float = 0.0
    outer_speed: float = 0.0
    carrier_speed: float = 0.0

    @property
    def relative_speed(self) -> float:
        """The inner ring's speed relative to the outer ring [rad/s]: what sets the
        rolling speeds, the friction torque of a friction power and the rating life's
        revolutions."""
        return self.speed - self.outer_speed

    def core(self) -> tuple:
        tilt = None if self.misalignment is None else (0.0, self.misalignment)
        return (
            self.radial_load,
            self.axial_load,
            self.moment_y,
            self.moment_z,
            self.speed,
            tilt,
            self.roller_set_phase,
            self.outer_speed,
            self.carrier_speed,
        )


def config_case(cfg: BearingConfig) -> StaticCase:
    """The case of a configuration: its loads and speed after the ramps, its misalignment
    (free tilt when ``inner_ring.tilt = "free"``)."""
    op = cfg.operating
    late = math.inf
    return StaticCase(
        radial_load=op.radial_load_at(late),
        axial_load=op.axial_load_at(late),
        speed=op.inner_ring_speed_at(late),
        misalignment=None if cfg.inner_ring.tilt == "free" else cfg.inner_ring.misalignment,
        outer_speed=op.outer_ring_speed_at(late),
        carrier_speed=op.carrier_speed_at(late),
    )


def _core_model(cfg: BearingConfig) -> _core.Model:
    """The core model of the quasi-static analysis. Its normal forces use no traction, so
    the traction's untabulated form stands in for the table, which takes 1.3-1.5 s to
    build (the results are the same bit for bit: tests/test_statics.py)."""
    traction = Model(cfg).traction_model(tabulated=False)
    return _core.Model(model_parameters(cfg, SEMI_ANALYTICAL), traction)


def _solve(
    cfg: BearingConfig,
    cases: Sequence[StaticCase],
    stiffness: bool,
    progress: Callable[[int, int], None] | None = None,
) -> list[dict | str]:
    model = _core_model(cfg)
    out: list[dict | str] = []
    chunk = 50
    try:
        for start in range(0, len(cases), chunk):
            part = [c.core() for c in cases[start : start + chunk]]
            out.extend(_core.statics(model, part, chain=True, stiffness=stiffness))
            if progress is not None:
                progress(len(out), len(cases))
    except KeyboardInterrupt:
        raise _Stopped(out) from None
    return out


def statics(
    config: BearingConfig | str | os.PathLike,
    *,
    radial_load: float | None = None,
    axial_load: float | None = None,
    speed: float | None = None,
    misalignment: float | None = None,
    moment: tuple[float, float] | None = None,
    roller_set_phase: float | None = None,
    contamination: float = DEFAULT_CONTAMINATION,
    outer_speed: float | None = None,
    carrier_speed: float | None = None,
) -> xr.Dataset:
    """The equilibrium of one load case (SI values; None: the configuration's, after its
    ramps). A ``moment`` (N*m about y and z) frees the ring's tilt; a ``misalignment`` (rad)
    prescribes it; ``roller_set_phase`` (rad, default 0: roller 0 under the load) turns the
    roller set. Raises :class:`StaticsError` when the bearing has no equilibrium for it."""
    cfg = as_config(config)
    given = dict(
        radial_load=radial_load,
        axial_load=axial_load,
        speed=speed,
        misalignment=misalignment,
        roller_set_phase=roller_set_phase,
        outer_speed=outer_speed,
        carrier_speed=carrier_speed,
    )
    case = _case_with(config_case(cfg), moment=moment, **given)
    for path, (field, _) in STATIC_FIELDS.items():
        if given.get(field) is not None:
            check_range(cfg, path, "", [getattr(case, field)], label=f"{field} = {given[field]!r}")
    (result,) = _solve(cfg, [case], stiffness=True)
    if isinstance(result, str):
        raise StaticsError(_no_equilibrium_hint(cfg, case, result))
    ds = _case_dataset(cfg, _ratings(cfg), case, result, contamination)
    ds.attrs.update(record_attrs(cfg))
    return ds


#: The remedies the core appends to its "no quasi-static equilibrium" message, each from
#: where it begins (``bearing/quasi_static/solver.rs``): the prescribed misalignment, the
#: point end-flange law with the ring's tilt free, and with an axial load.
_CORE_HINTS = {
    "misalignment": "; the misalignment is applied whole at every load level",
    "free tilt": "; with the ring's tilt free, the point law's flange contact jumps",
    "axial load": "; where the axial load tips the rollers onto their end faces",
}
#: Loads up to this multiple of the solver's force tolerance are within its reach of 0 N:
#: B1 without gravity finds no equilibrium at 1e-6 ... 1e-5 N of radial load (tolerance
#: 1e-6 N), and finds one at 1e-4 N and above (and at 1e-7 N).
_TINY_LOAD = 100.0


def _no_equilibrium_hint(cfg: BearingConfig, case: StaticCase, message: str) -> str:
    """The core's "no quasi-static equilibrium" ``message`` for ``case`` with the remedy
    that fits it: with one slice per roller (``geometry.roller.slices = 1``) and something
    that tilts the rollers (an axial load or the ring's weight along the axis, a
    misalignment, a tilting moment), the slices, whatever the flange law; without an axial
    load along the axis, not the point law's tipping on the flanges, and for a load within
    :data:`_TINY_LOAD` times the solver's tolerance, that load."""
    import re

    if "no quasi-static equilibrium" not in message:
        return message
    weight = cfg.inner_ring.mass * np.asarray(cfg.operating.gravity)
    along_axis = case.axial_load + weight[0]
    tilted = case.misalignment not in (None, 0.0) or case.moment_y or case.moment_z

    def without(*hints: str) -> str:
        starts = [message.find(_CORE_HINTS[h]) for h in hints if _CORE_HINTS[h] in message]
        return message[: min(starts)] if starts else message

    if cfg.geometry.roller.slices == 1 and (along_axis != 0.0 or tilted):
        from .notes import ONE_SLICE

        return without(*_CORE_HINTS) + "; " + ONE_SLICE
    if along_axis != 0.0 or tilted or _CORE_HINTS["axial load"] not in message:
        return message
    text = without("axial load")
    tolerance = re.search(r"tolerance,? ([0-9.]+e[-+]?[0-9]+) N\b", message)
    load = carried_radial_load(cfg, case)
    if tolerance is not None and load <= _TINY_LOAD * float(tolerance.group(1)):
        text += (
            f"; the load on the ring ({load:.3g} N with its weight) is within "
            f"{_TINY_LOAD:g} times the solver's force tolerance ({tolerance.group(1)} N), "
            "too small to resolve: give 0 N or a larger load"
        )
    return text


def _number(name: str, value: Any) -> float:
    """``value`` as a float, or :class:`StaticsError` naming ``name`` (SI numbers only)."""
    if isinstance(value, bool) or not isinstance(value, int | float | np.integer | np.floating):
        raise StaticsError(
            f"{name} = {value!r}: must be a number in SI units (N, rad/s, rad, N*m); units "
            "are read by the command line's --set"
        )
    return float(value)


def _case_with(case: StaticCase, *, moment=None, **values) -> StaticCase:
    changes = {k: _number(k, v) for k, v in values.items() if v is not None}
    for name, value in changes.items():
        if not math.isfinite(value):
            raise StaticsError(f"{name} = {value}: must be finite")
    case = replace(case, **changes)
    if moment is not None:
        pair = list(moment) if isinstance(moment, list | tuple | np.ndarray) else []
        if len(pair) != 2:
            raise StaticsError(f"moment = {moment!r}: must be a pair (about y, about z) in N*m")
        my, mz = (_number("moment", v) for v in pair)
        if not (math.isfinite(my) and math.isfinite(mz)):
            raise StaticsError(f"moment = ({my}, {mz}) N*m: must be finite")
        case = replace(case, moment_y=my, moment_z=mz)
        if (my or mz) and "misalignment" in changes:
            raise StaticsError(
                f"moment = ({my:g}, {mz:g}) N*m with misalignment = {changes['misalignment']:g} "
                "rad: a prescribed misalignment holds the ring's tilt, so a tilting moment "
                "would act on nothing; give one or the other"
            )
        if my or mz:
            case = replace(case, misalignment=None)
    return case


def _check_path(path: str) -> None:
    """Refuses a path a statics sweep cannot vary."""
    if path not in STATIC_FIELDS:
        raise StaticsError(
            f"--set {path}: the grid holds the load case only ({', '.join(STATIC_FIELDS)}); "
            "give the bearing's other values as the design (statics_sweep(design=...))"
        )


def check_range(
    cfg: BearingConfig, path: str, text: str, values: Sequence[float], label: str = ""
) -> None:
    """The configuration's rules for the load case's fields, on the values of a sweep
    option (``--set path=text``): loads up to the configuration's load limit (radial ones
    not negative; axial ones only where the bearing has the flanges that carry them),
    speeds up to its pitch-circle speed, misalignments within 1 deg, the roller set's
    phase within one turn. Raises :class:`StaticsError` naming the option (or ``label``),
    the value and the rule."""
    from .config.base import MAX_MISALIGNMENT_DEG, MAX_PITCH_SPEED
    from .config.schema import axial_load_flange_rule

    limit = cfg.load_limit
    field = STATIC_FIELDS[path][0]
    for v in values:
        if field == "radial_load" and not 0.0 <= v <= limit:
            rule = f"must lie in [0, {limit:.6g}] N (the configuration's load limit)"
        elif field == "axial_load" and not abs(v) <= limit:
            rule = f"must be at most {limit:.6g} N in size (the configuration's load limit)"
        elif field == "axial_load" and (flanges := axial_load_flange_rule(cfg, v)) is not None:
            rule = flanges
        elif (
            field in ("speed", "outer_speed", "carrier_speed")
            and not abs(v) * cfg.speed_radius(path.split(".")[-1]) <= MAX_PITCH_SPEED
        ):
            rule = f"must give a pitch-circle speed of at most {MAX_PITCH_SPEED:g} m/s"
        elif field == "misalignment" and not abs(v) <= math.radians(MAX_MISALIGNMENT_DEG):
            rule = f"must lie within +-{MAX_MISALIGNMENT_DEG:g} deg, as inner_ring.misalignment"
        elif field == "roller_set_phase" and not abs(v) <= 2.0 * math.pi:
            rule = "must lie within one turn of the roller set, +-360 deg"
        else:
            continue
        raise StaticsError(f"{label or f'--set {path}={text}'}: {v:.6g} (SI) {rule}")


#: The most cases one statics sweep solves (1.1 ms each in the core, 2.6 ms with the
#: datasets, `rollerdyn bench statics`: 100 000 take about four minutes).
MAX_STATIC_CASES = 100_000


def check_grid_size(counts: Mapping[str, int]) -> None:
    """Refuses a sweep whose paths' value ``counts`` make more than :data:`MAX_STATIC_CASES`
    cases (their product), naming the counts."""
    total = math.prod(counts.values())
    if total > MAX_STATIC_CASES:
        shown = " x ".join(f"{n} ({p})" for p, n in counts.items())
        raise StaticsError(
            f"statics sweep: {shown} = {total} cases, more than {MAX_STATIC_CASES} (a few "
            "ms each); sweep fewer values"
        )


def _unquoted(text: str) -> str:
    """``text`` without one pair of quotes around it (``"500 rpm"`` as the configuration
    file and ``rollerdyn run --set`` write a quantity), and without surrounding blanks."""
    text = text.strip()
    quote = text[:1]
    if len(text) >= 2 and quote in ("'", '"') and text[-1] == quote and quote not in text[1:-1]:
        return text[1:-1].strip()
    return text


#: The unit families whose bare numbers ``--set`` refuses, with an example of each.
BARE_REFUSED = {"angular velocity": '"3000 rpm"', "angle": '"0.05 deg"'}


def parse_range(path: str, text: str) -> list[float]:
    """The SI values of a sweep option: ``"a:b:n"`` (n values from a to b) or a comma list,
    each value a quantity with its unit (``"500 rpm"``, quoted or not) or a bare number in
    the field's SI unit (N, N*m). A bare speed or angle other than 0 is refused: rad/s and
    rad are not what a bearing's speed and tilt are written in (a bare 1000 meant
    9549 rpm), and the operating maps read a bare ``--speed`` as rpm."""
    _check_path(path)
    family = STATIC_FIELDS[path][1]

    def value(item: str) -> float:
        item = _unquoted(item)
        try:
            number = float(item)
        except ValueError:
            pass
        else:
            if not math.isfinite(number):
                raise StaticsError(f"--set {path}={text}: {item.strip()} is not finite")
            if number != 0.0 and family in BARE_REFUSED:
                raise StaticsError(
                    f"--set {path}={text}: {item.strip()} has no unit, and a bare {family} is "
                    f"ambiguous; give its unit, e.g. {BARE_REFUSED[family]}"
                )
            return number
        if not family:
            raise StaticsError(f"--set {path}={text}: {item.strip()} is not a number (N*m)")
        try:
            return parse_quantity(item.strip(), family)
        except QuantityError as err:
            raise StaticsError(f"--set {path}={text}: {err}") from None

    parts = _unquoted(text).split(":")
    if len(parts) == 3:
        a, b = value(parts[0]), value(parts[1])
        try:
            n = int(_unquoted(parts[2]))
        except ValueError:
            raise StaticsError(
                f"--set {path}={text}: the count after the second ':' must be an integer"
            ) from None
        if not 1 <= n <= 100_000 or (n == 1 and a != b):
            raise StaticsError(
                f"--set {path}={text}: the count must be 2 ... 100000 (or 1 with START = STOP), "
                f"not {n}"
            )
        if n > 1 and a == b:  # the same case n times
            raise StaticsError(f"--set {path}={text}: START = STOP with {n} values")
        return list(np.linspace(a, b, n))
    if len(parts) != 1:
        raise StaticsError(f"--set {path}={text}: expected START:STOP:COUNT or a comma list")
    items = _unquoted(text).split(",")
    if not text.strip():
        raise StaticsError(f"--set {path}={text}: no value given")
    if not all(v.strip() for v in items):
        raise StaticsError(f"--set {path}={text}: an empty value (two commas, or one at an end)")
    values = [value(v) for v in items]
    if len(set(values)) != len(values):  # the same case solved twice (the maps refuse it)
        raise StaticsError(f"--set {path}={text}: a value is given twice")
    return values


#: The most configurations one design sweep builds (``statics_sweep(design=...)``): each
#: is parsed and gets its own core model (about 0.1 s each).
MAX_DESIGNS = 1_000


def statics_sweep(
    config: BearingConfig | str | os.PathLike,
    grid: Mapping[str, Sequence[float]],
    *,
    design: Mapping[str, Sequence[Any]] | None = None,
    contamination: float = DEFAULT_CONTAMINATION,
    stiffness: bool = True,
    progress: Callable[[int, int], None] | None = None,
) -> xr.Dataset:
    """The equilibria of the cartesian product of ``grid`` (path -> SI values, paths of
    :data:`STATIC_FIELDS`; the last varies fastest), along a ``case`` dimension with one
    coordinate per swept path. A case without equilibrium keeps NaN values and its message in
    ``error``; the others are solved, each from its neighbour's solution. At most
    :data:`MAX_STATIC_CASES` cases, and ``stiffness`` is a boolean.

    ``design`` varies the bearing itself: configuration paths outside
    :data:`STATIC_FIELDS` (``geometry.diametral_clearance``, ``operating.temperature``,
    ``surfaces.flange_law``, ...) -> values written as in the configuration file (``"10
    um"``; SI numbers when ``config`` is a :class:`BearingConfig`), as ``rollerdyn sweep
    --set`` takes them. Each combination is validated as a configuration (a bad one raises
    :class:`StaticsError` listing every problem), gets its own model, ratings and load
    case, and is solved over ``grid``; the design paths vary slower than the load case's.
    A coordinate per design path holds its SI value. The roller count and the slices
    cannot be swept (they shape every case's arrays): run such bearings apart."""
    cfg = as_config(config)
    if not isinstance(grid, Mapping):
        raise StaticsError(
            f"grid = {grid!r}: must be a mapping of paths to SI values, e.g. "
            '{"operating.radial_load": [1000.0, 5000.0]}'
        )
    if not isinstance(stiffness, bool):
        raise StaticsError(f"stiffness = {stiffness!r}: must be True or False")
    if progress is not None and not callable(progress):
        raise StaticsError(
            f"progress = {progress!r}: must be a function progress(done, total) (or None)"
        )
    if design is not None and not isinstance(design, Mapping):
        raise StaticsError(
            f"design = {design!r}: must be a mapping of configuration paths to lists of "
            'values, e.g. {"geometry.diametral_clearance": ["10 um", "20 um"]} (or None)'
        )
    design = dict(design or {})
    check_grid_size(
        {p: len(v) if hasattr(v, "__len__") else 1 for p, v in {**design, **grid}.items()}
    )
    for path, values in grid.items():
        _check_path(path)
        if isinstance(values, str | bytes) or not isinstance(values, Sequence | np.ndarray):
            raise StaticsError(f"grid[{path!r}] = {values!r}: must be a list of SI numbers")
        numbers = [_number(f"grid[{path!r}]", v) for v in values]
        if STATIC_FIELDS[path][1] != "torque":
            check_range(cfg, path, "", numbers, label=f"grid[{path!r}]")
    designs = design_configs(config if design else cfg, design, case_config_values(grid))
    paths = list(grid)
    combos = list(itertools.product(*(grid[p] for p in paths)))
    if not combos:
        raise StaticsError("statics sweep: the grid is empty")
    total = len(designs) * len(combos)
    # (design values, case, variables or None, message): one tuple per solved case, each
    # appended whole, so that Ctrl-C at any moment leaves the list consistent
    solved: list[tuple[dict[str, Any], StaticCase, dict[str, _Var] | None, str]] = []
    stopped = False
    try:
        for values, design_cfg in designs:
            base = config_case(design_cfg)
            own = [_combined_case(base, paths, combo) for combo in combos]
            done = len(solved)

            def step(n: int, _: int, done: int = done) -> None:
                if progress is not None:
                    progress(done + n, total)

            try:
                results = _solve(design_cfg, own, stiffness=stiffness, progress=step)
            except _Stopped as stop:
                results, stopped = stop.results, True
            ratings = _ratings(design_cfg)
            for case, result in zip(own, results, strict=False):
                if isinstance(result, str):
                    message = _no_equilibrium_hint(design_cfg, case, result)
                    solved.append((values, case, None, message))
                else:
                    part = _case_variables(design_cfg, ratings, case, result, contamination)
                    solved.append((values, case, part, ""))
            if stopped:
                break
    except KeyboardInterrupt:
        stopped = True
    return _finished(cfg, design, paths, solved, total, stopped)


def _finished(cfg, design, paths, solved, total: int, stopped: bool) -> xr.Dataset:
    """The dataset of a sweep's ``solved`` cases; :class:`StaticsInterrupted` carrying it
    when the sweep was ``stopped`` before its ``total`` cases."""
    parts = [part for _, _, part, _ in solved]
    errors = [message for _, _, _, message in solved]
    if all(part is None for part in parts):
        if stopped:
            raise StaticsInterrupted(f"interrupted after {len(solved)} of {total} cases", None)
        raise StaticsError(f"no case of the sweep has an equilibrium; the first: {errors[0]}")
    cases = [(values, case) for values, case, _, _ in solved]
    ds = _sweep_dataset(cfg, design, paths, cases, parts, errors)
    if stopped:
        ds.attrs["interrupted"] = f"{len(solved)} of {total} cases solved"
        raise StaticsInterrupted(f"interrupted after {len(solved)} of {total} cases", ds)
    return ds


def _sweep_dataset(
    cfg: BearingConfig,
    design: Mapping[str, Sequence[Any]],
    paths: Sequence[str],
    cases: list[tuple[dict[str, Any], StaticCase]],
    parts: list[dict[str, _Var] | None],
    errors: list[str],
) -> xr.Dataset:
    """The dataset of a sweep's ``cases`` (design values, load case), with their variables
    (``parts``, None where no equilibrium) and messages, a coordinate per swept path."""
    template = next(p for p in parts if p is not None)
    ds = _dataset(cfg, _stacked(template, parts), case_dim=True)
    ds = ds.assign_coords(case=np.arange(len(cases)))
    swept = []
    for path in design:
        name = _coordinate_name(path, ds)
        column = _column([v[path] for v, _ in cases])
        unit = _si_unit_of(path)
        attrs = {"long_name": path, **({"units": unit} if unit else {})}
        ds = ds.assign_coords({name: ("case", column, attrs)})
        swept.append(name)
    for path in paths:
        name = STATIC_FIELDS[path][0]
        column = [
            getattr(c, name) if name != "misalignment" else (c.misalignment or 0.0)
            for _, c in cases
        ]
        unit = family(STATIC_FIELDS[path][1]).si_unit
        coordinate = ("case", np.asarray(column, float), {"units": unit, "long_name": path})
        ds = ds.assign_coords({path.split(".")[-1]: coordinate})
        swept.append(path.split(".")[-1])
    ds["error"] = ("case", np.asarray(errors, dtype=object))
    ds.attrs.update(record_attrs(cfg))
    ds.attrs["swept"] = ",".join(swept)
    ds.attrs["failed_cases"] = sum(1 for e in errors if e)
    return ds


def _combined_case(base: StaticCase, paths: Sequence[str], combo: Sequence[float]) -> StaticCase:
    """``base`` with the load-case values ``combo`` of ``paths`` (:data:`STATIC_FIELDS`)."""
    fields = {STATIC_FIELDS[p][0]: v for p, v in zip(paths, combo, strict=True)}
    moment = None
    if "moment_y" in fields or "moment_z" in fields:
        moment = (fields.pop("moment_y", 0.0), fields.pop("moment_z", 0.0))
    return _case_with(base, moment=moment, **fields)


#: The parts of the friction power of steady rolling (``friction_power``), as the core gives
#: them.
FRICTION_PARTS = ("flanges", "inner race", "outer race", "roller pairs", "drag")

#: Design paths a statics sweep cannot vary: they set the size of every case's arrays.
_SHAPING_PATHS = ("geometry.roller_count", "geometry.roller.slices")


def design_configs(
    config: Any, design: Mapping[str, Sequence[Any]], case: Mapping[str, float] | None = None
) -> list[tuple[dict[str, Any], BearingConfig]]:
    """(SI values of the design paths, configuration) of every combination of ``design``,
    each validated with the load case's values ``case`` (:func:`case_config_values`); the
    configuration itself when there is none."""
    from .sweep import SweepError, parsed_grid

    if not design:
        return [({}, as_config(config))]
    for path in design:
        if path in STATIC_FIELDS:
            raise StaticsError(
                f"design path {path}: a load case's value; give it in the grid (SI numbers)"
            )
        if path in _SHAPING_PATHS:
            raise StaticsError(
                f"--set {path}: a statics sweep cannot vary it (every case of one sweep has "
                "the same rollers and slices); run each value with its own 'rollerdyn "
                f"statics --set {path}=VALUE'"
            )
    count = math.prod(len(v) if hasattr(v, "__len__") else 1 for v in design.values())
    if count > MAX_DESIGNS:
        raise StaticsError(
            f"statics sweep: {count} bearing designs, more than {MAX_DESIGNS} (each builds "
            "its own model); sweep fewer values of the configuration's paths"
        )
    si = isinstance(config, BearingConfig)
    extra = {
        p: [v if si else f"{v!r} {CASE_CONFIG_UNITS[p]}"]
        for p, v in (case or {}).items()
        if p not in design
    }
    try:
        points = parsed_grid(config, {**design, **extra})
    except SweepError as err:
        raise StaticsError(str(err).replace("no run was started", "nothing was solved")) from None
    return [
        ({p: v for p, v in point.si_values.items() if p not in extra}, cfg) for point, cfg in points
    ]


def _column(values: list[Any]) -> np.ndarray:
    """A design coordinate's values: floats where every value is a number, else text."""
    if all(isinstance(v, int | float) and not isinstance(v, bool) for v in values):
        return np.asarray(values, float)
    return np.asarray([str(v) for v in values], dtype=object)


def _coordinate_name(path: str, ds: xr.Dataset) -> str:
    """The coordinate of a design path: its last part, or the whole path with ``_`` for
    ``.`` where that name is taken (``geometry.flange.height`` -> ``height``)."""
    name = path.split(".")[-1]
    loads = {p.split(".")[-1] for p in STATIC_FIELDS}
    taken = name in ds.variables or name in ds.dims or name in loads
    return path.replace(".", "_") if taken else name


def _si_unit_of(path: str) -> str:
    """The SI unit of a configuration path's values ("" for numbers without one or text)."""
    from .sweep import _si_unit

    unit = _si_unit(path)
    return "" if unit in (None, "1") else unit


# --------------------------------------------------------------------------- the dataset


class _Var(NamedTuple):
    """One variable of a case: its dims, data, unit and description."""

    dims: tuple
    data: Any
    units: str
    description: str


def _var(data, dims, units: str, description: str) -> _Var:
    return _Var(tuple(dims), data, units, description)


#: The coordinates of a case's dimensions, but for roller and slice (from the configuration).
_COORDS = {
    "flange": list(FLANGES),
    "friction_part": list(FRICTION_PARTS),
    "ring_dof": list(RING_DOF),
    "ring_load_dof": ["force_x", "force_y", "force_z", "moment_y", "moment_z"],
}


def _dataset(cfg: BearingConfig, variables: dict[str, _Var], case_dim: bool = False) -> xr.Dataset:
    """The dataset of ``variables``; with ``case_dim``, each one's data has a leading case
    axis."""
    prefix = ("case",) if case_dim else ()
    return xr.Dataset(
        {
            name: xr.Variable(
                prefix + v.dims, v.data, attrs={"units": v.units, "description": v.description}
            )
            for name, v in variables.items()
        },
        coords={
            "roller": np.arange(cfg.geometry.roller_count),
            "slice": np.arange(cfg.geometry.roller.slices),
            **_COORDS,
        },
    )


def _case_dataset(
    cfg: BearingConfig, ratings: _Ratings, case: StaticCase, r: dict, contamination: float
) -> xr.Dataset:
    """The dataset of one solved case (result ``r`` of the core)."""
    return _dataset(cfg, _case_variables(cfg, ratings, case, r, contamination))


def _case_variables(
    cfg: BearingConfig, ratings: _Ratings, case: StaticCase, r: dict, contamination: float
) -> dict[str, _Var]:
    """The variables of one solved case (result ``r`` of the core)."""
    z, ns = cfg.geometry.roller_count, cfg.geometry.roller.slices
    slices = {
        k: np.asarray(r[k]).reshape(z, ns)
        for k in ("inner_slices", "outer_slices", "inner_pressures", "outer_pressures")
    }
    flange = {
        k: np.asarray(r[k]).reshape(z, 4)
        for k in ("flange_force", "flange_pressure", "flange_penetration", "flange_pairing")
    }
    height = _flange_contact_height(cfg, np.asarray(r["flange_contact_radius"]).reshape(z, 4))
    forces = flange["flange_force"]
    heaviest = int(np.argmax(forces)) if forces.max() > 0.0 else None
    race_peak = float(max(slices["inner_pressures"].max(), slices["outer_pressures"].max()))
    inner_load = slices["inner_slices"].sum(axis=1)
    outer_load = slices["outer_slices"].sum(axis=1)
    ring = np.asarray(r["ring"])
    pairing = np.where(
        flange["flange_pairing"] >= 0,
        np.asarray(PAIRINGS + ("",), dtype=object)[flange["flange_pairing"].astype(int)],
        "",
    )
    friction_note = _point_law_friction_note(
        cfg, case, str(pairing.flat[heaviest]) if heaviest is not None else ""
    )
    friction_caveat = "" if friction_note else _slow_sliding_caveat(cfg, case, forces, r)
    if friction_note:  # no estimate: the steady rolling's outputs are NaN
        r = {
            **r,
            **{
                k: np.full(np.shape(r[k]), np.nan)
                for k in (
                    "friction_power",
                    "roller_slip",
                    "roller_skew",
                    "flange_offsets",
                    "flange_sliding_speeds",
                )
            },
        }
    data = {
        "roller_azimuth": _var(
            np.degrees(r["roller_azimuth"]), ("roller",), "deg", "roller azimuth from +y towards +z"
        ),
        "roller_radial_offset": _var(
            r["roller_radial"], ("roller",), "m", "roller centre from the pitch circle, outwards"
        ),
        "roller_axial_position": _var(
            r["roller_axial"], ("roller",), "m", "roller centre along the bearing axis"
        ),
        "roller_tilt": _var(
            r["roller_tilt"], ("roller",), "rad", "roller tilt about its tangential axis"
        ),
        "slice_position": _var(
            np.asarray(cfg.geometry.roller.slice_centres),
            ("slice",),
            "m",
            "slice centre along the roller axis from the roller's middle",
        ),
        "inner_slice_load": _var(
            slices["inner_slices"],
            ("roller", "slice"),
            "N",
            "slice load at the inner race (eq. 11)",
        ),
        "outer_slice_load": _var(
            slices["outer_slices"],
            ("roller", "slice"),
            "N",
            "slice load at the outer race (eq. 11)",
        ),
        "inner_slice_pressure": _var(
            slices["inner_pressures"],
            ("roller", "slice"),
            "Pa",
            "Hertz pressure p0 of the slice at the inner race (eqs. 17, 18)",
        ),
        "outer_slice_pressure": _var(
            slices["outer_pressures"],
            ("roller", "slice"),
            "Pa",
            "Hertz pressure p0 of the slice at the outer race (eqs. 17, 18)",
        ),
        "inner_race_load": _var(
            inner_load, ("roller",), "N", "roller load at the inner race (sum of slices)"
        ),
        "outer_race_load": _var(
            outer_load, ("roller",), "N", "roller load at the outer race (sum of slices)"
        ),
        "flange_force": _var(
            flange["flange_force"],
            ("roller", "flange"),
            "N",
            "roller end / flange normal force (Hertz, eqs. 5-8)",
        ),
        "flange_pressure": _var(
            flange["flange_pressure"],
            ("roller", "flange"),
            "Pa",
            "Hertz pressure p0 of the roller end / flange contact (its force on the exact "
            "elliptic-integral ellipse; with the distributed law the larger of that and its "
            "overlap's ellipse)",
        ),
        "flange_penetration": _var(
            flange["flange_penetration"],
            ("roller", "flange"),
            "m",
            "roller end / flange penetration (negative: gap; NaN: none found)",
        ),
        "flange_contact_height": _var(
            height,
            ("roller", "flange"),
            "m",
            "where the roller end presses the flange: the height of the force's point above "
            "the raceway, along the ring's radius (the flange's own height is "
            "geometry.flange.height; NaN where nothing is carried)",
        ),
        "flange_contact_offset": _var(
            np.asarray(r["flange_offsets"]).reshape(-1, 4),
            ("roller", "flange"),
            "m",
            "where the roller end presses the flange in steady rolling along the orbit: the "
            "contact point's distance from the roller's meridian plane (towards x cross "
            "e_r), off it where the roller skews (roller_skew); NaN where nothing is carried",
        ),
        "flange_sliding_speed": _var(
            np.asarray(r["flange_sliding_speeds"]).reshape(-1, 4),
            ("roller", "flange"),
            "m/s",
            "how fast the roller end slides on the flange in steady rolling, at the point of "
            "its force; NaN where nothing is carried",
        ),
        "flange_pairing": _var(
            pairing.astype(str),
            ("roller", "flange"),
            "",
            "pairing of the loaded roller end / flange contact (paper fig. 1)",
        ),
        "ring_displacement": _var(
            ring,
            ("ring_dof",),
            "m or rad",
            "inner ring displacement (x, y, z) [m] and tilt (about y, z) [rad]",
        ),
        "ring_reaction": _var(
            np.asarray(r["ring_load"])[[0, 1, 2, 4, 5]],
            ("ring_dof",),
            "N or N*m",
            "sum of the contact forces on the inner ring: minus the load, with a prescribed "
            "tilt the moment that holds it",
        ),
        "max_roller_load": _var(
            float(inner_load.max()), (), "N", "heaviest roller load at the inner race"
        ),
        "max_pressure": _var(
            race_peak,
            (),
            "Pa",
            "largest race contact pressure",
        ),
        "friction_power": _var(
            np.asarray(r["friction_power"]),
            ("friction_part",),
            "W",
            "the power the contacts and the drag take in steady rolling at the equilibrium "
            "(the dynamic model's laws at its positions, the roller set orbiting at the "
            "epicyclic speed, each roller spinning and skewed where its friction moments "
            "balance (roller_slip, roller_skew); the roller-roller contacts where the "
            "roller train presses them (pair_force); docs/statics.md, 'Friction of steady "
            "rolling')",
        ),
        "pair_force": _var(
            np.asarray(r["pair_force"]),
            ("roller",),
            "N",
            "the roller train's force between each roller and the next (roller i and i + 1): "
            "the field (gravity, a planet carrier's) and the drag pushing the rollers along "
            "their orbit against their neighbours, the net push taken by the rollers' races "
            "in proportion to their lighter race load; docs/statics.md, 'The roller train'",
        ),
        "roller_slip": _var(
            np.asarray(r["roller_slip"]),
            ("roller",),
            "1",
            "each roller's slip in steady rolling, 1 - spin / spin of rolling without slip: "
            "negative where the flanges' friction drives it faster, near 1 where an "
            "unloaded roller's films and drag stop it (0 at rest)",
        ),
        "roller_skew": _var(
            np.asarray(r["roller_skew"]),
            ("roller",),
            "rad",
            "each roller's skew in steady rolling (its axis turned about its radial "
            "direction, towards x cross e_r, as a run's skew) where its moments about that "
            "direction balance: the flanges' friction skews the rollers they press "
            "(0 at rest); docs/statics.md, 'The rollers' skew'",
        ),
        "friction_torque": _var(
            _friction_torque(r["friction_power"], case),
            (),
            "N*m",
            "frictional torque of steady rolling: the friction power over the inner ring's "
            "speed relative to the outer ring (NaN at rest, and where the rings turn "
            f"together: the relative speed below {100 * TORQUE_RELATIVE_SPEED:g} % of the faster "
            "ring's speed, where the power is no torque between the rings; and where "
            "friction_note says why there is no estimate)",
        ),
        "friction_note": _var(
            friction_note,
            (),
            "",
            "why the friction of steady rolling (friction_torque, friction_power, roller_slip, "
            "roller_skew, flange_contact_offset) is NaN: the point law's most loaded roller "
            "end lying on its end face; empty where it is estimated",
        ),
        "friction_caveat": _var(
            friction_caveat,
            (),
            "",
            "why the friction of steady rolling may be underestimated, where it is: the "
            "roller ends sliding on the flanges slower than the boundary friction's "
            "smoothing speed (a slowly turning bearing); empty otherwise",
        ),
        "max_flange_force": _var(
            float(flange["flange_force"].max()), (), "N", "largest roller end / flange force"
        ),
        "max_flange_force_height": _var(
            float(height.flat[heaviest]) if heaviest is not None else math.nan,
            (),
            "m",
            "height above the raceway of the largest flange force (flange_contact_height; NaN "
            "without flange force)",
        ),
        "max_flange_force_pairing": _var(
            str(pairing.flat[heaviest]) if heaviest is not None else "",
            (),
            "",
            "pairing of the largest flange force (paper fig. 1; empty without flange force)",
        ),
        "s0_races": _var(
            life.stress_static_safety(race_peak, "line"),
            (),
            "1",
            "static safety by stress at the races, (4 GPa / largest race p0)^2 (ISO 76's "
            "limit; inf unloaded)",
        ),
        "s0_flanges": _var(
            life.stress_static_safety(
                float(np.nan_to_num(flange["flange_pressure"], nan=0.0).max()), "point"
            ),
            (),
            "1",
            "static safety by stress at the flanges, (4 GPa / largest flange p0)^3 (ISO 76's "
            "limit; inf unloaded)",
        ),
        "loaded_rollers": _var(
            _rollers_in_the_load_zone(inner_load, outer_load),
            (),
            "1",
            "rollers in the load zone: pressed between the races, each race's load on them "
            "at least 1 % of the heaviest roller's (not those that rest on the inner ring "
            "by their weight, or press the outer ring only by their centrifugal force)",
        ),
        "load_zone_angle": _var(
            _load_zone_angle(cfg, ring),
            (),
            "deg",
            "load zone half-angle psi_l, cos psi_l = P_d/(2 delta_r) (Harris & Kotzalas, eq. 7.41)",
        ),
        "residual": _var(
            float(r["residual"]),
            (),
            "N",
            "largest unbalanced force left (moments over the roller radius)",
        ),
        "iterations": _var(float(r["iterations"]), (), "1", "Newton iterations"),
    }
    if "stiffness" in r:
        data["stiffness"] = _var(
            np.asarray(r["stiffness"]).reshape(5, 5),
            ("ring_load_dof", "ring_dof"),
            "N/m, N/rad, N*m/m, N*m/rad",
            "bearing stiffness: load on the ring per displacement / tilt, rollers in equilibrium",
        )
    data.update(
        _life_variables(
            cfg, ratings, case, slices["inner_slices"], slices["outer_slices"], contamination
        )
    )
    data.update(_film_variables(cfg, ratings, case, slices))
    data["radial_load_applied"] = _var(
        case.radial_load, (), "N", "radial load on the inner ring, along -y"
    )
    data["axial_load_applied"] = _var(
        case.axial_load, (), "N", "axial load on the inner ring, along +x"
    )
    data["speed_applied"] = _var(case.speed, (), "rad/s", "inner ring speed")
    data["outer_speed_applied"] = _var(case.outer_speed, (), "rad/s", "outer ring speed")
    data["carrier_speed_applied"] = _var(
        case.carrier_speed, (), "rad/s", "planet carrier speed (the rings' relative to it)"
    )
    data["misalignment_applied"] = _var(
        np.nan if case.misalignment is None else case.misalignment,
        (),
        "rad",
        "prescribed tilt about z (NaN: free)",
    )
    data["roller_set_phase_applied"] = _var(
        case.roller_set_phase, (), "rad", "roller set's turn from roller 0 under the load"
    )
    return data


def _stacked(template: dict[str, _Var], parts: list[dict[str, _Var] | None]) -> dict[str, _Var]:
    """The variables of every case along a leading case axis; a case without equilibrium
    (None) is NaN, or an empty text."""
    out = {}
    for name, v in template.items():
        sample = np.asarray(v.data)
        blank = np.full(sample.shape, "" if sample.dtype.kind in "OUS" else np.nan)
        rows = [blank if p is None else np.asarray(p[name].data) for p in parts]
        out[name] = v._replace(data=np.stack(rows))
    return out


#: The least speed of the inner ring relative to the outer ring, as a share of the faster
#: ring's speed, at which the friction power over that relative speed is reported as the
#: frictional torque (NaN below). Where the rings turn together, the contacts and the
#: drag of steady rolling still take power (B1 at its 5 kN / 1 kN: 0.58 W, 3.6 % of the
#: 15.9 W with its outer ring fixed), which no relative speed makes, and the quotient
#: grows as 1 / relative speed: B1 with its outer ring turning slower than the inner
#: ring's 500 rpm by a share f of it gives 0.304 N*m at f = 1, 0.330 at 0.1, 0.372 at
#: 0.05, 0.715 at 0.01, 1.29 at 0.005, 6.4 at 0.001 and 1.1e7 at 1e-9. Below 1 % the
#: quotient is more than twice the torque of the relative motion, no torque between the
#: rings.
TORQUE_RELATIVE_SPEED = 0.01


#: The share of the largest flange force from which a flange contact's sliding speed is
#: judged by :func:`_slow_sliding_caveat`.
_PRESSED_SHARE = 0.01


def _slow_sliding_caveat(cfg: BearingConfig, case: StaticCase, forces, r: dict) -> str:
    """Why the friction of steady rolling is underestimated, or "": the roller ends pressed
    on the flanges (at least :data:`_PRESSED_SHARE` of the largest flange force) slide
    slower than ``surfaces.boundary_friction.smoothing_speed`` v_s, below which the
    boundary friction and the EHL traction are smoothed towards zero (docs/dynamics.md,
    "Creep zone of the EHL traction"). The smoothing keeps the integrator's Jacobian
    finite where a sliding speed changes sign; at steady sliding below v_s it is not the
    Coulomb friction of the contact. B1's most loaded ends slide at about 0.18 (inner
    ring's flange) and 0.14 mm/s (outer's) per rpm: its friction torque is 0.3038 N*m at
    30 rpm (slowest pressed contact 1.9 mm/s), 3 % less at 10 rpm (0.9 mm/s), 64 % less at
    3 rpm."""
    if not _turns_relatively(case) or not forces.max() > 0.0:
        return ""
    sliding = np.asarray(r["flange_sliding_speeds"], dtype=float).reshape(forces.shape)
    pressed = forces >= _PRESSED_SHARE * forces.max()
    slowest = float(np.nanmin(np.where(pressed, sliding, np.inf)))
    v_s = cfg.surfaces.boundary_friction.smoothing_speed
    if not slowest < v_s:
        return ""
    return (
        f"the roller ends slide on the flanges at {1e3 * slowest:.2g} mm/s and up, below "
        f"surfaces.boundary_friction.smoothing_speed ({1e3 * v_s:g} mm/s), where the model "
        "smooths the friction towards zero: the friction torque is "
        'underestimated at this speed (docs/statics.md, "Friction of steady rolling")'
    )


def _turns_relatively(case: StaticCase) -> bool:
    """Whether the rings of ``case`` turn relative to each other: not at rest, and not
    together (the relative speed at least :data:`TORQUE_RELATIVE_SPEED` of the faster
    ring's speed)."""
    relative = abs(case.relative_speed)
    faster = max(abs(case.speed), abs(case.outer_speed))
    return relative > 0.0 and relative >= TORQUE_RELATIVE_SPEED * faster


def _friction_torque(power: Sequence[float], case: StaticCase) -> float:
    """The torque of a friction power [W] at the inner ring's speed relative to the outer
    ring [rad/s]: NaN where the rings do not turn relative to each other
    (:func:`_turns_relatively`)."""
    if not _turns_relatively(case):
        return math.nan
    return float(np.sum(power)) / abs(case.relative_speed)


#: Why the point law gives no friction of steady rolling where its most loaded roller end
#: lies on its end face (pairings of the end sphere, SP-*): past the tilt at which the
#: nearly flat face lies on the flange its point contact jumps across the face and the rim,
#: and the skew balance moves it there (B1 at 5 kN: 0.45-0.56 N*m at 1.7-1.85 kN axially,
#: SP-CO, within 1 % of the distributed law's where compared, then 0.46, 0.17 and 0.14 N*m
#: at 1.9, 1.95 and 2 kN against the distributed law's 0.59 at 2 kN). A dynamic run with
#: the point law is refused there for the same reason (``BearingSystem::check_point_law``).
POINT_LAW_ON_THE_FACE = (
    "the point law's most loaded roller end lies on its end face ({pairing}), where its "
    "point contact jumps across the face: no friction estimate; use surfaces.flange_law = "
    '"distributed" (--set surfaces.flange_law=distributed)'
)


def _point_law_friction_note(cfg: BearingConfig, case: StaticCase, pairing: str) -> str:
    """Why the friction of steady rolling is not estimated (:data:`POINT_LAW_ON_THE_FACE`),
    or "": with the point law, the largest flange force's ``pairing`` on the end sphere,
    where the rings turn relative to each other (at rest and where they turn together
    there is no torque to estimate with any law: :func:`_turns_relatively`)."""
    if cfg.surfaces.flange_law != "point" or not pairing.startswith("SP"):
        return ""
    if not _turns_relatively(case):
        return ""
    return POINT_LAW_ON_THE_FACE.format(pairing=pairing)


def _rollers_in_the_load_zone(inner: np.ndarray, outer: np.ndarray) -> float:
    """How many rollers carry load between the races: the lesser of their two race loads
    at least 1 % of the heaviest roller's (B1 at 5 kN: 9; the rollers above the ring rest
    on it with 2 mN by their weight, which 1e-6 of the heaviest counted: 13)."""
    heaviest = max(float(inner.max()), float(outer.max()))
    if heaviest <= 0.0:
        return 0.0
    return float((np.minimum(inner, outer) >= 0.01 * heaviest).sum())


def _flange_contact_height(cfg: BearingConfig, radius: np.ndarray) -> np.ndarray:
    """Heights above their raceways of the flange contacts at ``radius`` from their rings'
    axes (shape (Z, 4), flanges in the order of :data:`FLANGES`: the inner ring's flanges
    rise outwards from the inner raceway, the outer ring's inwards from the outer one)."""
    g = cfg.geometry
    inner, outer = g.inner_raceway_diameter / 2.0, g.outer_raceway_diameter / 2.0
    on_inner = np.array([name.startswith("inner") for name in FLANGES])
    return np.where(on_inner, radius - inner, outer - radius)


def _load_zone_angle(cfg: BearingConfig, ring: np.ndarray) -> float:
    """Harris's load zone half-angle from the ring's radial displacement delta_r and the
    diametral clearance P_d: cos psi_l = P_d / (2 delta_r); 0 when the ring does not close
    the clearance, 180 deg with a preload (P_d < 0)."""
    delta_r = math.hypot(ring[1], ring[2])
    pd = cfg.geometry.diametral_clearance
    if delta_r <= 0.0:
        return 0.0
    x = pd / (2.0 * delta_r)
    return float(np.degrees(np.arccos(np.clip(x, -1.0, 1.0))))


@dataclass(frozen=True)
class _Ratings:
    """What the lives of every case of a configuration share: C_r [N], C_0r [N], C_u [N]
    and the oil's kinematic viscosity at the operating temperature [m^2/s]; and what the
    race films need (:func:`rollerdyn.lubrication.film_data`)."""

    dynamic: float
    static: float
    fatigue_limit: float
    viscosity: float
    films: FilmData


def _ratings(cfg: BearingConfig) -> _Ratings:
    """The bearing's load ratings and what its lives need; :class:`StaticsError` where
    ISO 281 has no factor f_c for its D/d_m (Table 7: 0.01 ... 0.3)."""
    g = cfg.geometry
    d, dpw, length = g.roller_diameter, g.pitch_diameter, g.roller.effective_length
    c_0 = life.static_load_rating(g.roller_count, d, length, dpw)
    try:
        dynamic = life.dynamic_load_rating(g.roller_count, d, length, dpw)
    except ValueError as err:  # D/d_m outside ISO 281's Table 7
        raise StaticsError(
            f"geometry: {err}; the statics rate the bearing by ISO 281 and ISO/TS 16281"
        ) from None
    return _Ratings(
        dynamic=dynamic,
        static=c_0,
        fatigue_limit=life.fatigue_load_limit(c_0, dpw),
        viscosity=Model(cfg).eta0 / cfg.lubricant.density_at(cfg.operating.temperature),
        films=film_data(cfg),
    )


def _rotating_ring(case: StaticCase) -> life.Ring:
    """The ring that turns relative to the radial load (fixed in direction): the faster
    one, the inner ring when both stand or turn alike (ISO/TS 16281's equivalent lamina
    loads, :func:`rollerdyn.life.equivalent_lamina_loads`)."""
    return "outer" if abs(case.outer_speed) > abs(case.speed) else "inner"


def _film_variables(cfg: BearingConfig, ratings: _Ratings, case: StaticCase, slices) -> dict:
    """The central film and the specific film thickness Lambda = h_c / sigma of each
    roller's most loaded slice at each race, rolling without slip at the case's speeds
    (:func:`rollerdyn.lubrication.rolling_race_films`, the dynamic model's film of a race
    slice; docs/dynamics.md, "Lubrication at the contacts"); NaN unloaded or without
    relative speed."""
    loads = {race: slices[f"{race}_slices"] for race in RACES}
    if case.relative_speed == 0.0:
        films = {race: np.full(loads[race].shape[0], np.nan) for race in RACES}
    else:
        films = rolling_race_films(cfg, ratings.films, case.relative_speed, loads)
    sigma = cfg.surfaces.raceway.roughness
    lam = {race: films[race] / sigma for race in RACES}
    smallest = np.concatenate([lam[race] for race in RACES])
    out = {}
    for race in RACES:
        out[f"{race}_film_thickness"] = _var(
            films[race],
            ("roller",),
            "m",
            f"central film of the roller's most loaded slice at the {race} race, rolling "
            "without slip (Moes, eqs. 33-38, thermally corrected, eq. 47); NaN unloaded",
        )
        out[f"{race}_specific_film_thickness"] = _var(
            lam[race],
            ("roller",),
            "1",
            f"Lambda = h_c / sigma there ({race} race; < 1 boundary, 1-3 mixed, > 3 full film)",
        )
    out["min_specific_film_thickness"] = _var(
        float(np.nanmin(smallest)) if np.isfinite(smallest).any() else math.nan,
        (),
        "1",
        "smallest Lambda of the loaded race contacts (NaN at rest)",
    )
    return out


def carried_radial_load(cfg: BearingConfig, case: StaticCase) -> float:
    """The radial load the bearing carries [N]: the applied radial load (along -y on the
    inner ring) and the weight of the inner ring with its shaft section across the axis,
    added as vectors. ISO 281's P and ISO 76's P_0r are the load on the bearing; the ring's
    weight is part of it (a 22 kg ring and shaft of a 50 mm bore under 1 N gave L_10 =
    1.5e16 against L_10r = 6.2e8, which its slice loads, carrying the weight, give)."""
    gravity = np.asarray(cfg.operating.gravity, dtype=float)
    weight = cfg.inner_ring.mass * gravity
    return float(math.hypot(weight[1] - case.radial_load, weight[2]))


def _life_variables(
    cfg: BearingConfig,
    ratings: _Ratings,
    case: StaticCase,
    inner: np.ndarray,
    outer: np.ndarray,
    contamination: float,
) -> dict:
    """Rating lives of the case (:mod:`rollerdyn.life`): ISO 281's L_10 with P the radial
    load the bearing carries (a cylindrical roller bearing's equivalent load ignores the
    axial load: :func:`carried_radial_load`), ISO/TS 16281's
    L_10r from the slice loads and its modified L_nmr with a_ISO from the lubricant's
    viscosity ratio kappa at the operating temperature and speed and the contamination
    factor e_C. Lives in 10^6 revolutions of one ring relative to the other (ISO 281:2007,
    3.6). The ring that turns relative to the load (the radial load's direction is fixed)
    takes ISO/TS 16281's equivalent load of a rotating ring: the outer ring where it turns
    faster than the inner one (a planet gear's bearing), else the inner ring."""
    c_r, c_u, nu = ratings.dynamic, ratings.fatigue_limit, ratings.viscosity
    d, dpw = cfg.geometry.roller_diameter, cfg.geometry.pitch_diameter
    rotating = _rotating_ring(case)
    radial = carried_radial_load(cfg, case)
    l10 = life.basic_rating_life(c_r, radial) if radial > 0 else math.inf
    l10r = life.reference_rating_life(inner, outer, c_r, d, dpw, rotating=rotating)
    rpm = abs(case.relative_speed) * 60.0 / (2.0 * math.pi)
    kappa = life.viscosity_ratio(nu, rpm, dpw) if rpm > 0 else math.nan
    lnmr = math.nan
    if rpm > 0 and math.isfinite(l10r):
        lnmr = life.modified_reference_rating_life(
            inner,
            outer,
            c_r,
            d,
            dpw,
            rotating=rotating,
            kappa=kappa,
            contamination=contamination,
            fatigue_limit=c_u,
        )
    return {
        "dynamic_load_rating": _var(
            c_r, (), "N", "basic dynamic radial load rating C_r (ISO 281:2007, 7.1)"
        ),
        "fatigue_load_limit": _var(c_u, (), "N", "fatigue load limit C_u (ISO 281:2007, annex B)"),
        "static_load_rating": _var(
            ratings.static, (), "N", "basic static radial load rating C_0r (ISO 76:2006)"
        ),
        "s0": _var(
            life.static_safety_factor(ratings.static, radial),
            (),
            "1",
            "static safety factor s_0 = C_0r / P_0r, P_0r the radial load carried "
            "(carried_radial_load: F_r and the inner ring's weight; ISO 76:2006; inf "
            "without radial load)",
        ),
        "l10": _var(
            l10,
            (),
            "1e6 rev",
            "basic rating life L_10 with P the radial load carried (carried_radial_load: "
            "F_r and the inner ring's weight; ISO 281:2007, 7.3)",
        ),
        "carried_radial_load": _var(
            radial,
            (),
            "N",
            "the radial load the bearing carries, P of L_10 and P_0r of s_0: the applied "
            "radial load and the weight of the inner ring with its shaft section "
            "(inner_ring.mass times operating.gravity across the axis), added as vectors",
        ),
        "l10r": _var(
            l10r,
            (),
            "1e6 rev",
            "basic reference rating life L_10r from the slice loads (ISO/TS 16281:2008)",
        ),
        "kappa": _var(
            float(kappa), (), "1", "viscosity ratio nu/nu_1 (ISO 281:2007, 9.3; NaN at rest)"
        ),
        "lnmr": _var(
            float(lnmr),
            (),
            "1e6 rev",
            f"modified reference rating life L_nmr, e_C = {contamination:g}, "
            "90 % reliability (ISO/TS 16281:2008, 7)",
        ),
    }
