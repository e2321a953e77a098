//! Drawing of the oscillation-boundary panels (Figs 15, 16): the shaded rest region under the
//! simulated boundary, each method's curve in its style, one colour per method or, in a family
//! panel, per parameter value.
//!
//! Drawing only: the boundaries and their distances are [`trirhythm_paper::boundary`].

use crate::render::legend::outline;
use crate::render::plot::{
    chart, draw_line, draw_markers, pe, pxi, series, stroke, Backend, Dash, LegendStrip, Marker,
    SeriesStyle, Symbol, PALETTE,
};
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

/// Draw one panel (its legend below it when `strip` > 0): the shaded rest region under the simulated boundary, then every curve
/// (simulation solid with its bracket as tick marks, averaging dashed, exact dotted or as
/// markers where it has a single point).
pub fn draw_panel<DB: Backend>(
    area: &DrawingArea<DB, Shift>,
    panel: &Panel,
    strip: u32,
    differences: bool,
) -> Result<()> {
    // the legend in a strip `strip` pixels high below the chart (none when 0), outside the data
    let h = area.dim_in_pixel().1;
    let (area, below) = area.split_vertically(h.saturating_sub(strip));
    if strip > 0 {
        legend_of(&[panel]).draw(&below)?;
    }
    // (a panel whose members lie close together: its chart above, their differences below)
    let (area, lower) = if differences {
        let (a, b) = area.split_vertically(area.dim_in_pixel().1 * 2 / 3);
        (a, Some(b))
    } else {
        (area, None)
    };
    let area = &area;
    let top = panel
        .curves
        .iter()
        .flat_map(|c| c.points.iter())
        .filter(|q| q.side == Side::Boundary)
        .map(|q| q.y)
        .fold(0.0f64, f64::max);
    let (y0, y1) = (0.0, (1.12 * top).min(panel.y_range.1).max(1e-3));
    // the axes a little beyond the data, so that no mark at a corner (the exact boundary at
    // λ = 1, μ0 = 0) sits on the ticks
    let pad = 0.06 * (panel.x_range.1 - panel.x_range.0);
    let mut c = chart(
        area,
        &panel.caption,
        panel.x_range.0 - pad..panel.x_range.1 + pad,
        y0 - 0.06 * (y1 - y0)..y1,
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
                .map_err(pe)?;
        }
    }
    // a family's first member (the reference, e.g. λ = 1) drawn last, on top of the others
    // that run close to it
    let mut order: Vec<&Curve> = panel.curves.iter().collect();
    order.sort_by_key(|c| std::cmp::Reverse(c.member));
    for curve in order {
        draw_curve(&mut c, curve)?;
    }
    if let Some(lower) = &lower {
        draw_differences(lower, panel)?;
    }
    Ok(())
}

/// A family member's boundary (`method`) as (x, μ0) points.
fn boundary_of(panel: &Panel, member: usize, method: &str) -> Vec<(f64, f64)> {
    panel
        .curves
        .iter()
        .filter(|c| c.member == Some(member) && c.method == method)
        .flat_map(|c| c.points.iter())
        .filter(|q| q.side == Side::Boundary)
        .map(|q| (q.x, q.y))
        .collect()
}

/// `pts` at `x`, linearly interpolated (none outside them).
fn at(pts: &[(f64, f64)], x: f64) -> Option<f64> {
    pts.windows(2).find_map(|w| {
        let ((xa, ya), (xb, yb)) = (w[0], w[1]);
        let (lo, hi) = (xa.min(xb), xa.max(xb));
        (x >= lo - 1e-12 && x <= hi + 1e-12).then(|| {
            if (xb - xa).abs() < 1e-15 {
                ya
            } else {
                ya + (yb - ya) * (x - xa) / (xb - xa)
            }
        })
    })
}

