//! The stationary statistics of a metastable ensemble by well decomposition: the conditional
//! (quasi-stationary) statistics inside each well, the well-to-well rates by rare-event
//! splitting, the stationary weights from the rates, and the stationary result as their
//! mixture — where direct paths never hop between the wells within any affordable window.
//!
//! # Problem
//! With wells of the amplitude (the theory's modes and antimodes) whose escape times exceed
//! the window by decades, a direct ensemble reports each path's own well and the stationarity
//! diagnosis refuses it. The stationary density is still determined: P = Σ_i π_i P_i, with P_i
//! the density of the samples whose last visited core is well i's, and π_i the stationary
//! fraction of time with that label.
//!
//! # Method
//! - **Labels.** A path's label is the last well core its turning amplitude visited
//!   ([`Wells::core`]), the hysteresis of the direct ensemble's first passages. Every sample
//!   has exactly one label, so P = Σ π_i P_i holds exactly.
//! - **Conditional statistics P_i.** For each of `spec.paths` independent replicas, one path
//!   per well starts at the well's mode (U = m_i, U̇ = 0), discards `burn_in`, and records
//!   `length` time units in label i with the direct ensemble's recorder (moments, densities of
//!   A, turning amplitude, energy and (U, U̇), occupancies). A path that reaches another core
//!   is restarted from its latest re-entry into core i (killed and restarted; rare when the
//!   decomposition is valid, and counted).
//! - **Rates** k_{i,i±1} = Φ p (module `splitting`): the flux Φ of exits from the core toward
//!   the neighbour counted on the same path, the probability p that an exit reaches the
//!   neighbour's core first by adaptive multilevel splitting with `clones` replicas; each
//!   branch is a clone of the whole [`Stepper`] — U, U̇, the fractional memory (exact window
//!   and sum-of-exponentials modes), the coloured noise's present value — with a fresh noise
//!   stream ([`Stepper::renoise`]).
//! - **Weights.** The net flux across every gap between neighbouring wells vanishes in the
//!   stationary state: π_i k_{i,i+1} = π_{i+1} k_{i+1,i} (exact for the labels, not a Markov
//!   approximation); π normalised.
//! - **Errors.** The replicas are independent: every result (rates, weights, each bin of each
//!   density, moments, occupancies) is a function of the replicas' sums and gets its
//!   delete-one jackknife standard error over the replicas. The per-unit amplitude histograms
//!   handed to the theory comparison are each replica's own mixture (Σ_i π_i^ρ P_i^ρ).
//! - **Validity.** The decomposition is refused (`valid` false, with the reasons) when a rate
//!   between neighbours is zero and, set to its bound (the flux times the estimated probability
//!   of passing the farthest level the splitting reached), would move a weight by more than
//!   [`MAX_WEIGHT_SHIFT`], or the weights are undetermined, or an AMS is unfinished, when a well's path saw fewer than
//!   [`MIN_EXITS`] exits toward a neighbour, when a well's conditional statistics are not
//!   stationary by the direct diagnosis (R̂ over the replicas, drift), or when the mean
//!   residence time 1/Σ_j k_ij of a well is not at least `separation` times its relaxation
//!   time (sampled time over the effective sample size of A): the rates must be slow against
//!   the relaxation inside the wells for P_i to be the quasi-stationary density.
//!
//! # Cost
//! The paths cost replicas × wells × (burn-in + length); an AMS needs about
//! N(1 + ln(1/p)) excursions, each a few periods long, so the cost grows like the logarithm
//! of the escape time, where a direct simulation needs ≈ 1/k time units per transition.
//!
//! # Tests
//! `tests/wells.rs`: the averaged amplitude diffusion's rates against the exact mean
//! first-passage times (six decades and more, known answer); a mixing panel where the direct
//! ensemble is stationary: the two estimators agree in the weights and the density (extended);
//! reproducibility; refusals (no wells, one replica).

use super::merging::{assemble, jackknife, Density, EnsembleResult, Estimate, JointDensity};
use super::recording::{Layout, PathStats, Recorder};
use super::spec::{EnsembleSpec, Wells, QUARTERS};
use super::splitting::{
    ams, chain_weights, neighbours, stream, well_path, Cores, Splitting, Transition, Walker,
    WellPath,
};
use super::Stationarity;
use crate::engine::{fresh_history, PredictorCorrector, Problem, Stepper, System};
use crate::error::{Error, Result};
use crate::monitor::Monitor;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::sync::atomic::{AtomicU64, Ordering};

/// Fewest exits toward a neighbour per replica on average for a valid decomposition.
pub const MIN_EXITS: f64 = 10.0;

