//! Scalar Caputo problems D^α y = f(t, y) on the oscillator's predictor–corrector and memory.
//!
//! Equation: y(t) = y₀ + J^α f(·, y)(t), α ∈ (0, 1].
//!
//! Method: the corrector's sum with the predictor's f_{n+1} replaced by f_n; only corrected
//! values enter the memory ([`History`]).
//!
//! Reference: Diethelm, Ford & Freed, Nonlinear Dyn. 29 (2002) 3–22 (PECE product-trapezoidal
//! method).
//!
//! Tests: `scalar_solver_at_order_one_is_the_trapezoidal_predictor_corrector` (unit);
//! `tests/convergence.rs` (order of accuracy on known answers).

use super::{History, Memory, Piece, DEFAULT_WINDOW};
use crate::error::{Error, Result};

/// Solve the scalar Caputo problem D^α y = f(t, y), y(0) = y₀, α ∈ (0, 1], on the grid
/// t_n = n·dt, n = 0..=steps, with the same predictor–corrector and memory as the oscillator
/// (see [`crate::engine::Stepper`]): the predictor replaces f_{n+1} by f_n in the corrector's sum
/// (constant extrapolation of the composite f(t, y(t)), which stays smooth when y does not); only corrected values are stored (at α = 1: the trapezoidal rule in integral form,
/// corrected once from an Euler predictor). Returns y at every node.
///
/// Arguments: `alpha` ∈ (0, 1], `y0` finite, `dt` > 0 finite, `steps` ≤ 10⁸ (the nodes are
/// kept), dt·steps finite; an SOE memory's tolerance as [`crate::engine::kernel::SoeKernel`].
pub fn solve_scalar(
    alpha: f64,
    f: &dyn Fn(f64, f64) -> f64,
    y0: f64,
    dt: f64,
    steps: usize,
    memory: Memory,
) -> Result<Vec<f64>> {
    if !(alpha > 0.0 && alpha <= 1.0) {
        return Err(Error::invalid("alpha", alpha, "(0, 1]"));
    }
    if !y0.is_finite() {
        return Err(Error::invalid("y0", y0, "a finite number"));
    }
    check_steps(dt, steps)?;
    let t_end = dt * steps as f64;
    let mut conv = History::new(alpha, dt, t_end, memory, DEFAULT_WINDOW)?;
    let mut ys = Vec::with_capacity(steps + 1);
    ys.push(y0);
    let mut fy = f(0.0, y0);
    let (wl, wr) = conv.current_weights();
    for n in 0..steps {
        let t1 = (n + 1) as f64 * dt;
        let base = y0 + conv.value() + wl * fy;
        let yp = base + wr * fy;
        let y1 = base + wr * f(t1, yp);
        if !y1.is_finite() {
            return Err(Error::Overflow {
                what: "scalar fractional solve",
                at: format!("t = {t1}"),
                value: y1,
            });
        }
        let f1 = f(t1, y1);
        conv.push(Piece {
            left: fy,
            right: f1,
            split: None,
        });
        fy = f1;
        ys.push(y1);
    }
    Ok(ys)
}

/// Most steps of [`solve_scalar`] and [`super::probe_memory`] (the scalar solve keeps every
/// node: 800 MB at the bound).
pub(crate) const MAX_SCALAR_STEPS: usize = 100_000_000;

/// `dt` > 0 finite, `steps` ≤ [`MAX_SCALAR_STEPS`], and their product (the horizon) finite.
pub(super) fn check_steps(dt: f64, steps: usize) -> Result<()> {
    if !(dt > 0.0 && dt.is_finite()) {
        return Err(Error::invalid("dt", dt, "(0, ∞), finite"));
    }
    if steps > MAX_SCALAR_STEPS {
        return Err(Error::invalid("steps", steps as f64, "[0, 1e8]"));
    }
    let t_end = dt * steps as f64;
    if !t_end.is_finite() {
        return Err(Error::invalid(
            "dt",
            dt,
            format!("a step whose {steps} steps end at a finite time"),
        ));
    }
    Ok(())
}
