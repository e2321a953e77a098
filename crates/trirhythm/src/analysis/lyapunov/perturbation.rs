//! How one realisation follows its perturbation — a perturbed copy pulled back with its whole
//! memory, or the tangent equation renormalised whole — and the loop that measures its
//! finite-time exponent (module docs of [`super`]).

use super::{LyapunovSpec, PathExponent};
use crate::engine::{Stepper, Tangent};
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
        let (du, dv) = self.b.separation(&self.a);
        let d = crate::maths::hypot(du, dv);
        if d > 0.0 && d.is_finite() && self.b.contract_toward(&self.a, self.d0 / d) {
            Renormalised::Grown(d / self.d0)
        } else {
            Renormalised::Refused {
                merged: d == 0.0 && self.b.coincides_with(&self.a),
            }
        }
    }

    fn reference(&self) -> &Stepper {
        &self.a
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
        let d = self.t.norm();
        if d > 0.0 && d.is_finite() {
            self.t.scale(1.0 / d);
            Renormalised::Grown(d)
        } else {
            Renormalised::Refused {
                merged: d == 0.0 && self.t.is_zero(),
            }
        }
    }

    fn reference(&self) -> &Stepper {
        &self.a
    }
}

/// One realisation: its exponent and its running estimate at `running_points` checkpoints.
pub(super) fn one_path(
    mut p: impl Perturbation,
    spec: &LyapunovSpec,
    (transient, window): (u64, u64),
    path: u64,
    tick: &dyn Fn(u64) -> Result<()>,
) -> Result<(PathExponent, Vec<f64>)> {
    let total = transient + window;
    let every = spec.renormalise_every;
    let checkpoints = spec.running_points as u64;
    let mut running = Vec::with_capacity(spec.running_points);
    let mut next_checkpoint = 1;
    let (mut log_sum, mut count, mut deferred) = (0.0, 0u64, 0u64);
    // the step at which the copy merged with the reference for good
    let mut merged_at: Option<u64> = None;
    // the step of the last accepted renormalisation, and of the one that opened the window
    let (mut last, mut start) = (0u64, 0u64);
    let mut next = every;
    let dt = p.reference().dt();
    let tick_every = 1u64 << 14;
    for n in 1..=total {
        p.step().map_err(|e| match e {
            Error::BlowUp { .. } => Error::Undefined {
                what: "Lyapunov exponent",
                why: format!("path {path}: {e}"),
            },
            other => other,
        })?;
        if n >= next && merged_at.is_none() {
            match p.renormalise() {
                Renormalised::Grown(factor) => {
                    if n > transient {
                        log_sum += crate::maths::ln(factor);
                        count += 1;
                    } else {
                        start = n;
                    }
                    last = n;
                    next = n + every;
                }
                // identical for good: nothing left to renormalise
                Renormalised::Refused { merged: true } => merged_at = Some(n),
                Renormalised::Refused { merged: false } => deferred += 1,
            }
        }
        if n > transient {
            let k = n - transient;
            if k * checkpoints >= next_checkpoint * window {
                let span = (last.saturating_sub(start)) as f64 * dt;
                running.push(if merged_at.is_some() {
                    f64::NEG_INFINITY
                } else if count > 0 {
                    log_sum / span
                } else {
                    f64::NAN
                });
                next_checkpoint += 1;
            }
        }
        if n % tick_every == 0 {
            tick(tick_every)?;
        }
    }
    tick(total % tick_every)?;
    let impacts = p.reference().impacts();
    let measured_time = if count > 0 {
        (last - start) as f64 * dt
    } else {
        0.0
    };
    if let Some(m) = merged_at {
        // the perturbation vanished for good: a contraction faster than any exponential
        return Ok((
            PathExponent {
                path,
                exponent: f64::NEG_INFINITY,
                measured_time,
                renormalisations: count,
                deferred,
                impacts,
                merged_at: Some(m as f64 * dt),
            },
            running,
        ));
    }
    if count == 0 {
        return Err(Error::Undefined {
            what: "Lyapunov exponent",
            why: format!(
                "path {path}: no renormalisation was possible in the measured window (the two \
                 paths were never combinable: at rest on the wall, or an impact in every window)"
            ),
        });
    }
    Ok((
        PathExponent {
            path,
            exponent: log_sum / measured_time,
            measured_time,
            renormalisations: count,
            deferred,
            impacts,
            merged_at: None,
        },
        running,
    ))
}
