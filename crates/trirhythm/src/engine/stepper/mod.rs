//! One path of the predictor–corrector as an object: [`Stepper`] owns the whole state of a path
//! — U, V, the noise, the memory (exact window, SOE modes, lumped terms, impact jumps), the
//! impact bookkeeping — and advances it one step at a time. Every driver (trajectories,
//! ensembles, streaming statistics, early-stopping sweeps) is a loop over [`Stepper::step`]; see
//! [`super::drivers`]. A stepper is built from a [`Problem`] ([`Stepper::new`]): the
//! equation, the wall, the start of its path and the blow-up bound are the problem's.
//!
//! The step is here; `affine` holds the paper's kernel (the arithmetic of a step of Eq. 1/5/9:
//! predictor, corrector passes, their tangents), `general` the General kernel (Duffing,
//! Rayleigh, harmonic forcing, fractional terms K_j·D^{α_j}U with a memory of U̇ each,
//! multiplicative noise U·η_m: the rest of the class the engine steps), `walls` the General
//! kernel's walls (any δ, keeping above or below, two walls, r(|U̇₋|), sticking at δ),
//! `impact` locates an impact inside a step and redoes the rest of it, `tangent` steps the
//! variational equation with the path, `renormalise` pulls a perturbed copy toward its
//! reference, `polynomial` evaluates μP.
//!
//! **Two kernels, absent terms cost nothing** (model-class.md §2). A path of the paper's
//! family steps with [`Affine`] (the former `Rhs`, moved verbatim: same expressions, same
//! order, same bits — `tests/pinned.rs` digests every step of scalar, lane and tangent runs,
//! recorded before the move). A path whose problem has the General kernel's terms
//! ([`crate::engine::Oscillator::terms`]) holds a boxed `General` with its forcing phase, and
//! [`Stepper::step`] takes one branch on it per step (not a generic parameter: that would put
//! the kernel into every driver's signature for a second implementation that has no lanes of
//! its own). The lane steppers step General paths path by path (out of line, so that the lane
//! step's callers keep their code). Measured side by side with main's
//! `examples/lanes_timing.rs` and `examples/drivers_timing.rs` (CHANGELOG.md): the paper's
//! ensembles, lane steps and Lyapunov runs at 0.95–1.02 of main's CPU time.
//!
//! # Equation
//! Caputo D^{1+λ}U = D^λ(U′), so Eq. (1) is the multi-order system
//! U′ = V,  D^λ V = g(U, V, η),  g = μ P(U) V − ω² U + γη,
//! solved in Volterra form V(t) = V(0) + J^λ g(t) + Σ (impact jumps), U(t) = U(0) + ∫V, with
//! the impact law U̇₊ = −rU̇₋ at U = 0 (wall on). [`System::Equivalent`] integrates Eq. (5)
//! (μ = μ1, P → β1 − c0 + P, ω = ω1, γ = β2) at λ = 1 with the same wall; [`System::Zhuravlev`]
//! integrates Eq. (9), Z on the whole line with η → sgn(Z)η and Ż₊ = rŻ₋ at Z = 0 (U = |Z|).
//!
//! # Method: a linearly implicit PECE step
//! With the product-trapezoidal weights (w_l, w_r) of the step and the memory's value J of all
//! completed pieces ([`super::memory`]), the corrector of Diethelm–Ford–Freed reads
//! V_{n+1} = V₀ + J + w_l g_n + w_r g(U_{n+1}, V_{n+1}, η). g is **affine in V**, so the
//! corrector is solved for V exactly with U frozen at a predictor U^P:
//!
//!   U^P = U_n + ΔtV_n + ½Δt² g_n/(1 + Δt|μP(U_n)|),
//!   V_{n+1} = (V₀ + J + w_l g_n + w_r(−ω²U^P + γη)) / (1 − w_r μP(U^P)),
//!   U_{n+1} = U_n + Δt(V_n + V_{n+1})/2 + (Δt²/12)·L(z)·(g_n − g^P_{n+1}),
//!
//! with g^P_{n+1} = μP(U^P)V_{n+1} − ω²U^P + γη, z = 2w_r μP(U^P) (= Δt·μP at λ = 1) and
//! L(z) = 1/(1 + z²/12). The pass is then repeated once with U^P replaced by the U_{n+1} of the
//! first pass, and the second pass is the step. g_{n+1} = g(U_{n+1}, V_{n+1}, η) is stored
//! (only corrected values enter the history).
//!
//! - Why linearly implicit: the explicit corrector g(U^P, V^P) amplifies the damping mode by
//!   1 + w_r a(1 + w_r a) with a = μP(U); it is unstable once Δt·μ|P(U)| ≳ 2, which the paper's
//!   own parameters reach (μ0 = 0.2 at U ≈ 13: μ0|P| ≈ 350). Solving the affine equation costs
//!   one division, keeps the grid uniform — which the SOE memory and the bit-identical
//!   ensembles rely on — and turns the damping factor into the trapezoidal
//!   (1 + w_r a)/(1 − w_r a) at λ = 1, bounded by 1 for every a ≤ 0. An adaptive step would
//!   break the uniform grid of the memory and, with it, the O(1) cost per step.
//! - U: the product-trapezoidal rule holds g linear on the step, so V is quadratic there at
//!   λ = 1 and ∫V = Δt(V_n + V_{n+1})/2 + (Δt²/12)(g_n − g_{n+1}) exactly (the Euler–Maclaurin
//!   correction with V′ = g). For λ < 1, V′ = g + O(1 − λ) smoothly, so the correction stays
//!   consistent and the method second order. The factor L(z) keeps it bounded where the
//!   damping is stiff: without it the U-increment of the frozen linear mode grows like
//!   Δt|z|V/6 as |z| → ∞ (measured with the Taylor predictor: Fig. 5(e) blows up at
//!   t = 39.6); with it the increment decays like |z|⁻³ and L = 1 − O(Δt²) elsewhere.
//! - U^P: the Taylor predictor with U″ ≈ g, its g-term damped by 1/(1 + Δt|μP|) so that it
//!   stays bounded (→ Δt/(2|μP|)·g) where the damping is stiff. Its error O(Δt³) enters V
//!   through w_r·μP′; the second pass evaluates μP and ω²U at the first pass's
//!   U instead.
//! - The second pass on every step, not only on stiff ones: the step map must be smooth in the
//!   state. Up to 6ae8a9e the second pass was taken only where |z| > 1/2; the map then jumped
//!   by the passes' difference wherever an orbit crossed |z| = 1/2, twice a period on a stiff
//!   cycle, and the jump locked the cycle's phase to the time grid: the noise-free cycle's
//!   Lyapunov exponent, which is 0 (its flow direction is neutral), came out at −2.5·10⁻²
//!   (Fig. 17(a)'s μ0 = 0.1, Δt = 0.01; +0.23 at μ0 = 0.2). A C² blend of the two passes over
//!   1/2 < |z| < 1 removed the jump but not the locking at μ0 = 0.2 (−0.11 at Δt = 0.005: a
//!   smooth step map that still changes within a few steps of the orbit); two passes
//!   everywhere give 0 within the window's bound (`tests/cycle_exponent.rs`) for 1.04–1.17×
//!   the time of a step in eight lanes (1.2–1.3× one path at a time; CHANGELOG.md).
//! - Where z > 2 on a cycle the trapezoidal damping factor (1 − z/2)/(1 + z/2) of V is
//!   negative: V alternates in sign across the stiff turning point and the discrete map is
//!   chaotic there, though the amplitude stays within 10⁻³ of the converged one (Fig. 13(b)'s
//!   μ0 = 0.2 at Δt = 0.01: z ≈ 2.8, noise-free exponent +0.23; at Δt = 0.005, 0 within its
//!   bound). Such runs need Δt·μ0|P(A)| < 2.
//! - Measured on Fig. 13(b)'s outer cycle from U = 13 (`tests/stiff.rs`; turning amplitude,
//!   relative change from Δt = 0.01 to 0.005 / 0.005 to 0.0025): the plain trapezoidal U with
//!   U^P = U_n + ΔtV_n 1.98·10⁻³ / 5.9·10⁻⁴; the Hermite-corrected U 1.38·10⁻³ / 1.9·10⁻⁴;
//!   with the Taylor predictor too 2.2·10⁻⁴ / 2.5·10⁻⁵, but without L(z) that blows up on
//!   Fig. 5(e); with L(z) and the damped Taylor predictor 1.27·10⁻³ / 1.6·10⁻⁴;
//!   with the second pass on stiff steps 7.5·10⁻⁴ / 8.2·10⁻⁵ (second-pass thresholds |z| > 1
//!   and > 2: 8.1·10⁻⁴ and 7.4·10⁻⁴); with the second pass on every step (this method), as
//!   `tests/stiff.rs` reports it. The same at λ = 1, with r = 1 and
//!   without the wall: 7.5–8.4·10⁻⁴, so the error is the smooth stiff turning point's, not the
//!   impacts' or the memory's. The steps of ordinary paths (μ0 ≤ 0.05) never reach |z| > 1/2.
//!   The Mittag-Leffler and impact-oscillator errors (`tests/convergence.rs`) are equal or
//!   smaller than with the plain trapezoidal U (λ = 0.998: 7.3·10⁻⁷ against 1.5·10⁻⁶ at the
//!   finest level; λ = 0.5 unchanged, where the t^λ start dominates).
//! - What is still not integrable is reported as [`Error::BlowUp`] with the time, the state
//!   and the stiffness Δt·μ|P(U)|.
//!
//! - Impacts (one routine for the wall and for the Zhuravlev crossing): when the step ends
//!   across U = 0, the crossing θ ∈ (0, 1) is located on the cubic Hermite interpolant of
//!   (U_n, V_n, U_{n+1}, V_{n+1}); the velocity just before it, V₋, is the scheme's own Volterra
//!   value at t* = t_n + θΔt (g is affine in V at U = 0: solved exactly); the jump V₊ = −rV₋
//!   (wall) or V₊ = rV₋ (Zhuravlev, sgn Z flips) is applied and the rest of the step is redone
//!   from (0, V₊) with the same corrector over (1 − θ)Δt. g is stored as two linear pieces on
//!   that step, so its memory stays exact. [`ImpactMemory::Continuous`] (default) keeps the lower
//!   terminal at 0 and adds the jump to the constant of V's Volterra form;
//!   [`ImpactMemory::Restart`] restarts the memory at t*. They coincide at λ = 1.
//! - Sticking (grazing, chattering): at most one impact per step. If the redone part of the
//!   step would cross U = 0 again, the oscillator sticks: U = 0, V = 0 (the wall's reaction goes
//!   into the Volterra constant, or the memory restarts at rest). While stuck every step is
//!   computed freely from rest; if it ends at U ≤ 0 the state is clamped again (a sticking step),
//!   else the oscillator leaves the wall. So U ≥ 0 always and a step never loops.
//! - Noise ([`super::noise`]): η is constant on each step at its exact step mean, so the
//!   forcing's step integrals have the exact law for any Δt/τ.
//!
//! # Reference
//! Diethelm, Ford & Freed, Nonlinear Dyn. 29 (2002) 3–22 (PECE product-trapezoidal method);
//! Garrappa, Math. Comput. Simul. 110 (2015) 96–112 (implicit product-integration rules for
//! stiff fractional problems); Zhuravlev's transformation for Eq. (9).
//!
//! # Tests
//! `tests/general.rs` (the General kernel's known answers), `tests/convergence.rs` (observed
//! orders on Mittag-Leffler and impact-oscillator solutions),
//! `tests/cycle_exponent.rs` (the noise-free exponent on every stable cycle of the Lyapunov
//! figures is 0 within the window's bound, both methods, at the figures' Δt and half of it),
//! `tests/stiff.rs` (Fig. 13(b) from U = 13 and Fig. 5(e) at μ0 = 0.7 at Δt = 0.01; amplitude
//! converged in Δt), `tests/pinned.rs` (a λ = 0.998 trajectory against an independent
//! integrator, exact counts of a noisy run), `tests/impacts.rs`, `tests/systems.rs`,
//! `tests/stochastic.rs`, `tests/tangent.rs` (the renormalisation of a perturbed copy acts on
//! the whole memory: exact for a linear system, −μ/2 for the damped oscillator), the unit
//! tests of [`tangent`] (the tangent step against finite differences of [`Stepper::step`] for
//! every kind of step: smooth, stiff, an impact and the steps after it, sticking, leaving the
//! wall), the unit tests of `impact` (the crossing by Newton equals
//! bisection).

