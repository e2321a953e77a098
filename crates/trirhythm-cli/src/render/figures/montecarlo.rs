//! What Figs 11, 13 and 14 share: Monte Carlo ensembles of Eq. (1) and Eq. (5) beside the
//! averaged theory's P(A) in both variants, with the distances, the modes and the stationarity
//! verdict of each run, and the drawing of one such amplitude panel.
//!
//! Drawing only: the ensembles and their comparison with the theory are [`trirhythm_paper::montecarlo`].

use crate::render::plot::{
    chart, chart_log_y, draw_line, draw_markers, series, Backend, Dash, Marker, SeriesStyle,
    Symbol, PALETTE,
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

/// The right end of an amplitude panel's A axis: its histograms' and theory's last edge.
pub fn a_max(p: &AmplitudePanel) -> f64 {
    p.runs
        .iter()
        .filter_map(|r| r.edges.last().copied())
        .chain(p.theory.iter().filter_map(|t| t.1.last().copied()))
        .fold(1.0f64, f64::max)
}

/// The marks a panel title puts after a system: its ensemble is not stationary, its density
/// is estimated by wells, its step is coarse (the notes say where).
pub const NOT_STATIONARY: char = '†';
/// See [`NOT_STATIONARY`].
pub const BY_WELLS: char = '‡';
/// See [`NOT_STATIONARY`].
pub const COARSE_STEP: char = '§';

/// Draw one amplitude panel over A ∈ [0, `x_max`] (shared by the panels of a column). The y
/// range holds every histogram with its error bars and the theory's peaks, none cut: on a
/// log axis where a theory peak stands over three times the histograms; the title is the
/// panel's label with each system's marks ([`NOT_STATIONARY`] …), the details in the caption.
pub fn draw_amplitude_panel<DB: Backend>(
    area: &DrawingArea<DB, Shift>,
    p: &AmplitudePanel,
    x_max: f64,
) -> Result<()> {
    let finite_max =
        |it: &mut dyn Iterator<Item = f64>| it.filter(|v| v.is_finite()).fold(0.0f64, f64::max);
    let shown: Vec<(Shown, bool)> = p.runs.iter().map(McRun::shown_density).collect();
    let mc_max = finite_max(&mut shown.iter().flat_map(|((density, stderr), _)| {
        density.iter().zip(stderr).map(|(d, s)| d + s.max(0.0))
    }));
    let theory_max = finite_max(&mut p.theory.iter().flat_map(|t| t.2.iter().copied()));
    let y_max = theory_max.max(mc_max).max(1e-3);
    let mut caption = p.caption.clone();
    // each system's flags as marks the legend explains: † not stationary, ‡ by wells
    let marks: Vec<String> = p
        .runs
        .iter()
        .zip(&shown)
        .filter_map(|(r, (_, mixture))| {
            let mut m = String::new();
            if !mixture && !r.stationary {
                m.push(NOT_STATIONARY);
            }
            if *mixture || r.estimator == "wells" {
                m.push(BY_WELLS);
            }
            if !r.step_warnings.is_empty() {
                m.push(COARSE_STEP);
            }
            (!m.is_empty()).then(|| format!("{}{m}", r.system))
        })
        .collect();
    if !marks.is_empty() {
        caption.push_str(&format!(" · {}", marks.join(", ")));
    }
    // a theory peak far above the histograms: a log axis shows both, none cut
    let log = theory_max > 3.0 * mc_max && mc_max > 0.0;
    let floor = y_max * 1e-4;
    let yv = |v: f64| if log { v.max(floor).log10() } else { v };
    let c = if log {
        chart_log_y(
            area,
            &caption,
            0.0..x_max,
            floor.log10()..(y_max * 1.5).log10(),
            "A",
            "P(A) (log scale)",
        )?
    } else {
        chart(area, &caption, 0.0..x_max, 0.0..y_max * 1.05, "A", "P(A)")?
    };
    for (i, (_, xs, ys)) in p.theory.iter().enumerate() {
        let pts: Vec<(f64, f64)> = xs.iter().zip(ys).map(|(&x, &y)| (x, yv(y))).collect();
        draw_line(&c, &pts, theory_style(i), 2)?;
    }
    for (k, (r, ((density, stderr), _))) in p.runs.iter().zip(&shown).enumerate() {
        let style = mc_style(k);
        let mids: Vec<(f64, f64, f64)> = r
            .edges
            .windows(2)
            .zip(density.iter().zip(stderr))
            .filter(|(_, (d, _))| **d > 0.0 && (!log || **d >= floor))
            .map(|(w, (&d, &s))| (0.5 * (w[0] + w[1]), d, if s.is_finite() { s } else { 0.0 }))
            .collect();
        for &(x, d, s) in &mids {
            let bar = [(x, yv((d - s).max(0.0))), (x, yv(d + s))];
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
        let centres: Vec<(f64, f64)> = mids.iter().map(|&(x, d, _)| (x, yv(d))).collect();
        draw_markers(&c, &centres, style)?;
    }
    Ok(())
}

/// The amplitude panels in a grid of `columns` columns, filled column by column (a
/// column holds one series of the figure), each column on one A axis.
pub fn draw_amplitude_columns<DB: Backend>(
    area: &DrawingArea<DB, Shift>,
    panels: &[AmplitudePanel],
    columns: usize,
) -> Result<()> {
    let rows = panels.len().div_ceil(columns.max(1));
    let cells = area.split_evenly((rows, columns));
    for (k, p) in panels.iter().enumerate() {
        let (col, row) = (k / rows, k % rows);
        let column = &panels[col * rows..((col + 1) * rows).min(panels.len())];
        let x_max = column.iter().map(a_max).fold(1.0f64, f64::max);
        draw_amplitude_panel(&cells[row * columns + col], p, x_max)?;
    }
    Ok(())
}

/// Size of one amplitude panel in pixels (Figs 11 and 13): two to a row of a 7 in page.
pub const PANEL: (u32, u32) = (720, 400);

/// Size of a figure of amplitude panels in two columns with the legend strip below.
pub fn two_columns(panels: &[AmplitudePanel]) -> (u32, u32) {
    let w = 2 * PANEL.0;
    let rows = panels.len().div_ceil(2) as u32;
    (w, rows * PANEL.1 + amplitude_legend(panels).height(w))
}

/// The legend of amplitude panels: both theories and every simulated system.
pub fn amplitude_legend(panels: &[AmplitudePanel]) -> crate::render::plot::LegendStrip {
    let systems: Vec<&str> = panels
        .first()
        .map(|p| p.runs.iter().map(|r| r.system.as_str()).collect())
        .unwrap_or_default();
    let mut entries = legend_entries(&systems);
    let runs = || panels.iter().flat_map(|p| p.runs.iter());
    if runs().any(|r| !r.stationary) {
        entries.push((
            Symbol::Mark(NOT_STATIONARY),
            "ensemble not stationary".into(),
        ));
    }
    if runs().any(|r| r.estimator == "wells" || r.shown_density().1) {
        entries.push((Symbol::Mark(BY_WELLS), "density by wells (H_min)".into()));
    }
    if runs().any(|r| !r.step_warnings.is_empty()) {
        entries.push((Symbol::Mark(COARSE_STEP), "Δt coarse (notes)".into()));
    }
    crate::render::plot::LegendStrip { entries }
}
