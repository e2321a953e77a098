//! Fig. 16: oscillation and rest regions at D = 0 — (a) the (μ0, λ) plane at r = 0.99,
//! (b) the effect of r on it, (c) the (μ0, r) plane at λ = 0.999, (d) the effect of λ on it —
//! each boundary by simulation, by averaging and (where exact) by the linearisation at U = 0.
//!
//! Method: [`crate::boundary`], shared with Fig. 15 (panels a and c compare the methods,
//! b and d are families). Checked by the library's oscillation tests and `tests/figures.rs`.

use crate::boundary::{distance_text, linspace, table, Boundaries, Curve, Family, Panel, Sweep};
use crate::notes::{caption, table_notes, Caption};
use crate::table::Table;
use crate::{Figure, FigureOptions, Monitor};

use serde::{Deserialize, Serialize};
use trirhythm::engine::Barrier;
use trirhythm::model::{preset, Params};
use trirhythm::Result;

/// r of panel (b).
pub const RS: [f64; 4] = [1.0, 0.99, 0.97, 0.95];
/// λ of panel (d).
pub const LAMBDAS: [f64; 4] = [1.0, 0.999, 0.995, 0.99];

/// Fig. 16's data.
#[derive(Serialize, Deserialize)]
pub struct Fig16 {
    /// What the figure shows, shared parameters, variant, method.
    pub caption: Caption,
    /// Notes of the data table: distances between the methods per panel and member.
    pub notes: Vec<String>,
    /// Panels a–d.
    pub panels: Vec<Panel>,
}

impl Figure for Fig16 {
    const NUMBER: u32 = 16;
    const TITLE: &'static str = "oscillation and rest regions in (μ0, λ) and (μ0, r)";

    fn compute(options: &FigureOptions, monitor: &dyn Monitor) -> Result<Fig16> {
        compute(options, monitor)
    }

    fn validate(&self) -> crate::validate::Valid {
        for (i, p) in self.panels.iter().enumerate() {
            p.validate(&format!("panels[{i}]"))?;
        }
        Ok(())
    }

    fn tables(&self) -> Vec<Table> {
        vec![table(&self.notes, &self.panels)]
    }
}

/// (a) the (μ0, λ) plane at the preset's r.
fn panel_a(b: &Boundaries, options: &FigureOptions, sweep: Sweep) -> Result<(Panel, String)> {
    let r_a = sweep.base.restitution;
    let (s, a) = b.methods(sweep)?;
    let e = b.exact(sweep, Barrier::On)?;
    let free = b.exact(sweep, Barrier::Off)?;
    let note = format!(
        "panel a (r = {r_a}): largest distance simulation–averaging {}; simulation–exact (λ = 1 only) {}; exact without the wall (reference) {}",
        distance_text(&s, &a, "λ"),
        distance_text(&s, &e, "λ"),
        distance_text(&s, &free, "λ")
    );
    let panel = Panel {
        caption: format!("(a) (μ0, λ) plane, r = {r_a}"),
        label: "a".into(),
        x_desc: "λ".into(),
        x_range: (0.9, 1.0),
        y_range: sweep.y_range,
        curves: vec![
            Curve::new("simulation", "simulation", s),
            Curve::new(
                "averaging",
                format!("averaging ({})", options.variant.name()),
                a,
            ),
            Curve::new("exact", "exact, wall (λ = 1 only)", e),
            Curve::new("exact, no wall", "exact without the wall", free),
        ],
    };
    Ok((panel, note))
}

/// (c) the (μ0, r) plane at the preset's λ, the exact boundary at λ = 1 for reference.
fn panel_c(b: &Boundaries, options: &FigureOptions, sweep: Sweep) -> Result<(Panel, String)> {
    let l_c = sweep.base.lambda;
    let (s, a) = b.methods(sweep)?;
    let at1 = sweep.base.with("lambda", 1.0)?;
    let e1 = b.exact(
        Sweep {
            base: &at1,
            ..sweep
        },
        Barrier::On,
    )?;
    let note = format!(
        "panel c (λ = {l_c}): largest distance simulation–averaging {}; no exact boundary with the wall at λ < 1 — the exact one at λ = 1, drawn for reference, is {} from the simulated one",
        distance_text(&s, &a, "r"),
        distance_text(&s, &e1, "r")
    );
    let panel = Panel {
        caption: format!("(c) (μ0, r) plane, λ = {l_c}"),
        label: "c".into(),
        x_desc: "r".into(),
        x_range: (0.9, 0.999),
        y_range: sweep.y_range,
        curves: vec![
            Curve::new("simulation", "simulation", s),
            Curve::new(
                "averaging",
                format!("averaging ({})", options.variant.name()),
                a,
            ),
            Curve::new("exact, λ = 1", "exact at λ = 1 (reference)", e1),
        ],
    };
    Ok((panel, note))
}

fn compute(options: &FigureOptions, monitor: &dyn Monitor) -> Result<Fig16> {
    let pre = preset("fig16")?;
    let base: Params = pre.params.clone();
    let b = Boundaries::of(options, monitor);
    let mut notes: Vec<String> = pre.notes.iter().map(|s| s.to_string()).collect();
    let xs = linspace(0.9, 1.0, b.points);
    let along_lambda = Sweep {
        base: &base,
        x_key: "lambda",
        xs: &xs,
        y_range: (1e-4, 0.25),
    };
    let xr = linspace(0.9, 0.999, b.points);
    let along_r = Sweep {
        base: &base,
        x_key: "r",
        xs: &xr,
        y_range: (1e-4, 0.09),
    };
    crate::step(monitor, 0, 4)?;
    let (a, note) = panel_a(&b, options, along_lambda)?;
    notes.push(note);
    crate::step(monitor, 1, 4)?;
    let effect_of_r = Family {
        caption: "(b) effect of r; shaded: rest at r = 1",
        label: "b",
        key: "r",
        symbol: "r",
        values: &RS,
        x_range: (0.9, 1.0),
        // the exact boundary with the wall is known at λ = 1 only
        exact_at: |r, _| (r < 1.0).then(|| vec![1.0]),
        exact_first: false,
    };
    let (b_panel, n) = b.family(&effect_of_r, along_lambda)?;
    notes.extend(n);
    crate::step(monitor, 2, 4)?;
    let (c, note) = panel_c(&b, options, along_r)?;
    notes.push(note);
    crate::step(monitor, 3, 4)?;
    let effect_of_lambda = Family {
        caption: "(d) effect of λ; shaded: rest at λ = 1",
        label: "d",
        key: "lambda",
        symbol: "λ",
        values: &LAMBDAS,
        x_range: (0.9, 0.999),
        exact_at: |l, xs| (l == 1.0).then(|| xs.to_vec()),
        exact_first: true,
    };
    let (d, n) = b.family(&effect_of_lambda, along_r)?;
    notes.extend(n);
    let header = table_notes(
        16,
        "oscillation and rest regions in (μ0, λ) and (μ0, r)",
        options,
        &notes,
    );
    let caption = caption(
        16,
        "oscillation (white) and rest (shaded) regions in (μ0, λ) and (μ0, r), with the effect of r and λ",
        options,
        &base,
        &["mu0", "lambda", "r"],
        vec![
            "solid: simulation (predictor–corrector from U(0) = 1e-9, growth rate of ln(amplitude) after the start-up transient, bracket below the line width); dashed: averaging, f′(0) = 0 of Eq. 18; ○ / ×: exact linearisation (with the wall known only at λ = 1)".into(),
        ],
    );
    Ok(Fig16 {
        caption,
        notes: header,
        panels: vec![a, b_panel, c, d],
    })
}
