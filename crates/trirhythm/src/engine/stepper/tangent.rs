//! The tangent (variational) dynamics of a path: [`Tangent`] holds δx = (δU, δV), δ of the
//! Volterra constant, δg at the node and the memory of δg, and [`Stepper::step_with_tangent`]
//! advances a path and its tangent in one pass.
//!
//! # Equation
//! Linearising U′ = V, V = V₀ + Σ jumps + J^λ g, g = μP(U)V − ω²U + γη about a path gives the
//! variational system δU′ = δV, δV = δV₀ + δ(jumps) + J^λ δg, δg = (μP′(U)V − ω²)δU + μP(U)δV.
//! The additive noise drops out of δg, but it enters through the path the tangent follows
//! (frozen noise). δg has a memory of its own: J^λ δg is a linear functional of the whole
//! history of δg, kept in a second [`History`] with the reference's layout (same kernel, same
//! pieces held exactly, impact splits at the same fractions). Renormalising δ therefore means
//! scaling **every** number of the tangent state by one factor ([`Tangent::scale`]).
//!
//! # Smooth steps: the exact derivative of the discrete step
//! The step ([`super`], module docs) is a pass with U frozen at up = U_n + ΔtV_n + p(U_n)g_n
//! (p the predictor's weight), a = μP(up), inv = 1/(1 − w_r a), N = base + J + w_l g_l,
//! V_{n+1} = (N + w_r(F_r − ω²up))·inv, g^P = aV_{n+1} − ω²up + F_r, L = L(2w_r a),
//! U_{n+1} = U_n + Δt(V_n + V_{n+1})/2 + (Δt²/12)L(g_l − g^P); the step repeats the pass with
//! up = U_{n+1} of the first. Its derivative with respect to (U_n, V_n, base, history) is
//! δup = δU + ΔtδV + pδg_l + g_l p′δU, δa = μP′(up)δup, δN = δbase + δJ + w_l δg_l,
//! δV_{n+1} = inv·(δN − w_r ω²δup + V_{n+1} w_r δa), δg^P = V_{n+1}δa + aδV_{n+1} − ω²δup,
//! δL = −L²(z/6)·2w_r δa, δU_{n+1} = δU + Δt(δV + δV_{n+1})/2 + (Δt²/12)(δL(g_l − g^P) +
//! L(δg_l − δg^P)) (the second pass: the same with δup = δU_{n+1} of the first),
//! with δg_l the stored δ(drift) of the node and δJ the tangent memory's value; the piece
//! (δg_l, δdrift_{n+1}) goes into the tangent memory. This is the derivative of the map the
//! stepper computes, not of the ODE: central finite differences of [`Stepper::step`] agree with
//! it to 10⁻⁸ or better (unit tests below, for (U, V), the Volterra constant and a memory
//! direction, λ = 1 and 0.998, mildly and strongly stiff steps).
//! The quantities up, a, inv, w_l, w_r, N are the step's own: the tangent costs a second memory
//! update, evaluations of P′ and a few multiply–adds.

