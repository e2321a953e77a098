//! The D = 0 control of the Lyapunov figures: on a stable deterministic limit cycle the largest
//! exponent is 0, for every parameter set of Figs 13(b) and 17–19 that has a stable cycle, at
//! the figures' Δt and half of it, by both methods.
//!
//! # What theory says, and the bound
//! Along a periodic orbit x(t) of an autonomous system the direction of the flow is neutral:
//! the perturbation ẋ(t) = F(x(t)) stays ẋ(t) (time shift), every other direction decays on a
//! stable cycle. After the transient the tangent is c·F(x(t)), so its log-norm
//! S(t) = ln‖δx(t)‖ changes between two instants by ln‖F(x(t₂))‖ − ln‖F(x(t₁))‖: it stays in a
//! band of width R = ln(max‖F‖/min‖F‖) over the orbit, and a finite-time exponent over a
//! window W, (S(W) − S(0))/W, is bounded by R/W. (δx = (δU, δU̇), so F = (U̇, Ü); Ü is taken by
//! central differences of the recorded noise-free path, away from impacts.) For λ < 1 the
//! fractional memory makes the orbit only asymptotically periodic and the flow direction only
//! asymptotically neutral: its tail, with weight ≈ (1 − λ), adds ≈ (1 − λ)·ln(W/Δt)/W at most
//! (the kernel's integral over the window against a bounded forcing). The bound tested is
//! |λ̂| ≤ (R + (1 − λ)·ln(W/Δt) + 1)/W: the + 1 is e-fold of room for a transverse component
//! left by the transient on the slowest cycle (μ0 = 0.001), stated and not tuned per case.
//!
//! # The defect this guards
//! Up to 6ae8a9e a step took a second corrector pass only where |Δt·μP| > 1/2: the step map
//! jumped there, twice a period on a stiff cycle, and locked the orbit's phase to the time
//! grid. Fig. 17(a)'s μ0 = 0.1 at Δt = 0.01 gave λ̂ = −2.5·10⁻² (λ̂W = −50 against R ≈ 8).

use trirhythm::analysis::lyapunov::{largest_lyapunov, LyapunovMethod, LyapunovSpec};
use trirhythm::engine::{simulate, ImpactMemory, Options, PredictorCorrector, Problem};
use trirhythm::model::{preset, Params};
use trirhythm::monitor::Silent;
use trirhythm::theory::averaging::{Theory, Variant};

const SEED: u64 = 20240611;
const TRANSIENT: f64 = 500.0;
const WINDOW: f64 = 2000.0;
/// Nodes closer to the wall than this are left out of the band: V changes by (1 + r)|V₋| within
/// one step there (|V₋| ≈ 28 on these cycles: 0.5 is about 0.02 time units of the orbit).
const NEAR_WALL: f64 = 0.5;

/// One parameter set of a figure with the step its figure uses.
struct Case {
    label: String,
    params: Params,
    dt: f64,
}

fn with(name: &str, pairs: &[(&str, f64)]) -> Params {
    let mut p = preset(name).unwrap().params;
    for &(k, v) in pairs {
        p = p.with(k, v).unwrap();
    }
    p.with("D", 0.0).unwrap()
}

/// Every parameter set of the Lyapunov figures (and Fig. 13(b)'s stiff μ0 = 0.2), at the
/// figures' Δt (τ/10 on the ladder 0.01, 0.005, 0.0025: `trirhythm_paper::lle::dt_for`).
fn cases() -> Vec<Case> {
    let mut out = Vec::new();
    let mut add = |fig: &str, p: Params, dt: f64| {
        let label = format!("{fig} {}", p.describe());
        out.push(Case {
            label,
            params: p,
            dt,
        });
    };
    for mu0 in [0.001, 0.01, 0.05, 0.1] {
        add("fig17a", with("fig17a", &[("mu0", mu0)]), 0.005);
    }
    for lambda in [0.95, 0.98, 0.995, 1.0] {
        add("fig18a", with("fig18a", &[("lambda", lambda)]), 0.0025);
    }
    for r in [0.998, 0.95, 0.9, 0.8] {
        add("fig18b", with("fig18b", &[("r", r)]), 0.0025);
    }
    for mu0 in [0.005, 0.01, 0.02, 0.05, 0.1] {
        add("fig19a", with("fig19", &[("mu0", mu0)]), 0.01);
    }
    for lambda in [0.95, 0.97, 0.98, 0.99] {
        add("fig19c", with("fig19", &[("lambda", lambda)]), 0.01);
    }
    for r in [0.8, 0.85, 0.9, 0.95] {
        add("fig19d", with("fig19", &[("r", r)]), 0.01);
    }
    add("fig13b", with("fig13b", &[("r", 0.95)]), 0.005);
    out
}

