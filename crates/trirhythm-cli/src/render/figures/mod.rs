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
//! A figure's data and its computation live in the library crate `trirhythm-paper`
//! ([`trirhythm_paper::Figure`]: number, title, `compute(options, monitor)`, and its data as
//! tables); this module only writes it: each table as a CSV file, and the picture (PNG + SVG)
//! drawn from the data value alone, deterministically, so that rendering the data read back
//! from `figNN.json` gives the same bytes. To add figure NN: its data type, computation and
//! tables in `trirhythm-paper` (`figNN_what.rs` there), then here `figNN_what.rs` with
//! `impl Picture for FigNN` (the drawing, [`crate::render::plot::save`] writes it), and
//! `entry::<FigNN>()` in [`registry`]. Progress of a computation goes to a bar on the terminal
//! through [`Bar`], the library's [`Monitor`].

mod boundary;
/// `impl Picture for $figure`, a newtype of shared data drawn through the view `$view`
/// (`$view(&self.0)` is a [`Picture`]): the map figures and the LLE-against-noise figures.
macro_rules! picture_through {
    ($figure:ty, $view:ident) => {
        impl crate::render::plot::Picture for $figure {
            fn size(&self) -> (u32, u32) {
                $view(&self.0).size()
            }

            fn heading(&self) -> crate::render::plot::Heading {
                $view(&self.0).heading()
            }

            fn draw<DB: plotters::prelude::DrawingBackend>(
                &self,
                root: &plotters::prelude::DrawingArea<DB, plotters::coord::Shift>,
            ) -> anyhow::Result<()>
            where
                DB::ErrorType: 'static,
            {
                $view(&self.0).draw(root)
            }
        }
    };
}

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

use crate::error::bad;
use crate::io::{write_atomic, Csv};
use crate::render::plot::{save, Heading, Picture};
use anyhow::{Context, Result};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use trirhythm::monitor::Monitor;
use trirhythm::theory::averaging::Variant;
use trirhythm_paper::notes::Caption;
use trirhythm_paper::table::Table;
use trirhythm_paper::{Figure, FigureOptions};

/// What every figure gets.
pub struct FigureContext {
    /// Output directory (created if missing).
    pub out_dir: PathBuf,
    /// Coarser grids, shorter runs.
    pub quick: bool,
    /// Formula variant of the averaged theory.
    pub variant: Variant,
}

impl FigureContext {
    /// What the library's computation needs.
    pub fn options(&self) -> FigureOptions {
        FigureOptions {
            quick: self.quick,
            variant: self.variant,
        }
    }
}

/// `dir/figNN` (without extension).
pub fn stem(dir: &Path, n: u32) -> PathBuf {
    dir.join(format!("fig{n:02}"))
}

/// The library's [`Monitor`] drawn as a progress bar on the terminal (hidden otherwise).
pub struct Bar(indicatif::ProgressBar);

impl Bar {
    /// A bar labelled `message`, hidden until the first progress.
    pub fn new(message: &str) -> Bar {
        Bar(crate::io::progress(0, message))
    }
}

impl Monitor for Bar {
    fn progress(&self, done: u64, total: u64) {
        self.0.set_length(total);
        self.0.set_position(done);
    }
}

impl Drop for Bar {
    fn drop(&mut self) {
        self.0.finish_and_clear();
    }
}

/// A caption drawn as a picture's heading.
pub fn heading_of(caption: &Caption) -> Heading {
    Heading {
        title: caption.title.clone(),
        lines: caption.lines.clone(),
    }
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
    /// The value the files are drawn from (the library's data type, serialised).
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

fn entry<F: Figure + Picture>() -> Entry {
    Entry {
        number: F::NUMBER,
        title: F::TITLE,
        make: make::<F>,
    }
}

/// The figures this build can make, by number.
pub fn registry() -> Vec<Entry> {
    vec![
        entry::<trirhythm_paper::fig01_phase_recurrence::Fig01>(),
        entry::<trirhythm_paper::fig02_rhythmicity_planes::Fig02>(),
        entry::<trirhythm_paper::fig03_restitution_planes::Fig03>(),
        entry::<trirhythm_paper::fig04_drift::Fig04>(),
        entry::<trirhythm_paper::fig05_branches::Fig05>(),
        entry::<trirhythm_paper::fig06_fractional_planes::Fig06>(),
        entry::<trirhythm_paper::fig07_pseudo_potential::Fig07>(),
        entry::<trirhythm_paper::fig08_barriers::Fig08>(),
        entry::<trirhythm_paper::fig09_barrier_surfaces::Fig09>(),
        entry::<trirhythm_paper::fig10_pbif_lambda_tau::Fig10>(),
        entry::<trirhythm_paper::fig11_amplitude_lambda::Fig11>(),
        entry::<trirhythm_paper::fig12_pbif_maps::Fig12>(),
        entry::<trirhythm_paper::fig13_pdf_restitution::Fig13>(),
        entry::<trirhythm_paper::fig14_joint_pdf::Fig14>(),
        entry::<trirhythm_paper::fig15_oscillation_boundaries::Fig15>(),
        entry::<trirhythm_paper::fig16_oscillation_regions::Fig16>(),
        entry::<trirhythm_paper::fig17_lle_noise::Fig17>(),
        entry::<trirhythm_paper::fig18_lle_noise_fractional::Fig18>(),
        entry::<trirhythm_paper::fig19_critical_noise::Fig19>(),
    ]
}

fn make<F: Figure + Picture>(request: &Request) -> Result<Vec<PathBuf>> {
    let (file, out_dir, data) = match request {
        Request::Compute { ctx, data } => {
            let file = DataFile {
                figure: F::NUMBER,
                trirhythm: env!("CARGO_PKG_VERSION").to_string(),
                variant: ctx.variant,
                quick: ctx.quick,
                data: F::compute(&ctx.options(), &Bar::new(&format!("figure {}", F::NUMBER)))?,
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
    for table in file.data.tables() {
        files.push(write_table(&stem, &table)?);
    }
    files.extend(save(&file.data, &stem)?);
    Ok(files)
}

/// Write one of a figure's tables as `stem{suffix}.csv` (notes as `#` lines); refuses a table
/// with NaN, or ±∞ outside the columns that allow it. Returns the path written.
fn write_table(stem: &Path, table: &Table) -> Result<PathBuf> {
    let columns: Vec<&str> = table.columns.iter().map(String::as_str).collect();
    let mut csv = Csv::new(&table.notes, &columns);
    for column in &table.infinite {
        csv = csv.allow_infinity(column);
    }
    for row in &table.rows {
        csv.row(row.iter().cloned());
    }
    let name = stem.file_name().unwrap_or_default().to_string_lossy();
    let path = stem.with_file_name(format!("{name}{}.csv", table.suffix));
    write_atomic(&path, csv.finish()?.as_bytes())?;
    Ok(path)
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
