//! The critical noise D_c at which the LLE changes sign: a grid of D, the first sign change
//! among the D without merged realisations, bisection, and the bracket of significant signs
//! (module docs of [`super`]).

use super::{largest_lyapunov, LyapunovSpec};
use crate::analysis::ensemble::Estimate;
use crate::engine::{PredictorCorrector, Problem};
use crate::error::{Error, Exact, Result};
use crate::model::MAX_NOISE;
use crate::monitor::{Monitor, OnlyCancel};
use serde::{Deserialize, Serialize};

/// How [`critical_noise`] searches D.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CriticalSearch {
    /// Lower end of the D range, in [0, 1e6) (the parameter D's range).
    pub d_lo: f64,
    /// Upper end of the D range, in (d_lo, 1e6].
    pub d_hi: f64,
    /// Equally spaced D values evaluated first, ends included, 2 to [`MAX_GRID`].
    pub grid: usize,
    /// Bisections of the first bracketing pair, 0 to [`MAX_REFINEMENTS`].
    pub refinements: usize,
    /// Standard errors an LLE must be away from 0 to count as significant, in [0, 10].
    pub z: f64,
}

/// Most D values of a [`CriticalSearch`]'s grid.
pub const MAX_GRID: usize = 1000;
/// Most bisections of a [`CriticalSearch`].
pub const MAX_REFINEMENTS: usize = 60;
/// Largest [`CriticalSearch::z`].
pub const MAX_Z: f64 = 10.0;

impl CriticalSearch {
    /// Check the search: 0 ≤ `d_lo` < `d_hi` ≤ 1e6 ([`MAX_NOISE`], the parameter D's range),
    /// `grid` 2 to [`MAX_GRID`], `refinements` 0 to [`MAX_REFINEMENTS`], `z` in [0, 10].
    pub fn validate(&self) -> Result<()> {
        if !(self.d_lo >= 0.0 && self.d_lo < MAX_NOISE) {
            return Err(Error::invalid("d_lo", self.d_lo, "[0, 1e6)"));
        }
        if !(self.d_hi > self.d_lo && self.d_hi <= MAX_NOISE) {
            return Err(Error::invalid(
                "d_hi",
                self.d_hi,
                format!("(D_lo = {}, 1e6]", Exact(self.d_lo)),
            ));
        }
        if !(2..=MAX_GRID).contains(&self.grid) {
            return Err(Error::invalid(
                "grid",
                self.grid as f64,
                format!("2 to {MAX_GRID}"),
            ));
        }
        if self.refinements > MAX_REFINEMENTS {
            return Err(Error::invalid(
                "refinements",
                self.refinements as f64,
                format!("0 to {MAX_REFINEMENTS}"),
            ));
        }
        if !(self.z >= 0.0 && self.z <= MAX_Z) {
            return Err(Error::invalid("z", self.z, "[0, 10]"));
        }
        Ok(())
    }
}

impl Default for CriticalSearch {
    fn default() -> Self {
        CriticalSearch {
            d_lo: 0.0,
            d_hi: 1.0,
            grid: 5,
            refinements: 3,
            z: 2.0,
        }
    }
}

/// One evaluated noise intensity.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct NoisePoint {
    /// D.
    pub d: f64,
    /// Its LLE (−∞ when a realisation merged).
    pub lle: Estimate,
    /// Realisations whose copy merged with its reference: such a D gets no sign.
    #[serde(default)]
    pub merged: usize,
}

impl NoisePoint {
    /// The sign of the LLE (true: negative), or None when a realisation merged (−∞).
    pub(super) fn negative(&self) -> Option<bool> {
        (self.merged == 0).then_some(self.lle.value < 0.0)
    }
}

/// The first pair of consecutive signed points (those without merged realisations, in the
/// given order) whose LLEs have opposite signs: their indices.
pub(super) fn first_sign_change(points: &[NoisePoint]) -> Option<(usize, usize)> {
    let signed: Vec<usize> = (0..points.len())
        .filter(|&k| points[k].negative().is_some())
        .collect();
    signed
        .windows(2)
        .find(|w| points[w[0]].negative() != points[w[1]].negative())
        .map(|w| (w[0], w[1]))
}

/// The outcome of a critical-noise search.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CriticalNoise {
    /// D_c (NaN when the LLE has no sign change in the range).
    #[serde(with = "crate::non_finite")]
    pub d_c: f64,
    /// Lower end of D_c's uncertainty (NaN without a sign change).
    #[serde(with = "crate::non_finite")]
    pub d_c_lo: f64,
    /// Upper end of D_c's uncertainty (NaN without a sign change).
    #[serde(with = "crate::non_finite")]
    pub d_c_hi: f64,
    /// Whether the LLE goes from negative to positive across D_c (false: the other way).
    pub rising: bool,
    /// Every evaluated D, ascending.
    pub evaluated: Vec<NoisePoint>,
}

