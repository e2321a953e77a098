//! Claims of the averaged theory, checked against values derived independently.
//!
//! Reference values come from `tests/reference/averaging_reference.py` (mpmath, 30 digits,
//! written from the paper's printed formulas in A, not from this library's x = A² form).

// Reference values are pasted verbatim from the script, digits beyond f64 included.
#![allow(clippy::excessive_precision)]

use proptest::prelude::*;
use trirhythm::model::Equivalents;
use trirhythm::model::{preset, Damping, Params};
use trirhythm::theory::averaging::{stable_count, Theory, Variant};

fn fig4c_r1() -> Params {
    preset("fig4c").unwrap().params.with("r", 1.0).unwrap()
}

fn close(a: f64, b: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * b.abs().max(1e-300)
}

#[test]
fn equivalents_match_the_reference() {
    let e = Equivalents::new(&fig4c_r1());
    let want = [
        0.010000049348224941868,
        0.68584125141204366481,
        1.0000024674082030418,
        1.0000049348224941868,
    ];
    for (got, want) in [e.mu1, e.beta1, e.omega1, e.beta2].into_iter().zip(want) {
        assert!(close(got, want, 1e-14), "{got} vs {want}");
    }
    let p = Params {
        mu0: 0.002,
        omega0: 0.9,
        lambda: 0.99,
        ..Params::default()
    };
    let e = Equivalents::new(&p);
    let want = [
        0.0019981404050039677893,
        -6.0757439046283384827,
        0.89958149382176985436,
        0.99907020250198389463,
    ];
    for (got, want) in [e.mu1, e.beta1, e.omega1, e.beta2].into_iter().zip(want) {
        assert!(close(got, want, 1e-13), "{got} vs {want}");
    }
}

#[test]
fn fig4c_at_r1_has_the_five_reference_cycles() {
    let th = Theory::new(&fig4c_r1(), Variant::Paper).unwrap();
    let cycles = th.limit_cycles();
    let want = [
        (1.9001579450034421443, true),
        (4.160557963615901368, false),
        (8.2139058439941037759, true),
        (10.550873696377930656, false),
        (12.932065923587930305, true),
    ];
    assert_eq!(cycles.len(), want.len(), "{cycles:?}");
    for (c, (a, s)) in cycles.iter().zip(want) {
        assert!(close(c.amplitude, a, 1e-12), "{} vs {a}", c.amplitude);
        assert_eq!(c.stable, s);
    }
    assert_eq!(th.rhythmicity().name(), "trirhythmic");
}

#[test]
fn another_parameter_set_matches_the_reference() {
    let p = fig4c_r1()
        .with("r", 0.999)
        .unwrap()
        .with("lambda", 0.999)
        .unwrap()
        .with("mu0", 0.05)
        .unwrap();
    let p = p.with("omega0", 0.9).unwrap();
    let th = Theory::new(&p, Variant::Paper).unwrap();
    let want = [
        2.5311372589068405691,
        3.6551435629279450658,
        8.3488307557487647329,
        10.488704536966553424,
        12.940855020691347578,
    ];
    let got: Vec<f64> = th.limit_cycles().iter().map(|c| c.amplitude).collect();
    assert_eq!(got.len(), 5);
    for (g, w) in got.iter().zip(want) {
        assert!(close(*g, w, 1e-12), "{g} vs {w}");
    }
}

#[test]
fn general_degree_drift_reduces_to_the_printed_eq18() {
    let p = fig4c_r1().with("r", 0.97).unwrap();
    let th = Theory::new(&p, Variant::Paper).unwrap();
    let e = th.equivalents();
    let [a0, b0, g0, d0] = p.damping.control_parameters();
    for i in 1..60 {
        let a = i as f64 * 0.25;
        let printed = (e.mu1 * a / 1024.0)
            * (512.0 * e.beta1 - 128.0 * a.powi(2) + 64.0 * a0 * a.powi(4) - 40.0 * b0 * a.powi(6)
                + 28.0 * g0 * a.powi(8)
                - 21.0 * d0 * a.powi(10))
            - (1.0 - 0.97) * e.omega1 * a / std::f64::consts::PI;
        let scale = (e.mu1 * a * 21.0 * d0 * a.powi(10) / 1024.0).max(1e-3);
        assert!((th.drift(a) - printed).abs() < 1e-12 * scale, "A = {a}");
    }
}

#[test]
fn consistent_variant_uses_log_loss_and_sgn_averaged_noise() {
    let p = fig4c_r1().with("r", 0.9).unwrap();
    let paper = Theory::new(&p, Variant::Paper).unwrap();
    let cons = Theory::new(&p, Variant::Consistent).unwrap();
    let w1 = paper.equivalents().omega1;
    for a in [0.5, 3.0, 9.0] {
        let want = (1.0 - 0.9 + 0.9f64.ln()) * w1 * a / std::f64::consts::PI;
        assert!((cons.drift(a) - paper.drift(a) - want).abs() < 1e-14);
    }
    // λ = 1 makes ω1 = ω0: ω1 = 0.9, τ = 0.5.
    let p = Params {
        lambda: 1.0,
        omega0: 0.9,
        noise_intensity: 0.3,
        correlation_time: 0.5,
        ..Params::default()
    };
    let th = Theory::new(&p, Variant::Consistent).unwrap();
    let e = th.equivalents();
    let factor = th.diffusion() * e.omega1 * e.omega1 / (e.beta2 * e.beta2 * 0.3);
    assert!(close(factor, 0.43462922026515490492, 1e-13), "{factor}");
    let paper = Theory::new(&p, Variant::Paper).unwrap();
    assert!(close(
        paper.diffusion() * e.omega1 * e.omega1 / (e.beta2 * 0.3),
        0.8,
        1e-14
    ));
    assert!(Theory::new(&p.with("r", 0.0).unwrap(), Variant::Consistent).is_err());
}

/// Composite Simpson on n (even) intervals: an integrator independent of the library's.
fn simpson(f: impl Fn(f64) -> f64, a: f64, b: f64, n: usize) -> f64 {
    let h = (b - a) / n as f64;
    let mut s = f(a) + f(b);
    for i in 1..n {
        s += f(a + h * i as f64) * if i % 2 == 1 { 4.0 } else { 2.0 };
    }
    s * h / 3.0
}

