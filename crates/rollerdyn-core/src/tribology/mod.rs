//! Tribology: the force laws of the reference paper, sect. 3.1.2 – 3.3, as pure
//! functions of the contact's state.
//!
//! * [`hertz`]: elliptical (eqs. 5–8, 13–15) and line (eqs. 16–18) Hertz contact.
//! * [`line_contact`]: Tripp's load–deflection law (eqs. 9, 10) and its power-law fit (eq. 11).
//! * [`lubricant`]: Vogel (20), Roelands (19), Dicke, Carreau (21), shear rate (22),
//!   Blok's α* (31) and its temperature fit (32).
//! * [`film`]: Moes (33–38), zero-entrainment film (39–44), Chittenden (45, 46),
//!   thermal correction (47–49).
//! * [`traction`]: limiting shear stress (50) and the EHL tangential force.
//! * [`friction`]: boundary friction with micro-slip (51, 52) and Zhou–Hoeprich load
//!   sharing (53, 54).
//! * [`rolling_resistance`]: hysteresis (55) and EHL (56, 57) rolling resistance.
//! * [`squeeze`]: squeeze-film damping at the flanges (not in the paper; Reynolds).
//! * [`hydrodynamic`]: the rigid-isoviscous film of line contacts across a gap (not in
//!   the paper; Martin, Reynolds).
//! * [`drag`]: drag of the oil–air mixture on a roller (not in the paper; Harris &
//!   Kotzalas).

pub mod drag;
pub mod film;
pub mod foundation;
pub mod friction;
pub mod hertz;
pub mod hydrodynamic;
pub mod line_contact;
pub mod lubricant;
pub mod rolling_resistance;
pub mod squeeze;
pub mod traction;

/// Effective Young's modulus E' = 2 / ((1 − ν₁²)/E₁ + (1 − ν₂²)/E₂) (paper, nomenclature;
/// Hamrock, Schmid & Jacobson 2004). Note E' = 2E* in Johnson's notation.
pub fn effective_modulus(e1: f64, nu1: f64, e2: f64, nu2: f64) -> f64 {
    2.0 / ((1.0 - nu1 * nu1) / e1 + (1.0 - nu2 * nu2) / e2)
}

/// Equivalent radius R' = (1/R_x + 1/R_y)⁻¹ (paper, nomenclature).
pub fn equivalent_radius(rx: f64, ry: f64) -> f64 {
    1.0 / (1.0 / rx + 1.0 / ry)
}

/// An elastic body's material: Young's modulus E and Poisson's ratio ν.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Elastic {
    /// Young's modulus E [Pa].
    pub youngs_modulus: f64,
    /// Poisson's ratio ν [-].
    pub poisson_ratio: f64,
}

impl Elastic {
    /// The compliance factor (1 − ν²)/E [1/Pa].
    pub fn compliance(&self) -> f64 {
        (1.0 - self.poisson_ratio * self.poisson_ratio) / self.youngs_modulus
    }

    /// E' of this body against another (see [`effective_modulus`]).
    pub fn effective_modulus_with(&self, other: &Elastic) -> f64 {
        2.0 / (self.compliance() + other.compliance())
    }
}
