"""Parameter sweeps: one configuration, a grid of changes, every run on Dask distributed.

:func:`sweep` mirrors ``rollerdyn sweep``. The grid is the cartesian product of the
swept values (dotted configuration paths such as ``operating.axial_load``); every grid
point's configuration is validated before any run starts. Each run is one Dask task that
simulates in its worker process and writes its own result file ``run_XXXX.nc`` (netCDF,
h5netcdf, the same content as ``rollerdyn run`` writes) into the output directory; only a
small dict of summary numbers travels back. The summary (one row per run, see
:data:`SUMMARY_COLUMNS`) is returned as a :class:`pandas.DataFrame` and written to
``summary.parquet``. A run that fails still writes what it computed and is listed with its
error; the sweep goes on. A worker that dies mid-run (killed, out of memory) loses nothing:
Dask runs the task again on another worker (``retries``), and since a run writes its file
under a temporary name and renames it into place, a retried or duplicated run leaves one
complete file and one summary row. See ``docs/sweeps.md``; the command is
:mod:`rollerdyn.cli.sweep`.
"""

from __future__ import annotations

import contextlib
import io
import itertools
import logging
import math
import os
import re
import signal
import time
import tomllib
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from .config import BearingConfig, ConfigError, _field_at, parse_config
from .names import DETECTORS
from .paths import printable, write_atomically
from .units import IntegerSpec, NumberSpec, QuantitySpec, parse_time

__all__ = [
    "SUMMARY_COLUMNS",
    "GridPoint",
    "SweepError",
    "build_grid",
    "changed",
    "check_reachable",
    "connect",
    "parse_set",
    "run_one",
    "summarize",
    "sweep",
]

#: The summary's result columns and their meaning (units in the column names).
SUMMARY_COLUMNS = {
    "run": "run number, 0, 1, ... in grid order (the last --set varies fastest)",
    "status": "completed or failed",
    "error": "why a run failed (empty if it completed)",
    "final_time [s]": "simulated time reached",
    "mean_frictional_torque [N*m]": "mean bearing frictional torque over the last 20 % "
    "of the simulated time (outputs with t >= t0 + 0.8 (t_final - t0))",
    "mean_power_loss [W]": "mean power the contacts and the oil-air drag take from the "
    "motion over the same outputs: in steady running the friction power, torque times ring "
    "speed (NaN for a result written before power losses were recorded)",
    "max_race_load [N]": "largest roller-race normal force (inner or outer, any roller, "
    "any output time; NaN if the runs do not record the rollers: solver.outputs)",
    "max_flange_normal_force [N]": "largest roller end / flange normal force (any roller, "
    "any flange, any output time; NaN if the runs do not record the flanges)",
    "max_abs_srr_inner [1]": "largest |slide-to-roll ratio| at the inner race (eq. 49, "
    "any roller, any output time at which the inner ring turns; NaN outputs ignored; NaN "
    "if the ring never turns: the ratio has no meaning before, or if the runs do not record "
    "the rollers)",
    "roller_pass_frequency [Hz]": "the rate Z f_c at which rollers pass a point of the "
    "outer ring at full speed (rollerdyn.ripple; f_c the rollers' mean orbital speed, or the "
    "kinematic one without the rollers)",
    "ring_amplitude_y [m]": "the inner ring's vibration along the radial load at Z f_c, "
    "over the outputs at full speed (the varying compliance, docs/dynamics.md; NaN with "
    "fewer than 6 roller passes at full speed)",
    "ring_amplitude_z [m]": "the same across the load",
    "steps": "integrator steps",
    "note": "what the run noted about itself: that it crawled, with its likely cause "
    "(attribute crawl_note of its result: rollerdyn.simulate); empty otherwise",
    "wall [s]": "wall time of the run in its worker (simulation and writing its file)",
    "file": "result file in the output directory (empty if none was written)",
}

SUMMARY_FILE = "summary.parquet"


class SweepError(ValueError):
    """A sweep that cannot start: a malformed --set, or a grid point that fails validation.

    ``str(err)`` names the --set path, the value and the rule broken (the configuration's
    own messages, see :class:`rollerdyn.ConfigError`).
    """


# --------------------------------------------------------------------------- the grid


def split_values(text: str) -> list[str]:
    """``"0 N,500 N"`` -> ``["0 N", "500 N"]``: split at commas that are outside quotes,
    brackets and braces (so a TOML array or inline table stays one value)."""
    out, cur, depth, quote = [], [], 0, ""
    for ch in text:
        if quote:
            cur.append(ch)
            if ch == quote:
                quote = ""
        elif ch in "\"'":
            quote = ch
            cur.append(ch)
        elif ch in "[{":
            depth += 1
            cur.append(ch)
        elif ch in "]}":
            depth -= 1
            cur.append(ch)
        elif ch == "," and depth == 0:
            out.append("".join(cur).strip())
            cur = []
        else:
            cur.append(ch)
    out.append("".join(cur).strip())
    return out


def toml_value(text: str) -> Any:
    """A --set value as it would appear in the TOML file: text that is a TOML value (a
    number ``0.3``, an integer ``20``, ``true``/``false``, a quoted string, an array or an
    inline table) is that value; anything else (``500 N``, ``gradient``) is a string."""
    try:
        return tomllib.loads(f"v = {text}")["v"]
    except tomllib.TOMLDecodeError:
        return text


