//! The theory claims (Figs 1–10, 12): deterministic numbers from the averaged theory and
//! from noise-free simulations, decided by the count, trend and closeness rules.
//!
//! # Equations
//! The averaged drift f(A) of Eq. 18 (stable cycles: roots with df/dA < 0), the
//! pseudo-potential U_eff of Eq. 23 and the P(A) of Eq. 27 (modes: roots of m1 with m1′ < 0).
//!
//! # Method
//! Counts and shares from the maps and branch diagrams; the (γ0, δ0) zone areas of Figs 3 and
//! 6 between the exact fold polylines, line by line ([`exact_share`]: each line cut at the fold
//! crossings, each piece classified by the theory's count, 400 and 800 lines for the bracket);
//! the A01 well of Fig. 7 by its floor below U_eff(0).
//!
//! # Reference
//! docs/verdicts.md, "The rules" and "The claims".
//!
//! # Test
//! `tests/verdicts.rs`: `theory_claims_in_quick_mode_with_their_numbers` and the edited-data
//! flips (`editing_the_theory_figures_flips_the_issue_34_rows`).

use super::super::rules::{
    closeness, count, curve_distance, dependence, trend, Count, CountSource, CurveSets, Direction,
    Polyline, Series, CLOSENESS_REL_TOL, CURVE_TOL,
};
use super::super::{all_of, Decision, Measured};
use crate::fig01_phase_recurrence::Fig01;
use crate::fig04_drift::Fig04;
use crate::fig05_branches::Fig05;
use crate::fig07_pseudo_potential::{Curve as UeffCurve, Fig07};
use crate::fig08_barriers::Fig08;
use crate::fig09_barrier_surfaces::Fig09;
use crate::maps::MapPanel;
use trirhythm::theory::averaging::Variant;
use trirhythm::theory::bifurcation::BranchDiagram;

pub(super) fn fig01_align(f: &Fig01) -> Decision {
    let pairs: Vec<(String, Measured, Measured)> = match (f.panels.first(), f.panels.get(1)) {
        (Some(a), Some(b)) => vec![(
            "mean amplitude, Eq. 1 against Eq. 5".into(),
            Measured::exact(a.amplitude),
            Measured::exact(b.amplitude),
        )],
        _ => Vec::new(),
    };
    closeness(&pairs, CLOSENESS_REL_TOL)
}

/// Fig. 1's recurrence plots: the recurrence rate RR and the determinism DET of Eq. 1 against
/// Eq. 5 (same threshold ε, same window), by closeness.
pub(super) fn fig01_recurrence(f: &Fig01) -> Decision {
    let pairs: Vec<(String, Measured, Measured)> = match (f.panels.first(), f.panels.get(1)) {
        (Some(a), Some(b)) => vec![
            (
                format!(
                    "recurrence rate RR (ε = {}), Eq. 1 against Eq. 5",
                    f.epsilon
                ),
                Measured::exact(a.rr),
                Measured::exact(b.rr),
            ),
            (
                format!("determinism DET (ε = {}), Eq. 1 against Eq. 5", f.epsilon),
                Measured::exact(a.det),
                Measured::exact(b.det),
            ),
        ],
        _ => Vec::new(),
    };
    closeness(&pairs, CLOSENESS_REL_TOL)
}

/// The share of count `k` with what the grid resolves of it: a bracket from the region's
/// interior to its closure on the grid ([`MapPanel::share_bracket`]), so that a trend decides
/// only on changes larger than the grid's resolution.
pub(super) fn share_measured(p: &MapPanel, k: usize) -> Measured {
    let (lo, hi) = p.share_bracket(k);
    Measured::bracket(share(p, k), lo, hi)
}

/// Share (per cent of the grid) of grid points with count `k`.
pub(super) fn share(p: &MapPanel, k: usize) -> f64 {
    p.share(k)
}

