//! The critical noise D_c by regime: what `trirhythm critical-noise` and the Python
//! `critical_noise` compute, with the rules and the code of Figs 17–19.
//!
//! For the parameters given, or for each value of a swept parameter, the starts are classified
//! by the attractor their noise-free path reaches ([`crate::lle::plan_value`]: rest on the wall,
//! inner / middle / outer cycle), and one curve of the largest Lyapunov exponent against D is run
//! per attractor ([`crate::lle::run_curve`]) on the D given. Each curve carries the regime rules'
//! decision (`verdict::rules::regime`, docs/verdicts.md "The Lyapunov claims by regime"): every
//! point called chaotic / not chaotic / synchronised / undecided against δ = 1/W (one-sided t on
//! the unmerged realisations, Bonferroni over the curve's points, merged realisations kept); D_c
//! only as a bracket (largest regular D below the smallest chaotic D), one-sided (chaotic at
//! the smallest D: below it; regular up to the largest: above it) or none at all (never chaotic,
//! the exponent falling at strong noise), a located bracket on a cycle with the escape of the
//! reference paths from the cycle's well at its ends; on a rest curve the pooled
//! exponent and slope over D ≤ 1e-2 ("chaotic as D → 0: D_c = 0" when positive, flat and over
//! at least three decades); on a cycle the phase-reduction prediction λ ≈ −c·D and each point's
//! equivalence with it.
//!
//! Unlike the figures, nothing is added to the D given: no rest-regime points below them, no
//! extension of cycle curves ([`NoiseGrid::only`]); the rest rule needs points at D ≤ 1e-2
//! spanning three decades, which the D given must include.
//!
//! The document ([`CriticalNoise`]) is what the command writes as JSON (beside the parameters)
//! and what the Python package reads; [`crate::views::critical_table`] is its CSV. Tested by
//! the command line's `tests/lyapunov.rs` and the Python package's `tests/test_critical.py`.

use crate::lle::{plan_value, run_curve, Curve, NoiseGrid, PlannedCurve, Sizes, StartKind};
use crate::requests::Named;
use crate::verdict::rules::{Bracket, Call, RestRegime};
use crate::Monitor;
use serde::{Deserialize, Serialize};
use trirhythm::analysis::check_step;
use trirhythm::analysis::lyapunov::{LyapunovMethod, DT_RANGE};
use trirhythm::model::Params;
use trirhythm::theory::averaging::Variant;
use trirhythm::{Error, Result};

/// Most noise intensities of one request.
pub const MAX_NOISES: usize = 1000;
/// Most values of the swept parameter.
pub const MAX_VALUES: usize = 1000;
/// Most Lyapunov realisations per attractor: D values × parameter values × paths (each curve
/// runs them all; a parameter set has at most a few attractors).
pub const MAX_REALISATIONS: usize = 1_000_000;

/// What to compute: the parameters, the swept parameter's values, the D of every curve, the run
/// sizes, model and integrator, and the averaged theory's variant that names the cycles.
#[derive(Debug, Clone)]
pub struct CriticalRequest {
    /// The parameters (their D is not used: each point sets its own).
    pub base: Params,
    /// The swept parameter and its values (`None`: `base` alone).
    pub sweep: Option<(String, Vec<f64>)>,
    /// The noise intensities of every curve, ascending, each > 0.
    pub noises: Vec<f64>,
    /// Paths, window, transient, seed, method; model, Δt (or the figures' rule), impact memory.
    pub sizes: Sizes,
    /// The variant of the averaged theory whose stable amplitudes are tried as starts and name
    /// the cycles.
    pub variant: Variant,
}

/// Each swept value with its parameters (`None` without a sweep).
type ParameterSets = Vec<(Option<f64>, Params)>;

