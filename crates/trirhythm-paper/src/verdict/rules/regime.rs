//! Rules that follow the regime: what the theory of noisy oscillators predicts for the
//! frozen-noise exponent on each kind of attractor, and the tests that call a point and a curve.
//!
//! # Theory
//! - **Rest against the wall.** Near U = 0 the equation is positively homogeneous: the wall,
//!   the impact law, ω0²U and the fractional operator all scale with the state, only
//!   μ0(P(U) − P(0))U̇ does not. Scaling the state and the noise together (D → c²D) leaves the
//!   tangent dynamics unchanged, so the exponent of a path that stays near the wall does not
//!   depend on D as D → 0: it is flat in log D, and where it is positive D_c = 0 is the answer.
//! - **A stable cycle.** Weak noise makes the exponent negative, of order D (noise-induced
//!   synchronisation): λ ≈ −c·D, c from the cycle's phase response
//!   (`trirhythm::analysis::lyapunov::phase_response`; Teramae & Tanaka, PRL 93, 204103
//!   (2004); Goldobin, Teramae, Nakao & Ermentrout, PRL 105, 154101 (2010)). A positive exponent
//!   needs noise beyond the reach of that expansion.
//!
//! # Rules
//! Every test is one-sided at [`ALPHA`] with Student's t on the realisations that did not merge
//! (ν = n − m − 1), Bonferroni over the points of the curve. The **margin** δ = 1/W (W the
//! window of the finite-time exponent): an exponent below it does not make one e-fold in the
//! window, so a finite-time estimate cannot call it chaos; it is the same margin for every
//! curve and is stated in each decision.
//! - **A point** ([`call`]): *synchronised* when at least half the realisations merged (the
//!   copy became identical to its reference: exponent −∞; then the median realisation is −∞);
//!   else *chaotic* when the lower confidence bound of the unmerged mean exceeds δ, *not
//!   chaotic* when the upper confidence bound lies below δ, otherwise *undecided*. The merged
//!   fraction is kept beside the call, never dropped.
//! - **Against the phase reduction** ([`agrees_with_prediction`]): two one-sided tests that
//!   |λ − (−cD)| < δ (equivalence), for the figures' small-D points.
//! - **A curve's D_c** ([`bracket`]): D2 the smallest chaotic D, D1 the largest not-chaotic
//!   (or synchronised) D below it: D_c ∈ (D1, D2). No chaotic point: not chaotic throughout
//!   (D_c above the range, when the largest D is called not chaotic). Chaotic at the smallest D:
//!   D_c below the range.
//! - **No D_c at all** ([`strong_noise`], [`Bracket::Never`]): a curve with no chaotic point
//!   whose exponent, over its last decade of D (at least three points, the two largest called
//!   regular), falls with D — the weighted least-squares slope against log10 D significantly
//!   negative (one-sided t at [`ALPHA`]). Strong noise drives the path to amplitudes where the
//!   damping's highest power dominates μ0P(U); there the motion is overdamped and contracts, so
//!   the exponent moves away from the margin as D grows: the curve has no critical noise, not
//!   one above the range. (Measured beyond the figures' range on Fig. 19's base point, τ = 0.3
//!   and 0.5: −0.01 to −0.05 at D = 100, 300 and 1000; docs/verdicts.md.)
//! - **The rest regime** ([`rest_regime`]): over the points at D ≤ [`REST_HOMOGENEOUS_D`]
//!   (where the homogeneity holds), the pooled (inverse-variance) exponent and the weighted
//!   least-squares slope against log10 D; "chaotic as D → 0: D_c = 0" when the pooled exponent
//!   exceeds δ (one-sided t), the slope is not significant (two-sided t, both at [`ALPHA`]) and
//!   the points span at least [`REST_DECADES`] decades.
//!
//! Reference: docs/verdicts.md, "The Lyapunov claims by regime". Tested by the unit tests
//! below (each outcome of each rule, and the merged realisations kept).

use super::super::stats::{t_for_two_sided, t_two_sided_p};
use super::ALPHA;
use serde::{Deserialize, Serialize};

