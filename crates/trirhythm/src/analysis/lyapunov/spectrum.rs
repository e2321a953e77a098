//! The phase-reduction coefficient from sampled phase responses: the Fourier coefficients of
//! Z(θ) with its jump at the impact, and the sum c = 2Σ_{k≥1} k²|Z_k|²/(1 + k²a²), a = Ωτ.
//!
//! # Equation
//! Z = s + r, s(θ) = J(½ − θ/2π) the sawtooth of the jump J = Z(0⁺) − Z(2π⁻) (coefficients
//! J/(2πik), i.e. s = (J/π)Σ sin(kθ)/k), r continuous; Z_k = r_k + J/(2πik).
//!
//! # Method
//! J by quadratic extrapolation of the first and last three samples to 0⁺ and 2π⁻; r fitted by
//! least squares with the harmonics k ≤ K (normal equations: the samples' phases are the time
//! grid's, not uniform, and a quadrature on them errs by O((kΔθ)²), which grows with k; the fit
//! does not); above K, r_k dropped and the sawtooth's tail summed in closed form,
//! Σ_{k≥1} 1/(1 + k²a²) = (π/a·coth(π/a) − 1)/2.
//!
//! # Reference
//! The closed form: partial fractions of π coth(πx) (Abramowitz & Stegun 4.5.69).
//!
//! # Tests
//! Unit tests below: c of Z = −sin θ is 1/(2(1 + a²)) to rounding; a sawtooth's c against its
//! series summed to 2·10⁶ terms, to 10⁻⁵.

use std::f64::consts::PI;

/// Most harmonics fitted to the sampled Z.
pub const MAX_HARMONICS: usize = 64;

/// Harmonics K fitted from `phases` samples: a quarter of them, at most [`MAX_HARMONICS`].
pub(super) fn harmonics(phases: usize) -> usize {
    (phases / 4).min(MAX_HARMONICS)
}

/// Z(0⁺) and Z(2π⁻) by quadratic extrapolation from the first three and the last three
/// samples.
pub(super) fn ends(thetas: &[f64], zs: &[f64]) -> (f64, f64) {
    let n = thetas.len();
    // the Lagrange quadratic through three samples, at t
    let quad = |j: [usize; 3], t: f64| {
        let x = j.map(|i| thetas[i]);
        (0..3)
            .map(|a| {
                let (b, c) = ((a + 1) % 3, (a + 2) % 3);
                zs[j[a]] * (t - x[b]) * (t - x[c]) / ((x[a] - x[b]) * (x[a] - x[c]))
            })
            .sum::<f64>()
    };
    (quad([0, 1, 2], 0.0), quad([n - 3, n - 2, n - 1], 2.0 * PI))
}

/// c = 2Σ_{k≥1} k²|Z_k|²/(1 + k²a²) from samples (θ_j, Z_j) with the jump `jump` at θ = 0
/// (module docs of `phase`, step 5): the sum and the part of it from the sawtooth's tail above `harmonics`.
/// `a` = Ωτ > 0, or 0 for white noise without a jump.
pub(super) fn coefficient(
    thetas: &[f64],
    zs: &[f64],
    jump: f64,
    harmonics: usize,
    a: f64,
) -> (f64, f64) {
    // the continuous rest r = Z − s by least squares, s the sawtooth J(½ − θ/2π)
    let saw = |t: f64| jump * (0.5 - t / (2.0 * PI));
    let rest: Vec<f64> = thetas.iter().zip(zs).map(|(&t, &z)| z - saw(t)).collect();
    let fit = fourier_fit(thetas, &rest, harmonics);
    let mut sum = 0.0;
    for (k, &(a_k, b_k)) in fit.iter().enumerate() {
        let kf = (k + 1) as f64;
        // Z_k = (a_k − i(b_k + J/(πk)))/2: the sawtooth is (J/π)Σ sin(kθ)/k
        let b = b_k + jump / (PI * kf);
        sum += kf * kf * 0.25 * (a_k * a_k + b * b) / (1.0 + kf * kf * a * a);
    }
    let tail = if jump == 0.0 {
        0.0
    } else {
        let total = if a > 0.0 {
            // x·coth x with x = π/a, coth x = (1 + e^{−2x})/(1 − e^{−2x})
            let x = PI / a;
            let e = crate::maths::exp(-2.0 * x);
            0.5 * (x * (1.0 + e) / -crate::maths::expm1(-2.0 * x) - 1.0)
        } else {
            f64::INFINITY
        };
        let head: f64 = (1..=harmonics)
            .map(|k| 1.0 / (1.0 + (k * k) as f64 * a * a))
            .sum();
        jump * jump / (4.0 * PI * PI) * (total - head)
    };
    (2.0 * (sum + tail), 2.0 * tail)
}

