//! Command-line arguments shared by the commands: clap structs and value enums, each mapped
//! to its library type once (`From`, or a method). Parses; never computes or writes. Depends on
//! [`crate::error`] only.

use crate::error::bad;
use anyhow::{Context, Result};
use clap::{Args, ValueEnum};
use std::path::PathBuf;
use trirhythm::engine::{
    Barrier, ImpactMemory, Lanes, PredictorCorrector, Problem, System, LANE_WIDTHS,
};
use trirhythm::model::{preset, Params};
use trirhythm::theory::averaging::Variant;
use trirhythm_paper::requests::{MemoryKind, Model};

/// The name a value of a value enum has on the command line (`soe`, `restart`).
pub trait Named {
    /// The name as typed.
    fn name(&self) -> String;
}

impl<T: ValueEnum> Named for T {
    fn name(&self) -> String {
        self.to_possible_value()
            .map(|p| p.get_name().to_string())
            .unwrap_or_default()
    }
}

/// `From<$arg> for $lib` where both enums have the same variants.
macro_rules! same_variants {
    ($arg:ident => $lib:ident: $($v:ident),+) => {
        impl From<$arg> for $lib {
            fn from(a: $arg) -> Self {
                match a {
                    $($arg::$v => $lib::$v,)+
                }
            }
        }
    };
}

/// `soe` or `direct`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum, Default)]
pub enum MemoryArg {
    /// Sum of exponentials beyond an 8-step exact window: O(1) work and memory per step.
    #[default]
    Soe,
    /// Exact weights over the whole history: O(N) per step (reference; short runs only).
    Direct,
}

/// `continuous` or `restart`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum, Default)]
pub enum ImpactMemoryArg {
    /// The lower terminal stays at 0; jumps are constants in V's Volterra form.
    #[default]
    Continuous,
    /// The memory restarts at each impact.
    Restart,
}

same_variants!(ImpactMemoryArg => ImpactMemory: Continuous, Restart);

/// `on` or `off`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum, Default)]
pub enum OnOff {
    /// The wall at U = 0 with U̇₊ = −rU̇₋.
    #[default]
    On,
    /// No wall: the same equation on the whole line.
    Off,
}

same_variants!(OnOff => Barrier: On, Off);

/// `fractional`, `equivalent` or `zhuravlev`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum, Default)]
pub enum SystemArg {
    /// Eq. (1), the fractional system.
    #[default]
    Fractional,
    /// Eq. (5), the harmonic-balance integer-order equivalent.
    Equivalent,
    /// Eq. (9), Eq. (5) after Zhuravlev's transformation (Z on the whole line).
    Zhuravlev,
}

same_variants!(SystemArg => System: Fractional, Equivalent, Zhuravlev);

/// `csv` or `json`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum, Default)]
pub enum SimFormat {
    /// `t,U,V[,eta]` rows, `#` header lines; summary on standard error.
    #[default]
    Csv,
    /// One JSON object: parameters, method, summary, columns.
    Json,
}

/// `paper` or `consistent` (see the `averaging` module).
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum, Default)]
pub enum VariantArg {
    /// The paper's formulas as printed (Eq. 27's typo fixed).
    #[default]
    Paper,
    /// The corrected formulas (exact impact loss, coloured noise through sgn Z).
    Consistent,
}

same_variants!(VariantArg => Variant: Paper, Consistent);
same_variants!(Variant => VariantArg: Paper, Consistent);

/// Parameter selection: a preset, then `--param KEY=VALUE` overrides.
#[derive(Debug, Clone, Args)]
pub struct ParamArgs {
    /// A figure's parameter set (e.g. fig4c); without it, Fig. 4(c)'s set with r = 1, D = 0, τ = 0.
    #[arg(long)]
    pub preset: Option<String>,
    /// KEY=VALUE override (repeatable); KEY: mu0 omega0 lambda r alpha0 beta0 gamma0 delta0 D tau c<k>.
    #[arg(long = "param", value_name = "KEY=VALUE")]
    pub params: Vec<String>,
    /// Formula variant of the averaged theory [default: paper; with --model, paper where the
    /// paper's formulas apply to the file's model, else consistent].
    #[arg(long, value_enum)]
    pub variant: Option<VariantArg>,
    /// The parameters of a model file (`--model`), in place of a preset's.
    #[arg(skip)]
    pub base: Option<Params>,
}