/// The fewest decades of D over which the rest regime's exponent must be flat.
pub const REST_DECADES: f64 = 3.0;

/// One exponent at one noise intensity, with what the realisations did.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct RegimePoint {
    /// Noise intensity D.
    #[serde(with = "trirhythm::non_finite")]
    pub d: f64,
    /// Mean exponent of the realisations that did not merge.
    #[serde(with = "trirhythm::non_finite")]
    pub mean: f64,
    /// Its standard error (NaN with fewer than two).
    #[serde(with = "trirhythm::non_finite")]
    pub se: f64,
    /// Realisations.
    pub n: usize,
    /// Realisations whose copy merged with its reference (exponent −∞).
    pub merged: usize,
}

impl RegimePoint {
    /// The share of realisations that merged.
    pub fn merged_fraction(&self) -> f64 {
        if self.n == 0 {
            f64::NAN
        } else {
            self.merged as f64 / self.n as f64
        }
    }

    /// Degrees of freedom of the unmerged mean.
    fn dof(&self) -> f64 {
        (self.n - self.merged) as f64 - 1.0
    }
}

/// What a point says about chaos.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Call {
    /// The exponent exceeds the margin δ (one-sided t).
    Chaotic,
    /// The exponent lies below the margin δ (one-sided t).
    NotChaotic,
    /// At least half the realisations merged (synchronised: exponent −∞).
    Synchronised,
    /// Neither shown (or no standard error).
    Undecided,
}

impl Call {
    /// Short, for tables and pictures.
    pub fn tag(self) -> &'static str {
        match self {
            Call::Chaotic => "chaotic",
            Call::NotChaotic => "not chaotic",
            Call::Synchronised => "synchronised",
            Call::Undecided => "undecided",
        }
    }

    /// Not chaotic or synchronised.
    pub fn is_regular(self) -> bool {
        matches!(self, Call::NotChaotic | Call::Synchronised)
    }
}

/// The one-sided critical t at level `alpha` with `nu` degrees of freedom.
fn one_sided(alpha: f64, nu: f64) -> f64 {
    t_for_two_sided(2.0 * alpha, nu)
}

/// The call of one point with margin `margin` (δ = 1/W), at one-sided level `alpha` (the
/// family level over the curve divided by its points).
pub fn call(p: &RegimePoint, margin: f64, alpha: f64) -> Call {
    if p.n > 0 && 2 * p.merged >= p.n {
        return Call::Synchronised;
    }
    let nu = p.dof();
    if !(p.mean.is_finite() && p.se.is_finite() && p.se > 0.0 && nu >= 1.0) {
        return Call::Undecided;
    }
    let t = one_sided(alpha, nu);
    if (p.mean - margin) / p.se > t {
        Call::Chaotic
    } else if (margin - p.mean) / p.se > t {
        Call::NotChaotic
    } else {
        Call::Undecided
    }
}

/// Every point's call over a curve, Bonferroni over its points at family level [`ALPHA`].
pub fn calls(points: &[RegimePoint], margin: f64) -> Vec<Call> {
    let k = points.len().max(1) as f64;
    points.iter().map(|p| call(p, margin, ALPHA / k)).collect()
}

/// Equivalence of the exponent with the phase reduction's −c·D within `margin`: two one-sided
/// t tests at level `alpha`; None where there is no test (merged realisations, no standard
/// error, no coefficient).
pub fn agrees_with_prediction(
    p: &RegimePoint,
    coefficient: Option<f64>,
    margin: f64,
    alpha: f64,
) -> Option<bool> {
    let c = coefficient?;
    let nu = p.dof();
    if p.merged > 0 || !(p.se.is_finite() && p.se > 0.0 && nu >= 1.0 && p.mean.is_finite()) {
        return None;
    }
    let predicted = -c * p.d;
    let t = one_sided(alpha, nu);
    let lower = (p.mean - (predicted - margin)) / p.se;
    let upper = ((predicted + margin) - p.mean) / p.se;
    Some(lower > t && upper > t)
}

