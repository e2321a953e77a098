//! Fig. 2: rhythmicity maps of the noise-free averaged system (roots of f, Eq. 18/24):
//! (i) the (α0, β0) plane with γ0 = δ0 = 0, (ii) the (γ0, δ0) plane at (α0, β0) = (0.144, 0.005),
//! with the saddle-node lines (L1, L2, L3) traced exactly.
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

/// Fig. 2's data: two map panels.
#[derive(Serialize, Deserialize)]
#[serde(transparent)]
pub struct Fig02(pub MapFigure);

impl Figure for Fig02 {
    const NUMBER: u32 = 2;
    const TITLE: &'static str = "rhythmicity maps in (α0, β0) and (γ0, δ0) with saddle-node lines";

    fn compute(ctx: &FigureOptions, monitor: &dyn Monitor) -> Result<Fig02> {
        compute(ctx, monitor).map(Fig02)
    }

    fn tables(&self) -> Vec<Table> {
        self.0.tables()
    }

    fn validate(&self) -> crate::validate::Valid {
        self.0.validate()
    }
}

fn compute(ctx: &FigureOptions, monitor: &dyn Monitor) -> Result<MapFigure> {
    let p1 = preset("fig2i")?;
    let p2 = preset("fig2ii")?;
    let mut panels = vec![
        compute_panel(
            ctx,
            monitor,
            "i",
            "γ0 = δ0 = 0".into(),
            &p1.params,
            AxisSpec::new("alpha0", 0.04, 0.24, "α0", 1.0),
            AxisSpec::new("beta0", 0.0005, 0.0105, "β0", 1e-3),
            What::Rhythmicity,
            false,
        )?,
        compute_panel(
            ctx,
            monitor,
            "ii",
            "(α0, β0) = (0.144, 0.005)".into(),
            &p2.params,
            AxisSpec::new("gamma0", 0.0, 1.2e-4, "γ0", 1e-5),
            AxisSpec::new("delta0", 1e-8, 6e-7, "δ0", 1e-7),
            What::Rhythmicity,
            false,
        )?,
    ];
    panels[0].mark = Some((0.144, 0.005, "paper's (α0, β0)".into()));
    panels[1].mark = Some((5.862e-5, 2.13e-7, "paper's (γ0, δ0)".into()));
    let mut notes: Vec<String> = p1.notes.iter().map(|s| format!("panel i: {s}")).collect();
    notes.extend(p2.notes.iter().map(|s| format!("panel ii: {s}")));
    notes.push("count = number of stable limit cycles (positive roots of f with df/dA < 0), certified by a Sturm count".into());
    notes.push("red lines: folds f = ∂f/∂A = 0 traced by pseudo-arclength continuation (the paper's L1-L3)".into());
    notes.push("lines named by computation, as the paper's text defines them: at the middle of each line the double root is the outermost positive root of f (L1, outer cycle), the innermost (L3, inner cycle) or one between (L2); in panel ii the right edge of the trirhythmic wedge is the middle cycle's fold, where the text's description would call it L3".into());
    notes.push("panel ii: the paper describes regions with 1, 2 and 3 stable cycles; at λ = 1, r = 1 the (γ0 ≥ 0) plane has no monorhythmic region (it appears for λ < 1 or r < 1: Figs 3, 6)".into());
    notes.push("panel i: the bistable wedge ends in a cusp at α0 = 1/6, β0 = 1/135, A = √12 (triple root of f)".into());
    Ok(map_figure(
        ctx,
        (2, "rhythmicity in the (α0, β0) and (γ0, δ0) planes"),
        "D = 0, r = 1, μ0 = 0.01, ω0 = 1, λ = 1 (λ not printed in the paper: chosen)".into(),
        notes,
        panels,
    ))
}
