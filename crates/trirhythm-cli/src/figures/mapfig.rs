//! Shared data and drawing of classification maps (Figs 2, 3, 6, 10, 12): regions coloured by
//! count (mono blue, bi green, tri black, as in the paper), exact fold curves on top, one legend
//! for the whole figure in a strip below the panels (outside the data).

use super::{csv_header, variant_line, FigureContext};
use crate::common::{num, Csv};
use crate::maps::{folds_csv, run_map};
use crate::output::write_atomic;
use crate::plot::{chart, pe, save, Heading, LegendStrip, Picture, Symbol, FONT};
use anyhow::Result;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use trirhythm::model::Params;
use trirhythm::theory::bifurcation::{trace_folds, trace_printed_eq37, Axis, Folds, Plane, What};

/// Colour of a count: 0 light grey, 1 blue, 2 green, 3 black, more purple.
pub fn count_colour(c: u8) -> RGBColor {
    match c {
        0 => RGBColor(225, 225, 225),
        1 => RGBColor(40, 90, 220),
        2 => RGBColor(40, 170, 70),
        3 => RGBColor(0, 0, 0),
        _ => RGBColor(150, 60, 180),
    }
}

/// Fold-curve colour (visible on blue, green and black).
pub const FOLD: RGBColor = RGBColor(230, 40, 40);
/// Printed-Eq. 37 curve colour.
pub const PRINTED: RGBColor = RGBColor(255, 170, 0);

/// One axis of a panel as requested: key, range, label and display scale (values / scale).
#[derive(Clone)]
pub struct AxisSpec {
    pub key: &'static str,
    pub start: f64,
    pub stop: f64,
    pub label: &'static str,
    pub scale: f64,
}

impl AxisSpec {
    pub fn new(key: &'static str, start: f64, stop: f64, label: &'static str, scale: f64) -> Self {
        AxisSpec {
            key,
            start,
            stop,
            label,
            scale,
        }
    }
}

/// A computed panel's axis: the grid, and how it is drawn.
#[derive(Clone, Serialize, Deserialize)]
pub struct PanelAxis {
    /// The grid's parameter key and values.
    pub grid: Axis,
    /// The parameter's symbol.
    pub label: String,
    /// Values are drawn divided by this.
    pub scale: f64,
}

impl PanelAxis {
    fn desc(&self) -> String {
        if self.scale == 1.0 {
            self.label.clone()
        } else {
            format!("{} / {:e}", self.label, self.scale)
        }
    }
}

/// A computed panel: counts on the grid, the fold curves, what is named and marked.
#[derive(Serialize, Deserialize)]
pub struct MapPanel {
    /// `a`, `b`, … or `i`, `ii`.
    pub label: String,
    pub caption: String,
    /// The panel's parameters (those not swept), described.
    pub params: String,
    /// Stable cycles or modes of P(A).
    pub what: What,
    pub x: PanelAxis,
    pub y: PanelAxis,
    /// Count at each grid point, row-major (`counts[iy * nx + ix]`).
    pub counts: Vec<u8>,
    pub folds: Folds,
    /// The paper's printed Eq. 36–37 construction, where drawn.
    pub printed: Option<Folds>,
    /// A parameter point to mark (x, y, label), e.g. the paper's standard values.
    pub mark: Option<(f64, f64, String)>,
    /// Names of saddle-node lines drawn on the picture: (index of the curve, name).
    pub fold_names: Vec<(usize, String)>,
}

impl MapPanel {
    /// Count at grid indices.
    fn count(&self, ix: usize, iy: usize) -> u8 {
        self.counts[iy * self.x.grid.count + ix]
    }

    /// How many grid points have each count 0, 1, 2, 3, ≥ 4.
    fn histogram(&self) -> [usize; 5] {
        let mut h = [0; 5];
        for &c in &self.counts {
            h[(c as usize).min(4)] += 1;
        }
        h
    }
}

