//! Merging the paths' statistics into an [`EnsembleResult`]: moments, densities, well
//! occupancies and first passages, each with a delete-one jackknife standard error over the
//! units (the paths, or the batches / quarters of a single path).

use super::diagnostics::{stationarity, warnings, Stationarity};
use super::recording::{BatchSums, Layout, PathStats};
use super::spec::{EnsembleSpec, Sizes, Wells};
use serde::{Deserialize, Serialize};

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
pub(super) fn jackknife(units: &[Vec<f64>], f: impl Fn(&[f64]) -> f64) -> Estimate {
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
    /// Per path amplitude histograms (for the bootstrap of theory distances); empty for a well
    /// decomposition whose weights are undetermined (no mixture, no unit of it).
    pub per_path_amplitude: Vec<Vec<u64>>,
}

/// The moments ⟨U⟩, Var U, ⟨U̇⟩, Var U̇, ⟨A⟩ with their standard errors.
#[derive(Debug, Clone, Copy)]
pub(super) struct Moments {
    pub(super) mean_u: Estimate,
    pub(super) var_u: Estimate,
    pub(super) mean_v: Estimate,
    pub(super) var_v: Estimate,
    pub(super) mean_amplitude: Estimate,
}

/// The moments over the units: the paths (`between`), or the batches of the single path.
fn moments(all: &[PathStats], between: bool) -> Moments {
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
    Moments {
        mean_u: jackknife(&batch_units, |t| t[1] / t[0]),
        var_u: jackknife(&batch_units, |t| {
            t[2] / t[0] - (t[1] / t[0]) * (t[1] / t[0])
        }),
        mean_v: jackknife(&batch_units, |t| t[3] / t[0]),
        var_v: jackknife(&batch_units, |t| {
            t[4] / t[0] - (t[3] / t[0]) * (t[3] / t[0])
        }),
        mean_amplitude: jackknife(&batch_units, |t| t[5] / t[0]),
    }
}

/// A histogram's units: each path's quarters summed (`between`), or the single path's quarters.
fn hist_units(
    all: &[PathStats],
    between: bool,
    get: &dyn Fn(&PathStats) -> &Vec<Vec<u64>>,
) -> Vec<Vec<u64>> {
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
}

/// The joint density of (U, U̇) on the layout's grid.
fn joint_density(layout: &Layout, joint_units: &[Vec<u64>]) -> JointDensity {
    let jb = layout.joint_bins;
    let (fraction, se) = fractions(joint_units);
    let (du, dv) = (1.0 / layout.u_scale, 1.0 / layout.v_scale);
    let cells = |x: &[f64]| -> Vec<Vec<f64>> {
        x[..jb * jb]
            .chunks(jb)
            .map(|row| row.iter().map(|f| f / (du * dv)).collect())
            .collect()
    };
    JointDensity {
        u_edges: (0..=jb).map(|i| layout.u_lo + du * i as f64).collect(),
        v_edges: (0..=jb).map(|i| layout.v_lo + dv * i as f64).collect(),
        density: cells(&fraction),
        stderr: cells(&se),
        outside: fraction[jb * jb],
    }
}

/// The fraction of samples in each of `nw` wells, over the units.
fn occupancy(all: &[PathStats], between: bool, nw: usize) -> Vec<Estimate> {
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
    (0..nw)
        .map(|k| jackknife(&well_units, |t| t[k + 1] / t[0]))
        .collect()
}

/// First passages between every ordered pair of `nw` wells, pooled over the paths.
fn passages(all: &[PathStats], nw: usize) -> Vec<Passage> {
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
    passages
}

/// The result of the paths `all` (checked: every path once, in path order, of this spec).
pub(super) fn assemble(
    spec: &EnsembleSpec,
    layout: &Layout,
    sizes: &Sizes,
    omega1: f64,
    all: &[PathStats],
) -> EnsembleResult {
    let between = all.len() >= 2;
    let m = moments(all, between);
    let a_max = spec.amplitude_max;
    let amp_units = hist_units(all, between, &|p| &p.amplitude);
    let amplitude = Density::from_units(layout.edges(a_max), &amp_units);
    let turning = Density::from_units(
        layout.edges(a_max),
        &hist_units(all, between, &|p| &p.turning),
    );
    let h_max = 0.5 * omega1 * omega1 * a_max * a_max;
    let energy = Density::from_units(
        layout.edges(h_max),
        &hist_units(all, between, &|p| &p.energy),
    );
    let joint = joint_density(layout, &hist_units(all, between, &|p| &p.joint));
    let nw = spec.wells.as_ref().map_or(0, Wells::len);
    let occupancy = occupancy(all, between, nw);
    let passages = passages(all, nw);
    let stationarity = stationarity(all, spec, &m, layout.inv_omega1_sq);
    let warnings = warnings(
        &stationarity,
        between,
        &amplitude,
        &energy,
        &joint,
        &passages,
    );
    EnsembleResult {
        paths: all.len(),
        steps_per_path: sizes.burn + sizes.window,
        burn_in_steps: sizes.burn,
        samples_per_path: sizes.samples,
        omega1,
        between_paths: between,
        mean_u: m.mean_u,
        var_u: m.var_u,
        mean_v: m.mean_v,
        var_v: m.var_v,
        mean_amplitude: m.mean_amplitude,
        amplitude,
        turning,
        energy,
        joint,
        wells: spec.wells.clone(),
        occupancy,
        passages,
        stationarity,
        impacts: all.iter().map(|p| p.impacts).sum(),
        sticking_steps: all.iter().map(|p| p.sticking_steps).sum(),
        warnings,
        per_path_amplitude: amp_units,
    }
}

/// The batch means of a path's batches with samples, by `f`.
pub(super) fn chains(all: &[PathStats], f: &dyn Fn(&BatchSums) -> f64) -> Vec<Vec<f64>> {
    all.iter()
        .map(|p| p.batches.iter().filter(|b| b.n > 0).map(f).collect())
        .collect()
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
}
