//! What Figs 17–19 share: panels of the largest Lyapunov exponent against D on a log axis with
//! error bars, one colour and one marker shape per value of the panel's parameter (apart in
//! greyscale), filled markers for the rest regime and open markers for the cycle regime.
//! Each panel keeps its legend in a strip below its chart, so no legend covers data; the
//! panel's verdict details are in the caption (the CSV notes), and the y range is the data's.
//! A panel with many curves is split into one sub-panel per value on shared axes; there the
//! value is the sub-panel's title, so colour and shape tell the attractors apart, and the
//! sub-panels share one legend below them.
//!
//! Drawing only: the runs and verdicts are [`trirhythm_paper::lle`].

use crate::render::plot::{
    draw_line, font_px, padded_range, pe, px, pxi, rich_text, stroke, tick_formatter, times_ten,
    Backend, Dash, LegendStrip, Marker, SeriesStyle, Symbol, AXIS_DESC, CAPTION, FONT, PALETTE,
    TICK,
};
use anyhow::{anyhow, Result};
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::ops::Range;
use trirhythm_paper::lle::{Curve, Flag, LleAgainstNoise, Panel, StartKind};

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

/// The attractors a split panel's curves are told apart by, in the legend's order: the first
/// word of [`Curve::attractor`](trirhythm_paper::lle::Curve) and its name in the legend.
const ATTRACTORS: [(&str, &str); 4] = [
    ("rest", "rest"),
    ("inner", "inner cycle"),
    ("middle", "middle cycle"),
    ("outer", "outer cycle"),
];

/// The index of `attractor` in [`ATTRACTORS`] (an unknown word: the outer cycle's).
fn attractor_index(attractor: &str) -> usize {
    let word = attractor.split_whitespace().next().unwrap_or("");
    ATTRACTORS
        .iter()
        .position(|(w, _)| *w == word)
        .unwrap_or(ATTRACTORS.len() - 1)
}

/// How a curve is drawn: its colour, marker shape and line dash. In a panel of its own the
/// colour and shape are its value's and the dash its attractor's ([`dash_of`]); in a split
/// panel (one value) colour and shape are its attractor's, the line solid.
fn look(curve: &Curve, parent: &Panel, split: bool) -> (RGBColor, Marker, Dash) {
    if split {
        let k = attractor_index(&curve.attractor);
        (
            PALETTE[k % PALETTE.len()],
            SHAPES[k % SHAPES.len()],
            Dash::Solid,
        )
    } else {
        (
            colour_of(parent, curve.value),
            shape_of(parent, curve.value),
            dash_of(&curve.attractor),
        )
    }
}

pub(super) use crate::render::legend::outline;

/// The legend strip of a panel of its own: a colour and shape per value, the attractors by
/// their lines' dash.
fn strip(panel: &Panel) -> LegendStrip {
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
                colour: colour_of(panel, c.value),
                dash: Dash::Solid,
                marker: shape_of(panel, c.value),
            }),
            name,
        ));
    }
    let black = RGBColor(0, 0, 0);
    entries.push((Symbol::Dot(black), "filled: rest regime".into()));
    entries.push((Symbol::Ring(black), "open: cycle regime".into()));
    // the attractors met, by their lines' dash (the rest regime's line thicker)
    for (word, dash, name) in [
        ("inner", Dash::Dotted, "inner cycle (smaller markers)"),
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
    finish_strip(entries, &panel.curves)
}

/// The one legend of the sub-panels a panel was split into: a colour and shape per attractor
/// met in any of them.
fn split_strip(panel: &Panel) -> LegendStrip {
    let mut entries: Vec<(Symbol, String)> = Vec::new();
    for (k, (_, name)) in ATTRACTORS.iter().enumerate() {
        if panel
            .curves
            .iter()
            .any(|c| attractor_index(&c.attractor) == k)
        {
            entries.push((
                Symbol::Series(SeriesStyle {
                    colour: PALETTE[k % PALETTE.len()],
                    dash: Dash::Solid,
                    marker: SHAPES[k % SHAPES.len()],
                }),
                (*name).into(),
            ));
        }
    }
    let black = RGBColor(0, 0, 0);
    entries.push((Symbol::Dot(black), "filled: rest regime".into()));
    entries.push((Symbol::Ring(black), "open: cycle regime".into()));
    finish_strip(entries, &panel.curves)
}

/// `entries` followed by the entries every LLE legend ends with: the predictions' dash and
/// the marks of the points without a value among `curves`.
fn finish_strip(mut entries: Vec<(Symbol, String)>, curves: &[Curve]) -> LegendStrip {
    let black = RGBColor(0, 0, 0);
    entries.push((
        Symbol::Dashed(black),
        "dashed: prediction (its series' colour)".into(),
    ));
    let flagged = |f: Flag| curves.iter().any(|c| c.points.iter().any(|q| q.flag == f));
    if flagged(Flag::Merged) {
        entries.push((
            Symbol::Cross(black),
            "× in the band −∞: ≥ half the copies merged".into(),
        ));
    }
    if flagged(Flag::Undefined) {
        entries.push((Symbol::Cross(black), "× in the band −∞: no value".into()));
    }
    LegendStrip { entries }
}

