//! What a front end asks for, in library terms: the model choices every simulating command
//! shares ([`Model`]: equation, wall, memory, with their names), and an ensemble request
//! ([`EnsembleRequest`]: the choices made for the user, the method line, the JSON document).
//!
//! The command-line tool and the Python package both build their runs here, so that the same
//! arguments give the same problem, the same method and the same document, bit for bit.
//! Errors name the argument as the library does (`amplitude_max`, `u0`); each front end tells
//! them in its own spelling (`--amplitude-max` for the command line).
//!
//! Tests: the command line's `tests/ensemble.rs` (documents), the Python package's
//! `tests/test_api.py` (the same document from Python).

use crate::montecarlo;
use crate::views::{self, TheoryEntry};
use serde::Serialize;
use serde_json::Value;
use std::collections::BTreeMap;
use trirhythm::analysis::ensemble::{
    run_wells, EnsembleResult, EnsembleSpec, WellsEstimate, WellsResult, WellsSpec,
};
use trirhythm::analysis::TheoryComparison;
use trirhythm::engine::{
    Barrier, ImpactMemory, Lanes, Memory, PredictorCorrector, Problem, System, DEFAULT_WINDOW,
};
use trirhythm::model::{GeneralTerms, Params};
use trirhythm::theory::averaging::{Theory, Variant};
use trirhythm::{Error, Result};

/// How the fractional memory is kept.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum MemoryKind {
    /// Sum of exponentials beyond an exact local window: O(1) work per step.
    #[default]
    Soe,
    /// Exact weights over the whole history: O(N) per step (reference; short runs only).
    Direct,
}

/// A name as users type it, and back.
pub trait Named: Sized + Copy + 'static {
    /// The kind of thing named, for errors (`system`).
    const KIND: &'static str;
    /// Every value with its name.
    const ALL: &'static [(Self, &'static str)];

    /// The name as typed.
    fn name(self) -> &'static str
    where
        Self: PartialEq,
    {
        Self::ALL
            .iter()
            .find(|(v, _)| *v == self)
            .map(|(_, n)| *n)
            .unwrap_or("?")
    }

    /// The value of a name; [`Error::Unknown`] naming the accepted ones otherwise.
    fn parse(name: &str) -> Result<Self> {
        Self::ALL
            .iter()
            .find(|(_, n)| *n == name)
            .map(|(v, _)| *v)
            .ok_or_else(|| Error::Unknown {
                kind: Self::KIND,
                name: name.to_string(),
                expected: Self::ALL
                    .iter()
                    .map(|(_, n)| *n)
                    .collect::<Vec<_>>()
                    .join(", "),
            })
    }
}

impl Named for System {
    const KIND: &'static str = "system";
    const ALL: &'static [(Self, &'static str)] = &[
        (System::Fractional, "fractional"),
        (System::Equivalent, "equivalent"),
        (System::Zhuravlev, "zhuravlev"),
    ];
}

impl Named for Barrier {
    const KIND: &'static str = "barrier";
    const ALL: &'static [(Self, &'static str)] = &[(Barrier::On, "on"), (Barrier::Off, "off")];
}

impl Named for MemoryKind {
    const KIND: &'static str = "memory";
    const ALL: &'static [(Self, &'static str)] =
        &[(MemoryKind::Soe, "soe"), (MemoryKind::Direct, "direct")];
}

impl Named for ImpactMemory {
    const KIND: &'static str = "impact memory";
    const ALL: &'static [(Self, &'static str)] = &[
        (ImpactMemory::Continuous, "continuous"),
        (ImpactMemory::Restart, "restart"),
    ];
}

impl Named for Variant {
    const KIND: &'static str = "variant";
    const ALL: &'static [(Self, &'static str)] = &[
        (Variant::Paper, "paper"),
        (Variant::Consistent, "consistent"),
    ];
}

/// How an ensemble's stationary statistics are estimated.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Estimator {
    /// Paths run side by side, every sample counted (`run_ensemble`).
    #[default]
    Direct,
    /// Well decomposition: conditional statistics per well, rates by splitting
    /// ([`trirhythm::analysis::ensemble::run_wells`]).
    Wells,
}

