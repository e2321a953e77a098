//! What an ensemble runs: its spec (paths, seed, window, sampling, histograms, batches) with the
//! checked sizes of a run, and the wells of the amplitude from the theory.

use crate::engine::{whole_steps, Lanes, PredictorCorrector};
use crate::error::{Error, Result};
use serde::{Deserialize, Serialize};

/// Most paths of one ensemble.
pub use crate::engine::MAX_PATHS;
/// Most wells of an ensemble's [`Wells`].
pub const MAX_WELLS: usize = 100;
/// Most batches per path.
pub const MAX_BATCHES: usize = 1000;
/// Most bins of a one-dimensional histogram.
pub const MAX_BINS: usize = 10_000;
/// Most bins per axis of the joint (U, U̇) histogram.
pub const MAX_JOINT_BINS: usize = 1_000;
/// Largest histogram range of the amplitude.
pub const MAX_AMPLITUDE: f64 = 1e6;
/// Most bytes of per-path statistics held at once (paths × histograms, batches, passages).
pub const MAX_STATISTICS_BYTES: usize = 4_000_000_000;
/// Quarters of a path whose histograms are kept apart (the units for one path).
pub(super) const QUARTERS: usize = 4;

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
        let wells = Wells { modes, antimodes };
        wells.validate()?;
        Ok(wells)
    }

    /// Check the wells: 1 to [`MAX_WELLS`] modes, finite and ≥ 0, with one antimode between
    /// two consecutive modes, all ascending.
    pub fn validate(&self) -> Result<()> {
        let (modes, antimodes) = (&self.modes, &self.antimodes);
        if modes.is_empty() || modes.len() > MAX_WELLS {
            return Err(Error::invalid(
                "wells",
                modes.len() as f64,
                format!("1 to {MAX_WELLS} modes"),
            ));
        }
        if antimodes.len() + 1 != modes.len() {
            return Err(Error::invalid(
                "wells",
                antimodes.len() as f64,
                format!("{} antimodes (one between two modes)", modes.len() - 1),
            ));
        }
        // modes and antimodes interleaved: m0 < a0 < m1 < a1 < …, all finite and ≥ 0
        let interleaved = (0..2 * modes.len() - 1).map(|k| {
            if k % 2 == 0 {
                modes[k / 2]
            } else {
                antimodes[k / 2]
            }
        });
        let mut previous = -0.0f64;
        for (k, x) in interleaved.enumerate() {
            if !(x.is_finite() && x >= 0.0 && (k == 0 || x > previous)) {
                return Err(Error::invalid(
                    "wells",
                    x,
                    "modes and antimodes finite, ≥ 0, alternating and ascending",
                ));
            }
            previous = x;
        }
        Ok(())
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
    pub(super) fn core_of(&self, a: f64) -> Option<usize> {
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

/// What an ensemble runs and records beyond its [`Problem`](crate::engine::Problem) and method: how many paths, the
/// seed, the window, the sampling, the histograms, the batches and the wells.
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
    /// Record every k-th step of the window.
    pub sample_every: u64,
    /// Bins of the amplitude, turning-amplitude and energy histograms.
    pub bins: usize,
    /// Bins per axis of the joint (U, U̇) histogram.
    pub joint_bins: usize,
    /// Half-width of the joint histogram's U̇ axis, as a multiple of ω1·`amplitude_max` (1: the
    /// harmonic cycle's ±ω1·A; a relaxation oscillation's fast returns need more).
    pub joint_velocity_factor: f64,
    /// Histogram range of A: [0, amplitude_max]; U in [0 or −max, max], U̇ in ±ω1·max, H up to
    /// ω1²·max²/2.
    pub amplitude_max: f64,
    /// Batches per path (for batch means and R̂; at least 4).
    pub batches: usize,
    /// Wells for occupancies and passages (from the theory), if any.
    pub wells: Option<Wells>,
    /// How many paths are stepped together ([`Lanes`]; the default suits the CPU). The
    /// statistics do not depend on it: every path gives the same bits in any lane count.
    pub lanes: Lanes,
}

impl Default for EnsembleSpec {
    fn default() -> Self {
        EnsembleSpec {
            paths: 8,
            seed: 1,
            burn_in: 100.0,
            length: 1000.0,
            sample_every: 1,
            bins: 100,
            joint_bins: 48,
            joint_velocity_factor: 1.0,
            amplitude_max: 15.0,
            batches: 20,
            wells: None,
            lanes: Lanes::Auto,
        }
    }
}

/// The checked sizes of a run.
#[derive(Debug, Clone, Copy)]
pub(super) struct Sizes {
    pub(super) burn: u64,
    pub(super) window: u64,
    pub(super) samples: u64,
}

impl EnsembleSpec {
    /// Check the spec, before any work, by every driver that takes it: `paths` 1 to
    /// [`MAX_PATHS`], `bins` 2 to [`MAX_BINS`], `joint_bins` 2 to [`MAX_JOINT_BINS`], `batches`
    /// 4 to [`MAX_BATCHES`], `amplitude_max` in (0, [`MAX_AMPLITUDE`]], `joint_velocity_factor` in
    /// (0, 1000], the wells
    /// ([`Wells::validate`]), the statistics of all paths at most [`MAX_STATISTICS_BYTES`],
    /// `sample_every` ≥ 1, `burn_in` ≥ 0 and `length` > 0 finite, `lanes` 1, 4 or 8 when given. The steps are checked against
    /// the method's Δt by the drivers.
    pub fn validate(&self) -> Result<()> {
        self.lanes.width()?;
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
        if !(4..=MAX_BATCHES).contains(&self.batches) {
            return Err(Error::invalid(
                "batches",
                self.batches as f64,
                format!("4 to {MAX_BATCHES}"),
            ));
        }
        if !(self.amplitude_max > 0.0 && self.amplitude_max <= MAX_AMPLITUDE) {
            return Err(Error::invalid(
                "amplitude_max",
                self.amplitude_max,
                format!("(0, {MAX_AMPLITUDE:e}] (beyond it the energy's range overflows)"),
            ));
        }
        if !(self.joint_velocity_factor > 0.0 && self.joint_velocity_factor <= 1e3) {
            return Err(Error::invalid(
                "joint_velocity_factor",
                self.joint_velocity_factor,
                "(0, 1e3] (a multiple of ω1·amplitude_max)",
            ));
        }
        if let Some(w) = &self.wells {
            w.validate()?;
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
        if self.sample_every == 0 {
            return Err(Error::invalid("sample_every", 0.0, "1 or more"));
        }
        if !(self.burn_in >= 0.0 && self.burn_in.is_finite()) {
            return Err(Error::invalid("burn_in", self.burn_in, "[0, ∞), finite"));
        }
        if !(self.length > 0.0 && self.length.is_finite()) {
            return Err(Error::invalid("t_end", self.length, "(0, ∞), finite"));
        }
        Ok(())
    }

    /// The spec and `method` checked ([`EnsembleSpec::validate`],
    /// [`PredictorCorrector::validate`]), and the steps of the burn-in and the window and the
    /// samples per path: whole numbers of steps, at most [`crate::engine::MAX_STEPS`] in all, at
    /// least four samples per batch.
    pub(super) fn sizes(&self, method: &PredictorCorrector) -> Result<Sizes> {
        method.validate()?;
        self.validate()?;
        let dt = method.dt;
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
        let least = 4 * self.batches as u64;
        if window < least {
            return Err(Error::invalid(
                "t_end",
                self.length,
                format!("long enough for {least} samples (4 per batch): {least} steps of dt = {dt} or more"),
            ));
        }
        let samples = window / self.sample_every;
        if samples < least {
            return Err(Error::invalid(
                "sample_every",
                self.sample_every as f64,
                format!(
                    "1 to {} (4 samples per batch from {window} steps)",
                    window / least
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

#[cfg(test)]
mod tests {
    use super::*;

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
