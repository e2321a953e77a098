//! Shared data and drawing of classification maps (Figs 2, 3, 6, 10, 12): regions coloured by
//! count (mono blue, bi green, tri black, as in the paper), exact fold curves on top, one legend
//! for the whole figure in a strip below the panels (outside the data). A panel of stable
//! cycles states its mono/bi/tri shares of the grid in its title ([`MapPanel::share`], the
//! numbers the verdicts on Figs 3 and 6 are decided on) and, where the trirhythmic region is
//! small, zooms on it in an inset ([`MapPanel::bounding_box`], padded; on a map of modes a
//! thin band, [`MapPanel::slivers`]) placed where it hides the least: no trirhythmic cell,
//! fold curve or mark, a corner when one does as well as anywhere. The folds are named "L1"–
//! "L3" beside their curves, where a name covers no fold, inset or other name; the legend
//! says which cycle's fold each name is.
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

/// Colour of a count: 0 light grey, 1 blue, 2 green, 3 black, more purple; blue, green and
/// black of distinct greys (luminance 145, 98, 0), so that the regions part in greyscale.
pub fn count_colour(c: u8) -> RGBColor {
    match c {
        0 => RGBColor(225, 225, 225),
        1 => RGBColor(100, 150, 240),
        2 => RGBColor(30, 140, 60),
        3 => RGBColor(0, 0, 0),
        _ => RGBColor(150, 60, 180),
    }
}

/// Fold-curve colour (visible on blue, green and black).
pub const FOLD: RGBColor = RGBColor(230, 40, 40);
/// Printed-Eq. 37 curve colour.
pub const PRINTED: RGBColor = RGBColor(255, 170, 0);
/// The strip beyond the computed grid (no data).
const BEYOND: RGBColor = RGBColor(228, 228, 228);

/// Whether a map's panels zoom on a small region in an inset: the paper's figures do; the
/// simulated map's panels do not (its marks would fall on the inset).
#[derive(Clone, Copy, PartialEq, Eq)]
pub(super) enum Insets {
    /// Where [`inset_ranges`] finds a region to enlarge.
    Drawn,
    /// Never.
    Off,
}

