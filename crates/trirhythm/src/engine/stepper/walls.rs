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
//! the General step from (δ, V₊). With fractional terms K_j·D^{α_j}U, g at the wall has
//! −Σ_j K_j m_j(t*) too and each term's memory of V is split at the instant
//! (`Stepper::impact_wall_fractional`; module docs of `super::general`, "Fractional terms at a
//! wall").
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
//! **The tangent** (`step_walls_with_tangent`; module docs of `super::tangent`, "Walls of the
//! General kernel"): the derivative of the step taken — δθ from the interpolant of U − δ, δV(t*)
//! from the root's equation with the memory and forcing at the moving instant (the force at the
//! wall, −k(δ) + F cos ψ*, enters with δθ: the saltation of a wall where the force is not zero),
//! δV₊ = −(r(|V₋|) + r′(|V₋|)|V₋|)δV₋, the redone rest with its moving length and weights. A
//! clamped step's tangent is 0 in U and V. With fractional terms their memories of δV are split
//! as the reference's, with the instant's θ-derivative (module docs of `super::tangent`,
//! "Fractional terms and multiplicative noise").
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
//! the force pushes into it, and staying; the lanes give the scalar bits; the tangent's
//! exponents between two walls (elastic: ≈ 0; damped: negative). `tests/fractional_walls.rs`:
//! fractional terms at these walls. `super::tangent`'s unit tests:
//! the tangent step through impacts on these walls against central differences of the step.

