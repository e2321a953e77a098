//! Pictures: an embedded font, PNG + SVG output of one drawing, chart helpers, colours.
//!
//! A figure implements [`Picture`] once, generically over the plotters backend, and
//! [`save`] renders it to both formats through temporary files and renames. Every picture
//! states on itself what it shows: [`save`] draws its [`Heading`] (title, parameters, formula
//! variant, the values chosen where the paper is silent) above it.
//!
//! Text: every font size is even. The bitmap text renderer places a glyph at
//! `(size/2 + top) as i32`, which truncates toward zero; with an odd size the half pixel
//! rounds digits down and a decimal point up, so "0.04" printed as "0·04".
//! SVG: the same DejaVu Sans the PNGs use is embedded in each SVG as a web font
//! ([`embed_font`]), so the two render alike on any machine.

use crate::io::{write_atomic, Temporary};
use anyhow::{anyhow, Context, Result};
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use serde::{Deserialize, Serialize};
use std::ops::Range;
use std::path::{Path, PathBuf};
use std::sync::Once;

/// The font family every label uses (DejaVu Sans, embedded).
pub const FONT: &str = "sans-serif";

static FONTS: Once = Once::new();

fn init_fonts() {
    FONTS.call_once(|| {
        let reg = |style, bytes| {
            plotters::style::register_font(FONT, style, bytes)
                .map_err(|_| ())
                .expect("embedded font parses")
        };
        reg(FontStyle::Normal, dejavu::sans::regular());
        reg(FontStyle::Bold, dejavu::sans::bold());
        reg(FontStyle::Italic, dejavu::sans::oblique());
        reg(FontStyle::Oblique, dejavu::sans::oblique());
    });
}

/// What a picture says about itself, drawn above it: a title, then lines giving the
/// parameters, the formula variant and the choices the project made.
#[derive(Clone, Serialize, Deserialize)]
pub struct Heading {
    /// "Fig. N: what it shows".
    pub title: String,
    /// Parameters, variant, choices (wrapped to the picture's width).
    pub lines: Vec<String>,
    /// The verdicts on the paper's claims that rest on the figure, drawn below the lines in
    /// the verdict's colour.
    pub verdicts: Vec<VerdictLine>,
}

/// One verdict on a claim, as drawn on a picture.
#[derive(Clone, Serialize, Deserialize)]
pub struct VerdictLine {
    /// `confirmed`, `refuted` or `undetermined` (sets the colour).
    pub tag: String,
    /// The line: the claim, the verdict, the deciding numbers.
    pub text: String,
}

impl VerdictLine {
    /// The colour of a verdict (Okabe–Ito: blue, vermillion, and a dark grey).
    fn colour(&self) -> RGBColor {
        match self.tag.as_str() {
            "confirmed" => RGBColor(0, 114, 178),
            "refuted" => RGBColor(213, 94, 0),
            _ => RGBColor(90, 90, 90),
        }
    }
}

const TITLE_SIZE: u32 = 20;
const LINE_SIZE: u32 = 14;
const LINE_HEIGHT: u32 = 19;

impl Heading {
    /// The lines, then the verdicts, wrapped at word boundaries to `width` pixels, each
    /// with its colour.
    fn wrapped(&self, width: u32) -> Vec<(String, RGBColor)> {
        let plain = RGBColor(40, 40, 40);
        let all = self.lines.iter().map(|l| (l.clone(), plain)).chain(
            self.verdicts
                .iter()
                .map(|v| (format!("Verdict {}", v.text), v.colour())),
        );
        all.flat_map(|(line, colour)| wrap(&line, width).into_iter().map(move |l| (l, colour)))
            .collect()
    }

    fn height(&self, width: u32) -> u32 {
        14 + TITLE_SIZE + 8 + LINE_HEIGHT * self.wrapped(width).len() as u32
    }

    fn draw<DB: Backend>(&self, area: &DrawingArea<DB, Shift>) -> Result<()> {
        let width = area.dim_in_pixel().0;
        area.draw(&Text::new(
            self.title.clone(),
            (12, 8),
            (FONT, TITLE_SIZE).into_font().color(&BLACK),
        ))
        .map_err(pe)?;
        for (i, (line, colour)) in self.wrapped(width).into_iter().enumerate() {
            let y = (14 + TITLE_SIZE + LINE_HEIGHT * i as u32) as i32;
            area.draw(&Text::new(
                line,
                (12, y),
                (FONT, LINE_SIZE).into_font().color(&colour),
            ))
            .map_err(pe)?;
        }
        Ok(())
    }
}

