//! What Figs 17–19 share: runs of the largest Lyapunov exponent at quick or paper quality,
//! panels of curves with error bars, and their CSV and drawing. Each panel keeps its legend in
//! a strip below its chart, so no legend covers data.

use super::symbol;
use crate::common::{num, sig, Csv};
use crate::plot::{chart, padded_range, pe, LegendStrip, Symbol, PALETTE};
use anyhow::Result;
use plotters::coord::Shift;
use plotters::prelude::*;
use serde::{Deserialize, Serialize};
use trirhythm::analysis::lyapunov::LyapunovSpec;
use trirhythm::engine::{ImpactMemory, PredictorCorrector};

/// U(0) of every LLE run: a [`trirhythm::engine::Problem`]'s default start (1, 0).
const START_U0: f64 = 1.0;

/// Sizes of the runs behind one LLE.
pub struct Sizes {
    /// Paths, transient, window.
    pub spec: LyapunovSpec,
    /// The method.
    pub method: PredictorCorrector,
}

impl Sizes {
    /// Quick (CI) or paper quality.
    pub fn of(quick: bool) -> Sizes {
        let spec = if quick {
            LyapunovSpec {
                paths: 2,
                seed: 1,
                transient: 20.0,
                length: 100.0,
                ..Default::default()
            }
        } else {
            LyapunovSpec {
                paths: 8,
                seed: 1,
                transient: 500.0,
                length: 4000.0,
                ..Default::default()
            }
        };
        let method = PredictorCorrector {
            impact_memory: ImpactMemory::Restart,
            ..Default::default()
        };
        Sizes { spec, method }
    }

    /// One line for headings and notes.
    pub fn describe(&self) -> String {
        format!(
            "LLE with frozen noise, two trajectories with whole-memory renormalisation (d0 = {}, \
             every {} steps), predictor-corrector dt = {}, restart impact memory, U(0) = {}; \
             finite-time exponent over a window of {} after a transient of {}; mean ± standard \
             error over {} noise realisations (seed {})",
            num(self.spec.separation),
            self.spec.renormalise_every,
            num(self.method.dt),
            num(START_U0),
            num(self.spec.length),
            num(self.spec.transient),
            self.spec.paths,
            self.spec.seed
        )
    }
}

/// A point with its error bar (NaN y: nothing to draw there).
#[derive(Debug, Clone, Copy, Serialize, Deserialize)]
pub struct Point {
    /// Abscissa.
    pub x: f64,
    /// Ordinate (NaN when undefined, e.g. no sign change).
    #[serde(with = "super::non_finite")]
    pub y: f64,
    /// Lower end of the error bar.
    #[serde(with = "super::non_finite")]
    pub lo: f64,
    /// Upper end of the error bar.
    #[serde(with = "super::non_finite")]
    pub hi: f64,
}

/// One curve of a panel.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Curve {
    /// Legend text.
    pub label: String,
    /// Its points.
    pub points: Vec<Point>,
}

/// One panel.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Panel {
    /// Caption above the chart.
    pub caption: String,
    /// Key of the abscissa in the CSV.
    pub x_key: String,
    /// Axis descriptions.
    pub x_desc: String,
    /// Axis descriptions.
    pub y_desc: String,
    /// Key of the ordinate in the CSV.
    pub y_key: String,
    /// Draw the line y = 0.
    pub zero_line: bool,
    /// The curves.
    pub curves: Vec<Curve>,
    /// Short verdicts drawn inside the chart's top-left corner.
    pub verdicts: Vec<String>,
}

/// The CSV of panels: `panel,curve,X,Y,Y_lo,Y_hi` (points without a value are left out and
/// named in the header's notes by the figure).
pub fn panels_csv(header: &[String], panels: &[Panel]) -> Result<String> {
    let mut csv = Csv::new(
        header,
        &["panel", "curve", "x_key", "x", "y_key", "y", "y_lo", "y_hi"],
    );
    for p in panels {
        for c in &p.curves {
            for q in c.points.iter().filter(|q| q.y.is_finite()) {
                csv.row([
                    p.caption
                        .split(')')
                        .next()
                        .unwrap_or("")
                        .trim_start_matches('(')
                        .into(),
                    c.label.replace(',', ";"),
                    p.x_key.clone(),
                    num(q.x),
                    p.y_key.clone(),
                    num(q.y),
                    num(q.lo),
                    num(q.hi),
                ]);
            }
        }
    }
    csv.finish()
}

