//! What Figs 11, 13 and 14 share: Monte Carlo ensembles of Eq. (1) and Eq. (5) beside the
//! averaged theory's P(A) (Eq. 27) in both variants, with the distances (Hellinger with its
//! bootstrap standard error, L1, KS), the modes and the stationarity verdict (R̂, ESS, drift)
//! of each run.
//!
//! Method: [`run_ensemble`] with the impact memory restarted at each impact (the ensembles'
//! convention), starts and wells from [`theory_layout`]; [`compare`] against each variant's
//! [`Theory`]. Where the direct ensemble is not stationary and the theory has two wells or
//! more, the well decomposition ([`run_wells`]: conditional statistics per well, rates by
//! adaptive multilevel splitting, weights from the rates) is run with [`Sizes::wells`]; when
//! its diagnostic accepts it, the panel shows its stationary mixture (`estimator: "wells"`),
//! otherwise the direct histogram stays with the refusal in [`McRun::wells`]. Checked by the
//! library's ensemble and well tests (statistics, merge, known answers) and `tests/figures.rs`
//! (cancellation, quick computation, JSON round trip).

use crate::notes::num;
use crate::table::Table;
use crate::Monitor;
use serde::{Deserialize, Serialize};
use trirhythm::analysis::check_step;
use trirhythm::analysis::ensemble::{
    run_ensemble, run_wells, EnsembleResult, EnsembleSpec, Wells, WellsResult, WellsSpec,
};
use trirhythm::analysis::versus::{compare, model_layout, theory_layout, TheoryComparison};
use trirhythm::engine::{ImpactMemory, PredictorCorrector, Problem, System};
use trirhythm::model::Params;
use trirhythm::theory::averaging::{Theory, Variant};
use trirhythm::{Error, Result};

/// Ensemble sizes of a figure.
#[derive(Debug, Clone, Copy, Serialize, Deserialize)]
pub struct Sizes {
    /// Paths per ensemble.
    pub paths: usize,
    /// Burn-in and recorded window per path.
    pub burn_in: f64,
    /// Recorded window per path.
    pub t_end: f64,
    /// Bins of the amplitude histogram.
    pub bins: usize,
    /// Half-width of the joint histogram's U̇ axis as a multiple of ω1·A_max (1 for Figs 11
    /// and 13; Fig. 14's relaxation oscillation needs 2 to hold 99 % of its samples).
    #[serde(default = "one")]
    pub joint_velocity_factor: f64,
}

fn one() -> f64 {
    1.0
}

impl Sizes {
    /// The ensembles of Figs 11, 13 and 14: full quality (16 paths of 1.5e5 time units; each
    /// figure in a few minutes on 2 cores) or `--quick`.
    pub fn of(quick: bool) -> Sizes {
        if quick {
            Sizes {
                paths: 2,
                burn_in: 10.0,
                t_end: 100.0,
                bins: 50,
                joint_velocity_factor: 1.0,
            }
        } else {
            Sizes {
                paths: 16,
                burn_in: 500.0,
                t_end: 150_000.0,
                bins: 80,
                joint_velocity_factor: 1.0,
            }
        }
    }

    /// The well decomposition's sizes where the direct ensemble is not stationary: `paths`
    /// replicas of one path per well of `length` time units (after `burn_in`), and its
    /// splitting: 200 replicas per transition and at most 700 iterations, each killing a tenth
    /// (full quality: probabilities resolved or bounded down to ≈ 10⁻³², at a bounded cost) or
    /// 8 replicas (`--quick`, 100 time units).
    pub fn wells(&self) -> (f64, WellsSpec) {
        if self.t_end <= 1000.0 {
            (
                self.t_end,
                WellsSpec {
                    clones: 8,
                    ..Default::default()
                },
            )
        } else {
            (
                5000.0,
                WellsSpec {
                    clones: 200,
                    max_iterations: 700,
                    ..Default::default()
                },
            )
        }
    }

    /// One line for headings and notes.
    pub fn describe(&self) -> String {
        format!(
            "{} paths per ensemble, burn-in {}, window {} per path, Δt = 0.01, impact memory \
             restarted, seed 1, {} bins",
            self.paths, self.burn_in, self.t_end, self.bins
        )
    }
}

/// The theory against one ensemble, one variant.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Distance {
    /// `paper` or `consistent`.
    pub variant: String,
    /// Hellinger distance and its bootstrap standard error, L1, KS.
    pub hellinger: f64,
    /// Bootstrap standard error of the Hellinger distance.
    #[serde(with = "trirhythm::non_finite")]
    pub hellinger_stderr: f64,
    /// L1 distance.
    pub l1: f64,
    /// Largest CDF difference.
    pub ks: f64,
    /// Modes of the binned theory and of the histogram (prominence rule).
    pub modes_theory: usize,
    /// Modes of the histogram.
    pub modes_mc: usize,
}

