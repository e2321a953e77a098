//! Fig. 7: the pseudo-potential U_eff(A0) (Eq. 23) for several r (a) and several λ (b).

use super::write_figure;
use super::{csv_header, heading, panel_line, Figure, FigureContext};
use crate::common::{num, Csv};
use crate::plot::{chart, framed, legend, padded_range, pe, ChartSize, Heading, Picture, PALETTE};
use anyhow::Result;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use trirhythm::model::preset;
use trirhythm::theory::averaging::{Extremum, Theory};

/// One U_eff curve with its extrema.
#[derive(Serialize, Deserialize)]
pub(super) struct Curve {
    pub label: String,
    pub points: Vec<(f64, f64)>,
    pub extrema: Vec<Extremum>,
}

impl Curve {
    /// U_eff of `th` on `grid` (A = 0 skipped when the potential has a log term).
    pub fn new(label: String, th: &Theory, grid: &[f64]) -> Curve {
        let points = grid
            .iter()
            .filter(|&&a| a > 0.0 || th.diffusion() == 0.0)
            .map(|&a| (a, th.potential(a)))
            .collect();
        Curve {
            label,
            points,
            extrema: th.extrema(),
        }
    }
}

/// A y-range framing the extrema of `curves` that lie below `x_end` (the walls of U_eff at
/// A → 0 and A → ∞ would otherwise flatten everything), and the curves' points inside it.
pub(super) fn frame(curves: &[Curve], x_end: f64) -> (std::ops::Range<f64>, Vec<Curve>) {
    let levels = curves
        .iter()
        .flat_map(|c| c.extrema.iter())
        .filter(|e| e.amplitude <= x_end)
        .map(|e| e.potential);
    let (lo, hi) = levels.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
        (a.min(v), b.max(v))
    });
    let span = (hi - lo).max(1e-9);
    let y = padded_range([lo - 0.3 * span, hi + 0.6 * span]);
    let clipped = curves
        .iter()
        .map(|c| Curve {
            label: c.label.clone(),
            points: c
                .points
                .iter()
                .copied()
                .filter(|p| p.0 <= x_end && y.contains(&p.1))
                .collect(),
            extrema: c.extrema.clone(),
        })
        .collect();
    (y, clipped)
}

/// Draw curves with their wells (filled) and crests (open) marked.
pub(super) fn draw_curves<'a, DB: DrawingBackend + 'a>(
    c: &mut ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    curves: &[Curve],
    with_legend: bool,
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let y = c.y_range();
    let x = c.x_range();
    for (i, cv) in curves.iter().enumerate() {
        let color = PALETTE[i % PALETTE.len()];
        let s = c
            .draw_series(LineSeries::new(
                cv.points.iter().copied(),
                color.stroke_width(2),
            ))
            .map_err(pe)?;
        if with_legend {
            s.label(cv.label.clone()).legend(move |(x, y)| {
                PathElement::new([(x, y), (x + 15, y)], color.stroke_width(2))
            });
        }
        let inside = |e: &&Extremum| x.contains(&e.amplitude) && y.contains(&e.potential);
        c.draw_series(cv.extrema.iter().filter(inside).map(|e| {
            let fill = if e.minimum {
                color.filled()
            } else {
                WHITE.filled()
            };
            EmptyElement::at((e.amplitude, e.potential))
                + Circle::new((0, 0), 5, fill)
                + Circle::new((0, 0), 5, color.stroke_width(2))
        }))
        .map_err(pe)?;
    }
    Ok(())
}

/// The depth of the inner well A01 (to the crest after it) and of the outer well (to the
/// crest before it), and the well amplitudes, of one curve; `None` where a well is missing.
fn wells(cv: &Curve) -> (Option<f64>, Option<f64>, Vec<f64>) {
    let ex: Vec<&Extremum> = cv.extrema.iter().filter(|e| e.amplitude > 0.0).collect();
    let minima: Vec<f64> = ex
        .iter()
        .filter(|e| e.minimum)
        .map(|e| e.amplitude)
        .collect();
    let depth = |i: usize, crest: Option<&&Extremum>| {
        crest
            .filter(|c| !c.minimum)
            .map(|c| c.potential - ex[i].potential)
    };
    let first = ex.iter().position(|e| e.minimum);
    let last = ex.iter().rposition(|e| e.minimum);
    let inner = first
        .filter(|_| minima.len() >= 3)
        .and_then(|i| depth(i, ex.get(i + 1)));
    let outer = last.and_then(|i| depth(i, i.checked_sub(1).and_then(|j| ex.get(j))));
    (inner, outer, minima)
}

