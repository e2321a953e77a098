//! The attractor of a noise-free start (`analysis::lyapunov::classify_start`) on the Lyapunov
//! figures' parameters.
//!
//! - Fig. 17(a) (μ0 = 0.001, 0.01, 0.05, 0.1; Δt = 0.01 at μ0 ≤ 0.01, 0.0025 above, where the
//!   stepper's stiff step is still being corrected): the start at each stable amplitude of the
//!   averaged theory ends on the cycle of the same rank; the outer one within 2 % of the
//!   theory's amplitude (the inner ones differ more: 0.87 against 1.23 at μ0 = 0.01).
//! - U(0) = 1 ends at rest where the theory's rest state is stable (μ0 = 0.001) and on the
//!   inner cycle where it is not (μ0 ≥ 0.01): the start is named by its attractor.
//! - Fig. 18(b) at r = 0.8, 0.9, 0.95 (no cycle in the theory): every start ends at rest, one
//!   start per attractor is a single rest start.

use trirhythm::analysis::lyapunov::{attractor_starts, classify_start, Attractor, AttractorSpec};
use trirhythm::engine::{ImpactMemory, PredictorCorrector, Problem};
use trirhythm::model::preset;
use trirhythm::theory::averaging::{Theory, Variant};

fn method(dt: f64) -> PredictorCorrector {
    PredictorCorrector {
        dt,
        impact_memory: ImpactMemory::Restart,
        ..Default::default()
    }
}

#[test]
fn fig17a_starts_end_on_the_cycles_of_their_rank() {
    let spec = AttractorSpec::default();
    for (mu0, dt) in [(0.001, 0.01), (0.01, 0.01), (0.05, 0.0025), (0.1, 0.0025)] {
        let params = preset("fig17a").unwrap().params.with("mu0", mu0).unwrap();
        let problem = Problem::from_params(&params).unwrap();
        let theory = Theory::new(&params.with("D", 0.0).unwrap(), Variant::Paper).unwrap();
        let stable: Vec<f64> = theory
            .limit_cycles()
            .iter()
            .filter(|c| c.stable)
            .map(|c| c.amplitude)
            .collect();
        for (rank, &a0) in stable.iter().enumerate() {
            let s = classify_start(&problem, &method(dt), a0, &spec).unwrap();
            let Attractor::Cycle {
                amplitude, index, ..
            } = s.attractor
            else {
                panic!("μ0 = {mu0}, U(0) = {a0}: {s:?}");
            };
            assert_eq!(index, Some(rank), "μ0 = {mu0}: {s:?}");
            if rank + 1 == stable.len() {
                assert_eq!(s.attractor.label(), "outer");
                assert!((amplitude - a0).abs() < 0.02 * a0, "μ0 = {mu0}: {s:?}");
            }
        }
        let from_one = classify_start(&problem, &method(dt), 1.0, &spec).unwrap();
        let expected = if theory.rest_state_slope() < 0.0 {
            "rest"
        } else {
            "inner"
        };
        assert_eq!(
            from_one.attractor.label(),
            expected,
            "μ0 = {mu0}: {from_one:?}"
        );
    }
}

#[test]
fn one_start_per_attractor() {
    // μ0 = 0.01: rest unstable, three cycles; μ0 = 0.001: rest and the outer cycle
    let params = preset("fig17a").unwrap().params;
    for (mu0, labels) in [
        (0.01, vec!["inner", "middle", "outer"]),
        (0.001, vec!["rest", "outer"]),
    ] {
        let problem = Problem::from_params(&params.with("mu0", mu0).unwrap()).unwrap();
        let starts = attractor_starts(&problem, &method(0.01), &AttractorSpec::default()).unwrap();
        let found: Vec<&str> = starts.iter().map(|s| s.attractor.label()).collect();
        assert_eq!(found, labels, "μ0 = {mu0}: {starts:?}");
    }
    for r in [0.8, 0.9, 0.95] {
        let params = preset("fig18b").unwrap().params.with("r", r).unwrap();
        let problem = Problem::from_params(&params).unwrap();
        let starts = attractor_starts(&problem, &method(0.01), &AttractorSpec::default()).unwrap();
        assert_eq!(starts.len(), 1, "r = {r}: {starts:?}");
        assert_eq!(starts[0].attractor, Attractor::Rest);
    }
}
