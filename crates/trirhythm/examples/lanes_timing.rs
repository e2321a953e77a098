//! The lane stepper against the scalar stepper, side by side in one run: the fig13a ensemble
//! (8 paths, OU noise D = 0.1, τ = 0.5, wall on, Δt = 0.01) at λ = 0.998 and at λ = 1, with
//! `Lanes::Width(1)` (the scalar stepper, path after path), 4 and 8, on one thread and on two,
//! the cases interleaved round by round; medians of the rounds, in path·steps per second of
//! wall time and of CPU time (the process's, so that waiting for a shared core does not count).
//! The statistics of every lane count are checked to be identical. The same paths are also
//! timed by the stepper alone (`run_lanes` with an observer that keeps nothing), one thread.
//!
//! `cargo run --release -p trirhythm --example lanes_timing [-- steps-per-path [rounds [lanes,…]]]`
//! (default 10⁶ steps, 3 rounds, lanes 1,4,8).

use std::time::Instant;
use trirhythm::analysis::ensemble::{run_ensemble, EnsembleResult, EnsembleSpec};
use trirhythm::engine::{detected_lanes, run_lanes, Flow, Lanes, PredictorCorrector, Stepper};
use trirhythm::monitor::Silent;

#[path = "support/mod.rs"]
mod support;
use support::{cpu_s, fig13a_problem, median};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let steps: f64 = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(1e6);
    let rounds: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(3);
    let paths = 8usize;
    let isa = if std::arch::is_x86_feature_detected!("avx2") {
        "lane arrays in AVX2 (4 doubles a vector)"
    } else {
        "portable lane arrays (no AVX2)"
    };
    println!(
        "fig13a ensemble: {paths} paths x {steps:.0e} steps, D = 0.1, tau = 0.5, wall on, dt = 0.01; \
         {isa}, Lanes::Auto = {}; medians of {rounds} interleaved rounds",
        detected_lanes()
    );
    // a third argument picks the lane counts, e.g. `8` or `1,4` (for a profiler)
    let widths: Vec<usize> = args.get(3).map_or(vec![1, 4, 8], |s| {
        s.split(',')
            .map(|w| w.parse().expect("lane counts 1, 4, 8"))
            .collect()
    });
    let pools: Vec<rayon::ThreadPool> = [1, 2]
        .iter()
        .map(|&n| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .unwrap()
        })
        .collect();
    for lambda in [0.998, 1.0] {
        let problem = fig13a_problem(lambda);
        let method = PredictorCorrector::default();
        let run = |threads: usize, lanes: usize| -> (f64, f64, EnsembleResult) {
            let spec = EnsembleSpec {
                paths,
                burn_in: 0.0,
                length: steps * 0.01,
                amplitude_max: 16.0,
                lanes: Lanes::Width(lanes),
                ..Default::default()
            };
            let pool = &pools[threads - 1];
            let (c0, t0) = (cpu_s(), Instant::now());
            let r = pool
                .install(|| run_ensemble(&problem, &method, &spec, &Silent))
                .unwrap();
            let wall = t0.elapsed().as_secs_f64();
            let cpu = cpu_s().zip(c0).map_or(f64::NAN, |(b, a)| b - a);
            (wall, cpu, r)
        };
        // the stepper alone: the same paths by `run_lanes`, an observer that keeps nothing
        let bare = |lanes: usize| -> (f64, f64, Vec<u64>) {
            let horizon = steps * 0.01;
            let mut paths: Vec<Stepper> = (0..paths as u64)
                .map(|i| Stepper::new(&problem, &method, (1, i), horizon).unwrap())
                .collect();
            let mut observers: Vec<_> = (0..paths.len())
                .map(|_| |_: &Stepper| Flow::Continue)
                .collect();
            let (c0, t0) = (cpu_s(), Instant::now());
            run_lanes(
                &mut paths,
                steps as u64,
                &mut observers,
                Lanes::Width(lanes),
                &Silent,
            )
            .unwrap();
            let wall = t0.elapsed().as_secs_f64();
            let cpu = cpu_s().zip(c0).map_or(f64::NAN, |(b, a)| b - a);
            (
                wall,
                cpu,
                paths
                    .iter()
                    .map(|p| p.u().to_bits() ^ p.impacts())
                    .collect(),
            )
        };
        // [threads][width] → wall and CPU seconds per round
        let mut bare_wall = vec![vec![]; widths.len()];
        let mut bare_cpu = vec![vec![]; widths.len()];
        let mut bare_ends: Option<Vec<u64>> = None;
        let mut wall = vec![vec![vec![]; widths.len()]; 2];
        let mut cpu = vec![vec![vec![]; widths.len()]; 2];
        let mut reference: Option<EnsembleResult> = None;
        for _ in 0..rounds {
            for (k, &w) in widths.iter().enumerate() {
                let (t, c, ends) = pools[0].install(|| bare(w));
                match &bare_ends {
                    None => bare_ends = Some(ends),
                    Some(e) => assert!(*e == ends, "lanes {w}: other paths"),
                }
                bare_wall[k].push(t);
                bare_cpu[k].push(c);
            }
            for threads in [1, 2] {
                if threads == 2 && widths.len() == 1 {
                    continue;
                }
                for (k, &w) in widths.iter().enumerate() {
                    let (t, c, r) = run(threads, w);
                    match &reference {
                        None => reference = Some(r),
                        Some(a) => {
                            assert!(*a == r, "lanes {w}, {threads} threads: other statistics")
                        }
                    }
                    wall[threads - 1][k].push(t);
                    cpu[threads - 1][k].push(c);
                }
            }
        }
        let work = paths as f64 * steps;
        let scalar = median(wall[0][0].clone());
        let scalar_cpu = median(cpu[0][0].clone());
        let a = reference
            .as_ref()
            .map_or(f64::NAN, |r| r.mean_amplitude.value);
        println!(
            "lambda = {lambda} (mean amplitude {a}; statistics identical for every lane count and \
             thread count):"
        );
        let (bare0, bare0_cpu) = (median(bare_wall[0].clone()), median(bare_cpu[0].clone()));
        for (k, &w) in widths.iter().enumerate() {
            let (t, c) = (median(bare_wall[k].clone()), median(bare_cpu[k].clone()));
            println!(
                "  stepper alone (run_lanes, no statistics), lanes {w}: {:6.2} ns per path-step of \
                 wall, {:6.2} of CPU; against lanes {}: {:.2}x wall, {:.2}x CPU",
                t / work * 1e9,
                c / work * 1e9,
                widths[0],
                bare0 / t,
                bare0_cpu / c
            );
        }
        for threads in [1, 2] {
            if wall[threads - 1][0].is_empty() {
                continue;
            }
            for (k, &w) in widths.iter().enumerate() {
                let (t, c) = (
                    median(wall[threads - 1][k].clone()),
                    median(cpu[threads - 1][k].clone()),
                );
                println!(
                    "  {threads} thread(s), lanes {w}: {:6.2} ns per path-step of wall ({:.3e} /s), \
                     {:6.2} of CPU; against 1 thread lanes 1: {:.2}x wall, {:.2}x CPU",
                    t / work * 1e9,
                    work / t,
                    c / work * 1e9,
                    scalar / t,
                    scalar_cpu / c
                );
            }
        }
        for (k, &w) in widths.iter().enumerate() {
            if wall[1][k].is_empty() {
                continue;
            }
            println!(
                "  two threads against one, lanes {w}: {:.2}x wall",
                median(wall[0][k].clone()) / median(wall[1][k].clone())
            );
        }
    }
}
