//! Rigid-body kinematics and Euler's equations for axisymmetric bodies (rollers, rings).
//!
//! A roller is axisymmetric, so its spin angle never enters a force: its orientation is
//! the direction of its axis, two angles, and its angular velocity ω is a free
//! 3-vector (docs/dynamics.md, "Bodies and state"). The axis is parametrised as
//! a = R_z(θ_z)·R_y(θ_y)·e_x, singular only at θ_y = ±90°, far from any bearing pose.
//!
//! Euler's equations in the inertial frame, I·ω̇ = M − ω × (I·ω), with the inertia
//! tensor I = I_a·a aᵀ + I_t·(1 − a aᵀ) of the current axis. They equal the Resal-frame
//! form (a frame that follows the axis but not the spin) and have no singularity from the
//! spin (Gupta 1984, ch. 2; Goldstein, Classical Mechanics, sect. 5.6). They are tested
//! on a free symmetric top below (conserved energy, angular momentum, and the closed-form
//! precession rate).

use crate::geometry::primitives::Vec3;

/// Unit axis a = R_z(θ_z)·R_y(θ_y)·e_x.
#[inline]
pub fn axis_from_angles(theta_y: f64, theta_z: f64) -> Vec3 {
    let (sy, cy) = theta_y.sin_cos();
    let (sz, cz) = theta_z.sin_cos();
    Vec3::new(cy * cz, cy * sz, -sy)
}

/// Angle rates (θ̇_y, θ̇_z) for which the axis moves at ȧ = ω × a.
#[inline]
pub fn angle_rates(theta_y: f64, theta_z: f64, omega: &Vec3) -> (f64, f64) {
    let a = axis_from_angles(theta_y, theta_z);
    let a_dot = omega.cross(&a);
    let (sy, cy) = theta_y.sin_cos();
    let (sz, cz) = theta_z.sin_cos();
    // ∂a/∂θ_y = e1 (unit), ∂a/∂θ_z = cos θ_y · e2 (e2 unit); e1, e2, a orthonormal.
    let e1 = Vec3::new(-sy * cz, -sy * sz, -cy);
    let e2 = Vec3::new(-sz, cz, 0.0);
    (a_dot.dot(&e1), a_dot.dot(&e2) / cy)
}

/// Angular momentum H = I·ω of an axisymmetric body with axis a.
#[inline]
pub fn angular_momentum(axis: &Vec3, omega: &Vec3, axial: f64, transverse: f64) -> Vec3 {
    let spin = omega.dot(axis);
    transverse * omega + (axial - transverse) * spin * axis
}

/// The right-hand side of Euler's equations, M − ω × I·ω.
#[inline]
fn euler_rhs(axis: &Vec3, omega: &Vec3, moment: &Vec3, axial: f64, transverse: f64) -> Vec3 {
    moment - omega.cross(&angular_momentum(axis, omega, axial, transverse))
}

/// ω̇ = I⁻¹·(M − ω × I·ω) for an axisymmetric body (axial inertia I_a, transverse I_t).
#[inline]
pub fn angular_acceleration(
    axis: &Vec3,
    omega: &Vec3,
    moment: &Vec3,
    axial: f64,
    transverse: f64,
) -> Vec3 {
    let rhs = euler_rhs(axis, omega, moment, axial, transverse);
    let along = rhs.dot(axis);
    (rhs - along * axis) / transverse + along / axial * axis
}

/// Rate of the transverse angular velocity ω_⊥ of a body whose spin Ω about its axis is
/// prescribed, ω = Ω·a + ω_⊥: the transverse part of Euler's equations,
/// I_t·(ω̇)_⊥ = (M − ω × I·ω)_⊥ with (ω̇)_⊥ = ω̇_⊥ + Ω·ȧ. The axial part is whatever
/// moment the drive applies.
#[inline]
pub fn driven_transverse_acceleration(
    axis: &Vec3,
    omega: &Vec3,
    moment: &Vec3,
    axial: f64,
    transverse: f64,
) -> Vec3 {
    let rhs = euler_rhs(axis, omega, moment, axial, transverse);
    let spin = omega.dot(axis);
    (rhs - rhs.dot(axis) * axis) / transverse - spin * omega.cross(axis)
}

