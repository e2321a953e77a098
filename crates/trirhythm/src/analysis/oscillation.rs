//! Oscillation boundaries (Hopf): where the rest state U = 0 of Eq. (1) at D = 0 loses its
//! stability, by simulation, by averaging and by the exact linearisation (Figs 15–16).
//!
//! # Equation
//! D^{1+λ}U − μ0 P(U) U̇ + ω0² U = 0 on U ≥ 0 with U̇₊ = −rU̇₋ at U = 0 (or on the whole line,
//! [`Barrier::Off`]). P(0) = c0 (= 1 for the paper's polynomial), so at rest the term
//! −μ0c0U̇ is a *negative* damping μ0c0 against the fractional term's positive one. A small
//! oscillation grows (the system oscillates) or dies (it rests); the boundary in one parameter
//! y at fixed other parameters is where the growth rate of the amplitude changes sign.
//!
//! # Methods
//! - [`Method::Simulation`]: from U(0) = a0 tiny (10⁻⁹, so P(U) = c0 to 10⁻¹⁸ and the run
//!   is the linearisation's), the predictor–corrector of [`crate::engine`] with the wall; the
//!   amplitude is read at every turning point (the extremum of the quadratic through the two
//!   nodes around V = 0; without the wall half the difference of consecutive extrema, which
//!   removes the slowly decaying offset of the fractional memory). After a start-up transient of
//!   [`Classifier::settle_periods`] periods 2π/ω0 (the Caputo memory of the start), the growth
//!   rate σ is the least-squares slope of ln(amplitude) against time over the window; the path
//!   stops as soon as the sign is clear (|σ| above [`Classifier::clarity`] standard errors on
//!   the window and on its second half, same sign on both, window at least
//!   [`Classifier::min_periods`] long), when the amplitude has grown 10⁵-fold or shrunk
//!   10⁵-fold, or at [`Classifier::max_periods`]. σ is close to linear in the parameter, so
//!   the boundary is bracketed by regula falsi on σ: each secant estimate c is followed by
//!   the pair c ∓ ½·tolerance, which straddles the root once the secant is accurate
//!   ([`Refinement::Secant`]); a step that does not halve the bracket is followed by a
//!   bisection, and [`Refinement::Bisection`] uses bisection on the sign alone. The result is
//!   the bracket [y_lo, y_hi] (width ≤ tolerance·|y|) and the secant root inside it.
//! - [`Method::Averaging`]: f′(0) = μ1β1/2 − κ = 0 of Eq. (18) (the theory's
//!   [`Theory::rest_state_slope`]), i.e. for μ0 the closed form [`averaging_mu0`]:
//!   μ0c0 = ω0^λ cos(πλ/2) + 2κ sin(πλ/2)/ω0^{1−λ}, κ = (1−r)ω1/π (paper) or −ω1 ln r/π
//!   (consistent). Without the wall there are no impacts: r = 1.
//! - [`Method::Exact`]: the linearisation at U = 0. Without the wall
//!   D^{1+λ}U − μ0c0U̇ + ω0²U = 0 grows iff s^{1+λ} − μ0c0 s + ω0² = 0 has a root with
//!   Re s > 0 (principal branch); on the boundary s = iΩ, so Ω^{1+λ} = ω0²/sin(πλ/2) and
//!   μ0c0 = Ω^λ cos(πλ/2) ([`exact_mu0`]). With the wall at λ = 1 each half-oscillation
//!   multiplies the amplitude by e^{μ0c0π/(2ω_d)} and each impact by r
//!   (ω_d² = ω0² − μ0²c0²/4): the boundary is μ0c0π/(2ω_d) + ln r = 0, i.e.
//!   μ0c0 = kω0/√(1 + k²/4), k = −2 ln r/π. With the wall and λ < 1 there is no exact
//!   half-period map under the continuous memory convention: [`Side::Unavailable`].
//!
//! With the wall at λ < 1 the decaying side is not a clean exponential: the memory's algebraic
//! tail acts on an exponentially shrinking bounce and the fitted rate drifts slowly, so the
//! simulated boundary there is the one over the horizon [`Classifier::max_periods`] (at
//! ω0 = 0.5, λ = 0.95, r = 0.99: 0.0206 over 40 periods, 0.0210 over 120).
//!
//! The analytic boundaries along any parameter are found by bisection on the sign of their
//! margin to full precision. Abscissae run in parallel (rayon); every point is deterministic
//! (no noise), so the results do not depend on the number of threads.
//!
//! # Reference
//! The paper's Section IV.B (Figs 15–16, predictor–corrector at D = 0); the averaged drift
//! Eq. (18); Matignon, "Stability results for fractional differential equations" (1996) for
//! the characteristic equation s^{1+λ} − μs + ω² = 0 of a Caputo equation and its roots on
//! the principal sheet.
//!
//! # Tests
//! `tests/oscillation.rs`: the simulated boundary against the exact one without the wall
//! (λ ∈ {0.7, 0.9, 0.998}, ω0 ∈ {0.3, 0.9}) and with the wall at λ = 1 (r ∈ {0.95, 0.9, 0.7})
//! within the bracket plus 2·10⁻⁴ relative; the averaging boundary against its closed form
//! (both variants, along μ0 and along r); thread-count independence; the unit tests below.

