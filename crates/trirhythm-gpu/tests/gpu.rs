//! The GPU backend on a device (each test prints why it skips where there is none): the
//! kernel's statistics against the CPU engine's — per path bit for bit where no transcendental
//! function rounds differently (counted and printed), and every moment and density bin within
//! three combined standard errors on Fig. 13(a), on a General-kernel model with every term and
//! on the linear oscillator's known variances — and its reproducibility run to run.

use trirhythm::analysis::ensemble::{
    merge, run_paths, Density, EnsembleResult, EnsembleSpec, Estimate, PathStats,
};
use trirhythm::engine::{Barrier, PredictorCorrector, Problem};
use trirhythm::known_answers::{linear_fractional_moments, linear_fractional_oscillator};
use trirhythm::model::{
    preset, Fractional, Harmonic, Keep, Model, NoiseTerm, Restitution, SpeedRestitution, Wall,
};
use trirhythm::monitor::Silent;
use trirhythm_gpu::{run_ensemble as run_on, Backend};

/// Whether a GPU is here; prints the reason where not.
fn gpu() -> bool {
    match trirhythm_gpu::cuda::device() {
        Ok(d) => {
            println!("GPU: {}", d.name);
            true
        }
        Err(e) => {
            let required = std::env::var("TRIRHYTHM_REQUIRE_GPU").is_ok_and(|v| v == "1");
            assert!(!required, "TRIRHYTHM_REQUIRE_GPU=1 but {e}");
            println!("skipped: {e}");
            false
        }
    }
}

/// |a − b| ≤ 3 combined standard errors (or both exactly equal).
fn close(what: &str, a: &Estimate, b: &Estimate) {
    let tol = 3.0 * (a.stderr * a.stderr + b.stderr * b.stderr).sqrt();
    assert!(
        a.value == b.value || (a.value - b.value).abs() <= tol,
        "{what}: {} ± {} against {} ± {}",
        a.value,
        a.stderr,
        b.value,
        b.stderr
    );
}

fn densities(what: &str, a: &Density, b: &Density) {
    for (k, ((x, sx), (y, sy))) in a
        .density
        .iter()
        .zip(&a.stderr)
        .zip(b.density.iter().zip(&b.stderr))
        .enumerate()
    {
        let tol = 3.0 * (sx * sx + sy * sy).sqrt();
        assert!(
            x == y || (x - y).abs() <= tol,
            "{what} bin {k}: {x} ± {sx} against {y} ± {sy}"
        );
    }
}

fn statistically_equal(cpu: &EnsembleResult, gpu: &EnsembleResult) {
    close("mean U", &cpu.mean_u, &gpu.mean_u);
    close("Var U", &cpu.var_u, &gpu.var_u);
    close("mean U̇", &cpu.mean_v, &gpu.mean_v);
    close("Var U̇", &cpu.var_v, &gpu.var_v);
    close("mean A", &cpu.mean_amplitude, &gpu.mean_amplitude);
    densities("P(A)", &cpu.amplitude, &gpu.amplitude);
    densities("P(H)", &cpu.energy, &gpu.energy);
    densities("turning", &cpu.turning, &gpu.turning);
}

/// The ensemble on the GPU against the CPU engine's: reproducible run to run, statistically
/// equal (every moment and density bin within three combined standard errors), and the paths
/// identical bit for bit counted and printed; returns the GPU's paths.
fn against_the_cpu(
    what: &str,
    problem: &Problem,
    method: &PredictorCorrector,
    spec: &EnsembleSpec,
) -> Vec<PathStats> {
    let all: Vec<u64> = (0..spec.paths as u64).collect();
    let cpu_paths = run_paths(problem, method, spec, &all, &Silent).unwrap();
    let gpu_paths = trirhythm_gpu::gpu_paths(problem, method, spec, &Silent)
        .unwrap()
        .stats;
    let identical = cpu_paths
        .iter()
        .zip(&gpu_paths)
        .filter(|(a, b)| a == b)
        .count();
    println!(
        "{what}: paths identical to the CPU's bit for bit: {identical} of {}",
        spec.paths
    );
    let gpu = merge(problem, method, spec, gpu_paths.clone()).unwrap();
    let again = run_on(problem, method, spec, &Silent, Backend::Gpu).unwrap();
    assert_eq!(
        gpu, again,
        "{what}: the GPU's results are reproducible run to run"
    );
    let cpu = merge(problem, method, spec, cpu_paths).unwrap();
    statistically_equal(&cpu, &gpu);
    gpu_paths
}