/// A reference frame that turns at Ω (with rate Ω̇) about an axis through `axis_point`,
/// all in its own coordinates: a planet carrier, in which a planet gear's bearing is
/// simulated. A body's position, velocity and angular velocity are taken relative to it.
/// Newton's and Euler's laws then gain the frame's inertial terms (Goldstein, Poole &
/// Safko, *Classical Mechanics*, 3rd ed., sect. 4.10; Greenwood, *Principles of Dynamics*,
/// 2nd ed., sect. 7.1): [`Self::inertial_acceleration`], [`Self::angular_acceleration`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TurningFrame {
    /// The frame's angular velocity Ω [rad/s].
    pub omega: Vec3,
    /// Its rate Ω̇ [rad/s²].
    pub omega_rate: Vec3,
    /// A point of its axis [m].
    pub axis_point: Vec3,
}

impl TurningFrame {
    /// A frame at rest.
    pub fn at_rest() -> Self {
        Self {
            omega: Vec3::zeros(),
            omega_rate: Vec3::zeros(),
            axis_point: Vec3::zeros(),
        }
    }

    /// The acceleration relative to the frame that its turning adds to F/m at a point ρ
    /// from its axis moving at v relative to it: the Euler, Coriolis and centrifugal
    /// terms, −Ω̇ × ρ − 2 Ω × v − Ω × (Ω × ρ).
    #[inline]
    pub fn inertial_acceleration(&self, position: &Vec3, velocity: &Vec3) -> Vec3 {
        let rho = position - self.axis_point;
        -self.omega_rate.cross(&rho)
            - 2.0 * self.omega.cross(velocity)
            - self.omega.cross(&self.omega.cross(&rho))
    }

