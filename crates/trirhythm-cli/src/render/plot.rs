//! Pictures: an embedded font, PNG + SVG output of one drawing, chart helpers, colours.
//!
//! A figure implements [`Picture`] once, generically over the plotters backend, and
//! [`save`] draws it as SVG and rasterises that SVG (resvg) to the PNG ([`rasterise`]):
//! [`PNG_WIDTH`] = 2100 px, 7 in at 300 dpi, one picture in both formats, written atomically.
//! One style for every figure (Rougier et al., "Ten simple rules for better figures"): [`save`]
//! draws the [`Heading`]'s title on one line above the picture and one short verdict badge
//! below it, never cut (a figure's one claim, or one summary line of several); the explanations (parameters, formula variant, the values chosen where
//! the paper is silent, the verdicts' details) are the caption: the heading's lines, written
//! to the figure's CSV notes, the report page and the contact sheet, never drawn inside the
//! plot.
//!
//! Print size: [`save`] sets a scale from the canvas width ([`ScaleGuard`], [`scale_for`]) so
//! that, printed 7 in (504 pt) wide, the smallest text ([`TICK`]) is at least 7 pt: an em of
//! at least width / 72 px (plotters' size / 1.24, its `font-size`; the SVG carries the em the
//! text is laid out with, size / 1.164, [`true_font_sizes`]). Font sizes ([`font_px`]) and
//! text-dependent layout ([`px`]) are designed at scale 1 and drawn at the scale. Rich text
//! ([`rich_text`]) draws subscripts (`U_eff`, `ΔU_1`, `A_{01}`) as smaller, lowered runs.
//! Series: [`series`] gives the i-th curve an Okabe–Ito colour, a dash and a marker
//! ([`draw_line`], [`draw_markers`]). Tests: unit tests below; the CLI's `pictures` test parses
//! every SVG's font sizes and layout.
//!
//! Files: every PNG carries a `Software` text chunk and every SVG a comment with the
//! [`SIGNATURE`], so that a destination holding a picture this tool drew can be told from a
//! file it must not replace ([`signed`]).
//!
//! Text: every font size is even (the layout's pixel arithmetic stays whole). SVG: the same
//! DejaVu Sans the PNG is rasterised with is embedded in each SVG as a web font
//! ([`embed_font`]), so the two render alike on any machine.

use crate::io::write_atomic;
use anyhow::{anyhow, Context, Result};
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use serde::{Deserialize, Serialize};
use std::ops::Range;
use std::path::{Path, PathBuf};
use std::sync::Once;

pub use super::legend::{LegendStrip, Symbol};
pub use super::series::{
    draw_line, draw_markers, series, stroke, Dash, Marker, SeriesStyle, PALETTE,
};

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

/// What a picture says about itself: a title (drawn above it, one line), then the caption's
/// lines giving the parameters, the formula variant and the choices the project made (not
/// drawn: the CSV notes, the report and the contact sheet carry them).
#[derive(Clone, Serialize, Deserialize)]
pub struct Heading {
    /// "Fig. N: what it shows".
    pub title: String,
    /// Parameters, variant, choices: the caption.
    pub lines: Vec<String>,
    /// The verdicts on the paper's claims that rest on the figure, drawn below the picture in
    /// the verdict's colour, one line each.
    pub verdicts: Vec<VerdictLine>,
}

/// One verdict on a claim, as drawn on a picture.
#[derive(Clone, Serialize, Deserialize)]
pub struct VerdictLine {
    /// `confirmed`, `refuted` or `undetermined` (sets the colour).
    pub tag: String,
    /// The line: the claim, the verdict, the deciding numbers (at most
    /// [`crate::render::paper::VERDICT_CHARS`] characters, for the picture's badge).
    pub text: String,
    /// The same for the caption: more of the deciding checks (at most
    /// [`crate::render::paper::CAPTION_CHARS`] characters, and then where all are).
    #[serde(default)]
    pub full: String,
    /// How many characters of `text` open it as `{claim} — {verdict} ({deciding number})`:
    /// the badge never cuts them.
    #[serde(default)]
    pub head: usize,
    /// The badge drawn under the picture: `{claim} — {verdict} ({deciding statistic})`.
    #[serde(default)]
    pub badge: String,
}

impl VerdictLine {
    /// `{claim} — {verdict}`: the opening of the line, which a badge always shows.
    fn short(&self) -> String {
        match self.text.split_once(" — ") {
            Some((claim, _)) => format!("{claim} — {}", self.tag),
            None => self.tag.clone(),
        }
    }

    /// The colour of a verdict (Okabe–Ito: blue, vermillion, and a dark grey).
    fn colour(&self) -> RGBColor {
        match self.tag.as_str() {
            "confirmed" => RGBColor(0, 114, 178),
            "refuted" => RGBColor(213, 94, 0),
            _ => RGBColor(90, 90, 90),
        }
    }
}

impl Heading {
    fn line_height() -> u32 {
        font_px(HEADING_LINE) * 5 / 4
    }

    /// The height of the title strip above the picture: one line.
    fn height(&self) -> u32 {
        px(8) + font_px(HEADING_TITLE) * 5 / 4 + px(6)
    }

    /// The title on one line of `width` pixels, and its font size: whole at the title's
    /// size, else whole at a panel title's, else cut there at the last clause that fits
    /// (", ", ": ", "; "), else with "…" (the contact sheet and the CSV notes have it whole).
    fn title_line(&self, width: u32) -> (String, u32) {
        let room = width.saturating_sub(2 * px(12));
        for base in [HEADING_TITLE, CAPTION] {
            if rich_width(&self.title, base) <= room {
                return (self.title.clone(), base);
            }
        }
        (fit_title(&self.title, room, CAPTION), CAPTION)
    }

