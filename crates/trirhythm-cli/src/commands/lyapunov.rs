//! `trirhythm lyapunov`: the largest Lyapunov exponent with frozen noise (two trajectories or the tangent equation,
//! whole-history renormalisation), optionally swept over a parameter; `trirhythm
//! critical-noise`: the exponent against D by regime (one curve per attractor of the
//! noise-free system) and each curve's D_c, by the rules of Figs 17–19. Keys, columns and flags
//! are a contract: keep them.

use crate::args::{
    guard_step, parse_axis, ImpactMemoryArg, ModelArgs, ModelFileArg, Named, ParamArgs, SimFormat,
};
use crate::error::{allowed, bad};
use crate::io::progress::Bar;
use crate::io::{emit, num, params_json, pretty, progress, Csv};
use anyhow::Result;
use clap::{Args, ValueEnum};
use serde::Serialize;
use serde_json::{json, Value};
use std::path::PathBuf;
use trirhythm::analysis::lyapunov::LyapunovMethod as Lib;
use trirhythm::analysis::lyapunov::{largest_lyapunov, LyapunovResult, LyapunovSpec};
use trirhythm::engine::{PredictorCorrector, Problem};
use trirhythm::model::Params;
use trirhythm::monitor::Silent;
use trirhythm_paper::critical::{
    critical_noise, log_noises, starts_line, CriticalNoise, CriticalRequest, MAX_NOISES,
};
use trirhythm_paper::lle::Sizes;
use trirhythm_paper::views::{self, SweepPoint};

/// How the exponent is computed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum, Default)]
pub enum LyapunovMethod {
    /// The variational equation with its own memory: the exact derivative of every step, impacts included.
    Tangent,
    /// Two paths on the same noise, the copy pulled back to --separation (Benettin).
    #[default]
    TwoTrajectory,
}

same_variants!(LyapunovMethod => Lib: Tangent, TwoTrajectory);

impl LyapunovMethod {
    fn name(self) -> &'static str {
        Lib::from(self).name()
    }
}

/// How the exponent is computed: the flags `lyapunov` and `critical-noise` share.
#[derive(Debug, Args)]
pub struct ExponentArgs {
    /// How the exponent is computed (`tangent` has no copy to pull back: --separation is
    /// refused with it; README, "Lyapunov exponents").
    #[arg(long, value_enum, default_value_t = LyapunovMethod::TwoTrajectory)]
    pub method: LyapunovMethod,
    /// Steps between renormalisations, 1 to 1000000 (at least two per window).
    #[arg(
        long = "renormalise-every",
        default_value_t = 100,
        allow_hyphen_values = true
    )]
    pub renormalise_every: u64,
    /// Separation d₀ the perturbed copy is pulled back to, in [1e-12, 1e-4].
    #[arg(long, default_value_t = 1e-8, allow_hyphen_values = true)]
    pub separation: f64,
    /// Paths stepped together: 1 (one after the other), 4 or 8 (default the fastest measured:
    /// 8 for the reference and its copy, 4 for each path with its tangent). The exponents are
    /// the same bits for every choice.
    #[arg(long, allow_hyphen_values = true)]
    pub lanes: Option<usize>,
}

impl ExponentArgs {
    /// The library's spec for `paths` realisations of `seed` over `t_end` after `transient`,
    /// these flags and the model's `tolerance` checked first (narrower than the library's
    /// ranges: a copy pulled back to below 1e-12 merges with its reference in rounding; the
    /// library's `2 × renormalise_every` overflows past 2⁶³).
    fn spec(
        &self,
        (paths, seed): (usize, u64),
        (transient, t_end): (f64, f64),
        tolerance: Option<f64>,
    ) -> Result<LyapunovSpec> {
        let d0 = self.separation;
        allowed(
            (1e-12..=1e-4).contains(&d0),
            "--separation",
            num(d0),
            "[1e-12, 1e-4]",
        )?;
        if let Some(tolerance) = tolerance {
            allowed(
                tolerance > 0.0 && tolerance < 1e-2,
                "--tolerance",
                num(tolerance),
                "(0, 1e-2)",
            )?;
        }
        allowed(
            (1..=1_000_000).contains(&self.renormalise_every),
            "--renormalise-every",
            self.renormalise_every,
            "1 to 1000000 steps",
        )?;
        Ok(LyapunovSpec {
            paths,
            seed,
            transient,
            length: t_end,
            renormalise_every: self.renormalise_every,
            separation: self.separation,
            method: self.method.into(),
            lanes: crate::args::lanes(self.lanes)?,
            ..Default::default()
        })
    }
}

