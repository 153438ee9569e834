//! Tests of the circle–circle distance ([`super`]); their strategies and reference
//! solvers also serve the fast path's tests ([`crate::geometry::circle_fast`]).

use super::*;
use proptest::prelude::*;
use std::f64::consts::{PI, TAU};

pub(crate) fn circle(center: [f64; 3], normal: [f64; 3], radius: f64) -> Circle3 {
    Circle3 {
        center: V3::from(center),
        normal: V3::from(normal),
        radius,
    }
}

pub(crate) fn scale(c1: &Circle3, c2: &Circle3) -> f64 {
    c1.radius.max(c2.radius).max((c1.center - c2.center).norm())
}

/// Squared distance from a point to a circle in the closed form of Eberly sect. 2:
/// h² + (ρ − r)², h the height over the plane and ρ the in-plane distance to the
/// centre (written differently from the code under test).
fn point_circle_sq(p: &V3, c: &Circle3) -> f64 {
    let n = c.normal.normalize();
    let d = p - c.center;
    let h = n.dot(&d);
    let rho = (d - n * h).norm();
    h * h + (rho - c.radius) * (rho - c.radius)
}

/// An in-plane frame built independently of the code under test (Gram–Schmidt
/// against the coordinate axis least aligned with the normal, other order).
pub(crate) fn frame(c: &Circle3) -> (V3, V3) {
    let n = c.normal.normalize();
    let k = (0..3)
        .min_by(|&i, &j| n[i].abs().total_cmp(&n[j].abs()))
        .unwrap();
    let mut a = V3::zeros();
    a[k] = 1.0;
    let v = n.cross(&a).normalize();
    (v.cross(&n), v)
}

pub(crate) fn point(c: &Circle3, frame: &(V3, V3), t: f64) -> V3 {
    c.center + (frame.0 * t.cos() + frame.1 * t.sin()) * c.radius
}

/// Brute-force reference: circle 1 sampled at `n` points with the exact point-circle
/// distance, then every sampled local minimum refined by golden-section search over
/// its two neighbouring intervals.
pub(crate) fn brute_force(c1: &Circle3, c2: &Circle3, n: usize) -> f64 {
    let fr = frame(c1);
    let f = |t: f64| point_circle_sq(&point(c1, &fr, t), c2);
    let h = TAU / n as f64;
    let vals: Vec<f64> = (0..n).map(|k| f(k as f64 * h)).collect();
    let mut best = f64::INFINITY;
    for k in 0..n {
        let (prev, next) = (vals[(k + n - 1) % n], vals[(k + 1) % n]);
        if vals[k] > prev || vals[k] > next {
            continue;
        }
        let (mut a, mut b) = ((k as f64 - 1.0) * h, (k as f64 + 1.0) * h);
        let g = 0.5 * (5f64.sqrt() - 1.0);
        for _ in 0..120 {
            let (x1, x2) = (b - g * (b - a), a + g * (b - a));
            if f(x1) < f(x2) {
                b = x2;
            } else {
                a = x1;
            }
        }
        best = best.min(f(0.5 * (a + b))).min(vals[k]);
    }
    best
}

/// Raw sampling of both circles, n × n points (an upper bound on the minimum).
fn grid_min(c1: &Circle3, c2: &Circle3, n: usize) -> f64 {
    let (f1, f2) = (frame(c1), frame(c2));
    let p2: Vec<V3> = (0..n)
        .map(|k| point(c2, &f2, TAU * k as f64 / n as f64))
        .collect();
    let mut best = f64::INFINITY;
    for i in 0..n {
        let p = point(c1, &f1, TAU * i as f64 / n as f64);
        for q in &p2 {
            best = best.min((p - q).norm_squared());
        }
    }
    best
}

fn pairs_of(r: &CircleDistance) -> Vec<(V3, V3)> {
    match &r.pairs {
        ClosestPairs::Unique(p, q) | ClosestPairs::Infinite(p, q) => vec![(*p, *q)],
        ClosestPairs::Several(v) => v.clone(),
    }
}

