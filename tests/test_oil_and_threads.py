"""The physics that holds unloaded rollers (oil film in the line-contact gaps, drag of the
oil-air mixture, gravity), its configuration, the threads of a run and the operating-point
benchmark (docs/dynamics.md, "What holds an unloaded roller")."""

from __future__ import annotations

import numpy as np
import pytest
from b1 import b1_data, changed_b1, variant

from rollerdyn import _core
from rollerdyn.bench_cases import CASES, case_config, run_case
from rollerdyn.config import ConfigError, parse_config
from rollerdyn.model import Model
from rollerdyn.simulation import model_parameters, simulate


def test_gravity_is_on_by_default_and_takes_a_vector() -> None:
    data = b1_data()
    del data["operating"]["gravity"]
    assert parse_config(data).operating.gravity == (0.0, -9.81, 0.0)
    cfg = variant(**{"operating.gravity": ["1 m/s^2", "0 m/s^2", "-2 m/s^2"]})
    assert cfg.operating.gravity == (1.0, 0.0, -2.0)
    assert model_parameters(cfg)["operating"]["gravity"] == [1.0, 0.0, -2.0]


@pytest.mark.parametrize(
    ("path", "value", "words"),
    [
        ("operating.gravity", ["9.81 m/s^2", "0 m/s^2"], "three components"),
        ("operating.gravity", "9.81 N", "acceleration"),
        ("operating.gravity", ["0 m/s^2", "1e9 m/s^2", "0 m/s^2"], "magnitude"),
        ("cavity.oil_fraction", -0.1, ">= 0"),
        ("cavity.oil_fraction", 1.5, "<= 1"),
        ("surfaces.race_film.cutoff", "0 um", "> 0"),
    ],
)
def test_bad_oil_and_gravity_input_names_the_field_and_the_rule(path, value, words) -> None:
    with pytest.raises(ConfigError) as err:
        variant(**{path: value})
    text = str(err.value)
    assert path.split(".")[-1] in text and words in text, text


def test_an_unloaded_roller_is_held_by_the_film_and_gravity_pulls_it_down() -> None:
    """At the start (rollers on the pitch circle, nothing loaded, at rest) the only forces
    are the oil films across the race gaps and gravity. At rest the films carry only the
    load of the regularised entrainment speed v_s = 1 mm/s (docs/dynamics.md): Martin's
    load 4.895*eta*v_s*R'/h over the 4 mm straight length, 5 um gaps; the outer race's R'
    (2.7 mm) above the inner's (1.8 mm), so the film pushes each roller inwards by under
    0.2 m/s^2 against a roller's 9.81 (measured: up to 0.14). A roller
    moving towards the outer race is pushed back by the film's squeeze (the paper's model:
    no force at all across a gap)."""
    cfg = variant()
    params = model_parameters(cfg)
    traction = Model(cfg).traction
    y = list(_core.initial_state(params, traction))
    dy, _ = _core.model_rhs(params, traction, 0.0, y)
    ring = 6
    z = cfg.geometry.roller_count
    accel_y = [dy[ring + 11 * i + 6] for i in range(z)]
    assert all(abs(a + 9.81) < 0.2 for a in accel_y), accel_y
    # What the films add to gravity points inwards, the same for every roller (each sees
    # the same two gaps): its radial component is negative and equal for all to round-off
    # (measured -0.1396 m/s^2 each), its tangential one nil.
    film = np.array([[dy[ring + 11 * i + 6] + 9.81, dy[ring + 11 * i + 7]] for i in range(z)])
    centre = np.array([[y[ring + 11 * i + 1], y[ring + 11 * i + 2]] for i in range(z)])
    outward = centre / np.linalg.norm(centre, axis=1)[:, None]
    radial = np.sum(film * outward, axis=1)
    tangential = film[:, 0] * outward[:, 1] - film[:, 1] * outward[:, 0]
    assert np.all(radial < -0.1), radial
    assert np.ptp(radial) < 1e-9 * abs(radial[0]), radial
    assert np.abs(tangential).max() < 1e-9 * abs(radial[0]), tangential
    # Roller 0 (at the bottom, psi = pi, centre at -y) moving down at 1 mm/s towards the
    # outer race: the squeeze film of the outer race pushes it back up.
    moving = list(y)
    moving[ring + 6] = -1e-3
    dy_moving, _ = _core.model_rhs(params, traction, 0.0, moving)
    assert dy_moving[ring + 6] > 0.0, dy_moving[ring + 6]
    off = changed_b1({"surfaces.race_film.enabled": False}, params)
    dy_off, _ = _core.model_rhs(off, traction, 0.0, moving)
    assert dy_off[ring + 6] == pytest.approx(-9.81, rel=1e-3)


