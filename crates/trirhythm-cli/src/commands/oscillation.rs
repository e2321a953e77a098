//! `trirhythm oscillation`: where the rest state of Eq. (1) at D = 0 gives way to an
//! oscillation (Hopf boundary), by simulation, by averaging (f′(0) = 0 of Eq. 18) and by the
//! exact linearisation; or, with `--grid`, a whole plane classified.

use crate::args::{parse_axis, ImpactMemoryArg, ModelFileArg, Named, OnOff, ParamArgs, SimFormat};
use crate::error::{allowed, bad};
use crate::io::progress::Bar;
use crate::io::{emit, jnum, num, params_json, pretty, progress, Csv, Report};
use anyhow::Result;
use clap::{Args, ValueEnum};
use serde_json::json;
use std::path::PathBuf;
use trirhythm::analysis::oscillation::{
    boundary, classify_plane, Boundary, Classifier, Method, Plane, Search,
};
use trirhythm::engine::Problem;
use trirhythm::model::Params;
use trirhythm::theory::averaging::Variant;
use trirhythm_paper::views;

/// Which boundary.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum MethodArg {
    /// Predictor–corrector runs from a small amplitude, bracketed along y.
    Simulation,
    /// f′(0) = 0 of the averaged drift (Eq. 18), in the --variant chosen.
    Averaging,
    /// The exact linearisation at U = 0 (no wall: any λ; wall: λ = 1 only).
    Exact,
    /// The three (boundary mode only).
    All,
}

/// Arguments of `oscillation`.
#[derive(Debug, Args)]
pub struct OscillationArgs {
    #[command(flatten)]
    pub params: ParamArgs,
    #[command(flatten)]
    pub file: ModelFileArg,
    /// Abscissae: KEY=START:STOP:COUNT (COUNT = 1 with START = STOP for one abscissa).
    #[arg(long, value_name = "KEY=START:STOP:COUNT", allow_hyphen_values = true)]
    pub x: String,
    /// The parameter whose boundary value is sought, and the interval: KEY=LO:HI
    /// (with --grid: KEY=LO:HI:COUNT, the plane's ordinates).
    #[arg(long, value_name = "KEY=LO:HI", allow_hyphen_values = true)]
    pub y: String,
    /// The wall at U = 0.
    #[arg(long, value_enum, default_value_t = OnOff::On)]
    pub barrier: OnOff,
    /// Which boundary (default: all; with --grid: simulation).
    #[arg(long, value_enum)]
    pub method: Option<MethodArg>,
    /// Classify every point of the plane x × y instead (CSV x,y,oscillates).
    #[arg(long)]
    pub grid: bool,
    /// Width of the simulated bracket relative to the boundary value, in (0, 0.1].
    #[arg(long, default_value_t = 1e-3, allow_hyphen_values = true)]
    pub tolerance: f64,
    /// Step Δt of the simulations, in [1e-4, 0.1].
    #[arg(long, default_value_t = 0.01, allow_hyphen_values = true)]
    pub dt: f64,
    /// What the memory does at impacts.
    #[arg(long = "impact-memory", value_enum, default_value_t = ImpactMemoryArg::Continuous)]
    pub impact_memory: ImpactMemoryArg,
    /// Simulations stepped together: 1 (one after the other), 4 or 8 (default 8: the runs of a
    /// row of the grid, or the probes of up to four abscissae's searches). The results are the
    /// same bits for every choice.
    #[arg(long, allow_hyphen_values = true)]
    pub lanes: Option<usize>,
    /// Output format.
    #[arg(long, value_enum, default_value_t = SimFormat::Csv)]
    pub format: SimFormat,
    /// Write to this file (atomically) instead of standard output.
    #[arg(long)]
    pub out: Option<PathBuf>,
}

/// Most abscissae of one boundary, and most points of a classified plane.
const MAX_ABSCISSAE: usize = 100_000;
const MAX_CELLS: usize = 1_000_000;

/// Parse `KEY=START:STOP:COUNT`, COUNT ≥ 1 (COUNT = 1 needs START = STOP).
fn parse_abscissae(s: &str) -> Result<(String, Vec<f64>)> {
    let parts: Vec<&str> = s
        .split_once('=')
        .map_or(vec![], |(_, r)| r.split(':').collect());
    if parts.len() == 3 && parts[2].trim() == "1" {
        let num = |t: &str| -> Result<f64> {
            match t.trim().parse::<f64>() {
                Ok(v) if v.is_finite() => Ok(v),
                _ => bad(format!("--x: `{t}` is not a finite number (in `{s}`)")),
            }
        };
        let (a, b) = (num(parts[0])?, num(parts[1])?);
        if a != b {
            return bad(format!(
                "--x: COUNT = 1 is one abscissa: START = {a} and STOP = {b} must be equal"
            ));
        }
        let key = s.split_once('=').map_or("", |(k, _)| k.trim());
        return Ok((key.to_string(), vec![a]));
    }
    let (key, g) = parse_axis(s, "--x", true)?;
    allowed(
        g.count <= MAX_ABSCISSAE,
        "--x: COUNT",
        g.count,
        &format!("1 to {MAX_ABSCISSAE}"),
    )?;
    Ok((key, g.points()))
}

