//! The problem and the method of a simulation: which equation ([`Problem`]: the
//! [`Oscillator`] — the paper family's parameters and, optionally, the General kernel's terms
//! ([`GeneralTerms`]: Duffing, Rayleigh, harmonic forcing, multiplicative noise, fractional
//! terms, walls other than the paper's; with [`System::Fractional`]) —, the [`System`], the [`Barrier`], the start and the blow-up bound), how it is
//! discretised ([`PredictorCorrector`], [`Memory`], [`ImpactMemory`]) and what one trajectory
//! records ([`Options`]). Every driver — [`super::simulate`], the ensembles, the Lyapunov
//! exponents, the oscillation search — takes the same [`Problem`]; its spec holds only what is
//! its own. Results are in [`super::drivers`].

use super::memory::{Memory, DEFAULT_WINDOW};
use super::noise::Noise;
use crate::error::{Error, Exact, Result};
use crate::model::{Equivalents, GeneralTerms, Model, Params};

/// What the memory does at an impact.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ImpactMemory {
    /// The lower terminal stays at t = 0; each jump is a constant added to V's Volterra form.
    #[default]
    Continuous,
    /// The memory restarts at each impact (and at each sticking step).
    Restart,
}

/// Whether the wall at U = 0 is present.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Barrier {
    /// U ≥ 0 with the impact law U̇₊ = −rU̇₋.
    #[default]
    On,
    /// The same equation on the whole line (the plain fractional multirhythmic oscillator).
    Off,
}

/// Which equation is integrated.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum System {
    /// Eq. (1): the fractional system itself.
    #[default]
    Fractional,
    /// Eq. (5): the harmonic-balance integer-order equivalent (λ = 1 driver).
    Equivalent,
    /// Eq. (9): Eq. (5) after Zhuravlev's transformation, Z on the whole line, Ż₊ = rŻ₋ at Z = 0.
    Zhuravlev,
}

/// The method: step, memory, impact convention.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PredictorCorrector {
    /// Step Δt > 0.
    pub dt: f64,
    /// How the history is kept.
    pub memory: Memory,
    /// What the memory does at impacts.
    pub impact_memory: ImpactMemory,
    /// Steps of exact weights before the exponential modes take over (≥ 2).
    pub window: usize,
}

/// Largest step Δt of a [`PredictorCorrector`]: larger steps are refused as a slip, not taken.
pub const MAX_DT: f64 = 1e3;
/// Most steps of the exact local window of a [`PredictorCorrector`] (the window's work and
/// memory grow with it; the default is [`DEFAULT_WINDOW`]).
pub const MAX_WINDOW: usize = 4096;

impl PredictorCorrector {
    /// Check the method: Δt in (0, [`MAX_DT`]], the memory's tolerance ([`Memory::validate`]),
    /// the window in [2, [`MAX_WINDOW`]] steps. Every driver calls it before any work.
    pub fn validate(&self) -> Result<()> {
        if !(self.dt > 0.0 && self.dt <= MAX_DT) {
            return Err(Error::invalid("dt", self.dt, "(0, 1e3]"));
        }
        self.memory.validate()?;
        if !(2..=MAX_WINDOW).contains(&self.window) {
            return Err(Error::invalid(
                "window",
                self.window as f64,
                format!("2 to {MAX_WINDOW} steps"),
            ));
        }
        Ok(())
    }
}

impl Default for PredictorCorrector {
    fn default() -> Self {
        PredictorCorrector {
            dt: 0.01,
            memory: Memory::default(),
            impact_memory: ImpactMemory::default(),
            window: DEFAULT_WINDOW,
        }
    }
}

