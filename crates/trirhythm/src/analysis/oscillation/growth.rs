//! One simulated path from a small amplitude and the growth rate σ of its oscillation: the
//! turning points read off the stepper, the least-squares slope of ln(amplitude) against time,
//! and the early stop once the sign is clear (module docs of [`super`]).

use crate::engine::{
    fresh_history, run, run_lanes, Flow, History, ImpactMemory, Lanes, Memory, Observer,
    PredictorCorrector, Problem, Stepper, System,
};
use crate::error::{Error, Exact, Result};
use crate::model::Params;
use crate::monitor::Monitor;
use std::f64::consts::PI;

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
    /// How many simulations are stepped together ([`Lanes`]; the default suits the CPU): the
    /// two probes of a search step, a row of a classified plane. The results do not depend on
    /// it.
    pub lanes: Lanes,
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
            lanes: Lanes::Auto,
        }
    }
}

/// The growth rate of one simulated path.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Growth {
    /// σ, the slope of ln(amplitude) over the window (per unit time): > 0 where a small
    /// oscillation grows.
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

/// Growth rate of a small oscillation of `problem` (Eq. 1 with D = 0, with or without its wall,
/// its blow-up bound) from U(0) = `classifier.amplitude`, U̇(0) = 0 (the problem's start is
/// not used: the run must start in the linear regime).
pub fn growth_rate(problem: &Problem, classifier: &Classifier) -> Result<Growth> {
    classifier.validate()?;
    let mut cache = Cache::default();
    grow(problem, classifier, &mut cache, &crate::monitor::Silent)
}

/// The empty memories kept between the runs of one search, by (λ, horizon): the most recent
/// few (the memory is the same for every run of one λ and horizon, so which are kept changes
/// no result).
#[derive(Default)]
pub(super) struct Cache(Vec<(f64, f64, History)>);

/// Memories a [`Cache`] keeps.
const CACHED: usize = 16;

impl Cache {
    /// The empty memory of λ = `lambda` over `t_max` for `problem` with `c`'s method.
    fn history(&mut self, problem: &Problem, c: &Classifier, t_max: f64) -> Result<History> {
        let lambda = problem.params().lambda;
        if let Some((_, _, h)) = self.0.iter().find(|(l, t, _)| *l == lambda && *t == t_max) {
            return Ok(h.clone());
        }
        let hist = fresh_history(problem, &c.method, t_max)?;
        if self.0.len() == CACHED {
            self.0.remove(0);
        }
        self.0.push((lambda, t_max, hist.clone()));
        Ok(hist)
    }
}

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
    /// Check the settings; the error names the field and its range: the method
    /// ([`PredictorCorrector::validate`]) with Δt in [1e-4, 0.1], `amplitude` in (0, 1e-3],
    /// `settle_periods` in [0, 1000], `min_periods` in [1, 1000], `max_periods` in
    /// [settle_periods + min_periods, 10000], `clarity` in (0, 1e6], `agreement` in (0, 1].
    pub fn validate(&self) -> Result<()> {
        let dt = self.method.dt;
        if !(1e-4..=0.1).contains(&dt) {
            return Err(Error::invalid("dt", dt, "[1e-4, 0.1]"));
        }
        self.method.validate()?;
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
        if !(self.clarity > 0.0 && self.clarity <= 1e6) {
            return Err(Error::invalid("clarity", self.clarity, "(0, 1e6]"));
        }
        if !(self.agreement > 0.0 && self.agreement <= 1.0) {
            return Err(Error::invalid("agreement", self.agreement, "(0, 1]"));
        }
        Ok(())
    }
}

/// Growth or decay by this factor ends a run: the sign is plain.
const DECIDED: f64 = 1e5;

/// Whether `problem` is one whose oscillation boundary is sought: Eq. (1) at D = 0.
pub(super) fn check_problem(problem: &Problem) -> Result<()> {
    let p = problem.params();
    if p.noise_intensity != 0.0 {
        return Err(Error::invalid(
            "D",
            p.noise_intensity,
            "0 (the oscillation boundary is that of the noise-free system)",
        ));
    }
    if problem.system() != System::Fractional {
        return Err(Error::invalid(
            "system",
            f64::NAN,
            "fractional (the oscillation boundary is that of Eq. 1)",
        ));
    }
    Ok(())
}

