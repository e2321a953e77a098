//! Well-to-well transition rates of a metastable path by forward flux out of each well's core
//! and adaptive multilevel splitting (AMS) of the excursions, for any [`Walker`] whose whole
//! state can be cloned (the fractional oscillator's memory included).
//!
//! # Problem
//! A path hops between the wells of its amplitude so rarely that a direct simulation sees no
//! transition in its window. The rate k_ij of the jumps from well i to well j is what decides
//! the wells' stationary weights; it must be estimated without waiting 1/k_ij for a jump.
//!
//! # Method
//! A walker reports two variables ([`Observation`]): the *label* amplitude `a` at its
//! observation points (the turning amplitude of the oscillator, once per half-cycle), which
//! sets the cores and the labels, and the *score* after every step, which sets the splitting's
//! levels. Well i's *core* is an interval of `a` ([`Cores`]); a path's label is the last core it
//! visited (the hysteresis of the ensemble's first passages).
//! - **Flux out of the core.** One path per well and replica runs `burn` steps, then `window`
//!   steps in label i. An *exit* upward (downward) is the first observation above (below) the
//!   core after an observation inside it; Φ_i^± = exits / (window · Δt). Up to `clones` exit
//!   states are kept by reservoir sampling (uniform over the exits) as whole cloned walkers,
//!   with their score. Should the path reach another core it is restarted from its latest
//!   re-entry into core i (the state is kept in label i: killed and restarted).
//! - **Probability of reaching the neighbour.** From the exit states, excursions run until
//!   they land in a core (by their label): the target (the neighbouring well's core, i ± 1) is a
//!   success, core i or any other core a failure; the landing step ends the excursion (a
//!   success scores +∞). Generalised AMS with N = `clones` replicas (Cérou & Guyader 2007;
//!   Bréhier, Gazeau, Goudenège, Lelièvre & Rousset 2016): at each iteration the level z is the
//!   k-th lowest maximum of the score (±score) among the replicas, k = ⌈[`KILL_FRACTION`]·N⌉;
//!   every replica whose maximum is ≤ z (K ≥ k of them, ties included) is killed and replaced
//!   by a branch of a uniformly drawn survivor, cloned at its first step with a score above z
//!   and continued with a fresh noise stream (the clone keeps the whole state;
//!   [`Walker::renoise`] changes only the future noise). The estimate
//!   p = Π_n (1 − K_n/N) · (successes at the end)/N is unbiased for any score that is a function
//!   of the walker's state. The state at the first crossing of z is recovered by replaying the
//!   survivor's excursion from its own start with its own stream (deterministic), so a replica
//!   holds one clone.
//! - **The score.** A score whose short-time increments are deterministic (smooth in time, as
//!   every amplitude of an oscillator driven by coloured noise is) makes the branches of a
//!   survivor cloned at its own maximum fall back together: all replicas end with the same
//!   maximum and the splitting dies out (every replica killed: p = 0 for that run). Setting the
//!   level at the k-th lowest maximum rather than the lowest puts it below most survivors'
//!   maxima, so branches start while their parents still climb.
//! - **Resolution.** Where every replica died out, or any stopped at `max_iterations`, the
//!   splitting only bounds p by the estimated probability of passing the farthest level it
//!   reached ([`Transition::level_probability`]); the caller decides whether the bound matters.
//! - **Rate.** k_{i,i±1} = Φ_i^± p_i^±. Transitions that jump over a well are counted as
//!   failures: the rates of a birth–death chain.
//!
//! Everything is a function of (seed, replica, well, direction): bit-identical whatever the
//! number of threads.
//!
//! # Reference
//! Allen, Frenkel & ten Wolde, J. Chem. Phys. 124 (2006) 024102 (forward-flux sampling);
//! Cérou & Guyader, Stoch. Anal. Appl. 25 (2007) 417 (AMS); Bréhier et al., Ann. Appl. Probab.
//! 26 (2016) 3559 (the unbiased estimator with ties).
//!
//! # Tests
//! `tests/wells.rs`: the rates of the averaged amplitude diffusion dA = m1 dt + √σ1 dW (the
//! theory's m1, σ1) against its exact mean first-passage times over more than six decades;
//! unit tests below: AMS (with k = ⌈0.1 N⌉) on a random walk with a closed-form hitting
//! probability.

