//! The measurement behind the default size of the sum-of-exponentials memory (`Memory::Auto`,
//! module docs of `engine::memory`, Memory size):
//! `cargo run --release -p trirhythm --example memory_size [-- T DT LAMBDAS REFERENCE]`.
//!
//! For each λ (default 0.3, 0.5, 0.8, 0.95, 0.995, 0.998, 0.999) on the fig13a set (μ0 = 0.005,
//! r = 0.99, wall on, U(0) = 7) to T (default 1000) at step DT (default 0.01), three paths: the
//! deterministic one (D = 0, continuous impact memory) and the noisy one (OU noise D = 0.1,
//! τ = 0.5, seed 1) with the continuous and with the restarting impact memory. Prints
//! - the scheme's own error on the deterministic path, max |U_Δt − U_Δt/2| over the common
//!   nodes (the Δt/2 run with a 1e-13 kernel);
//! - for each kernel tolerance ε (default 1e-10, 1e-8, 1e-7, 1e-6, 1e-5, 1e-4, 1e-3; the
//!   environment variable `EPS`, comma-separated, replaces them): the exponentials, the
//!   memory's error max |U_SOE(ε) − U_ref| over every step, its ratio to the scheme's error
//!   and the steps per second (best of three).
//!
//! REFERENCE is `direct` (default: the exact memory, O(N²): about 10 s per path at 10⁵ steps)
//! or `soe` (a 1e-13 kernel, for long runs).
//!
//! `-- one LAMBDA D old|auto STEPS` runs one path (the same set, Δt = 0.01, continuous impact
//! memory) with the previous default (1e-10) or `Memory::Auto` and prints its time and
//! exponentials: for counting its instructions, e.g. under
//! `valgrind --tool=cachegrind --cache-sim=no`, where timings on a shared machine are too noisy.

use std::time::Instant;
use trirhythm::engine::{simulate, ImpactMemory, Memory, PredictorCorrector, Trajectory};
use trirhythm::known_answers::memory_case;

fn run(
    (lambda, d): (f64, f64),
    dt: f64,
    t_end: f64,
    memory: Memory,
    im: ImpactMemory,
) -> (Trajectory, f64) {
    let (problem, m, o) = memory_case(lambda, d, (dt, t_end, 1), memory, im).unwrap();
    let start = Instant::now();
    let tr = simulate(&problem, &m, &o).unwrap();
    (tr, start.elapsed().as_secs_f64())
}

/// max |a_i − b_{stride·i}|.
fn max_gap(a: &[f64], b: &[f64], stride: usize) -> f64 {
    a.iter()
        .zip(b.iter().step_by(stride))
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

fn list(s: &str) -> Vec<f64> {
    s.split(',').map(|x| x.trim().parse().unwrap()).collect()
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if args.get(1).is_some_and(|a| a == "one") {
        let lambda: f64 = args[2].parse().unwrap();
        let d: f64 = args[3].parse().unwrap();
        let memory = match args[4].as_str() {
            "old" => Memory::SumOfExponentials {
                tolerance: trirhythm::engine::PREVIOUS_DEFAULT_TOLERANCE,
            },
            _ => Memory::Auto,
        };
        let steps: f64 = args[5].parse().unwrap();
        let im = PredictorCorrector::default().impact_memory;
        let t_end = steps * 0.01;
        let (problem, m, o) =
            memory_case(lambda, d, (0.01, t_end, steps as usize), memory, im).unwrap();
        let start = Instant::now();
        let tr = simulate(&problem, &m, &o).unwrap();
        println!(
            "{:.4} s, {} exponentials",
            start.elapsed().as_secs_f64(),
            tr.exponentials
        );
        return;
    }
    let t_end: f64 = args.get(1).map_or(1000.0, |s| s.parse().unwrap());
    let dt: f64 = args.get(2).map_or(0.01, |s| s.parse().unwrap());
    let lambdas = args.get(3).map_or_else(
        || vec![0.3, 0.5, 0.8, 0.95, 0.995, 0.998, 0.999],
        |s| list(s),
    );
    let direct = args.get(4).is_none_or(|s| s == "direct");
    let eps = std::env::var("EPS").map_or_else(
        |_| vec![1e-10, 1e-8, 1e-7, 1e-6, 1e-5, 1e-4, 1e-3],
        |s| list(&s),
    );
    let fine = Memory::SumOfExponentials { tolerance: 1e-13 };
    let reference = if direct { Memory::Direct } else { fine };
    println!(
        "# T = {t_end}, dt = {dt}, reference {}",
        if direct { "Direct" } else { "SOE 1e-13" }
    );
    for &lambda in &lambdas {
        // the scheme's own error, on the deterministic path
        let det = (lambda, 0.0);
        let (coarse, _) = run(det, dt, t_end, reference, ImpactMemory::Continuous);
        let (half, _) = run(det, dt / 2.0, t_end, fine, ImpactMemory::Continuous);
        let scheme = max_gap(&coarse.u, &half.u, 2);
        for (name, d, im) in [
            ("deterministic", 0.0, ImpactMemory::Continuous),
            ("noisy, continuous", 0.1, ImpactMemory::Continuous),
            ("noisy, restart", 0.1, ImpactMemory::Restart),
        ] {
            let p = (lambda, d);
            let (r, _) = run(p, dt, t_end, reference, im);
            println!(
                "lambda {lambda} {name}: {} impacts, scheme error {scheme:.3e}",
                r.impacts
            );
            for &e in &eps {
                let memory = Memory::SumOfExponentials { tolerance: e };
                let (s, mut best) = run(p, dt, t_end, memory, im);
                for _ in 0..2 {
                    best = best.min(run(p, dt, t_end, memory, im).1);
                }
                let err = max_gap(&r.u, &s.u, 1);
                println!(
                    "  eps {e:.0e}: {:3} exponentials, memory error {err:.3e}, ratio {:.3e}, \
                     {:.3e} steps/s",
                    s.exponentials,
                    err / scheme,
                    s.steps as f64 / best
                );
            }
        }
    }
}
