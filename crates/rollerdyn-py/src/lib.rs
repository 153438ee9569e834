//! PyO3 bindings of rollerdyn-core: the module `rollerdyn._core`.
//!
//! Bindings only: every function forwards to the core. Array arguments arrive as
//! one-dimensional float64 arrays of equal length (the Python wrappers in
//! `rollerdyn.tribology` broadcast and reshape); scalars are model parameters. Core errors
//! become `ValueError`s carrying the core's message (quantity, value, rule); nothing here
//! panics across the boundary.

use numpy::{PyArray1, PyReadonlyArray1};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rollerdyn_core::geometry::roller::RollerShape;
use rollerdyn_core::numerics::elliptic::complete_elliptic_integrals;
use rollerdyn_core::tribology::{
    self as tri,
    film::FilmInputs,
    friction::{BoundaryFriction, LoadSharing},
    hertz::{EllipticalContact, EllipticalMethod, Ellipticity},
    line_contact::{Counterface, LinePowerLaw, TrippContact},
    lubricant::{self, AlphaStarFit, Carreau, Dicke, Roelands, Vogel, ZFit},
    rolling_resistance,
    traction::{EhlTraction, LimitingShearStress, TableGrid},
    Elastic,
};

type Array<'py> = Bound<'py, PyArray1<f64>>;
type In<'py> = PyReadonlyArray1<'py, f64>;

fn core_err(e: rollerdyn_core::Error) -> PyErr {
    PyValueError::new_err(e.to_string())
}

/// Applies `f` elementwise over equally long input arrays.
fn map<'py, const N: usize>(
    py: Python<'py>,
    names: [&str; N],
    inputs: [&In<'py>; N],
    f: impl Fn([f64; N]) -> f64,
) -> PyResult<Array<'py>> {
    let slices: Vec<&[f64]> = inputs
        .iter()
        .map(|a| a.as_slice())
        .collect::<Result<_, _>>()
        .map_err(|_| PyValueError::new_err("arrays must be contiguous"))?;
    let n = slices.first().map_or(0, |s| s.len());
    if let Some((i, s)) = slices.iter().enumerate().find(|(_, s)| s.len() != n) {
        return Err(PyValueError::new_err(format!(
            "{}: length {} differs from {}'s length {}",
            names[i],
            s.len(),
            names[0],
            n
        )));
    }
    let out: Vec<f64> = (0..n)
        .map(|k| f(std::array::from_fn(|j| slices[j][k])))
        .collect();
    Ok(PyArray1::from_vec(py, out))
}

fn method(name: &str) -> PyResult<EllipticalMethod> {
    match name {
        "brewe_hamrock" => Ok(EllipticalMethod::BreweHamrock),
        "exact" => Ok(EllipticalMethod::Exact),
        other => Err(PyValueError::new_err(format!(
            "method = {other:?}: must be \"brewe_hamrock\" or \"exact\""
        ))),
    }
}

fn elastic(e: f64, nu: f64) -> Elastic {
    Elastic {
        youngs_modulus: e,
        poisson_ratio: nu,
    }
}

/// Mass, axial and transverse inertia of a roller (SI), see core `RollerShape`.
#[pyfunction]
fn roller_mass_properties<'py>(
    py: Python<'py>,
    diameter: f64,
    length: f64,
    edge_radius: f64,
    end_face_radius: f64,
    density: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let shape =
        RollerShape::new(0.5 * diameter, length, edge_radius, end_face_radius).map_err(core_err)?;
    let m = shape.mass_properties(density).map_err(core_err)?;
    let d = PyDict::new(py);
    d.set_item("volume", m.volume)?;
    d.set_item("mass", m.mass)?;
    d.set_item("axial_inertia", m.axial_inertia)?;
    d.set_item("transverse_inertia", m.transverse_inertia)?;
    d.set_item("straight_length", shape.straight_length())?;
    Ok(d)
}

