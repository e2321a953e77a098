//! Ensembles of simulated paths and their stationary statistics, streamed: moments, densities,
//! well occupancies, first-passage times between wells, and a stationarity diagnosis.
//!
//! # Problem
//! N paths of Eq. (1) (or Eq. 5 / Eq. 9) driven by noise streams 0..N of one seed, path i from
//! U(0) = `starts[i mod len]`, U̇(0) = 0; the first `burn_in` time units are discarded, the next
//! `length` are recorded every `sample_every` steps. Nothing grows with the number of steps.
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
//! result is bit-identical whatever the number of threads, and a run resumed from saved
//! [`PathStats`] equals the uninterrupted one.
//!
//! # Tests
//! `tests/ensemble.rs`: the linear fractional oscillator's exact stationary variances
//! ([`crate::known_answers::linear_fractional_moments`]) within three standard errors at λ = 1
//! and λ < 1, white and coloured noise; thread-count invariance; resumed = uninterrupted; the
//! diagnosis flags two paths stuck in different wells.

use crate::engine::{fresh_history, Barrier, Oscillator, PredictorCorrector, Stepper, System};
use crate::error::{Error, Result};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::sync::atomic::{AtomicU64, Ordering};

/// Most paths of one ensemble.
pub const MAX_PATHS: usize = 1_000_000;
/// Most bins of a one-dimensional histogram.
pub const MAX_BINS: usize = 10_000;
/// Most bins per axis of the joint (U, U̇) histogram.
pub const MAX_JOINT_BINS: usize = 1_000;
/// Largest histogram range of the amplitude.
pub const MAX_AMPLITUDE: f64 = 1e6;
/// Most bytes of per-path statistics held at once (paths × histograms, batches, passages).
pub const MAX_STATISTICS_BYTES: usize = 4_000_000_000;
/// Quarters of a path whose histograms are kept apart (the units for one path).
const QUARTERS: usize = 4;

/// The wells of the amplitude: modes m_0 < … < m_{k} of P(A) and the antimodes between them.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Wells {
    /// Amplitudes of the maxima of P(A), ascending.
    pub modes: Vec<f64>,
    /// Amplitudes of the minima between consecutive modes (one fewer than `modes`).
    pub antimodes: Vec<f64>,
}

impl Wells {
    /// Validated wells.
    pub fn new(modes: Vec<f64>, antimodes: Vec<f64>) -> Result<Self> {
        let ok = !modes.is_empty()
            && antimodes.len() + 1 == modes.len()
            && modes
                .iter()
                .chain(&antimodes)
                .all(|x| x.is_finite() && *x >= 0.0)
            && (0..antimodes.len()).all(|i| modes[i] < antimodes[i] && antimodes[i] < modes[i + 1]);
        if !ok {
            return Err(Error::invalid(
                "wells",
                modes.len() as f64,
                "modes and antimodes alternating and ascending (one antimode between two modes)",
            ));
        }
        Ok(Wells { modes, antimodes })
    }

    /// The well of amplitude `a` (by the antimodes).
    #[inline]
    pub fn well_of(&self, a: f64) -> usize {
        self.antimodes.iter().take_while(|&&m| a > m).count()
    }

    /// The core [lo, hi] of well k: closer to the mode than half the distance to the
    /// neighbouring antimodes (unbounded toward 0 and ∞ for the outer wells).
    pub fn core(&self, k: usize) -> (f64, f64) {
        let m = self.modes[k];
        let lo = if k == 0 {
            0.0
        } else {
            m - 0.5 * (m - self.antimodes[k - 1])
        };
        let hi = if k + 1 == self.modes.len() {
            f64::INFINITY
        } else {
            m + 0.5 * (self.antimodes[k] - m)
        };
        (lo, hi)
    }

    /// The well whose core holds `a`, if any.
    fn core_of(&self, a: f64) -> Option<usize> {
        let k = self.well_of(a);
        let (lo, hi) = self.core(k);
        (a >= lo && a <= hi).then_some(k)
    }

    /// Number of wells.
    pub fn len(&self) -> usize {
        self.modes.len()
    }

    /// True when there are no wells (never for validated wells).
    pub fn is_empty(&self) -> bool {
        self.modes.is_empty()
    }
}

/// What to simulate and record: the ensemble's problem beyond the oscillator and the method.
#[derive(Debug, Clone, PartialEq)]
pub struct EnsembleSpec {
    /// Number of paths N (path i is noise stream i of the seed).
    pub paths: usize,
    /// Seed of the noise streams.
    pub seed: u64,
    /// Time discarded at the start of each path.
    pub burn_in: f64,
    /// Time recorded after the burn-in.
    pub length: f64,
    /// Initial displacements U(0), used in turn (path i starts at `starts[i % len]`, U̇ = 0).
    pub starts: Vec<f64>,
    /// Which equation.
    pub system: System,
    /// Wall on or off.
    pub barrier: Barrier,
    /// Record every k-th step of the window.
    pub sample_every: u64,
    /// Bins of the amplitude, turning-amplitude and energy histograms.
    pub bins: usize,
    /// Bins per axis of the joint (U, U̇) histogram.
    pub joint_bins: usize,
    /// Histogram range of A: [0, amplitude_max]; U in [0 or −max, max], U̇ in ±ω1·max, H up to
    /// ω1²·max²/2.
    pub amplitude_max: f64,
    /// Batches per path (for batch means and R̂; at least 4).
    pub batches: usize,
    /// Wells for occupancies and passages (from the theory), if any.
    pub wells: Option<Wells>,
    /// |U| or |U̇| above this is a blow-up.
    pub blow_up: f64,
}