/// The paper's names of the saddle-node lines (Sec. 3: "L1 … the saddle-node bifurcation of
/// the outer limit cycle …, L3 … of the inner limit cycle"): at the middle of each curve, the
/// double root is the outermost positive root of f (L1), the innermost (L3) or between (L2).
/// The longest curve of each name is labelled.
fn name_folds(base: &Params, plane: &Plane, folds: &Folds) -> Vec<(usize, String)> {
    let mut best: Vec<(usize, String, usize)> = Vec::new();
    for (i, curve) in folds.curves.iter().enumerate() {
        let Some(q) = curve.points.get(curve.points.len() / 2) else {
            continue;
        };
        let Ok(p) = base
            .with(&plane.x.key, q.x)
            .and_then(|p| p.with(&plane.y.key, q.y))
        else {
            continue;
        };
        let Ok(th) = trirhythm::theory::averaging::Theory::new(&p, plane.variant) else {
            continue;
        };
        let roots = th.limit_cycles();
        let tol = 1e-4 * q.amplitude.max(1e-9);
        let below = roots
            .iter()
            .filter(|c| c.amplitude < q.amplitude - tol)
            .count();
        let above = roots
            .iter()
            .filter(|c| c.amplitude > q.amplitude + tol)
            .count();
        let name = match (below, above) {
            (_, 0) => "L1 (outer cycle)",
            (0, _) => "L3 (inner cycle)",
            _ => "L2 (middle cycle)",
        };
        let len = curve.points.len();
        match best.iter_mut().find(|b| b.1 == name) {
            Some(b) if b.2 < len => *b = (i, name.to_string(), len),
            Some(_) => {}
            None => best.push((i, name.to_string(), len)),
        }
    }
    best.into_iter().map(|(i, n, _)| (i, n)).collect()
}

/// Grid points per axis: quick or paper quality.
pub fn resolution(ctx: &FigureContext) -> usize {
    if ctx.quick {
        81
    } else {
        401
    }
}

/// Classify a plane and trace its folds (and the printed Eq. 37 curves when asked).
#[allow(clippy::too_many_arguments)]
pub fn compute_panel(
    ctx: &FigureContext,
    label: &str,
    caption: String,
    base: &Params,
    xs: AxisSpec,
    ys: AxisSpec,
    what: What,
    printed: bool,
) -> Result<MapPanel> {
    let n = resolution(ctx);
    let plane = Plane::new(
        base,
        Axis::new(xs.key, xs.start, xs.stop, n)?,
        Axis::new(ys.key, ys.start, ys.stop, n)?,
        ctx.variant,
    )?;
    let map = run_map(&plane, what, &format!("panel {label}"));
    let folds = trace_folds(&map);
    let printed = if printed && ctx.variant == trirhythm::theory::averaging::Variant::Paper {
        Some(trace_printed_eq37(&map)?)
    } else {
        None
    };
    let fold_names = if what == What::Rhythmicity {
        name_folds(base, &map.plane, &folds)
    } else {
        Vec::new()
    };
    let axis = |spec: AxisSpec, grid: &Axis| PanelAxis {
        grid: grid.clone(),
        label: spec.label.to_string(),
        scale: spec.scale,
    };
    Ok(MapPanel {
        label: label.to_string(),
        caption,
        params: map.plane.base.describe(),
        what,
        x: axis(xs, &map.plane.x),
        y: axis(ys, &map.plane.y),
        counts: map.counts,
        folds,
        printed,
        mark: None,
        fold_names,
    })
}

