//! The EHL traction model of one lubricant at one temperature as a Python class,
//! `rollerdyn._core.EhlTraction` (core `tribology::traction`, paper sect. 3.2.1: Roelands
//! eq. 19, Carreau eq. 21, the limiting shear stress eq. 50).

use crate::convert::{count, elementwise, MAX_REPETITIONS};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use rollerdyn_core::tribology::lubricant::{Carreau, Roelands};
use rollerdyn_core::tribology::traction::{EhlTraction, LimitingShearStress, TableGrid};

/// Most nodes across or along an ellipse of `ellipse_force_tensor` (the paper's scheme
/// converges with tens; a count above it is a mistake, not a quadrature).
const MAX_ELLIPSE_NODES: usize = 10_000;

/// The EHL traction model of one lubricant at one temperature (paper sect. 3.2.1).
#[pyclass(name = "EhlTraction", module = "rollerdyn._core")]
pub(crate) struct PyEhlTraction {
    pub(crate) inner: EhlTraction,
    lss: LimitingShearStress,
}

elementwise! {
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
            nodes: i64,
            tabulated: bool,
        ) -> PyResult<Self> {
            for (name, v) in [
                ("eta0", eta0),
                ("tau0", tau0),
                ("eta_p", eta_p),
                ("lss_smoothing", lss_smoothing),
                ("z", z),
                ("p_star", p_star),
                ("tau_l0", tau_l0),
            ] {
                if !(v.is_finite() && v > 0.0) {
                    return Err(PyValueError::new_err(format!(
                        "{name} = {v}: must be finite and positive"
                    )));
                }
            }
            if !(chi.is_finite() && chi >= 0.0) {
                return Err(PyValueError::new_err(format!(
                    "chi = {chi}: must be finite and >= 0"
                )));
            }
            if !(p_p.is_finite() && p_p < 0.0) {
                return Err(PyValueError::new_err(format!(
                    "p_p = {p_p}: must be finite and negative (the pole of eq. 19)"
                )));
            }
            if !(n > 0.0 && n <= 1.0) {
                return Err(PyValueError::new_err(format!(
                    "n = {n}: must lie in (0, 1]"
                )));
            }
            let nodes = count("nodes", nodes, 1..=200)?;
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

        /// The paper's tensor scheme for the ellipse (Gauss–Legendre x trapezoid).
        #[allow(clippy::too_many_arguments)]
        fn ellipse_force_tensor(
            &self,
            max_pressure: f64,
            semi_major: f64,
            semi_minor: f64,
            sliding_speed: f64,
            film: f64,
            across: i64,
            along: i64,
        ) -> PyResult<f64> {
            let across = count("across", across, 1..=MAX_ELLIPSE_NODES)?;
            let along = count("along", along, 1..=MAX_ELLIPSE_NODES)?;
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
        /// Runs without the interpreter's lock, so that the caller may wait for it in
        /// another thread and still take Ctrl-C.
        fn time_per_evaluation(&self, py: Python<'_>, repetitions: i64) -> PyResult<(f64, f64)> {
            let reps = count("repetitions", repetitions, 1..=MAX_REPETITIONS)?;
            let inner = &self.inner;
            Ok(py.detach(|| {
                let line = nanoseconds_per_call(reps, |p0, du| {
                    inner.line_force(p0, 1.2e-4, 2.5e-4, 0.01 + du, 2e-7)
                });
                let ellipse = nanoseconds_per_call(reps, |p0, du| {
                    inner.ellipse_force(p0, 3e-4, 1e-4, 0.05 + du, 2e-7)
                });
                (line, ellipse)
            }))
        }
    }

    /// Roelands viscosity at pressure.
    fn viscosity(&self, pressure) -> Array => self.inner.viscosity(pressure);

    /// Limiting shear stress (eq. 50, smoothed corner).
    fn limiting_shear_stress(&self, pressure) -> Array => self.lss.at(pressure);

    /// Film shear stress at pressure and shear rate.
    fn shear_stress(&self, pressure, shear_rate) -> Array =>
        self.inner.shear_stress(pressure, shear_rate);

    /// EHL tangential force of line slices.
    fn line_force(&self, max_pressure, half_width, length, sliding_speed, film) -> Array =>
        self.inner.line_force(max_pressure, half_width, length, sliding_speed, film);

    /// EHL tangential force of elliptical contacts.
    fn ellipse_force(&self, max_pressure, semi_major, semi_minor, sliding_speed, film) -> Array =>
        self.inner.ellipse_force(max_pressure, semi_major, semi_minor, sliding_speed, film);
}

/// Nanoseconds per call of `force(max_pressure, sliding_speed_offset)` over `reps` calls on
/// B1-like contacts (max. pressures 0.5–2 GPa, sliding speeds in steps of 1 mm/s).
fn nanoseconds_per_call(reps: usize, force: impl Fn(f64, f64) -> f64) -> f64 {
    let mut sink = 0.0;
    let start = std::time::Instant::now();
    for i in 0..reps {
        let p0 = 0.5e9 + 1.5e9 * (i % 97) as f64 / 97.0;
        sink += force(p0, 1e-3 * (i % 13) as f64);
    }
    std::hint::black_box(sink);
    start.elapsed().as_secs_f64() * 1e9 / reps as f64
}
