//! `trirhythm figure`: a paper figure's data (CSV, JSON) and picture (PNG + SVG); `trirhythm
//! presets`: the parameter sets.

use crate::args::VariantArg;
use crate::error::bad;
use crate::io::progress::Bar;
use crate::io::{stdout_write, write_atomic, Csv};
use crate::render::plot::{save, Picture, VerdictLine};
use anyhow::{Context, Result};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use trirhythm::theory::averaging::Variant;
use trirhythm_paper::table::Table;
use trirhythm_paper::verdict::claims::{judge_figure, ClaimVerdict, Slot};
use trirhythm_paper::verdict::Verdict;
use trirhythm_paper::{Figure, FigureOptions};

#[derive(Debug, clap::Args)]
#[command(
    after_help = "Files, in --out-dir: figNN.csv (the data, parameters and notes in `#` \
    lines), figNN.png and figNN.svg; the map figures also figNN_folds.csv.\n\
    With --data also figNN.json: {\"figure\", \"trirhythm\" (version), \"variant\", \"quick\", \
    \"data\"}, the value the CSV and pictures are drawn from. `figure N --from-data DIR` draws \
    them again from DIR/figNN.json without computing (byte-identical files)."
)]
pub struct FigureArgs {
    /// Figure number, or `all`.
    pub figure: String,
    /// Coarser grids and shorter runs (for CI and previews).
    #[arg(long)]
    pub quick: bool,
    /// Directory for the files.
    #[arg(long, default_value = "out")]
    pub out_dir: PathBuf,
    /// Formula variant of the averaged theory.
    #[arg(long, value_enum, default_value_t = VariantArg::Paper)]
    pub variant: VariantArg,
    /// Also write the figure's data as figNN.json (what the CSV and pictures are drawn from).
    #[arg(long)]
    pub data: bool,
    /// Draw from DIR/figNN.json (written by --data) instead of computing; the variant and
    /// quality are those of the file.
    #[arg(long, value_name = "DIR", conflicts_with_all = ["quick", "variant"])]
    pub from_data: Option<PathBuf>,
}

/// `figure`: compute (or read back) and draw one figure or all.
pub fn figure(args: &FigureArgs) -> Result<()> {
    let registry = registry();
    let available = registry
        .iter()
        .map(|r| r.number.to_string())
        .collect::<Vec<_>>()
        .join(", ");
    if args.out_dir.exists() && !args.out_dir.is_dir() {
        return bad(format!(
            "--out-dir {}: exists and is not a directory",
            args.out_dir.display()
        ));
    }
    let selected: Vec<_> = if args.figure == "all" {
        registry.iter().collect()
    } else {
        let Ok(n) = args.figure.parse::<u32>() else {
            return bad(format!(
                "figure: `{}` is not a figure number (the paper has figures 1 to 19; \
                 available: {available}, or all)",
                args.figure
            ));
        };
        let Some(r) = registry.iter().find(|r| r.number == n) else {
            return bad(format!(
                "figure {n}: no such figure (the paper has figures 1 to 19; available: \
                 {available}, or all)"
            ));
        };
        vec![r]
    };
    let request = match &args.from_data {
        None => Request::Compute(FigureOptions {
            quick: args.quick,
            variant: args.variant.into(),
        }),
        Some(dir) => Request::FromData(dir),
    };
    for entry in selected {
        let start = std::time::Instant::now();
        let files = (entry.make)(&request, &args.out_dir, args.data)?;
        eprintln!(
            "figure {} ({}): {:.1} s",
            entry.number,
            entry.title,
            start.elapsed().as_secs_f64()
        );
        let text: String = files.iter().map(|f| format!("{}\n", f.display())).collect();
        stdout_write(text.as_bytes())?;
    }
    Ok(())
}

/// `presets`: the parameter sets with their notes.
pub fn presets() -> Result<()> {
    let mut text = String::new();
    for p in trirhythm::model::presets() {
        text.push_str(&format!(
            "{:8} {}\n         {}\n",
            p.name,
            p.description,
            p.params.describe()
        ));
        for n in p.notes {
            text.push_str(&format!("         note: {n}\n"));
        }
    }
    stdout_write(text.as_bytes())
}

/// `dir/figNN` (without extension).
fn stem(dir: &Path, n: u32) -> PathBuf {
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

/// Where each selected figure's data comes from (the files go to `--out-dir`, with
/// `figNN.json` when `--data` is set).
enum Request<'a> {
    /// Computed with these options.
    Compute(FigureOptions),
    /// Read from `DIR/figNN.json`.
    FromData(&'a Path),
}

/// One figure of the registry: its number, title and how to make it.
struct Entry {
    /// The paper's figure number.
    pub number: u32,
    /// What it shows.
    pub title: &'static str,
    /// Make the figure's files; returns the paths written.
    pub make: fn(&Request, &Path, bool) -> Result<Vec<PathBuf>>,
}

fn entry<F: Slot + Picture>() -> Entry {
    Entry {
        number: F::NUMBER,
        title: F::TITLE,
        make: make::<F>,
    }
}

/// The figures this build can make, by number.
fn registry() -> Vec<Entry> {
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

fn make<F: Slot + Picture>(request: &Request, out_dir: &Path, data: bool) -> Result<Vec<PathBuf>> {
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
    Ok(files)
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
