//! Fig. 19 as the paper draws it: the critical noise D_c against μ0 (a), τ (b), λ (c) and r (d),
//! one series per attractor of the noise-free system (rest, inner, middle, outer cycle). A
//! located D_c is its bracket (D1, D2) drawn as a bar with a marker at √(D1·D2); a one-sided
//! bracket as a bar to the edge of the searched range; a curve never chaotic (no D_c at all)
//! in a row above the range, the rest regime chaotic as D → 0 (D_c = 0) in a row below it.
//!
//! Rendering only: the data and its computation are [`trirhythm_paper::fig19_critical_noise`].

use super::lle::{outline, CHART_HEIGHT, PANEL_WIDTH};
use crate::render::plot::{
    font_px, pe, px, pxi, stroke, superscript, times_ten, Backend, LegendStrip, Marker, Symbol,
    AXIS_DESC, CAPTION, FONT, PALETTE, TICK,
};
use anyhow::{anyhow, Result};
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use trirhythm_paper::fig19_critical_noise::{Fig19, SignMap};
use trirhythm_paper::lle::Curve;
use trirhythm_paper::notes::num;
use trirhythm_paper::verdict::rules::Bracket;

/// The attractors in the order of their slots in a column, with their colours.
/// Each attractor's marker shape (filled for the rest regime, open for the cycles, see
/// [`filled`]), so that they part in greyscale too.
const SHAPES: [Marker; 4] = [
    Marker::Circle,
    Marker::Square,
    Marker::Triangle,
    Marker::Diamond,
];

const ATTRACTORS: [(&str, RGBColor); 4] = [
    ("rest", RGBColor(0, 0, 0)),
    ("inner", PALETTE[1]),
    ("middle", PALETTE[3]),
    ("outer", PALETTE[2]),
];

/// Horizontal offset of an attractor's slot within its column: the four slots a marker's
/// width or more apart (a column is about 0.5 in wide at print size).
fn slot(k: usize) -> f64 {
    -0.36 + 0.24 * k as f64
}

/// The attractor's index in [`ATTRACTORS`] (its first word: `rest`, `inner`, …).
fn attractor_of(c: &Curve) -> usize {
    let word = c.attractor.split_whitespace().next().unwrap_or("");
    ATTRACTORS
        .iter()
        .position(|(n, _)| *n == word)
        .unwrap_or(ATTRACTORS.len() - 1)
}

/// What a curve says about D_c, as drawn.
enum Mark {
    /// D_c in (lo, hi).
    Located(f64, f64),
    /// D_c < d (chaotic from the smallest D).
    Below(f64),
    /// D_c > d (regular up to the largest D).
    Above(f64),
    /// No D_c: never chaotic, falling at strong noise.
    Never,
    /// D_c = 0: the rest regime chaotic as D → 0.
    Zero,
    /// No bracket.
    Undecided,
}

fn mark_of(c: &Curve) -> Mark {
    let Some(r) = c.redecided() else {
        return Mark::Undecided;
    };
    if r.rest.as_ref().is_some_and(|s| s.d_c_zero) {
        return Mark::Zero;
    }
    match r.bracket {
        Bracket::Located { lo, hi } => Mark::Located(lo, hi),
        Bracket::Below { d } => Mark::Below(d),
        Bracket::Above { d } => Mark::Above(d),
        Bracket::Never { .. } => Mark::Never,
        Bracket::Undecided => Mark::Undecided,
    }
}

/// Whether attractor `k`'s markers are filled: the rest regime's, as the Lyapunov figures'
/// shared notes say ("filled: rest regime, open: cycle regime"); the cycles' are open.
fn filled(k: usize) -> bool {
    ATTRACTORS[k].0 == "rest"
}

/// The legend below the panels: the attractors' markers, then the marks, a few words each
/// (the caption key, [`key`], says the rest).
fn strip() -> LegendStrip {
    let black = RGBColor(0, 0, 0);
    let mut entries: Vec<(Symbol, String)> = ATTRACTORS
        .iter()
        .zip(SHAPES)
        .enumerate()
        .map(|(k, ((n, c), marker))| {
            (
                Symbol::Shape(marker, *c, filled(k)),
                if *n == "rest" {
                    "rest regime".to_string()
                } else {
                    format!("{n} cycle")
                },
            )
        })
        .collect();
    entries.extend([
        (Symbol::Mark('I'), "D_c bracket".into()),
        (Symbol::Mark('↑'), "regular up to the largest D".into()),
        (Symbol::Cross(black), "undecided".into()),
    ]);
    LegendStrip { entries }
}