impl Default for EnsembleSpec {
    fn default() -> Self {
        EnsembleSpec {
            paths: 8,
            seed: 1,
            burn_in: 100.0,
            length: 1000.0,
            starts: vec![1.0],
            system: System::Fractional,
            barrier: Barrier::On,
            sample_every: 1,
            bins: 100,
            joint_bins: 48,
            amplitude_max: 15.0,
            batches: 20,
            wells: None,
            blow_up: 1e8,
        }
    }
}

/// Whole steps of `t` at step `dt`, or an error naming `name`.
fn whole_steps(name: &str, t: f64, dt: f64, allow_zero: bool) -> Result<u64> {
    let ratio = t / dt;
    let n = ratio.round();
    let min = if allow_zero { 0.0 } else { 1.0 };
    if !(t.is_finite() && n >= min && n <= crate::engine::MAX_STEPS as f64) {
        return Err(Error::invalid(
            name,
            t,
            format!(
                "{} a whole number of steps of dt = {dt}, at most {:e} steps",
                if allow_zero { "0 or" } else { "one or more," },
                crate::engine::MAX_STEPS as f64
            ),
        ));
    }
    if (ratio - n).abs() > 1e-9 * n.max(1.0) {
        return Err(Error::invalid(
            name,
            t,
            format!(
                "a whole number of steps of dt = {dt} (nearest: {} or {})",
                crate::error::Exact(ratio.floor() * dt),
                crate::error::Exact((ratio.floor() + 1.0) * dt)
            ),
        ));
    }
    Ok(n as u64)
}

/// The checked sizes of a run.
#[derive(Debug, Clone, Copy)]
struct Sizes {
    burn: u64,
    window: u64,
    samples: u64,
}

impl EnsembleSpec {
    fn sizes(&self, dt: f64) -> Result<Sizes> {
        if self.paths == 0 || self.paths > MAX_PATHS {
            return Err(Error::invalid(
                "paths",
                self.paths as f64,
                format!("1 to {MAX_PATHS}"),
            ));
        }
        if !(2..=MAX_BINS).contains(&self.bins) {
            return Err(Error::invalid(
                "bins",
                self.bins as f64,
                format!("2 to {MAX_BINS}"),
            ));
        }
        if !(2..=MAX_JOINT_BINS).contains(&self.joint_bins) {
            return Err(Error::invalid(
                "joint_bins",
                self.joint_bins as f64,
                format!("2 to {MAX_JOINT_BINS}"),
            ));
        }
        if !(4..=1000).contains(&self.batches) {
            return Err(Error::invalid("batches", self.batches as f64, "4 to 1000"));
        }
        if !(self.amplitude_max > 0.0 && self.amplitude_max <= MAX_AMPLITUDE) {
            return Err(Error::invalid(
                "amplitude_max",
                self.amplitude_max,
                format!("(0, {MAX_AMPLITUDE:e}] (beyond it the energy's range overflows)"),
            ));
        }
        // every path's statistics are held until the merge: bound them before any work
        let wells = self.wells.as_ref().map_or(0, Wells::len);
        let per_path = 8
            * (QUARTERS * (3 * (self.bins + 1) + self.joint_bins * self.joint_bins + 1)
                + self.batches * (6 + wells)
                + 4 * wells * wells);
        let total = per_path as f64 * self.paths as f64;
        if total > MAX_STATISTICS_BYTES as f64 {
            return Err(Error::invalid(
                "paths",
                self.paths as f64,
                format!(
                    "at most {} with these bins ({per_path} bytes of statistics per path, \
                     {MAX_STATISTICS_BYTES:e} in all)",
                    MAX_STATISTICS_BYTES / per_path
                ),
            ));
        }
        if self.starts.is_empty() {
            return Err(Error::invalid("u0", f64::NAN, "at least one start"));
        }
        for &u in &self.starts {
            let wall = self.barrier == Barrier::On && self.system != System::Zhuravlev;
            if !u.is_finite() || (wall && u < 0.0) || u.abs() >= self.blow_up {
                return Err(Error::invalid(
                    "u0",
                    u,
                    if wall {
                        "[0, blow-up threshold) with the barrier on"
                    } else {
                        "finite, below the blow-up threshold"
                    },
                ));
            }
        }
        if self.sample_every == 0 {
            return Err(Error::invalid("sample_every", 0.0, "1 or more"));
        }
        let burn = whole_steps("burn_in", self.burn_in, dt, true)?;
        let window = whole_steps("t_end", self.length, dt, false)?;
        if burn + window > crate::engine::MAX_STEPS {
            return Err(Error::invalid(
                "t_end",
                self.length,
                format!(
                    "burn-in and window together at most {:e} steps",
                    crate::engine::MAX_STEPS as f64
                ),
            ));
        }
        let samples = window / self.sample_every;
        if samples < 4 * self.batches as u64 {
            return Err(Error::invalid(
                "t_end",
                self.length,
                format!(
                    "long enough for {} samples (4 per batch; {samples} with sample_every = {})",
                    4 * self.batches,
                    self.sample_every
                ),
            ));
        }
        Ok(Sizes {
            burn,
            window,
            samples,
        })
    }
}

/// Sums of one batch of samples.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct BatchSums {
    /// Samples.
    pub n: u64,
    /// Σ U, Σ U², Σ U̇, Σ U̇², Σ A.
    pub u: f64,
    /// Σ U².
    pub u2: f64,
    /// Σ U̇.
    pub v: f64,
    /// Σ U̇².
    pub v2: f64,
    /// Σ A.
    pub a: f64,
    /// Samples in each well (by A between antimodes).
    pub wells: Vec<u64>,
}

/// First-passage sums i → j of one path.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct PassageSums {
    /// Completed passages.
    pub count: u64,
    /// Σ time, Σ time².
    pub time: f64,
    /// Σ time².
    pub time2: f64,
    /// Passages still running at the end of the window.
    pub censored: u64,
}

