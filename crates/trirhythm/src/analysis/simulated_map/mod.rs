//! The P-bifurcation map by Monte Carlo: at each point of a parameter plane, the number of modes
//! of the simulated stationary P(A), with its range and the ensemble's stationarity verdict,
//! beside the averaged theory's count at the same point (Figs 10 and 12 by simulation).
//!
//! # Equation
//! At every grid point (p_x, p_y) of a [`Plane`], Eq. (1) with its wall (the parameters of the
//! plane's base with the two swept) is simulated as an ensemble ([`run_ensemble`]'s statistics:
//! the density of the amplitude A = √(U² + U̇²/ω1²) with a jackknife standard error per bin, the
//! split-R̂ diagnosis). The theory's count is the number of stable roots of h = A·m1 (Eq. 26),
//! the maxima of the averaged P(A) (Eq. 27), from [`classify`] with [`What::Modes`].
//!
//! # Method
//! - **Each point's ensemble** is the spec's [`EnsembleSpec`] (paths, burn-in, window, sampling,
//!   bins, batches, lanes) with three things set per point: its seed, derived from (the map's
//!   seed, the point's row-major index) by [`point_seed`]; the paths' starts, the theory's modes
//!   of P(A) in turn (as `trirhythm ensemble` starts them: every mode the theory predicts is
//!   visited, and paths that never leave their start show as a non-stationary point, because
//!   the theory's wells are passed on and their occupancies enter R̂); the histogram's range,
//!   1.2 × the largest (mode + 6 widths) of both variants
//!   ([`crate::analysis::versus::theory_layout`]) unless [`SimulatedMapSpec::amplitude_max`]
//!   fixes it.
//! - **The runner.** The ensemble is run by a caller-given function with the signature of
//!   [`run_ensemble`] less the monitor (the command line passes one that picks the CPU or the
//!   GPU backend); the library depends on no backend.
//! - **The count** of the simulated density's modes is [`ModeRule`] ([`modes`] module): a
//!   mode dips deeper than z = 3 combined standard errors to its neighbouring modes or the
//!   ends; the range [`ModeCount::low`] … [`ModeCount::high`] is the count at z = 4 and z = 2.
//! - **The verdict** per point ([`Agreement`]), in this order: `non_stationary` when the
//!   ensemble's diagnosis is not stationary (R̂ > 1.1 or a drift beyond 3 standard errors; the
//!   count is reported, never compared); `outside_range` when more than 1 % of the samples lie
//!   beyond the histogram; `agree` when low = high = the theory's count; `disagree` when the
//!   theory's count lies outside [low, high]; `uncertain` otherwise.
//! - Points are run one after the other, each ensemble on every core: the map's bits do not
//!   depend on the thread count because an ensemble's do not.
//!
//! # Reference
//! The paper's Figs 10 and 12 (the theory's maps) and Sec. 4 (Monte Carlo of Eq. 1 against
//! Eq. 27); docs/statistics.md, "Counting the modes of a simulated density".
//!
//! # Tests
//! `tests/simulated_map.rs`: the linear oscillator (no nonlinear damping: P(A) is Rayleigh's,
//! one mode) counts 1/1/1 at every point of a 2 × 2 grid and agrees with the theory; around a
//! point of Fig. 12(d)'s set at λ = 1 where the theory has two well-separated modes and the
//! paths hop between them, 2/2/2 at every point; the same map on one thread and on two is the
//! same bits; the runner sees the derived seeds and the monitor every point, and stops the
//! run; bad input is refused by name before any work. The rule's own tests are in [`modes`].
//!
//! # Example
//! ```
//! use trirhythm::analysis::ensemble::{run_ensemble, EnsembleSpec};
//! use trirhythm::analysis::simulated_map::{simulate_map, SimulatedMapSpec};
//! use trirhythm::engine::{Memory, PredictorCorrector};
//! use trirhythm::model::preset;
//! use trirhythm::monitor::Silent;
//! use trirhythm::theory::averaging::Variant;
//! use trirhythm::theory::bifurcation::{Axis, Plane};
//!
//! let base = preset("fig12d")?.params.with("lambda", 1.0)?;
//! let plane = Plane::new(
//!     &base,
//!     Axis::new("r", 0.9, 1.0, 2)?,
//!     Axis::new("D", 0.1, 0.2, 2)?,
//!     Variant::Paper,
//! )?;
//! let spec = SimulatedMapSpec {
//!     ensemble: EnsembleSpec { paths: 2, burn_in: 1.0, length: 10.0, bins: 10, joint_bins: 2,
//!                              batches: 4, ..Default::default() },
//!     method: PredictorCorrector { dt: 0.1, memory: Memory::Direct, ..Default::default() },
//!     ..Default::default()
//! };
//! let runner = |problem: &_, method: &_, spec: &_| run_ensemble(problem, method, spec, &Silent);
//! let map = simulate_map(&plane, &spec, &runner, &Silent)?;
//! assert_eq!(map.points.len(), 4);
//! let t = map.tally();
//! assert_eq!(t.agree + t.disagree + t.uncertain + t.non_stationary + t.outside_range, 4);
//! # Ok::<(), trirhythm::Error>(())
//! ```

