//! The paper's kernel: g(U, V, η) = μP(U)V − ω²U + γ·side·η, affine in V, for Eq. (1), (5)
//! and (9) — the arithmetic of the step ([`Affine::advance`]: the predictor, the two linearly
//! implicit corrector passes, the Hermite-corrected U) and its tangent. Moved verbatim from
//! `stepper/mod.rs` (where it was `Affine`) when the General kernel (`super::general`) came: the
//! same expressions in the same order, so the same bits (`tests/pinned.rs`). The method is in
//! the module docs of [`super`].

use super::polynomial::Polynomial;
use crate::engine::{Oscillator, System};

/// g(U, V, η) = μP(U)V − ω²U + γ·side·η of one system.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Affine {
    pub lambda: f64,
    /// μP as a polynomial in U².
    pub(super) damping: Polynomial,
    /// Its derivative in U², so that d(μP)/dU = 2U·slope(U²) (the tangent method).
    pub(super) slope: Polynomial,
    pub(crate) omega2: f64,
    pub(crate) gain: f64,
    pub(crate) restitution: f64,
}

impl Affine {
    pub fn new(osc: &Oscillator, system: System) -> Self {
        let p = osc.params();
        let e = osc.equivalents();
        match system {
            System::Fractional => Affine {
                lambda: p.lambda,
                slope: Polynomial::scaled(p.mu0, &p.damping.coefficients).derivative(),
                damping: Polynomial::scaled(p.mu0, &p.damping.coefficients),
                omega2: p.omega0 * p.omega0,
                gain: 1.0,
                restitution: p.restitution,
            },
            System::Equivalent | System::Zhuravlev => {
                let mut c = p.damping.coefficients.clone();
                c[0] = e.beta1;
                Affine {
                    lambda: 1.0,
                    slope: Polynomial::scaled(e.mu1, &c).derivative(),
                    damping: Polynomial::scaled(e.mu1, &c),
                    omega2: e.omega1 * e.omega1,
                    gain: e.beta2,
                    restitution: p.restitution,
                }
            }
        }
    }

    /// μP(U), the coefficient of V in g.
    /// μ times the damping polynomial's coefficients in U² (for [`crate::engine::StepPlan`]).
    pub(crate) fn damping_coefficients(&self) -> Vec<f64> {
        match &self.damping {
            Polynomial::Short(c) => c.to_vec(),
            Polynomial::Long(c) => c.clone(),
        }
    }

    #[inline]
    pub(super) fn damping(&self, u: f64) -> f64 {
        self.damping.eval(u * u)
    }

    /// d(μP)/dU = 2U·(μP)′ in U², the tangent method's derivative of the damping.
    #[inline]
    pub(super) fn damping_slope(&self, u: f64) -> f64 {
        2.0 * u * self.slope.eval(u * u)
    }

    /// The drift μP(U)V − ω²U and the predictor's weight at a node (u1, v1) where μP = `a1`,
    /// for steps of length `h`.
    #[inline(always)]
    pub(super) fn node(&self, h: f64, a1: f64, u1: f64, v1: f64) -> (f64, f64) {
        node_with(self.omega2, h, a1, u1, v1)
    }

    /// The deterministic part μP(U)V − ω²U of g.
    #[inline]
    pub(super) fn drift(&self, u: f64, v: f64) -> f64 {
        self.damping(u) * v - self.omega2 * u
    }

    /// The forcing term γ·side·η.
    #[inline]
    pub(super) fn forcing(&self, eta: f64, side: f64) -> f64 {
        self.gain * side * eta
    }
}

/// [`Affine::node`] with ω² = `omega2` given (the lane stepper's lanes may each have their own).
#[inline(always)]
pub(super) fn node_with(omega2: f64, h: f64, a1: f64, u1: f64, v1: f64) -> (f64, f64) {
    (a1 * v1 - omega2 * u1, predictor_weight(h, a1))
}