/// The simulation shared by `lyapunov` and `critical-noise`.
#[derive(Debug, Args)]
pub struct LleArgs {
    #[command(flatten)]
    pub params: ParamArgs,
    #[command(flatten)]
    pub model: ModelArgs,
    #[command(flatten)]
    pub file: ModelFileArg,
    /// Measured window after the transient (the finite-time exponent's T).
    #[arg(long = "t-end", default_value_t = 2000.0, allow_hyphen_values = true)]
    pub t_end: f64,
    /// Time renormalised but not counted at the start of each path.
    #[arg(long, default_value_t = 200.0, allow_hyphen_values = true)]
    pub transient: f64,
    /// Step Δt, in [1e-4, 0.1].
    #[arg(long, default_value_t = 0.01, allow_hyphen_values = true)]
    pub dt: f64,
    /// Noise realisations (path i is noise stream i of the seed), 1 to 100000.
    #[arg(long, default_value_t = 8, allow_hyphen_values = true)]
    pub paths: usize,
    /// Seed of the noise streams.
    #[arg(long, default_value_t = 1, allow_hyphen_values = true)]
    pub seed: u64,
    /// U(0) of the reference path.
    #[arg(long, default_value_t = 1.0, allow_hyphen_values = true)]
    pub u0: f64,
    /// What the memory does at an impact (the ensembles' default, `restart`).
    #[arg(long = "impact-memory", value_enum, default_value_t = ImpactMemoryArg::Restart)]
    pub impact_memory: ImpactMemoryArg,
    #[command(flatten)]
    pub exponent: ExponentArgs,
}

impl LleArgs {
    fn setup(&self) -> Result<(Params, Problem, PredictorCorrector, LyapunovSpec)> {
        let params = self.params.resolve()?;
        // the library takes any dt that divides the window; this command's runs are tested
        // in [1e-4, 0.1]
        allowed(
            (1e-4..=0.1).contains(&self.dt),
            "--dt",
            num(self.dt),
            "[1e-4, 0.1]",
        )?;
        let method = self.model.method(self.dt, self.impact_memory);
        let spec = self.exponent.spec(
            (self.paths, self.seed),
            (self.transient, self.t_end),
            self.model.tolerance,
        )?;
        let problem = self.model.problem(&params)?.with_start(self.u0, 0.0)?;
        Ok((params, problem, method, spec))
    }

    /// The notes on the method: the library's spec in words, the simulation between.
    fn describe(&self, spec: &LyapunovSpec) -> Vec<String> {
        let [method, window] = views::lyapunov_spec(spec);
        let simulation = format!(
            "simulation: predictor-corrector dt = {}, {} memory, {} impact memory, system {}, \
             barrier {}, U(0) = {}",
            num(self.dt),
            self.model.memory.name(),
            self.impact_memory.name(),
            self.model.system.name(),
            self.model.barrier.name(),
            num(self.u0)
        );
        vec![method, simulation, window]
    }
}

/// Parse `KEY=START:STOP:COUNT` (COUNT 2 to 1000) for `--sweep`.
fn parse_sweep(s: &str) -> Result<(String, Vec<f64>)> {
    let (key, g) = parse_axis(s, "--sweep", true)?;
    allowed(g.count <= 1000, "--sweep: COUNT", g.count, "2 to 1000")?;
    Ok((key, g.points()))
}

/// Arguments of `lyapunov`.
#[derive(Debug, Args)]
pub struct LyapunovArgs {
    #[command(flatten)]
    pub sim: LleArgs,
    /// Sweep a parameter: KEY=START:STOP:COUNT (CSV `KEY,lle,stderr,merged,unmerged,unmerged_stderr`).
    #[arg(long, value_name = "KEY=START:STOP:COUNT", allow_hyphen_values = true)]
    pub sweep: Option<String>,
    /// Output format (default: json; csv with --sweep).
    #[arg(long, value_enum)]
    pub format: Option<SimFormat>,
    /// Write to this file (atomically) instead of standard output.
    #[arg(long)]
    pub out: Option<PathBuf>,
}

