//! Ensembles of simulated paths and their stationary statistics, streamed: moments, densities,
//! well occupancies, first-passage times between wells, and a stationarity diagnosis.
//!
//! # Problem
//! N paths of one [`Problem`] (Eq. 1, Eq. 5 or Eq. 9, with or without the wall) driven by
//! noise streams 0..N of one seed, path i from the problem's start `problem.start(i)`; the first
//! `burn_in` time units are discarded, the next `length` are recorded every `sample_every`
//! steps. Nothing grows with the number of steps.
//!
//! # Running it in pieces
//! [`run_ensemble`] is [`run_paths`] over every path, then [`merge`]. The two halves are public
//! so that the paths can be run anywhere (threads, processes, a cluster) in any split and any
//! order: [`merge`] sorts the paths' [`PathStats`] by index and refuses duplicates, missing
//! paths and statistics of another run, and the result is bit-identical to one whole run. A
//! [`Monitor`] hears the steps done, receives each path's statistics as soon as they are
//! finished (to checkpoint them) and can stop the run ([`crate::Error::Cancelled`]).
//!
//! # What is recorded, and how the errors are estimated
//! - **Amplitudes.** The theory's A = √(U² + U̇²/ω1²) (Eq. 27–31 are densities of this A, with
//!   ω1 of Eq. 5) at every sample, and the **turning-point amplitude**, U at each maximum of |U|
//!   (one value per half-cycle of the Zhuravlev variable: sgn(Z)U̇ changes from + to −). For a
//!   sinusoidal cycle the two agree; for a relaxation cycle (large μ0) A is not constant along
//!   the orbit while the turning amplitude is.
//! - **Densities** of A, of the energy H = U̇²/2 + ω1²U²/2 and of (U, U̇) (joint, on a fixed
//!   grid), each normalised to the whole sample (the mass outside the grid is reported).
//! - **Units for standard errors.** Every path keeps its sums in `batches` equal batches and its
//!   histograms in four quarters. With two paths or more the units are the paths (they are
//!   independent); with one path, its batches (moments) or quarters (densities) — batch means,
//!   valid when a batch is much longer than the correlation time, which the diagnosis checks.
//!   Standard errors are jackknife over units (delete-one), for ratios and variances alike.
//! - **Wells** (given as the theory's modes and antimodes of P(A)): occupancy = fraction of
//!   samples whose A lies between consecutive antimodes (the theory's ∫P(A) over the well is its
//!   prediction). For passages a path is *in* well k from the first turning amplitude inside
//!   the core of k (closer to the mode m_k than half the distance to the neighbouring antimodes)
//!   until it reaches the core of another well: a hysteresis that ignores the fluctuation of A
//!   along one cycle. The first-passage time i → j runs from the first entry into i after the
//!   last visit to j to the next entry into j; passages still running at the end are counted
//!   as censored.
//!
//! # Stationarity, diagnosed
//! - Split-R̂ (Gelman et al., Bayesian Data Analysis, 3rd ed., §11.4): every path is cut into
//!   two half-chains of batch means; R̂ = √(((n−1)/n·W + B/n)/W) for the mean amplitude and for
//!   each well's occupancy (∞ when the chains never vary within yet differ between them).
//! - Effective sample size of the mean amplitude from batch means:
//!   ESS = s²·(units·batches)/s²_batch.
//! - Drift: the difference of the mean amplitude between the window's second and first halves
//!   in units of its standard error (paired per path).
//! - Verdict: stationary when every R̂ ≤ 1.1 and |drift| ≤ 3 standard errors. Otherwise the
//!   suggested length T·(R̂² − 1)/(1.1² − 1) (B/W of R̂ falls as 1/T for a stationary process)
//!   is reported.
//!
//! # Reproducibility
//! Path i depends only on (seed, i) and the paths' statistics are merged in path order, so the
//! result is bit-identical whatever the number of threads, the lane count
//! ([`EnsembleSpec::lanes`]: paths stepped together, each with its own bits; `tests/lanes.rs`)
//! or the split into pieces, and a run resumed from saved [`PathStats`] equals the uninterrupted
//! one.
//!
//! # Tests
//! `tests/ensemble.rs`: the linear fractional oscillator's exact stationary variances
//! ([`crate::known_answers::linear_fractional_moments`]) within three standard errors at λ = 1
//! and λ < 1, white and coloured noise; thread-count invariance; resumed = uninterrupted; the
//! diagnosis flags two paths stuck in different wells; pieces run in any split and order merge
//! to the whole run; a cancelled run stops with [`crate::Error::Cancelled`].
//!
//! # Example
//! ```
//! use trirhythm::analysis::ensemble::{merge, run_ensemble, run_paths, EnsembleSpec};
//! use trirhythm::engine::{Memory, PredictorCorrector, Problem};
//! use trirhythm::model::preset;
//! use trirhythm::monitor::Silent;
//!
//! let problem = Problem::from_params(&preset("fig1")?.params.with("D", 0.05)?)?
//!     .with_starts(&[(1.0, 0.0), (6.8, 0.0)])?; // paths take the starts in turn
//! let method = PredictorCorrector { dt: 0.05, memory: Memory::Direct, ..Default::default() };
//! let spec = EnsembleSpec {
//!     paths: 4, seed: 7, burn_in: 1.0, length: 10.0, batches: 4, bins: 20, joint_bins: 8,
//!     ..Default::default()
//! };
//! // two pieces, run anywhere, in any order, then merged
//! let mut stats = run_paths(&problem, &method, &spec, &[3, 1], &Silent)?;
//! stats.extend(run_paths(&problem, &method, &spec, &[0, 2], &Silent)?);
//! let merged = merge(&problem, &method, &spec, stats)?;
//! assert_eq!(merged, run_ensemble(&problem, &method, &spec, &Silent)?);
//! assert_eq!(merged.paths, 4);
//! # Ok::<(), trirhythm::Error>(())
//! ```