use super::drivers::MAX_STEPS;
use super::memory::{History, Memory, Piece, Split};
use super::noise::NoiseStream;
use super::problem::{ImpactMemory, PredictorCorrector, Problem, System};
use crate::error::{Error, Exact, Result};
pub(crate) use affine::Affine;
use affine::{
    node_with, pass_with, predictor_weight, predictor_weight_len_slope, predictor_weight_slope,
    Free, Pass,
};
use general::General;

mod affine;
mod general;
mod impact;
pub(crate) mod lanes;
mod polynomial;
mod pulse;
mod renormalise;
mod tangent;
mod walls;
pub use lanes::{detected_lanes, Lanes, LANE_WIDTHS};
pub(crate) use lanes::{group_lanes, Group};
pub(crate) use tangent::Tangent;

/// What a step needs from the state and the noise ([`Stepper::begin`]).
#[derive(Debug, Clone, Copy, Default)]
struct Begin {
    /// The noise at the step's start and end.
    el: f64,
    er: f64,
    u: f64,
    v: f64,
    /// g at the start.
    gl: f64,
    /// The part of V at the end that does not depend on g there.
    known: f64,
    /// The forcing at the end.
    fr: f64,
}

/// The end of a step after its events ([`Stepper::end_events`]).
#[derive(Debug, Clone, Copy)]
struct End {
    u1: f64,
    v1: f64,
    /// The step's piece of g (its right value set by [`Stepper::complete`]).
    piece: Piece,
    /// Whether the piece enters the memory.
    push: bool,
}

