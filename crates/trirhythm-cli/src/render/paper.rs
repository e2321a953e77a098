//! A paper figure's files, shared by `trirhythm figure` and `trirhythm report`: compute the
//! figure (or read its `figNN.json` back), write its tables as CSV, its data as JSON when
//! asked, and its picture as PNG + SVG with the verdicts on the claims resting on it drawn
//! under the heading.
//!
//! Method: the data is a `trirhythm_paper` figure value ([`trirhythm_paper::Figure`]); its
//! verdicts come from [`judge_figure`] (the figure's data alone, with the options it was
//! computed with), its caption from the picture's [`Heading`]. A report also collects the data
//! in a [`Figures`] value to judge every claim at once ([`Made`] carries what it shows).
//!
//! Tests: `tests/figure_data.rs` (JSON round trip, `--from-data` byte-identical),
//! `tests/pictures.rs`, `tests/report.rs`.

use crate::error::bad;
use crate::io::progress::Bar;
use crate::io::{write_atomic, Csv};
use crate::render::plot::{save, Heading, Picture, VerdictLine};
use anyhow::{Context, Result};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use trirhythm::theory::averaging::Variant;
use trirhythm_paper::table::Table;
use trirhythm_paper::verdict::claims::{judge_figure, ClaimVerdict, Figures, Slot};
use trirhythm_paper::verdict::Verdict;
use trirhythm_paper::{Figure, FigureOptions};

/// `dir/figNN` (without extension).
pub fn stem(dir: &Path, n: u32) -> PathBuf {
    dir.join(format!("fig{n:02}"))
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

/// Where a figure's data comes from.
#[derive(Clone, Copy)]
pub enum Request<'a> {
    /// Computed with these options.
    Compute(FigureOptions),
    /// Read from `DIR/figNN.json`.
    FromData(&'a Path),
}

/// What making one figure gave: the files written and what the figure says.
pub struct Made {
    /// The paths written, in order (JSON, CSV, PNG, SVG).
    pub files: Vec<PathBuf>,
    /// The picture's heading: title and caption lines (parameters, variant, choices).
    pub heading: Heading,
}

/// Make a figure's files: `(request, out_dir, write figNN.json, collect the data here)`.
pub type Make = fn(&Request, &Path, bool, Option<&mut Figures>) -> Result<Made>;

/// One figure of the registry: its number, title and how to make it.
pub struct Entry {
    /// The paper's figure number.
    pub number: u32,
    /// What it shows.
    pub title: &'static str,
    /// Make the figure's files.
    pub make: Make,
}

fn entry<F: Slot + Picture>() -> Entry {
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

fn make<F: Slot + Picture>(
    request: &Request,
    out_dir: &Path,
    data: bool,
    figures: Option<&mut Figures>,
) -> Result<Made> {
    let file = match request {
        Request::Compute(options) => DataFile {
            figure: F::NUMBER,
            trirhythm: env!("CARGO_PKG_VERSION").to_string(),
            variant: options.variant,
            quick: options.quick,
            data: F::compute(options, &Bar::new(&format!("figure {}", F::NUMBER)))?,
        },
        Request::FromData(dir) => read_data::<F>(dir)?,
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
    let options = FigureOptions {
        quick: file.quick,
        variant: file.variant,
    };
    let (data, verdicts) = judge_figure(file.data, &options);
    files.extend(save(&data, verdict_lines(&verdicts), &stem)?);
    let heading = data.heading();
    if let Some(figures) = figures {
        *F::slot(figures) = Some(data);
    }
    Ok(Made { files, heading })
}

/// The verdicts on a figure's claims as short lines for its picture: the claim's id, the
/// verdict, and for up to three deciding checks what was measured, its statistic and the
/// threshold or the paper's value it was held against (all from the decision); an
/// undetermined verdict's reason is cut to its first clause.
pub fn verdict_lines(verdicts: &[ClaimVerdict]) -> Vec<VerdictLine> {
    use trirhythm_paper::notes::sig;
    verdicts
        .iter()
        .map(|v| {
            let d = &v.decision;
            let mut text = format!("{} — {}", v.claim.id, d.verdict.tag());
            if let Verdict::Undetermined { why } = &d.verdict {
                text.push_str(&format!(" ({})", first_clause(why)));
            }
            let checks: Vec<String> = d
                .deciding(3)
                .iter()
                .map(|c| {
                    format!(
                        "{}: {} {} vs {}",
                        first_clause(&c.what),
                        c.statistic,
                        sig(c.statistic_value, 3),
                        sig(c.threshold, 3)
                    )
                })
                .collect();
            if !checks.is_empty() {
                text.push_str(": ");
                text.push_str(&checks.join("; "));
            }
            VerdictLine {
                tag: d.verdict.tag().to_string(),
                text,
            }
        })
        .collect()
}

/// `text` up to its first `;` or ` (` (with "…" when cut), at most 90 characters.
fn first_clause(text: &str) -> String {
    let cut = [text.find("; "), text.find(" (")]
        .into_iter()
        .flatten()
        .min()
        .unwrap_or(text.len());
    let mut out: String = text[..cut].chars().take(90).collect();
    if out.len() < text.len() {
        out.push('…');
    }
    out
}

/// Write one of a figure's tables as `stem{suffix}.csv` (notes as `#` lines); refuses a table
/// with NaN, or ±∞ outside the columns that allow it. Returns the path written.
fn write_table(stem: &Path, table: &Table) -> Result<PathBuf> {
    let name = stem.file_name().unwrap_or_default().to_string_lossy();
    let path = stem.with_file_name(format!("{name}{}.csv", table.suffix));
    write_atomic(&path, Csv::of(table)?.as_bytes())?;
    Ok(path)
}

/// Read `dir/figNN.json` for figure `F` (bad input when missing, malformed or of another
/// figure).
fn read_data<F: Figure>(dir: &Path) -> Result<DataFile<F>> {
    let path = stem(dir, F::NUMBER).with_extension("json");
    let text = std::fs::read_to_string(&path).or_else(|e| {
        bad(format!(
            "--from-data {}: cannot read {} ({e}); write it with `figure {} --data`",
            dir.display(),
            path.display(),
            F::NUMBER
        ))
    })?;
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
    serde_json::from_str(&text).or_else(|e| {
        bad(format!(
            "--from-data: {} is not the data of figure {} as this version writes it ({e})",
            path.display(),
            F::NUMBER
        ))
    })
}

/// The options `DIR/figNN.json` was computed with, without reading its data: `None` when the
/// file does not exist; bad input when it exists but is not figure data.
pub fn data_options(dir: &Path, n: u32) -> Result<Option<FigureOptions>> {
    let path = stem(dir, n).with_extension("json");
    if !path.exists() {
        return Ok(None);
    }
    #[derive(Deserialize)]
    struct Head {
        figure: u32,
        variant: Variant,
        quick: bool,
    }
    let text = std::fs::read_to_string(&path)
        .or_else(|e| bad(format!("--from-data: cannot read {} ({e})", path.display())))?;
    match serde_json::from_str::<Head>(&text) {
        Ok(h) if h.figure == n => Ok(Some(FigureOptions {
            quick: h.quick,
            variant: h.variant,
        })),
        Ok(h) => bad(format!(
            "--from-data: {} holds the data of figure {}, not {n}",
            path.display(),
            h.figure
        )),
        Err(e) => bad(format!(
            "--from-data: {} is not figure data ({e})",
            path.display()
        )),
    }
}
