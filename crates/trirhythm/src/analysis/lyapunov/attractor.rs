//! The attractor a start reaches without noise: rest on the wall, or a limit cycle named by the
//! averaged theory's stable cycle it matches (inner, middle, outer).
//!
//! # Equation
//! The noise-free system of the [`Problem`] (D set to 0): D^{1+λ}U − μ0P(U)U̇ + ω0²U = 0, U ≥ 0,
//! U̇₊ = −rU̇₋ at U = 0 (or the problem's Eq. 5 / the wall off), from (U(0), U̇(0)) = (u0, 0). Its
//! attractors are the rest state U = U̇ = 0 and the limit cycles; the averaged theory
//! ([`Theory::limit_cycles`]) predicts the cycles' amplitudes as the stable roots of f(A)
//! (Eq. 18) and the rest state's stability by the sign of f′(0).
//!
//! # Method
//! The path is stepped with the problem's integrator and its **turning points** are located:
//! a step on which U̇ changes sign from + to − (no impact, not stuck) holds a maximum of U,
//! found on the step's cubic Hermite interpolant of (U, U̇) at both nodes; its value is the
//! turning amplitude A_k, its time t_k. After each turning point, with d₁ = A_{k−1} − A_{k−2},
//! d₂ = A_k − A_{k−1} and q = d₂/d₁ (the per-period contraction of the approach):
//! - the **remaining change** is d₂q/(1 − q) for 0 ≤ q < 1 (Aitken's extrapolation of a
//!   geometric approach), |d₂| for q < 0, +∞ for q ≥ 1 (moving away) or d₁ = 0 ≠ d₂;
//! - the path has **settled on a cycle** when |remaining| ≤ `tolerance`·A_k at `confirm`
//!   turning points in a row; the cycle's amplitude is A_k plus the remaining change, its
//!   period the mean spacing of the last `confirm` turning points;
//! - it is **at rest** when A_k < `rest_amplitude`, or when no turning point comes for
//!   [`REST_GAP_PERIODS`] periods 2π/ω1 while ‖(U, U̇/ω1)‖ < `rest_amplitude` (stuck on the
//!   wall). Near the wall the equation is positively homogeneous (module docs of [`super`]),
//!   so a path below the smallest cycle can only decay geometrically to rest;
//! - at `t_max` without either it is [`Attractor::Unsettled`], with its last amplitude.
//!
//! A settled cycle is matched to the **nearest** stable cycle of the averaged theory of the same
//! parameters (with D = 0) in the variant the spec names ([`Variant::Paper`] by default, the
//! variant `trirhythm cycles` prints); `index` is that cycle's rank among the theory's stable
//! cycles, ascending, and the [`CycleName`] follows from the rank and the count: with three
//! stable cycles inner / middle / outer, with two inner / outer, with one outer where the
//! theory's rest state is stable (the cycle lies beyond an unstable one) and sole where it is
//! not. Where the theory has no stable cycle, or refuses the parameters, the cycle is
//! [`CycleName::Unmatched`].
//!
//! [`attractor_starts`] gives one start per attractor: it classifies U(0) = each stable cycle
//! amplitude of the theory, 1 and 0.01 (not 0: the rest state is an equilibrium a noise-free
//! path never leaves, stable or not; 0.01 says whether it attracts), and keeps the first
//! start of each attractor (cycles within `tolerance`·100 of each other in amplitude are the
//! same), rest first, then the cycles by amplitude.
//!
//! # Reference
//! Aitken's Δ² extrapolation (Aitken, Proc. R. Soc. Edinb. 46 (1926) 289); the averaged theory:
//! the paper's Eq. 18 ([`crate::theory::averaging`]).
//!
//! # Tests
//! Unit tests below: the turning point of a cubic; Fig. 17(a)'s μ0 = 0.01 from its outer
//! averaged amplitude ends on the outer cycle within 2 % of the theory; Fig. 18(b) at r = 0.9
//! from U(0) = 1 (rest stable, f′(0) < 0) ends at rest. `tests/attractor.rs` (ignored, extended
//! suite): every μ0 of Fig. 17(a) from each stable amplitude; the starts of each attractor.

