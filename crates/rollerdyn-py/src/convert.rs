//! What every binding shares: arrays in and out (elementwise maps over equally long
//! one-dimensional float64 arrays, and `elementwise!`, which writes such bindings from a
//! one-line description), core errors as `ValueError`, named choices, dicts filled from a
//! struct's fields and the registration of a module's functions.

use std::ops::RangeInclusive;

use numpy::{PyArray1, PyReadonlyArray1};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// A float64 array returned to Python.
pub(crate) type Array<'py> = Bound<'py, PyArray1<f64>>;
/// A float64 array argument.
pub(crate) type In<'py> = PyReadonlyArray1<'py, f64>;

/// A count argument (a Python int) named `name`, which must lie in `range`; a `ValueError`
/// naming it, its value and the range otherwise (PyO3's own conversion to an unsigned
/// integer says only "can't convert negative int to unsigned").
pub(crate) fn count(name: &str, value: i64, range: RangeInclusive<usize>) -> PyResult<usize> {
    match usize::try_from(value) {
        Ok(v) if range.contains(&v) => Ok(v),
        _ => Err(PyValueError::new_err(format!(
            "{name} = {value}: must be a whole number in {}..={}",
            range.start(),
            range.end()
        ))),
    }
}

/// Most right-hand sides, Jacobians or trajectory steps a timing call takes (a count above it
/// is a mistake, not a benchmark).
pub(crate) const MAX_REPETITIONS: usize = 1_000_000_000;

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

/// A dict of the arrays `columns` under the keys `names`, in order.
pub(crate) fn dict_of<'py, const K: usize>(
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

/// Adds the `#[pyfunction]`s named to the module `m` (`?` on failure).
macro_rules! add_functions {
    ($m:expr; $($f:ident),+ $(,)?) => {
        $( $m.add_function(pyo3::wrap_pyfunction!($f, $m)?)?; )+
    };
}
pub(crate) use add_functions;

/// Elementwise bindings, one per definition:
///
/// ```text
/// /// Docstring.
/// #[pyfunction]
/// fn name(x, y; scalar: f64, choice: &str) -> OUT where law = setup(scalar)? => body;
/// ```
///
/// becomes `fn name<'py>(py, x: In<'py>, y: In<'py>, scalar: f64, choice: &str)` (a method
/// when the list starts with `&self,`): the array arguments come first, the scalars after
/// `;`, so that Python sees the same names in the same order. The `where` bindings are
/// evaluated once (`?` allowed); then `body` is evaluated at each element, with each array
/// argument standing for its element there ([`map_many`], whose errors name the
/// arguments). `OUT` says what Python gets: `Array` (body gives an `f64`: one array),
/// `(a, b)` (body gives `[f64; 2]`: a tuple of arrays; the names are for the reader) or
/// `{a, b}` (body gives `[f64; 2]`: a dict of arrays under those keys). The attributes
/// before `fn` (docstring, `#[pyfunction]`) are kept.
///
/// Functions also get a table `ARRAY_ARGUMENTS` of their names and numbers of array
/// arguments (so one such `elementwise!` per module). For methods, the `#[pymethods]` block is written first and its own items are kept as
/// they are (PyO3 wants one block per class): `elementwise! { #[pymethods] impl Class {
/// ... } fn method(&self, x) -> Array => self.f(x); }`. Code inside the macro's braces is
/// not reformatted by rustfmt.
macro_rules! elementwise {
    (
        $(#[$class_attr:meta])* impl $class:ident { $($class_items:tt)* }
        $(
            $(#[$attr:meta])*
            fn $name:ident(&$s:ident, $($x:ident),+ $(; $($p:ident: $t:ty),+)?) -> $out:tt
            $(where $($v:ident = $init:expr),+)? => $body:expr;
        )+
    ) => {
        $(#[$class_attr])*
        impl $class {
            $($class_items)*
            $(
                $(#[$attr])*
                #[allow(clippy::too_many_arguments)]
                fn $name<'py>(
                    &$s, py: Python<'py>, $($x: $crate::convert::In<'py>,)+ $($($p: $t),+)?
                ) -> PyResult<Bound<'py, PyAny>> {
                    $crate::convert::elementwise!(
                        @body py, $out, [$($x),+], [$($($v = $init),+)?], $body
                    )
                }
            )+
        }
    };
    (
        $(
            $(#[$attr:meta])*
            fn $name:ident($($x:ident),+ $(; $($p:ident: $t:ty),+)?) -> $out:tt
            $(where $($v:ident = $init:expr),+)? => $body:expr;
        )+
    ) => {
        /// How many leading arguments of each function are arrays (`_core.ARRAY_ARGUMENTS`,
        /// for the Python wrappers that broadcast them).
        pub(crate) const ARRAY_ARGUMENTS: &[(&str, usize)] =
            &[$((stringify!($name), [$(stringify!($x)),+].len())),+];
        $(
            $(#[$attr])*
            #[allow(clippy::too_many_arguments)]
            fn $name<'py>(
                py: Python<'py>, $($x: $crate::convert::In<'py>,)+ $($($p: $t),+)?
            ) -> PyResult<Bound<'py, PyAny>> {
                $crate::convert::elementwise!(
                    @body py, $out, [$($x),+], [$($($v = $init),+)?], $body
                )
            }
        )+
    };
    (@body $py:ident, $out:tt, [$($x:ident),+], [$($v:ident = $init:expr),*], $body:expr) => {{
        $(let $v = $init;)*
        let names = [$(stringify!($x)),+];
        let inputs = [$(&$x),+];
        $crate::convert::elementwise!(@out $py, $out, names, inputs, |[$($x),+]| $body)
    }};
    (@out $py:ident, Array, $names:ident, $inputs:ident, $f:expr) => {
        $crate::convert::map($py, $names, $inputs, $f).map(Bound::into_any)
    };
    (@out $py:ident, ($($o:ident),+), $names:ident, $inputs:ident, $f:expr) => {
        $crate::convert::map_many($py, $names, $inputs, $f)
            .and_then(|columns| Ok(pyo3::types::PyTuple::new($py, columns)?.into_any()))
    };
    (@out $py:ident, {$($k:ident),+}, $names:ident, $inputs:ident, $f:expr) => {
        $crate::convert::map_many($py, $names, $inputs, $f)
            .and_then(|columns| $crate::convert::dict_of($py, [$(stringify!($k)),+], columns))
            .map(Bound::into_any)
    };
}
pub(crate) use elementwise;