/// Largest change of a weight that a rate below resolution, set to its bound, may cause for a
/// valid decomposition.
pub const MAX_WEIGHT_SHIFT: f64 = 0.01;

/// The well method's own sizes (the rest is the [`EnsembleSpec`]: `paths` are the replicas,
/// `burn_in` and `length` each well's path, the histograms and wells as for a direct ensemble).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct WellsSpec {
    /// AMS replicas per transition.
    pub clones: usize,
    /// Longest excursion in time units (counted as a failure beyond).
    pub max_excursion: f64,
    /// Most AMS iterations per transition.
    pub max_iterations: usize,
    /// Residence time needed, in units of a well's relaxation time.
    pub separation: f64,
    /// The cores are the [q, 1 − q] quantiles of a pilot path's turning amplitudes in each
    /// well (within [`Wells::core`]): q = `core_quantile`.
    pub core_quantile: f64,
}

impl Default for WellsSpec {
    fn default() -> Self {
        WellsSpec {
            clones: 100,
            max_excursion: 10_000.0,
            max_iterations: 200_000,
            separation: 10.0,
            core_quantile: 0.1,
        }
    }
}

/// A rate between neighbouring wells over the replicas.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Rate {
    /// Well left.
    pub from: usize,
    /// Well reached.
    pub to: usize,
    /// k = Φ·p per unit time.
    pub rate: Estimate,
    /// Exits from the core toward `to` per unit time.
    pub flux: Estimate,
    /// Probability that an exit reaches the core of `to` first.
    pub probability: Estimate,
}

/// One replica's rates and weights.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Replica {
    /// Replica number (its noise streams).
    pub replica: u64,
    /// Its weights (empty when a rate is zero).
    pub weights: Vec<f64>,
    /// Its transitions (0 → 1, 1 → 0, 1 → 2, …).
    pub transitions: Vec<Transition>,
    /// Its wells' paths.
    pub paths: Vec<WellPath>,
}

/// What the well method adds to an ensemble's result.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct WellsEstimate {
    /// The method's sizes.
    pub spec: WellsSpec,
    /// The wells' cores used for the labels (from the pilot paths).
    pub cores: Cores,
    /// The fraction of each pilot path's turning amplitudes inside [`Wells::core`].
    pub pilot_inside: Vec<f64>,
    /// Rates between neighbours (0 → 1, 1 → 0, 1 → 2, …).
    pub rates: Vec<Rate>,
    /// The rate matrix, `rate_matrix[i][j]` = k_ij (0 on the diagonal and between non-neighbours).
    pub rate_matrix: Vec<Vec<f64>>,
    /// Stationary weights of the labels.
    pub weights: Vec<Estimate>,
    /// Mean residence time per well, 1/Σ_j k_ij.
    pub residence: Vec<f64>,
    /// Relaxation time per well: sampled time over the effective sample size of A.
    pub relaxation: Vec<f64>,
    /// The amplitude density conditioned on each label.
    pub conditional: Vec<Density>,
    /// The decomposition passed its validity diagnostic.
    pub valid: bool,
    /// Why not, in words (empty when valid).
    pub refusals: Vec<String>,
    /// Rates below the method's resolution (taken as 0), in words.
    pub notes: Vec<String>,
    /// Per replica.
    pub replicas: Vec<Replica>,
    /// Steps computed in all (paths, excursions, replays).
    pub steps: u64,
}

/// The ensemble's result by well decomposition: the mixture in the direct result's form, and
/// what the method adds.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct WellsResult {
    /// The stationary mixture (its `stationarity.stationary` is the decomposition's validity).
    pub result: EnsembleResult,
    /// Rates, weights, replicas, diagnostic.
    pub wells: WellsEstimate,
}

/// The oscillator as a [`Walker`]: its turning amplitudes |U| at the maxima of |U|.
#[derive(Clone)]
struct Oscillator {
    s: Stepper,
    rising: bool,
    crossing: bool,
}

impl Walker for Oscillator {
    #[inline]
    fn advance(&mut self) -> Result<Option<f64>> {
        self.s.step()?;
        let side = if self.crossing {
            self.s.u().signum()
        } else {
            1.0
        };
        let rising = side * self.s.v() > 0.0;
        let turning = self.rising && !rising;
        self.rising = rising;
        Ok(turning.then(|| self.s.u().abs()))
    }

    fn renoise(&mut self, seed: u64, stream: u64) {
        self.s.renoise(seed, stream);
    }
}