/// Where a curve's D_c lies, from its points' calls (D ascending).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", tag = "kind")]
pub enum Bracket {
    /// D_c in (lo, hi): `lo` the largest regular D below `hi`, the smallest chaotic D.
    Located {
        /// Largest not-chaotic or synchronised D below `hi`.
        lo: f64,
        /// Smallest chaotic D.
        hi: f64,
    },
    /// Chaotic at the smallest D: D_c below it (0 in the rest regime).
    Below {
        /// The smallest D.
        d: f64,
    },
    /// No chaotic point, the largest D regular: D_c above it.
    Above {
        /// The largest D.
        d: f64,
    },
    /// No chaotic point and the exponent falling with D over the last decade ([`strong_noise`]):
    /// no D_c at any D.
    Never {
        /// The largest D.
        d: f64,
    },
    /// Neither: a chaotic point with nothing regular below it but undecided points, or no
    /// chaotic point with the largest D undecided.
    Undecided,
}

impl Bracket {
    /// In words.
    pub fn words(&self) -> String {
        use crate::notes::num;
        match self {
            Bracket::Located { lo, hi } => format!("D_c in ({}, {})", num(*lo), num(*hi)),
            Bracket::Below { d } => format!(
                "chaotic from the smallest D = {}: D_c < {}",
                num(*d),
                num(*d)
            ),
            Bracket::Above { d } => format!(
                "not chaotic up to the largest D = {}: D_c > {}",
                num(*d),
                num(*d)
            ),
            Bracket::Never { d } => format!(
                "never chaotic: regular up to D = {} and falling with D there: no D_c",
                num(*d)
            ),
            Bracket::Undecided => "D_c not bracketed (undecided points between)".into(),
        }
    }
}

/// The bracket of D_c of a curve whose points (D ascending) have the calls `calls`.
pub fn bracket(ds: &[f64], calls: &[Call]) -> Bracket {
    let first_chaotic = calls.iter().position(|&c| c == Call::Chaotic);
    match first_chaotic {
        Some(0) => Bracket::Below { d: ds[0] },
        Some(k) => match (0..k).rev().find(|&j| calls[j].is_regular()) {
            Some(j) => Bracket::Located {
                lo: ds[j],
                hi: ds[k],
            },
            None => Bracket::Undecided,
        },
        None => match calls.last() {
            Some(c) if c.is_regular() => Bracket::Above {
                d: ds[ds.len() - 1],
            },
            _ => Bracket::Undecided,
        },
    }
}

/// The rest regime's statistics over a curve, from its points at D ≤ [`REST_HOMOGENEOUS_D`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct RestRegime {
    /// The inverse-variance pooled exponent over the unmerged means.
    #[serde(with = "trirhythm::non_finite")]
    pub pooled: f64,
    /// Its standard error.
    #[serde(with = "trirhythm::non_finite")]
    pub pooled_se: f64,
    /// Weighted least-squares slope of the exponent against log10 D (per decade).
    #[serde(with = "trirhythm::non_finite")]
    pub slope: f64,
    /// Its standard error.
    #[serde(with = "trirhythm::non_finite")]
    pub slope_se: f64,
    /// Decades of D spanned by the points used.
    #[serde(with = "trirhythm::non_finite")]
    pub decades: f64,
    /// The pooled exponent above δ (one-sided t at [`ALPHA`]), the slope not significant
    /// (two-sided t at [`ALPHA`]), at least [`REST_DECADES`] decades: chaotic as D → 0,
    /// D_c = 0.
    #[serde(alias = "chaotic_every_d")]
    pub d_c_zero: bool,
}

/// The largest D the rest regime's rule reads: the state's scale is √D, and the term that
/// breaks the homogeneity, μ0(P(U) − P(0)) ≈ −μ0U², is then at most 10⁻² of μ0P(0).
pub const REST_HOMOGENEOUS_D: f64 = 1e-2;

/// The inverse-variance pooled mean of points, the weighted least-squares slope against
/// log10 D, their standard errors, the decades spanned and the degrees of freedom of the
/// least-informed point (conservative for the tests).
struct LogFit {
    pooled: f64,
    pooled_se: f64,
    slope: f64,
    slope_se: f64,
    decades: f64,
    nu: f64,
}

