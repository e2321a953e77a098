//! What one path records, streamed: its sums per batch, its histograms per quarter, its first
//! passages between wells ([`PathStats`], the unit of merging and of checkpoints), and the
//! recorder that fills them step by step without a division on the hot path.

use super::spec::{EnsembleSpec, Wells, QUARTERS};
use crate::engine::{Barrier, Flow, Observer, Problem, Stepper, System};
use serde::{Deserialize, Serialize};

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
pub(super) struct Layout {
    pub(super) bins: usize,
    pub(super) joint_bins: usize,
    pub(super) a_scale: f64,
    pub(super) h_scale: f64,
    pub(super) u_lo: f64,
    pub(super) u_scale: f64,
    pub(super) v_lo: f64,
    pub(super) v_scale: f64,
    pub(super) inv_omega1_sq: f64,
    pub(super) omega1_sq: f64,
    pub(super) batches: usize,
    pub(super) samples: u64,
    pub(super) wells: Option<Wells>,
    pub(super) crossing: bool,
}

impl Layout {
    pub(super) fn new(spec: &EnsembleSpec, problem: &Problem, samples: u64) -> Self {
        let omega1 = problem.oscillator().equivalents().omega1;
        let a = spec.amplitude_max;
        let crossing = problem.system() == System::Zhuravlev;
        let whole_line = crossing || problem.barrier() == Barrier::Off;
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
    pub(super) fn edges(&self, max: f64) -> Vec<f64> {
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
pub(super) struct Recorder<'a> {
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
    pub(super) fn new(layout: &'a Layout, burn: u64, every: u64, path: u64, u0: f64) -> Self {
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

    /// The statistics with the path's impacts and sticking steps given (a path that was
    /// restarted from earlier states: the well method).
    pub(super) fn finish_counted(mut self, (impacts, sticking): (u64, u64)) -> PathStats {
        for (p, c) in self.stats.passages.iter_mut().zip(&self.clocks) {
            if !c.is_nan() {
                p.censored += 1;
            }
        }
        self.stats.impacts = impacts;
        self.stats.sticking_steps = sticking;
        self.stats
    }

    pub(super) fn finish(mut self, s: &Stepper) -> PathStats {
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

impl Observer for Recorder<'_> {
    #[inline]
    fn observe(&mut self, s: &Stepper) -> Flow {
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

#[cfg(test)]
mod tests {
    use super::*;

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
}