/// One replica's well paths: statistics and exits.
type WellRun = (PathStats, WellPath, super::splitting::Exits<Oscillator>);

/// The ensemble of `problem` by well decomposition (module docs). `spec.wells` must be given
/// and `spec.paths` (the replicas) be at least 2.
pub fn run_wells(
    problem: &Problem,
    method: &PredictorCorrector,
    spec: &EnsembleSpec,
    wspec: &WellsSpec,
    monitor: &dyn Monitor<()>,
) -> Result<WellsResult> {
    let sizes = spec.sizes(method)?;
    let Some(wells) = spec.wells.clone() else {
        return Err(Error::Undefined {
            what: "the well method",
            why: "no wells: the theory has no modes and antimodes of P(A) here".into(),
        });
    };
    if spec.paths < 2 {
        return Err(Error::invalid(
            "paths",
            spec.paths as f64,
            "2 or more replicas for the well method's standard errors",
        ));
    }
    if !(wspec.max_excursion > 0.0 && wspec.max_excursion.is_finite()) {
        return Err(Error::invalid(
            "max_excursion",
            wspec.max_excursion,
            "(0, ∞), finite",
        ));
    }
    if !(wspec.core_quantile >= 0.0 && wspec.core_quantile < 0.5) {
        return Err(Error::invalid(
            "core_quantile",
            wspec.core_quantile,
            "[0, 0.5)",
        ));
    }
    if !(wspec.separation >= 0.0 && wspec.separation.is_finite()) {
        return Err(Error::invalid(
            "separation",
            wspec.separation,
            "[0, ∞), finite",
        ));
    }
    let dt = method.dt;
    let sp = Splitting {
        seed: spec.seed,
        dt,
        clones: wspec.clones,
        burn: sizes.burn,
        window: sizes.window,
        max_excursion: (wspec.max_excursion / dt).ceil().max(1.0) as u64,
        max_iterations: wspec.max_iterations,
    };
    sp.validate()?;
    monitor.check()?;
    let nw = wells.len();
    let replicas = spec.paths;
    let layout = Layout::new(spec, problem, sizes.samples);
    let history = fresh_history(problem, method, (sizes.burn + sizes.window) as f64 * dt)?;
    let crossing = problem.system() == System::Zhuravlev;
    let oscillator = |i: usize, path: u64| -> Result<Oscillator> {
        let start = (wells.modes[i], 0.0);
        let s = Stepper::with_history(problem, method, start, (spec.seed, path), history.clone())?;
        Ok(Oscillator {
            s,
            rising: false,
            crossing,
        })
    };
    // 0. a pilot path per well: its turning amplitudes set the core
    let pilot_steps = sizes.burn + (sizes.window / 4).max(1);
    let pilots: Vec<(f64, (f64, f64))> = (0..nw)
        .into_par_iter()
        .map(|i| {
            let mut w = oscillator(i, 0)?;
            w.renoise(spec.seed, stream(u64::MAX, i, 3, 0));
            let mut seen = Vec::new();
            for n in 0..pilot_steps {
                if let Some(a) = w.advance()? {
                    if n >= sizes.burn {
                        seen.push(a);
                    }
                }
                if n % (1 << 16) == 0 {
                    monitor.check()?;
                }
            }
            let (lo, hi) = wells.core(i);
            let inside = seen.iter().filter(|&&a| a >= lo && a <= hi).count() as f64
                / seen.len().max(1) as f64;
            seen.sort_by(f64::total_cmp);
            let q =
                |f: f64| seen[((f * (seen.len() - 1) as f64).round() as usize).min(seen.len() - 1)];
            let core = if seen.len() >= 10 && inside >= 0.5 {
                (
                    q(wspec.core_quantile).max(lo),
                    q(1.0 - wspec.core_quantile).min(hi),
                )
            } else {
                (lo, hi)
            };
            Ok((inside, core))
        })
        .collect::<Result<_>>()?;
    let cores = Cores::new(pilots.iter().map(|p| p.1).collect())?;
    let pilot_inside: Vec<f64> = pilots.iter().map(|p| p.0).collect();
    // 1. one path per (replica, well)
    let units: Vec<(usize, usize)> = (0..replicas)
        .flat_map(|r| (0..nw).map(move |i| (r, i)))
        .collect();
    // progress: pieces finished (the wells' paths, then the splittings)
    let total = (units.len() + replicas * 2 * (nw - 1)) as u64;
    let finished = AtomicU64::new(0);
    let tick = || {
        let d = finished.fetch_add(1, Ordering::Relaxed) + 1;
        monitor.progress(d, total);
    };
    let runs: Vec<WellRun> = units
        .par_iter()
        .map(|&(r, i)| {
            monitor.check()?;
            let start = (wells.modes[i], 0.0);
            let w = oscillator(i, 0)?;
            let mut rec = Recorder::new(&layout, sizes.burn, spec.sample_every, r as u64, start.0);
            let mut counts = (0, 0);
            let (path, exits) = well_path(
                w,
                i,
                &cores,
                &sp,
                r as u64,
                monitor,
                &mut |o: &Oscillator| {
                    let _ = crate::engine::Observer::observe(&mut rec, &o.s);
                    counts = (o.s.impacts(), o.s.sticking_steps());
                },
            )
            .map_err(|e| Error::InPath {
                path: r as u64,
                u0: start.0,
                error: Box::new(e),
            })?;
            let stats = rec.finish_counted(counts);
            tick();
            Ok((stats, path, exits))
        })
        .collect::<Result<_>>()?;
    // 2. the AMS of every (replica, transition)
    let mut exits: Vec<Option<super::splitting::Exits<Oscillator>>> = Vec::new();
    let mut stats: Vec<PathStats> = Vec::new();
    let mut paths: Vec<WellPath> = Vec::new();
    for (s, p, e) in runs {
        stats.push(s);
        paths.push(p);
        exits.push(Some(e));
    }
    let pairs = neighbours(nw);
    let mut jobs = Vec::new();
    for r in 0..replicas {
        for &(i, j, d) in &pairs {
            let e = exits[r * nw + i]
                .as_mut()
                .expect("exits taken once per direction");
            let starts = std::mem::take(
                &mut e[match d {
                    super::splitting::Direction::Up => 0,
                    super::splitting::Direction::Down => 1,
                }],
            );
            jobs.push((r, i, j, d, starts));
        }
    }
    drop(exits);
    let mut transitions: Vec<Transition> = jobs
        .into_par_iter()
        .map(|(r, i, j, d, starts)| {
            let t = ams(starts, i, j, d, &cores, &sp, r as u64, monitor);
            tick();
            t
        })
        .collect::<Result<_>>()?;
    for (k, t) in transitions.iter_mut().enumerate() {
        let r = k / pairs.len();
        let p = &paths[r * nw + t.from];
        let d = if t.to > t.from { 0 } else { 1 };
        t.flux = p.exits[d] as f64 / p.time;
        t.rate = t.flux * t.probability;
    }
    Ok(combine(
        (cores, pilot_inside),
        spec,
        &layout,
        &sizes,
        problem.oscillator().equivalents().omega1,
        wspec,
        &wells,
        stats,
        paths,
        transitions,
    ))
}

