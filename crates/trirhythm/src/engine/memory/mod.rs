//! The memory of one path: J^λ g over the whole history, kept exactly over a short window and
//! by the verified sum of exponentials of [`super::kernel`] beyond it.
//!
//! # Equation
//! J^λ g(t) = (1/Γ(λ)) ∫₀ᵗ (t − s)^{λ−1} g(s) ds for g piecewise linear on the grid t_n = n·h
//! (split at impacts), λ ∈ (0, 1]: the memory term of the Caputo derivative in Eq. (1). The same
//! [`History`] keeps each fractional term's m_j = J^{1−α_j}U̇ = D^{α_j}U (the memory of V, order
//! 1 − α_j, its pieces split at impacts where V jumps; module docs of `engine::stepper::general`).
//!
//! # Method
//! The last w − 1 pieces of g (piecewise linear, split in two at impacts) are held as
//! (left, right) pairs in a mirrored ring, so the weighted sum of the older ones is one dot
//! product over a contiguous run of doubles (rounded up to a multiple of four, zero weights in
//! front: no scalar tail); a piece leaving the window enters every
//! exponential mode by the exact recursion Y ← e^{−sΔt}Y + Δtψ g_start + Δt(φ − ψ) g_end (four
//! lanes at a time, no fused multiply–add, so the bits do not depend on the CPU), and the lumped
//! slow rates (a cubic in t, see [`super::kernel`]) by the moments m_k = ∫(t_m − s)ᵏ g ds,
//! k ≤ 3, advanced exactly by the binomial theorem. At λ = 1 there is no window: J¹g is the
//! running trapezoidal integral. `Direct` keeps every piece (the O(N) reference). The history
//! is linear in g, so a perturbed copy is renormalised toward its reference number by number,
//! the whole memory included ([`History::contract_toward`], Benettin's method for the
//! fractional state).
//!
//! A split piece may carry a point mass at its impact ([`Split::mass`], in g·Δt; only a
//! tangent's history has one: the derivative of its reference's split piece in θ, module docs
//! of `engine::stepper::tangent`). It is weighed with the kernel itself — (h^λ/Γ(λ))·u^{λ−1}
//! at u steps in the window and the direct memory, e^{−sℓ} into each mode and ℓᵏ into the
//! moments when it leaves the window (ℓ its distance from the window's new start) — so that it
//! is carried as exactly as the linear pieces. For the tangent's impact step the history also
//! gives the derivatives in θ of its value at an instant inside the step and of a split
//! current step ([`History::at_fraction_rate`], [`History::current_split_rate`]), from the
//! derivatives of the interval weights under their limits.
//!
//! # Cost and the step's dependency chain
//! The step's critical path runs through the memory: the newest piece (g_n, computed from
//! V_n) enters J for the next step, which gives V_{n+1}. Everything else — the modes advanced
//! by the piece leaving the window (7 steps old with the default 8-step window), the lumped
//! terms, the window's 6 older pieces — does not depend on it. The fast path ([`History::push`] for an unsplit piece that
//! does not push a split piece out of the window, all but two steps per impact) therefore sums
//! all of that first and adds the newest piece last, with its weights pre-multiplied by
//! h^λ/Γ(λ): two operations on the chain instead of a 7-term dot product, and the rest
//! overlaps with the step. The mode sums Σ out·Y run in two accumulators (even and odd blocks
//! of four), halving the serial additions; the part a·l + b·r of each mode, independent of Y,
//! is formed first. The AVX versions do the portable versions' operations in the same order
//! (no FMA): same bits on every CPU (unit test `portable_and_avx_memories_give_the_same_bits`).
//! The moments advance over a full step with their coefficients (powers of Δt over the
//! binomial and the pieces' integers) computed once.
//! A split piece inside the window adds its exact-minus-plain weights, tabulated for every
//! distance once when it is pushed; pushing a split piece, a split piece leaving the window,
//! `Direct` and the first steps take the general path. At λ = 1 a push is one addition to the
//! running integral.
//!
//! What bounds the cost (measured, see the README's Simulation section): with 41 modes (λ =
//! 0.998, 10⁷ steps, 1e-10) the mode update is 11 four-lane blocks of 4 multiplies, 3 adds and
//! one store per step, plus ~14 multiply–adds of the window: throughput work of the same order
//! as the step's own dependency chain (two evaluations of P, a division). Impacts cost ~4 µs
//! each at λ < 1 (the split's weight table, the Volterra value at the impact instant, the
//! split piece entering every mode with its own exponential). Updating the modes in blocks of
//! B steps does not reduce the work: every piece still needs its two weights in every mode
//! and every step its own output weights (about 6 instead of 7 flops per mode and step at
//! B = 4), so it is not used.
//!
//! # Memory size
//! The default [`Memory::Auto`] asks the kernel for the tolerance ε = 10⁻⁵·Δt² ([`step_tolerance`],
//! within [10⁻¹⁰, 10⁻⁶]; 10⁻⁹ at Δt = 0.01), chosen by the error the memory causes in the
//! solution rather than in the kernel: max |U_SOE(ε) − U_Direct| over a path must stay below a
//! tenth of the scheme's own error max |U_Δt − U_Δt/2|. Measured on the fig13a set (μ0 = 0.005,
//! r = 0.99, wall on, U(0) = 7, T = 1000) at λ ∈ {0.3, 0.5, 0.8, 0.95, 0.995, 0.998, 0.999}:
//! - the memory's error grows like ε·T and does not depend on Δt (λ = 0.998, ε = 10⁻¹⁰:
//!   1.04·10⁻⁷ at Δt = 0.01 and at Δt = 0.001); the scheme's like Δt²·T (2.3·10⁻² and
//!   2.3·10⁻⁴). Their ratio depends on ε/Δt² only, hence the rule's form;
//! - at Δt = 0.01 the deterministic paths allow ε = 10⁻⁷ (worst ratio 0.062, λ = 0.95); the
//!   noisy paths (OU noise D = 0.1, τ = 0.5, seed 1, both impact memories, measured against the
//!   deterministic path's scheme error, since the noise is not nested under halving Δt) bring it
//!   to 10⁻⁹ (λ = 0.998 continuous: 0.014 at 10⁻⁹, 0.15 at 10⁻⁸; λ = 0.8 restart: 4·10⁻⁴ at
//!   10⁻⁹, 0.014 at 3·10⁻⁹, 0.067 at 10⁻⁸);
//! - a noisy path that amplifies every perturbation breaks the bound: λ = 0.999 continuous at
//!   every tolerance (0.17 at 10⁻¹³), every noisy λ = 0.998 path by T = 10⁴, and λ = 0.995
//!   restart at 10⁻⁹ (0.30 of the scheme's error; 0.052 at 10⁻¹⁰). Only the statistics of such
//!   paths are defined, and those are what the figures compare (CHANGELOG, the memory's size).
//!
//! The kernel needs about a fifth fewer exponentials at 10⁻⁹ than at 10⁻¹⁰ (λ = 0.998: 26
//! against 32 at 10⁵ steps, 29 against 36 at 10⁶), but the modes are a small part of a step
//! (Cost, above): a noisy path takes 1.4–2.3 % fewer instructions at 10⁶ steps (λ = 0.5 …
//! 0.998, counted by cachegrind), a gain below what timings on a shared machine resolve.
//! [`Memory::SumOfExponentials`] keeps any tolerance explicitly
//! ([`PREVIOUS_DEFAULT_TOLERANCE`] reproduces the earlier paths). `tests/soe.rs` checks the
//! bound on a deterministic and a noisy path at λ = 0.998 and 0.8, and that a 10⁴ times
//! looser kernel breaks it.
//!
//! # Reference
//! Diethelm, Ford & Freed, Nonlinear Dyn. 29 (2002) 3–22 (product trapezoidal rule); Jiang,
//! Zhang, Zhang & Zhang, Commun. Comput. Phys. 21 (2017) 650–678 (sum of exponentials).
//!
//! # Tests
//! Unit tests in `tests.rs` (the scalar solver at order 1 is the trapezoidal PECE by hand; scaling the
//! history equals the history of the scaled g, for both memories, with a split piece; the
//! portable and AVX fast paths give the same bits; every window of 2 … 10 steps, padded or
//! not, agrees with `Direct` to 10⁻¹⁰; a point mass and two lines are the θ-derivative of a
//! split piece, against differences in θ, in the window and in the modes, for both memories;
//! the rates in θ against differences of `at_fraction` and `current_split`);
//! `tests/soe.rs` (SOE against Direct on Eq. 1); `tests/fractional.rs` (the fractional terms'
//! memories of V against Direct, and their known answers).
//!
//! # Layout
//! - `window`: the exact local window (the mirrored ring of the last pieces, its dot product);
//! - `modes`: the exponential (SOE) modes and their exact recursion;
//! - `moments`: the lumped slow rates' moments m_k;
//! - `history`: [`History`], the whole memory of one path, and its fast path;
//! - `general`: the general path of a push (split pieces, the direct memory, λ = 1);
//! - `state`: the history as numbers (restart, scaling, renormalisation, comparisons);
//! - `scalar`: [`solve_scalar`], scalar Caputo problems on the same memory;
//! - `probe`: [`probe_memory`], the memory's own cost per step.