//! # Impact steps: the saltation of the impact map
//! The discrete impact step is not differentiated (its θ-dependence runs through the kernel
//! weights of the split piece, the memory's whole layout); the tangent jumps by the saltation
//! of the continuous impact map instead, at the reference's instant t* = t_n + θΔt:
//! 1. δx at t*₋: δU₋ from the step's cubic Hermite interpolant (the one the stepper locates θ
//!    with; linear in its data) applied to (δU_n, δV_n, δU_{n+1}, δV_{n+1}) of the free step;
//!    δV₋ the tangent's own Volterra value at t*, (δbase + δJ(t*) − w_s ω² δU₋)/(1 − w_s μP(0)),
//!    as the stepper takes V₋.
//! 2. The perturbed path hits at t* + δt*, δt* = −δU₋/V₋. With the reset V₊ = ρV₋ (ρ = −r at the
//!    wall, +r for Eq. 9's crossing), δU₊ = ρ δU₋, and the constant of V's Volterra form jumps
//!    by (ρ − 1)V₋ taken **at the perturbed instant**: δ(jump) = (ρ − 1)(δV₋ + V̇₋δt*). With
//!    the restarting memory the constant becomes ρV₋ at the perturbed instant and the tangent
//!    memory restarts with the reference's.
//! 3. g jumps by [g] = g₊ − g₋ at t*; in the perturbed path it jumps δt* later, which puts an
//!    impulse of mass m = −[g]δt* at t* into δg's history (−g₊δt* with the restarting memory,
//!    whose history begins at t*). Its J^λ is m·k(t − t*), k the kernel.
//!
//! At λ = 1 (k ≡ 1, V̇₋ = g₋) this is the saltation matrix: δU₊ = ρδU₋,
//! δV₊ = ρδV₋ + (g₊ − ρg₋)δU₋/V₋ (for the wall ρ = −r: −rδV₋ + (g₊ + rg₋)δU₋/V₋).
//!
//! **The impulse in the tangent memory.** The memory holds piecewise-linear pieces, so a Dirac
//! mass is not representable exactly. It is folded into the tangent's split piece at the
//! reference's θ: δg₋ gains 2m(1 − θ)/(θΔt) and δg₊ gains 2mθ/((1 − θ)Δt), two hat functions
//! whose total mass is m and whose first moment about t* is zero (with the restarting memory only
//! the part after t* exists: δg₊ gains 2m/((1 − θ)Δt), mass m). At λ = 1 (k constant) this is
//! exact. For λ < 1 it is not, and not at a rate in Δt: the kernel k(τ) ∝ τ^{λ−1} is scale-free,
//! so spreading the mass over a step changes its weight at the next nodes, O(Δt) away, by a
//! fixed fraction of order (1 − λ) (the error fades as (Δt/distance)² further on). Measured on
//! the impact step's Jacobian (unit test below): 2·10⁻⁴ relative at λ = 0.998, up to 10⁻² at
//! λ = 0.95, for every Δt from 0.02 to 0.00125. An exact treatment would need a Dirac piece in
//! the memory's exact window (the SOE modes could take it exactly); not done, to keep the
//! tangent memory a plain [`History`]. The value δV₊ from which the rest of the step is
//! linearised counts the impulse at its λ = 1 weight (k(0⁺) is infinite for λ < 1; the
//! singular part is carried by the memory from the end of the step on).
//!
//! **V̇₋ for λ < 1.** V = base + J^λ g is not differentiable to g: V̇ = d/dt J^λ g. It is taken
//! as the derivative in θ of the scheme's own J^λ of the history and of the current piece,
//! held as the line through (t_n, g_l) and (t*, g₋) (central difference of
//! [`History::at_fraction`], ε = 10⁻⁴ of a step), which is exactly g₋ at λ = 1.
//!
//! The rest of the step [t*, t_{n+1}] is the linearisation of the stepper's redone step from
//! (δU₊, δV₊), with its own quantities (the split weights, up, the denominator). The discrete
//! impact step and this saltation differ at O(Δt^p): at λ = 1 the unit test measures p ≈ 1.8
//! (relative error of the step's Jacobian 5.6·10⁻⁵ at Δt = 0.02, 3.1·10⁻⁷ at Δt = 0.00125,
//! both impact memories); for λ < 1 see the impulse above (p ≈ 0).
//!
//! Why not differentiate the discrete impact step exactly: θ enters the kernel weights of the
//! split piece, in the current step and in every later one (and in the SOE absorption of the
//! split piece), so the exact derivative needs a θ-direction of the memory — the same Dirac
//! piece — and the kernel weights' derivatives in θ, i.e. a restructured memory. The
//! saltation reuses the memory as it is.
//!
//! - A grazing impact with V₋ = 0 (the wall clips a scheme value ≥ 0) has no saltation (δt*
//!   unbounded): the tangent is clamped like a sticking step.
//! - Sticking steps: the clamped state (0, 0) does not depend on the state before, so
//!   (δU, δV) = (0, 0); the wall's reaction −V_{n+1} in the Volterra constant has the
//!   derivative −δV_{n+1} (continuous memory), or the tangent memory restarts at rest.
//!
//! # Tests
//! Unit tests below: the reference advanced by [`Stepper::step_with_tangent`] is bit-identical
//! to [`Stepper::step`]; smooth steps against central finite differences of the stepper
//! (U, V, base and memory directions; λ = 1 and 0.998); impact steps against finite differences
//! with the observed order in Δt. `tests/lyapunov.rs`: the exponent by the tangent against the
//! damped oscillator's −μ0/2 and against two trajectories.

