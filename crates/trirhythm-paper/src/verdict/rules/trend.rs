//! The trend rule: a claimed monotone change along each series.
//!
//! Each step between neighbouring values and the change across the whole range is a test:
//! z (Student's t where degrees of freedom are given) from standard errors, two-sided at
//! [`ALPHA`] with Holm–Bonferroni over the stochastic tests of the claim; exact values up to
//! [`EXACT_REL_TOL`]; brackets by overlap (as open intervals). Reference: docs/verdicts.md, "Trend". Tested by
//! `tests/verdicts.rs`.

use super::super::stats::{holm, t_for_two_sided, t_two_sided_p};
use super::super::{Check, Decision, Measured, Outcome, Uncertainty, Verdict};
use super::{stat_name, ALPHA, EXACT_REL_TOL};
use serde::{Deserialize, Serialize};

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
        Uncertainty::Bracket { .. } => m.bracket_words(4),
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
            // brackets are open intervals (D_c ∈ (D1, D2): regular at D1, chaotic at D2): two
            // that touch at a finite, positive end differ there, one regular and one not; an
            // infinite value (no D_c at all) equals another
            let both = bracketed(a) && bracketed(b);
            let apart =
                |lo: f64, hi: f64| lo > hi || (both && lo == hi && lo.is_finite() && lo > 0.0);
            if alo == f64::INFINITY && blo == f64::INFINITY {
                return (
                    0.0,
                    Measured::exact(0.0),
                    Pair::Bracket(0.0, Outcome::Neither),
                );
            }
            // one of the two is none: the change is infinite where the other is bounded above
            // (a one-sided [D, ∞) may itself be none: no change shown)
            if alo == f64::INFINITY || blo == f64::INFINITY {
                let up = blo == f64::INFINITY;
                let other_hi = if up { ahi } else { bhi };
                if other_hi == f64::INFINITY {
                    return (
                        f64::NAN,
                        Measured::exact(f64::NAN),
                        Pair::Bracket(0.0, Outcome::Neither),
                    );
                }
                let change = if up { f64::INFINITY } else { f64::NEG_INFINITY };
                let outcome = if up == (s > 0.0) {
                    Outcome::For
                } else {
                    Outcome::Against
                };
                return (
                    change,
                    Measured::exact(change),
                    Pair::Bracket(f64::INFINITY, outcome),
                );
            }
            let up = apart(blo, ahi);
            let down = apart(alo, bhi);
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
/// beside a bracket counts as ±2 s.e.). Brackets are open intervals — a critical noise in
/// (D1, D2) is regular at D1 and chaotic at D2 — so two that touch at a finite, positive end
/// differ (the two curves were called differently there); an infinite value (no critical noise
/// at all) lies above every finite bracket and equals another.
///
/// Verdict: refuted when any step or range change is significant against the claimed
/// direction; otherwise undetermined when a value is undefined; confirmed when the change
/// across the range of every series is significant in the claimed direction; else
/// undetermined (not significant).
pub fn trend(series: &[Series], direction: Direction) -> Decision {
    let tests: Vec<Test> = series
        .iter()
        .flat_map(|s| {
            let mut t = step_tests(s, direction);
            t.extend(range_test(s, direction));
            t
        })
        .collect();
    let (mut outcome, mut stat, n_stochastic) = stochastic_outcomes(&tests);
    deterministic_outcomes(&tests, &mut outcome, &mut stat);
    let verdict = verdict_from(&tests, &outcome, direction);
    let checks = listed_checks(&tests, &outcome, stat);
    let mut d = Decision::new(
        verdict,
        "trend",
        format!(
            "{} along each series: steps and the change across the range; z = change/√(se₁²+se₂²) (Student's t with the smaller degrees of freedom where given) two-sided at α = {ALPHA} with Holm–Bonferroni over the {} stochastic tests; exact values up to a relative tolerance {EXACT_REL_TOL:e}; brackets by overlap, as open intervals",
            match direction {
                Direction::Increases => "increase",
                Direction::Decreases => "decrease",
            },
            n_stochastic
        ),
        n_stochastic,
        (n_stochastic > 0).then_some(ALPHA),
        checks,
    );
    d.tally = super::super::tally_outcomes(&outcome);
    d
}

/// One test of a trend: what is compared (with the values), whether it is the change across
/// a series' range (a two-point series' one step is), the change, and how the values compare.
struct Test {
    what: String,
    is_range: bool,
    change: Measured,
    pair: Pair,
}

/// A test's statistic: its name, its value and the threshold it is held against.
type Stat = (String, f64, f64);

/// `x = value` at point `i` of a series.
fn at(s: &Series, i: usize) -> String {
    format!("{} = {}", s.x_name, crate::notes::num(s.points[i].0))
}

/// The values at points `i` and `j` of a series with their uncertainties: `a → b`.
fn values(s: &Series, i: usize, j: usize) -> String {
    format!("{} → {}", shown(&s.points[i].1), shown(&s.points[j].1))
}

