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
//!   averaging, stationary PDFs, barriers), depending on `model` and `polynomial` only.
//!
//! The library computes; it does no file I/O and prints nothing. The `trirhythm` binary writes.

pub mod averaging;
pub mod bifurcation;
pub mod error;
pub mod model;
pub mod polynomial;
pub mod quadrature;

pub use error::{Error, Result};
pub use model::{Damping, Params, Preset};