use super::{predictor_weight_slope, Begin, Piece, Split, Stepper};
use crate::engine::History;
use crate::error::Result;

/// The tangent of a path: δU, δV, δ of the Volterra constant, δg at the node (without noise)
/// and the memory of δg, with the reference's layout.
#[derive(Debug, Clone)]
pub(crate) struct Tangent {
    u: f64,
    v: f64,
    drift: f64,
    base: f64,
    history: History,
}

impl Tangent {
    /// The tangent of `reference`'s current state along (δU, δV), the Volterra constant moved
    /// with δV, no memory.
    pub fn new(reference: &Stepper, (du, dv): (f64, f64)) -> Self {
        let mut history = reference.history.clone();
        history.scale_state(0.0);
        Tangent {
            u: du,
            v: dv,
            drift: reference.drift_derivative(du, dv),
            base: dv,
            history,
        }
    }

    /// ‖(δU, δV)‖.
    pub fn norm(&self) -> f64 {
        crate::maths::hypot(self.u, self.v)
    }

    /// Whether the whole tangent state is zero (δU, δV, δ of the Volterra constant, δg at the
    /// node and the tangent memory): the perturbation has vanished for good.
    pub fn is_zero(&self) -> bool {
        self.u == 0.0
            && self.v == 0.0
            && self.drift == 0.0
            && self.base == 0.0
            && self.history.is_zero()
    }

    /// Multiply the whole tangent state by `c`: δU, δV, δ of the Volterra constant, δg at the
    /// node and every number of the tangent memory (the variational system is linear).
    pub fn scale(&mut self, c: f64) {
        self.u *= c;
        self.v *= c;
        self.drift *= c;
        self.base *= c;
        self.history.scale_state(c);
    }

    /// Every number of the tangent state that a step reads, as bits (δU, δV, δg at the node, δ
    /// of the Volterra constant, the tangent memory's value).
    #[cfg(test)]
    pub(crate) fn bits(&self) -> [u64; 5] {
        [self.u, self.v, self.drift, self.base, self.history.value()].map(f64::to_bits)
    }

    /// The tangent of a state clamped at rest on the wall whose free value was V + δV.
    fn stick(&mut self, dv1: f64, restart: bool) {
        if restart {
            self.history.restart();
            self.base = 0.0;
        } else {
            self.base -= dv1;
        }
    }
}

/// What the tangent's step needs at its start ([`Stepper::begin_tangent`]).
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct TangentBegin {
    pub(super) du: f64,
    pub(super) dv: f64,
    /// δg at the start.
    pub(super) dgl: f64,
    /// δ of the predictor's weight.
    pub(super) dpw: f64,
    /// δ of the known part.
    pub(super) dknown: f64,
}

/// The end of a step and of its tangent after their events
/// ([`Stepper::end_events_with_tangent`]).
#[derive(Debug, Clone, Copy)]
pub(super) struct TangentEnd {
    pub(super) u1: f64,
    pub(super) v1: f64,
    pub(super) du1: f64,
    pub(super) dv1: f64,
    piece: Piece,
    dpiece: Piece,
    push: bool,
}

/// The cubic Hermite basis (h00, h10, h01, h11) at t ∈ [0, 1].
fn hermite_basis(t: f64) -> [f64; 4] {
    let t2 = t * t;
    let t3 = t2 * t;
    [
        2.0 * t3 - 3.0 * t2 + 1.0,
        t3 - 2.0 * t2 + t,
        -2.0 * t3 + 3.0 * t2,
        t3 - t2,
    ]
}

