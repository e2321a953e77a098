//! Fig. 19: the sign of the largest Lyapunov exponent over (parameter, D) for μ0 (a), τ (b),
//! λ (c) and r (d), each cell decided with significance, from two starts, with the D_c brackets
//! drawn where a significant − → + change is located.
//!
//! Rendering only: the data and its computation are [`trirhythm_paper::fig19_critical_noise`].

use super::lle::{draw_sign_map, sign_strip, CHART_HEIGHT, PANEL_WIDTH};
use trirhythm_paper::fig19_critical_noise::Fig19;

picture!(Fig19, |self, root| size (2 * PANEL_WIDTH, 2 * CHART_HEIGHT + sign_strip().height(2 * PANEL_WIDTH) + 8), draw {
    let (maps, legend) = root.split_vertically(2 * CHART_HEIGHT);
    for (area, map) in maps.split_evenly((2, 2)).iter().zip(&self.panels) {
        draw_sign_map(area, map)?;
    }
    sign_strip().draw(&legend)
});
