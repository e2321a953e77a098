//! The general path of [`History::push`]: split pieces (impacts), the direct memory (every
//! piece held exactly, the O(N) reference) and a split piece leaving the window into the modes.
//!
//! Equation: a piece split at θ is two linear pieces, g from `left` to `before` on [0, θh] and
//! from `after` to `right` on [θh, h]; its exact weights replace the plain ones, and it enters
//! every exponential mode by the recursion over each part.
//!
//! Method: the split's corrections (exact minus plain weights) are tabulated for every distance
//! in the window when it is pushed; the direct memory sums every piece with the exact weights.
//!
//! Reference: Diethelm, Ford & Freed, Nonlinear Dyn. 29 (2002) 3–22 (product integration).
//!
//! Tests: `scaling_the_history_equals_the_history_of_the_scaled_g` and
//! `every_window_size_agrees_with_the_direct_memory` in the memory's unit tests.

use super::moments::advance_moments;
use super::{piece_integral, History, Piece, Split};
use crate::engine::kernel::{phi_psi_given, Powers, LUMPED_TERMS};
use crate::maths::exp;

impl History {
    /// The scaled corrections of a split piece at distances 1..=cap (see `split_weights`).
    pub(super) fn split_weight_table(&mut self, s: &Split) -> Vec<[f64; 5]> {
        let cap = self.local.cap;
        self.grow_weights(cap);
        let memo = &mut Powers::default();
        (1..=cap)
            .map(|p| {
                let pf = p as f64;
                let mid = pf + 1.0 - s.theta;
                let (wa, wb) = self.iw.of_with(pf, mid, memo);
                let (wa2, wb2) = if s.keep_before {
                    self.iw.of_with(mid, pf + 1.0, memo)
                } else {
                    (0.0, 0.0)
                };
                let k = self.scale;
                let point = if s.mass != 0.0 {
                    k * self.iw.kernel_with(mid, memo)
                } else {
                    0.0
                };
                [
                    k * (wb2 - self.wl[p]),
                    k * wa2,
                    k * wb,
                    k * (wa - self.wr[p]),
                    point,
                ]
            })
            .collect()
    }

    /// [`History::push`] in general: Direct memory, split pieces, λ = 1.
    #[inline(never)]
    pub(super) fn push_general(&mut self, piece: Piece) {
        let seq = self.pushed;
        self.pushed += 1;
        if let Some(s) = piece.split {
            self.splits.push((seq, s));
            if !self.direct && self.local.cap > 0 {
                let w = self.split_weight_table(&s);
                self.split_weights.push(w);
            }
        }
        if self.direct {
            self.all.push([piece.left, piece.right]);
            let len = self.all.len();
            self.grow_weights(len);
            let acc = self.plain_sum(&self.all) + self.split_corrections(len);
            self.cached = self.scale * acc;
            return;
        }
        let leaving = self.local.push(piece.left, piece.right);
        let mut modes = 0.0;
        if let Some((left, right)) = leaving {
            let gone = seq - self.local.len as u64;
            let split = match self.splits.first() {
                Some(&(s, sp)) if s == gone => {
                    self.splits.remove(0);
                    if !self.split_weights.is_empty() {
                        self.split_weights.remove(0);
                    }
                    Some(sp)
                }
                _ => None,
            };
            modes = self.absorb(left, right, split);
        }
        modes += self.lumped_value();
        let held = self.local.pieces();
        let local = self.plain_sum(held) + self.split_corrections(held.len());
        self.cached = modes + self.scale * local;
    }

    /// Σ_k wl[p]·left_k + wr[p]·right_k over `pieces` (the last ones held exactly, oldest
    /// first) at their distances p = n − k from the next node, as if none were split
    /// (unscaled).
    pub(super) fn plain_sum(&self, pieces: &[[f64; 2]]) -> f64 {
        let n = pieces.len();
        pieces
            .iter()
            .enumerate()
            .map(|(k, &[l, r])| self.wl[n - k] * l + self.wr[n - k] * r)
            .sum()
    }

    /// Exact minus plain weights for the split pieces among the last `len` held exactly.
    pub(super) fn split_corrections(&self, len: usize) -> f64 {
        if self.splits.is_empty() {
            return 0.0;
        }
        let held = self.held();
        let first = self.pushed - len as u64;
        let mut acc = 0.0;
        let memo = &mut Powers::default();
        for &(seq, s) in &self.splits {
            let k = (seq - first) as usize;
            let p = len - k;
            let [left, right] = held[k];
            let piece = Piece {
                left,
                right,
                split: Some(s),
            };
            acc += piece_integral(&self.iw, &piece, p as f64, memo)
                - (self.wl[p] * piece.left + self.wr[p] * piece.right);
        }
        acc
    }

    /// Move a piece leaving the window into the modes and the lumped terms; returns Σ out·Y.
    pub(super) fn absorb(&mut self, left: f64, right: f64, split: Option<Split>) -> f64 {
        let h = self.dt;
        match split {
            None => {
                let modes = if self.modes.y.is_empty() {
                    0.0
                } else {
                    self.modes.advance(left, right)
                };
                advance_moments(&mut self.moments, self.flat, h, left, right);
                modes
            }
            Some(s) => {
                let l1 = s.theta * h;
                let l2 = h - l1;
                let kernel = self.soe.as_ref().expect("SOE memory");
                let decays = self.modes.decay.iter().flatten();
                let modes = kernel.rates.iter().zip(decays);
                for ((&rate, &decay), y) in modes.zip(self.modes.y.iter_mut().flatten()) {
                    // e^{−s l₂} = e^{−sh}/e^{−s l₁}: one exponential per mode (s·h ≤ ~2.4)
                    let e1 = exp(-rate * l1);
                    let e2 = decay / e1;
                    let (phi, psi) = phi_psi_given(rate * l1, e1);
                    let mut v = if s.keep_before {
                        e1 * *y + l1 * psi * left + l1 * (phi - psi) * s.before
                    } else {
                        0.0
                    };
                    let (phi, psi) = phi_psi_given(rate * l2, e2);
                    v = e2 * v + l2 * psi * s.after + l2 * (phi - psi) * right;
                    if s.mass != 0.0 {
                        // the point mass at the impact, l₂ before the window's new start
                        v += h * s.mass * e2;
                    }
                    *y = v;
                }
                if s.keep_before {
                    advance_moments(&mut self.moments, self.flat, l1, left, s.before);
                } else {
                    self.moments = [0.0; LUMPED_TERMS];
                }
                advance_moments(&mut self.moments, self.flat, l2, s.after, right);
                if s.mass != 0.0 {
                    // m_k gains mass·h·l₂ᵏ (only m₀ is kept with a flat kernel)
                    let kept = if self.flat { 1 } else { LUMPED_TERMS };
                    let mut x = h * s.mass;
                    for m in &mut self.moments[..kept] {
                        *m += x;
                        x *= l2;
                    }
                }
                self.modes.dot()
            }
        }
    }
}
