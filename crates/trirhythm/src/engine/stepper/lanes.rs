//! The lane stepper: several paths (of one problem, or each of its own) advanced together, the
//! arithmetic of their step in structure-of-arrays form so that one vector instruction serves
//! every path; a path's tangent can go with it.
//!
//! # Equation
//! The step of [`Stepper::step`] (module docs of [`super`]), unchanged: for each path the
//! damped Taylor predictor U^P, the linearly implicit corrector
//! V₁ = (known + w(f − ω²U^P))/(1 − w·μP(U^P)), the Hermite-corrected U₁, the second pass from
//! the first's U₁, and at the end the node's drift μP(U₁)V₁ − ω²U₁ and predictor weight.
//!
//! # Method
//! A step of L paths (L = 4 or 8) runs in five phases: (1) per path, the noise and the numbers
//! the step needs from the state ([`Stepper::begin`]); (2) for all L at once, the polynomial
//! μP, the predictor, both divisions and the corrector in arrays `[f64; L]`, twice (the two
//! passes); (3) per path, the
//! events (sticking, an impact located and the rest of the step redone, blow-up) by the scalar
//! stepper's own code, only for the lanes that have them; (4) for all L, the node's μP, drift
//! and predictor weight; (5) per path, the piece of g into its memory. Every lane performs the
//! scalar stepper's operations in the scalar stepper's order (the same functions, evaluated
//! element by element; no fused multiply–add, which Rust never forms by itself), so path i
//! gives the same bits in a lane as alone, whatever the lane count, its position, the other
//! paths and the ISA the arrays are compiled for. The arrays are compiled twice — for AVX2 (four
//! doubles a vector) and for the baseline target — and the version is chosen at run time from
//! the CPU's features ([`is_x86_feature_detected!`]). Eight lanes are the default on every CPU:
//! measured on the fig13a paths (8 paths × 10⁶ steps, the stepper alone, wall time of two or
//! three runs on the shared machine), eight lanes
//! took 43.6 ns per path-step at λ = 0.998 and 24.2 at λ = 1 with AVX2, 44.7 and 25.8 with the
//! portable arrays, against 49.2 / 31.4 and 47.7 / 29.1 with four; arrays compiled for AVX-512
//! were 2–5 % slower than AVX2's (43.8 / 25.3), so they are not built.
//!
//! **Lanes of different problems.** The oscillation searches run several parameter values at
//! once (μ0, λ, ω0 or r differing from lane to lane), which share no problem. The array phases
//! are generic over where their coefficients come from ([`Coefficients`]): [`Shared`] reads the
//! first path's (one problem, the ensembles and the Lyapunov realisations: the code as before),
//! [`PerLane`] holds the coefficients of the polynomial μP, Δt, the weight w_r and ω² as arrays
//! `[f64; L]`, so each lane performs the scalar stepper's operations with its own numbers and
//! gives its own bits; the per-path phases are the scalar code and never shared anything.
//! Grouping the simulations that share a problem instead would leave the searches nothing to
//! group (every probe has its own parameter value). Polynomials of different forms (degree ≤ 7
//! in U² against higher) cannot share one evaluation: such a group is stepped path by path.
//! Measured (`examples/drivers_timing.rs`, 8 fig13a paths × 2·10⁵ steps, λ = 0.998, the stepper
//! alone, one thread, medians of CPU time): shared 42.5 ns per path-step, per-lane 42.5 (μ0
//! changed in its last digits so that the eight lanes' problems differ), scalar 61; and the
//! shared step against the one before the generic coefficients (the same timing loop built from
//! both, three alternations): 42.4 / 23.0 ns at λ = 0.998 / 1 before, 42.5 / 23.5 after — the
//! same within the run-to-run spread.
//!
//! **Paths with their tangents** ([`step_group_tangent`], the tangent method of the Lyapunov
//! exponent): the same phases, the tangent's linearised step beside the path's — μP and its
//! slope at the start, at each pass's predictor and at the end evaluated in arrays across lanes,
//! the tangent's passes lane by lane with the path's quantities of the step, the derivative of
//! its impact steps and its memory per path by the scalar code ([`Stepper::step_with_tangent`] is split
//! into the same phases, so the bits are the same by construction). Measured at Fig. 17(a)'s
//! sizes (8 realisations, `examples/drivers_timing.rs`): 1.08–1.13× with four lanes, 1.00–1.04×
//! with eight — the two memory pushes per step (path and tangent), the deviates and the impacts
//! are per-path work and take most of the step.
//!
//! What it gains: one path's step is bound by the latency of its dependency chain (two
//! evaluations of P, two divisions, the memory's last addition); L independent chains overlap
//! and their arithmetic shares the vector instructions. What it does not change: the memory's
//! mode update (already four modes per AVX instruction for one path), the noise generator (one
//! ChaCha8 stream per path) and the impacts are per-path work (see docs/numerics.md, Speed, for
//! the measured split). The lane groups' width for a thread pool is [`group_lanes`].
//!
//! # Reference
//! Structure-of-arrays vectorisation across independent Monte Carlo paths (e.g. the SIMD
//! "lanes" of path-parallel SDE solvers); the method itself is [`super`]'s.
//!
//! # Tests
//! `tests/lanes.rs`: paths in lanes of 1, 4 and 8, in every position and batch split, give the
//! scalar stepper's bits (U, V, counts, the whole memory) for random parameters with impacts,
//! sticking, stiff steps, white, coloured and no noise, λ < 1 and λ = 1, both impact memories,
//! the equivalent and Zhuravlev systems, and so do groups of paths of different problems (each
//! its own parameters, Δt, memory and system) and of polynomials of different forms; the
//! ensemble's statistics and the Lyapunov exponents (both methods) are identical for
//! `--lanes 1`, 4 and 8. The unit tests below: paths with their tangents in lanes of 4 and 8
//! give `step_with_tangent`'s bits step by step (path, tangent state and tangent memory) over
//! random parameters, with impacts, sticking and stiff steps.

