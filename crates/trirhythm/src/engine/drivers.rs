//! Drivers: loops over a [`Stepper`] with an [`Observer`] deciding what to keep.
//!
//! [`run`] steps a path and shows every node to the observer, which records what it wants
//! (a trajectory every K steps, streaming statistics, …) and may stop the path early
//! ([`Flow::Stop`]). [`simulate`] and [`simulate_ensemble`] are such loops with the
//! [`TrajectoryRecorder`]. Ensembles build the verified SOE kernel once and run paths in
//! parallel; path i depends only on (seed, i), so results are bit-identical whatever the number
//! of threads.
//!
//! # Example
//! ```
//! use trirhythm::engine::{run, simulate, Flow, Options, PredictorCorrector, Problem, Stepper};
//! use trirhythm::model::preset;
//! use trirhythm::monitor::Silent;
//!
//! let problem = Problem::from_params(&preset("fig1")?.params)?.with_start(6.78, 0.0)?; // Eq. 1
//! let method = PredictorCorrector { dt: 0.01, ..Default::default() }; // SOE memory, 1e-5·Δt² = 1e-9
//! let options = Options { t_end: 50.0, seed: 42, ..Default::default() }; // path 0 of seed 42
//! let path = simulate(&problem, &method, &options)?;
//! assert_eq!(path.steps, 5000);
//! assert!(path.u.iter().all(|&u| u >= 0.0) && path.impacts > 0);
//!
//! // the same path, stopped at its first impact by an observer
//! let mut stepper = options.stepper(&problem, &method)?;
//! let mut first = None;
//! run(&mut stepper, 5000, &mut |s: &Stepper| match s.events().impact {
//!     Some(i) => { first = Some(i.time); Flow::Stop }
//!     None => Flow::Continue,
//! }, &Silent)?;
//! let t = first.expect("an impact before t = 50");
//! assert_eq!(stepper.impacts(), 1);
//! assert!(stepper.time() - 0.01 < t && t <= stepper.time()); // inside the last step
//! # Ok::<(), trirhythm::Error>(())
//! ```

use super::memory::History;
use super::problem::{
    Options, Oscillator, PredictorCorrector, Problem, MAX_AMPLITUDE_PERIODS, MAX_DT,
};
use super::stepper::lanes::{
    group_lanes, same_problem, step_group, step_group_mixed, Isa, PerLane,
};
use super::stepper::{fresh_history, Impact, Lanes, Stepper};
use crate::error::{Error, Result};
use crate::monitor::{Monitor, Silent};
use rayon::prelude::*;

/// Whether a driver goes on after an observation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Flow {
    /// Take the next step.
    Continue,
    /// End the path here.
    Stop,
}

/// What a driver shows each node to: once at the start and after every step.
pub trait Observer {
    /// Look at the path after its latest step (or at its start).
    fn observe(&mut self, path: &Stepper) -> Flow;
}

impl<F: FnMut(&Stepper) -> Flow> Observer for F {
    fn observe(&mut self, path: &Stepper) -> Flow {
        self(path)
    }
}

/// Step `path` up to `steps` times, showing the start and every step to `observer`; returns
/// the number of steps taken (fewer when the observer stopped the path). `monitor` hears the
/// steps done about a thousand times, and is asked as often whether to stop
/// ([`Error::Cancelled`]). `steps` is at most [`MAX_STEPS`].
pub fn run(
    path: &mut Stepper,
    steps: u64,
    observer: &mut impl Observer,
    monitor: &dyn Monitor,
) -> Result<u64> {
    if steps > MAX_STEPS {
        return Err(Error::invalid(
            "steps",
            steps as f64,
            format!("0 to {MAX_STEPS:e}"),
        ));
    }
    if observer.observe(path) == Flow::Stop {
        return Ok(0);
    }
    let tick = (steps / 1000).max(1);
    // a countdown, not n % tick: an integer division per step would cost more than the check
    let mut until_tick = tick;
    for n in 1..=steps {
        path.step()?;
        if observer.observe(path) == Flow::Stop {
            return Ok(n);
        }
        until_tick -= 1;
        if until_tick == 0 {
            until_tick = tick;
            monitor.progress(n, steps);
            monitor.check()?;
        }
    }
    Ok(steps)
}

