//! Side-by-side timings of the engine for the README and the closing note:
//! `cargo run --release -p trirhythm --example engine_timing [-- quick]`.
//!
//! Prints, in one run: SOE at λ = 0.998 vs λ = 1 at 1e6 and 1e7 steps (cost ratio, steps/s);
//! SOE vs Direct at 1e4, 3e4, 1e5 steps (speed-up and max |ΔU|); the number of exponentials.

use std::time::Instant;
use trirhythm::engine::Memory;
use trirhythm::engine::{simulate, Trajectory};
use trirhythm::known_answers::engine_benchmark_case;

fn run(lambda: f64, steps: usize, memory: Memory, every: usize) -> (Trajectory, f64) {
    let (osc, m, o) = engine_benchmark_case(lambda, steps, memory, every).unwrap();
    let start = Instant::now();
    let tr = simulate(&osc, &m, &o, 0).unwrap();
    (tr, start.elapsed().as_secs_f64())
}

fn main() {
    let quick = std::env::args().any(|a| a == "quick");
    println!("Eq. (1), fig1 parameters with mu0 = 0.1, barrier on, dt = 0.01, U(0) = 2");
    println!("\nSOE (tolerance 1e-10) at lambda = 0.998 vs lambda = 1 (no memory):");
    let sizes: &[usize] = if quick {
        &[1_000_000]
    } else {
        &[1_000_000, 10_000_000]
    };
    for &n in sizes {
        let (a, ta) = run(0.998, n, Memory::default(), n);
        let (b, tb) = run(1.0, n, Memory::default(), n);
        println!(
            "  N = {n:>9}: lambda=0.998 {ta:7.3} s ({:.2e} steps/s, {} exponentials, {} impacts) | lambda=1 {tb:7.3} s ({:.2e} steps/s) | ratio {:.2}x",
            n as f64 / ta,
            a.exponentials,
            a.impacts,
            n as f64 / tb,
            ta / tb
        );
        let _ = b;
    }
    println!("\nSOE (tolerance 1e-12) vs Direct at lambda = 0.998:");
    let sizes: &[usize] = if quick {
        &[10_000, 30_000]
    } else {
        &[10_000, 30_000, 100_000]
    };
    for &n in sizes {
        let (s, ts) = run(0.998, n, Memory::SumOfExponentials { tolerance: 1e-12 }, 1);
        let (d, td) = run(0.998, n, Memory::Direct, 1);
        let du =
            s.u.iter()
                .zip(&d.u)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
        println!(
            "  N = {n:>7}: SOE {ts:8.4} s ({} exponentials) | Direct {td:8.3} s | speed-up {:7.1}x | max |dU| = {du:.2e} | state {} B vs {} B",
            s.exponentials,
            td / ts,
            s.memory_bytes,
            d.memory_bytes
        );
    }
}
