"""Tests of the configuration layer: units, schema, derived quantities, error messages."""

from __future__ import annotations

import math
import re
import sys
import tomllib
import types
from pathlib import Path

import numpy as np
import pytest
from b1 import B1_TEXT, b1_data, b1_file_with, changed_b1, load_b1
from hypothesis import given, settings
from hypothesis import strategies as st
from pydantic import BaseModel, ValidationError

from rollerdyn.config import (
    BearingConfig,
    ConfigError,
    TimeTable,
    fit_roelands_z,
    load_config,
    parse_config,
)
from rollerdyn.config.loading import toml_text
from rollerdyn.units import Integer, Number, Quantity, QuantityError, parse_quantity

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs" / "configuration.md"
DEL = object()


def mutate(data: dict, path: str, value: object) -> dict:
    """A copy of ``data`` with ``path`` set to ``value`` (DEL: removed); tests/b1.py."""
    return changed_b1({path: None if value is DEL else value}, data)


# --------------------------------------------------------------------------- B1 loads


def test_b1_loads(b1: BearingConfig) -> None:
    assert isinstance(b1, BearingConfig)
    assert b1.name == "B1"
    assert b1.geometry.roller_count == 17
    assert b1.inner_ring.tilt == "locked"
    assert b1.solver.detector == "semi-analytical"


def test_si_conversions_exact(b1: BearingConfig) -> None:
    g, op, lub = b1.geometry, b1.operating, b1.lubricant
    assert g.inner_raceway_diameter == 0.02
    assert g.outer_raceway_diameter == 0.029
    assert g.diametral_clearance == 1e-05
    assert g.roller.end_face_radius == 5.0
    assert g.flange.opening_angle == math.radians(0.11)
    assert op.inner_ring_speed == 52.35987755982988
    assert op.temperature == 353.15
    assert op.radial_load == 5000.0
    assert lub.reference_viscosity is not None
    assert lub.reference_viscosity.viscosity == 0.081
    assert lub.reference_viscosity.temperature == 313.15
    assert lub.vogel.k == 6.2e-05
    assert lub.vogel.b == 1021.7
    assert lub.vogel.c == 101.5517
    assert lub.roelands.eta_p == 6.31e-05
    assert lub.roelands.p_p == -196e6
    assert lub.dicke is not None
    assert lub.dicke.a1 == 32779180.0
    assert lub.dicke.a2 == 298620.0
    assert lub.dicke.b2 == 3.0115e-4
    assert lub.density.slope == -0.6
    assert lub.thermal_conductivity == 0.134
    assert b1.materials.roller.youngs_modulus == 210e9
    assert b1.surfaces.raceway.roughness == 1.6e-07
    assert b1.surfaces.boundary_friction.smoothing_speed == 0.001
    assert b1.solver.line_fit.load_max is None  # derived from the radial load (rollerdyn.model)


def test_b1_derived(b1: BearingConfig) -> None:
    g = b1.geometry
    assert g.roller_diameter == pytest.approx(4.495e-3, rel=1e-12)
    assert g.pitch_diameter == pytest.approx(24.5e-3, rel=1e-12)
    assert g.circumferential_gap > 0.0
    assert g.fill_ratio == pytest.approx(0.993, abs=5e-4)
    assert g.inner_flange is g.flange and g.outer_flange is g.flange
    assert g.roller.effective_length == pytest.approx(4e-3)
    assert g.roller.slice_width == pytest.approx(2e-4)


def test_b1_vogel_rescaled(b1: BearingConfig) -> None:
    lub = b1.lubricant
    assert lub.eta0(313.15) == pytest.approx(0.081, rel=1e-9)
    unscaled = lub.vogel.eta0(313.15)
    assert unscaled == pytest.approx(84.54e-3, rel=1e-3)
    assert lub.vogel_scale == pytest.approx(81 / 84.54, rel=1e-3)
    assert lub.vogel_k == pytest.approx(lub.vogel.k * 0.081 / unscaled, rel=1e-12)


def test_b1_end_time_and_cage_speed(b1: BearingConfig) -> None:
    assert b1.operating.end_time is None
    assert b1.roller_set_speed * 60 / (2 * math.pi) == pytest.approx(204.1, abs=0.1)
    assert b1.end_time == pytest.approx(1.288, abs=0.002)


def test_b1_roelands_z_fit(b1: BearingConfig) -> None:
    assert b1.roelands_z == pytest.approx(0.62, abs=0.01)
    lub = b1.lubricant
    assert lub.dicke is not None
    z_ls = fit_roelands_z(
        b1.base_viscosity, lub.roelands.eta_p, lub.roelands.p_p, lub.dicke, 353.15, "least_squares"
    )
    # The least-squares z minimises sum (ln eta_Roelands - ln eta_Dicke)^2 over 200 equally
    # spaced pressures up to 1 GPa (docs/configuration.md): a brute-force scan of that cost,
    # written here from eqs. 19 and Dicke's law, finds the same minimum (measured: both
    # 0.63628) within its own step of 1e-5.
    d, eta0, theta = lub.dicke, b1.base_viscosity, 353.15 - 273.15
    p = 1e9 * np.arange(1, 201) / 200
    dicke = np.log(eta0) + p / (d.a1 + d.a2 * theta + (d.b1 + d.b2 * theta) * p)
    growth = np.log1p(p / -lub.roelands.p_p)
    ln_ratio = np.log(eta0 / lub.roelands.eta_p)
    zs = np.linspace(0.6, 0.7, 10_001)
    roelands = np.log(lub.roelands.eta_p) + ln_ratio * np.exp(np.outer(zs, growth))
    scan = zs[np.argmin(np.sum((roelands - dicke) ** 2, axis=1))]
    assert z_ls == pytest.approx(scan, abs=1e-5)


def test_b1_inner_ring_inertia_default(b1: BearingConfig, raw: dict) -> None:
    # B1's ring with its shaft section: 1 kg, transverse inertia given (B1.md); the axial
    # inertia and, without the given value, the transverse one of the solid cylinder.
    m, r = 1.0, 0.01
    w = m / (7850 * math.pi * r * r)
    assert b1.inner_ring_equivalent_length == pytest.approx(w)
    assert b1.inner_ring_axial_inertia == pytest.approx(m * r * r / 2)
    assert b1.inner_ring_transverse_inertia == pytest.approx(5e-4)
    derived = parse_config(mutate(raw, "inner_ring.transverse_inertia", DEL))
    assert derived.inner_ring_transverse_inertia == pytest.approx(m * (3 * r * r + w * w) / 12)


def test_inner_ring_inertia_given(raw: dict) -> None:
    data = mutate(raw, "inner_ring.axial_inertia", "6e-6 kg*m^2")
    cfg = parse_config(mutate(data, "inner_ring.transverse_inertia", "2e-5 kg*m^2"))
    assert cfg.inner_ring_axial_inertia == pytest.approx(6e-6)
    assert cfg.inner_ring_transverse_inertia == pytest.approx(2e-5)


def test_b1_histories(b1: BearingConfig) -> None:
    op = b1.operating
    assert op.radial_load_at(0.0) == 0.0
    assert op.radial_load_at(0.25) == pytest.approx(2500.0)
    assert op.axial_load_at(1.0) == 1000.0
    assert op.inner_ring_speed_at(0.5) == 0.0
    assert op.inner_ring_speed_at(0.6) == pytest.approx(52.35987755982988 / 2)
    assert op.inner_ring_speed_at(0.7) == pytest.approx(52.35987755982988)


