//! The picture of `map --simulate`: the theory's count of the modes of P(A) on the left, the
//! simulated count on the right, over the same grid and axes.
//!
//! # Equation
//! Left, the number of maxima of the averaged stationary P(A) (Eq. 27: the stable roots of
//! h = A·m1, Eq. 26); right, the number of modes of the amplitude density of an ensemble of
//! Eq. (1) at the same point, counted at z = 3 ([`trirhythm::analysis::simulated_map`]).
//!
//! # Method
//! Each panel is a [`MapPanel`] of the simulated map's grid ([`SimulatedMapPicture::new`]),
//! drawn by the map figures' own [`draw_panel`] and coloured as the paper's maps are
//! ([`count_colour`](super::mapfig::count_colour): unimodal blue, bimodal green, trimodal
//! black), with no inset (the marks would fall on it). On the simulated panel every point
//! whose verdict is not `agree` carries a mark at the centre of its cell as drawn, black on a
//! white halo so that it reads on every colour and in greyscale: × `disagree` (the theory's
//! count outside the simulated range), ○ `uncertain` (inside a range of several counts),
//! ● not stationary, □ more than 1 % of the samples beyond the histogram (the last two not
//! compared). The legend strip below the panels names the counts met and the marks drawn;
//! under it the caption states the rule (z = 3, the range at z = 4 … 2), the sizes (points,
//! paths, t_end, burn-in, Δt, seed), the parameters and the tally of verdicts.
//!
//! # Reference
//! The rule and the verdicts: [`trirhythm::analysis::simulated_map`] and docs/statistics.md;
//! the maps' drawing: [`super::mapfig`]; the print rules: [`crate::render::plot`].
//!
//! # Tests
//! `tests/maps.rs`: `map --simulate --png/--svg` on a 2 × 2 grid writes a PNG 2100 pixels
//! wide (7 in at 300 dpi) of the SVG's height at that scale, signed, with both panels' titles,
//! the rule's range and the CSV's tally in the SVG, and a mark's legend entry exactly where a
//! point has that verdict; a second run replaces the pictures the first drew. Five bad
//! destinations (a directory, a missing directory, the wrong extension twice, a file this
//! tool did not write) are refused before the work starts, the file left as it was.
//! `tests/pictures.rs`: a 6 × 6 map's SVG passes the figures' layout checks (no text over
//! text or data, four ticks per axis, titles of one line, panels 2.2 in wide or more). Unit
//! tests below: the caption's wrapping, one mark per verdict.

use super::mapfig::{clear_ends, draw_panel, legend, Insets, MapChart, PANEL};
use crate::render::plot::{
    draw_lines, font_px, pe, px, pxi, rich_width, stroke, Backend, Marker, Symbol, LABEL,
};
use anyhow::Result;
use plotters::prelude::*;
use trirhythm::analysis::simulated_map::{Agreement, SimulatedMap};
use trirhythm::model::Params;
use trirhythm::theory::bifurcation::{Axis, Folds, What};
use trirhythm_paper::maps::{MapFigure, MapPanel, PanelAxis};
use trirhythm_paper::notes::{params_text, symbol, variant_line, Caption};

/// How the map was simulated, as the caption states it.
pub struct Sizes {
    /// Paths per point.
    pub paths: usize,
    /// Each path's recorded window.
    pub t_end: f64,
    /// Time discarded at the start of each path.
    pub burn_in: f64,
    /// The step Δt.
    pub dt: f64,
    /// The map's seed.
    pub seed: u64,
}

/// The two panels of a simulated map, the marks on the simulated one and the caption drawn
/// under them.
pub struct SimulatedMapPicture {
    fig: MapFigure,
    /// (x, y, verdict) of every point whose verdict is not `agree`.
    marks: Vec<(f64, f64, Agreement)>,
}

/// The mark of a verdict on the simulated panel and in the legend (none for `agree`).
fn mark_of(a: Agreement) -> Option<(Symbol, &'static str)> {
    match a {
        Agreement::Agree => None,
        Agreement::Disagree => Some((Symbol::Cross(BLACK), "disagree (theory outside the range)")),
        Agreement::Uncertain => Some((Symbol::Ring(BLACK), "uncertain (range of several counts)")),
        Agreement::NonStationary => Some((Symbol::Dot(BLACK), "not stationary (not compared)")),
        Agreement::OutsideRange => Some((
            Symbol::Shape(Marker::Square, BLACK, false),
            "over 1 % beyond the histogram (not compared)",
        )),
    }
}

