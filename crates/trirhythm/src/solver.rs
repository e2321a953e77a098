//! The predictor–corrector driver for the fractional vibro-impact oscillator (Eq. 1) and its
//! integer-order companions (Eq. 5 and Eq. 9).
//!
//! # Equation
//! Caputo D^{1+λ}U = D^λ(U′), so Eq. (1) is the multi-order system
//! U′ = V,  D^λ V = g(U, V, η),  g = μ0 P(U) V − ω0² U + η,
//! solved in Volterra form V(t) = V(0) + J^λ g(t) + Σ (impact jumps), U(t) = U(0) + ∫V,
//! with the impact law U̇₊ = −r U̇₋ at U = 0 (barrier on). [`System::Equivalent`] integrates the
//! harmonic-balance ODE/SDE Eq. (5), Ü − μ1(β1 − c0 + P(U))U̇ + ω1²U = β2 η, with the same driver
//! at λ = 1 (with the same barrier and impact law); [`System::Zhuravlev`] integrates Eq. (9),
//! Z̈ − μ1(β1 − c0 + P(Z))Ż + ω1²Z = β2 sgn(Z) η with Ż₊ = rŻ₋ at Z = 0 (U = |Z|).
//!
//! # Method
//! One PECE step of the product-trapezoidal rule on the grid t_n = nΔt (see
//! [`crate::fractional`] for the weights and the memory):
//! - predictor: V^P = V₀ + J + H_{n+1} + w_l g_n + w_r g(U_n, V_n, η_{n+1}) (the corrector's own
//!   sums with g_{n+1} replaced by its value at the old state), U^P = U_n + ΔtV_n;
//! - corrector: V_{n+1} = V₀ + J + H_{n+1} + w_l g_n + w_r g(U^P, V^P, η_{n+1}),
//!   U_{n+1} = U_n + Δt(V_n + V_{n+1})/2 (U is the trapezoidal integral of the corrected V),
//!   then g_{n+1} = g(U_{n+1}, V_{n+1}, η_{n+1}) is stored. Only corrected values enter the
//!   history (DFF's PECE; storing predicted values would drop the order to 1 for λ < 1).
//! - λ = 1: the weights are exactly the trapezoidal ones and the step is the trapezoidal rule
//!   in integral form corrected once from an Euler predictor: with S_n = V₀ + J + Δt Σ'' g_j
//!   (trapezoidal sum of corrected values), V^P = S_n + Δt g(U_n, V_n), V_{n+1} = S_n +
//!   Δt(g_n + g^P)/2. It differs from textbook Heun only in that Heun's V_n would carry the
//!   predicted g (a difference O(Δt³) per step; both are of order 2).
//! - impacts: when U_{n+1} < 0 the crossing θ ∈ (0, 1) is located on the cubic Hermite
//!   interpolant of (U_n, V_n, U_{n+1}, V_{n+1}); the velocity just before it, V₋, is the
//!   scheme's own Volterra value at t* = t_n + θΔt (g is linear in V at U = 0, so this is solved
//!   exactly); the jump V₊ = −rV₋ is applied and the rest of the step [t*, t_{n+1}] is redone
//!   from (0, V₊). g is stored as two linear pieces on that step, so its memory stays exact.
//!   [`ImpactMemory::Continuous`] (default) keeps the lower terminal at 0 and adds the jump
//!   ΔV = V₊ − V₋ = −(1+r)V₋ to the constant of V's Volterra form; [`ImpactMemory::Restart`]
//!   restarts the memory at t* (V(t) = V₊ + J^λ_{t*} g). They coincide at λ = 1.
//! - sticking (grazing, chattering): at most one impact per step. If after it the redone part
//!   of the step would cross U = 0 again (the next impact would come within the same step, as
//!   in chattering with r < 1 or at grazing V₋ → 0), the oscillator **sticks**: U = 0, V = 0
//!   (the wall's reaction is added to the constant of V's Volterra form, or the memory restarts
//!   at rest under `Restart`). While stuck, every step is computed freely from U = 0, V = 0; if
//!   it ends at U ≤ 0 the state is clamped again (a sticking step, not an impact), else the
//!   oscillator leaves the wall. So U ≥ 0 always and a step never loops.
//! - noise: [`crate::noise`]: η is constant on each step at its exact step mean (OU: sampled
//!   jointly with the exact node update; white: variance 2D/Δt), so the forcing's step
//!   integrals have the exact law for any Δt/τ, including the white-noise limit.
//! - blow-up: a non-finite state or |U|, |V| above [`Options::blow_up`] returns
//!   [`Error::BlowUp`] with the time.
//!
//! # Example
//! ```
//! use trirhythm::model::preset;
//! use trirhythm::solver::{simulate, Options, Oscillator, PredictorCorrector};
//!
//! let osc = Oscillator::new(&preset("fig1")?.params)?;            // the problem (Eq. 1)
//! let method = PredictorCorrector { dt: 0.01, ..Default::default() }; // SOE memory, 1e-10
//! let options = Options { t_end: 50.0, u0: 6.78, v0: 0.0, ..Default::default() };
//! let path = simulate(&osc, &method, &options, 42)?;               // seed 42, path 0
//! assert_eq!(path.steps, 5000);
//! assert!(path.u.iter().all(|&u| u >= 0.0) && path.impacts > 0);
//! # Ok::<(), trirhythm::Error>(())
//! ```
//!
//! # Reference
//! Diethelm, Ford & Freed (2002) (PECE product-trapezoidal method); the memory compression of
//! [`crate::fractional`]; Zhuravlev's transformation for Eq. (9).
//!
//! # Tests
//! `tests/convergence.rs`: observed orders on D^{1+λ}U = −ω²U (Mittag-Leffler solution) and on
//! the linear impact oscillator at λ = 1 (exact piecewise solution), Continuous = Restart at
//! λ = 1; `tests/soe.rs`: SOE vs Direct on Eq. (1); `tests/stochastic.rs`: white-noise energy
//! growth 2Dt, OU → white limit, determinism across thread counts; `tests/impacts.rs`: the
//! impact invariant |V₊| = r|V₋| (proptest), U ≥ 0, chattering ends in sticking;
//! `tests/systems.rs`: Eq. (5) at λ = 1 is Eq. (1), U = |Z| between Eq. (5) and Eq. (9).