/// What the well decomposition found for one ensemble whose direct paths were not
/// stationary.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct WellsSummary {
    /// Its diagnostic accepted the decomposition (the run shows its mixture).
    pub valid: bool,
    /// The stationary weights of the wells (NaN where undetermined).
    #[serde(with = "trirhythm::non_finite::vec")]
    pub weights: Vec<f64>,
    /// Their standard errors over the replicas.
    #[serde(with = "trirhythm::non_finite::vec")]
    pub weight_stderr: Vec<f64>,
    /// The rates between neighbours: `i → j` and the rate per time unit.
    pub rates: Vec<(usize, usize)>,
    /// Rates per time unit (0 below the method's resolution).
    #[serde(with = "trirhythm::non_finite::vec")]
    pub rate: Vec<f64>,
    /// Their standard errors.
    #[serde(with = "trirhythm::non_finite::vec")]
    pub rate_stderr: Vec<f64>,
    /// Upper bounds of the rates below the method's resolution (NaN where resolved).
    #[serde(default, with = "trirhythm::non_finite::vec")]
    pub rate_bound: Vec<f64>,
    /// Why the decomposition was refused (empty when valid).
    pub refusals: Vec<String>,
    /// Rates below the method's resolution and the theory's wells that the simulation lacks,
    /// in words.
    pub notes: Vec<String>,
    /// The theory's wells that the simulation lacks (the decomposition is over the others).
    #[serde(default)]
    pub missing: Vec<trirhythm::analysis::ensemble::MissingWell>,
    /// Steps computed.
    pub steps: u64,
    /// Seconds of wall time.
    pub wall_time_s: f64,
    /// The conditional statistics passed the diagnostic and only the rates and weights did not
    /// (then `bounds` holds the distances for every weighting).
    #[serde(default)]
    pub conditional_valid: bool,
    /// Every refusal is about the rates and weights or a well's conditional statistics
    /// drifting between the window's halves (the replicas agreeing): `bounds` holds the
    /// distances for every weighting and `bounds_halves` those of each half alone.
    #[serde(default)]
    pub conditional_drifting: bool,
    /// Each well's conditional density P_i (on the run's edges) with its standard errors.
    #[serde(default)]
    pub conditional: Vec<Conditional>,
    /// The distance to each variant's theory for every weighting of the wells, where the
    /// conditional statistics are valid but the decomposition was refused.
    #[serde(default)]
    pub bounds: Vec<Bounds>,
    /// Where the conditional statistics drift: the same for the window's first half and its
    /// second half alone (`[half]`, each with both variants).
    #[serde(default)]
    pub bounds_halves: Vec<Vec<Bounds>>,
    /// Independent replicas behind the standard errors.
    #[serde(default)]
    pub replicas: usize,
}

/// One well's conditional amplitude density.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Conditional {
    /// Density per bin (the run's edges).
    pub density: Vec<f64>,
    /// Its standard errors over the replicas.
    #[serde(with = "trirhythm::non_finite::vec")]
    pub stderr: Vec<f64>,
    /// Effective sample size of the well's amplitude.
    #[serde(with = "trirhythm::non_finite")]
    pub ess: f64,
}

/// The Hellinger distance to one variant's theory over every weighting of the wells
/// ([`trirhythm::analysis::versus::wells_bounds`]).
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Bounds {
    /// `paper` or `consistent`.
    pub variant: String,
    /// The smallest H over every weighting.
    pub h_min: f64,
    /// Its jackknife standard error over the replicas.
    #[serde(with = "trirhythm::non_finite")]
    pub h_min_stderr: f64,
    /// The weights of the smallest H.
    pub weights_min: Vec<f64>,
    /// The largest H (one well's density alone).
    pub h_max: f64,
    /// Its jackknife standard error.
    #[serde(with = "trirhythm::non_finite")]
    pub h_max_stderr: f64,
    /// H of each well's density alone.
    pub per_well: Vec<f64>,
}

impl Bounds {
    /// "[0.41 ± 0.02, 0.88 ± 0.01] (min at weights 0.3, 0.7)".
    pub fn line(&self) -> String {
        format!(
            "H ∈ [{} ± {}, {} ± {}] for every weighting of the wells (min at weights {}; each well alone {})",
            crate::notes::sig(self.h_min, 3),
            crate::notes::sig(self.h_min_stderr, 2),
            crate::notes::sig(self.h_max, 3),
            crate::notes::sig(self.h_max_stderr, 2),
            self.weights_min
                .iter()
                .map(|x| crate::notes::sig(*x, 3))
                .collect::<Vec<_>>()
                .join(", "),
            self.per_well
                .iter()
                .map(|x| crate::notes::sig(*x, 3))
                .collect::<Vec<_>>()
                .join(", ")
        )
    }
}

