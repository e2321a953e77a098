//! The verdict rules decide as their docs say (cases that confirm, refute and are
//! undetermined, the multiplicity of tests included); the cheap theory claims computed in quick
//! mode give their verdicts with their numbers; changing a figure's data changes its verdict.
//! The Monte Carlo and Lyapunov claims are behind `#[ignore]` (extended tests).

use trirhythm::monitor::Silent;
use trirhythm::theory::averaging::{Cycle, Variant};
use trirhythm_paper::verdict::claims::{
    judge, Figures, FIG04_CLAIMED_ROOTS, JUDGED_FIGURES, THEORY_FIGURES,
};
use trirhythm_paper::verdict::rules::{
    agreement, closeness, count, curve_distance, dependence, directed_distance, locate,
    separate_maxima, separate_maxima_significant, sign_change, significance, trend, Comparison,
    Count, CountSource, CurveSets, Direction, LleCurve, LlePoint, Located, PointSign, Series,
    CLOSENESS_REL_TOL, CURVE_TOL, PEAK_DIP, PEAK_FLOOR, PEAK_SE_K,
};
use trirhythm_paper::verdict::{Decision, Measured, Outcome, Uncertainty, Verdict};
use trirhythm_paper::FigureOptions;

const QUICK: FigureOptions = FigureOptions {
    quick: true,
    variant: Variant::Paper,
};

fn tag(d: &Decision) -> &'static str {
    d.verdict.tag()
}

fn series(label: &str, values: &[(f64, Measured)]) -> Series {
    Series {
        label: label.into(),
        x_name: "x".into(),
        points: values.to_vec(),
    }
}

// ---- trend ----

#[test]
fn trend_of_exact_values_confirms_refutes_and_sees_no_change() {
    let falling = series(
        "share",
        &[
            (1.0, Measured::exact(3.3)),
            (0.99, Measured::exact(2.9)),
            (0.98, Measured::exact(2.5)),
        ],
    );
    assert_eq!(
        tag(&trend(std::slice::from_ref(&falling), Direction::Decreases)),
        "confirmed"
    );
    // the same numbers against a claimed increase: refuted
    assert_eq!(tag(&trend(&[falling], Direction::Increases)), "refuted");
    // one step against the claim anywhere refutes a monotone claim
    let bump = series(
        "share",
        &[
            (1.0, Measured::exact(3.3)),
            (0.99, Measured::exact(3.4)),
            (0.98, Measured::exact(2.5)),
        ],
    );
    assert_eq!(tag(&trend(&[bump], Direction::Decreases)), "refuted");
    // a change within the relative tolerance for numerical error is no change
    let flat = series(
        "share",
        &[
            (1.0, Measured::exact(3.3)),
            (0.99, Measured::exact(3.3 * (1.0 + 1e-12))),
        ],
    );
    let d = trend(&[flat], Direction::Decreases);
    assert!(matches!(d.verdict, Verdict::Undetermined { .. }), "{d:?}");
}

#[test]
fn trend_with_standard_errors_needs_significance() {
    // change 0.10 with combined se 0.01·√2: z ≈ 7, significant
    let clear = series(
        "LLE",
        &[
            (0.998, Measured::with_se(0.02, 0.01)),
            (0.8, Measured::with_se(0.12, 0.01)),
        ],
    );
    let d = trend(&[clear], Direction::Increases);
    assert_eq!(tag(&d), "confirmed");
    assert_eq!(d.tests, 1);
    assert!((d.checks[0].statistic_value - 0.10 / 0.01f64.hypot(0.01)).abs() < 1e-9);
    // change 0.01 with combined se 0.014: z ≈ 0.7, not significant
    let weak = series(
        "LLE",
        &[
            (0.998, Measured::with_se(0.02, 0.01)),
            (0.8, Measured::with_se(0.03, 0.01)),
        ],
    );
    let d = trend(std::slice::from_ref(&weak), Direction::Increases);
    assert!(
        matches!(d.verdict, Verdict::Undetermined { ref why } if why.contains("not significant"))
    );
    let d = trend(&[weak], Direction::Decreases);
    assert!(matches!(d.verdict, Verdict::Undetermined { .. }));
    // significant the other way: refuted
    let against = series(
        "LLE",
        &[
            (0.998, Measured::with_se(0.12, 0.01)),
            (0.8, Measured::with_se(0.02, 0.01)),
        ],
    );
    assert_eq!(tag(&trend(&[against], Direction::Increases)), "refuted");
}

#[test]
fn trend_counts_every_test_of_the_claim_holm_bonferroni() {
    // one change at z = 2.2 (p = 0.028) is significant alone; among ten series whose changes
    // are 0, Holm's first threshold is 0.005: not significant
    let one = |z: f64| {
        series(
            "v",
            &[
                (0.0, Measured::with_se(0.0, 1.0 / 2f64.sqrt())),
                (1.0, Measured::with_se(z, 1.0 / 2f64.sqrt())),
            ],
        )
    };
    assert_eq!(tag(&trend(&[one(2.2)], Direction::Increases)), "confirmed");
    let mut many = vec![one(2.2)];
    many.extend((0..9).map(|_| one(0.0)));
    let d = trend(&many, Direction::Increases);
    assert_eq!(d.tests, 10);
    assert!(matches!(d.verdict, Verdict::Undetermined { .. }));
    assert!(
        (d.checks[0].threshold - 2.807).abs() < 2e-3,
        "{}",
        d.checks[0].threshold
    );
}

#[test]
fn trend_of_brackets_decides_by_overlap_and_undefined_values_stop_it() {
    let apart = series(
        "D_c",
        &[
            (0.1, Measured::bracket(0.3, 0.2, 0.4)),
            (0.5, Measured::bracket(0.8, 0.6, 1.0)),
        ],
    );
    assert_eq!(tag(&trend(&[apart], Direction::Increases)), "confirmed");
    let overlapping = series(
        "D_c",
        &[
            (0.1, Measured::bracket(0.3, 0.01, 2.0)),
            (0.5, Measured::bracket(0.8, 0.6, 1.0)),
        ],
    );
    assert!(matches!(
        trend(&[overlapping], Direction::Increases).verdict,
        Verdict::Undetermined { .. }
    ));
    let missing = series(
        "D_c",
        &[
            (0.1, Measured::bracket(f64::NAN, f64::NAN, f64::NAN)),
            (0.5, Measured::bracket(0.8, 0.6, 1.0)),
        ],
    );
    let d = trend(&[missing], Direction::Increases);
    assert!(matches!(d.verdict, Verdict::Undetermined { ref why } if why.contains("undefined")));
    // a half-open bracket (rest over the whole searched interval: the boundary is above it)
    let above = series(
        "boundary",
        &[
            (1.0, Measured::bracket(0.03, 0.029, 0.031)),
            (0.95, Measured::bracket(f64::NAN, 0.09, f64::INFINITY)),
        ],
    );
    assert_eq!(tag(&trend(&[above], Direction::Increases)), "confirmed");
    // open brackets that touch at a finite end differ there: D_c ∈ (12, 30) (chaotic at 30)
    // against D_c > 30 (regular at 30); at 0 they do not (D_c = 0 against D_c < 0.002)
    let touching = series(
        "D_c",
        &[
            (0.1, Measured::bracket(19.0, 12.0, 30.0)),
            (0.3, Measured::bracket(f64::NAN, 30.0, f64::INFINITY)),
        ],
    );
    assert_eq!(tag(&trend(&[touching], Direction::Increases)), "confirmed");
    let at_zero = series(
        "D_c",
        &[
            (0.1, Measured::exact(0.0)),
            (0.3, Measured::bracket(f64::NAN, 0.0, 0.002)),
        ],
    );
    assert!(matches!(
        trend(&[at_zero], Direction::Increases).verdict,
        Verdict::Undetermined { .. }
    ));
    // no D_c at all (infinite) is above any located one, and equal to another
    let never = |x: f64| {
        (
            x,
            Measured::bracket(f64::INFINITY, f64::INFINITY, f64::INFINITY),
        )
    };
    let to_never = series(
        "D_c",
        &[
            (0.1, Measured::bracket(19.0, 12.0, 30.0)),
            never(0.3),
            never(0.5),
        ],
    );
    let d = trend(&[to_never], Direction::Increases);
    assert_eq!(tag(&d), "confirmed");
    assert!(
        d.checks.iter().all(|c| !c.value.value.is_nan()),
        "{:?}",
        d.checks
    );
    // none against a one-sided [30, ∞), which may itself be none: no change shown
    let above = |x: f64| (x, Measured::bracket(f64::NAN, 30.0, f64::INFINITY));
    let d = trend(
        &[series("D_c", &[never(0.3), above(0.5)])],
        Direction::Increases,
    );
    assert!(matches!(d.verdict, Verdict::Undetermined { .. }), "{d:?}");
    let d = trend(
        &[series("D_c", &[above(0.3), never(0.5)])],
        Direction::Decreases,
    );
    assert!(matches!(d.verdict, Verdict::Undetermined { .. }), "{d:?}");
    // none after a bounded bracket, against the claimed direction: refuted
    let d = trend(
        &[series(
            "D_c",
            &[(0.1, Measured::bracket(19.0, 12.0, 30.0)), never(0.3)],
        )],
        Direction::Decreases,
    );
    assert_eq!(tag(&d), "refuted");
    let only_never = series("D_c", &[never(0.3), never(0.5)]);
    assert!(matches!(
        trend(&[only_never], Direction::Decreases).verdict,
        Verdict::Undetermined { .. }
    ));
}

// ---- count ----

#[test]
fn count_refutes_on_a_mismatch_and_waits_for_stationarity() {
    let exact = |claimed, computed| Count {
        what: "roots".into(),
        claimed,
        computed,
        source: CountSource::Exact,
    };
    assert_eq!(tag(&count(&[exact(5, 5), exact(3, 3)])), "confirmed");
    assert_eq!(tag(&count(&[exact(5, 5), exact(3, 2)])), "refuted");
    let drifting = Count {
        what: "peaks".into(),
        claimed: 3,
        computed: 2,
        source: CountSource::Ensemble {
            stationary: false,
            r_hat: 8.5,
        },
    };
    let d = count(&[exact(5, 5), drifting.clone()]);
    assert!(
        matches!(d.verdict, Verdict::Undetermined { ref why } if why.contains("not stationary") && why.contains("8.5"))
    );
    // a stationary ensemble's count decides
    let settled = Count {
        source: CountSource::Ensemble {
            stationary: true,
            r_hat: 1.01,
        },
        ..drifting
    };
    assert_eq!(tag(&count(&[settled])), "refuted");
}

