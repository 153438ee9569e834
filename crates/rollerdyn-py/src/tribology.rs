//! Bindings of the force laws (core `tribology`, paper sect. 3.1.2 – 3.3): Hertz and
//! Brewe–Hamrock (eqs. 5–8, 13–18), Tripp and the power law of eq. 11, the lubricant's
//! viscosity (eqs. 19–21, 31, 32), the films (eqs. 33–48), boundary friction (eqs. 51–53)
//! and rolling resistance (eqs. 55–57). Array arguments are one-dimensional float64
//! arrays of equal length (the Python wrappers in `rollerdyn.tribology` broadcast and
//! reshape); scalars are model parameters.

use crate::convert::{add_functions, choose, core_err, count, elementwise, set_fields};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{IntoPyDict, PyDict};
use rollerdyn_core::numerics::elliptic::complete_elliptic_integrals;
use rollerdyn_core::tribology::{
    self as tri,
    film::FilmInputs,
    friction::{BoundaryFriction, LoadSharing},
    hertz::{EllipticalContact, EllipticalMethod, Ellipticity},
    line_contact::{Counterface, LinePowerLaw, TrippContact},
    lubricant::{self, AlphaStarFit, Carreau, Dicke, Roelands, Vogel, ZFit},
    rolling_resistance, Elastic,
};

fn method(name: &str) -> PyResult<EllipticalMethod> {
    choose(
        name,
        &[
            ("brewe_hamrock", EllipticalMethod::BreweHamrock),
            ("exact", EllipticalMethod::Exact),
        ],
        |other| format!("method = {other:?}: must be \"brewe_hamrock\" or \"exact\""),
    )
}

fn elastic(e: f64, nu: f64) -> Elastic {
    Elastic {
        youngs_modulus: e,
        poisson_ratio: nu,
    }
}

/// The Tripp contact of a roller (radius, material) and its counterface ("convex" or
/// "outer_ring", radius, wall thickness, material).
fn tripp_contact(
    roller_radius: f64,
    roller: Elastic,
    counterface: &str,
    counter_radius: f64,
    wall_thickness: f64,
    counter: Elastic,
) -> PyResult<TrippContact> {
    let face = choose(
        counterface,
        &[
            (
                "convex",
                Counterface::Convex {
                    radius: counter_radius,
                },
            ),
            (
                "outer_ring",
                Counterface::OuterRing {
                    raceway_radius: counter_radius,
                    wall_thickness,
                },
            ),
        ],
        |other| format!("counterface = {other:?}: must be \"convex\" or \"outer_ring\""),
    )?;
    TrippContact::new(roller_radius, roller, face, counter).map_err(core_err)
}

