//! The General kernel: the terms of the class beyond the paper's Eq. (1) that the engine
//! steps — an odd restoring force, Rayleigh damping, a harmonic forcing, up to two fractional
//! terms K_j·D^{α_j}U and a multiplicative noise U·η_m — with the same predictor–corrector as
//! the paper's kernel ([`super::Affine`]), and its tangent (`super::tangent`, the fractional
//! terms' memories and U·η_m included).
//!
//! # Equation
//! D^{1+λ}U + Σ_j K_j D^{α_j}U − h(U, U̇)U̇ + k(U) = F cos(Ωt + φ) + η_a(t) + U·η_m(t), no wall,
//! the wall at 0, or the model's walls (one at any δ keeping U above or below it, two at
//! δ1 < δ2: `super::walls`; fractional terms and multiplicative noise with any of these), with h = μ0P(U) + Σ_{k≥1} d_k U̇^{2k}, k(U) = ω0²U + k3U³ + k5U⁵, Caputo
//! derivatives, α_j ∈ (0, 1]; in Volterra form, with m_j = J^{1−α_j}V (= D^{α_j}U, U being
//! continuous),
//! U′ = V, V = V₀ + J^λ g, g = h(U, V)V − k(U) − Σ_j K_j m_j + F cos ψ + η_a + Uη_m,
//! ψ = Ωt + φ; η_a, η_m white (⟨ηη⟩ = 2Dδ) or OU (⟨ηη⟩ = (D/τ)e^{−|t−s|/τ}), with correlation c.
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
//! tangent of such impact steps is that of the model's walls below (`super::walls`, with this
//! wall as a lower wall at 0).
//!
//! **The model's walls** (a wall off 0, keeping U below, two walls, a speed-dependent
//! restitution r(|U̇₋|)): `super::walls` — the same location and redone rest with g at the wall
//! h(δ, V)V − k(δ) + F cos ψ* + η* ([`General::wall_drift`], [`General::wall_velocity`] take δ),
//! and sticking at δ while the net force there pushes into the wall. A General path holds them
//! in `walls`; without them no step looks further than one `Option`.
//!
//! **Fractional terms: a memory of V each.** m_j is a [`History`] of V of order 1 − α_j — the
//! leading memory's machinery (exact window, verified sum of exponentials, lumped moments),
//! built for the run's memory kind, window, tolerance and horizon once per ensemble (a small
//! cache by (α, Δt, T, tolerance, window)) — into which each step pushes its piece
//! (V_n, V_{n+1}). Over a step m_{j,n+1} = M_j + ϖ_l^j V_n + ϖ_r^j V_{n+1} (M_j the completed
//! pieces' value, ϖ the memory's current weights), affine in V_{n+1}: the corrector stays one
//! division, with a − κ in place of a (κ = Σ_j K_j ϖ_r^j, in the division, the Hermite limiter and
//! the predictor's weight) and −Σ_j K_j(M_j + ϖ_l^j V_n) added to the step's known forcing F_r;
//! g's value at the end, stored in the leading memory, has −Σ_j K_j m_{j,n+1}. α_j = 1 is local:
//! m_j = V (ϖ = (0, 1), no history), the same as K·U̇ in h. m_j(0) = 0 for α_j < 1 and V(0)
//! at α_j = 1. Clones carry the memories; the two-trajectory Lyapunov method pulls them with the
//! state (split pieces included: they combine when the leading memory's do).
//!
//! **Fractional terms at a wall.** Caputo's D^αU = J^{1−α}U̇ and U̇ jumps at an impact, so each
//! memory of V is split there exactly as the leading memory of g is (`super::impact`): V's piece
//! of the impact step is two linear pieces, V_n → V(t*) on [t_n, t*] and V₊ → V_{n+1} on
//! [t*, t_{n+1}] (the memory's [`Split`], held exactly in the window and entering the modes
//! exactly). The step, at a wall U = δ (the paper's at 0 or the model's):
//! - at the instant t* = t_n + θΔt, m_j(t*) = A_j + c_j V(t*) with (A_j, c_j) the memory's
//!   value of the completed pieces and of [t_n, t*] ([`History::at_fraction`], from V_n), and
//!   m_j(t*) = V(t*) at α_j = 1 ([`General::memories_at`]); so g at the wall,
//!   h(δ, V)V − k(δ) + F cos ψ* + η* − Σ_j K_j m_j(t*), stays affine in V(t*) (plus the Rayleigh
//!   terms) and V(t*) is the root of V = N + w_s·g as before, with κ* = Σ_j K_j c_j taken off
//!   ∂_V g ([`General::wall_velocity_lagged`]);
//! - the leading memory's split piece of g has −Σ K_j m_j(t*) on both sides: J^{1−α}V is
//!   continuous for α < 1, so only the α = 1 terms follow V to V₊;
//! - the redone rest [t*, t_{n+1}] from (δ, V₊): m_{j,n+1} = M_j + (the split step's known part
//!   from V_n, V(t*), V₊) + ϖ_j^s V_{n+1} ([`History::current_split`]), so the corrector is the
//!   same one division with κ_s = Σ_j K_j ϖ_j^s in place of κ and −Σ_j K_j(M_j + known_j) in
//!   the known forcing ([`General::split_memories`], [`General::advance_split`]);
//! - the step's end pushes V's split piece into each memory, and −Σ_j K_j m_{j,n+1} at the node.
//!
//! With [`crate::engine::ImpactMemory::Restart`] the fractional terms' memories restart with the
//! leading one (at the instant of an impact, and at the end of a sticking step): the whole
//! fractional state forgets the past, m_j = 0 just after t* for α_j < 1. Sticking at δ clamps V
//! to 0: the step's piece of V ends at 0, as g's does. The tangent differentiates these steps
//! too (module docs of `super::tangent`, "Fractional terms and multiplicative noise"). Cost:
//! only an impact step of a path with fractional terms does any of this (cold code); a path
//! without them takes the branches it took before (`fractional()` false: the same bits).
//! The lanes step such paths one by one with this scalar step (as every General path), so an
//! ensemble gives each path's scalar bits (`tests/fractional_walls.rs`, 4 and 8 lanes).
//!
//! **Multiplicative noise.** η_m is piecewise constant at its exact step mean, like η_a, from a
//! stream of its own per path (seed XOR a constant): η_a's deviates, hence every other path's
//! bits, do not move. With correlation c to η_a (one τ), η_m = c√(D_m/D_a)η_a + √(1 − c²)η′: η_a
//! and η′ are the same linear map of their deviates, so the mixture has η_m's law and
//! correlation c exactly. η_a here is the additive noise as it enters g, side·η_a (a path
//! started below 0 carries side = −1: `super`), so c is the correlation of the equation's
//! terms whichever side the path starts on. The corrector carries U_nη_m at the left end and U^Pη_m at the right
//! (each pass's U frozen there; U_{n+1}η_m stored): the trapezoid ½(U_n + U_{n+1})η_mΔt.
//! **Calculus**: the coefficient U of the noise does not depend on V and has finite variation
//! (U̇ bounded, U continuous at impacts), so [U, W] = 0 and ∫U∘dW = ∫U dW: Itô, Stratonovich and
//! the τ → 0 limit of OU noise (Wong–Zakai) are one process, at λ = 1 and below, and there is no
//! drift correction. The predictor U^P sees the step's deviate only at O(Δt^{3/2}), so the
//! scheme adds no O(1) drift. At the wall at 0, U·η_m = 0: the impact code is unchanged, and
//! the redone rest of the step carries U^Pη_m. At a wall U = δ ≠ 0 (`super::walls`) the force
//! δ·η_m ([`General::parametric_at`]; η_m is constant over the step) is part of g at the
//! instant: in the scheme's V(t*), the split piece of g on both sides (U is continuous) and
//! the net force that decides sticking.
//!
//! # Reference
//! model-class.md §2, §3, §4, §5 (the design); Diethelm, Ford & Freed (2002) for the scheme;
//! Wong & Zakai, Ann. Math. Statist. 36 (1965) 1560–1564 (coloured noise's white limit is
//! Stratonovich's).
//!
//! # Tests
//! `tests/general.rs`: the Duffing oscillator under white noise against its exact stationary
//! density ∝ exp(−cH/D) (⟨U²⟩, ⟨U̇²⟩ = D/c by quadrature); the forced linear oscillator's
//! steady amplitude against |F·H(iΩ)| at λ = 1 and λ = 0.9, with its observed convergence as Δt
//! halves; a Rayleigh oscillator's cycle; lanes and clones give the scalar bits; at the wall,
//! the paper kernel's bits when the terms vanish (k3 = 1e-300) and a Duffing oscillator at
//! r = 1 keeping energy and half-period at second order. `tests/walls.rs`: the model's walls
//! (exact periods between two walls and against an offset wall at r = 1 with the energy kept,
//! at second order; r(|U̇₋|); sticking at δ). `tests/fractional.rs`: the fractional
//! terms' memories against the direct memory (as `tests/soe.rs` checks the leading one), α = 1
//! against K·U̇ in h, the fractionally damped linear oscillator's stationary variances under
//! white and OU noise against the spectral integral, the parametric oscillator's second moments
//! against the exact moment system below and above D_c = 2ζω0³, lanes and clones, multiplicative
//! noise at the wall; `tests/walls.rs`: multiplicative noise at a wall off 0 against the same
//! oscillator moved to put its wall at 0 (δ·η_m becomes additive noise: the paths agree to
//! rounding). `tests/fractional_walls.rs`: fractional terms with the paper's wall and
//! the model's walls (α = 1 against K·U̇ in h to rounding and against the exact damped arcs at
//! second order; α = 0.5 at its observed order with impacts; SOE against Direct through
//! impacts and sticking, both impact memories; K = 1e-12 against no term; lanes and clones).
//! Unit test below: the correlated η_m's law. `engine/stepper/tangent.rs`:
//! the tangent step against finite differences of the step, fractional terms and U·η_m
//! included, with and without walls.

