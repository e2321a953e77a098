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
//! - **The simulation's wells.** The theory's wells (modes and antimodes of its P(A)) are
//!   candidates: a pilot path per theory well starts at its mode. A well the pilot leaves for
//!   another well's core within [`MIN_STAY`] turning points (it relaxes there) is *missing* in
//!   the simulation — a finding about the theory, reported in [`WellsEstimate::missing`] and
//!   the notes; the decomposition runs over the remaining wells, each missing well's region
//!   joined to the well its pilot settled in. Refused only when a pilot settles in no well's
//!   core, or stays but spends less than [`MIN_INSIDE`] of its turning points in its core: the
//!   simulation visits amplitudes that no well covers. The pilot's turning amplitudes in its
//!   well set the core ([q, 1 − q] quantiles).
//! - **Labels.** A path's label is the last well core its turning amplitude visited
//!   ([`Wells::core`]), the hysteresis of the direct ensemble's first passages. Every sample
//!   has exactly one label, so P = Σ π_i P_i holds exactly.
//! - **Score of the splitting.** The levels of the splitting are set by the phase-averaged
//!   energy amplitude Ā(t) = (1/T) ∫_{t−T}^{t} A_E, A_E = √(U² + (U̇/ω1)²), T = 2π/ω1 (ω1 the
//!   equivalent frequency): A_E is the amplitude variable of the averaging ansatz
//!   U = A cos(ω1 t + φ), and its average over a period is the theory's slow amplitude A. It
//!   moves every step (the turning amplitude, once per half-cycle, made every branch start at a
//!   turning point, and on a strongly contracting cycle all branches fell back: the splitting
//!   died about three standard deviations past the core). A_E itself swings within a cycle
//!   (impacts, the nonlinear stiffness) by far more than the noise moves it, so its levels
//!   follow the phase, not the progress toward the neighbour; the average over a period
//!   removes that swing. The window of A_E is part of the cloned state, so the score is a
//!   function of the state and the splitting stays unbiased.
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
//! - **Validity.** A rate is *unresolved* when its splitting died out in every replica or
//!   stopped at its iteration limit in any: it is taken as 0 and bounded by the flux times the
//!   estimated probability of passing the farthest level reached (said in the notes). The
//!   decomposition is refused (`valid` false, with the reasons) when such a bound, put in place
//!   of the 0, would move a weight by more than [`MAX_WEIGHT_SHIFT`], or the weights are
//!   undetermined (two groups of wells exchange no resolved transition), when a well's path saw
//!   fewer than [`MIN_EXITS`] exits toward a neighbour, when the simulation visits amplitudes
//!   no well covers (above), when a well's conditional statistics are not stationary by the
//!   direct diagnosis (R̂ over the replicas, drift), or when the mean residence time
//!   1/Σ_j k_ij of a well is not at least `separation` times its relaxation time (sampled time
//!   over the effective sample size of A): the rates must be slow against the relaxation inside
//!   the wells for P_i to be the quasi-stationary density. Where every refusal is about the
//!   rates and weights the conditional densities stand (`conditional_valid`); where the only
//!   other refusal is a well's drift between the window's halves with its replicas agreeing
//!   (`conditional_drifting`), each half's per-replica counts are kept
//!   (`conditional_counts_halves`) so that a statement over every weighting can be checked on
//!   each half alone.
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
//! reproducibility; refusals (no wells, one replica, rates bounded by an iteration limit);
//! unit tests below: when a bound moves the weights, which wells the simulation lacks.