/// The text's claims on Fig. 7 ("when r decreases, the potential well in A01 tends to
/// disappear and … that one in A05 increases in depth"; "the amplitudes A01, A03 and A05
/// change very slightly"; "quasi-same phenomena" with λ), checked on the computed curves.
fn text_claims(panel: &str, symbol: &str, values: &[f64], curves: &[Curve]) -> Vec<String> {
    let mut out = Vec::new();
    let rows: Vec<_> = curves.iter().map(wells).collect();
    for (v, (inner, outer, minima)) in values.iter().zip(&rows) {
        out.push(format!(
            "panel {panel}, {symbol} = {v}: wells at A = {}; depth of the A01 well {}, of the outer well {}",
            minima.iter().map(|a| format!("{a:.4}")).collect::<Vec<_>>().join(", "),
            inner.map_or("(no A01 well)".into(), |d| format!("{d:.3e}")),
            outer.map_or("-".into(), |d| format!("{d:.4}"))
        ));
    }
    // values are listed from the largest down
    let inner: Vec<Option<f64>> = rows.iter().map(|r| r.0).collect();
    let outer: Vec<Option<f64>> = rows.iter().map(|r| r.1).collect();
    let shrinking = inner
        .windows(2)
        .all(|w| matches!((w[0], w[1]), (Some(a), Some(b)) if b < a) || w[1].is_none());
    let deepening = outer
        .windows(2)
        .all(|w| matches!((w[0], w[1]), (Some(a), Some(b)) if b > a));
    let spread = rows
        .iter()
        .filter(|r| r.2.len() == rows[0].2.len())
        .flat_map(|r| r.2.iter().zip(&rows[0].2).map(|(a, b)| (a - b).abs() / b))
        .fold(0.0f64, f64::max);
    out.push(format!(
        "panel {panel}, the text's claims as {symbol} decreases: the A01 well becomes shallower or disappears: {}; the outer well (A05) deepens: {}; the well amplitudes change by at most {:.1}% (the text: 'very slightly')",
        if shrinking { "yes" } else { "no" },
        if deepening { "yes" } else { "no" },
        100.0 * spread
    ));
    out
}

/// One panel: U_eff curves for several (r, λ).
#[derive(Serialize, Deserialize)]
pub struct Panel {
    /// `a` or `b`.
    id: String,
    caption: String,
    /// (r, λ) of each curve.
    params: Vec<(f64, f64)>,
    curves: Vec<Curve>,
}

/// Fig. 7's data: U_eff on a grid, with its extrema, per curve.
#[derive(Serialize, Deserialize)]
pub struct Fig07 {
    heading: Heading,
    /// CSV comment lines.
    header: Vec<String>,
    panels: Vec<Panel>,
}

impl Figure for Fig07 {
    const NUMBER: u32 = 7;
    const TITLE: &'static str = "pseudo-potential U_eff for several r and λ (Eq. 23)";

    fn compute(ctx: &FigureContext) -> Result<Fig07> {
        compute(ctx)
    }

    fn render(&self, stem: &Path) -> Result<Vec<PathBuf>> {
        let mut csv = Csv::new(&self.header, &["panel", "r", "lambda", "A", "U_eff"]);
        for panel in &self.panels {
            for (cv, &(r, l)) in panel.curves.iter().zip(&panel.params) {
                for &(a, u) in &cv.points {
                    csv.row([panel.id.clone(), num(r), num(l), num(a), num(u)]);
                }
            }
        }
        write_figure(self, stem, &csv.finish()?)
    }
}