impl Named for Estimator {
    const KIND: &'static str = "method";
    const ALL: &'static [(Self, &'static str)] =
        &[(Estimator::Direct, "direct"), (Estimator::Wells, "wells")];
}

/// The equation, the wall and the memory: said once for every run that simulates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Model {
    /// Which equation.
    pub system: System,
    /// The wall at U = 0.
    pub barrier: Barrier,
    /// How the fractional memory is kept.
    pub memory: MemoryKind,
    /// Relative tolerance of the sum-of-exponentials kernel; `None`: the library's default,
    /// [`trirhythm::engine::step_tolerance`] of the step (10⁻⁵·Δt²).
    pub tolerance: Option<f64>,
}

impl Default for Model {
    fn default() -> Self {
        Model {
            system: System::Fractional,
            barrier: Barrier::On,
            memory: MemoryKind::Soe,
            tolerance: None,
        }
    }
}

impl Model {
    /// The problem of `params` with this equation and wall (its start still to be set).
    pub fn problem(&self, params: &Params) -> Result<Problem> {
        Problem::from_params(params)?
            .with_barrier(self.barrier)?
            .with_system(self.system)
    }

    /// `memory=… tolerance=… impact_memory=… barrier=… system=…`, for `method:` lines.
    pub fn line(&self, impact_memory: ImpactMemory) -> String {
        format!(
            "memory={} tolerance={} impact_memory={} barrier={} system={}",
            self.memory.name(),
            match self.tolerance {
                Some(t) => t.to_string(),
                None => "auto".to_string(),
            },
            impact_memory.name(),
            self.barrier.name(),
            self.system.name()
        )
    }

    /// The predictor–corrector of step `dt`, this memory and `impact_memory`.
    pub fn method(&self, dt: f64, impact_memory: ImpactMemory) -> PredictorCorrector {
        PredictorCorrector {
            dt,
            memory: match self.memory {
                MemoryKind::Direct => Memory::Direct,
                MemoryKind::Soe => match self.tolerance {
                    Some(tolerance) => Memory::SumOfExponentials { tolerance },
                    None => Memory::Auto,
                },
            },
            impact_memory,
            window: DEFAULT_WINDOW,
        }
    }
}

/// The least `amplitude_max`: the energy histogram spans ½ω1²·max², which underflows to 0
/// (zero-width bins, infinite densities) for max below about 1e-154; 1e-100 keeps every bin width
/// and density finite.
pub const MIN_AMPLITUDE_MAX: f64 = 1e-100;

/// An ensemble as a user asks for it; [`EnsembleRequest::setup`] fills in what is left open.
#[derive(Debug, Clone, PartialEq)]
pub struct EnsembleRequest {
    /// The validated parameters.
    pub params: Params,
    /// Formula variant of the averaged theory (chooses the starts, wells and range).
    pub variant: Variant,
    /// Equation, wall, memory.
    pub model: Model,
    /// What the memory does at an impact.
    pub impact_memory: ImpactMemory,
    /// Step Δt.
    pub dt: f64,
    /// Number of paths (path i is noise stream i of the seed).
    pub paths: usize,
    /// Length of each path's recorded window.
    pub t_end: f64,
    /// Time discarded at the start of each path.
    pub burn_in: f64,
    /// Seed of the noise streams.
    pub seed: u64,
    /// Initial displacements, used in turn (empty: the theory's modes).
    pub u0: Vec<f64>,
    /// Bins of the one-dimensional histograms.
    pub bins: usize,
    /// Bins per axis of the joint histogram.
    pub joint_bins: usize,
    /// Upper end of the amplitude histogram (`None`: from the theory).
    pub amplitude_max: Option<f64>,
    /// Record every K-th step of the window.
    pub sample_every: u64,
    /// Paths stepped together ([`Lanes`]); the result is the same bits for every choice.
    pub lanes: Lanes,
    /// The General kernel's terms of a model file (Duffing, Rayleigh, forcing; None for the
    /// paper's family): the starts, wells and range come from the model's averaged theory by
    /// quadrature where it holds; where it does not (a forcing, a strong Duffing shift) nothing
    /// is chosen from it and the comparison says why.
    pub terms: Option<GeneralTerms>,
}

