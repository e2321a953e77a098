//! What Figs 11, 13 and 14 share: Monte Carlo ensembles of Eq. (1) and Eq. (5) beside the
//! averaged theory's P(A) in both variants, with the distances, the modes and the stationarity
//! verdict of each run, and the drawing of one such amplitude panel.
//!
//! Drawing only: the ensembles and their comparison with the theory are [`trirhythm_paper::montecarlo`].

use crate::render::plot::{chart, pe, Backend, Symbol, PALETTE};
use anyhow::Result;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use trirhythm_paper::montecarlo::AmplitudePanel;

/// The legend entries of an amplitude panel's series.
pub fn legend_entries(systems: &[&str]) -> Vec<(Symbol, String)> {
    let mut e = vec![
        (
            Symbol::Line(PALETTE[0]),
            "theory, paper variant (Eq. 27)".to_string(),
        ),
        (
            Symbol::Dashed(PALETTE[2]),
            "theory, consistent variant".to_string(),
        ),
    ];
    for (i, s) in systems.iter().enumerate() {
        let c = mc_colour(i);
        e.push(if i == 0 {
            (Symbol::Ring(c), format!("Monte Carlo of {s} (± 1 s.e.)"))
        } else {
            (Symbol::Cross(c), format!("Monte Carlo of {s} (± 1 s.e.)"))
        });
    }
    e
}

fn mc_colour(i: usize) -> RGBColor {
    [PALETTE[1], PALETTE[3]][i % 2]
}

/// Draw one amplitude panel.
pub fn draw_amplitude_panel<DB: Backend>(
    area: &DrawingArea<DB, Shift>,
    p: &AmplitudePanel,
) -> Result<()> {
    let x_max = p
        .runs
        .iter()
        .filter_map(|r| r.edges.last().copied())
        .chain(p.theory.iter().filter_map(|t| t.1.last().copied()))
        .fold(1.0f64, f64::max);
    let finite_max =
        |it: &mut dyn Iterator<Item = f64>| it.filter(|v| v.is_finite()).fold(0.0f64, f64::max);
    let mc_max = finite_max(
        &mut p
            .runs
            .iter()
            .flat_map(|r| r.density.iter().zip(&r.stderr).map(|(d, s)| d + s.max(0.0))),
    );
    let theory_max = finite_max(&mut p.theory.iter().flat_map(|t| t.2.iter().copied()));
    // a theory spike far above the histograms would flatten them: it is cut, and its height
    // given in the caption
    let cut = theory_max > 3.0 * mc_max && mc_max > 0.0;
    let y_max = if cut {
        1.5 * mc_max
    } else {
        theory_max.max(mc_max)
    }
    .max(1e-3);
    let stationary = p.runs.iter().all(|r| r.stationary);
    let mut c = chart(area, &p.caption, 0.0..x_max, 0.0..y_max * 1.08, "A", "P(A)")?;
    // the verdicts, inside the panel at its upper right
    let status = [
        (!stationary).then(|| {
            (
                "Monte Carlo NOT stationary".to_string(),
                RGBColor(200, 0, 0),
            )
        }),
        cut.then(|| {
            (
                format!("theory peak {theory_max:.1}, cut"),
                RGBColor(90, 90, 90),
            )
        }),
    ];
    for (k, (text, colour)) in status.into_iter().flatten().enumerate() {
        let style = (crate::render::plot::FONT, 14)
            .into_font()
            .color(&colour)
            .pos(Pos::new(HPos::Right, VPos::Top));
        c.draw_series(std::iter::once(
            EmptyElement::at((x_max, y_max * 1.08))
                + Text::new(text, (-8, 6 + 18 * k as i32), style),
        ))
        .map_err(pe)?;
    }
    for (i, (_, xs, ys)) in p.theory.iter().enumerate() {
        let pts: Vec<(f64, f64)> = xs.iter().copied().zip(ys.iter().copied()).collect();
        if i == 0 {
            c.draw_series(LineSeries::new(pts, PALETTE[0].stroke_width(2)))
                .map_err(pe)?;
        } else {
            c.draw_series(DashedLineSeries::new(pts, 7, 5, PALETTE[2].stroke_width(2)))
                .map_err(pe)?;
        }
    }
    for (k, r) in p.runs.iter().enumerate() {
        let col = mc_colour(k);
        let mids: Vec<(f64, f64, f64)> = r
            .edges
            .windows(2)
            .zip(r.density.iter().zip(&r.stderr))
            .filter(|(_, (d, _))| **d > 0.0)
            .map(|(w, (&d, &s))| (0.5 * (w[0] + w[1]), d, if s.is_finite() { s } else { 0.0 }))
            .collect();
        c.draw_series(mids.iter().map(|&(x, d, s)| {
            PathElement::new([(x, (d - s).max(0.0)), (x, d + s)], col.stroke_width(1))
        }))
        .map_err(pe)?;
        if k == 0 {
            c.draw_series(
                mids.iter()
                    .map(|&(x, d, _)| Circle::new((x, d), 3, col.stroke_width(1))),
            )
            .map_err(pe)?;
        } else {
            c.draw_series(
                mids.iter()
                    .map(|&(x, d, _)| Cross::new((x, d), 3, col.stroke_width(1))),
            )
            .map_err(pe)?;
        }
    }
    Ok(())
}

/// A grid of amplitude panels with one legend strip below them.
pub fn draw_amplitude_grid<DB: Backend>(
    root: &DrawingArea<DB, Shift>,
    panels: &[AmplitudePanel],
    layout: (usize, usize),
    panel_height: u32,
) -> Result<()> {
    let (area, strip) = root.split_vertically(panel_height * layout.0 as u32);
    for (a, p) in area.split_evenly(layout).iter().zip(panels) {
        draw_amplitude_panel(a, p)?;
    }
    amplitude_legend(panels).draw(&strip)
}

/// Size of one amplitude panel in pixels (Figs 11 and 13).
pub const PANEL: (u32, u32) = (470, 400);

/// Size of a figure of two rows of four amplitude panels with the legend strip below.
pub fn two_rows_of_four(panels: &[AmplitudePanel]) -> (u32, u32) {
    let w = 4 * PANEL.0;
    (w, 2 * PANEL.1 + amplitude_legend(panels).height(w))
}

/// The legend of amplitude panels: both theories and every simulated system.
pub fn amplitude_legend(panels: &[AmplitudePanel]) -> crate::render::plot::LegendStrip {
    let systems: Vec<&str> = panels
        .first()
        .map(|p| p.runs.iter().map(|r| r.system.as_str()).collect())
        .unwrap_or_default();
    crate::render::plot::LegendStrip {
        entries: legend_entries(&systems),
    }
}
