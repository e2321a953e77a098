//! What the map figures (Figs 2, 3, 6, 10, 12) share: a parameter plane classified point by
//! point — the number of stable limit cycles (roots of f with df/dA < 0, Eq. 18) or the
//! number of modes of the stationary P(A) (Eq. 27) — with the fold curves traced exactly by
//! pseudo-arclength continuation (f = ∂f/∂A = 0, or m1 = ∂m1/∂A = 0 for the P-bifurcation),
//! the paper's printed Eq. 36–37 construction where asked, and the saddle-node lines named as
//! the paper's text defines L1–L3.
//!
//! Method: [`classify`] (a Sturm count per grid point), [`trace_folds`],
//! [`trace_printed_eq37`]. Checked by the library's bifurcation tests (the cusp of Fig. 2 (i)
//! at α0 = 1/6, β0 = 1/135) and `tests/figures.rs`.

use crate::notes::{num, table_notes, variant_line, Caption};
use crate::table::Table;
use crate::{FigureOptions, Monitor};
use serde::{Deserialize, Serialize};
use trirhythm::model::Params;
use trirhythm::theory::bifurcation::{
    classify, trace_folds, trace_printed_eq37, Axis, Folds, Plane, What,
};
use trirhythm::Result;

/// One axis of a panel as requested: key, range, label and display scale (values / scale).
#[derive(Clone)]
pub struct AxisSpec {
    /// Parameter key.
    pub key: &'static str,
    /// First grid value.
    pub start: f64,
    /// Last grid value.
    pub stop: f64,
    /// The parameter's symbol.
    pub label: &'static str,
    /// The unit its values are read in (values / scale).
    pub scale: f64,
}

impl AxisSpec {
    /// An axis of `key` from `start` to `stop`, named `label`, read in units of `scale`.
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
    /// The unit its values are read in (values / scale).
    pub scale: f64,
}

impl PanelAxis {
    /// The axis' name with its unit: `β0 (×10⁻³)` for values read in thousandths.
    pub fn desc(&self) -> String {
        if self.scale == 1.0 {
            return self.label.clone();
        }
        let e = format!("{:e}", self.scale);
        match e.split_once('e') {
            Some(("1", exp)) => {
                let sup: String = exp
                    .chars()
                    .map(|c| match c {
                        '-' => '⁻',
                        d => ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹']
                            [d.to_digit(10).unwrap_or(0) as usize],
                    })
                    .collect();
                format!("{} (×10{sup})", self.label)
            }
            _ => format!("{} (×{e})", self.label),
        }
    }
}

/// A computed panel: counts on the grid, the fold curves, what is named and marked.
#[derive(Serialize, Deserialize)]
pub struct MapPanel {
    /// `a`, `b`, … or `i`, `ii`.
    pub label: String,
    /// What the panel sets.
    pub caption: String,
    /// The panel's parameters (those not swept), described.
    pub params: String,
    /// Stable cycles or modes of P(A).
    pub what: What,
    /// Horizontal axis.
    pub x: PanelAxis,
    /// Vertical axis.
    pub y: PanelAxis,
    /// Count at each grid point, row-major (`counts[iy * nx + ix]`).
    pub counts: Vec<u8>,
    /// The fold curves, traced exactly.
    pub folds: Folds,
    /// The paper's printed Eq. 36–37 construction, where drawn.
    pub printed: Option<Folds>,
    /// A parameter point to mark (x, y, label), e.g. the paper's standard values.
    pub mark: Option<(f64, f64, String)>,
    /// The name of every saddle-node line (L1 outer, L2 middle, L3 inner cycle's fold): (index
    /// of the curve, name).
    pub fold_names: Vec<(usize, String)>,
}

impl MapPanel {
    /// Count at grid indices.
    pub fn count(&self, ix: usize, iy: usize) -> u8 {
        self.counts[iy * self.x.grid.count + ix]
    }