/// [`run`] for several paths: path k is stepped up to `steps` times and shown, at its start
/// and after every step, to `observers[k]`, which may stop it; the paths go in groups of
/// `lanes` ([`Lanes::width`]: 1, 4 or 8) whose steps are taken together (module docs of
/// `stepper::lanes`). The paths of a group may be of different problems and methods (the
/// oscillation searches run several parameter values at once): each lane then takes its own
/// coefficients. Every path gives exactly the bits that [`run`] gives it alone, whatever the
/// lane count, the group it falls in and its neighbours. Returns for each path the steps it
/// took, or the error of its failed step (the other paths go on). `monitor` hears the steps
/// of all paths done about a thousand times and is asked as often whether to stop
/// ([`Error::Cancelled`] for the whole call). Refused: `steps` above [`MAX_STEPS`], as many
/// observers as paths wanted, a lane count other than 1, 4 or 8.
pub fn run_lanes<O: Observer>(
    paths: &mut [Stepper],
    steps: u64,
    observers: &mut [O],
    lanes: Lanes,
    monitor: &dyn Monitor,
) -> Result<Vec<Result<u64>>> {
    let width = lanes.width()?;
    if steps > MAX_STEPS {
        return Err(Error::invalid(
            "steps",
            steps as f64,
            format!("0 to {MAX_STEPS:e}"),
        ));
    }
    if observers.len() != paths.len() {
        return Err(Error::invalid(
            "observers",
            observers.len() as f64,
            format!("one per path ({})", paths.len()),
        ));
    }
    let total = steps.saturating_mul(paths.len() as u64);
    let tick = (total / 1000).max(1);
    let mut done = 0u64;
    let mut out = Vec::with_capacity(paths.len());
    if width == 1 {
        for (p, o) in paths.iter_mut().zip(observers.iter_mut()) {
            out.push(run(p, steps, o, &Silent));
            done += steps;
            monitor.progress(done.min(total), total);
            monitor.check()?;
        }
        return Ok(out);
    }
    let isa = Isa::detect();
    for (group, obs) in paths.chunks_mut(width).zip(observers.chunks_mut(width)) {
        let results = if width == 8 {
            run_group::<8, O>(isa, group, obs, steps, (&mut done, tick, total), monitor)?
        } else {
            run_group::<4, O>(isa, group, obs, steps, (&mut done, tick, total), monitor)?
        };
        out.extend(results);
    }
    Ok(out)
}

/// [`run_lanes`] for one group of at most L paths.
fn run_group<const L: usize, O: Observer>(
    isa: Isa,
    paths: &mut [Stepper],
    observers: &mut [O],
    steps: u64,
    (done, tick, total): (&mut u64, u64, u64),
    monitor: &dyn Monitor,
) -> Result<Vec<Result<u64>>> {
    let n = paths.len();
    let mut live = [false; L];
    let mut taken: Vec<Result<u64>> = (0..n).map(|_| Ok(steps)).collect();
    for k in 0..n {
        if observers[k].observe(&paths[k]) == Flow::Stop {
            taken[k] = Ok(0);
        } else {
            live[k] = true;
        }
    }
    let mut errors: [Option<Error>; L] = std::array::from_fn(|_| None);
    // one problem: its coefficients shared; several: each lane its own; polynomials of
    // different forms (which no lane step can share): one path after the other
    let (shared, mixed) = if same_problem(paths) {
        (true, None)
    } else {
        (false, PerLane::<L>::new(paths))
    };
    let mut until_tick = tick;
    for step in 1..=steps {
        let alive = live.iter().filter(|&&l| l).count() as u64;
        if alive == 0 {
            break;
        }
        match &mixed {
            _ if shared => step_group::<L>(isa, paths, &live, &mut errors),
            Some(c) => step_group_mixed::<L>(isa, c, paths, &live, &mut errors),
            None => {
                for (k, p) in paths.iter_mut().enumerate() {
                    if live[k] {
                        errors[k] = p.step().err();
                    }
                }
            }
        }
        for k in 0..n {
            if !live[k] {
                continue;
            }
            if let Some(e) = errors[k].take() {
                live[k] = false;
                taken[k] = Err(e);
            } else if observers[k].observe(&paths[k]) == Flow::Stop {
                live[k] = false;
                taken[k] = Ok(step);
            }
        }
        // the progress in path-steps, a countdown as in `run`
        *done += alive;
        if until_tick <= alive {
            until_tick = tick;
            monitor.progress((*done).min(total), total);
            monitor.check()?;
        } else {
            until_tick -= alive;
        }
    }
    Ok(taken)
}