    /// ω̇ relative to the frame of an axisymmetric body turning at ω relative to it:
    /// Euler's equations hold for the absolute ω_a = ω + Ω ([`angular_acceleration`],
    /// inertial rates), and d/dt seen from the frame is the inertial one less Ω × (·), so
    /// ω̇ = I⁻¹(M − ω_a × I·ω_a) − Ω × ω − Ω̇. The axis moves at ȧ = ω × a in the frame.
    #[inline]
    pub fn angular_acceleration(
        &self,
        axis: &Vec3,
        omega: &Vec3,
        moment: &Vec3,
        axial: f64,
        transverse: f64,
    ) -> Vec3 {
        let absolute = omega + self.omega;
        angular_acceleration(axis, &absolute, moment, axial, transverse)
            - self.omega.cross(omega)
            - self.omega_rate
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Integrates a torque-free symmetric top with classical RK4 (small steps), the
    /// axis by ȧ = ω × a. Reference: Goldstein sect. 5.6 — energy ½ω·Iω and H = Iω are
    /// conserved; the axis precesses about H at Ω_p = |H|/I_t.
    #[test]
    fn free_symmetric_top_conserves_energy_momentum_and_precesses_at_h_over_it() {
        let (ia, it) = (2.0e-9, 1.3e-9);
        let mut a = axis_from_angles(0.3, -0.2);
        let mut w = Vec3::new(40.0, -15.0, 25.0) + 300.0 * a;
        let energy = |a: &Vec3, w: &Vec3| 0.5 * w.dot(&angular_momentum(a, w, ia, it));
        let (e0, h0) = (energy(&a, &w), angular_momentum(&a, &w, ia, it));
        let f = |a: &Vec3, w: &Vec3| {
            (
                w.cross(a),
                angular_acceleration(a, w, &Vec3::zeros(), ia, it),
            )
        };
        let dt = 1e-6;
        let steps = 20_000;
        let a_start = a;
        for _ in 0..steps {
            let (k1a, k1w) = f(&a, &w);
            let (k2a, k2w) = f(&(a + 0.5 * dt * k1a), &(w + 0.5 * dt * k1w));
            let (k3a, k3w) = f(&(a + 0.5 * dt * k2a), &(w + 0.5 * dt * k2w));
            let (k4a, k4w) = f(&(a + dt * k3a), &(w + dt * k3w));
            a += dt / 6.0 * (k1a + 2.0 * k2a + 2.0 * k3a + k4a);
            w += dt / 6.0 * (k1w + 2.0 * k2w + 2.0 * k3w + k4w);
            a = a.normalize();
        }
        // RK4 at this step: relative drift ~1e-12; 1e-9 leaves room for rounding.
        assert!((energy(&a, &w) / e0 - 1.0).abs() < 1e-9);
        let h1 = angular_momentum(&a, &w, ia, it);
        assert!((h1 - h0).norm() / h0.norm() < 1e-9);
        // The axis turns about H at Ω_p = |H|/I_t: compare the angle swept.
        let hn = h0.normalize();
        let perp = |v: Vec3| (v - v.dot(&hn) * hn).normalize();
        let (p0, p1) = (perp(a_start), perp(a));
        let swept = p0.cross(&p1).dot(&hn).atan2(p0.dot(&p1));
        let expected = (h0.norm() / it * dt * steps as f64 + std::f64::consts::PI)
            .rem_euclid(2.0 * std::f64::consts::PI)
            - std::f64::consts::PI;
        assert!((swept - expected).abs() < 1e-6, "{swept} vs {expected}");
    }

    /// A vector turned about x by `angle`.
    fn turned_about_x(v: &Vec3, angle: f64) -> Vec3 {
        let (s, c) = angle.sin_cos();
        Vec3::new(v.x, c * v.y - s * v.z, s * v.y + c * v.z)
    }

    /// One classical RK4 step of y' = f(t, y) for a pair of vectors.
    fn rk4(
        f: &impl Fn(f64, &Vec3, &Vec3) -> (Vec3, Vec3),
        t: f64,
        (p, q): (Vec3, Vec3),
        dt: f64,
    ) -> (Vec3, Vec3) {
        let k1 = f(t, &p, &q);
        let k2 = f(t + 0.5 * dt, &(p + 0.5 * dt * k1.0), &(q + 0.5 * dt * k1.1));
        let k3 = f(t + 0.5 * dt, &(p + 0.5 * dt * k2.0), &(q + 0.5 * dt * k2.1));
        let k4 = f(t + dt, &(p + dt * k3.0), &(q + dt * k3.1));
        (
            p + dt / 6.0 * (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0),
            q + dt / 6.0 * (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1),
        )
    }

    /// A carrier turning at Ω(t) = Ω₀ + Ω̇t about x through P (a planet carrier spinning
    /// up): the frame of `TurningFrame` at time t, and the angle it has turned by then.
    fn carrier(t: f64) -> (TurningFrame, f64) {
        let (w0, rate) = (300.0, 2.0e4);
        let frame = TurningFrame {
            omega: Vec3::new(w0 + rate * t, 0.0, 0.0),
            omega_rate: Vec3::new(rate, 0.0, 0.0),
            axis_point: Vec3::new(0.0, 0.04, -0.01),
        };
        (frame, w0 * t + 0.5 * rate * t * t)
    }

    /// A free particle moves on a straight line in space (Newton's first law); seen from
    /// the turning, spinning-up carrier it must follow that line turned back by the
    /// carrier's angle about its axis: r' = P + R_x(−θ)(r − P). Integrated in the carrier
    /// with the Euler, Coriolis and centrifugal terms alone (RK4, 20 000 steps over 10 ms,
    /// which turns the carrier by 3.3 rad); the tolerance, 1e-9 of the 45 mm travelled,
    /// is far above RK4's error at this step (~1e-13) and far below any missing term's
    /// (the Euler term alone moves the point by ~1e-3 of the travel).
    #[test]
    fn a_free_particle_seen_from_a_turning_carrier_moves_on_the_turned_straight_line() {
        let (r0, v0) = (Vec3::new(0.001, -0.012, 0.003), Vec3::new(0.5, 2.0, -3.0));
        let (frame0, _) = carrier(0.0);
        let p = frame0.axis_point;
        let mut state = (r0, v0 - frame0.omega.cross(&(r0 - p)));
        let f = |t: f64, r: &Vec3, v: &Vec3| (*v, carrier(t).0.inertial_acceleration(r, v));
        let (dt, steps) = (5e-7, 20_000);
        for k in 0..steps {
            state = rk4(&f, k as f64 * dt, state, dt);
        }
        let t = dt * steps as f64;
        let (_, angle) = carrier(t);
        let expected = p + turned_about_x(&(r0 + v0 * t - p), -angle);
        let travel = (v0 * t).norm();
        assert!(
            (state.0 - expected).norm() < 1e-9 * travel,
            "{:?} {expected:?}",
            state.0
        );
    }

    /// A torque-free symmetric top seen from the turning, spinning-up carrier: its axis
    /// and its angular velocity relative to the carrier must be the inertial ones (the
    /// top of `free_symmetric_top_…`, integrated in space) turned back by the carrier's
    /// angle, less the carrier's Ω: ω' = R_x(−θ) ω − Ω. Both integrated with RK4 at 1e-7
    /// s over 4 ms; tolerance 1e-8 relative (RK4's error ~1e-12; dropping −Ω × ω or −Ω̇
    /// from the frame's law leaves errors of order 1).
    #[test]
    fn a_free_top_seen_from_a_turning_carrier_is_the_inertial_top_turned_back() {
        let (ia, it) = (2.0e-9, 1.3e-9);
        let a0 = axis_from_angles(0.2, 0.4);
        let w0 = Vec3::new(40.0, -15.0, 25.0) + 300.0 * a0;
        let zero = Vec3::zeros();
        let inertial =
            |_: f64, a: &Vec3, w: &Vec3| (w.cross(a), angular_acceleration(a, w, &zero, ia, it));
        let relative = |t: f64, a: &Vec3, w: &Vec3| {
            let (frame, _) = carrier(t);
            (w.cross(a), frame.angular_acceleration(a, w, &zero, ia, it))
        };
        let (frame0, _) = carrier(0.0);
        let (mut space, mut seen) = ((a0, w0), (a0, w0 - frame0.omega));
        let (dt, steps) = (1e-7, 40_000);
        for k in 0..steps {
            let t = k as f64 * dt;
            space = rk4(&inertial, t, space, dt);
            seen = rk4(&relative, t, seen, dt);
        }
        let t = dt * steps as f64;
        let (frame, angle) = carrier(t);
        let axis = turned_about_x(&space.0, -angle);
        let omega = turned_about_x(&space.1, -angle) - frame.omega;
        assert!((seen.0 - axis).norm() < 1e-8, "{:?} {axis:?}", seen.0);
        assert!(
            (seen.1 - omega).norm() < 1e-8 * space.1.norm(),
            "{:?} {omega:?}",
            seen.1
        );
    }

    #[test]
    fn angle_rates_reproduce_the_axis_motion() {
        let (ty, tz) = (0.01, -0.02);
        let w = Vec3::new(120.0, 3.0, -7.0);
        let (dy, dz) = angle_rates(ty, tz, &w);
        let h = 1e-7;
        let a_next = axis_from_angles(ty + h * dy, tz + h * dz);
        let a_dot = (a_next - axis_from_angles(ty, tz)) / h;
        let expected = w.cross(&axis_from_angles(ty, tz));
        assert!((a_dot - expected).norm() < 1e-5 * expected.norm());
    }
}
