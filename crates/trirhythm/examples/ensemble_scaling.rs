//! Side by side in one run: an ensemble (fig13a set, 8 paths, λ = 0.998, OU noise, wall on,
//! Δt = 0.01) on one thread and on two, alternated three times; the results must be identical.
//!
//! `cargo run --release -p trirhythm --example ensemble_scaling [steps per path]`

use std::time::Instant;
use trirhythm::analysis::ensemble::{run_ensemble, EnsembleSpec};
use trirhythm::engine::{PredictorCorrector, Problem};
use trirhythm::model::preset;
use trirhythm::monitor::Silent;

fn main() {
    let steps: f64 = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(1e6);
    let p = preset("fig13a").unwrap().params;
    let osc = Problem::from_params(&p)
        .and_then(|q| q.with_starts(&[(2.9, 0.0), (7.4, 0.0), (12.9, 0.0)]))
        .unwrap();
    let m = PredictorCorrector::default();
    let spec = |t: f64| EnsembleSpec {
        paths: 8,
        burn_in: 0.0,
        length: t,
        amplitude_max: 16.0,
        ..Default::default()
    };
    let time = |threads: usize, t: f64| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let start = Instant::now();
        let r = pool
            .install(|| run_ensemble(&osc, &m, &spec(t), &Silent))
            .unwrap();
        (start.elapsed().as_secs_f64(), r)
    };
    let t = steps * 0.01;
    let mut ratios = Vec::new();
    for round in 0..3 {
        let (one, a) = time(1, t);
        let (two, b) = time(2, t);
        assert_eq!(
            format!("{a:?}"),
            format!("{b:?}"),
            "thread count changed the result"
        );
        let total = 8.0 * steps;
        println!(
            "round {round}: 1 thread {one:.2} s ({:.2e} steps/s), 2 threads {two:.2} s \
             ({:.2e} steps/s): speed-up {:.2}×",
            total / one,
            total / two,
            one / two
        );
        ratios.push(one / two);
    }
    ratios.sort_by(f64::total_cmp);
    println!("speed-up on 2 threads: {:.2}–{:.2}×", ratios[0], ratios[2]);
}
