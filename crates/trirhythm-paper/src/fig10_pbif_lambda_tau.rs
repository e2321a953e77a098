//! Fig. 10: stochastic P-bifurcation map in the (λ, τ) plane for four noise intensities D:
//! number of maxima of the stationary P(A) (Eq. 27), the exact transition curves
//! m1 = ∂m1/∂A = 0 (Eq. 35 with Eq. 37 corrected) and, for the paper variant, the paper's printed
//! Eq. 36–37 construction.
//!
//! Method and checks: [`crate::maps`] (a Sturm count per grid point, fold curves by
//! continuation); `tests/figures.rs` computes it and reads it back.

use crate::maps::{compute_panel, map_figure, AxisSpec, MapFigure};
use crate::table::Table;
use crate::{Figure, FigureOptions, Monitor};
use serde::{Deserialize, Serialize};
use trirhythm::model::preset;
use trirhythm::theory::bifurcation::What;
use trirhythm::Result;

/// The noise intensities D of the panels.
pub const D_VALUES: [f64; 4] = [0.05, 0.3, 0.7, 1.2];

/// Fig. 10's data: four map panels, one per D.
#[derive(Serialize, Deserialize)]
#[serde(transparent)]
pub struct Fig10(pub MapFigure);

impl Figure for Fig10 {
    const NUMBER: u32 = 10;
    const TITLE: &'static str = "P-bifurcation map in (λ, τ) for four D";

    fn compute(ctx: &FigureOptions, monitor: &dyn Monitor) -> Result<Fig10> {
        compute(ctx, monitor).map(Fig10)
    }

    fn tables(&self) -> Vec<Table> {
        self.0.tables()
    }

    fn validate(&self) -> crate::validate::Valid {
        self.0.validate()
    }
}

fn compute(ctx: &FigureOptions, monitor: &dyn Monitor) -> Result<MapFigure> {
    let pre = preset("fig10")?;
    let mut panels = Vec::new();
    for (label, d) in ["a", "b", "c", "d"].into_iter().zip(D_VALUES) {
        panels.push(compute_panel(
            ctx,
            monitor,
            label,
            format!("D = {d}"),
            &pre.params.with("D", d)?,
            AxisSpec::new("lambda", 0.9, 1.0, "λ", 1.0),
            AxisSpec::new("tau", 0.0, 5.0, "τ", 1.0),
            What::Modes,
            true,
        )?);
    }
    let mut notes: Vec<String> = pre.notes.iter().map(|s| s.to_string()).collect();
    notes.push("λ ∈ [0.9, 1] and τ ∈ [0, 5] chosen (the paper prints no ranges)".into());
    notes.push("count = number of maxima of P(A): stable roots of m1 (sign changes of d ln P/dA = 2m1/σ1 on the analytic expression)".into());
    notes.push("red: m1 = ∂m1/∂A = 0 traced exactly; dashed orange: h = 0 with Eq. 37 as printed (β1 on the wrong term), which agrees with the exact curves only at λ = 1".into());
    Ok(map_figure(
        ctx,
        (10, "P-bifurcation map in the (λ, τ) plane for four noise intensities"),
        "unimodal (blue), bimodal (green), trimodal (black) P(A); μ0 = 0.01, ω0 = 0.9, cp = (0.144, 0.005, 5.862e-5, 2.13e-7), r = 0.998 (not printed: chosen)".into(),
        notes,
        panels,
    ))
}