mod general;
mod history;
mod modes;
mod moments;
mod probe;
mod scalar;
mod state;
#[cfg(test)]
mod tests;
mod window;

use super::kernel::{IntervalWeights, Powers};
use crate::error::{Error, Result};

pub(crate) use history::History;
pub use probe::probe_memory;
pub use scalar::solve_scalar;

/// How the history of J^λ g is kept.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Memory {
    /// The exact product-integration weights over the whole history: O(N) work per step.
    /// The reference, for tests and short runs.
    Direct,
    /// Exact weights over a short local window, a verified sum of exponentials beyond it.
    SumOfExponentials {
        /// Relative tolerance of the kernel approximation on [window·Δt, T] (e.g. 1e-9).
        tolerance: f64,
    },
    /// The default: [`Memory::SumOfExponentials`] with the tolerance [`step_tolerance`]`(Δt)`,
    /// sized by the error it causes in the solution (a tenth of the scheme's own at most;
    /// module docs, Memory size).
    Auto,
}

/// The kernel tolerance of [`Memory::Auto`] for the step Δt: 10⁻⁵·Δt² (10⁻⁹ at Δt = 0.01,
/// 2.5·10⁻¹⁰ at 0.005), kept in [[`AUTO_TOLERANCE_MIN`], [`AUTO_TOLERANCE_MAX`]]. The memory's
/// error in the solution grows like tolerance × T and the scheme's own like Δt² × T (both
/// measured; module docs, Memory size), so their ratio depends on tolerance/Δt² only: the
/// constant is the largest (in steps of 10^{1/2}) for which the memory's error stayed below a
/// tenth of the scheme's on the measured paths at Δt = 0.01.
pub fn step_tolerance(dt: f64) -> f64 {
    (AUTO_TOLERANCE_PER_DT2 * dt * dt).clamp(AUTO_TOLERANCE_MIN, AUTO_TOLERANCE_MAX)
}

