//! Fig. 11: (a) limit-cycle amplitude against λ — the averaging's branches (f = 0, Eq. 18, at
//! D = 0) against long noise-free simulations of Eq. (1) from several initial amplitudes;
//! (b) the stationary P(A) for four λ — theory (both variants) against Monte Carlo of Eq. (1)
//! and Eq. (5), with error bars, distances and stationarity verdicts.

use super::fig05_branches::runs;
use super::montecarlo::{
    amplitude_csv, amplitude_legend, amplitude_panel, draw_amplitude_panel, stationary_count,
    two_rows_of_four, AmplitudePanel, Sizes, PANEL,
};
use super::{csv_header, heading, Figure, FigureContext};
use crate::common::{num, Csv};
use crate::maps::branch_diagram;
use crate::output::write_atomic;
use crate::plot::{chart, pe, save, Heading, Picture, PALETTE};
use anyhow::Result;
use plotters::coord::Shift;
use plotters::prelude::*;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use trirhythm::engine::{run, Flow, ImpactMemory, PredictorCorrector, Problem, Stepper, System};
use trirhythm::model::{preset, Params};
use trirhythm::theory::bifurcation::{BranchDiagram, What};

/// λ of the simulations of panel (a) and of the P(A) panels (b): one, two, three and two
/// peaks in the theory (the paper does not print its λ).
const LAMBDAS_A: [f64; 8] = [0.9, 0.93, 0.95, 0.97, 0.98, 0.99, 0.995, 1.0];
const STARTS_A: [f64; 4] = [0.5, 4.0, 8.0, 14.0];
const LAMBDAS_B: [f64; 4] = [0.93, 0.97, 0.99, 0.998];

/// One simulated point of panel (a): λ, the initial amplitude, the settled amplitude (mean of
/// the last maxima of U) and how much those maxima still spread.
#[derive(Serialize, Deserialize, Clone, Copy)]
pub struct Settled {
    lambda: f64,
    u0: f64,
    amplitude: f64,
    spread: f64,
}

/// Fig. 11's data.
#[derive(Serialize, Deserialize)]
pub struct Fig11 {
    heading: Heading,
    header: Vec<String>,
    branches: BranchDiagram,
    settled: Vec<Settled>,
    panels: Vec<AmplitudePanel>,
}

/// The maxima of U over the last tenth of a noise-free path from U(0) = u0.
fn settle(p: &Params, u0: f64, t_end: f64) -> Result<Settled> {
    let problem = Problem::from_params(p)?.with_start(u0, 0.0)?;
    // the ensembles' convention: the memory restarts at each impact (README, "Ensembles")
    let m = PredictorCorrector {
        impact_memory: ImpactMemory::Restart,
        ..Default::default()
    };
    let steps = (t_end / m.dt).round() as u64;
    let mut s = Stepper::new(&problem, &m, (0, 0), t_end)?;
    let from = 0.9 * t_end;
    let (mut prev_v, mut maxima) = (0.0f64, Vec::new());
    run(
        &mut s,
        steps,
        &mut |s: &Stepper| {
            if s.time() >= from && prev_v > 0.0 && s.v() <= 0.0 {
                maxima.push(s.u());
            }
            prev_v = s.v();
            Flow::Continue
        },
        &trirhythm::monitor::Silent,
    )?;
    let n = maxima.len().max(1) as f64;
    let mean = maxima.iter().sum::<f64>() / n;
    // below 1e-6 the path has come to rest (the rest state is stable there)
    let (mean, spread) = if mean < 1e-6 {
        (0.0, 0.0)
    } else {
        (
            mean,
            maxima.iter().fold(0.0f64, |m, &x| m.max((x - mean).abs())),
        )
    };
    Ok(Settled {
        lambda: p.lambda,
        u0,
        amplitude: if maxima.is_empty() { 0.0 } else { mean },
        spread,
    })
}

impl Figure for Fig11 {
    const NUMBER: u32 = 11;
    const TITLE: &'static str = "limit-cycle amplitude vs λ and P(A) against Monte Carlo";

