//! Lubricant rheology: ambient viscosity (Vogel, eq. 20), pressure–viscosity (Roelands,
//! eq. 19, with its exponent z fitted to the Dicke law of the oil's data sheet),
//! shear-thinning (Carreau, eq. 21), shear rate (eq. 22), Blok's reciprocal asymptotic
//! isoviscous pressure coefficient α* (eq. 31) and its temperature fit (eq. 32).
//!
//! Temperatures are in kelvin; Vogel's and Dicke's constants are given for the Celsius
//! temperature ϑ = T − 273.15 K, as the oil data sheets give them.

use crate::error::{require_positive, Error, Result};
use crate::numerics::{
    fit::{linear_least_squares, nelder_mead},
    quadrature::integrate_converged,
};

/// Kelvin at 0 °C.
pub const ZERO_CELSIUS: f64 = 273.15;
/// The ambient pressure of Blok's integral, eq. 31: 0.1 MPa.
pub const AMBIENT_PRESSURE: f64 = 0.1e6;

/// Vogel's law, paper eq. 20: η₀(ϑ) = K·exp(B/(ϑ + C)), ϑ in °C.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Vogel {
    /// K [Pa·s] (the paper's A).
    pub k: f64,
    /// B [K].
    pub b: f64,
    /// C [K], added to the Celsius temperature.
    pub c: f64,
}

impl Vogel {
    /// Ambient-pressure viscosity η₀ at absolute temperature T [K].
    pub fn viscosity(&self, temperature: f64) -> f64 {
        self.k * (self.b / (temperature - ZERO_CELSIUS + self.c)).exp()
    }

    /// dη₀/dT [Pa·s/K] (negative), for the thermal load parameter of eq. 48.
    pub fn viscosity_slope(&self, temperature: f64) -> f64 {
        let x = temperature - ZERO_CELSIUS + self.c;
        -self.viscosity(temperature) * self.b / (x * x)
    }

    /// The same law with K rescaled so that η₀(T_ref) = η_ref (used for B1, whose data
    /// sheet gives 84.5 mPa·s at 40 °C where the paper states 81 mPa·s).
    pub fn scaled_to(&self, temperature: f64, viscosity: f64) -> Self {
        Self {
            k: self.k * viscosity / self.viscosity(temperature),
            ..*self
        }
    }
}

/// Roelands' pressure–viscosity law, paper eq. 19:
/// η(p) = η_p·(η₀/η_p)^(((p_p − p)/p_p)^z), with the universal η_p = 0.0631 mPa·s and
/// p_p = −196 MPa (Hamrock, Schmid & Jacobson 2004, eq. 4.9).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Roelands {
    /// η_p [Pa·s].
    pub eta_p: f64,
    /// p_p [Pa] (negative).
    pub p_p: f64,
    /// Pressure–viscosity index z [-].
    pub z: f64,
}

impl Default for Roelands {
    fn default() -> Self {
        Self {
            eta_p: 0.0631e-3,
            p_p: -196e6,
            z: 0.6,
        }
    }
}

impl Roelands {
    /// η at gauge pressure p for the ambient viscosity η₀.
    pub fn viscosity(&self, pressure: f64, eta0: f64) -> f64 {
        let exponent = ((self.p_p - pressure) / self.p_p).powf(self.z);
        self.eta_p * (eta0 / self.eta_p).powf(exponent)
    }

    /// Initial pressure–viscosity coefficient d ln η/dp at p = 0: z·ln(η₀/η_p)/|p_p|.
    pub fn initial_coefficient(&self, eta0: f64) -> f64 {
        self.z * (eta0 / self.eta_p).ln() / (-self.p_p)
    }
}

/// Dicke's pressure–viscosity law, as given for the FVA reference oils (Schwarz et al.,
/// Lubricants 11 (2023) 369, table A1):
/// η = η₀·exp(p/(a₁ + a₂ϑ + (b₁ + b₂ϑ)·p)), ϑ in °C.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Dicke {
    /// a₁ [Pa].
    pub a1: f64,
    /// a₂ [Pa/K].
    pub a2: f64,
    /// b₁ [-].
    pub b1: f64,
    /// b₂ [1/K].
    pub b2: f64,
}

