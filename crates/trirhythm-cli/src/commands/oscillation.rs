//! `trirhythm oscillation`: where the rest state of Eq. (1) at D = 0 gives way to an
//! oscillation (Hopf boundary), by simulation, by averaging (f′(0) = 0 of Eq. 18) and by the
//! exact linearisation; or, with `--grid`, a whole plane classified.

use crate::args::{Grid, ImpactMemoryArg, OnOff, ParamArgs, SimFormat};
use crate::error::bad;
use crate::io::{jnum, num, params_json, progress, Csv, Report};
use anyhow::Result;
use clap::{Args, ValueEnum};
use serde_json::{json, Value};
use std::path::PathBuf;
use trirhythm::analysis::oscillation::{
    boundary, classify_plane, Boundary, Classifier, Method, Plane, Search, Side,
};
use trirhythm::engine::{Barrier, ImpactMemory, Problem};
use trirhythm::theory::averaging::Variant;

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
    let Some((k, rest)) = s.split_once('=') else {
        return bad(format!("--x expects KEY=START:STOP:COUNT, got `{s}`"));
    };
    let parts: Vec<&str> = rest.split(':').collect();
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
        return Ok((k.trim().to_string(), vec![a]));
    }
    if parts.len() == 3 {
        match parts[2].trim().parse::<usize>() {
            Ok(c) if (1..=MAX_ABSCISSAE).contains(&c) => {}
            _ => {
                return bad(format!(
                    "--x: COUNT = `{}` must be an integer in [1, {MAX_ABSCISSAE}]",
                    parts[2]
                ))
            }
        }
    }
    let g = Grid::parse(rest, "--x")?;
    Ok((k.trim().to_string(), g.points()))
}

/// Parse `KEY=LO:HI` (boundary mode) or `KEY=LO:HI:COUNT` (grid mode).
fn parse_ordinate(s: &str, grid: bool) -> Result<(String, f64, f64, Vec<f64>)> {
    let form = if grid { "KEY=LO:HI:COUNT" } else { "KEY=LO:HI" };
    let Some((k, rest)) = s.split_once('=') else {
        return bad(format!("--y expects {form}, got `{s}`"));
    };
    let parts = rest.split(':').count();
    let g = match (grid, parts) {
        (false, 2) => Grid::parse(&format!("{rest}:2"), "--y")?,
        (true, 3) => Grid::parse(rest, "--y")?,
        _ => return bad(format!("--y expects {form}, got `{s}`")),
    };
    Ok((k.trim().to_string(), g.start, g.stop, g.points()))
}

fn method_of(m: MethodArg, classifier: Classifier, variant: Variant) -> Method {
    match m {
        MethodArg::Simulation | MethodArg::All => Method::Simulation(classifier),
        MethodArg::Averaging => Method::Averaging(variant),
        MethodArg::Exact => Method::Exact,
    }
}

