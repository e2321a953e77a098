//! Stiff damping: the paper's own parameters where μ0|P(U)| reaches hundreds (Fig. 13(b) at
//! U ≈ 13, Fig. 5(e) at μ0 = 0.7). The explicit corrector of the previous engine blew up there at
//! Δt = 0.01 (t = 0.06 and t = 0.04); the linearly implicit corrector must integrate them, land
//! on the averaging's outer cycle, and converge in Δt.

use trirhythm::engine::{run, Barrier, Flow, PredictorCorrector, Problem, Stepper};
use trirhythm::model::preset;
use trirhythm::monitor::Silent;
use trirhythm::theory::averaging::{Theory, Variant};
use trirhythm::Error;

/// Turning-point amplitudes (maxima of U) of the last `keep` cycles, and the largest stiffness
/// Δt·μ|P(U)| met on the way.
fn turning_points(preset_name: &str, mu0: Option<f64>, dt: f64, t_end: f64) -> (Vec<f64>, f64) {
    let mut p = preset(preset_name).unwrap().params.with("D", 0.0).unwrap();
    if let Some(m) = mu0 {
        p = p.with("mu0", m).unwrap();
    }
    let problem = Problem::from_params(&p)
        .and_then(|p| p.with_start(13.0, 0.0))
        .unwrap();
    let m = PredictorCorrector {
        dt,
        ..Default::default()
    };
    let mut s = Stepper::new(&problem, &m, (1, 0), t_end).unwrap();
    let (mut prev, mut rising) = (13.0, false);
    let mut maxima = vec![];
    let mut stiffness: f64 = 0.0;
    let c = p.damping.coefficients.clone();
    let steps = (t_end / dt).round() as u64;
    run(
        &mut s,
        steps,
        &mut |s: &Stepper| {
            let u = s.u();
            let pu: f64 = c.iter().rev().fold(0.0, |a, &c| a * u * u + c);
            stiffness = stiffness.max(dt * p.mu0 * pu.abs());
            if u < prev && rising {
                maxima.push(prev);
            }
            rising = u > prev;
            prev = u;
            Flow::Continue
        },
        &Silent,
    )
    .unwrap();
    (maxima, stiffness)
}

#[test]
fn fig13b_from_u13_settles_on_the_outer_cycle_and_converges_in_dt() {
    let outer = Theory::new(
        &preset("fig13b").unwrap().params.with("D", 0.0).unwrap(),
        Variant::Paper,
    )
    .unwrap()
    .limit_cycles()
    .last()
    .unwrap()
    .amplitude;
    let runs: Vec<(f64, f64)> = [0.01, 0.005, 0.0025]
        .iter()
        .map(|&dt| {
            let (m, stiff) = turning_points("fig13b", None, dt, 300.0);
            let last = *m.last().unwrap();
            // settled: the last cycles repeat
            let spread = m[m.len() - 4..]
                .iter()
                .fold(0.0f64, |a, &x| a.max((x - last).abs()));
            assert!(
                spread < 1e-3 * last,
                "Δt = {dt}: not settled, spread {spread}"
            );
            (last, stiff)
        })
        .collect();
    let (a1, a2, a3) = (runs[0].0, runs[1].0, runs[2].0);
    let (d12, d23) = ((a1 - a2).abs() / a2, (a2 - a3).abs() / a3);
    let order = (d12 / d23).log2();
    println!(
        "fig13b turning amplitudes {a1:.6} / {a2:.6} / {a3:.6} (Δt = 0.01 / 0.005 / 0.0025), \
         averaging's outer cycle {outer:.6}; relative changes {d12:.2e}, {d23:.2e}, observed order \
         {order:.2}; largest stiffness Δt·μ0|P(U)| = {:.2}",
        runs[0].1
    );
    // the stiff regime is really met at Δt = 0.01
    assert!(runs[0].1 > 2.0, "stiffness {}", runs[0].1);
    // on the outer cycle (the other stable cycles are at 2.6 and 8.4)
    assert!((a1 - outer).abs() < 0.02 * outer, "{a1} vs {outer}");
    // the criterion: halving Δt = 0.01 moves the amplitude by less than 10⁻³
    assert!(d12 < 1e-3, "{d12:e}");
    // and it converges at least at second order (the Hermite-corrected U and the second pass
    // of stiff steps make the pre-asymptotic rate higher, ≈ 3)
    assert!(
        order > 1.8 && d23 < d12 / 3.0,
        "order {order}, {d12:e} {d23:e}"
    );
}

