//! `trirhythm ensemble`: N paths, streamed stationary statistics with standard errors, the
//! stationarity diagnosis, and the averaged theory (both variants) against the simulation.
//!
//! `--method wells` estimates the same statistics by well decomposition (conditional
//! statistics per well, well-to-well rates by adaptive multilevel splitting, stationary
//! weights from the rates: `trirhythm::analysis::ensemble::run_wells`): `--paths` replicas of
//! one path per well of `--t-end` each; the document adds `estimator` and `decomposition`.
//!
//! Output: one JSON object (`--format json`, the default) or the amplitude histogram as CSV
//! `A_lo,A_hi,density,stderr` with the summary in `#` lines. A summary goes to standard error.
//! With `--checkpoint DIR` every finished path's statistics are saved in DIR; a rerun of the
//! same command continues from them and gives a bit-identical result. Keys, columns and flags
//! are a contract: keep them.
//!
//! `--backend gpu` steps the direct method's paths on the GPU (`trirhythm_gpu::run_ensemble`,
//! in one piece: no `--checkpoint`, no `--lanes`, no `--method wells`); the document then adds
//! `"backend": "gpu"`. Without a driver or a device it fails before any output
//! with the GPU backend's reason (exit status 2). `cpu`, the default, is the CPU engine, the
//! same bits as before the option existed.

use crate::args::{Given, ImpactMemoryArg, ModelArgs, ModelFileArg, ParamArgs};
use crate::error::bad;
use crate::io::progress::note;
use crate::io::{emit, progress, Csv};
use anyhow::{Context, Result};
use clap::{Args, ValueEnum};
use std::path::{Path, PathBuf};
use std::time::Instant;
use trirhythm::analysis::ensemble::{
    fingerprint, merge, run_paths, EnsembleResult, PathStats, Piece, WellsSpec,
};
use trirhythm::monitor::Monitor;
use trirhythm_paper::requests::EnsembleRequest;
use trirhythm_paper::views::{self, Comparisons};

/// `json` or `csv`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum, Default)]
pub enum EnsembleFormat {
    /// One JSON object with every statistic.
    #[default]
    Json,
    /// The amplitude histogram `A_lo,A_hi,density,stderr`, the summary in `#` lines.
    Csv,
}

/// `direct` or `wells`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum, Default)]
pub enum EstimatorArg {
    /// Paths side by side, every sample counted.
    #[default]
    Direct,
    /// Well decomposition with rates by adaptive multilevel splitting.
    Wells,
}

/// `cpu` or `gpu`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum, Default)]
pub enum BackendArg {
    /// The CPU engine on every core (the reference).
    #[default]
    Cpu,
    /// The CUDA kernel on the first GPU (a CUDA driver and device needed at run time).
    Gpu,
}

impl From<BackendArg> for trirhythm_gpu::Backend {
    fn from(b: BackendArg) -> Self {
        match b {
            BackendArg::Cpu => trirhythm_gpu::Backend::Cpu,
            BackendArg::Gpu => trirhythm_gpu::Backend::Gpu,
        }
    }
}

