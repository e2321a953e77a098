//! Series told apart in colour and in greyscale: the Okabe–Ito palette ([`PALETTE`]), a dash
//! and a marker per series ([`series`]), and the drawing of dashed, clipped lines and markers
//! in a chart ([`draw_line`], [`draw_markers`]), scaled with the canvas ([`super::plot`]).
//! Tested below (series differ in dash and marker, dashes cover their share, clipping).

use super::plot::{pe, px, pxi, Backend};
use anyhow::Result;
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;

/// Line colours for several curves in one panel: the Okabe–Ito colour-blind-safe palette
/// without its yellow (black, vermillion, blue, bluish green, orange, reddish purple, sky
/// blue). Pair a colour with a dash or marker ([`series`]) so curves also part in greyscale.
pub const PALETTE: [RGBColor; 7] = [
    RGBColor(0, 0, 0),
    RGBColor(213, 94, 0),
    RGBColor(0, 114, 178),
    RGBColor(0, 158, 115),
    RGBColor(230, 159, 0),
    RGBColor(204, 121, 167),
    RGBColor(86, 180, 233),
];

/// A line's dash pattern.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum Dash {
    /// Unbroken.
    Solid,
    /// Long dashes.
    Dashed,
    /// Dots.
    Dotted,
    /// Dash, dot (chain line).
    Chain,
}

impl Dash {
    /// On/off lengths in pixels at scale 1 (empty: solid).
    fn pattern(self) -> &'static [u32] {
        match self {
            Dash::Solid => &[],
            Dash::Dashed => &[10, 6],
            Dash::Dotted => &[3, 5],
            Dash::Chain => &[11, 5, 3, 5],
        }
    }
}

/// A point marker.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum Marker {
    /// None.
    None,
    /// An open circle.
    Circle,
    /// An open square.
    Square,
    /// An open upward triangle.
    Triangle,
    /// An open diamond.
    Diamond,
    /// A diagonal cross.
    Cross,
    /// An upright cross.
    Plus,
}

/// How one series of a panel is drawn: colour, dash and marker.
#[derive(Clone, Copy, PartialEq, Debug)]
pub struct SeriesStyle {
    /// The colour (from [`PALETTE`]).
    pub colour: RGBColor,
    /// The line's dash pattern.
    pub dash: Dash,
    /// The marker of its points (drawn by [`draw_markers`]).
    pub marker: Marker,
}

const DASHES: [Dash; 4] = [Dash::Solid, Dash::Dashed, Dash::Dotted, Dash::Chain];
const MARKERS: [Marker; 6] = [
    Marker::Circle,
    Marker::Cross,
    Marker::Square,
    Marker::Triangle,
    Marker::Diamond,
    Marker::Plus,
];

/// The style of series `i` of a panel: colour `PALETTE[i]`, dash cycling solid, dashed,
/// dotted, dash-dot, marker cycling circle, cross, square, triangle, diamond, plus. Any two
/// of the first four series differ in dash and of the first six in marker, so they part in
/// greyscale too.
pub fn series(i: usize) -> SeriesStyle {
    SeriesStyle {
        colour: PALETTE[i % PALETTE.len()],
        dash: DASHES[i % DASHES.len()],
        marker: MARKERS[i % MARKERS.len()],
    }
}

/// A line width designed at scale 1, at the current scale.
pub fn stroke(base: u32) -> u32 {
    px(base).max(1)
}

/// Draw a polyline in pixels of `area` with a dash pattern (the pattern runs on across
/// vertices).
pub(super) fn dashed_path<DB: Backend>(
    area: &DrawingArea<DB, Shift>,
    pts: &[(i32, i32)],
    dash: Dash,
    colour: RGBColor,
    width: u32,
) -> Result<()> {
    let style = colour.stroke_width(width);
    for piece in dash_pieces(pts, dash) {
        area.draw(&PathElement::new(piece, style)).map_err(pe)?;
    }
    Ok(())
}

