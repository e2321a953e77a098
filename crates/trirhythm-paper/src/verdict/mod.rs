//! Verdicts on the paper's claims as data: a claim, the rule that decides it, and the numbers
//! the rule used.
//!
//! # What a verdict is
//! A [`Decision`] holds the [`Verdict`] — [`Verdict::Confirmed`], [`Verdict::Refuted`] or
//! [`Verdict::Undetermined`] with the reason — and the deciding numbers: one [`Check`] per
//! comparison (the value with its [`Uncertainty`]: exact, a standard error or a bracket; the
//! statistic; the threshold it was held against; the outcome), the number of tests the
//! multiple-testing correction counted and the significance level.
//!
//! # The rules ([`rules`])
//! - [`rules::trend`]: a claimed monotone change. Each step between neighbouring values and the
//!   change across the whole plotted range is a test; standard errors give a z statistic,
//!   decided two-sided at α = 0.05 with the Holm–Bonferroni correction over every stochastic
//!   test of the claim; exact (deterministic) values compare exactly up to a relative
//!   tolerance; brackets compare by overlap. Confirmed when the change across the range is
//!   significant in the claimed direction and no step is significant against it; refuted when
//!   a step or the range is significant against it.
//! - [`rules::count`]: claimed counts against computed ones; refuted by any mismatch of an
//!   exact count or a count from a stationary ensemble; undetermined when a count comes from
//!   a non-stationary ensemble.
//! - [`rules::sign_change`]: the largest Lyapunov exponent turns from negative to positive as
//!   D grows: significant values of both signs (Student's t with realisations − 1 degrees of
//!   freedom, Holm–Bonferroni over all points of the claim), every significant negative below
//!   every significant positive.
//! - [`rules::agreement`]: theory against Monte Carlo: the Hellinger distance within the
//!   finite-sample floor √(bins/(8·ESS)) plus k = 2 standard errors, stationary ensembles only.
//! - [`rules::closeness`]: a relative difference below a stated tolerance (5 %).
//!
//! The claims themselves, computed from the figures' data, are in [`claims`]; docs/verdicts.md
//! states every rule and lists the claims. Tested by `tests/verdicts.rs` (each rule's
//! confirming, refuting and undetermined cases; cheap theory claims in quick mode; a changed
//! figure changes its verdict).

pub mod claims;
pub mod rules;
pub mod stats;

use serde::{Deserialize, Serialize};

/// The outcome of a rule on a claim.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(tag = "verdict", rename_all = "snake_case")]
pub enum Verdict {
    /// The claim holds by the rule.
    Confirmed,
    /// The claim fails by the rule.
    Refuted,
    /// The computation cannot decide the claim.
    Undetermined {
        /// Why: not stationary, not significant, a parameter not printed, …
        why: String,
    },
}

impl Verdict {
    /// `confirmed`, `refuted` or `undetermined`.
    pub fn tag(&self) -> &'static str {
        match self {
            Verdict::Confirmed => "confirmed",
            Verdict::Refuted => "refuted",
            Verdict::Undetermined { .. } => "undetermined",
        }
    }

    /// An undetermined verdict for `why`.
    pub fn undetermined(why: impl Into<String>) -> Verdict {
        Verdict::Undetermined { why: why.into() }
    }
}

/// The uncertainty of a number.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Uncertainty {
    /// A deterministic number (theory, a count on a grid): compared up to a relative
    /// tolerance for numerical error.
    Exact,
    /// A standard error (a Monte Carlo mean, a Lyapunov exponent over realisations).
    StdErr {
        /// The standard error (non-finite or ≤ 0: none could be estimated).
        #[serde(with = "trirhythm::non_finite")]
        se: f64,
        /// Its degrees of freedom (realisations − 1) where few: tests then use Student's t;
        /// `None`: many, the normal distribution.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        dof: Option<f64>,
    },
    /// A bracket known to hold the value (a boundary found by bisection).
    Bracket {
        /// Lower end.
        #[serde(with = "trirhythm::non_finite")]
        lo: f64,
        /// Upper end.
        #[serde(with = "trirhythm::non_finite")]
        hi: f64,
    },
}

