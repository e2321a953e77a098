//! What the kernel and its emulation share on the host side: a run's constants prepared once
//! ([`Prepared`]: the step's [`StepPlan`] and [`GeneralPlan`], the recorder's [`RecordPlan`], the noise's
//! `StepConstants`, the ziggurat's tables), the raw per-path outputs in the kernel's
//! `#[repr(C)]` layouts, and their conversion into the engine's [`PathStats`], so that both
//! backends end in `trirhythm::analysis::ensemble::merge`, as the CPU engine does.
//!
//! The CPU emulation ([`emulate_paths`], [`emulate_ensemble`]) runs the kernel's own source
//! (`kernel/path.h`, compiled as C by `build.rs`) one path per call on every core; its tests
//! (`tests/emulation.rs`) compare it with the engine bit for bit.

use crate::emulate::TrNoise;
use rayon::prelude::*;
use trirhythm::analysis::ensemble::{
    merge, BatchSums, EnsembleResult, EnsembleSpec, PassageSums, PathStats, RecordPlan,
};
use trirhythm::engine::noise::NoiseStream;
use trirhythm::engine::{GeneralPlan, PredictorCorrector, Problem, StepPlan, Stepper};
use trirhythm::error::Exact;
use trirhythm::{Error, Result};

/// The kernel's `TrBatch`.
#[repr(C)]
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Batch {
    n: u64,
    u: f64,
    u2: f64,
    v: f64,
    v2: f64,
    a: f64,
}

/// The kernel's `TrPassage`.
#[repr(C)]
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Passage {
    count: u64,
    time: f64,
    time2: f64,
    censored: u64,
}

/// The kernel's `TrPathEnd`: how a path ended.
#[repr(C)]
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct PathEnd {
    status: u64,
    steps: u64,
    impacts: u64,
    sticking_steps: u64,
    u: f64,
    v: f64,
    from_u: f64,
    from_v: f64,
}

/// The kernel's status codes (`kernel/step.h`).
const TR_OK: u64 = 0;
const TR_BLOW_UP: u64 = 1;
const TR_TWO_WALLS: u64 = 3;

/// A run's constants, prepared and checked once before any work.
pub(crate) struct Prepared {
    pub(crate) plan: StepPlan,
    /// The General kernel's constants (`active` = 0 for the paper's family).
    pub(crate) general: GeneralPlan,
    pub(crate) record: RecordPlan,
    pub(crate) noise: TrNoise,
    /// Steps of a path (burn-in and window).
    pub(crate) steps: u64,
    pub(crate) seed: u64,
    /// Histogram counts of one path (four quarters of rows).
    pub(crate) counts: usize,
}

impl Prepared {
    /// Everything `run_paths` checks, in the same order where it matters (the spec, then the
    /// method and the horizon, then every start as a stepper would), then the plans; what the
    /// kernel does not hold is refused by name.
    pub(crate) fn new(
        problem: &Problem,
        method: &PredictorCorrector,
        spec: &EnsembleSpec,
    ) -> Result<Self> {
        let (record, steps) = RecordPlan::new(problem, method, spec)?;
        let horizon = steps as f64 * method.dt;
        let plan = StepPlan::new(problem, method, horizon)?;
        let general = GeneralPlan::new(problem, method, horizon)?;
        // each start as the engine's stepper checks it (the checks do not depend on the
        // horizon: a zero one keeps the memories it builds and throws away small), and the
        // noise's constants (every path's)
        for k in 0..problem.starts().len().min(spec.paths) as u64 {
            Stepper::new(problem, method, (spec.seed, k), 0.0)?;
        }
        let constants =
            NoiseStream::new(problem.oscillator().noise(), method.dt, 0, 0)?.step_constants();
        let (bins, jb) = (record.bins as usize, record.joint_bins as usize);
        Ok(Prepared {
            plan,
            general,
            record,
            noise: TrNoise::new(&constants),
            steps,
            seed: spec.seed,
            counts: 4 * (3 * (bins + 1) + jb * jb + 1),
        })
    }

