//! Fig. 11: (a) limit-cycle amplitude against λ — the averaging's branches (f = 0, Eq. 18, at
//! D = 0) against long noise-free simulations of Eq. (1) from several initial amplitudes;
//! (b) the stationary P(A) for four λ — theory (both variants) against Monte Carlo of Eq. (1)
//! and Eq. (5), with error bars, distances and stationarity verdicts: (a) across the top with
//! its key beside it, (b) as a 2 × 2 grid below (each panel on the part of the A axis where
//! its densities are), one legend under all.
//!
//! Rendering only: the data and its computation are [`trirhythm_paper::fig11_amplitude_lambda`].

use super::fig05_branches::runs;
use super::montecarlo::{
    a_range, amplitude_key, amplitude_legend, draw_amplitude_panel, two_columns, PANEL,
};
use crate::render::plot::{chart, pe, PALETTE};
use plotters::prelude::*;
use trirhythm_paper::fig11_amplitude_lambda::Fig11;

/// Width of panel (a), the rest of its row being its key, and its height.
const A_WIDTH: u32 = 2 * PANEL.0 * 3 / 4;
const A_HEIGHT: u32 = 400;

picture!(Fig11, |self, root| key amplitude_key(&self.panels), size {
    let (w, h) = two_columns(&self.panels);
    (w, h + A_HEIGHT)
}, draw {
    let (top, rest) = root.split_vertically(A_HEIGHT);
    let (bottom, strip) = rest.split_vertically(self.panels.len().div_ceil(2) as u32 * PANEL.1);
    let (a_area, key) = top.split_horizontally(A_WIDTH);
    let amax = self
        .branches
        .branches
        .iter()
        .flat_map(|b| b.points.iter().map(|q| q.amplitude))
        .chain(self.settled.iter().map(|s| s.amplitude))
        .fold(1.0f64, f64::max);
    let mut c = chart(
        &a_area,
        "(a) limit-cycle amplitude against λ (D = 0)",
        // padded, so that no marker sits on an axis
        {
            let pad = 0.02 * (self.branches.stop - self.branches.start);
            self.branches.start - pad..self.branches.stop + pad
        },
        -0.04 * amax..amax * 1.08,
        "λ",
        "A",
    )?;
    for b in &self.branches.branches {
        for (stable, pts) in runs(&b.points) {
            if stable {
                c.draw_series(LineSeries::new(pts, PALETTE[0].stroke_width(2)))
                    .map_err(pe)?;
            } else {
                c.draw_series(DashedLineSeries::new(pts, 6, 4, PALETTE[1].stroke_width(2)))
                    .map_err(pe)?;
            }
        }
    }
    c.draw_series(
        self.settled
            .iter()
            .map(|s| Circle::new((s.lambda, s.amplitude), 6, PALETTE[2].stroke_width(2))),
    )
    .map_err(pe)?;
    // panel (a)'s key, beside it
    crate::render::plot::LegendStrip {
        entries: vec![
            (
                crate::render::plot::Symbol::Line(PALETTE[0]),
                "stable branch".into(),
            ),
            (
                crate::render::plot::Symbol::Dashed(PALETTE[1]),
                "unstable branch".into(),
            ),
            (
                crate::render::plot::Symbol::Ring(PALETTE[2]),
                "simulation of Eq. 1".into(),
            ),
        ],
    }
    .draw(&key.margin(crate::render::plot::px(20), 0, 0, 0))?;
    // (b): the four λ as a 2 × 2 grid, by rows
    let cells = bottom.split_evenly((self.panels.len().div_ceil(2), 2));
    // each λ on the part of the A axis where its densities are
    for (area, p) in cells.iter().zip(&self.panels) {
        draw_amplitude_panel(area, p, a_range(p))?;
    }
    amplitude_legend(&self.panels).draw(&strip)
});