/// Notes on a panel for the CSV header: counts, curves, cusps.
pub fn panel_notes(p: &MapPanel) -> Vec<String> {
    let h = p.histogram();
    let total: usize = h.iter().sum();
    let pct = |k: usize| 100.0 * h[k] as f64 / total as f64;
    let mut v = vec![format!(
        "panel {}: {} ({}); share of grid points with count 0/1/2/3: {:.1}% / {:.1}% / {:.1}% / {:.1}%; {} fold curves, {} cusps{}",
        p.label,
        p.caption,
        p.params,
        pct(0),
        pct(1),
        pct(2),
        pct(3),
        p.folds.curves.len(),
        p.folds.cusps.len(),
        p.folds
            .cusps
            .iter()
            .map(|c| format!(" (cusp at {}={:.6e}, {}={:.6e}, A={:.5})", p.x.grid.key, c.x, p.y.grid.key, c.y, c.amplitude))
            .collect::<String>()
    )];
    if let Some(pr) = &p.printed {
        v.push(format!(
            "panel {}: printed Eq. 36-37 construction gives {} curves",
            p.label,
            pr.curves.len()
        ));
    }
    v
}

/// A map figure's data: panels on a grid of `layout` (rows, columns).
#[derive(Serialize, Deserialize)]
pub struct MapFigure {
    heading: Heading,
    /// CSV comment lines (both CSV files).
    header: Vec<String>,
    panels: Vec<MapPanel>,
    layout: (usize, usize),
}

/// Assemble a map figure from computed panels: the heading, and the CSV header with the
/// notes and each panel's counts, curves and cusps.
pub fn map_figure(
    ctx: &FigureContext,
    (n, title): (u32, &str),
    subtitle: String,
    mut notes: Vec<String>,
    panels: Vec<MapPanel>,
    layout: (usize, usize),
) -> MapFigure {
    for p in &panels {
        notes.extend(panel_notes(p));
    }
    let mut header = csv_header(n, title, ctx, &notes);
    for p in &panels {
        header.push(format!(
            "panel {}: x = {}, y = {}",
            p.label, p.x.grid.key, p.y.grid.key
        ));
    }
    MapFigure {
        heading: Heading {
            title: format!("Fig. {n}: {title}"),
            lines: vec![subtitle, variant_line(ctx.variant)],
        },
        header,
        panels,
        layout,
    }
}

impl MapFigure {
    /// Write `stem.csv` (panel,x,y,count), `stem_folds.csv` and the picture.
    pub fn render(&self, stem: &Path) -> Result<Vec<PathBuf>> {
        let mut csv = Csv::new(&self.header, &["panel", "x", "y", "count"]);
        for p in &self.panels {
            for iy in 0..p.y.grid.count {
                let y = num(p.y.grid.value(iy));
                for ix in 0..p.x.grid.count {
                    csv.row([
                        p.label.clone(),
                        num(p.x.grid.value(ix)),
                        y.clone(),
                        p.count(ix, iy).to_string(),
                    ]);
                }
            }
        }
        let csv_path = stem.with_extension("csv");
        write_atomic(&csv_path, csv.finish()?.as_bytes())?;
        let mut fc = Csv::new(
            &self.header,
            &["panel", "curve", "system", "x", "y", "amplitude"],
        );
        for p in &self.panels {
            let mut sets = vec![&p.folds];
            if let Some(pr) = &p.printed {
                sets.push(pr);
            }
            folds_csv(&mut fc, std::slice::from_ref(&p.label), &sets);
        }
        let name = stem.file_name().unwrap_or_default().to_string_lossy();
        let folds_path = stem.with_file_name(format!("{name}_folds.csv"));
        write_atomic(&folds_path, fc.finish()?.as_bytes())?;
        let mut files = vec![csv_path, folds_path];
        files.extend(save(self, stem)?);
        Ok(files)
    }

