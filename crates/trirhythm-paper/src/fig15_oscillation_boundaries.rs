//! Fig. 15: the oscillation (Hopf) boundary μ0 against λ and against r for ω0 ∈ {0.9, 0.5, 0.3}
//! at D = 0 — by simulation (predictor–corrector from a small amplitude, bracketed), by
//! averaging (f′(0) = 0 of Eq. 18) and by the exact linearisation where it is exact — the
//! region below the simulated boundary being the non-oscillating one.
//!
//! Method: [`crate::boundary`], shared with Fig. 16. Checked by the library's oscillation
//! tests and `tests/figures.rs`.

use crate::boundary::{distance_text, linspace, table, Boundaries, Curve, Panel, Sweep};
use crate::notes::{caption, table_notes, Caption};
use crate::table::Table;
use crate::{Figure, FigureOptions, Monitor};

use serde::{Deserialize, Serialize};
use trirhythm::engine::Barrier;
use trirhythm::model::{preset, Params};
use trirhythm::Result;

/// ω0 of the three rows.
pub const OMEGAS: [f64; 3] = [0.9, 0.5, 0.3];
/// λ of the (μ0, r) panels: the exact boundary with the wall is known at λ = 1.
pub const LAMBDA_R: f64 = 1.0;

/// Fig. 15's data.
#[derive(Serialize, Deserialize)]
pub struct Fig15 {
    /// What the figure shows, shared parameters, variant, method.
    pub caption: Caption,
    /// Notes of the data table: simulations per panel, distances between the methods.
    pub notes: Vec<String>,
    /// Panels a–f: per ω0, μ0 against λ then μ0 against r.
    pub panels: Vec<Panel>,
}

impl Figure for Fig15 {
    const NUMBER: u32 = 15;
    const TITLE: &'static str = "oscillation (Hopf) boundary μ0 against λ and r, three ω0";

