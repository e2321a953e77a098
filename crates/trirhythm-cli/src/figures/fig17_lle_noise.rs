//! Fig. 17: the largest Lyapunov exponent (frozen noise) against the noise intensity D for four
//! μ0 at τ = 0.06 (a) and four τ at μ0 = 0.001 (b), with error bars, and the paper's claim (the
//! LLE turns positive past a critical D) checked curve by curve.

use super::lle::{
    draw_side_by_side, lle_against_noise, panel_height, panels_csv, Panel, Sizes, PANEL_WIDTH,
};
use super::write_figure;
use super::{csv_header, heading, Figure, FigureContext};
use crate::plot::{Heading, Picture};
use anyhow::Result;
use plotters::coord::Shift;
use plotters::prelude::*;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use trirhythm::model::preset;

/// The noise intensities of a curve.
pub fn noises(quick: bool) -> Vec<f64> {
    if quick {
        vec![0.05, 1.0, 2.0]
    } else {
        (0..9).map(|k| 0.05 + 0.24375 * k as f64).collect()
    }
}

/// Fig. 17's data.
#[derive(Serialize, Deserialize)]
pub struct Fig17 {
    heading: Heading,
    header: Vec<String>,
    panels: Vec<Panel>,
}

impl Figure for Fig17 {
    const NUMBER: u32 = 17;
    const TITLE: &'static str = "largest Lyapunov exponent against noise for several μ0 and τ";

    fn compute(ctx: &FigureContext) -> Result<Fig17> {
        let sz = Sizes::of(ctx.quick);
        let d = noises(ctx.quick);
        let a = preset("fig17a")?.params;
        let b = preset("fig17b")?.params;
        let (pa, na) = lle_against_noise(
            "(a) τ = 0.06",
            &a,
            "mu0",
            &[0.001, 0.01, 0.05, 0.1],
            &d,
            &sz,
        )?;
        let (pb, nb) = lle_against_noise(
            "(b) μ0 = 0.001",
            &b,
            "tau",
            &[0.06, 0.25, 0.5, 1.0],
            &d,
            &sz,
        )?;
        let mut notes = vec![
            sz.describe(),
            "the paper does not print the four μ0 and τ values nor the D range: μ0 ∈ {0.001, 0.01, 0.05, 0.1}, τ ∈ {0.06, 0.25, 0.5, 1}, D ∈ [0.05, 2] chosen".into(),
            "error bars: ± one standard error over noise realisations; the exponents are finite-time exponents over the window stated (λ < 1: Mittag-Leffler tails, README \"Lyapunov exponents\")".into(),
        ];
        notes.extend(na);
        notes.extend(nb);
        let heading = heading(
            17,
            "largest Lyapunov exponent (frozen noise) against D",
            ctx,
            &a,
            &["mu0", "tau", "D"],
            vec![sz.describe()],
        );
        Ok(Fig17 {
            heading,
            header: csv_header(17, Self::TITLE, ctx, &notes),
            panels: vec![pa, pb],
        })
    }

    fn render(&self, stem: &Path) -> Result<Vec<PathBuf>> {
        write_figure(self, stem, &panels_csv(&self.header, &self.panels)?)
    }
}

impl Picture for Fig17 {
    fn size(&self) -> (u32, u32) {
        (2 * PANEL_WIDTH, panel_height(&self.panels))
    }

    fn heading(&self) -> Heading {
        self.heading.clone()
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()>
    where
        DB::ErrorType: 'static,
    {
        draw_side_by_side(root, &self.panels)
    }
}
