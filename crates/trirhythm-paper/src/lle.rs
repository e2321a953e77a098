//! The largest Lyapunov exponent against the noise intensity (Figs 17, 18) and what Fig. 19
//! shares with them: run sizes at quick or paper quality, the step rule, the curves by regime,
//! panels of curves with error bars and the regime rules' outcome per curve.
//!
//! Figs 17 and 18 are one computation, [`lle_against_noise_figure`], with two configurations
//! ([`LleNoiseFigure`]): two panels, each a set of curves of the LLE against D on a log-spaced
//! grid ([`noises`]). For every value of the panel's parameter the starts are classified by the
//! attractor their noise-free path reaches ([`regime_starts`]: the averaged theory's stable
//! amplitudes, 1 and 0.01 tried) and one curve is drawn per attractor: the rest regime
//! ([`StartKind::Rest`], also at [`REST_EXTRA_NOISES`]) or a cycle ([`StartKind::Cycle`], named
//! inner / middle / outer in [`Curve::attractor`]). Each curve carries the regime rules'
//! decision ([`CurveRegime`], `verdict::rules::regime`): every point's call against δ = 1/W with
//! the merged realisations kept, the bracket of D_c, the rest regime's pooled exponent and slope,
//! and on a cycle the phase-reduction prediction −c·D with its equivalence test.
//!
//! Step: Δt = the largest of [`DT_LADDER`] not above τ/10 ([`dt_for`]): the coloured noise's
//! correlation time is resolved by at least ten steps (at Δt = 0.01 and τ = 0.025 the exponent
//! was ≈ 6 % low against Δt = 0.0025, an under-resolved noise at impacts).
//!
//! Method: [`largest_lyapunov`] with frozen noise: two trajectories with whole-memory
//! renormalisation, the finite-time exponent over a window after a transient, mean ± standard
//! error over noise realisations. Checked by the library's Lyapunov tests (a linear system's
//! exponent is its eigenvalue's real part) and `tests/figures.rs`.

use crate::notes::{caption, num, sig, symbol, table_notes, variant_line, Caption};
use crate::requests::{Model, Named};
use crate::table::Table;
use crate::verdict::rules::{
    agrees_with_prediction, bracket, calls, rest_regime, significance, strong_noise, Bracket, Call,
    LleCurve, LlePoint, PointSign, RegimePoint, RestRegime, StrongNoise, ALPHA,
};
use crate::{FigureOptions, Monitor};
use serde::{Deserialize, Serialize};
use trirhythm::analysis::lyapunov::{
    attractor_starts, largest_lyapunov, phase_response, well_escape, Attractor, AttractorSpec,
    LyapunovMethod, LyapunovSpec, PhaseSpec, WellEscape,
};
use trirhythm::engine::{ImpactMemory, PredictorCorrector, Problem};
use trirhythm::maths;
use trirhythm::model::{preset, Params};
use trirhythm::monitor::OnlyCancel;
use trirhythm::theory::averaging::{Theory, Variant};
use trirhythm::Result;

/// The steps Δt may take: whole fractions of the windows, from the figures' former 0.01 down.
pub const DT_LADDER: [f64; 8] = [0.01, 0.005, 0.0025, 0.002, 0.001, 0.0005, 0.00025, 0.0001];

/// The step for correlation time `tau`: the largest of [`DT_LADDER`] not above τ/10 (0.01 for
/// τ ≥ 0.1 and for white noise, τ = 0; the smallest rung below τ = 0.001).
pub fn dt_for(tau: f64) -> f64 {
    if tau <= 0.0 {
        return DT_LADDER[0];
    }
    DT_LADDER
        .iter()
        .copied()
        .find(|&dt| dt <= tau / 10.0 * (1.0 + 1e-12))
        .unwrap_or(DT_LADDER[DT_LADDER.len() - 1])
}

/// Sizes of the runs behind one LLE, and the model and integrator they run with.
#[derive(Debug, Clone)]
pub struct Sizes {
    /// Paths, transient, window (and the method that follows the perturbation).
    pub spec: LyapunovSpec,
    /// The equation, the wall and the memory (the figures: Eq. 1 with the wall, the
    /// sum-of-exponentials memory at the default tolerance 1e-5·Δt²).
    pub model: Model,
    /// The step Δt; `None`: the figures' rule, [`dt_for`] of each parameter set's τ.
    pub dt: Option<f64>,
    /// What the memory does at an impact (the figures: restart).
    pub impact_memory: ImpactMemory,
}

impl Sizes {
    /// Quick (CI) or paper quality of Figs 17 and 18.
    pub fn of(quick: bool) -> Sizes {
        Sizes::with_window(quick, 100.0, 1500.0)
    }

    /// Quick (2 realisations, transient 20, window `quick_window`) or paper quality (16
    /// realisations, transient 200, window `full_window`), seed 1.
    pub fn with_window(quick: bool, quick_window: f64, full_window: f64) -> Sizes {
        let (paths, transient, length) = if quick {
            (2, 20.0, quick_window)
        } else {
            (16, 200.0, full_window)
        };
        Sizes::of_spec(LyapunovSpec {
            paths,
            seed: 1,
            transient,
            length,
            ..Default::default()
        })
    }

    /// The runs of `spec` with the figures' model and integrator: Eq. 1 with the wall, Δt by
    /// [`dt_for`], restart impact memory.
    pub fn of_spec(spec: LyapunovSpec) -> Sizes {
        Sizes {
            spec,
            model: Model::default(),
            dt: None,
            impact_memory: ImpactMemory::Restart,
        }
    }

    /// The integrator for correlation time `tau`: Δt given, else from [`dt_for`]; the
    /// model's memory and the impact memory.
    pub fn method(&self, tau: f64) -> PredictorCorrector {
        self.model
            .method(self.dt.unwrap_or_else(|| dt_for(tau)), self.impact_memory)
    }

    /// The problem of `params` with the model's equation and wall (start still to be set).
    pub fn problem(&self, params: &Params) -> Result<Problem> {
        self.model.problem(params)
    }

    /// One line for the figures' headings and notes: the method, the step and the impact
    /// memory as set; the model is not named (the figures' own, Eq. 1 with the wall).
    pub fn describe(&self) -> String {
        let method = match self.spec.method {
            LyapunovMethod::TwoTrajectory => format!(
                "two trajectories with whole-memory renormalisation (d0 = {}, every {} steps)",
                num(self.spec.separation),
                self.spec.renormalise_every
            ),
            LyapunovMethod::Tangent => format!(
                "the tangent equation renormalised every {} steps",
                self.spec.renormalise_every
            ),
        };
        let step = match self.dt {
            Some(dt) => num(dt),
            None => format!(
                "the largest of {{{}}} not above τ/10",
                DT_LADDER[..5]
                    .iter()
                    .map(|&d| num(d))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        };
        format!(
            "LLE with frozen noise, {method}, predictor-corrector with Δt = {step}, {} impact \
             memory; finite-time exponent over a window of {} after a transient of {}; mean ± \
             standard error over {} noise realisations (seed {})",
            self.impact_memory.name(),
            num(self.spec.length),
            num(self.spec.transient),
            self.spec.paths,
            self.spec.seed
        )
    }
}

/// The regime of a curve: the attractor its start's noise-free path reaches
/// (`trirhythm::analysis::lyapunov::classify_start`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum StartKind {
    /// The noise-free path comes to rest on the wall.
    Rest,
    /// The noise-free path settles on a limit cycle (which one: [`Curve::attractor`]).
    #[serde(alias = "outer")]
    Cycle,
}

