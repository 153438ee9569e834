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
