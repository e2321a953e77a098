//! The figures of "Managing trirhythmicity and bifurcation in the fractional biological
//! vibro-impact system under correlated noise" as data.
//!
//! Each figure is one module (`figNN_what`) with its data type (`FigNN`: the numbers, the
//! parameters used and the scientific notes — choices where the paper is silent, methods,
//! verdicts — serialisable with serde) and its computation, [`Figure::compute`]. Nothing here
//! draws, prints or writes a file: the `trirhythm figure N` command renders these values to
//! CSV, PNG and SVG, and a report or a binding can use them as they are.
//!
//! - [`FigureOptions`]: quick (coarse, for CI) or paper quality, and the formula variant of
//!   the averaged theory.
//! - [`Figure`]: number, title and `compute(options, monitor)` of a figure's data type.
//! - [`registry`] / [`compute_json`]: the 19 figures by number, computed to a JSON value.
//! - Every computation takes a [`Monitor`]: it reports progress per panel or point where the
//!   work is long, and stops with [`Error::Cancelled`] when the
//!   monitor asks (polled between panels and points).
//!
//! Shared machinery: [`montecarlo`] (ensembles against the theory, Figs 11, 13, 14), [`lle`]
//! (the largest Lyapunov exponent against the noise, Figs 17, 18), [`maps`] (classified
//! parameter planes with fold curves, Figs 2, 3, 6, 10, 12), [`boundary`] (oscillation
//! boundaries, Figs 15, 16), [`notes`] (captions and number formats) and [`table`] (a
//! figure's data as rows, what its CSV files hold).
//!
//! Beyond the figures: [`verdict`] (the paper's claims decided from the figures' data by stated
//! rules), [`views`] (the library's results as sentences and tables, what the command line
//! prints and writes) and [`critical`] (the critical noise by regime with the figures' rules,
//! what `trirhythm critical-noise` and the Python `critical_noise` compute).
//!
//! # Example
//! ```
//! use trirhythm::monitor::Silent;
//! use trirhythm::theory::averaging::Variant;
//! use trirhythm_paper::fig07_pseudo_potential::Fig07;
//! use trirhythm_paper::{Figure, FigureOptions};
//!
//! let options = FigureOptions { quick: true, variant: Variant::Paper };
//! let fig = Fig07::compute(&options, &Silent)?;
//! // panel (a), r = 1: the pseudo-potential has three wells (trirhythmicity), the stable
//! // cycles A01 < A03 < A05 of the averaged theory
//! let wells: Vec<f64> = fig.panels[0].curves[0]
//!     .extrema
//!     .iter()
//!     .filter(|e| e.minimum && e.amplitude > 0.0)
//!     .map(|e| e.amplitude)
//!     .collect();
//! assert_eq!(wells.len(), 3);
//! assert!(wells.windows(2).all(|w| w[0] < w[1]));
//! # Ok::<(), trirhythm::Error>(())
//! ```

pub mod boundary;
pub mod critical;
pub mod lle;
pub mod maps;
pub mod montecarlo;
pub mod notes;
pub mod requests;
pub mod table;
pub mod validate;
pub mod verdict;
pub mod views;

pub mod fig01_phase_recurrence;
pub mod fig02_rhythmicity_planes;
pub mod fig03_restitution_planes;
pub mod fig04_drift;
pub mod fig05_branches;
pub mod fig06_fractional_planes;
pub mod fig07_pseudo_potential;
pub mod fig08_barriers;
pub mod fig09_barrier_surfaces;
pub mod fig10_pbif_lambda_tau;
pub mod fig11_amplitude_lambda;
pub mod fig12_pbif_maps;
pub mod fig13_pdf_restitution;
pub mod fig14_joint_pdf;
pub mod fig15_oscillation_boundaries;
pub mod fig16_oscillation_regions;
pub mod fig17_lle_noise;
pub mod fig18_lle_noise_fractional;
pub mod fig19_critical_noise;

use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};
pub use trirhythm::monitor::Monitor;
use trirhythm::theory::averaging::Variant;
use trirhythm::{Error, Result};

/// How a figure is computed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct FigureOptions {
    /// Coarser grids, fewer and shorter paths (seconds per figure, for CI); `false` is paper
    /// quality.
    pub quick: bool,
    /// Formula variant of the averaged theory.
    pub variant: Variant,
}

impl Default for FigureOptions {
    fn default() -> Self {
        FigureOptions {
            quick: false,
            variant: Variant::Paper,
        }
    }
}

