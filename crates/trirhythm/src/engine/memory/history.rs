//! [`History`]: the whole memory of J^λ g of one path, its construction, its queries and the
//! fast path of a push.
//!
//! Equation: J^λ g(t_{n+1}) = (h^λ/Γ(λ)) Σ (exact window) + Σ_j w_j e^{−s_j·back} Y_j
//! (exponential modes) + Σ_i out_i m_i (lumped moments), the kernel of
//! [`crate::engine::kernel`].
//!
//! Method: see the parent module (the step's dependency chain, the fast path's order of
//! operations).
//!
//! Reference: Diethelm, Ford & Freed, Nonlinear Dyn. 29 (2002) 3–22; Jiang, Zhang, Zhang &
//! Zhang, Commun. Comput. Phys. 21 (2017) 650–678.
//!
//! Tests: the memory's unit tests; `tests/soe.rs`.

use super::modes::{advance_modes, Modes};
use super::moments::{dot_moments, lumped_weights, MomentStep};
use super::window::{dot, Window};
#[cfg(target_arch = "x86_64")]
use super::{modes::advance_modes_avx, window::dot_avx};
use super::{piece_integral, piece_shift_rate, Memory, Piece, Split};
use crate::engine::kernel::{phi_psi, IntervalWeights, Powers, SoeKernel, LUMPED_TERMS};
use crate::error::{Error, Result};
use crate::maths::{exp, pow};
use crate::special::gamma;

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
    pub(super) iw: IntervalWeights,
    pub(super) dt: f64,
    /// h^λ / Γ(λ)
    pub(super) scale: f64,
    pub(super) direct: bool,
    /// Direct: every piece (chronological); SOE: the last `window − 1` (none at λ = 1).
    pub(super) all: Vec<[f64; 2]>,
    pub(super) local: Window,
    /// Split pieces still held exactly, by sequence number (pieces pushed since the start).
    pub(super) splits: Vec<(u64, Split)>,
    /// For each held split (same order), with a window: its scaled corrections — exact minus
    /// plain weights of (left, before, after, right), and the weight of its point mass (0 when
    /// it has none) — at distances 1..=cap (index p − 1), computed once when the split is
    /// pushed, so that the fast path carries split pieces.
    pub(super) split_weights: Vec<Vec<[f64; 5]>>,
    pub(super) pushed: u64,
    /// Weights of left/right of an unsplit piece at distance p (index p).
    pub(super) wl: Vec<f64>,
    pub(super) wr: Vec<f64>,
    /// SOE with a window, the fast path of [`History::push`]: the weights (wl, wr) of the
    /// window's older pieces (distances cap … 2) times h^λ/Γ(λ), interleaved as the window
    /// stores its pieces, after zeros up to a multiple of four ([`Window::older_run`]).
    pub(super) older: Vec<f64>,
    /// The scaled weights of the newest piece (distance 1).
    pub(super) newest: (f64, f64),
    /// The moments' advance over one full step, its coefficients precomputed.
    pub(super) moment_step: MomentStep,
    pub(super) soe: Option<SoeKernel>,
    /// SOE mode state Y_j = ∫ e^{−s_j (t_m − s)} g(s) ds up to the window's start t_m.
    pub(super) modes: Modes,
    /// The CPU runs AVX (the modes are advanced four lanes at once, same bits).
    pub(super) avx: bool,
    /// The SOE kernel's lumped polynomial p₀…p₃ (copied out of `soe` for the hot path); at
    /// λ = 1 only p₀ ≠ 0 (`flat`), and only the integral is kept.
    pub(super) lumped: [f64; LUMPED_TERMS],
    pub(super) flat: bool,
    /// The lumped polynomial's weights of the moments at the fixed distance back = w·h of the
    /// window's start from the next node (w = cap + 1): Σ_k p_k (back + x)ᵏ = Σ_i out_i xⁱ.
    pub(super) lumped_out: [f64; LUMPED_TERMS],
    /// m_k = ∫ (t_m − s)ᵏ g(s) ds, k = 0…3, over the history up to the window's start t_m
    /// (the lumped terms' state; m₀ is ∫ g).
    pub(super) moments: [f64; LUMPED_TERMS],
    /// The history's value for the next step.
    pub(super) cached: f64,
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
        let scale = pow(dt, lambda) / gamma(lambda);
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
        if let Some(tolerance) = memory.tolerance(dt) {
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
                flat[1].push(exp(-z));
                flat[2].push(dt * psi);
                flat[3].push(dt * (phi - psi));
                flat[4].push(w * exp(-s * back));
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
    pub(super) fn grow_weights(&mut self, p: usize) {
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
        let memo = &mut Powers::default();
        let (wa, wb) = self.iw.of_with(0.0, mid, memo);
        let mut known = wb * split.after;
        if split.keep_before {
            let (wa2, wb2) = self.iw.of_with(mid, 1.0, memo);
            known += wa2 * split.before + wb2 * left;
        }
        (self.scale * known, self.scale * wa)
    }

    /// The derivatives in θ of [`History::current_split`]'s two numbers, with the values of
    /// the split held: the part after the impact, [0, 1 − θ] in distances from t_{n+1},
    /// shrinks at its far end, the part before, [1 − θ, 1], grows at its near end.
    pub fn current_split_rate(&self, left: f64, split: &Split) -> (f64, f64) {
        let mid = 1.0 - split.theta;
        let memo = &mut Powers::default();
        // d/dθ = −d/d(mid)
        let (_, _, (dwa, dwb)) = self.iw.rates_with(0.0, mid, memo);
        let mut dknown = dwb * split.after;
        if split.keep_before {
            let (_, (dwa2, dwb2), _) = self.iw.rates_with(mid, 1.0, memo);
            dknown += dwa2 * split.before + dwb2 * left;
        }
        (-self.scale * dknown, -self.scale * dwa)
    }

    /// The pieces held exactly as (left, right), oldest first.
    pub(super) fn held(&self) -> &[[f64; 2]] {
        if self.direct {
            &self.all
        } else {
            self.local.pieces()
        }
    }

    /// The pieces held exactly, oldest first, with their splits.
    pub(super) fn exact_pieces(&self) -> impl Iterator<Item = Piece> + '_ {
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
        let memo = &mut Powers::default();
        for (k, piece) in self.exact_pieces().enumerate() {
            sum += piece_integral(&self.iw, &piece, (len - k) as f64 - shift, memo);
        }
        let mut total = self.scale * sum;
        if let Some(kernel) = &self.soe {
            let back = ((self.local.cap + 1) as f64 - shift) * self.dt;
            let y = self.modes.y.iter().flatten();
            for ((&s, &w), &y) in kernel.rates.iter().zip(&kernel.weights).zip(y) {
                total += w * exp(-s * back) * y;
            }
            total += dot_moments(&lumped_weights(&kernel.lumped, back), &self.moments);
        }
        let (wa, wb) = self.iw.of_with(0.0, theta, memo);
        (total + self.scale * wb * left, self.scale * wa)
    }

    /// The derivatives in θ of [`History::at_fraction`]'s two numbers (J at t_n + θh of the
    /// completed pieces and of the current step's part [t_n, t_n + θh], which is held as the
    /// line from `left` at t_n to the unknown value at the instant; the weight of that value):
    /// the instant moves, every distance to the past grows. The window's pieces by the
    /// derivatives of their weights ([`piece_shift_rate`]), the modes by −s_j·w_j e^{−s_j·back},
    /// the lumped cubic by its derivative, the current part by ∂/∂u_b of the weights of [0, θ]
    /// (the piece stretches with the instant). The derivative of the memory as the stepper
    /// computes it, the SOE kernel included (the tangent's impact step).
    pub fn at_fraction_rate(&self, theta: f64, left: f64) -> (f64, f64) {
        let shift = 1.0 - theta;
        let len = self.held().len();
        let mut sum = 0.0;
        let memo = &mut Powers::default();
        for (k, piece) in self.exact_pieces().enumerate() {
            sum += piece_shift_rate(&self.iw, &piece, (len - k) as f64 - shift, memo);
        }
        let mut total = self.scale * sum;
        if let Some(kernel) = &self.soe {
            let back = ((self.local.cap + 1) as f64 - shift) * self.dt;
            let y = self.modes.y.iter().flatten();
            for ((&s, &w), &y) in kernel.rates.iter().zip(&kernel.weights).zip(y) {
                total -= s * self.dt * w * exp(-s * back) * y;
            }
            let p = &kernel.lumped;
            let dp = [p[1], 2.0 * p[2], 3.0 * p[3], 0.0];
            total += self.dt * dot_moments(&lumped_weights(&dp, back), &self.moments);
        }
        let (_, _, (dwa, dwb)) = self.iw.rates_with(0.0, theta, memo);
        (total + self.scale * dwb * left, self.scale * dwa)
    }

    /// Store a completed (corrected) piece and prepare the history of the next step.
    // always: the constant kernel's running integral and the choice of the path are a few
    // operations, inlined into the step (a call on every step otherwise: measured 3–4 % of the
    // lane-8 step at λ = 0.998); the fast path and the general one are one call away
    #[inline(always)]
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

    #[inline(never)]
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
        let mut moments = self.moments;
        if let Some((l0, r0)) = leaving {
            if !self.modes.y.is_empty() {
                off = advance(&mut self.modes, l0, r0);
            }
            moments = self.moment_step.advanced(&moments, self.flat, l0, r0);
            self.moments = moments;
        }
        off += self.lumped_value_of(&moments);
        off += dot(self.local.older_run(self.older.len()), &self.older);
        self.cached = off + (self.newest.0 * left + self.newest.1 * right);
        if !self.splits.is_empty() {
            self.cached += self.held_split_corrections();
        }
    }

    /// The lumped slow rates' contribution at the next node.
    #[inline(always)]
    pub(super) fn lumped_value(&self) -> f64 {
        self.lumped_value_of(&self.moments)
    }

    /// The lumped slow rates' contribution at the next node with the moments `m`.
    #[inline(always)]
    fn lumped_value_of(&self, m: &[f64; LUMPED_TERMS]) -> f64 {
        if self.flat {
            self.lumped[0] * m[0]
        } else {
            dot_moments(&self.lumped_out, m)
        }
    }

    /// Whether the next push moves a split piece out of a full window (the general path).
    #[inline]
    pub(super) fn split_leaves(&self) -> bool {
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
    pub(super) fn held_split_corrections(&self) -> f64 {
        let held = self.local.pieces();
        let first = self.pushed - held.len() as u64;
        let mut acc = 0.0;
        for (&(seq, s), w) in self.splits.iter().zip(&self.split_weights) {
            let [l, r] = held[(seq - first) as usize];
            let c = w[(self.pushed - seq) as usize - 1];
            acc += ((c[0] * l + c[1] * s.before) + c[2] * s.after) + c[3] * r;
            if s.mass != 0.0 {
                acc += c[4] * s.mass;
            }
        }
        acc
    }
}