    /// How many grid points have each count 0, 1, 2, 3, ≥ 4.
    pub fn histogram(&self) -> [usize; 5] {
        let mut h = [0; 5];
        for &c in &self.counts {
            h[(c as usize).min(4)] += 1;
        }
        h
    }

    /// Share, in per cent of the grid, of the grid points with count `k` (`k ≥ 4`: four or
    /// more). The verdicts on the map figures' trends are decided on these numbers.
    pub fn share(&self, k: usize) -> f64 {
        let h = self.histogram();
        let total: usize = h.iter().sum();
        100.0 * h[k.min(4)] as f64 / total.max(1) as f64
    }

    /// What the grid resolves of the share of count `k` (per cent, as [`MapPanel::share`]):
    /// `(lo, hi)`, from the points of count `k` whose four neighbours all have it (the region's
    /// interior at this resolution) to those of count `k` or with a neighbour of count `k` (its
    /// closure). The region's share of the plane lies in this bracket up to features smaller
    /// than a grid step; a change of share smaller than its width is not resolved by the grid.
    pub fn share_bracket(&self, k: usize) -> (f64, f64) {
        let (nx, ny) = (self.x.grid.count, self.y.grid.count);
        let is_k = |ix: usize, iy: usize| (self.count(ix, iy) as usize).min(4) == k.min(4);
        let (mut inner, mut closure) = (0usize, 0usize);
        for iy in 0..ny {
            for ix in 0..nx {
                let mut neighbours = Vec::with_capacity(4);
                if ix > 0 {
                    neighbours.push((ix - 1, iy));
                }
                if ix + 1 < nx {
                    neighbours.push((ix + 1, iy));
                }
                if iy > 0 {
                    neighbours.push((ix, iy - 1));
                }
                if iy + 1 < ny {
                    neighbours.push((ix, iy + 1));
                }
                let here = is_k(ix, iy);
                if here && neighbours.iter().all(|&(a, b)| is_k(a, b)) {
                    inner += 1;
                }
                if here || neighbours.iter().any(|&(a, b)| is_k(a, b)) {
                    closure += 1;
                }
            }
        }
        let total = (nx * ny).max(1) as f64;
        (100.0 * inner as f64 / total, 100.0 * closure as f64 / total)
    }

    /// The grid-index bounding box `((ix0, ix1), (iy0, iy1))`, inclusive, of the grid points
    /// with count `k` (`k ≥ 4`: four or more); `None` when there are none.
    pub fn bounding_box(&self, k: u8) -> Option<GridBox> {
        let nx = self.x.grid.count;
        let mut b: Option<((usize, usize), (usize, usize))> = None;
        for (i, &c) in self.counts.iter().enumerate() {
            if c.min(4) != k.min(4) {
                continue;
            }
            let (ix, iy) = (i % nx, i / nx);
            b = Some(match b {
                None => ((ix, ix), (iy, iy)),
                Some(((x0, x1), (y0, y1))) => ((x0.min(ix), x1.max(ix)), (y0.min(iy), y1.max(iy))),
            });
        }
        b
    }