#[test]
fn fig5e_cycles_at_mu0_07_are_integrated_at_dt_001_and_converge() {
    // Fig. 5(e): μ0 = 0.7, λ = 1, r = 1: the averaging's outer cycle. At Δt = 0.01 the step is
    // stable (stiffness Δt·μ0|P| up to ≈ 80) but the relaxation's fast phase is under-resolved:
    // the turning amplitude is ≈ 10 % high there. Halving Δt five times converges it.
    let p = preset("fig5").unwrap().params.with("mu0", 0.7).unwrap();
    let outer = Theory::new(&p, Variant::Paper)
        .unwrap()
        .limit_cycles()
        .last()
        .unwrap()
        .amplitude;
    let dts = [0.01, 0.005, 0.0025, 0.00125, 0.000625, 0.0003125];
    let runs: Vec<(f64, f64)> = dts
        .iter()
        .map(|&dt| {
            let (m, stiff) = turning_points("fig5", Some(0.7), dt, 300.0);
            (*m.last().unwrap(), stiff)
        })
        .collect();
    let a: Vec<f64> = runs.iter().map(|r| r.0).collect();
    let stiff = runs[0].1;
    let n = a.len();
    let order = ((a[n - 3] - a[n - 2]) / (a[n - 2] - a[n - 1])).abs().log2();
    println!(
        "fig5 μ0 = 0.7: turning amplitudes {} (Δt = 0.01 … 0.0003125); averaging {outer:.5}; \
         stiffness up to {stiff:.1} at Δt = 0.01; observed order over the finest three {order:.2}",
        a.iter()
            .map(|x| format!("{x:.5}"))
            .collect::<Vec<_>>()
            .join(" / ")
    );
    assert!(stiff > 50.0, "stiffness {stiff}");
    // integrated without blow-up and on the outer branch (the others are below 9)
    assert!(a[0] > 11.0 && a[0] < 15.0, "{}", a[0]);
    // converged: the finest halving moves it by < 10⁻⁵, at least at second order, onto the
    // averaging's cycle within 1 %
    assert!((a[n - 2] - a[n - 1]).abs() < 1e-5 * a[n - 1], "{a:?}");
    assert!(order > 1.8, "order {order} ({a:?})");
    assert!(
        (a[n - 1] - outer).abs() < 0.01 * outer,
        "{} vs {outer}",
        a[n - 1]
    );
}

#[test]
fn what_cannot_be_integrated_is_reported_with_time_state_and_stiffness() {
    // strongly negative damping everywhere: the model itself runs away
    let mut p = trirhythm::known_answers::linear_oscillator(1.0, 1.0, 1.0);
    p.damping.coefficients = vec![50.0];
    let problem = Problem::from_params(&p)
        .and_then(|p| p.with_barrier(Barrier::Off))
        .and_then(|p| p.with_start(1.0, 0.0))
        .and_then(|p| p.with_blow_up(1e6))
        .unwrap();
    let m = PredictorCorrector::default();
    let mut s = Stepper::new(&problem, &m, (0, 0), 100.0).unwrap();
    let err = run(&mut s, 10_000, &mut |_: &Stepper| Flow::Continue, &Silent).unwrap_err();
    let Error::BlowUp {
        t,
        u,
        v,
        stiffness,
        dt,
        ..
    } = err
    else {
        panic!("expected a blow-up, got {err:?}")
    };
    assert!(t > 0.0 && t < 100.0 && dt == 0.01);
    assert!(u.abs() > 1e6 || v.abs() > 1e6);
    assert!((stiffness - 0.01 * 50.0).abs() < 1e-12, "{stiffness}");
    let msg = err.to_string();
    println!("{msg}");
    // readable numbers: no run of more than 8 digits anywhere in the message
    let longest = msg
        .split(|c: char| !c.is_ascii_digit())
        .map(str::len)
        .max()
        .unwrap();
    assert!(longest <= 8, "{msg}");
    assert!(msg.contains("stiffness"));
}