use super::affine::{
    hermite_limiter, pass_tangent_u1, pass_tangent_u1_moving, predictor_weight,
    predictor_weight_slope, Affine,
};
use super::polynomial::Polynomial;
use super::tangent::{fold_theta, Tangent};
use super::walls::Walls;
use crate::engine::kernel::MIN_SOE_LAMBDA;
use crate::engine::memory::{History, Memory, Piece, Split};
use crate::engine::noise::{Noise, NoiseStream};
use crate::error::{Error, Result};
use crate::maths;
use crate::model::{GeneralTerms, Harmonic, NoiseTerm};
use std::sync::Mutex;

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

/// One fractional term K·D^αU = K·m, m = J^{1−α}V (module docs): its memory of V.
#[derive(Debug, Clone)]
struct FractionalMemory {
    /// K.
    k: f64,
    /// The memory of J^{1−α}V over the completed steps; None at α = 1 (the term is local:
    /// m = V).
    history: Option<History>,
    /// The scaled weights of V_n and V_{n+1} in m_{n+1} ((0, 1) at α = 1).
    wl: f64,
    wr: f64,
}

/// The multiplicative noise η_m = mix·η_a + own·η′ (module docs): η′ of η_m's law from a
/// stream of its own, mixed with the additive noise's level for the correlation c.
#[derive(Debug, Clone)]
struct Parametric {
    stream: NoiseStream,
    /// c·√(D_m/D_a) (0 when uncorrelated).
    mix: f64,
    /// √(1 − c²).
    own: f64,
}

/// The seed of η_m's stream is the run's seed XOR this (η_a's deviates, hence the paper's
/// bits, do not move).
const PARAMETRIC_SALT: u64 = 0x6d75_6c74_6970_6c79;

/// The multiplicative noise of `term` (τ = 0: white), correlated by `c` with `additive`.
fn parametric(
    term: NoiseTerm,
    c: f64,
    additive: Noise,
    h: f64,
    (seed, path): (u64, u64),
) -> Result<Parametric> {
    let kind = if term.correlation_time == 0.0 {
        Noise::White {
            intensity: term.intensity,
        }
    } else {
        Noise::Colored {
            intensity: term.intensity,
            correlation_time: term.correlation_time,
        }
    };
    let d_a = match additive {
        Noise::None => 0.0,
        Noise::White { intensity } | Noise::Colored { intensity, .. } => intensity,
    };
    // one correlation time (validated): η_a and η′ are the same linear map of their deviates,
    // so c·√(D_m/D_a)·η_a + √(1 − c²)·η′ has η_m's law and correlation c with η_a
    let (mix, own) = if c != 0.0 && d_a > 0.0 {
        (c * (term.intensity / d_a).sqrt(), (1.0 - c * c).sqrt())
    } else {
        (0.0, 1.0)
    };
    Ok(Parametric {
        stream: NoiseStream::new(kind, h, seed ^ PARAMETRIC_SALT, path)?,
        mix,
        own,
    })
}

