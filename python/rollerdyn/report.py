"""One self-contained HTML report of one or more result files (``rollerdyn report``):
reading the results, their summary and the page; the figures are in
:mod:`rollerdyn.report_figures`, the command in :mod:`rollerdyn.cli.report`.

The page holds the inputs of each run (its attributes and the load and speed histories
from the data), a summary table, the paper's figures 8-13 as interactive plotly plots and
an animated view of the roller set that can be scrubbed through time. Every script and
style is inline (plotly.js included once), so the file opens without network access.
All quantities are SI (lengths of the roller-set view in mm, angles of the azimuth plots
in degrees, as their axes say).
"""

from __future__ import annotations

import html
import json
import math
import os
from collections.abc import Iterable
from pathlib import Path

import numpy as np
import xarray as xr

from .report_figures import (
    MAX_FRAMES,
    MAX_POINTS,
    animation_figure,
    azimuth_figures,
    inputs_figure,
    lubrication_figures,
    nanmax,
    pairing_figures,
    pairing_shares,
    ripple_figures,
    time_figures,
)
from .simulation import recorded, ring_speeds

__all__ = [
    "LAST_SHARE",
    "MAX_FRAMES",
    "MAX_POINTS",
    "POWER_MECHANISMS",
    "POWER_COLUMNS",
    "POWER_CONTACTS",
    "POWER_SOURCES",
    "REQUIRED",
    "SUMMARY_ROWS",
    "ReportError",
    "animation_figure",
    "CSS",
    "FigureEmbedder",
    "build_html",
    "check_report_output",
    "html_page",
    "last_outputs",
    "max_abs_srr_inner",
    "open_result",
    "pairing_shares",
    "power_by_contact",
    "power_summary",
    "report",
    "summary",
    "table",
]

LAST_SHARE = 0.2
"""Share of the run (by time, at its end) over which the frictional torque is averaged."""

REQUIRED = (
    "frictional_torque",
    "radial_load",
    "axial_load",
    "ring_speed",
    "ring_position",
    "azimuth",
    "skew",
    "position",
    "srr_inner",
    "inner_normal_force",
    "outer_normal_force",
    "flange_pairing",
    "flange_normal_force",
    "flange_friction_force",
    "flange_axial_force",
)
"""Variables a rollerdyn result must hold for the report."""


class ReportError(ValueError):
    """A file that cannot be reported on: missing, unreadable or not a rollerdyn result."""


# --------------------------------------------------------------------------- reading


def open_result(
    path: Path, required: tuple[str, ...] = REQUIRED, recorded_only: bool = False
) -> xr.Dataset:
    """The result in ``path``, loaded into memory; :class:`ReportError` (one line naming
    the file and what is wrong) if it is missing, unreadable or not a rollerdyn result
    (one of the ``required`` variables or its final time missing, or no outputs), or if
    it lacks required variables because its run did not record them (``solver.outputs``).
    ``recorded_only``: require only those of ``required`` that its run recorded (to
    continue the run, say)."""
    path = Path(path)
    _check_result_path(path)
    ds, reason = _read_netcdf(path)
    if ds is None:
        raise ReportError(f"{path}: not a rollerdyn result (cannot be read as netCDF: {reason})")
    if recorded_only and "outputs" in ds.attrs:
        from .simulation import output_group_of

        recorded = str(ds.attrs["outputs"]).split()
        required = tuple(v for v in required if output_group_of(v) in (None, *recorded))
    missing = [v for v in required if v not in ds]
    if missing and "inner_slice_load" in ds and "time" not in ds.dims:
        raise ReportError(
            f"{path}: is a quasi-static result (rollerdyn statics); this needs a dynamic "
            "run's result (rollerdyn run)"
        )
    _refuse_unrecorded(path, ds, missing)
    if missing or "final_time_s" not in ds.attrs:
        what = _listed(missing) if missing else "attribute final_time_s"
        raise ReportError(f"{path}: not a rollerdyn result (missing {what})")
    not_numbers = [v for v in required if not np.issubdtype(ds[v].dtype, np.number)]
    if not_numbers:
        raise ReportError(
            f"{path}: not a rollerdyn result ({_listed(not_numbers)} not numeric: "
            f"{ds[not_numbers[0]].dtype})"
        )
    if ds.sizes.get("time", 0) == 0:
        raise ReportError(f"{path}: the result holds no outputs (empty time axis)")
    if "roller" in ds.sizes and ds.sizes["roller"] == 0:  # a bearing has at least 3
        raise ReportError(f"{path}: not a rollerdyn result (it holds no rollers)")
    _check_numeric_attributes(path, ds.attrs)
    return ds


