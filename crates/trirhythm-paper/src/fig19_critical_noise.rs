//! Fig. 19: the critical noise D_c against μ0 (a), τ (b), λ (c) and r (d) at the paper's printed
//! base point (λ = r = 0.998, μ0 = 0.01, τ = 0.5; the caption's "r = 9.998" is a misprint of
//! 0.998): per panel, five values of the parameter, one curve per attractor of the noise-free
//! system ([`crate::lle::plan_curves`]) on a log-spaced grid of D, each point called chaotic /
//! not chaotic / synchronised / undecided and each curve's D_c decided by the regime rules
//! (`verdict::rules::regime`): a bracket (D1, D2), one-sided (below the smallest or above the
//! largest D), none at all (never chaotic, the exponent falling at strong noise) or 0 (the rest
//! regime chaotic as D → 0). Drawn as the paper draws it, D_c against the parameter, one series
//! per attractor; the points' calls are in the data. The paper's trends of D_c are decided on
//! these brackets, per attractor.
//!
//! Method: [`crate::lle::run_curve`] (frozen noise, two trajectories, Δt by
//! [`crate::lle::dt_for`]). Checked by `tests/figures.rs` and the rules' tests in
//! `tests/verdicts.rs`.

use crate::lle::{
    log_spaced, lyapunov_caption, panels_table, plan_curves, run_curve, starts_line, Curve,
    NoiseGrid, Panel, StartKind,
};
use crate::notes::{num, symbol, table_notes, Caption};
use crate::table::Table;
use crate::verdict::rules::{Bracket, Located};
use crate::{Figure, FigureOptions, Monitor};

use serde::{Deserialize, Serialize};
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

/// The run sizes of a cell: quick (CI) or paper quality (windows 60 and 1000).
pub fn sizes(quick: bool) -> crate::lle::Sizes {
    crate::lle::Sizes::with_window(quick, 60.0, 1000.0)
}

/// The D grid of every column: nine values log-spaced from 0.002 to 2 (a factor
/// 10^(3/8) apart; two at quick quality).
pub fn noises(quick: bool) -> Vec<f64> {
    if quick {
        vec![0.01, 2.0]
    } else {
        log_spaced(0.002, 2.0, 9)
    }
}

/// The panels in one caption line: each varies one parameter over its values, the others
/// held at the base point.
fn panels_line(base: &Params) -> Result<String> {
    let mut held = Vec::new();
    for &(_, key, _, _) in &PANELS {
        held.push(format!("{} = {}", symbol(key), num(base.get(key)?)));
    }
    let varied: Vec<String> = PANELS
        .iter()
        .map(|(label, key, values, _)| {
            let vs: Vec<String> = values.iter().map(|&v| num(v)).collect();
            format!("{label} {} ∈ {{{}}}", symbol(key), vs.join(", "))
        })
        .collect();
    Ok(format!(
        "each panel varies one parameter, the others held at the base point {}: {}",
        held.join(", "),
        varied.join("; ")
    ))
}

/// The D searched for D_c, in one caption line.
fn searched_line(grid: &NoiseGrid) -> String {
    let list = |v: &[f64]| v.iter().map(|&x| num(x)).collect::<Vec<_>>().join(", ");
    let mut line = format!(
        "D searched: {} values log-spaced in [{}, {}]",
        grid.noises.len(),
        num(grid.noises[0]),
        num(grid.noises[grid.noises.len() - 1])
    );
    if !grid.rest_below.is_empty() {
        line.push_str(&format!("; rest curves also at {}", list(&grid.rest_below)));
    }
    if !grid.extension.is_empty() {
        line.push_str(&format!(
            "; a cycle curve not chaotic up to {} is extended to {} (so \"none\" means no D_c up to D = {})",
            num(grid.noises[grid.noises.len() - 1]),
            list(&grid.extension),
            num(grid.extension[grid.extension.len() - 1])
        ));
    }
    line
}

