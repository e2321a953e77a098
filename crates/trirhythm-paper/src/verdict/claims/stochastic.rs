//! The simulated claims (Figs 11, 13, 16–19): Monte Carlo and Lyapunov numbers with standard
//! errors and the stationarity of their ensembles, boundaries with brackets, decided by the
//! agreement, count, sign-change and trend rules.

use super::super::rules::{
    agreement, count, dependence, separate_maxima, separate_maxima_significant, sign_change, trend,
    Bracket, Comparison, Count, CountSource, Direction, LleCurve, Located, Series, WeightingRange,
    Weightings, AGREEMENT_K, CLOSENESS_REL_TOL, PEAK_DIP, PEAK_FLOOR, PEAK_SE_K, WINDOW_MASS_TOL,
};
use super::super::{all_of, Decision, Measured, Outcome, Verdict};
use crate::boundary::Panel as BoundaryPanel;
use crate::fig13_pdf_restitution::Fig13;
use crate::fig14_joint_pdf::Fig14;
use crate::fig15_oscillation_boundaries::{Fig15, OMEGAS as FIG15_OMEGAS};
use crate::fig19_critical_noise::Fig19;
use crate::lle::{Panel as LlePanel, StartKind};
use crate::montecarlo::{AmplitudePanel, McRun};
use trirhythm::analysis::oscillation::Side;

/// How an ensemble's numbers were estimated, for the verdict's words: the well decomposition,
/// or the direct paths with the decomposition's refusal where it was tried.
fn estimator_of(r: &McRun) -> String {
    match &r.wells {
        Some(w) if r.estimator == "wells" => format!(
            " (well decomposition: weights {})",
            w.weights
                .iter()
                .map(|x| crate::notes::sig(*x, 3))
                .collect::<Vec<_>>()
                .join(", ")
        ),
        Some(w) if w.conditional_valid && !w.bounds.is_empty() => {
            " (well decomposition: valid conditional densities, weights undetermined)".into()
        }
        Some(w) if w.conditional_drifting && !w.bounds.is_empty() => {
            " (well decomposition: weights undetermined, a well's conditional densities drift)"
                .into()
        }
        Some(_) => " (direct; the well decomposition refused: the figure's notes say why)".into(),
        None => String::new(),
    }
}

/// H over every weighting of the wells, where the run's well decomposition has valid
/// conditional densities but undetermined weights, or conditional densities that drift
/// between the window's halves (then each half's range too).
fn weightings_of(r: &McRun, variant: &str) -> Option<Weightings> {
    let w = r
        .wells
        .as_ref()
        .filter(|w| (w.conditional_valid || w.conditional_drifting) && !w.valid)?;
    let range = |b: &crate::montecarlo::Bounds| WeightingRange {
        h_min: b.h_min,
        h_min_se: b.h_min_stderr,
        h_max: b.h_max,
        h_max_se: b.h_max_stderr,
    };
    let b = w.bounds.iter().find(|b| b.variant == variant)?;
    let halves = if w.conditional_drifting {
        // drifting statistics without each half's range decide nothing over the weightings
        let half = |h: usize| {
            w.bounds_halves
                .get(h)?
                .iter()
                .find(|b| b.variant == variant)
                .map(range)
        };
        Some([half(0)?, half(1)?])
    } else {
        None
    };
    let ess: Vec<f64> = w.conditional.iter().map(|c| c.ess).collect();
    Some(Weightings {
        h_min: b.h_min,
        h_min_se: b.h_min_stderr,
        h_max: b.h_max,
        h_max_se: b.h_max_stderr,
        ess_min: ess.iter().copied().fold(f64::INFINITY, f64::min),
        ess_sum: ess.iter().sum(),
        replicas: w.replicas,
        halves,
    })
}

pub(super) fn agreement_of(panels: &[AmplitudePanel], system: &str, variant: &str) -> Decision {
    let mut items = Vec::new();
    for p in panels {
        for r in p.runs.iter().filter(|r| r.system == system) {
            if let Some(d) = r.distances.iter().find(|d| d.variant == variant) {
                items.push(Comparison {
                    what: format!(
                        "{}, MC of {}{}, {} formulas",
                        p.caption,
                        r.system,
                        estimator_of(r),
                        variant
                    ),
                    hellinger: d.hellinger,
                    se: d.hellinger_stderr,
                    bins: r.edges.len().saturating_sub(1),
                    ess: r.ess,
                    stationary: r.stationary,
                    r_hat: r.r_hat,
                    weightings: weightings_of(r, variant),
                });
            }
        }
    }
    agreement(&items)
}

/// The peak counts the paper's text gives for Fig. 13 (a1)–(a4).
pub const FIG13_CLAIMED_PEAKS: [u32; 4] = [3, 2, 2, 1];

pub(super) fn fig13_peaks(f: &Fig13) -> Decision {
    let claimed: Vec<(&AmplitudePanel, u32)> = f.panels.iter().zip(FIG13_CLAIMED_PEAKS).collect();
    peak_counts(&claimed)
}

/// The peak count the text gives for Fig. 13 (b1)–(b4): "the three peaks endure" at μ0 = 0.2.
pub const FIG13B_CLAIMED_PEAKS: u32 = 3;

