//! The count rule: claimed counts (roots, peaks, wells) against computed ones.
//!
//! An exact count or a count from a stationary ensemble decides; a count from a non-stationary
//! ensemble cannot. Reference: docs/verdicts.md, "Count". Tested by `tests/verdicts.rs`.

use super::super::{Check, Decision, Measured, Outcome, Verdict};
use serde::{Deserialize, Serialize};

/// Where a computed count comes from.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum CountSource {
    /// A certified count (Sturm sequence, exact roots of a theory function, grid classes).
    Exact,
    /// Modes of a Monte Carlo histogram by the prominence rule (three standard errors).
    Ensemble {
        /// Whether the ensemble passed the stationarity check.
        stationary: bool,
        /// Its R̂.
        #[serde(with = "trirhythm::non_finite")]
        r_hat: f64,
    },
}

/// One claimed count against its computed value.
#[derive(Debug, Clone)]
pub struct Count {
    /// What is counted ("roots of f, panel a (r = 1)").
    pub what: String,
    /// The paper's count.
    pub claimed: u32,
    /// The computed count.
    pub computed: u32,
    /// Where the computed count comes from.
    pub source: CountSource,
}

/// **Count**: claimed counts (roots, peaks, wells) against computed ones.
///
/// Verdict: refuted on any mismatch of an exact count or of a count from a stationary
/// ensemble; otherwise undetermined when a count comes from a non-stationary ensemble (R̂
/// given); confirmed when every count matches.
pub fn count(items: &[Count]) -> Decision {
    let mut checks = Vec::new();
    let mut refuted = false;
    let mut open = Vec::new();
    for c in items {
        let decisive = match c.source {
            CountSource::Exact => true,
            CountSource::Ensemble { stationary, r_hat } => {
                if !stationary {
                    open.push(format!(
                        "{}: not stationary (R̂ = {})",
                        c.what,
                        crate::notes::sig(r_hat, 3)
                    ));
                }
                stationary
            }
        };
        let outcome = match (decisive, c.claimed == c.computed) {
            (false, _) => Outcome::Undefined,
            (true, true) => Outcome::For,
            (true, false) => Outcome::Against,
        };
        refuted |= outcome == Outcome::Against;
        checks.push(Check {
            what: c.what.clone(),
            value: Measured::exact(c.computed as f64),
            statistic: "count".into(),
            statistic_value: c.computed as f64,
            threshold: c.claimed as f64,
            outcome,
        });
    }
    let verdict = if refuted {
        Verdict::Refuted
    } else if !open.is_empty() {
        Verdict::undetermined(open.join("; "))
    } else if items.is_empty() {
        Verdict::undetermined("no counts")
    } else {
        Verdict::Confirmed
    };
    Decision::new(
        verdict,
        "count",
        "computed count = claimed count (threshold: the claimed count); exact and stationary-ensemble counts decide, non-stationary ones cannot".into(),
        0,
        None,
        checks,
    )
}

/// The number of separate maxima of a density on a grid (`density[i][k]`, rows and columns of
/// cells), as a reader of a heat map counts them: local maxima over the eight neighbours among
/// cells at least `floor` times the largest density (what the colour scale shows), each
/// counted when the highest path from it to a higher maximum — through cells above the floor —
/// dips to at most `dip` times its own height (a maximum joined to a higher one by a ridge
/// higher than that is a shoulder of it, not a separate peak). The highest maximum always
/// counts; a maximum cut off from every higher one by the floor counts. Plateaus count once.
pub fn separate_maxima(density: &[Vec<f64>], floor: f64, dip: f64) -> usize {
    maxima(density, None, floor, dip)
}