    /// Wells per batch row.
    fn wells(&self) -> usize {
        self.record.wells as usize
    }

    /// μP(U) as the kernel evaluates it (for a blow-up's stiffness).
    fn damping(&self, u: f64) -> f64 {
        let x = u * u;
        let c = &self.plan.damping;
        if self.plan.damping_long == 0 {
            let (x2, x4) = (x * x, x * x * x * x);
            let p01 = c[0] + c[1] * x;
            let p23 = c[2] + c[3] * x;
            let p45 = c[4] + c[5] * x;
            let p67 = c[6] + c[7] * x;
            return (p01 + p23 * x2) + (p45 + p67 * x2) * x4;
        }
        c[..self.plan.damping_terms as usize]
            .iter()
            .rev()
            .fold(0.0, |acc, &c| acc * x + c)
    }
}

/// One path's raw outputs in the kernel's layouts.
#[derive(Debug, Clone)]
pub(crate) struct Raw {
    pub(crate) batches: Vec<Batch>,
    pub(crate) wells: Vec<u64>,
    pub(crate) passages: Vec<Passage>,
    pub(crate) counts: Vec<u64>,
    pub(crate) end: PathEnd,
}

impl Raw {
    pub(crate) fn zeroed(prep: &Prepared) -> Self {
        let (b, w) = (prep.record.batches as usize, prep.wells());
        Raw {
            batches: vec![Batch::default(); b],
            wells: vec![0; b * w],
            passages: vec![Passage::default(); w * w],
            counts: vec![0; prep.counts],
            end: PathEnd::default(),
        }
    }

    /// The engine's statistics of path `path`, or the error that stopped it (as the engine
    /// reports it: [`Error::InPath`] around [`Error::BlowUp`]).
    pub(crate) fn into_stats(
        self,
        prep: &Prepared,
        problem: &Problem,
        path: u64,
    ) -> Result<PathStats> {
        let u0 = problem.start(path).0;
        let h = prep.plan.h;
        let e = self.end;
        if e.status != TR_OK {
            let error = if e.status == TR_BLOW_UP {
                Error::BlowUp {
                    t: e.steps as f64 * h,
                    u: e.u,
                    v: e.v,
                    from_u: e.from_u,
                    from_v: e.from_v,
                    stiffness: h * prep.damping(e.from_u).abs(),
                    dt: h,
                }
            } else if e.status == TR_TWO_WALLS {
                // the engine's refusal (`stepper::walls`), at the time the step began
                Error::invalid(
                    "dt",
                    h,
                    format!(
                        "a step that meets one wall at most: at t = {} the step meets both walls \
                         (their distance is too small for this Δt)",
                        Exact(e.steps as f64 * h)
                    ),
                )
            } else {
                Error::NotApplicable {
                    method: "the GPU kernel".into(),
                    assumption: "at most one impact per step of the memory's window".into(),
                    reason: format!("path {path} had more (status {})", e.status),
                }
            };
            return Err(Error::InPath {
                path,
                u0,
                error: Box::new(error),
            });
        }
        let nw = prep.wells();
        let batches = self
            .batches
            .iter()
            .enumerate()
            .map(|(k, b)| BatchSums {
                n: b.n,
                u: b.u,
                u2: b.u2,
                v: b.v,
                v2: b.v2,
                a: b.a,
                wells: self.wells[k * nw..(k + 1) * nw].to_vec(),
            })
            .collect();
        let passages = self
            .passages
            .iter()
            .map(|p| PassageSums {
                count: p.count,
                time: p.time,
                time2: p.time2,
                censored: p.censored,
            })
            .collect();
        let (bins, jb) = (prep.record.bins as usize, prep.record.joint_bins as usize);
        let row = bins + 1;
        let stride = prep.counts / 4;
        let rows = |offset: usize, n: usize| -> Vec<Vec<u64>> {
            (0..4)
                .map(|q| self.counts[q * stride + offset..q * stride + offset + n].to_vec())
                .collect()
        };
        Ok(PathStats {
            path,
            u0,
            batches,
            amplitude: rows(0, row),
            energy: rows(row, row),
            turning: rows(2 * row, row),
            joint: rows(3 * row, jb * jb + 1),
            passages,
            impacts: e.impacts,
            sticking_steps: e.sticking_steps,
        })
    }
}