def test_b1_defaults(b1: BearingConfig) -> None:
    assert b1.lubricant.alpha_star_fit.t_min == 293.15
    assert b1.lubricant.alpha_star_fit.t_max == 413.15
    assert b1.geometry.roller.crown_drop == 0.0
    assert b1.geometry.roller.crown_length is None
    assert b1.surfaces.roller_roller_pair is b1.surfaces.raceway
    assert b1.lubricant.roelands.fit_pressure_max == 1e9


def test_solver_defaults(raw: dict) -> None:
    cfg = parse_config(mutate(raw, "solver", DEL))
    s = cfg.solver
    assert (s.rtol, s.atol, s.dt_max, s.output_interval) == (1e-5, 1e-9, 1e-3, 1e-4)
    assert (s.detector, s.traction_nodes) == ("semi-analytical", 12)
    assert (s.line_fit.load_min, s.line_fit.load_max, s.line_fit.samples) == (None, None, 64)


def test_rolling_resistance_defaults_to_balanced_and_b1_keeps_the_papers(
    b1: BearingConfig, raw: dict
) -> None:
    # The default conserves angular momentum in every contact (docs/dynamics.md, "Torque
    # balance of the rings"); B1's example sets the paper's law for the paper's study.
    assert b1.surfaces.rolling_resistance == "paper"
    cfg = parse_config(mutate(raw, "surfaces.rolling_resistance", DEL))
    assert cfg.surfaces.rolling_resistance == "balanced"


def test_frozen(b1: BearingConfig) -> None:
    with pytest.raises(ValidationError):
        b1.geometry.roller_count = 18  # type: ignore[misc]


def test_model_dump_round_trip(b1: BearingConfig) -> None:
    again = parse_config(b1.model_dump(), si_numbers=True)
    assert again == b1
    assert again.end_time == b1.end_time


def test_unicode_units(raw: dict) -> None:
    data = mutate(raw, "geometry.diametral_clearance", "10 µm")
    data = mutate(data, "operating.temperature", "80 °C")
    data = mutate(data, "lubricant.reference_viscosity.viscosity", "81 mPa·s")
    cfg = parse_config(data)
    assert cfg.geometry.diametral_clearance == 1e-05
    assert cfg.operating.temperature == 353.15
    assert cfg.lubricant.reference_viscosity.viscosity == 0.081


def test_time_tables(raw: dict) -> None:
    data = mutate(raw, "operating.radial_load", {"table": [["0 s", "0 N"], ["0.5 s", "5 kN"]]})
    data = mutate(
        data,
        "operating.inner_ring_speed",
        {"table": [["0 s", "0 rpm"], ["0.5 s", "0 rpm"], ["0.8 s", "500 rpm"]]},
    )
    data = mutate(data, "operating.speed_ramp", DEL)
    cfg = parse_config(data)
    op = cfg.operating
    assert isinstance(op.radial_load, TimeTable)
    assert op.radial_load.table == ((0.0, 0.0), (0.5, 5000.0))
    assert op.radial_load_at(0.25) == pytest.approx(2500.0)
    assert op.radial_load_at(3.0) == 5000.0
    assert op.axial_load_at(0.25) == pytest.approx(500.0)  # constant load keeps the ramp
    assert op.speed_history_end == 0.8
    assert op.inner_ring_speed_at(0.65) == pytest.approx(52.35987755982988 / 2)
    assert cfg.end_time == pytest.approx(0.8 + 0.588, abs=0.002)


def test_flange_override(raw: dict) -> None:
    cfg = parse_config(mutate(raw, "geometry.outer_ring_flange", {"height": "1.3 mm"}))
    g = cfg.geometry
    assert g.outer_flange.height == pytest.approx(1.3e-3)
    assert g.outer_flange.opening_angle == g.flange.opening_angle
    assert g.inner_flange is g.flange


@pytest.mark.parametrize(
    ("flanges", "words", "carried"),
    [
        (["inner-x", "inner+x", "outer-x", "outer+x"], "all four (type NUP)", "both directions"),
        (["outer+x", "outer-x"], "the outer ring's two (type NU)", "none"),
        (["inner-x", "inner+x"], "the inner ring's two (type N)", "none"),
        (
            ["inner+x", "outer-x", "outer+x"],
            "the outer ring's two and the inner ring's +x (type NJ;",
            "along -x only",
        ),
        (
            ["inner-x", "inner+x", "outer+x"],
            "the inner ring's two and the outer ring's +x (type NF;",
            "along +x only",
        ),
        (["inner-x", "outer+x"], "the inner ring's -x and the outer ring's +x", "along +x only"),
    ],
)
def test_flange_arrangement_names_the_bearing_type(raw: dict, flanges, words, carried) -> None:
    """ISO 15 / DIN 5412-1: NU has ribs on the outer ring only, N on the inner ring only,
    NJ both on the outer ring and one on the inner, NF the reverse, NUP all four. An axial
    load along +x on the inner ring needs its -x flange and the outer ring's +x one."""
    data = mutate(mutate(raw, "geometry.flanges", flanges), "operating.axial_load", "0 N")
    geometry = parse_config(data).geometry
    assert geometry.flange_arrangement.startswith(words)
    assert geometry.axial_load_carried == carried


def test_a_vertical_shafts_ring_weight_needs_its_two_flanges(raw: dict) -> None:
    """Gravity along -x presses the inner ring's 1 kg onto its +x flange, which the
    rollers pass on to the outer ring's -x flange: an NJ arrangement without the inner
    ring's +x flange is refused even without an axial load, naming the weight."""
    data = mutate(raw, "geometry.flanges", ["inner-x", "outer-x", "outer+x"])
    data = mutate(data, "operating.axial_load", "0 N")
    parse_config(data)
    data = mutate(data, "operating.gravity", ["-9.81 m/s^2", "0 m/s^2", "0 m/s^2"])
    with pytest.raises(ConfigError) as info:
        parse_config(data)
    (problem,) = info.value.problems
    assert problem.path == "operating.axial_load"
    assert "along -x with the ring's weight along the axis (-9.81 N)" in problem.rule
    assert 'geometry.flanges has no "inner+x"' in problem.rule


def test_crowned_profile(raw: dict) -> None:
    data = mutate(raw, "geometry.roller.profile", "crowned")
    data = mutate(data, "geometry.roller.crown_drop", "2 um")
    cfg = parse_config(mutate(data, "geometry.roller.crown_length", "1 mm"))
    assert cfg.geometry.roller.crown_drop == 2e-6
    assert cfg.geometry.roller.crown_length == 1e-3


def test_logarithmic_profile(raw: dict) -> None:
    """ISO/TS 16281's relief 0.00035 D by default, or the configuration's factor."""
    data = mutate(raw, "geometry.roller.profile", "logarithmic")
    cfg = parse_config(data)
    assert cfg.geometry.log_relief == pytest.approx(0.00035 * cfg.geometry.roller_diameter)
    cfg = parse_config(mutate(data, "geometry.roller.relief_factor", 0.0005))
    assert cfg.geometry.log_relief == pytest.approx(0.0005 * cfg.geometry.roller_diameter)
    assert parse_config(raw).geometry.log_relief == 0.0  # B1 is straight


def test_roelands_z_number(raw: dict) -> None:
    data = mutate(raw, "lubricant.roelands", {"z": 0.6})
    data = mutate(data, "lubricant.dicke", DEL)
    cfg = parse_config(data)
    assert cfg.roelands_z == 0.6
    assert cfg.lubricant.roelands.eta_p == 6.31e-05
    assert cfg.lubricant.roelands.p_p == -196e6