impl CriticalRequest {
    /// The parameter sets, checked: every value of the sweep valid, D not swept.
    pub fn parameter_sets(&self) -> Result<ParameterSets> {
        match &self.sweep {
            None => Ok(vec![(None, self.base.clone())]),
            Some((key, values)) => {
                if key == "D" {
                    return Err(Error::Unknown {
                        kind: "swept parameter",
                        name: key.clone(),
                        expected: "any parameter but D (the noise intensity is the abscissa of \
                                   every curve: give its values as the noises)"
                            .into(),
                    });
                }
                if values.is_empty() || values.len() > MAX_VALUES {
                    return Err(Error::invalid(
                        "sweep",
                        values.len() as f64,
                        format!("1 to {MAX_VALUES} values"),
                    ));
                }
                values
                    .iter()
                    .map(|&v| Ok((Some(v), self.base.with(key, v)?)))
                    .collect()
            }
        }
    }

    /// Check everything before any work: the noises (1 to [`MAX_NOISES`], finite, > 0,
    /// ascending, each a valid D), the sweep, the run sizes against each parameter set's step
    /// (whole numbers of steps, Δt in [1e-4, 0.1]), at most [`MAX_REALISATIONS`] realisations
    /// per attractor; then the step guard of each parameter set at the largest D (a step that
    /// cannot resolve the problem is refused): its warnings.
    pub fn validate(&self) -> Result<Vec<String>> {
        let n = self.noises.len();
        if n == 0 || n > MAX_NOISES {
            return Err(Error::invalid(
                "noises",
                n as f64,
                format!("1 to {MAX_NOISES} values"),
            ));
        }
        for (k, &d) in self.noises.iter().enumerate() {
            if !(d > 0.0 && d.is_finite()) {
                return Err(Error::invalid("noises", d, "(0, ∞), finite"));
            }
            if k > 0 && d <= self.noises[k - 1] {
                return Err(Error::invalid(
                    "noises",
                    d,
                    format!(
                        "above the value before it, {} (the noises ascending, no repeats)",
                        trirhythm::error::Exact(self.noises[k - 1])
                    ),
                ));
            }
            self.base.with("D", d)?;
        }
        let sets = self.parameter_sets()?;
        if let Some(dt) = self.sizes.dt {
            if !(DT_RANGE.0..=DT_RANGE.1).contains(&dt) {
                return Err(Error::invalid("dt", dt, "[1e-4, 0.1]"));
            }
        }
        let spec = &self.sizes.spec;
        spec.validate()?;
        let per_path = n.saturating_mul(sets.len());
        if per_path.saturating_mul(spec.paths) > MAX_REALISATIONS {
            return Err(Error::invalid(
                "paths",
                spec.paths as f64,
                format!(
                    "1 to {} here: D values × parameter values × paths at most {MAX_REALISATIONS} \
                     ({n} D values, {} parameter values)",
                    (MAX_REALISATIONS / per_path).max(1),
                    sets.len()
                ),
            ));
        }
        let top = self.noises[n - 1];
        let mut warnings = Vec::new();
        for (v, p) in &sets {
            let method = self.sizes.method(p.correlation_time);
            spec.sizes(&method)?;
            let problem = self.sizes.problem(&p.with("D", top)?)?;
            let at = match (&self.sweep, v) {
                (Some((key, _)), Some(v)) => {
                    format!("at {key} = {}: ", crate::notes::num(*v))
                }
                _ => String::new(),
            };
            for w in check_step(&problem, &method)?.require()?.warnings() {
                warnings.push(format!("{at}{w}"));
            }
        }
        Ok(warnings)
    }
}

