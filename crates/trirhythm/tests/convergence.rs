//! Observed orders of accuracy of the predictor–corrector on problems with exact solutions
//! (`known_answers`), each estimated from a ladder of step sizes and compared with theory.
//!
//! Theory for this PECE (product-trapezoidal corrector, predictor = the corrector's sums with
//! g_{n+1} replaced by g_n): the corrector is second order when D^α y is C²; the predictor's
//! defect O(h^{1+α}) enters through the weight O(h^α), so the global error is
//! O(h^{min(2, 1+2α)}) (DFF's rectangle predictor gives min(2, 1+α)).

use trirhythm::engine::*;
use trirhythm::engine::{solve_scalar, Memory};
use trirhythm::known_answers::*;

/// Order fitted over the three finest levels of a ladder of max-norm errors.
fn finest_order(hs: &[f64], errs: &[f64]) -> f64 {
    let k = hs.len();
    observed_order(&hs[k - 3..], &errs[k - 3..])
}

fn scalar_errors(
    alpha: f64,
    f: &dyn Fn(f64, f64) -> f64,
    exact: &dyn Fn(f64) -> f64,
    levels: usize,
) -> (Vec<f64>, Vec<f64>) {
    let mut hs = vec![];
    let mut errs = vec![];
    for k in 0..levels {
        let n = 20usize << k;
        let h = 1.0 / n as f64;
        let ys = solve_scalar(alpha, f, 0.0, h, n, Memory::Direct).unwrap();
        let e = ys
            .iter()
            .enumerate()
            .map(|(i, y)| (y - exact(i as f64 * h)).abs())
            .fold(0.0, f64::max);
        hs.push(h);
        errs.push(e);
    }
    (hs, errs)
}

#[test]
fn diethelm_benchmark_orders() {
    for &(alpha, theory, levels) in &[(0.9, 2.0, 6), (0.5, 2.0, 6), (0.25, 1.5, 9)] {
        let f = diethelm_rhs(alpha);
        let (hs, errs) = scalar_errors(alpha, &f, &|t| diethelm_exact(alpha, t), levels);
        let p = finest_order(&hs, &errs);
        eprintln!("Diethelm α = {alpha}: observed order {p:.3}, theory {theory}");
        assert!(
            (p - theory).abs() < 0.1,
            "α = {alpha}: observed {p:.3}, theory {theory} (errors {errs:?})"
        );
    }
}

#[test]
fn square_problem_orders() {
    for &alpha in &[0.5, 0.9] {
        let f = square_rhs(alpha);
        let (hs, errs) = scalar_errors(alpha, &f, &|t| t * t, 7);
        let p = finest_order(&hs, &errs);
        eprintln!("y = t² α = {alpha}: observed order {p:.3}, theory 2");
        assert!((p - 2.0).abs() < 0.1, "α = {alpha}: observed {p:.3}");
    }
}

#[test]
fn fractional_relaxation_matches_mittag_leffler() {
    // D^α y = −y: y = E_α(−t^α); y ~ 1 − t^α/Γ(1+α) is not smooth at 0, so only closeness
    // (and convergence) is asserted here, at α = 0.8 on [0, 1]
    let alpha = 0.8;
    let mut last = f64::INFINITY;
    for k in 0..4 {
        let n = 40usize << k;
        let h = 1.0 / n as f64;
        let ys = solve_scalar(alpha, &|_, y| -y, 1.0, h, n, Memory::Direct).unwrap();
        let e = (ys[n] - relaxation(alpha, 1.0).unwrap()).abs();
        assert!(e < last / 1.8, "error must shrink: {e} after {last}");
        last = e;
    }
    assert!(last < 1e-4, "{last}");
}

