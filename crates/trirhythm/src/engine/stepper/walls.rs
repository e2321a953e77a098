//! Walls of the General kernel: one wall at any U = δ keeping U above or below it, or two
//! walls δ1 < δ2 with the motion between them, each with a constant restitution coefficient
//! or the speed-dependent r(|U̇₋|); impacts and sticking at a wall where the force is not zero.
//!
//! # Equation
//! U′ = V, V = V₀ + J^λ g + Σ (impact jumps), g = h(U, V)V − k(U) + F cos ψ + η (module docs
//! of `super::general`), with U kept in [δ1, δ2] (δ1 = −∞ without a lower wall, δ2 = +∞
//! without an upper one) and at a wall i (inward normal n = +1 for the lower, −1 for the upper)
//! the impact law U̇₊ = −r_i(|U̇₋|)·U̇₋, where r is a constant in [0, 1] or
//! r(v) = r_fast + (r0 − r_fast)·e^{−v/v_s} (`model::Restitution`). The paper's wall (at 0,
//! keeping U ≥ 0, constant r) is not stepped here: a problem with it keeps the paper kernel's
//! events (`super::impact`) and its bits.
//!
//! # Method
//! A step runs freely (the General kernel's step); if its end U₁ lies beyond wall i,
//! n(U₁ − δ) < 0, the impact is located at θ ∈ (0, 1] of the step as the root of the cubic
//! Hermite interpolant of U − δ (`super::impact::hermite_root`); the scheme's velocity there is
//! the root of V₋ = N + w_s(h(δ, V₋)V₋ − k(δ) + F cos ψ* + η*) (the wall's force −k(δ) is in
//! g at the wall), clipped to nV₋ ≤ 0 (a grazing impact); V₊ = −r(|V₋|)V₋; the memory holds
//! the jump exactly (the split piece with g before and after the instant, the Volterra
//! constant shifted by V₊ − V₋, or a restart); the rest of the step, of length (1 − θ)Δt, is
//! the General step from (δ, V₊).
//!
//! **Sticking at δ.** If the redone rest ends beyond the same wall again (the next impact
//! would come within the step), the mass is clamped at (δ, 0) and the wall's reaction goes
//! into the constant of V's Volterra form (or the memory restarts at rest), as at the paper's
//! wall at 0. While stuck, every step runs freely from rest at δ and clamps again if
//! n(U₁ − δ) ≤ 0: the discrete form of "the mass stays at the wall while the net force
//! g(δ, 0) = −k(δ) + F cos ψ + η + … pushes into it (n·g ≤ 0) and leaves when it pulls away".
//! With k(δ) ≠ 0 the force at the wall is not zero: a mass at rest on a lower wall at δ > 0
//! (k(δ) > 0) stays there without forcing. A step that leaves one wall and ends beyond the
//! other is an impact on the other. A step whose redone rest ends beyond the *other* wall
//! (two impacts within one step) is refused with [`crate::Error::InvalidParameter`] naming Δt.
//!
//! **Cost.** The paper's model never comes here: its problem has no General kernel
//! (`super::Stepper::step` takes the paper kernel's branch); General paths without these walls
//! take one more `Option` test per step.
//!
//! # Reference
//! model-class.md §4 (the design); Diethelm, Ford & Freed (2002) for the scheme; the
//! restitution law's form: `docs/model-file.md`.
//!
//! # Tests
//! `tests/walls.rs`: a linear oscillator between two walls and against an offset wall (keeping
//! above and below) at r = 1: the period against the exact time between the walls along arcs of
//! the harmonic solution, the energy kept, and the observed order as Δt halves; one impact with
//! a speed-dependent restitution (V₊ = r(|V₋|)·|V₋|); a mass settling onto a wall at δ where
//! the force pushes into it, and staying; the lanes give the scalar bits.

use super::super::memory::{Piece, Split};
use super::general::General;
use super::impact::hermite_root;
use super::{predictor_weight, Begin, StepEvents, Stepper};
use crate::error::{Error, Exact, Result};
use crate::model::{Keep, Restitution, Wall};

/// One wall: its position and its restitution law.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Law {
    pub(super) position: f64,
    pub(super) restitution: Restitution,
}

/// Which wall.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Side {
    /// The lower wall (keeps U above it; n = +1).
    Lower,
    /// The upper wall (keeps U below it; n = −1).
    Upper,
}

/// The walls of a General path: U ∈ [lower, upper].
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Walls {
    lower: Option<Law>,
    upper: Option<Law>,
}

impl Walls {
    /// The walls of the model's list (a wall keeping above is a lower wall, one keeping below an
    /// upper wall); None for an empty list.
    pub(super) fn new(walls: &[Wall]) -> Option<Self> {
        if walls.is_empty() {
            return None;
        }
        let mut out = Walls {
            lower: None,
            upper: None,
        };
        for w in walls {
            let law = Law {
                position: w.position,
                restitution: w.restitution,
            };
            match w.keep {
                Keep::Above => out.lower = Some(law),
                Keep::Below => out.upper = Some(law),
            }
        }
        Some(out)
    }

    fn law(&self, side: Side) -> Law {
        match side {
            Side::Lower => self.lower,
            Side::Upper => self.upper,
        }
        .expect("a wall on this side")
    }

