//! The semi-analytical roller end–flange contact detection of Wolf, Sanner & Fatemi
//! (Proc. IMechE J, 2020), as described in the reference paper, sect. 2:
//!
//! * sphere–cone and sphere–torus in closed form, in the plane through the sphere's centre
//!   and the other figure's axis (the meridian plane, where the contact points lie);
//! * torus–cone by the one-dimensional extremum of the penetration over the torus angle
//!   (Gupta 1984), bracketed on the half circle around the plane-model estimate so that it
//!   cannot settle on the wrong extremum;
//! * torus–torus by the minimum distance of the two tube-centre circles (the certified
//!   fast path of [`crate::geometry::circle_fast`], falling back to Eberly's solver,
//!   [`crate::geometry::circle`]) followed by sphere–sphere with the two tube radii.
//!
//! Every function returns a [`Contact`] whether or not the points lie on their patches;
//! [`Contact::valid`] says whether the pairing counts.

use super::{Contact, Pairing};
use crate::geometry::circle::{Circle3, ClosestPairs};
use crate::geometry::circle_fast::{circle_circle_distance_fast, converged, rotate};
use crate::geometry::end_flange::{Flange, RollerEnd};
use crate::geometry::primitives::{any_perpendicular, ConePatch, SpherePatch, TorusPatch, Vec3};
use std::f64::consts::FRAC_PI_2;

/// All six pairings of a roller end against a flange, in [`Pairing::ALL`] order.
pub fn detect(end: &RollerEnd, flange: &Flange) -> [Contact; 6] {
    [
        torus_cone(&end.torus, &flange.cone),
        torus_torus(&end.torus, &flange.root, Pairing::TorusRoot),
        torus_torus(&end.torus, &flange.rim, Pairing::TorusRim),
        sphere_cone(&end.sphere, &flange.cone),
        sphere_torus(&end.sphere, &flange.root, Pairing::SphereRoot),
        sphere_torus(&end.sphere, &flange.rim, Pairing::SphereRim),
    ]
}

/// The composite of one roller end against one flange: the deepest valid pairing
/// ([`super::deepest`] of [`detect`]), evaluated cheaply first.
///
/// The roller end (edge torus tangent to the end sphere) and the flange (cone face between
/// tangent convex tori) are each a convex, tangent-continuous surface, so their extremal
/// pair of points (closest, or deepest in overlap) is unique and lies on one pairing of
/// patches; only at a border between tangent patches do two pairings find it, with equal
/// penetration. So once a pairing is valid, no other pairing can be valid with a different
/// result, and the expensive torus–torus pairings (Eberly's polynomial) are only solved
/// when none of the four others is valid. The property tests check that this returns
/// exactly what [`super::deepest`] of all six returns.
pub fn composite(end: &RollerEnd, flange: &Flange) -> Option<Contact> {
    let cheap = [
        sphere_cone(&end.sphere, &flange.cone),
        sphere_torus(&end.sphere, &flange.root, Pairing::SphereRoot),
        sphere_torus(&end.sphere, &flange.rim, Pairing::SphereRim),
        torus_cone(&end.torus, &flange.cone),
    ];
    if let Some(best) = super::deepest(&cheap) {
        return Some(best);
    }
    super::deepest(&[
        torus_torus(&end.torus, &flange.root, Pairing::TorusRoot),
        torus_torus(&end.torus, &flange.rim, Pairing::TorusRim),
    ])
}

/// Roller end sphere against the flange face: the foot of the sphere's centre on the cone.
pub fn sphere_cone(sphere: &SpherePatch, cone: &ConePatch) -> Contact {
    let foot = cone.foot(&sphere.center);
    let n = foot.normal;
    let p1 = sphere.center - n * sphere.radius;
    Contact::assemble(
        Pairing::SphereCone,
        p1,
        foot.point,
        n,
        sphere.radius - foot.distance,
        || (sphere.curvature(&(-n)), cone.curvature(&foot.point, &n)),
        foot.on_patch && sphere.contains_direction(&(-n)),
    )
}

/// Roller end sphere against a flange torus: the tube centre in the sphere centre's
/// meridian plane, then sphere–sphere.
pub fn sphere_torus(sphere: &SpherePatch, torus: &TorusPatch, pairing: Pairing) -> Contact {
    let (q, _) = torus.tube_center_towards(&sphere.center);
    sphere_sphere(
        pairing,
        (sphere.center, sphere.radius),
        (q, torus.minor_radius),
        |_, n| sphere.curvature(&(-n)),
        |p2, n| torus.curvature(&p2, &n),
        |n| sphere.contains_direction(&(-n)),
        |n| torus.contains_normal(&q, &n),
    )
}