/// Arguments of `ensemble`.
#[derive(Debug, Args)]
pub struct EnsembleArgs {
    #[command(flatten)]
    pub params: ParamArgs,
    #[command(flatten)]
    pub model: ModelArgs,
    #[command(flatten)]
    pub file: ModelFileArg,
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
    /// What the memory does at an impact. Ensembles default to `restart`: under `continuous`
    /// the noise-free cycle of Eq. 1 keeps drifting (no stationary state found up to t = 3e5),
    /// under `restart` it settles (README, "Ensembles").
    #[arg(long = "impact-memory", value_enum, default_value_t = ImpactMemoryArg::Restart)]
    pub impact_memory: ImpactMemoryArg,
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
    /// Paths stepped together: 1 (one path after the other), 4 or 8 (default 8, the fastest
    /// measured). The result is the same bits for every choice.
    #[arg(long, allow_hyphen_values = true)]
    pub lanes: Option<usize>,
    /// Save each finished path's statistics here; a rerun continues from them.
    #[arg(long)]
    pub checkpoint: Option<PathBuf>,
    /// How the stationary statistics are estimated: `direct` (the paths' samples) or `wells`
    /// (well decomposition, for wells between which direct paths do not hop: `--paths`
    /// replicas of one path per well of `--t-end` each, rates by splitting).
    #[arg(long = "method", value_enum, default_value_t = EstimatorArg::Direct)]
    pub method: EstimatorArg,
    /// `--method wells`: splitting replicas per transition.
    #[arg(long, default_value_t = 100, allow_hyphen_values = true)]
    pub clones: usize,
    /// `--method wells`: longest excursion from a well, in time units.
    #[arg(
        long = "max-excursion",
        default_value_t = 10_000.0,
        allow_hyphen_values = true
    )]
    pub max_excursion: f64,
    /// `--method wells`: most splitting iterations per transition (each kills a tenth of the
    /// replicas: n iterations resolve probabilities down to about 0.9ⁿ).
    #[arg(
        long = "max-iterations",
        default_value_t = 2_000,
        allow_hyphen_values = true
    )]
    pub max_iterations: usize,
    /// `--method wells`: residence time needed, in units of a well's relaxation time.
    #[arg(long, default_value_t = 10.0, allow_hyphen_values = true)]
    pub separation: f64,
    /// `--method wells`: cores are the [q, 1 − q] quantiles of a pilot path's turning
    /// amplitudes.
    #[arg(
        long = "core-quantile",
        default_value_t = 0.1,
        allow_hyphen_values = true
    )]
    pub core_quantile: f64,
    /// Where the paths are stepped: `cpu` (the CPU engine, the reference) or `gpu` (the CUDA
    /// kernel on the first GPU; `--method direct` only, in one piece).
    #[arg(long, value_enum, default_value_t = BackendArg::Cpu)]
    pub backend: BackendArg,
    /// Output format.
    #[arg(long, value_enum, default_value_t = EnsembleFormat::Json)]
    pub format: EnsembleFormat,
    /// Write to this file (atomically) instead of standard output.
    #[arg(long)]
    pub out: Option<PathBuf>,
}

/// An ensemble's inputs in library types, with the choices made for the user.
pub use trirhythm_paper::requests::EnsembleSetup;

impl EnsembleArgs {
    /// The request in library terms.
    pub fn request(&self) -> Result<EnsembleRequest> {
        Ok(EnsembleRequest {
            params: self.params.resolve()?,
            variant: self.params.variant(),
            model: self.model.model(),
            impact_memory: self.impact_memory.into(),
            dt: self.dt,
            paths: self.paths,
            t_end: self.t_end,
            burn_in: self.burn_in,
            seed: self.seed,
            u0: self.u0.clone(),
            bins: self.bins,
            joint_bins: self.joint_bins,
            amplitude_max: self.amplitude_max,
            sample_every: self.sample_every,
            lanes: crate::args::lanes(self.lanes)?,
            terms: self.model.terms.clone(),
        })
    }

    /// The well method's sizes.
    pub fn wells_spec(&self) -> WellsSpec {
        WellsSpec {
            clones: self.clones,
            max_excursion: self.max_excursion,
            max_iterations: self.max_iterations,
            separation: self.separation,
            core_quantile: self.core_quantile,
        }
    }

    /// Validate and convert, filling the open choices from the theory.
    pub fn setup(&self) -> Result<EnsembleSetup> {
        Ok(self.request()?.setup()?)
    }

