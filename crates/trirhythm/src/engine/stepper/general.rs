//! The General kernel: the terms of the class beyond the paper's Eq. (1) that the engine
//! steps — an odd restoring force, Rayleigh damping and a harmonic forcing — with the same
//! predictor–corrector as the paper's kernel ([`super::Affine`]), and its tangent.
//!
//! # Equation
//! D^{1+λ}U − h(U, U̇)U̇ + k(U) = F cos(Ωt + φ) + η(t), no wall, the wall at 0, or the model's
//! walls (one at any δ keeping U above or below it, two at δ1 < δ2: `super::walls`), with
//! h = μ0P(U) + Σ_{k≥1} d_k U̇^{2k} and k(U) = ω0²U + k3U³ + k5U⁵; in Volterra form
//! U′ = V, V = V₀ + J^λ g, g = h(U, V)V − k(U) + F cos ψ + η, ψ = Ωt + φ.
//!
//! # Method
//! The paper kernel's step (module docs of [`super`]) with g no longer affine in V. Each
//! corrector pass freezes U at its predictor U^P and linearises hV in V at a point V_l:
//! a = ∂_V(hV)(U^P, V_l) = μ0P(U^P) + Σ(2k+1)d_k V_l^{2k}, and
//!
//!   V_{n+1} = [N + w_r(F_r − k(U^P) + (h(U^P, V_l) − a)V_l)] / (1 − w_r a),
//!   U_{n+1} = U_n + Δt(V_n + V_{n+1})/2 + (Δt²/12)·L(2w_r a)·(g_n − g^P_{n+1}),
//!
//! N = V₀ + J + w_l g_n, g^P_{n+1} = h(U^P, V_{n+1})V_{n+1} − k(U^P) + F_r. The first pass
//! linearises at V_l = V_n (model-class.md §3), the second, from the first pass's U, at the
//! first pass's V (a Newton step on the Rayleigh term). Without Rayleigh terms a = μ0P(U^P),
//! (h − a)V_l = 0 and the pass is the paper's with ω0²U^P replaced by k(U^P). The predictor's
//! weight uses a = ∂_V(hV) at the node.
//!
//! **The forcing's phase is state.** Each path keeps (cos ψ_n, sin ψ_n), rotated at every
//! step by the fixed (cos ΩΔt, sin ΩΔt) (four products, no cos per step) and re-anchored from
//! ψ = φ + (ΩΔt·n mod 2π) every 256 steps, so that the rotation's rounding cannot accumulate;
//! F cos ψ enters g at the nodes, so the memory holds it as linear pieces (error O(Ω²Δt²)).
//! Clones (rare-event splitting, Lyapunov copies) carry the phase with the path. In the tangent
//! the phase is neutral: δψ ≡ 0 (a time shift is not a perturbation of the state).
//!
//! **Absent terms cost nothing.** A path holds this kernel only when its problem has one of
//! these terms ([`crate::engine::Oscillator::terms`]); [`super::Stepper::step`] takes one branch
//! on it, and the paper's arithmetic ([`super::Affine`]) is untouched (`tests/pinned.rs`
//! digests, recorded before this kernel existed). The lane stepper steps General paths path
//! by path (the scalar step in each lane's turn; same bits as alone), as does the lane tangent.
//!
//! **The wall at U = 0** (as the paper's): the impact is located and redone as in
//! `super::impact`, with g at the wall h(0, V)V + F cos ψ* + η* (k(0) = 0 for an odd k):
//! the scheme's V₋ solves V = N + w_s(h(0, V)V + F cos ψ* + η*), affine without Rayleigh terms
//! and else by Newton's method; ψ* = ψ_{n+1} − (1 − θ)ΩΔt; the rest of the step is this
//! kernel's step from (0, V₊); sticking and leaving the wall as for the paper's kernel. The
//! tangent of such impact steps is not built yet: `lyapunov --method tangent` refuses a
//! General model with a wall (two trajectories take it).
//!
//! **The model's walls** (a wall off 0, keeping U below, two walls, a speed-dependent
//! restitution r(|U̇₋|)): `super::walls` — the same location and redone rest with g at the wall
//! h(δ, V)V − k(δ) + F cos ψ* + η* ([`General::wall_drift`], [`General::wall_velocity`] take δ),
//! and sticking at δ while the net force there pushes into the wall. A General path holds them
//! in `walls`; without them no step looks further than one `Option`.
//!
//! Not yet: fractional terms K·D^αU, multiplicative noise, the tangent of impact steps.
//!
//! # Reference
//! model-class.md §2, §3, §4, §5 (the design); Diethelm, Ford & Freed (2002) for the scheme.
//!
//! # Tests
//! `tests/general.rs`: the Duffing oscillator under white noise against its exact stationary
//! density ∝ exp(−cH/D) (⟨U²⟩, ⟨U̇²⟩ = D/c by quadrature); the forced linear oscillator's
//! steady amplitude against |F·H(iΩ)| at λ = 1 and λ = 0.9, with its observed convergence as Δt
//! halves; a Rayleigh oscillator's cycle; lanes and clones give the scalar bits; at the wall,
//! the paper kernel's bits when the terms vanish (k3 = 1e-300) and a Duffing oscillator at
//! r = 1 keeping energy and half-period at second order. `tests/walls.rs`: the model's walls
//! (exact periods between two walls and against an offset wall at r = 1 with the energy kept,
//! at second order; r(|U̇₋|); sticking at δ). `engine/stepper/tangent.rs`: the tangent step
//! against finite differences of the step.

