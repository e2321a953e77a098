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
        e.push((Symbol::Points(mc_style(i)), format!("Monte Carlo, {s}")));
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

/// Where a panel's densities (the shown histograms and the theory) stand at or above
/// `fraction` of the panel's highest density: (lo, hi), empty (lo ≥ hi) where none does.
fn span_above(p: &AmplitudePanel, fraction: f64) -> (f64, f64) {
    let shown: Vec<Vec<f64>> = p.runs.iter().map(|r| r.shown_density().0 .0).collect();
    let top = shown
        .iter()
        .flatten()
        .chain(p.theory.iter().flat_map(|t| t.2.iter()))
        .copied()
        .filter(|y| y.is_finite())
        .fold(0.0f64, f64::max);
    let seen = |y: f64| y.is_finite() && y > 0.0 && y >= fraction * top;
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for (r, density) in p.runs.iter().zip(&shown) {
        for (w, &d) in r.edges.windows(2).zip(density) {
            if seen(d) {
                (lo, hi) = (lo.min(w[0]), hi.max(w[1]));
            }
        }
    }
    for (_, xs, ys) in &p.theory {
        for (&x, &y) in xs.iter().zip(ys) {
            if seen(y) {
                (lo, hi) = (lo.min(x), hi.max(x));
            }
        }
    }
    (lo, hi)
}

/// The lowest density a panel's A range holds, as a fraction of its highest (the floor of a
/// log axis).
const RANGE_FLOOR: f64 = 1e-4;
/// What a linear axis shows of a density: from this fraction of its top up.
const LINEAR_SEEN: f64 = 1e-2;

/// A panel whose A range is more than twice as wide as the part a linear axis shows (where a
/// density stands over [`LINEAR_SEEN`] of the top): a second mode or a long tail that only a
/// log axis can show (Fig. 13 (a3): the outer cycle's mode at A ≈ 12.5, 0.3 % of the mass).
pub fn hidden_on_linear(p: &AmplitudePanel) -> bool {
    let (lo, hi) = span_above(p, RANGE_FLOOR);
    let (a, b) = span_above(p, LINEAR_SEEN);
    lo < hi && a < b && hi - lo > 2.0 * (b - a)
}

/// The part of the A axis where a panel's densities are: the bins of its histograms with
/// a density, and the theory, where they stand at or above [`RANGE_FLOOR`] of the panel's
/// highest density (the floor of a log axis), padded by 5 % (never below A = 0) and widened
/// to hold four ticks where a step of the 1-2-5 ladder cannot.
pub fn a_range(p: &AmplitudePanel) -> (f64, f64) {
    let (lo, hi) = span_above(p, RANGE_FLOOR);
    if lo >= hi {
        return (0.0, 1.0);
    }
    let pad = 0.05 * (hi - lo);
    let (mut lo, mut hi) = ((lo - pad).max(0.0), hi + pad);
    // at least four whole steps of the 1-2-5 ladder inside, for four labelled ticks: a
    // narrow range is widened a step at a time, alternately above and below
    let step = {
        let raw = (hi - lo) / 4.0;
        let decade = 10f64.powf(raw.log10().floor());
        [1.0, 2.0, 5.0, 10.0]
            .into_iter()
            .map(|m| m * decade)
            .find(|s| *s >= raw)
            .unwrap_or(10.0 * decade)
    };
    let inside_at = |lo: f64, hi: f64, step: f64| (hi / step).floor() - (lo / step).ceil() + 1.0;
    // where the ladder's next smaller step already gives four, nothing is widened (an axis
    // run on past the data would stand empty)
    let smaller = {
        let m = step / 10f64.powf(step.log10().floor());
        step * if (m - 5.0).abs() < 1e-9 { 0.4 } else { 0.5 }
    };
    if inside_at(lo, hi, smaller) >= 4.0 {
        return (lo, hi);
    }
    let inside = |lo: f64, hi: f64| inside_at(lo, hi, step);
    let mut up = true;
    while inside(lo, hi) < 4.0 {
        if up || lo <= 0.0 {
            hi = ((hi / step).floor() + 1.0) * step;
        } else {
            lo = (((lo / step).ceil() - 1.0) * step).max(0.0);
        }
        up = !up;
    }
    (lo, hi)
}

/// The marks a panel title puts after a system: its ensemble is not stationary, its density
/// is estimated by wells, its step is coarse (the notes say where).
pub const NOT_STATIONARY: char = '†';
/// See [`NOT_STATIONARY`].
pub const BY_WELLS: char = '‡';
/// See [`NOT_STATIONARY`].
pub const COARSE_STEP: char = '§';