/// The growth of `problem`'s small oscillation (module docs of [`super`]), reusing the empty
/// memories of `cache`; `monitor` may stop the run.
pub(super) fn grow(
    problem: &Problem,
    c: &Classifier,
    cache: &mut Cache,
    monitor: &dyn Monitor,
) -> Result<Growth> {
    let mut r = Run::new(problem, c, cache)?;
    run(&mut r.stepper, r.steps, &mut r.peaks, monitor)?;
    Ok(r.shape.finish(&r.stepper, r.peaks))
}

/// [`grow`] for each of `problems`, the simulations stepped together in lanes
/// ([`Classifier::lanes`]; paths of different parameters, each lane with its own
/// coefficients): each result is bit for bit [`grow`]'s, an error included (the runs of the
/// others are not affected). `monitor` may stop them all ([`crate::Error::Cancelled`]).
pub(super) fn grow_all(
    problems: &[Problem],
    c: &Classifier,
    cache: &mut Cache,
    monitor: &dyn Monitor,
) -> Result<Vec<Result<Growth>>> {
    let lanes = c.lanes.width()?;
    if lanes == 1 || problems.len() < 2 {
        return Ok(problems
            .iter()
            .map(|p| grow(p, c, cache, monitor))
            .collect());
    }
    // a group no wider than needed: dead lanes still take the array phases' work
    let width = if problems.len() <= 4 { 4 } else { lanes };
    let (mut steppers, mut observers) = (vec![], vec![]);
    let shapes: Vec<Result<Shape>> = problems
        .iter()
        .map(|p| {
            let r = Run::new(p, c, cache)?;
            steppers.push(r.stepper);
            observers.push(Limited {
                steps: r.steps,
                peaks: r.peaks,
            });
            Ok(r.shape)
        })
        .collect();
    let steps = observers.iter().map(|o| o.steps).max().unwrap_or(0);
    let taken = run_lanes(
        &mut steppers,
        steps,
        &mut observers,
        Lanes::Width(width),
        monitor,
    )?;
    let mut done = steppers.into_iter().zip(observers).zip(taken);
    Ok(shapes
        .into_iter()
        .map(|shape| {
            let shape = shape?;
            let ((stepper, observer), taken) = done.next().expect("one run per prepared path");
            taken?;
            Ok(shape.finish(&stepper, observer.peaks))
        })
        .collect())
}

/// [`TurningPoints`] that also stops its path after `steps` steps (the run's own horizon, in a
/// group whose paths have others).
struct Limited {
    steps: u64,
    peaks: TurningPoints,
}

impl Observer for Limited {
    fn observe(&mut self, s: &Stepper) -> Flow {
        match self.peaks.observe(s) {
            Flow::Continue if s.steps() >= self.steps => Flow::Stop,
            flow => flow,
        }
    }
}

/// One growth run: the path from the small amplitude, its turning points, its horizon.
struct Run {
    stepper: Stepper,
    peaks: TurningPoints,
    steps: u64,
    shape: Shape,
}

/// What the growth rate needs of a run besides its path and turning points.
#[derive(Debug, Clone, Copy)]
struct Shape {
    a0: f64,
    dt: f64,
    omega0: f64,
    period: f64,
}

impl Run {
    fn new(problem: &Problem, c: &Classifier, cache: &mut Cache) -> Result<Run> {
        check_problem(problem)?;
        let params = problem.params();
        let t_max = horizon(params, c)?;
        let history = cache.history(problem, c, t_max)?;
        let dt = c.method.dt;
        let steps = (t_max / dt).round() as u64;
        let period = 2.0 * PI / params.omega0;
        let a0 = c.amplitude;
        let stepper = Stepper::with_history(problem, &c.method, (a0, 0.0), (0, 0), history)?;
        let peaks = TurningPoints {
            a0,
            wall: problem.barrier() == crate::engine::Barrier::On,
            dt,
            settle: c.settle_periods * period,
            min_window: c.min_periods * period,
            clarity: c.clarity,
            agreement: c.agreement,
            prev: (a0, 0.0),
            last_extremum: None,
            clear: false,
            stuck: false,
            latest: a0,
            all: Vec::new(),
            window: Vec::new(),
        };
        Ok(Run {
            stepper,
            peaks,
            steps,
            shape: Shape {
                a0,
                dt,
                omega0: params.omega0,
                period,
            },
        })
    }
}