use crate::averaging::Equivalents;
use crate::error::{Error, Result};
use crate::fractional::{Convolution, Memory, Piece, Split, DEFAULT_WINDOW};
use crate::model::Params;
use crate::noise::{Noise, NoiseStream};
use rayon::prelude::*;

/// What the memory does at an impact.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ImpactMemory {
    /// The lower terminal stays at t = 0; each jump is a constant added to V's Volterra form.
    #[default]
    Continuous,
    /// The memory restarts at each impact (and at each sticking step).
    Restart,
}

/// Whether the wall at U = 0 is present.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Barrier {
    /// U ≥ 0 with the impact law U̇₊ = −rU̇₋.
    #[default]
    On,
    /// The same equation on the whole line (the plain fractional multirhythmic oscillator).
    Off,
}

/// Which equation is integrated.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum System {
    /// Eq. (1): the fractional system itself.
    #[default]
    Fractional,
    /// Eq. (5): the harmonic-balance integer-order equivalent (λ = 1 driver).
    Equivalent,
    /// Eq. (9): Eq. (5) after Zhuravlev's transformation, Z on the whole line, Ż₊ = rŻ₋ at Z = 0.
    Zhuravlev,
}

/// The method: step, memory, impact convention.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PredictorCorrector {
    /// Step Δt > 0.
    pub dt: f64,
    /// How the history is kept.
    pub memory: Memory,
    /// What the memory does at impacts.
    pub impact_memory: ImpactMemory,
    /// Steps of exact weights before the exponential modes take over (≥ 2).
    pub window: usize,
}

impl Default for PredictorCorrector {
    fn default() -> Self {
        PredictorCorrector {
            dt: 0.01,
            memory: Memory::default(),
            impact_memory: ImpactMemory::default(),
            window: DEFAULT_WINDOW,
        }
    }
}