// ---- sign change of the LLE ----

fn curve(label: &str, pts: &[(f64, f64, f64)]) -> LleCurve {
    LleCurve {
        label: label.into(),
        points: pts
            .iter()
            .map(|&(d, lle, se)| LlePoint {
                d,
                lle,
                se,
                dof: None,
            })
            .collect(),
    }
}

#[test]
fn sign_change_needs_both_signs_in_order() {
    let rising = curve(
        "μ0 = 0.01",
        &[
            (0.05, -0.05, 0.005),
            (0.2, -0.04, 0.005),
            (0.5, 0.0, 0.005),
            (1.0, 0.05, 0.005),
        ],
    );
    let d = sign_change(&[rising]);
    assert_eq!(tag(&d), "confirmed");
    assert_eq!(d.tests, 4);
    // the same change with only the ends significant: its bracket is the whole range
    let whole = curve(
        "μ0 = 0.01",
        &[(0.05, -0.05, 0.005), (0.5, 0.0, 0.005), (1.0, 0.05, 0.005)],
    );
    let d = sign_change(&[whole]);
    assert!(
        matches!(d.verdict, Verdict::Undetermined { ref why } if why.contains("whole range: D_c not located")),
        "{d:?}"
    );
    let falling = curve(
        "μ0 = 0.01",
        &[(0.05, 0.05, 0.005), (0.5, 0.0, 0.005), (1.0, -0.05, 0.005)],
    );
    let d = sign_change(&[falling]);
    assert_eq!(tag(&d), "refuted");
    assert!(d.checks.iter().any(|c| c.outcome == Outcome::Against));
    // positive from the range's start: D_c below the range cannot be excluded
    let positive = curve(
        "μ0 = 0.001",
        &[(0.05, 0.05, 0.005), (1.0, 0.06, 0.005), (2.0, 0.07, 0.005)],
    );
    let d = sign_change(&[positive]);
    assert!(
        matches!(d.verdict, Verdict::Undetermined { ref why } if why.contains("D_c below the smallest D = 0.05 not excluded")),
        "{d:?}"
    );
    // negative throughout: D_c above the range cannot be excluded
    let negative = curve("μ0 = 0.1", &[(0.05, -0.05, 0.005), (2.0, -0.04, 0.005)]);
    assert!(matches!(
        sign_change(&[negative]).verdict,
        Verdict::Undetermined { ref why } if why.contains("no significant positive")
    ));
    // merged realisations: the point is undefined, and the negative side is missing
    let merged = curve(
        "r = 0.998",
        &[(0.05, f64::NEG_INFINITY, 0.0), (1.0, 0.05, 0.005)],
    );
    let d = sign_change(&[merged]);
    assert!(matches!(d.verdict, Verdict::Undetermined { ref why } if why.contains("merged")));
    assert_eq!(d.tests, 1);
}

#[test]
fn exponents_consistent_with_zero_are_not_significant() {
    // ≈ 1e-3 with standard errors of the same size: nothing is significant, no sign change
    let flat = curve(
        "λ = 0.95",
        &[
            (0.01, -0.001, 0.001),
            (0.1, 0.0012, 0.001),
            (1.0, 0.0015, 0.001),
        ],
    );
    let d = sign_change(std::slice::from_ref(&flat));
    assert!(
        matches!(d.verdict, Verdict::Undetermined { ref why } if why.contains("no significant value of either sign")),
        "{d:?}"
    );
    assert!(d.checks.iter().all(|c| c.outcome == Outcome::Neither));
    let signs = significance(&[flat]);
    assert_eq!(signs[0], vec![PointSign::NotSignificant; 3]);
}

#[test]
fn locate_names_every_outcome_of_a_curve() {
    use PointSign::{Negative as N, NotSignificant as O, Positive as P, Undefined as U};
    let ds = [0.001, 0.01, 0.1, 1.0];
    assert_eq!(
        locate(&ds, &[N, N, P, P]),
        Located::Bracket { lo: 0.01, hi: 0.1 }
    );
    // significant only at the two ends: the bracket is the whole range, not a located D_c
    assert_eq!(locate(&ds, &[N, O, U, P]), Located::WholeRange);
    assert_eq!(locate(&ds, &[P, N, O, O]), Located::Opposite);
    assert_eq!(locate(&ds, &[P, O, P, P]), Located::PositiveFromStart);
    assert_eq!(locate(&ds, &[O, O, P, P]), Located::NoNegative);
    assert_eq!(locate(&ds, &[N, O, O, O]), Located::NoPositive);
    assert_eq!(locate(&ds, &[O, U, O, O]), Located::NotSignificant);
    assert!(Located::PositiveFromStart
        .words(0.001)
        .contains("D_c below the smallest D = 0.001 not excluded"));
    // two points only: the bracket is the range, and the change is located there
    assert_eq!(
        locate(&[0.1, 1.0], &[N, P]),
        Located::Bracket { lo: 0.1, hi: 1.0 }
    );
}

#[test]
fn one_point_at_2_03_sigma_among_36_tests_is_not_significant() {
    // curve 1: −2.03σ at the first D, then clearly positive; three more curves within one
    // standard error of 0 (as at small μ0 where nothing is significant): 4 × 9 = 36 tests
    let ds: Vec<f64> = (0..9).map(|k| 0.05 + 0.24375 * k as f64).collect();
    let mut first = vec![(ds[0], -0.0203, 0.01)];
    first.extend(ds[1..].iter().map(|&d| (d, 0.1, 0.005)));
    let mut curves = vec![curve("μ0 = 0.01", &first)];
    for label in ["μ0 = 0.001", "μ0 = 0.05", "μ0 = 0.1"] {
        let pts: Vec<(f64, f64, f64)> = ds.iter().map(|&d| (d, 0.005, 0.005)).collect();
        curves.push(curve(label, &pts));
    }
    let d = sign_change(&curves);
    assert_eq!(d.tests, 36);
    assert!(matches!(d.verdict, Verdict::Undetermined { .. }), "{d:?}");
    let weak = &d.checks[0];
    assert_eq!(weak.outcome, Outcome::Neither);
    assert!((weak.statistic_value + 2.03).abs() < 1e-9);
    // eight tests rejected before it: Holm holds it against α/28, |z| > 3.12
    assert!((weak.threshold - 3.12).abs() < 0.01, "{}", weak.threshold);
    // alone (two tests), the same point is significant and the curve changes sign
    let alone = curve("μ0 = 0.01", &[(ds[0], -0.0203, 0.01), (ds[1], 0.1, 0.005)]);
    assert_eq!(tag(&sign_change(&[alone])), "confirmed");
    // Holm, not Bonferroni: were all 35 other tests significant, the last step is at α
    let mut strong = vec![curve("μ0 = 0.01", &first)];
    for label in ["μ0 = 0.001", "μ0 = 0.05", "μ0 = 0.1"] {
        let pts: Vec<(f64, f64, f64)> = ds.iter().map(|&d| (d, 0.1, 0.005)).collect();
        strong.push(curve(label, &pts));
    }
    assert_eq!(sign_change(&strong).checks[0].outcome, Outcome::For);
}

#[test]
fn few_realisations_test_with_students_t() {
    // −0.05 ± 0.01 then +0.05 ± 0.01: z = ∓5, significant with the normal distribution…
    let pts = |dof: Option<f64>| LleCurve {
        label: "r = 0.9".into(),
        points: vec![
            LlePoint {
                d: 0.05,
                lle: -0.05,
                se: 0.01,
                dof,
            },
            LlePoint {
                d: 1.0,
                lle: 0.05,
                se: 0.01,
                dof,
            },
        ],
    };
    assert_eq!(tag(&sign_change(&[pts(None)])), "confirmed");
    assert_eq!(tag(&sign_change(&[pts(Some(7.0))])), "confirmed");
    // …but not from two realisations (t with 1 degree of freedom: |t| > 25.45 at α/2 = 0.025)
    let d = sign_change(&[pts(Some(1.0))]);
    assert!(matches!(d.verdict, Verdict::Undetermined { .. }));
    assert!(
        (d.checks[0].threshold - 25.45).abs() < 0.01,
        "{}",
        d.checks[0].threshold
    );
    assert!(d.checks[0].statistic.starts_with('t'));
    // a trend with few degrees of freedom: the smaller of the two is used
    let s = series(
        "LLE",
        &[
            (0.998, Measured::with_se_dof(0.02, 0.01, Some(1.0))),
            (0.8, Measured::with_se_dof(0.12, 0.01, Some(7.0))),
        ],
    );
    assert!(matches!(
        trend(&[s], Direction::Increases).verdict,
        Verdict::Undetermined { .. }
    ));
}

// ---- agreement ----

fn comparison(h: f64, se: f64, ess: f64, stationary: bool) -> Comparison {
    Comparison {
        what: "(a3) r = 0.96".into(),
        hellinger: h,
        se,
        bins: 80,
        ess,
        stationary,
        r_hat: if stationary { 1.01 } else { 180.0 },
        weightings: None,
    }
}

#[test]
fn agreement_within_the_floor_plus_k_standard_errors_on_stationary_ensembles() {
    // floor √(80/(8·2000)) = 0.0707
    assert!((comparison(0.0, 0.0, 2000.0, true).floor() - 0.070_71).abs() < 1e-4);
    assert_eq!(
        tag(&agreement(&[comparison(0.044, 0.012, 2000.0, true)])),
        "confirmed"
    );
    let d = agreement(&[comparison(0.240, 0.002, 2000.0, true)]);
    assert_eq!(tag(&d), "refuted");
    assert!((d.checks[0].threshold - (0.070_71 + 0.004)).abs() < 1e-4);
    let d = agreement(&[comparison(0.044, 0.012, 2000.0, false)]);
    assert!(
        matches!(d.verdict, Verdict::Undetermined { ref why } if why.contains("not stationary") && why.contains("180"))
    );
    // one path: no standard error
    assert!(matches!(
        agreement(&[comparison(0.044, f64::INFINITY, 2000.0, true)]).verdict,
        Verdict::Undetermined { .. }
    ));
}

/// Counts `[replica][well]` over 80 bins and the count beyond: well i has `per_bin` samples
/// in each of `bins[i]` (a replica moves one sample per bin by its index, so the replicas
/// differ and the jackknife has something to measure).
fn well_counts(
    bins: &[std::ops::Range<usize>],
    replicas: usize,
    per_bin: u64,
) -> Vec<Vec<Vec<u64>>> {
    (0..replicas)
        .map(|r| {
            bins.iter()
                .map(|range| {
                    (0..81)
                        .map(|b| {
                            if range.contains(&b) {
                                per_bin + if b % 2 == 0 { r as u64 } else { 0 }
                            } else {
                                0
                            }
                        })
                        .collect()
                })
                .collect()
        })
        .collect()
}