    fn draw<DB: Backend>(&self, area: &DrawingArea<DB, Shift>) -> Result<()> {
        let width = area.dim_in_pixel().0;
        let title_h = font_px(HEADING_TITLE) * 5 / 4;
        let (title, base) = self.title_line(width);
        rich_text(
            area,
            &title,
            (px(12) as i32, (px(8) + title_h / 2) as i32),
            Pos::new(HPos::Left, VPos::Center),
            base,
            BLACK,
            false,
        )
    }

    /// The verdict badge in its colour, one short line never cut: a figure's one verdict as
    /// the claim, the verdict and, where it fits, the deciding statistic, else "(see
    /// caption)"; several verdicts as one summary line ("verdicts: 2 confirmed, 1 refuted
    /// (see caption)", in the colour of a refutation where there is one). The caption has
    /// every verdict whole.
    fn badges(&self, width: u32) -> Vec<(String, RGBColor)> {
        let room = width.saturating_sub(2 * px(12));
        let fits = |t: &str| rich_width(t, HEADING_LINE) <= room;
        if self.verdicts.len() > 1 {
            let mut counts: Vec<(&str, usize)> = Vec::new();
            for v in &self.verdicts {
                match counts.iter_mut().find(|(t, _)| *t == v.tag) {
                    Some((_, n)) => *n += 1,
                    None => counts.push((&v.tag, 1)),
                }
            }
            let words: Vec<String> = counts.iter().map(|(t, n)| format!("{n} {t}")).collect();
            let worst = self
                .verdicts
                .iter()
                .find(|v| v.tag == "refuted")
                .unwrap_or(&self.verdicts[0]);
            let line = format!("verdicts: {} (see caption)", words.join(", "));
            return vec![(one_line(&line, room, HEADING_LINE), worst.colour())];
        }
        self.verdicts
            .iter()
            .map(|v| {
                let short = v.short();
                let line = [
                    v.badge.clone(),
                    drop_asides(&v.badge),
                    format!("{short} (see caption)"),
                ]
                .into_iter()
                .find(|t| !t.is_empty() && fits(t))
                .unwrap_or_else(|| one_line(&short, room, HEADING_LINE));
                (line, v.colour())
            })
            .collect()
    }

    /// The height of the badge strip below the picture, `width` pixels wide (nothing without
    /// verdicts).
    fn badges_height(&self, width: u32) -> u32 {
        if self.verdicts.is_empty() {
            0
        } else {
            px(6) + Self::line_height() * self.badges(width).len() as u32 + px(6)
        }
    }

    fn draw_badges<DB: Backend>(&self, area: &DrawingArea<DB, Shift>) -> Result<()> {
        let width = area.dim_in_pixel().0;
        draw_lines(area, self.badges(width), HEADING_LINE, Self::line_height())
    }
}

/// `lines` of rich text ([`rich_text`]) at font size `base`, each in its colour, left-aligned
/// from the top of `area` ([`px`]`(12)` in, [`px`]`(6)` down), `height` pixels apart.
pub fn draw_lines<DB: Backend>(
    area: &DrawingArea<DB, Shift>,
    lines: impl IntoIterator<Item = (String, RGBColor)>,
    base: u32,
    height: u32,
) -> Result<()> {
    for (i, (line, colour)) in lines.into_iter().enumerate() {
        rich_text(
            area,
            &line,
            (
                px(12) as i32,
                (px(6) + height * i as u32 + height / 2) as i32,
            ),
            Pos::new(HPos::Left, VPos::Center),
            base,
            colour,
            false,
        )?;
    }
    Ok(())
}

/// `text` without its parenthesised asides inside parentheses ("a (b (c) d)" → "a (b d)"),
/// spaces before a removed aside dropped with it.
fn drop_asides(text: &str) -> String {
    let mut out = String::new();
    let mut depth = 0usize;
    for ch in text.chars() {
        match ch {
            '(' => {
                depth += 1;
                if depth >= 2 {
                    while out.ends_with(' ') && depth == 2 {
                        out.pop();
                    }
                    continue;
                }
            }
            ')' => {
                depth = depth.saturating_sub(1);
                if depth >= 1 {
                    continue;
                }
            }
            _ if depth >= 2 => continue,
            _ => {}
        }
        out.push(ch);
    }
    out
}

/// A title on one line of at most `width` pixels at font size `base`: whole, else cut at
/// the last clause that fits (before ", ", ": " or "; " outside parentheses, keeping more
/// than its label), else
/// with "…". The caption carries it whole.
pub fn fit_title(title: &str, width: u32, base: u32) -> String {
    if rich_width(title, base) <= width {
        return title.to_string();
    }
    // the separators outside parentheses
    let mut depth = 0i32;
    let mut clauses = Vec::new();
    for (i, c) in title.char_indices() {
        match c {
            '(' | '[' | '{' => depth += 1,
            ')' | ']' | '}' => depth -= 1,
            ',' | ':' | ';' if depth == 0 && title[i + 1..].starts_with(' ') => clauses.push(i),
            _ => {}
        }
    }
    let clause = clauses
        .into_iter()
        .filter(|&i| i > 5 && rich_width(&title[..i], base) <= width)
        .max();
    match clause {
        Some(i) => title[..i].to_string(),
        None => one_line(title, width, base),
    }
}

/// `line` on one line of at most `width` pixels at font size `base`: whole, or cut at a
/// character boundary and ended with "…".
pub fn one_line(line: &str, width: u32, base: u32) -> String {
    if rich_width(line, base) <= width {
        return line.to_string();
    }
    let chars: Vec<char> = line.chars().collect();
    let (mut lo, mut hi) = (0, chars.len());
    // the longest prefix that fits with the ellipsis
    while lo < hi {
        let mid = (lo + hi).div_ceil(2);
        let cut: String = chars[..mid].iter().collect();
        if rich_width(&format!("{}…", cut.trim_end()), base) <= width {
            lo = mid;
        } else {
            hi = mid - 1;
        }
    }
    let cut: String = chars[..lo].iter().collect();
    format!("{}…", cut.trim_end())
}

