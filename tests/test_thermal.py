"""The thermal balance of an operating map (``rollerdyn study map --temperature ...
--heat-dissipation ...``, :mod:`rollerdyn.study.thermal`): the balance against closed
forms and an independent root finder, its statuses and notes, the options' refusals, and
B1's map over two oil temperatures."""

from __future__ import annotations

import math
import re

import numpy as np
import pandas as pd
import pytest
from b1 import B1, load_b1
from hypothesis import given, settings
from hypothesis import strategies as st
from typer.testing import CliRunner

from rollerdyn.cli import app
from rollerdyn.study import StudyError, operating_map
from rollerdyn.study.thermal import (
    ABOVE,
    BALANCED,
    BELOW,
    BRACKETED,
    FASTER,
    FOUND,
    NO_VALUE,
    SLOWER,
    UNKNOWN,
    Dissipation,
    balance,
    balance_temperatures,
    oil_specific_heat,
    permissible_speeds,
    write_balance_figure,
    write_speed_figure,
)

RUNNER = CliRunner()
C = 273.15  # 0 degC in K


def _exact_root(p0: float, decay: float, t0: float, conductance: float, ambient: float):
    """The root of p0 exp(-decay (T - t0)) = conductance (T - ambient) by Newton's method
    from the right of it (the function is convex and decreasing, so Newton converges
    monotonically from where it is negative): independent of the module's bisection on
    its interpolant."""
    t = ambient + p0 / conductance + 1.0  # f(t) < 0 here
    for _ in range(200):
        p = p0 * math.exp(-decay * (t - t0))
        f = p - conductance * (t - ambient)
        step = f / (-decay * p - conductance)
        t -= step
        if abs(step) < 1e-13 * max(1.0, abs(t)):
            break
    return t


@settings(max_examples=200, deadline=None)
@given(
    p0=st.floats(0.05, 200.0),
    decay=st.floats(0.0, 0.06),
    conductance=st.floats(0.005, 5.0),
    ambient=st.floats(-20.0, 60.0),
    n=st.integers(2, 7),
    t_low=st.floats(0.0, 80.0),
    span=st.floats(5.0, 120.0),
)
def test_balance_of_an_exponential_friction_is_its_exact_root(
    p0, decay, conductance, ambient, n, t_low, span
):
    """Friction power falling exponentially with temperature (the Vogel law's viscosity
    over tens of kelvin) is what the interpolation assumes, so the balance is the exact
    root wherever the map brackets it, to the bisection's 1e-12 of an interval; outside
    the map the status says on which side (P - Q is decreasing: one root at most)."""
    temps = C + t_low + span * np.arange(n) / (n - 1)
    power = p0 * np.exp(-decay * (temps - temps[0]))
    ambient_k = C + ambient
    status, t_star, p_star = balance(temps, power, conductance, ambient_k)
    surplus = power - conductance * (temps - ambient_k)
    if surplus[0] <= 0:
        assert status == BELOW and math.isnan(t_star)
    elif surplus[-1] > 0:
        assert status == ABOVE and math.isnan(t_star)
    else:
        exact = _exact_root(p0, decay, temps[0], conductance, ambient_k)
        assert status == BALANCED
        assert t_star == pytest.approx(exact, abs=1e-9 * span + 1e-9)
        # the balance's power is the heat given off there (to the bisection's tolerance)
        assert p_star == pytest.approx(conductance * (t_star - ambient_k), rel=1e-8, abs=1e-9)