/// The steps between neighbouring values of a series.
fn step_tests(s: &Series, direction: Direction) -> Vec<Test> {
    let n = s.points.len();
    (1..n)
        .map(|i| {
            let (_, change, pair) = compare(&s.points[i - 1].1, &s.points[i].1, direction);
            Test {
                what: format!(
                    "{}, {} → {}: {}",
                    s.label,
                    at(s, i - 1),
                    at(s, i),
                    values(s, i - 1, i)
                ),
                is_range: n == 2,
                change,
                pair,
            }
        })
        .collect()
}

/// The change across the whole range of a series with more than two values.
fn range_test(s: &Series, direction: Direction) -> Option<Test> {
    let n = s.points.len();
    (n > 2).then(|| {
        let (_, change, pair) = compare(&s.points[0].1, &s.points[n - 1].1, direction);
        Test {
            what: format!(
                "{}, across the range {} → {}: {}",
                s.label,
                at(s, 0),
                at(s, n - 1),
                values(s, 0, n - 1)
            ),
            is_range: true,
            change,
            pair,
        }
    })
}

/// The Holm–Bonferroni adjustment over the stochastic tests: every test's outcome and
/// statistic (the others left undefined for [`deterministic_outcomes`]), and how many tests
/// were stochastic.
fn stochastic_outcomes(tests: &[Test]) -> (Vec<Outcome>, Vec<Stat>, usize) {
    let zs: Vec<(usize, f64, f64)> = tests
        .iter()
        .enumerate()
        .filter_map(|(i, t)| match t.pair {
            Pair::Z(z, dof) => Some((i, z, dof)),
            _ => None,
        })
        .collect();
    let ps: Vec<f64> = zs
        .iter()
        .map(|&(_, z, dof)| t_two_sided_p(z, dof))
        .collect();
    let (reject, thresholds) = holm(&ps, ALPHA);
    let mut outcome = vec![Outcome::Undefined; tests.len()];
    let mut stat = vec![(String::new(), f64::NAN, f64::NAN); tests.len()];
    for (k, &(i, z, dof)) in zs.iter().enumerate() {
        outcome[i] = match (reject[k], z > 0.0) {
            (true, true) => Outcome::For,
            (true, false) => Outcome::Against,
            _ => Outcome::Neither,
        };
        stat[i] = (stat_name(dof), z, t_for_two_sided(thresholds[k], dof));
    }
    (outcome, stat, zs.len())
}

/// The outcomes and statistics of the exact, bracketed and undefined tests.
fn deterministic_outcomes(tests: &[Test], outcome: &mut [Outcome], stat: &mut [Stat]) {
    for (i, t) in tests.iter().enumerate() {
        match t.pair {
            Pair::Exact(rel, o) => {
                outcome[i] = o;
                stat[i] = ("relative change".into(), rel, EXACT_REL_TOL);
            }
            Pair::Bracket(gap, o) => {
                outcome[i] = o;
                stat[i] = ("gap between the open brackets".into(), gap, 0.0);
            }
            Pair::Undefined => stat[i] = ("undefined".into(), f64::NAN, f64::NAN),
            Pair::Z(..) => {}
        }
    }
}

/// The verdict from the tests' outcomes: refuted by any test against the claim, undetermined
/// by an undefined one, confirmed when every range change is for it.
fn verdict_from(tests: &[Test], outcome: &[Outcome], direction: Direction) -> Verdict {
    let against = outcome.contains(&Outcome::Against);
    let undefined = outcome.contains(&Outcome::Undefined);
    let ranges_for = tests
        .iter()
        .zip(outcome)
        .filter(|(t, _)| t.is_range)
        .all(|(_, &o)| o == Outcome::For);
    if against {
        Verdict::Refuted
    } else if undefined {
        let at: Vec<&str> = tests
            .iter()
            .zip(outcome)
            .filter(|(_, &o)| o == Outcome::Undefined)
            .map(|(t, _)| t.what.as_str())
            .collect();
        Verdict::undetermined(format!(
            "undefined value or no standard error at {}",
            at.join("; ")
        ))
    } else if ranges_for && !tests.is_empty() {
        Verdict::Confirmed
    } else if tests.is_empty() {
        Verdict::undetermined("no values to compare")
    } else {
        Verdict::undetermined(format!(
            "not significant: the change across the range is not significantly {} in every series",
            match direction {
                Direction::Increases => "positive",
                Direction::Decreases => "negative",
            }
        ))
    }
}

/// The checks of a decision: every range change and every test against the claim or
/// undefined, and the first [`LISTED_STEPS`] other steps.
fn listed_checks(tests: &[Test], outcome: &[Outcome], stat: Vec<Stat>) -> Vec<Check> {
    let mut checks: Vec<Check> = Vec::new();
    let mut listed_steps = 0;
    for ((t, o), (name, value, threshold)) in tests.iter().zip(outcome).zip(stat) {
        let decisive = t.is_range || *o == Outcome::Against || *o == Outcome::Undefined;
        if !decisive {
            if listed_steps >= LISTED_STEPS {
                continue;
            }
            listed_steps += 1;
        }
        checks.push(Check {
            what: t.what.clone(),
            value: t.change,
            statistic: name,
            statistic_value: value,
            threshold,
            outcome: *o,
        });
    }
    checks
}