def test_explicit_end_time(raw: dict) -> None:
    cfg = parse_config(mutate(raw, "operating.end_time", "1.5 s"))
    assert cfg.end_time == 1.5


# --------------------------------------------------------------------------- units


@pytest.mark.parametrize(
    ("text", "family", "expected"),
    [
        ("20 mm", "length", 0.02),
        ("20mm", "length", 0.02),
        ("10 um", "length", 1e-05),
        ("10 µm", "length", 1e-05),
        ("5 kN", "force", 5000.0),
        ("500 rpm", "angular velocity", 52.35987755982988),
        ("80 degC", "temperature", 353.15),
        ("80 °C", "temperature", 353.15),
        ("353.15 K", "temperature", 353.15),
        ("1021.7 K", "temperature interval", 1021.7),
        ("1021.7 delta_degC", "temperature interval", 1021.7),
        ("81 mPa*s", "dynamic viscosity", 0.081),
        ("2.9862 bar/K", "pressure per temperature", 298620.0),
        ("2.9862 bar/degC", "pressure per temperature", 298620.0),
        ("3.0115e-4 1/K", "inverse temperature", 3.0115e-4),
        ("0.134 W/(m*K)", "thermal conductivity", 0.134),
        ("887.6 kg/m^3", "density", 887.6),
        ("-0.6 kg/m^3/K", "density per temperature", -0.6),
        ("1 N/mm", "force per length", 1000.0),
        ("0.5 turn", "angle", math.pi),
        ("1 mm/s", "speed", 0.001),
        ("20 mm", "[length]", 0.02),
    ],
)
def test_parse_quantity(text: str, family: str, expected: float) -> None:
    assert parse_quantity(text, family) == expected


@pytest.mark.parametrize(
    ("value", "family", "message"),
    [
        (20, "length", "a bare number is ambiguous"),
        ("20", "length", "without a unit"),
        ("5000 N", "length", 'expected a length (e.g. "20 mm"), got a force'),
        ("50 Hz", "angular velocity", "got a frequency"),
        ("0.11", "angle", "without a unit"),
        ("20 delta_degC", "temperature", "got a temperature difference"),
        ("101.5 degC", "temperature interval", "use K or delta_degC"),
        ("-300 degC", "temperature", "above 0 K"),
        ("nan mm", "length", "must be finite"),
        ("20 parsecz", "length", "unknown unit"),
        # pint does not read a run-together "Nm" as newton times metre
        ("5 Nm", "torque", 'write newton metres with a product, e.g. "5 N*m"'),
        ("2 kNm", "torque", '"2 kN*m"'),
        (None, "length", "expected a string"),
    ],
)
def test_parse_quantity_errors(value: object, family: str, message: str) -> None:
    with pytest.raises(QuantityError, match=re.escape(message)):
        parse_quantity(value, family)


def test_type_factories() -> None:
    class M(BaseModel):
        d: Quantity("[length]", positive=True)
        a: Quantity("angle", ge=0, lt="90 deg") = "1 deg"
        nu: Number(gt=0, lt=0.5) = 0.3
        k: Integer(ge=3) = 3

    assert M(d="2 mm").d == 0.002
    with pytest.raises(ValidationError, match="must be > 0"):
        M(d="-2 mm")
    with pytest.raises(ValidationError, match="must be >= 0 and < 90 deg"):
        M(d="2 mm", a="90 deg")
    with pytest.raises(ValidationError, match="expected a plain number"):
        M(d="2 mm", nu="0.3 mm")
    with pytest.raises(ValidationError, match="expected an integer"):
        M(d="2 mm", k=3.0)
    with pytest.raises(ValueError, match="ambiguous"):
        Quantity("[temperature]")


# --------------------------------------------------------------------------- bad inputs