use super::merging::{assemble, jackknife, Density, EnsembleResult, Estimate, JointDensity};
use super::recording::{Layout, PathStats, Recorder};
use super::spec::{EnsembleSpec, Wells, QUARTERS};
use super::splitting::{
    ams, chain_weights, neighbours, stream, well_path, Cores, Observation, Splitting, Transition,
    Walker, WellPath,
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
    /// Most AMS iterations per transition; each kills a tenth of the replicas
    /// ([`super::splitting::KILL_FRACTION`]), so n iterations resolve probabilities down to
    /// about 0.9ⁿ (2000: 10⁻⁹¹).
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
            max_iterations: 2_000,
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
    /// The theory's wells (modes and antimodes of its P(A)); the decomposition is over those
    /// the simulation has (the result's `wells`).
    pub theory_wells: Wells,
    /// The theory's wells that the simulation lacks: a path started at the mode settled in
    /// another well.
    pub missing: Vec<MissingWell>,
    /// The simulation's wells' cores used for the labels (from the pilot paths).
    pub cores: Cores,
    /// The fraction of each pilot path's turning amplitudes inside [`Wells::core`], per theory
    /// well.
    pub pilot_inside: Vec<f64>,
    /// Rates between neighbours (0 → 1, 1 → 0, 1 → 2, …).
    pub rates: Vec<Rate>,
    /// Upper bound of each rate below the method's resolution (same order as `rates`; NaN
    /// where the rate is resolved).
    #[serde(default, with = "crate::non_finite::vec")]
    pub rate_bounds: Vec<f64>,
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
    /// The effective sample size of A in each well's conditional statistics.
    #[serde(default, with = "crate::non_finite::vec")]
    pub conditional_ess: Vec<f64>,
    /// Each replica's amplitude counts per well (`[replica][well]`, the histogram's bins and
    /// the count beyond the last edge): the replicas' own conditional densities.
    #[serde(default)]
    pub conditional_counts: Vec<Vec<Vec<u64>>>,
    /// The same counts of the window's first and second halves (`[half][replica][well]`):
    /// where a well's conditional statistics drift, a statement over every weighting is made
    /// only when it holds on each half alone.
    #[serde(default)]
    pub conditional_counts_halves: Vec<Vec<Vec<Vec<u64>>>>,
    /// The decomposition passed its validity diagnostic.
    pub valid: bool,
    /// The conditional statistics passed the diagnostic (every refusal, if any, is about the
    /// rates and weights: a rate bound that could move the weights, undetermined weights, too
    /// few exits): the stationary density is some mixture Σ π_i P_i of valid P_i
    /// ([`super::hellinger_bounds`] over every weighting).
    #[serde(default)]
    pub conditional_valid: bool,
    /// Every refusal, if any, is about the rates and weights or about a well's conditional
    /// statistics drifting between the window's halves (R̂ over the replicas within 1.1): the
    /// conditional densities are estimates of a distribution that may still move, and a
    /// statement over every weighting is made only where it holds on each half
    /// ([`WellsEstimate::conditional_counts_halves`]).
    #[serde(default)]
    pub conditional_drifting: bool,
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

/// The oscillator as a [`Walker`]: its score is the phase-averaged energy amplitude — the
/// mean of A_E = √(U² + (U̇/ω1)²) over the last period 2π/ω1 — after every step, its label the
/// turning amplitude |U| at the maxima of |U|. The window of A_E is part of the walker's state
/// (cloned with it), so the score is a function of the state.
#[derive(Clone)]
struct Oscillator {
    s: Stepper,
    rising: bool,
    crossing: bool,
    /// 1/ω1².
    inv_omega1_sq: f64,
    /// The last period's A_E (a ring), its sum and the next slot.
    window: Vec<f64>,
    sum: f64,
    next: usize,
    filled: usize,
}

impl Oscillator {
    fn new(s: Stepper, crossing: bool, omega1: f64, dt: f64) -> Self {
        let len = (std::f64::consts::TAU / (omega1 * dt)).round().max(1.0) as usize;
        Oscillator {
            s,
            rising: false,
            crossing,
            inv_omega1_sq: 1.0 / (omega1 * omega1),
            window: vec![0.0; len],
            sum: 0.0,
            next: 0,
            filled: 0,
        }
    }
}

impl Walker for Oscillator {
    #[inline]
    fn advance(&mut self) -> Result<Observation> {
        self.s.step()?;
        let (u, v) = (self.s.u(), self.s.v());
        let side = if self.crossing { u.signum() } else { 1.0 };
        let rising = side * v > 0.0;
        let turning = self.rising && !rising;
        self.rising = rising;
        let a = (u * u + v * v * self.inv_omega1_sq).sqrt();
        let n = self.window.len();
        self.sum += a - self.window[self.next];
        self.window[self.next] = a;
        self.next = if self.next + 1 == n { 0 } else { self.next + 1 };
        if self.filled < n {
            self.filled += 1;
        }
        if self.next == 0 {
            // once a period, the sum afresh (no drift of rounding)
            self.sum = self.window.iter().sum();
        }
        Ok(Observation {
            score: self.sum / self.filled as f64,
            label: turning.then(|| u.abs()),
        })
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
    let replicas = spec.paths;
    let history = fresh_history(problem, method, (sizes.burn + sizes.window) as f64 * dt)?;
    let crossing = problem.system() == System::Zhuravlev;
    let omega1 = problem.oscillator().equivalents().omega1;
    let oscillator = |mode: f64, path: u64| -> Result<Oscillator> {
        let start = (mode, 0.0);
        let s = Stepper::with_history(problem, method, start, (spec.seed, path), history.clone())?;
        Ok(Oscillator::new(s, crossing, omega1, dt))
    };
    // 0. a pilot path per theory well: where it settles (the fraction of its turning
    // amplitudes in each well's core) and, in its own well, the core
    let theory_wells = wells;
    let nt = theory_wells.len();
    let pilot_steps = sizes.burn + (sizes.window / 4).max(1);
    let pilots: Vec<Pilot> = crate::profile::parallel(|stage| {
        (0..nt)
            .into_par_iter()
            .map(|i| {
                stage.task(|| {
                    let mut w = oscillator(theory_wells.modes[i], 0)?;
                    w.renoise(spec.seed, stream(u64::MAX, i, 3, 0));
                    // every turning amplitude after the burn-in, and those before the first landing in
                    // another well's core (the pilot's time in label i)
                    let mut seen = Vec::new();
                    let mut own = Vec::new();
                    let mut stay: Option<u64> = None;
                    let mut turnings = 0u64;
                    for n in 0..pilot_steps {
                        if let Some(a) = w.advance()?.label {
                            turnings += 1;
                            if stay.is_none() {
                                let k = theory_wells.well_of(a);
                                let (lo, hi) = theory_wells.core(k);
                                if k != i && a >= lo && a <= hi {
                                    stay = Some(turnings - 1);
                                }
                            }
                            if n >= sizes.burn {
                                seen.push(a);
                                if stay.is_none() {
                                    own.push(a);
                                }
                            }
                        }
                        if n % (1 << 16) == 0 {
                            monitor.check()?;
                        }
                    }
                    let in_core = |k: usize, of: &[f64]| {
                        let (lo, hi) = theory_wells.core(k);
                        of.iter().filter(|&&a| a >= lo && a <= hi).count() as f64
                            / of.len().max(1) as f64
                    };
                    let share: Vec<f64> = (0..nt).map(|k| in_core(k, &seen)).collect();
                    let inside = in_core(i, &own);
                    let (lo, hi) = theory_wells.core(i);
                    own.sort_by(f64::total_cmp);
                    let q = |f: f64| {
                        own[((f * (own.len() - 1) as f64).round() as usize).min(own.len() - 1)]
                    };
                    let core = if own.len() >= 10 && inside >= MIN_INSIDE {
                        (
                            q(wspec.core_quantile).max(lo),
                            q(1.0 - wspec.core_quantile).min(hi),
                        )
                    } else {
                        (lo, hi)
                    };
                    Ok(Pilot {
                        share,
                        inside,
                        stay,
                        core,
                    })
                })
            })
            .collect::<Result<_>>()
    })?;
    let pilot_inside: Vec<f64> = pilots.iter().map(|p| p.inside).collect();
    let (kept, mut missing, mut refusals) = simulated_wells(&pilots);
    for m in &mut missing {
        m.mode = theory_wells.modes[m.well];
    }
    let wells = reduced_wells(&theory_wells, &kept, &missing)?;
    let cores = Cores::new(kept.iter().map(|&i| pilots[i].core).collect())?;
    let spec = &EnsembleSpec {
        wells: Some(wells.clone()),
        ..spec.clone()
    };
    let nw = wells.len();
    let layout = Layout::new(spec, problem, sizes.samples);
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
    let runs: Vec<WellRun> = crate::profile::parallel(|stage| {
        units
            .par_iter()
            .map(|&(r, i)| {
                stage.task(|| {
                    monitor.check()?;
                    let start = (wells.modes[i], 0.0);
                    let w = oscillator(wells.modes[i], 0)?;
                    let mut rec =
                        Recorder::new(&layout, sizes.burn, spec.sample_every, r as u64, start.0);
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
            })
            .collect::<Result<_>>()
    })?;
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
    let mut transitions: Vec<Transition> = crate::profile::parallel(|stage| {
        jobs.into_par_iter()
            .map(|(r, i, j, d, starts)| {
                stage.task(|| {
                    let t = ams(starts, i, j, d, &cores, &sp, r as u64, monitor);
                    tick();
                    t
                })
            })
            .collect::<Result<_>>()
    })?;
    for (k, t) in transitions.iter_mut().enumerate() {
        let r = k / pairs.len();
        let p = &paths[r * nw + t.from];
        let d = if t.to > t.from { 0 } else { 1 };
        t.flux = p.exits[d] as f64 / p.time;
        t.rate = t.flux * t.probability;
    }
    let found = Found {
        cores,
        pilot_inside,
        theory_wells,
        missing,
        refusals: std::mem::take(&mut refusals),
    };
    Ok(combine(
        found,
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

/// What a pilot path started at a theory well's mode saw.
struct Pilot {
    /// The fraction of its turning amplitudes after the burn-in in each theory well's core
    /// ([`Wells::core`]).
    share: Vec<f64>,
    /// The fraction in its own well's core of those after the burn-in and before its first
    /// landing in another well's core.
    inside: f64,
    /// Turning points before its first landing in another well's core (`None`: never).
    stay: Option<u64>,
    /// Its own well's core for the labels: the quantiles of its turning amplitudes in label i.
    core: (f64, f64),
}

/// Least fraction of a pilot's turning amplitudes in its own well's core for the simulation
/// to have that well (and in another well's core for a missing well to be settled there).
pub const MIN_INSIDE: f64 = 0.5;

/// Fewest turning points a pilot started at a theory well's mode must stay before it first
/// lands in another well's core for the simulation to have that well (50 periods: a well whose
/// paths leave sooner is not metastable, it relaxes into the other well).
pub const MIN_STAY: u64 = 100;

/// A theory well that the simulation does not have: a path started at its mode relaxes into
/// another well.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MissingWell {
    /// The theory's well (index among the theory's wells).
    pub well: usize,
    /// Its mode.
    pub mode: f64,
    /// Turning points the pilot stayed before it landed in another well's core.
    pub stay: u64,
    /// The theory well whose core the pilot settled in.
    pub settled_in: usize,
    /// The fraction of the pilot's turning amplitudes after its burn-in in that core.
    pub settled: f64,
}

/// The theory wells the simulation has (their indices, ascending), those it lacks, and the
/// refusals: a pilot that settled in no well's core (the simulation visits amplitudes that no
/// well covers), or in a core of another missing well.
fn simulated_wells(pilots: &[Pilot]) -> (Vec<usize>, Vec<MissingWell>, Vec<String>) {
    let n = pilots.len();
    let left = |i: usize| pilots[i].stay.is_some_and(|s| s < MIN_STAY);
    let mut kept = Vec::new();
    let mut missing = Vec::new();
    let mut refusals = Vec::new();
    for (i, p) in pilots.iter().enumerate() {
        if !left(i) {
            if p.inside < MIN_INSIDE {
                refusals.push(format!(
                    "theory well {i}: a path started at its mode stayed, but only {:.0} % of its \
                     turning points were in the well's core: the simulation visits amplitudes \
                     that no well covers",
                    100.0 * p.inside
                ));
            }
            kept.push(i);
            continue;
        }
        let (j, settled) = (0..n)
            .filter(|&k| k != i)
            .map(|k| (k, p.share[k]))
            .fold((i, 0.0), |b, x| if x.1 > b.1 { x } else { b });
        if settled >= MIN_INSIDE && !left(j) {
            missing.push(MissingWell {
                well: i,
                mode: 0.0,
                stay: p.stay.unwrap_or(0),
                settled_in: j,
                settled,
            });
        } else {
            let inside: f64 = p.share.iter().sum();
            refusals.push(format!(
                "theory well {i}: a path started at its mode left it after {} turning points and \
                 settled in no other well's core ({:.0} % of its turning points in any core): \
                 the simulation visits amplitudes that no well covers",
                p.stay.unwrap_or(0),
                100.0 * inside
            ));
        }
    }
    if kept.is_empty() {
        // nothing to decompose over: keep the theory's wells (the refusals say why)
        kept = (0..n).collect();
        missing.clear();
    }
    (kept, missing, refusals)
}

/// The wells of the simulation: the theory's modes `kept`; between two kept wells the
/// antimode below the lowest well (kept or missing) that belongs to the upper one.
fn reduced_wells(theory: &Wells, kept: &[usize], missing: &[MissingWell]) -> Result<Wells> {
    let home = |m: usize| {
        missing
            .iter()
            .find(|w| w.well == m)
            .map_or(m, |w| w.settled_in)
    };
    let modes = kept.iter().map(|&i| theory.modes[i]).collect();
    let antimodes = kept
        .windows(2)
        .map(|w| {
            let m = (w[0] + 1..=w[1]).find(|&m| home(m) >= w[1]).unwrap_or(w[1]);
            theory.antimodes[m - 1]
        })
        .collect();
    Wells::new(modes, antimodes)
}

/// The largest change of the `weights` when the unresolved rates `zero` (indices into the
/// chain's rates, in the order 0 → 1, 1 → 0, 1 → 2, …) are set to their `bounds`, each alone
/// and all together: (the change, the rates set, the weights then). `None` when no such set
/// gives weights.
fn largest_shift(
    rates: &[f64],
    bounds: &[f64],
    zero: &[usize],
    weights: &[f64],
) -> Option<(f64, Vec<usize>, Vec<f64>)> {
    let gaps = rates.len() / 2;
    let with = |set: &[usize]| {
        let k: Vec<f64> = (0..rates.len())
            .map(|j| {
                if set.contains(&j) {
                    bounds[j]
                } else {
                    rates[j].max(0.0)
                }
            })
            .collect();
        let up: Vec<f64> = (0..gaps).map(|g| k[2 * g]).collect();
        let down: Vec<f64> = (0..gaps).map(|g| k[2 * g + 1]).collect();
        chain_weights(&up, &down)
    };
    let mut trials: Vec<Vec<usize>> = zero.iter().map(|&k| vec![k]).collect();
    trials.push(zero.to_vec());
    trials
        .into_iter()
        .filter_map(|set| with(&set).map(|wb| (set, wb)))
        .map(|(set, wb)| {
            let shift = weights
                .iter()
                .zip(&wb)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            (shift, set, wb)
        })
        .max_by(|a, b| a.0.total_cmp(&b.0))
}

/// What the pilots decided: the cores of the simulation's wells, the theory's wells and those
/// the simulation lacks, and the refusals so far.
struct Found {
    cores: Cores,
    pilot_inside: Vec<f64>,
    theory_wells: Wells,
    missing: Vec<MissingWell>,
    refusals: Vec<String>,
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
    quarters_in(q, 0..QUARTERS)
}

/// The counts of the quarters in `range` summed.
fn quarters_in(q: &[Vec<u64>], range: std::ops::Range<usize>) -> Vec<u64> {
    let mut s = vec![0u64; q[0].len()];
    for h in q.iter().take(range.end).skip(range.start) {
        for (x, y) in s.iter_mut().zip(h) {
            *x += y;
        }
    }
    s
}

/// The replicas' results combined: conditional results per well, the weights, the mixture.
#[allow(clippy::too_many_arguments)]
fn combine(
    found: Found,
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
    let Found {
        cores,
        pilot_inside,
        theory_wells,
        missing,
        mut refusals,
    } = found;
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
    // a transition is unresolved when its splitting died out in every replica (no excursion
    // reached the target) or stopped at its iteration limit in any: its rate is then only
    // bounded by the flux times the estimated probability of passing the farthest level (the
    // rate itself where a replica resolved it), and taken as 0 in the weights
    let tr = &transitions;
    let of = |k: usize| (0..replicas).map(move |q| &tr[q * np + k]);
    let unresolved: Vec<bool> = (0..np)
        .map(|k| of(k).any(|t| !t.complete) || of(k).all(|t| t.rate.is_nan() || t.rate <= 0.0))
        .collect();
    let bounds: Vec<f64> = (0..np)
        .map(|k| {
            of(k)
                .map(|t| {
                    if t.complete && t.probability > 0.0 {
                        t.rate
                    } else {
                        t.flux * t.level_probability
                    }
                })
                .sum::<f64>()
                / replicas as f64
        })
        .collect();
    let units: Vec<Vec<f64>> = (0..replicas)
        .map(|r| {
            let mut u = vec![0.0; off.len()];
            for k in 0..np {
                u[k] = if unresolved[k] {
                    0.0
                } else {
                    transitions[r * np + k].rate
                };
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
            rate: if unresolved[k] {
                Estimate {
                    value: 0.0,
                    stderr: 0.0,
                }
            } else {
                mean_of(k, &|t| t.rate)
            },
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
    let mut notes: Vec<String> = missing
        .iter()
        .map(|m| {
            format!(
                "the theory's well {} (mode {:.4}) is missing in the simulation: a path started \
                 at its mode left it after {} turning points and settled in the theory's well {} \
                 ({:.0} % of its turning points there); the decomposition is over the \
                 simulation's {} wells",
                m.well,
                m.mode,
                m.stay,
                m.settled_in,
                100.0 * m.settled,
                nw
            )
        })
        .collect();
    // refusals about the rates and weights only (the conditional statistics stand)
    let mut weight_refusals = 0usize;
    for (k, r) in rates.iter().enumerate() {
        if unresolved[k] {
            let (level, passed) = of(k).map(|t| (t.level, t.level_probability)).fold(
                (f64::NAN, 0.0f64),
                |(l, p), (tl, tp)| {
                    let farther = l.is_nan() || (tl - l) * (r.to as f64 - r.from as f64) > 0.0;
                    if farther {
                        (tl, tp)
                    } else {
                        (l, p.max(tp))
                    }
                },
            );
            let incomplete = of(k).filter(|t| !t.complete).count();
            let how = if incomplete > 0 {
                format!(
                    "the splitting reached its iteration limit in {incomplete} of {replicas} \
                     replicas"
                )
            } else {
                format!(
                    "no excursion reached the core of well {} in any replica",
                    r.to
                )
            };
            if level.is_nan() {
                notes.push(format!(
                    "{} → {}: no exit from the core toward well {} in any replica: the rate is \
                     unresolved, taken as 0",
                    r.from, r.to, r.to
                ));
            } else {
                notes.push(format!(
                    "{} → {}: {how}; it got as far as phase-averaged amplitude {level:.4} \
                     (passed with probability {passed:.2e}): the rate is below the method's \
                     resolution (< {:.2e}), taken as 0",
                    r.from, r.to, bounds[k]
                ));
            }
        }
        let d = if r.to > r.from { 0 } else { 1 };
        let exits = (0..replicas)
            .map(|q| paths[q * nw + r.from].exits[d] as f64)
            .sum::<f64>()
            / replicas as f64;
        if exits < MIN_EXITS {
            weight_refusals += 1;
            refusals.push(format!(
                "well {}: {exits:.1} exits toward well {} per replica (at least {MIN_EXITS} \
                 needed): lengthen the wells' paths",
                r.from, r.to
            ));
        }
    }
    let mut drift_refusals = 0usize;
    for (i, c) in conditional.iter().enumerate() {
        if !c.stationarity.stationary {
            // only the drift between the halves failed, the replicas agree (R̂ ≤ 1.1)
            if c.stationarity.r_hat.is_nan() || c.stationarity.r_hat <= 1.1 {
                drift_refusals += 1;
            }
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
    let zero: Vec<usize> = (0..np).filter(|&k| unresolved[k]).collect();
    if let (Some(w), false) = (&pooled_weights, zero.is_empty()) {
        let values: Vec<f64> = rates.iter().map(|r| r.rate.value).collect();
        let worst = largest_shift(&values, &bounds, &zero, w);
        if let Some((shift, set, wb)) = worst {
            if shift > MAX_WEIGHT_SHIFT {
                weight_refusals += 1;
                let named: Vec<String> = set
                    .into_iter()
                    .map(|k| format!("{} → {} < {:.2e}", rates[k].from, rates[k].to, bounds[k]))
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
        weight_refusals += 1;
        refusals.push(
            "the weights are undetermined: two groups of wells exchange no transition within \
             the method's resolution (each would keep the mass it starts with)"
                .into(),
        );
    }
    let valid = refusals.is_empty();
    let conditional_valid = refusals.len() == weight_refusals;
    let conditional_drifting =
        drift_refusals > 0 && refusals.len() == weight_refusals + drift_refusals;
    let replica_list: Vec<Replica> = (0..replicas)
        .map(|r| Replica {
            replica: r as u64,
            weights: off.weights(&units[r]).unwrap_or_default(),
            transitions: transitions[r * np..(r + 1) * np].to_vec(),
            paths: paths[r * nw..(r + 1) * nw].to_vec(),
        })
        .collect();
    // each replica's own mixture as pseudo-counts (the theory comparison's units): a replica
    // without weights of its own takes the pooled ones; where those are undetermined too there
    // is no mixture, and no unit (no weights are substituted)
    let nb = spec.bins;
    let per_path_amplitude: Vec<Vec<u64>> = match &pooled_weights {
        None => vec![],
        Some(pooled) => units
            .iter()
            .zip(&replica_list)
            .map(|(u, rep)| {
                let w = if rep.weights.is_empty() {
                    pooled
                } else {
                    &rep.weights
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
            .collect(),
    };
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
            theory_wells,
            missing,
            cores,
            pilot_inside,
            rates,
            rate_matrix,
            rate_bounds: (0..np)
                .map(|k| if unresolved[k] { bounds[k] } else { f64::NAN })
                .collect(),
            weights,
            residence,
            relaxation,
            conditional_ess: conditional.iter().map(|c| c.stationarity.ess).collect(),
            conditional: conditional.into_iter().map(|c| c.amplitude).collect(),
            conditional_counts: (0..replicas)
                .map(|r| {
                    (0..nw)
                        .map(|i| quarters(&stats[r * nw + i].amplitude))
                        .collect()
                })
                .collect(),
            conditional_counts_halves: [0..QUARTERS / 2, QUARTERS / 2..QUARTERS]
                .into_iter()
                .map(|half| {
                    (0..replicas)
                        .map(|r| {
                            (0..nw)
                                .map(|i| quarters_in(&stats[r * nw + i].amplitude, half.clone()))
                                .collect()
                        })
                        .collect()
                })
                .collect(),
            valid,
            conditional_valid,
            conditional_drifting,
            refusals,
            notes,
            replicas: replica_list,
            steps,
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_bound_moves_the_weights_only_when_it_is_not_small() {
        // two wells: 0 → 1 at 1e-3, 1 → 0 unresolved: weights (0, 1)
        let w = [0.0, 1.0];
        let (shift, set, wb) = largest_shift(&[1e-3, 0.0], &[1e-3, 1e-9], &[1], &w).unwrap();
        assert_eq!(set, vec![1]);
        assert!((shift - 1e-6).abs() < 1e-9, "{shift}");
        assert!((wb[0] - 1e-6).abs() < 1e-9);
        // a bound as large as the rate out: half the mass could be in well 0
        let (shift, _, wb) = largest_shift(&[1e-3, 0.0], &[1e-3, 1e-3], &[1], &w).unwrap();
        assert!((shift - 0.5).abs() < 1e-12 && (wb[1] - 0.5).abs() < 1e-12);
        // both unresolved: each alone keeps a closed class; together they give weights
        let (shift, set, _) = largest_shift(&[0.0, 0.0], &[1.0, 3.0], &[0, 1], &w).unwrap();
        assert!(set.len() <= 2 && shift > 0.0);
    }

    /// A pilot with these shares after the burn-in; it left its well after `stay` turning
    /// points (or never), with `inside` of its own turning points in its core before.
    fn pilot(share: Vec<f64>, stay: Option<u64>, inside: f64) -> Pilot {
        Pilot {
            share,
            inside,
            stay,
            core: (0.0, 1.0),
        }
    }

    #[test]
    fn a_missing_well_is_dropped_and_a_path_in_no_well_is_refused() {
        let theory = Wells::new(vec![1.0, 5.0, 10.0], vec![3.0, 7.0]).unwrap();
        // the inner well's pilot settles in the middle well
        let pilots = vec![
            pilot(vec![0.1, 0.8, 0.0], Some(20), 0.9),
            pilot(vec![0.0, 0.9, 0.0], None, 0.9),
            pilot(vec![0.0, 0.0, 1.0], None, 1.0),
        ];
        let (kept, missing, refusals) = simulated_wells(&pilots);
        assert_eq!(kept, vec![1, 2]);
        assert_eq!(missing.len(), 1);
        assert_eq!((missing[0].well, missing[0].settled_in), (0, 1));
        assert!(refusals.is_empty());
        let w = reduced_wells(&theory, &kept, &missing).unwrap();
        assert_eq!((w.modes, w.antimodes), (vec![5.0, 10.0], vec![7.0]));
        // the middle well's pilot settles in the outer well: its region goes up
        let pilots = vec![
            pilot(vec![0.9, 0.0, 0.0], Some(5000), 0.9),
            pilot(vec![0.0, 0.2, 0.7], Some(3), 1.0),
            pilot(vec![0.0, 0.0, 1.0], None, 1.0),
        ];
        let (kept, missing, _) = simulated_wells(&pilots);
        let w = reduced_wells(&theory, &kept, &missing).unwrap();
        assert_eq!((w.modes, w.antimodes), (vec![1.0, 10.0], vec![3.0]));
        // ... or down
        let pilots = vec![
            pilot(vec![0.9, 0.0, 0.0], Some(5000), 0.9),
            pilot(vec![0.7, 0.2, 0.0], Some(99), 0.6),
            pilot(vec![0.0, 0.0, 1.0], None, 1.0),
        ];
        let (kept, missing, _) = simulated_wells(&pilots);
        let w = reduced_wells(&theory, &kept, &missing).unwrap();
        assert_eq!((w.modes, w.antimodes), (vec![1.0, 10.0], vec![7.0]));
        // a pilot between the cores: amplitudes that no well covers
        let pilots = vec![
            pilot(vec![0.9, 0.0, 0.0], Some(5000), 0.9),
            pilot(vec![0.1, 0.3, 0.1], Some(40), 0.5),
            pilot(vec![0.0, 0.0, 1.0], None, 1.0),
        ];
        let (kept, missing, refusals) = simulated_wells(&pilots);
        assert_eq!(kept, vec![0, 2]);
        assert!(missing.is_empty());
        assert!(refusals[0].contains("no well covers"), "{refusals:?}");
    }
}