/// Below a family panel whose members' boundaries lie close together, on `area`: each
/// member's boundary less the first member's (simulation solid, averaging dashed, in the
/// member's colour with its marker), so that the members' differences are read.
fn draw_differences<DB: Backend>(area: &DrawingArea<DB, Shift>, panel: &Panel) -> Result<()> {
    let members = panel
        .curves
        .iter()
        .filter_map(|c| c.member)
        .max()
        .map_or(0, |m| m + 1);
    let mut lines: Vec<(Vec<(f64, f64)>, SeriesStyle)> = Vec::new();
    for method in ["simulation", "averaging"] {
        let reference = boundary_of(panel, 0, method);
        for m in 1..members {
            let d: Vec<(f64, f64)> = boundary_of(panel, m, method)
                .into_iter()
                .filter_map(|(x, y)| at(&reference, x).map(|r| (x, y - r)))
                .collect();
            if d.len() >= 2 {
                let dash = if method == "simulation" {
                    Dash::Solid
                } else {
                    Dash::Dashed
                };
                let st = SeriesStyle {
                    colour: PALETTE[m % PALETTE.len()],
                    dash,
                    marker: series(m).marker,
                };
                lines.push((d, st));
            }
        }
    }
    let ys = lines.iter().flat_map(|(d, _)| d.iter().map(|p| p.1));
    let (lo, hi) = ys.fold((0.0f64, 0.0f64), |(a, b), y| (a.min(y), b.max(y)));
    if lines.is_empty() || hi - lo <= 0.0 {
        return Ok(());
    }
    let pad = 0.08 * (hi - lo);
    let xpad = 0.06 * (panel.x_range.1 - panel.x_range.0);
    let first = short_label(
        &panel
            .curves
            .iter()
            .find(|c| c.member == Some(0) && !c.label.is_empty())
            .map_or(String::new(), |c| c.label.clone()),
    )
    .to_string();
    let mut z = chart(
        area,
        "",
        panel.x_range.0 - xpad..panel.x_range.1 + xpad,
        (lo - pad).min(0.0)..hi + pad,
        &panel.x_desc,
        &format!("Δμ0 from {first}"),
    )?;
    z.draw_series(std::iter::once(PathElement::new(
        [(panel.x_range.0 - xpad, 0.0), (panel.x_range.1 + xpad, 0.0)],
        BLACK.stroke_width(stroke(2)),
    )))
    .map_err(pe)?;
    for (d, st) in &lines {
        draw_line(&z, d, *st, if st.dash == Dash::Solid { 3 } else { 2 })?;
        let every: Vec<(f64, f64)> = d.iter().copied().step_by(4).collect();
        draw_markers(&z, &every, *st)?;
    }
    Ok(())
}

/// How a curve is drawn: simulation solid (a family member with its [`series`] marker),
/// averaging dashed, exact dotted with upright crosses (a mark no member has).
fn style(curve: &Curve) -> SeriesStyle {
    let colour = colour(curve);
    match curve.method.as_str() {
        "simulation" => SeriesStyle {
            colour,
            dash: Dash::Solid,
            marker: curve.member.map_or(Marker::None, |i| series(i).marker),
        },
        // (a family member's averaging line carries its member's marker too: the dashed
        // lines part in greyscale)
        "averaging" => SeriesStyle {
            colour,
            dash: Dash::Dashed,
            marker: curve.member.map_or(Marker::None, |i| series(i).marker),
        },
        _ => SeriesStyle {
            colour,
            dash: Dash::Dotted,
            marker: Marker::Plus,
        },
    }
}

/// The legend of `panels` together: the shaded rest region, each labelled curve in its
/// style, and for a family panel the methods' styles (an entry met twice listed once).
pub fn legend_of(panels: &[&Panel]) -> LegendStrip {
    let mut entries: Vec<(Symbol, String)> = Vec::new();
    for panel in panels {
        for (symbol, text) in legend_entries(panel) {
            if !entries.iter().any(|(_, t)| *t == text) {
                entries.push((symbol, text));
            }
        }
    }
    LegendStrip { entries }
}

/// A panel's legend entries (see [`legend_of`]).
fn legend_entries(panel: &Panel) -> Vec<(Symbol, String)> {
    let mut entries = Vec::new();
    if panel.curves.iter().any(|c| c.rest_below) {
        entries.push((
            Symbol::Swatch(SHADE),
            "no oscillation (simulated)".to_string(),
        ));
    }
    for curve in panel.curves.iter().filter(|c| !c.label.is_empty()) {
        let points = curve
            .points
            .iter()
            .filter(|q| q.side == Side::Boundary)
            .count();
        let symbol = match points {
            0 => continue,
            1 => Symbol::Shape(Marker::Diamond, colour(curve), true),
            // (an unmarked simulated line carries a dot at each point, as [`draw_curve`] draws)
            _ if curve.method == "simulation" && style(curve).marker == Marker::None => {
                Symbol::DottedLine(colour(curve))
            }
            _ => Symbol::Series(style(curve)),
        };
        // (a label's formula after ": " goes to the caption key, [`key_of`])
        entries.push((symbol, short_label(&curve.label).to_string()));
    }
    if panel.is_family() {
        let plain = |dash, marker| {
            Symbol::Series(SeriesStyle {
                colour: BLACK,
                dash,
                marker,
            })
        };
        entries.push((plain(Dash::Solid, Marker::None), "solid: simulation".into()));
        entries.push((
            plain(Dash::Dashed, Marker::None),
            "dashed: averaging".into(),
        ));
        // the exact boundaries: dotted with upright crosses, or a diamond where a curve has
        // one point
        let exact_points = |many: bool| {
            panel.curves.iter().any(|c| {
                let n = c.points.iter().filter(|q| q.side == Side::Boundary).count();
                !matches!(c.method.as_str(), "simulation" | "averaging") && n > 0 && (n > 1) == many
            })
        };
        if exact_points(true) {
            entries.push((
                plain(Dash::Dotted, Marker::Plus),
                "dotted with +: exact".into(),
            ));
        }
        if exact_points(false) {
            entries.push((
                Symbol::Shape(Marker::Diamond, BLACK, true),
                "exact (one point)".into(),
            ));
        }
    }
    entries
}

