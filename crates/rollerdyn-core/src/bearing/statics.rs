//! The quasi-static start of a run (`solver.start = "equilibrium"`): the positions of the
//! inner ring and the rollers at which every body is in steady motion under the loads and
//! the speed of the start time, so that a run at full load and speed need not ramp up
//! through a loose roller set (docs/dynamics.md, "Start from equilibrium").
//!
//! The velocities are those of rolling without slip: the roller set orbits at the
//! epicyclic speed ω_c = Ω·(1 − D/d_m)/2 of a fixed outer ring (Harris & Kotzalas, 2007,
//! sect. 8.2), each roller spins relative to it at ω_s = −(Ω − ω_c)·r_i/r about its axis,
//! the inner ring only spins. The unknowns are the inner ring's centre (and its tilt when
//! free) and, per roller, its radial offset from the pitch circle, its axial position and
//! its two axis angles (its azimuth stays where it is). The equations: the ring's
//! acceleration zero, each roller's acceleration the centripetal one of its orbit
//! (radially and axially) and its angular acceleration that of the steady precession
//! ω_c·x × ω_s·a about the two transverse axes. They are solved by Levenberg–Marquardt
//! (Moré 1978) with a Jacobian by forward differences of the model's right-hand side, the
//! load applied in ten steps (continuation), each step limited to 4 µm and 2e-4 rad;
//! directions the contacts leave free (an unloaded roller's axial position and skew) keep
//! their start values under a floor of the damping. The search starts with the bodies in
//! the contacts the loads close, radially and axially (a roller floats in its clearance
//! until it touches, and a centred start gives no gradient to follow).
//!
//! The equilibrium is that of the normal forces, without friction, as in the classical
//! quasi-static analysis (Harris & Kotzalas; ISO/TS 16281): with the speeds prescribed,
//! the traction and its moments could only be balanced by slip, which is not an unknown
//! here. The run then settles the friction within its first steps. Checked against the
//! steady state of a dynamic run (tests/test_oil_and_threads.py).

use super::model::BearingModel;
use super::params::{BearingParams, ModelOptions};
use super::state::ROLLER_STATES;
use crate::dynamics::integrate::OdeSystem;
use crate::dynamics::rigid::axis_from_angles;
use crate::error::{Error, Result};
use crate::geometry::primitives::Vec3;
use nalgebra::{DMatrix, DVector};

/// Steps of the load continuation.
const LOAD_STEPS: usize = 10;
/// Iterations after which the search gives up.
const MAX_ITERATIONS: usize = 300;
/// The largest move of a position in one iteration [m] (a fifth of B1's axial play).
const MAX_MOVE: f64 = 4e-6;
/// The largest turn of an angle in one iteration [rad].
const MAX_TURN: f64 = 2e-4;

/// The steady motion whose positions are sought.
struct Steady {
    t: f64,
    /// Roller-set (orbital) speed ω_c [rad/s].
    orbit: f64,
    /// Roller spin relative to the roller set ω_s [rad/s].
    spin: f64,
    /// Azimuths of the rollers [rad] (from +y towards +z).
    azimuths: Vec<f64>,
    /// The share of the external load applied (continuation from the unloaded bearing).
    load_factor: f64,
}

impl BearingModel {
    /// The state of steady rolling at time `t` whose positions balance every force
    /// (module doc). Errors name the residual and the body where no equilibrium is found
    /// (a load larger than the bearing can carry).
    pub fn equilibrium_state(&self, t: f64) -> Result<Vec<f64>> {
        if self.params.options.friction {
            let frictionless = BearingModel::new(BearingParams {
                options: ModelOptions {
                    friction: false,
                    ..self.params.options.clone()
                },
                ..self.params.clone()
            })?;
            return frictionless.equilibrium_state(t);
        }
        let rest = self.initial_state()?;
        let p = &self.params;
        let omega = p.inner_ring_speed.at(t).0;
        let r = p.roller.radius;
        let pitch = self.pitch_radius();
        let orbit = 0.5 * omega * (1.0 - r / pitch);
        let mut steady = Steady {
            t,
            orbit,
            spin: -(omega - orbit) * p.inner_raceway_radius / r,
            azimuths: (0..self.layout.rollers)
                .map(|i| {
                    let s = self.layout.roller(i);
                    rest[s + 2].atan2(rest[s + 1])
                })
                .collect(),
            load_factor: 0.0,
        };
        let tolerance = self.force_tolerance(t);
        let mut u = self.contact_guess(t, &steady.azimuths);
        // The load in steps (continuation): each equilibrium starts the next search.
        for k in 1..=LOAD_STEPS {
            steady.load_factor = k as f64 / LOAD_STEPS as f64;
            let last = k == LOAD_STEPS;
            let (found, res) = self.levenberg_marquardt(
                &steady,
                u,
                if last { tolerance } else { 1e3 * tolerance },
            );
            u = found;
            if last || res.amax() >= 1e3 * tolerance {
                return self.verdict(&steady, &u, &res, tolerance);
            }
        }
        unreachable!("the last load step returns")
    }

