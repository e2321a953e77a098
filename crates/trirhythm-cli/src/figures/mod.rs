//! `trirhythm figure N`: one source file, one command and one set of files per paper figure.
//!
//! Each figure writes `figNN.csv` (its data, parameters and notes in `#` header lines) and
//! `figNN.png` + `figNN.svg` into the output directory; with `--data` also `figNN.json`, the
//! value everything else is rendered from. `--quick` trades resolution for speed (used by CI);
//! the default is paper quality. `--from-data DIR` renders from `DIR/figNN.json` without
//! computing anything.
//!
//! # Data first, pictures second
//!
//! A figure is a serialisable data type that implements [`Figure`]:
//! [`Figure::compute`] does all the numerical work and returns the data (the headings and CSV
//! header lines included, as text); [`Figure::render`] writes the CSV, PNG and SVG from that
//! value alone, deterministically, so that rendering the data read back from `figNN.json`
//! gives the same bytes. To add figure NN:
//!
//! 1. write `figNN_what.rs` with `pub struct FigNN { … }` deriving `Serialize, Deserialize`
//!    (plain numbers, strings and the library's serialisable result types, no plotting types),
//!    `impl Figure for FigNN` (number, title, `compute`, `render`), and `impl Picture for FigNN`
//!    for the drawing ([`crate::plot::save`] writes it);
//! 2. add `mod figNN_what;` below and `entry::<figNN_what::FigNN>()` to [`registry`].
//!
//! Figures that share a drawing (the maps, [`mapfig::MapFigure`]) wrap it in a newtype per
//! figure. JSON has no NaN or ±∞: an `f64` field that may hold one takes
//! `#[serde(with = "non_finite")]` (written as the strings `"NaN"`, `"inf"`, `"-inf"`); data
//! that would not read back is refused before `figNN.json` is written.

mod fig01_phase_recurrence;
mod fig02_rhythmicity_planes;
mod fig03_restitution_planes;
mod fig04_drift;
mod fig05_branches;
mod fig06_fractional_planes;
mod fig07_pseudo_potential;
mod fig08_barriers;
mod fig09_barrier_surfaces;
mod fig10_pbif_lambda_tau;
mod fig11_amplitude_lambda;
mod fig12_pbif_maps;
mod fig13_pdf_restitution;
mod fig14_joint_pdf;
mod fig15_oscillation_boundaries;
mod fig16_oscillation_regions;
mod fig17_lle_noise;
mod fig18_lle_noise_fractional;
mod fig19_critical_noise;
mod lle;
mod mapfig;
mod montecarlo;

use crate::common::bad;
use crate::output::write_atomic;
use crate::plot::{save, Heading, Picture};
use anyhow::{Context, Result};
use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use trirhythm::model::Params;
use trirhythm::theory::averaging::Variant;

/// What every figure gets.
pub struct FigureContext {
    /// Output directory (created if missing).
    pub out_dir: PathBuf,
    /// Coarser grids, shorter runs.
    pub quick: bool,
    /// Formula variant of the averaged theory.
    pub variant: Variant,
}

/// `dir/figNN` (without extension).
pub fn stem(dir: &Path, n: u32) -> PathBuf {
    dir.join(format!("fig{n:02}"))
}

/// A paper figure: its data, computed once, and the files rendered from it.
pub trait Figure: Serialize + DeserializeOwned {
    /// The paper's figure number.
    const NUMBER: u32;
    /// What the figure shows, in one line (printed as each figure is made).
    const TITLE: &'static str;
    /// All the numerical work; writes no file.
    fn compute(ctx: &FigureContext) -> Result<Self>;
    /// Write `stem.csv` (and any other data files), `stem.png` and `stem.svg` from the data
    /// alone; returns the paths written.
    fn render(&self, stem: &Path) -> Result<Vec<PathBuf>>;
}

/// `figNN.json`: the figure's data with what produced it.
#[derive(Serialize, Deserialize)]
struct DataFile<F> {
    /// The figure number.
    figure: u32,
    /// The version of trirhythm that computed it.
    trirhythm: String,
    /// The formula variant of the averaged theory.
    variant: Variant,
    /// Quick (coarse) or paper quality.
    quick: bool,
    /// The value [`Figure::render`] draws.
    data: F,
}

