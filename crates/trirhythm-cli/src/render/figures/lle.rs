//! What Figs 17–19 share: panels of the largest Lyapunov exponent against D on a log axis with
//! error bars, one colour and one marker shape per value of the panel's parameter (apart in
//! greyscale), filled markers for the rest regime and open markers for the cycle regime.
//! Each panel keeps its legend in a strip below its chart, so no legend covers data; the
//! panel's verdict details are in the caption (the CSV notes), and the y range is the data's.
//!
//! Drawing only: the runs and verdicts are [`trirhythm_paper::lle`].

use crate::render::plot::{
    draw_line, font_px, padded_range, pe, px, pxi, stroke, tick_formatter, times_ten, Backend,
    Dash, LegendStrip, Marker, SeriesStyle, Symbol, AXIS_DESC, CAPTION, FONT, PALETTE, TICK,
};
use anyhow::{anyhow, Result};
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::ops::Range;
use trirhythm_paper::lle::{Flag, LleAgainstNoise, Panel, StartKind};

/// Height of the chart part of a panel.
pub const CHART_HEIGHT: u32 = 440;
/// Width of a panel.
pub const PANEL_WIDTH: u32 = 620;

/// The distinct values of a panel's curves, in order (one colour each).
fn values(panel: &Panel) -> Vec<f64> {
    let mut v: Vec<f64> = Vec::new();
    for c in &panel.curves {
        if !v.contains(&c.value) {
            v.push(c.value);
        }
    }
    v
}

fn index_of(panel: &Panel, value: f64) -> usize {
    values(panel).iter().position(|&v| v == value).unwrap_or(0)
}

fn colour_of(panel: &Panel, value: f64) -> RGBColor {
    PALETTE[index_of(panel, value) % PALETTE.len()]
}

/// The marker shapes of a panel's values, in order (each can be filled or open).
const SHAPES: [Marker; 4] = [
    Marker::Circle,
    Marker::Square,
    Marker::Triangle,
    Marker::Diamond,
];

fn shape_of(panel: &Panel, value: f64) -> Marker {
    SHAPES[index_of(panel, value) % SHAPES.len()]
}

/// The dash of an attractor's line: rest and outer cycle solid (the rest regime's line is
/// the thicker), inner cycle dotted, middle chain (the attractor's first word); dashed is the
/// predictions'.
fn dash_of(attractor: &str) -> Dash {
    match attractor.split_whitespace().next().unwrap_or("") {
        "inner" => Dash::Dotted,
        "middle" => Dash::Chain,
        _ => Dash::Solid,
    }
}

pub(super) use crate::render::legend::outline;

fn strip(panel: &Panel) -> LegendStrip {
    strip_of(panel, panel)
}

/// The legend strip of `panel`, its colours and shapes those of `parent` (a sub-panel keeps
/// the colours of the panel it was split from).
fn strip_of(panel: &Panel, parent: &Panel) -> LegendStrip {
    let mut entries: Vec<(Symbol, String)> = Vec::new();
    let mut seen: Vec<f64> = Vec::new();
    for c in &panel.curves {
        if seen.contains(&c.value) {
            continue;
        }
        seen.push(c.value);
        let name = c.label.split(',').next().unwrap_or("").to_string();
        entries.push((
            Symbol::Series(SeriesStyle {
                colour: colour_of(parent, c.value),
                dash: Dash::Solid,
                marker: shape_of(parent, c.value),
            }),
            name,
        ));
    }
    let black = RGBColor(0, 0, 0);
    entries.push((Symbol::Dot(black), "filled: rest regime".into()));
    entries.push((Symbol::Ring(black), "open: cycle regime".into()));
    // the attractors met, by their lines' dash (the rest regime's line thicker)
    for (word, dash, name) in [
        ("inner", Dash::Dotted, "inner cycle"),
        ("middle", Dash::Chain, "middle cycle"),
        ("outer", Dash::Solid, "solid: outer cycle (or rest)"),
    ] {
        if panel
            .curves
            .iter()
            .any(|c| c.attractor.split_whitespace().next() == Some(word))
        {
            entries.push((
                Symbol::Series(SeriesStyle {
                    colour: black,
                    dash,
                    marker: Marker::None,
                }),
                name.into(),
            ));
        }
    }
    entries.push((
        Symbol::Dashed(black),
        "dashed: prediction (its series' colour)".into(),
    ));
    let flagged = |f: Flag| {
        panel
            .curves
            .iter()
            .any(|c| c.points.iter().any(|q| q.flag == f))
    };
    if flagged(Flag::Merged) {
        entries.push((
            Symbol::Cross(black),
            "× at the bottom: copies merged (−∞)".into(),
        ));
    }
    if flagged(Flag::Undefined) {
        entries.push((Symbol::Cross(black), "× at the bottom: no value".into()));
    }
    LegendStrip { entries }
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

/// A panel with more curves than this is drawn as sub-panels, one per value of its
/// parameter, on shared axes (so its attractors' lines and markers can be told apart).
const SPLIT_ABOVE: usize = 8;

/// A panel as drawn: the panel, the panel its colours come from, its shared axes' ranges.
type Drawn<'a> = (Panel, &'a Panel, Option<(Range<f64>, Range<f64>)>);