def test_balance_takes_the_first_stable_crossing_and_a_straight_line_without_power():
    temps = C + np.array([40.0, 60.0, 80.0, 100.0])
    # a friction power that dips and rises again: P - Q is +, -, +, -; the balance is the
    # first crossing from + to - (a bearing just warmer gives off more than it makes)
    power = np.array([10.0, 2.0, 30.0, 1.0])
    status, t_star, _ = balance(temps, power, 0.2, C + 20.0)
    q = 0.2 * (temps - (C + 20.0))  # 4, 8, 12, 16 W
    assert status == BALANCED and temps[0] < t_star < temps[1]
    # exponential between 10 and 2 W: 10 * 0.2**s = 4 + 4 s, solved by hand to 1e-9
    s = (t_star - temps[0]) / 20.0
    assert 10.0 * 0.2**s == pytest.approx(4.0 + 4.0 * s, abs=1e-9)
    # a power of zero at one end (nothing turns): the straight line between the two
    power = np.array([10.0, 0.0, 0.0, 0.0])
    status, t_star, p_star = balance(temps, power, 0.2, C + 20.0)
    s = (10.0 - q[0]) / ((10.0 - q[0]) - (0.0 - q[1]))  # the line's root, by hand
    assert status == BALANCED and t_star == pytest.approx(temps[0] + 20.0 * s, abs=1e-9)
    assert p_star == pytest.approx(10.0 * (1 - s), abs=1e-9)
    # one temperature: no balance
    assert balance(temps[:1], power[:1], 0.2, C + 20.0)[0] == NO_VALUE


def test_a_circulating_oil_adds_its_heat_capacity_rate_to_the_dissipation():
    """Q(T) = W_s (T - T_amb) + rho c_p V (T - T_in) is one line, W (T - T_ref); c_p by
    Cragoe's formula: 1.685 + 0.00339 t kJ/(kg K) over sqrt(d) in SI (t in degC; its
    constants rounded, hence 2e-4), and the specific heat of a mineral oil near 2 kJ/(kg K)
    at 60 degC (e.g. 1.9-2.1 in tables of lubricant properties)."""
    d15 = 887.6 / 999.0
    for t_c in (20.0, 60.0, 100.0):
        si = 1000.0 * (1.685 + 0.00339 * t_c) / math.sqrt(d15)
        assert oil_specific_heat(C + t_c, 887.6) == pytest.approx(si, rel=2e-4)
    assert 1900.0 < oil_specific_heat(C + 60.0, 887.6) < 2100.0
    d = Dissipation(0.3, C + 20.0, oil_rate=12.0, oil_inlet=C + 40.0)
    for t in (C + 50.0, C + 90.0):
        q = 0.3 * (t - (C + 20.0)) + 12.0 * (t - (C + 40.0))
        assert d.total * (t - d.reference) == pytest.approx(q, rel=1e-12)
    assert Dissipation(0.3, C + 20.0).reference == C + 20.0


def test_the_map_options_make_the_dissipation_with_the_configurations_oil():
    """--oil-flow 0.5 l/min at --oil-inlet 40 degC on B1: rho (887.6 - 0.6 * 25 kg/m^3 at 40
    degC) times Cragoe's c_p times the flow; the inlet defaults to the ambient."""
    from rollerdyn.study.thermal import dissipation_from_options as _dissipation

    cfg = load_b1()
    options = {
        "--heat-dissipation": "0.34 W/K",
        "--ambient": None,
        "--oil-flow": "0.5 l/min",
        "--oil-inlet": "40 degC",
        "--permissible-temperature": "70",
    }
    d = _dissipation(cfg, [C + 40.0, C + 60.0], options)
    rho = 887.6 - 0.6 * 25.0
    flow = 0.5e-3 / 60.0
    assert d.oil_rate == pytest.approx(flow * rho * oil_specific_heat(C + 40.0, 887.6), rel=1e-12)
    assert (d.conductance, d.ambient, d.oil_inlet, d.permissible) == (
        0.34,
        pytest.approx(C + 20.0),
        pytest.approx(C + 40.0),
        pytest.approx(C + 70.0),
    )
    options["--oil-inlet"] = None
    assert _dissipation(cfg, [C + 40.0, C + 60.0], options).oil_inlet == pytest.approx(C + 20.0)
    # a limit at or below the sinks' temperature has no permissible speed: refused (10 degC
    # under a 20 degC ambient drew an empty figure with exit status 0; a review)
    from rollerdyn.study import StudyError

    for limit, sink in (("10", "20"), ("20 degC", "20")):
        options["--permissible-temperature"] = limit
        with pytest.raises(StudyError, match=f"must be above {sink} degC, the temperature of"):
            _dissipation(cfg, [C + 40.0, C + 60.0], options)
    options |= {"--oil-inlet": "40 degC", "--permissible-temperature": "25 degC"}
    # the oil (13.8 W/K) outweighs the housing (0.34 W/K): the sinks are near 40 degC
    with pytest.raises(StudyError, match=r"must be above 39\.\d+ degC"):
        _dissipation(cfg, [C + 40.0, C + 60.0], options)