pub mod modes;

pub use modes::{ModeCount, ModeRule};

use crate::analysis::ensemble::{run_ensemble, Density, EnsembleResult, EnsembleSpec};
use crate::analysis::versus::theory_layout;
use crate::engine::{ImpactMemory, PredictorCorrector, Problem};
use crate::error::{Error, Result};
use crate::monitor::Monitor;
use crate::theory::averaging::Variant;
use crate::theory::bifurcation::{classify, Axis, Plane, What};
use serde::{Deserialize, Serialize};

/// Most grid points of a simulated map.
pub const MAX_MAP_POINTS: usize = 10_000;
/// Most path-steps of a simulated map (points × paths × steps per path).
pub const MAX_MAP_PATH_STEPS: f64 = 1e13;
/// Fraction of the samples beyond the histogram above which a point is `outside_range`.
pub const MAX_BEYOND: f64 = 0.01;

/// What runs one point's ensemble: [`run_ensemble`] without its monitor, on any backend.
pub type Runner<'a> =
    dyn Fn(&Problem, &PredictorCorrector, &EnsembleSpec) -> Result<EnsembleResult> + 'a;

/// How a simulated map is made: the ensemble at each point, its step, the counting rule.
#[derive(Debug, Clone, PartialEq)]
pub struct SimulatedMapSpec {
    /// Each point's ensemble: paths, burn-in, window, sampling, bins, batches, lanes. Its `seed`
    /// is the map's (each point's own is [`point_seed`] of it); its `wells` and its
    /// `amplitude_max` are set per point (module docs).
    pub ensemble: EnsembleSpec,
    /// The step Δt and the memory (default: Δt = 0.01, the memory restarted at impacts, as
    /// `trirhythm ensemble` runs Eq. 1).
    pub method: PredictorCorrector,
    /// The mode-counting rule.
    pub rule: ModeRule,
    /// A fixed histogram range of A for every point (default: the theory's per point).
    pub amplitude_max: Option<f64>,
}

impl Default for SimulatedMapSpec {
    fn default() -> Self {
        SimulatedMapSpec {
            ensemble: EnsembleSpec {
                bins: 40,
                joint_bins: 2,
                ..Default::default()
            },
            method: PredictorCorrector {
                impact_memory: ImpactMemory::Restart,
                ..Default::default()
            },
            rule: ModeRule::default(),
            amplitude_max: None,
        }
    }
}

impl SimulatedMapSpec {
    /// Check the spec against `plane` before any work: the rule, the ensemble and the method,
    /// `amplitude_max` in (0, 1e6] when given, D > 0 on the whole plane (the theory's P(A) needs
    /// noise), at most [`MAX_MAP_POINTS`] points and [`MAX_MAP_PATH_STEPS`] path-steps.
    pub fn validate(&self, plane: &Plane) -> Result<()> {
        self.rule.validate()?;
        self.ensemble.validate()?;
        self.method.validate()?;
        if let Some(a) = self.amplitude_max {
            let top = crate::analysis::ensemble::MAX_AMPLITUDE;
            if !(a > 0.0 && a <= top) {
                return Err(Error::invalid("amplitude_max", a, format!("(0, {top:e}]")));
            }
        }
        let points = plane.x.count * plane.y.count;
        if points > MAX_MAP_POINTS {
            return Err(Error::invalid(
                "points (x count × y count)",
                points as f64,
                format!("at most {MAX_MAP_POINTS} points for a simulated map"),
            ));
        }
        for px in [plane.x.start, plane.x.stop] {
            for py in [plane.y.start, plane.y.stop] {
                let d = plane.params(px, py)?.noise_intensity;
                if d <= 0.0 {
                    return Err(Error::invalid(
                        "D",
                        d,
                        "(0, ∞) on the whole plane (the stationary P(A) needs noise)",
                    ));
                }
            }
        }
        let work = self.path_steps(plane);
        if work > MAX_MAP_PATH_STEPS {
            return Err(Error::invalid(
                "paths × steps × points",
                work,
                format!("at most {MAX_MAP_PATH_STEPS:e} path-steps in all"),
            ));
        }
        Ok(())
    }

