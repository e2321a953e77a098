//! Is the step Δt fine enough for the problem? A guard run before any long simulation.
//!
//! # Problem
//! The predictor–corrector is stable for any stiffness in the damping (the corrector is
//! linearly implicit), so a step far too large for the problem does not blow up: it returns
//! a wrong answer that looks plausible (at Δt = 1 the Fig. 13(a) cycle of amplitude 7.49 comes
//! out at 0.26). Three time scales bound Δt: the period 2π/ω1 of Eq. (5), the noise's
//! correlation time τ, and the stiffness of the damping μ0P(U) at the amplitudes the paths
//! visit — which a formula cannot bound usefully (μ0 max|P| reaches 4·10³ on the outer cycle of
//! Fig. 13(b), where Δt = 0.01 is still accurate to 10⁻³ because |P| is large only near the
//! turning points, where U̇ is small), so it is measured.
//!
//! # Method
//! - **Period.** n_T = 2π/(ω1Δt) steps per period. Below [`MIN_STEPS_PER_PERIOD`] the step is
//!   refused without further ado (measured on Fig. 13(a) without noise over 600 time units:
//!   at 6.3 steps per period the amplitude 7.49 comes out at 0.26, at 12.6 it is 2 % low, at 21
//!   within 0.05 %).
//! - **Step halving at the expected amplitudes.** For each amplitude the caller names (the
//!   paths' starts, the cycles of the averaged theory) the noise-free problem is integrated
//!   from (A, 0) over [`CHECK_PERIODS`] periods with Δt and with Δt/2 — the same stepper, memory,
//!   wall and impacts as the run. The quantity compared is the one the tool reports, the
//!   amplitude √(U² + U̇²/ω1²), averaged over the last period: δ = |Ā_Δt − Ā_Δt/2| / max(A,
//!   Ā_Δt/2). (The end state itself would count a phase error, which amplitude statistics do
//!   not see and which a relaxation cycle's jump timing makes O(1) at any step.) For a method of
//!   order p, δ estimates the Δt run's error to within a factor 2^p/(2^p − 1). δ above
//!   [`REFUSE_DEVIATION`] refuses the step (a quarter of the amplitude: the run's amplitudes
//!   would be wrong in their leading digit); above [`WARN_DEVIATION`] the run goes on with a warning carried in its output and
//!   on its figure. A step that blows up in the check is refused. The window is long enough
//!   (10 periods) for a start at rest to settle on its cycle, so that the check judges the
//!   cycle rather than the transient: over 3 periods Fig. 13(b)'s relaxation from rest at the
//!   theory's outer cycle (A ≈ 12.9, μ0 = 0.2, where μ0|P| reaches 10³) changes by 7 % when
//!   Δt = 0.01 halves, over 10 by 0.14 % (0.015 % at Δt = 0.005: third order, as
//!   `tests/stiff.rs` finds on the settled cycle). Measured at the default Δt = 0.01: at most
//!   0.14 % on every preset as printed, but 5.7 % (warned) on Fig. 13(b) at r = 0.85 with the
//!   memory restarted at impacts (12.5 % from the noisy theory's mode A = 12.92), where the
//!   relaxation from rest reaches its asymptotic order only below Δt = 0.0025 (3.8 % at 0.005,
//!   0.5 % at 0.0025). The refusal threshold is set above these (a coarse step is warned, a
//!   wrong one refused): Δt = 1 on Fig. 13(a) (the period rule), Δt = 0.5 on Fig. 13(b) (205 %
//!   from A = 8.7) are refused.
//! - **Correlation time.** With coloured noise, n_τ = τ/Δt steps per correlation time. The
//!   noise's step integrals have their exact law whatever Δt/τ (see [`crate::engine::noise`]),
//!   so an unresolved τ is not refused; but inside a step η is its step mean, which flattens
//!   the forcing's spectrum above 1/Δt. Below [`WARN_STEPS_PER_TAU`] the run carries a warning
//!   (largest Lyapunov exponents at 2.5 steps per τ were measured ≈ 6 % low).
//!
//! The suggested step of a refusal assumes second order: Δt·(REFUSE_DEVIATION/δ)^{1/2}/2, and
//! at most 2π/(ω1·[`MIN_STEPS_PER_PERIOD`]).
//!
//! # Cost
//! 3·[`CHECK_PERIODS`]·n_T steps per amplitude (≈ 2·10⁴ at the default Δt = 0.01, ω1 ≈ 1),
//! with the sum-of-exponentials memory whatever the run's, and none beyond
//! [`MAX_CHECK_STEPS_PER_PERIOD`] steps per period: milliseconds, against runs of 10⁶–10¹⁰ steps.
//!
//! # Tests
//! Unit tests below: the default step passes on the paper's presets at their cycles; Δt = 1 on
//! Fig. 13(a) is refused and the refusal names `dt`; a coarse step warns; the deviation falls
//! by about 2^p when Δt halves (an observed order); coloured noise with Δt > τ/10 warns; a
//! model with multiplicative noise is checked as the same model without it (noise-free).

