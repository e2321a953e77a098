//! The averaged theory against an ensemble: distances between the simulated and the predicted
//! amplitude densities, modes, well occupancies, and escape times between wells.
//!
//! # Equations
//! The stationary P(A) of Eq. (27–28) is the density of the one-dimensional diffusion
//! dA = m1(A)dt + √σ1 dW (Eq. 26, generator m1 d/dA + (σ1/2) d²/dA², reflecting at A = 0).
//! Its mean first-passage time from a to b is exact (Gardiner, Handbook of Stochastic Methods,
//! §5.2.7):
//!   T(a → b) = ∫_a^b 2F(y)/(σ1 P(y)) dy,  F(y) = ∫_0^y P,        for b > a,
//!   T(a → b) = ∫_b^a 2(1 − F(y))/(σ1 P(y)) dy,                    for b < a,
//! whose low-noise limit is Kramers' rate e^{ΔU_eff/…}: the barriers of Figs 8–9 as escape
//! times that a simulation can measure. An ensemble's passage i → j runs from the core of well
//! i to the core of well j ([`super::ensemble::Wells::core`]), so the theory's time is taken from
//! the mode m_i to the near edge of the core of j.
//!
//! # Distances (per bin of the ensemble's amplitude histogram, the mass beyond it as one more bin)
//! Hellinger H = √(1 − Σ√(p_b q_b)), L1 = Σ|p_b − q_b|, and the largest CDF difference
//! (Kolmogorov–Smirnov statistic at the bin edges), q_b = ∫ P(A) over bin b. Their standard
//! errors are bootstrap over the ensemble's units (paths), 200 resamples from a fixed seed.
//! A finite sample has a noise floor: even the exact density gives H ≈ √(bins/(8·ESS)).
//!
//! # Modes, with a stated prominence rule
//! A bin is a mode when it is a local maximum whose prominence (its height above the higher of
//! the lowest points between it and a higher bin on either side) exceeds 1 % of the largest
//! density and, for the simulation, three standard errors of the difference. The theory's
//! binned density is counted by the same rule (`modes_theory`); `modes_theory_exact` counts the
//! analytic maxima of P(A), some of which no histogram can show (e.g. a well 10⁻³ deep).
//!
//! # Tests
//! `tests/ensemble.rs`: the escape time of the Rayleigh amplitude process (P ≡ −1, so
//! f(A) = −κA) against its closed form T(a → b < a) = ln(a/b)/κ and a Simpson quadrature of
//! the upward integral (1e-6); the well probabilities sum to 1 even for peaks 10⁻³ wide.
//! Unit tests below: distances vanish for equal densities and are symmetric; the prominence
//! rule counts and rejects modes as stated.

use super::ensemble::{
    hellinger_bounds, EnsembleResult, Estimate, HellingerBounds, Wells, WellsResult,
};
use crate::error::Error;
use crate::theory::averaging::{AmplitudePdf, Theory};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};

/// Bootstrap resamples of the distances.
pub const RESAMPLES: usize = 200;

/// The theory (one variant) against an ensemble.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TheoryComparison {
    /// `paper` or `consistent`.
    pub variant: String,
    /// Hellinger distance with its bootstrap standard error.
    pub hellinger: Estimate,
    /// L1 distance.
    pub l1: Estimate,
    /// Largest CDF difference.
    pub ks: Estimate,
    /// Modes of the binned theory by the prominence rule.
    pub modes_theory: usize,
    /// Analytic maxima of P(A).
    pub modes_theory_exact: usize,
    /// Modes of the simulated histogram by the prominence rule; `None` (JSON `null`) when the
    /// simulated density does not exist (a well decomposition whose weights are undetermined:
    /// then the distances are NaN too).
    pub modes_mc: Option<usize>,
    /// The theory's mean density in each bin of the ensemble's histogram.
    pub density: Vec<f64>,
    /// ⟨A⟩ of the theory.
    pub mean_amplitude: f64,
    /// ∫P(A) over each of the ensemble's wells.
    pub occupancy: Vec<f64>,
    /// The theory's mean first-passage time for each of the ensemble's passages (same order).
    pub escape_times: Vec<f64>,
}

/// Subintervals of composite Simpson per piece between consecutive extrema of P(A).
const ESCAPE_NODES: usize = 2000;