impl Stepper {
    /// δ(μP(U)V − ω²U) at the current node along (δU, δV).
    fn drift_derivative(&self, du: f64, dv: f64) -> f64 {
        (self.rhs.damping_slope(self.u) * self.v - self.rhs.omega2) * du
            + self.rhs.damping(self.u) * dv
    }

    /// Advance one step Δt, the tangent `t` with it (module docs). The path is advanced exactly
    /// as by [`Stepper::step`], bit for bit.
    pub(crate) fn step_with_tangent(&mut self, t: &mut Tangent) -> Result<()> {
        let h = self.h;
        let b = self.begin();
        let free = self
            .rhs
            .advance(h, (b.u, b.v, b.gl), self.pw, b.known, self.wr, b.fr);
        let (u1, v1) = free.end();
        // the derivative of the same formulas
        let (a0, slope0) = (self.rhs.damping(b.u), self.rhs.damping_slope(b.u));
        let tb = self.begin_tangent(t, (a0, slope0));
        let (du1, dv1) = self
            .rhs
            .advance_tangent(&free, (tb.du, tb.dv, tb.dgl), tb.dpw, tb.dknown);
        let end = self.end_events_with_tangent(t, &b, &tb, [u1, v1, du1, dv1])?;
        let a1 = self.set_node(end.u1, end.v1);
        let ddrift = self.drift_derivative_at(a1, self.rhs.damping_slope(end.u1), &end);
        self.complete_with_tangent(t, &b, end, ddrift);
        Ok(())
    }

    /// The tangent's part of [`Stepper::begin`]: δg at the start, δ of the known part and the
    /// predictor weight's derivative, where μP(U) = `a0` and d(μP)/dU = `slope0` (the lane
    /// stepper evaluates them for several paths at once).
    #[inline(always)]
    pub(super) fn begin_tangent(&self, t: &Tangent, (a0, slope0): (f64, f64)) -> TangentBegin {
        let dgl = t.drift;
        TangentBegin {
            du: t.u,
            dv: t.v,
            dgl,
            dpw: predictor_weight_slope(self.h, a0, slope0) * t.u,
            dknown: t.base + t.history.value() + self.wl * dgl,
        }
    }

    /// The events of a step whose free end is `free` = (U₁, V₁, δU₁, δV₁), for the path and its
    /// tangent: sticking, an impact with the tangent's saltation, the blow-up check, the side of
    /// the Zhuravlev crossing. Counts the step.
    #[inline(always)]
    pub(super) fn end_events_with_tangent(
        &mut self,
        t: &mut Tangent,
        b: &Begin,
        tb: &TangentBegin,
        free: [f64; 4],
    ) -> Result<TangentEnd> {
        let (u, v) = (b.u, b.v);
        let [mut u1, mut v1, mut du1, mut dv1] = free;
        self.events = Default::default();
        let mut piece = Piece {
            left: b.gl,
            right: 0.0,
            split: None,
        };
        let mut dpiece = Piece {
            left: tb.dgl,
            right: 0.0,
            split: None,
        };
        let mut push = true;
        if self.wall && self.stuck {
            if u1 <= 0.0 {
                push = self.stick(v1);
                t.stick(dv1, self.restart);
                (u1, v1, du1, dv1) = (0.0, 0.0, 0.0, 0.0);
            } else {
                self.stuck = false;
            }
        } else if (self.wall && u1 < 0.0) || (self.crossing && u * u1 < 0.0) {
            let free = [u1, v1, du1, dv1];
            let (split, dsplit, end) =
                self.impact_with_tangent(t, (b.gl, tb.dgl), (b.el, b.er), free);
            [u1, v1, du1, dv1] = end;
            piece.split = Some(split);
            dpiece.split = Some(dsplit);
            if self.wall && u1 < 0.0 {
                push = self.stick(v1);
                t.stick(dv1, self.restart);
                (u1, v1, du1, dv1) = (0.0, 0.0, 0.0, 0.0);
                self.stuck = true;
            }
        }
        self.steps += 1;
        self.check_blow_up((u, v), (u1, v1))?;
        if self.crossing && u1 != 0.0 {
            self.side = u1.signum();
        }
        Ok(TangentEnd {
            u1,
            v1,
            du1,
            dv1,
            piece,
            dpiece,
            push,
        })
    }