impl ParamArgs {
    /// The validated parameters.
    pub fn resolve(&self) -> Result<Params> {
        let mut p = match (&self.base, &self.preset) {
            (Some(base), _) => base.clone(),
            (None, Some(name)) => preset(name)?.params,
            (None, None) => Params::default(),
        };
        for kv in &self.params {
            let Some((k, v)) = kv.split_once('=') else {
                return bad(format!("--param expects KEY=VALUE, got `{kv}`"));
            };
            let Ok(value) = v.trim().parse() else {
                return bad(format!(
                    "invalid value for parameter {}: `{v}` is not a number",
                    k.trim()
                ));
            };
            p.set(k.trim(), value)?;
        }
        p.validate()?;
        Ok(p)
    }

    /// The variant as the library's type (paper unless chosen).
    pub fn variant(&self) -> Variant {
        self.variant.map_or(Variant::Paper, Into::into)
    }

    /// The variant for a model file's model: the one chosen, else the paper's where its
    /// formulas apply to `model` and the consistent one where they do not (a model outside
    /// Eq. (1) with its wall at 0: the paper's κ and σ1 are printed for that equation only).
    pub fn variant_for(&self, model: &trirhythm::model::Model) -> Variant {
        match self.variant {
            Some(v) => v.into(),
            None if trirhythm::theory::averaging::applies(model, Variant::Paper).is_ok() => {
                Variant::Paper
            }
            None => Variant::Consistent,
        }
    }
}

/// `--model FILE`: a model file (`docs/model-file.md`) in place of `--preset`, `--barrier` and
/// the start flags.
#[derive(Debug, Clone, Args)]
pub struct ModelFileArg {
    /// A model file (`trirhythm model show` prints one): the equation, the wall and the start,
    /// in place of --preset, --barrier and --u0/--v0; --param KEY=VALUE still overrides its
    /// parameters. The engine steps the paper's family and Duffing, Rayleigh, forcing,
    /// multiplicative-noise (no wall, the wall at 0) and fractional terms (no wall), with no
    /// wall, one wall at any position (keeping U above or below it) or two walls, each with a
    /// constant or speed-dependent restitution; other terms are refused.
    #[arg(long = "model", value_name = "FILE", conflicts_with = "preset")]
    pub model: Option<PathBuf>,
}

impl ModelFileArg {
    /// The file's model as the engine steps it (none without `--model`): read, validated,
    /// and refused by name where it has a term the engine does not step; the paper family's
    /// part and the General kernel's terms (Duffing, Rayleigh, forcing, walls other than the
    /// paper's; none for the paper's family), with the model itself (the commands built on the
    /// theory ask it whether the theory applies).
    #[allow(clippy::type_complexity)]
    pub fn load(
        &self,
    ) -> Result<
        Option<(
            trirhythm::model::Model,
            trirhythm::model::PaperFamily,
            Option<trirhythm::model::GeneralTerms>,
        )>,
    > {
        let Some(path) = &self.model else {
            return Ok(None);
        };
        let model = crate::io::files::read_model(path, "--model")?;
        let (family, terms) = model
            .engine_terms("the engine")
            .with_context(|| format!("--model {}", path.display()))?;
        Ok(Some((model, family, terms)))
    }
}

/// `--model FILE` on the commands of the averaged theory (`docs/model-file.md`, "what the
/// averaged theory covers").
#[derive(Debug, Clone, Args)]
pub struct TheoryModelArg {
    /// A model file (`trirhythm model show` prints one) in place of --preset: its averaged
    /// theory by phase quadrature, or the refusal naming the term it does not cover (exit 2);
    /// --param KEY=VALUE overrides only a model of the paper's family.
    #[arg(long = "model", value_name = "FILE", conflicts_with = "preset")]
    pub model: Option<PathBuf>,
}

impl TheoryModelArg {
    /// The file's model (none without `--model`), with the `--param` overrides of `params`
    /// applied when it is of the paper's family (refused otherwise: the file says it).
    pub fn load(&self, params: &ParamArgs) -> Result<Option<trirhythm::model::Model>> {
        let Some(path) = &self.model else {
            return Ok(None);
        };
        let model = crate::io::files::read_model(path, "--model")?;
        if params.params.is_empty() {
            return Ok(Some(model));
        }
        let family = match model.paper_family("--param") {
            Ok(f) => f,
            Err(e) => {
                return bad(format!(
                    "--param overrides the paper family's parameters; --model {} is outside it \
                     ({e}): change the file instead",
                    path.display()
                ))
            }
        };
        let resolved = ParamArgs {
            base: Some(family.params),
            ..params.clone()
        }
        .resolve()?;
        let mut out = trirhythm::model::Model::from(&resolved);
        if !family.wall {
            out.walls.clear();
        }
        out.start = model.start;
        Ok(Some(out))
    }