    fn compute(options: &FigureOptions, monitor: &dyn Monitor) -> Result<Fig15> {
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

/// Panel `label`: μ0 against λ at r of the preset, the exact boundary with and without the
/// wall beside the simulated and averaged ones.
fn against_lambda(
    b: &Boundaries,
    options: &FigureOptions,
    p: &Params,
    (label, w): (&str, f64),
) -> Result<(Panel, String)> {
    let xs = linspace(0.9, 1.0, b.points);
    let yr = (1e-4, if w > 0.6 { 0.16 } else { 0.12 });
    let sweep = Sweep {
        base: p,
        x_key: "lambda",
        xs: &xs,
        y_range: yr,
    };
    let (s, a) = b.methods(sweep)?;
    let e = b.exact(sweep, Barrier::On)?;
    let free = b.exact(sweep, Barrier::Off)?;
    let r_lambda = p.restitution;
    let note = format!(
        "panel {label} (ω0 = {w}, r = {r_lambda}, μ0 against λ): {} simulations; largest distance simulation–averaging {}; simulation–exact (λ = 1 only) {}; the exact boundary without the wall, drawn for reference, is {} from the simulated one with the wall",
        s.iter().map(|q| q.simulations).sum::<usize>(),
        distance_text(&s, &a, "λ"),
        distance_text(&s, &e, "λ"),
        distance_text(&s, &free, "λ"),
    );
    let panel = Panel {
        caption: format!("({label}) ω0 = {w}, r = {r_lambda}"),
        label: label.into(),
        x_desc: "λ".into(),
        x_range: (0.9, 1.0),
        y_range: yr,
        curves: vec![
            Curve::new("simulation", "simulation (bracket < line width)", s),
            Curve::new(
                "averaging",
                format!("averaging, f′(0) = 0 ({})", options.variant.name()),
                a,
            ),
            Curve::new("exact", "exact, wall (λ = 1 only)", e),
            Curve::new("exact, no wall", "exact without the wall (reference)", free),
        ],
    };
    Ok((panel, note))
}

/// Panel `label`: μ0 against r at λ = 1, where the exact boundary with the wall is known.
fn against_r(
    b: &Boundaries,
    options: &FigureOptions,
    p: &Params,
    (label, w): (&str, f64),
) -> Result<(Panel, String)> {
    let p = p.with("lambda", LAMBDA_R)?;
    let xs = linspace(0.9, 0.999, b.points);
    let yr = (1e-4, if w > 0.6 { 0.08 } else { 0.045 });
    let sweep = Sweep {
        base: &p,
        x_key: "r",
        xs: &xs,
        y_range: yr,
    };
    let (s, a) = b.methods(sweep)?;
    let e = b.exact(sweep, Barrier::On)?;
    let note = format!(
        "panel {label} (ω0 = {w}, λ = {LAMBDA_R}, μ0 against r): {} simulations; largest distance simulation–averaging {}; simulation–exact {}",
        s.iter().map(|q| q.simulations).sum::<usize>(),
        distance_text(&s, &a, "r"),
        distance_text(&s, &e, "r"),
    );
    let panel = Panel {
        caption: format!("({label}) ω0 = {w}, λ = {LAMBDA_R}"),
        label: label.into(),
        x_desc: "r".into(),
        x_range: (0.9, 0.999),
        y_range: yr,
        curves: vec![
            Curve::new("simulation", "simulation (bracket < line width)", s),
            Curve::new(
                "averaging",
                format!("averaging, f′(0) = 0 ({})", options.variant.name()),
                a,
            ),
            Curve::new("exact", "exact at λ = 1: μ0π/(2ω_{d}) + ln r = 0", e),
        ],
    };
    Ok((panel, note))
}

fn compute(options: &FigureOptions, monitor: &dyn Monitor) -> Result<Fig15> {
    let pre = preset("fig15")?;
    let base = pre.params.clone();
    let r_lambda = base.restitution;
    let b = Boundaries::of(options, monitor);
    let mut panels = Vec::new();
    let mut notes: Vec<String> = pre.notes.iter().map(|s| s.to_string()).collect();
    notes.push(format!(
        "the paper prints neither λ nor r: μ0-against-λ panels at r = {r_lambda} (preset), μ0-against-r panels at λ = {LAMBDA_R}, where the exact boundary with the wall is known"
    ));
    let letters = ["a", "b", "c", "d", "e", "f"];
    for (row, &w) in OMEGAS.iter().enumerate() {
        let p = base.with("omega0", w)?;
        crate::step(monitor, 2 * row, 6)?;
        let (panel, note) = against_lambda(&b, options, &p, (letters[2 * row], w))?;
        panels.push(panel);
        notes.push(note);
        crate::step(monitor, 2 * row + 1, 6)?;
        let (panel, note) = against_r(&b, options, &p, (letters[2 * row + 1], w))?;
        panels.push(panel);
        notes.push(note);
    }
    notes.push(
        "with decreasing ω0 the boundary against λ falls (ω0^λ cos(πλ/2)) and the impact term (∝ ω1 ∝ ω0) shrinks: the rest region narrows; the averaging's and the simulated boundary separate as ω0 falls and λ moves away from 1".into(),
    );
    let header = table_notes(
        15,
        "oscillation (Hopf) boundary μ0 against λ and r, three ω0",
        options,
        &notes,
    );
    let caption = caption(
        15,
        "oscillation (Hopf) boundary: μ0 against λ (left) and r (right) for ω0 = 0.9, 0.5, 0.3",
        options,
        &base,
        &["mu0", "omega0", "lambda", "r"],
        vec![
            format!("shaded: no oscillation (a small amplitude dies, simulated); white: oscillation. Left: r = {r_lambda}; right: λ = {LAMBDA_R} (not printed in the paper; the exact boundary with the wall is known only at λ = 1)"),
            format!("simulation: predictor–corrector from U(0) = 1e-9, Δt = {}, growth rate of ln(amplitude) after the start-up transient, bracket ≤ {} relative", b.classifier.method.dt, b.search.tolerance),
        ],
    );
    Ok(Fig15 {
        caption,
        notes: header,
        panels,
    })
}