use super::super::memory::{Piece, Split};
use super::affine::{predictor_weight_len_slope, predictor_weight_slope};
use super::general::{General, GeneralFree};
use super::impact::{hermite_root, split_fractional, Crossing};
use super::tangent::{fold_theta, hermite_basis, hermite_basis_slope, Tangent};
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

    /// The paper's wall at 0 (keeping U ≥ 0, constant `r`) as a lower wall: the General
    /// kernel's steps at it are those of `super::impact` bit for bit (k(0) = 0, the same
    /// location, jump and redone rest), so the tangent of [`Stepper::step_walls_with_tangent`]
    /// serves both.
    pub(super) fn paper(r: f64) -> Self {
        Walls {
            lower: Some(Law {
                position: 0.0,
                restitution: Restitution::Constant(r),
            }),
            upper: None,
        }
    }

    /// Copy the walls into `plan` ([`crate::engine::GeneralPlan`]: [0] lower, [1] upper).
    pub(super) fn export(&self, plan: &mut crate::engine::GeneralPlan) {
        plan.walls = 1;
        for (i, law) in [self.lower, self.upper].into_iter().enumerate() {
            let Some(law) = law else { continue };
            plan.wall_present[i] = 1;
            plan.wall_position[i] = law.position;
            match law.restitution {
                Restitution::Constant(r) => plan.wall_r[i] = r,
                Restitution::Speed(s) => {
                    plan.wall_speed_dependent[i] = 1;
                    plan.wall_r[i] = s.r0;
                    plan.wall_r_fast[i] = s.r_fast;
                    plan.wall_speed[i] = s.speed;
                }
            }
        }
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
        if let Some(delta) = self.pressed(walls, u1) {
            push = self.stick(v1);
            (u1, v1) = (delta, 0.0);
        } else if let Some(side) = walls.beyond(u1) {
            let hit = self.impact_wall(walls.law(side), side, &b, (u1, v1));
            piece.split = Some(hit.split);
            (u1, v1) = hit.free.end();
            if self.beyond_again(walls, side, u1)? {
                // the next impact would come within this step: stick
                push = self.stick(v1);
                (u1, v1) = (walls.law(side).position, 0.0);
                self.stuck = true;
            }
        }
        self.end_wall_step(&b, (u1, v1), push.then_some(piece))?;
        Ok(())
    }

    /// Whether a stuck path is still pressed against its wall at the free end U₁ = `u1`
    /// (n(U₁ − δ) ≤ 0): then δ, to clamp at; otherwise the path is free (a renormalised copy
    /// pulled off the wall is free again).
    fn pressed(&mut self, walls: Walls, u1: f64) -> Option<f64> {
        if let Some(side) = walls.at(self.u).filter(|_| self.stuck) {
            let delta = walls.law(side).position;
            if side.normal() * (u1 - delta) <= 0.0 {
                return Some(delta);
            }
        }
        self.stuck = false;
        None
    }

    /// Whether the redone rest of an impact step on `side`, ending at U = `u1`, lies beyond
    /// the same wall again (the path then sticks); a refusal if it lies beyond the other wall
    /// (a step meets one wall at most).
    fn beyond_again(&self, walls: Walls, side: Side, u1: f64) -> Result<bool> {
        match walls.beyond(u1) {
            None => Ok(false),
            Some(again) if again == side => Ok(true),
            Some(_) => Err(Error::invalid(
                "dt",
                self.h,
                format!(
                    "a step that meets one wall at most: at t = {} the step meets both walls \
                     (their distance is too small for this Δt)",
                    Exact(self.time())
                ),
            )),
        }
    }

    /// The end of a step with walls, at (U₁, V₁): the blow-up check, the node, the piece of g
    /// completed and pushed (`None`: a stuck step pushes none), the state. Returns the piece
    /// as pushed.
    fn end_wall_step(
        &mut self,
        b: &Begin,
        (u1, v1): (f64, f64),
        piece: Option<Piece>,
    ) -> Result<Option<Piece>> {
        self.steps += 1;
        self.check_blow_up((b.u, b.v), (u1, v1))?;
        let g = self.general.as_deref_mut().expect("a General path");
        (self.drift, self.pw) = g.node(self.h, u1, v1);
        if g.extras() {
            // the fractional terms' pieces of V (split at an impact) and U·η_m at the end (as
            // `Stepper::step_general` at the wall at 0); a step that sticks with the memory
            // restarting pushes nothing: the fractional memories restart too
            let extra = if piece.is_none() && g.fractional() {
                g.restart_memories();
                0.0
            } else {
                g.end_step(b.v, u1, v1)
            };
            let right = self.drift + b.fr + extra;
            let piece = piece.map(|mut piece| {
                piece.right = right;
                self.history.push(piece);
                piece
            });
            self.u = u1;
            self.v = v1;
            return Ok(piece);
        }
        let piece = piece.map(|mut piece| {
            piece.right = self.drift + b.fr;
            self.history.push(piece);
            piece
        });
        self.u = u1;
        self.v = v1;
        Ok(piece)
    }

    /// The impact on wall `law` (on `side`) inside the current step whose free end was
    /// (u1, v1): locate it, jump by the restitution law, redo the rest of the step from the
    /// wall. Returns what it found and did (the split, V(t*), the jump, the redone rest).
    #[cold]
    fn impact_wall(&mut self, law: Law, side: Side, b: &Begin, (u1, v1): (f64, f64)) -> WallImpact {
        let h = self.h;
        let delta = law.position;
        let theta = hermite_root(self.u - delta, self.v, u1 - delta, v1, h);
        let eta_star = b.el + theta * (b.er - b.el);
        let (hs, ws) = self.history.at_fraction(theta, b.gl);
        let g: &General = self.general.as_deref().expect("a General path");
        // the forcing at the instant (noise, harmonic and δ·η_m) and the wall's force −k(δ)
        let forcing = self.rhs.forcing(eta_star, self.side) + g.force_at(theta);
        let forcing = if g.multiplicative() {
            forcing + g.parametric_at(delta)
        } else {
            forcing
        };
        let at_wall = forcing - g.restoring(delta);
        let fractional = g.fractional();
        let (v_at, memories) = if fractional {
            // and the fractional terms' −Σ K_j m_j(t*), affine in V(t*)
            let memories = g.memories_at(theta, self.v);
            let (lag, weight, local) = memories;
            let kappa = weight + local;
            let v = g.wall_velocity_lagged(delta, self.base + hs, ws, at_wall + lag, kappa);
            (v, memories)
        } else {
            (
                g.wall_velocity(delta, self.base + hs, ws, at_wall),
                (0.0, 0.0, 0.0),
            )
        };
        // the scheme's V(t*−) may point away from the wall at a grazing impact: then V₋ = 0
        let v_minus = match side {
            Side::Lower => v_at.min(0.0),
            Side::Upper => v_at.max(0.0),
        };
        let v_plus = -law.restitution.at(v_minus.abs()) * v_minus;
        if fractional {
            return self.impact_wall_fractional(
                b,
                Crossing {
                    theta,
                    eta_star,
                    a0: 0.0,
                    ws,
                    forcing,
                    v_at,
                    memories,
                },
                delta,
                (v_minus, v_plus),
            );
        }
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
        WallImpact {
            split,
            ws,
            v_at,
            v_minus,
            v_plus,
            free,
        }
    }
}

