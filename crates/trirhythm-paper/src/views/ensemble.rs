//! Ensembles and single paths in words and tables: the ensemble summary, its theory
//! comparisons in JSON, the amplitude density, a path's summary.

use super::{estimate, list};
use crate::notes::num;
use crate::table::Table;
use serde::Serialize;
use std::collections::BTreeMap;
use trirhythm::analysis::ensemble::{Density, EnsembleResult, WellsEstimate};
use trirhythm::analysis::versus::TheoryComparison;
use trirhythm::engine::Trajectory;
use trirhythm::theory::averaging::Variant;

/// The theory of each variant against an ensemble, or why there is none
/// ([`crate::montecarlo::comparisons`]).
pub type Comparisons = [(Variant, std::result::Result<TheoryComparison, String>)];

/// One variant of the theory against an ensemble in JSON: the comparison, or why there is none.
#[derive(Serialize)]
#[serde(untagged)]
pub enum TheoryEntry<'a> {
    /// The theory's P(A) against the simulation.
    Comparison(&'a TheoryComparison),
    /// Why the theory has no P(A) here.
    Error {
        /// The reason, in words.
        error: &'a str,
    },
}

/// The comparisons by variant name (`consistent`, `paper`), for a JSON document.
pub fn theory_entries(theory: &Comparisons) -> BTreeMap<&'static str, TheoryEntry<'_>> {
    theory
        .iter()
        .map(|(v, c)| {
            let entry = match c {
                Ok(c) => TheoryEntry::Comparison(c),
                Err(e) => TheoryEntry::Error { error: e },
            };
            (v.name(), entry)
        })
        .collect()
}

/// An ensemble in words: size and wall time, the moments, the stationarity diagnosis, the
/// wells' occupancy, the first passages and the theory against the simulation; one line each.
pub fn ensemble(r: &EnsembleResult, theory: &Comparisons, wall: f64) -> String {
    let st = &r.stationarity;
    let mut t = format!(
        "{} paths × {} steps in {wall:.1} s; ⟨A⟩ = {}; Var U = {}; Var U̇ = {}\n\
         stationarity: {} (R̂ = {:.3}, ESS = {:.0}, drift {:.1} standard errors)\n",
        r.paths,
        r.steps_per_path,
        estimate(r.mean_amplitude),
        estimate(r.var_u),
        estimate(r.var_v),
        if st.stationary {
            "passed"
        } else {
            "NOT STATIONARY"
        },
        st.r_hat,
        st.ess,
        st.drift_z
    );
    if !r.occupancy.is_empty() {
        let occupancy: Vec<String> = r.occupancy.iter().map(|&e| estimate(e)).collect();
        t.push_str(&format!(
            "occupancy of the wells: {}\n",
            occupancy.join(", ")
        ));
    }
    for (k, p) in r.passages.iter().enumerate() {
        let theory_times: Vec<String> = theory
            .iter()
            .filter_map(|(v, c)| {
                c.as_ref()
                    .ok()
                    .and_then(|c| c.escape_times.get(k))
                    .map(|t| format!("{} {t:.4e}", v.name()))
            })
            .collect();
        t.push_str(&format!(
            "first passage {} → {}: {} ({} completed, {} censored); theory's escape time: {}\n",
            p.from,
            p.to,
            if p.count > 0 {
                estimate(p.mean_time)
            } else {
                "none completed".into()
            },
            p.count,
            p.censored,
            theory_times.join(", ")
        ));
    }
    for (v, c) in theory {
        match c {
            Ok(c) => match c.modes_mc {
                None => t.push_str(&format!(
                    "theory ({}): no distance and no mode count: the simulated density does \
                     not exist; modes {} (theory, binned; {} exact); occupancy {}\n",
                    v.name(),
                    c.modes_theory,
                    c.modes_theory_exact,
                    list(&c.occupancy)
                )),
                Some(modes_mc) => t.push_str(&format!(
                    "theory ({}): Hellinger {:.4} ± {:.4}, L1 {:.4}, KS {:.4}; modes {} \
                     (theory, binned; {} exact) vs {modes_mc} (simulation); occupancy {}\n",
                    v.name(),
                    c.hellinger.value,
                    c.hellinger.stderr,
                    c.l1.value,
                    c.ks.value,
                    c.modes_theory,
                    c.modes_theory_exact,
                    list(&c.occupancy)
                )),
            },
            Err(e) => t.push_str(&format!("theory ({}): {e}\n", v.name())),
        }
    }
    for w in &r.warnings {
        t.push_str(&format!("warning: {w}\n"));
    }
    t
}

