//! `trirhythm ensemble`: N paths, streamed stationary statistics with standard errors, the
//! stationarity diagnosis, and the averaged theory (both variants) against the simulation.
//!
//! Output: one JSON object (`--format json`, the default) or the amplitude histogram as CSV
//! `A_lo,A_hi,density,stderr` with the summary in `#` lines. A summary goes to standard error.
//! With `--checkpoint DIR` every finished path's statistics are saved in DIR; a rerun of the
//! same command continues from them and gives a bit-identical result. Keys, columns and flags
//! are a contract: keep them.

use crate::args::{ImpactMemoryArg, MemoryArg, Named, OnOff, ParamArgs, SystemArg};
use crate::error::bad;
use crate::io::{emit, jnum, params_json, progress};
use anyhow::{Context, Result};
use clap::{Args, ValueEnum};
use serde_json::{json, Value};
use std::path::{Path, PathBuf};
use std::time::Instant;
use trirhythm::analysis::ensemble::{
    merge, run_paths, EnsembleResult, EnsembleSpec, PathStats, Wells,
};
use trirhythm::analysis::versus::{theory_layout, TheoryComparison};
use trirhythm::engine::{PredictorCorrector, Problem};
use trirhythm::model::Params;
use trirhythm::monitor::Monitor;
use trirhythm::theory::averaging::Variant;
use trirhythm_paper::montecarlo::comparisons;

/// `json` or `csv`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum, Default)]
pub enum EnsembleFormat {
    /// One JSON object with every statistic.
    #[default]
    Json,
    /// The amplitude histogram `A_lo,A_hi,density,stderr`, the summary in `#` lines.
    Csv,
}

/// Arguments of `ensemble`.
#[derive(Debug, Args)]
pub struct EnsembleArgs {
    #[command(flatten)]
    pub params: ParamArgs,
    /// Number of paths (path i is noise stream i of the seed).
    #[arg(long, default_value_t = 8, allow_hyphen_values = true)]
    pub paths: usize,
    /// Length of each path's recorded window, after the burn-in.
    #[arg(long = "t-end", default_value_t = 1000.0, allow_hyphen_values = true)]
    pub t_end: f64,
    /// Time discarded at the start of each path.
    #[arg(long = "burn-in", default_value_t = 100.0, allow_hyphen_values = true)]
    pub burn_in: f64,
    /// Step Δt.
    #[arg(long, default_value_t = 0.01, allow_hyphen_values = true)]
    pub dt: f64,
    /// Seed of the noise streams.
    #[arg(long, default_value_t = 1, allow_hyphen_values = true)]
    pub seed: u64,
    /// Initial displacements, used in turn by the paths (default: the theory's modes of P(A),
    /// or its stable limit cycles at D = 0).
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    pub u0: Vec<f64>,
    /// Which equation.
    #[arg(long, value_enum, default_value_t = SystemArg::Fractional)]
    pub system: SystemArg,
    /// What the memory does at an impact. Ensembles default to `restart`: under `continuous`
    /// the noise-free cycle of Eq. 1 keeps drifting (no stationary state found up to t = 3e5),
    /// under `restart` it settles (README, "Ensembles").
    #[arg(long = "impact-memory", value_enum, default_value_t = ImpactMemoryArg::Restart)]
    pub impact_memory: ImpactMemoryArg,
    /// The wall at U = 0.
    #[arg(long, value_enum, default_value_t = OnOff::On)]
    pub barrier: OnOff,
    /// How the fractional memory is kept.
    #[arg(long, value_enum, default_value_t = MemoryArg::Soe)]
    pub memory: MemoryArg,
    /// Relative tolerance of the sum-of-exponentials kernel.
    #[arg(long, default_value_t = 1e-10, allow_hyphen_values = true)]
    pub tolerance: f64,
    /// Bins of the amplitude, turning-amplitude and energy histograms.
    #[arg(long, default_value_t = 100, allow_hyphen_values = true)]
    pub bins: usize,
    /// Bins per axis of the joint (U, U̇) histogram.
    #[arg(long = "joint-bins", default_value_t = 48, allow_hyphen_values = true)]
    pub joint_bins: usize,
    /// Upper end of the amplitude histogram (default: from the theory's densities).
    #[arg(long = "amplitude-max", allow_hyphen_values = true)]
    pub amplitude_max: Option<f64>,
    /// Record every K-th step of the window.
    #[arg(long = "sample-every", default_value_t = 1, allow_hyphen_values = true)]
    pub sample_every: u64,
    /// Save each finished path's statistics here; a rerun continues from them.
    #[arg(long)]
    pub checkpoint: Option<PathBuf>,
    /// Output format.
    #[arg(long, value_enum, default_value_t = EnsembleFormat::Json)]
    pub format: EnsembleFormat,
    /// Write to this file (atomically) instead of standard output.
    #[arg(long)]
    pub out: Option<PathBuf>,
}