impl Stepper {
    /// The jump and the redone rest of [`Stepper::impact_wall`] for a path with fractional
    /// terms (module docs of `super::general`, "Fractional terms at a wall"): their memories
    /// split at the instant, g's split piece with −Σ_j K_j m_j(t*), the rest with the split
    /// memories' known part and weight (its tangent: `Stepper::impact_wall_with_tangent`).
    #[cold]
    fn impact_wall_fractional(
        &mut self,
        b: &Begin,
        c: Crossing,
        delta: f64,
        (v_minus, v_plus): (f64, f64),
    ) -> WallImpact {
        let h = self.h;
        self.record_impact(c.theta, v_minus, v_plus);
        self.memory_at_impact(c.v_at, v_plus);
        let (v_n, keep_before) = (self.v, !self.restart);
        let g = self.general.as_deref_mut().expect("a General path");
        let split = split_fractional(g, &c, delta, v_n, keep_before, (c.v_at, v_plus), h);
        let (known_s, wr_s) = self.history.current_split(b.gl, &split.split);
        let known = self.base + self.history.value() + known_s;
        // the step's known forcing without the unsplit memories' part, with the split's
        let fr = self.rhs.forcing(b.er, self.side) + g.force_now() + split.ahead;
        let free = g.advance_split(
            split.kappa,
            split.len,
            (delta, v_plus, split.split.after),
            split.pw,
            known,
            wr_s,
            fr,
        );
        WallImpact {
            split: split.split,
            ws: c.ws,
            v_at: c.v_at,
            v_minus,
            v_plus,
            free,
        }
    }
}

/// What [`Stepper::impact_wall`] found and did, kept for the tangent.
#[derive(Debug, Clone, Copy)]
pub(super) struct WallImpact {
    /// The split of g at the instant (θ in it).
    pub(super) split: Split,
    /// The scaled weight of g at the instant in V(t*).
    pub(super) ws: f64,
    /// The scheme's V(t*−), before the wall's clipping.
    pub(super) v_at: f64,
    pub(super) v_minus: f64,
    pub(super) v_plus: f64,
    /// The redone rest of the step, from (δ, V₊).
    pub(super) free: GeneralFree,
}

/// dr/dv of the restitution law at the impact speed v (0 for a constant r).
fn restitution_slope(r: Restitution, speed: f64) -> f64 {
    match r {
        Restitution::Constant(_) => 0.0,
        Restitution::Speed(s) => {
            -(s.r0 - s.r_fast) / s.speed * crate::maths::exp(-speed.abs() / s.speed)
        }
    }
}

