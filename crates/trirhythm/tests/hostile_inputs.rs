//! Hostile inputs: every public entry point of the model, the theory, the special functions,
//! the engine (problem, method, options, stepper, drivers), the ensembles, the Lyapunov
//! exponents, the oscillation boundaries and the recurrence analysis, called with each numeric
//! argument in turn replaced by NaN, ±∞, 0, a negative value and a huge one (1e300; 10¹² and
//! `usize::MAX` for counts) while the others stay valid.
//!
//! The claim (every check is in the library): within one second, without a panic, the call
//! returns an `Err` that names the argument, or — where the value is legitimately in range, as
//! each row's `accepts` states — anything but an invalid-parameter error. Functions that return
//! a plain number (evaluations such as P(A) at a point, Γ(x), a quadrature) are total: they are
//! only required to return promptly without panicking (`Kind::Total`).
//!
//! The table is one `Row` per (entry point, argument). The valid arguments of the drivers'
//! rows are tiny (a few paths of 20 steps, three periods of a growth rate), so that a value
//! legitimately accepted runs in milliseconds; every refused value is refused before any work.

use proptest::prelude::*;
use std::panic::catch_unwind;
use std::sync::mpsc;
use std::sync::OnceLock;
use std::time::{Duration, Instant};
use trirhythm::analysis::ensemble::{
    self, run_ensemble, EnsembleResult, EnsembleSpec, PathStats, Wells,
};
use trirhythm::analysis::lyapunov::{self, largest_lyapunov, LyapunovSpec, PathRun};
use trirhythm::analysis::oscillation::{
    averaging_mu0, boundary, classify_plane, exact_mu0, growth_rate, margin, Classifier, Method,
    Plane as OscillationPlane, Search,
};
use trirhythm::analysis::recurrence::{RecurrenceMatrix, RecurrenceThreshold};
use trirhythm::analysis::versus::{compare, escape_time, theory_layout};
use trirhythm::engine::kernel::{interval_weights, SoeKernel};
use trirhythm::engine::noise::{Noise, NoiseStream};
use trirhythm::engine::{
    probe_memory, run as run_path, simulate, simulate_ensemble, simulate_with, solve_scalar,
    Barrier, Flow, Lanes, Memory, Options, Oscillator, PredictorCorrector, Problem, Stepper,
    TrajectoryRecorder,
};
use trirhythm::model::preset;
use trirhythm::model::Equivalents;
use trirhythm::monitor::Silent;
use trirhythm::special::{gamma, ln_gamma, mittag_leffler};
use trirhythm::theory::averaging::{
    phase_average_weight, sgn_harmonic_sum, AmplitudePdf, Theory, Variant,
};
use trirhythm::theory::bifurcation::{
    branches, cusp_monitor, fold_residuals, Axis, FoldPoint, FoldSystem, Kernel, Key, Plane, Point,
    What,
};
use trirhythm::theory::polynomial::Polynomial;
use trirhythm::theory::quadrature::integrate_with_breakpoints;
use trirhythm::{Damping, Error, Params};

/// How long one call may take.
const LIMIT: Duration = Duration::from_secs(1);

/// What an argument is, and so which hostile values it meets.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Kind {
    /// A real number with an allowed range: NaN, ±∞, 0, −0.1, 1e300.
    Real,
    /// A size or count (`usize`): 0, 10¹², `usize::MAX`.
    Count,
    /// An argument of a total function (returns a number, never an error): every hostile value
    /// of both lists; only promptness and the absence of a panic are checked.
    Total,
}

/// One argument of one entry point.
struct Row {
    /// The entry point, as a user calls it.
    entry: &'static str,
    /// The argument.
    arg: &'static str,
    /// What the error message must contain (the argument's user-facing name).
    needle: &'static str,
    kind: Kind,
    /// Whether a value is legitimately in range (then no invalid-parameter error is allowed).
    accepts: fn(f64) -> bool,
    /// The call with this argument set to the value and the others valid.
    call: fn(f64) -> Result<(), Error>,
}

const REALS: [f64; 6] = [f64::NAN, f64::INFINITY, f64::NEG_INFINITY, 0.0, -0.1, 1e300];
const COUNTS: [f64; 3] = [0.0, 1e12, usize::MAX as f64];

fn finite(v: f64) -> bool {
    v.is_finite()
}
fn positive(v: f64) -> bool {
    v > 0.0 && v.is_finite()
}
fn unit(v: f64) -> bool {
    v > 0.0 && v <= 1.0
}
fn anything(_: f64) -> bool {
    true
}

/// A noisy trirhythmic point (Fig. 4c's set with D = 0.01): its P(A) has three modes.
fn noisy() -> Params {
    Params::default().with("D", 0.01).unwrap()
}

fn pdf() -> &'static AmplitudePdf {
    static PDF: OnceLock<AmplitudePdf> = OnceLock::new();
    PDF.get_or_init(|| {
        Theory::new(&noisy(), Variant::Paper)
            .unwrap()
            .amplitude_pdf()
            .unwrap()
    })
}

/// `Theory::new` of the noisy point with one parameter set (unchecked) to `v`.
fn theory_with(key: &str, v: f64, variant: Variant) -> Result<(), Error> {
    let mut p = noisy();
    p.set(key, v)?;
    Theory::new(&p, variant).map(|_| ())
}

fn branch(start: f64, stop: f64, max_step: f64) -> Result<(), Error> {
    let base = preset("fig5").unwrap().params.with("mu0", 0.04).unwrap();
    branches(
        &base,
        Variant::Paper,
        What::Rhythmicity,
        "r",
        start,
        stop,
        max_step,
    )
    .map(|_| ())
}

fn plane(x: Result<Axis, Error>, y: Result<Axis, Error>) -> Result<(), Error> {
    Plane::new(&Params::default(), x?, y?, Variant::Paper).map(|_| ())
}

fn scalar(alpha: f64, y0: f64, dt: f64, steps: usize, tolerance: f64) -> Result<(), Error> {
    let memory = Memory::SumOfExponentials { tolerance };
    solve_scalar(alpha, &|_, y| -y, y0, dt, steps, memory).map(|_| ())
}

fn total<T>(x: T) -> Result<(), Error> {
    std::hint::black_box(x);
    Ok(())
}

fn count(v: f64) -> usize {
    v as usize
}

// ---- the drivers' valid arguments: tiny, so that an accepted value runs in milliseconds

/// Fig. 1's parameters with noise D = 0.05, the wall on, from U = 1.
fn problem() -> Problem {
    static PROBLEM: OnceLock<Problem> = OnceLock::new();
    PROBLEM
        .get_or_init(|| {
            Problem::from_params(&preset("fig1").unwrap().params.with("D", 0.05).unwrap()).unwrap()
        })
        .clone()
}

/// Δt = 0.05 with the direct memory (no kernel to build).
fn method() -> PredictorCorrector {
    PredictorCorrector {
        dt: 0.05,
        memory: Memory::Direct,
        ..Default::default()
    }
}

