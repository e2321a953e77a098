//! Fig. 5: one-parameter bifurcation diagrams, limit-cycle amplitude A0 vs r for five μ0, every
//! branch traced by pseudo-arclength continuation through its folds (stable solid, unstable
//! dashed, folds and births at A0 = 0 marked).
//!
//! Rendering only: the data and its computation are [`trirhythm_paper::fig05_branches`].

use crate::render::plot::{
    chart, draw_line, pe, pxi, Dash, LegendStrip, Marker, SeriesStyle, Symbol, PALETTE,
};
use plotters::prelude::*;
use trirhythm_paper::fig05_branches::Fig05;

/// Split a branch into runs of equal stability, sharing the boundary points.
pub(super) fn runs(
    points: &[trirhythm::theory::bifurcation::BranchPoint],
) -> Vec<(bool, Vec<(f64, f64)>)> {
    let mut out: Vec<(bool, Vec<(f64, f64)>)> = Vec::new();
    for q in points {
        let xy = (q.param, q.amplitude);
        match out.last_mut() {
            Some((s, v)) if *s == q.stable => v.push(xy),
            Some((_, v)) => {
                let last = *v.last().unwrap();
                out.push((q.stable, vec![last, xy]));
            }
            None => out.push((q.stable, vec![xy])),
        }
    }
    out
}

// Three rows of two panels (each 3.5 in wide printed 7 in), the legend in the sixth cell.
picture!(Fig05, |self, root| size (1500, 1380), draw {
    let areas = root.split_evenly((3, 2));
    for (area, (label, mu0, bd)) in areas.iter().zip(&self.panels) {
        let amax = bd
            .branches
            .iter()
            .flat_map(|b| b.points.iter().map(|q| q.amplitude))
            .fold(0.0f64, f64::max)
            .max(1.0);
        let mut c = chart(
            area,
            &format!("({label}) μ0 = {mu0}"),
            bd.start..bd.stop,
            // below zero, so that the births at A0 = 0 sit above the axis
            -0.05 * amax..amax * 1.08,
            "r",
            "A_0",
        )?;
        for b in &bd.branches {
            for (stable, pts) in runs(&b.points) {
                draw_line(&c, &pts, if stable { STABLE } else { UNSTABLE }, 2)?;
            }
        }
        c.draw_series(bd.folds.iter().map(|&(r, a)| {
            EmptyElement::at((r, a)) + Circle::new((0, 0), pxi(6), FOLD_DOT.filled())
        }))
        .map_err(pe)?;
        c.draw_series(bd.hopf.iter().map(|&r| {
            EmptyElement::at((r, 0.0))
                + Rectangle::new([(-pxi(6), -pxi(6)), (pxi(6), pxi(6))], BORN.filled())
        }))
        .map_err(pe)?;
    }
    // the legend in the free sixth cell, outside the data
    if let Some(free) = areas.get(self.panels.len()) {
        let legend = LegendStrip {
            entries: vec![
                (Symbol::Series(STABLE), "stable (df/dA_{0} < 0)".into()),
                (Symbol::Series(UNSTABLE), "unstable".into()),
                (Symbol::Dot(FOLD_DOT), "fold (saddle-node)".into()),
                (Symbol::Swatch(BORN), "branch born at A_0 = 0".into()),
            ],
        };
        let (w, h) = free.dim_in_pixel();
        let top = h.saturating_sub(legend.height(w)) / 2;
        legend.draw(&free.clone().shrink((0, top), (w, h - top)))?;
    }
    Ok(())
});

/// Stable branches: black, solid; unstable: vermillion, dashed (they part in greyscale).
const STABLE: SeriesStyle = SeriesStyle {
    colour: PALETTE[0],
    dash: Dash::Solid,
    marker: Marker::None,
};
const UNSTABLE: SeriesStyle = SeriesStyle {
    colour: PALETTE[1],
    dash: Dash::Dashed,
    marker: Marker::None,
};
/// Folds: blue dots; branches born at A0 = 0: bluish-green squares (shapes part them).
const FOLD_DOT: RGBColor = PALETTE[2];
const BORN: RGBColor = PALETTE[3];
