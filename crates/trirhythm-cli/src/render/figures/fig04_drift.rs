//! Fig. 4: the averaged drift f(A0) (Eq. 18) for four parameter sets, its zones and roots.
//!
//! f > 0 means the amplitude grows (energy uptake); f < 0 that it decays. The paper labels
//! f > 0 "dissipation"; the figure labels by the physics and says so in its notes.
//!
//! Rendering only: the data and its computation are [`trirhythm_paper::fig04_drift`].

use crate::render::plot::{
    chart, framed, padded_range, pe, pxi, rich_text, Backend, ChartSize, LegendStrip, Symbol, LABEL,
};
use anyhow::Result;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use trirhythm_paper::fig04_drift::{cycle_names, Fig04, Panel};

/// The legend below the panels (it holds for every panel).
fn key() -> LegendStrip {
    LegendStrip {
        entries: vec![
            (
                Symbol::Swatch(UP),
                "f > 0: amplitude grows (energy uptake)".into(),
            ),
            (
                Symbol::Swatch(DOWN),
                "f < 0: amplitude decays (dissipation)".into(),
            ),
            (Symbol::Line(BLACK), "f(A_0) at the panel's r".into()),
            (
                Symbol::Dashed(GREY),
                "same control parameters, r = 1".into(),
            ),
            (Symbol::Dot(BLACK), "stable cycle (df/dA_{0} < 0)".into()),
            (Symbol::Ring(BLACK), "unstable cycle".into()),
        ],
    }
}

const UP: RGBColor = RGBColor(250, 200, 200);
const DOWN: RGBColor = RGBColor(200, 215, 250);
const GREY: RGBColor = RGBColor(120, 120, 120);

picture!(Fig04, |self, root| size (1400, 1000 + key().height(1400)), draw {
    let h = root.dim_in_pixel().1;
    let (panels, strip) = root.split_vertically(h - key().height(1400));
    key().draw(&strip)?;
    let areas = panels.split_evenly((2, 2));
    // roots are named after the r = 1 panel's (see `cycle_names`)
    let reference = self
        .panels
        .iter()
        .find(|p| p.r == 1.0)
        .map_or(&[][..], |p| &p.cycles[..]);
    for (area, p) in areas.iter().zip(&self.panels) {
        draw_panel(area, p, &cycle_names(reference, &p.cycles))?;
    }
    Ok(())
});

/// The right end of a panel's chart: just beyond the outermost root of the r = 1 curve.
fn x_end(p: &Panel) -> f64 {
    (p.outermost_at_r1 * 1.06).min(14.0)
}

/// One panel: f(A0) with its zones, the r = 1 reference, the cycles, a zoom on the inner roots.
fn draw_panel<DB: Backend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    p: &Panel,
    names: &[String],
) -> Result<()> {
    let x_end = x_end(p);
    let x = 0.0..x_end;
    // The range shows the roots' neighbourhood; the steep fall beyond is cut at four
    // times the largest |f| met before the outermost root.
    let shown_vals = p
        .curve
        .iter()
        .chain(p.reference.iter().flatten())
        .filter(|c| c.0 <= x_end);
    let inner = shown_vals
        .clone()
        .filter(|c| c.0 <= x_end / 1.06)
        .fold(0.0f64, |m, c| m.max(c.1.abs()));
    let y = padded_range(shown_vals.map(|c| c.1.max(-4.0 * inner)));
    let [a0, b0, g0, d0] = p.cp;
    let caption = format!(
        "({}) r = {}, (α0,β0,γ0,δ0) = ({a0}, {b0}, {g0:e}, {d0:e})",
        p.label, p.r
    );
    let shown = |pts: &[(f64, f64)]| -> Vec<(f64, f64)> {
        pts.iter()
            .copied()
            .filter(|c| c.0 <= x_end && c.1 >= y.start)
            .collect()
    };
    let mut c = chart(area, &caption, x, y.clone(), "A_0", "f(A_0)")?;
    let (up, down) = (UP, DOWN);
    c.draw_series(AreaSeries::new(
        shown(&p.curve).into_iter().map(|(a, f)| (a, f.max(0.0))),
        0.0,
        up.mix(0.8),
    ))
    .map_err(pe)?
    .label("f > 0: amplitude grows (energy uptake)")
    .legend(move |(x, y)| Rectangle::new([(x, y - 5), (x + 15, y + 5)], up.filled()));
    c.draw_series(AreaSeries::new(
        shown(&p.curve).into_iter().map(|(a, f)| (a, f.min(0.0))),
        0.0,
        down.mix(0.8),
    ))
    .map_err(pe)?
    .label("f < 0: amplitude decays (dissipation)")
    .legend(move |(x, y)| Rectangle::new([(x, y - 5), (x + 15, y + 5)], down.filled()));
    {
        let clipped: Vec<(f64, f64)> = shown(p.reference.as_deref().unwrap_or(&[]))
            .into_iter()
            .filter(|&(_, f)| f >= y.start && f <= y.end)
            .collect();
        c.draw_series(DashedLineSeries::new(
            clipped,
            6,
            4,
            RGBColor(120, 120, 120).stroke_width(1),
        ))
        .map_err(pe)?
        .label("same control parameters, r = 1")
        .legend(|(x, y)| PathElement::new([(x, y), (x + 15, y)], RGBColor(120, 120, 120)));
    }
    c.draw_series(LineSeries::new(shown(&p.curve), BLACK.stroke_width(2)))
        .map_err(pe)?
        .label("f(A0) at the panel's r")
        .legend(|(x, y)| PathElement::new([(x, y), (x + 15, y)], BLACK.stroke_width(2)));
    c.draw_series(LineSeries::new(
        [(0.0, 0.0), (x_end, 0.0)],
        BLACK.stroke_width(1),
    ))
    .map_err(pe)?;
    let marks = |stable: bool| {
        p.cycles
            .iter()
            .filter(move |cy| cy.stable == stable)
            .map(move |cy| {
                let fill = if stable {
                    BLACK.filled()
                } else {
                    WHITE.filled()
                };
                EmptyElement::at((cy.amplitude, 0.0))
                    + Circle::new((0, 0), 6, fill)
                    + Circle::new((0, 0), 6, BLACK.stroke_width(2))
            })
    };
    c.draw_series(marks(true))
        .map_err(pe)?
        .label("stable cycle (df/dA0 < 0)")
        .legend(|(x, y)| Circle::new((x + 7, y), 5, BLACK.filled()));
    c.draw_series(marks(false))
        .map_err(pe)?
        .label("unstable cycle")
        .legend(|(x, y)| Circle::new((x + 7, y), 5, BLACK.stroke_width(2)));
    // the roots' names, just above each root
    let (bx, by) = area.get_base_pixel();
    for (cy, name) in p.cycles.iter().zip(names) {
        let (x, y) = c.backend_coord(&(cy.amplitude, 0.0));
        rich_text(
            area,
            name,
            (x - bx, y - by - pxi(9)),
            Pos::new(HPos::Center, VPos::Bottom),
            LABEL,
            BLACK,
            false,
        )?;
    }
    draw_zoom(area, &c, p, &y, x_end)
}

