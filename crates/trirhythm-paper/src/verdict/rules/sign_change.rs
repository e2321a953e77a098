//! The sign-change rule: the largest Lyapunov exponent turns from negative to positive as the
//! noise intensity D grows, on every curve of the claim.
//!
//! z = LLE/se at every testable point (Student's t with realisations − 1 degrees of freedom
//! where given), two-sided at [`ALPHA`] with Holm–Bonferroni over all points of the claim; a
//! curve needs significant values of both signs, every negative below every positive, and a
//! bracket (largest significant negative D, smallest significant positive D) narrower than the
//! curve's whole range. [`significance`] and [`locate`] give the same per-point signs and the
//! per-curve outcome ([`Located`]) to the figures that read them (data of earlier versions).
//! Reference: docs/verdicts.md, "Sign change of the largest Lyapunov exponent". Tested by
//! `tests/verdicts.rs`.

use super::super::stats::{holm, t_for_two_sided, t_two_sided_p};
use super::super::{Check, Decision, Measured, Outcome, Verdict};
use super::{stat_name, ALPHA};

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

/// The sign of one exponent decided with significance.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum PointSign {
    /// Significantly positive (Holm-adjusted).
    Positive,
    /// Significantly negative (Holm-adjusted).
    Negative,
    /// Consistent with zero at the adjusted level.
    NotSignificant,
    /// No test: a non-finite exponent (merged realisations) or no standard error.
    Undefined,
}

/// Where a curve's sign change lies, from its points' [`PointSign`]s.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case", tag = "kind")]
pub enum Located {
    /// Significant negatives all below significant positives, bracket narrower than the range:
    /// D_c in (lo, hi).
    Bracket {
        /// Largest significantly negative D.
        lo: f64,
        /// Smallest significantly positive D.
        hi: f64,
    },
    /// A − → + change whose bracket is the whole range: not located.
    WholeRange,
    /// A significant positive below a significant negative: the opposite transition.
    Opposite,
    /// Significantly positive already at the smallest D, no significant negative: D_c below
    /// the smallest D is not excluded.
    PositiveFromStart,
    /// Significant positives (not at the smallest D) and no significant negative.
    NoNegative,
    /// Significant negatives and no significant positive: D_c above the range not excluded.
    NoPositive,
    /// No significant value of either sign.
    NotSignificant,
}

impl Located {
    /// In words, for notes and reasons ("D_c in (0.01, 0.1)").
    pub fn words(&self, first_d: f64) -> String {
        match self {
            Located::Bracket { lo, hi } => format!(
                "D_c in ({}, {})",
                crate::notes::num(*lo),
                crate::notes::num(*hi)
            ),
            Located::WholeRange => {
                "a − → + change whose bracket is the whole range: D_c not located".into()
            }
            Located::Opposite => {
                "a significant positive below a significant negative: the opposite transition"
                    .into()
            }
            Located::PositiveFromStart => format!(
                "significantly positive already at the smallest D = {} with no significant negative: D_c below the smallest D = {} not excluded",
                crate::notes::num(first_d),
                crate::notes::num(first_d)
            ),
            Located::NoNegative => "no significant negative value in range".into(),
            Located::NoPositive => {
                "no significant positive value in range (D_c above the range not excluded)".into()
            }
            Located::NotSignificant => {
                "no significant value of either sign (consistent with 0)".into()
            }
        }
    }

    /// Short, for a picture.
    pub fn tag(&self) -> &'static str {
        match self {
            Located::Bracket { .. } => "bracketed",
            Located::WholeRange => "whole range",
            Located::Opposite => "+ → −",
            Located::PositiveFromStart => "+ from smallest D",
            Located::NoNegative => "no −",
            Located::NoPositive => "no +",
            Located::NotSignificant => "n.s.",
        }
    }

    /// The outcome without its numbers, for grouping columns by outcome: [`Located::words`]
    /// except for a bracket ("D_c located").
    pub fn kind_words(&self, first_d: f64) -> String {
        match self {
            Located::Bracket { .. } => "D_c located".into(),
            l => l.words(first_d),
        }
    }
}