impl History {
    /// [`History::export`] of a memory of its own (a fractional term's): with its λ, Δt and
    /// the φ, ψ series, which a [`crate::engine::StepPlan`] otherwise takes from the step.
    pub(crate) fn export_memory(
        &self,
        plan: &mut crate::engine::StepPlan,
    ) -> std::result::Result<(), (&'static str, usize, usize)> {
        self.export(plan)?;
        plan.lambda = self.iw.lambda();
        plan.h = self.dt;
        (plan.phi_series, plan.psi_series) = crate::engine::kernel::phi_psi_series();
        Ok(())
    }

    /// Copy the empty memory's constants into `plan` (module docs of [`crate::engine::StepPlan`]);
    /// `Err((what, n, max))` when the window or the kernel exceeds the plan's sizes.
    pub(crate) fn export(
        &self,
        plan: &mut crate::engine::StepPlan,
    ) -> std::result::Result<(), (&'static str, usize, usize)> {
        use crate::engine::{PLAN_MAX_CAP, PLAN_MAX_MODES};
        let cap = self.local.cap;
        if cap > PLAN_MAX_CAP {
            return Err(("window − 1", cap, PLAN_MAX_CAP));
        }
        let modes = 4 * self.modes.y.len();
        if modes > PLAN_MAX_MODES {
            return Err((
                "the number of exponentials (padded to 4)",
                modes,
                PLAN_MAX_MODES,
            ));
        }
        plan.scale = self.scale;
        (plan.wl0, plan.wr0) = self.current_weights();
        plan.cap = cap as u32;
        plan.wl[..=cap].copy_from_slice(&self.wl[..=cap]);
        plan.wr[..=cap].copy_from_slice(&self.wr[..=cap]);
        plan.older_len = self.older.len() as u32;
        plan.older[..self.older.len()].copy_from_slice(&self.older);
        plan.newest = [self.newest.0, self.newest.1];
        plan.modes = modes as u32;
        let flat = |v: &[[f64; 4]], out: &mut [f64]| {
            for (o, x) in out.iter_mut().zip(v.iter().flatten()) {
                *o = *x;
            }
        };
        flat(&self.modes.decay, &mut plan.decay);
        flat(&self.modes.start, &mut plan.start);
        flat(&self.modes.end, &mut plan.end);
        flat(&self.modes.out, &mut plan.out);
        if let Some(k) = &self.soe {
            plan.soe = 1;
            plan.n_exp = k.rates.len() as u32;
            plan.rates[..k.rates.len()].copy_from_slice(&k.rates);
            plan.weights[..k.weights.len()].copy_from_slice(&k.weights);
        }
        plan.lumped = self.lumped;
        plan.lumped_out = self.lumped_out;
        plan.flat = u32::from(self.flat);
        (plan.shift, plan.piece) = self.moment_step.coefficients();
        (plan.iw_even, plan.iw_odd, plan.iw_whole) = self.iw.tables();
        Ok(())
    }
}