/// A paper figure's data: computed once, serialisable, rendered elsewhere.
pub trait Figure: Serialize + DeserializeOwned + Sized {
    /// The paper's figure number.
    const NUMBER: u32;
    /// What the figure shows, in one line.
    const TITLE: &'static str;
    /// All the numerical work. Reports progress to `monitor` and stops with
    /// [`Error::Cancelled`] when it asks.
    fn compute(options: &FigureOptions, monitor: &dyn Monitor) -> Result<Self>;
    /// The data as tables (what `figNN.csv` and its siblings hold), in file order.
    fn tables(&self) -> Vec<table::Table>;
    /// Check the data as a whole before anything is drawn from it (read back from a file, it
    /// may be damaged or edited): array lengths against their grids and edges, ranges finite
    /// and ordered, indices in range. The first inconsistent field is named
    /// ([`validate::Invalid`]). Computed data passes. Figures whose data has no shape to
    /// check keep the default, which accepts.
    fn validate(&self) -> validate::Valid {
        Ok(())
    }
}

/// One figure of the [`registry`].
#[derive(Clone, Copy)]
pub struct Entry {
    /// The paper's figure number.
    pub number: u32,
    /// What it shows.
    pub title: &'static str,
    /// Compute the figure's data as a JSON value (the serde form of its data type).
    pub compute_json: fn(&FigureOptions, &dyn Monitor) -> Result<serde_json::Value>,
}

fn entry<F: Figure>() -> Entry {
    Entry {
        number: F::NUMBER,
        title: F::TITLE,
        compute_json: |options, monitor| to_json(&F::compute(options, monitor)?),
    }
}

/// A figure's data as a JSON value.
pub fn to_json<F: Serialize>(data: &F) -> Result<serde_json::Value> {
    serde_json::to_value(data).map_err(|e| Error::Undefined {
        what: "the figure's data as JSON",
        why: e.to_string(),
    })
}

/// The 19 figures, by number.
pub fn registry() -> Vec<Entry> {
    vec![
        entry::<fig01_phase_recurrence::Fig01>(),
        entry::<fig02_rhythmicity_planes::Fig02>(),
        entry::<fig03_restitution_planes::Fig03>(),
        entry::<fig04_drift::Fig04>(),
        entry::<fig05_branches::Fig05>(),
        entry::<fig06_fractional_planes::Fig06>(),
        entry::<fig07_pseudo_potential::Fig07>(),
        entry::<fig08_barriers::Fig08>(),
        entry::<fig09_barrier_surfaces::Fig09>(),
        entry::<fig10_pbif_lambda_tau::Fig10>(),
        entry::<fig11_amplitude_lambda::Fig11>(),
        entry::<fig12_pbif_maps::Fig12>(),
        entry::<fig13_pdf_restitution::Fig13>(),
        entry::<fig14_joint_pdf::Fig14>(),
        entry::<fig15_oscillation_boundaries::Fig15>(),
        entry::<fig16_oscillation_regions::Fig16>(),
        entry::<fig17_lle_noise::Fig17>(),
        entry::<fig18_lle_noise_fractional::Fig18>(),
        entry::<fig19_critical_noise::Fig19>(),
    ]
}

/// Compute figure `number`'s data as a JSON value; [`Error::Unknown`] for a number that is
/// not a figure of the paper.
pub fn compute_json(
    number: u32,
    options: &FigureOptions,
    monitor: &dyn Monitor,
) -> Result<serde_json::Value> {
    match registry().into_iter().find(|e| e.number == number) {
        Some(e) => (e.compute_json)(options, monitor),
        None => Err(Error::Unknown {
            kind: "figure",
            name: number.to_string(),
            expected: "1 to 19".into(),
        }),
    }
}

/// Report `done` of `total` to `monitor`, then stop if it asks: the step between two panels
/// or points of a figure.
pub(crate) fn step(monitor: &dyn Monitor, done: usize, total: usize) -> Result<()> {
    monitor.progress(done as u64, total as u64);
    monitor.check()
}

/// The points or panels of a figure done so far, shared by the tasks that run them side by
/// side: each finished one is reported to the monitor, which may stop the run.
pub struct Progress {
    done: std::sync::atomic::AtomicUsize,
    total: usize,
}

impl Progress {
    /// `first` of `total` done.
    pub fn new(first: usize, total: usize) -> Progress {
        Progress {
            done: first.into(),
            total,
        }
    }

    /// `n` more done (skipped or finished): reported to `monitor`, then stop if it asks.
    pub fn advance(&self, monitor: &dyn Monitor, n: usize) -> Result<()> {
        let done = self.done.fetch_add(n, std::sync::atomic::Ordering::Relaxed) + n;
        step(monitor, done.min(self.total), self.total)
    }
}

/// `f` of each of `items`, as independent tasks of one stage of the pool (rayon, profiled by
/// [`trirhythm::profile`]), in the order of `items` whatever the threads.
pub(crate) fn each<'a, T: Sync, R: Send>(
    items: &'a [T],
    f: impl Fn(&'a T) -> Result<R> + Sync,
) -> Result<Vec<R>> {
    use rayon::prelude::*;
    trirhythm::profile::parallel(|stage| {
        items
            .par_iter()
            .map(|x| stage.task(|| f(x)))
            .collect::<Result<Vec<R>>>()
    })
}
