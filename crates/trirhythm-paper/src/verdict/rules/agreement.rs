//! The agreement and closeness rules: theory against Monte Carlo by the Hellinger distance,
//! and two numbers within a relative tolerance.
//!
//! Agreement: H within the finite-sample floor √(bins/(8·ESS)) plus k standard errors,
//! stationary ensembles only; where the well decomposition's weights are undetermined but its
//! conditional densities are valid, the range of H over every weighting of the wells against
//! the floors the weighting allows; where a well's conditional statistics drift, only what the
//! whole window and each of its halves give alike. Closeness: the relative difference, widened by 2 s.e. and the
//! half-widths of brackets, against the tolerance. Reference: docs/verdicts.md, "Agreement of
//! theory and Monte Carlo" and "Closeness". Tested by `tests/verdicts.rs`.

use super::super::{Check, Decision, Measured, Outcome, Uncertainty, Verdict};
use super::AGREEMENT_K;

/// One theory-against-Monte-Carlo comparison.
#[derive(Debug, Clone)]
pub struct Comparison {
    /// Which ensemble ("(a3) r = 0.96, MC of Eq. 1, paper formulas").
    pub what: String,
    /// Hellinger distance H = √(1 − Σ√(p q)) between the binned theory and the histogram.
    pub hellinger: f64,
    /// Its bootstrap standard error.
    pub se: f64,
    /// Bins of the histogram.
    pub bins: usize,
    /// Effective sample size of the ensemble.
    pub ess: f64,
    /// Whether the ensemble passed the stationarity check.
    pub stationary: bool,
    /// Its R̂.
    pub r_hat: f64,
    /// Where the ensemble is not stationary but a well decomposition's conditional densities
    /// are valid and only its weights undetermined: H over every weighting.
    pub weightings: Option<Weightings>,
}

/// The Hellinger distance over every weighting of a well decomposition's conditional
/// densities (the stationary density is Σ π_i P_i for some unknown π on the simplex).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Weightings {
    /// min over the weights of H, with its standard error.
    pub h_min: f64,
    /// Standard error of `h_min`.
    pub h_min_se: f64,
    /// max over the weights (one well alone), with its standard error.
    pub h_max: f64,
    /// Standard error of `h_max`.
    pub h_max_se: f64,
    /// The smallest effective sample size of a well's conditional statistics: the mixture's
    /// ESS 1/Σ π_i²/ESS_i is at least this for every π, so its floor at most
    /// √(bins/(8·ess_min)).
    pub ess_min: f64,
    /// The sum of the wells' ESS: the mixture's ESS is at most this (at π_i ∝ ESS_i), so its
    /// floor at least √(bins/(8·ess_sum)).
    pub ess_sum: f64,
    /// Independent replicas behind the standard errors (their jackknife).
    pub replicas: usize,
    /// Where a well's conditional statistics drift between the window's halves: the same
    /// range on the first half and on the second half alone. The decision over every
    /// weighting then stands only where the whole window and each half give it.
    pub halves: Option<[WeightingRange; 2]>,
}

/// H over every weighting on part of the window: min and max with their standard errors.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WeightingRange {
    /// min over the weights of H.
    pub h_min: f64,
    /// Its standard error.
    pub h_min_se: f64,
    /// max over the weights of H.
    pub h_max: f64,
    /// Its standard error.
    pub h_max_se: f64,
}

/// Fewest replicas whose delete-one jackknife standard error a decision over the weightings
/// rests on: with fewer (quick mode runs 2), the error of the error is too large for a
/// two-standard-error margin to mean what it says.
pub const MIN_WEIGHTING_REPLICAS: usize = 8;

/// The floor √(bins/(8·ESS)).
fn floor_of(bins: usize, ess: f64) -> f64 {
    (bins as f64 / (8.0 * ess)).sqrt()
}

impl WeightingRange {
    /// Refuted when H_min − k·se exceeds `largest` (no weighting agrees), confirmed when
    /// H_max + k·se is within `smallest` (every weighting agrees), else neither; undefined
    /// where a number is not finite.
    fn outcome(&self, largest: f64, smallest: f64) -> Outcome {
        let usable = [
            self.h_min,
            self.h_min_se,
            self.h_max,
            self.h_max_se,
            largest,
            smallest,
        ]
        .iter()
        .all(|x| x.is_finite());
        if !usable {
            Outcome::Undefined
        } else if self.h_min - AGREEMENT_K * self.h_min_se > largest {
            Outcome::Against
        } else if self.h_max + AGREEMENT_K * self.h_max_se <= smallest {
            Outcome::For
        } else {
            Outcome::Neither
        }
    }
}