/// `simulate` to T = 1 (20 steps) with the method and options changed by `f`.
fn sim(f: impl FnOnce(&mut PredictorCorrector, &mut Options)) -> Result<(), Error> {
    let (mut m, mut o) = (
        method(),
        Options {
            t_end: 1.0,
            seed: 1,
            ..Default::default()
        },
    );
    f(&mut m, &mut o);
    simulate(&problem(), &m, &o).map(|_| ())
}

fn soe(tolerance: f64) -> Memory {
    Memory::SumOfExponentials { tolerance }
}

/// Two paths of 10 + 20 steps, 4 bins, 4 batches.
fn ensemble_spec() -> EnsembleSpec {
    EnsembleSpec {
        paths: 2,
        seed: 3,
        burn_in: 0.5,
        length: 1.0,
        sample_every: 1,
        bins: 4,
        joint_bins: 2,
        joint_velocity_factor: 1.0,
        amplitude_max: 10.0,
        batches: 4,
        wells: None,
        lanes: Lanes::Auto,
    }
}

/// `run_ensemble` with the spec changed by `f`.
fn ens(f: impl FnOnce(&mut EnsembleSpec)) -> Result<(), Error> {
    let mut spec = ensemble_spec();
    f(&mut spec);
    run_ensemble(&problem(), &method(), &spec, &Silent).map(|_| ())
}

/// The two paths' statistics of [`ensemble_spec`] (for the merge's rows).
fn ensemble_stats() -> Vec<PathStats> {
    static STATS: OnceLock<Vec<PathStats>> = OnceLock::new();
    STATS
        .get_or_init(|| {
            ensemble::run_paths(&problem(), &method(), &ensemble_spec(), &[0, 1], &Silent).unwrap()
        })
        .clone()
}

/// The result of [`ensemble_spec`] (for the comparison's rows).
fn ensemble_result() -> EnsembleResult {
    static RESULT: OnceLock<EnsembleResult> = OnceLock::new();
    RESULT
        .get_or_init(|| {
            ensemble::merge(&problem(), &method(), &ensemble_spec(), ensemble_stats()).unwrap()
        })
        .clone()
}

/// Two realisations of 10 + 20 steps, renormalised every 5 steps.
fn lyapunov_spec() -> LyapunovSpec {
    LyapunovSpec {
        paths: 2,
        seed: 3,
        transient: 0.5,
        length: 1.0,
        renormalise_every: 5,
        separation: 1e-8,
        running_points: 2,
        ..Default::default()
    }
}

/// `largest_lyapunov` with the spec and the method changed by `f`.
fn lle(f: impl FnOnce(&mut LyapunovSpec, &mut PredictorCorrector)) -> Result<(), Error> {
    let (mut spec, mut m) = (lyapunov_spec(), method());
    f(&mut spec, &mut m);
    largest_lyapunov(&problem(), &m, &spec, &Silent).map(|_| ())
}

/// The two realisations of [`lyapunov_spec`] (for the merge's rows).
fn lyapunov_runs() -> Vec<PathRun> {
    static RUNS: OnceLock<Vec<PathRun>> = OnceLock::new();
    RUNS.get_or_init(|| {
        lyapunov::run_paths(&problem(), &method(), &lyapunov_spec(), &[0, 1], &Silent).unwrap()
    })
    .clone()
}

/// The default parameters (D = 0) with the wall: an oscillation-boundary template.
fn template() -> Problem {
    Problem::from_params(&Params::default()).unwrap()
}

/// A classifier of three periods at Δt = 0.05.
fn classifier() -> Classifier {
    Classifier {
        method: PredictorCorrector {
            dt: 0.05,
            ..Default::default()
        },
        settle_periods: 1.0,
        min_periods: 1.0,
        max_periods: 3.0,
        ..Default::default()
    }
}

/// `growth_rate` of the template with the classifier changed by `f`.
fn growth(f: impl FnOnce(&mut Classifier)) -> Result<(), Error> {
    let mut c = classifier();
    f(&mut c);
    growth_rate(&template(), &c).map(|_| ())
}

/// The plane ω0 ∈ {1} × r ∈ [0.5, 1].
fn oscillation_plane() -> OscillationPlane {
    OscillationPlane::new(&template(), ("omega0", vec![1.0]), ("r", 0.5, 1.0)).unwrap()
}

