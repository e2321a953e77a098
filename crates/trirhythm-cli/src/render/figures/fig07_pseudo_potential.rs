//! Fig. 7: the pseudo-potential U_eff(A0) (Eq. 23) for several r (a) and several λ (b), each
//! with a second panel below it zoomed on the inner well.
//!
//! Rendering only: the data and its computation are [`trirhythm_paper::fig07_pseudo_potential`].

use super::lle::outline;
use crate::render::plot::{
    chart, draw_line, framed, padded_range, pe, pxi, series, stroke, Backend, ChartSize,
    LegendStrip, Marker, SeriesStyle, Symbol,
};
use anyhow::Result;
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::ops::Range;
use trirhythm::theory::averaging::Extremum;
use trirhythm_paper::fig07_pseudo_potential::{Curve, Fig07, Panel};

/// A y-range framing the extrema of `curves` that lie below `x_end` (the walls of U_eff at
/// A → 0 and A → ∞ would otherwise flatten everything), and the curves' points inside it.
pub(super) fn frame(curves: &[Curve], x_end: f64) -> (std::ops::Range<f64>, Vec<Curve>) {
    frame_with(curves, x_end, 0.6, false)
}

/// [`frame`] with room `above` the extrema (a share of their span), and, `to_lowest`, down
/// to just below the lowest point of a curve drawn instead of a share below the extrema.
fn frame_with(
    curves: &[Curve],
    x_end: f64,
    above: f64,
    to_lowest: bool,
) -> (std::ops::Range<f64>, Vec<Curve>) {
    let levels = curves
        .iter()
        .flat_map(|c| c.extrema.iter())
        .filter(|e| e.amplitude <= x_end)
        .map(|e| e.potential);
    let (lo, hi) = levels.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
        (a.min(v), b.max(v))
    });
    // (down to the lowest point of a curve drawn, which may lie below every extremum at the
    // zoom's end)
    let lowest = curves
        .iter()
        .flat_map(|c| c.points.iter())
        .filter(|p| p.0 <= x_end)
        .map(|p| p.1)
        .fold(lo, f64::min);
    let span = (hi - lo).max(1e-9);
    let bottom = if to_lowest {
        lowest - 0.06 * span
    } else {
        lo - 0.3 * span
    };
    let y = padded_range([bottom, hi + above * span]);
    let clipped = clip(curves, &(f64::NEG_INFINITY..x_end), &y);
    (y, clipped)
}

/// The curves with only their points inside the window `x` × `y` (A0 up to and including
/// `x.end`).
fn clip(curves: &[Curve], x: &Range<f64>, y: &Range<f64>) -> Vec<Curve> {
    curves
        .iter()
        .map(|c| Curve {
            label: c.label.clone(),
            points: c
                .points
                .iter()
                .copied()
                .filter(|p| p.0 >= x.start && p.0 <= x.end && y.contains(&p.1))
                .collect(),
            extrema: c.extrema.clone(),
        })
        .collect()
}

/// The radius of the extrema's markers (before scaling).
pub(super) const MARKER: i32 = 5;
/// The radius of the markers in the enlargements, where neighbouring extrema lie close.
const ZOOM_MARKER: i32 = 4;

/// The style of curve `i` of a panel: [`series`] colour and dash, no marker (the markers
/// are the extrema).
pub(super) fn curve_style(i: usize) -> SeriesStyle {
    SeriesStyle {
        marker: Marker::None,
        ..series(i)
    }
}

/// The marker shape of curve `i`'s extrema (apart in greyscale).
fn shape(i: usize) -> Marker {
    [
        Marker::Circle,
        Marker::Square,
        Marker::Triangle,
        Marker::Diamond,
    ][i % 4]
}

