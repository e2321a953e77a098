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
    #[error("invalid parameter {name} = {}: allowed range is {allowed}", Exact(*.value))]
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
    /// A computation of the theory produced a non-finite or runaway value.
    #[error("numerical overflow in {what} at {at}: value {}", Readable(*.value))]
    Overflow {
        /// Which computation.
        what: &'static str,
        /// Where (amplitude, grid point) in words.
        at: String,
        /// The non-finite or runaway value.
        value: f64,
    },
    /// A simulated path left the representable range (|U| or |V| above the blow-up bound, or
    /// not finite) on the step that ended at time `t`.
    #[error(
        "numerical blow-up of the simulation at t = {}: (U, U̇) = ({}, {}) after a step from ({}, {}) \
         with stiffness Δt·μ|P(U)| = {} (Δt = {}); the step is stable for any stiffness in the \
         damping, so the blow-up is the model's own growth or a much too large Δt for the \
         oscillation: try a smaller dt",
        Readable(*.t), Readable(*.u), Readable(*.v), Readable(*.from_u), Readable(*.from_v),
        Readable(*.stiffness), Readable(*.dt)
    )]
    BlowUp {
        /// Time at the end of the step.
        t: f64,
        /// U at the end of the step.
        u: f64,
        /// V = U̇ at the end of the step.
        v: f64,
        /// U at the start of the step.
        from_u: f64,
        /// V at the start of the step.
        from_v: f64,
        /// Δt·μ|P(U)| at the start of the step.
        stiffness: f64,
        /// The step Δt.
        dt: f64,
    },
    /// An iterative method did not converge.
    #[error("{what} did not converge: {detail}")]
    NoConvergence {
        /// Which method.
        what: &'static str,
        /// Residual or iteration count.
        detail: String,
    },
    /// One path of an ensemble failed: which path (noise stream), from where, and why.
    #[error("path {path} (noise stream {path}, from U = {}): {error}", Readable(*.u0))]
    InPath {
        /// The path index.
        path: u64,
        /// Its initial displacement.
        u0: f64,
        /// What went wrong on it.
        error: Box<Error>,
    },
    /// A model file (or the tables of a model) that does not read as the model's form: a
    /// syntax error, a missing or unknown field, a value of the wrong type.
    #[error("model file: {field}: {detail}")]
    Malformed {
        /// The dotted field (`damping.mu0`, `wall.0.restitution`), or `(syntax)`.
        field: String,
        /// What is wrong with it.
        detail: String,
    },
    /// A method applied to a model outside its assumptions: which method, the assumption it
    /// makes, and why the model does not meet it (the term named by its dotted field).
    #[error("{method} does not apply to this model: it assumes {assumption}; {reason}")]
    NotApplicable {
        /// The method or routine refusing (`the engine`, `the averaged theory`).
        method: String,
        /// The assumption it makes (`restoring.cubic = 0`).
        assumption: String,
        /// Why the model does not meet it, naming the term.
        reason: String,
    },
    /// The caller's [`crate::monitor::Monitor`] asked the run to stop.
    #[error("cancelled")]
    Cancelled,
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

/// A number as the user typed it (shortest round-trip digits), in scientific notation when
/// it would otherwise be long: `1e308`, not 309 digits.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Exact(pub f64);

impl std::fmt::Display for Exact {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let a = self.0.abs();
        if self.0.is_finite() && a != 0.0 && !(1e-4..1e15).contains(&a) {
            write!(f, "{:e}", self.0)
        } else {
            write!(f, "{}", self.0)
        }
    }
}

/// A number printed for people: six significant digits, in scientific notation outside
/// [1e-4, 1e6), `inf`/`NaN` as such.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Readable(pub f64);

impl std::fmt::Display for Readable {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let x = self.0;
        let a = x.abs();
        if !x.is_finite() || x == 0.0 {
            write!(f, "{x}")
        } else if (1e-4..1e6).contains(&a) {
            let digits = (5 - a.log10().floor() as i32).clamp(0, 10) as usize;
            let s = format!("{x:.digits$}");
            let s = if s.contains('.') {
                s.trim_end_matches('0').trim_end_matches('.').to_string()
            } else {
                s
            };
            write!(f, "{s}")
        } else {
            write!(f, "{x:.5e}")
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn readable_numbers() {
        let r = |x: f64| Readable(x).to_string();
        assert_eq!(r(116389576378.43837), "1.16390e11");
        assert_eq!(r(0.06), "0.06");
        assert_eq!(r(12.9412345678), "12.9412");
        assert_eq!(r(-350.25), "-350.25");
        assert_eq!(r(1e-7), "1.00000e-7");
        assert_eq!(r(f64::INFINITY), "inf");
        assert_eq!(r(0.0), "0");
    }
}