def parse_set(option: str, ranges: bool = True) -> tuple[str, list[Any]]:
    """``"operating.axial_load=0 N,500 N"`` -> ``("operating.axial_load", ["0 N", "500 N"])``
    (values read by :func:`toml_value`); ``A:B:N`` a range where ``ranges`` (a sweep's),
    else text as any other value (``rollerdyn run``'s: ``description=ratio 1:2:3``)."""
    if not isinstance(option, str):
        raise SweepError(f"--set {option!r}: expected a string PATH=VALUE[,VALUE...]")
    shown = printable(option)
    if shown != option:
        raise SweepError(f"--set {shown}: not UTF-8 text (a result file could not record it)")
    if any(ord(c) < 32 or ord(c) == 127 for c in option):
        raise SweepError(
            f"--set {option!r}: a line break or control character; one PATH=VALUE per --set "
            "(repeat --set for more)"
        )
    path, sep, values = option.partition("=")
    path = path.strip()
    parts = path.split(".")
    if not sep or not path or not all(p.strip() for p in parts):
        raise SweepError(
            f"--set {option!r}: expected PATH=VALUE[,VALUE...], e.g. "
            '--set operating.axial_load="0 N,500 N"'
        )
    texts = split_values(values)
    if any(not t for t in texts):
        raise SweepError(f"--set {path}={values}: an empty value (two commas, or none given)")
    if ranges and len(texts) == 1 and _RANGE.match(texts[0]):
        return path, range_values(path, texts[0])
    return path, [toml_value(t) for t in texts]


#: ``A:B:N``: N evenly spaced values from A to B, each a number with or without a unit.
_RANGE = re.compile(r"^\s*([^:\[\]{}\"']+):([^:\[\]{}\"']+):\s*([-+]?[0-9.eE+-]+)\s*$")
_NUMBER_UNIT = re.compile(r"^\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*(.*?)\s*$")

#: Most values one A:B:N range of a sweep gives (each value is at least one run).
MAX_RANGE_VALUES = 10_000

#: The most points of a sweep's grid (the product of its --set lists; a map has the same).
MAX_GRID_POINTS = 10_000

#: The most worker processes per core of a local cluster: a worker runs one run on one
#: core, so more than a few per core only add processes of about 150 MB each.
WORKERS_PER_CORE = 4


def check_workers(workers: Any, option: str = "workers") -> None:
    """Refuses (:class:`SweepError`, naming ``option``) a worker count that is no whole
    number of at least 1, or more than :data:`WORKERS_PER_CORE` per core of this machine."""
    whole = isinstance(workers, int) and not isinstance(workers, bool)
    if not (whole and workers >= 1):
        raise SweepError(f"{option} = {workers!r}: must be a whole number, at least 1")
    most = WORKERS_PER_CORE * (os.cpu_count() or 1)
    if workers > most:
        raise SweepError(
            f"{option} = {workers}: at most {most} on this machine ({WORKERS_PER_CORE} per "
            "core; each worker is a process that runs one run on one core)"
        )


def range_values(path: str, text: str) -> list[Any]:
    """The values of ``A:B:N`` in ``--set PATH=A:B:N``: N evenly spaced from A to B, in A's
    and B's unit (which must be the same text), as strings such as ``"500 N"``; bare
    numbers stay numbers (integers where A, B and the spacing are whole)."""
    m = _RANGE.match(text)
    assert m is not None
    first, last = (_NUMBER_UNIT.match(part) for part in m.groups()[:2])
    try:
        n = int(m.group(3))
    except ValueError:
        n = 0  # not a whole count: refused below
    if first is None or last is None:
        raise SweepError(f"--set {path}={text}: A:B:N needs a number (with its unit) at both ends")
    (a, unit_a), (b, unit_b) = first.groups(), last.groups()
    if unit_a != unit_b:
        raise SweepError(
            f"--set {path}={text}: the ends of A:B:N take the same unit ({unit_a!r} and {unit_b!r})"
        )
    if not 1 <= n <= MAX_RANGE_VALUES or (n == 1 and float(a) != float(b)):
        raise SweepError(
            f"--set {path}={text}: N must be 2 ... {MAX_RANGE_VALUES} (or 1 with A = B)"
        )
    lo, hi = float(a), float(b)
    if not (math.isfinite(lo) and math.isfinite(hi)):
        raise SweepError(f"--set {path}={text}: the ends must be finite")
    values = [lo + (hi - lo) * i / (n - 1) for i in range(n)] if n > 1 else [lo]
    whole = all(v == int(v) for v in values) and "." not in a + b and "e" not in (a + b).lower()
    if not unit_a:
        return [int(v) for v in values] if whole else values
    return [f"{int(v) if whole else repr(v)} {unit_a}" for v in values]


def _show(value: Any) -> str:
    """A swept value as typed (strings bare, booleans as in TOML)."""
    if isinstance(value, str):
        return value
    if isinstance(value, bool):
        return "true" if value else "false"
    return str(value)


@dataclass(frozen=True)
class GridPoint:
    """One run of a sweep: its number, file name, swept values (as given and SI) and the
    full configuration data to parse in the worker."""

    run: int
    values: dict[str, Any]
    si_values: dict[str, Any]
    data: dict
    si_numbers: bool

    @property
    def file(self) -> str:
        return f"run_{self.run:04d}.nc"

    def label(self) -> str:
        return ", ".join(f"{p}={_show(v)}" for p, v in self.values.items())


def changed(data: Mapping, changes: Mapping[str, Any]) -> dict:
    """A deep copy of ``data`` with dotted-path changes (``{"operating.axial_load": 0.0}``;
    None removes the key, leaving the field's default); :class:`SweepError` naming the path
    where a parent is not a table. Shared with the studies (:mod:`rollerdyn.study`) and the
    benchmark cases."""
    import copy

    out = copy.deepcopy(dict(data))
    for path, value in changes.items():
        section = out
        *parents, key = path.split(".")
        for i, p in enumerate(parents):
            nxt = section.setdefault(p, {})
            if not isinstance(nxt, dict):
                where = ".".join(parents[: i + 1])
                raise SweepError(
                    f"--set {path}: {where} is {_show(nxt)!r} in the configuration, not a "
                    "table, so it has no keys to set"
                )
            section = nxt
        if value is None:
            section.pop(key, None)
        else:
            section[key] = value
    return out


