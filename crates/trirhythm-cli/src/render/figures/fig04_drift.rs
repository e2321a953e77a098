//! Fig. 4: the averaged drift f(A0) (Eq. 18) for four parameter sets, its zones and roots.
//!
//! f > 0 means the amplitude grows (energy uptake); f < 0 that it decays. The paper labels
//! f > 0 "dissipation"; the figure labels by the physics and says so in its notes.
//!
//! Rendering only: the data and its computation are [`trirhythm_paper::fig04_drift`].

use crate::render::plot::{
    chart, font_px, padded_range, pe, pxi, rich_text, rich_width, times_ten, Backend, LegendStrip,
    Symbol, LABEL,
};
use anyhow::Result;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use trirhythm_paper::fig04_drift::{cycle_names, Fig04, Panel};

/// The legend below the panels (it holds for every panel).
fn key() -> LegendStrip {
    LegendStrip {
        entries: vec![
            (Symbol::Swatch(UP), "f > 0: amplitude grows".into()),
            (Symbol::Swatch(DOWN), "f < 0: amplitude decays".into()),
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

const UP: RGBColor = RGBColor(253, 222, 218);
const DOWN: RGBColor = RGBColor(150, 180, 225);
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
    // roots are named after their panel's own r = 1 curve's (see `cycle_names`), or the
    // r = 1 panel's where a panel has none
    let fallback = self
        .panels
        .iter()
        .find(|p| p.r == 1.0)
        .map_or(vec![], |p| p.cycles.clone());
    for (area, p) in areas.iter().zip(&self.panels) {
        let reference = p.reference_cycles().unwrap_or_else(|| fallback.clone());
        draw_panel(area, p, &cycle_names(&reference, &p.cycles))?;
    }
    // the zooms continue the lettering: (e), (f)
    for ((area, p), letter) in areas[4..].iter().zip(zoomed).zip(["e", "f"]) {
        draw_zoom(area, p, letter)?;
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
    .label("f > 0: amplitude grows")
    .legend(move |(x, y)| Rectangle::new([(x, y - 5), (x + 15, y + 5)], up.filled()));
    c.draw_series(AreaSeries::new(
        shown(&p.curve).into_iter().map(|(a, f)| (a, f.min(0.0))),
        0.0,
        down.mix(0.8),
    ))
    .map_err(pe)?
    .label("f < 0: amplitude decays")
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
    // the roots' names beside each root, each in a quadrant (up-right, up-left, down-right,
    // down-left; near, or a line further out), the quadrants chosen together so that the boxes cover the fewest points of
    // the curves, no box covers another and all stay inside the plotting area
    let (bx, by) = area.get_base_pixel();
    let (rx, ry) = c.plotting_area().get_pixel_range();
    let curve_px: Vec<(i32, i32)> = shown(&p.curve)
        .iter()
        .chain(shown(p.reference.as_deref().unwrap_or(&[])).iter())
        .filter(|q| q.1 <= y.end)
        .map(|q| c.backend_coord(q))
        .collect();
    let (pad, h) = (pxi(7), font_px(LABEL) as i32);
    let boxes: Vec<[[i32; 4]; 8]> = p
        .cycles
        .iter()
        .zip(names)
        .map(|(cy, name)| {
            let (x, y) = c.backend_coord(&(cy.amplitude, 0.0));
            let w = rich_width(name, LABEL) as i32;
            // each quadrant near the root, then a line further out
            [
                (x + pad, y - pad - h),
                (x - pad - w, y - pad - h),
                (x + pad, y + pad),
                (x - pad - w, y + pad),
                (x + pad, y - pad - 2 * h),
                (x - pad - w, y - pad - 2 * h),
                (x + pad, y + pad + h),
                (x - pad - w, y + pad + h),
            ]
            .map(|(l, t)| [l, t, l + w, t + h])
        })
        .collect();
    let cost = |b: &[i32; 4]| {
        let outside = b[0] < rx.start || b[2] > rx.end || b[1] < ry.start || b[3] > ry.end;
        let hits = curve_px
            .iter()
            .filter(|&&(qx, qy)| {
                qx >= b[0] - 2 && qx <= b[2] + 2 && qy >= b[1] - 2 && qy <= b[3] + 2
            })
            .count();
        hits + if outside { 100_000 } else { 0 }
    };
    let costs: Vec<[usize; 8]> = boxes.iter().map(|b| b.each_ref().map(cost)).collect();
    let n = boxes.len().min(5);
    let mut best = (usize::MAX, vec![0usize; n]);
    for code in 0..8usize.pow(n as u32) {
        let pick: Vec<usize> = (0..n).map(|i| code / 8usize.pow(i as u32) % 8).collect();
        let chosen: Vec<&[i32; 4]> = pick.iter().zip(&boxes).map(|(&k, b)| &b[k]).collect();
        // (the far places only where the near ones are taken)
        let mut total: usize = pick
            .iter()
            .zip(&costs)
            .map(|(&k, c)| c[k] + usize::from(k >= 4))
            .sum();
        for (i, a) in chosen.iter().enumerate() {
            for o in &chosen[i + 1..] {
                if o[0] < a[2] && a[0] < o[2] && o[1] < a[3] && a[1] < o[3] {
                    total += 10_000;
                }
            }
        }
        if total < best.0 {
            best = (total, pick);
        }
    }
    for ((k, b), name) in best.1.iter().zip(&boxes).zip(names) {
        let [l, _, _, bottom] = b[*k];
        rich_text(
            area,
            name,
            (l - bx, bottom - by),
            Pos::new(HPos::Left, VPos::Bottom),
            LABEL,
            BLACK,
            false,
        )?;
    }
    Ok(())
}

/// The zoom on panel `p`'s small-amplitude part ([`zoom_end`]), at its own scale (its roots,
/// or their absence, visible), as a panel of its own.
fn draw_zoom<DB: Backend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    p: &Panel,
    letter: &str,
) -> Result<()> {
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
            &format!("({letter}) ({}) enlarged: A_0 ≤ {zoom_end:.1}", p.label),
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