impl Shape {
    /// The growth rate of a run's path once it has stopped.
    fn finish(self, stepper: &Stepper, peaks: TurningPoints) -> Growth {
        let Shape {
            a0,
            dt,
            omega0,
            period,
        } = self;
        let taken = stepper.steps();
        let TurningPoints {
            all,
            window,
            stuck,
            clear,
            latest,
            ..
        } = peaks;
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
                stepper.u().abs() + stepper.v().abs() / omega0
            };
            let ratio = (now / a0).max(1e-300);
            (crate::maths::ln(ratio) / t, 0.0, all.len())
        };
        Growth {
            rate: if stuck { rate.min(-1.0 / period) } else { rate },
            standard_error,
            clear: clear || stuck,
            peaks,
            steps: taken,
        }
    }
}

/// The turning points of a path, (t, ln amplitude), all of them and those of the window after
/// the start-up transient; stops the path once the sign of the growth is clear.
struct TurningPoints {
    a0: f64,
    wall: bool,
    dt: f64,
    settle: f64,
    min_window: f64,
    clarity: f64,
    agreement: f64,
    /// (U, V) at the previous node.
    prev: (f64, f64),
    /// The previous extremum without the wall (t, U).
    last_extremum: Option<(f64, f64)>,
    clear: bool,
    stuck: bool,
    latest: f64,
    all: Vec<(f64, f64)>,
    window: Vec<(f64, f64)>,
}

impl Observer for TurningPoints {
    fn observe(&mut self, s: &Stepper) -> Flow {
        let (u, v) = (s.u(), s.v());
        let (u0, v0) = self.prev;
        self.prev = (u, v);
        let ev = s.events();
        if s.steps() == 0 || ev.impact.is_some() {
            return Flow::Continue;
        }
        if ev.stuck {
            self.stuck = true;
            return Flow::Stop;
        }
        let maximum = v0 > 0.0 && v <= 0.0;
        let minimum = !self.wall && v0 < 0.0 && v >= 0.0;
        if !(maximum || minimum) {
            return Flow::Continue;
        }
        // the extremum of the quadratic through (u0, v0) and (u, v) over the step
        let h = self.dt;
        let acc = (v - v0) / h;
        let tau = if acc != 0.0 { -v0 / acc } else { 0.0 };
        let value = if acc != 0.0 {
            u0 - v0 * v0 / (2.0 * acc)
        } else {
            u
        };
        let t = s.time() - h + tau.clamp(0.0, h);
        let (ta, amp) = if self.wall {
            (t, value)
        } else {
            let out = self
                .last_extremum
                .map(|(tp, up)| (0.5 * (t + tp), 0.5 * (value - up).abs()));
            self.last_extremum = Some((t, value));
            match out {
                Some(x) => x,
                None => return Flow::Continue,
            }
        };
        if amp.is_nan() || amp <= 0.0 {
            return Flow::Continue;
        }
        self.latest = amp;
        let y = crate::maths::ln(amp);
        self.all.push((ta, y));
        let a0 = self.a0;
        if !(amp / a0 < DECIDED && a0 / amp < DECIDED) {
            self.clear = true;
            return Flow::Stop;
        }
        if ta < self.settle {
            return Flow::Continue;
        }
        self.window.push((ta, y));
        if self.sign_is_clear(ta) {
            self.clear = true;
            return Flow::Stop;
        }
        Flow::Continue
    }
}

impl TurningPoints {
    /// The window spans at least the shortest one, and the rates fitted on it and on its
    /// second half have the same sign, are both clear of their standard errors and agree.
    fn sign_is_clear(&self, ta: f64) -> bool {
        let window = &self.window;
        let span = ta - window[0].0;
        if span >= self.min_window && window.len() >= 6 {
            let (b, se) = fit(window);
            let mid = window[0].0 + 0.5 * span;
            let second: Vec<(f64, f64)> = window.iter().copied().filter(|p| p.0 >= mid).collect();
            let (b2, se2) = fit(&second);
            return b != 0.0
                && b.signum() == b2.signum()
                && b.abs() > self.clarity * se
                && b2.abs() > self.clarity * se2
                && (b - b2).abs() <= self.agreement * b.abs();
        }
        false
    }
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_fit_recovers_an_exponential() {
        let pts: Vec<(f64, f64)> = (0..20).map(|i| (i as f64, 1e-3 * i as f64 - 2.0)).collect();
        let (b, se) = fit(&pts);
        assert!((b - 1e-3).abs() < 1e-15 && se < 1e-12);
    }
}
