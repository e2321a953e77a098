//! # trirhythm
//!
//! Stochastic fractional-order vibro-impact oscillators with several coexisting limit cycles,
//!
//! D^{1+λ}U − μ0 P(U) U̇ + ω0² U = η(t),  U > 0;   U̇₊ = −r U̇₋ at U = 0,
//!
//! with P(U) = 1 − U² + α0U⁴ − β0U⁶ + γ0U⁸ − δ0U¹⁰ (any even degree is supported) and η an
//! Ornstein–Uhlenbeck noise with ⟨η(t)η(s)⟩ = (D/τ)e^{−|t−s|/τ}.
//!
//! Modules, with dependencies pointing one way:
//! - [`model`]: parameters, validation, the paper's presets;
//! - [`polynomial`]: real polynomials, certified real-root isolation (Sturm sequences);
//! - [`averaging`]: the analytic theory (harmonic balance, Zhuravlev transformation, stochastic
//!   averaging, stationary PDFs, barriers), depending on `model` and `polynomial` only;
//! - [`noise`]: Ornstein–Uhlenbeck and white forcing on a grid, seeded per-path streams;
//! - [`fractional`]: Γ, Mittag-Leffler, product-integration weights, the verified
//!   sum-of-exponentials kernel and the convolution memory;
//! - [`solver`]: the predictor–corrector driver (Eq. 1 with impacts, Eq. 5, Eq. 9);
//! - [`analysis`]: recurrence plots and their quantification (Eq. 6–7);
//! - [`known_answers`]: problems with exact solutions, shared by tests and benchmarks.
//!
//! The library computes; it does no file I/O and prints nothing. The `trirhythm` binary writes.

pub mod analysis;
pub mod averaging;
pub mod bifurcation;
pub mod error;
pub mod fractional;
pub mod known_answers;
pub mod model;
pub mod noise;
pub mod polynomial;
pub mod quadrature;
pub mod solver;

pub use error::{Error, Result};
pub use model::{Damping, Params, Preset};

/// The README's Rust examples, compiled and run as doctests so that they cannot rot.
#[cfg(doctest)]
#[doc = include_str!("../../../README.md")]
pub struct ReadmeDoctests;