def _si_unit(path: str) -> str | None:
    """SI unit of the numeric field at ``path`` (None: not a number field)."""
    info = _field_at(path.split("."))
    if info is None:
        return None
    for meta in info.metadata:
        if isinstance(meta, QuantitySpec):
            return meta.family.si_unit or "1"
        if isinstance(meta, NumberSpec | IntegerSpec):
            return "1"
    stack = [info.annotation]
    while stack:
        ann = stack.pop()
        for meta in getattr(ann, "__metadata__", ()):
            if isinstance(meta, QuantitySpec):
                return meta.family.si_unit or "1"
            if isinstance(meta, NumberSpec | IntegerSpec):
                return "1"
        stack.extend(getattr(ann, "__args__", ()))
    return None


def _si_value(cfg: BearingConfig, path: str) -> Any:
    cur: Any = cfg
    for part in path.split("."):
        cur = getattr(cur, part, None)
    if isinstance(cur, bool | int | float | str) or cur is None:
        return cur
    return str(cur)


def _source(config: Any) -> tuple[dict, bool, str | None]:
    """(TOML data, si_numbers, source name) of a path, a mapping or a BearingConfig."""
    if isinstance(config, BearingConfig):
        return config.model_dump(), True, None
    if isinstance(config, Mapping):
        return dict(config), False, None
    if not isinstance(config, str | os.PathLike):
        raise SweepError(
            f"config = {config!r}: expected a TOML file's path, its data as a mapping or a "
            "BearingConfig"
        )
    from .config import load_config

    path = Path(config)
    load_config(path)  # the same clean ConfigError as `rollerdyn run` for a bad file
    return tomllib.loads(path.read_text(encoding="utf-8-sig")), False, str(path)


def build_grid(
    config: str | Path | Mapping | BearingConfig,
    parameters: Mapping[str, Sequence[Any]],
    t_end: float | None = None,
    detector: str | None = None,
) -> list[GridPoint]:
    """Every grid point of the cartesian product of ``parameters`` (the last path varies
    fastest), each validated, also for the cost of its run to ``t_end`` (default: its
    configuration's end) with ``detector`` (default: its configuration's;
    :func:`rollerdyn.simulation.check_cost`); raises :class:`SweepError` listing every
    point that fails."""
    from .simulation import check_cost

    def cost(cfg: BearingConfig) -> None:
        end = cfg.end_time if t_end is None else t_end
        check_cost(cfg, end, remedy="", detector=detector)

    return [point for point, _ in parsed_grid(config, parameters, check=cost)]


def parsed_grid(
    config: str | Path | Mapping | BearingConfig,
    parameters: Mapping[str, Sequence[Any]],
    check: Callable[[BearingConfig], None] | None = None,
) -> list[tuple[GridPoint, BearingConfig]]:
    """Every grid point of the cartesian product of ``parameters`` (the last path varies
    fastest) with its parsed configuration, each validated (and by ``check``, which raises
    ``ValueError`` naming what it refuses); raises :class:`SweepError` listing every point
    that fails. Shared by :func:`build_grid` and the quasi-static design sweeps
    (:func:`rollerdyn.statics.statics_sweep`)."""
    if not isinstance(parameters, Mapping):
        raise SweepError(
            f"parameters = {parameters!r}: expected a mapping of paths to lists of values, "
            "e.g. {'operating.axial_load': ['0 N', '500 N']}"
        )
    data, si_numbers, source = _source(config)
    paths = list(parameters)
    for path in paths:
        values = parameters[path]
        if isinstance(values, str | bytes) or not isinstance(values, Sequence) or not values:
            raise SweepError(f"--set {path}: expected a non-empty list of values")
    total = math.prod(len(parameters[p]) for p in paths)
    if total > MAX_GRID_POINTS:
        counts = " x ".join(str(len(parameters[p])) for p in paths)
        raise SweepError(
            f"--set: {counts} = {total} grid points; a sweep has at most {MAX_GRID_POINTS}"
        )
    points, failures = [], []
    for run, combo in enumerate(itertools.product(*(parameters[p] for p in paths))):
        values = dict(zip(paths, combo, strict=True))
        point_data = changed(data, values)
        label = ", ".join(f"{p}={_show(v)}" for p, v in values.items())
        try:
            cfg = parse_config(point_data, source=source, si_numbers=si_numbers)
        except ConfigError as err:
            lines = []
            for prob in err.problems or ():
                swept = " (--set " + prob.path + ")" if prob.path in values else ""
                lines.append(f"  {prob}{swept}")
            failures.append(f"run {run} ({label}):\n" + ("\n".join(lines) or f"  {err}"))
            continue
        if check is not None:
            try:
                check(cfg)
            except ValueError as err:
                failures.append(f"run {run} ({label}):\n  {err}")
                continue
        si = {p: _si_value(cfg, p) for p in paths}
        points.append((GridPoint(run, values, si, point_data, si_numbers), cfg))
    if failures:
        total = len(points) + len(failures)
        head = (
            f"invalid sweep: {len(failures)} of {total} grid point"
            f"{'s' if total != 1 else ''} fail validation (no run was started):"
        )
        raise SweepError("\n".join([head, *failures]))
    return points


# --------------------------------------------------------------------------- one run


def summarize(ds) -> dict:
    """The summary numbers of one result Dataset (see :data:`SUMMARY_COLUMNS`)."""
    from .report import max_abs_srr_inner
    from .ripple import ripple

    def finite_max(values) -> float:
        arr = np.asarray(values, dtype=float)
        arr = arr[np.isfinite(arr)]
        return float(arr.max()) if arr.size else math.nan

    time_ = np.asarray(ds["time"].values, dtype=float)
    torque = power = math.nan
    if time_.size:
        t0, t1 = time_[0], time_[-1]
        last = time_ >= t0 + 0.8 * (t1 - t0)
        torque = _finite_mean(ds["frictional_torque"].values, last)
        if "power_loss" in ds:
            power = _finite_mean(ds["power_loss"].values, last)
    # NaN for what the run did not record (solver.outputs)
    race = [
        np.ravel(ds[name].values)
        for name in ("inner_normal_force", "outer_normal_force")
        if name in ds
    ]
    flange = ds["flange_normal_force"].values if "flange_normal_force" in ds else []
    vibration = ripple(ds) if time_.size else {}
    return {
        "final_time [s]": float(ds.attrs.get("final_time_s", math.nan)),
        "mean_frictional_torque [N*m]": torque,
        "mean_power_loss [W]": power,
        "max_race_load [N]": finite_max(np.concatenate(race) if race else []),
        "max_flange_normal_force [N]": finite_max(flange),
        "max_abs_srr_inner [1]": max_abs_srr_inner(ds) if "srr_inner" in ds else math.nan,
        "roller_pass_frequency [Hz]": vibration.get("roller_pass_frequency", math.nan),
        "ring_amplitude_y [m]": vibration.get("ring_y_amplitude_1", math.nan),
        "ring_amplitude_z [m]": vibration.get("ring_z_amplitude_1", math.nan),
        "steps": int(ds.attrs.get("stats_steps", 0)),
        "note": str(ds.attrs.get("crawl_note", "")),
    }


