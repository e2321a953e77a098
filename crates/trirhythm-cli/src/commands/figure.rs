//! `trirhythm figure`: a paper figure's data (CSV, JSON) and picture (PNG + SVG); `trirhythm
//! presets`: the parameter sets.

use crate::args::VariantArg;
use crate::error::bad;
use crate::io::stdout_write;
use crate::render::paper::{registry, Request};
use anyhow::Result;
use std::path::PathBuf;
use trirhythm_paper::FigureOptions;

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
        Some(dir) => Request::FromData(dir.as_path()),
    };
    for entry in selected {
        let start = std::time::Instant::now();
        let files = (entry.make)(&request, &args.out_dir, args.data, None)?.files;
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
