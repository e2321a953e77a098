//! # trirhythm
//!
//! Stochastic fractional-order vibro-impact oscillators with several coexisting limit cycles,
//!
//! D^{1+λ}U − μ0 P(U) U̇ + ω0² U = η(t),  U > 0;   U̇₊ = −r U̇₋ at U = 0,
//!
//! with P(U) = 1 − U² + α0U⁴ − β0U⁶ + γ0U⁸ − δ0U¹⁰ (any even degree is supported) and η an
//! Ornstein–Uhlenbeck noise with ⟨η(t)η(s)⟩ = (D/τ)e^{−|t−s|/τ}.
//!
//! Layers, with dependencies pointing one way (a layer uses only those above it):
//! - [`error`], [`maths`] (exp, ln, pow, sin, cos, normal deviates: the same bits on every
//!   platform), [`special`] (Γ, Mittag-Leffler): the foundation;
//! - [`model`]: parameters, validation, the paper's presets, the Eq. 5 equivalents;
//! - [`theory`]: the averaged theory (harmonic balance, stochastic averaging, stationary PDFs,
//!   certified polynomial roots, quadrature, bifurcation maps and fold curves);
//! - [`engine`]: the simulation (memory kernels, noise, the stepper with impacts, drivers); it
//!   does not import the theory;
//! - [`analysis`]: analyses of simulated paths, where simulation and theory meet (recurrence
//!   quantification, ensembles with stationary statistics and the theory against them,
//!   oscillation boundaries);
//! - [`monitor`]: the one convention for watching a long call (progress, finished pieces,
//!   cancellation);
//! - [`known_answers`]: problems with exact solutions, shared by tests and benchmarks;
//! - [`non_finite`]: serde for numbers that may be NaN or ±∞;
//! - [`profile`]: the parallel profile of a long call (CPU time, critical path, speed-up bound).
//!
//! The library computes; it does no file I/O and prints nothing. The `trirhythm` binary writes.

pub mod analysis;
pub mod engine;
pub mod error;
pub mod known_answers;
pub mod maths;
pub mod model;
pub mod monitor;
pub mod non_finite;
pub mod profile;
pub mod special;
pub mod theory;

pub use error::{Error, Result};
pub use model::{Damping, Params, Preset};

/// The README's Rust examples, compiled and run as doctests so that they cannot rot.
#[cfg(doctest)]
#[doc = include_str!("../../../README.md")]
pub struct ReadmeDoctests;
