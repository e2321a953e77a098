//! `trirhythm`: the command-line front end. The library computes; this binary parses
//! arguments, writes files, draws pictures and progress bars.
//!
//! Layers, dependencies pointing one way (`main → commands → {args, io, render}`,
//! `render → io`, everyone → `error`):
//! - [`args`]: clap arguments shared by the commands, each mapped to its library type once;
//! - [`commands`]: one file per command or family (parse → library types → library call with a
//!   progress-bar monitor → write); a command never imports another;
//! - [`io`]: atomic files and the signal cleanup, CSV and tables, JSON, the progress bar;
//! - [`render`]: plotting and each paper figure's picture;
//! - [`error`]: bad input (exit 2) and library errors told in the flags the user typed.
//!
//! This file only dispatches.
//!
//! Exit status: 0 on success (and when the reader of standard output closes the pipe), 2 for
//! bad input (a parameter out of range, an unknown name, a malformed flag, an output path that
//! cannot receive a file), 1 for anything else (I/O, a full device, a computation that
//! overflowed), 130 when interrupted. No partial output file is ever left ([`io::files`]).

#[macro_use]
mod args;
mod commands;
mod error;
mod io;
mod render;

use commands::{
    ensemble, figure, lyapunov, maps, model, oscillation, phase, report, simulate, theory,
};

use anyhow::{Context, Result};
use clap::{CommandFactory, FromArgMatches, Parser, Subcommand};
use std::io::Write;
use std::path::Path;
use std::process::ExitCode;

#[derive(Debug, Parser)]
#[command(
    name = "trirhythm",
    version,
    about = "Stochastic fractional-order vibro-impact oscillators with several coexisting limit cycles"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Harmonic-balance equivalents μ1, β1, ω1, β2 (Eq. 5), σ1 and the impact loss rate.
    Equivalents(theory::TheoryArgs),
    /// Limit cycles (roots of f, Eq. 18) or, when D > 0, extrema of P(A) (roots of m1, Eq. 26).
    Cycles(theory::TheoryArgs),
    /// The averaged drift f(A) on a grid (Eq. 18), with df/dA and ΔE (Eq. 20).
    Drift(theory::CurveArgs),
    /// The pseudo-potential U_eff(A) on a grid (Eq. 23), with m1.
    Potential(theory::CurveArgs),
    /// Energy barriers ΔU_i between consecutive extrema of U_eff.
    Barriers(theory::TheoryArgs),
    /// Stationary PDFs: amplitude (Eq. 27), energy (Eq. 29), joint (Eq. 30–31).
    Pdf(theory::PdfArgs),
    /// Simulate one path of Eq. 1 (or Eq. 5 / Eq. 9) with the fractional predictor–corrector.
    Simulate(simulate::SimulateArgs),
    /// Ensemble of N paths: stationary statistics, stationarity (R̂, ESS, drift), theory against them.
    Ensemble(ensemble::EnsembleArgs),
    /// Two-parameter map: cycle or P(A)-mode count (CSV x,y,count), exact fold curves (--folds).
    Map(maps::MapArgs),
    /// One-parameter branch diagram: every cycle branch traced through its folds.
    Branches(maps::BranchArgs),
    /// Oscillation (Hopf) boundary by simulation, averaging, exact linearisation, or a plane (--grid).
    Oscillation(oscillation::OscillationArgs),
    /// Largest Lyapunov exponent with frozen noise (JSON; with --sweep CSV per parameter value).
    Lyapunov(lyapunov::LyapunovArgs),
    /// The largest Lyapunov exponent against D by regime (one curve per attractor) and each curve's D_c.
    CriticalNoise(lyapunov::CriticalNoiseArgs),
    /// Phase response Z(θ) of a stable cycle by small kicks, and c of λ ≈ −c·D under weak noise.
    PhaseResponse(phase::PhaseArgs),
    /// Reproduce a figure of the paper: data (CSV, and JSON with --data) and picture (PNG + SVG).
    Figure(figure::FigureArgs),
    /// Every figure and every claim judged: one HTML page (index.html), verdicts.json, figures/.
    Report(report::ReportArgs),
    /// List the parameter presets (one per figure panel) with their notes.
    Presets,
    /// Model files: `model show --preset NAME` prints one, `model check FILE` validates one.
    #[command(subcommand)]
    Model(model::ModelCommand),
}