/// The problem and method of a `lyapunov` document, beside the library's result.
#[derive(Serialize)]
struct Run<'a> {
    params: Value,
    /// The General kernel's terms of a `--model` file, absent for the paper's family.
    #[serde(skip_serializing_if = "Option::is_none")]
    terms: Option<String>,
    method: &'static str,
    system: String,
    barrier: String,
    impact_memory: String,
    dt: f64,
    transient: f64,
    paths: usize,
    seed: u64,
    separation: f64,
    renormalise_every: u64,
    step_warnings: &'a [String],
    #[serde(flatten)]
    result: &'a LyapunovResult,
}

/// `lyapunov`.
pub fn lyapunov(args: &LyapunovArgs) -> Result<()> {
    let (base, problem, method, spec) = args.sim.setup()?;
    let warnings = guard_step(&problem, &method)?;
    let mut header = vec!["trirhythm lyapunov: largest Lyapunov exponent".to_string()];
    header.push(format!("params: {}", base.describe()));
    let terms = problem.oscillator().terms().map(|t| t.describe());
    if let Some(t) = &terms {
        header.push(format!("terms: {t}"));
    }
    header.extend(args.sim.describe(&spec));
    header.extend(warnings.iter().map(|w| format!("warning: {w}")));
    if let Some(sweep) = &args.sweep {
        return sweep_lyapunov(args, sweep, header, &base, &problem, &method, &spec);
    }
    let r = largest_lyapunov(&problem, &method, &spec, &Bar::new("lyapunov"))?;
    eprintln!(
        "LLE = {} (finite-time, window {}; {} paths)",
        views::lle(&r),
        num(spec.length),
        spec.paths
    );
    let text = match args.format.unwrap_or(SimFormat::Json) {
        SimFormat::Csv => Csv::of(&views::lle_table(&header, &r))?,
        SimFormat::Json => pretty(&Run {
            params: params_json(&base),
            terms,
            method: args.sim.exponent.method.name(),
            system: args.sim.model.system.name(),
            barrier: args.sim.model.barrier.name(),
            impact_memory: args.sim.impact_memory.name(),
            dt: args.sim.dt,
            transient: spec.transient,
            paths: spec.paths,
            seed: spec.seed,
            separation: spec.separation,
            renormalise_every: spec.renormalise_every,
            step_warnings: &warnings,
            result: &r,
        })?,
    };
    emit(args.out.as_deref(), &text)
}

/// `lyapunov --sweep KEY=START:STOP:COUNT`: the exponent at each value of a parameter.
fn sweep_lyapunov(
    args: &LyapunovArgs,
    sweep: &str,
    header: Vec<String>,
    base: &Params,
    problem: &Problem,
    method: &PredictorCorrector,
    spec: &LyapunovSpec,
) -> Result<()> {
    let (key, values) = parse_sweep(sweep)?;
    let points = sweep_params(base, Some(&key), &values)?;
    // every point's step is checked before the first is computed
    let mut header = header;
    for (p, v) in points.iter().zip(&values) {
        for w in guard_step(&problem.with_params(p)?, method)? {
            header.push(format!("warning at {key} = {}: {w}", num(*v)));
        }
    }
    let bar = progress(values.len() as u64, "lyapunov sweep");
    // the points are independent tasks of the pool (each runs its realisations as tasks too)
    let done = std::sync::atomic::AtomicU64::new(0);
    let rows: Vec<(f64, LyapunovResult)> = trirhythm::profile::parallel(|stage| {
        use rayon::prelude::*;
        points
            .par_iter()
            .zip(&values)
            .map(|(p, &v)| {
                stage.task(|| {
                    let r = largest_lyapunov(&problem.with_params(p)?, method, spec, &Silent)?;
                    let n = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
                    bar.set_position(n);
                    Ok((v, r))
                })
            })
            .collect::<Result<_>>()
    })?;
    bar.finish_and_clear();
    let text = match args.format.unwrap_or(SimFormat::Csv) {
        SimFormat::Csv => Csv::of(&views::lle_sweep_table(&header, &key, &rows))?,
        SimFormat::Json => pretty(&json!({
            "params": params_json(base),
            "method": args.sim.exponent.method.name(),
            "sweep": key,
            "window": spec.length,
            "step_warnings": header
                .iter()
                .filter(|h| h.starts_with("warning"))
                .collect::<Vec<_>>(),
            "points": rows
                .iter()
                .map(|(value, result)| SweepPoint { value: *value, result })
                .collect::<Vec<_>>(),
        }))?,
    };
    emit(args.out.as_deref(), &text)
}

