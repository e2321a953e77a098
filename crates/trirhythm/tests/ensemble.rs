//! Ensembles against known answers: the stationary variances of the linear fractional
//! oscillator under white and coloured noise (spectral integrals, closed form at λ = 1); the
//! exact escape time of the Rayleigh amplitude process; thread-count invariance; a resumed run
//! equals the uninterrupted one; pieces run in any split and order merge to the whole run;
//! a cancelled run stops at once; the diagnosis flags paths stuck in different wells.

use std::time::{Duration, Instant};
use trirhythm::analysis::ensemble::{
    merge, run_ensemble, run_paths, EnsembleResult, EnsembleSpec, PathStats, Wells,
};
use trirhythm::analysis::versus::escape_time;
use trirhythm::engine::{Barrier, PredictorCorrector, Problem};
use trirhythm::known_answers::{linear_fractional_moments, linear_fractional_oscillator};
use trirhythm::model::preset;
use trirhythm::monitor::{CancelFlag, Monitor, Silent};
use trirhythm::theory::averaging::{Theory, Variant};
use trirhythm::{Error, Result};

fn linear_run(lambda: f64, tau: f64) -> (trirhythm::analysis::EnsembleResult, (f64, f64)) {
    let (mu, w, d) = (0.5, 1.0, 0.1);
    let p = linear_fractional_oscillator(lambda, mu, w, d, tau);
    let problem = Problem::from_params(&p)
        .and_then(|q| q.with_barrier(Barrier::Off))
        .and_then(|q| q.with_start(0.0, 0.0))
        .unwrap();
    let method = PredictorCorrector::default();
    let spec = EnsembleSpec {
        paths: 8,
        seed: 11,
        burn_in: 100.0,
        length: 2000.0,
        amplitude_max: 3.0,
        ..Default::default()
    };
    let r = run_ensemble(&problem, &method, &spec, &Silent).unwrap();
    (r, linear_fractional_moments(lambda, mu, w, d, tau))
}

#[test]
fn linear_oscillator_variances_match_the_spectral_integrals() {
    for &(lambda, tau) in &[(1.0, 0.0), (1.0, 0.5), (0.9, 0.0), (0.9, 0.5)] {
        let (r, (vu, vv)) = linear_run(lambda, tau);
        let zu = (r.var_u.value - vu) / r.var_u.stderr;
        let zv = (r.var_v.value - vv) / r.var_v.stderr;
        let zm = r.mean_u.value / r.mean_u.stderr;
        println!(
            "λ = {lambda}, τ = {tau}: Var U {:.5} ± {:.5} (exact {vu:.5}, z = {zu:.2}); \
             Var U̇ {:.5} ± {:.5} (exact {vv:.5}, z = {zv:.2}); ⟨U⟩ z = {zm:.2}; R̂ {:.3}, ESS {:.0}",
            r.var_u.value,
            r.var_u.stderr,
            r.var_v.value,
            r.var_v.stderr,
            r.stationarity.r_hat,
            r.stationarity.ess
        );
        assert!(zu.abs() < 3.0, "Var U off by {zu:.2} standard errors");
        assert!(zm.abs() < 3.0, "⟨U⟩ off by {zm:.2} standard errors");
        // white noise at λ < 1: the step-mean forcing cuts the slowly converging Ω^{−2λ}
        // tail of Var U̇ at Ω ~ π/Δt (≈ 1 % here), so U̇ is checked with coloured noise or λ = 1
        if tau > 0.0 || lambda == 1.0 {
            assert!(zv.abs() < 3.0, "Var U̇ off by {zv:.2} standard errors");
        }
        assert!(
            r.var_u.stderr < 0.1 * vu,
            "too few samples to test anything"
        );
        assert!(r.stationarity.stationary, "{:?}", r.warnings);
    }
}