/// The visible pieces of a polyline under a dash pattern (pixels; pattern lengths scaled).
fn dash_pieces(pts: &[(i32, i32)], dash: Dash) -> Vec<Vec<(i32, i32)>> {
    let pattern: Vec<f64> = dash
        .pattern()
        .iter()
        .map(|&l| px(l).max(1) as f64)
        .collect();
    if pattern.is_empty() {
        return vec![pts.to_vec()];
    }
    let mut pieces = Vec::new();
    let mut cur: Vec<(i32, i32)> = Vec::new();
    let (mut k, mut left) = (0usize, pattern[0]);
    let round = |x: f64, y: f64| (x.round() as i32, y.round() as i32);
    for w in pts.windows(2) {
        let (a, b) = (
            (w[0].0 as f64, w[0].1 as f64),
            (w[1].0 as f64, w[1].1 as f64),
        );
        let len = ((b.0 - a.0).powi(2) + (b.1 - a.1).powi(2)).sqrt();
        let mut t = 0.0;
        let on = |k: usize| k % 2 == 0;
        if on(k) && cur.is_empty() {
            cur.push(round(a.0, a.1));
        }
        while len - t > left {
            t += left;
            let p = round(a.0 + (b.0 - a.0) * t / len, a.1 + (b.1 - a.1) * t / len);
            if on(k) {
                cur.push(p);
                pieces.push(std::mem::take(&mut cur));
            } else {
                cur = vec![p];
            }
            k = (k + 1) % pattern.len();
            left = pattern[k];
        }
        left -= len - t;
        if on(k) {
            cur.push(round(b.0, b.1));
        }
    }
    if cur.len() > 1 {
        pieces.push(cur);
    }
    pieces
}

/// Clip the segment a–b to the rectangle `[x0, x1] × [y0, y1]` (Liang–Barsky).
fn clip(
    a: (f64, f64),
    b: (f64, f64),
    (x0, x1, y0, y1): (f64, f64, f64, f64),
) -> Option<((f64, f64), (f64, f64))> {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (p, q) in [
        (-dx, a.0 - x0),
        (dx, x1 - a.0),
        (-dy, a.1 - y0),
        (dy, y1 - a.1),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
        } else {
            let r = q / p;
            if p < 0.0 {
                t0 = t0.max(r);
            } else {
                t1 = t1.min(r);
            }
        }
    }
    (t0 <= t1).then_some({
        (
            (a.0 + t0 * dx, a.1 + t0 * dy),
            (a.0 + t1 * dx, a.1 + t1 * dy),
        )
    })
}

/// Draw `points` (data coordinates) as a line in `style`'s colour and dash, `width` pixels
/// at scale 1, clipped to the plotting area (points that are not finite break the line).
pub fn draw_line<DB: Backend>(
    chart: &ChartContext<'_, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    points: &[(f64, f64)],
    style: SeriesStyle,
    width: u32,
) -> Result<()> {
    let plot = chart.plotting_area();
    let (rx, ry) = plot.get_pixel_range();
    let area = plot.strip_coord_spec();
    let (bx, by) = (rx.start, ry.start);
    let rect = (
        0.0,
        (rx.end - rx.start) as f64,
        0.0,
        (ry.end - ry.start) as f64,
    );
    // pixel positions, unrounded, of the finite points; runs broken at the others
    let mut runs: Vec<Vec<(f64, f64)>> = vec![Vec::new()];
    for &(x, y) in points {
        if x.is_finite() && y.is_finite() {
            let (px_, py_) = plot.map_coordinate(&(x, y));
            runs.last_mut()
                .expect("one run")
                .push(((px_ - bx) as f64, (py_ - by) as f64));
        } else if !runs.last().expect("one run").is_empty() {
            runs.push(Vec::new());
        }
    }
    for run in runs {
        // the clipped pieces, joined while consecutive
        let mut pieces: Vec<Vec<(i32, i32)>> = Vec::new();
        let mut joined = false;
        for w in run.windows(2) {
            match clip(w[0], w[1], rect) {
                Some((a, b)) => {
                    let (a, b) = (
                        (a.0.round() as i32, a.1.round() as i32),
                        (b.0.round() as i32, b.1.round() as i32),
                    );
                    if joined {
                        pieces.last_mut().expect("joined").push(b);
                    } else {
                        pieces.push(vec![a, b]);
                    }
                    joined = b == (w[1].0.round() as i32, w[1].1.round() as i32);
                }
                None => joined = false,
            }
        }
        for piece in pieces {
            dashed_path(&area, &piece, style.dash, style.colour, stroke(width))?;
        }
    }
    Ok(())
}

