//! Shared data and drawing of classification maps (Figs 2, 3, 6, 10, 12): regions coloured by
//! count (mono blue, bi green, tri black, as in the paper), exact fold curves on top, one legend
//! for the whole figure in a strip below the panels (outside the data).
//!
//! Rendering only: the data and its computation are [`trirhythm_paper::maps`].

use crate::render::plot::{
    chart, font_px, pe, pxi, rich_text, rich_width, Backend, LegendStrip, Symbol, LABEL,
};
use anyhow::Result;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use trirhythm::theory::bifurcation::What;
use trirhythm_paper::maps::{MapFigure, MapPanel};

/// Colour of a count: 0 light grey, 1 blue, 2 green, 3 black, more purple.
pub fn count_colour(c: u8) -> RGBColor {
    match c {
        0 => RGBColor(225, 225, 225),
        1 => RGBColor(40, 90, 220),
        2 => RGBColor(40, 170, 70),
        3 => RGBColor(0, 0, 0),
        _ => RGBColor(150, 60, 180),
    }
}

/// Fold-curve colour (visible on blue, green and black).
pub const FOLD: RGBColor = RGBColor(230, 40, 40);
/// Printed-Eq. 37 curve colour.
pub const PRINTED: RGBColor = RGBColor(255, 170, 0);

/// One legend for every panel: the counts met in any panel, the curves and markers drawn.
fn legend(fig: &MapFigure) -> LegendStrip {
    let mut counts = [0usize; 5];
    for p in &fig.panels {
        for (c, h) in counts.iter_mut().zip(p.histogram()) {
            *c += h;
        }
    }
    let modes = fig.panels.iter().any(|p| p.what == What::Modes);
    let names = if modes {
        ["-", "unimodal", "bimodal", "trimodal", "4+ modes"]
    } else {
        [
            "no stable cycle",
            "mono (1)",
            "bi (2)",
            "tri (3)",
            "4 or more",
        ]
    };
    let mut entries: Vec<(Symbol, String)> = (0..5)
        .filter(|&k| counts[k] > 0)
        .map(|k| (Symbol::Swatch(count_colour(k as u8)), names[k].to_string()))
        .collect();
    if fig.panels.iter().any(|p| !p.folds.curves.is_empty()) {
        let name = if modes {
            "P-bifurcation (m1 = m1' = 0)"
        } else {
            "saddle-node (f = f' = 0)"
        };
        entries.push((Symbol::Line(FOLD), name.into()));
    }
    if fig
        .panels
        .iter()
        .any(|p| p.printed.as_ref().is_some_and(|f| !f.curves.is_empty()))
    {
        entries.push((Symbol::Dashed(PRINTED), "Eq. 36-37 as printed".into()));
    }
    if fig.panels.iter().any(|p| !p.folds.cusps.is_empty()) {
        entries.push((Symbol::Ring(FOLD), "cusp".into()));
    }
    // one entry for the marked points, however many panels mark different parameters
    let mut marks: Vec<&str> = Vec::new();
    for (_, _, text) in fig.panels.iter().filter_map(|p| p.mark.as_ref()) {
        if !marks.contains(&text.as_str()) {
            marks.push(text);
        }
    }
    if !marks.is_empty() {
        entries.push((Symbol::Cross(MARK), marks.join(" / ")));
    }
    LegendStrip { entries }
}

/// Panel size in pixels.
const PANEL: (u32, u32) = (560, 470);

/// Panels per (row, column): two side by side, four in a square.
fn layout(fig: &MapFigure) -> (usize, usize) {
    match fig.panels.len() {
        n @ 0..=2 => (1, n.max(1)),
        n => (2, n.div_ceil(2)),
    }
}

// A map figure: its panels, one legend strip for all of them below.
picture!(MapFigure, |self, root| size {
    let (r, c) = layout(self);
    let w = PANEL.0 * c as u32;
    (w, PANEL.1 * r as u32 + legend(self).height(w))
}, draw {
    let (panels, strip) = root.split_vertically(PANEL.1 * layout(self).0 as u32);
    for (area, p) in panels.split_evenly(layout(self)).iter().zip(&self.panels) {
        draw_panel(area, p)?;
    }
    legend(self).draw(&strip)
});

