//! Fig. 8: the energy barriers ΔU_i of the pseudo-potential U_eff(A0) (Eq. 23): from each
//! well (stable cycle) to the crest (unstable cycle) beside it.
//!
//! Method: [`Theory::potential`] on a grid of A0 ∈ (0, 14] and [`Theory::barriers`]; the paper
//! shows four barriers, and the notes say when these parameters give another count. Checked
//! by `tests/figures.rs` and the library's averaging tests of the barriers.

use crate::fig07_pseudo_potential::Curve;
use crate::notes::num;
use crate::notes::{caption, panel_line, table_notes, Caption};
use crate::table::Table;
use crate::{Figure, FigureOptions, Monitor};

use serde::{Deserialize, Serialize};
use trirhythm::model::preset;
use trirhythm::theory::averaging::{Barrier, Side, Theory};
use trirhythm::Result;

/// Fig. 8's data: U_eff on a grid with its extrema, and the barriers.
#[derive(Serialize, Deserialize)]
pub struct Fig08 {
    /// What the figure shows, shared parameters, variant, choices.
    pub caption: Caption,
    /// Notes of the data table: σ1, each barrier.
    pub notes: Vec<String>,
    /// U_eff(A0) with its wells and crests.
    pub curve: Curve,
    /// ΔU1, ΔU2, … from the innermost well out.
    pub barriers: Vec<Barrier>,
}

impl Figure for Fig08 {
    const NUMBER: u32 = 8;
    const TITLE: &'static str = "energy barriers ΔU_i of U_eff";

    fn compute(options: &FigureOptions, monitor: &dyn Monitor) -> Result<Fig08> {
        compute(options, monitor)
    }

    fn validate(&self) -> crate::validate::Valid {
        use crate::validate::{finite, limits};
        limits("curve.points", &self.curve.points)?;
        for (i, b) in self.barriers.iter().enumerate() {
            finite(&format!("barriers[{i}]"), &[b.well, b.crest, b.height])?;
        }
        Ok(())
    }

    fn tables(&self) -> Vec<Table> {
        let mut csv = Table::new(&self.notes, &["A", "U_eff"]);
        for &(a, u) in &self.curve.points {
            csv.row([num(a), num(u)]);
        }
        vec![csv]
    }
}

fn compute(ctx: &FigureOptions, monitor: &dyn Monitor) -> Result<Fig08> {
    monitor.check()?;
    let pre = preset("fig8")?;
    let p = pre.params;
    let th = Theory::new(&p, ctx.variant)?;
    let n = if ctx.quick { 400 } else { 2000 };
    let grid: Vec<f64> = (1..=n).map(|i| 14.0 * i as f64 / n as f64).collect();
    let curve = Curve::new("U_eff".into(), &th, &grid);
    let barriers = th.barriers();
    let mut notes: Vec<String> = pre.notes.iter().map(|s| s.to_string()).collect();
    notes.push(format!("σ1 = {}", th.diffusion()));
    for (i, b) in barriers.iter().enumerate() {
        notes.push(format!(
            "ΔU{} = {:.6e}: well A = {:.6} → crest A = {:.6} ({})",
            i + 1,
            b.height,
            b.well,
            b.crest,
            if b.side == Side::Left {
                "left"
            } else {
                "right"
            }
        ));
    }
    if barriers.len() != 4 {
        notes.push(format!(
            "{} barriers (not the paper's four) for these parameters",
            barriers.len()
        ));
    }
    let mut header = table_notes(8, "energy barriers of U_eff(A0)", ctx, &notes);
    header.push(panel_line("", &p));
    Ok(Fig08 {
        caption: caption(
            8,
            "energy barriers ΔU_i of the pseudo-potential U_eff(A0)",
            ctx,
            &p,
            &[],
            pre.notes.iter().map(|s| s.to_string()).collect(),
        ),
        notes: header,
        curve,
        barriers,
    })
}