/// An ensemble's inputs in library types, with the choices made for the user.
pub struct EnsembleSetup {
    pub params: Params,
    pub problem: Problem,
    pub method: PredictorCorrector,
    pub spec: EnsembleSpec,
    /// What was chosen where the user left a value open (printed with the result).
    pub choices: Vec<String>,
}

impl EnsembleArgs {
    /// Validate and convert, filling the open choices from the theory.
    pub fn setup(&self) -> Result<EnsembleSetup> {
        let params = self.params.resolve()?;
        let method = crate::args::method(self.dt, self.memory, self.tolerance, self.impact_memory);
        let layout = theory_layout(&params, self.params.variant());
        let mut choices = Vec::new();
        let starts = if !self.u0.is_empty() {
            self.u0.clone()
        } else if let Some(l) = &layout {
            choices.push(format!(
                "u0 = {} (the theory's modes, {} variant)",
                list(&l.starts),
                self.params.variant().name()
            ));
            l.starts.clone()
        } else {
            return bad(
                "--u0: the averaged theory offers no cycle to start from for these parameters; \
                 give the initial displacements (--u0 A[,A…])",
            );
        };
        let amplitude_max = match (self.amplitude_max, &layout) {
            (Some(a), _) => a,
            (None, Some(l)) => {
                let a = l
                    .amplitude_max
                    .max(1.2 * starts.iter().fold(0.0f64, |m, x| m.max(x.abs())));
                choices.push(format!(
                    "amplitude-max = {a:.4} (1.2 × the theory's largest mode + 6 widths)"
                ));
                a
            }
            (None, None) => {
                return bad(
                    "--amplitude-max: no theory to choose the histogram range from; give it",
                )
            }
        };
        let wells: Option<Wells> = layout.and_then(|l| l.wells);
        if let Some(w) = &wells {
            choices.push(format!(
                "wells: modes {} and antimodes {} of P(A) ({} variant)",
                list(&w.modes),
                list(&w.antimodes),
                self.params.variant().name()
            ));
        }
        let spec = EnsembleSpec {
            paths: self.paths,
            seed: self.seed,
            burn_in: self.burn_in,
            length: self.t_end,
            sample_every: self.sample_every,
            bins: self.bins,
            joint_bins: self.joint_bins,
            amplitude_max,
            wells,
            ..Default::default()
        };
        let starts: Vec<(f64, f64)> = starts.iter().map(|&u| (u, 0.0)).collect();
        let problem = Problem::from_params(&params)?
            .with_barrier(self.barrier.into())?
            .with_system(self.system.into())?
            .with_starts(&starts)?;
        Ok(EnsembleSetup {
            problem,
            params,
            method,
            spec,
            choices,
        })
    }
}

