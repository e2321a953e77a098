//! Fig. 3: rhythmicity in the (γ0, δ0) plane for four restitution coefficients r, with the
//! saddle-node lines traced exactly.

use super::mapfig::gamma_delta_family;
use super::FigureContext;
use anyhow::Result;
use std::path::PathBuf;

/// The r values (not printed in the paper).
pub const R_VALUES: [f64; 4] = [1.0, 0.998, 0.995, 0.99];

pub fn run(ctx: &FigureContext) -> Result<Vec<PathBuf>> {
    gamma_delta_family(
        ctx,
        3,
        "fig3",
        ("r", "r", R_VALUES),
        "rhythmicity in the (γ0, δ0) plane for four restitution coefficients",
        "(α0, β0) = (0.144, 0.005), D = 0, μ0 = 0.01, λ = 0.999, ω0 = 1; r values not printed in the paper: chosen".into(),
    )
}