def _check_result_path(path: Path) -> None:
    """:class:`ReportError` unless ``path`` names a regular file that is not empty: one line
    for a missing file, a folder, a device or a pipe, a symbolic link loop, a name too long
    for the file system."""
    import stat

    from .paths import name_problem

    try:
        info = os.stat(path)
    except (FileNotFoundError, NotADirectoryError):
        info = None
    except (OSError, ValueError):
        info = None
        problem = name_problem(path)
        if problem is not None:
            raise ReportError(f"{path}: cannot be read as a result file ({problem})") from None
    if info is None:
        raise ReportError(f"{path}: result file not found")
    if stat.S_ISDIR(info.st_mode):
        raise ReportError(f"{path}: is a folder, not a result file")
    if not stat.S_ISREG(info.st_mode):
        raise ReportError(f"{path}: not a regular file (a device or a pipe), not a result file")
    if info.st_size == 0:
        raise ReportError(f"{path}: not a rollerdyn result (the file is empty)")


def _read_netcdf(path: Path) -> tuple[xr.Dataset | None, str]:
    """The netCDF file ``path`` loaded into memory, or None and why it cannot be read.

    A file that h5py opens but h5netcdf cannot (a damaged HDF5 object header) leaves a
    half-made ``h5netcdf.File`` whose destructor fails ("Exception ignored in: File.close
    ... AttributeError"): it is collected here, with that one error not printed, so the
    refusal stays one line. xarray's warning about an HDF5 file without netCDF dimensions
    ("phony_dims") is not printed either: the refusal says what is wrong."""
    import gc
    import sys
    import warnings

    previous = sys.unraisablehook

    def hook(unraisable) -> None:
        where = getattr(unraisable.object, "__module__", "") or ""
        if isinstance(unraisable.exc_value, AttributeError) and where.startswith("h5netcdf"):
            return
        previous(unraisable)

    ds, reason = None, ""
    sys.unraisablehook = hook
    try:
        try:
            with warnings.catch_warnings():
                warnings.filterwarnings("ignore", message=".*phony_dims")
                with xr.open_dataset(path, engine="h5netcdf") as opened:
                    ds = opened.load()
        except Exception as err:  # h5py/h5netcdf raise several kinds for non-HDF5 input
            reason = " ".join(str(err).split()) or type(err).__name__
        if ds is None:  # the failed objects, freed once the exception is gone
            gc.collect()
    finally:
        sys.unraisablehook = previous
    return ds, reason


#: Attributes of a result that the commands read as numbers: name, whether it must be a
#: finite number (a time, a count) or may be NaN (a wall time not measured).
NUMERIC_ATTRIBUTES = (
    ("final_time_s", True),
    ("completed", True),
    ("stats_steps", True),
    ("stats_error_test_failures", True),
    ("stats_total_seconds", False),
)


def _check_numeric_attributes(path: Path, attrs: dict) -> None:
    """:class:`ReportError` naming the first of :data:`NUMERIC_ATTRIBUTES` in ``attrs``
    that is no number (text, a list) or, where it must be, not a finite one."""
    for name, finite in NUMERIC_ATTRIBUTES:
        if name not in attrs:
            continue
        value = attrs[name]
        if isinstance(value, np.ndarray | np.generic):
            value = value.tolist()  # a number, or a list of them, as Python shows it
        number = value[0] if isinstance(value, list) and len(value) == 1 else value
        if not isinstance(number, int | float):
            raise ReportError(
                f"{path}: not a rollerdyn result (attribute {name} = {_short(value)} is not "
                "a number)"
            )
        if finite and not math.isfinite(number):
            raise ReportError(
                f"{path}: not a rollerdyn result (attribute {name} = {_short(value)} is not "
                "a finite number)"
            )


def _refuse_unrecorded(path: Path, ds: xr.Dataset, missing: list[str]) -> None:
    """:class:`ReportError` if ``missing`` variables belong to output groups the run did
    not record (its ``solver.outputs``, attribute ``outputs``), naming them."""
    from .config.solver import OUTPUT_GROUPS
    from .simulation import output_group_of

    if not missing or "final_time_s" not in ds.attrs or "outputs" not in ds.attrs:
        return
    recorded = str(ds.attrs["outputs"]).split()
    needed = {output_group_of(v) for v in missing}
    absent = [g for g in OUTPUT_GROUPS if g in needed and g not in recorded]
    if absent:

        def listed(groups) -> str:
            return "[" + ", ".join(f'"{g}"' for g in groups) + "]"

        wanted = [g for g in OUTPUT_GROUPS if g in recorded or g in absent]
        raise ReportError(
            f"{path}: the run recorded solver.outputs = {listed(recorded)} (and the "
            f"bearing's own outputs); this needs {' and '.join(absent)} as well: run it "
            f"again with solver.outputs = {listed(wanted)}"
        )


def _listed(names: list[str], most: int = 4) -> str:
    """``a, b, c and 5 more``: the first ``most`` names and how many follow."""
    shown = ", ".join(names[:most])
    return shown + (f" and {len(names) - most} more" if len(names) > most else "")


def run_names(paths: list[Path]) -> list[str]:
    """The names that tell runs apart in legends: the files' names without extension, or
    their paths where two of those are the same (``sweep/run_0000`` and ``sweep3/run_0000``);
    bytes of a name that are not UTF-8 shown as ``\\xe9`` (:func:`rollerdyn.paths.printable`),
    which every font and page can show."""
    from .paths import printable

    stems = [printable(Path(p).stem) for p in paths]
    return stems if len(set(stems)) == len(stems) else [printable(p) for p in paths]