/// One impact (or Zhuravlev crossing).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Impact {
    /// Time t*.
    pub time: f64,
    /// Velocity just before.
    pub v_minus: f64,
    /// Velocity just after.
    pub v_plus: f64,
}

/// What happened on the last step.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct StepEvents {
    /// The impact on this step, if any.
    pub impact: Option<Impact>,
    /// The step ended clamped at the wall.
    pub stuck: bool,
}

/// The state and history of one path, advanced by [`Stepper::step`].
#[derive(Debug, Clone)]
pub struct Stepper {
    rhs: Affine,
    /// The General kernel with the path's forcing phase, when the problem has its terms
    /// (`general`): then every step is [`Stepper::step_general`]'s.
    general: Option<Box<General>>,
    h: f64,
    wall: bool,
    crossing: bool,
    restart: bool,
    blow_up: f64,
    // state
    steps: u64,
    u: f64,
    v: f64,
    /// μP(U)V − ω²U at the current node (g without its forcing).
    drift: f64,
    /// The predictor's weight of g at the current node ([`predictor_weight`]).
    pw: f64,
    /// sgn Z (Eq. 9), else 1.
    side: f64,
    stuck: bool,
    /// The constant of V's Volterra form: V(0) plus the impact jumps (continuous memory).
    base: f64,
    history: History,
    noise: NoiseStream,
    wl: f64,
    wr: f64,
    // bookkeeping
    impacts: u64,
    sticking_steps: u64,
    events: StepEvents,
}

