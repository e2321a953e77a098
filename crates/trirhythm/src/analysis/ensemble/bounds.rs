//! The distance between a density and every mixture of given component densities: the
//! theory's P(A) against the stationary density of a well decomposition whose weights are
//! undetermined.
//!
//! # Problem
//! Where the well-to-well rates are only bounded, the stationary density
//! P_S(π) = Σ_i π_i P_i is known up to its weights π on the simplex, while the conditional
//! densities P_i are valid. A claim that the theory's P_T agrees (or does not) with the
//! stationary density is still decided when it holds for every weighting.
//!
//! # Method
//! On the binned probabilities (the histogram's bins and the mass beyond the last edge as one
//! more bin) the Bhattacharyya coefficient BC(π) = Σ_b √(q_b Σ_i π_i p_ib) is concave in π
//! (the square root of a linear function is concave, a sum of concave functions is concave),
//! and H(π) = √(1 − BC(π)):
//! - **H_max** = max over the simplex = √(1 − min BC): a concave function takes its minimum over
//!   a polytope at a vertex, so H_max = max_i H(P_T, P_i), exactly.
//! - **H_min** = √(1 − max BC): a concave maximisation, by projected gradient ascent (Euclidean
//!   projection onto the simplex, Michelot's algorithm by sorting) with a backtracking step that
//!   never lowers BC, started from every vertex's neighbourhood and the centre; the gradient
//!   ∂BC/∂π_i = Σ_b √q_b p_ib / (2√m_b), m_b = Σ_j π_j p_jb, is infinite where m_b = 0 < q_b p_ib,
//!   which is handled by evaluating it at a point moved a hair into the interior.
//! - **Errors.** The replicas are independent: H_min and H_max get a delete-one jackknife
//!   standard error over the replicas, each replica's own conditional counts left out in turn
//!   (the theory is exact).
//!
//! # Tests
//! Unit tests below: disjoint supports (closed form BC = Σ_i √π_i BC_i, maximal at
//! π_i ∝ BC_i²); a random property test that H_min ≤ H(π) ≤ H_max and that a fine simplex grid
//! does not beat the maximiser; the jackknife against a hand-computed case.

use super::merging::{jackknife, Estimate};
use serde::{Deserialize, Serialize};

/// The Hellinger distance to every mixture of the components.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct HellingerRange {
    /// min over the simplex of H(P_T, Σ π_i P_i).
    pub h_min: f64,
    /// The weights where it is reached.
    pub weights_min: Vec<f64>,
    /// max over the simplex (at a vertex).
    pub h_max: f64,
    /// The component where it is reached.
    pub component_max: usize,
}

/// [`HellingerRange`] with standard errors over the replicas.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct HellingerBounds {
    /// The theory's variant (`paper`, `consistent`), when known.
    pub variant: String,
    /// min over every weighting, with its jackknife standard error over the replicas.
    pub h_min: Estimate,
    /// The weights of the minimum (pooled replicas).
    pub weights_min: Vec<f64>,
    /// max over every weighting (a single well's density), with its jackknife standard error.
    pub h_max: Estimate,
    /// The well of the maximum.
    pub well_max: usize,
    /// H between the theory and each well's own density.
    pub per_well: Vec<f64>,
    /// Over which weights: `simplex` (every weighting).
    pub over: String,
}

/// Bhattacharyya coefficient of `q` with the mixture `pi` of `p`.
fn bc(q: &[f64], p: &[Vec<f64>], pi: &[f64]) -> f64 {
    q.iter()
        .enumerate()
        .map(|(b, &qb)| {
            let m: f64 = p.iter().zip(pi).map(|(pi_, w)| w * pi_[b]).sum();
            (qb * m.max(0.0)).sqrt()
        })
        .sum()
}

/// H from a Bhattacharyya coefficient.
fn h_of(bc: f64) -> f64 {
    (1.0 - bc).max(0.0).sqrt()
}

