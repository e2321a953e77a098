//! Hot paths of the averaged theory: building the problem, isolating every root, the
//! Sturm-only stable count, building a normalised PDF, evaluating it on a grid.

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use trirhythm::model::preset;
use trirhythm::theory::averaging::{Theory, Variant};

fn averaging(c: &mut Criterion) {
    let p = preset("fig4c").unwrap().params.with("r", 1.0).unwrap();
    let noisy = preset("fig13a").unwrap().params;
    let th = Theory::new(&p, Variant::Paper).unwrap();
    let thn = Theory::new(&noisy, Variant::Paper).unwrap();
    let pdf = thn.amplitude_pdf().unwrap();
    let mut g = c.benchmark_group("averaging");
    g.sample_size(20);
    g.bench_function("theory_new", |b| {
        b.iter(|| Theory::new(black_box(&p), Variant::Paper).unwrap())
    });
    g.bench_function(
        "limit_cycles (all roots, isolated to full precision)",
        |b| b.iter(|| black_box(&th).limit_cycles()),
    );
    g.bench_function("stable_count_fast (Sturm count only)", |b| {
        b.iter(|| black_box(&th).stable_count_fast())
    });
    g.bench_function("new + limit_cycles", |b| {
        b.iter(|| {
            Theory::new(black_box(&p), Variant::Paper)
                .unwrap()
                .limit_cycles()
        })
    });
    g.bench_function("amplitude_pdf (modes + log-space normalisation)", |b| {
        b.iter(|| black_box(&thn).amplitude_pdf().unwrap())
    });
    g.bench_function("pdf density on 1000 points", |b| {
        b.iter(|| {
            (0..1000)
                .map(|i| pdf.density(black_box(i as f64 * 0.015)))
                .sum::<f64>()
        })
    });
    g.finish();
}

criterion_group!(benches, averaging);
criterion_main!(benches);
