//! One configuration of the fig13a paths for a profiler or an instruction counter: the
//! ensemble (`run_ensemble`, statistics at every step) or the stepper alone (`run_lanes`, an
//! observer that keeps nothing), 8 paths, OU noise D = 0.1, τ = 0.5, wall on, Δt = 0.01.
//! Instructions per path-step: the difference of two runs' counts (e.g. 10⁵ and 2·10⁵ steps
//! under `valgrind --tool=callgrind`) over 8 × the difference of their steps, so that the set-up
//! cancels.
//!
//! `cargo run --release -p trirhythm --example lanes_profile -- lambda lanes ensemble|stepper steps`

use std::collections::hash_map::DefaultHasher;
use std::hash::{Hash, Hasher};
use trirhythm::analysis::ensemble::{run_ensemble, EnsembleSpec};
use trirhythm::engine::{run_lanes, Flow, Lanes, PredictorCorrector, Stepper};
use trirhythm::monitor::Silent;

#[path = "support/mod.rs"]
mod support;
use support::fig13a_problem;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let usage = "lanes_profile lambda lanes ensemble|stepper steps";
    let lambda: f64 = args.get(1).and_then(|s| s.parse().ok()).expect(usage);
    let lanes: usize = args.get(2).and_then(|s| s.parse().ok()).expect(usage);
    let what = args.get(3).expect(usage).as_str();
    let steps: f64 = args.get(4).and_then(|s| s.parse().ok()).expect(usage);
    let paths = 8usize;
    let problem = fig13a_problem(lambda);
    let method = PredictorCorrector::default();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    match what {
        "ensemble" => {
            let spec = EnsembleSpec {
                paths,
                burn_in: 0.0,
                length: steps * 0.01,
                amplitude_max: 16.0,
                lanes: Lanes::Width(lanes),
                ..Default::default()
            };
            let r = pool
                .install(|| run_ensemble(&problem, &method, &spec, &Silent))
                .unwrap();
            // the whole result, hashed: equal hashes for equal bits (f64's Debug is exact)
            let mut hash = DefaultHasher::new();
            format!("{r:?}").hash(&mut hash);
            println!(
                "mean amplitude {}; result hash {:016x}",
                r.mean_amplitude.value,
                hash.finish()
            );
        }
        "stepper" => {
            let mut steppers: Vec<Stepper> = (0..paths as u64)
                .map(|i| Stepper::new(&problem, &method, (1, i), steps * 0.01).unwrap())
                .collect();
            let mut observers: Vec<_> = (0..paths).map(|_| |_: &Stepper| Flow::Continue).collect();
            run_lanes(
                &mut steppers,
                steps as u64,
                &mut observers,
                Lanes::Width(lanes),
                &Silent,
            )
            .unwrap();
            let ends: Vec<(f64, f64, u64)> = steppers
                .iter()
                .map(|s| (s.u(), s.v(), s.impacts()))
                .collect();
            println!("ends {ends:?}; {} exponentials", steppers[0].exponentials());
        }
        _ => panic!("{usage}"),
    }
}
