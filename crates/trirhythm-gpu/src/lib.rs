//! Ensembles on a GPU: the engine's step and ensemble recorder as a CUDA kernel, one thread per
//! path, over the whole model class the engine steps.
//!
//! # Problem
//! The ensembles of `trirhythm::analysis::ensemble` (the direct method: N paths of one
//! [`Problem`] from (seed, path) noise streams, their statistics merged), with the paths
//! stepped on a GPU ([`Backend::Gpu`]) instead of the CPU ([`Backend::Cpu`], the default and
//! the reference).
//!
//! # Method
//! The kernel's source (`kernel/`) is the engine's step written out in a C99 subset, the same
//! expressions in the same order, with the constants the engine itself builds
//! (`trirhythm::engine::{StepPlan, GeneralPlan}`, `RecordPlan`, the noise's step constants). It
//! is compiled twice: by NVRTC for the GPU ([`cuda`], `gpu`: [`gpu_paths`]), and by the host's C
//! compiler for the CPU emulation ([`emulate_paths`], [`emulate_ensemble`]). Each path's
//! statistics come back as the engine's `PathStats` and are merged by the engine's `merge`.
//! Method, scope and which equality holds: `docs/gpu.md`.
//!
//! # Reference
//! The engine's predictor–corrector (module docs of `trirhythm::engine`); the CUDA driver API
//! and NVRTC (NVIDIA, CUDA 12).
//!
//! # Tests
//! `tests/emulation.rs` (the emulation against the engine, bit for bit, every kind of path),
//! `tests/noise.rs` (the noise's words, deviates and steps, bit for bit), `tests/ptx.rs` (the
//! kernel compiled to PTX without contraction), `tests/gpu.rs` (on a device: statistical
//! equality with the CPU, reproducibility; skipped with the reason elsewhere).

pub mod emulate;
mod paths;

pub use paths::{emulate_ensemble, emulate_paths};

use trirhythm::analysis::ensemble::{
    run_ensemble as run_cpu, EnsembleResult, EnsembleSpec, PathStats,
};
use trirhythm::engine::{PredictorCorrector, Problem};
use trirhythm::monitor::Monitor;
use trirhythm::{Error, Result};

#[cfg(feature = "cuda")]
pub mod cuda;
#[cfg(feature = "cuda")]
mod gpu;
#[cfg(feature = "cuda")]
pub use gpu::{gpu_paths, GpuPaths};

/// Where an ensemble's paths are stepped.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Backend {
    /// The CPU engine on every core (the reference).
    #[default]
    Cpu,
    /// The CUDA kernel on the first GPU.
    Gpu,
}

impl std::str::FromStr for Backend {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self> {
        match s {
            "cpu" => Ok(Backend::Cpu),
            "gpu" => Ok(Backend::Gpu),
            _ => Err(Error::Unknown {
                kind: "backend",
                name: s.into(),
                expected: "cpu, gpu".into(),
            }),
        }
    }
}

/// The ensemble of `spec` on `backend`: [`Backend::Cpu`] is
/// `trirhythm::analysis::ensemble::run_ensemble`; [`Backend::Gpu`] steps the paths on the GPU.
pub fn run_ensemble(
    problem: &Problem,
    method: &PredictorCorrector,
    spec: &EnsembleSpec,
    monitor: &dyn Monitor<PathStats>,
    backend: Backend,
) -> Result<EnsembleResult> {
    match backend {
        Backend::Cpu => run_cpu(problem, method, spec, monitor),
        Backend::Gpu => run_gpu(problem, method, spec, monitor),
    }
}

/// The ensemble on the GPU: every path's statistics from the kernel ([`gpu_paths`]), merged by
/// the engine's `merge`.
#[cfg(feature = "cuda")]
fn run_gpu(
    problem: &Problem,
    method: &PredictorCorrector,
    spec: &EnsembleSpec,
    monitor: &dyn Monitor<PathStats>,
) -> Result<EnsembleResult> {
    let run = gpu_paths(problem, method, spec, monitor)?;
    trirhythm::analysis::ensemble::merge(problem, method, spec, run.stats)
}

/// Without the `cuda` feature: the refusal.
#[cfg(not(feature = "cuda"))]
fn run_gpu(
    _problem: &Problem,
    _method: &PredictorCorrector,
    _spec: &EnsembleSpec,
    _monitor: &dyn Monitor<PathStats>,
) -> Result<EnsembleResult> {
    Err(Error::NotApplicable {
        method: "the GPU backend".into(),
        assumption: "a build with CUDA support".into(),
        reason:
            "this build of trirhythm has none (the cargo feature `cuda` of trirhythm-gpu is off)"
                .into(),
    })
}

/// The C build's size or offset number `which` of the structures shared with the kernel
/// (`kernel/emulate_paths.c`: 0 the plan's size, …), for the layout tests.
#[doc(hidden)]
pub fn layout_of_c(which: i32) -> u64 {
    paths::c_layout(which)
}

/// The size of the kernel's noise structure on the Rust side, for the layout tests.
#[doc(hidden)]
pub fn noise_layout() -> usize {
    std::mem::size_of::<emulate::TrNoise>()
}
