//! Bindings of the force laws (core `tribology`, paper sect. 3.1.2 – 3.3): Hertz and
//! Brewe–Hamrock (eqs. 5–8, 13–18), Tripp and the power law of eq. 11, the lubricant's
//! viscosity (eqs. 19–21, 31, 32), the films (eqs. 33–48), boundary friction (eqs. 51–53)
//! and rolling resistance (eqs. 55–57). Array arguments are one-dimensional float64
//! arrays of equal length (the Python wrappers in `rollerdyn.tribology` broadcast and
//! reshape); scalars are model parameters.

use crate::convert::{choose, core_err, map, map_many, set_fields, Array, In};
use pyo3::prelude::*;
use pyo3::types::PyDict;
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

/// A dict of the arrays `columns` under the keys `names`, in order.
fn dict_of<'py, const K: usize>(
    py: Python<'py>,
    names: [&str; K],
    columns: [Array<'py>; K],
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    for (name, column) in names.into_iter().zip(columns) {
        d.set_item(name, column)?;
    }
    Ok(d)
}

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

/// Complete elliptic integrals K, E from the complementary parameter m1 = 1 - m.
#[pyfunction]
fn elliptic_integrals<'py>(py: Python<'py>, m1: In<'py>) -> PyResult<(Array<'py>, Array<'py>)> {
    let [k, e] = map_many(py, ["m1"], [&m1], |[x]| {
        let (k, e) = complete_elliptic_integrals(x);
        [k, e]
    })?;
    Ok((k, e))
}

/// Ellipticity kappa and elliptic integrals F (1st kind), E (2nd kind) for Ry/Rx.
#[pyfunction]
fn ellipticity<'py>(
    py: Python<'py>,
    radius_ratio: In<'py>,
    method_name: &str,
) -> PyResult<(Array<'py>, Array<'py>, Array<'py>)> {
    let m = method(method_name)?;
    let [kappa, first, second] = map_many(py, ["radius_ratio"], [&radius_ratio], |[r]| {
        let e = Ellipticity::new(r, m);
        [e.kappa, e.first_kind, e.second_kind]
    })?;
    Ok((kappa, first, second))
}

/// Hertz point contact from the normal force: penetration, semi-axes, max. pressure.
#[pyfunction]
fn hertz_point<'py>(
    py: Python<'py>,
    r1: In<'py>,
    r2: In<'py>,
    e_prime: In<'py>,
    force: In<'py>,
    method_name: &str,
) -> PyResult<Bound<'py, PyDict>> {
    let m = method(method_name)?;
    let names = ["r1", "r2", "e_prime", "force"];
    let ins = [&r1, &r2, &e_prime, &force];
    let columns = map_many(py, names, ins, |[a, b, e, f]| {
        let s = EllipticalContact::new(a, b, e, m).at_force(f);
        [s.penetration, s.semi_major, s.semi_minor, s.max_pressure]
    })?;
    dict_of(
        py,
        ["penetration", "semi_major", "semi_minor", "max_pressure"],
        columns,
    )
}

/// Hertz point-contact normal force from penetration (paper eq. 5).
#[pyfunction]
fn hertz_point_force<'py>(
    py: Python<'py>,
    r1: In<'py>,
    r2: In<'py>,
    e_prime: In<'py>,
    penetration: In<'py>,
    method_name: &str,
) -> PyResult<Array<'py>> {
    let m = method(method_name)?;
    map(
        py,
        ["r1", "r2", "e_prime", "penetration"],
        [&r1, &r2, &e_prime, &penetration],
        |[a, b, e, d]| EllipticalContact::new(a, b, e, m).force(d),
    )
}

/// Line contact half-width (eq. 18) and maximum pressure (eq. 17).
#[pyfunction]
fn hertz_line<'py>(
    py: Python<'py>,
    force: In<'py>,
    length: In<'py>,
    r_eff: In<'py>,
    e_prime: In<'py>,
) -> PyResult<(Array<'py>, Array<'py>)> {
    let names = ["force", "length", "r_eff", "e_prime"];
    let ins = [&force, &length, &r_eff, &e_prime];
    let [a, p] = map_many(py, names, ins, |[f, l, r, e]| {
        let a = tri::hertz::line_half_width(f, l, r, e);
        [a, tri::hertz::line_max_pressure(f, a, l)]
    })?;
    Ok((a, p))
}

