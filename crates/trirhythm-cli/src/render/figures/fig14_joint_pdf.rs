//! Fig. 14: the joint density P(U, U̇) for four restitution coefficients — the averaged
//! theory's Eq. (30–31) (left) against the Monte Carlo histogram of Eq. (1) (right), a row per r,
//! as heat maps with one colour scale per r, the Hellinger distance between them and the
//! stationarity verdict of each ensemble.
//!
//! Rendering only: the data and its computation are [`trirhythm_paper::fig14_joint_pdf`].

use crate::render::plot::{chart, colour_bar_vertical, pe, viridis, Backend};
use anyhow::Result;
use plotters::coord::Shift;
use plotters::prelude::*;
use trirhythm_paper::fig14_joint_pdf::{refine, Fig14, FINE};

/// A row (one r): the theory's map, the Monte Carlo map, the row's colour bar.
const PANEL: (u32, u32) = (610, 400);
const BAR: u32 = 180;
/// Decades of the logarithmic colour scale.
const DECADES: f64 = 3.0;

/// A heat map of `values` on the cells of (`u_edges`, `v_edges`).
fn heat<DB: Backend>(
    area: &DrawingArea<DB, Shift>,
    caption: &str,
    (u_edges, v_edges): (&[f64], &[f64]),
    values: &[Vec<f64>],
    top: f64,
) -> Result<()> {
    let (u0, u1) = (u_edges[0], *u_edges.last().unwrap_or(&1.0));
    let (v0, v1) = (v_edges[0], *v_edges.last().unwrap_or(&1.0));
    let mut c = chart(area, caption, u0..u1, v0..v1, "U", "dU/dt")?;
    let cells = u_edges.windows(2).enumerate().flat_map(|(i, u)| {
        v_edges.windows(2).enumerate().filter_map(move |(k, v)| {
            let x = values[i][k];
            // three decades below the panel's top, logarithmic: rings and creeping phases alike
            (x > top * 1e-3).then(|| {
                Rectangle::new(
                    [(u[0], v[0]), (u[1], v[1])],
                    viridis(((x / top).log10() + DECADES) / DECADES).filled(),
                )
            })
        })
    });
    c.draw_series(cells).map_err(pe)?;
    Ok(())
}

// One row per r: theory left, Monte Carlo right (the same axes), the row's colour scale on
// the right.
picture!(Fig14, |self, root| size (2 * PANEL.0 + BAR, 4 * PANEL.1), draw {
    let rows = root.split_evenly((4, 1));
    for (row, (p, label)) in rows
        .iter()
        .zip(self.panels.iter().zip([("a", "b"), ("c", "d"), ("e", "f"), ("g", "h")]))
    {
        let (label, mc_label) = label;
        let (maps, bar) = row.split_horizontally(2 * PANEL.0);
        let (left, right) = maps.split_horizontally(PANEL.0);
        let top = p
            .theory
            .iter()
            .chain(&p.mc)
            .flatten()
            .copied()
            .fold(0.0f64, f64::max)
            .max(1e-300);
        let fine = (refine(&p.u_edges, FINE), refine(&p.v_edges, FINE));
        heat(
            &left,
            // (the mass outside the window is in the caption)
            &format!("({label}) r = {}, theory", p.r),
            (&fine.0, &fine.1),
            &p.theory_fine,
            top,
        )?;
        heat(
            &right,
            // a non-stationary map decides nothing: its title says only that (H and the share
            // outside the window are in the caption)
            &if p.stationary {
                format!(
                    "({mc_label}) r = {}, Monte Carlo{}: H = {:.2}",
                    p.r,
                    if p.estimator == "wells" { " (wells)" } else { "" },
                    p.hellinger
                )
            } else {
                format!("({mc_label}) r = {}, Monte Carlo: not stationary", p.r)
            },
            (&p.u_edges, &p.v_edges),
            &p.mc,
            top,
        )?;
        colour_bar_vertical(
            &bar,
            "log₁₀ P(U, dU/dt)",
            top.log10() - DECADES,
            top.log10(),
        )?;
    }
    Ok(())
});
