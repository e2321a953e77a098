//! Impacts inside a step (one routine for the wall and for the Zhuravlev crossing): the
//! crossing located on the step's cubic Hermite interpolant, the jump V₊ = ∓rV₋, and the rest
//! of the step redone from the wall (module docs of [`super`]).
//!
//! # Equation
//! At the wall U = 0 (keeping U ≥ 0): U̇₊ = −rU̇₋ (Eq. 1); at Eq. 9's crossing Z = 0:
//! Ż₊ = rŻ₋. The model's other walls (any δ, keeping below, two walls, r(|U̇₋|)) are the
//! General kernel's, in `super::walls`, which uses [`hermite_root`] and the bookkeeping here
//! (`record_impact`, `memory_at_impact`). A General path with fractional terms K_j·D^{α_j}U also
//! splits each term's memory of V at the instant ([`split_fractional`]; module docs of
//! `super::general`, "Fractional terms at a wall").
//!
//! # Method
//! θ ∈ (0, 1] of the step from the cubic Hermite interpolant of (U_n, V_n) → (U₁, V₁) (Newton
//! inside a shrinking bracket); the scheme's V(t*) = (N + J(θ) + w_s F(t*))/(1 − w_s a(0)) (for
//! the General kernel the root of V = N + w_s(h(0, V)V + F(t*)), `General::wall_velocity` at
//! δ = 0); the jump; the memory holds it exactly (a split piece with g before and after, the
//! Volterra constant shifted by V₊ − V(t*), or a restart); the rest of the step redone from
//! (0, V₊).
//!
//! # Reference
//! Diethelm, Ford & Freed (2002) for the scheme; model-class.md §4 for the walls.
//!
//! # Tests
//! `newton_crossing_equals_bisection` below; `tests/impacts.rs`, `tests/pinned.rs` (the paper's
//! impacts pinned bit for bit); `tests/walls.rs` (the model's walls); `tests/fractional_walls.rs`
//! (fractional terms at the walls).

use super::general::General;
use super::{predictor_weight, Free, Impact, Split, Stepper};

/// θ ∈ (0, 1] where the cubic Hermite interpolant of (u0, v0) → (u1, v1) over a step h
/// changes sign (u0 and u1 of opposite signs, or u1 = 0): Newton's method from the secant
/// root, kept inside a bracket that every iterate shrinks (a bisection step whenever Newton
/// would leave it), to |Δθ| ≤ 1e-15. Typically 3–5 iterations; at most 100.
pub(super) fn hermite_root(u0: f64, v0: f64, u1: f64, v1: f64, h: f64) -> f64 {
    let (hv0, hv1) = (h * v0, h * v1);
    let f = |t: f64| {
        let t2 = t * t;
        let t3 = t2 * t;
        (2.0 * t3 - 3.0 * t2 + 1.0) * u0
            + (t3 - 2.0 * t2 + t) * hv0
            + (-2.0 * t3 + 3.0 * t2) * u1
            + (t3 - t2) * hv1
    };
    let df = |t: f64| {
        let t2 = t * t;
        (6.0 * t2 - 6.0 * t) * (u0 - u1)
            + (3.0 * t2 - 4.0 * t + 1.0) * hv0
            + (3.0 * t2 - 2.0 * t) * hv1
    };
    let (mut a, mut b) = (0.0, 1.0);
    let fa_pos = u0 > 0.0 || (u0 == 0.0 && u1 < 0.0);
    let secant = if u0 != u1 { u0 / (u0 - u1) } else { 0.5 };
    let mut t = if secant > 0.0 && secant < 1.0 {
        secant
    } else {
        0.5
    };
    for _ in 0..100 {
        let ft = f(t);
        if ft == 0.0 {
            return t;
        }
        if (ft > 0.0) == fa_pos {
            a = t;
        } else {
            b = t;
        }
        let d = df(t);
        let mut next = t - ft / d;
        if !(next > a && next < b) {
            next = 0.5 * (a + b);
        }
        let done = (next - t).abs() <= 1e-15 || b - a <= 1e-15;
        t = next;
        if done {
            break;
        }
    }
    t
}