/// Roller edge torus against a flange torus: the closest points of the two tube-centre
/// circles ([`circle_circle_distance_fast`]: a certified 1-D search, Eberly's solver where
/// the certificate fails, with the same result), then sphere–sphere with the tube radii.
/// Where the circles have a continuum of closest pairs (coaxial), the representative pair
/// Eberly's solver returns is used (every pair gives the same penetration).
pub fn torus_torus(roller: &TorusPatch, flange: &TorusPatch, pairing: Pairing) -> Contact {
    let c1 = Circle3 {
        center: roller.origin,
        normal: roller.axis,
        radius: roller.major_radius,
    };
    let c2 = Circle3 {
        center: flange.origin,
        normal: flange.axis,
        radius: flange.major_radius,
    };
    let closest = circle_circle_distance_fast(&c1, &c2).pairs;
    let (q1, q2) = closest.first();
    let mut contact = sphere_sphere(
        pairing,
        (q1, roller.minor_radius),
        (q2, flange.minor_radius),
        |p1, n| roller.curvature(&p1, &(-n)),
        |p2, n| flange.curvature(&p2, &n),
        |n| roller.contains_normal(&q1, &(-n)),
        |n| flange.contains_normal(&q2, &n),
    );
    contact.multiple = !matches!(closest, ClosestPairs::Unique(..));
    contact
}

/// Roller edge torus against the flange face (Gupta): the penetration r − d(q(β)) of the
/// tube-centre point q(β) is maximal where d(q(β)), its distance from the cone, is
/// minimal. Its stationarity h(β) = n(q)·q'(β) = 0 is solved by Newton's method with the
/// exact derivative h' = q'ᵀ·H·q' + n·q'' (H the Hessian of the cone's distance,
/// (n_ρ/ρ)·(projector on the circumferential direction)), started from the estimate of a
/// plane through the cone's tangent at the torus centre and safeguarded by bisection on the
/// half circle around it, on which the distance has exactly one minimum.
///
/// Evaluated without trigonometric calls: in the cone's frame the tube-centre point has
/// the axial coordinate s(β) and in-plane coordinates X(β), Y(β), all sinusoids in β; with
/// ρ = √(X² + Y²) and (n_s, n_ρ) the cone's meridian normal, d = n_s·s + n_ρ·ρ + const,
/// so h = d' = n_s s' + n_ρ ρ' with ρ' = (XX' + YY')/ρ, and h' = n_s s'' + n_ρ ρ'' with
/// ρ'' = (X'² + Y'² + XX'' + YY'' − ρ'²)/ρ (the same h and h' as above). The angle is
/// advanced by rotating (cos β, sin β) with a short Taylor series (`circle_fast::rotate`).
pub fn torus_cone(torus: &TorusPatch, cone: &ConePatch) -> Contact {
    let e = torus.axis;
    let (u, v) = basis(&e);
    let big = torus.major_radius;
    let a = cone.axis;
    let (e1, e2) = basis(&a);
    let w = torus.origin - cone.origin;
    // Sinusoids g(β) = g₀ + g_c cos β + g_s sin β of the tube-centre point's coordinates.
    let sinusoid = |k: &Vec3| (k.dot(&w), big * k.dot(&u), big * k.dot(&v));
    let (sx, sy, ss) = (sinusoid(&e1), sinusoid(&e2), sinusoid(&a));
    let (ns, nr) = cone.meridian_normal();
    // h(β) and h'(β) at (cos β, sin β).
    let slope = |c: f64, sn: f64| {
        let at = |g: (f64, f64, f64)| {
            let val = g.0 + g.1 * c + g.2 * sn;
            (val, g.2 * c - g.1 * sn, g.0 - val)
        };
        let ((x, xp, xpp), (y, yp, ypp), (_, sp, spp)) = (at(sx), at(sy), at(ss));
        let inv = 1.0 / (x * x + y * y).sqrt();
        let rp = (x * xp + y * yp) * inv;
        let rpp = (xp * xp + yp * yp + x * xpp + y * ypp - rp * rp) * inv;
        (ns * sp + nr * rp, ns * spp + nr * rpp)
    };
    // Plane model: the distance falls fastest along −n₀ projected on the circle's plane,
    // n₀ = n_s·a + n_ρ·e_ρ₀ the cone's normal in the torus centre's meridian plane; its
    // components along u and v follow from the sinusoids' coefficients (g_c = R k·u,
    // g_s = R k·v).
    let rho0 = (sx.0 * sx.0 + sy.0 * sy.0).sqrt();
    let (wu, wv) = if rho0 > 1e-300 {
        let k = nr / rho0;
        (
            -(ns * ss.1 + k * (sx.0 * sx.1 + sy.0 * sy.1)) / big,
            -(ns * ss.2 + k * (sx.0 * sx.2 + sy.0 * sy.2)) / big,
        )
    } else {
        // Torus centre on the cone's axis: the meridian plane as `ConePatch::foot` picks it.
        let n0 = cone.foot(&torus.origin).normal;
        (-n0.dot(&u), -n0.dot(&v))
    };
    let m = (wu * wu + wv * wv).sqrt();
    let parallel = m <= 1e-14;
    let (c0, s0) = if parallel {
        (1.0, 0.0) // circle parallel to the face: every β is a minimum of the plane model
    } else {
        (wu / m, wv / m)
    };
    // Safeguarded Newton on the offset t of β from the estimate, t ∈ [−π/2, π/2].
    let (mut lo, mut hi) = (-FRAC_PI_2, FRAC_PI_2);
    let (mut t, mut c, mut sn) = (0.0, c0, s0);
    let mut previous = f64::INFINITY;
    for _ in 0..100 {
        let (h, dh) = slope(c, sn);
        let step = h / dh;
        // Quadratic convergence: the error after this step is about K·step², with
        // K ≈ |step|/|previous step|²; done when that is below 1e-18 rad (or the step
        // itself below 1e-9).
        let a = step.abs();
        if dh > 0.0 && (a <= 1e-9 || converged(a, previous, 1e-18)) {
            (c, sn) = rotate(c, sn, -step);
            break;
        }
        if h <= 0.0 {
            lo = t;
        } else {
            hi = t;
        }
        let newton = t - step;
        let target = if dh > 0.0 && newton >= lo && newton <= hi {
            previous = a;
            newton
        } else {
            previous = f64::INFINITY;
            0.5 * (lo + hi)
        };
        (c, sn) = if (target - t).abs() <= 0.4 {
            rotate(c, sn, target - t)
        } else {
            rotate(c0, s0, target)
        };
        t = target;
        if hi - lo <= 1e-15 {
            break;
        }
    }
    let m = (c * c + sn * sn).sqrt();
    let q = torus.origin + (u * (c / m) + v * (sn / m)) * big;
    let foot = cone.foot(&q);
    let n = foot.normal;
    let p1 = q - n * torus.minor_radius;
    let mut contact = Contact::assemble(
        Pairing::TorusCone,
        p1,
        foot.point,
        n,
        torus.minor_radius - foot.distance,
        || (torus.curvature(&p1, &(-n)), cone.curvature(&foot.point, &n)),
        foot.on_patch && torus.contains_normal(&q, &(-n)),
    );
    contact.multiple = parallel;
    contact
}

