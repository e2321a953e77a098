//! The modes of a simulated binned density, counted by a rule fixed before any result was seen.
//!
//! # Rule
//! Pad the density with one bin of density 0 and standard error 0 beyond each end (A ≥ 0, and
//! the density vanishes far out). A candidate is a local maximum: a run of equal bins whose
//! neighbours on both sides are lower. For a candidate p with the neighbouring candidates (or
//! the padded ends) on either side, its dip on a side is d_p − d_m, m the lowest bin between p
//! and that neighbour; in units of the combined standard error it is
//! z_side = (d_p − d_m)/√(s_p² + s_m²) (∞ for a positive dip with s_p = s_m = 0, 0 for none).
//! A candidate's score is the smaller of its two z_side. While the lowest score is ≤ z, the
//! candidate holding it (the first, on a tie) is dropped and the scores of its neighbours are
//! taken again over the merged interval. What is left are the modes: each dips deeper than z
//! standard errors to both its neighbouring modes (or the ends).
//!
//! # Uncertainty
//! The count is taken at z (3 by default) and again at a lenient z (2) and a strict z (4): a
//! mode whose weaker dip lies between 2 and 4 standard errors is counted by one and not the
//! other, so [`ModeCount::low`] … [`ModeCount::high`] is the range of counts that the data
//! cannot tell apart at that resolution. It costs nothing beyond the ensemble's jackknife
//! standard errors of the bins (a bootstrap over paths would rerun the rule hundreds of times
//! for the same information, and needs more paths than a map can afford per point). The
//! thresholds are not corrected for the number of bins compared: a density of 40 bins has at
//! most 20 candidates, and a spurious mode needs two independent dips beyond z, each of
//! probability ≈ 1.3·10⁻³ at z = 3 under normal errors.
//!
//! # Tests
//! Unit tests below: two Gaussian bumps whose dip is 3.5 standard errors deep give count 2,
//! low 1, high 2; a flat density with noise of one standard error gives no spurious modes; a
//! shoulder is not a mode; plateaus and modes at the ends; bad input is refused by name.

use crate::error::{Error, Result};
use serde::{Deserialize, Serialize};

/// The thresholds of the mode-counting rule, in combined standard errors (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ModeRule {
    /// A mode's dips to its neighbouring modes (or the ends) exceed `z` standard errors (3).
    pub z: f64,
    /// The lenient threshold of [`ModeCount::high`] (2).
    pub z_lenient: f64,
    /// The strict threshold of [`ModeCount::low`] (4).
    pub z_strict: f64,
}

impl Default for ModeRule {
    fn default() -> Self {
        ModeRule {
            z: 3.0,
            z_lenient: 2.0,
            z_strict: 4.0,
        }
    }
}

/// Most standard errors a threshold may ask for.
pub const MAX_Z: f64 = 100.0;

/// A simulated density's modes at the rule's threshold, with the counts at its lenient and
/// strict thresholds.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ModeCount {
    /// Modes at z.
    pub count: usize,
    /// Fewest modes: at the strict threshold (never more than `count`).
    pub low: usize,
    /// Most modes: at the lenient threshold (never fewer than `count`).
    pub high: usize,
    /// Centres of the bins of the modes at z, ascending.
    pub modes: Vec<f64>,
}

impl ModeRule {
    /// Check the thresholds: 0 < `z_lenient` ≤ `z` ≤ `z_strict` ≤ [`MAX_Z`].
    pub fn validate(&self) -> Result<()> {
        if !(self.z_lenient > 0.0 && self.z_lenient <= MAX_Z) {
            return Err(Error::invalid(
                "z_lenient",
                self.z_lenient,
                format!("(0, {MAX_Z}] standard errors"),
            ));
        }
        if !(self.z >= self.z_lenient && self.z <= MAX_Z) {
            return Err(Error::invalid(
                "z",
                self.z,
                format!("[z_lenient = {}, {MAX_Z}] standard errors", self.z_lenient),
            ));
        }
        if !(self.z_strict >= self.z && self.z_strict <= MAX_Z) {
            return Err(Error::invalid(
                "z_strict",
                self.z_strict,
                format!("[z = {}, {MAX_Z}] standard errors", self.z),
            ));
        }
        Ok(())
    }

