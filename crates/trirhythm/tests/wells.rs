//! The well decomposition's known answers.
//!
//! - The averaged amplitude diffusion dA = m1 dt + √σ1 dW (the theory's own m1 = f + σ1/(2A)
//!   and σ1, simulated as the radius of the planar process dX = (f(R)/R)X dt + √σ1 dW, whose
//!   radius obeys exactly that equation): the splitting's rates out of the outer wells against
//!   the exact mean first-passage times of the diffusion between the cores
//!   ([`escape_time`]), within three standard errors over the replicas, and within the
//!   Euler–Maruyama step's bias (5 %). The default test spans two and a half decades of rate;
//!   the extended one (ignored) more than seven.
//! - The oscillator itself (`#[ignore]`, extended): on a panel where direct paths mix, the
//!   well method and the direct ensemble agree in the well occupancies and the amplitude
//!   density within their errors.

use rand_chacha::ChaCha8Rng;
use trirhythm::analysis::ensemble::splitting::{
    replica_rates, Cores, Observation, Splitting, Walker,
};
use trirhythm::analysis::ensemble::Wells;
use trirhythm::analysis::versus::{escape_time, theory_layout};
use trirhythm::engine::noise::path_rng;
use trirhythm::maths::standard_normal;
use trirhythm::model::preset;
use trirhythm::monitor::Silent;
use trirhythm::theory::averaging::{Theory, Variant};
use trirhythm::theory::polynomial::Polynomial;
use trirhythm::Result;

/// The planar process whose radius is the averaged amplitude diffusion; observed every step.
#[derive(Clone)]
struct Amplitude {
    x: f64,
    y: f64,
    dt: f64,
    noise: f64,
    g: Polynomial,
    rng: ChaCha8Rng,
}

impl Walker for Amplitude {
    fn advance(&mut self) -> Result<Observation> {
        // f(A)/A = g(A²)
        let k = self.g.eval(self.x * self.x + self.y * self.y) * self.dt;
        let (n1, n2) = (
            standard_normal(&mut self.rng),
            standard_normal(&mut self.rng),
        );
        self.x += k * self.x + self.noise * n1;
        self.y += k * self.y + self.noise * n2;
        Ok(Observation::every_step(
            (self.x * self.x + self.y * self.y).sqrt(),
        ))
    }

    fn renoise(&mut self, seed: u64, stream: u64) {
        self.rng = path_rng(seed, stream);
    }
}

/// (measured residence time, its standard error, exact) for the lowest and the highest well.
fn residences(preset_name: &str, r: f64, d: f64, replicas: u64) -> Vec<(f64, f64, f64)> {
    let p = preset(preset_name)
        .unwrap()
        .params
        .with("r", r)
        .unwrap()
        .with("D", d)
        .unwrap();
    let th = Theory::new(&p, Variant::Paper).unwrap();
    let pdf = th.amplitude_pdf().unwrap();
    let s1 = th.diffusion();
    let wells: Wells = theory_layout(&p, Variant::Paper).unwrap().wells.unwrap();
    let n = wells.len();
    assert!(n >= 2);
    let dt = 0.05;
    let sp = Splitting {
        seed: 3,
        dt,
        clones: 400,
        burn: 2000,
        window: 1_000_000,
        max_excursion: 10_000_000,
        max_iterations: 1_000_000,
    };
    let walkers: Vec<Amplitude> = wells
        .modes
        .iter()
        .map(|&m| Amplitude {
            x: m,
            y: 0.0,
            dt,
            noise: (s1 * dt).sqrt(),
            g: th.drift_polynomial().clone(),
            rng: path_rng(0, 0),
        })
        .collect();
    let cores = Cores::of_wells(&wells);
    let runs: Vec<_> = std::thread::scope(|s| {
        let hs: Vec<_> = (0..replicas)
            .map(|rep| {
                let (w, cores) = (walkers.clone(), &cores);
                s.spawn(move || replica_rates(w, cores, &sp, rep, &Silent).unwrap())
            })
            .collect();
        hs.into_iter().map(|h| h.join().unwrap()).collect()
    });
    // transitions 0 → 1 (first) and n−1 → n−2 (last)
    let last = 2 * (n - 1) - 1;
    let stat = |k: usize| {
        let ks: Vec<f64> = runs.iter().map(|(_, t)| t[k].rate).collect();
        for (_, t) in &runs {
            assert!(t[k].complete, "{:?}", t[k]);
        }
        let m = ks.iter().sum::<f64>() / ks.len() as f64;
        let sd = (ks.iter().map(|x| (x - m) * (x - m)).sum::<f64>() / (ks.len() as f64 - 1.0))
            .sqrt()
            / (ks.len() as f64).sqrt();
        // residence 1/k with the delta-method standard error
        (1.0 / m, sd / (m * m))
    };
    let (t0, e0) = stat(0);
    let (tn, en) = stat(last);
    let x0 = escape_time(&pdf, s1, wells.core(0).1, wells.core(1).0);
    let xn = escape_time(&pdf, s1, wells.core(n - 1).0, wells.core(n - 2).1);
    vec![(t0, e0, x0), (tn, en, xn)]
}