def _finite_mean(values, where) -> float:
    """The mean of the finite ``values[where]``; NaN if there are none."""
    sel = np.asarray(values, dtype=float)[where]
    sel = sel[np.isfinite(sel)]
    return float(sel.mean()) if sel.size else math.nan


def _empty_numbers() -> dict:
    return {
        "final_time [s]": math.nan,
        "mean_frictional_torque [N*m]": math.nan,
        "mean_power_loss [W]": math.nan,
        "max_race_load [N]": math.nan,
        "max_flange_normal_force [N]": math.nan,
        "max_abs_srr_inner [1]": math.nan,
        "roller_pass_frequency [Hz]": math.nan,
        "ring_amplitude_y [m]": math.nan,
        "ring_amplitude_z [m]": math.nan,
        "steps": 0,
        "note": "",
    }


def run_one(
    data: dict,
    si_numbers: bool,
    outdir: str,
    file: str,
    t_end: float | None = None,
    detector: str | None = None,
    force: bool = False,
) -> dict:
    """One sweep run, as executed in a Dask worker: parse, simulate (``force`` as in
    :func:`rollerdyn.simulate`), write ``outdir/file``, return the summary numbers, status
    and error (never raises).

    Idempotent: the file is written under a name of this process's own and renamed into
    place (atomic on one file system), so a run killed while writing leaves no partial
    ``outdir/file`` and a run executed twice (a retry after a lost worker) leaves one
    complete file, the same either way."""
    from .simulation import SimulationError, failure_note, simulate, write

    start = time.perf_counter()
    status, error, written = "completed", "", ""
    numbers = _empty_numbers()
    try:
        cfg = parse_config(data, si_numbers=si_numbers)
        try:
            # One thread per run: the sweep runs its points in parallel already.
            ds = simulate(cfg, t_end=t_end, detector=detector, threads=1, force=force)
        except SimulationError as err:
            ds, status, error = err.dataset, "failed", str(err)
        numbers = summarize(ds)
        final = Path(outdir) / file
        partial = final.with_name(f".{file}.{os.getpid()}.partial")
        # what --overwrite of a later sweep tells the sweep's own files by (earlier_results)
        ds.attrs["sweep_file"] = file
        try:
            write(ds, partial)
            os.replace(partial, final)
        finally:
            partial.unlink(missing_ok=True)
        written = file
    except Exception as err:  # a run's failure must not stop the sweep
        status, error = "failed", failure_note(err)
    return {
        "status": status,
        "error": error,
        **numbers,
        "wall [s]": time.perf_counter() - start,
        "file": written,
    }


# --------------------------------------------------------------------------- the sweep


def _row(point: GridPoint, result: dict) -> dict:
    row: dict[str, Any] = {"run": point.run}
    for path, value in point.values.items():
        row[path] = _show(value)
        unit = _si_unit(path)
        if unit is not None:
            si = point.si_values[path]
            numeric = isinstance(si, int | float) and not isinstance(si, bool)
            row[f"{path} [{unit}]"] = float(si) if numeric else math.nan  # NaN: a time table
    row.update(result)
    return row