/// Complete elliptic integrals K, E from the complementary parameter m1 = 1 - m.
#[pyfunction]
fn elliptic_integrals<'py>(py: Python<'py>, m1: In<'py>) -> PyResult<(Array<'py>, Array<'py>)> {
    let k = map(py, ["m1"], [&m1], |[x]| complete_elliptic_integrals(x).0)?;
    let e = map(py, ["m1"], [&m1], |[x]| complete_elliptic_integrals(x).1)?;
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
    let get = |pick: fn(&Ellipticity) -> f64| {
        map(py, ["radius_ratio"], [&radius_ratio], |[r]| {
            pick(&Ellipticity::new(r, m))
        })
    };
    Ok((
        get(|e| e.kappa)?,
        get(|e| e.first_kind)?,
        get(|e| e.second_kind)?,
    ))
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
    let solve = |[a, b, e, f]: [f64; 4]| EllipticalContact::new(a, b, e, m).at_force(f);
    let d = PyDict::new(py);
    d.set_item(
        "penetration",
        map(py, names, ins, |x| solve(x).penetration)?,
    )?;
    d.set_item("semi_major", map(py, names, ins, |x| solve(x).semi_major)?)?;
    d.set_item("semi_minor", map(py, names, ins, |x| solve(x).semi_minor)?)?;
    d.set_item(
        "max_pressure",
        map(py, names, ins, |x| solve(x).max_pressure)?,
    )?;
    Ok(d)
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
    let a = map(py, names, ins, |[f, l, r, e]| {
        tri::hertz::line_half_width(f, l, r, e)
    })?;
    let p = map(py, names, ins, |[f, l, r, e]| {
        tri::hertz::line_max_pressure(f, tri::hertz::line_half_width(f, l, r, e), l)
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
    let face = match counterface {
        "convex" => Counterface::Convex {
            radius: counter_radius,
        },
        "outer_ring" => Counterface::OuterRing {
            raceway_radius: counter_radius,
            wall_thickness,
        },
        other => {
            return Err(PyValueError::new_err(format!(
                "counterface = {other:?}: must be \"convex\" or \"outer_ring\""
            )))
        }
    };
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
    d.set_item("k1", law.k1)?;
    d.set_item("k2", law.k2)?;
    d.set_item("load_min", report.load_min)?;
    d.set_item("load_max", report.load_max)?;
    d.set_item("max_force_error", report.max_force_error)?;
    d.set_item("max_deflection_error", report.max_deflection_error)?;
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
    Ok((
        map(py, ["temperature"], [&temperature], |[t]| v.viscosity(t))?,
        map(py, ["temperature"], [&temperature], |[t]| {
            v.viscosity_slope(t)
        })?,
    ))
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
    let m = match method_name {
        "initial_slope" => ZFit::InitialSlope,
        "least_squares" => ZFit::LeastSquares,
        other => {
            return Err(PyValueError::new_err(format!(
                "z_fit = {other:?}: must be \"initial_slope\" or \"least_squares\""
            )))
        }
    };
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
    for (key, value) in [
        ("c1", fit.c1),
        ("c2", fit.c2),
        ("c3", fit.c3),
        ("c4", fit.c4),
        ("max_relative_error", fit.max_relative_error),
    ] {
        d.set_item(key, value)?;
    }
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
    let d = PyDict::new(py);
    d.set_item(
        "moes",
        map(py, names, ins, |[r, a, b, q]| {
            f.moes_line(r, 0.5 * (a + b), q)
        })?,
    )?;
    d.set_item(
        "zev",
        map(py, names, ins, |[r, a, b, q]| {
            f.zev_line(r, 0.5 * (a.abs() + b.abs()), q)
        })?,
    )?;
    d.set_item(
        "film",
        map(py, names, ins, |[r, a, b, q]| f.line(r, a, b, q))?,
    )?;
    Ok(d)
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

/// The EHL traction model of one lubricant at one temperature (paper sect. 3.2.1).
#[pyclass(name = "EhlTraction", module = "rollerdyn._core")]
struct PyEhlTraction {
    inner: EhlTraction,
    lss: LimitingShearStress,
}

#[pymethods]
impl PyEhlTraction {
    #[new]
    #[pyo3(signature = (*, eta0, z, tau0, n, chi, p_star, tau_l0, lss_smoothing=20e6, eta_p=0.0631e-3, p_p=-196e6, nodes=12, tabulated=false))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        eta0: f64,
        z: f64,
        tau0: f64,
        n: f64,
        chi: f64,
        p_star: f64,
        tau_l0: f64,
        lss_smoothing: f64,
        eta_p: f64,
        p_p: f64,
        nodes: usize,
        tabulated: bool,
    ) -> PyResult<Self> {
        for (name, v) in [
            ("eta0", eta0),
            ("tau0", tau0),
            ("eta_p", eta_p),
            ("lss_smoothing", lss_smoothing),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(PyValueError::new_err(format!(
                    "{name} = {v}: must be finite and positive"
                )));
            }
        }
        if !(n > 0.0 && n <= 1.0) {
            return Err(PyValueError::new_err(format!(
                "n = {n}: must lie in (0, 1]"
            )));
        }
        if !(1..=200).contains(&nodes) {
            return Err(PyValueError::new_err(format!(
                "nodes = {nodes}: must lie in 1..=200"
            )));
        }
        let lss = LimitingShearStress {
            chi,
            p_star,
            tau_l0,
            smoothing: lss_smoothing,
        };
        let mut inner = EhlTraction::new(
            Roelands { eta_p, p_p, z },
            Carreau { tau0, n },
            lss,
            eta0,
            nodes,
        );
        if tabulated {
            inner = inner.tabulated(TableGrid::default());
        }
        Ok(Self { inner, lss })
    }

    /// Roelands viscosity at pressure.
    fn viscosity<'py>(&self, py: Python<'py>, pressure: In<'py>) -> PyResult<Array<'py>> {
        map(py, ["pressure"], [&pressure], |[p]| self.inner.viscosity(p))
    }

    /// Limiting shear stress (eq. 50, smoothed corner).
    fn limiting_shear_stress<'py>(
        &self,
        py: Python<'py>,
        pressure: In<'py>,
    ) -> PyResult<Array<'py>> {
        map(py, ["pressure"], [&pressure], |[p]| self.lss.at(p))
    }

    /// Film shear stress at pressure and shear rate.
    fn shear_stress<'py>(
        &self,
        py: Python<'py>,
        pressure: In<'py>,
        shear_rate: In<'py>,
    ) -> PyResult<Array<'py>> {
        map(
            py,
            ["pressure", "shear_rate"],
            [&pressure, &shear_rate],
            |[p, g]| self.inner.shear_stress(p, g),
        )
    }

    /// EHL tangential force of line slices.
    fn line_force<'py>(
        &self,
        py: Python<'py>,
        max_pressure: In<'py>,
        half_width: In<'py>,
        length: In<'py>,
        sliding_speed: In<'py>,
        film: In<'py>,
    ) -> PyResult<Array<'py>> {
        map(
            py,
            [
                "max_pressure",
                "half_width",
                "length",
                "sliding_speed",
                "film",
            ],
            [&max_pressure, &half_width, &length, &sliding_speed, &film],
            |[p, a, l, u, h]| self.inner.line_force(p, a, l, u, h),
        )
    }

    /// EHL tangential force of elliptical contacts.
    fn ellipse_force<'py>(
        &self,
        py: Python<'py>,
        max_pressure: In<'py>,
        semi_major: In<'py>,
        semi_minor: In<'py>,
        sliding_speed: In<'py>,
        film: In<'py>,
    ) -> PyResult<Array<'py>> {
        map(
            py,
            [
                "max_pressure",
                "semi_major",
                "semi_minor",
                "sliding_speed",
                "film",
            ],
            [
                &max_pressure,
                &semi_major,
                &semi_minor,
                &sliding_speed,
                &film,
            ],
            |[p, a, b, u, h]| self.inner.ellipse_force(p, a, b, u, h),
        )
    }

    /// The paper's tensor scheme for the ellipse (Gauss–Legendre x trapezoid).
    #[allow(clippy::too_many_arguments)]
    fn ellipse_force_tensor(
        &self,
        max_pressure: f64,
        semi_major: f64,
        semi_minor: f64,
        sliding_speed: f64,
        film: f64,
        across: usize,
        along: usize,
    ) -> PyResult<f64> {
        if across == 0 || along == 0 {
            return Err(PyValueError::new_err("across and along must be at least 1"));
        }
        Ok(self.inner.ellipse_force_tensor(
            max_pressure,
            semi_major,
            semi_minor,
            sliding_speed,
            film,
            across,
            along,
        ))
    }

    /// Nanoseconds per line-slice and per ellipse traction evaluation, timed over
    /// `repetitions` evaluations on B1-like contacts (for `rollerdyn bench`).
    fn time_per_evaluation(&self, repetitions: usize) -> (f64, f64) {
        let reps = repetitions.max(1);
        let mut sink = 0.0;
        let start = std::time::Instant::now();
        for i in 0..reps {
            let p0 = 0.5e9 + 1.5e9 * (i % 97) as f64 / 97.0;
            sink += self
                .inner
                .line_force(p0, 1.2e-4, 2.5e-4, 0.01 + 1e-3 * (i % 13) as f64, 2e-7);
        }
        let line = start.elapsed().as_secs_f64() * 1e9 / reps as f64;
        let start = std::time::Instant::now();
        for i in 0..reps {
            let p0 = 0.5e9 + 1.5e9 * (i % 97) as f64 / 97.0;
            sink += self
                .inner
                .ellipse_force(p0, 3e-4, 1e-4, 0.05 + 1e-3 * (i % 13) as f64, 2e-7);
        }
        let ellipse = start.elapsed().as_secs_f64() * 1e9 / reps as f64;
        std::hint::black_box(sink);
        (line, ellipse)
    }
}

