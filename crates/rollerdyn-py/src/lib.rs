//! PyO3 bindings of rollerdyn-core: the module `rollerdyn._core`.
//!
//! Bindings only: every function forwards to the core. Array arguments arrive as
//! one-dimensional float64 arrays of equal length (the Python wrappers in
//! `rollerdyn.tribology` broadcast and reshape); scalars are model parameters. Core errors
//! become `ValueError`s carrying the core's message (quantity, value, rule); nothing here
//! panics across the boundary.
//!
//! By domain: `tribology` (the force laws, and `ARRAY_ARGUMENTS`: how many leading
//! arguments of each are arrays) and `traction` (the `EhlTraction` class),
//! `contact` (detection benchmark, circle–circle distance), `geometry` (roller mass
//! properties), `params` (the parameter dicts read into typed, nested structs, then into
//! the core's types), `simulation` (runs and the model at one state), `statics`
//! (quasi-static equilibria), `time` (the ramp and the time slack the front end applies
//! too), `constants` (`PAIRINGS`, `FLANGES`, `DETECTORS`); `convert`
//! holds what they share, among it `elementwise!`, which writes the bindings that map a
//! force law over arrays from one line each.

use pyo3::prelude::*;

mod constants;
mod contact;
mod convert;
mod geometry;
mod params;
mod simulation;
mod statics;
mod time;
mod traction;
mod tribology;

/// The module `rollerdyn._core`.
#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    constants::register(m)?;
    m.add_class::<traction::PyEhlTraction>()?;
    simulation::register(m)?;
    statics::register(m)?;
    geometry::register(m)?;
    contact::register(m)?;
    time::register(m)?;
    tribology::register(m)?;
    Ok(())
}