/// The returned points lie on their circles and realise the squared distance.
fn check_points(c1: &Circle3, c2: &Circle3, r: &CircleDistance) {
    let s = scale(c1, c2);
    let on = |p: &V3, c: &Circle3| {
        let n = c.normal.normalize();
        let d = p - c.center;
        assert!((d.norm() - c.radius).abs() <= 1e-12 * s, "off radius: {d}");
        assert!(n.dot(&d).abs() <= 1e-12 * s, "off plane: {d}");
    };
    let pairs = pairs_of(r);
    assert!(!pairs.is_empty());
    let (p0, q0) = r.pairs.first();
    assert_eq!((p0 - q0).norm_squared(), r.squared_distance);
    for (p, q) in &pairs {
        on(p, c1);
        on(q, c2);
        let d = (p - q).norm();
        assert!(d - r.squared_distance.sqrt() <= 1e-10 * s);
    }
}

fn assert_close(a: f64, b: f64, tol: f64) {
    assert!((a - b).abs() <= tol, "{a} vs {b} (tol {tol})");
}

// ---- 1. Eberly's published cases -------------------------------------------------
//
// Source: Geometric Tools unit test of the circle-circle query,
// github.com/davideberly/GeometricToolsUnitTests,
// UnitTests/Mathematics/Distance/3D/TestDistCircle3Circle3.cpp (commit 76cae295):
// circle 0 = unit circle in z = 0 at the origin. Its expected values are single
// precision checked to maxError = 1e-6 there, and are checked to that tolerance
// here; tighter checks use closed forms derived below.

fn unit_xy() -> Circle3 {
    circle([0.0, 0.0, 0.0], [0.0, 0.0, 1.0], 1.0)
}

#[test]
fn eberly_nonparallel_concentric_axes() {
    // "Circles in nonparallel planes (concentric)": centre (0,0,1), r = 1.25,
    // normal ∝ (0.0625, 0, 1). Published: 0.911423385 (float, tol 1e-6), closest
    // points (1,0,0) and (1.24756575, 0, 0.922027528).
    let c2 = circle([0.0, 0.0, 1.0], [0.0625, 0.0, 1.0], 1.25);
    let c1 = unit_xy();
    // Double-precision reference, closed form: by the mirror symmetry y → −y and the
    // brute force below, the minimum is at P = (1,0,0): with n the unit normal,
    // h = n·(P − c₂), ρ² = |P − c₂|² − h², F = h² + (ρ − 1.25)² (Eberly sect. 2).
    let n = V3::new(0.0625, 0.0, 1.0).normalize();
    let dvec = V3::new(1.0, 0.0, -1.0);
    let h = n.dot(&dvec);
    let rho = (dvec.norm_squared() - h * h).sqrt();
    let exact = h * h + (rho - 1.25) * (rho - 1.25);
    assert_close(exact, 0.911_422_838_404_8, 1e-12);
    for (a, b, swapped) in [(&c1, &c2, false), (&c2, &c1, true)] {
        let r = circle_circle_distance(a, b);
        check_points(a, b, &r);
        assert!(matches!(r.pairs, ClosestPairs::Unique(..)), "{r:?}");
        assert_close(r.squared_distance, 0.911423385, 1e-6);
        assert_close(r.squared_distance, exact, 1e-13);
        assert_close(r.squared_distance, brute_force(a, b, 4096), 1e-13);
        let (mut p, mut q) = r.pairs.first();
        if swapped {
            std::mem::swap(&mut p, &mut q);
        }
        assert!((p - V3::new(1.0, 0.0, 0.0)).norm() <= 1e-9);
        assert!((q - V3::new(1.24756575, 0.0, 0.922027528)).norm() <= 1e-6);
    }
}

