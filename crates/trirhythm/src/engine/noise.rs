//! The random forcing η(t) of Eq. (1) on a uniform grid, with seeded per-path streams.
//!
//! # Equation
//! Ornstein–Uhlenbeck noise with ⟨η(t)η(s)⟩ = (D/τ) e^{−|t−s|/τ}, i.e.
//! dη = −η/τ dt + (√(2D)/τ) dW; as τ → 0 it becomes white noise with ⟨η(t)η(s)⟩ = 2D δ(t−s).
//!
//! # Method
//! - Coloured (τ > 0): the exact OU update η_{n+1} = ρ η_n + √(D/τ) √(1 − ρ²) ξ_n,
//!   ρ = e^{−Δt/τ}, from a stationary start η_0 ~ N(0, D/τ), sampled **jointly** with the exact
//!   step integral I_n = ∫ η over the step (Gaussian given η_n: mean τ(1−ρ)η_n, variance
//!   2D[Δt − 2τ(1−ρ) + τ(1−ρ²)/2], covariance with η_{n+1} D(1−ρ)²). Inside a step η is
//!   represented by its step mean I_n/Δt, so every step integral has the exact law whatever
//!   Δt/τ (linear interpolation between node values over-forces by Δt/(4τ) when τ ≪ Δt and
//!   cannot reach the white-noise limit).
//! - White (τ = 0): η is constant on each step, η = √(2D/Δt) ξ_n, so that ∫ η over a step has
//!   exactly the variance 2DΔt of the white-noise increment. (Linear interpolation between node
//!   samples of variance 2D/Δt would give variance (2/3)·2DΔt for the step integral: wrong.)
//!   The interval carries the pair (η_n, η_n); g is then discontinuous at the nodes, which the
//!   product integration of [`crate::engine::kernel`] handles piece by piece.
//! - Streams: path i of seed S draws from `ChaCha8Rng::seed_from_u64(S)` with stream i, so a
//!   path does not depend on which thread computes it or on the other paths. Deviates are drawn
//!   in blocks of 256 (the ziggurat of [`crate::maths::standard_normal`], the same bits on every
//!   platform): the same sequence as one at a time, at about a third of the cost.
//!
//! # Reference
//! Gillespie, Phys. Rev. E 54 (1996) 2084 (exact OU update).
//!
//! # Tests
//! Unit tests below: stationary variance D/τ and lag correlation e^{−kΔt/τ} within Monte Carlo
//! error bars; white-noise step integrals of variance 2DΔt; streams reproducible and distinct.

use crate::error::{Error, Result};
use crate::maths::{exp, expm1, standard_normal};
use crate::model::Params;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

/// The kind of forcing.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Noise {
    /// No forcing (D = 0).
    None,
    /// White noise ⟨η(t)η(s)⟩ = 2D δ(t−s).
    White {
        /// Intensity D.
        intensity: f64,
    },
    /// Ornstein–Uhlenbeck noise ⟨η(t)η(s)⟩ = (D/τ) e^{−|t−s|/τ}.
    Colored {
        /// Intensity D.
        intensity: f64,
        /// Correlation time τ > 0.
        correlation_time: f64,
    },
}

impl Noise {
    /// The forcing of a parameter set: none when D = 0, white when τ = 0.
    pub fn from_params(params: &Params) -> Self {
        let d = params.noise_intensity;
        let tau = params.correlation_time;
        if d == 0.0 {
            Noise::None
        } else if tau == 0.0 {
            Noise::White { intensity: d }
        } else {
            Noise::Colored {
                intensity: d,
                correlation_time: tau,
            }
        }
    }

    /// True for [`Noise::None`].
    pub fn is_none(&self) -> bool {
        matches!(self, Noise::None)
    }
}

/// The random generator of path `path` of an experiment seeded with `seed`.
pub fn path_rng(seed: u64, path: u64) -> ChaCha8Rng {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(path);
    rng
}

