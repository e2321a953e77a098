//! Commands of the bifurcation structure: `map` (two-parameter classification with exact fold
//! curves) and `branches` (one-parameter branch diagrams by continuation).

use crate::args::{parse_axis, Format, OutputArgs, ParamArgs};
use crate::error::bad;
use crate::io::{emit, jnum, num, params_json, progress, Csv, Stream, Temporary};
use anyhow::{Context, Result};
use clap::{Args, ValueEnum};
use serde_json::{json, Value};
use std::io::Write;
use std::path::PathBuf;
use trirhythm::theory::bifurcation::{
    branches as trace_branches, classify, trace_folds, trace_printed_eq37, Axis, BranchDiagram,
    FoldCurve, Folds, Map, Plane, What,
};

/// What a map counts.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum, Default)]
pub enum WhatArg {
    /// Stable limit cycles of the noise-free averaged system (roots of f, Eq. 18).
    #[default]
    Rhythmicity,
    /// Maxima of the stationary amplitude PDF P(A) (roots of m1, Eq. 26; needs D > 0).
    Modes,
}

impl From<WhatArg> for What {
    fn from(w: WhatArg) -> Self {
        match w {
            WhatArg::Rhythmicity => What::Rhythmicity,
            WhatArg::Modes => What::Modes,
        }
    }
}

/// Arguments of `map`.
#[derive(Debug, Args)]
pub struct MapArgs {
    #[command(flatten)]
    pub params: ParamArgs,
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
    /// With --what modes and the paper variant: also trace the paper's printed Eq. 36–37
    /// construction (implies --folds).
    #[arg(long)]
    pub printed_eq37: bool,
    /// CSV file for the fold polylines (columns curve,system,x,y,amplitude); by default
    /// FILE-folds.csv next to --out. In JSON the curves are part of the document.
    #[arg(long, value_name = "FILE")]
    pub folds_out: Option<PathBuf>,
    #[command(flatten)]
    pub output: OutputArgs,
}

fn end_name(e: trirhythm::theory::bifurcation::CurveEnd) -> &'static str {
    e.name()
}

/// Curves as JSON.
pub fn folds_json(f: &Folds) -> Value {
    json!({
        "curves": f.curves.iter().map(curve_json).collect::<Vec<_>>(),
        "cusps": f.cusps.iter().map(|p| json!({"x": jnum(p.x), "y": jnum(p.y), "amplitude": jnum(p.amplitude)})).collect::<Vec<_>>(),
        "seeds": f.seeds,
        "unlocated": f.unlocated,
    })
}

fn curve_json(c: &FoldCurve) -> Value {
    json!({
        "system": c.system.name(),
        "start": end_name(c.start),
        "end": end_name(c.end),
        "points": c.points.iter().map(|p| json!([jnum(p.x), jnum(p.y), jnum(p.amplitude)])).collect::<Vec<_>>(),
    })
}

/// Rows `curve,system,x,y,amplitude` for every curve of `sets`, numbered on across them.
pub fn folds_csv(csv: &mut Csv, prefix: &[String], sets: &[&Folds]) {
    for row in trirhythm_paper::maps::fold_rows(prefix, sets) {
        csv.row(row);
    }
}

/// Build and classify a plane with a progress bar.
pub fn run_map(plane: &Plane, what: What, label: &str) -> Map {
    let bar = progress(plane.y.count as u64, label);
    let m = classify(plane, what, &|done, _| bar.set_position(done as u64));
    bar.finish_and_clear();
    m
}