def _frame(rows):
    keys = (
        "speed [rpm]",
        "radial_load [N]",
        "axial_load [N]",
        "temperature [degC]",
        "status",
        "torque [N*m]",
    )
    return pd.DataFrame([dict(zip(keys, r, strict=True)) for r in rows])


def test_balance_table_has_one_row_per_speed_and_loads_with_its_reasons(tmp_path):
    w = 1000 * math.pi / 30  # 1000 rpm
    rows = [
        # balanced between 60 and 100 degC (P = 10.5 and 2.1 W; Q = 8 and 16 W)
        (1000.0, 5000.0, 0.0, 60.0, "steady", 10.5 / w),
        (1000.0, 5000.0, 0.0, 100.0, "not steady", 2.1 / w),
        # hotter than the map: 40 W at 100 degC against 16 W given off
        (1000.0, 5000.0, 1000.0, 60.0, "steady", 50.0 / w),
        (1000.0, 5000.0, 1000.0, 100.0, "steady", 40.0 / w),
        # cooler than the map: 1 W at 60 degC against 8 W
        (2000.0, 5000.0, 0.0, 60.0, "steady", 1.0 / (2 * w)),
        (2000.0, 5000.0, 0.0, 100.0, "steady", 0.5 / (2 * w)),
        # one point failed (no torque): one temperature left, no balance
        (2000.0, 5000.0, 1000.0, 60.0, "steady", 20.0 / (2 * w)),
        (2000.0, 5000.0, 1000.0, 100.0, "failed", math.nan),
    ]
    frame = _frame(rows)
    table = balance_temperatures(frame, Dissipation(0.2, C + 20.0))
    assert len(table) == 4
    by = {(r["speed [rpm]"], r["axial_load [N]"]): r for _, r in table.iterrows()}
    ok = by[(1000.0, 0.0)]
    assert ok["status"] == BALANCED and 60.0 < ok["balance temperature [degC]"] < 100.0
    t = ok["balance temperature [degC]"]
    assert ok["friction power [W]"] == pytest.approx(0.2 * (t - 20.0), rel=1e-9)
    assert ok["torque [N*m]"] == pytest.approx(ok["friction power [W]"] / w, rel=1e-12)
    assert ok["note"] == "points not steady at 100 degC"
    hot = by[(1000.0, 1000.0)]
    assert hot["status"] == ABOVE and math.isnan(hot["balance temperature [degC]"])
    assert hot["note"].startswith("at 100 degC the friction makes 40 W and 0.2 W/K give off 16 W")
    cold = by[(2000.0, 0.0)]
    assert cold["status"] == BELOW and "at 60 degC the friction makes 1 W" in cold["note"]
    assert by[(2000.0, 1000.0)]["status"] == NO_VALUE
    assert by[(2000.0, 1000.0)]["temperatures [degC]"] == "60"
    files = write_balance_figure(frame, table, Dissipation(0.2, C + 20.0), tmp_path, "B1")
    assert [f.name for f in files] == ["thermal_balance.png", "thermal_balance.svg"]
    assert all(f.stat().st_size > 1000 for f in files)