fn compute(ctx: &FigureContext) -> Result<Fig07> {
    let n = if ctx.quick { 281 } else { 1401 };
    let grid: Vec<f64> = (0..n).map(|i| 14.0 * i as f64 / (n - 1) as f64).collect();
    let rs = [1.0, 0.999, 0.998, 0.996];
    let lambdas = [1.0, 0.999, 0.998, 0.997];
    let pa = preset("fig7a")?.params;
    let pb = preset("fig7b")?.params;
    let mut a_curves = Vec::new();
    for r in rs {
        let th = Theory::new(&pa.with("r", r)?, ctx.variant)?;
        a_curves.push(Curve::new(format!("r = {r}"), &th, &grid));
    }
    let mut b_curves = Vec::new();
    for l in lambdas {
        let th = Theory::new(&pb.with("lambda", l)?, ctx.variant)?;
        b_curves.push(Curve::new(format!("λ = {l}"), &th, &grid));
    }
    let notes = vec![
        format!(
            "panel a: λ = {}, r ∈ {rs:?} (r values not printed in the paper; chosen)",
            pa.lambda
        ),
        format!(
            "panel b: r = {}, λ ∈ {lambdas:?} (λ values not printed in the paper; chosen)",
            pb.restitution
        ),
        "ω0 is not printed; ω0 = 1 chosen. D = 0, so U_eff = −∫f dA (no log term)".into(),
        "wells: filled markers; crests: open markers".into(),
    ];
    let mut notes = notes;
    notes.extend(text_claims("a", "r", &rs, &a_curves));
    notes.extend(text_claims("b", "λ", &lambdas, &b_curves));
    let mut header = csv_header(7, "pseudo-potential U_eff(A0) (Eq. 23)", ctx, &notes);
    header.push(panel_line("a (base)", &pa));
    header.push(panel_line("b (base)", &pb));
    Ok(Fig07 {
        heading: heading(
            7,
            "the pseudo-potential U_eff(A0) (Eq. 23): wells are stable cycles, crests unstable ones",
            ctx,
            &pa,
            &["r", "lambda"],
            vec![
                format!("r values (a) and λ values (b) are not printed in the paper: chosen; ω0 = 1 chosen (not printed); D = 0, so U_eff = −∫f dA"),
            ],
        ),
        header,
        panels: vec![
            Panel {
                id: "a".into(),
                caption: format!("(a) λ = {}, several r", pa.lambda),
                params: rs.iter().map(|&r| (r, pa.lambda)).collect(),
                curves: a_curves,
            },
            Panel {
                id: "b".into(),
                caption: format!("(b) r = {}, several λ", pb.restitution),
                params: lambdas.iter().map(|&l| (pb.restitution, l)).collect(),
                curves: b_curves,
            },
        ],
    })
}

impl Picture for Fig07 {
    fn size(&self) -> (u32, u32) {
        (1400, 620)
    }

    fn heading(&self) -> Heading {
        self.heading.clone()
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, plotters::coord::Shift>) -> Result<()>
    where
        DB::ErrorType: 'static,
    {
        let areas = root.split_evenly((1, 2));
        for (
            area,
            Panel {
                caption, curves, ..
            },
        ) in areas.iter().zip(&self.panels)
        {
            let (y, clipped) = frame(curves, 14.0);
            let mut c = chart(area, caption, 0.0..14.0, y, "A0", "U_eff(A0)")?;
            draw_curves(&mut c, &clipped, true)?;
            legend(&mut c, SeriesLabelPosition::UpperMiddle)?;
            // The inner well A01 is ~1e-3 deep against ~1 for the outer ones: an inset zooms
            // on it, up to the first crest beyond it.
            let zoom_end = curves
                .iter()
                .filter_map(|cv| {
                    let well = cv.extrema.iter().find(|e| e.minimum && e.amplitude > 0.0)?;
                    cv.extrema
                        .iter()
                        .find(|e| !e.minimum && e.amplitude > well.amplitude)
                        .map(|e| e.amplitude)
                })
                .fold(0.0f64, f64::max)
                * 1.15;
            if zoom_end > 0.0 && zoom_end < 14.0 {
                let (w, h) = area.dim_in_pixel();
                // below the curves, where the main panel is empty
                let inset = area.clone().shrink(
                    (100, (0.5 * h as f64) as u32),
                    ((0.45 * w as f64) as u32, (0.4 * h as f64) as u32),
                );
                inset.fill(&WHITE).map_err(pe)?;
                let (yz, zoomed) = frame(curves, zoom_end);
                let mut z = framed(
                    &inset,
                    &format!("zoom on the inner well: A0 ≤ {zoom_end:.1}"),
                    (0.0..zoom_end, yz),
                    ("", ""),
                    ChartSize::Inset,
                )?;
                draw_curves(&mut z, &zoomed, false)?;
            }
        }
        Ok(())
    }
}
