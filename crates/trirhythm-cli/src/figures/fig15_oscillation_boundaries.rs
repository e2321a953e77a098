//! Fig. 15: the oscillation (Hopf) boundary μ0 against λ and against r for ω0 ∈ {0.9, 0.5, 0.3}
//! at D = 0 — by simulation (predictor–corrector from a small amplitude, bracketed), by
//! averaging (f′(0) = 0 of Eq. 18) and by the exact linearisation where it is exact — with the
//! non-oscillating region (below the simulated boundary) shaded as in the paper.
//!
//! The panel machinery ([`Panel`], [`Curve`], [`compute`], [`draw_panel`], [`distances`]) is
//! shared with Fig. 16.

use super::write_figure;
use super::{csv_header, heading, Figure, FigureContext};
use crate::common::{num, progress, Csv};
use crate::plot::{chart, legend, pe, Heading, Picture};
use anyhow::Result;
use plotters::coord::Shift;
use plotters::prelude::*;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use trirhythm::analysis::oscillation::{
    boundary, BoundaryPoint, Classifier, Method, Plane, Search, Side,
};
use trirhythm::engine::{Barrier, Problem};
use trirhythm::model::{preset, Params};

/// One boundary curve of a panel.
#[derive(Serialize, Deserialize)]
pub struct Curve {
    /// Legend label.
    pub label: String,
    /// `simulation`, `averaging`, `exact` or `exact, no wall`.
    pub method: String,
    /// The boundary at each abscissa.
    pub points: Vec<BoundaryPoint>,
    /// Colour.
    #[serde(with = "super::rgb")]
    pub color: RGBColor,
    /// Whether this curve's lower side is shaded (the simulated boundary of the panel).
    pub shade: bool,
}

/// What a curve is: its method name, colour and whether its lower side is shaded.
#[derive(Clone, Copy)]
pub enum Role {
    /// The simulated boundary (shaded below).
    Simulation,
    /// The averaging's f′(0) = 0.
    Averaging,
    /// The exact linearisation.
    Exact,
    /// The exact linearisation without the wall, drawn for reference.
    ExactNoWall,
}

impl Curve {
    /// A boundary curve drawn as its role says.
    pub fn new(role: Role, label: impl Into<String>, points: Vec<BoundaryPoint>) -> Curve {
        let (method, color, shade) = match role {
            Role::Simulation => ("simulation", SIM, true),
            Role::Averaging => ("averaging", AVG, false),
            Role::Exact => ("exact", EXACT, false),
            Role::ExactNoWall => ("exact, no wall", NOWALL, false),
        };
        Curve {
            label: label.into(),
            method: method.into(),
            points,
            color,
            shade,
        }
    }
}

/// One panel: an abscissa, μ0 searched in an interval, curves.
#[derive(Serialize, Deserialize)]
pub struct Panel {
    /// "(a) ω0 = 0.9: μ0 against λ, r = 0.998".
    pub caption: String,
    /// Short label for the CSV.
    pub label: String,
    /// Axis name.
    pub x_desc: String,
    /// Abscissa range.
    pub x_range: (f64, f64),
    /// μ0 range shown (and searched).
    pub y_range: (f64, f64),
    /// The curves.
    pub curves: Vec<Curve>,
    /// Add a key of the line styles to the legend (panels whose colours are parameter values).
    pub style_key: bool,
}

/// Accuracy of a figure's simulations.
pub fn settings(quick: bool) -> (Classifier, Search, usize) {
    let mut c = Classifier::default();
    let mut s = Search::default();
    let n = if quick {
        c.max_periods = 40.0;
        s.tolerance = 1e-2;
        5
    } else {
        21
    };
    (c, s, n)
}

/// Points of [a, b], `n` of them.
pub fn linspace(a: f64, b: f64, n: usize) -> Vec<f64> {
    (0..n)
        .map(|i| a + (b - a) * i as f64 / (n - 1).max(1) as f64)
        .collect()
}