/// What the well decomposition adds, in words: the cores, each rate (flux × probability), the
/// weights, residence against relaxation, the verdict of its diagnostic, the cost.
pub fn wells(w: &WellsEstimate) -> String {
    let mut t =
        String::from("estimator: well decomposition (rates by adaptive multilevel splitting)\n");
    let cores: Vec<String> = w
        .cores
        .bounds
        .iter()
        .map(|(lo, hi)| format!("[{}, {}]", num(*lo), num(*hi)))
        .collect();
    for m in &w.missing {
        t.push_str(&format!(
            "theory well {} (mode {}) missing in the simulation: its pilot left after {} turning \
             points and settled in theory well {}\n",
            m.well,
            num(m.mode),
            m.stay,
            m.settled_in
        ));
    }
    t.push_str(&format!(
        "cores (turning amplitude): {}\n",
        cores.join(", ")
    ));
    for r in &w.rates {
        t.push_str(&format!(
            "rate {} → {}: {} per time unit (flux {} × probability {})\n",
            r.from,
            r.to,
            estimate(r.rate),
            estimate(r.flux),
            estimate(r.probability)
        ));
    }
    let weights: Vec<String> = w.weights.iter().map(|&e| estimate(e)).collect();
    t.push_str(&format!("stationary weights: {}\n", weights.join(", ")));
    for (i, (res, rel)) in w.residence.iter().zip(&w.relaxation).enumerate() {
        t.push_str(&format!(
            "well {i}: residence {res:.4e}, relaxation {rel:.4e}\n"
        ));
    }
    t.push_str(&format!(
        "decomposition: {}; {:.3e} steps\n",
        if w.valid { "valid" } else { "REFUSED" },
        w.steps as f64
    ));
    for r in &w.refusals {
        t.push_str(&format!("refused: {r}\n"));
    }
    t
}

/// A histogram density `A_lo,A_hi,density,stderr`, one row per bin.
///
/// A density or standard error that does not exist (NaN: the mixture of a well decomposition
/// whose weights are undetermined, a standard error from one unit) is an empty cell, as the
/// JSON writes `null`, and a note says so.
pub fn density_table(notes: &[String], d: &Density) -> Table {
    let mut notes = notes.to_vec();
    let cell = |v: f64| if v.is_nan() { String::new() } else { num(v) };
    if d.density.iter().chain(&d.stderr).any(|v| v.is_nan()) {
        notes.push(
            "an empty density or stderr cell is a value that does not exist (JSON null)".into(),
        );
    }
    let mut t = Table::new(&notes, &["A_lo", "A_hi", "density", "stderr"]);
    for (i, w) in d.edges.windows(2).enumerate() {
        t.row([num(w[0]), num(w[1]), cell(d.density[i]), cell(d.stderr[i])]);
    }
    t
}

/// A path's summary: the `summary` object of `simulate`'s JSON, and [`PathSummary::line`].
#[derive(Debug, Clone, Serialize)]
pub struct PathSummary {
    /// Steps taken.
    pub steps: usize,
    /// Impacts.
    pub impacts: usize,
    /// Steps that ended clamped at the wall.
    pub sticking_steps: usize,
    /// Mean amplitude over the last periods.
    pub final_amplitude: f64,
    /// Wall time of the run, seconds.
    pub wall_time_s: f64,
    /// Steps per second of wall time.
    pub steps_per_second: f64,
    /// Exponentials of the SOE memory.
    pub exponentials: usize,
    /// The SOE kernel's maximal relative error.
    pub soe_max_relative_error: f64,
    /// Bytes of memory state at the end.
    pub memory_state_bytes: usize,
}

impl PathSummary {
    /// The summary of `tr`, run in `wall` seconds.
    pub fn of(tr: &Trajectory, wall: f64) -> PathSummary {
        PathSummary {
            steps: tr.steps,
            impacts: tr.impacts,
            sticking_steps: tr.sticking_steps,
            final_amplitude: tr.final_amplitude,
            wall_time_s: wall,
            steps_per_second: tr.steps as f64 / wall.max(1e-12),
            exponentials: tr.exponentials,
            soe_max_relative_error: tr.soe_error,
            memory_state_bytes: tr.memory_bytes,
        }
    }

    /// In one line.
    pub fn line(&self) -> String {
        format!(
            "steps {}  impacts {}  sticking steps {}  final amplitude {:.6}  wall time {:.3} s  \
             ({:.3e} steps/s, {} exponentials)",
            self.steps,
            self.impacts,
            self.sticking_steps,
            self.final_amplitude,
            self.wall_time_s,
            self.steps_per_second,
            self.exponentials
        )
    }
}
