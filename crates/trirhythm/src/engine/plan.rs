//! The step of a path as plain data: every constant the predictor–corrector of the paper's
//! family (the `Affine` kernel) and its memory use, in a `#[repr(C)]` layout, for a backend that
//! runs the same step elsewhere (the CUDA kernel of `trirhythm-gpu` and its CPU emulation,
//! whose `kernel/plan.h` mirrors [`StepPlan`] field by field).
//!
//! Method: [`StepPlan::new`] builds the path's empty memory exactly as every driver does
//! (`fresh_history`, the SOE kernel verified once) and the kernel's coefficients exactly as
//! [`super::Stepper::new`] does, then copies them out; nothing is recomputed, so a step taken
//! from the plan can equal the engine's step bit for bit (`trirhythm-gpu`'s emulation tests).
//!
//! [`GeneralPlan`] adds the General kernel's constants (`stepper::general`: Duffing and
//! quintic restoring, Rayleigh terms, the harmonic forcing's phase rotation, the multiplicative
//! noise's stream and mixing, the model's walls), copied out of the engine's own `General` of
//! the problem (`General::export`, `Walls::export`), so again nothing is recomputed.
//!
//! Scope: the paper's family (Eq. 1, 5, 9 with or without the wall at 0, any damping
//! polynomial, additive white or OU noise, both impact memories) with the sum-of-exponentials
//! memory, and the whole General kernel: Duffing, quintic, Rayleigh, forcing, fractional
//! terms (a memory of V each, exported as a [`StepPlan`]'s memory fields) and multiplicative
//! noise, with no wall, the paper's wall at 0 or the model's walls. The direct memory is
//! refused by name ([`Error::NotApplicable`]), as are windows, SOE kernels and numbers of
//! terms beyond the plan's fixed sizes.

use super::kernel::{phi_psi_series, LUMPED_TERMS};
use super::memory::Memory;
use super::noise::StepConstants;
use super::problem::{ImpactMemory, PredictorCorrector, Problem, System};
use super::stepper::{export_general, fresh_history, Affine};
use crate::error::{Error, Result};

/// Most exponentials of the SOE memory in a plan (a multiple of 4).
pub const PLAN_MAX_MODES: usize = 128;
/// Most pieces of the exact window in a plan (`window − 1`).
pub const PLAN_MAX_CAP: usize = 63;
/// Most coefficients of the damping polynomial (in U²) in a plan.
pub const PLAN_MAX_DAMPING: usize = 16;
/// Most Rayleigh coefficients d_k in a [`GeneralPlan`] (the model file's own bound).
pub const PLAN_MAX_RAYLEIGH: usize = 20;
/// Most fractional terms K_j·D^{α_j}U in a [`GeneralPlan`] (the model file's own bound).
pub const PLAN_MAX_FRACTIONAL: usize = 2;

