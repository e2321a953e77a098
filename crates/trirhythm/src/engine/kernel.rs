//! Fractional calculus kernels: Γ, the Mittag-Leffler function, product-integration weights,
//! the sum-of-exponentials (SOE) approximation of the Riemann–Liouville kernel, and the
//! convolution memory used by the predictor–corrector of [`crate::engine::Stepper`].
//!
//! # Equation
//! The Riemann–Liouville integral of order λ ∈ (0, 1],
//! J^λ g(t) = ∫₀ᵗ k(t − s) g(s) ds,  k(t) = t^{λ−1}/Γ(λ),
//! with g piecewise linear between its node values (product integration). A Caputo problem
//! D^λ y = f(t, y), y(0) = y₀ is solved in its Volterra form y(t) = y₀ + J^λ f(t).
//!
//! # Method
//! - **Product-integration weights** ([`interval_weights`]): the exact integral of u^{λ−1}
//!   against the two hat functions of an interval [u_a, u_b] (u = distance to the evaluation time
//!   in steps). Far from the evaluation time the closed form cancels catastrophically, so there
//!   the integrand is expanded around the interval's midpoint (binomial series, ratio ≤ 0.1).
//!   At λ = 1 the weights are exactly the trapezoidal ones.
//! - **Sum of exponentials** ([`SoeKernel`]): k(t) = sin(πβ)/π ∫ e^{βx} exp(−eˣ t) dx with
//!   β = 1 − λ; the trapezoidal rule in x (step Δx) turns this into Σ c_j e^{−s_j t}. Rates with
//!   s_j T ≤ q ≪ 1 are lumped into the cubic Σ_{k≤3} (−t)ᵏ/k! Σ c_j s_jᵏ (e^{−st} by its Taylor
//!   polynomial, remainder ≤ (st)⁴/24), each sum in closed form as a geometric series (for λ
//!   near 1 the kernel is nearly flat and would otherwise need thousands of slow modes); the
//!   state of the term tᵏ is the moment ∫(t_m − s)ᵏ g(s) ds, advanced exactly by the binomial
//!   theorem. q is the largest power of 1/2 whose lumped remainder stays below a tenth of the
//!   tolerance at T: with the cubic (instead of the linear term of earlier versions) q grows from
//!   1.2·10⁻⁴ to ≈ 2·10⁻², which removes about nine of the slowest modes at 1e-10.
//!   The largest Δx that meets the requested relative tolerance is chosen, and the result is
//!   **checked against the exact kernel on a log grid over [δ, T]**; construction fails with
//!   [`Error::NoConvergence`] when the tolerance is not met.
//! - **Memory** ([`super::Memory`]): `Direct` keeps every interval and applies the exact weights
//!   (O(N) work per step, O(N²) per path); `SumOfExponentials` keeps a short local window of
//!   exact weights and moves older intervals into the exponential modes, each advanced by the
//!   exact recursion Y ← e^{−sℓ}Y + ℓψ(sℓ) g_start + ℓ(φ(sℓ) − ψ(sℓ)) g_end for a linear g
//!   (O(modes) work and memory per step, independent of N). The default tolerance is sized by
//!   the error it causes in the solution, not in the kernel: 10⁻⁵·Δt² (module docs of
//!   `engine::memory`, Memory size).
//! - **Mittag-Leffler** ([`crate::special::mittag_leffler`]): the power series in log-space terms, with an error
//!   estimate from the largest term; refused where cancellation would cost more than 1e-10.
//!
//! # Reference
//! Diethelm, Ford & Freed, Nonlinear Dyn. 29 (2002) 3–22 (product trapezoidal rule);
//! Jiang, Zhang, Zhang & Zhang, Commun. Comput. Phys. 21 (2017) 650–678 (SOE for the Caputo
//! derivative); McLean, ANZIAM J. 59 (2018) (exponential sums for t^{−β}); Baffet & Hesthaven,
//! SIAM J. Numer. Anal. 55 (2017) (kernel compression); Gorenflo, Kilbas, Mainardi & Rogosin,
//! *Mittag-Leffler Functions* (2014).
//!
//! # Tests
//! Unit tests below (Γ against factorials and Γ(1/2) = √π, E_{1,1}(z) = eᶻ, E_{2,1}(−x²) = cos x,
//! E_{2,2}(−x²) = sin x / x, weights at λ = 1 equal trapezoid weights and sum to ∫u^{λ−1},
//! SOE relative error on a denser grid than the build check); `tests/convergence.rs` (observed
//! orders on known solutions), `tests/soe.rs` (SOE vs Direct).