def sweep(
    config: str | Path | Mapping | BearingConfig,
    parameters: Mapping[str, Sequence[Any]],
    outdir: str | Path,
    scheduler: Any = None,
    workers: int = 2,
    t_end: float | None = None,
    detector: str | None = None,
    progress: Callable[[int, int, dict | None], Any] | None = None,
    retries: int = 2,
    connect_timeout: float = 10.0,
    force: bool = False,
    overwrite: bool = False,
    resume: bool = False,
):
    """Run the grid of ``parameters`` over ``config`` on Dask; return the summary.

    ``config``: a TOML file, its data as a mapping, or a :class:`BearingConfig` (then the
    paths address ``config.model_dump()`` and bare numbers are taken as SI).
    ``parameters``: ``{"operating.axial_load": ["0 N", "500 N"], ...}``, each value as it
    would appear in the TOML data; several paths make the full grid (cartesian product,
    the last path varying fastest). Every grid point is validated before any run starts
    (:class:`SweepError` otherwise). ``scheduler``: None starts a ``LocalCluster`` of
    ``workers`` processes with one thread each; an address (``"tcp://host:8786"``) or a
    ``distributed.Client`` uses that cluster instead (its workers must see ``outdir``).
    ``t_end`` (s, or a time such as ``"50 ms"``), ``detector`` and ``force`` as in
    :func:`rollerdyn.simulate`. ``progress(done,
    total, row)`` is called once with ``row=None`` when the runs are submitted and then
    after each run. ``retries``: how many more times Dask runs a task whose attempt did not
    return (its worker died mid-run, or the task raised); each grid point keeps one row,
    from its attempt that returned. Returns a :class:`pandas.DataFrame`, one row per run in
    run order (columns: :data:`SUMMARY_COLUMNS` and, per path, the value as given and, for numeric
    fields, its SI value in ``"<path> [<unit>]"``), also written to
    ``outdir/summary.parquet``, and a figure of the summary over the swept quantity with
    the most values (``outdir/summary.png``, ``.svg``; :mod:`rollerdyn.sweep_figures`;
    none when no numeric value is swept). A folder that holds an earlier sweep's files
    (``run_XXXX.nc``, the summary and its figure) is refused unless ``overwrite``, which
    removes them first, once the cluster is up; even then a file of those names that is not
    a sweep's (:func:`earlier_results`) is refused, and nothing is removed. A scheduler
    that cannot be reached (within ``connect_timeout`` seconds) raises :class:`SweepError`
    before ``outdir`` is touched. ``resume``: continue the earlier sweep in ``outdir`` (one
    that was interrupted): the points whose run files are there, of the same configuration,
    detector and end time, are kept (their rows read from the files; a failed run stays
    failed) and the others run; a run file that is not this grid's is refused
    (:func:`rollerdyn.sweep_resume.kept_runs`). Without an earlier sweep it runs them all.
    """
    t_end = _check_sweep_arguments(
        detector, t_end, scheduler, workers, retries, progress, force, overwrite, resume
    )
    points = build_grid(config, parameters, t_end, detector)
    if not isinstance(outdir, str | os.PathLike):
        raise SweepError(f"outdir = {outdir!r}: must be a folder's path")
    out = Path(outdir).resolve()
    if out.exists() and not out.is_dir():
        raise SweepError(f"outdir = {outdir}: is a file, not a folder")
    _check_unlocked(out)
    flag = "resume=True" if resume else "overwrite=True"
    earlier = earlier_results(out, overwrite or resume, f"outdir = {outdir}", flag, resume)
    rows: dict[int, dict] = {}
    if resume:
        from .sweep_resume import kept_runs

        rows, earlier = kept_runs(out, points, t_end, detector), []
    todo = [p for p in points if p.run not in rows]
    # What writes the summary, loaded before the runs: a Ctrl-C must not land in its
    # imports (a second of them) while the summary of an interrupted sweep is written.
    import pandas  # noqa: F401
    import pyarrow.parquet  # noqa: F401

    # no more workers than runs: each costs a process
    client, cluster = (
        (None, None)
        if not todo
        else connect(
            scheduler, min(workers, len(todo)) if scheduler is None else workers, connect_timeout
        )
    )
    job = _Job(out, points, list(parameters), t_end, detector, force, retries)
    try:
        lock = _lock(out)
    except BaseException:
        disconnect(client, cluster, scheduler)
        raise
    try:
        return _run(job, (client, cluster, scheduler), rows, todo, earlier, progress)
    finally:
        lock.unlink(missing_ok=True)


@dataclass(frozen=True)
class _Job:
    """What a sweep runs: into the folder ``out``, the grid ``points`` of the swept
    ``paths``, each run to ``t_end`` with ``detector`` and ``force``, retried ``retries``
    times."""

    out: Path
    points: list[GridPoint]
    paths: list[str]
    t_end: float | None
    detector: str | None
    force: bool
    retries: int


#: The sweep folder's lock file (:func:`rollerdyn.paths.take_folder_lock`).
LOCK = ".sweep.lock"


def _check_unlocked(out: Path) -> None:
    """:class:`SweepError` if another sweep is running in the folder ``out``."""
    from .paths import check_unlocked

    check_unlocked(out, LOCK, "sweep", SweepError)


def _lock(out: Path) -> Path:
    """The folder ``out`` made and its lock taken (:class:`SweepError` if another sweep
    holds it: two sweeps in one folder replaced each other's run files, and both said
    they completed)."""
    from .paths import take_folder_lock

    out.mkdir(parents=True, exist_ok=True)
    return take_folder_lock(out, LOCK, "sweep", SweepError)


def _run(job: _Job, dask: tuple, rows: dict, todo: list, earlier: list, progress):
    """The runs ``todo`` of ``job`` on ``dask`` (client, cluster, scheduler of
    :func:`connect`; None: nothing to run) into its folder (locked), after the ``earlier``
    sweep's files are removed; ``rows``: the kept runs' rows, to which the others' are
    added. Writes the summary and its figure; returns the summary."""
    from distributed import as_completed

    from .simulation import failure_note

    client, cluster, scheduler = dask
    out, points = job.out, job.points
    try:
        for f in earlier:  # so that none of it can pass for this sweep's (earlier_results)
            f.unlink(missing_ok=True)
        futures, by_key = [], {}
        for p in todo:
            fut = client.submit(
                run_one,
                p.data,
                p.si_numbers,
                str(out),
                p.file,
                job.t_end,
                job.detector,
                job.force,
                pure=False,
                retries=job.retries,
            )
            futures.append(fut)
            by_key[fut.key] = p
        total = len(points)
        if progress is not None:
            progress(len(rows), total, None)
        for fut in as_completed(futures) if futures else ():
            p = by_key[fut.key]
            try:
                result = fut.result()
            except Exception as err:  # workers lost more often than retried: this run only
                result = {
                    "status": "failed",
                    "error": failure_note(err),
                    **_empty_numbers(),
                    "wall [s]": math.nan,
                    "file": p.file if (out / p.file).is_file() else "",
                }
            rows[p.run] = _row(p, result)
            if progress is not None:
                progress(len(rows), total, rows[p.run])
    except KeyboardInterrupt as err:
        # Ctrl-C (a further one is ignored meanwhile): the workers, which ignore it, are
        # stopped first; then the summary lists the runs that finished, those that finished
        # while the workers stopped among them (from their files), and the others as
        # interrupted. A summary that cannot be written must not hide the interrupt.
        # SIGTERM comes as a KeyboardInterrupt that says so (cli.common).
        cause = "SIGTERM" if "SIGTERM" in str(err) else "KeyboardInterrupt (Ctrl-C)"
        with _ctrl_c_ignored(), _sigterm_deferred():
            disconnect(client, cluster, scheduler)
            if out.is_dir():
                _remove_partial_files(out, points)
                _rows_from_files(out, points, rows)
                with contextlib.suppress(OSError):
                    _summarize(out, points, rows, "interrupted", f"{cause}: not finished")
        raise
    finally:
        disconnect(client, cluster, scheduler)  # a no-op once closed (Ctrl-C above)
    with _ctrl_c_ignored(), _sigterm_deferred():
        _remove_partial_files(out, points)
        frame = _summarize(out, points, rows)
    from .sweep_figures import write_summary_figure

    # titled with the bearing's name, as the operating maps are
    write_summary_figure(frame, job.paths, out, str(points[0].data.get("name", "")))
    return frame