    /// One legend for every panel: the counts met in any panel, the curves and markers drawn.
    fn legend(&self) -> LegendStrip {
        let mut counts = [0usize; 5];
        for p in &self.panels {
            for (c, h) in counts.iter_mut().zip(p.histogram()) {
                *c += h;
            }
        }
        let modes = self.panels.iter().any(|p| p.what == What::Modes);
        let names = if modes {
            ["-", "unimodal", "bimodal", "trimodal", "4+ modes"]
        } else {
            [
                "no stable cycle",
                "mono (1)",
                "bi (2)",
                "tri (3)",
                "4 or more",
            ]
        };
        let mut entries: Vec<(Symbol, String)> = (0..5)
            .filter(|&k| counts[k] > 0)
            .map(|k| (Symbol::Swatch(count_colour(k as u8)), names[k].to_string()))
            .collect();
        if self.panels.iter().any(|p| !p.folds.curves.is_empty()) {
            let name = if modes {
                "P-bifurcation (m1 = m1' = 0)"
            } else {
                "saddle-node (f = f' = 0)"
            };
            entries.push((Symbol::Line(FOLD), name.into()));
        }
        if self
            .panels
            .iter()
            .any(|p| p.printed.as_ref().is_some_and(|f| !f.curves.is_empty()))
        {
            entries.push((Symbol::Dashed(PRINTED), "Eq. 36-37 as printed".into()));
        }
        if self.panels.iter().any(|p| !p.folds.cusps.is_empty()) {
            entries.push((Symbol::Ring(FOLD), "cusp".into()));
        }
        // one entry for the marked points, however many panels mark different parameters
        let mut marks: Vec<&str> = Vec::new();
        for (_, _, text) in self.panels.iter().filter_map(|p| p.mark.as_ref()) {
            if !marks.contains(&text.as_str()) {
                marks.push(text);
            }
        }
        if !marks.is_empty() {
            entries.push((Symbol::Cross(MARK), marks.join(" / ")));
        }
        LegendStrip { entries }
    }
}

/// Panel size in pixels.
const PANEL: (u32, u32) = (560, 470);

impl Picture for MapFigure {
    fn size(&self) -> (u32, u32) {
        let (r, c) = self.layout;
        let w = PANEL.0 * c as u32;
        (w, PANEL.1 * r as u32 + self.legend().height(w))
    }

