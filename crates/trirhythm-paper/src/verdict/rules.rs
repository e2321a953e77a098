//! The verdict rules: pure functions from numbers with uncertainties to a [`Decision`].
//!
//! Each rule states its statistic and thresholds in the decision (`statistic`, each check's
//! `threshold`), so a reader can redo it by hand. The constants below are the thresholds;
//! docs/verdicts.md gives the reasons. Tested by `tests/verdicts.rs`: every rule with cases
//! that confirm, refute and are undetermined, including the multiplicity effect (one 2.03σ
//! point among 36 tests is not significant).

use super::stats::{holm, t_for_two_sided, t_two_sided_p};
use super::{Check, Decision, Measured, Outcome, Uncertainty, Verdict};
use serde::{Deserialize, Serialize};

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

/// At most this many steps of a trend are listed in a decision besides the changes across the
/// range and the steps against the claim (the tally counts all).
const LISTED_STEPS: usize = 12;

/// The direction of a claimed change as the series is read (the series is ordered along the
/// claim's wording: "as r drops" lists r from large to small).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Direction {
    /// The value grows along the series.
    Increases,
    /// The value falls along the series.
    Decreases,
}

/// One series of a trend: values at abscissae, in the order of the claim's wording.
#[derive(Debug, Clone)]
pub struct Series {
    /// What the series is ("trimodal share").
    pub label: String,
    /// The abscissa's symbol ("D").
    pub x_name: String,
    /// (abscissa, value) in the claim's order.
    pub points: Vec<(f64, Measured)>,
}

/// How two values compare: the statistic, the p-value where stochastic.
enum Pair {
    /// Deterministic: the relative change and the outcome.
    Exact(f64, Outcome),
    /// Bracketed: the gap between the brackets (> 0: apart) and the outcome.
    Bracket(f64, Outcome),
    /// Stochastic: z or t (signed in the claim's favour) and the degrees of freedom (∞: z).
    Z(f64, f64),
    /// Undefined.
    Undefined,
}

/// A number with its uncertainty in words: `v`, `v ± se`, `v in [lo, hi]`.
fn shown(m: &Measured) -> String {
    use crate::notes::sig;
    match m.uncertainty {
        Uncertainty::Exact => sig(m.value, 4),
        Uncertainty::StdErr { se, .. } => format!("{} ± {}", sig(m.value, 3), sig(se, 2)),
        Uncertainty::Bracket { lo, hi } => {
            format!("{} in [{}, {}]", sig(m.value, 4), sig(lo, 4), sig(hi, 4))
        }
    }
}

/// `z`, or `t (ν = …)` for a statistic with few degrees of freedom.
fn stat_name(dof: f64) -> String {
    if dof.is_finite() {
        format!("t (ν = {})", crate::notes::num(dof))
    } else {
        "z".into()
    }
}

fn sign_for(direction: Direction) -> f64 {
    match direction {
        Direction::Increases => 1.0,
        Direction::Decreases => -1.0,
    }
}

