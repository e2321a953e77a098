//! Allocation-free evaluation of the averaged polynomials g(x) = f/A and h(x) = A·m1 at one
//! parameter point, and the certified stable-root count on them.
//!
//! [`crate::theory::averaging::Theory::new`] clones the parameters and allocates its polynomials; a map
//! of 10⁶ points cannot afford that. Here a parameter point is a `Copy` struct, the
//! coefficients are built on the stack with the same arithmetic as `Theory` (bit-identical
//! coefficients for the paper variant), and the Sturm count follows
//! [`crate::theory::polynomial::Polynomial::sturm_count`] on fixed-size arrays (power-of-two scaling,
//! rolled sequence: only rounding differs, so counts agree except within ~1e-10 of a fold).

use crate::error::{Error, Result};
use crate::model::Equivalents;
use crate::model::Params;
use crate::theory::averaging::{phase_average_weight, Variant};
use serde::{Deserialize, Serialize};

/// Most damping coefficients c_0 … c_{MAXC−1} the fast path supports (P(U) up to U^22).
pub const MAXC: usize = 12;
/// Capacity of a stack polynomial: h has one coefficient more than g.
pub(crate) const CAP: usize = MAXC + 1;

/// Which polynomial a classification looks at.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum What {
    /// Stable limit cycles of the noise-free averaged system: stable roots of g = f/A.
    #[default]
    Rhythmicity,
    /// Maxima of the stationary P(A): stable roots of h = A·m1 (needs D > 0).
    Modes,
}

impl What {
    /// `rhythmicity` or `modes`.
    pub fn name(self) -> &'static str {
        match self {
            What::Rhythmicity => "rhythmicity",
            What::Modes => "modes",
        }
    }
}

/// A parameter by key, resolved once so that setting it per grid point costs nothing.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Key {
    /// μ0.
    Mu0,
    /// ω0.
    Omega0,
    /// λ.
    Lambda,
    /// r.
    Restitution,
    /// D.
    Noise,
    /// τ.
    Tau,
    /// c_k times a sign (α0 = c2, β0 = −c3, γ0 = c4, δ0 = −c5).
    Coefficient(usize, f64),
}

impl Key {
    /// Resolve a key as [`Params::get`] accepts it.
    pub fn parse(key: &str) -> Result<Key> {
        let k = match key {
            "mu0" => Key::Mu0,
            "omega0" => Key::Omega0,
            "lambda" => Key::Lambda,
            "r" => Key::Restitution,
            "D" => Key::Noise,
            "tau" => Key::Tau,
            "alpha0" => Key::Coefficient(2, 1.0),
            "beta0" => Key::Coefficient(3, -1.0),
            "gamma0" => Key::Coefficient(4, 1.0),
            "delta0" => Key::Coefficient(5, -1.0),
            _ => {
                // Let Params report unknown keys with its own message.
                Params::default().get(key)?;
                let k: usize = key[1..].parse().expect("Params accepted c<k>");
                Key::Coefficient(k, 1.0)
            }
        };
        if let Key::Coefficient(k, _) = k {
            if k >= MAXC {
                return Err(Error::invalid(
                    key,
                    k as f64,
                    format!("a coefficient index below {MAXC} for maps"),
                ));
            }
        }
        Ok(k)
    }
}

/// One parameter point, `Copy`, with the damping polynomial inline.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Point {
    mu0: f64,
    omega0: f64,
    lambda: f64,
    r: f64,
    d: f64,
    tau: f64,
    c: [f64; MAXC],
    nc: usize,
}

impl Point {
    /// From (valid) parameters; fails when P(U) has more than [`MAXC`] coefficients.
    pub fn new(params: &Params) -> Result<Point> {
        let n = params.damping.coefficients.len();
        if n > MAXC {
            return Err(Error::invalid(
                format!("c{}", n - 1),
                params.damping.coefficients[n - 1],
                format!("a damping polynomial of at most {MAXC} coefficients for maps"),
            ));
        }
        let mut c = [0.0; MAXC];
        c[..n].copy_from_slice(&params.damping.coefficients);
        Ok(Point {
            mu0: params.mu0,
            omega0: params.omega0,
            lambda: params.lambda,
            r: params.restitution,
            d: params.noise_intensity,
            tau: params.correlation_time,
            c,
            nc: n,
        })
    }

    /// Set one parameter.
    #[inline]
    pub fn set(&mut self, key: Key, v: f64) {
        match key {
            Key::Mu0 => self.mu0 = v,
            Key::Omega0 => self.omega0 = v,
            Key::Lambda => self.lambda = v,
            Key::Restitution => self.r = v,
            Key::Noise => self.d = v,
            Key::Tau => self.tau = v,
            Key::Coefficient(k, s) => {
                self.c[k] = s * v;
                if k >= self.nc {
                    self.nc = k + 1;
                }
            }
        }
    }
}

