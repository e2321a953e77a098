//! The simulation of Eq. (1) and its integer-order companions (Eq. 5, Eq. 9): memory kernels,
//! noise, the stepper with its impacts, and the drivers.
//!
//! Layers, each depending only on those before it:
//! - [`kernel`]: product-integration weights and the verified sum-of-exponentials kernel;
//! - `memory`: the whole history of J^λ g of one path (exact window, SOE modes, lumped terms),
//!   with [`Memory`] choosing how it is kept, and [`solve_scalar`] for scalar Caputo problems;
//! - [`noise`]: Ornstein–Uhlenbeck and white forcing with seeded per-path streams;
//! - the [`Problem`] every driver takes (oscillator, system, wall, starts, blow-up bound) and
//!   the method [`PredictorCorrector`];
//! - [`Stepper`]: the linearly implicit predictor–corrector step with impacts (module docs of
//!   `stepper` give the method and why), with two kernels: the paper's (Eq. 1/5/9, the wall)
//!   and the General one (Duffing, Rayleigh, harmonic forcing; no wall or the wall at 0);
//! - [`Lanes`]: several paths of one problem stepped together, the arithmetic of their step
//!   vectorised across them, with the scalar stepper's bits (module docs of `stepper::lanes`);
//! - drivers: [`run`] with an [`Observer`], [`run_lanes`] for several paths at once, [`simulate`], [`simulate_ensemble`]; a
//!   [`crate::monitor::Monitor`] hears their progress and can stop them.
//!
//! The engine depends on [`crate::model`] (parameters, Eq. 5 equivalents), [`crate::special`]
//! and [`crate::monitor`] only, never on the averaged theory.

mod drivers;
pub mod kernel;
mod memory;
pub mod noise;
mod plan;
mod problem;
pub mod resolution;
mod stepper;

pub(crate) use drivers::{group_steppers, whole_steps};
pub use drivers::{
    run, run_lanes, simulate, simulate_ensemble, simulate_with, Flow, Observer, Trajectory,
    TrajectoryRecorder, MAX_KEPT_SAMPLES, MAX_PATHS, MAX_STEPS,
};
pub(crate) use memory::History;
pub use memory::{
    probe_memory, solve_scalar, step_tolerance, Memory, AUTO_TOLERANCE_MAX, AUTO_TOLERANCE_MIN,
    AUTO_TOLERANCE_PER_DT2, DEFAULT_WINDOW, MAX_TOLERANCE, MIN_TOLERANCE,
    PREVIOUS_DEFAULT_TOLERANCE,
};
pub use plan::{
    GeneralPlan, StepPlan, PLAN_MAX_CAP, PLAN_MAX_DAMPING, PLAN_MAX_FRACTIONAL, PLAN_MAX_MODES,
    PLAN_MAX_RAYLEIGH,
};
pub use problem::{
    Barrier, ImpactMemory, Options, Oscillator, PredictorCorrector, Problem, System,
    MAX_AMPLITUDE_PERIODS, MAX_DT, MAX_STARTS, MAX_WINDOW,
};
pub use resolution::Resolution;
pub use stepper::{
    detected_lanes, Impact, Lanes, StepEvents, Stepper, LANE_WIDTHS, MAX_DIRECT_STEPS,
};
pub(crate) use stepper::{fresh_history, group_lanes, Group, Tangent};