use crate::engine::{PredictorCorrector, Problem, Stepper, System};
use crate::error::{Error, Result};
use crate::theory::averaging::{Theory, Variant};
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// Periods 2π/ω1 without a turning point after which a path near U = U̇ = 0 is at rest.
pub const REST_GAP_PERIODS: f64 = 4.0;
/// Longest noise-free run of an [`AttractorSpec`] (time units).
pub const MAX_RUN_TIME: f64 = 1e6;

/// How the noise-free run from a start is followed and judged (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AttractorSpec {
    /// Longest run, in (0, [`MAX_RUN_TIME`]] time units.
    pub t_max: f64,
    /// Relative tolerance of the remaining amplitude change of a settled cycle, in (0, 0.1].
    pub tolerance: f64,
    /// Turning points in a row that must meet the tolerance, 1 to 100.
    pub confirm: usize,
    /// Turning amplitude below which the path is at rest, in (0, 1).
    pub rest_amplitude: f64,
    /// The averaged theory's variant whose stable cycles name the simulated ones.
    pub variant: Variant,
}

impl Default for AttractorSpec {
    fn default() -> Self {
        AttractorSpec {
            t_max: 20_000.0,
            tolerance: 1e-5,
            confirm: 3,
            rest_amplitude: 1e-3,
            variant: Variant::Paper,
        }
    }
}

impl AttractorSpec {
    /// Check the spec: `t_max` in (0, 1e6], `tolerance` in (0, 0.1], `confirm` 1 to 100,
    /// `rest_amplitude` in (0, 1).
    pub fn validate(&self) -> Result<()> {
        if !(self.t_max > 0.0 && self.t_max <= MAX_RUN_TIME) {
            return Err(Error::invalid("t_max", self.t_max, "(0, 1e6]"));
        }
        if !(self.tolerance > 0.0 && self.tolerance <= 0.1) {
            return Err(Error::invalid("tolerance", self.tolerance, "(0, 0.1]"));
        }
        if !(1..=100).contains(&self.confirm) {
            return Err(Error::invalid("confirm", self.confirm as f64, "1 to 100"));
        }
        if !(self.rest_amplitude > 0.0 && self.rest_amplitude < 1.0) {
            return Err(Error::invalid(
                "rest_amplitude",
                self.rest_amplitude,
                "(0, 1)",
            ));
        }
        Ok(())
    }
}

/// The name of a simulated cycle by the averaged theory's stable cycle it matches.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CycleName {
    /// The smallest of two or more stable cycles.
    Inner,
    /// Between the smallest and the largest of three or more.
    Middle,
    /// The largest of two or more, or the only one where the rest state is stable too.
    Outer,
    /// The only attractor: one stable cycle and an unstable rest state.
    Sole,
    /// The theory has no stable cycle here (or does not apply).
    Unmatched,
}

impl CycleName {
    /// `inner`, `middle`, `outer`, `sole` or `unmatched`.
    pub fn name(self) -> &'static str {
        match self {
            CycleName::Inner => "inner",
            CycleName::Middle => "middle",
            CycleName::Outer => "outer",
            CycleName::Sole => "sole",
            CycleName::Unmatched => "unmatched",
        }
    }

    /// The name of rank `index` among `count` stable cycles (ascending), the rest state stable
    /// or not.
    pub fn of_rank(index: usize, count: usize, rest_stable: bool) -> Self {
        match (count, index) {
            (0, _) => CycleName::Unmatched,
            (1, _) if rest_stable => CycleName::Outer,
            (1, _) => CycleName::Sole,
            (_, 0) => CycleName::Inner,
            (n, i) if i + 1 == n => CycleName::Outer,
            _ => CycleName::Middle,
        }
    }
}

