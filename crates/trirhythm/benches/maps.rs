//! Throughput of map classification: the allocation-free kernel against
//! `Theory::new(..).stable_count_fast()` on the same points, one core; and a whole parallel map.

use criterion::{black_box, criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use std::time::Duration;
use trirhythm::model::preset;
use trirhythm::theory::averaging::{Theory, Variant};
use trirhythm::theory::bifurcation::{classify, Axis, Plane, What};

const SIDE: usize = 100;

fn plane(what: What) -> Plane {
    match what {
        What::Rhythmicity => Plane::new(
            &preset("fig2ii").unwrap().params,
            Axis::new("gamma0", 2e-5, 1e-4, SIDE).unwrap(),
            Axis::new("delta0", 2e-8, 4e-7, SIDE).unwrap(),
            Variant::Paper,
        )
        .unwrap(),
        What::Modes => Plane::new(
            &preset("fig10").unwrap().params.with("D", 0.3).unwrap(),
            Axis::new("lambda", 0.95, 1.0, SIDE).unwrap(),
            Axis::new("tau", 0.0, 5.0, SIDE).unwrap(),
            Variant::Paper,
        )
        .unwrap(),
    }
}

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("maps");
    g.sample_size(10)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(2));
    for what in [What::Rhythmicity, What::Modes] {
        let pl = plane(what);
        let n = SIDE * SIDE;
        g.throughput(Throughput::Elements(n as u64));
        // One core, the fast kernel.
        g.bench_function(BenchmarkId::new("fast_one_core", what.name()), |b| {
            b.iter(|| {
                let mut s = 0usize;
                for iy in 0..SIDE {
                    for ix in 0..SIDE {
                        let p = pl.point(pl.x.value(ix), pl.y.value(iy));
                        s += pl.kernel().stable_count(&p, what);
                    }
                }
                black_box(s)
            })
        });
        // One core, the general path (validated params, allocating Theory, Sturm count).
        let base = pl.base.clone();
        g.bench_function(BenchmarkId::new("theory_one_core", what.name()), |b| {
            b.iter(|| {
                let mut s = 0usize;
                let mut p = base.clone();
                for iy in 0..SIDE {
                    p.set(&pl.y.key, pl.y.value(iy)).unwrap();
                    for ix in 0..SIDE {
                        p.set(&pl.x.key, pl.x.value(ix)).unwrap();
                        s += Theory::new(&p, Variant::Paper).unwrap().stable_count_fast();
                    }
                }
                black_box(s)
            })
        });
        // The whole map on every core (rayon).
        g.bench_function(BenchmarkId::new("classify_parallel", what.name()), |b| {
            b.iter(|| black_box(classify(&pl, what, &|_, _| {}).counts.len()))
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