def _check_sweep_arguments(
    detector, t_end, scheduler, workers, retries, progress, force, overwrite, resume
) -> float | None:
    """Refuses (:class:`SweepError`, naming the argument) what :func:`sweep` cannot take,
    before anything starts or an earlier sweep's files are removed; returns ``t_end`` in s
    (read as :func:`rollerdyn.simulate` reads it: ``"50 ms"`` too)."""
    if detector is not None and detector not in DETECTORS:
        raise SweepError(f"detector = {detector!r}: must be {', '.join(DETECTORS)}")
    if t_end is not None:
        try:
            t_end = parse_time(t_end, "t_end")
        except ValueError as err:
            clauses = str(err).split(": ", 1)[-1].split("; ")  # [what is wrong;] the rule
            shown = repr(t_end) if len(repr(t_end)) <= 40 else repr(t_end)[:37] + "..."
            raise SweepError(
                f"t_end = {shown}: must be a time of at least 1 ns, in seconds or with its "
                "unit (e.g. 0.05 or '50 ms')" + (f"; {clauses[0]}" if len(clauses) > 1 else "")
            ) from None
    if scheduler is None:
        check_workers(workers)
    if isinstance(retries, bool) or not isinstance(retries, int) or retries < 0:
        raise SweepError(f"retries = {retries!r}: must be a whole number, 0 or more")
    if progress is not None and not callable(progress):
        raise SweepError(f"progress = {progress!r}: must be a function (or None)")
    for name, value in (("force", force), ("overwrite", overwrite), ("resume", resume)):
        if not isinstance(value, bool | np.bool_):
            raise SweepError(f"{name} = {value!r}: must be True or False")
    if overwrite and resume:
        raise SweepError(
            "overwrite = True and resume = True: choose one (resume keeps the earlier "
            "sweep's finished runs, overwrite removes them)"
        )
    return t_end


#: The names of an earlier sweep's result files in its folder.
RUN_FILES = "run_[0-9][0-9][0-9][0-9].nc"


def earlier_results(
    out: Path, overwrite: bool, where: str, flag: str, resume: bool = False
) -> list[Path]:
    """The files an earlier sweep wrote into the folder ``out`` (``run_XXXX.nc``, the
    summary and its figure), which ``overwrite`` lets a new sweep remove (``resume``: keep
    and continue; then a summary that cannot be read beside the sweep's run files is taken
    as the earlier sweep's, cut short); raises
    :class:`SweepError` (starting with ``where``, e.g. ``"-o DIR"``; ``flag`` is the
    option that allows it) if there are any and not ``overwrite``, or if one of them
    cannot be told to be a sweep's: a run file that is not a rollerdyn result, a summary
    without the summary's columns, or a figure that matplotlib did not draw or that has no
    sweep's summary beside it (the figure is drawn from it). Nothing is removed here."""
    from .sweep_figures import FIGURE_NAME

    if not out.is_dir():
        return []
    names = (SUMMARY_FILE, f"{FIGURE_NAME}.png", f"{FIGURE_NAME}.svg")
    found = sorted({*out.glob(RUN_FILES), *(out / n for n in names if _exists(out / n))})
    if not found:
        return []
    if not overwrite:
        shown = ", ".join(f.name for f in found[:3]) + (", ..." if len(found) > 3 else "")
        raise SweepError(
            f"{where}: holds earlier results ({shown}); pass {flag} to replace them, or "
            "choose another folder"
        )
    summary = _not_a_summary(out / SUMMARY_FILE)
    if summary and resume and _sweeps_folder(found):
        # a summary the interrupted sweep could not finish writing (killed during an older
        # version's write in place) beside its run files: rewritten by the resumed sweep
        summary = ""
    listed = set() if summary else _listed_files(out / SUMMARY_FILE)
    # the summary first: a foreign one is the reason its run files are not this sweep's
    for f in sorted(found, key=lambda f: (f.name != SUMMARY_FILE, f.name)):
        if f.name == SUMMARY_FILE:
            why = summary
        elif f.name.startswith(f"{FIGURE_NAME}."):
            why = summary and f"no summary of a sweep beside it: {summary}"
            why = why or _not_drawn(f)
        else:
            why = "" if f.name in listed else _not_a_run(f)
            why += ", nor does the summary list it" if why.startswith("a rollerdyn") else ""
        if why:
            verb = "writes over" if resume else "replaces"
            raise SweepError(
                f"{where}: {f.name} is not a file an earlier sweep wrote ({why}); {flag} "
                f"{verb} only a sweep's own files: move it or choose another folder"
            )
    return found


def _sweeps_folder(found: list[Path]) -> bool:
    """Whether ``found`` holds a run file that a sweep wrote under its name (a folder of
    an earlier sweep, whatever its summary)."""
    return any(f.name.startswith("run_") and not _not_a_run(f) for f in found)


def _exists(path: Path) -> bool:
    return path.exists() or path.is_symlink()


def _not_a_run(path: Path) -> str:
    """Why ``path`` is not a sweep's run file of its name ("" if it is one): a rollerdyn
    result whose ``sweep_file`` (:func:`run_one`) is its name; read without its data. (A
    result of ``rollerdyn run``, or a sweep's file copied to another name, is not.)"""
    attrs = run_attributes(path)
    return attrs if isinstance(attrs, str) else ""