use super::spec::Wells;
use crate::error::{Error, Result};
use crate::monitor::Monitor;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// The cores of the wells on the order parameter: disjoint, ascending intervals [lo, hi], one
/// per well. A path's label is the last core it visited.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Cores {
    /// [lo, hi] of each well's core, ascending and disjoint.
    pub bounds: Vec<(f64, f64)>,
}

impl Cores {
    /// The cores of [`Wells::core`]: closer to the mode than half the distance to the
    /// neighbouring antimodes.
    pub fn of_wells(wells: &Wells) -> Self {
        Cores {
            bounds: (0..wells.len()).map(|k| wells.core(k)).collect(),
        }
    }

    /// Checked cores: at least one, each lo ≤ hi (not NaN), ascending and disjoint.
    pub fn new(bounds: Vec<(f64, f64)>) -> Result<Self> {
        let ok = !bounds.is_empty()
            && bounds.iter().all(|(lo, hi)| lo <= hi)
            && bounds.windows(2).all(|w| w[0].1 < w[1].0);
        if !ok {
            return Err(Error::invalid(
                "cores",
                bounds.len() as f64,
                "one or more intervals lo ≤ hi, ascending and disjoint",
            ));
        }
        Ok(Cores { bounds })
    }

    /// Number of cores.
    pub fn len(&self) -> usize {
        self.bounds.len()
    }

    /// True when there are none (never for checked cores).
    pub fn is_empty(&self) -> bool {
        self.bounds.is_empty()
    }

    /// The core (well) holding `a`, if any.
    #[inline]
    pub fn core_of(&self, a: f64) -> Option<usize> {
        let k = self.bounds.partition_point(|&(_, hi)| hi < a);
        (k < self.bounds.len() && a >= self.bounds[k].0).then_some(k)
    }
}

/// What a walker reports after each step: the splitting's score variable (every step) and,
/// at its observation points, the amplitude that sets the labels.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Observation {
    /// The reaction coordinate of the splitting's levels (an amplitude ≥ 0), every step.
    pub score: f64,
    /// The label variable (an amplitude ≥ 0, the cores' coordinate) when the step ends at an
    /// observation point (a turning point), else `None`.
    pub label: Option<f64>,
}

impl Observation {
    /// One variable for both: the score and, every step, the label.
    #[inline]
    pub fn every_step(a: f64) -> Self {
        Observation {
            score: a,
            label: Some(a),
        }
    }
}

/// A path whose whole state can be cloned and whose future noise can be redrawn.
pub trait Walker: Clone + Send + Sync {
    /// Advance one step: its score and, at an observation point, its label amplitude.
    fn advance(&mut self) -> Result<Observation>;
    /// Draw the future noise from stream `stream` of `seed`, keeping the state.
    fn renoise(&mut self, seed: u64, stream: u64);
}

/// Sizes of the splitting.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Splitting {
    /// Seed of every noise stream.
    pub seed: u64,
    /// Time step of the walker.
    pub dt: f64,
    /// AMS replicas N per transition (and exit states kept per direction).
    pub clones: usize,
    /// Steps discarded at the start of each well's path.
    pub burn: u64,
    /// Steps of each well's path in its label (the flux's time).
    pub window: u64,
    /// Longest excursion, in steps, before it is counted as a failure.
    pub max_excursion: u64,
    /// Most AMS iterations per transition (the estimate is marked incomplete beyond).
    pub max_iterations: usize,
}

/// Least AMS replicas.
pub const MIN_CLONES: usize = 4;
/// Most AMS replicas.
pub const MAX_CLONES: usize = 100_000;