impl Stepper {
    /// The impact (wall) or crossing (Eq. 9) inside the current step, whose free end was
    /// (u1, v1): locate it, jump, and redo the rest of the step. Returns the split of g and the
    /// state at the end of the step.
    #[cold]
    pub(super) fn impact(
        &mut self,
        gl: f64,
        (el, er): (f64, f64),
        (u1, v1): (f64, f64),
    ) -> (Split, f64, f64) {
        let c = self.locate(gl, (el, er), (u1, v1));
        if self.general.is_some() {
            return self.jump_general(&c, gl, er);
        }
        let rest = self.jump(&c, gl, er);
        let (u_end, v_end) = rest.free.end();
        (rest.split, u_end, v_end)
    }

    /// Where the current step, whose free end was (u1, v1), crosses U = 0, and the scheme's
    /// velocity there (changes nothing).
    pub(super) fn locate(&self, gl: f64, (el, er): (f64, f64), (u1, v1): (f64, f64)) -> Crossing {
        let h = self.h;
        let theta = hermite_root(self.u, self.v, u1, v1, h);
        let eta_star = el + theta * (er - el);
        // g at U = 0 is a0·V + forcing
        let a0 = self.rhs.damping(0.0);
        let (hs, ws) = self.history.at_fraction(theta, gl);
        let mut forcing = self.rhs.forcing(eta_star, self.side);
        // the scheme's own V(t*−); at a grazing wall impact it may come out ≥ 0: then V₋ = 0
        let mut v_at = (self.base + hs + ws * forcing) / (1.0 - ws * a0);
        let mut memories = (0.0, 0.0, 0.0);
        if let Some(g) = &self.general {
            // g at the wall is h(0, V)V + F cos ψ* + η* (module docs of `general`)
            forcing += g.force_at(theta);
            if g.fractional() {
                // and −Σ K_j m_j(t*), affine in V(t*)
                memories = g.memories_at(theta, self.v);
                let (lag, weight, local) = memories;
                let kappa = weight + local;
                v_at = g.wall_velocity_lagged(0.0, self.base + hs, ws, forcing + lag, kappa);
            } else {
                v_at = g.wall_velocity(0.0, self.base + hs, ws, forcing);
            }
        }
        Crossing {
            theta,
            eta_star,
            a0,
            ws,
            forcing,
            v_at,
            memories,
        }
    }

    /// Count an impact at θ of the step and report it as the step's event.
    #[inline]
    pub(super) fn record_impact(&mut self, theta: f64, v_minus: f64, v_plus: f64) {
        self.impacts += 1;
        self.events.impact = Some(Impact {
            time: self.time() + theta * self.h,
            v_minus,
            v_plus,
        });
    }

    /// V(t*+) = V₊ exactly: restart the memory at the impact, or shift V's Volterra constant
    /// by the jump V₊ − V(t*).
    #[inline]
    pub(super) fn memory_at_impact(&mut self, v_at: f64, v_plus: f64) {
        if self.restart {
            self.history.restart();
            self.base = v_plus;
        } else {
            self.base += v_plus - v_at;
        }
    }

    /// Jump at the located crossing `c` and redo the rest of the step.
    pub(super) fn jump(&mut self, c: &Crossing, gl: f64, er: f64) -> Rest {
        let h = self.h;
        let side = self.side;
        let (theta, a0, v_at) = (c.theta, c.a0, c.v_at);
        let (v_minus, v_plus, new_side) = if self.crossing {
            (v_at, self.rhs.restitution * v_at, -side)
        } else {
            let vm = v_at.min(0.0);
            (vm, -self.rhs.restitution * vm, side)
        };
        self.record_impact(theta, v_minus, v_plus);
        self.side = new_side;
        let after_forcing = self.rhs.forcing(c.eta_star, new_side);
        let split = Split {
            theta,
            before: a0 * v_at + c.forcing,
            after: a0 * v_plus + after_forcing,
            keep_before: !self.restart,
            mass: 0.0,
        };
        self.memory_at_impact(v_at, v_plus);
        // the rest of the step, [t*, t_{n+1}], from (0, V₊), linearly implicit in V
        let (known_s, wr_s) = self.history.current_split(gl, &split);
        let known = self.base + self.history.value() + known_s;
        let hh = (1.0 - theta) * h;
        let free = self.rhs.advance(
            hh,
            (0.0, v_plus, split.after),
            predictor_weight(hh, a0),
            known,
            wr_s,
            self.rhs.forcing(er, new_side),
        );
        Rest {
            split,
            v_minus,
            free,
        }
    }
}

