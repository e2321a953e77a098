//! The simulated boundary at one abscissa: regula falsi (Illinois) on the growth rate with a
//! straddling pair after each estimate, or bisection on its sign (module docs of [`super`]).
//!
//! Each abscissa's search is a [`Bracket`]: a state machine that asks for the growth runs it
//! needs next and goes on with their results, so that the searches of several abscissae, and the
//! runs each of them may need at once, are stepped together in lanes ([`Classifier::lanes`]): both
//! ends of the interval, and both probes of a straddling pair (the second is needed unless the
//! first moves the upper end; it is run beside the first all the same, and its result dropped
//! when the sequence does not reach it), for `lanes / 2` abscissae at a time. Each search's
//! sequence of probes, its bracket and its simulation count are those of one simulation after
//! the other (`tests/oscillation.rs`); with `Lanes::Width(1)` it is run so.
//!
//! Measured (`examples/drivers_timing.rs`, docs/numerics.md, Speed): two runs in lanes gain
//! nothing over one after the other (the group's per-step overhead and the lanes left empty eat
//! the overlap of two dependency chains); eight gain 1.7× at λ = 0.95 and 2.7× at λ = 1 (the lane
//! step alone), hence several abscissae a group.

use super::growth::{grow_all, Cache, Classifier, Growth};
use super::{BoundaryPoint, Plane, Refinement, Search, Side};
use crate::engine::Problem;
use crate::error::Result;
use crate::monitor::Monitor;

/// Most steps of one search.
const MAX_ITERATIONS: usize = 200;

/// Where a search stands.
enum Phase {
    /// Both ends of the interval wanted.
    Ends,
    /// A new step of the bracketing to begin (or the search to end).
    NewStep,
    /// A step under way: its probes, the next one to take, what has moved, the width before.
    Step {
        probes: Vec<f64>,
        next: usize,
        moved: (bool, bool),
        width: f64,
    },
    Done(BoundaryPoint),
}

/// One abscissa's search (module docs).
pub(super) struct Bracket {
    x: f64,
    lo: f64,
    hi: f64,
    search: Search,
    phase: Phase,
    a: f64,
    fa: f64,
    b: f64,
    fb: f64,
    ga: bool,
    gb: bool,
    wa: f64,
    wb: f64,
    last_moved: (bool, bool),
    stalls: usize,
    iterations: usize,
    simulations: usize,
    unclear: usize,
    /// Results given ahead of the sequence, by y.
    ahead: Vec<(f64, Result<Growth>)>,
}

/// The secant root of (a, fa), (b, fb) clamped to [a, b] (the midpoint when not finite).
fn secant(a: f64, fa: f64, b: f64, fb: f64) -> f64 {
    let c = a - fa * (b - a) / (fb - fa);
    if c.is_finite() {
        c.clamp(a, b)
    } else {
        0.5 * (a + b)
    }
}

impl Bracket {
    pub(super) fn new(plane: &Plane, x: f64, search: &Search) -> Bracket {
        let (lo, hi) = plane.y_range;
        Bracket {
            x,
            lo,
            hi,
            search: *search,
            phase: Phase::Ends,
            a: lo,
            fa: f64::NAN,
            b: hi,
            fb: f64::NAN,
            ga: false,
            gb: false,
            wa: 1.0,
            wb: 1.0,
            last_moved: (false, false),
            stalls: 0,
            iterations: 0,
            simulations: 0,
            unclear: 0,
            ahead: vec![],
        }
    }

    /// The result of the run at `y`.
    pub(super) fn give(&mut self, y: f64, run: Result<Growth>) {
        self.ahead.push((y, run));
    }

    /// The point, once the search is done.
    pub(super) fn point(&self) -> Option<BoundaryPoint> {
        match self.phase {
            Phase::Done(p) => Some(p),
            _ => None,
        }
    }

    /// The growth rate at `y` if given: counted as a simulation of the search (its error, if
    /// it failed, is the search's).
    fn take(&mut self, y: f64) -> Option<Result<f64>> {
        let k = self
            .ahead
            .iter()
            .position(|(z, _)| z.to_bits() == y.to_bits())?;
        Some(self.ahead.remove(k).1.map(|g| {
            self.simulations += 1;
            self.unclear += usize::from(!g.clear);
            g.rate
        }))
    }

    fn finish(&mut self, side: Side) {
        let boundary = side == Side::Boundary;
        let nan = f64::NAN;
        self.phase = Phase::Done(BoundaryPoint {
            x: self.x,
            side,
            y: if boundary {
                secant(self.a, self.fa, self.b, self.fb)
            } else {
                nan
            },
            y_lo: if boundary { self.a } else { nan },
            y_hi: if boundary { self.b } else { nan },
            oscillates_above: self.gb,
            simulations: self.simulations,
            unclear: self.unclear,
        });
        self.ahead.clear();
    }

