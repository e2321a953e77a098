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
use crate::engine::{Barrier, Options, Oscillator, PredictorCorrector};
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

/// Stationary variance D/τ of the OU forcing.
pub fn ou_variance(intensity: f64, correlation_time: f64) -> f64 {
    intensity / correlation_time
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
) -> Result<(Oscillator, PredictorCorrector, Options)> {
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
        u0: 2.0,
        v0: 0.0,
        barrier: Barrier::On,
        record_every: every,
        ..Default::default()
    };
    Ok((Oscillator::new(&params)?, method, options))
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
