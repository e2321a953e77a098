//! `trirhythm simulate`: one path of the fractional oscillator (Eq. 1) or of its integer-order
//! companions (Eq. 5, Eq. 9) with the predictor–corrector engine.
//!
//! Output: CSV `t,U,V` (plus `eta` when D > 0) with the parameters and the method in `#`
//! header lines and the summary on standard error, or one JSON object with the summary and the
//! columns. Flags, keys and column names are a contract: keep them.

use crate::args::{guard_step, ImpactMemoryArg, ModelArgs, ModelFileArg, ParamArgs, SimFormat};
use crate::error::bad;
use crate::io::{emit, jvec, num, params_json, progress, Report, Stream};
use anyhow::{Context, Result};
use clap::Args;
use serde_json::{json, Value};
use std::io::Write;
use std::path::PathBuf;
use std::time::Instant;
use trirhythm::engine::{
    run, simulate_with, Flow, Observer, Options, PredictorCorrector, Problem, Stepper, Trajectory,
    TrajectoryRecorder,
};
use trirhythm::monitor::Monitor;
use trirhythm_paper::views::PathSummary;

/// Arguments of `simulate`.
#[derive(Debug, Args)]
pub struct SimulateArgs {
    #[command(flatten)]
    pub params: ParamArgs,
    #[command(flatten)]
    pub model: ModelArgs,
    #[command(flatten)]
    pub file: ModelFileArg,
    /// End time T.
    #[arg(long = "t-end", default_value_t = 200.0, allow_hyphen_values = true)]
    pub t_end: f64,
    /// Step Δt.
    #[arg(long, default_value_t = 0.01, allow_hyphen_values = true)]
    pub dt: f64,
    /// What the memory does at an impact.
    #[arg(long = "impact-memory", value_enum, default_value_t = ImpactMemoryArg::Continuous)]
    pub impact_memory: ImpactMemoryArg,
    /// U(0).
    #[arg(long, default_value_t = 1.0, allow_hyphen_values = true)]
    pub u0: f64,
    /// U̇(0).
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub v0: f64,
    /// Seed of the noise (path 0 of this seed).
    #[arg(long, default_value_t = 1, allow_hyphen_values = true)]
    pub seed: u64,
    /// Write every K-th step.
    #[arg(long, default_value_t = 1, allow_hyphen_values = true)]
    pub every: usize,
    /// Output format.
    #[arg(long, value_enum, default_value_t = SimFormat::Csv)]
    pub format: SimFormat,
    /// Write to this file (atomically) instead of standard output.
    #[arg(long)]
    pub out: Option<PathBuf>,
}

/// The run's inputs in library types.
pub struct Setup {
    pub problem: Problem,
    pub method: PredictorCorrector,
    pub options: Options,
    /// The step guard's warnings (a coarse `--dt`), carried in the output.
    pub warnings: Vec<String>,
}

impl SimulateArgs {
    /// Validate and convert.
    pub fn setup(&self) -> Result<Setup> {
        let p = self.params.resolve()?;
        if self.every == 0 {
            return bad("--every = 0: allowed range is 1 or more");
        }
        let method = self.model.method(self.dt, self.impact_memory);
        let options = Options {
            t_end: self.t_end,
            seed: self.seed,
            record_every: self.every,
            ..Default::default()
        };
        let problem = self.model.problem(&p)?.with_start(self.u0, self.v0)?;
        method.validate()?;
        options.steps(method.dt)?;
        let warnings = guard_step(&problem, &method)?;
        Ok(Setup {
            problem,
            method,
            options,
            warnings,
        })
    }
}

fn method_line(a: &SimulateArgs) -> String {
    format!(
        "method: predictor-corrector dt={} t_end={} {} u0={} v0={} seed={} every={}",
        a.dt,
        a.t_end,
        a.model.line(a.impact_memory),
        a.u0,
        a.v0,
        a.seed,
        a.every
    )
}

/// Most rows `simulate` writes as CSV (streamed; ~5 GB).
pub const MAX_CSV_ROWS: u64 = 100_000_000;
/// Most samples `simulate` holds for a JSON document.
pub const MAX_JSON_SAMPLES: u64 = 1_000_000;

/// Streams the CSV rows of a path while a [`TrajectoryRecorder`] keeps its summary.
struct CsvRows<'a> {
    out: &'a mut dyn Write,
    every: u64,
    eta: bool,
    summary: TrajectoryRecorder,
    error: Option<std::io::Error>,
}

impl Observer for CsvRows<'_> {
    fn observe(&mut self, s: &Stepper) -> Flow {
        self.summary.observe(s);
        if s.steps() % self.every == 0 {
            let (t, u, v) = (num(s.time()), num(s.u()), num(s.v()));
            let written = if self.eta {
                writeln!(self.out, "{t},{u},{v},{}", num(s.eta()))
            } else {
                writeln!(self.out, "{t},{u},{v}")
            };
            if let Err(e) = written {
                self.error = Some(e);
                return Flow::Stop;
            }
        }
        Flow::Continue
    }
}

