//! Load–deflection of the line contacts (roller–race, roller–roller).
//!
//! Tripp's approach (J. H. Tripp, *Hertzian Contact in Two and Three Dimensions*, NASA
//! TP-2473, 1985; paper eqs. 9, 10, recommended by Houpert, J. Tribol. 123 (2001) 582)
//! gives the deflection of a line contact from its load, but cannot be inverted in closed
//! form. The dynamic model therefore uses the power law of paper eq. 11,
//! F_n = (l/k₁) δ^(1/k₂), whose k₁, k₂ are fitted here to Tripp over the load range the
//! bearing sees ([`LinePowerLaw::fit`]), with the fit's error reported.
//!
//! Tripp's deflection depends on the load only through the load per unit length
//! q = F/l, so k₁, k₂ do not depend on the slice width.
//!
//! Roller–roller contacts: the paper says they are "modelled according to eq. 10", but
//! eq. 10 needs the wall thickness t of a ring, which a roller does not have. Two rollers
//! are two convex cylinders, the case of eq. 9, which is what this code uses (see
//! docs/model.md).

use super::{hertz::line_half_width, Elastic};
use crate::error::{require_positive, Error, Result};
use crate::numerics::{fit::line_fit, roots::brent};
use std::f64::consts::PI;

/// The body a roller presses against in a line contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Counterface {
    /// A convex cylinder of radius R₂: the inner raceway or another roller (eq. 9).
    Convex {
        /// Radius R₂ [m].
        radius: f64,
    },
    /// The concave outer raceway of radius R₂ in a ring of wall thickness t (eq. 10).
    OuterRing {
        /// Raceway radius [m].
        raceway_radius: f64,
        /// Wall thickness t [m].
        wall_thickness: f64,
    },
}

/// A roller–counterface line contact for Tripp's law.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TrippContact {
    /// Roller radius R₁ [m].
    pub roller_radius: f64,
    /// Roller material.
    pub roller: Elastic,
    /// The other body's geometry.
    pub counterface: Counterface,
    /// The other body's material.
    pub counter: Elastic,
}

impl TrippContact {
    /// Validated contact.
    pub fn new(
        roller_radius: f64,
        roller: Elastic,
        counterface: Counterface,
        counter: Elastic,
    ) -> Result<Self> {
        require_positive("roller radius", roller_radius)?;
        match counterface {
            Counterface::Convex { radius } => {
                require_positive("counterface radius", radius)?;
            }
            Counterface::OuterRing {
                raceway_radius,
                wall_thickness,
            } => {
                require_positive("outer ring wall thickness", wall_thickness)?;
                if raceway_radius.partial_cmp(&roller_radius) != Some(std::cmp::Ordering::Greater) {
                    return Err(Error::InvalidParameter {
                        name: "outer raceway radius",
                        value: raceway_radius,
                        rule: "must exceed the roller radius",
                    });
                }
            }
        }
        Ok(Self {
            roller_radius,
            roller,
            counterface,
            counter,
        })
    }

    /// Equivalent radius R' of the pair (negative curvature for the concave raceway).
    pub fn equivalent_radius(&self) -> f64 {
        let r1 = self.roller_radius;
        match self.counterface {
            Counterface::Convex { radius } => r1 * radius / (r1 + radius),
            Counterface::OuterRing { raceway_radius, .. } => {
                r1 * raceway_radius / (raceway_radius - r1)
            }
        }
    }

    /// Effective modulus E'.
    pub fn e_prime(&self) -> f64 {
        self.roller.effective_modulus_with(&self.counter)
    }

    /// Deflection δ from the load per unit length q = F/l, paper eq. 9 (convex
    /// counterface) or eq. 10 (outer ring), with the Hertz half-width a of eq. 18.
    pub fn deflection(&self, load_per_length: f64) -> f64 {
        if load_per_length <= 0.0 {
            return 0.0;
        }
        let a = line_half_width(
            load_per_length,
            1.0,
            self.equivalent_radius(),
            self.e_prime(),
        );
        let roller_term = self.roller.compliance() * ((4.0 * self.roller_radius / a).ln() - 0.5);
        let counter_term = match self.counterface {
            Counterface::Convex { radius } => {
                self.counter.compliance() * ((4.0 * radius / a).ln() - 0.5)
            }
            Counterface::OuterRing { wall_thickness, .. } => {
                let nu = self.counter.poisson_ratio;
                self.counter.compliance()
                    * ((2.0 * wall_thickness / a).ln() - nu / (2.0 * (1.0 - nu)))
            }
        };
        2.0 * load_per_length / PI * (roller_term + counter_term)
    }

