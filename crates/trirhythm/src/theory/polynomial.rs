//! Real polynomials and certified isolation of their real roots.
//!
//! Equation: p(x) = Σ_i a_i x^i with real coefficients.
//!
//! Method:
//! - evaluation by compensated Horner (error-free transformations TwoSum/TwoProduct): the value
//!   is as accurate as plain Horner in twice the working precision, and comes with a bound on its
//!   error, so a sign is either certain or reported as "zero within rounding";
//! - the number of distinct real roots in (a, b] by a Sturm sequence, computed on the polynomial
//!   rescaled so that its roots are of order one;
//! - every real root in an interval by the derivative cascade: the real roots of p′ (found
//!   recursively) split the interval into pieces on which p is monotone, so each piece holds at
//!   most one root, present exactly when p changes sign across it; a critical point where p is
//!   zero within rounding is a double root (a fold) and is reported as such. Nothing is sampled,
//!   so no root is missed, however close two roots are.
//!
//! Reference: Graillat, Langlois & Louvet, "Compensated Horner scheme" (2005); Sturm's theorem
//! (e.g. Basu, Pollack & Roy, *Algorithms in Real Algebraic Geometry*, ch. 2).
//!
//! Tests: unit tests below (Wilkinson-type clusters, double roots, Sturm count equals the number
//! of roots found, proptest over random products of linear factors).

/// A real polynomial, coefficients in ascending powers.
#[derive(Debug, Clone, PartialEq)]
pub struct Polynomial {
    /// a_0, a_1, …, a_n (trailing zeros are trimmed by [`Polynomial::new`]).
    pub coefficients: Vec<f64>,
}

/// A real root with the slope of the polynomial there.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RealRoot {
    /// The root.
    pub x: f64,
    /// p′(x); zero within rounding for a double root.
    pub slope: f64,
    /// True when p′(x) is zero within rounding (a fold: two roots merging).
    pub double: bool,
}

#[inline]
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

#[inline]
fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    (p, a.mul_add(b, -p))
}

const EPS: f64 = f64::EPSILON / 2.0;

impl Polynomial {
    /// A polynomial from ascending coefficients; trailing zeros are removed.
    pub fn new(mut coefficients: Vec<f64>) -> Self {
        while coefficients.len() > 1 && *coefficients.last().unwrap() == 0.0 {
            coefficients.pop();
        }
        if coefficients.is_empty() {
            coefficients.push(0.0);
        }
        Polynomial { coefficients }
    }

    /// Degree (0 for constants, including the zero polynomial).
    pub fn degree(&self) -> usize {
        self.coefficients.len() - 1
    }

    /// Leading coefficient.
    pub fn leading(&self) -> f64 {
        *self.coefficients.last().unwrap()
    }

    /// p(x) by Horner's rule.
    #[inline]
    pub fn eval(&self, x: f64) -> f64 {
        self.coefficients
            .iter()
            .rev()
            .fold(0.0, |acc, &c| acc.mul_add(x, c))
    }

    /// p(x) by compensated Horner, with a bound on the absolute error of the returned value.
    pub fn eval_compensated(&self, x: f64) -> (f64, f64) {
        let (s, c, abs_sum) = self.horner_parts(x);
        let value = s + c;
        let gamma = (2 * self.degree() + 2) as f64 * EPS;
        let bound = EPS * value.abs() + gamma * gamma * abs_sum * 4.0 + f64::MIN_POSITIVE;
        (value, bound)
    }

    /// p(x) as an unevaluated sum `hi + lo` (compensated Horner before its final rounding): the
    /// difference of two such values is accurate even when p(x) is large and the difference small.
    pub fn eval_double_double(&self, x: f64) -> (f64, f64) {
        let (s, c, _) = self.horner_parts(x);
        let hi = s + c;
        (hi, c - (hi - s))
    }

    /// Compensated Horner: the Horner value s, its correction c, and Σ|a_i||x|^i.
    fn horner_parts(&self, x: f64) -> (f64, f64, f64) {
        let n = self.degree();
        let mut s = self.leading();
        let mut c = 0.0;
        let mut abs_sum = s.abs();
        for &a in self.coefficients[..n].iter().rev() {
            let (p, pi) = two_prod(s, x);
            let (s2, sigma) = two_sum(p, a);
            s = s2;
            c = c * x + (pi + sigma);
            abs_sum = abs_sum * x.abs() + a.abs();
        }
        (s, c, abs_sum)
    }

