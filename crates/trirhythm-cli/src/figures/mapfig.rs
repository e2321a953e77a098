//! Shared drawing of classification maps (Figs 2, 3, 6, 10, 12): regions coloured by count
//! (mono blue, bi green, tri black, as in the paper), exact fold curves on top, a legend.

use super::{csv_header, variant_line, FigureContext};
use crate::common::{num, Csv};
use crate::maps::{folds_csv, run_map};
use crate::output::write_atomic;
use crate::plot::{chart, legend, pe, save, Heading, Picture, FONT};
use anyhow::Result;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::path::PathBuf;
use trirhythm::model::Params;
use trirhythm::theory::bifurcation::{
    trace_folds, trace_printed_eq37, Axis, Folds, Map, Plane, What,
};

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

/// One axis of a panel: key, range, points, label and display scale (values / scale).
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

    fn desc(&self) -> String {
        if self.scale == 1.0 {
            self.label.to_string()
        } else {
            format!("{} / {:e}", self.label, self.scale)
        }
    }
}

/// A computed panel.
pub struct MapPanel {
    pub label: String,
    pub caption: String,
    pub map: Map,
    pub folds: Folds,
    pub printed: Option<Folds>,
    pub xs: AxisSpec,
    pub ys: AxisSpec,
    /// A parameter point to mark (x, y, label), e.g. the paper's standard values.
    pub mark: Option<(f64, f64, String)>,
    /// Names of saddle-node lines drawn on the picture: (index of the curve, name).
    pub fold_names: Vec<(usize, String)>,
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
    Ok(MapPanel {
        label: label.to_string(),
        caption,
        map,
        folds,
        printed,
        xs,
        ys,
        mark: None,
        fold_names,
    })
}

