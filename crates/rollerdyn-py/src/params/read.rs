//! How a typed parameter struct is read from a Python dict: every value through
//! [`Param`], each nested dict as a [`Section`] that records the keys read and refuses the
//! rest. Errors are `ValueError`s naming the value by its path ("model parameter
//! geometry.roller.radius is missing", "... is not a parameter of the core",
//! "... = x: wrong type", "... = x: must be a or b").
//!
//! The structs themselves are declared with [`section!`]: the declaration is the schema,
//! so a field added to a struct is a key the dict must hold, and a key the dict holds
//! without a field is refused.

use crate::convert::choose;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::cell::RefCell;
use std::collections::BTreeSet;

/// What a dict holds, for messages: the model's parameters or a run's options.
#[derive(Clone, Copy)]
pub(crate) enum Kind {
    Parameter,
    Option,
}

impl Kind {
    /// "model parameter" or "run option", before a path.
    fn noun(self) -> &'static str {
        match self {
            Kind::Parameter => "model parameter",
            Kind::Option => "run option",
        }
    }

    /// "a parameter" or "an option", after "is not".
    fn short(self) -> &'static str {
        match self {
            Kind::Parameter => "a parameter",
            Kind::Option => "an option",
        }
    }
}

/// One dict being read into one struct: its path and the keys read from it so far.
pub(crate) struct Section<'py> {
    dict: Bound<'py, PyDict>,
    kind: Kind,
    /// Prefix of the keys in messages: "" at the top, "geometry." in a nested dict.
    prefix: String,
    read: RefCell<BTreeSet<String>>,
}

impl<'py> Section<'py> {
    fn new(dict: Bound<'py, PyDict>, kind: Kind, prefix: String) -> Self {
        Section {
            dict,
            kind,
            prefix,
            read: RefCell::new(BTreeSet::new()),
        }
    }

    /// `key` as messages name it ("model parameter geometry.roller_count").
    fn name(&self, key: &str) -> String {
        format!("{} {}{key}", self.kind.noun(), self.prefix)
    }

    /// A `ValueError` about `key` of this dict: its name followed by `what`.
    pub(crate) fn error(&self, key: &str, what: &str) -> PyErr {
        PyValueError::new_err(format!("{}{what}", self.name(key)))
    }

    /// The wrong-type error of `key`, whose value is `v`.
    pub(crate) fn wrong_type(&self, key: &str, v: &Bound<'py, PyAny>) -> PyErr {
        self.error(key, &format!(" = {v}: wrong type"))
    }

    /// The value under `key` (None when absent), recorded as read.
    pub(crate) fn item(&self, key: &str) -> PyResult<Option<Bound<'py, PyAny>>> {
        self.read.borrow_mut().insert(key.to_owned());
        self.dict.get_item(key)
    }

    /// The dict `v` under `key`, as a section of its own.
    fn nested(&self, key: &str, v: &Bound<'py, PyAny>) -> PyResult<Section<'py>> {
        let dict = v.cast::<PyDict>().map_err(|_| self.wrong_type(key, v))?;
        Ok(Section::new(
            dict.clone(),
            self.kind,
            format!("{}{key}.", self.prefix),
        ))
    }

    /// Ok when every key of the dict was read; else ValueError naming the first one that
    /// was not (in the dict's order).
    pub(crate) fn done(&self) -> PyResult<()> {
        let read = self.read.borrow();
        for key in self.dict.keys() {
            let unread = match key.extract::<String>() {
                Ok(k) if read.contains(&k) => continue,
                Ok(k) => k,
                Err(_) => key.repr()?.to_string(),
            };
            let what = format!(" is not {} of the core", self.kind.short());
            return Err(self.error(&unread, &what));
        }
        Ok(())
    }
}

/// A value that can be read from a dict: a number, a flag, a name, a list, or a nested
/// struct (a dict of its own).
pub(crate) trait Param: Sized {
    /// The value `v` under `key` of `section`.
    fn from_value<'py>(section: &Section<'py>, key: &str, v: &Bound<'py, PyAny>) -> PyResult<Self>;

    /// The value under `key` of `section`, which must be there.
    fn from_key(section: &Section<'_>, key: &str) -> PyResult<Self> {
        match section.item(key)? {
            Some(v) => Self::from_value(section, key, &v),
            None => Err(section.error(key, " is missing")),
        }
    }
}

/// Values Python gives directly (`extract`).
macro_rules! extracted {
    ($($t:ty),+) => {$(
        impl Param for $t {
            fn from_value<'py>(s: &Section<'py>, key: &str, v: &Bound<'py, PyAny>) -> PyResult<Self> {
                v.extract::<$t>().map_err(|_| s.wrong_type(key, v))
            }
        }
    )+};
}
extracted!(f64, usize, bool, String, Vec<f64>, [f64; 3], [bool; 4]);