BAD = [
    # (id, path to change, new value, expected problem path, expected rule text)
    (
        "misalignment beyond 1 deg",
        "inner_ring.misalignment",
        "2 deg",
        "inner_ring.misalignment",
        "<= 1 deg",
    ),
    (
        "zero radius",
        "geometry.roller.edge_radius",
        "0 mm",
        "geometry.roller.edge_radius",
        "must be > 0",
    ),
    (
        "negative radius",
        "geometry.flange.root_radius",
        "-0.2 mm",
        "geometry.flange.root_radius",
        "must be > 0",
    ),
    (
        "negative end face",
        "geometry.roller.end_face_radius",
        "-5 m",
        "geometry.roller.end_face_radius",
        "must be > 0",
    ),
    (
        "rollers do not fit",
        "geometry.roller_count",
        18,
        "geometry.roller_count",
        "rollers do not fit",
    ),
    ("too few rollers", "geometry.roller_count", 2, "geometry.roller_count", "must be >= 3"),
    (
        "flange taller than roller",
        "geometry.flange.height",
        "5 mm",
        "geometry.flange.height",
        "must be < roller diameter",
    ),
    (
        "flange below its tori",
        "geometry.flange.height",
        "0.4 mm",
        "geometry.flange.height",
        "must be > root_radius + rim_radius",
    ),
    (
        "edge radius vs diameter",
        "geometry.roller.edge_radius",
        "2.3 mm",
        "geometry.roller.edge_radius",
        "must be < roller diameter/2",
    ),
    (
        "edge radius vs length",
        "geometry.roller.length",
        "0.9 mm",
        "geometry.roller.edge_radius",
        "must be < length/2",
    ),
    (
        "end face too small",
        "geometry.roller.end_face_radius",
        "2 mm",
        "geometry.roller.end_face_radius",
        "must be > roller diameter/2",
    ),
    (
        "outer below inner",
        "geometry.outer_raceway_diameter",
        "19 mm",
        "geometry.outer_raceway_diameter",
        "must be > inner_raceway_diameter",
    ),
    (
        "clearance eats rollers",
        "geometry.diametral_clearance",
        "10 mm",
        "geometry.diametral_clearance",
        "leaves no room for rollers",
    ),
    # absurd values that ended in solver failures naming no field, or passed silently
    (
        "mu_b0 1e6",
        "surfaces.boundary_friction.mu_b0",
        1e6,
        "surfaces.boundary_friction.mu_b0",
        "must be >= 0 and <= 1",
    ),
    (
        "hysteresis 1e300",
        "surfaces.hysteresis_coefficient",
        1e300,
        "surfaces.hysteresis_coefficient",
        "must be >= 0 and <= 1",
    ),
    (
        "viscosity 1e30 mPa*s",
        "lubricant.reference_viscosity.viscosity",
        "1e30 mPa*s",
        "lubricant.reference_viscosity.viscosity",
        "<= 1000 Pa*s",
    ),
    (  # exactly the gap: 4e-16 mm of roller by round-off passed on to other rules (a review)
        "clearance equal to the gap",
        "geometry.diametral_clearance",
        "9 mm",
        "geometry.diametral_clearance",
        "must be > 0 (this is round-off of the raceways' difference)",
    ),
    ("NaN", "geometry.roller.length", float("nan"), "geometry.roller.length", "must be finite"),
    (
        "NaN plain number",
        "surfaces.raceway.zh_b",
        float("nan"),
        "surfaces.raceway.zh_b",
        "must be finite",
    ),
    ("inf", "operating.radial_load", "inf N", "operating.radial_load", "must be finite"),
    ("inf plain number", "solver.atol", float("inf"), "solver.atol", "must be finite"),
    (
        "unknown key",
        "geometry.roller_cnt",
        17,
        "geometry.roller_cnt",
        "unknown key 'roller_cnt' in section 'geometry' (allowed: roller_count,",
    ),
    ("unknown top-level key", "extra", 1, "extra", "unknown key 'extra' in section '<top level>'"),
    (
        "missing field",
        "geometry.roller.length",
        DEL,
        "geometry.roller.length",
        "required: a length",
    ),
    ("missing section", "lubricant", DEL, "lubricant", "required: a [section] table"),
    (
        "wrong dimension",
        "operating.radial_load",
        "5000 mm",
        "operating.radial_load",
        'expected a force (e.g. "5000 N"), got a length',
    ),
    (
        "wrong dimension viscosity",
        "lubricant.vogel.k",
        "0.062 mPa",
        "lubricant.vogel.k",
        "expected a dynamic viscosity",
    ),
    (
        "bare number",
        "geometry.inner_raceway_diameter",
        20,
        "geometry.inner_raceway_diameter",
        'a bare number is ambiguous (no unit); expected a length with a unit, e.g. "20 mm"',
    ),
    (
        "bare number angle",
        "geometry.flange.opening_angle",
        0.11,
        "geometry.flange.opening_angle",
        "expected an angle with a unit",
    ),
    (
        "poisson 0.6",
        "materials.roller.poisson_ratio",
        0.6,
        "materials.roller.poisson_ratio",
        "must be > 0 and < 0.5",
    ),
    (
        "poisson with unit",
        "materials.outer_ring.poisson_ratio",
        "0.3 mm",
        "materials.outer_ring.poisson_ratio",
        "expected a plain number",
    ),
    (
        "table times not increasing",
        "operating.axial_load",
        {"table": [["0 s", "0 N"], ["0.5 s", "1 kN"], ["0.5 s", "2 kN"]]},
        "operating.axial_load.table.2.0",
        "times must be strictly increasing",
    ),
    (
        "table value dimension",
        "operating.radial_load",
        {"table": [["0 s", "0 N"], ["0.5 s", "5 mm"]]},
        "operating.radial_load.table.1.1",
        "expected a force",
    ),
    (
        "table short row",
        "operating.radial_load",
        {"table": [["0 s", "0 N"], ["0.5 s"]]},
        "operating.radial_load.table.1",
        "each row must be [time, value]",
    ),
    (
        "table one row",
        "operating.radial_load",
        {"table": [["0 s", "0 N"]]},
        "operating.radial_load.table",
        "at least 2 rows",
    ),
    (
        "negative radial load",
        "operating.radial_load",
        "-5 kN",
        "operating.radial_load",
        "must be >= 0",
    ),
    (
        "ramp end before start",
        "operating.speed_ramp.end",
        "0.4 s",
        "operating.speed_ramp.end",
        "must be > start",
    ),
    (
        "ramp shape",
        "operating.load_ramp.shape",
        "smooth",
        "operating.load_ramp.shape",
        'must be one of "cosine" or "linear"',
    ),
    (
        "end time before ramp end",
        "operating.end_time",
        "0.6 s",
        "operating.end_time",
        "must be > the end of the speed ramp",
    ),
    (
        "z fit without dicke",
        "lubricant.dicke",
        DEL,
        "lubricant.roelands.z",
        "needs a [lubricant.dicke] section",
    ),
    (
        "z wrong",
        "lubricant.roelands.z",
        "fitted",
        "lubricant.roelands.z",
        'expected a positive number or "fit"',
    ),
    ("positive p_p", "lubricant.roelands.p_p", "196 MPa", "lubricant.roelands.p_p", "must be < 0"),
    (
        "alpha fit range",
        "lubricant.alpha_star_fit.t_max",
        "10 degC",
        "lubricant.alpha_star_fit.t_max",
        "must be > t_min",
    ),
    (
        "absolute temperature for interval",
        "lubricant.vogel.c",
        "101.5517 degC",
        "lubricant.vogel.c",
        "use K or delta_degC",
    ),
    (
        "interval for absolute temperature",
        "operating.temperature",
        "80 delta_degC",
        "operating.temperature",
        "got a temperature difference",
    ),
    (
        "below absolute zero",
        "operating.temperature",
        "-300 degC",
        "operating.temperature",
        "above 0 K",
    ),
    (
        "temperature outside alpha fit",
        "operating.temperature",
        "150 degC",
        "operating.temperature",
        "must lie within lubricant.alpha_star_fit",
    ),
    ("carreau n", "lubricant.carreau.n", 1.5, "lubricant.carreau.n", "must be > 0 and <= 1"),
    (
        "frequency for speed",
        "operating.inner_ring_speed",
        "8 Hz",
        "operating.inner_ring_speed",
        "got a frequency",
    ),
    (
        "integer slices",
        "geometry.roller.slices",
        20.5,
        "geometry.roller.slices",
        "expected an integer",
    ),
    # Values that passed the configuration and then failed inside the model, with a
    # traceback or a panic: Roelands' eta_p above B1's ambient 16.5 mPa*s; a Vogel law whose
    # viscosity overflows; the alpha* fit's range far past any oil; a density and a modulus
    # no solid has.
    (
        "eta_p above the ambient viscosity",
        "lubricant.roelands.eta_p",
        "20 mPa*s",
        "lubricant.roelands.eta_p",
        "must be below the ambient viscosity",
    ),
    ("overflowing Vogel law", "lubricant.vogel.b", "1e300 K", "lubricant.vogel", "finite and > 0"),
    (
        "alpha* fit far past any oil",
        "lubricant.alpha_star_fit.t_max",
        "1e6 degC",
        "lubricant.alpha_star_fit.t_max",
        "<= 1000 degC",
    ),
    (
        "density of no solid",
        "materials.roller.density",
        "1e300 kg/m^3",
        "materials.roller.density",
        "<= 100000 kg/m^3",
    ),
    (
        "modulus of no solid",
        "materials.inner_ring.youngs_modulus",
        "1e-300 GPa",
        "materials.inner_ring.youngs_modulus",
        ">= 1 MPa",
    ),
    # values that passed the check and failed only in the run (a roller 1e300 mm long, an
    # absolute tolerance of 1e300 m: "roller 0 left the bearing")
    ("tolerance of no use", "solver.atol", 1e300, "solver.atol", "<= 0.001"),
    ("ring of no mass", "inner_ring.mass", "1e-300 kg", "inner_ring.mass", ">= 1 g"),
    ("roller of no size", "geometry.roller.length", "1e300 mm", "geometry.roller.length", "<= 1 m"),
    # a switch takes a TOML boolean: the string "false", 0 and 1 were converted silently
    (
        "string for a switch",
        "solver.friction",
        "false",
        "solver.friction",
        "expected true or false",
    ),
    ("integer for a switch", "solver.pruning", 0, "solver.pruning", "expected true or false"),
    (
        "crowned without crown",
        "geometry.roller.profile",
        "crowned",
        "geometry.roller.crown_length",
        "required for a crowned profile",
    ),
    (
        "crown on straight roller",
        "geometry.roller.crown_drop",
        "2 um",
        "geometry.roller.crown_drop",
        'needs profile = "crowned"',
    ),
    (
        "relief on a straight roller",
        "geometry.roller.relief_factor",
        0.00035,
        "geometry.roller.relief_factor",
        'only used with profile = "logarithmic" (profile is "straight")',
    ),
    (
        "relief factor too large",
        "geometry.roller.relief_factor",
        0.5,
        "geometry.roller.relief_factor",
        "<= 0.01",
    ),
    (
        "unknown detector",
        "solver.detector",
        "fast",
        "solver.detector",
        'must be one of "semi-analytical", "gradient" or "mesh"',
    ),
    ("rtol >= 1", "solver.rtol", 1.0, "solver.rtol", "must be >= 1e-12 and < 1"),
    (
        "unknown output group",
        "solver.outputs",
        ["rollers", "cage"],
        "solver.outputs.1",
        'must be one of "rollers", "flanges", "power" or "lubrication"',
    ),
    (
        "output groups not an array",
        "solver.outputs",
        "rollers",
        "solver.outputs",
        "expected an array",
    ),
    (
        "line fit range half given",
        "solver.line_fit.load_min",
        "3000 N/mm",
        "solver.line_fit.load_max",
        "give both load_min and load_max",
    ),
    (
        "speed ramp with table",
        "operating.inner_ring_speed",
        {"table": [["0 s", "0 rpm"], ["1 s", "500 rpm"]]},
        "operating.speed_ramp",
        "a speed ramp only applies to a constant speed",
    ),
    ("unknown unit", "geometry.roller.length", "5 mmm", "geometry.roller.length", "unknown unit"),
    ("section not a table", "geometry", 5, "geometry", "expected a table"),
    ("empty name", "name", "", "name", "must not be empty"),
    (
        "opening angle too big",
        "geometry.flange.opening_angle",
        "15 deg",
        "geometry.flange.opening_angle",
        "must be >= 0 and < 10 deg",  # the core's rule (geometry/end_flange.rs)
    ),
    (
        "negative LSS at p=0",
        "lubricant.limiting_shear_stress.chi",
        0.2,
        "lubricant.limiting_shear_stress.tau_l0",
        "must be >= chi*p_star",
    ),
    (
        "override flange taller than roller",
        "geometry.inner_ring_flange",
        {"height": "4.6 mm"},
        "geometry.inner_ring_flange.height",
        "must be < roller diameter",
    ),
    (
        "override unknown key",
        "geometry.outer_ring_flange",
        {"hight": "1 mm"},
        "geometry.outer_ring_flange.hight",
        "did you mean 'height'?",
    ),
    (
        "zero roughness",
        "surfaces.flange.roughness",
        "0 um",
        "surfaces.flange.roughness",
        "must be > 0",
    ),
    (
        "negative squeeze-film half-width",
        "surfaces.squeeze_film.half_width",
        "-0.5 mm",
        "surfaces.squeeze_film.half_width",
        "must be > 0",
    ),
    (
        "squeeze-film floor in seconds",
        "surfaces.squeeze_film.floor",
        "1 s",
        "surfaces.squeeze_film.floor",
        "length",
    ),
    (
        "zero velocity tolerance time",
        "solver.atol_time_scale",
        "0 s",
        "solver.atol_time_scale",
        "must be > 0",
    ),
    (
        "friction at its old place",
        "surfaces.friction",
        False,
        "surfaces.friction",
        "has moved to solver.friction (a numerical setting)",
    ),
    (
        "flange that does not exist",
        "geometry.flanges",
        ["inner-y", "outer+x"],
        "geometry.flanges.0",
        'must be one of "inner-x", "inner+x", "outer-x" or "outer+x"',
    ),
    (
        "flange named twice",
        "geometry.flanges",
        ["inner-x", "outer+x", "outer+x"],
        "geometry.flanges",
        "names each flange at most once",
    ),
    (
        "no flange on the rollers' +x side",
        "geometry.flanges",
        ["inner-x", "outer-x"],
        "geometry.flanges",
        "needs a flange on the rollers' +x side",
    ),
    (
        "type NU under B1's axial load",
        "geometry.flanges",
        ["outer-x", "outer+x"],
        "operating.axial_load",
        'only the flanges "inner-x" and "outer+x" carry; geometry.flanges has no "inner-x"',
    ),
    (
        "an output group twice",
        "solver.outputs",
        ["rollers", "rollers"],
        "solver.outputs",
        'names each group at most once ("rollers" twice)',
    ),
    (
        "flanges taller together than the annulus (each below the roller)",
        "geometry.flange.height",
        "2.3 mm",
        "geometry.flange.height",
        "the inner and outer flanges together must be lower than the annulus",
    ),
    (
        "an end time longer than the longest",
        "operating.end_time",
        "1e306 s",
        "operating.end_time",
        "must be <= 1e+05 s",
    ),
    (
        "a speed so slow that two roller-set revolutions pass the longest end time",
        "operating.inner_ring_speed",
        "1e-300 rpm",
        "operating.end_time",
        "two revolutions take that long; give operating.end_time",
    ),
    (
        "roller border band at its old place",
        "surfaces.border_band_roller",
        "1.5e-4 rad",
        "surfaces.border_band_roller",
        "has moved to solver.border_band_roller (a numerical setting)",
    ),
    (
        "flange border band at its old place",
        "surfaces.border_band_flange",
        "50 um",
        "surfaces.border_band_flange",
        "has moved to solver.border_band_flange (a numerical setting)",
    ),
]