/// The boundary in μ0 ∈ y_range along `x_key` at `xs` by `method`.
pub fn compute(
    base: &Params,
    barrier: Barrier,
    x_key: &str,
    xs: &[f64],
    y_range: (f64, f64),
    method: &Method,
    search: &Search,
) -> Result<Vec<BoundaryPoint>> {
    let template = Problem::from_params(base)?.with_barrier(barrier)?;
    let plane = Plane::new(
        &template,
        (x_key, xs.to_vec()),
        ("mu0", y_range.0, y_range.1),
    )?;
    Ok(boundary(&plane, method, search, &trirhythm::monitor::Silent)?.points)
}

/// The largest |Δμ0| (and relative to the simulated value) between the simulated curve and
/// another, over the abscissae where both have a boundary.
pub fn distances(sim: &[BoundaryPoint], other: &[BoundaryPoint]) -> Option<(f64, f64, f64)> {
    sim.iter()
        .zip(other)
        .filter(|(s, o)| s.side == Side::Boundary && o.side == Side::Boundary)
        .map(|(s, o)| ((s.y - o.y).abs(), (s.y - o.y).abs() / s.y, s.x))
        .fold(None, |acc: Option<(f64, f64, f64)>, d| match acc {
            Some(a) if a.0 >= d.0 => Some(a),
            _ => Some(d),
        })
}

/// "largest |Δμ0| = … (…%) at x = …" or "no common point".
pub fn distance_text(sim: &[BoundaryPoint], other: &[BoundaryPoint], x_name: &str) -> String {
    match distances(sim, other) {
        Some((d, rel, x)) => format!(
            "{:.3e} ({} of the simulated μ0) at {x_name} = {}",
            d,
            if rel >= 1e-3 {
                format!("{:.1} %", 100.0 * rel)
            } else {
                format!("{rel:.1e} relative")
            },
            num(x)
        ),
        None => "no abscissa where both have a boundary".into(),
    }
}

/// The rows of a panel for the figure's CSV.
pub fn csv_rows(csv: &mut Csv, panel: &Panel) {
    for c in &panel.curves {
        for q in c.points.iter().filter(|q| q.side == Side::Boundary) {
            csv.row([
                panel.label.clone(),
                c.label.replace(',', ";"),
                c.method.clone(),
                num(q.x),
                num(q.y),
                num(q.y_lo),
                num(q.y_hi),
            ]);
        }
    }
}

/// Colours: simulation black, averaging red, exact blue, exact without the wall grey.
pub const SIM: RGBColor = RGBColor(0, 0, 0);
/// Averaging.
pub const AVG: RGBColor = RGBColor(200, 30, 30);
/// Exact.
pub const EXACT: RGBColor = RGBColor(30, 90, 200);
/// Exact without the wall (reference).
pub const NOWALL: RGBColor = RGBColor(130, 130, 130);
/// The non-oscillating region.
pub const SHADE: RGBColor = RGBColor(170, 200, 245);