/// Where the memories of the fractional terms are built: the leading memory's kind, window
/// and horizon ([`General::new`]).
#[derive(Debug, Clone, Copy)]
pub(super) struct MemorySetup {
    pub(super) memory: Memory,
    pub(super) window: usize,
    /// The SOE kernel's certified horizon T (unused by the direct memory).
    pub(super) horizon: f64,
}

/// Empty memories of J^{1−α}V already built (their SOE kernels verified), by (order, Δt, T,
/// tolerance, window): an ensemble builds each once, not once per path.
static BUILT: Mutex<Vec<([u64; 5], History)>> = Mutex::new(Vec::new());
/// Most memories [`BUILT`] keeps.
const BUILT_MAX: usize = 16;

/// The empty memory of J^{1−α}V of term `index` (order α ∈ (0, 1)), steps of `h`.
fn fractional_history(index: usize, order: f64, h: f64, setup: &MemorySetup) -> Result<History> {
    let lambda = 1.0 - order;
    if lambda < MIN_SOE_LAMBDA {
        return Err(Error::invalid(
            format!("fractional.{index}.order").as_str(),
            order,
            "(0, 1 − 1e-6] or exactly 1 (K·U̇): the memory J^{1−α}U̇ of an order closer to 1 is \
             a near-delta the sum of exponentials does not resolve",
        ));
    }
    let tolerance = setup.memory.tolerance(h).map_or(u64::MAX, f64::to_bits);
    let key = [
        order.to_bits(),
        h.to_bits(),
        setup.horizon.to_bits(),
        tolerance,
        setup.window as u64,
    ];
    if let Some((_, built)) = BUILT
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .iter()
        .find(|(k, _)| *k == key)
    {
        return Ok(built.clone());
    }
    let built = History::new(lambda, h, setup.horizon, setup.memory, setup.window)?;
    let mut cache = BUILT.lock().unwrap_or_else(|e| e.into_inner());
    if cache.len() >= BUILT_MAX {
        cache.remove(0);
    }
    cache.push((key, built.clone()));
    Ok(built)
}

/// g = h(U, V)V − k(U) − Σ_j K_j m_j + F cos ψ + η_a + Uη_m of the General kernel (module
/// docs), with the path's forcing phase, its memories of the fractional terms and its stream of
/// multiplicative noise.
#[derive(Debug, Clone)]
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
    /// The fractional terms' memories.
    memories: Vec<FractionalMemory>,
    /// κ = Σ_j K_j ϖ_r^j: −κV_{n+1} is the fractional terms' part of g at a step's end that
    /// depends on V_{n+1}.
    kappa: f64,
    /// −Σ_j K_j m_j at the current node.
    lag: f64,
    /// −Σ_j K_j(M_j + ϖ_l^j V_n) of the step in progress (the part of −ΣK_j m_{j,n+1} known
    /// at its start).
    ahead: f64,
    parametric: Option<Parametric>,
    /// η_m on the step in progress (0 without multiplicative noise).
    eta_m: f64,
    /// Fractional terms or multiplicative noise present (the step's extra work).
    extras: bool,
    /// The fractional terms' memories at an impact inside the step in progress
    /// ([`General::split_memories`]; taken by [`General::end_step`]).
    pending: Option<SplitMemories>,
}

/// The fractional terms' memories of V split at an impact inside the step in progress: V
/// jumps from V(t*) to V₊ at the fraction θ (module docs, "Fractional terms at a wall").
#[derive(Debug, Clone, Copy, PartialEq)]
struct SplitMemories {
    /// The split of V's piece: θ, V(t*) before, V₊ after.
    split: Split,
    /// −Σ_j K_j(M_j + known_j): the part of −Σ_j K_j m_{j,n+1} known after the impact.
    ahead: f64,
    /// Σ_j K_j ϖ_j^s: the weight of V_{n+1} in Σ_j K_j m_{j,n+1} on the split step.
    kappa: f64,
}

/// The tangent of [`SplitMemories`] ([`General::split_tangent`]; taken by
/// [`General::end_tangent`]).
#[derive(Debug, Clone, Copy)]
pub(super) struct TangentSplit {
    /// The reference's split of V's piece and its κ_s.
    split: Split,
    kappa: f64,
    /// The split's values' δ (θ held), and δ(ahead_s), δκ_s, δθ.
    d: Split,
    dahead: f64,
    dkappa: f64,
    dtheta: f64,
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
    /// The κ of its corrector (the split step's on an impact's redone rest).
    kappa: f64,
    passes: [GeneralPass; 2],
}

impl GeneralFree {
    /// The κ of its corrector.
    #[inline]
    pub(super) fn kappa(&self) -> f64 {
        self.kappa
    }

    /// The end (U₁, V₁).
    #[inline]
    pub(super) fn end(&self) -> (f64, f64) {
        let p = &self.passes[1];
        (p.u1, p.v1)
    }
}

impl General {
    /// The kernel of the paper kernel `affine`'s μ0P and ω0² with `terms`, steps of `h`: the
    /// fractional terms' memories as `setup` says (α = 1: local), the multiplicative noise
    /// from stream `path` of `seed` (salted), correlated with the additive noise `additive`.
    pub(super) fn new(
        affine: &Affine,
        terms: &GeneralTerms,
        h: f64,
        setup: &MemorySetup,
        additive: Noise,
        (seed, path): (u64, u64),
    ) -> Result<Self> {
        let mut memories = Vec::with_capacity(terms.fractional.len());
        for (j, f) in terms.fractional.iter().enumerate() {
            let (history, wl, wr) = if f.order == 1.0 {
                (None, 0.0, 1.0)
            } else {
                let history = fractional_history(j, f.order, h, setup)?;
                let (wl, wr) = history.current_weights();
                (Some(history), wl, wr)
            };
            memories.push(FractionalMemory {
                k: f.coefficient,
                history,
                wl,
                wr,
            });
        }
        let kappa = memories.iter().map(|m| m.k * m.wr).sum();
        let parametric = match terms.multiplicative {
            None => None,
            Some(m) => Some(parametric(m, terms.correlation, additive, h, (seed, path))?),
        };
        Ok(General {
            damping: affine.damping.clone(),
            slope: affine.slope.clone(),
            rayleigh: terms.rayleigh.clone(),
            omega2: affine.omega2,
            cubic: terms.cubic,
            quintic: terms.quintic,
            phase: terms.forcing.as_ref().map(|f| Phase::new(f, h)),
            walls: Walls::new(&terms.walls),
            extras: !memories.is_empty() || parametric.is_some(),
            memories,
            kappa,
            lag: 0.0,
            ahead: 0.0,
            parametric,
            eta_m: 0.0,
            pending: None,
        })
    }