/// Every row. Where a hostile value is legitimately allowed the row's `accepts` says so and the
/// comment names the case (e.g. r = 0: a perfectly plastic wall).
fn rows() -> Vec<Row> {
    macro_rules! row {
        ($entry:expr, $arg:expr, $needle:expr, $kind:expr, $accepts:expr, $call:expr) => {
            Row {
                entry: $entry,
                arg: $arg,
                needle: $needle,
                kind: $kind,
                accepts: $accepts,
                call: $call,
            }
        };
    }
    use Kind::*;
    vec![
        // ---- model: Params::with validates every field (names as users type them)
        row!(
            "Params::with",
            "mu0",
            "mu0",
            Real,
            |v| v > 0.0 && v <= 1e3,
            |v| Params::default().with("mu0", v).map(|_| ())
        ),
        row!(
            "Params::with",
            "omega0",
            "omega0",
            Real,
            |v| (1e-6..=1e3).contains(&v),
            |v| Params::default().with("omega0", v).map(|_| ())
        ),
        row!("Params::with", "lambda", "lambda", Real, unit, |v| {
            Params::default().with("lambda", v).map(|_| ())
        }),
        // r = 0 is allowed: a perfectly plastic wall
        row!(
            "Params::with",
            "r",
            "r",
            Real,
            |v| (0.0..=1.0).contains(&v),
            |v| Params::default().with("r", v).map(|_| ())
        ),
        // damping coefficients of either sign and zero are allowed, up to 1e20 in size
        row!(
            "Params::with",
            "alpha0",
            "alpha0",
            Real,
            |v| v.abs() <= 1e20,
            |v| Params::default().with("alpha0", v).map(|_| ())
        ),
        row!(
            "Params::with",
            "beta0",
            "beta0",
            Real,
            |v| v.abs() <= 1e20,
            |v| Params::default().with("beta0", v).map(|_| ())
        ),
        row!(
            "Params::with",
            "gamma0",
            "gamma0",
            Real,
            |v| v.abs() <= 1e20,
            |v| Params::default().with("gamma0", v).map(|_| ())
        ),
        row!(
            "Params::with",
            "delta0",
            "delta0",
            Real,
            |v| v.abs() <= 1e20,
            |v| Params::default().with("delta0", v).map(|_| ())
        ),
        row!("Params::with", "c7", "c7", Real, |v| v.abs() <= 1e20, |v| {
            Params::default().with("c7", v).map(|_| ())
        }),
        // D = 0 and τ = 0 are allowed: no noise, white noise
        row!(
            "Params::with",
            "D",
            "D",
            Real,
            |v| (0.0..=1e6).contains(&v),
            |v| Params::default().with("D", v).map(|_| ())
        ),
        row!(
            "Params::with",
            "tau",
            "tau",
            Real,
            |v| (0.0..=1e6).contains(&v),
            |v| Params::default().with("tau", v).map(|_| ())
        ),
        row!(
            "Damping::set_coefficient",
            "k",
            "c0 … c20",
            Count,
            |v| v < 21.0,
            |v| Damping::paper(0.1, 0.0, 0.0, 0.0).set_coefficient(count(v), 1.0)
        ),
        row!("Damping::eval", "u", "", Total, anything, |v| total(
            Damping::paper(0.1, 0.0, 0.0, 0.0).eval(v)
        )),
        // ---- theory::averaging
        row!(
            "Theory::new",
            "mu0",
            "mu0",
            Real,
            |v| v > 0.0 && v <= 1e3,
            |v| theory_with("mu0", v, Variant::Paper)
        ),
        row!(
            "Theory::new",
            "omega0",
            "omega0",
            Real,
            |v| (1e-6..=1e3).contains(&v),
            |v| theory_with("omega0", v, Variant::Paper)
        ),
        row!("Theory::new", "lambda", "lambda", Real, unit, |v| {
            theory_with("lambda", v, Variant::Paper)
        }),
        row!(
            "Theory::new",
            "r",
            "r",
            Real,
            |v| (0.0..=1.0).contains(&v),
            |v| theory_with("r", v, Variant::Paper)
        ),
        // the consistent variant's loss −ω1 ln(r)/π is infinite at r = 0
        row!("Theory::new (consistent)", "r", "r", Real, unit, |v| {
            theory_with("r", v, Variant::Consistent)
        }),
        row!(
            "Theory::new",
            "D",
            "D",
            Real,
            |v| (0.0..=1e6).contains(&v),
            |v| theory_with("D", v, Variant::Paper)
        ),
        row!(
            "Theory::new",
            "tau",
            "tau",
            Real,
            |v| (0.0..=1e6).contains(&v),
            |v| theory_with("tau", v, Variant::Paper)
        ),
        row!(
            "Theory::new",
            "delta0",
            "delta0",
            Real,
            |v| v.abs() <= 1e20,
            |v| theory_with("delta0", v, Variant::Paper)
        ),
        // D = 0 is a valid parameter; the PDF is then `Undefined`, not an invalid parameter
        row!(
            "Theory::amplitude_pdf",
            "D",
            "D",
            Real,
            |v| (0.0..=1e6).contains(&v),
            |v| {
                let mut p = noisy();
                p.set("D", v)?;
                Theory::new(&p, Variant::Paper)?.amplitude_pdf().map(|_| ())
            }
        ),
        row!("Theory::drift", "a", "", Total, anything, |v| total(
            Theory::new(&noisy(), Variant::Paper)?.drift(v)
        )),
        row!("Theory::potential", "a", "", Total, anything, |v| total(
            Theory::new(&noisy(), Variant::Paper)?.potential(v)
        )),
        row!("Theory::fpk_drift", "a", "", Total, anything, |v| total(
            Theory::new(&noisy(), Variant::Paper)?.fpk_drift(v)
        )),
        row!(
            "AmplitudePdf::density",
            "a",
            "",
            Total,
            anything,
            |v| total(pdf().density(v))
        ),
        row!(
            "AmplitudePdf::energy_density",
            "h",
            "",
            Total,
            anything,
            |v| total(pdf().energy_density(v))
        ),
        row!(
            "AmplitudePdf::joint_density",
            "u",
            "",
            Total,
            anything,
            |v| total(pdf().joint_density(v, 0.1))
        ),
        row!("AmplitudePdf::probability", "a", "", Total, anything, |v| {
            total(pdf().probability(v, 5.0))
        }),
        row!("AmplitudePdf::probability", "b", "", Total, anything, |v| {
            total(pdf().probability(0.5, v))
        }),
        row!("phase_average_weight", "k", "", Total, anything, |v| total(
            phase_average_weight(count(v))
        )),
        row!("sgn_harmonic_sum", "c", "", Total, anything, |v| total(
            sgn_harmonic_sum(v)
        )),
        // ---- theory::bifurcation: axes, planes, branches
        // an axis holds any finite range; the plane checks the values against the parameter
        row!("Axis::new", "start", "mu0 start", Real, finite, |v| {
            Axis::new("mu0", v, 0.5, 3).map(|_| ())
        }),
        row!(
            "Axis::new",
            "stop",
            "mu0 stop",
            Real,
            |v| v.is_finite() && v != 0.01,
            |v| Axis::new("mu0", 0.01, v, 3).map(|_| ())
        ),
        row!(
            "Axis::new",
            "count",
            "mu0 count",
            Count,
            |v| (2.0..=5e7).contains(&v),
            |v| Axis::new("mu0", 0.01, 0.5, count(v)).map(|_| ())
        ),
        row!(
            "Plane::new",
            "x start",
            "mu0",
            Real,
            |v| v > 0.0 && v <= 1e3,
            |v| plane(Axis::new("mu0", v, 0.5, 3), Axis::new("r", 0.5, 1.0, 3))
        ),
        row!(
            "Plane::new",
            "y stop",
            "r",
            Real,
            |v| (0.0..=1.0).contains(&v) && v != 0.5,
            |v| plane(Axis::new("mu0", 0.01, 0.5, 3), Axis::new("r", 0.5, v, 3))
        ),
        row!(
            "Plane::new",
            "x count",
            "count",
            Count,
            |v| (2.0..=1e4).contains(&v),
            |v| plane(
                Axis::new("mu0", 0.01, 0.5, count(v)),
                Axis::new("r", 0.5, 1.0, 10_000)
            )
        ),
        row!(
            "branches",
            "start",
            "r start",
            Real,
            |v| (0.0..=1.0).contains(&v),
            |v| branch(v, 1.0, 0.01)
        ),
        row!(
            "branches",
            "stop",
            "r stop",
            Real,
            |v| (0.0..=1.0).contains(&v) && v != 0.7,
            |v| branch(0.7, v, 0.01)
        ),
        row!(
            "branches",
            "max_step",
            "max_step",
            Real,
            |v| (1e-6..=0.1).contains(&v),
            |v| branch(0.7, 1.0, v)
        ),
        // the stack kernel and the fold certificates evaluate at any point (hot paths: no checks)
        row!(
            "Kernel::stable_count",
            "point mu0",
            "",
            Total,
            anything,
            |v| {
                let mut point = Point::new(&Params::default())?;
                point.set(Key::parse("mu0")?, v);
                total(Kernel::new(Variant::Paper).stable_count(&point, What::Rhythmicity))
            }
        ),
        row!("fold_residuals", "amplitude", "", Total, anything, |v| {
            let pl = Plane::new(
                &Params::default(),
                Axis::new("mu0", 0.01, 0.5, 3)?,
                Axis::new("r", 0.5, 1.0, 3)?,
                Variant::Paper,
            )?;
            let p = FoldPoint {
                x: 0.1,
                y: 0.9,
                amplitude: v,
            };
            total((
                fold_residuals(&pl, FoldSystem::Drift, &p),
                cusp_monitor(&pl, FoldSystem::Fpk, &p),
            ))
        }),
        row!(
            "Equivalents::from_scalars",
            "mu0",
            "",
            Total,
            anything,
            |v| total(Equivalents::from_scalars(v, 1.0, 0.9, 1.0))
        ),
        // the extrema of P(A) need noise: D = 0 is refused there (a valid D elsewhere)
        row!(
            "branches (modes)",
            "D",
            "D",
            Real,
            |v| v > 0.0 && v <= 1e6,
            |v| {
                let mut base = preset("fig5").unwrap().params;
                base.set("D", v)?;
                branches(&base, Variant::Paper, What::Modes, "r", 0.7, 1.0, 0.01).map(|_| ())
            }
        ),
        // ---- theory::polynomial and quadrature: total functions
        row!(
            "Polynomial::real_roots",
            "coefficient",
            "",
            Total,
            anything,
            |v| total(Polynomial::new(vec![1.0, v, -3.0, 0.5]).real_roots(0.0, f64::INFINITY))
        ),
        row!("Polynomial::real_roots", "lo", "", Total, anything, |v| {
            total(Polynomial::new(vec![1.0, -2.0, -3.0, 0.5]).real_roots(v, 10.0))
        }),
        row!("Polynomial::real_roots", "hi", "", Total, anything, |v| {
            total(Polynomial::new(vec![1.0, -2.0, -3.0, 0.5]).real_roots(-10.0, v))
        }),
        row!("Polynomial::sturm_count", "a", "", Total, anything, |v| {
            total(Polynomial::new(vec![1.0, -2.0, -3.0, 0.5]).sturm_count(v, f64::INFINITY))
        }),
        row!("Polynomial::rescaled", "s", "", Total, anything, |v| total(
            Polynomial::new(vec![1.0, -2.0, -3.0, 0.5])
                .rescaled(v)
                .real_roots(0.0, 1.0)
        )),
        row!(
            "integrate_with_breakpoints",
            "rel_tol",
            "",
            Total,
            anything,
            |v| total(integrate_with_breakpoints(
                &|x: f64| (-x * x).exp(),
                &[-3.0, 0.0, 3.0],
                v
            ))
        ),
        row!(
            "integrate_with_breakpoints",
            "point",
            "",
            Total,
            anything,
            |v| total(integrate_with_breakpoints(
                &|x: f64| 1.0 / (1.0 + x * x),
                &[0.0, v],
                1e-10
            ))
        ),
        // ---- special functions
        row!("gamma", "x", "", Total, anything, |v| total(gamma(v))),
        row!("ln_gamma", "x", "", Total, anything, |v| total(ln_gamma(v))),
        row!("mittag_leffler", "alpha", "alpha", Real, positive, |v| {
            mittag_leffler(v, 1.0, -1.0).map(|_| ())
        }),
        row!("mittag_leffler", "beta", "beta", Real, positive, |v| {
            mittag_leffler(0.8, v, -1.0).map(|_| ())
        }),
        // z = 0, negative and huge z are in range (huge z gives NoConvergence, not a hang)
        row!("mittag_leffler", "z", "z", Real, finite, |v| {
            mittag_leffler(0.8, 1.0, v).map(|_| ())
        }),
        // ---- engine::kernel
        row!(
            "interval_weights",
            "lambda",
            "",
            Total,
            anything,
            |v| total(interval_weights(v, 0.0, 1.0))
        ),
        row!("interval_weights", "ub", "", Total, anything, |v| total(
            interval_weights(0.9, 0.0, v)
        )),
        row!(
            "SoeKernel::new",
            "lambda",
            "lambda",
            Real,
            |v| (1e-6..=1.0).contains(&v),
            |v| SoeKernel::new(v, 0.07, 100.0, 1e-10).map(|_| ())
        ),
        row!(
            "SoeKernel::new",
            "from",
            "soe window",
            Real,
            positive,
            |v| SoeKernel::new(0.9, v, 100.0, 1e-10).map(|_| ())
        ),
        row!(
            "SoeKernel::new",
            "to",
            "t_end",
            Real,
            |v| v > 0.0 && v <= 0.07e20,
            |v| { SoeKernel::new(0.9, 0.07, v, 1e-10).map(|_| ()) }
        ),
        row!(
            "SoeKernel::new",
            "tolerance",
            "tolerance",
            Real,
            |v| v > 1e-15 && v < 1.0,
            |v| SoeKernel::new(0.9, 0.07, 100.0, v).map(|_| ())
        ),
        row!("SoeKernel::check", "per_decade", "", Total, anything, |v| {
            total(SoeKernel::new(0.9, 0.07, 100.0, 1e-10)?.check(count(v)))
        }),
        // ---- engine::memory
        row!("solve_scalar", "alpha", "alpha", Real, unit, |v| scalar(
            v, 1.0, 0.01, 100, 1e-10
        )),
        // a finite y0 of any size is allowed (1e300 overflows later: an Overflow error)
        row!("solve_scalar", "y0", "y0", Real, finite, |v| scalar(
            0.8, v, 0.01, 100, 1e-10
        )),
        row!(
            "solve_scalar",
            "dt",
            "dt",
            Real,
            |v| v > 0.0 && (v * 100.0).is_finite(),
            |v| scalar(0.8, 1.0, v, 100, 1e-10)
        ),
        // no steps is allowed: y at t = 0 only
        row!("solve_scalar", "steps", "steps", Count, |v| v <= 1e8, |v| {
            scalar(0.8, 1.0, 0.01, count(v), 1e-10)
        }),
        row!(
            "solve_scalar",
            "tolerance",
            "tolerance",
            Real,
            |v| v > 1e-15 && v < 1.0,
            |v| scalar(0.8, 1.0, 0.01, 100, v)
        ),
        row!("probe_memory", "lambda", "lambda", Real, unit, |v| {
            probe_memory(v, 0.01, 100).map(|_| ())
        }),
        row!(
            "probe_memory",
            "dt",
            "dt",
            Real,
            |v| v > 0.0 && (v * 100.0).is_finite(),
            |v| probe_memory(0.9, v, 100).map(|_| ())
        ),
        row!("probe_memory", "steps", "steps", Count, |v| v <= 1e8, |v| {
            probe_memory(0.9, 0.01, count(v)).map(|_| ())
        }),
        // ---- engine::Problem and Oscillator (the wall is on: U(0) ≥ 0)
        // U(0) = 0 is allowed (at the wall)
        row!(
            "Problem::with_start",
            "u0",
            "u0",
            Real,
            |v| (0.0..1e8).contains(&v),
            |v| problem().with_start(v, 0.0).map(|_| ())
        ),
        // U̇(0) = 0 and negative U̇(0) are allowed
        row!(
            "Problem::with_start",
            "v0",
            "v0",
            Real,
            |v| v.abs() < 1e8,
            |v| problem().with_start(1.0, v).map(|_| ())
        ),
        // an infinite bound (never a blow-up) and a huge one are allowed
        row!(
            "Problem::with_blow_up",
            "blow_up",
            "blow_up",
            Real,
            |v| v > 1.0,
            |v| problem().with_blow_up(v).map(|_| ())
        ),
        row!("Oscillator::new", "lambda", "lambda", Real, unit, |v| {
            let mut p = noisy();
            p.set("lambda", v)?;
            Oscillator::new(&p).map(|_| ())
        }),
        row!(
            "Problem::with_params",
            "mu0",
            "mu0",
            Real,
            |v| v > 0.0 && v <= 1e3,
            |v| {
                let mut p = noisy();
                p.set("mu0", v)?;
                problem().with_params(&p).map(|_| ())
            }
        ),
        // ---- engine: the method, the options, the stepper, the drivers
        row!(
            "simulate (PredictorCorrector)",
            "dt",
            "dt",
            Real,
            |v| v > 0.0 && v <= 1e3,
            |v| sim(|m, _| m.dt = v)
        ),
        row!(
            "simulate (Memory::SumOfExponentials)",
            "tolerance",
            "tolerance",
            Real,
            |v| v > 1e-15 && v < 1e-2,
            |v| sim(|m, _| m.memory = soe(v))
        ),
        row!(
            "simulate (PredictorCorrector)",
            "window",
            "window",
            Count,
            |v| (2.0..=4096.0).contains(&v),
            |v| sim(|m, _| m.window = count(v))
        ),
        row!(
            "simulate (Options)",
            "t_end",
            "t_end",
            Real,
            |v| v == 1.0,
            |v| { sim(|_, o| o.t_end = v) }
        ),
        // any k ≥ 1 is allowed (a huge k records the start only)
        row!(
            "simulate (Options)",
            "record_every",
            "every",
            Count,
            |v| v >= 1.0,
            |v| sim(|_, o| o.record_every = count(v))
        ),
        // 0 periods is allowed: the amplitude of the last node
        row!(
            "simulate (Options)",
            "amplitude_periods",
            "amplitude_periods",
            Real,
            |v| (0.0..=1e6).contains(&v),
            |v| sim(|_, o| o.amplitude_periods = v)
        ),
        row!(
            "simulate_with",
            "dt",
            "dt",
            Real,
            |v| v > 0.0 && v <= 1e3,
            |v| {
                let m = PredictorCorrector { dt: v, ..method() };
                let o = Options {
                    t_end: 1.0,
                    ..Default::default()
                };
                simulate_with(&problem(), &m, &o, &Silent).map(|_| ())
            }
        ),
        // no paths is an empty ensemble
        row!(
            "simulate_ensemble",
            "paths",
            "paths",
            Count,
            |v| v <= 1e6,
            |v| {
                let o = Options {
                    t_end: 1.0,
                    ..Default::default()
                };
                simulate_ensemble(&problem(), &method(), &o, count(v)).map(|_| ())
            }
        ),
        row!(
            "simulate_ensemble",
            "tolerance",
            "tolerance",
            Real,
            |v| v > 1e-15 && v < 1e-2,
            |v| {
                let m = PredictorCorrector {
                    memory: soe(v),
                    ..method()
                };
                let o = Options {
                    t_end: 1.0,
                    ..Default::default()
                };
                simulate_ensemble(&problem(), &m, &o, 2).map(|_| ())
            }
        ),
        // a horizon of 0 is allowed (a stepper to look at its start)
        row!(
            "Stepper::new",
            "horizon",
            "horizon",
            Real,
            |v| v >= 0.0 && v / 0.05 <= 1e7,
            |v| Stepper::new(&problem(), &method(), (1, 0), v).map(|_| ())
        ),
        row!(
            "Stepper::new",
            "dt",
            "dt",
            Real,
            |v| v > 0.0 && v <= 1e3,
            |v| {
                let m = PredictorCorrector { dt: v, ..method() };
                Stepper::new(&problem(), &m, (1, 0), 1.0).map(|_| ())
            }
        ),
        // no steps is allowed
        row!("run", "steps", "steps", Count, |v| v <= 1e11, |v| {
            let mut s = Stepper::new(&problem(), &method(), (1, 0), 1.0)?;
            run_path(
                &mut s,
                count(v) as u64,
                &mut |_: &Stepper| Flow::Continue,
                &Silent,
            )
            .map(|_| ())
        }),
        row!(
            "TrajectoryRecorder::new",
            "steps",
            "steps",
            Count,
            |v| v < 1e8,
            |v| {
                let o = Options::default();
                TrajectoryRecorder::new(problem().oscillator(), &o, count(v) as u64, 0.05)
                    .map(|_| ())
            }
        ),
        row!(
            "TrajectoryRecorder::new",
            "dt",
            "dt",
            Real,
            |v| v > 0.0 && v <= 1e3,
            |v| TrajectoryRecorder::new(problem().oscillator(), &Options::default(), 20, v)
                .map(|_| ())
        ),
        // a contraction by any factor returns promptly: a non-finite or negative one is refused
        // (false), never applied
        row!("Stepper::contract_toward", "c", "", Total, anything, |v| {
            let a = Stepper::new(&problem(), &method(), (1, 0), 1.0)?;
            let mut b = a.clone();
            total(b.contract_toward(&a, v))
        }),
        // ---- engine::noise: the streams take any finite step, intensity and correlation time
        row!("NoiseStream::new", "dt", "dt", Real, positive, |v| {
            NoiseStream::new(Noise::White { intensity: 0.1 }, v, 1, 0).map(|_| ())
        }),
        // D = 0 is allowed: no forcing
        row!(
            "NoiseStream::new (white)",
            "intensity",
            "D",
            Real,
            |v| v >= 0.0 && v.is_finite(),
            |v| NoiseStream::new(Noise::White { intensity: v }, 0.01, 1, 0).map(|_| ())
        ),
        row!(
            "NoiseStream::new (coloured)",
            "correlation_time",
            "tau",
            Real,
            positive,
            |v| {
                let kind = Noise::Colored {
                    intensity: 0.1,
                    correlation_time: v,
                };
                NoiseStream::new(kind, 0.01, 1, 0).map(|_| ())
            }
        ),
        // ---- analysis::ensemble: every field of the spec, the pieces, the merge
        row!(
            "run_ensemble (EnsembleSpec)",
            "paths",
            "paths",
            Count,
            |v| (1.0..=1e6).contains(&v),
            |v| ens(|s| s.paths = count(v))
        ),
        // no burn-in is allowed
        row!(
            "run_ensemble (EnsembleSpec)",
            "burn_in",
            "burn_in",
            Real,
            |v| v == 0.0,
            |v| ens(|s| s.burn_in = v)
        ),
        row!(
            "run_ensemble (EnsembleSpec)",
            "length",
            "t_end",
            Real,
            |v| v == 1.0,
            |v| ens(|s| s.length = v)
        ),
        row!(
            "run_ensemble (EnsembleSpec)",
            "sample_every",
            "sample_every",
            Count,
            |v| v == 1.0,
            |v| ens(|s| s.sample_every = count(v) as u64)
        ),
        row!(
            "run_ensemble (EnsembleSpec)",
            "bins",
            "bins",
            Count,
            |v| (2.0..=1e4).contains(&v),
            |v| ens(|s| s.bins = count(v))
        ),
        row!(
            "run_ensemble (EnsembleSpec)",
            "joint_bins",
            "joint_bins",
            Count,
            |v| (2.0..=1e3).contains(&v),
            |v| ens(|s| s.joint_bins = count(v))
        ),
        row!(
            "run_ensemble (EnsembleSpec)",
            "amplitude_max",
            "amplitude_max",
            Real,
            |v| v > 0.0 && v <= 1e6,
            |v| ens(|s| s.amplitude_max = v)
        ),
        row!(
            "run_ensemble (EnsembleSpec)",
            "joint_velocity_factor",
            "joint_velocity_factor",
            Real,
            |v| v > 0.0 && v <= 1e3,
            |v| ens(|s| s.joint_velocity_factor = v)
        ),
        row!(
            "run_ensemble (EnsembleSpec)",
            "lanes",
            "lanes",
            Count,
            |v| [1.0, 4.0, 8.0].contains(&v),
            |v| ens(|s| s.lanes = Lanes::Width(count(v)))
        ),
        row!(
            "run_ensemble (EnsembleSpec)",
            "batches",
            "batches",
            Count,
            |v| v == 4.0,
            |v| ens(|s| s.batches = count(v))
        ),
        // a last mode far out (1e300) is allowed: a well nobody reaches
        row!(
            "run_ensemble (EnsembleSpec::wells)",
            "mode",
            "wells",
            Real,
            |v| v.is_finite() && v > 2.0,
            |v| ens(|s| s.wells = Some(Wells {
                modes: vec![1.0, v],
                antimodes: vec![2.0],
            }))
        ),
        row!(
            "run_ensemble (PredictorCorrector)",
            "dt",
            "dt",
            Real,
            |v| v > 0.0 && v <= 1e3,
            |v| {
                let m = PredictorCorrector { dt: v, ..method() };
                run_ensemble(&problem(), &m, &ensemble_spec(), &Silent).map(|_| ())
            }
        ),
        // index 0 of two paths is allowed
        row!(
            "ensemble::run_paths",
            "index",
            "paths",
            Count,
            |v| v < 2.0,
            |v| ensemble::run_paths(
                &problem(),
                &method(),
                &ensemble_spec(),
                &[count(v) as u64],
                &Silent
            )
            .map(|_| ())
        ),
        row!(
            "ensemble::run_paths",
            "index (after path 0)",
            "paths",
            Count,
            |v| v == 1.0,
            |v| ensemble::run_paths(
                &problem(),
                &method(),
                &ensemble_spec(),
                &[0, count(v) as u64],
                &Silent
            )
            .map(|_| ())
        ),
        row!(
            "ensemble::merge",
            "path index",
            "paths",
            Count,
            |v| v == 1.0,
            |v| {
                let mut stats = ensemble_stats();
                stats[1].path = count(v) as u64;
                ensemble::merge(&problem(), &method(), &ensemble_spec(), stats).map(|_| ())
            }
        ),
        row!(
            "ensemble::merge",
            "amplitude_max",
            "amplitude_max",
            Real,
            |v| v == 10.0,
            |v| {
                let spec = EnsembleSpec {
                    amplitude_max: v,
                    ..ensemble_spec()
                };
                ensemble::merge(&problem(), &method(), &spec, ensemble_stats()).map(|_| ())
            }
        ),
        // ---- analysis::lyapunov: every field of the spec, Δt, the pieces
        row!(
            "largest_lyapunov (LyapunovSpec)",
            "lanes",
            "lanes",
            Count,
            |v| [1.0, 4.0, 8.0].contains(&v),
            |v| lle(|s, _| s.lanes = Lanes::Width(count(v)))
        ),
        row!(
            "largest_lyapunov (LyapunovSpec)",
            "paths",
            "paths",
            Count,
            |v| (1.0..=1e5).contains(&v),
            |v| lle(|s, _| s.paths = count(v))
        ),
        // no transient is allowed
        row!(
            "largest_lyapunov (LyapunovSpec)",
            "transient",
            "transient",
            Real,
            |v| v == 0.0,
            |v| lle(|s, _| s.transient = v)
        ),
        row!(
            "largest_lyapunov (LyapunovSpec)",
            "length",
            "t_end",
            Real,
            |v| v == 1.0,
            |v| lle(|s, _| s.length = v)
        ),
        row!(
            "largest_lyapunov (LyapunovSpec)",
            "renormalise_every",
            "renormalise_every",
            Count,
            |v| (1.0..=10.0).contains(&v),
            |v| lle(|s, _| s.renormalise_every = count(v) as u64)
        ),
        row!(
            "largest_lyapunov (LyapunovSpec)",
            "separation",
            "separation",
            Real,
            |v| (1e-12..=1e-4).contains(&v),
            |v| lle(|s, _| s.separation = v)
        ),
        row!(
            "largest_lyapunov (LyapunovSpec)",
            "running_points",
            "running_points",
            Count,
            |v| (1.0..=1e5).contains(&v),
            |v| lle(|s, _| s.running_points = count(v))
        ),
        row!(
            "largest_lyapunov (PredictorCorrector)",
            "dt",
            "dt",
            Real,
            |v| (1e-4..=0.1).contains(&v),
            |v| lle(|_, m| m.dt = v)
        ),
        row!(
            "largest_lyapunov (Memory::SumOfExponentials)",
            "tolerance",
            "tolerance",
            Real,
            |v| v > 1e-15 && v < 1e-2,
            |v| lle(|_, m| m.memory = soe(v))
        ),
        row!(
            "lyapunov::run_paths",
            "index",
            "paths",
            Count,
            |v| v < 2.0,
            |v| lyapunov::run_paths(
                &problem(),
                &method(),
                &lyapunov_spec(),
                &[count(v) as u64],
                &Silent
            )
            .map(|_| ())
        ),
        row!(
            "lyapunov::run_paths",
            "index (after path 0)",
            "paths",
            Count,
            |v| v == 1.0,
            |v| lyapunov::run_paths(
                &problem(),
                &method(),
                &lyapunov_spec(),
                &[0, count(v) as u64],
                &Silent
            )
            .map(|_| ())
        ),
        row!(
            "lyapunov::merge",
            "path index",
            "paths",
            Count,
            |v| v == 1.0,
            |v| {
                let mut runs = lyapunov_runs();
                runs[1].exponent.path = count(v) as u64;
                lyapunov::merge(&lyapunov_spec(), runs).map(|_| ())
            }
        ),
        row!(
            "lyapunov::merge",
            "separation",
            "separation",
            Real,
            |v| (1e-12..=1e-4).contains(&v),
            |v| {
                let spec = LyapunovSpec {
                    separation: v,
                    ..lyapunov_spec()
                };
                lyapunov::merge(&spec, lyapunov_runs()).map(|_| ())
            }
        ),
        // ---- analysis::oscillation: the plane, the classifier, the search, the drivers
        row!(
            "oscillation::Plane::new",
            "abscissa",
            "omega0",
            Real,
            |v| (1e-6..=1e3).contains(&v),
            |v| OscillationPlane::new(&template(), ("omega0", vec![v]), ("r", 0.5, 1.0))
                .map(|_| ())
        ),
        // r = 0 is allowed: a perfectly plastic wall
        row!(
            "oscillation::Plane::new",
            "y lo",
            "r",
            Real,
            |v| (0.0..1.0).contains(&v),
            |v| OscillationPlane::new(&template(), ("omega0", vec![1.0]), ("r", v, 1.0))
                .map(|_| ())
        ),
        row!(
            "oscillation::Plane::new",
            "y hi",
            "r",
            Real,
            |v| v > 0.5 && v <= 1.0,
            |v| OscillationPlane::new(&template(), ("omega0", vec![1.0]), ("r", 0.5, v))
                .map(|_| ())
        ),
        row!(
            "growth_rate (Classifier)",
            "dt",
            "dt",
            Real,
            |v| (1e-4..=0.1).contains(&v),
            |v| growth(|c| c.method.dt = v)
        ),
        row!(
            "growth_rate (Classifier)",
            "tolerance",
            "tolerance",
            Real,
            |v| v > 1e-15 && v < 1e-2,
            |v| growth(|c| c.method.memory = soe(v))
        ),
        row!(
            "growth_rate (Classifier)",
            "amplitude",
            "amplitude",
            Real,
            |v| v > 0.0 && v <= 1e-3,
            |v| growth(|c| c.amplitude = v)
        ),
        // no settling is allowed
        row!(
            "growth_rate (Classifier)",
            "settle_periods",
            "settle_periods",
            Real,
            |v| (0.0..=2.0).contains(&v),
            |v| growth(|c| c.settle_periods = v)
        ),
        row!(
            "growth_rate (Classifier)",
            "min_periods",
            "min_periods",
            Real,
            |v| (1.0..=2.0).contains(&v),
            |v| growth(|c| c.min_periods = v)
        ),
        row!(
            "growth_rate (Classifier)",
            "max_periods",
            "max_periods",
            Real,
            |v| (2.0..=1e4).contains(&v),
            |v| growth(|c| c.max_periods = v)
        ),
        row!(
            "growth_rate (Classifier)",
            "clarity",
            "clarity",
            Real,
            |v| v > 0.0 && v <= 1e6,
            |v| growth(|c| c.clarity = v)
        ),
        row!(
            "growth_rate (Classifier)",
            "agreement",
            "agreement",
            Real,
            unit,
            |v| growth(|c| c.agreement = v)
        ),
        // only the noise-free system has an oscillation boundary: D = 0 only
        row!("growth_rate", "D", "D", Real, |v| v == 0.0, |v| {
            let p = Params::default().with("D", v)?;
            growth_rate(&Problem::from_params(&p)?, &classifier()).map(|_| ())
        }),
        row!(
            "boundary (Search)",
            "tolerance",
            "tolerance",
            Real,
            |v| v > 0.0 && v <= 0.1,
            |v| {
                let search = Search {
                    tolerance: v,
                    ..Default::default()
                };
                boundary(&oscillation_plane(), &Method::Exact, &search, &Silent).map(|_| ())
            }
        ),
        row!(
            "boundary (Method::Simulation)",
            "amplitude",
            "amplitude",
            Real,
            |v| v > 0.0 && v <= 1e-3,
            |v| {
                let c = Classifier {
                    amplitude: v,
                    ..classifier()
                };
                let m = Method::Simulation(c);
                boundary(&oscillation_plane(), &m, &Search::default(), &Silent).map(|_| ())
            }
        ),
        row!(
            "boundary (Plane::y_range)",
            "y lo",
            "r",
            Real,
            |v| (0.0..1.0).contains(&v),
            |v| {
                let mut plane = oscillation_plane();
                plane.y_range.0 = v;
                boundary(&plane, &Method::Exact, &Search::default(), &Silent).map(|_| ())
            }
        ),
        // r = 0 is allowed: a perfectly plastic wall
        row!(
            "classify_plane",
            "y",
            "r",
            Real,
            |v| (0.0..=1.0).contains(&v),
            |v| classify_plane(
                &oscillation_plane(),
                &[0.9, v],
                &Method::Averaging(Variant::Paper),
                &Silent
            )
            .map(|_| ())
        ),
        row!(
            "classify_plane (Method::Simulation)",
            "dt",
            "dt",
            Real,
            |v| (1e-4..=0.1).contains(&v),
            |v| {
                let mut c = classifier();
                c.method.dt = v;
                classify_plane(
                    &oscillation_plane(),
                    &[0.9],
                    &Method::Simulation(c),
                    &Silent,
                )
                .map(|_| ())
            }
        ),
        row!("margin", "mu0", "mu0", Real, |v| v > 0.0 && v <= 1e3, |v| {
            let mut p = Params::default();
            p.set("mu0", v)?;
            margin(&p, Barrier::Off, &Method::Exact).map(|_| ())
        }),
        row!("averaging_mu0", "lambda", "", Total, anything, |v| {
            let mut p = Params::default();
            p.set("lambda", v)?;
            total(averaging_mu0(&p, Barrier::On, Variant::Paper))
        }),
        row!("exact_mu0", "lambda", "", Total, anything, |v| {
            let mut p = Params::default();
            p.set("lambda", v)?;
            total(exact_mu0(&p, Barrier::Off))
        }),
        // ---- analysis::recurrence and versus
        row!(
            "RecurrenceMatrix::new",
            "epsilon",
            "epsilon",
            Real,
            positive,
            |v| {
                let x: Vec<f64> = (0..200).map(|i| (0.1 * i as f64).sin()).collect();
                RecurrenceMatrix::new(&x, &x, RecurrenceThreshold(v)).map(|_| ())
            }
        ),
        row!(
            "RecurrenceMatrix::determinism",
            "min_line",
            "",
            Total,
            anything,
            |v| {
                let x: Vec<f64> = (0..200).map(|i| (0.1 * i as f64).sin()).collect();
                total(
                    RecurrenceMatrix::new(&x, &x, RecurrenceThreshold(0.1))?.determinism(count(v)),
                )
            }
        ),
        // a last edge far out (1e300) is allowed: an empty last bin
        row!(
            "compare (EnsembleResult)",
            "last edge",
            "edges",
            Real,
            |v| v.is_finite() && v > 7.5,
            |v| {
                let mut result = ensemble_result();
                *result.amplitude.edges.last_mut().unwrap() = v;
                compare(&result, &Theory::new(&noisy(), Variant::Paper)?, 1).map(|_| ())
            }
        ),
        row!("escape_time", "sigma1", "", Total, anything, |v| total(
            escape_time(pdf(), v, 1.0, 3.0)
        )),
        row!("escape_time", "a", "", Total, anything, |v| total(
            escape_time(pdf(), 1e-3, v, 3.0)
        )),
        row!("escape_time", "b", "", Total, anything, |v| total(
            escape_time(pdf(), 1e-3, 1.0, v)
        )),
        row!("theory_layout", "D", "", Total, anything, |v| {
            let mut p = noisy();
            p.set("D", v)?;
            total(theory_layout(&p, Variant::Paper))
        }),
    ]
}

