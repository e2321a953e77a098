//! Library results as people read them: the sentences the CLI prints (standard error, `#`
//! lines) and the tables its CSV files hold, written once so that a report or a binding shows
//! the same.

use crate::lle::{merged_points_text, Sign};
use crate::notes::{num, sig};
use crate::table::Table;
use serde::Serialize;
use std::collections::BTreeMap;
use trirhythm::analysis::ensemble::{Density, EnsembleResult};
use trirhythm::analysis::lyapunov::{
    CriticalNoise, CriticalSearch, LyapunovMethod, LyapunovResult, LyapunovSpec,
};
use trirhythm::analysis::oscillation::{Boundary, Side};
use trirhythm::analysis::versus::TheoryComparison;
use trirhythm::analysis::Estimate;
use trirhythm::engine::Trajectory;
use trirhythm::model::Params;
use trirhythm::theory::averaging::{AmplitudePdf, Theory, Variant};
use trirhythm::theory::bifurcation::{BranchDiagram, Folds, Map, What};

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
            Ok(c) => t.push_str(&format!(
                "theory ({}): Hellinger {:.4} ± {:.4}, L1 {:.4}, KS {:.4}; modes {} (theory, \
                 binned; {} exact) vs {} (simulation); occupancy {}\n",
                v.name(),
                c.hellinger.value,
                c.hellinger.stderr,
                c.l1.value,
                c.ks.value,
                c.modes_theory,
                c.modes_theory_exact,
                c.modes_mc,
                list(&c.occupancy)
            )),
            Err(e) => t.push_str(&format!("theory ({}): {e}\n", v.name())),
        }
    }
    for w in &r.warnings {
        t.push_str(&format!("warning: {w}\n"));
    }
    t
}

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

/// A CSV cell: the number, or empty when undefined.
pub fn cell(v: f64) -> String {
    if v.is_finite() {
        num(v)
    } else {
        String::new()
    }
}

/// A Lyapunov run's running estimate `t,lle,stderr`, the exponent in the notes.
pub fn lle_table(notes: &[String], r: &LyapunovResult) -> Table {
    let mut notes = notes.to_vec();
    notes.push(format!("lle: {}", lle(r)));
    notes.push(
        "columns: running estimate (time since the transient, mean over paths, standard error)"
            .into(),
    );
    let mut t = Table::new(&notes, &["t", "lle", "stderr"]).allow_infinity("lle");
    for q in &r.running {
        t.row([num(q.t), num(q.value), cell(q.stderr)]);
    }
    t
}

