//! Benchmarks of the lane stepper (criterion, short): the fig13a ensemble (8 paths of 2·10⁴
//! steps, OU noise D = 0.1, τ = 0.5, wall on) at λ = 0.998 and at λ = 1 with the paths
//! stepped one after the other (`Lanes::Width(1)`, the scalar stepper), 4 and 8 together, on
//! one thread; and the stepper alone (`run_lanes`, no statistics) for the same paths. The other
//! drivers, lanes 1 against 8 on one thread: the tangent-method Lyapunov exponent (8
//! realisations of Fig. 17(a)'s problem, 2·10⁴ steps each), the simulated oscillation boundary
//! on three abscissae of a Fig. 15 plane and `classify_plane` on one row of 8 of its points.
//!
//! Long runs, side by side in one process with CPU times and two threads, are in
//! `examples/lanes_timing.rs` and `examples/drivers_timing.rs` (the numbers in
//! docs/numerics.md, Speed).

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use std::time::Duration;
use trirhythm::analysis::ensemble::{run_ensemble, EnsembleSpec};
use trirhythm::analysis::lyapunov::{largest_lyapunov, LyapunovMethod, LyapunovSpec};
use trirhythm::analysis::oscillation::{
    boundary, classify_plane, Classifier, Method, Plane, Search,
};
use trirhythm::engine::{
    run_lanes, Barrier, Flow, ImpactMemory, Lanes, PredictorCorrector, Problem, Stepper,
};
use trirhythm::model::preset;
use trirhythm::monitor::Silent;

#[path = "../examples/support/mod.rs"]
mod support;
use support::fig13a_problem as problem;

const STEPS: u64 = 20_000;

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

fn one_thread() -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap()
}

fn tangent_lyapunov(c: &mut Criterion) {
    let pool = one_thread();
    let mut g = c.benchmark_group("lanes_tangent_lyapunov_8_paths_2e4_steps");
    g.sample_size(10).measurement_time(Duration::from_secs(3));
    let p = preset("fig17a")
        .unwrap()
        .params
        .with("mu0", 0.05)
        .and_then(|p| p.with("D", 0.1))
        .unwrap();
    let problem = Problem::from_params(&p).unwrap();
    let method = PredictorCorrector {
        dt: 0.005,
        impact_memory: ImpactMemory::Restart,
        ..Default::default()
    };
    for lanes in [1usize, 8] {
        let spec = LyapunovSpec {
            paths: 8,
            transient: 10.0,
            length: 90.0,
            method: LyapunovMethod::Tangent,
            lanes: Lanes::Width(lanes),
            ..Default::default()
        };
        g.bench_with_input(BenchmarkId::from_parameter(lanes), &lanes, |b, _| {
            b.iter(|| {
                pool.install(|| largest_lyapunov(&problem, &method, &spec, &Silent))
                    .unwrap()
            })
        });
    }
    g.finish();
}

fn oscillation(c: &mut Criterion) {
    let pool = one_thread();
    let mut g = c.benchmark_group("lanes_oscillation_fig15_plane");
    g.sample_size(10).measurement_time(Duration::from_secs(3));
    let base = preset("fig15").unwrap().params.with("omega0", 0.5).unwrap();
    let template = Problem::from_params(&base)
        .and_then(|q| q.with_barrier(Barrier::On))
        .unwrap();
    let plane = Plane::new(
        &template,
        ("lambda", vec![0.9, 0.95, 1.0]),
        ("mu0", 1e-4, 0.12),
    )
    .unwrap();
    let row = Plane {
        x: vec![0.95],
        ..plane.clone()
    };
    let ys: Vec<f64> = (1..=8).map(|k| 0.015 * k as f64).collect();
    let search = Search {
        tolerance: 1e-2,
        ..Default::default()
    };
    for lanes in [1usize, 8] {
        let m = Method::Simulation(Classifier {
            max_periods: 40.0,
            lanes: Lanes::Width(lanes),
            ..Default::default()
        });
        let id = BenchmarkId::new("boundary_3_points", lanes);
        g.bench_with_input(id, &lanes, |b, _| {
            b.iter(|| {
                pool.install(|| boundary(&plane, &m, &search, &Silent))
                    .unwrap()
            })
        });
        let id = BenchmarkId::new("classify_plane_8_points", lanes);
        g.bench_with_input(id, &lanes, |b, _| {
            b.iter(|| {
                pool.install(|| classify_plane(&row, &ys, &m, &Silent))
                    .unwrap()
            })
        });
    }
    g.finish();
}

criterion_group!(benches, ensemble, stepper, tangent_lyapunov, oscillation);
criterion_main!(benches);