/// Roller end / flange detection benchmark on a roller's trajectory against one inner-ring
/// flange (see core `contact::benchmark`). Lengths in m, angles in rad.
#[pyfunction]
#[pyo3(signature = (*, roller_diameter, roller_length, edge_radius, end_face_radius, opening_angle, flange_height, root_radius, rim_radius, raceway_radius, pitch_radius, axial_play, steps=6283, step=1e-3, push=22e-6, wobble=1e-3, reference_every=100, mesh_every=0, mesh_resolutions=Vec::new()))]
#[allow(clippy::too_many_arguments)]
fn contact_benchmark<'py>(
    py: Python<'py>,
    roller_diameter: f64,
    roller_length: f64,
    edge_radius: f64,
    end_face_radius: f64,
    opening_angle: f64,
    flange_height: f64,
    root_radius: f64,
    rim_radius: f64,
    raceway_radius: f64,
    pitch_radius: f64,
    axial_play: f64,
    steps: usize,
    step: f64,
    push: f64,
    wobble: f64,
    reference_every: usize,
    mesh_every: usize,
    mesh_resolutions: Vec<(usize, usize)>,
) -> PyResult<Bound<'py, PyDict>> {
    use rollerdyn_core::contact::benchmark::{mesh_study, run, Trajectory};
    use rollerdyn_core::contact::mesh::MeshResolution;
    use rollerdyn_core::geometry::end_flange::{Flange, FlangePlacement, FlangeShape};
    use rollerdyn_core::geometry::primitives::Vec3;
    if steps == 0 {
        return Err(PyValueError::new_err("steps = 0: must be at least 1"));
    }
    let shape = RollerShape::new(
        0.5 * roller_diameter,
        roller_length,
        edge_radius,
        end_face_radius,
    )
    .map_err(core_err)?;
    let flange_shape = FlangeShape::new(opening_angle, flange_height, root_radius, rim_radius)
        .map_err(core_err)?;
    let flange = Flange::new(
        &flange_shape,
        &FlangePlacement {
            origin: Vec3::zeros(),
            axis: Vec3::x(),
            raceway_radius,
            rises: 1.0,
            face_position: 0.5 * roller_length + axial_play,
            facing: -1.0,
        },
    );
    let trajectory = Trajectory {
        pitch_radius,
        step,
        steps,
        push,
        wobble,
    };
    let r = py.detach(|| run(&shape, &flange, &trajectory, reference_every));
    let d = PyDict::new(py);
    d.set_item("evaluations", r.evaluations)?;
    d.set_item("semi_analytical_ns", r.semi_analytical_ns)?;
    d.set_item("pruned_ns", r.pruned_ns)?;
    d.set_item("composite_ns", r.composite_ns)?;
    d.set_item("pruned_composite_ns", r.pruned_composite_ns)?;
    d.set_item("gradient_ns", r.gradient_ns)?;
    d.set_item("gradient_pruned_ns", r.gradient_pruned_ns)?;
    d.set_item("gradient_mean_iterations", r.gradient_mean_iterations)?;
    d.set_item("gradient_not_converged", r.gradient_not_converged)?;
    d.set_item("gradient_wrong_stationary", r.gradient_wrong_stationary)?;
    d.set_item("gradient_wrong_composite", r.gradient_wrong_composite)?;
    d.set_item("pruned_pairings", r.pruned_pairings)?;
    d.set_item("pruned_flanges", r.pruned_flanges)?;
    d.set_item("steps_in_contact", r.steps_in_contact)?;
    d.set_item("semi_max_location_error", r.semi_max_location_error)?;
    d.set_item("semi_max_penetration_error", r.semi_max_penetration_error)?;
    d.set_item("reference_checks", r.reference_checks)?;
    if mesh_every > 0 && !mesh_resolutions.is_empty() {
        let resolutions: Vec<MeshResolution> = mesh_resolutions
            .iter()
            .map(|&(around, along)| MeshResolution { around, along })
            .collect();
        let points =
            py.detach(|| mesh_study(&shape, &flange, &trajectory, mesh_every, &resolutions));
        let rows: Vec<(usize, usize, f64, f64, usize)> = points
            .iter()
            .map(|p| {
                (
                    p.resolution.around,
                    p.resolution.along,
                    p.ns,
                    p.max_penetration_error,
                    p.samples,
                )
            })
            .collect();
        d.set_item("mesh", rows)?;
    }
    Ok(d)
}