fn method_of(m: MethodArg, classifier: Classifier, variant: Variant) -> Method {
    match m {
        MethodArg::Simulation | MethodArg::All => Method::Simulation(classifier),
        MethodArg::Averaging => Method::Averaging(variant),
        MethodArg::Exact => Method::Exact,
    }
}

/// What both modes share: the plane, the classifier, the header lines.
struct Setup {
    base: Params,
    variant: Variant,
    kx: String,
    ky: String,
    plane: Plane,
    classifier: Classifier,
    header: Vec<String>,
}

impl OscillationArgs {
    /// Refuse, before any work, an option typed that the chosen mode or method does not use:
    /// the simulations' step, impact memory and lanes with `--method averaging` or `exact`;
    /// the bracket's `--tolerance` with `--grid` (each point is classified, no boundary
    /// bracketed).
    pub fn refuse_unused(&self, given: &crate::args::Given) -> Result<()> {
        if matches!(self.method, Some(MethodArg::Averaging | MethodArg::Exact)) {
            given.refuse(
                &[
                    ("dt", "--dt"),
                    ("impact_memory", "--impact-memory"),
                    ("lanes", "--lanes"),
                ],
                "--method simulation or all",
                "the averaging and exact boundaries simulate nothing",
            )?;
        }
        if self.grid {
            given.refuse(
                &[("tolerance", "--tolerance")],
                "boundary mode, without --grid",
                "with --grid each point is classified and no boundary is bracketed",
            )?;
        }
        Ok(())
    }

    /// Check and convert the flags (the checks the library does not make: a noise-free
    /// system, two different axes, the ranges this command is tested in).
    fn setup(&self) -> Result<Setup> {
        let base = self.params.resolve()?;
        let variant = self.params.variant();
        allowed(
            self.tolerance > 0.0 && self.tolerance <= 0.1,
            "--tolerance",
            num(self.tolerance),
            "(0, 0.1]",
        )?;
        allowed(
            self.dt >= 1e-4 && self.dt <= 0.1,
            "--dt",
            num(self.dt),
            "[1e-4, 0.1]",
        )?;
        if base.noise_intensity != 0.0 {
            return bad(format!(
                "--param D = {}: the oscillation boundary is that of the noise-free system; allowed: D = 0",
                num(base.noise_intensity)
            ));
        }
        let (kx, xs) = parse_abscissae(&self.x)?;
        let (ky, gy) = parse_axis(&self.y, "--y", self.grid)?;
        if kx == ky {
            return bad(format!(
                "--x and --y name the same parameter `{kx}`: choose two different keys"
            ));
        }
        if kx == "D" || ky == "D" {
            return bad("--x/--y: D cannot be an axis (the oscillation boundary is at D = 0)");
        }
        let mut classifier = Classifier::default();
        classifier.method.dt = self.dt;
        classifier.method.impact_memory = self.impact_memory.into();
        classifier.lanes = crate::args::lanes(self.lanes)?;
        let template = Problem::from_params(&base)?.with_barrier(self.barrier.into())?;
        let plane = Plane::new(&template, (&kx, xs), (&ky, gy.start, gy.stop))?;
        let header = vec![
            format!("trirhythm oscillation: boundary of {ky} (rest below/above) along {kx}"),
            format!("params: {}", base.describe()),
            format!("barrier: {}", self.barrier.name()),
            format!("averaging variant: {}", variant.name()),
            views::classifier_note(&classifier),
        ];
        Ok(Setup {
            base,
            variant,
            kx,
            ky,
            plane,
            classifier,
            header,
        })
    }
}

/// `oscillation`.
pub fn oscillation(args: &OscillationArgs) -> Result<()> {
    let s = args.setup()?;
    // a read-only destination is refused before the grid or the boundaries are computed
    if let Some(out) = &args.out {
        crate::io::files::check_writable(out, "--out")?;
    }
    let text = if args.grid {
        let (_, gy) = parse_axis(&args.y, "--y", true)?;
        classify(args, s, &gy.points())?
    } else {
        boundaries(args, s)?
    };
    emit(args.out.as_deref(), &text)
}

