//! The drivers that run several simulations at once, in lanes and one after the other, side by
//! side in one run on one thread, the cases interleaved round by round; medians of the rounds,
//! in seconds of CPU time (the process's, so that waiting for a shared core does not count)
//! and of wall time. Every result is checked to be identical for every lane count.
//!
//! - The tangent-method Lyapunov exponent at Fig. 17(a)'s sizes (μ0 = 0.05, D = 0.1, τ = 0.06:
//!   Δt = 0.005, restart impact memory; 8 realisations, transient 200, window 1500), and the
//!   two-trajectory method beside it.
//! - The oscillation boundary by simulation on a Fig. 15 plane (ω0 = 0.5, μ0 against λ at 21
//!   values of λ in [0.9, 1], the wall on, paper-quality classifier and search), and
//!   `classify_plane` on a grid of it (11 λ × 16 μ0).
//! - The lane step with one problem in every lane (coefficients shared) and with a problem per
//!   lane (coefficients lane by lane; the same fig13a paths, μ0 changed in its last digits so
//!   that the lanes' problems differ): 8 paths, λ = 0.998, D = 0.1, τ = 0.5, the stepper alone.
//!
//! `cargo run --release -p trirhythm --example drivers_timing [-- rounds [scale [case]]]`
//! (default 3 rounds; `scale` < 1 shortens every run, for a smoke test; `case` one of
//! `tangent`, `two`, `boundary`, `classify`, `step` runs that case alone, e.g. for a profiler).

use std::time::Instant;
use trirhythm::analysis::lyapunov::{largest_lyapunov, LyapunovMethod, LyapunovSpec};
use trirhythm::analysis::oscillation::Search;
use trirhythm::analysis::oscillation::{boundary, classify_plane, Classifier, Method, Plane};
use trirhythm::engine::{
    run_lanes, Barrier, Flow, ImpactMemory, Lanes, PredictorCorrector, Problem, Stepper,
};
use trirhythm::model::preset;
use trirhythm::monitor::Silent;

#[path = "support/mod.rs"]
mod support;
use support::{cpu_s, median};

/// (CPU, wall) seconds of `f` and its result.
fn timed<T>(f: impl FnOnce() -> T) -> (f64, f64, T) {
    let (c0, t0) = (cpu_s(), Instant::now());
    let r = f();
    let wall = t0.elapsed().as_secs_f64();
    let cpu = cpu_s().zip(c0).map_or(f64::NAN, |(b, a)| b - a);
    (cpu, wall, r)
}

/// A case timed with several settings: the results (as text) must agree.
struct Case {
    name: String,
    settings: Vec<String>,
    cpu: Vec<Vec<f64>>,
    wall: Vec<Vec<f64>>,
    result: Option<String>,
}

impl Case {
    fn new(name: &str, settings: &[&str]) -> Case {
        Case {
            name: name.into(),
            settings: settings.iter().map(|s| s.to_string()).collect(),
            cpu: vec![vec![]; settings.len()],
            wall: vec![vec![]; settings.len()],
            result: None,
        }
    }

    fn record(&mut self, k: usize, (cpu, wall, result): (f64, f64, String)) {
        match &self.result {
            None => self.result = Some(result),
            Some(r) => assert!(*r == result, "{}: {} differs", self.name, self.settings[k]),
        }
        self.cpu[k].push(cpu);
        self.wall[k].push(wall);
    }