    /// Copy the constants into `plan` (module docs of [`crate::engine::GeneralPlan`]): the
    /// phase's rotation and start as [`Phase::new`] computed them, the multiplicative noise's
    /// stream constants and mixing, κ as summed here. `Err((what, n, max))` when the Rayleigh
    /// terms exceed the plan's size.
    pub(crate) fn export(
        &self,
        plan: &mut crate::engine::GeneralPlan,
    ) -> std::result::Result<(), (&'static str, usize, usize)> {
        use crate::engine::PLAN_MAX_RAYLEIGH;
        let n = self.rayleigh.len();
        if n > PLAN_MAX_RAYLEIGH {
            return Err(("the number of Rayleigh terms", n, PLAN_MAX_RAYLEIGH));
        }
        plan.active = 1;
        plan.rayleigh_terms = n as u32;
        plan.rayleigh[..n].copy_from_slice(&self.rayleigh);
        plan.cubic = self.cubic;
        plan.quintic = self.quintic;
        plan.kappa = self.kappa;
        if let Some(p) = &self.phase {
            plan.forcing = 1;
            plan.amplitude = p.amplitude;
            plan.angle = p.angle;
            plan.phase = p.phi;
            (plan.rotation_cos, plan.rotation_sin) = p.rotation;
            (plan.start_cos, plan.start_sin) = p.now;
        }
        if let Some(p) = &self.parametric {
            plan.multiplicative = 1;
            plan.mix = p.mix;
            plan.own = p.own;
            plan.salt = PARAMETRIC_SALT;
            plan.parametric = p.stream.step_constants();
        }
        if let Some(w) = &self.walls {
            w.export(plan);
        }
        let n = self.memories.len();
        if n > crate::engine::PLAN_MAX_FRACTIONAL {
            return Err((
                "the number of fractional terms",
                n,
                crate::engine::PLAN_MAX_FRACTIONAL,
            ));
        }
        plan.fractional_terms = n as u32;
        for (j, m) in self.memories.iter().enumerate() {
            plan.fractional_k[j] = m.k;
            plan.fractional_wl[j] = m.wl;
            plan.fractional_wr[j] = m.wr;
            if let Some(h) = &m.history {
                plan.fractional_memory[j] = 1;
                h.export_memory(&mut plan.memories[j])?;
            }
        }
        Ok(())
    }

    /// Start the path at V(0) = `v0`: −Σ_j K_j m_j(0) = −Σ_{α_j = 1} K_j·v0 (m_j(0) =
    /// J^{1−α_j}V(0) = 0 for α_j < 1, but an α = 1 term is V itself).
    pub(super) fn start(&mut self, v0: f64) {
        self.lag = 0.0;
        for m in &self.memories {
            if m.history.is_none() {
                self.lag -= m.k * v0;
            }
        }
    }

    /// Whether the kernel has fractional terms or multiplicative noise (the step's extra work,
    /// [`General::begin_step`] and [`General::end_step`]).
    #[inline]
    pub(super) fn extras(&self) -> bool {
        self.extras
    }

    /// The tangent's memories of δV: one per fractional term with a memory (α < 1), in the
    /// terms' order, with the reference's layout and every number 0.
    pub(super) fn tangent_memories(&self) -> Vec<History> {
        self.memories
            .iter()
            .filter_map(|m| m.history.clone())
            .map(|mut h| {
                h.scale_state(0.0);
                h
            })
            .collect()
    }

    /// The tangent's part of [`General::begin_step`] (after it: η_m drawn), for the tangent
    /// `t` at the step's start: δ of g's extras there, δ(−Σ_j K_j m_{j,n}) + δU_n·η_m, and of
    /// the part of −Σ_j K_j m_{j,n+1} known now, −Σ_j K_j(δM_j + ϖ_l^j δV_n) (δM_j the tangent
    /// memory's value).
    #[inline]
    pub(super) fn begin_tangent(&self, t: &Tangent) -> (f64, f64) {
        let mut ahead = 0.0;
        let mut held = t.fractional.iter();
        for m in &self.memories {
            if m.history.is_some() {
                let past = held.next().expect("a tangent memory per memory").value();
                ahead -= m.k * (past + m.wl * t.v);
            }
        }
        (t.lag + t.u * self.eta_m, ahead)
    }

    /// The tangent's part of [`General::end_step`] (after it) of the step from V_n = `v` to
    /// V_{n+1} = `v1`, from δV_n = `dv` with the known part `dahead`
    /// ([`General::begin_tangent`]) to (δU₁, δV₁): δV's piece into every tangent memory (an
    /// impact's split piece with its θ-derivative, [`fold_theta`]), δ(−Σ_j K_j m_{j,n+1}) into
    /// `t.lag` (δahead − κδV₁ without an impact); returns δ of `end_step`'s value,
    /// δ(−Σ_j K_j m_{j,n+1}) − δahead + δU₁·η_m.
    pub(super) fn end_tangent(
        &self,
        t: &mut Tangent,
        (v, v1): (f64, f64),
        (dv, dahead): (f64, f64),
        (du1, dv1): (f64, f64),
    ) -> f64 {
        let Some(s) = t.pending.take() else {
            for h in &mut t.fractional {
                h.push(Piece {
                    left: dv,
                    right: dv1,
                    split: None,
                });
            }
            let now = -self.kappa * dv1;
            t.lag = dahead + now;
            return now + du1 * self.eta_m;
        };
        // the split piece: its values' derivatives with θ held, and the θ-derivative of the
        // reference's piece (V_n → V(t*), V₊ → V_{n+1})
        let mut d = s.d;
        if s.dtheta != 0.0 {
            let piece = Piece {
                left: v,
                right: v1,
                split: Some(s.split),
            };
            fold_theta(&piece, &mut d, s.dtheta);
        }
        for h in &mut t.fractional {
            h.push(Piece {
                left: dv,
                right: dv1,
                split: Some(d),
            });
        }
        // m_{j,n+1} = ahead_s − κ_s V_{n+1}, both moving with θ
        t.lag = s.dahead - s.kappa * dv1 - s.dkappa * v1;
        t.lag - dahead + du1 * self.eta_m
    }