/// A curve's label as its legend entry gives it: the words before a formula (": ").
fn short_label(label: &str) -> &str {
    label.split(": ").next().unwrap_or(label)
}

/// The caption's key to `panels`' drawing: the formulas the legend leaves out (a label's
/// part after ": ", the exact boundary's damped frequency ω_d defined), and what the marks
/// of the exact boundary are (+ on its dotted line; ◆ where it is a single point).
pub fn key_of(panels: &[Panel]) -> Vec<String> {
    let mut key: Vec<String> = Vec::new();
    let curves = || panels.iter().flat_map(|p| p.curves.iter());
    for curve in curves() {
        if let Some((head, formula)) = curve.label.split_once(": ") {
            let mut line = format!("{head}: {formula}");
            if formula.contains("ω_{d}") {
                line.push_str(", with ω_{d}² = ω0² − μ0²/4 the damped frequency");
            }
            if !key.contains(&line) {
                key.push(line);
            }
        }
    }
    let exact = |c: &&Curve| !matches!(c.method.as_str(), "simulation" | "averaging");
    let points = |c: &Curve| c.points.iter().filter(|q| q.side == Side::Boundary).count();
    let family = panels.iter().any(|p| p.is_family());
    let many = |free: bool| {
        curves()
            .filter(exact)
            .any(|c| points(c) > 1 && (c.method == "exact, no wall") == free)
    };
    let single = curves().filter(exact).any(|c| points(c) == 1);
    let mut marks: Vec<&str> = Vec::new();
    if !family {
        if curves().any(|c| c.method == "simulation" && c.member.is_none() && points(c) > 1) {
            marks.push(
                "● on the solid black line: the simulated boundary, one dot per simulated point",
            );
        }
        if many(false) {
            marks.push(
                "+ on a dotted line in colour: the exact boundary with the wall along the axis",
            );
        }
        if many(true) {
            marks.push(
                "grey + on a grey dotted line (\"exact without the wall\"): the exact \
                 linearisation at U = 0 of the oscillator with the wall removed (no impacts), \
                 drawn for reference only",
            );
        }
        if single {
            marks.push(
                "◆ (a filled diamond): the exact linearisation with the wall where it is a \
                 single point (λ = 1 only)",
            );
        }
    } else {
        let mut drawn = Vec::new();
        if single {
            drawn.push("the filled diamond ◆ (one point: with the wall, λ = 1 only)");
        }
        if many(false) || many(true) {
            drawn.push("the dotted line with upright crosses + (along the axis)");
        }
        if !drawn.is_empty() {
            key.push(format!(
                "the caption's \"○ / ×: exact linearisation\" is drawn here as {}; in this \
                 drawing ○ and × are markers of the r and λ family members, not the exact \
                 linearisation",
                drawn.join(" and ")
            ));
        }
    }
    if !marks.is_empty() {
        key.push(format!("marks as drawn: {}", marks.join("; ")));
    }
    if panels.iter().any(|p| p.is_family() && p.x_desc == "r") {
        key.push(
            "under the family panel in r, its members' differences: each member's boundary \
             less the first member's (Δμ0 against r; solid simulation, dashed averaging, in \
             the member's colour and marker; the black line Δμ0 = 0 is the first member)"
                .to_string(),
        );
    }
    if panels.iter().any(|p| p.is_family()) {
        key.push(
            "the simulated curves of a family carry their markers at every fourth point, \
             staggered between the members, so that coinciding lines stay apart"
                .to_string(),
        );
    }
    key
}

/// One curve in its method's style ([`style`]), a single point as a marked cross.
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
    if pts.len() == 1 {
        let diamond = outline(Marker::Diamond, pxi(5));
        c.draw_series(std::iter::once(
            EmptyElement::at(pts[0])
                + Polygon::new(diamond.clone(), color.filled())
                + PathElement::new(diamond, WHITE.stroke_width(stroke(1))),
        ))
        .map_err(pe)?;
        return Ok(());
    }
    let st = style(curve);
    let width = if curve.method == "averaging" { 2 } else { 3 };
    draw_line(c, &pts, st, width)?;
    match (curve.method.as_str(), st.marker) {
        ("simulation", Marker::None) => {
            c.draw_series(pts.iter().map(|&p| Circle::new(p, pxi(3), color.filled())))
                .map_err(pe)?;
        }
        (_, Marker::None) => {}
        // (an averaging line's markers at every other point: its line stays readable)
        ("averaging", _) => {
            let every: Vec<(f64, f64)> = pts.iter().copied().skip(1).step_by(2).collect();
            draw_markers(c, &every, st)?
        }
        // (a family's simulated lines may coincide: each member's markers at every fourth
        // point, starting at its own, so that the members' markers stand apart)
        ("simulation", _) if curve.member.is_some() => {
            let start = curve.member.unwrap_or(0) % 4;
            let every: Vec<(f64, f64)> = pts.iter().copied().skip(start).step_by(4).collect();
            draw_markers(c, &every, st)?
        }
        _ => draw_markers(c, &pts, st)?,
    }
    Ok(())
}
