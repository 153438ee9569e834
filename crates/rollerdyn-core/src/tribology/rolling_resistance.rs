//! Rolling resistance of the roller–race line contacts (paper sect. 3.3): elastic
//! hysteresis in boundary lubrication (eq. 55) and the hydrodynamic rolling force of the
//! EHL film (Biboulet & Houpert, Proc. IMechE J 224 (2010) 765; eqs. 56, 57), mixed by
//! Zhou–Hoeprich (eqs. 53, 54) and thermally corrected by φ_th (eq. 47).

use std::f64::consts::PI;

/// Hysteresis rolling-resistance moment of a line contact, paper eq. 55 read with
/// Johnson's derivation (*Contact Mechanics*, 1985, sect. 9.2): the moment of the
/// pressure on the leading half, ∫₀ᵃ p x dx·l = 2F_N a/(3π), of which the fraction α_v
/// is lost: M_B = α_v·F_N·2a/(3π), a the Hertz half-width.
///
/// The paper prints the lever arm as 2l/(3π) with l the slice length; that would make
/// the total moment grow with the number of slices, so the half-width of Johnson's
/// derivation is used (docs/model.md).
#[inline]
pub fn hysteresis_moment(alpha_v: f64, normal_force: f64, half_width: f64) -> f64 {
    alpha_v * normal_force.max(0.0) * 2.0 * half_width / (3.0 * PI)
}

/// Hydrodynamic rolling force of a line contact, Biboulet & Houpert (2010), eq. 40–42 of
/// the source, paper eqs. 56, 57 without the radius:
/// F_R = 1.42·E'R'l·Ũ^0.5·W^0.5·ψ, ψ = (1 + (0.966·W^0.5·Ũ^−0.25)^10)^−0.1,
/// with Ũ = 2η₀u₀/(E'R'), W = q/(E'R'), q = F_N/l. The moment on a body of radius R is
/// F_R·R (eq. 56; the source shows moment = force × radius, eqs. 30, 31).
///
/// Limits: ψ → 1 gives the isoviscous-rigid F̃ = 1.42 Ũ^½ W^½; large M = W/Ũ^½ gives
/// the piezoviscous-elastic F̃ = (1.42/0.966)·Ũ^¾ = 1.47 Ũ^¾.
#[inline]
pub fn ehl_rolling_force(
    e_prime: f64,
    r_eff: f64,
    length: f64,
    eta0: f64,
    u0: f64,
    normal_force: f64,
) -> f64 {
    if normal_force <= 0.0 || u0 == 0.0 {
        return 0.0;
    }
    let scale = e_prime * r_eff;
    let u_tilde = 2.0 * eta0 * u0.abs() / scale;
    let w = normal_force / (length * scale);
    let root_w = w.sqrt();
    let x = 0.966 * root_w / u_tilde.sqrt().sqrt();
    let x2 = x * x;
    let x10 = x2 * x2 * x2 * x2 * x2;
    let psi = (1.0 + x10).powf(-0.1);
    1.42 * scale * length * u_tilde.sqrt() * root_w * psi
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numerics::quadrature::integrate_converged;

    #[test]
    fn hysteresis_is_alpha_times_leading_half_moment() {
        // Independent: integrate the Hertz pressure moment over the leading half.
        let (f, a, l) = (500.0, 1e-4, 2.5e-4);
        let p0 = 2.0 * f / (PI * a * l);
        let moment = l * integrate_converged(0.0, a, 1e-13, |x| {
            p0 * (1.0 - (x / a).powi(2)).max(0.0).sqrt() * x
        });
        assert!((hysteresis_moment(0.007, f, a) / (0.007 * moment) - 1.0).abs() < 1e-8);
    }

    #[test]
    fn asymptotes_of_biboulet_houpert() {
        let (e, r, l, eta): (f64, f64, f64, f64) = (2.3e11, 2e-3, 1e-3, 0.0165);
        // Isoviscous-rigid: tiny load, fast rolling → 1.42·E'R'l·(ŨW)^½.
        let (u0, f): (f64, f64) = (10.0, 1e-3);
        let ut = 2.0 * eta * u0 / (e * r);
        let w = f / (l * e * r);
        let ivr = 1.42 * e * r * l * (ut * w).sqrt();
        assert!((ehl_rolling_force(e, r, l, eta, u0, f) / ivr - 1.0).abs() < 1e-6);
        // Piezoviscous-elastic: heavy load, slow rolling → 1.47·E'R'l·Ũ^¾ (source eq. 41
        // prints 1.47; 1.42/0.966 = 1.470).
        let (u0, f): (f64, f64) = (0.01, 1000.0);
        let ut = 2.0 * eta * u0 / (e * r);
        let pe = 1.47 * e * r * l * ut.powf(0.75);
        assert!((ehl_rolling_force(e, r, l, eta, u0, f) / pe - 1.0).abs() < 2e-3);
    }
}