use super::drivers::simulate;
use super::problem::{Options, PredictorCorrector, Problem};
use crate::error::{Error, Result};
use std::f64::consts::PI;

/// Fewest steps per period 2π/ω1: coarser steps are refused before any check.
pub const MIN_STEPS_PER_PERIOD: f64 = 10.0;
/// Periods 2π/ω1 of each step-halving check.
pub const CHECK_PERIODS: f64 = 10.0;
/// Relative step-halving deviation above which a run carries a warning.
pub const WARN_DEVIATION: f64 = 1e-2;
/// Relative step-halving deviation above which the step is refused.
pub const REFUSE_DEVIATION: f64 = 0.25;
/// Fewest steps per correlation time τ without a warning.
pub const WARN_STEPS_PER_TAU: f64 = 10.0;
/// Most amplitudes one check integrates.
pub const MAX_CHECK_AMPLITUDES: usize = 16;
/// Steps per period 2π/ω1 beyond which the halving is not run: far finer than any step the
/// rules warn at (the stiffest preset, Fig. 13(b), changes by 2·10⁻⁵ at 2500 steps per
/// period), and it bounds the check's cost at 3·[`CHECK_PERIODS`]·2·10⁴ steps per amplitude.
pub const MAX_CHECK_STEPS_PER_PERIOD: f64 = 2e4;

/// One step-halving check: the noise-free problem from (A, 0) over [`CHECK_PERIODS`] periods.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Halving {
    /// The start amplitude A.
    pub amplitude: f64,
    /// δ = |Ā_Δt − Ā_Δt/2| / max(A, Ā_Δt/2) (module docs); ∞ when a run blew up.
    pub deviation: f64,
}

/// How well Δt resolves the problem's time scales; see the module docs for the rules.
#[derive(Debug, Clone, PartialEq)]
pub struct Resolution {
    /// The step Δt.
    pub dt: f64,
    /// 2π/(ω1Δt).
    pub steps_per_period: f64,
    /// τ/Δt with coloured noise, else `None`.
    pub steps_per_tau: Option<f64>,
    /// The step-halving checks, one per distinct amplitude (empty when the period rule refused
    /// or the step is finer than [`MAX_CHECK_STEPS_PER_PERIOD`]).
    pub halvings: Vec<Halving>,
}

impl Resolution {
    /// Check `method.dt` for `problem` at the amplitudes `amplitudes` (non-positive and
    /// non-finite ones are skipped, duplicates checked once, at most [`MAX_CHECK_AMPLITUDES`]).
    /// Errors only for an invalid method; a refused step is [`Resolution::refusal`].
    pub fn check(
        problem: &Problem,
        method: &PredictorCorrector,
        amplitudes: &[f64],
    ) -> Result<Resolution> {
        method.validate()?;
        let params = problem.params();
        let omega1 = problem.oscillator().equivalents().omega1;
        let period = 2.0 * PI / omega1;
        let steps_per_period = period / method.dt;
        let tau = params.correlation_time;
        let steps_per_tau = (params.noise_intensity > 0.0 && tau > 0.0).then_some(tau / method.dt);
        let mut res = Resolution {
            dt: method.dt,
            steps_per_period,
            steps_per_tau,
            halvings: vec![],
        };
        if !(MIN_STEPS_PER_PERIOD..=MAX_CHECK_STEPS_PER_PERIOD).contains(&steps_per_period) {
            return Ok(res);
        }
        // the step's error, not the memory's: the check keeps the history by sums of
        // exponentials (O(1) per step) even for a run with the exact O(N) memory
        let method = &PredictorCorrector {
            memory: super::Memory::default(),
            ..*method
        };
        let mut list: Vec<f64> = amplitudes
            .iter()
            .copied()
            .filter(|a| a.is_finite() && *a > 0.0 && *a < problem.blow_up())
            .collect();
        list.sort_by(f64::total_cmp);
        list.dedup_by(|a, b| (*a - *b).abs() <= 1e-6 * b.abs());
        list.truncate(MAX_CHECK_AMPLITUDES);
        // noise-free: the additive noise off, and the multiplicative U·η_m too
        let mut quiet = problem.with_params(&params.clone().with("D", 0.0)?)?;
        if let Some(terms) = quiet.oscillator().terms() {
            if terms.multiplicative.is_some() {
                let mut terms = terms.clone();
                terms.multiplicative = None;
                terms.correlation = 0.0;
                quiet = quiet.with_terms((!terms.is_empty()).then_some(terms))?;
            }
        }
        let steps = (CHECK_PERIODS * steps_per_period).ceil();
        let t_end = steps * method.dt;
        for a in list {
            let start = quiet.clone().with_start(a, 0.0);
            // a start the problem does not allow (below the wall) is not the run's
            let Ok(start) = start else { continue };
            let deviation = halving(&start, method, t_end, steps as usize, omega1, a)?;
            res.halvings.push(Halving {
                amplitude: a,
                deviation,
            });
        }
        Ok(res)
    }