impl Splitting {
    /// `clones` in [[`MIN_CLONES`], [`MAX_CLONES`]], `window` ≥ 1, `max_excursion` ≥ 1,
    /// `max_iterations` ≥ 1.
    pub fn validate(&self) -> Result<()> {
        if !(MIN_CLONES..=MAX_CLONES).contains(&self.clones) {
            return Err(Error::invalid(
                "clones",
                self.clones as f64,
                format!("{MIN_CLONES} to {MAX_CLONES}"),
            ));
        }
        if !(self.dt > 0.0 && self.dt.is_finite()) {
            return Err(Error::invalid("dt", self.dt, "(0, ∞), finite"));
        }
        if self.window == 0 {
            return Err(Error::invalid("t_end", 0.0, "at least one step"));
        }
        if self.max_excursion == 0 {
            return Err(Error::invalid("max_excursion", 0.0, "at least one step"));
        }
        if self.max_iterations == 0 {
            return Err(Error::invalid("max_iterations", 0.0, "1 or more"));
        }
        Ok(())
    }
}

/// Up (toward well i + 1) or down (toward well i − 1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Direction {
    /// Toward the next well up.
    Up,
    /// Toward the next well down.
    Down,
}

impl Direction {
    fn index(self) -> u64 {
        match self {
            Direction::Up => 0,
            Direction::Down => 1,
        }
    }
    fn score(self, a: f64) -> f64 {
        match self {
            Direction::Up => a,
            Direction::Down => -a,
        }
    }
}

/// What one well's path found: its exits, its time, what it cost.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct WellPath {
    /// The well.
    pub well: usize,
    /// Exits upward and downward from the core.
    pub exits: [u64; 2],
    /// Time in the label (the window).
    pub time: f64,
    /// Transitions to another core seen directly (each followed by a restart).
    pub restarts: u64,
    /// Steps taken (burn-in and window).
    pub steps: u64,
}

/// One transition's estimate from one replica.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Transition {
    /// Well left.
    pub from: usize,
    /// Well reached.
    pub to: usize,
    /// Exits per unit time toward `to` (Φ).
    pub flux: f64,
    /// Probability that an exit reaches the core of `to` before returning (AMS).
    pub probability: f64,
    /// k = Φ·p.
    pub rate: f64,
    /// AMS replicas used.
    pub clones: usize,
    /// Distinct exit states they started from (the replicas draw them with replacement when
    /// fewer exits than replicas were seen).
    pub distinct_starts: usize,
    /// AMS iterations.
    pub iterations: usize,
    /// The farthest amplitude level the splitting passed toward `to` (the exits' own level
    /// before the first iteration), and the estimated probability that an exit passes it:
    /// where the splitting died out (every replica at the same level, `probability` 0), this
    /// says how far it got — p is below `level_probability`.
    pub level: f64,
    /// The estimated probability of passing `level`.
    pub level_probability: f64,
    /// Excursions that reached the step limit (counted as failures).
    pub unended: u64,
    /// AMS finished before its iteration limit.
    pub complete: bool,
    /// Steps of the AMS (excursions and replays).
    pub steps: u64,
}

/// A stream number for (replica, well, purpose, counter): splitmix64 of the tuple.
pub(super) fn stream(replica: u64, well: usize, purpose: u64, counter: u64) -> u64 {
    let mut z = replica
        .wrapping_mul(0x9E37_79B9_7F4A_7C15)
        .wrapping_add((well as u64).wrapping_mul(0xC2B2_AE3D_27D4_EB4F))
        .wrapping_add(purpose.wrapping_mul(0x1656_67B1_9E37_79F9))
        .wrapping_add(counter)
        .wrapping_add(0x5745_4C4C_5300_0000); // "WELLS"
    for _ in 0..2 {
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
    }
    z
}

/// A small deterministic generator for the reservoir and the survivors' draws.
pub(super) struct Draws(u64);

impl Draws {
    pub(super) fn new(s: u64) -> Self {
        Draws(s)
    }
    /// Uniform in 0..n.
    pub(super) fn below(&mut self, n: usize) -> usize {
        self.0 = stream(self.0, 0, 7, 1);
        ((self.0 >> 11) as f64 / (1u64 << 53) as f64 * n as f64) as usize % n.max(1)
    }
}

/// The exit states of one well's path: per direction, up to `clones` walkers with the level
/// at which they left.
pub(super) type Exits<W> = [Vec<(W, f64)>; 2];