/// `points` values of D log-spaced over [`lo`, `hi`], ends included, rounded to 3 significant
/// digits (as the figures' grids, [`crate::lle::log_spaced`]): 0 < lo < hi finite, `points` 2
/// to [`MAX_NOISES`], the rounded values distinct. Errors name `d_range` or `points`.
pub fn log_noises(lo: f64, hi: f64, points: usize) -> Result<Vec<f64>> {
    if !(lo > 0.0 && lo.is_finite()) {
        return Err(Error::invalid(
            "d_range",
            lo,
            "a low end in (0, ∞), finite (the values are log-spaced)",
        ));
    }
    if !(hi > lo && hi.is_finite()) {
        return Err(Error::invalid(
            "d_range",
            hi,
            format!(
                "a high end in ({}, ∞), finite (above the low end)",
                trirhythm::error::Exact(lo)
            ),
        ));
    }
    if !(2..=MAX_NOISES).contains(&points) {
        return Err(Error::invalid(
            "points",
            points as f64,
            format!("2 to {MAX_NOISES}"),
        ));
    }
    let d = crate::lle::log_spaced(lo, hi, points);
    if d.windows(2).any(|w| w[1] <= w[0]) {
        return Err(Error::invalid(
            "points",
            points as f64,
            format!(
                "fewer here: {points} values log-spaced in [{}, {}] repeat at 3 significant \
                 digits (use fewer points or a wider range)",
                trirhythm::error::Exact(lo),
                trirhythm::error::Exact(hi)
            ),
        ));
    }
    Ok(d)
}

/// How the curves are made, in a line (the command's header, the Python docs).
pub fn starts_line(variant: Variant) -> String {
    format!(
        "curves: starts U(0) = the averaged theory's stable amplitudes (variant {}), 1 and 0.01 \
         (U̇(0) = 0), each followed without noise until it settles; one curve per attractor \
         reached, rest (the path comes to rest on the wall) or a cycle (inner / middle / outer: \
         the theory's stable cycle it matches); a rest curve's point at D starts at \
         min(U(0), √D); every point of every curve runs with the same seed",
        variant.name()
    )
}

/// A curve's D_c: `kind` `located` (D_c in (lo, hi)), `below` (chaotic from the smallest D:
/// D_c < hi), `above` (regular up to the largest D: D_c > lo) or `undecided` (no bracket);
/// `None` where the side is open.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct DcBracket {
    /// `located`, `below`, `above` or `undecided`.
    pub kind: BracketKind,
    /// The largest regular D below D_c.
    pub lo: Option<f64>,
    /// The smallest chaotic D.
    pub hi: Option<f64>,
}

/// What a bracket says of D_c.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum BracketKind {
    /// D_c in (lo, hi).
    Located,
    /// Chaotic from the smallest D: D_c below it.
    Below,
    /// Not chaotic up to the largest D: D_c above it.
    Above,
    /// Never chaotic, the exponent falling with D over the last decade: no D_c at all.
    Never,
    /// Undecided points between: no bracket.
    Undecided,
}

impl BracketKind {
    /// The name in CSV and JSON.
    pub fn name(self) -> &'static str {
        match self {
            BracketKind::Located => "located",
            BracketKind::Below => "below",
            BracketKind::Above => "above",
            BracketKind::Never => "never",
            BracketKind::Undecided => "undecided",
        }
    }
}

impl From<Bracket> for DcBracket {
    fn from(b: Bracket) -> Self {
        let (kind, lo, hi) = match b {
            Bracket::Located { lo, hi } => (BracketKind::Located, Some(lo), Some(hi)),
            Bracket::Below { d } => (BracketKind::Below, None, Some(d)),
            Bracket::Above { d } => (BracketKind::Above, Some(d), None),
            Bracket::Never { d } => (BracketKind::Never, Some(d), None),
            Bracket::Undecided => (BracketKind::Undecided, None, None),
        };
        DcBracket { kind, lo, hi }
    }
}

/// The name of a call in CSV and JSON: `chaotic`, `not-chaotic`, `synchronised`, `undecided`.
pub fn call_name(c: Call) -> &'static str {
    match c {
        Call::Chaotic => "chaotic",
        Call::NotChaotic => "not-chaotic",
        Call::Synchronised => "synchronised",
        Call::Undecided => "undecided",
    }
}

