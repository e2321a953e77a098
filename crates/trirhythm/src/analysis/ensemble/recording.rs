//! What one path records, streamed: its sums per batch, its histograms per quarter, its first
//! passages between wells ([`PathStats`], the unit of merging and of checkpoints), and the
//! recorder that fills them step by step without a division on the hot path: its histograms
//! in one flat array (the current quarter's rows at offsets set when the quarter changes),
//! bins found by one multiply, two comparisons with the bin count as a double (computed once)
//! and one truncation to a signed integer, then handed out as [`PathStats`]' histograms at the
//! end. The bins are those of the plain `(x·scale) as usize` (unit test), and the ensembles'
//! results are bit-identical (`tests/ensemble.rs`, the CLI's golden outputs).

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
    /// `bins` and `joint_bins` as doubles (the bins' upper limits on the hot path).
    bins_f: f64,
    joint_bins_f: f64,
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
            v_lo: -omega1 * a * spec.joint_velocity_factor,
            v_scale: jb / (2.0 * omega1 * a * spec.joint_velocity_factor),
            inv_omega1_sq: 1.0 / (omega1 * omega1),
            omega1_sq: omega1 * omega1,
            batches: spec.batches,
            samples,
            wells: spec.wells.clone(),
            crossing,
            bins_f: spec.bins as f64,
            joint_bins_f: jb,
        }
    }

    /// Edges of the amplitude histogram.
    pub(super) fn edges(&self, max: f64) -> Vec<f64> {
        (0..=self.bins)
            .map(|i| max * i as f64 / self.bins as f64)
            .collect()
    }
}

/// Bin of x·scale in 0..n, or n (beyond); `nf` is n as a double.
#[inline(always)]
fn bin(x: f64, scale: f64, n: usize, nf: f64) -> usize {
    let b = x * scale;
    if b >= 0.0 && b < nf {
        // SAFETY: 0 ≤ b < n, finite and below 2⁶³: its truncation is an i64, the same integer
        // as `b as usize` (one conversion instruction instead of the unsigned sequence)
        unsafe { b.to_int_unchecked::<i64>() as usize }
    } else {
        n
    }
}

/// One more count in cell `i` of a recorder's histograms: `i` is a row's offset ([`Rows`] of a
/// quarter in 0..4) plus a bin of that row (at most its length − 1, from [`bin`]), so it lies
/// inside the array the recorder allocated for four quarters' rows.
#[inline(always)]
fn count(counts: &mut [u64], i: usize) {
    debug_assert!(i < counts.len());
    // SAFETY: see above; the unit tests and every debug-build test check the bound
    unsafe { *counts.get_unchecked_mut(i) += 1 }
}

/// Offsets in a recorder's flat histogram array: per quarter the amplitude, energy and turning
/// rows (bins + 1 each), then the joint row (joint_bins² + 1).
#[derive(Debug, Clone, Copy)]
struct Rows {
    amplitude: usize,
    energy: usize,
    turning: usize,
    joint: usize,
}

impl Rows {
    /// The rows of quarter q.
    fn of(layout: &Layout, q: usize) -> Rows {
        let row = layout.bins + 1;
        let start = q * Rows::stride(layout);
        Rows {
            amplitude: start,
            energy: start + row,
            turning: start + 2 * row,
            joint: start + 3 * row,
        }
    }