/// Replica-wise sum of two halves' counts (the whole window).
fn whole_of(a: &[Vec<Vec<u64>>], b: &[Vec<Vec<u64>>]) -> Vec<Vec<Vec<u64>>> {
    a.iter()
        .zip(b)
        .map(|(x, y)| {
            x.iter()
                .zip(y)
                .map(|(u, v)| u.iter().zip(v).map(|(p, q)| p + q).collect())
                .collect()
        })
        .collect()
}

/// The rule over every weighting, end to end: counts per replica and well on each half of the
/// window, the library's H range over the simplex with its jackknife, and the agreement rule;
/// a well's statistics drift, so the halves are given.
fn drifting(
    q: &[f64],
    early: &[Vec<Vec<u64>>],
    late: &[Vec<Vec<u64>>],
) -> (Comparison, trirhythm::analysis::ensemble::HellingerBounds) {
    use trirhythm::analysis::ensemble::hellinger_bounds;
    use trirhythm_paper::verdict::rules::{WeightingRange, Weightings};
    let range = |c: &[Vec<Vec<u64>>]| {
        let b = hellinger_bounds("paper", q, c);
        (
            WeightingRange {
                h_min: b.h_min.value,
                h_min_se: b.h_min.stderr,
                h_max: b.h_max.value,
                h_max_se: b.h_max.stderr,
            },
            b,
        )
    };
    let (whole, bounds) = range(&whole_of(early, late));
    let nw = early[0].len();
    let c = Comparison {
        weightings: Some(Weightings {
            h_min: whole.h_min,
            h_min_se: whole.h_min_se,
            h_max: whole.h_max,
            h_max_se: whole.h_max_se,
            // ESS 1000 per well: largest floor 0.1 on the whole window, 0.141 on a half
            ess_min: 1000.0,
            ess_sum: 1000.0 * nw as f64,
            replicas: early.len(),
            halves: Some([range(early).0, range(late).0]),
        }),
        ..comparison(f64::NAN, f64::NAN, f64::NAN, false)
    };
    (c, bounds)
}

#[test]
fn agreement_over_every_weighting_of_drifting_wells_needs_each_half() {
    use trirhythm::analysis::ensemble::hellinger_of_mixture;
    use trirhythm_paper::verdict::rules::Weightings;
    // the theory: all its mass on bins 60..70 (the outer cycle), none beyond
    let mut q = vec![0.0; 81];
    for x in &mut q[60..70] {
        *x = 0.1;
    }
    let replicas = 16;
    // three wells; the outer one sits two bins below the theory's peak and drifts by a bin
    let early = well_counts(&[5..15, 30..40, 57..67], replicas, 1000);
    let late = well_counts(&[5..15, 30..40, 58..68], replicas, 1000);
    let (c, bounds) = drifting(&q, &early, &late);
    // every weighting disagrees, on the whole window and on each half: refuted
    let d = agreement(std::slice::from_ref(&c));
    assert_eq!(tag(&d), "refuted", "{:?}", d.checks[0].what);
    assert!(
        d.checks[0].what.contains("first half"),
        "{}",
        d.checks[0].what
    );
    // the bound is one: no weighting of a grid over the simplex comes nearer than H_min
    let whole = whole_of(&early, &late);
    let p: Vec<Vec<f64>> = (0..3)
        .map(|i| {
            let t: Vec<f64> = (0..81)
                .map(|b| whole.iter().map(|r| r[i][b] as f64).sum())
                .collect();
            let s: f64 = t.iter().sum();
            t.into_iter().map(|x| x / s).collect()
        })
        .collect();
    let threshold = 0.1;
    for a in 0..=20 {
        for b in 0..=(20 - a) {
            let pi = [a as f64 / 20.0, b as f64 / 20.0, (20 - a - b) as f64 / 20.0];
            let h = hellinger_of_mixture(&q, &p, &pi);
            assert!(
                h >= bounds.h_min.value - 1e-9 && h > threshold,
                "{pi:?}: {h}"
            );
        }
    }
    // the outer well on the theory's bins: that mixture agrees, others do not: undetermined
    let early = well_counts(&[5..15, 30..40, 60..70], replicas, 1000);
    let (c, _) = drifting(&q, &early, &early);
    let d = agreement(&[c]);
    assert!(
        matches!(d.verdict, Verdict::Undetermined { ref why } if why.contains("for every weighting of the wells")),
        "{:?}",
        d.verdict
    );
    // the whole window disagrees for every weighting but the late half agrees: the drift
    // decides, and the rule does not pick the whole window's answer
    let early = well_counts(&[5..15, 30..40, 20..30], replicas, 1000);
    let late = well_counts(&[5..15, 30..40, 60..70], replicas, 1000);
    let (c, bounds) = drifting(&q, &early, &late);
    assert!(bounds.h_min.value > 0.3, "{}", bounds.h_min.value);
    let whole_only = Comparison {
        weightings: c.weightings.map(|w| Weightings { halves: None, ..w }),
        ..c.clone()
    };
    assert_eq!(tag(&agreement(&[whole_only])), "refuted");
    let d = agreement(&[c]);
    assert!(
        matches!(d.verdict, Verdict::Undetermined { ref why } if why.contains("do not give the same decision")),
        "{:?}",
        d.verdict
    );
}

#[test]
fn agreement_for_every_weighting_of_wells_whose_weights_are_undetermined() {
    use trirhythm_paper::verdict::rules::{Weightings, MIN_WEIGHTING_REPLICAS};
    // bins 80; ESS per well ≥ 1000 (largest floor √(80/8000) = 0.1), ΣESS = 8000 (smallest
    // floor √(80/64000) = 0.0354)
    let with_replicas = |h_min: f64, h_max: f64, se: f64, replicas: usize| Comparison {
        weightings: Some(Weightings {
            h_min,
            h_min_se: se,
            h_max,
            h_max_se: se,
            ess_min: 1000.0,
            ess_sum: 8000.0,
            replicas,
            halves: None,
        }),
        ..comparison(f64::NAN, f64::NAN, f64::NAN, false)
    };
    let with = |h_min: f64, h_max: f64, se: f64| with_replicas(h_min, h_max, se, 16);
    // no weighting agrees: H_min − 2 s.e. = 0.46 > 0.1
    let d = agreement(&[with(0.5, 0.9, 0.02)]);
    assert_eq!(tag(&d), "refuted");
    assert_eq!(d.checks[0].outcome, Outcome::Against);
    assert!((d.checks[0].threshold - (0.1 + 0.04)).abs() < 1e-12);
    assert!(d.checks[0].what.contains("every weighting"));
    // just within: H_min − 2 s.e. = 0.099 ≤ 0.1
    let d = agreement(&[with(0.139, 0.9, 0.02)]);
    assert!(
        matches!(d.verdict, Verdict::Undetermined { ref why } if why.contains("for every weighting of the wells")),
        "{:?}",
        d.verdict
    );
    // every weighting agrees: H_max + 2 s.e. = 0.03 ≤ 0.0354
    let d = agreement(&[with(0.01, 0.02, 0.005)]);
    assert_eq!(tag(&d), "confirmed");
    assert_eq!(d.checks[0].outcome, Outcome::For);
    // H_max + 2 s.e. = 0.04 > 0.0354 although each weighting may agree: undetermined
    assert_eq!(tag(&agreement(&[with(0.01, 0.03, 0.005)])), "undetermined");
    // no standard error over the replicas: undetermined
    assert_eq!(tag(&agreement(&[with(0.5, 0.9, f64::NAN)])), "undetermined");
    // a standard error from too few replicas decides nothing (quick mode's 2)
    let few = agreement(&[with_replicas(0.5, 0.9, 0.02, MIN_WEIGHTING_REPLICAS - 1)]);
    assert!(
        matches!(few.verdict, Verdict::Undetermined { ref why } if why.contains("at least 8 replicas")),
        "{:?}",
        few.verdict
    );
    assert_eq!(
        tag(&agreement(&[with_replicas(
            0.5,
            0.9,
            0.02,
            MIN_WEIGHTING_REPLICAS
        )])),
        "refuted"
    );
    // combined as before: a refuted panel refutes the claim beside an undetermined one, and a
    // panel refused for another reason (no weightings) stays undetermined
    let other = comparison(0.044, 0.012, 2000.0, false);
    assert_eq!(
        tag(&agreement(&[with(0.5, 0.9, 0.02), other.clone()])),
        "refuted"
    );
    assert_eq!(
        tag(&agreement(&[with(0.01, 0.02, 0.005), other])),
        "undetermined"
    );
    // weightings on a stationary ensemble are not used: its own H decides
    let stationary = Comparison {
        stationary: true,
        ..with(0.5, 0.9, 0.02)
    };
    let stationary = Comparison {
        hellinger: 0.044,
        se: 0.012,
        ess: 2000.0,
        ..stationary
    };
    assert_eq!(tag(&agreement(&[stationary])), "confirmed");
}

// ---- closeness ----

#[test]
fn closeness_below_the_stated_tolerance() {
    let pair = |a: f64, b: f64| {
        vec![(
            "amplitude".to_string(),
            Measured::exact(a),
            Measured::exact(b),
        )]
    };
    assert_eq!(
        tag(&closeness(&pair(6.782, 6.780), CLOSENESS_REL_TOL)),
        "confirmed"
    );
    let d = closeness(&pair(7.887, 6.780), CLOSENESS_REL_TOL);
    assert_eq!(tag(&d), "refuted");
    assert!((d.checks[0].statistic_value - (7.887 - 6.780) / 7.887).abs() < 1e-12);
    // a bracket's half-width is part of the margin: 0.100 in [0.09, 0.11] against 0.1
    // (exact) is within 5 % only if the bracket is narrow enough
    let bracketed = |lo: f64, hi: f64| {
        vec![(
            "boundary".to_string(),
            Measured::bracket(0.1, lo, hi),
            Measured::exact(0.1),
        )]
    };
    assert_eq!(
        tag(&closeness(&bracketed(0.099, 0.101), CLOSENESS_REL_TOL)),
        "confirmed"
    );
    assert!(matches!(
        closeness(&bracketed(0.09, 0.11), CLOSENESS_REL_TOL).verdict,
        Verdict::Undetermined { .. }
    ));
    // within 2 s.e. of the tolerance: undetermined
    let noisy = vec![(
        "amplitude".to_string(),
        Measured::with_se(1.05, 0.02),
        Measured::exact(1.0),
    )];
    assert!(matches!(
        closeness(&noisy, CLOSENESS_REL_TOL).verdict,
        Verdict::Undetermined { .. }
    ));
}

