//! How one realisation follows its perturbation — a perturbed copy pulled back with its whole
//! memory, or the tangent equation renormalised whole — and the loop that measures its
//! finite-time exponent (module docs of [`super`]).

use super::{LyapunovSpec, PathExponent};
use crate::engine::{Group, Stepper, Tangent};
use crate::error::{Error, Result};

/// The outcome of a due renormalisation.
pub(super) enum Renormalised {
    /// Done: the perturbation had grown by this factor since the last one.
    Grown(f64),
    /// Refused now (tried again at the next step); `merged` when the perturbation has
    /// vanished for good (the copy coincides with the reference, or the whole tangent is 0).
    Refused { merged: bool },
}

/// How one realisation follows its perturbation: advance both one step, renormalise.
pub(super) trait Perturbation {
    fn step(&mut self) -> Result<()>;
    fn renormalise(&mut self) -> Renormalised;
    /// The reference path.
    fn reference(&self) -> &Stepper;
}

/// Two trajectories on the same noise; the copy pulled back to d₀ with its whole memory.
pub(super) struct TwoPaths {
    pub(super) a: Stepper,
    pub(super) b: Stepper,
    pub(super) d0: f64,
}

impl Perturbation for TwoPaths {
    fn step(&mut self) -> Result<()> {
        self.a.step().and_then(|_| self.b.step())
    }

    fn renormalise(&mut self) -> Renormalised {
        renormalise_pair(&self.a, &mut self.b, self.d0)
    }

    fn reference(&self) -> &Stepper {
        &self.a
    }
}

/// Pull the copy `b` back to the distance `d0` from the reference `a`, whole memory included.
fn renormalise_pair(a: &Stepper, b: &mut Stepper, d0: f64) -> Renormalised {
    let (du, dv) = b.separation(a);
    let d = crate::maths::hypot(du, dv);
    if d > 0.0 && d.is_finite() && b.contract_toward(a, d0 / d) {
        Renormalised::Grown(d / d0)
    } else {
        Renormalised::Refused {
            merged: d == 0.0 && b.coincides_with(a),
        }
    }
}

/// The path and its tangent, renormalised to norm 1 by scaling the whole tangent state.
pub(super) struct PathAndTangent {
    pub(super) a: Stepper,
    pub(super) t: Tangent,
}

impl Perturbation for PathAndTangent {
    fn step(&mut self) -> Result<()> {
        self.a.step_with_tangent(&mut self.t)
    }

    fn renormalise(&mut self) -> Renormalised {
        renormalise_tangent(&mut self.t)
    }

    fn reference(&self) -> &Stepper {
        &self.a
    }
}

/// Scale the whole tangent state back to norm 1.
fn renormalise_tangent(t: &mut Tangent) -> Renormalised {
    let d = t.norm();
    if d > 0.0 && d.is_finite() {
        t.scale(1.0 / d);
        Renormalised::Grown(d)
    } else {
        Renormalised::Refused {
            merged: d == 0.0 && t.is_zero(),
        }
    }
}

/// The measurement of one realisation's exponent, advanced after each of its steps.
struct Measure<'a> {
    spec: &'a LyapunovSpec,
    transient: u64,
    window: u64,
    path: u64,
    dt: f64,
    checkpoints: u64,
    running: Vec<f64>,
    next_checkpoint: u64,
    log_sum: f64,
    count: u64,
    deferred: u64,
    /// The step at which the copy merged with the reference for good.
    merged_at: Option<u64>,
    /// The step of the last accepted renormalisation, and of the one that opened the window.
    last: u64,
    start: u64,
    next: u64,
}

/// Steps between two reports of a realisation's progress.
const TICK_EVERY: u64 = 1 << 14;

impl<'a> Measure<'a> {
    fn new(spec: &'a LyapunovSpec, (transient, window): (u64, u64), path: u64, dt: f64) -> Self {
        Measure {
            spec,
            transient,
            window,
            path,
            dt,
            checkpoints: spec.running_points as u64,
            running: Vec::with_capacity(spec.running_points),
            next_checkpoint: 1,
            log_sum: 0.0,
            count: 0,
            deferred: 0,
            merged_at: None,
            last: 0,
            start: 0,
            next: spec.renormalise_every,
        }
    }