pub(super) fn fig13b_peaks(f: &Fig13) -> Decision {
    let claimed: Vec<(&AmplitudePanel, u32)> = f
        .panels
        .iter()
        .skip(4)
        .map(|p| (p, FIG13B_CLAIMED_PEAKS))
        .collect();
    peak_counts(&claimed)
}

/// Local maxima of a drawn theory curve (its analytic modes, to the curve's grid).
fn curve_maxima(d: &[f64]) -> usize {
    d.windows(3).filter(|w| w[1] > w[0] && w[1] >= w[2]).count()
}

/// Peaks of P(A) per panel against the text's counts, by the prominence rule of
/// `analysis::versus` (a local maximum standing more than 1 % of the largest density above the
/// way to a higher one; for a histogram also three standard errors): first the averaged
/// theory's P(A) as printed, binned as the histogram (exact: the peaks a reader of the curve
/// sees), then Monte Carlo of Eq. 1 (stationary ensembles only). The theory's checks come
/// first: they are exact and decide whatever the ensembles' stationarity.
fn peak_counts(panels: &[(&AmplitudePanel, u32)]) -> Decision {
    let mut theory = Vec::new();
    let mut mc = Vec::new();
    for &(p, claimed) in panels {
        let Some(r) = p.runs.iter().find(|r| r.system == "Eq. 1") else {
            continue;
        };
        if let Some(d) = r.distances.iter().find(|d| d.variant == "paper") {
            let analytic = p
                .theory
                .iter()
                .find(|t| t.0 == "paper")
                .map(|t| curve_maxima(&t.2));
            theory.push(Count {
                what: format!(
                    "{}: visible peaks of P(A) as printed{}",
                    p.caption,
                    analytic
                        .map(|n| format!(
                            " (analytic maxima: {n}; those less prominent than 1 % of the largest density are not visible)"
                        ))
                        .unwrap_or_default()
                ),
                claimed,
                computed: d.modes_theory as u32,
                source: CountSource::Exact,
            });
        }
        if let Some(d) = r.distances.first() {
            mc.push(Count {
                what: format!("{}: peaks of the histogram{}", p.caption, estimator_of(r)),
                claimed,
                computed: d.modes_mc as u32,
                source: CountSource::Ensemble {
                    stationary: r.stationary,
                    r_hat: r.r_hat,
                },
            });
        }
    }
    all_of(
        "count",
        vec![
            ("averaged theory (Eq. 27)".into(), count(&theory)),
            ("Eq. 1 (Monte Carlo)".into(), count(&mc)),
        ],
    )
}

/// A claim on an LLE panel decided per start ([`StartKind`]) and combined with
/// [`all_of`]: refuted when one start refutes it, confirmed when both confirm, else
/// undetermined with each start's reason (a start without an outer cycle on some curve says so).
fn per_start(p: &LlePanel, rule: &str, decide: impl Fn(&[LleCurve]) -> Decision) -> Decision {
    let parts = StartKind::BOTH
        .iter()
        .map(|&start| {
            let curves = p.lle_curves(start);
            let mut d = decide(&curves);
            let missing = p.without_cycle(start);
            if !missing.is_empty() && d.verdict != Verdict::Refuted {
                d.verdict = Verdict::undetermined(format!(
                    "{}no outer stable cycle (averaged theory) for {}",
                    match &d.verdict {
                        Verdict::Undetermined { why } => format!("{why}; "),
                        _ => String::new(),
                    },
                    missing.join(", ")
                ));
            }
            (start.words().to_string(), d)
        })
        .collect();
    per_start_all_of(rule, parts)
}

/// [`all_of`] over the starts, its statistic followed by each start's own verdict ("per start:
/// from the rest basin …: refuted; from the outer cycle …: undetermined (why)").
fn per_start_all_of(rule: &str, parts: Vec<(String, Decision)>) -> Decision {
    let each: Vec<String> = parts
        .iter()
        .map(|(name, d)| match &d.verdict {
            Verdict::Undetermined { why } => format!("{name}: undetermined ({why})"),
            v => format!("{name}: {}", v.tag()),
        })
        .collect();
    let mut d = all_of(rule, parts);
    d.statistic = format!("{}; per start: {}", d.statistic, each.join("; "));
    d
}

/// "When the noise level reaches D_c, the LLE turns positive", by the regime rules
/// (`verdict::rules::regime`, docs/verdicts.md): one check per curve of the paper, that is per
/// value of the panel's parameter. A value is **for** the sentence when one of its regimes has
/// a located transition D_c ∈ (D1, D2) (not chaotic at D1, chaotic at D2); **against** when
/// none of its regimes changes sign: each has D_c = 0 (the rest regime chaotic as D → 0:
/// positive down to D = 10⁻⁶ and flat in log D) or no D_c at all (a cycle never chaotic, its
/// exponent falling at strong noise) — no transition, whatever start the paper used; otherwise
/// neither, with each curve's outcome. Refuted when a value is against, confirmed when every
/// value is for, else undetermined. Data without regimes (an earlier version) fall back to the
/// sign-change rule per start.
pub(super) fn lle_sign_change(p: &LlePanel) -> Decision {
    if p.curves.iter().any(|c| c.regime.is_none()) {
        return per_start(p, "sign_change", sign_change);
    }
    regime_sign_change(p)
}