impl StartKind {
    /// Both, in drawing order.
    pub const BOTH: [StartKind; 2] = [StartKind::Rest, StartKind::Cycle];

    /// Short name (CSV, legends).
    pub fn name(self) -> &'static str {
        match self {
            StartKind::Rest => "rest",
            StartKind::Cycle => "cycle",
        }
    }

    /// In words, for verdicts.
    pub fn words(self) -> &'static str {
        match self {
            StartKind::Rest => {
                "in the rest regime (the start's noise-free path comes to rest on the wall)"
            }
            StartKind::Cycle => {
                "in the cycle regime (the start's noise-free path settles on a limit cycle)"
            }
        }
    }
}

/// One start of a curve: where it begins and the attractor its noise-free path reaches.
#[derive(Debug, Clone, PartialEq)]
pub struct RegimeStart {
    /// The regime.
    pub kind: StartKind,
    /// U(0) (U̇(0) = 0).
    pub u0: f64,
    /// The attractor in words: `rest`, `inner cycle (A = 1.23)`, ….
    pub attractor: String,
    /// The noise-free cycle's turning amplitude (NaN at rest).
    pub amplitude: f64,
}

/// One start per attractor of the noise-free system of `params` (D set to 0) with the model
/// and step of `sizes` ([`attractor_starts`]: the theory's stable amplitudes in `variant`, 1
/// and 0.01 tried), and a note for each start that settled on nothing within the run.
pub fn regime_starts(
    params: &Params,
    sizes: &Sizes,
    variant: Variant,
) -> Result<(Vec<RegimeStart>, Vec<String>)> {
    let method = &sizes.method(params.correlation_time);
    let problem = sizes.problem(&params.with("D", 0.0)?)?;
    let spec = AttractorSpec {
        variant,
        ..Default::default()
    };
    let mut starts = Vec::new();
    let mut notes = Vec::new();
    for s in attractor_starts(&problem, method, &spec)? {
        match s.attractor {
            Attractor::Rest => starts.push(RegimeStart {
                kind: StartKind::Rest,
                u0: s.u0,
                attractor: "rest".into(),
                amplitude: f64::NAN,
            }),
            Attractor::Cycle {
                amplitude, name, ..
            } => starts.push(RegimeStart {
                kind: StartKind::Cycle,
                u0: s.u0,
                attractor: format!("{} cycle (A = {})", name.name(), sig(amplitude, 4)),
                amplitude,
            }),
            Attractor::Unsettled { amplitude } => notes.push(format!(
                "{}: the noise-free path from U(0) = {} settled on nothing within t = {} (last turning amplitude {}): no curve",
                params.describe(),
                sig(s.u0, 4),
                num(spec.t_max),
                sig(amplitude, 4)
            )),
        }
    }
    Ok((starts, notes))
}

/// The amplitude of the outer (largest) stable limit cycle of the averaged theory for `params`
/// at D = 0, or `None` when the averaged system has no stable cycle.
pub fn outer_amplitude(params: &Params, variant: Variant) -> Result<Option<f64>> {
    let p = params.with("D", 0.0)?;
    let theory = Theory::new(&p, variant)?;
    Ok(theory
        .limit_cycles()
        .into_iter()
        .filter(|c| c.stable && c.amplitude.is_finite())
        .map(|c| c.amplitude)
        .fold(None, |m: Option<f64>, a| Some(m.map_or(a, |m| m.max(a)))))
}

/// The well in amplitude of a noise-free cycle of amplitude `amplitude`: between the averaged
/// theory's unstable cycles (D = 0) next below and above the theory's stable cycle nearest to
/// it (0 and ∞ where there is none); None when the theory has no stable cycle.
pub fn cycle_well(params: &Params, variant: Variant, amplitude: f64) -> Result<Option<(f64, f64)>> {
    let theory = Theory::new(&params.with("D", 0.0)?, variant)?;
    let cycles: Vec<_> = theory
        .limit_cycles()
        .into_iter()
        .filter(|c| c.amplitude.is_finite())
        .collect();
    let Some(stable) = cycles
        .iter()
        .filter(|c| c.stable)
        .map(|c| c.amplitude)
        .min_by(|a, b| (a - amplitude).abs().total_cmp(&(b - amplitude).abs()))
    else {
        return Ok(None);
    };
    let unstable = cycles.iter().filter(|c| !c.stable).map(|c| c.amplitude);
    let lo = unstable.clone().filter(|&a| a < stable).fold(0.0, f64::max);
    let hi = unstable
        .filter(|&a| a > stable)
        .fold(f64::INFINITY, f64::min);
    Ok(Some((lo, hi)))
}

/// The escape of a point's reference paths from its cycle's well ([`well_escape`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct EscapeAt {
    /// The point's noise intensity.
    pub d: f64,
    /// What the paths did.
    pub escape: WellEscape,
}

/// What a point of a curve holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Flag {
    /// A finite exponent with its standard error.
    #[default]
    Value,
    /// At least half the realisations' copies merged with their references: the median
    /// realisation synchronised, the mean is −∞ (no sign). A minority of merged realisations
    /// leaves a [`Flag::Value`]: the mean of the others, their number kept in
    /// [`Point::merged`].
    Merged,
    /// No value (no standard error with one realisation, or a non-finite result).
    Undefined,
}

impl Flag {
    /// The flag of an exponent `y ± se` (the mean of the realisations that did not merge) from
    /// `n` realisations of which `merged` merged: merged when at least half did (the rule of
    /// a point's call, `verdict::rules::regime`).
    pub fn of(merged: usize, n: usize, y: f64, se: f64) -> Flag {
        if merged > 0 && 2 * merged >= n {
            Flag::Merged
        } else if y.is_finite() && se.is_finite() {
            Flag::Value
        } else {
            Flag::Undefined
        }
    }

    /// The CSV cell.
    pub fn name(self) -> &'static str {
        match self {
            Flag::Value => "",
            Flag::Merged => "merged",
            Flag::Undefined => "undefined",
        }
    }
}

/// A point with its error bar (NaN y: nothing to draw there).
#[derive(Debug, Clone, Copy, Serialize, Deserialize)]
pub struct Point {
    /// Abscissa.
    pub x: f64,
    /// Ordinate (NaN or −∞ when undefined: see `flag`).
    #[serde(with = "trirhythm::non_finite")]
    pub y: f64,
    /// Lower end of the error bar (y − se).
    #[serde(with = "trirhythm::non_finite")]
    pub lo: f64,
    /// Upper end of the error bar (y + se).
    #[serde(with = "trirhythm::non_finite")]
    pub hi: f64,
    /// Standard error over realisations (NaN where none).
    #[serde(with = "trirhythm::non_finite", default = "nan")]
    pub se: f64,
    /// Realisations behind the value (the t test has n − 1 degrees of freedom).
    #[serde(default)]
    pub n: usize,
    /// What the point holds.
    #[serde(default)]
    pub flag: Flag,
    /// The sign decided with significance: in a curve with a [`CurveRegime`] the sign of its
    /// call (chaotic +, not chaotic or synchronised −, undecided n.s.), else Holm–Bonferroni
    /// over the panel and start.
    #[serde(default = "undefined_sign")]
    pub sign: PointSign,
    /// Realisations whose copy merged with its reference (exponent −∞).
    #[serde(default)]
    pub merged: usize,
    /// Mean exponent of the realisations that did not merge (equal to `y` when none merged).
    #[serde(default = "nan", with = "trirhythm::non_finite")]
    pub unmerged: f64,
    /// Its standard error.
    #[serde(default = "nan", with = "trirhythm::non_finite")]
    pub unmerged_se: f64,
}