    /// Refuse, before any work, an option typed that the chosen method does not use: the
    /// well method's sizes without `--method wells`; starts, lanes and a checkpoint with it.
    pub fn refuse_unused(&self, given: &Given) -> Result<()> {
        if self.backend == BackendArg::Gpu {
            if self.method == EstimatorArg::Wells {
                return bad(
                    "--backend gpu applies to --method direct only (the well method's \
                     splitting runs on the CPU); leave out one of them",
                );
            }
            given.refuse(
                &[("checkpoint", "--checkpoint"), ("lanes", "--lanes")],
                "--backend cpu",
                "the GPU steps the whole ensemble in one piece",
            )?;
        }
        match self.method {
            EstimatorArg::Direct => given.refuse(
                &[
                    ("clones", "--clones"),
                    ("max_excursion", "--max-excursion"),
                    ("max_iterations", "--max-iterations"),
                    ("separation", "--separation"),
                    ("core_quantile", "--core-quantile"),
                ],
                "--method wells",
                "",
            ),
            EstimatorArg::Wells => {
                given.refuse(
                    &[("u0", "--u0")],
                    "--method direct",
                    "--method wells starts one path in each of the theory's wells, at its mode",
                )?;
                given.refuse(
                    &[("lanes", "--lanes")],
                    "--method direct",
                    "--method wells steps its paths one at a time",
                )?;
                given.refuse(
                    &[("checkpoint", "--checkpoint")],
                    "--method direct",
                    "the well method's run is one piece, with no paths to save one by one",
                )
            }
        }
    }
}

/// Open the checkpoint directory of a run (`run.txt` names the run, `path-<i>.json` hold
/// finished paths, `lock` claims the directory while a run owns it): the claim and the paths
/// already done. Every path file must carry this run's fingerprint and its own index.
fn resume(
    dir: &Path,
    fingerprint: &str,
    s: &EnsembleSetup,
) -> Result<(crate::io::DirLock, Vec<PathStats>)> {
    if dir.exists() && !dir.is_dir() {
        return bad(format!(
            "--checkpoint {}: exists and is not a directory",
            dir.display()
        ));
    }
    std::fs::create_dir_all(dir)
        .with_context(|| format!("creating the checkpoint directory {}", dir.display()))?;
    let lock = crate::io::DirLock::claim(dir, fingerprint)?;
    let tag = dir.join("run.txt");
    let mut done = Vec::new();
    match std::fs::read_to_string(&tag) {
        Ok(text) if text == fingerprint => {
            for i in 0..s.spec.paths {
                let f = dir.join(format!("path-{i}.json"));
                if let Ok(t) = std::fs::read_to_string(&f) {
                    done.push(read_path(&f, &t, fingerprint, i as u64, s)?);
                }
            }
        }
        Ok(_) => {
            return bad(format!(
                "--checkpoint {}: holds another run (different parameters, method, sizes or \
                 trirhythm version); use an empty directory",
                dir.display()
            ))
        }
        Err(_) => {
            if let Some(f) = path_files(dir)?.first() {
                return bad(format!(
                    "--checkpoint {}: holds path files ({}) but no run.txt naming their run; \
                     use an empty directory",
                    dir.display(),
                    f.display()
                ));
            }
            crate::io::write_atomic(&tag, fingerprint.as_bytes())?
        }
    }
    Ok((lock, done))
}

/// The `path-*.json` files in `dir`.
fn path_files(dir: &Path) -> Result<Vec<PathBuf>> {
    let mut out = Vec::new();
    for e in std::fs::read_dir(dir)
        .with_context(|| format!("reading the checkpoint directory {}", dir.display()))?
    {
        let e = e.with_context(|| format!("reading the checkpoint directory {}", dir.display()))?;
        let n = e.file_name();
        let n = n.to_string_lossy();
        if n.starts_with("path-") && n.ends_with(".json") {
            out.push(e.path());
        }
    }
    out.sort();
    Ok(out)
}

/// A saved path, verified ([`Piece::verify`]): this run's fingerprint, the index `i` of its
/// file name and this run's shapes.
fn read_path(
    f: &Path,
    text: &str,
    fingerprint: &str,
    i: u64,
    s: &EnsembleSetup,
) -> Result<PathStats> {
    let refuse = |why: &str| -> Result<PathStats> {
        bad(format!(
            "checkpoint {}: {why}; it cannot be used for this run (remove it, or use an empty \
             directory)",
            f.display()
        ))
    };
    let piece: Piece = match serde_json::from_str(text) {
        Ok(p) => p,
        Err(e) => return refuse(&format!("not a path file of this version ({e})")),
    };
    match piece.verify(fingerprint, i, &s.problem, &s.spec) {
        Ok(p) => Ok(p),
        Err(trirhythm::Error::Undefined { why, .. }) => refuse(&why),
        Err(e) => Err(e.into()),
    }
}

