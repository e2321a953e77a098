//! The dependence rule: a quantity "depends on" a parameter, "changes significantly with" it.
//!
//! The complement of closeness: per series (the quantity at the parameter's values, everything
//! else fixed) the largest and the smallest value are compared by their relative difference,
//! with the margin of the closeness rule (2 s.e. plus the half-widths of brackets), against the
//! same tolerance. Reference: docs/verdicts.md, "Dependence". Tested by `tests/verdicts.rs`.

use super::super::{Check, Decision, Measured, Outcome, Uncertainty, Verdict};
use super::agreement::{gap, Gap};
use super::Series;

/// **Dependence**: the quantity of each series changes with the parameter by more than `tol`
/// of its larger magnitude ([`CLOSENESS_REL_TOL`] for "depends on", "changes significantly").
///
/// Per series, the largest value a and the smallest b (by value): *for* when
/// (|a − b| − m)/max(|a|, |b|) > tol, *against* when (|a − b| + m)/max(|a|, |b|) ≤ tol (every
/// value lies within the tolerance of every other: no dependence the claim could mean), else
/// neither; m = 2 s.e. + the half-widths of brackets; a series with an undefined value or
/// fewer than two values is undefined. Verdict: refuted when a series is against, confirmed
/// when every series is for, else undetermined (named). The rule is the negation of
/// [`closeness`](super::closeness) on the extreme pair, with the same tolerance, so that "changes
/// very slightly" and "changes significantly" cannot both be confirmed.
///
/// [`CLOSENESS_REL_TOL`]: super::CLOSENESS_REL_TOL
pub fn dependence(series: &[Series], tol: f64) -> Decision {
    use crate::notes::sig;
    let mut checks = Vec::new();
    let mut open = Vec::new();
    for s in series {
        let defined = |m: &Measured| {
            m.value.is_finite()
                && match m.uncertainty {
                    Uncertainty::Bracket { lo, hi } => !(lo.is_nan() || hi.is_nan()),
                    Uncertainty::StdErr { se, .. } => se.is_finite(),
                    Uncertainty::Exact => true,
                }
        };
        let values = s
            .points
            .iter()
            .map(|(x, m)| format!("{} at {} = {}", shown(m), s.x_name, crate::notes::num(*x)))
            .collect::<Vec<_>>()
            .join(", ");
        let what = format!("{}: {values}", s.label);
        if s.points.len() < 2 || !s.points.iter().all(|(_, m)| defined(m)) {
            open.push(format!("{}: an undefined value or fewer than two", s.label));
            checks.push(Check {
                what,
                value: Measured::exact(f64::NAN),
                statistic: "relative change".into(),
                statistic_value: f64::NAN,
                threshold: tol,
                outcome: Outcome::Undefined,
            });
            continue;
        }
        let by_value = |a: &&(f64, Measured), b: &&(f64, Measured)| a.1.value.total_cmp(&b.1.value);
        let hi = s.points.iter().max_by(by_value).expect("two values");
        let lo = s.points.iter().min_by(by_value).expect("two values");
        let Gap {
            diff,
            scale,
            se,
            margin,
        } = gap(&hi.1, &lo.1);
        let rel = if scale > 0.0 { diff / scale } else { 0.0 };
        let outcome = if scale == 0.0 || diff + margin <= tol * scale {
            Outcome::Against
        } else if diff - margin > tol * scale {
            Outcome::For
        } else {
            Outcome::Neither
        };
        if outcome == Outcome::Neither {
            open.push(format!(
                "{}: the change {} is within its margin of the tolerance {tol}",
                s.label,
                sig(rel, 3)
            ));
        }
        checks.push(Check {
            what: format!(
                "{what}; largest against smallest: {} ({} = {}) against {} ({} = {})",
                sig(hi.1.value, 4),
                s.x_name,
                crate::notes::num(hi.0),
                sig(lo.1.value, 4),
                s.x_name,
                crate::notes::num(lo.0)
            ),
            value: if se > 0.0 {
                Measured::with_se(diff, se)
            } else if margin > 0.0 {
                Measured::bracket(diff, (diff - margin).max(0.0), diff + margin)
            } else {
                Measured::exact(diff)
            },
            statistic: "relative change".into(),
            statistic_value: rel,
            threshold: tol,
            outcome,
        });
    }
    let against = checks.iter().any(|c| c.outcome == Outcome::Against);
    let verdict = if against {
        Verdict::Refuted
    } else if checks.is_empty() {
        Verdict::undetermined("no values")
    } else if !open.is_empty() {
        Verdict::undetermined(open.join("; "))
    } else {
        Verdict::Confirmed
    };
    Decision::new(
        verdict,
        "dependence",
        format!("relative change (largest − smallest)/max(|largest|, |smallest|) > {tol} beyond its margin (2 s.e. + bracket half-widths), per series; within the tolerance with its margin: no dependence"),
        0,
        None,
        checks,
    )
}

/// A number with its uncertainty in words.
fn shown(m: &Measured) -> String {
    use crate::notes::sig;
    match m.uncertainty {
        Uncertainty::Exact => sig(m.value, 4),
        Uncertainty::StdErr { se, .. } => format!("{} ± {}", sig(m.value, 3), sig(se, 2)),
        Uncertainty::Bracket { .. } => m.bracket_words(4),
    }
}