/// Run well `well`'s path of replica `replica`: `burn` steps, then `window` steps in label
/// `well`, `record` called after every window step (with the walker in label `well`).
pub(super) fn well_path<W: Walker>(
    mut w: W,
    well: usize,
    wells: &Cores,
    sp: &Splitting,
    replica: u64,
    monitor: &dyn Monitor<()>,
    record: &mut dyn FnMut(&W),
) -> Result<(WellPath, Exits<W>)> {
    w.renoise(sp.seed, stream(replica, well, 0, 0));
    let (lo, hi) = wells.bounds[well];
    let mut draws = Draws::new(stream(replica, well, 1, 0));
    let mut exits: Exits<W> = [Vec::new(), Vec::new()];
    let mut seen = [0u64; 2];
    let mut steps = 0u64;
    // the path starts in core `well`; a visit to another core sends it back to its latest
    // re-entry into this core (or, in the burn-in, to its start)
    let mut armed = true;
    let mut home = w.clone();
    let mut restarts = 0u64;
    for n in 0..sp.burn {
        if let Some(a) = w.advance()?.label {
            match wells.core_of(a) {
                Some(k) if k == well => armed = true,
                Some(_) => {
                    restarts += 1;
                    w = home.clone();
                    w.renoise(sp.seed, stream(replica, well, 2, restarts));
                    armed = true;
                }
                None => {}
            }
        }
        if n % (1 << 16) == 0 {
            monitor.check()?;
        }
    }
    steps += sp.burn;
    // the burn-in ends at the first observation inside the core (the window's first home)
    let mut extra = 0u64;
    loop {
        if let Some(a) = w.advance()?.label {
            extra += 1;
            match wells.core_of(a) {
                Some(k) if k == well => break,
                Some(_) => {
                    restarts += 1;
                    w = home.clone();
                    w.renoise(sp.seed, stream(replica, well, 2, restarts));
                }
                None => {}
            }
        } else {
            extra += 1;
        }
        if extra % (1 << 16) == 0 {
            monitor.check()?;
        }
        if extra > sp.window.max(sp.max_excursion) {
            return Err(Error::Undefined {
                what: "a well's path",
                why: format!(
                    "it did not come back to the core of well {well} within {extra} steps after \
                     its burn-in"
                ),
            });
        }
    }
    steps += extra;
    home = w.clone();
    let burn_restarts = restarts;
    for n in 0..sp.window {
        let o = w.advance()?;
        if let Some(a) = o.label {
            match wells.core_of(a) {
                Some(k) if k == well => {
                    if !armed {
                        home = w.clone();
                    }
                    armed = true;
                }
                Some(_) => {
                    // a transition seen directly: back to the latest re-entry, in label `well`
                    restarts += 1;
                    w = home.clone();
                    w.renoise(sp.seed, stream(replica, well, 2, restarts));
                    armed = true;
                }
                None if armed => {
                    armed = false;
                    let d = if a > hi {
                        Direction::Up
                    } else if a < lo {
                        Direction::Down
                    } else {
                        unreachable!("outside the core but neither above nor below")
                    };
                    let k = d.index() as usize;
                    seen[k] += 1;
                    // reservoir sampling: each exit kept with probability clones / seen
                    if exits[k].len() < sp.clones {
                        exits[k].push((w.clone(), o.score));
                    } else {
                        let j = draws.below(seen[k] as usize);
                        if j < sp.clones {
                            exits[k][j] = (w.clone(), o.score);
                        }
                    }
                }
                None => {}
            }
        }
        record(&w);
        if n % (1 << 16) == 0 {
            monitor.check()?;
        }
    }
    steps += sp.window;
    Ok((
        WellPath {
            well,
            exits: seen,
            time: sp.window as f64 * sp.dt,
            restarts: restarts - burn_restarts,
            steps,
        },
        exits,
    ))
}

/// The fraction of the AMS replicas killed at each iteration (at least one): the level is the
/// k-th lowest maximum, k = ⌈fraction·N⌉. Killing more than the lowest one sets the level below
/// most survivors' maxima, so that a branch starts where its parent was still climbing: with a
/// smooth score (the phase-averaged amplitude) the branches of a parent cloned at its very
/// maximum would all fall back together and the splitting die out. The estimator stays
/// unbiased for every k (Bréhier et al. 2016).
pub const KILL_FRACTION: f64 = 0.1;