use crate::engine::{
    fresh_history, run, Barrier, Flow, History, ImpactMemory, Memory, Oscillator,
    PredictorCorrector, Stepper, System,
};
use crate::error::{Error, Exact, Result};
use crate::model::Params;
use crate::theory::averaging::{Theory, Variant};
use rayon::prelude::*;
use std::f64::consts::PI;
use std::sync::atomic::{AtomicUsize, Ordering};

/// How one simulation decides whether a small oscillation grows.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Classifier {
    /// The integrator (step, memory, impact convention).
    pub method: PredictorCorrector,
    /// Initial displacement U(0) (U̇(0) = 0): small enough that P(U) = P(0).
    pub amplitude: f64,
    /// Periods 2π/ω0 of start-up transient skipped before the window.
    pub settle_periods: f64,
    /// Shortest window, in periods 2π/ω0.
    pub min_periods: f64,
    /// Longest run, in periods 2π/ω0 (the sign of σ is taken as it is then).
    pub max_periods: f64,
    /// The sign is clear when |σ| exceeds this many standard errors of the fit.
    pub clarity: f64,
    /// … and the rates fitted on the window and on its second half agree to this fraction of
    /// |σ| (the transient has died out; the rates then feed the secant accurately).
    pub agreement: f64,
}

impl Default for Classifier {
    fn default() -> Self {
        Classifier {
            method: PredictorCorrector {
                dt: 0.01,
                memory: Memory::SumOfExponentials { tolerance: 1e-10 },
                impact_memory: ImpactMemory::Continuous,
                ..Default::default()
            },
            amplitude: 1e-9,
            settle_periods: 4.0,
            min_periods: 6.0,
            max_periods: 120.0,
            clarity: 20.0,
            agreement: 0.1,
        }
    }
}

/// The growth rate of one simulated path.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Growth {
    /// σ, the slope of ln(amplitude) over the window (per unit time).
    pub rate: f64,
    /// Its standard error from the fit's residuals.
    pub standard_error: f64,
    /// Whether the sign was clear before the run's end.
    pub clear: bool,
    /// Turning points in the window.
    pub peaks: usize,
    /// Steps taken.
    pub steps: u64,
}

impl Growth {
    /// The small oscillation grows.
    pub fn oscillates(&self) -> bool {
        self.rate > 0.0
    }
}

/// Growth rate of a small oscillation of `params` (D must be 0) with or without the wall.
pub fn growth_rate(params: &Params, barrier: Barrier, classifier: &Classifier) -> Result<Growth> {
    let mut cache = None;
    grow(params, barrier, classifier, &mut cache)
}

/// The memory kept between the runs of one search: (λ, horizon) and the empty history.
type Cache = Option<(f64, f64, History)>;

/// The run's horizon T = max_periods · 2π/ω0 as a whole number of steps.
fn horizon(params: &Params, c: &Classifier) -> Result<f64> {
    let period = 2.0 * PI / params.omega0;
    let steps = (c.max_periods * period / c.method.dt).ceil();
    if !(1.0..=1e9).contains(&steps) {
        return Err(Error::invalid(
            "dt",
            c.method.dt,
            format!(
                "a step giving at most 1e9 steps over {} periods 2π/ω0",
                Exact(c.max_periods)
            ),
        ));
    }
    Ok(steps * c.method.dt)
}

