//! Ensembles on a GPU: the engine's step as a CUDA kernel, one thread per path (work in
//! progress; see `docs/gpu.md`).

use trirhythm::analysis::ensemble::{
    run_ensemble as run_cpu, EnsembleResult, EnsembleSpec, PathStats,
};
use trirhythm::engine::{PredictorCorrector, Problem};
use trirhythm::monitor::Monitor;
use trirhythm::{Error, Result};

#[cfg(feature = "cuda")]
pub mod cuda;

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

/// The ensemble on the GPU: the device first, so that a machine without one gets
/// [`cuda::device`]'s refusal before any work.
#[cfg(feature = "cuda")]
fn run_gpu(
    _problem: &Problem,
    _method: &PredictorCorrector,
    _spec: &EnsembleSpec,
    _monitor: &dyn Monitor<PathStats>,
) -> Result<EnsembleResult> {
    cuda::device()?;
    Err(Error::NotApplicable {
        method: "the GPU backend".into(),
        assumption: "the ensemble kernel".into(),
        reason: "this build has the host side only; the kernel is not written yet".into(),
    })
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