/// A panel with more curves than this is drawn as sub-panels, one per value of its
/// parameter, on shared axes (so its attractors' lines and markers can be told apart).
const SPLIT_ABOVE: usize = 8;

/// A panel as drawn: the panel, the panel it was split from (or itself), and the shared axes'
/// ranges of a sub-panel (`None`: a panel of its own).
type Drawn<'a> = (Panel, &'a Panel, Option<(Range<f64>, Range<f64>)>);

/// A panel as drawn ([`Drawn`]): itself, or its sub-panels.
fn drawn(p: &Panel) -> Vec<Drawn<'_>> {
    let vs = values(p);
    if p.curves.len() <= SPLIT_ABOVE || vs.len() < 2 {
        return vec![(p.clone(), p, None)];
    }
    let ranges = ranges_of(p);
    let (head, rest) = match p.caption.find(')') {
        Some(i) if p.caption.starts_with('(') => (&p.caption[1..i], p.caption[i + 1..].trim()),
        _ => ("", p.caption.as_str()),
    };
    vs.iter()
        .enumerate()
        .map(|(k, v)| {
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
            (sub, p, Some(ranges.clone()))
        })
        .collect()
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
    // the range is the data's (the panel's verdicts are in the caption, not over the data),
    // and below it a band for the points without a value ([`BAND`])
    let y = padded_range(ys);
    let unvalued = panel
        .curves
        .iter()
        .any(|c| c.points.iter().any(|q| q.flag != Flag::Value));
    let band = if unvalued {
        BAND * (y.end - y.start)
    } else {
        0.0
    };
    (x, (y.start - band)..y.end)
}

/// The height of the band below a panel's data for the points without a value (copies
/// merged: −∞; no value), as a fraction of the data's range: the band is labelled "−∞" on the
/// y axis, set off by a grey line, and carries no numeric tick.
const BAND: f64 = 0.12;

/// The bottom of a panel's data range above its band of points without a value (`y.start`
/// where the panel has none).
fn band_top(panel: &Panel, y: &Range<f64>) -> f64 {
    let unvalued = panel
        .curves
        .iter()
        .any(|c| c.points.iter().any(|q| q.flag != Flag::Value));
    if unvalued {
        y.start + BAND / (1.0 + BAND) * (y.end - y.start)
    } else {
        y.start
    }
}

type Chart<'a, DB> = ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// A chart whose x axis is log10 D, its ticks labelled with D itself.
fn log_x_chart<'a, DB: Backend>(
    area: &'a DrawingArea<DB, Shift>,
    caption: &str,
    (x, y): (Range<f64>, Range<f64>),
    (x_desc, y_desc): (&str, &str),
    floor: f64,
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
    let numbers = tick_formatter(&y, 10);
    // (no numeric label in the band below `floor`)
    let plain = |v: &f64| {
        if *v < floor {
            String::new()
        } else {
            numbers(v)
        }
    };
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
/// open (cycle regime) markers, and (a panel of its own) its legend strip below. Points
/// without a value (copies merged: −∞) are drawn as crosses in a band below the data
/// labelled "−∞".
fn draw_panel<DB: Backend>(
    area: &DrawingArea<DB, Shift>,
    (panel, parent, ranges): &Drawn,
) -> Result<()> {
    let split = ranges.is_some();
    let (top, bottom) = area.split_vertically(CHART_HEIGHT);
    let lx = |d: f64| d.log10();
    let (x, y) = ranges.clone().unwrap_or_else(|| ranges_of(panel));
    let floor = band_top(parent, &y);
    let mut c = log_x_chart(
        &top,
        &panel.caption,
        (x.clone(), y.clone()),
        (&panel.x_desc, &panel.y_desc),
        floor,
    )?;
    let band = (y.start + floor) / 2.0;
    if floor > y.start {
        c.draw_series(std::iter::once(PathElement::new(
            [(x.start, floor), (x.end, floor)],
            RGBColor(150, 150, 150).stroke_width(stroke(1)),
        )))
        .map_err(pe)?;
        // "−∞" where the band's tick label would be
        let (px, py) = c.backend_coord(&(x.start, band));
        let (bx, by) = top.get_base_pixel();
        rich_text(
            &top,
            "−∞",
            (px - bx - pxi(8), py - by),
            Pos::new(HPos::Right, VPos::Center),
            TICK,
            BLACK,
            false,
        )?;
    }
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
        let (colour, _, _) = look(curve, parent, split);
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
                .filter(|&(_, v)| v >= floor)
                .collect()
        } else {
            vec![]
        };
        // (only where it is on the chart: no dash below or above the axes)
        let line: Vec<(f64, f64)> = line
            .into_iter()
            .filter(|&(_, v)| v >= floor && v <= y.end)
            .collect();
        if line.len() >= 2 {
            c.draw_series(DashedLineSeries::new(line, 6, 4, colour.stroke_width(1)))
                .map_err(pe)?;
        }
    }
    let n = panel.curves.len().max(1) as f64;
    for (i, curve) in panel.curves.iter().enumerate() {
        let (colour, shape, dash) = look(curve, parent, split);
        let open = curve.start == StartKind::Cycle;
        // a small horizontal offset per curve keeps overlapping error bars apart
        let shift = (x.end - x.start) * 0.003 * (i as f64 - (n - 1.0) / 2.0);
        // in a panel of its own the line in its attractor's dash (inner dotted, middle chain,
        // rest and outer solid, the rest regime's thicker): the attractors of one value part
        // in greyscale
        let style = SeriesStyle {
            colour,
            dash,
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
                    (xq, band),
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
            // (in a panel of its own the inner cycle's markers smaller: apart from the outer
            // cycle's of the same value)
            let inner = !split && attractor_index(&curve.attractor) == 1;
            let ring = outline(shape, pxi(if inner { 3 } else { 4 }));
            let fill = if open { WHITE } else { colour };
            c.draw_series(std::iter::once(
                EmptyElement::at((xq, q.y))
                    + Polygon::new(ring.clone(), fill.filled())
                    + PathElement::new(ring, colour.stroke_width(stroke(2))),
            ))
            .map_err(pe)?;
        }
    }
    if split {
        Ok(())
    } else {
        strip(panel).draw(&bottom)
    }
}