/// One legend for every panel: the counts met in any panel, the curves and markers drawn.
pub(super) fn legend(fig: &MapFigure, insets: Insets) -> LegendStrip {
    let mut counts = [0usize; 5];
    for p in &fig.panels {
        for (c, h) in counts.iter_mut().zip(p.histogram()) {
            *c += h;
        }
    }
    let modes = fig.panels.iter().any(|p| p.what == What::Modes);
    let names = if modes {
        ["no mode", "unimodal", "bimodal", "trimodal", "4+ modes"]
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
    // the fold names drawn beside the lines: L1 the outer cycle's fold, L3 the inner one's
    let named: Vec<String> = [("L1", "outer"), ("L2", "middle"), ("L3", "inner")]
        .into_iter()
        .filter(|(n, _)| {
            fig.panels
                .iter()
                .any(|p| p.fold_names.iter().any(|(_, m)| short_name(m) == *n))
        })
        .map(|(n, what)| format!("{n} the {what}"))
        .collect();
    if fig.panels.iter().any(|p| !p.folds.curves.is_empty()) {
        let name = if modes {
            "P-bifurcation: m1 = m1' = 0 (Eq. 35–37)".to_string()
        } else if named.is_empty() {
            "saddle-node (f = f' = 0)".to_string()
        } else {
            format!("saddle-node (f = f' = 0), {} cycle's", named.join(", "))
        };
        entries.push((Symbol::Line(FOLD), name));
    }
    if insets == Insets::Drawn && fig.panels.iter().any(|p| inset_ranges(p).is_some()) {
        entries.push((
            Symbol::Framed(count_colour(2), WHITE),
            "enlarged in the inset".into(),
        ));
    }
    if fig
        .panels
        .iter()
        .any(|p| p.printed.as_ref().is_some_and(|f| !f.curves.is_empty()))
    {
        entries.push((Symbol::Underlaid(PRINTED), "Eq. 36-37 as printed".into()));
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
pub(super) const PANEL: (u32, u32) = (560, 470);

/// Panels per (row, column): two side by side, four in a square.
fn layout(fig: &MapFigure) -> (usize, usize) {
    match fig.panels.len() {
        n @ 0..=2 => (1, n.max(1)),
        n => (2, n.div_ceil(2)),
    }
}

// A map figure: its panels, one legend strip for all of them below.
picture!(MapFigure, |self, root| key map_key(self), size {
    let (r, c) = layout(self);
    let w = PANEL.0 * c as u32;
    (w, PANEL.1 * r as u32 + legend(self, Insets::Drawn).height(w))
}, draw {
    let (panels, strip) = root.split_vertically(PANEL.1 * layout(self).0 as u32);
    let ends = clear_ends(self, Insets::Drawn);
    for ((area, p), ends) in panels.split_evenly(layout(self)).iter().zip(&self.panels).zip(ends) {
        draw_panel(area, p, ends, Insets::Drawn)?;
    }
    legend(self, Insets::Drawn).draw(&strip)
});

/// Which ends of its axes (x start, x end, y start, y end) a panel leaves a strip beyond the
/// map at ([`END_GAP`] of the axis): those along which a printed curve runs (its points
/// within [`ON_END`] of the axis from the end spanning [`ALONG`] of the other axis or more:
/// drawn on the spine) or an inset's zoom box lies, so that neither sits on a spine.
fn panel_ends(p: &MapPanel, insets: Insets) -> [bool; 4] {
    let mut ends = [false; 4];
    let (gx, gy) = (&p.x.grid, &p.y.grid);
    let (sx, sy) = (p.x.scale, p.y.scale);
    let (wx, wy) = ((gx.stop - gx.start) / sx, (gy.stop - gy.start) / sy);
    let bounds = [gx.start / sx, gx.stop / sx, gy.start / sy, gy.stop / sy];
    for curve in p.printed.iter().flat_map(|f| &f.curves) {
        for (k, &end) in bounds.iter().enumerate() {
            let (width, other) = if k < 2 { (wx, wy) } else { (wy, wx) };
            let (lo, hi) = curve
                .points
                .iter()
                .map(|q| (q.x / sx, q.y / sy))
                .map(|(x, y)| if k < 2 { (x, y) } else { (y, x) })
                .filter(|(v, _)| (v - end).abs() <= ON_END * width.abs())
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), (_, w)| {
                    (a.min(w), b.max(w))
                });
            ends[k] |= hi - lo >= ALONG * other.abs();
        }
    }
    if let Some((zx, zy)) = inset_ranges(p).filter(|_| insets == Insets::Drawn) {
        for (k, v) in [zx.start, zx.end, zy.start, zy.end].into_iter().enumerate() {
            ends[k] |= (v - bounds[k]).abs() <= 1e-9 * (1.0 + v.abs());
        }
    }
    ends
}

/// How near an end of an axis (a share of it) a curve is drawn on its spine.
const ON_END: f64 = 0.03;
/// How much of the other axis (a share of it) a curve runs along a spine before the spine
/// moves off.
const ALONG: f64 = 0.05;

/// [`panel_ends`] of each panel, shared by the panels with the same axis (a row or column
/// of a figure keeps one range).
pub(super) fn clear_ends(fig: &MapFigure, insets: Insets) -> Vec<[bool; 4]> {
    let own: Vec<[bool; 4]> = fig.panels.iter().map(|p| panel_ends(p, insets)).collect();
    let same = |a: &MapPanel, b: &MapPanel, k: usize| {
        let (u, v) = if k < 2 { (&a.x, &b.x) } else { (&a.y, &b.y) };
        u.grid.start == v.grid.start && u.grid.stop == v.grid.stop && u.scale == v.scale
    };
    fig.panels
        .iter()
        .map(|p| {
            std::array::from_fn(|k| {
                fig.panels
                    .iter()
                    .zip(&own)
                    .any(|(q, e)| e[k] && same(p, q, k))
            })
        })
        .collect()
}

/// The strip left beyond a map at an end [`clear_ends`] picks, as a share of the axis.
const END_GAP: f64 = 0.03;

/// Colour of the marked parameter point.
const MARK: RGBColor = RGBColor(255, 0, 255);

/// Draw one map panel: merged row runs of equal count, fold curves (named where known),
/// cusps, the marked point, the inset where `insets` allows one. The legend is the figure's,
/// outside the panels. Returns the panel's chart, for marks drawn on top.
pub(super) fn draw_panel<'a, DB: Backend>(
    area: &'a DrawingArea<DB, Shift>,
    p: &MapPanel,
    ends: [bool; 4],
    insets: Insets,
) -> Result<MapChart<'a, DB>> {
    let (gx, gy) = (&p.x.grid, &p.y.grid);
    let (sx, sy) = (p.x.scale, p.y.scale);
    let xr = (gx.start / sx)..(gx.stop / sx);
    let yr = (gy.start / sy)..(gy.stop / sy);
    // the axes, with a strip beyond the map at the ends a curve or zoom box would sit on
    let gap = |r: &std::ops::Range<f64>, lo: bool, hi: bool| {
        let g = END_GAP * (r.end - r.start);
        (r.start - if lo { g } else { 0.0 })..(r.end + if hi { g } else { 0.0 })
    };
    let (ax, ay) = (gap(&xr, ends[0], ends[1]), gap(&yr, ends[2], ends[3]));
    let mut c = chart(
        area,
        &panel_title(p),
        ax.clone(),
        ay.clone(),
        &p.x.desc(),
        &p.y.desc(),
    )?;
    let (nx, ny) = (gx.count, gy.count);
    let hx = (gx.stop - gx.start) / (nx - 1) as f64 / sx;
    let hy = (gy.stop - gy.start) / (ny - 1) as f64 / sy;
    let clampx = |v: f64| v.clamp(xr.start, xr.end);
    let clampy = |v: f64| v.clamp(yr.start, yr.end);
    // the strip beyond the computed grid, where one is kept: light grey, no data
    let mut rects = vec![Rectangle::new(
        [(ax.start, ay.start), (ax.end, ay.end)],
        BEYOND.filled(),
    )];
    for iy in 0..ny {
        let y = gy.value(iy) / sy;
        let mut ix = 0;
        while ix < nx {
            let cnt = p.count(ix, iy);
            let mut jx = ix;
            while jx + 1 < nx && p.count(jx + 1, iy) == cnt {
                jx += 1;
            }
            // (the cells on the grid's edge end there, half a cell wide: nothing drawn past
            // the computed range, e.g. past λ = 1 or r = 1)
            let x0 = clampx(gx.value(ix) / sx - hx / 2.0);
            let x1 = clampx(gx.value(jx) / sx + hx / 2.0);
            let y0 = clampy(y - hy / 2.0);
            let y1 = clampy(y + hy / 2.0);
            rects.push(Rectangle::new(
                [(x0, y0), (x1, y1)],
                count_colour(cnt).filled(),
            ));
            ix = jx + 1;
        }
    }
    c.draw_series(rects).map_err(pe)?;
    // each fold on a white halo: red alone has the grey of the blue and green regions
    for curve in &p.folds.curves {
        let pts: Vec<(f64, f64)> = curve.points.iter().map(|q| (q.x / sx, q.y / sy)).collect();
        c.draw_series(LineSeries::new(pts.clone(), WHITE.stroke_width(stroke(4))))
            .map_err(pe)?;
        c.draw_series(LineSeries::new(pts, FOLD.stroke_width(stroke(2))))
            .map_err(pe)?;
    }
    for curve in p.printed.iter().flat_map(|f| &f.curves) {
        let pts: Vec<(f64, f64)> = curve.points.iter().map(|q| (q.x / sx, q.y / sy)).collect();
        // (long dashes on a black underlay, wider than a fold: apart from a fold it runs on)
        c.draw_series(DashedLineSeries::new(
            pts.clone(),
            pxi(14) as u32,
            pxi(8) as u32,
            BLACK.stroke_width(stroke(4)),
        ))
        .map_err(pe)?;
        c.draw_series(DashedLineSeries::new(
            pts,
            pxi(14) as u32,
            pxi(8) as u32,
            PRINTED.stroke_width(stroke(2)),
        ))
        .map_err(pe)?;
    }
    // the inset (and the outline of the box it zooms on) first: the names go beside them
    let mut taken: Vec<PixelBox> = Vec::new();
    {
        let drawn = match insets {
            Insets::Drawn => draw_inset(area, &mut c, p)?,
            Insets::Off => None,
        };
        if let Some((inset, zoom)) = drawn {
            taken.push(inset);
            // the zoom box's four edges (a name may sit inside the box, not on its outline)
            let t = pxi(3);
            taken.extend([
                [zoom[0], zoom[1] - t, zoom[2], zoom[1] + t],
                [zoom[0], zoom[3] - t, zoom[2], zoom[3] + t],
                [zoom[0] - t, zoom[1], zoom[0] + t, zoom[3]],
                [zoom[2] - t, zoom[1], zoom[2] + t, zoom[3]],
            ]);
        }
    }
    let mark = |x: f64, y: f64, r: i32| {
        let (x, y) = c.backend_coord(&(x, y));
        [x - r, y - r, x + r, y + r]
    };
    taken.extend(
        p.folds
            .cusps
            .iter()
            .map(|q| mark(q.x / sx, q.y / sy, pxi(8))),
    );
    if let Some((mx, my, _)) = &p.mark {
        taken.push(mark(mx / sx, my / sy, pxi(9)));
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
    let plot = [rx.start, ry.start, rx.end, ry.end];
    let (bx, by) = area.get_base_pixel();
    // the grid's first and last points in pixels: a pixel's nearest grid cell
    let (gx, gy) = (&p.x.grid, &p.y.grid);
    let first = c.backend_coord(&(gx.start / sx, gy.start / sy));
    let last = c.backend_coord(&(gx.stop / sx, gy.stop / sy));
    let cell = |px_: i32, py: i32| {
        let at = |v: i32, a: i32, b: i32, n: usize| {
            let f = f64::from(v - a) / f64::from(b - a) * (n - 1) as f64;
            (f >= -0.5 && f <= n as f64 - 0.5).then(|| f.round().max(0.0) as usize)
        };
        Some((
            at(px_, first.0, last.0, gx.count)?,
            at(py, first.1, last.1, gy.count)?,
        ))
    };
    let shares: Vec<f64> = (0..5).map(|k| p.share(k)).collect();
    let minority = |b: &PixelBox| {
        (0..5)
            .flat_map(|i| (0..3).map(move |j| (i, j)))
            .filter_map(|(i, j)| cell(b[0] + (b[2] - b[0]) * i / 4, b[1] + (b[3] - b[1]) * j / 2))
            .filter(|&(ix, iy)| shares[(p.count(ix, iy) as usize).min(4)] < MINORITY)
            .count() as u64
    };
    for (i, name) in display_names(p) {
        let curve: Vec<(i32, i32)> = p.folds.curves[i]
            .points
            .iter()
            .map(|q| c.backend_coord(&(q.x / sx, q.y / sy)))
            .collect();
        let name = name.as_str();
        let Some([x0, y0, x1, y1]) = place_name(name, &curve, &fold_px, &taken, plot, &minority)
        else {
            continue;
        };
        taken.push([x0, y0, x1, y1]);
        // on a white box: red on green, blue or black is hard to read
        area.draw(&Rectangle::new(
            [(x0 - bx, y0 - by), (x1 - bx, y1 - by)],
            WHITE.mix(0.85).filled(),
        ))
        .map_err(pe)?;
        rich_text(
            area,
            name,
            ((x0 + x1) / 2 - bx, (y0 + y1) / 2 - by),
            Pos::new(HPos::Center, VPos::Center),
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
    Ok(c)
}

/// A box in backend pixels: left, top, right, bottom.
type PixelBox = [i32; 4];

/// The short name a fold is labelled with on the map ("L1"); the legend says what it means.
fn short_name(name: &str) -> &str {
    name.split_whitespace().next().unwrap_or(name)
}

/// The names drawn beside a panel's fold curves: the short name ("L1"), a second curve of
/// the same name primed ("L1′"), a third double-primed, so that no two curves of a panel
/// carry one name; of two curves of one name the one higher up (mean y) is unprimed, the
/// same in every panel.
fn display_names(p: &MapPanel) -> Vec<(usize, String)> {
    let mean_y = |i: usize| {
        let pts = &p.folds.curves[i].points;
        pts.iter().map(|q| q.y).sum::<f64>() / pts.len().max(1) as f64
    };
    let mut order: Vec<&(usize, String)> = p.fold_names.iter().collect();
    order.sort_by(|a, b| mean_y(b.0).total_cmp(&mean_y(a.0)));
    let mut seen: Vec<&str> = Vec::new();
    order
        .into_iter()
        .map(|(i, name)| {
            let short = short_name(name);
            let primes = seen.iter().filter(|&&n| n == short).count();
            seen.push(short);
            (*i, format!("{short}{}", "′".repeat(primes)))
        })
        .collect()
}

/// The caption's key to a map figure's drawing: what the insets' axes are, and why two
/// fold curves of a panel share a name (primed on the picture).
fn map_key(fig: &MapFigure) -> Vec<String> {
    let mut key = Vec::new();
    if fig.panels.iter().any(|p| inset_ranges(p).is_some()) {
        key.push(
            "inset: the box outlined on its panel enlarged, on the panel's own axes and units \
             (its x axis the panel's x, its y axis the panel's y; an axis marked ×10ᵉ under \
             its labels is in units of 10ᵉ), joined to the box by two leader lines"
                .to_string(),
        );
    }
    if fig
        .panels
        .iter()
        .any(|p| p.what != What::Rhythmicity && inset_ranges(p).is_some())
    {
        key.push(
            "in the inset of a map of modes, each square is one point of the computed grid              (its colour: that point's number of modes), with white between them; the fold              curve is computed exactly and runs between the grid's points"
                .to_string(),
        );
    }
    if fig
        .panels
        .iter()
        .any(|p| display_names(p).iter().any(|(_, n)| n.contains('′')))
    {
        key.push(
            "L1 and L1′ (likewise L2′, L3′): two saddle-node lines of one panel named after the \
             same cycle, each by the cycles present at its middle (L1: no larger cycle there, \
             the outer cycle's fold); the prime tells the two lines apart, L1 the higher one"
                .to_string(),
        );
    }
    if clear_ends(fig, Insets::Drawn)
        .iter()
        .any(|e| e.iter().any(|&b| b))
    {
        key.push(
            "light grey: the narrow strip between the computed grid and the axis, no data \
             (kept so that no curve lies on a spine)"
                .to_string(),
        );
    }
    key
}

/// A region covering less than this share of its panel (per cent) is one a name must not
/// cover (Figs 3 and 6: the trirhythmic wedge).
const MINORITY: f64 = 10.0;

/// Where the name of a fold curve (`curve`, backend pixels) goes: a box beside one of its
/// points (from its middle outwards), on the side that covers no point of any fold curve
/// (`folds`), no box `taken` (the inset, the zoom box's edges, marks, other names), the
/// fewest cells of a small region (`minority`: of 15 sample points in the box, those on a
/// region under [`MINORITY`] per cent of the panel) and stays inside the plotting area
/// `plot`; the one nearest the curve's middle among the best. None for a curve too short to
/// name (under two names' widths long).
fn place_name(
    name: &str,
    curve: &[(i32, i32)],
    folds: &[(i32, i32)],
    taken: &[PixelBox],
    plot: PixelBox,
    minority: &dyn Fn(&PixelBox) -> u64,
) -> Option<PixelBox> {
    let w = rich_width(name, LABEL) as i32 + pxi(8);
    let h = font_px(LABEL) as i32 * 5 / 4;
    let span = |a: (i32, i32), b: (i32, i32)| {
        (((a.0 - b.0) as f64).powi(2) + ((a.1 - b.1) as f64).powi(2)).sqrt()
    };
    let length: f64 = curve.windows(2).map(|s| span(s[0], s[1])).sum();
    if curve.len() < 2 || length < 2.0 * w as f64 {
        return None;
    }
    let gap = pxi(3);
    let overlaps =
        |a: &PixelBox, b: &PixelBox| a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3];
    let mut best: Option<(u64, PixelBox)> = None;
    // anchors from the middle outwards: 1/2, 2/5, 3/5, 3/10, 7/10, …
    for (rank, tenth) in [5usize, 4, 6, 3, 7, 2, 8, 1, 9].into_iter().enumerate() {
        let (x, y) = curve[(curve.len() - 1) * tenth / 10];
        let places = [
            (x + gap, y - h / 2),
            (x - gap - w, y - h / 2),
            (x - w / 2, y - gap - h),
            (x - w / 2, y + gap),
            (x + gap, y - gap - h),
            (x + gap, y + gap),
            (x - gap - w, y - gap - h),
            (x - gap - w, y + gap),
        ];
        for (side, &(l, t)) in places.iter().enumerate() {
            let b = [l, t, l + w, t + h];
            let outside = b[0] < plot[0] || b[2] > plot[2] || b[1] < plot[1] || b[3] > plot[3];
            let hits = folds
                .iter()
                .filter(|&&(px_, py)| {
                    px_ >= b[0] - 2 && px_ <= b[2] + 2 && py >= b[1] - 2 && py <= b[3] + 2
                })
                .count() as u64;
            let blocked = taken.iter().filter(|o| overlaps(o, &b)).count() as u64;
            let cost = 1_000_000 * u64::from(outside)
                + 10_000 * blocked
                + 1_000 * hits
                + 1_000 * minority(&b)
                + 8 * rank as u64
                + side as u64;
            if best.is_none_or(|(c, _)| cost < c) {
                best = Some((cost, b));
            }
        }
    }
    best.map(|(_, b)| b)
}

/// A panel's title: its label and caption, and for a panel of stable cycles the shares of
/// the grid with one, two and three cycles (per cent, one decimal; a share the grid does not
/// meet is left out, one under 0.05 % reads "< 0.1 %"; the caption names all three).
fn panel_title(p: &MapPanel) -> String {
    let title = format!("({}) {}", p.label, p.caption);
    if p.what != What::Rhythmicity {
        return title;
    }
    let shares: Vec<String> = [(1, "mono"), (2, "bi"), (3, "tri")]
        .into_iter()
        .filter(|&(k, _)| p.share(k) > 0.0)
        .map(|(k, name)| match p.share(k) {
            s if s < 0.05 => format!("{name} <\u{a0}0.1\u{a0}%"),
            s => format!("{name} {s:.1}\u{a0}%"),
        })
        .collect();
    format!("{title}: {}", shares.join(", "))
}

/// The largest share of the plane (per cent) the trirhythmic region may cover and still be
/// zoomed on in an inset.
const INSET_BELOW: f64 = 20.0;
/// The inset's size as a fraction of the plotting area's width and height (a larger one
/// would hide curves of the panel; where four decimal x tick labels do not fit, they are
/// written in units of a power of ten).
fn inset_fraction(_p: &MapPanel) -> (f64, f64) {
    (0.5, 0.5)
}

/// The data ranges (display units) an inset zooms on: on a map of stable cycles, the bounding
/// box of the trirhythmic cells (where they cover at most [`INSET_BELOW`] % of the plane); on
/// a map of modes, the largest thin region ([`MapPanel::slivers`]: a band under
/// [`SLIVER`] of an axis, of at least a thousandth of the grid), which the plane's scale shows
/// as a line. Padded by a tenth of its size and at least one cell on each side (a band by
/// twice its width, so that what borders it shows), within the plane.
fn inset_ranges(p: &MapPanel) -> Option<(std::ops::Range<f64>, std::ops::Range<f64>)> {
    let (((ix0, ix1), (iy0, iy1)), pad_cells) = if p.what == What::Rhythmicity {
        if p.share(3) == 0.0 || p.share(3) > INSET_BELOW {
            return None;
        }
        (p.bounding_box(3)?, 1.0)
    } else {
        let min_cells = (p.counts.len() / 1000).max(8);
        let (_, b) = p.slivers(min_cells, SLIVER).into_iter().next()?;
        (b, 2.0)
    };
    let zoom = |g: &trirhythm::theory::bifurcation::Axis, s: f64, i0: usize, i1: usize| {
        let h = (g.stop - g.start) / (g.count - 1) as f64 / s;
        let (a, b) = (g.value(i0) / s - h / 2.0, g.value(i1) / s + h / 2.0);
        let thin = (i1 + 1 - i0) as f64 <= SLIVER * g.count as f64;
        let pad = if thin && pad_cells > 1.0 {
            pad_cells * (b - a)
        } else {
            (0.1 * (b - a)).max(h)
        };
        let (lo, hi) = (g.start / s, g.stop / s);
        (a - pad).max(lo)..(b + pad).min(hi)
    };
    // (an inset's x axis on a map of stable cycles takes in four whole steps of its decade,
    // widened downward then upward within the plane: at least four labelled ticks)
    let mut zx = zoom(&p.x.grid, p.x.scale, ix0, ix1);
    if p.what == What::Rhythmicity {
        let (lo, hi) = (p.x.grid.start / p.x.scale, p.x.grid.stop / p.x.scale);
        let step = 10f64.powf((zx.end - zx.start).log10().floor());
        let count = |r: &std::ops::Range<f64>| {
            ((r.end / step).floor() - (r.start / step).ceil() + 1.0) as i64
        };
        if step.is_finite() && step > 0.0 && count(&zx) < 4 {
            zx.start = ((zx.start / step).floor() * step - 0.1 * step).max(lo);
            if count(&zx) < 4 {
                zx.end = ((zx.end / step).ceil() * step + 0.1 * step).min(hi);
            }
        }
    }
    let zy = zoom(&p.y.grid, p.y.scale, iy0, iy1);
    // an inset only where it enlarges: by MAGNIFY or more along one axis and by at least
    // KEEP along the other (its plotting area taken as INSET_PLOT of its share of the panel)
    let (fx, fy) = inset_fraction(p);
    let scale = |r: &std::ops::Range<f64>, g: &trirhythm::theory::bifurcation::Axis, s: f64, f| {
        f * INSET_PLOT * (g.stop - g.start).abs() / s / (r.end - r.start)
    };
    let (mx, my) = (
        scale(&zx, &p.x.grid, p.x.scale, fx),
        scale(&zy, &p.y.grid, p.y.scale, fy),
    );
    (mx.max(my) >= MAGNIFY && mx.min(my) >= KEEP).then_some((zx, zy))
}

/// The least enlargement of an inset along its more enlarged axis (an inset that would show
/// its box at about the size it has on the panel is not drawn).
const MAGNIFY: f64 = 1.5;
/// The least scale of an inset along its other axis (a thin box enlarged across its length
/// may be drawn a little shorter along it).
const KEEP: f64 = 0.75;
/// The share of an inset's width and height its plotting area takes (the rest: tick labels).
const INSET_PLOT: f64 = 0.75;

/// The side of a grid point's cell in the inset of a map of modes, as a fraction of the
/// grid's spacing, along an axis where the cells are large.
const SAMPLE: f64 = 0.6;

/// The largest extent (fraction of an axis) of a region an inset enlarges on a map of modes.
const SLIVER: f64 = 0.02;

pub(super) type MapChart<'a, DB> =
    ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// Draw the inset zooming on the trirhythmic region (where [`inset_ranges`] gives one): the
/// zoomed box outlined on the panel, the inset where in the plotting area its cover hides the
/// least (a corner where one hides as little as any other place). Returns the inset's box and the zoomed box (backend pixels).
fn draw_inset<DB: Backend>(
    area: &DrawingArea<DB, Shift>,
    c: &mut MapChart<'_, DB>,
    p: &MapPanel,
) -> Result<Option<(PixelBox, PixelBox)>> {
    let Some((zx, zy)) = inset_ranges(p) else {
        return Ok(None);
    };
    let (rx, ry) = c.plotting_area().get_pixel_range();
    let (iw, ih) = (
        ((rx.end - rx.start) as f64 * inset_fraction(p).0) as i32,
        ((ry.end - ry.start) as f64 * inset_fraction(p).1) as i32,
    );
    let gap = pxi(6);
    // the corners first, then every position on a grid of eighths of the free room (a corner
    // wins a tie)
    let (free_x, free_y) = (
        rx.end - rx.start - iw - 2 * gap,
        ry.end - ry.start - ih - 2 * gap,
    );
    let places: Vec<(i32, i32)> = [(8, 0), (0, 0), (8, 8), (0, 8)]
        .into_iter()
        .chain((0..=8).flat_map(|i| (0..=8).map(move |j| (i, j))))
        .map(|(i, j)| {
            (
                rx.start + gap + free_x * i / 8,
                ry.start + gap + free_y * j / 8,
            )
        })
        .collect();
    let zoom_box = [
        c.backend_coord(&(zx.start, zy.end)),
        c.backend_coord(&(zx.end, zy.start)),
    ];
    let Some(&(ax, ay)) = places
        .iter()
        .min_by_key(|&&corner| cover_cost(c, p, corner, (iw, ih), zoom_box))
    else {
        return Ok(None);
    };
    // the zoomed box on the panel: white on a black rim, seen on every colour of the map
    // and on the white beyond it
    for (colour, width) in [(BLACK, stroke(4)), (WHITE, stroke(2))] {
        c.draw_series(std::iter::once(Rectangle::new(
            [(zx.start, zy.start), (zx.end, zy.end)],
            colour.stroke_width(width),
        )))
        .map_err(pe)?;
    }
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
    // on a map of modes the grid's points with white between them along an axis where a
    // cell is large in the inset (the fold curve is exact and runs between the points; whole
    // cells would read as its position)
    let part = |h: f64, r: &std::ops::Range<f64>| {
        if p.what != What::Rhythmicity && h > (r.end - r.start) / 30.0 {
            SAMPLE
        } else {
            1.0
        }
    };
    let (fx, fy) = (part(hx, &zx), part(hy, &zy));
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
                    (cx(x - fx * hx / 2.0), cy(y - fy * hy / 2.0)),
                    (cx(x + fx * hx / 2.0), cy(y + fy * hy / 2.0)),
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
    let printed = SeriesStyle {
        colour: PRINTED,
        dash: Dash::Dashed,
        marker: Marker::None,
    };
    for curve in p.printed.iter().flat_map(|f| &f.curves) {
        let pts: Vec<(f64, f64)> = curve.points.iter().map(|q| (q.x / sx, q.y / sy)).collect();
        draw_line(&z, &pts, printed, 2)?;
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
    let [a, b] = zoom_box;
    let zoomed = [a.0.min(b.0), a.1.min(b.1), a.0.max(b.0), a.1.max(b.1)];
    let framed = [ax, ay, ax + iw, ay + ih];
    // two leader lines from the zoomed box to the inset's facing corners (white on a black
    // rim, as the box), so a thin box is found at once
    for (from, to) in leaders(zoomed, framed) {
        for (colour, width) in [(BLACK, stroke(3)), (WHITE, stroke(1))] {
            area.draw(&PathElement::new(
                [(from.0 - bx, from.1 - by), (to.0 - bx, to.1 - by)],
                colour.stroke_width(width),
            ))
            .map_err(pe)?;
        }
    }
    Ok(Some((framed, zoomed)))
}

/// The leader lines from a zoomed box to its inset (boxes `[left, top, right, bottom]`,
/// pixels): from the box's side that faces the inset to the inset's facing side, corner to
/// corner (below or above where the inset clears the box vertically, else beside it).
fn leaders(zoomed: PixelBox, inset: PixelBox) -> [((i32, i32), (i32, i32)); 2] {
    let [zl, zt, zr, zb] = zoomed;
    let [il, it, ir, ib] = inset;
    if it >= zb {
        [((zl, zb), (il, it)), ((zr, zb), (ir, it))]
    } else if ib <= zt {
        [((zl, zt), (il, ib)), ((zr, zt), (ir, ib))]
    } else if il >= zr {
        [((zr, zt), (il, it)), ((zr, zb), (il, ib))]
    } else {
        [((zl, zt), (ir, it)), ((zl, zb), (ir, ib))]
    }
}

/// What an inset at `corner` (backend pixels, top left) of `size` would hide on the panel:
/// the zoomed box, cusps and the marked point weigh most, then (on a map of stable cycles)
/// trirhythmic cells, then fold curves and printed curves, then cells of a count other than
/// the place's commonest (a uniform place hides least).
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
    // (the trirhythmic cells an inset of a map of stable cycles enlarges)
    let enlarged = if p.what == What::Rhythmicity {
        counts[3]
    } else {
        0
    };
    let mut cost = 1000 * enlarged + (inside - commonest);
    let overlaps = |[a, b]: [(i32, i32); 2]| {
        a.0.max(b.0) >= corner.0
            && a.0.min(b.0) <= corner.0 + w
            && a.1.max(b.1) >= corner.1
            && a.1.min(b.1) <= corner.1 + h
    };
    if overlaps(zoom_box) {
        cost += 1_000_000;
    }
    for curve in p
        .folds
        .curves
        .iter()
        .chain(p.printed.iter().flat_map(|f| &f.curves))
    {
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
    if let Some((mx, my, _)) = &p.mark {
        if hit(c.backend_coord(&(mx / sx, my / sy))) {
            cost += 100_000;
        }
    }
    cost
}