/// Draw one panel: the shaded rest region under the simulated boundary, then every curve
/// (simulation solid with its bracket as tick marks, averaging dashed, exact dotted or as
/// markers where it has a single point).
pub fn draw_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    panel: &Panel,
    with_legend: bool,
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let top = panel
        .curves
        .iter()
        .flat_map(|c| c.points.iter())
        .filter(|q| q.side == Side::Boundary)
        .map(|q| q.y)
        .fold(0.0f64, f64::max);
    let (y0, y1) = (0.0, (1.12 * top).min(panel.y_range.1).max(1e-3));
    let mut c = chart(
        area,
        &panel.caption,
        panel.x_range.0..panel.x_range.1,
        y0..y1,
        &panel.x_desc,
        "μ0",
    )?;
    for curve in panel.curves.iter().filter(|c| c.shade) {
        let level = |q: &BoundaryPoint| match q.side {
            Side::Boundary => Some(q.y.clamp(y0, y1)),
            Side::Rests => Some(y1),
            Side::Oscillates => Some(y0),
            Side::Unavailable => None,
        };
        let mut poly: Vec<(f64, f64)> = curve
            .points
            .iter()
            .filter_map(|q| level(q).map(|y| (q.x, y)))
            .collect();
        if poly.len() >= 2 {
            let (xa, xb) = (poly[0].0, poly[poly.len() - 1].0);
            poly.push((xb, y0));
            poly.push((xa, y0));
            c.draw_series(std::iter::once(Polygon::new(poly, SHADE.filled())))
                .map_err(pe)?
                .label("no oscillation (simulated)")
                .legend(|(x, y)| Rectangle::new([(x, y - 5), (x + 16, y + 5)], SHADE.filled()));
        }
    }
    for curve in &panel.curves {
        let pts: Vec<(f64, f64)> = curve
            .points
            .iter()
            .filter(|q| q.side == Side::Boundary)
            .map(|q| (q.x, q.y))
            .collect();
        if pts.is_empty() {
            continue;
        }
        let color = curve.color;
        let label = curve.label.clone();
        let keyed = !label.is_empty();
        if pts.len() == 1 {
            let s = c
                .draw_series(std::iter::once(
                    EmptyElement::at(pts[0])
                        + Cross::new((0, 0), 7, color.stroke_width(3))
                        + Circle::new((0, 0), 9, color.stroke_width(2)),
                ))
                .map_err(pe)?;
            if keyed {
                s.label(label)
                    .legend(move |(x, y)| Cross::new((x + 8, y), 5, color.stroke_width(3)));
            }
            continue;
        }
        match curve.method.as_str() {
            "simulation" => {
                let s = c
                    .draw_series(LineSeries::new(pts.clone(), color.stroke_width(3)))
                    .map_err(pe)?;
                if keyed {
                    s.label(label).legend(move |(x, y)| {
                        PathElement::new([(x, y), (x + 16, y)], color.stroke_width(3))
                    });
                }
                c.draw_series(pts.iter().map(|&p| Circle::new(p, 3, color.filled())))
                    .map_err(pe)?;
            }
            "averaging" => {
                let s = c
                    .draw_series(DashedLineSeries::new(pts, 9, 6, color.stroke_width(2)))
                    .map_err(pe)?;
                if keyed {
                    s.label(label).legend(move |(x, y)| {
                        EmptyElement::at((x, y))
                            + PathElement::new([(0, 0), (8, 0)], color.stroke_width(2))
                            + PathElement::new([(12, 0), (20, 0)], color.stroke_width(2))
                    });
                }
            }
            _ => {
                c.draw_series(DashedLineSeries::new(
                    pts.clone(),
                    3,
                    5,
                    color.stroke_width(3),
                ))
                .map_err(pe)?;
                let s = c
                    .draw_series(
                        pts.iter()
                            .map(|&p| Circle::new(p, 5, color.stroke_width(2))),
                    )
                    .map_err(pe)?;
                if keyed {
                    s.label(label)
                        .legend(move |(x, y)| Circle::new((x + 8, y), 5, color.stroke_width(2)));
                }
            }
        }
    }
    if panel.style_key {
        for (text, dash) in [
            ("solid: simulation", 0),
            ("dashed: averaging", 1),
            ("○ / ×: exact", 2),
        ] {
            c.draw_series(std::iter::empty::<Circle<(f64, f64), i32>>())
                .map_err(pe)?
                .label(text)
                .legend(move |(x, y)| match dash {
                    0 => PathElement::new([(x, y), (x + 20, y)], BLACK.stroke_width(3)),
                    1 => PathElement::new([(x, y), (x + 8, y)], BLACK.stroke_width(2)),
                    _ => PathElement::new([(x + 6, y - 4), (x + 12, y + 4)], BLACK.stroke_width(2)),
                });
        }
    }
    if with_legend {
        legend(&mut c, SeriesLabelPosition::UpperRight)?;
    }
    Ok(())
}