/// `line` wrapped at word boundaries to `width` pixels (continuations indented).
fn wrap(line: &str, width: u32) -> Vec<String> {
    // DejaVu Sans averages ~0.55 em per character
    let max = ((width as f64 - 24.0) / (0.56 * LINE_SIZE as f64)).max(20.0) as usize;
    let mut out = Vec::new();
    let mut cur = String::new();
    for word in line.split(' ') {
        if !cur.is_empty() && cur.chars().count() + 1 + word.chars().count() > max {
            out.push(std::mem::take(&mut cur));
            cur.push_str("    ");
        } else if !cur.is_empty() {
            cur.push(' ');
        }
        cur.push_str(word);
    }
    out.push(cur);
    out
}

/// A plotters backend whose errors `anyhow` can carry (every backend drawn on here).
pub trait Backend: DrawingBackend<ErrorType: 'static> {}

impl<B: DrawingBackend<ErrorType: 'static>> Backend for B {}

/// A drawing that can be rendered on any plotters backend.
pub trait Picture {
    /// Size in pixels of the drawing (the heading is added above it).
    fn size(&self) -> (u32, u32);
    /// What the picture shows, drawn above it.
    fn heading(&self) -> Heading;
    /// Draw on `root` (already filled white).
    fn draw<DB: Backend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()>;
}

/// Render `picture` with its heading and `verdicts` (on the claims resting on it) to
/// `stem.png` and `stem.svg`; returns the paths written.
pub fn save(
    picture: &impl Picture,
    verdicts: Vec<VerdictLine>,
    stem: &Path,
) -> Result<Vec<PathBuf>> {
    init_fonts();
    let (w, h) = picture.size();
    let mut heading = picture.heading();
    heading.verdicts = verdicts;
    let hh = heading.height(w);
    let size = (w, h + hh);
    fn render<DB: Backend>(
        root: DrawingArea<DB, Shift>,
        heading: &Heading,
        hh: u32,
        picture: &impl Picture,
    ) -> Result<()> {
        root.fill(&WHITE).map_err(pe)?;
        let (top, body) = root.split_vertically(hh);
        heading.draw(&top)?;
        picture.draw(&body)?;
        root.present().map_err(pe)
    }
    let png = stem.with_extension("png");
    let reserved = Temporary::reserve(&png)?;
    let tmp = reserved.path().to_path_buf();
    render(
        BitMapBackend::new(&tmp, size).into_drawing_area(),
        &heading,
        hh,
        picture,
    )
    .with_context(|| format!("drawing {}", png.display()))?;
    reserved.commit()?;
    let svg = stem.with_extension("svg");
    let mut text = String::new();
    render(
        SVGBackend::with_string(&mut text, size).into_drawing_area(),
        &heading,
        hh,
        picture,
    )
    .with_context(|| format!("drawing {}", svg.display()))?;
    write_atomic(&svg, embed_font(&text).as_bytes())?;
    Ok(vec![png, svg])
}

/// Embed the DejaVu Sans faces an SVG uses as base64 web fonts (`@font-face`), so that it
/// renders with the font of the PNG rather than whatever `sans-serif` is on the reader's
/// machine. Only the faces the text uses are embedded (regular ≈ 0.9 MB as base64).
pub fn embed_font(svg: &str) -> String {
    use base64::Engine;
    let Some(open_end) = svg
        .find("<svg")
        .and_then(|i| svg[i..].find('>').map(|j| i + j + 1))
    else {
        return svg.to_string();
    };
    let mut faces = String::new();
    let mut face = |bytes: &[u8], weight: &str, style: &str| {
        faces.push_str(&format!(
            "@font-face{{font-family:\"{EMBEDDED_FAMILY}\";font-weight:{weight};font-style:{style};\
             src:url(data:font/ttf;base64,{})format(\"truetype\");}}",
            base64::engine::general_purpose::STANDARD.encode(bytes)
        ));
    };
    face(dejavu::sans::regular(), "normal", "normal");
    if svg.contains("font-weight=\"bold\"") {
        face(dejavu::sans::bold(), "bold", "normal");
    }
    if svg.contains("font-style=\"italic\"") || svg.contains("font-style=\"oblique\"") {
        face(dejavu::sans::oblique(), "normal", "italic");
    }
    let body = svg[open_end..].replace(
        &format!("font-family=\"{FONT}\""),
        &format!("font-family=\"{EMBEDDED_FAMILY}, {FONT}\""),
    );
    format!(
        "{}\n<defs><style>{faces}</style></defs>{body}",
        &svg[..open_end]
    )
}

