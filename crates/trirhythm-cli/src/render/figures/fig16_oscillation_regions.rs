//! Fig. 16: oscillation and rest regions at D = 0 — (a) the (μ0, λ) plane at r = 0.99,
//! (b) the effect of r on it, (c) the (μ0, r) plane at λ = 0.999, (d) the effect of λ on it —
//! each boundary by simulation, by averaging and (where exact) by the linearisation at U = 0.
//!
//! Rendering only: the data and its computation are [`trirhythm_paper::fig16_oscillation_regions`].

use super::boundary::draw_panel;
use super::heading_of;
use crate::render::plot::{Heading, Picture};
use anyhow::Result;
use plotters::coord::Shift;
use plotters::prelude::*;
use trirhythm_paper::fig16_oscillation_regions::Fig16;

impl Picture for Fig16 {
    fn size(&self) -> (u32, u32) {
        (1400, 1100)
    }

    fn heading(&self) -> Heading {
        heading_of(&self.caption)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()>
    where
        DB::ErrorType: 'static,
    {
        let areas = root.split_evenly((2, 2));
        for (area, panel) in areas.iter().zip(&self.panels) {
            draw_panel(area, panel, true)?;
        }
        Ok(())
    }
}