/// What a call did.
#[derive(Debug)]
enum Outcome {
    Returned(Result<(), Error>),
    Panicked,
    Hung,
}

/// Run `call(v)` on its own thread: a panic is caught, a call past [`LIMIT`] is a hang (its
/// thread is left behind; the test fails anyway).
fn run(call: fn(f64) -> Result<(), Error>, v: f64) -> (Outcome, Duration) {
    let (tx, rx) = mpsc::channel();
    let start = Instant::now();
    std::thread::spawn(move || {
        let r = catch_unwind(|| call(v));
        let _ = tx.send(r);
    });
    let outcome = match rx.recv_timeout(LIMIT) {
        Ok(Ok(r)) => Outcome::Returned(r),
        Ok(Err(_)) | Err(mpsc::RecvTimeoutError::Disconnected) => Outcome::Panicked,
        Err(mpsc::RecvTimeoutError::Timeout) => Outcome::Hung,
    };
    (outcome, start.elapsed())
}

/// The row's verdict on one value: None when it behaved, else what went wrong.
fn judge(row: &Row, v: f64) -> Option<String> {
    // a count is the value as the closure sees it (saturated to usize)
    let v = if row.kind == Kind::Count {
        count(v) as f64
    } else {
        v
    };
    let (outcome, took) = run(row.call, v);
    let at = format!("{}({} = {v:e})", row.entry, row.arg);
    if std::env::var_os("HOSTILE_VERBOSE").is_some() {
        eprintln!("{at} [{took:?}]: {outcome:?}");
    }
    match outcome {
        Outcome::Panicked => Some(format!("{at} panicked")),
        Outcome::Hung => Some(format!("{at} took more than {LIMIT:?}")),
        Outcome::Returned(_) if took > LIMIT => Some(format!("{at} took {took:?}")),
        Outcome::Returned(_) if row.kind == Kind::Total => None,
        Outcome::Returned(r) if (row.accepts)(v) => match r {
            Err(e @ Error::InvalidParameter { .. }) => {
                Some(format!("{at} is in range but was refused: {e}"))
            }
            _ => None,
        },
        Outcome::Returned(Ok(())) => Some(format!("{at} is out of range but was accepted")),
        Outcome::Returned(Err(e)) => {
            let msg = e.to_string();
            (!msg.contains(row.needle))
                .then(|| format!("{at}: the error does not name `{}`: {msg}", row.needle))
        }
    }
}