// ---------------------------------------------------------------------------------------
// Scale: text sized for print

/// Base sizes (pixels at scale 1) of the text: the heading's title and lines, a panel's
/// caption, axis descriptions, tick labels, legend entries, in-panel labels.
const HEADING_TITLE: u32 = 20;
const HEADING_LINE: u32 = 14;
/// A panel's caption.
pub const CAPTION: u32 = 16;
/// Axis descriptions.
pub const AXIS_DESC: u32 = 16;
/// Tick labels: the smallest text, the one the scale is set by.
pub const TICK: u32 = 14;
/// Legend entries and in-panel labels.
pub const LABEL: u32 = 14;

/// Printed width of a figure, in points (7 in), and the smallest printed text size.
const PRINT_WIDTH_PT: f64 = 504.0;
const PRINT_MIN_PT: f64 = 7.0;
/// plotters' font size is the line height: the em (SVG `font-size`) is `size / 1.24`.
const EM_PER_SIZE: f64 = 1.0 / 1.24;

thread_local! {
    static SCALE: std::cell::Cell<f64> = const { std::cell::Cell::new(1.0) };
}

/// The scale for a canvas `width` pixels wide: the one at which the smallest text
/// ([`TICK`]) prints at 7 pt when the canvas is printed 7 in wide, i.e. an em of at least
/// `width / 72` pixels.
pub fn scale_for(width: u32) -> f64 {
    let min_em = width as f64 * PRINT_MIN_PT / PRINT_WIDTH_PT;
    (min_em / EM_PER_SIZE / TICK as f64).max(1.0)
}

/// The scale text and text-dependent layout are drawn at (set by [`save`] from the canvas
/// width; 1 outside it).
pub fn scale() -> f64 {
    SCALE.with(|s| s.get())
}

/// Sets the scale for the lifetime of the guard (restoring the previous one).
pub struct ScaleGuard(f64);

impl ScaleGuard {
    /// Draw at the scale for a canvas `width` pixels wide until the guard is dropped.
    pub fn for_width(width: u32) -> Self {
        let previous = scale();
        SCALE.with(|s| s.set(scale_for(width)));
        ScaleGuard(previous)
    }
}

impl Drop for ScaleGuard {
    fn drop(&mut self) {
        SCALE.with(|s| s.set(self.0));
    }
}

/// A length in pixels designed at scale 1 (margins, label areas, marks), at the current
/// scale.
pub fn px(base: u32) -> u32 {
    (base as f64 * scale()).round() as u32
}

/// [`px`] as `i32` (offsets of text and marks).
pub fn pxi(base: i32) -> i32 {
    (base as f64 * scale()).round() as i32
}

/// A font size designed at scale 1, at the current scale: rounded up to an even number of
/// pixels (see the module doc), so never below `base × scale`.
pub fn font_px(base: u32) -> u32 {
    let v = (base as f64 * scale() - 1e-9).ceil() as u32;
    v + v % 2
}

// ---------------------------------------------------------------------------------------
// Rich text: subscripts

/// The runs of `markup`: `(text, subscript)`. A subscript is written `_{…}`, or `_` then
/// letters and digits after a one-letter symbol (optionally with Δ): `U_eff`, `ΔU_1`, `D_c`,
/// `A_01`; other underscores (`fig14_folds`) stay as they are.
pub fn rich_runs(markup: &str) -> Vec<(String, bool)> {
    let chars: Vec<char> = markup.chars().collect();
    let mut runs: Vec<(String, bool)> = Vec::new();
    let mut cur = String::new();
    let mut i = 0;
    let push = |runs: &mut Vec<(String, bool)>, text: String, sub: bool| {
        if !text.is_empty() {
            runs.push((text, sub));
        }
    };
    while i < chars.len() {
        let c = chars[i];
        if c == '_' && i + 1 < chars.len() {
            if chars[i + 1] == '{' {
                if let Some(close) = chars[i + 2..].iter().position(|&c| c == '}') {
                    push(&mut runs, std::mem::take(&mut cur), false);
                    push(
                        &mut runs,
                        chars[i + 2..i + 2 + close].iter().collect(),
                        true,
                    );
                    i += close + 3;
                    continue;
                }
            } else if chars[i + 1].is_alphanumeric() && symbol_before(&chars[..i]) {
                let n = chars[i + 1..]
                    .iter()
                    .take_while(|c| c.is_alphanumeric())
                    .count();
                push(&mut runs, std::mem::take(&mut cur), false);
                push(&mut runs, chars[i + 1..i + 1 + n].iter().collect(), true);
                i += n + 1;
                continue;
            }
        }
        cur.push(c);
        i += 1;
    }
    push(&mut runs, cur, false);
    runs
}

/// Whether `before` ends in a one-letter symbol (a letter, optionally after Δ, itself at
/// the start or after a character that is not a letter or digit).
fn symbol_before(before: &[char]) -> bool {
    let n = before.len();
    if n == 0 || !before[n - 1].is_alphabetic() {
        return false;
    }
    let start = if n >= 2 && before[n - 2] == 'Δ' {
        n - 2
    } else {
        n - 1
    };
    start == 0 || !before[start - 1].is_alphanumeric()
}

/// The size of a subscript in text of size `size` px: smaller, but never below the
/// smallest text.
fn sub_size(size: u32) -> u32 {
    let v = (size as f64 * 0.72).round() as u32;
    (v + v % 2).max(font_px(TICK)).min(size)
}

fn text_width(text: &str, size: u32) -> u32 {
    init_fonts();
    (FONT, size)
        .into_font()
        .box_size(text)
        .map_or(size * text.chars().count() as u32 / 2, |(w, _)| w)
}

