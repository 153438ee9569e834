//! The reference solver: brute force plus local refinement, slow and sure, used only to
//! check the other detectors.
//!
//! Every pairing is a distance problem between the roller figure's *core* and the flange
//! figure's full surface: the core of a sphere is its centre (offset R), the core of a
//! torus its tube-centre circle (offset r). The closest pair (q on the core, P₂ on the flange
//! surface) is found by a grid search over all parameters (the circle angle, and azimuth and
//! generator coordinate or tube angle of the flange surface), then polished by Newton's
//! method on the stationarity conditions ∂/∂xᵢ ½|q − P₂|² = 0, written with the analytic
//! tangent vectors of the parametrisations (Jacobian by finite differences). Minimising the
//! distance itself would not do: next to the 5 m end-face sphere the distance is flat to
//! 1e-15 m over 100 nm of surface, so only the stationarity conditions fix P₂ to the
//! nanometre. Then n = (q − P₂)/|q − P₂|, δ = offset − |q − P₂| and P₁ = q − offset·n.
//! Nothing of the semi-analytical method's closed forms or of Eberly's circle distance is
//! used.

use super::{Contact, Pairing};
use crate::geometry::end_flange::{Flange, RollerEnd};
use crate::geometry::primitives::{
    any_perpendicular, meridian, ConePatch, Curvature, TorusPatch, Vec3,
};
use crate::numerics::fit::nelder_mead;
use nalgebra::{DMatrix, DVector};
use std::f64::consts::PI;

/// The flange figure of a pairing as a parametrised surface.
#[derive(Clone, Copy)]
enum FlangeSurface<'a> {
    Cone(&'a ConePatch),
    Torus(&'a TorusPatch),
}

impl FlangeSurface<'_> {
    fn frame(&self) -> (Vec3, Vec3) {
        match self {
            FlangeSurface::Cone(c) => (c.origin, c.axis),
            FlangeSurface::Torus(t) => (t.origin, t.axis),
        }
    }

    /// Surface point at azimuth α and generator coordinate g (cone) or tube angle φ (torus).
    fn point(&self, alpha: f64, w: f64, e1: &Vec3, e2: &Vec3) -> Vec3 {
        let radial = e1 * alpha.cos() + e2 * alpha.sin();
        match self {
            FlangeSurface::Cone(c) => {
                c.origin + c.axis * (c.s0 + w * c.ds) + radial * (c.rho0 + w * c.drho)
            }
            FlangeSurface::Torus(t) => {
                let (s, co) = w.sin_cos();
                t.origin
                    + t.axis * (t.minor_radius * s)
                    + radial * (t.major_radius + t.minor_radius * co)
            }
        }
    }

    /// The surface's partial derivatives ∂P/∂α and ∂P/∂w.
    fn tangents(&self, alpha: f64, w: f64, e1: &Vec3, e2: &Vec3) -> (Vec3, Vec3) {
        let radial = e1 * alpha.cos() + e2 * alpha.sin();
        let around = e2 * alpha.cos() - e1 * alpha.sin();
        match self {
            FlangeSurface::Cone(c) => (
                around * (c.rho0 + w * c.drho),
                c.axis * c.ds + radial * c.drho,
            ),
            FlangeSurface::Torus(t) => {
                let (s, co) = w.sin_cos();
                (
                    around * (t.major_radius + t.minor_radius * co),
                    t.axis * (t.minor_radius * co) - radial * (t.minor_radius * s),
                )
            }
        }
    }

    /// Search range of the second surface parameter.
    fn range(&self) -> (f64, f64) {
        match self {
            FlangeSurface::Cone(c) => {
                let margin = 2.0 * (c.g_max - c.g_min).abs() + 1e-3;
                (c.g_min - margin, c.g_max + margin)
            }
            FlangeSurface::Torus(_) => (-PI, PI),
        }
    }

    fn curvature(&self, p: &Vec3, n: &Vec3) -> Curvature {
        match self {
            FlangeSurface::Cone(c) => c.curvature(p, n),
            FlangeSurface::Torus(t) => t.curvature(p, n),
        }
    }

    fn on_patch(&self, p2: &Vec3, n: &Vec3) -> bool {
        match self {
            FlangeSurface::Cone(c) => c.contains_point(p2),
            FlangeSurface::Torus(t) => t.contains_surface_point(p2, n),
        }
    }
}

/// All six pairings by the reference solver, in [`Pairing::ALL`] order.
pub fn detect(end: &RollerEnd, flange: &Flange) -> [Contact; 6] {
    let cone = FlangeSurface::Cone(&flange.cone);
    let root = FlangeSurface::Torus(&flange.root);
    let rim = FlangeSurface::Torus(&flange.rim);
    [
        torus_against(end, cone, Pairing::TorusCone),
        torus_against(end, root, Pairing::TorusRoot),
        torus_against(end, rim, Pairing::TorusRim),
        sphere_against(end, cone, Pairing::SphereCone),
        sphere_against(end, root, Pairing::SphereRoot),
        sphere_against(end, rim, Pairing::SphereRim),
    ]
}

fn sphere_against(end: &RollerEnd, surface: FlangeSurface, pairing: Pairing) -> Contact {
    let s = &end.sphere;
    let (origin, axis) = surface.frame();
    let e1 = any_perpendicular(&axis);
    let e2 = axis.cross(&e1);
    let alpha0 = azimuth(&s.center, &origin, &axis, &e1, &e2);
    let (w_lo, w_hi) = surface.range();
    let distance = |x: &[f64]| (s.center - surface.point(x[0], x[1], &e1, &e2)).norm();
    let seed = grid_minimum(
        &distance,
        &[(alpha0 - 0.5, alpha0 + 0.5), (w_lo, w_hi)],
        200,
    );
    let stationarity = |x: &[f64]| {
        let gap = s.center - surface.point(x[0], x[1], &e1, &e2);
        let (ta, tw) = surface.tangents(x[0], x[1], &e1, &e2);
        vec![ta.dot(&gap), tw.dot(&gap)]
    };
    let x = newton(&stationarity, seed);
    let p2 = surface.point(x[0], x[1], &e1, &e2);
    finish(pairing, s.center, s.radius, p2, &surface, |_, n| {
        (s.curvature(&(-n)), s.contains_direction(&(-n)))
    })
}