    fn heading(&self) -> Heading {
        self.heading.clone()
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()>
    where
        DB::ErrorType: 'static,
    {
        let (panels, strip) = root.split_vertically(PANEL.1 * self.layout.0 as u32);
        for (area, p) in panels.split_evenly(self.layout).iter().zip(&self.panels) {
            draw_panel(area, p)?;
        }
        self.legend().draw(&strip)
    }
}

/// Colour of the marked parameter point.
const MARK: RGBColor = RGBColor(255, 0, 255);

/// Draw one map panel: merged row runs of equal count, fold curves (named where known),
/// cusps, the marked point. The legend is the figure's, outside the panels.
fn draw_panel<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, p: &MapPanel) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let (gx, gy) = (&p.x.grid, &p.y.grid);
    let (sx, sy) = (p.x.scale, p.y.scale);
    let xr = (gx.start / sx)..(gx.stop / sx);
    let yr = (gy.start / sy)..(gy.stop / sy);
    let mut c = chart(
        area,
        &format!("({}) {}", p.label, p.caption),
        xr.clone(),
        yr.clone(),
        &p.x.desc(),
        &p.y.desc(),
    )?;
    let (nx, ny) = (gx.count, gy.count);
    let hx = (gx.stop - gx.start) / (nx - 1) as f64 / sx;
    let hy = (gy.stop - gy.start) / (ny - 1) as f64 / sy;
    let clampx = |v: f64| v.clamp(xr.start, xr.end);
    let clampy = |v: f64| v.clamp(yr.start, yr.end);
    let mut rects = Vec::new();
    for iy in 0..ny {
        let y = gy.value(iy) / sy;
        let mut ix = 0;
        while ix < nx {
            let cnt = p.count(ix, iy);
            let mut jx = ix;
            while jx + 1 < nx && p.count(jx + 1, iy) == cnt {
                jx += 1;
            }
            let x0 = clampx(gx.value(ix) / sx - hx / 2.0);
            let x1 = clampx(gx.value(jx) / sx + hx / 2.0);
            rects.push(Rectangle::new(
                [(x0, clampy(y - hy / 2.0)), (x1, clampy(y + hy / 2.0))],
                count_colour(cnt).filled(),
            ));
            ix = jx + 1;
        }
    }
    c.draw_series(rects).map_err(pe)?;
    for curve in &p.folds.curves {
        let pts: Vec<(f64, f64)> = curve.points.iter().map(|q| (q.x / sx, q.y / sy)).collect();
        c.draw_series(LineSeries::new(pts, FOLD.stroke_width(2)))
            .map_err(pe)?;
    }
    for curve in p.printed.iter().flat_map(|f| &f.curves) {
        let pts: Vec<(f64, f64)> = curve.points.iter().map(|q| (q.x / sx, q.y / sy)).collect();
        c.draw_series(DashedLineSeries::new(pts, 7, 5, PRINTED.stroke_width(2)))
            .map_err(pe)?;
    }
    for (i, name) in &p.fold_names {
        let curve = &p.folds.curves[*i];
        let q = &curve.points[curve.points.len() / 2];
        let style = (FONT, 16)
            .into_font()
            .color(&FOLD)
            .pos(Pos::new(HPos::Left, VPos::Center));
        // on a white box: red on green, blue or black is hard to read
        let w = (0.5 * 16.0 * name.chars().count() as f64) as i32 + 8;
        c.draw_series(std::iter::once(
            EmptyElement::at((q.x / sx, q.y / sy))
                + Rectangle::new([(6, -11), (6 + w, 11)], WHITE.mix(0.85).filled())
                + Text::new(name.clone(), (10, 0), style.clone()),
        ))
        .map_err(pe)?;
    }
    c.draw_series(p.folds.cusps.iter().map(|q| {
        EmptyElement::at((q.x / sx, q.y / sy))
            + Circle::new((0, 0), 6, WHITE.filled())
            + Circle::new((0, 0), 6, FOLD.stroke_width(2))
    }))
    .map_err(pe)?;
    if let Some((mx, my, _)) = &p.mark {
        c.draw_series(std::iter::once(
            EmptyElement::at((mx / sx, my / sy))
                + Cross::new((0, 0), 7, WHITE.stroke_width(4))
                + Cross::new((0, 0), 7, MARK.stroke_width(2)),
        ))
        .map_err(pe)?;
    }
    Ok(())
}

/// A figure of four (γ0, δ0) rhythmicity panels, one per value of `key` (Figs 3 and 6): the
/// preset's parameters with `key` set to each value, folds traced, the paper's point marked.
pub fn gamma_delta_family(
    ctx: &FigureContext,
    (number, title): (u32, &str),
    preset_name: &str,
    (key, symbol, values): (&str, &str, [f64; 4]),
    subtitle: String,
) -> Result<MapFigure> {
    let pre = trirhythm::model::preset(preset_name)?;
    let mut panels = Vec::new();
    for (label, value) in ["a", "b", "c", "d"].into_iter().zip(values) {
        let mut panel = compute_panel(
            ctx,
            label,
            format!("{symbol} = {value}"),
            &pre.params.with(key, value)?,
            AxisSpec::new("gamma0", 0.0, 1.2e-4, "γ0", 1e-5),
            AxisSpec::new("delta0", 1e-8, 6e-7, "δ0", 1e-7),
            What::Rhythmicity,
            false,
        )?;
        panel.mark = Some((5.862e-5, 2.13e-7, "paper's (γ0, δ0)".into()));
        panels.push(panel);
    }
    let mut notes: Vec<String> = pre.notes.iter().map(|s| s.to_string()).collect();
    notes.push(format!("{symbol} values chosen: {values:?}"));
    notes.push(
        "count = number of stable limit cycles; red: folds f = ∂f/∂A = 0 traced exactly".into(),
    );
    Ok(map_figure(
        ctx,
        (number, title),
        subtitle,
        notes,
        panels,
        (2, 2),
    ))
}
