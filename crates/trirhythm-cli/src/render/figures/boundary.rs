//! Drawing of the oscillation-boundary panels (Figs 15, 16): the shaded rest region under the
//! simulated boundary, each method's curve in its style, one colour per method or, in a family
//! panel, per parameter value.
//!
//! Drawing only: the boundaries and their distances are [`trirhythm_paper::boundary`].

use crate::render::plot::{chart, legend, pe, Backend, PALETTE};
use anyhow::Result;
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use trirhythm::analysis::oscillation::{BoundaryPoint, Side};
use trirhythm_paper::boundary::{Curve, Panel};

/// Colours: simulation black, averaging red, exact blue, exact without the wall grey.
pub const SIM: RGBColor = RGBColor(0, 0, 0);
/// Averaging.
pub const AVG: RGBColor = RGBColor(200, 30, 30);
/// Exact.
pub const EXACT: RGBColor = RGBColor(30, 90, 200);
/// Exact without the wall (reference).
pub const NOWALL: RGBColor = RGBColor(130, 130, 130);
/// The non-oscillating region.
pub const SHADE: RGBColor = RGBColor(170, 200, 245);

/// A curve's colour: by method, or by member in a family panel.
fn colour(curve: &Curve) -> RGBColor {
    match (curve.member, curve.method.as_str()) {
        (Some(i), _) => PALETTE[i % PALETTE.len()],
        (None, "simulation") => SIM,
        (None, "averaging") => AVG,
        (None, "exact, no wall") => NOWALL,
        (None, _) => EXACT,
    }
}

/// Draw one panel: the shaded rest region under the simulated boundary, then every curve
/// (simulation solid with its bracket as tick marks, averaging dashed, exact dotted or as
/// markers where it has a single point).
pub fn draw_panel<DB: Backend>(
    area: &DrawingArea<DB, Shift>,
    panel: &Panel,
    with_legend: bool,
) -> Result<()> {
    let top = panel
        .curves
        .iter()
        .flat_map(|c| c.points.iter())
        .filter(|q| q.side == Side::Boundary)
        .map(|q| q.y)
        .fold(0.0f64, f64::max);
    let (y0, y1) = (0.0, (1.12 * top).min(panel.y_range.1).max(1e-3));
    let mut c = chart(
        area,
        &panel.caption,
        panel.x_range.0..panel.x_range.1,
        y0..y1,
        &panel.x_desc,
        "μ0",
    )?;
    for curve in panel.curves.iter().filter(|c| c.rest_below) {
        let level = |q: &BoundaryPoint| match q.side {
            Side::Boundary => Some(q.y.clamp(y0, y1)),
            Side::Rests => Some(y1),
            Side::Oscillates => Some(y0),
            Side::Unavailable => None,
        };
        let mut poly: Vec<(f64, f64)> = curve
            .points
            .iter()
            .filter_map(|q| level(q).map(|y| (q.x, y)))
            .collect();
        if poly.len() >= 2 {
            let (xa, xb) = (poly[0].0, poly[poly.len() - 1].0);
            poly.push((xb, y0));
            poly.push((xa, y0));
            c.draw_series(std::iter::once(Polygon::new(poly, SHADE.filled())))
                .map_err(pe)?
                .label("no oscillation (simulated)")
                .legend(|(x, y)| Rectangle::new([(x, y - 5), (x + 16, y + 5)], SHADE.filled()));
        }
    }
    for curve in &panel.curves {
        draw_curve(&mut c, curve)?;
    }
    if panel.is_family() {
        for (text, dash) in [
            ("solid: simulation", 0),
            ("dashed: averaging", 1),
            ("○ / ×: exact", 2),
        ] {
            c.draw_series(std::iter::empty::<Circle<(f64, f64), i32>>())
                .map_err(pe)?
                .label(text)
                .legend(move |(x, y)| match dash {
                    0 => PathElement::new([(x, y), (x + 20, y)], BLACK.stroke_width(3)),
                    1 => PathElement::new([(x, y), (x + 8, y)], BLACK.stroke_width(2)),
                    _ => PathElement::new([(x + 6, y - 4), (x + 12, y + 4)], BLACK.stroke_width(2)),
                });
        }
    }
    if with_legend {
        legend(&mut c, SeriesLabelPosition::UpperRight)?;
    }
    Ok(())
}

/// One curve in its method's style: simulation solid with markers, averaging dashed, exact
/// dotted with rings, a single point as a marked cross; keyed in the legend when labelled.
fn draw_curve<'a, DB: Backend + 'a>(
    c: &mut ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    curve: &Curve,
) -> Result<()> {
    let pts: Vec<(f64, f64)> = curve
        .points
        .iter()
        .filter(|q| q.side == Side::Boundary)
        .map(|q| (q.x, q.y))
        .collect();
    if pts.is_empty() {
        return Ok(());
    }
    let color = colour(curve);
    let label = curve.label.clone();
    let keyed = !label.is_empty();
    if pts.len() == 1 {
        let s = c
            .draw_series(std::iter::once(
                EmptyElement::at(pts[0])
                    + Cross::new((0, 0), 7, color.stroke_width(3))
                    + Circle::new((0, 0), 9, color.stroke_width(2)),
            ))
            .map_err(pe)?;
        if keyed {
            s.label(label)
                .legend(move |(x, y)| Cross::new((x + 8, y), 5, color.stroke_width(3)));
        }
        return Ok(());
    }
    match curve.method.as_str() {
        "simulation" => {
            let s = c
                .draw_series(LineSeries::new(pts.clone(), color.stroke_width(3)))
                .map_err(pe)?;
            if keyed {
                s.label(label).legend(move |(x, y)| {
                    PathElement::new([(x, y), (x + 16, y)], color.stroke_width(3))
                });
            }
            c.draw_series(pts.iter().map(|&p| Circle::new(p, 3, color.filled())))
                .map_err(pe)?;
        }
        "averaging" => {
            let s = c
                .draw_series(DashedLineSeries::new(pts, 9, 6, color.stroke_width(2)))
                .map_err(pe)?;
            if keyed {
                s.label(label).legend(move |(x, y)| {
                    EmptyElement::at((x, y))
                        + PathElement::new([(0, 0), (8, 0)], color.stroke_width(2))
                        + PathElement::new([(12, 0), (20, 0)], color.stroke_width(2))
                });
            }
        }
        _ => {
            c.draw_series(DashedLineSeries::new(
                pts.clone(),
                3,
                5,
                color.stroke_width(3),
            ))
            .map_err(pe)?;
            let s = c
                .draw_series(
                    pts.iter()
                        .map(|&p| Circle::new(p, 5, color.stroke_width(2))),
                )
                .map_err(pe)?;
            if keyed {
                s.label(label)
                    .legend(move |(x, y)| Circle::new((x + 8, y), 5, color.stroke_width(2)));
            }
        }
    }
    Ok(())
}
