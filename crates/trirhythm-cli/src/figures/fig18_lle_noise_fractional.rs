//! Fig. 18: the largest Lyapunov exponent (frozen noise) against the noise intensity D for four
//! λ at r = 0.998 (a) and four r at λ = 0.998 (b), μ0 = 0.001, τ = 0.025, with error bars, and the
//! paper's claims (the LLE turns positive past a critical D; more impact loss, more chaos)
//! checked curve by curve.

use super::fig17_lle_noise::noises;
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

/// Fig. 18's data.
#[derive(Serialize, Deserialize)]
pub struct Fig18 {
    heading: Heading,
    header: Vec<String>,
    panels: Vec<Panel>,
}

impl Figure for Fig18 {
    const NUMBER: u32 = 18;
    const TITLE: &'static str = "largest Lyapunov exponent against noise for several λ and r";

    fn compute(ctx: &FigureContext) -> Result<Fig18> {
        let sz = Sizes::of(ctx.quick);
        let d = noises(ctx.quick);
        let a = preset("fig18a")?.params;
        let b = preset("fig18b")?.params;
        let (pa, na) = lle_against_noise(
            "(a) r = 0.998",
            &a,
            "lambda",
            &[0.95, 0.98, 0.995, 1.0],
            &d,
            &sz,
        )?;
        let (pb, nb) =
            lle_against_noise("(b) λ = 0.998", &b, "r", &[0.998, 0.95, 0.9, 0.8], &d, &sz)?;
        let mut notes = vec![
            sz.describe(),
            "the paper does not print the four λ and r values, ω0 nor the D range: λ ∈ {0.95, 0.98, 0.995, 1}, r ∈ {0.998, 0.95, 0.9, 0.8}, ω0 = 0.9, D ∈ [0.05, 2] chosen".into(),
            "error bars: ± one standard error over noise realisations; the exponents are finite-time exponents over the window stated (λ < 1: Mittag-Leffler tails, README \"Lyapunov exponents\")".into(),
        ];
        notes.extend(na);
        notes.extend(nb);
        let heading = heading(
            18,
            "largest Lyapunov exponent (frozen noise) against D, fractional order and restitution",
            ctx,
            &a,
            &["lambda", "r", "D"],
            vec![sz.describe()],
        );
        Ok(Fig18 {
            heading,
            header: csv_header(18, Self::TITLE, ctx, &notes),
            panels: vec![pa, pb],
        })
    }

    fn render(&self, stem: &Path) -> Result<Vec<PathBuf>> {
        write_figure(self, stem, &panels_csv(&self.header, &self.panels)?)
    }
}

impl Picture for Fig18 {
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
