//! Library results as people read them: the sentences the CLI prints (standard error, `#`
//! lines) and the tables its CSV files hold, written once so that a report or a binding shows
//! the same. By result: ensembles and a path, Lyapunov exponents and critical noise, the
//! averaged theory, planes (boundaries, branches, maps).

mod ensemble;
mod lyapunov;
mod planes;
mod theory;

pub use ensemble::*;
pub use lyapunov::*;
pub use planes::*;
pub use theory::*;

use crate::notes::num;
use trirhythm::analysis::Estimate;

/// An estimate with five decimals: "value ± stderr", or "(no standard error)".
pub fn estimate(e: Estimate) -> String {
    if e.stderr.is_finite() {
        format!("{:.5} ± {:.5}", e.value, e.stderr)
    } else {
        format!("{:.5} (no standard error)", e.value)
    }
}

/// Numbers with four decimals, comma-separated.
pub fn list(v: &[f64]) -> String {
    v.iter()
        .map(|x| format!("{x:.4}"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// A CSV cell: the number, or empty when undefined.
pub fn cell(v: f64) -> String {
    if v.is_finite() {
        num(v)
    } else {
        String::new()
    }
}

/// A cell of a table for reading with `digits` decimals, in exponent notation outside
/// [1e-4, 1e9) so that no cell runs to hundreds of digits or rounds a small value to 0.
pub fn fixed(v: f64, digits: usize) -> String {
    let v = v + 0.0;
    let a = v.abs();
    if !v.is_finite() {
        num(v)
    } else if v == 0.0 || (1e-4..1e9).contains(&a) {
        format!("{v:.digits$}")
    } else {
        format!("{v:.digits$e}")
    }
}