/// Fig. 2: "L1, L2, and L3 in Figs.2 (i) and (ii) … enclose the birhythmic and trirhythmic
/// areas": the birhythmic area of (i) (three positive roots in (α0, β0) at γ0 = δ0 = 0), the bi-
/// and trirhythmic areas of (ii), and the three saddle-node lines, named as the paper names
/// them (L1 the outer cycle's fold, L3 the inner one's, L2 between), over both panels.
pub(super) fn fig02_regions(panels: &[MapPanel]) -> Decision {
    let mut items = Vec::new();
    for (label, ks) in [("i", &[2usize][..]), ("ii", &[2, 3][..])] {
        let Some(p) = panels.iter().find(|p| p.label == label) else {
            continue;
        };
        for &k in ks {
            let name = if k == 2 { "birhythmic" } else { "trirhythmic" };
            items.push(Count {
                what: format!(
                    "{name} area present in panel ({label}) ({} % of the grid)",
                    crate::notes::sig(share(p, k), 3)
                ),
                claimed: 1,
                computed: u32::from(share(p, k) > 0.0),
                source: CountSource::Exact,
            });
        }
    }
    let mut names: Vec<String> = panels
        .iter()
        .flat_map(|p| {
            p.fold_names
                .iter()
                .filter_map(|(_, n)| n.split_whitespace().next())
                .map(|n| format!("{n} ({})", p.label))
        })
        .collect();
    names.sort();
    // (a name once per panel, however many curves carry it)
    names.dedup();
    let mut distinct: Vec<&str> = names
        .iter()
        .filter_map(|n| n.split_whitespace().next())
        .collect();
    distinct.dedup();
    items.push(Count {
        what: format!(
            "saddle-node lines L1–L3 traced exactly in panels (i) and (ii) (found: {})",
            if names.is_empty() {
                "none".to_string()
            } else {
                names.join(", ")
            }
        ),
        claimed: 3,
        computed: distinct.len() as u32,
        source: CountSource::Exact,
    });
    // the lines first: the sentence's subject
    items.rotate_right(1);
    count(&items)
}

pub(super) fn share_trend(
    panels: &[MapPanel],
    xs: &[f64],
    x_name: &str,
    k: usize,
    direction: Direction,
) -> Decision {
    let label = ["zero", "one", "two", "three"][k.min(3)];
    let series = Series {
        label: format!("share of grid points with count {label} (%)"),
        x_name: x_name.into(),
        points: panels
            .iter()
            .zip(xs)
            .map(|(p, &x)| (x, share_measured(p, k)))
            .collect(),
    };
    trend(&[series], direction)
}

/// Rows of the line-by-line area of [`exact_share`] (and twice as many for its error).
pub const EXACT_SHARE_ROWS: usize = 400;

/// The share (per cent of the window) of a map panel where the averaged theory has `k` stable
/// cycles, measured between the exact fold polylines rather than on the grid: along each of
/// `rows` horizontal lines (midpoint rule in y) the line is cut where it crosses a fold curve,
/// each piece is classified by the count at its quarter, middle and three-quarter points
/// (pieces whose points disagree, a crossing the polylines missed, are split by bisection on
/// the count), and the lengths of the pieces with count `k` are summed. None where the
/// panel's parameters cannot be read.
pub(super) fn exact_share(
    p: &MapPanel,
    preset_name: &str,
    k: usize,
    variant: Variant,
    rows: usize,
) -> Option<f64> {
    let base = super::sequences::panel_params(preset_name, &p.params)?;
    let (xa, xb) = (p.x.grid.start, p.x.grid.stop);
    let (ya, yb) = (p.y.grid.start, p.y.grid.stop);
    let count_at = |x: f64, y: f64| {
        base.with(&p.x.grid.key, x)
            .and_then(|q| q.with(&p.y.grid.key, y))
            .and_then(|q| trirhythm::theory::averaging::Theory::new(&q, variant))
            .map_or(usize::MAX, |t| t.stable_count_fast())
    };
    // the length of [a, b] with count k on the line at y
    fn piece(count_at: &dyn Fn(f64) -> usize, a: f64, b: f64, k: usize, depth: u32) -> f64 {
        let c: Vec<usize> = [0.25, 0.5, 0.75]
            .iter()
            .map(|t| count_at(a + t * (b - a)))
            .collect();
        if c.iter().all(|&x| x == c[0]) || depth == 0 {
            return if c[1] == k { b - a } else { 0.0 };
        }
        let m = 0.5 * (a + b);
        piece(count_at, a, m, k, depth - 1) + piece(count_at, m, b, k, depth - 1)
    }
    let mut total = 0.0;
    for j in 0..rows {
        let y = ya + (yb - ya) * (j as f64 + 0.5) / rows as f64;
        let mut cuts = vec![xa, xb];
        for c in &p.folds.curves {
            for w in c.points.windows(2) {
                let (y1, y2) = (w[0].y, w[1].y);
                if (y1 - y) * (y2 - y) < 0.0 {
                    let x = w[0].x + (y - y1) * (w[1].x - w[0].x) / (y2 - y1);
                    if x > xa && x < xb {
                        cuts.push(x);
                    }
                }
            }
        }
        cuts.sort_by(f64::total_cmp);
        let line = |x: f64| count_at(x, y);
        for w in cuts.windows(2) {
            total += piece(&line, w[0], w[1], k, 12);
        }
    }
    Some(100.0 * total / ((xb - xa) * rows as f64))
}