/// The constants of one path's step and memory (field meanings as in the engine's
/// `stepper::affine` and `memory::history`).
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct StepPlan {
    /// μ times the damping polynomial's coefficients in U² (P(U) = Σ c_k U^{2k}).
    pub damping: [f64; PLAN_MAX_DAMPING],
    /// How many of `damping` are used.
    pub damping_terms: u32,
    /// 1 when the engine evaluates the polynomial by Horner (more than 8 coefficients), 0
    /// for its split even–odd form.
    pub damping_long: u32,
    /// ω² (ω1² for Eq. 5/9).
    pub omega2: f64,
    /// The noise's gain (1, or β2 for Eq. 5/9).
    pub gain: f64,
    /// r.
    pub restitution: f64,
    /// λ (1 for Eq. 5/9).
    pub lambda: f64,
    /// Δt.
    pub h: f64,
    /// The blow-up bound.
    pub blow_up: f64,
    /// The wall at U = 0 (1) or none (0).
    pub wall: u32,
    /// The Zhuravlev crossing (Eq. 9).
    pub crossing: u32,
    /// The memory restarts at an impact ([`ImpactMemory::Restart`]).
    pub restart: u32,
    /// Whether an SOE kernel exists (else the memory is the flat lumped sum of λ = 1).
    pub soe: u32,
    /// Δt^λ/Γ(λ).
    pub scale: f64,
    /// The current step's weights, scaled.
    pub wl0: f64,
    /// See `wl0`.
    pub wr0: f64,
    /// Pieces of the exact window (window − 1, or 0 when the kernel is flat).
    pub cap: u32,
    /// Exponentials of the kernel (`n_exp`), and their count padded to a multiple of 4.
    pub n_exp: u32,
    /// See `n_exp`.
    pub modes: u32,
    /// Whether the lumped polynomial is a constant.
    pub flat: u32,
    /// Length of `older`.
    pub older_len: u32,
    /// Unscaled product-integration weights of the pieces 0..=cap back (left, right).
    pub wl: [f64; PLAN_MAX_CAP + 1],
    /// See `wl`.
    pub wr: [f64; PLAN_MAX_CAP + 1],
    /// The scaled weights of the window's older pieces, in the engine's padded order.
    pub older: [f64; 2 * PLAN_MAX_CAP + 4],
    /// The scaled weights of the newest piece.
    pub newest: [f64; 2],
    /// The kernel's decay rates s_j.
    pub rates: [f64; PLAN_MAX_MODES],
    /// The kernel's weights c_j.
    pub weights: [f64; PLAN_MAX_MODES],
    /// e^{−s_jΔt} (padded with 0).
    pub decay: [f64; PLAN_MAX_MODES],
    /// Δt·ψ(s_jΔt).
    pub start: [f64; PLAN_MAX_MODES],
    /// Δt·(φ − ψ)(s_jΔt).
    pub end: [f64; PLAN_MAX_MODES],
    /// c_j e^{−s_j(cap + 1)Δt}.
    pub out: [f64; PLAN_MAX_MODES],
    /// The lumped polynomial's coefficients.
    pub lumped: [f64; LUMPED_TERMS],
    /// Its weights at the window's end.
    pub lumped_out: [f64; LUMPED_TERMS],
    /// The moments' shift coefficients (`memory::moments::MomentStep`).
    pub shift: [f64; 7],
    /// The moments' piece coefficients.
    pub piece: [f64; 6],
    /// The interval weights' even series (`kernel::IntervalWeights`).
    pub iw_even: [f64; 12],
    /// Its odd series.
    pub iw_odd: [f64; 12],
    /// k^λ for k < 16.
    pub iw_whole: [f64; 16],
    /// The series of φ and ψ (`kernel::phi_psi`).
    pub phi_series: [f64; 17],
    /// See `phi_series`.
    pub psi_series: [f64; 17],
}

impl StepPlan {
    /// The plan of `problem`'s paths with `method`, the memory certified up to `horizon` (as
    /// [`super::Stepper::new`]). Refuses what the plan does not hold, by name. For a problem
    /// with the General kernel's terms this is the leading memory, the damping μ0P and the
    /// wall; the terms are in its [`GeneralPlan`].
    pub fn new(problem: &Problem, method: &PredictorCorrector, horizon: f64) -> Result<Self> {
        let refuse = |assumption: &str, reason: String| Error::NotApplicable {
            method: "the GPU kernel".into(),
            assumption: assumption.into(),
            reason,
        };
        if method.memory == Memory::Direct {
            return Err(refuse(
                "memory = soe or auto",
                "the direct memory keeps the whole history of every path".into(),
            ));
        }
        let history = fresh_history(problem, method, horizon)?;
        let rhs = Affine::new(problem.oscillator(), problem.system());
        let mut plan = StepPlan::zeroed();
        let coefficients = rhs.damping_coefficients();
        if coefficients.len() > PLAN_MAX_DAMPING {
            return Err(refuse(
                "at most 16 damping coefficients",
                format!("the damping has {}", coefficients.len()),
            ));
        }
        plan.damping[..coefficients.len()].copy_from_slice(&coefficients);
        plan.damping_terms = coefficients.len() as u32;
        plan.damping_long = u32::from(coefficients.len() > 8);
        plan.omega2 = rhs.omega2;
        plan.gain = rhs.gain;
        plan.restitution = rhs.restitution;
        plan.lambda = rhs.lambda;
        plan.h = method.dt;
        plan.blow_up = problem.blow_up();
        plan.wall = u32::from(problem.wall());
        plan.crossing = u32::from(problem.system() == System::Zhuravlev);
        plan.restart = u32::from(method.impact_memory == ImpactMemory::Restart);
        history.export(&mut plan).map_err(|(what, n, max)| {
            refuse(
                "a window and an SOE kernel within the kernel's fixed sizes",
                format!("{what} is {n}, at most {max}"),
            )
        })?;
        let (phi, psi) = phi_psi_series();
        plan.phi_series = phi;
        plan.psi_series = psi;
        Ok(plan)
    }

