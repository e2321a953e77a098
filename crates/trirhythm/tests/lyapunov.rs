//! The largest Lyapunov exponent with frozen noise (`analysis::lyapunov`) on problems whose
//! exponent is known.
//!
//! - The damped linear oscillator U″ + μ0U′ + ω0²U = η (P ≡ −1, no wall, λ = 1) has LLE = −μ0/2
//!   for every noise intensity: additive noise does not enter the difference of two paths.
//! - A stable deterministic limit cycle (λ = 1, no wall, D = 0) has LLE 0 (the phase is neutral).
//! - At λ = 1, Eq. (1) with the wall and Eq. (9) on the whole line are the same motion (U = |Z|),
//!   so they have the same LLE, noise included.
//! - Path i depends only on (seed, i): one thread and two give bit-identical results.
//! - The tangent (variational) method: the damped oscillator's −μ0/2, and agreement with two
//!   trajectories within their combined standard errors on a limit cycle with the wall (λ = 1),
//!   a noisy case with the wall (λ = 0.998, Fig. 17(a)'s parameters, both impact memories) and a
//!   fractional case without the wall (where, with no impact, the tangent is the exact
//!   derivative of the step and the two agree path by path).
//! - The tangent through the General kernel's fractional terms K·D^αU: a van der Pol cycle with
//!   a fractional damping term has exponent 0 within the band R/W of ln‖F‖ along the orbit
//!   (plus one e-fold), by both methods, which agree path by path; a damped linear oscillator
//!   with a fractional term has no positive exponent (its power-law tail: → 0⁻ as the window
//!   grows), the tangent equal to two trajectories to rounding (linear).

use trirhythm::analysis::lyapunov::{
    largest_lyapunov, LyapunovMethod, LyapunovResult, LyapunovSpec,
};
use trirhythm::analysis::lyapunov::{merge, run_paths, PathRun};
use trirhythm::engine::{
    simulate, Barrier, ImpactMemory, Options, PredictorCorrector, Problem, System,
};
use trirhythm::model::{preset, Fractional, Model, Params};
use trirhythm::monitor::{CancelFlag, Silent};

const SEED: u64 = 20240611;

fn params(pairs: &[(&str, f64)]) -> Params {
    let mut p = preset("fig17a").unwrap().params;
    for &(k, v) in pairs {
        p = p.with(k, v).unwrap();
    }
    p
}

fn linear(mu0: f64, d: f64) -> Params {
    params(&[
        ("c0", -1.0),
        ("c1", 0.0),
        ("alpha0", 0.0),
        ("beta0", 0.0),
        ("gamma0", 0.0),
        ("delta0", 0.0),
        ("lambda", 1.0),
        ("omega0", 1.0),
        ("mu0", mu0),
        ("D", d),
        ("tau", 0.1),
    ])
}

/// The problem of `p` with the wall on or off, from (u0, 0).
fn problem(p: &Params, barrier: Barrier, u0: f64) -> Problem {
    Problem::from_params(p)
        .and_then(|q| q.with_barrier(barrier))
        .and_then(|q| q.with_start(u0, 0.0))
        .unwrap()
}

fn lle(problem: &Problem, spec: &LyapunovSpec) -> LyapunovResult {
    largest_lyapunov(problem, &PredictorCorrector::default(), spec, &Silent).unwrap()
}

#[test]
fn damped_linear_oscillator_has_minus_half_the_damping_for_every_noise() {
    let mu0 = 0.1;
    let spec = LyapunovSpec {
        paths: 2,
        seed: SEED,
        transient: 50.0,
        length: 1000.0,
        ..Default::default()
    };
    for d in [0.0, 0.1, 1.0] {
        let r = lle(&problem(&linear(mu0, d), Barrier::Off, 1.0), &spec);
        let err = r.lle.value + mu0 / 2.0;
        assert!(
            err.abs() < 1e-3,
            "D = {d}: LLE {} vs −μ0/2 = {} (error {err:e})",
            r.lle.value,
            -mu0 / 2.0
        );
        // the noise does not enter: every realisation has the same exponent
        assert!(r.lle.stderr < 1e-6, "D = {d}: stderr {}", r.lle.stderr);
        assert_eq!(r.running.len(), spec.running_points);
    }
}

