"""A turning outer ring (``operating.outer_ring_speed``; not in the paper, whose outer ring
is fixed): a planet gear's bearing turns its outer ring about a fixed pin.

Independent references: the contacts see only the bodies' relative motion (frame
indifference; the core's ``frame_tests`` check every contact force under a rigid turn of
the whole bearing), so at one relative speed the friction torque is the same whichever
ring turns, apart from what depends on the absolute motion (the rollers' centrifugal force
and the oil-air drag on the roller set's orbit); the roller set orbits at the epicyclic
speed omega_c = [Omega_i (1 - D/d_m) + Omega_o (1 + D/d_m)]/2 (Harris & Kotzalas, Rolling
Bearing Analysis, 5th ed., vol. 1, eq. 8.23); ISO/TS 16281 gives the ring that turns
relative to the load the power-4 equivalent load.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from b1 import B1, changed_b1, variant

from rollerdyn import life, simulate
from rollerdyn.config import ConfigError, parse_config
from rollerdyn.statics import statics

RPM = math.pi / 30.0
W = 500.0 * RPM


def _from_equilibrium(inner: str, outer: str) -> dict:
    """B1 at full load and at the ring speeds given from t = 0 (no ramps), for 60 ms."""
    return changed_b1(
        {
            "solver.start": "equilibrium",
            "operating.load_ramp": None,
            "operating.speed_ramp": None,
            "operating.inner_ring_speed": inner,
            "operating.outer_ring_speed": outer,
            "operating.end_time": "60 ms",
            "solver.output_interval": "0.5 ms",
        }
    )


def test_the_friction_torque_depends_on_the_relative_speed_only():
    """B1 at 5000 N, 1000 N: the inner ring at 500 rpm, the outer ring at 500 rpm, and both
    turning 500 rpm apart (250 and 750 rpm). The mean frictional torque over 30-60 ms
    agrees within 1 % (measured: 0.3025, 0.3028 and 0.3026 N*m, 0.1 %; what differs is
    the drag on an orbit up to 2.7 times as fast, 0.1 W of 15.8 W, and a centrifugal
    force of millinewtons on rollers carrying up to 1.3 kN); it is positive against the
    relative rotation whichever ring turns, and the outer ring takes it back. The roller
    set orbits within 1 % of the epicyclic speed (measured: 0.1-0.3 %)."""
    torques = []
    for inner, outer in (("500 rpm", "0 rpm"), ("0 rpm", "500 rpm"), ("250 rpm", "750 rpm")):
        cfg = parse_config(_from_equilibrium(inner, outer))
        ds = simulate(cfg, threads=1)
        late = ds.isel(time=ds.time.values > 0.03)
        torque = float(late.frictional_torque.mean())
        torques.append(torque)
        assert torque > 0.25, (inner, outer, torque)
        sense = np.sign(cfg.operating.final_relative_speed)
        outer_torque = float(late.outer_ring_torque.mean())
        assert sense * outer_torque == pytest.approx(torque, rel=0.02), (inner, outer)
        orbit = float(late.orbital_speed.mean())
        assert orbit == pytest.approx(cfg.roller_set_speed, rel=0.01), (inner, outer)
        assert float(ds.outer_ring_speed[-1]) == pytest.approx(cfg.operating.outer_ring_speed_at(1))
    assert max(torques) - min(torques) < 0.01 * torques[0], torques


def test_the_roller_set_speed_and_end_time_of_both_rings():
    """omega_c of eq. 8.23 for a turning outer ring alone and for both rings; the derived
    end time counts two revolutions of that roller set."""
    g = variant().geometry
    gamma = g.roller_diameter / g.pitch_diameter
    alone = variant(
        **{"operating.inner_ring_speed": "0 rpm", "operating.outer_ring_speed": "500 rpm"}
    )
    assert alone.roller_set_speed == pytest.approx(W * (1 + gamma) / 2, rel=1e-12)
    both = variant(**{"operating.outer_ring_speed": "-500 rpm"})
    assert both.roller_set_speed == pytest.approx(-W * gamma, rel=1e-12)
    assert both.end_time == pytest.approx(0.7 + 2 * 2 * math.pi / (W * gamma), rel=1e-12)
    # both rings alike turn the bearing rigidly: the set orbits with them
    rigid = variant(**{"operating.outer_ring_speed": "500 rpm"})
    assert rigid.roller_set_speed == pytest.approx(W, rel=1e-12)
    assert rigid.operating.final_relative_speed == 0.0


def test_statics_of_a_turning_outer_ring():
    """The equilibrium's loads are those of a turning inner ring (the centrifugal force on
    the faster orbit, 7 mN against 1.3 kN, moves them by 1e-6; tolerance 1e-5); L_10r
    takes the outer ring as the ring that turns relative to the load (ISO/TS 16281), which
    shortens it (B1: 42.4 against 48.0); the torque of steady rolling is the friction
    power over the relative speed, within 1 % of the inner ring's (measured 0.3 %: the
    closed-form rolling speeds ignore the ring's 53 um eccentricity, which leaves the races
    sliding by a slide-to-roll ratio of about 1e-3 in either frame, differently). The
    power is taken relative to the outer ring: with the bodies' absolute motion the
    paper's rolling resistance, couples without reaction, made it 0.7 % higher here and
    gave the outer race a negative power at half the inner ring's speed (below)."""
    inner = statics(B1)
    outer = statics(B1, speed=0.0, outer_speed=W)
    assert float(outer.max_roller_load) == pytest.approx(float(inner.max_roller_load), rel=1e-5)
    assert float(outer.outer_speed_applied) == W
    rebuilt = life.reference_rating_life(
        outer.inner_slice_load.values,
        outer.outer_slice_load.values,
        float(outer.dynamic_load_rating),
        variant().geometry.roller_diameter,
        variant().geometry.pitch_diameter,
        rotating="outer",
    )
    assert float(outer.l10r) == pytest.approx(rebuilt, rel=1e-12)
    assert float(outer.l10r) < 0.95 * float(inner.l10r)
    assert float(outer.friction_torque) == pytest.approx(
        float(outer.friction_power.sum()) / W, rel=1e-12
    )
    assert float(outer.friction_torque) == pytest.approx(float(inner.friction_torque), rel=0.01)
    # every contact takes power, the outer race too, with the outer ring at half the inner
    # ring's speed and no axial load (measured: 0.017 W inner race, 0.014 W outer race;
    # with the absolute motion the outer race gave -0.025 W)
    half = statics(B1, radial_load=1000.0, axial_load=0.0, speed=W, outer_speed=W / 2)
    assert (half.friction_power.sel(friction_part=["inner race", "outer race"]).values > 0.0).all()
    # the films follow the relative speed: the same rolling speeds at the races
    assert float(outer.min_specific_film_thickness) == pytest.approx(
        float(inner.min_specific_film_thickness), rel=1e-4
    )
    # no relative speed: no film and no friction torque to speak of
    rigid = statics(B1, outer_speed=W)
    assert math.isnan(float(rigid.friction_torque))
    assert math.isnan(float(rigid.min_specific_film_thickness))


