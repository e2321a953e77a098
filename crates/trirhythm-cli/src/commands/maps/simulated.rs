//! `map --simulate`: the P-bifurcation map by Monte Carlo
//! (`trirhythm::analysis::simulated_map`): at every grid point an ensemble of Eq. (1), the
//! modes of its P(A) counted with their range, beside the theory's count, with the ensemble's
//! stationarity verdict.
//!
//! Output: CSV `x,y,theory,simulated,low,high,agreement,stationary,beyond` with the
//! parameters, the method, the rule and the tally in `#` lines, or JSON (`--format json`): the
//! library's `SimulatedMap` (every point's density with its standard errors) with the
//! parameters and the method. The work (points × paths × steps) is sized before it starts and
//! refused beyond `--max-path-steps`; a bar shows the path-steps done.
//!
//! Picture: `--png FILE` and/or `--svg FILE`, the theory's count beside the simulated one
//! with the points that do not agree marked ([`crate::render::figures::simmap`]). Each
//! destination is checked before any work: named `.png` / `.svg`, writable, and where a file
//! is there, a picture this tool drew ([`crate::render::plot::signed`]): a file it did not
//! write is never replaced. Written atomically, after the data.

use super::MapArgs;
use crate::args::{lanes, Format, ImpactMemoryArg, Named};
use crate::commands::ensemble::BackendArg;
use crate::error::{allowed, bad};
use crate::io::files::check_writable;
use crate::io::progress::note;
use crate::io::write_atomic;
use crate::io::{emit, num, params_json, progress, Csv, Report};
use crate::render::figures::simmap::{SimulatedMapPicture, Sizes};
use crate::render::plot::{draw_svg, rasterise, signed, svg_file};
use anyhow::{Context, Result};
use clap::Args;
use serde::Serialize;
use serde_json::Value;
use std::io::Read;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Instant;
use trirhythm::analysis::ensemble::{EnsembleResult, EnsembleSpec};
use trirhythm::analysis::simulated_map::{simulate_map, ModeRule, SimulatedMap, SimulatedMapSpec};
use trirhythm::engine::{PredictorCorrector, Problem};
use trirhythm::monitor::Silent;
use trirhythm_gpu::run_ensemble;

/// The options of `map --simulate` (their ids, for refusing them without it).
pub const SIMULATION_FLAGS: &[(&str, &str)] = &[
    ("paths", "--paths"),
    ("t_end", "--t-end"),
    ("burn_in", "--burn-in"),
    ("dt", "--dt"),
    ("seed", "--seed"),
    ("bins", "--bins"),
    ("batches", "--batches"),
    ("impact_memory", "--impact-memory"),
    ("amplitude_max", "--amplitude-max"),
    ("lanes", "--lanes"),
    ("z", "--z"),
    ("z_lenient", "--z-lenient"),
    ("z_strict", "--z-strict"),
    ("max_path_steps", "--max-path-steps"),
    ("backend", "--backend"),
    ("png", "--png"),
    ("svg", "--svg"),
];

/// Arguments of `map --simulate`.
#[derive(Debug, Args)]
pub struct SimulateMapArgs {
    /// Count the modes of the simulated P(A) at every point (an ensemble of Eq. 1 each) beside
    /// the theory's count (implies --what modes).
    #[arg(long)]
    pub simulate: bool,
    /// --simulate: paths per point (path i is noise stream i of the point's seed).
    #[arg(long, default_value_t = 8, allow_hyphen_values = true)]
    pub paths: usize,
    /// --simulate: each path's recorded window, after the burn-in.
    #[arg(long = "t-end", default_value_t = 1000.0, allow_hyphen_values = true)]
    pub t_end: f64,
    /// --simulate: time discarded at the start of each path.
    #[arg(long = "burn-in", default_value_t = 100.0, allow_hyphen_values = true)]
    pub burn_in: f64,
    /// --simulate: step Δt.
    #[arg(long, default_value_t = 0.01, allow_hyphen_values = true)]
    pub dt: f64,
    /// --simulate: the map's seed (each point's is derived from it and the point's index).
    #[arg(long, default_value_t = 1, allow_hyphen_values = true)]
    pub seed: u64,
    /// --simulate: bins of the amplitude histogram.
    #[arg(long, default_value_t = 40, allow_hyphen_values = true)]
    pub bins: usize,
    /// --simulate: batches per path (for R̂).
    #[arg(long, default_value_t = 20, allow_hyphen_values = true)]
    pub batches: usize,
    /// --simulate: what the memory does at an impact (as `ensemble`: restart by default).
    #[arg(long = "impact-memory", value_enum, default_value_t = ImpactMemoryArg::Restart)]
    pub impact_memory: ImpactMemoryArg,
    /// --simulate: a fixed upper end of the amplitude histogram (default: the theory's per
    /// point).
    #[arg(long = "amplitude-max", allow_hyphen_values = true)]
    pub amplitude_max: Option<f64>,
    /// --simulate: paths stepped together, 1, 4 or 8 (the same bits for every choice).
    #[arg(long, allow_hyphen_values = true)]
    pub lanes: Option<usize>,
    /// --simulate: a mode's dips exceed this many standard errors.
    #[arg(long, default_value_t = 3.0, allow_hyphen_values = true)]
    pub z: f64,
    /// --simulate: the lenient threshold (the count's upper end).
    #[arg(long = "z-lenient", default_value_t = 2.0, allow_hyphen_values = true)]
    pub z_lenient: f64,
    /// --simulate: the strict threshold (the count's lower end).
    #[arg(long = "z-strict", default_value_t = 4.0, allow_hyphen_values = true)]
    pub z_strict: f64,
    /// --simulate: refuse a map of more path-steps (points × paths × steps per path) than
    /// this (2e10: about half an hour on two cores at 10⁷ steps/s).
    #[arg(
        long = "max-path-steps",
        default_value_t = 2e10,
        allow_hyphen_values = true
    )]
    pub max_path_steps: f64,
    /// Where every point's paths are stepped: `cpu` (the CPU engine, the reference) or `gpu`
    /// (the CUDA kernel on the first GPU; docs/gpu.md).
    #[arg(long, value_enum, default_value_t = BackendArg::Cpu)]
    pub backend: BackendArg,
    /// --simulate: draw the theory's count beside the simulated one, the points that do not
    /// agree marked, as a PNG 7 in wide at 300 dpi (a file named .png; an existing one only
    /// if this tool drew it).
    #[arg(long, value_name = "FILE")]
    pub png: Option<PathBuf>,
    /// --simulate: the same picture as SVG (a file named .svg; an existing one only if this
    /// tool drew it).
    #[arg(long, value_name = "FILE")]
    pub svg: Option<PathBuf>,
}

