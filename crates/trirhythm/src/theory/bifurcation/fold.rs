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
//! of h′ = 0) for comparison.

use super::grid::{Map, Plane};
use super::kernel::{sturm_count_positive, Coeffs, What};
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

/// All curves traced on a map.
#[derive(Debug, Clone, Serialize, Deserialize)]
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

/// The equations in scaled unknowns v = (x/xs, u, w), u and w the fractions of the axes.
pub(crate) struct System<'a> {
    plane: &'a Plane,
    sys: FoldSystem,
    xs: f64,
    /// Finite-difference step in the axis fractions.
    h: f64,
}

const NEWTON_TOL: f64 = 1e-13;

impl<'a> System<'a> {
    pub(crate) fn new(plane: &'a Plane, sys: FoldSystem, xs: f64) -> Self {
        System {
            plane,
            sys,
            xs,
            h: 1e-7,
        }
    }

    fn polys(&self, u: f64, w: f64) -> (Coeffs, Option<Coeffs>) {
        let p = self.plane.point_at(u, w);
        let k = &self.plane.kernel;
        let e1 = k.coefficients(&p, self.sys.what());
        let e2 = match self.sys {
            FoldSystem::FpkPrinted => Some(k.printed_eq37(&p)),
            _ => None,
        };
        (e1, e2)
    }

    /// Unscaled (E1, E2) at x and the scales (Σ|a_i|x^i of each).
    fn raw(&self, x: f64, u: f64, w: f64) -> ([f64; 2], [f64; 2]) {
        let (e1, e2) = self.polys(u, w);
        let [p, d1, _, s] = e1.eval_derivs(x);
        match e2 {
            None => {
                // x·E1′ = Σ i a_i x^i, scaled like E1.
                ([p, x * d1], [s, s])
            }
            Some(e2) => {
                let [q, _, _, s2] = e2.eval_derivs(x);
                ([p, q], [s, s2])
            }
        }
    }

    /// Scaled residuals and the scales used.
    pub(crate) fn residual(&self, v: [f64; 3]) -> [f64; 2] {
        let (r, s) = self.raw(v[0] * self.xs, v[1], v[2]);
        [r[0] / s[0], r[1] / s[1]]
    }

    /// Residuals with frozen scales, and their Jacobian (2 × 3).
    fn jacobian(&self, v: [f64; 3]) -> ([f64; 2], [[f64; 3]; 2]) {
        let x = v[0] * self.xs;
        let (e1, e2) = self.polys(v[1], v[2]);
        let [p, d1, d2, s] = e1.eval_derivs(x);
        let (f, dx, scale) = match e2 {
            None => ([p, x * d1], [d1, d1 + x * d2], [s, s]),
            Some(e2) => {
                let [q, q1, _, s2] = e2.eval_derivs(x);
                ([p, q], [d1, q1], [s, s2])
            }
        };
        let mut j = [[0.0; 3]; 2];
        for i in 0..2 {
            j[i][0] = dx[i] * self.xs / scale[i];
        }
        // Central differences inside the plane, one-sided at its borders: parameters are never
        // evaluated outside (where they may be invalid, and where σ1 has a kink at τ = 0).
        for col in [1usize, 2] {
            let (lo, hi) = one_sided(v[col], self.h);
            let at = |u: f64| {
                let (a, b) = if col == 1 { (u, v[2]) } else { (v[1], u) };
                self.raw(x, a, b).0
            };
            let (fp, fm) = (at(hi), at(lo));
            for i in 0..2 {
                j[i][col] = (fp[i] - fm[i]) / ((hi - lo) * scale[i]);
            }
        }
        ([f[0] / scale[0], f[1] / scale[1]], j)
    }

    /// x²E1″/S: the cusp monitor (zero where three roots merge).
    fn monitor(&self, v: [f64; 3]) -> f64 {
        let x = v[0] * self.xs;
        let (e1, _) = self.polys(v[1], v[2]);
        let [_, _, d2, s] = e1.eval_derivs(x);
        x * x * d2 / s
    }

    /// Unit tangent (null vector of the Jacobian), oriented along `prev` when given.
    fn tangent(&self, v: [f64; 3], prev: Option<[f64; 3]>) -> [f64; 3] {
        let (_, j) = self.jacobian(v);
        let mut t = cross(j[0], j[1]);
        let n = norm(t);
        for c in &mut t {
            *c /= n;
        }
        if let Some(p) = prev {
            if dot(t, p) < 0.0 {
                for c in &mut t {
                    *c = -*c;
                }
            }
        }
        t
    }