/// The outer stable cycle's amplitude of the averaged theory (the figures' cycle start).
fn outer_cycle(p: &Params) -> Option<f64> {
    let theory = Theory::new(p, Variant::Paper).unwrap();
    theory
        .limit_cycles()
        .into_iter()
        .filter(|c| c.stable && c.amplitude.is_finite())
        .map(|c| c.amplitude)
        .reduce(f64::max)
}

/// R = ln(max‖F‖/min‖F‖), F = (U̇, Ü), over the noise-free path's window, with whether the
/// path is still oscillating at its end (not at rest on the wall).
fn band(problem: &Problem, method: &PredictorCorrector) -> (f64, bool) {
    let o = Options {
        t_end: TRANSIENT + WINDOW,
        seed: SEED,
        record_every: 1,
        ..Default::default()
    };
    let tr = simulate(problem, method, &o).unwrap();
    let (u, v, dt) = (&tr.u, &tr.v, method.dt);
    let first = (TRANSIENT / dt) as usize;
    let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
    for n in first.max(1)..u.len() - 1 {
        // away from the wall: an impact's jump of V inside the difference is not Ü (the flow
        // vector's jump there is the saltation's, |V₊| = r|V₋|, inside the band)
        if u[n - 1] < NEAR_WALL || u[n] < NEAR_WALL || u[n + 1] < NEAR_WALL {
            continue;
        }
        let acc = (v[n + 1] - v[n - 1]) / (2.0 * dt);
        let f = v[n].hypot(acc);
        lo = lo.min(f);
        hi = hi.max(f);
    }
    let oscillating = u[first..].iter().cloned().fold(0.0, f64::max) > 0.5;
    ((hi / lo).ln(), oscillating)
}

#[test]
fn a_deterministic_cycle_has_a_zero_exponent_at_the_figures_steps() {
    let mut checked = 0;
    let mut failures = Vec::new();
    for case in cases() {
        let Some(a) = outer_cycle(&case.params) else {
            continue;
        };
        for dt in [case.dt, case.dt / 2.0] {
            let problem = Problem::from_params(&case.params)
                .and_then(|q| q.with_start(a, 0.0))
                .unwrap();
            let method = PredictorCorrector {
                dt,
                impact_memory: ImpactMemory::Restart,
                ..Default::default()
            };
            let (r, oscillating) = band(&problem, &method);
            if !oscillating {
                continue;
            }
            let lambda = case.params.lambda;
            let bound = (r + (1.0 - lambda) * (WINDOW / dt).ln() + 1.0) / WINDOW;
            for m in [LyapunovMethod::Tangent, LyapunovMethod::TwoTrajectory] {
                let spec = LyapunovSpec {
                    paths: 1,
                    seed: SEED,
                    transient: TRANSIENT,
                    length: WINDOW,
                    method: m,
                    ..Default::default()
                };
                let e = largest_lyapunov(&problem, &method, &spec, &Silent)
                    .unwrap()
                    .lle
                    .value;
                println!(
                    "{}, A = {a:.3}, dt = {dt}, {}: λ̂ = {e:+.2e}, bound {bound:.2e} (R = {r:.2})",
                    case.label,
                    m.name()
                );
                checked += 1;
                if e.abs() > bound {
                    failures.push(format!("{} dt = {dt} {}: {e:e}", case.label, m.name()));
                }
            }
        }
    }
    assert!(checked >= 40, "{checked} exponents checked");
    assert!(
        failures.is_empty(),
        "nonzero cycle exponents: {failures:#?}"
    );
}
