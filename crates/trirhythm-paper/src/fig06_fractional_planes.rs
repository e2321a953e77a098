//! Fig. 6: rhythmicity in the (γ0, δ0) plane for four fractional orders λ, with the
//! saddle-node lines traced exactly.
//!
//! Method and checks: [`crate::maps`] (a Sturm count per grid point, fold curves by
//! continuation); `tests/figures.rs` computes it and reads it back.

use crate::maps::{gamma_delta_family, MapFigure};
use crate::table::Table;
use crate::{Figure, FigureOptions, Monitor};
use serde::{Deserialize, Serialize};
use trirhythm::Result;

/// The λ values (not printed in the paper).
pub const LAMBDA_VALUES: [f64; 4] = [1.0, 0.999, 0.998, 0.997];

/// Fig. 6's data: four map panels, one per λ.
#[derive(Serialize, Deserialize)]
#[serde(transparent)]
pub struct Fig06(pub MapFigure);

impl Figure for Fig06 {
    const NUMBER: u32 = 6;
    const TITLE: &'static str = "mono/bi/tri regions in (γ0, δ0) for four fractional orders";

    fn compute(ctx: &FigureOptions, monitor: &dyn Monitor) -> Result<Fig06> {
        gamma_delta_family(
            ctx,
            monitor,
            (6, "mono (blue), bi (green), tri (black) regions in the (γ0, δ0) plane for four λ"),
            "fig6",
            ("lambda", "λ", LAMBDA_VALUES),
            "(α0, β0) = (0.144, 0.005), D = 0, μ0 = 0.01, r = 0.998, ω0 = 1; λ values not printed in the paper: chosen".into(),
        )
        .map(Fig06)
    }

    fn tables(&self) -> Vec<Table> {
        self.0.tables()
    }

    fn validate(&self) -> crate::validate::Valid {
        self.0.validate()
    }
}