/// The steppers of paths `group` (stream i of `seed` from `problem.start(i)`, in the order
/// given) with a copy of the empty memory `history` built once for the ensemble: a lane
/// group's paths for [`run_lanes`].
pub(crate) fn group_steppers(
    problem: &Problem,
    method: &PredictorCorrector,
    seed: u64,
    group: &[u64],
    history: &History,
) -> Result<Vec<Stepper>> {
    group
        .iter()
        .map(|&i| {
            let start = problem.start(i);
            Stepper::with_history(problem, method, start, (seed, i), history.clone())
        })
        .collect()
}

/// Whole steps of Δt = `dt` in a span `t` named `name` (0 allowed when `allow_zero`), checked:
/// finite, a whole number of steps (to 10⁻⁹ relative; the grid is uniform, so a span between
/// two grid points is refused rather than silently moved) and at most [`MAX_STEPS`].
pub(crate) fn whole_steps(name: &str, t: f64, dt: f64, allow_zero: bool) -> Result<u64> {
    if !(dt > 0.0 && dt.is_finite()) {
        return Err(Error::invalid("dt", dt, "(0, ∞), finite"));
    }
    let least = if allow_zero {
        "0 or more"
    } else {
        "one or more"
    };
    let ratio = t / dt;
    let steps = ratio.round();
    let min = if allow_zero { 0.0 } else { 1.0 };
    if !(t >= 0.0 && t.is_finite() && steps >= min && steps <= MAX_STEPS as f64) {
        return Err(Error::invalid(
            name,
            t,
            format!("{least} steps of dt = {dt}, at most {MAX_STEPS:e} of them"),
        ));
    }
    if (ratio - steps).abs() > 1e-9 * steps.max(1.0) {
        let below = ratio.floor().max(min);
        return Err(Error::invalid(
            name,
            t,
            format!(
                "a whole number of steps of dt = {dt} ({name}/dt = {ratio:.6}; nearest: {} or {})",
                tidy(below * dt),
                tidy((below + 1.0) * dt)
            ),
        ));
    }
    Ok(steps as u64)
}

impl Options {
    /// The number of steps of Δt in [0, T], checked: T finite, a whole number of steps (to
    /// 10⁻⁹ relative; the grid is uniform, so a T between two grid points is refused rather
    /// than silently moved) and at most [`MAX_STEPS`] of them.
    pub fn steps(&self, dt: f64) -> Result<u64> {
        whole_steps("t_end", self.t_end, dt, false)
    }

    /// Check the options for `method` (validated too) and return the number of steps: T a
    /// whole number of steps ([`Options::steps`]), `record_every` ≥ 1 keeping at most
    /// [`MAX_KEPT_SAMPLES`] nodes, `amplitude_periods` in [0, [`MAX_AMPLITUDE_PERIODS`]].
    pub fn validate(&self, method: &PredictorCorrector) -> Result<u64> {
        method.validate()?;
        let steps = self.steps(method.dt)?;
        self.check_recording(steps)?;
        Ok(steps)
    }