elementwise! {
    /// Complete elliptic integrals K, E from the complementary parameter m1 = 1 - m.
    #[pyfunction]
    fn elliptic_integrals(m1) -> (k, e) => {
        let (k, e) = complete_elliptic_integrals(m1);
        [k, e]
    };

    /// Ellipticity kappa and elliptic integrals F (1st kind), E (2nd kind) for Ry/Rx.
    #[pyfunction]
    fn ellipticity(radius_ratio; method_name: &str) -> (kappa, first_kind, second_kind)
    where m = method(method_name)? => {
        let e = Ellipticity::new(radius_ratio, m);
        [e.kappa, e.first_kind, e.second_kind]
    };

    /// Hertz point contact from the normal force: penetration, semi-axes, max. pressure.
    #[pyfunction]
    fn hertz_point(r1, r2, e_prime, force; method_name: &str)
        -> {penetration, semi_major, semi_minor, max_pressure}
    where m = method(method_name)? => {
        let s = EllipticalContact::new(r1, r2, e_prime, m).at_force(force);
        [s.penetration, s.semi_major, s.semi_minor, s.max_pressure]
    };

    /// Hertz point-contact normal force from penetration (paper eq. 5).
    #[pyfunction]
    fn hertz_point_force(r1, r2, e_prime, penetration; method_name: &str) -> Array
    where m = method(method_name)? => EllipticalContact::new(r1, r2, e_prime, m).force(penetration);

    /// Line contact half-width (eq. 18) and maximum pressure (eq. 17).
    #[pyfunction]
    fn hertz_line(force, length, r_eff, e_prime) -> (half_width, max_pressure) => {
        let a = tri::hertz::line_half_width(force, length, r_eff, e_prime);
        [a, tri::hertz::line_max_pressure(force, a, length)]
    };

    /// Tripp deflection (eqs. 9, 10) for loads per unit length.
    #[pyfunction]
    fn tripp_deflection(
        load_per_length; roller_radius: f64, counterface: &str, counter_radius: f64,
        wall_thickness: f64, e1: f64, nu1: f64, e2: f64, nu2: f64
    ) -> Array
    where c = tripp_contact(
        roller_radius, elastic(e1, nu1), counterface, counter_radius, wall_thickness,
        elastic(e2, nu2),
    )? => c.deflection(load_per_length);

    /// Normal force of a slice by the power law of eq. 11.
    #[pyfunction]
    fn line_power_law_force(deflection, length; k1: f64, k2: f64) -> Array
    where law = LinePowerLaw { k1, k2 } => law.force(deflection, length);

    /// Vogel viscosity (eq. 20) and its temperature slope.
    #[pyfunction]
    fn vogel_viscosity(temperature; k: f64, b: f64, c: f64) -> (viscosity, slope)
    where v = Vogel { k, b, c } => [v.viscosity(temperature), v.viscosity_slope(temperature)];

    /// Roelands viscosity (eq. 19).
    #[pyfunction]
    fn roelands_viscosity(pressure, eta0; eta_p: f64, p_p: f64, z: f64) -> Array
    where r = Roelands { eta_p, p_p, z } => r.viscosity(pressure, eta0);

    /// Dicke viscosity.
    #[pyfunction]
    fn dicke_viscosity(pressure, temperature, eta0; a1: f64, a2: f64, b1: f64, b2: f64) -> Array
    where d = Dicke { a1, a2, b1, b2 } => d.viscosity(pressure, temperature, eta0);

    /// Carreau shear stress (eq. 21).
    #[pyfunction]
    fn carreau_shear_stress(viscosity, shear_rate; tau0: f64, n: f64) -> Array
    where c = Carreau { tau0, n } => c.shear_stress(viscosity, shear_rate);

    /// Blok's alpha* (eq. 31) for the Roelands law at ambient viscosities eta0.
    #[pyfunction]
    fn alpha_star_roelands(eta0; eta_p: f64, p_p: f64, z: f64) -> Array
    where r = Roelands { eta_p, p_p, z } =>
        lubricant::blok_alpha_star(|p| r.viscosity(p, eta0), 50e6);

    /// Blok's alpha* (eq. 31) for Barus' law eta0*exp(alpha p): equals alpha exactly.
    #[pyfunction]
    fn alpha_star_barus(alpha) -> Array =>
        lubricant::blok_alpha_star(|p| (alpha * p).exp(), 50e6);

    /// Line-contact films: Moes (eqs. 33-38), ZEV (39-44) and the greater-of rule.
    #[pyfunction]
    fn line_films(r_eff, u1, u2, load_per_length; e_prime: f64, alpha_star: f64, eta0: f64)
        -> {moes, zev, film}
    where f = FilmInputs { e_prime, alpha_star, eta0 } => [
        f.moes_line(r_eff, 0.5 * (u1 + u2), load_per_length),
        f.zev_line(r_eff, 0.5 * (u1.abs() + u2.abs()), load_per_length),
        f.line(r_eff, u1, u2, load_per_length),
    ];

    /// Chittenden's central film of an elliptical contact (eqs. 45, 46).
    #[pyfunction]
    fn chittenden_film(rx, ry, xi, u0, force; e_prime: f64, alpha_star: f64, eta0: f64) -> Array
    where f = FilmInputs { e_prime, alpha_star, eta0 } => f.chittenden(rx, ry, xi, u0, force);

    /// Thermal correction factor (eqs. 47, 48).
    #[pyfunction]
    fn thermal_correction(u0, sliding_speed; viscosity_slope: f64, thermal_conductivity: f64)
        -> Array
    => tri::film::thermal_correction(viscosity_slope, thermal_conductivity, u0, sliding_speed);

    /// Boundary friction coefficient (eqs. 51, 52, smoothed).
    #[pyfunction]
    fn boundary_friction_coefficient(
        sliding_speed, rolling_speed; mu_b0: f64, s0: f64, smoothing_speed: f64
    ) -> Array
    where b = BoundaryFriction { mu_b0, s0, smoothing_speed } =>
        b.coefficient(sliding_speed, rolling_speed);

    /// Zhou–Hoeprich boundary share (eq. 53).
    #[pyfunction]
    fn boundary_share(film_ratio; b: f64, c: f64) -> Array
    where z = LoadSharing { b, c } => z.boundary_share(film_ratio);

    /// Hysteresis rolling-resistance moment (eq. 55).
    #[pyfunction]
    fn hysteresis_moment(normal_force, half_width; alpha_v: f64) -> Array =>
        rolling_resistance::hysteresis_moment(alpha_v, normal_force, half_width);

    /// Hydrodynamic rolling force (eqs. 56, 57 without the radius).
    #[pyfunction]
    fn ehl_rolling_force(r_eff, length, u0, normal_force; e_prime: f64, eta0: f64) -> Array =>
        rolling_resistance::ehl_rolling_force(e_prime, r_eff, length, eta0, u0, normal_force);
}