use crate::error::{Error, Result};
use crate::maths::{exp, expm1, ln, log10, pow, sin};
use crate::special::gamma;
use std::f64::consts::PI;

/// Exact product-integration weights of one interval: with u the distance (in steps) to the
/// evaluation time and 0 ≤ u_a < u_b,
/// returns (w_a, w_b) = (∫ u^{λ−1} (u_b − u)/(u_b − u_a) du, ∫ u^{λ−1} (u − u_a)/(u_b − u_a) du)
/// over [u_a, u_b]: the weights of the values at u_a and at u_b of a linear function.
///
/// Multiply by h^λ/Γ(λ) to get the contribution to J^λ g. At λ = 1 both weights are
/// (u_b − u_a)/2 (the trapezoidal rule).
pub fn interval_weights(lambda: f64, ua: f64, ub: f64) -> (f64, f64) {
    IntervalWeights::new(lambda).of(ua, ub)
}

/// [`interval_weights`] for one order λ, its series' coefficients computed once: the memory
/// evaluates weights of arbitrary intervals at every impact (the split of a step), where the
/// series' 24 divisions per call used to cost a noisy path as much as its memory. The powers
/// uᵏ of the closed form come, for whole u in 1..[`WHOLE_POWERS`], from a table made once with
/// the same `pow` call, and for the other u from a [`Powers`] memo when the caller passes one
/// ([`IntervalWeights::of_with`]): the same bits as calling `pow` each time.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct IntervalWeights {
    lambda: f64,
    /// 2C(λ−1, 2k)/(2k + 1): the even terms of the series in ε.
    even: [f64; 12],
    /// 2C(λ−1, 2k + 1)/(2k + 3): the odd terms.
    odd: [f64; 12],
    /// k^λ for k = 0..WHOLE_POWERS (`pow(k, λ)`; index 0 unused).
    whole: [f64; WHOLE_POWERS],
}

/// The whole distances whose powers [`IntervalWeights`] tabulates: the closed form is used only
/// for intervals within about five steps of the evaluation time (farther, the series).
pub(crate) const WHOLE_POWERS: usize = 16;

/// The last two powers u^λ of non-whole u that one group of weights computed (an impact's
/// split, the memory at an instant inside a step): neighbouring intervals share their ends, so
/// about half the `pow` calls of an impact are answered from here, with the same bits.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Powers {
    seen: [Option<(u64, f64)>; 2],
    next: usize,
}

impl IntervalWeights {
    pub fn new(lambda: f64) -> Self {
        let a = lambda - 1.0;
        let mut even = [0.0; 12];
        let mut odd = [0.0; 12];
        let mut binom = 1.0; // C(a, m)
        for m in 0..24usize {
            if m > 0 {
                binom *= (a - (m as f64 - 1.0)) / m as f64;
            }
            if m % 2 == 0 {
                even[m / 2] = 2.0 * binom / (m as f64 + 1.0);
            } else {
                odd[m / 2] = 2.0 * binom / (m as f64 + 2.0);
            }
        }
        let whole = std::array::from_fn(|k| if k == 0 { 0.0 } else { pow(k as f64, lambda) });
        IntervalWeights {
            lambda,
            even,
            odd,
            whole,
        }
    }

    /// u^λ: from the table for whole u, else from `memo` or `pow` (remembered in `memo`).
    #[inline]
    fn power(&self, u: f64, memo: &mut Powers) -> f64 {
        if u >= 1.0 && u < WHOLE_POWERS as f64 && u.fract() == 0.0 {
            return self.whole[u as usize];
        }
        let bits = u.to_bits();
        for (b, v) in memo.seen.iter().flatten() {
            if *b == bits {
                return *v;
            }
        }
        let v = pow(u, self.lambda);
        memo.seen[memo.next] = Some((bits, v));
        memo.next = 1 - memo.next;
        v
    }

    /// The series and whole powers this evaluates with (for [`super::StepPlan`]).
    pub(crate) fn tables(&self) -> ([f64; 12], [f64; 12], [f64; WHOLE_POWERS]) {
        (self.even, self.odd, self.whole)
    }

