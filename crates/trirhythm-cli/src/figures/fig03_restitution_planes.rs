//! Fig. 3: rhythmicity in the (γ0, δ0) plane for four restitution coefficients r, with the
//! saddle-node lines traced exactly.

use super::mapfig::{compute_panel, write_map_figure, AxisSpec};
use super::FigureContext;
use anyhow::Result;
use std::path::PathBuf;
use trirhythm::bifurcation::What;
use trirhythm::model::preset;

/// The r values (not printed in the paper).
pub const R_VALUES: [f64; 4] = [1.0, 0.998, 0.995, 0.99];

pub fn run(ctx: &FigureContext) -> Result<Vec<PathBuf>> {
    let pre = preset("fig3")?;
    let mut panels = Vec::new();
    for (label, r) in ["a", "b", "c", "d"].into_iter().zip(R_VALUES) {
        let mut panel = compute_panel(
            ctx,
            label,
            format!("r = {r}"),
            &pre.params.with("r", r)?,
            AxisSpec::new("gamma0", 0.0, 1.2e-4, "γ0", 1e-5),
            AxisSpec::new("delta0", 1e-8, 6e-7, "δ0", 1e-7),
            What::Rhythmicity,
            false,
        )?;
        panel.mark = Some((5.862e-5, 2.13e-7, "paper's (γ0, δ0)".into()));
        panels.push(panel);
    }
    let mut notes: Vec<String> = pre.notes.iter().map(|s| s.to_string()).collect();
    notes.push(format!("r values chosen: {R_VALUES:?}"));
    notes.push(
        "count = number of stable limit cycles; red: folds f = ∂f/∂A = 0 traced exactly".into(),
    );
    write_map_figure(
        ctx,
        3,
        "rhythmicity in the (γ0, δ0) plane for four restitution coefficients",
        "(α0, β0) = (0.144, 0.005), D = 0, μ0 = 0.01, λ = 0.999, ω0 = 1; r values not printed in the paper: chosen".into(),
        notes,
        panels,
        (2, 2),
        plotters::prelude::SeriesLabelPosition::UpperRight,
    )
}