// ---- dependence ----

#[test]
fn dependence_needs_a_change_beyond_the_tolerance_and_its_margin() {
    let exact = |v: &[f64]| {
        series(
            "interval",
            &v.iter()
                .enumerate()
                .map(|(i, &x)| (i as f64, Measured::exact(x)))
                .collect::<Vec<_>>(),
        )
    };
    // 0.0016 → 0.95: depends
    let d = dependence(&[exact(&[0.0016, 0.016, 0.95])], CLOSENESS_REL_TOL);
    assert_eq!(tag(&d), "confirmed");
    assert!((d.checks[0].statistic_value - (0.95 - 0.0016) / 0.95).abs() < 1e-12);
    // every value within 5 % of the largest: no dependence the claim could mean
    let d = dependence(&[exact(&[1.0, 1.02, 0.98])], CLOSENESS_REL_TOL);
    assert_eq!(tag(&d), "refuted");
    assert_eq!(d.checks[0].outcome, Outcome::Against);
    // one series against, one for: refuted (the claim holds at every place it names)
    let d = dependence(
        &[exact(&[1.0, 2.0]), exact(&[1.0, 1.01])],
        CLOSENESS_REL_TOL,
    );
    assert_eq!(tag(&d), "refuted");
    // brackets: a change of 10 % that the brackets' half-widths could make 4 %: undetermined
    let wide = series(
        "boundary",
        &[
            (0.9, Measured::bracket(1.0, 0.97, 1.03)),
            (0.3, Measured::bracket(0.9, 0.87, 0.93)),
        ],
    );
    assert!(matches!(
        dependence(&[wide], CLOSENESS_REL_TOL).verdict,
        Verdict::Undetermined { .. }
    ));
    // the same change with narrow brackets: confirmed
    let narrow = series(
        "boundary",
        &[
            (0.9, Measured::bracket(1.0, 0.999, 1.001)),
            (0.3, Measured::bracket(0.9, 0.899, 0.901)),
        ],
    );
    assert_eq!(tag(&dependence(&[narrow], CLOSENESS_REL_TOL)), "confirmed");
    // an undefined value stops it
    let d = dependence(&[exact(&[1.0, f64::NAN, 3.0])], CLOSENESS_REL_TOL);
    assert!(matches!(d.verdict, Verdict::Undetermined { .. }));
    assert_eq!(d.checks[0].outcome, Outcome::Undefined);
}

// ---- curve distance ----

#[test]
fn curve_distance_needs_each_set_near_the_other() {
    let line = |x: f64| (0..=100).map(|k| (x, k as f64 / 100.0)).collect::<Vec<_>>();
    // the distance from a point to a segment, not just to vertices
    let seg = vec![vec![(0.0, 0.0), (1.0, 0.0)]];
    assert!((directed_distance(&[vec![(0.5, 0.3)]], &seg) - 0.3).abs() < 1e-12);
    assert_eq!(directed_distance(&[], &seg), 0.0);
    assert_eq!(directed_distance(&seg, &[]), f64::INFINITY);
    let sets = |tested: Vec<Vec<(f64, f64)>>, reference: Vec<Vec<(f64, f64)>>| CurveSets {
        what: "panel".into(),
        tested,
        reference,
        cell: 0.0025,
    };
    // the same curves, one 0.01 of the plane off: confirmed
    let d = curve_distance(
        &[sets(
            vec![line(0.51), line(0.8)],
            vec![line(0.5), line(0.8)],
        )],
        CURVE_TOL,
    );
    assert_eq!(tag(&d), "confirmed");
    assert!((d.checks[0].statistic_value - 0.01).abs() < 1e-12);
    // a curve 0.1 off: refuted
    let d = curve_distance(&[sets(vec![line(0.6)], vec![line(0.5)])], CURVE_TOL);
    assert_eq!(tag(&d), "refuted");
    // a reference curve the tested set misses: refuted, though every tested point lies on
    // the reference
    let d = curve_distance(
        &[sets(vec![line(0.5)], vec![line(0.5), line(0.9)])],
        CURVE_TOL,
    );
    assert_eq!(tag(&d), "refuted");
    assert!((d.checks[0].statistic_value - 0.4).abs() < 1e-12);
    // nothing to compare
    let d = curve_distance(&[sets(vec![], vec![])], CURVE_TOL);
    assert!(matches!(d.verdict, Verdict::Undetermined { .. }));
}

// ---- separate maxima of a 2-D density ----

/// A density on an n × n grid of [−1, 1]²: Gaussian bumps (centre, width, height) plus a ring
/// (radius, width, height) when given.
fn density(
    n: usize,
    bumps: &[(f64, f64, f64, f64)],
    ring: Option<(f64, f64, f64)>,
) -> Vec<Vec<f64>> {
    let at = |i: usize| -1.0 + 2.0 * (i as f64 + 0.5) / n as f64;
    (0..n)
        .map(|i| {
            (0..n)
                .map(|k| {
                    let (x, y) = (at(i), at(k));
                    let mut v: f64 = bumps
                        .iter()
                        .map(|&(cx, cy, w, h)| {
                            h * (-((x - cx).powi(2) + (y - cy).powi(2)) / (2.0 * w * w)).exp()
                        })
                        .sum();
                    if let Some((r0, w, h)) = ring {
                        v += h * (-((x.hypot(y) - r0).powi(2)) / (2.0 * w * w)).exp();
                    }
                    v
                })
                .collect()
        })
        .collect()
}

#[test]
fn separate_maxima_count_peaks_not_rings_or_shoulders() {
    let four = [
        (0.5, 0.5, 0.1, 1.0),
        (-0.5, 0.5, 0.1, 0.8),
        (0.5, -0.5, 0.1, 0.6),
        (-0.5, -0.5, 0.1, 0.9),
    ];
    assert_eq!(
        separate_maxima(&density(64, &four, None), PEAK_FLOOR, PEAK_DIP),
        4
    );
    // a ring (a crater's rim) is one maximum
    assert_eq!(
        separate_maxima(
            &density(64, &[], Some((0.6, 0.05, 1.0))),
            PEAK_FLOOR,
            PEAK_DIP
        ),
        1
    );
    // two bumps whose valley stays above half the lower one: one peak with a shoulder
    let close = [(0.0, 0.1, 0.15, 1.0), (0.0, -0.1, 0.15, 0.9)];
    assert_eq!(
        separate_maxima(&density(64, &close, None), PEAK_FLOOR, PEAK_DIP),
        1
    );
    // pulled apart, they separate
    let apart = [(0.0, 0.5, 0.15, 1.0), (0.0, -0.5, 0.15, 0.9)];
    assert_eq!(
        separate_maxima(&density(64, &apart, None), PEAK_FLOOR, PEAK_DIP),
        2
    );
    // a speck below the floor (1 % of the largest) is not a peak; above it, it is
    let speck = |h: f64| [(0.0, 0.0, 0.1, 1.0), (0.8, 0.8, 0.03, h)];
    assert_eq!(
        separate_maxima(&density(64, &speck(0.005), None), PEAK_FLOOR, PEAK_DIP),
        1
    );
    assert_eq!(
        separate_maxima(&density(64, &speck(0.05), None), PEAK_FLOOR, PEAK_DIP),
        2
    );
    assert_eq!(
        separate_maxima(&vec![vec![0.0; 4]; 4], PEAK_FLOOR, PEAK_DIP),
        0
    );
}

#[test]
fn separate_maxima_of_a_histogram_need_dips_beyond_their_standard_errors() {
    let four = [
        (0.5, 0.5, 0.1, 1.0),
        (-0.5, 0.5, 0.1, 0.8),
        (0.5, -0.5, 0.1, 0.6),
        (-0.5, -0.5, 0.1, 0.9),
    ];
    let d = density(64, &four, None);
    let se = |s: f64| vec![vec![s; 64]; 64];
    // standard errors small against the dips: the four peaks stand
    assert_eq!(
        separate_maxima_significant(&d, &se(0.01), PEAK_FLOOR, PEAK_DIP, PEAK_SE_K),
        4
    );
    // standard errors as large as the peaks: only the highest counts
    assert_eq!(
        separate_maxima_significant(&d, &se(0.5), PEAK_FLOOR, PEAK_DIP, PEAK_SE_K),
        1
    );
    // peaks cut off from each other by the floor count when 3 s.e. above zero: the weakest
    // (0.54 in its cell) falls below 3 × 0.22 = 0.66, the next (0.73) stays
    assert_eq!(
        separate_maxima_significant(&d, &se(0.22), PEAK_FLOOR, PEAK_DIP, PEAK_SE_K),
        3
    );
    // a peak joined to a higher one: its dip must be significant as well as deep
    let apart = density(64, &[(0.0, 0.25, 0.1, 1.0), (0.0, -0.25, 0.1, 0.9)], None);
    assert_eq!(
        separate_maxima_significant(&apart, &se(0.01), PEAK_FLOOR, PEAK_DIP, PEAK_SE_K),
        2
    );
    assert_eq!(
        separate_maxima_significant(&apart, &se(0.2), PEAK_FLOOR, PEAK_DIP, PEAK_SE_K),
        1
    );
}

// ---- the Monte Carlo claims on constructed data ----

/// A Fig. 13 panel with one ensemble of Eq. 1: the theory's (binned) and the histogram's mode
/// counts, its stationarity, and a drawn theory curve with `analytic` maxima.
fn amplitude_panel(
    caption: &str,
    modes_theory: usize,
    modes_mc: usize,
    stationary: bool,
    analytic: usize,
) -> trirhythm_paper::montecarlo::AmplitudePanel {
    use trirhythm_paper::montecarlo::{AmplitudePanel, Distance, McRun};
    let a: Vec<f64> = (0..200).map(|i| i as f64 * 0.05).collect();
    let curve: Vec<f64> = a
        .iter()
        .map(|&x| {
            (1.0 + (std::f64::consts::PI * analytic as f64 * x / 10.0)
                .sin()
                .powi(2))
                * 0.1
        })
        .collect();
    AmplitudePanel {
        caption: caption.into(),
        theory: vec![("paper".into(), a, curve)],
        runs: vec![McRun {
            system: "Eq. 1".into(),
            edges: vec![0.0, 1.0],
            density: vec![1.0],
            stderr: vec![0.0],
            beyond: 0.0,
            stationary,
            r_hat: if stationary { 1.0 } else { 5.0 },
            ess: 1e4,
            distances: vec![Distance {
                variant: "paper".into(),
                hellinger: 0.0,
                hellinger_stderr: 0.0,
                l1: 0.0,
                ks: 0.0,
                modes_theory,
                modes_mc,
            }],
            step_warnings: vec![],
            estimator: "direct".into(),
            wells: None,
        }],
    }
}