fn check(cases: &[(&str, f64, f64)], replicas: u64) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
    for &(name, r, d) in cases {
        for (t, e, x) in residences(name, r, d, replicas) {
            println!(
                "{name} r = {r} D = {d}: residence {t:.4e} ± {e:.2e}, exact {x:.4e}, ratio {:.3}",
                t / x
            );
            let allowed = 3.0 * e + 0.05 * x;
            assert!(
                (t - x).abs() < allowed,
                "{name} r = {r} D = {d}: {t:e} ± {e:e} against the exact {x:e}"
            );
            assert!(e < 0.3 * t, "standard error {e:e} of {t:e}");
            lo = lo.min(x);
            hi = hi.max(x);
        }
    }
    (lo, hi)
}

#[test]
fn rates_of_the_averaged_diffusion_are_its_exact_escape_times() {
    let (lo, hi) = check(&[("fig13a", 0.97, 0.3)], 6);
    assert!(hi / lo > 10.0, "{lo} {hi}");
}

#[test]
#[ignore = "extended: seven decades of rate (about 10 s)"]
fn rates_of_the_averaged_diffusion_over_seven_decades() {
    let (lo, hi) = check(
        &[
            ("fig13a", 0.97, 0.3),
            ("fig13a", 0.97, 0.2),
            ("fig13a", 0.97, 0.1),
            ("fig13a", 0.96, 0.1),
        ],
        8,
    );
    assert!(hi / lo > 1e6, "{lo} {hi}");
}

/// Fig. 13(a)'s μ0 = 0.005 at r = 0.99 and D = 0.2: two wells whose escape times (about 10⁴)
/// let direct paths of 1.5·10⁵ mix. The well method's occupancies, mean amplitude and density
/// agree with the direct ensemble's within their errors.
#[test]
#[ignore = "extended: a direct ensemble of 1.2e8 steps beside the well method (about 20 s)"]
fn the_well_method_agrees_with_a_direct_ensemble_that_mixes() {
    use trirhythm::analysis::ensemble::{run_ensemble, run_wells, EnsembleSpec, WellsSpec};
    use trirhythm::engine::{ImpactMemory, PredictorCorrector, Problem};
    let p = preset("fig13a")
        .unwrap()
        .params
        .with("r", 0.99)
        .unwrap()
        .with("D", 0.2)
        .unwrap();
    let layout = theory_layout(&p, Variant::Paper).unwrap();
    let spec = EnsembleSpec {
        paths: 8,
        seed: 1,
        burn_in: 200.0,
        length: 4000.0,
        bins: 60,
        joint_bins: 8,
        amplitude_max: layout.amplitude_max,
        wells: layout.wells.clone(),
        ..Default::default()
    };
    let method = PredictorCorrector {
        impact_memory: ImpactMemory::Restart,
        ..Default::default()
    };
    let problem = Problem::from_params(&p).unwrap();
    let wspec = WellsSpec {
        clones: 200,
        ..Default::default()
    };
    let w = run_wells(&problem, &method, &spec, &wspec, &Silent).unwrap();
    assert!(w.wells.valid, "{:?}", w.wells.refusals);
    let starts: Vec<(f64, f64)> = layout.starts.iter().map(|&u| (u, 0.0)).collect();
    let direct_spec = EnsembleSpec {
        length: 150_000.0,
        ..spec.clone()
    };
    let d = run_ensemble(
        &problem.with_starts(&starts).unwrap(),
        &method,
        &direct_spec,
        &Silent,
    )
    .unwrap();
    assert!(d.stationarity.stationary, "{:?}", d.stationarity);
    let z = |a: (f64, f64), b: (f64, f64)| (a.0 - b.0) / (a.1 * a.1 + b.1 * b.1).sqrt();
    for (k, (x, y)) in w.result.occupancy.iter().zip(&d.occupancy).enumerate() {
        let zk = z((x.value, x.stderr), (y.value, y.stderr));
        println!("occupancy {k}: wells {x:?}, direct {y:?}, z = {zk:.2}");
        assert!(zk.abs() < 3.0);
        assert!(x.value > 0.1 && x.value < 0.9, "both wells matter: {x:?}");
    }
    let (x, y) = (w.result.mean_amplitude, d.mean_amplitude);
    let za = z((x.value, x.stderr), (y.value, y.stderr));
    println!("mean A: wells {x:?}, direct {y:?}, z = {za:.2}");
    assert!(za.abs() < 3.0);
    // each bin within Bonferroni's bound over the 60 bins at a family level of 1 %: both
    // standard errors come from 8 replicas, so a bin's difference over its standard error is
    // Student's t with ν ≈ 14 (Welch–Satterthwaite for equal counts), and the bound is
    // t_{1 − 0.01/120}(14) = 5.08. (It read 4, the normal quantile's: under t(14) some bin
    // of 60 exceeds 4 in about one run of ten; the second corrector pass on every step drew
    // 4.25, family p ≈ 0.05.)
    let worst = (0..d.amplitude.density.len())
        .map(|b| {
            let s = (w.result.amplitude.stderr[b].powi(2) + d.amplitude.stderr[b].powi(2)).sqrt();
            let diff = (w.result.amplitude.density[b] - d.amplitude.density[b]).abs();
            if s > 0.0 {
                diff / s
            } else {
                assert!(diff == 0.0, "bin {b}: {diff} without an error");
                0.0
            }
        })
        .fold(0.0f64, f64::max);
    println!("largest bin difference: {worst:.2} standard errors");
    assert!(worst < 5.08);
}

