//! Benchmarks of the fractional engine (criterion, short: 10 samples).
//!
//! - one path of Eq. (1) with the SOE memory at λ = 0.998 against the same engine at λ = 1
//!   (no memory), 1e5 steps;
//! - SOE against Direct memory at 1e4, 3e4 and 1e5 steps (Direct is O(N²));
//! - the scalar known-answer problem (Diethelm's benchmark) with both memories;
//! - the General kernel (Duffing, Rayleigh, harmonic forcing) against the paper's kernel on the
//!   same path (fig1 with the wall, μ0 = 0.1), λ = 0.998 and 1, 1e5 steps;
//! - the default memory (`Memory::Auto`, tolerance 1e-5·Δt² = 1e-9 at Δt = 0.01) against the
//!   previous default (1e-10) side by side, on the noisy fig13a path (λ = 0.998 and 0.8, OU
//!   noise D = 0.1, τ = 0.5, wall on, U(0) = 7, seed 1), 1e5 and 1e6 steps.
//!
//! Long runs (1e6, 1e7 steps) are timed by `examples/engine_timing.rs`, not here.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use std::hint::black_box;
use std::time::Duration;
use trirhythm::engine::simulate;
use trirhythm::engine::{
    solve_scalar, Memory, Options, PredictorCorrector, Problem, PREVIOUS_DEFAULT_TOLERANCE,
};
use trirhythm::known_answers::{diethelm_rhs, engine_benchmark_case};
use trirhythm::model::{GeneralTerms, Harmonic};

fn path(lambda: f64, steps: usize, memory: Memory) -> f64 {
    let (osc, m, o) = engine_benchmark_case(lambda, steps, memory, steps).unwrap();
    simulate(&osc, &m, &o).unwrap().final_amplitude
}

fn soe_vs_lambda_one(c: &mut Criterion) {
    let mut g = c.benchmark_group("path_1e5_steps");
    g.sample_size(10).measurement_time(Duration::from_secs(3));
    for lambda in [0.998, 1.0] {
        g.bench_with_input(BenchmarkId::new("soe", lambda), &lambda, |b, &l| {
            b.iter(|| path(black_box(l), 100_000, Memory::default()))
        });
    }
    g.finish();
}

fn soe_vs_direct(c: &mut Criterion) {
    let mut g = c.benchmark_group("soe_vs_direct");
    g.sample_size(10).measurement_time(Duration::from_secs(3));
    for steps in [10_000usize, 30_000, 100_000] {
        g.bench_with_input(BenchmarkId::new("soe", steps), &steps, |b, &n| {
            b.iter(|| path(0.998, n, Memory::SumOfExponentials { tolerance: 1e-12 }))
        });
        g.bench_with_input(BenchmarkId::new("direct", steps), &steps, |b, &n| {
            b.iter(|| path(0.998, n, Memory::Direct))
        });
    }
    g.finish();
}

fn scalar(c: &mut Criterion) {
    let mut g = c.benchmark_group("diethelm_scalar_5000_steps");
    g.sample_size(10);
    let f = diethelm_rhs(0.5);
    for (name, memory) in [("soe", Memory::default()), ("direct", Memory::Direct)] {
        g.bench_function(name, |b| {
            b.iter(|| solve_scalar(0.5, &f, 0.0, 1.0 / 5000.0, 5000, memory).unwrap())
        });
    }
    g.finish();
}

/// The paper's kernel and the General one (k3 = 0.1, d1 = −0.001, F = 0.2 at Ω = 0.9) on the
/// benchmark case.
fn general_vs_paper(c: &mut Criterion) {
    let mut g = c.benchmark_group("general_kernel_1e5_steps");
    g.sample_size(10).measurement_time(Duration::from_secs(3));
    let terms = GeneralTerms {
        cubic: 0.1,
        quintic: 0.0,
        rayleigh: vec![-0.001],
        forcing: Some(Harmonic {
            amplitude: 0.2,
            frequency: 0.9,
            phase: 0.0,
        }),
        ..Default::default()
    };
    for lambda in [0.998, 1.0] {
        let (paper, m, o) =
            engine_benchmark_case(lambda, 100_000, Memory::default(), 100_000).unwrap();
        let general = paper.clone().with_terms(Some(terms.clone())).unwrap();
        for (name, problem) in [("paper", &paper), ("general", &general)] {
            g.bench_with_input(BenchmarkId::new(name, lambda), problem, |b, p| {
                b.iter(|| simulate(black_box(p), &m, &o).unwrap().final_amplitude)
            });
        }
    }
    g.finish();
}

/// The noisy fig13a path at order λ with `memory`, `steps` steps of 0.01: its final amplitude.
fn fig13a_path(lambda: f64, steps: usize, memory: Memory) -> f64 {
    let p = trirhythm::model::preset("fig13a")
        .unwrap()
        .params
        .with("lambda", lambda)
        .unwrap();
    let problem = Problem::from_params(&p)
        .and_then(|q| q.with_start(7.0, 0.0))
        .unwrap();
    let m = PredictorCorrector {
        dt: 0.01,
        memory,
        ..Default::default()
    };
    let o = Options {
        t_end: steps as f64 * 0.01,
        seed: 1,
        record_every: steps,
        ..Default::default()
    };
    simulate(&problem, &m, &o).unwrap().final_amplitude
}

/// The default memory against the previous default, one run.
fn default_memory(c: &mut Criterion) {
    let mut g = c.benchmark_group("default_memory");
    g.sample_size(10).measurement_time(Duration::from_secs(3));
    let previous = Memory::SumOfExponentials {
        tolerance: PREVIOUS_DEFAULT_TOLERANCE,
    };
    for steps in [100_000usize, 1_000_000] {
        for lambda in [0.998, 0.8] {
            for (name, memory) in [("tolerance_1e-10", previous), ("auto", Memory::Auto)] {
                let id = BenchmarkId::new(format!("{name}/lambda_{lambda}"), steps);
                g.bench_with_input(id, &steps, |b, &n| {
                    b.iter(|| fig13a_path(black_box(lambda), n, memory))
                });
            }
        }
    }
    g.finish();
}

criterion_group!(
    benches,
    soe_vs_lambda_one,
    soe_vs_direct,
    scalar,
    general_vs_paper,
    default_memory
);
criterion_main!(benches);
