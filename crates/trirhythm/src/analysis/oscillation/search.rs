//! The simulated boundary at one abscissa: regula falsi (Illinois) on the growth rate with a
//! straddling pair after each estimate, or bisection on its sign (module docs of [`super`]).
//!
//! The simulations a step of the search may need are run together in lanes
//! ([`Classifier::lanes`]): both ends of the interval, and both probes of a straddling pair
//! (the second is needed unless the first moves the upper end; it is run beside the first all
//! the same, and its result dropped when the sequence does not reach it). The sequence of
//! probes, the brackets and the simulation counts are those of one simulation after the other.

use super::growth::{grow_all, Cache, Classifier, Growth};
use super::{BoundaryPoint, Plane, Refinement, Search, Side};
use crate::engine::Problem;
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
    let mut cache = Cache::default();
    let mut simulations = 0;
    let mut unclear = 0;
    let speculate = c.lanes.width()? > 1;
    // runs evaluated ahead of the sequence, by y
    let mut ahead = vec![];
    type Ahead = Vec<(f64, Result<Growth>)>;
    let mut eval = |y: f64, ahead: &mut Ahead, cache: &mut Cache| -> Result<f64> {
        let g = match ahead.iter().position(|(z, _)| z.to_bits() == y.to_bits()) {
            Some(k) => ahead.remove(k).1,
            None => grow_at(plane, x, &[y], c, cache, monitor)?.remove(0),
        }?;
        simulations += 1;
        unclear += usize::from(!g.clear);
        Ok(g.rate)
    };
    if speculate {
        let ends = grow_at(plane, x, &[lo, hi], c, &mut cache, monitor)?;
        ahead.extend([lo, hi].into_iter().zip(ends));
    }
    let fa0 = eval(lo, &mut ahead, &mut cache)?;
    let fb0 = eval(hi, &mut ahead, &mut cache)?;
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
        ahead.clear();
        if speculate {
            // the probes this step may evaluate, run together: the first if inside (a, b),
            // the second if inside it with a moved to the first
            let mut ask = vec![];
            let mut low = a;
            for &y in &probes {
                if y > low && y < b {
                    ask.push(y);
                    low = y;
                }
            }
            if ask.len() > 1 {
                let runs = grow_at(plane, x, &ask, c, &mut cache, monitor)?;
                ahead = ask.into_iter().zip(runs).collect();
            }
        }
        let mut moved = (false, false);
        for y in probes {
            if !(y > a && y < b) {
                continue;
            }
            let f = eval(y, &mut ahead, &mut cache)?;
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

/// The growth runs at (x, y) for each of `ys`, together in lanes ([`grow_all`]); each result
/// (or error, a parameter set out of range included) is that of one run alone.
pub(super) fn grow_at(
    plane: &Plane,
    x: f64,
    ys: &[f64],
    c: &Classifier,
    cache: &mut Cache,
    monitor: &dyn Monitor,
) -> Result<Vec<Result<Growth>>> {
    let problems: Vec<Result<Problem>> = ys.iter().map(|&y| plane.problem_at(x, y)).collect();
    let valid: Vec<Problem> = problems.iter().flatten().cloned().collect();
    let mut runs = grow_all(&valid, c, cache, monitor)?.into_iter();
    Ok(problems
        .into_iter()
        .map(|p| {
            p?;
            runs.next().expect("one run per valid problem")
        })
        .collect())
}