/// ω0 of the three rows.
const OMEGAS: [f64; 3] = [0.9, 0.5, 0.3];
/// λ of the (μ0, r) panels: the exact boundary with the wall is known at λ = 1.
const LAMBDA_R: f64 = 1.0;

/// Fig. 15's data.
#[derive(Serialize, Deserialize)]
pub struct Fig15 {
    heading: Heading,
    header: Vec<String>,
    panels: Vec<Panel>,
}

impl Figure for Fig15 {
    const NUMBER: u32 = 15;
    const TITLE: &'static str = "oscillation (Hopf) boundary μ0 against λ and r, three ω0";

    fn compute(ctx: &FigureContext) -> Result<Fig15> {
        compute_fig15(ctx)
    }

    fn render(&self, stem: &Path) -> Result<Vec<PathBuf>> {
        render_panels(self, &self.header, &self.panels, stem)
    }
}

/// The CSV of boundary panels (`panel,curve,method,x,mu0,mu0_lo,mu0_hi`) and the pictures.
pub fn render_panels(
    picture: &impl Picture,
    header: &[String],
    panels: &[Panel],
    stem: &Path,
) -> Result<Vec<PathBuf>> {
    let mut csv = Csv::new(
        header,
        &["panel", "curve", "method", "x", "mu0", "mu0_lo", "mu0_hi"],
    );
    for p in panels {
        csv_rows(&mut csv, p);
    }
    write_figure(picture, stem, &csv.finish()?)
}

