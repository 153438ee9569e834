//! Complete elliptic integrals of the first and second kind by the arithmetic–geometric
//! mean (Abramowitz & Stegun 17.6; DLMF 19.8.1, 19.8.6).
//!
//! Both take the *complementary* parameter m₁ = 1 − m (m = k², k the modulus), so that
//! the nearly degenerate ellipses of roller end–flange contacts (m → 1) keep full
//! precision: for a Hertz contact of ellipticity κ = a/b, m₁ = 1/κ².

/// K(m) and E(m) from the complementary parameter m₁ = 1 − m, 0 < m₁ ≤ 1.
///
/// Returns (K, E). For m₁ → 0, K diverges logarithmically; at m₁ = 0 exactly (K, E) =
/// (∞, 1), the limit (DLMF 19.6.1; the iteration would spoil E there).
pub fn complete_elliptic_integrals(m1: f64) -> (f64, f64) {
    debug_assert!((0.0..=1.0).contains(&m1));
    if m1 == 0.0 {
        return (f64::INFINITY, 1.0);
    }
    let m = 1.0 - m1;
    let mut a = 1.0_f64;
    let mut b = m1.sqrt();
    // DLMF 19.8.6: E = K · (1 − Σ_{n≥0} 2^(n−1) c_n²), c_0² = m, c_{n+1} = (a_n − b_n)/2.
    let mut sum = 0.5 * m;
    let mut power = 0.5;
    for _ in 0..64 {
        let c = 0.5 * (a - b);
        let a_next = 0.5 * (a + b);
        let b_next = (a * b).sqrt();
        power *= 2.0;
        sum += power * c * c;
        a = a_next;
        b = b_next;
        // Stop once a and b agree to rounding: continuing would double the weight of a
        // one-ulp c forever and spoil E.
        if c.abs() <= f64::EPSILON * a {
            break;
        }
    }
    let k = std::f64::consts::FRAC_PI_2 / a;
    (k, k * (1.0 - sum))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::FRAC_PI_2;

    #[test]
    fn circle_limit() {
        let (k, e) = complete_elliptic_integrals(1.0);
        assert!((k - FRAC_PI_2).abs() < 1e-15);
        assert!((e - FRAC_PI_2).abs() < 1e-15);
    }

    #[test]
    fn tabulated_values() {
        // A&S table 17.1 at m = 0.5: K = 1.854074677301372, E = 1.350643881047675.
        let (k, e) = complete_elliptic_integrals(0.5);
        assert!((k - 1.854_074_677_301_372).abs() < 1e-14);
        assert!((e - 1.350_643_881_047_675).abs() < 1e-14, "{e}");
        // m = 0.9: K = 2.578092113348173, E = 1.104774732704073.
        let (k, e) = complete_elliptic_integrals(0.1);
        assert!((k - 2.578_092_113_348_173).abs() < 1e-13);
        assert!((e - 1.104_774_732_704_073).abs() < 1e-13);
    }

    #[test]
    fn legendre_relation_holds() {
        // Legendre's relation E K' + E' K − K K' = π/2 (DLMF 19.7.1), an identity
        // that checks K and E together at every parameter.
        for i in 1..100 {
            let m1 = i as f64 / 100.0;
            let (k, e) = complete_elliptic_integrals(m1);
            let (kp, ep) = complete_elliptic_integrals(1.0 - m1 + 1e-300);
            let lhs = e * kp + ep * k - k * kp;
            assert!((lhs - FRAC_PI_2).abs() < 1e-12, "m1={m1}: {lhs}");
        }
    }

    #[test]
    fn logarithmic_singularity() {
        // K ≈ ln(4/sqrt(m1)) and E → 1 as m1 → 0 (A&S 17.3.26, 17.3.36).
        let m1 = 1e-12;
        let (k, e) = complete_elliptic_integrals(m1);
        assert!((k - (4.0 / m1.sqrt()).ln()).abs() < 1e-9);
        assert!((e - 1.0).abs() < 1e-9);
    }
}