    /// The recording options for a path of `steps` steps.
    fn check_recording(&self, steps: u64) -> Result<()> {
        if self.record_every == 0 {
            return Err(Error::invalid("every", 0.0, "1 or more"));
        }
        let every = self.record_every as u64;
        if steps / every + 1 > MAX_KEPT_SAMPLES {
            return Err(Error::invalid(
                "every",
                every as f64,
                format!(
                    "{} or more for {steps} steps (at most {MAX_KEPT_SAMPLES:e} samples are kept)",
                    steps / (MAX_KEPT_SAMPLES - 1) + 1
                ),
            ));
        }
        let periods = self.amplitude_periods;
        if !(0.0..=MAX_AMPLITUDE_PERIODS).contains(&periods) {
            return Err(Error::invalid(
                "amplitude_periods",
                periods,
                "[0, 1e6] periods",
            ));
        }
        Ok(())
    }

    /// Nodes a trajectory of `steps` steps keeps.
    fn kept(&self, steps: u64) -> u64 {
        steps / self.record_every.max(1) as u64 + 1
    }

    /// A stepper for these options' path of `problem`, its memory certified up to T.
    pub fn stepper(&self, problem: &Problem, method: &PredictorCorrector) -> Result<Stepper> {
        method.validate()?;
        let steps = self.steps(method.dt)?;
        Stepper::new(
            problem,
            method,
            (self.seed, self.path),
            steps as f64 * method.dt,
        )
    }
}

/// `x` rounded to 12 significant digits, shortest form: 0.9, not 0.8999999999999999.
fn tidy(x: f64) -> crate::error::Exact {
    let rounded: f64 = format!("{x:.11e}").parse().unwrap_or(x);
    crate::error::Exact(rounded)
}

/// Most steps of one path (at 10⁷ steps/s, three hours).
pub const MAX_STEPS: u64 = 100_000_000_000;
/// Most nodes a [`TrajectoryRecorder`] keeps in memory (four columns: 3.2 GB), and most
/// nodes of all the trajectories of one [`simulate_ensemble`].
pub const MAX_KEPT_SAMPLES: u64 = 100_000_000;
/// Most paths of one ensemble ([`simulate_ensemble`] and the ensembles of the analysis).
pub const MAX_PATHS: usize = 1_000_000;

/// Records a [`Trajectory`]: every `record_every`-th node, the impacts when asked for, and
/// the mean amplitude over the last periods.
#[derive(Debug, Clone)]
pub struct TrajectoryRecorder {
    every: u64,
    /// No node before this step is recorded (the next multiple of `every` after the last one
    /// looked at).
    next_record: u64,
    record_impacts: bool,
    has_noise: bool,
    omega1: f64,
    avg_from: f64,
    amp_sum: f64,
    amp_n: u64,
    out: Trajectory,
}

impl TrajectoryRecorder {
    /// A recorder for `options` on `oscillator` (capacity for `steps` steps of Δt = `dt`, at
    /// most [`MAX_STEPS`] steps, Δt in (0, [`MAX_DT`]]); the recording options are checked
    /// as by [`Options::validate`].
    pub fn new(oscillator: &Oscillator, options: &Options, steps: u64, dt: f64) -> Result<Self> {
        if !(dt > 0.0 && dt <= MAX_DT) {
            return Err(Error::invalid("dt", dt, "(0, 1e3]"));
        }
        if steps > MAX_STEPS {
            return Err(Error::invalid(
                "steps",
                steps as f64,
                format!("0 to {MAX_STEPS:e}"),
            ));
        }
        options.check_recording(steps)?;
        let every = options.record_every as u64;
        let cap = (options.kept(steps) + 1) as usize;
        let has_noise = !oscillator.noise().is_none();
        let omega1 = oscillator.equivalents().omega1;
        let t_end = steps as f64 * dt;
        Ok(TrajectoryRecorder {
            every,
            next_record: 0,
            record_impacts: options.record_impacts,
            has_noise,
            omega1,
            avg_from: t_end - options.amplitude_periods * 2.0 * std::f64::consts::PI / omega1,
            amp_sum: 0.0,
            amp_n: 0,
            out: Trajectory {
                t: Vec::with_capacity(cap),
                u: Vec::with_capacity(cap),
                v: Vec::with_capacity(cap),
                eta: Vec::with_capacity(if has_noise { cap } else { 0 }),
                dt,
                ..Default::default()
            },
        })
    }