/// Exact mean first-passage time of the averaged amplitude diffusion from `a` to `b`: composite
/// Simpson on each piece between the extrema of P(A) (the integrand 1/P peaks at the antimodes,
/// which are piece ends), with F (or 1 − F) accumulated node by node from small exact
/// integrals of P, in log form so that deep barriers do not overflow.
pub fn escape_time(pdf: &AmplitudePdf, sigma1: f64, a: f64, b: f64) -> f64 {
    if a == b {
        return 0.0;
    }
    let (lo, hi) = (a.min(b).max(0.0), a.max(b));
    let up = b > a;
    let mut cuts = vec![lo];
    cuts.extend(
        pdf.modes
            .iter()
            .chain(&pdf.antimodes)
            .copied()
            .filter(|&x| x > lo && x < hi),
    );
    cuts.push(hi);
    cuts.sort_by(f64::total_cmp);
    let mut nodes = Vec::new();
    for w in cuts.windows(2) {
        for k in 0..ESCAPE_NODES {
            nodes.push(w[0] + (w[1] - w[0]) * k as f64 / ESCAPE_NODES as f64);
        }
    }
    nodes.push(hi);
    // the mass below (up) or above (down) each node
    let mut mass = vec![0.0; nodes.len()];
    if up {
        mass[0] = pdf.probability(0.0, nodes[0]);
        for k in 1..nodes.len() {
            mass[k] = mass[k - 1] + pdf.probability(nodes[k - 1], nodes[k]);
        }
    } else {
        let n = nodes.len();
        mass[n - 1] = pdf.probability(nodes[n - 1], pdf.support_end);
        for k in (0..n - 1).rev() {
            mass[k] = mass[k + 1] + pdf.probability(nodes[k], nodes[k + 1]);
        }
    }
    let f = |k: usize| {
        let y = nodes[k];
        if y <= 0.0 || mass[k] <= 0.0 {
            return 0.0;
        }
        2.0 * crate::maths::exp(crate::maths::ln(mass[k]) - pdf.log_density(y)) / sigma1
    };
    let mut total = 0.0;
    for piece in 0..cuts.len() - 1 {
        let k0 = piece * ESCAPE_NODES;
        let h = nodes[k0 + 1] - nodes[k0];
        let mut s = f(k0) + f(k0 + ESCAPE_NODES);
        for j in 1..ESCAPE_NODES {
            s += if j % 2 == 1 { 4.0 } else { 2.0 } * f(k0 + j);
        }
        total += s * h / 3.0;
    }
    total
}

/// Local maxima with prominence above `floor` and above `noise[i]` (the same bin's noise).
pub fn count_modes(values: &[f64], noise: &[f64]) -> usize {
    let n = values.len();
    let max = values.iter().copied().fold(0.0, f64::max);
    let floor = 0.01 * max;
    let mut count = 0;
    let mut i = 0;
    while i < n {
        // a plateau [i, j)
        let mut j = i + 1;
        while j < n && values[j] == values[i] {
            j += 1;
        }
        let v = values[i];
        let left_lower = i == 0 || values[i - 1] < v;
        let right_lower = j == n || values[j] < v;
        if v > 0.0 && left_lower && right_lower {
            let side_min = |range: &mut dyn Iterator<Item = usize>| {
                let mut m = v;
                for k in range {
                    if values[k] > v {
                        return m;
                    }
                    m = m.min(values[k]);
                }
                m
            };
            let left = side_min(&mut (0..i).rev());
            let right = side_min(&mut (j..n));
            let prominence = v - left.max(right);
            let noise_i = noise
                .get(i)
                .copied()
                .filter(|x| x.is_finite())
                .unwrap_or(0.0);
            if prominence > floor && prominence > noise_i {
                count += 1;
            }
        }
        i = j;
    }
    count
}

/// (Hellinger, L1, KS) between probability vectors (bins and the mass beyond).
fn distances(p: &[f64], q: &[f64]) -> (f64, f64, f64) {
    let bc: f64 = p.iter().zip(q).map(|(a, b)| (a * b).sqrt()).sum();
    let l1: f64 = p.iter().zip(q).map(|(a, b)| (a - b).abs()).sum();
    let mut cdf = 0.0f64;
    let mut ks = 0.0f64;
    for (a, b) in p.iter().zip(q) {
        cdf += a - b;
        ks = ks.max(cdf.abs());
    }
    ((1.0 - bc).max(0.0).sqrt(), l1, ks)
}