/// [`exact_share`] with `EXACT_SHARE_ROWS` and twice as many rows: the finer value in a bracket
/// widened by the difference (the midpoint rule's error).
pub(super) fn exact_share_measured(
    p: &MapPanel,
    preset_name: &str,
    k: usize,
    variant: Variant,
) -> Measured {
    match (
        exact_share(p, preset_name, k, variant, EXACT_SHARE_ROWS),
        exact_share(p, preset_name, k, variant, 2 * EXACT_SHARE_ROWS),
    ) {
        (Some(a), Some(b)) => {
            let e = (a - b).abs().max(1e-9 * b.abs());
            Measured::bracket(b, b - e, b + e)
        }
        _ => Measured::exact(f64::NAN),
    }
}

/// A share trend on the area between the exact fold polylines ([`exact_share_measured`]).
pub(super) fn exact_share_trend(
    panels: &[MapPanel],
    preset_name: &str,
    xs: &[f64],
    x_name: &str,
    k: usize,
    direction: Direction,
    variant: Variant,
) -> Decision {
    let label = ["zero", "one", "two", "three"][k.min(3)];
    let series = Series {
        label: format!(
            "area with count {label} between the exact fold curves (% of the window; bracket: {} against {} rows)",
            EXACT_SHARE_ROWS,
            2 * EXACT_SHARE_ROWS
        ),
        x_name: x_name.into(),
        points: panels
            .iter()
            .zip(xs)
            .map(|(p, &x)| (x, exact_share_measured(p, preset_name, k, variant)))
            .collect(),
    };
    trend(&[series], direction)
}

/// The root counts the paper's text gives for Fig. 4 (a)–(d).
pub const FIG04_CLAIMED_ROOTS: [u32; 4] = [5, 5, 3, 0];

pub(super) fn fig04_roots(f: &Fig04) -> Decision {
    let items: Vec<Count> = f
        .panels
        .iter()
        .zip(FIG04_CLAIMED_ROOTS)
        .map(|(p, claimed)| Count {
            what: format!("positive roots of f, panel {} (r = {})", p.label, p.r),
            claimed,
            computed: p.cycles.len() as u32,
            source: CountSource::Exact,
        })
        .collect();
    count(&items)
}

/// Stable branches of a branch diagram crossing parameter value `x`.
pub(super) fn stable_at(bd: &BranchDiagram, x: f64) -> u32 {
    let mut n = 0;
    for b in &bd.branches {
        for w in b.points.windows(2) {
            let (lo, hi) = if w[0].param <= w[1].param {
                (w[0].param, w[1].param)
            } else {
                (w[1].param, w[0].param)
            };
            if lo <= x && x < hi && w[0].stable && w[1].stable {
                n += 1;
            }
        }
    }
    n
}

pub(super) fn fig05_tri_all_r(f: &Fig05) -> Decision {
    let Some((label, mu0, bd)) = f.panels.iter().find(|p| (p.1 - 0.7).abs() < 1e-12) else {
        return count(&[]);
    };
    let n = 20;
    let items: Vec<Count> = (0..n)
        .map(|j| {
            let r = bd.start + (bd.stop - bd.start) * (j as f64 + 0.5) / n as f64;
            Count {
                what: format!(
                    "stable cycles at r = {}, panel {label} (μ0 = {mu0})",
                    crate::notes::sig(r, 4)
                ),
                claimed: 3,
                computed: stable_at(bd, r),
                source: CountSource::Exact,
            }
        })
        .collect();
    count(&items)
}

