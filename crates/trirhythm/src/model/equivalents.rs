//! Harmonic-balance equivalents of the fractional term (Eq. 4–5 of the paper).
//!
//! # Equation
//! Over a cycle of frequency ω0 the fractional term is replaced by an equivalent damping and
//! stiffness (harmonic balance), which turns Eq. (1) into the integer-order Eq. (5):
//! Ü − μ1(β1 − c0 + P(U))U̇ + ω1²U = β2η with
//! μ1 = μ0ω0^{1−λ}/sin(πλ/2), β1 = c0 − ω0^λcos(πλ/2)/μ0, ω1² = ω0^{3−λ}/sin(πλ/2),
//! β2 = ω0^{1−λ}/sin(πλ/2).
//!
//! # Tests
//! `tests/averaging.rs` checks the four coefficients against an independent mpmath evaluation
//! (`tests/reference/averaging_reference.py`) to 1e-13; `tests/systems.rs` checks that Eq. (5)
//! at λ = 1 is Eq. (1).

use crate::maths::{pow, sin};
use crate::model::Params;
use std::f64::consts::PI;

/// Harmonic-balance equivalents of the fractional term (Eq. 4–5).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Equivalents {
    /// μ1 = μ0 ω0^{1−λ} / sin(πλ/2).
    pub mu1: f64,
    /// β1 = c0 − ω0^λ cos(πλ/2) / μ0 (c0 = 1 for the paper's polynomial).
    pub beta1: f64,
    /// ω1 = sqrt(ω0^{3−λ} / sin(πλ/2)).
    pub omega1: f64,
    /// β2 = ω0^{1−λ} / sin(πλ/2).
    pub beta2: f64,
}

impl Equivalents {
    /// Eq. 5's coefficients; `params` must be valid.
    pub fn new(params: &Params) -> Self {
        Self::from_scalars(
            params.mu0,
            params.omega0,
            params.lambda,
            params.damping.coefficient(0),
        )
    }

    /// Eq. 5's coefficients from μ0, ω0, λ and the constant term c0 of P(U), without allocating
    /// (the bifurcation maps call this per grid point).
    #[inline]
    pub fn from_scalars(mu0: f64, omega0: f64, lambda: f64, c0: f64) -> Self {
        let (l, w0) = (lambda, omega0);
        let s = sin(PI * l / 2.0);
        // cos(πλ/2) = sin(π(1−λ)/2): 1 − λ is exact near λ = 1, so no cancellation.
        let c = sin(PI * (1.0 - l) / 2.0);
        Equivalents {
            mu1: mu0 * pow(w0, 1.0 - l) / s,
            beta1: c0 - pow(w0, l) * c / mu0,
            omega1: (pow(w0, 3.0 - l) / s).sqrt(),
            beta2: pow(w0, 1.0 - l) / s,
        }
    }
}