/// Everything one path contributes: the unit of merging, of standard errors and of
/// checkpoints (serialisable; restored bit for bit).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PathStats {
    /// Path index (noise stream).
    pub path: u64,
    /// U(0).
    pub u0: f64,
    /// Per batch.
    pub batches: Vec<BatchSums>,
    /// Amplitude histogram per quarter (bins, then the count beyond the range).
    pub amplitude: Vec<Vec<u64>>,
    /// Energy histogram per quarter (bins, then beyond).
    pub energy: Vec<Vec<u64>>,
    /// Turning-point amplitude histogram per quarter (bins, then beyond).
    pub turning: Vec<Vec<u64>>,
    /// Joint (U, U̇) histogram per quarter, row-major (U index × U̇ bins + U̇ index), then the
    /// count outside.
    pub joint: Vec<Vec<u64>>,
    /// First passages, row-major [from × wells + to].
    pub passages: Vec<PassageSums>,
    /// Impacts and sticking steps over the whole path (burn-in included).
    pub impacts: u64,
    /// Steps that ended clamped at the wall.
    pub sticking_steps: u64,
}

/// Layout shared by every path's recorder.
#[derive(Debug, Clone)]
struct Layout {
    bins: usize,
    joint_bins: usize,
    a_scale: f64,
    h_scale: f64,
    u_lo: f64,
    u_scale: f64,
    v_lo: f64,
    v_scale: f64,
    inv_omega1_sq: f64,
    omega1_sq: f64,
    batches: usize,
    samples: u64,
    wells: Option<Wells>,
    crossing: bool,
}

impl Layout {
    fn new(spec: &EnsembleSpec, omega1: f64, samples: u64) -> Self {
        let a = spec.amplitude_max;
        let crossing = spec.system == System::Zhuravlev;
        let whole_line = crossing || spec.barrier == Barrier::Off;
        let u_lo = if whole_line { -a } else { 0.0 };
        let jb = spec.joint_bins as f64;
        Layout {
            bins: spec.bins,
            joint_bins: spec.joint_bins,
            a_scale: spec.bins as f64 / a,
            h_scale: spec.bins as f64 / (0.5 * omega1 * omega1 * a * a),
            u_lo,
            u_scale: jb / (a - u_lo),
            v_lo: -omega1 * a,
            v_scale: jb / (2.0 * omega1 * a),
            inv_omega1_sq: 1.0 / (omega1 * omega1),
            omega1_sq: omega1 * omega1,
            batches: spec.batches,
            samples,
            wells: spec.wells.clone(),
            crossing,
        }
    }

    /// Edges of the amplitude histogram.
    fn edges(&self, max: f64) -> Vec<f64> {
        (0..=self.bins)
            .map(|i| max * i as f64 / self.bins as f64)
            .collect()
    }
}

/// Bin of x·scale in 0..n, or n (beyond).
#[inline]
fn bin(x: f64, scale: f64, n: usize) -> usize {
    let b = x * scale;
    if b >= 0.0 && b < n as f64 {
        b as usize
    } else {
        n
    }
}

/// First window step k (1-based) of quarter q: the smallest k with 4(k − 1) ≥ q·len.
fn quarter_start(q: usize, len: u64) -> u64 {
    if q >= QUARTERS {
        return u64::MAX;
    }
    (q as u64 * len).div_ceil(QUARTERS as u64) + 1
}

/// First sample (0-based) of batch b of `batches` over `samples`: the smallest i with
/// i·batches ≥ b·samples.
fn batch_start(b: usize, batches: usize, samples: u64) -> u64 {
    if b >= batches {
        return u64::MAX;
    }
    (b as u64 * samples).div_ceil(batches as u64)
}

/// Streams the statistics of one path.
/// Counters replace divisions on the hot path: the window step k, the steps to the next sample,
/// the quarter and batch in force with the step / sample at which the next one begins.
struct Recorder<'a> {
    layout: &'a Layout,
    burn: u64,
    every: u64,
    sample: u64,
    /// Window steps so far (k = n − burn).
    k: u64,
    until_sample: u64,
    quarter: usize,
    next_quarter: u64,
    batch: usize,
    next_batch: u64,
    stats: PathStats,
    /// sgn(Z)·U̇ of the previous node (the direction of |U|).
    rising: bool,
    state: Option<usize>,
    /// Start time of the running passage i → j (NaN when none), row-major.
    clocks: Vec<f64>,
}

impl<'a> Recorder<'a> {
    fn new(layout: &'a Layout, burn: u64, every: u64, path: u64, u0: f64) -> Self {
        let nw = layout.wells.as_ref().map_or(0, Wells::len);
        let q = |n: usize| vec![vec![0u64; n + 1]; QUARTERS];
        Recorder {
            layout,
            burn,
            every,
            sample: 0,
            k: 0,
            until_sample: every,
            quarter: 0,
            next_quarter: quarter_start(1, every * layout.samples),
            batch: 0,
            next_batch: batch_start(1, layout.batches, layout.samples),
            stats: PathStats {
                path,
                u0,
                batches: vec![
                    BatchSums {
                        wells: vec![0; nw],
                        ..Default::default()
                    };
                    layout.batches
                ],
                amplitude: q(layout.bins),
                energy: q(layout.bins),
                turning: q(layout.bins),
                joint: q(layout.joint_bins * layout.joint_bins),
                passages: vec![PassageSums::default(); nw * nw],
                impacts: 0,
                sticking_steps: 0,
            },
            rising: false,
            state: None,
            clocks: vec![f64::NAN; nw * nw],
        }
    }

