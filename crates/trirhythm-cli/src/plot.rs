//! Pictures: an embedded font, PNG + SVG output of one drawing, chart helpers, colours.
//!
//! A figure implements [`Picture`] once, generically over the plotters backend, and
//! [`save`] renders it to both formats through temporary files and renames.

use crate::output::{write_atomic, Temporary};
use anyhow::{anyhow, Context, Result};
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
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

/// A drawing that can be rendered on any plotters backend.
pub trait Picture {
    /// Size in pixels.
    fn size(&self) -> (u32, u32);
    /// Draw on `root` (already filled white).
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()>
    where
        DB::ErrorType: 'static;
}

/// Render `picture` to `stem.png` and `stem.svg`; returns the paths written.
pub fn save(picture: &impl Picture, stem: &Path) -> Result<Vec<PathBuf>> {
    init_fonts();
    let size = picture.size();
    let png = stem.with_extension("png");
    let reserved = Temporary::reserve(&png)?;
    let tmp = reserved.path().to_path_buf();
    {
        let root = BitMapBackend::new(&tmp, size).into_drawing_area();
        root.fill(&WHITE).map_err(|e| anyhow!("{e}"))?;
        picture
            .draw(&root)
            .with_context(|| format!("drawing {}", png.display()))?;
        root.present()
            .map_err(|e| anyhow!("writing {}: {e}", tmp.display()))?;
    }
    reserved.commit()?;
    let svg = stem.with_extension("svg");
    let mut text = String::new();
    {
        let root = SVGBackend::with_string(&mut text, size).into_drawing_area();
        root.fill(&WHITE).map_err(|e| anyhow!("{e}"))?;
        picture.draw(&root)?;
        root.present().map_err(|e| anyhow!("{e}"))?;
    }
    write_atomic(&svg, text.as_bytes())?;
    Ok(vec![png, svg])
}

/// A chart in `area` with a caption, axis ranges and axis descriptions, mesh drawn.
pub fn chart<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    caption: &str,
    x: Range<f64>,
    y: Range<f64>,
    x_desc: &str,
    y_desc: &str,
) -> Result<ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>>
where
    DB::ErrorType: 'static,
{
    let mut c = ChartBuilder::on(area)
        .caption(caption, (FONT, 20))
        .margin(10)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d(x, y)
        .map_err(|e| anyhow!("{e}"))?;
    c.configure_mesh()
        .x_desc(x_desc)
        .y_desc(y_desc)
        .axis_desc_style((FONT, 16))
        .label_style((FONT, 13))
        .light_line_style(RGBColor(235, 235, 235))
        .draw()
        .map_err(|e| anyhow!("{e}"))?;
    Ok(c)
}

/// Draw the legend of a chart whose series carry labels.
pub fn legend<'a, DB: DrawingBackend + 'a>(
    chart: &mut ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    position: SeriesLabelPosition,
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    chart
        .configure_series_labels()
        .position(position)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font((FONT, 13))
        .draw()
        .map_err(|e| anyhow!("{e}"))
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