/// The width in pixels of `markup` drawn at font size `base` (at the current scale).
pub fn rich_width(markup: &str, base: u32) -> u32 {
    let size = font_px(base);
    rich_runs(markup)
        .iter()
        .map(|(t, sub)| text_width(t, if *sub { sub_size(size) } else { size }))
        .sum()
}

/// Draw `markup` (subscripts as in [`rich_runs`]) at `at`, anchored by `pos`, font size
/// `base` at the current scale, in `colour`; `vertical` reads it bottom to top (a y axis
/// description).
pub fn rich_text<DB: Backend>(
    area: &DrawingArea<DB, Shift>,
    markup: &str,
    at: (i32, i32),
    pos: Pos,
    base: u32,
    colour: RGBColor,
    vertical: bool,
) -> Result<()> {
    init_fonts();
    let size = font_px(base);
    let total = rich_width(markup, base) as i32;
    let start = match pos.h_pos {
        HPos::Left => 0,
        HPos::Center => -total / 2,
        HPos::Right => -total,
    };
    // the runs are drawn centred on a line: the anchor's vertical position moves the line
    let centre = match pos.v_pos {
        VPos::Top => size as i32 / 2,
        VPos::Center => 0,
        VPos::Bottom => -(size as i32) / 2,
    };
    let mut along = start;
    for (text, sub) in rich_runs(markup) {
        let s = if sub { sub_size(size) } else { size };
        let across = centre + if sub { (size as i32) * 3 / 10 } else { 0 };
        let mut style = (FONT, s)
            .into_font()
            .color(&colour)
            .pos(Pos::new(HPos::Left, VPos::Center));
        let point = if vertical {
            style = style.transform(FontTransform::Rotate270);
            (at.0 + across, at.1 - along)
        } else {
            (at.0 + along, at.1 + across)
        };
        let w = text_width(&text, s) as i32;
        // a space at either end of a run as a no-break space: an SVG reader drops plain ones
        // there (the run after a subscript would touch it)
        let text = match (text.strip_prefix(' '), text.ends_with(' ')) {
            (None, false) => text,
            _ => {
                let inner = text.trim_matches(' ');
                let lead = text.len() - text.trim_start_matches(' ').len();
                let trail = text.len() - text.trim_end_matches(' ').len();
                format!("{}{inner}{}", "\u{a0}".repeat(lead), "\u{a0}".repeat(trail))
            }
        };
        area.draw(&Text::new(text, point, style)).map_err(pe)?;
        along += w;
    }
    Ok(())
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
    let svg = stem.with_extension("svg");
    let text = draw_svg(picture, verdicts).with_context(|| format!("drawing {}", svg.display()))?;
    // the PNG is the SVG rasterised: the same picture, at print resolution
    let png = stem.with_extension("png");
    let bytes = rasterise(&text).with_context(|| format!("drawing {}", png.display()))?;
    write_atomic(&png, &bytes)?;
    write_atomic(&svg, svg_file(&text).as_bytes())?;
    Ok(vec![png, svg])
}

/// `picture` with its heading and `verdicts` drawn as SVG text, the fonts not yet embedded:
/// what [`save`] rasterises ([`rasterise`]) and writes ([`svg_file`]).
pub fn draw_svg(picture: &impl Picture, verdicts: Vec<VerdictLine>) -> Result<String> {
    init_fonts();
    // the scale is set by the canvas width (which does not depend on it); the height does
    let _scale = ScaleGuard::for_width(picture.size().0);
    let (w, h) = picture.size();
    let mut heading = picture.heading();
    heading.verdicts = verdicts;
    let (hh, bh) = (heading.height(), heading.badges_height(w));
    let size = (w, hh + h + bh);
    fn render<DB: Backend>(
        root: DrawingArea<DB, Shift>,
        heading: &Heading,
        (hh, h): (u32, u32),
        picture: &impl Picture,
    ) -> Result<()> {
        root.fill(&WHITE).map_err(pe)?;
        let (top, rest) = root.split_vertically(hh);
        let (body, bottom) = rest.split_vertically(h);
        heading.draw(&top)?;
        picture.draw(&body)?;
        heading.draw_badges(&bottom)?;
        root.present().map_err(pe)
    }
    let mut text = String::new();
    render(
        SVGBackend::with_string(&mut text, size).into_drawing_area(),
        &heading,
        (hh, h),
        picture,
    )?;
    // rectangles (map cells, heat-map cells, swatches) edge to edge: without anti-aliased
    // edges, or every shared edge shows as a faint seam
    let text = text.replace("<rect ", "<rect shape-rendering=\"crispEdges\" ");
    Ok(true_font_sizes(&text))
}

/// The signature every picture file carries: a PNG's `Software` text chunk, a comment after
/// an SVG's opening tag. A destination holding a picture without it was not written here.
pub const SIGNATURE: &str = "trirhythm";

/// The SVG file of a picture drawn by [`draw_svg`]: its fonts embedded ([`embed_font`]) and
/// the [`SIGNATURE`] in a comment after the opening tag.
pub fn svg_file(svg: &str) -> String {
    let text = embed_font(svg);
    match text
        .find("<svg")
        .and_then(|i| text[i..].find('>').map(|j| i + j + 1))
    {
        Some(end) => format!("{}<!-- {SIGNATURE} -->{}", &text[..end], &text[end..]),
        None => text,
    }
}

/// Whether `bytes` are a picture written here ([`rasterise`]'s PNG or [`svg_file`]'s SVG,
/// told by the [`SIGNATURE`]): the only files a picture's destination may replace.
pub fn signed(bytes: &[u8]) -> bool {
    const PNG: &[u8] = b"\x89PNG\r\n\x1a\n";
    let contains = |hay: &[u8], needle: &[u8]| hay.windows(needle.len()).any(|w| w == needle);
    if bytes.starts_with(PNG) {
        // (the text chunk follows the header, before the image data)
        let chunk = format!("tEXtSoftware\0{SIGNATURE}");
        contains(&bytes[..bytes.len().min(256)], chunk.as_bytes())
    } else {
        let head = &bytes[..bytes.len().min(4096)];
        contains(head, b"<svg") && contains(head, format!("<!-- {SIGNATURE} -->").as_bytes())
    }
}