/// The sign of every point of every curve, decided as [`sign_change`] decides them: z = LLE/se
/// (Student's t with the point's degrees of freedom, normal without), two-sided at [`ALPHA`],
/// Holm–Bonferroni over all testable points of all curves together.
pub fn significance(curves: &[LleCurve]) -> Vec<Vec<PointSign>> {
    let tested = testable(curves);
    let ps: Vec<f64> = tested.iter().map(|t| t_two_sided_p(t.z, t.dof)).collect();
    let (reject, _) = holm(&ps, ALPHA);
    curves
        .iter()
        .enumerate()
        .map(|(c, curve)| {
            (0..curve.points.len())
                .map(
                    |k| match tested.iter().position(|t| t.curve == c && t.point == k) {
                        None => PointSign::Undefined,
                        Some(j) if !reject[j] => PointSign::NotSignificant,
                        Some(j) if tested[j].z > 0.0 => PointSign::Positive,
                        Some(_) => PointSign::Negative,
                    },
                )
                .collect()
        })
        .collect()
}

/// Where a curve's sign change lies, from the D of its points (ascending) and their signs.
pub fn locate(ds: &[f64], signs: &[PointSign]) -> Located {
    let at = |s: PointSign| -> Vec<f64> {
        ds.iter()
            .zip(signs)
            .filter(|(_, &x)| x == s)
            .map(|(&d, _)| d)
            .collect()
    };
    let (neg, pos) = (at(PointSign::Negative), at(PointSign::Positive));
    let first = ds.first().copied().unwrap_or(f64::NAN);
    let last = ds.last().copied().unwrap_or(f64::NAN);
    match (neg.is_empty(), pos.is_empty()) {
        (true, true) => Located::NotSignificant,
        (true, false) if pos.contains(&first) => Located::PositiveFromStart,
        (true, false) => Located::NoNegative,
        (false, true) => Located::NoPositive,
        (false, false) => {
            let lo = neg.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            let hi = pos.iter().copied().fold(f64::INFINITY, f64::min);
            if lo >= hi {
                Located::Opposite
            } else if lo == first && hi == last && ds.len() > 2 {
                Located::WholeRange
            } else {
                Located::Bracket { lo, hi }
            }
        }
    }
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
/// Per curve ([`locate`]): confirmed when it has a significant negative and a significant
/// positive value, every significant negative lies at a smaller D than every significant
/// positive, and the bracket (largest negative D, smallest positive D) is narrower than the
/// curve's range (D_c is then located inside it); refuted when a significant positive lies
/// below a significant negative (the opposite transition); else undetermined: a bracket equal
/// to the whole range (a change, not located), significantly positive already at the smallest
/// D with no significant negative ("D_c below the smallest D = … not excluded"), no significant
/// negative, no significant positive, nothing significant (consistent with 0), with the
/// untestable points named. The
/// claim: refuted when a curve is, confirmed when every curve is, else undetermined.
pub fn sign_change(curves: &[LleCurve]) -> Decision {
    let tested = testable(curves);
    let ps: Vec<f64> = tested.iter().map(|t| t_two_sided_p(t.z, t.dof)).collect();
    let (reject, thresholds) = holm(&ps, ALPHA);
    let mut checks = Vec::new();
    let mut parts: Vec<Part> = Vec::new();
    for (c, curve) in curves.iter().enumerate() {
        let found = |k: usize| {
            tested
                .iter()
                .position(|t| t.curve == c && t.point == k)
                .map(|j| (tested[j].z, reject[j], thresholds[j], tested[j].dof))
        };
        let (mut curve_checks, signs) = curve_checks(curve, found);
        let part = curve_part(curve, &signs);
        // significant points in the wrong order count against the claim
        if part.1 {
            mark_wrong_order(&mut curve_checks, curve, &signs);
        }
        checks.extend(curve_checks);
        parts.push(part);
    }
    Decision::new(
        claim_verdict(&parts),
        "sign_change",
        format!(
            "z = LLE/se at each point (Student's t with realisations − 1 degrees of freedom where given), two-sided at α = {ALPHA} with Holm–Bonferroni over the {} testable points of the claim; a curve needs significant values of both signs, every negative below every positive",
            tested.len()
        ),
        tested.len(),
        Some(ALPHA),
        checks,
    )
}

/// A testable point: its curve, its index on the curve, z = LLE/se and the degrees of freedom
/// (∞: a normal test).
struct Tested {
    curve: usize,
    point: usize,
    z: f64,
    dof: f64,
}

/// The Holm-adjusted test of one point: z, whether significant, the per-test level and the
/// degrees of freedom.
type Found = (f64, bool, f64, f64);

/// One curve's part of the claim: (confirmed, refuted, why undetermined).
type Part = (bool, bool, Option<String>);

/// The values of D of one curve's significant negatives, significant positives and untestable
/// points.
#[derive(Default)]
struct Signs {
    neg: Vec<f64>,
    pos: Vec<f64>,
    untestable: Vec<f64>,
}

impl Signs {
    fn max_neg(&self) -> f64 {
        self.neg.iter().copied().fold(f64::NEG_INFINITY, f64::max)
    }

    fn min_pos(&self) -> f64 {
        self.pos.iter().copied().fold(f64::INFINITY, f64::min)
    }
}

/// The points with a finite exponent and a positive, finite standard error, over all curves.
fn testable(curves: &[LleCurve]) -> Vec<Tested> {
    let mut tested = Vec::new();
    for (c, curve) in curves.iter().enumerate() {
        for (k, q) in curve.points.iter().enumerate() {
            if q.lle.is_finite() && q.se.is_finite() && q.se > 0.0 {
                tested.push(Tested {
                    curve: c,
                    point: k,
                    z: q.lle / q.se,
                    dof: q.dof.unwrap_or(f64::INFINITY),
                });
            }
        }
    }
    tested
}

/// One check per point of a curve (`found`: the Holm-adjusted test of point k, `None` where
/// untestable), and the curve's points sorted by sign.
fn curve_checks(curve: &LleCurve, found: impl Fn(usize) -> Option<Found>) -> (Vec<Check>, Signs) {
    let mut signs = Signs::default();
    let mut checks = Vec::new();
    for (k, q) in curve.points.iter().enumerate() {
        let (outcome, z, thr) = match found(k) {
            None => {
                signs.untestable.push(q.d);
                (Outcome::Undefined, f64::NAN, f64::NAN)
            }
            Some((z, sig, t, dof)) => {
                let o = if sig {
                    if z > 0.0 {
                        signs.pos.push(q.d);
                    } else {
                        signs.neg.push(q.d);
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
    (checks, signs)
}

/// "; undefined … at D = …" naming a curve's untestable points, or nothing.
fn untestable_text(signs: &Signs) -> String {
    if signs.untestable.is_empty() {
        String::new()
    } else {
        format!(
            "; undefined (merged realisations or no standard error) at D = {}",
            signs
                .untestable
                .iter()
                .map(|&d| crate::notes::num(d))
                .collect::<Vec<_>>()
                .join(", ")
        )
    }
}

/// One curve's part from its significant points: both signs in order with a bracket narrower
/// than the range, in the wrong order, or why undetermined ([`locate`]).
fn curve_part(curve: &LleCurve, signs: &Signs) -> Part {
    let ds: Vec<f64> = curve.points.iter().map(|q| q.d).collect();
    let per_point: Vec<PointSign> = ds
        .iter()
        .map(|d| {
            if signs.neg.contains(d) {
                PointSign::Negative
            } else if signs.pos.contains(d) {
                PointSign::Positive
            } else {
                PointSign::NotSignificant
            }
        })
        .collect();
    let first_d = ds.first().copied().unwrap_or(f64::NAN);
    let located = locate(&ds, &per_point);
    match located {
        Located::Bracket { .. } => (true, false, None),
        Located::Opposite => (false, true, None),
        _ => (
            false,
            false,
            Some(format!(
                "{}: {}{}",
                curve.label,
                located.words(first_d),
                untestable_text(signs)
            )),
        ),
    }
}

/// Marks against the claim a refuted curve's significant points in the wrong order: a
/// positive below the largest significant negative, a negative above the smallest significant
/// positive.
fn mark_wrong_order(checks: &mut [Check], curve: &LleCurve, signs: &Signs) {
    let (max_neg, min_pos) = (signs.max_neg(), signs.min_pos());
    for (ch, q) in checks.iter_mut().zip(&curve.points) {
        let wrong = (ch.statistic_value > 0.0 && q.d < max_neg)
            || (ch.statistic_value < 0.0 && q.d > min_pos);
        if ch.outcome == Outcome::For && wrong {
            ch.outcome = Outcome::Against;
        }
    }
}

/// The claim from its curves: refuted when a curve is, confirmed when every curve is, else
/// undetermined with the curves' reasons.
fn claim_verdict(parts: &[Part]) -> Verdict {
    if parts.iter().any(|p| p.1) {
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
    }
}
