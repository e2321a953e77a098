//! Commands of the bifurcation structure: `map` (two-parameter classification with exact fold
//! curves; with `--simulate`, the P-bifurcation map by Monte Carlo beside the theory's) and
//! `branches` (one-parameter branch diagrams by continuation).

use crate::args::{parse_axis, Format, Given, OutputArgs, ParamArgs, TheoryModelArg};
use crate::error::bad;
use crate::io::files::check_destination;
use crate::io::{emit, num, params_json, progress, Csv, Stream, Temporary};
use anyhow::{Context, Result};
use clap::{Args, ValueEnum};
use serde::Serialize;
use serde_json::Value;
use std::io::Write;
use std::path::{Path, PathBuf};
use trirhythm::theory::bifurcation::{
    branches as trace_branches, classify, trace_folds, trace_printed_eq37, Axis, BranchDiagram,
    Folds, Map, Plane, What,
};
use trirhythm_paper::views;

mod simulated;
pub use simulated::{SimulateMapArgs, SIMULATION_FLAGS};

/// What a map counts.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum, Default)]
pub enum WhatArg {
    /// Stable limit cycles of the noise-free averaged system (roots of f, Eq. 18).
    #[default]
    Rhythmicity,
    /// Maxima of the stationary amplitude PDF P(A) (roots of m1, Eq. 26; needs D > 0).
    Modes,
}

same_variants!(WhatArg => What: Rhythmicity, Modes);

/// Arguments of `map`.
#[derive(Debug, Args)]
pub struct MapArgs {
    #[command(flatten)]
    pub params: ParamArgs,
    #[command(flatten)]
    pub file: TheoryModelArg,
    /// Horizontal axis: KEY=START:STOP:COUNT (KEY as for --param).
    #[arg(long, value_name = "KEY=START:STOP:COUNT", allow_hyphen_values = true)]
    pub x: String,
    /// Vertical axis: KEY=START:STOP:COUNT.
    #[arg(long, value_name = "KEY=START:STOP:COUNT", allow_hyphen_values = true)]
    pub y: String,
    /// What to count at each point.
    #[arg(long, value_enum, default_value_t = WhatArg::Rhythmicity)]
    pub what: WhatArg,
    /// Trace the fold curves (f = ∂f/∂A = 0, or m1 = ∂m1/∂A = 0 for modes) exactly.
    #[arg(long)]
    pub folds: bool,
    /// With --what modes, paper variant: also trace the printed Eq. 36–37 (implies --folds).
    #[arg(long)]
    pub printed_eq37: bool,
    /// CSV of the fold polylines `curve,system,x,y,amplitude` (default: FILE-folds.csv by --out).
    #[arg(long, value_name = "FILE")]
    pub folds_out: Option<PathBuf>,
    #[command(flatten)]
    pub sim: SimulateMapArgs,
    #[command(flatten)]
    pub output: OutputArgs,
}

impl MapArgs {
    /// Refuse, before any work, an option typed that the chosen map does not use: the
    /// simulation's without `--simulate`; the fold curves and `--what rhythmicity` with it.
    pub fn refuse_unused(&self, given: &Given) -> Result<()> {
        if self.sim.simulate {
            given.refuse(
                &[
                    ("folds", "--folds"),
                    ("printed_eq37", "--printed-eq37"),
                    ("folds_out", "--folds-out"),
                ],
                "the theory's map (without --simulate)",
                "",
            )?;
            if given.typed("what") && self.what != WhatArg::Modes {
                return bad(
                    "--simulate counts the modes of P(A): --what rhythmicity has no simulated \
                     counterpart (leave --what out, or give --what modes)",
                );
            }
            Ok(())
        } else {
            given.refuse(SIMULATION_FLAGS, "--simulate", "")
        }
    }
}

/// Where the fold curves of a CSV map go, settled before the work starts: `--folds-out`, or
/// `FILE-folds.csv` next to `--out` (none with JSON, where they are part of the document).
fn folds_destination(args: &MapArgs) -> Result<Option<PathBuf>> {
    if args.output.format == Format::Json || !(args.folds || args.printed_eq37) {
        return Ok(None);
    }
    let path = match (&args.folds_out, &args.output.out) {
        (Some(p), _) => p.clone(),
        (None, Some(out)) => {
            let stem = out
                .file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_default();
            out.with_file_name(format!("{stem}-folds.csv"))
        }
        (None, None) => return bad(
            "--folds with CSV on standard output needs --folds-out FILE (or --out FILE, or --format json)",
        ),
    };
    check_destination(&path, "--folds-out")?;
    Ok(Some(path))
}

/// The plane of `map`'s `--x` and `--y` over the resolved parameters (the theory's map and the
/// simulated one alike): the parameters, the plane and the axes' keys.
fn plane_of(args: &MapArgs) -> Result<(trirhythm::Params, Plane, String, String)> {
    let mut params = args.params.clone();
    args.file.paper_base(&mut params, "map")?;
    let base = params.resolve()?;
    let (kx, gx) = parse_axis(&args.x, "--x", true)?;
    let (ky, gy) = parse_axis(&args.y, "--y", true)?;
    let plane = Plane::new(
        &base,
        Axis::new(&kx, gx.start, gx.stop, gx.count)?,
        Axis::new(&ky, gy.start, gy.stop, gy.count)?,
        args.params.variant(),
    )?;
    Ok((base, plane, kx, ky))
}

