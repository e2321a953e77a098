//! Fig. 13: the stationary P(A) for several restitution coefficients at μ0 = 0.005 (a) and
//! μ0 = 0.2 (b): the averaged theory (Eq. 27, both variants) against Monte Carlo ensembles of
//! the fractional system (Eq. 1) and of its integer-order equivalent (Eq. 5), with error bars,
//! distances and the stationarity verdict of every ensemble. Drawn as a 4 × 2 grid: (a) in the
//! left column, (b) in the right, each panel on the part of the A axis where its densities
//! are, one legend below.
//!
//! Rendering only: the data and its computation are [`trirhythm_paper::fig13_pdf_restitution`].

use super::montecarlo::{
    amplitude_key, amplitude_legend, draw_amplitude_columns, two_columns, PANEL,
};
use trirhythm_paper::fig13_pdf_restitution::Fig13;

picture!(Fig13, |self, root| key amplitude_key(&self.panels), size two_columns(&self.panels), draw {
    let rows = self.panels.len().div_ceil(2) as u32;
    let (grid, strip) = root.split_vertically(rows * PANEL.1);
    draw_amplitude_columns(&grid, &self.panels, 2)?;
    amplitude_legend(&self.panels).draw(&strip)
});