    /// The thin regions of the map: connected sets of grid points of one count (4-neighbour
    /// connectivity) at least `min_cells` points large whose bounding box spans at most
    /// `thin` of the grid along one axis but more than that along the other — a feature a
    /// picture at the plane's scale shows as a line (Fig. 12 (a): the bimodal band at
    /// r ≳ 0.998). Each as (count, bounding box as [`MapPanel::bounding_box`]), largest first.
    pub fn slivers(&self, min_cells: usize, thin: f64) -> Vec<(u8, GridBox)> {
        let (nx, ny) = (self.x.grid.count, self.y.grid.count);
        let mut seen = vec![false; self.counts.len()];
        let mut out = Vec::new();
        for start in 0..self.counts.len() {
            if seen[start] {
                continue;
            }
            let k = self.counts[start];
            let (mut size, mut stack) = (0usize, vec![start]);
            seen[start] = true;
            let (mut x0, mut x1, mut y0, mut y1) = (nx, 0, ny, 0);
            while let Some(i) = stack.pop() {
                size += 1;
                let (ix, iy) = (i % nx, i / nx);
                (x0, x1, y0, y1) = (x0.min(ix), x1.max(ix), y0.min(iy), y1.max(iy));
                let mut push = |j: usize| {
                    if !seen[j] && self.counts[j] == k {
                        seen[j] = true;
                        stack.push(j);
                    }
                };
                if ix > 0 {
                    push(i - 1);
                }
                if ix + 1 < nx {
                    push(i + 1);
                }
                if iy > 0 {
                    push(i - nx);
                }
                if iy + 1 < ny {
                    push(i + nx);
                }
            }
            let (wx, wy) = (
                (x1 - x0 + 1) as f64 / nx as f64,
                (y1 - y0 + 1) as f64 / ny as f64,
            );
            if size >= min_cells && (wx <= thin) != (wy <= thin) {
                out.push((size, k, ((x0, x1), (y0, y1))));
            }
        }
        out.sort_by_key(|c| std::cmp::Reverse(c.0));
        out.into_iter().map(|(_, k, b)| (k, b)).collect()
    }
}

/// A box of grid indices `((ix0, ix1), (iy0, iy1))`, inclusive.
pub type GridBox = ((usize, usize), (usize, usize));

/// The paper's names of the saddle-node lines (Sec. 3: "L1 … the saddle-node bifurcation of
/// the outer limit cycle …, L3 … of the inner limit cycle"): at the middle of each curve, the
/// double root is the outermost positive root of f (L1), the innermost (L3) or between (L2).
/// Every curve is named (a fold curve the theory cannot be evaluated on is left out).
fn name_folds(base: &Params, plane: &Plane, folds: &Folds) -> Vec<(usize, String)> {
    let mut names = Vec::new();
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
        names.push((i, name.to_string()));
    }
    names
}

/// Grid points per axis: quick or paper quality.
pub fn resolution(ctx: &FigureOptions) -> usize {
    if ctx.quick {
        81
    } else {
        401
    }
}

/// Classify a plane and trace its folds (and the printed Eq. 37 curves when asked).
#[allow(clippy::too_many_arguments)]
pub fn compute_panel(
    ctx: &FigureOptions,
    monitor: &dyn Monitor,
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
    monitor.check()?;
    let map = classify(&plane, what, &|done, total| {
        monitor.progress(done as u64, total as u64)
    });
    monitor.check()?;
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
    /// What the figure shows, shared parameters, variant.
    pub caption: Caption,
    /// Notes of the data tables (counts, curves, cusps per panel).
    pub notes: Vec<String>,
    /// The panels.
    pub panels: Vec<MapPanel>,
}

/// Assemble a map figure from computed panels: the heading, and the CSV header with the
/// notes and each panel's counts, curves and cusps.
pub fn map_figure(
    ctx: &FigureOptions,
    (n, title): (u32, &str),
    subtitle: String,
    mut notes: Vec<String>,
    panels: Vec<MapPanel>,
) -> MapFigure {
    for p in &panels {
        notes.extend(panel_notes(p));
    }
    let mut header = table_notes(n, title, ctx, &notes);
    for p in &panels {
        header.push(format!(
            "panel {}: x = {}, y = {}",
            p.label, p.x.grid.key, p.y.grid.key
        ));
    }
    MapFigure {
        caption: Caption {
            title: format!("Fig. {n}: {title}"),
            lines: vec![subtitle, variant_line(ctx.variant)],
        },
        notes: header,
        panels,
    }
}

