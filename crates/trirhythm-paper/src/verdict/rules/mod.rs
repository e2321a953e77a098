//! The verdict rules: pure functions from numbers with uncertainties to a [`Decision`].
//!
//! Each rule states its statistic and thresholds in the decision (`statistic`, each check's
//! `threshold`), so a reader can redo it by hand. The constants below are the thresholds;
//! one file per rule family: [`trend()`] (with [`Direction`] and [`Series`]), [`count()`],
//! [`sign_change()`], [`agreement()`] and [`closeness()`]. docs/verdicts.md gives the reasons.
//! Tested by `tests/verdicts.rs`: every rule with cases that confirm, refute and are
//! undetermined, including the multiplicity effect (one 2.03σ point among 36 tests is not
//! significant).
//!
//! [`Decision`]: super::Decision

mod agreement;
mod count;
mod regime;
mod sign_change;
mod trend;

pub use agreement::{agreement, closeness, Comparison, Weightings, MIN_WEIGHTING_REPLICAS};
pub use count::{count, Count, CountSource};
pub use regime::{
    agrees_with_prediction, bracket, call, calls, rest_regime, strong_noise, Bracket, Call,
    RegimePoint, RestRegime, StrongNoise, REST_DECADES, REST_HOMOGENEOUS_D,
};
pub use sign_change::{locate, sign_change, significance, LleCurve, LlePoint, Located, PointSign};
pub use trend::{trend, Direction, Series};

/// Family-wise significance level of every stochastic test (two-sided, Holm–Bonferroni over
/// the tests of one claim).
pub const ALPHA: f64 = 0.05;

/// Relative tolerance for numerical error when deterministic numbers are compared: a change
/// smaller than this fraction of the larger magnitude is no change.
pub const EXACT_REL_TOL: f64 = 1e-9;

/// Standard errors above the finite-sample floor that a Hellinger distance may lie and still
/// agree (k of the agreement rule).
pub const AGREEMENT_K: f64 = 2.0;

/// Relative difference below which two numbers "align closely" / change "very slightly".
pub const CLOSENESS_REL_TOL: f64 = 0.05;

/// `z`, or `t (ν = …)` for a statistic with few degrees of freedom.
fn stat_name(dof: f64) -> String {
    if dof.is_finite() {
        format!("t (ν = {})", crate::notes::num(dof))
    } else {
        "z".into()
    }
}
