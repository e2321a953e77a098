//! Hostile inputs: every public entry point of the model, the theory, the special functions,
//! the memory kernels and the recurrence analysis, called with each numeric argument in turn
//! replaced by NaN, ±∞, 0, a negative value and a huge one (1e300; 10¹² and `usize::MAX` for
//! counts) while the others stay valid.
//!
//! The claim (issue "every check in the library"): within one second, without a panic, the call
//! returns an `Err` that names the argument, or — where the value is legitimately in range, as
//! each row's `accepts` states — anything but an invalid-parameter error. Functions that return
//! a plain number (evaluations such as P(A) at a point, Γ(x), a quadrature) are total: they are
//! only required to return promptly without panicking (`Kind::Total`).
//!
//! The table is one `Row` per (entry point, argument); other drivers (simulation, ensembles,
//! Lyapunov exponents) extend it by adding rows.

use proptest::prelude::*;
use std::panic::catch_unwind;
use std::sync::mpsc;
use std::sync::OnceLock;
use std::time::{Duration, Instant};
use trirhythm::analysis::recurrence::{RecurrenceMatrix, RecurrenceThreshold};
use trirhythm::analysis::versus::{escape_time, theory_layout};
use trirhythm::engine::kernel::{interval_weights, SoeKernel};
use trirhythm::engine::{probe_memory, solve_scalar, Memory};
use trirhythm::model::preset;
use trirhythm::model::Equivalents;
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