impl Stepper {
    /// Path `path` of `problem` (its start `problem.start(path)`, noise stream `path` of
    /// `seed`) with the given method, its memory certified up to `horizon` (the SOE kernel's T):
    /// the method is validated ([`PredictorCorrector::validate`]) and `horizon` must lie in
    /// [0, [`MAX_STEPS`]·Δt] (with [`Memory::Direct`], at most [`MAX_DIRECT_STEPS`] steps).
    pub fn new(
        problem: &Problem,
        method: &PredictorCorrector,
        (seed, path): (u64, u64),
        horizon: f64,
    ) -> Result<Self> {
        let history = fresh_history(problem, method, horizon)?;
        Self::with_history(problem, method, problem.start(path), (seed, path), history)
    }

    /// As [`Stepper::new`] from the start (u0, v0), reusing an empty memory built once (its
    /// SOE kernel verified once) for many paths.
    pub(crate) fn with_history(
        problem: &Problem,
        method: &PredictorCorrector,
        (u0, v0): (f64, f64),
        (seed, path): (u64, u64),
        history: History,
    ) -> Result<Self> {
        let (oscillator, system, blow_up) =
            (problem.oscillator(), problem.system(), problem.blow_up());
        let h = method.dt;
        if !(h > 0.0 && h.is_finite()) {
            return Err(Error::invalid("dt", h, "(0, ∞), finite"));
        }
        if blow_up.is_nan() || blow_up <= 0.0 {
            return Err(Error::invalid("blow_up", blow_up, "(0, ∞]"));
        }
        // a start at or beyond the blow-up threshold would be reported as a blow-up at once
        let limit = format!("|·| < {} (the blow-up threshold)", Exact(blow_up));
        if u0.is_nan() || u0.abs() >= blow_up {
            return Err(Error::invalid("u0", u0, limit.as_str()));
        }
        if v0.is_nan() || v0.abs() >= blow_up {
            return Err(Error::invalid("v0", v0, limit.as_str()));
        }
        let rhs = Affine::new(oscillator, system);
        let wall = problem.wall();
        if wall && u0 < 0.0 {
            return Err(Error::invalid("u0", u0, "[0, ∞) with the barrier on"));
        }
        problem.check_start_in_walls(u0)?;
        let noise = NoiseStream::new(oscillator.noise(), h, seed, path)?;
        let (wl, wr) = history.current_weights();
        let general = match oscillator.terms() {
            None => None,
            Some(t) => {
                let setup = general::MemorySetup {
                    memory: method.memory,
                    window: method.window,
                    horizon: history.kernel().map_or(0.0, |k| k.to),
                };
                let mut g = General::new(&rhs, t, h, &setup, oscillator.noise(), (seed, path))?;
                g.start(v0);
                Some(Box::new(g))
            }
        };
        let (drift, pw) = match &general {
            None => (rhs.drift(u0, v0), predictor_weight(h, rhs.damping(u0))),
            Some(g) => g.node(h, u0, v0),
        };
        Ok(Stepper {
            general,
            h,
            wall,
            crossing: system == System::Zhuravlev,
            restart: method.impact_memory == ImpactMemory::Restart,
            blow_up,
            steps: 0,
            u: u0,
            v: v0,
            drift,
            pw,
            side: if u0 < 0.0 { -1.0 } else { 1.0 },
            stuck: false,
            base: v0,
            history,
            noise,
            wl,
            wr,
            impacts: 0,
            sticking_steps: 0,
            events: StepEvents::default(),
            rhs,
        })
    }