fn torus_against(end: &RollerEnd, surface: FlangeSurface, pairing: Pairing) -> Contact {
    let t = &end.torus;
    let u = any_perpendicular(&t.axis);
    let v = t.axis.cross(&u);
    let core = |beta: f64| t.origin + (u * beta.cos() + v * beta.sin()) * t.major_radius;
    let core_tangent = |beta: f64| (v * beta.cos() - u * beta.sin()) * t.major_radius;
    let (origin, axis) = surface.frame();
    let e1 = any_perpendicular(&axis);
    let e2 = axis.cross(&e1);
    let alpha0 = azimuth(&t.origin, &origin, &axis, &e1, &e2);
    let (w_lo, w_hi) = surface.range();
    let distance = |x: &[f64]| (core(x[0]) - surface.point(x[1], x[2], &e1, &e2)).norm();
    let stationarity = |x: &[f64]| {
        let gap = core(x[0]) - surface.point(x[1], x[2], &e1, &e2);
        let (ta, tw) = surface.tangents(x[1], x[2], &e1, &e2);
        vec![core_tangent(x[0]).dot(&gap), ta.dot(&gap), tw.dot(&gap)]
    };
    // Two circles can have two nearly equally close pairs (near-symmetric poses): seed
    // Newton from the best grid point of each of 12 sectors of the circle angle and keep
    // the closest result.
    let sectors = 12;
    let x = (0..sectors)
        .map(|k| {
            let lo = -PI + 2.0 * PI * k as f64 / sectors as f64;
            let hi = lo + 2.0 * PI / sectors as f64;
            let seed = grid_minimum(
                &distance,
                &[(lo, hi), (alpha0 - 0.5, alpha0 + 0.5), (w_lo, w_hi)],
                24,
            );
            newton(&stationarity, seed)
        })
        .min_by(|a, b| distance(a).total_cmp(&distance(b)))
        .expect("at least one sector");
    let q = core(x[0]);
    let p2 = surface.point(x[1], x[2], &e1, &e2);
    finish(pairing, q, t.minor_radius, p2, &surface, |p1, n| {
        (t.curvature(&p1, &(-n)), t.contains_normal(&q, &(-n)))
    })
}

fn finish(
    pairing: Pairing,
    q: Vec3,
    offset: f64,
    p2: Vec3,
    surface: &FlangeSurface,
    roller: impl Fn(Vec3, Vec3) -> (Curvature, bool),
) -> Contact {
    let w = q - p2;
    let d = w.norm();
    let n = w / d;
    let p1 = q - n * offset;
    let (roller_curvature, roller_ok) = roller(p1, n);
    Contact::from_parts(
        pairing,
        p1,
        p2,
        n,
        offset - d,
        &roller_curvature,
        &surface.curvature(&p2, &n),
        roller_ok && surface.on_patch(&p2, &n),
    )
}

fn azimuth(p: &Vec3, origin: &Vec3, axis: &Vec3, e1: &Vec3, e2: &Vec3) -> f64 {
    let (_, _, e_rho) = meridian(p, origin, axis);
    e_rho.dot(e2).atan2(e_rho.dot(e1))
}

/// The best point of a regular grid of `per_axis` points per parameter over `bounds`,
/// refined by Nelder–Mead from there.
fn grid_minimum(f: &impl Fn(&[f64]) -> f64, bounds: &[(f64, f64)], per_axis: usize) -> Vec<f64> {
    let dims = bounds.len();
    let total = per_axis.pow(dims as u32);
    let mut best = (vec![0.0; dims], f64::INFINITY);
    let mut x = vec![0.0; dims];
    for k in 0..total {
        let mut index = k;
        for (d, (lo, hi)) in bounds.iter().enumerate() {
            let i = index % per_axis;
            index /= per_axis;
            x[d] = lo + (hi - lo) * (i as f64 + 0.5) / per_axis as f64;
        }
        let value = f(&x);
        if value < best.1 {
            best = (x.clone(), value);
        }
    }
    let steps: Vec<f64> = bounds
        .iter()
        .map(|(lo, hi)| (hi - lo) / per_axis as f64)
        .collect();
    nelder_mead(|x| f(x), &best.0, &steps, 0.0, 20_000).0
}

/// Newton's method on g(x) = 0 with a forward-difference Jacobian, from `x`; stops when
/// the step is below 1e-14 (parameters are angles or millimetre-scale lengths).
fn newton(g: &impl Fn(&[f64]) -> Vec<f64>, mut x: Vec<f64>) -> Vec<f64> {
    let n = x.len();
    for _ in 0..100 {
        let g0 = g(&x);
        let mut jac = DMatrix::zeros(n, n);
        for j in 0..n {
            let h = 1e-7 * x[j].abs().max(1e-3);
            let mut xh = x.clone();
            xh[j] += h;
            let gh = g(&xh);
            for i in 0..n {
                jac[(i, j)] = (gh[i] - g0[i]) / h;
            }
        }
        let Some(step) = jac.lu().solve(&DVector::from_vec(g0)) else {
            break;
        };
        for (xi, si) in x.iter_mut().zip(step.iter()) {
            *xi -= si;
        }
        if step.amax() < 1e-14 {
            break;
        }
    }
    x
}
