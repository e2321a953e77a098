//! The memory of one path: J^λ g over the whole history, kept exactly over a short window and
//! by the verified sum of exponentials of [`super::kernel`] beyond it.
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
//! # Tests
//! Unit tests below (the scalar solver at order 1 is the trapezoidal PECE by hand; scaling the
//! history equals the history of the scaled g, for both memories, with a split piece; the
//! portable and AVX fast paths give the same bits; every window of 2 … 10 steps, padded or
//! not, agrees with `Direct` to 10⁻¹⁰);
//! `tests/soe.rs` (SOE against Direct on Eq. 1).

use super::kernel::{phi_psi, phi_psi_given, IntervalWeights, SoeKernel, LUMPED_TERMS};
use crate::error::{Error, Result};
use crate::special::gamma;

/// How the history of J^λ g is kept.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Memory {
    /// The exact product-integration weights over the whole history: O(N) work per step.
    /// The reference, for tests and short runs.
    Direct,
    /// Exact weights over a short local window, a verified sum of exponentials beyond it.
    SumOfExponentials {
        /// Relative tolerance of the kernel approximation on [window·Δt, T] (e.g. 1e-10).
        tolerance: f64,
    },
}

impl Default for Memory {
    fn default() -> Self {
        Memory::SumOfExponentials { tolerance: 1e-10 }
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
fn piece_integral(weights: &IntervalWeights, piece: &Piece, p: f64) -> f64 {
    match piece.split {
        None => {
            let (wa, wb) = weights.of(p, p + 1.0);
            wa * piece.right + wb * piece.left
        }
        Some(s) => {
            let mid = p + 1.0 - s.theta;
            let (wa, wb) = weights.of(p, mid);
            let mut v = wa * piece.right + wb * s.after;
            if s.keep_before {
                let (wa, wb) = weights.of(mid, p + 1.0);
                v += wa * s.before + wb * piece.left;
            }
            v
        }
    }
}

/// The last `cap` pieces of g in chronological order as (left, right) pairs, stored twice
/// (mirrored ring) so that they are always one contiguous slice, after one pair of zeros that
/// is never written: the fast path reads the window's older pieces as one run of doubles whose
/// length is a multiple of four, starting up to one pair early (with zero weights there).
#[derive(Debug, Clone)]
struct Window {
    cap: usize,
    /// The zero pair, then the ring twice.
    pairs: Vec<[f64; 2]>,
    /// Index of the oldest piece in `0..cap`.
    head: usize,
    len: usize,
}

impl Window {
    fn new(cap: usize) -> Self {
        Window {
            cap,
            pairs: vec![[0.0; 2]; 1 + 2 * cap],
            head: 0,
            len: 0,
        }
    }

    /// Append a piece; returns the one that left (the oldest) when the window was full.
    #[inline(always)]
    fn push(&mut self, left: f64, right: f64) -> Option<(f64, f64)> {
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
    fn pieces(&self) -> &[[f64; 2]] {
        &self.pairs[1 + self.head..1 + self.head + self.len]
    }

    /// The `n` doubles (a multiple of four, at most 2·cap) that end with the right value of
    /// the piece before the newest: all of the window's older pieces, preceded by whatever
    /// (finite) values the zero-weighted padding meets. The window must be full.
    #[inline(always)]
    fn older_run(&self, n: usize) -> &[f64] {
        let end = 2 * (self.head + self.cap);
        &self.pairs.as_flattened()[end - n..end]
    }

    fn clear(&mut self) {
        self.head = 0;
        self.len = 0;
    }
}

/// Σ a_i b_i with four fixed partial sums, combined as (s0 + s1) + (s2 + s3): the same bits
/// whatever vector width the compiler uses.
#[inline(always)]
fn dot(a: &[f64], b: &[f64]) -> f64 {
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

/// Move the window's start t_m on by ℓ over a linear piece (l → r) of g: the moments
/// m_k = ∫ (t_m − s)ᵏ g(s) ds become Σ_{i≤k} C(k, i) ℓ^{k−i} m_i (the old history, now ℓ
/// further away) + ℓ^{k+1}(l/(k + 2) + r/((k + 1)(k + 2))) (the piece). With a `flat` kernel
/// (λ = 1) only m₀ = ∫ g is kept, by the trapezoidal rule.
#[inline(always)]
fn advance_moments(m: &mut [f64; LUMPED_TERMS], flat: bool, len: f64, l: f64, r: f64) {
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
struct MomentStep {
    /// 3h, 3h², h³, 2h, h², h, h/2.
    shift: [f64; 7],
    /// The piece's weights (of l, of r) in m₃, m₂, m₁: h⁴/5, h⁴/20, h³/4, h³/12, h²/3, h²/6.
    piece: [f64; 6],
}

impl MomentStep {
    fn new(h: f64) -> Self {
        let (h2, h3) = (h * h, h * h * h);
        let h4 = h2 * h2;
        MomentStep {
            shift: [3.0 * h, 3.0 * h2, h3, 2.0 * h, h2, h, 0.5 * h],
            piece: [h4 / 5.0, h4 / 20.0, h3 / 4.0, h3 / 12.0, h2 / 3.0, h2 / 6.0],
        }
    }

    #[inline(always)]
    fn advance(&self, m: &mut [f64; LUMPED_TERMS], flat: bool, l: f64, r: f64) {
        let [s3, s31, s30, s2, s20, s1, half] = self.shift;
        let [a3, b3, a2, b2, a1, b1] = self.piece;
        if !flat {
            let [m0, m1, m2, m3] = *m;
            m[3] = ((m3 + s3 * m2) + (s31 * m1 + s30 * m0)) + (a3 * l + b3 * r);
            m[2] = (m2 + s2 * m1) + (s20 * m0 + (a2 * l + b2 * r));
            m[1] = (m1 + s1 * m0) + (a1 * l + b1 * r);
        }
        m[0] += half * (l + r);
    }
}

/// The weights of the moments in Σ_k p_k (back + x)ᵏ = Σ_i out_i xⁱ (the lumped polynomial at a
/// distance `back` beyond the window's start): out_i = Σ_{k≥i} C(k, i) p_k back^{k−i}.
fn lumped_weights(p: &[f64; LUMPED_TERMS], back: f64) -> [f64; LUMPED_TERMS] {
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
fn dot_moments(w: &[f64; LUMPED_TERMS], m: &[f64; LUMPED_TERMS]) -> f64 {
    (w[0] * m[0] + w[1] * m[1]) + (w[2] * m[2] + w[3] * m[3])
}

/// The exponential modes of an SOE kernel, advanced by one unsplit piece (l, r):
/// Y ← e^{−sh}Y + a·l + b·r, returning Σ out·Y. Laid out in blocks of four; the arithmetic is
/// plain multiplies and adds in a fixed order (no fused multiply–add), so the result is
/// bit-identical on every machine, whether it runs the portable or the AVX version.
#[derive(Debug, Clone, Default)]
struct Modes {
    y: Vec<[f64; 4]>,
    decay: Vec<[f64; 4]>,
    start: Vec<[f64; 4]>,
    end: Vec<[f64; 4]>,
    out: Vec<[f64; 4]>,
}

/// Y ← e^{−sh}Y + a·l + b·r and Σ out·Y, lane by lane as (d·y + (a·l + b·r)) (the part that
/// does not depend on Y first), the sums of out·Y kept in two accumulators of four lanes (even
/// and odd blocks: half the serial additions), combined lane by lane and then as
/// (s0 + s1) + (s2 + s3).
#[inline(always)]
fn advance_modes(m: &mut Modes, l: f64, r: f64) -> f64 {
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
unsafe fn advance_modes_avx(m: &mut Modes, l: f64, r: f64) -> f64 {
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

/// [`dot`] of two slices of equal length, a multiple of four, in AVX: the same operations in
/// the same order, four lanes at once.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
#[inline]
unsafe fn dot_avx(a: &[f64], b: &[f64]) -> f64 {
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

impl Modes {
    fn len(&self) -> usize {
        4 * self.y.len()
    }

    #[inline]
    fn advance(&mut self, l: f64, r: f64) -> f64 {
        advance_modes(self, l, r)
    }

    fn dot(&self) -> f64 {
        let mut acc = [0.0; 4];
        for (y, o) in self.y.iter().zip(&self.out) {
            for i in 0..4 {
                acc[i] += o[i] * y[i];
            }
        }
        (acc[0] + acc[1]) + (acc[2] + acc[3])
    }

    fn flat_mut(&mut self) -> impl Iterator<Item = &mut f64> {
        self.y.iter_mut().flatten()
    }
}

/// The memory of J^λ g on a uniform grid, the whole history of one path: completed pieces of g
/// (the exact local window), the exponential modes and the lumped constant/linear terms beyond
/// it. It is linear in the history: [`History::contract_toward`] pulls all of it toward a
/// reference history (renormalising a perturbed copy acts on the entire memory, not just the
/// state).
///
/// Protocol per step n → n+1: [`History::value`] gives the contribution of all completed
/// pieces to J^λ g(t_{n+1}); [`History::current_weights`] the weights of the step's own
/// left and right values; [`History::push`] stores the corrected piece. Predicted values are
/// never pushed. At λ = 1 (constant kernel) the SOE memory keeps no window: J¹g is the running
/// trapezoidal integral.
#[derive(Debug, Clone)]
pub(crate) struct History {
    /// The exact weights of an interval at this λ (series coefficients computed once).
    iw: IntervalWeights,
    dt: f64,
    /// h^λ / Γ(λ)
    scale: f64,
    direct: bool,
    /// Direct: every piece (chronological); SOE: the last `window − 1` (none at λ = 1).
    all: Vec<[f64; 2]>,
    local: Window,
    /// Split pieces still held exactly, by sequence number (pieces pushed since the start).
    splits: Vec<(u64, Split)>,
    /// For each held split (same order), with a window: its scaled corrections — exact minus
    /// plain weights of (left, before, after, right) — at distances 1..=cap (index p − 1),
    /// computed once when the split is pushed, so that the fast path carries split pieces.
    split_weights: Vec<Vec<[f64; 4]>>,
    pushed: u64,
    /// Weights of left/right of an unsplit piece at distance p (index p).
    wl: Vec<f64>,
    wr: Vec<f64>,
    /// SOE with a window, the fast path of [`History::push`]: the weights (wl, wr) of the
    /// window's older pieces (distances cap … 2) times h^λ/Γ(λ), interleaved as the window
    /// stores its pieces, after zeros up to a multiple of four ([`Window::older_run`]).
    older: Vec<f64>,
    /// The scaled weights of the newest piece (distance 1).
    newest: (f64, f64),
    /// The moments' advance over one full step, its coefficients precomputed.
    moment_step: MomentStep,
    soe: Option<SoeKernel>,
    /// SOE mode state Y_j = ∫ e^{−s_j (t_m − s)} g(s) ds up to the window's start t_m.
    modes: Modes,
    /// The CPU runs AVX (the modes are advanced four lanes at once, same bits).
    avx: bool,
    /// The SOE kernel's lumped polynomial p₀…p₃ (copied out of `soe` for the hot path); at
    /// λ = 1 only p₀ ≠ 0 (`flat`), and only the integral is kept.
    lumped: [f64; LUMPED_TERMS],
    flat: bool,
    /// The lumped polynomial's weights of the moments at the fixed distance back = w·h of the
    /// window's start from the next node (w = cap + 1): Σ_k p_k (back + x)ᵏ = Σ_i out_i xⁱ.
    lumped_out: [f64; LUMPED_TERMS],
    /// m_k = ∫ (t_m − s)ᵏ g(s) ds, k = 0…3, over the history up to the window's start t_m
    /// (the lumped terms' state; m₀ is ∫ g).
    moments: [f64; LUMPED_TERMS],
    /// The history's value for the next step.
    cached: f64,
}

impl History {
    /// Memory for order λ, step h, horizon T (the SOE is certified on [(w−1)h, T]).
    pub fn new(lambda: f64, dt: f64, t_end: f64, memory: Memory, window: usize) -> Result<Self> {
        if !(lambda > 0.0 && lambda <= 1.0) {
            return Err(Error::invalid("lambda", lambda, "(0, 1]"));
        }
        if !(dt > 0.0 && dt.is_finite()) {
            return Err(Error::invalid("dt", dt, "(0, ∞), finite"));
        }
        if window < 2 {
            return Err(Error::invalid("window", window as f64, "2 or more steps"));
        }
        let scale = dt.powf(lambda) / gamma(lambda);
        let direct = matches!(memory, Memory::Direct);
        let iw = IntervalWeights::new(lambda);
        let (wa, wb) = iw.of(0.0, 1.0);
        let mut c = History {
            iw,
            dt,
            scale,
            direct,
            all: vec![],
            local: Window::new(0),
            splits: vec![],
            split_weights: vec![],
            pushed: 0,
            wl: vec![wb],
            wr: vec![wa],
            older: vec![],
            newest: (0.0, 0.0),
            moment_step: MomentStep::new(dt),
            soe: None,
            modes: Modes::default(),
            avx: false,
            lumped: [0.0; LUMPED_TERMS],
            flat: true,
            lumped_out: [0.0; LUMPED_TERMS],
            moments: [0.0; LUMPED_TERMS],
            cached: 0.0,
        };
        if let Memory::SumOfExponentials { tolerance } = memory {
            // the modes serve kernel arguments ≥ (w−1)h (impact instants inside a step)
            let from = (window as f64 - 1.0) * dt;
            let k = SoeKernel::new(lambda, from, t_end.max(from * 1.0001), tolerance)?;
            // a constant kernel (λ = 1) needs no window: every piece goes to the integral
            let cap = if k.is_empty() && k.lumped[1..].iter().all(|&p| p == 0.0) {
                0
            } else {
                window - 1
            };
            let back = (cap + 1) as f64 * dt;
            let mut flat: [Vec<f64>; 5] = Default::default();
            for (&s, &w) in k.rates.iter().zip(&k.weights) {
                let z = s * dt;
                let (phi, psi) = phi_psi(z);
                flat[0].push(0.0);
                flat[1].push((-z).exp());
                flat[2].push(dt * psi);
                flat[3].push(dt * (phi - psi));
                flat[4].push(w * (-s * back).exp());
            }
            // pad to a multiple of 4 with inert modes
            while flat[0].len() % 4 != 0 {
                flat.iter_mut().for_each(|v| v.push(0.0));
            }
            let blocks = |v: &Vec<f64>| -> Vec<[f64; 4]> {
                v.chunks_exact(4)
                    .map(|c| [c[0], c[1], c[2], c[3]])
                    .collect()
            };
            c.modes = Modes {
                y: blocks(&flat[0]),
                decay: blocks(&flat[1]),
                start: blocks(&flat[2]),
                end: blocks(&flat[3]),
                out: blocks(&flat[4]),
            };
            #[cfg(target_arch = "x86_64")]
            {
                c.avx = std::arch::is_x86_feature_detected!("avx");
            }
            c.local = Window::new(cap);
            c.grow_weights(cap);
            if cap > 0 {
                let pairs = 2 * (cap - 1);
                c.older = vec![0.0; pairs.next_multiple_of(4) - pairs];
                for p in (2..=cap).rev() {
                    c.older.extend([scale * c.wl[p], scale * c.wr[p]]);
                }
                c.newest = (scale * c.wl[1], scale * c.wr[1]);
            }
            c.lumped = k.lumped;
            c.flat = k.lumped[1..].iter().all(|&p| p == 0.0);
            c.lumped_out = lumped_weights(&k.lumped, (cap + 1) as f64 * dt);
            c.soe = Some(k);
        }
        Ok(c)
    }

    /// Extend the weights of an unsplit piece to distances 0..=p.
    fn grow_weights(&mut self, p: usize) {
        while self.wl.len() <= p {
            let q = self.wl.len() as f64;
            let (wa, wb) = self.iw.of(q, q + 1.0);
            self.wl.push(wb);
            self.wr.push(wa);
        }
    }

    /// The SOE kernel in use, if any.
    pub fn kernel(&self) -> Option<&SoeKernel> {
        self.soe.as_ref()
    }

    /// Contribution of all completed pieces to J^λ g at the end of the current step.
    #[inline]
    pub fn value(&self) -> f64 {
        self.cached
    }

    /// Scaled weights (of g_n, of g_{n+1}) of the current, unsplit step.
    #[inline]
    pub fn current_weights(&self) -> (f64, f64) {
        (self.scale * self.wl[0], self.scale * self.wr[0])
    }

    /// For a current step split at θ (impact), the known part (before piece, after-impact
    /// value) and the scaled weight of g_{n+1}.
    pub fn current_split(&self, left: f64, split: &Split) -> (f64, f64) {
        let mid = 1.0 - split.theta;
        let (wa, wb) = self.iw.of(0.0, mid);
        let mut known = wb * split.after;
        if split.keep_before {
            let (wa2, wb2) = self.iw.of(mid, 1.0);
            known += wa2 * split.before + wb2 * left;
        }
        (self.scale * known, self.scale * wa)
    }

    /// The pieces held exactly as (left, right), oldest first.
    fn held(&self) -> &[[f64; 2]] {
        if self.direct {
            &self.all
        } else {
            self.local.pieces()
        }
    }

    /// The pieces held exactly, oldest first, with their splits.
    fn exact_pieces(&self) -> impl Iterator<Item = Piece> + '_ {
        let held = self.held();
        let first = self.pushed - held.len() as u64;
        held.iter().enumerate().map(move |(k, &[left, right])| {
            let seq = first + k as u64;
            Piece {
                left,
                right,
                split: self.splits.iter().find(|(s, _)| *s == seq).map(|(_, s)| *s),
            }
        })
    }

    /// J^λ g at the instant t_n + θh inside the current step: all completed pieces plus the
    /// current step's part [t_n, t_n + θh], without the (unknown) value at the instant, whose
    /// scaled weight is returned second. Used to find the velocity just before an impact.
    pub fn at_fraction(&self, theta: f64, left: f64) -> (f64, f64) {
        let shift = 1.0 - theta; // distances to t* are (distances to t_{n+1}) − shift
        let len = self.held().len();
        let mut sum = 0.0;
        for (k, piece) in self.exact_pieces().enumerate() {
            sum += piece_integral(&self.iw, &piece, (len - k) as f64 - shift);
        }
        let mut total = self.scale * sum;
        if let Some(kernel) = &self.soe {
            let back = ((self.local.cap + 1) as f64 - shift) * self.dt;
            let y = self.modes.y.iter().flatten();
            for ((&s, &w), &y) in kernel.rates.iter().zip(&kernel.weights).zip(y) {
                total += w * (-s * back).exp() * y;
            }
            total += dot_moments(&lumped_weights(&kernel.lumped, back), &self.moments);
        }
        let (wa, wb) = self.iw.of(0.0, theta);
        (total + self.scale * wb * left, self.scale * wa)
    }

    /// Store a completed (corrected) piece and prepare the history of the next step.
    #[inline]
    pub fn push(&mut self, piece: Piece) {
        if !self.direct && self.local.cap == 0 && piece.split.is_none() && self.flat {
            // a constant kernel (λ = 1): the running trapezoidal integral
            self.pushed += 1;
            self.moments[0] += 0.5 * self.dt * (piece.left + piece.right);
            self.cached = self.lumped[0] * self.moments[0];
            return;
        }
        if !self.direct
            && self.local.cap > 0
            && self.local.len + 1 >= self.local.cap
            && piece.split.is_none()
            && !self.split_leaves()
        {
            #[cfg(target_arch = "x86_64")]
            if self.avx {
                // SAFETY: `avx` is true only when the CPU reported AVX at construction.
                unsafe { self.push_plain_avx(piece.left, piece.right) };
                return;
            }
            self.push_plain(piece.left, piece.right);
            return;
        }
        self.push_general(piece);
    }

    /// [`History::push_plain`] compiled for AVX: the same operations in the same order (no
    /// fused multiply–add), four lanes at a time, so the same bits.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx")]
    unsafe fn push_plain_avx(&mut self, left: f64, right: f64) {
        self.push_plain_body(
            left,
            right,
            |m, l, r| advance_modes_avx(m, l, r),
            |a, b| dot_avx(a, b),
        )
    }

    fn push_plain(&mut self, left: f64, right: f64) {
        self.push_plain_body(left, right, advance_modes, dot)
    }

    /// The fast path of [`History::push`]: an unsplit piece into an SOE memory with a window
    /// that is full after it, no split piece leaving it. Everything that does not depend on the newest piece — the
    /// modes advanced by the piece leaving the window, the lumped terms, the window's older
    /// pieces — is summed first; the newest piece enters last, through one multiply–add pair,
    /// so that the step's dependency chain (newest g → memory value → next V) is two
    /// operations long and the rest overlaps with it.
    #[inline(always)]
    fn push_plain_body(
        &mut self,
        left: f64,
        right: f64,
        advance: impl FnOnce(&mut Modes, f64, f64) -> f64,
        dot: impl FnOnce(&[f64], &[f64]) -> f64,
    ) {
        self.pushed += 1;
        let leaving = self.local.push(left, right);
        let mut off = 0.0;
        if let Some((l0, r0)) = leaving {
            if !self.modes.y.is_empty() {
                off = advance(&mut self.modes, l0, r0);
            }
            self.moment_step
                .advance(&mut self.moments, self.flat, l0, r0);
        }
        off += self.lumped_value();
        off += dot(self.local.older_run(self.older.len()), &self.older);
        self.cached = off + (self.newest.0 * left + self.newest.1 * right);
        if !self.splits.is_empty() {
            self.cached += self.held_split_corrections();
        }
    }

    /// The lumped slow rates' contribution at the next node.
    #[inline(always)]
    fn lumped_value(&self) -> f64 {
        if self.flat {
            self.lumped[0] * self.moments[0]
        } else {
            dot_moments(&self.lumped_out, &self.moments)
        }
    }

    /// Whether the next push moves a split piece out of a full window (the general path).
    #[inline]
    fn split_leaves(&self) -> bool {
        match self.splits.first() {
            None => false,
            Some(&(seq, _)) => {
                self.local.len == self.local.cap && seq + self.local.cap as u64 == self.pushed
            }
        }
    }

    /// The held split pieces' corrections (exact minus plain weights, scaled), from the
    /// weights computed when each was pushed.
    #[cold]
    fn held_split_corrections(&self) -> f64 {
        let held = self.local.pieces();
        let first = self.pushed - held.len() as u64;
        let mut acc = 0.0;
        for (&(seq, s), w) in self.splits.iter().zip(&self.split_weights) {
            let [l, r] = held[(seq - first) as usize];
            let c = w[(self.pushed - seq) as usize - 1];
            acc += ((c[0] * l + c[1] * s.before) + c[2] * s.after) + c[3] * r;
        }
        acc
    }

    /// The scaled corrections of a split piece at distances 1..=cap (see `split_weights`).
    fn split_weight_table(&mut self, s: &Split) -> Vec<[f64; 4]> {
        let cap = self.local.cap;
        self.grow_weights(cap);
        (1..=cap)
            .map(|p| {
                let pf = p as f64;
                let mid = pf + 1.0 - s.theta;
                let (wa, wb) = self.iw.of(pf, mid);
                let (wa2, wb2) = if s.keep_before {
                    self.iw.of(mid, pf + 1.0)
                } else {
                    (0.0, 0.0)
                };
                let k = self.scale;
                [
                    k * (wb2 - self.wl[p]),
                    k * wa2,
                    k * wb,
                    k * (wa - self.wr[p]),
                ]
            })
            .collect()
    }

    /// [`History::push`] in general: Direct memory, split pieces, λ = 1.
    fn push_general(&mut self, piece: Piece) {
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
    fn plain_sum(&self, pieces: &[[f64; 2]]) -> f64 {
        let n = pieces.len();
        pieces
            .iter()
            .enumerate()
            .map(|(k, &[l, r])| self.wl[n - k] * l + self.wr[n - k] * r)
            .sum()
    }

    /// Exact minus plain weights for the split pieces among the last `len` held exactly.
    fn split_corrections(&self, len: usize) -> f64 {
        if self.splits.is_empty() {
            return 0.0;
        }
        let held = self.held();
        let first = self.pushed - len as u64;
        let mut acc = 0.0;
        for &(seq, s) in &self.splits {
            let k = (seq - first) as usize;
            let p = len - k;
            let [left, right] = held[k];
            let piece = Piece {
                left,
                right,
                split: Some(s),
            };
            acc += piece_integral(&self.iw, &piece, p as f64)
                - (self.wl[p] * piece.left + self.wr[p] * piece.right);
        }
        acc
    }

    /// Move a piece leaving the window into the modes and the lumped terms; returns Σ out·Y.
    fn absorb(&mut self, left: f64, right: f64, split: Option<Split>) -> f64 {
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
                    let e1 = (-rate * l1).exp();
                    let e2 = decay / e1;
                    let (phi, psi) = phi_psi_given(rate * l1, e1);
                    let mut v = if s.keep_before {
                        e1 * *y + l1 * psi * left + l1 * (phi - psi) * s.before
                    } else {
                        0.0
                    };
                    let (phi, psi) = phi_psi_given(rate * l2, e2);
                    v = e2 * v + l2 * psi * s.after + l2 * (phi - psi) * right;
                    *y = v;
                }
                if s.keep_before {
                    advance_moments(&mut self.moments, self.flat, l1, left, s.before);
                } else {
                    self.moments = [0.0; LUMPED_TERMS];
                }
                advance_moments(&mut self.moments, self.flat, l2, s.after, right);
                self.modes.dot()
            }
        }
    }

    /// Forget everything (the memory restarts; the lower terminal moves to now).
    pub fn restart(&mut self) {
        self.all.clear();
        self.splits.clear();
        self.split_weights.clear();
        self.local.clear();
        self.modes.flat_mut().for_each(|y| *y = 0.0);
        self.moments = [0.0; LUMPED_TERMS];
        self.cached = 0.0;
    }

    /// Multiply the whole history by `c` (J^λ is linear in g).
    #[cfg(test)]
    pub fn scale(&mut self, c: f64) {
        self.zip_state(None, &mut |_, v| *v *= c);
    }

    /// Apply `f(reference's number, own number)` to every number of the history's state, paired
    /// with the same number of `reference` when one is given.
    fn zip_state(&mut self, reference: Option<&History>, f: &mut dyn FnMut(Option<f64>, &mut f64)) {
        fn pair(r: Option<&[f64]>, own: &mut [f64], f: &mut dyn FnMut(Option<f64>, &mut f64)) {
            for (k, v) in own.iter_mut().enumerate() {
                f(r.map(|r| r[k]), v);
            }
        }
        let flat = |m: &Modes| -> Vec<f64> { m.y.iter().flatten().copied().collect() };
        let r_modes = reference.map(|r| flat(&r.modes));
        pair(
            reference.map(|r| r.all.as_flattened()),
            self.all.as_flattened_mut(),
            f,
        );
        pair(
            reference.map(|r| r.local.pairs.as_flattened()),
            self.local.pairs.as_flattened_mut(),
            f,
        );
        for (k, (_, s)) in self.splits.iter_mut().enumerate() {
            let rs = reference.map(|r| r.splits[k].1);
            f(rs.map(|s| s.before), &mut s.before);
            f(rs.map(|s| s.after), &mut s.after);
        }
        for (k, y) in self.modes.flat_mut().enumerate() {
            f(r_modes.as_ref().map(|r| r[k]), y);
        }
        for (k, m) in self.moments.iter_mut().enumerate() {
            f(reference.map(|r| r.moments[k]), m);
        }
        f(reference.map(|r| r.cached), &mut self.cached);
    }

    /// Whether `other` holds its history in the same layout (same pieces held exactly, split at
    /// the same steps and fractions), so that the two can be combined number by number.
    fn same_layout(&self, other: &History) -> bool {
        self.direct == other.direct
            && self.pushed == other.pushed
            && self.all.len() == other.all.len()
            && self.local.cap == other.local.cap
            && self.local.head == other.local.head
            && self.local.len == other.local.len
            && self.modes.y.len() == other.modes.y.len()
            && self.splits.len() == other.splits.len()
            && self
                .splits
                .iter()
                .zip(&other.splits)
                .all(|((a, s), (b, t))| {
                    a == b && s.theta == t.theta && s.keep_before == t.keep_before
                })
    }

    /// Whether this history and `other` are the same history, number by number: the same
    /// layout and equal pieces held exactly (not the ring's stale slots), split values, modes,
    /// moments and cached value. Two paths whose states coincide in this sense and in (U, V, …)
    /// stay identical under the same noise.
    pub(crate) fn coincides(&self, other: &History) -> bool {
        self.same_layout(other)
            && self.all == other.all
            && self.local.pieces() == other.local.pieces()
            && self.splits == other.splits
            && self.modes.y == other.modes.y
            && self.moments == other.moments
            && self.cached == other.cached
    }

    /// Whether every number of the history's state is zero (the history of g ≡ 0), the ring's
    /// stale slots aside.
    pub(crate) fn is_zero(&self) -> bool {
        let zero = |x: &f64| *x == 0.0;
        self.all.as_flattened().iter().all(zero)
            && self.local.pieces().as_flattened().iter().all(zero)
            && self
                .splits
                .iter()
                .all(|(_, s)| s.before == 0.0 && s.after == 0.0)
            && self.modes.y.as_flattened().iter().all(zero)
            && self.moments.iter().all(zero)
            && self.cached == 0.0
    }

    /// Pull this history toward `reference` by the factor `c`: every number x of its state
    /// becomes x_ref + c·(x − x_ref). The map is affine in the history and J^λ is linear in g,
    /// so this is exactly the history of the path g_ref + c·(g − g_ref): the renormalisation of
    /// a perturbed copy in Benettin's method, applied to the entire memory (a fractional
    /// system's state is its whole history, not just (U, V)). Returns false, changing nothing,
    /// when the two layouts differ (different steps, an impact split at different fractions, a
    /// restart in one of them).
    pub fn contract_toward(&mut self, reference: &History, c: f64) -> bool {
        if !self.same_layout(reference) {
            return false;
        }
        self.zip_state(Some(reference), &mut |r, v| {
            let r = r.expect("reference given");
            *v = r + c * (*v - r);
        });
        true
    }

    /// Number of exponential modes (0 for Direct or λ = 1).
    pub fn exponentials(&self) -> usize {
        self.soe.as_ref().map_or(0, |k| k.len())
    }

    /// Bytes of state held (grows with N for Direct, constant for SOE).
    pub fn state_bytes(&self) -> usize {
        8 * (2 * self.all.capacity()
            + 2 * self.local.pairs.len()
            + self.wl.capacity()
            + self.wr.capacity()
            + 5 * self.modes.len())
            + std::mem::size_of::<(u64, Split)>() * self.splits.capacity()
            + std::mem::size_of::<[f64; 4]>()
                * self.split_weights.iter().map(Vec::len).sum::<usize>()
    }
}

/// Solve the scalar Caputo problem D^α y = f(t, y), y(0) = y₀, α ∈ (0, 1], on the grid
/// t_n = n·dt, n = 0..=steps, with the same predictor–corrector and memory as the oscillator
/// (see [`crate::engine::Stepper`]): the predictor replaces f_{n+1} by f_n in the corrector's sum
/// (constant extrapolation of the composite f(t, y(t)), which stays smooth when y does not); only corrected values are stored (at α = 1: the trapezoidal rule in integral form,
/// corrected once from an Euler predictor). Returns y at every node.
pub fn solve_scalar(
    alpha: f64,
    f: &dyn Fn(f64, f64) -> f64,
    y0: f64,
    dt: f64,
    steps: usize,
    memory: Memory,
) -> Result<Vec<f64>> {
    let t_end = dt * steps as f64;
    let mut conv = History::new(alpha, dt, t_end, memory, DEFAULT_WINDOW)?;
    let mut ys = Vec::with_capacity(steps + 1);
    ys.push(y0);
    let mut fy = f(0.0, y0);
    let (wl, wr) = conv.current_weights();
    for n in 0..steps {
        let t1 = (n + 1) as f64 * dt;
        let base = y0 + conv.value() + wl * fy;
        let yp = base + wr * fy;
        let y1 = base + wr * f(t1, yp);
        if !y1.is_finite() {
            return Err(Error::Overflow {
                what: "scalar fractional solve",
                at: format!("t = {t1}"),
                value: y1,
            });
        }
        let f1 = f(t1, y1);
        conv.push(Piece {
            left: fy,
            right: f1,
            split: None,
        });
        fy = f1;
        ys.push(y1);
    }
    Ok(ys)
}

/// Push `steps` pieces of a smooth g into a fresh memory of order λ and return its final value:
/// the memory's own cost per step, for the engine's timing breakdown.
#[doc(hidden)]
pub fn probe_memory(lambda: f64, dt: f64, steps: usize) -> Result<f64> {
    let mut h = History::new(
        lambda,
        dt,
        dt * steps as f64,
        Memory::default(),
        DEFAULT_WINDOW,
    )?;
    // g = sin t by rotation (cheap, so that the probe times the memory, not `sin`)
    let (c, s) = (dt.cos(), dt.sin());
    let (mut left, mut cos) = (0.0, 1.0);
    let mut acc = 0.0;
    for _ in 0..steps {
        let right = left * c + cos * s;
        cos = cos * c - left * s;
        h.push(Piece {
            left,
            right,
            split: None,
        });
        acc += h.value();
        left = right;
    }
    Ok(acc)
}

/// What the tangent (variational) method needs from a history: the memory of δg is a second
/// [`History`] with the reference's layout (same kernel, same pieces held exactly, splits at the
/// same fractions), renormalised by scaling every number of it.
impl History {
    /// Multiply every number of the history's state by `c` (window, split values, SOE modes,
    /// lumped integral and moment, the cached value): the history of c·g, since J^λ is linear.
    pub(crate) fn scale_state(&mut self, c: f64) {
        self.zip_state(None, &mut |_, v| *v *= c);
    }

    /// Whether `other` holds its history in the same layout as this one (see
    /// [`History::contract_toward`]): a tangent memory must stay in step with its reference's.
    #[cfg(test)]
    pub(crate) fn same_layout_as(&self, other: &History) -> bool {
        self.same_layout(other)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scalar_solver_at_order_one_is_the_trapezoidal_predictor_corrector() {
        // y' = −y: S_n = y0 + trapezoidal sum of corrected f; y_{n+1} = S_n + h/2 (f_n + f(S_n + h f_n))
        let h = 0.1;
        for memory in [Memory::Direct, Memory::default()] {
            let ys = solve_scalar(1.0, &|_, y| -y, 1.0, h, 40, memory).unwrap();
            let (mut s, mut y) = (1.0, 1.0);
            for (n, &got) in ys.iter().enumerate().skip(1) {
                let f = -y;
                let yp = s + h * f;
                let y1 = s + 0.5 * h * (f - yp);
                s += 0.5 * h * (f - y1);
                y = y1;
                assert!((got - y).abs() < 1e-14, "{n}: {got} vs {y}");
            }
        }
    }

    #[test]
    fn moments_advance_exactly() {
        // pieces of lengths ℓ_j, linear from l_j to r_j; m_k = ∫ (t_m − s)ᵏ g(s) ds against
        // Simpson's rule, exact for the cubic-and-lower integrands of k ≤ 2 and, per piece,
        // for k = 3 after splitting each piece in 64
        let pieces: Vec<(f64, f64, f64)> = (0..40)
            .map(|j| {
                let j = j as f64;
                (
                    0.01 + 0.005 * (j * 0.7).sin().abs(),
                    (0.3 * j).cos(),
                    (0.3 * j + 0.2).sin(),
                )
            })
            .collect();
        let mut m = [0.0; LUMPED_TERMS];
        for &(len, l, r) in &pieces {
            advance_moments(&mut m, false, len, l, r);
        }
        let t_m: f64 = pieces.iter().map(|p| p.0).sum();
        for (k, &mk) in m.iter().enumerate() {
            let mut exact = 0.0;
            let mut start = 0.0;
            for &(len, l, r) in &pieces {
                let n = 64;
                let f = |x: f64| (t_m - start - x).powi(k as i32) * (l + (r - l) * x / len);
                let dx = len / n as f64;
                for i in 0..n {
                    let a = i as f64 * dx;
                    exact += dx / 6.0 * (f(a) + 4.0 * f(a + 0.5 * dx) + f(a + dx));
                }
                start += len;
            }
            assert!(
                (mk - exact).abs() <= 1e-13 * (1.0 + exact.abs()),
                "m{k}: {mk} vs {exact}"
            );
        }
        let mut flat = [0.0; LUMPED_TERMS];
        for &(len, l, r) in &pieces {
            advance_moments(&mut flat, true, len, l, r);
        }
        assert_eq!(flat[0], m[0]);
        // the lumped polynomial moved by `back`: Σ_k p_k (back + x)ᵏ = Σ_i out_i xⁱ
        let p = [0.9, -3e-3, 2e-5, -7e-8];
        let out = lumped_weights(&p, 0.16);
        for x in [0.0_f64, 1.0, 37.5, 1e3] {
            let direct: f64 = (0..4).map(|k| p[k] * (0.16 + x).powi(k as i32)).sum();
            let moved: f64 = (0..4).map(|i| out[i] * x.powi(i as i32)).sum();
            assert!(
                (direct - moved).abs() <= 1e-14 * direct.abs().max(1.0),
                "{x}"
            );
        }
    }

    #[test]
    fn portable_and_avx_memories_give_the_same_bits() {
        // the AVX path does the portable path's operations in the same order: same bits, so
        // results do not depend on the CPU (pieces leave the window, an impact split and the
        // odd number of mode blocks included)
        let mut a = [1e3, 1e4, 1e5, 1e6, 1e7]
            .into_iter()
            .map(|t| History::new(0.998, 0.01, t, Memory::default(), DEFAULT_WINDOW).unwrap())
            .find(|h| h.modes.y.len() % 2 == 1)
            .expect("a horizon with an odd number of mode blocks");
        if !a.avx {
            return;
        }
        let mut b = a.clone();
        b.avx = false;
        for n in 0..200 {
            let piece = Piece {
                left: (0.37 * n as f64).sin(),
                right: (0.37 * n as f64 + 0.3).cos(),
                split: (n == 50).then_some(Split {
                    theta: 0.4,
                    before: 3.0,
                    after: -1.0,
                    keep_before: true,
                }),
            };
            a.push(piece);
            b.push(piece);
            assert_eq!(a.value().to_bits(), b.value().to_bits(), "step {n}");
        }
    }

    #[test]
    fn histories_coincide_after_the_same_restart_whatever_their_stale_slots() {
        // two paths with different pasts that restart on the same step and then see the same
        // pieces hold the same history, although the ring's unused slots still differ
        let mut a = History::new(0.998, 0.01, 100.0, Memory::default(), DEFAULT_WINDOW).unwrap();
        let mut b = a.clone();
        let piece = |x: f64| Piece {
            left: x,
            right: x + 0.5,
            split: None,
        };
        for n in 0..20 {
            a.push(piece(n as f64));
            b.push(piece(n as f64 + 1e-8));
        }
        assert!(!a.coincides(&b));
        a.restart();
        b.restart();
        assert!(a.coincides(&b) && a.is_zero() && b.is_zero());
        for n in 0..3 {
            a.push(piece(-(n as f64)));
            b.push(piece(-(n as f64)));
        }
        assert!(a.coincides(&b));
        assert!(!a.is_zero());
        b.push(piece(1.0));
        assert!(!a.coincides(&b));
    }

    #[test]
    fn every_window_size_agrees_with_the_direct_memory() {
        // the fast path reads the window's older pieces as one run whose length is rounded up
        // to a multiple of four, zero-weighted values in front (a padding of two doubles when
        // the window holds an odd number of older pieces): against the exact O(N) memory, for
        // windows of 2 … 10 steps, through the fill, the steady state and a restart
        let g = |n: usize| (0.37 * n as f64).sin() + 0.02 * n as f64;
        for lambda in [0.6, 0.998] {
            for window in 2..=10 {
                let soe = Memory::SumOfExponentials { tolerance: 1e-12 };
                let mut fast = History::new(lambda, 0.01, 4.0, soe, window).unwrap();
                let mut exact = History::new(lambda, 0.01, 4.0, Memory::Direct, window).unwrap();
                let mut worst: f64 = 0.0;
                for n in 0..400 {
                    if n == 250 {
                        fast.restart();
                        exact.restart();
                    }
                    let piece = Piece {
                        left: g(n),
                        right: g(n + 1) + 0.01,
                        split: None,
                    };
                    fast.push(piece);
                    exact.push(piece);
                    let scale = exact.value().abs().max(1e-3);
                    worst = worst.max((fast.value() - exact.value()).abs() / scale);
                }
                assert!(worst < 1e-10, "λ = {lambda}, window {window}: {worst:e}");
            }
        }
    }

    #[test]
    fn scaling_the_history_equals_the_history_of_the_scaled_g() {
        // J^λ is linear: scale(c) after pieces of g = pieces of c·g, for every memory, through
        // the window, the modes and a split (impact) piece
        let c = 2.5;
        for memory in [Memory::Direct, Memory::default()] {
            for lambda in [0.9, 0.998, 1.0] {
                let mut a = History::new(lambda, 0.01, 10.0, memory, DEFAULT_WINDOW).unwrap();
                let mut b = a.clone();
                let g = |n: usize| (0.37 * n as f64).sin() + 0.1 * n as f64;
                let piece = |n: usize, k: f64| Piece {
                    left: k * g(n),
                    right: k * g(n + 1),
                    split: (n == 5).then_some(Split {
                        theta: 0.4,
                        before: k * 3.0,
                        after: -k,
                        keep_before: true,
                    }),
                };
                for n in 0..40 {
                    a.push(piece(n, 1.0));
                    b.push(piece(n, c));
                }
                a.scale(c);
                for n in 40..80 {
                    let (va, vb) = (a.value(), b.value());
                    assert!(
                        (va - vb).abs() <= 1e-13 * vb.abs().max(1.0),
                        "{memory:?} λ={lambda} n={n}: {va} vs {vb}"
                    );
                    let (fa, fb) = (a.at_fraction(0.3, 1.0).0, b.at_fraction(0.3, 1.0).0);
                    assert!((fa - fb).abs() <= 1e-13 * fb.abs().max(1.0));
                    a.push(piece(n, c));
                    b.push(piece(n, c));
                }
            }
        }
    }
}