/// A number with its uncertainty.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Measured {
    /// The value (NaN or infinite: undefined, e.g. a merged Lyapunov realisation).
    #[serde(with = "trirhythm::non_finite")]
    pub value: f64,
    /// Its uncertainty.
    pub uncertainty: Uncertainty,
}

impl Measured {
    /// A deterministic value.
    pub fn exact(value: f64) -> Measured {
        Measured {
            value,
            uncertainty: Uncertainty::Exact,
        }
    }

    /// A value with a standard error from many realisations (normal tests).
    pub fn with_se(value: f64, se: f64) -> Measured {
        Measured {
            value,
            uncertainty: Uncertainty::StdErr { se, dof: None },
        }
    }

    /// A value with a standard error of `dof` degrees of freedom (Student's t tests).
    pub fn with_se_dof(value: f64, se: f64, dof: Option<f64>) -> Measured {
        Measured {
            value,
            uncertainty: Uncertainty::StdErr { se, dof },
        }
    }

    /// A value inside a bracket.
    pub fn bracket(value: f64, lo: f64, hi: f64) -> Measured {
        Measured {
            value,
            uncertainty: Uncertainty::Bracket { lo, hi },
        }
    }

    /// A bracketed value in words with `digits` significant digits: `v in [lo, hi]`; `none`
    /// when infinite (no such value at all); `> lo`, `< hi` or `in [lo, hi]` when one-sided or
    /// without a point value. Other values: as [`crate::notes::sig`].
    pub fn bracket_words(&self, digits: usize) -> String {
        use crate::notes::sig;
        let Uncertainty::Bracket { lo, hi } = self.uncertainty else {
            return sig(self.value, digits);
        };
        if lo == f64::INFINITY {
            "none".into()
        } else if self.value.is_nan() && hi == f64::INFINITY {
            format!("> {}", sig(lo, digits))
        } else if self.value.is_nan() && lo == 0.0 {
            format!("< {}", sig(hi, digits))
        } else if self.value.is_nan() {
            format!("in [{}, {}]", sig(lo, digits), sig(hi, digits))
        } else {
            format!(
                "{} in [{}, {}]",
                sig(self.value, digits),
                sig(lo, digits),
                sig(hi, digits)
            )
        }
    }

    /// The interval the value is known to lie in: a point when exact, the bracket, or
    /// value ± z·se.
    pub(crate) fn interval(&self, z: f64) -> (f64, f64) {
        match self.uncertainty {
            Uncertainty::Exact => (self.value, self.value),
            Uncertainty::Bracket { lo, hi } => (lo, hi),
            Uncertainty::StdErr { se, .. } => (self.value - z * se, self.value + z * se),
        }
    }
}

/// What a check found.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Outcome {
    /// Significant (or exactly true) in the claim's favour.
    For,
    /// Significant (or exactly true) against the claim.
    Against,
    /// Neither: not significant.
    Neither,
    /// The number is undefined or has no usable uncertainty.
    Undefined,
}

/// One comparison a rule made: the number, the statistic, the threshold, the outcome.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Check {
    /// What was compared, in words ("trimodal share, D = 0.05 → 1.2").
    pub what: String,
    /// The compared quantity (a difference, a distance, a count, an exponent) with its
    /// uncertainty.
    pub value: Measured,
    /// The statistic's name (`z`, `relative change`, `H`, `count`, `relative difference`).
    pub statistic: String,
    /// The statistic's value.
    #[serde(with = "trirhythm::non_finite")]
    pub statistic_value: f64,
    /// The threshold it was held against (Holm-adjusted |z|, tolerance, floor + k s.e., the
    /// claimed count).
    #[serde(with = "trirhythm::non_finite")]
    pub threshold: f64,
    /// What the check found.
    pub outcome: Outcome,
}