/// The Hellinger distance between `q` and the mixture `pi` of the components `p` (probability
/// vectors of one length).
pub fn hellinger_of_mixture(q: &[f64], p: &[Vec<f64>], pi: &[f64]) -> f64 {
    h_of(bc(q, p, pi))
}

/// Euclidean projection onto the probability simplex.
fn project(v: &[f64]) -> Vec<f64> {
    let mut u: Vec<f64> = v.to_vec();
    u.sort_by(|a, b| b.total_cmp(a));
    let mut cum = 0.0;
    let mut theta = 0.0;
    for (k, &x) in u.iter().enumerate() {
        cum += x;
        let t = (cum - 1.0) / (k + 1) as f64;
        if x - t > 0.0 {
            theta = t;
        }
    }
    v.iter().map(|&x| (x - theta).max(0.0)).collect()
}

/// Gradient of BC at `pi` (evaluated a hair inside the simplex, where it is finite).
fn gradient(q: &[f64], p: &[Vec<f64>], pi: &[f64]) -> Vec<f64> {
    let n = pi.len() as f64;
    let inner: Vec<f64> = pi.iter().map(|&x| (1.0 - 1e-9) * x + 1e-9 / n).collect();
    let mut g = vec![0.0; pi.len()];
    for (b, &qb) in q.iter().enumerate() {
        if qb <= 0.0 {
            continue;
        }
        let m: f64 = p.iter().zip(&inner).map(|(c, w)| w * c[b]).sum();
        if m <= 0.0 {
            continue;
        }
        let f = qb.sqrt() / (2.0 * m.sqrt());
        for (gi, c) in g.iter_mut().zip(p) {
            *gi += f * c[b];
        }
    }
    g
}

/// Projected gradient ascent of BC from `start`.
fn ascend(q: &[f64], p: &[Vec<f64>], start: Vec<f64>) -> (f64, Vec<f64>) {
    let mut pi = start;
    let mut best = bc(q, p, &pi);
    let mut step = 0.1;
    for _ in 0..5000 {
        let g = gradient(q, p, &pi);
        let mut moved = false;
        while step > 1e-15 {
            let trial: Vec<f64> = pi.iter().zip(&g).map(|(x, d)| x + step * d).collect();
            let next = project(&trial);
            let v = bc(q, p, &next);
            if v > best {
                let change: f64 = next.iter().zip(&pi).map(|(a, b)| (a - b).abs()).sum();
                moved = change > 1e-13;
                pi = next;
                best = v;
                step *= 2.0;
                break;
            }
            step *= 0.5;
        }
        if !moved {
            break;
        }
    }
    (best, pi)
}

/// The smallest and largest Hellinger distance between `q` and Σ π_i p_i over the simplex
/// (module docs). `p` holds at least one component of `q`'s length.
pub fn hellinger_range(q: &[f64], p: &[Vec<f64>]) -> HellingerRange {
    let n = p.len();
    let vertex = |i: usize| {
        (0..n)
            .map(|j| if j == i { 1.0 } else { 0.0 })
            .collect::<Vec<_>>()
    };
    let per: Vec<f64> = (0..n).map(|i| bc(q, p, &vertex(i))).collect();
    let (component_max, bc_min) = per
        .iter()
        .copied()
        .enumerate()
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .unwrap_or((0, 0.0));
    let mut starts = vec![vec![1.0 / n as f64; n]];
    for i in 0..n {
        // near each vertex, in the interior
        let mut s = vec![0.05 / n as f64; n];
        s[i] += 0.95;
        starts.push(s);
        starts.push(vertex(i));
    }
    let (bc_max, weights_min) = starts
        .into_iter()
        .map(|s| ascend(q, p, s))
        .max_by(|a, b| a.0.total_cmp(&b.0))
        .unwrap_or((0.0, vec![]));
    HellingerRange {
        h_min: h_of(bc_max),
        weights_min,
        h_max: h_of(bc_min),
        component_max,
    }
}

