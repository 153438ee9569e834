//! The core's rules about time that the front end applies too, exported so that Python
//! need not mirror them: the load and speed ramp (core `History::Ramp`) and the slack
//! within which two times count as equal (core `dynamics::integrate::slack`).

use crate::convert::core_err;
use pyo3::prelude::*;
use rollerdyn_core::bearing::History;
use rollerdyn_core::dynamics::integrate::slack;
use rollerdyn_core::error::Error;

/// The ramp's factor at the fraction ``x`` of its span (clipped to 0 … 1): ``x`` for
/// ``shape = "linear"``, ``(1 - cos(pi x))/2`` for ``"cosine"`` (core ``History::Ramp``).
#[pyfunction]
fn ramp_factor(shape: &str, x: f64) -> PyResult<f64> {
    let cosine = match shape {
        "cosine" => true,
        "linear" => false,
        other => {
            return Err(core_err(Error::invalid(
                "shape",
                other,
                "must be 'cosine' or 'linear'",
            )))
        }
    };
    let ramp = History::Ramp {
        value: 1.0,
        start: 0.0,
        end: 1.0,
        cosine,
    };
    Ok(ramp.at(x).0)
}

/// Times closer than this to ``t`` count as equal [s] (the core's rule for output and
/// checkpoint times: relative 1e-12, absolute below 1 s).
#[pyfunction]
fn time_slack(t: f64) -> f64 {
    slack(t)
}

/// Adds this module's functions to `m`.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(ramp_factor, m)?)?;
    m.add_function(wrap_pyfunction!(time_slack, m)?)
}
