//! Models and checks shared by the tests of the General kernel's terms (`tests/fractional.rs`,
//! `tests/general.rs`, `tests/walls.rs`): the linear oscillator the known answers start from,
//! the chattering preset, time averages, and the check that paths give the same bits alone,
//! as clones and in lanes.
// Each test crate uses a different subset.
#![allow(dead_code)]

use std::fmt::Debug;
use trirhythm::engine::{run, run_lanes, Flow, Lanes, PredictorCorrector, Problem, Stepper};
use trirhythm::model::{Model, Params};
use trirhythm::monitor::Silent;

/// The seed of every path of these tests.
pub const SEED: u64 = 20_261_127;

/// The paper's fig1 model made linear: λ, h ≡ −c (μ0 = c, P ≡ −1), ω0 = 1, no wall, no noise.
pub fn linear(lambda: f64, c: f64) -> Model {
    let mut m = Model::from(&trirhythm::model::preset("fig1").unwrap().params);
    m.leading.lambda = lambda;
    m.damping.mu0 = c;
    m.damping.coefficients = vec![-1.0];
    m.restoring.omega0 = 1.0;
    m.walls.clear();
    m.noise.additive = None;
    m
}

/// fig13a with r = 0.3, D = 0.5 (λ = 0.998, OU noise: impacts, chattering, sticking).
pub fn chattering() -> Params {
    trirhythm::model::preset("fig13a")
        .unwrap()
        .params
        .with("r", 0.3)
        .unwrap()
        .with("D", 0.5)
        .unwrap()
}

/// Mean and standard error of the mean.
pub fn mean_se(xs: &[f64]) -> (f64, f64) {
    let n = xs.len() as f64;
    let m = xs.iter().sum::<f64>() / n;
    let var = xs.iter().map(|x| (x - m) * (x - m)).sum::<f64>() / (n - 1.0);
    (m, (var / n).sqrt())
}

/// Time averages of U² and U̇² over [transient, transient + length] of path `path`.
pub fn averages(
    problem: &Problem,
    dt: f64,
    path: u64,
    (transient, length): (f64, f64),
) -> (f64, f64) {
    let method = PredictorCorrector {
        dt,
        ..Default::default()
    };
    let skip = (transient / dt).round() as u64;
    let steps = skip + (length / dt).round() as u64;
    let mut s = Stepper::new(problem, &method, (SEED, path), steps as f64 * dt).unwrap();
    let (mut n, mut u2, mut v2) = (0u64, 0.0, 0.0);
    let mut obs = |s: &Stepper| {
        if s.steps() > skip {
            n += 1;
            u2 += s.u() * s.u();
            v2 += s.v() * s.v();
        }
        Flow::Continue
    };
    run(&mut s, steps, &mut obs, &Silent).unwrap();
    (u2 / n as f64, v2 / n as f64)
}

/// Paths 0..8 of `problem` over `steps` steps of `method`, read by `bits` at the end: each
/// path alone, where a clone taken halfway continues as its original, and the same paths in
/// lanes of 4 and 8 give the same `bits` (`label` names the case in a failure); `each` sees
/// every step of the paths alone. Returns the paths' `bits`.
pub fn same_alone_as_clones_and_in_lanes<B: PartialEq + Debug>(
    problem: &Problem,
    method: &PredictorCorrector,
    steps: u64,
    bits: impl Fn(&Stepper) -> B,
    each: impl Fn(&Stepper),
    label: &str,
) -> Vec<B> {
    let horizon = steps as f64 * method.dt;
    let alone: Vec<_> = (0..8)
        .map(|i| {
            let mut s = Stepper::new(problem, method, (SEED, i), horizon).unwrap();
            let mut half = None;
            for n in 0..steps {
                s.step().unwrap();
                each(&s);
                if n == steps / 2 {
                    half = Some(s.clone());
                }
            }
            let mut c = half.unwrap();
            for _ in steps / 2 + 1..steps {
                c.step().unwrap();
            }
            assert_eq!(bits(&c), bits(&s), "a clone continues as its original");
            bits(&s)
        })
        .collect();
    for width in [4, 8] {
        let mut paths: Vec<Stepper> = (0..8)
            .map(|i| Stepper::new(problem, method, (SEED, i), horizon).unwrap())
            .collect();
        let mut obs: Vec<_> = (0..8).map(|_| |_: &Stepper| Flow::Continue).collect();
        run_lanes(&mut paths, steps, &mut obs, Lanes::Width(width), &Silent).unwrap();
        let got: Vec<_> = paths.iter().map(&bits).collect();
        assert_eq!(got, alone, "{label}{width} lanes");
    }
    alone
}