/// What `figure` does with each selected figure.
pub enum Request<'a> {
    /// Compute the data and render it; write `figNN.json` too when `data` is set.
    Compute { ctx: &'a FigureContext, data: bool },
    /// Read `figNN.json` from `dir` and render it into `out_dir` (and write the JSON there
    /// again when `data` is set).
    FromData {
        dir: &'a Path,
        out_dir: &'a Path,
        data: bool,
    },
}

/// One figure of the registry: its number, title and how to make it.
pub struct Entry {
    /// The paper's figure number.
    pub number: u32,
    /// What it shows.
    pub title: &'static str,
    /// Make the figure's files; returns the paths written.
    pub make: fn(&Request) -> Result<Vec<PathBuf>>,
}

fn entry<F: Figure>() -> Entry {
    Entry {
        number: F::NUMBER,
        title: F::TITLE,
        make: make::<F>,
    }
}

/// The figures this build can make, by number.
pub fn registry() -> Vec<Entry> {
    vec![
        entry::<fig01_phase_recurrence::Fig01>(),
        entry::<fig02_rhythmicity_planes::Fig02>(),
        entry::<fig03_restitution_planes::Fig03>(),
        entry::<fig04_drift::Fig04>(),
        entry::<fig05_branches::Fig05>(),
        entry::<fig06_fractional_planes::Fig06>(),
        entry::<fig07_pseudo_potential::Fig07>(),
        entry::<fig08_barriers::Fig08>(),
        entry::<fig09_barrier_surfaces::Fig09>(),
        entry::<fig10_pbif_lambda_tau::Fig10>(),
        entry::<fig11_amplitude_lambda::Fig11>(),
        entry::<fig12_pbif_maps::Fig12>(),
        entry::<fig13_pdf_restitution::Fig13>(),
        entry::<fig14_joint_pdf::Fig14>(),
        entry::<fig15_oscillation_boundaries::Fig15>(),
        entry::<fig16_oscillation_regions::Fig16>(),
        entry::<fig17_lle_noise::Fig17>(),
        entry::<fig18_lle_noise_fractional::Fig18>(),
        entry::<fig19_critical_noise::Fig19>(),
    ]
}

fn make<F: Figure>(request: &Request) -> Result<Vec<PathBuf>> {
    let (file, out_dir, data) = match request {
        Request::Compute { ctx, data } => {
            let file = DataFile {
                figure: F::NUMBER,
                trirhythm: env!("CARGO_PKG_VERSION").to_string(),
                variant: ctx.variant,
                quick: ctx.quick,
                data: F::compute(ctx)?,
            };
            (file, ctx.out_dir.as_path(), *data)
        }
        Request::FromData { dir, out_dir, data } => (read_data::<F>(dir)?, *out_dir, *data),
    };
    std::fs::create_dir_all(out_dir).with_context(|| format!("creating {}", out_dir.display()))?;
    let stem = stem(out_dir, F::NUMBER);
    let mut files = Vec::new();
    if data {
        let path = stem.with_extension("json");
        let json = serde_json::to_string(&file).context("serialising the figure's data")?;
        // a file that `--from-data` could not read is not written
        if let Err(e) = serde_json::from_str::<DataFile<F>>(&json) {
            anyhow::bail!(
                "figure {}: its data does not read back from JSON ({e}); {} not written",
                F::NUMBER,
                path.display()
            );
        }
        write_atomic(&path, json.as_bytes())?;
        files.push(path);
    }
    files.extend(file.data.render(&stem)?);
    Ok(files)
}

/// Write a figure's CSV (`stem.csv`) and its pictures (`stem.png`, `stem.svg`); returns the
/// paths written. The usual tail of [`Figure::render`].
pub fn write_figure(picture: &impl Picture, stem: &Path, csv: &str) -> Result<Vec<PathBuf>> {
    let csv_path = stem.with_extension("csv");
    write_atomic(&csv_path, csv.as_bytes())?;
    let mut files = vec![csv_path];
    files.extend(save(picture, stem)?);
    Ok(files)
}