/// The numbers that define [`NoiseStream::next_step`] for one (kind, D, τ, Δt), all computed on
/// the host by [`NoiseStream::new`]; with ξ, ξ₁, ξ₂ the stream's next standard normal deviates
/// ([`crate::maths::standard_normal`]) the step is
/// - kind [`StepConstants::NONE`]: (0, 0), no deviate drawn;
/// - kind [`StepConstants::WHITE`]: w = σ·ξ, the pair (w, w), and the state becomes w;
/// - kind [`StepConstants::COLORED`]: with η_n the state, m = (mean_coef·η_n + cross·ξ₁ +
///   rest·ξ₂)/Δt, the pair (m, m), and the state becomes ρ·η_n + σ·ξ₁; the state starts at
///   sd·ξ (the stream's first deviate), before any step.
///
/// Every operation in that order, as IEEE double operations without fused multiply–add.
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C)]
pub struct StepConstants {
    /// The kind: [`StepConstants::NONE`] (0), [`StepConstants::WHITE`] (1) or
    /// [`StepConstants::COLORED`] (2, Ornstein–Uhlenbeck).
    pub kind: u32,
    /// ρ = e^{−Δt/τ}, the OU node value's decay over a step (0 unless coloured).
    pub rho: f64,
    /// σ: the white level's standard deviation √(2D/Δt), or the OU innovation's
    /// √(D/τ)·√(1 − ρ²) (0 with no noise).
    pub sigma: f64,
    /// τ(1 − ρ): the OU step integral's mean per unit of η_n (0 unless coloured).
    pub mean_coef: f64,
    /// Cov(I_n, η_{n+1} | η_n)/σ: the step integral's part along the innovation ξ₁.
    pub cross: f64,
    /// The step integral's remaining standard deviation, along ξ₂.
    pub rest: f64,
    /// The step Δt.
    pub dt: f64,
    /// √(D/τ), the OU stationary standard deviation of the start η_0 = sd·ξ (0 unless coloured).
    pub sd: f64,
}

impl StepConstants {
    /// [`StepConstants::kind`] of [`Noise::None`].
    pub const NONE: u32 = 0;
    /// [`StepConstants::kind`] of [`Noise::White`].
    pub const WHITE: u32 = 1;
    /// [`StepConstants::kind`] of [`Noise::Colored`] (Ornstein–Uhlenbeck).
    pub const COLORED: u32 = 2;
}

/// Successive steps of η on a grid of step Δt: each call of [`NoiseStream::next_step`] gives
/// the forcing on the next step as the values at its start and end of the function used inside
/// it (both equal to the step mean: η is piecewise constant with exact step integrals).
#[derive(Debug, Clone)]
pub struct NoiseStream {
    rng: ChaCha8Rng,
    kind: Noise,
    rho: f64,
    sigma: f64,
    state: f64,
    /// I | η_n = mean_coef·η_n + cross·ξ₁ + rest·ξ₂
    mean_coef: f64,
    cross: f64,
    rest: f64,
    dt: f64,
    /// √(D/τ), the stationary standard deviation of the OU node value (0 otherwise).
    sd: f64,
    /// Standard normal deviates drawn ahead in blocks (the same sequence as drawing them one
    /// by one, several times faster: the generator and the ziggurat pipeline over a block).
    normals: Box<[f64; BLOCK]>,
    next: usize,
}

/// Deviates drawn per block.
const BLOCK: usize = 256;

impl NoiseStream {
    /// A stream for path `path` of `seed`; the OU process starts from its stationary law.
    pub fn new(kind: Noise, dt: f64, seed: u64, path: u64) -> Result<Self> {
        if !(dt > 0.0 && dt.is_finite()) {
            return Err(Error::invalid("dt", dt, "(0, ∞), finite"));
        }
        let mut rng = path_rng(seed, path);
        let (mut mean_coef, mut cross, mut rest, mut stationary_sd) = (0.0, 0.0, 0.0, 0.0);
        let (rho, sigma, state) = match kind {
            Noise::None => (0.0, 0.0, 0.0),
            Noise::White { intensity } => {
                if !(intensity >= 0.0 && intensity.is_finite()) {
                    return Err(Error::invalid("D", intensity, "[0, ∞), finite"));
                }
                (0.0, (2.0 * intensity / dt).sqrt(), 0.0)
            }
            Noise::Colored {
                intensity,
                correlation_time,
            } => {
                if !(intensity >= 0.0 && intensity.is_finite()) {
                    return Err(Error::invalid("D", intensity, "[0, ∞), finite"));
                }
                if !(correlation_time > 0.0 && correlation_time.is_finite()) {
                    return Err(Error::invalid("tau", correlation_time, "(0, ∞), finite"));
                }
                let rho = exp(-dt / correlation_time);
                let sd = (intensity / correlation_time).sqrt();
                // √(1 − ρ²) = √(−expm1(−2Δt/τ)), accurate for Δt ≪ τ
                let tau = correlation_time;
                let one_minus_rho = -expm1(-dt / tau);
                let one_minus_rho2 = -expm1(-2.0 * dt / tau);
                let sigma = sd * one_minus_rho2.sqrt();
                let var_i =
                    2.0 * intensity * (dt - 2.0 * tau * one_minus_rho + 0.5 * tau * one_minus_rho2);
                let cov = intensity * one_minus_rho * one_minus_rho;
                mean_coef = tau * one_minus_rho;
                cross = if sigma > 0.0 { cov / sigma } else { 0.0 };
                rest = (var_i - cross * cross).max(0.0).sqrt();
                stationary_sd = sd;
                let xi = standard_normal(&mut rng);
                (rho, sigma, sd * xi)
            }
        };
        Ok(NoiseStream {
            rng,
            kind,
            rho,
            sigma,
            state,
            mean_coef,
            cross,
            rest,
            dt,
            sd: stationary_sd,
            normals: Box::new([0.0; BLOCK]),
            next: BLOCK,
        })
    }