impl Point {
    /// The point as the regime rules read it.
    pub fn regime_point(&self) -> RegimePoint {
        RegimePoint {
            d: self.x,
            mean: self.unmerged,
            se: self.unmerged_se,
            n: self.n,
            merged: self.merged,
        }
    }
}

fn nan() -> f64 {
    f64::NAN
}

fn undefined_sign() -> PointSign {
    PointSign::Undefined
}

/// One curve of a panel.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Curve {
    /// Legend text.
    pub label: String,
    /// The parameter's value of the curve.
    #[serde(default = "nan", with = "trirhythm::non_finite")]
    pub value: f64,
    /// Where its paths start.
    #[serde(default = "rest")]
    pub start: StartKind,
    /// U(0) (NaN: no outer stable cycle, no points).
    #[serde(default = "nan", with = "trirhythm::non_finite")]
    pub u0: f64,
    /// The step Δt (NaN for a curve that is not an LLE run).
    #[serde(default = "nan", with = "trirhythm::non_finite")]
    pub dt: f64,
    /// The attractor of the start's noise-free path in words (`rest`, `outer cycle (A = …)`).
    #[serde(default)]
    pub attractor: String,
    /// Its points.
    pub points: Vec<Point>,
    /// The regime rules' outcome over the points (None: data of an earlier version).
    #[serde(default)]
    pub regime: Option<CurveRegime>,
}

impl Curve {
    /// "`prefix` label (attractor, U(0), Δt): the regime decision in words", for the notes;
    /// None without a decision.
    pub fn regime_note(&self, prefix: &str) -> Option<String> {
        self.regime.as_ref().map(|r| {
            format!(
                "{prefix} {} ({}, U(0) = {}, Δt = {}): {}",
                self.label,
                self.attractor,
                sig(self.u0, 4),
                num(self.dt),
                r.words()
            )
        })
    }

    /// The regime rules applied now to the stored points, with the stored margin and
    /// phase-reduction coefficient (figure data keep the decision of the rules they were
    /// computed with; the verdicts read this one); None for data without a decision.
    pub fn redecided(&self) -> Option<CurveRegime> {
        let r = self.regime.as_ref()?;
        let prediction = (self.start == StartKind::Cycle).then(|| {
            (
                r.coefficient,
                r.coefficient_uncertainty,
                r.prediction_note.clone(),
            )
        });
        // the escapes are runs of their own, not a function of the points: kept
        let mut again = decide_regime(
            self.start,
            &self.points,
            prediction.as_ref(),
            1.0 / r.margin,
        );
        again.escape = r.escape.clone();
        Some(again)
    }
}

/// What the regime rules say about a curve (`verdict::rules::regime`).
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct CurveRegime {
    /// The margin δ = 1/W of the calls (W the window).
    pub margin: f64,
    /// Each point's call.
    pub calls: Vec<Call>,
    /// Where D_c lies.
    pub bracket: Bracket,
    /// The slope of the exponent over the curve's last decade of D (the strong-noise rule;
    /// None in data of an earlier version).
    #[serde(default)]
    pub strong: Option<StrongNoise>,
    /// The rest regime's pooled exponent and slope (rest curves only).
    pub rest: Option<RestRegime>,
    /// The phase-reduction coefficient c of λ ≈ −c·D on the cycle (cycle curves; None with
    /// the reason in `prediction_note`).
    #[serde(with = "trirhythm::non_finite")]
    pub coefficient: f64,
    /// Its numerical uncertainty.
    #[serde(with = "trirhythm::non_finite")]
    pub coefficient_uncertainty: f64,
    /// Why there is no coefficient, or how it was measured.
    pub prediction_note: String,
    /// Per point: the exponent equivalent to −c·D within δ (two one-sided tests), None
    /// where not tested.
    pub agrees: Vec<Option<bool>>,
    /// On a cycle with a located bracket: the escape of the reference paths from the cycle's
    /// well at the bracket's ends D1 and D2 (empty otherwise).
    #[serde(default)]
    pub escape: Vec<EscapeAt>,
}

impl CurveRegime {
    /// One line: the bracket, the rest regime's numbers or the prediction's agreement.
    pub fn words(&self) -> String {
        let mut out = self.bracket.words();
        if let Some(s) = self.strong.filter(|s| s.falling) {
            out.push_str(&format!(
                " (slope {} ± {} per decade over D = {} … {})",
                sig(s.slope, 2),
                sig(s.slope_se, 2),
                num(s.from),
                num(s.to)
            ));
        }
        if let Some(r) = &self.rest {
            out.push_str(&format!(
                "; at D ≤ 0.01: pooled exponent {} ± {}, slope {} ± {} per decade of D over {} decades{}",
                sig(r.pooled, 3),
                sig(r.pooled_se, 2),
                sig(r.slope, 2),
                sig(r.slope_se, 2),
                sig(r.decades, 2),
                if r.d_c_zero {
                    ": chaotic as D → 0, D_c = 0"
                } else {
                    ""
                }
            ));
        }
        if self.coefficient.is_finite() {
            let tested: Vec<bool> = self.agrees.iter().flatten().copied().collect();
            out.push_str(&format!(
                "; phase reduction λ ≈ −c·D, c = {} ± {}: equivalent within δ at {} of {} tested points",
                sig(self.coefficient, 4),
                sig(self.coefficient_uncertainty, 2),
                tested.iter().filter(|&&a| a).count(),
                tested.len()
            ));
        } else if !self.prediction_note.is_empty() {
            out.push_str(&format!("; {}", self.prediction_note));
        }
        if let Some(e) = self.escape_words() {
            out.push_str("; ");
            out.push_str(&e);
        }
        let merged = self
            .calls
            .iter()
            .filter(|&&c| c == Call::Synchronised)
            .count();
        if merged > 0 {
            out.push_str(&format!(
                "; synchronised (≥ half the realisations merged) at {merged} D"
            ));
        }
        out
    }

    /// The escape of the reference paths from the cycle's well at the bracket's ends, in
    /// words; None where it was not measured.
    pub fn escape_words(&self) -> Option<String> {
        let first = self.escape.first()?;
        let w = &first.escape;
        let at: Vec<String> = self
            .escape
            .iter()
            .map(|e| {
                format!(
                    "{} of {} at D = {}{}",
                    e.escape.escaped,
                    e.escape.paths,
                    num(e.d),
                    if e.escape.escaped > 0 {
                        format!(" (median first exit t = {})", sig(e.escape.median_time, 3))
                    } else {
                        String::new()
                    }
                )
            })
            .collect();
        let mut out = format!(
            "reference paths that left the cycle's well A ∈ ({}, {}) within t = {}: {}",
            sig(w.lo, 4),
            if w.hi.is_finite() {
                sig(w.hi, 4)
            } else {
                "∞".into()
            },
            num(w.run),
            at.join(", ")
        );
        if self.escape.iter().any(|e| e.escape.escaped > 0) {
            out.push_str(": the bracket depends on the window");
        }
        Some(out)
    }
}

