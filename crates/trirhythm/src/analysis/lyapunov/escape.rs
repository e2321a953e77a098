//! Whether the exponent's reference paths stay in the well of the attractor they start on.
//!
//! # Problem
//! A finite-time exponent measured from a stable cycle describes that cycle only while the path
//! stays in its basin. Under strong noise the path may leave the cycle's well within the
//! transient and window; then a positive exponent may be the motion after the escape, and the
//! critical noise found depends on the window's length.
//!
//! # Method
//! The reference paths of [`super::largest_lyapunov`] are rerun alone — path i from
//! `problem.start(i)` on noise stream i of `spec.seed`, for the same transient + window — and
//! each path's turning amplitudes (U where U̇ changes sign from + to −) are compared with the
//! well (lo, hi) in amplitude: the first turning amplitude outside it is the path's escape time.
//! The paths are the exponent's own reference paths (same start, stream and step), run in
//! parallel; the result does not depend on the thread count.
//!
//! # Result
//! [`WellEscape`]: the share of paths that left the well within the run and the median first
//! escape time over the paths that left.
//!
//! # Tests
//! Unit tests below: a noise-free path on a stable cycle never leaves its well; a well that
//! excludes the cycle is left at the first turning point; the result is identical whatever the
//! thread count.

use super::LyapunovSpec;
use crate::engine::{PredictorCorrector, Problem, Stepper};
use crate::error::{Error, Result};
use crate::monitor::Monitor;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// How many of the exponent's reference paths left an amplitude well, and when.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct WellEscape {
    /// The well's lower amplitude end (0: none).
    #[serde(with = "crate::non_finite")]
    pub lo: f64,
    /// The well's upper amplitude end (∞: none).
    #[serde(with = "crate::non_finite")]
    pub hi: f64,
    /// Paths run.
    pub paths: usize,
    /// Paths whose turning amplitude left (lo, hi) within the run.
    pub escaped: usize,
    /// The median first escape time over the paths that left (NaN when none did).
    #[serde(with = "crate::non_finite")]
    pub median_time: f64,
    /// The run's length (transient + window).
    #[serde(with = "crate::non_finite")]
    pub run: f64,
}

impl WellEscape {
    /// The share of paths that left.
    pub fn fraction(&self) -> f64 {
        self.escaped as f64 / self.paths.max(1) as f64
    }
}

/// The first time path `i`'s turning amplitude leaves (lo, hi) within `steps` steps.
fn first_escape(
    problem: &Problem,
    method: &PredictorCorrector,
    (seed, i): (u64, u64),
    (lo, hi): (f64, f64),
    steps: u64,
) -> Result<Option<f64>> {
    let horizon = steps as f64 * method.dt;
    let mut s = Stepper::new(problem, method, (seed, i), horizon)?;
    let mut v_prev = s.v();
    for _ in 0..steps {
        s.step()?;
        let v = s.v();
        if v_prev > 0.0 && v <= 0.0 {
            let a = s.u();
            if !(a > lo && a < hi) {
                return Ok(Some(s.time()));
            }
        }
        v_prev = v;
    }
    Ok(None)
}

/// Run the reference paths of [`super::largest_lyapunov`] for `problem`, `method` and `spec`
/// (module docs) and count their escapes from the amplitude well (`lo`, `hi`), 0 ≤ lo < hi.
pub fn well_escape(
    problem: &Problem,
    method: &PredictorCorrector,
    spec: &LyapunovSpec,
    (lo, hi): (f64, f64),
    monitor: &dyn Monitor,
) -> Result<WellEscape> {
    if !(lo >= 0.0 && lo.is_finite()) {
        return Err(Error::invalid("well lower end", lo, "[0, ∞)"));
    }
    if hi.is_nan() || hi <= lo {
        return Err(Error::invalid("well upper end", hi, "(lower end, ∞]"));
    }
    let (transient, window) = spec.sizes(method)?;
    let steps = transient + window;
    monitor.check()?;
    let times: Vec<Option<f64>> = crate::profile::parallel(|stage| {
        (0..spec.paths as u64)
            .into_par_iter()
            .map(|i| {
                stage.task(|| {
                    monitor.check()?;
                    first_escape(problem, method, (spec.seed, i), (lo, hi), steps)
                })
            })
            .collect::<Result<_>>()
    })?;
    let mut left: Vec<f64> = times.iter().flatten().copied().collect();
    left.sort_by(f64::total_cmp);
    let median_time = match left.len() {
        0 => f64::NAN,
        n if n % 2 == 1 => left[n / 2],
        n => 0.5 * (left[n / 2 - 1] + left[n / 2]),
    };
    Ok(WellEscape {
        lo,
        hi,
        paths: spec.paths,
        escaped: left.len(),
        median_time,
        run: steps as f64 * method.dt,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::preset;
    use crate::monitor::Silent;

    fn setup(d: f64) -> (Problem, PredictorCorrector, LyapunovSpec) {
        let p = preset("fig19").unwrap().params.with("D", d).unwrap();
        let problem = Problem::from_params(&p)
            .unwrap()
            .with_start(12.9, 0.0)
            .unwrap();
        let method = PredictorCorrector {
            dt: 0.01,
            ..Default::default()
        };
        let spec = LyapunovSpec {
            paths: 4,
            transient: 20.0,
            length: 60.0,
            ..Default::default()
        };
        (problem, method, spec)
    }

    #[test]
    fn a_noise_free_cycle_stays_in_its_well_and_a_wrong_well_is_left_at_once() {
        let (problem, method, spec) = setup(0.0);
        let e = well_escape(&problem, &method, &spec, (10.0, 16.0), &Silent).unwrap();
        assert_eq!((e.escaped, e.paths), (0, 4), "{e:?}");
        assert!(e.median_time.is_nan() && e.run == 80.0);
        // the outer cycle (A ≈ 12.9) lies above this well: left at the first turning point,
        // within the first period (2π/ω0 ≈ 7)
        let e = well_escape(&problem, &method, &spec, (0.0, 10.0), &Silent).unwrap();
        assert_eq!(e.escaped, 4);
        assert!(e.median_time > 0.0 && e.median_time < 7.0, "{e:?}");
        assert!(well_escape(&problem, &method, &spec, (5.0, 5.0), &Silent).is_err());
    }

    #[test]
    fn escapes_do_not_depend_on_the_thread_count() {
        let (problem, method, spec) = setup(30.0);
        let run = |threads| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap()
                .install(|| well_escape(&problem, &method, &spec, (10.0, 14.0), &Silent))
                .unwrap()
        };
        let (one, two) = (run(1), run(2));
        assert_eq!(one, two);
        assert!(
            one.escaped > 0,
            "strong noise leaves a narrow well: {one:?}"
        );
    }
}
