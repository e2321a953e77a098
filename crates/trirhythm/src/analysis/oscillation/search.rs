//! The simulated boundary at one abscissa: regula falsi (Illinois) on the growth rate with a
//! straddling pair after each estimate, or bisection on its sign (module docs of [`super`]).

use super::growth::{grow, Cache, Classifier};
use super::{BoundaryPoint, Plane, Refinement, Search, Side};
use crate::error::Result;
use crate::monitor::Monitor;

/// The simulated boundary at abscissa `x` of `plane` (module docs of [`super`]); `monitor`
/// may stop the search, also inside a simulation.
pub(super) fn simulated(
    plane: &Plane,
    x: f64,
    c: &Classifier,
    search: &Search,
    monitor: &dyn Monitor,
) -> Result<BoundaryPoint> {
    let (lo, hi) = plane.y_range;
    let mut cache: Cache = None;
    let mut simulations = 0;
    let mut unclear = 0;
    let mut eval = |y: f64| -> Result<f64> {
        let g = grow(&plane.problem_at(x, y)?, c, &mut cache, monitor)?;
        simulations += 1;
        unclear += usize::from(!g.clear);
        Ok(g.rate)
    };
    let (fa0, fb0) = (eval(lo)?, eval(hi)?);
    let (ga, gb) = (fa0 > 0.0, fb0 > 0.0);
    if ga == gb {
        return Ok(BoundaryPoint {
            x,
            side: if ga { Side::Oscillates } else { Side::Rests },
            y: f64::NAN,
            y_lo: f64::NAN,
            y_hi: f64::NAN,
            oscillates_above: gb,
            simulations,
            unclear,
        });
    }
    let ((mut a, mut fa), (mut b, mut fb)) = ((lo, fa0), (hi, fb0));
    let secant = |a: f64, fa: f64, b: f64, fb: f64| {
        let c = a - fa * (b - a) / (fb - fa);
        if c.is_finite() {
            c.clamp(a, b)
        } else {
            0.5 * (a + b)
        }
    };
    let floor = 1e-12 * (hi - lo);
    // Illinois: an end kept twice in a row has its rate halved in the secant
    let (mut wa, mut wb) = (1.0, 1.0);
    let mut last_moved = (false, false);
    let mut stalls = 0;
    for _ in 0..200 {
        let width = b - a;
        let est = secant(a, wa * fa, b, wb * fb);
        let target = (search.tolerance * est.abs()).max(floor);
        if width <= target {
            break;
        }
        let mut probes = Vec::with_capacity(2);
        if search.refinement == Refinement::Bisection || stalls >= 2 {
            probes.push(0.5 * (a + b));
        } else {
            probes.push(est - 0.45 * target);
            probes.push(est + 0.45 * target);
        }
        let mut moved = (false, false);
        for y in probes {
            if !(y > a && y < b) {
                continue;
            }
            let f = eval(y)?;
            if (f > 0.0) == ga {
                (a, fa, wa) = (y, f, 1.0);
                moved.0 = true;
            } else {
                (b, fb, wb) = (y, f, 1.0);
                moved.1 = true;
                break;
            }
        }
        match moved {
            (true, false) if last_moved == moved => wb *= 0.5,
            (false, true) if last_moved == moved => wa *= 0.5,
            _ => {}
        }
        last_moved = moved;
        stalls = if b - a > 0.5 * width { stalls + 1 } else { 0 };
    }
    Ok(BoundaryPoint {
        x,
        side: Side::Boundary,
        y: secant(a, fa, b, fb),
        y_lo: a,
        y_hi: b,
        oscillates_above: gb,
        simulations,
        unclear,
    })
}
