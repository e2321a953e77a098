//! Two-parameter classification maps: stable-cycle counts or P(A) mode counts on a grid.

use super::kernel::{Kernel, Key, Point, What};
use crate::error::{Error, Result};
use crate::model::Params;
use crate::theory::averaging::Variant;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::sync::atomic::{AtomicUsize, Ordering};

/// One axis of a map: `count` equally spaced values of a parameter from `start` to `stop`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Axis {
    /// Parameter key (see [`crate::model::KEYS`]).
    pub key: String,
    /// First value.
    pub start: f64,
    /// Last value.
    pub stop: f64,
    /// Number of values (≥ 2).
    pub count: usize,
}

impl Axis {
    /// An axis; the key must be known, the range finite and non-empty, `count` in
    /// [2, [`MAX_PLANE_POINTS`]/2] (a plane has at least two values on its other axis).
    pub fn new(key: &str, start: f64, stop: f64, count: usize) -> Result<Axis> {
        Key::parse(key)?;
        if !start.is_finite() {
            return Err(Error::invalid(
                format!("{key} start"),
                start,
                "a finite number",
            ));
        }
        if !stop.is_finite() || stop == start {
            return Err(Error::invalid(
                format!("{key} stop"),
                stop,
                "a finite number different from the start",
            ));
        }
        if !(2..=MAX_PLANE_POINTS / 2).contains(&count) {
            return Err(Error::invalid(
                format!("{key} count"),
                count as f64,
                format!("[2, {:e}]", (MAX_PLANE_POINTS / 2) as f64),
            ));
        }
        Ok(Axis {
            key: key.to_string(),
            start,
            stop,
            count,
        })
    }

    /// The i-th value.
    #[inline]
    pub fn value(&self, i: usize) -> f64 {
        if i + 1 == self.count {
            return self.stop;
        }
        self.start + (self.stop - self.start) * i as f64 / (self.count - 1) as f64
    }

    /// All values.
    pub fn values(&self) -> Vec<f64> {
        (0..self.count).map(|i| self.value(i)).collect()
    }

    /// Value at the fraction u ∈ [0, 1] of the range.
    #[inline]
    pub fn at(&self, u: f64) -> f64 {
        self.start + (self.stop - self.start) * u
    }

    /// Fraction of the range at value v.
    #[inline]
    pub fn fraction(&self, v: f64) -> f64 {
        (v - self.start) / (self.stop - self.start)
    }
}

/// A parameter plane: base parameters, two axes, a variant. Validated at construction (every
/// parameter constraint is an interval, so checking the four corners covers the plane).
#[derive(Debug, Clone)]
pub struct Plane {
    /// Parameters not swept.
    pub base: Params,
    /// Horizontal axis.
    pub x: Axis,
    /// Vertical axis.
    pub y: Axis,
    /// Formula variant.
    pub variant: Variant,
    pub(crate) kx: Key,
    pub(crate) ky: Key,
    pub(crate) point: Point,
    pub(crate) kernel: Kernel,
}

/// Most points of one plane (counts held as one byte each: 100 MB).
pub const MAX_PLANE_POINTS: usize = 100_000_000;

impl Plane {
    /// Check the axes against each other and the parameters at the plane's corners.
    pub fn new(base: &Params, x: Axis, y: Axis, variant: Variant) -> Result<Plane> {
        let kx = Key::parse(&x.key)?;
        let ky = Key::parse(&y.key)?;
        if kx == ky {
            return Err(Error::invalid(
                format!("{} (y axis)", y.key),
                y.start,
                "a parameter different from the x axis",
            ));
        }
        base.validate()?;
        let points = x.count as u128 * y.count as u128;
        if points > MAX_PLANE_POINTS as u128 {
            return Err(Error::invalid(
                "points (x count × y count)",
                points as f64,
                format!("at most {MAX_PLANE_POINTS:e} points in all (x count × y count)"),
            ));
        }
        for vx in [x.start, x.stop] {
            for vy in [y.start, y.stop] {
                let p = base.with(&x.key, vx)?.with(&y.key, vy)?;
                if variant == Variant::Consistent && p.restitution == 0.0 {
                    return Err(Error::invalid(
                        "r",
                        0.0,
                        "(0, 1] for the consistent variant",
                    ));
                }
            }
        }
        let point = Point::new(base)?;
        Ok(Plane {
            base: base.clone(),
            x,
            y,
            variant,
            kx,
            ky,
            point,
            kernel: Kernel::new(variant),
        })
    }