/// Notes on a panel for the CSV header: counts, curves, cusps.
pub fn panel_notes(p: &MapPanel) -> Vec<String> {
    let h = p.map.histogram();
    let total: usize = h.iter().sum();
    let pct = |k: usize| 100.0 * h[k] as f64 / total as f64;
    let mut v = vec![format!(
        "panel {}: {} ({}); share of grid points with count 0/1/2/3: {:.1}% / {:.1}% / {:.1}% / {:.1}%; {} fold curves, {} cusps{}",
        p.label,
        p.caption,
        p.map.plane.base.describe(),
        pct(0),
        pct(1),
        pct(2),
        pct(3),
        p.folds.curves.len(),
        p.folds.cusps.len(),
        p.folds
            .cusps
            .iter()
            .map(|c| format!(" (cusp at {}={:.6e}, {}={:.6e}, A={:.5})", p.xs.key, c.x, p.ys.key, c.y, c.amplitude))
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

/// Write `figNN.csv` (panel,x,y,count), `figNN_folds.csv` and the picture.
#[allow(clippy::too_many_arguments)]
pub fn write_map_figure(
    ctx: &FigureContext,
    n: u32,
    title: &str,
    subtitle: String,
    mut notes: Vec<String>,
    panels: Vec<MapPanel>,
    layout: (usize, usize),
    legend_at: SeriesLabelPosition,
) -> Result<Vec<PathBuf>> {
    for p in &panels {
        notes.extend(panel_notes(p));
    }
    std::fs::create_dir_all(&ctx.out_dir)?;
    let header = csv_header(n, title, ctx, &notes);
    let stem = ctx.stem(n);
    let mut header = header;
    for p in &panels {
        header.push(format!(
            "panel {}: x = {}, y = {}",
            p.label, p.map.plane.x.key, p.map.plane.y.key
        ));
    }
    let mut csv = Csv::new(&header, &["panel", "x", "y", "count"]);
    for p in &panels {
        let pl = &p.map.plane;
        for iy in 0..pl.y.count {
            let y = num(pl.y.value(iy));
            for ix in 0..pl.x.count {
                csv.row([
                    p.label.clone(),
                    num(pl.x.value(ix)),
                    y.clone(),
                    p.map.count(ix, iy).to_string(),
                ]);
            }
        }
    }
    let csv_path = stem.with_extension("csv");
    write_atomic(&csv_path, csv.finish()?.as_bytes())?;
    let mut fc = Csv::new(
        &header,
        &["panel", "curve", "system", "x", "y", "amplitude"],
    );
    for p in &panels {
        let mut sets = vec![&p.folds];
        if let Some(pr) = &p.printed {
            sets.push(pr);
        }
        folds_csv(&mut fc, std::slice::from_ref(&p.label), &sets);
    }
    let folds_path = stem.with_file_name(format!("fig{n:02}_folds.csv"));
    write_atomic(&folds_path, fc.finish()?.as_bytes())?;
    let mut files = vec![csv_path, folds_path];
    files.extend(save(
        &MapFigure {
            heading: Heading {
                title: format!("Fig. {n}: {title}"),
                lines: vec![subtitle, variant_line(ctx.variant)],
            },
            panels,
            layout,
            legend_at,
        },
        &stem,
    )?);
    Ok(files)
}

struct MapFigure {
    heading: Heading,
    panels: Vec<MapPanel>,
    layout: (usize, usize),
    legend_at: SeriesLabelPosition,
}

impl Picture for MapFigure {
    fn size(&self) -> (u32, u32) {
        let (r, c) = self.layout;
        (560 * c as u32, 470 * r as u32)
    }

    fn heading(&self) -> Heading {
        self.heading.clone()
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()>
    where
        DB::ErrorType: 'static,
    {
        let areas = root.split_evenly(self.layout);
        // the legend (on the first panel) lists the counts met in any panel
        let mut counts = [0usize; 5];
        for p in &self.panels {
            for (c, h) in counts.iter_mut().zip(p.map.histogram()) {
                *c += h;
            }
        }
        for (i, (area, p)) in areas.iter().zip(&self.panels).enumerate() {
            draw_panel(area, p, (i == 0).then(|| (self.legend_at.clone(), counts)))?;
        }
        Ok(())
    }
}

/// Draw one map panel: merged row runs of equal count, fold curves, cusps.
pub fn draw_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    p: &MapPanel,
    legend_at: Option<(SeriesLabelPosition, [usize; 5])>,
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let pl = &p.map.plane;
    let (sx, sy) = (p.xs.scale, p.ys.scale);
    let xr = (pl.x.start / sx)..(pl.x.stop / sx);
    let yr = (pl.y.start / sy)..(pl.y.stop / sy);
    let mut c = chart(
        area,
        &format!("({}) {}", p.label, p.caption),
        xr.clone(),
        yr.clone(),
        &p.xs.desc(),
        &p.ys.desc(),
    )?;
    let (nx, ny) = (pl.x.count, pl.y.count);
    let hx = (pl.x.stop - pl.x.start) / (nx - 1) as f64 / sx;
    let hy = (pl.y.stop - pl.y.start) / (ny - 1) as f64 / sy;
    let clampx = |v: f64| v.clamp(xr.start, xr.end);
    let clampy = |v: f64| v.clamp(yr.start, yr.end);
    let mut rects = Vec::new();
    for iy in 0..ny {
        let y = pl.y.value(iy) / sy;
        let mut ix = 0;
        while ix < nx {
            let cnt = p.map.count(ix, iy);
            let mut jx = ix;
            while jx + 1 < nx && p.map.count(jx + 1, iy) == cnt {
                jx += 1;
            }
            let x0 = clampx(pl.x.value(ix) / sx - hx / 2.0);
            let x1 = clampx(pl.x.value(jx) / sx + hx / 2.0);
            rects.push(Rectangle::new(
                [(x0, clampy(y - hy / 2.0)), (x1, clampy(y + hy / 2.0))],
                count_colour(cnt).filled(),
            ));
            ix = jx + 1;
        }
    }
    c.draw_series(rects).map_err(pe)?;
    let h = legend_at
        .as_ref()
        .map_or_else(|| p.map.histogram(), |l| l.1);
    let names = [
        "no stable cycle",
        "mono (1)",
        "bi (2)",
        "tri (3)",
        "4 or more",
    ];
    let names_modes = ["-", "unimodal", "bimodal", "trimodal", "4+ modes"];
    for k in 0..5 {
        if h[k] == 0 {
            continue;
        }
        let name = if p.map.what == What::Modes {
            names_modes[k]
        } else {
            names[k]
        };
        let col = count_colour(k as u8);
        c.draw_series(std::iter::empty::<Circle<(f64, f64), i32>>())
            .map_err(pe)?
            .label(name)
            .legend(move |(x, y)| Rectangle::new([(x, y - 6), (x + 14, y + 6)], col.filled()));
    }
    let mut first = true;
    for curve in &p.folds.curves {
        let pts: Vec<(f64, f64)> = curve.points.iter().map(|q| (q.x / sx, q.y / sy)).collect();
        let s = c
            .draw_series(LineSeries::new(pts, FOLD.stroke_width(2)))
            .map_err(pe)?;
        if first {
            s.label(if p.map.what == What::Modes {
                "P-bifurcation (m1 = m1' = 0)"
            } else {
                "saddle-node (f = f' = 0)"
            })
            .legend(|(x, y)| PathElement::new([(x, y), (x + 14, y)], FOLD.stroke_width(2)));
            first = false;
        }
    }
    if let Some(pr) = &p.printed {
        let mut first = true;
        for curve in &pr.curves {
            let pts: Vec<(f64, f64)> = curve.points.iter().map(|q| (q.x / sx, q.y / sy)).collect();
            let s = c
                .draw_series(DashedLineSeries::new(pts, 7, 5, PRINTED.stroke_width(2)))
                .map_err(pe)?;
            if first {
                s.label("Eq. 36-37 as printed").legend(|(x, y)| {
                    PathElement::new([(x, y), (x + 14, y)], PRINTED.stroke_width(2))
                });
                first = false;
            }
        }
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
    if !p.folds.cusps.is_empty() {
        c.draw_series(p.folds.cusps.iter().map(|q| {
            EmptyElement::at((q.x / sx, q.y / sy))
                + Circle::new((0, 0), 6, WHITE.filled())
                + Circle::new((0, 0), 6, FOLD.stroke_width(2))
        }))
        .map_err(pe)?
        .label("cusp")
        .legend(|(x, y)| Circle::new((x + 7, y), 5, FOLD.stroke_width(2)));
    }
    if let Some((mx, my, text)) = &p.mark {
        let (mx, my) = (mx / sx, my / sy);
        c.draw_series(std::iter::once(
            EmptyElement::at((mx, my))
                + Cross::new((0, 0), 7, WHITE.stroke_width(4))
                + Cross::new((0, 0), 7, RGBColor(255, 0, 255).stroke_width(2)),
        ))
        .map_err(pe)?
        .label(text.clone())
        .legend(|(x, y)| Cross::new((x + 7, y), 5, RGBColor(255, 0, 255).stroke_width(2)));
    }
    if let Some((pos, _)) = legend_at {
        legend(&mut c, pos)?;
    }
    Ok(())
}

/// A figure of four (γ0, δ0) rhythmicity panels, one per value of `key` (Figs 3 and 6): the
/// preset's parameters with `key` set to each value, folds traced, the paper's point marked.
pub fn gamma_delta_family(
    ctx: &FigureContext,
    number: u32,
    preset_name: &str,
    (key, symbol, values): (&str, &str, [f64; 4]),
    title: &str,
    subtitle: String,
) -> Result<Vec<PathBuf>> {
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
    write_map_figure(
        ctx,
        number,
        title,
        subtitle,
        notes,
        panels,
        (2, 2),
        SeriesLabelPosition::UpperRight,
    )
}
