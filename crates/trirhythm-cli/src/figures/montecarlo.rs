//! What Figs 11, 13 and 14 share: Monte Carlo ensembles of Eq. (1) and Eq. (5) beside the
//! averaged theory's P(A) in both variants, with the distances, the modes and the stationarity
//! verdict of each run, and the drawing of one such amplitude panel.

use crate::ensemble::comparisons;
use crate::plot::{chart, pe, Symbol, PALETTE};
use anyhow::Result;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use serde::{Deserialize, Serialize};
use trirhythm::analysis::ensemble::{run_ensemble, EnsembleResult, EnsembleSpec};
use trirhythm::analysis::versus::theory_layout;
use trirhythm::engine::{ImpactMemory, PredictorCorrector, Problem, System};
use trirhythm::model::Params;
use trirhythm::monitor::Silent;
use trirhythm::theory::averaging::{Theory, Variant};

/// Ensemble sizes of a figure.
#[derive(Debug, Clone, Copy, Serialize, Deserialize)]
pub struct Sizes {
    /// Paths per ensemble.
    pub paths: usize,
    /// Burn-in and recorded window per path.
    pub burn_in: f64,
    /// Recorded window per path.
    pub t_end: f64,
    /// Bins of the amplitude histogram.
    pub bins: usize,
}

impl Sizes {
    /// The ensembles of Figs 11, 13 and 14: full quality (16 paths of 1.5e5 time units; each
    /// figure in a few minutes on 2 cores) or `--quick`.
    pub fn of(quick: bool) -> Sizes {
        if quick {
            Sizes {
                paths: 2,
                burn_in: 10.0,
                t_end: 100.0,
                bins: 50,
            }
        } else {
            Sizes {
                paths: 16,
                burn_in: 500.0,
                t_end: 150_000.0,
                bins: 80,
            }
        }
    }

    /// One line for headings and notes.
    pub fn describe(&self) -> String {
        format!(
            "{} paths per ensemble, burn-in {}, window {} per path, Δt = 0.01, impact memory \
             restarted, seed 1, {} bins",
            self.paths, self.burn_in, self.t_end, self.bins
        )
    }
}

/// The theory against one ensemble, one variant.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Distance {
    /// `paper` or `consistent`.
    pub variant: String,
    /// Hellinger distance and its bootstrap standard error, L1, KS.
    pub hellinger: f64,
    /// Bootstrap standard error of the Hellinger distance.
    #[serde(with = "super::non_finite")]
    pub hellinger_stderr: f64,
    /// L1 distance.
    pub l1: f64,
    /// Largest CDF difference.
    pub ks: f64,
    /// Modes of the binned theory and of the histogram (prominence rule).
    pub modes_theory: usize,
    /// Modes of the histogram.
    pub modes_mc: usize,
}

/// One ensemble's amplitude histogram and verdict.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct McRun {
    /// "Eq. 1" or "Eq. 5".
    pub system: String,
    /// Bin edges, density and standard error.
    pub edges: Vec<f64>,
    /// Density per bin.
    pub density: Vec<f64>,
    /// Standard error per bin.
    pub stderr: Vec<f64>,
    /// Passed the stationarity check.
    pub stationary: bool,
    /// R̂ and ESS.
    #[serde(with = "super::non_finite")]
    pub r_hat: f64,
    /// Effective sample size of the mean amplitude.
    pub ess: f64,
    /// Distances to each variant's theory.
    pub distances: Vec<Distance>,
}

/// One P(A) panel: theory curves and ensembles.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct AmplitudePanel {
    /// Caption.
    pub caption: String,
    /// Theory curves: variant name, amplitudes, densities (empty where undefined).
    pub theory: Vec<(String, Vec<f64>, Vec<f64>)>,
    /// The ensembles.
    pub runs: Vec<McRun>,
}