// element i of every array, lane by lane: the form the loop vectoriser takes and the scalar
// stepper's expressions read the same
#![allow(clippy::needless_range_loop)]

use super::polynomial::LanePolynomial;
use super::tangent::{TangentBegin, TangentEnd};
use super::{node_with, pass_with, Affine, Begin, End, Free, Pass, Stepper, Tangent};
use crate::error::{Error, Result};

/// How many paths the drivers step together.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Lanes {
    /// The count that is fastest on this CPU ([`detected_lanes`]).
    #[default]
    Auto,
    /// 1 (the scalar stepper, one path after the other), 4 or 8.
    Width(usize),
}

/// The lane counts [`Lanes::Width`] accepts.
pub const LANE_WIDTHS: [usize; 3] = [1, 4, 8];

impl Lanes {
    /// The number of paths stepped together: [`detected_lanes`] for `Auto`, else the width,
    /// which must be 1, 4 or 8.
    pub fn width(self) -> Result<usize> {
        match self {
            Lanes::Auto => Ok(detected_lanes()),
            Lanes::Width(w) if LANE_WIDTHS.contains(&w) => Ok(w),
            Lanes::Width(w) => Err(Error::invalid("lanes", w as f64, "1, 4 or 8")),
        }
    }
}

/// The lane count that suits this CPU: 8. Measured (module docs): eight lanes beat four at
/// λ = 0.998 and at λ = 1, with the AVX2 arrays and with the portable ones alike (the gain is
/// the overlap of the paths' dependency chains more than the vector width); the AVX-512 arrays
/// were 2–5 % slower than the AVX2 ones on a CPU that has both, so they are not built.
pub fn detected_lanes() -> usize {
    8
}

/// The width of the lane groups for `units` independent units of work shared among the current
/// thread pool's threads, each unit taking `lanes_per_unit` lanes (a path: 1; a Lyapunov
/// realisation's reference and copy: 2): `lanes`' width, narrowed from 8 to 4 when a thread's
/// share of units would fill no more than four lanes, so that every thread has a group. A path's
/// bits do not depend on its group, so neither do the results.
pub(crate) fn group_lanes(lanes: Lanes, units: usize, lanes_per_unit: usize) -> Result<usize> {
    let width = lanes.width()?;
    let threads = rayon::current_num_threads().max(1);
    let per_thread = units.div_ceil(threads) * lanes_per_unit;
    Ok(if width == 8 && per_thread <= 4 {
        4
    } else {
        width
    })
}

/// The instruction set the lane arrays are compiled for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Isa {
    Portable,
    #[cfg_attr(not(target_arch = "x86_64"), allow(dead_code))]
    Avx2,
}

impl Isa {
    pub(crate) fn detect() -> Isa {
        #[cfg(target_arch = "x86_64")]
        {
            if std::arch::is_x86_feature_detected!("avx2") {
                return Isa::Avx2;
            }
        }
        Isa::Portable
    }
}

/// Whether every stepper in `paths` integrates the same equation with the same step and
/// weights (the lane step shares them): one problem, one method.
pub(crate) fn same_problem(paths: &[Stepper]) -> bool {
    let Some(first) = paths.first() else {
        return true;
    };
    paths.iter().all(|p| {
        p.rhs == first.rhs
            && p.h.to_bits() == first.h.to_bits()
            && p.wr.to_bits() == first.wr.to_bits()
            && p.wl.to_bits() == first.wl.to_bits()
    })
}

/// One step of every live path of `paths` (at most L of them, all of one problem: see
/// [`same_problem`]), as [`Stepper::step`] would take it; a path whose step fails gets its
/// error in `errors` (its state is then as after a failed [`Stepper::step`]).
pub(crate) fn step_group<const L: usize>(
    isa: Isa,
    paths: &mut [Stepper],
    live: &[bool; L],
    errors: &mut [Option<Error>; L],
) {
    step_group_with::<L, _>(isa, &Shared, paths, live, errors)
}

/// [`step_group`] for paths of different problems (at most L of them), each lane with its own
/// coefficients `c` ([`PerLane::new`] of these paths, in this order).
pub(crate) fn step_group_mixed<const L: usize>(
    isa: Isa,
    c: &PerLane<L>,
    paths: &mut [Stepper],
    live: &[bool; L],
    errors: &mut [Option<Error>; L],
) {
    step_group_with::<L, _>(isa, c, paths, live, errors)
}