fn regime_sign_change(p: &LlePanel) -> Decision {
    use super::super::rules::ALPHA;
    use super::super::{Check, Outcome};
    use crate::notes::{num, sig};
    let mut values: Vec<f64> = Vec::new();
    for c in &p.curves {
        if !values.contains(&c.value) {
            values.push(c.value);
        }
    }
    let mut checks = Vec::new();
    let mut open = Vec::new();
    let mut tests = 0;
    for v in values {
        let of: Vec<&crate::lle::Curve> = p.curves.iter().filter(|c| c.value == v).collect();
        let name = of[0]
            .label
            .split(',')
            .next()
            .unwrap_or("")
            .trim()
            .to_string();
        let mut words = Vec::new();
        let mut transition: Option<(f64, f64)> = None;
        let mut always = 0;
        let mut never = 0;
        let mut pooled = None;
        for c in &of {
            let r = &c.redecided().expect("checked");
            tests += r.calls.len();
            words.push(match r.escape_words() {
                Some(e) => format!("{}: {} ({e})", c.attractor, r.bracket.words()),
                None => format!("{}: {}", c.attractor, r.bracket.words()),
            });
            match r.bracket {
                Bracket::Located { lo, hi } => {
                    transition.get_or_insert((lo, hi));
                }
                Bracket::Never { .. } => never += 1,
                _ => {}
            }
            if let Some(rest) = &r.rest {
                pooled = Some((rest.pooled, rest.pooled_se));
                if rest.d_c_zero {
                    always += 1;
                }
            }
        }
        let (value, outcome, statistic, stat_value, threshold) = match (transition, pooled) {
            (Some((lo, hi)), _) => (
                Measured::bracket((lo * hi).sqrt(), lo, hi),
                Outcome::For,
                "smallest chaotic D".to_string(),
                hi,
                lo,
            ),
            (None, Some((m, se))) if always + never == of.len() && always > 0 => (
                Measured::with_se(m, se),
                Outcome::Against,
                "pooled exponent of the rest regime at D ≤ 0.01 (flat in log D: D_c = 0)"
                    .to_string(),
                m,
                of.iter()
                    .filter_map(|c| c.regime.as_ref().map(|r| r.margin))
                    .fold(0.0, f64::max),
            ),
            (None, _) if never == of.len() => (
                Measured::exact(f64::INFINITY),
                Outcome::Against,
                "no regime chaotic at any D (exponent falling with D at strong noise)".to_string(),
                f64::INFINITY,
                f64::NAN,
            ),
            _ => (
                Measured::exact(f64::NAN),
                Outcome::Neither,
                "no located transition".to_string(),
                f64::NAN,
                f64::NAN,
            ),
        };
        if outcome == Outcome::Neither {
            open.push(format!("{name}: {}", words.join("; ")));
        }
        checks.push(Check {
            what: format!("{name}: {}", words.join("; ")),
            value,
            statistic,
            statistic_value: stat_value,
            threshold,
            outcome,
        });
    }
    let against = checks.iter().any(|c| c.outcome == Outcome::Against);
    let verdict = if against {
        Verdict::Refuted
    } else if open.is_empty() && !checks.is_empty() {
        Verdict::Confirmed
    } else {
        Verdict::undetermined(if open.is_empty() {
            "no curves".to_string()
        } else {
            format!("no located transition at {}", open.join(" | "))
        })
    };
    let margin = p
        .curves
        .iter()
        .filter_map(|c| c.regime.as_ref().map(|r| r.margin))
        .fold(0.0, f64::max);
    let statistic = format!(
        "per value of the parameter (a curve of the paper), the regimes of its noise-free system: calls against δ = 1/W = {} (one-sided Student's t on the unmerged realisations, Bonferroni over a curve's points at {}); for: a located D_c (not chaotic at D1, chaotic at D2); against: every regime has D_c = 0 (the rest regime: pooled exponent above δ and flat in log D over D = 1e-6 … 1e-2, where the equation near the wall is homogeneous)",
        sig(margin, 2),
        num(ALPHA)
    );
    Decision::new(verdict, "regime", statistic, tests, Some(ALPHA), checks)
}

/// "More impact loss makes chaos likelier": with regimes, the rest regime's D-independent
/// exponent (pooled over D ≤ 0.01, `verdict::rules::regime`) grows as r falls, one series over
/// the rest curves in the panel's order of r (falling); data without regimes fall back to the
/// LLE at each D per start.
pub(super) fn fig18_impact_loss(p: &LlePanel) -> Decision {
    if p.curves.iter().any(|c| c.regime.is_none()) {
        return per_start(p, "trend", impact_loss);
    }
    let points: Vec<(f64, Measured)> = p
        .curves
        .iter()
        .filter(|c| c.start == StartKind::Rest)
        .filter_map(|c| {
            let r = c.redecided()?.rest?;
            Some((c.value, Measured::with_se(r.pooled, r.pooled_se)))
        })
        .collect();
    trend(
        &[Series {
            label: "pooled exponent of the rest regime (D ≤ 0.01)".into(),
            x_name: "r".into(),
            points,
        }],
        Direction::Increases,
    )
}

