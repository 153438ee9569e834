"""The quasi-static analysis (``rollerdyn.statics``, core ``bearing/quasi_static``) against
closed forms: Stribeck's load distribution, the stiffness against differences of
equilibria, the centrifugal force, and its refusals."""

from __future__ import annotations

import math

import numpy as np
import pytest
from b1 import B1, load_b1, variant
from typer.testing import CliRunner

from rollerdyn import life
from rollerdyn.cli import app
from rollerdyn.statics import StaticsError, parse_range, statics, statics_sweep


def _stribeck_shares(azimuth_deg: np.ndarray, exponent: float) -> np.ndarray:
    """Discrete Stribeck distribution for zero clearance (Harris & Kotzalas, Rolling Bearing
    Analysis, sect. 7.2): with the ring moved by delta_r along the load, roller j at psi_j
    from the load line is compressed by delta_r cos psi_j, carries K (delta_r cos psi_j)^n,
    and the loads sum to F_r along the load: Q_j / F_r = cos^n / sum(cos^(n+1))."""
    # the rollers' azimuths from +y; the load along -y (azimuth 180 deg)
    c = np.clip(-np.cos(np.radians(azimuth_deg)), 0.0, None)
    return c**exponent / np.sum(c ** (exponent + 1))


def test_zero_clearance_follows_stribeck():
    """B1 without clearance, gravity and speed: every roller's load is Stribeck's discrete
    share within 1 % of the heaviest (the inner and outer power laws of eq. 11 differ a
    little in k2, so their series law is not exactly a power law), and Z Q_max / F_r is
    Stribeck's 4.08 for line contact (published-values.md) within 1 %: with a roller on
    the load line (B1's roller 0 at 180 deg) the discrete sum for Z = 17 gives 4.080 at
    Stribeck's exponent 1.1 and 4.093 at the model's 1/k2 = 1.12 (the continuous integral
    4.077 and 4.090), and the model's loads lie within 1 % of the discrete shares."""
    cfg = variant(**{"geometry.diametral_clearance": "0 um", "operating.gravity": "0 m/s^2"})
    ds = statics(cfg, radial_load=5000.0, axial_load=0.0, speed=0.0)
    q = ds.inner_race_load.values
    laws = _laws(cfg)
    k2 = 0.5 * (laws["inner"].k2 + laws["outer"].k2)
    expected = 5000.0 * _stribeck_shares(ds.roller_azimuth.values, 1.0 / k2)
    assert np.max(np.abs(q - expected)) < 0.01 * q.max()
    ratio = 17 * q.max() / 5000.0
    assert ratio == pytest.approx(4.08, rel=0.01)  # measured 4.095
    assert float(ds.load_zone_angle) == pytest.approx(90.0)


def _sjovall_jr(epsilon: float, n: float) -> float:
    """Sjövall's radial integral J_r(eps) = 1/(2 pi) int_{-psi_l}^{psi_l}
    [1 - (1 - cos psi)/(2 eps)]^n cos psi dpsi, cos psi_l = 1 - 2 eps (Harris & Kotzalas,
    Rolling Bearing Analysis, 5th ed., eq. 7.40; tabulated there for line contact, n = 1.1),
    by the trapezoidal rule on 20 001 points (the integrand is smooth and vanishes at the
    limits; error below 1e-7)."""
    limit = math.acos(1.0 - 2.0 * epsilon)
    psi = np.linspace(-limit, limit, 20_001)
    integrand = np.clip(1.0 - (1.0 - np.cos(psi)) / (2.0 * epsilon), 0.0, None) ** n * np.cos(psi)
    value = float(np.trapezoid(integrand, psi))
    return value / (2.0 * math.pi)


def test_clearance_follows_the_per_roller_solution_and_sjovall():
    """B1 with its 10 um clearance, no gravity, at rest, 5 kN radially: every roller's load
    equals the per-roller solution of Harris & Kotzalas sect. 7.2 with the same contact law
    (inner and outer eq. 11 in series, each roller squeezed by delta_r cos psi less the
    clearance; tests/test_dynamics.py) within 1 % of the heaviest, as the zero-clearance
    case does. The load zone's extent eps = (1 - P_d/(2 delta_r))/2 gives Sjövall's
    F_r = Z Q_max J_r(eps): with Z = 17 the discrete sum differs from the integral by its
    discreteness, 3 % at eps = 0.5 (3.96 against Stribeck's 4.08, the test above), so 5 %
    here."""
    from test_dynamics import quasi_static_loads

    cfg = variant(**{"operating.gravity": "0 m/s^2", "operating.axial_load": "0 N"})
    ds = statics(cfg, radial_load=5000.0, axial_load=0.0, speed=0.0)
    q = ds.inner_race_load.values
    expected, delta_r = quasi_static_loads(cfg)
    assert np.max(np.abs(q - expected)) < 0.01 * q.max(), (q, expected)
    assert float(-ds.ring_displacement[1]) == pytest.approx(delta_r, rel=0.01)
    clearance = cfg.geometry.diametral_clearance
    epsilon = 0.5 * (1.0 - clearance / (2.0 * delta_r))
    assert 0.3 < epsilon < 0.5  # a clearance that narrows the load zone
    # the quadrature against Harris & Kotzalas' table 7.1 (line contact, eps = 0.5)
    assert _sjovall_jr(0.5, 1.1) == pytest.approx(0.2453, abs=1e-4)
    laws = _laws(cfg)
    n = 1.0 / (0.5 * (laws["inner"].k2 + laws["outer"].k2))
    assert 5000.0 / (17 * q.max()) == pytest.approx(_sjovall_jr(epsilon, n), rel=0.05)


def test_radial_stiffness_of_zero_clearance_is_n_fr_over_delta():
    """Closed form for zero clearance: with Q_j = K (delta_r cos psi_j)^n every roller's load
    scales as delta_r^n, so F_r = sum Q_j cos psi_j does too and k_yy = dF_r/d delta_r =
    n F_r / delta_r (Harris & Kotzalas sect. 7.2); n = 1/k2 of eq. 11 (inner and outer k2
    differ by about 1 %, hence 2 %)."""
    cfg = variant(**{"geometry.diametral_clearance": "0 um", "operating.gravity": "0 m/s^2"})
    ds = statics(cfg, radial_load=5000.0, axial_load=0.0, speed=0.0)
    laws = _laws(cfg)
    n = 1.0 / (0.5 * (laws["inner"].k2 + laws["outer"].k2))
    delta_r = float(-ds.ring_displacement[1])
    assert float(ds.stiffness.values[1, 1]) == pytest.approx(n * 5000.0 / delta_r, rel=0.02)


def _laws(cfg):
    from rollerdyn.model import Model

    return Model(cfg).line_contacts


def test_radial_stiffness_equals_differences_of_equilibria(b1):
    """k_yy of the condensed Jacobian against (F_r2 - F_r1) / (y2 - y1) of two equilibria
    10 N apart (B1 at 5 kN, at rest): within 1 % (the law is smooth there; the difference
    quotient's own error is 10 N / 5 kN times the curvature, about 0.1 %)."""
    a = statics(b1, radial_load=5000.0, axial_load=0.0, speed=0.0)
    b = statics(b1, radial_load=5010.0, axial_load=0.0, speed=0.0)
    dy = float(b.ring_displacement[1] - a.ring_displacement[1])
    k_yy = float(a.stiffness.values[1, 1])
    assert k_yy == pytest.approx(-10.0 / dy, rel=0.01)
    assert k_yy > 0