    /// Load per unit length from deflection: Tripp's law inverted by a bracketed root
    /// search (the slow, exact reference of eq. 11).
    pub fn load_per_length(&self, deflection: f64) -> Result<f64> {
        if deflection <= 0.0 {
            return Ok(0.0);
        }
        // Bracket in log q between 1 mN/m and 100 kN/mm; above that the Hertz half-width
        // reaches the roller radius and Tripp's law has no meaning.
        let target = deflection.ln();
        let residual = |log_q: f64| self.deflection(log_q.exp()).ln() - target;
        let log_q = brent(1e-3f64.ln(), 1e8f64.ln(), 1e-13, residual)?;
        Ok(log_q.exp())
    }
}

/// The power law of paper eq. 11, F_n = (l/k₁)·δ^(1/k₂), with its fit report.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinePowerLaw {
    /// k₁ [m^(1/k₂)·m/N].
    pub k1: f64,
    /// k₂ [-] (about 0.9 for steel, cf. Palmgren's δ ∝ Q^0.9).
    pub k2: f64,
}

/// How well a [`LinePowerLaw`] reproduces Tripp over its fit range.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FitReport {
    /// Smallest load per unit length of the range [N/m].
    pub load_min: f64,
    /// Largest load per unit length of the range [N/m].
    pub load_max: f64,
    /// max |F_fit(δ)/F_Tripp(δ) − 1| over the range (force at equal deflection).
    pub max_force_error: f64,
    /// max |δ_fit(q)/δ_Tripp(q) − 1| over the range (deflection at equal load).
    pub max_deflection_error: f64,
}

impl LinePowerLaw {
    /// Normal force of a slice of length `length` at deflection δ (eq. 11); zero for δ ≤ 0.
    #[inline]
    pub fn force(&self, deflection: f64, length: f64) -> f64 {
        if deflection <= 0.0 {
            return 0.0;
        }
        length / self.k1 * deflection.powf(1.0 / self.k2)
    }

    /// The inverse: deflection for a force on a slice of length `length`.
    pub fn deflection(&self, force: f64, length: f64) -> f64 {
        if force <= 0.0 {
            return 0.0;
        }
        (self.k1 * force / length).powf(self.k2)
    }

    /// The sample counts [`Self::fit`] takes.
    pub const SAMPLES: std::ops::RangeInclusive<usize> = 2..=10_000;

    /// Fits k₁, k₂ to Tripp over loads per unit length in [q_min, q_max] (log-spaced
    /// samples), minimising the largest relative force error: a least-squares line in
    /// (ln δ, ln q), then Lawson's iteratively reweighted least squares towards the
    /// minimax fit (Lawson 1961; Rice & Usow, Math. Comp. 22 (1968) 118).
    pub fn fit(
        contact: &TrippContact,
        q_min: f64,
        q_max: f64,
        samples: usize,
    ) -> Result<(Self, FitReport)> {
        if !Self::SAMPLES.contains(&samples) {
            return Err(Error::InvalidParameter {
                name: "line fit samples",
                value: samples as f64,
                rule: "must lie in 2 ..= 10000",
            });
        }
        require_positive("line fit load_min", q_min)?;
        if q_max.partial_cmp(&q_min) != Some(std::cmp::Ordering::Greater) || !q_max.is_finite() {
            return Err(Error::InvalidParameter {
                name: "line fit load_max",
                value: q_max,
                rule: "must be finite and greater than load_min",
            });
        }
        let n = samples.max(8);
        let log_q: Vec<f64> = (0..n)
            .map(|i| q_min.ln() + (q_max / q_min).ln() * i as f64 / (n - 1) as f64)
            .collect();
        let log_d: Vec<f64> = log_q
            .iter()
            .map(|lq| contact.deflection(lq.exp()).ln())
            .collect();
        let mut weights = vec![1.0; n];
        let mut best: Option<(Self, f64)> = None;
        for _ in 0..200 {
            let (slope, intercept) = line_fit(&log_d, &log_q, &weights);
            let law = Self {
                k1: (-intercept).exp(),
                k2: 1.0 / slope,
            };
            let errors: Vec<f64> = log_q
                .iter()
                .zip(&log_d)
                .map(|(lq, ld)| (slope * ld + intercept - lq).abs())
                .collect();
            let worst = errors.iter().cloned().fold(0.0, f64::max);
            if best.is_none_or(|(_, e)| worst < e) {
                best = Some((law, worst));
            }
            let total: f64 = weights.iter().zip(&errors).map(|(w, e)| w * e).sum();
            if total <= 0.0 {
                break;
            }
            for (w, e) in weights.iter_mut().zip(&errors) {
                *w *= e / total;
            }
        }
        let (law, _) = best.expect("at least one fit");
        let report = law.report(contact, q_min, q_max);
        Ok((law, report))
    }