/// The parameters at each value of the swept key (the base parameters alone without one).
fn sweep_params(base: &Params, key: Option<&str>, values: &[f64]) -> Result<Vec<Params>> {
    let at = |v: f64| match key {
        Some(k) => base.with(k, v),
        None => Ok(base.clone()),
    };
    Ok(values
        .iter()
        .map(|&v| at(v))
        .collect::<trirhythm::Result<_>>()?)
}

/// Arguments of `critical-noise`.
#[derive(Debug, Args)]
#[command(group = clap::ArgGroup::new("d").required(true).args(["d_range", "noises"]))]
pub struct CriticalNoiseArgs {
    #[command(flatten)]
    pub params: ParamArgs,
    #[command(flatten)]
    pub model: ModelArgs,
    #[command(flatten)]
    pub file: ModelFileArg,
    /// The noise range: LO:HI with 0 < LO < HI, --points values log-spaced (3 significant digits).
    #[arg(long = "d-range", value_name = "LO:HI", allow_hyphen_values = true)]
    pub d_range: Option<String>,
    /// Values of D log-spaced over --d-range, ends included, 2 to 1000 (default 9).
    #[arg(long, allow_hyphen_values = true)]
    pub points: Option<usize>,
    /// The noise intensities, ascending, each > 0: D1,D2,… (instead of --d-range).
    #[arg(
        long,
        value_name = "D1,D2,...",
        allow_hyphen_values = true,
        conflicts_with = "d_range"
    )]
    pub noises: Option<String>,
    /// The curves for each value of a parameter: KEY=START:STOP:COUNT (COUNT 2 to 1000).
    #[arg(long, value_name = "KEY=START:STOP:COUNT", allow_hyphen_values = true)]
    pub sweep: Option<String>,
    /// Measured window W after the transient (the finite-time exponent's T; the calls' margin
    /// is δ = 1/W).
    #[arg(long = "t-end", default_value_t = 2000.0, allow_hyphen_values = true)]
    pub t_end: f64,
    /// Time renormalised but not counted at the start of each path.
    #[arg(long, default_value_t = 200.0, allow_hyphen_values = true)]
    pub transient: f64,
    /// Step Δt, in [1e-4, 0.1] (default: the figures' rule, the largest of 0.01, 0.005,
    /// 0.0025, 0.002, 0.001, … not above τ/10).
    #[arg(long, allow_hyphen_values = true)]
    pub dt: Option<f64>,
    /// Noise realisations per point (path i is noise stream i of the seed at every point),
    /// 1 to 100000.
    #[arg(long, default_value_t = 8, allow_hyphen_values = true)]
    pub paths: usize,
    /// Seed of the noise streams.
    #[arg(long, default_value_t = 1, allow_hyphen_values = true)]
    pub seed: u64,
    /// What the memory does at an impact (the figures': `restart`).
    #[arg(long = "impact-memory", value_enum, default_value_t = ImpactMemoryArg::Restart)]
    pub impact_memory: ImpactMemoryArg,
    #[command(flatten)]
    pub exponent: ExponentArgs,
    /// Output format: CSV, a row per point with its curve's decision (default), or JSON.
    #[arg(long, value_enum, default_value_t = SimFormat::Csv)]
    pub format: SimFormat,
    /// Write to this file (atomically) instead of standard output.
    #[arg(long)]
    pub out: Option<PathBuf>,
}

/// Parse `LO:HI` for `--d-range`, and the `points` values log-spaced over it
/// ([`log_noises`]: 0 < LO < HI, 2 to 1000 points, distinct at 3 significant digits).
fn noises_of_range(s: &str, points: usize) -> Result<Vec<f64>> {
    let Some((lo, hi)) = s.split_once(':') else {
        return bad(format!("--d-range expects LO:HI, got `{s}`"));
    };
    let parse = |t: &str| -> Result<f64> {
        match t.trim().parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            _ => bad(format!(
                "--d-range: `{t}` is not a finite number (in `{s}`)"
            )),
        }
    };
    Ok(log_noises(parse(lo)?, parse(hi)?, points)?)
}

/// Parse `--noises D1,D2,…`: 1 to 1000 finite values, each > 0, ascending.
fn noises_of_list(s: &str) -> Result<Vec<f64>> {
    let mut d = Vec::new();
    for t in s.split(',') {
        match t.trim().parse::<f64>() {
            Ok(v) if v.is_finite() => d.push(v),
            _ => {
                return bad(format!(
                    "--noises: `{}` is not a finite number (in `{s}`)",
                    t.trim()
                ))
            }
        }
    }
    allowed(
        d.len() <= MAX_NOISES,
        "--noises",
        format!("{} values", d.len()),
        "1 to 1000 values",
    )?;
    for (k, &v) in d.iter().enumerate() {
        allowed(v > 0.0, "--noises", num(v), "(0, ∞), each D > 0")?;
        if k > 0 {
            allowed(
                v > d[k - 1],
                "--noises",
                num(v),
                &format!("above {} (ascending, no repeats)", num(d[k - 1])),
            )?;
        }
    }
    Ok(d)
}