/// The lane step with coefficients `c`, in the arrays compiled for `isa`.
#[inline(always)]
fn step_group_with<const L: usize, C: Coefficients<L>>(
    isa: Isa,
    c: &C,
    paths: &mut [Stepper],
    live: &[bool; L],
    errors: &mut [Option<Error>; L],
) {
    assert!(
        paths.len() <= L,
        "at most {L} paths in a group of {L} lanes"
    );
    if paths.iter().any(|p| p.general.is_some()) {
        return step_one_by_one::<L>(paths, live, errors);
    }
    match isa {
        #[cfg(target_arch = "x86_64")]
        // SAFETY: `Isa::Avx2` is only detected where the CPU reports AVX2.
        Isa::Avx2 => unsafe { step_avx2::<L, _>(c, paths, live, errors) },
        _ => step_body::<L, _>(c, paths, live, errors),
    }
}

/// A group holding General paths (module docs of `general`): every live path by the scalar
/// stepper, one after the other. Out of line, so that the lane step's callers (their loops
/// inlined around it) keep the code they had.
#[cold]
#[inline(never)]
fn step_one_by_one<const L: usize>(
    paths: &mut [Stepper],
    live: &[bool; L],
    errors: &mut [Option<Error>; L],
) {
    for (k, p) in paths.iter_mut().enumerate() {
        if live[k] {
            errors[k] = p.step().err();
        }
    }
}

/// [`step_one_by_one`] with the tangents.
#[cold]
#[inline(never)]
fn step_tangents_one_by_one<const L: usize>(
    paths: &mut [Stepper],
    tangents: &mut [Tangent],
    live: &[bool; L],
    errors: &mut [Option<Error>; L],
) {
    for (k, (p, t)) in paths.iter_mut().zip(tangents.iter_mut()).enumerate() {
        if live[k] {
            errors[k] = p.step_with_tangent(t).err();
        }
    }
}

/// [`step_body`] compiled for AVX2 (four doubles a vector).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,avx")]
unsafe fn step_avx2<const L: usize, C: Coefficients<L>>(
    c: &C,
    paths: &mut [Stepper],
    live: &[bool; L],
    errors: &mut [Option<Error>; L],
) {
    step_body::<L, C>(c, paths, live, errors)
}

/// The coefficients of the lanes' equations in the array phases of the step: shared by every
/// lane ([`Shared`], one problem: read from the first path) or lane by lane ([`PerLane`]).
/// `paths` are the group's steppers.
pub(crate) trait Coefficients<const L: usize> {
    /// μP of lane i at the point sq[i] (= U²), for every lane.
    fn damping(&self, paths: &[Stepper], sq: &[f64; L]) -> [f64; L];
    /// Lane i's (Δt, scaled weight w_r of g at a step's end, ω²).
    fn lane(&self, paths: &[Stepper], i: usize) -> (f64, f64, f64);
}

/// One problem for every lane: the coefficients are the first path's.
pub(crate) struct Shared;

impl<const L: usize> Coefficients<L> for Shared {
    #[inline(always)]
    fn damping(&self, paths: &[Stepper], sq: &[f64; L]) -> [f64; L] {
        paths[0].rhs.damping.eval_lanes(sq)
    }

    #[inline(always)]
    fn lane(&self, paths: &[Stepper], _: usize) -> (f64, f64, f64) {
        let p = &paths[0];
        (p.h, p.wr, p.rhs.omega2)
    }
}

/// Each lane its own problem: the coefficients of the polynomial μP, Δt, the weight w_r and
/// ω² as arrays `[f64; L]`, every lane's arithmetic the scalar stepper's with its own numbers.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct PerLane<const L: usize> {
    damping: LanePolynomial<L>,
    h: [f64; L],
    w: [f64; L],
    omega2: [f64; L],
}

impl<const L: usize> PerLane<L> {
    /// The coefficients of `paths` (1 to L steppers; the lanes beyond take the first's), or
    /// None when their polynomials μP are not of one form (all of degree ≤ 7 in U², or all
    /// of one degree above): their lanes would not perform the same operations.
    pub(crate) fn new(paths: &[Stepper]) -> Option<Self> {
        if paths.is_empty() || paths.len() > L {
            return None;
        }
        let polys: Vec<_> = paths.iter().map(|p| &p.rhs.damping).collect();
        let damping = LanePolynomial::new(&polys)?;
        let lane = |i: usize| paths.get(i).unwrap_or(&paths[0]);
        Some(PerLane {
            damping,
            h: std::array::from_fn(|i| lane(i).h),
            w: std::array::from_fn(|i| lane(i).wr),
            omega2: std::array::from_fn(|i| lane(i).rhs.omega2),
        })
    }
}

impl<const L: usize> Coefficients<L> for PerLane<L> {
    #[inline(always)]
    fn damping(&self, _: &[Stepper], sq: &[f64; L]) -> [f64; L] {
        self.damping.eval_lanes(sq)
    }

    #[inline(always)]
    fn lane(&self, _: &[Stepper], i: usize) -> (f64, f64, f64) {
        (self.h[i], self.w[i], self.omega2[i])
    }
}

/// The corrector's pass for L lanes: (U₁, V₁).
struct PassLanes<const L: usize> {
    u1: [f64; L],
    v1: [f64; L],
}

