//! The problem and the method of a simulation: which equation ([`Oscillator`], [`System`],
//! [`Barrier`]), how it is discretised ([`PredictorCorrector`], [`Memory`], [`ImpactMemory`]) and
//! what is simulated ([`Options`]). Results are in [`super::drivers`].

use super::memory::{Memory, DEFAULT_WINDOW};
use super::noise::Noise;
use crate::error::Result;
use crate::model::{Equivalents, Params};

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
