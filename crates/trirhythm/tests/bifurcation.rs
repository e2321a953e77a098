//! Claims of the `bifurcation` module: maps agree with the averaged theory point by point,
//! every count change of a map lies on a traced fold curve, curve points solve their equations,
//! analytic folds and cusps are reproduced, branches agree with the roots of f.

use trirhythm::model::preset;
use trirhythm::theory::averaging::{Theory, Variant};
use trirhythm::theory::bifurcation::*;
use trirhythm::{Error, Params};

const N: usize = 121;

fn map(base: Params, x: (&str, f64, f64), y: (&str, f64, f64), what: What, v: Variant) -> Map {
    map_n(base, x, y, what, v, N)
}

fn map_n(
    base: Params,
    x: (&str, f64, f64),
    y: (&str, f64, f64),
    what: What,
    v: Variant,
    n: usize,
) -> Map {
    let plane = Plane::new(
        &base,
        Axis::new(x.0, x.1, x.2, n).unwrap(),
        Axis::new(y.0, y.1, y.2, n).unwrap(),
        v,
    )
    .unwrap();
    classify(&plane, what, &|_, _| {})
}

/// The maps the figures use, at test resolution.
fn cases() -> Vec<(&'static str, Map)> {
    let p = |n: &str| preset(n).unwrap().params;
    vec![
        (
            "fig2ii",
            map(
                p("fig2ii"),
                ("gamma0", 2e-5, 1e-4),
                ("delta0", 2e-8, 4e-7),
                What::Rhythmicity,
                Variant::Paper,
            ),
        ),
        (
            "fig2i",
            map(
                p("fig2i"),
                ("alpha0", 0.0, 0.3),
                ("beta0", 5e-4, 0.02),
                What::Rhythmicity,
                Variant::Paper,
            ),
        ),
        (
            "fig6 λ=0.99",
            map(
                p("fig6").with("lambda", 0.99).unwrap(),
                ("gamma0", 2e-5, 1e-4),
                ("delta0", 2e-8, 4e-7),
                What::Rhythmicity,
                Variant::Paper,
            ),
        ),
        (
            "fig10 D=0.7",
            map(
                p("fig10").with("D", 0.7).unwrap(),
                ("lambda", 0.95, 1.0),
                ("tau", 0.0, 5.0),
                What::Modes,
                Variant::Paper,
            ),
        ),
        (
            "fig12a",
            map(
                p("fig12a"),
                ("mu0", 0.001, 0.1),
                ("r", 0.8, 1.0),
                What::Modes,
                Variant::Paper,
            ),
        ),
        (
            "fig12c consistent",
            map(
                p("fig12c"),
                ("lambda", 0.95, 1.0),
                ("r", 0.8, 1.0),
                What::Modes,
                Variant::Consistent,
            ),
        ),
    ]
}