    /// Count the modes of the binned density `density` (bins between `edges`, standard errors
    /// `stderr`) at the three thresholds.
    pub fn count(&self, edges: &[f64], density: &[f64], stderr: &[f64]) -> Result<ModeCount> {
        self.validate()?;
        if edges.len() != density.len() + 1 {
            return Err(Error::invalid(
                "edges",
                edges.len() as f64,
                format!("one more than the {} bins", density.len()),
            ));
        }
        let at = modes(density, stderr, self.z)?;
        let low = modes(density, stderr, self.z_strict)?.len().min(at.len());
        let high = modes(density, stderr, self.z_lenient)?.len().max(at.len());
        Ok(ModeCount {
            count: at.len(),
            low,
            high,
            modes: at
                .iter()
                .map(|&b| 0.5 * (edges[b] + edges[b + 1]))
                .collect(),
        })
    }
}

/// The bins of the modes of `density` (standard errors `stderr`) at threshold `z` (module
/// docs): the first bin of each mode's plateau, ascending.
pub fn modes(density: &[f64], stderr: &[f64], z: f64) -> Result<Vec<usize>> {
    let n = density.len();
    if n == 0 {
        return Err(Error::invalid("density", 0.0, "at least one bin"));
    }
    if stderr.len() != n {
        return Err(Error::invalid(
            "stderr",
            stderr.len() as f64,
            format!("one per bin ({n})"),
        ));
    }
    if let Some(&d) = density.iter().find(|d| !(d.is_finite() && **d >= 0.0)) {
        return Err(Error::invalid("density", d, "finite and ≥ 0 in every bin"));
    }
    if let Some(&s) = stderr.iter().find(|s| !(s.is_finite() && **s >= 0.0)) {
        return Err(Error::invalid(
            "stderr",
            s,
            "finite and ≥ 0 in every bin (two units or more)",
        ));
    }
    if !(z > 0.0 && z <= MAX_Z) {
        return Err(Error::invalid(
            "z",
            z,
            format!("(0, {MAX_Z}] standard errors"),
        ));
    }
    // padded access: bins −1 and n are density 0 with standard error 0
    let d = |i: isize| {
        if i < 0 || i >= n as isize {
            0.0
        } else {
            density[i as usize]
        }
    };
    let s = |i: isize| {
        if i < 0 || i >= n as isize {
            0.0
        } else {
            stderr[i as usize]
        }
    };
    // candidates: runs of equal bins, lower on both sides
    let mut peaks: Vec<isize> = Vec::new();
    let mut a = 0isize;
    while a < n as isize {
        let mut b = a;
        while b + 1 < n as isize && d(b + 1) == d(a) {
            b += 1;
        }
        if d(a - 1) < d(a) && d(b + 1) < d(a) {
            peaks.push(a);
        }
        a = b + 1;
    }
    // the lowest bin of [lo, hi] (the first on a tie)
    let lowest = |lo: isize, hi: isize| {
        (lo..=hi)
            .min_by(|&i, &j| d(i).total_cmp(&d(j)))
            .unwrap_or(lo)
    };
    let dip = |p: isize, m: isize| {
        let depth = d(p) - d(m);
        if depth <= 0.0 {
            return 0.0;
        }
        let se = (s(p) * s(p) + s(m) * s(m)).sqrt();
        if se == 0.0 {
            f64::INFINITY
        } else {
            depth / se
        }
    };
    loop {
        let mut weakest: Option<(usize, f64)> = None;
        for k in 0..peaks.len() {
            let p = peaks[k];
            let left = if k == 0 { -1 } else { peaks[k - 1] };
            let right = if k + 1 == peaks.len() {
                n as isize
            } else {
                peaks[k + 1]
            };
            let score = dip(p, lowest(left, p)).min(dip(p, lowest(p, right)));
            if weakest.is_none_or(|(_, w)| score < w) {
                weakest = Some((k, score));
            }
        }
        match weakest {
            Some((k, score)) if score <= z => {
                peaks.remove(k);
            }
            _ => break,
        }
    }
    Ok(peaks.into_iter().map(|p| p as usize).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two Gaussian bumps at bins 15 and 45 of 60, heights 1 and 0.8, width 4 bins.
    fn bumps() -> Vec<f64> {
        (0..60)
            .map(|b| {
                let g = |c: f64, h: f64| h * (-((b as f64 - c) / 4.0).powi(2) / 2.0).exp();
                g(15.0, 1.0) + g(45.0, 0.8)
            })
            .collect()
    }

    #[test]
    fn a_dip_between_the_thresholds_is_counted_by_one_and_not_the_other() {
        let d = bumps();
        // the smaller bump's dip to the valley, in units of a common standard error s:
        // (d_45 − d_valley)/(s√2) = 3.5
        let valley = (15..=45).min_by(|&i, &j| d[i].total_cmp(&d[j])).unwrap();
        let depth = d[45] - d[valley];
        let s = depth / (3.5 * 2f64.sqrt());
        let se = vec![s; 60];
        let edges: Vec<f64> = (0..=60).map(|b| b as f64).collect();
        let c = ModeRule::default().count(&edges, &d, &se).unwrap();
        assert_eq!((c.count, c.low, c.high), (2, 1, 2));
        assert_eq!(c.modes, vec![15.5, 45.5]);
        assert_eq!(modes(&d, &se, 3.49).unwrap(), vec![15, 45]);
        assert_eq!(modes(&d, &se, 3.51).unwrap(), vec![15]);
        // with a tenth of that error both are clear at every threshold
        let c = ModeRule::default()
            .count(&edges, &d, &vec![s / 10.0; 60])
            .unwrap();
        assert_eq!((c.count, c.low, c.high), (2, 2, 2));
    }

    #[test]
    fn noise_of_one_standard_error_makes_no_modes_on_a_plateau() {
        // a flat top of 40 bins with deterministic ±1 s.e. wiggles, zero at the ends
        let mut d = vec![0.0; 50];
        let mut se = vec![0.0; 50];
        let mut x = 12345u64;
        for b in 5..45 {
            x = x
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let u = (x >> 11) as f64 / (1u64 << 53) as f64; // in [0, 1)
            d[b] = 1.0 + 0.02 * (2.0 * u - 1.0);
            se[b] = 0.02;
        }
        let m = modes(&d, &se, 3.0).unwrap();
        assert_eq!(m.len(), 1, "one mode on the plateau, not {m:?}");
        // many local maxima before the rule merges them
        assert!(modes(&d, &se, 1e-9).unwrap().len() > 5);
    }

    #[test]
    fn a_shoulder_is_not_a_mode_and_ends_and_plateaus_count_once() {
        // a big peak with a shoulder 0.01 above its dip, s.e. 0.01
        let d = [0.0, 0.5, 1.0, 0.5, 0.30, 0.31, 0.1, 0.0];
        let se = [0.01; 8];
        assert_eq!(modes(&d, &se, 3.0).unwrap(), vec![2]);
        // a maximum in the first bin dips to the padded 0 on the left
        assert_eq!(modes(&[1.0, 0.2, 0.0], &[0.01; 3], 3.0).unwrap(), vec![0]);
        // a plateau of three equal bins is one mode, named by its first bin
        assert_eq!(
            modes(&[0.0, 1.0, 1.0, 1.0, 0.0], &[0.0; 5], 3.0).unwrap(),
            vec![1]
        );
        // zero density: no mode
        assert!(modes(&[0.0; 4], &[0.0; 4], 3.0).unwrap().is_empty());
    }

    #[test]
    fn bad_input_is_refused_by_name() {
        let msg = |r: Result<Vec<usize>>| r.unwrap_err().to_string();
        assert!(msg(modes(&[], &[], 3.0)).contains("density"));
        assert!(msg(modes(&[1.0], &[0.1, 0.1], 3.0)).contains("stderr"));
        assert!(msg(modes(&[f64::NAN], &[0.1], 3.0)).contains("density"));
        assert!(msg(modes(&[1.0], &[f64::NAN], 3.0)).contains("stderr"));
        assert!(msg(modes(&[1.0], &[0.1], 0.0)).contains("z"));
        let rule = ModeRule {
            z: 1.0,
            ..Default::default()
        };
        assert!(rule.validate().unwrap_err().to_string().contains("z = 1"));
        let rule = ModeRule {
            z_strict: 2.5,
            ..Default::default()
        };
        assert!(rule
            .validate()
            .unwrap_err()
            .to_string()
            .contains("z_strict"));
        let e = ModeRule::default()
            .count(&[0.0, 1.0], &[1.0, 2.0], &[0.1, 0.1])
            .unwrap_err();
        assert!(e.to_string().contains("edges"));
    }
}