#[test]
fn escape_time_of_the_rayleigh_process_is_exact() {
    // P ≡ −1: f(A) = −κA and P(A) is Rayleigh; T(a → b < a) = ln(a/b)/κ,
    // T(a → b > a) = ∫_a^b (e^{κy²/σ1} − 1)/(κy) dy
    let p = linear_fractional_oscillator(1.0, 0.5, 1.0, 0.1, 0.0);
    let th = Theory::new(&p, Variant::Paper).unwrap();
    let kappa = -th.drift(1.0);
    let s1 = th.diffusion();
    let pdf = th.amplitude_pdf().unwrap();
    let down = escape_time(&pdf, s1, 1.0, 0.3);
    let exact_down = (1.0f64 / 0.3).ln() / kappa;
    assert!(
        (down / exact_down - 1.0).abs() < 1e-6,
        "{down} vs {exact_down}"
    );
    let (a, b) = (0.2, 1.5);
    let n = 20_000;
    let h = (b - a) / n as f64;
    let f = |y: f64| ((kappa * y * y / s1).exp() - 1.0) / (kappa * y);
    let simpson: f64 = (0..=n)
        .map(|i| {
            let w = if i == 0 || i == n {
                1.0
            } else if i % 2 == 1 {
                4.0
            } else {
                2.0
            };
            w * f(a + i as f64 * h)
        })
        .sum::<f64>()
        * h
        / 3.0;
    let up = escape_time(&pdf, s1, a, b);
    assert!((up / simpson - 1.0).abs() < 1e-6, "{up} vs {simpson}");
}

fn fig13a_spec(paths: usize, length: f64) -> (Problem, PredictorCorrector, EnsembleSpec) {
    let p = preset("fig13a").unwrap().params;
    let th = Theory::new(&p, Variant::Paper).unwrap();
    let pdf = th.amplitude_pdf().unwrap();
    let spec = EnsembleSpec {
        paths,
        seed: 5,
        burn_in: 10.0,
        length,
        amplitude_max: 16.0,
        wells: Some(Wells::new(pdf.modes.clone(), pdf.antimodes.clone()).unwrap()),
        ..Default::default()
    };
    let starts: Vec<(f64, f64)> = pdf.modes.iter().map(|&a| (a, 0.0)).collect();
    let problem = Problem::from_params(&p)
        .and_then(|q| q.with_starts(&starts))
        .unwrap();
    (problem, PredictorCorrector::default(), spec)
}

#[test]
fn results_do_not_depend_on_threads_and_a_resumed_run_equals_the_whole() {
    let (osc, m, spec) = fig13a_spec(5, 100.0);
    let run = |threads: usize, done: &[PathStats]| {
        let saved = Saved::default();
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let todo: Vec<u64> = (0..spec.paths as u64)
            .filter(|i| !done.iter().any(|d| d.path == *i))
            .collect();
        let r = pool
            .install(|| {
                let fresh = run_paths(&osc, &m, &spec, &todo, &saved)?;
                merge(&osc, &m, &spec, done.iter().cloned().chain(fresh).collect())
            })
            .unwrap();
        (r, saved.0.into_inner().unwrap())
    };
    // compared as printed: NaN (a passage never completed) is not equal to itself
    let same = |a: &trirhythm::analysis::EnsembleResult,
                b: &trirhythm::analysis::EnsembleResult| {
        format!("{a:?}") == format!("{b:?}")
    };
    let (one, saved) = run(1, &[]);
    let (two, _) = run(2, &[]);
    assert!(same(&one, &two));
    // "interrupted" after paths 0, 2 and 3: their saved statistics go through JSON and back
    let kept: Vec<PathStats> = saved
        .into_iter()
        .filter(|p| [0, 2, 3].contains(&p.path))
        .map(|p| serde_json::from_str(&serde_json::to_string(&p).unwrap()).unwrap())
        .collect();
    let (resumed, fresh) = run(2, &kept);
    assert_eq!(fresh.len(), 2);
    assert!(same(&one, &resumed));
}

#[test]
fn paths_stuck_in_different_wells_are_not_called_stationary() {
    // fig13a's wells are separated by barriers far above σ1: over 200 time units no path
    // leaves the well it started in, so the occupancies differ between paths
    let (osc, m, spec) = fig13a_spec(6, 200.0);
    let r = run_ensemble(&osc, &m, &spec, &Silent).unwrap();
    println!("{:?}\n{:?}", r.stationarity, r.warnings);
    assert!(!r.stationarity.stationary);
    assert!(r.stationarity.r_hat > 1.1);
    assert!(r.warnings.iter().any(|w| w.starts_with("not stationary")));
    assert_eq!(r.occupancy.len(), 3);
    let total: f64 = r.occupancy.iter().map(|o| o.value).sum();
    assert!((total - 1.0).abs() < 1e-12);
}