#[allow(clippy::too_many_arguments)]
fn tripp_contact(
    roller_radius: f64,
    counterface: &str,
    counter_radius: f64,
    wall_thickness: f64,
    e1: f64,
    nu1: f64,
    e2: f64,
    nu2: f64,
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
    TrippContact::new(roller_radius, elastic(e1, nu1), face, elastic(e2, nu2)).map_err(core_err)
}

/// Tripp deflection (eqs. 9, 10) for loads per unit length.
#[pyfunction]
#[allow(clippy::too_many_arguments)]
fn tripp_deflection<'py>(
    py: Python<'py>,
    load_per_length: In<'py>,
    roller_radius: f64,
    counterface: &str,
    counter_radius: f64,
    wall_thickness: f64,
    e1: f64,
    nu1: f64,
    e2: f64,
    nu2: f64,
) -> PyResult<Array<'py>> {
    let c = tripp_contact(
        roller_radius,
        counterface,
        counter_radius,
        wall_thickness,
        e1,
        nu1,
        e2,
        nu2,
    )?;
    map(py, ["load_per_length"], [&load_per_length], |[q]| {
        c.deflection(q)
    })
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
    samples: usize,
) -> PyResult<Bound<'py, PyDict>> {
    let c = tripp_contact(
        roller_radius,
        counterface,
        counter_radius,
        wall_thickness,
        e1,
        nu1,
        e2,
        nu2,
    )?;
    let (law, report) = LinePowerLaw::fit(&c, load_min, load_max, samples).map_err(core_err)?;
    let d = PyDict::new(py);
    set_fields!(d, law; k1, k2);
    set_fields!(d, report; load_min, load_max, max_force_error, max_deflection_error);
    Ok(d)
}

/// Normal force of a slice by the power law of eq. 11.
#[pyfunction]
fn line_power_law_force<'py>(
    py: Python<'py>,
    deflection: In<'py>,
    length: In<'py>,
    k1: f64,
    k2: f64,
) -> PyResult<Array<'py>> {
    let law = LinePowerLaw { k1, k2 };
    map(
        py,
        ["deflection", "length"],
        [&deflection, &length],
        |[d, l]| law.force(d, l),
    )
}

/// Vogel viscosity (eq. 20) and its temperature slope.
#[pyfunction]
fn vogel_viscosity<'py>(
    py: Python<'py>,
    temperature: In<'py>,
    k: f64,
    b: f64,
    c: f64,
) -> PyResult<(Array<'py>, Array<'py>)> {
    let v = Vogel { k, b, c };
    let [viscosity, slope] = map_many(py, ["temperature"], [&temperature], |[t]| {
        [v.viscosity(t), v.viscosity_slope(t)]
    })?;
    Ok((viscosity, slope))
}

/// Roelands viscosity (eq. 19).
#[pyfunction]
fn roelands_viscosity<'py>(
    py: Python<'py>,
    pressure: In<'py>,
    eta0: In<'py>,
    eta_p: f64,
    p_p: f64,
    z: f64,
) -> PyResult<Array<'py>> {
    let r = Roelands { eta_p, p_p, z };
    map(py, ["pressure", "eta0"], [&pressure, &eta0], |[p, e]| {
        r.viscosity(p, e)
    })
}

/// Dicke viscosity.
#[pyfunction]
#[allow(clippy::too_many_arguments)]
fn dicke_viscosity<'py>(
    py: Python<'py>,
    pressure: In<'py>,
    temperature: In<'py>,
    eta0: In<'py>,
    a1: f64,
    a2: f64,
    b1: f64,
    b2: f64,
) -> PyResult<Array<'py>> {
    let d = Dicke { a1, a2, b1, b2 };
    map(
        py,
        ["pressure", "temperature", "eta0"],
        [&pressure, &temperature, &eta0],
        |[p, t, e]| d.viscosity(p, t, e),
    )
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
    let r = Roelands { eta_p, p_p, z: 0.6 };
    lubricant::fit_roelands_z(&r, &Dicke { a1, a2, b1, b2 }, eta0, temperature, m, p_max)
        .map_err(core_err)
}