/// Closest points of two circles in 3D (Eberly's method, core `geometry::circle`):
/// returns (squared distance, kind: "unique" | "several" | "infinite", point on circle 1,
/// point on circle 2).
#[pyfunction]
#[allow(clippy::type_complexity)]
fn circle_circle_distance(
    center1: [f64; 3],
    normal1: [f64; 3],
    radius1: f64,
    center2: [f64; 3],
    normal2: [f64; 3],
    radius2: f64,
) -> PyResult<(f64, &'static str, [f64; 3], [f64; 3])> {
    use rollerdyn_core::geometry::circle::{self as circle, Circle3, ClosestPairs};
    use rollerdyn_core::geometry::primitives::Vec3;
    let all = center1
        .iter()
        .chain(&normal1)
        .chain(&center2)
        .chain(&normal2)
        .chain([&radius1, &radius2]);
    if all.clone().any(|v| !v.is_finite()) || radius1 <= 0.0 || radius2 <= 0.0 {
        return Err(PyValueError::new_err(
            "circle centres and normals must be finite and radii finite and positive",
        ));
    }
    let c1 = Circle3 {
        center: Vec3::from(center1),
        normal: Vec3::from(normal1),
        radius: radius1,
    };
    let c2 = Circle3 {
        center: Vec3::from(center2),
        normal: Vec3::from(normal2),
        radius: radius2,
    };
    let d = circle::circle_circle_distance(&c1, &c2);
    let kind = match d.pairs {
        ClosestPairs::Unique(..) => "unique",
        ClosestPairs::Several(..) => "several",
        ClosestPairs::Infinite(..) => "infinite",
    };
    let (p1, p2) = d.pairs.first();
    Ok((
        d.squared_distance,
        kind,
        [p1.x, p1.y, p1.z],
        [p2.x, p2.y, p2.z],
    ))
}

/// The module `rollerdyn._core`.
#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_class::<PyEhlTraction>()?;
    m.add_function(wrap_pyfunction!(simulation::simulate, m)?)?;
    m.add_function(wrap_pyfunction!(simulation::initial_state, m)?)?;
    m.add_function(wrap_pyfunction!(simulation::equilibrium_state, m)?)?;
    m.add_function(wrap_pyfunction!(simulation::model_rhs, m)?)?;
    m.add_function(wrap_pyfunction!(simulation::model_timing, m)?)?;
    m.add_function(wrap_pyfunction!(simulation::model_energy, m)?)?;
    m.add_function(wrap_pyfunction!(roller_mass_properties, m)?)?;
    m.add_function(wrap_pyfunction!(contact_benchmark, m)?)?;
    m.add_function(wrap_pyfunction!(circle_circle_distance, m)?)?;
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

// ----- The dynamic model -------------------------------------------------------------

mod simulation {
    use super::*;
    use pyo3::types::PyList;
    use rollerdyn_core::bearing::model::Profile;
    use rollerdyn_core::bearing::run::{
        run, Progress, Record, RunCheckpoint, RunOptions, RunOutput,
    };
    use rollerdyn_core::bearing::{BearingModel, BearingParams, Detector, History, SurfacePair};
    use rollerdyn_core::contact::border::BorderBands;
    use rollerdyn_core::dynamics::integrate::{Method, Start, Stats, StepControl};
    use rollerdyn_core::geometry::end_flange::FlangeShape;
    use rollerdyn_core::geometry::primitives::Vec3;
    use rollerdyn_core::tribology::drag::Mixture;
    use rollerdyn_core::tribology::hydrodynamic::RigidFilm;
    use rollerdyn_core::tribology::squeeze::SqueezeFilm;
    use std::ops::ControlFlow;

    fn get<'py, T: pyo3::conversion::FromPyObjectOwned<'py>>(
        d: &Bound<'py, PyDict>,
        key: &str,
    ) -> PyResult<T> {
        match d.get_item(key)? {
            Some(v) => v.extract::<T>().map_err(|_| {
                PyValueError::new_err(format!("model parameter {key} = {v}: wrong type"))
            }),
            None => Err(PyValueError::new_err(format!(
                "model parameter {key} is missing"
            ))),
        }
    }