def test_balance_table_gives_the_steady_rolling_estimates_balance_beside_it():
    """The quasi-static estimate's power (the map's steady rolling torque times the
    speed) is balanced by the same rule as the dynamic one: its temperature is
    balance()'s on those powers; outside the map it is NaN and the note says on which
    side."""
    from rollerdyn.study.estimates import STEADY_ROLLING
    from rollerdyn.study.thermal import STEADY_ROLLING_BALANCE

    w = 1000 * math.pi / 30
    frame = _frame(
        [
            (1000.0, 5000.0, 0.0, 60.0, "steady", 10.5 / w),
            (1000.0, 5000.0, 0.0, 100.0, "steady", 2.1 / w),
            (2000.0, 5000.0, 0.0, 60.0, "steady", 10.5 / (2 * w)),
            (2000.0, 5000.0, 0.0, 100.0, "steady", 2.1 / (2 * w)),
        ]
    )
    # at 1000 rpm 12 and 4 W (balanced, hotter than the dynamic balance); at 2000 rpm
    # 40 and 30 W against 8 and 16 W given off: above the map
    frame[STEADY_ROLLING] = [12.0 / w, 4.0 / w, 40.0 / (2 * w), 30.0 / (2 * w)]
    table = balance_temperatures(frame, Dissipation(0.2, C + 20.0))
    slow, fast = table.iloc[0], table.iloc[1]
    _, t_star, _ = balance(np.array([C + 60, C + 100]), np.array([12.0, 4.0]), 0.2, C + 20)
    assert slow[STEADY_ROLLING_BALANCE] == pytest.approx(t_star - C, rel=1e-12)
    assert slow[STEADY_ROLLING_BALANCE] > slow["balance temperature [degC]"]
    assert slow["note"] == ""
    assert math.isnan(fast[STEADY_ROLLING_BALANCE]) and fast["status"] == BALANCED
    assert fast["note"] == "steady rolling (quasi-static): above the map"
    # a table of before (no estimate column): NaN, no note
    old = balance_temperatures(frame.drop(columns=STEADY_ROLLING), Dissipation(0.2, C + 20.0))
    assert old[STEADY_ROLLING_BALANCE].isna().all() and (old["note"] == "").all()


def _balances(rows):
    """A balance table: (speed, axial load, status, T* [degC]) per row, the map's
    temperatures 60 ... 100 degC."""
    return pd.DataFrame(
        [
            {
                "speed [rpm]": n,
                "radial_load [N]": 5000.0,
                "axial_load [N]": fa,
                "status": status,
                "balance temperature [degC]": t,
                "lowest temperature [degC]": 60.0,
                "highest temperature [degC]": 100.0,
            }
            for n, fa, status, t in rows
        ]
    )


