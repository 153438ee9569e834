//! Koch's gradient method (O. Koch, *Dreidimensionale Simulation von kombiniert belasteten
//! Radialzylinderrollenlagern*, PhD thesis, Bochum 2008; paper sect. 2, fig. 2).
//!
//! With implicit functions F₁ (roller figure) and F₂ (flange figure), the contact points
//! satisfy three conditions, eight scalar equations in x = (P₁, P₂, λ₁, λ₂):
//!
//! 1. F₁(P₁) = 0, F₂(P₂) = 0 (on the surfaces);
//! 2. ∇F₁(P₁) + λ₁∇F₂(P₂) = 0 (gradients collinear);
//! 3. P₂ − P₁ − λ₂∇F₁(P₁) = 0 (connecting vector collinear with the gradient).
//!
//! Condition 3 is written with the gradient on the right so that touching (P₁ = P₂) is
//! regular (λ₂ = 0). The implicit functions are signed distances (|∇F| = 1 on the
//! surface), which keeps the 8 × 8 Newton system well scaled for the 5 m end-face sphere
//! and the 0.2 mm flange tori alike. Newton's method with the analytic Jacobian (the
//! Hessians of F) is warm-started from the previous solution.
//!
//! **Cold start** (documented guess, paper sect. 5.4): P₂⁰ = foot on the flange figure of
//! the roller figure's centre (sphere centre, or torus centre); P₁⁰ = foot on the roller
//! figure of P₂⁰; P₂⁰ ← foot on the flange figure of P₁⁰; λ₁⁰ = 1 (opposite unit normals);
//! λ₂⁰ = (P₂⁰ − P₁⁰)·∇F₁(P₁⁰).
//!
//! **Failures** are reported, not hidden: no convergence within the iteration limit, and
//! convergence to a wrong stationary point — a solution whose outward normals are not
//! opposite (λ₁ ≤ 0, e.g. the far side of a sphere, paper fig. 2).

use super::{Contact, Pairing};
use crate::geometry::end_flange::{Flange, RollerEnd};
use crate::geometry::primitives::{meridian, ConePatch, Curvature, SpherePatch, TorusPatch, Vec3};
use nalgebra::{Matrix3, SMatrix, SVector};

type Mat8 = SMatrix<f64, 8, 8>;
type Vec8 = SVector<f64, 8>;

/// Newton's iteration limit.
pub const MAX_ITERATIONS: usize = 50;

