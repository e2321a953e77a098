//! `trirhythm model show` and `trirhythm model check`: the model file (`docs/model-file.md`).
//!
//! `show` prints a preset (or the default parameters) as a commented model file, the template
//! of a user's own oscillator; `check` reads a file, validates it (exit 2 naming the dotted
//! field, its value and the allowed range) and says whether the engine steps it today.
//! `show` → `check` is a round trip (`tests/model.rs`).

use crate::error::bad;
use crate::io::files::{read_model, stdout_write};
use anyhow::Result;
use clap::{Args, Subcommand};
use std::path::PathBuf;
use trirhythm::model::{preset, Model, Params};

/// `model show` or `model check`.
#[derive(Debug, Subcommand)]
pub enum ModelCommand {
    /// Print a preset (default: Fig. 4(c)'s set with r = 1, D = 0, τ = 0) as a commented model file.
    Show(ShowArgs),
    /// Validate a model file; say whether the engine steps it today.
    Check(CheckArgs),
}

/// Arguments of `model show`.
#[derive(Debug, Args)]
pub struct ShowArgs {
    /// A figure's parameter set (e.g. fig13a; `trirhythm presets` lists them).
    #[arg(long)]
    pub preset: Option<String>,
}

/// Arguments of `model check`.
#[derive(Debug, Args)]
pub struct CheckArgs {
    /// The model file.
    pub file: PathBuf,
}

/// Run a `model` subcommand.
pub fn model(command: &ModelCommand) -> Result<()> {
    match command {
        ModelCommand::Show(a) => show(a),
        ModelCommand::Check(a) => check(a),
    }
}

fn show(a: &ShowArgs) -> Result<()> {
    let mut text = String::new();
    let params = match &a.preset {
        Some(name) => {
            let p = preset(name)?;
            text.push_str(&format!("# {} — {}\n", p.name, p.description));
            for n in p.notes {
                text.push_str(&format!("# note: {n}\n"));
            }
            p.params
        }
        None => {
            text.push_str("# the default parameters: Fig. 4(c)'s set with r = 1, D = 0, tau = 0\n");
            Params::default()
        }
    };
    text.push_str("# the model-file reference: docs/model-file.md\n");
    let model = Model::from(&params);
    text.push_str(&model.to_toml());
    // what is printed reads back as the same model (the round trip `model check` tests)
    if Model::from_toml_str(&text).as_ref() != Ok(&model) {
        return bad("internal: the printed model does not read back");
    }
    stdout_write(text.as_bytes())
}

fn check(a: &CheckArgs) -> Result<()> {
    let model = read_model(&a.file, "model check")?;
    let engine = match model.engine_terms("the engine") {
        Ok((f, terms)) => format!(
            "the engine steps it ({}, {}, {} noise): {}",
            if terms.is_some() {
                "the General kernel: Duffing, Rayleigh, forcing, fractional, multiplicative or \
                 wall terms"
            } else {
                "the paper's family"
            },
            match terms.as_ref().map_or(0, |t| t.walls.len()) {
                0 if f.wall => "wall at U = 0",
                0 => "no wall",
                1 => "one wall (the General kernel's)",
                _ => "two walls",
            },
            if f.params.noise_intensity == 0.0 {
                "no"
            } else if f.params.correlation_time == 0.0 {
                "white"
            } else {
                "Ornstein-Uhlenbeck"
            },
            if terms.is_some() {
                "simulate, ensemble (compared with the model's own theory where it holds), \
                 lyapunov take it with --model"
            } else {
                "simulate, ensemble, lyapunov, critical-noise, oscillation, phase-response take \
                 it with --model"
            }
        ),
        Err(e) => format!("valid, but not stepped yet: {e}"),
    };
    let theory = averaged_theory(&model);
    stdout_write(
        format!(
            "{}: a valid model file (format {}); {engine}\n{theory}\n",
            a.file.display(),
            trirhythm::model::FORMAT
        )
        .as_bytes(),
    )
}

/// Whether the averaged theory applies to `model`, in which variants, or why not.
fn averaged_theory(model: &Model) -> String {
    use trirhythm::theory::averaging::{Theory, Variant};
    match Theory::from_model(model, Variant::Consistent) {
        Ok(_) => {
            let variants = if Theory::from_model(model, Variant::Paper).is_ok() {
                "--variant paper or consistent"
            } else {
                "--variant consistent"
            };
            format!(
                "the averaged theory applies ({variants}): equivalents, cycles, drift, potential, \
                 barriers, pdf take it with --model"
            )
        }
        Err(e) => format!("{e}"),
    }
}