    /// The derivative p′.
    pub fn derivative(&self) -> Polynomial {
        if self.degree() == 0 {
            return Polynomial::new(vec![0.0]);
        }
        Polynomial::new(
            self.coefficients
                .iter()
                .enumerate()
                .skip(1)
                .map(|(i, &c)| c * i as f64)
                .collect(),
        )
    }

    /// The antiderivative vanishing at 0.
    pub fn integral(&self) -> Polynomial {
        let mut c = vec![0.0];
        c.extend(
            self.coefficients
                .iter()
                .enumerate()
                .map(|(i, &a)| a / (i + 1) as f64),
        );
        Polynomial::new(c)
    }

    /// p(s·y) as a polynomial in y.
    pub fn rescaled(&self, s: f64) -> Polynomial {
        let mut k = 1.0;
        Polynomial::new(
            self.coefficients
                .iter()
                .map(|&c| {
                    let v = c * k;
                    k *= s;
                    v
                })
                .collect(),
        )
    }

    /// An upper bound on the modulus of every root (Fujiwara's bound); 0 for constants.
    pub fn root_bound(&self) -> f64 {
        let n = self.degree();
        if n == 0 {
            return 0.0;
        }
        let an = self.leading().abs();
        let mut m: f64 = 0.0;
        for i in 1..=n {
            let a = self.coefficients[n - i].abs() / an;
            let t = if i == n {
                (a / 2.0).powf(1.0 / i as f64)
            } else {
                a.powf(1.0 / i as f64)
            };
            m = m.max(t);
        }
        2.0 * m
    }

    /// The number of distinct real roots in (a, b] by a Sturm sequence (b may be +∞).
    ///
    /// The sequence is built on the polynomial rescaled to roots of order one, with each
    /// remainder normalised and its cancelled leading coefficients (below 1e-13 of the largest)
    /// dropped, so that the count is exact except within about 1e-10 (relative) of a double root.
    pub fn sturm_count(&self, a: f64, b: f64) -> usize {
        if self.degree() == 0 {
            return 0;
        }
        let s = self.root_bound().max(f64::MIN_POSITIVE);
        let seq = sturm_sequence(&self.rescaled(s));
        let va = sign_variations(&seq, a / s);
        let vb = sign_variations(&seq, b / s);
        va.saturating_sub(vb)
    }

    /// Every real root in the open interval (lo, hi), ascending, each once (a double root once,
    /// flagged). `hi` may be `f64::INFINITY` (the root bound is used).
    pub fn real_roots(&self, lo: f64, hi: f64) -> Vec<RealRoot> {
        let bound = self.root_bound();
        let lo = lo.max(-bound * 1.0001 - f64::MIN_POSITIVE);
        let hi = hi.min(bound * 1.0001 + f64::MIN_POSITIVE);
        if self.degree() == 0 || lo.partial_cmp(&hi) != Some(std::cmp::Ordering::Less) {
            return Vec::new();
        }
        let d = self.derivative();
        let xs = roots_in(self, lo, hi);
        xs.into_iter()
            .map(|(x, double)| {
                let (slope, _) = d.eval_compensated(x);
                RealRoot {
                    x,
                    slope: if double { 0.0 } else { slope },
                    double,
                }
            })
            .collect()
    }
}

/// Roots of p in (lo, hi) with a double-root flag, by the derivative cascade.
fn roots_in(p: &Polynomial, lo: f64, hi: f64) -> Vec<(f64, bool)> {
    let n = p.degree();
    if n == 0 {
        return Vec::new();
    }
    if n == 1 {
        let x = -p.coefficients[0] / p.coefficients[1];
        return if x > lo && x < hi {
            vec![(x, false)]
        } else {
            Vec::new()
        };
    }
    let critical: Vec<f64> = roots_in(&p.derivative(), lo, hi)
        .into_iter()
        .map(|(x, _)| x)
        .collect();
    let mut out: Vec<(f64, bool)> = Vec::new();
    // Breakpoints: lo, the critical points, hi. Signs at each: +1, −1, or 0 (zero within rounding).
    let mut points = Vec::with_capacity(critical.len() + 2);
    points.push(lo);
    points.extend(critical.iter().copied());
    points.push(hi);
    let sign_at = |x: f64| -> i8 {
        let (v, err) = p.eval_compensated(x);
        if v.abs() <= err {
            0
        } else if v > 0.0 {
            1
        } else {
            -1
        }
    };
    let signs: Vec<i8> = points.iter().map(|&x| sign_at(x)).collect();
    for i in 0..points.len() - 1 {
        let (a, b) = (points[i], points[i + 1]);
        // A critical point that is a root: a double root (or a root of odd multiplicity ≥ 3,
        // which the flag reports the same way).
        if i > 0 && signs[i] == 0 {
            out.push((a, true));
        }
        let (sa, sb) = (signs[i], signs[i + 1]);
        if sa != 0 && sb != 0 && sa != sb {
            out.push((bisect_monotone(p, a, b, sa), false));
        }
    }
    out
}