    /// The trajectory, with the path's counters.
    pub fn finish(mut self, path: &Stepper) -> Trajectory {
        let (u, v, w) = (path.u(), path.v(), self.omega1);
        let out = &mut self.out;
        out.steps = path.steps() as usize;
        out.impacts = path.impacts() as usize;
        out.sticking_steps = path.sticking_steps() as usize;
        out.final_amplitude = if self.amp_n > 0 {
            self.amp_sum / self.amp_n as f64
        } else {
            (u * u + v * v / (w * w)).sqrt()
        };
        out.exponentials = path.exponentials();
        out.soe_error = path.soe_error();
        out.memory_bytes = path.memory_bytes();
        self.out
    }
}

impl Observer for TrajectoryRecorder {
    #[inline]
    fn observe(&mut self, s: &Stepper) -> Flow {
        let n = s.steps();
        if n > 0 {
            if let Some(i) = s.events().impact {
                if self.record_impacts {
                    self.out.impact_events.push(i);
                }
            }
            let t = s.time();
            if t >= self.avg_from {
                let (u, v) = (s.u(), s.v());
                self.amp_sum += (u * u + v * v / (self.omega1 * self.omega1)).sqrt();
                self.amp_n += 1;
            }
        }
        // n % every only from the next multiple on: an integer division per step would cost
        // more than the rest of the observation
        // (saturating: `every` may be u64::MAX, "record the start only")
        if n >= self.next_record {
            self.next_record = (n / self.every + 1).saturating_mul(self.every);
        }
        if self.next_record - n == self.every {
            self.out.t.push(s.time());
            self.out.u.push(s.u());
            self.out.v.push(s.v());
            if self.has_noise {
                self.out.eta.push(s.eta());
            }
        }
        Flow::Continue
    }
}

/// Simulate the path of `options` (stream `options.path` of `options.seed`, from
/// `problem.start(options.path)`).
pub fn simulate(
    problem: &Problem,
    method: &PredictorCorrector,
    options: &Options,
) -> Result<Trajectory> {
    simulate_with(problem, method, options, &Silent)
}

/// [`simulate`], reporting the steps done to `monitor`, which may stop the run.
pub fn simulate_with(
    problem: &Problem,
    method: &PredictorCorrector,
    options: &Options,
    monitor: &dyn Monitor,
) -> Result<Trajectory> {
    let steps = options.validate(method)?;
    let mut recorder = TrajectoryRecorder::new(problem.oscillator(), options, steps, method.dt)?;
    let mut stepper = options.stepper(problem, method)?;
    run(&mut stepper, steps, &mut recorder, monitor)?;
    Ok(recorder.finish(&stepper))
}

