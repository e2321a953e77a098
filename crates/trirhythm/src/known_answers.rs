//! Problems with known exact answers, shared by the tests and the benchmarks.
//!
//! # Equations
//! - fractional relaxation D^α y = −y, y(0) = 1: y = E_α(−t^α);
//! - fractional oscillation D^{1+λ}U = −ω²U, U(0) = 1, U̇(0) = 0:
//!   U = E_{1+λ}(−ω²t^{1+λ}), U̇ = −ω² t^λ E_{1+λ,1+λ}(−ω²t^{1+λ});
//! - Diethelm's benchmark (Diethelm, Ford & Freed 2004, Numer. Algorithms 36, Example 5.1):
//!   D^α y = 40320 t^{8−α}/Γ(9−α) − 3Γ(5+α/2) t^{4−α/2}/Γ(5−α/2) + (9/4)Γ(α+1)
//!   + (3t^{α/2}/2 − t⁴)³ − y^{3/2}, y(0) = 0, exact y = t⁸ − 3t^{4+α/2} + (9/4)t^α;
//! - the y = t² problem: D^α y = 2t^{2−α}/Γ(3−α) + t² − y, y(0) = 0, exact y = t²;
//! - Ornstein–Uhlenbeck: stationary variance D/τ, correlation e^{−|s|/τ};
//! - the linear fractional oscillator D^{1+λ}U + μU̇ + ω²U = η under OU noise (P ≡ −1, no
//!   wall): stationary Var U = (1/π)∫₀^∞ S(Ω)|H(Ω)|² dΩ and Var U̇ = (1/π)∫₀^∞ S Ω²|H|² dΩ,
//!   S = 2D/(1 + τ²Ω²), H = 1/((iΩ)^{1+λ} + iμΩ + ω²); at λ = 1 Var U =
//!   D(1 + μτ)/(μω²(1 + μτ + ω²τ²)) and Var U̇ = D/(μ(1 + μτ + ω²τ²));
//! - the linear impact oscillator Ü + ω²U = 0 on U ≥ 0, U(0) = 0, U̇(0) = v₀ > 0, U̇₊ = −rU̇₋:
//!   U = A_k sin(ω(t − kπ/ω)) on the k-th arc, A_k = (v₀/ω) r^k (amplitude × r per impact).
//!
//! # Method
//! Closed forms (the Mittag-Leffler function from [`crate::special`]); [`observed_order`]
//! fits log(error) against log(step) by least squares.
//!
//! # Reference
//! Diethelm, Ford & Freed (2004); Garrappa, Mathematics 6 (2018) 16 (test problems).
//!
//! # Tests
//! Used by `tests/convergence.rs`, `tests/soe.rs`, `benches/engine.rs` and
//! `examples/engine_timing.rs`; the unit test below
//! checks the exact solutions against their equations where that is elementary.

use crate::engine::Memory;
use crate::engine::{Barrier, ImpactMemory, Options, PredictorCorrector, Problem};
use crate::error::Result;
use crate::model::{Damping, Params};
use crate::special::{gamma, mittag_leffler};
use std::f64::consts::PI;

/// y(t) = E_α(−t^α), the solution of D^α y = −y, y(0) = 1.
pub fn relaxation(alpha: f64, t: f64) -> Result<f64> {
    mittag_leffler(alpha, 1.0, -t.powf(alpha))
}

/// (U, U̇) of D^{1+λ}U = −ω²U with U(0) = 1, U̇(0) = 0.
pub fn oscillation(lambda: f64, omega: f64, t: f64) -> Result<(f64, f64)> {
    let a = 1.0 + lambda;
    let z = -omega * omega * t.powf(a);
    let u = mittag_leffler(a, 1.0, z)?;
    let v = -omega * omega * t.powf(lambda) * mittag_leffler(a, a, z)?;
    Ok((u, v))
}

/// Right-hand side f(t, y) of Diethelm's benchmark of order α.
pub fn diethelm_rhs(alpha: f64) -> impl Fn(f64, f64) -> f64 {
    let c1 = 40320.0 / gamma(9.0 - alpha);
    let c2 = 3.0 * gamma(5.0 + alpha / 2.0) / gamma(5.0 - alpha / 2.0);
    let c3 = 2.25 * gamma(alpha + 1.0);
    move |t: f64, y: f64| {
        let s = 1.5 * t.powf(alpha / 2.0) - t.powi(4);
        c1 * t.powf(8.0 - alpha) - c2 * t.powf(4.0 - alpha / 2.0) + c3 + s * s * s
            - y.max(0.0).powf(1.5)
    }
}

/// Exact solution of Diethelm's benchmark.
pub fn diethelm_exact(alpha: f64, t: f64) -> f64 {
    t.powi(8) - 3.0 * t.powf(4.0 + alpha / 2.0) + 2.25 * t.powf(alpha)
}