/// The first error in path order, else every path's statistics.
pub(crate) fn first_error(results: Vec<Result<PathStats>>) -> Result<Vec<PathStats>> {
    results.into_iter().collect()
}

mod ffi {
    use super::{Batch, Passage, PathEnd};
    use crate::emulate::TrNoise;
    use trirhythm::analysis::ensemble::RecordPlan;
    use trirhythm::engine::{GeneralPlan, StepPlan};

    extern "C" {
        #[allow(clippy::too_many_arguments)]
        pub(super) fn tr_emulate_path(
            plan: *const StepPlan,
            general: *const GeneralPlan,
            noise: *const TrNoise,
            record: *const RecordPlan,
            zx: *const f64,
            zf: *const f64,
            seed: u64,
            path: u64,
            u0: f64,
            v0: f64,
            steps: u64,
            batches: *mut Batch,
            wells: *mut u64,
            passages: *mut Passage,
            counts: *mut u64,
            end: *mut PathEnd,
        );
        pub(super) fn tr_layout(which: i32) -> u64;
    }
}

/// The C build's size or offset number `which` of the shared structures (`kernel/emulate_paths.c`).
pub(crate) fn c_layout(which: i32) -> u64 {
    // SAFETY: a pure function of an integer
    unsafe { ffi::tr_layout(which) }
}

/// One path in the emulation.
fn emulate_one(prep: &Prepared, problem: &Problem, path: u64) -> Result<PathStats> {
    let mut raw = Raw::zeroed(prep);
    let (u0, v0) = problem.start(path);
    let (zx, zf) = trirhythm::maths::ziggurat_tables();
    // SAFETY: every pointer is to a live buffer of the size the kernel writes: the plan's
    // batches, wells × batches, wells², and four quarters of histogram rows (`Raw::zeroed`)
    unsafe {
        ffi::tr_emulate_path(
            &prep.plan,
            &prep.general,
            &prep.noise,
            &prep.record,
            zx.as_ptr(),
            zf.as_ptr(),
            prep.seed,
            path,
            u0,
            v0,
            prep.steps,
            raw.batches.as_mut_ptr(),
            raw.wells.as_mut_ptr(),
            raw.passages.as_mut_ptr(),
            raw.counts.as_mut_ptr(),
            &mut raw.end,
        );
    }
    raw.into_stats(prep, problem, path)
}

/// The paths `paths` of the ensemble through the CPU emulation of the kernel (the kernel's
/// source compiled as C), in parallel, in the order asked: the same [`PathStats`] as
/// `trirhythm::analysis::ensemble::run_paths` for every problem the kernel holds.
pub fn emulate_paths(
    problem: &Problem,
    method: &PredictorCorrector,
    spec: &EnsembleSpec,
    paths: &[u64],
) -> Result<Vec<PathStats>> {
    let prep = Prepared::new(problem, method, spec)?;
    if let Some(&p) = paths.iter().find(|&&p| p >= spec.paths as u64) {
        return Err(Error::invalid(
            "paths",
            p as f64,
            format!("path indices in 0..{}", spec.paths),
        ));
    }
    let results: Vec<Result<PathStats>> = paths
        .par_iter()
        .map(|&p| emulate_one(&prep, problem, p))
        .collect();
    first_error(results)
}

/// The whole ensemble through the CPU emulation: [`emulate_paths`] over every path, then the
/// engine's `merge`.
pub fn emulate_ensemble(
    problem: &Problem,
    method: &PredictorCorrector,
    spec: &EnsembleSpec,
) -> Result<EnsembleResult> {
    let all: Vec<u64> = (0..spec.paths as u64).collect();
    let stats = emulate_paths(problem, method, spec, &all)?;
    merge(problem, method, spec, stats)
}