/// One point of a curve as the rules read it, with its call.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct RegimeCall {
    /// Noise intensity D.
    pub d: f64,
    /// The mean exponent of the realisations that did not merge (`"NaN"` when none did not).
    #[serde(with = "trirhythm::non_finite")]
    pub lle: f64,
    /// Its standard error (`"NaN"` with fewer than two).
    #[serde(with = "trirhythm::non_finite")]
    pub se: f64,
    /// Realisations.
    pub n: usize,
    /// Realisations whose copy merged with its reference (exponent −∞).
    pub merged: usize,
    /// The call against δ = 1/W.
    pub call: Call,
    /// On a cycle with a coefficient: the exponent equivalent to −c·D within δ (two one-sided
    /// tests); `None` where not tested (merged realisations, no standard error, no c, rest).
    pub agrees: Option<bool>,
}

/// One curve: the attractor of its start, its points and the rules' decision.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RegimeCurve {
    /// The attractor in words: `rest`, `inner cycle (A = 1.23)`, ….
    pub attractor: String,
    /// `rest` or `cycle`.
    pub regime: StartKind,
    /// U(0) of the start (U̇(0) = 0); a rest curve's point at D starts at min(U(0), √D).
    pub u0: f64,
    /// The step Δt.
    pub dt: f64,
    /// Its points, D ascending.
    pub points: Vec<RegimeCall>,
    /// Where D_c lies.
    pub bracket: DcBracket,
    /// The rest regime's pooled exponent and slope over D ≤ 1e-2 (rest curves; `None` on a
    /// cycle).
    pub rest: Option<RestRegime>,
    /// The phase-reduction coefficient c of λ ≈ −c·D (cycle curves; `None` on rest curves and
    /// where undefined, the reason in `prediction_note`).
    pub coefficient: Option<f64>,
    /// Its numerical uncertainty.
    pub coefficient_uncertainty: Option<f64>,
    /// How c was measured, or why there is none.
    pub prediction_note: String,
    /// On a cycle with a located bracket: the escape of the reference paths from the cycle's
    /// well at D_c_lo and D_c_hi (empty otherwise).
    pub escape: Vec<crate::lle::EscapeAt>,
    /// The decision in words.
    pub decision: String,
}

impl RegimeCurve {
    /// The view of a curve computed by [`run_curve`] (which always carries a decision).
    pub fn of(c: &Curve) -> RegimeCurve {
        let r = c.regime.as_ref().expect("run_curve decides every curve");
        let finite = |x: f64| x.is_finite().then_some(x);
        let points = c
            .points
            .iter()
            .zip(&r.calls)
            .zip(&r.agrees)
            .map(|((q, &call), &agrees)| {
                let p = q.regime_point();
                RegimeCall {
                    d: p.d,
                    lle: p.mean,
                    se: p.se,
                    n: p.n,
                    merged: p.merged,
                    call,
                    agrees,
                }
            })
            .collect();
        RegimeCurve {
            attractor: c.attractor.clone(),
            regime: c.start,
            u0: c.u0,
            dt: c.dt,
            points,
            bracket: r.bracket.into(),
            rest: r.rest,
            coefficient: finite(r.coefficient),
            coefficient_uncertainty: finite(r.coefficient).and(finite(r.coefficient_uncertainty)),
            prediction_note: r.prediction_note.clone(),
            escape: r.escape.clone(),
            decision: r.words(),
        }
    }
}

/// The curves of one parameter set.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ValueCurves {
    /// The swept parameter's value (`None` without a sweep).
    pub value: Option<f64>,
    /// One curve per attractor of the noise-free system: rest first, then the cycles by
    /// amplitude.
    pub curves: Vec<RegimeCurve>,
}