impl Check {
    /// How far the statistic lies past its threshold, relative to the threshold: |s − t|/|t|
    /// (a z of 6 against 2.5 gives 1.4, a count of 3 against 5 gives 0.4, a Hellinger
    /// distance of 0.55 against a floor of 0.011 gives 49), or |s − t| when the threshold is
    /// 0 (a gap between brackets); 0 when either is undefined. The measure by which
    /// [`Decision::deciding`] names the strongest evidence first.
    pub fn margin(&self) -> f64 {
        let (s, t) = (self.statistic_value, self.threshold);
        if s.is_nan() || t.is_nan() {
            return 0.0;
        }
        let gap = (s - t).abs();
        if gap.is_nan() {
            // both infinite with the same sign: no distance to speak of
            0.0
        } else if t == 0.0 || t.is_infinite() {
            gap
        } else {
            gap / t.abs()
        }
    }

    /// The check in words: what, the value with its uncertainty, the statistic against its
    /// threshold ("r = 1 → 0.99: Δ = −0.0081 (exact), relative change = −0.25, threshold 1e-9").
    pub fn describe(&self) -> String {
        use crate::notes::sig;
        let value = match self.value.uncertainty {
            Uncertainty::Exact => format!("{} (exact)", sig(self.value.value, 3)),
            Uncertainty::StdErr { se, .. } => {
                format!("{} ± {}", sig(self.value.value, 3), sig(se, 3))
            }
            Uncertainty::Bracket { .. } => self.value.bracket_words(3),
        };
        format!("{}: {value}, {}", self.what, self.statistic_words())
    }

    /// The statistic against its threshold, to three significant digits (`count = 2 against
    /// 5`, `z = 52.7 against 2.5`): the words every rendering of a verdict quotes for its
    /// deciding number (the figure's verdict line, claims.md, the report page), so that they
    /// cannot differ (tested in the CLI's `tests/report.rs`).
    pub fn statistic_words(&self) -> String {
        use crate::notes::sig;
        format!(
            "{} = {} against {}",
            self.statistic,
            sig(self.statistic_value, 3),
            sig(self.threshold, 3)
        )
    }
}

/// A rule's decision: the verdict and the numbers behind it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Decision {
    /// The verdict.
    #[serde(flatten)]
    pub verdict: Verdict,
    /// The rule (`trend`, `count`, `sign_change`, `agreement`, `closeness`).
    pub rule: String,
    /// The statistic and the thresholds, in one sentence.
    pub statistic: String,
    /// Number of stochastic tests the Holm–Bonferroni correction counted (0: none).
    pub tests: usize,
    /// Significance level (family-wise), where the rule tests.
    pub alpha: Option<f64>,
    /// The deciding checks (for a large family: the decisive ones; see `tally`).
    pub checks: Vec<Check>,
    /// How many checks came out for, against, neither, undefined (all of them, also those
    /// not listed in `checks`).
    pub tally: [usize; 4],
}

impl Decision {
    /// A decision with its tally counted from `checks`.
    pub(crate) fn new(
        verdict: Verdict,
        rule: &str,
        statistic: String,
        tests: usize,
        alpha: Option<f64>,
        checks: Vec<Check>,
    ) -> Decision {
        let tally = tally(&checks);
        Decision {
            verdict,
            rule: rule.into(),
            statistic,
            tests,
            alpha,
            checks,
            tally,
        }
    }