    /// The tangent's memories restart with the reference's ([`General::restart_memories`]).
    pub(super) fn restart_tangent(&self, t: &mut Tangent) {
        for h in &mut t.fractional {
            h.restart();
        }
        t.pending = None;
        t.lag = 0.0;
    }

    /// The tangent of [`General::memories_at`] at θ of the step in progress from V_n = `v`,
    /// from the tangent memories (before any restart at the instant) along δV_n = `dv`, θ
    /// moving by `dtheta`: (δ of the known part −Σ_j K_j(δpast_j + ∂_θpast_j·δθ), δ of the
    /// weight Σ_j K_j ∂_θw_j·δθ) ([`History::at_fraction_rate`]; the α = 1 terms' weight is
    /// fixed).
    pub(super) fn memories_at_tangent(
        &self,
        t: &Tangent,
        (theta, dtheta): (f64, f64),
        (v, dv): (f64, f64),
    ) -> (f64, f64) {
        let (mut known, mut weight) = (0.0, 0.0);
        let mut held = t.fractional.iter();
        for m in &self.memories {
            if let Some(h) = &m.history {
                let d = held.next().expect("a tangent memory per memory");
                let (dpast, _) = d.at_fraction(theta, dv);
                let (rate_past, rate_w) = if dtheta != 0.0 {
                    h.at_fraction_rate(theta, v)
                } else {
                    (0.0, 0.0)
                };
                known -= m.k * (dpast + rate_past * dtheta);
                weight += m.k * rate_w * dtheta;
            }
        }
        (known, weight)
    }

    /// The tangent of [`General::split_memories`] (after it): the tangent memories restart
    /// where the reference's did, and δ of (the part of −Σ_j K_j m_{j,n+1} known after the
    /// impact, κ_s) along δV_n = `dv` and the split's values' δ `d` (δV(t*), δV₊; θ held), θ
    /// moving by `dtheta` ([`History::current_split_rate`]); kept in `t` for
    /// [`General::end_tangent`].
    pub(super) fn split_tangent(
        &self,
        t: &mut Tangent,
        (v, dv): (f64, f64),
        d: Split,
        dtheta: f64,
    ) -> (f64, f64) {
        let s = self.pending.expect("the memories split on this step");
        let (mut ahead, mut kappa) = (0.0, 0.0);
        let mut held = t.fractional.iter_mut();
        for m in &self.memories {
            if let Some(h) = &m.history {
                let dh = held.next().expect("a tangent memory per memory");
                if !s.split.keep_before {
                    dh.restart();
                }
                let (dknown, _) = dh.current_split(dv, &d);
                let (rate_known, rate_w) = if dtheta != 0.0 {
                    h.current_split_rate(v, &s.split)
                } else {
                    (0.0, 0.0)
                };
                ahead -= m.k * (dh.value() + dknown + rate_known * dtheta);
                kappa += m.k * rate_w * dtheta;
            }
        }
        t.pending = Some(TangentSplit {
            split: s.split,
            kappa: s.kappa,
            d,
            dahead: ahead,
            dkappa: kappa,
            dtheta,
        });
        (ahead, kappa)
    }

    /// The start of a step from (u, v) whose additive noise level is `el` (η_a, before any
    /// gain): draws η_m for the step; returns g's extra parts at the step's start,
    /// −Σ_j K_j m_{j,n} + u·η_m, and the part of −Σ_j K_j m_{j,n+1} known now,
    /// −Σ_j K_j(M_j + ϖ_l^j V_n).
    #[inline]
    pub(super) fn begin_step(&mut self, u: f64, v: f64, el: f64) -> (f64, f64) {
        if let Some(p) = &mut self.parametric {
            let (own, _) = p.stream.next_step();
            self.eta_m = p.mix * el + p.own * own;
        }
        let mut ahead = 0.0;
        for m in &self.memories {
            let past = m.history.as_ref().map_or(0.0, History::value);
            ahead -= m.k * (past + m.wl * v);
        }
        self.ahead = ahead;
        (self.lag + u * self.eta_m, ahead)
    }

    /// The end of the step begun by [`General::begin_step`] from V_n = `v` at (u1, v1): V's
    /// piece into every memory; returns the part of g's extras there not in the step's known
    /// forcing (which holds −Σ_j K_j(M_j + ϖ_l^j V_n)): −κV_{n+1} + u1·η_m.
    #[inline]
    pub(super) fn end_step(&mut self, v: f64, u1: f64, v1: f64) -> f64 {
        if self.pending.is_some() {
            return self.end_split_step(v, u1, v1);
        }
        for m in &mut self.memories {
            if let Some(h) = &mut m.history {
                h.push(Piece {
                    left: v,
                    right: v1,
                    split: None,
                });
            }
        }
        let now = -self.kappa * v1;
        self.lag = self.ahead + now;
        now + u1 * self.eta_m
    }

    /// [`General::end_step`] of a step with an impact ([`General::split_memories`]): V's split
    /// piece (V_n → V(t*), V₊ → V_{n+1}) into every memory; −Σ_j K_j m_{j,n+1} from the split
    /// step's known part and weight. Returns the same quantity as `end_step`, relative to the
    /// step's known forcing (which holds the unsplit −Σ_j K_j(M_j + ϖ_l^j V_n)).
    #[cold]
    fn end_split_step(&mut self, v: f64, u1: f64, v1: f64) -> f64 {
        let s = self.pending.take().expect("a split step");
        for m in &mut self.memories {
            if let Some(h) = &mut m.history {
                h.push(Piece {
                    left: v,
                    right: v1,
                    split: Some(s.split),
                });
            }
        }
        self.lag = s.ahead - s.kappa * v1;
        (self.lag - self.ahead) + u1 * self.eta_m
    }

    /// Whether the kernel has multiplicative noise U·η_m.
    #[inline]
    pub(super) fn multiplicative(&self) -> bool {
        self.parametric.is_some()
    }

    /// Whether the kernel has fractional terms K_j·D^{α_j}U.
    #[inline]
    pub(super) fn fractional(&self) -> bool {
        !self.memories.is_empty()
    }