/// Draw one amplitude panel over A ∈ `x` (where the densities are, [`a_range`]). The y
/// range holds every histogram with its error bars and the theory's peaks, none cut: on a
/// log axis where a theory peak stands over three times the histograms or the densities
/// reach far beyond what a linear axis shows ([`hidden_on_linear`]), the theory drawn only
/// above the axis' floor (a density below it is not drawn along the axis); the title is the
/// panel's label with each system's marks ([`NOT_STATIONARY`] …), the details in the caption.
pub fn draw_amplitude_panel<DB: Backend>(
    area: &DrawingArea<DB, Shift>,
    p: &AmplitudePanel,
    (x_min, x_max): (f64, f64),
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
            // (a wells' mixture stands in for a run that is not stationary: it keeps its †)
            if !r.stationary {
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
    // a theory peak far above the histograms, or densities a linear axis hides: a log axis
    // shows both, none cut
    let log = (theory_max > 3.0 * mc_max && mc_max > 0.0) || hidden_on_linear(p);
    let floor = y_max * RANGE_FLOOR;
    let yv = |v: f64| if log { v.max(floor).log10() } else { v };
    let c = if log {
        chart_log_y(
            area,
            &caption,
            x_min..x_max,
            // (a quarter decade below the floor and above the peak: no marker on a spine)
            floor.log10() - 0.25..(y_max * 1.5).log10() + 0.25,
            "A",
            "P(A) (log scale)",
        )?
    } else {
        chart(area, &caption, x_min..x_max, 0.0..y_max * 1.12, "A", "P(A)")?
    };
    let in_view = |x: f64| x >= x_min && x <= x_max;
    // the Monte Carlo first, the theory drawn on top of it
    for (k, (r, ((density, stderr), _))) in p.runs.iter().zip(&shown).enumerate() {
        let style = mc_style(k);
        let mids: Vec<(f64, f64, f64)> = r
            .edges
            .windows(2)
            .zip(density.iter().zip(stderr))
            .filter(|(w, (d, _))| {
                **d > 0.0 && (!log || **d >= floor) && in_view(0.5 * (w[0] + w[1]))
            })
            .map(|(w, (&d, &s))| (0.5 * (w[0] + w[1]), d, if s.is_finite() { s } else { 0.0 }))
            .collect();
        // markers on at most about 30 bins (every k-th): many merge into a band that hides
        // the theory; the error bars only on the marked bins (a bar alone reads as a dash)
        let every = mids.len().div_ceil(30).max(1);
        let marked: Vec<(f64, f64, f64)> = mids
            .iter()
            .copied()
            .skip(k % every)
            .step_by(every)
            .collect();
        for &(x, d, s) in &marked {
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
        // wide bins (few in view) as a step outline, so that a bin's width is seen against
        // a narrow theory peak
        let bins: Vec<(f64, f64, f64)> = r
            .edges
            .windows(2)
            .zip(density.iter())
            .filter(|(w, d)| d.is_finite() && in_view(w[0]) && in_view(w[1]))
            .map(|(w, &d)| (w[0], w[1], d))
            .collect();
        if !bins.is_empty() && bins.len() < 30 {
            let mut step: Vec<(f64, f64)> = Vec::new();
            for &(a, b, d) in &bins {
                // (on a log axis a bin below the floor drops to the axis' bottom, as the
                // theory does: never a false plateau at the floor)
                let y = match log {
                    true if d >= floor => d.log10(),
                    true => floor.log10() - 0.25,
                    false => d,
                };
                step.push((a, y));
                step.push((b, y));
            }
            draw_line(
                &c,
                &step,
                SeriesStyle {
                    dash: Dash::Solid,
                    marker: Marker::None,
                    ..style
                },
                1,
            )?;
        }
        let centres: Vec<(f64, f64)> = marked.iter().map(|&(x, d, _)| (x, yv(d))).collect();
        draw_markers(&c, &centres, style)?;
    }
    for (i, (_, xs, ys)) in p.theory.iter().enumerate() {
        // the runs of points inside the view (and above the floor of a log axis)
        // (on a log axis the theory runs down to the axis' bottom: where it crosses it, the
        // line between its two points is drawn to the crossing)
        let bottom = floor * 10f64.powf(-0.25);
        let tv = |v: f64| if log { v.log10() } else { v };
        let mut run: Vec<(f64, f64)> = Vec::new();
        let mut last: Option<(f64, f64)> = None;
        for (&x, &y) in xs.iter().zip(ys) {
            let above = |y: f64| y.is_finite() && (!log || y >= bottom);
            let crossing = |(x0, y0): (f64, f64)| {
                let (l0, l1, lb) = (y0.log10(), y.log10(), bottom.log10());
                (x0 + (x - x0) * (lb - l0) / (l1 - l0), lb)
            };
            if in_view(x) && above(y) {
                if let Some((x0, y0)) = last.filter(|&(x0, y0)| {
                    log && run.is_empty() && in_view(x0) && y0.is_finite() && y0 > 0.0
                }) {
                    run.push(crossing((x0, y0)));
                }
                run.push((x, tv(y)));
            } else if !run.is_empty() {
                if let Some((x0, y0)) = last {
                    if log && in_view(x) && y.is_finite() && y > 0.0 {
                        run.push(crossing((x0, y0)));
                    }
                }
                draw_line(&c, &run, theory_style(i), 3)?;
                run.clear();
            }
            last = Some((x, y));
        }
        if !run.is_empty() {
            draw_line(&c, &run, theory_style(i), 3)?;
        }
    }
    Ok(())
}

/// The amplitude panels in a grid of `columns` columns, filled column by column (a
/// column holds one series of the figure), each panel on the part of the A axis where its
/// densities are ([`a_range`]).
pub fn draw_amplitude_columns<DB: Backend>(
    area: &DrawingArea<DB, Shift>,
    panels: &[AmplitudePanel],
    columns: usize,
) -> Result<()> {
    let rows = panels.len().div_ceil(columns.max(1));
    let cells = area.split_evenly((rows, columns));
    for (k, p) in panels.iter().enumerate() {
        let (col, row) = (k / rows, k % rows);
        draw_amplitude_panel(&cells[row * columns + col], p, a_range(p))?;
    }
    Ok(())
}

/// Size of one amplitude panel in pixels (Figs 11 and 13): two to a row of a 7 in page.
pub const PANEL: (u32, u32) = (720, 350);

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
            "Monte Carlo NOT stationary".into(),
        ));
    }
    if runs().any(|r| r.estimator == "wells" || r.shown_density().1) {
        entries.push((Symbol::Mark(BY_WELLS), "MC by wells".into()));
    }
    if runs().any(|r| !r.step_warnings.is_empty()) {
        entries.push((Symbol::Mark(COARSE_STEP), "Δt flagged coarse".into()));
    }
    crate::render::plot::LegendStrip { entries }
}