/// More impact loss, larger LLE: one series over r per D, in the panel's order of r.
fn impact_loss(curves: &[LleCurve]) -> Decision {
    let r_of = |label: &str| {
        label
            .split(',')
            .next()
            .and_then(|s| s.rsplit("= ").next())
            .and_then(|s| s.trim().parse::<f64>().ok())
            .unwrap_or(f64::NAN)
    };
    let n = curves.iter().map(|c| c.points.len()).min().unwrap_or(0);
    let series: Vec<Series> = (0..n)
        .map(|k| Series {
            label: format!("LLE at D = {}", crate::notes::num(curves[0].points[k].d)),
            x_name: "r".into(),
            points: curves
                .iter()
                .map(|c| {
                    let q = c.points[k];
                    (r_of(&c.label), Measured::with_se_dof(q.lle, q.se, q.dof))
                })
                .collect(),
        })
        .collect();
    trend(&series, Direction::Increases)
}

/// The paper's trend of D_c on one panel of Fig. 19, per start: the located brackets of D_c
/// (geometric midpoint as value) against the parameter; a column without a located bracket
/// makes the start undetermined (with its reason) unless the located ones already refute.
pub(super) fn fig19_trend(f: &Fig19, panel: usize) -> Decision {
    let Some(m) = f.panels.get(panel) else {
        return trend(&[], Direction::Increases);
    };
    let direction = if m.claim == "decreases" {
        Direction::Decreases
    } else {
        Direction::Increases
    };
    let first_d = m
        .panel
        .curves
        .iter()
        .find_map(|c| c.points.first().map(|q| q.x))
        .unwrap_or(f64::NAN);
    // with regimes, D_c is the paper's: "the highest intensity of correlated noise that allows
    // for a stable cycle" — the cycle regime's; the rest regime (D_c = 0 where it is chaotic as
    // D → 0) has no cycle to lose and is shown in the figure, not judged here
    let by_regime = m.panel.curves.iter().any(|c| c.regime.is_some());
    let parts = StartKind::BOTH
        .iter()
        .filter(|&&start| !by_regime || start == StartKind::Cycle)
        .filter(|&&start| m.panel.curves.iter().any(|c| c.start == start))
        .map(|&start| {
            // one series per attractor of the regime (inner, outer, … cycle; rest)
            let mut series: Vec<(String, Vec<(f64, Measured)>)> = Vec::new();
            // the located brackets whose reference paths left the cycle's well
            let mut escaped: Vec<String> = Vec::new();
            // the columns without a located D_c, grouped by outcome: (words, values)
            let mut missing: Vec<(String, Vec<String>)> = Vec::new();
            for (c, l) in m.panel.curves.iter().zip(&m.located) {
                if c.start != start {
                    continue;
                }
                let name = c.attractor.split(" (").next().unwrap_or("").to_string();
                let mut push =
                    |x: f64, v: Measured| match series.iter_mut().find(|(n, _)| *n == name) {
                        Some((_, pts)) => pts.push((x, v)),
                        None => series.push((name.clone(), vec![(x, v)])),
                    };
                // the rest regime chaotic as D → 0 (flat in log D from 1e-6 to 1e-2): D_c = 0
                let decided = c.redecided();
                if decided
                    .as_ref()
                    .and_then(|r| r.rest.as_ref())
                    .is_some_and(|r| r.d_c_zero)
                {
                    push(c.value, Measured::exact(0.0));
                    continue;
                }
                // the regime rules' bracket: located, or one-sided where the curve is chaotic
                // from its smallest D ([0, D]) or not chaotic up to its largest ([D, ∞))
                if let Some(r) = &decided {
                    if let Some(e) = r.escape.iter().rev().find(|e| e.escape.escaped > 0) {
                        escaped.push(format!(
                            "{} = {} {name}: {} of {} at D = {} (median t = {})",
                            m.key,
                            crate::notes::num(c.value),
                            e.escape.escaped,
                            e.escape.paths,
                            crate::notes::num(e.d),
                            crate::notes::sig(e.escape.median_time, 3)
                        ));
                    }
                    match r.bracket {
                        Bracket::Located { lo, hi } => {
                            push(c.value, Measured::bracket((lo * hi).sqrt(), lo, hi))
                        }
                        Bracket::Below { d } => push(c.value, Measured::bracket(f64::NAN, 0.0, d)),
                        Bracket::Above { d } => {
                            push(c.value, Measured::bracket(f64::NAN, d, f64::INFINITY))
                        }
                        // no D_c at any D: infinite, above every located or one-sided one
                        Bracket::Never { .. } => push(
                            c.value,
                            Measured::bracket(f64::INFINITY, f64::INFINITY, f64::INFINITY),
                        ),
                        Bracket::Undecided => {
                            let why = r.bracket.words();
                            let v = crate::notes::num(c.value);
                            match missing.iter_mut().find(|(w, _)| *w == why) {
                                Some((_, vs)) => vs.push(v),
                                None => missing.push((why, vec![v])),
                            }
                        }
                    }
                    continue;
                }
                let why = match l {
                    Some(Located::Bracket { lo, hi }) => {
                        push(c.value, Measured::bracket((lo * hi).sqrt(), *lo, *hi));
                        continue;
                    }
                    Some(l) => l.kind_words(first_d),
                    None => "no outer stable cycle (averaged theory)".into(),
                };
                let v = crate::notes::num(c.value);
                match missing.iter_mut().find(|(w, _)| *w == why) {
                    Some((_, vs)) => vs.push(v),
                    None => missing.push((why, vec![v])),
                }
            }
            let missing_count: usize = missing.iter().map(|(_, v)| v.len()).sum();
            let missing: Vec<String> = missing
                .into_iter()
                .map(|(why, vs)| format!("{} = {}: {why}", m.key, vs.join(", ")))
                .collect();
            let located: usize = series.iter().map(|(_, p)| p.len()).sum();
            let finite = |m: &Measured| m.interval(0.0).0.is_finite();
            // an attractor with no D_c at any value says nothing about how D_c changes: its
            // series is named, not tested; when no attractor has a D_c anywhere, the claim has
            // nothing to change
            let (without, series): (Vec<_>, Vec<_>) = series
                .into_iter()
                .partition(|(_, p)| !p.iter().any(|(_, m)| finite(m)));
            if series.is_empty() && !without.is_empty() && missing.is_empty() {
                let names: Vec<String> = without.iter().map(|(n, _)| n.clone()).collect();
                let mut xs: Vec<f64> = without
                    .iter()
                    .flat_map(|(_, p)| p.iter().map(|(x, _)| *x))
                    .collect();
                xs.sort_by(f64::total_cmp);
                xs.dedup();
                let largest = m
                    .panel
                    .curves
                    .iter()
                    .filter(|c| c.start == start)
                    .flat_map(|c| c.points.iter().map(|q| q.x))
                    .fold(f64::NAN, f64::max);
                let what = format!(
                    "no D_c at any {} = {} on the {}: never chaotic up to D = {}, the exponent falling with D at strong noise",
                    m.key,
                    xs.iter().map(|&x| crate::notes::num(x)).collect::<Vec<_>>().join(", "),
                    names.join(", "),
                    crate::notes::num(largest)
                );
                let d = Decision::new(
                    Verdict::Refuted,
                    "trend",
                    format!("{what}: there is no critical noise to change with {}", m.key),
                    0,
                    None,
                    vec![super::super::Check {
                        what,
                        value: Measured::bracket(f64::INFINITY, f64::INFINITY, f64::INFINITY),
                        statistic: "D_c (none) against the largest D tried".into(),
                        statistic_value: f64::INFINITY,
                        threshold: largest,
                        outcome: super::super::Outcome::Against,
                    }],
                );
                return (start.words().to_string(), d);
            }
            let series: Vec<Series> = series
                .into_iter()
                .filter(|(_, p)| p.len() >= 2)
                .map(|(name, points)| Series {
                    label: format!("D_c ({name})"),
                    x_name: m.key.clone(),
                    points,
                })
                .collect();
            let mut d = trend(&series, direction);
            if !escaped.is_empty() {
                d.statistic.push_str(&format!(
                    "; brackets that depend on the window (reference paths left the cycle's well within it): {}",
                    escaped.join("; ")
                ));
            }
            if !without.is_empty() {
                let names: Vec<String> = without.iter().map(|(n, _)| n.clone()).collect();
                d.statistic.push_str(&format!(
                    "; not tested: the {} (no D_c at any {}: never chaotic)",
                    names.join(", "),
                    m.key
                ));
            }
            let d = if missing.is_empty() || d.verdict == Verdict::Refuted {
                d
            } else {
                Decision {
                    verdict: Verdict::undetermined(format!(
                        "D_c located at {located} of {} values; no located D_c at {}",
                        located + missing_count,
                        missing.join("; ")
                    )),
                    ..d
                }
            };
            (start.words().to_string(), d)
        })
        .collect();
    per_start_all_of("trend", parts)
}