#[test]
fn eberly_same_plane_separated() {
    let c2 = circle([4.0, 0.0, 0.0], [0.0, 0.0, 1.0], 2.0);
    for (a, b) in [(unit_xy(), c2), (c2, unit_xy())] {
        let r = circle_circle_distance(&a, &b);
        check_points(&a, &b, &r);
        assert_eq!(r.squared_distance, 1.0);
        let (p, q) = r.pairs.first();
        let (p1, p2) = if a.radius == 1.0 { (p, q) } else { (q, p) };
        assert_eq!(p1, V3::new(1.0, 0.0, 0.0));
        assert_eq!(p2, V3::new(2.0, 0.0, 0.0));
        assert!(matches!(r.pairs, ClosestPairs::Unique(..)));
    }
}

#[test]
fn eberly_parallel_planes_containment() {
    // Projection of circle 2 (r 0.125 at (0.25, 0)) inside the unit circle: in-plane
    // gap 1 − 0.375, height 1: 1 + 0.625² = 1.390625 exactly.
    let c2 = circle([0.25, 0.0, 1.0], [0.0, 0.0, 1.0], 0.125);
    for (a, b) in [(unit_xy(), c2), (c2, unit_xy())] {
        let r = circle_circle_distance(&a, &b);
        check_points(&a, &b, &r);
        assert_close(r.squared_distance, 1.390625, 1e-15);
        assert!(matches!(r.pairs, ClosestPairs::Unique(..)));
        let (p, q) = r.pairs.first();
        let (p1, p2) = if a.radius == 1.0 { (p, q) } else { (q, p) };
        assert!((p1 - V3::new(1.0, 0.0, 0.0)).norm() < 1e-15);
        assert!((p2 - V3::new(0.375, 0.0, 1.0)).norm() < 1e-15);
    }
}

#[test]
fn eberly_parallel_planes_overlap_two_pairs() {
    // Projections cross at x = 0.21875, y = ±0.975780964: two pairs at distance 1.
    let c2 = circle([1.0, 0.0, 1.0], [0.0, 0.0, 1.0], 1.25);
    for (a, b) in [(unit_xy(), c2), (c2, unit_xy())] {
        let r = circle_circle_distance(&a, &b);
        check_points(&a, &b, &r);
        assert_close(r.squared_distance, 1.0, 1e-15);
        let ClosestPairs::Several(pairs) = &r.pairs else {
            panic!("expected two pairs: {r:?}");
        };
        assert_eq!(pairs.len(), 2);
        let y = (1.0f64 - 0.21875 * 0.21875).sqrt();
        assert_close(y, 0.975780964, 1e-6);
        let mut ys: Vec<f64> = pairs.iter().map(|(p, _)| p.y).collect();
        ys.sort_by(f64::total_cmp);
        assert_close(ys[0], -y, 1e-15);
        assert_close(ys[1], y, 1e-15);
        for (p, q) in pairs {
            assert_close(p.x, 0.21875, 1e-15);
            assert_close(q.x, 0.21875, 1e-15);
            assert_close((p - q).norm_squared(), 1.0, 1e-15);
        }
    }
}

#[test]
fn eberly_equal_and_concentric_are_infinite() {
    // Equal circles: distance 0, a continuum of pairs.
    let r = circle_circle_distance(&unit_xy(), &unit_xy());
    check_points(&unit_xy(), &unit_xy(), &r);
    assert!(matches!(r.pairs, ClosestPairs::Infinite(..)), "{r:?}");
    assert_eq!(r.squared_distance, 0.0);
    // Concentric coplanar, radii 1 and 2: squared distance 1 for every aligned pair.
    let c2 = circle([0.0, 0.0, 0.0], [0.0, 0.0, 1.0], 2.0);
    for (a, b) in [(unit_xy(), c2), (c2, unit_xy())] {
        let r = circle_circle_distance(&a, &b);
        check_points(&a, &b, &r);
        assert!(matches!(r.pairs, ClosestPairs::Infinite(..)), "{r:?}");
        assert_close(r.squared_distance, 1.0, 1e-15);
    }
    // Coaxial in parallel planes (Eberly sect. 5.2), opposite normals.
    let c3 = circle([0.0, 0.0, 0.5], [0.0, 0.0, -1.0], 1.5);
    let r = circle_circle_distance(&unit_xy(), &c3);
    check_points(&unit_xy(), &c3, &r);
    assert!(matches!(r.pairs, ClosestPairs::Infinite(..)), "{r:?}");
    assert_close(r.squared_distance, 0.5, 1e-15);
}