/// Right-hand side of the y = t² problem of order α.
pub fn square_rhs(alpha: f64) -> impl Fn(f64, f64) -> f64 {
    let c = 2.0 / gamma(3.0 - alpha);
    move |t: f64, y: f64| c * t.powf(2.0 - alpha) + t * t - y
}

/// Parameters of the linear oscillator D^{1+λ}U + ω²U = 0 (P ≡ 0, no noise) with restitution
/// r: with λ = 1 and the wall on, the linear impact oscillator of [`impact_oscillator`].
pub fn linear_oscillator(lambda: f64, omega: f64, r: f64) -> Params {
    Params {
        mu0: 1.0,
        omega0: omega,
        lambda,
        restitution: r,
        damping: Damping {
            coefficients: vec![0.0],
        },
        noise_intensity: 0.0,
        correlation_time: 0.0,
    }
}

/// The engine's benchmark case, shared by `benches/engine.rs` and `examples/engine_timing.rs`:
/// Eq. 1 with the fig1 set and μ0 = 0.1 at fractional order λ, barrier on, Δt = 0.01, N steps
/// from (U, U̇) = (2, 0), recording every `every` steps.
pub fn engine_benchmark_case(
    lambda: f64,
    steps: usize,
    memory: Memory,
    every: usize,
) -> Result<(Problem, PredictorCorrector, Options)> {
    let params = crate::model::preset("fig1")?
        .params
        .with("lambda", lambda)?
        .with("mu0", 0.1)?;
    let method = PredictorCorrector {
        dt: 0.01,
        memory,
        ..Default::default()
    };
    let options = Options {
        t_end: steps as f64 * 0.01,
        record_every: every,
        ..Default::default()
    };
    let problem = Problem::from_params(&params)?
        .with_barrier(Barrier::On)?
        .with_start(2.0, 0.0)?;
    Ok((problem, method, options))
}

/// The memory-size case, shared by `tests/soe.rs`, `examples/memory_size.rs` and
/// `examples/engine_timing.rs`: the fig13a set at order λ and noise intensity D (OU noise,
/// the wall on), from (U, U̇) = (7, 0), seed 1, Δt `dt` with `memory` and `impact_memory`, to
/// `t_end`, recording every `every` steps.
pub fn memory_case(
    lambda: f64,
    d: f64,
    (dt, t_end, every): (f64, f64, usize),
    memory: Memory,
    impact_memory: ImpactMemory,
) -> Result<(Problem, PredictorCorrector, Options)> {
    let params = crate::model::preset("fig13a")?
        .params
        .with("lambda", lambda)?
        .with("D", d)?;
    let method = PredictorCorrector {
        dt,
        memory,
        impact_memory,
        ..Default::default()
    };
    let options = Options {
        t_end,
        seed: 1,
        record_every: every,
        ..Default::default()
    };
    Ok((
        Problem::from_params(&params)?.with_start(7.0, 0.0)?,
        method,
        options,
    ))
}

/// Stationary (Var U, Var U̇) of the linear fractional oscillator D^{1+λ}U + μU̇ + ω²U = η,
/// ⟨η(t)η(s)⟩ = (D/τ)e^{−|t−s|/τ} (τ = 0: 2Dδ), from the spectral integrals (adaptive
/// Gauss–Kronrod, breakpoints around the resonance Ω_r^{1+λ} = ω²/sin(πλ/2), the tail mapped
/// by Ω = Ω_c/s). Var U̇ is +∞ for white noise with λ ≤ 1/2 (the integral diverges).
pub fn linear_fractional_moments(lambda: f64, mu: f64, omega: f64, d: f64, tau: f64) -> (f64, f64) {
    let (sn, cs) = (PI * (1.0 + lambda) / 2.0).sin_cos();
    let h2 = |w: f64| {
        let p = w.powf(1.0 + lambda);
        let re = p * cs + omega * omega;
        let im = p * sn + mu * w;
        1.0 / (re * re + im * im)
    };
    let s = |w: f64| 2.0 * d / (1.0 + tau * tau * w * w);
    let resonance = (omega * omega / (PI * lambda / 2.0).sin()).powf(1.0 / (1.0 + lambda));
    let wc = 4.0 * resonance.max(mu) + 1.0;
    let mut cuts = vec![0.0];
    for f in [0.25, 0.5, 0.8, 0.9, 0.95, 1.0, 1.05, 1.1, 1.25, 2.0] {
        cuts.push(f * resonance);
    }
    cuts.push(wc);
    cuts.retain(|&x| x <= wc);
    cuts.sort_by(f64::total_cmp);
    cuts.dedup();
    let integral = |f: &dyn Fn(f64) -> f64| {
        let head = crate::theory::quadrature::integrate_with_breakpoints(f, &cuts, 1e-12);
        let tail = crate::theory::quadrature::integrate_with_breakpoints(
            &|x: f64| {
                if x <= 0.0 {
                    0.0
                } else {
                    f(wc / x) * wc / (x * x)
                }
            },
            &[0.0, 1e-6, 1e-3, 0.1, 1.0],
            1e-12,
        );
        (head + tail) / PI
    };
    let var_u = integral(&|w| s(w) * h2(w));
    let var_v = if tau == 0.0 && lambda <= 0.5 {
        f64::INFINITY
    } else {
        integral(&|w| s(w) * w * w * h2(w))
    };
    (var_u, var_v)
}