use super::affine::{hermite_limiter, predictor_weight, predictor_weight_slope, Affine};
use super::polynomial::Polynomial;
use super::walls::Walls;
use crate::maths;
use crate::model::{GeneralTerms, Harmonic};

/// Steps between re-anchorings of the forcing's phase.
const REANCHOR: u64 = 256;

/// F cos ψ, ψ = Ωt + φ, with the phase as state: (cos ψ_n, sin ψ_n) at the current node n.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Phase {
    amplitude: f64,
    /// ΩΔt.
    angle: f64,
    phi: f64,
    /// (cos ΩΔt, sin ΩΔt).
    rotation: (f64, f64),
    /// (cos ψ_n, sin ψ_n).
    now: (f64, f64),
    /// The node's index n.
    n: u64,
}

impl Phase {
    fn new(f: &Harmonic, h: f64) -> Self {
        let angle = f.frequency * h;
        Phase {
            amplitude: f.amplitude,
            angle,
            phi: f.phase,
            rotation: (maths::cos(angle), maths::sin(angle)),
            now: (maths::cos(f.phase), maths::sin(f.phase)),
            n: 0,
        }
    }

    /// F cos ψ at the current node.
    #[inline]
    fn force(&self) -> f64 {
        self.amplitude * self.now.0
    }

    /// Move to the next node; returns F cos ψ there.
    #[inline]
    fn advance(&mut self) -> f64 {
        self.n += 1;
        if self.n % REANCHOR == 0 {
            let psi = self.phi + (self.angle * self.n as f64).rem_euclid(std::f64::consts::TAU);
            self.now = (maths::cos(psi), maths::sin(psi));
        } else {
            let (c, s) = self.now;
            let (cr, sr) = self.rotation;
            self.now = (c * cr - s * sr, s * cr + c * sr);
        }
        self.force()
    }
}

/// g = h(U, V)V − k(U) + F cos ψ + η of the General kernel (module docs), with the path's
/// forcing phase.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct General {
    /// μ0P in U².
    damping: Polynomial,
    /// Its derivative in U².
    slope: Polynomial,
    /// d_k (k ≥ 1: `rayleigh[0]` multiplies V²).
    rayleigh: Vec<f64>,
    omega2: f64,
    cubic: f64,
    quintic: f64,
    phase: Option<Phase>,
    /// The model's walls when not the paper's (`super::walls`); None: no wall or the paper's
    /// wall at 0 (the stepper's `wall`).
    pub(super) walls: Option<Walls>,
}

/// The Rayleigh parts at a velocity v (x = v²): Σd_k x^k, Σ(2k+1)d_k x^k (∂_V of its V-term),
/// its derivative in v, and the linearisation's rest (h − a)v with its derivative in v.
#[derive(Debug, Clone, Copy, Default)]
struct RayleighAt {
    h: f64,
    a: f64,
    a_slope: f64,
    rest: f64,
    rest_slope: f64,
}

/// One pass of the General corrector (module docs), kept for the tangent.
#[derive(Debug, Clone, Copy)]
pub(super) struct GeneralPass {
    up: f64,
    /// The velocity the pass linearises at.
    vl: f64,
    /// ∂_V(hV)(up, vl).
    a: f64,
    inv: f64,
    lim: f64,
    /// g at the end with U at up.
    gr: f64,
    u1: f64,
    v1: f64,
}

/// A General step of length `len` (two passes), kept for the tangent.
#[derive(Debug, Clone, Copy)]
pub(super) struct GeneralFree {
    len: f64,
    w: f64,
    g0: f64,
    pw: f64,
    passes: [GeneralPass; 2],
}

impl GeneralFree {
    /// The end (U₁, V₁).
    #[inline]
    pub(super) fn end(&self) -> (f64, f64) {
        let p = &self.passes[1];
        (p.u1, p.v1)
    }
}

