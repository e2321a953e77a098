//! The sign-change rule: the largest Lyapunov exponent turns from negative to positive as the
//! noise intensity D grows, on every curve of the claim.
//!
//! z = LLE/se at every testable point (Student's t with realisations − 1 degrees of freedom
//! where given), two-sided at [`ALPHA`] with Holm–Bonferroni over all points of the claim; a
//! curve needs significant values of both signs, every negative below every positive.
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

/// One curve's part from its significant points: both signs in order, in the wrong order, or
/// why undetermined.
fn curve_part(curve: &LleCurve, signs: &Signs) -> Part {
    let (neg, pos) = (&signs.neg, &signs.pos);
    let first_d = curve.points.first().map(|q| q.d);
    let untestable_text = untestable_text(signs);
    if !neg.is_empty() && !pos.is_empty() {
        if signs.max_neg() < signs.min_pos() {
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