    pub(crate) fn zeroed() -> Self {
        StepPlan {
            damping: [0.0; PLAN_MAX_DAMPING],
            damping_terms: 0,
            damping_long: 0,
            omega2: 0.0,
            gain: 0.0,
            restitution: 0.0,
            lambda: 0.0,
            h: 0.0,
            blow_up: 0.0,
            wall: 0,
            crossing: 0,
            restart: 0,
            soe: 0,
            scale: 0.0,
            wl0: 0.0,
            wr0: 0.0,
            cap: 0,
            n_exp: 0,
            modes: 0,
            flat: 0,
            older_len: 0,
            wl: [0.0; PLAN_MAX_CAP + 1],
            wr: [0.0; PLAN_MAX_CAP + 1],
            older: [0.0; 2 * PLAN_MAX_CAP + 4],
            newest: [0.0; 2],
            rates: [0.0; PLAN_MAX_MODES],
            weights: [0.0; PLAN_MAX_MODES],
            decay: [0.0; PLAN_MAX_MODES],
            start: [0.0; PLAN_MAX_MODES],
            end: [0.0; PLAN_MAX_MODES],
            out: [0.0; PLAN_MAX_MODES],
            lumped: [0.0; LUMPED_TERMS],
            lumped_out: [0.0; LUMPED_TERMS],
            shift: [0.0; 7],
            piece: [0.0; 6],
            iw_even: [0.0; 12],
            iw_odd: [0.0; 12],
            iw_whole: [0.0; 16],
            phi_series: [0.0; 17],
            psi_series: [0.0; 17],
        }
    }
}