/// (inner A01 well depth, outer well depth, well amplitudes) of a U_eff curve. The inner
/// depth is the well's floor below U_eff(0), the rest state it forms beside (Fig. 7 is drawn at
/// D = 0, where U_eff(0) = 0 is a maximum): 0 where the A01 well has disappeared (fewer than
/// three wells, or A01 merged into the rest state), NaN where the curve has no value at
/// A = 0. The outer depth is the depth to the crest beside the outer well.
fn wells(cv: &UeffCurve) -> (f64, Option<f64>, Vec<f64>) {
    let positive: Vec<_> = cv.extrema.iter().filter(|e| e.amplitude > 0.0).collect();
    let minima: Vec<f64> = positive
        .iter()
        .filter(|e| e.minimum)
        .map(|e| e.amplitude)
        .collect();
    let rest = cv
        .extrema
        .iter()
        .find(|e| e.amplitude == 0.0)
        .map_or(f64::NAN, |e| e.potential);
    let inner = if minima.len() >= 3 {
        positive
            .iter()
            .find(|e| e.minimum)
            .map_or(0.0, |e| (rest - e.potential).max(0.0))
    } else {
        0.0
    };
    let last = positive.iter().rposition(|e| e.minimum);
    let outer = last.and_then(|i| {
        i.checked_sub(1)
            .and_then(|j| positive.get(j))
            .filter(|c| !c.minimum)
            .map(|c| c.potential - positive[i].potential)
    });
    (inner, outer, minima)
}

pub(super) fn fig07_depths(f: &Fig07, inner: bool) -> Decision {
    // curves are listed from the largest r (λ) down: the claim's order
    let series: Vec<Series> = f
        .panels
        .iter()
        .map(|p| {
            // panel a varies r, panel b λ: (r, λ) = params of each curve
            let by_r = p.id == "a";
            let x_name = if by_r { "r" } else { "λ" };
            let pick = |q: &(f64, f64)| if by_r { q.0 } else { q.1 };
            Series {
                label: format!(
                    "panel {}: {}",
                    p.id,
                    if inner {
                        "floor of the A01 well below U_eff(0)"
                    } else {
                        "depth of the outer well"
                    }
                ),
                x_name: x_name.into(),
                points: p
                    .curves
                    .iter()
                    .zip(&p.params)
                    .map(|(cv, q)| {
                        let (i, o, _) = wells(cv);
                        let v = if inner { i } else { o.unwrap_or(f64::NAN) };
                        (pick(q), Measured::exact(v))
                    })
                    .collect(),
            }
        })
        .collect();
    let mut d = trend(
        &series,
        if inner {
            Direction::Decreases
        } else {
            Direction::Increases
        },
    );
    // the change across the plotted range decides a confirmation: shown first
    if d.verdict == super::super::Verdict::Confirmed {
        d.checks
            .sort_by_key(|c| !c.what.contains("across the range"));
    }
    d
}

/// "The amplitudes A01, A03 and A05 change very slightly": each well's amplitude on every
/// curve against the first (largest r or λ), and, where the averaged theory's f′(0) changes
/// sign within 0.02 below the panel's smallest r (λ), A01 at that point, where the inner well
/// has merged with the rest state (A01 = 0: relative change 1). The checks against the claim
/// come first, the largest first.
pub(super) fn fig07_wells_move(f: &Fig07, variant: Variant) -> Decision {
    let mut pairs = Vec::new();
    for p in &f.panels {
        let all: Vec<Vec<f64>> = p.curves.iter().map(|c| wells(c).2).collect();
        let Some(first) = all.first() else { continue };
        for (cv, w) in p.curves.iter().zip(&all).skip(1) {
            if w.len() != first.len() {
                continue;
            }
            for (k, (a, b)) in first.iter().zip(w).enumerate() {
                pairs.push((
                    format!("panel {}, well {} at {}", p.id, k + 1, cv.label),
                    Measured::exact(*b),
                    Measured::exact(*a),
                ));
            }
        }
        // where the A01 well vanishes: the averaged Hopf point just below the plotted range
        let by_r = p.id == "a";
        let (key, name) = if by_r { ("r", "r") } else { ("lambda", "λ") };
        let pick = |q: &(f64, f64)| if by_r { q.0 } else { q.1 };
        let (Some(q0), Some(a01)) = (p.params.first(), first.first()) else {
            continue;
        };
        let smallest = p.params.iter().map(pick).fold(f64::INFINITY, f64::min);
        let base = super::sequences::panel_params(
            if by_r { "fig7a" } else { "fig7b" },
            &format!("r={} lambda={}", q0.0, q0.1),
        );
        let vanish = base.and_then(|b| {
            super::sequences::hopf_point(&b, key, smallest - 0.02, smallest, variant)
        });
        if let Some(v) = vanish {
            pairs.push((
                format!(
                    "panel {}, well 1 (A01) vanishes at {name} = {} (f′(0) = 0, just below the plotted {name} = {}): A01 = 0",
                    p.id,
                    crate::notes::sig(v, 5),
                    crate::notes::sig(smallest, 4)
                ),
                Measured::exact(0.0),
                Measured::exact(*a01),
            ));
        }
    }
    super::sequences::strongest_first(closeness(&pairs, CLOSENESS_REL_TOL))
}

