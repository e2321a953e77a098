//! What Figs 11, 13 and 14 share: Monte Carlo ensembles of Eq. (1) and Eq. (5) beside the
//! averaged theory's P(A) in both variants, with the distances, the modes and the stationarity
//! verdict of each run, and the drawing of one such amplitude panel.
//!
//! Drawing only: the ensembles and their comparison with the theory are [`trirhythm_paper::montecarlo`].

use crate::render::plot::{
    chart, draw_line, draw_markers, series, Backend, Dash, Marker, SeriesStyle, Symbol, PALETTE,
};
use anyhow::Result;
use plotters::coord::Shift;
use plotters::prelude::*;
use trirhythm_paper::montecarlo::{AmplitudePanel, McRun, Shown};

/// Densities and standard errors per bin.
/// The legend entries of an amplitude panel's series.
pub fn legend_entries(systems: &[&str]) -> Vec<(Symbol, String)> {
    let mut e = vec![
        (
            Symbol::Series(SeriesStyle {
                marker: Marker::None,
                ..theory_style(0)
            }),
            "theory, paper variant (Eq. 27)".to_string(),
        ),
        (
            Symbol::Series(SeriesStyle {
                marker: Marker::None,
                ..theory_style(1)
            }),
            "theory, consistent variant".to_string(),
        ),
    ];
    for (i, s) in systems.iter().enumerate() {
        let style = mc_style(i);
        e.push((
            Symbol::Series(SeriesStyle {
                dash: Dash::Solid,
                ..style
            }),
            format!("Monte Carlo of {s} (± 1 s.e.)"),
        ));
    }
    e
}

/// The theory's curves: the paper variant black and solid, the consistent one blue and
/// dashed.
fn theory_style(i: usize) -> SeriesStyle {
    series(2 * i)
}

/// Monte Carlo of the k-th system: vermillion circles, then bluish-green crosses (the
/// markers part them in greyscale).
fn mc_style(k: usize) -> SeriesStyle {
    SeriesStyle {
        colour: [PALETTE[1], PALETTE[3]][k % 2],
        dash: Dash::Solid,
        marker: [Marker::Circle, Marker::Cross][k % 2],
    }
}

/// Draw one amplitude panel.
pub fn draw_amplitude_panel<DB: Backend>(
    area: &DrawingArea<DB, Shift>,
    p: &AmplitudePanel,
) -> Result<()> {
    let x_max = p
        .runs
        .iter()
        .filter_map(|r| r.edges.last().copied())
        .chain(p.theory.iter().filter_map(|t| t.1.last().copied()))
        .fold(1.0f64, f64::max);
    let finite_max =
        |it: &mut dyn Iterator<Item = f64>| it.filter(|v| v.is_finite()).fold(0.0f64, f64::max);
    let shown: Vec<(Shown, bool)> = p.runs.iter().map(McRun::shown_density).collect();
    let mc_max = finite_max(&mut shown.iter().flat_map(|((density, stderr), _)| {
        density.iter().zip(stderr).map(|(d, s)| d + s.max(0.0))
    }));
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
    // (a run by the well decomposition is stationary by that method's diagnostic)
    // the badges go into the panel's title, never over the data
    let mut caption = p.caption.clone();
    if cut {
        caption.push_str(&format!("; theory peak {theory_max:.1} cut"));
    }
    let mixtures: Vec<&str> = p
        .runs
        .iter()
        .zip(&shown)
        .filter(|(_, (_, m))| *m)
        .map(|(r, _)| r.system.as_str())
        .collect();
    if mixtures.is_empty() {
        if !stationary {
            caption.push_str("; MC NOT stationary");
        }
    } else {
        caption.push_str(&format!("; {}: wells at H_min", mixtures.join(", ")));
        let others: Vec<&str> = p
            .runs
            .iter()
            .zip(&shown)
            .filter(|(r, (_, m))| !*m && !r.stationary)
            .map(|(r, _)| r.system.as_str())
            .collect();
        if !others.is_empty() {
            caption.push_str(&format!("; {} NOT stationary", others.join(", ")));
        }
    }
    for r in p.runs.iter().filter(|r| r.estimator == "wells") {
        caption.push_str(&format!("; {} by wells", r.system));
    }
    if p.runs.iter().any(|r| !r.step_warnings.is_empty()) {
        caption.push_str("; Δt coarse (notes)");
    }
    let c = chart(area, &caption, 0.0..x_max, 0.0..y_max * 1.08, "A", "P(A)")?;
    for (i, (_, xs, ys)) in p.theory.iter().enumerate() {
        let pts: Vec<(f64, f64)> = xs.iter().copied().zip(ys.iter().copied()).collect();
        draw_line(&c, &pts, theory_style(i), 2)?;
    }
    for (k, (r, ((density, stderr), _))) in p.runs.iter().zip(&shown).enumerate() {
        let style = mc_style(k);
        let mids: Vec<(f64, f64, f64)> = r
            .edges
            .windows(2)
            .zip(density.iter().zip(stderr))
            .filter(|(_, (d, _))| **d > 0.0)
            .map(|(w, (&d, &s))| (0.5 * (w[0] + w[1]), d, if s.is_finite() { s } else { 0.0 }))
            .collect();
        for &(x, d, s) in &mids {
            let bar = [(x, (d - s).max(0.0)), (x, d + s)];
            draw_line(
                &c,
                &bar,
                SeriesStyle {
                    dash: Dash::Solid,
                    ..style
                },
                1,
            )?;
        }
        let centres: Vec<(f64, f64)> = mids.iter().map(|&(x, d, _)| (x, d)).collect();
        draw_markers(&c, &centres, style)?;
    }
    Ok(())
}

/// A grid of amplitude panels with one legend strip below them.
pub fn draw_amplitude_grid<DB: Backend>(
    root: &DrawingArea<DB, Shift>,
    panels: &[AmplitudePanel],
    layout: (usize, usize),
    panel_height: u32,
) -> Result<()> {
    let (area, strip) = root.split_vertically(panel_height * layout.0 as u32);
    for (a, p) in area.split_evenly(layout).iter().zip(panels) {
        draw_amplitude_panel(a, p)?;
    }
    amplitude_legend(panels).draw(&strip)
}

/// Size of one amplitude panel in pixels (Figs 11 and 13).
pub const PANEL: (u32, u32) = (360, 440);

/// Size of a figure of two rows of four amplitude panels with the legend strip below.
pub fn two_rows_of_four(panels: &[AmplitudePanel]) -> (u32, u32) {
    let w = 4 * PANEL.0;
    (w, 2 * PANEL.1 + amplitude_legend(panels).height(w))
}

/// The legend of amplitude panels: both theories and every simulated system.
pub fn amplitude_legend(panels: &[AmplitudePanel]) -> crate::render::plot::LegendStrip {
    let systems: Vec<&str> = panels
        .first()
        .map(|p| p.runs.iter().map(|r| r.system.as_str()).collect())
        .unwrap_or_default();
    crate::render::plot::LegendStrip {
        entries: legend_entries(&systems),
    }
}
