"""``rollerdyn statics``: the quasi-static equilibrium of a configuration's load case, or
of a sweep of load cases (:mod:`rollerdyn.statics`), printed as a table, written as netCDF
and drawn as curves."""

from __future__ import annotations

import math
import shutil
from pathlib import Path
from typing import Annotated

import numpy as np
import typer
from rich.table import Table

from ..paths import check_output_file, same_file
from .common import (
    checked,
    console,
    error,
    load,
    refuse,
    refuse_overlap,
    say,
    sigterm_as_interrupt,
)


def statics_command(
    config: Annotated[Path, typer.Argument(help="Bearing configuration (TOML).", metavar="CONFIG")],
    sets: Annotated[
        list[str] | None,
        typer.Option(
            "--set",
            metavar="PATH=VALUES",
            help="Vary the load case: PATH=START:STOP:COUNT or PATH=VALUE[,VALUE...], PATH "
            "one of operating.radial_load, operating.axial_load [N], "
            "operating.inner_ring_speed, operating.outer_ring_speed, "
            "operating.carrier_speed, "
            "inner_ring.misalignment, moment_y, "
            "moment_z [N*m], roller_set_phase (the roller set turned from roller 0 "
            "under the load; over one pitch, 360 deg / Z, the ring's equilibrium shows the "
            'varying compliance). Values carry a unit ("3000 rpm", "0.05 deg"; speeds and '
            "angles must, but for 0) or are bare numbers in the SI unit in brackets: --set "
            'operating.radial_load="0:10000:101"; quoted as in the configuration file or not. '
            "Any other configuration path varies the bearing itself (a design sweep), with "
            "values written as in the file, as 'rollerdyn sweep --set' takes them: --set "
            'geometry.diametral_clearance="0 um,10 um,20 um", --set '
            'operating.temperature="40 degC:100 degC:4" (each end with its unit); not '
            "geometry.roller_count or geometry.roller.slices. "
            "One value changes the case; more make a sweep (the cartesian product of all "
            "--set, the bearing's values varying slowest). Default: the configuration's "
            "loads and speed after its ramps.",
        ),
    ] = None,
    output: Annotated[
        Path | None,
        typer.Option("--output", "-o", help="Write the results to this netCDF file (SI units)."),
    ] = None,
    plot: Annotated[
        Path | None,
        typer.Option(
            "--plot",
            help="Draw the load distribution (one case) or the roller load, ring "
            "displacement and life curves (a sweep) to this PNG file.",
        ),
    ] = None,
    contamination: Annotated[
        float,
        typer.Option(
            help="ISO 281 contamination factor e_C for the modified life L_nmr, 0 ... 1 "
            "(default 0.5: normal cleanliness)."
        ),
    ] = 0.5,
    per_roller: Annotated[
        bool,
        typer.Option(
            "--per-roller",
            help="With one case, also print a table of every roller: azimuth [deg], its "
            "loads at the inner and outer race [N], its ends' forces on the four flanges "
            "[N], its tilt [mrad], its skew and slip in steady rolling [mrad, %] and the "
            "roller train's "
            "force on the next roller [N].",
        ),
    ] = False,
    overwrite: Annotated[
        bool, typer.Option(help="Replace existing --output / --plot files.")
    ] = False,
) -> None:
    """Quasi-static analysis: load distribution, stiffness and rating life.

    The inner ring's and every roller's equilibrium under the case's radial load (along
    -y), axial load (+x), tilting moment or prescribed misalignment, at its speed
    (centrifugal forces), with the dynamic model's contact laws: race slices (eq. 11) and
    roller end / flange contacts by the semi-analytical detector, with the configuration's
    surfaces.flange_law (the paper's point contact or the distributed overlap). Prints the ring's
    displacement, the heaviest roller, the largest flange force and its height above the
    raceway, the friction of steady rolling (the dynamic model's laws at the equilibrium,
    each roller spinning where its friction moments balance: a quick estimate) and the
    rollers' slip there (docs/statics.md), the load zone, the stiffness, the static safety
    (ISO 76 s_0 = C_0r / P, P the radial load carried: F_r with the inner ring's weight,
    and by stress the load factor to 4 000 MPa at the races and at the flanges) and the
    rating lives (ISO 281 L_10 at P, ISO/TS 16281 L_10r and L_nmr, in 10^6 revolutions);
    below the table, where the roller ends slide on the flanges slower than
    surfaces.boundary_friction.smoothing_speed, that the friction is underestimated. A
    sweep keeps its cases without equilibrium as NaN with their message, writes
    everything, and then exits with status 1; one case without
    equilibrium exits with status 1 naming the load level reached and the residual.
    """
    from .. import statics as st

    if not 0.0 <= contamination <= 1.0:
        raise refuse(f"--contamination = {contamination}: must lie in [0, 1] (ISO 281 e_C)")
    if output is not None and plot is not None and same_file(output, plot):
        raise refuse(f"-o {output} and --plot {plot} name the same file; give two files")
    if plot is not None:
        _check_image_format(plot)
    for option, path in (("-o", output), ("--plot", plot)):
        if path is not None:
            checked(
                check_output_file,
                path,
                option,
                inputs=[("the configuration file", config)],
                overwrite=overwrite,
                hint="; pass --overwrite to replace it",
                reserve=0,  # written through a short temporary name (_save, _write)
            )
    grid, design = _split_sets(sets or [])
    for path, (text, _) in list(grid.items()):
        try:
            grid[path] = (text, st.parse_range(path, text))
        except st.StaticsError as err:
            raise refuse(err) from None
    changes = {p: v[0] for p, v in design.items() if len(v) == 1}
    checked_ranges = _check_ranges(config, changes, grid)
    cfg = load(config, {**changes, **_case_values(grid)})
    if not checked_ranges:
        _check_ranges(config, changes, grid, cfg)
    loads = {p: values for p, (_, values) in grid.items()}
    try:
        st.check_grid_size({p: len(v) for p, v in {**design, **loads}.items()})
        if any(len(v) > 1 for v in design.values()):
            st.design_configs(config, design, st.case_config_values(loads))
    except st.StaticsError as err:
        raise refuse(err) from None
    grid = loads
    moments = [p for p in ("moment_y", "moment_z") if any(grid.get(p, []))]
    if moments and "inner_ring.misalignment" in grid:
        raise refuse(
            f"--set {moments[0]} with --set inner_ring.misalignment: a prescribed misalignment "
            "holds the ring's tilt, so a tilting moment would act on nothing; give one or the "
            "other"
        )
    single = all(len(v) == 1 for v in [*grid.values(), *design.values()])
    if per_roller and not single:
        raise refuse(
            "--per-roller: prints the rollers of one case; a sweep's are in its --output "
            "file (variables over case and roller)"
        )
    terminated: list[int] = []
    with sigterm_as_interrupt(terminated):
        ds = _solve(
            config, cfg, (grid, design), per_roller, contamination, output, terminated, overwrite
        )
    _write(ds, output, plot, overwrite)
    if not single and ds.attrs["failed_cases"]:
        raise typer.Exit(1)  # as a sweep with a failed run: written, and said by the status


