//! The EHL traction model of one lubricant at one temperature as a Python class,
//! `rollerdyn._core.EhlTraction` (core `tribology::traction`, paper sect. 3.2.1: Roelands
//! eq. 19, Carreau eq. 21, the limiting shear stress eq. 50).

use crate::convert::{map, Array, In};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use rollerdyn_core::tribology::lubricant::{Carreau, Roelands};
use rollerdyn_core::tribology::traction::{EhlTraction, LimitingShearStress, TableGrid};

/// The EHL traction model of one lubricant at one temperature (paper sect. 3.2.1).
#[pyclass(name = "EhlTraction", module = "rollerdyn._core")]
pub(crate) struct PyEhlTraction {
    pub(crate) inner: EhlTraction,
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