/// Where a noise-free path ends.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Attractor {
    /// At rest on the wall (or at the origin without it): the turning amplitude went to 0.
    Rest,
    /// A limit cycle.
    Cycle {
        /// Its turning amplitude (max U), extrapolated (module docs).
        amplitude: f64,
        /// Its period (time between turning points).
        period: f64,
        /// Rank of the matched stable cycle of the theory, ascending (None: unmatched).
        index: Option<usize>,
        /// Its name by that rank.
        name: CycleName,
        /// The matched theory amplitude A0 (None: unmatched).
        theory_amplitude: Option<f64>,
    },
    /// Neither within `t_max`.
    Unsettled {
        /// The last turning amplitude (|U| when there was none).
        amplitude: f64,
    },
}

impl Attractor {
    /// `rest`, the cycle's name, or `unsettled`.
    pub fn label(&self) -> &'static str {
        match self {
            Attractor::Rest => "rest",
            Attractor::Cycle { name, .. } => name.name(),
            Attractor::Unsettled { .. } => "unsettled",
        }
    }

    /// Whether `other` is the same attractor: both at rest, or cycles whose amplitudes differ
    /// by at most `relative` of the larger.
    pub fn same_as(&self, other: &Attractor, relative: f64) -> bool {
        match (self, other) {
            (Attractor::Rest, Attractor::Rest) => true,
            (Attractor::Cycle { amplitude: a, .. }, Attractor::Cycle { amplitude: b, .. }) => {
                (a - b).abs() <= relative * a.max(*b)
            }
            _ => false,
        }
    }
}

/// A start and the attractor it reaches.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StartAttractor {
    /// U(0) (U̇(0) = 0).
    pub u0: f64,
    /// Where the noise-free path ends.
    pub attractor: Attractor,
    /// Time at which it was decided (`t_max` when unsettled).
    pub decided_at: f64,
    /// Turning points seen.
    pub turning_points: usize,
    /// The last remaining amplitude change relative to the amplitude (NaN before three
    /// turning points).
    #[serde(with = "crate::non_finite")]
    pub remaining: f64,
    /// The averaged theory's variant used to name cycles.
    pub variant: Variant,
}

/// The noise-free problem of `problem` from (u0, 0): D = 0, one start.
pub(crate) fn noise_free(problem: &Problem, u0: f64) -> Result<Problem> {
    let params = problem.params().with("D", 0.0)?;
    problem.with_params(&params)?.with_start(u0, 0.0)
}

/// The maximum of U on a step from (u0, v0) to (u1, v1) of length h with v0 > 0 ≥ v1, on the
/// cubic Hermite interpolant: (fraction s of the step, U there).
pub(crate) fn hermite_turning(h: f64, (u0, v0): (f64, f64), (u1, v1): (f64, f64)) -> (f64, f64) {
    // p'(s)/h = 6s(s − 1)(u0 − u1)/h + (3s² − 4s + 1)v0 + (3s² − 2s)v1
    let slope = |s: f64| {
        6.0 * s * (s - 1.0) * (u0 - u1) / h
            + (3.0 * s * s - 4.0 * s + 1.0) * v0
            + (3.0 * s * s - 2.0 * s) * v1
    };
    let s = bisect(&slope, 0.0, 1.0);
    (s, hermite(h, (u0, v0), (u1, v1), s))
}

/// The upward crossing of U = 0 on a step from (u0, v0) to (u1, v1) with u0 < 0 ≤ u1, on the
/// cubic Hermite interpolant: the fraction s of the step.
pub(crate) fn hermite_crossing(h: f64, (u0, v0): (f64, f64), (u1, v1): (f64, f64)) -> f64 {
    bisect(&|s| -hermite(h, (u0, v0), (u1, v1), s), 0.0, 1.0)
}

/// The cubic Hermite interpolant of (u, v) at both ends of a step of length h, at fraction s.
fn hermite(h: f64, (u0, v0): (f64, f64), (u1, v1): (f64, f64), s: f64) -> f64 {
    let (s2, s3) = (s * s, s * s * s);
    (2.0 * s3 - 3.0 * s2 + 1.0) * u0
        + (s3 - 2.0 * s2 + s) * h * v0
        + (-2.0 * s3 + 3.0 * s2) * u1
        + (s3 - s2) * h * v1
}