/// Carreau shear stress (eq. 21).
#[pyfunction]
fn carreau_shear_stress<'py>(
    py: Python<'py>,
    viscosity: In<'py>,
    shear_rate: In<'py>,
    tau0: f64,
    n: f64,
) -> PyResult<Array<'py>> {
    let c = Carreau { tau0, n };
    map(
        py,
        ["viscosity", "shear_rate"],
        [&viscosity, &shear_rate],
        |[e, g]| c.shear_stress(e, g),
    )
}

/// Blok's alpha* (eq. 31) for the Roelands law at ambient viscosities eta0.
#[pyfunction]
fn alpha_star_roelands<'py>(
    py: Python<'py>,
    eta0: In<'py>,
    eta_p: f64,
    p_p: f64,
    z: f64,
) -> PyResult<Array<'py>> {
    let r = Roelands { eta_p, p_p, z };
    map(py, ["eta0"], [&eta0], |[e]| {
        lubricant::blok_alpha_star(|p| r.viscosity(p, e), 50e6)
    })
}

/// Blok's alpha* (eq. 31) for Barus' law eta0*exp(alpha p): equals alpha exactly.
#[pyfunction]
fn alpha_star_barus<'py>(py: Python<'py>, alpha: In<'py>) -> PyResult<Array<'py>> {
    map(py, ["alpha"], [&alpha], |[a]| {
        lubricant::blok_alpha_star(|p| (a * p).exp(), 50e6)
    })
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

/// Line-contact films: Moes (eqs. 33-38), ZEV (39-44) and the greater-of rule.
#[pyfunction]
#[allow(clippy::too_many_arguments)]
fn line_films<'py>(
    py: Python<'py>,
    r_eff: In<'py>,
    u1: In<'py>,
    u2: In<'py>,
    load_per_length: In<'py>,
    e_prime: f64,
    alpha_star: f64,
    eta0: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let f = FilmInputs {
        e_prime,
        alpha_star,
        eta0,
    };
    let names = ["r_eff", "u1", "u2", "load_per_length"];
    let ins = [&r_eff, &u1, &u2, &load_per_length];
    let columns = map_many(py, names, ins, |[r, a, b, q]| {
        [
            f.moes_line(r, 0.5 * (a + b), q),
            f.zev_line(r, 0.5 * (a.abs() + b.abs()), q),
            f.line(r, a, b, q),
        ]
    })?;
    dict_of(py, ["moes", "zev", "film"], columns)
}

/// Chittenden's central film of an elliptical contact (eqs. 45, 46).
#[pyfunction]
#[allow(clippy::too_many_arguments)]
fn chittenden_film<'py>(
    py: Python<'py>,
    rx: In<'py>,
    ry: In<'py>,
    xi: In<'py>,
    u0: In<'py>,
    force: In<'py>,
    e_prime: f64,
    alpha_star: f64,
    eta0: f64,
) -> PyResult<Array<'py>> {
    let f = FilmInputs {
        e_prime,
        alpha_star,
        eta0,
    };
    map(
        py,
        ["rx", "ry", "xi", "u0", "force"],
        [&rx, &ry, &xi, &u0, &force],
        |[a, b, x, u, w]| f.chittenden(a, b, x, u, w),
    )
}

/// Thermal correction factor (eqs. 47, 48).
#[pyfunction]
fn thermal_correction<'py>(
    py: Python<'py>,
    u0: In<'py>,
    sliding_speed: In<'py>,
    viscosity_slope: f64,
    thermal_conductivity: f64,
) -> PyResult<Array<'py>> {
    map(
        py,
        ["u0", "sliding_speed"],
        [&u0, &sliding_speed],
        |[u, s]| tri::film::thermal_correction(viscosity_slope, thermal_conductivity, u, s),
    )
}

