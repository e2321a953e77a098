//! The step guard of [`crate::engine::resolution`] at the amplitudes a run will visit.
//!
//! # Problem and method
//! [`Resolution::check`] needs the amplitudes at which to halve the step; the engine does not
//! know the theory, so this layer names them: the amplitude √(U0² + U̇0²/ω1²) of every start of
//! the problem, and every limit cycle of the noise-free averaged theory in both variants (the
//! paper's and the consistent one), where the paths spend their time.
//!
//! # Tests
//! Unit tests below: the amplitudes include the starts and the cycles; Fig. 13(a) at Δt = 1 is
//! refused.

use crate::engine::{PredictorCorrector, Problem, Resolution};
use crate::error::Result;
use crate::theory::averaging::{Theory, Variant};

/// The amplitudes a run of `problem` visits: its starts and the noise-free theory's cycles.
pub fn expected_amplitudes(problem: &Problem) -> Vec<f64> {
    let omega1 = problem.oscillator().equivalents().omega1;
    let mut out: Vec<f64> = problem
        .starts()
        .iter()
        .map(|&(u, v)| crate::maths::hypot(u, v / omega1))
        .collect();
    if let Ok(quiet) = problem.params().with("D", 0.0) {
        for variant in [Variant::Paper, Variant::Consistent] {
            if let Ok(theory) = Theory::new(&quiet, variant) {
                out.extend(theory.limit_cycles().iter().map(|c| c.amplitude));
            }
        }
    }
    out
}

/// [`Resolution::check`] at [`expected_amplitudes`]: how well `method.dt` resolves `problem`.
pub fn check_step(problem: &Problem, method: &PredictorCorrector) -> Result<Resolution> {
    Resolution::check(problem, method, &expected_amplitudes(problem))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::preset;

    #[test]
    fn amplitudes_are_the_starts_and_the_cycles() {
        let p = preset("fig13a").unwrap().params;
        let problem = Problem::from_params(&p)
            .unwrap()
            .with_start(2.0, 0.0)
            .unwrap();
        let a = expected_amplitudes(&problem);
        assert_eq!(a[0], 2.0);
        let cycles = Theory::new(&p.with("D", 0.0).unwrap(), Variant::Paper)
            .unwrap()
            .limit_cycles();
        assert!(cycles.len() >= 3);
        for c in cycles {
            assert!(a.contains(&c.amplitude));
        }
    }

    #[test]
    fn a_unit_step_on_fig13a_is_refused_and_the_default_passes() {
        let problem = Problem::from_params(&preset("fig13a").unwrap().params).unwrap();
        let coarse = PredictorCorrector {
            dt: 1.0,
            ..Default::default()
        };
        assert!(check_step(&problem, &coarse).unwrap().refusal().is_some());
        let r = check_step(&problem, &PredictorCorrector::default()).unwrap();
        assert!(r.refusal().is_none() && r.warnings().is_empty(), "{r:?}");
        assert!(r.halvings.len() >= 4, "{r:?}");
    }
}
