//! Boundary friction with micro-slip (paper eqs. 51, 52) and the mixed-lubrication load
//! sharing of Zhou & Hoeprich (J. Tribol. 113 (1991) 590; paper eqs. 53, 54).

use crate::numerics::smooth::smooth_saturation;

/// Boundary (Coulomb) friction with a micro-slip ramp, paper eqs. 51, 52.
///
/// μ_B rises linearly with the slide-to-roll ratio S = u_rel/u₀ up to μ_B,0 at S = S₀
/// and stays there; F_B = μ_B(S)·F_N·sgn(u_rel). Written in the relative speed,
/// μ_B = μ_B,0·sat(u_rel/(S₀|u₀| + v_s)) with sat(x) = sgn(x)·min(|x|, 1): the ramp spans
/// S₀|u₀| of sliding speed, widened by the smoothing speed v_s so that F_B passes through
/// zero smoothly even without rolling (paper fig. 5). The corner of sat is rounded by
/// [`smooth_saturation`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BoundaryFriction {
    /// μ_B,0 [-].
    pub mu_b0: f64,
    /// Critical slide-to-roll ratio S₀ [-].
    pub s0: f64,
    /// Smoothing speed v_s [m/s].
    pub smoothing_speed: f64,
}

impl BoundaryFriction {
    /// Boundary coefficient of friction μ_B, signed like u_rel, for sliding speed u_rel
    /// and rolling (entrainment) speed u₀.
    #[inline]
    pub fn coefficient(&self, sliding_speed: f64, rolling_speed: f64) -> f64 {
        let width = self.s0 * rolling_speed.abs() + self.smoothing_speed;
        self.mu_b0 * smooth_saturation(sliding_speed / width)
    }

    /// Boundary friction force F_B (eq. 51), signed like u_rel.
    #[inline]
    pub fn force(&self, normal_force: f64, sliding_speed: f64, rolling_speed: f64) -> f64 {
        self.coefficient(sliding_speed, rolling_speed) * normal_force
    }
}

/// Zhou & Hoeprich's asperity load share, paper eq. 53: φ = exp(−B·Λ^C), Λ = h_c/σ.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LoadSharing {
    /// B_ZH [-].
    pub b: f64,
    /// C_ZH [-].
    pub c: f64,
}

impl LoadSharing {
    /// φ for the film thickness ratio Λ (Λ ≤ 0 gives φ = 1: all boundary).
    #[inline]
    pub fn boundary_share(&self, film_ratio: f64) -> f64 {
        if film_ratio <= 0.0 {
            return 1.0;
        }
        (-self.b * film_ratio.powf(self.c)).exp()
    }

    /// Mixed tangential force, paper eq. 54: F_t = φF_B + (1 − φ)F_EHL (also used for the
    /// rolling-resistance moments, paper sect. 3.3).
    #[inline]
    pub fn mix(&self, film_ratio: f64, boundary: f64, fluid: f64) -> f64 {
        Self::mix_by_share(self.boundary_share(film_ratio), boundary, fluid)
    }

    /// Eq. 54 for a known share φ (one φ serves a slice's traction and both of its
    /// rolling-resistance moments).
    #[inline]
    pub fn mix_by_share(share: f64, boundary: f64, fluid: f64) -> f64 {
        share * boundary + (1.0 - share) * fluid
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    const B: BoundaryFriction = BoundaryFriction {
        mu_b0: 0.1,
        s0: 0.02,
        smoothing_speed: 1e-3,
    };

    #[test]
    fn macro_slip_is_coulomb() {
        // Far beyond S₀ the law is Coulomb's (eq. 51) with μ_B,0.
        let f = B.force(1000.0, 1.0, 5.0);
        assert!((f - 100.0).abs() < 1e-3);
        assert!((B.force(1000.0, -1.0, 5.0) + 100.0).abs() < 1e-3);
    }

    #[test]
    fn micro_slip_is_linear_in_srr() {
        // Well inside S₀: μ_B = μ_B,0·S/S₀ (eq. 52), up to the smoothing speed's share.
        let (u0, s) = (10.0, 0.002);
        let mu = B.coefficient(s * u0, u0);
        let expected = 0.1 * s / 0.02 * (0.02 * u0) / (0.02 * u0 + 1e-3);
        assert!((mu / expected - 1.0).abs() < 1e-6, "{mu} vs {expected}");
    }

    proptest! {
        #[test]
        fn boundary_friction_is_bounded_and_odd(us in -10.0..10.0f64, u0 in -10.0..10.0f64) {
            let mu = B.coefficient(us, u0);
            prop_assert!(mu.abs() <= 0.1);
            prop_assert!((B.coefficient(-us, u0) + mu).abs() < 1e-15);
            prop_assert!(mu * us >= 0.0);
        }

        #[test]
        fn load_share_limits(log_lambda in -3.0..2.0f64) {
            let zh = LoadSharing { b: 2.32, c: 0.97 };
            let phi = zh.boundary_share(10f64.powf(log_lambda));
            prop_assert!((0.0..=1.0).contains(&phi));
            prop_assert!(zh.boundary_share(10f64.powf(log_lambda) * 1.1) <= phi);
        }
    }

    #[test]
    fn load_share_values() {
        // φ(Λ = 1) = e^(−B) whatever C; thick films carry everything.
        let zh = LoadSharing { b: 2.32, c: 0.97 };
        assert!((zh.boundary_share(1.0) - (-2.32f64).exp()).abs() < 1e-15);
        assert!(zh.boundary_share(10.0) < 1e-9);
        assert_eq!(zh.boundary_share(0.0), 1.0);
        assert!((zh.mix(1.0, 10.0, 2.0) - (2.0 + 8.0 * (-2.32f64).exp())).abs() < 1e-12);
    }
}