    /// (w_a, w_b) of the interval [u_a, u_b], as [`interval_weights`].
    pub fn of(&self, ua: f64, ub: f64) -> (f64, f64) {
        self.of_with(ua, ub, &mut Powers::default())
    }

    /// [`IntervalWeights::of`] with the powers of the closed form taken from (and kept in)
    /// `memo` where it has them: for several intervals that share their ends.
    pub fn of_with(&self, ua: f64, ub: f64, memo: &mut Powers) -> (f64, f64) {
        let lambda = self.lambda;
        let d = ub - ua;
        if d <= 0.0 {
            return (0.0, 0.0);
        }
        let c = 0.5 * (ua + ub);
        let eps = 0.5 * d / c;
        if ua > 0.0 && eps < 0.1 {
            // u = c(1 + εx), x ∈ [−1, 1]; (1 + εx)^{λ−1} = Σ C(λ−1, m) εᵐ xᵐ, integrated
            // against 1 and x: s0 = Σ_even 2C εᵐ/(m+1), s1 = Σ_odd 2C εᵐ/(m+2), in ε² by
            // Horner (ε < 0.1: the 24th term is below 1e-24)
            let e2 = eps * eps;
            let s0 = self.even.iter().rev().fold(0.0, |acc, &c| acc * e2 + c);
            let s1 = eps * self.odd.iter().rev().fold(0.0, |acc, &c| acc * e2 + c);
            let f = 0.5 * d * pow(c, lambda - 1.0);
            (0.5 * f * (s0 - s1), 0.5 * f * (s0 + s1))
        } else {
            // u^{λ+1} = u·u^λ: two powers, one when u_a = 0 (the impacts call this often, and
            // the platform-independent `pow` is not cheap)
            let pb = self.power(ub, memo);
            let pa = if ua == 0.0 { 0.0 } else { self.power(ua, memo) };
            let m0 = (pb - pa) / lambda;
            let m1 = (ub * pb - ua * pa) / (lambda + 1.0);
            ((ub * m0 - m1) / d, (m1 - ua * m0) / d)
        }
    }

    /// u^{λ−1}, the kernel in units of steps without its 1/Γ(λ) (u ≥ 0; +∞ at u = 0 for
    /// λ < 1), its power u^λ from the table or `memo` as in [`IntervalWeights::of_with`].
    pub fn kernel_with(&self, u: f64, memo: &mut Powers) -> f64 {
        if u > 0.0 {
            self.power(u, memo) / u
        } else if self.lambda == 1.0 {
            1.0
        } else {
            f64::INFINITY
        }
    }

    /// The weights (w_a, w_b) of [u_a, u_b] and their derivatives with respect to each end:
    /// with d = u_b − u_a, ∂w_a/∂u_a = w_a/d − u_a^{λ−1}, ∂w_b/∂u_a = −w_a/d,
    /// ∂w_a/∂u_b = w_b/d, ∂w_b/∂u_b = u_b^{λ−1} − w_b/d (differentiate the integrals of
    /// [`interval_weights`] under their limits; the weights' own series or closed form, so the
    /// derivatives are those of the weights the memory uses). Returns
    /// ((w_a, w_b), (∂w_a/∂u_a, ∂w_b/∂u_a), (∂w_a/∂u_b, ∂w_b/∂u_b)); the derivatives in u_a
    /// are +∞-valued at u_a = 0 for λ < 1 and must then not be used.
    #[allow(clippy::type_complexity)]
    pub fn rates_with(
        &self,
        ua: f64,
        ub: f64,
        memo: &mut Powers,
    ) -> ((f64, f64), (f64, f64), (f64, f64)) {
        let (wa, wb) = self.of_with(ua, ub, memo);
        let d = ub - ua;
        let ka = self.kernel_with(ua, memo);
        let kb = self.kernel_with(ub, memo);
        ((wa, wb), (wa / d - ka, -wa / d), (wb / d, kb - wb / d))
    }