#[test]
fn the_well_method_refuses_what_it_cannot_do() {
    use trirhythm::analysis::ensemble::{run_wells, EnsembleSpec, WellsSpec};
    use trirhythm::engine::{PredictorCorrector, Problem};
    let p = preset("fig13a").unwrap().params;
    let problem = Problem::from_params(&p).unwrap();
    let method = PredictorCorrector::default();
    let spec = EnsembleSpec {
        paths: 4,
        length: 10.0,
        ..Default::default()
    };
    let e = run_wells(&problem, &method, &spec, &WellsSpec::default(), &Silent)
        .unwrap_err()
        .to_string();
    assert!(e.contains("no wells"), "{e}");
    let spec = EnsembleSpec {
        paths: 1,
        wells: Some(Wells::new(vec![2.0, 12.0], vec![8.0]).unwrap()),
        ..spec
    };
    let e = run_wells(&problem, &method, &spec, &WellsSpec::default(), &Silent)
        .unwrap_err()
        .to_string();
    assert!(e.contains("paths = 1") && e.contains("2 or more"), "{e}");
    let spec = EnsembleSpec { paths: 2, ..spec };
    let bad = WellsSpec {
        clones: 1,
        ..Default::default()
    };
    let e = run_wells(&problem, &method, &spec, &bad, &Silent)
        .unwrap_err()
        .to_string();
    assert!(e.contains("clones = 1"), "{e}");
}

/// A short run of the oscillator's well method is reproducible to the bit and its weights
/// are a probability vector.
#[test]
fn the_well_method_is_reproducible() {
    use trirhythm::analysis::ensemble::{run_wells, EnsembleSpec, WellsSpec};
    use trirhythm::engine::{PredictorCorrector, Problem};
    let p = preset("fig13a")
        .unwrap()
        .params
        .with("r", 0.99)
        .unwrap()
        .with("D", 0.2)
        .unwrap();
    let layout = theory_layout(&p, Variant::Paper).unwrap();
    let spec = EnsembleSpec {
        paths: 2,
        burn_in: 20.0,
        length: 300.0,
        bins: 20,
        joint_bins: 4,
        batches: 4,
        amplitude_max: layout.amplitude_max,
        wells: layout.wells,
        ..Default::default()
    };
    let problem = Problem::from_params(&p).unwrap();
    let method = PredictorCorrector::default();
    let wspec = WellsSpec {
        clones: 8,
        ..Default::default()
    };
    let a = run_wells(&problem, &method, &spec, &wspec, &Silent).unwrap();
    let b = run_wells(&problem, &method, &spec, &wspec, &Silent).unwrap();
    // (NaN fields compare unequal: compare the documents)
    assert_eq!(
        serde_json::to_string(&a).unwrap(),
        serde_json::to_string(&b).unwrap()
    );
    let total: f64 = a.wells.weights.iter().map(|w| w.value).sum();
    assert!(total.is_nan() || (total - 1.0).abs() < 1e-12, "{total}");
    assert_eq!(a.wells.replicas.len(), 2);
    assert_eq!(a.wells.rates.len(), 2);
}