/// The phase-reduction prediction of a cycle curve: c of λ ≈ −c·D from the phase response of
/// the noise-free cycle through `u0` (64 phases, 24 periods followed) with the model and step
/// of `sizes`, its uncertainty and a note (the reason where there is none: NaN).
pub fn phase_prediction(
    params: &Params,
    sizes: &Sizes,
    u0: f64,
    monitor: &dyn Monitor,
) -> Result<(f64, f64, String)> {
    monitor.check()?;
    let method = &sizes.method(params.correlation_time);
    let problem = sizes.problem(&params.with("D", 0.0)?)?;
    let spec = PhaseSpec {
        phases: 64,
        periods: 24,
        ..Default::default()
    };
    Ok(
        match phase_response(&problem, method, u0, &spec, &OnlyCancel(monitor)) {
            Ok(r) => match r.coefficient {
                Some(c) => (
                    c,
                    r.uncertainty,
                    format!(
                        "phase response by impulses at {} phases, linearity {}",
                        spec.phases,
                        sig(r.linearity, 2)
                    ),
                ),
                None => (
                    f64::NAN,
                    f64::NAN,
                    format!(
                        "no phase-reduction prediction: {}",
                        r.undefined.unwrap_or_default()
                    ),
                ),
            },
            Err(trirhythm::Error::Cancelled) => return Err(trirhythm::Error::Cancelled),
            Err(e) => (
                f64::NAN,
                f64::NAN,
                format!("no phase-reduction prediction: {e}"),
            ),
        },
    )
}

/// The regime rules over the points of a curve of regime `kind` for a window `window`
/// (δ = 1/window): the calls, the bracket of D_c, the rest regime's statistics or, with the
/// cycle's phase-reduction `prediction` (c, its uncertainty, a note; [`phase_prediction`]),
/// the equivalence of each point with −c·D.
pub fn decide_regime(
    kind: StartKind,
    points: &[Point],
    prediction: Option<&(f64, f64, String)>,
    window: f64,
) -> CurveRegime {
    let margin = 1.0 / window;
    let rp: Vec<RegimePoint> = points.iter().map(Point::regime_point).collect();
    let c = calls(&rp, margin);
    let ds: Vec<f64> = rp.iter().map(|p| p.d).collect();
    let strong = strong_noise(&rp, &c);
    let b = match bracket(&ds, &c) {
        Bracket::Above { d } if strong.is_some_and(|s| s.falling) => Bracket::Never { d },
        b => b,
    };
    let mut out = CurveRegime {
        margin,
        calls: c,
        bracket: b,
        strong,
        rest: None,
        coefficient: f64::NAN,
        coefficient_uncertainty: f64::NAN,
        prediction_note: String::new(),
        agrees: vec![None; rp.len()],
        escape: Vec::new(),
    };
    if kind == StartKind::Rest {
        out.rest = Some(rest_regime(&rp, margin));
    }
    if let Some((c, unc, note)) = prediction {
        out.coefficient = *c;
        out.coefficient_uncertainty = *unc;
        out.prediction_note = note.clone();
        if c.is_finite() {
            let k = rp.len().max(1) as f64;
            out.agrees = rp
                .iter()
                .map(|p| agrees_with_prediction(p, Some(*c), margin, ALPHA / k))
                .collect();
        }
    }
    out
}

/// The point's sign as its call says (chaotic +, not chaotic or synchronised −, undecided
/// n.s.).
pub fn sign_of_call(c: Call) -> PointSign {
    match c {
        Call::Chaotic => PointSign::Positive,
        Call::NotChaotic | Call::Synchronised => PointSign::Negative,
        Call::Undecided => PointSign::NotSignificant,
    }
}

fn rest() -> StartKind {
    StartKind::Rest
}

/// [`sign_of_call`] on every point of a curve with a regime.
pub fn mark_calls(c: &mut Curve) {
    if let Some(r) = &c.regime {
        for (q, &call) in c.points.iter_mut().zip(&r.calls) {
            q.sign = sign_of_call(call);
        }
    }
}

/// One panel.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Panel {
    /// Caption above the chart.
    pub caption: String,
    /// Key of the abscissa in the CSV.
    pub x_key: String,
    /// Axis descriptions.
    pub x_desc: String,
    /// Axis descriptions.
    pub y_desc: String,
    /// Key of the ordinate in the CSV.
    pub y_key: String,
    /// The curves.
    pub curves: Vec<Curve>,
    /// Short verdicts drawn inside the chart's top-left corner.
    pub verdicts: Vec<String>,
}

/// Points at finite abscissae whose brackets [lo, hi] are in order.
fn points_in_order(field: &str, points: &[Point]) -> crate::validate::Valid {
    for (k, p) in points.iter().enumerate() {
        if !p.x.is_finite() || p.lo > p.hi || p.y.is_nan() && p.n > 1 && p.lo.is_finite() {
            return crate::validate::invalid(
                format!("{field}[{k}]"),
                format!(
                    "x = {}, y = {} in [{}, {}]: x must be finite and the bracket ordered",
                    p.x, p.y, p.lo, p.hi
                ),
            );
        }
    }
    Ok(())
}

impl Panel {
    /// Every curve's value finite and its points at finite abscissae with ordered brackets
    /// ([`crate::validate`]).
    pub fn validate(&self, field: &str) -> crate::validate::Valid {
        for (j, c) in self.curves.iter().enumerate() {
            let f = format!("{field}.curves[{j}]");
            // u0 is NaN where the start does not exist (no outer cycle)
            crate::validate::finite(&format!("{f}.value"), &[c.value])?;
            if !(c.dt > 0.0 && c.dt.is_finite()) {
                return crate::validate::invalid(
                    format!("{f}.dt"),
                    format!("{} is not a step", c.dt),
                );
            }
            points_in_order(&format!("{f}.points"), &c.points)?;
        }
        Ok(())
    }

    /// The curves of one start with their points as the sign-change rule reads them (a curve
    /// without points, no outer cycle, is left out).
    pub fn lle_curves(&self, start: StartKind) -> Vec<LleCurve> {
        self.curves
            .iter()
            .filter(|c| c.start == start && !c.points.is_empty())
            .map(lle_curve)
            .collect()
    }

    /// The labels of the curves of `start` without an outer stable cycle.
    pub fn without_cycle(&self, start: StartKind) -> Vec<String> {
        self.curves
            .iter()
            .filter(|c| c.start == start && c.points.is_empty())
            .map(|c| c.label.clone())
            .collect()
    }
}

/// A curve's points as the sign-change and trend rules read them: the value (the mean of the
/// realisations that did not merge), its standard error and those realisations − 1 degrees
/// of freedom (no test where the flag is not a value).
pub fn lle_curve(c: &Curve) -> LleCurve {
    LleCurve {
        label: c.label.clone(),
        points: c
            .points
            .iter()
            .map(|q| LlePoint {
                d: q.x,
                lle: if q.flag == Flag::Value { q.y } else { f64::NAN },
                se: q.se,
                dof: Some(q.n.saturating_sub(q.merged + 1).max(1) as f64),
            })
            .collect(),
    }
}