    /// −Σ_j K_j m_j at the instant t* = t_n + θΔt inside the step in progress (from V_n = `v`)
    /// as (known part, weight of V(t*) of the terms with a memory, Σ K_j of the α = 1 terms):
    /// −Σ_j K_j m_j(t*−) = known − (weight + local)·V(t*) (each memory's
    /// [`History::at_fraction`]; an α = 1 term is V(t*) itself). After the instant the terms
    /// with a memory keep their value (J^{1−α}V is continuous for α < 1) and the α = 1 terms
    /// follow V to V₊. (0, 0, 0) without fractional terms.
    pub(super) fn memories_at(&self, theta: f64, v: f64) -> (f64, f64, f64) {
        let (mut known, mut weight, mut local) = (0.0, 0.0, 0.0);
        for m in &self.memories {
            match &m.history {
                None => local += m.k,
                Some(h) => {
                    let (past, w) = h.at_fraction(theta, v);
                    known -= m.k * past;
                    weight += m.k * w;
                }
            }
        }
        (known, weight, local)
    }

    /// Split the fractional terms' memories at an impact inside the step in progress (module
    /// docs, "Fractional terms at a wall"): V jumps from V(t*) = `v_at` to V₊ = `v_plus` at
    /// the fraction θ = `split.theta`; with `restart` (the memory restarts at impacts) each
    /// memory restarts at t* and forgets the part before. Returns (the part of
    /// −Σ_j K_j m_{j,n+1} known now, Σ_j K_j ϖ_j^s: the weight of V_{n+1}) for the redone rest
    /// of the step ([`General::advance_split`]); [`General::end_step`] pushes the split pieces.
    pub(super) fn split_memories(&mut self, v: f64, split: Split) -> (f64, f64) {
        let (mut ahead, mut kappa) = (0.0, 0.0);
        for m in &mut self.memories {
            match &mut m.history {
                None => kappa += m.k,
                Some(h) => {
                    if !split.keep_before {
                        h.restart();
                    }
                    let (known, w) = h.current_split(v, &split);
                    ahead -= m.k * (h.value() + known);
                    kappa += m.k * w;
                }
            }
        }
        self.pending = Some(SplitMemories {
            split,
            ahead,
            kappa,
        });
        (ahead, kappa)
    }

    /// The fractional terms' memories restart at the end of the step in progress (a sticking
    /// step with the memory restarting, [`super::Stepper`]'s `stick`): nothing of the step
    /// enters them, and −Σ_j K_j m_j = 0 at the node.
    pub(super) fn restart_memories(&mut self) {
        for m in &mut self.memories {
            if let Some(h) = &mut m.history {
                h.restart();
            }
        }
        self.pending = None;
        self.lag = 0.0;
        self.ahead = 0.0;
    }

    /// Draw η_m's future deviates from stream `path` of `seed` (salted), keeping its present
    /// OU value ([`super::Stepper::renoise`]).
    pub(super) fn renoise(&mut self, seed: u64, path: u64) {
        if let Some(p) = &mut self.parametric {
            p.stream.renoise(seed ^ PARAMETRIC_SALT, path);
        }
    }

    /// Pull the fractional terms' memories toward `reference`'s by the factor `c`
    /// ([`super::Stepper::contract_toward`]; split pieces combine when both memories hold them
    /// at the same θ, as the leading memory's). False when they cannot be combined, possibly
    /// after some were pulled: the caller works on a copy.
    pub(super) fn contract_toward(&mut self, reference: &General, c: f64) -> bool {
        if self.memories.len() != reference.memories.len() {
            return false;
        }
        for (m, r) in self.memories.iter_mut().zip(&reference.memories) {
            if let (Some(h), Some(hr)) = (&mut m.history, &r.history) {
                if !h.contract_toward(hr, c) {
                    return false;
                }
            }
        }
        self.lag = reference.lag + c * (self.lag - reference.lag);
        true
    }

    /// Multiply the fractional terms' memories of V and −Σ_j K_j m_j at the node by `c` (a
    /// direction of the state for the tangent's tests).
    #[cfg(test)]
    pub(super) fn scale_memories(&mut self, c: f64) {
        for h in self.memories.iter_mut().filter_map(|m| m.history.as_mut()) {
            h.scale_state(c);
        }
        self.lag *= c;
    }

    /// The tangent's (δ(−Σ_j K_j m_j), memories of δV) along [`General::scale_memories`]'s
    /// direction, `s` times.
    #[cfg(test)]
    pub(super) fn scaled_memories(&self, s: f64) -> (f64, Vec<History>) {
        let mut held = self.tangent_memories();
        for (t, h) in held
            .iter_mut()
            .zip(self.memories.iter().filter_map(|m| m.history.as_ref()))
        {
            *t = h.clone();
            t.scale_state(s);
        }
        (s * self.lag, held)
    }

    /// −Σ_j K_j m_j at the node and Σ_j K_j·(memory j's value) (what the tangent's tests
    /// compare).
    #[cfg(test)]
    pub(super) fn memories_seen(&self) -> (f64, f64) {
        let value = self
            .memories
            .iter()
            .filter_map(|m| m.history.as_ref().map(|h| m.k * h.value()))
            .sum();
        (self.lag, value)
    }

    /// Σ_j K_j·(the value of the tangent's memory j of δV).
    #[cfg(test)]
    pub(super) fn tangent_memories_seen(&self, t: &Tangent) -> f64 {
        self.memories
            .iter()
            .filter(|m| m.history.is_some())
            .zip(&t.fractional)
            .map(|(m, h)| m.k * h.value())
            .sum()
    }

    /// Whether the tangent's memories of δV hold their pieces in the layouts of the reference's
    /// memories of V.
    #[cfg(test)]
    pub(super) fn memories_in_layout(&self, t: &Tangent) -> bool {
        let held: Vec<&History> = self
            .memories
            .iter()
            .filter_map(|m| m.history.as_ref())
            .collect();
        held.len() == t.fractional.len()
            && held
                .iter()
                .zip(&t.fractional)
                .all(|(h, d)| d.same_layout_as(h))
    }