/// What to simulate beyond the parameters: span, start, barrier, system, output.
#[derive(Debug, Clone, PartialEq)]
pub struct Options {
    /// End time T (rounded to a whole number of steps).
    pub t_end: f64,
    /// U(0) (≥ 0 with the barrier on).
    pub u0: f64,
    /// V(0) = U̇(0).
    pub v0: f64,
    /// Wall on or off.
    pub barrier: Barrier,
    /// Equation.
    pub system: System,
    /// Keep every k-th node in the trajectory (k ≥ 1).
    pub record_every: usize,
    /// Keep the list of impacts (time, V₋, V₊).
    pub record_impacts: bool,
    /// The summary amplitude is averaged over this many periods 2π/ω1 before T.
    pub amplitude_periods: f64,
    /// |U| or |V| above this is a blow-up.
    pub blow_up: f64,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            t_end: 100.0,
            u0: 1.0,
            v0: 0.0,
            barrier: Barrier::On,
            system: System::Fractional,
            record_every: 1,
            record_impacts: false,
            amplitude_periods: 5.0,
            blow_up: 1e8,
        }
    }
}

/// One impact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Impact {
    /// Time t*.
    pub time: f64,
    /// Velocity just before.
    pub v_minus: f64,
    /// Velocity just after.
    pub v_plus: f64,
}

/// The result of one path.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Trajectory {
    /// Recorded times.
    pub t: Vec<f64>,
    /// U at the recorded times (Z for [`System::Zhuravlev`]).
    pub u: Vec<f64>,
    /// V = U̇ at the recorded times.
    pub v: Vec<f64>,
    /// η at the recorded times (OU: the node value; white: the level of the step that led
    /// there; empty when there is no noise).
    pub eta: Vec<f64>,
    /// Number of impacts.
    pub impacts: usize,
    /// The impacts, when asked for.
    pub impact_events: Vec<Impact>,
    /// Steps that ended clamped at the wall (sticking).
    pub sticking_steps: usize,
    /// Steps taken.
    pub steps: usize,
    /// Step Δt.
    pub dt: f64,
    /// Mean of A = sqrt(U² + V²/ω1²) over the last [`Options::amplitude_periods`] periods.
    pub final_amplitude: f64,
    /// Number of exponentials of the SOE memory (0 for Direct or λ = 1).
    pub exponentials: usize,
    /// The SOE kernel's verified maximal relative error (0 when unused).
    pub soe_error: f64,
    /// Bytes of memory state held at the end of the run.
    pub memory_bytes: usize,
}

/// The problem: Eq. (1) for a parameter set, with its equivalents (Eq. 5).
#[derive(Debug, Clone, PartialEq)]
pub struct Oscillator {
    params: Params,
    equivalents: Equivalents,
    noise: Noise,
}

impl Oscillator {
    /// Validate the parameters and precompute Eq. (5)'s coefficients.
    pub fn new(params: &Params) -> Result<Self> {
        params.validate()?;
        Ok(Oscillator {
            params: params.clone(),
            equivalents: Equivalents::new(params),
            noise: Noise::from_params(params),
        })
    }

    /// The parameters.
    pub fn params(&self) -> &Params {
        &self.params
    }

    /// Eq. (5)'s coefficients.
    pub fn equivalents(&self) -> Equivalents {
        self.equivalents
    }

    /// The forcing.
    pub fn noise(&self) -> Noise {
        self.noise
    }
}

/// g(U, V, η) of one system, with the noise gain and (Eq. 9) its sign.
#[derive(Debug, Clone)]
struct Rhs {
    lambda: f64,
    mu: f64,
    coefficients: Vec<f64>,
    omega2: f64,
    gain: f64,
    reflect: bool,
    restitution: f64,
}

impl Rhs {
    fn new(osc: &Oscillator, system: System) -> Self {
        let p = &osc.params;
        let e = osc.equivalents;
        match system {
            System::Fractional => Rhs {
                lambda: p.lambda,
                mu: p.mu0,
                coefficients: p.damping.coefficients.clone(),
                omega2: p.omega0 * p.omega0,
                gain: 1.0,
                reflect: true,
                restitution: p.restitution,
            },
            System::Equivalent | System::Zhuravlev => {
                let mut c = p.damping.coefficients.clone();
                c[0] = e.beta1;
                Rhs {
                    lambda: 1.0,
                    mu: e.mu1,
                    coefficients: c,
                    omega2: e.omega1 * e.omega1,
                    gain: e.beta2,
                    reflect: system == System::Equivalent,
                    restitution: p.restitution,
                }
            }
        }
    }