def run_attributes(path: Path) -> dict | str:
    """The attributes of the sweep's run file ``path``, read without its data (text
    decoded), or why it is not one: not a rollerdyn result, or a result whose
    ``sweep_file`` (:func:`run_one`) is not its name."""
    import h5py

    try:
        with h5py.File(path, "r") as f:
            attrs = dict(f.attrs)
    except Exception as err:  # h5py raises several kinds for files that are not HDF5
        return f"not a rollerdyn result: {' '.join(str(err).split()) or type(err).__name__}"
    missing = {"final_time_s", "rollerdyn_version"} - set(attrs)
    if missing:
        return f"not a rollerdyn result: no {', '.join(sorted(missing))}"
    for key, value in attrs.items():
        if isinstance(value, np.ndarray) and value.size == 1:
            value = value.reshape(()).item()
        attrs[key] = bytes(value).decode("utf-8", "replace") if isinstance(value, bytes) else value
    stamp = attrs.get("sweep_file")
    if stamp != path.name:
        written = f"a sweep wrote it as {stamp}" if stamp else "no sweep wrote it"
        return f"a rollerdyn result that no sweep wrote under this name ({written})"
    return attrs


def _listed_files(summary: Path) -> set[str]:
    """The run files the sweep's summary ``summary`` lists (its ``file`` column)."""
    import pyarrow.parquet as pq

    try:
        files = pq.read_table(summary, columns=["file"]).column("file").to_pylist()
    except Exception:  # read once already (_not_a_summary): a file changed meanwhile
        return set()
    return {f for f in files if isinstance(f, str) and f}


def _not_drawn(path: Path) -> str:
    """Why ``path`` is not a figure of matplotlib ("" if it is one): the name it writes
    into the head of its PNG and SVG files."""
    try:
        with open(path, "rb") as f:
            head = f.read(8192)
    except OSError as err:
        return f"cannot be read: {err.strerror or err}"
    return "" if b"matplotlib" in head.lower() else "not a figure drawn by matplotlib"


def _not_a_summary(path: Path) -> str:
    """Why ``path`` is not a sweep's summary ("" if it is one): its columns."""
    import pyarrow.parquet as pq

    if not _exists(path):
        return f"{path.name} is missing"
    try:
        columns = set(pq.read_schema(path).names)
    except Exception as err:  # pyarrow raises several kinds for files that are not parquet
        return f"{path.name} is not parquet: {' '.join(str(err).split()) or type(err).__name__}"
    missing = {"run", "status", "error", "file"} - columns
    return f"{path.name} has no column {', '.join(sorted(missing))}" if missing else ""


def _remove_partial_files(out: Path, points) -> None:
    """Removes what attempts killed while writing left behind: ``.run_XXXX.nc.<pid>.partial``
    (:func:`run_one`) and its own temporary ``...partial.tmp<pid>`` (:func:`simulation.write`)."""
    for p in points:
        for partial in out.glob(f".{p.file}.*.partial*"):
            partial.unlink(missing_ok=True)


def _rows_from_files(out: Path, points, rows: dict[int, dict]) -> None:
    """Rows for the points whose run wrote its file but returned no row (it finished while
    an interrupted sweep stopped its workers), from that file; a file that cannot be read
    is left to the interrupted rows."""
    for p in points:
        if p.run in rows or not (out / p.file).is_file():
            continue
        row = row_from_file(out / p.file, p)
        if row is not None:
            rows[p.run] = row


def row_from_file(path: Path, point: GridPoint) -> dict | None:
    """The summary row of ``point`` from its result file ``path``, without a wall time
    (None if the file cannot be read as a result)."""
    from .report import open_result

    try:
        ds = open_result(path)  # in memory, the file closed
        numbers, attrs = summarize(ds), ds.attrs
    except Exception:  # a damaged file
        return None
    completed = int(attrs.get("completed", 0)) == 1
    result = {
        "status": "completed" if completed else "failed",
        "error": "" if completed else str(attrs.get("error", "")),
        **numbers,
        "wall [s]": math.nan,
        "file": point.file,
    }
    return _row(point, result)


def _summarize(out: Path, points, rows: dict[int, dict], status: str = "", error: str = ""):
    """Writes ``summary.parquet`` (one row per point, in order) and returns its frame; points
    without a row (an interrupted sweep) get ``status`` and ``error``."""
    import pandas as pd

    for p in points:
        if p.run not in rows:
            rows[p.run] = _row(
                p,
                {
                    "status": status,
                    "error": error,
                    **_empty_numbers(),
                    "wall [s]": math.nan,
                    "file": p.file if (out / p.file).is_file() else "",
                },
            )
    frame = pd.DataFrame([rows[p.run] for p in points])
    # through a temporary file renamed into place: a sweep killed while writing it (the
    # case --resume is for) leaves the earlier summary whole, not a truncated one
    buffer = io.BytesIO()
    frame.to_parquet(buffer, engine="pyarrow", index=False)
    write_atomically(out / SUMMARY_FILE, buffer.getbuffer(), replace=True)
    return frame


def check_reachable(address: str, timeout: float) -> None:
    """Raises :class:`SweepError` (one line) unless a Dask scheduler answers at ``address``
    within ``timeout`` seconds: a refused connection or an unknown host fails at once, and
    a server that accepts the connection but never answers (where Dask's own handshake
    waits forever) after ``timeout``. Addresses of other schemes than tcp are left to
    Dask. Shared with the studies (:mod:`rollerdyn.study.schedule`)."""
    import socket

    from distributed.comm import parse_address, parse_host_port

    try:
        scheme, location = parse_address(address)
        host, port = parse_host_port(location) if scheme in ("tcp", "tls") else (None, None)
    except (ValueError, TypeError) as err:
        raise SweepError(f"scheduler = {address!r}: not a scheduler address ({err})") from None
    if host is None:
        return
    try:
        socket.create_connection((host, port), timeout=timeout).close()
        if scheme == "tcp":
            _handshake(address, timeout)
    except (OSError, TimeoutError, EOFError) as err:
        reason = getattr(err, "strerror", None) or str(err) or type(err).__name__
        if isinstance(err, TimeoutError):
            reason = f"no answer within {timeout:g} s"
        raise SweepError(f"scheduler = {address!r}: cannot connect ({reason})") from None
    except Exception as err:  # a server that answers, but not as a Dask scheduler
        reason = " ".join(str(err).split()) or type(err).__name__
        raise SweepError(f"scheduler = {address!r}: no Dask scheduler there ({reason})") from None