/// `map`: classification of a parameter plane, with fold curves on request; with
/// `--simulate`, the simulated P-bifurcation map beside the theory's.
pub fn map(args: &MapArgs) -> Result<()> {
    if args.sim.simulate {
        return simulated::map(args);
    }
    let (base, plane, kx, ky) = plane_of(args)?;
    let variant = args.params.variant();
    let what: What = args.what.into();
    // D may be an axis; only a constant D = 0 is an error
    if what == What::Modes && base.noise_intensity <= 0.0 && kx != "D" && ky != "D" {
        return bad("--what modes needs noise: set D > 0 (e.g. --param D=0.1)");
    }
    let folds_path = folds_destination(args)?;
    let bar = progress(plane.y.count as u64, "map");
    let m = classify(&plane, what, &|done, _| bar.set_position(done as u64));
    bar.finish_and_clear();
    let mut sets: Vec<Folds> = Vec::new();
    if args.folds || args.printed_eq37 {
        sets.push(trace_folds(&m));
    }
    if args.printed_eq37 {
        sets.push(trace_printed_eq37(&m)?);
    }
    if args.output.format == Format::Json {
        let doc = views::MapView::of(params_json(&base), &m, &sets);
        return emit(
            args.output.out.as_deref(),
            &(serde_json::to_string(&doc)? + "\n"),
        );
    }
    let header = views::map_notes(&base, variant, what, (&kx, &ky), &m, &sets);
    write_map_csv(args, &header, &plane, &m, &sets, folds_path.as_deref())
}

/// The map streamed to its output as `x,y,count`; the fold curves into a temporary that is
/// renamed only after the map is complete, so a failing main output leaves no folds file.
fn write_map_csv(
    args: &MapArgs,
    header: &[String],
    plane: &Plane,
    m: &Map,
    sets: &[Folds],
    folds_path: Option<&Path>,
) -> Result<()> {
    let mut stream = Stream::open(args.output.out.as_deref())?;
    let w = stream.writer();
    w.write_all(Csv::new(header, &["x", "y", "count"]).finish()?.as_bytes())?;
    for iy in 0..plane.y.count {
        let y = num(plane.y.value(iy));
        for ix in 0..plane.x.count {
            writeln!(w, "{},{y},{}", num(plane.x.value(ix)), m.count(ix, iy))?;
        }
    }
    let folds = match folds_path {
        Some(path) if !sets.is_empty() => {
            let mut fc = Csv::new(header, &["curve", "system", "x", "y", "amplitude"]);
            let refs: Vec<&Folds> = sets.iter().collect();
            for row in trirhythm_paper::maps::fold_rows(&[], &refs) {
                fc.row(row);
            }
            let (tmp, mut fw) = Temporary::create(path)?;
            fw.write_all(fc.finish()?.as_bytes())
                .and_then(|()| fw.flush())
                .with_context(|| format!("writing {}", tmp.path().display()))?;
            Some(tmp)
        }
        _ => None,
    };
    stream.finish()?;
    folds.map_or(Ok(()), Temporary::commit)
}

/// Arguments of `branches`.
#[derive(Debug, Args)]
pub struct BranchArgs {
    #[command(flatten)]
    pub params: ParamArgs,
    #[command(flatten)]
    pub file: TheoryModelArg,
    /// The swept parameter: KEY=START:STOP.
    #[arg(long, value_name = "KEY=START:STOP", allow_hyphen_values = true)]
    pub x: String,
    /// Cycles (roots of f) or extrema of P(A) (roots of m1).
    #[arg(long, value_enum, default_value_t = WhatArg::Rhythmicity)]
    pub what: WhatArg,
    /// Largest continuation step, as a fraction of the interval (and of the largest A²).
    #[arg(long, default_value_t = 0.004, allow_hyphen_values = true)]
    pub step: f64,
    #[command(flatten)]
    pub output: OutputArgs,
}

/// The `branches` JSON document: the library's diagram with the parameters and variant.
#[derive(Serialize)]
struct BranchDocument<'a> {
    params: Value,
    variant: &'static str,
    #[serde(flatten)]
    diagram: &'a BranchDiagram,
}

/// `branches`: every branch of cycles vs one parameter, traced through its folds.
pub fn branches(args: &BranchArgs) -> Result<()> {
    let mut params = args.params.clone();
    args.file.paper_base(&mut params, "branches")?;
    let base = params.resolve()?;
    let variant = args.params.variant();
    let (key, g) = parse_axis(&args.x, "--x", false)?;
    // the continuation takes at least 1/step steps: bound the work before it starts
    if !(args.step >= 1e-6 && args.step <= 0.1) {
        return bad(format!(
            "--step = {}: allowed range is [1e-6, 0.1] (the fraction of the interval per \
             continuation step)",
            num(args.step)
        ));
    }
    let what: What = args.what.into();
    if what == What::Modes && base.noise_intensity <= 0.0 && key != "D" {
        return bad("--what modes needs noise: set D > 0 (e.g. --param D=0.1)");
    }
    let bd = trace_branches(&base, variant, what, &key, g.start, g.stop, args.step)?;
    let text = match args.output.format {
        Format::Json => {
            let doc = BranchDocument {
                params: params_json(&base),
                variant: variant.name(),
                diagram: &bd,
            };
            serde_json::to_string(&doc)? + "\n"
        }
        Format::Csv | Format::Table => {
            let header = vec![
                format!("params: {}", base.describe()),
                format!("variant: {}", variant.name()),
                format!("what: {}, swept: {key}", what.name()),
            ];
            Csv::of(&views::branches_table(&header, &bd))?
        }
    };
    emit(args.output.out.as_deref(), &text)
}