/// The panels as drawn ([`Drawn`]).
fn drawn(panels: &[Panel]) -> Vec<Drawn<'_>> {
    let mut out = Vec::new();
    for p in panels {
        let vs = values(p);
        if p.curves.len() <= SPLIT_ABOVE || vs.len() < 2 {
            out.push((p.clone(), p, None));
            continue;
        }
        let ranges = ranges_of(p);
        let (head, rest) = match p.caption.find(')') {
            Some(i) if p.caption.starts_with('(') => (&p.caption[1..i], p.caption[i + 1..].trim()),
            _ => ("", p.caption.as_str()),
        };
        for (k, v) in vs.iter().enumerate() {
            let curves: Vec<_> = p.curves.iter().filter(|c| c.value == *v).cloned().collect();
            let name = curves[0]
                .label
                .split(',')
                .next()
                .unwrap_or("")
                .trim()
                .to_string();
            let caption = if head.is_empty() {
                format!("{rest}, {name}")
            } else {
                format!("({head}{}) {rest}, {name}", k + 1)
            };
            let mut sub = p.clone();
            sub.caption = caption;
            sub.curves = curves;
            out.push((sub, p, Some(ranges.clone())));
        }
    }
    out
}

/// The x (log10 D) and y ranges of a panel's data.
fn ranges_of(panel: &Panel) -> (Range<f64>, Range<f64>) {
    let x = padded_range(
        panel
            .curves
            .iter()
            .flat_map(|c| c.points.iter().map(|q| q.x.log10())),
    );
    let mut ys: Vec<f64> = panel
        .curves
        .iter()
        .flat_map(|c| c.points.iter())
        .filter(|q| q.flag == Flag::Value)
        .flat_map(|q| [q.lo, q.hi, q.y])
        .collect();
    ys.push(0.0);
    // the range is the data's (the panel's verdicts are in the caption, not over the data)
    (x, padded_range(ys))
}

type Chart<'a, DB> = ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// A chart whose x axis is log10 D, its ticks labelled with D itself.
fn log_x_chart<'a, DB: Backend>(
    area: &'a DrawingArea<DB, Shift>,
    caption: &str,
    (x, y): (Range<f64>, Range<f64>),
    (x_desc, y_desc): (&str, &str),
) -> Result<Chart<'a, DB>> {
    let mut c = ChartBuilder::on(area)
        .caption(caption, (FONT, font_px(CAPTION)))
        .margin(px(10))
        .margin_right(px(26))
        .x_label_area_size(px(45))
        .y_label_area_size(px(70))
        .build_cartesian_2d(x, y.clone())
        .map_err(|e| anyhow!("{e}"))?;
    let pow = |v: &f64| times_ten(10f64.powf(*v), 2);
    let plain = tick_formatter(&y, 10);
    c.configure_mesh()
        .x_desc(x_desc)
        .y_desc(y_desc)
        .x_labels(8)
        .y_labels(10)
        .x_label_formatter(&pow)
        .y_label_formatter(&plain)
        .axis_desc_style((FONT, font_px(AXIS_DESC)))
        .label_style((FONT, font_px(TICK)))
        .light_line_style(RGBColor(235, 235, 235))
        .draw()
        .map_err(|e| anyhow!("{e}"))?;
    Ok(c)
}

