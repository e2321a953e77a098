//! The lumped slow rates of the sum-of-exponentials kernel: their moments m_k of g.
//!
//! Equation: the lumped part of the kernel is a cubic Σ_k p_k (t − s)ᵏ (see
//! [`crate::engine::kernel`]); its contribution to J^λ g needs only the moments
//! m_k = ∫ (t_m − s)ᵏ g(s) ds, k ≤ 3, of the history before the window's start t_m.
//!
//! Method: the moments move on by a piece exactly by the binomial theorem; over a full step the
//! coefficients are computed once ([`MomentStep`]); at λ = 1 only m₀ = ∫ g is kept.
//!
//! Reference: the binomial shift of polynomial moments (exact for linear pieces).
//!
//! Tests: `moments_advance_exactly` in the memory's unit tests (against Simpson's rule).

use crate::engine::kernel::LUMPED_TERMS;

/// Move the window's start t_m on by ℓ over a linear piece (l → r) of g: the moments
/// m_k = ∫ (t_m − s)ᵏ g(s) ds become Σ_{i≤k} C(k, i) ℓ^{k−i} m_i (the old history, now ℓ
/// further away) + ℓ^{k+1}(l/(k + 2) + r/((k + 1)(k + 2))) (the piece). With a `flat` kernel
/// (λ = 1) only m₀ = ∫ g is kept, by the trapezoidal rule.
#[inline(always)]
pub(super) fn advance_moments(m: &mut [f64; LUMPED_TERMS], flat: bool, len: f64, l: f64, r: f64) {
    if !flat {
        let [m0, m1, m2, m3] = *m;
        let (h, h2) = (len, len * len);
        let h3 = h2 * h;
        m[3] = ((m3 + 3.0 * h * m2) + (3.0 * h2 * m1 + h3 * m0)) + h3 * h * (l / 5.0 + r / 20.0);
        m[2] = (m2 + 2.0 * h * m1) + (h2 * m0 + h3 * (l / 4.0 + r / 12.0));
        m[1] = (m1 + h * m0) + h2 * (l / 3.0 + r / 6.0);
    }
    m[0] += 0.5 * len * (l + r);
}

/// [`advance_moments`] over one full step Δt with its coefficients (the powers of Δt over the
/// binomial and the pieces' integers) precomputed: the fast path's version.
#[derive(Debug, Clone, Copy)]
pub(super) struct MomentStep {
    /// 3h, 3h², h³, 2h, h², h, h/2.
    shift: [f64; 7],
    /// The piece's weights (of l, of r) in m₃, m₂, m₁: h⁴/5, h⁴/20, h³/4, h³/12, h²/3, h²/6.
    piece: [f64; 6],
}

impl MomentStep {
    /// Its shift and piece coefficients (for [`crate::engine::StepPlan`]).
    pub(super) fn coefficients(&self) -> ([f64; 7], [f64; 6]) {
        (self.shift, self.piece)
    }

    pub(super) fn new(h: f64) -> Self {
        let (h2, h3) = (h * h, h * h * h);
        let h4 = h2 * h2;
        MomentStep {
            shift: [3.0 * h, 3.0 * h2, h3, 2.0 * h, h2, h, 0.5 * h],
            piece: [h4 / 5.0, h4 / 20.0, h3 / 4.0, h3 / 12.0, h2 / 3.0, h2 / 6.0],
        }
    }

    /// The moments `m` moved on by a full step over the piece (l → r), as new values: the
    /// caller keeps them in registers for the lumped value (reading them back from memory at
    /// once, as a vector over four separate scalar stores, stalls the store forwarding on the
    /// step's dependency chain: measured ≈ 30 % of the memory's time).
    #[inline(always)]
    pub(super) fn advanced(
        &self,
        m: &[f64; LUMPED_TERMS],
        flat: bool,
        l: f64,
        r: f64,
    ) -> [f64; LUMPED_TERMS] {
        let [s3, s31, s30, s2, s20, s1, half] = self.shift;
        let [a3, b3, a2, b2, a1, b1] = self.piece;
        let [m0, m1, m2, m3] = *m;
        let n0 = m0 + half * (l + r);
        if flat {
            return [n0, m1, m2, m3];
        }
        [
            n0,
            (m1 + s1 * m0) + (a1 * l + b1 * r),
            (m2 + s2 * m1) + (s20 * m0 + (a2 * l + b2 * r)),
            ((m3 + s3 * m2) + (s31 * m1 + s30 * m0)) + (a3 * l + b3 * r),
        ]
    }
}

/// The weights of the moments in Σ_k p_k (back + x)ᵏ = Σ_i out_i xⁱ (the lumped polynomial at a
/// distance `back` beyond the window's start): out_i = Σ_{k≥i} C(k, i) p_k back^{k−i}.
pub(super) fn lumped_weights(p: &[f64; LUMPED_TERMS], back: f64) -> [f64; LUMPED_TERMS] {
    let b = back;
    [
        p[0] + b * (p[1] + b * (p[2] + b * p[3])),
        p[1] + b * (2.0 * p[2] + 3.0 * b * p[3]),
        p[2] + 3.0 * b * p[3],
        p[3],
    ]
}

/// Σ_i w_i m_i.
#[inline(always)]
pub(super) fn dot_moments(w: &[f64; LUMPED_TERMS], m: &[f64; LUMPED_TERMS]) -> f64 {
    (w[0] * m[0] + w[1] * m[1]) + (w[2] * m[2] + w[3] * m[3])
}