    /// Whether the fractional memories and the multiplicative noise's state equal `other`'s.
    pub(super) fn coincides_with(&self, other: &General) -> bool {
        self.lag == other.lag
            && self.memories.len() == other.memories.len()
            && self.memories.iter().zip(&other.memories).all(|(a, b)| {
                match (&a.history, &b.history) {
                    (Some(x), Some(y)) => x.coincides(y),
                    (None, None) => true,
                    _ => false,
                }
            })
            && self.parametric.as_ref().map(|p| p.stream.current())
                == other.parametric.as_ref().map(|p| p.stream.current())
            && self.phase == other.phase
    }

    /// Exponentials of the fractional terms' SOE memories, all together.
    pub(super) fn exponentials(&self) -> usize {
        self.memories
            .iter()
            .filter_map(|m| m.history.as_ref().map(History::exponentials))
            .sum()
    }

    /// Bytes held by the fractional terms' memories.
    pub(super) fn memory_bytes(&self) -> usize {
        self.memories
            .iter()
            .filter_map(|m| m.history.as_ref().map(History::state_bytes))
            .sum()
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
        (
            self.drift(u1, v1),
            predictor_weight(h, self.slope_v(u1, v1)),
        )
    }

    /// ∂_V g at (u, v) with the fractional terms' −κ (the predictor's weight's damping).
    #[inline]
    pub(super) fn slope_v(&self, u: f64, v: f64) -> f64 {
        self.a(u, v) - self.kappa
    }