/// The inputs of a step for L lanes, as arrays.
struct Inputs<const L: usize> {
    u: [f64; L],
    v: [f64; L],
    gl: [f64; L],
    known: [f64; L],
    fr: [f64; L],
    pw: [f64; L],
}

/// Phase (1) of a lane step: per live path, the noise and the numbers the step needs from the
/// state ([`Stepper::begin`]), gathered into arrays; dead lanes and lanes beyond the paths hold
/// zeros.
#[inline(always)]
fn begin_lanes<const L: usize>(paths: &mut [Stepper], live: &[bool; L]) -> ([Begin; L], Inputs<L>) {
    let mut begun = [Begin::default(); L];
    let mut x = Inputs {
        u: [0.0; L],
        v: [0.0; L],
        gl: [0.0; L],
        known: [0.0; L],
        fr: [0.0; L],
        pw: [0.0; L],
    };
    for (i, p) in paths.iter_mut().enumerate() {
        if live[i] {
            let b = p.begin();
            begun[i] = b;
            (x.u[i], x.v[i], x.gl[i], x.known[i], x.fr[i], x.pw[i]) =
                (b.u, b.v, b.gl, b.known, b.fr, p.pw);
        }
    }
    (begun, x)
}

/// [`Affine::pass`] for L lanes: μP in one vectorised evaluation, then the pass element by element
/// (the same function as the scalar stepper's).
#[inline(always)]
fn pass_lanes<const L: usize, C: Coefficients<L>>(
    c: &C,
    paths: &[Stepper],
    x: &Inputs<L>,
    up: &[f64; L],
) -> PassLanes<L> {
    let mut sq = [0.0; L];
    for i in 0..L {
        sq[i] = up[i] * up[i];
    }
    let a = c.damping(paths, &sq);
    let (mut u1, mut v1) = ([0.0; L], [0.0; L]);
    for i in 0..L {
        let (h, w, omega2) = c.lane(paths, i);
        let p = pass_with(
            omega2,
            a[i],
            h,
            (x.u[i], x.v[i], x.gl[i]),
            up[i],
            x.known[i],
            w,
            x.fr[i],
        );
        u1[i] = p.u1;
        v1[i] = p.v1;
    }
    PassLanes { u1, v1 }
}

/// The lane step (module docs: its five phases). Lanes beyond `paths.len()` and dead lanes
/// carry zeros through the arrays and are never written back.
#[inline(always)]
fn step_body<const L: usize, C: Coefficients<L>>(
    c: &C,
    paths: &mut [Stepper],
    live: &[bool; L],
    errors: &mut [Option<Error>; L],
) {
    let n = paths.len();
    if n == 0 {
        return;
    }
    // (1) per path: the noise and the state
    let (begun, x) = begin_lanes::<L>(paths, live);
    // (2) all lanes: the predictor and the corrector's two passes
    let mut up = [0.0; L];
    for i in 0..L {
        let (h, _, _) = c.lane(paths, i);
        up[i] = x.u[i] + h * x.v[i] + x.pw[i] * x.gl[i];
    }
    let one = pass_lanes(c, paths, &x, &up);
    let two = pass_lanes(c, paths, &x, &one.u1);
    let (u1, v1) = (two.u1, two.v1);
    // (3) per path: the events, for the lanes that have them
    let mut ends: [Option<End>; L] = [None; L];
    for (i, p) in paths.iter_mut().enumerate() {
        if live[i] {
            match p.end_events(&begun[i], u1[i], v1[i]) {
                Ok(e) => ends[i] = Some(e),
                Err(e) => errors[i] = Some(e),
            }
        }
    }
    // (4) all lanes: the node's μP, drift and predictor weight
    let (mut eu, mut ev) = ([0.0; L], [0.0; L]);
    for i in 0..L {
        if let Some(e) = &ends[i] {
            (eu[i], ev[i]) = (e.u1, e.v1);
        }
    }
    let mut sq = [0.0; L];
    for i in 0..L {
        sq[i] = eu[i] * eu[i];
    }
    let a1 = c.damping(paths, &sq);
    let (mut drift, mut pw) = ([0.0; L], [0.0; L]);
    for i in 0..L {
        let (h, _, omega2) = c.lane(paths, i);
        (drift[i], pw[i]) = node_with(omega2, h, a1[i], eu[i], ev[i]);
    }
    // (5) per path: the piece into the memory, the new state
    for (i, p) in paths.iter_mut().enumerate() {
        if let Some(e) = ends[i] {
            (p.drift, p.pw) = (drift[i], pw[i]);
            p.complete(&begun[i], e);
        }
    }
}

/// One step of every live path of `paths` (at most L of them, all of one problem: see
/// [`same_problem`]) with its tangent `tangents[i]`, as [`Stepper::step_with_tangent`] would
/// take it; a path whose step fails gets its error in `errors`.
pub(crate) fn step_group_tangent<const L: usize>(
    isa: Isa,
    paths: &mut [Stepper],
    tangents: &mut [Tangent],
    live: &[bool; L],
    errors: &mut [Option<Error>; L],
) {
    assert!(
        paths.len() <= L && tangents.len() == paths.len(),
        "at most {L} paths, each with its tangent, in a group of {L} lanes"
    );
    if paths.iter().any(|p| p.general.is_some()) {
        return step_tangents_one_by_one::<L>(paths, tangents, live, errors);
    }
    match isa {
        #[cfg(target_arch = "x86_64")]
        // SAFETY: `Isa::Avx2` is only detected where the CPU reports AVX2.
        Isa::Avx2 => unsafe { step_tangent_avx2::<L>(paths, tangents, live, errors) },
        _ => step_tangent_body::<L>(paths, tangents, live, errors),
    }
}