/// k of [`KILL_FRACTION`] for `n` replicas: ⌈fraction·n⌉, at least 1, below n.
fn kill_count(n: usize) -> usize {
    ((KILL_FRACTION * n as f64).ceil() as usize).clamp(1, n.saturating_sub(1).max(1))
}

/// One AMS replica: where its excursion starts, its stream, its best score and fate.
#[derive(Clone)]
struct Replica<W> {
    start: W,
    start_score: f64,
    stream: u64,
    max: f64,
    success: bool,
}

/// What an excursion did.
struct Excursion<W> {
    max: f64,
    success: bool,
    unended: bool,
    steps: u64,
    /// Where a replay asked for a level stopped: the state at the first step whose score
    /// exceeds the level, with that score, or the landing in the target core first (a success:
    /// the target's score is +∞).
    branch: Option<Branch<W>>,
}

/// A branch point found by a replay.
enum Branch<W> {
    /// The state at the first step above the level, and its score.
    Above(W, f64),
    /// The replay landed in the target core before its finite score passed the level.
    Landed,
}

/// Run the excursion of `start` (score `start_score`) with stream `stream` until it lands in a
/// core (by its label), or, when `above` is given, until its first step with a score above it.
/// The landing step ends the excursion before its score counts: a landing is scored +∞ (the
/// target) or ends the path (any other core), so run and replay agree step by step.
#[allow(clippy::too_many_arguments)]
fn excursion<W: Walker>(
    start: &W,
    start_score: f64,
    stream: u64,
    seed: u64,
    to: usize,
    d: Direction,
    wells: &Cores,
    max_steps: u64,
    above: Option<f64>,
) -> Result<Excursion<W>> {
    let mut w = start.clone();
    w.renoise(seed, stream);
    let mut max = start_score;
    for n in 1..=max_steps {
        let o = w.advance()?;
        if let Some(k) = o.label.and_then(|a| wells.core_of(a)) {
            let success = k == to;
            return Ok(Excursion {
                max,
                success,
                unended: false,
                steps: n,
                branch: (success && above.is_some()).then_some(Branch::Landed),
            });
        }
        let s = d.score(o.score);
        if let Some(z) = above {
            if s > z {
                return Ok(Excursion {
                    max: s,
                    success: false,
                    unended: false,
                    steps: n,
                    branch: Some(Branch::Above(w, s)),
                });
            }
        }
        if s > max {
            max = s;
        }
    }
    Ok(Excursion {
        max,
        success: false,
        unended: true,
        steps: max_steps,
        branch: None,
    })
}

/// The replica that replaces a killed one at level `z`: a branch of `parent` where its replay
/// first passes `z` (where it starts, if it starts above), then run with stream `stream` until
/// it lands; with the steps computed and whether its excursion was cut.
fn branch<W: Walker>(
    parent: &Replica<W>,
    z: f64,
    stream: u64,
    run: &(impl Fn(&Replica<W>, Option<f64>) -> Result<Excursion<W>> + Sync),
) -> Result<(Replica<W>, u64, u64)> {
    let mut steps = 0;
    let found = if parent.start_score > z {
        // the parent starts above the level: the branch starts where it does
        Some(Branch::Above(parent.start.clone(), parent.start_score))
    } else {
        let e = run(parent, Some(z))?;
        steps += e.steps;
        e.branch
    };
    let (w, s, landed) = match found {
        Some(Branch::Above(w, s)) => (w, s, false),
        // the parent entered the target before its score passed the level: the branch is that
        // success
        Some(Branch::Landed) => (parent.start.clone(), parent.start_score, true),
        None => {
            return Err(Error::Undefined {
                what: "an AMS branch",
                why: "the replay of a survivor did not pass its own maximum (the walker is not \
                      deterministic given its stream)"
                    .into(),
            })
        }
    };
    let mut r = Replica {
        start: w,
        start_score: s,
        stream,
        max: f64::NEG_INFINITY,
        success: false,
    };
    let mut unended = 0;
    if landed {
        r.max = f64::INFINITY;
        r.success = true;
    } else {
        let e = run(&r, None)?;
        steps += e.steps;
        unended += e.unended as u64;
        r.max = if e.success { f64::INFINITY } else { e.max };
        r.success = e.success;
    }
    Ok((r, steps, unended))
}