/// One panel: D_c against one parameter, from the curves of the LLE against D behind it.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct SignMap {
    /// The cells as curves of the LLE against D, one per (value, start), with their signs.
    pub panel: Panel,
    /// The parameter.
    pub key: String,
    /// Its values (the map's columns).
    pub values: Vec<f64>,
    /// The paper's claimed trend of D_c: `increases` or `decreases`.
    pub claim: String,
    /// Per curve of `panel` (same order): where the sign change lies; `None`: no points (no
    /// outer stable cycle).
    pub located: Vec<Option<Located>>,
}

/// Fig. 19's data.
#[derive(Serialize, Deserialize)]
pub struct Fig19 {
    /// What the figure shows, shared parameters, method.
    pub caption: Caption,
    /// Notes of the data table: the grid, the outcome per column, the paper's trends.
    pub notes: Vec<String>,
    /// Panels (a)–(d).
    pub panels: Vec<SignMap>,
}

impl Figure for Fig19 {
    const NUMBER: u32 = 19;
    const TITLE: &'static str = "the critical noise D_c against μ0, τ, λ and r, per attractor";

    fn compute(options: &FigureOptions, monitor: &dyn Monitor) -> Result<Fig19> {
        let sz = sizes(options.quick);
        let base = preset("fig19")?.params;
        let d = noises(options.quick);
        let mut notes = vec![
            sz.describe(),
            starts_line(options.variant),
            format!(
                "grid: 5 values per panel × {} D log-spaced in [{}, {}] ({}) × one curve per attractor of the noise-free system (rest curves also at D = 1e-6, 1e-5, 1e-4); a cell's call against the margin δ = 1/W (one-sided Student's t on the unmerged realisations, Bonferroni over the curve's points at 0.05): chaotic (lower bound > δ), not chaotic (upper bound < δ), synchronised (at least half the realisations merged), undecided; D_c bracket: (largest not-chaotic or synchronised D, smallest chaotic D) of a curve; no D_c: never chaotic with the exponent falling over the last decade of D (weighted slope in log D significantly negative, the two largest D regular); D_c = 0: the rest regime chaotic as D → 0",
                d.len(),
                num(d[0]),
                num(d[d.len() - 1]),
                d.iter().map(|&x| num(x)).collect::<Vec<_>>().join(", ")
            ),
            "the caption prints r = 9.998: 0.998 is meant; ω0 is not printed: 0.9 (as in Fig. 17); the swept values and the D grid are chosen (not printed)".into(),
        ];
        let planned_panels = crate::each(&PANELS, |(_, key, values, _)| {
            plan_curves(
                &base,
                key,
                values,
                &d,
                &sz,
                (options.variant, options.quick),
            )
        })?;
        let mut plans = Vec::new();
        for (planned, n) in planned_panels {
            notes.extend(n);
            plans.push(planned);
        }
        let total: usize = plans
            .iter()
            .flat_map(|p| p.iter().map(crate::lle::PlannedCurve::most_points))
            .sum();
        let progress = crate::Progress::new(0, total);
        // every curve of both panels side by side
        let jobs: Vec<(&str, &str, &crate::lle::PlannedCurve)> = PANELS
            .iter()
            .zip(&plans)
            .flat_map(|(&(label, key, _, _), planned)| planned.iter().map(move |c| (label, key, c)))
            .collect();
        let mut computed = crate::each(&jobs, |&(label, key, c)| {
            run_curve(monitor, label, key, c, &sz, &progress)
        })?
        .into_iter();
        let mut panels = Vec::new();
        for ((label, key, values, claim), planned) in PANELS.into_iter().zip(&plans) {
            let mut curves = Vec::new();
            for (curve, n) in computed.by_ref().take(planned.len()) {
                notes.extend(n);
                curves.push(curve);
            }
            let located: Vec<Option<Located>> = curves
                .iter()
                .map(|c| c.regime.as_ref().map(|r| located_of(&r.bracket)))
                .collect();
            notes.extend(curves.iter().filter_map(|c| c.regime_note(label)));
            let verdicts = panel_verdicts(key, claim, &curves);
            panels.push(SignMap {
                panel: Panel {
                    caption: format!("{label} D_c against {}", symbol(key)),
                    x_key: "D".into(),
                    x_desc: symbol(key).into(),
                    y_desc: "noise intensity D (log scale)".into(),
                    y_key: "lle".into(),
                    curves,
                    verdicts,
                },
                key: key.into(),
                values: values.to_vec(),
                claim: claim.into(),
                located,
            });
        }
        let caption = lyapunov_caption(
            19,
            "the critical noise D_c against μ0, τ, λ and r, per attractor",
            options,
            &base,
            &["mu0", "tau", "lambda", "r", "D"],
            vec![
                panels_line(&base)?,
                searched_line(&NoiseGrid::figure(&d, options.quick)),
                sz.describe(),
                starts_line(options.variant),
            ],
        );
        Ok(Fig19 {
            caption,
            notes: table_notes(19, Self::TITLE, options, &notes),
            panels,
        })
    }