fn compare(a: &Measured, b: &Measured, direction: Direction) -> (f64, Measured, Pair) {
    let s = sign_for(direction);
    let diff = b.value - a.value;
    let bracketed = |m: &Measured| matches!(m.uncertainty, Uncertainty::Bracket { .. });
    // a bracket may be half-open (a boundary above the searched range: [top, ∞)) and then
    // has no point value; anything else needs a finite value
    let defined = |m: &Measured| match m.uncertainty {
        Uncertainty::Bracket { lo, hi } => !(lo.is_nan() || hi.is_nan()),
        _ => m.value.is_finite(),
    };
    if !defined(a) || !defined(b) {
        return (diff, Measured::exact(f64::NAN), Pair::Undefined);
    }
    match (a.uncertainty, b.uncertainty) {
        (Uncertainty::Exact, Uncertainty::Exact) => {
            let scale = a.value.abs().max(b.value.abs());
            let rel = if scale > 0.0 { diff / scale } else { 0.0 };
            let outcome = if diff.abs() <= EXACT_REL_TOL * scale || scale == 0.0 {
                Outcome::Neither
            } else if s * diff > 0.0 {
                Outcome::For
            } else {
                Outcome::Against
            };
            (diff, Measured::exact(diff), Pair::Exact(rel, outcome))
        }
        _ if bracketed(a) || bracketed(b) => {
            // a standard error beside a bracket counts as a ±2 s.e. interval
            let (alo, ahi) = a.interval(2.0);
            let (blo, bhi) = b.interval(2.0);
            if [alo, ahi, blo, bhi].iter().any(|v| v.is_nan()) {
                return (diff, Measured::exact(f64::NAN), Pair::Undefined);
            }
            let up = blo > ahi;
            let down = bhi < alo;
            let outcome = match (up, down) {
                (true, _) if s > 0.0 => Outcome::For,
                (true, _) => Outcome::Against,
                (_, true) if s < 0.0 => Outcome::For,
                (_, true) => Outcome::Against,
                _ => Outcome::Neither,
            };
            let gap = (blo - ahi).max(alo - bhi);
            (
                diff,
                Measured::bracket(diff, blo - ahi, bhi - alo),
                Pair::Bracket(gap, outcome),
            )
        }
        _ => {
            let se_of = |m: &Measured| match m.uncertainty {
                Uncertainty::StdErr { se, dof } => (se, dof.unwrap_or(f64::INFINITY)),
                _ => (0.0, f64::INFINITY),
            };
            let ((sa, da), (sb, db)) = (se_of(a), se_of(b));
            let se = sa.hypot(sb);
            // the smaller of the two degrees of freedom: conservative against Welch's
            let dof = da.min(db);
            let m = Measured::with_se_dof(diff, se, dof.is_finite().then_some(dof));
            if !(se.is_finite() && se > 0.0) {
                return (diff, m, Pair::Undefined);
            }
            (diff, m, Pair::Z(s * diff / se, dof))
        }
    }
}