impl WellsSummary {
    /// The summary of `w`; where its conditional statistics are valid but it was refused, the
    /// distances to each variant's theory of `params` over every weighting.
    pub fn of(w: &WellsResult, params: &Params, wall_time_s: f64) -> Self {
        let e = &w.wells;
        let of = |b: trirhythm::analysis::ensemble::HellingerBounds| Bounds {
            variant: b.variant,
            h_min: b.h_min.value,
            h_min_stderr: b.h_min.stderr,
            weights_min: b.weights_min,
            h_max: b.h_max.value,
            h_max_stderr: b.h_max.stderr,
            per_well: b.per_well,
        };
        let variants = [Variant::Paper, Variant::Consistent];
        let bounds = if (e.conditional_valid || e.conditional_drifting) && !e.valid {
            variants
                .into_iter()
                .filter_map(|v| {
                    let b = Theory::new(params, v)
                        .and_then(|th| trirhythm::analysis::versus::wells_bounds(w, &th))
                        .ok()?;
                    Some(of(b))
                })
                .collect()
        } else {
            vec![]
        };
        let bounds_halves = if e.conditional_drifting && !e.valid {
            let per_variant: Vec<Vec<Bounds>> = variants
                .into_iter()
                .filter_map(|v| {
                    let h = Theory::new(params, v)
                        .and_then(|th| trirhythm::analysis::versus::wells_bounds_halves(w, &th))
                        .ok()?;
                    Some(h.into_iter().map(&of).collect())
                })
                .collect();
            // [variant][half] → [half][variant]
            (0..2)
                .map(|h| {
                    per_variant
                        .iter()
                        .filter_map(|v| v.get(h).cloned())
                        .collect()
                })
                .collect()
        } else {
            vec![]
        };
        WellsSummary {
            conditional_valid: e.conditional_valid,
            conditional_drifting: e.conditional_drifting,
            bounds_halves,
            conditional: e
                .conditional
                .iter()
                .zip(&e.conditional_ess)
                .map(|(c, &ess)| Conditional {
                    density: c.density.clone(),
                    stderr: c.stderr.clone(),
                    ess,
                })
                .collect(),
            bounds,
            valid: e.valid,
            weights: e.weights.iter().map(|x| x.value).collect(),
            weight_stderr: e.weights.iter().map(|x| x.stderr).collect(),
            rates: e.rates.iter().map(|r| (r.from, r.to)).collect(),
            rate: e.rates.iter().map(|r| r.rate.value).collect(),
            rate_stderr: e.rates.iter().map(|r| r.rate.stderr).collect(),
            rate_bound: e.rate_bounds.clone(),
            refusals: e.refusals.clone(),
            notes: e.notes.clone(),
            missing: e.missing.clone(),
            steps: e.steps,
            wall_time_s,
            replicas: e.replicas.len(),
        }
    }

    /// Where the conditional statistics are valid but the weights are not determined: "weights
    /// undetermined (rates k1→0 < 1.5e-11, …); paper: H ∈ […] for every weighting …; consistent:
    /// …" (None otherwise).
    pub fn bounds_line(&self) -> Option<String> {
        if self.bounds.is_empty() {
            return None;
        }
        let bounded: Vec<String> = self
            .rates
            .iter()
            .zip(&self.rate_bound)
            .filter(|(_, b)| b.is_finite())
            .map(|((i, j), b)| format!("k{i}→{j} < {}", crate::notes::sig(*b, 2)))
            .collect();
        let resolved: Vec<String> = self
            .rates
            .iter()
            .zip(self.rate.iter().zip(&self.rate_bound))
            .filter(|(_, (_, b))| !b.is_finite())
            .map(|((i, j), (r, _))| format!("k{i}→{j} = {}", crate::notes::sig(*r, 3)))
            .collect();
        Some(
            format!(
                "weights undetermined (rates {}{}); {}",
                if bounded.is_empty() {
                    "too few exits".to_string()
                } else {
                    bounded.join(", ")
                },
                if resolved.is_empty() {
                    String::new()
                } else {
                    format!("; resolved {}", resolved.join(", "))
                },
                self.bounds
                    .iter()
                    .map(|b| format!("{}: {}", b.variant, b.line()))
                    .collect::<Vec<_>>()
                    .join("; ")
            ) + &self.halves_line(),
        )
    }

