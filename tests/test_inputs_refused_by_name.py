"""Bad input to the Python API refused by the project's own errors, each naming the field
or argument, the value and the rule (an adversarial review of the Python API, items 3,
5-15 and 17): no bare RecursionError, OverflowError, AttributeError, KeyError or numpy
message from deep inside, no silent NaN, no result lost at the end of a run."""

from __future__ import annotations

import math
import tomllib

import numpy as np
import pytest
from b1 import B1, b1_file_with
from typer.testing import CliRunner

import rollerdyn
from rollerdyn import life
from rollerdyn import tribology as tri
from rollerdyn.cli import app
from rollerdyn.config import ConfigError, load_config, parse_config
from rollerdyn.model import Model
from rollerdyn.starter import StarterError, new_bearing
from rollerdyn.statics import (
    TORQUE_RELATIVE_SPEED,
    StaticsError,
    statics,
    statics_sweep,
)

RUNNER = CliRunner()


# --------------------------------------------------------------------------- 3: text fields


@pytest.mark.parametrize(
    ("field", "value", "shown"),
    [
        ("name", "B1\x00", r'"B1\u0000"'),
        ("name", "my\nbearing", r'"my\nbearing"'),
        ("description", "notes\x00", r'"notes\u0000"'),
        ("description", "a\x07bell", r'"a\u0007bell"'),
        ("lubricant.name", "oil\x7f", r'"oil\u007f"'),
    ],
)
def test_control_characters_in_text_fields_are_refused_by_name(field, value, shown):
    """A NUL was accepted, the whole run made, and its result then could not be written
    (netCDF's strings refuse NULs): refused at load time, naming the field; the message
    shows the character escaped and holds none."""
    with pytest.raises(ConfigError) as err:
        load_config(B1, {field: value})
    (problem,) = err.value.problems
    assert problem.path == field
    assert problem.value == shown
    assert "must not hold control characters" in problem.rule
    assert not any(c in str(err.value) for c in "\x00\x07\x7f")


def test_a_nul_written_in_the_file_is_refused(tmp_path):
    path = b1_file_with(tmp_path, 'name = "B1"', 'name = "B1\\u0000x"')
    with pytest.raises(ConfigError, match=r"name: .* must not hold control characters"):
        load_config(path)
    result = RUNNER.invoke(app, ["check", str(path)])
    assert result.exit_code == 2, result.output
    assert "Traceback" not in result.output


def test_a_description_keeps_its_tabs_and_line_breaks():
    cfg = load_config(B1, {"description": "line one\n\tline two\r\n"})
    assert cfg.description == "line one\n\tline two\r\n"


# --------------------------------------------------------------------------- 5: deep TOML


@pytest.mark.parametrize(
    "text",
    ["x = " + "[" * 600 + "]" * 600 + "\n", "x = " + "{a = " * 600 + "1" + "}" * 600 + "\n"],
    ids=["arrays", "inline tables"],
)
def test_deeply_nested_toml_is_a_config_error(tmp_path, text):
    path = tmp_path / "deep.toml"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(ConfigError, match="malformed TOML — arrays or tables nested too deeply"):
        load_config(path)


def test_deeply_nested_values_in_python_are_a_config_error():
    deep: dict = {}
    inner = deep
    for _ in range(3000):
        inner["a"] = {}
        inner = inner["a"]
    with pytest.raises(ConfigError, match="nested too deeply"):
        parse_config({"name": "x", "geometry": deep})
    with pytest.raises(ConfigError, match="nested too deeply"):
        load_config(B1, {"description": deep})


# --------------------------------------------------------------------------- 6: huge integers


def test_a_huge_integer_in_a_file_names_its_field(tmp_path):
    path = b1_file_with(tmp_path, "rtol = 1e-5", "rtol = 1" + "0" * 400)
    with pytest.raises(ConfigError) as err:
        load_config(path)
    (problem,) = err.value.problems
    assert problem.path == "solver.rtol"
    assert "401 digits" in problem.value and "64-bit range" in problem.rule
    result = RUNNER.invoke(app, ["check", str(path)])
    assert result.exit_code == 2, result.output
    assert "solver.rtol" in result.output and "Traceback" not in result.output