/// What one trajectory records beyond the problem: span, noise stream, output.
#[derive(Debug, Clone, PartialEq)]
pub struct Options {
    /// End time T (a whole number of steps of Δt).
    pub t_end: f64,
    /// Seed of the noise streams.
    pub seed: u64,
    /// Which stream of the seed drives the path (and which of the problem's starts it takes).
    pub path: u64,
    /// Keep every k-th node in the trajectory (k ≥ 1).
    pub record_every: usize,
    /// Keep the list of impacts (time, V₋, V₊).
    pub record_impacts: bool,
    /// The summary amplitude is averaged over this many periods 2π/ω1 before T, in
    /// [0, [`MAX_AMPLITUDE_PERIODS`]] (0: the last node only).
    pub amplitude_periods: f64,
}

/// Most periods [`Options::amplitude_periods`] of the summary amplitude's average.
pub const MAX_AMPLITUDE_PERIODS: f64 = 1e6;

impl Default for Options {
    fn default() -> Self {
        Options {
            t_end: 100.0,
            seed: 0,
            path: 0,
            record_every: 1,
            record_impacts: false,
            amplitude_periods: 5.0,
        }
    }
}

/// The problem: Eq. (1) for a parameter set, with its equivalents (Eq. 5).
#[derive(Debug, Clone, PartialEq)]
pub struct Oscillator {
    params: Params,
    equivalents: Equivalents,
    noise: Noise,
    /// The terms beyond the paper's family (Duffing, Rayleigh, forcing): the General kernel.
    general: Option<GeneralTerms>,
}

impl Oscillator {
    /// Validate the parameters and precompute Eq. (5)'s coefficients.
    pub fn new(params: &Params) -> Result<Self> {
        params.validate()?;
        Ok(Oscillator {
            params: params.clone(),
            equivalents: Equivalents::new(params),
            noise: Noise::from_params(params),
            general: None,
        })
    }

    /// The same oscillator with the General kernel's terms added (Duffing k3U³ + k5U⁵,
    /// Rayleigh Σ d_k U̇^{2k}, F cos(Ωt + φ), K_j·D^{α_j}U, U·η_m, the model's walls); `None`
    /// or empty terms: the paper's equation. The walls: at most two, the lower keeping U above
    /// it, the upper below, δ1 < δ2 (they need [`Barrier::Off`]: they replace the paper's
    /// wall). Validated: |k3|, |k5| ≤ 1e6, at most 20 Rayleigh coefficients each |d_k| ≤ 1e6,
    /// the forcing's F ∈ [0, 1e6], Ω ∈ (0, 1e3], |φ| ≤ 1e6, at most two fractional terms with
    /// K ∈ [0, 1e3], α ∈ (0, 1], the multiplicative noise's D and τ, and a correlation
    /// c ∈ [−1, 1] between noises of one correlation time (the model file's ranges; c acts only
    /// where the additive noise is present).
    pub fn with_terms(self, terms: Option<GeneralTerms>) -> Result<Self> {
        let general = terms.filter(|t| !t.is_empty());
        if let Some(t) = &general {
            for (name, v) in [
                ("restoring.cubic", t.cubic),
                ("restoring.quintic", t.quintic),
            ] {
                if v.is_nan() || v.abs() > 1e6 {
                    return Err(Error::invalid(name, v, "[-1e6, 1e6]"));
                }
            }
            if t.rayleigh.len() > 20 {
                return Err(Error::invalid(
                    "damping.rayleigh",
                    t.rayleigh.len() as f64,
                    "at most 20 coefficients (U̇² … U̇⁴⁰)",
                ));
            }
            for (k, &d) in t.rayleigh.iter().enumerate() {
                if d.is_nan() || d.abs() > 1e6 {
                    return Err(Error::invalid(
                        format!("damping.rayleigh.{k}").as_str(),
                        d,
                        "[-1e6, 1e6]",
                    ));
                }
            }
            if let Some(f) = &t.forcing {
                f.validate()?;
            }
            check_walls(&t.walls)?;
            if t.fractional.len() > 2 {
                return Err(Error::invalid(
                    "fractional",
                    t.fractional.len() as f64,
                    "at most 2 terms",
                ));
            }
            for (j, f) in t.fractional.iter().enumerate() {
                f.validate(j)?;
            }
            if let Some(m) = &t.multiplicative {
                crate::model::Noises {
                    additive: None,
                    multiplicative: Some(*m),
                    correlation: 0.0,
                }
                .validate()?;
            }
            if !(-1.0..=1.0).contains(&t.correlation) {
                return Err(Error::invalid(
                    "noise.correlation",
                    t.correlation,
                    "[-1, 1]",
                ));
            }
            // c correlates η_m with η_a when both are present (without η_a, e.g. a noise-free
            // probe at D = 0, it has nothing to act on); they need one correlation time
            if t.correlation != 0.0 {
                let differ = t.multiplicative.is_some_and(|m| match self.noise {
                    Noise::White { .. } => m.correlation_time != 0.0,
                    Noise::Colored {
                        correlation_time, ..
                    } => m.correlation_time != correlation_time,
                    Noise::None => false,
                });
                if differ {
                    return Err(Error::invalid(
                        "noise.correlation",
                        t.correlation,
                        "0 unless noise.additive and noise.multiplicative have one \
                         correlation_time",
                    ));
                }
            }
        }
        Ok(Oscillator { general, ..self })
    }