fn list(v: &[f64]) -> String {
    v.iter()
        .map(|x| format!("{x:.4}"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// A statistic that may be undefined (NaN: one unit; ∞: R̂ of chains that never mix): `null`
/// then, as documented, rather than an error.
fn jstat(v: f64) -> Value {
    serde_json::Number::from_f64(v).map_or(Value::Null, Value::Number)
}

fn jest(e: trirhythm::analysis::Estimate) -> Value {
    json!({"value": jstat(e.value), "stderr": jstat(e.stderr)})
}

fn jvec(v: &[f64]) -> Value {
    Value::Array(v.iter().map(|&x| jnum(x)).collect())
}

fn jstats(v: &[f64]) -> Value {
    Value::Array(v.iter().map(|&x| jstat(x)).collect())
}

fn theory_json(c: &TheoryComparison) -> Value {
    json!({
        "hellinger": jnum(c.hellinger.value),
        "hellinger_stderr": jstat(c.hellinger.stderr),
        "l1": jnum(c.l1.value),
        "l1_stderr": jstat(c.l1.stderr),
        "ks": jnum(c.ks.value),
        "ks_stderr": jstat(c.ks.stderr),
        "modes_theory": c.modes_theory,
        "modes_theory_exact": c.modes_theory_exact,
        "modes_mc": c.modes_mc,
        "mean_amplitude": jnum(c.mean_amplitude),
        "occupancy": jvec(&c.occupancy),
        "escape_times": jstats(&c.escape_times),
        "density": jvec(&c.density),
    })
}

fn method_line(a: &EnsembleArgs) -> String {
    format!(
        "method: predictor-corrector dt={} memory={} tolerance={} impact_memory={} barrier={} \
         system={} paths={} burn_in={} t_end={} seed={} sample_every={}",
        a.dt,
        a.memory.name(),
        a.tolerance,
        a.impact_memory.name(),
        a.barrier.name(),
        a.system.name(),
        a.paths,
        a.burn_in,
        a.t_end,
        a.seed,
        a.sample_every
    )
}

/// The whole result as the JSON document of the command's contract.
pub fn result_json(
    s: &EnsembleSetup,
    method: &str,
    r: &EnsembleResult,
    theory: &[(Variant, std::result::Result<TheoryComparison, String>)],
    wall: f64,
) -> Value {
    let mut warnings: Vec<Value> = r.warnings.iter().map(|w| json!(w)).collect();
    let mut th = serde_json::Map::new();
    for (v, c) in theory {
        match c {
            Ok(c) => {
                th.insert(v.name().into(), theory_json(c));
            }
            Err(e) => warnings.push(json!(format!("{} theory: {e}", v.name()))),
        }
    }
    let st = &r.stationarity;
    let density = |d: &trirhythm::analysis::ensemble::Density| {
        json!({"edges": jvec(&d.edges), "density": jvec(&d.density),
               "stderr": jstats(&d.stderr), "beyond": jnum(d.beyond), "count": d.count})
    };
    let passages: Vec<Value> = r
        .passages
        .iter()
        .map(|p| {
            json!({"from": p.from, "to": p.to, "count": p.count, "censored": p.censored,
                   "mean_time": jest(p.mean_time)})
        })
        .collect();
    json!({
        "params": params_json(&s.params),
        "method": method,
        "choices": s.choices,
        "summary": {
            "paths": r.paths,
            "steps_per_path": r.steps_per_path,
            "burn_in_steps": r.burn_in_steps,
            "samples_per_path": r.samples_per_path,
            "wall_time_s": jnum(wall),
            "omega1": jnum(r.omega1),
            "impacts": r.impacts,
            "sticking_steps": r.sticking_steps,
            "stderr_units": if r.between_paths { "paths" } else { "batches of the one path" },
        },
        "moments": {
            "mean_U": jest(r.mean_u),
            "var_U": jest(r.var_u),
            "mean_V": jest(r.mean_v),
            "var_V": jest(r.var_v),
            "mean_A": jest(r.mean_amplitude),
        },
        "stationarity": {
            "r_hat": jstat(st.r_hat),
            "r_hat_amplitude": jstat(st.r_hat_amplitude),
            "r_hat_wells": jstats(&st.r_hat_wells),
            "ess": jnum(st.ess),
            "drift": jnum(st.drift),
            "drift_z": jstat(st.drift_z),
            "stationary": st.stationary,
            "suggested_t_end": jstat(st.suggested_length),
        },
        "warnings": warnings,
        "amplitude_pdf": density(&r.amplitude),
        "turning_amplitude_pdf": density(&r.turning),
        "energy_pdf": density(&r.energy),
        "joint_pdf": {
            "u_edges": jvec(&r.joint.u_edges),
            "v_edges": jvec(&r.joint.v_edges),
            "density": Value::Array(r.joint.density.iter().map(|row| jvec(row)).collect()),
            "stderr": Value::Array(r.joint.stderr.iter().map(|row| jstats(row)).collect()),
            "outside": jnum(r.joint.outside),
        },
        "wells": r.wells.as_ref().map(|w| json!({"modes": jvec(&w.modes), "antimodes": jvec(&w.antimodes)})),
        "occupancy": Value::Array(r.occupancy.iter().map(|&e| jest(e)).collect()),
        "passages": passages,
        "theory": th,
    })
}

/// The checkpoint directory of a run: `run.txt` names the run, `path-<i>.json` hold finished
/// paths.
struct Checkpoint {
    dir: PathBuf,
}

impl Checkpoint {
    fn open(dir: &Path, fingerprint: &str, paths: usize) -> Result<(Checkpoint, Vec<PathStats>)> {
        if dir.exists() && !dir.is_dir() {
            return bad(format!(
                "--checkpoint {}: exists and is not a directory",
                dir.display()
            ));
        }
        std::fs::create_dir_all(dir)
            .with_context(|| format!("creating the checkpoint directory {}", dir.display()))?;
        let tag = dir.join("run.txt");
        let mut done = Vec::new();
        match std::fs::read_to_string(&tag) {
            Ok(text) if text == fingerprint => {
                for i in 0..paths {
                    let f = dir.join(format!("path-{i}.json"));
                    if let Ok(t) = std::fs::read_to_string(&f) {
                        let p: PathStats = serde_json::from_str(&t)
                            .with_context(|| format!("reading the checkpoint {}", f.display()))?;
                        done.push(p);
                    }
                }
            }
            Ok(_) => {
                return bad(format!(
                    "--checkpoint {}: holds another run (different parameters, method or \
                     sizes); use an empty directory",
                    dir.display()
                ))
            }
            Err(_) => crate::io::write_atomic(&tag, fingerprint.as_bytes())?,
        }
        Ok((
            Checkpoint {
                dir: dir.to_path_buf(),
            },
            done,
        ))
    }

    fn save(&self, p: &PathStats) -> Result<()> {
        let text = serde_json::to_string(p)?;
        crate::io::write_atomic(
            &self.dir.join(format!("path-{}.json", p.path)),
            text.as_bytes(),
        )
    }
}

/// How the command watches its run: the progress bar, and each finished path saved in the
/// checkpoint directory.
struct Watch<'a> {
    bar: &'a indicatif::ProgressBar,
    checkpoint: Option<&'a Checkpoint>,
    save_error: std::sync::Mutex<Option<anyhow::Error>>,
}

impl Monitor<PathStats> for Watch<'_> {
    fn progress(&self, done: u64, total: u64) {
        let f = done as f64 / total as f64;
        self.bar.set_position((f * 1000.0).min(1000.0) as u64);
    }

    fn finished(&self, p: &PathStats) -> trirhythm::Result<()> {
        if let Some(c) = self.checkpoint {
            if let Err(e) = c.save(p) {
                *self.save_error.lock().unwrap_or_else(|e| e.into_inner()) = Some(e);
                return Err(trirhythm::Error::Undefined {
                    what: "checkpoint",
                    why: "a path's statistics could not be saved".into(),
                });
            }
        }
        Ok(())
    }
}

/// Run `ensemble`.
pub fn ensemble(args: &EnsembleArgs) -> Result<()> {
    let s = args.setup()?;
    let method = method_line(args);
    let fingerprint = format!(
        "trirhythm ensemble\nparams: {}\n{method}\nspec: {:?}\nstarts: {:?} system: {:?} barrier: {:?} \
         blow_up: {:e}\n",
        s.params.describe(),
        s.spec,
        s.problem.starts(),
        s.problem.system(),
        s.problem.barrier(),
        s.problem.blow_up()
    );
    let (checkpoint, done) = match &args.checkpoint {
        Some(dir) => {
            let (c, d) = Checkpoint::open(dir, &fingerprint, args.paths)?;
            if !d.is_empty() {
                eprintln!(
                    "checkpoint: {} of {} paths already done",
                    d.len(),
                    args.paths
                );
            }
            (Some(c), d)
        }
        None => (None, vec![]),
    };
    for c in &s.choices {
        eprintln!("chosen: {c}");
    }
    let bar = progress(1000, "ensemble");
    let start = Instant::now();
    let watch = Watch {
        bar: &bar,
        checkpoint: checkpoint.as_ref(),
        save_error: std::sync::Mutex::new(None),
    };
    let todo: Vec<u64> = (0..args.paths as u64)
        .filter(|i| !done.iter().any(|d| d.path == *i))
        .collect();
    let result = run_paths(&s.problem, &s.method, &s.spec, &todo, &watch);
    bar.finish_and_clear();
    if let Some(e) = watch
        .save_error
        .into_inner()
        .unwrap_or_else(|e| e.into_inner())
    {
        return Err(e.context("saving a checkpoint"));
    }
    let fresh = result?;
    let r = merge(
        &s.problem,
        &s.method,
        &s.spec,
        done.into_iter().chain(fresh).collect(),
    )?;
    let wall = start.elapsed().as_secs_f64();
    let theory = comparisons(&s.params, &r, args.seed);
    eprint!("{}", summary_text(&r, &theory, wall));
    let text = match args.format {
        EnsembleFormat::Json => {
            let mut t = serde_json::to_string(&result_json(&s, &method, &r, &theory, wall))?;
            t.push('\n');
            t
        }
        EnsembleFormat::Csv => csv_text(&s, &method, &r, &theory, wall),
    };
    emit(args.out.as_deref(), &text)
}

fn fmt_est(e: trirhythm::analysis::Estimate) -> String {
    if e.stderr.is_finite() {
        format!("{:.5} ± {:.5}", e.value, e.stderr)
    } else {
        format!("{:.5} (no standard error)", e.value)
    }
}

/// The human summary (standard error, and the CSV's `#` lines).
pub fn summary_text(
    r: &EnsembleResult,
    theory: &[(Variant, std::result::Result<TheoryComparison, String>)],
    wall: f64,
) -> String {
    let st = &r.stationarity;
    let mut t = format!(
        "{} paths × {} steps in {wall:.1} s; ⟨A⟩ = {}; Var U = {}; Var U̇ = {}\n\
         stationarity: {} (R̂ = {:.3}, ESS = {:.0}, drift {:.1} standard errors)\n",
        r.paths,
        r.steps_per_path,
        fmt_est(r.mean_amplitude),
        fmt_est(r.var_u),
        fmt_est(r.var_v),
        if st.stationary {
            "passed"
        } else {
            "NOT STATIONARY"
        },
        st.r_hat,
        st.ess,
        st.drift_z
    );
    if !r.occupancy.is_empty() {
        t.push_str(&format!(
            "occupancy of the wells: {}\n",
            r.occupancy
                .iter()
                .map(|&e| fmt_est(e))
                .collect::<Vec<_>>()
                .join(", ")
        ));
    }
    for (k, p) in r.passages.iter().enumerate() {
        let theory_times: Vec<String> = theory
            .iter()
            .filter_map(|(v, c)| {
                c.as_ref()
                    .ok()
                    .and_then(|c| c.escape_times.get(k))
                    .map(|t| format!("{} {t:.4e}", v.name()))
            })
            .collect();
        t.push_str(&format!(
            "first passage {} → {}: {} ({} completed, {} censored); theory's escape time: {}\n",
            p.from,
            p.to,
            if p.count > 0 {
                fmt_est(p.mean_time)
            } else {
                "none completed".into()
            },
            p.count,
            p.censored,
            theory_times.join(", ")
        ));
    }
    for (v, c) in theory {
        match c {
            Ok(c) => t.push_str(&format!(
                "theory ({}): Hellinger {:.4} ± {:.4}, L1 {:.4}, KS {:.4}; modes {} (theory, \
                 binned; {} exact) vs {} (simulation); occupancy {}\n",
                v.name(),
                c.hellinger.value,
                c.hellinger.stderr,
                c.l1.value,
                c.ks.value,
                c.modes_theory,
                c.modes_theory_exact,
                c.modes_mc,
                list(&c.occupancy)
            )),
            Err(e) => t.push_str(&format!("theory ({}): {e}\n", v.name())),
        }
    }
    for w in &r.warnings {
        t.push_str(&format!("warning: {w}\n"));
    }
    t
}

fn csv_text(
    s: &EnsembleSetup,
    method: &str,
    r: &EnsembleResult,
    theory: &[(Variant, std::result::Result<TheoryComparison, String>)],
    wall: f64,
) -> String {
    let mut t = format!(
        "# trirhythm ensemble\n# params: {}\n# {method}\n",
        s.params.describe()
    );
    for c in &s.choices {
        t.push_str(&format!("# chosen: {c}\n"));
    }
    for line in summary_text(r, theory, wall).lines() {
        t.push_str(&format!("# {line}\n"));
    }
    t.push_str("A_lo,A_hi,density,stderr\n");
    let d = &r.amplitude;
    for (i, w) in d.edges.windows(2).enumerate() {
        t.push_str(&format!(
            "{},{},{},{}\n",
            crate::io::num(w[0]),
            crate::io::num(w[1]),
            crate::io::num(d.density[i]),
            crate::io::num(d.stderr[i])
        ));
    }
    t
}