/// DejaVu Sans' height (ascender − descender, 1901 + 483 font units) per em (2048 units).
const FONT_HEIGHT_PER_EM: f64 = 2384.0 / 2048.0;

/// The SVG with every `font-size` the em the text was laid out with. plotters measures and
/// places text with a font scaled to a height (ascender − descender) of its size, an em of
/// size / 1.164 for DejaVu Sans, but writes `font-size` as size / 1.24: as written, every
/// text would render 6 % narrower than the room it was given (a subscript drifting off its
/// symbol, a centred label off centre).
fn true_font_sizes(svg: &str) -> String {
    let mut out = String::with_capacity(svg.len());
    let mut rest = svg;
    while let Some(at) = rest.find("font-size=\"") {
        let (head, tail) = rest.split_at(at + "font-size=\"".len());
        out.push_str(head);
        let end = tail.find('"').unwrap_or(0);
        match tail[..end].parse::<f64>() {
            Ok(v) => out.push_str(&format!("{}", v * 1.24 / FONT_HEIGHT_PER_EM)),
            Err(_) => out.push_str(&tail[..end]),
        }
        rest = &tail[end..];
    }
    out.push_str(rest);
    out
}

/// The width of every PNG in pixels: 7 in at 300 dpi.
pub const PNG_WIDTH: u32 = 2100;

/// An SVG drawn by [`save`] as a PNG [`PNG_WIDTH`] pixels wide (white background), its text
/// in the DejaVu Sans faces the SVG embeds.
pub fn rasterise(svg: &str) -> Result<Vec<u8>> {
    use resvg::{tiny_skia, usvg};
    let mut options = usvg::Options::default();
    {
        let fonts = options.fontdb_mut();
        fonts.load_font_data(dejavu::sans::regular().to_vec());
        fonts.load_font_data(dejavu::sans::bold().to_vec());
        fonts.load_font_data(dejavu::sans::oblique().to_vec());
        fonts.set_sans_serif_family(EMBEDDED_FAMILY);
    }
    let tree = usvg::Tree::from_str(svg, &options).map_err(|e| anyhow!("the SVG: {e}"))?;
    let zoom = PNG_WIDTH as f32 / tree.size().width();
    let height = (tree.size().height() * zoom).round() as u32;
    let mut pixmap = tiny_skia::Pixmap::new(PNG_WIDTH, height)
        .ok_or_else(|| anyhow!("a picture of {PNG_WIDTH} × {height} pixels"))?;
    pixmap.fill(tiny_skia::Color::WHITE);
    resvg::render(
        &tree,
        tiny_skia::Transform::from_scale(zoom, zoom),
        &mut pixmap.as_mut(),
    );
    // opaque (white below everything): RGB, compressed hard (a tenth of tiny-skia's RGBA)
    let rgb: Vec<u8> = pixmap
        .data()
        .chunks_exact(4)
        .flat_map(|p| [p[0], p[1], p[2]])
        .collect();
    let mut bytes = Vec::new();
    let mut encoder = png::Encoder::new(&mut bytes, PNG_WIDTH, height);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.set_compression(png::Compression::Best);
    encoder.set_adaptive_filter(png::AdaptiveFilterType::Adaptive);
    // 300 dpi (11811 pixels per metre), so that the picture opens at 7 in wide
    encoder.set_pixel_dims(Some(png::PixelDimensions {
        xppu: 11811,
        yppu: 11811,
        unit: png::Unit::Meter,
    }));
    let encoding = |e: png::EncodingError| anyhow!("encoding the PNG: {e}");
    encoder
        .add_text_chunk("Software".into(), SIGNATURE.into())
        .map_err(encoding)?;
    let mut writer = encoder.write_header().map_err(encoding)?;
    writer.write_image_data(&rgb).map_err(encoding)?;
    writer.finish().map_err(encoding)?;
    Ok(bytes)
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
    // the step plotters takes for at most `ticks` ticks, and the decimals it needs
    let step = key_step(
        range.start.min(range.end),
        range.start.max(range.end),
        ticks,
    );
    let decimals = if step > 0.0 && step.is_finite() {
        (-step.log10() - 1e-9).ceil().max(0.0) as usize
    } else {
        0
    };
    let exponent = big >= 1e5 || (big > 0.0 && big < 1e-3);
    move |v: &f64| {
        let v = *v;
        // zero in the axis' format ("0.00" among "0.05"), negatives with the minus sign
        let text = if v.abs() <= span * 1e-9 {
            if exponent {
                "0".to_string()
            } else {
                format!("{:.decimals$}", 0.0)
            }
        } else if exponent {
            times_ten(v, 3)
        } else {
            format!("{v:.decimals$}")
        };
        match text.strip_prefix('-') {
            Some(rest) => format!("\u{2212}{rest}"),
            None => text,
        }
    }
}

/// The spacing of the ticks plotters puts on `[lo, hi]` when asked for at most `max`: the
/// largest of the steps 10ᵏ × {1, 0.5, 0.2} that it refines to (as its
/// `compute_f64_key_points`).
fn key_step(lo: f64, hi: f64, max: usize) -> f64 {
    let span = hi - lo;
    if span.is_nan() || span <= 0.0 || max == 0 {
        return 0.0;
    }
    let rem = |a: f64, b: f64| {
        let r = a - (a / b).floor() * b;
        if (r - b).abs() < f64::EPSILON {
            0.0
        } else {
            r
        }
    };
    let mut scale = 10f64.powf(span.log10().floor());
    if 1 + (span / scale).floor() as usize > max {
        scale *= 10.0;
    }
    for _ in 0..64 {
        let old = scale;
        for nxt in [2.0, 5.0, 10.0] {
            let mut left = lo - rem(lo, old / nxt);
            if left < lo {
                left += old / nxt;
            }
            let right = hi - rem(hi, old / nxt);
            let n = 1.0 + (right - left) / old * nxt;
            if n.round() as usize > max {
                return scale;
            }
            scale = old / nxt;
        }
        scale = old / 10.0;
    }
    scale
}