    /// The General kernel's terms, None for the paper's equation.
    pub fn terms(&self) -> Option<&GeneralTerms> {
        self.general.as_ref()
    }

    /// The parameters.
    pub fn params(&self) -> &Params {
        &self.params
    }

    /// Eq. (5)'s coefficients.
    pub fn equivalents(&self) -> Equivalents {
        self.equivalents
    }

    /// The forcing.
    pub fn noise(&self) -> Noise {
        self.noise
    }
}

/// The General kernel's walls: at most two, each valid, two ordered (the lower keeping U
/// above it, the upper below it, δ1 < δ2), as [`Model::validate`] checks them.
fn check_walls(walls: &[crate::model::Wall]) -> Result<()> {
    use crate::model::Keep;
    if walls.len() > 2 {
        return Err(Error::invalid(
            "wall",
            walls.len() as f64,
            "at most 2 walls",
        ));
    }
    for (i, w) in walls.iter().enumerate() {
        w.validate(i)?;
    }
    if let [lower, upper] = walls {
        if lower.keep != Keep::Above || upper.keep != Keep::Below {
            return Err(Error::Malformed {
                field: "wall".into(),
                detail: "with two walls the first keeps U above it, the second below it".into(),
            });
        }
        if upper.position <= lower.position {
            return Err(Error::invalid(
                "wall.1.position",
                upper.position,
                format!("({}, 1e6] (above wall.0.position)", Exact(lower.position)),
            ));
        }
    }
    Ok(())
}

/// Most starts of one problem.
pub const MAX_STARTS: usize = 100_000;

/// The problem every driver takes: Eq. (1) (or Eq. 5 / Eq. 9) for one oscillator, with or
/// without the wall, from one start (or several, taken in turn by path index: path i starts
/// at `starts[i mod len]`), with a bound beyond which a path has blown up.
///
/// Validated on construction: every setter checks the whole problem and names the offending
/// value. Set the wall and the system before a start that needs them (a negative U(0) needs
/// [`Barrier::Off`] or [`System::Zhuravlev`]).
///
/// ```
/// use trirhythm::engine::{Barrier, Oscillator, Problem};
/// use trirhythm::model::preset;
///
/// let osc = Oscillator::new(&preset("fig1")?.params)?;
/// let problem = Problem::new(osc)
///     .with_barrier(Barrier::Off)?
///     .with_starts(&[(-1.0, 0.0), (2.0, 0.5)])?;
/// assert_eq!(problem.start(3), (2.0, 0.5)); // path 3 takes start 3 mod 2
/// assert!(problem.clone().with_barrier(Barrier::On).is_err()); // U(0) = −1 below the wall
/// # Ok::<(), trirhythm::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Problem {
    oscillator: Oscillator,
    system: System,
    barrier: Barrier,
    starts: Vec<(f64, f64)>,
    blow_up: f64,
}