@pytest.mark.parametrize(
    ("path", "value", "where", "rule"), [b[1:] for b in BAD], ids=[b[0] for b in BAD]
)
def test_bad_input(raw: dict, path: str, value: object, where: str, rule: str) -> None:
    with pytest.raises(ConfigError) as info:
        parse_config(mutate(raw, path, value), source="b1.toml")
    err = info.value
    lines = str(err).splitlines()
    assert lines[0].startswith("invalid configuration b1.toml")
    hits = [p for p in err.problems if p.path == where and rule in p.rule]
    assert hits, f"no problem at {where} with {rule!r} in:\n{err}"
    # each problem is one line "<path>: <value> — <rule>"
    assert f"{where}: " in str(err)
    assert all(re.match(r"^[\w.<>\- ]+: .+ — .+$", line) for line in lines[1:]), str(err)


def test_bad_input_count() -> None:
    assert len(BAD) >= 25
    assert len({b[0] for b in BAD}) == len(BAD)


def test_value_shown_as_given(raw: dict) -> None:
    with pytest.raises(ConfigError) as info:
        parse_config(mutate(raw, "geometry.flange.height", "5 mm"))
    assert 'geometry.flange.height: "5 mm" — must be < roller diameter' in str(info.value)
    with pytest.raises(ConfigError) as info:
        parse_config(mutate(raw, "geometry.inner_raceway_diameter", 20))
    line = str(info.value).splitlines()[1]
    assert line == (
        "geometry.inner_raceway_diameter: 20 — a bare number is ambiguous (no unit); "
        'expected a length with a unit, e.g. "20 mm"'
    )


def test_all_problems_reported_at_once(raw: dict) -> None:
    data = mutate(raw, "geometry.roller.length", "5 N")
    data = mutate(data, "materials.roller.poisson_ratio", 0.7)
    data = mutate(data, "solver.bogus", 1)
    with pytest.raises(ConfigError) as info:
        parse_config(data)
    paths = [p.path for p in info.value.problems]
    assert paths == ["geometry.roller.length", "materials.roller.poisson_ratio", "solver.bogus"]
    assert len(str(info.value).splitlines()) == 4


def test_inherited_flange_value_named(raw: dict) -> None:
    with pytest.raises(ConfigError) as info:
        parse_config(mutate(raw, "geometry.inner_ring_flange", {"root_radius": "1 mm"}))
    (problem,) = info.value.problems
    assert problem.path == "geometry.inner_ring_flange.height"
    assert problem.value == '"1.1 mm" (inherited from geometry.flange)'