/// The family name the embedded font is declared under in SVGs.
const EMBEDDED_FAMILY: &str = "DejaVu Sans";

/// Tick labels for an axis over `range`: as many decimals as the tick spacing needs, the
/// same for every tick, no "-0", exponent notation for very large or very small values.
/// (About `ticks` ticks.)
pub fn tick_formatter(range: &Range<f64>, ticks: usize) -> impl Fn(&f64) -> String {
    let span = (range.end - range.start).abs();
    let big = range.start.abs().max(range.end.abs());
    // plotters puts about ten ticks on 1-2-5 steps: the spacing is about span / 10
    let step = span / ticks as f64;
    let decimals = if step > 0.0 {
        (-step.log10().floor()).max(0.0) as usize
    } else {
        0
    };
    let exponent = big >= 1e5 || (big > 0.0 && big < 1e-3);
    move |v: &f64| {
        let v = *v;
        if v.abs() <= span * 1e-9 {
            return "0".into();
        }
        if exponent {
            let s = format!("{v:.2e}");
            // 2.50e-7 → 2.5e-7
            match s.split_once('e') {
                Some((m, e)) if m.contains('.') => {
                    format!("{}e{e}", m.trim_end_matches('0').trim_end_matches('.'))
                }
                _ => s,
            }
        } else {
            format!("{v:.decimals$}")
        }
    }
}

/// A chart in `area` with a caption, axis ranges and axis descriptions, mesh drawn.
pub fn chart<'a, DB: Backend>(
    area: &'a DrawingArea<DB, Shift>,
    caption: &str,
    x: Range<f64>,
    y: Range<f64>,
    x_desc: &str,
    y_desc: &str,
) -> Result<ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>> {
    framed(area, caption, (x, y), (x_desc, y_desc), ChartSize::Panel)
}

/// How large a chart's text and label areas are.
#[derive(Clone, Copy, PartialEq)]
pub enum ChartSize {
    /// A figure panel.
    Panel,
    /// An inset inside a panel: smaller caption, fewer ticks.
    Inset,
}

/// [`chart`] at a given size.
pub fn framed<'a, DB: Backend>(
    area: &'a DrawingArea<DB, Shift>,
    caption: &str,
    (x, y): (Range<f64>, Range<f64>),
    (x_desc, y_desc): (&str, &str),
    size: ChartSize,
) -> Result<ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>> {
    let inset = size == ChartSize::Inset;
    let mut c = ChartBuilder::on(area)
        .caption(caption, (FONT, if inset { 16 } else { 20 }))
        .margin(if inset { 6 } else { 10 })
        // room for half of the last x tick label, which is centred on the right edge
        .margin_right(if inset { 16 } else { 26 })
        .x_label_area_size(if inset { 28 } else { 45 })
        .y_label_area_size(if inset { 56 } else { 70 })
        .build_cartesian_2d(x.clone(), y.clone())
        .map_err(|e| anyhow!("{e}"))?;
    let ticks = if inset { 5 } else { 10 };
    let (fx, fy) = (tick_formatter(&x, ticks), tick_formatter(&y, ticks));
    c.configure_mesh()
        .x_desc(x_desc)
        .y_desc(y_desc)
        .x_labels(ticks)
        .y_labels(ticks)
        .x_label_formatter(&fx)
        .y_label_formatter(&fy)
        .axis_desc_style((FONT, 16))
        .label_style((FONT, 14))
        .light_line_style(RGBColor(235, 235, 235))
        .draw()
        .map_err(|e| anyhow!("{e}"))?;
    Ok(c)
}

