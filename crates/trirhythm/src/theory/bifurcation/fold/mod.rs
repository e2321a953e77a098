//! Fold (saddle-node) curves of the averaged polynomials, traced exactly by pseudo-arclength
//! continuation in (x = A², p1, p2).
//!
//! A fold of g is a double root: g(x) = g′(x) = 0 (equivalently f = ∂f/∂A = 0). Two equations in
//! three unknowns define a curve; it is followed by predictor (tangent = the cross product of
//! the two gradient rows) and corrector (Newton on the two equations plus the arclength
//! condition), with the step halved when Newton is slow or fails. Parameter derivatives are
//! central differences of the stack kernel; the x derivatives are analytic. Curves start from
//! grid cells where the count changes (bisection on the segment, then Newton on the segment),
//! stop at the plane's borders, at A = 0, and at cusps (g″ = 0 too: a sign change of g″ along
//! the curve, located by bisection), and are deduplicated by distance.
//!
//! The same machinery traces the P-bifurcation set: folds of h = A·m1 (h = h′ = 0, the paper's
//! Eq. 35), and the printed construction of Eq. 36–37 (h = 0 with the misprinted Eq. 37 in place
//! of h′ = 0) for comparison.//!
//! Reference: Kuznetsov, *Elements of Applied Bifurcation Theory*, ch. 10 (continuation of
//! folds).
//!
//! Tests: `tests/bifurcation.rs` (every count change of a map lies within one cell of a traced
//! curve; curve points satisfy both equations to 1e-10; an analytic cusp).
//!
//! Layout: this module (the curves' types, seeding from a map's count changes, the public
//! tracers and certificates), `continuation` (the predictor–corrector along one curve).

mod continuation;

pub(crate) use continuation::one_sided;
use continuation::{norm, sub, System};

use super::grid::{Map, Plane};
use super::kernel::{sturm_count_positive, What};
use crate::error::{Error, Result};
use crate::theory::averaging::Variant;
use crate::theory::polynomial::Polynomial;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// Which pair of equations defines the curve.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum FoldSystem {
    /// g = g′ = 0: saddle-node of limit cycles (the paper's L1, L2, L3).
    Drift,
    /// h = h′ = 0: a P-bifurcation, two extrema of P(A) merging (Eq. 35, corrected Eq. 37).
    Fpk,
    /// h = 0 (Eq. 36) with the printed Eq. 37: the paper's construction as printed.
    FpkPrinted,
}

impl FoldSystem {
    /// `drift`, `fpk`, `fpk-printed`.
    pub fn name(self) -> &'static str {
        match self {
            FoldSystem::Drift => "drift",
            FoldSystem::Fpk => "fpk",
            FoldSystem::FpkPrinted => "fpk-printed",
        }
    }

    fn what(self) -> What {
        match self {
            FoldSystem::Drift => What::Rhythmicity,
            _ => What::Modes,
        }
    }
}

/// Why a traced curve ends.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CurveEnd {
    /// At the plane's border.
    Border,
    /// At a cusp (g″ = 0 too), where two fold curves meet.
    Cusp,
    /// The double root reached A = 0.
    ZeroAmplitude,
    /// Back at its start (a closed curve).
    Closed,
    /// The corrector failed even at the smallest step.
    Failed,
    /// Too many points.
    StepLimit,
    /// The double root ran off to large amplitude (x = A² beyond 64 times the seeds' largest).
    Unbounded,
}

impl CurveEnd {
    /// `border`, `cusp`, `zero_amplitude`, `closed`, `failed`, `step_limit`, `unbounded`.
    pub fn name(self) -> &'static str {
        match self {
            CurveEnd::Border => "border",
            CurveEnd::Cusp => "cusp",
            CurveEnd::ZeroAmplitude => "zero_amplitude",
            CurveEnd::Closed => "closed",
            CurveEnd::Failed => "failed",
            CurveEnd::StepLimit => "step_limit",
            CurveEnd::Unbounded => "unbounded",
        }
    }
}

/// A point of a fold curve.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct FoldPoint {
    /// Value of the plane's x parameter.
    pub x: f64,
    /// Value of the plane's y parameter.
    pub y: f64,
    /// Amplitude A of the double root.
    pub amplitude: f64,
}

/// A traced curve.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct FoldCurve {
    /// Its equations.
    pub system: FoldSystem,
    /// Points in order along the curve.
    pub points: Vec<FoldPoint>,
    /// Why the first point ends the curve.
    pub start: CurveEnd,
    /// Why the last point ends the curve.
    pub end: CurveEnd,
}

/// All curves traced on a map (none by default: a map drawn without its folds).
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
pub struct Folds {
    /// The curves.
    pub curves: Vec<FoldCurve>,
    /// Cusp points found (each once).
    pub cusps: Vec<FoldPoint>,
    /// Seeds examined (grid transitions or sign changes).
    pub seeds: usize,
    /// Seeds where no point of a curve could be located.
    pub unlocated: usize,
}