/// Fit of eq. 11 to Tripp over [q_min, q_max]: k1, k2 and the fit's errors.
#[pyfunction]
#[allow(clippy::too_many_arguments)]
fn fit_line_power_law<'py>(
    py: Python<'py>,
    roller_radius: f64,
    counterface: &str,
    counter_radius: f64,
    wall_thickness: f64,
    e1: f64,
    nu1: f64,
    e2: f64,
    nu2: f64,
    load_min: f64,
    load_max: f64,
    samples: i64,
) -> PyResult<Bound<'py, PyDict>> {
    let samples = count("samples", samples, LinePowerLaw::SAMPLES)?;
    let roller = elastic(e1, nu1);
    let counter = elastic(e2, nu2);
    let c = tripp_contact(
        roller_radius,
        roller,
        counterface,
        counter_radius,
        wall_thickness,
        counter,
    )?;
    let (law, report) = LinePowerLaw::fit(&c, load_min, load_max, samples).map_err(core_err)?;
    let d = PyDict::new(py);
    set_fields!(d, law; k1, k2);
    set_fields!(d, report; load_min, load_max, max_force_error, max_deflection_error);
    Ok(d)
}

/// Roelands z fitted to a Dicke law ("initial_slope" or "least_squares").
#[pyfunction]
#[allow(clippy::too_many_arguments)]
fn fit_roelands_z(
    eta0: f64,
    temperature: f64,
    eta_p: f64,
    p_p: f64,
    a1: f64,
    a2: f64,
    b1: f64,
    b2: f64,
    method_name: &str,
    p_max: f64,
) -> PyResult<f64> {
    let m = choose(
        method_name,
        &[
            ("initial_slope", ZFit::InitialSlope),
            ("least_squares", ZFit::LeastSquares),
        ],
        |other| format!("z_fit = {other:?}: must be \"initial_slope\" or \"least_squares\""),
    )?;
    for (name, v, ok) in [
        ("temperature", temperature, temperature > 0.0),
        ("eta_p", eta_p, eta_p > 0.0),
        ("p_p", p_p, p_p < 0.0),
        ("a1", a1, true),
        ("a2", a2, true),
        ("b1", b1, true),
        ("b2", b2, true),
    ] {
        if !(v.is_finite() && ok) {
            return Err(PyValueError::new_err(format!(
                "{name} = {v}: must be finite{}",
                match name {
                    "temperature" | "eta_p" => " and positive",
                    "p_p" => " and negative",
                    _ => "",
                }
            )));
        }
    }
    let r = Roelands { eta_p, p_p, z: 0.6 };
    lubricant::fit_roelands_z(&r, &Dicke { a1, a2, b1, b2 }, eta0, temperature, m, p_max)
        .map_err(core_err)
}

/// Fit of eq. 32 to Blok's alpha* of the Vogel–Roelands lubricant over [t_min, t_max].
#[pyfunction]
#[allow(clippy::too_many_arguments)]
fn fit_alpha_star<'py>(
    py: Python<'py>,
    k: f64,
    b: f64,
    c: f64,
    eta_p: f64,
    p_p: f64,
    z: f64,
    t_min: f64,
    t_max: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let v = Vogel { k, b, c };
    let r = Roelands { eta_p, p_p, z };
    let fit = AlphaStarFit::fit(
        |t| lubricant::blok_alpha_star(|p| r.viscosity(p, v.viscosity(t)), 50e6),
        t_min,
        t_max,
    )
    .map_err(core_err)?;
    let d = PyDict::new(py);
    set_fields!(d, fit; c1, c2, c3, c4, max_relative_error);
    Ok(d)
}

/// Effective modulus E' = 2/((1 - nu1^2)/E1 + (1 - nu2^2)/E2) (paper, nomenclature), Pa.
#[pyfunction]
fn effective_modulus(e1: f64, nu1: f64, e2: f64, nu2: f64) -> f64 {
    tri::effective_modulus(e1, nu1, e2, nu2)
}

/// Adds this module's functions to `m`, and `ARRAY_ARGUMENTS` (a dict: the elementwise
/// functions' names and how many of their leading arguments are arrays).
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("ARRAY_ARGUMENTS", ARRAY_ARGUMENTS.into_py_dict(m.py())?)?;
    add_functions!(m;
        effective_modulus, elliptic_integrals, ellipticity, hertz_point, hertz_point_force, hertz_line,
        tripp_deflection, fit_line_power_law, line_power_law_force, vogel_viscosity,
        roelands_viscosity, dicke_viscosity, fit_roelands_z, carreau_shear_stress,
        alpha_star_roelands, alpha_star_barus, fit_alpha_star, line_films, chittenden_film,
        thermal_correction, boundary_friction_coefficient, boundary_share, hysteresis_moment,
        ehl_rolling_force,
    );
    Ok(())
}