    /// The start of the search, with the bodies in the contacts that the loads close (a
    /// roller floats in its clearance and between the flanges until it touches, so a
    /// centred start gives the search no gradient to follow). Across the axis: the ring
    /// moved along its radial load and weight by the radial clearance c (both gaps of a
    /// centred roller) and 1 µm into contact, each roller it faces moved outwards by
    /// c/2·cos(angle to the load). Along an axial load: the rollers moved by the outer
    /// ring's axial play towards its loaded flange, the ring by both plays and 3 µm more
    /// (the opening angle widens the gap away from the raceway).
    fn contact_guess(&self, t: f64, azimuths: &[f64]) -> DVector<f64> {
        let mut u = DVector::zeros(self.unknowns());
        let p = &self.params;
        let ring = self.unknowns() - 4 * self.layout.rollers;
        let load = self.external_load(t) + p.inner_ring_mass * p.gravity;
        let across = Vec3::new(0.0, load.y, load.z);
        if across.norm() > 0.0 {
            let down = across.normalize();
            let clearance = p.outer_raceway_radius - p.inner_raceway_radius - 2.0 * p.roller.radius;
            u[1] = (clearance + 1e-6) * down.y;
            u[2] = (clearance + 1e-6) * down.z;
            for (i, psi) in azimuths.iter().enumerate() {
                let facing = Vec3::new(0.0, psi.cos(), psi.sin()).dot(&down);
                if facing > 0.0 {
                    u[ring + 4 * i] = 0.5 * clearance * facing;
                }
            }
        }
        let axial = load.x;
        if axial != 0.0 {
            let side = axial.signum();
            u[0] = side * (p.inner_axial_play + p.outer_axial_play + 3e-6);
            for i in 0..self.layout.rollers {
                u[ring + 4 * i + 1] = side * p.outer_axial_play;
            }
        }
        u
    }

    /// The state of the solution, or the error naming the largest residual.
    fn verdict(
        &self,
        steady: &Steady,
        u: &DVector<f64>,
        res: &DVector<f64>,
        tolerance: f64,
    ) -> Result<Vec<f64>> {
        if res.amax() < tolerance {
            return Ok(self.state_of(steady, u));
        }
        let worst = res.iamax();
        Err(Error::invalid(
            "solver.start",
            "equilibrium",
            format!(
                "no equilibrium found at t = {} s with {:.0} % of the load: residual force {:.3e} N on {} (tolerance \
                 {tolerance:.1e} N); the loads may exceed what the bearing can carry",
                steady.t,
                100.0 * steady.load_factor,
                res[worst],
                self.unknown_name(worst)
            ),
        ))
    }