def test_config_error_is_value_error() -> None:
    assert issubclass(ConfigError, ValueError)
    with pytest.raises(ConfigError, match="expected a table of sections"):
        parse_config([1, 2])  # type: ignore[arg-type]


# --------------------------------------------------------------------------- files


def test_malformed_toml(tmp_path: Path) -> None:
    p = tmp_path / "bad.toml"
    p.write_text('name = "x"\n[geometry]\nroller_count = = 17\n', encoding="utf-8")
    with pytest.raises(ConfigError) as info:
        load_config(p)
    msg = str(info.value)
    assert msg.startswith(f"{p}:3:")
    assert "malformed TOML" in msg


def test_duplicate_key_toml(tmp_path: Path) -> None:
    p = tmp_path / "dup.toml"
    p.write_text('name = "x"\nname = "y"\n', encoding="utf-8")
    with pytest.raises(ConfigError, match=rf"^{re.escape(str(p))}:2:.*malformed TOML"):
        load_config(p)


def test_missing_file(tmp_path: Path) -> None:
    p = tmp_path / "nope.toml"
    with pytest.raises(ConfigError, match="configuration file not found") as info:
        load_config(p)
    assert str(p) in str(info.value)


def test_not_utf8(tmp_path: Path) -> None:
    p = tmp_path / "latin1.toml"
    p.write_bytes('name = "Wälzlager"\n'.encode("latin-1"))
    with pytest.raises(ConfigError, match="not UTF-8"):
        load_config(p)


def test_invalid_file_names_source(tmp_path: Path) -> None:
    p = b1_file_with(tmp_path, '"5.0 mm"', '"5.0 N"', "b1_bad.toml")
    with pytest.raises(ConfigError) as info:
        load_config(p)
    assert info.value.source == str(p)
    assert str(info.value).splitlines()[0] == f"invalid configuration {p} (1 problem):"
    assert info.value.problems[0].path == "geometry.roller.length"


def _b1_with_solver_keys_in_surfaces(tmp_path: Path) -> Path:
    """B1's file as written before border_band_roller, border_band_flange and friction
    moved from [surfaces] to [solver]."""
    lines = B1_TEXT.splitlines(keepends=True)
    moved = [ln for ln in lines if ln.startswith(tuple(MOVED))]
    assert len(moved) == 3
    kept = [ln for ln in lines if ln not in moved]
    at = kept.index("[surfaces]\n") + 1
    path = tmp_path / "b1_old_layout.toml"
    path.write_text("".join(kept[:at] + moved + kept[at:]), encoding="utf-8")
    return path


MOVED = ("border_band_roller", "border_band_flange", "friction")


def test_every_numerical_setting_is_in_solver(b1: BearingConfig) -> None:
    """[solver] holds every numerical setting of the model (the core's ModelOptions), with
    the defaults and rules they had in [surfaces]; [surfaces] none of them."""
    solver = BearingConfig.model_fields["solver"].annotation
    surfaces = BearingConfig.model_fields["surfaces"].annotation
    for key in ("detector", "pruning", "mesh_around", "mesh_along", *MOVED):
        assert key in solver.model_fields, key  # type: ignore[union-attr]
        assert key not in surfaces.model_fields, key  # type: ignore[union-attr]
    s = b1.solver
    assert (s.border_band_roller, s.border_band_flange, s.friction) == (1.5e-4, 5e-5, True)
    defaults = parse_config(changed_b1({f"solver.{k}": None for k in MOVED})).solver
    assert (defaults.border_band_roller, defaults.border_band_flange, defaults.friction) == (
        1.5e-4,
        5e-5,
        True,
    )
    for key, value, rule in (
        ("border_band_roller", "2 deg", "must be >= 0 and <= 1 deg"),
        ("border_band_flange", "-1 um", "must be >= 0 and <= 1 mm"),
    ):
        with pytest.raises(ConfigError) as info:
            parse_config(changed_b1({f"solver.{key}": value}))
        (problem,) = info.value.problems
        assert problem.path == f"solver.{key}" and rule in problem.rule, problem


def test_a_setting_at_its_old_place_is_one_clear_line_each(tmp_path: Path) -> None:
    old = _b1_with_solver_keys_in_surfaces(tmp_path)
    with pytest.raises(ConfigError) as info:
        load_config(old)
    assert str(info.value).splitlines() == [
        f"invalid configuration {old} (3 problems):",
        'surfaces.border_band_roller: "1.5e-4 rad" — has moved to solver.border_band_roller '
        "(a numerical setting)",
        'surfaces.border_band_flange: "50 um" — has moved to solver.border_band_flange '
        "(a numerical setting)",
        "surfaces.friction: true — has moved to solver.friction (a numerical setting)",
    ]
    # other problems are still reported with them
    data = changed_b1({"surfaces.friction": False, "surfaces.damping_ratio": 5.0})
    with pytest.raises(ConfigError) as info:
        parse_config(data)
    assert [p.path for p in info.value.problems] == ["surfaces.damping_ratio", "surfaces.friction"]


def test_a_setting_at_its_old_place_is_a_clean_cli_error(tmp_path: Path) -> None:
    from typer.testing import CliRunner

    from rollerdyn.cli import app

    old = _b1_with_solver_keys_in_surfaces(tmp_path)
    for args in (
        ["check", str(old)],
        ["run", str(old), "-o", str(tmp_path / "r.nc"), "--resume", str(tmp_path / "r.nc")],
    ):
        result = CliRunner().invoke(app, args)
        assert result.exit_code == 2, result.output
        assert "surfaces.friction: true — has moved to solver.friction" in result.output
        assert "Traceback" not in result.output


# --------------------------------------------------------------------------- b1.toml itself

ORIGINS = (
    "paper",
    "B1.md",
    "Schwarz et al., Lubricants 2023, 11, 369",
    "rollerdyn default",
    "ASSUMED, to be replaced by cited values",
)


def test_b1_every_value_has_origin_comment() -> None:
    n = 0
    for number, line in enumerate(B1_TEXT.splitlines(), 1):
        stripped = line.strip()
        if not stripped or stripped.startswith(("#", "[")):
            continue
        assert "=" in stripped, f"line {number}: {line}"
        assert "#" in stripped, f"line {number} has no origin comment: {line}"
        comment = stripped.split("#", 1)[1]
        assert any(o in comment for o in ORIGINS), f"line {number}: unknown origin: {line}"
        n += 1
    assert n > 60


def test_b1_assumed_lubricant_values_marked() -> None:
    text = B1_TEXT
    for key in ("tau0", "n", "chi", "p_star", "tau_l0"):
        (line,) = [ln for ln in text.splitlines() if re.match(rf"^{key}\s*=", ln)]
        assert "ASSUMED, to be replaced by cited values" in line


def test_b1_has_no_derived_values(raw: dict) -> None:
    derived = {
        "roller_diameter",
        "pitch_diameter",
        "circumferential_gap",
        "fill_ratio",
        "end_time",
        "axial_inertia",
        # (inner_ring.transverse_inertia is data: B1.md gives it for the ring with its
        # shaft section, which no solid cylinder of the ring's mass reproduces)
        "roller_mass",
        "vogel_k",
        "roller_set_speed",
    }
    stack = [raw]
    while stack:
        table = stack.pop()
        for key, value in table.items():
            assert key not in derived, f"derived quantity {key!r} typed into b1.toml"
            if isinstance(value, dict):
                stack.append(value)
    assert raw["lubricant"]["roelands"]["z"] == "fit"