pub(super) fn fig08_barriers(f: &Fig08) -> Decision {
    count(&[Count {
        what: "energy barriers of U_eff".into(),
        claimed: 4,
        computed: f.barriers.len() as u32,
        source: CountSource::Exact,
    }])
    .undetermined_because(
        "τ is not printed in the paper; τ = 5 chosen, and the inner well exists only for τ ≳ 3",
    )
}

pub(super) fn fig09_lambda(f: &Fig09) -> Decision {
    let mut up = Vec::new();
    let mut down = Vec::new();
    for s in &f.surfaces {
        for i in 0..4 {
            for ix in 0..s.x.count {
                // runs of grid points with three wells along λ (ascending)
                let mut run: Vec<(f64, Measured)> = Vec::new();
                let mut flush = |run: &mut Vec<(f64, Measured)>| {
                    if run.len() >= 2 {
                        let series = Series {
                            label: format!(
                                "ΔU{} at r = {}, τ = {}",
                                i + 1,
                                crate::notes::sig(s.r, 4),
                                crate::notes::sig(s.x.value(ix), 4)
                            ),
                            x_name: "λ".into(),
                            points: std::mem::take(run),
                        };
                        if i == 1 {
                            down.push(series);
                        } else {
                            up.push(series);
                        }
                    }
                    run.clear();
                };
                for iy in 0..s.y.count {
                    match s.heights[iy * s.x.count + ix][i] {
                        Some(h) => run.push((s.y.value(iy), Measured::exact(h))),
                        None => flush(&mut run),
                    }
                }
                flush(&mut run);
            }
        }
    }
    all_of(
        "trend",
        vec![
            (
                "ΔU1, ΔU3, ΔU4 increase with λ".into(),
                trend(&up, Direction::Increases),
            ),
            (
                "ΔU2 decreases with λ".into(),
                trend(&down, Direction::Decreases),
            ),
        ],
    )
}

pub(super) fn fig09_r(f: &Fig09) -> Decision {
    let (Some(hi), Some(lo)) = (
        f.surfaces.iter().find(|s| (s.r - 0.998).abs() < 1e-9),
        f.surfaces.iter().find(|s| (s.r - 0.990).abs() < 1e-9),
    ) else {
        return trend(&[], Direction::Decreases);
    };
    let mut parts = Vec::new();
    for i in [0usize, 1, 3] {
        let mut series = Vec::new();
        for (k, (a, b)) in hi.heights.iter().zip(&lo.heights).enumerate() {
            if let (Some(a), Some(b)) = (a[i], b[i]) {
                let (ix, iy) = (k % hi.x.count, k / hi.x.count);
                series.push(Series {
                    label: format!(
                        "τ = {}, λ = {}",
                        crate::notes::num(hi.x.value(ix)),
                        crate::notes::num(hi.y.value(iy))
                    ),
                    x_name: "r".into(),
                    points: vec![(hi.r, Measured::exact(a)), (lo.r, Measured::exact(b))],
                });
            }
        }
        parts.push((
            format!("ΔU{} falls as r falls", i + 1),
            trend(&series, Direction::Decreases),
        ));
    }
    all_of("trend", parts)
}

pub(super) fn fig12_omega(panels: &[MapPanel], order: [&str; 2], direction: Direction) -> Decision {
    let pick: Vec<&MapPanel> = order
        .iter()
        .filter_map(|l| panels.iter().find(|p| p.label == *l))
        .collect();
    let omega = |p: &MapPanel| {
        if p.label == "a" || p.label == "c" {
            0.9
        } else {
            1.0
        }
    };
    let series = Series {
        label: format!("trimodal share (%) of panels {} → {}", order[0], order[1]),
        x_name: "ω0".into(),
        points: pick
            .iter()
            .map(|p| (omega(p), share_measured(p, 3)))
            .collect(),
    };
    trend(&[series], direction)
}