/// Draw a marker centred at `m` (pixels of `area`).
pub(super) fn marker<DB: Backend>(
    area: &DrawingArea<DB, Shift>,
    m: (i32, i32),
    marker: Marker,
    colour: RGBColor,
) -> Result<()> {
    let r = pxi(4);
    let st = colour.stroke_width(stroke(1));
    let poly = |pts: Vec<(i32, i32)>| area.draw(&PathElement::new(pts, st)).map_err(pe);
    match marker {
        Marker::None => Ok(()),
        Marker::Circle => area.draw(&Circle::new(m, r as u32, st)).map_err(pe),
        Marker::Square => poly(vec![
            (m.0 - r, m.1 - r),
            (m.0 + r, m.1 - r),
            (m.0 + r, m.1 + r),
            (m.0 - r, m.1 + r),
            (m.0 - r, m.1 - r),
        ]),
        Marker::Triangle => poly(vec![
            (m.0, m.1 - r - r / 4),
            (m.0 + r, m.1 + r * 3 / 4),
            (m.0 - r, m.1 + r * 3 / 4),
            (m.0, m.1 - r - r / 4),
        ]),
        Marker::Diamond => poly(vec![
            (m.0, m.1 - r - r / 4),
            (m.0 + r, m.1),
            (m.0, m.1 + r + r / 4),
            (m.0 - r, m.1),
            (m.0, m.1 - r - r / 4),
        ]),
        Marker::Cross => area.draw(&Cross::new(m, r as u32, st)).map_err(pe),
        Marker::Plus => {
            poly(vec![(m.0 - r, m.1), (m.0 + r, m.1)])?;
            poly(vec![(m.0, m.1 - r), (m.0, m.1 + r)])
        }
    }
}

/// Draw `style`'s marker at each of `points` (data coordinates) inside the plotting area.
pub fn draw_markers<DB: Backend>(
    chart: &ChartContext<'_, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    points: &[(f64, f64)],
    style: SeriesStyle,
) -> Result<()> {
    let plot = chart.plotting_area();
    let (rx, ry) = plot.get_pixel_range();
    let area = plot.strip_coord_spec();
    for &(x, y) in points.iter().filter(|p| p.0.is_finite() && p.1.is_finite()) {
        let (px_, py_) = plot.map_coordinate(&(x, y));
        if rx.contains(&px_) && (ry.start..=ry.end).contains(&py_) {
            marker(
                &area,
                (px_ - rx.start, py_ - ry.start),
                style.marker,
                style.colour,
            )?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn series_part_in_dash_and_marker() {
        for i in 0..4 {
            for j in 0..i {
                assert_ne!(series(i).dash, series(j).dash);
                assert_ne!(series(i).colour, series(j).colour);
            }
        }
        for i in 0..6 {
            for j in 0..i {
                assert_ne!(series(i).marker, series(j).marker);
            }
        }
        // no Okabe–Ito yellow (240, 228, 66) on white
        assert!(!PALETTE.contains(&RGBColor(240, 228, 66)));
    }

    #[test]
    fn dashes_cover_the_pattern_share_of_a_line() {
        let line = [(0, 0), (100, 0), (100, 100)];
        let on: f64 = dash_pieces(&line, Dash::Dashed)
            .iter()
            .flat_map(|p| {
                p.windows(2)
                    .map(|w| ((w[1].0 - w[0].0).abs() + (w[1].1 - w[0].1).abs()) as f64)
            })
            .sum();
        // 10 on, 6 off at scale 1: 200 px drawn 10/16 on, within a dash
        assert!((on - 200.0 * 10.0 / 16.0).abs() <= 10.0, "{on}");
        assert_eq!(dash_pieces(&line, Dash::Solid), vec![line.to_vec()]);
    }

    #[test]
    fn clipping_keeps_the_inside_part() {
        let r = (0.0, 10.0, 0.0, 10.0);
        assert_eq!(
            clip((-5.0, 5.0), (5.0, 5.0), r),
            Some(((0.0, 5.0), (5.0, 5.0)))
        );
        assert_eq!(clip((-5.0, -5.0), (-1.0, 20.0), r), None);
    }
}
