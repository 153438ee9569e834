//! Bindings of the roller's geometry (core `geometry::roller`).

use crate::convert::{core_err, set_fields};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rollerdyn_core::geometry::roller::RollerShape;

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
    set_fields!(d, m; volume, mass, axial_inertia, transverse_inertia);
    d.set_item("straight_length", shape.straight_length())?;
    Ok(d)
}

/// Adds this module's functions to `m`.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(roller_mass_properties, m)?)
}