/// Draw the legend of a chart whose series carry labels.
pub fn legend<'a, DB: Backend + 'a>(
    chart: &mut ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    position: SeriesLabelPosition,
) -> Result<()> {
    chart
        .configure_series_labels()
        .position(position)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font((FONT, 14))
        .draw()
        .map_err(|e| anyhow!("{e}"))
}

/// The mark of a legend entry.
#[derive(Clone, Copy)]
pub enum Symbol {
    /// A filled square: a region's colour.
    Swatch(RGBColor),
    /// A solid line.
    Line(RGBColor),
    /// A dashed line.
    Dashed(RGBColor),
    /// An open circle.
    Ring(RGBColor),
    /// A cross.
    Cross(RGBColor),
}

/// A legend drawn in its own strip outside the plotting areas (below the panels), one for a
/// whole figure: entries side by side, wrapped into centred rows.
pub struct LegendStrip {
    /// Mark and text of each entry.
    pub entries: Vec<(Symbol, String)>,
}

const LEGEND_SIZE: u32 = 16;
const LEGEND_ROW: u32 = 28;
const LEGEND_PAD: u32 = 10;
/// Width of an entry's mark and the gap before its text.
const LEGEND_MARK: u32 = 30;
/// Space between entries.
const LEGEND_GAP: u32 = 30;

impl LegendStrip {
    /// An entry's width in pixels: the mark and the text as laid out by the embedded font
    /// (the same for every backend).
    fn entry_width(text: &str) -> u32 {
        init_fonts();
        let text_width = (FONT, LEGEND_SIZE)
            .into_font()
            .box_size(text)
            .map_or(LEGEND_SIZE * text.chars().count() as u32, |(w, _)| w);
        LEGEND_MARK + text_width
    }

    /// The entries' indices per row, for a strip `width` pixels wide.
    fn rows(&self, width: u32) -> Vec<Vec<usize>> {
        let max = width.saturating_sub(2 * LEGEND_PAD);
        let mut rows: Vec<Vec<usize>> = Vec::new();
        let mut used = 0;
        for (i, (_, text)) in self.entries.iter().enumerate() {
            let w = Self::entry_width(text);
            match rows.last_mut() {
                Some(row) if used + LEGEND_GAP + w <= max => {
                    row.push(i);
                    used += LEGEND_GAP + w;
                }
                _ => {
                    rows.push(vec![i]);
                    used = w;
                }
            }
        }
        rows
    }

    /// Height of the strip for a figure `width` pixels wide (0 without entries).
    pub fn height(&self, width: u32) -> u32 {
        match self.rows(width).len() as u32 {
            0 => 0,
            n => 2 * LEGEND_PAD + n * LEGEND_ROW,
        }
    }

    /// Draw the entries, framed, centred in `area`.
    pub fn draw<DB: Backend>(&self, area: &DrawingArea<DB, Shift>) -> Result<()> {
        let (width, _) = area.dim_in_pixel();
        let rows = self.rows(width);
        let row_width = |row: &Vec<usize>| -> u32 {
            row.iter()
                .map(|&i| Self::entry_width(&self.entries[i].1))
                .sum::<u32>()
                + LEGEND_GAP * (row.len() as u32).saturating_sub(1)
        };
        let Some(widest) = rows.iter().map(row_width).max() else {
            return Ok(());
        };
        let left = (width.saturating_sub(widest) / 2) as i32;
        let frame = [
            (left - LEGEND_PAD as i32, 4),
            (
                left + (widest + LEGEND_PAD) as i32,
                (LEGEND_PAD + rows.len() as u32 * LEGEND_ROW) as i32 + 4,
            ),
        ];
        area.draw(&Rectangle::new(frame, RGBColor(150, 150, 150)))
            .map_err(pe)?;
        let font = (FONT, LEGEND_SIZE)
            .into_font()
            .color(&BLACK)
            .pos(Pos::new(HPos::Left, VPos::Center));
        for (k, row) in rows.iter().enumerate() {
            let y = (LEGEND_PAD + k as u32 * LEGEND_ROW + LEGEND_ROW / 2) as i32;
            let mut x = left + (widest - row_width(row)) as i32 / 2;
            for &i in row {
                let (symbol, text) = &self.entries[i];
                let m = (x + 10, y);
                match *symbol {
                    Symbol::Swatch(c) => area.draw(&Rectangle::new(
                        [(m.0 - 8, m.1 - 8), (m.0 + 8, m.1 + 8)],
                        c.filled(),
                    )),
                    Symbol::Line(c) => area.draw(&PathElement::new(
                        [(m.0 - 10, m.1), (m.0 + 10, m.1)],
                        c.stroke_width(3),
                    )),
                    Symbol::Dashed(c) => {
                        area.draw(&PathElement::new(
                            [(m.0 - 10, m.1), (m.0 - 3, m.1)],
                            c.stroke_width(3),
                        ))
                        .map_err(pe)?;
                        area.draw(&PathElement::new(
                            [(m.0 + 3, m.1), (m.0 + 10, m.1)],
                            c.stroke_width(3),
                        ))
                    }
                    Symbol::Ring(c) => area.draw(&Circle::new(m, 6, c.stroke_width(2))),
                    Symbol::Cross(c) => area.draw(&Cross::new(m, 7, c.stroke_width(2))),
                }
                .map_err(pe)?;
                area.draw(&Text::new(
                    text.clone(),
                    (x + LEGEND_MARK as i32, y),
                    font.clone(),
                ))
                .map_err(pe)?;
                x += (Self::entry_width(text) + LEGEND_GAP) as i32;
            }
        }
        Ok(())
    }
}