/// Options of the continuation.
#[derive(Debug, Clone, Copy)]
pub struct TraceOptions {
    /// Largest step, in units of the plane's width (the axes are scaled to [0, 1]).
    pub max_step: f64,
    /// Most points per curve.
    pub max_points: usize,
}

impl TraceOptions {
    /// Steps of a quarter of the map's finer cell.
    pub fn for_map(map: &Map) -> Self {
        let n = map.plane.x.count.max(map.plane.y.count).max(8) - 1;
        TraceOptions {
            max_step: 0.25 / n as f64,
            max_points: 200_000,
        }
    }
}

/// Where along the segment a → b (axis fractions) the count changes, and a guess for the
/// double root there: bisection on the count, then the closest pair of roots on the side with
/// more roots.
fn bisect_transition(plane: &Plane, what: What, a: [f64; 2], b: [f64; 2]) -> (f64, Vec<f64>) {
    let k = &plane.kernel;
    let at = |s: f64| plane.point_at(a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1]));
    let ca = k.stable_count(&at(0.0), what);
    let (mut lo, mut hi) = (0.0, 1.0);
    for _ in 0..30 {
        let mid = 0.5 * (lo + hi);
        if k.stable_count(&at(mid), what) == ca {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let (pl, ph) = (k.coefficients(&at(lo), what), k.coefficients(&at(hi), what));
    let side = if sturm_count_positive(&pl) >= sturm_count_positive(&ph) {
        pl
    } else {
        ph
    };
    let poly = Polynomial::new(side.slice().to_vec());
    // Candidates: the critical points of the polynomial (a double root is one), those where it is
    // smallest relative to its scale first; then midpoints of neighbouring roots.
    let mut crit: Vec<(f64, f64)> = poly
        .derivative()
        .real_roots(0.0, f64::INFINITY)
        .into_iter()
        .map(|r| {
            let [v, _, _, s] = side.eval_derivs(r.x);
            ((v / s).abs(), r.x)
        })
        .collect();
    crit.sort_by(|p, q| p.0.total_cmp(&q.0));
    let mut xs: Vec<f64> = crit.into_iter().map(|c| c.1).collect();
    let roots: Vec<f64> = poly
        .real_roots(0.0, f64::INFINITY)
        .into_iter()
        .map(|r| r.x)
        .collect();
    let mut pairs: Vec<(f64, f64)> = roots
        .windows(2)
        .map(|p| ((p[1] - p[0]) / p[1], 0.5 * (p[0] + p[1])))
        .collect();
    pairs.sort_by(|p, q| p.0.total_cmp(&q.0));
    xs.extend(pairs.into_iter().map(|p| p.1));
    if xs.is_empty() {
        xs.push(1.0);
    }
    (0.5 * (lo + hi), xs)
}

fn frac(map: &Map, (ix, iy): (usize, usize)) -> [f64; 2] {
    [
        ix as f64 / (map.plane.x.count - 1) as f64,
        iy as f64 / (map.plane.y.count - 1) as f64,
    ]
}

/// Trace the fold curves of a map: g = g′ = 0 for a rhythmicity map, h = h′ = 0 for a mode map.
pub fn trace_folds(map: &Map) -> Folds {
    let sys = match map.what {
        What::Rhythmicity => FoldSystem::Drift,
        What::Modes => FoldSystem::Fpk,
    };
    let trans = map.transitions();
    let plane = &map.plane;
    // Locate a curve point for every transition, in parallel (independent and deterministic).
    let located: Vec<Option<(f64, f64, f64)>> = trans
        .par_iter()
        .map(|&(p, q)| {
            let (a, b) = (frac(map, p), frac(map, q));
            let (s, x) = bisect_transition(plane, map.what, a, b);
            let probe = System::new(plane, sys, 1.0);
            x.iter()
                .find_map(|&x| probe.locate_on_segment(a, b, s, x))
                .map(|v| (v[0], v[1], v[2]))
        })
        .collect();
    let seeds: Vec<(f64, f64, f64)> = located.iter().flatten().copied().collect();
    finish(map, sys, trans.len(), seeds)
}

/// The paper's printed construction of the P-bifurcation set (Eq. 36 with the printed Eq. 37),
/// traced over a mode map's plane; paper variant only. Seeds: grid neighbours where h changes
/// sign at the same-index positive root of the printed Eq. 37.
pub fn trace_printed_eq37(map: &Map) -> Result<Folds> {
    let plane = &map.plane;
    if plane.variant != Variant::Paper || map.what != What::Modes {
        return Err(Error::Undefined {
            what: "printed Eq. 37 curves",
            why: "they belong to the paper variant's mode maps".into(),
        });
    }
    let k = &plane.kernel;
    // On a subgrid of at most ~200 × 200 points (root isolation per point is costly): the
    // positive roots of the printed Eq. 37 and the sign of h there. Continuation then follows
    // each curve at the full map's resolution.
    let stride = |n: usize| (n - 1).div_ceil(200).max(1);
    let (sx, sy) = (stride(plane.x.count), stride(plane.y.count));
    let ix_list: Vec<usize> = (0..plane.x.count).step_by(sx).collect();
    let iy_list: Vec<usize> = (0..plane.y.count).step_by(sy).collect();
    let (nx, ny) = (ix_list.len(), iy_list.len());
    let table: Vec<Vec<(f64, bool)>> = (0..nx * ny)
        .into_par_iter()
        .map(|i| {
            let (ix, iy) = (ix_list[i % nx], iy_list[i / nx]);
            let p = plane.point(plane.x.value(ix), plane.y.value(iy));
            let e = k.printed_eq37(&p);
            let h = k.coefficients(&p, What::Modes);
            Polynomial::new(e.slice().to_vec())
                .real_roots(0.0, f64::INFINITY)
                .into_iter()
                .map(|r| (r.x, h.eval(r.x) > 0.0))
                .collect()
        })
        .collect();
    let mut pairs = Vec::new();
    for jy in 0..ny {
        for jx in 0..nx {
            let a = &table[jy * nx + jx];
            for (kx, ky) in [(jx + 1, jy), (jx, jy + 1)] {
                if kx >= nx || ky >= ny {
                    continue;
                }
                let b = &table[ky * nx + kx];
                if a.len() != b.len() {
                    continue;
                }
                for (ra, rb) in a.iter().zip(b) {
                    if ra.1 != rb.1 {
                        pairs.push((
                            (ix_list[jx], iy_list[jy]),
                            (ix_list[kx], iy_list[ky]),
                            0.5 * (ra.0 + rb.0),
                        ));
                    }
                }
            }
        }
    }
    let sys = FoldSystem::FpkPrinted;
    let located: Vec<Option<(f64, f64, f64)>> = pairs
        .par_iter()
        .map(|&(p, q, x)| {
            let probe = System::new(plane, sys, 1.0);
            probe
                .locate_on_segment(frac(map, p), frac(map, q), 0.5, x)
                .map(|v| (v[0], v[1], v[2]))
        })
        .collect();
    let seeds: Vec<(f64, f64, f64)> = located.iter().flatten().copied().collect();
    Ok(finish(map, sys, pairs.len(), seeds))
}

fn finish(map: &Map, sys: FoldSystem, n_seeds: usize, seeds: Vec<(f64, f64, f64)>) -> Folds {
    let plane = &map.plane;
    let unlocated = n_seeds - seeds.len();
    let xs = seeds.iter().map(|s| s.0).fold(0.0f64, f64::max).max(1e-300);
    let system = System::new(plane, sys, xs);
    let opt = TraceOptions::for_map(map);
    let mut curves: Vec<FoldCurve> = Vec::new();
    let mut all: Vec<[f64; 3]> = Vec::new();
    let mut cusps: Vec<[f64; 3]> = Vec::new();
    let near = 2.0 * opt.max_step;
    for &(x, u, w) in &seeds {
        let v = [x / xs, u, w];
        if all.iter().any(|p| norm(sub(*p, v)) < near) {
            continue;
        }
        let (pts, start, end, cs) = system.trace_both(v, &opt);
        for c in cs {
            if !cusps.iter().any(|q| norm(sub(*q, c)) < near) {
                cusps.push(c);
            }
        }
        all.extend(pts.iter().copied());
        curves.push(FoldCurve {
            system: sys,
            points: pts.iter().map(|v| to_point(plane, xs, *v)).collect(),
            start,
            end,
        });
    }
    Folds {
        curves,
        cusps: cusps.iter().map(|v| to_point(plane, xs, *v)).collect(),
        seeds: n_seeds,
        unlocated,
    }
}

fn to_point(plane: &Plane, xs: f64, v: [f64; 3]) -> FoldPoint {
    FoldPoint {
        x: plane.x.at(v[1]),
        y: plane.y.at(v[2]),
        amplitude: (v[0] * xs).max(0.0).sqrt(),
    }
}

/// Scaled residuals of a curve's two equations at a point (|E_i|/Σ|a_k|x^k, the second as
/// x·E′ for folds): what "on the curve to 1e-10" means.
pub fn fold_residuals(plane: &Plane, sys: FoldSystem, p: &FoldPoint) -> [f64; 2] {
    let s = System::new(plane, sys, 1.0);
    s.residual([
        p.amplitude * p.amplitude,
        plane.x.fraction(p.x),
        plane.y.fraction(p.y),
    ])
}

/// The cusp monitor x²E″/Σ|a_k|x^k at a point (zero at a cusp).
pub fn cusp_monitor(plane: &Plane, sys: FoldSystem, p: &FoldPoint) -> f64 {
    let s = System::new(plane, sys, 1.0);
    s.monitor([
        p.amplitude * p.amplitude,
        plane.x.fraction(p.x),
        plane.y.fraction(p.y),
    ])
}