    fn history(d: &Bound<'_, PyDict>, key: &str) -> PyResult<History> {
        let h: Bound<'_, PyDict> = get(d, key)?;
        let kind: String = get(&h, "kind")?;
        match kind.as_str() {
            "ramp" => Ok(History::Ramp {
                value: get(&h, "value")?,
                start: get(&h, "start")?,
                end: get(&h, "end")?,
                cosine: get::<String>(&h, "shape")? == "cosine",
            }),
            "table" => {
                let t: Vec<f64> = get(&h, "times")?;
                let v: Vec<f64> = get(&h, "values")?;
                Ok(History::Table(t.into_iter().zip(v).collect()))
            }
            other => Err(PyValueError::new_err(format!(
                "{key}.kind = {other}: must be 'ramp' or 'table'"
            ))),
        }
    }

    fn flange(d: &Bound<'_, PyDict>, ring: &str) -> PyResult<FlangeShape> {
        let g = |k: &str| get::<f64>(d, &format!("{ring}_flange_{k}"));
        FlangeShape::new(
            g("opening_angle")?,
            g("height")?,
            g("root_radius")?,
            g("rim_radius")?,
        )
        .map_err(core_err)
    }

    fn surface(d: &Bound<'_, PyDict>, name: &str) -> PyResult<SurfacePair> {
        Ok(SurfacePair {
            roughness: get(d, &format!("{name}_roughness"))?,
            sharing: LoadSharing {
                b: get(d, &format!("{name}_zh_b"))?,
                c: get(d, &format!("{name}_zh_c"))?,
            },
        })
    }

    fn params(d: &Bound<'_, PyDict>, traction: &EhlTraction) -> PyResult<BearingParams> {
        let roller = RollerShape::new(
            get(d, "roller_radius")?,
            get(d, "roller_length")?,
            get(d, "edge_radius")?,
            get(d, "end_face_radius")?,
        )
        .map_err(core_err)?;
        let law = |k: &str| -> PyResult<LinePowerLaw> {
            Ok(LinePowerLaw {
                k1: get(d, &format!("k1_{k}"))?,
                k2: get(d, &format!("k2_{k}"))?,
            })
        };
        let detector = match get::<String>(d, "detector")?.as_str() {
            "semi-analytical" => Detector::SemiAnalytical,
            "gradient" => Detector::Gradient,
            "mesh" => Detector::Mesh,
            other => {
                return Err(PyValueError::new_err(format!(
                    "detector = {other}: must be semi-analytical, gradient or mesh"
                )))
            }
        };
        Ok(BearingParams {
            roller_count: get(d, "roller_count")?,
            roller,
            slices: get(d, "slices")?,
            crown_drop: get(d, "crown_drop")?,
            crown_length: get(d, "crown_length")?,
            roller_density: get(d, "roller_density")?,
            inner_raceway_radius: get(d, "inner_raceway_radius")?,
            outer_raceway_radius: get(d, "outer_raceway_radius")?,
            inner_flange: flange(d, "inner")?,
            outer_flange: flange(d, "outer")?,
            inner_axial_play: get(d, "inner_axial_play")?,
            outer_axial_play: get(d, "outer_axial_play")?,
            e_prime: [
                get(d, "e_prime_inner")?,
                get(d, "e_prime_outer")?,
                get(d, "e_prime_roller")?,
            ],
            line_laws: [law("inner")?, law("outer")?, law("roller")?],
            inner_ring_mass: get(d, "inner_ring_mass")?,
            inner_ring_axial_inertia: get(d, "inner_ring_axial_inertia")?,
            inner_ring_transverse_inertia: get(d, "inner_ring_transverse_inertia")?,
            inner_ring_tilt_free: get(d, "inner_ring_tilt_free")?,
            inner_ring_misalignment: get(d, "inner_ring_misalignment")?,
            traction: traction.clone(),
            eta0: get(d, "eta0")?,
            viscosity_slope: get(d, "viscosity_slope")?,
            alpha_star: get(d, "alpha_star")?,
            thermal_conductivity: get(d, "thermal_conductivity")?,
            raceway: surface(d, "raceway")?,
            flange_surface: surface(d, "flange")?,
            roller_roller: surface(d, "roller_roller")?,
            boundary: BoundaryFriction {
                mu_b0: get(d, "mu_b0")?,
                s0: get(d, "s0")?,
                smoothing_speed: get(d, "smoothing_speed")?,
            },
            hysteresis_coefficient: get(d, "hysteresis_coefficient")?,
            damping_ratio: get(d, "damping_ratio")?,
            friction: get(d, "friction")?,
            gravity: {
                let g: [f64; 3] = get(d, "gravity")?;
                Vec3::new(g[0], g[1], g[2])
            },
            race_film: RigidFilm {
                enabled: get(d, "race_film")?,
                cutoff: get(d, "race_film_cutoff")?,
            },
            mixture: Mixture::new(
                get(d, "oil_fraction")?,
                get(d, "oil_density")?,
                get(d, "eta0")?,
                get(d, "air_density")?,
                get(d, "air_viscosity")?,
            ),
            radial_load: history(d, "radial_load")?,
            axial_load: history(d, "axial_load")?,
            inner_ring_speed: history(d, "inner_ring_speed")?,
            detector,
            mesh_resolution: (get(d, "mesh_around")?, get(d, "mesh_along")?),
            pruning: get(d, "pruning")?,
            border_bands: BorderBands {
                roller_angle: get(d, "border_band_roller")?,
                flange_length: get(d, "border_band_flange")?,
            },
            squeeze_film: SqueezeFilm {
                enabled: get(d, "squeeze_film")?,
                half_width: get(d, "squeeze_film_half_width")?,
                floor: get(d, "squeeze_film_floor")?,
                cutoff: get(d, "squeeze_film_cutoff")?,
            },
        })
    }