/// Two unit vectors completing the unit `n` to a right-handed orthonormal frame, without
/// square root (Duff et al., *Building an orthonormal basis, revisited*, JCGT 2017).
#[inline]
fn basis(n: &Vec3) -> (Vec3, Vec3) {
    let sign = 1f64.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    (
        Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x),
        Vec3::new(b, sign + n.y * n.y * a, -n.y),
    )
}

/// Two spheres (c₁, r₁) on the roller and (c₂, r₂) on the flange: n = (c₁ − c₂)/|c₁ − c₂|,
/// δ = r₁ + r₂ − |c₁ − c₂|, P₁ = c₁ − r₁n, P₂ = c₂ + r₂n.
#[allow(clippy::too_many_arguments)]
fn sphere_sphere(
    pairing: Pairing,
    (c1, r1): (Vec3, f64),
    (c2, r2): (Vec3, f64),
    roller_curvature: impl Fn(Vec3, Vec3) -> crate::geometry::primitives::Curvature,
    flange_curvature: impl Fn(Vec3, Vec3) -> crate::geometry::primitives::Curvature,
    roller_patch: impl Fn(Vec3) -> bool,
    flange_patch: impl Fn(Vec3) -> bool,
) -> Contact {
    let w = c1 - c2;
    let d = w.norm();
    let n = if d > 1e-300 {
        w / d
    } else {
        any_perpendicular(&Vec3::x())
    };
    let p1 = c1 - n * r1;
    let p2 = c2 + n * r2;
    Contact::from_parts(
        pairing,
        p1,
        p2,
        n,
        r1 + r2 - d,
        &roller_curvature(p1, n),
        &flange_curvature(p2, n),
        roller_patch(n) && flange_patch(n),
    )
}
