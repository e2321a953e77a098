//! Fig. 16: oscillation and rest regions at D = 0 — (a) the (μ0, λ) plane at r = 0.99,
//! (b) the effect of r on it, (c) the (μ0, r) plane at λ = 0.999, (d) the effect of λ on it —
//! each boundary by simulation, by averaging and (where exact) by the linearisation at U = 0.

use super::fig15_oscillation_boundaries::{
    compute, distance_text, draw_panel, linspace, render_panels, settings, Curve, Panel, Role,
    EXACT,
};
use super::{csv_header, heading, Figure, FigureContext};
use crate::common::progress;
use crate::plot::{Heading, Picture, PALETTE};
use anyhow::Result;
use plotters::coord::Shift;
use plotters::prelude::*;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use trirhythm::analysis::oscillation::Method;
use trirhythm::engine::Barrier;
use trirhythm::model::preset;

/// r of panel (b), λ of panel (d).
const RS: [f64; 4] = [1.0, 0.99, 0.97, 0.95];
const LAMBDAS: [f64; 4] = [1.0, 0.999, 0.995, 0.99];

/// Fig. 16's data.
#[derive(Serialize, Deserialize)]
pub struct Fig16 {
    heading: Heading,
    header: Vec<String>,
    panels: Vec<Panel>,
}

impl Figure for Fig16 {
    const NUMBER: u32 = 16;
    const TITLE: &'static str = "oscillation and rest regions in (μ0, λ) and (μ0, r)";

    fn compute(ctx: &FigureContext) -> Result<Fig16> {
        compute_fig16(ctx)
    }

    fn render(&self, stem: &Path) -> Result<Vec<PathBuf>> {
        render_panels(self, &self.header, &self.panels, stem)
    }
}