/// `--grid`: every point of the plane x × y classified.
fn classify(args: &OscillationArgs, mut s: Setup, ys: &[f64]) -> Result<String> {
    let m = match args.method.unwrap_or(MethodArg::Simulation) {
        MethodArg::All => return bad(
            "--method all needs boundary mode: with --grid choose simulation, averaging or exact",
        ),
        m => m,
    };
    let (kx, ky, plane) = (&s.kx, &s.ky, &s.plane);
    let cells = plane.x.len().saturating_mul(ys.len());
    if cells > MAX_CELLS {
        return bad(format!(
            "--grid: {} × {} = {cells} points; at most {MAX_CELLS} are classified",
            plane.x.len(),
            ys.len()
        ));
    }
    let method = method_of(m, s.classifier, s.variant);
    let cells = classify_plane(plane, ys, &method, &Bar::new("oscillation grid"))?;
    if let Some(c) = cells.iter().find(|c| c.rate.is_nan()) {
        return bad(format!(
            "--method exact: the exact linearisation with the wall is known at λ = 1 only (at {kx} = {}, {ky} = {} λ = {}); use --barrier off, or simulation",
            num(c.x),
            num(c.y),
            num(plane.at(c.x, c.y)?.lambda)
        ));
    }
    let simulations = if matches!(method, Method::Simulation(_)) {
        cells.len()
    } else {
        0
    };
    Ok(match args.format {
        SimFormat::Csv => {
            s.header.push(format!("method: {}", method.name()));
            s.header.push(format!("simulations: {simulations}"));
            let mut csv = Csv::new(&s.header, &["x", "y", "oscillates"]);
            for c in &cells {
                csv.row([num(c.x), num(c.y), u8::from(c.oscillates).to_string()]);
            }
            csv.finish()?
        }
        SimFormat::Json => pretty(&json!({
                "params": params_json(&s.base),
                "barrier": args.barrier.name(),
                "variant": s.variant.name(),
                "method": method.name(),
                "x_key": kx,
                "y_key": ky,
                "dt": jnum(args.dt),
                "simulations": simulations,
                "cells": cells,
        }))?,
    })
}

/// Boundary mode: the boundary along x by each method.
fn boundaries(args: &OscillationArgs, s: Setup) -> Result<String> {
    let methods: Vec<Method> = match args.method.unwrap_or(MethodArg::All) {
        MethodArg::All => vec![
            Method::Simulation(s.classifier),
            Method::Averaging(s.variant),
            Method::Exact,
        ],
        m => vec![method_of(m, s.classifier, s.variant)],
    };
    let search = Search {
        tolerance: args.tolerance,
        ..Default::default()
    };
    let n = s.plane.x.len();
    let bar = progress((n * methods.len()) as u64, "oscillation boundary");
    let mut results: Vec<Boundary> = Vec::new();
    for (i, m) in methods.iter().enumerate() {
        let report = Report(|done: u64, _total: u64| bar.set_position((i * n) as u64 + done));
        results.push(boundary(&s.plane, m, &search, &report)?);
    }
    bar.finish_and_clear();
    let simulations: usize = results.iter().map(|b| b.simulations()).sum();
    let (lo, hi) = s.plane.y_range;
    Ok(match args.format {
        SimFormat::Csv => boundaries_csv(args, s, &results, simulations)?,
        SimFormat::Json => pretty(&json!({
                "params": params_json(&s.base),
                "barrier": args.barrier.name(),
                "variant": s.variant.name(),
                "x_key": s.kx,
                "y_key": s.ky,
                "y_range": [jnum(lo), jnum(hi)],
                "tolerance": jnum(args.tolerance),
                "dt": jnum(args.dt),
                "simulations": simulations,
                "boundaries": results.iter().map(|b| json!({
                    "method": b.method,
                    "simulations": b.simulations(),
                    "points": b.points,
                })).collect::<Vec<_>>(),
        }))?,
    })
}

/// The CSV of boundary mode: `method,x,y,y_lo,y_hi`, the abscissae without a boundary in the
/// header.
fn boundaries_csv(
    args: &OscillationArgs,
    mut s: Setup,
    results: &[Boundary],
    simulations: usize,
) -> Result<String> {
    let (lo, hi) = s.plane.y_range;
    let tol = num(args.tolerance);
    s.header.extend([
        format!("tolerance: simulated bracket y_hi − y_lo ≤ {tol} · y"),
        format!("interval searched: {} ∈ [{}, {}]", s.ky, num(lo), num(hi)),
        format!("simulations: {simulations}"),
    ]);
    Csv::of(&views::boundaries_table(&s.header, &s.kx, results))
}