impl Weightings {
    /// The whole window's range.
    pub fn range(&self) -> WeightingRange {
        WeightingRange {
            h_min: self.h_min,
            h_min_se: self.h_min_se,
            h_max: self.h_max,
            h_max_se: self.h_max_se,
        }
    }

    /// Each half's outcome, against the floors of half the effective sample sizes (the ESS
    /// grows with the window at a fixed relaxation time), where the statistics drift.
    pub fn half_outcomes(&self, bins: usize) -> Option<[Outcome; 2]> {
        let (largest, smallest) = (
            floor_of(bins, self.ess_min / 2.0),
            floor_of(bins, self.ess_sum / 2.0),
        );
        self.halves.map(|h| h.map(|r| r.outcome(largest, smallest)))
    }

    /// The decision for every weighting: refuted when H_min − k·se exceeds the largest floor a
    /// weighting can have (no weighting agrees), confirmed when H_max + k·se is within the
    /// smallest (every weighting agrees), else neither; where the conditional statistics
    /// drift, only what the whole window and each half alone give alike. And the two floors
    /// (largest, smallest) of the whole window.
    pub fn outcome(&self, bins: usize) -> (Outcome, f64, f64) {
        let (largest, smallest) = (floor_of(bins, self.ess_min), floor_of(bins, self.ess_sum));
        if self.replicas < MIN_WEIGHTING_REPLICAS {
            return (Outcome::Undefined, largest, smallest);
        }
        let whole = self.range().outcome(largest, smallest);
        let outcome = match self.half_outcomes(bins) {
            None => whole,
            Some(halves) => {
                if whole == Outcome::Undefined || halves.contains(&Outcome::Undefined) {
                    Outcome::Undefined
                } else if halves.iter().all(|&h| h == whole) {
                    whole
                } else {
                    Outcome::Neither
                }
            }
        };
        (outcome, largest, smallest)
    }
}

impl Comparison {
    /// The finite-sample floor: the expected Hellinger distance between a histogram of `ess`
    /// independent samples in `bins` bins and the density it samples, √(bins/(8·ESS)) (from
    /// E\[H²\] ≈ (bins − 1)/(8n) for multinomial counts, the mass beyond the last edge as one
    /// more bin).
    pub fn floor(&self) -> f64 {
        floor_of(self.bins, self.ess)
    }
}

