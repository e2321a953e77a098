//! Fig. 16: oscillation and rest regions at D = 0 — (a) the (μ0, λ) plane at r = 0.99,
//! (b) the effect of r on it, (c) the (μ0, r) plane at λ = 0.999, (d) the effect of λ on it —
//! each boundary by simulation, by averaging and (where exact) by the linearisation at U = 0.
//!
//! Rendering only: the data and its computation are [`trirhythm_paper::fig16_oscillation_regions`].

use super::boundary::{draw_panel, key_of, legend_of};
use trirhythm_paper::fig16_oscillation_regions::Fig16;

/// Height of a panel's chart (its legend strip comes below).
const CHART: u32 = 550;
/// Height of the second row's charts: (d) holds its members' differences under its chart,
/// which keeps about [`CHART`] (and (c) beside it the same height).
const CHART_LOW: u32 = 3 * CHART / 2;

/// The height of the legend strips: the tallest panel's, so that charts side by side align.
fn strip(fig: &Fig16) -> u32 {
    fig.panels
        .iter()
        .map(|p| legend_of(&[p]).height(700))
        .max()
        .unwrap_or(0)
}

// four panels, each with its legend in a strip below its chart
picture!(Fig16, |self, root| key key_of(&self.panels), size (1400, CHART + CHART_LOW + 2 * strip(self)), draw {
    let (high, low) = root.split_vertically(CHART + strip(self));
    let (a, b) = high.split_horizontally(700);
    let (c, d) = low.split_horizontally(700);
    for (area, panel) in [a, b, c, d].iter().zip(&self.panels) {
        // (the (μ0, r) family's boundaries lie within a hundredth of μ0: an inset draws their
        // differences)
        let differences = panel.is_family() && panel.x_desc == "r";
        draw_panel(area, panel, strip(self), differences)?;
    }
    Ok(())
});