#[test]
fn eberly_general_case() {
    // "General case" of the same unit test (float inputs, tolerance 1e-6): squared
    // distance 0.245732963, closest points (0.424922794, 0.938110709, −1.26392782)
    // and (0.227285862, 1.05095041, −0.823541999) (Mathematica agrees to 6 digits).
    let c1 = circle(
        [0.629447341, -0.729045987, 0.811583877],
        [-0.512442946, 0.644127250, 0.567892849],
        2.67001724,
    );
    let c2 = circle(
        [-0.557931900, 0.264718533, -0.383665919],
        [0.122579113, -0.574992657, -0.808923900],
        1.19508076,
    );
    let r = circle_circle_distance(&c1, &c2);
    check_points(&c1, &c2, &r);
    assert!(matches!(r.pairs, ClosestPairs::Unique(..)), "{r:?}");
    assert_close(r.squared_distance, 0.245732963, 1e-6);
    assert_close(r.squared_distance, brute_force(&c1, &c2, 4096), 1e-13);
    let (p, q) = r.pairs.first();
    assert!((p - V3::new(0.424922794, 0.938110709, -1.26392782)).norm() < 1e-5);
    assert!((q - V3::new(0.227285862, 1.05095041, -0.823541999)).norm() < 1e-5);
    let s = circle_circle_distance(&c2, &c1);
    assert_close(s.squared_distance, r.squared_distance, 1e-14);
}

// ---- special configurations (derived here) ----------------------------------------

#[test]
fn point_on_axis_gives_continuum() {
    // Circle A (normal y, centre (2,0,0), radius 2) passes through the centre of the
    // unit circle B in z = 0, tangent to B's axis there. Points of A are
    // (2 − 2cos θ, 0, 2 sin θ), at squared distance 4 sin²θ + (1 − 2cos θ)² =
    // 5 − 4 cos θ from B: minimum 1 at the origin, equidistant from all of B.
    let a = circle([2.0, 0.0, 0.0], [0.0, 1.0, 0.0], 2.0);
    for (c1, c2) in [(a, unit_xy()), (unit_xy(), a)] {
        let r = circle_circle_distance(&c1, &c2);
        check_points(&c1, &c2, &r);
        assert!(matches!(r.pairs, ClosestPairs::Infinite(..)), "{r:?}");
        assert_close(r.squared_distance, 1.0, 1e-12);
    }
}

#[test]
fn linked_great_circles_meet_twice() {
    // Two unit circles centred at the origin in z = 0 and y = 0 meet at (±1, 0, 0)
    // (centres on each other's axes: Eberly sect. 5.3).
    let c2 = circle([0.0, 0.0, 0.0], [0.0, 1.0, 0.0], 1.0);
    let r = circle_circle_distance(&unit_xy(), &c2);
    check_points(&unit_xy(), &c2, &r);
    let ClosestPairs::Several(pairs) = &r.pairs else {
        panic!("expected two pairs: {r:?}");
    };
    assert_eq!(pairs.len(), 2);
    assert!(r.squared_distance < 1e-28);
    let mut xs: Vec<f64> = pairs.iter().map(|(p, _)| p.x).collect();
    xs.sort_by(f64::total_cmp);
    assert_close(xs[0], -1.0, 1e-14);
    assert_close(xs[1], 1.0, 1e-14);
}