/// ∫P(A)dA by Simpson panels of 2000 intervals between the cuts 0, the support's end and
/// m ± 40w around each mode m, w = (−d² ln P/dA²)^{−1/2} from a centred difference of the
/// pointwise log-density: fine enough for peaks of any width, and independent of the library's
/// own quadrature (it uses only the mode positions, which other tests check).
fn reference_mass(pdf: &trirhythm::theory::averaging::AmplitudePdf) -> f64 {
    let end = pdf.support_end;
    let mut cuts = vec![0.0, end];
    for &m in &pdf.modes {
        let h = 1e-4 * m;
        let d2 =
            (pdf.log_density(m + h) - 2.0 * pdf.log_density(m) + pdf.log_density(m - h)) / (h * h);
        let w = if d2 < 0.0 { (-d2).sqrt().recip() } else { m };
        cuts.extend(
            [m - 40.0 * w, m - 4.0 * w, m, m + 4.0 * w, m + 40.0 * w]
                .into_iter()
                .filter(|&c| c > 0.0 && c < end),
        );
    }
    cuts.sort_by(|a, b| a.partial_cmp(b).unwrap());
    cuts.windows(2)
        .map(|c| simpson(|a| pdf.density(a), c[0], c[1], 2000))
        .sum()
}

/// A peak ~3e-5 wide (σ1 = 5e-5) that a uniform grid misses.
#[test]
fn pdf_with_a_very_narrow_peak_normalises() {
    let p = Params {
        mu0: 0.4143895873468803,
        omega0: 0.9153374714481488,
        lambda: 0.9,
        restitution: 0.8,
        damping: Damping::paper(0.144, 0.005, 6.759204876734208e-5, 1.704e-7),
        noise_intensity: 0.001,
        correlation_time: 4.63103031732889,
    };
    let pdf = Theory::new(&p, Variant::Paper)
        .unwrap()
        .amplitude_pdf()
        .unwrap();
    let mass = reference_mass(&pdf);
    assert!((mass - 1.0).abs() < 1e-7, "∫P = {mass}");
}

#[test]
fn amplitude_pdf_matches_the_reference() {
    let p = preset("fig13a").unwrap().params;
    assert_eq!(
        (
            p.mu0,
            p.lambda,
            p.restitution,
            p.noise_intensity,
            p.correlation_time,
            p.omega0
        ),
        (0.005, 0.998, 0.99, 0.1, 0.5, 1.0)
    );
    let th = Theory::new(&p, Variant::Paper).unwrap();
    let pdf = th.amplitude_pdf().unwrap();
    assert!(
        close(pdf.density(8.0), 0.03970865129622402521, 1e-10),
        "{}",
        pdf.density(8.0)
    );
    assert!(
        close(pdf.mean_amplitude, 10.455703834500905018, 1e-10),
        "{}",
        pdf.mean_amplitude
    );
    let extrema = [
        2.86937075677981,
        5.2568615372192,
        7.44474056419618,
        10.8260068587157,
        12.881079042368,
    ];
    let mut got: Vec<f64> = pdf.modes.iter().chain(&pdf.antimodes).copied().collect();
    got.sort_by(|a, b| a.partial_cmp(b).unwrap());
    assert_eq!(got.len(), 5, "{got:?}");
    for (g, w) in got.iter().zip(extrema) {
        assert!(close(*g, w, 1e-12), "{g} vs {w}");
    }
    assert_eq!(pdf.modes.len(), 3);
}

#[test]
fn pdfs_normalise_from_tiny_to_large_noise() {
    for d in [1e-4, 1e-3, 0.01, 0.1, 1.0, 10.0] {
        let p = preset("fig13a").unwrap().params.with("D", d).unwrap();
        for v in [Variant::Paper, Variant::Consistent] {
            let th = Theory::new(&p, v).unwrap();
            let pdf = th.amplitude_pdf().unwrap();
            let mass = reference_mass(&pdf);
            assert!((mass - 1.0).abs() < 1e-7, "D = {d} {v:?}: ∫P dA = {mass}");
            assert!(pdf.mean_amplitude.is_finite() && pdf.mean_amplitude > 0.0);
        }
    }
}

#[test]
fn energy_pdf_is_the_amplitude_pdf_transformed_by_eq29() {
    let th = Theory::new(&preset("fig14").unwrap().params, Variant::Paper).unwrap();
    let pdf = th.amplitude_pdf().unwrap();
    let w1 = th.equivalents().omega1;
    for i in 1..50 {
        let a = i as f64 * 0.3;
        let h = 0.5 * w1 * w1 * a * a;
        assert!(
            close(pdf.energy_density(h) * w1 * w1 * a, pdf.density(a), 1e-12),
            "A = {a}"
        );
    }
    let h_end = 0.5 * w1 * w1 * pdf.support_end.powi(2);
    let mass = simpson(|h| pdf.energy_density(h), 0.0, h_end, 40_000);
    assert!((mass - 1.0).abs() < 1e-6, "∫P dH = {mass}");
}

#[test]
fn joint_pdf_integrates_to_one_on_the_half_plane() {
    let th = Theory::new(&preset("fig14").unwrap().params, Variant::Paper).unwrap();
    let pdf = th.amplitude_pdf().unwrap();
    let w1 = th.equivalents().omega1;
    let a = pdf.support_end;
    let mass = simpson(
        |u| simpson(|v| pdf.joint_density(u, v), -w1 * a, w1 * a, 1200),
        0.0,
        a,
        600,
    );
    assert!((mass - 1.0).abs() < 1e-4, "∫∫P dU dV = {mass}");
    assert_eq!(pdf.joint_density(-0.1, 0.0), 0.0);
}

