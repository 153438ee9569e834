//! What every binding shares: arrays in and out (elementwise maps over equally long
//! one-dimensional float64 arrays), core errors as `ValueError`, named choices and dicts
//! filled from a struct's fields.

use numpy::{PyArray1, PyReadonlyArray1};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

/// A float64 array returned to Python.
pub(crate) type Array<'py> = Bound<'py, PyArray1<f64>>;
/// A float64 array argument.
pub(crate) type In<'py> = PyReadonlyArray1<'py, f64>;

/// A core error as a `ValueError` carrying the core's message (quantity, value, rule).
pub(crate) fn core_err(e: rollerdyn_core::Error) -> PyErr {
    PyValueError::new_err(e.to_string())
}

/// Applies `f` elementwise over equally long input arrays (named `names` in errors),
/// giving `K` output arrays.
pub(crate) fn map_many<'py, const N: usize, const K: usize>(
    py: Python<'py>,
    names: [&str; N],
    inputs: [&In<'py>; N],
    f: impl Fn([f64; N]) -> [f64; K],
) -> PyResult<[Array<'py>; K]> {
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
    let mut out: [Vec<f64>; K] = std::array::from_fn(|_| Vec::with_capacity(n));
    for values in (0..n).map(|k| f(std::array::from_fn(|j| slices[j][k]))) {
        for (column, value) in out.iter_mut().zip(values) {
            column.push(value);
        }
    }
    Ok(out.map(|column| PyArray1::from_vec(py, column)))
}

/// Applies `f` elementwise over equally long input arrays (named `names` in errors).
pub(crate) fn map<'py, const N: usize>(
    py: Python<'py>,
    names: [&str; N],
    inputs: [&In<'py>; N],
    f: impl Fn([f64; N]) -> f64,
) -> PyResult<Array<'py>> {
    let [out] = map_many(py, names, inputs, |x| [f(x)])?;
    Ok(out)
}

/// The value named `name` among `choices`, or a `ValueError` with the message `refusal`
/// makes of the name.
pub(crate) fn choose<T: Copy>(
    name: &str,
    choices: &[(&str, T)],
    refusal: impl FnOnce(&str) -> String,
) -> PyResult<T> {
    (choices.iter())
        .find(|(n, _)| *n == name)
        .map(|&(_, value)| value)
        .ok_or_else(|| PyValueError::new_err(refusal(name)))
}

/// Sets `dict[field] = value.field` for each field named, in order (`?` on failure).
macro_rules! set_fields {
    ($dict:expr, $value:expr; $($field:ident),+ $(,)?) => {
        $( $dict.set_item(stringify!($field), $value.$field)?; )+
    };
}
pub(crate) use set_fields;
