//! The outer ring turning (a planet gear's bearing): the contacts see only the bodies'
//! relative motion, so turning the whole bearing rigidly about its axis changes no
//! contact force (the laws are objective: Truesdell & Noll, the principle of material
//! frame-indifference); and the velocities of rolling without slip make the roller roll
//! on both raceways for any pair of ring speeds (Harris & Kotzalas, 2007, sect. 8.2).

use super::conservation_tests::loaded_sliding_state;
use super::run::record;
use super::test_b1::{in_workspace, params, Bearing, B1};
use super::{BearingModel, History, RollingResistance};
use crate::geometry::primitives::Vec3;
use proptest::prelude::*;

/// `model`'s parameters with the inner ring at Ω + w and the outer ring at w [rad/s].
fn turned(model: &BearingModel, w: f64) -> BearingModel {
    let mut p = model.params.clone();
    let inner = p.inner_ring_speed.at(0.0).0;
    p.inner_ring_speed = History::constant(inner + w);
    p.outer_ring_speed = History::constant(w);
    BearingModel::new(p).unwrap()
}

/// `y` with the whole bearing turned at w about +x added: every centre's velocity gains
/// w x̂ × c, every angular velocity w x̂.
fn turned_state(model: &BearingModel, y: &[f64], w: f64) -> Vec<f64> {
    let turn = Vec3::new(w, 0.0, 0.0);
    let mut y = y.to_vec();
    let ring = turn.cross(&Vec3::new(y[0], y[1], y[2]));
    for k in 0..3 {
        y[3 + k] += ring[k];
    }
    for i in 0..model.layout.rollers {
        let s = model.layout.roller(i);
        let v = turn.cross(&Vec3::new(y[s], y[s + 1], y[s + 2]));
        for k in 0..3 {
            y[s + 5 + k] += v[k];
            y[s + 8 + k] += turn[k];
        }
    }
    y
}

/// B1 loaded, rolling and sliding at every contact, every oil film on (the state of the
/// conservation tests), seen from a frame turning at w = ±300 rad/s (2 865 rpm, six times
/// B1's speed): every contact's wrenches on both bodies are the same. Tolerance: 1e-8 of
/// the largest contact force or moment. The turn adds up to w·R_o ≈ 4.4 m/s to surface
/// speeds of which the contacts take differences of about 1 mm/s, so a relative rounding
/// of 1e-16 becomes about 4e-13 of a sliding speed; the traction's slope at low sliding
/// (1/(1 mm/s) of the boundary friction's smoothing) makes that about 1e-9 of a force.
#[test]
fn turning_the_whole_bearing_changes_no_contact_force() {
    for axial in [true, false] {
        let (model, y) = loaded_sliding_state(RollingResistance::Balanced, axial);
        let reference = in_workspace(&model, |m| {
            let kin = m.kinematics(0.0, &y);
            m.evaluate_all(&kin)
        });
        let scale = reference
            .iter()
            .map(|r| r.on_b.force.norm().max(r.on_b.moment.norm() / 1e-3))
            .fold(0.0, f64::max);
        assert!(scale > 100.0, "{scale}");
        for w in [300.0, -300.0] {
            let other = turned(&model, w);
            let y_turned = turned_state(&other, &y, w);
            let results = in_workspace(&other, |m| {
                let kin = m.kinematics(0.0, &y_turned);
                assert_eq!(kin.outer_ring.omega, Vec3::new(w, 0.0, 0.0));
                m.evaluate_all(&kin)
            });
            for (e, (a, b)) in model.elements().iter().zip(reference.iter().zip(&results)) {
                for (wa, wb) in [(&a.on_a, &b.on_a), (&a.on_b, &b.on_b)] {
                    let df = (wa.force - wb.force).norm();
                    let dm = (wa.moment - wb.moment).norm() / 1e-3;
                    assert!(
                        df.max(dm) < 1e-8 * scale,
                        "{e:?} at w = {w}: {df} N, {dm} N (moment / 1 mm) of {scale} N"
                    );
                }
                assert_eq!(a.pairing, b.pairing, "{e:?}");
            }
        }
    }
}