    /// A turning point of amplitude `a` at time t: update the well state and the passages.
    fn turning_point(&mut self, a: f64, t: f64, quarter: usize) {
        let l = self.layout;
        self.stats.turning[quarter][bin(a, l.a_scale, l.bins)] += 1;
        let Some(w) = &l.wells else { return };
        let Some(k) = w.core_of(a) else { return };
        if self.state == Some(k) {
            return;
        }
        let n = w.len();
        // arriving in k ends every running passage into k …
        for i in 0..n {
            let c = &mut self.clocks[i * n + k];
            if !c.is_nan() {
                let dt = t - *c;
                let p = &mut self.stats.passages[i * n + k];
                p.count += 1;
                p.time += dt;
                p.time2 += dt * dt;
                *c = f64::NAN;
            }
        }
        // … and starts k → j for every j not already timed from an earlier entry into k
        for j in 0..n {
            if j != k && self.clocks[k * n + j].is_nan() {
                self.clocks[k * n + j] = t;
            }
        }
        self.state = Some(k);
    }

    fn finish(mut self, s: &Stepper) -> PathStats {
        for (p, c) in self.stats.passages.iter_mut().zip(&self.clocks) {
            if !c.is_nan() {
                p.censored += 1;
            }
        }
        self.stats.impacts = s.impacts();
        self.stats.sticking_steps = s.sticking_steps();
        self.stats
    }
}

impl crate::engine::Observer for Recorder<'_> {
    #[inline]
    fn observe(&mut self, s: &Stepper) -> crate::engine::Flow {
        use crate::engine::Flow;
        let n = s.steps();
        if n <= self.burn {
            if n == self.burn {
                self.rising = s.u().signum() * s.v() > 0.0;
            }
            return Flow::Continue;
        }
        let (u, v) = (s.u(), s.v());
        let l = self.layout;
        self.k += 1;
        if self.k >= self.next_quarter {
            self.quarter += 1;
            self.next_quarter = quarter_start(self.quarter + 1, self.every * l.samples);
        }
        let quarter = self.quarter;
        // turning points of |U| are looked for at every step of the window
        let side = if l.crossing { u.signum() } else { 1.0 };
        let rising = side * v > 0.0;
        if self.rising && !rising {
            self.turning_point(u.abs(), s.time(), quarter);
        }
        self.rising = rising;
        self.until_sample -= 1;
        if self.until_sample != 0 {
            return Flow::Continue;
        }
        self.until_sample = self.every;
        if self.sample >= l.samples {
            return Flow::Continue;
        }
        if self.sample >= self.next_batch {
            self.batch += 1;
            self.next_batch = batch_start(self.batch + 1, l.batches, l.samples);
        }
        let b = self.batch;
        self.sample += 1;
        let a2 = u * u + v * v * l.inv_omega1_sq;
        let a = a2.sqrt();
        let st = &mut self.stats;
        let batch = &mut st.batches[b];
        batch.n += 1;
        batch.u += u;
        batch.u2 += u * u;
        batch.v += v;
        batch.v2 += v * v;
        batch.a += a;
        if let Some(w) = &l.wells {
            batch.wells[w.well_of(a)] += 1;
        }
        st.amplitude[quarter][bin(a, l.a_scale, l.bins)] += 1;
        st.energy[quarter][bin(0.5 * l.omega1_sq * a2, l.h_scale, l.bins)] += 1;
        let jb = l.joint_bins;
        let iu = bin(u - l.u_lo, l.u_scale, jb);
        let iv = bin(v - l.v_lo, l.v_scale, jb);
        let cell = if iu < jb && iv < jb {
            iu * jb + iv
        } else {
            jb * jb
        };
        st.joint[quarter][cell] += 1;
        Flow::Continue
    }
}

/// A value with its standard error.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Estimate {
    /// The estimate.
    pub value: f64,
    /// Its standard error (NaN when there is a single unit).
    pub stderr: f64,
}

impl Estimate {
    /// No estimate: value and standard error NaN.
    pub fn undefined() -> Self {
        Estimate {
            value: f64::NAN,
            stderr: f64::NAN,
        }
    }
}

/// Delete-one jackknife of `f` over units: `f` gets the sums over all units but one (or all).
fn jackknife(units: &[Vec<f64>], f: impl Fn(&[f64]) -> f64) -> Estimate {
    let m = units.first().map_or(0, Vec::len);
    let mut total = vec![0.0; m];
    for u in units {
        for (t, x) in total.iter_mut().zip(u) {
            *t += x;
        }
    }
    let value = f(&total);
    let n = units.len();
    if n < 2 {
        return Estimate {
            value,
            stderr: f64::NAN,
        };
    }
    let mut rest = vec![0.0; m];
    let loo: Vec<f64> = units
        .iter()
        .map(|u| {
            for ((r, t), x) in rest.iter_mut().zip(&total).zip(u) {
                *r = t - x;
            }
            f(&rest)
        })
        .collect();
    let mean = loo.iter().sum::<f64>() / n as f64;
    let ss: f64 = loo.iter().map(|x| (x - mean) * (x - mean)).sum();
    Estimate {
        value,
        stderr: ((n as f64 - 1.0) / n as f64 * ss).sqrt(),
    }
}

/// A histogram normalised to a density over the whole sample, with standard errors.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Density {
    /// Bin edges.
    pub edges: Vec<f64>,
    /// Density in each bin (count / (total·width)).
    pub density: Vec<f64>,
    /// Standard error of each bin's density (NaN with a single unit).
    pub stderr: Vec<f64>,
    /// Fraction of the samples beyond the last edge.
    pub beyond: f64,
    /// Number of samples (or turning points).
    pub count: u64,
}