/// **Trend**: a claimed monotone change along each series.
///
/// Tests: per series, each step between neighbouring values and, where a series has more
/// than two values, the change across the whole range. Values with standard errors give
/// z = (change in the claimed direction)/√(se₁² + se₂²), decided two-sided at [`ALPHA`] with
/// the Holm–Bonferroni correction over every such test of the claim (all series together);
/// exact values compare exactly (a change within [`EXACT_REL_TOL`] of the larger magnitude is
/// no change); bracketed values change where the brackets do not overlap (a standard error
/// beside a bracket counts as ±2 s.e.).
///
/// Verdict: refuted when any step or range change is significant against the claimed
/// direction; otherwise undetermined when a value is undefined; confirmed when the change
/// across the range of every series is significant in the claimed direction; else
/// undetermined (not significant).
pub fn trend(series: &[Series], direction: Direction) -> Decision {
    // (what, is_range, change, pair)
    let mut raw: Vec<(String, bool, Measured, Pair)> = Vec::new();
    for s in series {
        let n = s.points.len();
        let name = |i: usize| format!("{} = {}", s.x_name, crate::notes::num(s.points[i].0));
        let values =
            |i: usize, j: usize| format!("{} → {}", shown(&s.points[i].1), shown(&s.points[j].1));
        for i in 1..n {
            let (_, m, p) = compare(&s.points[i - 1].1, &s.points[i].1, direction);
            raw.push((
                format!(
                    "{}, {} → {}: {}",
                    s.label,
                    name(i - 1),
                    name(i),
                    values(i - 1, i)
                ),
                n == 2,
                m,
                p,
            ));
        }
        if n > 2 {
            let (_, m, p) = compare(&s.points[0].1, &s.points[n - 1].1, direction);
            raw.push((
                format!(
                    "{}, across the range {} → {}: {}",
                    s.label,
                    name(0),
                    name(n - 1),
                    values(0, n - 1)
                ),
                true,
                m,
                p,
            ));
        }
    }
    let zs: Vec<(usize, f64, f64)> = raw
        .iter()
        .enumerate()
        .filter_map(|(i, r)| match r.3 {
            Pair::Z(z, dof) => Some((i, z, dof)),
            _ => None,
        })
        .collect();
    let ps: Vec<f64> = zs
        .iter()
        .map(|&(_, z, dof)| t_two_sided_p(z, dof))
        .collect();
    let (reject, thresholds) = holm(&ps, ALPHA);
    let mut outcome = vec![Outcome::Undefined; raw.len()];
    let mut stat = vec![(String::new(), f64::NAN, f64::NAN); raw.len()];
    for (k, &(i, z, dof)) in zs.iter().enumerate() {
        outcome[i] = match (reject[k], z > 0.0) {
            (true, true) => Outcome::For,
            (true, false) => Outcome::Against,
            _ => Outcome::Neither,
        };
        stat[i] = (stat_name(dof), z, t_for_two_sided(thresholds[k], dof));
    }
    for (i, r) in raw.iter().enumerate() {
        match r.3 {
            Pair::Exact(rel, o) => {
                outcome[i] = o;
                stat[i] = ("relative change".into(), rel, EXACT_REL_TOL);
            }
            Pair::Bracket(gap, o) => {
                outcome[i] = o;
                stat[i] = ("gap between the brackets".into(), gap, 0.0);
            }
            Pair::Undefined => stat[i] = ("undefined".into(), f64::NAN, f64::NAN),
            Pair::Z(..) => {}
        }
    }
    let against = outcome.contains(&Outcome::Against);
    let undefined = outcome.contains(&Outcome::Undefined);
    let ranges_for = raw
        .iter()
        .zip(&outcome)
        .filter(|(r, _)| r.1)
        .all(|(_, &o)| o == Outcome::For);
    let verdict = if against {
        Verdict::Refuted
    } else if undefined {
        let at: Vec<&str> = raw
            .iter()
            .zip(&outcome)
            .filter(|(_, &o)| o == Outcome::Undefined)
            .map(|(r, _)| r.0.as_str())
            .collect();
        Verdict::undetermined(format!(
            "undefined value or no standard error at {}",
            at.join("; ")
        ))
    } else if ranges_for && !raw.is_empty() {
        Verdict::Confirmed
    } else if raw.is_empty() {
        Verdict::undetermined("no values to compare")
    } else {
        Verdict::undetermined(format!(
            "not significant: the change across the range is not significantly {} in every series",
            match direction {
                Direction::Increases => "positive",
                Direction::Decreases => "negative",
            }
        ))
    };
    let mut checks: Vec<Check> = Vec::new();
    let mut listed_steps = 0;
    for ((r, o), (name, value, threshold)) in raw.iter().zip(&outcome).zip(stat) {
        let decisive = r.1 || *o == Outcome::Against || *o == Outcome::Undefined;
        if !decisive {
            if listed_steps >= LISTED_STEPS {
                continue;
            }
            listed_steps += 1;
        }
        checks.push(Check {
            what: r.0.clone(),
            value: r.2,
            statistic: name,
            statistic_value: value,
            threshold,
            outcome: *o,
        });
    }
    let mut d = Decision::new(
        verdict,
        "trend",
        format!(
            "{} along each series: steps and the change across the range; z = change/√(se₁²+se₂²) (Student's t with the smaller degrees of freedom where given) two-sided at α = {ALPHA} with Holm–Bonferroni over the {} stochastic tests; exact values up to a relative tolerance {EXACT_REL_TOL:e}; brackets by overlap",
            match direction {
                Direction::Increases => "increase",
                Direction::Decreases => "decrease",
            },
            zs.len()
        ),
        zs.len(),
        (!zs.is_empty()).then_some(ALPHA),
        checks,
    );
    d.tally = super::tally_outcomes(&outcome);
    d
}

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

/// One Lyapunov exponent against the noise intensity D.
#[derive(Debug, Clone, Copy)]
pub struct LlePoint {
    /// Noise intensity D.
    pub d: f64,
    /// The exponent (non-finite: undefined, e.g. merged realisations).
    pub lle: f64,
    /// Its standard error over realisations.
    pub se: f64,
    /// Degrees of freedom of the standard error (realisations − 1); `None`: normal tests.
    pub dof: Option<f64>,
}

/// One curve of exponents against D, ascending in D.
#[derive(Debug, Clone)]
pub struct LleCurve {
    /// Which curve ("μ0 = 0.01").
    pub label: String,
    /// Its points, ascending in D.
    pub points: Vec<LlePoint>,
}