def configured_axial_load(ds: xr.Dataset) -> float:
    """The axial load [N] the run's configuration applies once its ramp is up (its record,
    ``config_resolved``), or, without one, the load at the last output: a run stopped
    during the load ramp is labelled with its load case, not with the load reached."""
    from .provenance import recorded_configuration

    recorded = recorded_configuration(ds.attrs) or {}
    value = recorded.get("operating", {}).get("axial_load")
    if isinstance(value, int | float) and not isinstance(value, bool) and math.isfinite(value):
        return float(value)
    return float(ds.axial_load[-1])


def _labels(paths: list[Path], sets: list[xr.Dataset]) -> list[str]:
    return [
        f"{n} (F_a = {configured_axial_load(ds):.0f} N)"
        for n, ds in zip(run_names(paths), sets, strict=True)
    ]


def relative_speed(ds: xr.Dataset) -> np.ndarray:
    """The inner ring's speed relative to the outer ring at every output [rad/s]
    (:func:`rollerdyn.simulation.ring_speeds`)."""
    inner, outer = ring_speeds(ds)
    return inner - outer


def max_abs_srr_inner(ds: xr.Dataset) -> float:
    """Largest |slide-to-roll ratio| at the inner race over the outputs at which the rings
    turn relative to each other (any roller; NaN outputs ignored); NaN if they never do:
    without it the ratio has no meaning (it divides by a rolling speed that is not
    there)."""
    turning = np.abs(relative_speed(ds)) > 0.0
    if not turning.any():
        return float("nan")
    return nanmax(np.abs(ds.srr_inner.values[turning]))


# --------------------------------------------------------------------------- summary

SUMMARY_ROWS = (
    ("mean_torque", "mean bearing frictional torque, last 20 % of the run", "N*m"),
    (
        "mean_power_loss",
        "mean power loss of the contacts and the drag, last 20 % of the run",
        "W",
    ),
    ("power_shares", "of it: flanges / races / roller pairs / drag", "%"),
    (
        "power_mechanisms",
        "of it: sliding / normal forces / rolling resistance / drag",
        "%",
    ),
    (
        "torque_from_power",
        "frictional torque from the power loss (mean power loss / relative ring speed)",
        "N*m",
    ),
    ("max_race_load", "max. roller-race load (inner and outer race)", "N"),
    ("max_flange_force", "max. roller end / flange normal force", "N"),
    ("max_srr_inner", "max. |slide-to-roll ratio| at the inner race", "-"),
    ("final_time", "final time", "s"),
    ("steps", "solver steps (rejected)", "-"),
    ("wall", "wall time", "s"),
    ("threads", "threads of the run", "-"),
    ("status", "status", ""),
)


#: Attributes that hold the configuration's text (shown as text, not in the table).
_CONFIG_TEXTS = ("config_toml", "config_resolved", "config")


def _pretty_json(text: str) -> str:
    """``text`` indented if it is JSON, else as it is."""
    import json

    try:
        return json.dumps(json.loads(text), indent=2)
    except ValueError:
        return text


def last_outputs(ds: xr.Dataset) -> np.ndarray:
    """Where the outputs of ``ds`` lie in the last :data:`LAST_SHARE` of its simulated time
    (the summary's means are over them)."""
    t = ds.time.values
    return t >= t[-1] - LAST_SHARE * (t[-1] - t[0])


def summary(ds: xr.Dataset) -> dict:
    """The summary quantities of one result (SI), keyed as :data:`SUMMARY_ROWS`."""
    last = last_outputs(ds)
    a = ds.attrs
    status = "completed" if int(a.get("completed", 0)) else "unfinished"
    if "error" in a:
        status += f": {a['error']}"
    # NaN (shown n/a) for what the run did not record (solver.outputs)
    rollers = recorded(ds, "rollers")
    return {
        "mean_torque": float(np.mean(ds.frictional_torque.values[last])),
        **power_summary(ds, last),
        "max_race_load": max(
            nanmax(ds.inner_normal_force.values), nanmax(ds.outer_normal_force.values)
        )
        if rollers
        else math.nan,
        "max_flange_force": nanmax(ds.flange_normal_force.values)
        if recorded(ds, "flanges")
        else math.nan,
        "max_srr_inner": max_abs_srr_inner(ds) if rollers else math.nan,
        "final_time": float(a["final_time_s"]),
        "steps": (int(a.get("stats_steps", -1)), int(a.get("stats_error_test_failures", 0))),
        "wall": float(a.get("stats_total_seconds", float("nan"))),
        # a result written before the attribute: not known
        "threads": float(a.get("threads", float("nan"))),
        "status": status,
    }


#: The power losses a result records, by mechanism (the contacts' sliding, normal forces
#: and rolling resistance; the drag): (share's name, variables).
POWER_MECHANISMS = (
    ("sliding", ("sliding_power_loss",)),
    ("normal forces", ("normal_power_loss",)),
    ("rolling resistance", ("rolling_power_loss",)),
    ("drag", ("drag_power_loss",)),
)

