//! Benchmarks of the lane stepper (criterion, short): the fig13a ensemble (8 paths of 2·10⁴
//! steps, OU noise D = 0.1, τ = 0.5, wall on) at λ = 0.998 and at λ = 1 with the paths
//! stepped one after the other (`Lanes::Width(1)`, the scalar stepper), 4 and 8 together, on
//! one thread; and the stepper alone (`run_lanes`, no statistics) for the same paths.
//!
//! Long runs, side by side in one process with CPU times and two threads, are in
//! `examples/lanes_timing.rs` (the numbers in docs/numerics.md, Speed).

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use std::time::Duration;
use trirhythm::analysis::ensemble::{run_ensemble, EnsembleSpec};
use trirhythm::engine::{run_lanes, Flow, Lanes, PredictorCorrector, Problem, Stepper};
use trirhythm::model::preset;
use trirhythm::monitor::Silent;

const STEPS: u64 = 20_000;

fn problem(lambda: f64) -> Problem {
    let p = preset("fig13a")
        .unwrap()
        .params
        .with("lambda", lambda)
        .unwrap();
    Problem::from_params(&p)
        .and_then(|q| q.with_starts(&[(2.9, 0.0), (7.4, 0.0), (12.9, 0.0)]))
        .unwrap()
}

fn ensemble(c: &mut Criterion) {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let mut g = c.benchmark_group("lanes_ensemble_8_paths_2e4_steps");
    g.sample_size(10).measurement_time(Duration::from_secs(3));
    for lambda in [0.998, 1.0] {
        let problem = problem(lambda);
        for lanes in [1usize, 4, 8] {
            let spec = EnsembleSpec {
                paths: 8,
                burn_in: 0.0,
                length: STEPS as f64 * 0.01,
                amplitude_max: 16.0,
                lanes: Lanes::Width(lanes),
                ..Default::default()
            };
            let id = BenchmarkId::new(format!("lambda_{lambda}"), lanes);
            g.bench_with_input(id, &lanes, |b, _| {
                b.iter(|| {
                    pool.install(|| {
                        run_ensemble(&problem, &PredictorCorrector::default(), &spec, &Silent)
                    })
                    .unwrap()
                })
            });
        }
    }
    g.finish();
}

fn stepper(c: &mut Criterion) {
    let mut g = c.benchmark_group("lanes_stepper_8_paths_2e4_steps");
    g.sample_size(10).measurement_time(Duration::from_secs(3));
    let method = PredictorCorrector::default();
    for lambda in [0.998, 1.0] {
        let problem = problem(lambda);
        let fresh: Vec<Stepper> = (0..8)
            .map(|i| Stepper::new(&problem, &method, (1, i), STEPS as f64 * 0.01).unwrap())
            .collect();
        for lanes in [1usize, 4, 8] {
            let id = BenchmarkId::new(format!("lambda_{lambda}"), lanes);
            g.bench_with_input(id, &lanes, |b, &w| {
                b.iter(|| {
                    let mut paths = fresh.clone();
                    let mut obs: Vec<_> = (0..8).map(|_| |_: &Stepper| Flow::Continue).collect();
                    run_lanes(&mut paths, STEPS, &mut obs, Lanes::Width(w), &Silent).unwrap();
                    paths[0].u()
                })
            });
        }
    }
    g.finish();
}

criterion_group!(benches, ensemble, stepper);
criterion_main!(benches);