/// The caption's key to amplitude panels: what the legend's few words stand for (the marks
/// after a panel's title, the bars).
pub fn amplitude_key(panels: &[AmplitudePanel]) -> Vec<String> {
    let runs = || panels.iter().flat_map(|p| p.runs.iter());
    let mut key = vec![
        "key: Monte Carlo markers with bars of ± 1 standard error on every bin or, where \
         more than 30 bins are in view, on every k-th bin only (at most about 30); a panel \
         with fewer than 30 bins in view draws its histogram as a thin step outline too; the \
         theory curves are drawn over the Monte Carlo; the marks after a panel's title \
         (†, and the others below) follow the equation of the ensemble they concern"
            .to_string(),
    ];
    if runs().any(|r| !r.stationary) {
        key.push(format!(
            "{NOT_STATIONARY} (Monte Carlo NOT stationary): the ensemble failed the \
             stationarity check; its density is not a stationary result"
        ));
    }
    if runs().any(|r| r.estimator == "wells" || r.shown_density().1) {
        key.push(format!(
            "{BY_WELLS} (MC by wells): the density drawn is the well decomposition's, the \
             weights the data leave undetermined taken nearest the theory (the least \
             Hellinger distance, H_min)"
        ));
    }
    // the drawn densities' mass the panels' A ranges cut off (a bin counted by its share
    // outside the range)
    let cut = panels
        .iter()
        .flat_map(|p| {
            let (lo, hi) = a_range(p);
            p.runs.iter().map(move |r| {
                let density = r.shown_density().0 .0;
                let out: f64 = r
                    .edges
                    .windows(2)
                    .zip(&density)
                    .map(|(w, d)| {
                        let inside = (w[1].min(hi) - w[0].max(lo)).max(0.0);
                        (w[1] - w[0] - inside) * d
                    })
                    .sum();
                (out, &p.caption, &r.system)
            })
        })
        .max_by(|a, b| a.0.total_cmp(&b.0));
    if let Some((out, caption, system)) = cut.filter(|c| c.0 >= 5e-5) {
        key.push(format!(
            "A range: each panel's axis holds its densities down to a ten-thousandth of its \
             highest; the drawn Monte Carlo mass outside it is at most {:.2} % ({caption}, \
             {system})",
            100.0 * out
        ));
    }
    if runs().any(|r| !r.step_warnings.is_empty()) {
        key.push(format!(
            "{COARSE_STEP} (Δt flagged coarse): the step guard flagged the ensemble's Δt as \
             coarse"
        ));
    }
    key
}