/// Read `dir/figNN.json` for figure `F` (bad input when missing, malformed or of another
/// figure).
fn read_data<F: Figure>(dir: &Path) -> Result<DataFile<F>> {
    let path = stem(dir, F::NUMBER).with_extension("json");
    let text = match std::fs::read_to_string(&path) {
        Ok(t) => t,
        Err(e) => {
            return bad(format!(
                "--from-data {}: cannot read {} ({e}); write it with `figure {} --data`",
                dir.display(),
                path.display(),
                F::NUMBER
            ))
        }
    };
    #[derive(Deserialize)]
    struct Number {
        figure: u32,
    }
    match serde_json::from_str::<Number>(&text) {
        Ok(n) if n.figure == F::NUMBER => {}
        Ok(n) => {
            return bad(format!(
                "--from-data: {} holds the data of figure {}, not {}",
                path.display(),
                n.figure,
                F::NUMBER
            ))
        }
        Err(e) => {
            return bad(format!(
                "--from-data: {} is not figure data ({e})",
                path.display()
            ))
        }
    }
    match serde_json::from_str(&text) {
        Ok(file) => Ok(file),
        Err(e) => bad(format!(
            "--from-data: {} is not the data of figure {} as this version writes it ({e})",
            path.display(),
            F::NUMBER
        )),
    }
}

/// JSON for an `f64` that may be NaN or ±∞ (the library's [`trirhythm::non_finite`]).
pub use trirhythm::non_finite;

/// Serde for a plotters colour, as `[r, g, b]`: `#[serde(with = "super::rgb")]`.
pub mod rgb {
    use plotters::style::RGBColor;
    use serde::{Deserialize, Deserializer, Serialize, Serializer};

    /// `[r, g, b]`.
    pub fn serialize<S: Serializer>(c: &RGBColor, s: S) -> Result<S::Ok, S::Error> {
        [c.0, c.1, c.2].serialize(s)
    }

    /// The inverse of [`serialize`].
    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<RGBColor, D::Error> {
        let [r, g, b] = <[u8; 3]>::deserialize(d)?;
        Ok(RGBColor(r, g, b))
    }
}

/// Header comment lines for a figure's CSV: title, variant, notes.
pub fn csv_header(n: u32, title: &str, ctx: &FigureContext, notes: &[String]) -> Vec<String> {
    let mut h = vec![
        format!("trirhythm figure {n}: {title}"),
        format!("variant: {}", ctx.variant.name()),
    ];
    h.extend(notes.iter().map(|s| format!("note: {s}")));
    h
}

/// A panel's parameters for a header line.
pub fn panel_line(label: &str, p: &Params) -> String {
    format!("panel {label}: {}", p.describe())
}

/// The formula variant, as a heading line: a `--variant consistent` picture says so on itself.
pub fn variant_line(v: Variant) -> String {
    match v {
        Variant::Paper => {
            "averaged theory: the paper's formulas as printed, typos fixed (--variant paper)".into()
        }
        Variant::Consistent => {
            "averaged theory: CONSISTENT variant — exact impact loss ω1A ln r/π, \
                                coloured noise through sgn Z (--variant consistent)"
                .into()
        }
    }
}

/// The user-facing symbol of a parameter key.
pub fn symbol(key: &str) -> &str {
    match key {
        "mu0" => "μ0",
        "omega0" => "ω0",
        "lambda" => "λ",
        "alpha0" => "α0",
        "beta0" => "β0",
        "gamma0" => "γ0",
        "delta0" => "δ0",
        "tau" => "τ",
        k => k,
    }
}

/// "μ0 = 0.01, ω0 = 1, …" for the keys of `p` not in `varying` (those the panels set).
pub fn params_text(p: &Params, varying: &[&str]) -> String {
    p.key_values()
        .into_iter()
        .filter(|(k, _)| !varying.contains(&k.as_str()))
        .map(|(k, v)| format!("{} = {}", symbol(&k), trirhythm::error::Exact(v)))
        .collect::<Vec<_>>()
        .join(", ")
}

/// A figure's heading: "Fig. N: title", the shared parameters (what the panels vary named),
/// the formula variant, then `extra` lines (choices where the paper is silent, methods).
pub fn heading(
    n: u32,
    title: &str,
    ctx: &FigureContext,
    base: &Params,
    varying: &[&str],
    extra: Vec<String>,
) -> Heading {
    let mut lines = vec![format!(
        "{}{}",
        params_text(base, varying),
        if varying.is_empty() {
            String::new()
        } else {
            format!(
                "; per panel: {}",
                varying
                    .iter()
                    .map(|k| symbol(k))
                    .collect::<Vec<_>>()
                    .join(", ")
            )
        }
    )];
    lines.push(variant_line(ctx.variant));
    lines.extend(extra);
    Heading {
        title: format!("Fig. {n}: {title}"),
        lines,
    }
}
