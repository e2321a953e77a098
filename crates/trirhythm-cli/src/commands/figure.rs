//! `trirhythm figure`: a paper figure's data (CSV, JSON) and picture (PNG + SVG); `trirhythm
//! presets`: the parameter sets.

use crate::args::VariantArg;
use crate::error::bad;
use crate::io::{stdout_write, write_atomic};
use crate::render::paper::{registry, Request};
use crate::render::plot::Heading;
use anyhow::Result;
use std::path::PathBuf;
use trirhythm_paper::FigureOptions;

#[derive(Debug, clap::Args)]
#[command(
    after_help = "Files, in --out-dir: figNN.csv (the data, parameters and notes in `#` \
    lines), figNN.png and figNN.svg; the map figures also figNN_folds.csv; `figure all` also \
    index.html, the contact sheet: every picture at print width with its caption.\n\
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
    /// Print each figure's parallel profile to stderr: the CPU time of its tasks, the critical
    /// path (the longest chain of work that must run one after the other) and the speed-up
    /// bound total / critical path.
    #[arg(long, conflicts_with = "from_data")]
    pub profile: bool,
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
        None => Request::Compute {
            options: FigureOptions {
                quick: args.quick,
                variant: args.variant.into(),
            },
            profile: args.profile,
        },
        Some(dir) => Request::FromData(dir.as_path()),
    };
    let all = args.figure == "all";
    let mut sheet = Vec::new();
    for entry in selected {
        let start = std::time::Instant::now();
        let made = (entry.make)(&request, &args.out_dir, args.data, None)?;
        let files = made.files;
        if all {
            sheet.push((entry.number, made.heading));
        }
        eprintln!(
            "figure {} ({}): {:.1} s",
            entry.number,
            entry.title,
            start.elapsed().as_secs_f64()
        );
        if let Some(p) = made.profile {
            eprintln!("figure {} profile: {}", entry.number, p.line());
        }
        let text: String = files.iter().map(|f| format!("{}\n", f.display())).collect();
        stdout_write(text.as_bytes())?;
    }
    if all {
        let path = args.out_dir.join("index.html");
        write_atomic(&path, contact_sheet(&sheet).as_bytes())?;
        stdout_write(format!("{}\n", path.display()).as_bytes())?;
    }
    Ok(())
}

/// The contact sheet of `figure all`: every picture at print width (7 in) with its caption
/// (title, parameters, variant, choices) and its verdicts, to look at the whole set at once.
fn contact_sheet(figures: &[(u32, Heading)]) -> String {
    let esc = |s: &str| {
        s.replace('&', "&amp;")
            .replace('<', "&lt;")
            .replace('>', "&gt;")
    };
    let mut html = String::from(
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\
         <title>trirhythm: the paper's figures</title><style>\
         body{font-family:sans-serif;max-width:7.4in;margin:auto}\
         figure{margin:0 0 3em 0;break-inside:avoid}img{width:7in;border:1px solid #ccc}\
         figcaption{font-size:9pt}p{margin:.2em 0}</style></head><body>\n",
    );
    for (n, h) in figures {
        html.push_str(&format!(
            "<figure id=\"fig{n:02}\"><img src=\"fig{n:02}.png\" alt=\"{}\">\
             <figcaption><p><b>{}</b></p>",
            esc(&h.title),
            esc(&h.title)
        ));
        for l in &h.lines {
            html.push_str(&format!("<p>{}</p>", esc(l)));
        }
        for v in &h.verdicts {
            html.push_str(&format!("<p><i>{}</i>: {}</p>", esc(&v.tag), esc(&v.full)));
        }
        html.push_str("</figcaption></figure>\n");
    }
    html.push_str("</body></html>\n");
    html
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