/// [`step_tangent_body`] compiled for AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,avx")]
unsafe fn step_tangent_avx2<const L: usize>(
    paths: &mut [Stepper],
    tangents: &mut [Tangent],
    live: &[bool; L],
    errors: &mut [Option<Error>; L],
) {
    step_tangent_body::<L>(paths, tangents, live, errors)
}

/// μP and d(μP)/dU = 2U·(μP)′(U²) at the points u, for every lane (as [`Affine::damping`] and
/// [`Affine::damping_slope`]).
#[inline(always)]
fn damping_and_slope<const L: usize>(rhs: &Affine, u: &[f64; L]) -> ([f64; L], [f64; L]) {
    let mut sq = [0.0; L];
    for i in 0..L {
        sq[i] = u[i] * u[i];
    }
    let a = rhs.damping.eval_lanes(&sq);
    let s = rhs.slope.eval_lanes(&sq);
    let mut slope = [0.0; L];
    for i in 0..L {
        slope[i] = 2.0 * u[i] * s[i];
    }
    (a, slope)
}

/// d(μP)/dU at the points u, for every lane.
#[inline(always)]
fn slope_lanes<const L: usize>(rhs: &Affine, u: &[f64; L]) -> [f64; L] {
    let mut sq = [0.0; L];
    for i in 0..L {
        sq[i] = u[i] * u[i];
    }
    let s = rhs.slope.eval_lanes(&sq);
    let mut slope = [0.0; L];
    for i in 0..L {
        slope[i] = 2.0 * u[i] * s[i];
    }
    slope
}

/// The corrector's pass for L lanes with everything the tangent needs (the scalar [`Pass`]).
#[inline(always)]
fn full_pass_lanes<const L: usize>(
    rhs: &Affine,
    (h, w): (f64, f64),
    x: &Inputs<L>,
    up: &[f64; L],
) -> [Pass; L] {
    let mut sq = [0.0; L];
    for i in 0..L {
        sq[i] = up[i] * up[i];
    }
    let a = rhs.damping.eval_lanes(&sq);
    std::array::from_fn(|i| {
        let y = (x.u[i], x.v[i], x.gl[i]);
        pass_with(rhs.omega2, a[i], h, y, up[i], x.known[i], w, x.fr[i])
    })
}

/// The lane step of paths with their tangents: the phases of [`step_body`], the tangent's
/// linearised step beside the path's — its polynomial evaluations (μP and (μP)′ at the start,
/// at each pass's up and at the end) in arrays across lanes, its events and its memory per
/// path by the scalar code ([`Stepper::step_with_tangent`]'s phases).
#[inline(always)]
fn step_tangent_body<const L: usize>(
    paths: &mut [Stepper],
    tangents: &mut [Tangent],
    live: &[bool; L],
    errors: &mut [Option<Error>; L],
) {
    let n = paths.len();
    if n == 0 {
        return;
    }
    // (1) per path: the noise and the state; all lanes: μP and its slope at U; per path: the
    // tangent's start
    let (begun, x) = begin_lanes::<L>(paths, live);
    let rhs = &paths[0].rhs;
    let (h, w) = (paths[0].h, paths[0].wr);
    let (a0, slope0) = damping_and_slope(rhs, &x.u);
    let mut tb = [TangentBegin::default(); L];
    for i in 0..n {
        if live[i] {
            tb[i] = paths[i].begin_tangent(&tangents[i], (a0[i], slope0[i]));
        }
    }
    // (2) all lanes: the predictor, the corrector's two passes; the
    // tangent's passes
    let mut up = [0.0; L];
    for i in 0..L {
        up[i] = x.u[i] + h * x.v[i] + x.pw[i] * x.gl[i];
    }
    let one = full_pass_lanes(rhs, (h, w), &x, &up);
    let u_one: [f64; L] = std::array::from_fn(|i| one[i].u1);
    let two = full_pass_lanes(rhs, (h, w), &x, &u_one);
    let (s_one, s_two) = (slope_lanes(rhs, &up), slope_lanes(rhs, &u_one));
    let mut free = [[0.0; 4]; L];
    for i in 0..L {
        let f = Free {
            len: h,
            w,
            g0: x.gl[i],
            pw: x.pw[i],
            passes: [one[i], two[i]],
        };
        let (u1, v1) = f.end();
        let t = &tb[i];
        let (du1, dv1) = rhs.advance_tangent_with(
            &f,
            [s_one[i], s_two[i]],
            (t.du, t.dv, t.dgl),
            t.dpw,
            t.dknown,
        );
        free[i] = [u1, v1, du1, dv1];
    }
    // (3) per path: the events, for the lanes that have them
    let mut ends: [Option<TangentEnd>; L] = [None; L];
    for (i, (p, t)) in paths.iter_mut().zip(tangents.iter_mut()).enumerate() {
        if live[i] {
            match p.end_events_with_tangent(t, &begun[i], &tb[i], free[i]) {
                Ok(e) => ends[i] = Some(e),
                Err(e) => errors[i] = Some(e),
            }
        }
    }
    // (4) all lanes: the node's μP, its slope, drift and predictor weight
    let (mut eu, mut ev) = ([0.0; L], [0.0; L]);
    for i in 0..L {
        if let Some(e) = &ends[i] {
            (eu[i], ev[i]) = (e.u1, e.v1);
        }
    }
    let rhs = &paths[0].rhs;
    let (a1, slope1) = damping_and_slope(rhs, &eu);
    let (mut drift, mut pw) = ([0.0; L], [0.0; L]);
    for i in 0..L {
        (drift[i], pw[i]) = rhs.node(h, a1[i], eu[i], ev[i]);
    }
    // (5) per path: the pieces into the memories, the new states
    for (i, (p, t)) in paths.iter_mut().zip(tangents.iter_mut()).enumerate() {
        if let Some(e) = ends[i] {
            (p.drift, p.pw) = (drift[i], pw[i]);
            let ddrift = p.drift_derivative_at(a1[i], slope1[i], &e);
            p.complete_with_tangent(t, &begun[i], e, ddrift);
        }
    }
}