    /// Draw the future deviates from stream `path` of `seed` instead, keeping the present
    /// state (the OU node value η_n): a copy of a path that branches off with noise of its own.
    pub fn renoise(&mut self, seed: u64, path: u64) {
        self.rng = path_rng(seed, path);
        self.next = BLOCK;
    }

    /// The constants of [`NoiseStream::next_step`] (computed by [`NoiseStream::new`]), for a
    /// re-implementation of the step elsewhere that must give the same bits (the GPU kernel of
    /// `trirhythm-gpu`, whose C copy of the step takes them from the host).
    pub fn step_constants(&self) -> StepConstants {
        let kind = match self.kind {
            Noise::None => StepConstants::NONE,
            Noise::White { .. } => StepConstants::WHITE,
            Noise::Colored { .. } => StepConstants::COLORED,
        };
        StepConstants {
            kind,
            rho: self.rho,
            sigma: self.sigma,
            mean_coef: self.mean_coef,
            cross: self.cross,
            rest: self.rest,
            dt: self.dt,
            sd: self.sd,
        }
    }

    /// The current node value η_n (coloured), the last step's level (white), or 0.
    pub fn current(&self) -> f64 {
        self.state
    }

    /// The next standard normal deviate of the stream (the block refill out of line: the
    /// step inlines only the read).
    #[inline(always)]
    fn normal(&mut self) -> f64 {
        if self.next == BLOCK {
            self.refill();
        }
        let x = self.normals[self.next];
        self.next += 1;
        x
    }

    /// Draw the next block of deviates.
    #[cold]
    #[inline(never)]
    fn refill(&mut self) {
        for x in self.normals.iter_mut() {
            *x = standard_normal(&mut self.rng);
        }
        self.next = 0;
    }