/// The model of the class of `params`' Eq. (1) with `barrier` and the General kernel's `terms`.
fn class_model(
    params: &Params,
    barrier: Barrier,
    terms: Option<&GeneralTerms>,
) -> trirhythm::model::Model {
    let mut m = trirhythm::model::Model::from(params);
    if barrier == Barrier::Off {
        m.walls.clear();
    }
    if let Some(t) = terms {
        m.restoring.cubic = t.cubic;
        m.restoring.quintic = t.quintic;
        m.damping.rayleigh = t.rayleigh.clone();
        m.forcing = t.forcing;
        m.fractional = t.fractional.clone();
        m.noise.multiplicative = t.multiplicative;
        m.noise.correlation = t.correlation;
        if !t.walls.is_empty() {
            // walls other than the paper's (offset, below, two, r(v)): the model's own, with a
            // start between them (the theory does not use it; the model must be valid)
            m.walls = t.walls.clone();
            use trirhythm::model::Keep;
            let lower = t.walls.iter().find(|w| w.keep == Keep::Above);
            let upper = t.walls.iter().find(|w| w.keep == Keep::Below);
            m.start.u0 = match (lower, upper) {
                (Some(l), Some(u)) => 0.5 * (l.position + u.position),
                (Some(l), None) => l.position.max(m.start.u0),
                (None, Some(u)) => u.position.min(m.start.u0),
                (None, None) => m.start.u0,
            };
        }
    }
    m
}

impl EnsembleRequest {
    /// The command line's defaults around `params`.
    pub fn new(params: Params) -> Self {
        EnsembleRequest {
            params,
            variant: Variant::Paper,
            model: Model::default(),
            impact_memory: ImpactMemory::Restart,
            dt: 0.01,
            paths: 8,
            t_end: 1000.0,
            burn_in: 100.0,
            seed: 1,
            u0: vec![],
            bins: 100,
            joint_bins: 48,
            amplitude_max: None,
            sample_every: 1,
            lanes: Lanes::Auto,
            terms: None,
        }
    }

    /// The model of the class this request simulates: the parameters' Eq. (1), its wall as
    /// the request has it, and the General kernel's terms.
    pub fn class_model(&self) -> trirhythm::model::Model {
        class_model(&self.params, self.model.barrier, self.terms.as_ref())
    }