/// **Sign change of the LLE**: the exponent turns from negative to positive as D grows past a
/// critical D_c, on every curve of the claim.
///
/// Tests: z = LLE/se at every defined point of every curve, two-sided at [`ALPHA`] with the
/// Holm–Bonferroni correction over all of them (a point with a non-finite exponent — merged
/// realisations — or without a standard error is not testable).
///
/// Per curve: confirmed when it has a significant negative and a significant positive value
/// and every significant negative lies at a smaller D than every significant positive (D_c is
/// then bracketed inside the range); refuted when a significant positive lies below a
/// significant negative (the opposite transition); else undetermined: the range starts where
/// the exponent is already significantly positive (D_c below the range cannot be excluded),
/// no significant negative, no significant positive, with the untestable points named. The
/// claim: refuted when a curve is, confirmed when every curve is, else undetermined.
pub fn sign_change(curves: &[LleCurve]) -> Decision {
    let mut idx = Vec::new(); // (curve, point, z, dof)
    for (c, curve) in curves.iter().enumerate() {
        for (k, q) in curve.points.iter().enumerate() {
            if q.lle.is_finite() && q.se.is_finite() && q.se > 0.0 {
                idx.push((c, k, q.lle / q.se, q.dof.unwrap_or(f64::INFINITY)));
            }
        }
    }
    let ps: Vec<f64> = idx
        .iter()
        .map(|&(_, _, z, dof)| t_two_sided_p(z, dof))
        .collect();
    let (reject, thresholds) = holm(&ps, ALPHA);
    let mut checks = Vec::new();
    let mut parts: Vec<(bool, bool, Option<String>)> = Vec::new(); // (confirmed, refuted, why)
    for (c, curve) in curves.iter().enumerate() {
        let mut neg = Vec::new();
        let mut pos = Vec::new();
        let mut untestable = Vec::new();
        let start = checks.len();
        for (k, q) in curve.points.iter().enumerate() {
            let found = idx
                .iter()
                .position(|&(ci, ki, _, _)| ci == c && ki == k)
                .map(|j| (idx[j].2, reject[j], thresholds[j], idx[j].3));
            let (outcome, z, thr) = match found {
                None => {
                    untestable.push(q.d);
                    (Outcome::Undefined, f64::NAN, f64::NAN)
                }
                Some((z, sig, t, dof)) => {
                    let o = if sig {
                        if z > 0.0 {
                            pos.push(q.d);
                        } else {
                            neg.push(q.d);
                        }
                        Outcome::For
                    } else {
                        Outcome::Neither
                    };
                    (o, z, t_for_two_sided(t, dof))
                }
            };
            checks.push(Check {
                what: format!("{}, D = {}", curve.label, crate::notes::num(q.d)),
                value: Measured::with_se_dof(q.lle, q.se, q.dof),
                statistic: stat_name(q.dof.unwrap_or(f64::INFINITY)),
                statistic_value: z,
                threshold: thr,
                outcome,
            });
        }
        let max_neg = neg.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let min_pos = pos.iter().copied().fold(f64::INFINITY, f64::min);
        let first_d = curve.points.first().map(|q| q.d);
        let untestable_text = if untestable.is_empty() {
            String::new()
        } else {
            format!(
                "; undefined (merged realisations or no standard error) at D = {}",
                untestable
                    .iter()
                    .map(|&d| crate::notes::num(d))
                    .collect::<Vec<_>>()
                    .join(", ")
            )
        };
        let part = if !neg.is_empty() && !pos.is_empty() {
            if max_neg < min_pos {
                (true, false, None)
            } else {
                (false, true, None)
            }
        } else if pos.is_empty() && neg.is_empty() {
            (
                false,
                false,
                Some(format!(
                    "{}: no significant value of either sign{untestable_text}",
                    curve.label
                )),
            )
        } else if neg.is_empty() {
            let starts_positive = first_d.is_some_and(|d| pos.contains(&d));
            (
                false,
                false,
                Some(if starts_positive {
                    format!(
                        "{}: the range starts where the LLE is already significantly positive (D = {}): D_c below the range cannot be excluded{untestable_text}",
                        curve.label,
                        crate::notes::num(first_d.unwrap_or(f64::NAN))
                    )
                } else {
                    format!(
                        "{}: no significant negative value in range{untestable_text}",
                        curve.label
                    )
                }),
            )
        } else {
            (
                false,
                false,
                Some(format!(
                    "{}: no significant positive value in range (D_c above the range cannot be excluded){untestable_text}",
                    curve.label
                )),
            )
        };
        // significant points in the wrong order count against the claim
        if part.1 {
            for (ch, q) in checks[start..].iter_mut().zip(&curve.points) {
                let wrong = (ch.statistic_value > 0.0 && q.d < max_neg)
                    || (ch.statistic_value < 0.0 && q.d > min_pos);
                if ch.outcome == Outcome::For && wrong {
                    ch.outcome = Outcome::Against;
                }
            }
        }
        parts.push(part);
    }
    let verdict = if parts.iter().any(|p| p.1) {
        Verdict::Refuted
    } else if parts.iter().all(|p| p.0) && !parts.is_empty() {
        Verdict::Confirmed
    } else {
        let whys: Vec<String> = parts.iter().filter_map(|p| p.2.clone()).collect();
        let held = parts.iter().filter(|p| p.0).count();
        Verdict::undetermined(format!(
            "{} of {} curves with a significant − → + change; {}",
            held,
            parts.len(),
            whys.join("; ")
        ))
    };
    Decision::new(
        verdict,
        "sign_change",
        format!(
            "z = LLE/se at each point (Student's t with realisations − 1 degrees of freedom where given), two-sided at α = {ALPHA} with Holm–Bonferroni over the {} testable points of the claim; a curve needs significant values of both signs, every negative below every positive",
            idx.len()
        ),
        idx.len(),
        Some(ALPHA),
        checks,
    )
}

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
}

