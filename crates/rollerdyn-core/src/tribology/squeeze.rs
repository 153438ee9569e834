//! Squeeze-film damping of the oil between a roller end and a flange, which the paper's
//! model does not have (see docs/dynamics.md, "Squeeze film at the flanges").
//!
//! Two lubricated surfaces that approach each other at the rate ḣ = −dh/dt squeeze the oil
//! out of the gap; the Reynolds equation for an isoviscous, rigid, fully flooded gap gives a
//! force against the motion that grows as the gap closes. Two closed forms bound it:
//!
//! * a sphere of radius R at the minimum gap h from a plane: F = 6π η R² ḣ / h, for h ≪ R;
//! * two parallel discs of radius w at the gap h: F = (3π/2) η w⁴ ḣ / h³
//!
//! (both from the Reynolds equation, Reynolds 1886; see Hamrock, Schmid, Jacobson,
//! *Fundamentals of Fluid Film Lubrication*, 2nd ed. 2004, the chapter on squeeze-film
//! bearings).
//!
//! A roller end is a 5 m sphere (its end face) and an edge torus; the flange face is a
//! bounded cone. Where the pressure of the sphere–plane solution would spread beyond the
//! face (its radius sqrt(2Rh) exceeds the face's half-width w), the face bounds it: each
//! principal radius is replaced by R_eff = (1/R + 2h/w²)⁻¹, which is R for small, curved
//! contacts and w²/(2h) for flat ones. With R_eff for R the sphere formula becomes exactly
//! the parallel-disc formula in the flat limit; between the limits it is an interpolation.
//! For an ellipsoidal gap (R_x ≠ R_y) R² is taken as R_x·R_y (exact for R_x = R_y).
//!
//! The film is taken as full (Sommerfeld): it resists separation as it resists approach,
//! whereas a real film cavitates at about −1 bar. At the gap h = 0 the formula is singular;
//! the gap is floored smoothly, h = sqrt(gap² + h_f²), with h_f of the order of the
//! composite roughness σ (B1: h_f = σ = 0.24 µm): below it the asperities touch and the
//! contact's own laws (Hertz with its contact damping, load sharing) carry the load.

use crate::numerics::smooth::fade_out;

/// Squeeze-film settings of the roller end–flange contacts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SqueezeFilm {
    /// Off: the paper's model (no force across a gap).
    pub enabled: bool,
    /// Half-width w of the end-face/flange-face overlap that bounds the film [m].
    pub half_width: f64,
    /// Gap floor h_f [m], of the order of the flange contact's composite roughness σ.
    pub floor: f64,
    /// Gap beyond which the film force is faded out (smoothly from half of it) [m]; the
    /// detection looks for gaps up to it.
    pub cutoff: f64,
}

impl SqueezeFilm {
    /// No squeeze film (the paper's model).
    pub const OFF: SqueezeFilm = SqueezeFilm {
        enabled: false,
        half_width: 0.0,
        floor: 1.0,
        cutoff: 0.0,
    };

    /// Widest gap at which a force acts [m] (0 when disabled).
    pub fn reach(&self) -> f64 {
        if self.enabled {
            self.cutoff
        } else {
            0.0
        }
    }

    /// Damping coefficient c [N s/m] at the signed penetration δ (negative: gap −δ) for the
    /// relative principal radii (R_x, R_y) and the viscosity η [Pa s]: the force on the
    /// approaching bodies is c·δ̇ along the contact normal. Zero beyond the cutoff, and for
    /// non-positive or undefined radii (a concave-on-convex pairing's radii come from the
    /// detector only where they mean something).
    pub fn damping(&self, eta: f64, rx: f64, ry: f64, penetration: f64) -> f64 {
        let gap = (-penetration).max(0.0);
        let applies = self.enabled && rx > 0.0 && ry > 0.0 && gap < self.cutoff;
        if !applies {
            return 0.0;
        }
        let h = (gap * gap + self.floor * self.floor).sqrt();
        let w2 = self.half_width * self.half_width;
        let bounded = |r: f64| 1.0 / (1.0 / r + 2.0 * h / w2);
        let c = squeeze_coefficient(eta, bounded(rx) * bounded(ry), h);
        c * fade_out(gap, self.cutoff)
    }
}