/// The exponent at each value of `key`: `KEY,lle,stderr,merged,unmerged,unmerged_stderr`.
pub fn lle_sweep_table(notes: &[String], key: &str, rows: &[(f64, LyapunovResult)]) -> Table {
    let mut notes = notes.to_vec();
    notes.push(
        "merged: realisations whose copy merged with its reference (then lle = -inf); \
         unmerged: the mean over the others"
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
            num(r.lle.value),
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

/// Oscillation boundaries along `x_key`: `method,x,y,y_lo,y_hi`, the abscissae without a
/// boundary in the interval named in the notes.
pub fn boundaries_table(notes: &[String], x_key: &str, results: &[Boundary]) -> Table {
    let mut notes = notes.to_vec();
    for b in results {
        for q in b.points.iter().filter(|q| q.side != Side::Boundary) {
            let why = match q.side {
                Side::Oscillates => "no boundary in the interval: oscillates throughout",
                Side::Rests => "no boundary in the interval: rests throughout",
                _ => "not available (exact linearisation with the wall at λ < 1)",
            };
            notes.push(format!("{}: at {x_key} = {} {why}", b.method, num(q.x)));
        }
    }
    let mut t = Table::new(&notes, &["method", "x", "y", "y_lo", "y_hi"]);
    for b in results {
        for q in b.points.iter().filter(|q| q.side == Side::Boundary) {
            let cells = [q.x, q.y, q.y_lo, q.y_hi].map(num);
            t.row(std::iter::once(b.method.to_string()).chain(cells));
        }
    }
    t
}

/// A branch diagram `branch,param,amplitude,stable`, its folds and Hopf points in the notes.
pub fn branches_table(notes: &[String], bd: &BranchDiagram) -> Table {
    let mut notes = notes.to_vec();
    let key = &bd.key;
    for f in &bd.folds {
        notes.push(format!("fold: {key} = {}, A = {}", num(f.0), num(f.1)));
    }
    for h in &bd.hopf {
        notes.push(format!("branch reaches A = 0 at {key} = {}", num(*h)));
    }
    let mut t = Table::new(&notes, &["branch", "param", "amplitude", "stable"]);
    for (i, b) in bd.branches.iter().enumerate() {
        for p in &b.points {
            let stable = u8::from(p.stable).to_string();
            t.row([i.to_string(), num(p.param), num(p.amplitude), stable]);
        }
    }
    t
}

/// The notes every table of the averaged theory starts with: the parameters and the variant.
pub fn theory_notes(th: &Theory) -> Vec<String> {
    vec![
        format!("params: {}", th.params().describe()),
        format!("variant: {}", th.variant().name()),
    ]
}

/// What the roots of the theory are: `pdf_extrema` (roots of m1, D > 0) or `limit_cycles`.
pub fn cycles_kind(th: &Theory) -> &'static str {
    if th.diffusion() > 0.0 {
        "pdf_extrema"
    } else {
        "limit_cycles"
    }
}

/// The theory's cycles `amplitude,stable,fold`, their count and rhythmicity in the notes.
pub fn cycles_table(th: &Theory) -> Table {
    let rhythm = th.rhythmicity();
    let mut notes = theory_notes(th);
    notes.push(format!(
        "{}: {} stable ({})",
        cycles_kind(th),
        rhythm.count(),
        rhythm.name()
    ));
    let mut t = Table::new(&notes, &["amplitude", "stable", "fold"]);
    for c in th.cycles() {
        t.row([num(c.amplitude), c.stable.to_string(), c.fold.to_string()]);
    }
    t
}

/// The barriers of U_eff `name,well,crest,side,height` (`dU1`, `dU2`, …).
pub fn barriers_table(th: &Theory) -> Table {
    let columns = ["name", "well", "crest", "side", "height"];
    let mut t = Table::new(&theory_notes(th), &columns);
    for (i, b) in th.barriers().iter().enumerate() {
        t.row([
            format!("dU{}", i + 1),
            num(b.well),
            num(b.crest),
            b.side.name().into(),
            num(b.height),
        ]);
    }
    t
}

/// Named columns of equal length as a table; ±∞ allowed in the columns named in `infinite`.
pub fn columns_table(
    notes: &[String],
    names: &[&str],
    cols: &[&[f64]],
    infinite: &[&str],
) -> Table {
    let mut t = Table::new(notes, names);
    for column in infinite {
        t = t.allow_infinity(column);
    }
    for i in 0..cols.first().map_or(0, |c| c.len()) {
        t.row(cols.iter().map(|col| num(col[i])));
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
                 memory a second history of the perturbation, the saltation of the impact \
                 map at impacts; the whole tangent state renormalised every {} steps",
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

/// The notes of a map's CSV files: parameters, variant, what is counted, the axes, the count
/// histogram and the fold curves traced.
pub fn map_notes(
    params: &Params,
    variant: Variant,
    what: What,
    (kx, ky): (&str, &str),
    m: &Map,
    sets: &[Folds],
) -> Vec<String> {
    let hist = m.histogram();
    let counted = if what == What::Rhythmicity {
        "limit cycles"
    } else {
        "maxima of P(A)"
    };
    let mut notes = vec![
        format!("params: {}", params.describe()),
        format!("variant: {}", variant.name()),
        format!("what: {} (count of stable {counted})", what.name()),
        format!("x: {kx}, y: {ky}"),
        format!(
            "points with count 0, 1, 2, 3, >=4: {}, {}, {}, {}, {}",
            hist[0], hist[1], hist[2], hist[3], hist[4]
        ),
    ];
    for f in sets {
        notes.push(format!(
            "fold curves ({}): {} traced from {} seeds, {} cusps",
            f.curves.first().map(|c| c.system.name()).unwrap_or("-"),
            f.curves.len(),
            f.seeds,
            f.cusps.len()
        ));
    }
    notes
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

/// The joint density P(U, U̇) on a grid `U,V,p,log_p` (`log_p[i][j]` at `us[i]`, `vs[j]`).
pub fn joint_pdf_table(notes: &[String], us: &[f64], vs: &[f64], log_p: &[Vec<f64>]) -> Table {
    let mut t = Table::new(notes, &["U", "V", "p", "log_p"]).allow_infinity("log_p");
    for (&u, row) in us.iter().zip(log_p) {
        for (&v, &l) in vs.iter().zip(row) {
            t.row([num(u), num(v), num(l.exp()), num(l)]);
        }
    }
    t
}

/// An axis of a [`MapView`]: the key and its values.
#[derive(Serialize)]
pub struct AxisValues {
    /// The parameter.
    pub key: String,
    /// Its values on the grid.
    pub values: Vec<f64>,
}

/// A classified plane in JSON: the axes, the counts (one row per y), the count histogram and
/// the fold curves traced (the exact ones, then Eq. 37 as printed).
#[derive(Serialize)]
pub struct MapView<'a> {
    /// The parameters (a JSON object, key by key).
    pub params: serde_json::Value,
    /// The formula variant.
    pub variant: &'static str,
    /// What is counted.
    pub what: What,
    /// The horizontal axis.
    pub x: AxisValues,
    /// The vertical axis.
    pub y: AxisValues,
    /// `counts[iy][ix]`.
    pub counts: Vec<Vec<u8>>,
    /// Points with count 0, 1, 2, 3, ≥ 4.
    pub histogram: [usize; 5],
    /// The fold curves.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub folds: Option<&'a Folds>,
    /// The fold curves of Eq. 37 as printed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub printed_eq37: Option<&'a Folds>,
}

impl<'a> MapView<'a> {
    /// The view of `m` with the fold curves `sets` and the parameters as `params`.
    pub fn of(params: serde_json::Value, m: &Map, sets: &'a [Folds]) -> MapView<'a> {
        let p = &m.plane;
        let axis = |a: &trirhythm::theory::bifurcation::Axis| AxisValues {
            key: a.key.clone(),
            values: a.values(),
        };
        MapView {
            params,
            variant: p.variant.name(),
            what: m.what,
            x: axis(&p.x),
            y: axis(&p.y),
            counts: (0..p.y.count)
                .map(|iy| (0..p.x.count).map(|ix| m.count(ix, iy)).collect())
                .collect(),
            histogram: m.histogram(),
            folds: sets.first(),
            printed_eq37: sets.get(1),
        }
    }
}

/// A histogram density `A_lo,A_hi,density,stderr`, one row per bin.
pub fn density_table(notes: &[String], d: &Density) -> Table {
    let mut t = Table::new(notes, &["A_lo", "A_hi", "density", "stderr"]);
    for (i, w) in d.edges.windows(2).enumerate() {
        t.row([w[0], w[1], d.density[i], d.stderr[i]].map(num));
    }
    t
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

/// The theory's cycles for reading: `cycle,amplitude,stability` (`A01`, …; stable, unstable
/// or fold), the count and rhythmicity as the closing note.
pub fn cycles_reading(th: &Theory) -> Table {
    let rhythm = th.rhythmicity();
    let note = format!(
        "{}: {} stable ({})",
        cycles_kind(th),
        rhythm.count(),
        rhythm.name()
    );
    let mut t = Table::new(&[note], &["cycle", "amplitude", "stability"]);
    for (i, c) in th.cycles().iter().enumerate() {
        let stability = if c.fold {
            "fold"
        } else if c.stable {
            "stable"
        } else {
            "unstable"
        };
        t.row([
            format!("A0{}", i + 1),
            fixed(c.amplitude, 10),
            stability.into(),
        ]);
    }
    t
}

/// The barriers of U_eff for reading: `barrier,well A,crest A,side,height` (`ΔU1`, …).
pub fn barriers_reading(th: &Theory) -> Table {
    let columns = ["barrier", "well A", "crest A", "side", "height"];
    let mut t = Table::new(&[], &columns);
    for (i, b) in th.barriers().iter().enumerate() {
        t.row([
            format!("ΔU{}", i + 1),
            fixed(b.well, 6),
            fixed(b.crest, 6),
            b.side.name().into(),
            format!("{:.6e}", b.height),
        ]);
    }
    t
}

/// Named columns for reading (8 significant decimals in exponent notation).
pub fn columns_reading(names: &[&str], cols: &[&[f64]], infinite: &[&str]) -> Table {
    let mut t = columns_table(&[], names, cols, infinite);
    for (i, row) in t.rows.iter_mut().enumerate() {
        *row = cols
            .iter()
            .map(|col| format!("{:.8e}", col[i] + 0.0))
            .collect();
    }
    t
}

/// A one-dimensional density for reading: `x,p,log_p`, the modes, antimodes and mean
/// amplitude of `pdf` as the closing note.
pub fn pdf_reading(
    x_name: &str,
    xs: &[f64],
    p: &[f64],
    log_p: &[f64],
    pdf: &AmplitudePdf,
) -> Table {
    let note = format!(
        "modes {:?}, antimodes {:?}, mean amplitude {}",
        pdf.modes, pdf.antimodes, pdf.mean_amplitude
    );
    let mut t = Table::new(&[note], &[x_name, "p", "log_p"]).allow_infinity("log_p");
    for ((&x, &p), &l) in xs.iter().zip(p).zip(log_p) {
        t.row([fixed(x, 6), format!("{p:.6e}"), fixed(l, 6)]);
    }
    t
}

/// The harmonic-balance equivalents (Eq. 5), σ1 and the impact loss rate: `name,value`.
pub fn equivalents_table(th: &Theory) -> Table {
    let e = th.equivalents();
    let mut t = Table::new(&theory_notes(th), &["name", "value"]);
    for (name, v) in [
        ("mu1", e.mu1),
        ("beta1", e.beta1),
        ("omega1", e.omega1),
        ("beta2", e.beta2),
        ("sigma1", th.diffusion()),
        ("loss_rate", th.loss_rate()),
    ] {
        t.row([name.to_string(), num(v)]);
    }
    t
}