    #[inline]
    fn damping(&self, u: f64) -> f64 {
        let u2 = u * u;
        self.coefficients
            .iter()
            .rev()
            .fold(0.0, |acc, &c| acc * u2 + c)
    }

    /// g at (u, v) with forcing η on the side `side` (±1; the sign of Z in Eq. 9, else 1).
    #[inline]
    fn g(&self, u: f64, v: f64, eta: f64, side: f64) -> f64 {
        self.mu * self.damping(u) * v - self.omega2 * u + self.gain * side * eta
    }
}

/// θ ∈ (0, 1] where the cubic Hermite interpolant of (u0, v0) → (u1, v1) over a step h
/// changes sign (u0 and u1 of opposite signs, or u1 = 0).
/// Hold the oscillator at rest on the wall at the end of a step whose free value was V = `v1`:
/// the wall's reaction goes into the constant of V's Volterra form (continuous memory), or the
/// memory restarts at rest. Returns whether the step's g still enters the history.
fn stick(conv: &mut Convolution, base: &mut f64, v1: f64, restart: bool) -> bool {
    if restart {
        conv.restart();
        *base = 0.0;
        false
    } else {
        *base -= v1;
        true
    }
}

/// The rest of a step after an impact at the fraction θ of `split`.
struct AfterImpact<'a> {
    split: &'a Split,
    /// The scheme's V(t*−) the jump starts from.
    v_at_impact: f64,
    /// V(t*+).
    v_plus: f64,
    /// sgn Z after the impact (the Zhuravlev form flips it; the wall does not).
    side: f64,
}

impl AfterImpact<'_> {
    /// Reset the memory (restart) or shift V's Volterra base so that V(t*+) = V₊ exactly, then
    /// take one predictor–corrector sub-step from (0, V₊) over (1 − θ)h; returns (U, V) at the
    /// end of the step.
    #[allow(clippy::too_many_arguments)]
    fn finish(
        &self,
        conv: &mut Convolution,
        base: &mut f64,
        rhs: &Rhs,
        restart: bool,
        gl: f64,
        er: f64,
        h: f64,
    ) -> (f64, f64) {
        if restart {
            conv.restart();
            *base = self.v_plus;
        } else {
            *base += self.v_plus - self.v_at_impact;
        }
        let (known_s, wr_s) = conv.current_split(gl, self.split);
        let known = *base + conv.history() + known_s;
        let hh = (1.0 - self.split.theta) * h;
        let vp = known + wr_s * rhs.g(0.0, self.v_plus, er, self.side);
        let gp = rhs.g(hh * self.v_plus, vp, er, self.side);
        let v1 = known + wr_s * gp;
        (0.5 * hh * (self.v_plus + v1), v1)
    }
}

fn hermite_root(u0: f64, v0: f64, u1: f64, v1: f64, h: f64) -> f64 {
    let f = |t: f64| {
        let t2 = t * t;
        let t3 = t2 * t;
        (2.0 * t3 - 3.0 * t2 + 1.0) * u0
            + (t3 - 2.0 * t2 + t) * h * v0
            + (-2.0 * t3 + 3.0 * t2) * u1
            + (t3 - t2) * h * v1
    };
    let (mut a, mut b) = (0.0, 1.0);
    let fa_pos = u0 > 0.0 || (u0 == 0.0 && u1 < 0.0);
    for _ in 0..60 {
        let m = 0.5 * (a + b);
        let fm = f(m);
        if (fm > 0.0) == fa_pos && fm != 0.0 {
            a = m;
        } else {
            b = m;
        }
    }
    0.5 * (a + b)
}

/// Simulate one path (path 0 of `seed`).
pub fn simulate(
    oscillator: &Oscillator,
    method: &PredictorCorrector,
    options: &Options,
    seed: u64,
) -> Result<Trajectory> {
    simulate_path(oscillator, method, options, seed, 0, None)
}