def test_permissible_speed_is_where_the_balance_reaches_the_permissible_temperature(tmp_path):
    nan = math.nan
    table = _balances(
        [
            # found: 65 degC at 1000 rpm, 85 degC at 2000 rpm -> 70 degC at 1250 rpm
            (1000.0, 0.0, BALANCED, 65.0),
            (2000.0, 0.0, BALANCED, 85.0),
            (3000.0, 0.0, ABOVE, nan),
            # bracketed: below the map (< 60 degC) at 1000 rpm, above it at 2000 rpm
            (1000.0, 500.0, BELOW, nan),
            (2000.0, 500.0, ABOVE, nan),
            (3000.0, 500.0, ABOVE, nan),
            # slower than the map: 75 degC already at 1000 rpm
            (1000.0, 1000.0, BALANCED, 75.0),
            (2000.0, 1000.0, ABOVE, nan),
            (3000.0, 1000.0, ABOVE, nan),
            # faster than the map: below 70 degC up to 3000 rpm
            (1000.0, 1500.0, BELOW, nan),
            (2000.0, 1500.0, BALANCED, 62.0),
            (3000.0, 1500.0, BALANCED, 69.0),
            # undetermined: no balance at 2000 rpm, before the crossing
            (1000.0, 2000.0, BALANCED, 65.0),
            (2000.0, 2000.0, NO_VALUE, nan),
            (3000.0, 2000.0, ABOVE, nan),
        ]
    )
    speeds = permissible_speeds(table, 70.0)
    by = {r["axial_load [N]"]: r for _, r in speeds.iterrows()}
    assert by[0.0]["status"] == FOUND
    assert by[0.0]["permissible speed [rpm]"] == pytest.approx(1250.0, rel=1e-12)
    assert (by[0.0]["from [rpm]"], by[0.0]["to [rpm]"]) == (1000.0, 2000.0)
    assert by[500.0]["status"] == BRACKETED and math.isnan(by[500.0]["permissible speed [rpm]"])
    assert by[500.0]["note"].startswith("between 1000 and 2000 rpm")
    assert by[1000.0]["status"] == SLOWER
    assert by[1000.0]["note"] == "the balance is above 70 degC already at 1000 rpm"
    assert by[1500.0]["status"] == FASTER
    assert by[1500.0]["note"] == "the balance stays below 70 degC up to 3000 rpm"
    assert by[2000.0]["status"] == UNKNOWN and "widen --temperature" in by[2000.0]["note"]
    # a permissible temperature outside the map's: "below the map" no longer tells the side
    assert permissible_speeds(table, 50.0).iloc[1]["status"] == UNKNOWN
    files = write_speed_figure(table, speeds, 70.0, tmp_path, "B1")
    assert [f.name for f in files] == ["thermal_speed.png", "thermal_speed.svg"]


@pytest.mark.parametrize(
    ("options", "message"),
    [
        ({"heat_dissipation": "0.3 W/K"}, "needs the friction at two or more oil temperatures"),
        (
            {"heat_dissipation": "-1 W/K", "temperature": "60,80"},
            "--heat-dissipation '-1 W/K': must be above 0 W/K",
        ),
        (
            {"heat_dissipation": "0.3 W", "temperature": "60,80"},
            "--heat-dissipation '0.3 W': expected a thermal conductance",
        ),
        ({"ambient": "20 degC"}, "--ambient '20 degC': belongs to the thermal balance"),
        (
            {"permissible_temperature": 70},
            "--permissible-temperature 70: belongs to the thermal balance",
        ),
        (
            {"heat_dissipation": 0.3, "temperature": "60,80", "permissible_temperature": "7 m"},
            "--permissible-temperature '7 m': expected a temperature",
        ),
        ({"oil_flow": "1 l/min"}, "--oil-flow '1 l/min': belongs to the thermal balance"),
        (
            {"heat_dissipation": 0.3, "temperature": "60,80", "oil_inlet": 40},
            "--oil-inlet 40: the temperature of an oil flow, which needs --oil-flow",
        ),
        (
            {"heat_dissipation": 0.3, "temperature": "60,80", "oil_flow": "-1 l/min"},
            "--oil-flow '-1 l/min': must be above 0 m",
        ),
        (
            {"heat_dissipation": 0.3, "temperature": "60,80", "oil_flow": "1 l"},
            "--oil-flow '1 l': expected a volume flow",
        ),
        (  # 887.6 - 0.6 (T - 15 degC) kg/m^3 is negative from 1494 degC on
            {
                "heat_dissipation": 0.3,
                "temperature": "60,80",
                "oil_flow": "1 l/min",
                "oil_inlet": "1600 degC",
            },
            "--oil-inlet '1600 degC': the oil's density there is -63.4 kg/m",
        ),
        (
            {"heat_dissipation": 0.3, "temperature": "60,80", "ambient": "hot"},
            "--ambient 'hot'",
        ),
        (
            {"heat_dissipation": "inf", "temperature": "60,80"},
            "--heat-dissipation 'inf': must be finite",
        ),
        ({"temperature": "80,80"}, "--temperature '80,80': a value is given twice"),
        # one point with three problems is one point that fails
        (
            {"temperature": "60 K,80 degC"},
            r"invalid map: 1 grid point\(s\) fail validation .* -213.15 degC",
        ),
        ({"temperature": "-300"}, "--temperature '-300': "),
        (
            {"temperature": "60,400"},
            r"point 1 \(1000 rpm, F_r = 5000 N, F_a = 1000 N, 400 degC\): operating.temperature",
        ),
    ],
)
def test_map_options_of_the_thermal_balance_are_refused_by_name(tmp_path, options, message):
    with pytest.raises(StudyError, match=message):
        operating_map(B1, tmp_path / "map", speed="1000", **options)
    assert not (tmp_path / "map").exists()  # refused before any folder or run