    /// δ(μP(U)V − ω²U) at a step's end, where μP = `a1` and d(μP)/dU = `slope1`.
    #[inline(always)]
    pub(super) fn drift_derivative_at(&self, a1: f64, slope1: f64, e: &TangentEnd) -> f64 {
        (slope1 * e.v1 - self.rhs.omega2) * e.du1 + a1 * e.dv1
    }

    /// The last part of a step with its tangent, after [`Stepper::set_node`] at its end: the
    /// pieces of g and δg (δg at the end = `ddrift`) into their memories, the new states.
    #[inline(always)]
    pub(super) fn complete_with_tangent(
        &mut self,
        t: &mut Tangent,
        b: &Begin,
        mut e: TangentEnd,
        ddrift: f64,
    ) {
        if e.push {
            e.piece.right = self.drift + self.rhs.forcing(b.er, self.side);
            self.history.push(e.piece);
            e.dpiece.right = ddrift;
            t.history.push(e.dpiece);
        }
        self.u = e.u1;
        self.v = e.v1;
        t.u = e.du1;
        t.v = e.dv1;
        t.drift = ddrift;
    }

    /// [`Stepper::impact`] with the tangent's saltation (module docs). `free` is the free end
    /// (U, V, δU, δV) of the step; returns the reference's and the tangent's split pieces and
    /// the end (U, V, δU, δV).
    #[cold]
    fn impact_with_tangent(
        &mut self,
        t: &mut Tangent,
        (gl, dgl): (f64, f64),
        (el, er): (f64, f64),
        free: [f64; 4],
    ) -> (Split, Split, [f64; 4]) {
        let h = self.h;
        let omega2 = self.rhs.omega2;
        let [u1, v1, du1, dv1] = free;
        let c = self.locate(gl, (el, er), (u1, v1));
        let theta = c.theta;
        // δx at t*₋: U by the step's Hermite interpolant, V by the tangent's Volterra value
        let b = hermite_basis(theta);
        let du_m = b[0] * t.u + b[1] * h * t.v + b[2] * du1 + b[3] * h * dv1;
        let (dhs, _) = t.history.at_fraction(theta, dgl);
        let dv_m = (t.base + dhs - c.ws * omega2 * du_m) / (1.0 - c.ws * c.a0);
        let g_minus = c.a0 * c.v_at + c.forcing;
        // V̇(t*−) before the reference's memory restarts
        let vdot = self.velocity_rate(theta, gl, g_minus);
        let rest = self.jump(&c, gl, er);
        let keep = !self.restart;
        let rho = if self.crossing {
            self.rhs.restitution
        } else {
            -self.rhs.restitution
        };
        let (du_p, dv_p, mass) = if rest.v_minus == 0.0 {
            // grazing: no saltation; clamped at rest like a sticking step
            t.stick(dv_m, self.restart);
            (0.0, 0.0, 0.0)
        } else {
            let dt_star = -du_m / rest.v_minus;
            let dv_minus_moved = dv_m + vdot * dt_star;
            let dv_regular = if keep {
                let dv = rho * dv_m + (rho - 1.0) * vdot * dt_star;
                t.base += (rho - 1.0) * dv_minus_moved;
                dv
            } else {
                t.history.restart();
                t.base = rho * dv_minus_moved;
                t.base
            };
            let jump_g = rest.split.after - if keep { rest.split.before } else { 0.0 };
            let mass = -jump_g * dt_star;
            (rho * du_m, dv_regular + mass, mass)
        };
        // the impulse folded into the split piece: mass m, first moment 0 about t*
        let (fold_before, fold_after) = if keep {
            (
                2.0 * mass * (1.0 - theta) / (theta * h),
                2.0 * mass * theta / ((1.0 - theta) * h),
            )
        } else {
            (0.0, 2.0 * mass / ((1.0 - theta) * h))
        };
        let dsplit = Split {
            theta,
            before: c.a0 * dv_m - omega2 * du_m + fold_before,
            after: c.a0 * dv_p - omega2 * du_p + fold_after,
            keep_before: keep,
        };
        // the rest of the step from (δU₊, δV₊), linearised with the redone step's quantities
        let (dknown_s, _) = t.history.current_split(dgl, &dsplit);
        let f = &rest.free;
        // δg₊ without the folded impulse (that is a memory artefact; the impulse's effect on
        // V₊ is in δV₊)
        let dg_p = c.a0 * dv_p - omega2 * du_p;
        // the predictor's weight at U = 0 does not move to first order: d(μP)/dU = 0 there
        let dknown = t.base + t.history.value() + dknown_s;
        let (du_end, dv_end) = self.rhs.advance_tangent(f, (du_p, dv_p, dg_p), 0.0, dknown);
        let (u_end, v_end) = f.end();
        (rest.split, dsplit, [u_end, v_end, du_end, dv_end])
    }