fn judge_fig13(panels: Vec<trirhythm_paper::montecarlo::AmplitudePanel>) -> Figures {
    use trirhythm_paper::fig13_pdf_restitution::Fig13;
    use trirhythm_paper::notes::Caption;
    Figures {
        fig13: Some(Fig13 {
            caption: Caption {
                title: String::new(),
                lines: vec![],
            },
            notes: vec![],
            panels,
        }),
        ..Default::default()
    }
}

#[test]
fn fig13_peaks_are_decided_by_the_theory_first_then_stationary_ensembles() {
    use trirhythm_paper::verdict::claims::{FIG13B_CLAIMED_PEAKS, FIG13_CLAIMED_PEAKS};
    let a = |theory: [usize; 4], mc: [usize; 4], stationary: bool| {
        (0..4)
            .map(|i| {
                amplitude_panel(
                    &format!("(a{})", i + 1),
                    theory[i],
                    mc[i],
                    stationary,
                    FIG13_CLAIMED_PEAKS[i] as usize,
                )
            })
            .collect::<Vec<_>>()
    };
    let claimed = FIG13_CLAIMED_PEAKS.map(|c| c as usize);
    // theory and stationary ensembles as the text says: confirmed
    let v = judge(&judge_fig13(a(claimed, claimed, true)));
    assert_eq!(tag(&v.get("fig13a-peaks").unwrap().decision), "confirmed");
    // the theory's visible peaks 2/1/1/1 (the full-quality data): refuted, and the first
    // deciding check is the theory's, whatever the ensembles
    let v = judge(&judge_fig13(a([2, 1, 1, 1], claimed, false)));
    let d = &v.get("fig13a-peaks").unwrap().decision;
    assert_eq!(tag(d), "refuted");
    let first = d.deciding(1)[0];
    assert!(first.what.starts_with("averaged theory"), "{}", first.what);
    assert!(first.what.contains("analytic maxima"), "{}", first.what);
    // theory as claimed, ensembles not stationary: undetermined
    let v = judge(&judge_fig13(a(claimed, [1, 1, 1, 1], false)));
    assert_eq!(
        tag(&v.get("fig13a-peaks").unwrap().decision),
        "undetermined"
    );
    // (b1)–(b4): "the three peaks endure"
    let b = |theory: usize, mc: usize, stationary: bool| {
        let mut p = a(claimed, claimed, true);
        p.extend((1..=4).map(|i| amplitude_panel(&format!("(b{i})"), theory, mc, stationary, 3)));
        judge(&judge_fig13(p))
    };
    let three = FIG13B_CLAIMED_PEAKS as usize;
    assert_eq!(
        tag(&b(three, three, true).get("fig13b-peaks").unwrap().decision),
        "confirmed"
    );
    assert_eq!(
        tag(&b(1, three, false).get("fig13b-peaks").unwrap().decision),
        "refuted"
    );
    assert_eq!(
        tag(&b(three, 1, false).get("fig13b-peaks").unwrap().decision),
        "undetermined"
    );
    assert_eq!(
        tag(&b(three, 2, true).get("fig13b-peaks").unwrap().decision),
        "refuted"
    );
}

/// A Fig. 14 panel: four bumps (or a ring) as both densities, the Monte Carlo's cell standard
/// errors, its mass outside the window, ⟨U̇²⟩ of both, stationarity.
fn joint_panel(
    r: f64,
    rings: bool,
    stationary: bool,
    outside: f64,
    var_theory: f64,
    var_mc: f64,
) -> trirhythm_paper::fig14_joint_pdf::JointPanel {
    let four = [
        (0.5, 0.5, 0.1, 1.0),
        (-0.5, 0.5, 0.1, 0.8),
        (0.5, -0.5, 0.1, 0.6),
        (-0.5, -0.5, 0.1, 0.9),
    ];
    let d = density(32, &four, None);
    let theory_fine = if rings {
        density(128, &[], Some((0.6, 0.05, 1.0)))
    } else {
        density(128, &four, None)
    };
    let edges: Vec<f64> = (0..=32).map(|i| i as f64 / 32.0).collect();
    trirhythm_paper::fig14_joint_pdf::JointPanel {
        r,
        u_edges: edges.clone(),
        v_edges: edges,
        theory: d.clone(),
        theory_fine,
        theory_outside: 0.0,
        mc_outside: outside,
        mc: d,
        mc_stderr: vec![vec![0.01; 32]; 32],
        mc_velocity_variance: vec![var_mc, 0.5],
        theory_velocity_variance: var_theory,
        hellinger: 0.0,
        stationary,
        r_hat: if stationary { 1.0 } else { 2.0 },
        estimator: "direct".into(),
        wells: None,
    }
}

fn judge_fig14(
    panels: Vec<trirhythm_paper::fig14_joint_pdf::JointPanel>,
) -> trirhythm_paper::verdict::claims::Verdicts {
    use trirhythm_paper::fig14_joint_pdf::Fig14;
    use trirhythm_paper::notes::Caption;
    judge(&Figures {
        fig14: Some(Fig14 {
            caption: Caption {
                title: String::new(),
                lines: vec![],
            },
            notes: vec![],
            panels,
        }),
        ..Default::default()
    })
}

#[test]
fn fig14_shift_and_peaks_per_model() {
    // ⟨U̇²⟩ falling as r grows in both models, ensembles stationary: confirmed
    let rs = [0.999, 0.96, 0.92, 0.86];
    let panels_of = |rings: bool, theory: [f64; 4], mc: [f64; 4], stationary: bool, outside| {
        (0..4)
            .map(|i| joint_panel(rs[i], rings, stationary, outside, theory[i], mc[i]))
            .collect::<Vec<_>>()
    };
    let panels =
        |theory, mc, stationary, outside| panels_of(false, theory, mc, stationary, outside);
    let falling = [80.0, 82.0, 84.0, 86.0];
    let v = judge_fig14(panels(falling, falling, true, 0.0));
    assert_eq!(tag(&v.get("fig14-shift").unwrap().decision), "confirmed");
    // the theory's rising with r (the full-quality 82.7 → 83.6): refuted whatever the ensembles
    let rising = [83.58, 83.37, 83.14, 82.73];
    let v = judge_fig14(panels(rising, falling, false, 0.0));
    assert_eq!(tag(&v.get("fig14-shift").unwrap().decision), "refuted");
    // the theory as claimed, the ensembles not stationary: undetermined
    let v = judge_fig14(panels(falling, rising, false, 0.0));
    assert_eq!(tag(&v.get("fig14-shift").unwrap().decision), "undetermined");
    // peaks: four in both models, the ensemble stationary and holding its mass: confirmed,
    // the Monte Carlo count with significant dips
    let crater = |rings, stationary, outside| {
        judge_fig14(panels_of(rings, falling, falling, stationary, outside))
            .get("fig14-crater")
            .unwrap()
            .decision
            .clone()
    };
    let d = crater(false, true, 0.0);
    assert_eq!(tag(&d), "confirmed");
    let mc: Vec<_> = d
        .checks
        .iter()
        .filter(|c| c.what.starts_with("Eq. 1"))
        .collect();
    assert_eq!(mc[0].statistic_value, 4.0);
    // 5 % of the samples outside the window, or not stationary: the Monte Carlo part decides
    // nothing
    assert_eq!(tag(&crater(false, true, 0.05)), "undetermined");
    assert_eq!(tag(&crater(false, false, 0.0)), "undetermined");
    // the theory's rings (Eq. 30–31 depends on the amplitude alone): one maximum, refuted
    assert_eq!(tag(&crater(true, true, 0.0)), "refuted");
}

#[test]
fn noise_disorder_needs_the_exponent_to_rise_with_d_on_every_curve() {
    use trirhythm_paper::fig17_lle_noise::Fig17;
    use trirhythm_paper::lle::{DtCheck, LleAgainstNoise, StartKind};
    use trirhythm_paper::notes::Caption;
    let judge17 = |curves: &[(StartKind, &[f64])]| {
        let data = LleAgainstNoise {
            caption: Caption {
                title: String::new(),
                lines: vec![],
            },
            notes: vec![],
            panels: vec![lle_panel("(a)", curves)],
            dt_check: DtCheck {
                what: String::new(),
                panel: "a".into(),
                dt_rule: 0.005,
                points: vec![],
            },
        };
        judge(&Figures {
            fig17: Some(Fig17(data)),
            ..Default::default()
        })
        .get("fig17-disorder")
        .unwrap()
        .decision
        .clone()
    };
    let rising: &[f64] = &[-0.05, -0.04, 0.05, 0.06];
    // synchronisation on a cycle: the exponent falls with D (the full-quality μ0 = 0.05 curves)
    let falling: &[f64] = &[0.0, -0.005, -0.03, -0.055];
    let flat: &[f64] = &[0.01, 0.011, 0.01, 0.011];
    assert_eq!(tag(&judge17(&[(StartKind::Rest, rising)])), "confirmed");
    assert_eq!(
        tag(&judge17(&[
            (StartKind::Rest, rising),
            (StartKind::Cycle, falling)
        ])),
        "refuted"
    );
    assert_eq!(
        tag(&judge17(&[
            (StartKind::Rest, rising),
            (StartKind::Cycle, flat)
        ])),
        "undetermined"
    );
}

#[test]
fn fig01_recurrence_is_closeness_of_rr_and_det() {
    use trirhythm_paper::fig01_phase_recurrence::{Fig01, Panel};
    use trirhythm_paper::notes::Caption;
    let fig = |rr: [f64; 2], det: [f64; 2]| {
        let panel = |k: usize| Panel {
            title: String::new(),
            phase: vec![],
            t: vec![],
            u: vec![],
            v: vec![],
            rr: rr[k],
            det: det[k],
            amplitude: 1.0,
        };
        judge(&Figures {
            fig01: Some(Fig01 {
                caption: Caption {
                    title: String::new(),
                    lines: vec![],
                },
                notes: vec![],
                panels: vec![panel(0), panel(1)],
                start: 0.0,
                epsilon: 0.1,
            }),
            ..Default::default()
        })
        .get("fig01-recurrence")
        .unwrap()
        .decision
        .clone()
    };
    assert_eq!(tag(&fig([0.0100, 0.0101], [1.0, 1.0])), "confirmed");
    // the full-quality RR 0.0086 against 0.0100: 14 % apart
    let d = fig([0.0086, 0.0100], [1.0, 1.0]);
    assert_eq!(tag(&d), "refuted");
    assert!(d.deciding(1)[0].what.starts_with("recurrence rate"));
    assert_eq!(tag(&fig([0.0100, 0.0100], [0.8, 1.0])), "refuted");
}