#[test]
fn mirror_symmetric_minima_are_both_reported() {
    // Circle 2 in the plane x = 0.5 (normal x), centre (0.5, 0, 2), radius 2:
    // symmetric under y → −y with its minima off the mirror plane.
    let c2 = circle([0.5, 0.0, 2.0], [1.0, 0.0, 0.0], 2.0);
    let r = circle_circle_distance(&unit_xy(), &c2);
    check_points(&unit_xy(), &c2, &r);
    let ClosestPairs::Several(pairs) = &r.pairs else {
        panic!("expected two pairs: {r:?}");
    };
    assert_eq!(pairs.len(), 2);
    let (a, b) = (pairs[0].0, pairs[1].0);
    assert!((a - V3::new(b.x, -b.y, b.z)).norm() < 1e-9);
    assert!(a.y.abs() > 0.1);
    assert_close(
        r.squared_distance,
        brute_force(&unit_xy(), &c2, 4096),
        1e-13,
    );
}

#[test]
fn grid_sampling_bounds() {
    // An independent 2000 × 2000 sampling of both circles bounds the minimum from
    // above; with spacing h the sampling error is at most ~ (r₁² + r₂²)(π/2000)²/2.
    let cases = [
        (unit_xy(), circle([0.3, -0.2, 0.4], [0.3, 0.8, 0.2], 0.7)),
        (
            circle([0.1, 0.2, 0.3], [1.0, -0.5, 0.2], 1.5),
            circle([-0.4, 0.1, 0.0], [0.2, 0.3, -1.0], 0.4),
        ),
    ];
    for (c1, c2) in cases {
        let r = circle_circle_distance(&c1, &c2);
        check_points(&c1, &c2, &r);
        let g = grid_min(&c1, &c2, 2000);
        let tol = (c1.radius.powi(2) + c2.radius.powi(2)) * (PI / 2000.0).powi(2);
        assert!(
            r.squared_distance <= g + 1e-12,
            "{} > {g}",
            r.squared_distance
        );
        assert!(
            r.squared_distance >= g - tol,
            "{} < {g} - {tol}",
            r.squared_distance
        );
    }
}

// ---- 2. brute-force reference over random circles ---------------------------------

pub(crate) fn unit_vector() -> impl Strategy<Value = V3> {
    (-1.0f64..1.0, 0.0..TAU).prop_map(|(z, phi)| {
        let s = (1.0 - z * z).sqrt();
        V3::new(s * phi.cos(), s * phi.sin(), z)
    })
}

pub(crate) fn any_circle() -> impl Strategy<Value = Circle3> {
    (
        prop::array::uniform3(-0.5f64..0.5),
        unit_vector(),
        0.1f64..2.0,
    )
        .prop_map(|(c, n, r)| Circle3 {
            center: V3::from(c),
            normal: n,
            radius: r,
        })
}