    /// The paper family's parameters of `--model FILE` for a command that sweeps them (a map,
    /// branches): the file's model must be the paper's Eq. (1) with its wall at 0, else the
    /// refusal naming the term. Sets `params.base`; nothing without `--model`.
    pub fn paper_base(&self, params: &mut ParamArgs, command: &str) -> Result<()> {
        let Some(path) = &self.model else {
            return Ok(());
        };
        let model = crate::io::files::read_model(path, "--model")?;
        let refuse = |reason: String| -> Result<()> {
            Err(anyhow::Error::new(trirhythm::Error::NotApplicable {
                method: format!("`{command}`"),
                assumption: "the paper's Eq. (1) with its wall at 0 (it sweeps the paper's \
                             parameters --x/--y)"
                    .into(),
                reason,
            }))
            .with_context(|| format!("--model {}", path.display()))
        };
        // the theory must apply before anything is swept
        if let Err(e) = trirhythm::theory::averaging::applies(&model, params.variant()) {
            return Err(anyhow::Error::new(e))
                .with_context(|| format!("--model {}", path.display()));
        }
        match model.paper_family(&format!("`{command}`")) {
            Ok(f) if f.wall => {
                params.base = Some(f.params);
                Ok(())
            }
            Ok(_) => refuse(
                "wall: none; the map's closed forms are those of the wall at 0: the theory \
                 commands (cycles, drift, potential, barriers, pdf) take this model"
                    .into(),
            ),
            Err(trirhythm::Error::NotApplicable { reason, .. }) => refuse(format!(
                "{}; the theory commands (cycles, drift, potential, barriers, pdf) take this model",
                reason.split(": the engine").next().unwrap_or(&reason)
            )),
            Err(e) => Err(anyhow::Error::new(e)),
        }
    }
}

/// `on` for a wall, `off` for none.
pub fn on_off(wall: bool) -> OnOff {
    if wall {
        OnOff::On
    } else {
        OnOff::Off
    }
}

/// Output format.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum, Default)]
pub enum Format {
    /// Aligned text for reading.
    #[default]
    Table,
    /// JSON object.
    Json,
    /// Comma-separated values with a `#` header.
    Csv,
}

/// Output selection.
#[derive(Debug, Clone, Args)]
pub struct OutputArgs {
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Table)]
    pub format: Format,
    /// Write to this file (atomically) instead of standard output.
    #[arg(long)]
    pub out: Option<PathBuf>,
}

/// A grid `START:STOP:COUNT` of `COUNT` equally spaced points.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Grid {
    /// First point.
    pub start: f64,
    /// Last point.
    pub stop: f64,
    /// Number of points (≥ 2).
    pub count: usize,
}

impl Grid {
    /// Parse `START:STOP:COUNT`; `what` names the flag in errors.
    pub fn parse(s: &str, what: &str) -> Result<Grid> {
        let parts: Vec<&str> = s.split(':').collect();
        if parts.len() != 3 {
            return bad(format!("{what} expects START:STOP:COUNT, got `{s}`"));
        }
        let num = |t: &str| -> Result<f64> {
            match t.trim().parse::<f64>() {
                Ok(v) if v.is_finite() => Ok(v),
                _ => bad(format!("{what}: `{t}` is not a finite number (in `{s}`)")),
            }
        };
        let (start, stop) = (num(parts[0])?, num(parts[1])?);
        let count: usize = match parts[2].trim().parse() {
            Ok(c) if (2..=10_000_000).contains(&c) => c,
            _ => {
                return bad(format!(
                    "{what}: COUNT = `{}` must be an integer in [2, 10000000]",
                    parts[2]
                ))
            }
        };
        if start >= stop {
            return bad(format!(
                "{what}: START = {start} must be below STOP = {stop}"
            ));
        }
        Ok(Grid { start, stop, count })
    }

    /// The points.
    pub fn points(&self) -> Vec<f64> {
        let h = (self.stop - self.start) / (self.count - 1) as f64;
        (0..self.count).map(|i| self.start + h * i as f64).collect()
    }
}

/// Parse `KEY=START:STOP:COUNT` (or `KEY=START:STOP` when `with_count` is false) for `flag`.
pub fn parse_axis(s: &str, flag: &str, with_count: bool) -> Result<(String, Grid)> {
    let form = if with_count {
        "KEY=START:STOP:COUNT"
    } else {
        "KEY=START:STOP"
    };
    let Some((k, rest)) = s.split_once('=') else {
        return bad(format!("{flag} expects {form}, got `{s}`"));
    };
    let rest = if with_count {
        rest.to_string()
    } else if rest.split(':').count() == 2 {
        format!("{rest}:2")
    } else {
        return bad(format!("{flag} expects {form}, got `{s}`"));
    };
    Ok((k.trim().to_string(), Grid::parse(&rest, flag)?))
}