    /// Go on as far as the results given allow; returns the ys whose runs are wanted next
    /// (none once done). With `speculate`, every run the sequence may need before its next
    /// decision is asked for at once; without, one at a time, as the sequence reaches it.
    pub(super) fn advance(&mut self, speculate: bool) -> Result<Vec<f64>> {
        loop {
            match &mut self.phase {
                Phase::Done(_) => return Ok(vec![]),
                Phase::Ends => {
                    let (lo, hi) = (self.lo, self.hi);
                    let given = |y: f64| self.ahead.iter().any(|(z, _)| z.to_bits() == y.to_bits());
                    match (given(lo), given(hi)) {
                        (true, true) => {}
                        (false, _) if speculate => return Ok(vec![lo, hi]),
                        (false, _) => return Ok(vec![lo]),
                        (true, false) => return Ok(vec![hi]),
                    }
                    let fa = self.take(lo).expect("given")?;
                    let fb = self.take(hi).expect("given")?;
                    (self.fa, self.fb) = (fa, fb);
                    (self.ga, self.gb) = (fa > 0.0, fb > 0.0);
                    if self.ga == self.gb {
                        let side = if self.ga {
                            Side::Oscillates
                        } else {
                            Side::Rests
                        };
                        self.finish(side);
                    } else {
                        self.phase = Phase::NewStep;
                    }
                }
                Phase::NewStep => {
                    if self.iterations == MAX_ITERATIONS {
                        self.finish(Side::Boundary);
                        continue;
                    }
                    let (a, b) = (self.a, self.b);
                    let width = b - a;
                    let est = secant(a, self.wa * self.fa, b, self.wb * self.fb);
                    let floor = 1e-12 * (self.hi - self.lo);
                    let target = (self.search.tolerance * est.abs()).max(floor);
                    if width <= target {
                        self.finish(Side::Boundary);
                        continue;
                    }
                    let probes =
                        if self.search.refinement == Refinement::Bisection || self.stalls >= 2 {
                            vec![0.5 * (a + b)]
                        } else {
                            vec![est - 0.45 * target, est + 0.45 * target]
                        };
                    self.ahead.clear();
                    self.phase = Phase::Step {
                        probes,
                        next: 0,
                        moved: (false, false),
                        width,
                    };
                }
                Phase::Step {
                    probes,
                    next,
                    moved,
                    width,
                } => {
                    let (probes, mut k, mut mv, width) = (probes.clone(), *next, *moved, *width);
                    while k < probes.len() {
                        let y = probes[k];
                        if !(y > self.a && y < self.b) {
                            k += 1;
                            continue;
                        }
                        let Some(f) = self.take(y) else {
                            self.phase = Phase::Step {
                                probes: probes.clone(),
                                next: k,
                                moved: mv,
                                width,
                            };
                            if !speculate {
                                return Ok(vec![y]);
                            }
                            // this probe, and the next if inside the bracket with a moved here
                            let mut ask = vec![];
                            let mut low = self.a;
                            for &z in &probes[k..] {
                                if z > low && z < self.b {
                                    ask.push(z);
                                    low = z;
                                }
                            }
                            return Ok(ask);
                        };
                        let f = f?;
                        k += 1;
                        if (f > 0.0) == self.ga {
                            (self.a, self.fa, self.wa) = (y, f, 1.0);
                            mv.0 = true;
                        } else {
                            (self.b, self.fb, self.wb) = (y, f, 1.0);
                            mv.1 = true;
                            break;
                        }
                    }
                    // Illinois: an end kept twice in a row has its rate halved in the secant
                    match mv {
                        (true, false) if self.last_moved == mv => self.wb *= 0.5,
                        (false, true) if self.last_moved == mv => self.wa *= 0.5,
                        _ => {}
                    }
                    self.last_moved = mv;
                    self.stalls = if self.b - self.a > 0.5 * width {
                        self.stalls + 1
                    } else {
                        0
                    };
                    self.iterations += 1;
                    self.phase = Phase::NewStep;
                }
            }
        }
    }
}

/// The simulated boundary at the abscissae `xs` of `plane` (module docs of [`super`]), their
/// searches advanced together, their runs stepped together in lanes; `finished` hears each
/// point as its search ends; `monitor` may stop the searches, also inside a simulation.
pub(super) fn simulated(
    plane: &Plane,
    xs: &[f64],
    c: &Classifier,
    search: &Search,
    monitor: &dyn Monitor,
    finished: &dyn Fn(&BoundaryPoint) -> Result<()>,
) -> Result<Vec<BoundaryPoint>> {
    let speculate = c.lanes.width()? > 1;
    let mut brackets: Vec<Bracket> = xs.iter().map(|&x| Bracket::new(plane, x, search)).collect();
    let mut cache = Cache::default();
    loop {
        let mut asks: Vec<(usize, f64)> = vec![];
        for (k, br) in brackets.iter_mut().enumerate() {
            if br.point().is_some() {
                continue;
            }
            let wants = br.advance(speculate)?;
            if let Some(p) = br.point() {
                finished(&p)?;
            }
            asks.extend(wants.into_iter().map(|y| (k, y)));
        }
        if asks.is_empty() {
            break;
        }
        monitor.check()?;
        let problems: Vec<Result<Problem>> = asks
            .iter()
            .map(|&(k, y)| plane.problem_at(xs[k], y))
            .collect();
        let runs = grow_valid(problems, c, &mut cache, monitor)?;
        for ((k, y), run) in asks.into_iter().zip(runs) {
            brackets[k].give(y, run);
        }
    }
    Ok(brackets
        .iter()
        .map(|b| b.point().expect("every search done"))
        .collect())
}

/// [`grow_all`] of the valid problems of `problems`; an invalid one keeps its error in place.
fn grow_valid(
    problems: Vec<Result<Problem>>,
    c: &Classifier,
    cache: &mut Cache,
    monitor: &dyn Monitor,
) -> Result<Vec<Result<Growth>>> {
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
    let problems = ys.iter().map(|&y| plane.problem_at(x, y)).collect();
    grow_valid(problems, c, cache, monitor)
}