def test_results_do_not_depend_on_the_thread_count() -> None:
    cfg = variant(**{"operating.load_ramp.end": "5 ms"})
    one = simulate(cfg, t_end=0.006, threads=1)
    two = simulate(cfg, t_end=0.006, threads=2)
    assert one.attrs["threads"] == 1 and two.attrs["threads"] == 2
    for name in one.data_vars:
        assert np.array_equal(one[name].values, two[name].values, equal_nan=True), name
    with pytest.raises(ValueError, match="threads"):
        simulate(cfg, t_end=0.001, threads=0)


def test_operating_point_cases_change_the_configuration_and_stop_at_the_wall_cap() -> None:
    cfg = variant()
    fast = case_config(cfg, "full-speed-3000rpm")
    assert fast.end_time == pytest.approx(0.1)
    assert fast.operating.final_inner_ring_speed == pytest.approx(3000 * 2 * np.pi / 60)
    assert case_config(cfg, "free-tilt").inner_ring.tilt == "free"
    assert case_config(cfg, "axial-0N").operating.axial_load == 0.0
    tilted = case_config(cfg, "distributed-tilt-0.05deg")
    assert tilted.inner_ring.misalignment == pytest.approx(np.radians(0.05))
    assert tilted.surfaces.flange_law == "distributed" and tilted.inner_ring.tilt == "locked"
    assert set(CASES) >= {"whole", "full-speed-500rpm", "free-tilt", "axial-0N"}
    with pytest.raises(ValueError, match="case"):
        case_config(cfg, "nope")
    result = run_case(cfg, "full-speed-500rpm", max_wall=1.0)
    assert not result.completed and 0.0 < result.reached < 0.1
    assert "stopped after 1 s" in result.message
    assert result.steps > 0 and result.sim_per_wall > 0.0


# --------------------------------------------------------------------------- equilibrium start


def _no_ramps(**changes) -> dict:
    """B1's data started from equilibrium, without its load and speed ramps."""
    return changed_b1(
        {
            "solver.start": "equilibrium",
            **changes,
            "operating.load_ramp": None,
            "operating.speed_ramp": None,
        }
    )


def test_equilibrium_start_gives_the_quasi_static_load_distribution() -> None:
    """Without gravity and axial load, at 500 rpm, the equilibrium's race loads are those of
    the quasi-static solution with the same stiffness model (Harris & Kotzalas 2007, sect.
    7.2, per roller; tests/test_dynamics.py), within 2 % of the heaviest as for the settled
    dynamic run (test a); the centrifugal force of a roller, 3.5 mN, is far below that."""
    from test_dynamics import quasi_static_loads

    cfg = parse_config(
        _no_ramps(
            **{
                "operating.gravity": "0 m/s^2",
                "operating.axial_load": "0 N",
                "operating.end_time": "0.2 ms",
                "solver.output_interval": "0.1 ms",
            }
        )
    )
    ds = simulate(cfg, threads=1)
    computed = ds.inner_normal_force.isel(time=0).values
    expected, _ = quasi_static_loads(cfg)
    assert np.abs(computed - expected).max() < 0.02 * expected.max(), (computed, expected)