/// The simulated oscillation boundary of each member of a family panel of Fig. 16, one series
/// per abscissa over the members in the panel's order: a boundary inside the searched μ0
/// interval is its bracket; rest over the whole interval, [top, ∞); oscillation, [0, bottom].
pub(super) fn fig16_family(p: &BoundaryPanel) -> Decision {
    let sims: Vec<(&str, &[trirhythm::analysis::oscillation::BoundaryPoint])> = p
        .curves
        .iter()
        .filter(|c| c.method == "simulation" && c.member.is_some())
        .map(|c| (c.label.as_str(), c.points.as_slice()))
        .collect();
    let (bottom, top) = p.y_range;
    let n = sims.iter().map(|s| s.1.len()).min().unwrap_or(0);
    let value = |label: &str| {
        label
            .rsplit("= ")
            .next()
            .and_then(|v| v.parse::<f64>().ok())
            .unwrap_or(f64::NAN)
    };
    let series: Vec<Series> = (0..n)
        .map(|k| Series {
            label: format!(
                "simulated boundary μ0 at {} = {}",
                p.x_desc,
                crate::notes::num(sims[0].1[k].x)
            ),
            x_name: sims
                .first()
                .and_then(|s| s.0.split(" =").next())
                .unwrap_or("member")
                .to_string(),
            points: sims
                .iter()
                .map(|(label, pts)| {
                    let q = pts[k];
                    let m = match q.side {
                        Side::Boundary => Measured::bracket(q.y, q.y_lo, q.y_hi),
                        Side::Rests => Measured::bracket(f64::NAN, top, f64::INFINITY),
                        Side::Oscillates => Measured::bracket(f64::NAN, 0.0, bottom),
                        Side::Unavailable => Measured::bracket(f64::NAN, f64::NAN, f64::NAN),
                    };
                    (value(label), m)
                })
                .collect(),
        })
        .collect();
    trend(&series, Direction::Increases)
}

