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
