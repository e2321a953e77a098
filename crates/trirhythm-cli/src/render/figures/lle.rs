//! What Figs 17–19 share: runs of the largest Lyapunov exponent at quick or paper quality,
//! panels of curves with error bars, and their CSV and drawing. Each panel keeps its legend in
//! a strip below its chart, so no legend covers data.
//!
//! Drawing only: the runs and verdicts are [`trirhythm_paper::lle`].

use crate::render::plot::{chart, padded_range, pe, Backend, LegendStrip, Symbol, PALETTE};
use anyhow::Result;
use plotters::coord::Shift;
use plotters::prelude::*;
use trirhythm_paper::lle::{LleAgainstNoise, Panel};

/// Height of the chart part of a panel.
pub const CHART_HEIGHT: u32 = 420;
/// Width of a panel.
pub const PANEL_WIDTH: u32 = 600;

fn strip(panel: &Panel) -> LegendStrip {
    LegendStrip {
        entries: panel
            .curves
            .iter()
            .enumerate()
            .map(|(i, c)| (Symbol::Line(PALETTE[i % PALETTE.len()]), c.label.clone()))
            .collect(),
    }
}

/// Height of a panel with its legend strip.
pub fn panel_height(panels: &[Panel]) -> u32 {
    CHART_HEIGHT
        + panels
            .iter()
            .map(|p| strip(p).height(PANEL_WIDTH))
            .max()
            .unwrap_or(0)
        + 8
}

/// Draw one panel: chart, error bars, zero line, verdicts, legend strip below.
pub fn draw_panel<DB: Backend>(area: &DrawingArea<DB, Shift>, panel: &Panel) -> Result<()> {
    let (top, bottom) = area.split_vertically(CHART_HEIGHT);
    let xs = panel
        .curves
        .iter()
        .flat_map(|c| c.points.iter().map(|q| q.x));
    let x = padded_range(xs);
    let mut ys: Vec<f64> = panel
        .curves
        .iter()
        .flat_map(|c| c.points.iter())
        .filter(|q| q.y.is_finite())
        .flat_map(|q| [q.lo, q.hi, q.y])
        .collect();
    if shows_zero(panel) {
        ys.push(0.0);
    }
    if ys.iter().all(|v| !v.is_finite()) {
        ys = vec![0.0, 1.0];
    }
    let mut y = padded_range(ys);
    // room at the top for the verdict lines
    y.end += (y.end - y.start) * 0.08 * panel.verdicts.len() as f64;
    let mut c = chart(
        &top,
        &panel.caption,
        x.clone(),
        y.clone(),
        &panel.x_desc,
        &panel.y_desc,
    )?;
    if shows_zero(panel) {
        c.draw_series(std::iter::once(PathElement::new(
            [(x.start, 0.0), (x.end, 0.0)],
            RGBColor(120, 120, 120).stroke_width(1),
        )))
        .map_err(pe)?;
    }
    for (i, curve) in panel.curves.iter().enumerate() {
        let colour = PALETTE[i % PALETTE.len()];
        // a small horizontal offset per curve keeps overlapping error bars apart
        let shift = (x.end - x.start) * 0.004 * (i as f64 - 1.5);
        let pts: Vec<(f64, f64)> = curve
            .points
            .iter()
            .filter(|q| q.y.is_finite())
            .map(|q| (q.x + shift, q.y))
            .collect();
        // the line is broken where a point has no value (−∞: merged realisations), so that it
        // never suggests a measurement there
        for run in curve.points.split(|q| !q.y.is_finite()) {
            let run: Vec<(f64, f64)> = run.iter().map(|q| (q.x + shift, q.y)).collect();
            c.draw_series(LineSeries::new(run, colour.stroke_width(2)))
                .map_err(pe)?;
        }
        c.draw_series(pts.iter().map(|&p| Circle::new(p, 4, colour.filled())))
            .map_err(pe)?;
        let cap = (x.end - x.start) * 0.006;
        for q in curve.points.iter().filter(|q| q.y.is_finite()) {
            let xq = q.x + shift;
            c.draw_series([
                PathElement::new([(xq, q.lo), (xq, q.hi)], colour.stroke_width(1)),
                PathElement::new([(xq - cap, q.lo), (xq + cap, q.lo)], colour.stroke_width(1)),
                PathElement::new([(xq - cap, q.hi), (xq + cap, q.hi)], colour.stroke_width(1)),
            ])
            .map_err(pe)?;
        }
    }
    for (k, v) in panel.verdicts.iter().enumerate() {
        let at = (
            x.start + 0.02 * (x.end - x.start),
            y.end - (0.02 + 0.075 * k as f64) * (y.end - y.start),
        );
        c.draw_series(std::iter::once(Text::new(
            v.clone(),
            at,
            (crate::render::plot::FONT, 14).into_font().color(&BLACK),
        )))
        .map_err(pe)?;
    }
    strip(panel).draw(&bottom)
}

// An LLE-against-noise figure (Figs 17, 18): the two panels side by side.
picture!(LleAgainstNoise, |self, root| size (2 * PANEL_WIDTH, panel_height(&self.panels)), draw {
    for (area, panel) in root.split_evenly((1, 2)).iter().zip(&self.panels) {
        draw_panel(area, panel)?;
    }
    Ok(())
});

/// Whether a panel draws the line y = 0: a Lyapunov exponent's sign is the point.
fn shows_zero(panel: &Panel) -> bool {
    panel.y_key == "lle"
}