/// The points with a finite mean and standard error and no merged realisation, `keep` of D.
fn usable(points: &[RegimePoint], keep: impl Fn(f64) -> bool) -> Vec<&RegimePoint> {
    points
        .iter()
        .filter(|p| {
            keep(p.d) && p.merged == 0 && p.mean.is_finite() && p.se.is_finite() && p.se > 0.0
        })
        .collect()
}

fn log_fit(usable: &[&RegimePoint]) -> LogFit {
    let w: Vec<f64> = usable.iter().map(|p| 1.0 / (p.se * p.se)).collect();
    let sw: f64 = w.iter().sum();
    let pooled = usable.iter().zip(&w).map(|(p, w)| w * p.mean).sum::<f64>() / sw;
    let pooled_se = (1.0 / sw).sqrt();
    let x: Vec<f64> = usable.iter().map(|p| p.d.log10()).collect();
    let mx = x.iter().zip(&w).map(|(x, w)| w * x).sum::<f64>() / sw;
    let sxx: f64 = x.iter().zip(&w).map(|(x, w)| w * (x - mx) * (x - mx)).sum();
    let sxy: f64 = x
        .iter()
        .zip(usable.iter())
        .zip(&w)
        .map(|((x, p), w)| w * (x - mx) * (p.mean - pooled))
        .sum();
    let slope = sxy / sxx;
    let slope_se = (1.0 / sxx).sqrt();
    let decades = match (usable.first(), usable.last()) {
        (Some(a), Some(b)) => (b.d / a.d).log10(),
        _ => 0.0,
    };
    // the tests with the degrees of freedom of the least-informed point (conservative)
    let nu = usable.iter().map(|p| p.dof()).fold(f64::INFINITY, f64::min);
    LogFit {
        pooled,
        pooled_se,
        slope,
        slope_se,
        decades,
        nu,
    }
}

/// The rest regime's rule over a curve (module docs), margin δ = `margin`: the points at
/// D ≤ [`REST_HOMOGENEOUS_D`] pooled and regressed on log10 D.
pub fn rest_regime(points: &[RegimePoint], margin: f64) -> RestRegime {
    let usable = usable(points, |d| d <= REST_HOMOGENEOUS_D);
    let LogFit {
        pooled,
        pooled_se,
        slope,
        slope_se,
        decades,
        nu,
    } = log_fit(&usable);
    let positive = (pooled - margin) / pooled_se > one_sided(ALPHA, nu);
    let flat = t_two_sided_p(slope / slope_se, nu) > ALPHA;
    RestRegime {
        pooled,
        pooled_se,
        slope,
        slope_se,
        decades,
        d_c_zero: usable.len() >= 3 && positive && flat && decades >= REST_DECADES,
    }
}

/// The strong-noise end of a curve: the slope of its exponent against log10 D over its last
/// decade of D.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct StrongNoise {
    /// The smallest D used (≥ a tenth of the largest).
    #[serde(with = "trirhythm::non_finite")]
    pub from: f64,
    /// The largest D.
    #[serde(with = "trirhythm::non_finite")]
    pub to: f64,
    /// Points used.
    pub points: usize,
    /// Weighted least-squares slope per decade of D.
    #[serde(with = "trirhythm::non_finite")]
    pub slope: f64,
    /// Its standard error.
    #[serde(with = "trirhythm::non_finite")]
    pub slope_se: f64,
    /// No chaotic point, the two largest D regular, at least three points and the slope
    /// significantly negative (one-sided t at [`ALPHA`]): the curve has no D_c.
    pub falling: bool,
}

