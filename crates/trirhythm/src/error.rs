//! The library's one error type.
//!
//! Every fallible function of the crate returns [`Result`]. Variants carry the data a user needs
//! to act on the message: the parameter's name, its value and the allowed range; the time at which
//! a simulation blew up; the quantity that failed to converge.

/// Errors of the `trirhythm` library.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A parameter is outside its allowed range (or not finite).
    #[error("invalid parameter {name} = {value}: allowed range is {allowed}")]
    InvalidParameter {
        /// The parameter's key as users type it (`lambda`, `r`, `D`, …).
        name: String,
        /// The offending value.
        value: f64,
        /// Human-readable allowed range, e.g. `(0, 1]`.
        allowed: String,
    },
    /// An unknown parameter key or preset name.
    #[error("unknown {kind} `{name}`: expected one of {expected}")]
    Unknown {
        /// What was looked up (`parameter`, `preset`, …).
        kind: &'static str,
        /// The name that was not found.
        name: String,
        /// The accepted names.
        expected: String,
    },
    /// The requested quantity does not exist for these parameters.
    #[error("{what} is undefined here: {why}")]
    Undefined {
        /// The quantity (e.g. `stationary amplitude PDF`).
        what: &'static str,
        /// Why, in terms of the parameters.
        why: String,
    },
    /// A numerical computation produced a non-finite value.
    #[error("numerical blow-up in {what} at {at}: value {value}")]
    BlowUp {
        /// Which computation.
        what: &'static str,
        /// Where (time, amplitude, grid point) in words.
        at: String,
        /// The non-finite or runaway value.
        value: f64,
    },
    /// An iterative method did not converge.
    #[error("{what} did not converge: {detail}")]
    NoConvergence {
        /// Which method.
        what: &'static str,
        /// Residual or iteration count.
        detail: String,
    },
}

/// Result alias of the library.
pub type Result<T> = std::result::Result<T, Error>;

impl Error {
    /// Build [`Error::InvalidParameter`].
    pub fn invalid(name: impl Into<String>, value: f64, allowed: impl Into<String>) -> Self {
        Error::InvalidParameter {
            name: name.into(),
            value,
            allowed: allowed.into(),
        }
    }
}