#: The power losses a result records, by where they arise: (share's name, variables).
POWER_SOURCES = (
    ("flanges", ("flange_power_loss",)),
    ("races", ("inner_power_loss", "outer_power_loss")),
    ("roller pairs", ("roller_roller_power_loss",)),
    ("drag", ("drag_power_loss",)),
)


def power_summary(ds: xr.Dataset, last: np.ndarray) -> dict:
    """The mean power loss over the outputs ``last`` [W], its shares by source [%] (as
    text) and the torque it means at the mean ring speed [N*m]; NaN (and "n/a") for a
    result written before power losses were recorded, and the torque NaN where the ring
    stands. In steady running the mean power loss is the friction power, torque times ring
    speed; it is the steadier estimate of the two where the torque is small
    (docs/dynamics.md, "Where the power goes")."""
    if "power_loss" not in ds:
        return {
            "mean_power_loss": math.nan,
            "power_shares": "n/a",
            "power_mechanisms": "n/a",
            "torque_from_power": math.nan,
        }
    power = float(np.mean(ds.power_loss.values[last]))

    def shares(groups) -> str:
        if any(n not in ds for _, names in groups for n in names):
            return "n/a"
        parts = [sum(_mean_total(ds, n, last) for n in names) for _, names in groups]
        return " / ".join(f"{100.0 * x / power:.1f}" if power > 0.0 else "n/a" for x in parts)

    speed = abs(float(np.mean(relative_speed(ds)[last])))
    return {
        "mean_power_loss": power,
        "power_shares": shares(POWER_SOURCES),
        "power_mechanisms": shares(POWER_MECHANISMS),
        "torque_from_power": power / speed if speed != 0.0 else math.nan,
    }


def _mean_total(ds: xr.Dataset, name: str, last: np.ndarray) -> float:
    """The mean over the outputs ``last`` of variable ``name`` summed over its rollers
    and flanges."""
    values = ds[name].values[last]
    return float(np.mean(values.reshape(values.shape[0], -1).sum(axis=1)))


#: The contacts' power losses and their parts: (source, total, sliding part, rolling
#: resistance part or None where the contact has none; the normal forces' part is the rest).
POWER_CONTACTS = (
    ("inner race", "inner_power_loss", "inner_sliding_power_loss", "inner_rolling_power_loss"),
    ("outer race", "outer_power_loss", "outer_sliding_power_loss", "outer_rolling_power_loss"),
    (
        "roller pairs",
        "roller_roller_power_loss",
        "roller_roller_sliding_power_loss",
        "roller_roller_rolling_power_loss",
    ),
    ("flanges", "flange_power_loss", "flange_sliding_power_loss", None),
)

#: The columns of :func:`power_by_contact`'s rows.
POWER_COLUMNS = ("sliding", "normal forces", "rolling resistance", "total")


def power_by_contact(ds: xr.Dataset, last: np.ndarray) -> list[tuple[str, list[float]]] | None:
    """Where the power goes, contact kind by contact kind: for the inner race, the outer
    race, the roller pairs, the flanges, the drag and all of them, the mean over the
    outputs ``last`` [W] of the power taken by sliding, by the normal forces (damping,
    squeeze, the films' load; in steady running their elastic part averages out), by the
    rolling resistance, and in all (:data:`POWER_COLUMNS`; NaN where a mechanism does not
    apply). None for a result written before the contacts' parts were recorded."""
    needed = [n for row in POWER_CONTACTS for n in row[1:] if n] + ["drag_power_loss"]
    if any(n not in ds for n in needed):
        return None
    rows = []
    for name, total_name, sliding_name, rolling_name in POWER_CONTACTS:
        total = _mean_total(ds, total_name, last)
        sliding = _mean_total(ds, sliding_name, last)
        rolling = _mean_total(ds, rolling_name, last) if rolling_name else 0.0
        rows.append((name, [sliding, total - sliding - rolling, rolling, total]))
    drag = _mean_total(ds, "drag_power_loss", last)
    rows.append(("drag", [math.nan, math.nan, math.nan, drag]))
    sums = [float(np.nansum([r[1][k] for r in rows])) for k in range(len(POWER_COLUMNS))]
    rows.append(("all", sums))
    return rows


def _fmt(key: str, value) -> str:
    if key == "steps":
        return "n/a" if value[0] < 0 else f"{value[0]} ({value[1]})"
    if isinstance(value, str):
        return value
    if not math.isfinite(value):
        return "n/a"
    return f"{value:.4g}"


# --------------------------------------------------------------------------- page
# The page's parts (style, tables, figures, the document around them) are shared with the
# study's report (rollerdyn.study.report_page).

