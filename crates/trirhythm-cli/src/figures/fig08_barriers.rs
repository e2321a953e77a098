//! Fig. 8: the energy barriers ΔU_i between the wells and crests of U_eff (Eq. 23), D > 0.

use super::fig07_pseudo_potential::{draw_curves, frame, Curve};
use super::write_figure;
use super::{csv_header, panel_line, Figure, FigureContext};
use crate::common::{num, Csv};
use crate::plot::{chart, pe, Heading, Picture, FONT};
use anyhow::Result;
use plotters::prelude::*;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use trirhythm::model::preset;
use trirhythm::theory::averaging::{Barrier, Side, Theory};

/// Fig. 8's data: U_eff on a grid with its extrema, the barriers, the zoom's right end.
#[derive(Serialize, Deserialize)]
pub struct Fig08 {
    heading: Heading,
    /// CSV comment lines.
    header: Vec<String>,
    curve: Curve,
    barriers: Vec<Barrier>,
    zoom_end: f64,
}

impl Figure for Fig08 {
    const NUMBER: u32 = 8;
    const TITLE: &'static str = "energy barriers ΔU_i of U_eff";

    fn compute(ctx: &FigureContext) -> Result<Fig08> {
        compute(ctx)
    }

    fn render(&self, stem: &Path) -> Result<Vec<PathBuf>> {
        let mut csv = Csv::new(&self.header, &["A", "U_eff"]);
        for &(a, u) in &self.curve.points {
            csv.row([num(a), num(u)]);
        }
        write_figure(self, stem, &csv.finish()?)
    }
}

fn compute(ctx: &FigureContext) -> Result<Fig08> {
    let pre = preset("fig8")?;
    let p = pre.params;
    let th = Theory::new(&p, ctx.variant)?;
    let n = if ctx.quick { 400 } else { 2000 };
    let grid: Vec<f64> = (1..=n).map(|i| 14.0 * i as f64 / n as f64).collect();
    let curve = Curve::new("U_eff".into(), &th, &grid);
    let barriers = th.barriers();
    let mut notes: Vec<String> = pre.notes.iter().map(|s| s.to_string()).collect();
    notes.push(format!("σ1 = {}", th.diffusion()));
    for (i, b) in barriers.iter().enumerate() {
        notes.push(format!(
            "ΔU{} = {:.6e}: well A = {:.6} → crest A = {:.6} ({})",
            i + 1,
            b.height,
            b.well,
            b.crest,
            if b.side == Side::Left {
                "left"
            } else {
                "right"
            }
        ));
    }
    if barriers.len() != 4 {
        notes.push(format!(
            "{} barriers (not the paper's four) for these parameters",
            barriers.len()
        ));
    }
    let mut header = csv_header(8, "energy barriers of U_eff(A0)", ctx, &notes);
    header.push(panel_line("", &p));
    // Zoom on the inner wells: up to the first crest beyond the first well, with margin.
    let zoom_end = barriers
        .iter()
        .filter(|b| b.side == Side::Right)
        .map(|b| b.crest)
        .next()
        .unwrap_or(14.0)
        * 1.4;
    Ok(Fig08 {
        heading: super::heading(
            8,
            "energy barriers ΔU_i of the pseudo-potential U_eff(A0)",
            ctx,
            &p,
            &[],
            pre.notes.iter().map(|s| s.to_string()).collect(),
        ),
        header,
        curve,
        barriers,
        zoom_end: zoom_end.min(14.0),
    })
}

impl Fig08 {
    fn draw_panel<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, plotters::coord::Shift>,
        caption: &str,
        x_end: f64,
    ) -> Result<()>
    where
        DB::ErrorType: 'static,
    {
        let (y, clipped) = frame(std::slice::from_ref(&self.curve), x_end);
        let mut c = chart(area, caption, 0.0..x_end, y, "A0", "U_eff(A0)")?;
        let clipped = &clipped[0];
        draw_curves(&mut c, std::slice::from_ref(clipped), false)?;
        for (i, b) in self.barriers.iter().enumerate() {
            if b.well > x_end || b.crest > x_end {
                continue;
            }
            let u_well = clipped
                .extrema
                .iter()
                .find(|e| e.amplitude == b.well)
                .map(|e| e.potential)
                .unwrap_or(0.0);
            let u_crest = u_well + b.height;
            let xa =
                b.well + if b.side == Side::Left { -0.12 } else { 0.12 } * (b.well - b.crest).abs();
            let color = RGBColor(200, 30, 30);
            c.draw_series(DashedLineSeries::new(
                [(b.crest, u_crest), (xa, u_crest)],
                4,
                3,
                color.stroke_width(1),
            ))
            .map_err(pe)?;
            c.draw_series(LineSeries::new(
                [(xa, u_well), (xa, u_crest)],
                color.stroke_width(2),
            ))
            .map_err(pe)?;
            for yv in [u_well, u_crest] {
                c.draw_series(
                    [EmptyElement::at((xa, yv)) + Circle::new((0, 0), 3, color.filled())],
                )
                .map_err(pe)?;
            }
            c.draw_series([EmptyElement::at((xa, 0.5 * (u_well + u_crest)))
                + Text::new(
                    format!("ΔU{}", i + 1),
                    (6, -8),
                    (FONT, 16).into_font().color(&color),
                )])
            .map_err(pe)?;
        }
        Ok(())
    }
}

impl Picture for Fig08 {
    fn size(&self) -> (u32, u32) {
        (1400, 620)
    }

    fn heading(&self) -> Heading {
        self.heading.clone()
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, plotters::coord::Shift>) -> Result<()>
    where
        DB::ErrorType: 'static,
    {
        let areas = root.split_evenly((1, 2));
        self.draw_panel(&areas[0], "(a) U_eff and its barriers ΔU_i", 14.0)?;
        self.draw_panel(&areas[1], "(b) zoom on the inner wells", self.zoom_end)?;
        Ok(())
    }
}
