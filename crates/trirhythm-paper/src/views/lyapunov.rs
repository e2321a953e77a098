//! Lyapunov exponents and critical-noise searches in words and tables.

use super::cell;
use crate::lle::{merged_points_text, Sign};
use crate::notes::{num, sig};
use crate::table::Table;
use serde::Serialize;
use trirhythm::analysis::lyapunov::{
    CriticalNoise, CriticalSearch, LyapunovMethod, LyapunovResult, LyapunovSpec,
};

/// A Lyapunov exponent with its standard error in words: −∞ and a missing standard error are
/// explained, never printed as bare `-inf ± nan`.
pub fn lle(r: &LyapunovResult) -> String {
    if r.lle.value == f64::NEG_INFINITY {
        let others = r.per_path.len() - r.merged;
        let rest = if others == 0 {
            String::new()
        } else {
            format!(
                "; the other {others}: {}",
                lle_estimate(r.unmerged.value, r.unmerged.stderr)
            )
        };
        return format!(
            "−∞: {} of {} realisations merged (the copy became identical to its reference, whole \
             memory included: both stuck at the wall on the same step with the memory restarted; \
             `per_path[].merged_at` in JSON){rest}",
            r.merged,
            r.per_path.len()
        );
    }
    lle_estimate(r.lle.value, r.lle.stderr)
}

/// A finite exponent with its standard error (4 and 2 significant digits: prose; the JSON has
/// every digit), or without one (a single path).
pub fn lle_estimate(value: f64, stderr: f64) -> String {
    if stderr.is_finite() {
        format!("{} ± {}", sig(value, 4), sig(stderr, 2))
    } else {
        format!("{} (no standard error: one path)", sig(value, 4))
    }
}

/// One value of a Lyapunov sweep in JSON: the swept value beside the library's result.
#[derive(Serialize)]
pub struct SweepPoint<'a> {
    /// The swept parameter's value.
    pub value: f64,
    /// The exponent there.
    #[serde(flatten)]
    pub result: &'a LyapunovResult,
}

/// A critical-noise search in JSON: the library's result with its verdict in words, at the
/// swept value (`None` without a sweep).
#[derive(Serialize)]
pub struct CriticalOutcome<'a> {
    /// The swept parameter's value.
    pub value: Option<f64>,
    /// Whether the LLE changes sign in the range.
    pub sign_change: bool,
    /// "sign change", or why there is none.
    pub verdict: String,
    /// The search.
    #[serde(flatten)]
    pub search: &'a CriticalNoise,
}

impl<'a> CriticalOutcome<'a> {
    /// The outcome of `search` at `value`.
    pub fn of(value: Option<f64>, search: &'a CriticalNoise) -> Self {
        let verdict = if search.found() {
            "sign change".to_string()
        } else {
            format!("no sign change in range (LLE {})", Sign::of(search).words())
        };
        CriticalOutcome {
            value,
            sign_change: search.found(),
            verdict,
            search,
        }
    }
}

/// A Lyapunov run's running estimate `t,lle,stderr`, the exponent in the notes.
pub fn lle_table(notes: &[String], r: &LyapunovResult) -> Table {
    let mut notes = notes.to_vec();
    notes.push(format!("lle: {}", lle(r)));
    notes.push(
        "columns: running estimate (time since the transient, mean over paths, standard error); \
         an empty lle is undefined there (JSON null: the window so far too short, or no \
         realisation left to average), -inf where every copy merged with its reference"
            .into(),
    );
    let mut t = Table::new(&notes, &["t", "lle", "stderr"]).allow_infinity("lle");
    for q in &r.running {
        t.row([num(q.t), lle_cell(q.value), cell(q.stderr)]);
    }
    t
}

/// An exponent's CSV cell: the number, `-inf` when every copy merged, empty when undefined
/// (NaN: too short a window, nothing to average), as JSON writes `null`.
fn lle_cell(v: f64) -> String {
    if v.is_nan() {
        String::new()
    } else {
        num(v)
    }
}

