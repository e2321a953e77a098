//! Fig. 19: the critical noise D_c where the largest Lyapunov exponent changes sign, against μ0
//! (a), τ (b), λ (c) and r (d), with its uncertainty from the standard errors; values without a
//! sign change in the searched range are said so on the panel, never drawn as a made-up value.
//!
//! Rendering only: the data and its computation are [`trirhythm_paper::fig19_critical_noise`].

use super::lle::{draw_panel, panel_height, PANEL_WIDTH};
use trirhythm_paper::fig19_critical_noise::Fig19;

picture!(Fig19, |self, root| size (2 * PANEL_WIDTH, 2 * panel_height(&self.panels)), draw {
    for (area, panel) in root.split_evenly((2, 2)).iter().zip(&self.panels) {
        draw_panel(area, panel)?;
    }
    Ok(())
});
