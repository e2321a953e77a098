//! The history as a vector of numbers: restart, scaling, the renormalisation toward a reference
//! (Benettin's method on the whole fractional state), comparisons and its size.
//!
//! Equation: J^λ is linear in g, so x ↦ x_ref + c·(x − x_ref) applied to every number of the
//! history is the history of g_ref + c·(g − g_ref).
//!
//! Method: every number of the state (window, split values, modes, moments, cached value) is
//! visited in one fixed order, paired with the reference's.
//!
//! Reference: Benettin's renormalisation of a perturbed copy (see `analysis::lyapunov`).
//!
//! Tests: `scaling_the_history_equals_the_history_of_the_scaled_g` and
//! `histories_coincide_after_the_same_restart_whatever_their_stale_slots` in the memory's unit
//! tests.

use super::modes::Modes;
use super::{History, Split};
use crate::engine::kernel::LUMPED_TERMS;

impl History {
    /// Forget everything (the memory restarts; the lower terminal moves to now).
    pub fn restart(&mut self) {
        self.all.clear();
        self.splits.clear();
        self.split_weights.clear();
        self.local.clear();
        self.modes.flat_mut().for_each(|y| *y = 0.0);
        self.moments = [0.0; LUMPED_TERMS];
        self.cached = 0.0;
    }

    /// Multiply the whole history by `c` (J^λ is linear in g).
    #[cfg(test)]
    pub fn scale(&mut self, c: f64) {
        self.zip_state(None, &mut |_, v| *v *= c);
    }

    /// Apply `f(reference's number, own number)` to every number of the history's state, paired
    /// with the same number of `reference` when one is given.
    fn zip_state(&mut self, reference: Option<&History>, f: &mut dyn FnMut(Option<f64>, &mut f64)) {
        fn pair(r: Option<&[f64]>, own: &mut [f64], f: &mut dyn FnMut(Option<f64>, &mut f64)) {
            for (k, v) in own.iter_mut().enumerate() {
                f(r.map(|r| r[k]), v);
            }
        }
        let flat = |m: &Modes| -> Vec<f64> { m.y.iter().flatten().copied().collect() };
        let r_modes = reference.map(|r| flat(&r.modes));
        pair(
            reference.map(|r| r.all.as_flattened()),
            self.all.as_flattened_mut(),
            f,
        );
        pair(
            reference.map(|r| r.local.pairs.as_flattened()),
            self.local.pairs.as_flattened_mut(),
            f,
        );
        for (k, (_, s)) in self.splits.iter_mut().enumerate() {
            let rs = reference.map(|r| r.splits[k].1);
            f(rs.map(|s| s.before), &mut s.before);
            f(rs.map(|s| s.after), &mut s.after);
            f(rs.map(|s| s.mass), &mut s.mass);
        }
        for (k, y) in self.modes.flat_mut().enumerate() {
            f(r_modes.as_ref().map(|r| r[k]), y);
        }
        for (k, m) in self.moments.iter_mut().enumerate() {
            f(reference.map(|r| r.moments[k]), m);
        }
        f(reference.map(|r| r.cached), &mut self.cached);
    }

    /// Whether `other` holds its history in the same layout (same pieces held exactly, split at
    /// the same steps and fractions), so that the two can be combined number by number.
    fn same_layout(&self, other: &History) -> bool {
        self.direct == other.direct
            && self.pushed == other.pushed
            && self.all.len() == other.all.len()
            && self.local.cap == other.local.cap
            && self.local.head == other.local.head
            && self.local.len == other.local.len
            && self.modes.y.len() == other.modes.y.len()
            && self.splits.len() == other.splits.len()
            && self
                .splits
                .iter()
                .zip(&other.splits)
                .all(|((a, s), (b, t))| {
                    a == b && s.theta == t.theta && s.keep_before == t.keep_before
                })
    }

    /// Whether this history and `other` are the same history, number by number: the same
    /// layout and equal pieces held exactly (not the ring's stale slots), split values, modes,
    /// moments and cached value. Two paths whose states coincide in this sense and in (U, V, …)
    /// stay identical under the same noise.
    pub(crate) fn coincides(&self, other: &History) -> bool {
        self.same_layout(other)
            && self.all == other.all
            && self.local.pieces() == other.local.pieces()
            && self.splits == other.splits
            && self.modes.y == other.modes.y
            && self.moments == other.moments
            && self.cached == other.cached
    }

    /// Whether every number of the history's state is zero (the history of g ≡ 0), the ring's
    /// stale slots aside.
    pub(crate) fn is_zero(&self) -> bool {
        let zero = |x: &f64| *x == 0.0;
        self.all.as_flattened().iter().all(zero)
            && self.local.pieces().as_flattened().iter().all(zero)
            && self
                .splits
                .iter()
                .all(|(_, s)| s.before == 0.0 && s.after == 0.0 && s.mass == 0.0)
            && self.modes.y.as_flattened().iter().all(zero)
            && self.moments.iter().all(zero)
            && self.cached == 0.0
    }

    /// Pull this history toward `reference` by the factor `c`: every number x of its state
    /// becomes x_ref + c·(x − x_ref). The map is affine in the history and J^λ is linear in g,
    /// so this is exactly the history of the path g_ref + c·(g − g_ref): the renormalisation of
    /// a perturbed copy in Benettin's method, applied to the entire memory (a fractional
    /// system's state is its whole history, not just (U, V)). Returns false, changing nothing,
    /// when the two layouts differ (different steps, an impact split at different fractions, a
    /// restart in one of them).
    pub fn contract_toward(&mut self, reference: &History, c: f64) -> bool {
        if !self.same_layout(reference) {
            return false;
        }
        self.zip_state(Some(reference), &mut |r, v| {
            let r = r.expect("reference given");
            *v = r + c * (*v - r);
        });
        true
    }

    /// Number of exponential modes (0 for Direct or λ = 1).
    pub fn exponentials(&self) -> usize {
        self.soe.as_ref().map_or(0, |k| k.len())
    }

    /// Bytes of state held (grows with N for Direct, constant for SOE).
    pub fn state_bytes(&self) -> usize {
        8 * (2 * self.all.capacity()
            + 2 * self.local.pairs.len()
            + self.wl.capacity()
            + self.wr.capacity()
            + 5 * self.modes.len())
            + std::mem::size_of::<(u64, Split)>() * self.splits.capacity()
            + std::mem::size_of::<[f64; 5]>()
                * self.split_weights.iter().map(Vec::len).sum::<usize>()
    }
}

/// What the tangent (variational) method needs from a history: the memory of δg is a second
/// [`History`] with the reference's layout (same kernel, same pieces held exactly, splits at the
/// same fractions), renormalised by scaling every number of it.
impl History {
    /// Multiply every number of the history's state by `c` (window, split values, SOE modes,
    /// lumped integral and moment, the cached value): the history of c·g, since J^λ is linear.
    pub(crate) fn scale_state(&mut self, c: f64) {
        self.zip_state(None, &mut |_, v| *v *= c);
    }

    /// Whether `other` holds its history in the same layout as this one (see
    /// [`History::contract_toward`]): a tangent memory must stay in step with its reference's.
    #[cfg(test)]
    pub(crate) fn same_layout_as(&self, other: &History) -> bool {
        self.same_layout(other)
    }
}