// ---- the claims, computed ----

#[test]
fn theory_claims_in_quick_mode_with_their_numbers() {
    let figs = Figures::compute(&QUICK, &Silent, &THEORY_FIGURES).unwrap();
    let v = judge(&figs);
    for c in &v.claims {
        eprintln!(
            "{} → {} {:?} tally {:?}",
            c.claim.id,
            c.decision.verdict.tag(),
            match &c.decision.verdict {
                Verdict::Undetermined { why } => why.chars().take(200).collect::<String>(),
                _ => String::new(),
            },
            c.decision.tally
        );
        for ch in c.decision.checks.iter().take(6) {
            eprintln!(
                "    {}: {} = {} vs {} → {:?}",
                ch.what, ch.statistic, ch.statistic_value, ch.threshold, ch.outcome
            );
        }
    }
    // Fig. 4: Eq. 18 gives 3, 2, 2, 0 positive roots against the text's 5, 5, 3, 0
    let roots = v.get("fig04-roots").unwrap();
    assert_eq!(roots.decision.verdict, Verdict::Refuted);
    let computed: Vec<f64> = roots
        .decision
        .checks
        .iter()
        .map(|c| c.statistic_value)
        .collect();
    assert_eq!(computed, vec![3.0, 2.0, 2.0, 0.0]);
    assert_eq!(roots.decision.checks[3].outcome, Outcome::For);
    // Fig. 1: the mean amplitudes differ by more than the 5 % of "align closely"
    let align = v.get("fig01-align").unwrap();
    assert_eq!(align.decision.verdict, Verdict::Refuted);
    assert!(align.decision.checks[0].statistic_value > 0.1);
    // the region trends of the maps: Figs 6, 10 as claimed, Fig. 12 (μ0, r) against; Fig.
    // 12 (λ, r)'s small change is within what the quick grid resolves (shares are brackets
    // from the region's interior to its closure on the grid): not significant
    let d = &v.get("fig12-omega-lambda-r").unwrap().decision;
    match &d.verdict {
        Verdict::Undetermined { why } => assert!(why.contains("not significant"), "{why}"),
        other => panic!("fig12-omega-lambda-r at quick resolution: {other:?}"),
    }
    // the (γ0, δ0) zones are measured between the exact fold curves: the trirhythmic area
    // rises by 0.016 points from r = 1 to 0.998 (Fig. 3) and by 0.022 from λ = 1 to 0.999
    // (Fig. 6), resolved (brackets of the midpoint rule far narrower), then falls
    for (id, step) in [("fig03-tri-shrinks", 0.016), ("fig06-bi-tri-shrink", 0.022)] {
        let d = &v.get(id).unwrap().decision;
        assert_eq!(d.verdict, Verdict::Refuted, "{id}");
        let against = d.deciding(1)[0];
        let Uncertainty::Bracket { lo, hi } = against.value.uncertainty else {
            panic!("{id}: an area's change is a bracket");
        };
        assert!(
            (against.value.value - step).abs() < 2e-3,
            "{}",
            against.what
        );
        assert!(lo > 0.0 && hi - lo < 1e-3, "{}", against.what);
    }
    for id in ["fig06-mono-grows", "fig10-trimodal-shrinks"] {
        assert_eq!(
            v.get(id).unwrap().decision.verdict,
            Verdict::Confirmed,
            "{id}"
        );
    }
    assert_eq!(
        v.get("fig12-omega-mu0-r").unwrap().decision.verdict,
        Verdict::Refuted
    );
    // Fig. 7: the A01 well's floor below U_eff(0) rises toward it as r (λ) falls, every step
    let inner = v.get("fig07-inner-well").unwrap();
    assert_eq!(inner.decision.verdict, Verdict::Confirmed);
    assert_eq!(inner.decision.tally[1], 0);
    // ... and A01 vanishes just below the plotted r: the strongest evidence comes first
    let moves = &v.get("fig07-wells-move").unwrap().decision;
    assert_eq!(moves.verdict, Verdict::Refuted);
    assert!(
        moves.checks[0].what.contains("vanishes"),
        "{}",
        moves.checks[0].what
    );
    assert_eq!(moves.checks[0].statistic_value, 1.0);
    // Fig. 2: the bi- and trirhythmic areas and L1–L3 over both panels
    assert_eq!(
        v.get("fig02-regions").unwrap().decision.verdict,
        Verdict::Confirmed
    );
    // Fig. 3: below the r where f′(0) = 0 (beyond the figure's range) no point is trirhythmic
    // and a birhythmic area remains
    let bi = &v.get("fig03-birhythmic").unwrap().decision;
    assert_eq!(bi.verdict, Verdict::Confirmed);
    assert!(
        bi.checks[0].what.contains("0.98676"),
        "{}",
        bi.checks[0].what
    );
    // Fig. 5: tri → bi → mono in panels a–c; panel d (μ0 = 0.3) stays birhythmic to r = 0
    let seq = &v.get("fig05-tri-bi-mono").unwrap().decision;
    assert_eq!(seq.verdict, Verdict::Refuted);
    assert_eq!(seq.tally, [3, 1, 0, 0]);
    assert!(seq.deciding(1)[0].what.contains("μ0 = 0.3"));
    // the abstract: some line of Fig. 12 where only λ, and one where only r, varies meets
    // one, two and three modes
    assert_eq!(
        v.get("abstract-lambda-r-alone").unwrap().decision.verdict,
        Verdict::Confirmed
    );
    // Fig. 8: τ is not printed, whatever the count
    assert!(matches!(
        v.get("fig08-four-barriers").unwrap().decision.verdict,
        Verdict::Undetermined { .. }
    ));
    // Fig. 5: the trirhythmic interval's length changes with μ0; its lower end sits at
    // (1 − r)/μ0 = π/2 in every panel where it lies inside the range (the rescaling)
    let interval = v.get("fig05-interval-mu0").unwrap();
    assert_eq!(interval.decision.verdict, Verdict::Confirmed);
    assert_eq!(interval.decision.rule, "dependence");
    assert!(
        interval.decision.checks[0].what.matches("= 1.5708").count() >= 3,
        "{}",
        interval.decision.checks[0].what
    );
    // Eq. 36–37 as printed: far from the exact P-bifurcation curves on every Fig. 10 and 12 panel
    for id in ["fig10-eq37-misprint", "fig12-eq37-misprint"] {
        let eq37 = v.get(id).unwrap();
        assert_eq!(eq37.decision.verdict, Verdict::Refuted, "{id}");
        assert_eq!(eq37.decision.checks.len(), 4, "{id}");
        assert!(eq37
            .decision
            .checks
            .iter()
            .all(|c| c.statistic_value > 2.0 * CURVE_TOL));
    }
    // every theory claim is judged, none of the Monte Carlo ones
    assert!(v.get("fig13a-agreement").is_none());
    assert!(v.not_judged.iter().any(|id| id == "fig13a-agreement"));
    // the verdicts are data: they read back from JSON
    let text = serde_json::to_string(&v).unwrap();
    let back: trirhythm_paper::verdict::claims::Verdicts = serde_json::from_str(&text).unwrap();
    assert_eq!(back, v);
}

#[test]
fn editing_the_fig04_roots_flips_the_verdict() {
    use trirhythm_paper::fig04_drift::Fig04;
    use trirhythm_paper::Figure;
    let mut fig = Fig04::compute(&QUICK, &Silent).unwrap();
    let figs = |f: Fig04| Figures {
        fig04: Some(f),
        ..Default::default()
    };
    let before = judge(&figs(Fig04::compute(&QUICK, &Silent).unwrap()));
    assert_eq!(
        before.get("fig04-roots").unwrap().decision.verdict,
        Verdict::Refuted
    );
    // give each panel the number of roots the paper's text says
    for (p, n) in fig.panels.iter_mut().zip(FIG04_CLAIMED_ROOTS) {
        p.cycles = (0..n)
            .map(|k| Cycle {
                amplitude: 1.0 + k as f64,
                stable: k % 2 == 0,
                fold: false,
            })
            .collect();
    }
    let after = judge(&figs(fig));
    assert_eq!(
        after.get("fig04-roots").unwrap().decision.verdict,
        Verdict::Confirmed
    );
    // only the claims of the figures given are judged
    assert_eq!(after.claims.len(), 1);
}

/// The verdict of claim `id` on `figs`.
fn verdict_of(figs: &Figures, id: &str) -> Verdict {
    judge(figs).get(id).unwrap().decision.verdict.clone()
}