/// Draw curves (each in [`curve_style`]) with their wells (filled) and crests (open) marked,
/// each curve's in its own shape.
pub(super) fn draw_curves<'a, DB: Backend + 'a>(
    c: &mut ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    curves: &[Curve],
    radius: i32,
) -> Result<()> {
    let y = c.y_range();
    let x = c.x_range();
    for (i, cv) in curves.iter().enumerate() {
        let style = curve_style(i);
        let color = style.colour;
        draw_line(c, &cv.points, style, 2)?;
        // (the rest state A0 = 0 is no cycle: left unmarked, see [`key`])
        let inside = |e: &&Extremum| {
            e.amplitude > 0.0 && x.contains(&e.amplitude) && y.contains(&e.potential)
        };
        let ring = outline(shape(i), pxi(radius));
        c.draw_series(cv.extrema.iter().filter(inside).map(|e| {
            let fill = if e.minimum {
                color.filled()
            } else {
                WHITE.filled()
            };
            EmptyElement::at((e.amplitude, e.potential))
                + Polygon::new(ring.clone(), fill)
                + PathElement::new(ring.clone(), color.stroke_width(stroke(2)))
        }))
        .map_err(pe)?;
    }
    Ok(())
}

/// A panel's legend, in a strip below it: each curve's colour, dash and marker with its
/// label, and what filled and open markers mean.
fn legend_of(panel: &Panel) -> LegendStrip {
    let mut entries: Vec<(Symbol, String)> = panel
        .curves
        .iter()
        .enumerate()
        .map(|(i, cv)| {
            let style = SeriesStyle {
                marker: shape(i),
                ..curve_style(i)
            };
            (Symbol::Series(style), cv.label.clone())
        })
        .collect();
    let black = RGBColor(0, 0, 0);
    entries.push((Symbol::Dot(black), "filled: well (stable cycle)".into()));
    entries.push((Symbol::Ring(black), "open: crest (unstable cycle)".into()));
    LegendStrip { entries }
}

/// The data ranges of an inset on the outer wells (each curve's well of largest amplitude),
/// where they lie below `x_end`: their markers would pile up at the main panel's scale.
fn outer_zoom(curves: &[Curve], x_end: f64) -> Option<(Range<f64>, Range<f64>)> {
    let wells: Vec<&Extremum> = curves
        .iter()
        .filter_map(|c| {
            c.extrema
                .iter()
                .filter(|e| e.minimum && e.amplitude > 0.0)
                .max_by(|a, b| a.amplitude.total_cmp(&b.amplitude))
        })
        .filter(|e| e.amplitude < x_end)
        .collect();
    if wells.len() < 2 {
        return None;
    }
    let (a0, a1) = wells
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), e| {
            (a.min(e.amplitude), b.max(e.amplitude))
        });
    let (u0, u1) = wells
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), e| {
            (a.min(e.potential), b.max(e.potential))
        });
    let du = (u1 - u0).max(0.02);
    // A0 from a whole fifth below the wells to one above them, a twentieth beyond: four
    // labelled ticks on the inset's narrow axis
    let (x0, x1) = (
        ((a0 - 0.3) / 0.2).floor() * 0.2 - 0.05,
        ((a1 + 0.25) / 0.2).ceil() * 0.2 + 0.05,
    );
    // (U_eff over four labelled ticks of the finest 1-2-5 step whose three steps span the
    // wells with a sixth of their spread below and a fifth above: the markers as far apart
    // as four labelled ticks allow)
    let (lo, hi) = (u0 - du / 6.0, u1 + 0.2 * du);
    let decade = 10f64.powf((hi - lo).log10().floor() - 1.0);
    let step = [1.0, 2.0, 5.0, 10.0, 20.0, 50.0]
        .iter()
        .map(|m| m * decade)
        .find(|s| (lo / s).floor() * s + 3.0 * s >= hi)
        .unwrap_or(hi - lo);
    let first = (lo / step).floor() * step;
    Some((x0..x1, (first - 0.15 * step)..(first + 3.15 * step)))
}

