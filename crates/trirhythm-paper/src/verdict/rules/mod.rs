//! The verdict rules: pure functions from numbers with uncertainties to a [`Decision`].
//!
//! Each rule states its statistic and thresholds in the decision (`statistic`, each check's
//! `threshold`), so a reader can redo it by hand. The constants below are the thresholds;
//! one file per rule family: [`trend()`] (with [`Direction`] and [`Series`]), [`count()`]
//! (with [`separate_maxima`] for a 2-D density), [`sign_change()`], [`agreement()`],
//! [`closeness()`], [`dependence()`] (its complement: "depends on", "changes significantly")
//! and [`curve_distance()`] (two sets of curves in a plane). docs/verdicts.md gives the reasons.
//! Tested by `tests/verdicts.rs`: every rule with cases that confirm, refute and are
//! undetermined, including the multiplicity effect (one 2.03σ point among 36 tests is not
//! significant).
//!
//! [`Decision`]: super::Decision

mod agreement;
mod count;
mod curves;
mod dependence;
mod regime;
mod sign_change;
mod trend;

pub use agreement::{
    agreement, closeness, Comparison, WeightingRange, Weightings, MIN_WEIGHTING_REPLICAS,
};
pub use count::{count, separate_maxima, separate_maxima_significant, Count, CountSource};
pub use curves::{curve_distance, directed_distance, CurveSets, Polyline};
pub use dependence::dependence;
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

/// Relative difference below which two numbers "align closely" / change "very slightly"; above
/// it (beyond the margin) a quantity "depends on" / "changes significantly with" a parameter.
pub const CLOSENESS_REL_TOL: f64 = 0.05;

/// Hausdorff distance, as a fraction of the plane (axes scaled to [0, 1]), within which two
/// sets of curves are the same set: the closeness tolerance applied to positions in the plane.
pub const CURVE_TOL: f64 = CLOSENESS_REL_TOL;

/// Fraction of a heat map's largest density below which cells are not drawn as features of it
/// when separate maxima are counted: two decades below the brightest cell.
pub const PEAK_FLOOR: f64 = 1e-2;

/// A maximum is separate when the highest path to a higher one dips to at most this fraction
/// of its height (resolved at half maximum).
pub const PEAK_DIP: f64 = 0.5;

/// Standard errors by which a Monte Carlo maximum must stand above the highest way to a higher
/// one to count as separate (the prominence rule's three standard errors of the 1-D mode count).
pub const PEAK_SE_K: f64 = 3.0;

/// Largest fraction of a Monte Carlo density outside a plotted window for a count of its
/// maxima on that window to stand for the density.
pub const WINDOW_MASS_TOL: f64 = 0.01;

/// `z`, or `t (ν = …)` for a statistic with few degrees of freedom.
fn stat_name(dof: f64) -> String {
    if dof.is_finite() {
        format!("t (ν = {})", crate::notes::num(dof))
    } else {
        "z".into()
    }
}
