//! `trirhythm`: the command-line front end. The library computes; this binary parses
//! arguments, writes files, draws pictures and progress bars.
//!
//! Exit status: 0 on success, 2 for bad input (a parameter out of range, an unknown name, a
//! malformed flag), 1 for anything else (I/O). No partial output file is ever left: every file
//! is written to a temporary sibling and renamed.

mod common;
mod figures;
mod maps;
mod plot;
mod simulate;
mod theory;

use anyhow::Result;
use clap::{Parser, Subcommand};
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Debug, Parser)]
#[command(
    name = "trirhythm",
    version,
    about = "Stochastic fractional-order vibro-impact oscillators with several coexisting limit cycles"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Harmonic-balance equivalents μ1, β1, ω1, β2 (Eq. 5), σ1 and the impact loss rate.
    Equivalents(theory::TheoryArgs),
    /// Limit cycles (roots of f, Eq. 18) or, when D > 0, extrema of P(A) (roots of m1, Eq. 26).
    Cycles(theory::TheoryArgs),
    /// The averaged drift f(A) on a grid (Eq. 18), with df/dA and ΔE (Eq. 20).
    Drift(theory::CurveArgs),
    /// The pseudo-potential U_eff(A) on a grid (Eq. 23), with m1.
    Potential(theory::CurveArgs),
    /// Energy barriers ΔU_i between consecutive extrema of U_eff.
    Barriers(theory::TheoryArgs),
    /// Stationary PDFs: amplitude (Eq. 27), energy (Eq. 29), joint (Eq. 30–31).
    Pdf(theory::PdfArgs),
    /// Simulate one path of Eq. 1 (or Eq. 5 / Eq. 9) with the fractional predictor–corrector.
    Simulate(simulate::SimulateArgs),
    /// Two-parameter map: stable-cycle or P(A)-mode count on a grid (CSV x,y,count), with the
    /// fold curves traced exactly (--folds).
    Map(maps::MapArgs),
    /// One-parameter branch diagram: every cycle branch traced through its folds.
    Branches(maps::BranchArgs),
    /// Reproduce a figure of the paper: data (CSV) and picture (PNG + SVG).
    Figure(FigureArgs),
    /// List the parameter presets (one per figure panel) with their notes.
    Presets,
}

#[derive(Debug, clap::Args)]
struct FigureArgs {
    /// Figure number, or `all`.
    figure: String,
    /// Coarser grids and shorter runs (for CI and previews).
    #[arg(long)]
    quick: bool,
    /// Directory for the files.
    #[arg(long, default_value = "out")]
    out_dir: PathBuf,
    /// Formula variant of the averaged theory.
    #[arg(long, value_enum, default_value_t = common::VariantArg::Paper)]
    variant: common::VariantArg,
}

fn figure(args: &FigureArgs) -> Result<()> {
    let registry = figures::registry();
    let available = registry
        .iter()
        .map(|r| r.0.to_string())
        .collect::<Vec<_>>()
        .join(", ");
    let selected: Vec<_> = if args.figure == "all" {
        registry.iter().collect()
    } else {
        let n: u32 = match args.figure.parse() {
            Ok(n) => n,
            Err(_) => {
                return common::bad(format!(
                    "figure: `{}` is not a figure number (available: {available}, or all)",
                    args.figure
                ))
            }
        };
        match registry.iter().find(|r| r.0 == n) {
            Some(r) => vec![r],
            None => {
                return common::bad(format!(
                    "figure {n} is not available (available: {available}, or all)"
                ))
            }
        }
    };
    let ctx = figures::FigureContext {
        out_dir: args.out_dir.clone(),
        quick: args.quick,
        variant: args.variant.into(),
    };
    for (n, title, run) in selected {
        let start = std::time::Instant::now();
        let files = run(&ctx)?;
        eprintln!(
            "figure {n} ({title}): {:.1} s",
            start.elapsed().as_secs_f64()
        );
        for f in files {
            println!("{}", f.display());
        }
    }
    Ok(())
}

fn presets() -> Result<()> {
    for p in trirhythm::model::presets() {
        println!(
            "{:8} {}\n         {}",
            p.name,
            p.description,
            p.params.describe()
        );
        for n in p.notes {
            println!("         note: {n}");
        }
    }
    Ok(())
}

fn run(cli: Cli) -> Result<()> {
    match &cli.command {
        Command::Equivalents(a) => theory::equivalents(a),
        Command::Cycles(a) => theory::cycles(a),
        Command::Drift(a) => theory::drift(a),
        Command::Potential(a) => theory::potential(a),
        Command::Barriers(a) => theory::barriers(a),
        Command::Pdf(a) => theory::pdf(a),
        Command::Simulate(a) => simulate::simulate(a),
        Command::Map(a) => maps::map(a),
        Command::Branches(a) => maps::branches(a),
        Command::Figure(a) => figure(a),
        Command::Presets => presets(),
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            if common::is_bad_input(&e) {
                ExitCode::from(2)
            } else {
                ExitCode::from(1)
            }
        }
    }
}