    /// Choose what is left open from the theory and convert to library types; sizes, steps
    /// and ranges are checked by the ensemble's driver.
    pub fn setup(&self) -> Result<EnsembleSetup> {
        let chosen = if self.terms.is_none() && self.model.barrier == Barrier::On {
            montecarlo::choices(&self.params, self.variant, &self.u0, self.amplitude_max)
        } else {
            // the wells and the range from the theory of the model simulated: without the wall
            // the wall-free theory, with the General kernel's terms their quadrature, in the
            // consistent variant where the paper's printed formulas (Eq. (1) with its wall at 0
            // only) do not hold
            let model = self.class_model();
            let variant = match trirhythm::theory::averaging::applies(&model, self.variant) {
                Ok(_) => self.variant,
                Err(_) => Variant::Consistent,
            };
            match Theory::from_model(&model, variant) {
                Ok(_) => montecarlo::model_choices(&model, variant, &self.u0, self.amplitude_max),
                Err(why) if self.terms.is_some() => {
                    if self.u0.is_empty() {
                        return Err(Error::Undefined {
                            what: "a start u0",
                            why: format!("{why}; give the initial displacements u0"),
                        });
                    }
                    if self.amplitude_max.is_none() {
                        return Err(Error::Undefined {
                            what: "amplitude_max",
                            why: format!("{why}; give the histogram's range amplitude_max"),
                        });
                    }
                    montecarlo::Choices {
                        starts: Some(self.u0.clone()),
                        amplitude_max: self.amplitude_max,
                        wells: None,
                        said: vec![],
                    }
                }
                Err(_) => montecarlo::model_choices(&model, variant, &self.u0, self.amplitude_max),
            }
        };
        let Some(starts) = chosen.starts else {
            return Err(Error::Undefined {
                what: "a start u0",
                why: "the averaged theory offers no cycle to start from for these parameters; \
                      give the initial displacements u0"
                    .into(),
            });
        };
        let Some(amplitude_max) = chosen.amplitude_max else {
            return Err(Error::Undefined {
                what: "amplitude_max",
                why: "no theory to choose the histogram range from; give it".into(),
            });
        };
        if amplitude_max > 0.0 && amplitude_max < MIN_AMPLITUDE_MAX {
            return Err(Error::InvalidParameter {
                name: "amplitude_max".into(),
                value: amplitude_max,
                allowed: format!(
                    "{MIN_AMPLITUDE_MAX:e} or more (below it the energy histogram's range \
                     ½ω1²·max² and its bin widths underflow to 0)"
                ),
            });
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
            wells: chosen.wells,
            lanes: self.lanes,
            ..Default::default()
        };
        let starts: Vec<(f64, f64)> = starts.iter().map(|&u| (u, 0.0)).collect();
        let problem = self
            .model
            .problem(&self.params)?
            .with_terms(self.terms.clone())?
            .with_starts(&starts)?;
        let method = self.model.method(self.dt, self.impact_memory);
        // every size, step and range checked (no path run) before the step guard
        trirhythm::analysis::run_paths(&problem, &method, &spec, &[], &trirhythm::monitor::Silent)?;
        let step_warnings = trirhythm::analysis::check_step(&problem, &method)?
            .require()?
            .warnings();
        Ok(EnsembleSetup {
            params: self.params.clone(),
            terms: self.terms.clone(),
            problem,
            method,
            spec,
            choices: chosen.said,
            method_line: self.method_line(),
            step_warnings,
        })
    }

    /// `method: predictor-corrector dt=… memory=… … sample_every=…`.
    pub fn method_line(&self) -> String {
        format!(
            "method: predictor-corrector dt={} {} paths={} burn_in={} t_end={} seed={} \
             sample_every={}",
            self.dt,
            self.model.line(self.impact_memory),
            self.paths,
            self.burn_in,
            self.t_end,
            self.seed,
            self.sample_every
        )
    }
}

/// `… estimator=wells clones=… max_excursion=… max_iterations=… separation=…
/// core_quantile=…`: the `method:` line of a well-decomposition run.
pub fn wells_line(method_line: &str, w: &WellsSpec) -> String {
    format!(
        "{method_line} estimator=wells clones={} max_excursion={} max_iterations={} \
         separation={} core_quantile={}",
        w.clones, w.max_excursion, w.max_iterations, w.separation, w.core_quantile
    )
}

/// An ensemble's inputs in library types, with the choices made for the user.
#[derive(Debug, Clone)]
pub struct EnsembleSetup {
    /// The parameters.
    pub params: Params,
    /// The General kernel's terms (None: the paper's family).
    pub terms: Option<GeneralTerms>,
    /// The problem with its starts.
    pub problem: Problem,
    /// The predictor–corrector.
    pub method: PredictorCorrector,
    /// Sizes, seed, histograms.
    pub spec: EnsembleSpec,
    /// What was chosen where the user left a value open, in words.
    pub choices: Vec<String>,
    /// The `method:` line of the document.
    pub method_line: String,
    /// The step guard's warnings for Δt ([`trirhythm::analysis::check_step`]; a step it
    /// refuses is an error of [`EnsembleRequest::setup`]).
    pub step_warnings: Vec<String>,
}