/// The result: the run's settings, the notes and, per parameter set, the curves by regime.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CriticalNoise {
    /// The swept parameter (`None`: the parameters alone).
    pub sweep: Option<String>,
    /// The noise intensities of every curve.
    pub noises: Vec<f64>,
    /// The window W of the finite-time exponents.
    pub window: f64,
    /// The transient before it.
    pub transient: f64,
    /// Noise realisations per point (path i is noise stream i of the seed at every point).
    pub paths: usize,
    /// The seed.
    pub seed: u64,
    /// How the perturbation is followed.
    pub method: LyapunovMethod,
    /// Steps between renormalisations.
    pub renormalise_every: u64,
    /// Separation d₀ of the two trajectories.
    pub separation: f64,
    /// The step Δt given (`None`: the figures' rule, the largest of 0.01, 0.005, 0.0025, 0.002,
    /// 0.001, … not above τ/10; each curve's `dt` is the one used).
    pub dt: Option<f64>,
    /// What the memory does at an impact.
    pub impact_memory: String,
    /// The equation.
    pub system: String,
    /// The wall.
    pub barrier: String,
    /// How the fractional memory is kept.
    pub memory: String,
    /// Its tolerance (`None`: the library's default of each curve's step,
    /// [`trirhythm::engine::step_tolerance`]).
    pub tolerance: Option<f64>,
    /// The averaged theory's variant that gives the starts and names the cycles.
    pub variant: String,
    /// The margin δ = 1/W of the calls.
    pub margin: f64,
    /// The step guard's warnings.
    pub step_warnings: Vec<String>,
    /// Starts that settled on nothing, realisations that merged.
    pub notes: Vec<String>,
    /// Per parameter set, its curves.
    pub results: Vec<ValueCurves>,
}

