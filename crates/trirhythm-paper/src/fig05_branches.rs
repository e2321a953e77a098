//! Fig. 5: one-parameter bifurcation diagrams, limit-cycle amplitude A0 against r for five μ0,
//! every branch of f(A0; r) = 0 (Eq. 18) traced by pseudo-arclength continuation through its
//! folds (stable ⇔ df/dA0 < 0), with the folds and the births at A0 = 0.
//!
//! Method: [`trace_branches`] in (A0², r). The r ranges are chosen per panel to show every
//! fold (the paper does not print them). Checked by `tests/figures.rs` and, for the
//! continuation itself, the library's bifurcation tests.

use crate::notes::num;
use crate::notes::{caption, panel_line, table_notes, Caption};
use crate::table::Table;
use crate::{Figure, FigureOptions, Monitor};

use serde::{Deserialize, Serialize};
use trirhythm::model::preset;
use trirhythm::theory::bifurcation::{branches as trace_branches, BranchDiagram, What};
use trirhythm::Result;

/// (label, μ0, r range shown).
const PANELS: [(&str, f64, f64, f64); 5] = [
    ("a", 0.001, 0.98, 1.0),
    ("b", 0.01, 0.8, 1.0),
    ("c", 0.04, 0.3, 1.0),
    ("d", 0.3, 0.05, 1.0),
    ("e", 0.7, 0.05, 1.0),
];

/// Fig. 5's data: per panel its label, μ0 and branch diagram.
#[derive(Serialize, Deserialize)]
pub struct Fig05 {
    /// What the figure shows, shared parameters, variant, choices.
    pub caption: Caption,
    /// Notes of the data table: parameters per panel, methods, verdicts.
    pub notes: Vec<String>,
    /// Per panel: its label, μ0 and branch diagram.
    pub panels: Vec<(String, f64, BranchDiagram)>,
}

impl Figure for Fig05 {
    const NUMBER: u32 = 5;
    const TITLE: &'static str = "limit-cycle amplitude vs r by continuation, five μ0";

    fn compute(options: &FigureOptions, monitor: &dyn Monitor) -> Result<Fig05> {
        compute(options, monitor)
    }

    fn validate(&self) -> crate::validate::Valid {
        use crate::validate::{finite, points, range};
        for (i, (_, value, d)) in self.panels.iter().enumerate() {
            let f = format!("panels[{i}]");
            finite(&format!("{f}.1"), &[*value])?;
            range(&format!("{f}.2.start"), (d.start, d.stop))?;
            for (j, b) in d.branches.iter().enumerate() {
                let pts: Vec<(f64, f64)> =
                    b.points.iter().map(|p| (p.param, p.amplitude)).collect();
                points(&format!("{f}.2.branches[{j}].points"), &pts)?;
            }
            points(&format!("{f}.2.folds"), &d.folds)?;
            finite(&format!("{f}.2.hopf"), &d.hopf)?;
        }
        Ok(())
    }

    fn tables(&self) -> Vec<Table> {
        let mut csv = Table::new(
            &self.notes,
            &["panel", "mu0", "branch", "r", "A0", "stable"],
        );
        for (label, mu0, bd) in &self.panels {
            for (i, b) in bd.branches.iter().enumerate() {
                for q in &b.points {
                    csv.row([
                        label.clone(),
                        num(*mu0),
                        i.to_string(),
                        num(q.param),
                        num(q.amplitude),
                        u8::from(q.stable).to_string(),
                    ]);
                }
            }
        }
        vec![csv]
    }
}

fn compute(ctx: &FigureOptions, monitor: &dyn Monitor) -> Result<Fig05> {
    let pre = preset("fig5")?;
    let step = if ctx.quick { 0.01 } else { 0.002 };
    let mut panels = Vec::new();
    let mut notes: Vec<String> = pre.notes.iter().map(|s| s.to_string()).collect();
    notes.push("branches of f(A0; r) = 0 (Eq. 18) by pseudo-arclength continuation in (A0², r); stable ⇔ df/dA0 < 0".into());
    notes
        .push("r ranges chosen per panel to show every fold; the paper does not print them".into());
    let mut lines = Vec::new();
    for (i, (label, mu0, r0, r1)) in PANELS.into_iter().enumerate() {
        crate::step(monitor, i, PANELS.len())?;
        let p = pre.params.with("mu0", mu0)?;
        let bd = trace_branches(&p, ctx.variant, What::Rhythmicity, "r", r0, r1, step)?;
        notes.push(format!(
            "panel {label} (μ0 = {mu0}): {} branches, folds at {}; branches born at A0 = 0 at r = [{}]",
            bd.branches.len(),
            if bd.folds.is_empty() {
                "none".to_string()
            } else {
                bd.folds.iter().map(|f| format!("(r = {:.6}, A0 = {:.4})", f.0, f.1)).collect::<Vec<_>>().join(", ")
            },
            bd.hopf.iter().map(|h| format!("{h:.6}")).collect::<Vec<_>>().join(", ")
        ));
        lines.push(panel_line(label, &p));
        panels.push((label.to_string(), mu0, bd));
    }
    let mut header = table_notes(
        5,
        "limit-cycle amplitude A0 vs r (branches by continuation)",
        ctx,
        &notes,
    );
    header.extend(lines);
    let caption = caption(
        5,
        "limit-cycle amplitude A0 against r, every branch traced through its folds",
        ctx,
        &pre.params,
        &["mu0", "r"],
        vec!["solid: stable (df/dA0 < 0), dashed: unstable; pseudo-arclength continuation of f(A0; r) = 0 (Eq. 18); the r ranges are chosen per panel (not printed in the paper)".into()],
    );
    Ok(Fig05 {
        caption,
        notes: header,
        panels,
    })
}