/// g(x) = f/A at the fold: κ equals a local maximum of the noise-free, loss-free part.
#[test]
fn no_root_is_missed_near_a_fold() {
    let base = fig4c_r1();
    let th1 = Theory::new(&base, Variant::Paper).unwrap();
    let e = th1.equivalents();
    // G(x) = g(x) + κ does not depend on r (κ = (1−r)ω1/π at fixed λ, ω0, μ0).
    let g = th1.drift_polynomial().clone();
    let crit = g.derivative().real_roots(0.0, f64::INFINITY);
    let x_star = crit
        .iter()
        .find(|c| c.slope < 0.0)
        .expect("a local maximum of G")
        .x;
    let r_fold = 1.0 - std::f64::consts::PI * g.eval(x_star) / e.omega1;
    assert!(r_fold < 1.0 && r_fold > 0.9, "{r_fold}");
    for delta in [1e-4, 1e-7, 1e-10] {
        let inside = Theory::new(&base.with("r", r_fold + delta).unwrap(), Variant::Paper).unwrap();
        let outside =
            Theory::new(&base.with("r", r_fold - delta).unwrap(), Variant::Paper).unwrap();
        let ci = inside.limit_cycles();
        let co = outside.limit_cycles();
        assert_eq!(ci.len(), co.len() + 2, "δ = {delta}: {ci:?} / {co:?}");
        assert_eq!(
            inside.drift_polynomial().sturm_count(0.0, f64::INFINITY),
            ci.len(),
            "δ = {delta}"
        );
        // The merging pair straddles √x* and closes like √δ (saddle-node scaling).
        let a_star = x_star.sqrt();
        let pair: Vec<f64> = ci
            .iter()
            .map(|c| c.amplitude)
            .filter(|a| (a - a_star).abs() < 1.0)
            .collect();
        assert_eq!(pair.len(), 2, "δ = {delta}: {pair:?}");
        assert!(pair[0] < a_star && a_star < pair[1]);
        let gap = pair[1] - pair[0];
        let g2 = g.derivative().derivative().eval(x_star);
        let kappa_rate = e.omega1 / std::f64::consts::PI; // dκ/dr
        let predicted = 2.0 * (2.0 * kappa_rate * delta / -g2).sqrt() / (2.0 * a_star); // in A
        assert!(
            close(gap, predicted, 0.05),
            "δ = {delta}: gap {gap} vs {predicted}"
        );
    }
}

#[test]
fn a_higher_degree_polynomial_can_be_quadrirhythmic() {
    // P(U) with roots of f/A placed at x = 1, 4, 9, 16, 25, 36, 49 (seven limit cycles).
    let roots = [1.0, 4.0, 9.0, 16.0, 25.0, 36.0, 49.0];
    let mut q = vec![-1.0];
    for r in roots {
        let mut n = vec![0.0; q.len() + 1];
        for (i, &a) in q.iter().enumerate() {
            n[i + 1] += a;
            n[i] -= r * a;
        }
        q = n;
    }
    // g(x) = μ1 Σ c_k w_k x^k: invert the weights (λ = 1 ⇒ β1 = c0, μ1 = μ0, r = 1).
    let mu0 = 0.01;
    let coefficients: Vec<f64> = q
        .iter()
        .enumerate()
        .map(|(k, &c)| c / (mu0 * trirhythm::theory::averaging::phase_average_weight(k)) * 1e-9)
        .collect();
    let p = Params {
        mu0,
        lambda: 1.0,
        damping: Damping { coefficients },
        ..Params::default()
    };
    let th = Theory::new(&p, Variant::Paper).unwrap();
    let cycles = th.limit_cycles();
    assert_eq!(cycles.len(), 7, "{cycles:?}");
    for (c, r) in cycles.iter().zip(roots) {
        assert!(close(c.amplitude, r.sqrt(), 1e-9));
    }
    assert_eq!(th.rhythmicity().count(), 4);
    assert_eq!(th.rhythmicity().name(), "4-rhythmic");
}

#[test]
fn barriers_follow_the_papers_order() {
    let th = Theory::new(&preset("fig8").unwrap().params, Variant::Paper).unwrap();
    let b = th.barriers();
    assert_eq!(b.len(), 4, "{b:?}");
    let ex = th.extrema();
    assert_eq!(ex.iter().filter(|e| e.minimum).count(), 3);
    // ΔU1 right of A01, ΔU2 left of A03, ΔU3 right of A03, ΔU4 left of A05.
    assert!(
        b[0].well < b[0].crest
            && b[1].crest < b[1].well
            && b[2].well < b[2].crest
            && b[3].crest < b[3].well
    );
    assert_eq!(b[1].well, b[2].well);
    for x in &b {
        let direct = th.potential(x.crest) - th.potential(x.well);
        assert!(x.height > 0.0 && close(x.height, direct, 1e-12));
    }
}

/// Roots spread over decades: a uniform coefficient threshold in the Sturm sequence once
/// miscounted this point (1 stable cycle and 0 modes instead of 2 and 2).
#[test]
fn sturm_count_survives_roots_spread_over_decades() {
    let p = Params {
        mu0: 0.38234,
        omega0: 0.5,
        lambda: 0.9,
        restitution: 0.8,
        damping: Damping::paper(0.144, 0.005, 1.105e-4, 1e-8),
        noise_intensity: 0.01,
        correlation_time: 0.0,
    };
    let th = Theory::new(&p, Variant::Paper).unwrap();
    let limit = th.limit_cycles();
    assert_eq!(limit.iter().filter(|c| c.stable).count(), 2, "{limit:?}");
    assert_eq!(stable_count(th.drift_polynomial()), 2);
    assert_eq!(
        th.drift_polynomial().sturm_count(0.0, f64::INFINITY),
        limit.len()
    );
    assert_eq!(th.amplitude_pdf().unwrap().modes.len(), 2);
    assert_eq!(th.stable_count_fast(), 2);
}