fn system_name(s: System) -> &'static str {
    match s {
        System::Fractional => "Eq. 1",
        System::Equivalent => "Eq. 5",
        System::Zhuravlev => "Eq. 9",
    }
}

/// An ensemble of `system` for `params` (starts and wells from the theory of `variant`).
pub fn ensemble(
    params: &Params,
    variant: Variant,
    system: System,
    sizes: Sizes,
    joint_bins: usize,
) -> Result<EnsembleResult> {
    let layout = theory_layout(params, variant)
        .ok_or_else(|| anyhow::anyhow!("no theory layout for {}", params.describe()))?;
    let spec = EnsembleSpec {
        paths: sizes.paths,
        seed: 1,
        burn_in: sizes.burn_in,
        length: sizes.t_end,
        bins: sizes.bins,
        joint_bins,
        amplitude_max: layout.amplitude_max,
        wells: layout.wells,
        ..Default::default()
    };
    let starts: Vec<(f64, f64)> = layout.starts.iter().map(|&u| (u, 0.0)).collect();
    let problem = Problem::from_params(params)?
        .with_system(system)?
        .with_starts(&starts)?;
    // the ensembles' convention (README, "Ensembles"): the memory restarts at each impact
    let method = PredictorCorrector {
        impact_memory: ImpactMemory::Restart,
        ..Default::default()
    };
    Ok(run_ensemble(&problem, &method, &spec, &Silent)?)
}

/// A P(A) panel: the theory of both variants and ensembles of each of `systems`.
pub fn amplitude_panel(
    caption: String,
    params: &Params,
    variant: Variant,
    systems: &[System],
    sizes: Sizes,
) -> Result<(AmplitudePanel, Vec<String>)> {
    let mut runs = Vec::new();
    let mut notes = Vec::new();
    let mut a_max = 0.0f64;
    for &system in systems {
        let r = ensemble(params, variant, system, sizes, 8)?;
        a_max = a_max.max(*r.amplitude.edges.last().unwrap_or(&1.0));
        let mut distances = Vec::new();
        for (v, c) in comparisons(params, &r, 1) {
            match c {
                Ok(c) => distances.push(Distance {
                    variant: v.name().into(),
                    hellinger: c.hellinger.value,
                    hellinger_stderr: c.hellinger.stderr,
                    l1: c.l1.value,
                    ks: c.ks.value,
                    modes_theory: c.modes_theory,
                    modes_mc: c.modes_mc,
                }),
                Err(e) => notes.push(format!("{caption}: {} theory: {e}", v.name())),
            }
        }
        let st = &r.stationarity;
        notes.push(format!(
            "{caption}, MC of {}: {}; R̂ = {:.3}, ESS = {:.0}, drift {:.1} s.e.; {}",
            system_name(system),
            if st.stationary {
                "stationarity check passed"
            } else {
                "NOT STATIONARY"
            },
            st.r_hat,
            st.ess,
            st.drift_z,
            distances
                .iter()
                .map(|d| format!(
                    "{}: Hellinger {:.3} ± {:.3}, L1 {:.3}, KS {:.3}, modes {} (theory) vs {} (MC)",
                    d.variant,
                    d.hellinger,
                    d.hellinger_stderr,
                    d.l1,
                    d.ks,
                    d.modes_theory,
                    d.modes_mc
                ))
                .collect::<Vec<_>>()
                .join("; ")
        ));
        runs.push(McRun {
            system: system_name(system).into(),
            edges: r.amplitude.edges.clone(),
            density: r.amplitude.density.clone(),
            stderr: r.amplitude.stderr.clone(),
            stationary: st.stationary,
            r_hat: st.r_hat,
            ess: st.ess,
            distances,
        });
    }
    let mut theory = Vec::new();
    for v in [Variant::Paper, Variant::Consistent] {
        let curve = Theory::new(params, v)
            .and_then(|th| th.amplitude_pdf())
            .map(|pdf| {
                let xs: Vec<f64> = (1..=600).map(|i| a_max * i as f64 / 600.0).collect();
                let ys = xs.iter().map(|&a| pdf.density(a)).collect();
                (xs, ys)
            })
            .unwrap_or_default();
        theory.push((v.name().to_string(), curve.0, curve.1));
    }
    Ok((
        AmplitudePanel {
            caption,
            theory,
            runs,
        },
        notes,
    ))
}