/// Height of the chart part of a panel.
pub const CHART_HEIGHT: u32 = 420;
/// Width of a panel.
pub const PANEL_WIDTH: u32 = 600;

fn strip(panel: &Panel) -> LegendStrip {
    LegendStrip {
        entries: panel
            .curves
            .iter()
            .enumerate()
            .map(|(i, c)| (Symbol::Line(PALETTE[i % PALETTE.len()]), c.label.clone()))
            .collect(),
    }
}

/// Height of a panel with its legend strip.
pub fn panel_height(panels: &[Panel]) -> u32 {
    CHART_HEIGHT
        + panels
            .iter()
            .map(|p| strip(p).height(PANEL_WIDTH))
            .max()
            .unwrap_or(0)
        + 8
}

/// Draw one panel: chart, error bars, zero line, verdicts, legend strip below.
pub fn draw_panel<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, panel: &Panel) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let (top, bottom) = area.split_vertically(CHART_HEIGHT);
    let xs = panel
        .curves
        .iter()
        .flat_map(|c| c.points.iter().map(|q| q.x));
    let x = padded_range(xs);
    let mut ys: Vec<f64> = panel
        .curves
        .iter()
        .flat_map(|c| c.points.iter())
        .filter(|q| q.y.is_finite())
        .flat_map(|q| [q.lo, q.hi, q.y])
        .collect();
    if panel.zero_line {
        ys.push(0.0);
    }
    if ys.iter().all(|v| !v.is_finite()) {
        ys = vec![0.0, 1.0];
    }
    let mut y = padded_range(ys);
    // room at the top for the verdict lines
    y.end += (y.end - y.start) * 0.08 * panel.verdicts.len() as f64;
    let mut c = chart(
        &top,
        &panel.caption,
        x.clone(),
        y.clone(),
        &panel.x_desc,
        &panel.y_desc,
    )?;
    if panel.zero_line {
        c.draw_series(std::iter::once(PathElement::new(
            [(x.start, 0.0), (x.end, 0.0)],
            RGBColor(120, 120, 120).stroke_width(1),
        )))
        .map_err(pe)?;
    }
    for (i, curve) in panel.curves.iter().enumerate() {
        let colour = PALETTE[i % PALETTE.len()];
        // a small horizontal offset per curve keeps overlapping error bars apart
        let shift = (x.end - x.start) * 0.004 * (i as f64 - 1.5);
        let pts: Vec<(f64, f64)> = curve
            .points
            .iter()
            .filter(|q| q.y.is_finite())
            .map(|q| (q.x + shift, q.y))
            .collect();
        // the line is broken where a point has no value (−∞: merged realisations), so that it
        // never suggests a measurement there
        for run in curve.points.split(|q| !q.y.is_finite()) {
            let run: Vec<(f64, f64)> = run.iter().map(|q| (q.x + shift, q.y)).collect();
            c.draw_series(LineSeries::new(run, colour.stroke_width(2)))
                .map_err(pe)?;
        }
        c.draw_series(pts.iter().map(|&p| Circle::new(p, 4, colour.filled())))
            .map_err(pe)?;
        let cap = (x.end - x.start) * 0.006;
        for q in curve.points.iter().filter(|q| q.y.is_finite()) {
            let xq = q.x + shift;
            c.draw_series([
                PathElement::new([(xq, q.lo), (xq, q.hi)], colour.stroke_width(1)),
                PathElement::new([(xq - cap, q.lo), (xq + cap, q.lo)], colour.stroke_width(1)),
                PathElement::new([(xq - cap, q.hi), (xq + cap, q.hi)], colour.stroke_width(1)),
            ])
            .map_err(pe)?;
        }
    }
    for (k, v) in panel.verdicts.iter().enumerate() {
        let at = (
            x.start + 0.02 * (x.end - x.start),
            y.end - (0.02 + 0.075 * k as f64) * (y.end - y.start),
        );
        c.draw_series(std::iter::once(Text::new(
            v.clone(),
            at,
            (crate::plot::FONT, 14).into_font().color(&BLACK),
        )))
        .map_err(pe)?;
    }
    strip(panel).draw(&bottom)
}

/// Two panels side by side (Figs 17 and 18).
pub fn draw_side_by_side<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    panels: &[Panel],
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    for (area, panel) in root.split_evenly((1, 2)).iter().zip(panels) {
        draw_panel(area, panel)?;
    }
    Ok(())
}

