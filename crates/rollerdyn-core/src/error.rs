//! The one error type of the core. Every refusal names the quantity, its value and the
//! rule it broke, so that the Python front end can show it to the user unchanged.

/// Errors of rollerdyn-core.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Error {
    /// A parameter outside its physical domain.
    #[error("{name} = {value}: {rule}")]
    InvalidParameter {
        /// Name of the parameter, in the paper's vocabulary.
        name: &'static str,
        /// The offending value.
        value: f64,
        /// The rule it broke, e.g. "must be positive".
        rule: &'static str,
    },
    /// A model setting that cannot be simulated (named field, value, rule).
    #[error("{name} = {value}: {rule}")]
    Invalid {
        /// The field.
        name: String,
        /// The offending value, as shown to the user.
        value: String,
        /// The rule it broke.
        rule: String,
    },
    /// An iterative method that did not converge.
    #[error("{what} did not converge: {detail}")]
    NoConvergence {
        /// What was being solved.
        what: &'static str,
        /// Why it stopped.
        detail: String,
    },
}

impl Error {
    /// A refusal of `name` = `value` by `rule`.
    pub fn invalid(
        name: impl Into<String>,
        value: impl std::fmt::Display,
        rule: impl Into<String>,
    ) -> Self {
        Error::Invalid {
            name: name.into(),
            value: value.to_string(),
            rule: rule.into(),
        }
    }
}

/// Result alias of the core.
pub type Result<T> = std::result::Result<T, Error>;

/// Refuses a value that is not finite and strictly positive.
pub fn require_positive(name: &'static str, value: f64) -> Result<f64> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(Error::InvalidParameter {
            name,
            value,
            rule: "must be finite and positive",
        })
    }
}

/// Refuses a value that is not finite and non-negative.
pub fn require_non_negative(name: &'static str, value: f64) -> Result<f64> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(Error::InvalidParameter {
            name,
            value,
            rule: "must be finite and non-negative",
        })
    }
}

/// Refuses a value that is not finite.
pub fn require_finite(name: &'static str, value: f64) -> Result<f64> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(Error::InvalidParameter {
            name,
            value,
            rule: "must be finite",
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn refusals_name_value_and_rule() {
        let e = require_positive("roller radius", -1.0).unwrap_err();
        assert_eq!(
            e.to_string(),
            "roller radius = -1: must be finite and positive"
        );
        assert!(require_positive("x", f64::NAN).is_err());
        assert!(require_non_negative("x", 0.0).is_ok());
        assert!(require_finite("x", f64::INFINITY).is_err());
    }
}