def test_centrifugal_force_loads_the_outer_race(b1):
    """At 3000 rpm an unloaded roller near the top presses the outer race with its
    centrifugal force m omega_c^2 r less its weight (omega_c = Omega (1 - D/d_m)/2)."""
    omega = 3000 * 2 * math.pi / 60
    ds = statics(b1, radial_load=5000.0, axial_load=0.0, speed=omega)
    g = b1.geometry
    d, dm = g.roller_diameter, g.pitch_diameter
    omega_c = 0.5 * omega * (1 - d / dm)
    azimuth = np.radians(ds.roller_azimuth.values)
    top = int(np.argmax(np.cos(azimuth)))  # the roller nearest +y, opposite the load
    mass = b1.roller_mass  # with its edge tori (2 % lighter than the sharp cylinder)
    radius = dm / 2 + float(ds.roller_radial_offset[top])
    # its weight's outward component is -g cos(azimuth)
    expected = mass * (omega_c**2 * radius - 9.81 * np.cos(azimuth[top]))
    assert float(ds.inner_race_load[top]) == 0.0
    # The roller's radial balance holds to the equilibrium's residual (measured 3.4e-10
    # of the force); 1e-6 leaves room for the solver's tolerance, and the sharp
    # cylinder's mass (1.8 % off) would fail it.
    assert float(ds.outer_race_load[top]) == pytest.approx(expected, rel=1e-6)


def test_life_follows_the_slice_loads(b1):
    """The dataset's ratings are B1's by hand (mm, N; Z = 17, D_we = 4.495 mm, L_we = 4 mm,
    the roller's length less its two 0.5 mm edge radii, D_pw = 24.5 mm): ISO 76's
    C_0r = 44 (1 - D_we/D_pw) Z L_we D_we = 10 981.6 N and ISO 281's
    C_r = 1.1 f_c L_we^(7/9) Z^(3/4) D_we^(29/27) = 12 077.9 N with f_c = 88.8 (Table 7 at
    gamma = 0.1835, between its rows 0.18 and 0.19, both 88.8). Its L_10r is ISO/TS 16281
    of its own slice loads, and ISO 281's L_10 is (C_r / P)^(10/3) with P the radial load
    the bearing carries: F_r and the 1 kg ring's weight, both along -y, 5009.81 N."""
    ds = statics(b1, radial_load=5000.0, axial_load=0.0)
    assert float(ds.static_load_rating) == pytest.approx(10_981.6, abs=0.1)
    assert float(ds.dynamic_load_rating) == pytest.approx(12_077.9, abs=0.1)
    g = b1.geometry
    l10r = life.reference_rating_life(
        ds.inner_slice_load.values,
        ds.outer_slice_load.values,
        float(ds.dynamic_load_rating),
        g.roller_diameter,
        g.pitch_diameter,
    )
    assert float(ds.l10r) == pytest.approx(l10r, rel=1e-12)
    assert float(ds.carried_radial_load) == pytest.approx(5000.0 + 1.0 * 9.81, rel=1e-12)
    assert float(ds.l10) == pytest.approx((float(ds.dynamic_load_rating) / 5009.81) ** (10 / 3))


def test_the_rings_weight_is_part_of_the_load_the_lives_take():
    """P of L_10 and s_0 is the load the bearing carries, as L_10r's slice loads carry it:
    with gravity across the load (along z) F_r and m g add as a right angle's sides; without
    radial load the weight alone is P (a 22 kg ring and shaft under 1 N gave L_10 = 1.5e16
    with P = F_r against L_10r = 6.2e8; found by a review, 2026-12-02); without gravity P
    is F_r."""
    gravity = ["0 m/s^2", "0 m/s^2", "-9.81 m/s^2"]
    across = variant(**{"operating.gravity": gravity, "inner_ring.mass": "30 kg"})
    ds = statics(across, radial_load=400.0, axial_load=0.0)
    assert float(ds.carried_radial_load) == pytest.approx(math.hypot(400.0, 30 * 9.81), rel=1e-12)
    c_r, c_0r = float(ds.dynamic_load_rating), float(ds.static_load_rating)
    assert float(ds.l10) == pytest.approx((c_r / math.hypot(400.0, 294.3)) ** (10 / 3))
    assert float(ds.s0) == pytest.approx(c_0r / math.hypot(400.0, 294.3), rel=1e-12)
    alone = statics(variant(**{"inner_ring.mass": "30 kg"}), radial_load=0.0, axial_load=0.0)
    assert float(alone.carried_radial_load) == pytest.approx(294.3, rel=1e-12)
    assert math.isfinite(float(alone.l10)) and math.isfinite(float(alone.s0))
    weightless = variant(**{"operating.gravity": "0 m/s^2"})
    assert float(statics(weightless).carried_radial_load) == pytest.approx(5000.0, rel=1e-12)


def test_static_safety_by_iso_76_and_by_stress_agree_at_the_static_rating(b1):
    """ISO 76's C_0r is the radial load that presses the heaviest roller of a bearing
    against its raceway at 4 000 MPa, from a closed-form load distribution; the slice
    model finds B1's own (its clearance, crowning and slices). At F_r = C_0r (10.98 kN)
    the model's largest race pressure gives a static safety by stress of 1.04: the two
    agree within 10 % (the model's pressures include the crowned slices' and the
    clearance's load zone, which ISO 76's factors approximate). The dataset's s_0 is
    C_0r / P, P the load carried (F_r and the ring's weight, 9.81 N), and the flanges'
    safety by stress is (4 GPa / p_0)^3 of its largest flange pressure."""
    c0 = float(statics(b1).static_load_rating)
    ds = statics(b1, radial_load=c0 - 9.81)
    assert float(ds.s0) == pytest.approx(1.0, rel=1e-12)
    assert float(ds.s0_races) == pytest.approx(1.0, abs=0.1)
    assert float(ds.s0_races) == pytest.approx((4e9 / float(ds.max_pressure)) ** 2, rel=1e-12)
    flange = float(np.nanmax(ds.flange_pressure.values))
    assert float(ds.s0_flanges) == pytest.approx((4e9 / flange) ** 3, rel=1e-12)
    # and both fall with the load
    lighter = statics(b1, radial_load=0.5 * c0 - 9.81)
    assert float(lighter.s0) == pytest.approx(2.0, rel=1e-12)
    assert float(lighter.s0_races) > float(ds.s0_races)


def test_sweep_is_monotonic_and_keeps_every_case(b1):
    """A radial-load sweep: the heaviest roller grows and the life falls with the load."""
    ds = statics_sweep(
        b1, {"operating.radial_load": [1000.0, 3000.0, 6000.0], "operating.axial_load": [0.0]}
    )
    assert ds.attrs["failed_cases"] == 0
    assert np.all(np.diff(ds.max_roller_load.values) > 0)
    assert np.all(np.diff(ds.l10r.values) < 0)
    # the swept values carry their SI unit, as every other variable does
    assert ds.radial_load.attrs == {"units": "N", "long_name": "operating.radial_load"}


def test_an_axial_load_sweep_in_large_steps_keeps_every_case(b1):
    """The sweep starts each case from its neighbour's solution; from B1's 0 N solution at
    500 rpm the 1000 N case found none (its continuation starts at a small share of the new
    load, far from the neighbour's state), and `rollerdyn statics --set
    operating.axial_load=0,1000,2000` printed NaN for 1000 and 2000 N. The solver now drops
    such a start for its cold one: every case has its equilibrium, the same as each case
    solved alone (the ring within the solver's tolerance, 1 nm)."""
    ds = statics_sweep(b1, {"operating.axial_load": [0.0, 1000.0, 2000.0]})
    assert ds.attrs["failed_cases"] == 0, list(ds.error.values)
    for k, fa in enumerate((0.0, 1000.0, 2000.0)):
        alone = statics(b1, axial_load=fa)
        got = ds.ring_displacement.isel(case=k).values[:3]
        np.testing.assert_allclose(got, alone.ring_displacement.values[:3], rtol=0, atol=1e-9)