/// The predictor's weight of g at the start of a step of length `len`: ½len²/(1 + len|a|), a
/// = μP(U) there. ½len² is the Taylor term (U″ = V′ ≈ g); the factor 1/(1 + len|a|) keeps the
/// predictor bounded where the damping is stiff (|a|len ≫ 1: it tends to len/(2|a|), the
/// linearly implicit Euler's velocity increment) and changes it by O(len³) elsewhere.
#[inline]
pub(super) fn predictor_weight(len: f64, a: f64) -> f64 {
    0.5 * len * len / (1.0 + len * a.abs())
}

/// d/dU of [`predictor_weight`] where da/dU = `slope`.
pub(super) fn predictor_weight_slope(len: f64, a: f64, slope: f64) -> f64 {
    let d = 1.0 + len * a.abs();
    -0.5 * len * len * len * a.signum() * slope / (d * d)
}

/// d/d(len) of [`predictor_weight`] at a fixed a: len(1 + ½len|a|)/(1 + len|a|)² (the rest of
/// an impact step, whose length moves with the impact).
pub(super) fn predictor_weight_len_slope(len: f64, a: f64) -> f64 {
    let d = 1.0 + len * a.abs();
    len * (1.0 + 0.5 * len * a.abs()) / (d * d)
}

/// The factor 1/(1 + z²/12) of the Hermite correction of U, z = 2w·a the stiffness of the
/// step's implicit velocity (z = Δt·μP at λ = 1).
#[inline]
pub(super) fn hermite_limiter(z: f64) -> f64 {
    1.0 / (1.0 + z * z * (1.0 / 12.0))
}

/// δU₁ of one corrector pass, the tail of the pass tangents of both kernels ([`Affine`]'s and
/// `super::general`'s): `step` = (len, w, g0), `pass` = (a, lim, g_r) at the pass, along
/// (δu, δv, δg0) with (δV₁, δg_r, δa) of the pass already formed. With z = 2w·a,
/// δL = −L²(z/6)·2w·δa and δU₁ = δu + (len/2)(δv + δV₁) + (len²/12)(δL(g0 − g_r) + L(δg0 − δg_r)).
#[inline(always)]
pub(super) fn pass_tangent_u1(
    (len, w, g0): (f64, f64, f64),
    (a, lim, gr): (f64, f64, f64),
    (du, dv, dg0): (f64, f64, f64),
    (dv1, dgr, da): (f64, f64, f64),
) -> f64 {
    let z = 2.0 * w * a;
    let dlim = -lim * lim * (z / 6.0) * 2.0 * w * da;
    let c = len * len / 12.0;
    du + 0.5 * len * (dv + dv1) + c * (dlim * (g0 - gr) + lim * (dg0 - dgr))
}

/// [`pass_tangent_u1`] with the step's length and weight moving (the rest of an impact step):
/// `pass` = (a, lim, g_r, V₁), `moving` = (v at the start, δlen, δ(wa)), so that
/// δL = −L²(z/6)·2δ(wa) and U₁'s terms in len are differentiated as well.
#[inline(always)]
pub(super) fn pass_tangent_u1_moving(
    (len, w, g0): (f64, f64, f64),
    (a, lim, gr, v1): (f64, f64, f64, f64),
    (v, dlen, dwa): (f64, f64, f64),
    (du, dv, dg0): (f64, f64, f64),
    (dv1, dgr): (f64, f64),
) -> f64 {
    let z = 2.0 * w * a;
    let dlim = -lim * lim * (z / 6.0) * 2.0 * dwa;
    let c = len * len / 12.0;
    let dc = len * dlen / 6.0;
    du + 0.5 * dlen * (v + v1)
        + 0.5 * len * (dv + dv1)
        + dc * lim * (g0 - gr)
        + c * (dlim * (g0 - gr) + lim * (dg0 - dgr))
}

/// One pass of the linearly implicit corrector: U frozen at `up` in μP and ω²U.
#[derive(Debug, Clone, Copy)]
pub(super) struct Pass {
    pub(super) up: f64,
    /// μP(up).
    pub(super) a: f64,
    /// 1/(1 − w·a).
    pub(super) inv: f64,
    /// The Hermite limiter at z = 2w·a.
    pub(super) lim: f64,
    /// g at the end, with μP and ω²U at `up`.
    pub(super) gr: f64,
    pub(super) u1: f64,
    pub(super) v1: f64,
}