/// The fraction of all samples in each bin (the units' counts; the last entry is the mass
/// beyond the grid) with its delete-one jackknife standard error over the units (NaN with one
/// unit), in O(units × bins).
fn fractions(units: &[Vec<u64>]) -> (Vec<f64>, Vec<f64>) {
    let m = units.first().map_or(0, Vec::len);
    let mut total = vec![0u64; m];
    for u in units {
        for (t, c) in total.iter_mut().zip(u) {
            *t += c;
        }
    }
    let all: u64 = total.iter().sum();
    let value: Vec<f64> = total
        .iter()
        .map(|&t| if all > 0 { t as f64 / all as f64 } else { 0.0 })
        .collect();
    let n = units.len();
    let mut stderr = vec![f64::NAN; m];
    if n >= 2 {
        let sizes: Vec<u64> = units.iter().map(|u| u.iter().sum()).collect();
        let mut loo = vec![0.0; n];
        for (b, se) in stderr.iter_mut().enumerate() {
            for ((x, u), &size) in loo.iter_mut().zip(units).zip(&sizes) {
                let rest = all - size;
                *x = if rest > 0 {
                    (total[b] - u[b]) as f64 / rest as f64
                } else {
                    0.0
                };
            }
            let mean = loo.iter().sum::<f64>() / n as f64;
            let ss: f64 = loo.iter().map(|x| (x - mean) * (x - mean)).sum();
            *se = ((n as f64 - 1.0) / n as f64 * ss).sqrt();
        }
    }
    (value, stderr)
}

impl Density {
    fn from_units(edges: Vec<f64>, units: &[Vec<u64>]) -> Self {
        let nb = edges.len() - 1;
        let (fraction, se) = fractions(units);
        let width = |b: usize| edges[b + 1] - edges[b];
        Density {
            density: (0..nb).map(|b| fraction[b] / width(b)).collect(),
            stderr: (0..nb).map(|b| se[b] / width(b)).collect(),
            beyond: fraction[nb],
            count: units.iter().flatten().sum(),
            edges,
        }
    }
}

/// The joint density of (U, U̇).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct JointDensity {
    /// Edges in U.
    pub u_edges: Vec<f64>,
    /// Edges in U̇.
    pub v_edges: Vec<f64>,
    /// Density, row-major: `density[i][j]` for U bin i and U̇ bin j.
    pub density: Vec<Vec<f64>>,
    /// Standard error of each cell's density (jackknife over the units; NaN with one unit).
    pub stderr: Vec<Vec<f64>>,
    /// Fraction of the samples outside the grid.
    pub outside: f64,
}

/// First passages i → j, pooled over paths.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Passage {
    /// Well left.
    pub from: usize,
    /// Well reached.
    pub to: usize,
    /// Completed passages.
    pub count: u64,
    /// Passages still running at the end.
    pub censored: u64,
    /// Mean first-passage time with its standard error (NaN when none completed; the
    /// standard error treats passages as independent).
    pub mean_time: Estimate,
}

/// The stationarity diagnosis.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Stationarity {
    /// Split-R̂ of the mean amplitude.
    pub r_hat_amplitude: f64,
    /// Split-R̂ of each well's occupancy (NaN for a well never or always occupied).
    pub r_hat_wells: Vec<f64>,
    /// The largest of them (the verdict's R̂).
    pub r_hat: f64,
    /// Effective sample size of the mean amplitude.
    pub ess: f64,
    /// (second half − first half) of the mean amplitude, and that in standard errors.
    pub drift: f64,
    /// The drift in standard errors.
    pub drift_z: f64,
    /// R̂ ≤ 1.1 everywhere and |drift_z| ≤ 3.
    pub stationary: bool,
    /// Window length that the R̂ scaling suggests for R̂ ≤ 1.1 (the length used when passed).
    pub suggested_length: f64,
}

/// The result of an ensemble.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct EnsembleResult {
    /// Paths run.
    pub paths: usize,
    /// Steps per path (burn-in and window).
    pub steps_per_path: u64,
    /// Burn-in steps.
    pub burn_in_steps: u64,
    /// Samples recorded per path.
    pub samples_per_path: u64,
    /// ω1 used for A = √(U² + U̇²/ω1²).
    pub omega1: f64,
    /// Standard errors are between paths (true) or between batches of one path (false).
    pub between_paths: bool,
    /// ⟨U⟩, Var U, ⟨U̇⟩, Var U̇, ⟨A⟩.
    pub mean_u: Estimate,
    /// Var U.
    pub var_u: Estimate,
    /// ⟨U̇⟩.
    pub mean_v: Estimate,
    /// Var U̇.
    pub var_v: Estimate,
    /// ⟨A⟩.
    pub mean_amplitude: Estimate,
    /// Density of A on [0, amplitude_max].
    pub amplitude: Density,
    /// Density of the turning-point amplitude.
    pub turning: Density,
    /// Density of H = U̇²/2 + ω1²U²/2.
    pub energy: Density,
    /// Joint density of (U, U̇).
    pub joint: JointDensity,
    /// The wells used, if any.
    pub wells: Option<Wells>,
    /// Fraction of samples in each well.
    pub occupancy: Vec<Estimate>,
    /// First passages between wells (every ordered pair).
    pub passages: Vec<Passage>,
    /// The diagnosis.
    pub stationarity: Stationarity,
    /// Impacts and sticking steps, all paths.
    pub impacts: u64,
    /// Sticking steps, all paths.
    pub sticking_steps: u64,
    /// Plain-language warnings (non-stationary, mass outside the histograms, few passages, …).
    pub warnings: Vec<String>,
    /// Per path amplitude histograms (for the bootstrap of theory distances).
    pub per_path_amplitude: Vec<Vec<u64>>,
}