/// The root of `f` in [a, b] with f(a) > 0 ≥ f(b), by bisection to rounding.
fn bisect(f: &dyn Fn(f64) -> f64, mut a: f64, mut b: f64) -> f64 {
    for _ in 0..60 {
        let m = 0.5 * (a + b);
        if f(m) > 0.0 {
            a = m;
        } else {
            b = m;
        }
    }
    0.5 * (a + b)
}

/// A turning point met while stepping: its time and amplitude.
pub(crate) fn turning_point(prev: (f64, f64, f64), path: &Stepper) -> Option<(f64, f64)> {
    let (t0, u0, v0) = prev;
    let ev = path.events();
    if ev.impact.is_some() || ev.stuck || !(v0 > 0.0 && path.v() <= 0.0) {
        return None;
    }
    let h = path.time() - t0;
    let (s, a) = hermite_turning(h, (u0, v0), (path.u(), path.v()));
    Some((t0 + s * h, a))
}

/// The averaged theory's stable cycle amplitudes (ascending) and the rest state's stability,
/// for the noise-free parameters of `problem`; empty where the theory refuses them.
fn theory_cycles(problem: &Problem, variant: Variant) -> (Vec<f64>, bool) {
    let Ok(theory) = Theory::new(problem.params(), variant) else {
        return (vec![], false);
    };
    let stable = theory
        .limit_cycles()
        .iter()
        .filter(|c| c.stable)
        .map(|c| c.amplitude)
        .collect();
    (stable, theory.rest_state_slope() < 0.0)
}

/// The attractor the noise-free path of `problem` from (u0, 0) reaches (module docs): D is set
/// to 0, the problem's system, wall and blow-up bound are kept. Eq. (9)'s Zhuravlev system is
/// refused (its Z turns on both sides: use Eq. 5 with the wall).
pub fn classify_start(
    problem: &Problem,
    method: &PredictorCorrector,
    u0: f64,
    spec: &AttractorSpec,
) -> Result<StartAttractor> {
    spec.validate()?;
    if problem.system() == System::Zhuravlev {
        return Err(Error::Undefined {
            what: "attractor of a start",
            why: "Eq. (9)'s Z crosses the wall; classify Eq. (5) with the wall instead".into(),
        });
    }
    let free = noise_free(problem, u0)?;
    let mut path = Stepper::new(&free, method, (0, 0), spec.t_max)?;
    let (attractor, decided_at, turning_points, remaining) = settle(&free, &mut path, spec)?;
    Ok(StartAttractor {
        u0,
        attractor,
        decided_at,
        turning_points,
        remaining,
        variant: spec.variant,
    })
}

/// Step `path` (of the noise-free problem `free`) until its attractor is decided or `t_max`
/// has passed (module docs): the attractor, the time it was decided, the turning points seen
/// and the last relative remaining change. The path is left at the decision.
pub(crate) fn settle(
    free: &Problem,
    path: &mut Stepper,
    spec: &AttractorSpec,
) -> Result<(Attractor, f64, usize, f64)> {
    let omega1 = free.oscillator().equivalents().omega1;
    let gap = REST_GAP_PERIODS * 2.0 * PI / omega1;
    let steps = (spec.t_max / path.dt()).ceil() as u64;
    let mut turns: Vec<(f64, f64)> = vec![];
    let (mut in_row, mut remaining) = (0, f64::NAN);
    for _ in 0..steps {
        let prev = (path.time(), path.u(), path.v());
        path.step()?;
        let t = path.time();
        let Some((tk, ak)) = turning_point(prev, path) else {
            let last = turns.last().map_or(0.0, |p| p.0);
            let at_rest = crate::maths::hypot(path.u(), path.v() / omega1) < spec.rest_amplitude;
            if t - last > gap && at_rest {
                return Ok((Attractor::Rest, t, turns.len(), remaining));
            }
            continue;
        };
        turns.push((tk, ak));
        if ak < spec.rest_amplitude {
            return Ok((Attractor::Rest, tk, turns.len(), remaining));
        }
        let k = turns.len();
        if k < 3 {
            continue;
        }
        let (d1, d2) = (turns[k - 2].1 - turns[k - 3].1, ak - turns[k - 2].1);
        let change = remaining_change(d1, d2);
        remaining = change / ak;
        if change.abs() <= spec.tolerance * ak {
            in_row += 1;
        } else {
            in_row = 0;
        }
        if in_row >= spec.confirm && k > spec.confirm {
            let period = (tk - turns[k - 1 - spec.confirm].0) / spec.confirm as f64;
            let amplitude = ak + if change.is_finite() { change } else { 0.0 };
            let attractor = name_cycle(free, spec.variant, amplitude, period);
            return Ok((attractor, tk, k, remaining));
        }
    }
    let amplitude = turns.last().map_or(path.u().abs(), |p| p.1);
    let unsettled = Attractor::Unsettled { amplitude };
    Ok((unsettled, path.time(), turns.len(), remaining))
}