/// Draw the inset on the outer wells ([`outer_zoom`]) in the upper left of the main chart
/// `c` (empty there: the curves stay below their highest crest up to A0 ≈ 13), with the box it enlarges
/// outlined on the chart.
fn draw_outer_inset<DB: Backend>(
    area: &DrawingArea<DB, Shift>,
    c: &mut ChartContext<'_, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    curves: &[Curve],
) -> Result<()> {
    let Some((zx, zy)) = outer_zoom(curves, c.x_range().end) else {
        return Ok(());
    };
    c.draw_series(std::iter::once(Rectangle::new(
        [(zx.start, zy.start), (zx.end, zy.end)],
        BLACK.stroke_width(stroke(1)),
    )))
    .map_err(pe)?;
    // (above the curves, which stay below the highest crest up to A0 ≈ 13; the frame leaves
    // room there)
    let y = c.y_range();
    let crest = curves
        .iter()
        .flat_map(|cv| cv.extrema.iter())
        .map(|e| e.potential)
        .fold(0.0f64, f64::max);
    let (p0, p1) = (
        c.backend_coord(&(0.3, y.end - 0.02 * (y.end - y.start))),
        c.backend_coord(&(10.2, crest + 0.04 * (y.end - y.start))),
    );
    let (bx, by) = area.get_base_pixel();
    let inset = area.clone().shrink(
        (p0.0 - bx, p0.1 - by),
        ((p1.0 - p0.0).max(1) as u32, (p1.1 - p0.1).max(1) as u32),
    );
    inset.fill(&WHITE).map_err(pe)?;
    let mut z = framed(&inset, "", (zx, zy), ("", ""), ChartSize::Inset)?;
    // (smaller markers: the wells lie close together even here)
    draw_curves(&mut z, curves, 3)?;
    let (w, h) = inset.dim_in_pixel();
    inset
        .draw(&Rectangle::new(
            [(0, 0), (w as i32 - 1, h as i32 - 1)],
            BLACK.stroke_width(stroke(1)),
        ))
        .map_err(pe)?;
    Ok(())
}

/// The caption's key to the drawing: what is marked and what the insets enlarge.
fn key() -> Vec<String> {
    vec![
        "marks as drawn: filled markers the wells (stable cycles), open ones the crests \
         (unstable cycles); the rest state A0 = 0, a crest of every curve, is no cycle and \
         left unmarked; the inset in (a) and (b) enlarges the outer wells (the box outlined \
         around them), whose markers pile up at the panels' scale; the inset's axes are its \
         panel's, A0 across and U_eff(A0) up; (c), (d) enlarge the inner well and (e), (f) \
         the middle well and the crests beside it, with smaller markers"
            .to_string(),
    ]
}

/// Heights of the main charts, and of the zooms on the inner well below them.
const CHARTS: u32 = 620;
const ZOOMS: u32 = 380;

/// Where the zoom on the inner well ends: beyond the first crest past the inner well of any
/// curve; `None` where there is nothing to zoom on.
fn zoom_end(curves: &[Curve]) -> Option<f64> {
    let end = curves
        .iter()
        .filter_map(|cv| {
            let well = cv.extrema.iter().find(|e| e.minimum && e.amplitude > 0.0)?;
            cv.extrema
                .iter()
                .find(|e| !e.minimum && e.amplitude > well.amplitude)
                .map(|e| e.amplitude)
        })
        .fold(0.0f64, f64::max)
        * 1.15;
    (end > 0.0 && end < 14.0).then_some(end)
}

/// The A0 window of the enlargement on the extrema between the inner well's zoom (ending at
/// `end`) and the outer well: the middle well and the crests beside it, whose markers pile up
/// at the main scale; `None` where there are none.
fn middle_window(curves: &[Curve], end: f64) -> Option<Range<f64>> {
    let outer = curves
        .iter()
        .filter_map(|c| {
            c.extrema
                .iter()
                .filter(|e| e.minimum)
                .map(|e| e.amplitude)
                .max_by(f64::total_cmp)
        })
        .fold(f64::INFINITY, f64::min);
    let between: Vec<f64> = curves
        .iter()
        .flat_map(|c| c.extrema.iter())
        .map(|e| e.amplitude)
        .filter(|&a| a > end && a < outer - 0.5)
        .collect();
    let (lo, hi) = between
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
            (a.min(v), b.max(v))
        });
    (lo <= hi).then(|| (lo - 0.8).max(end)..(hi + 0.6).min(outer))
}