/// The single root of a monotone p in (a, b), p(a) having sign `sa`, to full precision.
///
/// Illinois (modified regula falsi) steps inside the bracket, with a bisection step whenever
/// the bracket fails to halve in two steps; stops when the bracket cannot shrink in f64.
fn bisect_monotone(p: &Polynomial, mut a: f64, mut b: f64, sa: i8) -> f64 {
    let positive_at_a = sa > 0;
    let (mut fa, _) = p.eval_compensated(a);
    let (mut fb, _) = p.eval_compensated(b);
    let mut side = 0i8;
    let mut width = b - a;
    for i in 0..200 {
        let secant = if fa.is_finite() && fb.is_finite() && fa != fb {
            (a * fb - b * fa) / (fb - fa)
        } else {
            f64::NAN
        };
        let m = if i % 2 == 1 && b - a > 0.5 * width || !(secant > a && secant < b) {
            width = b - a;
            0.5 * (a + b)
        } else {
            secant
        };
        if m <= a || m >= b {
            break;
        }
        let (v, _) = p.eval_compensated(m);
        if v == 0.0 {
            return m;
        }
        if (v > 0.0) == positive_at_a {
            a = m;
            fa = v;
            if side == -1 {
                fb *= 0.5;
            }
            side = -1;
        } else {
            b = m;
            fb = v;
            if side == 1 {
                fa *= 0.5;
            }
            side = 1;
        }
        if b - a <= f64::EPSILON * a.abs().max(b.abs()) {
            break;
        }
    }
    let (va, _) = p.eval_compensated(a);
    let (vb, _) = p.eval_compensated(b);
    if va.abs() <= vb.abs() {
        a
    } else {
        b
    }
}

/// Scaled to unit maximum, with leading coefficients below 1e-13 removed: in a remainder those
/// are the cancellation residue of the division (the exact remainder has lower degree). Small
/// lower-order coefficients are kept: they carry the small roots when the roots spread over
/// decades, and a uniform threshold would miscount them.
fn normalised(mut c: Vec<f64>) -> Polynomial {
    let m = c.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    if m > 0.0 {
        for v in &mut c {
            *v /= m;
        }
    }
    while c.len() > 1 && c.last().is_some_and(|v| v.abs() < 1e-13) {
        c.pop();
    }
    if c.len() == 1 && c[0].abs() < 1e-13 {
        c[0] = 0.0;
    }
    Polynomial::new(c)
}

/// Remainder of a divided by b (both normalised), negated.
fn neg_remainder(a: &Polynomial, b: &Polynomial) -> Polynomial {
    let mut r = a.coefficients.clone();
    let nb = b.degree();
    let lb = b.leading();
    while r.len() > nb && r.len() > 1 {
        let k = r.len() - 1 - nb;
        let q = r[r.len() - 1] / lb;
        for (j, &bc) in b.coefficients.iter().enumerate() {
            r[k + j] -= q * bc;
        }
        r.pop();
    }
    if r.is_empty() {
        r.push(0.0);
    }
    normalised(r.into_iter().map(|v| -v).collect())
}

fn sturm_sequence(p: &Polynomial) -> Vec<Polynomial> {
    let p0 = normalised(p.coefficients.clone());
    let p1 = normalised(p0.derivative().coefficients);
    let mut seq = vec![p0, p1];
    loop {
        let n = seq.len();
        let last = &seq[n - 1];
        if last.degree() == 0 {
            break;
        }
        let r = neg_remainder(&seq[n - 2], last);
        if r.coefficients.iter().all(|&c| c == 0.0) {
            break;
        }
        seq.push(r);
    }
    seq
}