/// `v` as `m×10ⁿ` with at most `digits` significant digits (`2.5×10⁻⁷`, `10⁻⁶` for a mantissa
/// of one), the exponent in superscript digits.
pub fn times_ten(v: f64, digits: usize) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let s = format!("{v:.*e}", digits.saturating_sub(1));
    let Some((m, e)) = s.split_once('e') else {
        return s;
    };
    let m = if m.contains('.') {
        m.trim_end_matches('0').trim_end_matches('.')
    } else {
        m
    };
    let e = superscript(e);
    match m {
        "1" => format!("10{e}"),
        "-1" => format!("-10{e}"),
        _ => format!("{m}×10{e}"),
    }
}

/// An integer's digits and sign in superscript (`-7` → `⁻⁷`).
pub fn superscript(digits: &str) -> String {
    digits
        .chars()
        .map(|c| match c {
            '-' => '⁻',
            '0' => '⁰',
            '1' => '¹',
            '2' => '²',
            '3' => '³',
            '4' => '⁴',
            '5' => '⁵',
            '6' => '⁶',
            '7' => '⁷',
            '8' => '⁸',
            '9' => '⁹',
            other => other,
        })
        .collect()
}

/// A chart in `area` with a caption, axis ranges and axis descriptions, mesh drawn.
/// Caption and descriptions may carry subscripts (`U_eff`, see [`rich_runs`]).
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

/// [`chart`] whose y coordinate is log10 of the value drawn (`y` a range of exponents), its
/// ticks at whole decades labelled with the value itself (`10⁻²`), the others unlabelled.
pub fn chart_log_y<'a, DB: Backend>(
    area: &'a DrawingArea<DB, Shift>,
    caption: &str,
    x: Range<f64>,
    y: Range<f64>,
    x_desc: &str,
    y_desc: &str,
) -> Result<ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>> {
    let pow = |v: &f64| {
        if (v - v.round()).abs() < 1e-6 {
            format!("10{}", superscript(&format!("{}", v.round() as i64)))
        } else {
            String::new()
        }
    };
    framed_with(
        area,
        caption,
        (x, y),
        (x_desc, y_desc),
        ChartSize::Panel,
        Some(&pow),
    )
}

/// How large a chart's text and label areas are.
#[derive(Clone, Copy, PartialEq)]
pub enum ChartSize {
    /// A figure panel.
    Panel,
    /// An inset inside a panel: fewer ticks, tighter margins.
    Inset,
}

/// A chart caption as the panel title it is drawn as: one line of at most `width` pixels
/// (cut with "…"; the figure's caption carries the details).
fn caption_lines(caption: &str, width: u32) -> Vec<String> {
    if caption.is_empty() {
        return Vec::new();
    }
    vec![fit_title(caption, width, CAPTION)]
}

/// The height of a chart caption's strip (its lines, wrapped to `width` pixels, and the gap
/// below), at the current scale; 0 for an empty caption.
pub fn caption_height(caption: &str, width: u32) -> u32 {
    let n = caption_lines(caption, width).len() as u32;
    if n == 0 {
        0
    } else {
        font_px(CAPTION) * 6 / 5 * n + font_px(CAPTION) / 3
    }
}

/// [`chart`] at a given size. The caption is drawn centred above the plotting area, the axis
/// descriptions centred on it (the y one reading upwards), all as rich text; the label areas
/// are as wide as the tick labels need.
pub fn framed<'a, DB: Backend>(
    area: &'a DrawingArea<DB, Shift>,
    caption: &str,
    (x, y): (Range<f64>, Range<f64>),
    (x_desc, y_desc): (&str, &str),
    size: ChartSize,
) -> Result<ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>> {
    framed_with(area, caption, (x, y), (x_desc, y_desc), size, None)
}

