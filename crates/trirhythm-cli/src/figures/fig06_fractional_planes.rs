//! Fig. 6: rhythmicity in the (γ0, δ0) plane for four fractional orders λ, with the
//! saddle-node lines traced exactly.

use super::mapfig::gamma_delta_family;
use super::FigureContext;
use anyhow::Result;
use std::path::PathBuf;

/// The λ values (not printed in the paper).
pub const LAMBDA_VALUES: [f64; 4] = [1.0, 0.999, 0.998, 0.997];

pub fn run(ctx: &FigureContext) -> Result<Vec<PathBuf>> {
    gamma_delta_family(
        ctx,
        6,
        "fig6",
        ("lambda", "λ", LAMBDA_VALUES),
        "mono (blue), bi (green), tri (black) regions in the (γ0, δ0) plane for four λ",
        "(α0, β0) = (0.144, 0.005), D = 0, μ0 = 0.01, r = 0.998, ω0 = 1; λ values not printed in the paper: chosen".into(),
    )
}