    /// Counts of one quarter.
    fn stride(layout: &Layout) -> usize {
        3 * (layout.bins + 1) + layout.joint_bins * layout.joint_bins + 1
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
    /// The histograms' counts of every quarter ([`Rows`]), handed to `stats` at the end.
    counts: Vec<u64>,
    /// The current quarter's rows in `counts`.
    rows: Rows,
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
            counts: vec![0; QUARTERS * Rows::stride(layout)],
            rows: Rows::of(layout, 0),
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
                amplitude: vec![],
                energy: vec![],
                turning: vec![],
                joint: vec![],
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
    fn turning_point(&mut self, a: f64, t: f64) {
        let l = self.layout;
        count(
            &mut self.counts,
            self.rows.turning + bin(a, l.a_scale, l.bins, l.bins_f),
        );
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
        let l = self.layout;
        let row = |q: usize, at: fn(&Rows) -> usize, n: usize| {
            let start = at(&Rows::of(l, q));
            self.counts[start..start + n + 1].to_vec()
        };
        let jb2 = l.joint_bins * l.joint_bins;
        let st = &mut self.stats;
        st.amplitude = (0..QUARTERS)
            .map(|q| row(q, |r| r.amplitude, l.bins))
            .collect();
        st.energy = (0..QUARTERS)
            .map(|q| row(q, |r| r.energy, l.bins))
            .collect();
        st.turning = (0..QUARTERS)
            .map(|q| row(q, |r| r.turning, l.bins))
            .collect();
        st.joint = (0..QUARTERS).map(|q| row(q, |r| r.joint, jb2)).collect();
        st.impacts = impacts;
        st.sticking_steps = sticking;
        self.stats
    }

    pub(super) fn finish(self, s: &Stepper) -> PathStats {
        self.finish_counted((s.impacts(), s.sticking_steps()))
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
            self.rows = Rows::of(l, self.quarter);
        }
        // turning points of |U| are looked for at every step of the window
        let side = if l.crossing { u.signum() } else { 1.0 };
        let rising = side * v > 0.0;
        if self.rising && !rising {
            self.turning_point(u.abs(), s.time());
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
        let (rows, counts) = (self.rows, &mut self.counts);
        count(counts, rows.amplitude + bin(a, l.a_scale, l.bins, l.bins_f));
        count(
            counts,
            rows.energy + bin(0.5 * l.omega1_sq * a2, l.h_scale, l.bins, l.bins_f),
        );
        let jb = l.joint_bins;
        let iu = bin(u - l.u_lo, l.u_scale, jb, l.joint_bins_f);
        let iv = bin(v - l.v_lo, l.v_scale, jb, l.joint_bins_f);
        let cell = if iu < jb && iv < jb {
            iu * jb + iv
        } else {
            jb * jb
        };
        count(counts, rows.joint + cell);
        Flow::Continue
    }
}

/// Most wells a [`RecordPlan`] holds.
pub const RECORD_PLAN_WELLS: usize = 8;

/// What a path records, as plain data in a `#[repr(C)]` layout: the recorder's layout, the
/// window's sizes and the wells' antimodes and cores, for a backend that records elsewhere (the
/// CUDA kernel of `trirhythm-gpu` and its CPU emulation, whose `kernel/record.h` mirrors it).
/// Built from the same layout the CPU recorder uses, so its bins are the recorder's.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct RecordPlan {
    /// Histogram bins of A, of the energy and of the turning amplitude.
    pub bins: u32,
    /// Bins per axis of the joint (U, U̇) histogram.
    pub joint_bins: u32,
    /// Batches per path.
    pub batches: u32,
    /// Wells (0 without).
    pub wells: u32,
    /// The Zhuravlev crossing (turning points of sgn(U)·U̇).
    pub crossing: u32,
    /// Alignment.
    pub pad: u32,
    /// Burn-in steps.
    pub burn: u64,
    /// Steps between samples.
    pub every: u64,
    /// Samples per path.
    pub samples: u64,
    /// Bins per unit of A.
    pub a_scale: f64,
    /// Bins per unit of energy.
    pub h_scale: f64,
    /// Lower end of the joint histogram's U axis.
    pub u_lo: f64,
    /// Its bins per unit of U.
    pub u_scale: f64,
    /// Lower end of its U̇ axis.
    pub v_lo: f64,
    /// Its bins per unit of U̇.
    pub v_scale: f64,
    /// 1/ω1².
    pub inv_omega1_sq: f64,
    /// ω1².
    pub omega1_sq: f64,
    /// `bins` as a double.
    pub bins_f: f64,
    /// `joint_bins` as a double.
    pub joint_bins_f: f64,
    /// The wells' antimodes (`wells − 1` of them).
    pub antimodes: [f64; RECORD_PLAN_WELLS],
    /// The lower ends of the wells' cores.
    pub core_lo: [f64; RECORD_PLAN_WELLS],
    /// Their upper ends.
    pub core_hi: [f64; RECORD_PLAN_WELLS],
}

impl RecordPlan {
    /// The plan of `spec`'s paths of `problem` with `method`, and the steps of a path (burn-in
    /// and window). Refuses more than [`RECORD_PLAN_WELLS`] wells by name.
    pub fn new(
        problem: &Problem,
        method: &crate::engine::PredictorCorrector,
        spec: &EnsembleSpec,
    ) -> crate::Result<(Self, u64)> {
        let sizes = spec.sizes(method)?;
        let l = Layout::new(spec, problem, sizes.samples);
        let nw = l.wells.as_ref().map_or(0, Wells::len);
        if nw > RECORD_PLAN_WELLS {
            return Err(crate::Error::NotApplicable {
                method: "the GPU kernel".into(),
                assumption: format!("at most {RECORD_PLAN_WELLS} wells"),
                reason: format!("the spec has {nw}"),
            });
        }
        let mut plan = RecordPlan {
            bins: l.bins as u32,
            joint_bins: l.joint_bins as u32,
            batches: l.batches as u32,
            wells: nw as u32,
            crossing: u32::from(l.crossing),
            pad: 0,
            burn: sizes.burn,
            every: spec.sample_every,
            samples: l.samples,
            a_scale: l.a_scale,
            h_scale: l.h_scale,
            u_lo: l.u_lo,
            u_scale: l.u_scale,
            v_lo: l.v_lo,
            v_scale: l.v_scale,
            inv_omega1_sq: l.inv_omega1_sq,
            omega1_sq: l.omega1_sq,
            bins_f: l.bins_f,
            joint_bins_f: l.joint_bins_f,
            antimodes: [0.0; RECORD_PLAN_WELLS],
            core_lo: [0.0; RECORD_PLAN_WELLS],
            core_hi: [0.0; RECORD_PLAN_WELLS],
        };
        if let Some(w) = &l.wells {
            plan.antimodes[..w.antimodes.len()].copy_from_slice(&w.antimodes);
            for k in 0..nw {
                (plan.core_lo[k], plan.core_hi[k]) = w.core(k);
            }
        }
        Ok((plan, sizes.burn + sizes.window))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bins_are_those_of_the_plain_conversion() {
        // the hot path's bin against the plain one: edges, out of range, non-finite, random
        let plain = |x: f64, scale: f64, n: usize| {
            let b = x * scale;
            if b >= 0.0 && b < n as f64 {
                b as usize
            } else {
                n
            }
        };
        let mut xs = vec![
            0.0,
            -0.0,
            -1e-300,
            1e-300,
            0.999_999_999_999,
            1.0,
            99.999_999_999_99,
            100.0,
            100.000_000_000_01,
            1e300,
            -1e300,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ];
        let mut state = 0x2545_f491_4f6c_dd1du64;
        for _ in 0..10_000 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            xs.push((state >> 11) as f64 / (1u64 << 53) as f64 * 130.0 - 15.0);
        }
        for n in [1usize, 7, 100, 48 * 48] {
            for &x in &xs {
                for scale in [1.0, n as f64 / 100.0, 0.37] {
                    assert_eq!(
                        bin(x, scale, n, n as f64),
                        plain(x, scale, n),
                        "x = {x}, scale {scale}, n = {n}"
                    );
                }
            }
        }
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
}