def _solve(config, cfg, cases, per_roller, contamination, output, terminated, overwrite=False):
    """The case or the sweep (``cases``: the load-case grid and the design's values)
    solved and printed; a sweep stopped by Ctrl-C or SIGTERM keeps its cases solved
    (:func:`_keep_interrupted`)."""
    from .. import statics as st

    grid, design = cases
    single = all(len(v) == 1 for v in [*grid.values(), *design.values()])
    try:
        if single:
            values = {st.STATIC_FIELDS[p][0]: v[0] for p, v in grid.items()}
            moment = None
            if "moment_y" in values or "moment_z" in values:
                moment = (values.pop("moment_y", 0.0), values.pop("moment_z", 0.0))
            ds = st.statics(cfg, moment=moment, contamination=contamination, **values)
            _print_case(ds)
            if per_roller:
                _print_rollers(ds)
        else:
            with console.status("solving the load cases"):
                if any(len(v) > 1 for v in design.values()):
                    ds = st.statics_sweep(config, grid, design=design, contamination=contamination)
                else:
                    ds = st.statics_sweep(cfg, grid, contamination=contamination)
            _print_sweep(ds)
    except st.StaticsError as err:
        error(f"rollerdyn statics: {err}")
        raise typer.Exit(1) from None
    except st.StaticsInterrupted as stop:
        _keep_interrupted(stop, output, 143 if terminated else 130, overwrite)
    return ds