#[test]
fn editing_the_theory_figures_flips_the_issue_34_rows() {
    let theory = |numbers: &[u32]| Figures::compute(&QUICK, &Silent, numbers).unwrap();
    // Fig. 5 without panel d (μ0 = 0.3, birhythmic down to r = 0): tri → bi → mono everywhere
    let mut f5 = theory(&[5]);
    assert_eq!(verdict_of(&f5, "fig05-tri-bi-mono"), Verdict::Refuted);
    f5.fig05.as_mut().unwrap().panels.retain(|p| p.0 != "d");
    assert_eq!(verdict_of(&f5, "fig05-tri-bi-mono"), Verdict::Confirmed);
    // Fig. 3 whose smallest-r panel has no trirhythmic point: the zone is not there to vanish
    let mut f3 = theory(&[3]);
    assert_eq!(verdict_of(&f3, "fig03-birhythmic"), Verdict::Confirmed);
    let last = f3.fig03.as_mut().unwrap().0.panels.last_mut().unwrap();
    last.counts.iter_mut().for_each(|c| *c = (*c).min(2));
    assert_eq!(verdict_of(&f3, "fig03-birhythmic"), Verdict::Refuted);
    // ... and one whose window holds no birhythmic point below the Hopf r (a window at the
    // largest γ0, δ0, monorhythmic there)
    let mut f3 = theory(&[3]);
    let last = f3.fig03.as_mut().unwrap().0.panels.last_mut().unwrap();
    last.x.grid.start = 1.1e-4;
    last.y.grid.start = 5.5e-7;
    assert_eq!(verdict_of(&f3, "fig03-birhythmic"), Verdict::Refuted);
    // Fig. 2 without the panel (i) lines: L3 is missing
    let mut f2 = theory(&[2]);
    assert_eq!(verdict_of(&f2, "fig02-regions"), Verdict::Confirmed);
    f2.fig02.as_mut().unwrap().0.panels[0].fold_names.clear();
    assert_eq!(verdict_of(&f2, "fig02-regions"), Verdict::Refuted);
    // Fig. 7 read in the opposite order (r, λ rising): the A01 floor deepens
    let mut f7 = theory(&[7]);
    assert_eq!(verdict_of(&f7, "fig07-inner-well"), Verdict::Confirmed);
    for p in &mut f7.fig07.as_mut().unwrap().panels {
        p.curves.reverse();
        p.params.reverse();
    }
    assert_eq!(verdict_of(&f7, "fig07-inner-well"), Verdict::Refuted);
    // Fig. 12 with no trimodal point and without Fig. 10: λ or r alone never gives three
    let mut f12 = theory(&[12]);
    assert_eq!(
        verdict_of(&f12, "abstract-lambda-r-alone"),
        Verdict::Confirmed
    );
    for p in &mut f12.fig12.as_mut().unwrap().0.panels {
        p.counts.iter_mut().for_each(|c| *c = (*c).min(2));
    }
    assert_eq!(
        verdict_of(&f12, "abstract-lambda-r-alone"),
        Verdict::Refuted
    );
    // Fig. 6 with its panels in the opposite order: the zones grow as λ drops
    let mut f6 = theory(&[6]);
    f6.fig06.as_mut().unwrap().0.panels.reverse();
    assert_eq!(verdict_of(&f6, "fig06-mono-grows"), Verdict::Refuted);
}

/// Fig. 11 and Fig. 16 data made by hand (their figures simulate): the rows that read them.
#[test]
fn fig11_and_the_hopf_point_from_edited_data() {
    use trirhythm_paper::fig11_amplitude_lambda::Fig11;
    use trirhythm_paper::fig16_oscillation_regions::Fig16;
    let settled = |rows: &[(f64, f64, f64)]| {
        serde_json::json!(rows
            .iter()
            .map(|&(lambda, u0, amplitude)| serde_json::json!({
                "lambda": lambda, "u0": u0, "amplitude": amplitude, "spread": 1e-4
            }))
            .collect::<Vec<_>>())
    };
    let fig11 = |rows: &[(f64, f64, f64)]| -> Fig11 {
        serde_json::from_value(serde_json::json!({
            "caption": {"title": "Fig. 11", "lines": []},
            "notes": [],
            "branches": {"key": "lambda", "start": 0.9, "stop": 1.0, "what": "rhythmicity",
                         "branches": [], "folds": [], "hopf": []},
            "settled": settled(rows),
            "panels": []
        }))
        .unwrap()
    };
    let figs11 = |f: Fig11| Figures {
        fig11: Some(f),
        ..Default::default()
    };
    // at λ = 0.97 the theory has the rest state and a cycle at 12.75: the simulation's rest and
    // A = 12.8 agree within 5 %
    let agree = figs11(fig11(&[(0.97, 0.5, 0.0), (0.97, 14.0, 12.8)]));
    assert_eq!(verdict_of(&agree, "fig11a-amplitudes"), Verdict::Confirmed);
    // at λ = 0.93 the simulation's outer cycle A = 12.48 is one the theory lacks (fold ≈ 0.939)
    let lacks = figs11(fig11(&[(0.93, 0.5, 0.0), (0.93, 14.0, 12.48)]));
    let d = judge(&lacks)
        .get("fig11a-amplitudes")
        .unwrap()
        .decision
        .clone();
    assert_eq!(d.verdict, Verdict::Refuted);
    assert!(d.checks[0].what.contains("rest only") && d.checks[0].statistic_value == 1.0);
    // the theory never shows three peaks a reader sees over λ ∈ [0.9, 1]
    let peaks = judge(&agree).get("fig11b-peaks").unwrap().decision.clone();
    assert_eq!(peaks.verdict, Verdict::Refuted);
    assert!(peaks.checks.iter().any(|c| c.outcome == Outcome::Against
        && c.what
            .contains("3 peaks (none; exact modes, roots of m1: first at")));
    // Fig. 16 (a) at λ = 0.9: the averaged boundary μ0 = 0.16276; a point moved off it (μ0
    // halved, where the rest state is stable on both sides) has no cycle born there
    let fig16 = |mu0: f64| -> Fig16 {
        serde_json::from_value(serde_json::json!({
            "caption": {"title": "Fig. 16", "lines": []},
            "notes": [],
            "panels": [{"caption": "(a)", "label": "a", "x_desc": "λ", "x_range": [0.9, 1.0],
                        "y_range": [0.0001, 0.25],
                        "curves": [{"label": "averaging (paper)", "method": "averaging",
                                    "member": null, "rest_below": false,
                                    "points": [{"x": 0.9, "side": "boundary", "y": mu0,
                                                "y_lo": mu0, "y_hi": mu0,
                                                "oscillates_above": true,
                                                "simulations": 0, "unclear": 0}]}]}]
        }))
        .unwrap()
    };
    let figs16 = |f: Fig16| Figures {
        fig16: Some(f),
        ..Default::default()
    };
    assert_eq!(
        verdict_of(
            &figs16(fig16(0.16276135216547138)),
            "sec5-supercritical-hopf"
        ),
        Verdict::Confirmed
    );
    assert_eq!(
        verdict_of(&figs16(fig16(0.08)), "sec5-supercritical-hopf"),
        Verdict::Refuted
    );
}

#[test]
fn visible_peaks_count_what_a_reader_sees_on_the_curve() {
    use trirhythm_paper::verdict::claims::visible_peaks;
    // three Gaussian bumps of heights 1, 0.5, 0.2 with deep dips between: three peaks
    let bumps = |h: [f64; 3]| {
        move |a: f64| {
            let g = |m: f64, k: f64| k * (-(a - m) * (a - m) / 0.5).exp();
            (g(2.0, h[0]) + g(6.0, h[1]) + g(10.0, h[2])).ln()
        }
    };
    let modes = [2.0, 6.0, 10.0];
    let antimodes = [4.0, 8.0];
    assert_eq!(visible_peaks(&modes, &antimodes, bumps([1.0, 0.5, 0.2])), 3);
    // a mode at 10⁻³ of the largest is below the floor: not seen
    assert_eq!(
        visible_peaks(&modes, &antimodes, bumps([1.0, 0.5, 1e-3])),
        2
    );
    // a shoulder: a maximum whose dip toward the higher one stays above half its height
    let shoulder = |a: f64| {
        if a < 3.0 {
            0.9f64.ln()
        } else if a < 5.0 {
            0.8f64.ln()
        } else {
            0.0
        }
    };
    assert_eq!(visible_peaks(&[2.0, 6.0], &[4.0], shoulder), 1);
}

#[test]
#[ignore = "extended: Monte Carlo and Lyapunov figures (minutes in quick mode)"]
fn every_claim_in_quick_mode() {
    let figs = Figures::compute(&QUICK, &Silent, &JUDGED_FIGURES).unwrap();
    let v = judge(&figs);
    for c in &v.claims {
        eprintln!(
            "{} → {} {:?}",
            c.claim.id,
            c.decision.verdict.tag(),
            match &c.decision.verdict {
                Verdict::Undetermined { why } => why.chars().take(300).collect::<String>(),
                _ => String::new(),
            }
        );
        for ch in c.decision.checks.iter().take(8) {
            eprintln!(
                "    {}: {} = {} vs {} → {:?}",
                ch.what, ch.statistic, ch.statistic_value, ch.threshold, ch.outcome
            );
        }
    }
    assert!(v.not_judged.is_empty());
    let (c, r, u) = v.counts();
    assert_eq!(c + r + u, v.claims.len());
}

/// Saved figure data (`figNN.json` as `trirhythm figure N --data` writes it: the figure's data
/// under `data`, with `quick` and `variant`) in the folder named by `TRIRHYTHM_VERDICT_DATA`,
/// judged and printed: the verdicts of full-quality runs without recomputing them.
#[test]
#[ignore = "extended: needs saved figure data (TRIRHYTHM_VERDICT_DATA=folder)"]
fn verdicts_of_saved_figure_data() {
    use serde::de::DeserializeOwned;
    let Ok(dir) = std::env::var("TRIRHYTHM_VERDICT_DATA") else {
        return;
    };
    let mut quick = None;
    fn load<F: DeserializeOwned>(dir: &str, n: u32, quick: &mut Option<bool>) -> Option<F> {
        let text = std::fs::read_to_string(format!("{dir}/fig{n:02}.json")).ok()?;
        let v: serde_json::Value = serde_json::from_str(&text).unwrap();
        let q = v["quick"].as_bool().unwrap_or(false);
        assert!(quick.is_none_or(|x| x == q), "quick and full data mixed");
        *quick = Some(q);
        Some(serde_json::from_value(v["data"].clone()).unwrap())
    }
    let q = &mut quick;
    let mut figs = Figures {
        fig01: load(&dir, 1, q),
        fig02: load(&dir, 2, q),
        fig03: load(&dir, 3, q),
        fig04: load(&dir, 4, q),
        fig05: load(&dir, 5, q),
        fig06: load(&dir, 6, q),
        fig07: load(&dir, 7, q),
        fig08: load(&dir, 8, q),
        fig09: load(&dir, 9, q),
        fig10: load(&dir, 10, q),
        fig11: load(&dir, 11, q),
        fig12: load(&dir, 12, q),
        fig13: load(&dir, 13, q),
        fig16: load(&dir, 16, q),
        fig17: load(&dir, 17, q),
        fig18: load(&dir, 18, q),
        fig19: load(&dir, 19, q),
        ..Default::default()
    };
    figs.options.quick = quick.unwrap_or(false);
    let v = judge(&figs);
    println!("{}", serde_json::to_string_pretty(&v.claims).unwrap());
}

// ---- the Lyapunov claims per start ----