/// Split-R̂ over chains of draws.
fn split_r_hat(chains: &[Vec<f64>]) -> f64 {
    let halves: Vec<&[f64]> = chains
        .iter()
        .flat_map(|c| {
            let h = c.len() / 2;
            [&c[..h], &c[c.len() - h..]]
        })
        .filter(|h| h.len() >= 2)
        .collect();
    let m = halves.len();
    if m < 2 {
        return f64::NAN;
    }
    let n = halves[0].len() as f64;
    let means: Vec<f64> = halves
        .iter()
        .map(|h| h.iter().sum::<f64>() / h.len() as f64)
        .collect();
    let w = halves
        .iter()
        .zip(&means)
        .map(|(h, &mu)| h.iter().map(|x| (x - mu) * (x - mu)).sum::<f64>() / (n - 1.0))
        .sum::<f64>()
        / m as f64;
    let grand = means.iter().sum::<f64>() / m as f64;
    let b = n * means.iter().map(|x| (x - grand) * (x - grand)).sum::<f64>() / (m as f64 - 1.0);
    if w == 0.0 {
        return if b == 0.0 { f64::NAN } else { f64::INFINITY };
    }
    (((n - 1.0) / n * w + b / n) / w).sqrt()
}

/// Run the ensemble: paths not in `done` are simulated in parallel (path i's finished
/// statistics are handed to `on_path` — e.g. to checkpoint them), then all are merged in path
/// order. `progress` receives the fraction of steps done.
pub fn run_ensemble(
    oscillator: &Oscillator,
    method: &PredictorCorrector,
    spec: &EnsembleSpec,
    done: &[PathStats],
    on_path: &(dyn Fn(&PathStats) -> Result<()> + Sync),
    progress: crate::engine::Progress,
) -> Result<EnsembleResult> {
    let sizes = spec.sizes(method.dt)?;
    let steps = sizes.burn + sizes.window;
    let omega1 = oscillator.equivalents().omega1;
    let layout = Layout::new(spec, omega1, sizes.samples);
    // the verified SOE kernel is built once for all paths
    let history = fresh_history(oscillator, method, spec.system, steps as f64 * method.dt)?;
    let todo: Vec<u64> = (0..spec.paths as u64)
        .filter(|i| !done.iter().any(|d| d.path == *i))
        .collect();
    let total = (todo.len() as u64 * steps).max(1) as f64;
    let counter = AtomicU64::new(0);
    let tick = 1u64 << 16;
    let fresh: Vec<PathStats> = todo
        .par_iter()
        .map(|&i| {
            let u0 = spec.starts[i as usize % spec.starts.len()];
            let mut s = Stepper::with_history(
                oscillator,
                method,
                spec.system,
                spec.barrier,
                (u0, 0.0),
                (spec.seed, i),
                history.clone(),
                spec.blow_up,
            )?;
            let mut rec = Recorder::new(&layout, sizes.burn, spec.sample_every, i, u0);
            let mut observe = |st: &Stepper| {
                let f = crate::engine::Observer::observe(&mut rec, st);
                if st.steps() % tick == 0 {
                    let d = counter.fetch_add(tick, Ordering::Relaxed) + tick;
                    if let Some(p) = progress {
                        p(d as f64 / total);
                    }
                }
                f
            };
            crate::engine::run(&mut s, steps, &mut observe, None).map_err(|e| Error::InPath {
                path: i,
                u0,
                error: Box::new(e),
            })?;
            let stats = rec.finish(&s);
            on_path(&stats)?;
            Ok(stats)
        })
        .collect::<Result<_>>()?;
    let mut all: Vec<PathStats> = done.iter().cloned().chain(fresh).collect();
    all.sort_by_key(|p| p.path);
    all.dedup_by_key(|p| p.path);
    if all.len() != spec.paths {
        return Err(Error::invalid(
            "paths",
            all.len() as f64,
            format!(
                "{} paths (saved statistics belong to another run)",
                spec.paths
            ),
        ));
    }
    Ok(merge(spec, &layout, &sizes, omega1, steps, &all))
}

