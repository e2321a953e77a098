//! Fig. 5: one-parameter bifurcation diagrams, limit-cycle amplitude A0 vs r for five μ0, every
//! branch traced by pseudo-arclength continuation through its folds (stable solid, unstable
//! dashed, folds and births at A0 = 0 marked).

use super::write_figure;
use super::{csv_header, heading, panel_line, Figure, FigureContext};
use crate::common::{num, Csv};
use crate::maps::branch_diagram;
use crate::plot::{chart, legend, pe, Heading, Picture};
use anyhow::Result;
use plotters::coord::Shift;
use plotters::prelude::*;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use trirhythm::model::preset;
use trirhythm::theory::bifurcation::{BranchDiagram, What};

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
    heading: Heading,
    /// CSV comment lines.
    header: Vec<String>,
    panels: Vec<(String, f64, BranchDiagram)>,
}

impl Figure for Fig05 {
    const NUMBER: u32 = 5;
    const TITLE: &'static str = "limit-cycle amplitude vs r by continuation, five μ0";

    fn compute(ctx: &FigureContext) -> Result<Fig05> {
        compute(ctx)
    }

    fn render(&self, stem: &Path) -> Result<Vec<PathBuf>> {
        let mut csv = Csv::new(
            &self.header,
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
        write_figure(self, stem, &csv.finish()?)
    }
}

fn compute(ctx: &FigureContext) -> Result<Fig05> {
    let pre = preset("fig5")?;
    let step = if ctx.quick { 0.01 } else { 0.002 };
    let mut panels = Vec::new();
    let mut notes: Vec<String> = pre.notes.iter().map(|s| s.to_string()).collect();
    notes.push("branches of f(A0; r) = 0 (Eq. 18) by pseudo-arclength continuation in (A0², r); stable ⇔ df/dA0 < 0".into());
    notes
        .push("r ranges chosen per panel to show every fold; the paper does not print them".into());
    let mut lines = Vec::new();
    for (label, mu0, r0, r1) in PANELS {
        let p = pre.params.with("mu0", mu0)?;
        let bd = branch_diagram(&p, ctx.variant, What::Rhythmicity, "r", r0, r1, step)?;
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
    let mut header = csv_header(
        5,
        "limit-cycle amplitude A0 vs r (branches by continuation)",
        ctx,
        &notes,
    );
    header.extend(lines);
    let heading = heading(
        5,
        "limit-cycle amplitude A0 against r, every branch traced through its folds",
        ctx,
        &pre.params,
        &["mu0", "r"],
        vec!["solid: stable (df/dA0 < 0), dashed: unstable; pseudo-arclength continuation of f(A0; r) = 0 (Eq. 18); the r ranges are chosen per panel (not printed in the paper)".into()],
    );
    Ok(Fig05 {
        heading,
        header,
        panels,
    })
}

/// Split a branch into runs of equal stability, sharing the boundary points.
pub(super) fn runs(
    points: &[trirhythm::theory::bifurcation::BranchPoint],
) -> Vec<(bool, Vec<(f64, f64)>)> {
    let mut out: Vec<(bool, Vec<(f64, f64)>)> = Vec::new();
    for q in points {
        let xy = (q.param, q.amplitude);
        match out.last_mut() {
            Some((s, v)) if *s == q.stable => v.push(xy),
            Some((_, v)) => {
                let last = *v.last().unwrap();
                out.push((q.stable, vec![last, xy]));
            }
            None => out.push((q.stable, vec![xy])),
        }
    }
    out
}

impl Picture for Fig05 {
    fn size(&self) -> (u32, u32) {
        (1500, 960)
    }

    fn heading(&self) -> Heading {
        self.heading.clone()
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()>
    where
        DB::ErrorType: 'static,
    {
        let areas = root.split_evenly((2, 3));
        for (i, (area, (label, mu0, bd))) in areas.iter().zip(&self.panels).enumerate() {
            let amax = bd
                .branches
                .iter()
                .flat_map(|b| b.points.iter().map(|q| q.amplitude))
                .fold(0.0f64, f64::max)
                .max(1.0);
            let mut c = chart(
                area,
                &format!("({label}) μ0 = {mu0}"),
                bd.start..bd.stop,
                0.0..amax * 1.08,
                "r",
                "A0",
            )?;
            let mut shown = [false, false];
            for b in &bd.branches {
                for (stable, pts) in runs(&b.points) {
                    if stable {
                        let s = c
                            .draw_series(LineSeries::new(pts, BLACK.stroke_width(2)))
                            .map_err(pe)?;
                        if !shown[0] {
                            s.label("stable").legend(|(x, y)| {
                                PathElement::new([(x, y), (x + 16, y)], BLACK.stroke_width(2))
                            });
                            shown[0] = true;
                        }
                    } else {
                        let s = c
                            .draw_series(DashedLineSeries::new(
                                pts,
                                6,
                                4,
                                RGBColor(200, 30, 30).stroke_width(2),
                            ))
                            .map_err(pe)?;
                        if !shown[1] {
                            s.label("unstable").legend(|(x, y)| {
                                PathElement::new(
                                    [(x, y), (x + 16, y)],
                                    RGBColor(200, 30, 30).stroke_width(2),
                                )
                            });
                            shown[1] = true;
                        }
                    }
                }
            }
            c.draw_series(bd.folds.iter().map(|&(r, a)| {
                EmptyElement::at((r, a)) + Circle::new((0, 0), 5, RGBColor(30, 90, 200).filled())
            }))
            .map_err(pe)?
            .label("fold (saddle-node)")
            .legend(|(x, y)| Circle::new((x + 8, y), 5, RGBColor(30, 90, 200).filled()));
            c.draw_series(bd.hopf.iter().map(|&r| {
                EmptyElement::at((r, 0.0))
                    + Rectangle::new([(-5, -5), (5, 5)], RGBColor(20, 150, 60).filled())
            }))
            .map_err(pe)?
            .label("branch born at A0 = 0")
            .legend(|(x, y)| {
                Rectangle::new(
                    [(x + 3, y - 5), (x + 13, y + 5)],
                    RGBColor(20, 150, 60).filled(),
                )
            });
            if i == 0 {
                legend(&mut c, SeriesLabelPosition::LowerLeft)?;
            }
        }
        Ok(())
    }
}