/// A polynomial on the stack, ascending coefficients, `len` of them.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Coeffs {
    pub c: [f64; CAP],
    pub len: usize,
}

impl Coeffs {
    pub(crate) fn zero() -> Self {
        Coeffs {
            c: [0.0; CAP],
            len: 1,
        }
    }

    #[inline]
    pub(crate) fn slice(&self) -> &[f64] {
        &self.c[..self.len]
    }

    /// p(x) by Horner (fused, as `Polynomial::eval`).
    #[inline]
    pub(crate) fn eval(&self, x: f64) -> f64 {
        self.slice()
            .iter()
            .rev()
            .fold(0.0, |acc, &c| acc.mul_add(x, c))
    }

    /// (p, p′, p″) at x, and Σ|a_i| x^i (the scale of p's rounding and of its value).
    pub(crate) fn eval_derivs(&self, x: f64) -> [f64; 4] {
        let (mut p, mut d1, mut d2, mut s) = (0.0, 0.0, 0.0, 0.0);
        for &a in self.slice().iter().rev() {
            d2 = d2 * x + 2.0 * d1;
            d1 = d1 * x + p;
            p = p * x + a;
            s = s * x.abs() + a.abs();
        }
        [p, d1, d2, s]
    }

    fn trim(&mut self) {
        while self.len > 1 && self.c[self.len - 1] == 0.0 {
            self.len -= 1;
        }
    }
}

/// Builds g or h at a point; holds only constants (the phase-average weights).
#[derive(Debug, Clone, Copy)]
pub struct Kernel {
    variant: Variant,
    weights: [f64; MAXC],
}

impl Kernel {
    /// A kernel for one formula variant.
    pub fn new(variant: Variant) -> Self {
        let mut weights = [0.0; MAXC];
        for (k, w) in weights.iter_mut().enumerate() {
            *w = phase_average_weight(k);
        }
        Kernel { variant, weights }
    }

    /// The variant.
    pub fn variant(&self) -> Variant {
        self.variant
    }

    /// g (Rhythmicity) or h (Modes) at `p`, from the same scalar functions as `Theory::new`
    /// ([`Equivalents::from_scalars`], `loss_rate`, `diffusion`).
    #[inline]
    pub(crate) fn coefficients(&self, p: &Point, what: What) -> Coeffs {
        let eq = Equivalents::from_scalars(p.mu0, p.omega0, p.lambda, p.c[0]);
        let (mu1, beta1) = (eq.mu1, eq.beta1);
        let loss = eq.loss_rate(self.variant, p.r);
        let mut out = Coeffs::zero();
        let off = match what {
            What::Rhythmicity => 0,
            What::Modes => {
                out.c[0] = eq.diffusion(self.variant, p.d, p.tau) / 2.0;
                1
            }
        };
        for k in 0..p.nc {
            out.c[off + k] = mu1 * if k == 0 { beta1 } else { p.c[k] } * self.weights[k];
        }
        out.c[off] -= loss;
        out.len = off + p.nc;
        out.trim();
        out
    }

    /// The printed Eq. 37 at a point, as a polynomial in x = A² (paper variant's constants):
    /// μ1(−128β1x + 96α0x² − 80β0x³ + 70γ0x⁴ − 63δ0x⁵ …) + 256(μ1 − 2(1−r)ω1/π), i.e. the
    /// correct d(xg)/dx·512 with β1 moved from the constant to the x term, generalised to any
    /// degree by the same weights: coefficient of x^k (k ≥ 2) is 512 μ1 c_k (k+1) w_k.
    pub(crate) fn printed_eq37(&self, p: &Point) -> Coeffs {
        let eq = Equivalents::from_scalars(p.mu0, p.omega0, p.lambda, p.c[0]);
        let (mu1, beta1) = (eq.mu1, eq.beta1);
        let kappa = eq.loss_rate(Variant::Paper, p.r);
        let mut out = Coeffs::zero();
        // Constant: 256(μ1 c0 − 2κ) (c0 = 1 in the paper); x term: −128 μ1 β1 (the paper's
        // −c1·... with c1 = −1 replaced by β1).
        out.c[0] = 256.0 * (mu1 * p.c[0] - 2.0 * kappa);
        out.c[1] = if p.nc > 1 {
            128.0 * mu1 * beta1 * p.c[1]
        } else {
            0.0
        };
        for k in 2..p.nc {
            out.c[k] = 512.0 * mu1 * p.c[k] * (k + 1) as f64 * self.weights[k];
        }
        out.len = p.nc.max(1);
        out.trim();
        out
    }