fn probabilities(counts: &[u64]) -> Vec<f64> {
    let total: u64 = counts.iter().sum();
    counts
        .iter()
        .map(|&c| c as f64 / total.max(1) as f64)
        .collect()
}

/// Whether `result` has the shape of an ensemble's result (its fields are public): amplitude
/// edges finite, ≥ 0 and ascending, one count per bin and beyond in every unit, valid wells and
/// passages between them.
fn check_result(result: &EnsembleResult) -> crate::Result<()> {
    let edges = &result.amplitude.edges;
    let nb = edges.len().saturating_sub(1);
    if !(1..=super::ensemble::MAX_BINS).contains(&nb) {
        return Err(Error::invalid(
            "edges",
            edges.len() as f64,
            "2 to 10001 amplitude edges",
        ));
    }
    if let Some(k) = (0..edges.len()).find(|&k| {
        !(edges[k].is_finite() && edges[k] >= 0.0 && (k == 0 || edges[k] > edges[k - 1]))
    }) {
        return Err(Error::invalid(
            "edges",
            edges[k],
            "amplitude edges finite, ≥ 0 and ascending",
        ));
    }
    if let Some(u) = result.per_path_amplitude.iter().find(|u| u.len() != nb + 1) {
        return Err(Error::invalid(
            "per_path_amplitude",
            u.len() as f64,
            format!("{} counts per unit (the bins and the count beyond)", nb + 1),
        ));
    }
    if let Some(w) = &result.wells {
        w.validate()?;
        if let Some(p) = result
            .passages
            .iter()
            .find(|p| p.from >= w.len() || p.to >= w.len())
        {
            return Err(Error::invalid(
                "passages",
                p.from.max(p.to) as f64,
                format!("wells 0..{}", w.len()),
            ));
        }
    }
    Ok(())
}

/// Compare `result` with the theory (its PDF computed here); `seed` drives the bootstrap.
/// `result` is checked first (edges, units, wells: its fields are public).
pub fn compare(
    result: &EnsembleResult,
    theory: &Theory,
    seed: u64,
) -> crate::Result<TheoryComparison> {
    check_result(result)?;
    let pdf = theory.amplitude_pdf()?;
    let edges = &result.amplitude.edges;
    let nb = edges.len() - 1;
    let q = binned(&pdf, edges);
    let density: Vec<f64> = q[..nb]
        .iter()
        .zip(edges.windows(2))
        .map(|(p, w)| p / (w[1] - w[0]))
        .collect();
    let units = &result.per_path_amplitude;
    // the simulated side does not exist (a mixture whose weights are undetermined has a NaN
    // density and no units): nothing is compared, nothing is substituted
    let undefined = units.is_empty()
        || result.amplitude.density.iter().any(|d| !d.is_finite())
        || units.iter().flatten().all(|&c| c == 0);
    let mut total = vec![0u64; nb + 1];
    for u in units {
        for (t, c) in total.iter_mut().zip(u) {
            *t += c;
        }
    }
    let (h, l1, ks) = if undefined {
        (f64::NAN, f64::NAN, f64::NAN)
    } else {
        distances(&probabilities(&total), &q)
    };
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(0x7665_7273_7573); // "versus": a stream apart from every path's
    let mut boot = [Vec::new(), Vec::new(), Vec::new()];
    if units.len() >= 2 && !undefined {
        for _ in 0..RESAMPLES {
            let mut s = vec![0u64; nb + 1];
            for _ in 0..units.len() {
                let u = &units[rng.random_range(0..units.len())];
                for (t, c) in s.iter_mut().zip(u) {
                    *t += c;
                }
            }
            let d = distances(&probabilities(&s), &q);
            boot[0].push(d.0);
            boot[1].push(d.1);
            boot[2].push(d.2);
        }
    }
    let sd = |v: &Vec<f64>| {
        if v.len() < 2 {
            return f64::NAN;
        }
        let m = v.iter().sum::<f64>() / v.len() as f64;
        (v.iter().map(|x| (x - m) * (x - m)).sum::<f64>() / (v.len() as f64 - 1.0)).sqrt()
    };
    let noise: Vec<f64> = result
        .amplitude
        .stderr
        .iter()
        .map(|s| 3.0 * std::f64::consts::SQRT_2 * s)
        .collect();
    let modes_mc = (!undefined).then(|| count_modes(&result.amplitude.density, &noise));
    let modes_theory = count_modes(&density, &[]);
    let occupancy = match &result.wells {
        Some(w) => well_probabilities(&pdf, w),
        None => vec![],
    };
    let sigma1 = theory.diffusion();
    let escape_times = match &result.wells {
        Some(w) => result
            .passages
            .iter()
            .map(|p| {
                let (lo, hi) = w.core(p.to);
                let target = if p.to > p.from { lo } else { hi };
                escape_time(&pdf, sigma1, w.modes[p.from], target)
            })
            .collect(),
        None => vec![],
    };
    Ok(TheoryComparison {
        variant: theory.variant().name().to_string(),
        hellinger: Estimate {
            value: h,
            stderr: sd(&boot[0]),
        },
        l1: Estimate {
            value: l1,
            stderr: sd(&boot[1]),
        },
        ks: Estimate {
            value: ks,
            stderr: sd(&boot[2]),
        },
        modes_theory,
        modes_theory_exact: pdf.modes.len(),
        modes_mc,
        density,
        mean_amplitude: pdf.mean_amplitude,
        occupancy,
        escape_times,
    })
}