impl General {
    /// The kernel of the paper kernel `affine`'s μ0P and ω0² with `terms`, steps of `h`.
    pub(super) fn new(affine: &Affine, terms: &GeneralTerms, h: f64) -> Self {
        General {
            damping: affine.damping.clone(),
            slope: affine.slope.clone(),
            rayleigh: terms.rayleigh.clone(),
            omega2: affine.omega2,
            cubic: terms.cubic,
            quintic: terms.quintic,
            phase: terms.forcing.as_ref().map(|f| Phase::new(f, h)),
            walls: Walls::new(&terms.walls),
        }
    }

    /// k(U) = ω0²U + k3U³ + k5U⁵.
    #[inline]
    pub(super) fn restoring(&self, u: f64) -> f64 {
        let x = u * u;
        u * (self.omega2 + x * (self.cubic + self.quintic * x))
    }

    /// k′(U).
    #[inline]
    fn restoring_slope(&self, u: f64) -> f64 {
        let x = u * u;
        self.omega2 + x * (3.0 * self.cubic + 5.0 * self.quintic * x)
    }

    /// μ0P(U).
    #[inline]
    fn mu_p(&self, u: f64) -> f64 {
        self.damping.eval(u * u)
    }

    /// d(μ0P)/dU.
    #[inline]
    fn mu_p_slope(&self, u: f64) -> f64 {
        2.0 * u * self.slope.eval(u * u)
    }

    #[inline]
    fn rayleigh_at(&self, v: f64) -> RayleighAt {
        if self.rayleigh.is_empty() {
            return RayleighAt::default();
        }
        let x = v * v;
        let (mut h, mut a, mut a_slope, mut rest_slope) = (0.0, 0.0, 0.0, 0.0);
        let mut before = 1.0; // x^{k−1}
        for (i, &d) in self.rayleigh.iter().enumerate() {
            let k = (i + 1) as f64;
            let pow = before * x;
            h += d * pow;
            a += (2.0 * k + 1.0) * d * pow;
            a_slope += (2.0 * k + 1.0) * 2.0 * k * d * before;
            rest_slope -= 2.0 * k * (2.0 * k + 1.0) * d * pow;
            before = pow;
        }
        RayleighAt {
            h,
            a,
            a_slope: a_slope * v,
            rest: (h - a) * v,
            rest_slope,
        }
    }

    /// ∂_V(hV) at (u, v).
    #[inline]
    pub(super) fn a(&self, u: f64, v: f64) -> f64 {
        self.mu_p(u) + self.rayleigh_at(v).a
    }

    /// h(U, V)V − k(U): g without its forcing.
    #[inline]
    pub(super) fn drift(&self, u: f64, v: f64) -> f64 {
        (self.mu_p(u) + self.rayleigh_at(v).h) * v - self.restoring(u)
    }

    /// δ of [`General::drift`] along (δu, δv).
    pub(super) fn drift_derivative(&self, u: f64, v: f64, du: f64, dv: f64) -> f64 {
        (self.mu_p_slope(u) * v - self.restoring_slope(u)) * du + self.a(u, v) * dv
    }

    /// The drift and the predictor's weight at a node (u1, v1), steps of `h`.
    #[inline]
    pub(super) fn node(&self, h: f64, u1: f64, v1: f64) -> (f64, f64) {
        (self.drift(u1, v1), predictor_weight(h, self.a(u1, v1)))
    }

    /// The harmonic forcing F cos ψ at the current node (0 without forcing).
    #[inline]
    pub(super) fn force_now(&self) -> f64 {
        self.phase.as_ref().map_or(0.0, Phase::force)
    }

    /// F cos ψ at the fraction θ of the step that ends at the current node (after
    /// [`General::forces`]): ψ = ψ_{n+1} − (1 − θ)ΩΔt (an impact's instant; 0 without forcing).
    pub(super) fn force_at(&self, theta: f64) -> f64 {
        match &self.phase {
            None => 0.0,
            Some(p) => {
                let back = (1.0 - theta) * p.angle;
                let (c, s) = p.now;
                p.amplitude * (c * maths::cos(back) + s * maths::sin(back))
            }
        }
    }

    /// g at a wall U = δ without its forcing: h(δ, V)V − k(δ) (at δ = 0, h(0, V)V exactly:
    /// k(0) = +0).
    #[inline]
    pub(super) fn wall_drift(&self, delta: f64, v: f64) -> f64 {
        (self.mu_p(delta) + self.rayleigh_at(v).h) * v - self.restoring(delta)
    }

    /// The scheme's velocity at an impact on a wall U = δ: the root of
    /// V = N + w(h(δ, V)V + forcing), `forcing` holding −k(δ) (affine in V without Rayleigh
    /// terms: solved at once; else Newton's method from that value, to |ΔV| ≤ 1e-14(1 + |V|),
    /// at most 50 iterations).
    pub(super) fn wall_velocity(&self, delta: f64, known: f64, w: f64, forcing: f64) -> f64 {
        let a0 = self.mu_p(delta);
        let mut v = (known + w * forcing) / (1.0 - w * a0);
        if self.rayleigh.is_empty() {
            return v;
        }
        for _ in 0..50 {
            let r = self.rayleigh_at(v);
            let f = v - known - w * ((a0 + r.h) * v + forcing);
            let df = 1.0 - w * (a0 + r.a);
            let step = f / df;
            v -= step;
            // a NaN step ends the iteration too
            if step.is_nan() || step.abs() <= 1e-14 * (1.0 + v.abs()) {
                break;
            }
        }
        v
    }