    fn options(d: &Bound<'_, PyDict>) -> PyResult<RunOptions> {
        let method = match get::<String>(d, "method")?.as_str() {
            "tr-bdf2" => Method::TrBdf2,
            "esdirk34" => Method::Esdirk34,
            other => {
                return Err(PyValueError::new_err(format!(
                    "method = {other}: must be tr-bdf2 or esdirk34"
                )))
            }
        };
        Ok(RunOptions {
            t_end: get(d, "t_end")?,
            rtol: get(d, "rtol")?,
            atol: get(d, "atol")?,
            atol_time_scale: get(d, "atol_time_scale")?,
            dt_max: get(d, "dt_max")?,
            output_interval: get(d, "output_interval")?,
            method,
            step_control: StepControl {
                max_growth: get(d, "max_step_growth")?,
                gain: get(d, "step_gain")?,
                jacobian_after_newton_failure: get(d, "jacobian_after_newton_failure")?,
            },
            checkpoint_interval: match d.get_item("checkpoint_interval")? {
                Some(v) if !v.is_none() => Some(v.extract().map_err(|_| {
                    PyValueError::new_err(format!("checkpoint_interval = {v}: wrong type"))
                })?),
                _ => None,
            },
            start_from_equilibrium: match d.get_item("start")? {
                Some(v) if !v.is_none() => match v.extract::<String>()?.as_str() {
                    "rest" => false,
                    "equilibrium" => true,
                    other => {
                        return Err(PyValueError::new_err(format!(
                            "start = {other}: must be rest or equilibrium"
                        )))
                    }
                },
                _ => false,
            },
        })
    }

    /// The quasi-static equilibrium state at time t (`solver.start = "equilibrium"`), or
    /// ValueError with the residual and the body where there is none.
    #[pyfunction]
    pub fn equilibrium_state(
        params: &Bound<'_, PyDict>,
        traction: &PyEhlTraction,
        t: f64,
    ) -> PyResult<Vec<f64>> {
        let model = BearingModel::new(self::params(params, &traction.inner)?).map_err(core_err)?;
        model.equilibrium_state(t).map_err(core_err)
    }

    /// Checks a parameter set and returns the initial state (or raises ValueError).
    #[pyfunction]
    pub fn initial_state(
        params: &Bound<'_, PyDict>,
        traction: &PyEhlTraction,
    ) -> PyResult<Vec<f64>> {
        let model = BearingModel::new(self::params(params, &traction.inner)?).map_err(core_err)?;
        model.initial_state().map_err(core_err)
    }

    /// The model of `params`, checked to have as many states as `y`.
    fn model_for(
        params: &Bound<'_, PyDict>,
        traction: &PyEhlTraction,
        y: &[f64],
    ) -> PyResult<BearingModel> {
        use rollerdyn_core::dynamics::integrate::OdeSystem;
        let model = BearingModel::new(self::params(params, &traction.inner)?).map_err(core_err)?;
        if y.len() != model.len() {
            return Err(PyValueError::new_err(format!(
                "y has {} states: the model has {}",
                y.len(),
                model.len()
            )));
        }
        Ok(model)
    }

    /// f(t, y) and the structured Jacobian of the model at (t, y) (for tests).
    #[pyfunction]
    pub fn model_rhs(
        params: &Bound<'_, PyDict>,
        traction: &PyEhlTraction,
        t: f64,
        y: Vec<f64>,
    ) -> PyResult<(Vec<f64>, Vec<f64>)> {
        use rollerdyn_core::dynamics::integrate::OdeSystem;
        let model = model_for(params, traction, &y)?;
        let n = model.len();
        let mut dy = vec![0.0; n];
        model.rhs(t, &y, &mut dy);
        let mut jac = nalgebra::DMatrix::zeros(n, n);
        model.jacobian(t, &y, &mut jac);
        Ok((dy, jac.transpose().as_slice().to_vec()))
    }