#[test]
fn well_probabilities_sum_to_one_however_narrow_the_peaks() {
    // μ0 = 1000 makes peaks ~1e-3 wide inside wells several units wide: the quadrature must
    // still find them (it once returned 0.5)
    for mu0 in [0.005, 0.2, 1.0, 1000.0] {
        let p = preset("fig13a").unwrap().params.with("mu0", mu0).unwrap();
        for v in [Variant::Paper, Variant::Consistent] {
            let pdf = Theory::new(&p, v).unwrap().amplitude_pdf().unwrap();
            let w = Wells::new(pdf.modes.clone(), pdf.antimodes.clone()).unwrap();
            let total: f64 = trirhythm::analysis::versus::well_probabilities(&pdf, &w)
                .iter()
                .sum();
            assert!((total - 1.0).abs() < 1e-9, "μ0 = {mu0}, {v:?}: {total}");
        }
    }
}

/// A monitor that keeps every finished path (a checkpoint in memory).
#[derive(Default)]
struct Saved(std::sync::Mutex<Vec<PathStats>>);

impl Monitor<PathStats> for Saved {
    fn finished(&self, p: &PathStats) -> Result<()> {
        self.0.lock().unwrap().push(p.clone());
        Ok(())
    }
}

/// The result as serialised JSON: equal results print the same (NaN included).
fn json(r: &EnsembleResult) -> String {
    serde_json::to_string(r).unwrap()
}

#[test]
fn pieces_in_any_split_and_order_merge_to_the_whole_run() {
    let (problem, m, spec) = fig13a_spec(6, 20.0);
    let whole = run_ensemble(&problem, &m, &spec, &Silent).unwrap();
    // {0, 3}, {5, 1}, {2, 4}, run separately and handed over shuffled
    let mut pieces: Vec<PathStats> = Vec::new();
    for piece in [[5u64, 1], [0, 3], [2, 4]] {
        let mut stats = run_paths(&problem, &m, &spec, &piece, &Silent).unwrap();
        stats.reverse();
        pieces.splice(0..0, stats);
    }
    let merged = merge(&problem, &m, &spec, pieces.clone()).unwrap();
    assert_eq!(json(&merged), json(&whole));
    assert_eq!(format!("{merged:?}"), format!("{whole:?}"));
    // a duplicate, a missing path and a foreign path are refused, naming the path
    let named = |r: Result<EnsembleResult>, path: f64| match r {
        Err(Error::InvalidParameter { name, value, .. }) => {
            assert_eq!((name.as_str(), value), ("paths", path))
        }
        other => panic!("expected an error naming path {path}: {other:?}"),
    };
    let mut twice = pieces.clone();
    twice.push(pieces[2].clone());
    named(merge(&problem, &m, &spec, twice), pieces[2].path as f64);
    let missing: Vec<PathStats> = pieces.iter().filter(|p| p.path != 3).cloned().collect();
    named(merge(&problem, &m, &spec, missing), 3.0);
    let mut foreign = pieces.clone();
    foreign.iter_mut().find(|p| p.path == 4).unwrap().path = 9;
    named(merge(&problem, &m, &spec, foreign), 9.0);
    let other_spec = EnsembleSpec {
        bins: 50,
        ..spec.clone()
    };
    assert!(merge(&problem, &m, &other_spec, pieces).is_err());
    // and run_paths refuses indices out of range or asked twice
    assert!(run_paths(&problem, &m, &spec, &[6], &Silent).is_err());
    assert!(run_paths(&problem, &m, &spec, &[1, 1], &Silent).is_err());
}

#[test]
fn a_cancelled_ensemble_stops_at_once() {
    // 4 paths of 10⁷ steps each: minutes of work, stopped within a few ticks
    let (problem, m, spec) = fig13a_spec(4, 100_000.0);
    let flag = CancelFlag::default();
    flag.cancel();
    let start = Instant::now();
    let r = run_ensemble(&problem, &m, &spec, &flag);
    assert!(matches!(r, Err(Error::Cancelled)), "{r:?}");
    assert!(start.elapsed() < Duration::from_secs(1));
    // cancelled from another thread while it runs
    let flag = CancelFlag::default();
    let start = Instant::now();
    let r = std::thread::scope(|s| {
        s.spawn(|| {
            std::thread::sleep(Duration::from_millis(200));
            flag.cancel();
        });
        run_ensemble(&problem, &m, &spec, &flag)
    });
    assert!(matches!(r, Err(Error::Cancelled)), "{r:?}");
    assert!(
        start.elapsed() < Duration::from_secs(20),
        "{:?}",
        start.elapsed()
    );
}