/// Decide every point's sign over `curves` (Holm–Bonferroni over all their points) and store
/// it in the points.
pub fn mark_signs(curves: &mut [&mut Curve]) {
    let rule: Vec<LleCurve> = curves.iter().map(|c| lle_curve(c)).collect();
    for (c, signs) in curves.iter_mut().zip(significance(&rule)) {
        for (q, s) in c.points.iter_mut().zip(signs) {
            q.sign = s;
        }
    }
}

/// One LLE at parameters `p` from `u0`: a point at abscissa `x` (the mean of the realisations
/// that did not merge; merged, −∞, where at least half did: [`Flag::of`]), and a note when a
/// realisation merged.
pub fn lle_point(
    monitor: &dyn Monitor,
    p: &Params,
    u0: f64,
    x: f64,
    sizes: &Sizes,
    what: &str,
) -> Result<(Point, Option<String>)> {
    let problem = sizes.problem(p)?.with_start(u0, 0.0)?;
    let method = sizes.method(p.correlation_time);
    let r = largest_lyapunov(&problem, &method, &sizes.spec, &OnlyCancel(monitor))?;
    let mut note = None;
    if r.merged > 0 {
        let when: Vec<String> = r
            .per_path
            .iter()
            .filter_map(|q| {
                q.merged_at
                    .map(|t| format!("{} at t = {}", q.path, sig(t, 4)))
            })
            .collect();
        let n = r.per_path.len();
        note = Some(format!(
            "{what}: {}: {} of {} realisations merged (the copy became identical to its reference, both stuck at the wall on the same step with the memory restarted; path {}); the other {}: {}",
            if 2 * r.merged >= n {
                "LLE −∞ (at least half merged), not drawn"
            } else {
                "drawn: the mean of the realisations that did not merge"
            },
            r.merged,
            n,
            when.join(", path "),
            n - r.merged,
            if r.unmerged.value.is_finite() {
                format!("{} ± {}", sig(r.unmerged.value, 3), sig(r.unmerged.stderr, 2))
            } else {
                "none".into()
            }
        ));
    }
    Ok((point_of(x, &r), note))
}

/// The point at abscissa `x` of an estimate: the mean of the realisations that did not merge
/// (the mean of all when none merged); flagged merged (−∞, not drawn) when at least half
/// merged. The merged realisations' number and the others' mean are kept either way.
fn point_of(x: f64, r: &trirhythm::analysis::lyapunov::LyapunovResult) -> Point {
    let n = r.per_path.len();
    let flag = Flag::of(r.merged, n, r.unmerged.value, r.unmerged.stderr);
    let ok = flag == Flag::Value;
    let (y, se) = match flag {
        Flag::Merged => (f64::NEG_INFINITY, f64::NAN),
        _ => (r.unmerged.value, r.unmerged.stderr),
    };
    Point {
        x,
        y,
        lo: if ok { y - se } else { f64::NAN },
        hi: if ok { y + se } else { f64::NAN },
        se: if ok { se } else { f64::NAN },
        n,
        flag,
        sign: PointSign::Undefined,
        merged: r.merged,
        unmerged: r.unmerged.value,
        unmerged_se: r.unmerged.stderr,
    }
}

/// The extra noise intensities of a rest-regime curve at paper quality, below the figure's
/// grid: the rest regime's exponent must be flat over at least three decades down to 10⁻⁶
/// (`verdict::rules::regime`).
pub const REST_EXTRA_NOISES: [f64; 3] = [1e-6, 1e-5, 1e-4];

/// The noise intensities beyond a figure's grid that a cycle-regime curve is extended to at
/// paper quality when no point up to the grid's largest D is chaotic: the paper prints no D
/// range, so "D_c above the range" is pushed until chaos or this end.
pub const CYCLE_EXTRA_NOISES: [f64; 3] = [5.0, 12.0, 30.0];

/// The curves of one value of a panel's parameter: one per attractor of the noise-free system
/// ([`regime_starts`]), with the D grid `noises` (rest curves: [`REST_EXTRA_NOISES`] below it
/// unless `quick`).
pub struct PlannedCurve {
    /// The parameter's value.
    pub value: f64,
    /// The curve's parameters (D set per point).
    pub params: Params,
    /// Its start and attractor.
    pub start: RegimeStart,
    /// Its D grid, ascending.
    pub noises: Vec<f64>,
    /// The D it is extended to when not chaotic up to the grid's end ([`CYCLE_EXTRA_NOISES`]
    /// for cycle curves at paper quality).
    pub extension: Vec<f64>,
    /// The cycle's well in amplitude ([`cycle_well`]; None at rest or without a theory cycle).
    pub well: Option<(f64, f64)>,
}

impl PlannedCurve {
    /// The most points the curve may take (progress).
    pub fn most_points(&self) -> usize {
        self.noises.len() + self.extension.len()
    }
}

/// The noise intensities a planned curve runs at: `noises` on every curve, `rest_below` added
/// below them on rest-regime curves, and `extension` tried one at a time on cycle-regime curves
/// with no chaotic point ([`run_curve`]).
#[derive(Debug, Clone, PartialEq)]
pub struct NoiseGrid {
    /// Every curve's D, ascending.
    pub noises: Vec<f64>,
    /// Added below `noises` on rest curves, ascending.
    pub rest_below: Vec<f64>,
    /// The D a cycle curve is extended to, ascending.
    pub extension: Vec<f64>,
}

impl NoiseGrid {
    /// The figures' grid: `noises`, with [`REST_EXTRA_NOISES`] below on rest curves and
    /// [`CYCLE_EXTRA_NOISES`] as the extension of cycle curves unless `quick`.
    pub fn figure(noises: &[f64], quick: bool) -> NoiseGrid {
        NoiseGrid {
            noises: noises.to_vec(),
            rest_below: if quick {
                vec![]
            } else {
                REST_EXTRA_NOISES.to_vec()
            },
            extension: if quick {
                vec![]
            } else {
                CYCLE_EXTRA_NOISES.to_vec()
            },
        }
    }

    /// `noises` on every curve, nothing added.
    pub fn only(noises: &[f64]) -> NoiseGrid {
        NoiseGrid {
            noises: noises.to_vec(),
            rest_below: vec![],
            extension: vec![],
        }
    }
}

/// Plan the curves of `values` of `key` on `base`: classify the starts (noise-free runs) and
/// fix each curve's D grid; notes for starts that settled on nothing.
pub fn plan_curves(
    base: &Params,
    key: &str,
    values: &[f64],
    noises: &[f64],
    sizes: &Sizes,
    (variant, quick): (Variant, bool),
) -> Result<(Vec<PlannedCurve>, Vec<String>)> {
    let grid = NoiseGrid::figure(noises, quick);
    let mut planned = Vec::new();
    let mut notes = Vec::new();
    let plans = crate::each(values, |&v| {
        plan_value(&base.with(key, v)?, v, &grid, sizes, variant)
    })?;
    for (p, n) in plans {
        planned.extend(p);
        notes.extend(n);
    }
    Ok((planned, notes))
}