    /// The multiplicative noise's force U·η_m at a wall U = δ on the step in progress: δ·η_m
    /// (η_m is constant over the step). Exactly 0 at δ = 0 and without multiplicative noise, so
    /// that a path at the wall at 0 keeps its bits.
    #[inline]
    pub(super) fn parametric_at(&self, delta: f64) -> f64 {
        if self.multiplicative() && delta != 0.0 {
            delta * self.eta_m
        } else {
            0.0
        }
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

    /// d/dθ of [`General::force_at`] (0 without forcing): the instant ψ* moves with θ at
    /// the rate ΩΔt.
    pub(super) fn force_at_rate(&self, theta: f64) -> f64 {
        match &self.phase {
            None => 0.0,
            Some(p) => {
                let back = (1.0 - theta) * p.angle;
                let (c, s) = p.now;
                p.amplitude * p.angle * (c * maths::sin(back) - s * maths::cos(back))
            }
        }
    }

    /// δ of [`General::a`] along (δu, δv).
    #[inline]
    pub(super) fn a_derivative(&self, u: f64, v: f64, du: f64, dv: f64) -> f64 {
        self.mu_p_slope(u) * du + self.rayleigh_at(v).a_slope * dv
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
        self.wall_velocity_lagged(delta, known, w, forcing, 0.0)
    }

    /// [`General::wall_velocity`] with the fractional terms at the instant: g at the wall has
    /// −Σ_j K_j m_j(t*) = (its known part, in `forcing`) − `kappa`·V ([`General::memories_at`]),
    /// so the root is of V = N + w((h(δ, V) − κ*)V + forcing). `kappa` = 0: the same bits.
    pub(super) fn wall_velocity_lagged(
        &self,
        delta: f64,
        known: f64,
        w: f64,
        forcing: f64,
        kappa: f64,
    ) -> f64 {
        let a0 = if kappa == 0.0 {
            self.mu_p(delta)
        } else {
            self.mu_p(delta) - kappa
        };
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
        kappa: f64,
        len: f64,
        (u, v, g0): (f64, f64, f64),
        (up, vl): (f64, f64),
        known: f64,
        w: f64,
        fr: f64,
    ) -> GeneralPass {
        let mp = self.mu_p(up);
        let r = self.rayleigh_at(vl);
        // κ = 0 without fractional terms: a and g's V-factor are then the same bits as before
        let a = mp + r.a - kappa;
        let k = self.restoring(up);
        let fr = if self.parametric.is_some() {
            fr + up * self.eta_m
        } else {
            fr
        };
        let inv = 1.0 / (1.0 - w * a);
        let lim = hermite_limiter(2.0 * w * a);
        let v1 = (known + w * (fr - k + r.rest)) * inv;
        let gr = (mp + self.rayleigh_at(v1).h - kappa) * v1 - k + fr;
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
        self.advance_split(self.kappa, len, (u, v, g0), pw, known, w, fr)
    }

    /// [`General::advance`] with `kappa` = Σ_j K_j ϖ_j in place of the unsplit step's κ: the
    /// redone rest of an impact step, whose fractional memories are split
    /// ([`General::split_memories`]; `fr` then holds their known part).
    #[allow(clippy::too_many_arguments)]
    #[inline]
    pub(super) fn advance_split(
        &self,
        kappa: f64,
        len: f64,
        (u, v, g0): (f64, f64, f64),
        pw: f64,
        known: f64,
        w: f64,
        fr: f64,
    ) -> GeneralFree {
        let start = (u, v, g0);
        let first = self.pass(kappa, len, start, (u + len * v + pw * g0, v), known, w, fr);
        let second = self.pass(kappa, len, start, (first.u1, first.v1), known, w, fr);
        GeneralFree {
            len,
            w,
            g0,
            pw,
            kappa,
            passes: [first, second],
        }
    }

    /// The derivative of one pass along (δu, δv, δg0), δup, δvl, δknown and δ of the known
    /// forcing F_r (the fractional terms' known part; U^P·η_m with η_m frozen is added here):
    /// (δU₁, δV₁).
    fn pass_tangent(
        &self,
        f: &GeneralFree,
        p: &GeneralPass,
        (du, dv, dg0): (f64, f64, f64),
        (dup, dvl): (f64, f64),
        (dknown, dfr): (f64, f64),
    ) -> (f64, f64) {
        let mps = self.mu_p_slope(p.up);
        let r = self.rayleigh_at(p.vl);
        let da = mps * dup + r.a_slope * dvl;
        let kp = self.restoring_slope(p.up);
        let dfr = dfr + dup * self.eta_m;
        let dv1 = p.inv * (dknown + f.w * (dfr + r.rest_slope * dvl - kp * dup) + p.v1 * f.w * da);
        // g at the end has −κV₁ (the fractional terms)
        let a_end = self.mu_p(p.up) + self.rayleigh_at(p.v1).a - f.kappa;
        let dgr = mps * dup * p.v1 + a_end * dv1 - kp * dup + dfr;
        let step = (f.len, f.w, f.g0);
        let du1 = pass_tangent_u1(step, (p.a, p.lim, p.gr), (du, dv, dg0), (dv1, dgr, da));
        (du1, dv1)
    }

    /// The derivative of [`General::advance`] from (u, v) along (δu, δv, δg0), δknown and δ of
    /// the known forcing F_r (the fractional terms' known part, [`General::begin_tangent`]; the
    /// noise and the phase frozen): (δU₁, δV₁).
    pub(super) fn advance_tangent(
        &self,
        f: &GeneralFree,
        (u, v): (f64, f64),
        (du, dv, dg0): (f64, f64, f64),
        dknown: (f64, f64),
    ) -> (f64, f64) {
        // the node's predictor weight has ∂_V g = a − κ
        let a0 = self.a(u, v) - f.kappa;
        let da0 = self.mu_p_slope(u) * du + self.rayleigh_at(v).a_slope * dv;
        let dpw = predictor_weight_slope(f.len, a0, da0);
        let dup = du + f.len * dv + f.pw * dg0 + f.g0 * dpw;
        let first = self.pass_tangent(f, &f.passes[0], (du, dv, dg0), (dup, dv), dknown);
        self.pass_tangent(f, &f.passes[1], (du, dv, dg0), first, dknown)
    }

    /// The derivative of [`General::advance`] from (u, v) = `start` when the step's length and
    /// its weight of g at the end move as well (the redone rest of an impact step: length
    /// (1 − θ)Δt, weights following θ): along (δu, δv, δg0), δpw, δknown and (δlen, δw), the
    /// forcing frozen (`dknown`: δknown and δ of the known forcing, as in
    /// [`General::advance_tangent`]). Returns (δU₁, δV₁).
    #[allow(clippy::too_many_arguments)]
    pub(super) fn advance_tangent_moving(
        &self,
        f: &GeneralFree,
        (_, v): (f64, f64),
        (du, dv, dg0): (f64, f64, f64),
        dpw: f64,
        dknown: (f64, f64),
        (dlen, dw, dkappa): (f64, f64, f64),
    ) -> (f64, f64) {
        let dup = du + dlen * v + f.len * dv + f.pw * dg0 + f.g0 * dpw;
        let moving = (v, dlen, dw, dkappa);
        let start = (du, dv, dg0);
        let first = self.pass_tangent_moving(f, &f.passes[0], moving, start, (dup, dv), dknown);
        self.pass_tangent_moving(f, &f.passes[1], moving, start, first, dknown)
    }

    /// [`General::pass_tangent`] with the length, the weight and κ moving: `moving` = (v at
    /// the start, δlen, δw, δκ). With X = F_r − k(up) + (h(up, vl) − a)vl (so that V₁(1 − wa) =
    /// known + wX): δV₁ = inv·(δknown + δw·X + w·δX + V₁·(δw·a + w·δa)) (δa with −δκ),
    /// δL = −L²(z/6)·2δ(wa), and U₁'s terms in len differentiated as well.
    fn pass_tangent_moving(
        &self,
        f: &GeneralFree,
        p: &GeneralPass,
        (v, dlen, dw, dkappa): (f64, f64, f64, f64),
        (du, dv, dg0): (f64, f64, f64),
        (dup, dvl): (f64, f64),
        (dknown, dfr): (f64, f64),
    ) -> (f64, f64) {
        let mp = self.mu_p(p.up);
        let mps = self.mu_p_slope(p.up);
        let r = self.rayleigh_at(p.vl);
        let da = mps * dup + r.a_slope * dvl - dkappa;
        let kp = self.restoring_slope(p.up);
        let end = self.rayleigh_at(p.v1);
        // F_r − k(up) = g_r − (h(up, V₁) − κ)V₁ (F_r with U^P·η_m)
        let x = p.gr - (mp + end.h - f.kappa) * p.v1 + r.rest;
        let dfr = dfr + dup * self.eta_m;
        let dx = dfr + r.rest_slope * dvl - kp * dup;
        let dwa = dw * p.a + f.w * da;
        let dv1 = p.inv * (dknown + dw * x + f.w * dx + p.v1 * dwa);
        let a_end = mp + end.a - f.kappa;
        let dgr = mps * dup * p.v1 + a_end * dv1 - kp * dup + dfr - dkappa * p.v1;
        let step = (f.len, f.w, f.g0);
        let pass = (p.a, p.lim, p.gr, p.v1);
        let du1 = pass_tangent_u1_moving(step, pass, (v, dlen, dwa), (du, dv, dg0), (dv1, dgr));
        (du1, dv1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// η_m = c·√(D_m/D_a)·η_a + √(1 − c²)·η′ has η_m's step variance and correlation c with
    /// η_a, white and OU (one τ), within four standard errors.
    #[test]
    fn correlated_multiplicative_noise_has_its_law_and_correlation() {
        let (d_a, d_m, h, n) = (0.3, 0.05, 0.01, 200_000);
        for (tau, c) in [(0.0, 0.6), (0.0, -1.0), (0.4, 0.3), (0.4, 0.0)] {
            let additive = if tau == 0.0 {
                Noise::White { intensity: d_a }
            } else {
                Noise::Colored {
                    intensity: d_a,
                    correlation_time: tau,
                }
            };
            let term = NoiseTerm {
                intensity: d_m,
                correlation_time: tau,
            };
            let mut a = NoiseStream::new(additive, h, 11, 3).unwrap();
            let mut p = parametric(term, c, additive, h, (11, 3)).unwrap();
            let (mut saa, mut smm, mut sam) = (0.0, 0.0, 0.0);
            for _ in 0..n {
                let (ea, _) = a.next_step();
                let (own, _) = p.stream.next_step();
                let em = p.mix * ea + p.own * own;
                saa += ea * ea;
                smm += em * em;
                sam += ea * em;
            }
            let ratio = smm / saa;
            let corr = sam / (saa * smm).sqrt();
            // consecutive OU step means are correlated: a wide band (≈ 1 + 2τ/h effective)
            let sd = (2.0 / n as f64).sqrt() * (1.0 + 2.0 * tau / h).sqrt();
            assert!(
                (ratio - d_m / d_a).abs() < 4.0 * sd * d_m / d_a,
                "τ = {tau}, c = {c}: variance ratio {ratio} against {}",
                d_m / d_a
            );
            assert!(
                (corr - c).abs() < 4.0 * sd,
                "τ = {tau}, c = {c}: correlation {corr}"
            );
        }
    }
}
