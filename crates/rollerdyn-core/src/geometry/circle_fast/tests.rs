//! Tests of the certified fast path ([`super`]) against Eberly's solver.

use super::*;
use crate::geometry::circle::tests::{
    any_circle, brute_force, circle, roller_cases, scale, unit_vector,
};
use proptest::prelude::*;

#[test]
fn cos_sin_matches_libm() {
    let mut hs: Vec<f64> = (0..=4000).map(|k| -0.5 + k as f64 / 4000.0).collect();
    for e in 1..=12 {
        let h = 10f64.powi(-e);
        hs.extend([h, -h, 0.99 * h, 1.01 * h, 3.0 * h]);
    }
    hs.extend([0.0, 1e-4, 0.01, 0.4, 0.4000001, -0.4, 2.0, -3.0]);
    for h in hs {
        let (c, s) = cos_sin(h);
        assert!(
            (c - h.cos()).abs() <= 2.3e-16,
            "cos {h}: {c} vs {}",
            h.cos()
        );
        assert!(
            (s - h.sin()).abs() <= 2.3e-16,
            "sin {h}: {s} vs {}",
            h.sin()
        );
    }
}

/// The fast path against Eberly's solver: where it certifies, Eberly's solver reports a
/// unique pair at the same distance (1e-12 of the scale) and the same points (1e-9 of
/// the scale, flat minima apart); where it declines, the answer is Eberly's. Returns
/// whether it certified.
fn check(c1: &Circle3, c2: &Circle3) -> Result<bool, TestCaseError> {
    let slow = circle_circle_distance(c1, c2);
    let fast = circle_circle_distance_fast(c1, c2);
    let s = scale(c1, c2);
    let Some(cert) = certified_closest_pair(c1, c2) else {
        prop_assert_eq!(&fast, &slow);
        return Ok(false);
    };
    prop_assert_eq!(&fast, &cert);
    prop_assert!(
        matches!(slow.pairs, ClosestPairs::Unique(..)),
        "certified unique, Eberly: {:?}",
        slow
    );
    let (dfast, dslow) = (cert.squared_distance.sqrt(), slow.squared_distance.sqrt());
    prop_assert!(
        (dfast - dslow).abs() <= 1e-12 * s,
        "distance {dfast} vs Eberly {dslow} (scale {s})"
    );
    // The points agree to 1e-9 of the scale, except at flat minima (F'' nearly zero,
    // e.g. two mirror minima about to merge), where both solvers' Newton iterations
    // converge only linearly and the minimiser is determined to about 1e-8 only; the
    // distances then agree much closer (1e-13 of the scale).
    let ((p, q), (pe, qe)) = (cert.pairs.first(), slow.pairs.first());
    let flat = (dfast - dslow).abs() <= 1e-13 * s;
    let tol = if flat { 1e-6 * s } else { 1e-9 * s };
    prop_assert!(
        (p - pe).norm() <= tol && (q - qe).norm() <= tol,
        "points {p:?} {q:?} vs Eberly {pe:?} {qe:?}"
    );
    // On their circles.
    for (x, c) in [(p, c1), (q, c2)] {
        let n = c.normal.normalize();
        let d = x - c.center;
        prop_assert!(n.dot(&d).abs() <= 1e-12 * s);
        prop_assert!((d.norm() - c.radius).abs() <= 1e-12 * s);
    }
    Ok(true)
}