mod bounds;
mod diagnostics;
mod merging;
mod piece;
mod recording;
mod spec;
pub mod splitting;
mod wells;

pub use bounds::{
    hellinger_bounds, hellinger_of_mixture, hellinger_range, HellingerBounds, HellingerRange,
};
pub use diagnostics::Stationarity;
pub use merging::{Density, EnsembleResult, Estimate, JointDensity, Passage};
pub use piece::{fingerprint, Piece};
pub use recording::{BatchSums, PassageSums, PathStats, RecordPlan, RECORD_PLAN_WELLS};
pub use spec::{
    EnsembleSpec, Wells, MAX_AMPLITUDE, MAX_BATCHES, MAX_BINS, MAX_JOINT_BINS, MAX_PATHS,
    MAX_STATISTICS_BYTES, MAX_WELLS,
};
pub use wells::{
    run_wells, MissingWell, Rate, Replica, WellsEstimate, WellsResult, WellsSpec, MIN_EXITS,
    MIN_INSIDE,
};

use crate::engine::{
    fresh_history, group_lanes, group_steppers, run_lanes, Flow, Lanes, Observer,
    PredictorCorrector, Problem, Stepper,
};
use crate::error::{Error, Result};
use crate::monitor::{Monitor, Silent};
use rayon::prelude::*;
use recording::{Layout, Recorder};
use spec::QUARTERS;
use std::sync::atomic::{AtomicU64, Ordering};

/// Steps between two reports to the monitor (and two polls of its cancellation) on a path.
const TICK: u64 = 1 << 16;

/// Run the paths `paths` (indices in 0..`spec.paths`, each at most once, in any order) of the
/// ensemble in parallel; their statistics come back in the order asked. `monitor` hears the
/// steps done of all of them, receives each path's statistics as soon as it is finished (an
/// error from it stops the run) and may stop the run ([`Error::Cancelled`]).
pub fn run_paths(
    problem: &Problem,
    method: &PredictorCorrector,
    spec: &EnsembleSpec,
    paths: &[u64],
    monitor: &dyn Monitor<PathStats>,
) -> Result<Vec<PathStats>> {
    let sizes = spec.sizes(method)?;
    super::check_indices(paths, spec.paths)?;
    monitor.check()?;
    if paths.is_empty() {
        return Ok(vec![]);
    }
    let steps = sizes.burn + sizes.window;
    let layout = Layout::new(spec, problem, sizes.samples);
    // the verified SOE kernel is built once for all paths
    let history = fresh_history(problem, method, steps as f64 * method.dt)?;
    let total = paths.len() as u64 * steps;
    let counter = AtomicU64::new(0);
    // groups of `width` paths stepped together in lanes; with few paths, narrower groups so
    // that every thread has one (a path's bits do not depend on its group)
    let width = group_lanes(spec.lanes, paths.len(), 1)?;
    let lanes = Lanes::Width(width);
    let groups: Vec<Vec<PathStats>> = crate::profile::parallel(|stage| {
        paths
            .par_chunks(width)
            .map(|group| {
                stage.task(|| {
                    monitor.check()?;
                    let mut steppers = group_steppers(problem, method, spec.seed, group, &history)?;
                    let mut recorders: Vec<_> = group
                        .iter()
                        .map(|&i| {
                            let u0 = problem.start(i).0;
                            Recorder::new(&layout, sizes.burn, spec.sample_every, i, u0)
                        })
                        .collect();
                    let mut observers: Vec<_> = recorders
                        .iter_mut()
                        .map(|rec| {
                            let counter = &counter;
                            move |st: &Stepper| {
                                let f = rec.observe(st);
                                if st.steps() % TICK == 0 {
                                    let d = counter.fetch_add(TICK, Ordering::Relaxed) + TICK;
                                    monitor.progress(d.min(total), total);
                                    if monitor.cancelled() {
                                        return Flow::Stop;
                                    }
                                }
                                f
                            }
                        })
                        .collect();
                    let taken = run_lanes(&mut steppers, steps, &mut observers, lanes, &Silent)?;
                    drop(observers);
                    let mut out = Vec::with_capacity(group.len());
                    for (((&i, s), rec), t) in group.iter().zip(&steppers).zip(recorders).zip(taken)
                    {
                        t.map_err(|e| Error::InPath {
                            path: i,
                            u0: problem.start(i).0,
                            error: Box::new(e),
                        })?;
                        monitor.check()?;
                        let stats = rec.finish(s);
                        monitor.finished(&stats)?;
                        out.push(stats);
                    }
                    Ok(out)
                })
            })
            .collect::<Result<_>>()
    })?;
    Ok(groups.into_iter().flatten().collect())
}