/// `critical-noise`: the largest Lyapunov exponent against D by regime, and each attractor's
/// D_c, with the rules and the code of Figs 17–19 ([`trirhythm_paper::critical`]).
pub fn critical(args: &CriticalNoiseArgs) -> Result<()> {
    // D is the abscissa of every curve: a value given for it would be ignored
    if let Some(kv) = args
        .params
        .params
        .iter()
        .find(|kv| kv.split_once('=').is_some_and(|(k, _)| k.trim() == "D"))
    {
        return bad(format!(
            "--param {kv}: D is the noise intensity of every curve's points; give its values \
             with --d-range LO:HI (and --points) or --noises D1,D2,… instead"
        ));
    }
    let base = args.params.resolve()?;
    let noises = match (&args.d_range, &args.noises, args.points) {
        (Some(r), None, points) => noises_of_range(r, points.unwrap_or(9))?,
        (None, Some(list), None) => noises_of_list(list)?,
        (None, Some(_), Some(_)) => {
            return bad("--points: the values log-spaced over --d-range; --noises gives them all")
        }
        _ => return bad("give the noise intensities: --d-range LO:HI [--points N] or --noises"),
    };
    if let Some(dt) = args.dt {
        allowed((1e-4..=0.1).contains(&dt), "--dt", num(dt), "[1e-4, 0.1]")?;
    }
    let sweep = match &args.sweep {
        Some(s) => {
            let (k, v) = parse_sweep(s)?;
            if k == "D" {
                return bad(
                    "--sweep: D is every curve's abscissa (--d-range, --noises); sweep another \
                     parameter",
                );
            }
            Some((k, v))
        }
        None => None,
    };
    let spec = args.exponent.spec(
        (args.paths, args.seed),
        (args.transient, args.t_end),
        args.model.tolerance,
    )?;
    let request = CriticalRequest {
        base: base.clone(),
        sweep,
        noises,
        sizes: Sizes {
            model: args.model.model(),
            dt: args.dt,
            impact_memory: args.impact_memory.into(),
            ..Sizes::of_spec(spec.clone())
        },
        variant: args.params.variant(),
    };
    // everything checked, and the step guard's warnings said, before any work
    let warnings = request.validate()?;
    for w in &warnings {
        eprintln!("warning: {w}");
    }
    let doc = critical_noise(&request, &Bar::new("critical noise"))?;
    for line in views::critical_lines(&doc) {
        eprintln!("{line}");
    }
    let text = match args.format {
        SimFormat::Csv => {
            let mut header = vec![
                "trirhythm critical-noise: the largest Lyapunov exponent against D by regime \
                 and each attractor's critical noise D_c"
                    .to_string(),
                format!("params: {}", base.describe()),
                format!(
                    "D: {} values: {} (the D of the params above is not used)",
                    doc.noises.len(),
                    doc.noises
                        .iter()
                        .map(|&d| num(d))
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            ];
            let [method, window] = views::lyapunov_spec(&spec);
            header.push(method);
            header.push(format!(
                "simulation: predictor-corrector {}, {}",
                match args.dt {
                    Some(dt) => format!("dt = {}", num(dt)),
                    None => "dt = the largest of 0.01, 0.005, 0.0025, 0.002, 0.001, 0.0005, \
                             0.00025, 0.0001 not above τ/10 (the figures' rule; each curve's dt \
                             column)"
                        .into(),
                },
                args.model.line(args.impact_memory)
            ));
            header.push(window);
            header.push(starts_line(args.params.variant()));
            Csv::of(&views::critical_table(&header, &doc))?
        }
        SimFormat::Json => pretty(&CriticalRun {
            params: params_json(&base),
            result: &doc,
        })?,
    };
    emit(args.out.as_deref(), &text)
}

/// A `critical-noise` document: the parameters beside the library's result.
#[derive(Serialize)]
struct CriticalRun<'a> {
    params: Value,
    #[serde(flatten)]
    result: &'a CriticalNoise,
}