#[test]
fn stable_limit_cycle_has_a_zero_exponent() {
    let p = params(&[("lambda", 1.0), ("mu0", 0.1), ("omega0", 1.0), ("D", 0.0)]);
    let spec = LyapunovSpec {
        paths: 1,
        seed: SEED,
        transient: 500.0,
        length: 2000.0,
        ..Default::default()
    };
    let r = lle(&problem(&p, Barrier::Off, 2.0), &spec);
    assert!(
        r.lle.value.abs() < 2e-3,
        "limit cycle: LLE {} (should be 0)",
        r.lle.value
    );
}

#[test]
fn wall_and_zhuravlev_agree_at_lambda_one() {
    let p = params(&[
        ("lambda", 1.0),
        ("mu0", 0.05),
        ("r", 0.9),
        ("D", 0.2),
        ("tau", 0.1),
    ]);
    let spec = LyapunovSpec {
        paths: 4,
        seed: SEED,
        transient: 100.0,
        length: 1000.0,
        ..Default::default()
    };
    let with_wall = problem(&p, Barrier::On, 1.0);
    let zhuravlev = with_wall.clone().with_system(System::Zhuravlev).unwrap();
    let wall = lle(&with_wall, &spec);
    let z = lle(&zhuravlev, &spec);
    assert!(wall.per_path.iter().all(|q| q.impacts > 50));
    // path by path the two formulations part after a while: their rounding differs (the
    // memories sum g with opposite signs after a crossing) and near-grazing impacts amplify it
    // (measured: no sticking steps; U and |Z| of paths 0 and 2 part beyond 1e-6 at t = 317 and
    // 159, paths 1 and 3 stay within 1.2e-7 up to t = 1100). So over T = 1000 only some paths
    // agree (2 of 4 within 1e-3); over a window that ends before t = 159 every path must
    // (measured: 1.8e-6 … 1.8e-5 apart over T = 50, the rounding against the copy's 1e-8
    // separation amplified at near-grazing impacts)
    let close = wall
        .per_path
        .iter()
        .zip(&z.per_path)
        .filter(|(a, b)| (a.exponent - b.exponent).abs() < 1e-3)
        .count();
    eprintln!("T = 1000: {close} of 4 paths agree within 1e-3");
    let early = LyapunovSpec {
        length: 50.0,
        ..spec.clone()
    };
    for (a, b) in lle(&with_wall, &early)
        .per_path
        .iter()
        .zip(&lle(&zhuravlev, &early).per_path)
    {
        assert!(
            (a.exponent - b.exponent).abs() < 1e-4,
            "path {}, T = 50: {} vs {}",
            a.path,
            a.exponent,
            b.exponent
        );
    }
    let diff = (wall.lle.value - z.lle.value).abs();
    let sigma = wall.lle.stderr.hypot(z.lle.stderr);
    assert!(
        diff < 2.0 * sigma && diff < 0.01,
        "Eq. 1 with the wall {} ± {} vs Eq. 9 {} ± {}",
        wall.lle.value,
        wall.lle.stderr,
        z.lle.value,
        z.lle.stderr
    );
}

#[test]
fn one_thread_or_two_give_the_same_exponent() {
    let p = params(&[("D", 0.3)]);
    let spec = LyapunovSpec {
        paths: 3,
        seed: SEED,
        transient: 20.0,
        length: 200.0,
        ..Default::default()
    };
    let run = |threads| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| lle(&problem(&p, Barrier::On, 1.0), &spec))
    };
    assert_eq!(run(1), run(2));
}

fn lle_with(p: &Problem, method: &PredictorCorrector, spec: &LyapunovSpec) -> LyapunovResult {
    largest_lyapunov(p, method, spec, &Silent).unwrap()
}

/// Both methods on the same paths; returns (two-trajectory, tangent, z of their difference).
fn both(
    p: &Problem,
    method: &PredictorCorrector,
    spec: &LyapunovSpec,
) -> (LyapunovResult, LyapunovResult, f64) {
    let two = lle_with(
        p,
        method,
        &LyapunovSpec {
            method: LyapunovMethod::TwoTrajectory,
            ..spec.clone()
        },
    );
    let tangent = lle_with(
        p,
        method,
        &LyapunovSpec {
            method: LyapunovMethod::Tangent,
            ..spec.clone()
        },
    );
    let z = (two.lle.value - tangent.lle.value).abs() / two.lle.stderr.hypot(tangent.lle.stderr);
    eprintln!(
        "two-trajectory {} ± {}, tangent {} ± {}, z = {z:.3}; largest per-path difference {:e}",
        two.lle.value,
        two.lle.stderr,
        tangent.lle.value,
        tangent.lle.stderr,
        largest_difference(&two, &tangent)
    );
    (two, tangent, z)
}