/// `oscillation`.
pub fn oscillation(args: &OscillationArgs) -> Result<()> {
    let base = args.params.resolve()?;
    let variant = args.params.variant();
    if !(args.tolerance > 0.0 && args.tolerance <= 0.1) {
        return bad(format!(
            "--tolerance = {}: allowed range is (0, 0.1]",
            num(args.tolerance)
        ));
    }
    if !(args.dt >= 1e-4 && args.dt <= 0.1) {
        return bad(format!(
            "--dt = {}: allowed range is [1e-4, 0.1]",
            num(args.dt)
        ));
    }
    if base.noise_intensity != 0.0 {
        return bad(format!(
            "--param D = {}: the oscillation boundary is that of the noise-free system; allowed: D = 0",
            num(base.noise_intensity)
        ));
    }
    let (kx, xs) = parse_abscissae(&args.x)?;
    let (ky, lo, hi, ys) = parse_ordinate(&args.y, args.grid)?;
    if kx == ky {
        return bad(format!(
            "--x and --y name the same parameter `{kx}`: choose two different keys"
        ));
    }
    if kx == "D" || ky == "D" {
        return bad("--x/--y: D cannot be an axis (the oscillation boundary is at D = 0)");
    }
    let barrier = match args.barrier {
        OnOff::On => Barrier::On,
        OnOff::Off => Barrier::Off,
    };
    let mut classifier = Classifier::default();
    classifier.method.dt = args.dt;
    classifier.method.impact_memory = match args.impact_memory {
        ImpactMemoryArg::Continuous => ImpactMemory::Continuous,
        ImpactMemoryArg::Restart => ImpactMemory::Restart,
    };
    let template = Problem::from_params(&base)?.with_barrier(barrier)?;
    let problem = Plane::new(&template, (&kx, xs), (&ky, lo, hi))?;
    let search = Search {
        tolerance: args.tolerance,
        ..Default::default()
    };
    let mut header = vec![
        format!("trirhythm oscillation: boundary of {ky} (rest below/above) along {kx}"),
        format!("params: {}", base.describe()),
        format!(
            "barrier: {}",
            if barrier == Barrier::On { "on" } else { "off" }
        ),
        format!("averaging variant: {}", variant.name()),
        format!(
            "simulation: predictor–corrector from U(0) = {}, dt = {}, {} impact memory; growth rate of ln(amplitude) after {} periods 2π/ω0, early stop once its sign is clear (at most {} periods)",
            num(classifier.amplitude),
            num(classifier.method.dt),
            match classifier.method.impact_memory {
                ImpactMemory::Continuous => "continuous",
                ImpactMemory::Restart => "restart",
            },
            num(classifier.settle_periods),
            num(classifier.max_periods)
        ),
    ];
    if args.grid {
        let m = match args.method.unwrap_or(MethodArg::Simulation) {
            MethodArg::All => {
                return bad("--method all needs boundary mode: with --grid choose simulation, averaging or exact")
            }
            m => m,
        };
        let cells = problem.x.len().saturating_mul(ys.len());
        if cells > MAX_CELLS {
            return bad(format!(
                "--grid: {} × {} = {cells} points; at most {MAX_CELLS} are classified",
                problem.x.len(),
                ys.len()
            ));
        }
        let method = method_of(m, classifier, variant);
        let bar = progress(cells as u64, "oscillation grid");
        let report = Report(|done: u64, _total: u64| bar.set_position(done));
        let cells = classify_plane(&problem, &ys, &method, &report)?;
        bar.finish_and_clear();
        if let Some(c) = cells.iter().find(|c| c.rate.is_nan()) {
            return bad(format!(
                "--method exact: the exact linearisation with the wall is known at λ = 1 only (at {kx} = {}, {ky} = {} λ = {}); use --barrier off, or simulation",
                num(c.x),
                num(c.y),
                num(problem.at(c.x, c.y)?.lambda)
            ));
        }
        let simulations = if matches!(method, Method::Simulation(_)) {
            cells.len()
        } else {
            0
        };
        let text = match args.format {
            SimFormat::Csv => {
                header.push(format!("method: {}", method.name()));
                header.push(format!("simulations: {simulations}"));
                let mut csv = Csv::new(&header, &["x", "y", "oscillates"]);
                for c in &cells {
                    csv.row([num(c.x), num(c.y), u8::from(c.oscillates).to_string()]);
                }
                csv.finish()?
            }
            SimFormat::Json => {
                let doc = json!({
                    "params": params_json(&base),
                    "barrier": if barrier == Barrier::On { "on" } else { "off" },
                    "variant": variant.name(),
                    "method": method.name(),
                    "x_key": kx,
                    "y_key": ky,
                    "dt": jnum(args.dt),
                    "simulations": simulations,
                    "cells": cells.iter().map(|c| json!({
                        "x": jnum(c.x), "y": jnum(c.y), "oscillates": c.oscillates, "rate": jnum(c.rate),
                    })).collect::<Vec<_>>(),
                });
                serde_json::to_string_pretty(&doc)? + "\n"
            }
        };
        return crate::io::emit(args.out.as_deref(), &text);
    }
    let methods: Vec<Method> = match args.method.unwrap_or(MethodArg::All) {
        MethodArg::All => vec![
            Method::Simulation(classifier),
            Method::Averaging(variant),
            Method::Exact,
        ],
        m => vec![method_of(m, classifier, variant)],
    };
    let n = problem.x.len();
    let bar = progress((n * methods.len()) as u64, "oscillation boundary");
    let mut results: Vec<Boundary> = Vec::new();
    for (i, m) in methods.iter().enumerate() {
        let report = Report(|done: u64, _total: u64| bar.set_position((i * n) as u64 + done));
        results.push(boundary(&problem, m, &search, &report)?);
    }
    bar.finish_and_clear();
    let simulations: usize = results.iter().map(|b| b.simulations()).sum();
    let text = match args.format {
        SimFormat::Csv => {
            header.push(format!(
                "tolerance: simulated bracket y_hi − y_lo ≤ {} · y",
                num(args.tolerance)
            ));
            header.push(format!(
                "interval searched: {ky} ∈ [{}, {}]",
                num(lo),
                num(hi)
            ));
            header.push(format!("simulations: {simulations}"));
            for b in &results {
                for q in &b.points {
                    if q.side != Side::Boundary {
                        header.push(format!(
                            "{}: at {kx} = {} {}",
                            b.method,
                            num(q.x),
                            match q.side {
                                Side::Oscillates =>
                                    "no boundary in the interval: oscillates throughout",
                                Side::Rests => "no boundary in the interval: rests throughout",
                                _ => "not available (exact linearisation with the wall at λ < 1)",
                            }
                        ));
                    }
                }
            }
            let mut csv = Csv::new(&header, &["method", "x", "y", "y_lo", "y_hi"]);
            for b in &results {
                for q in b.points.iter().filter(|q| q.side == Side::Boundary) {
                    csv.row([
                        b.method.to_string(),
                        num(q.x),
                        num(q.y),
                        num(q.y_lo),
                        num(q.y_hi),
                    ]);
                }
            }
            csv.finish()?
        }
        SimFormat::Json => {
            let opt = |v: f64, q_side: Side| {
                if q_side == Side::Boundary {
                    jnum(v)
                } else {
                    Value::Null
                }
            };
            let doc = json!({
                "params": params_json(&base),
                "barrier": if barrier == Barrier::On { "on" } else { "off" },
                "variant": variant.name(),
                "x_key": kx,
                "y_key": ky,
                "y_range": [jnum(lo), jnum(hi)],
                "tolerance": jnum(args.tolerance),
                "dt": jnum(args.dt),
                "simulations": simulations,
                "boundaries": results.iter().map(|b| json!({
                    "method": b.method,
                    "simulations": b.simulations(),
                    "points": b.points.iter().map(|q| json!({
                        "x": jnum(q.x),
                        "side": q.side.name(),
                        "y": opt(q.y, q.side),
                        "y_lo": opt(q.y_lo, q.side),
                        "y_hi": opt(q.y_hi, q.side),
                        "oscillates_above": (q.side == Side::Boundary).then_some(q.oscillates_above),
                        "simulations": q.simulations,
                        "unclear": q.unclear,
                    })).collect::<Vec<_>>(),
                })).collect::<Vec<_>>(),
            });
            serde_json::to_string_pretty(&doc)? + "\n"
        }
    };
    crate::io::emit(args.out.as_deref(), &text)
}