impl Stepper {
    /// [`Stepper::jump`] for the General kernel (the wall at 0; module docs of `general`):
    /// the split piece's values h(0, V)V + forcing at V(t*) and V₊, the rest of the step by the
    /// General kernel from (0, V₊). Returns the split and the end of the step.
    fn jump_general(&mut self, c: &Crossing, gl: f64, er: f64) -> (Split, f64, f64) {
        let h = self.h;
        let (theta, v_at) = (c.theta, c.v_at);
        let v_minus = v_at.min(0.0);
        let v_plus = -self.rhs.restitution * v_minus;
        self.record_impact(theta, v_minus, v_plus);
        self.memory_at_impact(v_at, v_plus);
        let (v_n, keep_before) = (self.v, !self.restart);
        let g = self.general.as_deref_mut().expect("a General path");
        if g.fractional() {
            let split = split_fractional(g, c, 0.0, v_n, keep_before, (v_at, v_plus), h);
            let (known_s, wr_s) = self.history.current_split(gl, &split.split);
            let known = self.base + self.history.value() + known_s;
            let fr = self.rhs.forcing(er, self.side) + g.force_now() + split.ahead;
            let free = g.advance_split(
                split.kappa,
                split.len,
                (0.0, v_plus, split.split.after),
                split.pw,
                known,
                wr_s,
                fr,
            );
            let (u_end, v_end) = free.end();
            return (split.split, u_end, v_end);
        }
        let split = Split {
            theta,
            before: g.wall_drift(0.0, v_at) + c.forcing,
            after: g.wall_drift(0.0, v_plus) + c.forcing,
            keep_before,
            mass: 0.0,
        };
        let (known_s, wr_s) = self.history.current_split(gl, &split);
        let known = self.base + self.history.value() + known_s;
        let hh = (1.0 - theta) * h;
        let fr = self.rhs.forcing(er, self.side) + g.force_now();
        let pw = predictor_weight(hh, g.a(0.0, v_plus));
        let free = g.advance(hh, (0.0, v_plus, split.after), pw, known, wr_s, fr);
        let (u_end, v_end) = free.end();
        (split, u_end, v_end)
    }
}

/// The split of an impact step of a General path with fractional terms, on a wall at δ
/// (module docs of `general`, "Fractional terms at a wall"): g's split piece for the leading
/// memory, with −Σ_j K_j m_j(t*) at the instant on both sides (continuous in t; 0 after the
/// instant when the memories restart there), and what the redone rest of the step needs.
pub(super) struct FractionalSplit {
    /// g's split (for the leading memory).
    pub(super) split: Split,
    /// The part of −Σ_j K_j m_{j,n+1} known after the impact (into the rest's forcing).
    pub(super) ahead: f64,
    /// The weight of V_{n+1} in Σ_j K_j m_{j,n+1} on the split step.
    pub(super) kappa: f64,
    /// The rest's length (1 − θ)Δt and its predictor's weight.
    pub(super) len: f64,
    pub(super) pw: f64,
}