/// The constant c of [`step_tolerance`] = c·Δt².
pub const AUTO_TOLERANCE_PER_DT2: f64 = 1e-5;
/// Smallest tolerance [`Memory::Auto`] asks for: the previous default, reached at Δt ≈ 0.0032
/// (below it the default paths are those of earlier versions, bit for bit). At Δt = 0.001 it
/// keeps the memory's error below 0.0023 of the scheme's on the measured paths that do not
/// amplify perturbations; a tighter kernel costs exponentials (λ = 0.998, 10⁷ steps: 45 at
/// 10⁻¹¹ against 40) and is not certified for every λ (λ = 10⁻⁶ fails at 10⁻¹¹).
pub const AUTO_TOLERANCE_MIN: f64 = PREVIOUS_DEFAULT_TOLERANCE;
/// Largest tolerance [`Memory::Auto`] asks for (Δt above about 0.3).
pub const AUTO_TOLERANCE_MAX: f64 = 1e-6;

/// Smallest tolerance of [`Memory::SumOfExponentials`] (exclusive): the kernel's quadrature
/// cannot certify less in double precision.
pub const MIN_TOLERANCE: f64 = 1e-15;
/// Largest tolerance of [`Memory::SumOfExponentials`] (exclusive): a looser kernel is no
/// longer the fractional memory.
pub const MAX_TOLERANCE: f64 = 1e-2;

impl Memory {
    /// Check the memory: a sum of exponentials needs a tolerance in
    /// ([`MIN_TOLERANCE`], [`MAX_TOLERANCE`]).
    pub fn validate(&self) -> Result<()> {
        match *self {
            Memory::Direct | Memory::Auto => Ok(()),
            Memory::SumOfExponentials { tolerance } => {
                if tolerance > MIN_TOLERANCE && tolerance < MAX_TOLERANCE {
                    Ok(())
                } else {
                    Err(Error::invalid("tolerance", tolerance, "(1e-15, 1e-2)"))
                }
            }
        }
    }
}