fn sign_variations(seq: &[Polynomial], x: f64) -> usize {
    let mut count = 0;
    let mut prev = 0.0f64;
    for q in seq {
        let v = if x.is_infinite() {
            q.leading()
                * if x > 0.0 || q.degree() % 2 == 0 {
                    1.0
                } else {
                    -1.0
                }
        } else {
            q.eval(x)
        };
        if v != 0.0 {
            if prev != 0.0 && (v > 0.0) != (prev > 0.0) {
                count += 1;
            }
            prev = v;
        }
    }
    count
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn from_roots(roots: &[f64], lead: f64) -> Polynomial {
        let mut c = vec![lead];
        for &r in roots {
            let mut n = vec![0.0; c.len() + 1];
            for (i, &a) in c.iter().enumerate() {
                n[i + 1] += a;
                n[i] -= r * a;
            }
            c = n;
        }
        Polynomial::new(c)
    }

    #[test]
    fn finds_simple_roots_and_slopes() {
        let p = from_roots(&[0.5, 2.0, 3.0], 1.0);
        let r = p.real_roots(0.0, f64::INFINITY);
        assert_eq!(r.len(), 3);
        for (got, want) in r.iter().zip([0.5, 2.0, 3.0]) {
            assert!((got.x - want).abs() < 1e-14, "{} vs {want}", got.x);
        }
        assert!(r[0].slope > 0.0 && r[1].slope < 0.0 && r[2].slope > 0.0);
        assert_eq!(p.sturm_count(0.0, f64::INFINITY), 3);
    }

    #[test]
    fn exact_double_root_is_reported_once_as_double() {
        let p = from_roots(&[1.0, 1.0, 4.0], -2.0);
        let r = p.real_roots(0.0, 10.0);
        assert_eq!(r.len(), 2, "{r:?}");
        assert!(r[0].double && (r[0].x - 1.0).abs() < 1e-7);
        assert!(!r[1].double && (r[1].x - 4.0).abs() < 1e-13);
    }

    #[test]
    fn nearly_double_roots_are_both_found() {
        // Two roots 1e-6 apart (a fold approached to 1e-12 in the parameter).
        for gap in [1e-3, 1e-5, 1e-6] {
            let p = from_roots(&[1.0, 1.0 + gap, 5.0], 1.0);
            let r = p.real_roots(0.0, f64::INFINITY);
            assert_eq!(r.len(), 3, "gap {gap}: {r:?}");
            assert!((r[0].x - 1.0).abs() < 1e-9 && (r[1].x - 1.0 - gap).abs() < 1e-9);
            assert_eq!(p.sturm_count(0.0, f64::INFINITY), 3, "gap {gap}");
        }
        // The same pair pushed just off the real axis: no root there.
        let mut p = from_roots(&[1.0, 1.0, 5.0], 1.0);
        p.coefficients[0] -= 1e-9; // p(1) = 1e-9·(…) > 0 shift: complex pair
        let r = p.real_roots(0.0, f64::INFINITY);
        assert_eq!(r.len(), 1, "{r:?}");
    }

    #[test]
    fn compensated_horner_beats_plain_near_a_cluster() {
        // (x − 1)^5 expanded: plain Horner loses everything near x = 1.
        let p = from_roots(&[1.0; 5], 1.0);
        let x = 1.0 + 1e-3;
        let (v, err) = p.eval_compensated(x);
        let exact = 1e-15; // (1e-3)^5
        assert!(
            (v - exact).abs() < 1e-6 * exact + err,
            "{v} vs {exact} ± {err}"
        );
    }

    proptest! {
        #[test]
        fn roots_of_products_are_recovered(mut roots in proptest::collection::vec(0.05f64..20.0, 1..7), lead in prop_oneof![-3.0f64..-0.1, 0.1f64..3.0]) {
            roots.sort_by(|a, b| a.partial_cmp(b).unwrap());
            // keep roots separated by at least 1e-3 relative so the test is about completeness
            roots.dedup_by(|a, b| (*a - *b).abs() < 1e-3 * b.abs());
            let p = from_roots(&roots, lead);
            let found = p.real_roots(0.0, f64::INFINITY);
            prop_assert_eq!(found.len(), roots.len());
            for (f, r) in found.iter().zip(&roots) {
                prop_assert!((f.x - r).abs() < 1e-6 * r.max(1.0), "{} vs {}", f.x, r);
            }
            prop_assert_eq!(p.sturm_count(0.0, f64::INFINITY), roots.len());
            // slopes alternate in sign
            for w in found.windows(2) {
                prop_assert!(w[0].slope * w[1].slope < 0.0);
            }
        }
    }
}
