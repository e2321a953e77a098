//! Ensembles on a GPU: the engine's step as a CUDA kernel, one thread per path (work in
//! progress; see `docs/gpu.md`).

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
    std::mem::size_of::<paths::NoiseIn>()
}