    /// Let the noise continue from stream `path` of `seed` from the next step on; the state —
    /// U, V, the whole memory, the OU forcing's present value, the impact bookkeeping — is kept.
    /// A clone renoised this way is a branch of the path (rare-event splitting): it shares the
    /// past and has an independent future.
    pub fn renoise(&mut self, seed: u64, path: u64) {
        self.noise.renoise(seed, path);
        if let Some(g) = &mut self.general {
            g.renoise(seed, path);
        }
    }

    /// Time t_n = nΔt.
    #[inline]
    pub fn time(&self) -> f64 {
        self.steps as f64 * self.h
    }

    /// Steps taken.
    #[inline]
    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// U (Z for [`System::Zhuravlev`]).
    #[inline]
    pub fn u(&self) -> f64 {
        self.u
    }

    /// V = U̇.
    #[inline]
    pub fn v(&self) -> f64 {
        self.v
    }

    /// η at the current node (OU), the last step's level (white), or 0.
    #[inline]
    pub fn eta(&self) -> f64 {
        self.noise.current()
    }

    /// Step Δt.
    #[inline]
    pub fn dt(&self) -> f64 {
        self.h
    }

    /// Impacts so far.
    pub fn impacts(&self) -> u64 {
        self.impacts
    }

    /// Steps that ended clamped at the wall.
    pub fn sticking_steps(&self) -> u64 {
        self.sticking_steps
    }