def test_b1_map_over_two_oil_temperatures_finds_its_balance(tmp_path):
    """B1 without axial load at 3000 rpm at 60 and 100 degC (from equilibrium, one worker
    in this process; a loose criterion: steady within a few windows). Physics: the friction
    falls as the oil thins (Palmgren's and the SKF model's speed terms go as (nu n)^(2/3)
    and (nu n)^0.6; rollerdyn's with the mixed rolling resistance more steeply), the film
    with it (Lambda about nu^0.7, EHL film theory), and the balance lies where the map's
    power and the heat given off meet."""
    heat = 0.05  # W/K: between 9.8 W / 40 K and 3.3 W / 80 K, so the balance is inside
    result = RUNNER.invoke(
        app,
        [
            "study",
            "map",
            str(B1),
            "--speed",
            "3000",
            "--axial-load",
            "0",
            "--temperature",
            "60,100",
            "--heat-dissipation",
            f"{heat} W/K",
            "--permissible-temperature",
            "70 degC",
            "--window",
            "1 ms",
            "--tol",
            "0.5",
            "--max-time",
            "30 ms",
            "--workers",
            "1",
            "-o",
            str(tmp_path / "map"),
        ],
    )
    assert result.exit_code == 0, result.output
    assert "thermal balance of" in result.output and "balanced" in result.output
    points = pd.read_csv(tmp_path / "map" / "map.csv")
    assert list(points["temperature [degC]"]) == [60.0, 100.0]
    assert (points["status"] == "steady").all()
    cool, hot = points.iloc[0], points.iloc[1]
    # the oil at 60 and 100 degC (B1's Vogel law; Roelands' alpha = z ln(eta0/eta_p)/196 MPa
    # with z fitted at each temperature): eta0 33.1 and 9.45 mPa*s, alpha 19.7 and 16.0 1/GPa
    cfg = load_b1()
    lub = cfg.lubricant
    eta = [lub.eta0(C + t) for t in (60.0, 100.0)]
    alpha = [
        lub.roelands_z_at(C + t) * math.log(e / lub.roelands.eta_p)
        for t, e in zip((60.0, 100.0), eta, strict=True)
    ]
    eta_ratio, alpha_ratio = eta[0] / eta[1], alpha[0] / alpha[1]
    # friction grows with the viscosity, but more slowly than it (every film and traction
    # law of the model is sublinear in eta0) and not more slowly than the SKF model's
    # rolling term, (nu n)^0.6 (docs/study.md, "The thermal balance": nu^0.90 measured)
    torque_ratio = cool["torque [N*m]"] / hot["torque [N*m]"]
    assert eta_ratio**0.6 < torque_ratio < eta_ratio
    # the race film as Dowson & Higginson's line contact, h ~ U^0.7 G^0.54 (the load and
    # speed the same): 2.70 against 2.78 measured; 10 % for the thermal correction, Moes'
    # formula and the median over contacts of different loads
    lam = cool["inner race Lambda [1]"] / hot["inner race Lambda [1]"]
    assert lam == pytest.approx(eta_ratio**0.7 * alpha_ratio**0.54, rel=0.10)
    table = pd.read_csv(tmp_path / "map" / "thermal.csv")
    row = table.iloc[0]
    assert row["status"] == BALANCED and 60.0 < row["balance temperature [degC]"] < 100.0
    assert row["friction power [W]"] == pytest.approx(
        heat * (row["balance temperature [degC]"] - 20.0), rel=1e-8
    )
    p = [cool["torque [N*m]"] * 100 * math.pi, hot["torque [N*m]"] * 100 * math.pi]
    assert p[1] < row["friction power [W]"] < p[0]
    assert (tmp_path / "map" / "figures" / "thermal_balance.png").is_file()
    # the map's page: its points, the balance, the permissible speed and every map
    page = (tmp_path / "map" / "report.html").read_text(encoding="utf-8")
    for heading in ("Points", "Thermal balance", "Thermally permissible speed", "Maps"):
        assert f">{heading}</h2>" in page
    pngs = sorted(p.stem for p in (tmp_path / "map" / "figures").glob("*.png"))
    assert sorted(re.findall(r'<img alt="([^"]+)" src="data:image/png;base64,', page)) == pngs
    assert "map_torque" in pngs and "thermal_speed" in pngs
    # at 3000 rpm the balance (about 95 degC) is above 70 degC already
    speeds = pd.read_csv(tmp_path / "map" / "thermal_speed.csv")
    assert speeds.iloc[0]["status"] == SLOWER and "thermally permissible speed" in result.output
    assert (tmp_path / "map" / "figures" / "map_torque.png").is_file()
    # the same map again without a heat dissipation: its points are reused, the stale
    # balance is removed
    again = operating_map(
        B1,
        tmp_path / "map",
        speed="3000",
        axial_load="0",
        temperature="60,100",
        window=0.001,
        tol=0.5,
        max_time=0.03,
        workers=1,
    )
    assert again.thermal is None and not (tmp_path / "map" / "thermal.csv").exists()
    assert not (tmp_path / "map" / "figures" / "thermal_balance.png").exists()
    assert again.permissible is None and not (tmp_path / "map" / "thermal_speed.csv").exists()
    assert not (tmp_path / "map" / "figures" / "thermal_speed.svg").exists()