    fn compute(ctx: &FigureContext) -> Result<Fig11> {
        let pre = preset("fig11")?;
        let (t_settle, step, sz) = if ctx.quick {
            (200.0, 0.005, Sizes::of(true))
        } else {
            (3000.0, 0.001, Sizes::of(false))
        };
        let quiet = pre.params.with("D", 0.0)?;
        let branches = branch_diagram(
            &quiet,
            ctx.variant,
            What::Rhythmicity,
            "lambda",
            0.9,
            1.0,
            step,
        )?;
        let jobs: Vec<(f64, f64)> = LAMBDAS_A
            .iter()
            .flat_map(|&l| STARTS_A.iter().map(move |&u| (l, u)))
            .collect();
        let settled = jobs
            .par_iter()
            .map(|&(l, u)| settle(&quiet.with("lambda", l)?, u, t_settle))
            .collect::<Result<Vec<_>>>()?;
        let mut notes: Vec<String> = pre.notes.iter().map(|s| s.to_string()).collect();
        notes.push(format!(
            "(a): branches of f(A) = 0 (Eq. 18, D = 0) by continuation in λ; simulations of Eq. 1 at D = 0 (impact memory restarted) from U(0) ∈ {STARTS_A:?} for {t_settle} time units, amplitude = mean of the maxima of U over the last tenth (0: the path came to rest)"
        ));
        let unsettled: Vec<String> = settled
            .iter()
            .filter(|s| s.spread > 1e-2 * s.amplitude.max(1e-3))
            .map(|s| format!("λ = {}, U(0) = {} (spread {:.3})", s.lambda, s.u0, s.spread))
            .collect();
        notes.push(if unsettled.is_empty() {
            "(a): every simulation settled (maxima spread < 1 %)".into()
        } else {
            format!(
                "(a): not settled (maxima spread ≥ 1 %): {}",
                unsettled.join("; ")
            )
        });
        notes.push(format!("(b): λ ∈ {LAMBDAS_B:?} chosen (the paper does not print them): 1, 2, 3 and 2 peaks in the theory; ensembles: {}", sz.describe()));
        let mut panels = Vec::new();
        for (i, &l) in LAMBDAS_B.iter().enumerate() {
            let p = pre.params.with("lambda", l)?;
            let (panel, n) = amplitude_panel(
                format!("(b{}) λ = {l}", i + 1),
                &p,
                ctx.variant,
                &[System::Fractional, System::Equivalent],
                sz,
            )?;
            notes.extend(n);
            panels.push(panel);
        }
        let (passed, total) = stationary_count(&panels);
        let verdict = format!("(b): stationarity check passed by {passed} of {total} ensembles");
        notes.push(verdict.clone());
        let heading = heading(
            11,
            "limit-cycle amplitude against λ, and P(A) for four λ against Monte Carlo",
            ctx,
            &pre.params,
            &["lambda"],
            vec![
                format!("(a) D = 0: averaging's branches (solid stable, dashed unstable) and simulations of Eq. 1 ({t_settle} time units from U(0) = {STARTS_A:?})"),
                format!("(b) Monte Carlo: {}; {verdict}", sz.describe()),
            ],
        );
        Ok(Fig11 {
            heading,
            header: csv_header(11, Self::TITLE, ctx, &notes),
            branches,
            settled,
            panels,
        })
    }

    fn render(&self, stem: &Path) -> Result<Vec<PathBuf>> {
        let mut csv = Csv::new(&self.header, &["lambda", "u0", "amplitude", "spread"]);
        for s in &self.settled {
            csv.row([num(s.lambda), num(s.u0), num(s.amplitude), num(s.spread)]);
        }
        let a_path = stem.with_extension("csv");
        write_atomic(&a_path, csv.finish()?.as_bytes())?;
        let name = stem.file_name().unwrap_or_default().to_string_lossy();
        let b_path = stem.with_file_name(format!("{name}_pdf.csv"));
        write_atomic(
            &b_path,
            amplitude_csv(&self.header, &self.panels)?.as_bytes(),
        )?;
        let mut files = vec![a_path, b_path];
        files.extend(save(self, stem)?);
        Ok(files)
    }
}

impl Picture for Fig11 {
    fn size(&self) -> (u32, u32) {
        two_rows_of_four(&self.panels)
    }

    fn heading(&self) -> Heading {
        self.heading.clone()
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()>
    where
        DB::ErrorType: 'static,
    {
        let (top, rest) = root.split_vertically(PANEL.1);
        let (bottom, strip) = rest.split_vertically(PANEL.1);
        let (a_area, _) = top.split_horizontally(3 * PANEL.0);
        let amax = self
            .branches
            .branches
            .iter()
            .flat_map(|b| b.points.iter().map(|q| q.amplitude))
            .chain(self.settled.iter().map(|s| s.amplitude))
            .fold(1.0f64, f64::max);
        let mut c = chart(
            &a_area,
            "(a) limit-cycle amplitude against λ (D = 0)",
            self.branches.start..self.branches.stop,
            0.0..amax * 1.08,
            "λ",
            "A",
        )?;
        for b in &self.branches.branches {
            for (stable, pts) in runs(&b.points) {
                if stable {
                    c.draw_series(LineSeries::new(pts, PALETTE[0].stroke_width(2)))
                        .map_err(pe)?;
                } else {
                    c.draw_series(DashedLineSeries::new(pts, 6, 4, PALETTE[1].stroke_width(2)))
                        .map_err(pe)?;
                }
            }
        }
        c.draw_series(
            self.settled
                .iter()
                .map(|s| Circle::new((s.lambda, s.amplitude), 6, PALETTE[2].stroke_width(2))),
        )
        .map_err(pe)?;
        // panel (a)'s key, beside it
        let (_, key) = top.split_horizontally(3 * PANEL.0);
        crate::plot::LegendStrip {
            entries: vec![
                (
                    crate::plot::Symbol::Line(PALETTE[0]),
                    "stable branch".into(),
                ),
                (
                    crate::plot::Symbol::Dashed(PALETTE[1]),
                    "unstable branch".into(),
                ),
                (
                    crate::plot::Symbol::Ring(PALETTE[2]),
                    "simulation of Eq. 1".into(),
                ),
            ],
        }
        .draw(&key.margin(60, 0, 0, 0))?;
        for (area, p) in bottom.split_evenly((1, 4)).iter().zip(&self.panels) {
            draw_amplitude_panel(area, p)?;
        }
        amplitude_legend(&self.panels).draw(&strip)
    }
}