/// A y range framing the extrema of `curves` in the A0 window `x` (a fifth of their span
/// below, three tenths above), and the curves' points inside both.
fn frame_window(curves: &[Curve], x: &Range<f64>) -> (Range<f64>, Vec<Curve>) {
    let (lo, hi) = curves
        .iter()
        .flat_map(|c| c.extrema.iter())
        .filter(|e| x.contains(&e.amplitude))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), e| {
            (a.min(e.potential), b.max(e.potential))
        });
    let span = (hi - lo).max(1e-9);
    let y = padded_range([lo - 0.2 * span, hi + 0.3 * span]);
    let clipped = clip(curves, x, &y);
    (y, clipped)
}

// The two panels side by side, each with its zoom on the inner well below it (the well
// A01 is ~10⁻³ deep against ~1 for the outer ones: invisible at the main scale) and on the
// middle well and crests below that, and each column's legend below.
picture!(Fig07, |self, root| key key(), size {
    let w = 1400;
    let strip = self.panels.iter().map(|p| legend_of(p).height(w / 2)).max().unwrap_or(0);
    (w, CHARTS + 2 * ZOOMS + strip)
}, draw {
    let (charts, rest) = root.split_vertically(CHARTS);
    let (zooms, rest) = rest.split_vertically(ZOOMS);
    let (middles, strips) = rest.split_vertically(ZOOMS);
    let areas = charts.split_evenly((1, 2));
    let zoom_areas = zooms.split_evenly((1, 2));
    let middle_areas = middles.split_evenly((1, 2));
    for (strip, p) in strips.split_evenly((1, 2)).iter().zip(&self.panels) {
        legend_of(p).draw(strip)?;
    }
    for (k, (area, Panel { caption, curves, .. })) in areas.iter().zip(&self.panels).enumerate() {
        // (room above the curves for the inset on the outer wells)
        let (y, clipped) = frame_with(curves, 14.0, 0.9, true);
        // (A0 from a little below 0: the marker at A0 = 0 clear of the y ticks)
        let mut c = chart(area, caption, -0.3..14.0, y, "A_0", "U_eff(A_0)")?;
        draw_curves(&mut c, &clipped, MARKER)?;
        draw_outer_inset(area, &mut c, curves)?;
        if let Some(end) = zoom_end(curves) {
            let (yz, zoomed) = frame_with(curves, end, 0.6, true);
            let label = caption.split(' ').next().unwrap_or("");
            // the zooms continue the lettering: (c), (d)
            let letter = ["(c)", "(d)"][k.min(1)];
            let mut z = chart(
                &zoom_areas[k],
                &format!("{letter} {label} enlarged: inner well, A0 ≤ {end:.1}"),
                -0.02 * end..end,
                yz,
                "A_0",
                "U_eff(A_0)",
            )?;
            draw_curves(&mut z, &zoomed, ZOOM_MARKER)?;
            if let Some(x) = middle_window(curves, end) {
                let (ym, framed) = frame_window(curves, &x);
                let letter = ["(e)", "(f)"][k.min(1)];
                let mut m = chart(
                    &middle_areas[k],
                    &format!(
                        "{letter} {label} enlarged: {:.1} ≤ A0 ≤ {:.1}",
                        x.start, x.end
                    ),
                    x,
                    ym,
                    "A_0",
                    "U_eff(A_0)",
                )?;
                draw_curves(&mut m, &framed, ZOOM_MARKER)?;
            }
        }
    }
    Ok(())
});