#[test]
fn fig13a_on_the_gpu_is_the_cpus() {
    if !gpu() {
        return;
    }
    let p = preset("fig13a").unwrap().params;
    let problem = Problem::from_params(&p)
        .unwrap()
        .with_starts(&[(1.0, 0.0), (6.8, 0.0)])
        .unwrap();
    let method = PredictorCorrector {
        dt: 0.01,
        ..Default::default()
    };
    let spec = EnsembleSpec {
        paths: 256,
        seed: 13,
        burn_in: 100.0,
        length: 400.0,
        sample_every: 10,
        amplitude_max: 10.0,
        ..Default::default()
    };
    against_the_cpu("Fig. 13(a)", &problem, &method, &spec);
}

/// The General kernel (`kernel/general.h`) on the device: Fig. 13(a)'s oscillator with a
/// Duffing term, a Rayleigh term, a harmonic forcing, a fractional term (α = 0.5),
/// multiplicative noise and two walls (one with a speed-dependent restitution).
#[test]
fn the_general_kernel_on_the_gpu_is_the_cpus() {
    if !gpu() {
        return;
    }
    let mut m = Model::from(&preset("fig13a").unwrap().params.with("D", 0.3).unwrap());
    m.restoring.cubic = 0.3;
    m.damping.rayleigh = vec![-0.02];
    m.forcing = Some(Harmonic {
        amplitude: 0.4,
        frequency: 1.3,
        phase: 0.2,
    });
    m.fractional = vec![Fractional {
        coefficient: 0.2,
        order: 0.5,
    }];
    m.noise.multiplicative = Some(NoiseTerm {
        intensity: 0.05,
        correlation_time: m.noise.additive.unwrap().correlation_time,
    });
    m.noise.correlation = 0.3;
    m.walls = vec![
        Wall {
            position: -0.6,
            keep: Keep::Above,
            restitution: Restitution::Constant(0.7),
        },
        Wall {
            position: 0.9,
            keep: Keep::Below,
            restitution: Restitution::Speed(SpeedRestitution {
                r0: 0.9,
                r_fast: 0.4,
                speed: 0.8,
            }),
        },
    ];
    m.start.u0 = 0.2;
    m.start.v0 = 0.0;
    let problem = Problem::from_model(&m)
        .unwrap()
        .with_starts(&[(0.2, 0.0), (-0.5, 1.0)])
        .unwrap();
    let method = PredictorCorrector {
        dt: 0.01,
        ..Default::default()
    };
    let spec = EnsembleSpec {
        paths: 256,
        seed: 17,
        burn_in: 50.0,
        length: 300.0,
        sample_every: 10,
        amplitude_max: 1.0,
        ..Default::default()
    };
    let gpu_paths = against_the_cpu("General kernel", &problem, &method, &spec);
    let impacts: u64 = gpu_paths.iter().map(|p| p.impacts).sum();
    println!("General kernel: {impacts} impacts on the GPU");
    assert!(impacts > 0);
}

#[test]
fn the_linear_oscillators_variances_on_the_gpu() {
    if !gpu() {
        return;
    }
    let (mu, w, d, tau) = (0.5, 1.0, 0.1, 0.5);
    for lambda in [0.998, 1.0] {
        let p = linear_fractional_oscillator(lambda, mu, w, d, tau);
        let problem = Problem::from_params(&p)
            .and_then(|q| q.with_barrier(Barrier::Off))
            .and_then(|q| q.with_start(0.0, 0.0))
            .unwrap();
        let method = PredictorCorrector::default();
        let spec = EnsembleSpec {
            // the CPU engine's known-answer test's sizes (trirhythm's tests/ensemble.rs)
            paths: 8,
            seed: 11,
            burn_in: 100.0,
            length: 2000.0,
            amplitude_max: 3.0,
            ..Default::default()
        };
        let gpu = run_on(&problem, &method, &spec, &Silent, Backend::Gpu).unwrap();
        let (var_u, var_v) = linear_fractional_moments(lambda, mu, w, d, tau);
        for (what, e, exact) in [("Var U", gpu.var_u, var_u), ("Var U̇", gpu.var_v, var_v)] {
            assert!(
                (e.value - exact).abs() <= 3.0 * e.stderr,
                "λ = {lambda}, {what}: {} ± {} against {exact}",
                e.value,
                e.stderr
            );
        }
    }
}