impl Classifier {
    /// Check the settings; the error names the field and its range.
    pub fn validate(&self) -> Result<()> {
        let dt = self.method.dt;
        if !(dt > 0.0 && dt <= 0.1) {
            return Err(Error::invalid("dt", dt, "(0, 0.1]"));
        }
        if !(self.amplitude > 0.0 && self.amplitude <= 1e-3) {
            return Err(Error::invalid("amplitude", self.amplitude, "(0, 1e-3]"));
        }
        if !(self.settle_periods >= 0.0 && self.settle_periods <= 1e3) {
            return Err(Error::invalid(
                "settle_periods",
                self.settle_periods,
                "[0, 1000]",
            ));
        }
        if !(self.min_periods >= 1.0 && self.min_periods <= 1e3) {
            return Err(Error::invalid("min_periods", self.min_periods, "[1, 1000]"));
        }
        if !(self.max_periods >= self.settle_periods + self.min_periods && self.max_periods <= 1e4)
        {
            return Err(Error::invalid(
                "max_periods",
                self.max_periods,
                "[settle_periods + min_periods, 10000]",
            ));
        }
        if !(self.clarity > 0.0 && self.clarity.is_finite()) {
            return Err(Error::invalid("clarity", self.clarity, "(0, ∞)"));
        }
        if !(self.agreement > 0.0 && self.agreement <= 1.0) {
            return Err(Error::invalid("agreement", self.agreement, "(0, 1]"));
        }
        Ok(())
    }
}

/// Growth or decay by this factor ends a run: the sign is plain.
const DECIDED: f64 = 1e5;

fn grow(params: &Params, barrier: Barrier, c: &Classifier, cache: &mut Cache) -> Result<Growth> {
    if params.noise_intensity != 0.0 {
        return Err(Error::invalid(
            "D",
            params.noise_intensity,
            "0 (the oscillation boundary is that of the noise-free system)",
        ));
    }
    let osc = Oscillator::new(params)?;
    let t_max = horizon(params, c)?;
    let history = match cache {
        Some((l, h, hist)) if *l == params.lambda && *h == t_max => hist.clone(),
        _ => {
            let hist = fresh_history(&osc, &c.method, System::Fractional, t_max)?;
            *cache = Some((params.lambda, t_max, hist.clone()));
            hist
        }
    };
    let dt = c.method.dt;
    let steps = (t_max / dt).round() as u64;
    let period = 2.0 * PI / params.omega0;
    let settle = c.settle_periods * period;
    let min_window = c.min_periods * period;
    let a0 = c.amplitude;
    let wall = barrier == Barrier::On;
    let mut stepper = Stepper::with_history(
        &osc,
        &c.method,
        System::Fractional,
        barrier,
        (a0, 0.0),
        (0, 0),
        history,
        1e8,
    )?;
    // turning points: (t, ln amplitude); window = those after the transient
    let mut all: Vec<(f64, f64)> = Vec::new();
    let mut window: Vec<(f64, f64)> = Vec::new();
    let mut prev = (a0, 0.0);
    let mut last_extremum: Option<(f64, f64)> = None;
    let mut clear = false;
    let mut stuck = false;
    let mut latest = a0;
    run(
        &mut stepper,
        steps,
        &mut |s: &Stepper| {
            let (u, v) = (s.u(), s.v());
            let (u0, v0) = prev;
            prev = (u, v);
            let ev = s.events();
            if s.steps() == 0 || ev.impact.is_some() {
                return Flow::Continue;
            }
            if ev.stuck {
                stuck = true;
                return Flow::Stop;
            }
            let maximum = v0 > 0.0 && v <= 0.0;
            let minimum = !wall && v0 < 0.0 && v >= 0.0;
            if !(maximum || minimum) {
                return Flow::Continue;
            }
            // the extremum of the quadratic through (u0, v0) and (u, v) over the step
            let h = dt;
            let acc = (v - v0) / h;
            let tau = if acc != 0.0 { -v0 / acc } else { 0.0 };
            let value = if acc != 0.0 {
                u0 - v0 * v0 / (2.0 * acc)
            } else {
                u
            };
            let t = s.time() - h + tau.clamp(0.0, h);
            let (ta, amp) = if wall {
                (t, value)
            } else {
                let out = last_extremum.map(|(tp, up)| (0.5 * (t + tp), 0.5 * (value - up).abs()));
                last_extremum = Some((t, value));
                match out {
                    Some(x) => x,
                    None => return Flow::Continue,
                }
            };
            if amp.is_nan() || amp <= 0.0 {
                return Flow::Continue;
            }
            latest = amp;
            let y = amp.ln();
            all.push((ta, y));
            if !(amp / a0 < DECIDED && a0 / amp < DECIDED) {
                clear = true;
                return Flow::Stop;
            }
            if ta < settle {
                return Flow::Continue;
            }
            window.push((ta, y));
            let span = ta - window[0].0;
            if span >= min_window && window.len() >= 6 {
                let (b, se) = fit(&window);
                let mid = window[0].0 + 0.5 * span;
                let second: Vec<(f64, f64)> =
                    window.iter().copied().filter(|p| p.0 >= mid).collect();
                let (b2, se2) = fit(&second);
                if b != 0.0
                    && b.signum() == b2.signum()
                    && b.abs() > c.clarity * se
                    && b2.abs() > c.clarity * se2
                    && (b - b2).abs() <= c.agreement * b.abs()
                {
                    clear = true;
                    return Flow::Stop;
                }
            }
            Flow::Continue
        },
        None,
    )?;
    let taken = stepper.steps();
    let (rate, standard_error, peaks) = if window.len() >= 3 {
        let (b, se) = fit(&window);
        (b, se, window.len())
    } else if all.len() >= 3 {
        let (b, se) = fit(&all);
        (b, se, all.len())
    } else {
        // too few turning points: compare the latest amplitude (or the state) with the start
        let t = stepper.time().max(dt);
        let now = if stuck {
            0.0
        } else if !all.is_empty() {
            latest
        } else {
            stepper.u().abs() + stepper.v().abs() / params.omega0
        };
        let ratio = (now / a0).max(1e-300);
        (ratio.ln() / t, 0.0, all.len())
    };
    Ok(Growth {
        rate: if stuck { rate.min(-1.0 / period) } else { rate },
        standard_error,
        clear: clear || stuck,
        peaks,
        steps: taken,
    })
}

