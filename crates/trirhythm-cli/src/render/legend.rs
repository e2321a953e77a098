//! Legends drawn outside the plotting areas: the mark of an entry ([`Symbol`]) and a strip of
//! entries wrapped into centred rows below a figure's panels ([`LegendStrip`]), scaled with the
//! canvas like all text ([`super::plot`]).

use super::plot::{
    font_px, pe, px, pxi, rich_text, rich_width, stroke, Backend, SeriesStyle, LABEL,
};
use super::series::{dashed_path, marker, Dash, Marker};
use anyhow::Result;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// The mark of a legend entry.
#[derive(Clone, Copy)]
pub enum Symbol {
    /// A filled square: a region's colour.
    Swatch(RGBColor),
    /// A solid line.
    Line(RGBColor),
    /// A dashed line.
    Dashed(RGBColor),
    /// A dashed line on a wider black dashed underlay (the maps' "Eq. 36-37 as printed").
    Underlaid(RGBColor),
    /// An open circle.
    Ring(RGBColor),
    /// A cross.
    Cross(RGBColor),
    /// A filled circle.
    Dot(RGBColor),
    /// A solid line with a filled dot on it: a line marked with dots at its points.
    DottedLine(RGBColor),
    /// A series' line (its colour and dash) with its marker, as [`draw_line`] and
    /// [`draw_markers`] draw it.
    Series(SeriesStyle),
    /// A character a panel title carries (`†`), explained by the entry.
    Mark(char),
    /// A series' marker on a vertical error bar: points with standard errors.
    Points(SeriesStyle),
    /// A square of the first colour outlined in the second: a box drawn on a map.
    Framed(RGBColor, RGBColor),
    /// A marker alone (no line), filled in its colour (`true`) or open (white inside), as
    /// drawn by the figures that mark points with [`outline`].
    Shape(Marker, RGBColor, bool),
}

/// The outline of a marker `shape` of radius `r` around the origin (pixels), closed.
pub fn outline(shape: Marker, r: i32) -> Vec<(i32, i32)> {
    let q = r + r / 4;
    match shape {
        Marker::Square => vec![(-r, -r), (r, -r), (r, r), (-r, r), (-r, -r)],
        Marker::Triangle => vec![(0, -q), (q, r * 3 / 4), (-q, r * 3 / 4), (0, -q)],
        Marker::Diamond => vec![(0, -q), (q, 0), (0, q), (-q, 0), (0, -q)],
        _ => (0..=24)
            .map(|k| {
                let a = std::f64::consts::TAU * k as f64 / 24.0;
                (
                    (r as f64 * a.cos()).round() as i32,
                    (r as f64 * a.sin()).round() as i32,
                )
            })
            .collect(),
    }
}

impl Symbol {
    /// Draw the mark centred at `m` (a mark [`px`]`(20)` wide).
    pub fn draw<DB: Backend>(&self, area: &DrawingArea<DB, Shift>, m: (i32, i32)) -> Result<()> {
        let (h, w3, w2) = (pxi(10), stroke(3), stroke(2));
        match *self {
            Symbol::Swatch(c) => area
                .draw(&Rectangle::new(
                    [(m.0 - pxi(8), m.1 - pxi(8)), (m.0 + pxi(8), m.1 + pxi(8))],
                    c.filled(),
                ))
                .map_err(pe),
            Symbol::Framed(fill, line) => {
                let corners = [(m.0 - pxi(8), m.1 - pxi(8)), (m.0 + pxi(8), m.1 + pxi(8))];
                area.draw(&Rectangle::new(corners, fill.filled()))
                    .map_err(pe)?;
                // (a white square is outlined at its edge: white on the white page is not
                // seen otherwise)
                let k = if fill == WHITE { 0 } else { pxi(3) };
                let inner = [
                    (corners[0].0 + k, corners[0].1 + k),
                    (corners[1].0 - k, corners[1].1 - k),
                ];
                area.draw(&Rectangle::new(inner, line.stroke_width(w2)))
                    .map_err(pe)
            }
            Symbol::Line(c) => area
                .draw(&PathElement::new(
                    [(m.0 - h, m.1), (m.0 + h, m.1)],
                    c.stroke_width(w3),
                ))
                .map_err(pe),
            Symbol::Dashed(c) => {
                dashed_path(area, &[(m.0 - h, m.1), (m.0 + h, m.1)], Dash::Dashed, c, w3)
            }
            Symbol::Underlaid(c) => {
                let line = [(m.0 - h, m.1), (m.0 + h, m.1)];
                dashed_path(area, &line, Dash::Dashed, BLACK, stroke(4))?;
                dashed_path(area, &line, Dash::Dashed, c, w2)
            }
            Symbol::Ring(c) => area
                .draw(&Circle::new(m, pxi(6) as u32, c.stroke_width(w2)))
                .map_err(pe),
            Symbol::Cross(c) => area
                .draw(&Cross::new(m, pxi(7) as u32, c.stroke_width(w2)))
                .map_err(pe),
            Symbol::Points(s) => {
                area.draw(&PathElement::new(
                    [(m.0, m.1 - pxi(10)), (m.0, m.1 + pxi(10))],
                    s.colour.stroke_width(stroke(1)),
                ))
                .map_err(pe)?;
                marker(area, m, s.marker, s.colour)
            }
            Symbol::Shape(shape, c, filled) => {
                let ring: Vec<(i32, i32)> = outline(shape, pxi(6))
                    .into_iter()
                    .map(|(x, y)| (m.0 + x, m.1 + y))
                    .collect();
                let fill = if filled { c } else { WHITE };
                area.draw(&Polygon::new(ring.clone(), fill.filled()))
                    .map_err(pe)?;
                area.draw(&PathElement::new(ring, c.stroke_width(w2)))
                    .map_err(pe)
            }
            Symbol::Dot(c) => area
                .draw(&Circle::new(m, pxi(6) as u32, c.filled()))
                .map_err(pe),
            Symbol::DottedLine(c) => {
                area.draw(&PathElement::new(
                    [(m.0 - h, m.1), (m.0 + h, m.1)],
                    c.stroke_width(w3),
                ))
                .map_err(pe)?;
                area.draw(&Circle::new(m, pxi(5) as u32, c.filled()))
                    .map_err(pe)
            }
            Symbol::Series(s) => {
                let half = pxi(14);
                dashed_path(
                    area,
                    &[(m.0 - half, m.1), (m.0 + half, m.1)],
                    s.dash,
                    s.colour,
                    w3,
                )?;
                marker(area, m, s.marker, s.colour)
            }
            Symbol::Mark(c) => crate::render::plot::rich_text(
                area,
                &c.to_string(),
                m,
                plotters::style::text_anchor::Pos::new(
                    plotters::style::text_anchor::HPos::Center,
                    plotters::style::text_anchor::VPos::Center,
                ),
                crate::render::plot::CAPTION,
                RGBColor(0, 0, 0),
                false,
            ),
        }
    }
}