fn merge(
    spec: &EnsembleSpec,
    layout: &Layout,
    sizes: &Sizes,
    omega1: f64,
    steps: u64,
    all: &[PathStats],
) -> EnsembleResult {
    let between = all.len() >= 2;
    let nb = spec.batches;
    // units for moments: paths, or the batches of the single path
    let batch_units: Vec<Vec<f64>> = if between {
        all.iter()
            .map(|p| {
                let mut s = [0.0; 6];
                for b in &p.batches {
                    for (x, y) in s.iter_mut().zip([b.n as f64, b.u, b.u2, b.v, b.v2, b.a]) {
                        *x += y;
                    }
                }
                s.to_vec()
            })
            .collect()
    } else {
        all[0]
            .batches
            .iter()
            .map(|b| vec![b.n as f64, b.u, b.u2, b.v, b.v2, b.a])
            .collect()
    };
    let mean_u = jackknife(&batch_units, |t| t[1] / t[0]);
    let var_u = jackknife(&batch_units, |t| t[2] / t[0] - (t[1] / t[0]).powi(2));
    let mean_v = jackknife(&batch_units, |t| t[3] / t[0]);
    let var_v = jackknife(&batch_units, |t| t[4] / t[0] - (t[3] / t[0]).powi(2));
    let mean_amplitude = jackknife(&batch_units, |t| t[5] / t[0]);

    let hist_units = |get: &dyn Fn(&PathStats) -> &Vec<Vec<u64>>| -> Vec<Vec<u64>> {
        if between {
            all.iter()
                .map(|p| {
                    let q = get(p);
                    let mut s = vec![0u64; q[0].len()];
                    for h in q {
                        for (x, y) in s.iter_mut().zip(h) {
                            *x += y;
                        }
                    }
                    s
                })
                .collect()
        } else {
            get(&all[0]).clone()
        }
    };
    let a_max = spec.amplitude_max;
    let amp_units = hist_units(&|p| &p.amplitude);
    let amplitude = Density::from_units(layout.edges(a_max), &amp_units);
    let turning = Density::from_units(layout.edges(a_max), &hist_units(&|p| &p.turning));
    let h_max = 0.5 * omega1 * omega1 * a_max * a_max;
    let energy = Density::from_units(layout.edges(h_max), &hist_units(&|p| &p.energy));
    let joint_units = hist_units(&|p| &p.joint);
    let jb = layout.joint_bins;
    let (fraction, se) = fractions(&joint_units);
    let (du, dv) = (1.0 / layout.u_scale, 1.0 / layout.v_scale);
    let cells = |x: &[f64]| -> Vec<Vec<f64>> {
        x[..jb * jb]
            .chunks(jb)
            .map(|row| row.iter().map(|f| f / (du * dv)).collect())
            .collect()
    };
    let joint = JointDensity {
        u_edges: (0..=jb).map(|i| layout.u_lo + du * i as f64).collect(),
        v_edges: (0..=jb).map(|i| layout.v_lo + dv * i as f64).collect(),
        density: cells(&fraction),
        stderr: cells(&se),
        outside: fraction[jb * jb],
    };

    // wells
    let nw = spec.wells.as_ref().map_or(0, Wells::len);
    let well_units: Vec<Vec<f64>> = if between {
        all.iter()
            .map(|p| {
                let mut s = vec![0.0; nw + 1];
                for b in &p.batches {
                    s[0] += b.n as f64;
                    for (k, &c) in b.wells.iter().enumerate() {
                        s[k + 1] += c as f64;
                    }
                }
                s
            })
            .collect()
    } else {
        all[0]
            .batches
            .iter()
            .map(|b| {
                std::iter::once(b.n as f64)
                    .chain(b.wells.iter().map(|&c| c as f64))
                    .collect()
            })
            .collect()
    };
    let occupancy: Vec<Estimate> = (0..nw)
        .map(|k| jackknife(&well_units, |t| t[k + 1] / t[0]))
        .collect();
    let mut passages = Vec::new();
    for i in 0..nw {
        for j in 0..nw {
            if i == j {
                continue;
            }
            let (mut c, mut s, mut s2, mut cens) = (0u64, 0.0, 0.0, 0u64);
            for p in all {
                let x = &p.passages[i * nw + j];
                c += x.count;
                s += x.time;
                s2 += x.time2;
                cens += x.censored;
            }
            let mean = if c > 0 { s / c as f64 } else { f64::NAN };
            let stderr = if c > 1 {
                let var = (s2 / c as f64 - mean * mean).max(0.0) * c as f64 / (c as f64 - 1.0);
                (var / c as f64).sqrt()
            } else {
                f64::NAN
            };
            passages.push(Passage {
                from: i,
                to: j,
                count: c,
                censored: cens,
                mean_time: Estimate {
                    value: mean,
                    stderr,
                },
            });
        }
    }

    // stationarity: chains of batch means per path
    let chains = |f: &dyn Fn(&BatchSums) -> f64| -> Vec<Vec<f64>> {
        all.iter()
            .map(|p| p.batches.iter().filter(|b| b.n > 0).map(f).collect())
            .collect()
    };
    let r_hat_amplitude = split_r_hat(&chains(&|b| b.a / b.n as f64));
    let r_hat_wells: Vec<f64> = (0..nw)
        .map(|k| split_r_hat(&chains(&|b| b.wells[k] as f64 / b.n as f64)))
        .collect();
    let r_hat = std::iter::once(r_hat_amplitude)
        .chain(r_hat_wells.iter().copied())
        .filter(|x| !x.is_nan())
        .fold(f64::NAN, |m, x| if m.is_nan() || x > m { x } else { m });
    // ESS of the mean amplitude from batch means
    let n_total: f64 = all
        .iter()
        .flat_map(|p| &p.batches)
        .map(|b| b.n as f64)
        .sum();
    let bm: Vec<f64> = all
        .iter()
        .flat_map(|p| &p.batches)
        .filter(|b| b.n > 0)
        .map(|b| b.a / b.n as f64)
        .collect();
    let grand = mean_amplitude.value;
    let s2_batch = bm.iter().map(|x| (x - grand).powi(2)).sum::<f64>() / (bm.len() as f64 - 1.0);
    // Var A = ⟨A²⟩ − ⟨A⟩², ⟨A²⟩ = ⟨U²⟩ + ⟨U̇²⟩/ω1²
    let a2 = (var_u.value + mean_u.value.powi(2))
        + (var_v.value + mean_v.value.powi(2)) * layout.inv_omega1_sq;
    let var_a = (a2 - grand * grand).max(0.0);
    let ess = if s2_batch > 0.0 {
        (var_a * bm.len() as f64 / s2_batch).min(n_total)
    } else {
        n_total
    };
    // drift between the halves, paired per path (or batches of one path)
    let half = nb / 2;
    let half_means = |p: &PathStats, r: std::ops::Range<usize>| {
        let (n, a) = p.batches[r]
            .iter()
            .fold((0.0, 0.0), |(n, a), b| (n + b.n as f64, a + b.a));
        a / n
    };
    let diffs: Vec<f64> = if between {
        all.iter()
            .map(|p| half_means(p, half..nb) - half_means(p, 0..half))
            .collect()
    } else {
        // pairs of batches, one from each half
        let p = &all[0];
        (0..half)
            .map(|k| half_means(p, half + k..half + k + 1) - half_means(p, k..k + 1))
            .collect()
    };
    let dn = diffs.len() as f64;
    let drift = diffs.iter().sum::<f64>() / dn;
    let dsd = (diffs.iter().map(|d| (d - drift).powi(2)).sum::<f64>() / (dn - 1.0)).sqrt();
    let drift_z = if dsd > 0.0 {
        drift / (dsd / dn.sqrt())
    } else if drift == 0.0 {
        0.0
    } else {
        f64::INFINITY
    };
    let rh_ok = r_hat.is_nan() || r_hat <= 1.1;
    let stationary = rh_ok && drift_z.abs() <= 3.0;
    let suggested_length = if r_hat.is_finite() && r_hat > 1.1 {
        spec.length * (r_hat * r_hat - 1.0) / (1.1f64 * 1.1 - 1.0)
    } else if r_hat.is_infinite() {
        f64::INFINITY
    } else if !stationary {
        4.0 * spec.length
    } else {
        spec.length
    };

    let mut warnings = Vec::new();
    if !stationary {
        warnings.push(format!(
            "not stationary: R̂ = {r_hat:.3} (≤ 1.1 needed), drift between the halves {drift_z:.1} \
             standard errors (≤ 3 needed); densities and moments are not stationary results. \
             Suggested window length: {}",
            if suggested_length.is_finite() {
                format!("{suggested_length:.0} or more")
            } else {
                "unknown — the paths never left their wells".into()
            }
        ));
    }
    if !between {
        warnings.push(
            "one path: standard errors are batch means within it (valid only if a batch is much \
             longer than the correlation time); use two or more paths"
                .into(),
        );
    }
    if ess < 100.0 {
        warnings.push(format!(
            "effective sample size of the mean amplitude is {ess:.0} (< 100)"
        ));
    }
    for (name, d) in [("A", &amplitude), ("H", &energy)] {
        if d.beyond > 1e-3 {
            warnings.push(format!(
                "{:.2}% of the samples have {name} beyond the histogram (raise the amplitude range)",
                100.0 * d.beyond
            ));
        }
    }
    if joint.outside > 1e-3 {
        warnings.push(format!(
            "{:.2}% of the samples lie outside the joint (U, U̇) grid",
            100.0 * joint.outside
        ));
    }
    for p in &passages {
        if p.count < 10 && p.count + p.censored > 0 {
            warnings.push(format!(
                "first passage {} → {}: {} completed, {} censored: the mean is not reliable",
                p.from, p.to, p.count, p.censored
            ));
        }
    }
    EnsembleResult {
        paths: all.len(),
        steps_per_path: steps,
        burn_in_steps: sizes.burn,
        samples_per_path: sizes.samples,
        omega1,
        between_paths: between,
        mean_u,
        var_u,
        mean_v,
        var_v,
        mean_amplitude,
        amplitude,
        turning,
        energy,
        joint,
        wells: spec.wells.clone(),
        occupancy,
        passages,
        stationarity: Stationarity {
            r_hat_amplitude,
            r_hat_wells,
            r_hat,
            ess,
            drift,
            drift_z,
            stationary,
            suggested_length,
        },
        impacts: all.iter().map(|p| p.impacts).sum(),
        sticking_steps: all.iter().map(|p| p.sticking_steps).sum(),
        warnings,
        per_path_amplitude: amp_units,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn jackknife_of_a_mean_is_the_standard_error_of_the_mean() {
        let xs = [1.0, 2.0, 4.0, 7.0, 11.0];
        let units: Vec<Vec<f64>> = xs.iter().map(|&x| vec![1.0, x]).collect();
        let e = jackknife(&units, |t| t[1] / t[0]);
        let n = xs.len() as f64;
        let mean = xs.iter().sum::<f64>() / n;
        let sd = (xs.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt();
        assert!((e.value - mean).abs() < 1e-14);
        assert!((e.stderr - sd / n.sqrt()).abs() < 1e-12, "{e:?}");
    }

    #[test]
    fn r_hat_is_one_for_identical_chains_and_infinite_for_frozen_different_ones() {
        let a: Vec<f64> = (0..20).map(|i| ((i * 7) % 5) as f64).collect();
        let r = split_r_hat(&[a.clone(), a.clone(), a]);
        assert!(r < 1.05, "{r}");
        let r = split_r_hat(&[vec![1.0; 20], vec![0.0; 20]]);
        assert!(r.is_infinite());
    }

    #[test]
    fn counters_give_the_quarters_and_batches_of_the_divisions() {
        for (len, batches, samples) in [(40u64, 20usize, 40u64), (1003, 7, 1003), (4, 4, 4)] {
            let mut q = 0;
            let mut next = quarter_start(1, len);
            for k in 1..=len {
                if k >= next {
                    q += 1;
                    next = quarter_start(q + 1, len);
                }
                let by_division = (((k - 1) * 4) / len).min(3) as usize;
                assert_eq!(q, by_division, "k = {k} of {len}");
            }
            let mut b = 0;
            let mut next = batch_start(1, batches, samples);
            for i in 0..samples {
                if i >= next {
                    b += 1;
                    next = batch_start(b + 1, batches, samples);
                }
                assert_eq!(b, ((i * batches as u64) / samples) as usize, "sample {i}");
            }
        }
    }

    #[test]
    fn wells_assign_amplitudes_and_cores() {
        let w = Wells::new(vec![1.0, 4.0, 9.0], vec![2.0, 6.0]).unwrap();
        assert_eq!(w.well_of(0.5), 0);
        assert_eq!(w.well_of(2.5), 1);
        assert_eq!(w.well_of(7.0), 2);
        assert_eq!(w.core(1), (3.0, 5.0));
        assert_eq!(w.core_of(5.5), None);
        assert_eq!(w.core_of(100.0), Some(2));
        assert!(Wells::new(vec![1.0, 0.5], vec![2.0]).is_err());
    }
}