impl EnsembleSetup {
    /// The averaged theory of the model simulated against `result`, each variant's refusal in
    /// words where it does not apply: [`Theory::from_model`] of the paper's family (with its
    /// wall the paper's closed forms, bit for bit; without it the wall-free theory, not the
    /// wall's σ1), with the General kernel's terms their quadrature where first-order
    /// averaging holds (Duffing, Rayleigh; the refusal naming the assumption otherwise, e.g.
    /// a strong Duffing shift or a forcing).
    pub fn comparisons(
        &self,
        result: &EnsembleResult,
    ) -> Vec<(Variant, std::result::Result<TheoryComparison, String>)> {
        let model = self.class_model();
        [Variant::Paper, Variant::Consistent]
            .into_iter()
            .map(|v| {
                let c = Theory::from_model(&model, v)
                    .and_then(|th| {
                        trirhythm::analysis::versus::compare(result, &th, self.spec.seed)
                    })
                    .map_err(|e| e.to_string());
                (v, c)
            })
            .collect()
    }

    /// The model of the class this ensemble simulates: the parameters' Eq. (1), its wall as
    /// the run has it, and the General kernel's terms.
    pub fn class_model(&self) -> trirhythm::model::Model {
        class_model(&self.params, self.problem.barrier(), self.terms.as_ref())
    }

    /// The ensemble by well decomposition: `spec.paths` replicas of one path per well of
    /// `spec.length`, the rates by splitting with `wells` ([`run_wells`]). Needs the theory's
    /// wells (an error otherwise).
    pub fn run_wells(
        &self,
        wells: &WellsSpec,
        monitor: &dyn trirhythm::monitor::Monitor<()>,
    ) -> Result<WellsResult> {
        if self.terms.is_some() {
            if let Err(why) = Theory::from_model(&self.class_model(), Variant::Consistent) {
                return Err(Error::NotApplicable {
                    method: "the well method (ensemble --method wells)".into(),
                    assumption: "the averaged theory's wells of P(A)".into(),
                    reason: why.to_string(),
                });
            }
        }
        run_wells(&self.problem, &self.method, &self.spec, wells, monitor)
    }

    /// The JSON document of a well-decomposition run: the direct document's keys for its
    /// stationary mixture, `estimator: "wells"`, and `decomposition` (rates, rate matrix,
    /// weights, replicas, diagnostic).
    pub fn wells_document<'a>(
        &'a self,
        result: &'a WellsResult,
        theory: &'a views::Comparisons,
        wall_time_s: f64,
        method_line: &'a str,
    ) -> WellsDocument<'a> {
        let mut ensemble = self.document(&result.result, theory, wall_time_s);
        ensemble.method = method_line;
        WellsDocument {
            ensemble,
            estimator: "wells",
            decomposition: &result.wells,
            bounds: montecarlo::WellsSummary::of(result, &self.params, wall_time_s).bounds,
        }
    }

    /// The JSON document of `result` (what `trirhythm ensemble --format json` writes).
    pub fn document<'a>(
        &'a self,
        result: &'a EnsembleResult,
        theory: &'a views::Comparisons,
        wall_time_s: f64,
    ) -> EnsembleDocument<'a> {
        EnsembleDocument {
            params: params_json(&self.params),
            terms: self.terms.as_ref().map(GeneralTerms::describe),
            method: &self.method_line,
            choices: &self.choices,
            step_warnings: &self.step_warnings,
            wall_time_s,
            result,
            theory: views::theory_entries(theory),
        }
    }
}

/// The ensemble's JSON document: the library's result with the parameters, the method, the
/// choices made for the user, the wall time and the theory against the result.
#[derive(Serialize)]
pub struct EnsembleDocument<'a> {
    /// The parameters in key order.
    pub params: Value,
    /// The General kernel's terms ([`GeneralTerms::describe`]), absent for the paper's
    /// family.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub terms: Option<String>,
    /// The `method:` line.
    pub method: &'a str,
    /// The choices made for the user.
    pub choices: &'a [String],
    /// The step guard's warnings.
    pub step_warnings: &'a [String],
    /// Seconds of wall time.
    pub wall_time_s: f64,
    /// The result.
    #[serde(flatten)]
    pub result: &'a EnsembleResult,
    /// Each variant of the theory against the result.
    pub theory: BTreeMap<&'static str, TheoryEntry<'a>>,
}