/// Paths of one problem stepped together again and again, in groups of 1, 4 or 8, with no
/// observer: for drivers that act on the paths between steps (the renormalisations of the
/// Lyapunov realisations); with their tangents ([`Group::with_tangents`]) for the tangent
/// method.
pub(crate) struct Group<'a> {
    paths: &'a mut [Stepper],
    tangents: Option<&'a mut [Tangent]>,
    lanes: usize,
    isa: Isa,
    errors: Vec<Option<Error>>,
}

impl<'a> Group<'a> {
    /// `paths` of one problem and method in groups of `lanes` (1, 4 or 8).
    pub(crate) fn new(paths: &'a mut [Stepper], lanes: usize) -> Result<Self> {
        Lanes::Width(lanes).width()?;
        if !same_problem(paths) {
            return Err(Error::invalid(
                "paths",
                paths.len() as f64,
                "steppers of one problem and method (the lanes share its equation and weights)",
            ));
        }
        let errors = (0..paths.len()).map(|_| None).collect();
        Ok(Group {
            paths,
            tangents: None,
            lanes,
            isa: Isa::detect(),
            errors,
        })
    }

    /// [`Group::new`] with tangent k stepped with path k
    /// ([`Stepper::step_with_tangent`]).
    pub(crate) fn with_tangents(
        paths: &'a mut [Stepper],
        tangents: &'a mut [Tangent],
        lanes: usize,
    ) -> Result<Self> {
        if tangents.len() != paths.len() {
            return Err(Error::invalid(
                "tangents",
                tangents.len() as f64,
                format!("one per path ({})", paths.len()),
            ));
        }
        let mut g = Group::new(paths, lanes)?;
        g.tangents = Some(tangents);
        Ok(g)
    }

    /// One step of every path; a path whose step failed has its error kept
    /// ([`Group::take_error`]) and must not be stepped again.
    pub(crate) fn step(&mut self) {
        if self.tangents.is_some() {
            return self.step_with_tangents();
        }
        let live8 = [true; 8];
        let live4 = [true; 4];
        for (k, group) in self.paths.chunks_mut(self.lanes).enumerate() {
            let errors = &mut self.errors[k * self.lanes..];
            match self.lanes {
                8 => {
                    let mut e: [Option<Error>; 8] = Default::default();
                    step_group::<8>(self.isa, group, &live8, &mut e);
                    for (slot, e) in errors.iter_mut().zip(e) {
                        *slot = slot.take().or(e);
                    }
                }
                4 => {
                    let mut e: [Option<Error>; 4] = Default::default();
                    step_group::<4>(self.isa, group, &live4, &mut e);
                    for (slot, e) in errors.iter_mut().zip(e) {
                        *slot = slot.take().or(e);
                    }
                }
                _ => {
                    for (slot, p) in errors.iter_mut().zip(group.iter_mut()) {
                        if let Err(e) = p.step() {
                            *slot = Some(e);
                        }
                    }
                }
            }
        }
    }

    /// [`Group::step`] of the paths with their tangents.
    fn step_with_tangents(&mut self) {
        let Some(tangents) = self.tangents.as_deref_mut() else {
            return;
        };
        let width = self.lanes;
        let chunks = self.paths.chunks_mut(width).zip(tangents.chunks_mut(width));
        for (k, (group, tangents)) in chunks.enumerate() {
            let errors = &mut self.errors[k * width..];
            match width {
                8 => {
                    let mut e: [Option<Error>; 8] = Default::default();
                    step_group_tangent::<8>(self.isa, group, tangents, &[true; 8], &mut e);
                    for (slot, e) in errors.iter_mut().zip(e) {
                        *slot = slot.take().or(e);
                    }
                }
                4 => {
                    let mut e: [Option<Error>; 4] = Default::default();
                    step_group_tangent::<4>(self.isa, group, tangents, &[true; 4], &mut e);
                    for (slot, e) in errors.iter_mut().zip(e) {
                        *slot = slot.take().or(e);
                    }
                }
                _ => {
                    for ((slot, p), t) in errors.iter_mut().zip(group).zip(tangents) {
                        if let Err(e) = p.step_with_tangent(t) {
                            *slot = Some(e);
                        }
                    }
                }
            }
        }
    }