/// The probability that an exit of well `from` in direction `d` reaches the core of `to`
/// before any other core, by AMS from the exit states `starts`.
#[allow(clippy::too_many_arguments)]
pub(super) fn ams<W: Walker>(
    starts: Vec<(W, f64)>,
    from: usize,
    to: usize,
    d: Direction,
    wells: &Cores,
    sp: &Splitting,
    replica: u64,
    monitor: &dyn Monitor<()>,
) -> Result<Transition> {
    // fewer exits than replicas: the replicas start from exits drawn with replacement (each
    // with a noise stream of its own)
    let distinct = starts.len();
    let mut starts = starts;
    if distinct > 0 && distinct < sp.clones {
        let mut pick = Draws::new(stream(replica, from, 20 + d.index(), 0));
        for _ in distinct..sp.clones {
            let k = pick.below(distinct);
            starts.push(starts[k].clone());
        }
    }
    let n = starts.len();
    let mut t = Transition {
        from,
        to,
        flux: 0.0,
        probability: 0.0,
        rate: 0.0,
        clones: n,
        distinct_starts: distinct,
        iterations: 0,
        level: f64::NAN,
        level_probability: 1.0,
        unended: 0,
        complete: true,
        steps: 0,
    };
    if n == 0 {
        return Ok(t);
    }
    let purpose = 10 + d.index();
    let mut counter = 0u64;
    let mut next_stream = || {
        counter += 1;
        stream(replica, from, purpose, counter)
    };
    let run = |r: &Replica<W>, above: Option<f64>| {
        excursion(
            &r.start,
            r.start_score,
            r.stream,
            sp.seed,
            to,
            d,
            wells,
            sp.max_excursion,
            above,
        )
    };
    // the excursions of a stage are independent tasks; their streams and parents are drawn
    // in order beforehand, and their results put back in order: the bits do not depend on
    // the threads
    let streams: Vec<u64> = (0..n).map(|_| next_stream()).collect();
    let first: Vec<(Replica<W>, u64, u64)> = crate::profile::parallel(|stage| {
        starts
            .into_par_iter()
            .zip(streams)
            .map(|((w, a), stream)| {
                stage.task(|| {
                    let mut r = Replica {
                        start: w,
                        start_score: d.score(a),
                        stream,
                        max: f64::NEG_INFINITY,
                        success: false,
                    };
                    let e = run(&r, None)?;
                    r.max = if e.success { f64::INFINITY } else { e.max };
                    r.success = e.success;
                    Ok((r, e.steps, e.unended as u64))
                })
            })
            .collect::<Result<_>>()
    })?;
    let mut reps = Vec::with_capacity(n);
    for (r, steps, unended) in first {
        t.steps += steps;
        t.unended += unended;
        reps.push(r);
    }
    let mut draws = Draws::new(stream(replica, from, purpose + 100, 0));
    let mut log_p = 0.0f64;
    loop {
        monitor.check()?;
        // the level: the k-th lowest maximum (k = ⌈KILL_FRACTION·N⌉)
        let mut maxes: Vec<f64> = reps.iter().map(|r| r.max).collect();
        let k = kill_count(n);
        let (_, &mut z, _) = maxes.select_nth_unstable_by(k - 1, f64::total_cmp);
        if z == f64::INFINITY {
            break; // all but fewer than k replicas reached the target (the rest fail)
        }
        let killed: Vec<usize> = (0..n).filter(|&k| reps[k].max <= z).collect();
        if killed.len() == n {
            // extinction: no replica above the level
            t.probability = 0.0;
            t.iterations += 1;
            return Ok(t);
        }
        if t.iterations >= sp.max_iterations {
            t.complete = false;
            break;
        }
        t.iterations += 1;
        log_p += crate::maths::ln(1.0 - killed.len() as f64 / n as f64);
        t.level = d.score(z);
        t.level_probability = crate::maths::exp(log_p);
        let survivors: Vec<usize> = (0..n).filter(|&k| reps[k].max > z).collect();
        // (killed replica, its parent among the survivors, its stream), drawn in order
        let jobs: Vec<(usize, usize, u64)> = killed
            .iter()
            .map(|&k| (k, survivors[draws.below(survivors.len())], next_stream()))
            .collect();
        let reps_now = &reps;
        let branches: Vec<(usize, Replica<W>, u64, u64)> = crate::profile::parallel(|stage| {
            jobs.par_iter()
                .map(|&(k, parent, stream)| {
                    stage.task(|| {
                        let (r, steps, unended) = branch(&reps_now[parent], z, stream, &run)?;
                        Ok((k, r, steps, unended))
                    })
                })
                .collect::<Result<_>>()
        })?;
        for (k, r, steps, unended) in branches {
            t.steps += steps;
            t.unended += unended;
            reps[k] = r;
        }
    }
    let successes = reps.iter().filter(|r| r.success).count();
    t.probability = crate::maths::exp(log_p) * successes as f64 / n as f64;
    Ok(t)
}