def _write(ds, output: Path | None, plot: Path | None, overwrite: bool = False) -> None:
    """The result written to ``output`` and drawn to ``plot`` (either may be None), each
    through a temporary file renamed into place once whole (:func:`_save`): a failed write
    (a full disk, a reader's lock) leaves an earlier file as it was and exits with status 1
    after one line saying where the result was kept."""
    failed = False
    for path, option, verb, store in (
        (output, "-o", "write", _save),
        (plot, "--plot", "draw", _draw),
    ):
        if path is None:
            continue
        written, problem = store(ds, path, overwrite)
        if written is None:
            error(f"{option} {path}: could not {verb} the result ({problem})")
            failed = True
        else:
            say(_wrote(path, written))
    if failed:
        raise typer.Exit(1)


def _wrote(path: Path, written: Path) -> str:
    """The line saying that ``path`` was written (to ``written``, a free name beside it, if
    another program created ``path`` while the cases were solved)."""
    if written == path:
        return f"wrote {path}"
    return (
        f"wrote {written}: {path} was created by another program while the cases were "
        "solved; it is kept as it is"
    )


def _save(ds, output: Path, overwrite: bool) -> tuple[Path | None, str]:
    """Writes ``ds`` to ``output`` as netCDF: encoded in memory first (HDF5 that runs out
    of disk while writing a file prints tracebacks and can crash the process), then written
    to a temporary file and renamed into place (:func:`rollerdyn.paths.write_atomically`;
    an existing file is replaced only with ``overwrite``, otherwise the result goes to a
    free name beside it). Returns the file written and "", or None and what went wrong,
    which names the file the result was kept in instead, or says that it was lost."""
    from ..paths import keep_elsewhere, write_atomically

    try:
        data = ds.to_netcdf(engine="h5netcdf")
    except Exception as err:  # h5py raises RuntimeError, ValueError, OSError
        reason = " ".join(str(err).split()) or type(err).__name__
        return None, f"it cannot be encoded as netCDF: {reason}; the result is lost"
    existed = output.exists()
    try:
        return write_atomically(output, data, replace=overwrite), ""
    except OSError as err:
        left = "the earlier file is unchanged" if existed else "nothing was written there"
        kept = keep_elsewhere(data, "rollerdyn-statics-")
        return None, f"{err.strerror or err}; {left}; {kept}"


def _draw(ds, plot: Path, overwrite: bool) -> tuple[Path | None, str]:
    """Draws ``ds`` to ``plot`` through a temporary file of the same extension beside it,
    renamed into place once whole (:func:`rollerdyn.paths.place_file`); returns the file
    written and "", or None and what went wrong."""
    import os

    from ..paths import place_file
    from ..statics_plots import draw

    tmp = plot.with_name(f".rollerdyn.tmp{os.getpid()}{plot.suffix}")
    try:
        draw(ds, tmp)
        return place_file(tmp, plot, replace=overwrite), ""
    except (OSError, RuntimeError, ValueError) as err:
        return None, (err.strerror if isinstance(err, OSError) else None) or str(err)
    finally:
        tmp.unlink(missing_ok=True)


def _check_ranges(config: Path, changes: dict, grid: dict, cfg=None) -> bool:
    """Refuses a swept load-case value out of its range, naming the ``--set`` as typed
    (:func:`rollerdyn.statics.check_range`), against ``cfg`` or else the configuration
    with the bearing's ``changes`` only, where that is valid (with a bearing of type NU
    and no axial load swept it is not: its case values are then checked with it). False
    where nothing was checked for that reason."""
    from .. import statics as st
    from ..config import ConfigError, load_config

    if cfg is None:
        try:
            cfg = load_config(config, changes)
        except (ConfigError, OSError):
            return False  # load() says what is wrong, with the case's values in it
    for path, (text, values) in grid.items():
        try:
            st.check_range(cfg, path, text, values)
        except st.StaticsError as err:
            raise refuse(err) from None
    return True


def _case_values(grid: dict[str, tuple[str, list]]) -> dict[str, str]:
    """The load case's values that the configuration is validated with
    (:func:`rollerdyn.statics.case_config_values`), written as in the file."""
    from ..statics import CASE_CONFIG_UNITS, case_config_values

    values = case_config_values({p: v for p, (_, v) in grid.items()})
    return {p: f"{v!r} {CASE_CONFIG_UNITS[p]}" for p, v in values.items()}