    /// Newton on {E1 = 0, E2 = 0, n·v = c}: the point and the iteration count.
    fn newton(
        &self,
        mut v: [f64; 3],
        n: [f64; 3],
        c: f64,
        max_iter: usize,
    ) -> Option<([f64; 3], usize)> {
        for it in 0..max_iter {
            let (f, j) = self.jacobian(v);
            let g = dot(n, v) - c;
            let a = [j[0], j[1], n];
            let dv = solve3(a, [-f[0], -f[1], -g])?;
            for i in 0..3 {
                v[i] += dv[i];
            }
            if !v.iter().all(|c| c.is_finite()) {
                return None;
            }
            if norm(dv) < NEWTON_TOL * (1.0 + norm(v)) {
                let r = self.residual(v);
                if r[0].abs() < 1e-11 && r[1].abs() < 1e-11 {
                    return Some((v, it + 1));
                }
            }
        }
        None
    }
}

/// Finite-difference abscissae around u with step h, kept inside [0, 1].
pub(crate) fn one_sided(u: f64, h: f64) -> (f64, f64) {
    if u - h < 0.0 {
        (u, u + h)
    } else if u + h > 1.0 {
        (u - h, u)
    } else {
        (u - h, u + h)
    }
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn axpy(a: [f64; 3], s: f64, t: [f64; 3]) -> [f64; 3] {
    [a[0] + s * t[0], a[1] + s * t[1], a[2] + s * t[2]]
}

/// Gaussian elimination with partial pivoting on a 3 × 3 system.
#[allow(clippy::needless_range_loop)] // index form mirrors the textbook algorithm
fn solve3(mut a: [[f64; 3]; 3], mut b: [f64; 3]) -> Option<[f64; 3]> {
    for k in 0..3 {
        let p = (k..3).max_by(|&i, &j| a[i][k].abs().total_cmp(&a[j][k].abs()))?;
        if a[p][k] == 0.0 || !a[p][k].is_finite() {
            return None;
        }
        a.swap(k, p);
        b.swap(k, p);
        for i in k + 1..3 {
            let m = a[i][k] / a[k][k];
            for j in k..3 {
                a[i][j] -= m * a[k][j];
            }
            b[i] -= m * b[k];
        }
    }
    let mut x = [0.0; 3];
    for k in (0..3).rev() {
        let s: f64 = (k + 1..3).map(|j| a[k][j] * x[j]).sum();
        x[k] = (b[k] - s) / a[k][k];
    }
    Some(x)
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

struct Traced {
    points: Vec<[f64; 3]>,
    end: CurveEnd,
    cusp: Option<[f64; 3]>,
}

impl System<'_> {
    fn inside(v: [f64; 3]) -> bool {
        const E: f64 = 1e-12;
        v[1] >= -E && v[1] <= 1.0 + E && v[2] >= -E && v[2] <= 1.0 + E
    }

    /// Follow the curve from v0 in the direction t0.
    fn trace(&self, v0: [f64; 3], t0: [f64; 3], opt: &TraceOptions) -> Traced {
        let ds_max = opt.max_step;
        let ds_min = ds_max * 1e-6;
        let mut ds = ds_max;
        let mut v = v0;
        let mut t = t0;
        let mut pts = vec![v0];
        let watch_cusp = self.sys != FoldSystem::FpkPrinted;
        let mut m_prev = self.monitor(v0);
        let mut travelled = 0.0;
        loop {
            if pts.len() >= opt.max_points {
                return Traced {
                    points: pts,
                    end: CurveEnd::StepLimit,
                    cusp: None,
                };
            }
            let pred = axpy(v, ds, t);
            let step = self
                .newton(pred, t, dot(t, pred), 8)
                .filter(|(vn, it)| *it <= 6 && norm(sub(*vn, v)) < 2.0 * ds);
            let Some((vn, it)) = step else {
                ds *= 0.5;
                if ds < ds_min {
                    // Stuck on the plane's edge (a seed there, stepping outward) is an end at
                    // the border, not a failure.
                    let on_edge = [v[1], v[2]]
                        .iter()
                        .any(|&c| c.abs() < 1e-9 || (c - 1.0).abs() < 1e-9);
                    return Traced {
                        points: pts,
                        end: if on_edge {
                            CurveEnd::Border
                        } else {
                            CurveEnd::Failed
                        },
                        cusp: None,
                    };
                }
                continue;
            };
            // Leaving the plane: land exactly on the border.
            if !Self::inside(vn) {
                let (i, b) = if vn[1] < 0.0 {
                    (1, 0.0)
                } else if vn[1] > 1.0 {
                    (1, 1.0)
                } else if vn[2] < 0.0 {
                    (2, 0.0)
                } else {
                    (2, 1.0)
                };
                let frac = (b - v[i]) / (vn[i] - v[i]);
                let guess = axpy(v, frac, sub(vn, v));
                let mut e = [0.0; 3];
                e[i] = 1.0;
                if let Some((vb, _)) = self.newton(guess, e, b, 12) {
                    pts.push(vb);
                }
                return Traced {
                    points: pts,
                    end: CurveEnd::Border,
                    cusp: None,
                };
            }
            if vn[0] <= 0.0 {
                return Traced {
                    points: pts,
                    end: CurveEnd::ZeroAmplitude,
                    cusp: None,
                };
            }
            if vn[0] > 64.0 {
                return Traced {
                    points: pts,
                    end: CurveEnd::Unbounded,
                    cusp: None,
                };
            }
            if watch_cusp {
                let m = self.monitor(vn);
                if m != 0.0 && m_prev != 0.0 && (m > 0.0) != (m_prev > 0.0) {
                    let vc = self.locate_cusp(v, t, ds, m_prev);
                    if let Some(vc) = vc {
                        pts.push(vc);
                    }
                    return Traced {
                        points: pts,
                        end: CurveEnd::Cusp,
                        cusp: vc,
                    };
                }
                m_prev = m;
            }
            travelled += norm(sub(vn, v));
            let back = norm(sub(vn, v0));
            if travelled > 4.0 * ds_max && back < 0.75 * ds {
                pts.push(v0);
                return Traced {
                    points: pts,
                    end: CurveEnd::Closed,
                    cusp: None,
                };
            }
            t = self.tangent(vn, Some(t));
            v = vn;
            pts.push(v);
            if it <= 3 {
                ds = (ds * 1.5).min(ds_max);
            }
        }
    }

    /// The cusp between v (monitor sign `m0`) and the next point, by bisection on the step.
    fn locate_cusp(&self, v: [f64; 3], t: [f64; 3], ds: f64, m0: f64) -> Option<[f64; 3]> {
        let (mut lo, mut hi) = (0.0, ds);
        let mut best = None;
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            let pred = axpy(v, mid, t);
            let (vm, _) = self.newton(pred, t, dot(t, pred), 12)?;
            best = Some(vm);
            let m = self.monitor(vm);
            if (m > 0.0) == (m0 > 0.0) {
                lo = mid;
            } else {
                hi = mid;
            }
            if hi - lo < 1e-14 {
                break;
            }
        }
        best
    }

    /// Trace both ways from a located point.
    fn trace_both(
        &self,
        v0: [f64; 3],
        opt: &TraceOptions,
    ) -> (Vec<[f64; 3]>, CurveEnd, CurveEnd, Vec<[f64; 3]>) {
        let t0 = self.tangent(v0, None);
        let fwd = self.trace(v0, t0, opt);
        let mut cusps: Vec<[f64; 3]> = fwd.cusp.into_iter().collect();
        if fwd.end == CurveEnd::Closed {
            return (fwd.points, CurveEnd::Closed, CurveEnd::Closed, cusps);
        }
        let bwd = self.trace(v0, [-t0[0], -t0[1], -t0[2]], opt);
        cusps.extend(bwd.cusp);
        let mut pts: Vec<[f64; 3]> = bwd.points.into_iter().rev().collect();
        pts.pop(); // v0 again
        pts.extend(fwd.points);
        (pts, bwd.end, fwd.end, cusps)
    }

    /// A point of the curve on the segment from a to b (axis fractions), from a guess x.
    fn locate_on_segment(&self, a: [f64; 2], b: [f64; 2], s: f64, x: f64) -> Option<[f64; 3]> {
        let n = [0.0, -(b[1] - a[1]), b[0] - a[0]];
        let c = n[1] * a[0] + n[2] * a[1];
        let guess = [
            x / self.xs,
            a[0] + s * (b[0] - a[0]),
            a[1] + s * (b[1] - a[1]),
        ];
        let (v, _) = self.newton(guess, n, c, 30)?;
        // Stay near the segment.
        let d = [b[0] - a[0], b[1] - a[1]];
        let sv = ((v[1] - a[0]) * d[0] + (v[2] - a[1]) * d[1]) / (d[0] * d[0] + d[1] * d[1]);
        (v[0] > 0.0 && (-0.5..=1.5).contains(&sv)).then_some(v)
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
