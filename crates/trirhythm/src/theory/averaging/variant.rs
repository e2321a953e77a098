//! The two variants of the averaged coefficients: the impact loss rate κ, the amplitude
//! diffusion σ1, and the phase averages they are built from.
//!
//! Equation: κ = (1−r)ω1/π (paper) or −ω1 ln(r)/π (consistent); σ1 = β2D/(ω1²(1+τ²)) (paper,
//! Eq. 26) or (β2²D/ω1²) Σ_{k≥1} b_k²/(1+4k²τ²ω1²) (consistent); w_k = ⟨cos^{2k}φ sin²φ⟩.
//!
//! Method: w_k as a product of k factors; the harmonic sum in closed form (partial fractions
//! and π a coth(π a)).
//!
//! Reference: the paper (Eq. 18, 26) and the project's `formulas.md` (the consistent variant).
//!
//! Tests: the unit tests below (the paper's weights, the phase averages by quadrature, the
//! closed form against the series).

use crate::model::Equivalents;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// Which form of the averaged formulas to use.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Variant {
    /// The paper's formulas as printed (Eq. 27's typo fixed).
    #[default]
    Paper,
    /// The corrected, self-consistent formulas: exact impact loss ω1A ln(r)/π, the coloured
    /// noise averaged through sgn(Z), ΔE = 2πω1Af.
    Consistent,
}

impl Variant {
    /// `paper` or `consistent`.
    pub fn name(self) -> &'static str {
        match self {
            Variant::Paper => "paper",
            Variant::Consistent => "consistent",
        }
    }
}

impl Equivalents {
    /// The impact loss rate κ of the averaged drift (−κA): (1−r)ω1/π (paper) or −ω1 ln(r)/π
    /// (consistent; +∞ at r = 0, which [`super::Theory::new`] rejects).
    #[inline]
    pub fn loss_rate(&self, variant: Variant, r: f64) -> f64 {
        match variant {
            Variant::Paper => (1.0 - r) * self.omega1 / PI,
            Variant::Consistent => -r.ln() * self.omega1 / PI,
        }
    }

    /// The amplitude diffusion σ1 (Eq. 26) for noise intensity D and correlation time τ:
    /// β2D/(ω1²(1+τ²)) (paper) or (β2²D/ω1²) Σ_k b_k²/(1+4k²τ²ω1²) (consistent).
    #[inline]
    pub fn diffusion(&self, variant: Variant, d: f64, tau: f64) -> f64 {
        let w1 = self.omega1;
        match variant {
            Variant::Paper => self.beta2 * d / (w1 * w1 * (1.0 + tau * tau)),
            Variant::Consistent => {
                self.beta2 * self.beta2 * d / (w1 * w1)
                    * sgn_harmonic_sum(4.0 * tau * tau * w1 * w1)
            }
        }
    }
}

/// w_k = ⟨cos^{2k}φ sin²φ⟩ over a period = C(2k, k) / (4^k (2k + 2)).
///
/// Exact product for k ≤ 10⁶; beyond, the asymptotic series
/// C(2k, k)/4^k = (πk)^{−1/2}(1 − 1/(8k) + 1/(128k²)) (relative error below 1e-19), so that any
/// k costs bounded work.
pub fn phase_average_weight(k: usize) -> f64 {
    if k > 1_000_000 {
        let kf = k as f64;
        let central = (1.0 - 1.0 / (8.0 * kf) + 1.0 / (128.0 * kf * kf)) / (PI * kf).sqrt();
        return central / (2.0 * kf + 2.0);
    }
    // C(2k,k)/4^k = Π_{j=1..k} (2j−1)/(2j)
    let mut w = 1.0;
    for j in 1..=k {
        w *= (2 * j - 1) as f64 / (2 * j) as f64;
    }
    w / (2 * k + 2) as f64
}

