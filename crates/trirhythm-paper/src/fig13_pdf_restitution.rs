//! Fig. 13: the stationary P(A) for several restitution coefficients at μ0 = 0.005 (a) and
//! μ0 = 0.2 (b): the averaged theory (Eq. 27, both variants) against Monte Carlo ensembles of
//! the fractional system (Eq. 1) and of its integer-order equivalent (Eq. 5), with error bars,
//! distances and the stationarity verdict of every ensemble.
//!
//! Method: [`crate::montecarlo`]; r for (a) as printed, four r of the printed range for (b).
//! Checked by `tests/figures.rs` (computes, reads back, stops when cancelled).

use crate::montecarlo::{
    amplitude_panel, amplitude_table, beyond_line, stationary_count, wells_line, AmplitudePanel,
    Sizes,
};
use crate::notes::{caption, table_notes, Caption};
use crate::table::Table;
use crate::{Figure, FigureOptions, Monitor};

use serde::{Deserialize, Serialize};
use trirhythm::engine::System;
use trirhythm::model::preset;
use trirhythm::Result;

/// (preset, label, r) per panel: the paper's r for (a), four of "0.7 to 0.999" for (b).
pub const PANELS: [(&str, &str, f64); 8] = [
    ("fig13a", "a1", 0.99),
    ("fig13a", "a2", 0.97),
    ("fig13a", "a3", 0.96),
    ("fig13a", "a4", 0.84),
    ("fig13b", "b1", 0.999),
    ("fig13b", "b2", 0.95),
    ("fig13b", "b3", 0.85),
    ("fig13b", "b4", 0.7),
];

/// Fig. 13's data.
#[derive(Serialize, Deserialize)]
pub struct Fig13 {
    /// What the figure shows, shared parameters, variant, verdict.
    pub caption: Caption,
    /// Notes of the data table: every ensemble's distances and verdict.
    pub notes: Vec<String>,
    /// Panels a1 … b4.
    pub panels: Vec<AmplitudePanel>,
}

impl Figure for Fig13 {
    const NUMBER: u32 = 13;
    const TITLE: &'static str = "P(A) for several r: theory against Monte Carlo of Eq. 1 and Eq. 5";

    fn compute(options: &FigureOptions, monitor: &dyn Monitor) -> Result<Fig13> {
        let ctx = options;
        let sz = Sizes::of(ctx.quick);
        let mut notes = vec![
            format!(
                "ensembles: {}; starts at the theory's modes in turn",
                sz.describe()
            ),
            "the paper prints r for (a) only; (b) shows four r from its range 0.7–0.999".into(),
        ];
        let mut panels = Vec::new();
        // every panel side by side
        let progress = crate::Progress::new(0, PANELS.len());
        let computed = crate::each(&PANELS, |&(name, label, r)| {
            let pre = preset(name)?;
            let p = pre.params.with("r", r)?;
            let mu0 = p.mu0;
            let panel = amplitude_panel(
                monitor,
                format!("({label}) μ0 = {mu0}, r = {r}"),
                &p,
                ctx.variant,
                &[System::Fractional, System::Equivalent],
                sz,
            )?;
            progress.advance(monitor, 1)?;
            Ok(panel)
        })?;
        for (panel, n) in computed {
            notes.extend(n);
            panels.push(panel);
        }
        let (passed, total) = stationary_count(&panels);
        let verdict = format!(
            "stationarity check passed by {passed} of {total} ensembles (panels marked \"Monte Carlo NOT stationary\" are not stationary results)"
        );
        notes.push(verdict.clone());
        notes.push("the paper claims agreement between theory and Monte Carlo in every panel; the distances above say where it holds".into());
        let base = preset("fig13a")?.params;
        let caption = caption(
            13,
            "stationary P(A) for several r, theory against Monte Carlo",
            ctx,
            &base,
            &["mu0", "r"],
            vec![
                format!("Monte Carlo: {}", sz.describe()),
                verdict,
                beyond_line(&panels),
                wells_line(&panels),
            ],
        );
        Ok(Fig13 {
            caption,
            notes: table_notes(13, Self::TITLE, ctx, &notes),
            panels,
        })
    }

    fn validate(&self) -> crate::validate::Valid {
        for (i, p) in self.panels.iter().enumerate() {
            p.validate(&format!("panels[{i}]"))?;
        }
        Ok(())
    }

    fn tables(&self) -> Vec<Table> {
        vec![amplitude_table(&self.notes, &self.panels)]
    }
}