/// Least-squares slope of y against t and its standard error (two passes: centred sums, so
/// that a tiny slope on a large offset keeps its digits).
fn fit(points: &[(f64, f64)]) -> (f64, f64) {
    let n = points.len() as f64;
    if n < 3.0 {
        return (0.0, f64::INFINITY);
    }
    let (mt, my) = points
        .iter()
        .fold((0.0, 0.0), |(a, b), &(t, y)| (a + t / n, b + y / n));
    let (mut sxx, mut sxy) = (0.0, 0.0);
    for &(t, y) in points {
        sxx += (t - mt) * (t - mt);
        sxy += (t - mt) * (y - my);
    }
    if sxx.is_nan() || sxx <= 0.0 {
        return (0.0, f64::INFINITY);
    }
    let b = sxy / sxx;
    let rss: f64 = points
        .iter()
        .map(|&(t, y)| {
            let e = y - my - b * (t - mt);
            e * e
        })
        .sum();
    (b, (rss / (n - 2.0) / sxx).sqrt())
}

/// How a boundary is found.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Method {
    /// Predictor–corrector runs from a small amplitude, bracketed along y.
    Simulation(Classifier),
    /// f′(0) = 0 of the averaged drift (Eq. 18) in the given variant.
    Averaging(Variant),
    /// The exact linearisation at U = 0 (no wall: any λ; wall: λ = 1).
    Exact,
}

impl Method {
    /// `simulation`, `averaging` or `exact`.
    pub fn name(&self) -> &'static str {
        match self {
            Method::Simulation(_) => "simulation",
            Method::Averaging(_) => "averaging",
            Method::Exact => "exact",
        }
    }
}

/// How the simulated bracket is narrowed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Refinement {
    /// Regula falsi on the growth rate, each estimate followed by a pair straddling it.
    #[default]
    Secant,
    /// Bisection on the sign alone.
    Bisection,
}

/// Accuracy of the simulated boundary.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Search {
    /// Bracket width relative to |y| at which the search stops.
    pub tolerance: f64,
    /// How the bracket is narrowed.
    pub refinement: Refinement,
}

impl Default for Search {
    fn default() -> Self {
        Search {
            tolerance: 1e-3,
            refinement: Refinement::Secant,
        }
    }
}

/// The problem: a base parameter set, the wall, abscissae of one parameter and the interval of
/// another in which the boundary is sought.
#[derive(Debug, Clone, PartialEq)]
pub struct Problem {
    /// Everything that does not vary (D = 0).
    pub base: Params,
    /// Wall on or off.
    pub barrier: Barrier,
    /// The abscissa's key (as for [`Params::set`]).
    pub x_key: String,
    /// The abscissae.
    pub x: Vec<f64>,
    /// The searched parameter's key.
    pub y_key: String,
    /// The interval [lo, hi] searched.
    pub y_range: (f64, f64),
}