/// Σ_{k≥1} b_k²/(1 + c k²), b_k = 8k(−1)^{k+1}/(π(4k²−1)), in closed form; 1 at c = 0.
///
/// With q = k², b_k²/(1+ck²) = (4/π²) q/((q−¼)²(1+cq)) = (4/π²)[A/(q−¼) + B/(q−¼)² + C/(1+cq)],
/// A = 16/(4+c)², B = 1/(4+c), C = −16c/(4+c)², and Σ1/(k²−¼) = 2, Σ1/(k²−¼)² = π² − 8,
/// Σ1/(1+ck²) = (πa coth(πa) − 1)/2 with a = 1/√c. The unit test checks it against the series.
pub fn sgn_harmonic_sum(c: f64) -> f64 {
    if c == 0.0 {
        return 1.0;
    }
    let den = 4.0 + c;
    let a_ = 16.0 / (den * den);
    let b_ = 1.0 / den;
    let c_ = -16.0 * c / (den * den);
    let pa = PI / c.sqrt();
    // πa coth(πa) − 1, accurate for small πa too.
    let t = if pa < 1e-4 {
        pa * pa / 3.0
    } else {
        pa / pa.tanh() - 1.0
    };
    4.0 / (PI * PI) * (2.0 * a_ + b_ * (PI * PI - 8.0) + c_ * t / 2.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn weights_match_the_paper() {
        let paper = [512.0, 128.0, 64.0, 40.0, 28.0, 21.0];
        for (k, &w) in paper.iter().enumerate() {
            assert!(
                (phase_average_weight(k) - w / 1024.0).abs() < 1e-16,
                "k = {k}"
            );
        }
    }

    #[test]
    fn weights_are_the_phase_averages() {
        // Independent check by trapezoidal quadrature over a period (exact for trig polynomials).
        for k in 0..9 {
            let n = 64;
            let avg: f64 = (0..n)
                .map(|i| {
                    let p = 2.0 * PI * i as f64 / n as f64;
                    p.cos().powi(2 * k as i32) * p.sin().powi(2)
                })
                .sum::<f64>()
                / n as f64;
            assert!((avg - phase_average_weight(k)).abs() < 1e-15, "k = {k}");
        }
    }

    #[test]
    fn large_k_weights_continue_the_product() {
        // beyond 10⁶ the asymptotic series takes over: w_{k+1}/w_k = (2k+1)/(2k+4) across the
        // seam (the product's own rounding over 10⁶ factors is ~1e-10)
        let k = 1_000_000;
        let ratio = phase_average_weight(k + 1) / phase_average_weight(k);
        let exact = (2.0 * k as f64 + 1.0) / (2.0 * k as f64 + 4.0);
        assert!((ratio / exact - 1.0).abs() < 1e-9, "{ratio} vs {exact}");
        assert!(phase_average_weight(usize::MAX) > 0.0);
    }

    /// The series summed directly to K = 10⁶ with the integral of its large-k form as tail
    /// (π/2 − atan(y) written as atan(1/y), which does not cancel for large y).
    fn harmonic_series(c: f64) -> f64 {
        const K: usize = 1_000_000;
        let term =
            |k: f64| 64.0 * k * k / (PI * PI * (4.0 * k * k - 1.0).powi(2)) / (1.0 + c * k * k);
        let head: f64 = (1..=K).rev().map(|k| term(k as f64)).sum();
        let (a, sc) = (K as f64 + 0.5, c.sqrt());
        head + 4.0 / (PI * PI) * (1.0 / a - sc * (1.0 / (sc * a)).atan())
    }

    #[test]
    fn closed_form_harmonic_sum_matches_the_series() {
        assert_eq!(sgn_harmonic_sum(0.0), 1.0);
        for c in [
            1e-9, 1e-4, 0.01, 0.3, 0.81, 1.0, 3.24, 10.0, 100.0, 1e4, 1e7,
        ] {
            let (closed, series) = (sgn_harmonic_sum(c), harmonic_series(c));
            assert!(
                (closed - series).abs() < 1e-11 * series.max(1e-3),
                "c = {c}: {closed} vs {series}"
            );
        }
        // c → 0⁺ is continuous; large c: only k = 1 matters, ≈ b1²/c.
        assert!((sgn_harmonic_sum(1e-12) - 1.0).abs() < 1e-5);
        let b1 = 64.0 / (9.0 * PI * PI);
        assert!((sgn_harmonic_sum(1e6) * 1e6 / b1 - 1.0).abs() < 0.2);
    }
}