/// A value that must be given but may be None.
impl<T: Param> Param for Option<T> {
    fn from_value<'py>(s: &Section<'py>, key: &str, v: &Bound<'py, PyAny>) -> PyResult<Self> {
        if v.is_none() {
            Ok(None)
        } else {
            T::from_value(s, key, v).map(Some)
        }
    }
}

/// A value that may be left out (or None).
pub(crate) struct Omittable<T>(pub(crate) Option<T>);

impl<T: Param> Param for Omittable<T> {
    fn from_value<'py>(s: &Section<'py>, key: &str, v: &Bound<'py, PyAny>) -> PyResult<Self> {
        Option::<T>::from_value(s, key, v).map(Omittable)
    }

    fn from_key(s: &Section<'_>, key: &str) -> PyResult<Self> {
        match s.item(key)? {
            Some(v) => Self::from_value(s, key, &v),
            None => Ok(Omittable(None)),
        }
    }
}

/// A struct read from a dict, field by field (declared with [`section!`]).
pub(crate) trait Fields: Sized {
    /// The struct from `section`'s keys (the caller refuses the keys left unread).
    fn read_fields(section: &Section<'_>) -> PyResult<Self>;
}

/// The nested dict `v` under `key` of `s`, read as a `T` with no key left over.
pub(crate) fn nested<'py, T: Fields>(
    s: &Section<'py>,
    key: &str,
    v: &Bound<'py, PyAny>,
) -> PyResult<T> {
    nested_with(s, key, v, T::read_fields)
}

/// The nested dict `v` under `key` of `s`, read by `read` with no key left over.
pub(crate) fn nested_with<'py, T>(
    s: &Section<'py>,
    key: &str,
    v: &Bound<'py, PyAny>,
    read: impl FnOnce(&Section<'py>) -> PyResult<T>,
) -> PyResult<T> {
    read_whole(&s.nested(key, v)?, read)
}

/// `read(section)`, then every key of the section must have been read.
fn read_whole<'py, T>(
    section: &Section<'py>,
    read: impl FnOnce(&Section<'py>) -> PyResult<T>,
) -> PyResult<T> {
    let value = read(section)?;
    section.done()?;
    Ok(value)
}

/// The top-level dict `dict` (the model's parameters or a run's options) read as a `T`
/// with no key left over.
pub(crate) fn read_dict<T: Fields>(dict: &Bound<'_, PyDict>, kind: Kind) -> PyResult<T> {
    read_whole(
        &Section::new(dict.clone(), kind, String::new()),
        T::read_fields,
    )
}

/// One of a few names, each standing for a value of `T`.
pub(crate) fn choice<'py, T: Copy>(
    s: &Section<'py>,
    key: &str,
    v: &Bound<'py, PyAny>,
    choices: &[(&str, T)],
) -> PyResult<T> {
    let name = String::from_value(s, key, v)?;
    choose(&name, choices, |name| {
        let names: Vec<&str> = choices.iter().map(|(n, _)| *n).collect();
        let (last, rest) = names.split_last().expect("a choice has names");
        format!(
            "{} = {name}: must be {} or {last}",
            s.name(key),
            rest.join(", ")
        )
    })
}

/// Declares a struct read from a dict: one key per field, named as the field, every key
/// required (`Option<T>`: may be None; [`Omittable<T>`]: may be left out), no other key
/// allowed. Each field's type is a [`Param`]: a value, or a struct declared here too.
macro_rules! section {
    ($(
        $(#[$meta:meta])*
        struct $name:ident {
            $( $(#[$field_meta:meta])* $field:ident : $ty:ty ),* $(,)?
        }
    )+) => {$(
        $(#[$meta])*
        pub(crate) struct $name {
            $( $(#[$field_meta])* pub(crate) $field: $ty, )*
        }

        impl $crate::params::read::Fields for $name {
            fn read_fields(
                s: &$crate::params::read::Section<'_>,
            ) -> pyo3::PyResult<Self> {
                use $crate::params::read::Param;
                Ok($name {
                    $( $field: <$ty>::from_key(s, stringify!($field))?, )*
                })
            }
        }

        impl $crate::params::read::Param for $name {
            fn from_value<'py>(
                s: &$crate::params::read::Section<'py>,
                key: &str,
                v: &pyo3::Bound<'py, pyo3::PyAny>,
            ) -> pyo3::PyResult<Self> {
                $crate::params::read::nested(s, key, v)
            }
        }
    )+};
}
pub(crate) use section;