/// Refuse, before any work, a picture's destination that cannot take it: a name without the
/// `.ext` of `flag`'s format, a path [`check_writable`] refuses, or an existing file that is
/// not a picture this tool drew ([`signed`]), which is never replaced.
fn check_picture(path: &Path, flag: &str, ext: &str) -> Result<()> {
    if !path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case(ext))
    {
        return bad(format!(
            "{flag} {}: give a file name ending in .{ext}",
            path.display()
        ));
    }
    check_writable(path, flag)?;
    if path.exists() {
        let mut head = Vec::new();
        let read = std::fs::File::open(path).and_then(|f| f.take(4096).read_to_end(&mut head));
        if let Err(e) = read {
            return bad(format!("{flag} {}: cannot read it ({e})", path.display()));
        }
        if !signed(&head) {
            return bad(format!(
                "{flag} {}: exists and is not a picture trirhythm drew; it is never \
                 replaced (remove it, or give another name)",
                path.display()
            ));
        }
    }
    Ok(())
}

impl SimulateMapArgs {
    /// The library's spec of these flags.
    fn spec(&self) -> Result<SimulatedMapSpec> {
        Ok(SimulatedMapSpec {
            ensemble: EnsembleSpec {
                paths: self.paths,
                seed: self.seed,
                burn_in: self.burn_in,
                length: self.t_end,
                bins: self.bins,
                joint_bins: 2,
                batches: self.batches,
                lanes: lanes(self.lanes)?,
                ..Default::default()
            },
            method: PredictorCorrector {
                dt: self.dt,
                impact_memory: self.impact_memory.into(),
                ..Default::default()
            },
            rule: ModeRule {
                z: self.z,
                z_lenient: self.z_lenient,
                z_strict: self.z_strict,
            },
            amplitude_max: self.amplitude_max,
        })
    }

    /// `method: …`: the line that says how every point was simulated.
    fn method_line(&self) -> String {
        format!(
            "method: predictor-corrector dt={} impact_memory={} paths={} burn_in={} \
             t_end={} seed={} bins={} batches={}",
            self.dt,
            self.impact_memory.name(),
            self.paths,
            self.burn_in,
            self.t_end,
            self.seed,
            self.bins,
            self.batches
        ) + match self.backend {
            BackendArg::Cpu => "",
            BackendArg::Gpu => " backend=gpu",
        }
    }
}

/// The JSON document: the library's map with the parameters and the method.
#[derive(Serialize)]
struct Document<'a> {
    params: Value,
    method: String,
    #[serde(flatten)]
    map: &'a SimulatedMap,
}