/// Offsets of one replica's unit vector: the rates (up, down per gap), then per well its
/// samples, turning points, amplitude, turning, energy and joint counts, moment sums and
/// occupancy counts.
struct Offsets {
    nw: usize,
    bins: usize,
    joint: usize,
    per_well: usize,
}

impl Offsets {
    fn new(nw: usize, bins: usize, joint_bins: usize) -> Self {
        let joint = joint_bins * joint_bins + 1;
        Offsets {
            nw,
            bins,
            joint,
            per_well: 2 + 3 * (bins + 1) + joint + 5 + nw,
        }
    }
    fn rates(&self) -> usize {
        2 * (self.nw - 1)
    }
    fn well(&self, i: usize) -> usize {
        self.rates() + i * self.per_well
    }
    fn samples(&self, i: usize) -> usize {
        self.well(i)
    }
    fn turnings(&self, i: usize) -> usize {
        self.well(i) + 1
    }
    fn amplitude(&self, i: usize) -> usize {
        self.well(i) + 2
    }
    fn turning(&self, i: usize) -> usize {
        self.amplitude(i) + self.bins + 1
    }
    fn energy(&self, i: usize) -> usize {
        self.turning(i) + self.bins + 1
    }
    fn joint(&self, i: usize) -> usize {
        self.energy(i) + self.bins + 1
    }
    fn moments(&self, i: usize) -> usize {
        self.joint(i) + self.joint
    }
    fn occupancy(&self, i: usize) -> usize {
        self.moments(i) + 5
    }
    fn len(&self) -> usize {
        self.rates() + self.nw * self.per_well
    }
    /// The weights from a (sum of) unit vector(s).
    fn weights(&self, t: &[f64]) -> Option<Vec<f64>> {
        let up: Vec<f64> = (0..self.nw - 1).map(|g| t[2 * g]).collect();
        let down: Vec<f64> = (0..self.nw - 1).map(|g| t[2 * g + 1]).collect();
        if self.nw == 1 {
            return Some(vec![1.0]);
        }
        chain_weights(&up, &down)
    }
}