impl Problem {
    /// Validate: D = 0, two different known keys, lo < hi, and every abscissa valid with
    /// both ends of the interval.
    pub fn new(
        base: &Params,
        barrier: Barrier,
        (x_key, x): (&str, Vec<f64>),
        (y_key, lo, hi): (&str, f64, f64),
    ) -> Result<Problem> {
        base.validate()?;
        if base.noise_intensity != 0.0 {
            return Err(Error::invalid(
                "D",
                base.noise_intensity,
                "0 (the oscillation boundary is that of the noise-free system)",
            ));
        }
        base.get(x_key)?;
        base.get(y_key)?;
        if x_key == y_key {
            return Err(Error::invalid(
                x_key,
                f64::NAN,
                "a key different from the searched one",
            ));
        }
        if x_key == "D" || y_key == "D" {
            return Err(Error::invalid(
                "D",
                base.noise_intensity,
                "0, not an axis (the oscillation boundary is that of the noise-free system)",
            ));
        }
        if lo.is_nan() || hi.is_nan() || lo >= hi {
            return Err(Error::invalid(
                y_key,
                lo,
                format!("an interval start below its end {}", Exact(hi)),
            ));
        }
        if x.is_empty() {
            return Err(Error::invalid(x_key, f64::NAN, "at least one abscissa"));
        }
        let problem = Problem {
            base: base.clone(),
            barrier,
            x_key: x_key.to_string(),
            x,
            y_key: y_key.to_string(),
            y_range: (lo, hi),
        };
        for &xv in &problem.x {
            problem.at(xv, lo)?;
            problem.at(xv, hi)?;
        }
        Ok(problem)
    }

    /// The parameters at (x, y), validated.
    pub fn at(&self, x: f64, y: f64) -> Result<Params> {
        let mut p = self.base.clone();
        p.set(&self.x_key, x)?;
        p.set(&self.y_key, y)?;
        p.validate()?;
        Ok(p)
    }
}

/// Where the boundary is at one abscissa.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum Side {
    /// Inside the interval.
    Boundary,
    /// The system oscillates over the whole interval.
    Oscillates,
    /// The system rests over the whole interval.
    Rests,
    /// The method does not apply here (exact linearisation with the wall at λ < 1).
    Unavailable,
}

impl Side {
    /// `boundary`, `oscillates`, `rests`, `unavailable`.
    pub fn name(self) -> &'static str {
        match self {
            Side::Boundary => "boundary",
            Side::Oscillates => "oscillates",
            Side::Rests => "rests",
            Side::Unavailable => "unavailable",
        }
    }
}

/// The boundary at one abscissa.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct BoundaryPoint {
    /// The abscissa.
    pub x: f64,
    /// Whether a boundary lies in the interval.
    pub side: Side,
    /// The boundary (simulation: the secant root of the growth rates at the bracket's ends;
    /// NaN unless [`Side::Boundary`]).
    #[serde(with = "crate::non_finite")]
    pub y: f64,
    /// Lower end of the bracket (= y for the analytic methods).
    #[serde(with = "crate::non_finite")]
    pub y_lo: f64,
    /// Upper end of the bracket (= y for the analytic methods).
    #[serde(with = "crate::non_finite")]
    pub y_hi: f64,
    /// Whether the system oscillates just above the boundary (y_hi side).
    pub oscillates_above: bool,
    /// Simulations run for this point (0 for the analytic methods).
    pub simulations: usize,
    /// Simulations whose sign was not clear when they reached their longest run.
    pub unclear: usize,
}

/// The boundary along the abscissae.
#[derive(Debug, Clone, PartialEq)]
pub struct Boundary {
    /// `simulation`, `averaging` or `exact`.
    pub method: &'static str,
    /// One point per abscissa, in order.
    pub points: Vec<BoundaryPoint>,
}

impl Boundary {
    /// Simulations run in all.
    pub fn simulations(&self) -> usize {
        self.points.iter().map(|p| p.simulations).sum()
    }
}

/// Progress callback: (done, total).
pub type Progress<'a> = Option<&'a (dyn Fn(usize, usize) + Sync)>;

/// The boundary of `problem` by `method` at every abscissa (in parallel; deterministic).
pub fn boundary(
    problem: &Problem,
    method: &Method,
    search: &Search,
    progress: Progress,
) -> Result<Boundary> {
    if !(search.tolerance > 0.0 && search.tolerance <= 0.5) {
        return Err(Error::invalid("tolerance", search.tolerance, "(0, 0.5]"));
    }
    if let Method::Simulation(c) = method {
        c.validate()?;
    }
    let done = AtomicUsize::new(0);
    let total = problem.x.len();
    let points = problem
        .x
        .par_iter()
        .map(|&x| {
            let point = match method {
                Method::Simulation(c) => simulated(problem, x, c, search),
                Method::Averaging(_) | Method::Exact => analytic(problem, x, method),
            };
            let n = done.fetch_add(1, Ordering::Relaxed) + 1;
            if let Some(p) = progress {
                p(n, total);
            }
            point
        })
        .collect::<Result<Vec<_>>>()?;
    Ok(Boundary {
        method: method.name(),
        points,
    })
}

