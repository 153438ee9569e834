//! The quasi-static start of a run (`solver.start = "equilibrium"`): the positions of the
//! inner ring and the rollers at which every body is in steady motion under the loads and
//! the speed of the start time, so that a run at full load and speed need not ramp up
//! through a loose roller set (docs/dynamics.md, "Start from equilibrium").
//!
//! The positions are the quasi-static equilibrium of [`super::quasi_static`] (the one home
//! of that solver: race slices, flange contacts, centrifugal force, the gyroscopic moment
//! and gravity; normal forces only, as in Harris & Kotzalas and ISO/TS 16281) at the loads,
//! speed and ring tilt of the start time. The velocities are those of rolling without
//! slip: the roller set orbits at the epicyclic speed ω_c = Ω·(1 − D/d_m)/2 of a fixed
//! outer ring (Harris & Kotzalas, 2007, sect. 8.2), each roller spins relative to it at
//! ω_s = −(Ω − ω_c)·r_i/r about its axis, the inner ring only spins. Friction, the
//! roller–roller contacts and the oil films are not in the equilibrium: with the speeds
//! prescribed, the traction could only be balanced by slip, which is not an unknown here,
//! and the run settles them within its first steps (tests/test_oil_and_threads.py).

use super::model::BearingModel;
use super::quasi_static::{StaticCase, StaticSolution};
use super::state::ROLLER_STATES;
use crate::error::{Error, Result};
use crate::geometry::primitives::Vec3;

impl BearingModel {
    /// The state of steady rolling at time `t` whose positions balance the normal forces
    /// (module doc). Where there is no equilibrium (a load larger than the bearing can
    /// carry) the error names the load level reached, the residual and the body.
    pub fn equilibrium_state(&self, t: f64) -> Result<Vec<f64>> {
        let case = StaticCase::at_time(&self.params, t);
        let solution = self.statics(&case, None).map_err(|e| {
            Error::invalid(
                "solver.start",
                "equilibrium",
                format!("no equilibrium found at t = {t} s: {e}"),
            )
        })?;
        Ok(self.steady_state(&solution))
    }

    /// The state of steady rolling (module doc) at the positions of `solution`.
    fn steady_state(&self, solution: &StaticSolution) -> Vec<f64> {
        let mut y = vec![0.0; self.layout.len()];
        y[..3].copy_from_slice(&solution.ring[..3]);
        if self.layout.tilt_free {
            y[6] = solution.ring[3];
            y[7] = solution.ring[4];
        }
        let p = &self.params;
        let omega = solution.case.speed;
        let r = p.roller.radius;
        let orbit = 0.5 * omega * (1.0 - r / self.pitch_radius());
        let spin = -(omega - orbit) * p.inner_raceway_radius / r;
        let orbit_vector = Vec3::new(orbit, 0.0, 0.0);
        for (i, pose) in solution.rollers.iter().enumerate() {
            let kin = pose.kinematics(self.pitch_radius());
            let a = kin.axis;
            // The angles of the axis a = R_z(θ_z)·R_y(θ_y)·e_x (dynamics/rigid.rs).
            let theta_y = (-a.z).atan2(a.x.hypot(a.y));
            let theta_z = a.y.atan2(a.x);
            let velocity = orbit_vector.cross(&kin.center);
            let omega = orbit_vector + spin * a;
            let c = kin.center;
            let state = [
                c.x, c.y, c.z, theta_y, theta_z, velocity.x, velocity.y, velocity.z, omega.x,
                omega.y, omega.z,
            ];
            let s = self.layout.roller(i);
            y[s..s + ROLLER_STATES].copy_from_slice(&state);
        }
        y
    }
}