/// The caption's key to the drawing, after the shared notes of the Lyapunov figures (which
/// this figure shares with Figs 17 and 18): what the marks mean, and that the x axes are
/// categorical.
fn key() -> Vec<String> {
    vec![
        "Fig. 19 as drawn: markers filled for the rest regime, open for the cycle regime, as \
         above; no prediction is drawn (the dashed line of the notes is Figs 17 and 18's); the \
         x axes are categorical: the values tried, evenly spaced whatever their differences; \
         a bar with caps is the bracket of D_c, regular at its foot and chaotic at its top, \
         its marker at the geometric mean of its ends, markers of one attractor in \
         neighbouring columns joined by a thin line; a bar with an arrow (↑) up to the dotted \
         line: regular at its foot and not chaotic up to the largest D tried; a bare bar \
         down to the dotted line, its marker at its top: chaotic at its top, regular nowhere below; the dotted lines \
         lie just beyond the ends of the searched range of D, no value (a bar reaching one is \
         one-sided); row \"none\": never chaotic, no D_c; row \
         \"0\": the rest regime chaotic as D → 0 (D_c = 0); ×, on the row \"undecided\": undecided, no bracket (the row's height is no value)"
            .to_string(),
    ]
}

/// Draw attractor `k`'s marker at (`x`, `y`): its shape, filled or open (white inside).
fn draw_shape<DB: Backend>(
    c: &mut ChartContext<'_, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    (x, y): (f64, f64),
    k: usize,
    colour: RGBColor,
    filled: bool,
) -> Result<()> {
    let ring = outline(SHAPES[k % SHAPES.len()], pxi(5));
    let fill = if filled { colour } else { WHITE };
    c.draw_series(std::iter::once(
        EmptyElement::at((x, y))
            + Polygon::new(ring.clone(), fill.filled())
            + PathElement::new(ring, colour.stroke_width(stroke(2))),
    ))
    .map_err(pe)?;
    Ok(())
}