/// Save a finished path in the checkpoint directory, with the run's fingerprint.
fn save(dir: &Path, fingerprint: &str, p: &PathStats) -> Result<()> {
    let piece = Piece {
        fingerprint: fingerprint.into(),
        stats: p.clone(),
    };
    let text = serde_json::to_string(&piece)?;
    crate::io::write_atomic(&dir.join(format!("path-{}.json", p.path)), text.as_bytes())
}

/// How the command watches its run: the progress bar, and each finished path saved in the
/// checkpoint directory.
struct Watch<'a> {
    bar: &'a crate::io::Progress,
    checkpoint: Option<&'a Path>,
    fingerprint: &'a str,
    save_error: std::sync::Mutex<Option<anyhow::Error>>,
}

impl Monitor<PathStats> for Watch<'_> {
    fn progress(&self, done: u64, total: u64) {
        let f = done as f64 / total as f64;
        self.bar.set_position((f * 1000.0).min(1000.0) as u64);
    }

    fn finished(&self, p: &PathStats) -> trirhythm::Result<()> {
        if let Some(c) = self.checkpoint {
            if let Err(e) = save(c, self.fingerprint, p) {
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

/// Run `ensemble --method wells`.
fn ensemble_wells(args: &EnsembleArgs, s: &EnsembleSetup) -> Result<()> {
    let wspec = args.wells_spec();
    if let Some(out) = &args.out {
        crate::io::files::check_writable(out, "--out")?;
    }
    for c in &s.choices {
        note(&format!("chosen: {c}"));
    }
    for w in &s.step_warnings {
        note(&format!("warning: {w}"));
    }
    let bar = progress(1000, "ensemble (wells)");
    let start = Instant::now();
    let watch = Ticks(&bar);
    let result = s.run_wells(&wspec, &watch);
    bar.finish_and_clear();
    let w = result?;
    let wall = start.elapsed().as_secs_f64();
    let theory = s.comparisons(&w.result);
    let summary = format!(
        "{}{}",
        views::wells(&w.wells),
        views::ensemble(&w.result, &theory, wall)
    );
    eprint!("{summary}");
    let line = trirhythm_paper::requests::wells_line(&s.method_line, &wspec);
    let text = match args.format {
        EnsembleFormat::Json => {
            serde_json::to_string(&s.wells_document(&w, &theory, wall, &line))? + "\n"
        }
        EnsembleFormat::Csv => {
            let mut notes = vec![
                "trirhythm ensemble".to_string(),
                format!("params: {}", s.params.describe()),
                line.clone(),
            ];
            notes.extend(s.terms.as_ref().map(|t| format!("terms: {}", t.describe())));
            notes.extend(s.choices.iter().map(|c| format!("chosen: {c}")));
            notes.extend(s.step_warnings.iter().map(|w| format!("warning: {w}")));
            notes.push(summary);
            Csv::of(&views::density_table(&notes, &w.result.amplitude))?
        }
    };
    emit(args.out.as_deref(), &text)
}

/// The progress bar of a run without pieces.
struct Ticks<'a>(&'a crate::io::Progress);

impl Monitor<()> for Ticks<'_> {
    fn progress(&self, done: u64, total: u64) {
        let f = done as f64 / total as f64;
        self.0.set_position((f * 1000.0).min(1000.0) as u64);
    }
}

/// Run `ensemble`.
pub fn ensemble(args: &EnsembleArgs) -> Result<()> {
    let s = args.setup()?;
    if args.method == EstimatorArg::Wells {
        return ensemble_wells(args, &s);
    }
    let method = s.method_line.clone();
    // `setup` has checked every size, step and range (no path run) before the checkpoint
    // directory or anything in it is created, so that bad input leaves nothing behind
    if let Some(out) = &args.out {
        crate::io::files::check_writable(out, "--out")?;
    }
    let fingerprint = fingerprint(&s.problem, &s.method, &s.spec);
    // the claim lives until the command returns (or a signal removes it)
    let (_lock, done) = match &args.checkpoint {
        Some(dir) => {
            let (l, d) = resume(dir, &fingerprint, &s)?;
            (Some(l), d)
        }
        None => (None, vec![]),
    };
    if !done.is_empty() {
        note(&format!(
            "checkpoint: {} of {} paths already done",
            done.len(),
            args.paths
        ));
    }
    for c in &s.choices {
        note(&format!("chosen: {c}"));
    }
    for w in &s.step_warnings {
        note(&format!("warning: {w}"));
    }
    let bar = progress(1000, "ensemble");
    let start = Instant::now();
    let watch = Watch {
        bar: &bar,
        checkpoint: args.checkpoint.as_deref(),
        fingerprint: &fingerprint,
        save_error: std::sync::Mutex::new(None),
    };
    let todo: Vec<u64> = (0..args.paths as u64)
        .filter(|i| !done.iter().any(|d| d.path == *i))
        .collect();
    let result = match args.backend {
        BackendArg::Cpu => run_paths(&s.problem, &s.method, &s.spec, &todo, &watch),
        BackendArg::Gpu => {
            // one piece, all paths (`refuse_unused` refused a checkpoint)
            let r = trirhythm_gpu::run_ensemble(
                &s.problem,
                &s.method,
                &s.spec,
                &watch,
                trirhythm_gpu::Backend::Gpu,
            );
            bar.finish_and_clear();
            return gpu_output(args, &s, &method, r?, start);
        }
    };
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
    let theory = s.comparisons(&r);
    eprint!("{}", views::ensemble(&r, &theory, wall));
    let text = match args.format {
        EnsembleFormat::Json => serde_json::to_string(&s.document(&r, &theory, wall))? + "\n",
        EnsembleFormat::Csv => csv_text(&s, &method, &r, &theory, wall)?,
    };
    emit(args.out.as_deref(), &text)
}

/// Write the GPU's ensemble: the CPU run's document with `"backend": "gpu"` added.
fn gpu_output(
    args: &EnsembleArgs,
    s: &EnsembleSetup,
    method: &str,
    r: EnsembleResult,
    start: Instant,
) -> Result<()> {
    let wall = start.elapsed().as_secs_f64();
    let theory = s.comparisons(&r);
    eprint!("{}", views::ensemble(&r, &theory, wall));
    let text = match args.format {
        EnsembleFormat::Json => {
            let mut doc = serde_json::to_value(s.document(&r, &theory, wall))?;
            if let Some(o) = doc.as_object_mut() {
                o.insert("backend".into(), "gpu".into());
            }
            serde_json::to_string(&doc)? + "\n"
        }
        EnsembleFormat::Csv => csv_text(s, &format!("{method}; backend: gpu"), &r, &theory, wall)?,
    };
    emit(args.out.as_deref(), &text)
}

/// The CSV document: the amplitude density, the run and its summary in the notes.
fn csv_text(
    s: &EnsembleSetup,
    method: &str,
    r: &EnsembleResult,
    theory: &Comparisons,
    wall: f64,
) -> Result<String> {
    let mut notes = vec![
        "trirhythm ensemble".to_string(),
        format!("params: {}", s.params.describe()),
        method.to_string(),
    ];
    notes.extend(s.terms.as_ref().map(|t| format!("terms: {}", t.describe())));
    notes.extend(s.choices.iter().map(|c| format!("chosen: {c}")));
    notes.extend(s.step_warnings.iter().map(|w| format!("warning: {w}")));
    notes.push(views::ensemble(r, theory, wall));
    Csv::of(&views::density_table(&notes, &r.amplitude))
}