    /// A failed step of the realisation, as its error (a blow-up leaves the exponent undefined).
    fn failed(&self, e: Error) -> Error {
        match e {
            Error::BlowUp { .. } => Error::Undefined {
                what: "Lyapunov exponent",
                why: format!("path {}: {e}", self.path),
            },
            other => other,
        }
    }

    /// After step `n`: renormalise when due (`renormalise` does it), record the running
    /// estimate at its checkpoints, report the progress every [`TICK_EVERY`] steps.
    fn after_step(
        &mut self,
        n: u64,
        renormalise: impl FnOnce() -> Renormalised,
        tick: &dyn Fn(u64) -> Result<()>,
    ) -> Result<()> {
        if n >= self.next && self.merged_at.is_none() {
            match renormalise() {
                Renormalised::Grown(factor) => {
                    if n > self.transient {
                        self.log_sum += crate::maths::ln(factor);
                        self.count += 1;
                    } else {
                        self.start = n;
                    }
                    self.last = n;
                    self.next = n + self.spec.renormalise_every;
                }
                // identical for good: nothing left to renormalise
                Renormalised::Refused { merged: true } => self.merged_at = Some(n),
                Renormalised::Refused { merged: false } => self.deferred += 1,
            }
        }
        if n > self.transient {
            let k = n - self.transient;
            if k * self.checkpoints >= self.next_checkpoint * self.window {
                let span = (self.last.saturating_sub(self.start)) as f64 * self.dt;
                self.running.push(if self.merged_at.is_some() {
                    f64::NEG_INFINITY
                } else if self.count > 0 {
                    self.log_sum / span
                } else {
                    f64::NAN
                });
                self.next_checkpoint += 1;
            }
        }
        if n % TICK_EVERY == 0 {
            tick(TICK_EVERY)?;
        }
        Ok(())
    }

    /// The exponent after the last step, with the reference's `impacts`.
    fn finish(
        self,
        impacts: u64,
        tick: &dyn Fn(u64) -> Result<()>,
    ) -> Result<(PathExponent, Vec<f64>)> {
        let (path, dt, count) = (self.path, self.dt, self.count);
        tick((self.transient + self.window) % TICK_EVERY)?;
        let measured_time = if count > 0 {
            (self.last - self.start) as f64 * dt
        } else {
            0.0
        };
        if let Some(m) = self.merged_at {
            // the perturbation vanished for good: a contraction faster than any exponential
            return Ok((
                PathExponent {
                    path,
                    exponent: f64::NEG_INFINITY,
                    measured_time,
                    renormalisations: count,
                    deferred: self.deferred,
                    impacts,
                    merged_at: Some(m as f64 * dt),
                },
                self.running,
            ));
        }
        if count == 0 {
            return Err(Error::Undefined {
                what: "Lyapunov exponent",
                why: format!(
                    "path {path}: no renormalisation was possible in the measured window (the two \
                     paths were never combinable: at rest on the wall, or an impact in every \
                     window)"
                ),
            });
        }
        Ok((
            PathExponent {
                path,
                exponent: self.log_sum / measured_time,
                measured_time,
                renormalisations: count,
                deferred: self.deferred,
                impacts,
                merged_at: None,
            },
            self.running,
        ))
    }
}

/// One realisation: its exponent and its running estimate at `running_points` checkpoints.
pub(super) fn one_path(
    mut p: impl Perturbation,
    spec: &LyapunovSpec,
    sizes: (u64, u64),
    path: u64,
    tick: &dyn Fn(u64) -> Result<()>,
) -> Result<(PathExponent, Vec<f64>)> {
    let mut m = Measure::new(spec, sizes, path, p.reference().dt());
    for n in 1..=sizes.0 + sizes.1 {
        p.step().map_err(|e| m.failed(e))?;
        m.after_step(n, || p.renormalise(), tick)?;
    }
    m.finish(p.reference().impacts(), tick)
}

/// Realisations stepped together in lanes: one step of all, then each renormalised on its own.
trait InLanes {
    fn step(&mut self);
    /// The error of realisation `k`'s last step (its reference's first), if it failed.
    fn take_error(&mut self, k: usize) -> Option<Error>;
    fn renormalise(&mut self, k: usize) -> Renormalised;
    /// Impacts of realisation `k`'s reference.
    fn impacts(&self, k: usize) -> u64;
}