/// Plan the curves of the parameter set `p` (the swept parameter's `value`, NaN without one):
/// one per attractor of its noise-free system ([`regime_starts`]), each with its D from
/// `grid`; notes for starts that settled on nothing.
pub fn plan_value(
    p: &Params,
    value: f64,
    grid: &NoiseGrid,
    sizes: &Sizes,
    variant: Variant,
) -> Result<(Vec<PlannedCurve>, Vec<String>)> {
    let (starts, notes) = regime_starts(p, sizes, variant)?;
    let planned: Vec<PlannedCurve> = starts
        .into_iter()
        .map(|start| {
            let mut d: Vec<f64> = Vec::new();
            if start.kind == StartKind::Rest {
                d.extend(&grid.rest_below);
            }
            d.extend(&grid.noises);
            let extension = if start.kind == StartKind::Cycle {
                grid.extension.clone()
            } else {
                vec![]
            };
            let well = match start.kind {
                StartKind::Cycle => cycle_well(p, variant, start.amplitude)?,
                StartKind::Rest => None,
            };
            Ok(PlannedCurve {
                value,
                params: p.clone(),
                start,
                noises: d,
                extension,
                well,
            })
        })
        .collect::<Result<_>>()?;
    Ok((planned, notes))
}

/// The start of a point at noise `d` of a curve of regime `kind` whose start is `u0`: on a
/// cycle `u0`; in the rest regime min(`u0`, √D), the state scaled with the noise as the rest
/// regime's homogeneity scales it (`verdict::rules::regime`): a start far above the noise's
/// scale would spend the window decaying toward the wall, which the argument does not describe
/// (measured on Fig. 17(a)'s μ0 = 0.001: from U(0) = 1 the exponent at D = 10⁻⁶ was 0.0014 ±
/// 0.0009, from U(0) = 10⁻³ 0.0100 ± 0.0013, as at D = 10⁻⁴ from 10⁻², 0.0112 ± 0.0017).
pub fn rest_start(kind: StartKind, u0: f64, d: f64) -> f64 {
    match kind {
        StartKind::Cycle => u0,
        StartKind::Rest => u0.min(d.sqrt()),
    }
}

/// Compute one planned curve: its points, its regime decision, its points' signs from the
/// calls; `progress` counts the points done. `key` names the parameter the curve's value sets
/// (empty: none, the curve labelled by its attractor alone). The grid's points and the phase
/// prediction run side by side; the extension, one D at a time, waits for each decision.
pub fn run_curve(
    monitor: &dyn Monitor,
    what: &str,
    key: &str,
    c: &PlannedCurve,
    sizes: &Sizes,
    progress: &crate::Progress,
) -> Result<(Curve, Vec<String>)> {
    let u0 = c.start.u0;
    let run = |&d: &f64| -> Result<(Point, Vec<String>)> {
        monitor.check()?;
        let start = rest_start(c.start.kind, u0, d);
        let at = format!(
            "{what}, {}{} from U(0) = {}, D = {}",
            value_part(key, c.value),
            c.start.attractor,
            sig(start, 4),
            sig(d, 4)
        );
        let (q, note) = lle_point(monitor, &c.params.with("D", d)?, start, d, sizes, &at)?;
        progress.advance(monitor, 1)?;
        Ok((q, note.into_iter().collect()))
    };
    let predict = || match c.start.kind {
        StartKind::Cycle => phase_prediction(&c.params, sizes, u0, monitor).map(Some),
        StartKind::Rest => Ok(None),
    };
    let (grid, prediction) = trirhythm::profile::parallel(|stage| {
        rayon::join(
            || stage.task(|| crate::each(&c.noises, run)),
            || stage.task(predict),
        )
    });
    let (mut points, mut notes): (Vec<Point>, Vec<Vec<String>>) = grid?.into_iter().unzip();
    let prediction = prediction?;
    let method = sizes.method(c.params.correlation_time);
    let decide = |points: &[Point]| {
        decide_regime(c.start.kind, points, prediction.as_ref(), sizes.spec.length)
    };
    let mut regime = decide(&points);
    // no chaotic point up to the grid's end (regular or undecided there): extended, one D at a
    // time, until chaos
    let mut left = c.extension.iter();
    while !regime.calls.contains(&Call::Chaotic) {
        let Some(d) = left.next() else { break };
        let (q, note) = run(d)?;
        points.push(q);
        notes.push(note);
        regime = decide(&points);
    }
    progress.advance(monitor, left.count())?;
    // a located bracket on a cycle: did the reference paths leave the cycle's well at its ends?
    if let (Bracket::Located { lo, hi }, Some(well)) = (regime.bracket, c.well) {
        regime.escape = crate::each(&[lo, hi], |&d| {
            let problem = Problem::from_params(&c.params.with("D", d)?)?.with_start(u0, 0.0)?;
            let escape = well_escape(&problem, &method, &sizes.spec, well, &OnlyCancel(monitor))?;
            Ok(EscapeAt { d, escape })
        })?;
    }
    let notes: Vec<String> = notes.into_iter().flatten().collect();
    let name = c
        .start
        .attractor
        .split(" (")
        .next()
        .unwrap_or("")
        .to_string();
    let mut curve = Curve {
        label: format!("{}{name}", value_part(key, c.value)),
        value: c.value,
        start: c.start.kind,
        u0,
        dt: method.dt,
        attractor: c.start.attractor.clone(),
        points,
        regime: Some(regime),
    };
    mark_calls(&mut curve);
    Ok((curve, notes))
}

/// "`symbol(key)` = value, " for a curve's label and notes; empty without a key.
fn value_part(key: &str, value: f64) -> String {
    if key.is_empty() {
        String::new()
    } else {
        format!("{} = {}, ", symbol(key), num(value))
    }
}

/// Counts of a regime's calls and brackets over a panel's curves, for its verdict lines.
fn regime_counts(curves: &[Curve], start: StartKind) -> Option<String> {
    let of: Vec<&Curve> = curves.iter().filter(|c| c.start == start).collect();
    if of.is_empty() {
        return None;
    }
    let calls: Vec<Call> = of
        .iter()
        .filter_map(|c| c.regime.as_ref())
        .flat_map(|r| r.calls.iter().copied())
        .collect();
    let count = |k: Call| calls.iter().filter(|&&c| c == k).count();
    let located = of
        .iter()
        .filter(|c| {
            matches!(
                c.regime.as_ref().map(|r| r.bracket),
                Some(Bracket::Located { .. })
            )
        })
        .count();
    Some(format!(
        "{}: chaotic {}, not chaotic {}, synchronised {}, undecided {}; D_c bracketed {}/{}",
        start.name(),
        count(Call::Chaotic),
        count(Call::NotChaotic),
        count(Call::Synchronised),
        count(Call::Undecided),
        located,
        of.len()
    ))
}