/// The analytic margin at `p`: positive where the small oscillation grows; `None` where the
/// method does not apply.
pub fn margin(p: &Params, barrier: Barrier, method: &Method) -> Result<Option<f64>> {
    match method {
        Method::Averaging(v) => {
            let q = match barrier {
                Barrier::On => p.clone(),
                Barrier::Off => p.with("r", 1.0)?,
            };
            Ok(Some(Theory::new(&q, *v)?.rest_state_slope()))
        }
        Method::Exact => Ok(exact_margin(p, barrier)),
        Method::Simulation(_) => Err(Error::invalid(
            "method",
            f64::NAN,
            "averaging or exact (a simulation has a growth rate, not a margin)",
        )),
    }
}

/// cos(πλ/2) without cancellation near λ = 1, and sin(πλ/2).
fn trig(lambda: f64) -> (f64, f64) {
    ((PI * (1.0 - lambda) / 2.0).sin(), (PI * lambda / 2.0).sin())
}

/// The exact linearisation's margin: μ0c0 − Ω^λcos(πλ/2) without the wall;
/// μ0c0π/(2ω_d) + ln r with it at λ = 1 (+∞ when μ0c0 ≥ 2ω0: the motion leaves the wall
/// without returning); `None` with the wall at λ < 1.
fn exact_margin(p: &Params, barrier: Barrier) -> Option<f64> {
    let m = p.mu0 * p.damping.coefficient(0);
    match barrier {
        Barrier::Off => {
            let (c, s) = trig(p.lambda);
            let omega = (p.omega0 * p.omega0 / s).powf(1.0 / (1.0 + p.lambda));
            Some(m - omega.powf(p.lambda) * c)
        }
        Barrier::On if p.lambda == 1.0 => {
            let r = p.restitution;
            if r == 0.0 {
                return Some(f64::NEG_INFINITY);
            }
            if m >= 2.0 * p.omega0 {
                return Some(f64::INFINITY);
            }
            let wd = (p.omega0 * p.omega0 - m * m / 4.0).sqrt();
            Some(m * PI / (2.0 * wd) + r.ln())
        }
        Barrier::On => None,
    }
}

/// The averaging's boundary in μ0 (closed form of f′(0) = 0, Eq. 18):
/// μ0 = (ω0^λcos(πλ/2) + 2κ sin(πλ/2)/ω0^{1−λ})/c0 with κ the variant's impact loss rate
/// (r = 1 without the wall); `None` when c0 ≤ 0 (no boundary: the rest state is stable for
/// every μ0) or when κ is infinite (r = 0, consistent variant).
pub fn averaging_mu0(p: &Params, barrier: Barrier, variant: Variant) -> Option<f64> {
    let c0 = p.damping.coefficient(0);
    let r = match barrier {
        Barrier::On => p.restitution,
        Barrier::Off => 1.0,
    };
    let eq = crate::model::Equivalents::new(p);
    let kappa = eq.loss_rate(variant, r);
    let (c, s) = trig(p.lambda);
    let mu = (p.omega0.powf(p.lambda) * c + 2.0 * kappa * s / p.omega0.powf(1.0 - p.lambda)) / c0;
    (c0 > 0.0 && mu.is_finite()).then_some(mu)
}

/// The exact linearisation's boundary in μ0: Ω^λcos(πλ/2)/c0 with
/// Ω^{1+λ} = ω0²/sin(πλ/2) (no wall); kω0/(c0√(1 + k²/4)), k = −2 ln r/π (wall, λ = 1);
/// `None` with the wall at λ < 1, for r = 0, or when c0 ≤ 0.
pub fn exact_mu0(p: &Params, barrier: Barrier) -> Option<f64> {
    let c0 = p.damping.coefficient(0);
    if c0 <= 0.0 {
        return None;
    }
    match barrier {
        Barrier::Off => {
            let (c, s) = trig(p.lambda);
            let omega = (p.omega0 * p.omega0 / s).powf(1.0 / (1.0 + p.lambda));
            Some(omega.powf(p.lambda) * c / c0)
        }
        Barrier::On if p.lambda == 1.0 && p.restitution > 0.0 => {
            let k = -2.0 * p.restitution.ln() / PI;
            Some(k * p.omega0 / (1.0 + k * k / 4.0).sqrt() / c0)
        }
        Barrier::On => None,
    }
}