fn check_against_brute_force(c1: &Circle3, c2: &Circle3) {
    let r = circle_circle_distance(c1, c2);
    check_points(c1, c2, &r);
    let s = scale(c1, c2);
    // Both parameterisations (each gives attained values, i.e. upper bounds).
    let b = brute_force(c1, c2, 2048).min(brute_force(c2, c1, 2048));
    // The brief's bounds, then the much tighter agreement actually reached.
    assert!(
        r.squared_distance <= b + 1e-9,
        "{} > {b}",
        r.squared_distance
    );
    assert!(r.squared_distance >= b - 1e-6 * s * s);
    assert!(
        (r.squared_distance - b).abs() <= 1e-12 * s * s,
        "{} vs brute force {b}",
        r.squared_distance
    );
    // Symmetric in the two circles.
    let t = circle_circle_distance(c2, c1);
    assert!((t.squared_distance - r.squared_distance).abs() <= 1e-12 * s * s);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1000))]

    #[test]
    fn random_circles_match_brute_force(c1 in any_circle(), c2 in any_circle()) {
        check_against_brute_force(&c1, &c2);
    }

    #[test]
    fn parallel_and_nearly_parallel_match_brute_force(
        c1 in any_circle(),
        mut c2 in any_circle(),
        flip in any::<bool>(),
        tilt in prop::sample::select(vec![0.0, 1e-15, 1e-14, 3e-14, 1e-13, 1e-12, 1e-10, 1e-7, 1e-4, 1e-2]),
        axis in unit_vector(),
    ) {
        let n = if flip { -c1.normal } else { c1.normal };
        c2.normal = (n + axis.cross(&n) * tilt).normalize();
        check_against_brute_force(&c1, &c2);
    }

    #[test]
    fn nearly_coaxial_matches_brute_force(
        c1 in any_circle(),
        mut c2 in any_circle(),
        h in -1.0f64..1.0,
        offset in prop::sample::select(vec![0.0, 1e-15, 1e-13, 1e-11, 1e-9, 1e-7, 1e-5, 1e-3]),
        tilt in prop::sample::select(vec![0.0, 1e-15, 1e-14, 1e-13, 1e-11, 1e-9, 1e-7, 1e-5, 1e-3]),
        dir in unit_vector(),
        axis in unit_vector(),
    ) {
        c2.center = c1.center + c1.normal * h + dir * offset;
        c2.normal = (c1.normal + axis.cross(&c1.normal) * tilt).normalize();
        check_against_brute_force(&c1, &c2);
    }

    #[test]
    fn disparate_scales_match_brute_force(
        mut c1 in any_circle(),
        mut c2 in any_circle(),
        log_r1 in -3.0f64..1.0,
        log_r2 in -3.0f64..1.0,
        log_offset in -3.0f64..1.0,
    ) {
        // Radii and centre distance from 1e-3 to 10 (ratios up to 1e4).
        c1.radius = 10f64.powf(log_r1);
        c2.radius = 10f64.powf(log_r2);
        let dir = c2.center - c1.center;
        let dir = if dir.norm() > 0.0 { dir.normalize() } else { V3::x() };
        c2.center = c1.center + dir * 10f64.powf(log_offset);
        check_against_brute_force(&c1, &c2);
    }

    #[test]
    fn crossing_and_nearly_crossing_circles(
        c1 in any_circle(),
        mut c2 in any_circle(),
        t in 0.0..TAU,
        phi in 0.0..TAU,
        gap in prop::sample::select(vec![0.0, 1e-12, 1e-9, 1e-6, 1e-3]),
        dir in unit_vector(),
    ) {
        // Circle 2 passes through the point X(t) of circle 1, then is moved by `gap`.
        let (u, v) = frame(&c1);
        let x = point(&c1, &(u, v), t);
        let (u2, v2) = frame(&c2);
        c2.center = x - (u2 * phi.cos() + v2 * phi.sin()) * c2.radius + dir * gap;
        let r = circle_circle_distance(&c1, &c2);
        check_points(&c1, &c2, &r);
        let s = scale(&c1, &c2);
        prop_assert!(r.squared_distance <= gap * gap + 1e-24 * s * s, "{}", r.squared_distance);
        check_against_brute_force(&c1, &c2);
    }

    #[test]
    fn centre_on_axis_matches_brute_force(
        c1 in any_circle(),
        mut c2 in any_circle(),
        h in -1.0f64..1.0,
    ) {
        c2.center = c1.center + c1.normal * h;
        check_against_brute_force(&c1, &c2);
        check_against_brute_force(&c2, &c1);
    }
}

// ---- 3. roller edge vs flange rim -------------------------------------------------
//
// Tube-centre circles of the roller edge torus (radius R − r_e = 1.7475 mm) and of a
// flange rim torus (radius 10 mm, axis z), millimetre offsets, tilts of ±1° about x
// and y (0 included), in two arrangements: the edge axis nearly perpendicular to the
// rim axis (edge normal ≈ x), and nearly parallel to it (edge normal ≈ z, as for a
// roller whose axis follows the ring axis; zero tilt takes the parallel-plane branch).
// Reference: the brute force of both parameterisations, to 1e-15 m².

pub(crate) fn rotation(axis: V3, angle: f64) -> nalgebra::Rotation3<f64> {
    nalgebra::Rotation3::from_axis_angle(&nalgebra::Unit::new_normalize(axis), angle)
}