/// A panel of LLE against D: one curve per value of `key` and attractor of its noise-free
/// system, the regime rules per curve, with its notes.
#[allow(clippy::too_many_arguments)]
pub fn lle_against_noise(
    monitor: &dyn Monitor,
    caption: &str,
    planned: &[PlannedCurve],
    key: &str,
    sizes: &Sizes,
    progress: &crate::Progress,
) -> Result<(Panel, Vec<String>)> {
    let mut curves = Vec::new();
    let mut notes = Vec::new();
    let run = crate::each(planned, |c| {
        run_curve(monitor, caption, key, c, sizes, progress)
    })?;
    for (curve, n) in run {
        notes.extend(n);
        notes.extend(curve.regime_note(&format!("{caption},")));
        curves.push(curve);
    }
    let mut verdicts: Vec<String> = StartKind::BOTH
        .iter()
        .filter_map(|&s| regime_counts(&curves, s))
        .collect();
    let dts: Vec<String> = {
        let mut d: Vec<f64> = curves.iter().map(|c| c.dt).collect();
        d.sort_by(f64::total_cmp);
        d.dedup();
        d.iter().map(|&x| num(x)).collect()
    };
    verdicts.push(format!(
        "filled: rest regime, open: cycle regime; Δt = {}",
        dts.join(", ")
    ));
    let panel = Panel {
        caption: caption.into(),
        x_key: "D".into(),
        x_desc: "noise intensity D (log scale)".into(),
        y_desc: "largest Lyapunov exponent".into(),
        y_key: "lle".into(),
        curves,
        verdicts,
    };
    Ok((panel, notes))
}

/// The noise intensities D of a curve of Figs 17 and 18 (the paper does not print them):
/// log-spaced from 0.001 to 2 (ten values; three at quick quality).
pub fn noises(quick: bool) -> Vec<f64> {
    if quick {
        vec![0.01, 0.3, 2.0]
    } else {
        log_spaced(0.001, 2.0, 10)
    }
}

/// `n` values log-spaced from `lo` to `hi`, both included, rounded to 3 significant digits.
pub fn log_spaced(lo: f64, hi: f64, n: usize) -> Vec<f64> {
    (0..n)
        .map(|k| {
            let t = k as f64 / (n - 1).max(1) as f64;
            // the library's platform-independent maths: the same noise levels everywhere
            let v = maths::exp(maths::ln(lo) + t * (maths::ln(hi) - maths::ln(lo)));
            sig(v, 3).parse().unwrap_or(v)
        })
        .collect()
}

/// One panel of an LLE-against-noise figure: a preset and the parameter its curves vary.
#[derive(Debug, Clone, Copy)]
pub struct NoisePanel {
    /// Caption, e.g. `(a) τ = 0.06`.
    pub caption: &'static str,
    /// The preset of the panel's base parameters.
    pub preset: &'static str,
    /// The parameter each curve sets.
    pub key: &'static str,
    /// Its values, one curve each.
    pub values: &'static [f64],
}

/// What distinguishes Fig. 17 from Fig. 18.
#[derive(Debug, Clone, Copy)]
pub struct LleNoiseFigure {
    /// The paper's figure number.
    pub number: u32,
    /// The figure's title (registry and table notes).
    pub title: &'static str,
    /// The caption's title.
    pub caption_title: &'static str,
    /// The two panels.
    pub panels: [NoisePanel; 2],
    /// The parameters the panels set (named in the caption, not listed with the shared ones).
    pub varying: &'static [&'static str],
    /// The values chosen where the paper prints none.
    pub choices: &'static str,
    /// The representative point of the Δt-convergence check: (panel index, the panel's
    /// parameter value, D), from the rest start.
    pub dt_check: (usize, f64, f64),
}

/// The step multiples of a Δt-convergence check: 4Δt, 2Δt, Δt (the rule's) and Δt/2.
pub const DT_CHECK_FACTORS: [f64; 4] = [4.0, 2.0, 1.0, 0.5];

/// The exponent at one point of a figure at several Δt (rest start, the figure's run sizes).
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct DtCheck {
    /// Which panel, parameter and D.
    pub what: String,
    /// The panel's caption letter.
    pub panel: String,
    /// Δt of the rule ([`dt_for`]) at this point.
    pub dt_rule: f64,
    /// One point per Δt (x = Δt), coarsest first.
    pub points: Vec<Point>,
}

impl DtCheck {
    /// Three lines: "Δt check at …:", then the exponents at the two coarser and at the two
    /// finer steps ("0.01: 0.078 ± 0.001; …", the rule's Δt starred).
    pub fn lines(&self) -> Vec<String> {
        let cell = |q: &Point| {
            format!(
                "Δt = {}{}: {}",
                num(q.x),
                if q.x == self.dt_rule { "*" } else { "" },
                if q.flag == Flag::Value {
                    format!("{} ± {}", sig(q.y, 3), sig(q.se, 2))
                } else {
                    q.flag.name().to_string()
                }
            )
        };
        let mut lines = vec![format!(
            "Δt check at {}, {} realisations (* = the rule's Δt):",
            self.what,
            self.points.first().map_or(0, |q| q.n)
        )];
        for pair in self.points.chunks(2) {
            lines.push(pair.iter().map(cell).collect::<Vec<_>>().join("; "));
        }
        lines
    }
}

/// Realisations of a Δt check at full quality (four times a curve's point: the differences
/// between steps are a few per cent of the exponent).
pub const DT_CHECK_PATHS: usize = 32;

/// The exponent of `figure` at its Δt-check point for each of [`DT_CHECK_FACTORS`].
pub fn dt_check(figure: &LleNoiseFigure, sizes: &Sizes, monitor: &dyn Monitor) -> Result<DtCheck> {
    let (k, v, d) = figure.dt_check;
    let panel = &figure.panels[k];
    let p = preset(panel.preset)?
        .params
        .with(panel.key, v)?
        .with("D", d)?;
    let dt_rule = dt_for(p.correlation_time);
    let letter: String = panel
        .caption
        .split(')')
        .next()
        .unwrap_or("")
        .trim_start_matches('(')
        .into();
    let what = format!(
        "({letter}) {} = {}, D = {}, U(0) = 1",
        symbol(panel.key),
        num(v),
        num(d)
    );
    let problem = sizes
        .problem(&p)?
        .with_start(Problem::DEFAULT_START.0, 0.0)?;
    let spec = LyapunovSpec {
        paths: if sizes.spec.paths > 2 {
            DT_CHECK_PATHS
        } else {
            sizes.spec.paths
        },
        ..sizes.spec.clone()
    };
    let points = crate::each(&DT_CHECK_FACTORS, |&f| {
        let dt = dt_rule * f;
        let method = PredictorCorrector {
            dt,
            ..sizes.method(p.correlation_time)
        };
        let r = largest_lyapunov(&problem, &method, &spec, &OnlyCancel(monitor))?;
        Ok(point_of(dt, &r))
    })?;
    Ok(DtCheck {
        what,
        panel: letter,
        dt_rule,
        points,
    })
}

/// The table of a Δt check: `dt,lle,se,n,flag,used` (suffix `_dt`).
pub fn dt_check_table(notes: &[String], check: &DtCheck) -> Table {
    let mut t = Table::new(notes, &["dt", "lle", "se", "n", "flag", "used"]).named("_dt");
    for q in &check.points {
        let ok = q.flag == Flag::Value;
        t.row([
            num(q.x),
            if ok { num(q.y) } else { String::new() },
            if ok { num(q.se) } else { String::new() },
            q.n.to_string(),
            q.flag.name().into(),
            (q.x == check.dt_rule).to_string(),
        ]);
    }
    t
}

