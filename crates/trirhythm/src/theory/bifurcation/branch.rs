//! One-parameter branch diagrams: every branch of g(x; p) = 0 (limit cycles) or h(x; p) = 0
//! (extrema of P(A)) followed by pseudo-arclength continuation in (x = A², p), through folds.

use super::fold::{one_sided, CurveEnd};
use super::kernel::{Coeffs, Kernel, Key, Point, What};
use crate::error::{Error, Result};
use crate::model::Params;
use crate::theory::averaging::Variant;
use crate::theory::polynomial::Polynomial;
use serde::{Deserialize, Serialize};

/// A point of a branch.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct BranchPoint {
    /// The swept parameter.
    pub param: f64,
    /// Amplitude A.
    pub amplitude: f64,
    /// Stable cycle (df/dA < 0) or mode of P(A) (dm1/dA < 0).
    pub stable: bool,
}

/// One branch, in order along its arclength.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Branch {
    /// Points (folds included).
    pub points: Vec<BranchPoint>,
    /// Why the first point ends it.
    pub start: CurveEnd,
    /// Why the last point ends it.
    pub end: CurveEnd,
}

/// All branches over a parameter interval.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct BranchDiagram {
    /// Swept parameter.
    pub key: String,
    /// Interval start.
    pub start: f64,
    /// Interval end.
    pub stop: f64,
    /// Cycles or modes.
    pub what: What,
    /// The branches.
    pub branches: Vec<Branch>,
    /// Fold (saddle-node) points (param, amplitude).
    pub folds: Vec<(f64, f64)>,
    /// Parameter values where a branch reaches A = 0 (a cycle born at the rest state).
    pub hopf: Vec<f64>,
}

struct Line {
    point: Point,
    key: Key,
    start: f64,
    stop: f64,
    kernel: Kernel,
    what: What,
    xs: f64,
    h: f64,
}

impl Line {
    fn poly(&self, u: f64) -> Coeffs {
        let mut p = self.point;
        p.set(self.key, self.start + (self.stop - self.start) * u);
        self.kernel.coefficients(&p, self.what)
    }

    /// Scaled E and gradient (∂/∂x̂, ∂/∂u), scale frozen at v.
    fn eval(&self, v: [f64; 2]) -> (f64, [f64; 2], f64) {
        let x = v[0] * self.xs;
        let [p, d1, _, s] = self.poly(v[1]).eval_derivs(x);
        let (lo, hi) = one_sided(v[1], self.h);
        let ep = self.poly(hi).eval(x);
        let em = self.poly(lo).eval(x);
        (p / s, [d1 * self.xs / s, (ep - em) / ((hi - lo) * s)], d1)
    }

    fn tangent(&self, v: [f64; 2], prev: Option<[f64; 2]>) -> [f64; 2] {
        let (_, g, _) = self.eval(v);
        let n = (g[0] * g[0] + g[1] * g[1]).sqrt();
        let mut t = [-g[1] / n, g[0] / n];
        if let Some(p) = prev {
            if t[0] * p[0] + t[1] * p[1] < 0.0 {
                t = [-t[0], -t[1]];
            }
        }
        t
    }

    fn newton(
        &self,
        mut v: [f64; 2],
        n: [f64; 2],
        c: f64,
        max_iter: usize,
    ) -> Option<([f64; 2], usize)> {
        for it in 0..max_iter {
            let (f, g, _) = self.eval(v);
            let r = n[0] * v[0] + n[1] * v[1] - c;
            let det = g[0] * n[1] - g[1] * n[0];
            if det == 0.0 || !det.is_finite() {
                return None;
            }
            let d0 = (-f * n[1] + r * g[1]) / det;
            let d1 = (-r * g[0] + f * n[0]) / det;
            v = [v[0] + d0, v[1] + d1];
            if !(v[0].is_finite() && v[1].is_finite()) {
                return None;
            }
            if (d0 * d0 + d1 * d1).sqrt() < 1e-13 * (1.0 + v[0].abs() + v[1].abs()) {
                return Some((v, it + 1));
            }
        }
        None
    }

    fn to_point(&self, v: [f64; 2], stable: bool) -> BranchPoint {
        BranchPoint {
            param: self.start + (self.stop - self.start) * v[1],
            amplitude: (v[0] * self.xs).max(0.0).sqrt(),
            stable,
        }
    }

    fn stable(&self, v: [f64; 2]) -> bool {
        self.eval(v).2 < 0.0
    }

