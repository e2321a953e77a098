//! Fig. 3: rhythmicity in the (γ0, δ0) plane for four restitution coefficients r, with the
//! saddle-node lines traced exactly.
//!
//! Method and checks: [`crate::maps`] (a Sturm count per grid point, fold curves by
//! continuation); `tests/figures.rs` computes it and reads it back.

use crate::maps::{gamma_delta_family, MapFigure};
use crate::table::Table;
use crate::{Figure, FigureOptions, Monitor};
use serde::{Deserialize, Serialize};
use trirhythm::Result;

/// The r values (not printed in the paper).
pub const R_VALUES: [f64; 4] = [1.0, 0.998, 0.995, 0.99];

/// Fig. 3's data: four map panels, one per r.
#[derive(Serialize, Deserialize)]
#[serde(transparent)]
pub struct Fig03(pub MapFigure);

impl Figure for Fig03 {
    const NUMBER: u32 = 3;
    const TITLE: &'static str = "rhythmicity in (γ0, δ0) for four restitution coefficients";

    fn compute(ctx: &FigureOptions, monitor: &dyn Monitor) -> Result<Fig03> {
        gamma_delta_family(
            ctx,
            monitor,
            (3, "rhythmicity in the (γ0, δ0) plane for four restitution coefficients"),
            "fig3",
            ("r", "r", R_VALUES),
            "(α0, β0) = (0.144, 0.005), D = 0, μ0 = 0.01, λ = 0.999, ω0 = 1; r values not printed in the paper: chosen".into(),
        )
        .map(Fig03)
    }

    fn tables(&self) -> Vec<Table> {
        self.0.tables()
    }

    fn validate(&self) -> crate::validate::Valid {
        self.0.validate()
    }
}