/// The averaged boundary (f′(0) = 0 of Eq. 18) against the simulated one (its bracket, the
/// secant root as value) at every abscissa of a panel of methods of Fig. 16 where both are
/// inside the searched interval; the abscissae where only one is are named.
pub(super) fn fig16_averaged(p: &BoundaryPanel) -> Vec<(String, Measured, Measured)> {
    let find = |m: &str| {
        p.curves
            .iter()
            .find(|c| c.member.is_none() && c.method == m)
    };
    let (Some(sim), Some(avg)) = (find("simulation"), find("averaging")) else {
        return Vec::new();
    };
    sim.points
        .iter()
        .zip(&avg.points)
        .map(|(s, a)| {
            let what = format!(
                "panel {}, {} = {}: simulated against averaged boundary μ0",
                p.label,
                p.x_desc,
                crate::notes::num(s.x)
            );
            let sm = match s.side {
                Side::Boundary => Measured::bracket(s.y, s.y_lo, s.y_hi),
                _ => Measured::bracket(f64::NAN, f64::NAN, f64::NAN),
            };
            let am = match a.side {
                Side::Boundary => Measured::exact(a.y),
                _ => Measured::exact(f64::NAN),
            };
            (what, sm, am)
        })
        .collect()
}

/// Fig. 15: the simulated boundary of Eq. 1 at each abscissa, one series over ω0 per abscissa
/// and kind of panel (against λ: a, c, e; against r: b, d, f), where all three are located
/// inside the searched μ0 interval.
pub(super) fn fig15_omega(f: &Fig15) -> Decision {
    let mut series = Vec::new();
    let mut skipped = 0;
    for rows in [[0usize, 2, 4], [1, 3, 5]] {
        let panels: Vec<&BoundaryPanel> = rows.iter().filter_map(|&i| f.panels.get(i)).collect();
        if panels.len() != 3 {
            continue;
        }
        let sims: Vec<_> = panels
            .iter()
            .filter_map(|p| {
                p.curves
                    .iter()
                    .find(|c| c.member.is_none() && c.method == "simulation")
            })
            .collect();
        if sims.len() != 3 {
            continue;
        }
        let n = sims.iter().map(|c| c.points.len()).min().unwrap_or(0);
        for j in 0..n {
            let pts: Vec<_> = sims.iter().map(|c| &c.points[j]).collect();
            if pts.iter().any(|q| q.side != Side::Boundary) {
                skipped += 1;
                continue;
            }
            series.push(Series {
                label: format!(
                    "Eq. 1 (simulation), panels {}: boundary μ0 at {} = {}",
                    panels
                        .iter()
                        .map(|p| p.label.as_str())
                        .collect::<Vec<_>>()
                        .join(", "),
                    panels[0].x_desc,
                    crate::notes::num(pts[0].x)
                ),
                x_name: "ω0".into(),
                points: pts
                    .iter()
                    .zip(FIG15_OMEGAS)
                    .map(|(q, w)| (w, Measured::bracket(q.y, q.y_lo, q.y_hi)))
                    .collect(),
            });
        }
    }
    let mut d = dependence(&series, CLOSENESS_REL_TOL);
    if skipped > 0 {
        d.statistic.push_str(&format!(
            "; {skipped} abscissae where a boundary lies outside the searched μ0 interval are not tested"
        ));
    }
    d
}

/// Why a Fig. 14 ensemble decides nothing: its R̂ and, where the well decomposition was
/// tried, its first refusal.
fn fig14_not_stationary(p: &crate::fig14_joint_pdf::JointPanel) -> String {
    let refusal = p
        .wells
        .as_ref()
        .and_then(|w| w.refusals.first())
        .map(|r| format!("; the well decomposition refused: {r}"))
        .unwrap_or_default();
    format!(
        "r = {}: not stationary (R̂ = {}{refusal})",
        p.r,
        crate::notes::sig(p.r_hat, 3)
    )
}

/// The count Fig. 14's text gives: "four separate peaks" at r = 0.999. (Its "vast crater" at
/// r = 0.92 is a shape, not a count: a ring-shaped rim around a lower centre, which the count
/// of separate maxima cannot tell from one compact peak; it is not tested.)
pub const FIG14_CLAIMED_MAXIMA: [(f64, u32); 1] = [(0.999, 4)];

