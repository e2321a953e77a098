//! The exact local window of a memory: the last pieces of g as (left, right) pairs in a
//! mirrored ring, so that the older ones are one contiguous run of doubles, and the dot product
//! that weighs them.
//!
//! Equation: the window's part of J^λ g(t_{n+1}) is (h^λ/Γ(λ)) Σ_p (wl_p g_left + wr_p g_right)
//! over the pieces at distances p = 1 … w − 1 (the product-integration weights of
//! [`crate::engine::kernel`]).
//!
//! Method: a ring stored twice after one zero pair, read as one slice whose length is a multiple
//! of four; the dot product in four fixed partial sums (portable and AVX: the same bits).
//!
//! Reference: Diethelm, Ford & Freed, Nonlinear Dyn. 29 (2002) 3–22 (product trapezoidal rule).
//!
//! Tests: `every_window_size_agrees_with_the_direct_memory` and
//! `portable_and_avx_memories_give_the_same_bits` in the memory's unit tests.

/// The last `cap` pieces of g in chronological order as (left, right) pairs, stored twice
/// (mirrored ring) so that they are always one contiguous slice, after one pair of zeros that
/// is never written: the fast path reads the window's older pieces as one run of doubles whose
/// length is a multiple of four, starting up to one pair early (with zero weights there).
#[derive(Debug, Clone)]
pub(super) struct Window {
    pub(super) cap: usize,
    /// The zero pair, then the ring twice.
    pub(super) pairs: Vec<[f64; 2]>,
    /// Index of the oldest piece in `0..cap`.
    pub(super) head: usize,
    pub(super) len: usize,
}

impl Window {
    pub(super) fn new(cap: usize) -> Self {
        Window {
            cap,
            pairs: vec![[0.0; 2]; 1 + 2 * cap],
            head: 0,
            len: 0,
        }
    }

    /// Append a piece; returns the one that left (the oldest) when the window was full.
    #[inline(always)]
    pub(super) fn push(&mut self, left: f64, right: f64) -> Option<(f64, f64)> {
        let cap = self.cap;
        if cap == 0 {
            return Some((left, right));
        }
        let (pos, leaving) = if self.len < cap {
            // not yet full: head is 0
            self.len += 1;
            (self.len - 1, None)
        } else {
            let h = self.head;
            self.head = if h + 1 == cap { 0 } else { h + 1 };
            let [l, r] = self.pairs[1 + h];
            (h, Some((l, r)))
        };
        self.pairs[1 + pos] = [left, right];
        self.pairs[1 + pos + cap] = [left, right];
        leaving
    }

    /// The pieces as (left, right), oldest first.
    #[inline]
    pub(super) fn pieces(&self) -> &[[f64; 2]] {
        &self.pairs[1 + self.head..1 + self.head + self.len]
    }

    /// The `n` doubles (a multiple of four, at most 2·cap) that end with the right value of
    /// the piece before the newest: all of the window's older pieces, preceded by whatever
    /// (finite) values the zero-weighted padding meets. The window must be full.
    #[inline(always)]
    pub(super) fn older_run(&self, n: usize) -> &[f64] {
        let end = 2 * (self.head + self.cap);
        &self.pairs.as_flattened()[end - n..end]
    }

    pub(super) fn clear(&mut self) {
        self.head = 0;
        self.len = 0;
    }
}

/// Σ a_i b_i with four fixed partial sums, combined as (s0 + s1) + (s2 + s3): the same bits
/// whatever vector width the compiler uses.
#[inline(always)]
pub(super) fn dot(a: &[f64], b: &[f64]) -> f64 {
    let mut acc = [0.0; 4];
    let (ac, ar) = a.split_at(a.len() - a.len() % 4);
    let (bc, br) = b.split_at(ac.len());
    for (x, y) in ac.chunks_exact(4).zip(bc.chunks_exact(4)) {
        for i in 0..4 {
            acc[i] += x[i] * y[i];
        }
    }
    for (i, (x, y)) in ar.iter().zip(br).enumerate() {
        acc[i] += x * y;
    }
    (acc[0] + acc[1]) + (acc[2] + acc[3])
}

/// [`dot`] of two slices of equal length, a multiple of four, in AVX: the same operations in
/// the same order, four lanes at once.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
#[inline]
pub(super) unsafe fn dot_avx(a: &[f64], b: &[f64]) -> f64 {
    use std::arch::x86_64::*;
    let n = a.len();
    assert!(b.len() == n && n % 4 == 0);
    let mut acc = _mm256_setzero_pd();
    let mut k = 0;
    while k < n {
        // SAFETY: k + 4 ≤ n, the length of both slices (asserted above).
        let ab = _mm256_mul_pd(
            _mm256_loadu_pd(a.as_ptr().add(k)),
            _mm256_loadu_pd(b.as_ptr().add(k)),
        );
        acc = _mm256_add_pd(acc, ab);
        k += 4;
    }
    let mut s = [0.0; 4];
    _mm256_storeu_pd(s.as_mut_ptr(), acc);
    (s[0] + s[1]) + (s[2] + s[3])
}