    /// The largest step-halving deviation (0 with no check).
    pub fn worst_deviation(&self) -> f64 {
        self.halvings
            .iter()
            .map(|h| h.deviation)
            .fold(0.0, |m, d| if d > m || d.is_nan() { d } else { m })
    }

    /// The start amplitude of the largest deviation (NaN with no check).
    pub fn worst_amplitude(&self) -> f64 {
        let worst = self.worst_deviation();
        self.halvings
            .iter()
            .find(|h| h.deviation == worst || h.deviation.is_nan())
            .map_or(f64::NAN, |h| h.amplitude)
    }

    /// The error refusing the step, naming `dt`, its value and the largest step the rules
    /// suggest; `None` when the step is accepted.
    pub fn refusal(&self) -> Option<Error> {
        let period_max = self.steps_per_period * self.dt / MIN_STEPS_PER_PERIOD;
        if self.steps_per_period < MIN_STEPS_PER_PERIOD {
            return Some(Error::invalid(
                "dt",
                self.dt,
                format!(
                    "(0, {}] here: {:.3} steps per period 2π/ω1, fewer than {MIN_STEPS_PER_PERIOD}",
                    crate::error::Readable(period_max),
                    self.steps_per_period
                ),
            ));
        }
        let worst = self.worst_deviation();
        if worst > REFUSE_DEVIATION || worst.is_nan() {
            let at = self.worst_amplitude();
            let suggest = if worst.is_finite() {
                (self.dt * (REFUSE_DEVIATION / worst).sqrt() / 2.0).min(period_max)
            } else {
                self.dt / 10.0
            };
            return Some(Error::invalid(
                "dt",
                self.dt,
                format!(
                    "about (0, {}] here: halving the step changes the noise-free mean \
                     amplitude from A = {} by {} of it over {CHECK_PERIODS} periods (more than \
                     {REFUSE_DEVIATION})",
                    crate::error::Readable(suggest),
                    crate::error::Readable(at),
                    describe(worst)
                ),
            ));
        }
        None
    }

    /// Warnings for an accepted step that is coarse (empty when it is well resolved).
    pub fn warnings(&self) -> Vec<String> {
        let mut out = vec![];
        let worst = self.worst_deviation();
        if worst > WARN_DEVIATION && worst <= REFUSE_DEVIATION {
            out.push(format!(
                "dt = {}: halving the step changes the noise-free mean amplitude from A = {} \
                 by {} of it over {CHECK_PERIODS} periods (more than {WARN_DEVIATION}); \
                 amplitudes there carry an error of that order",
                crate::error::Exact(self.dt),
                crate::error::Readable(self.worst_amplitude()),
                describe(worst)
            ));
        }
        if let Some(n) = self.steps_per_tau.filter(|n| *n < WARN_STEPS_PER_TAU) {
            out.push(format!(
                "dt = {}: {:.3} steps per noise correlation time τ (fewer than \
                 {WARN_STEPS_PER_TAU}); the noise's step integrals are exact but its colour \
                 inside a step is lost (Lyapunov exponents ≈ 6 % low at 2.5 steps per τ)",
                crate::error::Exact(self.dt),
                n
            ));
        }
        out
    }

    /// [`Resolution::refusal`] as a result: the step, or the error.
    pub fn require(self) -> Result<Self> {
        match self.refusal() {
            Some(e) => Err(e),
            None => Ok(self),
        }
    }
}

fn describe(x: f64) -> String {
    if x.is_finite() {
        format!("{x:.3e}")
    } else {
        "a blow-up".into()
    }
}