/// The strong-noise rule (module docs) over a curve's points (D ascending) and calls; None
/// for a curve without points.
pub fn strong_noise(points: &[RegimePoint], calls: &[Call]) -> Option<StrongNoise> {
    let top = points.last()?.d;
    let used = usable(points, |d| d >= top / 10.0);
    let fit = log_fit(&used);
    let regular_end = calls.len() >= 2 && calls[calls.len() - 2..].iter().all(|c| c.is_regular());
    let never_chaotic = !calls.contains(&Call::Chaotic);
    let falling = never_chaotic
        && regular_end
        && used.len() >= 3
        && fit.slope.is_finite()
        && -fit.slope / fit.slope_se > one_sided(ALPHA, fit.nu);
    Some(StrongNoise {
        from: used.first().map_or(f64::NAN, |p| p.d),
        to: top,
        points: used.len(),
        slope: fit.slope,
        slope_se: fit.slope_se,
        falling,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(d: f64, mean: f64, se: f64) -> RegimePoint {
        RegimePoint {
            d,
            mean,
            se,
            n: 8,
            merged: 0,
        }
    }

    #[test]
    fn a_point_is_chaotic_regular_or_undecided_against_the_margin() {
        let m = 1e-3;
        // t(7) one-sided at 0.05 is 1.895
        assert_eq!(call(&point(0.1, 0.01, 0.001), m, 0.05), Call::Chaotic);
        assert_eq!(call(&point(0.1, -0.01, 0.001), m, 0.05), Call::NotChaotic);
        // zero with a tight error: below the margin, not chaotic (not "not significant")
        assert_eq!(call(&point(0.1, 0.0, 2e-4), m, 0.05), Call::NotChaotic);
        // zero with a wide error: undecided
        assert_eq!(call(&point(0.1, 0.0, 1e-3), m, 0.05), Call::Undecided);
        // just above the margin but not by t·se
        assert_eq!(call(&point(0.1, 2e-3, 1e-3), m, 0.05), Call::Undecided);
        assert_eq!(call(&point(0.1, f64::NAN, 1e-3), m, 0.05), Call::Undecided);
    }

    #[test]
    fn merged_realisations_are_kept_as_synchronised() {
        let mut p = point(0.3, 0.05, 0.001);
        p.merged = 4;
        assert_eq!(call(&p, 1e-3, 0.05), Call::Synchronised);
        assert_eq!(p.merged_fraction(), 0.5);
        // three of eight merged: the other five decide, with ν = 4
        p.merged = 3;
        assert_eq!(call(&p, 1e-3, 0.05), Call::Chaotic);
        assert_eq!(agrees_with_prediction(&p, Some(0.01), 1e-3, 0.05), None);
    }

    #[test]
    fn the_prediction_is_tested_for_equivalence() {
        // c = 0.013 at D = 0.05: −6.5e-4
        let p = point(0.05, -6.3e-4, 5e-5);
        assert_eq!(
            agrees_with_prediction(&p, Some(0.013), 1e-3, 0.05),
            Some(true)
        );
        let far = point(0.05, -3e-3, 5e-5);
        assert_eq!(
            agrees_with_prediction(&far, Some(0.013), 1e-3, 0.05),
            Some(false)
        );
        // too uncertain to show equivalence
        let wide = point(0.05, -6.3e-4, 1e-3);
        assert_eq!(
            agrees_with_prediction(&wide, Some(0.013), 1e-3, 0.05),
            Some(false)
        );
        assert_eq!(agrees_with_prediction(&p, None, 1e-3, 0.05), None);
    }

    #[test]
    fn undefined_statistics_survive_the_figure_data() {
        // a rest curve with fewer than two usable points has no slope: NaN, written as a
        // string, read back (figure data must round-trip)
        let r = rest_regime(&[point(1e-3, 0.01, f64::NAN)], 1e-3);
        assert!(r.slope.is_nan() && !r.d_c_zero);
        let back: RestRegime = serde_json::from_str(&serde_json::to_string(&r).unwrap()).unwrap();
        assert!(back.slope.is_nan() && back.pooled.is_nan());
        let p = point(0.1, f64::NAN, f64::NAN);
        let back: RegimePoint = serde_json::from_str(&serde_json::to_string(&p).unwrap()).unwrap();
        assert!(back.mean.is_nan() && back.d == 0.1);
    }

    #[test]
    fn brackets_follow_the_calls() {
        use Call::*;
        let ds = [0.001, 0.01, 0.1, 1.0];
        assert_eq!(
            bracket(&ds, &[NotChaotic, Synchronised, Undecided, Chaotic]),
            Bracket::Located { lo: 0.01, hi: 1.0 }
        );
        assert_eq!(bracket(&ds, &[Chaotic; 4]), Bracket::Below { d: 0.001 });
        assert_eq!(
            bracket(&ds, &[NotChaotic, NotChaotic, Undecided, NotChaotic]),
            Bracket::Above { d: 1.0 }
        );
        assert_eq!(
            bracket(&ds, &[Undecided, Chaotic, NotChaotic, Chaotic]),
            Bracket::Undecided
        );
        assert_eq!(
            bracket(&ds, &[NotChaotic, NotChaotic, NotChaotic, Undecided]),
            Bracket::Undecided
        );
    }

    #[test]
    fn a_curve_falling_at_strong_noise_has_no_critical_noise() {
        use Call::*;
        let ds = [0.1, 1.0, 5.0, 12.0, 30.0];
        let falling: Vec<RegimePoint> = ds
            .iter()
            .zip([0.0, 0.0, -0.006, -0.02, -0.035])
            .map(|(&d, m)| point(d, m, 3e-3))
            .collect();
        let calls = [NotChaotic, Undecided, Undecided, NotChaotic, NotChaotic];
        let s = strong_noise(&falling, &calls).unwrap();
        assert!(
            s.falling && s.points == 3 && s.from == 5.0 && s.slope < 0.0,
            "{s:?}"
        );
        // a chaotic point anywhere: a D_c exists
        let mut with_chaos = calls;
        with_chaos[1] = Chaotic;
        assert!(!strong_noise(&falling, &with_chaos).unwrap().falling);
        // the largest D undecided: not shown
        let mut open = calls;
        open[4] = Undecided;
        assert!(!strong_noise(&falling, &open).unwrap().falling);
        // flat at the end within the errors: D_c may lie beyond the range
        let flat: Vec<RegimePoint> = ds.iter().map(|&d| point(d, -0.01, 3e-3)).collect();
        assert!(!strong_noise(&flat, &calls).unwrap().falling);
        // rising toward the margin: not
        let rising: Vec<RegimePoint> = ds
            .iter()
            .zip([0.0, -0.03, -0.02, -0.01, -0.005])
            .map(|(&d, m)| point(d, m, 1e-3))
            .collect();
        assert!(!strong_noise(&rising, &calls).unwrap().falling);
        // two points in the last decade: too few
        assert!(!strong_noise(&falling[..4], &calls[..4]).unwrap().falling);
    }

    #[test]
    fn the_rest_regime_needs_a_positive_pooled_exponent_a_flat_curve_and_three_decades() {
        let ds = [1e-6, 1e-5, 1e-4, 1e-3, 1e-2, 1e-1];
        let flat: Vec<RegimePoint> = ds
            .iter()
            .enumerate()
            .map(|(k, &d)| point(d, 0.08 + if k % 2 == 0 { 1e-3 } else { -1e-3 }, 2e-3))
            .collect();
        let r = rest_regime(&flat, 1e-3);
        assert!(r.d_c_zero, "{r:?}");
        // the point at D = 0.1 is beyond the homogeneous range: four decades read
        assert!((r.pooled - 0.08).abs() < 1e-3 && r.decades == 4.0);
        // a trend of 0.01 per decade with errors of 0.002: significant, not flat
        let rising: Vec<RegimePoint> = ds
            .iter()
            .enumerate()
            .map(|(k, &d)| point(d, 0.05 + 0.01 * k as f64, 2e-3))
            .collect();
        let r = rest_regime(&rising, 1e-3);
        assert!(!r.d_c_zero && r.slope > 0.009, "{r:?}");
        // flat but only two decades
        let short: Vec<RegimePoint> = flat[2..].to_vec();
        assert!(!rest_regime(&short, 1e-3).d_c_zero);
        // flat at the margin: not above it
        let low: Vec<RegimePoint> = ds.iter().map(|&d| point(d, 1e-3, 2e-3)).collect();
        assert!(!rest_regime(&low, 1e-3).d_c_zero);
        // what happens above 10⁻² does not enter
        let mut high = flat.clone();
        high[5].mean = -0.5;
        assert_eq!(rest_regime(&high, 1e-3), rest_regime(&flat, 1e-3));
    }
}