impl Stepper {
    /// [`Stepper::step_walls`] with its tangent `t` (module docs of `super::tangent`, "Walls of
    /// the General kernel"): the path advanced bit for bit as by `step_walls`, the tangent the
    /// derivative of the step taken (free, clamped, or an impact with the redone rest).
    pub(super) fn step_walls_with_tangent(&mut self, walls: Walls, t: &mut Tangent) -> Result<()> {
        // with the fractional terms and U·η_m (module docs of `super::tangent`)
        let (b, [mut u1, mut v1, mut du1, mut dv1], (dgl, dahead)) =
            self.begin_general_with_tangent(t);
        self.events = StepEvents::default();
        let mut piece = Piece {
            left: b.gl,
            right: 0.0,
            split: None,
        };
        let mut dpiece = Piece {
            left: dgl,
            right: 0.0,
            split: None,
        };
        let mut dtheta = 0.0;
        let mut push = true;
        if let Some(delta) = self.pressed(walls, u1) {
            push = self.stick(v1);
            t.stick(dv1, self.restart);
            (u1, v1, du1, dv1) = (delta, 0.0, 0.0, 0.0);
        } else if let Some(side) = walls.beyond(u1) {
            let law = walls.law(side);
            let (split, dsplit, dth, end) =
                self.impact_wall_with_tangent(t, law, side, &b, (dgl, dahead), [u1, v1, du1, dv1]);
            [u1, v1, du1, dv1] = end;
            piece.split = Some(split);
            dpiece.split = Some(dsplit);
            dtheta = dth;
            if self.beyond_again(walls, side, u1)? {
                push = self.stick(v1);
                t.stick(dv1, self.restart);
                (u1, v1, du1, dv1) = (law.position, 0.0, 0.0, 0.0);
                self.stuck = true;
            }
        }
        let pushed = self.end_wall_step(&b, (u1, v1), push.then_some(piece))?;
        let g = self.general.as_deref().expect("a General path");
        let ddrift = g.drift_derivative(u1, v1, du1, dv1);
        // the fractional terms' δ(−Σ_j K_j m_j) and δV's piece (split at an impact), δ(U·η_m)
        // at the end (0 at the wall at 0, where a clamped step ends); a step that sticks with
        // the memory restarting restarts the tangent's memories of δV with the reference's
        let dextra = if !g.extras() {
            0.0
        } else if pushed.is_none() && g.fractional() {
            g.restart_tangent(t);
            0.0
        } else {
            let dv = t.v;
            dahead + g.end_tangent(t, (b.v, v1), (dv, dahead), (du1, dv1))
        };
        if let Some(piece) = pushed {
            dpiece.right = ddrift + dextra;
            if dtheta != 0.0 {
                if let Some(d) = dpiece.split.as_mut() {
                    fold_theta(&piece, d, dtheta);
                }
            }
            t.history.push(dpiece);
        }
        t.u = du1;
        t.v = dv1;
        t.drift = ddrift;
        Ok(())
    }