/// Reference and copy of realisation k in lanes 2k and 2k + 1.
struct PairLanes<'a> {
    group: Group<'a>,
    d0: f64,
}

impl InLanes for PairLanes<'_> {
    fn step(&mut self) {
        self.group.step();
    }

    fn take_error(&mut self, k: usize) -> Option<Error> {
        // the reference's error first, as `one_path` steps it first
        self.group
            .take_error(2 * k)
            .or_else(|| self.group.take_error(2 * k + 1))
    }

    fn renormalise(&mut self, k: usize) -> Renormalised {
        let (a, b) = self.group.pair(k);
        renormalise_pair(a, b, self.d0)
    }

    fn impacts(&self, k: usize) -> u64 {
        self.group.path(2 * k).impacts()
    }
}

/// Path k with its tangent in lane k.
struct TangentLanes<'a> {
    group: Group<'a>,
}

impl InLanes for TangentLanes<'_> {
    fn step(&mut self) {
        self.group.step();
    }

    fn take_error(&mut self, k: usize) -> Option<Error> {
        self.group.take_error(k)
    }

    fn renormalise(&mut self, k: usize) -> Renormalised {
        renormalise_tangent(self.group.with_tangent(k).1)
    }

    fn impacts(&self, k: usize) -> u64 {
        self.group.path(k).impacts()
    }
}

/// Realisations `paths` stepped together ([`InLanes`]), each measured as by [`one_path`].
fn measure_in_lanes(
    mut r: impl InLanes,
    dt: f64,
    paths: &[u64],
    spec: &LyapunovSpec,
    sizes: (u64, u64),
    tick: &dyn Fn(u64) -> Result<()>,
) -> Result<Vec<(PathExponent, Vec<f64>)>> {
    let mut measures: Vec<Measure> = paths
        .iter()
        .map(|&i| Measure::new(spec, sizes, i, dt))
        .collect();
    for n in 1..=sizes.0 + sizes.1 {
        r.step();
        for (k, m) in measures.iter_mut().enumerate() {
            if let Some(e) = r.take_error(k) {
                return Err(m.failed(e));
            }
            m.after_step(n, || r.renormalise(k), tick)?;
        }
    }
    measures
        .into_iter()
        .enumerate()
        .map(|(k, m)| m.finish(r.impacts(k), tick))
        .collect()
}

/// Two-trajectory realisations stepped together in lanes: `pairs` holds reference and copy of
/// each in neighbouring lanes (a₀, b₀, a₁, b₁, …), `paths` their indices; the groups of
/// `lanes` steppers take their steps together (`engine::Group`). Each realisation gives the bits
/// of [`one_path`] with [`TwoPaths`] (the lane step gives the scalar step's bits, and every
/// renormalisation acts on its own pair between steps, as there).
pub(super) fn pairs_in_lanes(
    mut pairs: Vec<Stepper>,
    d0: f64,
    paths: &[u64],
    spec: &LyapunovSpec,
    sizes: (u64, u64),
    lanes: usize,
    tick: &dyn Fn(u64) -> Result<()>,
) -> Result<Vec<(PathExponent, Vec<f64>)>> {
    assert_eq!(pairs.len(), 2 * paths.len(), "two steppers per realisation");
    let dt = pairs[0].dt();
    let group = Group::new(&mut pairs, lanes)?;
    measure_in_lanes(PairLanes { group, d0 }, dt, paths, spec, sizes, tick)
}

/// Tangent-method realisations stepped together in lanes: path k and its tangent k in lane k
/// of groups of `lanes` (`engine::Group::with_tangents`). Each realisation gives the bits of
/// [`one_path`] with [`PathAndTangent`].
pub(super) fn tangents_in_lanes(
    (mut refs, mut tangents): (Vec<Stepper>, Vec<Tangent>),
    paths: &[u64],
    spec: &LyapunovSpec,
    sizes: (u64, u64),
    lanes: usize,
    tick: &dyn Fn(u64) -> Result<()>,
) -> Result<Vec<(PathExponent, Vec<f64>)>> {
    assert_eq!(refs.len(), paths.len(), "one stepper per realisation");
    let dt = refs[0].dt();
    let group = Group::with_tangents(&mut refs, &mut tangents, lanes)?;
    measure_in_lanes(TangentLanes { group }, dt, paths, spec, sizes, tick)
}