/// The remaining change of a sequence whose last differences are d1, d2 (module docs).
fn remaining_change(d1: f64, d2: f64) -> f64 {
    if d2 == 0.0 {
        return 0.0;
    }
    let q = d2 / d1;
    if !q.is_finite() || q >= 1.0 {
        f64::INFINITY
    } else if q < 0.0 {
        d2.abs()
    } else {
        d2 * q / (1.0 - q)
    }
}

/// The simulated cycle of `amplitude` and `period` named by the nearest stable cycle of the
/// theory of `problem`'s parameters.
fn name_cycle(problem: &Problem, variant: Variant, amplitude: f64, period: f64) -> Attractor {
    let (stable, rest_stable) = theory_cycles(problem, variant);
    let nearest = (0..stable.len()).min_by(|&i, &j| {
        let (di, dj) = ((stable[i] - amplitude).abs(), (stable[j] - amplitude).abs());
        di.total_cmp(&dj)
    });
    Attractor::Cycle {
        amplitude,
        period,
        index: nearest,
        name: nearest.map_or(CycleName::Unmatched, |i| {
            CycleName::of_rank(i, stable.len(), rest_stable)
        }),
        theory_amplitude: nearest.map(|i| stable[i]),
    }
}

/// One start per attractor of the noise-free system of `problem` (module docs): the starts
/// tried are the theory's stable cycle amplitudes, 1 and 0.01, each
/// classified by [`classify_start`]; the first start of each attractor is kept (cycles the same
/// within 100·`tolerance` in amplitude), rest first, then the cycles by amplitude, the unsettled
/// last.
pub fn attractor_starts(
    problem: &Problem,
    method: &PredictorCorrector,
    spec: &AttractorSpec,
) -> Result<Vec<StartAttractor>> {
    spec.validate()?;
    let (stable, _) = theory_cycles(&noise_free(problem, 1.0)?, spec.variant);
    let mut starts = stable;
    // not U(0) = 0: an equilibrium that a noise-free path never leaves, stable or not
    starts.extend([1.0, 0.01]);
    let found: Vec<StartAttractor> = {
        use rayon::prelude::*;
        crate::profile::parallel(|stage| {
            starts
                .par_iter()
                .map(|&u0| stage.task(|| classify_start(problem, method, u0, spec)))
                .collect::<Result<_>>()
        })?
    };
    let mut kept: Vec<StartAttractor> = vec![];
    for s in found {
        let seen = kept.iter().any(|k| match (&k.attractor, &s.attractor) {
            (Attractor::Unsettled { .. }, _) | (_, Attractor::Unsettled { .. }) => false,
            (a, b) => a.same_as(b, 100.0 * spec.tolerance),
        });
        if !seen {
            kept.push(s);
        }
    }
    let key = |s: &StartAttractor| match s.attractor {
        Attractor::Rest => (0, 0.0),
        Attractor::Cycle { amplitude, .. } => (1, amplitude),
        Attractor::Unsettled { amplitude } => (2, amplitude),
    };
    kept.sort_by(|a, b| {
        let (ka, kb) = (key(a), key(b));
        ka.0.cmp(&kb.0).then(ka.1.total_cmp(&kb.1))
    });
    Ok(kept)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::preset;

    #[test]
    fn the_turning_point_of_a_cubic() {
        // U = 1 − (t − 0.3)² on [0, 1]: maximum 1 at t = 0.3
        let u = |t: f64| 1.0 - (t - 0.3) * (t - 0.3);
        let v = |t: f64| -2.0 * (t - 0.3);
        let (s, a) = hermite_turning(1.0, (u(0.0), v(0.0)), (u(1.0), v(1.0)));
        assert!(
            (s - 0.3).abs() < 1e-12 && (a - 1.0).abs() < 1e-12,
            "{s} {a}"
        );
        let s = hermite_crossing(1.0, (-1.0, 2.0), (1.0, 2.0));
        assert!((s - 0.5).abs() < 1e-12);
    }

    #[test]
    fn names_by_rank() {
        use CycleName::*;
        let names: Vec<_> = (0..3).map(|i| CycleName::of_rank(i, 3, false)).collect();
        assert_eq!(names, [Inner, Middle, Outer]);
        assert_eq!(CycleName::of_rank(0, 1, true), Outer);
        assert_eq!(CycleName::of_rank(0, 1, false), Sole);
        assert_eq!(CycleName::of_rank(1, 2, false), Outer);
        assert_eq!(CycleName::of_rank(0, 0, false), Unmatched);
    }

    fn fig(name: &str, key: &str, value: f64) -> Problem {
        let params = preset(name).unwrap().params.with(key, value).unwrap();
        Problem::from_params(&params).unwrap()
    }

    #[test]
    fn the_outer_start_of_fig17a_ends_on_the_outer_cycle() {
        let problem = fig("fig17a", "mu0", 0.01);
        let method = PredictorCorrector::default();
        let outer = 12.915346636317683; // `trirhythm cycles --preset fig17a --param mu0=0.01`
        let s = classify_start(&problem, &method, outer, &AttractorSpec::default()).unwrap();
        let Attractor::Cycle {
            amplitude,
            period,
            index,
            name,
            theory_amplitude,
        } = s.attractor
        else {
            panic!("{s:?}");
        };
        assert_eq!((index, name), (Some(2), CycleName::Outer));
        assert_eq!(theory_amplitude, Some(outer));
        assert!((amplitude - outer).abs() < 0.02 * outer, "{amplitude}");
        // the wall halves the period: ≈ π/ω1
        let omega1 = problem.oscillator().equivalents().omega1;
        assert!((period * omega1 / PI - 1.0).abs() < 0.05, "{period}");
    }

    #[test]
    fn with_the_rest_state_stable_a_small_start_ends_at_rest() {
        // Fig. 18(b)'s r = 0.9: no cycle of the theory, f′(0) < 0
        let problem = fig("fig18b", "r", 0.9);
        let method = PredictorCorrector::default();
        let s = classify_start(&problem, &method, 1.0, &AttractorSpec::default()).unwrap();
        assert_eq!(s.attractor, Attractor::Rest, "{s:?}");
        let all = attractor_starts(&problem, &method, &AttractorSpec::default()).unwrap();
        assert_eq!(all.len(), 1);
        assert_eq!(all[0].attractor.label(), "rest");
    }

    #[test]
    fn the_spec_is_checked() {
        let bad = [
            AttractorSpec {
                t_max: 0.0,
                ..Default::default()
            },
            AttractorSpec {
                tolerance: 0.5,
                ..Default::default()
            },
            AttractorSpec {
                confirm: 0,
                ..Default::default()
            },
            AttractorSpec {
                rest_amplitude: f64::NAN,
                ..Default::default()
            },
        ];
        for s in bad {
            assert!(
                matches!(s.validate(), Err(Error::InvalidParameter { .. })),
                "{s:?}"
            );
        }
    }
}