impl Problem {
    /// The start (U(0), U̇(0)) of a problem that sets none.
    pub const DEFAULT_START: (f64, f64) = (1.0, 0.0);
    /// The blow-up bound of a problem that sets none.
    pub const DEFAULT_BLOW_UP: f64 = 1e8;

    /// Eq. (1) of `oscillator` with the wall, from [`Problem::DEFAULT_START`], blow-up at
    /// [`Problem::DEFAULT_BLOW_UP`].
    pub fn new(oscillator: Oscillator) -> Self {
        Problem {
            oscillator,
            system: System::Fractional,
            barrier: Barrier::On,
            starts: vec![Self::DEFAULT_START],
            blow_up: Self::DEFAULT_BLOW_UP,
        }
    }

    /// [`Problem::new`] of the validated parameters.
    pub fn from_params(params: &Params) -> Result<Self> {
        Ok(Problem::new(Oscillator::new(params)?))
    }

    /// The problem a model file describes: its equation, its wall and its start, for the
    /// models the engine steps ([`Model::engine_terms`]): the paper's Eq. 1 with the wall at 0
    /// or none, additive white or OU noise, and the General kernel's terms — Duffing
    /// k3U³ + k5U⁵, Rayleigh Σ d_k U̇^{2k}, harmonic forcing F cos(Ωt + φ), multiplicative
    /// noise U·η_m (with the wall at 0 or none), fractional terms K_j·D^{α_j}U (with any wall
    /// or none), any other walls (offset, keeping below, two, speed-dependent r; the barrier then off).
    /// Every other term is refused with [`Error::NotApplicable`] naming it, never dropped. For
    /// `Model::from(&p)` this is `Problem::from_params(&p)` (the same value, hence the same
    /// paths, bit for bit: `tests/model_file.rs`, `tests/pinned.rs`).
    ///
    /// ```
    /// use trirhythm::engine::{Barrier, Problem};
    /// use trirhythm::model::{preset, Model};
    ///
    /// let p = preset("fig13a")?.params;
    /// let model = Model::from_toml_str(&Model::from(&p).to_toml())?;
    /// assert_eq!(Problem::from_model(&model)?, Problem::from_params(&p)?);
    /// let mut duffing = model.clone();
    /// duffing.restoring.cubic = 0.5;
    /// assert!(Problem::from_model(&duffing)?.oscillator().terms().is_some()); // General kernel
    /// duffing.fractional.push(trirhythm::model::Fractional { coefficient: 0.1, order: 0.5 });
    /// assert!(Problem::from_model(&duffing)?.wall()); // with the paper's wall: stepped
    /// duffing.walls[0].position = -0.5;
    /// duffing.noise.multiplicative = Some(trirhythm::model::NoiseTerm {
    ///     intensity: 0.1,
    ///     correlation_time: 0.0,
    /// });
    /// assert!(Problem::from_model(&duffing).is_ok()); // U·η_m at a wall off 0: δ·η_m there
    /// # Ok::<(), trirhythm::Error>(())
    /// ```
    pub fn from_model(model: &Model) -> Result<Self> {
        let (family, terms) = model.engine_terms("the engine (Problem::from_model)")?;
        // the start is set with the walls: the default start may lie beyond the model's walls
        Problem {
            starts: vec![family.start],
            ..Problem::new(Oscillator::new(&family.params)?.with_terms(terms)?)
        }
        .with_barrier(if family.wall {
            Barrier::On
        } else {
            Barrier::Off
        })
    }