/// c of F = c·ḣ for a sphere of radius R (here R² = R_x·R_y) at the gap h from a plane:
/// c = 6π η R² / h (Reynolds; Hamrock et al. 2004).
#[inline]
pub fn squeeze_coefficient(eta: f64, r_squared: f64, h: f64) -> f64 {
    6.0 * std::f64::consts::PI * eta * r_squared / h
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use std::f64::consts::PI;

    const ETA: f64 = 0.0137;

    fn film(half_width: f64) -> SqueezeFilm {
        SqueezeFilm {
            enabled: true,
            half_width,
            floor: 1e-12,
            cutoff: 1.0,
        }
    }

    /// A small sphere (R = 1 mm) far inside a wide face: the sphere–plane solution
    /// F = 6πηR²ḣ/h (Hamrock et al. 2004). The face bound changes each R by the factor
    /// 1/(1 + 2hR/w²), 1 − 8e-9 here, so c by 1.6e-8.
    #[test]
    fn small_sphere_gives_the_sphere_plane_solution() {
        let (r, h) = (1e-3, 1e-6);
        let c = film(0.5).damping(ETA, r, r, -h);
        let exact = 6.0 * PI * ETA * r * r / h;
        assert!((c / exact - 1.0).abs() < 2e-8, "{c} vs {exact}");
    }

    /// A flat end face against the face: the parallel-disc solution F = (3π/2)ηw⁴ḣ/h³
    /// (Hamrock et al. 2004). A curvature 1/R changes it by (1 + w²/(2hR))⁻²: 1 − 2.5e-10
    /// for R = 1e9 m. B1's 5 m end sphere at h = 1 µm is 5 % below the disc (factor 0.952).
    #[test]
    fn flat_face_gives_the_parallel_disc_solution() {
        let (w, h) = (0.5e-3, 1e-6);
        let c = film(w).damping(ETA, 1e9, 1e9, -h);
        let exact = 1.5 * PI * ETA * w.powi(4) / h.powi(3);
        assert!((c / exact - 1.0).abs() < 1e-6, "{c} vs {exact}");
        let b1 = film(w).damping(ETA, 5.0, 5.0, -h);
        assert!(
            (b1 / exact - 1.0 / 1.025f64.powi(2)).abs() < 1e-6,
            "{b1} vs {exact}"
        );
    }

    #[test]
    fn off_beyond_the_cutoff_and_for_undefined_radii() {
        let f = SqueezeFilm {
            cutoff: 20e-6,
            ..film(0.5e-3)
        };
        assert_eq!(f.damping(ETA, 1e-3, 1e-3, -20e-6), 0.0);
        assert_eq!(f.damping(ETA, 1e-3, 1e-3, -30e-6), 0.0);
        assert_eq!(f.damping(ETA, -1e-3, 1e-3, -1e-6), 0.0);
        assert_eq!(f.damping(ETA, f64::NAN, 1e-3, -1e-6), 0.0);
        assert_eq!(SqueezeFilm::OFF.damping(ETA, 1e-3, 1e-3, -1e-6), 0.0);
        // In contact (δ > 0) the gap is the floor σ, with the face-bounded radius.
        let sigma = 0.24e-6;
        let floored = SqueezeFilm { floor: sigma, ..f };
        let at_contact = floored.damping(ETA, 1e-3, 1e-3, 5e-6);
        let r = 1.0 / (1.0 / 1e-3 + 2.0 * sigma / (0.5e-3f64).powi(2));
        let exact = 6.0 * PI * ETA * r * r / sigma;
        assert!(
            (at_contact / exact - 1.0).abs() < 1e-12,
            "{at_contact} vs {exact}"
        );
    }

    proptest! {
        /// Finite, non-negative, and never growing as the gap opens (for any radii, floor
        /// and cutoff), and continuous at the cutoff.
        #[test]
        fn damping_falls_as_the_gap_opens(
            rx in 1e-4f64..10.0, ry in 1e-4f64..10.0, w in 1e-4f64..3e-3,
            floor in 1e-8f64..1e-6, cutoff in 1e-6f64..1e-4, g in 0.0f64..1.0, dg in 0.0f64..1.0,
        ) {
            let f = SqueezeFilm { enabled: true, half_width: w, floor, cutoff };
            let (g1, g2) = (g * cutoff, (g + dg).min(1.0) * cutoff);
            let (c1, c2) = (f.damping(ETA, rx, ry, -g1), f.damping(ETA, rx, ry, -g2));
            prop_assert!(c1.is_finite() && c1 >= 0.0 && c2 >= 0.0);
            prop_assert!(c2 <= c1 * (1.0 + 1e-12), "{c1} at {g1}, {c2} at {g2}");
            prop_assert!(f.damping(ETA, rx, ry, -cutoff * (1.0 - 1e-9)) <= 1e-6 * f.damping(ETA, rx, ry, 0.0));
        }
    }
}