/// Simulate path `path` of `seed`, reporting progress (fraction done) to `progress`.
pub fn simulate_path(
    oscillator: &Oscillator,
    method: &PredictorCorrector,
    options: &Options,
    seed: u64,
    path: u64,
    progress: Option<&(dyn Fn(f64) + Sync)>,
) -> Result<Trajectory> {
    run_path(oscillator, method, options, seed, path, progress, None)
}

/// The empty memory of a run (with its verified SOE kernel), built once per ensemble.
fn fresh_memory(
    oscillator: &Oscillator,
    method: &PredictorCorrector,
    options: &Options,
) -> Result<Convolution> {
    let h = method.dt;
    let steps = (options.t_end / h).round();
    let lambda = Rhs::new(oscillator, options.system).lambda;
    Convolution::new(lambda, h, steps * h, method.memory, method.window)
}

fn run_path(
    oscillator: &Oscillator,
    method: &PredictorCorrector,
    options: &Options,
    seed: u64,
    path: u64,
    progress: Option<&(dyn Fn(f64) + Sync)>,
    memory: Option<&Convolution>,
) -> Result<Trajectory> {
    let h = method.dt;
    if !(h > 0.0 && h.is_finite()) {
        return Err(Error::invalid("dt", h, "(0, ∞), finite"));
    }
    if !(options.t_end > 0.0 && options.t_end.is_finite()) {
        return Err(Error::invalid("t_end", options.t_end, "(0, ∞), finite"));
    }
    let steps_f = (options.t_end / h).round();
    if !(1.0..=1e11).contains(&steps_f) {
        return Err(Error::invalid(
            "t_end",
            options.t_end,
            "between one step and 1e11 steps of dt",
        ));
    }
    let steps = steps_f as usize;
    if !options.u0.is_finite() {
        return Err(Error::invalid("u0", options.u0, "finite"));
    }
    if !options.v0.is_finite() {
        return Err(Error::invalid("v0", options.v0, "finite"));
    }
    if options.record_every == 0 {
        return Err(Error::invalid("every", 0.0, "1 or more"));
    }
    let rhs = Rhs::new(oscillator, options.system);
    let wall = rhs.reflect && options.barrier == Barrier::On;
    let crossing = options.system == System::Zhuravlev;
    if wall && options.u0 < 0.0 {
        return Err(Error::invalid(
            "u0",
            options.u0,
            "[0, ∞) with the barrier on",
        ));
    }
    let t_end = steps as f64 * h;
    let mut conv = match memory {
        Some(m) => m.clone(),
        None => Convolution::new(rhs.lambda, h, t_end, method.memory, method.window)?,
    };
    let mut noise = NoiseStream::new(oscillator.noise, h, seed, path)?;
    let has_noise = !oscillator.noise.is_none();
    let omega1 = oscillator.equivalents.omega1;
    let avg_from = t_end - options.amplitude_periods * 2.0 * std::f64::consts::PI / omega1;
    let restart = method.impact_memory == ImpactMemory::Restart;
    // g at U = 0 is a0·V + forcing
    let a0 = rhs.mu * rhs.coefficients[0];

    let cap = steps / options.record_every + 2;
    let mut out = Trajectory {
        t: Vec::with_capacity(cap),
        u: Vec::with_capacity(cap),
        v: Vec::with_capacity(cap),
        eta: Vec::with_capacity(if has_noise { cap } else { 0 }),
        dt: h,
        ..Default::default()
    };
    let (mut u, mut v) = (options.u0, options.v0);
    let mut base = options.v0;
    let mut stuck = false;
    let mut side = if options.u0 < 0.0 { -1.0 } else { 1.0 };
    out.t.push(0.0);
    out.u.push(u);
    out.v.push(v);
    if has_noise {
        out.eta.push(noise.current());
    }
    let (mut amp_sum, mut amp_n) = (0.0, 0usize);
    let tick = (steps / 1000).max(1);
    let (wl, wr) = conv.current_weights();

    for n in 0..steps {
        let t1 = (n + 1) as f64 * h;
        let (el, er) = noise.next_step();
        let gl = rhs.g(u, v, el, side);
        let hist = conv.history();
        let known = base + hist + wl * gl;
        let vp = known + wr * rhs.g(u, v, er, side);
        let up = u + h * v;
        let gp = rhs.g(up, vp, er, side);
        let mut v1 = known + wr * gp;
        let mut u1 = u + 0.5 * h * (v + v1);
        let mut piece = Piece {
            left: gl,
            right: 0.0,
            split: None,
        };
        let mut push = true;
        let mut new_side = side;

        if wall {
            if stuck {
                if u1 <= 0.0 {
                    // still pressed against the wall
                    push = stick(&mut conv, &mut base, v1, restart);
                    (u1, v1) = (0.0, 0.0);
                    out.sticking_steps += 1;
                } else {
                    stuck = false;
                }
            } else if u1 < 0.0 {
                let theta = hermite_root(u, v, u1, v1, h);
                let eta_star = el + theta * (er - el);
                let (hs, ws) = conv.at_fraction(theta, gl);
                let forcing = rhs.gain * eta_star;
                // the scheme's own V(t*−); at grazing it may come out ≥ 0: then V₋ = 0
                let v_at = (base + hs + ws * forcing) / (1.0 - ws * a0);
                let vm = v_at.min(0.0);
                let vplus = -rhs.restitution * vm;
                out.impacts += 1;
                if options.record_impacts {
                    out.impact_events.push(Impact {
                        time: n as f64 * h + theta * h,
                        v_minus: vm,
                        v_plus: vplus,
                    });
                }
                let split = Split {
                    theta,
                    before: a0 * v_at + forcing,
                    after: a0 * vplus + forcing,
                    keep_before: !restart,
                };
                let step = AfterImpact {
                    split: &split,
                    v_at_impact: v_at,
                    v_plus: vplus,
                    side,
                };
                (u1, v1) = step.finish(&mut conv, &mut base, &rhs, restart, gl, er, h);
                piece.split = Some(split);
                if u1 < 0.0 {
                    // the next impact would come within this step: stick
                    push = stick(&mut conv, &mut base, v1, restart);
                    (u1, v1) = (0.0, 0.0);
                    stuck = true;
                    out.sticking_steps += 1;
                }
            }
        } else if crossing && u * u1 < 0.0 {
            let theta = hermite_root(u, v, u1, v1, h);
            let eta_star = el + theta * (er - el);
            let (hs, ws) = conv.at_fraction(theta, gl);
            let forcing = rhs.gain * side * eta_star;
            let vm = (base + hs + ws * forcing) / (1.0 - ws * a0);
            let vplus = rhs.restitution * vm;
            out.impacts += 1;
            if options.record_impacts {
                out.impact_events.push(Impact {
                    time: n as f64 * h + theta * h,
                    v_minus: vm,
                    v_plus: vplus,
                });
            }
            new_side = -side;
            let split = Split {
                theta,
                before: a0 * vm + forcing,
                after: a0 * vplus - forcing,
                keep_before: !restart,
            };
            let step = AfterImpact {
                split: &split,
                v_at_impact: vm,
                v_plus: vplus,
                side: new_side,
            };
            (u1, v1) = step.finish(&mut conv, &mut base, &rhs, restart, gl, er, h);
            piece.split = Some(split);
        }

        if !(u1.is_finite() && v1.is_finite())
            || u1.abs() > options.blow_up
            || v1.abs() > options.blow_up
        {
            let value = if !u1.is_finite() || u1.abs() > options.blow_up {
                u1
            } else {
                v1
            };
            return Err(Error::BlowUp {
                what: "simulation of the oscillator",
                at: format!("t = {t1}"),
                value,
            });
        }
        if crossing && u1 != 0.0 {
            new_side = u1.signum();
        }
        side = new_side;
        if push {
            piece.right = rhs.g(u1, v1, er, side);
            conv.push(piece);
        }
        u = u1;
        v = v1;
        if t1 >= avg_from {
            amp_sum += (u * u + v * v / (omega1 * omega1)).sqrt();
            amp_n += 1;
        }
        if (n + 1) % options.record_every == 0 {
            out.t.push(t1);
            out.u.push(u);
            out.v.push(v);
            if has_noise {
                out.eta.push(noise.current());
            }
        }
        if let Some(p) = progress {
            if (n + 1) % tick == 0 {
                p((n + 1) as f64 / steps as f64);
            }
        }
    }
    out.steps = steps;
    out.final_amplitude = if amp_n > 0 {
        amp_sum / amp_n as f64
    } else {
        (u * u + v * v / (omega1 * omega1)).sqrt()
    };
    if let Some(k) = conv.kernel() {
        out.exponentials = k.len();
        out.soe_error = k.max_relative_error;
    }
    out.memory_bytes = conv.state_bytes();
    Ok(out)
}