/// Normalised rows of counts.
fn probabilities(counts: &[f64]) -> Vec<f64> {
    let total: f64 = counts.iter().sum();
    counts
        .iter()
        .map(|&c| if total > 0.0 { c / total } else { 0.0 })
        .collect()
}

/// [`hellinger_range`] of the theory's binned probabilities `q` (bins and the mass beyond)
/// against the pooled conditional densities of `counts[replica][well]` (the same bins), with
/// delete-one jackknife standard errors over the replicas.
pub fn hellinger_bounds(variant: &str, q: &[f64], counts: &[Vec<Vec<u64>>]) -> HellingerBounds {
    let nw = counts.first().map_or(0, Vec::len);
    let nb = q.len();
    let units: Vec<Vec<f64>> = counts
        .iter()
        .map(|r| r.iter().flat_map(|c| c.iter().map(|&x| x as f64)).collect())
        .collect();
    let split = |t: &[f64]| -> Vec<Vec<f64>> {
        (0..nw)
            .map(|i| probabilities(&t[i * nb..(i + 1) * nb]))
            .collect()
    };
    let h_min = jackknife(&units, |t| hellinger_range(q, &split(t)).h_min);
    let h_max = jackknife(&units, |t| hellinger_range(q, &split(t)).h_max);
    let total: Vec<f64> = units.iter().fold(vec![0.0; nw * nb], |mut s, u| {
        for (x, y) in s.iter_mut().zip(u) {
            *x += y;
        }
        s
    });
    let p = split(&total);
    let range = hellinger_range(q, &p);
    let per_well = (0..nw)
        .map(|i| {
            let mut v = vec![0.0; nw];
            v[i] = 1.0;
            hellinger_of_mixture(q, &p, &v)
        })
        .collect();
    HellingerBounds {
        variant: variant.into(),
        h_min,
        weights_min: range.weights_min,
        h_max,
        well_max: range.component_max,
        per_well,
        over: "simplex".into(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    fn normalised(v: Vec<f64>) -> Vec<f64> {
        let s: f64 = v.iter().sum();
        v.into_iter().map(|x| x / s).collect()
    }

    #[test]
    fn disjoint_supports_have_the_closed_form() {
        // three components on disjoint bins: BC(π) = Σ √π_i BC_i, max at π_i ∝ BC_i²
        let q = normalised(vec![1.0, 2.0, 3.0, 0.5, 4.0, 1.0, 2.0, 0.2, 0.3]);
        let p = vec![
            normalised(vec![1.0, 1.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]),
            normalised(vec![0.0, 0.0, 0.0, 2.0, 1.0, 0.1, 0.0, 0.0, 0.0]),
            normalised(vec![0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 3.0, 1.0]),
        ];
        let bci: Vec<f64> = p
            .iter()
            .map(|c| bc(&q, std::slice::from_ref(c), &[1.0]))
            .collect();
        let s2: f64 = bci.iter().map(|b| b * b).sum();
        let best: Vec<f64> = bci.iter().map(|b| b * b / s2).collect();
        let r = hellinger_range(&q, &p);
        // max BC = Σ BC_i · BC_i/√Σ BC_j² = √Σ BC_i²
        assert!((r.h_min - h_of(s2.sqrt())).abs() < 1e-9, "{r:?}");
        for (a, b) in r.weights_min.iter().zip(&best) {
            assert!((a - b).abs() < 1e-5, "{:?} vs {best:?}", r.weights_min);
        }
        // the largest H at the worst component
        let worst = (0..3).min_by(|&a, &b| bci[a].total_cmp(&bci[b])).unwrap();
        assert_eq!(r.component_max, worst);
        assert!((r.h_max - h_of(bci[worst])).abs() < 1e-12);
    }

    #[test]
    fn every_mixture_lies_between_the_bounds_and_no_grid_point_beats_the_minimum() {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        for case in 0..40 {
            let bins = 12;
            let nw = 2 + case % 3;
            let mut rand_vec = |zeros: bool| {
                normalised(
                    (0..bins)
                        .map(|_| {
                            if zeros && rng.random::<f64>() < 0.4 {
                                0.0
                            } else {
                                rng.random::<f64>()
                            }
                        })
                        .collect(),
                )
            };
            let q = rand_vec(true);
            let p: Vec<Vec<f64>> = (0..nw).map(|_| rand_vec(true)).collect();
            let r = hellinger_range(&q, &p);
            assert!(r.h_min <= r.h_max + 1e-12);
            assert!((r.weights_min.iter().sum::<f64>() - 1.0).abs() < 1e-9);
            assert!(r.weights_min.iter().all(|&w| w >= 0.0));
            for _ in 0..200 {
                let pi = normalised((0..nw).map(|_| -rng.random::<f64>().ln()).collect());
                let h = hellinger_of_mixture(&q, &p, &pi);
                assert!(h >= r.h_min - 1e-9 && h <= r.h_max + 1e-12, "{h} {r:?}");
            }
            // a fine grid over the simplex (3 components: 1/200 steps)
            if nw <= 3 {
                let n = 200;
                for a in 0..=n {
                    for b in 0..=(n - a) {
                        let pi = if nw == 2 {
                            if b > 0 {
                                continue;
                            }
                            vec![a as f64 / n as f64, 1.0 - a as f64 / n as f64]
                        } else {
                            let (x, y) = (a as f64 / n as f64, b as f64 / n as f64);
                            vec![x, y, (1.0 - x - y).max(0.0)]
                        };
                        let h = hellinger_of_mixture(&q, &p, &pi);
                        assert!(h >= r.h_min - 1e-9, "grid {pi:?}: {h} < {}", r.h_min);
                    }
                }
            }
        }
    }

    #[test]
    fn jackknife_of_the_bounds_on_a_known_case() {
        // one well: the minimum and maximum are H of the pooled density; the jackknife is the
        // hand-computed delete-one spread of H over three replicas
        let q = vec![0.5, 0.5];
        let counts = vec![vec![vec![3u64, 1]], vec![vec![1, 1]], vec![vec![2, 6]]];
        let b = hellinger_bounds("paper", &q, &counts);
        let h = |a: f64, c: f64| {
            let s = a + c;
            h_of((0.5 * a / s).sqrt() + (0.5 * c / s).sqrt())
        };
        assert!((b.h_min.value - h(6.0, 8.0)).abs() < 1e-12);
        assert!((b.h_max.value - b.h_min.value).abs() < 1e-12);
        let loo = [h(3.0, 7.0), h(5.0, 7.0), h(4.0, 2.0)];
        let m = loo.iter().sum::<f64>() / 3.0;
        let se = (2.0 / 3.0 * loo.iter().map(|x| (x - m).powi(2)).sum::<f64>()).sqrt();
        assert!(
            (b.h_min.stderr - se).abs() < 1e-12,
            "{} {se}",
            b.h_min.stderr
        );
        assert!((b.h_max.stderr - se).abs() < 1e-12);
        assert_eq!(b.per_well.len(), 1);
        // two wells where one replica alone lacks a well's samples: still finite
        let counts = vec![
            vec![vec![3u64, 1], vec![0, 4]],
            vec![vec![1, 1], vec![1, 5]],
            vec![vec![2, 6], vec![0, 0]],
        ];
        let b = hellinger_bounds("paper", &q, &counts);
        assert!(b.h_min.value <= b.h_max.value);
        assert!(b.h_min.stderr.is_finite() && b.h_max.stderr.is_finite());
        // the mixture nearest q = (½, ½) from (6/14, 8/14) and (1/10, 9/10) is the first alone
        assert!((b.h_min.value - h(6.0, 8.0)).abs() < 1e-9, "{b:?}");
    }
}