impl MapFigure {
    /// Each panel's axes increase with at least two points, its counts hold one value per
    /// grid point (at most [`trirhythm::theory::bifurcation::MAXC`]), its fold curves and
    /// mark are finite and its named folds exist.
    pub fn validate(&self) -> crate::validate::Valid {
        use crate::validate::{axis, finite, invalid, len};
        for (i, p) in self.panels.iter().enumerate() {
            let f = format!("panels[{i}]");
            axis(&format!("{f}.x.grid"), &p.x.grid)?;
            axis(&format!("{f}.y.grid"), &p.y.grid)?;
            for (name, scale) in [("x", p.x.scale), ("y", p.y.scale)] {
                if !(scale.is_finite() && scale > 0.0) {
                    return invalid(format!("{f}.{name}.scale"), format!("{scale} is not > 0"));
                }
            }
            let points = p.x.grid.count * p.y.grid.count;
            let of = format!("{} × {} grid points", p.x.grid.count, p.y.grid.count);
            len(&format!("{f}.counts"), p.counts.len(), points, &of)?;
            let max = trirhythm::theory::bifurcation::MAXC;
            if let Some(j) = p.counts.iter().position(|&c| c as usize > max) {
                return invalid(
                    format!("{f}.counts[{j}]"),
                    format!("{} exceeds the most possible, {max}", p.counts[j]),
                );
            }
            for (name, folds) in [("folds", Some(&p.folds)), ("printed", p.printed.as_ref())] {
                for (c, curve) in folds.into_iter().flat_map(|f| f.curves.iter()).enumerate() {
                    let xs: Vec<f64> = curve
                        .points
                        .iter()
                        .flat_map(|q| [q.x, q.y, q.amplitude])
                        .collect();
                    finite(&format!("{f}.{name}.curves[{c}].points"), &xs)?;
                }
            }
            if let Some((x, y, _)) = &p.mark {
                finite(&format!("{f}.mark"), &[*x, *y])?;
            }
            for (j, (c, _)) in p.fold_names.iter().enumerate() {
                if *c >= p.folds.curves.len() {
                    return invalid(
                        format!("{f}.fold_names[{j}]"),
                        format!("curve {c} of {} curves", p.folds.curves.len()),
                    );
                }
            }
        }
        Ok(())
    }

    /// The figure's tables: `panel,x,y,count` over every grid point (row by row), and
    /// `panel,curve,system,x,y,amplitude` over the fold curves (and the printed Eq. 36–37
    /// curves where traced) as `_folds`.
    pub fn tables(&self) -> Vec<Table> {
        let mut counts = Table::new(&self.notes, &["panel", "x", "y", "count"]);
        for p in &self.panels {
            for iy in 0..p.y.grid.count {
                let y = num(p.y.grid.value(iy));
                for ix in 0..p.x.grid.count {
                    counts.row([
                        p.label.clone(),
                        num(p.x.grid.value(ix)),
                        y.clone(),
                        p.count(ix, iy).to_string(),
                    ]);
                }
            }
        }
        let mut folds = Table::new(
            &self.notes,
            &["panel", "curve", "system", "x", "y", "amplitude"],
        )
        .named("_folds");
        for p in &self.panels {
            let mut sets = vec![&p.folds];
            if let Some(pr) = &p.printed {
                sets.push(pr);
            }
            folds
                .rows
                .extend(fold_rows(std::slice::from_ref(&p.label), &sets));
        }
        vec![counts, folds]
    }
}

/// Rows `prefix…,curve,system,x,y,amplitude` for every curve of `sets`, the curves numbered
/// on across the sets.
pub fn fold_rows(prefix: &[String], sets: &[&Folds]) -> Vec<Vec<String>> {
    let mut rows = Vec::new();
    let mut i = 0;
    for f in sets {
        for c in &f.curves {
            for p in &c.points {
                let mut row = prefix.to_vec();
                row.extend([
                    i.to_string(),
                    c.system.name().to_string(),
                    num(p.x),
                    num(p.y),
                    num(p.amplitude),
                ]);
                rows.push(row);
            }
            i += 1;
        }
    }
    rows
}

