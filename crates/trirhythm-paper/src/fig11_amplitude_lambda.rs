//! Fig. 11: (a) limit-cycle amplitude against λ — the averaging's branches (f = 0, Eq. 18, at
//! D = 0) against long noise-free simulations of Eq. (1) from several initial amplitudes;
//! (b) the stationary P(A) for four λ — theory (both variants) against Monte Carlo of Eq. (1)
//! and Eq. (5), with error bars, distances and stationarity verdicts.
//!
//! Method: (a) [`trace_branches`] in λ at D = 0 and noise-free paths of Eq. (1) (impact memory
//! restarted) from four initial amplitudes, the settled amplitude the mean of the last maxima;
//! (b) [`crate::montecarlo`]. Checked by `tests/figures.rs`.

use crate::montecarlo::{
    amplitude_panel, amplitude_table, beyond_line, stationary_count, wells_line, AmplitudePanel,
    Sizes,
};
use crate::notes::num;
use crate::notes::{caption, table_notes, Caption};
use crate::table::Table;
use crate::{Figure, FigureOptions, Monitor};

use serde::{Deserialize, Serialize};
use trirhythm::engine::{run, Flow, ImpactMemory, PredictorCorrector, Problem, Stepper, System};
use trirhythm::model::{preset, Params};
use trirhythm::theory::bifurcation::{branches as trace_branches, BranchDiagram, What};
use trirhythm::Result;

/// λ of the simulations of panel (a) and of the P(A) panels (b): one, two, three and two
/// peaks in the theory (the paper does not print its λ).
pub const LAMBDAS_A: [f64; 8] = [0.9, 0.93, 0.95, 0.97, 0.98, 0.99, 0.995, 1.0];
/// Initial amplitudes U(0) of the simulations of panel (a).
pub const STARTS_A: [f64; 4] = [0.5, 4.0, 8.0, 14.0];
/// λ of the P(A) panels (b).
pub const LAMBDAS_B: [f64; 4] = [0.93, 0.97, 0.99, 0.998];

/// One simulated point of panel (a): λ, the initial amplitude, the settled amplitude (mean of
/// the last maxima of U) and how much those maxima still spread.
#[derive(Serialize, Deserialize, Clone, Copy)]
pub struct Settled {
    /// Fractional order λ.
    pub lambda: f64,
    /// Initial amplitude U(0).
    pub u0: f64,
    /// Settled amplitude (0: the path came to rest).
    pub amplitude: f64,
    /// Largest deviation of the last maxima from their mean.
    pub spread: f64,
}

/// Fig. 11's data.
#[derive(Serialize, Deserialize)]
pub struct Fig11 {
    /// What the figure shows, shared parameters, variant, verdict.
    pub caption: Caption,
    /// Notes of the data tables.
    pub notes: Vec<String>,
    /// (a) the averaging's branches against λ at D = 0.
    pub branches: BranchDiagram,
    /// (a) the simulations.
    pub settled: Vec<Settled>,
    /// (b) P(A) for four λ.
    pub panels: Vec<AmplitudePanel>,
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

    fn compute(options: &FigureOptions, monitor: &dyn Monitor) -> Result<Fig11> {
        let ctx = options;
        let pre = preset("fig11")?;
        let (t_settle, step, sz) = if ctx.quick {
            (200.0, 0.005, Sizes::of(true))
        } else {
            (3000.0, 0.001, Sizes::of(false))
        };
        let quiet = pre.params.with("D", 0.0)?;
        monitor.check()?;
        let jobs: Vec<(f64, f64)> = LAMBDAS_A
            .iter()
            .flat_map(|&l| STARTS_A.iter().map(move |&u| (l, u)))
            .collect();
        // (a)'s branches and simulations and (b)'s panels, all side by side
        let progress = crate::Progress::new(0, LAMBDAS_B.len());
        let b = |(i, &l): (usize, &f64)| {
            let p = pre.params.with("lambda", l)?;
            let panel = amplitude_panel(
                monitor,
                format!("(b{}) λ = {l}", i + 1),
                &p,
                ctx.variant,
                &[System::Fractional, System::Equivalent],
                sz,
            )?;
            progress.advance(monitor, 1)?;
            Ok(panel)
        };
        let indexed: Vec<(usize, &f64)> = LAMBDAS_B.iter().enumerate().collect();
        let (branches, (settled, computed)) = trirhythm::profile::parallel(|stage| {
            rayon::join(
                || {
                    stage.task(|| {
                        trace_branches(
                            &quiet,
                            ctx.variant,
                            What::Rhythmicity,
                            "lambda",
                            0.9,
                            1.0,
                            step,
                        )
                    })
                },
                || {
                    rayon::join(
                        || {
                            stage.task(|| {
                                crate::each(&jobs, |&(l, u)| {
                                    monitor.check()?;
                                    settle(&quiet.with("lambda", l)?, u, t_settle)
                                })
                            })
                        },
                        || stage.task(|| crate::each(&indexed, |&x| b(x))),
                    )
                },
            )
        });
        let (branches, settled, computed) = (branches?, settled?, computed?);
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
        for (panel, n) in computed {
            notes.extend(n);
            panels.push(panel);
        }
        let (passed, total) = stationary_count(&panels);
        let verdict = format!("(b): stationarity check passed by {passed} of {total} ensembles");
        notes.push(verdict.clone());
        let caption = caption(
            11,
            "limit-cycle amplitude against λ, and P(A) for four λ against Monte Carlo",
            ctx,
            &pre.params,
            &["lambda"],
            vec![
                format!("(a) D = 0: averaging's branches (solid stable, dashed unstable) and simulations of Eq. 1 ({t_settle} time units from U(0) = {STARTS_A:?})"),
                format!("(b) Monte Carlo: {}; {verdict}", sz.describe()),
                beyond_line(&panels),
                wells_line(&panels),
            ],
        );
        Ok(Fig11 {
            caption,
            notes: table_notes(11, Self::TITLE, ctx, &notes),
            branches,
            settled,
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
        let mut csv = Table::new(&self.notes, &["lambda", "u0", "amplitude", "spread"]);
        for s in &self.settled {
            csv.row([num(s.lambda), num(s.u0), num(s.amplitude), num(s.spread)]);
        }
        // (a)'s lines: the averaging's branches against λ
        let mut branches = Table::new(&self.notes, &["branch", "lambda", "A", "stable"]);
        for (i, b) in self.branches.branches.iter().enumerate() {
            for q in &b.points {
                branches.row([
                    i.to_string(),
                    num(q.param),
                    num(q.amplitude),
                    u8::from(q.stable).to_string(),
                ]);
            }
        }
        vec![
            csv,
            branches.named("_branches"),
            amplitude_table(&self.notes, &self.panels).named("_pdf"),
        ]
    }
}
