//! `trirhythm phase-response`: the phase response Z(θ) of a stable cycle, measured by small
//! impulses with the stepper, and the phase-reduction coefficient c of the frozen-noise
//! exponent λ ≈ −c·D under weak OU noise (the library's `analysis::lyapunov::phase_response`).
//! Keys, columns and flags are a contract: keep them.

use crate::args::{guard_step, ImpactMemoryArg, ModelArgs, ModelFileArg, Named, ParamArgs};
use crate::error::allowed;
use crate::io::progress::Bar;
use crate::io::{emit, num, params_json, pretty, Csv};
use anyhow::Result;
use clap::{Args, ValueEnum};
use serde::Serialize;
use serde_json::Value;
use std::path::PathBuf;
use trirhythm::analysis::lyapunov::{
    phase_response, AttractorSpec, PhaseResponse, PhaseSpec, MAX_FOLLOW_PERIODS, MAX_PHASES,
};

/// `text`, `json` or `csv`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum, Default)]
pub enum PhaseFormat {
    /// Ω, c and its uncertainty, the diagnostics, for reading.
    #[default]
    Text,
    /// The library's result with the run's parameters and method.
    Json,
    /// Z(θ) at the sampled phases (`theta,z,z_double,extrapolation`), the summary as `#` lines.
    Csv,
}

/// Arguments of `phase-response`.
#[derive(Debug, Args)]
pub struct PhaseArgs {
    #[command(flatten)]
    pub params: ParamArgs,
    #[command(flatten)]
    pub model: ModelArgs,
    #[command(flatten)]
    pub file: ModelFileArg,
    /// U(0) of the noise-free start (default: the largest stable amplitude of the averaged
    /// theory, the outer cycle).
    #[arg(long, allow_hyphen_values = true)]
    pub u0: Option<f64>,
    /// Step Δt, in [1e-4, 0.1].
    #[arg(long, default_value_t = 0.01, allow_hyphen_values = true)]
    pub dt: f64,
    /// What the memory does at an impact (as `lyapunov`: `restart`).
    #[arg(long = "impact-memory", value_enum, default_value_t = ImpactMemoryArg::Restart)]
    pub impact_memory: ImpactMemoryArg,
    /// Phases sampled over one period (even, 8 to 4096, at most T/Δt).
    #[arg(long, default_value_t = 128, allow_hyphen_values = true)]
    pub phases: usize,
    /// Impulse relative to the cycle's velocity scale A·Ω/2, in [1e-8, 1e-2].
    #[arg(long, default_value_t = 1e-4, allow_hyphen_values = true)]
    pub kick: f64,
    /// Sections each kicked copy is followed, 6 to 100000.
    #[arg(long, default_value_t = 60, allow_hyphen_values = true)]
    pub periods: usize,
    /// Longest noise-free run to reach the cycle.
    #[arg(long = "t-max", default_value_t = 20_000.0, allow_hyphen_values = true)]
    pub t_max: f64,
    /// Output format.
    #[arg(long, value_enum, default_value_t = PhaseFormat::Text)]
    pub format: PhaseFormat,
    /// Write to this file (atomically) instead of standard output.
    #[arg(long)]
    pub out: Option<PathBuf>,
}

/// The problem and method of a `phase-response` document, beside the library's result.
#[derive(Serialize)]
struct Run<'a> {
    params: Value,
    system: String,
    barrier: String,
    impact_memory: String,
    dt: f64,
    phases: usize,
    kick: f64,
    periods: usize,
    step_warnings: &'a [String],
    #[serde(flatten)]
    result: &'a PhaseResponse,
}