impl Comparison {
    /// The finite-sample floor: the expected Hellinger distance between a histogram of `ess`
    /// independent samples in `bins` bins and the density it samples, √(bins/(8·ESS)) (from
    /// E\[H²\] ≈ (bins − 1)/(8n) for multinomial counts, the mass beyond the last edge as one
    /// more bin).
    pub fn floor(&self) -> f64 {
        (self.bins as f64 / (8.0 * self.ess)).sqrt()
    }
}

/// **Agreement of theory and Monte Carlo**: H ≤ floor + k·se with k = [`AGREEMENT_K`], on
/// stationary ensembles only.
///
/// Per comparison: undetermined when the ensemble is not stationary (R̂ given) or H, its
/// standard error or the ESS is not finite; confirmed when H ≤ √(bins/(8·ESS)) + k·se; refuted
/// otherwise. The claim: refuted when a comparison is, confirmed when every one is, else
/// undetermined.
pub fn agreement(items: &[Comparison]) -> Decision {
    let mut checks = Vec::new();
    let mut open = Vec::new();
    for c in items {
        let floor = c.floor();
        let threshold = floor + AGREEMENT_K * c.se;
        let usable = c.hellinger.is_finite() && c.se.is_finite() && floor.is_finite();
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

/// **Closeness**: |a − b| / max(|a|, |b|) below `tol` ([`CLOSENESS_REL_TOL`] for "align
/// closely" and "change very slightly").
///
/// Exact values: confirmed when the relative difference is ≤ tol, refuted otherwise. With
/// uncertainties, the margin m = 2·se (combined se of a − b) + the half-widths of brackets:
/// confirmed when (|a − b| + m)/scale ≤ tol, refuted when (|a − b| − m)/scale > tol, else
/// undetermined. Several pairs: refuted when
/// one is, confirmed when all are.
pub fn closeness(pairs: &[(String, Measured, Measured)], tol: f64) -> Decision {
    let mut checks = Vec::new();
    for (what, a, b) in pairs {
        let scale = a.value.abs().max(b.value.abs());
        let diff = (a.value - b.value).abs();
        let se_of = |m: &Measured| match m.uncertainty {
            Uncertainty::StdErr { se, .. } => se,
            _ => 0.0,
        };
        let half_width = |m: &Measured| match m.uncertainty {
            Uncertainty::Bracket { lo, hi } => (hi - lo) / 2.0,
            _ => 0.0,
        };
        let se = se_of(a).hypot(se_of(b));
        // how far the difference may be off: 2 s.e., plus the half-widths of brackets (a
        // bracket is certain, its midpoint is off by at most half its width)
        let margin = 2.0 * se + half_width(a) + half_width(b);
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
                crate::notes::num(a.value),
                crate::notes::num(b.value)
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