    /// Stable roots of g (limit cycles) or h (modes of P(A)) on x > 0, by the certified Sturm
    /// count: the same count as `Theory::stable_count_fast` on the same polynomial.
    #[inline]
    pub fn stable_count(&self, p: &Point, what: What) -> usize {
        stable_count(&self.coefficients(p, what))
    }
}

/// Stable roots (+ → − crossings) on x > 0, as [`crate::theory::averaging::stable_count`].
#[inline]
pub(crate) fn stable_count(p: &Coeffs) -> usize {
    let n = sturm_count_positive(p);
    if p.c[0] > 0.0 {
        n.div_ceil(2)
    } else {
        n / 2
    }
}

/// Distinct real roots in (0, ∞]: the algorithm of `Polynomial::sturm_count(0, ∞)` (rescale
/// to roots of order one, normalised Sturm sequence with coefficients below 1e-13 dropped) on
/// the stack, with two differences that only change rounding: the scale is Fujiwara's bound
/// rounded up to a power of two (so the rescaling is exact and needs no `powf`), and the
/// sequence is rolled (only the signs of each member at 0 and +∞ are kept).
pub(crate) fn sturm_count_positive(p: &Coeffs) -> usize {
    let mut p = *p;
    p.trim();
    let n = p.len - 1;
    if n == 0 {
        return 0;
    }
    // log2 of Fujiwara's bound 2·max_i (|a_{n−i}|/|a_n|)^{1/i} (the last term halved), rounded
    // up to an integer: exponent arithmetic only.
    let an = p.c[n].abs();
    let mut e_max = i32::MIN;
    for i in 1..=n {
        let mut a = p.c[n - i].abs() / an;
        if i == n {
            a /= 2.0;
        }
        if a == 0.0 || !a.is_finite() {
            continue;
        }
        let e = exponent_ceil(a);
        e_max = e_max.max(e.div_euclid(i as i32) + i32::from(e.rem_euclid(i as i32) != 0));
    }
    if e_max != i32::MIN {
        let s = pow2(e_max + 1);
        let mut k = 1.0;
        for v in p.c[..p.len].iter_mut() {
            *v *= k;
            k *= s;
        }
        p.trim();
    }
    let mut at0 = Variations::default();
    let mut at_inf = Variations::default();
    // The polynomial and its derivative are exact data: scaled, never truncated (dropping their
    // small coefficients loses the small roots when the roots spread over decades).
    let mut a = scaled(p);
    let mut d = Coeffs::zero();
    if a.len > 1 {
        d.len = a.len - 1;
        for i in 1..a.len {
            d.c[i - 1] = a.c[i] * i as f64;
        }
        d.trim();
    }
    let mut b = scaled(d);
    at0.push(a.c[0]);
    at_inf.push(a.c[a.len - 1]);
    at0.push(b.c[0]);
    at_inf.push(b.c[b.len - 1]);
    let mut guard = 0;
    while b.len > 1 && guard <= CAP {
        let r = neg_remainder(&a, &b);
        if r.slice().iter().all(|&c| c == 0.0) {
            break;
        }
        at0.push(r.c[0]);
        at_inf.push(r.c[r.len - 1]);
        a = b;
        b = r;
        guard += 1;
    }
    at0.count.saturating_sub(at_inf.count)
}

/// Sign variations of a sequence of values, zeros skipped.
#[derive(Default)]
struct Variations {
    prev: f64,
    count: usize,
}

impl Variations {
    #[inline]
    fn push(&mut self, v: f64) {
        if v != 0.0 {
            if self.prev != 0.0 && (v > 0.0) != (self.prev > 0.0) {
                self.count += 1;
            }
            self.prev = v;
        }
    }
}

/// Smallest e with a ≤ 2^e (a > 0, finite).
#[inline]
fn exponent_ceil(a: f64) -> i32 {
    let bits = a.to_bits();
    let exp = ((bits >> 52) & 0x7ff) as i32;
    if exp == 0 {
        // subnormal: tiny, any small exponent will do
        return -1074;
    }
    let mant = bits & ((1u64 << 52) - 1);
    (exp - 1023) + i32::from(mant != 0)
}

/// 2^e for e in the normal range (clamped).
#[inline]
fn pow2(e: i32) -> f64 {
    let e = e.clamp(-1022, 1023);
    f64::from_bits(((e + 1023) as u64) << 52)
}