fn lle_panel(
    caption: &str,
    curves: &[(trirhythm_paper::lle::StartKind, &[f64])],
) -> trirhythm_paper::lle::Panel {
    use trirhythm_paper::lle::{Curve, Flag, Panel, Point};
    let ds = [0.001, 0.01, 0.1, 1.0];
    Panel {
        caption: caption.into(),
        x_key: "D".into(),
        x_desc: String::new(),
        y_desc: String::new(),
        y_key: "lle".into(),
        curves: curves
            .iter()
            .map(|&(start, ys)| Curve {
                label: format!("μ0 = 0.01, {}", start.name()),
                value: 0.01,
                start,
                u0: 1.0,
                dt: 0.005,
                attractor: String::new(),
                regime: None,
                points: ds
                    .iter()
                    .zip(ys)
                    .map(|(&x, &y)| Point {
                        x,
                        y,
                        lo: y - 0.002,
                        hi: y + 0.002,
                        se: 0.002,
                        n: 8,
                        flag: Flag::Value,
                        sign: trirhythm_paper::verdict::rules::PointSign::Undefined,
                        merged: 0,
                        unmerged: y,
                        unmerged_se: 0.002,
                    })
                    .collect(),
            })
            .collect(),
        verdicts: vec![],
    }
}

#[test]
fn a_lyapunov_claim_is_decided_per_start_and_says_so() {
    use trirhythm_paper::fig17_lle_noise::Fig17;
    use trirhythm_paper::lle::{DtCheck, LleAgainstNoise, StartKind};
    use trirhythm_paper::notes::Caption;
    let rising: &[f64] = &[-0.05, -0.04, 0.05, 0.06];
    let falling: &[f64] = &[0.05, 0.05, -0.05, -0.05];
    // (a): rising from the rest basin, falling from the outer cycle; (b): rising from rest,
    // no outer cycle (a curve without points)
    let a = lle_panel(
        "(a) τ = 0.06",
        &[(StartKind::Rest, rising), (StartKind::Cycle, falling)],
    );
    let b = lle_panel(
        "(b) μ0 = 0.001",
        &[(StartKind::Rest, rising), (StartKind::Cycle, &[])],
    );
    let data = LleAgainstNoise {
        caption: Caption {
            title: String::new(),
            lines: vec![],
        },
        notes: vec![],
        panels: vec![a, b],
        dt_check: DtCheck {
            what: String::new(),
            panel: "a".into(),
            dt_rule: 0.005,
            points: vec![],
        },
    };
    let figs = Figures {
        fig17: Some(Fig17(data)),
        ..Default::default()
    };
    let v = judge(&figs);
    let find = |id: &str| {
        v.claims
            .iter()
            .find(|c| c.claim.id == id)
            .unwrap()
            .decision
            .clone()
    };
    let a = find("fig17a-lle-sign-change");
    assert_eq!(tag(&a), "refuted");
    assert!(
        a.statistic
            .contains("per start: in the rest regime (the start's noise-free path comes to rest on the wall): confirmed; in the cycle regime"),
        "{}",
        a.statistic
    );
    assert!(a.statistic.ends_with("refuted"), "{}", a.statistic);
    let b = find("fig17b-lle-sign-change");
    assert!(
        matches!(b.verdict, Verdict::Undetermined { ref why } if why.contains("no outer stable cycle (averaged theory) for μ0 = 0.01, cycle")),
        "{b:?}"
    );
}

// ---- the Lyapunov claims by regime ----

/// How a synthetic curve's exponents run against D (standard error 0.001, 16 realisations).
#[derive(Clone, Copy)]
enum Shape {
    /// Not chaotic up to D = 0.01, chaotic from 0.1: D_c ∈ (0.01, 0.1).
    Located,
    /// Not chaotic up to D = 2.
    Regular,
    /// Not chaotic anywhere, falling from −0.005 to −0.04 over D = 3 … 30: no D_c.
    Falling,
    /// The rest regime, 0.08 at every D from 1e-6 to 1e-2: D_c = 0.
    RestFlat,
    /// The rest regime, chaotic but rising by 0.02 per decade: not flat.
    RestRising,
}

/// A curve of value `v` in `start`'s regime whose points run as `shape` (the verdicts apply
/// the regime rules to the points afresh; the stored decision only carries the margin).
fn regime_curve(
    v: f64,
    start: trirhythm_paper::lle::StartKind,
    shape: Shape,
) -> trirhythm_paper::lle::Curve {
    use trirhythm_paper::lle::{Curve, CurveRegime, Flag, Point};
    use trirhythm_paper::verdict::rules::{Bracket, PointSign};
    let pairs: Vec<(f64, f64)> = match shape {
        Shape::Located => vec![(0.001, -0.01), (0.01, -0.01), (0.1, 0.05), (1.0, 0.05)],
        Shape::Regular => vec![(0.001, -0.01), (0.1, -0.01), (2.0, -0.01)],
        Shape::Falling => vec![
            (0.001, -0.01),
            (0.1, -0.01),
            (3.0, -0.005),
            (10.0, -0.02),
            (30.0, -0.04),
        ],
        Shape::RestFlat => [1e-6, 1e-5, 1e-4, 1e-3, 1e-2].map(|d| (d, 0.08)).to_vec(),
        Shape::RestRising => [1e-6, 1e-5, 1e-4, 1e-3, 1e-2]
            .iter()
            .enumerate()
            .map(|(k, &d)| (d, 0.02 + 0.02 * k as f64))
            .collect(),
    };
    let points = pairs
        .iter()
        .map(|&(x, y)| Point {
            x,
            y,
            lo: y - 0.001,
            hi: y + 0.001,
            se: 0.001,
            n: 16,
            flag: Flag::Value,
            sign: PointSign::Undefined,
            merged: 0,
            unmerged: y,
            unmerged_se: 0.001,
        })
        .collect();
    Curve {
        label: format!("r = {v}, {}", start.name()),
        value: v,
        start,
        u0: 1.0,
        dt: 0.0025,
        attractor: if start == trirhythm_paper::lle::StartKind::Rest {
            "rest".into()
        } else {
            "outer cycle (A = 12.8)".into()
        },
        points,
        regime: Some(CurveRegime {
            margin: 1.0 / 1500.0,
            calls: vec![],
            bracket: Bracket::Undecided,
            strong: None,
            rest: None,
            coefficient: f64::NAN,
            coefficient_uncertainty: f64::NAN,
            prediction_note: String::new(),
            agrees: vec![],
            escape: vec![],
        }),
    }
}

fn judge_fig18b(curves: Vec<trirhythm_paper::lle::Curve>) -> Decision {
    use trirhythm_paper::fig18_lle_noise_fractional::Fig18;
    use trirhythm_paper::lle::{DtCheck, LleAgainstNoise, Panel};
    use trirhythm_paper::notes::Caption;
    let panel = |curves| Panel {
        caption: "(b) λ = 0.998".into(),
        x_key: "D".into(),
        x_desc: String::new(),
        y_desc: String::new(),
        y_key: "lle".into(),
        curves,
        verdicts: vec![],
    };
    let data = LleAgainstNoise {
        caption: Caption {
            title: String::new(),
            lines: vec![],
        },
        notes: vec![],
        panels: vec![panel(vec![]), panel(curves)],
        dt_check: DtCheck {
            what: String::new(),
            panel: "b".into(),
            dt_rule: 0.0025,
            points: vec![],
        },
    };
    let figs = Figures {
        fig18: Some(Fig18(data)),
        ..Default::default()
    };
    judge(&figs)
        .claims
        .into_iter()
        .find(|c| c.claim.id == "fig18b-lle-sign-change")
        .unwrap()
        .decision
}

#[test]
fn a_lyapunov_claim_by_regime_is_decided_per_value_of_the_parameter() {
    use trirhythm_paper::lle::StartKind::{Cycle, Rest};
    // r = 0.998: rest (D_c = 0) and a cycle with a located transition: for (the paper may have
    // started on the cycle); r = 0.9: a located transition: for
    let d = judge_fig18b(vec![
        regime_curve(0.998, Rest, Shape::RestFlat),
        regime_curve(0.998, Cycle, Shape::Located),
        regime_curve(0.9, Cycle, Shape::Located),
    ]);
    assert_eq!(tag(&d), "confirmed", "{d:?}");
    assert_eq!(d.rule, "regime");
    // r = 0.8 has only the rest regime, chaotic as D → 0 and flat: against
    let d = judge_fig18b(vec![
        regime_curve(0.998, Cycle, Shape::Located),
        regime_curve(0.8, Rest, Shape::RestFlat),
    ]);
    assert_eq!(tag(&d), "refuted", "{d:?}");
    // the rest regime chaotic but not flat: neither
    let d = judge_fig18b(vec![
        regime_curve(0.998, Cycle, Shape::Located),
        regime_curve(0.8, Rest, Shape::RestRising),
    ]);
    assert!(
        matches!(d.verdict, Verdict::Undetermined { ref why } if why.contains("r = 0.8")),
        "{d:?}"
    );
    // a cycle not chaotic up to the largest D: no located transition
    let d = judge_fig18b(vec![regime_curve(0.998, Cycle, Shape::Regular)]);
    assert!(
        matches!(d.verdict, Verdict::Undetermined { ref why } if why.contains("D_c > 2")),
        "{d:?}"
    );
    // a cycle never chaotic and falling at strong noise, beside the rest regime with D_c = 0:
    // no regime changes sign: against
    let d = judge_fig18b(vec![
        regime_curve(0.998, Cycle, Shape::Located),
        regime_curve(0.9, Rest, Shape::RestFlat),
        regime_curve(0.9, Cycle, Shape::Falling),
    ]);
    assert_eq!(tag(&d), "refuted", "{d:?}");
    // the falling cycle alone: against as well
    let d = judge_fig18b(vec![regime_curve(0.998, Cycle, Shape::Falling)]);
    assert_eq!(tag(&d), "refuted", "{d:?}");
}

/// One source of truth: a claim is decided by its own figure's data alone, so that the verdict
/// line drawn in the figure (`judge_figure`) and the report's (`judge` over every figure) are
/// the same decision. Checked on the theory figures in quick mode: each figure judged alone
/// gives exactly the claims, verdicts and numbers that the judgement of all of them gives.
#[test]
fn every_claim_rests_on_its_own_figure_alone() {
    let all = judge(&Figures::compute(&QUICK, &Silent, &THEORY_FIGURES).unwrap());
    for n in THEORY_FIGURES {
        let one = judge(&Figures::compute(&QUICK, &Silent, &[n]).unwrap());
        for c in &one.claims {
            assert_eq!(c.claim.figure, n, "{} is judged from Fig. {n}", c.claim.id);
            assert_eq!(Some(c), all.get(&c.claim.id), "{}", c.claim.id);
        }
        for c in all.claims.iter().filter(|c| c.claim.figure == n) {
            assert!(
                one.get(&c.claim.id).is_some(),
                "{}: not judged from Fig. {n} alone",
                c.claim.id
            );
        }
    }
}