/// [`framed`] with the y tick labels written by `y_labels` where given.
fn framed_with<'a, DB: Backend>(
    area: &'a DrawingArea<DB, Shift>,
    caption: &str,
    (x, y): (Range<f64>, Range<f64>),
    (x_desc, y_desc): (&str, &str),
    size: ChartSize,
    y_labels: Option<&dyn Fn(&f64) -> String>,
) -> Result<ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>> {
    init_fonts();
    let inset = size == ChartSize::Inset;
    // (an inset asks for six: plotters' 1-2-5 steps then give it four or more on most ranges)
    let ticks = if inset { 6 } else { 8 };
    let tick = font_px(TICK);
    let desc = font_px(AXIS_DESC);
    let widest = |f: &dyn Fn(&f64) -> String, r: &Range<f64>| {
        // samples across the range, and its whole numbers (a log axis labels only those)
        let whole = (r.start.ceil() as i64..=r.end.floor() as i64)
            .take(64)
            .map(|v| v as f64);
        (0..=20)
            .map(|k| r.start + (r.end - r.start) * k as f64 / 20.0)
            .chain(whole)
            .map(|v| text_width(&f(&v), tick))
            .max()
            .unwrap_or(0)
    };
    let has = |d: &str| !d.is_empty();
    let x_area = tick + px(10) + if has(x_desc) { desc * 5 / 4 } else { 0 };
    let margin = px(if inset { 4 } else { 8 });
    let width = area.dim_in_pixel().0;
    let cap = caption_height(caption, width.saturating_sub(2 * margin));
    // no more y ticks than fit, each label with a label's height of room (plotters keeps to
    // 1-2-5 steps and at most the count asked: asking for one label a line and a bit gives
    // at least four on any range)
    let y_room = area
        .dim_in_pixel()
        .1
        .saturating_sub(cap + x_area + 2 * margin);
    let mut y_ticks = (y_room / (tick * 9 / 8).max(1)).clamp(2, ticks as u32) as usize;
    // where plotters' step for that count leaves under four labelled ticks, ask for more as
    // long as the labels keep a label's height apart
    let labelled_on = |r: &Range<f64>, n: usize| {
        let step = key_step(r.start.min(r.end), r.start.max(r.end), n);
        if step > 0.0 {
            ((r.start.max(r.end) / step).floor() - (r.start.min(r.end) / step).ceil() + 1.0)
                as usize
        } else {
            0
        }
    };
    let labelled = |n: usize| labelled_on(&y, n);
    let most = (y_room / tick.max(1)) as usize;
    while y_labels.is_none() && labelled(y_ticks) < 4 && y_ticks < most.min(12) {
        y_ticks += 1;
    }
    let plain_y = tick_formatter(&y, y_ticks);
    let fy: &dyn Fn(&f64) -> String = match y_labels {
        Some(f) => f,
        None => &plain_y,
    };
    let y_tick_w = widest(fy, &y);
    // no more x ticks than fit, each label with a quarter of a label's width of room beside
    // it
    let room = width.saturating_sub(y_tick_w + px(80));
    let x_tick_w = widest(&tick_formatter(&x, ticks), &x);
    let mut x_ticks = (room / (x_tick_w.max(1) * 5 / 4)).clamp(2, ticks as u32) as usize;
    // where that leaves under four labelled ticks (a narrow inset), ask for more as long as
    // the labels keep a tenth of a label's width apart on the plotting area's width
    let plot_w = width.saturating_sub(y_tick_w + px(10) + 2 * margin + x_tick_w / 2);
    let fits = |n: usize| {
        let (lo, hi) = (x.start.min(x.end), x.start.max(x.end));
        let step = key_step(lo, hi, n);
        let w = widest(&tick_formatter(&x, n), &x) as f64;
        step > 0.0 && plot_w as f64 * step / (hi - lo) >= 1.1 * w
    };
    while labelled_on(&x, x_ticks) < 4 && x_ticks < 12 && fits(x_ticks + 1) {
        x_ticks += 1;
    }
    // an inset's axis of small values whose labels still leave under four ticks: the labels
    // in units of 10ᵉ (the largest value's decade), "×10ᵉ" written under the y labels
    let (lo_x, hi_x) = (x.start.min(x.end), x.start.max(x.end));
    let decade = lo_x.abs().max(hi_x.abs()).log10().floor();
    let scaled = inset && labelled_on(&x, x_ticks) < 4 && decade.is_finite() && decade < 0.0;
    let unit = 10f64.powf(decade);
    let x_in_units = (lo_x / unit)..(hi_x / unit);
    let mut unit_ticks = x_ticks;
    if scaled {
        let fits_units = |n: usize| {
            let (a, b) = (x_in_units.start, x_in_units.end);
            let step = key_step(a, b, n);
            let w = widest(&tick_formatter(&x_in_units, n), &x_in_units) as f64;
            step > 0.0 && plot_w as f64 * step / (b - a) >= 1.1 * w
        };
        while labelled_on(&x_in_units, unit_ticks) < 4
            && unit_ticks < 12
            && fits_units(unit_ticks + 1)
        {
            unit_ticks += 1;
        }
        x_ticks = unit_ticks;
    }
    let in_units = tick_formatter(&x_in_units, unit_ticks);
    let plain_x = tick_formatter(&x, x_ticks);
    let scaled_x = |v: &f64| in_units(&(v / unit));
    let fx: &dyn Fn(&f64) -> String = if scaled { &scaled_x } else { &plain_x };
    let x_tick_w = widest(fx, &x);
    let y_area = y_tick_w + px(10) + if has(y_desc) { desc * 5 / 4 } else { 0 };
    let mut c = ChartBuilder::on(area)
        .margin(margin)
        // (without a caption, room for half of the top y tick label, centred on the top edge)
        .margin_top(if cap == 0 {
            margin.max(tick / 2 + px(2))
        } else {
            margin + cap
        })
        // room for half of the last x tick label, which is centred on the right edge
        .margin_right(margin.max(x_tick_w / 2 + px(4)))
        .x_label_area_size(x_area)
        .y_label_area_size(y_area)
        .build_cartesian_2d(x.clone(), y.clone())
        .map_err(|e| anyhow!("{e}"))?;
    c.configure_mesh()
        .x_labels(x_ticks)
        .y_labels(y_ticks)
        .x_label_formatter(fx)
        .y_label_formatter(&fy)
        .label_style((FONT, tick))
        .light_line_style(RGBColor(235, 235, 235))
        .draw()
        .map_err(|e| anyhow!("{e}"))?;
    // the caption and axis descriptions, in the area's own pixels
    let (px_x, px_y) = c.plotting_area().get_pixel_range();
    let (bx, by) = area.get_base_pixel();
    let (x0, x1) = (px_x.start - bx, px_x.end - bx);
    let (y0, y1) = (px_y.start - by, px_y.end - by);
    let mid_x = (x0 + x1) / 2;
    let line = font_px(CAPTION) * 6 / 5;
    for (k, text) in caption_lines(caption, width.saturating_sub(2 * margin))
        .iter()
        .enumerate()
    {
        // centred on the plotting area where it fits there, else on the whole area
        let w = rich_width(text, CAPTION) as i32;
        let centre = mid_x.clamp(w / 2 + margin as i32, width as i32 - w / 2 - margin as i32);
        rich_text(
            area,
            text,
            (centre, (margin + line * k as u32 + line / 2) as i32),
            Pos::new(HPos::Center, VPos::Center),
            CAPTION,
            BLACK,
            false,
        )?;
    }
    if scaled {
        // the unit of the scaled labels, under the y labels, level with the x labels
        rich_text(
            area,
            &format!("×10{}", superscript(&format!("{}", decade as i64))),
            (x0 - pxi(4), y1 + pxi(4) + (tick / 2) as i32),
            Pos::new(HPos::Right, VPos::Center),
            TICK,
            BLACK,
            false,
        )?;
    }
    if has(x_desc) {
        rich_text(
            area,
            x_desc,
            (mid_x, y1 + (x_area - desc / 2) as i32 - pxi(2)),
            Pos::new(HPos::Center, VPos::Center),
            AXIS_DESC,
            BLACK,
            false,
        )?;
    }
    if has(y_desc) {
        rich_text(
            area,
            y_desc,
            (x0 - (y_area - desc / 2) as i32 + pxi(2), (y0 + y1) / 2),
            Pos::new(HPos::Center, VPos::Center),
            AXIS_DESC,
            BLACK,
            true,
        )?;
    }
    Ok(c)
}

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