/// `map --simulate`.
pub fn map(args: &MapArgs) -> Result<()> {
    debug_assert!(args.sim.simulate);
    let sim = &args.sim;
    let (base, plane, kx, ky) = super::plane_of(args)?;
    let variant = args.params.variant();
    let spec = sim.spec()?;
    spec.validate(&plane)?;
    // the work, sized before it starts
    allowed(
        sim.max_path_steps > 0.0 && sim.max_path_steps.is_finite(),
        "--max-path-steps",
        num(sim.max_path_steps),
        "(0, ∞)",
    )?;
    let work = spec.path_steps(&plane);
    if work > sim.max_path_steps {
        return bad(format!(
            "--max-path-steps = {}: this map takes {} path-steps ({} points × {} paths × {} \
             steps); give fewer points, --paths, a shorter --t-end or --burn-in, a larger --dt, \
             or raise --max-path-steps",
            num(sim.max_path_steps),
            num(work),
            plane.x.count * plane.y.count,
            sim.paths,
            num(((sim.burn_in + sim.t_end) / sim.dt).round())
        ));
    }
    if let Some(p) = &sim.png {
        check_picture(p, "--png", "png")?;
    }
    if let Some(p) = &sim.svg {
        check_picture(p, "--svg", "svg")?;
    }
    note(&format!(
        "map --simulate: {} points × {} paths × {} steps = {} path-steps on the {}",
        plane.x.count * plane.y.count,
        sim.paths,
        num(((sim.burn_in + sim.t_end) / sim.dt).round()),
        num(work),
        match sim.backend {
            BackendArg::Cpu => "CPU",
            BackendArg::Gpu => "GPU",
        }
    ));
    let bar = progress(work as u64, "map --simulate");
    let done = AtomicU64::new(0);
    // every point's ensemble on the chosen backend, the bar moved by the path-steps of every
    // point so far
    let backend = trirhythm_gpu::Backend::from(sim.backend);
    let runner = |problem: &Problem, method: &PredictorCorrector, es: &EnsembleSpec| {
        let before = done.load(Ordering::Relaxed);
        let moved = Report(|d: u64, _| bar.set_position(before + d));
        let r: EnsembleResult = run_ensemble(problem, method, es, &moved, backend)?;
        done.fetch_add(r.paths as u64 * r.steps_per_path, Ordering::Relaxed);
        bar.set_position(done.load(Ordering::Relaxed));
        Ok(r)
    };
    let started = Instant::now();
    let map = simulate_map(&plane, &spec, &runner, &Silent);
    bar.finish_and_clear();
    let map = map?;
    let t = map.tally;
    note(&format!(
        "map --simulate: {:.1} s; agree {}, disagree {}, uncertain {}, non-stationary {}, \
         outside the range {}",
        started.elapsed().as_secs_f64(),
        t.agree,
        t.disagree,
        t.uncertain,
        t.non_stationary,
        t.outside_range
    ));
    let text = match args.output.format {
        Format::Json => {
            let doc = Document {
                params: params_json(&base),
                method: sim.method_line(),
                map: &map,
            };
            serde_json::to_string(&doc)? + "\n"
        }
        Format::Csv | Format::Table => {
            let r = &map.rule;
            let header = vec![
                format!("params: {}", base.describe()),
                format!(
                    "variant: {}, what: modes (simulated beside the theory's), x: {kx}, y: {ky}",
                    variant.name()
                ),
                sim.method_line(),
                format!(
                    "rule: a mode dips more than z = {} combined standard errors to its \
                     neighbouring modes or the ends; low at z = {}, high at z = {}",
                    r.z, r.z_strict, r.z_lenient
                ),
                format!(
                    "tally: agree {}, disagree {}, uncertain {}, non_stationary {}, \
                     outside_range {}",
                    t.agree, t.disagree, t.uncertain, t.non_stationary, t.outside_range
                ),
            ];
            let mut csv = Csv::new(
                &header,
                &[
                    "x",
                    "y",
                    "theory",
                    "simulated",
                    "low",
                    "high",
                    "agreement",
                    "stationary",
                    "beyond",
                ],
            );
            for p in &map.points {
                csv.row([
                    num(p.x),
                    num(p.y),
                    p.theory.to_string(),
                    p.simulated.count.to_string(),
                    p.simulated.low.to_string(),
                    p.simulated.high.to_string(),
                    p.agreement.name().to_string(),
                    p.stationary.to_string(),
                    num(p.beyond),
                ]);
            }
            csv.finish()?
        }
    };
    emit(args.output.out.as_deref(), &text)?;
    if sim.png.is_none() && sim.svg.is_none() {
        return Ok(());
    }
    let sizes = Sizes {
        paths: sim.paths,
        t_end: sim.t_end,
        burn_in: sim.burn_in,
        dt: sim.dt,
        seed: sim.seed,
    };
    let picture = SimulatedMapPicture::new(&map, &base, &sizes);
    let svg = draw_svg(&picture, Vec::new()).context("drawing the simulated map")?;
    if let Some(p) = &sim.png {
        let bytes = rasterise(&svg).with_context(|| format!("drawing {}", p.display()))?;
        write_atomic(p, &bytes)?;
    }
    if let Some(p) = &sim.svg {
        write_atomic(p, svg_file(&svg).as_bytes())?;
    }
    Ok(())
}