/// [`Affine::pass`] with μP(up) = `a` and ω² = `omega2` given (the lane stepper evaluates μP for
/// several paths at once, and its lanes may each have their own ω²).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(super) fn pass_with(
    omega2: f64,
    a: f64,
    len: f64,
    (u, v, g0): (f64, f64, f64),
    up: f64,
    known: f64,
    w: f64,
    fr: f64,
) -> Pass {
    let inv = 1.0 / (1.0 - w * a);
    let lim = hermite_limiter(2.0 * w * a);
    let v1 = (known + w * (fr - omega2 * up)) * inv;
    let gr = a * v1 - omega2 * up + fr;
    let u1 = u + 0.5 * len * (v + v1) + len * len * (1.0 / 12.0) * lim * (g0 - gr);
    Pass {
        up,
        a,
        inv,
        lim,
        gr,
        u1,
        v1,
    }
}

/// One linearly implicit step of length `len` from (u, v), where g = `g0`, to its free end
/// (module docs): the quantities the step forms, kept for the tangent's derivative.
#[derive(Debug, Clone, Copy)]
pub(super) struct Free {
    pub(super) len: f64,
    /// Scaled weight of g at the end.
    pub(super) w: f64,
    pub(super) g0: f64,
    /// The predictor's weight of g0.
    pub(super) pw: f64,
    /// The first pass (from the predictor) and the second (from the first pass's U), which
    /// is the step's end.
    pub(super) passes: [Pass; 2],
}

impl Free {
    /// The end (U₁, V₁) of the step.
    #[inline]
    pub(super) fn end(&self) -> (f64, f64) {
        let p = &self.passes[1];
        (p.u1, p.v1)
    }
}

impl Affine {
    /// One corrector pass with U frozen at `up` (see [`Affine::advance`]).
    #[inline]
    #[allow(clippy::too_many_arguments)]
    pub(super) fn pass(
        &self,
        len: f64,
        (u, v, g0): (f64, f64, f64),
        up: f64,
        known: f64,
        w: f64,
        fr: f64,
    ) -> Pass {
        let a = self.damping(up);
        pass_with(self.omega2, a, len, (u, v, g0), up, known, w, fr)
    }

    /// The step of length `len` from (u, v) with g = `g0` there, `known` the part of V at the
    /// end that does not depend on g at the end, `w` the scaled weight of g at the end, `fr`
    /// the forcing there:
    /// up = u + len·v + pw·g0, V₁ = (known + w(fr − ω²up))/(1 − w·μP(up)),
    /// U₁ = u + len(v + V₁)/2 + (len²/12)·lim·(g0 − g₁); the pass is then repeated once with
    /// up = U₁, and the second pass is the step (module docs: why on every step).
    // always: left to itself the inliner keeps it out of `step` (a call on every step, ≈ 10 %
    // of an ensemble's time, measured with perf)
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub(super) fn advance(
        &self,
        len: f64,
        (u, v, g0): (f64, f64, f64),
        pw: f64,
        known: f64,
        w: f64,
        fr: f64,
    ) -> Free {
        let first = self.pass(len, (u, v, g0), u + len * v + pw * g0, known, w, fr);
        let second = self.pass(len, (u, v, g0), first.u1, known, w, fr);
        Free {
            len,
            w,
            g0,
            pw,
            passes: [first, second],
        }
    }

    /// The derivative of one pass along (δu, δv, δg0, δup, δknown): (δU₁, δV₁), with
    /// d(μP)/dU at the pass's up = `slope` given (the lane stepper evaluates it for several
    /// paths at once).
    #[inline(always)]
    pub(super) fn pass_tangent(
        &self,
        f: &Free,
        (p, slope): (&Pass, f64),
        (du, dv, dg0): (f64, f64, f64),
        dup: f64,
        dknown: f64,
    ) -> (f64, f64) {
        let da = slope * dup;
        let dv1 = p.inv * (dknown - f.w * self.omega2 * dup + p.v1 * f.w * da);
        let dgr = da * p.v1 + p.a * dv1 - self.omega2 * dup;
        let step = (f.len, f.w, f.g0);
        let du1 = pass_tangent_u1(step, (p.a, p.lim, p.gr), (du, dv, dg0), (dv1, dgr, da));
        (du1, dv1)
    }

