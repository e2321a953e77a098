//! Benchmarks of the ensemble driver (criterion, short): the fig13a set, 8 paths of 2·10⁴
//! steps each with every statistic streamed, on one thread and on two (the speed-up of the
//! parallel paths), and the theory's comparison (distances, bootstrap, escape times).
//!
//! `examples/ensemble_scaling.rs` prints the one-against-two-threads ratio and the memory
//! against the number of steps side by side in one run.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use std::time::Duration;
use trirhythm::analysis::ensemble::{run_ensemble, EnsembleResult, EnsembleSpec, Wells};
use trirhythm::analysis::versus::compare;
use trirhythm::engine::{PredictorCorrector, Problem};
use trirhythm::model::preset;
use trirhythm::monitor::Silent;
use trirhythm::theory::averaging::{Theory, Variant};

fn case() -> (Problem, EnsembleSpec, Theory) {
    let p = preset("fig13a").unwrap().params;
    let th = Theory::new(&p, Variant::Paper).unwrap();
    let pdf = th.amplitude_pdf().unwrap();
    let spec = EnsembleSpec {
        paths: 8,
        burn_in: 0.0,
        length: 200.0,
        amplitude_max: 16.0,
        wells: Some(Wells::new(pdf.modes.clone(), pdf.antimodes.clone()).unwrap()),
        ..Default::default()
    };
    let starts: Vec<(f64, f64)> = pdf.modes.iter().map(|&a| (a, 0.0)).collect();
    let problem = Problem::from_params(&p)
        .and_then(|q| q.with_starts(&starts))
        .unwrap();
    (problem, spec, th)
}

fn ensemble(problem: &Problem, spec: &EnsembleSpec) -> EnsembleResult {
    run_ensemble(problem, &PredictorCorrector::default(), spec, &Silent).unwrap()
}

fn threads(c: &mut Criterion) {
    let (osc, spec, _) = case();
    let mut g = c.benchmark_group("ensemble_8_paths_2e4_steps");
    g.sample_size(10).measurement_time(Duration::from_secs(3));
    for n in [1usize, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build()
            .unwrap();
        g.bench_with_input(BenchmarkId::new("threads", n), &n, |b, _| {
            b.iter(|| pool.install(|| ensemble(&osc, &spec)))
        });
    }
    g.finish();
}

fn versus(c: &mut Criterion) {
    let (osc, spec, th) = case();
    let r = ensemble(&osc, &spec);
    let mut g = c.benchmark_group("theory_against_ensemble");
    g.sample_size(10);
    g.bench_function("compare", |b| b.iter(|| compare(&r, &th, 1).unwrap()));
    g.finish();
}

criterion_group!(benches, threads, versus);
criterion_main!(benches);