    /// The path-steps the map takes: points × paths × (burn-in + window)/Δt.
    pub fn path_steps(&self, plane: &Plane) -> f64 {
        let e = &self.ensemble;
        (plane.x.count * plane.y.count) as f64
            * e.paths as f64
            * ((e.burn_in + e.length) / self.method.dt).round()
    }
}

/// The seed of point `index`'s ensemble: splitmix64 of (seed, index), so that a point's paths
/// depend only on the map's seed and the point's place, never on the order of the work.
pub fn point_seed(seed: u64, index: usize) -> u64 {
    let mut z = seed
        .wrapping_mul(0x9E37_79B9_7F4A_7C15)
        .wrapping_add((index as u64).wrapping_mul(0xC2B2_AE3D_27D4_EB4F))
        .wrapping_add(0x4D41_5053_0000_0000); // "MAPS"
    for _ in 0..2 {
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
    }
    z
}

/// What a point's simulated count says about the theory's (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Agreement {
    /// The simulated range is the theory's count alone.
    Agree,
    /// The theory's count lies outside the simulated range.
    Disagree,
    /// The theory's count lies inside a simulated range of more than one count.
    Uncertain,
    /// The ensemble was not stationary: the count is not compared.
    NonStationary,
    /// More than [`MAX_BEYOND`] of the samples lie beyond the histogram: not compared.
    OutsideRange,
}

impl Agreement {
    /// `agree`, `disagree`, `uncertain`, `non_stationary` or `outside_range`.
    pub fn name(self) -> &'static str {
        match self {
            Agreement::Agree => "agree",
            Agreement::Disagree => "disagree",
            Agreement::Uncertain => "uncertain",
            Agreement::NonStationary => "non_stationary",
            Agreement::OutsideRange => "outside_range",
        }
    }

    /// The verdict of a point (module docs, in that order).
    pub fn of(theory: usize, simulated: &ModeCount, stationary: bool, beyond: f64) -> Self {
        if !stationary {
            Agreement::NonStationary
        } else if beyond > MAX_BEYOND {
            Agreement::OutsideRange
        } else if simulated.low == theory && simulated.high == theory {
            Agreement::Agree
        } else if theory < simulated.low || theory > simulated.high {
            Agreement::Disagree
        } else {
            Agreement::Uncertain
        }
    }
}

/// One point of a simulated map.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MapPoint {
    /// Column (x index).
    pub ix: usize,
    /// Row (y index).
    pub iy: usize,
    /// The x parameter's value.
    pub x: f64,
    /// The y parameter's value.
    pub y: f64,
    /// The seed of its ensemble ([`point_seed`]).
    pub seed: u64,
    /// The theory's count of the modes of P(A) ([`classify`], [`What::Modes`]).
    pub theory: usize,
    /// The theory's modes (amplitudes; the paths' starts).
    pub theory_modes: Vec<f64>,
    /// The simulated count with its range.
    pub simulated: ModeCount,
    /// The verdict.
    pub agreement: Agreement,
    /// The ensemble's stationarity verdict.
    pub stationary: bool,
    /// Its largest split-R̂.
    #[serde(with = "crate::non_finite")]
    pub r_hat: f64,
    /// Fraction of the samples beyond the histogram.
    pub beyond: f64,
    /// The simulated density of A with its standard errors.
    pub amplitude: Density,
}

/// How many points of a map have each verdict.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub struct Tally {
    /// `agree`.
    pub agree: usize,
    /// `disagree`.
    pub disagree: usize,
    /// `uncertain`.
    pub uncertain: usize,
    /// `non_stationary`.
    pub non_stationary: usize,
    /// `outside_range`.
    pub outside_range: usize,
}

/// A simulated P-bifurcation map beside the theory's.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SimulatedMap {
    /// Horizontal axis.
    pub x: Axis,
    /// Vertical axis.
    pub y: Axis,
    /// The theory's variant.
    pub variant: Variant,
    /// The counting rule.
    pub rule: ModeRule,
    /// The map's seed.
    pub seed: u64,
    /// The points, row-major (`points[iy * x.count + ix]`).
    pub points: Vec<MapPoint>,
    /// The verdicts counted.
    pub tally: Tally,
}