fn analytic(problem: &Problem, x: f64, method: &Method) -> Result<BoundaryPoint> {
    let (lo, hi) = problem.y_range;
    let eval =
        |y: f64| -> Result<Option<f64>> { margin(&problem.at(x, y)?, problem.barrier, method) };
    let unavailable = BoundaryPoint {
        x,
        side: Side::Unavailable,
        y: f64::NAN,
        y_lo: f64::NAN,
        y_hi: f64::NAN,
        oscillates_above: false,
        simulations: 0,
        unclear: 0,
    };
    let (Some(fa), Some(fb)) = (eval(lo)?, eval(hi)?) else {
        return Ok(unavailable);
    };
    let (ga, gb) = (fa > 0.0, fb > 0.0);
    if ga == gb {
        return Ok(BoundaryPoint {
            side: if ga { Side::Oscillates } else { Side::Rests },
            oscillates_above: gb,
            ..unavailable
        });
    }
    let (mut a, mut b) = (lo, hi);
    for _ in 0..200 {
        let m = 0.5 * (a + b);
        if m <= a || m >= b {
            break;
        }
        match eval(m)? {
            Some(f) if (f > 0.0) == ga => a = m,
            Some(_) => b = m,
            None => return Ok(unavailable),
        }
    }
    let y = 0.5 * (a + b);
    Ok(BoundaryPoint {
        side: Side::Boundary,
        y,
        y_lo: y,
        y_hi: y,
        oscillates_above: gb,
        ..unavailable
    })
}

fn simulated(problem: &Problem, x: f64, c: &Classifier, search: &Search) -> Result<BoundaryPoint> {
    let (lo, hi) = problem.y_range;
    let mut cache: Cache = None;
    let mut simulations = 0;
    let mut unclear = 0;
    let mut eval = |y: f64| -> Result<f64> {
        let g = grow(&problem.at(x, y)?, problem.barrier, c, &mut cache)?;
        simulations += 1;
        unclear += usize::from(!g.clear);
        Ok(g.rate)
    };
    let (fa0, fb0) = (eval(lo)?, eval(hi)?);
    let (ga, gb) = (fa0 > 0.0, fb0 > 0.0);
    if ga == gb {
        return Ok(BoundaryPoint {
            x,
            side: if ga { Side::Oscillates } else { Side::Rests },
            y: f64::NAN,
            y_lo: f64::NAN,
            y_hi: f64::NAN,
            oscillates_above: gb,
            simulations,
            unclear,
        });
    }
    let ((mut a, mut fa), (mut b, mut fb)) = ((lo, fa0), (hi, fb0));
    let secant = |a: f64, fa: f64, b: f64, fb: f64| {
        let c = a - fa * (b - a) / (fb - fa);
        if c.is_finite() {
            c.clamp(a, b)
        } else {
            0.5 * (a + b)
        }
    };
    let floor = 1e-12 * (hi - lo);
    // Illinois: an end kept twice in a row has its rate halved in the secant
    let (mut wa, mut wb) = (1.0, 1.0);
    let mut last_moved = (false, false);
    let mut stalls = 0;
    for _ in 0..200 {
        let width = b - a;
        let est = secant(a, wa * fa, b, wb * fb);
        let target = (search.tolerance * est.abs()).max(floor);
        if width <= target {
            break;
        }
        let mut probes = Vec::with_capacity(2);
        if search.refinement == Refinement::Bisection || stalls >= 2 {
            probes.push(0.5 * (a + b));
        } else {
            probes.push(est - 0.45 * target);
            probes.push(est + 0.45 * target);
        }
        let mut moved = (false, false);
        for y in probes {
            if !(y > a && y < b) {
                continue;
            }
            let f = eval(y)?;
            if (f > 0.0) == ga {
                (a, fa, wa) = (y, f, 1.0);
                moved.0 = true;
            } else {
                (b, fb, wb) = (y, f, 1.0);
                moved.1 = true;
                break;
            }
        }
        match moved {
            (true, false) if last_moved == moved => wb *= 0.5,
            (false, true) if last_moved == moved => wa *= 0.5,
            _ => {}
        }
        last_moved = moved;
        stalls = if b - a > 0.5 * width { stalls + 1 } else { 0 };
    }
    Ok(BoundaryPoint {
        x,
        side: Side::Boundary,
        y: secant(a, fa, b, fb),
        y_lo: a,
        y_hi: b,
        oscillates_above: gb,
        simulations,
        unclear,
    })
}