    /// At most `n` checks that decided the verdict, the strongest evidence first: those
    /// against the claim when refuted, for it when confirmed, each kind ordered by its
    /// [`Check::margin`] (largest first; ties keep the rule's order) — except under the
    /// regime rule, whose checks are brackets on D_c listed by the rule in order of
    /// strength; for an undetermined verdict the undefined and not significant ones in the
    /// rule's order (the first checks when none is of that kind).
    pub fn deciding(&self, n: usize) -> Vec<&Check> {
        let (wanted, by_margin): (&[Outcome], bool) = match self.verdict {
            Verdict::Refuted => (&[Outcome::Against], true),
            Verdict::Confirmed => (&[Outcome::For], true),
            Verdict::Undetermined { .. } => (&[Outcome::Undefined, Outcome::Neither], false),
        };
        let mut picked: Vec<&Check> = self
            .checks
            .iter()
            .filter(|c| wanted.contains(&c.outcome))
            .collect();
        if by_margin && self.rule != "regime" {
            // a stable sort: equal margins keep the order the rule gave
            picked.sort_by(|a, b| b.margin().total_cmp(&a.margin()));
        }
        picked.truncate(n);
        if picked.is_empty() {
            picked = self.checks.iter().take(n).collect();
        }
        picked
    }

    /// The number that decides the verdict: the first of [`Decision::deciding`] (the
    /// strongest evidence); `None` for a decision without checks.
    pub fn decisive(&self) -> Option<&Check> {
        self.deciding(1).into_iter().next()
    }

    /// The same numbers, undetermined for `why` (e.g. a parameter the paper does not print):
    /// what the rule found is kept in `why` and in the checks.
    pub fn undetermined_because(mut self, why: &str) -> Decision {
        let found = match &self.verdict {
            Verdict::Undetermined { why } => format!("undetermined: {why}"),
            v => v.tag().to_string(),
        };
        self.verdict = Verdict::undetermined(format!("{why} (with the values chosen: {found})"));
        self
    }
}

pub(crate) fn tally(checks: &[Check]) -> [usize; 4] {
    tally_outcomes(&checks.iter().map(|c| c.outcome).collect::<Vec<_>>())
}

pub(crate) fn tally_outcomes(outcomes: &[Outcome]) -> [usize; 4] {
    let mut t = [0; 4];
    for o in outcomes {
        t[match o {
            Outcome::For => 0,
            Outcome::Against => 1,
            Outcome::Neither => 2,
            Outcome::Undefined => 3,
        }] += 1;
    }
    t
}

/// Several decisions on parts of one claim as one: refuted when any part is refuted, confirmed
/// when every part is confirmed, else undetermined (the parts' reasons joined). The checks and
/// tallies are pooled; the tests are summed.
pub fn all_of(rule: &str, parts: Vec<(String, Decision)>) -> Decision {
    let refuted: Vec<&String> = parts
        .iter()
        .filter(|(_, d)| d.verdict == Verdict::Refuted)
        .map(|(n, _)| n)
        .collect();
    let open: Vec<String> = parts
        .iter()
        .filter_map(|(n, d)| match &d.verdict {
            Verdict::Undetermined { why } => Some(format!("{n}: {why}")),
            _ => None,
        })
        .collect();
    let verdict = if !refuted.is_empty() {
        Verdict::Refuted
    } else if !open.is_empty() {
        Verdict::undetermined(open.join("; "))
    } else {
        Verdict::Confirmed
    };
    let statistic = parts
        .first()
        .map(|(_, d)| d.statistic.clone())
        .unwrap_or_default();
    let alpha = parts.iter().find_map(|(_, d)| d.alpha);
    let tests = parts.iter().map(|(_, d)| d.tests).sum();
    let mut tally_all = [0; 4];
    let mut checks = Vec::new();
    for (name, d) in parts {
        for (t, x) in tally_all.iter_mut().zip(d.tally) {
            *t += x;
        }
        checks.extend(d.checks.into_iter().map(|mut c| {
            c.what = format!("{name}: {}", c.what);
            c
        }));
    }
    Decision {
        verdict,
        rule: rule.into(),
        statistic,
        tests,
        alpha,
        checks,
        tally: tally_all,
    }
}