    /// d/dσ of the weights of [u_a + σ, u_b + σ] at σ = 0 (the interval moved away from the
    /// evaluation time): ((w_a, w_b), (dw_a, dw_b)) with dw_a = (w_a + w_b)/d − u_a^{λ−1} and
    /// dw_b = u_b^{λ−1} − (w_a + w_b)/d (the sums of the two columns of
    /// [`IntervalWeights::rates_with`]). u_a > 0 for λ < 1.
    pub fn shift_rates_with(
        &self,
        ua: f64,
        ub: f64,
        memo: &mut Powers,
    ) -> ((f64, f64), (f64, f64)) {
        let (wa, wb) = self.of_with(ua, ub, memo);
        let mean = (wa + wb) / (ub - ua);
        let ka = self.kernel_with(ua, memo);
        let kb = self.kernel_with(ub, memo);
        ((wa, wb), (mean - ka, kb - mean))
    }

    /// λ.
    pub fn lambda(&self) -> f64 {
        self.lambda
    }
}

/// The series form of [`interval_weights`] term by term, as first written (the reference of
/// the unit test for [`IntervalWeights`]).
#[cfg(test)]
fn interval_weights_termwise(lambda: f64, ua: f64, ub: f64) -> (f64, f64) {
    let d = ub - ua;
    if d <= 0.0 {
        return (0.0, 0.0);
    }
    let c = 0.5 * (ua + ub);
    let eps = 0.5 * d / c;
    if ua > 0.0 && eps < 0.1 {
        // u = c(1 + εx), x ∈ [−1, 1]; (1 + εx)^{λ−1} = Σ C(λ−1, m) εᵐ xᵐ
        let a = lambda - 1.0;
        let mut binom = 1.0;
        let mut epow = 1.0;
        let mut s0 = 0.0;
        let mut s1 = 0.0;
        for m in 0..24usize {
            if m > 0 {
                binom *= (a - (m as f64 - 1.0)) / m as f64;
                epow *= eps;
            }
            let t = binom * epow;
            if m % 2 == 0 {
                s0 += 2.0 * t / (m as f64 + 1.0);
            } else {
                s1 += 2.0 * t / (m as f64 + 2.0);
            }
            if t.abs() < 1e-20 {
                break;
            }
        }
        let f = 0.5 * d * c.powf(a);
        (0.5 * f * (s0 - s1), 0.5 * f * (s0 + s1))
    } else {
        let m0 = (ub.powf(lambda) - ua.powf(lambda)) / lambda;
        let m1 = (ub.powf(lambda + 1.0) - ua.powf(lambda + 1.0)) / (lambda + 1.0);
        ((ub * m0 - m1) / d, (m1 - ua * m0) / d)
    }
}

/// φ(z) = (1 − e^{−z})/z and ψ(z) = (1 − e^{−z}(1 + z))/z², the exact weights of a linear
/// function under e^{−s(ℓ−v)} on [0, ℓ] (z = sℓ): ∫ = ℓψ g_start + ℓ(φ − ψ) g_end.
pub(crate) fn phi_psi(z: f64) -> (f64, f64) {
    phi_psi_given(z, exp(-z))
}

/// [`phi_psi`] with e^{−z} already known (used only for z ≥ 0.5).
#[inline]
pub(crate) fn phi_psi_given(z: f64, e: f64) -> (f64, f64) {
    if z < 0.5 {
        // series in x = −z by Horner, as many terms as z needs for the first omitted one to be
        // below 1e-18 (6 for z < 1e-3, 10 for z < 0.05, else 17: slow modes are cheap):
        // φ = Σ x^k/(k+1)!, ψ = Σ (k+1) x^k/(k+2)! = Σ x^k/((k+2)·k!)
        let x = -z;
        let terms = if z < 1e-3 {
            6
        } else if z < 0.05 {
            10
        } else {
            PHI_SERIES.len()
        };
        let phi = PHI_SERIES[..terms]
            .iter()
            .rev()
            .fold(0.0, |acc, &c| acc * x + c);
        let psi = PSI_SERIES[..terms]
            .iter()
            .rev()
            .fold(0.0, |acc, &c| acc * x + c);
        (phi, psi)
    } else {
        ((1.0 - e) / z, (1.0 - e * (1.0 + z)) / (z * z))
    }
}

/// The series coefficients of φ and ψ that [`phi_psi_given`] sums (for [`super::StepPlan`]).
pub(crate) fn phi_psi_series() -> ([f64; 17], [f64; 17]) {
    (PHI_SERIES, PSI_SERIES)
}

