//! Fig. 19: the critical noise D_c where the largest Lyapunov exponent changes sign, against μ0
//! (a), τ (b), λ (c) and r (d), with its uncertainty from the standard errors; values without a
//! sign change in the searched range are said so on the panel, never drawn as a made-up value.
//!
//! Method: [`critical_noise`] (the first sign change of the LLE on a grid of D, bisected, the
//! last bracket interpolated; the error bar from the nearest D whose LLE is two standard errors
//! from 0), with the run sizes of Figs 17–18 ([`crate::lle::Sizes`]); the paper's claimed trend
//! of D_c per panel set against the computed one. Checked by the library's critical-noise tests
//! and `tests/figures.rs`.

use crate::lle::{
    merged_points_text, noise_point_text, panels_table, Curve, Panel, Point, Sign, Sizes,
};
use crate::notes::{caption, num, sig, symbol, table_notes, Caption};
use crate::table::Table;
use crate::{Figure, FigureOptions, Monitor};

use serde::{Deserialize, Serialize};
use trirhythm::analysis::lyapunov::{critical_noise, CriticalSearch};
use trirhythm::model::{preset, Params};
use trirhythm::Result;

/// (panel, key, values, the paper's claimed trend of D_c).
pub const PANELS: [(&str, &str, [f64; 5], &str); 4] = [
    ("(a)", "mu0", [0.005, 0.01, 0.02, 0.05, 0.1], "decreases"),
    ("(b)", "tau", [0.1, 0.3, 0.5, 0.75, 1.0], "increases"),
    (
        "(c)",
        "lambda",
        [0.95, 0.97, 0.98, 0.99, 0.998],
        "increases",
    ),
    ("(d)", "r", [0.8, 0.85, 0.9, 0.95, 0.998], "increases"),
];

/// Fig. 19's data.
#[derive(Serialize, Deserialize)]
pub struct Fig19 {
    /// What the figure shows, shared parameters, variant, method.
    pub caption: Caption,
    /// Notes of the data table: D_c per value, the paper's trends checked.
    pub notes: Vec<String>,
    /// Panels (a)–(d).
    pub panels: Vec<Panel>,
}

impl Figure for Fig19 {
    const NUMBER: u32 = 19;
    const TITLE: &'static str =
        "critical noise D_c where the LLE changes sign, against μ0, τ, λ, r";

    fn compute(options: &FigureOptions, monitor: &dyn Monitor) -> Result<Fig19> {
        let ctx = options;
        let sz = Sizes::of(ctx.quick);
        let base = preset("fig19")?.params;
        let search = CriticalSearch {
            d_lo: 0.01,
            d_hi: 2.0,
            grid: if ctx.quick { 3 } else { 6 },
            refinements: if ctx.quick { 1 } else { 3 },
            z: 2.0,
        };
        let mut notes = vec![
            sz.describe(),
            format!(
                "D_c: first sign change of the LLE on {} equally spaced D in [{}, {}], bisected {} times, linear interpolation of the last bracket; error bar: nearest evaluated D on each side whose LLE is {} standard errors from 0 (the range's end if none)",
                search.grid, num(search.d_lo), num(search.d_hi), search.refinements, num(search.z)
            ),
            "the caption prints r = 9.998: 0.998 is meant; ω0 is not printed: 0.9 (as in Fig. 17); the swept values are chosen (not printed)".into(),
        ];
        let mut panels = Vec::new();
        let total = PANELS.len() * PANELS[0].2.len();
        for (i, spec) in PANELS.into_iter().enumerate() {
            let first = i * spec.2.len();
            panels.push(panel(
                monitor,
                &base,
                (&sz, &search),
                spec,
                (first, total),
                &mut notes,
            )?);
        }
        let caption = caption(
            19,
            "critical noise D_c where the largest Lyapunov exponent changes sign",
            ctx,
            &base,
            &["mu0", "tau", "lambda", "r", "D"],
            vec![sz.describe()],
        );
        Ok(Fig19 {
            caption,
            notes: table_notes(19, Self::TITLE, ctx, &notes),
            panels,
        })
    }

    fn tables(&self) -> Vec<Table> {
        vec![panels_table(&self.notes, &self.panels)]
    }
}

