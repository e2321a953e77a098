//! A probe of the memory's own cost per step, for the engine's timing breakdown.
//!
//! Equation: J^λ g for g = sin t, pushed piece by piece.
//!
//! Method: a fresh default memory; g by rotation so that the probe times the memory, not `sin`.
//!
//! Reference: none (a timing aid).
//!
//! Tests: exercised by the engine's timing breakdown and the hostile-input property test.

use super::{History, Memory, Piece, DEFAULT_WINDOW};
use crate::error::Result;

/// Push `steps` pieces of a smooth g into a fresh memory of order λ and return its final value:
/// the memory's own cost per step, for the engine's timing breakdown. `lambda` ∈ (0, 1],
/// `dt` > 0 finite, `steps` ≤ 10⁸.
#[doc(hidden)]
pub fn probe_memory(lambda: f64, dt: f64, steps: usize) -> Result<f64> {
    super::scalar::check_steps(dt, steps)?;
    let mut h = History::new(
        lambda,
        dt,
        dt * steps as f64,
        Memory::default(),
        DEFAULT_WINDOW,
    )?;
    // g = sin t by rotation (cheap, so that the probe times the memory, not `sin`)
    let (c, s) = (crate::maths::cos(dt), crate::maths::sin(dt));
    let (mut left, mut cos) = (0.0, 1.0);
    let mut acc = 0.0;
    for _ in 0..steps {
        let right = left * c + cos * s;
        cos = cos * c - left * s;
        h.push(Piece {
            left,
            right,
            split: None,
        });
        acc += h.value();
        left = right;
    }
    Ok(acc)
}
