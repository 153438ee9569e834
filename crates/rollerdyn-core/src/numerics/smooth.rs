//! Smooth (C∞) replacements of the non-smooth operations that the paper's force laws
//! contain: minimum, maximum and saturation. A stiff implicit integrator needs force
//! laws that are at least C¹ (see docs/model.md, "Smoothing"); each use documents its
//! width.
//!
//! All three use the p-norm with p = 8, evaluated with multiplications and three square
//! roots. At the crossover of the two arguments the smooth minimum is 2^(−1/8) = 0.917
//! times the sharp one (an 8.3 % rounding of the corner); one argument twice the other
//! already brings the deviation under 0.05 %.

/// Smooth minimum of two non-negative magnitudes: x·y / (x⁸ + y⁸)^(1/8).
/// Equals min(x, y) to within 8.3 % at x = y and to within 0.05 % once the larger is
/// twice the smaller; 0 if either is 0; the other argument if one is +∞ (the limit;
/// the formula itself would give ∞/∞ = NaN).
#[inline]
pub fn smooth_min(x: f64, y: f64) -> f64 {
    let m = x.max(y);
    if m <= 0.0 {
        return 0.0;
    }
    if m == f64::INFINITY {
        return x.min(y);
    }
    x * y / (m * eighth_norm(x / m, y / m))
}

/// Smooth maximum of two non-negative magnitudes: (x⁸ + y⁸)^(1/8).
/// At most 2^(1/8) = 1.09 times max(x, y) (at x = y).
#[inline]
pub fn smooth_max(x: f64, y: f64) -> f64 {
    let m = x.max(y);
    if m <= 0.0 {
        return 0.0;
    }
    m * eighth_norm(x / m, y / m)
}

/// (u⁸ + v⁸)^(1/8) for u, v in [0, 1] (one of them 1): three squarings, three roots.
#[inline]
fn eighth_norm(u: f64, v: f64) -> f64 {
    let (u2, v2) = (u * u, v * v);
    let (u4, v4) = (u2 * u2, v2 * v2);
    (u4 * u4 + v4 * v4).sqrt().sqrt().sqrt()
}

/// Smooth saturation sign(x)·min(|x|, 1): an odd function, linear with slope 1 at 0,
/// tending to ±1.
#[inline]
pub fn smooth_saturation(x: f64) -> f64 {
    smooth_min(x.abs(), 1.0).copysign(x)
}

/// Smooth max(x, 0), a hyperbola of half-width `width`: ½(x + sqrt(x² + w²)). Above
/// max(x, 0) by at most w/2 (at x = 0); for w = 0 exactly max(x, 0). The smooth lower
/// bound of a force that cannot pull: the contact damping's and the oil film's.
#[inline]
pub fn hyperbolic_ramp(x: f64, width: f64) -> f64 {
    0.5 * (x + (x * x + width * width).sqrt())
}

/// The C¹ unit step 3t² − 2t³ of t clamped to [0, 1].
#[inline]
pub fn unit_smoothstep(t: f64) -> f64 {
    let t = t.clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// C¹ step of half-width `band` about 0: 0 for x ≤ −band, 1 for x ≥ band,
/// [`unit_smoothstep`] of t = (x/band + 1)/2 between; a sharp step for band = 0.
#[inline]
pub fn smoothstep(x: f64, band: f64) -> f64 {
    if band > 0.0 {
        unit_smoothstep(0.5 * (x / band + 1.0))
    } else if x >= 0.0 {
        1.0
    } else {
        0.0
    }
}

/// 1 up to half the `cutoff`, falling with a C¹ [`unit_smoothstep`] to 0 at the cutoff:
/// how a film force across a gap fades out.
#[inline]
pub fn fade_out(gap: f64, cutoff: f64) -> f64 {
    1.0 - unit_smoothstep((2.0 * gap - cutoff) / cutoff)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// An infinite argument gives the other one (the limit), not ∞/∞ = NaN
    /// (docs/robustness.md, finding 5).
    #[test]
    fn smooth_min_of_infinity_is_the_other_argument() {
        assert_eq!(smooth_min(f64::INFINITY, 3.0), 3.0);
        assert_eq!(smooth_min(2.0, f64::INFINITY), 2.0);
        assert_eq!(smooth_min(f64::INFINITY, f64::INFINITY), f64::INFINITY);
        assert_eq!(smooth_min(f64::INFINITY, 0.0), 0.0);
        // The limit is approached continuously.
        assert!((smooth_min(1e300, 3.0) - 3.0).abs() < 1e-12);
    }

    proptest! {
        #[test]
        fn smooth_min_is_bounded_by_the_sharp_one(x in 0.0..1e6f64, y in 0.0..1e6f64) {
            let s = smooth_min(x, y);
            prop_assert!(s <= x.min(y) * (1.0 + 1e-12));
            prop_assert!(s >= x.min(y) * 0.917);
        }

        #[test]
        fn hyperbolic_ramp_is_within_half_its_width_above_the_sharp_one(
            x in -1e3..1e3f64, width in 0.0..10.0f64,
        ) {
            let r = hyperbolic_ramp(x, width);
            prop_assert!(r >= x.max(0.0) && r <= x.max(0.0) + 0.5 * width + 1e-12);
            prop_assert_eq!(hyperbolic_ramp(x, 0.0), x.max(0.0));
        }

        #[test]
        fn smooth_max_is_bounded_by_the_sharp_one(x in 0.0..1e6f64, y in 0.0..1e6f64) {
            let s = smooth_max(x, y);
            prop_assert!(s >= x.max(y) * (1.0 - 1e-12));
            prop_assert!(s <= x.max(y) * 1.0906);
        }

        #[test]
        fn saturation_is_odd_and_bounded(x in -1e3..1e3f64) {
            prop_assert!((smooth_saturation(x) + smooth_saturation(-x)).abs() < 1e-15);
            prop_assert!(smooth_saturation(x).abs() <= 1.0);
        }
    }

    #[test]
    fn corner_values() {
        assert!((smooth_min(1.0, 1.0) - 2f64.powf(-0.125)).abs() < 1e-15);
        assert!((smooth_min(1.0, 2.0) - 1.0).abs() < 5e-4);
        assert_eq!(smooth_min(0.0, 3.0), 0.0);
        assert!((smooth_saturation(1e-3) - 1e-3).abs() < 1e-15);
        assert!(smooth_min(1e300, 1e-300).is_finite());
    }
}
