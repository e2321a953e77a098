//! Fig. 15: the oscillation (Hopf) boundary μ0 against λ and against r for ω0 ∈ {0.9, 0.5, 0.3}
//! at D = 0 — by simulation (predictor–corrector from a small amplitude, bracketed), by
//! averaging (f′(0) = 0 of Eq. 18) and by the exact linearisation where it is exact — with the
//! non-oscillating region (below the simulated boundary) shaded as in the paper.
//!
//! The panel machinery ([`Panel`], [`Curve`], [`compute`], [`draw_panel`], [`distances`]) is
//! shared with Fig. 16.
//!
//! Rendering only: the data and its computation are [`trirhythm_paper::fig15_oscillation_boundaries`].

use super::boundary::{draw_panel, key_of, legend_of};
use trirhythm_paper::fig15_oscillation_boundaries::Fig15;

/// Height of the panels above the legend strip.
const PANELS: u32 = 1500;

// six panels; one legend for all of them (the styles of the first row's panels) below
picture!(Fig15, |self, root| key key_of(&self.panels), size {
    let legend = legend_of(&self.panels.iter().take(2).collect::<Vec<_>>());
    (1400, PANELS + legend.height(1400))
}, draw {
    let (panels, strip) = root.split_vertically(PANELS);
    for (area, panel) in panels.split_evenly((3, 2)).iter().zip(&self.panels) {
        draw_panel(area, panel, 0, false)?;
    }
    legend_of(&self.panels.iter().take(2).collect::<Vec<_>>()).draw(&strip)
});
