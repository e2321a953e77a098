//! Benettin's renormalisation of a perturbed copy against its reference path (the
//! two-trajectory Lyapunov exponent, [`crate::analysis::lyapunov`]): separation, the pull of the
//! whole state toward the reference, and the test that two paths have merged for good.

use super::{predictor_weight, Stepper};

impl Stepper {
    /// (U − U_ref, V − V_ref) of this path against `reference` at the same time.
    pub fn separation(&self, reference: &Stepper) -> (f64, f64) {
        (self.u - reference.u, self.v - reference.v)
    }

    /// Benettin's renormalisation of a perturbed copy: pull this path toward `reference` (a
    /// path of the same problem at the same step, usually the one this copy was cloned from,
    /// so with the same noise) by the factor `c`, **whole state included** — U, V, the
    /// Volterra constant, g at the node and every number of the memory become
    /// x_ref + c·(x − x_ref). For a fractional system the state is the entire history: scaling
    /// (δU, δV) alone would leave the old perturbation in the memory.
    ///
    /// Returns false and changes nothing when the two paths cannot be combined number by
    /// number now: not at the same step, on different sides (Eq. 9) or in different sticking
    /// states, or an impact still inside the exact window of either (its split falls at a
    /// different fraction in each path; with `Memory::Direct` this holds after the first
    /// impact for good). A driver then tries again at a later step. A factor `c` that is not
    /// finite and ≥ 0 is refused the same way (it would poison the whole state).
    pub fn contract_toward(&mut self, reference: &Stepper, c: f64) -> bool {
        if !(c >= 0.0 && c.is_finite()) {
            return false;
        }
        if self.steps != reference.steps
            || self.side != reference.side
            || self.stuck != reference.stuck
            || self.h != reference.h
        {
            return false;
        }
        if let (Some(g), Some(r)) = (&self.general, &reference.general) {
            // the fractional terms' memories hold their split pieces where the leading memory
            // holds its own (the same impacts); tried first on a copy, so that nothing changes
            // on a refusal
            let mut trial = g.clone();
            if !trial.contract_toward(r, c) || !self.history.contract_toward(&reference.history, c)
            {
                return false;
            }
            self.general = Some(trial);
        } else if !self.history.contract_toward(&reference.history, c) {
            return false;
        }
        let pull = |r: f64, x: f64| r + c * (x - r);
        self.u = pull(reference.u, self.u);
        self.v = pull(reference.v, self.v);
        self.base = pull(reference.base, self.base);
        self.drift = pull(reference.drift, self.drift);
        self.pw = match &self.general {
            None => predictor_weight(self.h, self.rhs.damping(self.u)),
            Some(g) => predictor_weight(self.h, g.slope_v(self.u, self.v)),
        };
        true
    }

    /// Whether this path and `other` are in the same state, whole history included: same step,
    /// U, V, side, sticking state, Volterra constant, g at the node, noise and every number of
    /// the memory. Two such paths of the same problem and noise stream stay identical for good
    /// (a perturbed copy that has merged with its reference, e.g. both stuck at the wall at the
    /// same step with the memory restarted).
    pub fn coincides_with(&self, other: &Stepper) -> bool {
        self.steps == other.steps
            && self.h == other.h
            && self.u == other.u
            && self.v == other.v
            && self.side == other.side
            && self.stuck == other.stuck
            && self.base == other.base
            && self.drift == other.drift
            && self.noise.current() == other.noise.current()
            && self.history.coincides(&other.history)
            && match (&self.general, &other.general) {
                (Some(a), Some(b)) => a.coincides_with(b),
                (None, None) => true,
                _ => false,
            }
    }
}