    /// What happened on the last step.
    #[inline]
    pub fn events(&self) -> StepEvents {
        self.events
    }

    /// Number of exponentials of the SOE memory (0 for Direct or λ = 1), the fractional terms'
    /// memories included.
    pub fn exponentials(&self) -> usize {
        self.history.exponentials() + self.general.as_ref().map_or(0, |g| g.exponentials())
    }

    /// The SOE kernel's verified maximal relative error (0 when unused).
    pub fn soe_error(&self) -> f64 {
        self.history.kernel().map_or(0.0, |k| k.max_relative_error)
    }

    /// Bytes of memory state held.
    pub fn memory_bytes(&self) -> usize {
        self.history.state_bytes() + self.general.as_ref().map_or(0, |g| g.memory_bytes())
    }

    /// Hold the oscillator at rest on the wall at the end of a step whose free value was V = v1:
    /// the wall's reaction goes into the constant of V's Volterra form (continuous memory), or
    /// the memory restarts at rest. Returns whether the step's g still enters the history.
    fn stick(&mut self, v1: f64) -> bool {
        self.sticking_steps += 1;
        self.events.stuck = true;
        if self.restart {
            self.history.restart();
            self.base = 0.0;
            false
        } else {
            self.base -= v1;
            true
        }
    }

    /// Advance one step Δt.
    #[inline]
    pub fn step(&mut self) -> Result<()> {
        if self.general.is_some() {
            return self.step_general();
        }
        let b = self.begin();
        let free = self
            .rhs
            .advance(self.h, (b.u, b.v, b.gl), self.pw, b.known, self.wr, b.fr);
        let (u1, v1) = free.end();
        let end = self.end_events(&b, u1, v1)?;
        self.set_node(end.u1, end.v1);
        self.complete(&b, end);
        Ok(())
    }

    /// A step of the General kernel (module docs of `general`): without a wall no events;
    /// with the wall at 0 the paper kernel's impacts and sticking; the forcing at both ends is
    /// the noise's level plus F cos ψ.
    #[inline(never)]
    fn step_general(&mut self) -> Result<()> {
        if let Some(walls) = self.general.as_deref().and_then(|g| g.walls) {
            // the model's walls (offset, below, two, speed-dependent r): `walls`
            return self.step_walls(walls);
        }
        let (b, free) = self.begin_general();
        let (u1, v1) = free.end();
        if !self.wall {
            return self.end_general(&b, u1, v1);
        }
        // the wall at 0: the paper kernel's events (impact, sticking), the General kernel's
        // arithmetic inside them (`impact`)
        let mut end = self.end_events(&b, u1, v1)?;
        let g = self.general.as_deref_mut().expect("a General path");
        (self.drift, self.pw) = g.node(self.h, end.u1, end.v1);
        // U·η_m and the fractional terms' −Σ K_j m_j (their pieces of V split at an impact;
        // a step that sticks with the memory restarting pushes nothing: they restart too)
        let extra = if !g.extras() {
            0.0
        } else if !end.push && g.fractional() {
            g.restart_memories();
            0.0
        } else {
            g.end_step(b.v, end.u1, end.v1)
        };
        if end.push {
            end.piece.right = self.drift + b.fr + extra;
            self.history.push(end.piece);
        }
        self.u = end.u1;
        self.v = end.v1;
        Ok(())
    }