def test_the_distributed_law_is_the_statics_law_too(b1):
    """With surfaces.flange_law = "distributed" the statics take the overlap's load, as the
    run does (docs/statics.md): B1 at 2.5 kN axially, where the point law finds no
    equilibrium, has one whose inner ring is held by the flanges at a peak pressure below
    ISO 76's 4 GPa; at 3 kN the rims would be pressed past it (4.4 GPa) and the load is
    refused with that reason."""
    from b1 import variant

    distributed = variant(**{"surfaces.flange_law": "distributed"})
    with pytest.raises(StaticsError, match=r"reached \d+ % of the load"):
        statics(b1, axial_load=2500.0)
    carried = statics(distributed, axial_load=2500.0)
    assert 3e9 < float(carried.flange_pressure.max()) < 4e9
    with pytest.raises(StaticsError, match=r"flanges cannot carry it.*above the 4 GPa"):
        statics(distributed, axial_load=3000.0)


def test_bad_cases_are_refused_with_a_message(b1):
    with pytest.raises(StaticsError, match="must be finite"):
        statics(b1, radial_load=math.nan)
    with pytest.raises(StaticsError, match="the grid holds the load case only"):
        parse_range("geometry.roller_count", "10:20:3")
    with pytest.raises(StaticsError, match="count"):
        parse_range("operating.radial_load", "0:10:x")
    # one value from two different ends ran the first alone (the sweep refuses it too)
    with pytest.raises(StaticsError, match=r"2 \.\.\. 100000 \(or 1 with START = STOP\)"):
        parse_range("operating.radial_load", "1000 N:5000 N:1")
    assert parse_range("operating.radial_load", "1000 N:1000 N:1") == [1000.0]
    # 1e8 cases filled 7 GB of memory before anything was printed
    many = {"operating.radial_load": [1e3] * 10_000, "operating.axial_load": [0.0] * 10_000}
    with pytest.raises(StaticsError, match=r"= 100000000 cases, more than 100000"):
        statics_sweep(b1, many)
    for grid in ("abc", [1, 2], None):
        with pytest.raises(StaticsError, match="must be a mapping of paths"):
            statics_sweep(b1, grid)
    with pytest.raises(StaticsError, match="stiffness = 'no'"):
        statics_sweep(b1, {"operating.radial_load": [1e3]}, stiffness="no")
    assert parse_range("operating.inner_ring_speed", "0 rpm:3000 rpm:3")[-1] == pytest.approx(
        100 * math.pi
    )
    # a bare speed was rad/s: 1000 gave 9549 rpm and its torque without a word (a review);
    # the maps read a bare --speed as rpm. Speeds and angles need their unit but for 0.
    for path, text in (
        ("operating.inner_ring_speed", "1000"),
        ("operating.carrier_speed", "0,1000"),
        ("inner_ring.misalignment", "0.001"),
        ("roller_set_phase", "0:0.3:4"),
    ):
        with pytest.raises(StaticsError, match=r"has no unit, and a bare \w+ \w* ?is ambiguous"):
            parse_range(path, text)
    assert parse_range("operating.outer_ring_speed", "0:3000 rpm:3")[-1] == pytest.approx(
        100 * math.pi
    )
    assert parse_range("operating.radial_load", "0:10000:3") == [0.0, 5000.0, 10000.0]
    with pytest.raises(StaticsError, match="a value is given twice"):
        parse_range("operating.radial_load", "1000,1 kN")
    with pytest.raises(StaticsError, match="START = STOP with 3 values"):
        parse_range("operating.radial_load", "5000 N:5000 N:3")
    from typer.testing import CliRunner

    from rollerdyn.cli import app

    twice = ["statics", str(B1), "--set", "geometry.diametral_clearance=10 um,10 um"]
    res = CliRunner().invoke(app, twice)
    assert res.exit_code == 2 and "a value is given twice" in res.output, res.output


_RADIAL_ONLY = {"operating.radial_load": [5000.0], "operating.axial_load": [0.0]}


def test_a_design_sweep_solves_each_design_as_alone_and_meets_stribeck_at_zero_clearance():
    """A design sweep (``statics_sweep(design=...)``) over the diametral clearance, without
    gravity and at rest: each case is its configuration solved alone (the same model, ratings
    and cold start: the ring to 1 nm, the ratings exactly); at 0 um Z Q_max / F_r is
    Stribeck's 4.08 within 1 % (published-values.md, as test_zero_clearance_follows_stribeck);
    with clearance the load zone narrows, so the heaviest roller grows and L_10r falls
    (Harris & Kotzalas, Rolling Bearing Analysis, sect. 7.2)."""
    clearances = ["0 um", "10 um", "20 um"]
    design = {"geometry.diametral_clearance": clearances, "operating.gravity": ["0 m/s^2"]}
    grid = {**_RADIAL_ONLY, "operating.inner_ring_speed": [0.0]}
    ds = statics_sweep(B1, grid, design=design)
    assert ds.attrs["failed_cases"] == 0, list(ds.error.values)
    swept = "diametral_clearance,gravity,radial_load,axial_load,inner_ring_speed"
    assert ds.attrs["swept"] == swept
    np.testing.assert_array_equal(ds.diametral_clearance.values, [0.0, 1e-5, 2e-5])
    assert ds.diametral_clearance.attrs == {
        "long_name": "geometry.diametral_clearance",
        "units": "m",
    }
    for k, clearance in enumerate(clearances):
        cfg = variant(**{"geometry.diametral_clearance": clearance, "operating.gravity": "0 m/s^2"})
        alone = statics(cfg, radial_load=5000.0, axial_load=0.0, speed=0.0)
        case = ds.isel(case=k)
        got = case.ring_displacement.values
        np.testing.assert_allclose(got, alone.ring_displacement.values, rtol=0, atol=1e-9)
        assert float(case.dynamic_load_rating) == float(alone.dynamic_load_rating)
        assert float(case.l10r) == pytest.approx(float(alone.l10r), rel=1e-6)
    q_max = ds.max_roller_load.values
    assert 17 * q_max[0] / 5000.0 == pytest.approx(4.08, rel=0.01)
    assert np.all(np.diff(q_max) > 0) and np.all(np.diff(ds.l10r.values) < 0)


def test_a_design_sweep_varies_text_values_and_the_oil_temperature(b1, tmp_path):
    """Text values (``surfaces.flange_law``) and the oil temperature: the film ratio falls
    with the temperature at an unchanged load distribution (the race films do not enter the
    normal forces), so L_10r stays and L_nmr falls with kappa (ISO 281 a_ISO); the text
    coordinate is written to netCDF and read back."""
    design = {
        "surfaces.flange_law": ["point", "distributed"],
        "operating.temperature": ["60 degC", "100 degC"],
    }
    ds = statics_sweep(B1, {"operating.axial_load": [0.0]}, design=design)
    assert list(ds.flange_law.values) == ["point", "point", "distributed", "distributed"]
    np.testing.assert_allclose(ds.temperature.values, [333.15, 373.15] * 2)
    assert ds.temperature.attrs["units"] == "K"
    for law in range(2):
        hot, cold = ds.isel(case=2 * law + 1), ds.isel(case=2 * law)
        assert float(hot.l10r) == pytest.approx(float(cold.l10r), rel=1e-9)
        assert float(hot.kappa) < float(cold.kappa) and float(hot.lnmr) < float(cold.lnmr)
        assert float(hot.min_specific_film_thickness) < float(cold.min_specific_film_thickness)
    path = tmp_path / "design.nc"
    ds.to_netcdf(path, engine="h5netcdf")
    import xarray as xr

    with xr.open_dataset(path, engine="h5netcdf") as back:
        assert list(back.flange_law.values) == list(ds.flange_law.values)