fn dist_to_segment(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let d = [b[0] - a[0], b[1] - a[1]];
    let l2 = d[0] * d[0] + d[1] * d[1];
    let t = if l2 > 0.0 {
        (((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1]) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    ((p[0] - a[0] - t * d[0]).powi(2) + (p[1] - a[1] - t * d[1]).powi(2)).sqrt()
}

/// Largest distance (in cells) from a count change of the map to the traced curves, and the
/// largest scaled residual on the curves.
fn consistency(m: &Map) -> (f64, f64) {
    let folds = trace_folds(m);
    let pl = &m.plane;
    let sys = if m.what == What::Rhythmicity {
        FoldSystem::Drift
    } else {
        FoldSystem::Fpk
    };
    let polylines: Vec<Vec<[f64; 2]>> = folds
        .curves
        .iter()
        .map(|c| {
            c.points
                .iter()
                .map(|p| [pl.x.fraction(p.x), pl.y.fraction(p.y)])
                .collect()
        })
        .collect();
    let (cx, cy) = (1.0 / (pl.x.count - 1) as f64, 1.0 / (pl.y.count - 1) as f64);
    let cell = cx.max(cy);
    let trans = m.transitions();
    assert!(!trans.is_empty(), "the map has no transitions");
    let mut worst: f64 = 0.0;
    for ((ix, iy), (jx, jy)) in &trans {
        let mid = [0.5 * (ix + jx) as f64 * cx, 0.5 * (iy + jy) as f64 * cy];
        let d = polylines
            .iter()
            .flat_map(|l| l.windows(2).map(|w| dist_to_segment(mid, w[0], w[1])))
            .fold(f64::INFINITY, f64::min);
        worst = worst.max(d);
    }
    let res = folds
        .curves
        .iter()
        .flat_map(|c| c.points.iter())
        .map(|p| {
            let r = fold_residuals(pl, sys, p);
            r[0].abs().max(r[1].abs())
        })
        .fold(0.0, f64::max);
    assert!(
        folds.unlocated * 100 <= folds.seeds,
        "{} of {} seeds not located",
        folds.unlocated,
        folds.seeds
    );
    if folds.unlocated > 0 {
        eprintln!("{} of {} seeds not located", folds.unlocated, folds.seeds);
    }
    (worst / cell, res)
}

#[test]
fn every_count_change_lies_within_one_cell_of_a_traced_curve() {
    for (name, m) in cases() {
        let (cells, _) = consistency(&m);
        assert!(
            cells <= 1.0,
            "{name}: a transition lies {cells:.2} cells from every curve"
        );
    }
}

/// The figures' planes at their full resolution (401 × 401), both variants.
#[test]
#[ignore = "extended: full-resolution maps of every figure plane (about a minute)"]
fn figure_planes_at_full_resolution_are_consistent() {
    let p = |n: &str| preset(n).unwrap().params;
    let n = 401;
    let mut planes = vec![
        (
            p("fig2i"),
            ("alpha0", 0.04, 0.24),
            ("beta0", 0.0005, 0.0105),
            What::Rhythmicity,
        ),
        (
            p("fig2ii"),
            ("gamma0", 0.0, 1.2e-4),
            ("delta0", 1e-8, 6e-7),
            What::Rhythmicity,
        ),
    ];
    for r in [0.998, 0.99] {
        planes.push((
            p("fig3").with("r", r).unwrap(),
            ("gamma0", 0.0, 1.2e-4),
            ("delta0", 1e-8, 6e-7),
            What::Rhythmicity,
        ));
    }
    for l in [0.999, 0.997] {
        planes.push((
            p("fig6").with("lambda", l).unwrap(),
            ("gamma0", 0.0, 1.2e-4),
            ("delta0", 1e-8, 6e-7),
            What::Rhythmicity,
        ));
    }
    for d in [0.05, 0.3, 0.7, 1.2] {
        planes.push((
            p("fig10").with("D", d).unwrap(),
            ("lambda", 0.9, 1.0),
            ("tau", 0.0, 5.0),
            What::Modes,
        ));
    }
    for l in ["a", "b"] {
        planes.push((
            p(&format!("fig12{l}")),
            ("mu0", 0.001, 0.1),
            ("r", 0.8, 1.0),
            What::Modes,
        ));
    }
    for l in ["c", "d"] {
        planes.push((
            p(&format!("fig12{l}")),
            ("lambda", 0.95, 1.0),
            ("r", 0.8, 1.0),
            What::Modes,
        ));
    }
    for v in [Variant::Paper, Variant::Consistent] {
        for (i, (base, x, y, what)) in planes.iter().enumerate() {
            let m = map_n(base.clone(), *x, *y, *what, v, n);
            let (cells, res) = consistency(&m);
            assert!(
                cells <= 1.0,
                "plane {i} ({v:?}): a transition lies {cells:.2} cells from every curve"
            );
            assert!(res < 1e-10, "plane {i} ({v:?}): residual {res}");
        }
    }
}

#[test]
fn curve_points_satisfy_both_equations() {
    for (name, m) in cases() {
        let folds = trace_folds(&m);
        let sys = if m.what == What::Rhythmicity {
            FoldSystem::Drift
        } else {
            FoldSystem::Fpk
        };
        let mut n = 0;
        for c in &folds.curves {
            for p in &c.points {
                let r = fold_residuals(&m.plane, sys, p);
                assert!(
                    r[0].abs() < 1e-10 && r[1].abs() < 1e-10,
                    "{name}: {p:?} residuals {r:?}"
                );
                n += 1;
            }
        }
        assert!(n > 100, "{name}: only {n} points");
    }
}

/// Fig. 2(i) at λ = 1, r = 1, γ0 = δ0 = 0: g ∝ 64 − 16x + 8α0x² − 5β0x³, so a double root at x
/// fixes (α0, β0) by a linear 2 × 2 system, and the cusp (triple root) is x = 12, α0 = 1/6,
/// β0 = 1/135.
#[test]
fn fig2i_folds_and_cusp_match_the_closed_form() {
    let m = map(
        preset("fig2i").unwrap().params,
        ("alpha0", 0.0, 0.3),
        ("beta0", 5e-4, 0.02),
        What::Rhythmicity,
        Variant::Paper,
    );
    let folds = trace_folds(&m);
    assert_eq!(folds.cusps.len(), 1, "{:?}", folds.cusps);
    let c = folds.cusps[0];
    assert!((c.x - 1.0 / 6.0).abs() < 1e-8, "{c:?}");
    assert!((c.y - 1.0 / 135.0).abs() < 1e-10, "{c:?}");
    assert!((c.amplitude - 12f64.sqrt()).abs() < 1e-5, "{c:?}");
    let ends_at_cusp = folds
        .curves
        .iter()
        .filter(|c| c.start == CurveEnd::Cusp || c.end == CurveEnd::Cusp)
        .count();
    assert_eq!(ends_at_cusp, 2);
    for curve in &folds.curves {
        for p in &curve.points {
            let x = p.amplitude * p.amplitude;
            // 8α x² − 5β x³ = 16x − 64;  16α x − 15β x² = 16
            let (a11, a12, b1) = (8.0 * x * x, -5.0 * x * x * x, 16.0 * x - 64.0);
            let (a21, a22, b2) = (16.0 * x, -15.0 * x * x, 16.0);
            let det = a11 * a22 - a12 * a21;
            let alpha = (b1 * a22 - a12 * b2) / det;
            let beta = (a11 * b2 - a21 * b1) / det;
            assert!((alpha - p.x).abs() < 1e-8, "{p:?}: α0 = {alpha}");
            assert!(
                (beta - p.y).abs() < 1e-9 * 1e-2 + 1e-10,
                "{p:?}: β0 = {beta}"
            );
        }
    }
}

/// A cubic with a cusp placed by construction: with λ = 1, r = 1, μ0 = 1 and
/// P = c0 + c1U² + 48U⁴ − 25.6U⁶, g = c0/2 + c1x/8 + 3x² − x³ = −(x−1)³ + p(x−1) + q with
/// p = c1/8 + 3, q = c0/2 − 1 + p: folds q = ±2(p/3)^{3/2}, cusp at (c0, c1) = (2, −24), x = 1.
#[test]
fn constructed_cusp_is_found_where_it_was_put() {
    let mut base = Params {
        mu0: 1.0,
        lambda: 1.0,
        restitution: 1.0,
        ..Params::default()
    };
    base.damping.coefficients = vec![2.0, -24.0, 48.0, -25.6];
    let m = map(
        base,
        ("c0", 1.4, 2.8),
        ("c1", -26.0, -20.0),
        What::Rhythmicity,
        Variant::Paper,
    );
    let folds = trace_folds(&m);
    assert_eq!(folds.cusps.len(), 1, "{:?}", folds.cusps);
    let c = folds.cusps[0];
    assert!(
        (c.x - 2.0).abs() < 1e-7 && (c.y + 24.0).abs() < 1e-6 && (c.amplitude - 1.0).abs() < 1e-4,
        "{c:?}"
    );
    for curve in &folds.curves {
        for pt in &curve.points {
            let p = pt.y / 8.0 + 3.0;
            let q = pt.x / 2.0 - 1.0 + p;
            let fold = 2.0 * (p.max(0.0) / 3.0).powf(1.5);
            assert!(
                (q.abs() - fold).abs() < 1e-9,
                "{pt:?}: q = {q}, fold at ±{fold}"
            );
        }
    }
}

#[test]
fn branches_agree_with_the_roots_of_f() {
    for mu0 in [0.01, 0.04, 0.3, 0.7] {
        let base = preset("fig5").unwrap().params.with("mu0", mu0).unwrap();
        let bd = branches(
            &base,
            Variant::Paper,
            What::Rhythmicity,
            "r",
            0.7,
            1.0,
            0.004,
        )
        .unwrap();
        for i in 0..23 {
            let r = 0.7 + 0.3 * (i as f64 + 0.37) / 23.0;
            if bd.folds.iter().any(|f| (f.0 - r).abs() < 2e-3)
                || bd.hopf.iter().any(|h| (h - r).abs() < 2e-3)
            {
                continue;
            }
            let th = Theory::new(&base.with("r", r).unwrap(), Variant::Paper).unwrap();
            let want = th.limit_cycles();
            let mut got: Vec<(f64, bool)> = Vec::new();
            for b in &bd.branches {
                for w in b.points.windows(2) {
                    let (p, q) = (w[0], w[1]);
                    if (p.param - r) * (q.param - r) <= 0.0 && p.param != q.param {
                        let t = (r - p.param) / (q.param - p.param);
                        // The continuation is piecewise linear in x = A².
                        let (xp, xq) = (p.amplitude.powi(2), q.amplitude.powi(2));
                        got.push(((xp + t * (xq - xp)).sqrt(), p.stable));
                    }
                }
            }
            got.sort_by(|a, b| a.0.total_cmp(&b.0));
            assert_eq!(
                got.len(),
                want.len(),
                "μ0 = {mu0}, r = {r}: {got:?} vs {want:?}"
            );
            for (g, w) in got.iter().zip(&want) {
                assert!(
                    (g.0 - w.amplitude).abs() < 2e-3 * w.amplitude,
                    "μ0 = {mu0}, r = {r}: {g:?} vs {w:?}"
                );
                assert_eq!(g.1, w.stable, "μ0 = {mu0}, r = {r}");
            }
        }
        // Folds are double roots.
        for &(r, a) in &bd.folds {
            let th = Theory::new(&base.with("r", r).unwrap(), Variant::Paper).unwrap();
            let g = th.drift_polynomial();
            let x = a * a;
            let scale: f64 = g
                .coefficients
                .iter()
                .enumerate()
                .map(|(k, c)| c.abs() * x.powi(k as i32))
                .sum();
            assert!(
                g.eval(x).abs() < 1e-10 * scale
                    && (x * g.derivative().eval(x)).abs() < 1e-8 * scale,
                "fold ({r}, {a})"
            );
        }
    }
}

#[test]
fn map_counts_equal_the_theory_at_every_point() {
    let m = map(
        preset("fig12c").unwrap().params,
        ("lambda", 0.95, 1.0),
        ("r", 0.8, 1.0),
        What::Modes,
        Variant::Consistent,
    );
    let pl = &m.plane;
    for iy in (0..N).step_by(7) {
        for ix in (0..N).step_by(5) {
            let th = Theory::new(
                &pl.params(pl.x.value(ix), pl.y.value(iy)).unwrap(),
                Variant::Consistent,
            )
            .unwrap();
            let modes = th.amplitude_pdf().unwrap().modes.len();
            assert_eq!(m.count(ix, iy) as usize, modes, "({ix}, {iy})");
        }
    }
}

#[test]
fn maps_do_not_depend_on_the_thread_count() {
    let (_, m) = cases().swap_remove(0);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let single = pool.install(|| classify(&m.plane, m.what, &|_, _| {}));
    assert_eq!(single.counts, m.counts);
}

#[test]
fn printed_eq37_agrees_with_the_correct_condition_only_at_lambda_one() {
    let base = preset("fig12a").unwrap().params;
    for (lambda, same) in [(1.0, true), (0.995, false)] {
        let m = map(
            base.with("lambda", lambda).unwrap(),
            ("mu0", 0.001, 0.1),
            ("r", 0.8, 1.0),
            What::Modes,
            Variant::Paper,
        );
        let printed = trace_printed_eq37(&m).unwrap();
        assert!(!printed.curves.is_empty());
        let worst = printed
            .curves
            .iter()
            .flat_map(|c| c.points.iter())
            .map(|p| fold_residuals(&m.plane, FoldSystem::Fpk, p)[1].abs())
            .fold(0.0, f64::max);
        if same {
            assert!(
                worst < 1e-9,
                "λ = 1: printed curves off the folds by {worst}"
            );
        } else {
            assert!(
                worst > 1e-3,
                "λ = 0.995: printed and correct coincide ({worst})"
            );
        }
    }
    let m = map(
        base,
        ("mu0", 0.001, 0.1),
        ("r", 0.8, 1.0),
        What::Modes,
        Variant::Consistent,
    );
    assert!(matches!(
        trace_printed_eq37(&m),
        Err(Error::Undefined { .. })
    ));
}

/// ΔU = −∫ m1 dA between a well and its crest, by Simpson's rule on m1 (independent of the
/// potential's closed form).
#[test]
fn barriers_are_integrals_of_the_fpk_drift() {
    let base = preset("fig9").unwrap().params.with("tau", 5.0).unwrap();
    let plane = Plane::new(
        &base,
        Axis::new("tau", 3.0, 5.0, 3).unwrap(),
        Axis::new("lambda", 0.99, 1.0, 3).unwrap(),
        Variant::Paper,
    )
    .unwrap();
    let s = barrier_surfaces(&plane, &|_, _| {});
    let mut checked = 0;
    for (i, h) in s.heights.iter().enumerate() {
        let (ix, iy) = (i % 3, i / 3);
        let th = Theory::new(
            &plane.params(plane.x.value(ix), plane.y.value(iy)).unwrap(),
            Variant::Paper,
        )
        .unwrap();
        let ex: Vec<f64> = th.cycles().iter().map(|c| c.amplitude).collect();
        assert_eq!(h.iter().all(|v| v.is_some()), ex.len() == 5, "{i}");
        if ex.len() != 5 {
            continue;
        }
        let integral = |a: f64, b: f64| {
            let n = 2000;
            let hh = (b - a) / n as f64;
            let mut s = th.fpk_drift(a) + th.fpk_drift(b);
            for k in 1..n {
                s += th.fpk_drift(a + k as f64 * hh) * if k % 2 == 1 { 4.0 } else { 2.0 };
            }
            -s * hh / 3.0
        };
        let want = [
            integral(ex[0], ex[1]),
            integral(ex[2], ex[1]),
            integral(ex[2], ex[3]),
            integral(ex[4], ex[3]),
        ];
        for k in 0..4 {
            let got = h[k].unwrap();
            assert!(
                (got - want[k]).abs() < 1e-8 * want[k].abs().max(1e-3),
                "ΔU{}: {got} vs {}",
                k + 1,
                want[k]
            );
        }
        checked += 1;
    }
    assert!(checked > 0);
}

#[test]
fn bad_planes_are_rejected_naming_the_parameter() {
    let base = Params::default();
    let e = Plane::new(
        &base,
        Axis::new("lambda", 0.9, 1.1, 10).unwrap(),
        Axis::new("r", 0.9, 1.0, 10).unwrap(),
        Variant::Paper,
    )
    .unwrap_err();
    assert!(
        matches!(&e, Error::InvalidParameter { name, .. } if name == "lambda"),
        "{e}"
    );
    let e = Plane::new(
        &base,
        Axis::new("r", 0.9, 1.0, 10).unwrap(),
        Axis::new("r", 0.9, 1.0, 10).unwrap(),
        Variant::Paper,
    )
    .unwrap_err();
    assert!(matches!(&e, Error::InvalidParameter { .. }), "{e}");
    assert!(matches!(
        Axis::new("mu0", 0.1, 0.2, 1),
        Err(Error::InvalidParameter { .. })
    ));
    assert!(matches!(
        Axis::new("bogus", 0.1, 0.2, 5),
        Err(Error::Unknown { .. })
    ));
    let e = Plane::new(
        &base,
        Axis::new("r", 0.0, 1.0, 10).unwrap(),
        Axis::new("mu0", 0.1, 1.0, 10).unwrap(),
        Variant::Consistent,
    )
    .unwrap_err();
    assert!(
        matches!(&e, Error::InvalidParameter { name, .. } if name == "r"),
        "{e}"
    );
}

mod random_planes {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(24))]
        /// On random (γ0, δ0) and (λ, τ) planes around the paper's parameters: the counts are
        /// at most three (g has degree 5 in x), every count change lies on a traced curve, and
        /// the curves solve their equations.
        #[test]
        fn random_planes_are_consistent(mu0 in 0.003f64..0.3, lambda in 0.97f64..=1.0, r in 0.9f64..=1.0,
                                        d in 0.05f64..1.0, g0 in 3e-5f64..8e-5, d0 in 1e-7f64..3e-7,
                                        consistent in any::<bool>(), modes in any::<bool>()) {
            let v = if consistent { Variant::Consistent } else { Variant::Paper };
            let mut base = Params { mu0, lambda, restitution: r, noise_intensity: d, correlation_time: 0.5, ..Params::default() };
            base.set("gamma0", g0).unwrap();
            base.set("delta0", d0).unwrap();
            let m = if modes {
                map_n(base, ("lambda", 0.95, 1.0), ("tau", 0.0, 3.0), What::Modes, v, 41)
            } else {
                map_n(base, ("gamma0", 0.5 * g0, 1.5 * g0), ("delta0", 0.5 * d0, 1.5 * d0), What::Rhythmicity, v, 41)
            };
            prop_assert!(m.counts.iter().all(|&c| c <= 3));
            if !m.transitions().is_empty() {
                let (cells, res) = consistency(&m);
                prop_assert!(cells <= 1.0, "{cells} cells");
                prop_assert!(res < 1e-10, "residual {res}");
            }
        }
    }
}