    /// The General step's start and its free end.
    fn begin_general(&mut self) -> (Begin, general::GeneralFree) {
        let (el, er) = self.noise.next_step();
        let g = self.general.as_deref_mut().expect("a General path");
        let (fl, fr) = g.forces();
        let (u, v) = (self.u, self.v);
        let mut gl = self.drift + self.rhs.forcing(el, self.side) + fl;
        let mut fr = self.rhs.forcing(er, self.side) + fr;
        if g.extras() {
            // −Σ K_j m_j and U·η_m (module docs of `general`); η_m is correlated with the
            // additive noise as it enters g, side·η_a (side = −1 on a path started below 0)
            let (xl, xr) = g.begin_step(u, v, self.side * el);
            gl += xl;
            fr += xr;
        }
        let known = self.base + self.history.value() + self.wl * gl;
        let free = g.advance(self.h, (u, v, gl), self.pw, known, self.wr, fr);
        let b = Begin {
            el,
            er,
            u,
            v,
            gl,
            known,
            fr,
        };
        (b, free)
    }

    /// The General step's end at (u1, v1): the blow-up check, the node, the piece of g.
    fn end_general(&mut self, b: &Begin, u1: f64, v1: f64) -> Result<()> {
        self.events = StepEvents::default();
        self.steps += 1;
        self.check_blow_up((b.u, b.v), (u1, v1))?;
        let g = self.general.as_deref_mut().expect("a General path");
        (self.drift, self.pw) = g.node(self.h, u1, v1);
        let extra = if g.extras() {
            g.end_step(b.v, u1, v1)
        } else {
            0.0
        };
        self.history.push(Piece {
            left: b.gl,
            right: self.drift + b.fr + extra,
            split: None,
        });
        self.u = u1;
        self.v = v1;
        Ok(())
    }

    /// The first part of a step: the noise on it and what the corrector needs from the state
    /// (the lane stepper forms the same numbers for several paths, then steps them together).
    #[inline(always)]
    fn begin(&mut self) -> Begin {
        let rhs = &self.rhs;
        let (el, er) = self.noise.next_step();
        let (u, v, side) = (self.u, self.v, self.side);
        let gl = self.drift + rhs.forcing(el, side);
        let known = self.base + self.history.value() + self.wl * gl;
        Begin {
            el,
            er,
            u,
            v,
            gl,
            known,
            fr: rhs.forcing(er, side),
        }
    }

    /// The events of a step whose free end is (u1, v1): sticking, an impact (the rest of the
    /// step redone), the blow-up check, the side of the Zhuravlev crossing. Counts the step.
    #[inline(always)]
    fn end_events(&mut self, b: &Begin, mut u1: f64, mut v1: f64) -> Result<End> {
        let (u, v) = (b.u, b.v);
        self.events = StepEvents::default();
        let mut piece = Piece {
            left: b.gl,
            right: 0.0,
            split: None,
        };
        let mut push = true;
        if self.wall && self.stuck {
            if u1 <= 0.0 {
                // still pressed against the wall
                push = self.stick(v1);
                (u1, v1) = (0.0, 0.0);
            } else {
                self.stuck = false;
            }
        } else if (self.wall && u1 < 0.0) || (self.crossing && u * u1 < 0.0) {
            let (split, u2, v2) = self.impact(b.gl, (b.el, b.er), (u1, v1));
            (u1, v1) = (u2, v2);
            piece.split = Some(split);
            if self.wall && u1 < 0.0 {
                // the next impact would come within this step: stick
                push = self.stick(v1);
                (u1, v1) = (0.0, 0.0);
                self.stuck = true;
            }
        }
        self.steps += 1;
        self.check_blow_up((u, v), (u1, v1))?;
        if self.crossing && u1 != 0.0 {
            self.side = u1.signum();
        }
        Ok(End {
            u1,
            v1,
            piece,
            push,
        })
    }

    /// The last part of a step, after [`Stepper::set_node`] at its end: the piece of g into the
    /// memory, the new state.
    #[inline(always)]
    fn complete(&mut self, b: &Begin, mut end: End) {
        if end.push {
            end.piece.right = self.drift + self.rhs.forcing(b.er, self.side);
            self.history.push(end.piece);
        }
        self.u = end.u1;
        self.v = end.v1;
    }