    /// The point at parameter values (px, py).
    #[inline]
    pub fn point(&self, px: f64, py: f64) -> Point {
        let mut p = self.point;
        p.set(self.kx, px);
        p.set(self.ky, py);
        p
    }

    /// The point at fractions (u, v) of the axes.
    #[inline]
    pub fn point_at(&self, u: f64, v: f64) -> Point {
        self.point(self.x.at(u), self.y.at(v))
    }

    /// Full parameters at (px, py) (validated).
    pub fn params(&self, px: f64, py: f64) -> Result<Params> {
        self.base.with(&self.x.key, px)?.with(&self.y.key, py)
    }

    /// The kernel.
    pub fn kernel(&self) -> &Kernel {
        &self.kernel
    }
}

/// A classification map: counts on the grid, row-major (`counts[iy * nx + ix]`).
#[derive(Debug, Clone)]
pub struct Map {
    /// The plane.
    pub plane: Plane,
    /// Which count.
    pub what: What,
    /// Stable-cycle or mode count at each grid point.
    pub counts: Vec<u8>,
}

impl Map {
    /// Count at grid indices.
    #[inline]
    pub fn count(&self, ix: usize, iy: usize) -> u8 {
        self.counts[iy * self.plane.x.count + ix]
    }

    /// How many grid points have each count 0, 1, 2, 3, ≥ 4.
    pub fn histogram(&self) -> [usize; 5] {
        let mut h = [0; 5];
        for &c in &self.counts {
            h[(c as usize).min(4)] += 1;
        }
        h
    }

    /// Pairs of neighbouring grid points (horizontal or vertical) whose counts differ.
    pub fn transitions(&self) -> Vec<((usize, usize), (usize, usize))> {
        let (nx, ny) = (self.plane.x.count, self.plane.y.count);
        let mut out = Vec::new();
        for iy in 0..ny {
            for ix in 0..nx {
                let c = self.count(ix, iy);
                if ix + 1 < nx && self.count(ix + 1, iy) != c {
                    out.push(((ix, iy), (ix + 1, iy)));
                }
                if iy + 1 < ny && self.count(ix, iy + 1) != c {
                    out.push(((ix, iy), (ix, iy + 1)));
                }
            }
        }
        out
    }
}

/// Classify every grid point of the plane, in parallel (rows are independent, so the result
/// does not depend on the thread count). `progress(rows_done, rows_total)` is called after each
/// row from the worker threads.
pub fn classify(plane: &Plane, what: What, progress: &(dyn Fn(usize, usize) + Sync)) -> Map {
    let (nx, ny) = (plane.x.count, plane.y.count);
    let mut counts = vec![0u8; nx * ny];
    let done = AtomicUsize::new(0);
    let xs = plane.x.values();
    counts.par_chunks_mut(nx).enumerate().for_each(|(iy, row)| {
        let vy = plane.y.value(iy);
        let mut p = plane.point;
        p.set(plane.ky, vy);
        for (cell, &vx) in row.iter_mut().zip(&xs) {
            p.set(plane.kx, vx);
            *cell = plane.kernel.stable_count(&p, what).min(255) as u8;
        }
        let d = done.fetch_add(1, Ordering::Relaxed) + 1;
        progress(d, ny);
    });
    Map {
        plane: plane.clone(),
        what,
        counts,
    }
}
