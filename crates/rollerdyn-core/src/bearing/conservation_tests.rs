//! Every contact conserves momentum and angular momentum: the wrenches it puts on its two
//! bodies sum to zero force and to zero moment about any point (Newton's third law for the
//! contact and the massless oil film in it). Checked on B1's geometry and loads with the
//! simplified lubricant of `test_b1`, loaded and rolling, with every oil film on, the
//! velocities disturbed so that every contact slides. With the balanced rolling resistance
//! each contact applies its forces at one point and its couples in opposite pairs, so the
//! check guards that bookkeeping (a force or couple added to one body only would fail it);
//! with the paper's it shows the moment the race contacts create.

use super::contacts::Wrench;
use super::run::record;
use super::state::Kinematics;
use super::test_b1::{in_workspace, params, B1};
use super::topology::Element;
use super::History;
use super::{BearingModel, RollingResistance, Workspace};
use crate::dynamics::integrate::OdeSystem;
use crate::dynamics::rigid::angular_momentum;
use crate::geometry::primitives::Vec3;
use crate::tribology::hydrodynamic::RigidFilm;
use crate::tribology::squeeze::SqueezeFilm;

/// The net force and the net moment about the origin of the wrenches `on_a` and `on_b`
/// (each about its body's centre).
fn net(on_a: &Wrench, a: &Kinematics, on_b: &Wrench, b: &Kinematics) -> (Vec3, Vec3) {
    let force = on_a.force + on_b.force;
    let moment =
        a.center.cross(&on_a.force) + on_a.moment + b.center.cross(&on_b.force) + on_b.moment;
    (force, moment)
}

/// B1 with the films on, `how` the rolling resistance acts, at its quasi-static
/// equilibrium for t = 0 (full load and speed), every roller's velocities disturbed.
/// Without the axial load (`axial` false) the rollers' ends stand 20 µm from the flanges
/// (the squeeze film's reach), and the roller at the top is moved 10 µm along +x, so that
/// its +x end meets the squeeze film across a gap.
pub(super) fn loaded_sliding_state(
    how: RollingResistance,
    axial: bool,
) -> (BearingModel, Vec<f64>) {
    let mut p = params(&B1);
    p.rolling_resistance = how;
    if !axial {
        p.axial_load = History::constant(0.0);
    }
    p.race_film = RigidFilm {
        enabled: true,
        cutoff: 100e-6,
        suction_limit: 1e5,
    };
    // B1's (examples/b1.toml).
    p.squeeze_film = SqueezeFilm {
        enabled: true,
        half_width: 0.5e-3,
        floor: 0.24e-6,
        cutoff: 20e-6,
    };
    let model = BearingModel::new(p).unwrap();
    let mut y = in_workspace(&model, |m| m.equilibrium_state(0.0)).unwrap();
    if !axial {
        y[model.layout.roller(model.layout.rollers / 2)] += 10e-6;
    }
    for i in 0..model.layout.rollers {
        let s = model.layout.roller(i);
        let k = (i + 1) as f64;
        // The velocity (states 5-7, m/s) and angular velocity (8-10, rad/s), disturbed by
        // 1 mm/s and 50 mrad/s amplitudes that differ from roller to roller.
        for (j, v) in y[s + 5..s + 11].iter_mut().enumerate() {
            *v += 1e-3 * ((k * 1.7 + j as f64 * 0.9).sin()) * if j < 3 { 1.0 } else { 50.0 };
        }
    }
    (model, y)
}

/// What the check found: the largest net force and net moment of any contact, the largest
/// force and moment (about the origin) a contact puts on its roller, for scale, and how
/// many contacts acted across a gap, by line contacts (the race film) and by roller ends
/// (the squeeze film), and how many slid (tangential force).
#[derive(Default)]
struct Imbalance {
    force: f64,
    moment: f64,
    loads: f64,
    moments: f64,
    lines_across_gap: usize,
    ends_across_gap: usize,
    sliding: usize,
}

fn largest_imbalance(how: RollingResistance, axial: bool) -> Imbalance {
    let (model, y) = loaded_sliding_state(how, axial);
    let workspace = Workspace::single(&model);
    let model = model.system(&workspace);
    let kin = model.kinematics(0.0, &y);
    let mut found = Imbalance::default();
    for element in model.elements() {
        let r = model.evaluate(element, &kin);
        let [a, b] = element.bodies(model.layout.rollers);
        let (ka, kb) = (kin.of(a), kin.of(b));
        let (f, m) = net(&r.on_a, ka, &r.on_b, kb);
        found.force = found.force.max(f.norm());
        found.moment = found.moment.max(m.norm());
        found.loads = found.loads.max(r.on_b.force.norm());
        found.moments = found
            .moments
            .max(kb.center.cross(&r.on_b.force).norm() + r.on_b.moment.norm());
        if r.penetration < 0.0 && r.normal != 0.0 {
            match element {
                Element::End(..) => found.ends_across_gap += 1,
                _ => found.lines_across_gap += 1,
            }
        }
        if r.tangential.norm() > 0.0 {
            found.sliding += 1;
        }
    }
    found
}