/// A legend drawn in its own strip outside the plotting areas (below the panels), one for a
/// whole figure: entries side by side, wrapped into centred rows.
pub struct LegendStrip {
    /// Mark and text of each entry (the text may carry subscripts, see [`rich_runs`]).
    pub entries: Vec<(Symbol, String)>,
}

/// Legend strip layout at scale 1: row height, padding, width of an entry's mark and the
/// gap before its text, space between entries.
const LEGEND_ROW: u32 = 26;
const LEGEND_PAD: u32 = 8;
const LEGEND_MARK: u32 = 36;
const LEGEND_GAP: u32 = 26;

impl LegendStrip {
    /// An entry's width in pixels: the mark and the text as laid out by the embedded font
    /// (the same for every backend).
    fn entry_width(text: &str) -> u32 {
        px(LEGEND_MARK) + rich_width(text, LABEL)
    }

    fn row_height() -> u32 {
        px(LEGEND_ROW).max(font_px(LABEL) * 4 / 3)
    }

    /// The entries' indices per row, for a strip `width` pixels wide.
    fn rows(&self, width: u32) -> Vec<Vec<usize>> {
        let max = width.saturating_sub(2 * px(LEGEND_PAD));
        let gap = px(LEGEND_GAP);
        let mut rows: Vec<Vec<usize>> = Vec::new();
        let mut used = 0;
        for (i, (_, text)) in self.entries.iter().enumerate() {
            let w = Self::entry_width(text);
            match rows.last_mut() {
                Some(row) if used + gap + w <= max => {
                    row.push(i);
                    used += gap + w;
                }
                _ => {
                    rows.push(vec![i]);
                    used = w;
                }
            }
        }
        rows
    }

    /// Height of the strip for a figure `width` pixels wide (0 without entries), at the
    /// current scale.
    pub fn height(&self, width: u32) -> u32 {
        match self.rows(width).len() as u32 {
            0 => 0,
            // the frame's top margin, and as much below it
            n => 2 * px(LEGEND_PAD) + n * Self::row_height() + 2 * px(4),
        }
    }

    /// Draw the entries, framed, centred in `area`.
    pub fn draw<DB: Backend>(&self, area: &DrawingArea<DB, Shift>) -> Result<()> {
        let (width, _) = area.dim_in_pixel();
        let rows = self.rows(width);
        let (pad, gap, row_h) = (px(LEGEND_PAD), px(LEGEND_GAP), Self::row_height());
        let row_width = |row: &Vec<usize>| -> u32 {
            row.iter()
                .map(|&i| Self::entry_width(&self.entries[i].1))
                .sum::<u32>()
                + gap * (row.len() as u32).saturating_sub(1)
        };
        let Some(widest) = rows.iter().map(row_width).max() else {
            return Ok(());
        };
        let left = (width.saturating_sub(widest) / 2) as i32;
        let top = pxi(4);
        let frame = [
            (left - pad as i32, top),
            (
                left + (widest + pad) as i32,
                top + (2 * pad + rows.len() as u32 * row_h) as i32,
            ),
        ];
        area.draw(&Rectangle::new(frame, RGBColor(150, 150, 150)))
            .map_err(pe)?;
        for (k, row) in rows.iter().enumerate() {
            let y = top + (pad + k as u32 * row_h + row_h / 2) as i32;
            let mut x = left + (widest - row_width(row)) as i32 / 2;
            for &i in row {
                let (symbol, text) = &self.entries[i];
                symbol.draw(area, (x + pxi(14), y))?;
                rich_text(
                    area,
                    text,
                    (x + px(LEGEND_MARK) as i32, y),
                    Pos::new(HPos::Left, VPos::Center),
                    LABEL,
                    BLACK,
                    false,
                )?;
                x += (Self::entry_width(text) + gap) as i32;
            }
        }
        Ok(())
    }
}