/// `phase-response`.
pub fn phase(args: &PhaseArgs) -> Result<()> {
    let params = args.params.resolve()?;
    allowed(
        (1e-4..=0.1).contains(&args.dt),
        "--dt",
        num(args.dt),
        "[1e-4, 0.1]",
    )?;
    allowed(
        (8..=MAX_PHASES).contains(&args.phases) && args.phases % 2 == 0,
        "--phases",
        args.phases,
        "an even number from 8 to 4096",
    )?;
    allowed(
        (6..=MAX_FOLLOW_PERIODS).contains(&args.periods),
        "--periods",
        args.periods,
        "6 to 100000",
    )?;
    let u0 = match args.u0 {
        Some(u0) => u0,
        None => outer_amplitude(&params, &args.params)?,
    };
    let method = args.model.method(args.dt, args.impact_memory);
    let problem = args.model.problem(&params)?.with_start(u0, 0.0)?;
    let warnings = guard_step(&problem, &method)?;
    let spec = PhaseSpec {
        phases: args.phases,
        kick: args.kick,
        periods: args.periods,
        attractor: AttractorSpec {
            t_max: args.t_max,
            variant: args.params.variant(),
            ..Default::default()
        },
    };
    let r = phase_response(&problem, &method, u0, &spec, &Bar::new("phase response"))?;
    let summary = summary(&r);
    eprintln!("{}", summary[2]);
    let mut header = vec![
        "trirhythm phase-response: phase response of a cycle and the phase-reduction exponent"
            .to_string(),
        format!("params: {}", params.describe()),
        format!(
            "method: predictor-corrector dt = {}, {}, U(0) = {}; {} phases, impulse {} (kick {}), \
             {} sections followed",
            num(args.dt),
            args.model.line(args.impact_memory),
            num(u0),
            args.phases,
            num(r.impulse),
            num(args.kick),
            args.periods
        ),
    ];
    header.extend(summary.iter().cloned());
    header.extend(warnings.iter().map(|w| format!("warning: {w}")));
    let text = match args.format {
        PhaseFormat::Text => header.join("\n") + "\n",
        PhaseFormat::Csv => {
            let columns = ["theta", "z", "z_double", "extrapolation"];
            let mut csv = Csv::new(&header, &columns);
            for s in &r.samples {
                csv.row([s.theta, s.z, s.z_double, s.extrapolation].map(num));
            }
            csv.finish()?
        }
        PhaseFormat::Json => pretty(&Run {
            params: params_json(&params),
            system: args.model.system.name(),
            barrier: args.model.barrier.name(),
            impact_memory: args.impact_memory.name(),
            dt: args.dt,
            phases: args.phases,
            kick: args.kick,
            periods: args.periods,
            step_warnings: &warnings,
            result: &r,
        })?,
    };
    emit(args.out.as_deref(), &text)
}

/// The largest stable amplitude of the averaged theory at D = 0 (the default start,
/// [`trirhythm_paper::lle::outer_amplitude`]).
fn outer_amplitude(params: &trirhythm::Params, args: &ParamArgs) -> Result<f64> {
    match trirhythm_paper::lle::outer_amplitude(params, args.variant())? {
        Some(a) => Ok(a),
        None => crate::error::bad(
            "the averaged theory has no stable cycle here: give the start with --u0",
        ),
    }
}

/// The result in lines: the cycle, Ω, c and its uncertainty, the diagnostics.
fn summary(r: &PhaseResponse) -> Vec<String> {
    let c = match r.coefficient {
        Some(c) => format!(
            "c = {} ± {} (λ ≈ −c·D for weak noise of correlation time τ = {}; {} harmonics, \
             jump tail {})",
            num(c),
            num(r.uncertainty),
            num(r.correlation_time),
            r.harmonics,
            num(r.tail)
        ),
        None => format!(
            "c undefined: {}",
            r.undefined.as_deref().unwrap_or("no reason given")
        ),
    };
    vec![
        format!(
            "cycle: {} (amplitude {}, period {}), θ = 0 at the {}",
            r.cycle.label(),
            num(r.amplitude),
            num(r.period),
            match r.section {
                trirhythm::analysis::lyapunov::Section::Impact => "impact",
                trirhythm::analysis::lyapunov::Section::UpwardCrossing =>
                    "upward crossing of U = 0",
            }
        ),
        format!("omega = {}", num(r.omega)),
        c,
        format!(
            "Z(0+) = {}, Z(2pi-) = {}, jump = {}; linearity {}, extrapolation {}",
            num(r.z_after),
            num(r.z_before),
            num(r.jump),
            num(r.linearity),
            num(r.extrapolation)
        ),
    ]
}