/// δ of one start: the mean amplitude √(U² + U̇²/ω1²) over the last period of the window, of
/// the Δt and Δt/2 runs over `steps` steps of Δt, relative to the larger of A and the Δt/2 mean.
fn halving(
    problem: &Problem,
    method: &PredictorCorrector,
    t_end: f64,
    steps: usize,
    omega1: f64,
    amplitude: f64,
) -> Result<f64> {
    let period_steps = (steps as f64 / CHECK_PERIODS).round().max(1.0) as usize;
    let mean_amplitude = |m: &PredictorCorrector, last: usize| -> Result<Option<f64>> {
        let options = Options {
            t_end,
            amplitude_periods: 0.0,
            ..Default::default()
        };
        match simulate(problem, m, &options) {
            Ok(tr) => {
                let n = tr.u.len();
                let from = n.saturating_sub(last);
                let sum: f64 = (from..n)
                    .map(|i| crate::maths::hypot(tr.u[i], tr.v[i] / omega1))
                    .sum();
                Ok(Some(sum / (n - from) as f64))
            }
            Err(Error::BlowUp { .. }) => Ok(None),
            Err(e) => Err(e),
        }
    };
    let fine_method = PredictorCorrector {
        dt: method.dt / 2.0,
        ..*method
    };
    let Some(fine) = mean_amplitude(&fine_method, 2 * period_steps)? else {
        return Ok(f64::INFINITY);
    };
    let Some(coarse) = mean_amplitude(method, period_steps)? else {
        return Ok(f64::INFINITY);
    };
    Ok((coarse - fine).abs() / amplitude.max(fine))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::preset;

    fn check(name: &str, dt: f64, amplitudes: &[f64]) -> Resolution {
        let problem = Problem::from_params(&preset(name).unwrap().params).unwrap();
        let method = PredictorCorrector {
            dt,
            ..Default::default()
        };
        Resolution::check(&problem, &method, amplitudes).unwrap()
    }

    #[test]
    fn default_step_passes_on_the_cycles() {
        for (name, amps) in [("fig13a", [7.49, 12.94]), ("fig13b", [8.73, 14.89])] {
            let r = check(name, 0.01, &amps);
            assert_eq!(r.halvings.len(), 2);
            assert!(r.refusal().is_none(), "{name}: {:?}", r.halvings);
            assert!(
                r.worst_deviation() < WARN_DEVIATION,
                "{name}: {:?}",
                r.halvings
            );
        }
    }

    #[test]
    fn the_check_is_noise_free_for_multiplicative_noise_too() {
        // U·η_m is noise: the check of a model with it is that of the model without it
        let model = crate::model::Model::from(&preset("fig13a").unwrap().params);
        let mut parametric = model.clone();
        parametric.noise.multiplicative = Some(crate::model::NoiseTerm {
            intensity: 0.05,
            correlation_time: 0.0,
        });
        let method = PredictorCorrector::default();
        let [with, without] = [&parametric, &model].map(|m| {
            let problem = Problem::from_model(m).unwrap();
            Resolution::check(&problem, &method, &[7.49]).unwrap()
        });
        assert_eq!(with.halvings, without.halvings);
    }

    #[test]
    fn a_step_of_one_is_refused_naming_dt() {
        let r = check("fig13a", 1.0, &[7.49]);
        let e = r.refusal().expect("refused");
        match e {
            Error::InvalidParameter { name, value, .. } => {
                assert_eq!(name, "dt");
                assert_eq!(value, 1.0);
            }
            e => panic!("{e}"),
        }
    }

    #[test]
    fn deviation_falls_with_the_step_at_the_method_order() {
        let a = check("fig1", 0.2, &[1.0]).worst_deviation();
        let b = check("fig1", 0.1, &[1.0]).worst_deviation();
        let order = (a / b).log2();
        assert!((1.5..=3.5).contains(&order), "{a} {b} order {order}");
    }

    #[test]
    fn a_very_fine_step_is_not_halved() {
        let r = check("fig13b", 1e-5, &[12.94]);
        assert!(r.halvings.is_empty() && r.refusal().is_none(), "{r:?}");
    }

    #[test]
    fn unresolved_correlation_time_warns() {
        let problem =
            Problem::from_params(&preset("fig13a").unwrap().params.with("tau", 0.025).unwrap())
                .unwrap();
        let method = PredictorCorrector::default();
        let r = Resolution::check(&problem, &method, &[7.49]).unwrap();
        assert_eq!(r.steps_per_tau, Some(2.5));
        let w = r.warnings();
        assert_eq!(w.len(), 1, "{w:?}");
        assert!(w[0].contains("correlation time"));
        let fine = PredictorCorrector {
            dt: 0.0025,
            ..Default::default()
        };
        assert!(Resolution::check(&problem, &fine, &[])
            .unwrap()
            .warnings()
            .is_empty());
    }
}