def test_a_design_sweep_refuses_what_it_cannot_vary_by_name(b1):
    with pytest.raises(StaticsError, match="geometry.roller_count: a statics sweep cannot vary"):
        statics_sweep(B1, _RADIAL_ONLY, design={"geometry.roller_count": [16, 18]})
    with pytest.raises(StaticsError, match="a load case's value; give it in the grid"):
        statics_sweep(B1, _RADIAL_ONLY, design={"operating.axial_load": ["0 N"]})
    bad = {"geometry.diametral_clearance": ["10 um", "-5 um"]}
    with pytest.raises(StaticsError) as err:
        statics_sweep(B1, _RADIAL_ONLY, design=bad)
    text = str(err.value)
    assert "1 of 2 grid points fail validation (nothing was solved)" in text
    assert '"-5 um" — must be >= 0 (--set geometry.diametral_clearance)' in text
    many = {"geometry.diametral_clearance": [f"{k} nm" for k in range(1001)]}
    with pytest.raises(StaticsError, match="1001 bearing designs, more than 1000"):
        statics_sweep(B1, _RADIAL_ONLY, design=many)


def test_cli_sweeps_the_bearing_itself(tmp_path):
    """``rollerdyn statics --set`` with a configuration path outside the load case: a design
    sweep with every case in the table (up to 20), the netCDF file and the figure, one line
    per value of the other swept values; its refusals exit with status 2, naming the path."""
    runner = CliRunner()
    out, png = tmp_path / "d.nc", tmp_path / "d.png"
    args = [
        "statics",
        str(B1),
        "--set",
        "geometry.diametral_clearance=0 um:20 um:3",
        "--set",
        "operating.radial_load=2000,5000",
        "--set",
        "operating.axial_load=0",
    ]
    result = runner.invoke(app, [*args, "-o", str(out), "--plot", str(png)])
    assert result.exit_code == 0, result.output
    assert "quasi-static sweep: 6 cases" in result.output and "L_nmr" in result.output
    assert out.is_file() and png.stat().st_size > 10_000
    refused = runner.invoke(app, ["statics", str(B1), "--set", "geometry.roller_count=16,18"])
    assert refused.exit_code == 2 and "geometry.roller_count" in refused.output
    negative = runner.invoke(
        app, ["statics", str(B1), "--set", "geometry.diametral_clearance=-5 um,5 um"]
    )
    assert negative.exit_code == 2 and "must be >= 0" in negative.output
    single = runner.invoke(app, ["statics", str(B1), "--set", "geometry.diametral_clearance=0 um"])
    assert single.exit_code == 0 and "quasi-static equilibrium" in single.output
    assert "mm above the raceway (TO-CO)" in single.output
    assert "friction of steady rolling" in single.output
    assert "roller slip (1 - spin / spin of rolling)" in single.output
    assert "loaded (>= 10 % of the heaviest) -" in single.output


def _roller_axis_radius(cfg, ds, j: int, k: int) -> float:
    """Roller j's axis's distance from the axis of flange k's ring in the equilibrium ``ds``:
    from the roller's azimuth and radial offset, around the displaced inner ring's axis for
    the inner flanges (k < 2), the fixed outer ring's for the outer ones."""
    psi = math.radians(float(ds.roller_azimuth[j]))
    centre = (cfg.geometry.pitch_diameter / 2 + float(ds.roller_radial_offset[j])) * np.array(
        [math.cos(psi), math.sin(psi)]
    )
    ring = ds.ring_displacement.values[1:3] if k < 2 else np.zeros(2)
    return float(np.linalg.norm(centre - ring))


def _edge_torus_heights(cfg, ds, j: int, k: int) -> tuple[float, float]:
    """The band of heights above the raceway at which roller j's edge torus touches flange k
    (TO-CO) by the geometry alone: the point of the torus tube (minor radius r_t) whose
    normal is the cone's, tilted by the opening angle gamma from the axis, lies
    r_t (1 - sin phi) above the roller's surface line, phi = gamma -+ the roller's tilt
    theta (whichever way it leans), less the roller's approach to that ring's raceway (from
    its centre's radial offset, its azimuth and the ring's displacement)."""
    g = cfg.geometry
    radius = _roller_axis_radius(cfg, ds, j, k)
    if k < 2:
        approach = g.inner_raceway_diameter / 2 + g.roller_diameter / 2 - radius
    else:
        approach = radius + g.roller_diameter / 2 - g.outer_raceway_diameter / 2
    gamma, theta, r_t = g.flange.opening_angle, abs(float(ds.roller_tilt[j])), g.roller.edge_radius
    low = r_t * (1 - math.sin(gamma + theta)) - approach
    high = r_t * (1 - math.sin(max(gamma - theta, 0.0))) - approach
    return low, high


def test_the_flange_contact_height_is_the_edge_torus_point_facing_the_flange(b1):
    """Where the roller ends press the flanges (``flange_contact_height``): at B1's loads
    every edge-torus contact (TO-CO) carrying a fifth of the largest force lies at the
    height the geometry gives (:func:`_edge_torus_heights`) within 2 um (measured 0.5 um at
    300 N, 1.5 um at 1 kN; the rest is the roller's skew and the contact's own
    penetration, which the band leaves out), on the inner and the outer ring's flanges;
    the largest force's height and pairing are its own. With the flange face at right
    angles to the axis (opening angle 0) the tilted end lies across the rim instead, above
    the cone (the rim torus starts at 1.1 - 0.3 = 0.8 mm)."""
    for axial in (300.0, 1000.0):
        ds = statics(b1, axial_load=axial)
        force, height = ds.flange_force.values, ds.flange_contact_height.values
        checked = set()
        for j, k in zip(*np.nonzero(force >= 0.2 * force.max()), strict=True):
            assert ds.flange_pairing.values[j, k] == "TO-CO"
            low, high = _edge_torus_heights(b1, ds, j, k)
            assert low - 2e-6 <= height[j, k] <= high + 2e-6, (axial, j, k)
            checked.add(k < 2)
        assert checked == {True, False}  # both rings' flanges
        j, k = np.unravel_index(np.argmax(force), force.shape)
        assert float(ds.max_flange_force_height) == height[j, k]
        assert ds.max_flange_force_pairing.item() == "TO-CO"
    assert np.isnan(statics(b1, axial_load=0.0).max_flange_force_height)
    square = variant(**{"geometry.flange.opening_angle": "0 deg"})
    on_rim = statics(square, axial_load=1000.0)
    assert on_rim.max_flange_force_pairing.item() in ("SP-TO(rim)", "TO-TO(rim)")
    assert 0.8e-3 <= float(on_rim.max_flange_force_height) <= 1.1e-3


def _rib_sliding_speed(cfg, ds, j: int, k: int) -> float:
    """The sliding speed of roller j's end on flange k at its contact height (Harris &
    Kotzalas, Rolling Bearing Analysis, the roller end / rib sliding): in the frame of the
    roller set (omega_c = Omega (1 - r / R_pitch) / 2), the ring's point at radius rho from
    the bearing axis moves at (Omega - omega_c) rho (inner ring) or -omega_c rho (the fixed
    outer ring), the roller's point at distance d from its axis at omega_s d, omega_s =
    (Omega - omega_c) R_i / r in rolling without slip, times 1 - the roller's slip
    (``roller_slip``); the roller's axis lies where the equilibrium put it (its approach to
    the raceway included). A skewed roller (``roller_skew``) meets the flange a distance
    Delta off its meridian plane (``flange_contact_offset``), where its end's surface also
    moves across the rib, radially, at omega_s Delta: the two parts add as a right angle's
    sides."""
    g = cfg.geometry
    r, r_i, r_o = g.roller_diameter / 2, g.inner_raceway_diameter / 2, g.outer_raceway_diameter / 2
    omega = float(ds.speed_applied)
    omega_c = 0.5 * omega * (1 - r / (g.pitch_diameter / 2))
    # each roller spins where its moments balance: roller_slip of rolling without slip
    omega_s = (omega - omega_c) * r_i / r * (1.0 - float(ds.roller_slip[j]))
    height = float(ds.flange_contact_height[j, k])
    axis = _roller_axis_radius(cfg, ds, j, k)
    across = omega_s * float(ds.flange_contact_offset[j, k])
    if k < 2:
        rho = r_i + height
        return math.hypot((omega - omega_c) * rho - omega_s * (axis - rho), across)
    rho = r_o - height
    return math.hypot(omega_s * (rho - axis) - omega_c * rho, across)