/// One panel: D_c against `key` with its uncertainty, where the LLE changes sign from negative
/// to positive; a note per value and the paper's trend set against the computed one. Progress
/// counts from `first` of `total` values.
fn panel(
    monitor: &dyn Monitor,
    base: &Params,
    (sz, search): (&Sizes, &CriticalSearch),
    (label, key, values, claim): (&str, &str, [f64; 5], &str),
    (first, total): (usize, usize),
    notes: &mut Vec<String>,
) -> Result<Panel> {
    let mut points = Vec::new();
    let mut missing = Vec::new();
    let mut falling: Vec<String> = Vec::new();
    for (k, v) in values.into_iter().enumerate() {
        crate::step(monitor, first + k, total)?;
        let p = base.with(key, v)?;
        let problem = trirhythm::engine::Problem::from_params(&p)?;
        let c = critical_noise(
            &problem,
            &sz.method,
            &sz.spec,
            search,
            &trirhythm::monitor::OnlyCancel(monitor),
        )?;
        let merged = merged_points_text(&c);
        if c.found() {
            notes.push(format!(
                "{label} {} = {}: D_c = {} in [{}, {}] ({}){}",
                symbol(key),
                num(v),
                sig(c.d_c, 4),
                sig(c.d_c_lo, 4),
                sig(c.d_c_hi, 4),
                if c.rising {
                    "LLE negative below, positive above"
                } else {
                    "LLE positive below, negative above: the opposite of the paper's transition"
                },
                if merged.is_empty() {
                    String::new()
                } else {
                    format!(
                        "; no sign at D = {} (realisations merged)",
                        merged.join(", ")
                    )
                }
            ));
        } else {
            let sign = Sign::of(&c);
            notes.push(format!(
                "{label} {} = {}: no sign change in range D ∈ [{}, {}] (LLE {}; evaluated: {})",
                symbol(key),
                num(v),
                num(search.d_lo),
                num(search.d_hi),
                sign.words(),
                c.evaluated
                    .iter()
                    .map(noise_point_text)
                    .collect::<Vec<_>>()
                    .join("; ")
            ));
            let tag = sign.tag();
            missing.push((num(v), tag));
        }
        if c.found() && !c.rising {
            falling.push(num(v));
        }
        // only a negative → positive change is the paper's D_c
        let drawn = c.found() && c.rising;
        let nan = f64::NAN;
        points.push(Point {
            x: v,
            y: if drawn { c.d_c } else { nan },
            lo: if drawn { c.d_c_lo } else { nan },
            hi: if drawn { c.d_c_hi } else { nan },
        });
    }
    let verdicts = verdicts(
        (label, key, values.len(), claim),
        &points,
        &falling,
        &missing,
        notes,
    );
    Ok(Panel {
        caption: format!("{label} D_c against {}", symbol(key)),
        x_key: key.into(),
        x_desc: symbol(key).into(),
        y_desc: "critical noise D_c".into(),
        y_key: "D_c".into(),
        curves: vec![Curve {
            label: "D_c with its uncertainty".into(),
            points,
        }],
        verdicts,
    })
}

/// A panel's verdicts: the trend of the D_c found against the paper's claim (also as a note),
/// the values with the opposite transition, and one line per kind of missing sign change.
fn verdicts(
    (label, key, count, claim): (&str, &str, usize, &str),
    points: &[Point],
    falling: &[String],
    missing: &[(String, &str)],
    notes: &mut Vec<String>,
) -> Vec<String> {
    let found: Vec<&Point> = points.iter().filter(|q| q.y.is_finite()).collect();
    let trend = if found.len() >= 2 {
        let up = found.windows(2).all(|w| w[1].y >= w[0].y);
        let down = found.windows(2).all(|w| w[1].y <= w[0].y);
        match (up, down) {
            (true, false) => "increases",
            (false, true) => "decreases",
            _ => "not monotonic",
        }
    } else {
        "undetermined"
    };
    let verdict = if trend == claim {
        "agrees"
    } else {
        "not reproduced"
    };
    notes.push(format!(
        "{label} paper: D_c {claim} with {}; here: {trend} (negative → positive change at {} of {} values; positive → negative, the opposite transition, at {}): {verdict}",
        symbol(key), found.len(), count, falling.len()
    ));
    let mut verdicts = vec![format!("paper: D_c {claim}; here: {trend}")];
    if !falling.is_empty() {
        verdicts.push(format!(
            "LLE + → − (not drawn) at {} = {}",
            symbol(key),
            falling.join(", ")
        ));
    }
    // one line per kind of outcome, so that no line runs past the chart
    let mut tags: Vec<&str> = Vec::new();
    for m in missing {
        if !tags.contains(&m.1) {
            tags.push(m.1);
        }
    }
    for tag in tags {
        let at: Vec<&str> = missing
            .iter()
            .filter(|m| m.1 == tag)
            .map(|m| m.0.as_str())
            .collect();
        verdicts.push(format!(
            "no sign change in range at {} = {} ({tag})",
            symbol(key),
            at.join(", ")
        ));
    }
    verdicts
}