/// The rates of one replica (numbered `replica`: its noise streams): a path per well
/// (`walkers[i]` starts in well i's core), then the AMS of every exit toward a neighbour.
/// Returns the wells' paths and the transitions i → i ± 1, in the order (0 → 1, 1 → 0, 1 → 2,
/// 2 → 1, …).
pub fn replica_rates<W: Walker>(
    walkers: Vec<W>,
    wells: &Cores,
    sp: &Splitting,
    replica: u64,
    monitor: &dyn Monitor<()>,
) -> Result<(Vec<WellPath>, Vec<Transition>)> {
    sp.validate()?;
    let wells = &Cores::new(wells.bounds.clone())?;
    if walkers.len() != wells.len() {
        return Err(Error::invalid(
            "walkers",
            walkers.len() as f64,
            format!("one per well ({})", wells.len()),
        ));
    }
    let mut paths = Vec::new();
    let mut all_exits = Vec::new();
    for (i, w) in walkers.into_iter().enumerate() {
        let (p, e) = well_path(w, i, wells, sp, replica, monitor, &mut |_| {})?;
        paths.push(p);
        all_exits.push(e);
    }
    let mut transitions = Vec::new();
    for (i, j, d) in neighbours(wells.len()) {
        let starts = std::mem::take(&mut all_exits[i][d.index() as usize]);
        let mut t = ams(starts, i, j, d, wells, sp, replica, monitor)?;
        t.flux = paths[i].exits[d.index() as usize] as f64 / paths[i].time;
        t.rate = t.flux * t.probability;
        transitions.push(t);
    }
    Ok((paths, transitions))
}

/// The transitions between neighbours of `n` wells: (from, to, direction), in the order
/// 0 → 1, 1 → 0, 1 → 2, 2 → 1, …
pub fn neighbours(n: usize) -> Vec<(usize, usize, Direction)> {
    (0..n.saturating_sub(1))
        .flat_map(|i| [(i, i + 1, Direction::Up), (i + 1, i, Direction::Down)])
        .collect()
}

/// The stationary weights of a birth–death chain of wells from its rates up (k_{i,i+1}) and
/// down (k_{i+1,i}): π_{i+1}/π_i = k_{i,i+1}/k_{i+1,i} (the net flux across every gap
/// vanishes), in logarithms so that rates decades apart neither overflow nor underflow. A zero
/// rate cuts the chain: the wells from which the path cannot come back (transient) get weight
/// 0, and the weights are those of the one closed class of wells. `None` when a rate is
/// negative or not finite, or when two classes are closed (each keeps its mass: the weights
/// depend on the start).
pub fn chain_weights(up: &[f64], down: &[f64]) -> Option<Vec<f64>> {
    if up.len() != down.len() || up.iter().chain(down).any(|k| !(k.is_finite() && *k >= 0.0)) {
        return None;
    }
    let n = up.len() + 1;
    // segments of wells joined by gaps with both rates positive
    let mut segments = Vec::new();
    let mut start = 0;
    for g in 0..n - 1 {
        if !(up[g] > 0.0 && down[g] > 0.0) {
            segments.push((start, g));
            start = g + 1;
        }
    }
    segments.push((start, n - 1));
    let closed: Vec<(usize, usize)> = segments
        .into_iter()
        .filter(|&(a, b)| (a == 0 || down[a - 1] == 0.0) && (b == n - 1 || up[b] == 0.0))
        .collect();
    let [(a, b)] = closed[..] else {
        return None;
    };
    let mut log = vec![f64::NEG_INFINITY; n];
    log[a] = 0.0;
    for g in a..b {
        log[g + 1] = log[g] + crate::maths::ln(up[g]) - crate::maths::ln(down[g]);
    }
    let top = log.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let w: Vec<f64> = log.iter().map(|l| crate::maths::exp(l - top)).collect();
    let s: f64 = w.iter().sum();
    Some(w.iter().map(|x| x / s).collect())
}