fn largest_difference(a: &LyapunovResult, b: &LyapunovResult) -> f64 {
    a.per_path
        .iter()
        .zip(&b.per_path)
        .map(|(x, y)| (x.exponent - y.exponent).abs())
        .fold(0.0, f64::max)
}

#[test]
fn tangent_damped_linear_oscillator_has_minus_half_the_damping() {
    let mu0 = 0.1;
    let spec = LyapunovSpec {
        paths: 2,
        seed: SEED,
        transient: 50.0,
        length: 1000.0,
        method: LyapunovMethod::Tangent,
        ..Default::default()
    };
    for d in [0.0, 1.0] {
        let r = lle(&problem(&linear(mu0, d), Barrier::Off, 1.0), &spec);
        let err = r.lle.value + mu0 / 2.0;
        eprintln!("D = {d}: tangent LLE {} (error {err:e})", r.lle.value);
        assert!(
            err.abs() < 1e-3,
            "D = {d}: LLE {} (error {err:e})",
            r.lle.value
        );
        assert!(r.lle.stderr < 1e-9, "D = {d}: stderr {}", r.lle.stderr);
    }
}

#[test]
fn tangent_and_two_trajectories_agree_on_a_limit_cycle_with_the_wall() {
    // λ = 1, an impacting limit cycle (≈ 0.3 impacts per unit time), a trace of noise so that
    // the paths differ and the standard errors exist
    let p = params(&[("lambda", 1.0), ("mu0", 0.1), ("omega0", 1.0), ("D", 1e-4)]);
    let spec = LyapunovSpec {
        paths: 4,
        seed: SEED,
        transient: 200.0,
        length: 1000.0,
        ..Default::default()
    };
    let method = PredictorCorrector {
        impact_memory: ImpactMemory::Continuous,
        ..Default::default()
    };
    let (two, tangent, z) = both(&problem(&p, Barrier::On, 2.0), &method, &spec);
    assert!(two.per_path.iter().all(|q| q.impacts > 200));
    assert!(z < 3.0, "z = {z}");
    // a limit cycle: both near 0
    assert!(two.lle.value.abs() < 1e-3 && tangent.lle.value.abs() < 1e-3);
}

#[test]
fn tangent_and_two_trajectories_agree_on_a_noisy_fractional_impact_oscillator() {
    // Fig. 17(a)'s parameters at λ = 0.998, D = 0.5: ≈ 0.3 impacts per unit time
    let p = params(&[("lambda", 0.998), ("D", 0.5)]);
    let spec = LyapunovSpec {
        paths: 8,
        seed: SEED,
        transient: 100.0,
        length: 1000.0,
        ..Default::default()
    };
    for memory in [ImpactMemory::Restart, ImpactMemory::Continuous] {
        let method = PredictorCorrector {
            impact_memory: memory,
            ..Default::default()
        };
        let (two, _, z) = both(&problem(&p, Barrier::On, 1.0), &method, &spec);
        assert!(two.per_path.iter().all(|q| q.impacts > 200));
        assert!(z < 3.0, "{memory:?}: z = {z}");
    }
}

#[test]
fn tangent_and_two_trajectories_agree_path_by_path_without_the_wall() {
    // no impact: the tangent is the exact derivative of the step, so the two differ only by
    // the two-trajectory method's O(d₀) nonlinearity and rounding
    for lambda in [0.998, 0.95] {
        let p = params(&[("lambda", lambda), ("D", 0.3)]);
        let spec = LyapunovSpec {
            paths: 4,
            seed: SEED,
            transient: 100.0,
            length: 1000.0,
            ..Default::default()
        };
        let (two, tangent, z) = both(
            &problem(&p, Barrier::Off, 1.0),
            &PredictorCorrector::default(),
            &spec,
        );
        assert!(z < 3.0, "λ = {lambda}: z = {z}");
        let worst = largest_difference(&two, &tangent);
        assert!(worst < 3e-6, "λ = {lambda}: per-path difference {worst:e}");
    }
}

#[test]
fn tangent_one_thread_or_two_give_the_same_exponent() {
    let p = params(&[("D", 0.3)]);
    let spec = LyapunovSpec {
        paths: 3,
        seed: SEED,
        transient: 20.0,
        length: 200.0,
        method: LyapunovMethod::Tangent,
        ..Default::default()
    };
    let run = |threads| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| lle(&problem(&p, Barrier::On, 1.0), &spec))
    };
    let one = run(1);
    assert!(one.per_path.iter().all(|q| q.impacts > 10));
    assert_eq!(one, run(2));
}