    /// Path `k` and its tangent (a group made [`Group::with_tangents`]).
    pub(crate) fn with_tangent(&mut self, k: usize) -> (&Stepper, &mut Tangent) {
        let tangents = self
            .tangents
            .as_deref_mut()
            .expect("a group made with tangents");
        (&self.paths[k], &mut tangents[k])
    }

    /// The error of path `k`'s last step, if it failed.
    pub(crate) fn take_error(&mut self, k: usize) -> Option<Error> {
        self.errors[k].take()
    }

    /// Path `k`.
    pub(crate) fn path(&self, k: usize) -> &Stepper {
        &self.paths[k]
    }

    /// Paths 2k (a reference) and 2k + 1 (its copy).
    pub(crate) fn pair(&mut self, k: usize) -> (&Stepper, &mut Stepper) {
        let (a, b) = self.paths[2 * k..2 * k + 2].split_at_mut(1);
        (&a[0], &mut b[0])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::System;
    use crate::engine::{Barrier, ImpactMemory, Memory, Options, PredictorCorrector, Problem};
    use crate::model::preset;
    use proptest::prelude::*;

    /// Path and tangent state as bits, with the step's events.
    fn bits(p: &Stepper, t: &Tangent) -> Vec<u64> {
        let e = p.events();
        let mut out = vec![
            p.u().to_bits(),
            p.v().to_bits(),
            p.base.to_bits(),
            p.history.value().to_bits(),
            p.impacts(),
            p.sticking_steps(),
            e.stuck as u64,
            e.impact.map_or(0, |i| i.time.to_bits()),
        ];
        out.extend(t.bits());
        out
    }

    #[derive(Debug, Clone)]
    struct Case {
        lambda: f64,
        mu0: f64,
        r: f64,
        d: f64,
        system: usize,
        wall: bool,
        restart: bool,
        direct: bool,
        starts: Vec<(f64, f64)>,
    }

    /// Paths 0..n of the case with tangents along (1, k/n), stepped `steps` times and
    /// renormalised every 50 steps: alone by `step_with_tangent`, or in groups of `lanes`;
    /// each path's bits after every step, or its error.
    fn run(c: &Case, n: usize, steps: usize, lanes: usize) -> Vec<(Vec<Vec<u64>>, Option<String>)> {
        let (problem, method) = problem(c);
        run_problem(&problem, &method, n, steps, lanes)
    }

    fn problem(c: &Case) -> (Problem, PredictorCorrector) {
        let p = preset("fig13a")
            .unwrap()
            .params
            .with("lambda", c.lambda)
            .and_then(|p| p.with("mu0", c.mu0))
            .and_then(|p| p.with("r", c.r))
            .and_then(|p| p.with("D", c.d))
            .unwrap();
        let system = [System::Fractional, System::Equivalent, System::Zhuravlev][c.system];
        let barrier = if c.wall && system != System::Zhuravlev {
            Barrier::On
        } else {
            Barrier::Off
        };
        let problem = Problem::from_params(&p)
            .and_then(|q| q.with_system(system))
            .and_then(|q| q.with_barrier(barrier))
            .and_then(|q| q.with_starts(&c.starts))
            .unwrap();
        let method = PredictorCorrector {
            memory: if c.direct {
                Memory::Direct
            } else {
                Memory::default()
            },
            impact_memory: if c.restart {
                ImpactMemory::Restart
            } else {
                ImpactMemory::Continuous
            },
            ..Default::default()
        };
        (problem, method)
    }

    fn run_problem(
        problem: &Problem,
        method: &PredictorCorrector,
        n: usize,
        steps: usize,
        lanes: usize,
    ) -> Vec<(Vec<Vec<u64>>, Option<String>)> {
        let mut paths: Vec<Stepper> = (0..n)
            .map(|i| {
                let o = Options {
                    t_end: steps as f64 * method.dt,
                    seed: 11,
                    path: i as u64,
                    ..Default::default()
                };
                o.stepper(problem, method).unwrap()
            })
            .collect();
        let mut tangents: Vec<Tangent> = paths
            .iter()
            .enumerate()
            .map(|(k, p)| Tangent::new(p, (1.0, k as f64 / n as f64)))
            .collect();
        let mut logs = vec![(vec![], None); n];
        let mut group = Group::with_tangents(&mut paths, &mut tangents, lanes).unwrap();
        let mut alive = vec![true; n];
        for step in 1..=steps {
            group.step();
            for k in 0..n {
                if !alive[k] {
                    continue;
                }
                if let Some(e) = group.take_error(k) {
                    logs[k].1 = Some(e.to_string());
                    alive[k] = false;
                    continue;
                }
                let (p, t) = group.with_tangent(k);
                logs[k].0.push(bits(p, t));
                if step % 50 == 0 && t.norm() > 0.0 {
                    t.scale(1.0 / t.norm());
                }
            }
            if !alive.iter().any(|&a| a) {
                break;
            }
        }
        logs
    }

    fn case() -> impl Strategy<Value = Case> {
        (
            (
                prop_oneof![Just(1.0), 0.6f64..1.0],
                prop_oneof![0.001f64..0.05, 0.05f64..0.8],
                0.3f64..1.0,
                prop_oneof![Just(0.0), 0.01f64..0.6],
            ),
            (
                0usize..3,
                proptest::bool::weighted(0.8),
                proptest::bool::ANY,
                proptest::bool::weighted(0.15),
                proptest::collection::vec((0.0f64..12.0, -3.0f64..3.0), 1..4),
            ),
        )
            .prop_map(
                |((lambda, mu0, r, d), (system, wall, restart, direct, starts))| Case {
                    lambda,
                    mu0,
                    r,
                    d,
                    system,
                    wall,
                    restart,
                    direct,
                    starts,
                },
            )
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(24))]