    /// The wall that `u` lies beyond, if any.
    #[inline]
    fn beyond(&self, u: f64) -> Option<Side> {
        if self.lower.is_some_and(|l| u < l.position) {
            Some(Side::Lower)
        } else if self.upper.is_some_and(|w| u > w.position) {
            Some(Side::Upper)
        } else {
            None
        }
    }

    /// The wall that `u` sits on exactly (a clamped state), if any.
    fn at(&self, u: f64) -> Option<Side> {
        if self.lower.is_some_and(|l| u == l.position) {
            Some(Side::Lower)
        } else if self.upper.is_some_and(|w| u == w.position) {
            Some(Side::Upper)
        } else {
            None
        }
    }
}

impl Side {
    /// The inward normal n.
    fn normal(self) -> f64 {
        match self {
            Side::Lower => 1.0,
            Side::Upper => -1.0,
        }
    }
}

impl Stepper {
    /// A step of a General path with its walls (module docs): the free step, then sticking,
    /// an impact (the rest of the step redone), the blow-up check, the node and the piece of g.
    #[inline(never)]
    pub(super) fn step_walls(&mut self, walls: Walls) -> Result<()> {
        let (b, free) = self.begin_general();
        let (mut u1, mut v1) = free.end();
        self.events = StepEvents::default();
        let mut piece = Piece {
            left: b.gl,
            right: 0.0,
            split: None,
        };
        let mut push = true;
        let mut clamped = false;
        // a stuck path sits on its wall (a renormalised copy pulled off it is free again)
        if let Some(side) = walls.at(self.u).filter(|_| self.stuck) {
            let delta = walls.law(side).position;
            if side.normal() * (u1 - delta) <= 0.0 {
                // still pressed against the wall
                push = self.stick(v1);
                (u1, v1) = (delta, 0.0);
                clamped = true;
            } else {
                self.stuck = false;
            }
        } else {
            self.stuck = false;
        }
        if !clamped {
            if let Some(side) = walls.beyond(u1) {
                let (split, u2, v2) = self.impact_wall(walls.law(side), side, &b, (u1, v1));
                piece.split = Some(split);
                (u1, v1) = (u2, v2);
                match walls.beyond(u1) {
                    None => {}
                    Some(again) if again == side => {
                        // the next impact would come within this step: stick
                        push = self.stick(v1);
                        (u1, v1) = (walls.law(side).position, 0.0);
                        self.stuck = true;
                    }
                    Some(_) => {
                        return Err(Error::invalid(
                            "dt",
                            self.h,
                            format!(
                                "a step that meets one wall at most: at t = {} the step meets \
                                 both walls (their distance is too small for this Δt)",
                                Exact(self.time())
                            ),
                        ))
                    }
                }
            }
        }
        self.steps += 1;
        self.check_blow_up((b.u, b.v), (u1, v1))?;
        let g = self.general.as_deref().expect("a General path");
        (self.drift, self.pw) = g.node(self.h, u1, v1);
        if push {
            piece.right = self.drift + b.fr;
            self.history.push(piece);
        }
        self.u = u1;
        self.v = v1;
        Ok(())
    }

    /// The impact on wall `law` (on `side`) inside the current step whose free end was
    /// (u1, v1): locate it, jump by the restitution law, redo the rest of the step from the
    /// wall. Returns the split of g and the end of the step.
    #[cold]
    fn impact_wall(
        &mut self,
        law: Law,
        side: Side,
        b: &Begin,
        (u1, v1): (f64, f64),
    ) -> (Split, f64, f64) {
        let h = self.h;
        let delta = law.position;
        let theta = hermite_root(self.u - delta, self.v, u1 - delta, v1, h);
        let eta_star = b.el + theta * (b.er - b.el);
        let (hs, ws) = self.history.at_fraction(theta, b.gl);
        let g: &General = self.general.as_deref().expect("a General path");
        // the forcing at the instant (noise and harmonic) and the wall's force −k(δ)
        let forcing = self.rhs.forcing(eta_star, self.side) + g.force_at(theta);
        let at_wall = forcing - g.restoring(delta);
        let v_at = g.wall_velocity(delta, self.base + hs, ws, at_wall);
        // the scheme's V(t*−) may point away from the wall at a grazing impact: then V₋ = 0
        let v_minus = match side {
            Side::Lower => v_at.min(0.0),
            Side::Upper => v_at.max(0.0),
        };
        let v_plus = -law.restitution.at(v_minus.abs()) * v_minus;
        let split = Split {
            theta,
            before: g.wall_drift(delta, v_at) + forcing,
            after: g.wall_drift(delta, v_plus) + forcing,
            keep_before: !self.restart,
            mass: 0.0,
        };
        let pw = predictor_weight((1.0 - theta) * h, g.a(delta, v_plus));
        self.record_impact(theta, v_minus, v_plus);
        self.memory_at_impact(v_at, v_plus);
        let (known_s, wr_s) = self.history.current_split(b.gl, &split);
        let known = self.base + self.history.value() + known_s;
        let g: &General = self.general.as_deref().expect("a General path");
        let free = g.advance(
            (1.0 - theta) * h,
            (delta, v_plus, split.after),
            pw,
            known,
            wr_s,
            b.fr,
        );
        let (u_end, v_end) = free.end();
        (split, u_end, v_end)
    }
}