/// A vertical colour bar filling `area`: the viridis scale from `lo` (bottom) to `hi` (top),
/// its ticks left of it, `label` reading upwards on its right.
pub fn colour_bar_vertical<DB: Backend>(
    area: &DrawingArea<DB, Shift>,
    label: &str,
    lo: f64,
    hi: f64,
) -> Result<()> {
    let (_, height) = area.dim_in_pixel();
    let (tick, desc) = (font_px(TICK), font_px(AXIS_DESC));
    // ticks as dense as the bar's height allows (at least four labelled: plotters keeps to
    // 1-2-5 steps below the count asked, so ask for eight)
    let n = (height * 2 / (tick * 3)).clamp(8, 12) as usize;
    let fy = tick_formatter(&(lo..hi), n);
    let widest = (0..=20)
        .map(|k| text_width(&fy(&(lo + (hi - lo) * k as f64 / 20.0)), tick))
        .max()
        .unwrap_or(0);
    let mut c = ChartBuilder::on(area)
        .margin_top(tick)
        .margin_bottom(tick)
        .margin_right(desc * 3 / 2)
        .y_label_area_size(widest + px(12))
        .build_cartesian_2d(0.0..1.0, lo..hi)
        .map_err(pe)?;
    c.configure_mesh()
        .disable_x_axis()
        .disable_mesh()
        .y_labels(n)
        .y_label_formatter(&fy)
        .label_style((FONT, tick))
        .draw()
        .map_err(pe)?;
    let steps = 64;
    c.draw_series((0..steps).map(|i| {
        let (a, b) = (i as f64 / steps as f64, (i + 1) as f64 / steps as f64);
        Rectangle::new(
            [(0.0, lo + a * (hi - lo)), (1.0, lo + b * (hi - lo))],
            viridis((i as f64 + 0.5) / steps as f64).filled(),
        )
    }))
    .map_err(pe)?;
    let (rx, ry) = c.plotting_area().get_pixel_range();
    let (bx, by) = area.get_base_pixel();
    rich_text(
        area,
        label,
        (
            rx.end - bx + (desc * 3 / 4) as i32,
            (ry.start + ry.end) / 2 - by,
        ),
        Pos::new(HPos::Center, VPos::Center),
        AXIS_DESC,
        BLACK,
        true,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pictures_written_here_are_signed_and_others_are_not() {
        let svg = "<svg width=\"20\" height=\"10\" xmlns=\"http://www.w3.org/2000/svg\">\
                   <rect x=\"0\" y=\"0\" width=\"5\" height=\"5\" fill=\"black\"/></svg>";
        let png = rasterise(svg).unwrap();
        assert!(signed(&png));
        assert!(signed(svg_file(svg).as_bytes()));
        // the same picture without the signature: a PNG of another program, a plain SVG
        let mut foreign = png.clone();
        let at = foreign.windows(4).position(|w| w == b"tEXt").unwrap();
        foreign[at + 4] = b's';
        assert!(!signed(&foreign));
        assert!(!signed(svg.as_bytes()));
        assert!(!signed(b"x,y\n1,2\n"));
        assert!(!signed(b""));
    }

    #[test]
    fn subscripts_parse_from_markup_and_symbols_only() {
        let r = |s: &str| rich_runs(s);
        let run = |t: &str, sub: bool| (t.to_string(), sub);
        assert_eq!(
            r("U_eff(A0)"),
            [run("U", false), run("eff", true), run("(A0)", false)]
        );
        assert_eq!(
            r("ΔU_1 and D_c"),
            [
                run("ΔU", false),
                run("1", true),
                run(" and D", false),
                run("c", true)
            ]
        );
        assert_eq!(r("A_{01}"), [run("A", false), run("01", true)]);
        assert_eq!(
            r("dA_{0}/dt"),
            [run("dA", false), run("0", true), run("/dt", false)]
        );
        // not a one-letter symbol: left alone
        assert_eq!(r("fig14_folds.csv"), [run("fig14_folds.csv", false)]);
        assert_eq!(r("a_"), [run("a_", false)]);
    }

    #[test]
    fn text_is_scaled_to_print_at_seven_points_and_even() {
        for width in [600, 1120, 1400, 1880, 3000] {
            let _g = ScaleGuard::for_width(width);
            for base in [TICK, LABEL, AXIS_DESC, CAPTION, HEADING_LINE, HEADING_TITLE] {
                let size = font_px(base);
                assert_eq!(size % 2, 0);
                assert!(
                    size as f64 / 1.24 >= width as f64 / 72.0,
                    "{width}: {base} → {size}"
                );
            }
            assert!(sub_size(font_px(CAPTION)) as f64 / 1.24 >= width as f64 / 72.0);
        }
        assert_eq!(scale(), 1.0, "the guard restores the scale");
    }
}