/// 1/(k+1)!, k = 0..=16 (the series of φ; checked against the factorials in a unit test).
const PHI_SERIES: [f64; 17] = [
    1.0,
    0.5,
    0.16666666666666666,
    0.041666666666666664,
    0.008333333333333333,
    0.001388888888888889,
    0.0001984126984126984,
    2.48015873015873e-05,
    2.7557319223985893e-06,
    2.755731922398589e-07,
    2.505210838544172e-08,
    2.08767569878681e-09,
    1.6059043836821613e-10,
    1.1470745597729725e-11,
    7.647163731819816e-13,
    4.779477332387385e-14,
    2.8114572543455206e-15,
];

/// 1/((k+2)·k!), k = 0..=16 (the series of ψ).
const PSI_SERIES: [f64; 17] = [
    0.5,
    0.3333333333333333,
    0.125,
    0.03333333333333333,
    0.006944444444444444,
    0.0011904761904761906,
    0.00017361111111111112,
    2.2045855379188714e-05,
    2.48015873015873e-06,
    2.505210838544172e-07,
    2.296443268665491e-08,
    1.9270852604185937e-09,
    1.4911969277048643e-10,
    1.0706029224547743e-11,
    7.169215998581078e-13,
    4.498331606952833e-14,
    2.6552651846596585e-15,
];

/// Number of Taylor terms (t⁰…t³) that represent the slowest rates of an [`SoeKernel`].
pub const LUMPED_TERMS: usize = 4;

/// e^{−z} minus its Taylor polynomial of degree [`LUMPED_TERMS`] − 1, in absolute value,
/// for 0 ≤ z (the series Σ_{k≥4} (−z)ᵏ/k! where it converges fast, else directly).
fn taylor_remainder(z: f64) -> f64 {
    if z < 1.0 {
        let z2 = z * z;
        let mut term = z2 * z2 / 24.0;
        let mut sum = 0.0;
        for k in 4..40 {
            sum += term;
            term *= -z / (k as f64 + 1.0);
            if term.abs() < 1e-18 * sum.abs() {
                break;
            }
        }
        sum.abs()
    } else {
        (exp(-z) - (1.0 - z + z * z / 2.0 - z * z * z / 6.0)).abs()
    }
}

/// The kernel t^{λ−1}/Γ(λ) approximated by Σ_k p_k tᵏ (k ≤ 3) + Σ_j c_j e^{−s_j t} on [δ, T].
#[derive(Debug, Clone, PartialEq)]
pub struct SoeKernel {
    /// Order λ ∈ (0, 1].
    pub lambda: f64,
    /// Decay rates s_j > 0.
    pub rates: Vec<f64>,
    /// Weights c_j > 0.
    pub weights: Vec<f64>,
    /// The lumped slow rates (s·T ≤ q, q ≪ 1) as a polynomial in t, coefficients of t⁰…t³:
    /// Σ_slow c_j e^{−s_j t} = Σ_k (−t)^k/k! Σ_slow c_j s_jᵏ + O((qt/T)⁴), so the kernel is
    /// Σ_k lumped_k·tᵏ + Σ_j c_j e^{−s_j t} ((1, 0, 0, 0) at λ = 1).
    pub lumped: [f64; LUMPED_TERMS],
    /// Lower end δ of the interval on which the approximation is certified.
    pub from: f64,
    /// Upper end T.
    pub to: f64,
    /// Requested relative tolerance.
    pub tolerance: f64,
    /// Largest relative error measured on the log grid at construction.
    pub max_relative_error: f64,
}

/// The smallest λ the sum-of-exponentials kernel is built for: below it the kernel
/// t^{λ−1}/Γ(λ) is a near-delta of weight ~λ whose quadrature no longer converges at 1e-10
/// (λ = 1e-12 fails; the exact `Memory::Direct` weights have no such floor).
pub const MIN_SOE_LAMBDA: f64 = 1e-6;

/// Largest ratio of an [`SoeKernel`]'s end to its start: 20 decades (a simulation of the
/// most steps a driver takes spans 11); the construction's work grows with the decades.
pub const MAX_SOE_SPAN: f64 = 1e20;

/// Points per decade of the log grid on which an [`SoeKernel`] is verified.
pub const SOE_CHECK_POINTS_PER_DECADE: usize = 60;