/// Parameters of the linear fractional oscillator of [`linear_fractional_moments`] (P ≡ −1,
/// so −μ0P(U)U̇ = +μU̇), to be run with the barrier off.
pub fn linear_fractional_oscillator(lambda: f64, mu: f64, omega: f64, d: f64, tau: f64) -> Params {
    Params {
        mu0: mu,
        omega0: omega,
        lambda,
        restitution: 1.0,
        damping: Damping {
            coefficients: vec![-1.0],
        },
        noise_intensity: d,
        correlation_time: tau,
    }
}

/// (U, U̇, impacts so far) of the linear impact oscillator at time t.
pub fn impact_oscillator(omega: f64, r: f64, v0: f64, t: f64) -> (f64, f64, usize) {
    let half = PI / omega;
    let k = (t / half).floor();
    let a = v0 / omega * r.powf(k);
    let s = omega * (t - k * half);
    (a * s.sin(), a * omega * s.cos(), k as usize)
}

/// Least-squares slope of log(error) against log(step): the observed order of accuracy.
pub fn observed_order(steps: &[f64], errors: &[f64]) -> f64 {
    let n = steps.len() as f64;
    let xs: Vec<f64> = steps.iter().map(|h| h.ln()).collect();
    let ys: Vec<f64> = errors.iter().map(|e| e.ln()).collect();
    let mx = xs.iter().sum::<f64>() / n;
    let my = ys.iter().sum::<f64>() / n;
    let sxy: f64 = xs.iter().zip(&ys).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = xs.iter().map(|x| (x - mx) * (x - mx)).sum();
    sxy / sxx
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spectral_moments_reproduce_the_closed_forms_at_order_one() {
        for &(mu, w, d, tau) in &[
            (0.2, 1.0, 0.1, 0.0),
            (0.05, 0.7, 0.3, 0.5),
            (1.5, 2.0, 1.0, 3.0),
        ] {
            let (vu, vv) = linear_fractional_moments(1.0, mu, w, d, tau);
            let k = 1.0 + mu * tau + w * w * tau * tau;
            let eu = d * (1.0 + mu * tau) / (mu * w * w * k);
            let ev = d / (mu * k);
            assert!((vu / eu - 1.0).abs() < 1e-9, "Var U {vu} vs {eu}");
            assert!((vv / ev - 1.0).abs() < 1e-9, "Var V {vv} vs {ev}");
        }
        // white noise at λ ≤ 1/2: Var U̇ diverges; Var U stays finite and grows as λ falls
        let (vu, vv) = linear_fractional_moments(0.4, 0.2, 1.0, 0.1, 0.0);
        assert!(vv.is_infinite() && vu.is_finite() && vu > 0.0);
    }

    #[test]
    fn exact_solutions_are_consistent() {
        // α = 1: D y = f(t, y) with y exact; check y′ = f by central differences
        let f = diethelm_rhs(1.0);
        for &t in &[0.2, 0.5, 0.9] {
            let d = 1e-5;
            let dy = (diethelm_exact(1.0, t + d) - diethelm_exact(1.0, t - d)) / (2.0 * d);
            assert!((dy - f(t, diethelm_exact(1.0, t))).abs() < 1e-6);
        }
        // λ = 1: E_2(−ω²t²) = cos ωt
        let (u, v) = oscillation(1.0, 1.5, 0.8).unwrap();
        assert!((u - (1.2f64).cos()).abs() < 1e-13);
        assert!((v + 1.5 * (1.2f64).sin()).abs() < 1e-13);
        assert!((relaxation(1.0, 0.7).unwrap() - (-0.7f64).exp()).abs() < 1e-14);
        let (u, v, k) = impact_oscillator(2.0, 0.5, 1.0, PI / 2.0 + 0.1);
        assert_eq!(k, 1);
        assert!((u - 0.25 * (0.2f64).sin()).abs() < 1e-15);
        assert!((v - 0.5 * (0.2f64).cos()).abs() < 1e-15);
        assert!((observed_order(&[0.1, 0.05, 0.025], &[2e-2, 5e-3, 1.25e-3]) - 2.0).abs() < 1e-12);
    }
}