fn arb_params() -> impl Strategy<Value = Params> {
    (
        0.9f64..=1.0,
        0.001f64..0.5,
        0.8f64..=1.0,
        0.5f64..1.5,
        1e-3f64..2.0,
        0.0f64..5.0,
        0.8f64..1.2,
        0.8f64..1.2,
    )
        .prop_map(|(lambda, mu0, r, omega0, d, tau, sg, sd)| Params {
            mu0,
            omega0,
            lambda,
            restitution: r,
            damping: Damping::paper(0.144, 0.005, 5.862e-5 * sg, 2.13e-7 * sd),
            noise_intensity: d,
            correlation_time: tau,
        })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]

    #[test]
    fn roots_alternate_and_match_the_sturm_count(p in arb_params(), consistent in any::<bool>()) {
        let v = if consistent { Variant::Consistent } else { Variant::Paper };
        let th = Theory::new(&p, v).unwrap();
        for (poly, cycles) in [(th.drift_polynomial(), th.limit_cycles()), (th.fpk_polynomial(), th.cycles())] {
            prop_assert_eq!(poly.sturm_count(0.0, f64::INFINITY), cycles.len());
            prop_assert_eq!(stable_count(poly), cycles.iter().filter(|c| c.stable).count());
            for w in cycles.windows(2) {
                prop_assert!(w[0].amplitude < w[1].amplitude);
                prop_assert!(w[0].stable != w[1].stable || w[0].fold || w[1].fold);
            }
            if let Some(first) = cycles.first() {
                // The first root is stable exactly when the polynomial is positive at x = 0.
                prop_assert_eq!(first.stable, poly.coefficients[0] > 0.0);
            }
        }
        prop_assert_eq!(th.stable_count_fast(), th.rhythmicity().count());
    }

}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    #[test]
    fn pdfs_normalise_for_random_parameters(p in arb_params(), consistent in any::<bool>()) {
        let v = if consistent { Variant::Consistent } else { Variant::Paper };
        let th = Theory::new(&p, v).unwrap();
        let pdf = th.amplitude_pdf().unwrap();
        let mass = reference_mass(&pdf);
        prop_assert!((mass - 1.0).abs() < 1e-6, "∫P = {}", mass);
        prop_assert_eq!(pdf.modes.len(), th.cycles().iter().filter(|c| c.stable).count());
    }

    #[test]
    fn invalid_parameters_are_rejected_with_their_name(
        which in 0usize..7,
        bad in prop_oneof![Just(f64::NAN), Just(f64::INFINITY), -10.0f64..-1e-9, 1.0000001f64..10.0],
    ) {
        let (key, invalid) = match which {
            0 => ("mu0", bad <= 0.0 || !bad.is_finite()),
            1 => ("omega0", bad <= 0.0 || !bad.is_finite()),
            2 => ("lambda", !(bad > 0.0 && bad <= 1.0)),
            3 => ("r", !(0.0..=1.0).contains(&bad)),
            4 => ("D", bad < 0.0 || !bad.is_finite()),
            5 => ("tau", bad < 0.0 || !bad.is_finite()),
            _ => ("gamma0", !bad.is_finite()),
        };
        let res = Params::default().with(key, bad);
        prop_assert_eq!(res.is_err(), invalid, "{} = {}", key, bad);
        if let Err(e) = res {
            let msg = e.to_string();
            prop_assert!(msg.contains(key) || key == "gamma0", "{}", msg);
            prop_assert!(msg.contains("allowed"), "{}", msg);
        }
    }
}

// ---------------------------------------------------------------------------------------------
// The averaged theory of a model of the class (`Theory::from_model`, `Theory::by_quadrature`).

mod class {
    use super::{arb_params, close};
    use proptest::prelude::*;
    use proptest::test_runner::RngSeed;
    use trirhythm::model::{presets, Model, Params};
    use trirhythm::theory::averaging::{
        phase_average, phase_average_weight, Theory, Variant, DUFFING_LIMIT,
    };
    use trirhythm::Error;

    /// Relative difference |a − b|/max(|a|, |b|) (0 when both are 0).
    fn rel(a: f64, b: f64) -> f64 {
        if a == b {
            0.0
        } else {
            (a - b).abs() / a.abs().max(b.abs())
        }
    }

    /// The largest relative difference between the closed-form and the quadrature theory:
    /// g's coefficients, σ1, κ, every cycle of f and of m1 (and their stability must agree), and
    /// P(A) at 200 points over its support (relative where |ln P| ≤ 1, else of ln P).
    fn difference(closed: &Theory, quad: &Theory) -> [f64; 3] {
        let (a, b) = (closed.drift_polynomial(), quad.drift_polynomial());
        assert_eq!(a.coefficients.len(), b.coefficients.len());
        let mut worst: f64 = 0.0;
        for (x, y) in a.coefficients.iter().zip(&b.coefficients) {
            worst = worst.max(rel(*x, *y));
        }
        worst = worst
            .max(rel(closed.diffusion(), quad.diffusion()))
            .max(rel(closed.loss_rate(), quad.loss_rate()));
        let coefficients = worst;
        let mut worst: f64 = 0.0;
        for (c, q) in [
            (closed.limit_cycles(), quad.limit_cycles()),
            (closed.cycles(), quad.cycles()),
        ] {
            assert_eq!(c.len(), q.len(), "{c:?} vs {q:?}");
            for (x, y) in c.iter().zip(&q) {
                assert_eq!((x.stable, x.fold), (y.stable, y.fold));
                worst = worst.max(rel(x.amplitude, y.amplitude));
            }
        }
        let cycles = worst;
        let mut worst: f64 = 0.0;
        match (closed.amplitude_pdf(), quad.amplitude_pdf()) {
            (Ok(pc), Ok(pq)) => {
                // P to 1e-12 relative where |ln P| ≤ 1; in the far tails (P down to 1e-300,
                // where the error of ln P is that of its large terms G(A²)/σ1) ln P to 1e-12
                for i in 1..=200 {
                    let x = pc.support_end * i as f64 / 201.0;
                    let (lc, lq) = (pc.log_density(x), pq.log_density(x));
                    worst = worst.max((lc - lq).abs() / lc.abs().max(1.0));
                }
            }
            (Err(e), Err(f)) => assert_eq!(e.to_string(), f.to_string()),
            (c, q) => panic!("one PDF only: {:?} vs {:?}", c.err(), q.err()),
        }
        [coefficients, cycles, worst]
    }

    /// The random sets' seed.
    const SEED: u64 = 36;

    /// The tolerances: the coefficients, the cycles and P(A) (in `difference`'s measure) to
    /// 1e-12, the presets and the random sets alike. The two routes share σ1, κ, μ1 and β1 bit
    /// for bit and differ only in the phase weights w_k: the closed form's are exact dyadic
    /// rationals, the trapezoid's ([`phase_average`]) the exact averages rounded once, so g
    /// agrees bit for bit and so does P(A). With the trapezoid summed in doubles, w_1 and w_3
    /// were two ulps off, and ln P(A) = ln A + [G(A²) − G(A_p²)]/σ1 − ln(mass) amplified that by
    /// Σ_k |G_k|·|A^{2k} − A_p^{2k}|/σ1 (thousands at small σ1). Measured on 2026-11-27 (ln P's
    /// difference split at each set's worst point): before, the exponent [G(A²) − G(A_p²)]/σ1
    /// from the two routes' coefficients made the difference, P(A) up to 1.14e-12 over the
    /// presets (fig8, paper) and 5.7e-11 over 300 random sets; ln(mass) added at most 1.7e-12
    /// (its quadrature's own error, ≤ 2e-12 at peaks 1e5 times narrower than their amplitude,
    /// told the two densities apart), the exponent's evaluation from equal coefficients
    /// ≤ 1e-15. After, coefficients, cycles and P(A) 0 over the presets and over 3000 random
    /// sets (both variants): what error P(A) keeps of its own is the same in both routes.
    fn within(d: [f64; 3]) -> bool {
        d.iter().all(|&x| x <= 1e-12)
    }