fn compute_fig15(ctx: &FigureContext) -> Result<Fig15> {
    let pre = preset("fig15")?;
    let base = pre.params.clone();
    let r_lambda = base.restitution;
    let (classifier, search, n) = settings(ctx.quick);
    let sim = Method::Simulation(classifier);
    let avg = Method::Averaging(ctx.variant);
    let bar = progress(6, "figure 15");
    let mut panels = Vec::new();
    let mut notes: Vec<String> = pre.notes.iter().map(|s| s.to_string()).collect();
    notes.push(format!(
        "the paper prints neither λ nor r: μ0-against-λ panels at r = {r_lambda} (preset), μ0-against-r panels at λ = {LAMBDA_R}, where the exact boundary with the wall is known"
    ));
    let letters = ["a", "b", "c", "d", "e", "f"];
    for (row, &w) in OMEGAS.iter().enumerate() {
        let p = base.with("omega0", w)?;
        // μ0 against λ
        let xs = linspace(0.9, 1.0, n);
        let yr = (1e-4, if w > 0.6 { 0.16 } else { 0.12 });
        let s = compute(&p, Barrier::On, "lambda", &xs, yr, &sim, &search)?;
        let a = compute(&p, Barrier::On, "lambda", &xs, yr, &avg, &search)?;
        let e = compute(&p, Barrier::On, "lambda", &xs, yr, &Method::Exact, &search)?;
        let free = compute(&p, Barrier::Off, "lambda", &xs, yr, &Method::Exact, &search)?;
        let label = letters[2 * row];
        notes.push(format!(
            "panel {label} (ω0 = {w}, r = {r_lambda}, μ0 against λ): {} simulations; largest distance simulation–averaging {}; simulation–exact (λ = 1 only) {}; the exact boundary without the wall, drawn for reference, is {} from the simulated one with the wall",
            s.iter().map(|q| q.simulations).sum::<usize>(),
            distance_text(&s, &a, "λ"),
            distance_text(&s, &e, "λ"),
            distance_text(&s, &free, "λ"),
        ));
        panels.push(Panel {
            style_key: false,
            caption: format!("({label}) ω0 = {w}, r = {r_lambda}"),
            label: label.into(),
            x_desc: "λ".into(),
            x_range: (0.9, 1.0),
            y_range: yr,
            curves: vec![
                Curve::new(Role::Simulation, "simulation (bracket < line width)", s),
                Curve::new(
                    Role::Averaging,
                    format!("averaging, f′(0) = 0 ({})", ctx.variant.name()),
                    a,
                ),
                Curve::new(Role::Exact, "exact, wall (λ = 1 only)", e),
                Curve::new(
                    Role::ExactNoWall,
                    "exact without the wall (reference)",
                    free,
                ),
            ],
        });
        bar.inc(1);
        // μ0 against r at λ = 1
        let p = p.with("lambda", LAMBDA_R)?;
        let xs = linspace(0.9, 0.999, n);
        let yr = (1e-4, if w > 0.6 { 0.08 } else { 0.045 });
        let s = compute(&p, Barrier::On, "r", &xs, yr, &sim, &search)?;
        let a = compute(&p, Barrier::On, "r", &xs, yr, &avg, &search)?;
        let e = compute(&p, Barrier::On, "r", &xs, yr, &Method::Exact, &search)?;
        let label = letters[2 * row + 1];
        notes.push(format!(
            "panel {label} (ω0 = {w}, λ = {LAMBDA_R}, μ0 against r): {} simulations; largest distance simulation–averaging {}; simulation–exact {}",
            s.iter().map(|q| q.simulations).sum::<usize>(),
            distance_text(&s, &a, "r"),
            distance_text(&s, &e, "r"),
        ));
        panels.push(Panel {
            style_key: false,
            caption: format!("({label}) ω0 = {w}, λ = {LAMBDA_R}"),
            label: label.into(),
            x_desc: "r".into(),
            x_range: (0.9, 0.999),
            y_range: yr,
            curves: vec![
                Curve::new(Role::Simulation, "simulation", s),
                Curve::new(
                    Role::Averaging,
                    format!("averaging ({})", ctx.variant.name()),
                    a,
                ),
                Curve::new(Role::Exact, "exact: μ0π/(2ω_d) + ln r = 0", e),
            ],
        });
        bar.inc(1);
    }
    bar.finish_and_clear();
    notes.push(
        "with decreasing ω0 the boundary against λ falls (ω0^λ cos(πλ/2)) and the impact term (∝ ω1 ∝ ω0) shrinks: the rest region narrows; the averaging's and the simulated boundary separate as ω0 falls and λ moves away from 1".into(),
    );
    let header = csv_header(
        15,
        "oscillation (Hopf) boundary μ0 against λ and r, three ω0",
        ctx,
        &notes,
    );
    let heading = heading(
        15,
        "oscillation (Hopf) boundary: μ0 against λ (left) and r (right) for ω0 = 0.9, 0.5, 0.3",
        ctx,
        &base,
        &["mu0", "omega0", "lambda", "r"],
        vec![
            format!("shaded: no oscillation (a small amplitude dies, simulated); white: oscillation. Left: r = {r_lambda}; right: λ = {LAMBDA_R} (not printed in the paper; the exact boundary with the wall is known only at λ = 1)"),
            format!("simulation: predictor–corrector from U(0) = 1e-9, Δt = {}, growth rate of ln(amplitude) after the start-up transient, bracket ≤ {} relative", classifier.method.dt, search.tolerance),
        ],
    );
    Ok(Fig15 {
        heading,
        header,
        panels,
    })
}

impl Picture for Fig15 {
    fn size(&self) -> (u32, u32) {
        (1400, 1500)
    }

    fn heading(&self) -> Heading {
        self.heading.clone()
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()>
    where
        DB::ErrorType: 'static,
    {
        let areas = root.split_evenly((3, 2));
        for (i, (area, panel)) in areas.iter().zip(&self.panels).enumerate() {
            draw_panel(area, panel, i < 2)?;
        }
        Ok(())
    }
}
