//! Pseudo-arclength continuation of one fold curve in (x = A², p1, p2).
//!
//! Equation: the two equations of a [`FoldSystem`] (g = g′ = 0, h = h′ = 0 or the printed
//! Eq. 36–37) in the scaled unknowns v = (x/xs, u, w), u and w the fractions of the axes.
//!
//! Method: predictor along the tangent (the cross product of the two gradient rows), corrector
//! by Newton on the two equations plus the arclength condition (3 × 3, partial pivoting), the
//! step halved when Newton is slow or fails; cusps located by bisection on the sign of the
//! monitor g″ along the curve. Parameter derivatives are central differences (one-sided at the
//! plane's borders); x derivatives are analytic.
//!
//! Reference: Kuznetsov, *Elements of Applied Bifurcation Theory*, ch. 10.
//!
//! Tests: `tests/bifurcation.rs` (points on the curve to 1e-10, the analytic cusp).

use super::{CurveEnd, FoldSystem, TraceOptions};
use crate::theory::bifurcation::grid::Plane;
use crate::theory::bifurcation::kernel::Coeffs;

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
    pub(super) fn monitor(&self, v: [f64; 3]) -> f64 {
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

pub(super) fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

pub(super) fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
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
    pub(super) fn trace_both(
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
    pub(super) fn locate_on_segment(
        &self,
        a: [f64; 2],
        b: [f64; 2],
        s: f64,
        x: f64,
    ) -> Option<[f64; 3]> {
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