/// A panel of LLE against D, one curve per value of `key`, with its notes (a verdict per
/// curve on the paper's claim that the LLE turns positive past a critical D).
pub fn lle_against_noise(
    caption: &str,
    base: &trirhythm::model::Params,
    key: &str,
    values: &[f64],
    noises: &[f64],
    sizes: &Sizes,
) -> Result<(Panel, Vec<String>)> {
    use trirhythm::analysis::lyapunov::largest_lyapunov;
    use trirhythm::engine::Problem;
    use trirhythm::monitor::Silent;
    let mut curves = Vec::new();
    let mut notes = Vec::new();
    let (mut pos, mut neg, mut all, mut merged_points) = (0, 0, 0, 0);
    for &v in values {
        let mut points = Vec::new();
        for &d in noises {
            let p = base.with(key, v)?.with("D", d)?;
            let r = largest_lyapunov(
                &Problem::from_params(&p)?,
                &sizes.method,
                &sizes.spec,
                &Silent,
            )?;
            if r.merged > 0 {
                merged_points += 1;
                let when: Vec<String> = r
                    .per_path
                    .iter()
                    .filter_map(|q| {
                        q.merged_at
                            .map(|t| format!("{} at t = {}", q.path, sig(t, 4)))
                    })
                    .collect();
                notes.push(format!(
                    "{caption}, {} = {}, D = {}: LLE −∞, not drawn: {} of {} realisations merged (the copy became identical to its reference, both stuck at the wall on the same step with the memory restarted; path {}); the other {}: {}",
                    symbol(key),
                    num(v),
                    sig(d, 4),
                    r.merged,
                    r.per_path.len(),
                    when.join(", path "),
                    r.per_path.len() - r.merged,
                    if r.unmerged.value.is_finite() {
                        format!("{} ± {}", sig(r.unmerged.value, 3), sig(r.unmerged.stderr, 2))
                    } else {
                        "none".into()
                    }
                ));
            }
            let s = if r.lle.stderr.is_finite() {
                r.lle.stderr
            } else {
                0.0
            };
            points.push(Point {
                x: d,
                y: r.lle.value,
                lo: r.lle.value - s,
                hi: r.lle.value + s,
            });
        }
        // two standard errors; a −∞ point (merged realisations) has no sign
        let two_se = |q: &Point| (q.hi - q.lo) / 2.0 * 2.0;
        let p_count = points
            .iter()
            .filter(|q| q.y.is_finite() && q.y > two_se(q))
            .count();
        let n_count = points
            .iter()
            .filter(|q| q.y.is_finite() && q.y < -two_se(q))
            .count();
        pos += p_count;
        neg += n_count;
        all += points.len();
        let first_pos = points
            .iter()
            .find(|q| q.y.is_finite() && q.y > two_se(q))
            .map(|q| q.x);
        let neg_before = first_pos.is_some_and(|d0| {
            points
                .iter()
                .any(|q| q.x < d0 && q.y.is_finite() && q.y < -two_se(q))
        });
        notes.push(format!(
            "{caption}, {} = {}: LLE > 0 by 2 standard errors at {p_count} of {} D, < 0 at {n_count}; {}",
            symbol(key),
            num(v),
            points.len(),
            match (first_pos, neg_before) {
                (Some(d0), true) => format!("sign change negative → positive below D = {}: the paper's claim holds here", num(d0)),
                (Some(d0), false) => format!("positive from D = {} without a significantly negative LLE below: no critical noise in the range (the paper's claim not reproduced)", num(d0)),
                (None, _) if n_count > 0 => "never significantly positive: no transition to chaos in the range (the paper's claim not reproduced)".into(),
                (None, _) => "indistinguishable from 0 throughout".into(),
            }
        ));
        curves.push(Curve {
            label: format!("{} = {}", symbol(key), num(v)),
            points,
        });
    }
    let panel = Panel {
        caption: caption.into(),
        x_key: "D".into(),
        x_desc: "noise intensity D".into(),
        y_desc: "largest Lyapunov exponent".into(),
        y_key: "lle".into(),
        zero_line: true,
        curves,
        verdicts: vec![if merged_points > 0 {
            format!(
                "LLE > 0 (2 s.e.) at {pos} of {all} points, < 0 at {neg}; −∞ (merged, not drawn) at {merged_points}"
            )
        } else {
            format!("LLE > 0 (2 s.e.) at {pos} of {all} points, < 0 at {neg}")
        }],
    };
    Ok((panel, notes))
}