impl Dicke {
    /// η at gauge pressure p and temperature T for the ambient viscosity η₀.
    pub fn viscosity(&self, pressure: f64, temperature: f64, eta0: f64) -> f64 {
        let theta = temperature - ZERO_CELSIUS;
        eta0 * (pressure / (self.a1 + self.a2 * theta + (self.b1 + self.b2 * theta) * pressure))
            .exp()
    }

    /// Initial pressure–viscosity coefficient 1/(a₁ + a₂ϑ) [1/Pa].
    pub fn initial_coefficient(&self, temperature: f64) -> f64 {
        1.0 / (self.a1 + self.a2 * (temperature - ZERO_CELSIUS))
    }
}

/// How the Roelands index z is matched to a Dicke law.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ZFit {
    /// Equal initial slopes d ln η/dp at p = 0 (closed form).
    InitialSlope,
    /// Least squares in ln η over 0 … p_max (200 equally spaced pressures).
    LeastSquares,
}

/// Fits the Roelands index z to a Dicke law at temperature T.
pub fn fit_roelands_z(
    roelands: &Roelands,
    dicke: &Dicke,
    eta0: f64,
    temperature: f64,
    method: ZFit,
    p_max: f64,
) -> Result<f64> {
    require_positive("ambient viscosity", eta0)?;
    if eta0 <= roelands.eta_p {
        return Err(Error::InvalidParameter {
            name: "ambient viscosity",
            value: eta0,
            rule: "must exceed Roelands' eta_p (lubricant.roelands.eta_p)",
        });
    }
    let z_slope =
        dicke.initial_coefficient(temperature) * (-roelands.p_p) / (eta0 / roelands.eta_p).ln();
    match method {
        ZFit::InitialSlope => Ok(z_slope),
        ZFit::LeastSquares => {
            require_positive("fit pressure maximum", p_max)?;
            let pressures: Vec<f64> = (1..=200).map(|i| p_max * i as f64 / 200.0).collect();
            let target: Vec<f64> = pressures
                .iter()
                .map(|&p| dicke.viscosity(p, temperature, eta0).ln())
                .collect();
            let cost = |z: &[f64]| {
                let r = Roelands {
                    z: z[0],
                    ..*roelands
                };
                pressures
                    .iter()
                    .zip(&target)
                    .map(|(&p, t)| (r.viscosity(p, eta0).ln() - t).powi(2))
                    .sum::<f64>()
            };
            let (z, _) = nelder_mead(cost, &[z_slope], &[0.05], 1e-24, 2000);
            Ok(z[0])
        }
    }
}

/// Carreau's shear-thinning law, paper eq. 21:
/// τ = γ̇η·(1 + (ηγ̇/τ₀)²)^((n−1)/2).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Carreau {
    /// Critical shear stress τ₀ [Pa].
    pub tau0: f64,
    /// Power-law index n (0 < n ≤ 1).
    pub n: f64,
}

impl Carreau {
    /// Shear stress τ for viscosity η and shear rate γ̇ (odd in γ̇).
    #[inline]
    pub fn shear_stress(&self, eta: f64, shear_rate: f64) -> f64 {
        let newtonian = eta * shear_rate;
        let x = newtonian / self.tau0;
        newtonian * (0.5 * (self.n - 1.0) * (x * x).ln_1p()).exp()
    }
}

/// Shear rate across the film, paper eq. 22: γ̇ ≈ u_rel/h_c.
#[inline]
pub fn shear_rate(sliding_speed: f64, film_thickness: f64) -> f64 {
    sliding_speed / film_thickness
}

