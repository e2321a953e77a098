//! The lane stepper: several paths of one problem advanced together, the arithmetic of their
//! step in structure-of-arrays form so that one vector instruction serves every path.
//!
//! # Equation
//! The step of [`Stepper::step`] (module docs of [`super`]), unchanged: for each path the
//! damped Taylor predictor U^P, the linearly implicit corrector
//! V₁ = (known + w(f − ω²U^P))/(1 − w·μP(U^P)), the Hermite-corrected U₁, the second pass on
//! stiff steps, and at the end the node's drift μP(U₁)V₁ − ω²U₁ and predictor weight.
//!
//! # Method
//! A step of L paths (L = 4 or 8) runs in five phases: (1) per path, the noise and the numbers
//! the step needs from the state ([`Stepper::begin`]); (2) for all L at once, the polynomial
//! μP, the predictor, both divisions and the corrector in arrays `[f64; L]`, the second pass
//! taken for all lanes when any lane is stiff and kept only where it is; (3) per path, the
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
//! the equivalent and Zhuravlev systems; the ensemble's statistics are identical for
//! `--lanes 1`, 4 and 8.

// element i of every array, lane by lane: the form the loop vectoriser takes and the scalar
// stepper's expressions read the same
#![allow(clippy::needless_range_loop)]

use super::{Begin, End, Rhs, Stepper, SECOND_PASS};
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
    assert!(
        paths.len() <= L,
        "at most {L} paths in a group of {L} lanes"
    );
    match isa {
        #[cfg(target_arch = "x86_64")]
        // SAFETY: `Isa::Avx2` is only detected where the CPU reports AVX2.
        Isa::Avx2 => unsafe { step_avx2::<L>(paths, live, errors) },
        _ => step_body::<L>(paths, live, errors),
    }
}

/// [`step_body`] compiled for AVX2 (four doubles a vector).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,avx")]
unsafe fn step_avx2<const L: usize>(
    paths: &mut [Stepper],
    live: &[bool; L],
    errors: &mut [Option<Error>; L],
) {
    step_body::<L>(paths, live, errors)
}

/// The corrector's pass for L lanes: (μP(up), U₁, V₁).
struct PassLanes<const L: usize> {
    a: [f64; L],
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

/// [`Rhs::pass`] for L lanes: μP in one vectorised evaluation, then the pass element by element
/// (the same function as the scalar stepper's).
#[inline(always)]
fn pass_lanes<const L: usize>(
    rhs: &Rhs,
    h: f64,
    w: f64,
    x: &Inputs<L>,
    up: &[f64; L],
) -> PassLanes<L> {
    let mut sq = [0.0; L];
    for i in 0..L {
        sq[i] = up[i] * up[i];
    }
    let a = rhs.damping.eval_lanes(&sq);
    let (mut u1, mut v1) = ([0.0; L], [0.0; L]);
    for i in 0..L {
        let p = rhs.pass_with(
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
    PassLanes { a, u1, v1 }
}

/// The lane step (module docs: its five phases). Lanes beyond `paths.len()` and dead lanes
/// carry zeros through the arrays and are never written back.
#[inline(always)]
fn step_body<const L: usize>(
    paths: &mut [Stepper],
    live: &[bool; L],
    errors: &mut [Option<Error>; L],
) {
    let n = paths.len();
    if n == 0 {
        return;
    }
    // (1) per path: the noise and the state
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
    let first = &paths[0];
    let rhs = &first.rhs;
    let (h, w) = (first.h, first.wr);
    // (2) all lanes: the predictor and the corrector, the second pass where stiff
    let mut up = [0.0; L];
    for i in 0..L {
        up[i] = x.u[i] + h * x.v[i] + x.pw[i] * x.gl[i];
    }
    let one = pass_lanes(rhs, h, w, &x, &up);
    let mut stiff = [false; L];
    for i in 0..L {
        stiff[i] = (2.0 * w * one.a[i]).abs() > SECOND_PASS;
    }
    let (mut u1, mut v1) = (one.u1, one.v1);
    if stiff.iter().any(|&s| s) {
        let two = pass_lanes(rhs, h, w, &x, &one.u1);
        for i in 0..L {
            if stiff[i] {
                (u1[i], v1[i]) = (two.u1[i], two.v1[i]);
            }
        }
    }
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
    let rhs = &paths[0].rhs;
    let a1 = rhs.damping.eval_lanes(&sq);
    let (mut drift, mut pw) = ([0.0; L], [0.0; L]);
    for i in 0..L {
        (drift[i], pw[i]) = rhs.node(h, a1[i], eu[i], ev[i]);
    }
    // (5) per path: the piece into the memory, the new state
    for (i, p) in paths.iter_mut().enumerate() {
        if let Some(e) = ends[i] {
            (p.drift, p.pw) = (drift[i], pw[i]);
            p.complete(&begun[i], e);
        }
    }
}

/// Paths of one problem stepped together again and again, in groups of 1, 4 or 8, with no
/// observer: for drivers that act on the paths between steps (the renormalisations of the
/// Lyapunov realisations).
pub(crate) struct Group<'a> {
    paths: &'a mut [Stepper],
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
            lanes,
            isa: Isa::detect(),
            errors,
        })
    }

    /// One step of every path; a path whose step failed has its error kept
    /// ([`Group::take_error`]) and must not be stepped again.
    pub(crate) fn step(&mut self) {
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