#: The pages' style sheet.
CSS = """
body { font-family: system-ui, -apple-system, "Segoe UI", Roboto, sans-serif; margin: 0;
       color: #222; background: #fafafa; }
main { max-width: 1200px; margin: 0 auto; padding: 1em 2em 4em; }
h1 { font-size: 1.6em; } h2 { border-bottom: 1px solid #ccc; padding-bottom: .2em;
       margin-top: 2em; } h3 { margin-top: 1.5em; }
table { border-collapse: collapse; margin: .5em 0 1em; background: #fff; }
th, td { border: 1px solid #ddd; padding: .3em .7em; text-align: left; vertical-align: top; }
th { background: #f0f0f0; } td.num { text-align: right; font-variant-numeric: tabular-nums; }
pre { background: #fff; border: 1px solid #ddd; padding: .8em; overflow-x: auto; }
.figure { background: #fff; border: 1px solid #e3e3e3; margin: 1em 0; padding: .3em; }
.note { color: #555; font-size: .92em; } .warn { color: #a40000; }
nav a { margin-right: 1em; }
"""


def table(header: list[str], rows: list[list[str]], numeric_from: int = 1) -> str:
    """An HTML table of ``rows`` (cells escaped), columns from ``numeric_from`` on set
    right-aligned as numbers."""
    out = ["<table><thead><tr>"]
    out += [f"<th>{html.escape(h)}</th>" for h in header]
    out.append("</tr></thead><tbody>")
    for row in rows:
        out.append("<tr>")
        for j, cell in enumerate(row):
            cls = ' class="num"' if j >= numeric_from else ""
            out.append(f"<td{cls}>{html.escape(str(cell))}</td>")
        out.append("</tr>")
    out.append("</tbody></table>")
    return "".join(out)


class FigureEmbedder:
    """Turns plotly figures into ``<div class="figure">`` snippets of a page, with
    plotly.js inline in the first one only (the page opens without network access)."""

    def __init__(self) -> None:
        self.js_included = False

    def __call__(self, fig, key: str) -> str:
        import plotly.io as pio

        snippet = pio.to_html(
            fig,
            config={"displaylogo": False, "responsive": True},
            auto_play=False,
            include_plotlyjs=not self.js_included,
            full_html=False,
            div_id=f"plot-{key}",
        )
        self.js_included = True
        return f'<div class="figure">{snippet}</div>'


def html_page(title: str, body: list[str], css: str = "") -> str:
    """The whole page: ``title`` (text, escaped here), :data:`CSS` and ``css``, ``body``
    (HTML parts) followed by a note of the plotly version and the script that marks the
    page with its number of plots once every figure's script has run (used by the tests)."""
    import plotly

    footer = [
        f'<p class="note">Made by rollerdyn with plotly {plotly.__version__} (plotly.js '
        "inline: the page needs no network access).</p>",
        "<script>document.body.setAttribute('data-plots', "
        "String(document.querySelectorAll('.js-plotly-plot').length));</script>",
    ]
    return (
        '<!DOCTYPE html>\n<html lang="en"><head><meta charset="utf-8">'
        '<meta name="viewport" content="width=device-width, initial-scale=1">'
        f'<meta name="generator" content="{REPORT_GENERATOR}">'
        f"<title>{html.escape(title)}</title><style>{CSS}{css}</style></head>"
        f"<body><main>{''.join([*body, *footer])}</main></body></html>\n"
    )


def _attr_text(value) -> str:
    if isinstance(value, np.ndarray):
        return json.dumps(value.tolist())
    if isinstance(value, np.generic):
        return str(value.item())
    return str(value)