/// Blok's reciprocal asymptotic isoviscous pressure coefficient, paper eq. 31:
/// α* = [∫_{0.1 MPa}^∞ η(0.1 MPa)/η(p) dp]⁻¹, by converged Gauss–Legendre quadrature
/// after the map p = p_a + p_s·t/(1 − t), t ∈ [0, 1) (p_s a pressure scale).
pub fn blok_alpha_star(viscosity: impl Fn(f64) -> f64, pressure_scale: f64) -> f64 {
    let eta_a = viscosity(AMBIENT_PRESSURE);
    let integrand = |t: f64| {
        let one_minus = 1.0 - t;
        let p = AMBIENT_PRESSURE + pressure_scale * t / one_minus;
        let ratio = eta_a / viscosity(p);
        if ratio.is_finite() {
            ratio * pressure_scale / (one_minus * one_minus)
        } else {
            0.0
        }
    };
    1.0 / integrate_converged(0.0, 1.0 - 1e-12, 1e-12, integrand)
}

/// The temperature fit of α*, paper eq. 32: α*(T) = c₁e^(c₂T) + c₃e^(c₄T), T in K.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AlphaStarFit {
    /// c₁ [1/Pa].
    pub c1: f64,
    /// c₂ [1/K].
    pub c2: f64,
    /// c₃ [1/Pa].
    pub c3: f64,
    /// c₄ [1/K].
    pub c4: f64,
    /// Largest relative error of the fit against eq. 31 on its temperature range.
    pub max_relative_error: f64,
}

impl AlphaStarFit {
    /// α* at temperature T [K].
    pub fn alpha_star(&self, temperature: f64) -> f64 {
        self.c1 * (self.c2 * temperature).exp() + self.c3 * (self.c4 * temperature).exp()
    }

    /// Fits eq. 32 to Blok's α* of `alpha_star_at` on [t_min, t_max] (41 temperatures):
    /// variable projection, i.e. c₁, c₃ by linear least squares for each (c₂, c₄) and
    /// (c₂, c₄) by Nelder–Mead, minimising the relative residuals, from several starts.
    pub fn fit(alpha_star_at: impl Fn(f64) -> f64, t_min: f64, t_max: f64) -> Result<Self> {
        require_positive("alpha* fit t_min", t_min)?;
        if t_max.partial_cmp(&t_min) != Some(std::cmp::Ordering::Greater) || !t_max.is_finite() {
            return Err(Error::InvalidParameter {
                name: "alpha* fit t_max",
                value: t_max,
                rule: "must be finite and greater than t_min",
            });
        }
        let n = 41;
        let t_mid = 0.5 * (t_min + t_max);
        let temps: Vec<f64> = (0..n)
            .map(|i| t_min + (t_max - t_min) * i as f64 / (n - 1) as f64)
            .collect();
        let values: Vec<f64> = temps.iter().map(|&t| alpha_star_at(t)).collect();
        if values.iter().any(|v| !(v.is_finite() && *v > 0.0)) {
            return Err(Error::NoConvergence {
                what: "alpha* fit",
                detail: "alpha* is not finite and positive over the fit range".into(),
            });
        }
        // For given rates, the best amplitudes (relative residuals: rows divided by α*).
        let amplitudes = |rates: &[f64]| -> Vec<f64> {
            let cols: Vec<Vec<f64>> = rates
                .iter()
                .map(|r| {
                    temps
                        .iter()
                        .zip(&values)
                        .map(|(t, v)| (r * (t - t_mid)).exp() / v)
                        .collect()
                })
                .collect();
            linear_least_squares(&cols, &vec![1.0; n])
        };
        let residual = |rates: &[f64]| -> f64 {
            let c = amplitudes(rates);
            temps
                .iter()
                .zip(&values)
                .map(|(t, v)| {
                    let fit = c[0] * (rates[0] * (t - t_mid)).exp()
                        + c[1] * (rates[1] * (t - t_mid)).exp();
                    (fit / v - 1.0).powi(2)
                })
                .sum()
        };
        // A one-exponential slope as the scale of the starting rates.
        let slope = (values[n - 1] / values[0]).ln() / (t_max - t_min);
        let scale = slope.abs().max(1e-4);
        let mut best: Option<(Vec<f64>, f64)> = None;
        for (r0, r1) in [(1.0, 0.0), (2.0, 0.3), (0.5, 3.0), (1.0, -1.0), (3.0, -0.5)] {
            let start = [slope * r0, slope * r1 + 1e-3 * scale];
            let (x, f) = nelder_mead(residual, &start, &[0.3 * scale, 0.3 * scale], 1e-30, 4000);
            if best.as_ref().is_none_or(|(_, fb)| f < *fb) {
                best = Some((x, f));
            }
        }
        let (rates, _) = best.expect("at least one start");
        let c = amplitudes(&rates);
        let mut fit = Self {
            c1: c[0] * (-rates[0] * t_mid).exp(),
            c2: rates[0],
            c3: c[1] * (-rates[1] * t_mid).exp(),
            c4: rates[1],
            max_relative_error: 0.0,
        };
        fit.max_relative_error = (0..=200)
            .map(|i| {
                let t = t_min + (t_max - t_min) * i as f64 / 200.0;
                (fit.alpha_star(t) / alpha_star_at(t) - 1.0).abs()
            })
            .fold(0.0, f64::max);
        Ok(fit)
    }
}