/// `--system`, `--barrier`, `--memory`, `--tolerance`: said once for every command that simulates.
#[derive(Debug, Clone, Args)]
pub struct ModelArgs {
    /// Which equation.
    #[arg(long, value_enum, default_value_t = SystemArg::Fractional)]
    pub system: SystemArg,
    /// The wall at U = 0.
    #[arg(long, value_enum, default_value_t = OnOff::On)]
    pub barrier: OnOff,
    /// How the fractional memory is kept.
    #[arg(long, value_enum, default_value_t = MemoryArg::Soe)]
    pub memory: MemoryArg,
    /// Relative tolerance of the sum-of-exponentials kernel (checked at start-up); default:
    /// 1e-5·dt² within [1e-10, 1e-6] (1e-9 at dt = 0.01), the size whose error in the solution
    /// stays below a tenth of the scheme's own (docs/numerics.md).
    #[arg(long, allow_hyphen_values = true)]
    pub tolerance: Option<f64>,
    /// The General kernel's terms of a `--model` file (Duffing, Rayleigh, forcing, fractional,
    /// multiplicative, walls).
    #[arg(skip)]
    pub terms: Option<trirhythm::model::GeneralTerms>,
}

impl ModelArgs {
    /// The library's model of these flags.
    pub fn model(&self) -> Model {
        Model {
            system: self.system.into(),
            barrier: self.barrier.into(),
            memory: match self.memory {
                MemoryArg::Soe => MemoryKind::Soe,
                MemoryArg::Direct => MemoryKind::Direct,
            },
            tolerance: self.tolerance,
        }
    }

    /// The problem of `params` with this equation and wall (its start still to be set).
    pub fn problem(&self, params: &Params) -> trirhythm::Result<Problem> {
        self.model().problem(params)?.with_terms(self.terms.clone())
    }

    /// `memory=… tolerance=… impact_memory=… barrier=… system=…`, for `method:` header lines.
    pub fn line(&self, impact_memory: ImpactMemoryArg) -> String {
        self.model().line(impact_memory.into())
    }

    /// The predictor–corrector of `--dt`, this memory and `--impact-memory`.
    pub fn method(&self, dt: f64, impact_memory: ImpactMemoryArg) -> PredictorCorrector {
        self.model().method(dt, impact_memory.into())
    }
}

/// The step guard, before any work: a `--dt` that cannot resolve the problem's time scales is
/// refused (the library's [`trirhythm::analysis::check_step`]: fewer than 10 steps per period
/// 2π/ω1, or a step-halving deviation above 10 % at the amplitudes the run visits); a coarse
/// one runs, and its warnings are printed on standard error and returned for the output.
pub fn guard_step(problem: &Problem, method: &PredictorCorrector) -> Result<Vec<String>> {
    let warnings = trirhythm::analysis::check_step(problem, method)?
        .require()?
        .warnings();
    crate::io::progress::count_check();
    for w in &warnings {
        crate::io::progress::note(&format!("warning: {w}"));
    }
    Ok(warnings)
}

/// Which options the user typed: clap's record of where each value came from (the command
/// line, or a default). A default is never refused; a value typed for an option that the
/// chosen command or method does not use is ([`Given::refuse`]).
pub struct Given<'a>(Option<&'a clap::ArgMatches>);

impl<'a> Given<'a> {
    /// The matches of the subcommand run (none: nothing typed).
    pub fn of(matches: Option<&'a clap::ArgMatches>) -> Given<'a> {
        Given(matches)
    }

    /// Whether the argument `id` (its field name) was typed on the command line.
    pub fn typed(&self, id: &str) -> bool {
        self.0.is_some_and(|m| {
            m.try_contains_id(id).unwrap_or(false)
                && m.value_source(id) == Some(clap::parser::ValueSource::CommandLine)
        })
    }

    /// Bad input for the first of `options` (`(id, flag)`) typed: "FLAG applies to WHAT only
    /// (WHY); leave it out (it would be ignored here)".
    pub fn refuse(&self, options: &[(&str, &str)], applies_to: &str, why: &str) -> Result<()> {
        match options.iter().find(|(id, _)| self.typed(id)) {
            Some((_, flag)) => bad(format!(
                "{flag} applies to {applies_to} only{}; leave it out (it would be ignored here)",
                if why.is_empty() {
                    String::new()
                } else {
                    format!(" ({why})")
                }
            )),
            None => Ok(()),
        }
    }
}

/// `--lanes`: the paths or simulations stepped together, 1, 4 or 8 (none: the library's
/// default, [`Lanes::Auto`]).
pub fn lanes(w: Option<usize>) -> Result<Lanes> {
    match w {
        None => Ok(Lanes::Auto),
        Some(w) => {
            crate::error::allowed(LANE_WIDTHS.contains(&w), "--lanes", w, "1, 4 or 8")?;
            Ok(Lanes::Width(w))
        }
    }
}