def build_html(paths: list[Path], max_frames: int = MAX_FRAMES) -> str:
    """The report page for the results in ``paths`` (see :func:`report`)."""
    paths = [Path(p) for p in paths]
    if not paths:
        raise ReportError("no result files given")
    sets = [open_result(p, recorded_only=True) for p in paths]
    labels = _labels(paths, sets)
    embed = FigureEmbedder()
    body = []
    names = ", ".join(html.escape(str(p)) for p in paths)
    body.append(f"<h1>rollerdyn report</h1><p>Results: {names}</p>")
    body.append(
        '<nav><a href="#summary">summary</a><a href="#statics">quasi-static</a>'
        '<a href="#lubrication">lubrication</a>'
        '<a href="#ripple">ripple</a>'
        '<a href="#inputs">inputs</a>'
        '<a href="#figures">figures</a><a href="#animation">roller set</a></nav>'
    )

    # Summary.
    body.append('<h2 id="summary">Summary</h2>')
    values = [summary(ds) for ds in sets]
    rows = []
    for key, text, unit in SUMMARY_ROWS:
        rows.append([text, unit] + [_fmt(key, v[key]) for v in values])
    body.append(table(["quantity", "unit", *labels], rows, numeric_from=2))
    body.append(
        f'<p class="note">Mean torque over the last {LAST_SHARE:.0%} of each run\'s simulated '
        "time; maxima over every output, roller and contact. Slide-to-roll ratio: eq. 49 of "
        "the paper, over the outputs at which the inner ring turns ('n/a' if it never "
        "does: the ratio has no meaning before). Steps: accepted solver steps (rejected "
        "in brackets); wall time: the run's, on the threads it used (the row below).</p>"
    )

    body += _power_section(labels, sets)
    body += _statics_section(labels, sets)
    body += _lubrication_section(labels, sets, embed)
    body += _ripple_section(labels, sets, embed)

    # Inputs.
    body.append('<h2 id="inputs">Inputs</h2>')
    for p, label, ds in zip(paths, labels, sets, strict=True):
        body.append(f"<h3>{html.escape(label)}: {html.escape(str(p))}</h3>")
        if "error" in ds.attrs:
            body.append(
                f'<p class="warn">The run stopped early: {html.escape(ds.attrs["error"])}</p>'
            )
        if ds.attrs.get("forced"):
            body.append(f'<p class="warn">{html.escape(str(ds.attrs["forced"]).capitalize())}</p>')
        plain = [
            [k, _attr_text(v)]
            for k, v in ds.attrs.items()
            if not k.startswith("stats_") and k not in _CONFIG_TEXTS
        ]
        stats = [[k[6:], _attr_text(v)] for k, v in ds.attrs.items() if k.startswith("stats_")]
        body.append(table(["attribute", "value"], plain, numeric_from=9))
        if stats:
            body.append("<details><summary>solver statistics</summary>")
            body.append(table(["statistic", "value"], stats, numeric_from=1))
            body.append("</details>")
        text = next(
            (ds.attrs[k] for k in ("config_toml", "config") if isinstance(ds.attrs.get(k), str)),
            "",
        )
        resolved = ds.attrs.get("config_resolved")
        if text:
            body.append("<details open><summary>configuration (TOML)</summary>")
            body.append(f"<pre>{html.escape(text)}</pre></details>")
        elif isinstance(resolved, str) and resolved:
            body.append(
                "<details open><summary>configuration (resolved to SI; built in Python, "
                "no TOML text)</summary>"
            )
            body.append(f"<pre>{html.escape(_pretty_json(resolved), quote=False)}</pre></details>")
        else:
            body.append(
                '<p class="note">The result file holds no configuration text; the '
                "attributes above and the load and speed histories below are what it "
                "records of the inputs.</p>"
            )
    body.append(embed(inputs_figure(labels, sets), "inputs"))

    # Figures.
    body.append('<h2 id="figures">Figures of the paper (sect. 5.2)</h2>')
    body.append(
        '<p class="note">Interactive: zoom by dragging, double-click to reset, click a '
        "legend entry to hide a run. Azimuth plots use the outputs at (at least 99 % of) "
        "full speed of the rings that turn, or the whole run if neither turns.</p>"
    )
    for key, fig in time_figures(labels, sets):
        body.append(embed(fig, key))
    for key, fig in pairing_figures(labels, sets):
        body.append(embed(fig, key))
    for key, fig in azimuth_figures(labels, sets):
        body.append(embed(fig, key))

    # Animation.
    body.append('<h2 id="animation">Roller set over time</h2>')
    body.append(
        '<p class="note">Seen along the bearing axis: roller centres (marker size and colour: '
        "roller-inner race normal force), roller 0 as a diamond, a red line along the orbit "
        "for the skew (its length scaled to the largest skew of the run, pointing forward "
        "along increasing azimuth for positive skew). Drag the slider to scrub through time; "
        "frames are evenly subsampled outputs.</p>"
    )
    for j, (label, ds) in enumerate(zip(labels, sets, strict=True)):
        if not recorded(ds, "rollers"):
            body.append(f"<h3>{html.escape(label)}: the run did not record its rollers</h3>")
            continue
        fig, n = animation_figure(ds, max_frames)
        body.append(f"<h3>{html.escape(label)} ({n} frames of {ds.sizes['time']} outputs)</h3>")
        body.append(embed(fig, f"animation{j}"))
    return html_page("rollerdyn report: " + ", ".join(str(p) for p in paths), body)


def _contact_tables(
    labels: list[str], sets: list[xr.Dataset], rows_of, group: str, caption: str, header
) -> list[str]:
    """One table per result of the rows ``rows_of(ds, last outputs)`` gives ((name,
    values) each), headed ``header`` and introduced by the result's label and
    ``caption``; a note instead for a result without them (``rows_of`` None: an older
    file, or ``solver.outputs`` without ``group``)."""
    out = []
    for label, ds in zip(labels, sets, strict=True):
        rows = rows_of(ds, last_outputs(ds))
        if rows is None:
            out.append(
                f'<p class="note">{html.escape(label)}: not recorded (an older file, or '
                f'solver.outputs without "{group}").</p>'
            )
            continue
        cells = [[name, *(_fmt("", v) for v in values)] for name, values in rows]
        out.append(f"<p>{html.escape(label)}: {caption}</p>")
        out.append(table(header, cells))
    return out


def _power_section(labels: list[str], sets: list[xr.Dataset]) -> list[str]:
    """The page's tables of :func:`power_by_contact`, one per result that records it."""
    out = ['<h3 id="power">Where the power goes</h3>']
    caption = f"mean power [W], last {LAST_SHARE:.0%} of the run"
    header = ["contact", *POWER_COLUMNS]
    out += _contact_tables(labels, sets, power_by_contact, "power", caption, header)
    out.append(
        '<p class="note">Each contact\'s power is minus what its forces deliver to its two '
        "bodies; sliding is traction, boundary friction and film shear, the normal forces' "
        "part their damping, squeeze and film load (with the elastic energy's rate, which "
        "averages out), and the rolling resistance the rest.</p>"
    )
    return out


