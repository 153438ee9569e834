"""The lubrication a result records at every contact (solver.outputs group "lubrication";
not among the paper's outputs) and its summary, rollerdyn.lubrication.

The core's values are tested against Hertz's line contact and the exact ellipse in
crates/rollerdyn-core/src/bearing/lubrication_tests.rs; here the result's variables, the
film against a classical estimate, and the summary table.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from b1 import load_b1, variant

from rollerdyn.bench_cases import CASES
from rollerdyn.lubrication import LUBRICATION_COLUMNS, lubrication_by_contact
from rollerdyn.model import Model
from rollerdyn.simulation import simulate
from rollerdyn.tribology import effective_modulus


@pytest.fixture(scope="module")
def at_speed():
    """B1 from its equilibrium at full load and speed (500 rpm, no ramps), 20 ms: the
    rollers meet their neighbours within the first milliseconds."""
    return simulate(variant(**CASES["equilibrium-500rpm"][1]), t_end=0.02, threads=1)


def test_each_contact_records_pressure_film_lambda_and_sliding_with_units(at_speed):
    ds = at_speed
    cfg = load_b1()
    roughness = {
        "inner": cfg.surfaces.raceway.roughness,
        "outer": cfg.surfaces.raceway.roughness,
        "roller_roller": cfg.surfaces.roller_roller_pair.roughness,
        "flange": cfg.surfaces.flange.roughness,
    }
    units = {
        "max_pressure": "Pa",
        "film_thickness": "m",
        "specific_film_thickness": "1",
        "sliding_speed": "m/s",
    }
    for contact, sigma in roughness.items():
        for name, unit in units.items():
            assert ds[f"{contact}_{name}"].attrs["units"] == unit
        pressure = ds[f"{contact}_max_pressure"].values
        film = ds[f"{contact}_film_thickness"].values
        lam = ds[f"{contact}_specific_film_thickness"].values
        touching = pressure > 0.0
        assert touching.any() and (~touching).any(), contact
        # no film where nothing touches; Lambda is the film over the composite roughness
        assert np.isnan(film[~touching]).all() and np.isnan(lam[~touching]).all()
        assert np.all(film[touching] > 0.0)
        np.testing.assert_allclose(lam[touching], film[touching] / sigma, rtol=1e-14)
    # the loaded rollers carry the axial load from the inner ring's -x flange to the outer
    # ring's +x flange (about 140 N each): Hertz pressures of GPa on the nearly flat end
    loaded = ds.flange_normal_force.values > 100.0
    assert loaded.any() and (ds.flange_max_pressure.values[loaded] > 1e9).all()


def test_the_race_film_is_a_classical_line_contacts_film(at_speed):
    """The central film at the most loaded inner race contact against Dowson & Toyoda's
    central film of an isothermal line contact (1979; Hamrock, Schmid & Jacobson,
    Fundamentals of Fluid Film Lubrication, 2004, the chapter on rectangular conjunctions):
    H_c = 3.06 U^0.69 G^0.56 W^-0.10, U = eta0 u0 / (E' R'), G = alpha E', W = q / (E' R').
    The model takes Moes' fit (eqs. 33-38) with Roelands' viscosity through Blok's alpha*
    (eq. 31) and the thermal correction (eq. 47): measured 0.945 of Dowson & Toyoda's
    (31.7 nm against 33.5 nm; D&T here at the roller's mean line load, the model's film at
    its most loaded slice, which carries about a quarter more: at equal load about 0.967,
    an independent review's figure). Bound 10 %: two fits of numerical solutions with their own
    pressure-viscosity laws, and a thermal factor of a few per cent, against the film of
    another contact (the outer race's R' is 1.45 times the inner's: about 20 % more film)
    or a slice less loaded. The entrainment speed is the rolling speed (ring speed less
    roller-set speed) times the raceway radius: B1's loaded rollers slide at slide-to-roll
    ratios of about 1e-3 (checked below 1e-2)."""
    ds = at_speed.isel(time=-1)
    cfg = load_b1()
    model = Model(cfg)
    i = int(np.argmax(ds.inner_normal_force.values))
    q = float(ds.inner_normal_force[i]) / cfg.geometry.roller.effective_length
    r_race = cfg.geometry.inner_raceway_diameter / 2
    r_roller = cfg.geometry.roller_diameter / 2
    r_eff = 1.0 / (1.0 / r_race + 1.0 / r_roller)
    m = cfg.materials
    e_prime = effective_modulus(
        m.roller.youngs_modulus,
        m.roller.poisson_ratio,
        m.inner_ring.youngs_modulus,
        m.inner_ring.poisson_ratio,
    )
    u0 = (float(ds.ring_speed) - float(ds.orbital_speed[i])) * r_race
    assert abs(float(ds.srr_inner[i])) < 1e-2
    u, g, w = model.eta0 * u0 / (e_prime * r_eff), model.alpha_star * e_prime, q / (e_prime * r_eff)
    classical = 3.06 * u**0.69 * g**0.56 * w**-0.10 * r_eff
    film = float(ds.inner_film_thickness[i])
    assert film == pytest.approx(classical, rel=0.10), (film, classical)


def test_the_summary_sorts_every_contact_into_a_regime(at_speed):
    ds = at_speed
    rows = lubrication_by_contact(ds, np.ones(ds.sizes["time"], dtype=bool))
    assert [name for name, _ in rows] == ["inner race", "outer race", "roller pairs", "flanges"]
    for name, values in rows:
        assert len(values) == len(LUBRICATION_COLUMNS)
        p0, at_most, smallest, median, boundary, mixed, full, speed = values
        assert p0 > 0.0 and speed >= 0.0, name
        assert smallest <= median and smallest <= at_most, name
        assert boundary + mixed + full == pytest.approx(100.0, abs=1e-9), name
    # p0 in GPa: the most loaded race slice of B1 near 2.8 GPa (docs/dynamics.md)
    assert 2.0 < rows[0][1][0] < 3.5
    # a result that did not record it says so (None), and so does a window without contact
    bare = ds.drop_vars([v for v in ds.data_vars if v.startswith("flange_")])
    assert lubrication_by_contact(bare, np.ones(ds.sizes["time"], dtype=bool)) is None
    nowhere = lubrication_by_contact(ds, np.zeros(ds.sizes["time"], dtype=bool))
    assert all(v[0] == 0.0 and all(math.isnan(x) for x in v[1:]) for _, v in nowhere)


def test_plot_draws_lambda_over_azimuth_where_a_film_is_and_nothing_where_none_is(
    at_speed, tmp_path
):
    """``rollerdyn plot``'s lubrication_over_azimuth: drawn from a rolling result; from one
    in which nothing touches yet (its films all NaN) no figure and no error, as a log scale
    has nothing to show."""
    from rollerdyn.plots import plot_results
    from rollerdyn.simulation import write

    write(at_speed, tmp_path / "rolling.nc")
    drawn = {p.name for p in plot_results([tmp_path / "rolling.nc"], tmp_path / "a")}
    assert {"lubrication_over_azimuth.png", "lubrication_over_azimuth.svg"} <= drawn
    dry = at_speed.copy()
    for name in dry.data_vars:
        if name.endswith(("_film_thickness", "_specific_film_thickness")):
            dry[name] = dry[name] * np.nan
    write(dry, tmp_path / "dry.nc")
    drawn = {p.name for p in plot_results([tmp_path / "dry.nc"], tmp_path / "b")}
    assert "fig10_frictional_torque.png" in drawn
    assert not any(name.startswith("lubrication") for name in drawn)


def test_the_statics_race_films_are_the_runs_at_the_same_operating_point(at_speed):
    """``rollerdyn statics`` gives each roller's race films in rolling without slip
    (rollerdyn.lubrication.rolling_race_films); the dynamic run from that equilibrium
    records the film its slices see. At the most loaded roller they agree within 0.5 %
    (measured 0.16 % inner, 0.22 % outer: the run's rollers slide a little, which the
    thermal factor sees, it reads Moes' film from a table, and its loads move by the
    damping and the drag); and the statics' smallest Lambda is that film over the
    roughness. At rest there is no film (NaN)."""
    from rollerdyn.statics import statics

    cfg = variant(**CASES["equilibrium-500rpm"][1])
    ds = statics(cfg)
    last = at_speed.isel(time=-1)
    sigma = cfg.surfaces.raceway.roughness
    for race in ("inner", "outer"):
        static = np.nanmin(ds[f"{race}_film_thickness"].values)
        load = last[f"{race}_normal_force"].values
        dynamic = float(last[f"{race}_film_thickness"].values[np.argmax(load)])
        assert static == pytest.approx(dynamic, rel=5e-3), race
    smallest = np.nanmin(ds.inner_film_thickness.values) / sigma
    assert float(ds.min_specific_film_thickness) == pytest.approx(smallest, rel=1e-12)
    resting = statics(cfg, speed=0.0)
    assert math.isnan(float(resting.min_specific_film_thickness))
    assert np.isnan(resting.inner_film_thickness.values).all()