def test_a_run_from_equilibrium_at_full_load_and_speed_starts_settled() -> None:
    """B1 at 5000 N, 1000 N and 500 rpm from t = 0, no ramps: the equilibrium puts the ring
    where the dynamic run settles (the whole B1 run's steady state: 48.5 um axially,
    -20.8 um radially, docs/dynamics.md) and the ring moves by less than 0.5 um over the
    first 5 ms (at rest on the pitch circle it would fall through its 5 um of clearance and
    travel 48 um axially)."""
    cfg = parse_config(
        _no_ramps(**{"operating.end_time": "5 ms", "solver.output_interval": "0.5 ms"})
    )
    ds = simulate(cfg, threads=1)
    ring = ds.ring_position.values
    assert abs(ring[0, 0] - 48.5e-6) < 0.5e-6 and abs(ring[0, 1] + 20.8e-6) < 0.5e-6, ring[0]
    assert np.abs(ring - ring[0]).max() < 0.5e-6, np.abs(ring - ring[0]).max()
    assert ds.inner_normal_force.isel(time=0).max() > 1000.0


def test_no_equilibrium_is_a_clear_error_naming_the_residual_and_the_body() -> None:
    # 30 kN axially is more than B1's flanges carry before the rollers ride over their
    # rims (a radial load large enough to have no equilibrium is refused by the
    # configuration's load limit before any work). The point law's load check refuses the
    # run first, in the quasi-static solver's words for the full load; forced past it, the
    # start itself finds no equilibrium.
    cfg = parse_config(_no_ramps(**{"operating.axial_load": "30 kN"}))
    # the quasi-static solver's message: the load level reached, the residual, the body
    with pytest.raises(
        ValueError,
        match=r"solver.start = equilibrium: no equilibrium found at t = 0 s: .* reached \d+ % of "
        r"the load; .* residual is \S+ on (the inner ring|roller \d+) \(",
    ):
        simulate(cfg, t_end=0.001, threads=1, force=True)
    with pytest.raises(
        ValueError,
        match=r"the point law finds no quasi-static equilibrium \(at the full load: no "
        r"quasi-static equilibrium: reached \d+ % of the load; .* residual is \S+ on "
        r"(the inner ring|roller \d+) \(",
    ):
        simulate(cfg, t_end=0.001, threads=1)


def test_a_distributed_law_run_starts_settled_where_the_point_law_finds_no_equilibrium() -> None:
    """B1 at 2500 N axially: the roller ends lie on their faces, where the point law finds
    no equilibrium (and refuses the run, docs/dynamics.md); the statics have the
    configuration's law, and with the distributed law the run starts from its equilibrium:
    the flanges carry the axial load (the inner ring's flanges' axial forces sum to 2500 N
    within 0.1 %: what the equilibrium leaves out, the flange friction, acts in the flange
    faces, tilted by 0.11° from the axis' normal plane) and the ring moves by less than
    0.5 um over the first 3 ms. At 3000 N the equilibrium presses a flange rim past ISO 76's
    4 GPa, and the start says so."""

    def b1_at(axial: str, law: str) -> dict:
        return _no_ramps(
            **{
                "operating.axial_load": axial,
                "surfaces.flange_law": law,
                "operating.end_time": "3 ms",
                "solver.output_interval": "0.5 ms",
            }
        )

    ds = simulate(parse_config(b1_at("2.5 kN", "distributed")), threads=1)
    ring = ds.ring_position.values
    assert np.abs(ring - ring[0]).max() < 0.5e-6, np.abs(ring - ring[0]).max()
    inner = ds.flange_axial_force.isel(time=0).sel(flange=["inner-x", "inner+x"])
    carried = abs(float(np.nansum(inner.values)))
    assert abs(carried - 2500.0) < 2.5, carried
    with pytest.raises(ValueError, match='lies on its end face .* use surfaces.flange_law = "dis'):
        simulate(parse_config(b1_at("2.5 kN", "point")), t_end=0.001, threads=1)
    with pytest.raises(ValueError, match="no equilibrium found .* flanges cannot carry it"):
        simulate(parse_config(b1_at("3 kN", "distributed")), t_end=0.001, threads=1)