def test_slow_sliding_at_the_flanges_is_reported_and_said_to_lower_the_friction():
    """``flange_sliding_speed`` is the closed-form rib sliding speed of the equilibrium
    (:func:`_rib_sliding_speed`) within 5 % at every pressed flange (measured: within 1 %
    at 3 rpm, up to 3.6 % at 500 rpm, +3 % at the inner flange and -1 % at the outer one of
    the same roller, where the rollers skew; the closed form adds the skew's part as a
    right angle's side and takes the force's point for the ellipse's). Below the boundary
    friction's smoothing speed v_s = 1 mm/s the model's friction falls towards zero (a
    regularisation, not the contact's Coulomb friction): B1 at 3 rpm slides at 0.2-0.4
    mm/s and takes about a third of its torque at 500 rpm, and the dataset says so in
    ``friction_caveat``; at 30 rpm and up (every contact above v_s) the torque is within
    0.1 % of 500 rpm's and there is no caveat (a review found the torque falling towards
    zero at low speed without a word, 2026-12-02)."""
    cfg = load_b1()
    rpm = 2 * math.pi / 60
    fast, plateau, slow = (statics(cfg, speed=n * rpm) for n in (500.0, 30.0, 3.0))
    for ds in (fast, slow):
        force = ds.flange_force.values
        for j, k in zip(*np.nonzero(force > 0.01 * force.max()), strict=True):
            expected = _rib_sliding_speed(cfg, ds, j, k)
            assert float(ds.flange_sliding_speed[j, k]) == pytest.approx(expected, rel=0.05)
    assert str(fast.friction_caveat.values) == str(plateau.friction_caveat.values) == ""
    assert float(plateau.friction_torque) == pytest.approx(float(fast.friction_torque), rel=1e-3)
    caveat = str(slow.friction_caveat.values)
    assert "below surfaces.boundary_friction.smoothing_speed (1 mm/s)" in caveat
    assert "underestimated" in caveat
    assert float(slow.friction_torque) < 0.5 * float(fast.friction_torque)


def test_the_load_zone_counts_the_rollers_pressed_between_the_races(b1):
    """``loaded_rollers``: the rollers whose lesser race load is at least 1 % of the
    heaviest, counted by hand from the race loads; B1 at 5 kN has 9 (the load zone's
    half-angle 76 deg spans 2 x 76 / (360 / 17) + 1 = 8.2 pitches), not the 13 that rest on
    the inner ring, the four above it by their weight (mN)."""
    ds = statics(b1)
    inner, outer = ds.inner_race_load.values, ds.outer_race_load.values
    by_hand = int((np.minimum(inner, outer) >= 0.01 * max(inner.max(), outer.max())).sum())
    assert int(ds.loaded_rollers) == by_hand == 9
    assert int((inner > 0.0).sum()) > 9  # those resting on the ring by their weight


def test_the_friction_of_steady_rolling_at_the_flanges_is_boundary_friction_times_sliding():
    """``friction_power`` at the flanges: with a roughness of 10 um the flange contacts are
    wholly in boundary friction (Lambda about 0.003, Zhou-Hoeprich's asperity share
    exp(-1.9 Lambda^0.99) = 0.995) and slide far beyond the friction's micro-slip ramp, so
    each takes mu_B0 F_n v_s: the sum over the equilibrium's flange forces and the closed
    form rib sliding speeds (:func:`_rib_sliding_speed`) within 2 % (the asperity share
    0.5 %, the ramp 0.1 %, the point's place off the roller's meridian the rest; measured
    0.27 %). The torque is the power over the speed; at rest every part is 0 and the torque
    NaN."""
    cfg = variant(**{"surfaces.flange.roughness": "10 um"})
    ds = statics(cfg)
    force = ds.flange_force.values
    expected = sum(
        0.1 * force[j, k] * _rib_sliding_speed(cfg, ds, j, k)
        for j, k in zip(*np.nonzero(force > 0.0), strict=True)
    )
    flanges = float(ds.friction_power.sel(friction_part="flanges"))
    assert flanges == pytest.approx(expected, rel=0.02)
    speed = float(ds.speed_applied)
    assert float(ds.friction_torque) == pytest.approx(float(ds.friction_power.sum()) / speed)
    at_rest = statics(cfg, speed=0.0)
    assert np.all(at_rest.friction_power.values == 0.0)
    assert np.isnan(at_rest.friction_torque)
    assert np.all(at_rest.roller_slip.values == 0.0)
    assert ds.roller_slip.attrs["units"] == "1"


def test_a_sweep_stopped_by_ctrl_c_keeps_the_cases_it_solved(b1, tmp_path, capfd):
    """Ctrl-C in a sweep (here raised by its progress callback after the first chunk of 50
    cases) raises ``StaticsInterrupted``, a KeyboardInterrupt carrying the cases solved
    until then, the same as in the whole sweep; in a design sweep too."""
    from rollerdyn.statics import StaticsInterrupted

    loads = list(np.linspace(1000.0, 8000.0, 120))
    grid = {"operating.radial_load": loads, "operating.axial_load": [0.0]}

    def stop(done: int, total: int) -> None:
        raise KeyboardInterrupt

    with pytest.raises(StaticsInterrupted, match="after 50 of 120 cases") as err:
        statics_sweep(b1, grid, progress=stop)
    partial = err.value.dataset
    assert isinstance(err.value, KeyboardInterrupt)
    assert partial.sizes["case"] == 50 and partial.attrs["interrupted"] == "50 of 120 cases solved"
    whole = statics_sweep(b1, grid)
    np.testing.assert_array_equal(partial.max_roller_load, whole.max_roller_load[:50])
    design = {"geometry.diametral_clearance": ["0 um", "10 um"]}
    with pytest.raises(StaticsInterrupted, match="after 50 of 240 cases"):
        statics_sweep(B1, grid, design=design, progress=stop)
    # the command without -o lost them (one line only, a review): now it shows their table
    import typer

    from rollerdyn.cli.statics import _keep_interrupted

    capfd.readouterr()
    with pytest.raises(typer.Exit) as status:
        _keep_interrupted(err.value, None, 130)
    said = " ".join("".join(capfd.readouterr()).split())
    assert status.value.exit_code == 130
    assert "(5 of the 50 cases shown; -o writes them all)" in said
    assert said.endswith("the cases solved are above (-o FILE keeps them)"), said


def test_sigterm_stops_a_sweep_and_keeps_the_cases_it_solved(tmp_path):
    # SIGTERM (`kill`, `timeout`, a batch system) ended `rollerdyn statics` at once with no
    # line and lost every case solved; now it stops as Ctrl-C does: the cases solved
    # written to -o, one line, exit status 143
    import signal
    import subprocess
    import sys
    import time
    from pathlib import Path

    import xarray as xr

    command = Path(sys.executable).parent / "rollerdyn"
    out = tmp_path / "s.nc"
    args = [str(command), "statics", str(B1), "--set", "operating.radial_load=1000:10000:20000"]
    proc = subprocess.Popen(
        [*args, "-o", str(out)], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True
    )
    time.sleep(8.0)  # the start (about 2 s) and some chunks of 50 cases (about 15 ms each)
    proc.send_signal(signal.SIGTERM)
    text, _ = proc.communicate(timeout=120)
    assert proc.returncode == 143, text
    assert "Traceback" not in text, text
    last = text.strip().splitlines()[-1]
    assert "interrupted after" in last and f"wrote those to {out}" in last, text
    with xr.open_dataset(out) as ds:
        assert 0 < ds.sizes["case"] < 20000 and "interrupted" in ds.attrs