impl Command {
    /// The output file named on the command line, if any.
    fn out(&self) -> Option<&Path> {
        match self {
            Command::Equivalents(a) | Command::Cycles(a) | Command::Barriers(a) => {
                a.output.out.as_deref()
            }
            Command::Drift(a) | Command::Potential(a) => a.theory.output.out.as_deref(),
            Command::Pdf(a) => a.theory.output.out.as_deref(),
            Command::Simulate(a) => a.out.as_deref(),
            Command::Ensemble(a) => a.out.as_deref(),
            Command::Map(a) => a.output.out.as_deref(),
            Command::Branches(a) => a.output.out.as_deref(),
            Command::Oscillation(a) => a.out.as_deref(),
            Command::Lyapunov(a) => a.out.as_deref(),
            Command::CriticalNoise(a) => a.out.as_deref(),
            Command::PhaseResponse(a) => a.out.as_deref(),
            Command::Figure(_) | Command::Report(_) | Command::Presets | Command::Model(_) => None,
        }
    }

    /// The command's name as typed.
    fn name(&self) -> &'static str {
        match self {
            Command::Equivalents(_) => "equivalents",
            Command::Cycles(_) => "cycles",
            Command::Drift(_) => "drift",
            Command::Potential(_) => "potential",
            Command::Barriers(_) => "barriers",
            Command::Pdf(_) => "pdf",
            Command::Simulate(_) => "simulate",
            Command::Ensemble(_) => "ensemble",
            Command::Map(_) => "map",
            Command::Branches(_) => "branches",
            Command::Oscillation(_) => "oscillation",
            Command::Lyapunov(_) => "lyapunov",
            Command::CriticalNoise(_) => "critical-noise",
            Command::PhaseResponse(_) => "phase-response",
            Command::Figure(_) => "figure",
            Command::Report(_) => "report",
            Command::Presets => "presets",
            Command::Model(_) => "model",
        }
    }

    /// The `--model FILE` of a command that takes one.
    fn model_file(&self) -> Option<&args::ModelFileArg> {
        match self {
            Command::Simulate(a) => Some(&a.file),
            Command::Ensemble(a) => Some(&a.file),
            Command::Lyapunov(a) => Some(&a.sim.file),
            Command::CriticalNoise(a) => Some(&a.file),
            Command::Oscillation(a) => Some(&a.file),
            Command::PhaseResponse(a) => Some(&a.file),
            _ => None,
        }
        .filter(|f| f.model.is_some())
    }

    /// Read `--model FILE` (bad input naming the field if it is malformed, or naming the term
    /// the engine does not step yet) and put its parameters, wall and start in the command's
    /// arguments, so that the run and its header lines are those of the file.
    fn apply_model_file(&mut self) -> Result<()> {
        let Some((model, family, terms)) =
            self.model_file().map(|f| f.load()).transpose()?.flatten()
        else {
            return Ok(());
        };
        // the library decides where the paper's closed forms apply; the refusal names the term
        let theory_free = |command: &str| match trirhythm::theory::averaging::closed_forms(&model) {
            Err(why) => error::bad(format!(
                "--model: {command} is built on the paper's averaged theory (its cycles and \
                 boundaries): {why}"
            )),
            Ok(_) => Ok(()),
        };
        let barrier = args::on_off(family.wall);
        let (u0, v0) = family.start;
        let at_rest = |command: &str| {
            if v0 != 0.0 {
                error::bad(format!(
                    "--model: start.v0 = {v0}: {command} starts its paths at rest; set start.v0 = 0"
                ))
            } else {
                Ok(())
            }
        };
        match self {
            Command::Simulate(a) => {
                a.params.base = Some(family.params);
                a.model.barrier = barrier;
                a.model.terms = terms;
                (a.u0, a.v0) = (u0, v0);
            }
            Command::Ensemble(a) => {
                at_rest("ensemble")?;
                a.params.base = Some(family.params);
                a.model.barrier = barrier;
                a.model.terms = terms;
                a.u0 = vec![u0];
            }
            Command::Lyapunov(a) => {
                at_rest("lyapunov")?;
                a.sim.params.base = Some(family.params);
                a.sim.model.barrier = barrier;
                a.sim.model.terms = terms;
                a.sim.u0 = u0;
            }
            // critical-noise starts on each regime's cycle, oscillation searches: no start
            Command::CriticalNoise(a) => {
                theory_free("critical-noise")?;
                a.params.base = Some(family.params);
                a.model.barrier = barrier;
            }
            // the cycle reached from the file's start (at rest), named by the theory
            Command::PhaseResponse(a) => {
                theory_free("phase-response")?;
                at_rest("phase-response")?;
                a.params.base = Some(family.params);
                a.model.barrier = barrier;
                a.u0 = Some(u0);
            }
            Command::Oscillation(a) => {
                theory_free("oscillation")?;
                if family.params.noise_intensity != 0.0 {
                    return error::bad(format!(
                        "--model: noise.additive.intensity = {}: the oscillation boundary is that \
                         of the noise-free system; allowed: 0 (or no [noise.additive])",
                        family.params.noise_intensity
                    ));
                }
                a.params.base = Some(family.params);
                a.barrier = barrier;
            }
            _ => {}
        }
        Ok(())
    }

    /// Refuse an option given on the command line that the chosen command or method does not
    /// use (exit 2, naming it and what it applies to), before any work.
    fn refuse_unused(&self, given: &args::Given) -> Result<()> {
        if self.model_file().is_some() {
            given.refuse(
                &[("barrier", "--barrier"), ("u0", "--u0"), ("v0", "--v0")],
                "runs without --model",
                "the model file says the wall and the start",
            )?;
        }
        match self {
            Command::Ensemble(a) => a.refuse_unused(given),
            Command::Map(a) => a.refuse_unused(given),
            Command::Oscillation(a) => a.refuse_unused(given),
            // the tangent equation has no copy to pull back
            Command::Lyapunov(lyapunov::LyapunovArgs {
                sim: lyapunov::LleArgs { exponent, .. },
                ..
            })
            | Command::CriticalNoise(lyapunov::CriticalNoiseArgs { exponent, .. })
                if exponent.method == lyapunov::LyapunovMethod::Tangent =>
            {
                given.refuse(
                    &[("separation", "--separation")],
                    "--method two-trajectory",
                    "the tangent method has no perturbed copy to pull back",
                )
            }
            _ => Ok(()),
        }
    }
}