/// The exponent at each value of `key`: `KEY,lle,stderr,merged,unmerged,unmerged_stderr`.
pub fn lle_sweep_table(notes: &[String], key: &str, rows: &[(f64, LyapunovResult)]) -> Table {
    let mut notes = notes.to_vec();
    notes.push(
        "merged: realisations whose copy merged with its reference (then lle = -inf); \
         unmerged: the mean over the others; an empty cell is undefined (JSON null)"
            .into(),
    );
    let columns = [
        key,
        "lle",
        "stderr",
        "merged",
        "unmerged",
        "unmerged_stderr",
    ];
    let mut t = Table::new(&notes, &columns).allow_infinity("lle");
    for (v, r) in rows {
        t.row([
            num(*v),
            lle_cell(r.lle.value),
            cell(r.lle.stderr),
            r.merged.to_string(),
            cell(r.unmerged.value),
            cell(r.unmerged.stderr),
        ]);
    }
    t
}

/// Where a critical-noise search ran: "KEY = value", or "the parameters given" without a sweep.
pub fn point_label(key: Option<&str>, v: f64) -> String {
    match key {
        Some(k) => format!("{k} = {}", num(v)),
        None => "the parameters given".to_string(),
    }
}

/// Critical-noise searches `[KEY,]D_c,D_c_lo,D_c_hi`: the search, the searches without a
/// sign change and the merged points in the notes.
pub fn critical_table(
    notes: &[String],
    search: &CriticalSearch,
    key: Option<&str>,
    found: &[(f64, CriticalNoise)],
) -> Table {
    let mut notes = notes.to_vec();
    notes.push(format!(
        "search: D ∈ [{}, {}], {} grid points, {} bisections; D_c_lo/D_c_hi: the nearest \
         evaluated D on each side whose LLE is {} standard errors from 0",
        num(search.d_lo),
        num(search.d_hi),
        search.grid,
        search.refinements,
        num(search.z)
    ));
    for (v, c) in found {
        if !c.found() {
            notes.push(format!(
                "{}: no sign change in range (LLE {})",
                point_label(key, *v),
                Sign::of(c).words()
            ));
        }
        let merged = merged_points_text(c);
        if !merged.is_empty() {
            notes.push(format!(
                "{}: no sign at D = {} (realisations whose copy merged with its reference: LLE −∞)",
                point_label(key, *v),
                merged.join(", ")
            ));
        }
    }
    let mut columns: Vec<&str> = key.into_iter().collect();
    columns.extend(["D_c", "D_c_lo", "D_c_hi"]);
    let mut t = Table::new(&notes, &columns);
    for (v, c) in found.iter().filter(|(_, c)| c.found()) {
        let lead = key.map(|_| num(*v));
        t.row(
            lead.into_iter()
                .chain([num(c.d_c), num(c.d_c_lo), num(c.d_c_hi)]),
        );
    }
    t
}

/// A Lyapunov run's method and window in words (two lines of a table's notes).
pub fn lyapunov_spec(spec: &LyapunovSpec) -> [String; 2] {
    [
        match spec.method {
            LyapunovMethod::TwoTrajectory => format!(
                "method: two trajectories on the same noise (frozen noise), the copy pulled \
                 back to d0 = {} every {} steps with its whole memory",
                num(spec.separation),
                spec.renormalise_every
            ),
            LyapunovMethod::Tangent => format!(
                "method: tangent (variational) equation along the path (frozen noise), its \
                 memory a second history of the perturbation, the derivative of every step \
                 (impacts included); the whole tangent state renormalised every {} steps",
                spec.renormalise_every
            ),
        },
        format!(
            "window: finite-time exponent over t_end = {} after a transient of {}; {} \
             paths of seed {} (mean ± standard error over paths)",
            num(spec.length),
            num(spec.transient),
            spec.paths,
            spec.seed
        ),
    ]
}