    /// Where the conditional statistics drift: "; a well's statistics drift: first half paper
    /// H ∈ […], …; second half …" (empty otherwise).
    fn halves_line(&self) -> String {
        if self.bounds_halves.is_empty() {
            return String::new();
        }
        let half = |h: &[Bounds]| {
            h.iter()
                .map(|b| {
                    format!(
                        "{} H ∈ [{} ± {}, {} ± {}]",
                        b.variant,
                        crate::notes::sig(b.h_min, 3),
                        crate::notes::sig(b.h_min_stderr, 2),
                        crate::notes::sig(b.h_max, 3),
                        crate::notes::sig(b.h_max_stderr, 2)
                    )
                })
                .collect::<Vec<_>>()
                .join(", ")
        };
        format!(
            "; a well's conditional statistics drift between the halves, so each half alone: \
             first half {}; second half {}",
            self.bounds_halves
                .first()
                .map_or(String::new(), |h| half(h)),
            self.bounds_halves.get(1).map_or(String::new(), |h| half(h))
        )
    }

    /// One line: weights, rates, the diagnostic and the cost.
    pub fn line(&self) -> String {
        let pm =
            |v: f64, s: f64| format!("{} ± {}", crate::notes::sig(v, 3), crate::notes::sig(s, 2));
        let weights: Vec<String> = self
            .weights
            .iter()
            .zip(&self.weight_stderr)
            .map(|(&v, &s)| pm(v, s))
            .collect();
        let rates: Vec<String> = self
            .rates
            .iter()
            .zip(self.rate.iter().zip(&self.rate_stderr))
            .map(|((i, j), (&v, &s))| format!("k{i}→{j} = {}", pm(v, s)))
            .collect();
        let missing = if self.missing.is_empty() {
            String::new()
        } else {
            format!(
                " (the theory's well{} {} missing in the simulation)",
                if self.missing.len() == 1 { "" } else { "s" },
                self.missing
                    .iter()
                    .map(|m| format!("at A = {}", crate::notes::sig(m.mode, 4)))
                    .collect::<Vec<_>>()
                    .join(", ")
            )
        };
        format!(
            "well decomposition {}{missing}: weights {}; rates {}; {:.2e} steps in {:.0} s{}",
            if self.valid { "accepted" } else { "REFUSED" },
            weights.join(", "),
            rates.join(", "),
            self.steps as f64,
            self.wall_time_s,
            if self.refusals.is_empty() {
                String::new()
            } else {
                format!("; refused: {}", self.refusals.join("; "))
            }
        )
    }
}

/// One ensemble's amplitude histogram and verdict.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct McRun {
    /// "Eq. 1" or "Eq. 5".
    pub system: String,
    /// Bin edges, density and standard error.
    pub edges: Vec<f64>,
    /// Density per bin.
    pub density: Vec<f64>,
    /// Standard error per bin.
    pub stderr: Vec<f64>,
    /// Fraction of the samples with A beyond the last edge (not in the histogram: the
    /// densities integrate to 1 minus this).
    pub beyond: f64,
    /// Passed the stationarity check.
    pub stationary: bool,
    /// R̂ and ESS.
    #[serde(with = "trirhythm::non_finite")]
    pub r_hat: f64,
    /// Effective sample size of the mean amplitude.
    pub ess: f64,
    /// Distances to each variant's theory.
    pub distances: Vec<Distance>,
    /// The step guard's warnings for this ensemble's Δt
    /// ([`trirhythm::analysis::check_step`]); empty when the step resolves the problem.
    #[serde(default)]
    pub step_warnings: Vec<String>,
    /// `direct` (the paths' samples) or `wells` (the well decomposition's stationary mixture).
    #[serde(default = "direct")]
    pub estimator: String,
    /// The well decomposition, where the direct ensemble was not stationary.
    #[serde(default)]
    pub wells: Option<WellsSummary>,
}

/// A density per bin and its standard errors.
pub type Shown = (Vec<f64>, Vec<f64>);

impl McRun {
    /// What the run's markers show: its histogram, or, where its well decomposition has valid
    /// conditional densities but undetermined weights, their mixture nearest the paper
    /// variant's theory (the weights of H_min; standard errors √Σ π_i² s_i², the wells'
    /// replicas being independent). `true` in the second place for the mixture.
    pub fn shown_density(&self) -> (Shown, bool) {
        if let Some(w) = self
            .wells
            .as_ref()
            .filter(|w| (w.conditional_valid || w.conditional_drifting) && !w.valid)
        {
            let nb = self.edges.len().saturating_sub(1);
            let same = w.conditional.iter().all(|c| c.density.len() == nb);
            if let (Some(b), true) = (w.bounds.first(), same) {
                let pi = &b.weights_min;
                let mix = |f: &dyn Fn(&Conditional, f64, usize) -> f64| -> Vec<f64> {
                    (0..nb)
                        .map(|k| w.conditional.iter().zip(pi).map(|(c, &p)| f(c, p, k)).sum())
                        .collect()
                };
                let density = mix(&|c, p, k| p * c.density[k]);
                let stderr = mix(&|c, p, k| (p * c.stderr[k]).powi(2))
                    .into_iter()
                    .map(f64::sqrt)
                    .collect();
                return ((density, stderr), true);
            }
        }
        ((self.density.clone(), self.stderr.clone()), false)
    }
}