    /// Levenberg–Marquardt from `u` until the largest residual is below `tolerance` or
    /// no step improves: the unknowns reached and their residual.
    fn levenberg_marquardt(
        &self,
        steady: &Steady,
        mut u: DVector<f64>,
        tolerance: f64,
    ) -> (DVector<f64>, DVector<f64>) {
        let n = self.unknowns();
        let mut res = self.residual(steady, &u);
        let mut lambda = 1e-3;
        for _ in 0..MAX_ITERATIONS {
            if res.amax() < tolerance {
                break;
            }
            let jac = self.residual_jacobian(steady, &u, &res);
            let jtj = jac.transpose() * &jac;
            let jtr = jac.transpose() * &res;
            let floor = self.damping_floor(&jtj);
            let mut improved = false;
            for _ in 0..30 {
                let mut a = jtj.clone();
                for k in 0..n {
                    a[(k, k)] += lambda * jtj[(k, k)].max(floor[k]);
                }
                let Some(step) = a.lu().solve(&(-&jtr)) else {
                    lambda *= 10.0;
                    continue;
                };
                let step = self.limited(step);
                let trial = &u + &step;
                let trial_res = self.residual(steady, &trial);
                if trial_res.iter().all(|v| v.is_finite()) && trial_res.norm() < res.norm() {
                    (u, res) = (trial, trial_res);
                    lambda = (lambda / 3.0).max(1e-12);
                    improved = true;
                    break;
                }
                lambda *= 4.0;
            }
            if !improved {
                break;
            }
        }
        (u, res)
    }

    /// The least damping per unknown. Marquardt's damping scales with diag(JᵀJ), which is
    /// about zero along the directions no contact holds (an unloaded roller's axial
    /// position): there it is floored at 1e-6 of the stiffest direction (angles measured as
    /// arcs of the roller radius), so that those directions move little instead of freely.
    fn damping_floor(&self, jtj: &DMatrix<f64>) -> Vec<f64> {
        let n = self.unknowns();
        let arc = |k: usize| {
            if self.is_angle_unknown(k) {
                self.params.roller.radius
            } else {
                1.0
            }
        };
        let stiffest = (0..n)
            .map(|k| jtj[(k, k)] / (arc(k) * arc(k)))
            .fold(0.0, f64::max);
        (0..n).map(|k| 1e-6 * stiffest * arc(k) * arc(k)).collect()
    }

    /// `step` scaled down (direction kept) so that no position moves by more than
    /// [`MAX_MOVE`] and no angle by more than [`MAX_TURN`]: far from the solution (no
    /// contact yet) the film alone determines some directions only weakly, and a full step
    /// along them would leave the region where the linearisation holds.
    fn limited(&self, step: DVector<f64>) -> DVector<f64> {
        let largest = (0..step.len()).fold(0.0f64, |m, k| {
            let limit = if self.is_angle_unknown(k) {
                MAX_TURN
            } else {
                MAX_MOVE
            };
            m.max(step[k].abs() / limit)
        });
        if largest > 1.0 {
            step / largest
        } else {
            step
        }
    }

    /// Whether unknown k is an angle (ring tilt, roller tilt and skew).
    fn is_angle_unknown(&self, k: usize) -> bool {
        let ring = self.unknowns() - 4 * self.layout.rollers;
        (3..ring).contains(&k) || (k >= ring && (k - ring) % 4 >= 2)
    }

    /// Number of unknowns: the ring's centre (and tilt), four per roller.
    fn unknowns(&self) -> usize {
        3 + if self.layout.tilt_free { 2 } else { 0 } + 4 * self.layout.rollers
    }

    /// Which body and direction unknown k belongs to.
    fn unknown_name(&self, k: usize) -> String {
        let ring = self.unknowns() - 4 * self.layout.rollers;
        if k < ring {
            return format!(
                "the inner ring ({})",
                ["x", "y", "z", "tilt y", "tilt z"][k]
            );
        }
        let (i, j) = ((k - ring) / 4, (k - ring) % 4);
        let what = ["radially", "axially", "tilt", "skew"][j];
        format!("roller {i} ({what})")
    }

    /// The largest unbalanced force left on any body [N]: 1e-6 of the external load, but
    /// not below twice a roller's weight (or 1 mN without gravity). The directions that only
    /// the oil films hold converge slowly (an unloaded roller's tilt; at standstill, where
    /// the film carries little, its fall onto a race), and such an imbalance settles within
    /// the first microseconds of the run.
    fn force_tolerance(&self, t: f64) -> f64 {
        let weight = self.roller_mass.mass * self.params.gravity.norm();
        (1e-6 * self.external_load(t).norm())
            .max(2.0 * weight)
            .max(1e-3)
    }