    /// The same problem with the General kernel's terms (Duffing, Rayleigh, forcing, fractional
    /// terms, multiplicative noise, walls; [`Oscillator::with_terms`]); they need
    /// [`System::Fractional`] (walls of their own: [`Barrier::Off`]).
    pub fn with_terms(self, terms: Option<GeneralTerms>) -> Result<Self> {
        Problem {
            oscillator: self.oscillator.clone().with_terms(terms)?,
            ..self
        }
        .checked()
    }

    /// The same problem for other parameters (a sweep's point), validated.
    pub fn with_params(&self, params: &Params) -> Result<Self> {
        Problem {
            oscillator: Oscillator::new(params)?.with_terms(self.oscillator.general.clone())?,
            ..self.clone()
        }
        .checked()
    }

    /// The equation integrated.
    pub fn with_system(self, system: System) -> Result<Self> {
        Problem { system, ..self }.checked()
    }

    /// The wall on or off.
    pub fn with_barrier(self, barrier: Barrier) -> Result<Self> {
        Problem { barrier, ..self }.checked()
    }

    /// One start (U(0), U̇(0)) for every path (on the allowed side of every wall).
    pub fn with_start(self, u0: f64, v0: f64) -> Result<Self> {
        self.with_starts(&[(u0, v0)])
    }

    /// Starts (U(0), U̇(0)) taken in turn: path i starts at `starts[i mod len]`.
    pub fn with_starts(self, starts: &[(f64, f64)]) -> Result<Self> {
        let p = Problem {
            starts: starts.to_vec(),
            ..self
        }
        .checked()?;
        for &(u0, _) in &p.starts {
            p.check_start_in_walls(u0)?;
        }
        Ok(p)
    }

    /// The bound on |U| and |U̇| beyond which a path has blown up, in (0, ∞].
    pub fn with_blow_up(self, blow_up: f64) -> Result<Self> {
        Problem { blow_up, ..self }.checked()
    }

    /// The oscillator (parameters and their Eq. 5 equivalents).
    pub fn oscillator(&self) -> &Oscillator {
        &self.oscillator
    }

    /// The parameters.
    pub fn params(&self) -> &Params {
        self.oscillator.params()
    }

    /// The equation.
    pub fn system(&self) -> System {
        self.system
    }

    /// The wall.
    pub fn barrier(&self) -> Barrier {
        self.barrier
    }

    /// The starts, taken in turn by path index.
    pub fn starts(&self) -> &[(f64, f64)] {
        &self.starts
    }

    /// The start of path `path`: `starts[path mod len]`.
    pub fn start(&self, path: u64) -> (f64, f64) {
        self.starts[(path % self.starts.len() as u64) as usize]
    }

    /// The blow-up bound.
    pub fn blow_up(&self) -> f64 {
        self.blow_up
    }

    /// Whether paths reflect at U = 0 (the wall is on and the system is not Eq. 9's, which
    /// crosses).
    pub fn wall(&self) -> bool {
        self.barrier == Barrier::On && self.system != System::Zhuravlev
    }