impl CriticalNoise {
    /// Whether a sign change was found.
    pub fn found(&self) -> bool {
        self.d_c.is_finite()
    }
}

/// The critical noise D_c of `problem` (its D overridden) where the LLE changes sign (module
/// docs). `monitor` hears (evaluations done, evaluations planned), receives each evaluated D
/// as it is finished, and may stop the search ([`Error::Cancelled`]), also inside an
/// evaluation.
pub fn critical_noise(
    problem: &Problem,
    method: &PredictorCorrector,
    spec: &LyapunovSpec,
    search: &CriticalSearch,
    monitor: &dyn Monitor<NoisePoint>,
) -> Result<CriticalNoise> {
    search.validate()?;
    spec.sizes(method)?;
    // both ends of the range are valid problems before any work
    for d in [search.d_lo, search.d_hi] {
        problem.with_params(&problem.params().with("D", d)?)?;
    }
    let planned = search.grid + search.refinements;
    let mut done = 0;
    let mut eval = |d: f64| -> Result<NoisePoint> {
        let at = problem.with_params(&problem.params().with("D", d)?)?;
        let r = largest_lyapunov(&at, method, spec, &OnlyCancel(monitor))?;
        done += 1;
        monitor.progress(done as u64, planned as u64);
        let point = NoisePoint {
            d,
            lle: r.lle,
            merged: r.merged,
        };
        monitor.finished(&point)?;
        Ok(point)
    };
    let h = (search.d_hi - search.d_lo) / (search.grid - 1) as f64;
    let mut evaluated = Vec::with_capacity(planned);
    for k in 0..search.grid {
        let d = if k + 1 == search.grid {
            search.d_hi
        } else {
            search.d_lo + h * k as f64
        };
        evaluated.push(eval(d)?);
    }
    let Some((i, j)) = first_sign_change(&evaluated) else {
        return Ok(CriticalNoise {
            d_c: f64::NAN,
            d_c_lo: f64::NAN,
            d_c_hi: f64::NAN,
            rising: false,
            evaluated,
        });
    };
    let rising = evaluated[i].negative() == Some(true);
    let (mut a, mut b) = (evaluated[i], evaluated[j]);
    for _ in 0..search.refinements {
        let m = eval(0.5 * (a.d + b.d))?;
        evaluated.push(m);
        match m.negative() {
            Some(neg) if Some(neg) == a.negative() => a = m,
            Some(_) => b = m,
            // a realisation merged at the midpoint: no sign there, the bracket stays
            None => break,
        }
    }
    evaluated.sort_by(|p, q| p.d.total_cmp(&q.d));
    let d_c = if a.lle.value.is_finite() && b.lle.value.is_finite() {
        a.d - a.lle.value * (b.d - a.d) / (b.lle.value - a.lle.value)
    } else {
        0.5 * (a.d + b.d)
    };
    let significant = |p: &NoisePoint, below: bool| {
        if p.merged > 0 {
            return false;
        }
        let s = if p.lle.stderr.is_finite() {
            p.lle.stderr
        } else {
            0.0
        };
        if below == rising {
            p.lle.value < -search.z * s
        } else {
            p.lle.value > search.z * s
        }
    };
    let d_c_lo = evaluated
        .iter()
        .rev()
        .find(|p| p.d <= d_c && significant(p, true))
        .map_or(search.d_lo, |p| p.d);
    let d_c_hi = evaluated
        .iter()
        .find(|p| p.d >= d_c && significant(p, false))
        .map_or(search.d_hi, |p| p.d);
    Ok(CriticalNoise {
        d_c,
        d_c_lo,
        d_c_hi,
        rising,
        evaluated,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_sign_change_skips_merged_points() {
        let p = |d: f64, value: f64, merged: usize| NoisePoint {
            d,
            lle: Estimate {
                value,
                stderr: 0.01,
            },
            merged,
        };
        // − then −∞ (merged) then +: the change is between the first and the third
        let pts = [
            p(0.1, -0.2, 0),
            p(0.2, f64::NEG_INFINITY, 1),
            p(0.3, 0.1, 0),
        ];
        assert_eq!(first_sign_change(&pts), Some((0, 2)));
        // + then merged then +: no change (the −∞ is not a negative exponent)
        let pts = [p(0.1, 0.2, 0), p(0.2, f64::NEG_INFINITY, 2), p(0.3, 0.1, 0)];
        assert_eq!(first_sign_change(&pts), None);
        // a merged point never starts a bracket, even with a finite mean recorded
        let pts = [p(0.1, -0.2, 1), p(0.2, 0.3, 0), p(0.3, -0.1, 0)];
        assert_eq!(first_sign_change(&pts), Some((1, 2)));
    }
}