#[test]
fn fractional_oscillation_orders() {
    // D^{1+λ}U = −ω²U, U(0) = 1, U̇(0) = 0: U = E_{1+λ}(−ω² t^{1+λ})
    for &(lambda, memory) in &[
        (0.5, Memory::Direct),
        (0.9, Memory::Direct),
        (0.998, Memory::SumOfExponentials { tolerance: 1e-12 }),
    ] {
        let problem = Problem::from_params(&linear_oscillator(lambda, 1.0, 1.0))
            .and_then(|p| p.with_barrier(Barrier::Off))
            .and_then(|p| p.with_start(1.0, 0.0))
            .unwrap();
        let t_end = 3.0;
        let mut hs = vec![];
        let mut errs = vec![];
        for k in 0..5 {
            let h = 0.05 / (1 << k) as f64;
            let m = PredictorCorrector {
                dt: h,
                memory,
                ..Default::default()
            };
            let o = Options {
                t_end,
                ..Default::default()
            };
            let tr = simulate(&problem, &m, &o).unwrap();
            let mut e: f64 = 0.0;
            for (i, &t) in tr.t.iter().enumerate().step_by(1 << k) {
                let (u, _) = oscillation(lambda, 1.0, t).unwrap();
                e = e.max((tr.u[i] - u).abs());
            }
            hs.push(h);
            errs.push(e);
        }
        // V ~ t^λ near t = 0, so the trapezoidal U = ∫V has a first-step defect O(h^{1+λ})
        let theory = f64::min(2.0, 1.0 + lambda);
        let p = finest_order(&hs, &errs);
        eprintln!(
            "Mittag-Leffler oscillation λ = {lambda}: observed order {p:.3}, theory {theory}, \
             finest error {:.2e}",
            errs[errs.len() - 1]
        );
        assert!(
            (p - theory).abs() < 0.1,
            "λ = {lambda}: observed {p:.3}, theory {theory} ({errs:?})"
        );
    }
}

#[test]
fn linear_impact_oscillator_order_two() {
    // λ = 1, μ0·P = 0: U = A_k |sin|, amplitude × r per impact
    let (omega, r, v0) = (1.7, 0.8, 1.0);
    let problem = Problem::from_params(&linear_oscillator(1.0, omega, r))
        .and_then(|p| p.with_start(0.0, v0))
        .unwrap();
    let t_end = 7.0; // three impacts
    let mut hs = vec![];
    let mut errs = vec![];
    for k in 0..5 {
        let h = 0.02 / (1 << k) as f64;
        let m = PredictorCorrector {
            dt: h,
            ..Default::default()
        };
        let o = Options {
            t_end,
            ..Default::default()
        };
        let tr = simulate(&problem, &m, &o).unwrap();
        let (u, v, impacts) = impact_oscillator(omega, r, v0, tr.t[tr.t.len() - 1]);
        assert_eq!(tr.impacts, impacts);
        let e = (tr.u.last().unwrap() - u)
            .abs()
            .max((tr.v.last().unwrap() - v).abs() / omega);
        hs.push(h);
        errs.push(e);
    }
    let p = finest_order(&hs, &errs);
    eprintln!(
        "linear impact oscillator: observed order {p:.3}, theory 2, finest error {:.2e}",
        errs[errs.len() - 1]
    );
    assert!((p - 2.0).abs() < 0.1, "observed {p:.3} ({errs:?})");
}

#[test]
fn continuous_and_restart_coincide_at_lambda_one() {
    let mut p = trirhythm::model::preset("fig1").unwrap().params;
    p.lambda = 1.0;
    p.restitution = 0.9;
    p.mu0 = 0.05;
    let problem = Problem::from_params(&p)
        .and_then(|p| p.with_start(0.0, 3.0))
        .unwrap();
    let o = Options {
        t_end: 60.0,
        ..Default::default()
    };
    let mut runs = vec![];
    for im in [ImpactMemory::Continuous, ImpactMemory::Restart] {
        for memory in [Memory::Direct, Memory::default()] {
            let m = PredictorCorrector {
                dt: 0.01,
                memory,
                impact_memory: im,
                ..Default::default()
            };
            runs.push(simulate(&problem, &m, &o).unwrap());
        }
    }
    assert!(runs[0].impacts > 10);
    for r in &runs[1..] {
        assert_eq!(r.impacts, runs[0].impacts);
        let du =
            r.u.iter()
                .zip(&runs[0].u)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
        assert!(du < 1e-10, "max |ΔU| = {du:e}");
    }
    // and they differ for λ < 1 (the convention matters there)
    p.lambda = 0.9;
    let problem = problem.with_params(&p).unwrap();
    let a = simulate(&problem, &PredictorCorrector::default(), &o).unwrap();
    let m = PredictorCorrector {
        impact_memory: ImpactMemory::Restart,
        ..Default::default()
    };
    let b = simulate(&problem, &m, &o).unwrap();
    let du =
        a.u.iter()
            .zip(&b.u)
            .map(|(x, y)| (x - y).abs())
            .fold(0.0, f64::max);
    assert!(du > 1e-3, "{du}");
}
