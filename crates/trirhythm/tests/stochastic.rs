//! Noise inside the driver: white-noise variance, determinism across thread counts.

use trirhythm::engine::Memory;
use trirhythm::engine::*;
use trirhythm::model::{preset, Damping, Params};

const RNG_SEED: u64 = 20_240_003;

fn free(d: f64, tau: f64) -> Params {
    Params {
        mu0: 1.0,
        omega0: 1.0,
        lambda: 1.0,
        restitution: 1.0,
        damping: Damping {
            coefficients: vec![0.0],
        },
        noise_intensity: d,
        correlation_time: tau,
    }
}

/// Ü + U = η from rest: E[U̇² + U²](T) = 2DT for white noise ⟨ηη⟩ = 2Dδ (Itô: d E/dt = 2D).
/// [`free`] without the wall, from rest.
fn free_problem(d: f64, tau: f64) -> Problem {
    Problem::from_params(&free(d, tau))
        .and_then(|q| q.with_barrier(Barrier::Off))
        .and_then(|q| q.with_start(0.0, 0.0))
        .unwrap()
}

#[test]
fn white_noise_energy_grows_as_2dt() {
    let d = 0.2;
    let problem = free_problem(d, 0.0);
    let m = PredictorCorrector {
        dt: 0.01,
        memory: Memory::Direct,
        ..Default::default()
    };
    let t_end = 2.0;
    let o = Options {
        t_end,
        seed: RNG_SEED,
        record_every: 200,
        ..Default::default()
    };
    let paths = 4000;
    let runs = simulate_ensemble(&problem, &m, &o, paths).unwrap();
    let energies: Vec<f64> = runs
        .iter()
        .map(|r| r.u.last().unwrap().powi(2) + r.v.last().unwrap().powi(2))
        .collect();
    let mean = energies.iter().sum::<f64>() / paths as f64;
    let var = energies.iter().map(|e| (e - mean).powi(2)).sum::<f64>() / (paths - 1) as f64;
    let se = (var / paths as f64).sqrt();
    let expect = 2.0 * d * t_end;
    assert!(
        (mean - expect).abs() < 4.0 * se,
        "E = {mean} ± {se}, expected {expect}"
    );
    // the wrong scheme (linear interpolation of node samples) would give 2/3 of it
    assert!((mean - 2.0 / 3.0 * expect).abs() > 10.0 * se);
}

/// OU forcing with τ ≪ Δt acts as white noise of the same D (the step integrals are exact),
/// and with τ ≪ 1/ω it forces the unit oscillator as the spectrum 2D/(1+τ²ω²) says.
#[test]
fn colored_noise_tends_to_white_noise() {
    let d = 0.2;
    let t_end = 2.0;
    let o = Options {
        t_end,
        seed: RNG_SEED,
        record_every: 400,
        ..Default::default()
    };
    let m = PredictorCorrector {
        dt: 0.005,
        ..Default::default()
    };
    let paths = 4000;
    let white = 2.0 * d * t_end;
    for &tau in &[0.0005, 0.05] {
        let runs = simulate_ensemble(&free_problem(d, tau), &m, &o, paths).unwrap();
        let e: Vec<f64> = runs
            .iter()
            .map(|r| r.u.last().unwrap().powi(2) + r.v.last().unwrap().powi(2))
            .collect();
        let mean = e.iter().sum::<f64>() / paths as f64;
        let se =
            (e.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (paths as f64).powi(2)).sqrt();
        // energy input rate of OU forcing started stationary: 2D/(1+τ²) at ω = 1, less a
        // start-up deficit of order τ/T
        let expect = white / (1.0 + tau * tau) * (1.0 - tau / t_end);
        assert!(
            (mean - expect).abs() < 4.0 * se,
            "τ = {tau}: {mean} vs {expect} ± {se}"
        );
    }
}

#[test]
fn paths_are_bit_identical_whatever_the_thread_count() {
    let mut p = preset("fig17a").unwrap().params; // D > 0, τ > 0, impacts
    p.noise_intensity = 0.3;
    let problem = Problem::from_params(&p)
        .and_then(|q| q.with_start(0.5, 0.0))
        .unwrap();
    let m = PredictorCorrector::default();
    let o = Options {
        t_end: 20.0,
        seed: RNG_SEED,
        ..Default::default()
    };
    let run = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| simulate_ensemble(&problem, &m, &o, 8).unwrap())
    };
    let one = run(1);
    let two = run(2);
    assert_eq!(one, two);
    assert!(one.iter().map(|t| t.impacts).sum::<usize>() > 0);
    assert_ne!(one[0].u, one[1].u, "paths must differ");
    // path i alone equals path i of the ensemble
    let alone = simulate(&problem, &m, &Options { path: 5, ..o }).unwrap();
    assert_eq!(alone, one[5]);
}
