//! Fig. 9: the energy barriers ΔU1 … ΔU4 of U_eff (Eq. 23) over the (τ, λ) plane, for
//! r = 0.998 and r = 0.990.
//!
//! Method: [`barrier_surfaces`] on a grid of the plane (τ as printed, λ chosen); a point without
//! three wells has no barriers of those names and is left empty. Checked by
//! `tests/figures.rs`; the barriers themselves by the library's averaging tests.

use crate::notes::num;
use crate::notes::{caption, panel_line, table_notes, Caption};
use crate::table::Table;
use crate::{Figure, FigureOptions, Monitor};

use serde::{Deserialize, Serialize};
use trirhythm::model::preset;
use trirhythm::theory::bifurcation::{barrier_surfaces, Axis, Plane};
use trirhythm::Result;

const R_VALUES: [f64; 2] = [0.998, 0.990];
const LAMBDA: (f64, f64) = (0.98, 1.0);
const TAU: (f64, f64) = (0.0, 5.0);

/// The barriers over the (τ, λ) grid for one r (see
/// [`trirhythm::theory::bifurcation::BarrierSurfaces`]).
#[derive(Serialize, Deserialize)]
pub struct Surface {
    /// Restitution coefficient.
    pub r: f64,
    /// Horizontal axis (τ).
    pub x: Axis,
    /// Vertical axis (λ).
    pub y: Axis,
    /// [ΔU1, ΔU2, ΔU3, ΔU4] per grid point, row-major; `None` without three wells.
    pub heights: Vec<[Option<f64>; 4]>,
    /// Number of wells of U_eff per grid point.
    pub wells: Vec<u8>,
}

/// Fig. 9's data: the barrier surfaces for each r.
#[derive(Serialize, Deserialize)]
pub struct Fig09 {
    /// What the figure shows, shared parameters, variant, choices.
    pub caption: Caption,
    /// Notes of the data table: parameters per panel, methods, verdicts.
    pub notes: Vec<String>,
    /// One surface per r.
    pub surfaces: Vec<Surface>,
}

impl Figure for Fig09 {
    const NUMBER: u32 = 9;
    const TITLE: &'static str = "energy barriers ΔU_i over (τ, λ) for two r";

    fn compute(options: &FigureOptions, monitor: &dyn Monitor) -> Result<Fig09> {
        compute(options, monitor)
    }

    fn validate(&self) -> crate::validate::Valid {
        use crate::validate::{axis, finite, len, scalar};
        for (i, p) in self.surfaces.iter().enumerate() {
            let f = format!("surfaces[{i}]");
            scalar(&format!("{f}.r"), p.r)?;
            axis(&format!("{f}.x"), &p.x)?;
            axis(&format!("{f}.y"), &p.y)?;
            let points = p.x.count * p.y.count;
            let of = format!("{} × {} grid points", p.x.count, p.y.count);
            len(&format!("{f}.heights"), p.heights.len(), points, &of)?;
            len(&format!("{f}.wells"), p.wells.len(), points, &of)?;
            let hs: Vec<f64> = p.heights.iter().flatten().flatten().copied().collect();
            finite(&format!("{f}.heights"), &hs)?;
        }
        Ok(())
    }

    fn tables(&self) -> Vec<Table> {
        let mut csv = Table::new(
            &self.notes,
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
        vec![csv]
    }
}

fn compute(ctx: &FigureOptions, monitor: &dyn Monitor) -> Result<Fig09> {
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
        monitor.check()?;
        let s = barrier_surfaces(&plane, &|d, total| monitor.progress(d as u64, total as u64));
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
    monitor.check()?;
    let mut header = table_notes(9, "energy barriers ΔU_i over (τ, λ)", ctx, &notes);
    header.extend(lines);
    let mut lines: Vec<String> = pre.notes.iter().map(|s| s.to_string()).collect();
    lines.push(format!(
        "τ ∈ [{}, {}] as printed; λ ∈ [{}, {}] chosen (not printed); one colour scale per barrier, shared by both r",
        TAU.0, TAU.1, LAMBDA.0, LAMBDA.1
    ));
    let caption = caption(
        9,
        "energy barriers ΔU_i over (τ, λ) for r = 0.998 and r = 0.990",
        ctx,
        &pre.params,
        &["r", "tau", "lambda"],
        lines,
    );
    Ok(Fig09 {
        caption,
        notes: header,
        surfaces,
    })
}