def _split_sets(options: list[str]) -> tuple[dict[str, tuple[str, list]], dict[str, list]]:
    """The ``--set`` options as the load case's (path -> its text, to be read by
    :func:`rollerdyn.statics.parse_range`) and the bearing's (path -> its values as in the
    configuration file, read as ``rollerdyn sweep --set`` reads them)."""
    from ..statics import STATIC_FIELDS
    from ..sweep import SweepError, parse_set

    grid: dict[str, tuple[str, list]] = {}
    design: dict[str, list] = {}
    for option in options:
        path, sep, text = option.partition("=")
        path = path.strip()
        if not sep:
            raise refuse(f"--set {option!r}: expected PATH=VALUES")
        if path in grid or path in design:
            raise refuse(f"--set {path}: given twice; list all its values in one --set")
        if path in STATIC_FIELDS:
            grid[path] = (text, [])
            continue
        try:
            _, values = parse_set(option)
        except SweepError as err:
            raise refuse(err) from None
        refuse_overlap(option, path, design)
        if len({repr(v) for v in values}) != len(values):  # the same design solved twice
            raise refuse(f"--set {option}: a value is given twice")
        design[path] = values
    return grid, design


def _check_image_format(path: Path) -> None:
    """Refuses a --plot file whose extension matplotlib cannot write, before any work."""
    from matplotlib.figure import Figure

    formats = Figure().canvas.get_supported_filetypes()
    if shutil.which("xelatex") is None:
        formats.pop("pgf", None)  # matplotlib writes it through LaTeX
    suffix = path.suffix.lower().removeprefix(".")
    if suffix not in formats:
        what = "has no extension"
        if suffix:
            what = f".{suffix} is not an image format matplotlib writes here"
        names = ", ".join("." + f for f in sorted(formats))
        raise refuse(f"--plot {path}: {what}; use one of {names}")


def _thinnest_films(ds) -> str:
    """The thinnest race films of a case [nm], inner and outer ("n/a" at rest)."""
    parts = []
    for race in ("inner", "outer"):
        film = ds[f"{race}_film_thickness"].values
        ok = np.isfinite(film)
        parts.append(f"{film[ok].min() * 1e9:.4g} nm" if ok.any() else "n/a")
    return ", ".join(parts)


def _print_rollers(ds) -> None:
    """The table of ``--per-roller``: each roller's azimuth, race loads, flange forces,
    tilt, skew, slip and the roller train's force on the next roller."""
    flanges = [str(f) for f in ds.flange.values]
    table = Table(title="rollers")
    for column in (
        "roller",
        "azimuth [deg]",
        "inner race [N]",
        "outer race [N]",
        *(f"flange {f} [N]" for f in flanges),
        "tilt [mrad]",
        "skew [mrad]",
        "slip [%]",
        "on the next [N]",
    ):
        table.add_column(column, justify="right")
    for i in range(ds.sizes["roller"]):
        force = ds.flange_force.values[i]
        table.add_row(
            str(i),
            f"{float(ds.roller_azimuth[i]) % 360:.1f}",
            f"{float(ds.inner_race_load[i]):.4g}",
            f"{float(ds.outer_race_load[i]):.4g}",
            *(f"{f:.4g}" for f in force),
            f"{float(ds.roller_tilt[i]) * 1e3:.4g}",
            f"{float(ds.roller_skew[i]) * 1e3:.3g}",
            f"{float(ds.roller_slip[i]) * 100:.3g}",
            f"{float(ds.pair_force[i]):.4g}",
        )
    console.print(table)