/// Fig. 11(b) at λ = 0.998: the outer cycle's rate toward the inner well is far below the
/// inner well's rate outward. Stopped after one level (an iteration limit of 1), the splitting
/// resolves neither rate: both are only bounded and the weights are undetermined, said so
/// instead of calling either well absorbing; with the energy-amplitude score and the default
/// limits, the bound on the rate inward is decades below the rate outward and the
/// decomposition accepts the outer cycle's weight ≈ 1. (The unit tests of `wells.rs` check
/// when a bound moves the weights.)
#[test]
fn a_rate_below_resolution_is_bounded_and_refused_where_it_matters() {
    use trirhythm::analysis::ensemble::{run_wells, EnsembleSpec, WellsSpec};
    use trirhythm::engine::{ImpactMemory, PredictorCorrector, Problem};
    let p = preset("fig11")
        .unwrap()
        .params
        .with("lambda", 0.998)
        .unwrap();
    let layout = theory_layout(&p, Variant::Paper).unwrap();
    let spec = EnsembleSpec {
        paths: 2,
        burn_in: 100.0,
        length: 1500.0,
        bins: 20,
        joint_bins: 4,
        amplitude_max: layout.amplitude_max,
        wells: layout.wells,
        ..Default::default()
    };
    let method = PredictorCorrector {
        impact_memory: ImpactMemory::Restart,
        ..Default::default()
    };
    let problem = Problem::from_params(&p).unwrap();
    let run = |max_iterations: usize| {
        let wspec = WellsSpec {
            clones: 20,
            max_iterations,
            ..Default::default()
        };
        run_wells(&problem, &method, &spec, &wspec, &Silent).unwrap()
    };
    let w = run(1);
    let k = &w.wells.rates;
    assert!(k.iter().all(|r| r.rate.value == 0.0), "{k:?}");
    assert!(!w.wells.valid);
    assert!(
        w.wells
            .refusals
            .iter()
            .any(|r| r.contains("weights are undetermined")),
        "{:?}",
        w.wells.refusals
    );
    assert!(
        w.wells.notes.iter().all(|r| r.contains("iteration limit")),
        "{:?}",
        w.wells.notes
    );
    assert!(!w.result.stationarity.stationary);
    // the conditional statistics stand exactly when every refusal is about rates and weights
    let about_weights = |r: &String| {
        r.contains("weights are undetermined")
            || r.contains("could move the weights")
            || r.contains("exits toward")
    };
    assert_eq!(
        w.wells.conditional_valid,
        w.wells.refusals.iter().all(about_weights),
        "{:?}",
        w.wells.refusals
    );
    // the halves' counts are the window's counts split in two: they add up, replica by
    // replica and well by well, and each half has samples
    let halves = &w.wells.conditional_counts_halves;
    assert_eq!(halves.len(), 2);
    for (r, wells) in w.wells.conditional_counts.iter().enumerate() {
        for (i, counts) in wells.iter().enumerate() {
            let (a, b) = (&halves[0][r][i], &halves[1][r][i]);
            let sum: Vec<u64> = a.iter().zip(b).map(|(x, y)| x + y).collect();
            assert_eq!(&sum, counts, "replica {r}, well {i}");
            assert!(a.iter().sum::<u64>() > 0 && b.iter().sum::<u64>() > 0);
        }
    }
    // drifting only where every refusal is about the weights or a well's drift, and never
    // together with valid conditional statistics
    assert!(!(w.wells.conditional_valid && w.wells.conditional_drifting));
    // H over every weighting of the wells: brackets every mixture of the pooled conditional
    // counts, its ends each well alone or better
    let theory = Theory::new(&p, Variant::Paper).unwrap();
    let b = trirhythm::analysis::versus::wells_bounds(&w, &theory).unwrap();
    let pdf = theory.amplitude_pdf().unwrap();
    let q = trirhythm::analysis::versus::binned(&pdf, &w.result.amplitude.edges);
    let pooled: Vec<Vec<f64>> = (0..2)
        .map(|i| {
            let mut c = vec![0.0; q.len()];
            for r in &w.wells.conditional_counts {
                for (x, y) in c.iter_mut().zip(&r[i]) {
                    *x += *y as f64;
                }
            }
            let t: f64 = c.iter().sum();
            c.into_iter().map(|x| x / t).collect()
        })
        .collect();
    for f in [0.0, 0.1, 0.5, 0.9, 1.0] {
        let h = trirhythm::analysis::ensemble::hellinger_of_mixture(&q, &pooled, &[f, 1.0 - f]);
        assert!(
            h >= b.h_min.value - 1e-9 && h <= b.h_max.value + 1e-12,
            "{h} {b:?}"
        );
    }
    assert!((b.h_max.value - b.per_well[0].max(b.per_well[1])).abs() < 1e-12);
    assert!(b.h_min.stderr.is_finite() && b.h_max.stderr.is_finite());
    let w = run(WellsSpec::default().max_iterations);
    let k = &w.wells.rates;
    println!("{k:?}\n{:?}\n{:?}", w.wells.notes, w.wells.weights);
    assert!(w.wells.valid, "{:?}", w.wells.refusals);
    assert!(k[0].rate.value > 0.0, "{k:?}");
    assert_eq!(k[1].rate.value, 0.0, "{k:?}");
    assert!(w.wells.weights[1].value > 0.99, "{:?}", w.wells.weights);
    assert!(w.result.stationarity.stationary);
}