# --------------------------------------------------------------------------- docs


def _sections(model: type[BaseModel], prefix: str = "") -> dict[str, list[str]]:
    out = {prefix: list(model.model_fields)}
    for name, info in model.model_fields.items():
        stack, models = [info.annotation], []
        while stack:
            ann = stack.pop()
            if isinstance(ann, type) and issubclass(ann, BaseModel):
                models.append(ann)
            else:
                stack.extend(getattr(ann, "__args__", ()))
        for m in models:
            if not issubclass(m, TimeTable) and name not in (
                "inner_ring_flange",
                "outer_ring_flange",
            ):
                out.update(_sections(m, f"{prefix}.{name}" if prefix else name))
    return out


def test_docs_cover_every_field() -> None:
    chunks = re.split(r"^(?=### )", DOCS.read_text(encoding="utf-8"), flags=re.M)
    for section, fields in _sections(BearingConfig).items():
        tag = f"`[{section}]`" if section else "`top level`"
        found = [c for c in chunks if c.startswith("### ") and tag in c.splitlines()[0]]
        assert found, f"docs: no heading with {tag}"
        for field in fields:
            assert f"`{field}`" in found[0], f"docs: {tag} lacks `{field}`"


# --------------------------------------------------------------------------- Rust core


def test_roller_mass_properties_plumbing(monkeypatch: pytest.MonkeyPatch, raw: dict) -> None:
    calls = []

    def roller_mass_properties(diameter, length, edge_radius, end_face_radius, density):
        calls.append((diameter, length, edge_radius, end_face_radius, density))
        return {"mass": 1.0, "axial_inertia": 2.0, "transverse_inertia": 3.0}

    import rollerdyn
    from rollerdyn import _core

    fake = types.ModuleType("rollerdyn._core")
    fake.roller_mass_properties = roller_mass_properties  # type: ignore[attr-defined]
    # the configuration's check of the ambient viscosity evaluates the Vogel law
    fake.vogel_viscosity = _core.vogel_viscosity  # type: ignore[attr-defined]

    monkeypatch.setitem(sys.modules, "rollerdyn._core", fake)
    monkeypatch.setattr(rollerdyn, "_core", fake, raising=False)
    cfg = parse_config(raw)
    assert (cfg.roller_mass, cfg.roller_axial_inertia, cfg.roller_transverse_inertia) == (
        1.0,
        2.0,
        3.0,
    )
    assert cfg.roller_mass_properties == {
        "mass": 1.0,
        "axial_inertia": 2.0,
        "transverse_inertia": 3.0,
    }
    assert len(calls) == 1  # computed once per configuration
    d, length, r_e, r_f, rho = calls[0]
    assert d == pytest.approx(4.495e-3) and length == 5e-3 and r_e == 5e-4
    assert r_f == 5.0 and rho == 7850.0


def _rounded_roller(d: float, length: float, r_e: float, rho: float, n: int = 20000):
    """Mass, axial and transverse inertia of a cylinder with torus-rounded edges (flat ends)."""
    big_r, h = d / 2, length / n
    m = j_ax = j_tr = 0.0
    for i in range(n):
        x = -length / 2 + (i + 0.5) * h
        a = abs(x) - (length / 2 - r_e)
        r = big_r if a <= 0 else big_r - r_e + math.sqrt(max(0.0, r_e * r_e - a * a))
        m += rho * math.pi * r * r * h
        j_ax += rho * math.pi / 2 * r**4 * h
        j_tr += rho * (math.pi * r**4 / 4 + math.pi * r * r * x * x) * h
    return m, j_ax, j_tr


def test_roller_mass_properties_real(b1: BearingConfig) -> None:
    pytest.importorskip("rollerdyn._core")
    from rollerdyn import _core

    cfg = load_b1()  # fresh object: no value cached by other tests
    # B1.md's "about 0.62 g" is the sharp cylinder's mass to two digits (0.6229 g).
    assert math.pi * (4.495e-3 / 2) ** 2 * 5e-3 * 7850.0 == pytest.approx(0.62e-3, abs=5e-6)
    brute = _rounded_roller(4.495e-3, 5e-3, 0.5e-3, 7850.0)
    keys = ("mass", "axial_inertia", "transverse_inertia")
    # Flat ends (end sphere of 1e9 m): the core's Gauss quadrature against the 20 000
    # slices, whose midpoint rule errs by at most 1.6e-7 (measured; 8.5e-9 with 80 000)
    # where the edge torus's radius has its square-root ends.
    flat = _core.roller_mass_properties(4.495e-3, 5e-3, 0.5e-3, 1e9, 7850.0)
    for key, value in zip(keys, brute, strict=True):
        assert flat[key] == pytest.approx(value, rel=1e-6), key
    # B1's 5 m end spheres lower the ends towards the edge tori by their sagitta (0.3 µm
    # over the 1.75 mm face): 0.9e-4, 1.1e-4 and 2.0e-4 lighter (measured); 5e-4 bounds it.
    b1_values = (cfg.roller_mass, cfg.roller_axial_inertia, cfg.roller_transverse_inertia)
    for key, value, flat_value in zip(keys, b1_values, brute, strict=True):
        assert value == pytest.approx(flat_value, rel=5e-4), key
        assert value < flat_value, key


def test_misalignment_needs_the_tilt_locked(raw: dict) -> None:
    """A prescribed misalignment and a free tilt contradict each other: refused, with the
    field and the rule named; 0.05 deg with the tilt locked is accepted (in rad)."""
    with pytest.raises(ConfigError) as info:
        parse_config(
            mutate(mutate(raw, "inner_ring.tilt", "free"), "inner_ring.misalignment", "0.05 deg")
        )
    assert 'inner_ring.misalignment: "0.05 deg" — a prescribed misalignment needs tilt' in str(
        info.value
    )
    cfg = parse_config(mutate(raw, "inner_ring.misalignment", "0.05 deg"))
    assert cfg.inner_ring.misalignment == pytest.approx(math.radians(0.05), rel=1e-12)


def test_stall_step_defaults_to_a_fraction_of_dt_max(b1: BearingConfig) -> None:
    """`solver.min_mean_step` unset: the stall check stops a run whose steps average less
    than dt_max / 20 000 over 10 000 steps (50 ns for B1's 1 ms; B1's completing runs
    average at least 180 ns, docs/dynamics.md); set, its own value wins, and 0 turns the
    check off. A Δt_max below 50 ns is still valid (the check then scales with it)."""
    assert b1.solver.min_mean_step is None
    assert b1.solver.stall_step == pytest.approx(5e-8, rel=1e-12)
    data = b1.model_dump()
    set_to = parse_config(mutate(data, "solver.min_mean_step", "200 ns"), si_numbers=True)
    assert set_to.solver.stall_step == pytest.approx(2e-7, rel=1e-12)
    off = parse_config(mutate(data, "solver.min_mean_step", "0 s"), si_numbers=True)
    assert off.solver.stall_step == 0.0
    fine = parse_config(mutate(data, "solver.dt_max", "1e-7 s"), si_numbers=True)
    assert fine.solver.stall_step == pytest.approx(5e-12, rel=1e-12)


def test_an_unknown_key_that_starts_with_a_bracket_is_named():
    """Found by `test_mutated_b1_loads_or_names_the_field`: a top-level key "<" (pydantic's
    own location markers start with "<" too) was dropped from the location, and naming it
    raised IndexError. It is named as any unknown key, beside the other problems."""
    data = changed_b1({"name": math.nan, "<": []})
    with pytest.raises(ConfigError) as err:
        parse_config(data)
    text = str(err.value)
    assert "unknown key '<' in section '<top level>'" in text
    assert "name: nan" in text