/// The JSON document of a well-decomposition run ([`EnsembleSetup::wells_document`]).
#[derive(Serialize)]
pub struct WellsDocument<'a> {
    /// The direct document's keys, for the stationary mixture.
    #[serde(flatten)]
    pub ensemble: EnsembleDocument<'a>,
    /// `wells`.
    pub estimator: &'static str,
    /// What the well method adds (`decomposition`: the result's `wells` key holds the wells).
    pub decomposition: &'a WellsEstimate,
    /// Where the conditional statistics are valid but the weights are not determined (the
    /// mixture, its density and the distances to the theory are then null): the Hellinger
    /// distance to each variant's theory over every weighting of the wells, as the figures
    /// give it ([`montecarlo::Bounds`]); empty otherwise.
    pub bounds: Vec<montecarlo::Bounds>,
}

/// The parameters as a JSON object in key order (a non-finite value, which validated
/// parameters never hold, is `null`).
pub fn params_json(p: &Params) -> Value {
    let mut m = serde_json::Map::new();
    for (k, v) in p.key_values() {
        m.insert(
            k,
            serde_json::Number::from_f64(v)
                .map(Value::Number)
                .unwrap_or(Value::Null),
        );
    }
    Value::Object(m)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The ensemble is compared with the theory of the model it simulates: with the wall the
    /// paper's closed forms (the same P(A), bit for bit), without it the wall-free theory (its
    /// own σ1: another P(A)), and the paper's printed formulas refused there.
    #[test]
    fn an_ensemble_is_compared_with_the_theory_of_the_model_it_simulates() {
        let params = trirhythm::model::preset("fig13a").unwrap().params;
        let mut request = EnsembleRequest::new(params.clone());
        let with = request.setup().unwrap();
        request.model.barrier = Barrier::Off;
        let without = request.setup().unwrap();
        assert_eq!(with.class_model().walls.len(), 1);
        assert!(without.class_model().walls.is_empty());
        let pdf = |t: Theory| t.amplitude_pdf().unwrap();
        for v in [Variant::Paper, Variant::Consistent] {
            let ours = pdf(Theory::from_model(&with.class_model(), v).unwrap());
            let paper = pdf(Theory::new(&params, v).unwrap());
            for a in [0.5, 2.0, 8.0, 12.5] {
                assert_eq!(
                    ours.density(a).to_bits(),
                    paper.density(a).to_bits(),
                    "{v:?}, A = {a}"
                );
            }
        }
        let free = pdf(Theory::from_model(&without.class_model(), Variant::Consistent).unwrap());
        let walled = pdf(Theory::new(&params, Variant::Consistent).unwrap());
        let differ = [0.5, 2.0, 8.0, 12.5]
            .iter()
            .any(|&a| (free.density(a) - walled.density(a)).abs() > 1e-6 * walled.density(a).abs());
        assert!(differ, "the wall-free P(A) is the wall's");
        assert!(Theory::from_model(&without.class_model(), Variant::Paper).is_err());
    }

    #[test]
    fn names_parse_back_and_unknown_names_list_the_accepted() {
        for (v, n) in System::ALL {
            assert_eq!(System::parse(n).unwrap(), *v);
            assert_eq!(v.name(), *n);
        }
        let e = Barrier::parse("maybe").unwrap_err().to_string();
        assert!(
            e.contains("barrier `maybe`") && e.contains("on, off"),
            "{e}"
        );
    }

    #[test]
    fn a_tiny_amplitude_max_is_refused_by_name() {
        let mut r = EnsembleRequest::new(Params::default());
        r.amplitude_max = Some(1e-300);
        let e = r.setup().unwrap_err().to_string();
        assert!(e.contains("amplitude_max = 1e-300"), "{e}");
    }

    #[test]
    fn the_method_line_is_the_command_lines() {
        let r = EnsembleRequest::new(Params::default());
        assert_eq!(
            r.method_line(),
            "method: predictor-corrector dt=0.01 memory=soe tolerance=auto \
             impact_memory=restart barrier=on system=fractional paths=8 burn_in=100 t_end=1000 \
             seed=1 sample_every=1"
        );
    }
}