def test_huge_integers_from_python_are_listed_with_the_other_problems():
    with pytest.raises(ConfigError) as err:
        load_config(
            B1,
            {
                "solver.rtol": 10**400,
                "operating.gravity": [0, -(10**400), 0],
                "geometry.roller.slices": 2**64,
                "solver.atol": -1.0,
            },
        )
    paths = {p.path: p.rule for p in err.value.problems}
    assert set(paths) == {
        "solver.rtol",
        "operating.gravity.1",
        "geometry.roller.slices",
        "solver.atol",
    }
    assert "64-bit range" in paths["geometry.roller.slices"]
    assert "64-bit range" not in paths["solver.atol"]


def test_an_integer_beyond_pythons_digit_limit_is_malformed_toml(tmp_path):
    path = b1_file_with(tmp_path, "rtol = 1e-5", "rtol = 1" + "0" * 5000)
    with pytest.raises(ConfigError, match="malformed TOML — an integer of more than"):
        load_config(path)


# --------------------------------------------------------------------------- 7: copies, Model


def test_a_copy_computes_its_own_roller_mass():
    cfg = load_config(B1)
    mass = cfg.roller_mass  # computed and cached
    roller = cfg.geometry.roller.model_copy(update={"length": 0.010})
    longer = cfg.model_copy(update={"geometry": cfg.geometry.model_copy(update={"roller": roller})})
    expected = parse_config(longer.model_dump(), si_numbers=True).roller_mass
    assert longer.roller_mass == expected != mass
    assert cfg.roller_mass == mass


def test_model_takes_a_configuration_or_its_path():
    assert Model(str(B1)).eta0 == Model(B1).eta0 == Model(load_config(B1)).eta0
    for bad in (None, 5, {"name": "B1"}):
        with pytest.raises(ConfigError, match=r"config = .*: expected a BearingConfig"):
            Model(bad)


# --------------------------------------------------------------------------- 8: notes


@pytest.mark.parametrize("t_end", [math.nan, -1.0, math.inf, 0.0, "50 kg", [1.0]])
def test_configuration_notes_refuse_a_bad_t_end(b1, t_end):
    with pytest.raises(ValueError, match=r"^t_end = "):
        rollerdyn.configuration_notes(b1, t_end)


def test_configuration_notes_read_t_end_as_simulate_does():
    big = load_config(B1, {"operating.radial_load": "20 kN"})
    assert rollerdyn.configuration_notes(big, "1 s") == rollerdyn.configuration_notes(big, 1.0)
    assert rollerdyn.configuration_notes(big, "50 ms") == rollerdyn.configuration_notes(big, 0.05)


def test_configuration_notes_validate_a_copy(b1):
    one = b1.model_copy(update={"geometry": b1.geometry.model_copy(update={"roller_count": 1})})
    with pytest.raises(ConfigError, match="geometry.roller_count: 1 — must be >= 3"):
        rollerdyn.configuration_notes(one)


# --------------------------------------------------------------------------- 9: tribology


@pytest.mark.parametrize(
    ("call", "named"),
    [
        (lambda: tri.boundary_friction_coefficient(None, 1.0, 0.1, 0.02, 1e-3), "sliding_speed"),
        (lambda: tri.hertz_point_force(1e-3, 5e-3, 2.3e11, None, "exact"), "penetration = None"),
        (lambda: tri.roelands_viscosity("1 GPa", 0.016, 6.31e-5, -1.96e8, 0.6), "pressure"),
        (lambda: tri.vogel_viscosity("80 degC", 6e-5, 1021.7, 101.55), "temperature"),
        (lambda: tri.roelands_viscosity(1e8, 0.016, 6.31e-5, "x", 0.6), "p_p = 'x'"),
        (
            lambda: tri.boundary_friction_coefficient(0.1, 1.0, [0.1, 0.2], 0.02, 1e-3),
            "mu_b0 = [0.1, 0.2]: must be a single number",
        ),
        (
            lambda: tri.hertz_point(1e-3, 5e-3, 2.3e11, 100.0, 0.0),
            'method_name = 0.0: must be "brewe_hamrock" or "exact"',
        ),
        (
            lambda: tri.tripp_deflection(1e5, 2e-3, 5, 1e-2, 0, 2e11, 0.3, 2e11, 0.3),
            "counterface = 5",
        ),
        (lambda: tri.hertz_point(1e-3, 5e-3 + 1j, 2.3e11, 100.0, "exact"), "not complex"),
        (lambda: tri.hertz_point(True, 5e-3, 2.3e11, 100.0, "exact"), "r1 = True"),
        (lambda: tri.effective_modulus([2e11], 0.3, 2e11, 0.3), "e1 = [200000000000.0]"),
        (
            lambda: tri.hertz_point(1e-3, [5e-3, 1e-2], 2.3e11, [1.0, 2.0, 3.0], "exact"),
            "r2 (2,), e_prime (), force (3,)",
        ),
    ],
)
def test_tribology_refuses_arguments_by_name(call, named):
    with pytest.raises(ValueError) as err:
        call()
    assert named in str(err.value)