/// The legend entries of an amplitude panel's series.
pub fn legend_entries(systems: &[&str]) -> Vec<(Symbol, String)> {
    let mut e = vec![
        (
            Symbol::Line(PALETTE[0]),
            "theory, paper variant (Eq. 27)".to_string(),
        ),
        (
            Symbol::Dashed(PALETTE[2]),
            "theory, consistent variant".to_string(),
        ),
    ];
    for (i, s) in systems.iter().enumerate() {
        let c = mc_colour(i);
        e.push(if i == 0 {
            (Symbol::Ring(c), format!("Monte Carlo of {s} (± 1 s.e.)"))
        } else {
            (Symbol::Cross(c), format!("Monte Carlo of {s} (± 1 s.e.)"))
        });
    }
    e
}

fn mc_colour(i: usize) -> RGBColor {
    [PALETTE[1], PALETTE[3]][i % 2]
}

/// Draw one amplitude panel.
pub fn draw_amplitude_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    p: &AmplitudePanel,
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let x_max = p
        .runs
        .iter()
        .filter_map(|r| r.edges.last().copied())
        .chain(p.theory.iter().filter_map(|t| t.1.last().copied()))
        .fold(1.0f64, f64::max);
    let finite_max =
        |it: &mut dyn Iterator<Item = f64>| it.filter(|v| v.is_finite()).fold(0.0f64, f64::max);
    let mc_max = finite_max(
        &mut p
            .runs
            .iter()
            .flat_map(|r| r.density.iter().zip(&r.stderr).map(|(d, s)| d + s.max(0.0))),
    );
    let theory_max = finite_max(&mut p.theory.iter().flat_map(|t| t.2.iter().copied()));
    // a theory spike far above the histograms would flatten them: it is cut, and its height
    // given in the caption
    let cut = theory_max > 3.0 * mc_max && mc_max > 0.0;
    let y_max = if cut {
        1.5 * mc_max
    } else {
        theory_max.max(mc_max)
    }
    .max(1e-3);
    let stationary = p.runs.iter().all(|r| r.stationary);
    let mut c = chart(area, &p.caption, 0.0..x_max, 0.0..y_max * 1.08, "A", "P(A)")?;
    // the verdicts, inside the panel at its upper right
    let mut status = Vec::new();
    if !stationary {
        status.push((
            "Monte Carlo NOT stationary".to_string(),
            RGBColor(200, 0, 0),
        ));
    }
    if cut {
        status.push((
            format!("theory peak {theory_max:.1}, cut"),
            RGBColor(90, 90, 90),
        ));
    }
    for (k, (text, colour)) in status.into_iter().enumerate() {
        let style = (crate::plot::FONT, 14)
            .into_font()
            .color(&colour)
            .pos(Pos::new(HPos::Right, VPos::Top));
        c.draw_series(std::iter::once(
            EmptyElement::at((x_max, y_max * 1.08))
                + Text::new(text, (-8, 6 + 18 * k as i32), style),
        ))
        .map_err(pe)?;
    }
    for (i, (_, xs, ys)) in p.theory.iter().enumerate() {
        let pts: Vec<(f64, f64)> = xs.iter().copied().zip(ys.iter().copied()).collect();
        if i == 0 {
            c.draw_series(LineSeries::new(pts, PALETTE[0].stroke_width(2)))
                .map_err(pe)?;
        } else {
            c.draw_series(DashedLineSeries::new(pts, 7, 5, PALETTE[2].stroke_width(2)))
                .map_err(pe)?;
        }
    }
    for (k, r) in p.runs.iter().enumerate() {
        let col = mc_colour(k);
        let mids: Vec<(f64, f64, f64)> = r
            .edges
            .windows(2)
            .zip(r.density.iter().zip(&r.stderr))
            .filter(|(_, (d, _))| **d > 0.0)
            .map(|(w, (&d, &s))| (0.5 * (w[0] + w[1]), d, if s.is_finite() { s } else { 0.0 }))
            .collect();
        c.draw_series(mids.iter().map(|&(x, d, s)| {
            PathElement::new([(x, (d - s).max(0.0)), (x, d + s)], col.stroke_width(1))
        }))
        .map_err(pe)?;
        if k == 0 {
            c.draw_series(
                mids.iter()
                    .map(|&(x, d, _)| Circle::new((x, d), 3, col.stroke_width(1))),
            )
            .map_err(pe)?;
        } else {
            c.draw_series(
                mids.iter()
                    .map(|&(x, d, _)| Cross::new((x, d), 3, col.stroke_width(1))),
            )
            .map_err(pe)?;
        }
    }
    Ok(())
}