    /// a/b rounded once, for a rational whose numerator and denominator have at most 106 bits:
    /// each split exactly into two doubles, the quotient carried in double-double (~1e-31).
    fn rounded_ratio(a: u128, b: u128) -> f64 {
        assert!(a < 1 << 106 && b < 1 << 106);
        let split = |v: u128| {
            let hi = v as f64;
            (hi, (v as i128 - hi as i128) as f64)
        };
        let ((ah, al), (bh, bl)) = (split(a), split(b));
        let q = ah / bh;
        // a − q·b to double precision: q·bh exactly as p + e, then the small terms
        let p = q * bh;
        let e = q.mul_add(bh, -p);
        let r = ((ah - p) - e) + al - q * bl;
        q + r / bh
    }

    #[test]
    fn quadrature_is_the_closed_form() {
        // the weights ⟨cos^{2k}φ sin²φ⟩ = C(2k, k)/(4^k(2k + 2)) are dyadic rationals, exact in
        // doubles for these k: the periodic trapezoid gives the closed form's bits
        for k in 0..=20 {
            assert_eq!(phase_average(k, 1), phase_average_weight(k), "k = {k}");
        }
        // every mixed average is (2i − 1)!!(2j − 1)!!/(2(i + j))!! rounded once, i + j ≤ 22
        // (the Rayleigh terms' ⟨sin^{2k+2}φ⟩ included): the integers exact in u128
        for i in 0..=22usize {
            for j in 0..=22 - i {
                let odd = |n: usize| (0..n).map(|k| (2 * k + 1) as u128).product::<u128>();
                let even: u128 = (1..=(i + j)).map(|k| (2 * k) as u128).product();
                let exact = rounded_ratio(odd(i) * odd(j), even);
                let got = phase_average(i, j);
                assert_eq!(
                    got.to_bits(),
                    exact.to_bits(),
                    "⟨cos^{}sin^{}⟩ = {got:e} vs {exact:e}",
                    2 * i,
                    2 * j
                );
            }
        }
        let mut worst = [0.0f64; 3];
        for p in presets() {
            let model = Model::from(&p.params);
            for variant in [Variant::Consistent, Variant::Paper] {
                let closed = Theory::new(&p.params, variant).unwrap();
                // the paper family's theory from the model is the closed form, bit for bit
                let same = Theory::from_model(&model, variant).unwrap();
                assert_eq!(same.drift_polynomial(), closed.drift_polynomial());
                assert_eq!(same.fpk_polynomial(), closed.fpk_polynomial());
                assert!(same.model().is_none() && !same.assumptions().is_empty());
                let quad = Theory::by_quadrature(&model, variant).unwrap();
                let d = difference(&closed, &quad);
                assert!(within(d), "{} {}: {d:?}", p.name, variant.name());
                for (w, x) in worst.iter_mut().zip(d) {
                    *w = w.max(x);
                }
            }
        }
        eprintln!("presets: theories {worst:?} (max relative)");
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 64, rng_seed: RngSeed::Fixed(SEED), ..ProptestConfig::default() })]

        #[test]
        fn quadrature_is_the_closed_form_for_random_parameters(p in arb_params(), c0 in 0.5f64..1.5) {
            let mut p: Params = p;
            p.damping.coefficients[0] = c0;
            let model = Model::from(&p);
            for variant in [Variant::Consistent, Variant::Paper] {
                let closed = Theory::new(&p, variant).unwrap();
                let quad = Theory::by_quadrature(&model, variant).unwrap();
                let d = difference(&closed, &quad);
                prop_assert!(within(d), "{}: {:?}", variant.name(), d);
            }
        }
    }

    /// A model from the base file with `extra` TOML appended (tables not in the base).
    fn model(base: &str, extra: &str) -> Model {
        Model::from_toml_str(&format!("format = 1\n{base}\n{extra}")).unwrap()
    }

    const LINEAR: &str = "[leading]\nlambda = 1.0\n[restoring]\nomega0 = OMEGA\n";

    #[test]
    fn multiplicative_noise_gives_the_exact_moment_boundary() {
        // Ü + 2ζωU̇ + ω²U = Uη_m: the second moments' matrix
        // M = [[0, 2, 0], [−ω², −2ζω, 1], [2D, −2ω², −4ζω]] is singular at D_c = 2ζω³ (white);
        // the averaged E[A²] grows at 2(f + m_c)/A + b/A², zero at the theory's D_c
        for (zeta, omega, tau) in [(0.05, 1.0, 0.0), (0.01, 0.7, 0.0), (0.02, 1.3, 0.4)] {
            let rate = |d: f64| {
                let text = LINEAR.replace("OMEGA", &format!("{omega:?}"));
                let m = model(
                    &text,
                    &format!(
                        "[damping]\nmu0 = {:?}\ncoefficients = [-1.0]\n\
                         [noise.multiplicative]\nintensity = {d:?}\ncorrelation_time = {tau:?}\n",
                        2.0 * zeta * omega
                    ),
                );
                let th = Theory::from_model(&m, Variant::Consistent).unwrap();
                assert!(close(th.drift(1.0), -zeta * omega, 1e-14));
                2.0 * (th.drift(1.0) + th.drift_correction(1.0)) + th.diffusion_at(1.0)
            };
            // the rate is affine in D
            let (r0, r1) = (rate(0.0), rate(1.0));
            let averaged = -r0 / (r1 - r0);
            let exact = 2.0 * zeta * omega.powi(3) * (1.0 + 4.0 * tau * tau * omega * omega);
            if tau == 0.0 {
                let det = |d: f64| {
                    let (w2, z) = (omega * omega, zeta * omega);
                    // det [[0, 2, 0], [−ω², −2ζω, 1], [2D, −2ω², −4ζω]]
                    -2.0 * (-w2 * -4.0 * z - 2.0 * d)
                };
                assert!(det(exact).abs() < 1e-15, "{}", det(exact));
            }
            assert!(close(averaged, exact, 1e-12), "{averaged} vs {exact}");
            assert!(rate(0.9 * exact) < 0.0 && rate(1.1 * exact) > 0.0);
        }
    }

    #[test]
    fn rayleigh_van_der_pol_cycle_is_its_closed_form() {
        // Ü − μ(1 − U̇²)U̇ + ω²U = 0: f = μA(1/2 − 3ω²A²/8), the cycle A = 2/(√3 ω); with
        // λ < 1 the balance c = ω^λcos(πλ/2) and β2, ω1 of Eq. 5: A² = 4(μ − c)/(3μω1²)
        for (mu, omega, lambda) in [(0.1f64, 1.0f64, 1.0f64), (0.3, 0.8, 1.0), (0.2, 1.1, 0.97)] {
            let m = model(
                &format!("[leading]\nlambda = {lambda:?}\n[restoring]\nomega0 = {omega:?}\n"),
                &format!(
                    "[damping]\nmu0 = {mu:?}\ncoefficients = [1.0]\nrayleigh = [{:?}]\n",
                    -mu
                ),
            );
            let th = Theory::from_model(&m, Variant::Consistent).unwrap();
            let l = lambda;
            let s = (std::f64::consts::PI * l / 2.0).sin();
            let c = omega.powf(l) * (std::f64::consts::PI * l / 2.0).cos();
            let w1 = (omega.powf(3.0 - l) / s).sqrt();
            let a = (4.0 * (mu - c) / (3.0 * mu * w1 * w1)).sqrt();
            let cycles = th.limit_cycles();
            assert_eq!(cycles.len(), 1, "{cycles:?}");
            assert!(cycles[0].stable);
            assert!(
                close(cycles[0].amplitude, a, 1e-13),
                "{} vs {a}",
                cycles[0].amplitude
            );
            if lambda == 1.0 {
                assert!(close(a, 2.0 / (3f64.sqrt() * omega), 1e-15));
            }
            assert!(th.assumptions().iter().any(|x| x.name.contains("max|h")));
        }
    }

    #[test]
    fn duffing_leaves_the_drift_and_shifts_the_frequency() {
        let vdp = "[leading]\nlambda = 1.0\n[damping]\nmu0 = 0.1\ncoefficients = [1.0, -1.0]\n";
        let plain = Theory::from_model(
            &model(vdp, "[restoring]\nomega0 = 1.0\n"),
            Variant::Consistent,
        )
        .unwrap();
        let k3 = 0.02;
        let duffing = Theory::from_model(
            &model(vdp, &format!("[restoring]\nomega0 = 1.0\ncubic = {k3:?}\n")),
            Variant::Consistent,
        )
        .unwrap();
        // k_nl drops out of f: the same polynomial, bit for bit; the cycle A = 2
        assert_eq!(plain.drift_polynomial(), duffing.drift_polynomial());
        let a = duffing.limit_cycles()[0].amplitude;
        assert!(close(a, 2.0, 1e-14));
        // θ̇ = 3k3A²/(8ω): the Duffing frequency ω + 3k3A²/(8ω)
        assert!(close(
            duffing.frequency_shift(a),
            3.0 * k3 * a * a / 8.0,
            1e-14
        ));
        assert_eq!(plain.frequency_shift(a), 0.0);
        let dw = duffing
            .assumptions()
            .iter()
            .find(|x| x.name.contains("Δω"))
            .unwrap();
        assert!(close(dw.value, 3.0 * k3 * a * a / 8.0, 1e-14) && dw.holds);
        let shift = duffing
            .assumptions()
            .iter()
            .find(|x| x.name.contains("k3"))
            .unwrap();
        assert!(close(shift.value, k3 * 4.0, 1e-14) && shift.holds);
        // a strong shift at the cycle (k3·A² = 0.4 > 0.2) is refused, naming the term
        let strong = Theory::from_model(
            &model(vdp, "[restoring]\nomega0 = 1.0\ncubic = 0.1\n"),
            Variant::Consistent,
        );
        let e = strong.unwrap_err().to_string();
        assert!(
            e.contains("restoring.cubic = 0.1") && e.contains(&DUFFING_LIMIT.to_string()),
            "{e}"
        );
    }

    #[test]
    fn fractional_damping_enters_as_its_harmonic_balance() {
        // Ü + K D^α U − μ(1 − U²)U̇ + ω0²U = η_a (OU, no wall): K D^α U ≈ s U + c U̇ with
        // s = Kω0^α cos(πα/2), c = Kω0^{α−1} sin(πα/2); f = A[(μ − c)/2 − μA²/8], the cycle
        // A² = 4(μ − c)/μ; σ1 = D/(ω1²(1 + τ²ω1²)), ω1² = ω0² + s
        let (k, alpha, mu, w0, d, tau) = (0.05f64, 0.5f64, 0.2f64, 0.9f64, 0.01f64, 0.3f64);
        let m = model(
            &format!("[leading]\nlambda = 1.0\n[restoring]\nomega0 = {w0:?}\n"),
            &format!(
                "[damping]\nmu0 = {mu:?}\ncoefficients = [1.0, -1.0]\n\
                 [[fractional]]\ncoefficient = {k:?}\norder = {alpha:?}\n\
                 [noise.additive]\nintensity = {d:?}\ncorrelation_time = {tau:?}\n"
            ),
        );
        let th = Theory::from_model(&m, Variant::Consistent).unwrap();
        let h = std::f64::consts::FRAC_PI_2 * alpha;
        let (s, c) = (
            k * w0.powf(alpha) * h.cos(),
            k * w0.powf(alpha - 1.0) * h.sin(),
        );
        let w1 = (w0 * w0 + s).sqrt();
        assert!(close(th.equivalents().omega1, w1, 1e-14));
        assert!(close(
            th.limit_cycles()[0].amplitude,
            (4.0 * (mu - c) / mu).sqrt(),
            1e-13
        ));
        let sigma1 = d / (w1 * w1 * (1.0 + tau * tau * w1 * w1));
        assert!(close(th.diffusion(), sigma1, 1e-14));
        // the stationary P(A) exists and is normalised
        let pdf = th.amplitude_pdf().unwrap();
        assert!((pdf.probability(0.0, pdf.support_end) - 1.0).abs() < 1e-9);
        assert!(th.describe().contains("fractional"));
    }

    #[test]
    fn multiplicative_pdf_solves_the_fpk() {
        use trirhythm::theory::quadrature::adaptive_gauss_kronrod;
        // van der Pol (μ = 0.1, ω = 1) with additive and multiplicative noise, no wall:
        // σ1 = 0.01, b_1 = 0.00125 (white) so r0 = σ1/b_1 = 8: the series (x ≤ 4) and the
        // partial fractions (beyond) both cover the support
        for (additive, tau) in [(0.01, 0.0), (0.01, 0.3), (0.0, 0.0)] {
            let noise = if additive > 0.0 {
                format!("[noise.additive]\nintensity = {additive:?}\n")
            } else {
                String::new()
            };
            let m = model(
                "[leading]\nlambda = 1.0\n[restoring]\nomega0 = 1.0\n",
                &format!(
                    "[damping]\nmu0 = 0.1\ncoefficients = [1.0, -1.0]\n{noise}\
                     [noise.multiplicative]\nintensity = 0.005\ncorrelation_time = {tau:?}\n"
                ),
            );
            let th = Theory::from_model(&m, Variant::Consistent).unwrap();
            let pdf = th.amplitude_pdf().unwrap();
            // d ln P/dA = (2(f + m_c) − b′)/b, integrated independently by Gauss–Kronrod
            let slope = |a: f64| {
                let b1 = th.multiplicative_diffusion();
                (2.0 * (th.drift(a) + th.drift_correction(a)) - 2.0 * b1 * a) / th.diffusion_at(a)
            };
            let points = [0.3, 0.8, 1.5, 2.0, 2.5, 2.9, 3.3];
            for w in points.windows(2) {
                let want = adaptive_gauss_kronrod(&slope, w[0], w[1], 1e-14);
                let got = pdf.log_density(w[1]) - pdf.log_density(w[0]);
                assert!(
                    (got - want).abs() < 1e-10 * want.abs().max(1.0),
                    "{w:?}: {got} vs {want}"
                );
            }
            // normalised; the mode where 2(f + m_c) = b′, a stable root of the polynomial
            assert!((pdf.probability(0.0, pdf.support_end) - 1.0).abs() < 1e-9);
            assert_eq!(pdf.modes.len(), 1);
            assert!(slope(pdf.modes[0]).abs() < 1e-12, "{}", slope(pdf.modes[0]));
        }
        // a vanishing multiplicative noise gives the additive density back
        let additive = |extra: &str| {
            let m = model(
                "[leading]\nlambda = 1.0\n[restoring]\nomega0 = 1.0\n",
                &format!(
                    "[damping]\nmu0 = 0.1\ncoefficients = [1.0, -1.0]\n\
                     [noise.additive]\nintensity = 0.01\n{extra}"
                ),
            );
            Theory::from_model(&m, Variant::Consistent)
                .unwrap()
                .amplitude_pdf()
                .unwrap()
        };
        let (plain, tiny) = (
            additive(""),
            additive("[noise.multiplicative]\nintensity = 1e-9\n"),
        );
        for a in [0.5, 1.0, 2.0, 2.5] {
            assert!(close(tiny.density(a), plain.density(a), 1e-6), "A = {a}");
        }
    }

    /// A random model of the class the theory covers: van der Pol damping with a Rayleigh term,
    /// up to one fractional term, a weak Duffing term, the wall at 0 or none, additive and
    /// multiplicative noise (white or OU).
    fn arb_class() -> impl Strategy<Value = Model> {
        use trirhythm::model::terms::*;
        (
            (0.9f64..=1.0, 0.01f64..0.5, -0.2f64..=0.0, 0.5f64..1.5),
            (
                0.0f64..0.1,
                0.1f64..=1.0,
                0.0f64..0.01,
                prop::option::of(0.8f64..=1.0),
            ),
            (1e-3f64..0.1, 0.0f64..2.0, 0.0f64..0.01, 0.0f64..2.0),
        )
            .prop_map(
                |((lambda, mu0, d1, omega0), (k, alpha, k3, wall), (d, tau, dm, taum))| Model {
                    leading: Leading { lambda },
                    damping: Dissipation {
                        mu0,
                        coefficients: vec![1.0, -1.0],
                        rayleigh: vec![d1],
                    },
                    restoring: Restoring {
                        omega0,
                        cubic: k3,
                        quintic: 0.0,
                    },
                    fractional: vec![Fractional {
                        coefficient: k,
                        order: alpha,
                    }],
                    walls: wall
                        .map(|r| Wall {
                            position: 0.0,
                            keep: Keep::Above,
                            restitution: Restitution::Constant(r),
                        })
                        .into_iter()
                        .collect(),
                    forcing: None,
                    noise: Noises {
                        additive: Some(NoiseTerm {
                            intensity: d,
                            correlation_time: tau,
                        }),
                        multiplicative: Some(NoiseTerm {
                            intensity: dm,
                            correlation_time: taum,
                        }),
                        correlation: 0.0,
                    },
                    start: Start::default(),
                },
            )
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 64, rng_seed: RngSeed::Fixed(SEED), ..ProptestConfig::default() })]

        #[test]
        fn class_theories_are_consistent(m in arb_class()) {
            let th = match Theory::from_model(&m, Variant::Consistent) {
                Ok(th) => th,
                // a strong Duffing shift at a large cycle is the one refusal possible here
                Err(e) => {
                    prop_assert!(e.to_string().contains("restoring.cubic"), "{}", e);
                    return Ok(());
                }
            };
            let extrema = th.cycles();
            for w in extrema.windows(2) {
                prop_assert!(w[0].amplitude < w[1].amplitude);
                prop_assert!(w[0].stable != w[1].stable || w[0].fold || w[1].fold);
            }
            // each extremum of P(A) is where 2(f + m_c) = b′
            let b1 = th.multiplicative_diffusion();
            for c in &extrema {
                let a = c.amplitude;
                let terms = 2.0 * (th.drift(a).abs() + th.drift_correction(a).abs()) + 2.0 * b1 * a;
                let balance = 2.0 * (th.drift(a) + th.drift_correction(a)) - 2.0 * b1 * a;
                prop_assert!(balance.abs() <= 1e-9 * terms, "A = {}: {} of {}", a, balance, terms);
            }
            if let Ok(pdf) = th.amplitude_pdf() {
                let mass = pdf.probability(0.0, pdf.support_end);
                prop_assert!((mass - 1.0).abs() < 1e-8, "∫P = {}", mass);
                prop_assert_eq!(pdf.modes.len(), extrema.iter().filter(|c| c.stable).count());
            }
        }
    }

    #[test]
    fn the_self_consistent_balance_is_a_fixed_point() {
        use trirhythm::theory::averaging::{linearise_with, Balance};
        let m = model(
            "[leading]\nlambda = 0.9\n[restoring]\nomega0 = 0.8\n",
            "[damping]\nmu0 = 0.2\ncoefficients = [1.0, -1.0]\n\
             [[fractional]]\ncoefficient = 0.1\norder = 0.4\n\
             [noise.additive]\nintensity = 0.01\n",
        );
        let lin = linearise_with(&m, Balance::SelfConsistent).unwrap();
        assert!(close(lin.equivalents.omega1, lin.omega_b, 1e-14));
        let natural = Theory::from_model(&m, Variant::Consistent).unwrap();
        let th = Theory::from_model_with(&m, Variant::Consistent, Balance::SelfConsistent).unwrap();
        let gap = |t: &Theory| {
            t.assumptions()
                .iter()
                .find(|a| a.name == "|ω_b − ω1|/ω1")
                .unwrap()
                .value
        };
        assert!(
            gap(&th) < 1e-14 && gap(&natural) > 1e-3,
            "{} {}",
            gap(&th),
            gap(&natural)
        );
        assert!(close(th.equivalents().omega1, lin.omega_b, 1e-15));
        // λ = 1 with no fractional term: ω1 = ω0 already, the same theory
        let plain = model(
            "[leading]\nlambda = 1.0\n[restoring]\nomega0 = 0.8\n",
            "[damping]\nmu0 = 0.2\ncoefficients = [1.0, -1.0]\n",
        );
        let (a, b) = (
            Theory::from_model(&plain, Variant::Consistent).unwrap(),
            Theory::from_model_with(&plain, Variant::Consistent, Balance::SelfConsistent).unwrap(),
        );
        assert!(close(
            a.limit_cycles()[0].amplitude,
            b.limit_cycles()[0].amplitude,
            1e-15
        ));
        // the paper variant balances at ω0
        let e = Theory::from_model_with(&m, Variant::Paper, Balance::SelfConsistent);
        assert!(e.is_err());
    }

    #[test]
    fn the_theory_refuses_what_it_does_not_cover() {
        let paper = Model::from(&trirhythm::model::preset("fig13a").unwrap().params);
        let text = paper.to_toml();
        let cases: [(&str, String, Variant); 7] = [
            (
                "wall.0.position = 0.5",
                text.replace("position = 0.0", "position = 0.5").replace("u0 = 1.0", "u0 = 1.5"),
                Variant::Consistent,
            ),
            (
                "wall.1.position = 3",
                format!("{text}\n[[wall]]\nposition = 3.0\nkeep = \"below\"\nrestitution = 0.9\n"),
                Variant::Consistent,
            ),
            (
                "forcing.amplitude = 0.2",
                format!("{text}\n[forcing]\namplitude = 0.2\nfrequency = 1.0\n"),
                Variant::Consistent,
            ),
            (
                "noise.correlation = 0.5",
                text.replace("correlation = 0.0", "correlation = 0.5\n[noise.multiplicative]\nintensity = 0.01\ncorrelation_time = 0.5"),
                Variant::Consistent,
            ),
            (
                "damping.rayleigh.0 = -0.1",
                text.replace("rayleigh = []", "rayleigh = [-0.1]"),
                Variant::Paper,
            ),
            (
                "wall: none",
                text.replace("[[wall]]\nposition = 0.0\nkeep = \"above\"\nrestitution = 0.99\n", ""),
                Variant::Paper,
            ),
            (
                "wall.0.restitution is speed-dependent",
                text.replace("restitution = 0.99", "restitution = { r0 = 0.99, r_fast = 0.9, speed = 1.0 }"),
                Variant::Consistent,
            ),
        ];
        for (named, file, variant) in cases {
            let m = Model::from_toml_str(&file).unwrap_or_else(|e| panic!("{named}: {e}\n{file}"));
            match Theory::from_model(&m, variant) {
                Err(e @ Error::NotApplicable { .. }) => {
                    let msg = e.to_string();
                    assert!(msg.contains(named), "{named}: {msg}");
                    assert!(msg.contains("the averaged theory"), "{msg}");
                }
                other => panic!("{named}: not refused: {:?}", other.map(|t| t.describe())),
            }
        }
        // the wall at 0 keeping U ≤ 0 is the mirror image (h even, k odd): the same theory
        let below = Model::from_toml_str(
            &text
                .replace("keep = \"above\"", "keep = \"below\"")
                .replace("u0 = 1.0", "u0 = -1.0"),
        )
        .unwrap();
        let (above, below) = (
            Theory::by_quadrature(&paper, Variant::Consistent).unwrap(),
            Theory::from_model(&below, Variant::Consistent).unwrap(),
        );
        assert_eq!(above.drift_polynomial(), below.drift_polynomial());
        assert_eq!(above.fpk_polynomial(), below.fpk_polynomial());
        // correlated noises without a wall: the cross terms vanish at first order, accepted
        let free = text
            .replace("[[wall]]\nposition = 0.0\nkeep = \"above\"\nrestitution = 0.99\n", "")
            .replace("correlation = 0.0", "correlation = 0.5\n[noise.multiplicative]\nintensity = 0.01\ncorrelation_time = 0.5");
        let th =
            Theory::from_model(&Model::from_toml_str(&free).unwrap(), Variant::Consistent).unwrap();
        assert!(th.multiplicative_diffusion() > 0.0);
        let _ = DUFFING_LIMIT;
    }

    /// The routines built on the paper's closed forms (critical noise, oscillation
    /// boundaries, phase response) take the paper's family and refuse any other model, naming
    /// the term: a Rayleigh model the quadrature covers is refused by them.
    #[test]
    fn the_closed_forms_take_the_papers_family_only() {
        use trirhythm::theory::averaging::closed_forms;
        let paper = Model::from(&trirhythm::model::preset("fig13a").unwrap().params);
        let family = closed_forms(&paper).unwrap();
        assert_eq!(
            family.params,
            trirhythm::model::preset("fig13a").unwrap().params
        );
        let mut rayleigh = paper.clone();
        rayleigh.damping.rayleigh = vec![-0.1];
        assert!(Theory::from_model(&rayleigh, Variant::Consistent).is_ok());
        let mut duffing = paper;
        duffing.restoring.cubic = 1.0;
        for (named, m) in [
            ("damping.rayleigh.0 = -0.1", rayleigh),
            ("restoring.cubic = 1", duffing),
        ] {
            match closed_forms(&m) {
                Err(e @ Error::NotApplicable { .. }) => {
                    let msg = e.to_string();
                    assert!(
                        msg.contains(named) && msg.contains("the averaged theory does not apply"),
                        "{msg}"
                    );
                }
                other => panic!("{named}: not refused: {:?}", other.map(|f| f.params)),
            }
        }
    }
}
