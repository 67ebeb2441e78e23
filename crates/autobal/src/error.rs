//! Errors of the library: typed, so that a caller can match on what went wrong, and each one
//! names what it is about (the input field as the config spells it, the speed, the time).
//!
//! Numbers in messages are printed by [`fmt_num`] (six significant digits, exponent form outside
//! `1e-4 ≤ |x| < 1e6`), so that `1e308` reads `1e308`, not a 309-digit integer.
//!
//! ```
//! use autobal::error::Error;
//! let e = Error::invalid("planar.m3", "must be positive, got -1");
//! assert_eq!(e.to_string(), "planar.m3: must be positive, got -1");
//! match e {
//!     Error::InvalidParameter { field, .. } => assert_eq!(field, "planar.m3"),
//!     _ => unreachable!(),
//! }
//! ```

use thiserror::Error;

/// An input that cannot describe a physical system, an analysis that has no answer, or a run
/// that stopped early. New variants may be added (`#[non_exhaustive]`): match with a `_` arm.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum Error {
    /// A parameter is outside its physical or numerical range (negative mass, NaN, zero span,
    /// `1e308`, ...); the ranges are stated in [`crate::limits`].
    #[error("{field}: {reason}")]
    InvalidParameter {
        /// Dotted name of the offending field as the config spells it (`planar.m3`).
        field: String,
        /// Why the value is rejected.
        reason: String,
    },
    /// An input or a requested output exceeds a resource limit (file size, number of balls,
    /// grid points, ...).
    #[error("{what}: {size} exceeds the limit of {limit}{}", if reason.is_empty() { String::new() } else { format!(" ({reason})") })]
    TooLarge {
        /// The input or option (`--config`, `balancer.balls`, `--points`).
        what: String,
        /// The size asked for, in the unit of `limit`.
        size: u64,
        /// The largest size accepted.
        limit: u64,
        /// Why the limit exists (may be empty).
        reason: String,
    },
    /// An iterative solver (the eigenvalue QR iteration) did not converge at speed `omega`.
    #[error("the eigenvalue iteration did not converge at Ω = {}", fmt_num(*omega))]
    NoConvergence {
        /// The (dimensionless) speed at which it failed.
        omega: f64,
    },
    /// A long computation was stopped on request (Ctrl-C or a cancel callback) at time `t`
    /// (simulated seconds; for maps and sweeps the fraction done).
    #[error("interrupted at t = {}", fmt_num(*t))]
    Interrupted {
        /// Where it stopped.
        t: f64,
    },
    /// The mass matrix of the equations of motion became singular at time `t` (s).
    #[error("the mass matrix became singular at t = {} s", fmt_num(*t))]
    SingularMassMatrix {
        /// Simulated time (s).
        t: f64,
    },
    /// A computed quantity became NaN or infinite; `what` names it (and the input field most
    /// likely responsible, where known).
    #[error("{what} became non-finite{}", t.map_or(String::new(), |t| format!(" at t = {} s", fmt_num(t))))]
    NonFinite {
        /// The quantity (and the field responsible, where known).
        what: String,
        /// Simulated time (s), for a simulation.
        t: Option<f64>,
    },
    /// The integrator's step fell below what double precision resolves at time `t` (s).
    #[error("step size underflow at t = {} s", fmt_num(*t))]
    StepTooSmall {
        /// Simulated time (s).
        t: f64,
    },
    /// A stationary analysis asked for the linearisation of equations that have none there
    /// (friction dead zones, resting contacts of real balls); `reason` says what.
    #[error("no linearisation: {reason}")]
    NoLinearisation {
        /// What makes the equations non-differentiable.
        reason: String,
    },
    /// The integrator hit its step limit at time `t` (s).
    #[error("too many steps at t = {} s", fmt_num(*t))]
    TooManySteps {
        /// Simulated time (s).
        t: f64,
    },
}

impl Error {
    /// Shorthand for [`Error::InvalidParameter`].
    pub fn invalid(field: impl Into<String>, reason: impl Into<String>) -> Self {
        Error::InvalidParameter { field: field.into(), reason: reason.into() }
    }

    /// The input field the error names, where it names one.
    pub fn field(&self) -> Option<&str> {
        match self {
            Error::InvalidParameter { field, .. } => Some(field),
            Error::TooLarge { what, .. } => Some(what),
            _ => None,
        }
    }
}

