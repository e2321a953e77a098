//! `trirhythm figure N`: one source file, one command and one set of files per paper figure.
//!
//! Each figure writes `figNN.csv` (its data, parameters and notes in `#` header lines) and
//! `figNN.png` + `figNN.svg` into the output directory. `--quick` trades resolution for speed
//! (used by CI); the default is paper quality.

mod fig01_phase_recurrence;
mod fig02_rhythmicity_planes;
mod fig03_restitution_planes;
mod fig04_drift;
mod fig05_branches;
mod fig06_fractional_planes;
mod fig07_pseudo_potential;
mod fig08_barriers;
mod fig09_barrier_surfaces;
mod fig10_pbif_lambda_tau;
mod fig12_pbif_maps;
mod fig15_oscillation_boundaries;
mod fig16_oscillation_regions;
mod mapfig;

use crate::plot::Heading;
use anyhow::Result;
use std::path::PathBuf;
use trirhythm::model::Params;
use trirhythm::theory::averaging::Variant;

/// What every figure gets.
pub struct FigureContext {
    /// Output directory (created if missing).
    pub out_dir: PathBuf,
    /// Coarser grids, shorter runs.
    pub quick: bool,
    /// Formula variant of the averaged theory.
    pub variant: Variant,
}

impl FigureContext {
    /// `out_dir/figNN` (without extension).
    pub fn stem(&self, n: u32) -> PathBuf {
        self.out_dir.join(format!("fig{n:02}"))
    }
}

type FigureFn = fn(&FigureContext) -> Result<Vec<PathBuf>>;

/// The figures this build can make, by number.
pub fn registry() -> Vec<(u32, &'static str, FigureFn)> {
    vec![
        (
            1,
            "phase portraits and recurrence plots, Eq. (1) vs Eq. (5)",
            fig01_phase_recurrence::run,
        ),
        (
            2,
            "rhythmicity maps in (α0, β0) and (γ0, δ0) with saddle-node lines",
            fig02_rhythmicity_planes::run,
        ),
        (
            3,
            "rhythmicity in (γ0, δ0) for four restitution coefficients",
            fig03_restitution_planes::run,
        ),
        (
            4,
            "f(A0) with its zones and limit cycles (Eq. 18)",
            fig04_drift::run,
        ),
        (
            5,
            "limit-cycle amplitude vs r by continuation, five μ0",
            fig05_branches::run,
        ),
        (
            6,
            "mono/bi/tri regions in (γ0, δ0) for four fractional orders",
            fig06_fractional_planes::run,
        ),
        (
            7,
            "pseudo-potential U_eff for several r and λ (Eq. 23)",
            fig07_pseudo_potential::run,
        ),
        (8, "energy barriers ΔU_i of U_eff", fig08_barriers::run),
        (
            9,
            "energy barriers ΔU_i over (τ, λ) for two r",
            fig09_barrier_surfaces::run,
        ),
        (
            10,
            "P-bifurcation map in (λ, τ) for four D",
            fig10_pbif_lambda_tau::run,
        ),
        (
            12,
            "P-bifurcation maps in (μ0, r) and (λ, r)",
            fig12_pbif_maps::run,
        ),
        (
            15,
            "oscillation (Hopf) boundary μ0 against λ and r, three ω0",
            fig15_oscillation_boundaries::run,
        ),
        (
            16,
            "oscillation and rest regions in (μ0, λ) and (μ0, r)",
            fig16_oscillation_regions::run,
        ),
    ]
}

/// Header comment lines for a figure's CSV: title, variant, notes.
pub fn csv_header(n: u32, title: &str, ctx: &FigureContext, notes: &[String]) -> Vec<String> {
    let mut h = vec![
        format!("trirhythm figure {n}: {title}"),
        format!("variant: {}", ctx.variant.name()),
    ];
    h.extend(notes.iter().map(|s| format!("note: {s}")));
    h
}

/// A panel's parameters for a header line.
pub fn panel_line(label: &str, p: &Params) -> String {
    format!("panel {label}: {}", p.describe())
}

/// The formula variant, as a heading line: a `--variant consistent` picture says so on itself.
pub fn variant_line(v: Variant) -> String {
    match v {
        Variant::Paper => {
            "averaged theory: the paper's formulas as printed, typos fixed (--variant paper)".into()
        }
        Variant::Consistent => {
            "averaged theory: CONSISTENT variant — exact impact loss ω1A ln r/π, \
                                coloured noise through sgn Z (--variant consistent)"
                .into()
        }
    }
}

/// The user-facing symbol of a parameter key.
fn symbol(key: &str) -> String {
    match key {
        "mu0" => "μ0".into(),
        "omega0" => "ω0".into(),
        "lambda" => "λ".into(),
        "alpha0" => "α0".into(),
        "beta0" => "β0".into(),
        "gamma0" => "γ0".into(),
        "delta0" => "δ0".into(),
        "tau" => "τ".into(),
        k => k.into(),
    }
}

/// "μ0 = 0.01, ω0 = 1, …" for the keys of `p` not in `varying` (those the panels set).
pub fn params_text(p: &Params, varying: &[&str]) -> String {
    p.key_values()
        .into_iter()
        .filter(|(k, _)| !varying.contains(&k.as_str()))
        .map(|(k, v)| format!("{} = {}", symbol(&k), trirhythm::error::Exact(v)))
        .collect::<Vec<_>>()
        .join(", ")
}

/// A figure's heading: "Fig. N: title", the shared parameters (what the panels vary named),
/// the formula variant, then `extra` lines (choices where the paper is silent, methods).
pub fn heading(
    n: u32,
    title: &str,
    ctx: &FigureContext,
    base: &Params,
    varying: &[&str],
    extra: Vec<String>,
) -> Heading {
    let mut lines = vec![format!(
        "{}{}",
        params_text(base, varying),
        if varying.is_empty() {
            String::new()
        } else {
            format!(
                "; per panel: {}",
                varying
                    .iter()
                    .map(|k| symbol(k))
                    .collect::<Vec<_>>()
                    .join(", ")
            )
        }
    )];
    lines.push(variant_line(ctx.variant));
    lines.extend(extra);
    Heading {
        title: format!("Fig. {n}: {title}"),
        lines,
    }
}