impl SimulatedMapPicture {
    /// The picture of `map` of the plane whose base is `base`, simulated as `sizes` says.
    pub fn new(map: &SimulatedMap, base: &Params, sizes: &Sizes) -> Self {
        // (each "key = value" kept on one line of the caption)
        let params = params_text(base, &[map.x.key.as_str(), map.y.key.as_str()])
            .replace(" = ", "\u{a0}=\u{a0}");
        let axis = |a: &Axis| PanelAxis {
            grid: a.clone(),
            label: symbol(&a.key).to_string(),
            scale: 1.0,
        };
        let count = |c: usize| c.min(u8::MAX as usize) as u8;
        let panel = |label: &str, caption: &str, counts: Vec<u8>| MapPanel {
            label: label.into(),
            caption: caption.into(),
            params: params.clone(),
            what: What::Modes,
            x: axis(&map.x),
            y: axis(&map.y),
            counts,
            folds: Folds::default(),
            printed: None,
            mark: None,
            fold_names: Vec::new(),
        };
        let rule = &map.rule;
        let t = &map.tally;
        let theory = panel(
            "a",
            "theory (Eq. 27)",
            map.points.iter().map(|p| count(p.theory)).collect(),
        );
        let simulated = panel(
            "b",
            &format!("simulated (Eq. 1), z = {}", rule.z),
            map.points
                .iter()
                .map(|p| count(p.simulated.count))
                .collect(),
        );
        let lines =
            vec![
                format!(
                "(a) maxima of the averaged P(A) (Eq. 27); (b) modes of the simulated P(A), an \
                 ensemble of Eq. (1) at every point; colour: the number of modes; {}.",
                variant_line(map.variant)
            ),
                format!(
                "Rule: a mode dips more than z = {} combined standard errors to its neighbouring \
                 modes or the ends; the range low … high is the count at z = {} … z = {}; agree: \
                 low = high = the theory's count (unmarked points agree).",
                rule.z, rule.z_strict, rule.z_lenient
            ),
                format!(
                "Sizes: {} × {} points, {} paths each, t_end = {} after a burn-in of {}, Δt = {}, \
                 seed {} (each point's derived from it); {params}.",
                map.x.count, map.y.count, sizes.paths, sizes.t_end, sizes.burn_in, sizes.dt,
                sizes.seed
            ),
                format!(
                    "Tally: agree {}, disagree {}, uncertain {}, non-stationary {}, outside the \
                 range {}.",
                    t.agree, t.disagree, t.uncertain, t.non_stationary, t.outside_range
                ),
            ];
        let fig = MapFigure {
            caption: Caption {
                title: "Modes of P(A): the theory (Eq. 27) beside the simulation (Eq. 1)".into(),
                lines,
            },
            notes: Vec::new(),
            panels: vec![theory, simulated],
        };
        let marks = map
            .points
            .iter()
            .filter(|p| p.agreement != Agreement::Agree)
            .map(|p| (p.x, p.y, p.agreement))
            .collect();
        SimulatedMapPicture { fig, marks }
    }

    /// The legend: the counts met (as the map figures name them) and the marks drawn.
    fn legend(&self) -> crate::render::plot::LegendStrip {
        let mut strip = legend(&self.fig, Insets::Off);
        for a in [
            Agreement::Disagree,
            Agreement::Uncertain,
            Agreement::NonStationary,
            Agreement::OutsideRange,
        ] {
            if let Some((s, text)) = mark_of(a).filter(|_| self.marks.iter().any(|m| m.2 == a)) {
                strip.entries.push((s, text.to_string()));
            }
        }
        strip
    }

    /// The caption's lines wrapped to `width` pixels.
    fn caption(&self, width: u32) -> Vec<String> {
        let room = width.saturating_sub(2 * px(12));
        self.fig
            .caption
            .lines
            .iter()
            .flat_map(|l| wrap(l, room))
            .collect()
    }
}

/// `text` in lines of at most `width` pixels at the caption's size, broken between words (a
/// word wider than a line stands alone).
fn wrap(text: &str, width: u32) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    let mut line = String::new();
    for word in text.split(' ') {
        let longer = if line.is_empty() {
            word.to_string()
        } else {
            format!("{line} {word}")
        };
        if !line.is_empty() && rich_width(&longer, LABEL) > width {
            lines.push(std::mem::replace(&mut line, word.to_string()));
        } else {
            line = longer;
        }
    }
    lines.push(line);
    lines
}

/// The height of a caption line.
fn caption_line() -> u32 {
    font_px(LABEL) * 5 / 4
}

