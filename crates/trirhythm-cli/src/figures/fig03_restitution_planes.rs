//! Fig. 3: rhythmicity in the (γ0, δ0) plane for four restitution coefficients r, with the
//! saddle-node lines traced exactly.
//!
//! Rendering only: the data and its computation are [`trirhythm_paper::fig03_restitution_planes`].

use super::mapfig::render_map;
use super::Render;
use anyhow::Result;
use std::path::{Path, PathBuf};
use trirhythm_paper::fig03_restitution_planes::Fig03;

impl Render for Fig03 {
    fn render(&self, stem: &Path) -> Result<Vec<PathBuf>> {
        render_map(&self.0, stem)
    }
}