def _print_case(ds) -> None:
    ring = ds.ring_displacement.values
    k = ds.stiffness.values
    lam = float(ds.min_specific_film_thickness)
    table = Table(title="quasi-static equilibrium", show_header=False)
    rows = [
        (
            "radial / axial load",
            f"{float(ds.radial_load_applied):.6g} N / {float(ds.axial_load_applied):.6g} N",
        ),
        ("speed", _speed_text(ds)),
        ("ring displacement x, y, z", ", ".join(f"{v * 1e6:.4g} um" for v in ring[:3])),
        ("ring tilt about y, z", ", ".join(f"{v * 1e3:.4g} mrad" for v in ring[3:])),
        ("heaviest roller, inner / outer race", _heaviest_text(ds)),
        ("largest race pressure", f"{float(ds.max_pressure) / 1e9:.4g} GPa"),
        ("largest flange force", _flange_force_text(ds)),
        (
            "load zone half-angle",
            f"{float(ds.load_zone_angle):.4g} deg ({_count(int(ds.loaded_rollers), 'roller')} "
            "pressed between the races)",
        ),
        ("friction of steady rolling", _friction_text(ds)),
        ("roller slip (1 - spin / spin of rolling)", _slip_text(ds)),
        ("roller skew", _skew_text(ds)),
        ("roller train (rollers pressed on their neighbours)", _train_text(ds)),
        ("radial stiffness k_yy", f"{k[1, 1]:.4g} N/m"),
        ("tilt stiffness k_zz", f"{k[4, 4]:.4g} N*m/rad"),
        (
            "C_r (ISO 281), C_0r (ISO 76)",
            f"{float(ds.dynamic_load_rating):.6g} N, {float(ds.static_load_rating):.6g} N",
        ),
        (
            "radial load carried P (F_r with the ring's weight)",
            f"{float(ds.carried_radial_load):.6g} N",
        ),
        ("static safety s_0 = C_0r / P (ISO 76)", f"{float(ds.s0):.4g}"),
        (
            "static safety by stress: races, flanges",
            f"{float(ds.s0_races):.4g}, {float(ds.s0_flanges):.4g}",
        ),
        ("L_10 (ISO 281, at P)", f"{float(ds.l10):.4g} 1e6 rev"),
        ("L_10r (ISO/TS 16281)", f"{float(ds.l10r):.4g} 1e6 rev"),
        ("kappa, L_nmr", f"{float(ds.kappa):.3g}, {float(ds.lnmr):.4g} 1e6 rev"),
        ("race films (thinnest, inner, outer)", _thinnest_films(ds)),
        ("smallest Lambda = h_c / sigma at the races", f"{lam:.3g}" if lam == lam else "n/a"),
    ]
    for name, value in rows:
        table.add_row(name, value)
    console.print(table)
    caveat = str(ds["friction_caveat"].values) if "friction_caveat" in ds else ""
    if caveat:
        say(f"friction of steady rolling: {caveat}", "yellow")
    overload = _overload_text(ds)
    if overload:
        say(overload, "yellow")


def _overload_text(ds) -> str:
    """A note where a case's contacts are pressed past ISO 76's 4 GPa (a static safety by
    stress below 1: the surfaces deform for good, which the elastic contacts do not
    describe; ``rollerdyn check`` says the same of a configuration's loads), else ""."""
    s0 = {"races": float(ds.s0_races), "flanges": float(ds.s0_flanges)}
    past = [name for name, value in s0.items() if value < 1.0]
    if not past:
        return ""
    safety = ", ".join(f"{name} {s0[name]:.3g}" for name in past)
    pressures = {
        "races": f"largest race pressure {float(ds.max_pressure) / 1e9:.3g} GPa",
        # the flanges' safety is judged by Hertz's exact ellipse, 9-13 % above the fits'
        # pressure the forces use (docs/statics.md)
        "flanges": "largest flange pressure "
        f"{float(np.nanmax(ds.flange_pressure.values)) / 1e9:.3g} GPa by Hertz's exact ellipse",
    }
    return (
        f"the {' and the '.join(past)} cannot carry this load: pressed past ISO 76's static "
        f"limit of 4 GPa (static safety by stress {safety} < 1; "
        f"{'; '.join(pressures[name] for name in past)}), where the surfaces deform for good "
        "and the elastic contacts these results rest on no longer hold"
    )