    /// Follow the branch from v0 along t0; folds are recorded and passed.
    fn trace(
        &self,
        v0: [f64; 2],
        t0: [f64; 2],
        ds_max: f64,
        folds: &mut Vec<[f64; 2]>,
    ) -> (Vec<[f64; 2]>, CurveEnd) {
        let mut pts = vec![v0];
        let (mut v, mut t, mut ds) = (v0, t0, ds_max);
        let mut travelled = 0.0;
        let dist =
            |a: [f64; 2], b: [f64; 2]| ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt();
        loop {
            if pts.len() > 200_000 {
                return (pts, CurveEnd::StepLimit);
            }
            let pred = [v[0] + ds * t[0], v[1] + ds * t[1]];
            let step = self
                .newton(pred, t, t[0] * pred[0] + t[1] * pred[1], 8)
                .filter(|(vn, it)| *it <= 6 && dist(*vn, v) < 2.0 * ds);
            let Some((vn, it)) = step else {
                ds *= 0.5;
                if ds < ds_max * 1e-7 {
                    return (pts, CurveEnd::Failed);
                }
                continue;
            };
            let out_u = vn[1] < 0.0 || vn[1] > 1.0;
            if out_u || vn[0] <= 0.0 {
                // Land on the border u = 0/1 or on A = 0.
                let (n, c, end) = if out_u {
                    let b = if vn[1] < 0.0 { 0.0 } else { 1.0 };
                    ([0.0, 1.0], b, CurveEnd::Border)
                } else {
                    ([1.0, 0.0], 0.0, CurveEnd::ZeroAmplitude)
                };
                let fr = (c - (n[0] * v[0] + n[1] * v[1]))
                    / (n[0] * (vn[0] - v[0]) + n[1] * (vn[1] - v[1]));
                let guess = [v[0] + fr * (vn[0] - v[0]), v[1] + fr * (vn[1] - v[1])];
                if let Some((vb, _)) = self.newton(guess, n, c, 20) {
                    if vb[0] >= 0.0 && (0.0..=1.0).contains(&vb[1]) {
                        pts.push(vb);
                    }
                }
                return (pts, end);
            }
            let tn = self.tangent(vn, Some(t));
            // A fold: the tangent's parameter component changes sign.
            if tn[1] * t[1] < 0.0 {
                if let Some(vf) = self.locate_fold(v, t, ds) {
                    pts.push(vf);
                    folds.push(vf);
                }
            }
            travelled += dist(vn, v);
            if travelled > 4.0 * ds_max && dist(vn, v0) < 0.75 * ds {
                pts.push(v0);
                return (pts, CurveEnd::Closed);
            }
            v = vn;
            t = tn;
            pts.push(v);
            if it <= 3 {
                ds = (ds * 1.5).min(ds_max);
            }
        }
    }