def test_tribology_takes_numpy_scalars_and_zero_d_arrays():
    mu = tri.boundary_friction_coefficient(0.1, 1.0, np.float64(0.1), np.array(0.02), 1e-3)
    assert mu == tri.boundary_friction_coefficient(0.1, 1.0, 0.1, 0.02, 1e-3)
    assert tri.effective_modulus(np.float64(2e11), 0.3, 2e11, 0.3) == pytest.approx(2.1978e11, 1e-4)


# --------------------------------------------------------------------------- 10: friction torque


def test_friction_torque_is_nan_where_the_rings_turn_together(b1):
    """The torque P / (relative speed) was NaN at equal speeds and 1e7 N*m at 1e-9 apart;
    below 1 % of the rings' speed it is NaN, and the description says why."""
    w = b1.operating.final_inner_ring_speed
    for share in (0.0, 1e-9, 0.5 * TORQUE_RELATIVE_SPEED):
        ds = statics(b1, outer_speed=w * (1.0 - share))
        assert math.isnan(float(ds.friction_torque))
        assert float(ds.friction_power.sum()) > 0.0
    assert "turn together" in ds.friction_torque.attrs["description"]
    fixed = float(statics(b1, outer_speed=0.0).friction_torque)
    near = float(statics(b1, outer_speed=w * 0.9).friction_torque)
    assert 0.25 < fixed < 0.35 and near == pytest.approx(fixed, rel=0.1)


def test_the_cli_says_the_rings_turn_together():
    result = RUNNER.invoke(app, ["statics", str(B1), "--set", "operating.outer_ring_speed=500 rpm"])
    assert result.exit_code == 0, result.output
    assert "n/a: the rings turn together" in result.output


# --------------------------------------------------------------------------- 11: resume


def test_resume_from_a_time_trimmed_result_is_refused():
    cfg = load_config(B1, {"solver.checkpoint_interval": "1 ms"})
    first = rollerdyn.simulate(cfg, t_end="3.5 ms")  # checkpoint at 3 ms
    for trimmed, missing in (
        (first.isel(time=slice(0, 2)), "0.002 s"),
        (first.isel(time=slice(1, None)), "0 s"),
        (first.isel(time=[0, 1, 3, 4]), "0.002 s"),
    ):
        with pytest.raises(ValueError, match=rf"resume: .* no output at t = {missing}"):
            rollerdyn.simulate(cfg, t_end="5 ms", resume=trimmed)
    # the outputs after the checkpoint are computed again: those may be cut
    joined = rollerdyn.simulate(cfg, t_end="5 ms", resume=first.isel(time=slice(0, 4)))
    np.testing.assert_allclose(joined.time.values, [0.0, 0.001, 0.002, 0.003, 0.004, 0.005])


# --------------------------------------------------------------------------- 12: starter


@pytest.mark.parametrize(
    ("call", "named"),
    [
        (lambda: new_bearing(40e-3, 52e-3, "my\nbearing"), "--name 'my\\nbearing': must not"),
        (lambda: new_bearing(40e-3, 52e-3, "x\x01"), "must not hold control characters"),
        (lambda: new_bearing(40e-3, 52e-3, None), "--name None"),
        (lambda: new_bearing(None, 52e-3), "inner_raceway = None"),
        (lambda: new_bearing("40", "52 mm"), "inner_raceway = '40': a number without a unit"),
        (lambda: new_bearing(40e-3, 52e-3, "x", radial_load="5 kg"), "radial_load = '5 kg'"),
        (lambda: new_bearing(40e-3, 52e-3, "x", speed=[1.0]), "speed = [1.0]"),
        (lambda: new_bearing(40e-3, 52e-3, "x", rollers=5.0), "rollers = 5.0"),
        (lambda: new_bearing(40e-3, 52e-3, "x", bearing_type=["NU"]), "--type ['NU']"),
        (lambda: new_bearing(40e-3, 52e-3, "x", load=1.0), "load: not an option"),
    ],
)
def test_new_bearing_refuses_arguments_by_name(call, named):
    with pytest.raises(StarterError) as err:
        call()
    assert named in str(err.value)