#[cfg(test)]
mod tests {
    #[test]
    fn chain_weights_balance_the_fluxes() {
        let w = chain_weights(&[1e-30, 2.0], &[1.0, 1.0]).unwrap();
        assert!((w[1] / w[0] - 1e-30).abs() < 1e-42);
        assert!((w[2] / w[1] - 2.0).abs() < 1e-12);
        assert!((w.iter().sum::<f64>() - 1.0).abs() < 1e-15);
        // 0 → 1 never: well 0 is closed, well 1 transient
        assert_eq!(chain_weights(&[0.0], &[1.0]).unwrap(), vec![1.0, 0.0]);
        // 1 ⇄ 2 never, 0 → 1 only: wells 1 and 2 both closed
        assert!(chain_weights(&[1.0, 0.0], &[0.0, 0.0]).is_none());
        // 0 → 1 only, 1 ⇄ 2 both ways: the class {1, 2}
        let w = chain_weights(&[1.0, 3.0], &[0.0, 1.0]).unwrap();
        assert_eq!(w[0], 0.0);
        assert!((w[2] / w[1] - 3.0).abs() < 1e-12);
        assert!(chain_weights(&[f64::NAN], &[1.0]).is_none());
    }

    use super::*;

    /// A lazy random walk on the integers, observed every step: from 1 it reaches N before 0
    /// with probability 1/N (gambler's ruin).
    #[derive(Clone)]
    struct Ruin {
        x: i64,
        draws: u64,
    }

    impl Walker for Ruin {
        fn advance(&mut self) -> Result<Observation> {
            self.draws = stream(self.draws, 0, 3, 0);
            self.x += if self.draws >> 63 == 1 { 1 } else { -1 };
            Ok(Observation::every_step(self.x as f64))
        }
        fn renoise(&mut self, seed: u64, s: u64) {
            self.draws = stream(seed, 0, s, 0);
        }
    }

    #[test]
    fn ams_gives_the_gamblers_ruin_probability() {
        // wells: core 0 = [0, 0.5] and core 1 from 39.5: exits at 1 reach 40 with p = 1/40
        let wells = Cores::of_wells(&Wells::new(vec![0.0, 40.0], vec![20.0]).unwrap());
        assert_eq!(wells.bounds[0], (0.0, 10.0));
        assert_eq!(wells.core_of(10.0), Some(0));
        assert_eq!(wells.core_of(10.5), None);
        assert_eq!(wells.core_of(30.0), Some(1));
        // cores are half-way to the antimode: use a walk shifted so that the exit is at 11,
        // the target at 30 = core 1's lower edge, the return at 10: p = 1/20
        let sp = Splitting {
            seed: 5,
            dt: 1.0,
            clones: 50,
            burn: 0,
            window: 1,
            max_excursion: 1_000_000,
            max_iterations: 100_000,
        };
        let mut ps = Vec::new();
        for rep in 0..40 {
            let starts = (0..50).map(|_| (Ruin { x: 11, draws: 0 }, 11.0)).collect();
            let t = ams(
                starts,
                0,
                1,
                Direction::Up,
                &wells,
                &sp,
                rep,
                &crate::monitor::Silent,
            )
            .unwrap();
            assert!(t.complete);
            ps.push(t.probability);
        }
        let m = ps.iter().sum::<f64>() / ps.len() as f64;
        let sd = (ps.iter().map(|p| (p - m) * (p - m)).sum::<f64>() / (ps.len() as f64 - 1.0))
            .sqrt()
            / (ps.len() as f64).sqrt();
        assert!((m - 0.05).abs() < 4.0 * sd, "{m} ± {sd}");
        assert!(sd < 0.01, "{sd}");
    }
}
