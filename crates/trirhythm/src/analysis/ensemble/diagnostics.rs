//! Whether an ensemble is stationary: split-R̂ of the mean amplitude and of each well's
//! occupancy, the effective sample size, the drift between the window's halves, the verdict
//! with a suggested window, and the plain-language warnings of a result.

use super::merging::{chains, Density, JointDensity, Moments, Passage};
use super::recording::PathStats;
use super::spec::{EnsembleSpec, Wells};
use serde::{Deserialize, Serialize};

/// The stationarity diagnosis. Its numbers may be NaN or ±∞ (R̂ = ∞ where the paths never left
/// their wells); JSON writes those as `"NaN"`, `"inf"`, `"-inf"` ([`crate::non_finite`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Stationarity {
    /// Split-R̂ of the mean amplitude.
    #[serde(with = "crate::non_finite")]
    pub r_hat_amplitude: f64,
    /// Split-R̂ of each well's occupancy (NaN for a well never or always occupied).
    #[serde(with = "crate::non_finite::vec")]
    pub r_hat_wells: Vec<f64>,
    /// The largest of them (the verdict's R̂).
    #[serde(with = "crate::non_finite")]
    pub r_hat: f64,
    /// Effective sample size of the mean amplitude.
    #[serde(with = "crate::non_finite")]
    pub ess: f64,
    /// (second half − first half) of the mean amplitude, and that in standard errors.
    #[serde(with = "crate::non_finite")]
    pub drift: f64,
    /// The drift in standard errors.
    #[serde(with = "crate::non_finite")]
    pub drift_z: f64,
    /// R̂ ≤ 1.1 everywhere and |drift_z| ≤ 3.
    pub stationary: bool,
    /// Window length that the R̂ scaling suggests for R̂ ≤ 1.1 (the length used when passed).
    #[serde(with = "crate::non_finite")]
    pub suggested_length: f64,
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

/// The diagnosis of the paths `all` (module docs of [`super`]), `m` their moments.
pub(super) fn stationarity(
    all: &[PathStats],
    spec: &EnsembleSpec,
    m: &Moments,
    inv_omega1_sq: f64,
) -> Stationarity {
    let between = all.len() >= 2;
    let nb = spec.batches;
    let nw = spec.wells.as_ref().map_or(0, Wells::len);
    // stationarity: chains of batch means per path
    let r_hat_amplitude = split_r_hat(&chains(all, &|b| b.a / b.n as f64));
    let r_hat_wells: Vec<f64> = (0..nw)
        .map(|k| split_r_hat(&chains(all, &|b| b.wells[k] as f64 / b.n as f64)))
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
    let grand = m.mean_amplitude.value;
    let s2_batch =
        bm.iter().map(|x| (x - grand) * (x - grand)).sum::<f64>() / (bm.len() as f64 - 1.0);
    // Var A = ⟨A²⟩ − ⟨A⟩², ⟨A²⟩ = ⟨U²⟩ + ⟨U̇²⟩/ω1²
    let a2 = (m.var_u.value + m.mean_u.value * m.mean_u.value)
        + (m.var_v.value + m.mean_v.value * m.mean_v.value) * inv_omega1_sq;
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
    let dsd = (diffs.iter().map(|d| (d - drift) * (d - drift)).sum::<f64>() / (dn - 1.0)).sqrt();
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
    Stationarity {
        r_hat_amplitude,
        r_hat_wells,
        r_hat,
        ess,
        drift,
        drift_z,
        stationary,
        suggested_length,
    }
}

/// Plain-language warnings: not stationary, one path, a small effective sample, mass outside
/// the histograms, few passages.
pub(super) fn warnings(
    s: &Stationarity,
    between: bool,
    amplitude: &Density,
    energy: &Density,
    joint: &JointDensity,
    passages: &[Passage],
) -> Vec<String> {
    let Stationarity {
        r_hat,
        drift_z,
        stationary,
        suggested_length,
        ess,
        ..
    } = *s;
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
    for (name, d) in [("A", amplitude), ("H", energy)] {
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
    for p in passages {
        if p.count < 10 && p.count + p.censored > 0 {
            warnings.push(format!(
                "first passage {} → {}: {} completed, {} censored: the mean is not reliable",
                p.from, p.to, p.count, p.censored
            ));
        }
    }
    warnings
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn r_hat_is_one_for_identical_chains_and_infinite_for_frozen_different_ones() {
        let a: Vec<f64> = (0..20).map(|i| ((i * 7) % 5) as f64).collect();
        let r = split_r_hat(&[a.clone(), a.clone(), a]);
        assert!(r < 1.05, "{r}");
        let r = split_r_hat(&[vec![1.0; 20], vec![0.0; 20]]);
        assert!(r.is_infinite());
    }
}