impl SoeKernel {
    /// Build and verify the approximation of t^{λ−1}/Γ(λ) on [`from`, `to`] to relative
    /// `tolerance`; `to` at most [`MAX_SOE_SPAN`] × `from`. Errors when the parameters are invalid or no step Δx meets the tolerance.
    pub fn new(lambda: f64, from: f64, to: f64, tolerance: f64) -> Result<Self> {
        if !(lambda > 0.0 && lambda <= 1.0) {
            return Err(Error::invalid("lambda", lambda, "(0, 1]"));
        }
        if lambda < MIN_SOE_LAMBDA {
            return Err(Error::invalid(
                "lambda",
                lambda,
                "[1e-6, 1] with the sum-of-exponentials memory (the direct memory takes any λ in (0, 1])",
            ));
        }
        if !(from > 0.0 && from.is_finite()) {
            return Err(Error::invalid("soe window", from, "(0, ∞)"));
        }
        if !(to.is_finite() && to > 0.0 && to <= MAX_SOE_SPAN * from) {
            return Err(Error::invalid(
                "t_end",
                to,
                "(0, 1e20 × the kernel's start (the window)], finite",
            ));
        }
        if !(tolerance > 1e-15 && tolerance < 1.0) {
            return Err(Error::invalid("tolerance", tolerance, "(1e-15, 1)"));
        }
        let to = to.max(from);
        let beta = 1.0 - lambda;
        if beta == 0.0 {
            return Ok(SoeKernel {
                lambda,
                rates: vec![],
                weights: vec![],
                lumped: [1.0, 0.0, 0.0, 0.0],
                from,
                to,
                tolerance,
                max_relative_error: 0.0,
            });
        }
        let pref = sin(PI * beta) / PI;
        // highest rate: e^{−s δ} negligible
        let x_max = ln((-ln(tolerance) + 12.0) / from);
        let exact_at_end = pow(to, -beta) / gamma(lambda);
        let mut best: Option<SoeKernel> = None;
        let mut dx = 1.2;
        while dx > 0.15 {
            // lowest kept rate s₀ = q/T: the largest q whose lumped nodes (j < 0) are
            // represented by their cubic Taylor polynomial in t to a tenth of the tolerance at
            // t = T (the remainder of e^{−z} after 4 terms is below z⁴/24)
            let mut q: f64 = 1.0;
            loop {
                let x0 = ln(q / to);
                let mut err = 0.0;
                for m in 1..200 {
                    let x = x0 - m as f64 * dx;
                    let st = exp(x) * to;
                    let c = pref * dx * exp(beta * x);
                    let r = taylor_remainder(st);
                    err += c * r;
                    if c * r < 1e-3 * err {
                        break;
                    }
                }
                if err / exact_at_end <= 0.1 * tolerance || q < 1e-30 {
                    break;
                }
                q *= 0.5;
            }
            let x0 = ln(q / to);
            let n = ((x_max - x0) / dx).ceil() as usize + 1;
            let mut rates = Vec::with_capacity(n);
            let mut weights = Vec::with_capacity(n);
            for j in 0..n {
                let x = x0 + j as f64 * dx;
                rates.push(exp(x));
                weights.push(pref * dx * exp(beta * x));
            }
            // Σ_{j<0} c_j s_jᵏ = pref Δx e^{(β+k)x₀} Σ_{m≥1} e^{−(β+k)mΔx}, times (−1)ᵏ/k!
            let mut lumped = [0.0; LUMPED_TERMS];
            let mut factorial = 1.0;
            for (k, p) in lumped.iter_mut().enumerate() {
                if k > 0 {
                    factorial *= k as f64;
                }
                let a = beta + k as f64;
                let sum = pref * dx * exp(a * x0) / expm1(a * dx);
                *p = if k % 2 == 0 { sum } else { -sum } / factorial;
            }
            let mut k = SoeKernel {
                lambda,
                rates,
                weights,
                lumped,
                from,
                to,
                tolerance,
                max_relative_error: f64::INFINITY,
            };
            k.max_relative_error = k.check(SOE_CHECK_POINTS_PER_DECADE);
            if k.max_relative_error <= tolerance {
                best = Some(k);
                break;
            }
            dx -= 0.05;
        }
        best.ok_or_else(|| Error::NoConvergence {
            what: "sum-of-exponentials kernel",
            detail: format!(
                "no quadrature step met relative tolerance {tolerance:e} for λ = {} on [{from:e}, {to:e}]",
                crate::error::Exact(lambda)
            ),
        })
    }