/// **Agreement of theory and Monte Carlo**: H ≤ floor + k·se with k = [`AGREEMENT_K`], on
/// stationary ensembles only.
///
/// Per comparison: undetermined when the ensemble is not stationary (R̂ given) or H, its
/// standard error or the ESS is not finite; confirmed when H ≤ √(bins/(8·ESS)) + k·se; refuted
/// otherwise. A non-stationary ensemble whose well decomposition has valid conditional
/// densities but undetermined weights ([`Comparison::weightings`]) is decided for every
/// weighting of the wells ([`Weightings::outcome`]): refuted when H_min − k·se(H_min) exceeds
/// the largest floor any weighting has, confirmed when H_max + k·se(H_max) is within the
/// smallest, else undetermined; where a well's conditional statistics drift between the
/// window's halves ([`Weightings::halves`]), refuted or confirmed only when each half alone
/// (floors of half the ESS) gives the same, else undetermined. The claim: refuted when a
/// comparison is, confirmed when every one is, else undetermined.
pub fn agreement(items: &[Comparison]) -> Decision {
    let mut checks = Vec::new();
    let mut open = Vec::new();
    for c in items {
        let floor = c.floor();
        let threshold = floor + AGREEMENT_K * c.se;
        let usable = c.hellinger.is_finite() && c.se.is_finite() && floor.is_finite();
        if let (false, Some(w)) = (c.stationary, &c.weightings) {
            let (outcome, largest, smallest) = w.outcome(c.bins);
            let range_of = |r: &WeightingRange| {
                format!(
                    "H ∈ [{} ± {}, {} ± {}]",
                    crate::notes::sig(r.h_min, 3),
                    crate::notes::sig(r.h_min_se, 2),
                    crate::notes::sig(r.h_max, 3),
                    crate::notes::sig(r.h_max_se, 2)
                )
            };
            let range = range_of(&w.range());
            let mut halves = String::new();
            if let (Some([early, late]), Some([oe, ol])) = (w.halves, w.half_outcomes(c.bins)) {
                let word = |o: Outcome| match o {
                    Outcome::Against => "no weighting agrees",
                    Outcome::For => "every weighting agrees",
                    Outcome::Neither => "neither",
                    Outcome::Undefined => "undefined",
                };
                halves = format!(
                    "; a well's conditional statistics drift between the window's halves, so \
                     each half alone (floors of half the ESS, between {} and {}): first half {} \
                     ({}), second half {} ({})",
                    crate::notes::sig(floor_of(c.bins, w.ess_sum / 2.0), 3),
                    crate::notes::sig(floor_of(c.bins, w.ess_min / 2.0), 3),
                    range_of(&early),
                    word(oe),
                    range_of(&late),
                    word(ol)
                );
            }
            match outcome {
                Outcome::Undefined => open.push(format!(
                    "{}: weights undetermined and no standard error of H over the weightings \
                     from at least {MIN_WEIGHTING_REPLICAS} replicas ({} here; {range}{halves})",
                    c.what, w.replicas
                )),
                Outcome::Neither if w.range().outcome(largest, smallest) != Outcome::Neither => {
                    open.push(format!(
                        "{}: weights undetermined; {range} for every weighting of the wells: \
                         the whole window and its halves do not give the same decision{halves}",
                        c.what
                    ))
                }
                Outcome::Neither => open.push(format!(
                    "{}: weights undetermined; {range} for every weighting of the wells, \
                     neither beyond the largest floor {} (minus {AGREEMENT_K} s.e.) nor within \
                     the smallest {} (plus {AGREEMENT_K} s.e.){halves}",
                    c.what,
                    crate::notes::sig(largest, 3),
                    crate::notes::sig(smallest, 3)
                )),
                _ => {}
            }
            let (statistic_value, threshold) = match outcome {
                Outcome::For => (w.h_max, smallest - AGREEMENT_K * w.h_max_se),
                _ => (w.h_min, largest + AGREEMENT_K * w.h_min_se),
            };
            checks.push(Check {
                what: format!(
                    "{} (weights undetermined: {range} for every weighting of the wells; \
                     floor √(bins/(8·ESS)) between {} and {}, bins {}, ESS per well ≥ {}{halves})",
                    c.what,
                    crate::notes::sig(smallest, 3),
                    crate::notes::sig(largest, 3),
                    c.bins,
                    crate::notes::sig(w.ess_min, 3)
                ),
                value: if outcome == Outcome::For {
                    Measured::with_se(w.h_max, w.h_max_se)
                } else {
                    Measured::with_se(w.h_min, w.h_min_se)
                },
                statistic: if outcome == Outcome::For {
                    "H_max over every weighting".into()
                } else {
                    "H_min over every weighting".into()
                },
                statistic_value,
                threshold,
                outcome,
            });
            continue;
        }
        let outcome = if !c.stationary {
            open.push(format!(
                "{}: not stationary (R̂ = {})",
                c.what,
                crate::notes::sig(c.r_hat, 3)
            ));
            Outcome::Undefined
        } else if !usable {
            open.push(format!(
                "{}: no standard error or effective sample size",
                c.what
            ));
            Outcome::Undefined
        } else if c.hellinger <= threshold {
            Outcome::For
        } else {
            Outcome::Against
        };
        checks.push(Check {
            what: format!(
                "{} (floor √(bins/(8·ESS)) = {}, bins {}, ESS {})",
                c.what,
                crate::notes::sig(floor, 3),
                c.bins,
                crate::notes::sig(c.ess, 3)
            ),
            value: Measured::with_se(c.hellinger, c.se),
            statistic: "H".into(),
            statistic_value: c.hellinger,
            threshold,
            outcome,
        });
    }
    let outcomes: Vec<Outcome> = checks.iter().map(|c| c.outcome).collect();
    let verdict = if outcomes.contains(&Outcome::Against) {
        Verdict::Refuted
    } else if !open.is_empty() {
        Verdict::undetermined(open.join("; "))
    } else if items.is_empty() {
        Verdict::undetermined("no ensembles")
    } else {
        Verdict::Confirmed
    };
    Decision::new(
        verdict,
        "agreement",
        format!("Hellinger H ≤ √(bins/(8·ESS)) + {AGREEMENT_K}·se(H), stationary ensembles only"),
        0,
        None,
        checks,
    )
}