    /// V̇(t*−) = d/dt J^λ g at the fraction θ of the current step: the central difference in θ
    /// of the scheme's J^λ of the history and of the current piece held as the line through
    /// (t_n, g_l) and (t*, g₋). Exactly g₋ at λ = 1 (J is then quadratic in θ).
    fn velocity_rate(&self, theta: f64, gl: f64, g_minus: f64) -> f64 {
        let eps = 1e-4f64.min(0.5 * theta).min(0.5 * (1.0 - theta));
        let j = |th: f64| {
            let (hs, ws) = self.history.at_fraction(th, gl);
            hs + ws * (gl + (g_minus - gl) * th / theta)
        };
        (j(theta + eps) - j(theta - eps)) / (2.0 * eps * self.h)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::{Barrier, ImpactMemory, Memory, Options, PredictorCorrector, Problem};
    use crate::model::{preset, Params};

    fn params(name: &str, pairs: &[(&str, f64)]) -> Params {
        let mut p = preset(name).unwrap().params;
        for &(k, v) in pairs {
            p = p.with(k, v).unwrap();
        }
        p
    }

    fn stepper(
        p: &Params,
        dt: f64,
        barrier: Barrier,
        impact_memory: ImpactMemory,
        (u0, v0): (f64, f64),
        t_end: f64,
    ) -> Stepper {
        let problem = Problem::from_params(p)
            .and_then(|q| q.with_barrier(barrier))
            .and_then(|q| q.with_start(u0, v0))
            .unwrap();
        let method = PredictorCorrector {
            dt,
            memory: Memory::default(),
            impact_memory,
            ..Default::default()
        };
        let o = Options {
            t_end,
            seed: 5,
            ..Default::default()
        };
        o.stepper(&problem, &method).unwrap()
    }

    /// A direction in the state: δU, δV, δbase and the memory scaled by (1 + s).
    #[derive(Clone, Copy, Debug)]
    struct Direction {
        u: f64,
        v: f64,
        base: f64,
        memory: f64,
    }

    const DIRECTIONS: [Direction; 4] = [
        Direction {
            u: 1.0,
            v: 0.0,
            base: 0.0,
            memory: 0.0,
        },
        Direction {
            u: 0.0,
            v: 1.0,
            base: 0.0,
            memory: 0.0,
        },
        Direction {
            u: 0.0,
            v: 0.0,
            base: 1.0,
            memory: 0.0,
        },
        Direction {
            u: 0.0,
            v: 0.0,
            base: 0.0,
            memory: 1.0,
        },
    ];

    fn perturbed(s: &Stepper, eps: f64, d: Direction) -> Stepper {
        let mut p = s.clone();
        p.u += eps * d.u;
        p.v += eps * d.v;
        p.base += eps * d.base;
        p.history.scale_state(1.0 + eps * d.memory);
        p.set_node(p.u, p.v);
        p
    }

    fn tangent(s: &Stepper, d: Direction) -> Tangent {
        let mut t = Tangent::new(s, (d.u, d.v));
        t.base = d.base;
        t.history = s.history.clone();
        t.history.scale_state(d.memory);
        t
    }

    /// Relative error of the tangent after `steps` steps against the central difference of
    /// the stepper, along `d`.
    fn fd_error(s: &Stepper, d: Direction, steps: usize, eps: f64) -> (f64, [f64; 2], [f64; 2]) {
        let (mut plus, mut minus) = (perturbed(s, eps, d), perturbed(s, -eps, d));
        let mut reference = s.clone();
        let mut t = tangent(s, d);
        for _ in 0..steps {
            plus.step().unwrap();
            minus.step().unwrap();
            reference.step_with_tangent(&mut t).unwrap();
        }
        let fd = [
            (plus.u - minus.u) / (2.0 * eps),
            (plus.v - minus.v) / (2.0 * eps),
        ];
        let err = (t.u - fd[0]).hypot(t.v - fd[1]) / fd[0].hypot(fd[1]);
        (err, [t.u, t.v], fd)
    }

    #[test]
    fn the_reference_is_advanced_bit_for_bit_as_by_step() {
        // a chattering noisy path with the wall (impacts and sticking), both impact memories,
        // and Eq. 9's crossing
        for (memory, system) in [
            (ImpactMemory::Continuous, crate::engine::System::Fractional),
            (ImpactMemory::Restart, crate::engine::System::Fractional),
            (ImpactMemory::Continuous, crate::engine::System::Zhuravlev),
        ] {
            let p = params("fig13a", &[("r", 0.3), ("D", 0.5)]);
            let problem = Problem::from_params(&p)
                .and_then(|q| q.with_system(system))
                .and_then(|q| q.with_start(7.0, 0.0))
                .unwrap();
            let method = PredictorCorrector {
                impact_memory: memory,
                ..Default::default()
            };
            let o = Options {
                t_end: 200.0,
                seed: 7,
                ..Default::default()
            };
            let mut a = o.stepper(&problem, &method).unwrap();
            let mut b = a.clone();
            let mut t = Tangent::new(&b, (1.0, 0.0));
            for n in 0..20_000 {
                a.step().unwrap();
                b.step_with_tangent(&mut t).unwrap();
                assert_eq!((a.u, a.v, a.base), (b.u, b.v, b.base), "step {n}");
                if n % 100 == 0 {
                    let c = 1.0 / t.norm().max(1e-300);
                    t.scale(c);
                }
                assert!(t.history.same_layout_as(&b.history));
            }
            assert!(a.impacts() > 50, "{memory:?}: {} impacts", a.impacts());
            if system == crate::engine::System::Fractional {
                assert!(a.sticking_steps() > 0);
            }
        }
    }

    #[test]
    fn smooth_steps_are_the_derivative_of_the_discrete_step() {
        // no wall, noise on: a strongly nonlinear damping (fig17a's P at |U| ≈ 1…3, mild
        // steps), and fig13b's stiff outer turning point (U ≈ 13, Δt·μ0|P| ≈ 3)
        for (name, mu0, start, warm_up) in [
            ("fig17a", 0.2, (2.0, 0.0), 700),
            ("fig13b", 0.2, (12.9, 3.0), 5),
        ] {
            for lambda in [1.0, 0.998] {
                let p = params(name, &[("lambda", lambda), ("D", 0.3), ("mu0", mu0)]);
                let mut s = stepper(
                    &p,
                    0.01,
                    Barrier::Off,
                    ImpactMemory::Continuous,
                    start,
                    100.0,
                );
                for _ in 0..warm_up {
                    s.step().unwrap();
                }
                let stiffness = 0.01 * s.rhs.damping(s.u).abs();
                assert_eq!(
                    stiffness > 1.0,
                    name == "fig13b",
                    "{name}: stiffness {stiffness}"
                );
                for d in DIRECTIONS {
                    for steps in [1, 40] {
                        // central differences err by O(ε²) (curvature) and O(1/ε) (rounding,
                        // against a small response): the best of a ladder of ε
                        let (err, t, fd) = [1e-3, 1e-4, 1e-5]
                            .map(|e| fd_error(&s, d, steps, e))
                            .into_iter()
                            .min_by(|a, b| a.0.total_cmp(&b.0))
                            .unwrap();
                        eprintln!(
                            "{name} λ = {lambda} {d:?} {steps} steps: {err:.2e} {t:?} {fd:?}"
                        );
                        assert!(
                            err < 1e-8,
                            "{name} λ = {lambda}, {d:?}, {steps} steps: {err:e}"
                        );
                    }
                }
            }
        }
    }

    /// The stepper just before the first impact of a path from (1.5, 0) at step `dt`, with the
    /// impact's fraction θ of the step.
    fn before_first_impact(p: &Params, dt: f64, memory: ImpactMemory) -> (Stepper, f64) {
        let mut s = stepper(p, dt, Barrier::On, memory, (1.5, 0.0), 20.0);
        loop {
            let mut probe = s.clone();
            probe.step().unwrap();
            if let Some(i) = probe.events().impact {
                let theta = (i.time - s.time()) / dt;
                return (s, theta);
            }
            s = probe;
        }
    }

    /// Least-squares slope of ln(error) against ln(Δt): the observed order.
    fn observed_order(dts: &[f64], errs: &[f64]) -> f64 {
        let n = dts.len() as f64;
        let x: Vec<f64> = dts.iter().map(|d| d.ln()).collect();
        let y: Vec<f64> = errs.iter().map(|e| e.ln()).collect();
        let (mx, my) = (x.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
        let sxy: f64 = x.iter().zip(&y).map(|(a, b)| (a - mx) * (b - my)).sum();
        let sxx: f64 = x.iter().map(|a| (a - mx) * (a - mx)).sum();
        sxy / sxx
    }

    #[test]
    fn impact_steps_follow_the_saltation_to_the_order_of_the_step() {
        // the first impact of a deterministic path (the same impact at every Δt): the tangent's
        // 2×2 Jacobian of the impact step, columns δU and δV, against central differences of
        // the stepper; error = ‖J_tangent − J_fd‖ / ‖J_fd‖ (Frobenius)
        let dts = [0.02, 0.01, 0.005, 0.0025, 0.00125];
        let mut report = String::new();
        for (lambda, memory, bound) in [
            (1.0, ImpactMemory::Continuous, 1e-4),
            (1.0, ImpactMemory::Restart, 1e-4),
            (0.998, ImpactMemory::Continuous, 5e-4),
            (0.998, ImpactMemory::Restart, 5e-4),
            (0.95, ImpactMemory::Continuous, 2e-2),
        ] {
            let p = params("fig17a", &[("lambda", lambda), ("D", 0.0), ("mu0", 0.2)]);
            let mut errs = vec![];
            for &dt in &dts {
                let (s, theta) = before_first_impact(&p, dt, memory);
                assert!(theta > 1e-3 && theta < 1.0 - 1e-3, "θ = {theta}");
                let (mut diff, mut norm) = (0.0, 0.0);
                for d in &DIRECTIONS[..2] {
                    let (_, t, fd) = fd_error(&s, *d, 1, 1e-7);
                    for k in 0..2 {
                        diff += (t[k] - fd[k]).powi(2);
                        norm += fd[k].powi(2);
                    }
                }
                errs.push((diff / norm).sqrt());
            }
            let order = observed_order(&dts, &errs);
            report += &format!(
                "λ = {lambda} {memory:?}: errors {} (Δt = 0.02 … 0.00125), observed order \
                 {order:.2}\n",
                errs.iter()
                    .map(|e| format!("{e:.1e}"))
                    .collect::<Vec<_>>()
                    .join(", "),
            );
            assert!(
                errs.iter().all(|&e| e < bound),
                "λ = {lambda} {memory:?}: {errs:?}"
            );
            if lambda == 1.0 {
                // the discrete impact step converges to the saltation
                assert!(order > 1.5, "λ = 1 {memory:?}: order {order} ({errs:?})");
                assert!(errs[dts.len() - 1] < 1e-6, "{errs:?}");
            }
        }
        eprintln!("{report}");
    }
}