    /// The node's g without forcing and the predictor's weight at the end of a step at (u1, v1)
    /// (not yet stored as the state); returns μP(u1).
    #[inline]
    fn set_node(&mut self, u1: f64, v1: f64) -> f64 {
        let a1 = self.rhs.damping(u1);
        (self.drift, self.pw) = self.rhs.node(self.h, a1, u1, v1);
        a1
    }

    /// Err([`Error::BlowUp`]) when the step from `from` ended at `to` beyond the blow-up
    /// threshold (or not finite), with the time, both states and the stiffness Δt·μ|P(U)|.
    #[inline]
    fn check_blow_up(&self, from: (f64, f64), to: (f64, f64)) -> Result<()> {
        if to.0.abs() <= self.blow_up && to.1.abs() <= self.blow_up {
            return Ok(());
        }
        Err(Error::BlowUp {
            t: self.time(),
            u: to.0,
            v: to.1,
            from_u: from.0,
            from_v: from.1,
            stiffness: self.h * self.rhs.damping(from.0).abs(),
            dt: self.h,
        })
    }
}

/// The General kernel's constants of `problem`'s paths into `plan` ([`super::GeneralPlan`]),
/// from the `General` that [`Stepper::new`] builds (its multiplicative noise's stream at
/// path 0 of seed 0: the constants do not depend on them); nothing for the paper's family.
pub(crate) fn export_general(
    problem: &Problem,
    method: &PredictorCorrector,
    horizon: f64,
    plan: &mut super::GeneralPlan,
) -> Result<()> {
    let oscillator = problem.oscillator();
    let Some(t) = oscillator.terms() else {
        return Ok(());
    };
    let history = fresh_history(problem, method, horizon)?;
    let rhs = Affine::new(oscillator, problem.system());
    let setup = general::MemorySetup {
        memory: method.memory,
        window: method.window,
        horizon: history.kernel().map_or(0.0, |k| k.to),
    };
    let g = General::new(&rhs, t, method.dt, &setup, oscillator.noise(), (0, 0))?;
    g.export(plan)
        .map_err(|(what, n, max)| Error::NotApplicable {
            method: "the GPU kernel".into(),
            assumption: "the General kernel's terms within the kernel's fixed sizes".into(),
            reason: format!("{what} is {n}, at most {max}"),
        })
}

/// Most steps of a path with [`Memory::Direct`] (O(N) work and memory per step: 10⁷ steps
/// hold about half a gigabyte of history and take hours).
pub const MAX_DIRECT_STEPS: u64 = 10_000_000;

/// The empty memory of a path (with its verified SOE kernel), built once per ensemble: every
/// driver comes here before any work, so the method and the horizon are checked here (Δt, the
/// memory, the window; the horizon in [0, [`MAX_STEPS`] steps], with the direct memory at most
/// [`MAX_DIRECT_STEPS`]).
pub(crate) fn fresh_history(
    problem: &Problem,
    method: &PredictorCorrector,
    horizon: f64,
) -> Result<History> {
    method.validate()?;
    let dt = method.dt;
    let steps = horizon / dt;
    if !(horizon >= 0.0 && steps <= MAX_STEPS as f64) {
        return Err(Error::invalid(
            "horizon",
            horizon,
            format!("[0, {MAX_STEPS:e} steps of dt = {}]", Exact(dt)),
        ));
    }
    if method.memory == Memory::Direct && steps.round() > MAX_DIRECT_STEPS as f64 {
        return Err(Error::invalid(
            "t_end",
            horizon,
            format!(
                "at most {MAX_DIRECT_STEPS:e} steps of dt = {} with the direct memory (O(N) work \
                 per step; the sum-of-exponentials memory has no such bound)",
                Exact(dt)
            ),
        ));
    }
    let lambda = Affine::new(problem.oscillator(), problem.system()).lambda;
    History::new(lambda, method.dt, horizon, method.memory, method.window)
}