/// A figure of four (γ0, δ0) rhythmicity panels, one per value of `key` (Figs 3 and 6): the
/// preset's parameters with `key` set to each value, folds traced, the paper's point marked.
pub fn gamma_delta_family(
    ctx: &FigureOptions,
    monitor: &dyn Monitor,
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
            monitor,
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
    Ok(map_figure(ctx, (number, title), subtitle, notes, panels))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn panel(nx: usize, counts: Vec<u8>) -> MapPanel {
        let ny = counts.len() / nx;
        let axis = |key: &str, count| PanelAxis {
            grid: Axis {
                key: key.into(),
                start: 0.0,
                stop: 1.0,
                count,
            },
            label: key.into(),
            scale: 1.0,
        };
        MapPanel {
            label: "a".into(),
            caption: String::new(),
            params: String::new(),
            what: What::Rhythmicity,
            x: axis("gamma0", nx),
            y: axis("delta0", ny),
            counts,
            folds: Folds {
                curves: Vec::new(),
                cusps: Vec::new(),
                seeds: 0,
                unlocated: 0,
            },
            printed: None,
            mark: None,
            fold_names: Vec::new(),
        }
    }

    #[test]
    fn a_thin_band_is_a_sliver_and_a_wide_region_is_not() {
        // 40 × 40: count 3 everywhere, a band of count 2 one row high and 20 wide at the top,
        // a 15 × 15 block of count 1
        let mut p = panel(40, vec![3u8; 1600]);
        for ix in 5..25 {
            p.counts[39 * 40 + ix] = 2;
        }
        for iy in 0..15 {
            for ix in 0..15 {
                p.counts[iy * 40 + ix] = 1;
            }
        }
        assert_eq!(p.slivers(10, 0.05), vec![(2, ((5, 24), (39, 39)))]);
        // a band too small to matter is left out
        assert!(p.slivers(21, 0.05).is_empty());
    }

    #[test]
    fn shares_and_the_box_of_a_count_come_from_the_grid() {
        // 4 × 3 grid, row-major: two cells with 3 at (1, 1) and (2, 2), one with 5 (≥ 4)
        let p = panel(4, vec![1, 1, 2, 2, 1, 3, 2, 2, 1, 2, 3, 5]);
        assert_eq!(p.share(1), 100.0 * 4.0 / 12.0);
        assert_eq!(p.share(3), 100.0 * 2.0 / 12.0);
        assert_eq!(p.share(4), 100.0 / 12.0);
        assert_eq!(p.share(0), 0.0);
        assert_eq!(p.bounding_box(3), Some(((1, 2), (1, 2))));
        assert_eq!(p.bounding_box(7), Some(((3, 3), (2, 2))));
        assert_eq!(p.bounding_box(0), None);
    }

    #[test]
    fn a_share_is_bracketed_by_the_region_s_interior_and_closure_on_the_grid() {
        // 5 × 5, a 3 × 3 block of count 3 in the middle of count 2
        let mut counts = vec![2u8; 25];
        for iy in 1..4 {
            for ix in 1..4 {
                counts[iy * 5 + ix] = 3;
            }
        }
        let p = panel(5, counts);
        let (lo, hi) = p.share_bracket(3);
        // interior: the centre point only; closure: the block and its 12 edge neighbours
        assert_eq!(lo, 100.0 / 25.0);
        assert_eq!(hi, 100.0 * 21.0 / 25.0);
        assert!(lo <= p.share(3) && p.share(3) <= hi);
        // a count absent from the grid: an empty bracket at 0
        assert_eq!(p.share_bracket(1), (0.0, 0.0));
        // a count everywhere: the whole grid, exactly
        let all = panel(5, vec![2u8; 25]);
        assert_eq!(all.share_bracket(2), (100.0, 100.0));
    }
}