/// Lubricant density ρ(T) = ρ₁₅ + slope·(T − 288.15 K).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Density {
    /// Density at 15 °C [kg/m³].
    pub rho_15: f64,
    /// dρ/dT [kg/(m³·K)].
    pub slope: f64,
}

impl Density {
    /// ρ at temperature T [K].
    pub fn at(&self, temperature: f64) -> f64 {
        self.rho_15 + self.slope * (temperature - (ZERO_CELSIUS + 15.0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// FVA 3 (Schwarz et al., Lubricants 2023, 11, 369, table A1).
    pub(crate) fn fva3_vogel() -> Vogel {
        Vogel {
            k: 0.062e-3,
            b: 1021.7,
            c: 101.5517,
        }
    }

    pub(crate) fn fva3_dicke() -> Dicke {
        Dicke {
            a1: 327.7918e5,
            a2: 2.9862e5,
            b1: 4.419e-3,
            b2: 3.0115e-4,
        }
    }

    #[test]
    fn vogel_fva3_at_40_celsius() {
        // published-values.md: η₀(40 °C) = 84.54 mPa·s.
        let eta = fva3_vogel().viscosity(313.15);
        assert!((eta / 84.54e-3 - 1.0).abs() < 1e-4, "{eta}");
        let scaled = fva3_vogel().scaled_to(313.15, 81e-3);
        assert!((scaled.viscosity(313.15) / 81e-3 - 1.0).abs() < 1e-12);
    }

    #[test]
    fn vogel_slope_matches_finite_difference() {
        let v = fva3_vogel();
        let fd = (v.viscosity(353.15 + 1e-3) - v.viscosity(353.15 - 1e-3)) / 2e-3;
        assert!((v.viscosity_slope(353.15) / fd - 1.0).abs() < 1e-7);
    }

    #[test]
    fn dicke_initial_coefficient_at_40_celsius() {
        // published-values.md: α = 1/(a1 + a2 ϑ) = 22.36 GPa⁻¹ at 40 °C.
        let a = fva3_dicke().initial_coefficient(313.15);
        assert!((a / 22.36e-9 - 1.0).abs() < 2e-4, "{a}");
    }

    #[test]
    fn roelands_z_for_b1() {
        // B1.md: the initial-slope match gives z ≈ 0.62 at 80 °C.
        let vogel = fva3_vogel().scaled_to(313.15, 81e-3);
        let eta0 = vogel.viscosity(353.15);
        let r = Roelands::default();
        let z = fit_roelands_z(&r, &fva3_dicke(), eta0, 353.15, ZFit::InitialSlope, 1e9).unwrap();
        assert!((z - 0.62).abs() < 0.005, "z = {z}");
        // And the slopes then agree by construction.
        let rz = Roelands { z, ..r };
        let fd = (rz.viscosity(1e3, eta0).ln() - rz.viscosity(0.0, eta0).ln()) / 1e3;
        assert!((fd / fva3_dicke().initial_coefficient(353.15) - 1.0).abs() < 1e-4);
        let zl = fit_roelands_z(&r, &fva3_dicke(), eta0, 353.15, ZFit::LeastSquares, 1e9).unwrap();
        // The least-squares z is the minimum of its cost by brute force: a scan over
        // 0.5 … 0.8 in steps of 1e-5 (the cost written out here again, 200 pressures to
        // 1 GPa) finds it within a step (both 0.63628; tests/test_config.py scans the same
        // cost in numpy).
        let cost = |z: f64| {
            let rz = Roelands { z, ..r };
            (1..=200)
                .map(|i| 1e9 * i as f64 / 200.0)
                .map(|p| {
                    let dicke = fva3_dicke().viscosity(p, 353.15, eta0).ln();
                    (rz.viscosity(p, eta0).ln() - dicke).powi(2)
                })
                .sum::<f64>()
        };
        let scan = (0..=30_000)
            .map(|k| 0.5 + 1e-5 * k as f64)
            .min_by(|a, b| cost(*a).total_cmp(&cost(*b)))
            .unwrap();
        assert!(
            (zl - scan).abs() <= 1e-5,
            "least-squares z = {zl}, scan {scan}"
        );
    }

    #[test]
    fn roelands_is_eta0_at_zero_pressure() {
        let r = Roelands::default();
        assert!((r.viscosity(0.0, 0.0165) / 0.0165 - 1.0).abs() < 1e-14);
    }

    #[test]
    fn blok_alpha_star_equals_barus_coefficient() {
        // For Barus' law η = η₀ e^(αp) the integral of eq. 31 is 1/α exactly (the ambient
        // offset cancels): α* = α.
        let alpha = 2e-8;
        let a = blok_alpha_star(|p| 0.01 * (alpha * p).exp(), 50e6);
        assert!((a / alpha - 1.0).abs() < 1e-9, "{a}");
    }

    #[test]
    fn blok_alpha_star_below_initial_coefficient_for_roelands() {
        // Roelands with z < 1 bends below Barus: α* lies below the initial slope
        // (Vergne & Bair, Tribol. Lett. 54 (2014) 1).
        let r = Roelands {
            z: 0.62,
            ..Roelands::default()
        };
        let eta0 = 0.0165;
        let a = blok_alpha_star(|p| r.viscosity(p, eta0), 50e6);
        let a0 = r.initial_coefficient(eta0);
        assert!(a < a0 && a > 0.5 * a0, "α* = {a}, α0 = {a0}");
    }

    #[test]
    fn alpha_star_fit_reproduces_the_integral() {
        let vogel = fva3_vogel().scaled_to(313.15, 81e-3);
        let r = Roelands {
            z: 0.62,
            ..Roelands::default()
        };
        let at = |t: f64| blok_alpha_star(|p| r.viscosity(p, vogel.viscosity(t)), 50e6);
        let fit = AlphaStarFit::fit(at, 293.15, 413.15).unwrap();
        assert!(fit.max_relative_error < 2e-3, "{fit:?}");
    }

    proptest! {
        #[test]
        fn carreau_limits(log_eta in -3.0..3.0f64, log_rate in 0.0..9.0f64) {
            let c = Carreau { tau0: 5e6, n: 0.5 };
            let eta = 10f64.powf(log_eta);
            let rate = 10f64.powf(log_rate);
            let tau = c.shear_stress(eta, rate);
            // Never above Newtonian, odd, and power-law at large stress:
            // τ → τ₀^(1−n)(ηγ̇)^n (Bird, Armstrong & Hassager 1987, eq. 4.1-9 limit).
            prop_assert!(tau <= eta * rate * (1.0 + 1e-12));
            prop_assert!((c.shear_stress(eta, -rate) + tau).abs() <= 1e-12 * tau);
            let x = eta * rate / c.tau0;
            if x < 1e-3 { prop_assert!((tau / (eta * rate) - 1.0).abs() < 1e-6); }
            if x > 1e3 {
                let power = c.tau0.powf(1.0 - c.n) * (eta * rate).powf(c.n);
                prop_assert!((tau / power - 1.0).abs() < 1e-5);
            }
        }
    }
}
