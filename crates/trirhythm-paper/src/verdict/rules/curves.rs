//! The curve-distance rule: two sets of curves in a plane (a printed construction against the
//! exact one), drawn as polylines, are the same set when each lies within a tolerance of the
//! other (the symmetric Hausdorff distance, in the plane scaled to the unit square).
//! Reference: docs/verdicts.md, "Curve distance". Tested by `tests/verdicts.rs`.

use super::super::{Check, Decision, Measured, Outcome, Verdict};

/// A polyline: its vertices in order, in plane coordinates scaled to the unit square.
pub type Polyline = Vec<(f64, f64)>;

/// Two sets of curves of one panel: the construction under test and the reference.
#[derive(Debug, Clone)]
pub struct CurveSets {
    /// Which panel ("Fig. 10 (a) D = 0.05").
    pub what: String,
    /// The curves under test (the printed equations), scaled to the unit square.
    pub tested: Vec<Polyline>,
    /// The reference curves (the exact set), scaled alike.
    pub reference: Vec<Polyline>,
    /// One grid cell of the panel's map in scaled units (for the words: distances in cells).
    pub cell: f64,
}

/// Distance from point `p` to the segment `a`–`b`.
fn to_segment(p: (f64, f64), a: (f64, f64), b: (f64, f64)) -> f64 {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let len2 = dx * dx + dy * dy;
    let t = if len2 > 0.0 {
        (((p.0 - a.0) * dx + (p.1 - a.1) * dy) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p.0 - a.0 - t * dx).hypot(p.1 - a.1 - t * dy)
}

/// Distance from point `p` to the nearest curve of `to` (∞ when `to` has no point).
fn to_curves(p: (f64, f64), to: &[Polyline]) -> f64 {
    let mut best = f64::INFINITY;
    for c in to {
        match c.len() {
            0 => {}
            1 => best = best.min((p.0 - c[0].0).hypot(p.1 - c[0].1)),
            _ => {
                for w in c.windows(2) {
                    best = best.min(to_segment(p, w[0], w[1]));
                }
            }
        }
    }
    best
}

/// The directed distance from the curves `from` to the curves `to`: the largest distance of a
/// vertex of `from` to the nearest point of `to` (0 when `from` is empty; ∞ when only `to`
/// is). Measured at the vertices of `from` against the segments of `to`: a point between two
/// vertices is at most half their spacing farther (the traced curves' vertices are at most a
/// quarter of a grid cell apart).
pub fn directed_distance(from: &[Polyline], to: &[Polyline]) -> f64 {
    let mut worst: f64 = 0.0;
    for c in from {
        for &p in c {
            worst = worst.max(to_curves(p, to));
        }
    }
    worst
}

/// **Curve distance**: the symmetric Hausdorff distance max(d(tested → reference),
/// d(reference → tested)) between two sets of curves, in the plane scaled to the unit square,
/// against `tol` (a fraction of the plane's width and height).
///
/// Per panel: *for* when the distance is ≤ tol (every point of each set lies within tol of the
/// other: the same curves as a reader overlays them), *against* otherwise (a curve of one set
/// has no counterpart in the other within tol, or lies elsewhere); *undefined* when not
/// finite because both are empty. Both directions matter: a construction that misses a
/// curve of the reference (a boundary it does not give) fails as much as one whose curves lie
/// off. Verdict: refuted when a panel is against, confirmed when every panel is for, else
/// undetermined. The curves are deterministic: no uncertainty beyond the tracing's step
/// (a quarter of a grid cell).
pub fn curve_distance(items: &[CurveSets], tol: f64) -> Decision {
    use crate::notes::sig;
    let mut checks = Vec::new();
    for c in items {
        let d_tr = directed_distance(&c.tested, &c.reference);
        let d_rt = directed_distance(&c.reference, &c.tested);
        let h = d_tr.max(d_rt);
        let outcome = if c.tested.is_empty() && c.reference.is_empty() {
            Outcome::Undefined
        } else if h <= tol {
            Outcome::For
        } else {
            Outcome::Against
        };
        let cells = |d: f64| {
            if c.cell > 0.0 && d.is_finite() {
                format!(" ({} grid cells)", sig(d / c.cell, 3))
            } else {
                String::new()
            }
        };
        checks.push(Check {
            what: format!(
                "{}: {} tested and {} reference curves; tested → reference {}{}, reference → tested {}{}",
                c.what,
                c.tested.len(),
                c.reference.len(),
                sig(d_tr, 3),
                cells(d_tr),
                sig(d_rt, 3),
                cells(d_rt)
            ),
            value: Measured::exact(h),
            statistic: "Hausdorff distance (unit square)".into(),
            statistic_value: h,
            threshold: tol,
            outcome,
        });
    }
    let outcomes: Vec<Outcome> = checks.iter().map(|c| c.outcome).collect();
    let verdict = if outcomes.contains(&Outcome::Against) {
        Verdict::Refuted
    } else if outcomes.is_empty() {
        Verdict::undetermined("no curves to compare")
    } else if outcomes.contains(&Outcome::Undefined) {
        Verdict::undetermined("a panel has no curves in either set")
    } else {
        Verdict::Confirmed
    };
    Decision::new(
        verdict,
        "curve_distance",
        format!("symmetric Hausdorff distance between the two sets of curves, axes scaled to [0, 1], ≤ {tol} of the plane"),
        0,
        None,
        checks,
    )
}