    /// The derivative of [`Affine::advance`] along (δu, δv, δg0), with δpw the predictor weight's
    /// and δknown the known part's: returns (δU₁, δV₁).
    #[inline]
    pub(super) fn advance_tangent(
        &self,
        f: &Free,
        (du, dv, dg0): (f64, f64, f64),
        dpw: f64,
        dknown: f64,
    ) -> (f64, f64) {
        let slopes = [
            self.damping_slope(f.passes[0].up),
            self.damping_slope(f.passes[1].up),
        ];
        self.advance_tangent_with(f, slopes, (du, dv, dg0), dpw, dknown)
    }

    /// The derivative of [`Affine::advance`] from (u, v) = `start` when the step's length and its
    /// weight of g at the end move as well (the rest of an impact step: its length (1 − θ)Δt
    /// and its weights follow the impact's θ): along (δu, δv, δg0), δpw, δknown and
    /// (δlen, δw). Returns (δU₁, δV₁).
    #[allow(clippy::too_many_arguments)]
    pub(super) fn advance_tangent_moving(
        &self,
        f: &Free,
        (_, v): (f64, f64),
        (du, dv, dg0): (f64, f64, f64),
        dpw: f64,
        dknown: f64,
        (dlen, dw): (f64, f64),
    ) -> (f64, f64) {
        let dup = du + dlen * v + f.len * dv + f.pw * dg0 + f.g0 * dpw;
        let moving = (v, dlen, dw);
        let first = self.pass_tangent_moving(f, &f.passes[0], moving, (du, dv, dg0), dup, dknown);
        self.pass_tangent_moving(f, &f.passes[1], moving, (du, dv, dg0), first.0, dknown)
    }

    /// [`Affine::pass_tangent`] with the length and the weight moving: `moving` = (v at the
    /// start, δlen, δw). With inv = 1/(1 − w·a): δ(wa) = δw·a + w·δa,
    /// δV₁ = inv·(δknown + δw·(F_r − ω²up) − wω²δup + V₁δ(wa)) (F_r − ω²up = g_r − aV₁),
    /// δL = −L²(z/6)·2δ(wa), and U₁'s terms in len differentiated as well.
    pub(super) fn pass_tangent_moving(
        &self,
        f: &Free,
        p: &Pass,
        (v, dlen, dw): (f64, f64, f64),
        (du, dv, dg0): (f64, f64, f64),
        dup: f64,
        dknown: f64,
    ) -> (f64, f64) {
        let da = self.damping_slope(p.up) * dup;
        let dwa = dw * p.a + f.w * da;
        let free_part = p.gr - p.a * p.v1;
        let dv1 = p.inv * (dknown + dw * free_part - f.w * self.omega2 * dup + p.v1 * dwa);
        let dgr = da * p.v1 + p.a * dv1 - self.omega2 * dup;
        let step = (f.len, f.w, f.g0);
        let pass = (p.a, p.lim, p.gr, p.v1);
        let du1 = pass_tangent_u1_moving(step, pass, (v, dlen, dwa), (du, dv, dg0), (dv1, dgr));
        (du1, dv1)
    }

    /// [`Affine::advance_tangent`] with d(μP)/dU at the passes' up given.
    #[inline(always)]
    pub(super) fn advance_tangent_with(
        &self,
        f: &Free,
        slopes: [f64; 2],
        (du, dv, dg0): (f64, f64, f64),
        dpw: f64,
        dknown: f64,
    ) -> (f64, f64) {
        let dup = du + f.len * dv + f.pw * dg0 + f.g0 * dpw;
        let first = self.pass_tangent(f, (&f.passes[0], slopes[0]), (du, dv, dg0), dup, dknown);
        let p = (&f.passes[1], slopes[1]);
        self.pass_tangent(f, p, (du, dv, dg0), first.0, dknown)
    }
}