/// The theory's probability of each bin between `edges` and, last, of the mass beyond the last
/// edge (the distances' probability vectors).
pub fn binned(pdf: &AmplitudePdf, edges: &[f64]) -> Vec<f64> {
    let mut q: Vec<f64> = edges
        .windows(2)
        .map(|w| pdf.probability(w[0], w[1]))
        .collect();
    let inside: f64 = q.iter().sum();
    q.push((1.0 - inside).max(0.0));
    q
}

/// The Hellinger distance between the theory and every weighting of a well decomposition's
/// conditional densities ([`hellinger_bounds`]): for a decomposition whose conditional
/// statistics are valid but whose weights are undetermined. Errors when the replicas' counts
/// do not match the result's bins.
pub fn wells_bounds(result: &WellsResult, theory: &Theory) -> crate::Result<HellingerBounds> {
    bounds_of_counts(result, theory, &result.wells.conditional_counts)
}

/// [`wells_bounds`] on each half of the wells' windows alone (first, second;
/// `conditional_counts_halves`): where a well's conditional statistics drift, a statement over
/// every weighting stands only when it holds on both.
pub fn wells_bounds_halves(
    result: &WellsResult,
    theory: &Theory,
) -> crate::Result<Vec<HellingerBounds>> {
    let halves = &result.wells.conditional_counts_halves;
    if halves.len() != 2 {
        return Err(Error::invalid(
            "conditional_counts_halves",
            halves.len() as f64,
            "two halves",
        ));
    }
    halves
        .iter()
        .map(|c| bounds_of_counts(result, theory, c))
        .collect()
}

fn bounds_of_counts(
    result: &WellsResult,
    theory: &Theory,
    counts: &[Vec<Vec<u64>>],
) -> crate::Result<HellingerBounds> {
    let pdf = theory.amplitude_pdf()?;
    let edges = &result.result.amplitude.edges;
    let q = binned(&pdf, edges);
    let nw = result.wells.conditional.len();
    if counts.len() < 2 {
        return Err(Error::invalid(
            "conditional_counts",
            counts.len() as f64,
            "2 or more replicas",
        ));
    }
    if let Some(r) = counts.iter().find(|r| r.len() != nw) {
        return Err(Error::invalid(
            "conditional_counts",
            r.len() as f64,
            format!("{nw} wells per replica"),
        ));
    }
    if let Some(c) = counts.iter().flatten().find(|c| c.len() != q.len()) {
        return Err(Error::invalid(
            "conditional_counts",
            c.len() as f64,
            format!(
                "{} counts per well (the bins and the count beyond)",
                q.len()
            ),
        ));
    }
    Ok(hellinger_bounds(theory.variant().name(), &q, counts))
}

/// What the theory suggests for an ensemble of `params`: the wells (modes and antimodes of
/// P(A) in `variant`) and an amplitude range holding both variants' densities.
#[derive(Debug, Clone, PartialEq)]
pub struct TheoryLayout {
    /// The wells, when the theory has a stationary P(A) (D > 0).
    pub wells: Option<Wells>,
    /// Amplitudes to start paths from: the modes of P(A), or the stable limit cycles at D = 0.
    pub starts: Vec<f64>,
    /// A histogram range: 1.2 × the largest (mode + 6 widths) of both variants.
    pub amplitude_max: f64,
}