/// The environment variable that asks for a command's parallel profile (`1`).
const PROFILE_VAR: &str = "TRIRHYTHM_PROFILE";

fn run(mut cli: Cli, given: &args::Given) -> Result<()> {
    // an output that cannot be written (a directory, a missing or read-only directory) is
    // refused before any work starts, for every command
    if let Some(out) = cli.command.out() {
        io::files::check_writable(out, "--out")?;
    }
    match &cli.command {
        Command::Map(a) => {
            if let Some(f) = &a.folds_out {
                io::files::check_writable(f, "--folds-out")?;
            }
        }
        Command::Ensemble(a) => {
            if let Some(dir) = &a.checkpoint {
                io::files::check_dir_writable(dir, "--checkpoint")?;
            }
        }
        Command::Figure(a) => io::files::check_dir_writable(&a.out_dir, "--out-dir")?,
        _ => {}
    }
    cli.command.refuse_unused(given)?;
    cli.command.apply_model_file()?;
    if !matches!(cli.command, Command::Presets | Command::Model(_)) {
        io::progress::start_ticker(cli.command.name());
    }
    // TRIRHYTHM_PROFILE=1: the command's parallel profile on stderr (any command; `figure` and
    // `report` also per figure with --profile)
    let done = if std::env::var_os(PROFILE_VAR).is_some_and(|v| v == "1") {
        let (done, profile) = trirhythm::profile::record(|| dispatch(&cli));
        eprintln!("{} profile: {}", cli.command.name(), profile.line());
        done
    } else {
        dispatch(&cli)
    };
    io::progress::end_ticker();
    done?;
    std::io::stdout()
        .flush()
        .context("writing to standard output")
}