/// `direct`: the estimator of figure data written before the well decomposition.
pub fn direct() -> String {
    "direct".into()
}

/// One P(A) panel: theory curves and ensembles.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct AmplitudePanel {
    /// Caption.
    pub caption: String,
    /// Theory curves: variant name, amplitudes, densities (empty where undefined).
    pub theory: Vec<(String, Vec<f64>, Vec<f64>)>,
    /// The ensembles.
    pub runs: Vec<McRun>,
}

impl AmplitudePanel {
    /// Each theory curve has one density per amplitude (or none, where undefined), finite;
    /// each ensemble's edges increase and its densities and standard errors hold one finite
    /// value ≥ 0 per bin.
    pub fn validate(&self, field: &str) -> crate::validate::Valid {
        use crate::validate::{edges, finite, len, non_negative, scalar};
        for (i, (_, a, d)) in self.theory.iter().enumerate() {
            let f = format!("{field}.theory[{i}]");
            finite(&f, a)?;
            if !d.is_empty() {
                len(&f, d.len(), a.len(), "one density per amplitude")?;
                non_negative(&f, d)?;
            }
        }
        for (i, r) in self.runs.iter().enumerate() {
            let f = format!("{field}.runs[{i}]");
            edges(&format!("{f}.edges"), &r.edges)?;
            let bins = r.edges.len() - 1;
            let of = format!("{bins} bins of edges");
            len(&format!("{f}.density"), r.density.len(), bins, &of)?;
            non_negative(&format!("{f}.density"), &r.density)?;
            len(&format!("{f}.stderr"), r.stderr.len(), bins, &of)?;
            non_negative(&format!("{f}.stderr"), &r.stderr)?;
            scalar(&format!("{f}.beyond"), r.beyond)?;
        }
        Ok(())
    }
}

pub(crate) fn system_name(s: System) -> &'static str {
    match s {
        System::Fractional => "Eq. 1",
        System::Equivalent => "Eq. 5",
        System::Zhuravlev => "Eq. 9",
    }
}

/// An ensemble of `system` for `params` (starts and wells from the theory of `variant`), with
/// the step guard's warnings for its Δt (a step the guard refuses is an error).
pub fn ensemble(
    monitor: &dyn Monitor,
    params: &Params,
    variant: Variant,
    system: System,
    sizes: Sizes,
    joint_bins: usize,
) -> Result<(EnsembleResult, Vec<String>)> {
    let layout = theory_layout(params, variant).ok_or_else(|| Error::Undefined {
        what: "the theory's layout of starts and wells",
        why: format!("no stable cycle or mode for {}", params.describe()),
    })?;
    let spec = EnsembleSpec {
        paths: sizes.paths,
        seed: 1,
        burn_in: sizes.burn_in,
        length: sizes.t_end,
        bins: sizes.bins,
        joint_bins,
        joint_velocity_factor: sizes.joint_velocity_factor,
        amplitude_max: layout.amplitude_max,
        wells: layout.wells,
        ..Default::default()
    };
    let starts: Vec<(f64, f64)> = layout.starts.iter().map(|&u| (u, 0.0)).collect();
    let problem = Problem::from_params(params)?
        .with_system(system)?
        .with_starts(&starts)?;
    // the ensembles' convention (README, "Ensembles"): the memory restarts at each impact
    let method = PredictorCorrector {
        impact_memory: ImpactMemory::Restart,
        ..Default::default()
    };
    monitor.check()?;
    let warnings = check_step(&problem, &method)?.require()?.warnings();
    let result = run_ensemble(
        &problem,
        &method,
        &spec,
        &trirhythm::monitor::Relay(monitor),
    )?;
    Ok((result, warnings))
}

