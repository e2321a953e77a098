//! The largest Lyapunov exponent against a plain path of the same length (the target:
//! ≤ 2×), by two trajectories (the copy being a second path) and by the tangent method (a
//! second memory, no second noise stream), side by side in one run; and 8 realisations of
//! T = 2000 on one thread against two (≥ 1.8× on 2 cores). Fig. 17(a)'s parameters (λ = 0.995,
//! wall, coloured noise).

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use std::time::Duration;
use trirhythm::analysis::lyapunov::{largest_lyapunov, LyapunovMethod, LyapunovSpec};
use trirhythm::engine::{simulate, Options, PredictorCorrector, Problem};
use trirhythm::model::preset;
use trirhythm::monitor::Silent;

const T: f64 = 200.0;

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("lyapunov");
    g.sample_size(10)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(3));
    let osc =
        Problem::from_params(&preset("fig17a").unwrap().params.with("D", 0.5).unwrap()).unwrap();
    let method = PredictorCorrector::default();
    let options = Options {
        t_end: T,
        seed: 1,
        record_every: usize::MAX,
        ..Default::default()
    };
    g.bench_function("plain path, T = 200", |b| {
        b.iter(|| black_box(simulate(&osc, &method, &options).unwrap()))
    });
    let one = LyapunovSpec {
        paths: 1,
        transient: 0.0,
        length: T,
        ..Default::default()
    };
    g.bench_function("LLE, one realisation, T = 200", |b| {
        b.iter(|| black_box(largest_lyapunov(&osc, &method, &one, &Silent).unwrap()))
    });
    let tangent = LyapunovSpec {
        method: LyapunovMethod::Tangent,
        ..one.clone()
    };
    g.bench_function("LLE by the tangent, one realisation, T = 200", |b| {
        b.iter(|| black_box(largest_lyapunov(&osc, &method, &tangent, &Silent).unwrap()))
    });
    // long enough that the serial part (the verified SOE kernel, built once) is small
    let eight = LyapunovSpec {
        paths: 8,
        length: 10.0 * T,
        ..one.clone()
    };
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        g.bench_function(
            format!("LLE, 8 realisations, T = 2000, {threads} thread(s)"),
            |b| {
                b.iter(|| {
                    pool.install(|| {
                        black_box(largest_lyapunov(&osc, &method, &eight, &Silent).unwrap())
                    })
                })
            },
        );
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