/// The General kernel's constants (`stepper::general`), for a backend that steps it: the
/// restoring force k(U) = ω0²U + k3U³ + k5U⁵ beyond the [`StepPlan`]'s ω0², the Rayleigh
/// coefficients, the harmonic forcing's phase rotation, the multiplicative noise η_m (its
/// stream's step constants and its mixing with the additive noise), the model's walls, the
/// fractional terms (K_j, their weights, their memories' constants). All zero with `active` = 0
/// for the paper's family (the paper's kernel steps it).
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct GeneralPlan {
    /// 1 when the problem has the General kernel's terms.
    pub active: u32,
    /// How many of `rayleigh` are used.
    pub rayleigh_terms: u32,
    /// d_k: `rayleigh[0]` multiplies U̇² in h(U, U̇).
    pub rayleigh: [f64; PLAN_MAX_RAYLEIGH],
    /// k3.
    pub cubic: f64,
    /// k5.
    pub quintic: f64,
    /// κ = Σ_j K_j ϖ_r^j of the fractional terms (the engine's own sum: 0 without them).
    pub kappa: f64,
    /// 1 with a harmonic forcing F cos(Ωt + φ).
    pub forcing: u32,
    /// 1 with multiplicative noise U·η_m.
    pub multiplicative: u32,
    /// F.
    pub amplitude: f64,
    /// ΩΔt.
    pub angle: f64,
    /// φ.
    pub phase: f64,
    /// cos ΩΔt (the engine's `maths::cos`).
    pub rotation_cos: f64,
    /// sin ΩΔt.
    pub rotation_sin: f64,
    /// cos φ: the phase at the start.
    pub start_cos: f64,
    /// sin φ.
    pub start_sin: f64,
    /// c·√(D_m/D_a): η_a's part in η_m (0 uncorrelated).
    pub mix: f64,
    /// √(1 − c²): η′'s part.
    pub own: f64,
    /// η_m's stream is path `path` of `seed ^ salt`.
    pub salt: u64,
    /// η′'s step constants (white or OU, of η_m's intensity and correlation time).
    pub parametric: StepConstants,
    /// 1 with the model's walls (`stepper::walls`; the [`StepPlan`]'s `wall` is then 0).
    pub walls: u32,
    /// Whether each wall is there: index 0 the lower wall (keeping U above it), 1 the upper.
    pub wall_present: [u32; 2],
    /// 1 where the wall's restitution is speed-dependent, r(v) = r_fast + (r0 − r_fast)e^{−v/v_s}.
    pub wall_speed_dependent: [u32; 2],
    /// δ of each wall.
    pub wall_position: [f64; 2],
    /// The constant r, or r0.
    pub wall_r: [f64; 2],
    /// r_fast (speed-dependent).
    pub wall_r_fast: [f64; 2],
    /// v_s (speed-dependent).
    pub wall_speed: [f64; 2],
    /// How many fractional terms K_j·D^{α_j}U (at most [`PLAN_MAX_FRACTIONAL`]).
    pub fractional_terms: u32,
    /// 1 where term j has a memory of V (α_j < 1); 0 where it is local (α_j = 1: m_j = V).
    pub fractional_memory: [u32; PLAN_MAX_FRACTIONAL],
    /// K_j.
    pub fractional_k: [f64; PLAN_MAX_FRACTIONAL],
    /// ϖ_l^j, the scaled weight of V_n in m_{j,n+1} (0 at α_j = 1).
    pub fractional_wl: [f64; PLAN_MAX_FRACTIONAL],
    /// ϖ_r^j, that of V_{n+1} (1 at α_j = 1).
    pub fractional_wr: [f64; PLAN_MAX_FRACTIONAL],
    /// The memory of J^{1−α_j}V of term j (α_j < 1): its empty `History`'s constants, laid out
    /// as a [`StepPlan`]'s memory fields (with its λ = 1 − α_j, Δt and the φ, ψ series; the
    /// step's fields unused).
    pub memories: [StepPlan; PLAN_MAX_FRACTIONAL],
}

impl GeneralPlan {
    /// The General kernel's constants of `problem`'s paths with `method` up to `horizon`, from
    /// the engine's own `General` (as [`super::Stepper::new`] builds it); `active` = 0 for the
    /// paper's family. Refuses by name what exceeds the plan's sizes.
    pub fn new(problem: &Problem, method: &PredictorCorrector, horizon: f64) -> Result<Self> {
        let mut plan = GeneralPlan::zeroed();
        export_general(problem, method, horizon, &mut plan)?;
        Ok(plan)
    }

    pub(crate) fn zeroed() -> Self {
        GeneralPlan {
            active: 0,
            rayleigh_terms: 0,
            rayleigh: [0.0; PLAN_MAX_RAYLEIGH],
            cubic: 0.0,
            quintic: 0.0,
            kappa: 0.0,
            forcing: 0,
            multiplicative: 0,
            amplitude: 0.0,
            angle: 0.0,
            phase: 0.0,
            rotation_cos: 0.0,
            rotation_sin: 0.0,
            start_cos: 0.0,
            start_sin: 0.0,
            mix: 0.0,
            own: 0.0,
            salt: 0,
            parametric: StepConstants {
                kind: StepConstants::NONE,
                rho: 0.0,
                sigma: 0.0,
                mean_coef: 0.0,
                cross: 0.0,
                rest: 0.0,
                dt: 0.0,
                sd: 0.0,
            },
            walls: 0,
            wall_present: [0; 2],
            wall_speed_dependent: [0; 2],
            wall_position: [0.0; 2],
            wall_r: [0.0; 2],
            wall_r_fast: [0.0; 2],
            wall_speed: [0.0; 2],
            fractional_terms: 0,
            fractional_memory: [0; PLAN_MAX_FRACTIONAL],
            fractional_k: [0.0; PLAN_MAX_FRACTIONAL],
            fractional_wl: [0.0; PLAN_MAX_FRACTIONAL],
            fractional_wr: [0.0; PLAN_MAX_FRACTIONAL],
            memories: [StepPlan::zeroed(); PLAN_MAX_FRACTIONAL],
        }
    }
}
