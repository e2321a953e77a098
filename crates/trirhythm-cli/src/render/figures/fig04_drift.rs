//! Fig. 4: the averaged drift f(A0) (Eq. 18) for four parameter sets, its zones and roots.
//!
//! f > 0 means the amplitude grows (energy uptake); f < 0 that it decays. The paper labels
//! f > 0 "dissipation"; the figure labels by the physics and says so in its notes.
//!
//! Rendering only: the data and its computation are [`trirhythm_paper::fig04_drift`].

use crate::render::plot::{
    chart, padded_range, pe, pxi, rich_text, times_ten, Backend, LegendStrip, Symbol, LABEL,
};
use anyhow::Result;
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

/// Height of a row of panels.
const ROW: u32 = 500;

// The four panels in two rows, a third row with the zooms on the small-amplitude part where a
// panel's scale flattens it, and the key below.
picture!(Fig04, |self, root| size {
    let zooms = self.panels.iter().filter(|p| zoom_end(p).is_some()).count();
    (1400, ROW * (2 + u32::from(zooms > 0)) + key().height(1400))
}, draw {
    let zoomed: Vec<&Panel> = self.panels.iter().filter(|p| zoom_end(p).is_some()).collect();
    let rows = 2 + usize::from(!zoomed.is_empty());
    let (panels, strip) = root.split_vertically(ROW * rows as u32);
    key().draw(&strip)?;
    let areas = panels.split_evenly((rows, 2));
    // roots are named after the r = 1 panel's (see `cycle_names`)
    let reference = self
        .panels
        .iter()
        .find(|p| p.r == 1.0)
        .map_or(&[][..], |p| &p.cycles[..]);
    for (area, p) in areas.iter().zip(&self.panels) {
        draw_panel(area, p, &cycle_names(reference, &p.cycles))?;
    }
    for (area, p) in areas[4..].iter().zip(zoomed) {
        draw_zoom(area, p)?;
    }
    Ok(())
});

/// The right end of a panel's chart: just beyond the outermost root of the r = 1 curve.
fn x_end(p: &Panel) -> f64 {
    (p.outermost_at_r1 * 1.06).min(14.0)
}

/// A panel's range: A0 to just beyond the outermost root at r = 1, f around the roots'
/// neighbourhood (the steep fall beyond cut at four times the largest |f| met before the
/// outermost root).
fn frame(p: &Panel) -> (f64, std::ops::Range<f64>) {
    let x_end = x_end(p);
    let shown_vals = p
        .curve
        .iter()
        .chain(p.reference.iter().flatten())
        .filter(|c| c.0 <= x_end);
    let inner = shown_vals
        .clone()
        .filter(|c| c.0 <= x_end / 1.06)
        .fold(0.0f64, |m, c| m.max(c.1.abs()));
    (
        x_end,
        padded_range(shown_vals.map(|c| c.1.max(-4.0 * inner))),
    )
}

/// Where the small-amplitude part of a panel is flattened by the scale of the steep fall:
/// the A0 up to which |f| stays under a tenth of the panel's range, when that is a stretch
/// of the panel worth a zoom.
fn zoom_end(p: &Panel) -> Option<f64> {
    let (x_end, y) = frame(p);
    let span = y.end - y.start;
    let end = p
        .curve
        .iter()
        .find(|c| c.1.abs() > 0.1 * span)
        .map_or(x_end, |c| c.0);
    (end > 0.4 * x_end && end < x_end).then_some(end)
}

/// One panel: f(A0) with its zones, the r = 1 reference, the cycles, a zoom on the inner roots.
fn draw_panel<DB: Backend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    p: &Panel,
    names: &[String],
) -> Result<()> {
    let (x_end, y) = frame(p);
    let x = 0.0..x_end;
    // (α0, β0 are the same in every panel: the caption gives them)
    let [_, _, g0, d0] = p.cp;
    let caption = format!(
        "({}) r = {}, γ0 = {}, δ0 = {}",
        p.label,
        p.r,
        times_ten(g0, 4),
        times_ten(d0, 4)
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
        // in the quadrant the curve leaves free: it falls through a stable root (up-left to
        // down-right), so the name goes up-right; it rises through an unstable one
        let (dx, h) = if cy.stable {
            (pxi(7), HPos::Left)
        } else {
            (-pxi(7), HPos::Right)
        };
        rich_text(
            area,
            name,
            (x - bx + dx, y - by - pxi(7)),
            Pos::new(h, VPos::Bottom),
            LABEL,
            BLACK,
            false,
        )?;
    }
    Ok(())
}

/// The zoom on panel `p`'s small-amplitude part ([`zoom_end`]), at its own scale (its roots,
/// or their absence, visible), as a panel of its own.
fn draw_zoom<DB: Backend>(area: &DrawingArea<DB, plotters::coord::Shift>, p: &Panel) -> Result<()> {
    if let Some(zoom_end) = zoom_end(p) {
        let pts: Vec<(f64, f64)> = p
            .curve
            .iter()
            .copied()
            .filter(|c| c.0 <= zoom_end)
            .collect();
        let yz = padded_range(pts.iter().map(|c| c.1).chain([0.0]));
        let mut z = chart(
            area,
            &format!("({}) zoomed: A_0 ≤ {zoom_end:.1}", p.label),
            0.0..zoom_end,
            yz,
            "A_0",
            "f(A_0)",
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
                        + Circle::new((0, 0), pxi(5), fill.filled())
                        + Circle::new((0, 0), pxi(5), BLACK.stroke_width(2))
                }),
        )
        .map_err(pe)?;
    }
    Ok(())
}