fn dispatch(cli: &Cli) -> Result<()> {
    match &cli.command {
        Command::Equivalents(a) => theory::equivalents(a),
        Command::Cycles(a) => theory::cycles(a),
        Command::Drift(a) => theory::drift(a),
        Command::Potential(a) => theory::potential(a),
        Command::Barriers(a) => theory::barriers(a),
        Command::Pdf(a) => theory::pdf(a),
        Command::Simulate(a) => simulate::simulate(a),
        Command::Ensemble(a) => ensemble::ensemble(a),
        Command::Map(a) => maps::map(a),
        Command::Branches(a) => maps::branches(a),
        Command::Oscillation(a) => oscillation::oscillation(a),
        Command::Lyapunov(a) => lyapunov::lyapunov(a),
        Command::CriticalNoise(a) => lyapunov::critical(a),
        Command::PhaseResponse(a) => phase::phase(a),
        Command::Figure(a) => figure::figure(a),
        Command::Report(a) => report::report(a),
        Command::Presets => figure::presets(),
        Command::Model(a) => model::model(a),
    }
}

fn main() -> ExitCode {
    io::files::install_signal_cleanup();
    let parsed = Cli::command()
        .try_get_matches()
        .and_then(|m| Cli::from_arg_matches(&m).map(|cli| (cli, m)));
    let (cli, matches) = match parsed {
        Ok(parsed) => parsed,
        Err(e) => {
            let command = std::env::args().nth(1).unwrap_or_default();
            match error::clap_value_error(&command, &e) {
                Some(message) => {
                    eprintln!("error: {message}");
                    return ExitCode::from(2);
                }
                None => e.exit(),
            }
        }
    };
    let given = args::Given::of(matches.subcommand().map(|(_, m)| m));
    match run(cli, &given) {
        Ok(()) => ExitCode::SUCCESS,
        // the reader went away (`trirhythm simulate | head`): end quietly
        Err(e) if io::files::is_broken_pipe(&e) => ExitCode::SUCCESS,
        Err(e) => {
            let e = error::in_flags(e);
            eprintln!("error: {e:#}");
            if error::is_bad_input(&e) {
                ExitCode::from(2)
            } else {
                ExitCode::from(1)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An option typed for another method is refused; at its default, or for its method, it
    /// is not (the rules name argument ids that exist: a renamed field would disable them).
    #[test]
    fn options_another_method_uses_are_refused_only_when_typed() {
        let check = |line: &[&str]| -> Result<()> {
            let m = Cli::command().try_get_matches_from(line).unwrap();
            let cli = Cli::from_arg_matches(&m).unwrap();
            cli.command
                .refuse_unused(&args::Given::of(m.subcommand().map(|(_, m)| m)))
        };
        for refused in [
            &["trirhythm", "ensemble", "--clones", "8"][..],
            &["trirhythm", "ensemble", "--max-excursion", "5"],
            &["trirhythm", "ensemble", "--max-iterations", "5"],
            &["trirhythm", "ensemble", "--separation", "5"],
            &["trirhythm", "ensemble", "--core-quantile", "0.2"],
            &["trirhythm", "ensemble", "--method", "wells", "--u0", "1"],
            &["trirhythm", "ensemble", "--method", "wells", "--lanes", "1"],
            &[
                "trirhythm",
                "ensemble",
                "--method",
                "wells",
                "--checkpoint",
                "x",
            ],
            &[
                "trirhythm",
                "ensemble",
                "--backend",
                "gpu",
                "--method",
                "wells",
            ],
            &[
                "trirhythm",
                "ensemble",
                "--backend",
                "gpu",
                "--checkpoint",
                "x",
            ],
            &["trirhythm", "ensemble", "--backend", "gpu", "--lanes", "4"],
            &[
                "trirhythm",
                "oscillation",
                "--x",
                "r=0:1:2",
                "--y",
                "mu0=0:1",
                "--method",
                "exact",
                "--dt",
                "0.01",
            ],
            &[
                "trirhythm",
                "oscillation",
                "--x",
                "r=0:1:2",
                "--y",
                "mu0=0:1",
                "--method",
                "averaging",
                "--impact-memory",
                "restart",
            ],
            &[
                "trirhythm",
                "oscillation",
                "--x",
                "r=0:1:2",
                "--y",
                "mu0=0:1",
                "--method",
                "exact",
                "--lanes",
                "4",
            ],
            &[
                "trirhythm",
                "oscillation",
                "--x",
                "r=0:1:2",
                "--y",
                "mu0=0:1:2",
                "--grid",
                "--tolerance",
                "0.01",
            ],
            &[
                "trirhythm",
                "lyapunov",
                "--method",
                "tangent",
                "--separation",
                "1e-8",
            ],
            &[
                "trirhythm",
                "critical-noise",
                "--d-range",
                "0:1",
                "--method",
                "tangent",
                "--separation",
                "1e-8",
            ],
        ] {
            let e = check(refused).expect_err(&format!("{refused:?}"));
            assert!(error::is_bad_input(&e), "{refused:?}: {e}");
            assert!(e.to_string().contains("applies to"), "{refused:?}: {e}");
        }
        for accepted in [
            &["trirhythm", "ensemble"][..],
            &["trirhythm", "ensemble", "--u0", "1", "--lanes", "4"],
            &["trirhythm", "ensemble", "--backend", "cpu", "--lanes", "4"],
            &["trirhythm", "ensemble", "--backend", "gpu", "--u0", "1"],
            &[
                "trirhythm",
                "ensemble",
                "--method",
                "wells",
                "--clones",
                "8",
                "--max-excursion",
                "5",
                "--max-iterations",
                "5",
                "--separation",
                "5",
                "--core-quantile",
                "0.2",
            ],
            &[
                "trirhythm",
                "oscillation",
                "--x",
                "r=0:1:2",
                "--y",
                "mu0=0:1",
                "--dt",
                "0.01",
                "--tolerance",
                "0.01",
                "--lanes",
                "4",
                "--impact-memory",
                "restart",
            ],
            &[
                "trirhythm",
                "oscillation",
                "--x",
                "r=0:1:2",
                "--y",
                "mu0=0:1",
                "--method",
                "simulation",
                "--dt",
                "0.01",
            ],
            &[
                "trirhythm",
                "oscillation",
                "--x",
                "r=0:1:2",
                "--y",
                "mu0=0:1:2",
                "--grid",
                "--dt",
                "0.01",
            ],
            &["trirhythm", "lyapunov", "--separation", "1e-8"],
            &["trirhythm", "lyapunov", "--method", "tangent"],
        ] {
            check(accepted).unwrap_or_else(|e| panic!("{accepted:?}: {e}"));
        }
    }

    /// Every whole-number flag of every command has its range in the table, and clap's
    /// refusal of a negative, fractional or too large value is told with it.
    #[test]
    fn every_whole_number_flag_is_refused_with_its_range() {
        let cli = Cli::command();
        let mut checked = 0;
        for sub in cli.get_subcommands() {
            for arg in sub.get_arguments() {
                let Some(long) = arg.get_long() else { continue };
                let flag = format!("--{long}");
                let id = arg.get_value_parser().type_id();
                let parsers: [clap::builder::ValueParser; 3] = [
                    clap::value_parser!(u64).into(),
                    clap::value_parser!(usize).into(),
                    clap::value_parser!(u32).into(),
                ];
                let whole = parsers.iter().any(|p| p.type_id() == id);
                if !whole {
                    continue;
                }
                let name = sub.get_name();
                assert!(
                    error::whole_number_range(name, &flag).is_some(),
                    "{name} {flag}: no range in error::WHOLE_NUMBER_FLAGS"
                );
                for bad in ["-1", "1.5", "1e3", "99999999999999999999999"] {
                    let e = Cli::try_parse_from(["trirhythm", name, &flag, bad]).unwrap_err();
                    let message = error::clap_value_error(name, &e)
                        .unwrap_or_else(|| panic!("{name} {flag} {bad}: {e}"));
                    assert!(
                        message.starts_with(&format!("{flag} = {bad}: allowed range is ")),
                        "{message}"
                    );
                }
                checked += 1;
            }
        }
        assert!(checked >= 14, "only {checked} whole-number flags found");
    }
}