    /// The harmonic forcing at the current node and at the next, the phase moved there (0, 0
    /// without forcing).
    #[inline]
    pub(super) fn forces(&mut self) -> (f64, f64) {
        match &mut self.phase {
            None => (0.0, 0.0),
            Some(p) => {
                let left = p.force();
                (left, p.advance())
            }
        }
    }

    /// One pass with U frozen at `up`, hV linearised at `vl`.
    #[allow(clippy::too_many_arguments)]
    fn pass(
        &self,
        len: f64,
        (u, v, g0): (f64, f64, f64),
        (up, vl): (f64, f64),
        known: f64,
        w: f64,
        fr: f64,
    ) -> GeneralPass {
        let mp = self.mu_p(up);
        let r = self.rayleigh_at(vl);
        let a = mp + r.a;
        let k = self.restoring(up);
        let inv = 1.0 / (1.0 - w * a);
        let lim = hermite_limiter(2.0 * w * a);
        let v1 = (known + w * (fr - k + r.rest)) * inv;
        let gr = (mp + self.rayleigh_at(v1).h) * v1 - k + fr;
        let u1 = u + 0.5 * len * (v + v1) + len * len * (1.0 / 12.0) * lim * (g0 - gr);
        GeneralPass {
            up,
            vl,
            a,
            inv,
            lim,
            gr,
            u1,
            v1,
        }
    }

    /// The step of length `len` from (u, v) where g = `g0` (module docs): `pw` the predictor's
    /// weight, `known` the part of V at the end not depending on g there, `w` the weight of g
    /// at the end, `fr` the forcing (noise and harmonic) there.
    pub(super) fn advance(
        &self,
        len: f64,
        (u, v, g0): (f64, f64, f64),
        pw: f64,
        known: f64,
        w: f64,
        fr: f64,
    ) -> GeneralFree {
        let start = (u, v, g0);
        let first = self.pass(len, start, (u + len * v + pw * g0, v), known, w, fr);
        let second = self.pass(len, start, (first.u1, first.v1), known, w, fr);
        GeneralFree {
            len,
            w,
            g0,
            pw,
            passes: [first, second],
        }
    }

    /// The derivative of one pass along (δu, δv, δg0), δup, δvl, δknown: (δU₁, δV₁).
    fn pass_tangent(
        &self,
        f: &GeneralFree,
        p: &GeneralPass,
        (du, dv, dg0): (f64, f64, f64),
        (dup, dvl): (f64, f64),
        dknown: f64,
    ) -> (f64, f64) {
        let mps = self.mu_p_slope(p.up);
        let r = self.rayleigh_at(p.vl);
        let da = mps * dup + r.a_slope * dvl;
        let kp = self.restoring_slope(p.up);
        let dv1 = p.inv * (dknown + f.w * (r.rest_slope * dvl - kp * dup) + p.v1 * f.w * da);
        let a_end = self.mu_p(p.up) + self.rayleigh_at(p.v1).a;
        let dgr = mps * dup * p.v1 + a_end * dv1 - kp * dup;
        let z = 2.0 * f.w * p.a;
        let dlim = -p.lim * p.lim * (z / 6.0) * 2.0 * f.w * da;
        let c = f.len * f.len / 12.0;
        let du1 = du + 0.5 * f.len * (dv + dv1) + c * (dlim * (f.g0 - p.gr) + p.lim * (dg0 - dgr));
        (du1, dv1)
    }

    /// The derivative of [`General::advance`] from (u, v) along (δu, δv, δg0) and δknown (the
    /// forcing frozen: noise and phase): (δU₁, δV₁).
    pub(super) fn advance_tangent(
        &self,
        f: &GeneralFree,
        (u, v): (f64, f64),
        (du, dv, dg0): (f64, f64, f64),
        dknown: f64,
    ) -> (f64, f64) {
        let a0 = self.a(u, v);
        let da0 = self.mu_p_slope(u) * du + self.rayleigh_at(v).a_slope * dv;
        let dpw = predictor_weight_slope(f.len, a0, da0);
        let dup = du + f.len * dv + f.pw * dg0 + f.g0 * dpw;
        let first = self.pass_tangent(f, &f.passes[0], (du, dv, dg0), (dup, dv), dknown);
        self.pass_tangent(f, &f.passes[1], (du, dv, dg0), first, dknown)
    }
}