/// Where the small-amplitude part is flattened by the scale of the steep fall (the panel's
/// range `y`), an inset shows it at its own scale (roots there, or their absence, visible).
/// It goes where it hides least of the panel: of the plotting area's corners and the middles
/// of its top and bottom, the place covering the fewest points of the curves, no root and no
/// root's name.
fn draw_zoom<DB: Backend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    c: &ChartContext<'_, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    p: &Panel,
    y: &std::ops::Range<f64>,
    x_end: f64,
) -> Result<()> {
    let span = y.end - y.start;
    let zoom_end = p
        .curve
        .iter()
        .find(|c| c.1.abs() > 0.1 * span)
        .map_or(x_end, |c| c.0);
    if zoom_end > 0.4 * x_end && zoom_end < x_end {
        let (rx, ry) = c.plotting_area().get_pixel_range();
        let w = ((rx.end - rx.start) as f64 * 0.5) as i32;
        // the tallest inset (of three heights) that hides no root, else the shortest
        let mut best = None;
        for share in [0.48, 0.4, 0.34] {
            let h = ((ry.end - ry.start) as f64 * share) as i32;
            let gap = pxi(6);
            let (left, right) = (rx.start + gap, rx.end - gap - w);
            let (top, bottom) = (ry.start + gap, ry.end - gap - h);
            let middle = (rx.start + rx.end - w) / 2;
            let places = [
                (left, bottom),
                (right, bottom),
                (middle, bottom),
                (left, top),
                (right, top),
                (middle, top),
            ];
            let cost = |&(x0, y0): &(i32, i32)| -> u64 {
                let m = pxi(4);
                let hit = |(x, y): (i32, i32)| {
                    x >= x0 - m && x <= x0 + w + m && y >= y0 - m && y <= y0 + h + m
                };
                let curves = p
                    .curve
                    .iter()
                    .chain(p.reference.iter().flatten())
                    .filter(|q| q.0 <= x_end && y.contains(&q.1))
                    .filter(|q| hit(c.backend_coord(q)))
                    .count() as u64;
                let roots = p
                    .cycles
                    .iter()
                    .filter(|cy| {
                        let (x, y) = c.backend_coord(&(cy.amplitude, 0.0));
                        hit((x, y)) || hit((x, y - pxi(30)))
                    })
                    .count() as u64;
                curves + 10_000 * roots
            };
            if let Some((place, cost)) = places.iter().map(|q| (*q, cost(q))).min_by_key(|q| q.1) {
                best = Some((place, h));
                if cost < 10_000 {
                    break;
                }
            }
        }
        let Some(((ax, ay), h)) = best else {
            return Ok(());
        };
        let (bx, by) = area.get_base_pixel();
        let inset = area
            .clone()
            .shrink((ax - bx, ay - by), (w as u32, h as u32));
        inset.fill(&WHITE).map_err(pe)?;
        let pts: Vec<(f64, f64)> = p
            .curve
            .iter()
            .copied()
            .filter(|c| c.0 <= zoom_end)
            .collect();
        let yz = padded_range(pts.iter().map(|c| c.1).chain([0.0]));
        let mut z = framed(
            &inset,
            &format!("zoom: A_0 ≤ {zoom_end:.1}"),
            (0.0..zoom_end, yz),
            ("", ""),
            ChartSize::Inset,
        )?;
        z.draw_series(LineSeries::new(
            [(0.0, 0.0), (zoom_end, 0.0)],
            BLACK.stroke_width(1),
        ))
        .map_err(pe)?;
        z.draw_series(LineSeries::new(pts, BLACK.stroke_width(2)))
            .map_err(pe)?;
        z.draw_series(
            p.cycles
                .iter()
                .filter(|cy| cy.amplitude <= zoom_end)
                .map(|cy| {
                    let fill = if cy.stable { BLACK } else { WHITE };
                    EmptyElement::at((cy.amplitude, 0.0))
                        + Circle::new((0, 0), 5, fill.filled())
                        + Circle::new((0, 0), 5, BLACK.stroke_width(2))
                }),
        )
        .map_err(pe)?;
    }
    Ok(())
}