/// `map`: classification of a parameter plane, with fold curves on request.
pub fn map(args: &MapArgs) -> Result<()> {
    let base = args.params.resolve()?;
    let variant = args.params.variant();
    let (kx, gx) = parse_axis(&args.x, "--x", true)?;
    let (ky, gy) = parse_axis(&args.y, "--y", true)?;
    let plane = Plane::new(
        &base,
        Axis::new(&kx, gx.start, gx.stop, gx.count)?,
        Axis::new(&ky, gy.start, gy.stop, gy.count)?,
        variant,
    )?;
    let what: What = args.what.into();
    if what == What::Modes && base.noise_intensity <= 0.0 {
        // D may be an axis; only a constant D = 0 is an error.
        if kx != "D" && ky != "D" {
            return bad("--what modes needs noise: set D > 0 (e.g. --param D=0.1)");
        }
    }
    // where the fold curves go (CSV), settled before the work starts
    let folds_path = match (args.output.format, args.folds || args.printed_eq37) {
        (Format::Json, _) | (_, false) => None,
        (_, true) => Some(match (&args.folds_out, &args.output.out) {
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
        }),
    };
    if let Some(p) = &folds_path {
        crate::io::files::check_destination(p, "--folds-out")?;
    }
    let m = run_map(&plane, what, "map");
    let mut sets: Vec<Folds> = Vec::new();
    if args.folds || args.printed_eq37 {
        sets.push(trace_folds(&m));
    }
    if args.printed_eq37 {
        sets.push(trace_printed_eq37(&m)?);
    }
    let hist = m.histogram();
    let mut header = vec![
        format!("params: {}", base.describe()),
        format!("variant: {}", variant.name()),
        format!(
            "what: {} (count of stable {})",
            what.name(),
            if what == What::Rhythmicity {
                "limit cycles"
            } else {
                "maxima of P(A)"
            }
        ),
        format!("x: {kx}, y: {ky}"),
        format!(
            "points with count 0, 1, 2, 3, >=4: {}, {}, {}, {}, {}",
            hist[0], hist[1], hist[2], hist[3], hist[4]
        ),
    ];
    for f in &sets {
        header.push(format!(
            "fold curves ({}): {} traced from {} seeds, {} cusps",
            f.curves.first().map(|c| c.system.name()).unwrap_or("-"),
            f.curves.len(),
            f.seeds,
            f.cusps.len()
        ));
    }
    match args.output.format {
        Format::Json => {
            let (nx, ny) = (plane.x.count, plane.y.count);
            let counts: Vec<Value> = (0..ny)
                .map(|iy| Value::Array((0..nx).map(|ix| json!(m.count(ix, iy))).collect()))
                .collect();
            let mut doc = json!({
                "params": params_json(&base),
                "variant": variant.name(),
                "what": what.name(),
                "x": {"key": kx, "values": plane.x.values().into_iter().map(jnum).collect::<Vec<_>>()},
                "y": {"key": ky, "values": plane.y.values().into_iter().map(jnum).collect::<Vec<_>>()},
                "counts": counts,
                "histogram": hist,
            });
            if !sets.is_empty() {
                doc["folds"] = folds_json(&sets[0]);
            }
            if sets.len() > 1 {
                doc["printed_eq37"] = folds_json(&sets[1]);
            }
            let mut s = serde_json::to_string(&doc)?;
            s.push('\n');
            emit(args.output.out.as_deref(), &s)
        }
        Format::Csv | Format::Table => {
            // the map streamed to its output; the fold curves into a temporary that is renamed
            // only after the map is complete, so a failing main output leaves no folds file
            let mut stream = Stream::open(args.output.out.as_deref())?;
            let w = stream.writer();
            w.write_all(Csv::new(&header, &["x", "y", "count"]).finish()?.as_bytes())?;
            for iy in 0..plane.y.count {
                let y = num(plane.y.value(iy));
                for ix in 0..plane.x.count {
                    writeln!(w, "{},{y},{}", num(plane.x.value(ix)), m.count(ix, iy))?;
                }
            }
            let folds = match &folds_path {
                Some(path) if !sets.is_empty() => {
                    let mut fc = Csv::new(&header, &["curve", "system", "x", "y", "amplitude"]);
                    let refs: Vec<&Folds> = sets.iter().collect();
                    folds_csv(&mut fc, &[], &refs);
                    let (tmp, mut fw) = Temporary::create(path)?;
                    fw.write_all(fc.finish()?.as_bytes())
                        .and_then(|()| fw.flush())
                        .with_context(|| format!("writing {}", tmp.path().display()))?;
                    Some(tmp)
                }
                _ => None,
            };
            stream.finish()?;
            match folds {
                Some(tmp) => tmp.commit(),
                None => Ok(()),
            }
        }
    }
}

/// Arguments of `branches`.
#[derive(Debug, Args)]
pub struct BranchArgs {
    #[command(flatten)]
    pub params: ParamArgs,
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

/// Compute a branch diagram.
pub fn branch_diagram(
    base: &trirhythm::Params,
    variant: trirhythm::theory::averaging::Variant,
    what: What,
    key: &str,
    start: f64,
    stop: f64,
    step: f64,
) -> Result<BranchDiagram> {
    Ok(trace_branches(base, variant, what, key, start, stop, step)?)
}

/// `branches`: every branch of cycles vs one parameter, traced through its folds.
pub fn branches(args: &BranchArgs) -> Result<()> {
    let base = args.params.resolve()?;
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
    let bd = branch_diagram(&base, variant, what, &key, g.start, g.stop, args.step)?;
    match args.output.format {
        Format::Json => {
            let doc = json!({
                "params": params_json(&base),
                "variant": variant.name(),
                "what": what.name(),
                "key": key,
                "branches": bd.branches.iter().map(|b| json!({
                    "start": end_name(b.start),
                    "end": end_name(b.end),
                    "points": b.points.iter().map(|p| json!({"param": jnum(p.param), "amplitude": jnum(p.amplitude), "stable": p.stable})).collect::<Vec<_>>(),
                })).collect::<Vec<_>>(),
                "folds": bd.folds.iter().map(|f| json!({"param": jnum(f.0), "amplitude": jnum(f.1)})).collect::<Vec<_>>(),
                "hopf": bd.hopf.iter().map(|&h| jnum(h)).collect::<Vec<_>>(),
            });
            let mut s = serde_json::to_string(&doc)?;
            s.push('\n');
            emit(args.output.out.as_deref(), &s)
        }
        Format::Csv | Format::Table => {
            let mut header = vec![
                format!("params: {}", base.describe()),
                format!("variant: {}", variant.name()),
                format!("what: {}, swept: {key}", what.name()),
            ];
            for f in &bd.folds {
                header.push(format!("fold: {key} = {}, A = {}", num(f.0), num(f.1)));
            }
            for h in &bd.hopf {
                header.push(format!("branch reaches A = 0 at {key} = {}", num(*h)));
            }
            let mut csv = Csv::new(&header, &["branch", "param", "amplitude", "stable"]);
            for (i, b) in bd.branches.iter().enumerate() {
                for p in &b.points {
                    csv.row([
                        i.to_string(),
                        num(p.param),
                        num(p.amplitude),
                        u8::from(p.stable).to_string(),
                    ]);
                }
            }
            emit(args.output.out.as_deref(), &csv.finish()?)
        }
    }
}