def _statics_section(labels: list[str], sets: list[xr.Dataset]) -> list[str]:
    """The page's tables of :func:`rollerdyn.crosscheck.beside_statics`, one per result:
    the run beside the quasi-static estimate at its final loads and speed."""
    from .crosscheck import beside_statics

    out = ['<h3 id="statics">Beside the quasi-static estimate</h3>']
    for label, ds in zip(labels, sets, strict=True):
        rows = beside_statics(ds, last_outputs(ds))
        if isinstance(rows, str):
            out.append(f'<p class="note">{html.escape(label)}: {html.escape(rows)}</p>')
            continue
        cells = [
            [r.label, r.unit, _fmt("", r.run), _fmt("", r.estimate), _ratio(r.run, r.estimate)]
            for r in rows
        ]
        out.append(
            f"<p>{html.escape(label)}: the run (means over its last {LAST_SHARE:.0%}) and the "
            "quasi-static estimate at its final loads and speed</p>"
        )
        out.append(
            table(
                ["quantity", "unit", "run", "quasi-static", "run / quasi-static"],
                cells,
                numeric_from=2,
            )
        )
    out.append(
        '<p class="note">The estimate is <code>rollerdyn statics</code> of the run\'s own '
        "configuration: the equilibrium without friction, and its friction of steady "
        "rolling with each roller spinning where its moments balance (docs/statics.md). "
        "What the dynamics add shows in the difference: the rollers' skew, their ends' "
        "positions on the flanges, the neighbours' friction on the unloaded rollers; a "
        "large one in the loads says the run is not steady at its end.</p>"
    )
    return out


def _ratio(run: float, estimate: float) -> str:
    if not (math.isfinite(run) and math.isfinite(estimate)) or estimate == 0.0:
        return "n/a"
    return f"{run / estimate:.3g}"


def _lubrication_section(labels: list[str], sets: list[xr.Dataset], embed) -> list[str]:
    """The page's tables of :func:`rollerdyn.lubrication.lubrication_by_contact`, one per
    result that records it, and the specific film thickness over the azimuth."""
    from .lubrication import LUBRICATION_COLUMNS, lubrication_by_contact

    out = ['<h3 id="lubrication">Lubrication at the contacts</h3>']
    header = ["contact", *(f"{text} [{unit}]" for text, unit in LUBRICATION_COLUMNS)]
    caption = f"the last {LAST_SHARE:.0%} of the run"
    out += _contact_tables(labels, sets, lubrication_by_contact, "lubrication", caption, header)
    out.append(
        '<p class="note">Per contact and output, where the contact\'s pressure is highest '
        "(its most loaded slice, or the flange's contact ellipse): the maximum (Hertz) "
        "pressure p0, the central film thickness h_c and the specific film thickness "
        "Lambda = h_c / sigma (sigma the composite roughness of surfaces.*), which sorts the "
        "contacts in contact into boundary (Lambda &lt; 1), mixed and full film (Lambda "
        "&ge; 3) lubrication; the shares count each contact at each output once. At the "
        "flanges p0 is that of the paper's Brewe-Hamrock ellipse, which at B1's nearly flat "
        "roller ends lies 9-13 % below the exact Hertz solution (docs/dynamics.md, "
        '"Lubrication at the contacts").</p>'
    )
    for key, fig in lubrication_figures(labels, sets):
        out.append(embed(fig, key))
    return out


def _ripple_section(labels: list[str], sets: list[xr.Dataset], embed) -> list[str]:
    """The page's table of :func:`rollerdyn.ripple.ripple` and its spectra."""
    from .ripple import RIPPLE_ROWS, ripple

    ripples = [ripple(ds) for ds in sets]
    out = ['<h3 id="ripple">Vibration and torque ripple at the roller pass frequency</h3>']
    rows = [
        [text, unit, *(_fmt("", factor * r[key]) for r in ripples)]
        for key, text, unit, factor in RIPPLE_ROWS
    ]
    out.append(table(["quantity", "unit", *labels], rows, numeric_from=2))
    for label, r in zip(labels, ripples, strict=True):
        if r["note"]:
            out.append(f'<p class="note">{html.escape(label)}: {html.escape(r["note"])}</p>')
    out.append(
        '<p class="note">Over the outputs at full speed: the rollers pass the load zone '
        "one by one, so the inner ring's equilibrium repeats every roller pitch and the "
        "ring vibrates, and the torque ripples, at Z f_c and its harmonics (varying "
        "compliance; amplitudes of a Hann-windowed Fourier sum at those frequencies, of the "
        "values less their linear trend). docs/dynamics.md compares them with the "
        "quasi-static ring over one roller pitch.</p>"
    )
    for key, fig in ripple_figures(labels, sets, ripples):
        out.append(embed(fig, key))
    return out


