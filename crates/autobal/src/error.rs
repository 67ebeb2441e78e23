//! Errors of the library: every one names the input field it is about.

use thiserror::Error;

/// An input that cannot describe a physical system, or an analysis that has no answer.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum Error {
    /// A parameter is outside its physical range (negative mass, NaN, zero span, ...).
    #[error("{field}: {reason}")]
    InvalidParameter {
        /// Dotted name of the offending field as the config spells it.
        field: String,
        /// Why the value is rejected.
        reason: String,
    },
}

impl Error {
    /// Shorthand for [`Error::InvalidParameter`].
    pub fn invalid(field: impl Into<String>, reason: impl Into<String>) -> Self {
        Error::InvalidParameter { field: field.into(), reason: reason.into() }
    }
}

/// Result type of the library.
pub type Result<T> = std::result::Result<T, Error>;

/// Check that `value` is finite; returns it.
pub fn finite(field: &str, value: f64) -> Result<f64> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(Error::invalid(field, format!("must be a finite number, got {value}")))
    }
}

/// Check that `value` is finite and strictly positive.
pub fn positive(field: &str, value: f64) -> Result<f64> {
    finite(field, value)?;
    if value > 0.0 {
        Ok(value)
    } else {
        Err(Error::invalid(field, format!("must be positive, got {value}")))
    }
}

/// Check that `value` is finite and not negative.
pub fn non_negative(field: &str, value: f64) -> Result<f64> {
    finite(field, value)?;
    if value >= 0.0 {
        Ok(value)
    } else {
        Err(Error::invalid(field, format!("must not be negative, got {value}")))
    }
}