/// With the balanced rolling resistance every contact's net force and moment are
/// round-off (measured 0 N and 2.4e-15 N m, against contact moments about the origin of
/// up to 2.0 N m: bound 1e-12 of them). The paper's rolling resistance puts a net moment
/// into the race contacts (measured 4.1e-4 N m, 2.1e-4 of the largest; bound 1e-5).
#[test]
fn every_contact_conserves_momentum_and_angular_momentum() {
    for axial in [true, false] {
        let found = largest_imbalance(RollingResistance::Balanced, axial);
        assert_round_off(found.force, found.loads);
        assert_round_off(found.moment, found.moments);
        // The films were in the check: line contacts carried across gaps, contacts slid,
        // and without the axial load the top roller's end met the squeeze film across its
        // gap.
        assert!(found.lines_across_gap > 0 && found.sliding > 0);
        assert!(
            axial || found.ends_across_gap > 0,
            "{}",
            found.ends_across_gap
        );
    }
    let paper = largest_imbalance(RollingResistance::Paper, true);
    assert_round_off(paper.force, paper.loads);
    assert!(
        paper.moment > 1e-5 * paper.moments,
        "{} of {}",
        paper.moment,
        paper.moments
    );
}

/// `value` is round-off against `scale`: at most 1e-12 of it.
fn assert_round_off(value: f64, scale: f64) {
    assert!(value <= 1e-12 * scale, "{value} of {scale}");
}

/// The power balance of the whole bearing at one instant, from Newton–Euler: what the
/// drive (the ring's prescribed spin against the frictional torque T_f), gravity and the
/// external load put in, less the rate of the bodies' kinetic energy (from the model's own
/// accelerations), is what the contacts and the drag take from the motion, as a result
/// records it ([`super::run::record`]: `power_loss`). Returns (input, taken, scale):
/// scale sums the terms' magnitudes, for round-off.
///
/// In a planet carrier turning at a constant Ω the energy is the Jacobi integral's,
/// E − Ω·L in the bodies' absolute motion (Goldstein, Poole & Safko, sect. 4.10 and
/// Lagrangian mechanics' energy function of a rotating frame): per body
/// ½m v² − ½m |Ω × ρ|² + ½ω·Iω − ½Ω·IΩ, in velocities relative to the carrier, ρ from
/// its axis (the ring's from the bearing's, `Carrier`). The Coriolis force does no work,
/// the centrifugal one is the gradient of −½m|Ω × ρ|², and Euler's equations of the
/// absolute spin give d/dt(½ω·Iω − ½Ω·IΩ) = ω·M, so the same balance holds with these
/// rates: ½Ω·IΩ changes as the axis turns, by (I_a − I_t)(Ω·a)(Ω·(ω × a)).
fn power_balance(model: &BearingModel, y: &[f64]) -> (f64, f64, f64) {
    let workspace = Workspace::single(model);
    let system = model.system(&workspace);
    let t = 0.0;
    let recorded = record(&system, t, y);
    let kin = system.kinematics(t, y);
    let mut dy = vec![0.0; y.len()];
    system.rhs(t, y, &mut dy);
    let (m, g) = (&system.roller_mass, system.params.gravity);
    let frame = system.params.carrier.frame(t);
    assert_eq!(
        frame.omega_rate,
        Vec3::zeros(),
        "a carrier at constant speed"
    );
    let w = frame.omega;
    let drive = recorded.frictional_torque * recorded.ring_speed;
    let mut input = drive;
    let mut scale = recorded.power_loss.abs() + drive.abs();
    for (i, k) in kin.rollers.iter().enumerate() {
        let s = system.layout.roller(i);
        let (dv, dw) = (
            Vec3::from_column_slice(&dy[s + 5..s + 8]),
            Vec3::from_column_slice(&dy[s + 8..s + 11]),
        );
        let i_dw = angular_momentum(&k.axis, &dw, m.axial_inertia, m.transverse_inertia);
        let rho = k.center - frame.axis_point;
        let centrifugal = m.mass * w.cross(&rho).dot(&w.cross(&k.velocity));
        let axis_turn = (m.axial_inertia - m.transverse_inertia)
            * w.dot(&k.axis)
            * w.dot(&k.omega.cross(&k.axis));
        let kinetic = m.mass * k.velocity.dot(&dv) + k.omega.dot(&i_dw) - centrifugal - axis_turn;
        let gravity = m.mass * g.dot(&k.velocity);
        input += gravity - kinetic;
        scale += kinetic.abs() + gravity.abs() + centrifugal.abs() + axis_turn.abs();
    }
    let ring = &kin.inner_ring;
    let mr = system.params.inner_ring_mass;
    let centrifugal = mr * w.cross(&ring.center).dot(&w.cross(&ring.velocity));
    let kinetic = mr * ring.velocity.dot(&Vec3::from_column_slice(&dy[3..6])) - centrifugal;
    let external = (system.external_load(t) + mr * g).dot(&ring.velocity);
    input += external - kinetic;
    scale += external.abs() + kinetic.abs() + centrifugal.abs();
    (input, recorded.power_loss, scale)
}

