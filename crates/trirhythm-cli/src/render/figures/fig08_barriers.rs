//! Fig. 8: the energy barriers ΔU_i between the wells and crests of U_eff (Eq. 23), D > 0.
//!
//! Rendering only: the data and its computation are [`trirhythm_paper::fig08_barriers`].

use super::fig07_pseudo_potential::{draw_curves, frame, MARKER};
use crate::render::plot::{
    chart, font_px, pe, pxi, rich_text, Backend, LegendStrip, Symbol, AXIS_DESC,
};
use anyhow::Result;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use trirhythm::theory::averaging::{Barrier, Side};
use trirhythm_paper::fig08_barriers::Fig08;

/// The inner well's right end: the first crest beyond the first well, with margin.
fn zoom_end(fig: &Fig08) -> f64 {
    let crest = fig
        .barriers
        .iter()
        .filter(|b| b.side == Side::Right)
        .map(|b| b.crest)
        .next()
        .unwrap_or(14.0);
    (crest * 1.4).min(14.0)
}

/// One panel: U_eff up to `x_end` with the barriers that fit.
fn draw_panel<DB: Backend>(
    fig: &Fig08,
    area: &DrawingArea<DB, plotters::coord::Shift>,
    caption: &str,
    x_end: f64,
) -> Result<()> {
    let (y, clipped) = frame(std::slice::from_ref(&fig.curve), x_end);
    let mut c = chart(area, caption, 0.0..x_end, y, "A_0", "U_eff(A_0)")?;
    let clipped = &clipped[0];
    draw_curves(&mut c, std::slice::from_ref(clipped), MARKER)?;
    let bar_x = |b: &Barrier| {
        b.well + if b.side == Side::Left { -0.12 } else { 0.12 } * (b.well - b.crest).abs()
    };
    let shown: Vec<f64> = fig
        .barriers
        .iter()
        .filter(|b| b.well <= x_end && b.crest <= x_end)
        .map(bar_x)
        .collect();
    for (i, b) in fig.barriers.iter().enumerate() {
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
        let xa = bar_x(b);
        let color = BARRIER;
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
            c.draw_series([EmptyElement::at((xa, yv)) + Circle::new((0, 0), 3, color.filled())])
                .map_err(pe)?;
        }
        // above its bar's top, clear of the curve (which runs through the crest below and
        // the well at the bar's foot); neighbouring labels on alternate rows
        let (x, y) = c.backend_coord(&(xa, u_crest));
        // a bar too short to see at this scale is not named here (the zoom shows it)
        if c.backend_coord(&(xa, u_well)).1 - y < pxi(6) {
            continue;
        }
        let (bx, by) = area.get_base_pixel();
        let name = format!("ΔU_{}", i + 1);
        let row = shown.iter().take_while(|&&other| other != xa).count() % 2;
        let lift = pxi(8) + row as i32 * (font_px(AXIS_DESC) as i32 * 6 / 5);
        rich_text(
            area,
            &name,
            (x - bx, y - by - lift),
            Pos::new(HPos::Center, VPos::Bottom),
            AXIS_DESC,
            color,
            false,
        )?;
    }
    Ok(())
}
/// Barrier colour.
const BARRIER: RGBColor = RGBColor(200, 30, 30);

fn key() -> LegendStrip {
    let black = RGBColor(0, 0, 0);
    LegendStrip {
        entries: vec![
            (Symbol::Line(black), "U_eff(A0)".into()),
            (Symbol::Dot(black), "filled: well (stable cycle)".into()),
            (Symbol::Ring(black), "open: crest (unstable cycle)".into()),
            (
                Symbol::Line(BARRIER),
                "ΔU_i: from a well up to its crest".into(),
            ),
        ],
    }
}

picture!(Fig08, |self, root| size (1400, 620 + key().height(1400)), draw {
    let (panels, strip) = root.split_vertically(620);
    let areas = panels.split_evenly((1, 2));
    draw_panel(self, &areas[0], "(a) U_eff and its barriers ΔU_i", 14.0)?;
    draw_panel(
        self,
        &areas[1],
        "(b) zoom on the inner well",
        zoom_end(self),
    )?;
    key().draw(&strip)
});