/// The well decomposition of the ensemble [`ensemble`] runs (same problem, method, seed,
/// histograms and wells; `sizes.paths` replicas, [`Sizes::wells`]).
pub fn wells_ensemble(
    monitor: &dyn Monitor,
    params: &Params,
    variant: Variant,
    system: System,
    sizes: Sizes,
    joint_bins: usize,
) -> Result<WellsResult> {
    let layout = theory_layout(params, variant).ok_or_else(|| Error::Undefined {
        what: "the theory's layout of starts and wells",
        why: format!("no stable cycle or mode for {}", params.describe()),
    })?;
    let (length, wspec) = sizes.wells();
    let spec = EnsembleSpec {
        paths: sizes.paths,
        seed: 1,
        burn_in: sizes.burn_in,
        length,
        bins: sizes.bins,
        joint_bins,
        joint_velocity_factor: sizes.joint_velocity_factor,
        amplitude_max: layout.amplitude_max,
        wells: layout.wells,
        ..Default::default()
    };
    let problem = Problem::from_params(params)?.with_system(system)?;
    let method = PredictorCorrector {
        impact_memory: ImpactMemory::Restart,
        ..Default::default()
    };
    run_wells(
        &problem,
        &method,
        &spec,
        &wspec,
        &trirhythm::monitor::Relay(monitor),
    )
}

/// The direct ensemble, and where it is not stationary and the theory has two wells or more,
/// the well decomposition: (the result shown, its step warnings, the estimator's name, the
/// decomposition's summary).
pub fn stationary_ensemble(
    monitor: &dyn Monitor,
    params: &Params,
    variant: Variant,
    system: System,
    sizes: Sizes,
    joint_bins: usize,
) -> Result<(
    EnsembleResult,
    Vec<String>,
    &'static str,
    Option<WellsSummary>,
)> {
    let (r, warnings) = ensemble(monitor, params, variant, system, sizes, joint_bins)?;
    let wells = r.wells.as_ref().map_or(0, Wells::len);
    if r.stationarity.stationary || wells < 2 {
        return Ok((r, warnings, "direct", None));
    }
    let start = std::time::Instant::now();
    let w = wells_ensemble(monitor, params, variant, system, sizes, joint_bins)?;
    let summary = WellsSummary::of(&w, params, start.elapsed().as_secs_f64());
    if w.wells.valid {
        Ok((w.result, warnings, "wells", Some(summary)))
    } else {
        Ok((r, warnings, "direct", Some(summary)))
    }
}

/// A P(A) panel: the theory of both variants and ensembles of each of `systems`.
pub fn amplitude_panel(
    monitor: &dyn Monitor,
    caption: String,
    params: &Params,
    variant: Variant,
    systems: &[System],
    sizes: Sizes,
) -> Result<(AmplitudePanel, Vec<String>)> {
    let mut runs = Vec::new();
    let mut notes = Vec::new();
    let mut a_max = 0.0f64;
    // the systems' ensembles side by side
    let ensembles = crate::each(systems, |&system| {
        stationary_ensemble(monitor, params, variant, system, sizes, 8)
    })?;
    for (&system, (r, step_warnings, estimator, wells)) in systems.iter().zip(ensembles) {
        notes.extend(step_warnings.iter().map(|w| {
            format!(
                "{caption}, MC of {}: step warning: {w}",
                system_name(system)
            )
        }));
        a_max = a_max.max(*r.amplitude.edges.last().unwrap_or(&1.0));
        let mut distances = Vec::new();
        for (v, c) in comparisons(params, &r, 1) {
            match c {
                Ok(TheoryComparison {
                    modes_mc: Some(modes_mc),
                    hellinger,
                    l1,
                    ks,
                    modes_theory,
                    ..
                }) => distances.push(Distance {
                    variant: v.name().into(),
                    hellinger: hellinger.value,
                    hellinger_stderr: hellinger.stderr,
                    l1: l1.value,
                    ks: ks.value,
                    modes_theory,
                    modes_mc,
                }),
                // the shown result is a direct ensemble or an accepted decomposition, whose
                // density exists; should it not, there is no distance to give
                Ok(_) => notes.push(format!(
                    "{caption}: {} theory: no distance, the simulated density does not exist",
                    v.name()
                )),
                Err(e) => notes.push(format!("{caption}: {} theory: {e}", v.name())),
            }
        }
        let st = &r.stationarity;
        if let Some(w) = &wells {
            notes.push(format!(
                "{caption}, MC of {}: {}",
                system_name(system),
                w.line()
            ));
            if let Some(b) = w.bounds_line() {
                notes.push(format!("{caption}, MC of {}: {b}", system_name(system)));
            }
            notes.extend(
                w.notes
                    .iter()
                    .map(|n| format!("{caption}, MC of {}: {n}", system_name(system))),
            );
        }
        notes.push(format!(
            "{caption}, MC of {} ({estimator}): {}; R̂ = {:.3}, ESS = {:.0}, drift {:.1} s.e.; mass beyond A = {} (not in the histogram) {:.2} %; {}",
            system_name(system),
            if st.stationary && estimator == "wells" {
                "well decomposition accepted (stationary mixture)"
            } else if st.stationary {
                "stationarity check passed"
            } else {
                "NOT STATIONARY"
            },
            st.r_hat,
            st.ess,
            st.drift_z,
            num(*r.amplitude.edges.last().unwrap_or(&0.0)),
            100.0 * r.amplitude.beyond,
            distances
                .iter()
                .map(|d| format!(
                    "{}: Hellinger {:.3} ± {:.3}, L1 {:.3}, KS {:.3}, modes {} (theory) vs {} (MC)",
                    d.variant,
                    d.hellinger,
                    d.hellinger_stderr,
                    d.l1,
                    d.ks,
                    d.modes_theory,
                    d.modes_mc
                ))
                .collect::<Vec<_>>()
                .join("; ")
        ));
        runs.push(McRun {
            system: system_name(system).into(),
            edges: r.amplitude.edges.clone(),
            density: r.amplitude.density.clone(),
            stderr: r.amplitude.stderr.clone(),
            beyond: r.amplitude.beyond,
            stationary: st.stationary,
            r_hat: st.r_hat,
            ess: st.ess,
            distances,
            step_warnings,
            estimator: estimator.into(),
            wells,
        });
    }
    let mut theory = Vec::new();
    for v in [Variant::Paper, Variant::Consistent] {
        let curve = Theory::new(params, v)
            .and_then(|th| th.amplitude_pdf())
            .map(|pdf| {
                let xs: Vec<f64> = (1..=600).map(|i| a_max * i as f64 / 600.0).collect();
                let ys = xs.iter().map(|&a| pdf.density(a)).collect();
                (xs, ys)
            })
            .unwrap_or_default();
        theory.push((v.name().to_string(), curve.0, curve.1));
    }
    Ok((
        AmplitudePanel {
            caption,
            theory,
            runs,
        },
        notes,
    ))
}

