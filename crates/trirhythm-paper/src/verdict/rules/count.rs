//! The count rule: claimed counts (roots, peaks, wells) against computed ones.
//!
//! An exact count or a count from a stationary ensemble decides; a count from a non-stationary
//! ensemble cannot. Reference: docs/verdicts.md, "Count". Tested by `tests/verdicts.rs`.

use super::super::{Check, Decision, Measured, Outcome, Verdict};
use serde::{Deserialize, Serialize};

/// Where a computed count comes from.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum CountSource {
    /// A certified count (Sturm sequence, exact roots of a theory function, grid classes).
    Exact,
    /// Modes of a Monte Carlo histogram by the prominence rule (three standard errors).
    Ensemble {
        /// Whether the ensemble passed the stationarity check.
        stationary: bool,
        /// Its R̂.
        #[serde(with = "trirhythm::non_finite")]
        r_hat: f64,
    },
}

/// One claimed count against its computed value.
#[derive(Debug, Clone)]
pub struct Count {
    /// What is counted ("roots of f, panel a (r = 1)").
    pub what: String,
    /// The paper's count.
    pub claimed: u32,
    /// The computed count.
    pub computed: u32,
    /// Where the computed count comes from.
    pub source: CountSource,
}

/// **Count**: claimed counts (roots, peaks, wells) against computed ones.
///
/// Verdict: refuted on any mismatch of an exact count or of a count from a stationary
/// ensemble; otherwise undetermined when a count comes from a non-stationary ensemble (R̂
/// given); confirmed when every count matches.
pub fn count(items: &[Count]) -> Decision {
    let mut checks = Vec::new();
    let mut refuted = false;
    let mut open = Vec::new();
    for c in items {
        let decisive = match c.source {
            CountSource::Exact => true,
            CountSource::Ensemble { stationary, r_hat } => {
                if !stationary {
                    open.push(format!(
                        "{}: not stationary (R̂ = {})",
                        c.what,
                        crate::notes::sig(r_hat, 3)
                    ));
                }
                stationary
            }
        };
        let outcome = match (decisive, c.claimed == c.computed) {
            (false, _) => Outcome::Undefined,
            (true, true) => Outcome::For,
            (true, false) => Outcome::Against,
        };
        refuted |= outcome == Outcome::Against;
        checks.push(Check {
            what: c.what.clone(),
            value: Measured::exact(c.computed as f64),
            statistic: "count".into(),
            statistic_value: c.computed as f64,
            threshold: c.claimed as f64,
            outcome,
        });
    }
    let verdict = if refuted {
        Verdict::Refuted
    } else if !open.is_empty() {
        Verdict::undetermined(open.join("; "))
    } else if items.is_empty() {
        Verdict::undetermined("no counts")
    } else {
        Verdict::Confirmed
    };
    Decision::new(
        verdict,
        "count",
        "computed count = claimed count (threshold: the claimed count); exact and stationary-ensemble counts decide, non-stationary ones cannot".into(),
        0,
        None,
        checks,
    )
}