/// Refuse a request for more rows than the format holds, before any work starts.
fn check_rows(args: &SimulateArgs, steps: u64) -> Result<()> {
    let rows = steps / args.every as u64 + 1;
    let (most, what) = match args.format {
        SimFormat::Json => (MAX_JSON_SAMPLES, "samples"),
        SimFormat::Csv => (MAX_CSV_ROWS, "rows"),
    };
    if rows <= most {
        return Ok(());
    }
    let raise = format!("raise --every to {} or more", steps / (most - 1) + 1);
    let limit = match args.format {
        SimFormat::Json => {
            format!("JSON holds at most {most} ({raise}, or use --format csv, which streams)")
        }
        SimFormat::Csv => format!("at most {most} rows are written ({raise})"),
    };
    bad(format!(
        "--every {}: {rows} {what} of {steps} steps; {limit}",
        args.every
    ))
}

/// Run `simulate`. CSV is streamed row by row (memory independent of the number of steps);
/// JSON is one document held in memory, so it is bounded by [`MAX_JSON_SAMPLES`].
pub fn simulate(args: &SimulateArgs) -> Result<()> {
    let s = args.setup()?;
    let steps = s.options.steps(s.method.dt)?;
    check_rows(args, steps)?;
    let bar = progress(1000, "simulate");
    let report = Report(|done: u64, total: u64| {
        bar.set_position((done as f64 / total as f64 * 1000.0) as u64)
    });
    let start = Instant::now();
    if args.format == SimFormat::Json {
        let tr = simulate_with(&s.problem, &s.method, &s.options, &report)?;
        let wall = start.elapsed().as_secs_f64();
        bar.finish_and_clear();
        let mut m = serde_json::Map::new();
        m.insert("params".into(), params_json(s.problem.params()));
        if let Some(t) = s.problem.oscillator().terms() {
            m.insert("terms".into(), json!(t.describe()));
        }
        m.insert("method".into(), json!(method_line(args)));
        m.insert("step_warnings".into(), json!(s.warnings));
        m.insert("summary".into(), json!(PathSummary::of(&tr, wall)));
        m.insert("t".into(), jvec(&tr.t));
        m.insert("U".into(), jvec(&tr.u));
        m.insert("V".into(), jvec(&tr.v));
        if !tr.eta.is_empty() {
            m.insert("eta".into(), jvec(&tr.eta));
        }
        let text = serde_json::to_string(&Value::Object(m))? + "\n";
        return emit(args.out.as_deref(), &text);
    }
    let tr = stream_csv(args, &s, steps, &report, &bar)?;
    eprintln!(
        "{}",
        PathSummary::of(&tr, start.elapsed().as_secs_f64()).line()
    );
    Ok(())
}

/// Stream the path as CSV `t,U,V[,eta]` to the output while keeping its summary.
fn stream_csv(
    args: &SimulateArgs,
    s: &Setup,
    steps: u64,
    report: &dyn Monitor,
    bar: &crate::io::Progress,
) -> Result<Trajectory> {
    let mut stepper = s.options.stepper(&s.problem, &s.method)?;
    let eta = !s.problem.oscillator().noise().is_none();
    let quiet = Options {
        record_every: usize::MAX,
        ..s.options.clone()
    };
    let summary = TrajectoryRecorder::new(s.problem.oscillator(), &quiet, steps, s.method.dt)?;
    let mut stream = Stream::open(args.out.as_deref())?;
    let w = stream.writer();
    writeln!(w, "# trirhythm simulate: {steps} steps")?;
    writeln!(w, "# params: {}", s.problem.params().describe())?;
    if let Some(t) = s.problem.oscillator().terms() {
        writeln!(w, "# terms: {}", t.describe())?;
    }
    writeln!(w, "# {}", method_line(args))?;
    for warning in &s.warnings {
        writeln!(w, "# warning: {warning}")?;
    }
    writeln!(w, "{}", if eta { "t,U,V,eta" } else { "t,U,V" })?;
    let mut rows = CsvRows {
        out: w,
        every: args.every as u64,
        eta,
        summary,
        error: None,
    };
    let result = run(&mut stepper, steps, &mut rows, report);
    bar.finish_and_clear();
    if let Some(e) = rows.error {
        return Err(e).context("writing the path");
    }
    if let Err(e) = result {
        if let Stream::Stdout(w) = &mut stream {
            // a streamed table ends with the reason it ends early
            let _ = writeln!(w, "# error: {e}");
            let _ = w.flush();
        }
        return Err(e.into());
    }
    let tr = rows.summary.finish(&stepper);
    stream.finish()?;
    Ok(tr)
}