def test_new_bearing_takes_quantities_as_rollerdyn_new_does():
    text = new_bearing("40 mm", "52 mm", 'a "quoted" \\ name', radial_load="5 kN")
    cfg = parse_config(tomllib.loads(text))
    assert cfg.name == 'a "quoted" \\ name'
    assert cfg.geometry.inner_raceway_diameter == 0.04
    assert cfg.operating.radial_load == 5000.0


# --------------------------------------------------------------------------- 13: statics_sweep


def test_statics_sweep_checks_progress_and_design(b1):
    with pytest.raises(StaticsError, match=r"progress = 5: must be a function"):
        statics_sweep(b1, {"operating.radial_load": [1000.0]}, progress=5)
    with pytest.raises(StaticsError, match=r"design = \['geometry.diametral_clearance'\]"):
        statics_sweep(
            B1, {"operating.radial_load": [1000.0]}, design=["geometry.diametral_clearance"]
        )


# --------------------------------------------------------------------------- 14: hints


@pytest.mark.parametrize("law", ["point", "distributed"])
def test_one_slice_under_an_axial_load_names_the_slices(law):
    cfg = load_config(B1, {"geometry.roller.slices": 1, "surfaces.flange_law": law})
    with pytest.raises(StaticsError) as err:
        statics(cfg)
    message = str(err.value)
    assert "no quasi-static equilibrium" in message
    assert "geometry.roller.slices = 1" in message
    assert 'try surfaces.flange_law = "distributed"' not in message
    swept = statics_sweep(cfg, {"operating.axial_load": [0.0, 500.0]})
    assert swept.error.values[0] == ""
    assert "geometry.roller.slices = 1" in str(swept.error.values[1])
    if law == "point":  # a run's refusal advised the distributed law (a review)
        from rollerdyn.simulation import simulate

        with pytest.raises(ValueError) as refused:
            simulate(cfg, t_end="0.5 ms")
        message = str(refused.value)
        assert "(radial 0.012337 N, axial 0.0024674 N)" in message
        assert message.endswith("give more slices (B1 has 20)"), message
        assert 'use surfaces.flange_law = "distributed"' not in message


def test_no_axial_load_no_tipping_hint():
    cfg = load_config(B1, {"operating.gravity": "0 m/s^2"})
    with pytest.raises(StaticsError) as err:
        statics(cfg, radial_load=1e-6, axial_load=0.0)
    message = str(err.value)
    assert "axial load tips" not in message
    assert "too small to resolve" in message


# --------------------------------------------------------------------------- 15: arrays


def test_a_numpy_array_for_a_vector():
    gravity = np.array(["0 m/s^2", "-9.81 m/s^2", "0 m/s^2"])
    cfg = load_config(B1, {"operating.gravity": gravity})
    assert cfg.operating.gravity == (0.0, -9.81, 0.0)
    assert load_config(B1, {"operating.gravity": list(gravity)}).operating.gravity == (
        0.0,
        -9.81,
        0.0,
    )
    with pytest.raises(ConfigError, match="operating.gravity: .* three components"):
        load_config(B1, {"operating.gravity": gravity.reshape(1, 3)})


# --------------------------------------------------------------------------- 17: life


@pytest.mark.parametrize(
    ("call", "named"),
    [
        (lambda: life.basic_rating_life([1, 2], [1, 2, 3]), "c, p: their shapes must broadcast"),
        (lambda: life.viscosity_ratio([1e-5, 2e-5], [100, 200, 300], 0.03), "speed_rpm (3,)"),
        (lambda: life.reference_viscosity([100, 2000], [0.03, 0.04, 0.05]), "pitch_diameter"),
        (lambda: life.life_modification_factor([1, 2], [1, 2, 3]), "kappa, ec_cu_over_p"),
        (
            lambda: life.equivalent_lamina_loads(np.ones((2, 2)) * 1j, np.ones((2, 2))),
            "q_inner: must be real",
        ),
        (lambda: life.basic_rating_life(1 + 0j, 1.0), "c: must be real"),
        (lambda: life.reference_equivalent_load(1j, 1000.0), "l10r: must be a number"),
        (lambda: life.basic_rating_life(10**400, 1.0), "c: must be a number"),
    ],
)
def test_life_refuses_arguments_by_name(call, named):
    with pytest.raises(ValueError) as err:
        call()
    assert named in str(err.value)