/// Colour of the marked parameter point.
const MARK: RGBColor = RGBColor(255, 0, 255);

/// Draw one map panel: merged row runs of equal count, fold curves (named where known),
/// cusps, the marked point. The legend is the figure's, outside the panels.
fn draw_panel<DB: Backend>(area: &DrawingArea<DB, Shift>, p: &MapPanel) -> Result<()> {
    let (gx, gy) = (&p.x.grid, &p.y.grid);
    let (sx, sy) = (p.x.scale, p.y.scale);
    let xr = (gx.start / sx)..(gx.stop / sx);
    let yr = (gy.start / sy)..(gy.stop / sy);
    let mut c = chart(
        area,
        &format!("({}) {}", p.label, p.caption),
        xr.clone(),
        yr.clone(),
        &p.x.desc(),
        &p.y.desc(),
    )?;
    let (nx, ny) = (gx.count, gy.count);
    let hx = (gx.stop - gx.start) / (nx - 1) as f64 / sx;
    let hy = (gy.stop - gy.start) / (ny - 1) as f64 / sy;
    let clampx = |v: f64| v.clamp(xr.start, xr.end);
    let clampy = |v: f64| v.clamp(yr.start, yr.end);
    let mut rects = Vec::new();
    for iy in 0..ny {
        let y = gy.value(iy) / sy;
        let mut ix = 0;
        while ix < nx {
            let cnt = p.count(ix, iy);
            let mut jx = ix;
            while jx + 1 < nx && p.count(jx + 1, iy) == cnt {
                jx += 1;
            }
            let x0 = clampx(gx.value(ix) / sx - hx / 2.0);
            let x1 = clampx(gx.value(jx) / sx + hx / 2.0);
            rects.push(Rectangle::new(
                [(x0, clampy(y - hy / 2.0)), (x1, clampy(y + hy / 2.0))],
                count_colour(cnt).filled(),
            ));
            ix = jx + 1;
        }
    }
    c.draw_series(rects).map_err(pe)?;
    for curve in &p.folds.curves {
        let pts: Vec<(f64, f64)> = curve.points.iter().map(|q| (q.x / sx, q.y / sy)).collect();
        c.draw_series(LineSeries::new(pts, FOLD.stroke_width(2)))
            .map_err(pe)?;
    }
    for curve in p.printed.iter().flat_map(|f| &f.curves) {
        let pts: Vec<(f64, f64)> = curve.points.iter().map(|q| (q.x / sx, q.y / sy)).collect();
        c.draw_series(DashedLineSeries::new(pts, 7, 5, PRINTED.stroke_width(2)))
            .map_err(pe)?;
    }
    for (i, name) in &p.fold_names {
        let curve = &p.folds.curves[*i];
        let q = &curve.points[curve.points.len() / 2];
        // on a white box: red on green, blue or black is hard to read
        let w = rich_width(name, LABEL) as i32 + pxi(8);
        let h = font_px(LABEL) as i32 * 3 / 4;
        c.draw_series(std::iter::once(
            EmptyElement::at((q.x / sx, q.y / sy))
                + Rectangle::new([(pxi(6), -h), (pxi(6) + w, h)], WHITE.mix(0.85).filled()),
        ))
        .map_err(pe)?;
        let (x, y) = c.backend_coord(&(q.x / sx, q.y / sy));
        let (bx, by) = area.get_base_pixel();
        rich_text(
            area,
            name,
            (x - bx + pxi(10), y - by),
            Pos::new(HPos::Left, VPos::Center),
            LABEL,
            FOLD,
            false,
        )?;
    }
    c.draw_series(p.folds.cusps.iter().map(|q| {
        EmptyElement::at((q.x / sx, q.y / sy))
            + Circle::new((0, 0), 6, WHITE.filled())
            + Circle::new((0, 0), 6, FOLD.stroke_width(2))
    }))
    .map_err(pe)?;
    if let Some((mx, my, _)) = &p.mark {
        c.draw_series(std::iter::once(
            EmptyElement::at((mx / sx, my / sy))
                + Cross::new((0, 0), 7, WHITE.stroke_width(4))
                + Cross::new((0, 0), 7, MARK.stroke_width(2)),
        ))
        .map_err(pe)?;
    }
    Ok(())
}