    /// Errors of this law against Tripp on a dense log-spaced sample of [q_min, q_max].
    pub fn report(&self, contact: &TrippContact, q_min: f64, q_max: f64) -> FitReport {
        let n = 400;
        let mut max_force_error: f64 = 0.0;
        let mut max_deflection_error: f64 = 0.0;
        for i in 0..n {
            let q = q_min * (q_max / q_min).powf(i as f64 / (n - 1) as f64);
            let d = contact.deflection(q);
            max_force_error = max_force_error.max((self.force(d, 1.0) / q - 1.0).abs());
            max_deflection_error =
                max_deflection_error.max((self.deflection(q, 1.0) / d - 1.0).abs());
        }
        FitReport {
            load_min: q_min,
            load_max: q_max,
            max_force_error,
            max_deflection_error,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    const STEEL: Elastic = Elastic {
        youngs_modulus: 210e9,
        poisson_ratio: 0.3,
    };

    fn b1_inner() -> TrippContact {
        TrippContact::new(
            2.2475e-3,
            STEEL,
            Counterface::Convex { radius: 10e-3 },
            STEEL,
        )
        .unwrap()
    }

    fn b1_outer() -> TrippContact {
        TrippContact::new(
            2.2475e-3,
            STEEL,
            Counterface::OuterRing {
                raceway_radius: 14.5e-3,
                wall_thickness: 2.5e-3,
            },
            STEEL,
        )
        .unwrap()
    }

    #[test]
    fn tripp_is_close_to_palmgren() {
        // Palmgren (Harris & Kotzalas, Rolling Bearing Analysis, 5th ed., eq. 6.40):
        // δ = 3.84e-5 Q^0.9 / l^0.8 (mm, N): Q = 1000 N, l = 10 mm → 3.050 µm for one
        // roller–raceway contact. Palmgren is radius-free, Tripp is not: Tripp's δ moves by
        // about 5 % per doubling of the raceway radius (−4.5 % at 5 mm, +5.7 % at 20 mm),
        // and at B1's inner race (10 mm) the two agree to 0.28 % (measured), so 1 % holds
        // B1's radii.
        let q = 1000.0 / 0.01;
        let d = b1_inner().deflection(q);
        assert!((d / 3.050e-6 - 1.0).abs() < 0.01, "Tripp inner δ = {d}");
    }

    #[test]
    fn power_law_within_one_percent_of_tripp_over_b1_loads() {
        // B1's heaviest roller carries about 4.08 F_r/Z = 1.2 kN over 4 mm of straight
        // length (Stribeck/Harris): q_ref ≈ 300 N/mm; race contacts are fitted over
        // [0.1, 2]·q_ref = 30 … 600 N/mm (the default of rollerdyn.model).
        for contact in [b1_inner(), b1_outer()] {
            let (law, report) = LinePowerLaw::fit(&contact, 3e4, 6e5, 64).unwrap();
            assert!(report.max_force_error < 0.01, "{report:?}");
            assert!(law.k2 > 0.85 && law.k2 < 0.95, "k2 = {}", law.k2);
        }
    }

    proptest! {
        #[test]
        fn inverse_of_tripp_round_trips(log_q in 2.0..7.0f64) {
            let c = b1_outer();
            let q = 10f64.powf(log_q);
            let back = c.load_per_length(c.deflection(q)).unwrap();
            prop_assert!((back / q - 1.0).abs() < 1e-10);
        }

        #[test]
        fn deflection_grows_with_load(log_q in 2.0..7.0f64) {
            let c = b1_inner();
            let q = 10f64.powf(log_q);
            prop_assert!(c.deflection(q * 1.01) > c.deflection(q));
        }
    }

    #[test]
    fn refuses_bad_geometry() {
        assert!(
            TrippContact::new(-1.0, STEEL, Counterface::Convex { radius: 1.0 }, STEEL).is_err()
        );
        let bad = Counterface::OuterRing {
            raceway_radius: 1e-3,
            wall_thickness: 1e-3,
        };
        assert!(TrippContact::new(2e-3, STEEL, bad, STEEL).is_err());
    }
}