/// With the wall and the memory restarted at sticking, a copy can merge with its reference:
/// both stick on the same step and their whole states become identical. That realisation's
/// exponent is −∞ with its merge time, whenever it happens; the others keep finite exponents,
/// and `unmerged` is their mean.
#[test]
fn a_copy_that_merges_with_its_reference_gives_minus_infinity_with_its_time() {
    let p = preset("fig18b")
        .unwrap()
        .params
        .with("r", 0.8)
        .unwrap()
        .with("D", 0.29375)
        .unwrap();
    let method = PredictorCorrector {
        impact_memory: ImpactMemory::Restart,
        ..Default::default()
    };
    let spec = LyapunovSpec {
        paths: 6,
        seed: 1,
        transient: 20.0,
        length: 380.0,
        ..Default::default()
    };
    let r = lle_with(&problem(&p, Barrier::On, 1.0), &method, &spec);
    let merged: Vec<_> = r
        .per_path
        .iter()
        .filter(|q| q.merged_at.is_some())
        .collect();
    assert!(!merged.is_empty(), "{:?}", r.per_path);
    assert_eq!(r.merged, merged.len());
    for q in &merged {
        assert_eq!(q.exponent, f64::NEG_INFINITY);
        let t = q.merged_at.unwrap();
        assert!(t > 0.0 && t <= 400.0, "{t}");
    }
    assert_eq!(r.lle.value, f64::NEG_INFINITY);
    let others: Vec<f64> = r
        .per_path
        .iter()
        .filter(|q| q.merged_at.is_none())
        .map(|q| q.exponent)
        .collect();
    assert!(!others.is_empty() && others.iter().all(|e| e.is_finite()));
    let mean = others.iter().sum::<f64>() / others.len() as f64;
    assert!((r.unmerged.value - mean).abs() < 1e-15);
    eprintln!(
        "merged {:?}; unmerged {:.4} ± {:.4}",
        merged
            .iter()
            .map(|q| (q.path, q.merged_at))
            .collect::<Vec<_>>(),
        r.unmerged.value,
        r.unmerged.stderr
    );
}

#[test]
fn a_cancelled_estimate_stops_with_cancelled() {
    let flag = CancelFlag::default();
    flag.cancel();
    let spec = LyapunovSpec {
        paths: 2,
        seed: SEED,
        transient: 20.0,
        length: 200.0,
        ..Default::default()
    };
    let at = problem(&params(&[("D", 0.3)]), Barrier::On, 1.0);
    let method = PredictorCorrector::default();
    let r = largest_lyapunov(&at, &method, &spec, &flag);
    assert!(matches!(r, Err(trirhythm::Error::Cancelled)), "{r:?}");
}

#[test]
fn realisations_in_any_split_and_order_merge_to_the_whole_estimate() {
    let spec = LyapunovSpec {
        paths: 5,
        seed: SEED,
        transient: 20.0,
        length: 200.0,
        ..Default::default()
    };
    let at = problem(&params(&[("D", 0.3)]), Barrier::On, 1.0);
    let method = PredictorCorrector::default();
    let whole = largest_lyapunov(&at, &method, &spec, &Silent).unwrap();
    let mut runs: Vec<PathRun> = Vec::new();
    for piece in [&[4u64, 1][..], &[0], &[3, 2]] {
        runs.extend(run_paths(&at, &method, &spec, piece, &Silent).unwrap());
    }
    // through JSON and back, as a piece run elsewhere would come
    let runs: Vec<PathRun> = serde_json::from_str(&serde_json::to_string(&runs).unwrap()).unwrap();
    let merged = merge(&spec, runs.clone()).unwrap();
    assert_eq!(format!("{merged:?}"), format!("{whole:?}"));
    assert!(merge(&spec, runs[1..].to_vec()).is_err());
    let mut twice = runs.clone();
    twice.push(runs[0].clone());
    assert!(merge(&spec, twice).is_err());
    assert!(run_paths(&at, &method, &spec, &[5], &Silent).is_err());
}

/// A model of the class: fig17a's leading part at λ = 1, ω0 = 1, the damping μ0·P(U) with P's
/// coefficients in U² `p`, the fractional terms (K, α), no wall, no noise, from (u0, 0).
fn fractional_model(mu0: f64, p: &[f64], fractional: &[(f64, f64)], u0: f64) -> Problem {
    let mut m = Model::from(&params(&[("lambda", 1.0), ("omega0", 1.0), ("D", 0.0)]));
    m.damping.mu0 = mu0;
    m.damping.coefficients = p.to_vec();
    m.walls.clear();
    m.noise.additive = None;
    m.fractional = fractional
        .iter()
        .map(|&(coefficient, order)| Fractional { coefficient, order })
        .collect();
    m.start.u0 = u0;
    m.start.v0 = 0.0;
    Problem::from_model(&m).unwrap()
}