/// [`FractionalSplit`] at the crossing `c` on the wall at `delta`, from V_n = `v_n`, V jumping
/// from V(t*) to V₊: splits the fractional memories ([`General::split_memories`]).
pub(super) fn split_fractional(
    g: &mut General,
    c: &Crossing,
    delta: f64,
    v_n: f64,
    keep_before: bool,
    (v_at, v_plus): (f64, f64),
    h: f64,
) -> FractionalSplit {
    // the terms with a memory are continuous at the instant (0 after it when they restart
    // there), the α = 1 terms follow V
    let (lag, weight, local) = c.memories;
    let at = lag - (weight + local) * v_at;
    let kept = if keep_before {
        lag - weight * v_at
    } else {
        0.0
    };
    let after = kept - local * v_plus;
    let memories = Split {
        theta: c.theta,
        before: v_at,
        after: v_plus,
        keep_before,
        mass: 0.0,
    };
    let (ahead, kappa) = g.split_memories(v_n, memories);
    let split = Split {
        theta: c.theta,
        before: g.wall_drift(delta, v_at) + c.forcing + at,
        after: g.wall_drift(delta, v_plus) + c.forcing + after,
        keep_before,
        mass: 0.0,
    };
    let len = (1.0 - c.theta) * h;
    FractionalSplit {
        split,
        ahead,
        kappa,
        len,
        pw: predictor_weight(len, g.a(delta, v_plus) - kappa),
    }
}

/// An impact located inside a step ([`Stepper::locate`]).
#[derive(Debug, Clone, Copy)]
pub(super) struct Crossing {
    /// Its fraction θ of the step.
    pub(super) theta: f64,
    /// η at the instant.
    pub(super) eta_star: f64,
    /// μP(0).
    pub(super) a0: f64,
    /// The scaled weight of g(t*) in V(t*).
    pub(super) ws: f64,
    /// The forcing at the instant, on the side before.
    pub(super) forcing: f64,
    /// The scheme's V(t*−), before the wall's clipping of a grazing impact.
    pub(super) v_at: f64,
    /// −Σ_j K_j m_j(t*−) of a General path's fractional terms as (known part, weight of V(t*)
    /// of the terms with a memory, Σ K_j of the α = 1 terms) ([`General::memories_at`]);
    /// zeros without them.
    pub(super) memories: (f64, f64, f64),
}

/// The jump and the redone rest of an impact step ([`Stepper::jump`]).
#[derive(Debug, Clone, Copy)]
pub(super) struct Rest {
    pub(super) split: Split,
    pub(super) v_minus: f64,
    /// The rest of the step, of length (1 − θ)Δt from (0, V₊).
    pub(super) free: Free,
}

#[cfg(test)]
mod tests {
    use super::hermite_root;

    /// The root by plain bisection (60 halvings), the reference for Newton's iteration.
    fn bisected(u0: f64, v0: f64, u1: f64, v1: f64, h: f64) -> f64 {
        let f = |t: f64| {
            let (t2, t3) = (t * t, t * t * t);
            (2.0 * t3 - 3.0 * t2 + 1.0) * u0
                + (t3 - 2.0 * t2 + t) * h * v0
                + (-2.0 * t3 + 3.0 * t2) * u1
                + (t3 - t2) * h * v1
        };
        let (mut a, mut b) = (0.0, 1.0);
        for _ in 0..60 {
            let m = 0.5 * (a + b);
            if (f(m) > 0.0) == (u0 > 0.0) {
                a = m;
            } else {
                b = m;
            }
        }
        0.5 * (a + b)
    }

    #[test]
    fn newton_crossing_equals_bisection() {
        // steps that end across the wall: grazing (small velocities), fast, and skewed
        let cases = [
            (0.3, -40.0, -0.1, -41.0, 0.01),
            (1e-6, -1e-3, -1e-7, -2e-3, 0.01),
            (2.0, -1.0, -0.5, -3.0, 1.0),
            (0.01, 0.5, -0.02, -6.0, 0.01),
            (5e-3, -0.2, -1e-12, -0.2, 0.025),
        ];
        for (u0, v0, u1, v1, h) in cases {
            let t = hermite_root(u0, v0, u1, v1, h);
            let r = bisected(u0, v0, u1, v1, h);
            assert!(t > 0.0 && t <= 1.0);
            assert!(
                (t - r).abs() < 1e-13,
                "{t} vs {r} for {:?}",
                (u0, v0, u1, v1, h)
            );
        }
    }
}