/// Simulate paths 0..`paths` of `options.seed` in parallel (`options.path` is not used), in
/// groups stepped together in lanes ([`run_lanes`] with [`Lanes::Auto`]). Path i depends only on
/// (seed, i), so the result is bit-identical whatever the number of threads and lanes.
/// `paths` is at most [`MAX_PATHS`], and all the trajectories together keep at most
/// [`MAX_KEPT_SAMPLES`] nodes; no paths is an empty ensemble.
pub fn simulate_ensemble(
    problem: &Problem,
    method: &PredictorCorrector,
    options: &Options,
    paths: usize,
) -> Result<Vec<Trajectory>> {
    let steps = options.validate(method)?;
    let kept = options.kept(steps) as f64 * paths as f64;
    if paths > MAX_PATHS || kept > MAX_KEPT_SAMPLES as f64 {
        return Err(Error::invalid(
            "paths",
            paths as f64,
            format!(
                "0 to {} (at most {MAX_PATHS} paths keeping {MAX_KEPT_SAMPLES:e} nodes in all; \
                 {} each here)",
                MAX_PATHS.min((MAX_KEPT_SAMPLES / options.kept(steps)) as usize),
                options.kept(steps)
            ),
        ));
    }
    if paths == 0 {
        return Ok(vec![]);
    }
    let osc = problem.oscillator();
    // build (and verify) the SOE kernel once for all paths
    let history = fresh_history(problem, method, steps as f64 * method.dt)?;
    // groups of paths stepped together in lanes (the same bits as one by one), narrower when
    // there are too few paths to give every thread a group
    let width = group_lanes(Lanes::Auto, paths, 1)?;
    let indices: Vec<u64> = (0..paths as u64).collect();
    let groups: Vec<Vec<Trajectory>> = indices
        .par_chunks(width)
        .map(|group| {
            let mut steppers = group_steppers(problem, method, options.seed, group, &history)?;
            let mut recorders = group
                .iter()
                .map(|_| TrajectoryRecorder::new(osc, options, steps, method.dt))
                .collect::<Result<Vec<_>>>()?;
            let taken = run_lanes(
                &mut steppers,
                steps,
                &mut recorders,
                Lanes::Width(width),
                &Silent,
            )?;
            let mut out = Vec::with_capacity(group.len());
            for ((s, r), t) in steppers.iter().zip(recorders).zip(taken) {
                t?;
                out.push(r.finish(s));
            }
            Ok(out)
        })
        .collect::<Result<_>>()?;
    Ok(groups.into_iter().flatten().collect())
}

/// The result of one path.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Trajectory {
    /// Recorded times.
    pub t: Vec<f64>,
    /// U at the recorded times (Z for [`super::System::Zhuravlev`]).
    pub u: Vec<f64>,
    /// V = U̇ at the recorded times.
    pub v: Vec<f64>,
    /// η at the recorded times (OU: the node value; white: the level of the step that led
    /// there; empty when there is no noise).
    pub eta: Vec<f64>,
    /// Number of impacts.
    pub impacts: usize,
    /// The impacts, when asked for.
    pub impact_events: Vec<Impact>,
    /// Steps that ended clamped at the wall (sticking).
    pub sticking_steps: usize,
    /// Steps taken.
    pub steps: usize,
    /// Step Δt.
    pub dt: f64,
    /// Mean of A = sqrt(U² + V²/ω1²) over the last [`Options::amplitude_periods`] periods.
    pub final_amplitude: f64,
    /// Number of exponentials of the SOE memory (0 for Direct or λ = 1).
    pub exponentials: usize,
    /// The SOE kernel's verified maximal relative error (0 when unused).
    pub soe_error: f64,
    /// Bytes of memory state held at the end of the run.
    pub memory_bytes: usize,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_recorder_keeps_every_kth_node_and_only_the_start_for_the_largest_k() {
        let problem = Problem::from_params(&crate::model::preset("fig1").unwrap().params).unwrap();
        let m = PredictorCorrector::default();
        for (every, times) in [
            (3usize, vec![0.0, 0.03, 0.06, 0.09]),
            (usize::MAX, vec![0.0]),
        ] {
            let o = Options {
                t_end: 0.1,
                seed: 1,
                record_every: every,
                ..Default::default()
            };
            let tr = simulate(&problem, &m, &o).unwrap();
            assert_eq!(tr.t.len(), times.len(), "every {every}");
            for (a, b) in tr.t.iter().zip(&times) {
                assert!((a - b).abs() < 1e-12, "every {every}: {:?}", tr.t);
            }
        }
    }
}
