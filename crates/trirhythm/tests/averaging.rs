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