/// Energy: what the drive, gravity and the load put into B1 less the rate of its kinetic
/// energy equals what its contacts and the drag take from the motion, to round-off
/// (measured 1.4e-16 and 1.5e-16 of the terms' magnitudes; bound 1e-12), with and without the axial
/// load, the films, the squeeze film and the drag on, every contact sliding. It guards the
/// power that a result records ([`super::run::record`]): a contact's or the drag's power
/// counted on one body only, or with the wrong sign, would fail it by the size of that
/// term. The check also has teeth: the drag and the films take power here.
#[test]
fn the_power_taken_by_contacts_and_drag_balances_the_input() {
    for axial in [true, false] {
        let (model, y) = loaded_sliding_state(RollingResistance::Paper, axial);
        let mut p = model.params.clone();
        // examples/b1.toml's mixture: 3 % of an oil of 850 kg/m³ and 16.5 mPa s in air
        p.mixture = crate::tribology::drag::Mixture::new(0.03, 850.0, 16.5e-3, 1.2, 1.8e-5);
        let model = BearingModel::new(p).unwrap();
        let (input, taken, scale) = power_balance(&model, &y);
        assert!(
            (input - taken).abs() <= 1e-12 * scale,
            "{input} vs {taken} (scale {scale})"
        );
        assert!(taken.abs() > 1e-3 * scale, "{taken} of {scale}");
    }
}

/// The same balance in a planet carrier turning at 300 rad/s, 40 mm from the sun's axis
/// (a field of 3 600 m/s²), with the Jacobi integral's rates ([`power_balance`]): the
/// carrier's inertial forces do the work of a potential on the rollers and the ring, no
/// more. Bound as above; dropping −Ω × ω from the rollers' rotational law, or taking the
/// centrifugal term a tenth short, leaves 1.2e-8 and 1.1e-7 of the terms (measured), 10⁴
/// times the bound (the Coriolis force does no work: its sign is the frame test's).
#[test]
fn in_a_turning_carrier_the_power_balances_with_the_jacobi_integral() {
    for axial in [true, false] {
        let (model, mut y) = loaded_sliding_state(RollingResistance::Paper, axial);
        let mut p = model.params.clone();
        p.mixture = crate::tribology::drag::Mixture::new(0.03, 850.0, 16.5e-3, 1.2, 1.8e-5);
        p.carrier = super::Carrier {
            speed: History::constant(300.0),
            offset: Vec3::new(0.0, -0.03, 0.026),
        };
        let model = BearingModel::new(p).unwrap();
        // the ring moving too, and every roller turning about its transverse axes, so
        // that the ring's and the rollers' carrier terms all count
        y[3..6].copy_from_slice(&[1e-3, -2e-3, 1.5e-3]);
        for i in 0..model.layout.rollers {
            let s = model.layout.roller(i);
            y[s + 9] += 30.0 * ((i as f64) * 0.7).sin();
            y[s + 10] += 30.0 * ((i as f64) * 1.9).cos();
        }
        let (input, taken, scale) = power_balance(&model, &y);
        assert!(
            (input - taken).abs() <= 1e-12 * scale,
            "{input} vs {taken} (scale {scale})"
        );
    }
}

/// A contact's power loss splits into its sliding's, its normal forces' and the rest, the
/// rolling resistance's ([`super::contacts::ElementResult::sliding_power`], `normal_power`).
/// Checked on every contact of B1 (films, squeeze film and drag on, every contact sliding):
/// at the end–flange contacts, which have no rolling resistance, the rest is round-off
/// against the contact's parts (measured up to 1.1e-15; bound 1e-12); with the paper's
/// rolling resistance, a moment against each body's rolling, it is never negative at
/// the race contacts (bound: round-off) and is taken somewhere; the sliding's part is
/// never negative.
#[test]
fn a_contacts_power_loss_splits_into_sliding_normal_and_rolling_resistance() {
    for axial in [true, false] {
        let (model, y) = loaded_sliding_state(RollingResistance::Paper, axial);
        let workspace = Workspace::single(&model);
        let system = model.system(&workspace);
        let kin = system.kinematics(0.0, &y);
        let mut rolling_total = 0.0;
        for element in system.elements() {
            let r = system.evaluate(element, &kin);
            let [a, b] = element.bodies(system.layout.rollers);
            let loss = r.power_loss(kin.of(a), kin.of(b), &kin.outer_ring);
            let rest = loss - r.sliding_power - r.normal_power;
            let scale = r.sliding_power.abs() + r.normal_power.abs() + loss.abs();
            assert!(r.sliding_power >= 0.0, "{element:?}: {}", r.sliding_power);
            match element {
                Element::End(..) => assert!(
                    rest.abs() <= 1e-12 * scale,
                    "{element:?}: {rest} of {scale}"
                ),
                _ => {
                    assert!(rest >= -1e-12 * scale, "{element:?}: {rest} of {scale}");
                    rolling_total += rest;
                }
            }
        }
        assert!(rolling_total > 0.0, "{rolling_total}");
    }
}