/// R = ln(max‖F‖/min‖F‖), F = (U̇, Ü), over the noise-free path on [transient, transient + W]
/// (Ü by central differences): the band the log-norm of a tangent along the flow stays in.
fn flow_band(problem: &Problem, method: &PredictorCorrector, (transient, w): (f64, f64)) -> f64 {
    let o = Options {
        t_end: transient + w,
        seed: SEED,
        record_every: 1,
        ..Default::default()
    };
    let tr = simulate(problem, method, &o).unwrap();
    let (v, dt) = (&tr.v, method.dt);
    let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
    for n in ((transient / dt) as usize).max(1)..v.len() - 1 {
        let f = v[n].hypot((v[n + 1] - v[n - 1]) / (2.0 * dt));
        lo = lo.min(f);
        hi = hi.max(f);
    }
    (hi / lo).ln()
}

#[test]
fn tangent_fractional_van_der_pol_cycle_has_a_zero_exponent() {
    // Ü − μ(1 − U²)U̇ + K·D^{0.5}U + U = 0, μ = 0.5, K = 0.1 (the cycle survives the weak
    // fractional damping), no noise: the flow direction is neutral along the (asymptotically)
    // periodic orbit, so the finite-time exponent over W is bounded by the band R/W of
    // ln‖F‖ along the orbit, plus one e-fold for what the transient and the fractional
    // memory's power-law tail leave (as in tests/cycle_exponent.rs); both methods, which
    // agree path by path (no impact: the tangent is the exact derivative of the step)
    let problem = fractional_model(0.5, &[1.0, -1.0], &[(0.1, 0.5)], 2.0);
    let method = PredictorCorrector::default();
    let (transient, w) = (500.0, 2000.0);
    let r = flow_band(&problem, &method, (transient, w));
    let bound = (r + 1.0) / w;
    let spec = LyapunovSpec {
        paths: 1,
        seed: SEED,
        transient,
        length: w,
        ..Default::default()
    };
    let (two, tangent, _) = both(&problem, &method, &spec);
    let (t, v) = (tangent.lle.value, two.lle.value);
    eprintln!(
        "fractional van der Pol: tangent {t:+.3e}, two trajectories {v:+.3e}, bound {bound:.2e} \
         (R = {r:.2})"
    );
    assert!(
        t.abs() <= bound && v.abs() <= bound,
        "tangent {t}, two {v}, bound {bound}"
    );
    assert!((t - v).abs() < 1e-6, "tangent {t} vs two trajectories {v}");
}

#[test]
fn tangent_damped_fractional_linear_oscillator_has_no_positive_exponent() {
    // Ü + 0.1U̇ + K·D^{0.5}U + U = 0 (K = 0.3), no noise: every solution decays (the
    // fractional term's power-law tail makes the exponent tend to 0⁻ as the window grows, so
    // only its sign is asserted: no growth beyond the band of ‖(δU, δU̇)‖ over an oscillation,
    // ln 2 at most for ω0 = 1, per window); linear, so the two trajectories' difference is
    // the tangent itself: the methods agree to rounding
    let problem = fractional_model(0.1, &[-1.0], &[(0.3, 0.5)], 1.0);
    let method = PredictorCorrector::default();
    let mut before = f64::NEG_INFINITY;
    for w in [200.0, 1000.0] {
        let spec = LyapunovSpec {
            paths: 1,
            seed: SEED,
            transient: 50.0,
            length: w,
            ..Default::default()
        };
        let (two, tangent, _) = both(&problem, &method, &spec);
        let (t, v) = (tangent.lle.value, two.lle.value);
        eprintln!("damped fractional oscillator, W = {w}: tangent {t:+.3e}, two {v:+.3e}");
        assert!(t <= 2f64.ln() / w, "W = {w}: tangent {t}");
        assert!(
            (t - v).abs() < 1e-8,
            "W = {w}: tangent {t} vs two trajectories {v}"
        );
        // the algebraic tail: the longer window's exponent is nearer 0 (an exponential decay
        // would keep it)
        assert!(t > before, "W = {w}: {t} after {before}");
        before = t;
    }
}
