//! The normal load of a distributed roller end–flange contact (not in the paper): the
//! overlap field g of [`crate::contact::distributed`] on a Winkler foundation (Johnson,
//! *Contact Mechanics*, 1985, sect. 5.8): pressure p = K g, so the contact's potential is
//! U = K ∫ g²/2 dA and its force K ∫ g n dA, the gradient of U. Being a potential's
//! gradient, the law has a symmetric stiffness: a roller end rocking on the flange is never
//! pushed on by its own contact (an area-dependent law, such as a flat punch of the
//! support's current area, is not, and drove B1's unloaded rollers unstable at 7e4 1/s).
//!
//! The modulus K is that of the flat face the law is for: a rigid flat punch of area A_c
//! pressed by δ into an elastic half-space carries F = 2 a E* δ with a = √(A_c/π)
//! (Boussinesq; Johnson eq. 3.35), E* = E'/2, so the foundation that carries the same load
//! at the same overlap has K = E'/√(π A_c), A_c the area of the end face that lies on the
//! flange's face when the end lies flat on it
//! ([`crate::geometry::end_flange::face_contact_area`]).

use std::f64::consts::PI;

/// K = E'/√(π A_c) [Pa/m] for the face contact area `face_area` [m²].
pub fn foundation_modulus(e_prime: f64, face_area: f64) -> f64 {
    e_prime / (PI * face_area).sqrt()
}

/// The normal force K V [N] of overlap volume V = ∫ g dA [m³] (0 for none).
pub fn foundation_force(modulus: f64, volume: f64) -> f64 {
    modulus * volume.max(0.0)
}

/// The elastic energy K ∫ Φ dA [J] of the energy integral ∫ Φ dA [m⁴], Φ(g) = ∫ p dg the
/// load's integral over the overlap (g²/2 for smooth surfaces,
/// [`crate::contact::distributed::Asperities`]).
pub fn foundation_energy(modulus: f64, energy_integral: f64) -> f64 {
    modulus * energy_integral.max(0.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tribology::hertz::{EllipticalContact, EllipticalMethod};

    const E_PRIME: f64 = 230.77e9;

    #[test]
    fn flat_face_of_the_contact_area_is_boussinesq() {
        // Johnson eq. 3.35: F = 2 a E* δ for a circular punch of radius a, here the face
        // contact area itself pressed uniformly by δ (V = A_c δ).
        for (a, delta) in [(0.5e-3, 1e-6), (2e-3, 3e-7)] {
            let area = PI * a * a;
            let k = foundation_modulus(E_PRIME, area);
            let f = foundation_force(k, area * delta);
            let exact = 2.0 * a * 0.5 * E_PRIME * delta;
            assert!((f / exact - 1.0).abs() < 1e-14, "{f} vs {exact}");
        }
    }

    #[test]
    fn force_is_the_gradient_of_the_energy() {
        // A sphere of radius R pressed by δ: V = π R δ², ∫g²/2 dA = π R δ³/3 (the overlap
        // δ − r²/2R over r² < 2Rδ). dU/dδ = K π R δ² = K V.
        let (r, k) = (5.0, foundation_modulus(E_PRIME, 4e-7));
        let energy = |d: f64| foundation_energy(k, PI * r * d.powi(3) / 3.0);
        for delta in [0.3e-6, 2e-6] {
            let h = 1e-12;
            let slope = (energy(delta + h) - energy(delta - h)) / (2.0 * h);
            let force = foundation_force(k, PI * r * delta * delta);
            assert!((slope / force - 1.0).abs() < 1e-6, "{slope} vs {force}");
        }
    }

    #[test]
    fn softer_than_hertz_on_a_point() {
        // The foundation stands for B1's 0.40 mm² face (A_c). On a point contact, a sphere
        // of relative radius 0.5 mm (the edge torus) pressed by 1 µm, it is softer than
        // Hertz ((4/3) E* √R δ^1.5, Johnson eq. 4.23), π K R δ² against it: 0.094 of it.
        let k = foundation_modulus(E_PRIME, 4.0e-7);
        let (r, delta) = (0.5e-3, 1e-6);
        let winkler = foundation_force(k, PI * r * delta * delta);
        let hertz = EllipticalContact::new(r, r, E_PRIME, EllipticalMethod::Exact).force(delta);
        let closed_form = PI * k * r * delta.powf(0.5) / (4.0 / 3.0 * 0.5 * E_PRIME * r.sqrt());
        // The exact Hertz solution at α = 1 is Johnson's closed form (K = E = π/2): the
        // ratio holds to round-off.
        assert!((winkler / hertz / closed_form - 1.0).abs() < 1e-9);
        assert!((closed_form - 0.0942).abs() < 1e-3, "{closed_form}");
    }
}