#[inline]
fn scaled(mut p: Coeffs) -> Coeffs {
    let m = p.slice().iter().fold(0.0f64, |m, v| m.max(v.abs()));
    if m > 0.0 {
        let inv = 1.0 / m;
        for v in p.c[..p.len].iter_mut() {
            *v *= inv;
        }
    }
    p.trim();
    p
}

/// A remainder scaled to unit maximum, with leading coefficients below 1e-13 removed: those are
/// the cancellation residue of the division (the exact remainder has lower degree). Small
/// lower-order coefficients are kept: they carry the small roots when the roots spread over
/// decades, and truncating them (as a uniform threshold would) miscounts.
#[inline]
fn normalised(mut p: Coeffs) -> Coeffs {
    p = scaled(p);
    while p.len > 1 && p.c[p.len - 1].abs() < 1e-13 {
        p.len -= 1;
    }
    if p.len == 1 && p.c[0].abs() < 1e-13 {
        p.c[0] = 0.0;
    }
    p
}

#[inline]
fn neg_remainder(a: &Coeffs, b: &Coeffs) -> Coeffs {
    let mut r = *a;
    let nb = b.len - 1;
    let lb = b.c[nb];
    while r.len > nb && r.len > 1 {
        let k = r.len - 1 - nb;
        let q = r.c[r.len - 1] / lb;
        for j in 0..b.len {
            r.c[k + j] -= q * b.c[j];
        }
        r.len -= 1;
    }
    if r.len == 0 {
        r.len = 1;
        r.c[0] = 0.0;
    }
    for v in r.c[..r.len].iter_mut() {
        *v = -*v;
    }
    normalised(r)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::theory::averaging::Theory;
    use crate::theory::polynomial::Polynomial;
    use proptest::prelude::*;

    #[test]
    fn coefficients_equal_theorys_polynomials() {
        let k = Kernel::new(Variant::Paper);
        for name in ["fig4c", "fig10", "fig12b", "fig2i", "fig5"] {
            let params = crate::model::preset(name).unwrap().params;
            let th = Theory::new(&params, Variant::Paper).unwrap();
            let p = Point::new(&params).unwrap();
            assert_eq!(
                k.coefficients(&p, What::Rhythmicity).slice(),
                th.drift_polynomial().coefficients.as_slice(),
                "{name}"
            );
            if params.noise_intensity > 0.0 {
                assert_eq!(
                    k.coefficients(&p, What::Modes).slice(),
                    th.fpk_polynomial().coefficients.as_slice(),
                    "{name}"
                );
            }
        }
    }

    #[test]
    fn printed_eq37_equals_the_corrected_form_at_lambda_one() {
        // At λ = 1, β1 = 1 and the printed Eq. 37 is 512·d(xg)/dx.
        let mut params = crate::model::preset("fig12a").unwrap().params;
        params.lambda = 1.0;
        let k = Kernel::new(Variant::Paper);
        let p = Point::new(&params).unwrap();
        let e37 = k.printed_eq37(&p);
        let g = Polynomial::new(k.coefficients(&p, What::Rhythmicity).slice().to_vec());
        let mut xg = vec![0.0];
        xg.extend(g.coefficients.iter());
        let dxg = Polynomial::new(xg).derivative();
        for (a, b) in e37.slice().iter().zip(&dxg.coefficients) {
            assert!(
                (a - 512.0 * b).abs() < 1e-12 * a.abs().max(1e-3),
                "{a} vs {b}"
            );
        }
    }

    proptest! {
        #[test]
        fn fast_count_equals_the_root_isolation(mu0 in 0.001f64..0.8, lambda in 0.9f64..=1.0, r in 0.5f64..=1.0,
                                    g0 in 0.0f64..1.2e-4, d0 in 1e-8f64..6e-7, d in 0.01f64..1.5,
                                    tau in 0.0f64..5.0, w0 in 0.5f64..1.2) {
            let mut params = Params { mu0, lambda, restitution: r, omega0: w0,
                                      noise_intensity: d, correlation_time: tau, ..Params::default() };
            params.set("gamma0", g0).unwrap();
            params.set("delta0", d0).unwrap();
            let k = Kernel::new(Variant::Paper);
            let p = Point::new(&params).unwrap();
            let th = Theory::new(&params, Variant::Paper).unwrap();
            // D > 0: Theory counts modes (roots of h); `rhythmicity` isolates the roots by the
            // derivative cascade, an algorithm independent of the Sturm count.
            prop_assert_eq!(k.stable_count(&p, What::Modes), th.rhythmicity().count());
            let th0 = Theory::new(&Params { noise_intensity: 0.0, ..params.clone() }, Variant::Paper).unwrap();
            prop_assert_eq!(k.stable_count(&p, What::Rhythmicity), th0.rhythmicity().count());
        }
    }
}
