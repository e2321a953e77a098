//! Fig. 13: the stationary P(A) for several restitution coefficients at μ0 = 0.005 (a) and
//! μ0 = 0.2 (b): the averaged theory (Eq. 27, both variants) against Monte Carlo ensembles of
//! the fractional system (Eq. 1) and of its integer-order equivalent (Eq. 5), with error bars,
//! distances and the stationarity verdict of every ensemble.
//!
//! Rendering only: the data and its computation are [`trirhythm_paper::fig13_pdf_restitution`].

use super::montecarlo::{draw_amplitude_grid, two_rows_of_four, PANEL};
use trirhythm_paper::fig13_pdf_restitution::Fig13;

picture!(Fig13, |self, root| size two_rows_of_four(&self.panels), draw {
    draw_amplitude_grid(root, &self.panels, (2, 4), PANEL.1)
});