/// Simulate paths 0..`paths` of `seed` in parallel. Path i depends only on (seed, i), so the
/// result is bit-identical whatever the number of threads.
pub fn simulate_ensemble(
    oscillator: &Oscillator,
    method: &PredictorCorrector,
    options: &Options,
    seed: u64,
    paths: usize,
) -> Result<Vec<Trajectory>> {
    if paths == 0 {
        return Ok(vec![]);
    }
    // validate through path 0, then share its freshly built memory (SOE kernel) with the rest
    let first = simulate_path(oscillator, method, options, seed, 0, None)?;
    let memory = fresh_memory(oscillator, method, options)?;
    let rest: Result<Vec<Trajectory>> = (1..paths as u64)
        .into_par_iter()
        .map(|i| run_path(oscillator, method, options, seed, i, None, Some(&memory)))
        .collect();
    let mut all = Vec::with_capacity(paths);
    all.push(first);
    all.extend(rest?);
    Ok(all)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::known_answers::linear_oscillator;

    #[test]
    fn lambda_one_is_the_trapezoidal_predictor_corrector() {
        // U'' = −ω²U without barrier: the trapezoidal PECE in integral form, by hand
        let p = linear_oscillator(1.0, 1.3, 1.0);
        let osc = Oscillator::new(&p).unwrap();
        let h = 0.05;
        let m = PredictorCorrector {
            dt: h,
            ..Default::default()
        };
        let o = Options {
            t_end: 2.0,
            u0: 1.0,
            v0: 0.2,
            barrier: Barrier::Off,
            ..Default::default()
        };
        let tr = simulate(&osc, &m, &o, 1).unwrap();
        let w2 = 1.3f64 * 1.3;
        let (mut u, mut v) = (1.0, 0.2);
        let mut s = 0.2; // S_n = V0 + trapezoidal sum of corrected g
        for n in 0..40 {
            let g = -w2 * u;
            let up = u + h * v;
            // (g does not depend on V here, so V^P = S_n + h g_n is not needed)
            let v1 = s + 0.5 * h * (g - w2 * up);
            let u1 = u + 0.5 * h * (v + v1);
            s += 0.5 * h * (g - w2 * u1);
            u = u1;
            v = v1;
            assert!((tr.u[n + 1] - u).abs() < 1e-13, "step {n}");
            assert!((tr.v[n + 1] - v).abs() < 1e-13, "step {n}");
        }
    }

    #[test]
    fn blow_up_is_reported_with_its_time() {
        let mut p = linear_oscillator(0.9, 1.0, 1.0);
        p.damping.coefficients = vec![50.0]; // strong negative damping
        let osc = Oscillator::new(&p).unwrap();
        let o = Options {
            t_end: 100.0,
            barrier: Barrier::Off,
            blow_up: 1e6,
            ..Default::default()
        };
        match simulate(&osc, &PredictorCorrector::default(), &o, 1) {
            Err(Error::BlowUp { at, .. }) => assert!(at.starts_with("t = ")),
            other => panic!("expected a blow-up, got {other:?}"),
        }
    }

    #[test]
    fn bad_input_names_the_parameter() {
        let osc = Oscillator::new(&Params::default()).unwrap();
        let m = PredictorCorrector {
            dt: -1.0,
            ..Default::default()
        };
        let e = simulate(&osc, &m, &Options::default(), 0).unwrap_err();
        assert!(matches!(e, Error::InvalidParameter { ref name, .. } if name == "dt"));
        let o = Options {
            u0: -0.5,
            ..Default::default()
        };
        let e = simulate(&osc, &PredictorCorrector::default(), &o, 0).unwrap_err();
        assert!(matches!(e, Error::InvalidParameter { ref name, .. } if name == "u0"));
    }
}