/// Draw one LLE-against-D panel: log D axis, error bars, zero line, filled (rest regime) and
/// open (cycle regime) markers, legend strip below. Merged points are drawn as
/// crosses on the lower edge.
pub fn draw_panel<DB: Backend>(
    area: &DrawingArea<DB, Shift>,
    panel: &Panel,
    parent: &Panel,
    ranges: Option<(Range<f64>, Range<f64>)>,
) -> Result<()> {
    let (top, bottom) = area.split_vertically(CHART_HEIGHT);
    let lx = |d: f64| d.log10();
    let (x, y) = ranges.unwrap_or_else(|| ranges_of(panel));
    let mut c = log_x_chart(
        &top,
        &panel.caption,
        (x.clone(), y.clone()),
        (&panel.x_desc, &panel.y_desc),
    )?;
    c.draw_series(std::iter::once(PathElement::new(
        [(x.start, 0.0), (x.end, 0.0)],
        RGBColor(120, 120, 120).stroke_width(1),
    )))
    .map_err(pe)?;
    // the predictions first (under the data), dashed: −c·D on a cycle (over its D), the rest
    // regime's D-independent exponent (over D ≤ 0.01 where it was pooled)
    for curve in &panel.curves {
        let Some(r) = curve.regime.as_ref() else {
            continue;
        };
        let colour = colour_of(parent, curve.value);
        let ds: Vec<f64> = curve.points.iter().map(|q| q.x).collect();
        let line: Vec<(f64, f64)> = if let Some(rest) = r.rest.as_ref().filter(|r| r.d_c_zero) {
            ds.iter()
                .filter(|&&d| d <= trirhythm_paper::verdict::rules::REST_HOMOGENEOUS_D)
                .map(|&d| (lx(d), rest.pooled))
                .collect()
        } else if r.coefficient.is_finite() {
            // only where the prediction is on the chart (its order-D validity ends earlier)
            ds.iter()
                .map(|&d| (lx(d), -r.coefficient * d))
                .filter(|&(_, v)| v >= y.start)
                .collect()
        } else {
            vec![]
        };
        // (only where it is on the chart: no dash below or above the axes)
        let line: Vec<(f64, f64)> = line
            .into_iter()
            .filter(|&(_, v)| v >= y.start && v <= y.end)
            .collect();
        if line.len() >= 2 {
            c.draw_series(DashedLineSeries::new(line, 6, 4, colour.stroke_width(1)))
                .map_err(pe)?;
        }
    }
    let n = panel.curves.len().max(1) as f64;
    for (i, curve) in panel.curves.iter().enumerate() {
        let colour = colour_of(parent, curve.value);
        let open = curve.start == StartKind::Cycle;
        // a small horizontal offset per curve keeps overlapping error bars apart
        let shift = (x.end - x.start) * 0.003 * (i as f64 - (n - 1.0) / 2.0);
        // the line in its attractor's dash (inner dotted, middle chain, rest and outer solid,
        // the rest regime's thicker): the attractors of one value part in greyscale
        let style = SeriesStyle {
            colour,
            dash: dash_of(&curve.attractor),
            marker: Marker::None,
        };
        for run in curve.points.split(|q| q.flag != Flag::Value) {
            let run: Vec<(f64, f64)> = run.iter().map(|q| (lx(q.x) + shift, q.y)).collect();
            draw_line(&c, &run, style, if open { 1 } else { 2 })?;
        }
        let cap = (x.end - x.start) * 0.005;
        for q in &curve.points {
            let xq = lx(q.x) + shift;
            if q.flag != Flag::Value {
                c.draw_series(std::iter::once(Cross::new(
                    (xq, y.start + 0.02 * (y.end - y.start)),
                    5,
                    colour.stroke_width(2),
                )))
                .map_err(pe)?;
                continue;
            }
            c.draw_series([
                PathElement::new([(xq, q.lo), (xq, q.hi)], colour.stroke_width(1)),
                PathElement::new([(xq - cap, q.lo), (xq + cap, q.lo)], colour.stroke_width(1)),
                PathElement::new([(xq - cap, q.hi), (xq + cap, q.hi)], colour.stroke_width(1)),
            ])
            .map_err(pe)?;
            // the value's shape, open (white inside a thick outline) or filled
            let ring = outline(shape_of(parent, curve.value), pxi(4));
            let fill = if open { WHITE } else { colour };
            c.draw_series(std::iter::once(
                EmptyElement::at((xq, q.y))
                    + Polygon::new(ring.clone(), fill.filled())
                    + PathElement::new(ring, colour.stroke_width(stroke(2))),
            ))
            .map_err(pe)?;
        }
    }
    strip_of(panel, parent).draw(&bottom)
}

/// Rows of the figure: its drawn panels two to a row.
fn rows(panels: &[Panel]) -> u32 {
    drawn(panels).len().div_ceil(2) as u32
}

/// Height of a row of drawn panels.
fn row_height(panels: &[Panel]) -> u32 {
    let subs: Vec<Panel> = drawn(panels).into_iter().map(|(p, _, _)| p).collect();
    panel_height(&subs)
}

// An LLE-against-noise figure (Figs 17, 18): the panels two to a row (a panel with many
// curves split into one sub-panel per value on shared axes; a last lone panel centred).
picture!(LleAgainstNoise, |self, root| size (2 * PANEL_WIDTH, rows(&self.panels) * row_height(&self.panels)), draw {
    let panels = drawn(&self.panels);
    let h = row_height(&self.panels) as i32;
    let w = PANEL_WIDTH as i32;
    let n = panels.len();
    for (k, (panel, parent, ranges)) in panels.iter().enumerate() {
        let row = (k / 2) as i32;
        let lone = k + 1 == n && n % 2 == 1;
        let left = if lone { w / 2 } else { (k % 2) as i32 * w };
        let area = root.clone().shrink((left, row * h), (w as u32, h as u32));
        draw_panel(&area, panel, parent, ranges.clone())?;
    }
    Ok(())
});