/// The Monte Carlo mass the drawn densities leave out, in one line: the largest over
/// `panels` and where. For a histogram it is the mass beyond its last edge; for a wells'
/// mixture ([`McRun::shown_density`]) 1 − ∫ of the mixture over the bins, which adds the mass
/// its wells' paths spent beyond the edge.
pub fn beyond_line(panels: &[AmplitudePanel]) -> String {
    let largest = panels
        .iter()
        .flat_map(|p| {
            p.runs.iter().map(move |r| {
                let ((density, _), mixture) = r.shown_density();
                let held: f64 = r
                    .edges
                    .windows(2)
                    .zip(&density)
                    .map(|(w, d)| (w[1] - w[0]) * d)
                    .sum();
                let left = if mixture {
                    (1.0 - held).max(0.0)
                } else {
                    r.beyond
                };
                (left, mixture, &p.caption, &r.system)
            })
        })
        .max_by(|a, b| a.0.total_cmp(&b.0));
    match largest {
        Some((b, mixture, caption, system)) => format!(
            "Monte Carlo mass the drawn densities leave out (A beyond each histogram's A_max; for a wells' mixture also its wells' mass there; the drawn densities integrate to 1 minus it): at most {:.2} % ({caption}, {system}{}); each ensemble's in the CSV notes",
            100.0 * b,
            if mixture { ", the wells' mixture" } else { "" }
        ),
        None => "no Monte Carlo ensemble".into(),
    }
}

/// The ensembles of `panels` shown by the well decomposition, and those where it was tried: one
/// line for the figure's caption.
pub fn wells_line(panels: &[AmplitudePanel]) -> String {
    let runs = || panels.iter().flat_map(|p| &p.runs);
    let tried = runs().filter(|r| r.wells.is_some()).count();
    let used = runs().filter(|r| r.estimator == "wells").count();
    format!(
        "where the direct ensemble was not stationary the well decomposition was tried ({tried} \
         ensembles): accepted for {used}, whose stationarity is its diagnostic's (\"MC by \
         wells\"); the notes give every decomposition's weights, rates, cost and refusal"
    )
}

/// (ensembles that passed the stationarity check, ensembles) over `panels`.
pub fn stationary_count(panels: &[AmplitudePanel]) -> (usize, usize) {
    let runs = || panels.iter().flat_map(|p| &p.runs);
    (runs().filter(|r| r.stationary).count(), runs().count())
}

/// The theory of each variant against the result (an error, in words, where the theory has no
/// P(A)).
pub fn comparisons(
    params: &Params,
    r: &EnsembleResult,
    seed: u64,
) -> Vec<(Variant, std::result::Result<TheoryComparison, String>)> {
    [Variant::Paper, Variant::Consistent]
        .into_iter()
        .map(|v| {
            let c = Theory::new(params, v)
                .and_then(|th| compare(r, &th, seed))
                .map_err(|e| e.to_string());
            (v, c)
        })
        .collect()
}