/// Compute `request` (checked first, [`CriticalRequest::validate`]): the starts of every
/// parameter set classified, then each curve run point by point. `monitor` hears the points
/// done over the most there can be and may stop the run between points.
pub fn critical_noise(request: &CriticalRequest, monitor: &dyn Monitor) -> Result<CriticalNoise> {
    let step_warnings = request.validate()?;
    let sets = request.parameter_sets()?;
    let grid = NoiseGrid::only(&request.noises);
    let sizes = &request.sizes;
    let mut notes = Vec::new();
    let mut plans: Vec<(Option<f64>, Vec<PlannedCurve>)> = Vec::new();
    let planned_sets = crate::each(&sets, |(v, p)| {
        monitor.check()?;
        plan_value(p, v.unwrap_or(f64::NAN), &grid, sizes, request.variant)
    })?;
    for ((v, _), (planned, n)) in sets.iter().zip(planned_sets) {
        notes.extend(n);
        plans.push((*v, planned));
    }
    let total: usize = plans
        .iter()
        .flat_map(|(_, p)| p.iter().map(PlannedCurve::most_points))
        .sum();
    let key = request.sweep.as_ref().map_or("", |(k, _)| k.as_str());
    let progress = crate::Progress::new(0, total);
    // every curve of every value side by side
    let jobs: Vec<&PlannedCurve> = plans.iter().flat_map(|(_, p)| p).collect();
    let mut computed = crate::each(&jobs, |c| {
        run_curve(monitor, "critical-noise", key, c, sizes, &progress)
    })?
    .into_iter();
    let mut results = Vec::new();
    for (value, planned) in &plans {
        let mut curves = Vec::new();
        for (curve, n) in computed.by_ref().take(planned.len()) {
            notes.extend(n);
            curves.push(RegimeCurve::of(&curve));
        }
        results.push(ValueCurves {
            value: *value,
            curves,
        });
    }
    monitor.progress(total as u64, total as u64);
    let model = &sizes.model;
    Ok(CriticalNoise {
        sweep: request.sweep.as_ref().map(|(k, _)| k.clone()),
        noises: request.noises.clone(),
        window: sizes.spec.length,
        transient: sizes.spec.transient,
        paths: sizes.spec.paths,
        seed: sizes.spec.seed,
        method: sizes.spec.method,
        renormalise_every: sizes.spec.renormalise_every,
        separation: sizes.spec.separation,
        dt: sizes.dt,
        impact_memory: sizes.impact_memory.name().into(),
        system: model.system.name().into(),
        barrier: model.barrier.name().into(),
        memory: model.memory.name().into(),
        tolerance: model.tolerance,
        variant: request.variant.name().into(),
        margin: 1.0 / sizes.spec.length,
        step_warnings,
        notes,
        results,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use trirhythm::analysis::lyapunov::LyapunovSpec;
    use trirhythm::model::preset;

    fn request(noises: &[f64]) -> CriticalRequest {
        CriticalRequest {
            base: preset("fig17a").unwrap().params,
            sweep: None,
            noises: noises.to_vec(),
            sizes: Sizes::of_spec(LyapunovSpec {
                paths: 2,
                transient: 10.0,
                length: 20.0,
                ..Default::default()
            }),
            variant: Variant::Paper,
        }
    }

    #[test]
    fn bad_noises_and_sizes_are_refused_by_name() {
        let named = |r: &CriticalRequest, name: &str| {
            let e = r.validate().unwrap_err().to_string();
            assert!(e.contains(&format!("invalid parameter {name} =")), "{e}");
        };
        named(&request(&[]), "noises");
        named(&request(&[0.0, 0.1]), "noises");
        named(&request(&[0.1, 0.1]), "noises");
        named(&request(&[0.2, 0.1]), "noises");
        named(&request(&[f64::NAN]), "noises");
        let mut r = request(&[0.1]);
        r.sizes.dt = Some(0.5);
        named(&r, "dt");
        let mut r = request(&[0.1, 0.2]);
        r.sweep = Some(("mu0".into(), vec![0.01; 1000]));
        r.sizes.spec.paths = 600;
        named(&r, "paths");
        let mut r = request(&[0.1]);
        r.sweep = Some(("D".into(), vec![0.1]));
        assert!(r
            .validate()
            .unwrap_err()
            .to_string()
            .contains("any parameter but D"));
        let mut r = request(&[0.1]);
        r.sweep = Some(("lambda".into(), vec![2.0]));
        assert!(r.validate().unwrap_err().to_string().contains("lambda = 2"));
        assert!(request(&[1e-3, 0.1]).validate().is_ok());
    }

    #[test]
    fn log_spaced_noises_are_the_figures_grid_or_refused_by_name() {
        // Fig. 19's grid
        assert_eq!(
            log_noises(0.002, 2.0, 9).unwrap(),
            crate::lle::log_spaced(0.002, 2.0, 9)
        );
        assert_eq!(log_noises(0.01, 1.0, 3).unwrap(), vec![0.01, 0.1, 1.0]);
        let named = |r: Result<Vec<f64>>, what: &str| {
            let e = r.unwrap_err().to_string();
            assert!(e.starts_with(what), "{e}");
        };
        named(log_noises(0.0, 1.0, 3), "invalid parameter d_range = 0: ");
        named(log_noises(1.0, 1.0, 3), "invalid parameter d_range = 1: ");
        named(
            log_noises(0.1, f64::INFINITY, 3),
            "invalid parameter d_range = inf",
        );
        named(log_noises(0.1, 1.0, 1), "invalid parameter points = 1: ");
        named(
            log_noises(1.0, 1.001, 100),
            "invalid parameter points = 100: ",
        );
    }

    #[test]
    fn brackets_say_which_side_is_open() {
        let b: DcBracket = Bracket::Above { d: 2.0 }.into();
        assert_eq!((b.kind, b.lo, b.hi), (BracketKind::Above, Some(2.0), None));
        let b: DcBracket = Bracket::Below { d: 0.01 }.into();
        assert_eq!((b.kind, b.lo, b.hi), (BracketKind::Below, None, Some(0.01)));
        let text = serde_json::to_string(&DcBracket::from(Bracket::Undecided)).unwrap();
        assert_eq!(text, r#"{"kind":"undecided","lo":null,"hi":null}"#);
    }
}