/// The paper's rolling resistance, a couple against each body's rolling without a
/// reaction, does work that depends on the frame; the power losses are taken relative to
/// the outer ring ([`super::contacts::ElementResult::power_loss`]), so turning the whole
/// bearing rigidly at w = ±300 rad/s changes no contact's power loss. B1 loaded and
/// sliding as above, with the paper's law: every contact's loss within 1e-8 of the
/// largest (the forces' tolerance above, times their speeds; measured 1e-13). Teeth: the
/// same losses taken with the bodies' absolute motion differ by w times the couples' net
/// moment, measured 8 % of the largest at a race contact (bound 1 %).
#[test]
fn turning_the_whole_bearing_changes_no_contacts_power_loss() {
    let (model, y) = loaded_sliding_state(RollingResistance::Paper, true);
    let losses = |m: &BearingModel, y: &[f64], absolute: bool| {
        in_workspace(m, |s| {
            let kin = s.kinematics(0.0, y);
            let frame = if absolute {
                super::state::Kinematics::fixed()
            } else {
                kin.outer_ring
            };
            s.elements()
                .iter()
                .zip(s.evaluate_all(&kin))
                .map(|(e, r)| {
                    let [a, b] = e.bodies(s.layout.rollers);
                    r.power_loss(kin.of(a), kin.of(b), &frame)
                })
                .collect::<Vec<_>>()
        })
    };
    let reference = losses(&model, &y, false);
    let scale = reference.iter().fold(0.0, |m: f64, p| m.max(p.abs()));
    assert!(scale > 1e-3, "{scale} W");
    for w in [300.0, -300.0] {
        let other = turned(&model, w);
        let y_turned = turned_state(&other, &y, w);
        let turned_losses = losses(&other, &y_turned, false);
        let absolute = losses(&other, &y_turned, true);
        let mut largest_artefact = 0.0f64;
        for (e, ((p, q), r)) in model
            .elements()
            .iter()
            .zip(reference.iter().zip(&turned_losses).zip(&absolute))
        {
            assert!(
                (p - q).abs() < 1e-8 * scale,
                "{e:?} at w = {w}: {p} W, {q} W"
            );
            largest_artefact = largest_artefact.max((p - r).abs());
        }
        assert!(
            largest_artefact > 1e-2 * scale,
            "{largest_artefact} W of {scale} W"
        );
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// The velocities of rolling without slip (`rolling_speeds`, the equilibrium start's)
    /// at any inner and outer ring speeds of ±1000 rad/s, given to B1 with a clearance of
    /// 1 pm (each roller on the pitch circle touches both raceways, the inner ring
    /// centred; without it rounding makes them overlap by 1e-18 m at the start): the
    /// record's slide-to-roll ratios, taken from the surfaces' velocities at the contact
    /// points, are zero at both raceways. Tolerance 1e-9: the clearance's 1e-10 of a
    /// raceway radius, and rounding over rolling speeds at least a thousandth of the
    /// surfaces' speeds.
    #[test]
    fn rolling_speeds_roll_on_both_raceways(
        inner in -1000.0..1000.0f64,
        outer in -1000.0..1000.0f64,
    ) {
        prop_assume!((inner - outer).abs() > 1e-3 * inner.abs().max(outer.abs()));
        let mut p = params(&Bearing { clearance: 1e-12, ..B1 });
        p.inner_ring_speed = History::constant(inner);
        p.outer_ring_speed = History::constant(outer);
        let model = BearingModel::new(p).unwrap();
        let rec = in_workspace(&model, |m| {
            let mut y = m.initial_state().unwrap();
            let (orbit, spin) = m.rolling_speeds(inner, outer);
            let turn = Vec3::new(orbit, 0.0, 0.0);
            for i in 0..m.layout.rollers {
                let s = m.layout.roller(i);
                let v = turn.cross(&Vec3::new(y[s], y[s + 1], y[s + 2]));
                y[s + 5..s + 8].copy_from_slice(v.as_slice());
                y[s + 8] = orbit + spin;
            }
            record(&m, 0.0, &y)
        });
        prop_assert_eq!(rec.outer_ring_speed, outer);
        for (i, r) in rec.rollers.iter().enumerate() {
            prop_assert!(r.srr_inner.abs() < 1e-9, "roller {}: inner {}", i, r.srr_inner);
            prop_assert!(r.srr_outer.abs() < 1e-9, "roller {}: outer {}", i, r.srr_outer);
        }
    }
}

/// Both rings at one speed turn the bearing rigidly: the roller set orbits with them and
/// the rollers do not spin relative to the orbit; with the outer ring alone turning, the
/// roller set orbits at Ω_o(1 + γ)/2 (Harris & Kotzalas, 2007, eq. 8.23 inverted).
#[test]
fn rolling_speeds_closed_forms() {
    let model = BearingModel::new(params(&B1)).unwrap();
    in_workspace(&model, |m| {
        let (orbit, spin) = m.rolling_speeds(80.0, 80.0);
        assert!(
            (orbit - 80.0).abs() < 1e-12 && spin.abs() < 1e-12,
            "{orbit} {spin}"
        );
        let gamma = m.params.roller.radius / m.pitch_radius();
        let (orbit, _) = m.rolling_speeds(0.0, 80.0);
        assert!((orbit - 40.0 * (1.0 + gamma)).abs() < 1e-12, "{orbit}");
    });
}

/// The carrier at rest's state `y_space` (rings at Ω + w and w) seen from a carrier that
/// has turned by `angle` at speed w about the bearing's own axis: every position, velocity
/// and axis turned back about x by the angle, the carrier's w x̂ × r taken off the
/// velocities and w x̂ off the angular velocities (the inverse of [`turned_state`] at
/// angle 0); the ring's centre likewise (its tilt is locked here).
fn seen_from_carrier(model: &BearingModel, y_space: &[f64], w: f64, angle: f64) -> Vec<f64> {
    use crate::dynamics::rigid::axis_from_angles;
    let back = |v: Vec3| {
        let (s, c) = (-angle).sin_cos();
        Vec3::new(v.x, c * v.y - s * v.z, s * v.y + c * v.z)
    };
    let turn = Vec3::new(w, 0.0, 0.0);
    let mut y = y_space.to_vec();
    let ring = Vec3::new(y[0], y[1], y[2]);
    let ring_velocity = back(Vec3::new(y[3], y[4], y[5]) - turn.cross(&ring));
    y[..3].copy_from_slice(back(ring).as_slice());
    y[3..6].copy_from_slice(ring_velocity.as_slice());
    for i in 0..model.layout.rollers {
        let s = model.layout.roller(i);
        let r = Vec3::new(y[s], y[s + 1], y[s + 2]);
        let a = back(axis_from_angles(y[s + 3], y[s + 4]));
        let v = back(Vec3::new(y[s + 5], y[s + 6], y[s + 7]) - turn.cross(&r));
        let omega = back(Vec3::new(y[s + 8], y[s + 9], y[s + 10])) - turn;
        y[s..s + 3].copy_from_slice(back(r).as_slice());
        y[s + 3] = -a.z.asin();
        y[s + 4] = a.y.atan2(a.x);
        y[s + 5..s + 8].copy_from_slice(v.as_slice());
        y[s + 8..s + 11].copy_from_slice(omega.as_slice());
    }
    y
}

/// A planet carrier turning at w about the bearing's own axis (offset 0) is the same
/// bearing seen from a frame that turns with it: the rates of the rollers and of the
/// ring's centre that the carrier's model computes with its inertial terms (`TurningFrame`: Coriolis, centrifugal,
/// Euler's equations for ω + Ω) must be the time derivative of the carrier at rest's
/// motion (rings at Ω + w and w, the state turned by [`turned_state`]) seen from the
/// turning frame: d/dt [T(−w t) y_space(t)] at t = 0, by central differences of
/// y_space ± h ẏ_space turned back by ∓w h (exact to O(h²)). B1 loaded and sliding, every
/// roller tilted and skewed by up to 2 mrad and turning about its transverse axes at up
/// to 40 rad/s, so that the gyroscopic terms of the relative spin count. Drag off (the
/// oil–air mixture turns with the carrier, the carrier at rest's would not). Tolerance:
/// 1e-7 of the largest rate of each kind (velocity rates ~1e6 m/s², angular ones ~1e7
/// rad/s²), where the carrier's terms are 1e-3 to 1e-1 of them and h = 1e-7 s leaves
/// ~1e-10; the contacts agree to ~1e-9 (the test above).
#[test]
fn a_turning_carriers_rates_are_the_carrier_at_rests_motion_seen_from_it() {
    use crate::bearing::Carrier;
    use crate::dynamics::integrate::OdeSystem;
    let (model, mut y) = loaded_sliding_state(RollingResistance::Balanced, true);
    for i in 0..model.layout.rollers {
        let s = model.layout.roller(i);
        let k = (i + 1) as f64;
        y[s + 3] += 2e-3 * (k * 0.7).sin();
        y[s + 4] += 2e-3 * (k * 1.3).cos();
        y[s + 9] += 40.0 * (k * 2.1).sin();
        y[s + 10] += 40.0 * (k * 0.4).cos();
    }
    for w in [300.0, -300.0] {
        let mut p = model.params.clone();
        p.carrier = Carrier {
            speed: History::constant(w),
            offset: Vec3::zeros(),
        };
        let carried = BearingModel::new(p).unwrap();
        let rates = in_workspace(&carried, |m| {
            let mut dy = vec![0.0; y.len()];
            m.rhs(0.0, &y, &mut dy);
            dy
        });
        let space = turned(&model, w);
        let y_space = turned_state(&space, &y, w);
        let f_space = in_workspace(&space, |m| {
            let mut dy = vec![0.0; y.len()];
            m.rhs(0.0, &y_space, &mut dy);
            dy
        });
        let h = 1e-7;
        let at = |sign: f64| {
            let moved: Vec<f64> = y_space
                .iter()
                .zip(&f_space)
                .map(|(y, f)| y + sign * h * f)
                .collect();
            seen_from_carrier(&space, &moved, w, sign * w * h)
        };
        let (ahead, behind) = (at(1.0), at(-1.0));
        let expected: Vec<f64> = ahead
            .iter()
            .zip(&behind)
            .map(|(a, b)| (a - b) / (2.0 * h))
            .collect();
        let kinds = [
            (0..3, "position"),
            (3..5, "angle"),
            (5..8, "velocity"),
            (8..11, "spin"),
        ];
        for (range, kind) in kinds {
            let rows = |i: usize| {
                let s = model.layout.roller(i);
                (s + range.start)..(s + range.end)
            };
            let scale = (0..model.layout.rollers)
                .flat_map(|i| rows(i).map(|k| expected[k].abs()))
                .fold(0.0, f64::max);
            for i in 0..model.layout.rollers {
                for k in rows(i) {
                    assert!(
                        (rates[k] - expected[k]).abs() < 1e-7 * scale,
                        "w = {w}, roller {i} {kind} row {k}: {} against {} (scale {scale})",
                        rates[k],
                        expected[k]
                    );
                }
            }
        }
        // the ring's centre, 50 µm off the axis: its velocity to 1e-10 m/s (the central
        // difference's error h²w³|r|/6 is 2e-12 m/s; the frame's w × r, 6e-3 m/s) and its
        // acceleration to 5e-6 m/s² (1e-9 of the contacts' 5e3 m/s² on it; the carrier's
        // centrifugal w²|r| is 4.5 m/s²)
        assert_eq!(model.layout.ring_states(), 6);
        for k in 0..6 {
            let tolerance = if k < 3 { 1e-10 } else { 5e-6 };
            assert!(
                (rates[k] - expected[k]).abs() < tolerance,
                "w = {w}, ring row {k}: {} against {}",
                rates[k],
                expected[k]
            );
        }
    }
}