/// [`separate_maxima`] of a Monte Carlo histogram with standard errors per cell (`stderr`, the
/// shape of `density`): a maximum counts only where its dip is also **significant**, the
/// height of the maximum above the highest way to a higher one more than `k` standard errors
/// of their difference (√(se_peak² + se_pass²), the cells taken as independent); a maximum cut
/// off by the floor counts when its height is `k` standard errors above zero. The highest
/// maximum always counts. The same test as the prominence rule of the 1-D mode count (three
/// standard errors, `analysis::versus`).
pub fn separate_maxima_significant(
    density: &[Vec<f64>],
    stderr: &[Vec<f64>],
    floor: f64,
    dip: f64,
    k: f64,
) -> usize {
    maxima(density, Some((stderr, k)), floor, dip)
}

fn maxima(density: &[Vec<f64>], se: Option<(&[Vec<f64>], f64)>, floor: f64, dip: f64) -> usize {
    let se_of = |idx: usize, nv: usize| -> f64 {
        se.and_then(|(s, _)| s.get(idx / nv).and_then(|row| row.get(idx % nv)).copied())
            .unwrap_or(0.0)
    };
    let k_se = se.map_or(0.0, |(_, k)| k);
    let nu = density.len();
    let nv = density.first().map_or(0, Vec::len);
    let top = density
        .iter()
        .flatten()
        .copied()
        .filter(|v| v.is_finite())
        .fold(0.0, f64::max);
    if top <= 0.0 {
        return 0;
    }
    let mut cells: Vec<(usize, f64)> = density
        .iter()
        .flatten()
        .copied()
        .enumerate()
        .filter(|(_, v)| v.is_finite() && *v >= floor * top && *v > 0.0)
        .collect();
    cells.sort_by(|a, b| b.1.total_cmp(&a.1));
    // union-find over cells by decreasing height; each component keeps its peak height, and
    // its root is its peak's cell (a component is founded by its highest cell and joins a
    // higher one's root)
    let mut parent: Vec<usize> = (0..nu * nv).collect();
    let mut peak = vec![f64::NAN; nu * nv];
    let mut seen = vec![false; nu * nv];
    fn root(parent: &mut [usize], mut a: usize) -> usize {
        while parent[a] != a {
            parent[a] = parent[parent[a]];
            a = parent[a];
        }
        a
    }
    let mut separate = 0;
    for (idx, h) in cells {
        let (i, k) = (idx / nv, idx % nv);
        seen[idx] = true;
        peak[idx] = h;
        let mut roots: Vec<usize> = Vec::new();
        for di in -1i64..=1 {
            for dk in -1i64..=1 {
                let (j, l) = (i as i64 + di, k as i64 + dk);
                if (di, dk) == (0, 0) || j < 0 || l < 0 || j >= nu as i64 || l >= nv as i64 {
                    continue;
                }
                let n = j as usize * nv + l as usize;
                if seen[n] {
                    let r = root(&mut parent, n);
                    if !roots.contains(&r) {
                        roots.push(r);
                    }
                }
            }
        }
        roots.sort_by(|a, b| peak[*b].total_cmp(&peak[*a]));
        if let Some(&highest) = roots.first() {
            parent[idx] = highest;
            // every lower component meets higher ground here, at height h
            for &r in &roots[1..] {
                let pass = k_se * (se_of(r, nv).powi(2) + se_of(idx, nv).powi(2)).sqrt();
                if h <= dip * peak[r] && peak[r] - h > pass {
                    separate += 1;
                }
                parent[r] = highest;
            }
        }
    }
    // components never joined to a higher one (the highest, and those cut off by the floor)
    let mut tops = std::collections::BTreeSet::new();
    let joined: Vec<usize> = (0..nu * nv).filter(|&i| seen[i]).collect();
    for idx in joined {
        tops.insert(root(&mut parent, idx));
    }
    let highest = tops
        .iter()
        .copied()
        .max_by(|a, b| peak[*a].total_cmp(&peak[*b]));
    let isolated = tops
        .iter()
        .filter(|&&t| Some(t) == highest || peak[t] > k_se * se_of(t, nv))
        .count();
    separate + isolated
}