/// The table of amplitude panels: `panel,series,A_lo,A_hi,density,stderr` (theory rows have
/// A_lo = A_hi = A and a zero standard error).
pub fn amplitude_table(notes: &[String], panels: &[AmplitudePanel]) -> Table {
    let mut csv = Table::new(
        notes,
        &["panel", "series", "A_lo", "A_hi", "density", "stderr"],
    )
    .allow_infinity("stderr");
    for p in panels {
        for (v, xs, ys) in &p.theory {
            for (x, y) in xs.iter().zip(ys) {
                csv.row([
                    p.caption.clone(),
                    format!("theory {v}"),
                    num(*x),
                    num(*x),
                    num(*y),
                    "0".into(),
                ]);
            }
        }
        for r in &p.runs {
            // the histogram, and where the picture draws the wells' mixture instead
            // ([`McRun::shown_density`]) that mixture too, as its own series
            let ((density, stderr), mixture) = r.shown_density();
            let mut series = vec![(format!("MC {}", r.system), &r.density, &r.stderr)];
            if mixture {
                series.push((
                    format!("MC {}, wells' mixture (drawn)", r.system),
                    &density,
                    &stderr,
                ));
            }
            for (name, density, stderr) in series {
                for (i, w) in r.edges.windows(2).enumerate() {
                    let s = stderr[i];
                    csv.row([
                        p.caption.clone(),
                        name.clone(),
                        num(w[0]),
                        num(w[1]),
                        num(density[i]),
                        // one path: no standard error (said in the notes)
                        if s.is_finite() { num(s) } else { "inf".into() },
                    ]);
                }
            }
        }
    }
    csv
}

/// An ensemble's values left open by the user, filled from the averaged theory
/// ([`theory_layout`]), with each choice made said in words. `None` where the user gave
/// nothing and the theory offers nothing.
#[derive(Debug, Clone, Default)]
pub struct Choices {
    /// Initial displacements: the user's, or the theory's modes (stable cycles at D = 0).
    pub starts: Option<Vec<f64>>,
    /// Upper end of the amplitude histogram: the user's, or 1.2 × the theory's largest mode
    /// (+ 6 widths) and at least 1.2 × the largest start.
    pub amplitude_max: Option<f64>,
    /// The wells of P(A), when the theory has them.
    pub wells: Option<Wells>,
    /// The choices made, in words.
    pub said: Vec<String>,
}

/// Fill an ensemble's open choices (`u0` empty, `amplitude_max` `None`) from the theory of
/// `params` in `variant`.
pub fn choices(
    params: &Params,
    variant: Variant,
    u0: &[f64],
    amplitude_max: Option<f64>,
) -> Choices {
    choices_from(theory_layout(params, variant), variant, u0, amplitude_max)
}

/// [`choices`] from the theory of a model of the class ([`model_layout`]: e.g. the wall-free
/// theory of Eq. (1) without its wall).
pub fn model_choices(
    model: &trirhythm::model::Model,
    variant: Variant,
    u0: &[f64],
    amplitude_max: Option<f64>,
) -> Choices {
    choices_from(model_layout(model, variant), variant, u0, amplitude_max)
}

fn choices_from(
    layout: Option<trirhythm::analysis::versus::TheoryLayout>,
    variant: Variant,
    u0: &[f64],
    amplitude_max: Option<f64>,
) -> Choices {
    let mut said = Vec::new();
    let starts = if !u0.is_empty() {
        Some(u0.to_vec())
    } else {
        layout.as_ref().map(|l| {
            said.push(format!(
                "u0 = {} (the theory's modes, {} variant)",
                crate::views::list(&l.starts),
                variant.name()
            ));
            l.starts.clone()
        })
    };
    let amplitude_max = match (amplitude_max, &layout, &starts) {
        (Some(a), _, _) => Some(a),
        (None, Some(l), Some(starts)) => {
            let a = l
                .amplitude_max
                .max(1.2 * starts.iter().fold(0.0f64, |m, x| m.max(x.abs())));
            said.push(format!(
                "amplitude-max = {a:.4} (1.2 × the theory's largest mode + 6 widths)"
            ));
            Some(a)
        }
        _ => None,
    };
    let wells = layout.and_then(|l| l.wells);
    if let Some(w) = &wells {
        said.push(format!(
            "wells: modes {} and antimodes {} of P(A) ({} variant)",
            crate::views::list(&w.modes),
            crate::views::list(&w.antimodes),
            variant.name()
        ));
    }
    Choices {
        starts,
        amplitude_max,
        wells,
        said,
    }
}
