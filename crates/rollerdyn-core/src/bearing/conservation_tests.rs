//! Every contact conserves momentum and angular momentum: the wrenches it puts on its two
//! bodies sum to zero force and to zero moment about any point (Newton's third law for the
//! contact and the massless oil film in it). Checked on B1's geometry and loads with the
//! simplified lubricant of `test_b1`, loaded and rolling, with every oil film on, the
//! velocities disturbed so that every contact slides. With the balanced rolling resistance
//! each contact applies its forces at one point and its couples in opposite pairs, so the
//! check guards that bookkeeping (a force or couple added to one body only would fail it);
//! with the paper's it shows the moment the race contacts create.

use super::contacts::Wrench;
use super::state::Kinematics;
use super::test_b1::{in_workspace, params, B1};
use super::{BearingModel, RollingResistance, Workspace};
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
fn loaded_sliding_state(how: RollingResistance) -> (BearingModel, Vec<f64>) {
    let mut p = params(&B1);
    p.rolling_resistance = how;
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

/// The largest net force and net moment of any contact, and the largest force and moment
/// (about the origin) a contact puts on its roller, for scale.
fn largest_imbalance(how: RollingResistance) -> (f64, f64, f64, f64) {
    let (model, y) = loaded_sliding_state(how);
    let workspace = Workspace::single(&model);
    let model = model.system(&workspace);
    let kin = model.kinematics(0.0, &y);
    let fixed = Kinematics::fixed();
    let (mut force, mut moment, mut loads, mut moments) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    for element in model.elements() {
        let r = model.evaluate(element, &kin);
        let [a, b] = element.bodies(model.layout.rollers);
        let (ka, kb) = (kin.of(a, &fixed), kin.of(b, &fixed));
        let (f, m) = net(&r.on_a, ka, &r.on_b, kb);
        force = force.max(f.norm());
        moment = moment.max(m.norm());
        loads = loads.max(r.on_b.force.norm());
        moments = moments.max(kb.center.cross(&r.on_b.force).norm() + r.on_b.moment.norm());
    }
    (force, moment, loads, moments)
}

/// With the balanced rolling resistance every contact's net force and moment are
/// round-off (measured 0 N and 2.4e-15 N m, against contact moments about the origin of
/// up to 2.0 N m: bound 1e-12 of them). The paper's rolling resistance puts a net moment
/// into the race contacts (measured 4.1e-4 N m, 2.1e-4 of the largest; bound 1e-5).
#[test]
fn every_contact_conserves_momentum_and_angular_momentum() {
    let (force, moment, loads, moments) = largest_imbalance(RollingResistance::Balanced);
    assert!(force <= 1e-12 * loads, "{force} of {loads}");
    assert!(moment <= 1e-12 * moments, "{moment} of {moments}");
    let (_, moment, _, moments) = largest_imbalance(RollingResistance::Paper);
    assert!(moment > 1e-5 * moments, "{moment} of {moments}");
}