@pytest.mark.parametrize(
    ("changes", "path", "rule"),
    [
        (
            {"operating.outer_ring_speed": "300000 rpm"},
            "operating.outer_ring_speed",
            "pitch-circle",
        ),
        (
            {"operating.outer_ring_speed": {"table": [["0 s", "0 rpm"], ["0.5 s", "500 rpm"]]}},
            "operating.speed_ramp",
            "outer_ring_speed is a time table",
        ),
        ({"operating.outer_ring_speed": "5 N"}, "operating.outer_ring_speed", "angular velocity"),
        (
            {
                "operating.inner_ring_speed": "0 rpm",
                "operating.outer_ring_speed": "0 rpm",
            },
            "operating.end_time",
            "roller set does not orbit",
        ),
    ],
)
def test_bad_outer_ring_speeds_are_refused_naming_the_field(changes, path, rule):
    with pytest.raises(ConfigError) as err:
        parse_config(changed_b1(changes))
    assert any(p.path == path and rule in p.rule for p in err.value.problems), str(err.value)


def test_an_operating_map_refuses_both_rings_turning(tmp_path):
    from rollerdyn.study import StudyError, operating_map

    cfg = variant(**{"operating.outer_ring_speed": "100 rpm"})
    with pytest.raises(StudyError, match=r"operating.outer_ring_speed = 100 rpm: a map sweeps"):
        operating_map(cfg, tmp_path / "m", speed="500")
    assert not (tmp_path / "m").exists()
