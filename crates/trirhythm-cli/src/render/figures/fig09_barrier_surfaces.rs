//! Fig. 9: energy barriers ΔU1…ΔU4 of U_eff (Eq. 23) over the (τ, λ) plane for r = 0.998 and
//! r = 0.990, as heat maps; blank where U_eff does not have the three wells the labels refer to.
//! One row per barrier: both r side by side, and the row's colour scale (shared by both) on
//! their right.
//!
//! Rendering only: the data and its computation are [`trirhythm_paper::fig09_barrier_surfaces`].

use crate::render::plot::{chart, colour_bar_vertical, pe, viridis, LegendStrip, Symbol};
use plotters::prelude::*;
use trirhythm_paper::fig09_barrier_surfaces::Fig09;

/// A heat map's size, and the width of a row's colour bar.
const MAP: (u32, u32) = (610, 360);
const BAR: u32 = 180;

// One row per barrier: its two r side by side (each 3 in wide printed 7 in) and its colour
// bar, shared by both, on their right.
/// What the white of the maps means.
fn key() -> LegendStrip {
    LegendStrip {
        entries: vec![(
            Symbol::Framed(WHITE, RGBColor(110, 110, 110)),
            "white: fewer than three wells, the barrier undefined".into(),
        )],
    }
}

picture!(Fig09, |self, root| size (2 * MAP.0 + BAR, 4 * MAP.1 + key().height(2 * MAP.0 + BAR)), draw {
    let (root, strip) = root.split_vertically(4 * MAP.1);
    key().draw(&strip)?;
    // one colour scale per barrier, shared by both r: the rows can be compared
    let scales: Vec<(f64, f64)> = (0..4)
        .map(|k| {
            let vals = self
                .surfaces
                .iter()
                .flat_map(|s| s.heights.iter().filter_map(move |h| h[k]));
            vals.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
                (a.min(v), b.max(v))
            })
        })
        .collect();
    let rows = root.split_evenly((4, 1));
    let mut areas = Vec::new();
    for (k, row) in rows.iter().enumerate() {
        let (maps, bar) = row.split_horizontally(2 * MAP.0);
        areas.extend(maps.split_evenly((1, 2)));
        let (lo, hi) = scales[k];
        if lo < hi {
            colour_bar_vertical(&bar, &format!("ΔU_{}", k + 1), lo, hi)?;
        }
    }
    for (row, s) in self.surfaces.iter().enumerate() {
        let (nx, ny) = (s.x.count, s.y.count);
        let hx = (s.x.stop - s.x.start) / (nx - 1) as f64;
        let hy = (s.y.stop - s.y.start) / (ny - 1) as f64;
        for k in 0..4 {
            let vals: Vec<f64> = s.heights.iter().filter_map(|h| h[k]).collect();
            let here = vals
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
                    (a.min(v), b.max(v))
                });
            let (lo, hi) = scales[k];
            let label = ["a", "b", "c", "d"][k];
            let caption = if vals.is_empty() {
                format!("({label}{}) ΔU_{}, r = {}: undefined", row + 1, k + 1, s.r)
            } else {
                format!(
                    "({label}{}) r = {}: {:.3} ≤ ΔU_{} ≤ {:.3}",
                    row + 1,
                    s.r,
                    here.0,
                    k + 1,
                    here.1
                )
            };
            let area = &areas[k * 2 + row];
            let mut c = chart(
                area,
                &caption,
                s.x.start..s.x.stop,
                s.y.start..s.y.stop,
                "τ",
                "λ",
            )?;
            let span = if hi > lo { hi - lo } else { 1.0 };
            // Colours quantised to 64 levels; equal neighbours along a row merged into one
            // rectangle (keeps the SVG small).
            let level = |h: f64| ((h - lo) / span * 63.0).round() as u8;
            let mut cells = Vec::new();
            for iy in 0..ny {
                let y = s.y.value(iy);
                let mut ix = 0;
                while ix < nx {
                    let Some(h) = s.heights[iy * nx + ix][k] else {
                        ix += 1;
                        continue;
                    };
                    let lv = level(h);
                    let mut jx = ix;
                    while jx + 1 < nx && s.heights[iy * nx + jx + 1][k].map(level) == Some(lv) {
                        jx += 1;
                    }
                    let (x0, x1) = (s.x.value(ix), s.x.value(jx));
                    cells.push(Rectangle::new(
                        [
                            (
                                (x0 - hx / 2.0).max(s.x.start),
                                (y - hy / 2.0).max(s.y.start),
                            ),
                            ((x1 + hx / 2.0).min(s.x.stop), (y + hy / 2.0).min(s.y.stop)),
                        ],
                        viridis(lv as f64 / 63.0).filled(),
                    ));
                    ix = jx + 1;
                }
            }
            c.draw_series(cells).map_err(pe)?;
        }
    }
    Ok(())
});
