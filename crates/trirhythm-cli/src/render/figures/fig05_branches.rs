//! Fig. 5: one-parameter bifurcation diagrams, limit-cycle amplitude A0 vs r for five μ0, every
//! branch traced by pseudo-arclength continuation through its folds (stable solid, unstable
//! dashed, folds and births at A0 = 0 marked).
//!
//! Rendering only: the data and its computation are [`trirhythm_paper::fig05_branches`].

use crate::render::plot::{chart, legend, pe};
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

picture!(Fig05, |self, root| size (1500, 960), draw {
    let areas = root.split_evenly((2, 3));
    for (i, (area, (label, mu0, bd))) in areas.iter().zip(&self.panels).enumerate() {
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
            0.0..amax * 1.08,
            "r",
            "A0",
        )?;
        let mut shown = [false, false];
        for b in &bd.branches {
            for (stable, pts) in runs(&b.points) {
                if stable {
                    let s = c
                        .draw_series(LineSeries::new(pts, BLACK.stroke_width(2)))
                        .map_err(pe)?;
                    if !shown[0] {
                        s.label("stable").legend(|(x, y)| {
                            PathElement::new([(x, y), (x + 16, y)], BLACK.stroke_width(2))
                        });
                        shown[0] = true;
                    }
                } else {
                    let s = c
                        .draw_series(DashedLineSeries::new(
                            pts,
                            6,
                            4,
                            RGBColor(200, 30, 30).stroke_width(2),
                        ))
                        .map_err(pe)?;
                    if !shown[1] {
                        s.label("unstable").legend(|(x, y)| {
                            PathElement::new(
                                [(x, y), (x + 16, y)],
                                RGBColor(200, 30, 30).stroke_width(2),
                            )
                        });
                        shown[1] = true;
                    }
                }
            }
        }
        c.draw_series(bd.folds.iter().map(|&(r, a)| {
            EmptyElement::at((r, a)) + Circle::new((0, 0), 5, RGBColor(30, 90, 200).filled())
        }))
        .map_err(pe)?
        .label("fold (saddle-node)")
        .legend(|(x, y)| Circle::new((x + 8, y), 5, RGBColor(30, 90, 200).filled()));
        c.draw_series(bd.hopf.iter().map(|&r| {
            EmptyElement::at((r, 0.0))
                + Rectangle::new([(-5, -5), (5, 5)], RGBColor(20, 150, 60).filled())
        }))
        .map_err(pe)?
        .label("branch born at A0 = 0")
        .legend(|(x, y)| {
            Rectangle::new(
                [(x + 3, y - 5), (x + 13, y + 5)],
                RGBColor(20, 150, 60).filled(),
            )
        });
        if i == 0 {
            legend(&mut c, SeriesLabelPosition::LowerLeft)?;
        }
    }
    Ok(())
});