    fn report(&self) {
        println!("{} (results identical for every setting):", self.name);
        let c0 = median(self.cpu[0].clone());
        let w0 = median(self.wall[0].clone());
        for (k, s) in self.settings.iter().enumerate() {
            let (c, w) = (median(self.cpu[k].clone()), median(self.wall[k].clone()));
            println!(
                "  {s:>10}: {c:8.3} s CPU, {w:8.3} s wall; against {}: {:.2}x CPU, {:.2}x wall",
                self.settings[0],
                c0 / c,
                w0 / w
            );
        }
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let rounds: usize = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(3);
    let scale: f64 = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(1.0);
    let only = args.get(3).cloned();
    let wanted = |case: &str| only.as_deref().is_none_or(|o| o == case);
    let isa = if std::arch::is_x86_feature_detected!("avx2") {
        "AVX2"
    } else {
        "portable"
    };
    println!("one thread, lane arrays {isa}; medians of {rounds} interleaved rounds");
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();

    // Lyapunov, Fig. 17(a) sizes
    let p = preset("fig17a")
        .unwrap()
        .params
        .with("mu0", 0.05)
        .and_then(|p| p.with("D", 0.1))
        .unwrap();
    let lyap_problem = Problem::from_params(&p).unwrap();
    let lyap_method = PredictorCorrector {
        dt: 0.005,
        impact_memory: ImpactMemory::Restart,
        ..Default::default()
    };
    let lyap = |method, lanes| {
        let spec = LyapunovSpec {
            paths: 8,
            seed: 1,
            transient: (200.0 * scale).round().max(1.0),
            length: (1500.0 * scale).round().max(10.0),
            method,
            lanes: Lanes::Width(lanes),
            ..Default::default()
        };
        timed(|| {
            let r = largest_lyapunov(&lyap_problem, &lyap_method, &spec, &Silent).unwrap();
            format!("{r:?}")
        })
    };

    // Fig. 15 plane: ω0 = 0.5, μ0 against λ, the wall on
    let base = preset("fig15").unwrap().params.with("omega0", 0.5).unwrap();
    let template = Problem::from_params(&base)
        .and_then(|q| q.with_barrier(Barrier::On))
        .unwrap();
    let n = ((21.0 * scale).round() as usize).max(2);
    let xs: Vec<f64> = (0..n)
        .map(|k| 0.9 + 0.1 * k as f64 / (n - 1) as f64)
        .collect();
    let plane = Plane::new(&template, ("lambda", xs), ("mu0", 1e-4, 0.12)).unwrap();
    let classifier = |lanes| Classifier {
        lanes: Lanes::Width(lanes),
        ..Default::default()
    };
    let search = |lanes| {
        let m = Method::Simulation(classifier(lanes));
        timed(|| {
            format!(
                "{:?}",
                boundary(&plane, &m, &Search::default(), &Silent).unwrap()
            )
        })
    };
    let grid_x: Vec<f64> = (0..11).map(|k| 0.9 + 0.01 * k as f64).collect();
    let grid = Plane {
        x: grid_x[..((11.0 * scale).round() as usize).clamp(1, 11)].to_vec(),
        ..plane.clone()
    };
    let ys: Vec<f64> = (1..=16).map(|k| 0.0075 * k as f64).collect();
    let classify = |lanes| {
        let m = Method::Simulation(classifier(lanes));
        timed(|| format!("{:?}", classify_plane(&grid, &ys, &m, &Silent).unwrap()))
    };

    // the lane step: one problem, or one per lane
    let steps = (2e5 * scale).round().max(100.0) as u64;
    let q = preset("fig13a").unwrap().params;
    let problem_k = |k: usize| {
        let mu0 = q.mu0 * (1.0 + k as f64 * f64::EPSILON);
        Problem::from_params(&q.with("mu0", mu0).unwrap())
            .and_then(|p| p.with_starts(&[(2.9, 0.0), (7.4, 0.0), (12.9, 0.0)]))
            .unwrap()
    };
    let shared = problem_k(0);
    let per_lane: Vec<Problem> = (0..8).map(problem_k).collect();
    let step = |mixed: bool, lanes: usize| {
        let method = PredictorCorrector::default();
        let mut paths: Vec<Stepper> = (0..8)
            .map(|i| {
                let q = if mixed { &per_lane[i] } else { &shared };
                Stepper::new(q, &method, (1, i as u64), steps as f64 * 0.01).unwrap()
            })
            .collect();
        let mut obs: Vec<_> = (0..8).map(|_| |_: &Stepper| Flow::Continue).collect();
        let (c, w, _) =
            timed(|| run_lanes(&mut paths, steps, &mut obs, Lanes::Width(lanes), &Silent).unwrap());
        // the per-lane problems differ in μ0's last digits: their paths are not compared
        let ends: Vec<u64> = paths.iter().map(|p| p.impacts()).collect();
        (c, w, format!("{}", ends.len()))
    };

    let mut tangent = Case::new(
        "tangent-method LLE, Fig. 17(a) sizes (8 realisations)",
        &["lanes 1", "lanes 4", "lanes 8"],
    );
    let mut two = Case::new(
        "two-trajectory LLE, the same (for comparison)",
        &["lanes 1", "lanes 8"],
    );
    let mut bnd = Case::new(
        &format!("simulated boundary, Fig. 15 plane ({n} values of λ)"),
        &["lanes 1", "lanes 4", "lanes 8"],
    );
    let mut cls = Case::new(
        &format!("classify_plane, {} λ × {} μ0", grid.x.len(), ys.len()),
        &["lanes 1", "lanes 4", "lanes 8"],
    );
    let mut lane_step = Case::new(
        &format!("lane step alone, 8 fig13a paths × {steps} steps"),
        &["scalar", "shared 8", "per-lane 8"],
    );
    for _ in 0..rounds {
        pool.install(|| {
            if wanted("tangent") {
                for (k, w) in [1, 4, 8].into_iter().enumerate() {
                    tangent.record(k, lyap(LyapunovMethod::Tangent, w));
                }
            }
            if wanted("two") {
                for (k, w) in [1, 8].into_iter().enumerate() {
                    two.record(k, lyap(LyapunovMethod::TwoTrajectory, w));
                }
            }
            if wanted("boundary") {
                for (k, w) in [1, 4, 8].into_iter().enumerate() {
                    bnd.record(k, search(w));
                }
            }
            if wanted("classify") {
                for (k, w) in [1, 4, 8].into_iter().enumerate() {
                    cls.record(k, classify(w));
                }
            }
            if wanted("step") {
                lane_step.record(0, step(false, 1));
                lane_step.record(1, step(false, 8));
                lane_step.record(2, step(true, 8));
            }
        });
    }
    for c in [&tangent, &two, &bnd, &cls, &lane_step] {
        if c.result.is_some() {
            c.report();
        }
    }
}