    /// [`Stepper::impact_wall`] with the derivative of the impact step: `free` is the free end
    /// (U₁, V₁, δU₁, δV₁), `dgl` δg at the step's start, `dahead` δ of the known forcing's
    /// part from the fractional terms (of the unsplit step: the redone rest's is the split
    /// memories', `General::split_tangent`). Returns the reference's split, the
    /// tangent's (its values' derivatives with θ held; [`fold_theta`] adds the θ-derivative
    /// when the piece is complete), δθ and the end (U, V, δU, δV).
    #[cold]
    fn impact_wall_with_tangent(
        &mut self,
        t: &mut Tangent,
        law: Law,
        side: Side,
        b: &Begin,
        (dgl, dahead): (f64, f64),
        [u1, v1, du1, dv1]: [f64; 4],
    ) -> (Split, Split, f64, [f64; 4]) {
        let h = self.h;
        let delta = law.position;
        // δθ: θ is the root of the Hermite interpolant of U − δ over the free step
        let theta = hermite_root(self.u - delta, self.v, u1 - delta, v1, h);
        let hb = hermite_basis(theta);
        let db = hermite_basis_slope(theta);
        let dh = hb[0] * t.u + hb[1] * h * t.v + hb[2] * du1 + hb[3] * h * dv1;
        let slope =
            db[0] * (self.u - delta) + db[1] * h * self.v + db[2] * (u1 - delta) + db[3] * h * v1;
        let mut dtheta = -dh / slope;
        if !(dtheta.is_finite() && theta > 0.0 && theta < 1.0) {
            // the interpolant touches the wall (H′ = 0) or the impact ends the step: θ held
            dtheta = 0.0;
        }
        // the reference's memory at the moving instant, before a restart clears it
        let (dhs, _) = t.history.at_fraction(theta, dgl);
        let (rate_hs, rate_ws) = if dtheta != 0.0 {
            self.history.at_fraction_rate(theta, b.gl)
        } else {
            (0.0, 0.0)
        };
        // the fractional terms at the instant, −Σ_j K_j m_j(t*) = lag* − κ*V(t*) (κ* = weight
        // + local), and δ of lag* and of the weight, before a restart clears the memories
        let g: &General = self.general.as_deref().expect("a General path");
        let fractional = g.fractional();
        let ((_, weight, local), (dlag, dweight)) = if fractional {
            let memories = g.memories_at(theta, self.v);
            (
                memories,
                g.memories_at_tangent(t, (theta, dtheta), (self.v, t.v)),
            )
        } else {
            ((0.0, 0.0, 0.0), (0.0, 0.0))
        };
        let kappa = weight + local;
        let hit = self.impact_wall(law, side, b, (u1, v1));
        debug_assert_eq!(hit.split.theta, theta);
        let g: &General = self.general.as_deref().expect("a General path");
        // δ of g's forcing at the instant: the noise interpolated over the step and F cos ψ*
        let dforcing = (self.rhs.forcing(b.er - b.el, self.side) + g.force_at_rate(theta)) * dtheta;
        // V(t*) = N + w_s((h(δ, V) − κ*)V + at_wall + lag*):
        // (1 − w_s(∂_V(hV) − κ*))δV = δN + δw_s·g(t*) + w_s(δF + δlag* − δκ*·V(t*))
        let g_at = hit.split.before;
        let dws = rate_ws * dtheta;
        let dfrac = dlag - dweight * hit.v_at;
        let slope_at = if fractional {
            g.a(delta, hit.v_at) - kappa
        } else {
            g.a(delta, hit.v_at)
        };
        let dv_at = (t.base + dhs + rate_hs * dtheta + dws * g_at + hit.ws * (dforcing + dfrac))
            / (1.0 - hit.ws * slope_at);
        // V₋ = V(t*) unless the wall clipped it; V₊ = −r(|V₋|)V₋
        let dv_minus = if hit.v_minus == hit.v_at { dv_at } else { 0.0 };
        let speed = hit.v_minus.abs();
        let dv_plus = -(law.restitution.at(speed)
            + restitution_slope(law.restitution, speed) * speed)
            * dv_minus;
        let keep = !self.restart;
        // the fractional terms' part of g after the instant: the terms with a memory keep
        // their value (0 when they restart there), the α = 1 terms follow V to V₊
        let dafter = if keep {
            dlag - dweight * hit.v_at - weight * dv_at
        } else {
            0.0
        } - local * dv_plus;
        let dsplit = Split {
            theta,
            before: slope_at * dv_at + dforcing + dfrac,
            after: g.a(delta, hit.v_plus) * dv_plus + dforcing + dafter,
            keep_before: keep,
            mass: 0.0,
        };
        // the memories of δV split as the reference's (restarted with them), and δ of the
        // redone rest's known forcing and κ_s
        let (dfr, dkappa) = if fractional {
            let d = Split {
                theta,
                before: dv_at,
                after: dv_plus,
                keep_before: keep,
                mass: 0.0,
            };
            g.split_tangent(t, (self.v, t.v), d, dtheta)
        } else {
            (dahead, 0.0)
        };
        // the redone rest from (δ, V₊) over (1 − θ)Δt: its known part, weight, length and
        // predictor weight follow θ and V₊
        let (dknown, rate_w) = self.tangent_across_impact(
            t,
            (b.gl, dgl),
            (&hit.split, &dsplit),
            dtheta,
            (dv_at, dv_plus),
        );
        let g: &General = self.general.as_deref().expect("a General path");
        let len = (1.0 - theta) * h;
        let dlen = -h * dtheta;
        // the predictor's weight of the rest has ∂_V g = a(δ, V₊) − κ_s
        let (a_plus, da_plus) = (
            g.a(delta, hit.v_plus) - hit.free.kappa(),
            g.a_derivative(delta, hit.v_plus, 0.0, dv_plus) - dkappa,
        );
        let dpw = predictor_weight_len_slope(len, a_plus) * dlen
            + predictor_weight_slope(len, a_plus, da_plus);
        let (du_end, dv_end) = g.advance_tangent_moving(
            &hit.free,
            (delta, hit.v_plus),
            (0.0, dv_plus, dsplit.after),
            dpw,
            (dknown, dfr),
            (dlen, rate_w * dtheta, dkappa),
        );
        let (u_end, v_end) = hit.free.end();
        (hit.split, dsplit, dtheta, [u_end, v_end, du_end, dv_end])
    }
}