    /// The approximation at t.
    pub fn eval(&self, t: f64) -> f64 {
        self.lumped.iter().rev().fold(0.0, |acc, &p| acc * t + p)
            + self
                .rates
                .iter()
                .zip(&self.weights)
                .map(|(&s, &c)| c * exp(-s * t))
                .sum::<f64>()
    }

    /// The exact kernel t^{λ−1}/Γ(λ).
    pub fn exact(&self, t: f64) -> f64 {
        pow(t, self.lambda - 1.0) / gamma(self.lambda)
    }

    /// Number of exponentials (the constant term not counted).
    pub fn len(&self) -> usize {
        self.rates.len()
    }

    /// True when the kernel is represented by its constant alone (λ = 1).
    pub fn is_empty(&self) -> bool {
        self.rates.is_empty()
    }

    /// Largest relative error on a log grid with `per_decade` points per decade over
    /// [`from`, `to`] (both ends included), at most 10⁵ points in all (bounded work whatever
    /// `per_decade`).
    pub fn check(&self, per_decade: usize) -> f64 {
        let decades = log10(self.to / self.from);
        let n = ((decades * per_decade as f64).ceil() as usize).clamp(2, 100_000);
        let mut worst: f64 = 0.0;
        for i in 0..=n {
            let t = self.from * pow(self.to / self.from, i as f64 / n as f64);
            let e = self.exact(t);
            worst = worst.max(((self.eval(t) - e) / e).abs());
        }
        worst
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn weights_reduce_to_trapezoid_and_integrate_constants() {
        for &(ua, ub) in &[(0.0, 1.0), (3.0, 4.0), (1000.0, 1001.0), (2.5, 2.75)] {
            let (wa, wb) = interval_weights(1.0, ua, ub);
            assert!((wa - 0.5 * (ub - ua)).abs() < 1e-14);
            assert!((wb - 0.5 * (ub - ua)).abs() < 1e-14);
        }
        for &l in &[0.3, 0.7, 0.99, 0.998] {
            for &(ua, ub) in &[(0.0, 1.0), (3.0, 4.0), (1e5, 1e5 + 1.0), (7.0, 7.001)] {
                let (wa, wb) = interval_weights(l, ua, ub);
                let exact_m0 = (ub.powf(l) - ua.powf(l)) / l;
                // sum = ∫u^{λ−1}; first moment ∫u^{λ−1}u = ua wa + ub wb
                let rel = ((wa + wb) - exact_m0).abs() / exact_m0;
                assert!(rel < 1e-9, "λ={l} [{ua},{ub}]: {rel}");
                let m1 = (ub.powf(l + 1.0) - ua.powf(l + 1.0)) / (l + 1.0);
                let rel1 = (ua * wa + ub * wb - m1).abs() / m1;
                assert!(rel1 < 1e-9, "moment λ={l} [{ua},{ub}]: {rel1}");
            }
        }
    }

    #[test]
    fn tabulated_interval_weights_equal_the_termwise_series() {
        for &l in &[0.05, 0.5, 0.9, 0.998, 1.0] {
            let w = IntervalWeights::new(l);
            for &(ua, ub) in &[
                (0.0, 1.0),
                (0.3, 1.0),
                (1.0, 2.0),
                (5.0, 5.37),
                (14.0, 15.0),
                (15.2, 16.0),
                (1e3, 1e3 + 1.0),
            ] {
                let (a, b) = w.of(ua, ub);
                let (ra, rb) = interval_weights_termwise(l, ua, ub);
                let tol = 1e-14 * (ra.abs() + rb.abs());
                assert!(
                    (a - ra).abs() <= tol && (b - rb).abs() <= tol,
                    "λ={l} [{ua},{ub}]"
                );
            }
        }
    }

    #[test]
    fn tabulated_and_remembered_powers_give_the_bits_of_pow() {
        // the closed form with `pow` at each call (as before the table and the memo) against
        // `of_with` sharing one memo over the intervals of an impact: whole ends, shared
        // non-whole ends, a start at 0, the series branch in between
        let plain = |w: &IntervalWeights, l: f64, ua: f64, ub: f64| -> (f64, f64) {
            let d = ub - ua;
            if d <= 0.0 {
                return (0.0, 0.0);
            }
            let c = 0.5 * (ua + ub);
            if ua > 0.0 && 0.5 * d / c < 0.1 {
                return w.of_with(ua, ub, &mut Powers::default());
            }
            let pb = pow(ub, l);
            let pa = if ua == 0.0 { 0.0 } else { pow(ua, l) };
            let m0 = (pb - pa) / l;
            let m1 = (ub * pb - ua * pa) / (l + 1.0);
            ((ub * m0 - m1) / d, (m1 - ua * m0) / d)
        };
        for &l in &[0.3, 0.5, 0.9, 0.998, 1.0] {
            let w = IntervalWeights::new(l);
            for &theta in &[0.0, 1e-9, 0.25, 0.4, 0.5, 0.77, 1.0 - 1e-12] {
                let mut memo = Powers::default();
                let mut intervals = vec![(0.0, theta), (0.0, 1.0 - theta), (1.0 - theta, 1.0)];
                for p in 1..20 {
                    let pf = p as f64;
                    let mid = pf + 1.0 - theta;
                    intervals.extend([(pf, mid), (mid, pf + 1.0)]);
                    let q = pf - (1.0 - theta);
                    intervals.extend([(q, q + 1.0), (pf, pf + 1.0)]);
                }
                for (ua, ub) in intervals {
                    let (a, b) = w.of_with(ua, ub, &mut memo);
                    let (ra, rb) = plain(&w, l, ua, ub);
                    assert_eq!(
                        (a.to_bits(), b.to_bits()),
                        (ra.to_bits(), rb.to_bits()),
                        "λ = {l}, [{ua}, {ub}]"
                    );
                }
            }
        }
    }

    #[test]
    fn phi_psi_series_coefficients_are_the_factorials() {
        let mut fact = 1.0; // k!
        for k in 0..PHI_SERIES.len() {
            if k > 0 {
                fact *= k as f64;
            }
            let phi = 1.0 / (fact * (k as f64 + 1.0));
            let psi = 1.0 / (fact * (k as f64 + 2.0));
            assert!((PHI_SERIES[k] - phi).abs() <= 1e-15 * phi, "phi {k}");
            assert!((PSI_SERIES[k] - psi).abs() <= 1e-15 * psi, "psi {k}");
        }
        // the truncated series against all 17 terms (the truncation is below rounding), and
        // against the closed form where that is well conditioned
        let full = |z: f64, c: &[f64]| c.iter().rev().fold(0.0, |acc, &c| acc * -z + c);
        for &z in &[
            1e-7, 1e-5, 9.99e-4, 1e-3, 0.01, 0.0499, 0.05, 0.1, 0.3, 0.4999,
        ] {
            let (p, s) = phi_psi(z);
            assert!(
                (p - full(z, &PHI_SERIES)).abs() <= 2.3e-16 * p,
                "phi series at {z}"
            );
            assert!(
                (s - full(z, &PSI_SERIES)).abs() <= 2.3e-16 * s,
                "psi series at {z}"
            );
            let em1 = (-z).exp_m1();
            assert!((p - (-em1 / z)).abs() < 2e-16, "phi at {z}");
            if z >= 0.01 {
                let exact = (-em1 - z * (-z).exp()) / (z * z);
                assert!((s - exact).abs() < 1e-12, "psi at {z}");
            }
        }
    }

    #[test]
    fn phi_psi_branches_agree() {
        for &z in &[0.49999, 0.5] {
            let (p, s) = phi_psi(z);
            let e = (-z).exp();
            assert!((p - (1.0 - e) / z).abs() < 1e-14);
            assert!((s - (1.0 - e * (1.0 + z)) / (z * z)).abs() < 1e-13);
        }
    }

    #[test]
    fn soe_meets_tolerance_on_a_denser_grid() {
        for &(l, tol) in &[(0.5, 1e-8), (0.99, 1e-10), (0.998, 1e-10)] {
            let k = SoeKernel::new(l, 0.15, 1e5, tol).unwrap();
            assert!(k.len() > 10 && k.len() < 120, "λ={l}: {} modes", k.len());
            let dense = k.check(400);
            assert!(dense <= 2.0 * tol, "λ={l}: {dense:e}");
        }
        let one = SoeKernel::new(1.0, 0.1, 1e3, 1e-10).unwrap();
        assert!(one.is_empty());
        assert_eq!(one.eval(7.0), 1.0);
    }
}