pub(crate) fn roller_cases(perpendicular: bool) -> Vec<(Circle3, Circle3)> {
    let deg = PI / 180.0;
    let mut cases = Vec::new();
    for &tx in &[-1.0, -0.37, 0.0, 0.5, 1.0] {
        for &ty in &[-1.0, 0.0, 0.81, 1.0] {
            for &(dx, dy, dz) in &[
                (8.5e-3, 0.0, 1.2e-3),
                (9.1e-3, 0.4e-3, 0.8e-3),
                (10.3e-3, -0.7e-3, 2.5e-3),
                (11.9e-3, 0.2e-3, -1.5e-3),
            ] {
                let rim = circle([0.0, 0.0, 0.0], [0.0, 0.0, 1.0], 10e-3);
                let base = if perpendicular { V3::x() } else { V3::z() };
                let n = rotation(V3::x(), tx * deg) * (rotation(V3::y(), ty * deg) * base);
                let edge = Circle3 {
                    center: V3::new(dx, dy, dz),
                    normal: n,
                    radius: 1.7475e-3,
                };
                cases.push((edge, rim));
            }
        }
    }
    cases
}

#[test]
fn roller_edge_flange_rim_match_brute_force() {
    for perpendicular in [true, false] {
        for (edge, rim) in roller_cases(perpendicular) {
            for (a, b) in [(edge, rim), (rim, edge)] {
                let r = circle_circle_distance(&a, &b);
                check_points(&a, &b, &r);
                let bf = brute_force(&a, &b, 8192).min(brute_force(&b, &a, 8192));
                assert!(
                    (r.squared_distance - bf).abs() <= 1e-15,
                    "{} vs {bf} for {a:?} {b:?}",
                    r.squared_distance
                );
            }
        }
    }
}

#[test]
fn degenerate_inputs_do_not_panic() {
    let zero_normal = circle([0.1, 0.0, 0.0], [0.0, 0.0, 0.0], 1.0);
    let r = circle_circle_distance(&zero_normal, &unit_xy());
    assert!(r.squared_distance.is_finite());
    let point = circle([0.3, 0.2, 0.1], [0.0, 0.0, 1.0], 0.0);
    let r = circle_circle_distance(&point, &unit_xy());
    assert!(r.squared_distance.is_finite());
    for bad in [
        circle([f64::NAN, 0.0, 0.0], [0.0, 0.0, 1.0], 1.0),
        circle([0.0, 0.0, 0.0], [0.0, 0.0, 1.0], f64::NAN),
        circle([0.0, 0.0, 0.0], [0.0, 0.0, 1.0], f64::INFINITY),
        circle([0.0, f64::INFINITY, 0.0], [0.0, 0.0, 1.0], 1.0),
    ] {
        for (a, b) in [(bad, unit_xy()), (unit_xy(), bad)] {
            let r = circle_circle_distance(&a, &b);
            assert!(r.squared_distance.is_nan());
            let _ = r.pairs.first();
        }
    }
    // Non-finite normals fall back to +z.
    let odd = circle([0.5, 0.0, 0.3], [f64::NAN, 0.0, 1.0], 1.0);
    let r = circle_circle_distance(&odd, &unit_xy());
    assert!(r.squared_distance.is_finite());
    // Huge and tiny magnitudes.
    let big = circle([1e150, 0.0, 0.0], [0.3, 0.1, 1.0], 1e149);
    let r = circle_circle_distance(&big, &circle([0.0; 3], [1.0, 0.0, 0.0], 1e150));
    assert!(r.squared_distance.is_finite());
    let tiny = circle([1e-150, 0.0, 0.0], [0.3, 0.1, 1.0], 1e-151);
    let r = circle_circle_distance(&tiny, &circle([0.0; 3], [1.0, 0.0, 0.0], 1e-150));
    assert!(r.squared_distance.is_finite());
}