        /// Paths with their tangents in lanes of 4 and 8 give, step by step, the bits of
        /// `step_with_tangent` path by path (path and tangent state, events, counts).
        #[test]
        fn tangents_in_lanes_give_the_scalar_bits(c in case(), n in 1usize..11) {
            let steps = if c.direct { 300 } else { 1200 };
            let scalar = run(&c, n, steps, 1);
            let done: usize = scalar.iter().map(|l| l.0.len()).sum();
            eprintln!("{done} of {} path-steps", n * steps);
            for lanes in [4, 8] {
                let lane = run(&c, n, steps, lanes);
                for k in 0..n {
                    prop_assert!(lane[k] == scalar[k], "path {k} in lanes of {lanes} ({c:?})");
                }
            }
        }
    }

    /// Cases that the property above covers: impacts and sticking (a frozen push against the
    /// wall), stiff steps, checked to happen.
    #[test]
    fn tangents_in_lanes_meet_impacts_sticking_and_stiff_steps() {
        use crate::model::{Damping, Params};
        for (lambda, restart) in [(0.9, false), (1.0, false), (0.95, true)] {
            let p = Params {
                mu0: 1.0,
                omega0: 3.0,
                lambda,
                restitution: 0.5,
                damping: Damping {
                    coefficients: vec![-0.3, 0.0, 0.01],
                },
                noise_intensity: 1e6,
                correlation_time: 1e6,
            };
            let starts = [(1.0, 0.0), (0.2, -1.0), (13.0, 0.0)];
            let problem = Problem::from_params(&p)
                .and_then(|q| q.with_starts(&starts))
                .unwrap();
            let method = PredictorCorrector {
                impact_memory: if restart {
                    ImpactMemory::Restart
                } else {
                    ImpactMemory::Continuous
                },
                ..Default::default()
            };
            let scalar = run_problem(&problem, &method, 9, 2000, 1);
            let last: Vec<&Vec<u64>> = scalar.iter().map(|l| l.0.last().unwrap()).collect();
            let impacts: u64 = last.iter().map(|b| b[4]).sum();
            let stuck: u64 = last.iter().map(|b| b[5]).sum();
            assert!(
                impacts > 20 && stuck > 100,
                "impacts {impacts}, sticking {stuck}"
            );
            for lanes in [4, 8] {
                let lane = run_problem(&problem, &method, 9, 2000, lanes);
                assert!(lane == scalar, "λ = {lambda}, lanes {lanes}");
            }
        }
    }

    /// General paths with fractional terms (α = 0.5 and an α = 1 term) and white
    /// multiplicative noise, without a wall and with the wall at 0 (impacts), with their
    /// tangents in lanes of 4 and 8: the scalar `step_with_tangent`'s bits step by step (path,
    /// tangent state, the tangent's δ of the fractional terms and its memories of δV).
    #[test]
    fn general_tangents_with_fractional_terms_in_lanes_give_the_scalar_bits() {
        for wall in [false, true] {
            general_tangents_in_lanes(wall);
        }
    }

    fn general_tangents_in_lanes(wall: bool) {
        let mut m = crate::model::Model::from(&preset("fig17a").unwrap().params);
        if !wall {
            m.walls.clear();
        }
        m.fractional = vec![
            crate::model::Fractional {
                coefficient: 0.4,
                order: 0.5,
            },
            crate::model::Fractional {
                coefficient: 0.1,
                order: 1.0,
            },
        ];
        m.noise.multiplicative = Some(crate::model::NoiseTerm {
            intensity: 0.05,
            correlation_time: 0.0,
        });
        let starts = [(1.0, 0.0), (0.5, -1.0), (2.0, 0.5)];
        let problem = Problem::from_model(&m)
            .and_then(|q| q.with_starts(&starts))
            .unwrap();
        let method = PredictorCorrector::default();
        let scalar = run_problem(&problem, &method, 6, 1000, 1);
        for (k, (log, error)) in scalar.iter().enumerate() {
            assert!(error.is_none() && log.len() == 1000, "path {k}: {error:?}");
            // the tangent's bits end with δ(−ΣK_j m_j) and one memory's value, not 0
            let last = log.last().unwrap();
            assert!(last[last.len() - 2..]
                .iter()
                .all(|&b| f64::from_bits(b) != 0.0));
        }
        if wall {
            assert!(scalar.iter().any(|(log, _)| log.last().unwrap()[4] > 0));
        }
        for lanes in [4, 8] {
            let lane = run_problem(&problem, &method, 6, 1000, lanes);
            assert!(lane == scalar, "lanes {lanes}, wall {wall}");
        }
    }
}