/// Distinct line colours for several curves in one panel.
pub const PALETTE: [RGBColor; 6] = [
    RGBColor(0, 0, 0),
    RGBColor(200, 30, 30),
    RGBColor(30, 90, 200),
    RGBColor(20, 150, 60),
    RGBColor(150, 60, 180),
    RGBColor(230, 130, 0),
];

/// A range covering `values` with a margin of 5 % on each side.
pub fn padded_range(values: impl IntoIterator<Item = f64>) -> Range<f64> {
    let (lo, hi) = values
        .into_iter()
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
    if !lo.is_finite() {
        return 0.0..1.0;
    }
    let pad = ((hi - lo) * 0.05).max(1e-12 * hi.abs().max(1.0));
    (lo - pad)..(hi + pad)
}

/// Map a plotters error into anyhow.
pub fn pe<E: std::fmt::Display>(e: E) -> anyhow::Error {
    anyhow!("{e}")
}

/// Viridis by linear interpolation between five of its anchor colours, t ∈ [0, 1].
pub fn viridis(t: f64) -> RGBColor {
    const A: [(f64, f64, f64); 5] = [
        (68.0, 1.0, 84.0),
        (59.0, 82.0, 139.0),
        (33.0, 145.0, 140.0),
        (94.0, 201.0, 98.0),
        (253.0, 231.0, 37.0),
    ];
    let t = t.clamp(0.0, 1.0) * 4.0;
    let i = (t.floor() as usize).min(3);
    let f = t - i as f64;
    let mix = |a: f64, b: f64| (a + f * (b - a)).round() as u8;
    RGBColor(
        mix(A[i].0, A[i + 1].0),
        mix(A[i].1, A[i + 1].1),
        mix(A[i].2, A[i + 1].2),
    )
}

/// A horizontal colour bar for values in [lo, hi] with its ticks.
pub fn colour_bar<DB: Backend>(
    area: &DrawingArea<DB, Shift>,
    label: &str,
    lo: f64,
    hi: f64,
) -> Result<()> {
    let fx = tick_formatter(&(lo..hi), 5);
    let mut c = ChartBuilder::on(area)
        .margin_left(70)
        .margin_right(20)
        .margin_top(8)
        .x_label_area_size(40)
        .build_cartesian_2d(lo..hi, 0.0..1.0)
        .map_err(pe)?;
    c.configure_mesh()
        .disable_y_axis()
        .disable_mesh()
        .x_labels(5)
        .x_label_formatter(&fx)
        .x_desc(label)
        .axis_desc_style((FONT, 16))
        .label_style((FONT, 14))
        .draw()
        .map_err(pe)?;
    let n = 64;
    c.draw_series((0..n).map(|i| {
        let (a, b) = (i as f64 / n as f64, (i + 1) as f64 / n as f64);
        Rectangle::new(
            [(lo + a * (hi - lo), 0.0), (lo + b * (hi - lo), 1.0)],
            viridis((i as f64 + 0.5) / n as f64).filled(),
        )
    }))
    .map_err(pe)?;
    Ok(())
}