/// The [`TheoryLayout`] of `params`, or None when the averaged theory has no cycle to offer.
pub fn theory_layout(
    params: &crate::model::Params,
    variant: crate::theory::averaging::Variant,
) -> Option<TheoryLayout> {
    theory_layout_with(
        |v| Theory::new(params, v).ok(),
        variant,
        params.noise_intensity,
    )
}

/// The [`TheoryLayout`] of a model of the class ([`Theory::from_model`]: a variant whose
/// formulas do not hold for it is left out), or None when its theory has no cycle to offer.
pub fn model_layout(
    model: &crate::model::Model,
    variant: crate::theory::averaging::Variant,
) -> Option<TheoryLayout> {
    let noisy = model.noise.additive.is_some_and(|a| a.intensity > 0.0)
        || model
            .noise
            .multiplicative
            .is_some_and(|m| m.intensity > 0.0);
    theory_layout_with(
        |v| Theory::from_model(model, v).ok(),
        variant,
        if noisy { 1.0 } else { 0.0 },
    )
}

/// The layout from `theory` of each variant (None where it does not exist): the range over
/// both, the modes and wells of `variant`'s; wells only under noise (`noise` > 0).
fn theory_layout_with(
    theory: impl Fn(crate::theory::averaging::Variant) -> Option<Theory>,
    variant: crate::theory::averaging::Variant,
    noise: f64,
) -> Option<TheoryLayout> {
    use crate::theory::averaging::Variant;
    let mut top: f64 = 0.0;
    let mut chosen = None;
    for v in [Variant::Paper, Variant::Consistent] {
        let Some(th) = theory(v) else {
            continue;
        };
        let (modes, antimodes, widths) = match th.amplitude_pdf() {
            Ok(pdf) => (
                pdf.modes.clone(),
                pdf.antimodes.clone(),
                pdf.mode_widths.clone(),
            ),
            Err(_) => {
                let c: Vec<f64> = th
                    .limit_cycles()
                    .iter()
                    .filter(|c| c.stable)
                    .map(|c| c.amplitude)
                    .collect();
                let w = c.iter().map(|a| 0.05 * a).collect();
                (c, vec![], w)
            }
        };
        for (m, w) in modes.iter().zip(&widths) {
            top = top.max(m + 6.0 * w);
        }
        if v == variant {
            chosen = Some((modes, antimodes));
        }
    }
    let (modes, antimodes) = chosen?;
    if modes.is_empty() || top <= 0.0 {
        return None;
    }
    let wells = if antimodes.len() + 1 == modes.len() && noise > 0.0 {
        Wells::new(modes.clone(), antimodes).ok()
    } else {
        None
    };
    Some(TheoryLayout {
        wells,
        starts: modes,
        amplitude_max: 1.2 * top,
    })
}

/// ∫P(A) over each well (between consecutive antimodes).
pub fn well_probabilities(pdf: &AmplitudePdf, wells: &Wells) -> Vec<f64> {
    let mut bounds = vec![0.0];
    bounds.extend(&wells.antimodes);
    bounds.push(pdf.support_end);
    bounds
        .windows(2)
        .map(|w| pdf.probability(w[0], w[1]))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distances_vanish_for_equal_densities_and_are_symmetric() {
        let p = [0.1, 0.4, 0.5, 0.0];
        let q = [0.3, 0.3, 0.3, 0.1];
        assert_eq!(distances(&p, &p), (0.0, 0.0, 0.0));
        let (a, b) = (distances(&p, &q), distances(&q, &p));
        assert!((a.0 - b.0).abs() < 1e-15 && a.1 == b.1 && a.2 == b.2);
        assert!((a.1 - 0.6).abs() < 1e-15 && (a.2 - 0.2).abs() < 1e-15);
    }

    #[test]
    fn modes_follow_the_prominence_rule() {
        let v = [0.0, 1.0, 0.5, 2.0, 2.0, 0.1, 0.05, 0.06, 0.0];
        // the dip 0.05 → 0.06 is below 1 % of the maximum (0.02)
        assert_eq!(count_modes(&v, &[]), 2);
        // with noise 0.6 at bin 1 its prominence 0.5 no longer counts
        let mut noise = vec![0.0; v.len()];
        noise[1] = 0.6;
        assert_eq!(count_modes(&v, &noise), 1);
    }
}