# --------------------------------------------------------------------------- --set, TOML text

# TOML values as tomllib reads them (64-bit integers, finite floats: a NaN never reads back
# equal), nested in arrays and tables, with any keys and text but lone surrogates.
_TOML_TEXT = st.text(st.characters(exclude_categories=("Cs",)), max_size=8)
_TOML_VALUES = st.recursive(
    st.booleans() | st.integers(-(2**63), 2**63 - 1) | st.floats(allow_nan=False) | _TOML_TEXT,
    lambda inner: st.lists(inner, max_size=3) | st.dictionaries(_TOML_TEXT, inner, max_size=3),
    max_leaves=12,
)


@settings(max_examples=300, deadline=None)
@given(st.dictionaries(_TOML_TEXT, _TOML_VALUES, max_size=5), _TOML_TEXT)
def test_toml_text_reads_back_as_the_table(data: dict, header: str) -> None:
    """The TOML a changed configuration is recorded as (`rollerdyn run --set`) reads back
    as the table it was written from (tomllib, the reader of every configuration file):
    any keys (dots, quotes, control characters, DEL), text, floats (±inf, -0.0, 1e-300),
    integers to 64 bits, arrays of tables and tables in tables; any header (a file's name
    with control characters) is a comment that reads back as nothing."""
    text = toml_text(data, header=f"{header}\nof two lines")
    assert text is not None
    assert text.startswith("# ") and "# of two lines\n" in text
    assert tomllib.loads(text) == data


def test_toml_text_refuses_what_does_not_read_back() -> None:
    """A NaN reads back unequal, a set is no TOML value: no text (the result then records
    the configuration's SI values only)."""
    assert toml_text({"a": math.nan}) is None
    assert toml_text({"a": {1, 2}}) is None
    assert toml_text(b1_data()) is not None


def test_load_config_with_changes_records_the_changed_table(tmp_path: Path) -> None:
    """`load_config(path, changes)` (the command line's --set) changes values written as in
    the file; its TOML text, headed by the file and the changes, validates to the same
    configuration; a bad change is refused naming its path (--set) and the rule."""
    from b1 import B1

    changes = {"surfaces.flange_law": "distributed", "operating.axial_load": "500 N"}
    cfg = load_config(B1, changes)
    assert cfg.surfaces.flange_law == "distributed"
    assert cfg.operating.axial_load == 500.0
    assert cfg.toml_text is not None
    first = cfg.toml_text.splitlines()[0]
    assert first.startswith(f"# {B1}, changed: ")
    assert 'surfaces.flange_law = "distributed", operating.axial_load = "500 N"' in first
    again = parse_config(tomllib.loads(cfg.toml_text))
    assert again.model_dump() == cfg.model_dump()
    assert load_config(B1).toml_text == B1_TEXT  # no change: the file's text as read
    with pytest.raises(
        ConfigError, match=r"(?s)with --set operating\.axial_load .*expected a force"
    ):
        load_config(B1, {"operating.axial_load": 500})
    with pytest.raises(ConfigError, match="name is 'B1' in the configuration, not a table"):
        load_config(B1, {"name.first": "x"})
    # from Python: numpy's numbers and tuples are recorded as TOML numbers and arrays
    numbers = {
        "materials.roller.poisson_ratio": np.float64(0.29),
        "geometry.roller.slices": np.int64(10),
        "solver.pruning": np.bool_(False),
        "operating.axial_load": {"table": (("0 s", "0 N"), ("0.1 s", "500 N"))},
    }
    from_numpy = load_config(B1, numbers)
    assert from_numpy.toml_text is not None
    assert parse_config(tomllib.loads(from_numpy.toml_text)) == from_numpy
    assert from_numpy.geometry.roller.slices == 10 and from_numpy.solver.pruning is False
    for bad in ({1: 2}, ["surfaces.flange_law=distributed"], {"": 1}):
        with pytest.raises(ConfigError, match="expected a mapping of dotted paths"):
            load_config(B1, bad)
    odd = tmp_path / "b\x01.toml"  # a control character in the file's name
    odd.write_bytes(B1.read_bytes())
    recorded = load_config(odd, {"surfaces.flange_law": "distributed"}).toml_text
    assert recorded is not None and recorded.startswith("# ") and "b\\u0001.toml" in recorded


def test_output_groups_are_taken_once_each_in_their_order():
    """``solver.outputs``: the groups in any order, each at most once (a repeat is refused
    by name: docs/configuration.md's rule), kept in the order of OUTPUT_GROUPS; the default
    records them all, and [] none."""
    from rollerdyn.config.solver import OUTPUT_GROUPS

    groups = ("rollers", "flanges", "power", "lubrication")
    assert load_b1().solver.outputs == OUTPUT_GROUPS == groups
    changed = parse_config(changed_b1({"solver.outputs": ["power", "rollers"]}))
    assert changed.solver.outputs == ("rollers", "power")
    with pytest.raises(ConfigError, match='"power" twice'):
        parse_config(changed_b1({"solver.outputs": ["power", "rollers", "power"]}))
    assert parse_config(changed_b1({"solver.outputs": []})).solver.outputs == ()


def test_a_path_the_file_system_cannot_take_or_a_files_text_is_refused_cleanly(tmp_path):
    """A name of 300 bytes (past the file system's 255) raised OSError from Path.exists()
    through `rollerdyn check`, `run` and `validate -c` as a traceback; the file's text
    passed instead of its path raised a raw OSError (a review)."""
    with pytest.raises(ConfigError, match=r"\.\.\.: cannot be read \(File name too long\)"):
        load_config(tmp_path / ("a" * 300 + ".toml"))
    text = (Path(__file__).parents[1] / "examples" / "b1.toml").read_text()
    with pytest.raises(ConfigError, match="looks like a configuration's TOML text, not its file"):
        load_config(text)


def test_changes_take_a_pint_quantity_and_refuse_an_empty_path_part():
    """A pint Quantity as a change raised AttributeError ("Magnitude 'int' does not
    support tolist"), and "a..b" made a table of an empty key (a review)."""
    import pint

    units = pint.UnitRegistry()
    b1 = Path(__file__).parents[1] / "examples" / "b1.toml"
    cfg = load_config(b1, {"geometry.roller.length": units.Quantity(6, "mm")})
    assert cfg.geometry.roller.length == pytest.approx(6e-3)
    with pytest.raises(ConfigError, match="expected a mapping of dotted paths"):
        load_config(b1, {"a..b": 1})


def test_a_flood_of_problems_is_listed_in_part():
    """2 000 unknown keys gave a message of 2 001 lines headed by every key's path, and a
    unit of 2 000 characters was echoed whole (a review): the message lists the first 20
    problems and five paths, the error's ``problems`` keep them all."""
    b1 = Path(__file__).parents[1] / "examples" / "b1.toml"
    with pytest.raises(ConfigError) as err:
        load_config(b1, {f"x{i}": 1 for i in range(2000)})
    lines = str(err.value).splitlines()
    assert len(lines) == 22 and len(err.value.problems) == 2000
    assert lines[0].endswith("with --set x0, x1, x2, x3, x4 and 1995 more (2000 problems):")
    assert lines[-1] == "... and 1980 more problems"
    with pytest.raises(ConfigError) as err:
        load_config(b1, {"operating.radial_load": "5 " + "a" * 2000})
    assert len(str(err.value)) < 600
