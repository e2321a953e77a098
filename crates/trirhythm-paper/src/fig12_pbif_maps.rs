//! Fig. 12: P-bifurcation maps in the (μ0, r) plane at λ = 0.995 (a, b) and the (λ, r) plane at
//! μ0 = 0.01 (c, d), for ω0 = 0.9 (a, c) and ω0 = 1.0 (b, d; the caption prints 0.9 twice).
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

/// Fig. 12's data: four map panels.
#[derive(Serialize, Deserialize)]
#[serde(transparent)]
pub struct Fig12(pub MapFigure);

impl Figure for Fig12 {
    const NUMBER: u32 = 12;
    const TITLE: &'static str = "P-bifurcation maps in (μ0, r) and (λ, r)";

    fn compute(ctx: &FigureOptions, monitor: &dyn Monitor) -> Result<Fig12> {
        compute(ctx, monitor).map(Fig12)
    }

    fn tables(&self) -> Vec<Table> {
        self.0.tables()
    }

    fn validate(&self) -> crate::validate::Valid {
        self.0.validate()
    }
}

fn compute(ctx: &FigureOptions, monitor: &dyn Monitor) -> Result<MapFigure> {
    let mut panels = Vec::new();
    let mut notes = Vec::new();
    for label in ["a", "b", "c", "d"] {
        let pre = preset(&format!("fig12{label}"))?;
        notes.extend(pre.notes.iter().map(|s| format!("panel {label}: {s}")));
        let w0 = pre.params.omega0;
        let (xs, caption) = if label == "a" || label == "b" {
            (
                AxisSpec::new("mu0", 0.001, 0.1, "μ0", 1.0),
                format!("λ = 0.995, ω0 = {w0}"),
            )
        } else {
            (
                AxisSpec::new("lambda", 0.95, 1.0, "λ", 1.0),
                format!("μ0 = 0.01, ω0 = {w0}"),
            )
        };
        panels.push(compute_panel(
            ctx,
            monitor,
            label,
            caption,
            &pre.params,
            xs,
            AxisSpec::new("r", 0.8, 1.0, "r", 1.0),
            What::Modes,
            true,
        )?);
    }
    notes.push(
        "μ0 ∈ [0.001, 0.1], λ ∈ [0.95, 1], r ∈ [0.8, 1] chosen (the paper prints no ranges)".into(),
    );
    notes.push(
        "red: m1 = ∂m1/∂A = 0 traced exactly; dashed orange: the printed Eq. 36-37 construction"
            .into(),
    );
    Ok(map_figure(
        ctx,
        (12, "P-bifurcation maps in the (μ0, r) and (λ, r) planes"),
        "unimodal (blue), bimodal (green), trimodal (black) P(A); D = 0.1, τ = 0.5, cp = (0.144, 0.005, 5.862e-5, 2.13e-7); ω0 = 1.0 in b, d (caption prints 0.9 twice)".into(),
        notes,
        panels,
    ))
}