def test_a_vertical_shafts_flanges_carry_the_weights_of_ring_and_rollers():
    """A type NJ arrangement (B1 without the inner ring's -x flange) on a vertical shaft,
    gravity along -x, no axial load: the inner ring's +x flange carries the ring's weight
    (1 kg) and the outer ring's -x flange that and the 17 rollers' weight (force balance
    of the ring and of the roller set; the statics have no friction). Measured 9.81002 and
    9.91197 N against 9.81 and 9.91198 N; allowed 1e-4 relative: a flange's normal force
    exceeds its axial part by 1/cos of the opening angle (0.11 deg: 1.8e-6), and the
    equilibrium is solved to 1e-7 of the load. The missing flange carries nothing; along
    -x this bearing carries an axial load, along +x it refuses one by name."""
    g = 9.81
    cfg = variant(
        **{
            "geometry.flanges": ["inner+x", "outer-x", "outer+x"],
            "operating.gravity": [f"-{g} m/s^2", "0 m/s^2", "0 m/s^2"],
            "operating.axial_load": "0 N",
        }
    )
    carried = statics(cfg).flange_force.sum("roller")
    ring, rollers = cfg.inner_ring.mass * g, cfg.geometry.roller_count * cfg.roller_mass * g
    assert carried.sel(flange="inner+x").item() == pytest.approx(ring, rel=1e-4)
    assert carried.sel(flange="outer-x").item() == pytest.approx(ring + rollers, rel=1e-4)
    assert carried.sel(flange=["inner-x", "outer+x"]).values.tolist() == [0.0, 0.0]
    assert statics(cfg, axial_load=-500.0).max_flange_force.item() > 30.0
    with pytest.raises(StaticsError, match='geometry.flanges has no "inner-x"'):
        statics(cfg, axial_load=500.0)


def test_a_value_may_be_quoted_as_in_the_configuration_file():
    """`rollerdyn run --set` takes values as the TOML file writes them ("30 kN", quoted);
    `rollerdyn statics --set` takes the same text, quoted or not, whole or value by value."""
    expected = [0.0, 1000.0, 2000.0]
    for text in ('"0 N":"2 kN":3', '"0 N:2 kN:3"', "'0 N':'2 kN':'3'", "0 N:2 kN:3"):
        assert parse_range("operating.axial_load", text) == pytest.approx(expected), text
    assert parse_range("operating.axial_load", '"30 kN"') == [pytest.approx(30e3)]
    assert parse_range("operating.axial_load", '"1 kN", "2 kN"') == pytest.approx([1e3, 2e3])
    with pytest.raises(StaticsError, match="empty value"):
        parse_range("operating.axial_load", '""')


def test_loads_the_bearing_cannot_carry_are_refused_with_the_level_reached(b1):
    """Issue 18's bad input: a load past what B1 carries gives one message with the load
    level reached and the residual (no equilibrium: 3 kN axially, past the flat position
    of the roller ends), or the flange pressure against ISO 76's 4 GPa limit (10 kN
    axially, where the elastic model finds rollers tipped into the flange rims at ~16 GPa);
    never a hang or NaN. B1 at 2 kN axially is still carried (flange p0 about 2 GPa)."""
    with pytest.raises(StaticsError, match=r"reached \d+ % of the load.*residual is"):
        statics(b1, axial_load=3000.0)
    with pytest.raises(StaticsError, match=r"flanges cannot carry it.*GPa, above the 4 GPa"):
        statics(b1, axial_load=10000.0)
    carried = statics(b1, axial_load=2000.0)
    assert float(carried.flange_pressure.max()) < 4e9
    assert np.isfinite(carried.ring_displacement.values).all()


def test_cli_prints_the_equilibrium_and_refuses_bad_options(tmp_path):
    runner = CliRunner()
    out = tmp_path / "s.nc"
    result = runner.invoke(
        app, ["statics", str(B1), "--set", "operating.axial_load=0", "-o", str(out)]
    )
    assert result.exit_code == 0, result.output
    assert "heaviest roller" in result.output and out.exists()
    bad = runner.invoke(app, ["statics", str(B1), "--set", "operating.axial_load=abc"])
    assert bad.exit_code == 2 and "operating.axial_load" in bad.output
    again = runner.invoke(app, ["statics", str(B1), "-o", str(out)])
    assert again.exit_code == 2 and "--overwrite" in again.output
    # the configuration's rules hold for --set values (B1's load limit is 83 272.8 N; a
    # misalignment within 1 deg); 1e300 N was solved and reported as a failed equilibrium
    for option, rule in (
        ("operating.radial_load=1e300 N", "the configuration's load limit"),
        ("operating.radial_load=0:90000:3", "the configuration's load limit"),
        ("inner_ring.misalignment=90 deg", "+-1 deg"),
        ("operating.inner_ring_speed=1e9 rpm", "pitch-circle speed"),
    ):
        refused = runner.invoke(app, ["statics", str(B1), "--set", option])
        assert refused.exit_code == 2, refused.output
        assert f"--set {option}" in refused.output and rule in refused.output
    # a sweep with a case the bearing cannot carry (no radial load, 1000 N axially) keeps
    # the others and writes everything, then exits with status 1 as a failed sweep does
    swept = tmp_path / "sweep.nc"
    sweep = ["statics", str(B1), "--set", "operating.radial_load=5000,0,3000", "-o", str(swept)]
    partly = runner.invoke(app, sweep)
    assert partly.exit_code == 1, partly.output
    assert "1 case without equilibrium" in partly.output and swept.is_file()


def test_the_traction_table_does_not_enter_the_equilibrium(b1):
    """The quasi-static equilibrium takes normal forces only, so ``statics`` builds its core
    model with the untabulated traction (at once, instead of the table's 1.3-1.5 s): the
    equilibria with the tabulated traction are the same bit for bit (B1 at its loads and
    500 rpm, and at twice the axial load and 3000 rpm). Only the friction power of steady
    rolling, the rollers' slip there and the roller train (through the free rollers'
    friction on their races) see the traction: the direct rule's differ from the table's by
    the table's error (below 1e-4 of the traction, docs/model.md; at most 3e-4 of
    a part measured)."""
    from rollerdyn import _core
    from rollerdyn.model import Model
    from rollerdyn.names import SEMI_ANALYTICAL
    from rollerdyn.simulation import model_parameters
    from rollerdyn.statics import StaticCase, _core_model

    params = model_parameters(b1, SEMI_ANALYTICAL)
    tabulated = _core.Model(params, Model(b1).traction_model(tabulated=True))
    cases = [
        StaticCase(5000.0, 1000.0, speed=500.0 * math.pi / 30.0, misalignment=0.0),
        StaticCase(5000.0, 2000.0, speed=3000.0 * math.pi / 30.0, misalignment=0.0),
    ]
    part = [c.core() for c in cases]
    fast = _core.statics(_core_model(b1), part, chain=True, stiffness=True)
    table = _core.statics(tabulated, part, chain=True, stiffness=True)
    assert all(isinstance(r, dict) for r in fast), fast
    # the friction power at 2000 N and 3000 rpm passes the table's error on through the
    # balance of the rollers' spins and skews, whose ends lie on their faces there
    # (measured: 1.8e-3 of the flanges' part; 1.6e-3 with the balances converged to 1e-9;
    # at B1's 1000 N and 500 rpm 4e-5)
    for exact, tab, rtol in zip(fast, table, (1e-3, 3e-3), strict=True):
        np.testing.assert_allclose(
            exact.pop("friction_power"), tab.pop("friction_power"), rtol=rtol
        )
        # the skews (and where the skewed ends meet the flanges) move with it: within
        # 2e-5 rad of skews up to 0.67 mrad (measured 1e-7 and 9e-6 rad, 3e-7 and 4e-6 m)
        np.testing.assert_allclose(exact.pop("roller_skew"), tab.pop("roller_skew"), atol=2e-5)
        np.testing.assert_allclose(
            exact.pop("flange_offsets"), tab.pop("flange_offsets"), atol=2e-5
        )
        # the slip where the moments balance moves with the table's error in the traction
        # (measured: 1.0e-6 at 500 rpm, 4.6e-5 at 3000 rpm, on the unloaded rollers, whose
        # films' and drag's moments change slowly with their spin)
        np.testing.assert_allclose(exact.pop("roller_slip"), tab.pop("roller_slip"), atol=1e-4)
        # and with the spins and skews, the ends' sliding on the flanges, as the friction
        # power (measured: 1.3e-4 at 500 rpm; 2.5e-3 at 3000 rpm and 2000 N, where the
        # ends lie on their faces)
        np.testing.assert_allclose(
            exact.pop("flange_sliding_speeds"), tab.pop("flange_sliding_speeds"), rtol=rtol
        )
        # the roller train takes the free rollers' friction on their races (measured: the
        # forces move by 1e-6 of themselves)
        np.testing.assert_allclose(exact.pop("pair_force"), tab.pop("pair_force"), rtol=1e-3)
    assert repr(fast) == repr(table)