    fn locate_fold(&self, v: [f64; 2], t: [f64; 2], ds: f64) -> Option<[f64; 2]> {
        let s0 = self.eval(v).1[0];
        let (mut lo, mut hi) = (0.0, ds);
        let mut best = None;
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            let pred = [v[0] + mid * t[0], v[1] + mid * t[1]];
            let (vm, _) = self.newton(pred, t, t[0] * pred[0] + t[1] * pred[1], 12)?;
            best = Some(vm);
            if (self.eval(vm).1[0] > 0.0) == (s0 > 0.0) {
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
}

/// Allowed range of the continuation's largest step `max_step` (a fraction of the interval):
/// a branch takes at least 1/`max_step` steps, so the lower end bounds the work.
pub const MAX_STEP_RANGE: (f64, f64) = (1e-6, 0.1);

/// All branches of cycles (or P(A) extrema) as `key` runs from `start` to `stop`.
///
/// Seeds: the positive roots at `samples` equally spaced parameter values; each root not on an
/// already traced branch starts a new one, traced both ways through folds until the interval's
/// ends, A = 0, or closure. `max_step` is in units of the interval (and of the largest x = A²),
/// in [`MAX_STEP_RANGE`]; `start` and `stop` are finite, different, and valid values of `key`
/// (errors name them `<key> start`, `<key> stop`); the extrema of P(A) need noise (D > 0) unless
/// D is the swept parameter.
pub fn branches(
    base: &Params,
    variant: Variant,
    what: What,
    key: &str,
    start: f64,
    stop: f64,
    max_step: f64,
) -> Result<BranchDiagram> {
    let k = Key::parse(key)?;
    check_interval(base, variant, key, start, stop)?;
    if what == What::Modes && key != "D" && base.noise_intensity <= 0.0 {
        return Err(Error::invalid(
            "D",
            base.noise_intensity,
            "(0, 1e6] for the extrema of P(A) (no noise, no stationary density)",
        ));
    }
    let (lo, hi) = MAX_STEP_RANGE;
    if !(max_step >= lo && max_step <= hi) {
        return Err(Error::invalid(
            "max_step",
            max_step,
            "[1e-6, 0.1] (the fraction of the interval per continuation step)",
        ));
    }
    let mut line = Line {
        point: Point::new(base)?,
        key: k,
        start,
        stop,
        kernel: Kernel::new(variant),
        what,
        xs: 1.0,
        h: 1e-7,
    };
    let samples = 65;
    let mut seeds: Vec<[f64; 2]> = Vec::new();
    for i in 0..samples {
        let u = i as f64 / (samples - 1) as f64;
        let p = line.poly(u);
        for r in Polynomial::new(p.slice().to_vec()).real_roots(0.0, f64::INFINITY) {
            if !r.double {
                seeds.push([r.x, u]);
            }
        }
    }
    line.xs = seeds
        .iter()
        .map(|s| s[0])
        .fold(0.0f64, f64::max)
        .max(1e-300);
    let ds = max_step;
    let mut all: Vec<[f64; 2]> = Vec::new();
    let mut folds: Vec<[f64; 2]> = Vec::new();
    let mut out = Vec::new();
    for s in seeds {
        let v0 = [s[0] / line.xs, s[1]];
        let near =
            |p: &[f64; 2]| ((p[0] - v0[0]).powi(2) + (p[1] - v0[1]).powi(2)).sqrt() < 2.0 * ds;
        if all.iter().any(near) {
            continue;
        }
        let t0 = line.tangent(v0, None);
        let (fwd, e1) = line.trace(v0, t0, ds, &mut folds);
        let (pts, e0) = if e1 == CurveEnd::Closed {
            (fwd, CurveEnd::Closed)
        } else {
            let (bwd, e0) = line.trace(v0, [-t0[0], -t0[1]], ds, &mut folds);
            let mut pts: Vec<[f64; 2]> = bwd.into_iter().rev().collect();
            pts.pop();
            pts.extend(fwd);
            (pts, e0)
        };
        all.extend(pts.iter().copied());
        out.push(Branch {
            points: pts
                .iter()
                .map(|&v| line.to_point(v, line.stable(v)))
                .collect(),
            start: e0,
            end: e1,
        });
    }
    let mut fold_pts: Vec<(f64, f64)> = Vec::new();
    for f in folds {
        let p = line.to_point(f, false);
        if !fold_pts.iter().any(|q| {
            (q.0 - p.param).abs() < 1e-9 * (stop - start).abs() && (q.1 - p.amplitude).abs() < 1e-7
        }) {
            fold_pts.push((p.param, p.amplitude));
        }
    }
    let hopf = out
        .iter()
        .flat_map(|b| {
            let mut v = Vec::new();
            if b.start == CurveEnd::ZeroAmplitude {
                v.push(b.points[0].param);
            }
            if b.end == CurveEnd::ZeroAmplitude {
                v.push(b.points[b.points.len() - 1].param);
            }
            v
        })
        .collect();
    Ok(BranchDiagram {
        key: key.to_string(),
        start,
        stop,
        what,
        branches: out,
        folds: fold_pts,
        hopf,
    })
}

/// `start` and `stop` of a branch diagram's interval: finite, different, valid values of `key`
/// (for the consistent variant r = 0 excluded); errors name them `<key> start`, `<key> stop`.
fn check_interval(base: &Params, variant: Variant, key: &str, start: f64, stop: f64) -> Result<()> {
    for (end, value) in [("start", start), ("stop", stop)] {
        let name = format!("{key} {end}");
        if !value.is_finite() {
            return Err(Error::invalid(name, value, "a finite number"));
        }
        let p = base.with(key, value).map_err(|e| match e {
            Error::InvalidParameter {
                name: n,
                value,
                allowed,
            } if n == key => Error::invalid(name.clone(), value, allowed),
            e => e,
        })?;
        if variant == Variant::Consistent && p.restitution == 0.0 {
            let n = if key == "r" { name } else { "r".into() };
            return Err(Error::invalid(n, 0.0, "(0, 1] for the consistent variant"));
        }
    }
    if start == stop {
        return Err(Error::invalid(
            format!("{key} stop"),
            stop,
            "a finite number different from the start",
        ));
    }
    Ok(())
}
