//! Lyapunov exponents and the critical noise by regime in words and tables.

use super::cell;
use crate::critical::{call_name, CriticalNoise};
use crate::notes::{num, sig};
use crate::table::Table;
use crate::verdict::rules::RestRegime;
use serde::Serialize;
use trirhythm::analysis::lyapunov::{LyapunovMethod, LyapunovResult, LyapunovSpec};

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

/// Each curve's decision in a line: "[KEY = value: ]attractor (U(0) = …, Δt = …): the bracket,
/// the rest regime's numbers or the prediction's agreement".
pub fn critical_lines(doc: &CriticalNoise) -> Vec<String> {
    let mut lines = Vec::new();
    for r in &doc.results {
        let at = match (&doc.sweep, r.value) {
            (Some(k), Some(v)) => format!("{k} = {}: ", num(v)),
            _ => String::new(),
        };
        for c in &r.curves {
            lines.push(format!(
                "{at}{} (U(0) = {}, Δt = {}): {}",
                c.attractor,
                sig(c.u0, 4),
                num(c.dt),
                c.decision
            ));
        }
    }
    lines
}

/// The critical noise by regime as one table, a row per point of every curve:
/// `[KEY,]attractor,regime,u0,dt,D,lle,se,n,merged,call,agrees` and the curve's decision
/// repeated on each of its rows, `bracket,D_c_lo,D_c_hi,D_c_zero,rest_pooled,rest_pooled_se,
/// rest_slope,rest_slope_se,rest_decades,c,c_uncertainty` (empty where undefined or not
/// applicable); each curve's decision in words and the notes in `notes` and the comment lines.
pub fn critical_table(notes: &[String], doc: &CriticalNoise) -> Table {
    let mut notes = notes.to_vec();
    notes.push(format!(
        "rules (docs/verdicts.md, \"The Lyapunov claims by regime\"): a point is chaotic when the \
         lower one-sided bound of the unmerged mean exceeds δ = 1/W = {}, not-chaotic when the \
         upper bound lies below δ, synchronised when at least half the realisations merged, else \
         undecided (Student's t, Bonferroni over the curve's points at 0.05); D_c in (D_c_lo, \
         D_c_hi): the largest regular D below the smallest chaotic D (bracket located), D_c < \
         D_c_hi (below: chaotic from the smallest D), D_c > D_c_lo (above: regular up to the \
         largest D), no D_c at all (never: no chaotic point, the two largest D regular and the \
         exponent falling significantly with log D over the last decade; D_c_lo the largest D) \
         or not bracketed (undecided); rest curves: pooled exponent and slope per \
         decade over D ≤ 0.01, D_c_zero = true when the pooled exponent exceeds δ, the slope is \
         not significant and the points span at least 3 decades (chaotic as D → 0: D_c = 0); \
         cycle curves: c of the phase reduction λ ≈ −c·D, agrees = the exponent equivalent to \
         −c·D within δ (two one-sided t tests)",
        num(doc.margin)
    ));
    notes.extend(critical_lines(doc));
    notes.extend(doc.notes.iter().cloned());
    notes.extend(doc.step_warnings.iter().map(|w| format!("warning: {w}")));
    notes.push(
        "columns: lle and se are the mean and standard error over the realisations that did not \
         merge, n the realisations, merged those whose copy merged with its reference (exponent \
         −∞); an empty cell is undefined or does not apply"
            .into(),
    );
    let mut columns: Vec<&str> = doc.sweep.as_deref().into_iter().collect();
    columns.extend([
        "attractor",
        "regime",
        "u0",
        "dt",
        "D",
        "lle",
        "se",
        "n",
        "merged",
        "call",
        "agrees",
        "bracket",
        "D_c_lo",
        "D_c_hi",
        "D_c_zero",
        "rest_pooled",
        "rest_pooled_se",
        "rest_slope",
        "rest_slope_se",
        "rest_decades",
        "c",
        "c_uncertainty",
    ]);
    let mut t = Table::new(&notes, &columns);
    let opt = |x: Option<f64>| x.map_or(String::new(), cell);
    for r in &doc.results {
        for c in &r.curves {
            let rest =
                |f: fn(&RestRegime) -> f64| c.rest.as_ref().map_or(String::new(), |r| cell(f(r)));
            for q in &c.points {
                let lead = doc
                    .sweep
                    .as_ref()
                    .map(|_| r.value.map_or(String::new(), num));
                t.row(
                    lead.into_iter().chain([
                        c.attractor.clone(),
                        c.regime.name().into(),
                        num(c.u0),
                        num(c.dt),
                        num(q.d),
                        cell(q.lle),
                        cell(q.se),
                        q.n.to_string(),
                        q.merged.to_string(),
                        call_name(q.call).into(),
                        q.agrees.map_or(String::new(), |a| a.to_string()),
                        c.bracket.kind.name().into(),
                        opt(c.bracket.lo),
                        opt(c.bracket.hi),
                        c.rest
                            .as_ref()
                            .map_or(String::new(), |r| r.d_c_zero.to_string()),
                        rest(|r| r.pooled),
                        rest(|r| r.pooled_se),
                        rest(|r| r.slope),
                        rest(|r| r.slope_se),
                        rest(|r| r.decades),
                        opt(c.coefficient),
                        opt(c.coefficient_uncertainty),
                    ]),
                );
            }
        }
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