    /// The forcing on the next step: (value at its start, value at its end).
    #[inline(always)]
    pub fn next_step(&mut self) -> (f64, f64) {
        match self.kind {
            Noise::None => (0.0, 0.0),
            Noise::White { .. } => {
                let w = self.sigma * self.normal();
                self.state = w;
                (w, w)
            }
            Noise::Colored { .. } => {
                let x1 = self.normal();
                let x2 = self.normal();
                let start = self.state;
                self.state = self.rho * start + self.sigma * x1;
                let mean = (self.mean_coef * start + self.cross * x1 + self.rest * x2) / self.dt;
                // (a division, not a multiply by 1/Δt: the stream stays the same bits)
                (mean, mean)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const RNG_SEED: u64 = 0x5eed_0003;

    #[test]
    fn ou_stationary_variance_and_correlation() {
        let (d, tau, dt) = (0.3, 0.5, 0.01);
        let kind = Noise::Colored {
            intensity: d,
            correlation_time: tau,
        };
        // many short independent paths: samples at n = 0 and n = lag are exactly
        // (stationary, correlated e^{−lag·dt/τ}); independent across paths
        let paths = 20_000;
        let lag = 25;
        let (mut s0, mut s00, mut s0l) = (0.0, 0.0, 0.0);
        for i in 0..paths {
            let mut st = NoiseStream::new(kind, dt, RNG_SEED, i).unwrap();
            let x0 = st.current();
            let mut x = x0;
            for _ in 0..lag {
                st.next_step();
                x = st.current();
            }
            s0 += x0;
            s00 += x0 * x0;
            s0l += x0 * x;
        }
        let n = paths as f64;
        let var = s00 / n - (s0 / n).powi(2);
        let expect = d / tau;
        // sample variance of a Gaussian: sd = var·√(2/n)
        let sd = expect * (2.0 / n).sqrt();
        assert!(
            (var - expect).abs() < 4.0 * sd,
            "var {var} vs {expect} ± {sd}"
        );
        let corr = s0l / n / expect;
        let rho = (-(lag as f64) * dt / tau).exp();
        // sd of the product mean ≈ √((1 + ρ²)/n)
        let sd_c = ((1.0 + rho * rho) / n).sqrt();
        assert!(
            (corr - rho).abs() < 4.0 * sd_c,
            "corr {corr} vs {rho} ± {sd_c}"
        );
    }

    #[test]
    fn ou_step_integrals_have_the_exact_variance() {
        // stationary: Var ∫₀^h η = 2D[h − τ(1 − e^{−h/τ})], for τ ≫ h, τ ~ h and τ ≪ h
        let d = 0.4;
        let h = 0.01;
        for &tau in &[1.0, 0.01, 0.0005] {
            let kind = Noise::Colored {
                intensity: d,
                correlation_time: tau,
            };
            let mut st = NoiseStream::new(kind, h, RNG_SEED, 7).unwrap();
            let n = 100_000;
            let mut s2 = 0.0;
            for _ in 0..n {
                let (m, _) = st.next_step();
                s2 += (m * h).powi(2);
            }
            let var = s2 / n as f64;
            let expect = 2.0 * d * (h - tau * (-(-h / tau).exp_m1()));
            // consecutive step integrals are correlated: allow for it with a wide band
            let sd = expect * (2.0 / n as f64).sqrt() * (1.0 + 2.0 * tau / h).sqrt();
            assert!(
                (var - expect).abs() < 5.0 * sd,
                "τ = {tau}: {var} vs {expect} ± {sd}"
            );
        }
    }

    #[test]
    fn white_noise_step_integral_has_variance_2d_dt() {
        let (d, dt) = (0.7, 0.02);
        let mut st = NoiseStream::new(Noise::White { intensity: d }, dt, RNG_SEED, 0).unwrap();
        let n = 100_000;
        let mut s2 = 0.0;
        for _ in 0..n {
            let (a, b) = st.next_step();
            let integral = 0.5 * dt * (a + b);
            s2 += integral * integral;
        }
        let var = s2 / n as f64;
        let expect = 2.0 * d * dt;
        let sd = expect * (2.0 / n as f64).sqrt();
        assert!((var - expect).abs() < 4.0 * sd, "{var} vs {expect}");
    }

    #[test]
    fn step_constants_are_the_stream_s() {
        let none = NoiseStream::new(Noise::None, 0.01, RNG_SEED, 0).unwrap();
        assert_eq!(none.step_constants().kind, StepConstants::NONE);
        // white: σ = √(2D/Δt) = √50
        let white = NoiseStream::new(Noise::White { intensity: 0.5 }, 0.02, RNG_SEED, 0).unwrap();
        let c = white.step_constants();
        assert_eq!(
            (c.kind, c.dt, c.rho, c.sd),
            (StepConstants::WHITE, 0.02, 0.0, 0.0)
        );
        assert_eq!(c.sigma, 50f64.sqrt());
        // coloured: the start is sd·ξ with ξ the stream's first deviate, sd = √(D/τ) = √0.6
        let kind = Noise::Colored {
            intensity: 0.3,
            correlation_time: 0.5,
        };
        let mut ou = NoiseStream::new(kind, 0.01, RNG_SEED, 2).unwrap();
        let c = ou.step_constants();
        assert_eq!(c.kind, StepConstants::COLORED);
        assert_eq!(c.sd, 0.6f64.sqrt());
        assert_eq!(c.rho, exp(-0.01 / 0.5));
        let mut rng = path_rng(RNG_SEED, 2);
        let xi = standard_normal(&mut rng);
        assert_eq!(ou.current().to_bits(), (c.sd * xi).to_bits());
        // one step from the constants, the next two deviates
        let (x1, x2) = (standard_normal(&mut rng), standard_normal(&mut rng));
        let mean = (c.mean_coef * ou.current() + c.cross * x1 + c.rest * x2) / c.dt;
        let state = c.rho * ou.current() + c.sigma * x1;
        assert_eq!(ou.next_step(), (mean, mean));
        assert_eq!(ou.current().to_bits(), state.to_bits());
    }

    #[test]
    fn streams_are_reproducible_and_distinct() {
        let kind = Noise::White { intensity: 1.0 };
        let mut a = NoiseStream::new(kind, 0.1, RNG_SEED, 3).unwrap();
        let mut b = NoiseStream::new(kind, 0.1, RNG_SEED, 3).unwrap();
        let mut c = NoiseStream::new(kind, 0.1, RNG_SEED, 4).unwrap();
        let xa: Vec<f64> = (0..10).map(|_| a.next_step().0).collect();
        let xb: Vec<f64> = (0..10).map(|_| b.next_step().0).collect();
        let xc: Vec<f64> = (0..10).map(|_| c.next_step().0).collect();
        assert_eq!(xa, xb);
        assert_ne!(xa, xc);
    }
}