    /// Times the model at (t, y) on this thread: `rhs_repetitions` right-hand sides, then
    /// `jacobian_repetitions` Jacobians (`rollerdyn bench model`). Returns the mean wall
    /// time of each [s] and the profile of the right-hand sides (detection, line
    /// contacts, flange forces [s per right-hand side]; sampled as in a run).
    #[pyfunction]
    pub fn model_timing<'py>(
        py: Python<'py>,
        params: &Bound<'py, PyDict>,
        traction: &PyEhlTraction,
        t: f64,
        y: Vec<f64>,
        rhs_repetitions: usize,
        jacobian_repetitions: usize,
    ) -> PyResult<Bound<'py, PyDict>> {
        use rollerdyn_core::dynamics::integrate::OdeSystem;
        use std::time::Instant;
        let model = model_for(params, traction, &y)?;
        let n = model.len();
        let (rhs_n, jac_n) = (rhs_repetitions.max(1), jacobian_repetitions);
        let mut dy = vec![0.0; n];
        let mut jac = nalgebra::DMatrix::zeros(n, n);
        model.rhs(t, &y, &mut dy); // warm-up (and the gradient detector's warm starts)
        let before = model.profile();
        let start = Instant::now();
        for _ in 0..rhs_n {
            model.rhs(t, std::hint::black_box(&y), &mut dy);
        }
        let rhs = start.elapsed().as_secs_f64() / rhs_n as f64;
        let after = model.profile();
        let start = Instant::now();
        for _ in 0..jac_n {
            model.jacobian(t, std::hint::black_box(&y), &mut jac);
        }
        let jacobian = start.elapsed().as_secs_f64() / jac_n.max(1) as f64;
        let per = |a: f64, b: f64| (a - b) / rhs_n as f64;
        let d = PyDict::new(py);
        d.set_item("states", n)?;
        d.set_item("rhs_seconds", rhs)?;
        d.set_item(
            "jacobian_seconds",
            if jac_n > 0 { jacobian } else { f64::NAN },
        )?;
        d.set_item("detection_seconds", per(after.detection, before.detection))?;
        d.set_item(
            "line_contact_seconds",
            per(after.line_contacts, before.line_contacts),
        )?;
        d.set_item(
            "flange_force_seconds",
            per(after.flange_forces, before.flange_forces),
        )?;
        d.set_item(
            "detections",
            (after.detections - before.detections) as f64 / rhs_n as f64,
        )?;
        Ok(d)
    }

    /// Total mechanical energy of the model at (t, y) [J] (for conservation checks).
    #[pyfunction]
    pub fn model_energy(
        params: &Bound<'_, PyDict>,
        traction: &PyEhlTraction,
        t: f64,
        y: Vec<f64>,
    ) -> PyResult<f64> {
        Ok(model_for(params, traction, &y)?.energy(t, &y))
    }

    /// Runs the dynamic model. `progress(time, t_end, steps, rhs, jac, step)` is called at every
    /// output time; returning True stops the run. `checkpoint(dict)` is called at every
    /// checkpoint with the results so far (the dict `simulate` returns, cut at the
    /// checkpoint); returning True stops the run. `start = (t, y, h)` starts from a state,
    /// `h` None for a fresh start, a checkpoint's step to continue from it bit for bit.
    /// Returns a dict of flat arrays (see `rollerdyn.simulation`), the solver counters, the
    /// profile, the final state, the last checkpoint (or the start) and the error (None if
    /// the run completed).
    #[pyfunction]
    #[pyo3(signature = (params, traction, options, progress=None, start=None, checkpoint=None))]
    pub fn simulate<'py>(
        py: Python<'py>,
        params: &Bound<'py, PyDict>,
        traction: &PyEhlTraction,
        options: &Bound<'py, PyDict>,
        progress: Option<Bound<'py, PyAny>>,
        start: Option<(f64, Vec<f64>, Option<f64>)>,
        checkpoint: Option<Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let threads: usize = match options.get_item("threads")? {
            Some(v) if !v.is_none() => v.extract()?,
            _ => 1,
        };
        let model = BearingModel::new(self::params(params, &traction.inner)?)
            .and_then(|m| m.with_threads(threads))
            .map_err(core_err)?;
        let opts = self::options(options)?;
        let start = start.map(|(time, state, step)| Start { time, state, step });
        let z = model.layout.rollers;
        let callback_error = std::cell::RefCell::new(None::<PyErr>);
        let stop = |r: PyResult<Bound<'py, PyAny>>| match r {
            Ok(r) if r.is_truthy().unwrap_or(false) => ControlFlow::Break(()),
            Ok(_) => ControlFlow::Continue(()),
            Err(e) => {
                *callback_error.borrow_mut() = Some(e);
                ControlFlow::Break(())
            }
        };
        let output = run(
            &model,
            start,
            &opts,
            |p: &Progress| {
                if let Err(e) = py.check_signals() {
                    *callback_error.borrow_mut() = Some(e);
                    return ControlFlow::Break(());
                }
                let Some(cb) = &progress else {
                    return ControlFlow::Continue(());
                };
                let s = &p.stats;
                stop(cb.call1((
                    p.time,
                    p.t_end,
                    s.steps,
                    s.rhs_evaluations,
                    s.jacobian_evaluations,
                    s.last_step,
                    p.at_output,
                )))
            },
            |c: &RunCheckpoint, records: &[Record]| {
                let Some(cb) = &checkpoint else {
                    return ControlFlow::Continue(());
                };
                let d = match partial_dict(py, c, records, z) {
                    Ok(d) => d,
                    Err(e) => return stop(Err(e)),
                };
                stop(cb.call1((d,)))
            },
        )
        .map_err(core_err)?;
        let out = to_dict(py, &output, z)?;
        put_checkpoint(py, &out, &output.checkpoint)?;
        if let Some(e) = callback_error.into_inner() {
            out.set_item("interruption", e.to_string())?;
        }
        Ok(out)
    }

    /// The results up to a checkpoint, as `simulate` returns them (not completed).
    fn partial_dict<'py>(
        py: Python<'py>,
        c: &RunCheckpoint,
        records: &[Record],
        z: usize,
    ) -> PyResult<Bound<'py, PyDict>> {
        let k = &c.checkpoint;
        let partial = RunOutput {
            records: records[..c.records].to_vec(),
            stats: k.stats,
            profile: c.profile,
            final_state: k.state.clone(),
            final_time: k.time,
            error: None,
            interrupted: true,
            checkpoint: c.clone(),
        };
        let d = to_dict(py, &partial, z)?;
        put_checkpoint(py, &d, c)?;
        Ok(d)
    }

    /// The checkpoint entries: time, state, step (NaN: a fresh start) and counters.
    fn put_checkpoint(py: Python<'_>, d: &Bound<'_, PyDict>, c: &RunCheckpoint) -> PyResult<()> {
        let k = &c.checkpoint;
        d.set_item("checkpoint_time", k.time)?;
        d.set_item("checkpoint_step", k.step)?;
        d.set_item("checkpoint_state", PyList::new(py, &k.state)?)?;
        d.set_item("checkpoint_stats", stats_dict(py, &k.stats, &c.profile)?)?;
        Ok(())
    }

    fn stats_dict<'py>(py: Python<'py>, s: &Stats, p: &Profile) -> PyResult<Bound<'py, PyDict>> {
        let stats = PyDict::new(py);
        stats.set_item("steps", s.steps)?;
        stats.set_item("rhs_evaluations", s.rhs_evaluations)?;
        stats.set_item("jacobian_evaluations", s.jacobian_evaluations)?;
        stats.set_item("rhs_seconds", s.rhs_seconds)?;
        stats.set_item("jacobian_seconds", s.jacobian_seconds)?;
        stats.set_item("total_seconds", s.total_seconds)?;
        stats.set_item("t_reached", s.t_reached)?;
        stats.set_item("error_test_failures", s.error_test_failures)?;
        stats.set_item("newton_failures", s.newton_failures)?;
        stats.set_item("newton_iterations", s.newton_iterations)?;
        stats.set_item("linear_solver_setups", s.linear_solver_setups)?;
        stats.set_item("detection_seconds", p.detection)?;
        stats.set_item("line_contact_seconds", p.line_contacts)?;
        stats.set_item("flange_force_seconds", p.flange_forces)?;
        stats.set_item("detections", p.detections)?;
        stats.set_item("gradient_fallbacks", p.gradient_fallbacks)?;
        Ok(stats)
    }

    fn to_dict<'py>(py: Python<'py>, o: &RunOutput, z: usize) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        let recs = &o.records;
        let put = |name: &str, v: Vec<f64>| d.set_item(name, PyArray1::from_vec(py, v));
        put("time", recs.iter().map(|r| r.time).collect())?;
        put(
            "ring_position",
            recs.iter()
                .flat_map(|r| r.ring_position.iter().copied().collect::<Vec<_>>())
                .collect(),
        )?;
        put(
            "ring_tilt",
            recs.iter()
                .flat_map(|r| [r.ring_tilt.0, r.ring_tilt.1])
                .collect(),
        )?;
        put("ring_speed", recs.iter().map(|r| r.ring_speed).collect())?;
        put("radial_load", recs.iter().map(|r| r.loads.0).collect())?;
        put("axial_load", recs.iter().map(|r| r.loads.1).collect())?;
        put(
            "frictional_torque",
            recs.iter().map(|r| r.frictional_torque).collect(),
        )?;
        put(
            "outer_ring_torque",
            recs.iter().map(|r| r.outer_ring_torque).collect(),
        )?;
        macro_rules! per_roller {
            ($name:literal, $f:expr) => {
                put(
                    $name,
                    recs.iter().flat_map(|r| r.rollers.iter().map($f)).collect(),
                )?
            };
        }
        per_roller!("azimuth", |x| x.azimuth);
        per_roller!("tilt", |x| x.tilt);
        per_roller!("skew", |x| x.skew);
        per_roller!("spin_speed", |x| x.spin_speed);
        per_roller!("orbital_speed", |x| x.orbital_speed);
        per_roller!("srr_inner", |x| x.srr_inner);
        per_roller!("srr_outer", |x| x.srr_outer);
        per_roller!("inner_normal_force", |x| x.inner_normal);
        per_roller!("outer_normal_force", |x| x.outer_normal);
        per_roller!("inner_tangential_force", |x| x.inner_tangential);
        per_roller!("outer_tangential_force", |x| x.outer_tangential);
        per_roller!("roller_roller_normal_force", |x| x.pair_normal);
        per_roller!("roller_roller_tangential_force", |x| x.pair_tangential);
        put(
            "position",
            recs.iter()
                .flat_map(|r| {
                    r.rollers
                        .iter()
                        .flat_map(|x| x.position.iter().copied().collect::<Vec<_>>())
                })
                .collect(),
        )?;
        macro_rules! per_flange {
            ($name:literal, $f:expr) => {
                put(
                    $name,
                    recs.iter()
                        .flat_map(|r| r.rollers.iter().flat_map(|x| x.flanges.iter().map($f)))
                        .collect(),
                )?
            };
        }
        per_flange!("flange_pairing", |f| f.pairing as f64);
        per_flange!("flange_penetration", |f| if f.penetration.is_finite() {
            f.penetration
        } else {
            f64::NAN
        });
        per_flange!("flange_normal_force", |f| f.normal_force);
        per_flange!("flange_friction_force", |f| f.friction_force);
        per_flange!("flange_axial_force", |f| f.axial_force);
        put(
            "flange_location",
            recs.iter()
                .flat_map(|r| {
                    r.rollers.iter().flat_map(|x| {
                        x.flanges
                            .iter()
                            .flat_map(|f| f.location.iter().copied().collect::<Vec<_>>())
                    })
                })
                .collect(),
        )?;
        d.set_item("rollers", z)?;
        let stats = stats_dict(py, &o.stats, &o.profile)?;
        d.set_item("stats", stats)?;
        d.set_item("final_state", PyList::new(py, &o.final_state)?)?;
        d.set_item("final_time", o.final_time)?;
        d.set_item("error", o.error.clone())?;
        d.set_item("interrupted", o.interrupted)?;
        Ok(d)
    }
}