/// The trirhythmic interval of a branch diagram: the length of the set of r in the panel where
/// three stable branches coexist, and its lower end, from the exact fold and birth points
/// (the stable count changes only there). Where the set reaches an end of the panel's range
/// short of the physical range r ∈ [0, 1], the interval may continue beyond it: a bracket up to
/// that bound.
pub(super) fn trirhythmic_interval(bd: &BranchDiagram) -> (Measured, f64) {
    let (start, stop) = (bd.start.min(bd.stop), bd.start.max(bd.stop));
    let mut cuts: Vec<f64> = vec![start, stop];
    cuts.extend(bd.folds.iter().map(|f| f.0));
    cuts.extend(bd.hopf.iter().copied());
    cuts.retain(|c| c.is_finite() && (start..=stop).contains(c));
    cuts.sort_by(f64::total_cmp);
    cuts.dedup();
    let (mut len, mut lower) = (0.0, f64::NAN);
    let (mut at_start, mut at_stop) = (false, false);
    for w in cuts.windows(2) {
        if stable_at(bd, 0.5 * (w[0] + w[1])) == 3 {
            len += w[1] - w[0];
            if lower.is_nan() {
                lower = w[0];
            }
            at_start |= w[0] == start;
            at_stop |= w[1] == stop;
        }
    }
    let more = if at_start { start.max(0.0) } else { 0.0 }
        + if at_stop { (1.0 - stop).max(0.0) } else { 0.0 };
    let m = if more > 0.0 {
        Measured::bracket(len, len, len + more)
    } else {
        Measured::exact(len)
    };
    (m, lower)
}

pub(super) fn fig05_interval_mu0(f: &Fig05) -> Decision {
    let mut ends = Vec::new();
    let points = f
        .panels
        .iter()
        .map(|(label, mu0, bd)| {
            let (m, lower) = trirhythmic_interval(bd);
            ends.push(if lower == bd.start.min(bd.stop) {
                format!(
                    "({label}) below the panel's r = {}",
                    crate::notes::num(lower)
                )
            } else {
                format!(
                    "({label}) r = {}, (1 − r)/μ0 = {}",
                    crate::notes::sig(lower, 6),
                    crate::notes::sig((1.0 - lower) / mu0, 5)
                )
            });
            (*mu0, m)
        })
        .collect();
    let series = Series {
        label: format!(
            "averaged theory (Eq. 18): length in r of the trirhythmic interval (three stable cycles; lower ends {})",
            ends.join(", ")
        ),
        x_name: "μ0".into(),
        points,
    };
    dependence(&[series], CLOSENESS_REL_TOL)
}

/// The curves of a fold set in the panel's plane scaled to the unit square.
fn scaled(p: &MapPanel, folds: &trirhythm::theory::bifurcation::Folds) -> Vec<Polyline> {
    let (x, y) = (&p.x.grid, &p.y.grid);
    let sx = |v: f64| (v - x.start) / (x.stop - x.start);
    let sy = |v: f64| (v - y.start) / (y.stop - y.start);
    folds
        .curves
        .iter()
        .map(|c| c.points.iter().map(|q| (sx(q.x), sy(q.y))).collect())
        .collect()
}

/// The printed Eq. 36–37 curves against the exact P-bifurcation set (m1 = ∂m1/∂A = 0), panel
/// by panel, of every map panel that holds both (the paper variant's maps).
pub(super) fn eq37_curves(figures: &[(&str, &[MapPanel])]) -> Decision {
    let mut items = Vec::new();
    for (fig, panels) in figures {
        for p in panels.iter() {
            let Some(printed) = &p.printed else { continue };
            let n = p.x.grid.count.max(p.y.grid.count).max(2) - 1;
            items.push(CurveSets {
                what: format!("{fig} ({}) {}", p.label, p.caption),
                tested: scaled(p, printed),
                reference: scaled(p, &p.folds),
                cell: 1.0 / n as f64,
            });
        }
    }
    let mut d = curve_distance(&items, CURVE_TOL);
    if items.is_empty() {
        d.verdict = super::super::Verdict::undetermined(
            "the maps hold no printed Eq. 36–37 curves (they are drawn for the paper variant only)",
        );
    }
    d
}
