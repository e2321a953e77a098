//! Recurrence analysis of a trajectory (Eq. 6–7 of the paper).
//!
//! # Equation
//! R_ij = Θ(ε − ‖Φ_i − Φ_j‖), i, j = 1..N, with Φ_i = (U_i, U̇_i) and the Euclidean norm
//! (Eq. 7). Recurrence rate RR = (1/N²) Σ_ij R_ij; determinism
//! DET = Σ_{l ≥ l_min} l P(l) / Σ_{i≠j} R_ij, with P(l) the histogram of diagonal line lengths
//! off the main diagonal (the line of identity is excluded from DET, as usual in RQA).
//!
//! # Method
//! The full symmetric matrix as a bit set (N² bits); lines counted along each upper diagonal
//! and doubled by symmetry.
//!
//! # Reference
//! Marwan, Romano, Thiel & Kurths, Phys. Rep. 438 (2007) 237–329.
//!
//! # Tests
//! Unit tests below: a periodic orbit sampled k times per period gives diagonal lines only
//! (DET = 1) and RR known by counting; a sequence with no recurrences gives RR = 1/N, DET = 0.

use crate::error::{Error, Result};

/// Recurrence threshold ε of Eq. (7).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RecurrenceThreshold(pub f64);

/// Most points of a [`RecurrenceMatrix`]: 5·10⁴ points are 312 MB of bits and 2.5·10⁹ distances.
pub const MAX_RECURRENCE_POINTS: usize = 50_000;

/// A recurrence matrix.
#[derive(Debug, Clone, PartialEq)]
pub struct RecurrenceMatrix {
    n: usize,
    bits: Vec<u64>,
}

impl RecurrenceMatrix {
    /// R_ij for the points (x_i, y_i) with the Euclidean norm; at most
    /// [`MAX_RECURRENCE_POINTS`] points (the matrix holds n² bits).
    pub fn new(x: &[f64], y: &[f64], threshold: RecurrenceThreshold) -> Result<Self> {
        let eps = threshold.0;
        if !(eps > 0.0 && eps.is_finite()) {
            return Err(Error::invalid("epsilon", eps, "(0, ∞), finite"));
        }
        if x.len() != y.len() {
            return Err(Error::invalid(
                "points",
                y.len() as f64,
                format!("as many y as x ({})", x.len()),
            ));
        }
        if x.len() > MAX_RECURRENCE_POINTS {
            return Err(Error::invalid(
                "points",
                x.len() as f64,
                format!("at most {MAX_RECURRENCE_POINTS} (the matrix holds n² bits)"),
            ));
        }
        let n = x.len();
        let mut bits = vec![0u64; (n * n).div_ceil(64)];
        let e2 = eps * eps;
        for i in 0..n {
            for j in 0..n {
                let dx = x[i] - x[j];
                let dy = y[i] - y[j];
                if dx * dx + dy * dy < e2 {
                    let k = i * n + j;
                    bits[k / 64] |= 1 << (k % 64);
                }
            }
        }
        Ok(RecurrenceMatrix { n, bits })
    }

    /// N.
    pub fn len(&self) -> usize {
        self.n
    }

    /// True for an empty series.
    pub fn is_empty(&self) -> bool {
        self.n == 0
    }

    /// R_ij.
    #[inline]
    pub fn get(&self, i: usize, j: usize) -> bool {
        let k = i * self.n + j;
        self.bits[k / 64] >> (k % 64) & 1 == 1
    }

    /// Recurrence rate RR = (1/N²) Σ R_ij.
    pub fn recurrence_rate(&self) -> f64 {
        if self.n == 0 {
            return 0.0;
        }
        let count: u64 = self.bits.iter().map(|b| b.count_ones() as u64).sum();
        count as f64 / (self.n * self.n) as f64
    }

    /// Determinism: fraction of off-diagonal recurrence points on diagonal lines of length
    /// ≥ `min_line` (usually 2).
    pub fn determinism(&self, min_line: usize) -> f64 {
        let n = self.n;
        let (mut on_lines, mut total) = (0usize, 0usize);
        for d in 1..n {
            let mut run = 0usize;
            for i in 0..(n - d) {
                if self.get(i, i + d) {
                    run += 1;
                    total += 1;
                } else {
                    if run >= min_line {
                        on_lines += run;
                    }
                    run = 0;
                }
            }
            if run >= min_line {
                on_lines += run;
            }
        }
        if total == 0 {
            0.0
        } else {
            on_lines as f64 / total as f64
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn periodic_orbit_is_fully_deterministic() {
        // a circle sampled 20 times per turn for 5 turns: point i recurs with i ± 20k only
        let k = 20;
        let n = 5 * k;
        let x: Vec<f64> = (0..n)
            .map(|i| (2.0 * std::f64::consts::PI * i as f64 / k as f64).cos())
            .collect();
        let y: Vec<f64> = (0..n)
            .map(|i| (2.0 * std::f64::consts::PI * i as f64 / k as f64).sin())
            .collect();
        let r = RecurrenceMatrix::new(&x, &y, RecurrenceThreshold(0.1)).unwrap();
        // neighbours on the circle are 2 sin(π/20) = 0.313 apart > ε: only exact repeats
        let mut pairs = 0;
        for i in 0..n {
            for j in 0..n {
                if (i as i64 - j as i64) % k as i64 == 0 {
                    pairs += 1;
                }
            }
        }
        assert!((r.recurrence_rate() - pairs as f64 / (n * n) as f64).abs() < 1e-15);
        assert_eq!(r.determinism(2), 1.0);
    }

    #[test]
    fn no_recurrence_gives_identity_only() {
        let x: Vec<f64> = (0..50).map(|i| i as f64).collect();
        let y = vec![0.0; 50];
        let r = RecurrenceMatrix::new(&x, &y, RecurrenceThreshold(0.5)).unwrap();
        assert!((r.recurrence_rate() - 1.0 / 50.0).abs() < 1e-15);
        assert_eq!(r.determinism(2), 0.0);
        assert!(RecurrenceMatrix::new(&x, &y, RecurrenceThreshold(-1.0)).is_err());
    }
}