/// One panel: columns of the parameter's values, log D upward, the rows "no D_c" above and
/// "D_c = 0" below the searched range.
fn draw_dc_panel<DB: Backend>(area: &DrawingArea<DB, Shift>, map: &SignMap) -> Result<()> {
    let panel = &map.panel;
    let values = map.values.clone();
    let nv = values.len() as f64;
    let logs: Vec<f64> = panel
        .curves
        .iter()
        .flat_map(|c| c.points.iter().map(|q| q.x.log10()))
        .filter(|v| v.is_finite())
        .collect();
    let (lo, hi) = logs
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
            (a.min(v), b.max(v))
        });
    let (lo, hi) = if lo.is_finite() {
        (lo, hi)
    } else {
        (-3.0, 1.0)
    };
    // the rows outside the searched range, two units beyond its ends (and "undecided" two
    // more above "none" where a panel has one), the dotted edges one unit beyond: a unit of
    // 0.35 decades, or a twentieth of the axis where it spans more (so that a row's markers
    // stay clear of the dotted line at any span)
    let u = 0.35f64.max(0.05 * (hi - lo + 2.4));
    let (zero_row, never_row) = (lo - 2.0 * u, hi + 2.0 * u);
    let undecided = panel
        .curves
        .iter()
        .any(|c| matches!(mark_of(c), Mark::Undecided));
    let undecided_row = hi + 4.0 * u;
    let (below_edge, above_edge) = (lo - u, hi + u);
    // room beyond the rows, so that their markers stay inside the plotting area
    let y = (lo - 3.4 * u)..(hi + if undecided { 5.4 } else { 3.4 } * u);
    let caption = panel
        .caption
        .split(' ')
        .next()
        .map(|l| format!("{l} critical noise against {}", panel.x_desc))
        .unwrap_or_default();
    let mut c = ChartBuilder::on(area)
        .caption(caption, (FONT, font_px(CAPTION)))
        .margin(px(10))
        .margin_right(px(26))
        .x_label_area_size(px(45))
        .y_label_area_size(px(if undecided { 110 } else { 80 }))
        .build_cartesian_2d(-0.5..nv - 0.5, y.clone())
        .map_err(|e| anyhow!("{e}"))?;
    let xf = |v: &f64| {
        let i = v.round();
        if (v - i).abs() < 1e-6 && i >= 0.0 && (i as usize) < values.len() {
            num(values[i as usize])
        } else {
            String::new()
        }
    };
    // D ticks inside the searched range: at the whole decades, as 10ⁿ, where it spans four
    // or more, else every tick as m×10ⁿ; the two rows are named beside the axis
    let decades = (hi + 1e-9).floor() - (lo - 1e-9).ceil() + 1.0;
    let yf = |v: &f64| {
        let inside = *v >= lo - 1e-9 && *v <= hi + 1e-9;
        if inside && (v - v.round()).abs() < 1e-6 {
            format!("10{}", superscript(&format!("{}", v.round() as i64)))
        } else if inside && decades < 4.0 {
            times_ten(10f64.powf(*v), 2)
        } else {
            String::new()
        }
    };
    c.configure_mesh()
        .x_desc(format!("{} (values tried, evenly spaced)", panel.x_desc))
        .y_desc("critical noise (log scale)")
        .x_labels(values.len() * 2 + 1)
        .y_labels(16)
        .x_label_formatter(&xf)
        .y_label_formatter(&yf)
        .disable_x_mesh()
        .axis_desc_style((FONT, font_px(AXIS_DESC)))
        .label_style((FONT, font_px(TICK)))
        // (no minor grid: the decades' lines alone)
        .light_line_style(TRANSPARENT)
        .draw()
        .map_err(|e| anyhow!("{e}"))?;
    let base = area.get_base_pixel();
    let mut rows = vec![(never_row, "none"), (zero_row, "0")];
    if undecided {
        rows.push((undecided_row, "undecided"));
    }
    for (row, text) in rows {
        let at = c.backend_coord(&(-0.5, row));
        crate::render::plot::rich_text(
            area,
            text,
            (at.0 - base.0 - px(8) as i32, at.1 - base.1),
            Pos::new(HPos::Right, VPos::Center),
            TICK,
            BLACK,
            false,
        )?;
    }
    let grey = RGBColor(150, 150, 150);
    // the ends of the searched range, dotted (the Lyapunov figures' dashes are predictions)
    for edge in [below_edge, above_edge] {
        c.draw_series(DashedLineSeries::new(
            [(-0.5, edge), (nv - 0.5, edge)],
            pxi(2) as u32,
            pxi(4) as u32,
            grey.stroke_width(stroke(1)),
        ))
        .map_err(pe)?;
    }
    // per attractor: the marker positions of the located D_c, for the connecting lines
    let mut located: Vec<Vec<(f64, f64)>> = vec![Vec::new(); ATTRACTORS.len()];
    for curve in &panel.curves {
        let i = values.iter().position(|&v| v == curve.value).unwrap_or(0) as f64;
        let k = attractor_of(curve);
        let colour = ATTRACTORS[k].1;
        let x = i + slot(k);
        let cap = 0.05;
        let bar = |a: f64, b: f64| {
            [
                PathElement::new([(x, a), (x, b)], colour.stroke_width(3)),
                PathElement::new([(x - cap, a), (x + cap, a)], colour.stroke_width(2)),
                PathElement::new([(x - cap, b), (x + cap, b)], colour.stroke_width(2)),
            ]
        };
        match mark_of(curve) {
            Mark::Located(a, b) => {
                let (a, b) = (a.log10(), b.log10());
                let m = 0.5 * (a + b);
                // (the bar over its marker: a bracket shorter than the marker stays seen)
                draw_shape(&mut c, (x, m), k, colour, filled(k))?;
                c.draw_series(bar(a, b)).map_err(pe)?;
                located[k].push((x, m));
            }
            Mark::Above(d) => {
                c.draw_series(bar(d.log10(), above_edge)).map_err(pe)?;
                c.draw_series(std::iter::once(TriangleMarker::new(
                    (x, above_edge),
                    7,
                    colour.filled(),
                )))
                .map_err(pe)?;
            }
            Mark::Below(d) => {
                c.draw_series(bar(below_edge, d.log10())).map_err(pe)?;
                // (its attractor's marker at its top: the smallest D found chaotic)
                draw_shape(&mut c, (x, d.log10()), k, colour, filled(k))?;
            }
            Mark::Never => {
                draw_shape(&mut c, (x, never_row), k, colour, filled(k))?;
            }
            Mark::Zero => {
                draw_shape(&mut c, (x, zero_row), k, colour, filled(k))?;
            }
            Mark::Undecided => {
                c.draw_series(std::iter::once(Cross::new(
                    (x, undecided_row),
                    6,
                    colour.stroke_width(2),
                )))
                .map_err(pe)?;
            }
        }
    }
    for (k, pts) in located.iter().enumerate() {
        for w in pts.windows(2) {
            // only between neighbouring columns
            if (w[1].0 - w[0].0 - 1.0).abs() < 1e-9 {
                c.draw_series(std::iter::once(PathElement::new(
                    [w[0], w[1]],
                    ATTRACTORS[k].1.stroke_width(1),
                )))
                .map_err(pe)?;
            }
        }
    }
    Ok(())
}

picture!(Fig19, |self, root| key key(), size (2 * PANEL_WIDTH, 2 * CHART_HEIGHT + strip().height(2 * PANEL_WIDTH) + 8), draw {
    let (maps, legend) = root.split_vertically(2 * CHART_HEIGHT);
    for (area, map) in maps.split_evenly((2, 2)).iter().zip(&self.panels) {
        draw_dc_panel(area, map)?;
    }
    strip().draw(&legend)
});
