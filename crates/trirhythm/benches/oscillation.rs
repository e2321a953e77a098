//! One oscillation boundary point by simulation (secant bracketing and plain bisection), and
//! classifying a column of the plane, one simulation per point: the cost per boundary point
//! against a full grid at the same resolution.

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use std::time::Duration;
use trirhythm::analysis::oscillation::{
    boundary, classify_plane, Classifier, Method, Plane, Refinement, Search,
};
use trirhythm::engine::{Barrier, Problem};
use trirhythm::model::Params;
use trirhythm::monitor::Silent;

/// ω0 = 0.5, λ = 0.95, r = 0.99 with the wall: the fractional case without an exact answer.
fn problem() -> Plane {
    let p = Params {
        omega0: 0.5,
        lambda: 0.95,
        restitution: 0.99,
        ..Default::default()
    };
    let template = Problem::from_params(&p)
        .and_then(|q| q.with_barrier(Barrier::On))
        .unwrap();
    Plane::new(&template, ("omega0", vec![0.5]), ("mu0", 1e-3, 0.3)).unwrap()
}

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("oscillation");
    g.sample_size(10)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(3));
    let pr = problem();
    let method = Method::Simulation(Classifier::default());
    for (name, refinement) in [
        ("secant", Refinement::Secant),
        ("bisection", Refinement::Bisection),
    ] {
        let search = Search {
            refinement,
            ..Default::default()
        };
        g.bench_function(format!("boundary point, {name}"), |b| {
            b.iter(|| black_box(boundary(&pr, &method, &search, &Silent).unwrap()))
        });
    }
    // a column of 64 points across [1e-3, 0.3]: the per-point cost of a full grid
    let ys: Vec<f64> = (0..64)
        .map(|i| 1e-3 + (0.3 - 1e-3) * i as f64 / 63.0)
        .collect();
    g.bench_function("grid column, 64 points", |b| {
        b.iter(|| black_box(classify_plane(&pr, &ys, &method, &Silent).unwrap()))
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