    fn validate(&self) -> crate::validate::Valid {
        use crate::validate::{finite, len};
        for (i, m) in self.panels.iter().enumerate() {
            let f = format!("panels[{i}]");
            m.panel.validate(&format!("{f}.panel"))?;
            finite(&format!("{f}.values"), &m.values)?;
            len(
                &format!("{f}.located"),
                m.located.len(),
                m.panel.curves.len(),
                "one per curve",
            )?;
        }
        Ok(())
    }

    fn tables(&self) -> Vec<Table> {
        let panels: Vec<Panel> = self.panels.iter().map(|m| m.panel.clone()).collect();
        vec![panels_table(&self.notes, &panels)]
    }
}

/// A curve's bracket in the sign-change terms of earlier data: located, positive from the
/// smallest D (chaotic there: D_c below the grid), no positive (not chaotic up to the largest D,
/// or never) or not significant (undecided).
pub fn located_of(b: &Bracket) -> Located {
    match *b {
        Bracket::Located { lo, hi } => Located::Bracket { lo, hi },
        Bracket::Below { .. } => Located::PositiveFromStart,
        Bracket::Above { .. } | Bracket::Never { .. } => Located::NoPositive,
        Bracket::Undecided => Located::NotSignificant,
    }
}

/// A panel's lines: the paper's trend, and per regime how many curves end in each outcome of
/// the regime rules.
fn panel_verdicts(key: &str, claim: &str, curves: &[Curve]) -> Vec<String> {
    let mut lines = vec![format!("paper: D_c {claim} with {}", symbol(key))];
    for start in StartKind::BOTH {
        let of: Vec<&Curve> = curves.iter().filter(|c| c.start == start).collect();
        if of.is_empty() {
            continue;
        }
        // how many curves end in each outcome, in a fixed order
        let mut counts: Vec<(&str, usize)> = Vec::new();
        for c in &of {
            let tag = match c.regime.as_ref() {
                Some(r) if r.rest.as_ref().is_some_and(|s| s.d_c_zero) => "D_c = 0",
                Some(r) => match r.bracket {
                    Bracket::Located { .. } => "bracketed",
                    Bracket::Below { .. } => "below the range",
                    Bracket::Above { .. } => "above the range",
                    Bracket::Never { .. } => "none (never chaotic)",
                    Bracket::Undecided => "undecided",
                },
                None => "no decision",
            };
            match counts.iter_mut().find(|(t, _)| *t == tag) {
                Some((_, n)) => *n += 1,
                None => counts.push((tag, 1)),
            }
        }
        lines.push(format!(
            "{} ({} curves): D_c {}",
            start.name(),
            of.len(),
            counts
                .iter()
                .map(|(t, n)| format!("{t} at {n}"))
                .collect::<Vec<_>>()
                .join(", ")
        ));
    }
    lines
}