/// Merge the statistics of every path 0..`spec.paths` of the ensemble (from [`run_paths`], in
/// any split and order) into its result, bit-identical to one whole run. Refuses a path given
/// twice, a missing path, and statistics of another run (an index out of range, other sizes
/// of histograms, batches or wells, another start).
pub fn merge(
    problem: &Problem,
    method: &PredictorCorrector,
    spec: &EnsembleSpec,
    mut stats: Vec<PathStats>,
) -> Result<EnsembleResult> {
    let sizes = spec.sizes(method)?;
    let layout = Layout::new(spec, problem, sizes.samples);
    stats.sort_by_key(|p| p.path);
    if let Some(p) = stats.iter().find(|p| p.path >= spec.paths as u64) {
        return Err(Error::invalid(
            "paths",
            p.path as f64,
            format!(
                "path indices in 0..{} (statistics of another run)",
                spec.paths
            ),
        ));
    }
    for w in stats.windows(2) {
        if w[0].path == w[1].path {
            return Err(Error::invalid(
                "paths",
                w[0].path as f64,
                "each path once (this one is given twice)",
            ));
        }
    }
    for (k, p) in stats.iter().enumerate() {
        if p.path != k as u64 {
            return Err(Error::invalid(
                "paths",
                k as f64,
                format!("all {} paths (this one is missing)", spec.paths),
            ));
        }
        if !fits(p, spec, problem) {
            return Err(Error::invalid(
                "paths",
                p.path as f64,
                "statistics with this spec's bins, batches and wells and this problem's \
                 start (these belong to another run)",
            ));
        }
    }
    if stats.len() != spec.paths {
        return Err(Error::invalid(
            "paths",
            stats.len() as f64,
            format!("all {} paths (the last ones are missing)", spec.paths),
        ));
    }
    let omega1 = problem.oscillator().equivalents().omega1;
    Ok(merging::assemble(spec, &layout, &sizes, omega1, &stats))
}

/// Whether `p` has the shape of this spec's statistics and this problem's start: what
/// [`merge`] checks of every piece, for a caller that reads pieces back (a checkpoint) and
/// wants to refuse a foreign one by its name before any work.
pub fn fits(p: &PathStats, spec: &EnsembleSpec, problem: &Problem) -> bool {
    let nw = spec.wells.as_ref().map_or(0, Wells::len);
    let quarters =
        |q: &Vec<Vec<u64>>, n: usize| q.len() == QUARTERS && q.iter().all(|h| h.len() == n + 1);
    p.u0.to_bits() == problem.start(p.path).0.to_bits()
        && p.batches.len() == spec.batches
        && p.batches.iter().all(|b| b.wells.len() == nw)
        && quarters(&p.amplitude, spec.bins)
        && quarters(&p.energy, spec.bins)
        && quarters(&p.turning, spec.bins)
        && quarters(&p.joint, spec.joint_bins * spec.joint_bins)
        && p.passages.len() == nw * nw
}

/// Run the ensemble: [`run_paths`] over every path, then [`merge`].
pub fn run_ensemble(
    problem: &Problem,
    method: &PredictorCorrector,
    spec: &EnsembleSpec,
    monitor: &dyn Monitor<PathStats>,
) -> Result<EnsembleResult> {
    // the spec first: its paths are counted out below
    spec.sizes(method)?;
    let all: Vec<u64> = (0..spec.paths as u64).collect();
    let stats = run_paths(problem, method, spec, &all, monitor)?;
    merge(problem, method, spec, stats)
}