/// The difference of two numbers with how far it may be off.
pub(super) struct Gap {
    /// |a − b|.
    pub diff: f64,
    /// max(|a|, |b|).
    pub scale: f64,
    /// Combined standard error of a − b (0 where none).
    pub se: f64,
    /// 2 s.e. plus the half-widths of brackets.
    pub margin: f64,
}

/// |a − b| and its margin: 2 s.e., plus the half-widths of brackets (a bracket is certain, its
/// midpoint is off by at most half its width). A bracket without a point value (half-open)
/// gives a NaN difference.
pub(super) fn gap(a: &Measured, b: &Measured) -> Gap {
    let se_of = |m: &Measured| match m.uncertainty {
        Uncertainty::StdErr { se, .. } => se,
        _ => 0.0,
    };
    let half_width = |m: &Measured| match m.uncertainty {
        Uncertainty::Bracket { lo, hi } => (hi - lo) / 2.0,
        _ => 0.0,
    };
    let se = se_of(a).hypot(se_of(b));
    Gap {
        diff: (a.value - b.value).abs(),
        scale: a.value.abs().max(b.value.abs()),
        se,
        margin: 2.0 * se + half_width(a) + half_width(b),
    }
}

/// **Closeness**: |a − b| / max(|a|, |b|) below `tol` ([`CLOSENESS_REL_TOL`] for "align
/// closely" and "change very slightly").
///
/// Exact values: confirmed when the relative difference is ≤ tol, refuted otherwise. With
/// uncertainties, the margin m = 2·se (combined se of a − b) + the half-widths of brackets:
/// confirmed when (|a − b| + m)/scale ≤ tol, refuted when (|a − b| − m)/scale > tol, else
/// undetermined. Several pairs: refuted when
/// one is, confirmed when all are.
///
/// [`CLOSENESS_REL_TOL`]: super::CLOSENESS_REL_TOL
pub fn closeness(pairs: &[(String, Measured, Measured)], tol: f64) -> Decision {
    let mut checks = Vec::new();
    for (what, a, b) in pairs {
        let Gap {
            diff,
            scale,
            se,
            margin,
        } = gap(a, b);
        let rel = if scale > 0.0 { diff / scale } else { 0.0 };
        let outcome = if !(rel.is_finite() && margin.is_finite()) {
            Outcome::Undefined
        } else if (diff + margin) <= tol * scale || scale == 0.0 {
            Outcome::For
        } else if (diff - margin) > tol * scale {
            Outcome::Against
        } else {
            Outcome::Neither
        };
        checks.push(Check {
            what: format!(
                "{what}: {} against {}",
                crate::notes::sig(a.value, 4),
                crate::notes::sig(b.value, 4)
            ),
            value: if se > 0.0 {
                Measured::with_se(a.value - b.value, se)
            } else {
                Measured::exact(a.value - b.value)
            },
            statistic: "relative difference".into(),
            statistic_value: rel,
            threshold: tol,
            outcome,
        });
    }
    let outcomes: Vec<Outcome> = checks.iter().map(|c| c.outcome).collect();
    let verdict = if outcomes.contains(&Outcome::Against) {
        Verdict::Refuted
    } else if outcomes.contains(&Outcome::Undefined) {
        Verdict::undetermined("an undefined value")
    } else if outcomes.contains(&Outcome::Neither) || outcomes.is_empty() {
        Verdict::undetermined("not significant: the difference is within 2 s.e. of the tolerance")
    } else {
        Verdict::Confirmed
    };
    Decision::new(
        verdict,
        "closeness",
        format!("relative difference |a − b|/max(|a|, |b|) ≤ {tol} (±2 s.e. where stochastic)"),
        0,
        None,
        checks,
    )
}
