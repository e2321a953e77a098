//! Fig. 9: energy barriers ΔU1…ΔU4 of U_eff (Eq. 23) over the (τ, λ) plane for r = 0.998 and
//! r = 0.990, as heat maps; blank where U_eff does not have the three wells the labels refer to.

use super::write_figure;
use super::{csv_header, panel_line, Figure, FigureContext};
use crate::common::{num, progress, Csv};
use crate::plot::{chart, colour_bar, pe, viridis, Heading, Picture};
use anyhow::Result;
use plotters::coord::Shift;
use plotters::prelude::*;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use trirhythm::model::preset;
use trirhythm::theory::bifurcation::{barrier_surfaces, Axis, Plane};

const R_VALUES: [f64; 2] = [0.998, 0.990];
const LAMBDA: (f64, f64) = (0.98, 1.0);
const TAU: (f64, f64) = (0.0, 5.0);

/// The barriers over the (τ, λ) grid for one r (see
/// [`trirhythm::theory::bifurcation::BarrierSurfaces`]).
#[derive(Serialize, Deserialize)]
pub struct Surface {
    /// Restitution coefficient.
    r: f64,
    /// Horizontal axis (τ).
    x: Axis,
    /// Vertical axis (λ).
    y: Axis,
    /// [ΔU1, ΔU2, ΔU3, ΔU4] per grid point, row-major; `None` without three wells.
    heights: Vec<[Option<f64>; 4]>,
    /// Number of wells of U_eff per grid point.
    wells: Vec<u8>,
}

/// Fig. 9's data: the barrier surfaces for each r.
#[derive(Serialize, Deserialize)]
pub struct Fig09 {
    heading: Heading,
    /// CSV comment lines.
    header: Vec<String>,
    surfaces: Vec<Surface>,
}

impl Figure for Fig09 {
    const NUMBER: u32 = 9;
    const TITLE: &'static str = "energy barriers ΔU_i over (τ, λ) for two r";

    fn compute(ctx: &FigureContext) -> Result<Fig09> {
        compute(ctx)
    }

    fn render(&self, stem: &Path) -> Result<Vec<PathBuf>> {
        let mut csv = Csv::new(
            &self.header,
            &["r", "tau", "lambda", "wells", "dU1", "dU2", "dU3", "dU4"],
        );
        for s in &self.surfaces {
            for iy in 0..s.y.count {
                for ix in 0..s.x.count {
                    let i = iy * s.x.count + ix;
                    let mut row = vec![
                        num(s.r),
                        num(s.x.value(ix)),
                        num(s.y.value(iy)),
                        s.wells[i].to_string(),
                    ];
                    row.extend(s.heights[i].iter().map(|h| h.map(num).unwrap_or_default()));
                    csv.row(row);
                }
            }
        }
        write_figure(self, stem, &csv.finish()?)
    }
}

fn compute(ctx: &FigureContext) -> Result<Fig09> {
    let pre = preset("fig9")?;
    let n = if ctx.quick { 41 } else { 161 };
    let mut surfaces = Vec::new();
    let mut notes: Vec<String> = pre.notes.iter().map(|s| s.to_string()).collect();
    notes.push(format!(
        "τ ∈ [{}, {}] as printed; λ ∈ [{}, {}] chosen (not printed)",
        TAU.0, TAU.1, LAMBDA.0, LAMBDA.1
    ));
    notes.push("ΔU1: well A01 to its right crest; ΔU2: A03 to the left; ΔU3: A03 to the right; ΔU4: A05 to the left (U_eff → +∞ at A → 0 and ∞ when D > 0)".into());
    notes.push("blank (empty cells) where U_eff has fewer than three wells: the labels A01, A03, A05 do not apply there".into());
    let mut lines = Vec::new();
    for r in R_VALUES {
        let p = pre.params.with("r", r)?;
        let plane = Plane::new(
            &p,
            Axis::new("tau", TAU.0, TAU.1, n)?,
            Axis::new("lambda", LAMBDA.0, LAMBDA.1, n)?,
            ctx.variant,
        )?;
        let bar = progress(n as u64, &format!("r = {r}"));
        let s = barrier_surfaces(&plane, &|d, _| bar.set_position(d as u64));
        bar.finish_and_clear();
        let three = s.wells.iter().filter(|&&w| w == 3).count();
        notes.push(format!(
            "r = {r}: three wells at {:.1}% of the grid points",
            100.0 * three as f64 / s.wells.len() as f64
        ));
        lines.push(panel_line(&format!("r = {r}"), &p));
        surfaces.push(Surface {
            r,
            x: s.plane.x,
            y: s.plane.y,
            heights: s.heights,
            wells: s.wells,
        });
    }
    let mut header = csv_header(9, "energy barriers ΔU_i over (τ, λ)", ctx, &notes);
    header.extend(lines);
    let mut lines: Vec<String> = pre.notes.iter().map(|s| s.to_string()).collect();
    lines.push(format!(
        "τ ∈ [{}, {}] as printed; λ ∈ [{}, {}] chosen (not printed); one colour scale per barrier, shared by both r",
        TAU.0, TAU.1, LAMBDA.0, LAMBDA.1
    ));
    let heading = super::heading(
        9,
        "energy barriers ΔU_i over (τ, λ) for r = 0.998 and r = 0.990",
        ctx,
        &pre.params,
        &["r", "tau", "lambda"],
        lines,
    );
    Ok(Fig09 {
        heading,
        header,
        surfaces,
    })
}

impl Picture for Fig09 {
    fn size(&self) -> (u32, u32) {
        (1700, 960)
    }

    fn heading(&self) -> Heading {
        self.heading.clone()
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()>
    where
        DB::ErrorType: 'static,
    {
        let h = root.dim_in_pixel().1;
        let (rest, bars) = root.split_vertically(h - 90);
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
        for (k, bar) in bars.split_evenly((1, 4)).iter().enumerate() {
            let (lo, hi) = scales[k];
            if lo < hi {
                colour_bar(bar, &format!("ΔU{} (both r)", k + 1), lo, hi)?;
            }
        }
        let areas = rest.split_evenly((2, 4));
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
                    format!("({label}{}) ΔU{}, r = {}: undefined", row + 1, k + 1, s.r)
                } else {
                    format!(
                        "({label}{}) ΔU{}, r = {}: [{:.3}, {:.3}]",
                        row + 1,
                        k + 1,
                        s.r,
                        here.0,
                        here.1
                    )
                };
                let area = &areas[row * 4 + k];
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
    }
}
