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

use super::params::FlangeLaw;
use super::quasi_static::{flange_loads, StaticCase, StaticSolution};
use super::state::ROLLER_STATES;
use super::topology::FLANGE_NAMES;
use crate::bearing::workspace::BearingSystem;
use crate::contact::Pairing;
use crate::error::{Error, Result};
use crate::geometry::primitives::Vec3;

/// What a run with the paper's point law cannot follow, and what to use instead.
const USE_DISTRIBUTED: &str = "the paper's point contact jumps across the flat end face \
    there and a run's steps creep or collapse (docs/dynamics.md, \"Why the steps collapse at \
    2000 N\"); use surfaces.flange_law = \"distributed\" (rollerdyn run --set \
    surfaces.flange_law=distributed), or force the run (--force, force=True) to see it creep \
    or stop";

impl BearingSystem<'_> {
    /// The state of steady rolling at time `t` whose positions balance the normal forces
    /// (module doc), with the configuration's end–flange law. Where there is no
    /// equilibrium (a load larger than the bearing can carry) the error names the load
    /// level reached, the residual and the body.
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

    /// Refuses a run with the paper's point end–flange law (`surfaces.flange_law =
    /// "point"`) whose loads at time `t` (the run's end, when the loads have ramped up)
    /// press the roller ends past the tilt at which their nearly flat end face lies flat
    /// on the flange: where, in the quasi-static equilibrium of those loads, the most
    /// loaded roller end touches its flange with the end sphere (SP-CO, SP-TO). There the
    /// point contact jumps between edge, face and rim over nanometres, and a dynamic run
    /// creeps or stops after minutes (B1 at 2000 and 3000 N axially; docs/dynamics.md)
    /// instead of failing now. Where the point law finds no equilibrium at the full axial
    /// load (B1 above about 2.2 kN), the check is made at 85, 70, 55 and 40 % of it, the
    /// first that has one: the rollers tilt further with the load, so an end on its face
    /// there is on its face at the full load. It refuses only on that evidence, and only
    /// with the ring locked and aligned, where it was measured; other laws, a free or
    /// prescribed tilt, no axial load and loads at which no equilibrium is found pass.
    pub fn check_point_law(&self, t: f64) -> Result<()> {
        let p = &self.params;
        if p.flange_law != FlangeLaw::Point
            || p.inner_ring_tilt_free
            || p.inner_ring_misalignment != 0.0
        {
            return Ok(());
        }
        let full = StaticCase::at_time(p, t);
        if full.axial_load == 0.0 {
            return Ok(());
        }
        for fraction in [1.0, 0.85, 0.7, 0.55, 0.4] {
            let case = StaticCase {
                axial_load: fraction * full.axial_load,
                ..full
            };
            if let Ok(solution) = self.statics(&case, None) {
                return match end_on_its_face(&solution) {
                    Some(why) => Err(Error::invalid(
                        "surfaces.flange_law",
                        "point",
                        format!(
                            "at the loads of t = {t:.4} s (radial {} N, axial {} N) {}{why}; \
                             {USE_DISTRIBUTED}",
                            shown(full.radial_load),
                            shown(full.axial_load),
                            if fraction < 1.0 {
                                format!("and already at {} N axially ", shown(case.axial_load))
                            } else {
                                String::new()
                            },
                        ),
                    )),
                    None => Ok(()),
                };
            }
        }
        Ok(())
    }

    /// The state of steady rolling (module doc) at the positions of `solution`.
    pub(super) fn steady_state(&self, solution: &StaticSolution) -> Vec<f64> {
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

/// Where the most loaded roller end of `solution` touches its flange with the end sphere
/// ([`BearingSystem::check_point_law`]): which end, its load and pairing.
fn end_on_its_face(solution: &StaticSolution) -> Option<String> {
    let (i, k, load) = flange_loads(&solution.forces)
        .filter(|(_, _, x)| x.force > 0.0)
        .max_by(|a, b| a.2.force.total_cmp(&b.2.force))?;
    let pairing = Pairing::ALL[load.pairing?];
    (pairing.figures().0 == 1).then(|| {
        format!(
            "the most loaded roller end (roller {i} at the {} flange, {:.0} N) lies on its \
             end face ({}), past the tilt at which the face lies flat on the flange",
            FLANGE_NAMES[k],
            load.force,
            pairing.label()
        )
    })
}

/// A load in a message: as written for everyday magnitudes (5000), in exponent form
/// beyond them (1e-320, not three hundred zeros).
fn shown(x: f64) -> String {
    if x == 0.0 || (1e-3..1e9).contains(&x.abs()) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

#[cfg(test)]
mod tests {
    /// A refusal once printed a load of 1e-320 N as three hundred zeros and a digit.
    #[test]
    fn loads_in_messages_are_short_at_any_magnitude() {
        assert_eq!(super::shown(5000.0), "5000");
        assert_eq!(super::shown(0.0), "0");
        assert_eq!(super::shown(1e-320), "1e-320");
        assert_eq!(super::shown(2.5e12), "2.5e12");
    }
}
