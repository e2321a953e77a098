//! One path's statistics as a piece of one run, for pieces that travel (a checkpoint file, a
//! task on another machine) and come back to [`super::merge`].
//!
//! # Problem
//! A piece read back may belong to another run (other parameters, method, sizes, seed, or
//! another version of trirhythm), or be filed under another index. Merged, it would give a
//! wrong answer without an error.
//!
//! # Method
//! [`fingerprint`] names the run: the version, the parameters, the method, the spec and the
//! problem's starts, system, wall and blow-up bound, as text. A [`Piece`] carries it beside the
//! path's statistics (serialised flat: the statistics' fields and `fingerprint`), and
//! [`Piece::verify`] checks the fingerprint, the index and the shapes ([`super::fits`]) before
//! the statistics are used.
//!
//! # Tests
//! The CLI's `tests/checkpoint.rs`: foreign, re-indexed and reshaped path files are refused.

use super::{fits, EnsembleSpec, PathStats};
use crate::engine::{Lanes, PredictorCorrector, Problem};
use crate::error::{Error, Result};
use serde::{Deserialize, Serialize};

/// The run a piece belongs to, as text: everything that changes its statistics.
pub fn fingerprint(problem: &Problem, method: &PredictorCorrector, spec: &EnsembleSpec) -> String {
    // the lane count changes no statistic: pieces run with any lanes merge
    let spec = &EnsembleSpec {
        lanes: Lanes::Auto,
        ..spec.clone()
    };
    let mut text = format!(
        "trirhythm ensemble {}\nparams: {}\n{method:?}\nspec: {spec:?}\nstarts: {:?} system: {:?} \
         barrier: {:?} blow_up: {:e}\n",
        env!("CARGO_PKG_VERSION"),
        problem.params().describe(),
        problem.starts(),
        problem.system(),
        problem.barrier(),
        problem.blow_up()
    );
    // the General kernel's terms (absent for the paper's family, whose fingerprints stay)
    if let Some(t) = problem.oscillator().terms() {
        text.push_str(&format!("terms: {}\n", t.describe()));
    }
    text
}

/// One path's statistics with the [`fingerprint`] of their run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Piece {
    /// The run's [`fingerprint`].
    pub fingerprint: String,
    /// The path's statistics.
    #[serde(flatten)]
    pub stats: PathStats,
}

impl Piece {
    /// The statistics, if the piece is path `index` of the run `fingerprint` with this run's
    /// shapes; otherwise [`Error::Undefined`] saying why.
    pub fn verify(
        self,
        fingerprint: &str,
        index: u64,
        problem: &Problem,
        spec: &EnsembleSpec,
    ) -> Result<PathStats> {
        let refuse = |why: String| {
            Err(Error::Undefined {
                what: "this piece",
                why,
            })
        };
        if self.fingerprint != fingerprint {
            return refuse("written by another run (its fingerprint differs)".into());
        }
        if self.stats.path != index {
            return refuse(format!(
                "holds path {} but its name says path {index}",
                self.stats.path
            ));
        }
        if !fits(&self.stats, spec, problem) {
            return refuse(
                "its statistics have another shape than this run's (bins, batches, wells or start)"
                    .into(),
            );
        }
        Ok(self.stats)
    }
}