def test_the_point_laws_load_check_is_a_rule_of_thumb_that_force_overrides() -> None:
    """The point law's check refuses a run whose equilibrium puts the most loaded roller end
    on its end face (docs/dynamics.md, "The whole B1 run"). Without radial load it does so
    from about 100 N axially (roller ends on their faces at 7 N), where a run measured on
    2026-11-30 still goes (full speed to 0.1 s: 4 285 steps against B1's 3 471); at 300 N
    it creeps (44 197 steps) and at 1000 N it stops. So the refusal names the remedy and
    `force=True` (`--force`) runs it: here 1 ms from the equilibrium at 100 N."""
    cfg = parse_config(
        _no_ramps(
            **{
                "operating.radial_load": "0 N",
                "operating.axial_load": "100 N",
                "operating.end_time": "1 ms",
                "solver.output_interval": "0.5 ms",
            }
        )
    )
    with pytest.raises(ValueError, match=r"lies on its end face .* or force the run \(--force"):
        simulate(cfg, threads=1)
    ds = simulate(cfg, threads=1, force=True)
    assert ds.attrs["completed"] == 1 and float(ds.time[-1]) == pytest.approx(1e-3)
    # the file says what was forced, in the refusal's own words
    assert ds.attrs["forced"].startswith("run with --force past the point law's load check")
    assert "lies on its end face" in ds.attrs["forced"]
    # a forced run resumed (no check on resuming) keeps what its first part was forced past
    half = simulate(cfg, t_end=5e-4, threads=1, force=True)
    rest = simulate(cfg, threads=1, resume=half)
    assert rest.attrs["forced"] == half.attrs["forced"] and rest.attrs["completed"] == 1
    # it started from the equilibrium of the load it was refused for: the inner ring's
    # flanges carry the 100 N (within 0.1 %, as at 2500 N above; measured 100.01 N)
    carried = ds.flange_axial_force.isel(time=0).sel(flange=["inner-x", "inner+x"])
    assert abs(abs(float(np.nansum(carried.values))) - 100.0) < 0.1, carried.values


def test_a_case_that_cannot_start_is_reported_not_raised() -> None:
    """B1 at 30 kN axially: the point law's check refuses it before the start (no
    equilibrium at the full load, one past ISO 76 at 16.5 kN); with the distributed law the
    start from equilibrium finds none. Both are reported as the case's message."""
    cfg = variant(**{"operating.axial_load": "30 kN"})
    result = run_case(cfg, "equilibrium-500rpm", max_wall=10.0)
    assert not result.completed and result.steps == 0
    assert "the point law finds no quasi-static equilibrium" in result.message
    distributed = variant(**{"operating.axial_load": "30 kN", "surfaces.flange_law": "distributed"})
    result = run_case(distributed, "equilibrium-500rpm", max_wall=10.0)
    assert not result.completed and result.steps == 0
    assert "no equilibrium found" in result.message, result.message


def test_more_threads_than_cores_are_not_started() -> None:
    """The helper threads spin between jobs (docs/dynamics.md, "Time integration"), so
    helpers beyond the cores would only wait for them: 64 threads on this 2-core machine
    took B1 to 0.05 s in 110 s against 2.4 s on 2. The run uses at most the cores this
    process may use, says so in its attributes, and gives the same numbers."""
    import os

    cores = len(os.sched_getaffinity(0))
    cfg = variant(**{"operating.load_ramp.end": "5 ms"})
    many = simulate(cfg, t_end=0.002, threads=64)
    one = simulate(cfg, t_end=0.002, threads=1)
    assert many.attrs["threads"] == min(64, cores)
    for name in one.data_vars:
        assert np.array_equal(many[name].values, one[name].values, equal_nan=True), name