/// Boundary friction coefficient (eqs. 51, 52, smoothed).
#[pyfunction]
fn boundary_friction_coefficient<'py>(
    py: Python<'py>,
    sliding_speed: In<'py>,
    rolling_speed: In<'py>,
    mu_b0: f64,
    s0: f64,
    smoothing_speed: f64,
) -> PyResult<Array<'py>> {
    let b = BoundaryFriction {
        mu_b0,
        s0,
        smoothing_speed,
    };
    map(
        py,
        ["sliding_speed", "rolling_speed"],
        [&sliding_speed, &rolling_speed],
        |[s, r]| b.coefficient(s, r),
    )
}

/// Zhou–Hoeprich boundary share (eq. 53).
#[pyfunction]
fn boundary_share<'py>(
    py: Python<'py>,
    film_ratio: In<'py>,
    b: f64,
    c: f64,
) -> PyResult<Array<'py>> {
    let z = LoadSharing { b, c };
    map(py, ["film_ratio"], [&film_ratio], |[l]| z.boundary_share(l))
}

/// Hysteresis rolling-resistance moment (eq. 55).
#[pyfunction]
fn hysteresis_moment<'py>(
    py: Python<'py>,
    normal_force: In<'py>,
    half_width: In<'py>,
    alpha_v: f64,
) -> PyResult<Array<'py>> {
    map(
        py,
        ["normal_force", "half_width"],
        [&normal_force, &half_width],
        |[f, a]| rolling_resistance::hysteresis_moment(alpha_v, f, a),
    )
}

/// Hydrodynamic rolling force (eqs. 56, 57 without the radius).
#[pyfunction]
#[allow(clippy::too_many_arguments)]
fn ehl_rolling_force<'py>(
    py: Python<'py>,
    r_eff: In<'py>,
    length: In<'py>,
    u0: In<'py>,
    normal_force: In<'py>,
    e_prime: f64,
    eta0: f64,
) -> PyResult<Array<'py>> {
    map(
        py,
        ["r_eff", "length", "u0", "normal_force"],
        [&r_eff, &length, &u0, &normal_force],
        |[r, l, u, f]| rolling_resistance::ehl_rolling_force(e_prime, r, l, eta0, u, f),
    )
}

/// Adds this module's functions to `m`.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(elliptic_integrals, m)?)?;
    m.add_function(wrap_pyfunction!(ellipticity, m)?)?;
    m.add_function(wrap_pyfunction!(hertz_point, m)?)?;
    m.add_function(wrap_pyfunction!(hertz_point_force, m)?)?;
    m.add_function(wrap_pyfunction!(hertz_line, m)?)?;
    m.add_function(wrap_pyfunction!(tripp_deflection, m)?)?;
    m.add_function(wrap_pyfunction!(fit_line_power_law, m)?)?;
    m.add_function(wrap_pyfunction!(line_power_law_force, m)?)?;
    m.add_function(wrap_pyfunction!(vogel_viscosity, m)?)?;
    m.add_function(wrap_pyfunction!(roelands_viscosity, m)?)?;
    m.add_function(wrap_pyfunction!(dicke_viscosity, m)?)?;
    m.add_function(wrap_pyfunction!(fit_roelands_z, m)?)?;
    m.add_function(wrap_pyfunction!(carreau_shear_stress, m)?)?;
    m.add_function(wrap_pyfunction!(alpha_star_roelands, m)?)?;
    m.add_function(wrap_pyfunction!(alpha_star_barus, m)?)?;
    m.add_function(wrap_pyfunction!(fit_alpha_star, m)?)?;
    m.add_function(wrap_pyfunction!(line_films, m)?)?;
    m.add_function(wrap_pyfunction!(chittenden_film, m)?)?;
    m.add_function(wrap_pyfunction!(thermal_correction, m)?)?;
    m.add_function(wrap_pyfunction!(boundary_friction_coefficient, m)?)?;
    m.add_function(wrap_pyfunction!(boundary_share, m)?)?;
    m.add_function(wrap_pyfunction!(hysteresis_moment, m)?)?;
    m.add_function(wrap_pyfunction!(ehl_rolling_force, m)?)?;
    Ok(())
}