/// Fig. 14: the separate maxima of the joint density at r = 0.999, of the averaged theory (Eq. 30–31, on
/// the fine grid the figure draws) and of Monte Carlo of Eq. 1 (stationary ensembles, with the
/// plotted window holding the density), against the text's counts.
pub(super) fn fig14_crater(f: &Fig14) -> Decision {
    let mut theory = Vec::new();
    let mut mc = Vec::new();
    let mut outside = Vec::new();
    for (r, claimed) in FIG14_CLAIMED_MAXIMA {
        let Some(p) = f.panels.iter().find(|p| (p.r - r).abs() < 1e-9) else {
            continue;
        };
        theory.push(Count {
            what: format!("r = {r}: separate maxima of P(U, dU/dt)"),
            claimed,
            computed: separate_maxima(&p.theory_fine, PEAK_FLOOR, PEAK_DIP) as u32,
            source: CountSource::Exact,
        });
        // the Monte Carlo count needs the cells' standard errors (significant dips only)
        let stationary = p.stationary && !p.mc_stderr.is_empty();
        mc.push(Count {
            what: format!(
                "r = {r}: separate maxima of the joint histogram ({} estimator), dips significant at {PEAK_SE_K} s.e. ({} % of the samples outside the window{})",
                p.estimator,
                crate::notes::sig(100.0 * p.mc_outside, 3),
                if p.mc_stderr.is_empty() { "; no standard errors in the data" } else { "" }
            ),
            claimed,
            computed: if p.mc_stderr.is_empty() {
                separate_maxima(&p.mc, PEAK_FLOOR, PEAK_DIP) as u32
            } else {
                separate_maxima_significant(&p.mc, &p.mc_stderr, PEAK_FLOOR, PEAK_DIP, PEAK_SE_K)
                    as u32
            },
            source: CountSource::Ensemble {
                stationary,
                r_hat: p.r_hat,
            },
        });
        // NaN (unknown) counts as outside
        if p.mc_outside.is_nan() || p.mc_outside > WINDOW_MASS_TOL {
            outside.push(format!(
                "r = {r}: {} % of the Monte Carlo samples lie outside the plotted window",
                crate::notes::sig(100.0 * p.mc_outside, 3)
            ));
        }
    }
    let mut simulated = count(&mc);
    if let Verdict::Undetermined { why } = &mut simulated.verdict {
        let reasons: Vec<String> = FIG14_CLAIMED_MAXIMA
            .iter()
            .filter_map(|(r, _)| f.panels.iter().find(|p| (p.r - r).abs() < 1e-9))
            .filter(|p| !p.stationary)
            .map(fig14_not_stationary)
            .collect();
        if !reasons.is_empty() {
            *why = reasons.join("; ");
        }
    }
    if !outside.is_empty() && !matches!(simulated.verdict, Verdict::Undetermined { .. }) {
        simulated = simulated.undetermined_because(&format!(
            "the window does not hold the density (more than {} % outside: {})",
            100.0 * WINDOW_MASS_TOL,
            outside.join("; ")
        ));
    } else if !outside.is_empty() {
        if let Verdict::Undetermined { why } = &mut simulated.verdict {
            why.push_str(&format!("; {}", outside.join("; ")));
        }
    }
    all_of(
        "count",
        vec![
            ("averaged theory (Eq. 30–31)".into(), count(&theory)),
            ("Eq. 1 (Monte Carlo)".into(), simulated),
        ],
    )
}

/// Eq. 26–28: which of the printed and the corrected formulas' P(A) Monte Carlo of Eq. 5 (the
/// equation they are derived from) follows, on every ensemble of Fig. 13, by the agreement rule
/// applied to each: an ensemble that agrees with the corrected formulas and not with the
/// printed ones is against the printed formulas, the reverse for them; both or neither
/// agreeing does not tell them apart (where the two coincide, or where the averaging itself
/// fails); an ensemble undetermined for either is undefined.
pub(super) fn eq26_28(f: &Fig13) -> Decision {
    let comparison = |p: &AmplitudePanel, r: &McRun, variant: &str, words: &str| {
        r.distances
            .iter()
            .find(|d| d.variant == variant)
            .map(|d| Comparison {
                what: format!("{}, MC of Eq. 5{}, {words}", p.caption, estimator_of(r)),
                hellinger: d.hellinger,
                se: d.hellinger_stderr,
                bins: r.edges.len().saturating_sub(1),
                ess: r.ess,
                stationary: r.stationary,
                r_hat: r.r_hat,
                weightings: weightings_of(r, variant),
            })
    };
    let mut checks = Vec::new();
    let mut open = Vec::new();
    for p in &f.panels {
        for r in p.runs.iter().filter(|r| r.system == "Eq. 5") {
            let (Some(printed), Some(corrected)) = (
                comparison(p, r, "paper", "printed formulas"),
                comparison(p, r, "consistent", "corrected formulas"),
            ) else {
                continue;
            };
            let dp = agreement(std::slice::from_ref(&printed));
            let dc = agreement(std::slice::from_ref(&corrected));
            let Some(mut check) = dp.checks.first().cloned() else {
                continue;
            };
            let corrected_words = dc
                .checks
                .first()
                .map(|c| {
                    format!(
                        "corrected formulas: H = {} against {} ({})",
                        crate::notes::sig(c.statistic_value, 3),
                        crate::notes::sig(c.threshold, 3),
                        dc.verdict.tag()
                    )
                })
                .unwrap_or_default();
            check.what = format!("{}; {corrected_words}", check.what);
            check.outcome = match (&dp.verdict, &dc.verdict) {
                (Verdict::Refuted, Verdict::Confirmed) => Outcome::Against,
                (Verdict::Confirmed, Verdict::Refuted) => Outcome::For,
                (Verdict::Undetermined { why }, _) | (_, Verdict::Undetermined { why }) => {
                    open.push(format!("{}: {why}", p.caption));
                    Outcome::Undefined
                }
                _ => Outcome::Neither,
            };
            checks.push(check);
        }
    }
    let has = |o: Outcome| checks.iter().any(|c| c.outcome == o);
    let verdict = match (has(Outcome::Against), has(Outcome::For)) {
        (true, false) => Verdict::Refuted,
        (false, true) => Verdict::Confirmed,
        (true, true) => Verdict::undetermined(
            "some ensembles follow the printed formulas and others the corrected ones",
        ),
        (false, false) => Verdict::undetermined(if open.is_empty() {
            "no ensemble tells the printed from the corrected formulas (both or neither agree)"
                .to_string()
        } else {
            format!(
                "no ensemble tells the printed from the corrected formulas; {}",
                open.join("; ")
            )
        }),
    };
    Decision::new(
        verdict,
        "agreement",
        format!("the agreement rule on the printed and on the corrected formulas' P(A) against each ensemble of MC of Eq. 5 (H ≤ √(bins/(8·ESS)) + {AGREEMENT_K}·se(H), stationary ensembles only); an ensemble that agrees with one variant and not the other follows it; refuted when an ensemble follows the corrected formulas and none the printed ones"),
        0,
        None,
        checks,
    )
}