/// One classified point of a plane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cell {
    /// Abscissa.
    pub x: f64,
    /// Ordinate.
    pub y: f64,
    /// Whether a small oscillation grows here.
    pub oscillates: bool,
    /// The growth rate (simulation) or the margin (analytic methods; NaN where unavailable).
    pub rate: f64,
}

/// Classify every (x, y) of `problem.x` × `ys` by `method` (rows over x in parallel;
/// deterministic). The interval `problem.y_range` is not used.
pub fn classify_plane(
    problem: &Problem,
    ys: &[f64],
    method: &Method,
    progress: Progress,
) -> Result<Vec<Cell>> {
    if let Method::Simulation(c) = method {
        c.validate()?;
    }
    let done = AtomicUsize::new(0);
    let total = problem.x.len() * ys.len();
    let rows = problem
        .x
        .par_iter()
        .map(|&x| {
            let mut cache: Cache = None;
            let mut row = Vec::with_capacity(ys.len());
            for &y in ys {
                let p = problem.at(x, y)?;
                let rate = match method {
                    Method::Simulation(c) => grow(&p, problem.barrier, c, &mut cache)?.rate,
                    _ => margin(&p, problem.barrier, method)?.unwrap_or(f64::NAN),
                };
                row.push(Cell {
                    x,
                    y,
                    oscillates: rate > 0.0,
                    rate,
                });
                let n = done.fetch_add(1, Ordering::Relaxed) + 1;
                if let Some(p) = progress {
                    p(n, total);
                }
            }
            Ok(row)
        })
        .collect::<Result<Vec<_>>>()?;
    Ok(rows.into_iter().flatten().collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn params(mu0: f64, omega0: f64, lambda: f64, r: f64) -> Params {
        Params {
            mu0,
            omega0,
            lambda,
            restitution: r,
            ..Default::default()
        }
    }

    #[test]
    fn exact_boundary_solves_the_characteristic_equation_on_the_imaginary_axis() {
        for (w, l) in [(0.3, 0.9), (0.9, 0.7), (1.0, 0.5)] {
            let p = params(0.01, w, l, 1.0);
            let mu = exact_mu0(&p, Barrier::Off).unwrap();
            // s = iΩ: (iΩ)^{1+λ} − iμΩ + ω0² = 0 with the principal power
            let omega = (w * w / (PI * l / 2.0).sin()).powf(1.0 / (1.0 + l));
            let arg = PI / 2.0 * (1.0 + l);
            let mag = omega.powf(1.0 + l);
            let re = mag * arg.cos() + w * w;
            let im = mag * arg.sin() - mu * omega;
            assert!(re.abs() < 1e-14 && im.abs() < 1e-14, "{re} {im}");
        }
        // at λ = 1 the exact boundary without the wall is μ0 = 0, as the averaging's
        let p = params(0.01, 0.7, 1.0, 1.0);
        assert_eq!(exact_mu0(&p, Barrier::Off), Some(0.0));
        assert_eq!(averaging_mu0(&p, Barrier::Off, Variant::Paper), Some(0.0));
    }

    #[test]
    fn margins_vanish_on_their_closed_forms() {
        let p = params(0.01, 0.9, 1.0, 0.9);
        let mu = exact_mu0(&p, Barrier::On).unwrap();
        let m = exact_margin(&p.with("mu0", mu).unwrap(), Barrier::On).unwrap();
        assert!(m.abs() < 1e-14, "{m}");
        for v in [Variant::Paper, Variant::Consistent] {
            let p = params(0.01, 0.5, 0.95, 0.97);
            let mu = averaging_mu0(&p, Barrier::On, v).unwrap();
            let f = Theory::new(&p.with("mu0", mu).unwrap(), v)
                .unwrap()
                .rest_state_slope();
            assert!(f.abs() < 1e-15, "{f}");
        }
        assert_eq!(
            exact_margin(&params(0.01, 0.9, 0.99, 0.9), Barrier::On),
            None
        );
    }

    #[test]
    fn the_fit_recovers_an_exponential() {
        let pts: Vec<(f64, f64)> = (0..20).map(|i| (i as f64, 1e-3 * i as f64 - 2.0)).collect();
        let (b, se) = fit(&pts);
        assert!((b - 1e-3).abs() < 1e-15 && se < 1e-12);
    }
}
