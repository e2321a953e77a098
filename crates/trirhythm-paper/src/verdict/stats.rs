//! The statistics the rules use: the normal tail, its inverse, and the Holm–Bonferroni
//! step-down correction.
//!
//! Method: the complementary error function by the Chebyshev-fitted rational form of Numerical
//! Recipes (§6.2, `erfcc`, fractional error below 1.2·10⁻⁷ everywhere), its inverse by
//! bisection; Holm, "A simple sequentially rejective multiple test procedure", Scand. J.
//! Statist. 6 (1979) 65–70. Checked by the unit tests below (Φ at known quantiles; Holm on a
//! textbook family).

/// Complementary error function erfc(x), fractional error < 1.2·10⁻⁷.
pub fn erfc(x: f64) -> f64 {
    let z = x.abs();
    let t = 1.0 / (1.0 + 0.5 * z);
    let poly = -z * z - 1.265_512_23
        + t * (1.000_023_68
            + t * (0.374_091_96
                + t * (0.096_784_18
                    + t * (-0.186_288_06
                        + t * (0.278_868_07
                            + t * (-1.135_203_98
                                + t * (1.488_515_87 + t * (-0.822_152_23 + t * 0.170_872_77))))))));
    let ans = t * poly.exp();
    if x >= 0.0 {
        ans
    } else {
        2.0 - ans
    }
}

/// Upper tail of the standard normal, P(Z > z).
pub fn normal_sf(z: f64) -> f64 {
    0.5 * erfc(z / std::f64::consts::SQRT_2)
}

/// Two-sided p-value of a z statistic, 2·P(Z > |z|).
pub fn two_sided_p(z: f64) -> f64 {
    (2.0 * normal_sf(z.abs())).min(1.0)
}

/// The |z| whose two-sided p-value is `p` (bisection on [0, 40]).
pub fn z_for_two_sided(p: f64) -> f64 {
    if p >= 1.0 {
        return 0.0;
    }
    let (mut lo, mut hi) = (0.0f64, 40.0f64);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if two_sided_p(mid) > p {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// Two-sided p-value of Student's t with `nu` degrees of freedom, P(|T| > |t|), by the closed
/// forms of Abramowitz & Stegun 26.7.3–4 for integer ν (a fractional ν is rounded down, which
/// is conservative); the normal tail for ν ≥ 1000 or ν not finite.
pub fn t_two_sided_p(t: f64, nu: f64) -> f64 {
    if !nu.is_finite() || nu >= 1000.0 {
        return two_sided_p(t);
    }
    let n = nu.floor().max(1.0) as u32;
    let theta = (t.abs() / (n as f64).sqrt()).atan();
    let (s, c) = theta.sin_cos();
    let a = if n % 2 == 1 {
        // odd ν: (2/π)(θ + sinθ Σ), Σ = cosθ + (2/3)cos³θ + …, to cos^(ν−2)θ
        let mut sum = 0.0;
        if n > 1 {
            let mut term = c;
            sum = term;
            let mut k = 3;
            while k < n {
                term *= c * c * (k - 1) as f64 / k as f64;
                sum += term;
                k += 2;
            }
        }
        2.0 / std::f64::consts::PI * (theta + s * sum)
    } else {
        // even ν: sinθ Σ, Σ = 1 + (1/2)cos²θ + (1·3)/(2·4)cos⁴θ + …, to cos^(ν−2)θ
        let mut term = 1.0;
        let mut sum = 1.0;
        let mut k = 2;
        while k < n {
            term *= c * c * (k - 1) as f64 / k as f64;
            sum += term;
            k += 2;
        }
        s * sum
    };
    (1.0 - a).clamp(0.0, 1.0)
}

/// The |t| whose two-sided p-value with `nu` degrees of freedom is `p` (bisection).
pub fn t_for_two_sided(p: f64, nu: f64) -> f64 {
    if p >= 1.0 {
        return 0.0;
    }
    let (mut lo, mut hi) = (0.0f64, 1e6f64);
    for _ in 0..300 {
        let mid = 0.5 * (lo + hi);
        if t_two_sided_p(mid, nu) > p {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// Holm–Bonferroni at family-wise level `alpha` over two-sided p-values: which are rejected
/// (significant), and the per-test p threshold each was held against (α/(m − k) for the k-th
/// smallest, k from 0; tests after the first acceptance keep the threshold they would have had).
pub fn holm(p: &[f64], alpha: f64) -> (Vec<bool>, Vec<f64>) {
    let m = p.len();
    let mut order: Vec<usize> = (0..m).collect();
    order.sort_by(|&a, &b| p[a].total_cmp(&p[b]));
    let mut reject = vec![false; m];
    let mut threshold = vec![alpha; m];
    let mut still = true;
    for (k, &i) in order.iter().enumerate() {
        let t = alpha / (m - k) as f64;
        threshold[i] = t;
        if still && p[i] <= t {
            reject[i] = true;
        } else {
            still = false;
        }
    }
    (reject, threshold)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normal_tail_at_known_quantiles() {
        assert!((normal_sf(0.0) - 0.5).abs() < 1e-7);
        assert!((two_sided_p(1.959_964) - 0.05).abs() < 1e-6);
        assert!((normal_sf(3.0) - 1.349_898e-3).abs() < 1e-8);
        assert!((z_for_two_sided(0.05) - 1.959_964).abs() < 1e-5);
        // Bonferroni over 36 tests: |z| > 3.20
        assert!((z_for_two_sided(0.05 / 36.0) - 3.197).abs() < 2e-3);
    }

    #[test]
    fn student_t_at_known_quantiles() {
        // two-sided 5 % points: ν = 1, 2, 7, 30
        for (nu, q) in [
            (1.0, 12.706_2),
            (2.0, 4.302_7),
            (7.0, 2.364_6),
            (30.0, 2.042_3),
        ] {
            assert!((t_two_sided_p(q, nu) - 0.05).abs() < 2e-5, "ν = {nu}");
            assert!((t_for_two_sided(0.05, nu) - q).abs() < 1e-3, "ν = {nu}");
        }
        // ν = 7, two-sided 0.1 %: 5.408
        assert!((t_for_two_sided(0.001, 7.0) - 5.408).abs() < 2e-3);
        assert!((t_two_sided_p(1.959_964, f64::INFINITY) - 0.05).abs() < 1e-6);
    }

    #[test]
    fn holm_steps_down_and_stops_at_the_first_acceptance() {
        // α = 0.05, m = 4: thresholds 0.0125, 0.0167, 0.025, 0.05
        let (r, t) = holm(&[0.01, 0.04, 0.03, 0.005], 0.05);
        assert_eq!(r, vec![true, false, false, true]);
        assert!((t[3] - 0.0125).abs() < 1e-12 && (t[0] - 0.05 / 3.0).abs() < 1e-12);
        // 0.03 > 0.025: stops there, so 0.04 < 0.05 is not rejected either
        let (r, _) = holm(&[0.001, 0.02, 0.04], 0.05);
        assert_eq!(r, vec![true, true, true]);
    }
}