impl Memory {
    /// The kernel tolerance of this memory at step `dt` (None for [`Memory::Direct`]).
    pub fn tolerance(&self, dt: f64) -> Option<f64> {
        match *self {
            Memory::Direct => None,
            Memory::SumOfExponentials { tolerance } => Some(tolerance),
            Memory::Auto => Some(step_tolerance(dt)),
        }
    }
}

/// The tolerance of [`Memory::default`] before [`Memory::Auto`] (for every Δt): keep it explicitly with
/// `Memory::SumOfExponentials { tolerance: PREVIOUS_DEFAULT_TOLERANCE }` to reproduce earlier
/// paths bit for bit.
pub const PREVIOUS_DEFAULT_TOLERANCE: f64 = 1e-10;

impl Default for Memory {
    /// [`Memory::Auto`].
    fn default() -> Self {
        Memory::Auto
    }
}

/// Default number of steps in the exact local window of [`Memory::SumOfExponentials`]. Any
/// window ≥ 2 is exact (the kernel beyond it is certified to the tolerance and split pieces
/// enter the modes exactly); 8 costs about two more exponentials than 16 but half the window's
/// dot product and half the work per impact (the split's weights at each distance).
pub const DEFAULT_WINDOW: usize = 8;

/// An impact inside an interval: g jumps at the fraction `theta` of the step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Split {
    /// Position of the impact in the step, θ ∈ (0, 1).
    pub theta: f64,
    /// g just before the impact.
    pub before: f64,
    /// g just after the impact.
    pub after: f64,
    /// False when the memory restarted at the impact (the part before it is forgotten).
    pub keep_before: bool,
    /// A point mass at the impact, in units of g·Δt: its contribution to J^λ at u steps after
    /// the impact is (h^λ/Γ(λ))·mass·u^{λ−1}. Always 0 in a path's own history; a tangent's
    /// history holds there the derivative of its reference's split piece in θ, whose jump
    /// moves with the impact (module docs of `engine::stepper::tangent`).
    pub mass: f64,
}

/// One completed step of g: linear from `left` to `right`, or two linear pieces when split.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Piece {
    pub left: f64,
    pub right: f64,
    pub split: Option<Split>,
}

/// Weights (of `left`, `right`) of an unsplit piece at distance p plus, when split, the
/// exact contribution, all in units where the scale h^λ/Γ(λ) is left out.
/// The powers of the weights' closed form are taken from and kept in `memo` (neighbouring
/// pieces share their ends).
pub(super) fn piece_integral(
    weights: &IntervalWeights,
    piece: &Piece,
    p: f64,
    memo: &mut Powers,
) -> f64 {
    match piece.split {
        None => {
            let (wa, wb) = weights.of_with(p, p + 1.0, memo);
            wa * piece.right + wb * piece.left
        }
        Some(s) => {
            let mid = p + 1.0 - s.theta;
            let (wa, wb) = weights.of_with(p, mid, memo);
            let mut v = wa * piece.right + wb * s.after;
            if s.keep_before {
                let (wa, wb) = weights.of_with(mid, p + 1.0, memo);
                v += wa * s.before + wb * piece.left;
            }
            if s.mass != 0.0 {
                v += s.mass * weights.kernel_with(mid, memo);
            }
            v
        }
    }
}

/// d/dp of [`piece_integral`] (every distance of the piece moved by the same amount: the
/// evaluation time moving later), from the weights' own derivatives
/// ([`IntervalWeights::shift_rates_with`]). p > 0 for λ < 1.
pub(super) fn piece_shift_rate(
    weights: &IntervalWeights,
    piece: &Piece,
    p: f64,
    memo: &mut Powers,
) -> f64 {
    match piece.split {
        None => {
            let (_, (da, db)) = weights.shift_rates_with(p, p + 1.0, memo);
            da * piece.right + db * piece.left
        }
        Some(s) => {
            let mid = p + 1.0 - s.theta;
            let (_, (da, db)) = weights.shift_rates_with(p, mid, memo);
            let mut v = da * piece.right + db * s.after;
            if s.keep_before {
                let (_, (da, db)) = weights.shift_rates_with(mid, p + 1.0, memo);
                v += da * s.before + db * piece.left;
            }
            if s.mass != 0.0 {
                // d/du u^{λ−1} = (λ − 1)u^{λ−1}/u
                let lambda = weights.lambda();
                v += s.mass * (lambda - 1.0) * weights.kernel_with(mid, memo) / mid;
            }
            v
        }
    }
}
