//! Fig. 6: rhythmicity in the (γ0, δ0) plane for four fractional orders λ, with the
//! saddle-node lines traced exactly.
//!
//! Rendering only: the data and its computation are [`trirhythm_paper::fig06_fractional_planes`].

use super::mapfig::render_map;
use super::Render;
use anyhow::Result;
use std::path::{Path, PathBuf};
use trirhythm_paper::fig06_fractional_planes::Fig06;

impl Render for Fig06 {
    fn render(&self, stem: &Path) -> Result<Vec<PathBuf>> {
        render_map(&self.0, stem)
    }
}
