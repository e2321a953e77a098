//! Path-steps per second of an ensemble, side by side in one run: the CPU engine on all the
//! machine's cores, the kernel's CPU emulation on all of them, and the GPU (kernel time and end
//! to end, where a device is present; the reason printed where not), at λ = 0.998 and λ = 1.
//!
//! The case: Fig. 13(a)'s oscillator (μ0 = 0.005, r = 0.99, D = 0.1, τ = 0.5) with the wall,
//! Δt = 0.01, starts on its two cycles, every statistic recorded every 10 steps on small
//! histograms (so that the statistics of millions of paths fit the engine's bound).
//!
//! `cargo bench -p trirhythm-gpu --bench throughput` measures 10⁵ paths on the CPU and 10⁵,
//! 10⁶ and 4·10⁶ on the GPU (near the most whose statistics the engine's bound of 4 GB holds:
//! 832 bytes a path here; 10⁷ exceed one ensemble's bound); `TR_BENCH_PATHS` (CPU paths),
//! `TR_BENCH_GPU_PATHS` (a comma-separated list) and `TR_BENCH_STEPS` change the sizes.
//! `-- --test` (CI's smoke run) takes 64 paths of 200 steps.

use std::time::Instant;
use trirhythm::analysis::ensemble::{run_ensemble, EnsembleSpec};
use trirhythm::engine::{PredictorCorrector, Problem};
use trirhythm::model::preset;
use trirhythm::monitor::Silent;

fn case(lambda: f64, paths: usize, steps: u64) -> (Problem, PredictorCorrector, EnsembleSpec) {
    let p = preset("fig13a")
        .unwrap()
        .params
        .with("lambda", lambda)
        .unwrap();
    let problem = Problem::from_params(&p)
        .and_then(|q| q.with_starts(&[(2.0, 0.0), (6.5, 0.0)]))
        .unwrap();
    let method = PredictorCorrector {
        dt: 0.01,
        ..Default::default()
    };
    let spec = EnsembleSpec {
        paths,
        seed: 1,
        burn_in: 0.0,
        length: steps as f64 * method.dt,
        sample_every: 10,
        batches: 4,
        bins: 4,
        joint_bins: 2,
        amplitude_max: 10.0,
        ..Default::default()
    };
    (problem, method, spec)
}

fn env_or(name: &str, default: &str) -> String {
    std::env::var(name).unwrap_or_else(|_| default.to_string())
}

fn rate(paths: usize, steps: u64, seconds: f64) -> f64 {
    paths as f64 * steps as f64 / seconds
}

fn main() {
    let smoke = std::env::args().any(|a| a == "--test");
    let steps: u64 = if smoke {
        200
    } else {
        env_or("TR_BENCH_STEPS", "2000").parse().unwrap()
    };
    let cpu_paths: usize = if smoke {
        64
    } else {
        env_or("TR_BENCH_PATHS", "100000").parse().unwrap()
    };
    let gpu_paths: Vec<usize> = if smoke {
        vec![64]
    } else {
        env_or("TR_BENCH_GPU_PATHS", "100000,1000000,4000000")
            .split(',')
            .map(|s| s.trim().parse().unwrap())
            .collect()
    };
    let threads = rayon::current_num_threads();
    println!("throughput: {steps} steps per path, {threads} CPU threads");
    for lambda in [0.998, 1.0] {
        let (problem, method, spec) = case(lambda, cpu_paths, steps);
        let t = Instant::now();
        let cpu = run_ensemble(&problem, &method, &spec, &Silent).unwrap();
        let cpu_s = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let emulated = trirhythm_gpu::emulate_ensemble(&problem, &method, &spec).unwrap();
        let emu_s = t.elapsed().as_secs_f64();
        assert_eq!(cpu, emulated, "the emulation is the engine bit for bit");
        let cpu_rate = rate(cpu_paths, steps, cpu_s);
        println!(
            "λ = {lambda}: CPU engine {cpu_paths} paths {:.3e} path-steps/s ({:.1} ns per \
             path-step per thread); emulation {:.3e} ({:.2}× the engine)",
            cpu_rate,
            1e9 * threads as f64 / cpu_rate,
            rate(cpu_paths, steps, emu_s),
            cpu_s / emu_s
        );
        gpu(lambda, steps, &gpu_paths, cpu_rate);
    }
}

#[cfg(feature = "cuda")]
fn gpu(lambda: f64, steps: u64, sizes: &[usize], cpu_rate: f64) {
    if let Err(e) = trirhythm_gpu::cuda::device() {
        println!("  GPU: skipped ({e})");
        return;
    }
    for &n in sizes {
        let (problem, method, spec) = case(lambda, n, steps);
        match trirhythm_gpu::gpu_paths(&problem, &method, &spec, &Silent) {
            Ok(run) => {
                let kernel = rate(n, steps, run.kernel_seconds);
                println!(
                    "  GPU ({}) {n} paths: kernel {:.3e} path-steps/s ({:.0}× the CPU engine), \
                     end to end {:.3e} (compile {:.2} s, total {:.2} s)",
                    run.device,
                    kernel,
                    kernel / cpu_rate,
                    rate(n, steps, run.total_seconds),
                    run.compile_seconds,
                    run.total_seconds
                );
            }
            Err(e) => println!("  GPU {n} paths: {e}"),
        }
    }
}

#[cfg(not(feature = "cuda"))]
fn gpu(_: f64, _: u64, _: &[usize], _: f64) {
    println!("  GPU: skipped (built without the `cuda` feature)");
}