/// A figure as an implicit surface F(p) = signed distance (positive outside).
#[derive(Debug, Clone, Copy)]
pub enum Figure<'a> {
    /// Sphere: F = |p − c| − R.
    Sphere(&'a SpherePatch),
    /// Cone: F = (p's meridian point − (s₀, ρ₀))·n_meridian.
    Cone(&'a ConePatch),
    /// Torus: F = |(s, ρ − R)| − r in the meridian plane.
    Torus(&'a TorusPatch),
}

impl Figure<'_> {
    /// F, ∇F and the Hessian of F at p.
    fn evaluate(&self, p: &Vec3) -> (f64, Vec3, Matrix3<f64>) {
        match self {
            Figure::Sphere(s) => {
                let w = p - s.center;
                let d = w.norm();
                let g = w / d;
                (
                    d - s.radius,
                    g,
                    (Matrix3::identity() - g * g.transpose()) / d,
                )
            }
            Figure::Cone(c) => {
                let (sa, rho, e_rho) = meridian(p, &c.origin, &c.axis);
                let (ns, nr) = c.meridian_normal();
                let f = (sa - c.s0) * ns + (rho - c.rho0) * nr;
                let g = c.axis * ns + e_rho * nr;
                let circ =
                    Matrix3::identity() - c.axis * c.axis.transpose() - e_rho * e_rho.transpose();
                (f, g, circ * (nr / rho))
            }
            Figure::Torus(t) => {
                let (sa, rho, e_rho) = meridian(p, &t.origin, &t.axis);
                let w = e_rho * (rho - t.major_radius) + t.axis * sa;
                let d = w.norm();
                let g = w / d;
                let circ =
                    Matrix3::identity() - t.axis * t.axis.transpose() - e_rho * e_rho.transpose();
                let dw = e_rho * e_rho.transpose()
                    + t.axis * t.axis.transpose()
                    + circ * ((rho - t.major_radius) / rho);
                (
                    d - t.minor_radius,
                    g,
                    (Matrix3::identity() - g * g.transpose()) * dw / d,
                )
            }
        }
    }

    /// The foot of p on the figure (for the cold start).
    fn foot(&self, p: &Vec3) -> Vec3 {
        let (f, g, _) = self.evaluate(p);
        p - g * f
    }

    /// A representative interior point (cold start).
    fn center(&self) -> Vec3 {
        match self {
            Figure::Sphere(s) => s.center,
            Figure::Cone(c) => c.origin + c.axis * c.s0,
            Figure::Torus(t) => t.origin,
        }
    }

    fn curvature(&self, p: &Vec3, n: &Vec3) -> Curvature {
        match self {
            Figure::Sphere(s) => s.curvature(n),
            Figure::Cone(c) => c.curvature(p, n),
            Figure::Torus(t) => t.curvature(p, n),
        }
    }

    fn on_patch(&self, p: &Vec3, n: &Vec3) -> bool {
        match self {
            Figure::Sphere(s) => s.contains_direction(n),
            Figure::Cone(c) => c.contains_point(p),
            Figure::Torus(t) => t.contains_surface_point(p, n),
        }
    }
}

/// The unknowns of the 8 × 8 system, kept between calls for the warm start.
pub type Unknowns = [f64; 8];

/// The outcome of one gradient-method solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GradientOutcome {
    /// The contact (meaningful only if `converged`).
    pub contact: Contact,
    /// Newton iterations used.
    pub iterations: usize,
    /// True if Newton converged within [`MAX_ITERATIONS`].
    pub converged: bool,
    /// True if the converged point has opposite outward normals (λ₁ > 0); false marks a
    /// wrong stationary point.
    pub opposite_normals: bool,
    /// The solution, for the next warm start.
    pub unknowns: Unknowns,
}

/// The cold-start guess of the module documentation.
pub fn cold_start(roller: &Figure, flange: &Figure) -> Unknowns {
    let p2 = flange.foot(&roller.center());
    let p1 = roller.foot(&p2);
    let p2 = flange.foot(&p1);
    let (_, g1, _) = roller.evaluate(&p1);
    let l2 = (p2 - p1).dot(&g1);
    [p1.x, p1.y, p1.z, p2.x, p2.y, p2.z, 1.0, l2]
}

/// Solves the eight equations by Newton's method from `start`.
pub fn solve(
    roller: &Figure,
    flange: &Figure,
    pairing: Pairing,
    start: Unknowns,
) -> GradientOutcome {
    let mut x = Vec8::from_column_slice(&start);
    let mut iterations = 0;
    let mut converged = false;
    while iterations < MAX_ITERATIONS {
        let (residual, jacobian) = system(roller, flange, &x);
        if !residual.iter().all(|r| r.is_finite()) {
            break;
        }
        let step = match jacobian.lu().solve(&residual) {
            Some(s) if s.iter().all(|v| v.is_finite()) => s,
            _ => break, // singular system: keep the last finite iterate
        };
        x -= step;
        iterations += 1;
        let position_step = step.fixed_rows::<6>(0).amax();
        if position_step < 1e-15 && residual.fixed_rows::<2>(0).amax() < 1e-13 {
            converged = true;
            break;
        }
    }
    // A start that is not finite (the cold start's feet on a degenerate flange that
    // reaches the ring axis, found by fuzzing): a defined, invalid answer at the roller's
    // centre instead of NaN.
    let x_defined = x.iter().all(|v| v.is_finite());
    if !x_defined {
        let c = roller.center();
        x = Vec8::from_column_slice(&[c.x, c.y, c.z, c.x, c.y, c.z, 0.0, 0.0]);
        converged = false;
    }
    let p1 = Vec3::new(x[0], x[1], x[2]);
    let p2 = Vec3::new(x[3], x[4], x[5]);
    let (_, g2, _) = flange.evaluate(&p2);
    // On a torus' tube-centre circle (a tube radius at round-off level) the gradient
    // vanishes and the normal is undefined: fall back to a defined direction and report
    // the pairing invalid rather than NaN (found by fuzzing, docs/robustness.md).
    let g2_defined = g2.norm() > 0.0 && g2.iter().all(|v| v.is_finite());
    let n = if g2_defined {
        g2.normalize()
    } else {
        (p1 - p2)
            .try_normalize(0.0)
            .filter(|d| d.iter().all(|v| v.is_finite()))
            .unwrap_or_else(Vec3::x)
    };
    let opposite_normals = x[6] > 0.0;
    let contact = Contact::from_parts(
        pairing,
        p1,
        p2,
        n,
        (p2 - p1).dot(&n),
        &roller.curvature(&p1, &(-n)),
        &flange.curvature(&p2, &n),
        x_defined
            && g2_defined
            && converged
            && opposite_normals
            && roller.on_patch(&p1, &(-n))
            && flange.on_patch(&p2, &n),
    );
    GradientOutcome {
        contact,
        iterations,
        converged,
        opposite_normals,
        unknowns: x.into(),
    }
}

