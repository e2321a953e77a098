//! Fig. 15: the oscillation (Hopf) boundary μ0 against λ and against r for ω0 ∈ {0.9, 0.5, 0.3}
//! at D = 0 — by simulation (predictor–corrector from a small amplitude, bracketed), by
//! averaging (f′(0) = 0 of Eq. 18) and by the exact linearisation where it is exact — with the
//! non-oscillating region (below the simulated boundary) shaded as in the paper.
//!
//! The panel machinery ([`Panel`], [`Curve`], [`compute`], [`draw_panel`], [`distances`]) is
//! shared with Fig. 16.
//!
//! Rendering only: the data and its computation are [`trirhythm_paper::fig15_oscillation_boundaries`].

use super::boundary::draw_panel;
use trirhythm_paper::fig15_oscillation_boundaries::Fig15;

picture!(Fig15, |self, root| size (1400, 1500), draw {
    let areas = root.split_evenly((3, 2));
    for (i, (area, panel)) in areas.iter().zip(&self.panels).enumerate() {
        draw_panel(area, panel, i < 2)?;
    }
    Ok(())
});