fn values(kind: Kind) -> Vec<f64> {
    match kind {
        Kind::Real => REALS.to_vec(),
        Kind::Count => COUNTS.to_vec(),
        Kind::Total => REALS.iter().chain(&COUNTS).copied().collect(),
    }
}

#[test]
fn every_argument_refuses_hostile_values_by_name_promptly() {
    let table = rows();
    let mut failures = Vec::new();
    let mut calls = 0;
    for row in &table {
        for v in values(row.kind) {
            calls += 1;
            failures.extend(judge(row, v));
        }
    }
    eprintln!("{} rows, {calls} calls", table.len());
    assert!(
        failures.is_empty(),
        "{} of {calls} calls misbehaved:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

#[test]
fn valid_calls_of_the_table_succeed() {
    // each row's closure with a value in range really computes (so that a refusal above is the
    // argument's, not a broken closure's)
    let typical: &[(&str, &str, f64)] = &[
        ("branches", "max_step", 0.01),
        ("Plane::new", "x start", 0.02),
        ("solve_scalar", "steps", 50.0),
        ("SoeKernel::new", "tolerance", 1e-8),
        ("mittag_leffler", "z", -2.0),
        ("RecurrenceMatrix::new", "epsilon", 0.2),
        ("simulate (PredictorCorrector)", "dt", 0.05),
        ("simulate_ensemble", "paths", 2.0),
        ("run", "steps", 10.0),
        ("run_ensemble (EnsembleSpec)", "burn_in", 0.5),
        ("largest_lyapunov (LyapunovSpec)", "transient", 0.5),
        ("growth_rate (Classifier)", "settle_periods", 1.0),
        ("boundary (Search)", "tolerance", 0.01),
        ("classify_plane", "y", 0.7),
        ("compare (EnsembleResult)", "last edge", 10.0),
    ];
    let table = rows();
    for &(entry, arg, v) in typical {
        let row = table
            .iter()
            .find(|r| r.entry == entry && r.arg == arg)
            .expect("row");
        match run(row.call, v).0 {
            Outcome::Returned(Ok(())) => {}
            other => panic!("{entry}({arg} = {v}): {other:?}"),
        }
    }
}

#[test]
fn the_recurrence_matrix_refuses_more_points_than_it_can_hold() {
    let n = trirhythm::analysis::recurrence::MAX_RECURRENCE_POINTS + 1;
    let x = vec![0.0; n];
    let e = RecurrenceMatrix::new(&x, &x, RecurrenceThreshold(0.1)).unwrap_err();
    assert!(e.to_string().contains("points"), "{e}");
}

#[test]
fn sizes_that_cannot_be_built_in_a_row_are_refused_too() {
    // more abscissae than a plane holds: refused by count before any is checked
    let x = vec![1.0; trirhythm::analysis::oscillation::MAX_ABSCISSAE + 1];
    let e = OscillationPlane::new(&template(), ("omega0", x), ("r", 0.5, 1.0)).unwrap_err();
    assert!(e.to_string().contains("omega0"), "{e}");
    // more cells than a classification holds
    let ys = vec![0.9; trirhythm::analysis::oscillation::MAX_CELLS + 1];
    let e = classify_plane(&oscillation_plane(), &ys, &Method::Exact, &Silent).unwrap_err();
    assert!(e.to_string().contains("points"), "{e}");
    // a direct memory longer than it can hold
    let o = Options {
        t_end: 1e6,
        ..Default::default()
    };
    let e = simulate(&problem(), &method(), &o).unwrap_err();
    assert!(e.to_string().contains("direct memory"), "{e}");
    // more wells than the statistics hold
    let n = ensemble::MAX_WELLS + 1;
    let modes: Vec<f64> = (0..n).map(|i| 2.0 * i as f64).collect();
    let antimodes: Vec<f64> = (1..n).map(|i| 2.0 * i as f64 - 1.0).collect();
    let e = Wells::new(modes, antimodes).unwrap_err();
    assert!(e.to_string().contains("wells"), "{e}");
    // statistics of all paths beyond the bound
    let spec = EnsembleSpec {
        paths: 1_000_000,
        joint_bins: 1000,
        ..ensemble_spec()
    };
    let e = run_ensemble(&problem(), &method(), &spec, &Silent).unwrap_err();
    assert!(e.to_string().contains("paths"), "{e}");
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 96, ..ProptestConfig::default() })]

    /// Random hostile values (any NaN, infinity, negative number, or a huge one) in a random
    /// row: the same verdict as the fixed values.
    #[test]
    fn random_hostile_values_are_refused_by_name_promptly(
        pick in any::<prop::sample::Index>(),
        v in prop_oneof![
            Just(f64::NAN),
            Just(f64::INFINITY),
            Just(f64::NEG_INFINITY),
            -1e300..-1e-300f64,
            1e15..1e300f64,
        ],
    ) {
        let table = rows();
        let row = &table[pick.index(table.len())];
        if let Some(failure) = judge(row, v) {
            prop_assert!(false, "{}", failure);
        }
    }
}