def report(paths, out, max_frames: int = MAX_FRAMES) -> Path:
    """Writes one self-contained HTML report of the result files ``paths`` (netCDF written
    by ``rollerdyn run``) to ``out`` and returns its path. Raises :class:`ReportError` for
    a missing file or one that is not a rollerdyn result, for ``out`` naming one of them,
    a folder or an existing file other than an earlier report (which is replaced), and
    for arguments of the wrong kind (``paths`` of files, ``max_frames`` a
    whole number of at least 1), before the work. The page is written through a
    temporary file (a failed write leaves an earlier report as it was); if another
    program created ``out`` meanwhile, the page goes to a free name beside it
    (``report-2.html``): the path returned is where it went."""
    from .paths import OutputPathError, same_file

    if isinstance(paths, str | os.PathLike):
        paths = [paths]
    elif not isinstance(paths, xr.Dataset | bytes) and isinstance(paths, Iterable):
        paths = list(paths)  # a generator's items, read once (its check used them up)
    if not isinstance(paths, list) or not all(isinstance(p, str | os.PathLike) for p in paths):
        raise ReportError(
            f"paths = {_short(paths)}: must be result files' paths (a path or a list of them)"
        )
    if not isinstance(out, str | os.PathLike):
        raise ReportError(f"out = {out!r}: must be the report's file path")
    whole = isinstance(max_frames, int | np.integer) and not isinstance(max_frames, bool)
    if not (whole and max_frames >= 1):
        raise ReportError(f"max_frames = {max_frames!r}: must be a whole number, at least 1")
    paths, out = [Path(p) for p in paths], Path(out)
    refuse_repeats(paths)
    if out.is_dir():
        raise ReportError(f"-o {out}: is a folder; name the report's file in it")
    for p in paths:
        if same_file(out, p):
            raise ReportError(f"-o {out}: is the result file {p}, an input; choose another")
    try:
        out.parent.mkdir(parents=True, exist_ok=True)  # the API makes the report's folder
    except OSError as err:
        raise ReportError(f"-o {out}: cannot make its folder ({err.strerror})") from None
    try:
        check_report_output(paths, out)
    except OutputPathError as err:
        raise ReportError(str(err)) from None
    page = build_html(paths, max_frames=max_frames)
    return _write_page(out, page)


def refuse_repeats(paths: list[Path]) -> None:
    """:class:`ReportError` for a result given twice (it gave two identical columns under
    one label)."""
    from .paths import repeated_file

    repeat = repeated_file(paths)
    if repeat is not None:
        a, b = repeat
        also = "" if str(a) == str(b) else f" (also as {b})"
        raise ReportError(f"{a}: given twice{also}; give each result once")


def _write_page(out: Path, page: str) -> Path:
    """Writes ``page`` to ``out`` atomically (:func:`rollerdyn.paths.write_atomically`): a
    failed write (a full disk) leaves an earlier report as it was and no partial page. A
    file that appeared at ``out`` since the checks is replaced only if it is an earlier
    report; else the page goes to a free name beside it (``report-2.html``), which is
    returned. Bytes of file names that are not UTF-8 are shown as ``\\xe9``."""
    from .paths import printable, write_atomically

    out.parent.mkdir(parents=True, exist_ok=True)
    return write_atomically(out, printable(page), replace=is_report_page)


#: The page's generator (``<meta name="generator">``): what marks an earlier report.
REPORT_GENERATOR = "rollerdyn"


def _short(value: object) -> str:
    """``repr(value)`` on one line, cut to 60 characters, for messages."""
    text = " ".join(repr(value).split())
    return text if len(text) <= 60 else text[:57] + "..."


def is_report_page(path: Path) -> bool:
    """Whether ``path`` is a page rollerdyn wrote: its head names rollerdyn as generator, or
    (pages before that tag) its footer says "Made by rollerdyn"."""
    try:
        with open(path, "rb") as f:
            head = f.read(4096)
            f.seek(max(0, f.seek(0, 2) - 65536))
            tail = f.read()
    except OSError:
        return False
    return (
        f'<meta name="generator" content="{REPORT_GENERATOR}">'.encode() in head
        or b'<p class="note">Made by rollerdyn with plotly' in tail
    )


def check_report_output(results: list[Path], output: Path) -> Path:
    """Checks before any work that ``output`` may take the report (see
    :mod:`rollerdyn.paths`): not an input, its folder there and writable, and if it
    exists an earlier report (a page rollerdyn wrote, whatever its name's extension), not a
    result, a page of someone else's or any other file."""
    from .paths import check_name, check_output_file

    output = check_name(Path(output), "-o")
    replaceable = output.is_file() and is_report_page(output)
    return check_output_file(
        output,
        "-o",
        inputs=[(f"the result file {r}", r) for r in results],
        overwrite=replaceable,
        hint="; only an earlier report of rollerdyn is replaced: choose another name",
        reserve=0,  # written through paths.write_atomically, which keeps its name short
    )
