"""``rollerdyn new``: a starting configuration for another bearing (:mod:`rollerdyn.starter`)."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Annotated

import typer

from ..paths import check_output_file
from .common import checked, load, refuse, say

#: The unit families the options are read in.
_LENGTH, _FORCE, _SPEED = "length", "force", "angular velocity"


def _value(option: str, text: str | None, family: str, unit: str) -> float | None:
    """``text`` of ``option`` in SI (a bare number is in ``unit``); exits with status 2 and
    one line naming the option otherwise."""
    from ..study.maps import in_unit
    from ..units import QuantityError, parse_quantity

    if text is None:
        return None
    try:
        return parse_quantity(in_unit(text, unit), family)
    except QuantityError as err:
        raise refuse(f"{option} {text!r}: {err}") from None


def new_command(
    output: Annotated[
        Path,
        typer.Argument(help="The configuration file to write (TOML).", metavar="OUT"),
    ],
    inner_raceway: Annotated[
        str,
        typer.Option(
            "--inner-raceway",
            help='Inner raceway diameter, with a unit ("40 mm") or a bare number of mm.',
            metavar="LENGTH",
        ),
    ],
    outer_raceway: Annotated[
        str,
        typer.Option(
            "--outer-raceway",
            help="Outer raceway diameter, with a unit or a bare number of mm.",
            metavar="LENGTH",
        ),
    ],
    clearance: Annotated[
        str | None,
        typer.Option(
            "--clearance",
            help='Radial internal clearance (diametral), with a unit ("20 um") or a bare '
            "number of um. Default: B1's 10 um times the pitch diameter over B1's 24.5 mm; at "
            "most 1 % of the pitch diameter.",
            metavar="LENGTH",
        ),
    ] = None,
    rollers: Annotated[
        int | None,
        typer.Option(
            "--rollers",
            help="Roller count. Default: the most that fit the pitch circle with "
            "neighbours 0.1 % of a roller diameter apart (a full complement).",
        ),
    ] = None,
    roller_length: Annotated[
        str | None,
        typer.Option(
            "--roller-length",
            help="Roller length, with a unit or a bare number of mm. Default: B1's 5 mm "
            "times the roller diameter over B1's 4.495 mm; 0.5 ... 10 roller diameters.",
            metavar="LENGTH",
        ),
    ] = None,
    radial_load: Annotated[
        str | None,
        typer.Option(
            "--radial-load",
            help="Radial load on the inner ring (along -y), with a unit or a bare number of "
            "N. Default: B1's 5000 N times Z D L over B1's.",
            metavar="FORCE",
        ),
    ] = None,
    axial_load: Annotated[
        str | None,
        typer.Option(
            "--axial-load",
            help="Axial load on the inner ring (along +x), with a unit or a bare number of "
            "N. Default: a fifth of the radial load, as B1's.",
            metavar="FORCE",
        ),
    ] = None,
    speed: Annotated[
        str | None,
        typer.Option(
            "--speed",
            help="Inner ring speed, with a unit or a bare number of rpm. Default: B1's "
            "500 rpm at B1's n d_m (500 rpm times 24.5 mm over the pitch diameter).",
            metavar="SPEED",
        ),
    ] = None,
    bearing_type: Annotated[
        str,
        typer.Option(
            "--type",
            help="The bearing's type by its flanges (ISO 15): NUP (all four, as B1), NU (the "
            "outer ring's two), N (the inner ring's two), NJ (NU with the inner ring's -x "
            "flange), NF (N with the outer ring's +x flange). NU and N carry no axial load, "
            "so their axial load defaults to 0 N.",
        ),
    ] = "NUP",
    name: Annotated[
        str | None,
        typer.Option("--name", help="The bearing's name. Default: the file's name."),
    ] = None,
    overwrite: Annotated[
        bool, typer.Option("--overwrite", help="Replace OUT if it exists.")
    ] = False,
) -> None:
    """Write a starting configuration for another full-complement cylindrical roller
    bearing, made from its raceway diameters by the proportions of B1.

    The roller diameter is (D_o - D_i)/2 less half the clearance, the pitch diameter the
    raceways' mean, the roller count the most that fit. The other lengths of the roller
    and the flanges, the outer ring's wall, the inner ring's mass, the loads and the speed
    are B1's scaled by the size, each line of the file saying by what (and 'replace' where
    the bearing's drawing should give the value); materials, lubricant, surfaces and
    solver settings are B1's. The file is checked as `rollerdyn check` would, and its
    quasi-static equilibrium printed (`rollerdyn statics`). Lengths are in mm, clearance
    in um, loads in N and speeds in rpm where a bare number is given.
    """
    from ..starter import StarterError, starter_config, starter_geometry, write_starter

    path = checked(
        check_output_file,
        output,
        "OUT",
        overwrite=overwrite,
        hint="; pass --overwrite to replace it",
    )
    inner = _value("--inner-raceway", inner_raceway, _LENGTH, "mm")
    outer = _value("--outer-raceway", outer_raceway, _LENGTH, "mm")
    try:
        geometry = starter_geometry(
            inner, outer, _value("--clearance", clearance, _LENGTH, "um"), rollers
        )
        text = starter_config(
            geometry,
            name if name is not None else path.stem,
            _value("--roller-length", roller_length, _LENGTH, "mm"),
            _value("--radial-load", radial_load, _FORCE, "N"),
            _value("--axial-load", axial_load, _FORCE, "N"),
            _value("--speed", speed, _SPEED, "rpm"),
            bearing_type.upper(),
        )
    except (StarterError, FileNotFoundError) as err:  # the latter: B1's file not installed
        raise refuse(err) from None
    import tomllib

    from ..config import ConfigError, parse_config

    try:
        parse_config(tomllib.loads(text), source=str(path))
    except ConfigError as err:
        raise refuse(_invalid_bearing(err, axial_given=axial_load is not None)) from None
    try:
        write_starter(path, text)
    except OSError as err:
        raise refuse(f"OUT {path}: {err}", 1) from None
    cfg = load(path)
    g = cfg.geometry
    say(
        f"wrote {path}: {g.roller_count} rollers of {g.roller_diameter * 1e3:.4g} x "
        f"{g.roller.length * 1e3:.4g} mm on a pitch diameter of {g.pitch_diameter * 1e3:.4g} mm "
        f"(B1's proportions scaled {geometry.size:.4g} times)"
    )
    _print_statics(cfg)
    say(f"next: rollerdyn check {path}; rollerdyn statics {path}; rollerdyn run {path}")


def _print_statics(cfg) -> None:
    """One line of the new bearing's quasi-static equilibrium at its loads and speed, or
    the reason there is none."""
    from ..statics import StaticsError, statics

    try:
        ds = statics(cfg)
    except StaticsError as err:
        say(f"quasi-static equilibrium: none at the configured loads ({err})")
        return
    torque = float(ds.friction_torque)
    say(
        f"quasi-static equilibrium at {float(ds.radial_load_applied):.4g} N radially, "
        f"{float(ds.axial_load_applied):.4g} N axially: heaviest roller "
        f"{float(ds.max_roller_load):.4g} N, C_r {float(ds.dynamic_load_rating):.4g} N, "
        f"C_0r {float(ds.static_load_rating):.4g} N, L_10r {float(ds.l10r):.4g} 1e6 rev, "
        "friction torque "
        + (
            f"{torque:.4g} N*m"
            if math.isfinite(torque)
            else f"n/a ({str(ds.friction_note.values) or 'no relative speed'})"
        )
    )


#: The configuration paths an option of ``rollerdyn new`` writes; every other value is
#: B1's scaled by the size the raceways give.
_OPTION_OF = {
    "geometry.roller_count": "--rollers",
    "geometry.diametral_clearance": "--clearance",
    "geometry.roller.length": "--roller-length",
    "operating.radial_load": "--radial-load",
    "operating.axial_load": "--axial-load",
    "operating.inner_ring_speed": "--speed",
}


def _invalid_bearing(err, axial_given: bool) -> str:
    """One line for a configuration the options made that its rules refuse, each problem
    led by the option behind it (a tiny bearing's inner ring of 0.13 g was refused on
    inner_ring.mass, which no option sets: the raceways' size made it); an axial load not
    given is the radial load's default share."""
    problems = err.problems or ()
    if not problems:
        return f"these values make no valid bearing: {' '.join(str(err).split())}"
    said = []
    for problem in problems:
        option = _OPTION_OF.get(
            problem.path, "--inner-raceway, --outer-raceway (B1's value scaled by their size)"
        )
        if problem.path == "operating.axial_load" and not axial_given:
            option = "--radial-load (the axial load's default is a fifth of it)"
        said.append(f"{option}: {problem}")
    return "these values make no valid bearing: " + "; ".join(said)
