//! The exponential modes of a sum-of-exponentials memory.
//!
//! Equation: beyond the window the kernel is Σ_j w_j e^{−s_j t}; each mode holds
//! Y_j = ∫ e^{−s_j (t_m − s)} g(s) ds and a piece (l → r) leaving the window enters it exactly:
//! Y ← e^{−s h} Y + h ψ(sh) l + h (φ(sh) − ψ(sh)) r.
//!
//! Method: the modes in blocks of four lanes, plain multiplies and adds in a fixed order (no
//! fused multiply–add); the AVX version does the same operations in the same order, so the bits
//! do not depend on the CPU.
//!
//! Reference: Jiang, Zhang, Zhang & Zhang, Commun. Comput. Phys. 21 (2017) 650–678 (SOE for the
//! Caputo derivative).
//!
//! Tests: `portable_and_avx_memories_give_the_same_bits` in the memory's unit tests; `tests/soe.rs`.

/// The exponential modes of an SOE kernel, advanced by one unsplit piece (l, r):
/// Y ← e^{−sh}Y + a·l + b·r, returning Σ out·Y. Laid out in blocks of four; the arithmetic is
/// plain multiplies and adds in a fixed order (no fused multiply–add), so the result is
/// bit-identical on every machine, whether it runs the portable or the AVX version.
#[derive(Debug, Clone, Default)]
pub(super) struct Modes {
    pub(super) y: Vec<[f64; 4]>,
    pub(super) decay: Vec<[f64; 4]>,
    pub(super) start: Vec<[f64; 4]>,
    pub(super) end: Vec<[f64; 4]>,
    pub(super) out: Vec<[f64; 4]>,
}

/// Y ← e^{−sh}Y + a·l + b·r and Σ out·Y, lane by lane as (d·y + (a·l + b·r)) (the part that
/// does not depend on Y first), the sums of out·Y kept in two accumulators of four lanes (even
/// and odd blocks: half the serial additions), combined lane by lane and then as
/// (s0 + s1) + (s2 + s3).
#[inline(always)]
pub(super) fn advance_modes(m: &mut Modes, l: f64, r: f64) -> f64 {
    let mut acc = [[0.0; 4]; 2];
    for (k, ((((y, d), a), b), o)) in
        m.y.iter_mut()
            .zip(&m.decay)
            .zip(&m.start)
            .zip(&m.end)
            .zip(&m.out)
            .enumerate()
    {
        for i in 0..4 {
            let v = d[i] * y[i] + (a[i] * l + b[i] * r);
            y[i] = v;
            acc[k % 2][i] += o[i] * v;
        }
    }
    let s: [f64; 4] = std::array::from_fn(|i| acc[0][i] + acc[1][i]);
    (s[0] + s[1]) + (s[2] + s[3])
}

/// [`advance_modes`] in AVX: the same operations in the same order, four lanes at once.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
#[inline]
pub(super) unsafe fn advance_modes_avx(m: &mut Modes, l: f64, r: f64) -> f64 {
    use std::arch::x86_64::*;
    let lv = _mm256_set1_pd(l);
    let rv = _mm256_set1_pd(r);
    let (mut acc0, mut acc1) = (_mm256_setzero_pd(), _mm256_setzero_pd());
    let n = m.y.len();
    assert!(m.decay.len() == n && m.start.len() == n && m.end.len() == n && m.out.len() == n);
    let (y, d, a, b, o) = (
        m.y.as_mut_ptr() as *mut f64,
        m.decay.as_ptr() as *const f64,
        m.start.as_ptr() as *const f64,
        m.end.as_ptr() as *const f64,
        m.out.as_ptr() as *const f64,
    );
    // block k: Y ← d·Y + (a·l + b·r), returning out·Y
    let block = |k: usize| {
        let i = 4 * k;
        // SAFETY: all five arrays hold n > k blocks of four f64 (asserted above).
        let yv = _mm256_loadu_pd(y.add(i));
        let v = _mm256_add_pd(
            _mm256_mul_pd(_mm256_loadu_pd(d.add(i)), yv),
            _mm256_add_pd(
                _mm256_mul_pd(_mm256_loadu_pd(a.add(i)), lv),
                _mm256_mul_pd(_mm256_loadu_pd(b.add(i)), rv),
            ),
        );
        _mm256_storeu_pd(y.add(i), v);
        _mm256_mul_pd(_mm256_loadu_pd(o.add(i)), v)
    };
    // even blocks into acc0, odd ones into acc1 (two named registers: no stack round trip)
    let mut k = 0;
    while k + 1 < n {
        acc0 = _mm256_add_pd(acc0, block(k));
        acc1 = _mm256_add_pd(acc1, block(k + 1));
        k += 2;
    }
    if k < n {
        acc0 = _mm256_add_pd(acc0, block(k));
    }
    let mut s = [0.0; 4];
    _mm256_storeu_pd(s.as_mut_ptr(), _mm256_add_pd(acc0, acc1));
    (s[0] + s[1]) + (s[2] + s[3])
}

impl Modes {
    pub(super) fn len(&self) -> usize {
        4 * self.y.len()
    }

    #[inline]
    pub(super) fn advance(&mut self, l: f64, r: f64) -> f64 {
        advance_modes(self, l, r)
    }

    pub(super) fn dot(&self) -> f64 {
        let mut acc = [0.0; 4];
        for (y, o) in self.y.iter().zip(&self.out) {
            for i in 0..4 {
                acc[i] += o[i] * y[i];
            }
        }
        (acc[0] + acc[1]) + (acc[2] + acc[3])
    }

    pub(super) fn flat_mut(&mut self) -> impl Iterator<Item = &mut f64> {
        self.y.iter_mut().flatten()
    }
}