    fn checked(self) -> Result<Self> {
        if let Some(t) = self.oscillator.terms() {
            let field = if t.cubic != 0.0 {
                "restoring.cubic"
            } else if t.quintic != 0.0 {
                "restoring.quintic"
            } else if !t.rayleigh.is_empty() {
                "damping.rayleigh"
            } else if t.forcing.is_some() {
                "forcing.amplitude"
            } else if !t.fractional.is_empty() {
                "fractional"
            } else if t.multiplicative.is_some() {
                "noise.multiplicative"
            } else {
                "wall"
            };
            let refuse = |assumption: &str, reason: String| Error::NotApplicable {
                method: "the engine".into(),
                assumption: assumption.into(),
                reason,
            };
            if self.system != System::Fractional {
                return Err(refuse(
                    "Eq. (1) itself (System::Fractional)",
                    format!(
                        "{field}: the General kernel's terms have no Eq. (5)/(9) equivalent; \
                         system = {:?}",
                        self.system
                    ),
                ));
            }
            if !t.walls.is_empty() && self.barrier == Barrier::On {
                return Err(refuse(
                    "the model's walls only (Barrier::Off)",
                    "wall: the model's walls replace the paper's wall at U = 0; the barrier \
                     must be off"
                        .into(),
                ));
            }
        }
        let b = self.blow_up;
        if b.is_nan() || b <= 0.0 {
            return Err(Error::invalid("blow_up", b, "(0, ∞]"));
        }
        if self.starts.is_empty() || self.starts.len() > MAX_STARTS {
            return Err(Error::invalid(
                "u0",
                self.starts.len() as f64,
                format!("1 to {MAX_STARTS} starts"),
            ));
        }
        // a start at or beyond the blow-up bound would be reported as a blow-up at once
        let limit = format!("|·| < {} (the blow-up threshold)", Exact(b));
        for &(u0, v0) in &self.starts {
            if u0.is_nan() || u0.abs() >= b {
                return Err(Error::invalid("u0", u0, limit.as_str()));
            }
            if v0.is_nan() || v0.abs() >= b {
                return Err(Error::invalid("v0", v0, limit.as_str()));
            }
            if self.wall() && u0 < 0.0 {
                return Err(Error::invalid("u0", u0, "[0, ∞) with the barrier on"));
            }
        }
        Ok(self)
    }

    /// [δ1, δ2]: the interval the General kernel's walls keep U in (±∞ where there is no
    /// such wall; (−∞, ∞) for the paper's wall, which [`Problem::wall`] says).
    pub(crate) fn walls_interval(&self) -> (f64, f64) {
        let walls = self.oscillator.terms().map_or(&[][..], |t| &t.walls[..]);
        let (mut lo, mut hi) = (f64::NEG_INFINITY, f64::INFINITY);
        for w in walls {
            match w.keep {
                crate::model::Keep::Above => lo = w.position,
                crate::model::Keep::Below => hi = w.position,
            }
        }
        (lo, hi)
    }

    /// Err naming u0 when a start lies beyond one of the General kernel's walls (checked by
    /// [`Problem::with_starts`] and by every stepper at its start, not by the other setters:
    /// a problem may take its walls before its start).
    pub(crate) fn check_start_in_walls(&self, u0: f64) -> Result<()> {
        let walls = self.oscillator.terms().map_or(&[][..], |t| &t.walls[..]);
        for (i, w) in walls.iter().enumerate() {
            if !w.allows(u0) {
                let side = match w.keep {
                    crate::model::Keep::Above => format!("[{}, ∞)", Exact(w.position)),
                    crate::model::Keep::Below => format!("(−∞, {}]", Exact(w.position)),
                };
                return Err(Error::invalid(
                    "u0",
                    u0,
                    format!("{side}: wall.{i} keeps U {}", w.keep.name()),
                ));
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn setters_validate_the_whole_problem_and_name_the_value() {
        let p = Problem::from_params(&crate::model::preset("fig1").unwrap().params).unwrap();
        let named = |r: Result<Problem>, name: &str| match r {
            Err(Error::InvalidParameter { name: n, .. }) => assert_eq!(n, name),
            other => panic!("expected an error naming {name}: {other:?}"),
        };
        named(p.clone().with_start(-1.0, 0.0), "u0");
        named(p.clone().with_start(f64::NAN, 0.0), "u0");
        named(p.clone().with_start(1.0, f64::INFINITY), "v0");
        named(p.clone().with_starts(&[]), "u0");
        named(p.clone().with_blow_up(0.0), "blow_up");
        named(p.clone().with_blow_up(f64::NAN), "blow_up");
        named(
            p.clone().with_start(5.0, 0.0).unwrap().with_blow_up(5.0),
            "u0",
        );
        let z = p.clone().with_system(System::Zhuravlev).unwrap();
        assert_eq!(z.with_start(-1.0, 0.0).unwrap().start(7), (-1.0, 0.0));
        assert!(p.with_blow_up(f64::INFINITY).is_ok());
    }
}