def test_map_figure_of_four_swept_quantities_has_a_panel_per_combination_of_the_others(
    monkeypatch,
):
    """Speed x temperature as the colour map (the two with the most values), one panel per
    radial and axial load (2 x 2, laid out three to a row; the sixth place hidden)."""
    import itertools

    import rollerdyn.plots as plots
    from rollerdyn.study.map_figures import write_maps

    rows = [
        {
            "speed [rpm]": n,
            "radial_load [N]": fr,
            "axial_load [N]": fa,
            "temperature [degC]": t,
            "status": "steady",
            "torque [N*m]": 1e-5 * n + 1e-4 * fa / t,
        }
        for n, fr, fa, t in itertools.product(
            [500.0, 1000.0, 2000.0], [3000.0, 5000.0], [0.0, 1000.0], [60.0, 80.0, 100.0]
        )
    ]
    figures = []
    monkeypatch.setattr(plots, "save_figure", lambda fig, out, name: figures.append(fig) or [])
    write_maps(pd.DataFrame(rows), ".", "B1")
    panels = [ax for ax in figures[0].axes if ax.get_visible() and ax.get_title()]
    assert [ax.get_title() for ax in panels] == [
        f"radial load [N] = {fr:g}, axial load [N] = {fa:g}"
        for fr, fa in itertools.product([3000.0, 5000.0], [0.0, 1000.0])
    ]
    assert {(ax.get_xlabel(), ax.get_ylabel()) for ax in panels} == {
        ("speed of the turning ring [rpm]", "oil temperature [degC]")
    }