/// Fig. 14's text: "a greater restitution coefficient causes the distribution to move to a
/// lower Z value" (Z the velocity axis). What a reader of the maps sees move is the density's
/// extent along U̇: measured as ⟨U̇²⟩ over each panel's density (for the theory ω1²⟨A²⟩/2,
/// exact; for Monte Carlo of Eq. 1 the ensemble's Var U̇ with its standard error, stationary
/// ensembles only), one series per model over r in increasing order, decided by the trend rule
/// (decreases).
pub(super) fn fig14_shift(f: &Fig14) -> Decision {
    let mut panels: Vec<&crate::fig14_joint_pdf::JointPanel> = f.panels.iter().collect();
    panels.sort_by(|a, b| a.r.total_cmp(&b.r));
    let theory = trend(
        &[Series {
            label: "⟨U̇²⟩ = ω1²⟨A²⟩/2".into(),
            x_name: "r".into(),
            points: panels
                .iter()
                .map(|p| (p.r, Measured::exact(p.theory_velocity_variance)))
                .collect(),
        }],
        Direction::Decreases,
    );
    let mc_points: Vec<(f64, Measured)> = panels
        .iter()
        .filter_map(|p| match p.mc_velocity_variance.as_slice() {
            [v, se] => Some((p.r, Measured::with_se(*v, *se))),
            _ => None,
        })
        .collect();
    let mut simulated = trend(
        &[Series {
            label: "Var U̇".into(),
            x_name: "r".into(),
            points: mc_points.clone(),
        }],
        Direction::Decreases,
    );
    let open: Vec<String> = panels
        .iter()
        .filter(|p| !p.stationary)
        .map(|p| {
            format!(
                "r = {}: not stationary (R̂ = {})",
                p.r,
                crate::notes::sig(p.r_hat, 3)
            )
        })
        .collect();
    if mc_points.len() < panels.len() {
        simulated = simulated.undetermined_because("no Monte Carlo Var U̇ in the data");
    } else if !open.is_empty() {
        simulated = simulated.undetermined_because(&open.join("; "));
    }
    all_of(
        "trend",
        vec![
            ("averaged theory (Eq. 30–31)".into(), theory),
            ("Eq. 1 (Monte Carlo)".into(), simulated),
        ],
    )
}

/// Sec. V: "as correlated noise intensity increases, the model experiences a progressive
/// increase in disorder". Disorder as Sec. V measures it: the largest Lyapunov exponent (the
/// section's "past this threshold, disorder disrupts the system, leading to unpredictability …
/// the maximum Lyapunov exponent turns positive"), against D on every curve of Figs 17 and 18
/// (each regime of each parameter value: rest, inner, middle, outer cycle), decided by the
/// trend rule (increases; Student's t with realisations − 1 degrees of freedom, Holm over every
/// step and range of all curves). Points without a finite exponent (realisations merged: no
/// separation to measure) are left out and counted in the statistic.
pub(super) fn noise_disorder(panels: &[(&str, &LlePanel)]) -> Decision {
    let mut series = Vec::new();
    let mut left_out = 0;
    for (figure, p) in panels {
        for c in &p.curves {
            let lc = crate::lle::lle_curve(c);
            let points: Vec<(f64, Measured)> = lc
                .points
                .iter()
                .filter(|q| {
                    let ok = q.lle.is_finite() && q.se.is_finite();
                    left_out += usize::from(!ok);
                    ok
                })
                .map(|q| (q.d, Measured::with_se_dof(q.lle, q.se, q.dof)))
                .collect();
            if points.len() >= 2 {
                series.push(Series {
                    label: format!("{figure}, {}: largest Lyapunov exponent", c.label),
                    x_name: "D".into(),
                    points,
                });
            }
        }
    }
    let mut d = trend(&series, Direction::Increases);
    if left_out > 0 {
        d.statistic.push_str(&format!(
            "; {left_out} points without a finite exponent (merged realisations) left out"
        ));
    }
    d
}