/// Residual G(x) and Jacobian of the eight equations.
fn system(roller: &Figure, flange: &Figure, x: &Vec8) -> (Vec8, Mat8) {
    let p1 = Vec3::new(x[0], x[1], x[2]);
    let p2 = Vec3::new(x[3], x[4], x[5]);
    let (l1, l2) = (x[6], x[7]);
    let (f1, g1, h1) = roller.evaluate(&p1);
    let (f2, g2, h2) = flange.evaluate(&p2);
    let mut r = Vec8::zeros();
    r[0] = f1;
    r[1] = f2;
    r.fixed_rows_mut::<3>(2).copy_from(&(g1 + g2 * l1));
    r.fixed_rows_mut::<3>(5).copy_from(&(p2 - p1 - g1 * l2));
    let mut j = Mat8::zeros();
    j.fixed_view_mut::<1, 3>(0, 0).copy_from(&g1.transpose());
    j.fixed_view_mut::<1, 3>(1, 3).copy_from(&g2.transpose());
    j.fixed_view_mut::<3, 3>(2, 0).copy_from(&h1);
    j.fixed_view_mut::<3, 3>(2, 3).copy_from(&(h2 * l1));
    j.fixed_view_mut::<3, 1>(2, 6).copy_from(&g2);
    j.fixed_view_mut::<3, 3>(5, 0)
        .copy_from(&(-Matrix3::identity() - h1 * l2));
    j.fixed_view_mut::<3, 3>(5, 3)
        .copy_from(&Matrix3::identity());
    j.fixed_view_mut::<3, 1>(5, 7).copy_from(&(-g1));
    (r, j)
}

/// The six pairings of a roller end against a flange, each warm-started from `previous`
/// (or cold-started where it is None); in [`Pairing::ALL`] order.
pub fn detect(
    end: &RollerEnd,
    flange: &Flange,
    previous: &[Option<Unknowns>; 6],
) -> [GradientOutcome; 6] {
    std::array::from_fn(|k| detect_pairing(end, flange, k, previous[k]))
}

/// Pairing `k` ([`Pairing::ALL`] order) of a roller end against a flange, warm-started from
/// `previous` (or cold-started where it is None): one entry of [`detect`].
pub fn detect_pairing(
    end: &RollerEnd,
    flange: &Flange,
    k: usize,
    previous: Option<Unknowns>,
) -> GradientOutcome {
    let r = [Figure::Torus(&end.torus), Figure::Sphere(&end.sphere)][k / 3];
    let f = [
        Figure::Cone(&flange.cone),
        Figure::Torus(&flange.root),
        Figure::Torus(&flange.rim),
    ][k % 3];
    let start = previous.unwrap_or_else(|| cold_start(&r, &f));
    solve(&r, &f, Pairing::ALL[k], start)
}