impl SimulatedMap {
    /// The point at grid indices.
    pub fn point(&self, ix: usize, iy: usize) -> &MapPoint {
        &self.points[iy * self.x.count + ix]
    }

    /// How many points have each verdict.
    pub fn tally(&self) -> Tally {
        let mut t = Tally::default();
        for p in &self.points {
            *match p.agreement {
                Agreement::Agree => &mut t.agree,
                Agreement::Disagree => &mut t.disagree,
                Agreement::Uncertain => &mut t.uncertain,
                Agreement::NonStationary => &mut t.non_stationary,
                Agreement::OutsideRange => &mut t.outside_range,
            } += 1;
        }
        t
    }
}

/// The map of `plane` by simulation (module docs): every point's ensemble through `runner`,
/// its modes counted by the spec's rule, beside the theory's count. `monitor` hears the points
/// done, receives each point as it is finished and can stop the run between points
/// ([`Error::Cancelled`]; a runner that watches the same cancellation stops within a point).
pub fn simulate_map(
    plane: &Plane,
    spec: &SimulatedMapSpec,
    runner: &Runner,
    monitor: &dyn Monitor<MapPoint>,
) -> Result<SimulatedMap> {
    spec.validate(plane)?;
    monitor.check()?;
    let theory = classify(plane, What::Modes, &|_, _| {});
    let (nx, ny) = (plane.x.count, plane.y.count);
    let total = (nx * ny) as u64;
    let mut points = Vec::with_capacity(nx * ny);
    for iy in 0..ny {
        for ix in 0..nx {
            monitor.check()?;
            let index = iy * nx + ix;
            let (x, y) = (plane.x.value(ix), plane.y.value(iy));
            let params = plane.params(x, y)?;
            let layout = theory_layout(&params, plane.variant);
            let (starts, range, wells) = match &layout {
                Some(l) => (l.starts.clone(), l.amplitude_max, l.wells.clone()),
                None => (vec![], spec.ensemble.amplitude_max, None),
            };
            let amplitude_max = spec.amplitude_max.unwrap_or(range);
            // without a theory's mode to start from, the middle of the histogram
            let starts: Vec<(f64, f64)> = if starts.is_empty() {
                vec![(0.5 * amplitude_max, 0.0)]
            } else {
                starts.iter().map(|&u| (u, 0.0)).collect()
            };
            let problem = Problem::from_params(&params)?.with_starts(&starts)?;
            let ensemble = EnsembleSpec {
                seed: point_seed(spec.ensemble.seed, index),
                amplitude_max,
                wells: wells.clone(),
                ..spec.ensemble.clone()
            };
            let result = runner(&problem, &spec.method, &ensemble)?;
            let a = &result.amplitude;
            let simulated = spec.rule.count(&a.edges, &a.density, &a.stderr)?;
            let count = theory.count(ix, iy) as usize;
            let stationary = result.stationarity.stationary;
            let point = MapPoint {
                ix,
                iy,
                x,
                y,
                seed: ensemble.seed,
                theory: count,
                theory_modes: wells.map(|w| w.modes).unwrap_or_default(),
                agreement: Agreement::of(count, &simulated, stationary, a.beyond),
                simulated,
                stationary,
                r_hat: result.stationarity.r_hat,
                beyond: a.beyond,
                amplitude: result.amplitude,
            };
            monitor.finished(&point)?;
            points.push(point);
            monitor.progress(index as u64 + 1, total);
        }
    }
    let mut map = SimulatedMap {
        x: plane.x.clone(),
        y: plane.y.clone(),
        variant: plane.variant,
        rule: spec.rule,
        seed: spec.ensemble.seed,
        points,
        tally: Tally::default(),
    };
    map.tally = map.tally();
    Ok(map)
}

/// [`simulate_map`] with the library's CPU ensembles ([`run_ensemble`], silent inside a point).
pub fn simulate_map_cpu(
    plane: &Plane,
    spec: &SimulatedMapSpec,
    monitor: &dyn Monitor<MapPoint>,
) -> Result<SimulatedMap> {
    let cancel = crate::monitor::OnlyCancel(monitor);
    let runner = |problem: &Problem, method: &PredictorCorrector, es: &EnsembleSpec| {
        run_ensemble(problem, method, es, &cancel)
    };
    simulate_map(plane, spec, &runner, monitor)
}