/// CSV rows of amplitude panels: `panel,series,A_lo,A_hi,density,stderr` (theory rows have
/// A_lo = A_hi = A and a zero standard error).
pub fn amplitude_csv(header: &[String], panels: &[AmplitudePanel]) -> Result<String> {
    use crate::common::{num, Csv};
    let mut csv = Csv::new(
        header,
        &["panel", "series", "A_lo", "A_hi", "density", "stderr"],
    )
    .allow_infinity("stderr");
    for p in panels {
        for (v, xs, ys) in &p.theory {
            for (x, y) in xs.iter().zip(ys) {
                csv.row([
                    p.caption.clone(),
                    format!("theory {v}"),
                    num(*x),
                    num(*x),
                    num(*y),
                    "0".into(),
                ]);
            }
        }
        for r in &p.runs {
            for (i, w) in r.edges.windows(2).enumerate() {
                let s = r.stderr[i];
                csv.row([
                    p.caption.clone(),
                    format!("MC {}", r.system),
                    num(w[0]),
                    num(w[1]),
                    num(r.density[i]),
                    // one path: no standard error (said in the notes)
                    if s.is_finite() { num(s) } else { "inf".into() },
                ]);
            }
        }
    }
    csv.finish()
}

/// A grid of amplitude panels with one legend strip below them.
pub fn draw_amplitude_grid<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    panels: &[AmplitudePanel],
    layout: (usize, usize),
    panel_height: u32,
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let (area, strip) = root.split_vertically(panel_height * layout.0 as u32);
    for (a, p) in area.split_evenly(layout).iter().zip(panels) {
        draw_amplitude_panel(a, p)?;
    }
    amplitude_legend(panels).draw(&strip)
}

/// Size of one amplitude panel in pixels (Figs 11 and 13).
pub const PANEL: (u32, u32) = (470, 400);

/// Size of a figure of two rows of four amplitude panels with the legend strip below.
pub fn two_rows_of_four(panels: &[AmplitudePanel]) -> (u32, u32) {
    let w = 4 * PANEL.0;
    (w, 2 * PANEL.1 + amplitude_legend(panels).height(w))
}

/// (ensembles that passed the stationarity check, ensembles) over `panels`.
pub fn stationary_count(panels: &[AmplitudePanel]) -> (usize, usize) {
    let runs = || panels.iter().flat_map(|p| &p.runs);
    (runs().filter(|r| r.stationary).count(), runs().count())
}

/// The legend of amplitude panels: both theories and every simulated system.
pub fn amplitude_legend(panels: &[AmplitudePanel]) -> crate::plot::LegendStrip {
    let systems: Vec<&str> = panels
        .first()
        .map(|p| p.runs.iter().map(|r| r.system.as_str()).collect())
        .unwrap_or_default();
    crate::plot::LegendStrip {
        entries: legend_entries(&systems),
    }
}
