//! Shared data and drawing of classification maps (Figs 2, 3, 6, 10, 12): regions coloured by
//! count (mono blue, bi green, tri black, as in the paper), exact fold curves on top, one legend
//! for the whole figure in a strip below the panels (outside the data). A panel of stable
//! cycles states its mono/bi/tri shares of the grid in its title ([`MapPanel::share`], the
//! numbers the verdicts on Figs 3 and 6 are decided on) and, where the trirhythmic region is
//! small, zooms on it in an inset ([`MapPanel::bounding_box`], padded) placed in the corner
//! of the panel that hides the least: no trirhythmic cell, fold curve, label or mark.
//!
//! Rendering only: the data and its computation are [`trirhythm_paper::maps`].

use crate::render::plot::{
    chart, draw_line, font_px, framed, pe, px, pxi, rich_text, rich_width, stroke, Backend,
    ChartSize, Dash, LegendStrip, Marker, SeriesStyle, Symbol, LABEL,
};
use anyhow::Result;
use plotters::coord::types::RangedCoordf64;
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
        &panel_title(p),
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
    // the inset (and the outline of the box it zooms on) first: the names go over it
    if p.what == What::Rhythmicity {
        draw_inset(area, &mut c, p)?;
    }
    // the fold curves in backend pixels, for placing the names off them
    let fold_px: Vec<(i32, i32)> = p
        .folds
        .curves
        .iter()
        .chain(p.printed.iter().flat_map(|f| &f.curves))
        .flat_map(|cv| cv.points.iter())
        .map(|q| c.backend_coord(&(q.x / sx, q.y / sy)))
        .collect();
    let (rx, ry) = c.plotting_area().get_pixel_range();
    for (i, name) in &p.fold_names {
        let curve = &p.folds.curves[*i];
        let q = &curve.points[curve.points.len() / 2];
        let (x, y) = c.backend_coord(&(q.x / sx, q.y / sy));
        // on a white box: red on green, blue or black is hard to read; beside its curve's
        // middle, on the side (right, left, above, below) its box covers the fewest points
        // of the fold curves, inside the plotting area
        let w = rich_width(name, LABEL) as i32 + pxi(8);
        let h = font_px(LABEL) as i32 * 3 / 4;
        let gap = pxi(8);
        let places = [
            (x + gap, y - h),
            (x - gap - w, y - h),
            (x - w / 2, y - gap - 2 * h),
            (x - w / 2, y + gap),
            (x + gap, y - gap - 2 * h),
            (x + gap, y + gap),
            (x - gap - w, y - gap - 2 * h),
            (x - gap - w, y + gap),
        ];
        let cost = |&(x0, y0): &(i32, i32)| -> usize {
            let outside = x0 < rx.start || x0 + w > rx.end || y0 < ry.start || y0 + 2 * h > ry.end;
            let hits = fold_px
                .iter()
                .filter(|&&(px_, py)| px_ >= x0 && px_ <= x0 + w && py >= y0 && py <= y0 + 2 * h)
                .count();
            hits + if outside { 1_000_000 } else { 0 }
        };
        let (x0, y0) = places
            .iter()
            .copied()
            .min_by_key(cost)
            .unwrap_or((x + gap, y - h));
        let (bx, by) = area.get_base_pixel();
        area.draw(&Rectangle::new(
            [(x0 - bx, y0 - by), (x0 - bx + w, y0 - by + 2 * h)],
            WHITE.mix(0.85).filled(),
        ))
        .map_err(pe)?;
        rich_text(
            area,
            name,
            (x0 - bx + pxi(4), y0 - by + h),
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

/// A panel's title: its label and caption, and for a panel of stable cycles the shares of
/// the grid with one, two and three cycles (per cent, one decimal; a no-break space before
/// each % keeps a share on one line when the title wraps).
fn panel_title(p: &MapPanel) -> String {
    let title = format!("({}) {}", p.label, p.caption);
    if p.what != What::Rhythmicity {
        return title;
    }
    format!(
        "{title}: mono {:.1}\u{a0}%, bi {:.1}\u{a0}%, tri {:.1}\u{a0}%",
        p.share(1),
        p.share(2),
        p.share(3)
    )
}

/// The largest share of the plane (per cent) the trirhythmic region may cover and still be
/// zoomed on in an inset.
const INSET_BELOW: f64 = 20.0;
/// The inset's size as a fraction of the plotting area's width and height.
const INSET_FRACTION: f64 = 0.5;

/// The data ranges (display units) an inset zooms on: the bounding box of the trirhythmic
/// cells, padded by a tenth of its size and at least one cell on each side, within the plane.
fn inset_ranges(p: &MapPanel) -> Option<(std::ops::Range<f64>, std::ops::Range<f64>)> {
    if p.share(3) == 0.0 || p.share(3) > INSET_BELOW {
        return None;
    }
    let ((ix0, ix1), (iy0, iy1)) = p.bounding_box(3)?;
    let zoom = |g: &trirhythm::theory::bifurcation::Axis, s: f64, i0: usize, i1: usize| {
        let h = (g.stop - g.start) / (g.count - 1) as f64 / s;
        let (a, b) = (g.value(i0) / s - h / 2.0, g.value(i1) / s + h / 2.0);
        let pad = (0.1 * (b - a)).max(h);
        let (lo, hi) = (g.start / s, g.stop / s);
        (a - pad).max(lo)..(b + pad).min(hi)
    };
    Some((
        zoom(&p.x.grid, p.x.scale, ix0, ix1),
        zoom(&p.y.grid, p.y.scale, iy0, iy1),
    ))
}

type MapChart<'a, DB> = ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// Draw the inset zooming on the trirhythmic region (where [`inset_ranges`] gives one): the
/// zoomed box outlined on the panel, the inset in the corner of the plotting area whose cover
/// hides the least.
fn draw_inset<DB: Backend>(
    area: &DrawingArea<DB, Shift>,
    c: &mut MapChart<'_, DB>,
    p: &MapPanel,
) -> Result<()> {
    let Some((zx, zy)) = inset_ranges(p) else {
        return Ok(());
    };
    let (rx, ry) = c.plotting_area().get_pixel_range();
    let (iw, ih) = (
        ((rx.end - rx.start) as f64 * INSET_FRACTION) as i32,
        ((ry.end - ry.start) as f64 * INSET_FRACTION) as i32,
    );
    let gap = pxi(6);
    let corners = [
        (rx.end - gap - iw, ry.start + gap),
        (rx.start + gap, ry.start + gap),
        (rx.end - gap - iw, ry.end - gap - ih),
        (rx.start + gap, ry.end - gap - ih),
    ];
    let zoom_box = [
        c.backend_coord(&(zx.start, zy.end)),
        c.backend_coord(&(zx.end, zy.start)),
    ];
    let Some(&(ax, ay)) = corners
        .iter()
        .min_by_key(|&&corner| cover_cost(c, p, corner, (iw, ih), zoom_box))
    else {
        return Ok(());
    };
    // the zoomed box on the panel
    c.draw_series(std::iter::once(Rectangle::new(
        [(zx.start, zy.start), (zx.end, zy.end)],
        WHITE.stroke_width(stroke(2)),
    )))
    .map_err(pe)?;
    let (bx, by) = area.get_base_pixel();
    let inset = area
        .clone()
        .shrink((ax - bx, ay - by), (iw as u32, ih as u32));
    inset.fill(&WHITE).map_err(pe)?;
    let mut z = framed(
        &inset,
        "",
        (zx.clone(), zy.clone()),
        ("", ""),
        ChartSize::Inset,
    )?;
    let (gx, gy) = (&p.x.grid, &p.y.grid);
    let (sx, sy) = (p.x.scale, p.y.scale);
    let hx = (gx.stop - gx.start) / (gx.count - 1) as f64 / sx;
    let hy = (gy.stop - gy.start) / (gy.count - 1) as f64 / sy;
    let mut rects = Vec::new();
    for iy in 0..gy.count {
        let y = gy.value(iy) / sy;
        if y + hy / 2.0 < zy.start || y - hy / 2.0 > zy.end {
            continue;
        }
        for ix in 0..gx.count {
            let x = gx.value(ix) / sx;
            if x + hx / 2.0 < zx.start || x - hx / 2.0 > zx.end {
                continue;
            }
            let cx = |v: f64| v.clamp(zx.start, zx.end);
            let cy = |v: f64| v.clamp(zy.start, zy.end);
            rects.push(Rectangle::new(
                [
                    (cx(x - hx / 2.0), cy(y - hy / 2.0)),
                    (cx(x + hx / 2.0), cy(y + hy / 2.0)),
                ],
                count_colour(p.count(ix, iy)).filled(),
            ));
        }
    }
    z.draw_series(rects).map_err(pe)?;
    let fold = SeriesStyle {
        colour: FOLD,
        dash: Dash::Solid,
        marker: Marker::None,
    };
    for curve in &p.folds.curves {
        let pts: Vec<(f64, f64)> = curve.points.iter().map(|q| (q.x / sx, q.y / sy)).collect();
        draw_line(&z, &pts, fold, 2)?;
    }
    let inside = |x: f64, y: f64| zx.contains(&x) && zy.contains(&y);
    z.draw_series(
        p.folds
            .cusps
            .iter()
            .filter(|q| inside(q.x / sx, q.y / sy))
            .map(|q| {
                EmptyElement::at((q.x / sx, q.y / sy))
                    + Circle::new((0, 0), px(5), WHITE.filled())
                    + Circle::new((0, 0), px(5), FOLD.stroke_width(stroke(2)))
            }),
    )
    .map_err(pe)?;
    // the inset's frame
    inset
        .draw(&Rectangle::new(
            [(0, 0), (iw - 1, ih - 1)],
            BLACK.stroke_width(stroke(1)),
        ))
        .map_err(pe)?;
    Ok(())
}

/// What an inset at `corner` (backend pixels, top left) of `size` would hide on the panel:
/// trirhythmic cells, the zoomed box and labels weigh most, then fold curves and cusps, then
/// cells of a count other than the corner's commonest (a uniform corner hides least).
fn cover_cost<DB: Backend>(
    c: &MapChart<'_, DB>,
    p: &MapPanel,
    corner: (i32, i32),
    (w, h): (i32, i32),
    zoom_box: [(i32, i32); 2],
) -> u64 {
    let margin = pxi(4);
    let hit = |(x, y): (i32, i32)| {
        x >= corner.0 - margin
            && x <= corner.0 + w + margin
            && y >= corner.1 - margin
            && y <= corner.1 + h + margin
    };
    let (gx, gy) = (&p.x.grid, &p.y.grid);
    let (sx, sy) = (p.x.scale, p.y.scale);
    let mut counts = [0u64; 5];
    for iy in 0..gy.count {
        for ix in 0..gx.count {
            if hit(c.backend_coord(&(gx.value(ix) / sx, gy.value(iy) / sy))) {
                counts[p.count(ix, iy).min(4) as usize] += 1;
            }
        }
    }
    let inside: u64 = counts.iter().sum();
    let commonest = counts.iter().copied().max().unwrap_or(0);
    let mut cost = 1000 * counts[3] + (inside - commonest);
    let overlaps = |[a, b]: [(i32, i32); 2]| {
        a.0.max(b.0) >= corner.0
            && a.0.min(b.0) <= corner.0 + w
            && a.1.max(b.1) >= corner.1
            && a.1.min(b.1) <= corner.1 + h
    };
    if overlaps(zoom_box) {
        cost += 1_000_000;
    }
    for curve in &p.folds.curves {
        let n = curve
            .points
            .iter()
            .filter(|q| hit(c.backend_coord(&(q.x / sx, q.y / sy))))
            .count() as u64;
        cost += 20 * n;
    }
    for q in &p.folds.cusps {
        if hit(c.backend_coord(&(q.x / sx, q.y / sy))) {
            cost += 10_000;
        }
    }
    for (i, name) in &p.fold_names {
        let curve = &p.folds.curves[*i];
        let q = &curve.points[curve.points.len() / 2];
        let (x, y) = c.backend_coord(&(q.x / sx, q.y / sy));
        let w = rich_width(name, LABEL) as i32 + pxi(10);
        if overlaps([(x, y - pxi(8)), (x + w, y + pxi(8))]) {
            cost += 100_000;
        }
    }
    if let Some((mx, my, _)) = &p.mark {
        if hit(c.backend_coord(&(mx / sx, my / sy))) {
            cost += 100_000;
        }
    }
    cost
}
