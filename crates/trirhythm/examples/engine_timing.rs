//! Side-by-side timings of the engine for the README and the closing notes:
//! `cargo run --release -p trirhythm --example engine_timing [-- quick]`.
//!
//! Prints, in one run:
//! - the noisy fractional path of the speed target (Fig. 13(a) set: λ = 0.998, OU noise D = 0.1,
//!   τ = 0.5, wall on, Δt = 0.01, 10⁷ steps) against the same path at λ = 1 and without noise,
//!   in steps per second on one core, the best of five runs with the cases alternating (one run
//!   with `quick`), the ratio λ = 0.998 / λ = 1 of the best runs and run by run, and the
//!   per-step breakdown (memory, noise, the rest);
//! - SOE vs Direct at 1e4, 3e4, 1e5 steps (speed-up and max |ΔU|).
//!
//! `-- maths` times only the two noisy paths (λ = 0.998 and λ = 1, 10⁷ steps) and the noise
//! alone, once each, and says which elementary functions the build uses: run a default build
//! and one with `--features std-maths` alternately to measure what the platform-independent
//! `trirhythm::maths` costs (the numbers in docs/numerics.md, Speed).

use std::hint::black_box;
use std::time::Instant;
use trirhythm::engine::noise::NoiseStream;
use trirhythm::engine::{probe_memory, simulate, Memory, Oscillator, PredictorCorrector};
use trirhythm::known_answers::{engine_benchmark_case, memory_case};
use trirhythm::model::preset;

fn speed_case(lambda: f64, d: f64, steps: usize) -> (f64, usize, f64) {
    let t_end = steps as f64 * 0.01;
    let im = PredictorCorrector::default().impact_memory;
    let (problem, m, o) =
        memory_case(lambda, d, (0.01, t_end, steps), Memory::default(), im).unwrap();
    let start = Instant::now();
    let tr = simulate(&problem, &m, &o).unwrap();
    (
        start.elapsed().as_secs_f64(),
        tr.impacts,
        tr.final_amplitude,
    )
}

fn noise_only(steps: usize) -> f64 {
    let p = preset("fig13a").unwrap().params;
    let osc = Oscillator::new(&p).unwrap();
    let mut s = NoiseStream::new(osc.noise(), 0.01, 1, 0).unwrap();
    let start = Instant::now();
    let mut acc = 0.0;
    for _ in 0..steps {
        acc += s.next_step().0;
    }
    black_box(acc);
    start.elapsed().as_secs_f64()
}

fn memory_only(lambda: f64, steps: usize) -> f64 {
    let start = Instant::now();
    black_box(probe_memory(lambda, 0.01, steps).unwrap());
    start.elapsed().as_secs_f64()
}

/// Nanoseconds this thread has run on a CPU (Linux `schedstat`; `None` elsewhere): on a shared
/// machine the time spent waiting for a core does not count.
fn cpu_ns() -> Option<f64> {
    let text = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    text.split_whitespace().next()?.parse().ok()
}

/// One run of the two noisy paths and of the noise alone, as one line: steps per second of
/// wall time and of CPU time.
fn maths_run(n: usize) {
    let maths = if trirhythm::maths::PLATFORM_MATHS {
        "std "
    } else {
        "libm"
    };
    let mut line = String::from(maths);
    for lambda in [0.998, 1.0] {
        let c0 = cpu_ns();
        let (t, impacts, amp) = speed_case(lambda, 0.1, n);
        let cpu = cpu_ns().zip(c0).map_or(f64::NAN, |(b, a)| (b - a) * 1e-9);
        line += &format!(
            "  lambda = {lambda:<5}: {:.4e} steps/s, {:.4e} per CPU s ({impacts} impacts, A {amp:.6})",
            n as f64 / t,
            n as f64 / cpu
        );
    }
    let c0 = cpu_ns();
    noise_only(n);
    let cpu = cpu_ns().zip(c0).map_or(f64::NAN, |(b, a)| (b - a) * 1e-9);
    println!("{line}  noise: {:.2} ns/step of CPU", cpu / n as f64 * 1e9);
}

fn main() {
    let quick = std::env::args().any(|a| a == "quick");
    if std::env::args().any(|a| a == "maths") {
        maths_run(if quick { 1_000_000 } else { 10_000_000 });
        return;
    }
    let n: usize = if quick { 1_000_000 } else { 10_000_000 };
    // best of `reps` runs, the cases alternating: on a shared machine single runs vary by
    // ±10 %; the fastest run is the one least disturbed
    let reps = if quick { 1 } else { 5 };
    println!("Eq. (1), fig13a set (mu0 = 0.005, r = 0.99), wall on, dt = 0.01, U(0) = 7, N = {n}, one core, best of {reps} alternating runs");
    let cases = [(0.998, 0.1), (1.0, 0.1), (0.998, 0.0), (1.0, 0.0)];
    let mut best = [f64::INFINITY; 4];
    let mut seen = [(0, 0.0); 4];
    let mut ratios = vec![];
    for _ in 0..reps {
        let mut times = [0.0; 4];
        for (k, &(lambda, d)) in cases.iter().enumerate() {
            let (t, impacts, amp) = speed_case(lambda, d, n);
            times[k] = t;
            best[k] = best[k].min(t);
            seen[k] = (impacts, amp);
        }
        ratios.push(times[0] / times[1]);
    }
    for (k, &(lambda, d)) in cases.iter().enumerate() {
        let (impacts, amp) = seen[k];
        println!(
            "  lambda = {lambda:<5} D = {d:<3}: {:7.3} s  {:>6.2e} steps/s  ({:5.1} ns/step, {impacts} impacts, final A {amp:.4})",
            best[k],
            n as f64 / best[k],
            best[k] / n as f64 * 1e9
        );
    }
    let listed: Vec<String> = ratios.iter().map(|r| format!("{r:.2}")).collect();
    println!(
        "  cost of lambda = 0.998 relative to lambda = 1, both noisy: {:.2}x (best runs; run by run: {})",
        best[0] / best[1],
        listed.join(", ")
    );
    let tn = noise_only(n);
    let tm = memory_only(0.998, n);
    let tm1 = memory_only(1.0, n);
    let per = |t: f64| t / n as f64 * 1e9;
    println!("  per-step breakdown of the noisy lambda = 0.998 path (each part timed alone):");
    println!("    memory (SOE modes + 7-step window)       : {:5.1} ns  (lambda = 1, running integral: {:.1} ns)", per(tm), per(tm1));
    println!(
        "    noise (OU, two normal deviates)           : {:5.1} ns",
        per(tn)
    );
    println!(
        "    the rest (g, corrector, impacts, driver)   : {:5.1} ns",
        per(best[0]) - per(tm) - per(tn)
    );
    println!(
        "    total                                     : {:5.1} ns",
        per(best[0])
    );

    if std::env::args().any(|a| a == "speed") {
        return;
    }
    println!(
        "\nSOE (tolerance 1e-12) vs Direct at lambda = 0.998 (fig1 set, mu0 = 0.1, U(0) = 2):"
    );
    let sizes: &[usize] = if quick {
        &[10_000, 30_000]
    } else {
        &[10_000, 30_000, 100_000]
    };
    for &n in sizes {
        let run = |memory| {
            let (osc, m, o) = engine_benchmark_case(0.998, n, memory, 1).unwrap();
            let start = Instant::now();
            let tr = simulate(&osc, &m, &o).unwrap();
            (tr, start.elapsed().as_secs_f64())
        };
        let (s, ts) = run(Memory::SumOfExponentials { tolerance: 1e-12 });
        let (d, td) = run(Memory::Direct);
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