fn compute_fig16(ctx: &FigureContext) -> Result<Fig16> {
    let pre = preset("fig16")?;
    let base = pre.params.clone();
    let (classifier, search, n) = settings(ctx.quick);
    let sim = Method::Simulation(classifier);
    let avg = Method::Averaging(ctx.variant);
    let mut notes: Vec<String> = pre.notes.iter().map(|s| s.to_string()).collect();
    let bar = progress(4, "figure 16");
    let (r_a, l_c) = (base.restitution, base.lambda);
    // (a) (μ0, λ) at r = 0.99
    let xs = linspace(0.9, 1.0, n);
    let yr = (1e-4, 0.25);
    let s = compute(&base, Barrier::On, "lambda", &xs, yr, &sim, &search)?;
    let a = compute(&base, Barrier::On, "lambda", &xs, yr, &avg, &search)?;
    let e = compute(
        &base,
        Barrier::On,
        "lambda",
        &xs,
        yr,
        &Method::Exact,
        &search,
    )?;
    let free = compute(
        &base,
        Barrier::Off,
        "lambda",
        &xs,
        yr,
        &Method::Exact,
        &search,
    )?;
    notes.push(format!(
        "panel a (r = {r_a}): largest distance simulation–averaging {}; simulation–exact (λ = 1 only) {}; exact without the wall (reference) {}",
        distance_text(&s, &a, "λ"),
        distance_text(&s, &e, "λ"),
        distance_text(&s, &free, "λ")
    ));
    let mut panels = vec![Panel {
        style_key: false,
        caption: format!("(a) (μ0, λ) plane, r = {r_a}"),
        label: "a".into(),
        x_desc: "λ".into(),
        x_range: (0.9, 1.0),
        y_range: yr,
        curves: vec![
            Curve::new(Role::Simulation, "simulation", s),
            Curve::new(
                Role::Averaging,
                format!("averaging ({})", ctx.variant.name()),
                a,
            ),
            Curve::new(Role::Exact, "exact, wall (λ = 1 only)", e),
            Curve::new(Role::ExactNoWall, "exact without the wall", free),
        ],
    }];
    bar.inc(1);
    // (b) effect of r in (μ0, λ)
    let mut curves = Vec::new();
    for (i, &r) in RS.iter().enumerate() {
        let p = base.with("r", r)?;
        let color = PALETTE[i];
        let s = compute(&p, Barrier::On, "lambda", &xs, yr, &sim, &search)?;
        let a = compute(&p, Barrier::On, "lambda", &xs, yr, &avg, &search)?;
        let e = compute(
            &p,
            Barrier::On,
            "lambda",
            &[1.0],
            yr,
            &Method::Exact,
            &search,
        )?;
        notes.push(format!(
            "panel b, r = {r}: largest distance simulation–averaging {}",
            distance_text(&s, &a, "λ")
        ));
        curves.push(Curve {
            label: format!("r = {r}"),
            method: "simulation".into(),
            points: s,
            color,
            shade: i == 0,
        });
        curves.push(Curve {
            label: String::new(),
            method: "averaging".into(),
            points: a,
            color,
            shade: false,
        });
        if r < 1.0 {
            curves.push(Curve {
                label: String::new(),
                method: "exact".into(),
                points: e,
                color,
                shade: false,
            });
        }
    }
    panels.push(Panel {
        style_key: true,
        caption: "(b) effect of r; shaded: rest at r = 1".into(),
        label: "b".into(),
        x_desc: "λ".into(),
        x_range: (0.9, 1.0),
        y_range: yr,
        curves,
    });
    bar.inc(1);
    // (c) (μ0, r) at λ = 0.999
    let xr = linspace(0.9, 0.999, n);
    let yr2 = (1e-4, 0.09);
    let s = compute(&base, Barrier::On, "r", &xr, yr2, &sim, &search)?;
    let a = compute(&base, Barrier::On, "r", &xr, yr2, &avg, &search)?;
    let at1 = base.with("lambda", 1.0)?;
    let e1 = compute(&at1, Barrier::On, "r", &xr, yr2, &Method::Exact, &search)?;
    notes.push(format!(
        "panel c (λ = {l_c}): largest distance simulation–averaging {}; no exact boundary with the wall at λ < 1 — the exact one at λ = 1, drawn for reference, is {} from the simulated one",
        distance_text(&s, &a, "r"),
        distance_text(&s, &e1, "r")
    ));
    panels.push(Panel {
        style_key: false,
        caption: format!("(c) (μ0, r) plane, λ = {l_c}"),
        label: "c".into(),
        x_desc: "r".into(),
        x_range: (0.9, 0.999),
        y_range: yr2,
        curves: vec![
            Curve::new(Role::Simulation, "simulation", s),
            Curve::new(
                Role::Averaging,
                format!("averaging ({})", ctx.variant.name()),
                a,
            ),
            Curve {
                label: "exact at λ = 1 (reference)".into(),
                method: "exact, λ = 1".into(),
                points: e1,
                color: EXACT,
                shade: false,
            },
        ],
    });
    bar.inc(1);
    // (d) effect of λ in (μ0, r)
    let mut curves = Vec::new();
    for (i, &l) in LAMBDAS.iter().enumerate() {
        let p = base.with("lambda", l)?;
        let color = PALETTE[i];
        let s = compute(&p, Barrier::On, "r", &xr, yr2, &sim, &search)?;
        let a = compute(&p, Barrier::On, "r", &xr, yr2, &avg, &search)?;
        let mut text = format!(
            "panel d, λ = {l}: largest distance simulation–averaging {}",
            distance_text(&s, &a, "r")
        );
        if l == 1.0 {
            let e = compute(&p, Barrier::On, "r", &xr, yr2, &Method::Exact, &search)?;
            text.push_str(&format!(
                "; simulation–exact {}",
                distance_text(&s, &e, "r")
            ));
            curves.push(Curve {
                label: String::new(),
                method: "exact".into(),
                points: e,
                color,
                shade: false,
            });
        }
        notes.push(text);
        curves.push(Curve {
            label: format!("λ = {l}"),
            method: "simulation".into(),
            points: s,
            color,
            shade: i == 0,
        });
        curves.push(Curve {
            label: String::new(),
            method: "averaging".into(),
            points: a,
            color,
            shade: false,
        });
    }
    panels.push(Panel {
        style_key: true,
        caption: "(d) effect of λ; shaded: rest at λ = 1".into(),
        label: "d".into(),
        x_desc: "r".into(),
        x_range: (0.9, 0.999),
        y_range: yr2,
        curves,
    });
    bar.finish_and_clear();
    let header = csv_header(
        16,
        "oscillation and rest regions in (μ0, λ) and (μ0, r)",
        ctx,
        &notes,
    );
    let heading = heading(
        16,
        "oscillation (white) and rest (shaded) regions in (μ0, λ) and (μ0, r), with the effect of r and λ",
        ctx,
        &base,
        &["mu0", "lambda", "r"],
        vec![
            "solid: simulation (predictor–corrector from U(0) = 1e-9, growth rate of ln(amplitude) after the start-up transient, bracket below the line width); dashed: averaging, f′(0) = 0 of Eq. 18; ○ / ×: exact linearisation (with the wall known only at λ = 1)".into(),
        ],
    );
    Ok(Fig16 {
        heading,
        header,
        panels,
    })
}

impl Picture for Fig16 {
    fn size(&self) -> (u32, u32) {
        (1400, 1100)
    }

    fn heading(&self) -> Heading {
        self.heading.clone()
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()>
    where
        DB::ErrorType: 'static,
    {
        let areas = root.split_evenly((2, 2));
        for (area, panel) in areas.iter().zip(&self.panels) {
            draw_panel(area, panel, true)?;
        }
        Ok(())
    }
}