/// The least-squares fit of a₀ + Σ_{k≤K}(a_k cos kθ + b_k sin kθ) to the samples (θ_j, y_j):
/// (a_k, b_k) for k = 1..K (normal equations, Gaussian elimination with partial pivoting; the
/// samples are nearly uniform, so the system is nearly diagonal).
fn fourier_fit(thetas: &[f64], ys: &[f64], harmonics: usize) -> Vec<(f64, f64)> {
    let m = 2 * harmonics + 1;
    let basis = |t: f64| -> Vec<f64> {
        let mut row = Vec::with_capacity(m);
        row.push(1.0);
        for k in 1..=harmonics {
            let x = k as f64 * t;
            row.extend([crate::maths::cos(x), crate::maths::sin(x)]);
        }
        row
    };
    let mut g = vec![vec![0.0; m + 1]; m];
    for (&t, &y) in thetas.iter().zip(ys) {
        let row = basis(t);
        for p in 0..m {
            for q in 0..m {
                g[p][q] += row[p] * row[q];
            }
            g[p][m] += row[p] * y;
        }
    }
    for col in 0..m {
        let pivot = (col..m)
            .max_by(|&i, &j| g[i][col].abs().total_cmp(&g[j][col].abs()))
            .unwrap_or(col);
        g.swap(col, pivot);
        let (top, below) = g.split_at_mut(col + 1);
        let pivot_row = &top[col];
        for row in below {
            let f = row[col] / pivot_row[col];
            for (x, p) in row[col..].iter_mut().zip(&pivot_row[col..]) {
                *x -= f * p;
            }
        }
    }
    let mut x = vec![0.0; m];
    for i in (0..m).rev() {
        let tail: f64 = (i + 1..m).map(|q| g[i][q] * x[q]).sum();
        x[i] = (g[i][m] - tail) / g[i][i];
    }
    (1..=harmonics).map(|k| (x[2 * k - 1], x[2 * k])).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid(n: usize) -> Vec<f64> {
        (0..n)
            .map(|j| 2.0 * PI * (j as f64 + 0.5) / n as f64)
            .collect()
    }

    #[test]
    fn the_coefficient_of_a_sine_and_of_a_sawtooth() {
        let th = grid(64);
        let zs: Vec<f64> = th.iter().map(|t| -t.sin()).collect();
        let a = 0.3;
        let (c, tail) = coefficient(&th, &zs, 0.0, 16, a);
        assert!((c - 0.5 / (1.0 + a * a)).abs() < 1e-12, "{c}");
        assert_eq!(tail, 0.0);
        // a sawtooth J(½ − θ/2π): c = 2(J²/4π²)Σ 1/(1 + k²a²), all of it but the head a tail
        let j = 0.7;
        let zs: Vec<f64> = th.iter().map(|t| j * (0.5 - t / (2.0 * PI))).collect();
        let (after, before) = ends(&th, &zs);
        assert!((after - before - j).abs() < 1e-12);
        let (c, _) = coefficient(&th, &zs, j, 16, a);
        let exact: f64 = (1..2_000_000u64)
            .map(|k| 1.0 / (1.0 + (k * k) as f64 * a * a))
            .sum();
        let exact = 2.0 * j * j / (4.0 * PI * PI) * exact;
        assert!((c - exact).abs() < 1e-5 * exact, "{c} {exact}");
    }
}