/// Sum of a path's quarters.
fn quarters(q: &[Vec<u64>]) -> Vec<u64> {
    let mut s = vec![0u64; q[0].len()];
    for h in q.iter().take(QUARTERS) {
        for (x, y) in s.iter_mut().zip(h) {
            *x += y;
        }
    }
    s
}

/// The replicas' results combined: conditional results per well, the weights, the mixture.
#[allow(clippy::too_many_arguments)]
fn combine(
    (cores, pilot_inside): (Cores, Vec<f64>),
    spec: &EnsembleSpec,
    layout: &Layout,
    sizes: &super::spec::Sizes,
    omega1: f64,
    wspec: &WellsSpec,
    wells: &Wells,
    stats: Vec<PathStats>,
    paths: Vec<WellPath>,
    transitions: Vec<Transition>,
) -> WellsResult {
    let nw = wells.len();
    let replicas = spec.paths;
    let np = 2 * (nw - 1);
    let off = Offsets::new(nw, spec.bins, spec.joint_bins);
    // the conditional result of each well over the replicas
    let conditional: Vec<EnsembleResult> = (0..nw)
        .map(|i| {
            let of_well: Vec<PathStats> =
                (0..replicas).map(|r| stats[r * nw + i].clone()).collect();
            assemble(spec, layout, sizes, omega1, &of_well)
        })
        .collect();
    // one unit vector per replica
    let units: Vec<Vec<f64>> = (0..replicas)
        .map(|r| {
            let mut u = vec![0.0; off.len()];
            for k in 0..np {
                u[k] = transitions[r * np + k].rate;
            }
            for i in 0..nw {
                let p = &stats[r * nw + i];
                let put = |u: &mut Vec<f64>, at: usize, h: &[u64]| {
                    for (x, c) in u[at..at + h.len()].iter_mut().zip(h) {
                        *x = *c as f64;
                    }
                };
                let amp = quarters(&p.amplitude);
                u[off.samples(i)] = amp.iter().sum::<u64>() as f64;
                let tur = quarters(&p.turning);
                u[off.turnings(i)] = tur.iter().sum::<u64>() as f64;
                put(&mut u, off.amplitude(i), &amp);
                put(&mut u, off.turning(i), &tur);
                put(&mut u, off.energy(i), &quarters(&p.energy));
                put(&mut u, off.joint(i), &quarters(&p.joint));
                let m = off.moments(i);
                for b in &p.batches {
                    for (x, y) in u[m..m + 5].iter_mut().zip([b.u, b.u2, b.v, b.v2, b.a]) {
                        *x += y;
                    }
                    for (k, c) in b.wells.iter().enumerate() {
                        u[off.occupancy(i) + k] += *c as f64;
                    }
                }
            }
            u
        })
        .collect();
    let weights_of = |t: &[f64]| off.weights(t);
    // a quantity of the mixture: Σ_i π_i q_i(t), NaN where the weights are undefined
    let mixture = |q: &dyn Fn(&[f64], usize) -> f64| {
        jackknife(&units, |t| match weights_of(t) {
            Some(w) => (0..nw).map(|i| w[i] * q(t, i)).sum(),
            None => f64::NAN,
        })
    };
    let ratio = |t: &[f64], at: usize, n: usize| if t[n] > 0.0 { t[at] / t[n] } else { 0.0 };
    let density = |edges: Vec<f64>, at: &dyn Fn(usize) -> usize, n: &dyn Fn(usize) -> usize| {
        let nb = edges.len() - 1;
        let per_bin: Vec<Estimate> = (0..=nb)
            .map(|b| mixture(&|t, i| ratio(t, at(i) + b, n(i))))
            .collect();
        let width = |b: usize| edges[b + 1] - edges[b];
        Density {
            density: (0..nb).map(|b| per_bin[b].value / width(b)).collect(),
            stderr: (0..nb).map(|b| per_bin[b].stderr / width(b)).collect(),
            beyond: per_bin[nb].value,
            count: 0,
            edges,
        }
    };
    let a_max = spec.amplitude_max;
    let mut amplitude = density(layout.edges(a_max), &|i| off.amplitude(i), &|i| {
        off.samples(i)
    });
    amplitude.count = units
        .iter()
        .map(|u| (0..nw).map(|i| u[off.samples(i)]).sum::<f64>())
        .sum::<f64>() as u64;
    let mut turning = density(layout.edges(a_max), &|i| off.turning(i), &|i| {
        off.turnings(i)
    });
    turning.count = units
        .iter()
        .map(|u| (0..nw).map(|i| u[off.turnings(i)]).sum::<f64>())
        .sum::<f64>() as u64;
    let h_max = 0.5 * omega1 * omega1 * a_max * a_max;
    let mut energy = density(layout.edges(h_max), &|i| off.energy(i), &|i| off.samples(i));
    energy.count = amplitude.count;
    // the joint density on the direct result's grid
    let c0 = &conditional[0].joint;
    let jb = spec.joint_bins;
    let cells: Vec<Estimate> = (0..=jb * jb)
        .map(|c| mixture(&|t, i| ratio(t, off.joint(i) + c, off.samples(i))))
        .collect();
    let du = c0.u_edges[1] - c0.u_edges[0];
    let dv = c0.v_edges[1] - c0.v_edges[0];
    let grid = |f: &dyn Fn(&Estimate) -> f64| -> Vec<Vec<f64>> {
        cells[..jb * jb]
            .chunks(jb)
            .map(|row| row.iter().map(|e| f(e) / (du * dv)).collect())
            .collect()
    };
    let joint = JointDensity {
        u_edges: c0.u_edges.clone(),
        v_edges: c0.v_edges.clone(),
        density: grid(&|e| e.value),
        stderr: grid(&|e| e.stderr),
        outside: cells[jb * jb].value,
    };
    // moments: mixtures of the conditional first and second moments
    let off = &off;
    let moment = |t: &[f64], i: usize, k: usize| ratio(t, off.moments(i) + k, off.samples(i));
    let mean_u = mixture(&|t, i| moment(t, i, 0));
    let mean_v = mixture(&|t, i| moment(t, i, 2));
    let var = |k1: usize, k2: usize| {
        jackknife(&units, |t| match weights_of(t) {
            Some(w) => {
                let m1: f64 = (0..nw).map(|i| w[i] * moment(t, i, k1)).sum();
                let m2: f64 = (0..nw).map(|i| w[i] * moment(t, i, k2)).sum();
                m2 - m1 * m1
            }
            None => f64::NAN,
        })
    };
    let var_u = var(0, 1);
    let var_v = var(2, 3);
    let mean_amplitude = mixture(&|t, i| moment(t, i, 4));
    let occupancy: Vec<Estimate> = (0..nw)
        .map(|k| mixture(&|t, i| ratio(t, off.occupancy(i) + k, off.samples(i))))
        .collect();
    // rates and weights
    let pairs = neighbours(nw);
    // a mean over the replicas with its standard error
    let mean_of = |k: usize, f: &dyn Fn(&Transition) -> f64| {
        let u: Vec<Vec<f64>> = (0..replicas)
            .map(|r| vec![1.0, f(&transitions[r * np + k])])
            .collect();
        jackknife(&u, |t| t[1] / t[0])
    };
    let rates: Vec<Rate> = pairs
        .iter()
        .enumerate()
        .map(|(k, &(i, j, _))| Rate {
            from: i,
            to: j,
            rate: mean_of(k, &|t| t.rate),
            flux: mean_of(k, &|t| t.flux),
            probability: mean_of(k, &|t| t.probability),
        })
        .collect();
    let weights: Vec<Estimate> = (0..nw)
        .map(|i| jackknife(&units, |t| weights_of(t).map_or(f64::NAN, |w| w[i])))
        .collect();
    let pooled_weights = off.weights(&units.iter().fold(vec![0.0; off.len()], |mut s, u| {
        for (x, y) in s.iter_mut().zip(u) {
            *x += y;
        }
        s
    }));
    let mut rate_matrix = vec![vec![0.0; nw]; nw];
    for r in &rates {
        rate_matrix[r.from][r.to] = r.rate.value;
    }
    let residence: Vec<f64> = (0..nw)
        .map(|i| 1.0 / rate_matrix[i].iter().sum::<f64>())
        .collect();
    let sampled = spec.length * replicas as f64;
    let relaxation: Vec<f64> = conditional
        .iter()
        .map(|c| sampled / c.stationarity.ess.max(1.0))
        .collect();
    // the diagnostic
    let mut refusals = Vec::new();
    let mut notes = Vec::new();
    for (k, r) in rates.iter().enumerate() {
        if r.rate.value.is_nan() || r.rate.value <= 0.0 {
            let (level, passed) = (0..replicas)
                .map(|q| &transitions[q * np + k])
                .map(|t| (t.level, t.level_probability))
                .fold((f64::NAN, 0.0f64), |(l, p), (tl, tp)| {
                    let farther = l.is_nan() || (tl - l) * (r.to as f64 - r.from as f64) > 0.0;
                    if farther {
                        (tl, tp)
                    } else {
                        (l, p.max(tp))
                    }
                });
            notes.push(format!(
                "{} → {}: no excursion reached the core of well {} in any replica; the \
                 splitting got as far as amplitude {level:.4} (passed with probability \
                 {passed:.2e}): the rate is below the method's resolution, taken as 0",
                r.from, r.to, r.to
            ));
        }
        let incomplete = (0..replicas)
            .filter(|&q| !transitions[q * np + k].complete)
            .count();
        if incomplete > 0 {
            refusals.push(format!(
                "the splitting of {} → {} reached its iteration limit in {incomplete} replicas",
                r.from, r.to
            ));
        }
        let d = if r.to > r.from { 0 } else { 1 };
        let exits = (0..replicas)
            .map(|q| paths[q * nw + r.from].exits[d] as f64)
            .sum::<f64>()
            / replicas as f64;
        if exits < MIN_EXITS {
            refusals.push(format!(
                "well {}: {exits:.1} exits toward well {} per replica (at least {MIN_EXITS} \
                 needed): lengthen the wells' paths",
                r.from, r.to
            ));
        }
    }
    for (i, c) in conditional.iter().enumerate() {
        if pilot_inside[i] < 0.5 {
            refusals.push(format!(
                "well {i}: a path started at its mode spent only {:.0} % of its turning points in \
                 the well's core: the simulated system has no well there",
                100.0 * pilot_inside[i]
            ));
        }
        if !c.stationarity.stationary {
            refusals.push(format!(
                "well {i}: its conditional statistics are not stationary (R̂ = {:.3}, drift \
                 {:.1} s.e.): the path does not settle in the well",
                c.stationarity.r_hat, c.stationarity.drift_z
            ));
        }
        if residence[i].is_nan() || residence[i] < wspec.separation * relaxation[i] {
            refusals.push(format!(
                "well {i}: residence time {:.3e} is not {} times its relaxation time {:.3e}: \
                 the rates are not separated from the relaxation inside the well",
                residence[i], wspec.separation, relaxation[i]
            ));
        }
    }
    // a rate below resolution is not known to be 0: the splitting only says it is below the
    // flux times the probability of passing the last level it reached. Where that bound could
    // move the weights, they are not determined.
    let bounds: Vec<f64> = (0..np)
        .map(|k| {
            if rates[k].rate.value > 0.0 {
                rates[k].rate.value
            } else {
                (0..replicas)
                    .map(|q| {
                        let t = &transitions[q * np + k];
                        t.flux * t.level_probability
                    })
                    .sum::<f64>()
                    / replicas as f64
            }
        })
        .collect();
    let zero: Vec<usize> = (0..np)
        .filter(|&k| rates[k].rate.value.is_nan() || rates[k].rate.value <= 0.0)
        .collect();
    if let (Some(w), false) = (&pooled_weights, zero.is_empty()) {
        let with = |set: &[usize]| {
            let k: Vec<f64> = (0..np)
                .map(|j| {
                    if set.contains(&j) {
                        bounds[j]
                    } else {
                        rates[j].rate.value.max(0.0)
                    }
                })
                .collect();
            let up: Vec<f64> = (0..nw - 1).map(|g| k[2 * g]).collect();
            let down: Vec<f64> = (0..nw - 1).map(|g| k[2 * g + 1]).collect();
            chain_weights(&up, &down)
        };
        let mut trials: Vec<Vec<usize>> = zero.iter().map(|&k| vec![k]).collect();
        trials.push(zero.clone());
        let worst = trials
            .iter()
            .filter_map(|set| with(set).map(|wb| (set, wb)))
            .map(|(set, wb)| {
                let shift = w
                    .iter()
                    .zip(&wb)
                    .map(|(a, b)| (a - b).abs())
                    .fold(0.0, f64::max);
                (shift, set, wb)
            })
            .max_by(|a, b| a.0.total_cmp(&b.0));
        if let Some((shift, set, wb)) = worst {
            if shift > MAX_WEIGHT_SHIFT {
                let named: Vec<String> = set
                    .iter()
                    .map(|&k| format!("{} → {} < {:.2e}", rates[k].from, rates[k].to, bounds[k]))
                    .collect();
                let shown: Vec<String> = wb.iter().map(|x| format!("{x:.3}")).collect();
                refusals.push(format!(
                    "rates below the method's resolution could move the weights: with {} at \
                     their bounds the weights would be ({}) instead of ({})",
                    named.join(", "),
                    shown.join(", "),
                    w.iter()
                        .map(|x| format!("{x:.3}"))
                        .collect::<Vec<_>>()
                        .join(", ")
                ));
            }
        }
    }
    if pooled_weights.is_none() {
        refusals.push(
            "the weights are undetermined: two groups of wells exchange no transition within \
             the method's resolution (each would keep the mass it starts with)"
                .into(),
        );
    }
    let valid = refusals.is_empty();
    let replica_list: Vec<Replica> = (0..replicas)
        .map(|r| Replica {
            replica: r as u64,
            weights: off.weights(&units[r]).unwrap_or_default(),
            transitions: transitions[r * np..(r + 1) * np].to_vec(),
            paths: paths[r * nw..(r + 1) * nw].to_vec(),
        })
        .collect();
    // each replica's own mixture as pseudo-counts (the theory comparison's units)
    let nb = spec.bins;
    let pooled = pooled_weights.clone();
    let per_path_amplitude: Vec<Vec<u64>> = units
        .iter()
        .zip(&replica_list)
        .map(|(u, rep)| {
            let w = if rep.weights.is_empty() {
                pooled.clone().unwrap_or_else(|| vec![1.0 / nw as f64; nw])
            } else {
                rep.weights.clone()
            };
            let total: f64 = (0..nw).map(|i| u[off.samples(i)]).sum();
            (0..=nb)
                .map(|b| {
                    let p: f64 = (0..nw)
                        .map(|i| w[i] * ratio(u, off.amplitude(i) + b, off.samples(i)))
                        .sum();
                    (p * total).round() as u64
                })
                .collect()
        })
        .collect();
    let worst = |f: &dyn Fn(&Stationarity) -> f64| {
        conditional
            .iter()
            .map(|c| f(&c.stationarity))
            .filter(|x| !x.is_nan())
            .fold(f64::NAN, |m, x| if m.is_nan() || x > m { x } else { m })
    };
    let stationarity = Stationarity {
        r_hat_amplitude: worst(&|s| s.r_hat_amplitude),
        r_hat_wells: conditional.iter().map(|c| c.stationarity.r_hat).collect(),
        r_hat: worst(&|s| s.r_hat),
        // the mixture's effective sample: Var Σπ_i p_i = Σ π_i² Var p_i, Var p_i ∝ 1/ESS_i
        ess: match &pooled_weights {
            Some(w) => {
                1.0 / conditional
                    .iter()
                    .zip(w)
                    .map(|(c, p)| p * p / c.stationarity.ess.max(1.0))
                    .sum::<f64>()
            }
            None => conditional
                .iter()
                .map(|c| c.stationarity.ess)
                .fold(f64::INFINITY, f64::min),
        },
        drift: f64::NAN,
        drift_z: worst(&|s| s.drift_z.abs()),
        stationary: valid,
        suggested_length: spec.length,
    };
    let mut warnings: Vec<String> = refusals
        .iter()
        .map(|r| format!("well decomposition refused: {r}"))
        .collect();
    warnings.extend(notes.iter().cloned());
    for (i, c) in conditional.iter().enumerate() {
        warnings.extend(
            c.warnings
                .iter()
                .filter(|w| !w.starts_with("first passage"))
                .map(|w| format!("well {i}: {w}")),
        );
    }
    let steps = paths.iter().map(|p| p.steps).sum::<u64>()
        + transitions.iter().map(|t| t.steps).sum::<u64>();
    let result = EnsembleResult {
        paths: replicas,
        steps_per_path: sizes.burn + sizes.window,
        burn_in_steps: sizes.burn,
        samples_per_path: sizes.samples,
        omega1,
        between_paths: true,
        mean_u,
        var_u,
        mean_v,
        var_v,
        mean_amplitude,
        amplitude,
        turning,
        energy,
        joint,
        wells: Some(wells.clone()),
        occupancy,
        passages: vec![],
        stationarity,
        impacts: stats.iter().map(|p| p.impacts).sum(),
        sticking_steps: stats.iter().map(|p| p.sticking_steps).sum(),
        warnings,
        per_path_amplitude,
    };
    WellsResult {
        result,
        wells: WellsEstimate {
            spec: *wspec,
            cores,
            pilot_inside,
            rates,
            rate_matrix,
            weights,
            residence,
            relaxation,
            conditional: conditional.into_iter().map(|c| c.amplitude).collect(),
            valid,
            refusals,
            notes,
            replicas: replica_list,
            steps,
        },
    }
}