/// Result type of the library.
pub type Result<T> = std::result::Result<T, Error>;

/// A number for a message: at most six significant digits, trailing zeros dropped, exponent
/// form outside `1e-4 ≤ |x| < 1e6` (`1e308`, `-2.5e-9`, `0.0123`, `42`, `NaN`, `inf`).
///
/// ```
/// use autobal::error::fmt_num;
/// assert_eq!(fmt_num(1e308), "1e308");
/// assert_eq!(fmt_num(0.1 + 0.2), "0.3");
/// assert_eq!(fmt_num(-2.5e-9), "-2.5e-9");
/// assert_eq!(fmt_num(104509.44), "104509");
/// assert_eq!(fmt_num(1000.0), "1000");
/// ```
pub fn fmt_num(x: f64) -> String {
    if x.is_nan() {
        return "NaN".into();
    }
    if x.is_infinite() {
        return if x > 0.0 { "inf".into() } else { "-inf".into() };
    }
    if x == 0.0 {
        return "0".into();
    }
    let a = x.abs();
    if (1e-4..1e6).contains(&a) {
        let decimals = (5 - a.log10().floor() as i32).max(0) as usize;
        let s = format!("{x:.decimals$}");
        // rounding may carry into a seventh digit (999999.7 -> 1000000): still exact enough
        trim_fraction(&s).to_string()
    } else {
        let s = format!("{x:.5e}");
        let (mantissa, exponent) = s.split_once('e').unwrap_or((&s, "0"));
        format!("{}e{exponent}", trim_fraction(mantissa))
    }
}

fn trim_fraction(s: &str) -> &str {
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.')
    } else {
        s
    }
}

/// Check that `value` is finite; returns it.
pub fn finite(field: &str, value: f64) -> Result<f64> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(Error::invalid(field, format!("must be a finite number, got {}", fmt_num(value))))
    }
}

/// Check that `value` is finite and strictly positive.
pub fn positive(field: &str, value: f64) -> Result<f64> {
    finite(field, value)?;
    if value > 0.0 {
        Ok(value)
    } else {
        Err(Error::invalid(field, format!("must be positive, got {}", fmt_num(value))))
    }
}

/// Check that `value` is finite and not negative.
pub fn non_negative(field: &str, value: f64) -> Result<f64> {
    finite(field, value)?;
    if value >= 0.0 {
        Ok(value)
    } else {
        Err(Error::invalid(field, format!("must not be negative, got {}", fmt_num(value))))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_print_short() {
        for (x, s) in [
            (1e308, "1e308"),
            (-1e-308, "-1e-308"),
            (f64::MIN_POSITIVE, "2.22507e-308"),
            (0.0, "0"),
            (1.0, "1"),
            (2.5, "2.5"),
            (0.0001, "0.0001"),
            (0.00009999, "9.999e-5"),
            (123456.7, "123457"),
            (999999.9, "1000000"),
            (1e6, "1e6"),
            (1.0 / 3.0, "0.333333"),
            (f64::NAN, "NaN"),
            (f64::NEG_INFINITY, "-inf"),
        ] {
            assert_eq!(fmt_num(x), s, "{x:e}");
        }
        // never long, whatever the value
        let mut x = 1e-320;
        while x < 1e308 {
            assert!(fmt_num(x).len() <= 12, "{x:e} -> {}", fmt_num(x));
            assert!(fmt_num(-x * 1.2345678).len() <= 13);
            x *= 3.7;
        }
    }

    #[test]
    fn messages_name_what_they_are_about() {
        assert_eq!(Error::NoConvergence { omega: 1e308 }.to_string(), "the eigenvalue iteration did not converge at Ω = 1e308");
        assert_eq!(
            Error::TooLarge { what: "--config".into(), size: 2_000_000, limit: 1_048_576, reason: "bytes".into() }.to_string(),
            "--config: 2000000 exceeds the limit of 1048576 (bytes)"
        );
        assert_eq!(Error::NonFinite { what: "the state".into(), t: Some(0.0) }.to_string(), "the state became non-finite at t = 0 s");
        assert_eq!(positive("planar.k", -1e300).unwrap_err().field(), Some("planar.k"));
    }
}