/// The data of an LLE-against-noise figure (Figs 17 and 18).
#[derive(Serialize, Deserialize)]
pub struct LleAgainstNoise {
    /// What the figure shows, shared parameters, method.
    pub caption: Caption,
    /// Notes of the data table: method, choices, a verdict per curve, merged realisations.
    pub notes: Vec<String>,
    /// Panels (a) and (b).
    pub panels: Vec<Panel>,
    /// The exponent at one representative point at 4Δt, 2Δt, Δt and Δt/2.
    pub dt_check: DtCheck,
}

impl LleAgainstNoise {
    /// The figure's tables: the panels and the Δt check (`_dt`).
    /// The panels and the step check ([`crate::validate`]).
    pub fn validate(&self) -> crate::validate::Valid {
        for (i, p) in self.panels.iter().enumerate() {
            p.validate(&format!("panels[{i}]"))?;
        }
        points_in_order("dt_check.points", &self.dt_check.points)
    }

    pub fn tables(&self) -> Vec<Table> {
        vec![
            panels_table(&self.notes, &self.panels),
            dt_check_table(
                &[
                    format!("Δt convergence of the exponent at {}", self.dt_check.what),
                    "used: the step of the rule (the largest of the ladder not above τ/10)".into(),
                ],
                &self.dt_check,
            ),
        ]
    }
}

/// A caption without the formula-variant line (the Lyapunov figures use no averaged formula
/// but the outer start, stated with it).
pub fn lyapunov_caption(
    n: u32,
    title: &str,
    options: &FigureOptions,
    base: &Params,
    varying: &[&str],
    extra: Vec<String>,
) -> Caption {
    let mut c = caption(n, title, options, base, varying, extra);
    let v = variant_line(options.variant);
    c.lines.retain(|l| *l != v);
    c
}

/// The starts in one line, for captions.
pub fn starts_line(variant: Variant) -> String {
    format!(
        "one curve per attractor of the noise-free system: starts U(0) = the averaged theory's stable amplitudes (--variant {}), 1 and 0.01, each classified by its noise-free path and labelled by where it goes; filled markers: rest regime (the path comes to rest on the wall), open: cycle regime; dashed: the prediction, −c·D of the phase reduction on a cycle, the pooled D-independent exponent in the rest regime; calls per point against δ = 1/W (docs/verdicts.md, \"The Lyapunov claims by regime\")",
        variant.name()
    )
}

/// Compute the LLE-against-noise figure `figure`.
pub fn lle_against_noise_figure(
    figure: &LleNoiseFigure,
    options: &FigureOptions,
    monitor: &dyn Monitor,
) -> Result<LleAgainstNoise> {
    let sz = Sizes::of(options.quick);
    let d = noises(options.quick);
    let mut panels = Vec::new();
    let mut notes = vec![
        sz.describe(),
        starts_line(options.variant),
        figure.choices.to_string(),
        format!(
            "D: {} values log-spaced in [{}, {}]: {}",
            d.len(),
            num(d[0]),
            num(d[d.len() - 1]),
            d.iter().map(|&x| num(x)).collect::<Vec<_>>().join(", ")
        ),
        "error bars: ± one standard error over noise realisations; a point's call against the margin δ = 1/W (one-sided Student's t on the unmerged realisations, Bonferroni over the curve's points at 0.05): chaotic, not chaotic, synchronised (at least half the realisations merged) or undecided; rest-regime curves also at D = 1e-6, 1e-5, 1e-4; the exponents are finite-time exponents over the window stated (λ < 1: Mittag-Leffler tails, README \"Lyapunov exponents\")".into(),
    ];
    let planned_panels = crate::each(&figure.panels, |panel| {
        let base = preset(panel.preset)?.params;
        let (planned, n) = plan_curves(
            &base,
            panel.key,
            panel.values,
            &d,
            &sz,
            (options.variant, options.quick),
        )?;
        Ok((panel, base, planned, n))
    })?;
    let mut plans = Vec::new();
    for (panel, base, planned, n) in planned_panels {
        notes.extend(n);
        plans.push((panel, base, planned));
    }
    let total: usize = plans
        .iter()
        .flat_map(|(_, _, p)| p.iter().map(PlannedCurve::most_points))
        .sum();
    let progress = crate::Progress::new(0, total);
    // the panels' curves and the Δt check, side by side
    let (computed, check) = trirhythm::profile::parallel(|stage| {
        rayon::join(
            || {
                stage.task(|| {
                    crate::each(&plans, |(panel, _, planned)| {
                        lle_against_noise(
                            monitor,
                            panel.caption,
                            planned,
                            panel.key,
                            &sz,
                            &progress,
                        )
                    })
                })
            },
            || stage.task(|| dt_check(figure, &sz, monitor)),
        )
    });
    for (p, n) in computed? {
        panels.push(p);
        notes.extend(n);
    }
    let base = plans.first().expect("two panels").1.clone();
    let check = check?;
    let lines = check.lines();
    notes.push(format!("{} {}", lines[0], lines[1..].join("; ")));
    if let Some(p) = panels
        .iter_mut()
        .find(|p| p.caption.starts_with(&format!("({})", check.panel)))
    {
        p.verdicts.extend(check.lines());
    }
    let caption = lyapunov_caption(
        figure.number,
        figure.caption_title,
        options,
        &base,
        figure.varying,
        vec![sz.describe(), starts_line(options.variant)],
    );
    Ok(LleAgainstNoise {
        caption,
        notes: table_notes(figure.number, figure.title, options, &notes),
        panels,
        dt_check: check,
    })
}

/// The table of panels:
/// `panel,curve,start,u0,dt,x_key,x,y_key,y,y_lo,y_hi,se,n,merged,sign,flag`; every point is
/// a row (`y` the mean of the `n − merged` realisations that did not merge), one without a
/// value (at least half merged, undefined) with `y`, `y_lo`, `y_hi`, `se` empty and its
/// `flag` set (`merged`, `undefined`).
pub fn panels_table(notes: &[String], panels: &[Panel]) -> Table {
    let mut csv = Table::new(
        notes,
        &[
            "panel", "curve", "start", "u0", "dt", "x_key", "x", "y_key", "y", "y_lo", "y_hi",
            "se", "n", "merged", "sign", "flag",
        ],
    );
    let cell = |v: f64, flag: Flag| {
        if flag == Flag::Value {
            num(v)
        } else {
            String::new()
        }
    };
    for p in panels {
        for c in &p.curves {
            for q in &c.points {
                csv.row([
                    p.caption
                        .split(')')
                        .next()
                        .unwrap_or("")
                        .trim_start_matches('(')
                        .into(),
                    c.label.replace(',', ";"),
                    c.start.name().into(),
                    num(c.u0),
                    num(c.dt),
                    p.x_key.clone(),
                    num(q.x),
                    p.y_key.clone(),
                    cell(q.y, q.flag),
                    cell(q.lo, q.flag),
                    cell(q.hi, q.flag),
                    cell(q.se, q.flag),
                    q.n.to_string(),
                    q.merged.to_string(),
                    sign_name(q.sign).into(),
                    q.flag.name().into(),
                ]);
            }
        }
    }
    csv
}

/// The CSV cell of a point's sign.
pub fn sign_name(s: PointSign) -> &'static str {
    match s {
        PointSign::Positive => "+",
        PointSign::Negative => "-",
        PointSign::NotSignificant => "ns",
        PointSign::Undefined => "",
    }
}