/// Tube-centre circles of a B1 roller's edge torus and of a flange torus: the roller
/// anywhere on the pitch circle, ±50 µm radially, its edge circle ±0.2–1.5 mm axially
/// from the flange circle, tilt and skew up to ±1° (or exactly zero, or tiny);
/// flange circles from the inner ring's root (10.2 mm) to the outer ring's (14.3 mm).
fn b1_pair() -> impl Strategy<Value = (Circle3, Circle3)> {
    (
        0.0..TAU,
        -50e-6..50e-6f64,
        prop::bool::ANY,
        0.2e-3..1.5e-3f64,
        prop::sample::select(vec![9.8e-3, 10.2e-3, 10.8e-3, 13.7e-3, 14.3e-3]),
        -1.0..1.0f64,
        -1.0..1.0f64,
        prop::sample::select(vec![1.0, 1.0, 1.0, 0.0, 1e-15, 1e-12, 1e-9, 1e-6, 1e-3]),
    )
        .prop_map(|(psi, dr, front, dz, rk, tilt, skew, scale)| {
            let radial = V3::new(0.0, psi.cos(), psi.sin());
            let circumferential = V3::x().cross(&radial);
            let (tilt, skew) = (scale * tilt.to_radians(), scale * skew.to_radians());
            let axis = (V3::x() + radial * tilt + circumferential * skew).normalize();
            let z = if front { dz } else { -dz };
            let edge = Circle3 {
                center: V3::x() * z + radial * (12.25e-3 + dr),
                normal: axis,
                radius: 1.7475e-3,
            };
            (edge, circle([0.0; 3], [1.0, 0.0, 0.0], rk))
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(3000))]

    #[test]
    fn b1_like_pairs_match_eberly((edge, flange) in b1_pair()) {
        check(&edge, &flange)?;
        check(&flange, &edge)?;
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1000))]

    #[test]
    fn random_circles_match_eberly(c1 in any_circle(), c2 in any_circle()) {
        check(&c1, &c2)?;
        check(&c2, &c1)?;
    }

    #[test]
    fn nearly_parallel_match_eberly(
        c1 in any_circle(),
        mut c2 in any_circle(),
        flip in any::<bool>(),
        tilt in prop::sample::select(vec![0.0, 1e-15, 1e-14, 3e-14, 1e-13, 1e-12, 1e-10, 1e-7, 1e-4, 1e-2]),
        axis in unit_vector(),
    ) {
        let n = if flip { -c1.normal } else { c1.normal };
        c2.normal = (n + axis.cross(&n) * tilt).normalize();
        check(&c1, &c2)?;
        check(&c2, &c1)?;
    }

    #[test]
    fn nearly_coaxial_match_eberly(
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
        check(&c1, &c2)?;
        check(&c2, &c1)?;
    }

    #[test]
    fn centre_on_axis_matches_eberly(c1 in any_circle(), mut c2 in any_circle(), h in -1.0f64..1.0) {
        c2.center = c1.center + c1.normal * h;
        check(&c1, &c2)?;
        check(&c2, &c1)?;
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    /// The certified minimum is the global one: never above an independent brute force
    /// (sampling plus golden-section refinement of every sampled local minimum).
    #[test]
    fn certified_minimum_is_global(c1 in any_circle(), c2 in any_circle()) {
        if let Some(r) = certified_closest_pair(&c1, &c2) {
            let s = scale(&c1, &c2);
            let b = brute_force(&c1, &c2, 2048).min(brute_force(&c2, &c1, 2048));
            prop_assert!(r.squared_distance <= b + 1e-12 * s * s, "{} > {b}", r.squared_distance);
        }
    }
}

#[test]
fn roller_edge_flange_rim_cases_match_eberly() {
    for perpendicular in [true, false] {
        for (edge, rim) in roller_cases(perpendicular) {
            check(&edge, &rim).unwrap();
            check(&rim, &edge).unwrap();
        }
    }
}

#[test]
fn certifies_the_b1_trajectory() {
    // The benchmark trajectory's edge circles against the inner-ring flange's root and
    // rim circles: the fast path must answer (nearly) always for the speed-up to count.
    use crate::contact::benchmark::Trajectory;
    use crate::contact::tests::{b1_flange, b1_roller};
    let shape = b1_roller();
    let flange = b1_flange(true, true); // inner ring, face at +2.52 mm facing -x
    let trajectory = Trajectory {
        pitch_radius: 12.25e-3,
        step: 1e-3,
        steps: 6283,
        push: 22e-6,
        wobble: 1e-3,
    };
    let (mut total, mut certified) = (0, 0);
    for k in 0..trajectory.steps {
        let end = trajectory.end(&shape, k);
        let edge = Circle3 {
            center: end.torus.origin,
            normal: end.torus.axis,
            radius: end.torus.major_radius,
        };
        for torus in [flange.root, flange.rim] {
            let other = Circle3 {
                center: torus.origin,
                normal: torus.axis,
                radius: torus.major_radius,
            };
            total += 1;
            certified += usize::from(check(&edge, &other).unwrap());
        }
    }
    assert_eq!(certified, total, "{certified} of {total} certified");
}