/// Draw the marks of the points that do not agree on the simulated panel's chart: black on a
/// white halo, each at the centre of its cell as drawn (a cell on the grid's edge is half a
/// cell, inside the axes: no mark on a spine or a tick), at most half such a cell across.
fn draw_marks<DB: Backend>(
    c: &mut MapChart<'_, DB>,
    map: &MapPanel,
    marks: &[(f64, f64, Agreement)],
) -> Result<()> {
    let (gx, gy) = (&map.x.grid, &map.y.grid);
    let a = c.backend_coord(&(gx.value(0), gy.value(0)));
    let b = c.backend_coord(&(gx.value(1), gy.value(1)));
    let cell = (a.0 - b.0).abs().min((a.1 - b.1).abs());
    let r = pxi(7).min(cell / 4 - 2).max(2);
    let (halo, line) = (stroke(4), stroke(2));
    // the centre of the cell of value v on axis g, as drawn
    let centre = |v: f64, g: &Axis| {
        let h = (g.stop - g.start) / (g.count - 1) as f64 / 2.0;
        let (lo, hi) = (g.start.min(g.stop), g.start.max(g.stop));
        ((v - h).clamp(lo, hi) + (v + h).clamp(lo, hi)) / 2.0
    };
    for &(x, y, verdict) in marks {
        let at = EmptyElement::at((centre(x, gx), centre(y, gy)));
        match verdict {
            Agreement::Agree => continue,
            Agreement::Disagree => c.draw_series(std::iter::once(
                at + Cross::new((0, 0), r as u32, WHITE.stroke_width(halo))
                    + Cross::new((0, 0), r as u32, BLACK.stroke_width(line)),
            )),
            Agreement::Uncertain => c.draw_series(std::iter::once(
                at + Circle::new((0, 0), r, WHITE.stroke_width(halo))
                    + Circle::new((0, 0), r, BLACK.stroke_width(line)),
            )),
            Agreement::NonStationary => c.draw_series(std::iter::once(
                at + Circle::new((0, 0), r * 2 / 3 + 2, WHITE.filled())
                    + Circle::new((0, 0), r * 2 / 3, BLACK.filled()),
            )),
            Agreement::OutsideRange => c.draw_series(std::iter::once(
                at + Rectangle::new([(-r, -r), (r, r)], WHITE.stroke_width(halo))
                    + Rectangle::new([(-r, -r), (r, r)], BLACK.stroke_width(line)),
            )),
        }
        .map_err(pe)?;
    }
    Ok(())
}

// Two panels side by side, the legend strip below them, the caption under it.
picture!(SimulatedMapPicture, |self, root| caption self.fig.caption, size {
    let w = 2 * PANEL.0;
    let lines = self.caption(w).len() as u32;
    (w, PANEL.1 + self.legend().height(w) + px(6) + lines * caption_line() + px(8))
}, draw {
    let w = root.dim_in_pixel().0;
    let (panels, rest) = root.split_vertically(PANEL.1);
    let strip_h = self.legend().height(w);
    let (strip, caption) = rest.split_vertically(strip_h);
    let ends = clear_ends(&self.fig, Insets::Off);
    let areas = panels.split_evenly((1, 2));
    draw_panel(&areas[0], &self.fig.panels[0], ends[0], Insets::Off)?;
    let mut c = draw_panel(&areas[1], &self.fig.panels[1], ends[1], Insets::Off)?;
    draw_marks(&mut c, &self.fig.panels[1], &self.marks)?;
    self.legend().draw(&strip)?;
    let lines = self.caption(w).into_iter().map(|l| (l, BLACK));
    draw_lines(&caption, lines, LABEL, caption_line())
});

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wrap_breaks_between_words_within_the_width() {
        let text = "one two three four five six seven eight nine ten";
        let width = rich_width("one two three four", LABEL);
        let lines = wrap(text, width);
        assert_eq!(lines.join(" "), text);
        assert!(lines.len() >= 3, "{lines:?}");
        for l in &lines {
            assert!(rich_width(l, LABEL) <= width, "{l}");
        }
        assert_eq!(lines[0], "one two three four");
    }

    #[test]
    fn every_verdict_but_agree_has_its_own_mark() {
        let names: Vec<&str> = [
            Agreement::Disagree,
            Agreement::Uncertain,
            Agreement::NonStationary,
            Agreement::OutsideRange,
        ]
        .into_iter()
        .map(|a| mark_of(a).unwrap().1)
        .collect();
        assert_eq!(names.len(), 4);
        assert!(mark_of(Agreement::Agree).is_none());
        for (i, n) in names.iter().enumerate() {
            assert!(!names[..i].contains(n));
        }
    }
}
