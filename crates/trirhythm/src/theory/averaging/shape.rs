//! The shape of the stationary amplitude density, ln P(A) up to a constant, for a constant or
//! an amplitude-dependent diffusion.
//!
//! Equation: P(A) ∝ b⁻¹exp∫2(f + m_c)/b dA with f = A g(x), x = A², m_c = σ1/(2A) + qA,
//! b = σ1 + b_1x. With dA = dx/(2A): ln P = ln A − (3/2) ln b(x) + I(x) + const,
//! I(x) = ∫^x p(t)/b(t) dt, p = g + q (the σ1/(2x b) part of the integrand integrates to
//! ½ ln x − ½ ln b). Constant diffusion (b_1 = 0, q = 0): ln P = ln A + G(x)/σ1, G = ∫g (Eq. 27).
//!
//! Method: additive noise keeps the paper's form (G in double-double, divided by σ1: the same
//! bits as before). With b_1 > 0, I(x) is exact: for σ1 = 0 it is Σ_{k≥1}p_kx^k/(kb_1) +
//! (p_0/b_1) ln x; for σ1 > 0, with r0 = σ1/b_1, the geometric series
//! Σ_j (−1/r0)^j/σ1 ∫₀^x p(t)t^j dt for x ≤ r0/2 (ratio ≤ ½) and the partial fractions
//! p = (x + r0)s(x) + R, I = ∫₀^x s/b_1 + (R/b_1) ln(1 + x/r0) beyond (where their
//! cancellation is at most (r0/x)^n ≤ 2^n), so that neither suffers the other's cancellation.
//!
//! Reference: Khasminskii's stochastic averaging; the FPK equation's stationary solution with
//! zero flux.
//!
//! Tests: `tests/averaging.rs::class::multiplicative_pdf_solves_the_fpk` (I against adaptive
//! Gauss–Kronrod of p/b, the density normalised, its modes at the roots of 2(f + m_c) = b′).

use crate::theory::polynomial::Polynomial;

/// ln P(A) up to a constant, and its curvature.
#[derive(Debug, Clone)]
pub(super) enum Shape {
    /// b = σ1: ln P = ln A + G(x)/σ1.
    Additive {
        g_integral: Polynomial,
        g: Polynomial,
        g_derivative: Polynomial,
        sigma1: f64,
    },
    /// b = σ1 + b_1x: ln P = ln A − (3/2) ln b + I(x).
    General {
        /// p = g + q.
        p: Polynomial,
        p_derivative: Polynomial,
        sigma1: f64,
        b1: f64,
    },
}

impl Shape {
    /// The part of ln P that depends on x = A² beyond ln A, as a double-double (hi, lo); it is
    /// divided by [`Shape::divisor`].
    pub fn w(&self, x: f64) -> (f64, f64) {
        match self {
            Shape::Additive { g_integral, .. } => g_integral.eval_double_double(x),
            Shape::General { p, sigma1, b1, .. } => (
                integral(p, *sigma1, *b1, x) - 1.5 * (sigma1 + b1 * x).ln(),
                0.0,
            ),
        }
    }

    /// σ1 for additive noise, else 1.
    pub fn divisor(&self) -> f64 {
        match self {
            Shape::Additive { sigma1, .. } => *sigma1,
            Shape::General { .. } => 1.0,
        }
    }

    /// [w(x) − w(x_p)]/divisor from the double-doubles.
    pub fn difference(&self, w: (f64, f64), peak_w: (f64, f64)) -> f64 {
        ((w.0 - peak_w.0) + (w.1 - peak_w.1)) / self.divisor()
    }

    /// φ(A) = ln A + w(A²)/divisor (ln P up to a constant; for comparing modes).
    pub fn phi(&self, a: f64) -> f64 {
        match self {
            Shape::Additive {
                g_integral, sigma1, ..
            } => a.ln() + g_integral.eval(a * a) / sigma1,
            Shape::General { .. } => a.ln() + self.w(a * a).0,
        }
    }

    /// φ″ at x = A².
    pub fn curvature(&self, x: f64) -> f64 {
        match self {
            Shape::Additive {
                g,
                g_derivative,
                sigma1,
                ..
            } => -1.0 / x + (2.0 * g.eval(x) + 4.0 * x * g_derivative.eval(x)) / sigma1,
            Shape::General {
                p,
                p_derivative,
                sigma1,
                b1,
            } => {
                // w′ = p/b − (3/2)b_1/b, w″ = (p′b − p b_1)/b² + (3/2)b_1²/b²; φ″ = −1/x + 2w′ + 4xw″
                let b = sigma1 + b1 * x;
                let (pv, dp) = (p.eval(x), p_derivative.eval(x));
                let w1 = (pv - 1.5 * b1) / b;
                let w2 = (dp * b - pv * b1 + 1.5 * b1 * b1) / (b * b);
                -1.0 / x + 2.0 * w1 + 4.0 * x * w2
            }
        }
    }
}

/// I(x) = ∫^x p(t)/(σ1 + b_1t) dt (from 0 when σ1 > 0; up to a constant when σ1 = 0).
pub(super) fn integral(p: &Polynomial, sigma1: f64, b1: f64, x: f64) -> f64 {
    let c = &p.coefficients;
    if sigma1 == 0.0 {
        let mut sum = 0.0;
        for (k, &pk) in c.iter().enumerate().skip(1).rev() {
            sum = (sum + pk / k as f64) * x;
        }
        return (sum + c[0] * x.ln()) / b1;
    }
    let r0 = sigma1 / b1;
    if x <= 0.5 * r0 {
        // Σ_j (−x/r0)^j/σ1 · Σ_k p_k x^{k+1}/(k + j + 1)
        let mut total = 0.0;
        let mut factor = x / sigma1;
        for j in 0..400 {
            let mut inner = 0.0;
            for (k, &pk) in c.iter().enumerate().rev() {
                inner = inner * x + pk / (k + j + 1) as f64;
            }
            let term = factor * inner;
            total += term;
            if term.abs() <= 1e-17 * total.abs() && j > 0 {
                break;
            }
            factor *= -x / r0;
        }
        return total;
    }
    // synthetic division by (x + r0): p = (x + r0)s + R
    let n = c.len();
    let mut s = vec![0.0; n.saturating_sub(1)];
    let mut carry = 0.0;
    for k in (1..n).rev() {
        carry = c[k] - r0 * carry;
        s[k - 1] = carry;
    }
    let remainder = c[0] - r0 * carry;
    let mut poly = 0.0;
    for (k, &sk) in s.iter().enumerate().rev() {
        poly = (poly + sk / (k + 1) as f64) * x;
    }
    (poly + remainder * (x / r0).ln_1p()) / b1
}