/// The caption's key to the drawing: where markers are set apart, the inner cycle's marks.
fn key() -> Vec<String> {
    vec![
        "the markers and error bars of the curves of a panel are set apart sideways, each \
         curve by a fixed share of the axis (at most a tenth of a decade in D), so that points \
         at the same D stay visible; the CSV holds each point's D; in a panel with one colour \
         per value the inner cycle's markers are the smaller ones, on a dotted line"
            .to_string(),
    ]
}

/// A row of the figure: up to two drawn panels, or the legend of a split panel's sub-panels.
enum Row<'a> {
    Panels(Vec<Drawn<'a>>),
    Legend(LegendStrip),
}

impl Row<'_> {
    /// The width of each of its panels: a lone panel of its own takes the row's width.
    fn panel_width(&self) -> u32 {
        match self {
            Row::Panels(cells) if cells.len() == 1 && cells[0].2.is_none() => 2 * PANEL_WIDTH,
            _ => PANEL_WIDTH,
        }
    }

    /// Its height: a chart, with the tallest legend strip of its panels of their own.
    fn height(&self) -> u32 {
        match self {
            Row::Panels(cells) => {
                CHART_HEIGHT
                    + cells
                        .iter()
                        .filter(|(_, _, ranges)| ranges.is_none())
                        .map(|(p, _, _)| strip(p).height(self.panel_width()))
                        .max()
                        .unwrap_or(0)
                    + 8
            }
            Row::Legend(strip) => strip.height(2 * PANEL_WIDTH) + 8,
        }
    }
}

/// The figure's rows: its panels two to a row, a split panel's sub-panels two to a row
/// followed by their one legend.
fn rows(panels: &[Panel]) -> Vec<Row<'_>> {
    let mut out = Vec::new();
    let mut single: Vec<Drawn> = Vec::new();
    for p in panels {
        let subs = drawn(p);
        if subs.len() == 1 {
            single.extend(subs);
            if single.len() == 2 {
                out.push(Row::Panels(std::mem::take(&mut single)));
            }
            continue;
        }
        if !single.is_empty() {
            out.push(Row::Panels(std::mem::take(&mut single)));
        }
        let mut subs = subs.into_iter().peekable();
        while subs.peek().is_some() {
            out.push(Row::Panels(subs.by_ref().take(2).collect()));
        }
        out.push(Row::Legend(split_strip(p)));
    }
    if !single.is_empty() {
        out.push(Row::Panels(single));
    }
    out
}

// An LLE-against-noise figure (Figs 17, 18): the panels two to a row (a panel with many
// curves split into one sub-panel per value on shared axes, with one legend; a lone panel
// the row's width).
picture!(LleAgainstNoise, |self, root| key key(), size (2 * PANEL_WIDTH, rows(&self.panels).iter().map(Row::height).sum()), draw {
    let w = PANEL_WIDTH as i32;
    let mut top = 0;
    for row in rows(&self.panels) {
        let h = row.height();
        let area = root.clone().shrink((0, top), (2 * PANEL_WIDTH, h));
        match &row {
            Row::Legend(strip) => strip.draw(&area)?,
            Row::Panels(cells) => {
                let width = row.panel_width();
                for (k, cell) in cells.iter().enumerate() {
                    // (a lone sub-panel centred)
                    let left = if cells.len() == 1 && width == PANEL_WIDTH { w / 2 } else { k as i32 * w };
                    let panel = area.clone().shrink((left, 0), (width, h));
                    draw_panel(&panel, cell)?;
                }
            }
        }
        top += h as i32;
    }
    Ok(())
});