@pytest.mark.parametrize("factor", [None, 0.001])
def test_logarithmic_profile_relieves_each_slice_by_its_drop(factor):
    """With Lundberg's logarithmic profile (ISO/TS 16281) a slice at s from the roller's
    centre stands k D ln[1 / (1 - (2 s / L_we)^2)] lower than the middle. Without axial
    load or misalignment B1's rollers do not tilt, so every slice of a roller meets the
    inner race with the same approach less its drop: each slice's deflection by the
    inverse of eq. 11 (delta = k1^k2 (Q / l)^k2), plus the drop, is the same along the
    roller (measured: within 5e-5 of it; 2e-4 here), and the relief shifts the load to the
    middle (with the straight roller every slice carries the same load)."""
    from rollerdyn.model import Model

    changes = {"geometry.roller.profile": "logarithmic", "operating.axial_load": "0 N"}
    if factor is not None:
        changes["geometry.roller.relief_factor"] = factor
    cfg = variant(**changes)
    g = cfg.geometry
    k = 0.00035 if factor is None else factor
    assert g.log_relief == pytest.approx(k * g.roller_diameter, rel=1e-15)
    length, n = g.roller.effective_length, g.roller.slices
    width = length / n
    s = -length / 2 + (np.arange(n) + 0.5) * width
    drop = k * g.roller_diameter * np.log(1.0 / (1.0 - (2.0 * s / length) ** 2))
    law = Model(cfg).line_contacts["inner"]
    ds = statics(cfg)
    # the dataset's slice positions are the core's stations: centred, one width apart
    assert ds.slice_position.values == pytest.approx(s, rel=1e-12)
    assert ds.slice_position.attrs["units"] == "m"
    loads = ds.inner_slice_load.values
    heaviest = loads[np.argmax(loads.sum(axis=1))]
    deflection = law.k1**law.k2 * (heaviest / width) ** law.k2
    approach = deflection + drop
    assert approach == pytest.approx(np.full(n, approach.mean()), rel=2e-4)
    assert heaviest[n // 2] > heaviest[0] > 0.0  # relieved ends, still in contact
    straight = statics(variant(**{"operating.axial_load": "0 N"})).inner_slice_load.values
    flat = straight[np.argmax(straight.sum(axis=1))]
    assert flat == pytest.approx(np.full(n, flat.mean()), rel=1e-6)


def test_a_sweeps_warm_start_never_decides_whether_a_case_has_an_equilibrium():
    """Each case of a sweep starts from its neighbour's equilibrium; where that search
    fails the case is searched again cold, exactly as alone. B1 at 0.03 deg misalignment
    and 0 N after 0 deg and 500 N was refused so (the warm search's evaluations cut the
    cold one short): it is found, and equals the case solved alone (the same cold search:
    to round-off)."""
    tilt = math.radians(0.03)
    cfg = variant()
    grid = {"inner_ring.misalignment": [0.0, tilt], "operating.axial_load": [0.0, 500.0]}
    ds = statics_sweep(cfg, grid, stiffness=False)
    assert list(ds.error.values) == ["", "", "", ""]
    alone = statics(cfg, misalignment=tilt, axial_load=0.0)
    assert float(ds.max_roller_load[2]) == pytest.approx(float(alone.max_roller_load), rel=1e-9)


def test_a_sweeps_figure_draws_its_axis_in_the_units_engineers_give():
    """The swept value along a sweep figure's x axis: angles in degrees (a misalignment of
    0.1 deg is 1.745e-3 rad, whose tick labels ran into each other), speeds in rpm
    (pi/30 rad/s per rpm), temperatures in degC (273.15 K at 0 degC), lengths below 1 mm
    in um and below 1 m in mm; other units as they are."""
    from rollerdyn.statics_plots import shown_axis

    values, unit = shown_axis(np.array([0.0, math.radians(0.1)]), "rad")
    assert unit == "deg" and values == pytest.approx([0.0, 0.1], rel=1e-12)
    values, unit = shown_axis(np.array([500.0 * math.pi / 30.0]), "rad/s")
    assert unit == "rpm" and values == pytest.approx([500.0], rel=1e-12)
    values, unit = shown_axis(np.array([353.15]), "K")
    assert unit == "degC" and values == pytest.approx([80.0], rel=1e-12)
    values, unit = shown_axis(np.array([0.0, 20e-6]), "m")
    assert unit == "um" and values == pytest.approx([0.0, 20.0], rel=1e-12)
    values, unit = shown_axis(np.array([4e-3, 6e-3]), "m")
    assert unit == "mm" and values == pytest.approx([4.0, 6.0], rel=1e-12)
    values, unit = shown_axis(np.array([5000.0]), "N")
    assert unit == "N" and values == pytest.approx([5000.0])


def test_the_balanced_spin_and_skew_are_the_dynamic_models_in_the_load_zone():
    """The statics' spin and skew balances against the dynamic model: B1 started from
    equilibrium at full load and speed (1000 N axially, 500 rpm), 5-30 ms. The rollers
    within 10 deg of the load zone's centre spin 0.195 % faster than rolling without slip
    in the run (relative to the roller set's frame, measured), the statics' balance gives
    0.209 % for the roller there: within 15 % (7 % measured; before the skew was balanced
    0.225 %, 15 %; rolling without slip is the whole 0.195 % off). The remaining difference
    is the run's ends pressing the flanges 10-20 um higher. The rollers skew by -0.131,
    -0.128, -0.116 and -0.081 mrad at 0, 21, 42 and 64 deg from the centre in the run, the
    statics' skew balance -0.123, -0.121, -0.111 and -0.079 mrad: each within 10 % (2-6 %
    measured); the skew at zero, as the equilibrium has it, would be the whole of it off."""
    import rollerdyn

    cfg = variant(
        **{
            "operating.load_ramp": None,
            "operating.speed_ramp": None,
            "operating.end_time": "30 ms",
            "solver.start": "equilibrium",
            "solver.output_interval": "0.1 ms",
        }
    )
    ds = rollerdyn.simulate(cfg, t_end=0.03)
    g, speed = cfg.geometry, cfg.operating.inner_ring_speed
    r, r_i = g.roller_diameter / 2, g.inner_raceway_diameter / 2
    orbit = 0.5 * speed * (1 - g.roller_diameter / g.pitch_diameter)
    rolling = (orbit - speed) * r_i / r  # the spin of rolling without slip, relative
    late = ds.time.values >= 5e-3
    azimuth = np.degrees(ds.azimuth.values[late]) % 360
    bottom = np.abs(azimuth - 180.0) < 10.0
    run_slip = 1.0 - np.mean(ds.spin_speed.values[late][bottom] - orbit) / rolling
    st = statics(cfg)
    balanced = float(st.roller_slip[0])  # roller 0 stands at 180 deg
    assert run_slip < -1e-3  # spun up by the flanges
    assert abs(balanced - run_slip) <= 0.15 * abs(run_slip), (balanced, run_slip)
    for i in range(4):  # rollers 0-3 at 180, 201, 222 and 244 deg
        near = np.abs(azimuth - float(st.roller_azimuth[i]) % 360) < 10.0
        run_skew = float(np.mean(ds.skew.values[late][near]))
        assert run_skew < -5e-5
        assert float(st.roller_skew[i]) == pytest.approx(run_skew, rel=0.1), i


def test_cli_prints_every_rollers_loads_flange_forces_and_slip():
    """``rollerdyn statics --per-roller``: one row per roller with the case's values (roller
    0 of B1 at the load zone's centre: 1311 N at either race, 141.1 N at the inner -x and
    outer +x flanges, skew -0.123 mrad, slip -0.209 %, no roller train under gravity
    alone); with a sweep it
    is refused before any work."""
    runner = CliRunner()
    result = runner.invoke(app, ["statics", str(B1), "--per-roller"])
    assert result.exit_code == 0, result.output
    rows = [line for line in result.output.splitlines() if line.startswith("│")]
    table = rows[rows.index(next(r for r in rows if "180.0" in r)) :]
    assert len(table) == 17
    cells = [c.strip() for c in table[0].strip("│").split("│")]
    assert cells[:4] == ["0", "180.0", "1311", "1311"]
    assert cells[4] == cells[7] == "141.1" and cells[5] == cells[6] == "0"
    assert cells[-3:] == ["-0.123", "-0.209", "0"]
    sweep = runner.invoke(
        app, ["statics", str(B1), "--per-roller", "--set", "operating.radial_load=1000,2000"]
    )
    assert sweep.exit_code == 2 and "--per-roller" in sweep.output


def test_cli_validates_the_bearing_with_the_load_case_it_solves():
    """A bearing of type NU (the outer ring's flanges only) cannot carry B1's 1000 N
    axially; `rollerdyn statics --set geometry.flanges=... --set operating.axial_load=0`
    solves it (the configuration is validated with the case's axial load, as `rollerdyn
    check` with the same --set), and a sweep that includes 100 N is refused naming
    operating.axial_load."""
    runner = CliRunner()
    nu = ["statics", str(B1), "--set", 'geometry.flanges=["outer-x","outer+x"]']
    ok = runner.invoke(app, [*nu, "--set", "operating.axial_load=0 N"])
    assert ok.exit_code == 0, ok.output
    assert "largest flange force" in ok.output and "quasi-static equilibrium" in ok.output
    refused = runner.invoke(app, [*nu, "--set", "operating.axial_load=0,100"])
    assert refused.exit_code == 2 and "operating.axial_load" in refused.output
    assert 'geometry.flanges has no "inner-x"' in refused.output
    # and so is each bearing of a design sweep
    design = runner.invoke(
        app,
        [
            *nu,
            "--set",
            "geometry.diametral_clearance=0 um,10 um",
            "--set",
            "operating.axial_load=0",
        ],
    )
    assert design.exit_code == 0 and "quasi-static sweep: 2 cases" in design.output, design.output
    # ranges with units (numpy values inside) validate the same way
    for option in (
        'operating.inner_ring_speed="0 rpm:3000 rpm:4"',
        'inner_ring.misalignment="0 deg:0.05 deg:3"',
    ):
        swept = runner.invoke(
            app, ["statics", str(B1), "--set", option, "--set", "operating.axial_load=0"]
        )
        assert swept.exit_code == 0, swept.output
        assert "quasi-static sweep: 4 cases" in swept.output or "3 cases" in swept.output


def test_the_point_law_gives_no_friction_where_its_ends_lie_on_their_faces():
    """Past the tilt at which B1's nearly flat roller end lies on the flange, the point
    law's contact jumps across the face and rim (the dynamic run is refused there, core
    ``check_point_law``), and its friction of steady rolling was no estimate: B1 at 5 kN
    gave 0.46, 0.17 and 0.14 N*m at 1.9, 1.95 and 2 kN axially against the distributed
    law's 0.59 at 2 kN. Where the most loaded end touches with its end sphere (SP-*) the
    friction outputs are NaN and ``friction_note`` says why and names the remedy; the
    equilibrium's loads stay. At 1 kN (TO-CO) and with the distributed law at 2 kN there
    is an estimate and no note. In a sweep the note is per case."""
    on_face = statics(B1, axial_load=2000.0)
    assert str(on_face.max_flange_force_pairing.values).startswith("SP")
    note = str(on_face.friction_note.values)
    assert "lies on its end face (SP-TO(rim))" in note and "flange_law" in note
    for name in ("friction_torque", "friction_power", "roller_slip", "roller_skew"):
        assert np.isnan(on_face[name].values).all(), name
    assert np.isnan(on_face.flange_contact_offset.values).all()
    assert float(on_face.max_roller_load) > 1000.0
    distributed = statics(variant(**{"surfaces.flange_law": "distributed"}), axial_load=2000.0)
    at_1kn = statics(B1, axial_load=1000.0)
    for ds in (distributed, at_1kn):
        assert str(ds.friction_note.values) == ""
        assert math.isfinite(float(ds.friction_torque))
    # at rest and with the rings turning together there is no torque with any law: no
    # note, and no advice to change the law
    for kwargs in ({"speed": 0.0}, {"outer_speed": 500 * math.pi / 30}):
        still = statics(B1, axial_load=2000.0, **kwargs)
        assert str(still.friction_note.values) == "" and math.isnan(float(still.friction_torque))
    sweep = statics_sweep(B1, {"operating.axial_load": [1000.0, 2000.0]}, stiffness=False)
    assert [bool(v) for v in sweep.friction_note.values] == [False, True]
    assert np.isfinite(sweep.friction_torque.values).tolist() == [True, False]
    res = CliRunner().invoke(app, ["statics", str(B1), "--set", "operating.axial_load=2000 N"])
    assert res.exit_code == 0, res.output
    assert "n/a: the point law's most loaded roller end lies on its end face" in " ".join(
        res.output.split()
    )


def test_a_bearing_outside_iso_281s_range_is_refused_in_one_line(monkeypatch):
    """A bearing whose D/d_m lies outside ISO 281's Table 7 has no load rating: the statics
    refuse it with one line naming the geometry and the rule (it was a ValueError's
    traceback from ``rollerdyn statics`` on a 1000/1003 mm bearing of ``rollerdyn new``,
    which now refuses such raceways itself). The rating's own check is ISO 281's, raised
    here for B1 as it is for such a bearing."""
    import rollerdyn.statics as st

    def out_of_range(*args, **kwargs):
        raise ValueError(
            "roller_diameter, pitch_diameter: D_we cos(alpha) / D_pw = 0.00129 must lie in "
            "[0.01, 0.3], the range of ISO 281:2007 Table 7"
        )

    monkeypatch.setattr(st.life, "dynamic_load_rating", out_of_range)
    with pytest.raises(StaticsError, match=r"^geometry: .* the range of ISO 281:2007 Table 7"):
        statics(B1)
    res = CliRunner().invoke(app, ["statics", str(B1)])
    assert res.exit_code == 1 and "Traceback" not in res.output
    assert len(res.output.strip().splitlines()) == 1, res.output