    /// The state of `steady` motion with the unknowns `u`.
    fn state_of(&self, steady: &Steady, u: &DVector<f64>) -> Vec<f64> {
        let mut y = vec![0.0; self.layout.len()];
        let ring = self.unknowns() - 4 * self.layout.rollers;
        y[..3].copy_from_slice(&u.as_slice()[..3]);
        if self.layout.tilt_free {
            y[6] = u[3];
            y[7] = u[4];
        }
        let pitch = self.pitch_radius();
        for (i, psi) in steady.azimuths.iter().enumerate() {
            let s = self.layout.roller(i);
            let q = &u.as_slice()[ring + 4 * i..ring + 4 * i + 4];
            let center = Vec3::new(q[1], (pitch + q[0]) * psi.cos(), (pitch + q[0]) * psi.sin());
            let axis = axis_from_angles(q[2], q[3]);
            let velocity = Vec3::new(steady.orbit, 0.0, 0.0).cross(&center);
            let omega = Vec3::new(steady.orbit, 0.0, 0.0) + steady.spin * axis;
            let state = [
                center.x, center.y, center.z, q[2], q[3], velocity.x, velocity.y, velocity.z,
                omega.x, omega.y, omega.z,
            ];
            y[s..s + ROLLER_STATES].copy_from_slice(&state);
        }
        y
    }

    /// The unbalanced forces [N] (moments over the roller radius) of the unknowns `u`.
    fn residual(&self, steady: &Steady, u: &DVector<f64>) -> DVector<f64> {
        let y = self.state_of(steady, u);
        let mut dy = vec![0.0; y.len()];
        self.rhs(steady.t, &y, &mut dy);
        let mut out = DVector::zeros(self.unknowns());
        let p = &self.params;
        let unapplied = (1.0 - steady.load_factor) * self.external_load(steady.t);
        for k in 0..3 {
            out[k] = p.inner_ring_mass * dy[3 + k] - unapplied[k];
        }
        if self.layout.tilt_free {
            out[3] = p.inner_ring_transverse_inertia * dy[9] / p.roller.radius;
            out[4] = p.inner_ring_transverse_inertia * dy[10] / p.roller.radius;
        }
        let ring = self.unknowns() - 4 * self.layout.rollers;
        let m = &self.roller_mass;
        let r = p.roller.radius;
        for (i, psi) in steady.azimuths.iter().enumerate() {
            let s = self.layout.roller(i);
            let radial = Vec3::new(0.0, psi.cos(), psi.sin());
            let tangential = Vec3::x().cross(&radial);
            let center = Vec3::new(y[s], y[s + 1], y[s + 2]);
            let axis = axis_from_angles(y[s + 3], y[s + 4]);
            let orbit = Vec3::new(steady.orbit, 0.0, 0.0);
            let centripetal = orbit.cross(&orbit.cross(&center));
            let acc = Vec3::new(dy[s + 5], dy[s + 6], dy[s + 7]) - centripetal;
            let precession = orbit.cross(&(steady.spin * axis));
            let alpha = Vec3::new(dy[s + 8], dy[s + 9], dy[s + 10]) - precession;
            out[ring + 4 * i] = m.mass * acc.dot(&radial);
            out[ring + 4 * i + 1] = m.mass * acc.x;
            out[ring + 4 * i + 2] = m.transverse_inertia * alpha.dot(&tangential) / r;
            out[ring + 4 * i + 3] = m.transverse_inertia * alpha.dot(&radial) / r;
        }
        out
    }

    /// ∂(residual)/∂u by forward differences (steps of 1e-10 m and 1e-7 rad).
    fn residual_jacobian(
        &self,
        steady: &Steady,
        u: &DVector<f64>,
        at: &DVector<f64>,
    ) -> DMatrix<f64> {
        let n = self.unknowns();
        let mut jac = DMatrix::zeros(n, n);
        let mut v = u.clone();
        for k in 0..n {
            let h = if self.is_angle_unknown(k) {
                1e-7
            } else {
                1e-10
            };
            v[k] = u[k] + h;
            let col = (self.residual(steady, &v) - at) / h;
            jac.set_column(k, &col);
            v[k] = u[k];
        }
        jac
    }
}