def _handshake(address: str, timeout: float) -> None:
    """Opens and closes one Dask connection to ``address`` (its handshake included), given
    up after ``timeout`` seconds; in a thread of its own, so that it works inside a
    running event loop too."""
    import asyncio
    from concurrent.futures import ThreadPoolExecutor

    from distributed.comm import connect as dask_connect

    async def probe() -> None:
        comm = await asyncio.wait_for(dask_connect(address, timeout=timeout), timeout)
        await comm.close()

    with ThreadPoolExecutor(1) as pool:
        pool.submit(asyncio.run, probe()).result()


def connect(scheduler: Any, workers: int, timeout: float):
    """(client, cluster or None): a new local cluster of ``workers`` processes (one thread
    each), the given Client, or a Client of the scheduler at an address;
    :class:`SweepError` if that cannot be reached. Shared with the studies
    (:mod:`rollerdyn.study.schedule`); the caller closes what it gets."""
    from distributed import Client, LocalCluster

    if scheduler is None:
        # The workers ignore Ctrl-C (the command handles it): SIGINT ignored while they are
        # spawned (a spawned process inherits that), and again by their preload for
        # workers a nanny restarts later.
        # A SIGTERM while they start is taken once the cluster stands (a cluster stopped
        # half-built left Dask's exit with an assertion about a worker still starting),
        # and then closes it.
        client = cluster = None
        try:
            with _ctrl_c_ignored(), _sigterm_deferred():
                cluster = LocalCluster(
                    n_workers=workers,
                    threads_per_worker=1,
                    processes=True,
                    # a free port: the default 8787 taken (another cluster) made Dask warn
                    dashboard_address=":0",
                    preload=["rollerdyn._dask_worker"],
                    # Dask's messages are not the user's: they are about its own shutdown
                    # ("Worker process still alive ... killing", a worker's "Failed to
                    # communicate with scheduler during heartbeat" after a Ctrl-C); a run's
                    # failure is in its row of the summary.
                    silence_logs=logging.CRITICAL,
                )
                client = Client(cluster)
        except KeyboardInterrupt:
            if cluster is not None:
                disconnect(client, cluster, None)
            raise
        return client, cluster
    if isinstance(scheduler, Client):
        return scheduler, None
    check_reachable(str(scheduler), timeout)
    try:
        return Client(scheduler, timeout=timeout), None
    except Exception as err:  # Dask raises OSError, TimeoutError, ValueError, ...
        reason = " ".join(str(err).split()) or type(err).__name__
        raise SweepError(f"scheduler = {scheduler!r}: cannot connect ({reason})") from None


def disconnect(client: Any, cluster: Any, scheduler: Any) -> None:
    """Closes what :func:`connect` opened: the client unless it was the caller's
    ``scheduler``, and the local cluster. Ctrl-C is ignored meanwhile (in the main thread):
    the workers take about 5 s to stop (a worker in the middle of a run is killed after
    4 s), and a Ctrl-C that interrupted the closing would leave it to the interpreter's
    exit, which waited 12 s (measured). Dask's own log lines are held back meanwhile
    (:func:`_dask_logs_silenced`)."""
    with _ctrl_c_ignored(), _dask_logs_silenced():
        if client is not None and client is not scheduler:
            client.close()
        if cluster is not None:
            cluster.close()


@contextlib.contextmanager
def _dask_logs_silenced():
    """Dask's log records below CRITICAL dropped within the block. A local cluster silences
    its loggers' handlers only until the middle of its closing; what it logs after that
    about connections that a stop broke (a ``Batched Comm Closed`` at INFO with a
    ``CommClosedError`` traceback, seen in 2 of 11 sweeps stopped by SIGTERM to their
    process group) is not the user's business: a run's failure is in its row of the
    summary. Every logger of Dask's with a level of its own (``distributed.client`` at
    WARNING) is raised too, and each gets its level back."""
    loggers = [logging.getLogger("distributed")] + [
        logger
        for name, logger in logging.root.manager.loggerDict.items()
        if name.startswith("distributed.")
        and isinstance(logger, logging.Logger)
        and logger.level != logging.NOTSET
    ]
    previous = [logger.level for logger in loggers]
    for logger in loggers:
        logger.setLevel(logging.CRITICAL)
    try:
        yield
    finally:
        for logger, level in zip(loggers, previous, strict=True):
            logger.setLevel(level)


@contextlib.contextmanager
def _ctrl_c_ignored():
    """SIGINT ignored within the block, then its handler as before; nothing changes when
    called outside the main thread (Python handles signals there only), where a Ctrl-C
    reaches the main thread anyway."""
    import threading

    if threading.current_thread() is not threading.main_thread():
        yield
        return
    previous = signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        yield
    finally:
        # None: a handler not installed from Python; Python's own is the nearest
        signal.signal(signal.SIGINT, signal.default_int_handler if previous is None else previous)


@contextlib.contextmanager
def _sigterm_deferred():
    """SIGTERM within the block (the summary being written) taken once it is done: what its
    handler does then (``rollerdyn sweep``'s: stop as Ctrl-C; Python's default: end the
    process) comes when the file is whole. Nothing changes outside the main thread."""
    import threading

    if threading.current_thread() is not threading.main_thread():
        yield
        return
    pending: list[int] = []
    previous = signal.signal(signal.SIGTERM, lambda signum, _: pending.append(signum))
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)
        if pending and callable(previous):
            previous(signal.SIGTERM, None)
        elif pending and previous == signal.SIG_DFL:
            os.kill(os.getpid(), signal.SIGTERM)


# Their names before they were shared, kept for the callers that still use them
# (rollerdyn.bench_cases, tests/test_reliability_cli.py).
_changed = changed
_check_reachable = check_reachable