def _print_sweep(ds) -> None:
    swept = ds.attrs["swept"].split(",")
    table = Table(title=f"quasi-static sweep: {ds.sizes['case']} cases")
    columns = [
        "heaviest roller [N]",
        "largest flange force [N] @ height [mm]",
        "steady rolling friction [N*m]",
        "ring y [um]",
        "ring z [um]",
        "s_0 (ISO 76)",
        "s_0 races",
        "L_10r [1e6 rev]",
        "L_nmr [1e6 rev]",
        "smallest race Lambda",
    ]
    # speeds in rpm and angles in degrees, as they are given (the dataset keeps SI; a
    # review: a sweep typed in rpm was shown in rad/s)
    shown_in = [
        _SHOWN_IN.get(ds[s].attrs.get("units", ""), (ds[s].attrs.get("units", ""), 1.0))
        for s in swept
    ]
    for name in [
        *(f"{s} [{u}]" if u else s for s, (u, _) in zip(swept, shown_in, strict=True)),
        *columns,
    ]:
        table.add_column(name)
    n = ds.sizes["case"]
    shown = range(n) if n <= 20 else sorted({0, n // 4, n // 2, 3 * n // 4, n - 1})
    for i in shown:
        row = ds.isel(case=i)
        table.add_row(
            *[_cell(row[s].values, f) for s, (_, f) in zip(swept, shown_in, strict=True)],
            f"{float(row.max_roller_load):.6g}",
            _flange_cell(row),
            f"{float(row.friction_torque):.4g}",
            # six digits: a sweep over roller_set_phase moves the ring by nanometres
            f"{float(row.ring_displacement[1]) * 1e6:.6g}",
            f"{float(row.ring_displacement[2]) * 1e6:.6g}",
            f"{float(row.s0):.4g}",
            f"{float(row.s0_races):.4g}",
            f"{float(row.l10r):.4g}",
            f"{float(row.lnmr):.4g}",
            f"{float(row.min_specific_film_thickness):.3g}",
        )
    console.print(table)
    if n > 20:
        say(f"(5 of the {n} cases shown; -o writes them all)")
    if ds.attrs["failed_cases"]:
        first = next(e for e in ds.error.values if e)
        failed = int(ds.attrs["failed_cases"])
        cases = f"{failed} case" + ("s" if failed != 1 else "")
        say(f"{cases} without equilibrium (NaN); the first: {first}")
    notes = [str(v) for v in ds["friction_note"].values if v] if "friction_note" in ds else []
    if notes:
        cases = f"{len(notes)} case" + ("s" if len(notes) != 1 else "")
        say(f"{cases} without friction estimate (NaN): {notes[0]}", "yellow")
    caveats = [str(v) for v in ds["friction_caveat"].values if v] if "friction_caveat" in ds else []
    if caveats:
        say(f"{_count(len(caveats), 'case')} with friction underestimated: {caveats[0]}", "yellow")
    past = (ds.s0_races.values < 1.0) | (ds.s0_flanges.values < 1.0)
    if past.any():
        first = ds.isel(case=int(np.argmax(past)))
        say(
            f"{_count(int(past.sum()), 'case')} past ISO 76's 4 GPa; the first: "
            f"{_overload_text(first)}",
            "yellow",
        )


#: The sweep table's units for the dataset's SI ones: (unit shown, factor).
_SHOWN_IN = {"rad/s": ("rpm", 30.0 / math.pi), "rad": ("deg", 180.0 / math.pi)}


def _cell(value, factor: float = 1.0) -> str:
    """A swept value in the sweep's table: a number (times ``factor``) to six digits, a
    text as it is."""
    item = value.item() if hasattr(value, "item") else value
    if isinstance(item, bool) or not isinstance(item, int | float):
        return str(item)
    return f"{item * factor:.6g}"


def _flange_force_text(ds) -> str:
    """The largest flange force, where on its flange it presses and with which pairing."""
    force = float(ds.max_flange_force)
    if not force > 0.0:
        return "0 N"
    height = float(ds.max_flange_force_height) * 1e3
    return (
        f"{force:.6g} N, {height:.3g} mm above the raceway ({ds.max_flange_force_pairing.item()})"
    )


def _flange_cell(row) -> str:
    """The sweep table's largest flange force and its height above the raceway."""
    force = float(row.max_flange_force)
    if not force > 0.0:
        return "0" if force == 0.0 else "nan"
    return f"{force:.4g} @ {float(row.max_flange_force_height) * 1e3:.3g}"


def _speed_text(ds) -> str:
    """The inner ring's speed, and the outer ring's where it turns."""
    text = f"{float(ds.speed_applied) * 30 / math.pi:.6g} rpm"
    outer = float(ds.get("outer_speed_applied", 0.0))
    return text + (f" (outer ring {outer * 30 / math.pi:.6g} rpm)" if outer else "")


def _slip_text(ds) -> str:
    """The slip of the rollers in steady rolling, loaded and others (``_by_load``)."""
    return _by_load(ds, ds.roller_slip, 100.0, "%")


def _skew_text(ds) -> str:
    """The skew of the rollers in steady rolling, loaded and others (``_by_load``)."""
    return _by_load(ds, ds.roller_skew, 1e3, "mrad")


def _by_load(ds, values, scale: float, unit: str) -> str:
    """The range of a per-roller value of steady rolling over the rollers that carry at
    least a tenth of the heaviest roller's load at the inner race, and over the others."""
    if _friction_note(ds):
        return "n/a (friction of steady rolling, above)"
    if not math.isfinite(float(ds.friction_torque)):
        return "n/a without relative speed"
    value = np.asarray(values.values, dtype=float) * scale
    load = np.asarray(ds.inner_race_load.values, dtype=float)
    heavy = load >= 0.1 * load.max() if load.max() > 0.0 else np.zeros(load.shape, bool)
    parts = []
    for name, rows in (("loaded (>= 10 % of the heaviest)", heavy), ("others", ~heavy)):
        if rows.any():
            low, high = value[rows].min(), value[rows].max()
            parts.append(f"{name} {low:.3g} ... {high:.3g} {unit}")
    return ", ".join(parts)


def _count(n: int, thing: str) -> str:
    return f"{n} {thing}" + ("" if n == 1 else "s")


def _heaviest_text(ds) -> str:
    """The heaviest roller's load at each race (they differ by its centrifugal force and
    weight: at 100 000 rpm B1's outer race carries 10 % more)."""
    outer = np.asarray(ds.outer_race_load.values, dtype=float).max()
    return f"{float(ds.max_roller_load):.6g} N / {outer:.6g} N"


def _friction_note(ds) -> str:
    """Why the dataset has no friction of steady rolling (``friction_note``), or ""."""
    return str(ds["friction_note"].values) if "friction_note" in ds else ""


def _train_text(ds) -> str:
    """The roller train's largest force between neighbours, where, and its friction."""
    force = np.asarray(ds.pair_force.values, dtype=float)
    if not force.any():
        return "none: in a field below 10 g the rollers' films hold them apart (docs/statics.md)"
    z = force.size
    i = int(np.argmax(force))
    psi = float(ds.roller_azimuth[i]) % 360
    power = float(ds.friction_power.sel(friction_part="roller pairs"))
    friction = f"{power:.4g} W" if math.isfinite(power) else "n/a (above)"
    return (
        f"largest {force[i]:.4g} N (rollers {i} and {(i + 1) % z}, from {psi:.1f} deg), "
        f"friction {friction}"
    )


def _friction_text(ds) -> str:
    """The frictional torque of steady rolling and its power's largest parts; n/a at rest
    and where the rings turn together (``rollerdyn.statics.TORQUE_RELATIVE_SPEED``)."""
    from ..statics import TORQUE_RELATIVE_SPEED

    power = ds.friction_power
    total = float(power.sum())
    inner, outer = float(ds.speed_applied), float(ds.get("outer_speed_applied", 0.0))
    if inner == outer == 0.0:
        return "n/a at rest"
    if _friction_note(ds):
        return f"n/a: {_friction_note(ds)}"
    if not math.isfinite(float(ds.friction_torque)):
        return (
            f"n/a: the rings turn together (relative speed {abs(inner - outer):.3g} rad/s, "
            f"under {100 * TORQUE_RELATIVE_SPEED:g} % of their speed; {total:.4g} W)"
        )
    parts = ", ".join(
        f"{name} {100 * float(v) / total:.0f} %"
        for name, v in zip(power.friction_part.values, power.values, strict=True)
        if total > 0 and float(v) >= 0.005 * total
    )
    return f"{float(ds.friction_torque):.4g} N*m ({total:.4g} W{': ' + parts if parts else ''})"


def _keep_interrupted(stop, output: Path | None, status: int, overwrite: bool = False) -> None:
    """A sweep stopped by Ctrl-C or SIGTERM: the cases solved until then written to
    ``output`` (when given; :func:`_save`), one line saying so, exit ``status`` (130, or
    143 after SIGTERM)."""
    ds = stop.dataset
    if ds is not None and output is not None:
        written, problem = _save(ds, output, overwrite)
        if written is None:
            error(f"rollerdyn statics: {stop}; could not write them to {output} ({problem})")
            raise typer.Exit(status) from None
        other = "" if written == output else f" ({output} was created meanwhile by another program)"
        error(f"rollerdyn statics: {stop}; wrote those to {written}{other}")
    elif ds is not None:  # the cases solved shown, not lost (they were, without -o)
        _print_sweep(ds)
        error(f"rollerdyn statics: {stop}; the cases solved are above (-o FILE keeps them)")
    else:
        error(f"rollerdyn statics: {stop}")
    raise typer.Exit(status)
