//! Known answers of the General kernel (`engine::stepper::general`): the terms of the class
//! beyond the paper's Eq. (1) — Duffing, Rayleigh, harmonic forcing — each against an exact
//! result, every model built from a [`Model`] value (the model file's fields) through
//! [`Problem::from_model`].
//!
//! - **Duffing under additive white noise** (λ = 1, h ≡ −c, no wall):
//!   Ü + cU̇ + ω²U + k3U³ = η, ⟨η(t)η(s)⟩ = 2Dδ(t − s) (the engine's white noise, τ = 0), has
//!   the exact stationary density p ∝ exp(−cH/D), H = U̇²/2 + ω²U²/2 + k3U⁴/4: U̇ is Gaussian
//!   with ⟨U̇²⟩ = D/c, ⟨U²⟩ is a one-dimensional quadrature (Simpson's rule here). Measured as
//!   time averages of independent paths (seeded, one stream each), the standard error from
//!   their spread, at Δt = 0.02 and 0.01; the tolerance is four standard errors plus the
//!   discretisation bias estimated by the change from Δt = 0.02 to 0.01 beyond two standard
//!   errors of that change.
//! - **Harmonic forcing of the linear oscillator** (D = 0): D^{1+λ}U + cU̇ + ω²U = F cos Ωt has
//!   the steady amplitude |F·H(iΩ)|, H(s) = 1/(s^{1+λ} + cs + ω²) (h(0) = −c); at λ = 1 and at
//!   λ = 0.9 (the memory: slow algebraic transients, so the fit waits long), with the observed
//!   order as Δt halves (0.04 → 0.005).
//! - **Rayleigh damping**: Ü − μ(U̇ − U̇³/3) + U = 0 (h = μ − (μ/3)U̇²) is van der Pol's
//!   equation for U̇, whose cycle has amplitude 2 + O(μ²); so has U's (ω = 1).
//! - **The wall at 0**: the General kernel gives the paper kernel's bits when its terms vanish
//!   (k3 = 1e-300), and a Duffing oscillator bouncing at r = 1 without damping keeps its energy
//!   and its half-period (quadrature) at second order.
//! - **Lyapunov**: the forced, noisy damped linear oscillator has the exponent −c/2 by the
//!   tangent and by two trajectories.
//!
//! The tangent of the General step is checked against finite differences in the unit tests of
//! `engine::stepper::tangent`; the paper's path is pinned bit for bit in `tests/pinned.rs`.
//! Measured values are printed with `--nocapture`; the extended (ignored) variant of the
//! Duffing check runs 16 times the path-time.

mod common;

use common::{averages, chattering, linear, mean_se, same_alone_as_clones_and_in_lanes, SEED};
use trirhythm::engine::{run, Flow, PredictorCorrector, Problem, Stepper};
use trirhythm::model::{Harmonic, Model, NoiseTerm};
use trirhythm::monitor::Silent;

/// ⟨U²⟩ under p(U) ∝ exp(−(ω²U²/2 + k3U⁴/4)/T) by Simpson's rule on [−L, L].
fn exact_u2(omega2: f64, k3: f64, temperature: f64) -> f64 {
    let (l, n) = (12.0, 24_000);
    let h = 2.0 * l / n as f64;
    let (mut z, mut m) = (0.0, 0.0);
    for i in 0..=n {
        let u = -l + i as f64 * h;
        let w = if i == 0 || i == n {
            1.0
        } else if i % 2 == 1 {
            4.0
        } else {
            2.0
        };
        let p = (-(0.5 * omega2 * u * u + 0.25 * k3 * u.powi(4)) / temperature).exp();
        z += w * p;
        m += w * p * u * u;
    }
    m / z
}

/// The Duffing check with `paths` paths of `length` time units each.
fn duffing(paths: u64, length: f64) {
    let (c, d, k3) = (0.5, 0.5, 1.0);
    let mut m = linear(1.0, c);
    m.restoring.cubic = k3;
    m.noise.additive = Some(NoiseTerm {
        intensity: d,
        correlation_time: 0.0,
    });
    let problem = Problem::from_model(&m).unwrap();
    assert!(problem.oscillator().terms().is_some());
    let temperature = d / c;
    let (u2_exact, v2_exact) = (exact_u2(1.0, k3, temperature), temperature);
    let mut at = Vec::new();
    for dt in [0.02, 0.01] {
        let (u2, v2): (Vec<f64>, Vec<f64>) = (0..paths)
            .map(|i| averages(&problem, dt, i, (20.0, length)))
            .unzip();
        at.push((dt, mean_se(&u2), mean_se(&v2)));
    }
    let (_, u2c, v2c) = at[0];
    let (_, u2f, v2f) = at[1];
    for (name, coarse, fine, exact) in
        [("<U^2>", u2c, u2f, u2_exact), ("<V^2>", v2c, v2f, v2_exact)]
    {
        // the change from Δt = 0.02 to 0.01 beyond its own noise: at least the bias at 0.01
        // (first order) and at most twice it for any higher order
        let noise = 2.0 * coarse.1.hypot(fine.1);
        let bias = ((coarse.0 - fine.0).abs() - noise).max(0.0);
        let tol = 4.0 * fine.1 + bias;
        println!(
            "Duffing c = {c}, D = {d}, k3 = {k3}, {paths} paths x {length}: {name} exact {exact:.5}; \
             dt = 0.02: {:.5} ± {:.5}; dt = 0.01: {:.5} ± {:.5} (error {:+.5}, tolerance {tol:.5})",
            coarse.0,
            coarse.1,
            fine.0,
            fine.1,
            fine.0 - exact
        );
        assert!(
            (fine.0 - exact).abs() <= tol,
            "{name}: {:.5} ± {:.5} against the exact {exact:.5} (bias estimate {bias:.5})",
            fine.0,
            fine.1
        );
    }
}

#[test]
fn duffing_under_white_noise_has_the_exact_stationary_density() {
    duffing(96, 1000.0);
}

#[test]
#[ignore = "extended: 16 times the path-time of the quick Duffing check (about 16 s)"]
fn duffing_under_white_noise_has_the_exact_stationary_density_extended() {
    duffing(384, 4000.0);
}

/// |F·H(iΩ)|, H(s) = 1/(s^{1+λ} + cs + ω²).
fn exact_amplitude(lambda: f64, c: f64, f: f64, omega: f64) -> f64 {
    let r = omega.powf(1.0 + lambda);
    let phi = std::f64::consts::FRAC_PI_2 * (1.0 + lambda);
    let (re, im) = (r * phi.cos() + 1.0, r * phi.sin() + c * omega);
    f / (re * re + im * im).sqrt()
}

/// The steady amplitude of U: the least-squares fit of A cos Ωt + B sin Ωt + C over the last
/// `periods` periods of [0, t_end].
fn forced_amplitude(problem: &Problem, dt: f64, omega: f64, t_end: f64, periods: f64) -> f64 {
    let method = PredictorCorrector {
        dt,
        ..Default::default()
    };
    let steps = (t_end / dt).round() as u64;
    let from = t_end - periods * std::f64::consts::TAU / omega;
    let mut s = Stepper::new(problem, &method, (SEED, 0), t_end).unwrap();
    // normal equations of (cos, sin, 1)
    let mut a = [[0.0; 3]; 3];
    let mut b = [0.0; 3];
    let mut obs = |s: &Stepper| {
        let t = s.time();
        if t >= from {
            let x = [(omega * t).cos(), (omega * t).sin(), 1.0];
            for i in 0..3 {
                for j in 0..3 {
                    a[i][j] += x[i] * x[j];
                }
                b[i] += x[i] * s.u();
            }
        }
        Flow::Continue
    };
    run(&mut s, steps, &mut obs, &Silent).unwrap();
    let x = solve3(a, b);
    x[0].hypot(x[1])
}

/// Gaussian elimination of a 3 × 3 system.
#[allow(clippy::needless_range_loop)]
fn solve3(mut a: [[f64; 3]; 3], mut b: [f64; 3]) -> [f64; 3] {
    for k in 0..3 {
        for i in k + 1..3 {
            let f = a[i][k] / a[k][k];
            for j in k..3 {
                a[i][j] -= f * a[k][j];
            }
            b[i] -= f * b[k];
        }
    }
    let mut x = [0.0; 3];
    for i in (0..3).rev() {
        let s: f64 = (i + 1..3).map(|j| a[i][j] * x[j]).sum();
        x[i] = (b[i] - s) / a[i][i];
    }
    x
}

#[test]
fn harmonic_forcing_gives_the_exact_steady_amplitude() {
    let (f, omega) = (0.5, 1.3);
    // λ = 1: transient e^{−ct/2}; λ = 0.9: algebraic memory transients, waited out longer
    for (lambda, c, t_end, limit) in [(1.0, 0.5, 150.0, 2e-5), (0.9, 0.5, 400.0, 1e-4)] {
        let mut m = linear(lambda, c);
        m.forcing = Some(Harmonic {
            amplitude: f,
            frequency: omega,
            phase: 0.0,
        });
        m.start.u0 = 0.0;
        let problem = Problem::from_model(&m).unwrap();
        let exact = exact_amplitude(lambda, c, f, omega);
        let errors: Vec<(f64, f64)> = [0.04, 0.02, 0.01, 0.005]
            .iter()
            .map(|&dt| {
                let a = forced_amplitude(&problem, dt, omega, t_end, 10.0);
                (dt, (a - exact) / exact)
            })
            .collect();
        let orders: Vec<f64> = errors
            .windows(2)
            .map(|w| (w[0].1.abs() / w[1].1.abs()).log2())
            .collect();
        println!(
            "forced linear oscillator λ = {lambda}, c = {c}, F = {f}, Ω = {omega}: exact \
             |F·H(iΩ)| = {exact:.8}; relative errors {}; observed orders {}",
            errors
                .iter()
                .map(|(dt, e)| format!("{e:+.2e} (dt = {dt})"))
                .collect::<Vec<_>>()
                .join(", "),
            orders
                .iter()
                .map(|p| format!("{p:.2}"))
                .collect::<Vec<_>>()
                .join(", ")
        );
        let finest = errors.last().unwrap().1.abs();
        assert!(finest < limit, "λ = {lambda}: relative error {finest:e}");
        // second order as Δt halves (the coarsest pairs, where the error is the step's)
        assert!(
            orders[..2].iter().all(|&p| (1.6..=2.6).contains(&p)),
            "λ = {lambda}: orders {orders:?}"
        );
    }
}

#[test]
fn rayleigh_damping_gives_the_van_der_pol_cycle_of_the_velocity() {
    let mu = 0.05;
    let mut m = linear(1.0, mu);
    m.damping.coefficients = vec![1.0];
    m.damping.rayleigh = vec![-mu / 3.0];
    m.start.u0 = 0.5;
    let problem = Problem::from_model(&m).unwrap();
    let method = PredictorCorrector {
        dt: 0.01,
        ..Default::default()
    };
    let t_end = 600.0;
    let steps = (t_end / method.dt) as u64;
    let mut s = Stepper::new(&problem, &method, (SEED, 0), t_end).unwrap();
    let (mut umax, mut vmax) = (0.0_f64, 0.0_f64);
    let mut obs = |s: &Stepper| {
        if s.time() > t_end - 30.0 {
            umax = umax.max(s.u().abs());
            vmax = vmax.max(s.v().abs());
        }
        Flow::Continue
    };
    run(&mut s, steps, &mut obs, &Silent).unwrap();
    println!("Rayleigh μ = {mu}: max|U| = {umax:.5}, max|U̇| = {vmax:.5} (2 + O(μ²))");
    assert!((vmax - 2.0).abs() < 5e-3 && (umax - 2.0).abs() < 5e-3);
}

/// Lanes and clones: a General path gives the scalar bits in groups of 4 and 8 (stepped path
/// by path there), and a clone carries the forcing's phase (it continues as the original).
#[test]
fn general_paths_are_the_same_in_lanes_and_clones() {
    let mut m = linear(0.95, 0.3);
    m.restoring.cubic = 0.5;
    m.damping.rayleigh = vec![-0.01];
    m.forcing = Some(Harmonic {
        amplitude: 0.3,
        frequency: 0.8,
        phase: 0.4,
    });
    m.noise.additive = Some(NoiseTerm {
        intensity: 0.05,
        correlation_time: 0.5,
    });
    let problem = Problem::from_model(&m).unwrap();
    let method = PredictorCorrector::default();
    let bits = |s: &Stepper| (s.u().to_bits(), s.v().to_bits());
    same_alone_as_clones_and_in_lanes(&problem, &method, 3000, bits, |_| {}, "");
}

/// The General kernel at the wall (U = 0) reduces to the paper's kernel when its terms vanish:
/// a chattering fig13a path (λ = 0.998, OU noise, r = 0.3, D = 0.5: impacts and sticking, both
/// impact memories) with k3 = 1e-300 (k(U) = ω0²U to the last bit) steps through the General
/// kernel's impact code (`jump_general`, the scheme's V₋ at the wall) and gives the paper
/// kernel's bits.
#[test]
fn the_general_kernel_at_the_wall_gives_the_paper_kernels_bits_when_its_terms_vanish() {
    for memory in [
        trirhythm::engine::ImpactMemory::Continuous,
        trirhythm::engine::ImpactMemory::Restart,
    ] {
        let p = chattering();
        let paper = Problem::from_params(&p).unwrap();
        let mut m = Model::from(&p);
        m.restoring.cubic = 1e-300;
        let general = Problem::from_model(&m).unwrap();
        assert!(general.oscillator().terms().is_some() && general.wall());
        let method = PredictorCorrector {
            impact_memory: memory,
            ..Default::default()
        };
        let mut a = Stepper::new(&paper, &method, (7, 0), 200.0).unwrap();
        let mut b = Stepper::new(&general, &method, (7, 0), 200.0).unwrap();
        for n in 0..20_000 {
            a.step().unwrap();
            b.step().unwrap();
            assert_eq!(
                (a.u().to_bits(), a.v().to_bits(), a.events()),
                (b.u().to_bits(), b.v().to_bits(), b.events()),
                "{memory:?}: step {n}"
            );
        }
        assert!(a.impacts() > 100 && a.sticking_steps() > 1000, "{memory:?}");
        assert_eq!(
            (a.impacts(), a.sticking_steps()),
            (b.impacts(), b.sticking_steps())
        );
    }
}

/// A Duffing oscillator bouncing on the wall at 0 with r = 1 and no damping (h ≡ 0): the
/// energy H = U̇²/2 + U²/2 + k3U⁴/4 is kept across impacts and the time between impacts is
/// half the free period, 2∫₀^{π/2} dφ/√(1 + A²(1 + sin²φ)/2) (U = A sin φ), both converging at
/// second order as Δt halves. Both Lyapunov methods take it (the tangent through
/// the impact steps at the wall at 0).
#[test]
fn a_duffing_oscillator_on_the_wall_keeps_its_energy_and_its_period() {
    let (amplitude, k3) = (1.0, 1.0);
    let mut m = linear(1.0, 1.0);
    m.damping.coefficients = vec![0.0];
    m.restoring.cubic = k3;
    m.walls = Model::from(&trirhythm::model::preset("fig1").unwrap().params).walls;
    m.walls[0].restitution = trirhythm::model::Restitution::Constant(1.0);
    m.start.u0 = amplitude;
    let problem = Problem::from_model(&m).unwrap();
    assert!(problem.wall());
    let energy = |u: f64, v: f64| 0.5 * v * v + 0.5 * u * u + 0.25 * k3 * u.powi(4);
    let h0 = energy(amplitude, 0.0);
    // the exact time between impacts (Simpson on a smooth integrand)
    let n = 2000;
    let dphi = std::f64::consts::FRAC_PI_2 / n as f64;
    let f = |phi: f64| {
        let s = phi.sin();
        1.0 / (1.0 + amplitude * amplitude * (1.0 + s * s) * 0.5 * k3).sqrt()
    };
    let simpson: f64 = (0..=n)
        .map(|i| {
            let w = if i == 0 || i == n {
                1.0
            } else if i % 2 == 1 {
                4.0
            } else {
                2.0
            };
            w * f(i as f64 * dphi)
        })
        .sum::<f64>()
        * dphi
        / 3.0;
    let exact = 2.0 * simpson;
    let t_end = 100.0;
    let mut errors = Vec::new();
    for dt in [0.02, 0.01, 0.005] {
        let method = PredictorCorrector {
            dt,
            ..Default::default()
        };
        let mut s = Stepper::new(&problem, &method, (SEED, 0), t_end).unwrap();
        let mut times = Vec::new();
        let mut obs = |s: &Stepper| {
            if let Some(i) = s.events().impact {
                times.push(i.time);
            }
            Flow::Continue
        };
        run(&mut s, (t_end / dt).round() as u64, &mut obs, &Silent).unwrap();
        let interval = (times[times.len() - 1] - times[0]) / (times.len() - 1) as f64;
        let de = (energy(s.u(), s.v()) - h0) / h0;
        errors.push((dt, (interval - exact) / exact, de, times.len()));
    }
    println!(
        "Duffing on the wall, r = 1, h = 0, A = {amplitude}, k3 = {k3}: exact time between \
         impacts {exact:.10}; (dt, relative error of the interval, of the energy at t = {t_end}, \
         impacts) {errors:?}"
    );
    let (_, e_mid, h_mid, _) = errors[1];
    let (_, e_fine, h_fine, _) = errors[2];
    assert!(e_fine.abs() < 1e-5 && h_fine.abs() < 1e-4, "{errors:?}");
    for (coarse, fine) in [(e_mid, e_fine), (h_mid, h_fine)] {
        let order = (coarse / fine).abs().log2();
        assert!((1.6..=2.6).contains(&order), "order {order}: {errors:?}");
    }
    // both Lyapunov methods take it (the tangent through the impact steps at the wall at 0)
    use trirhythm::analysis::lyapunov::LyapunovMethod;
    use trirhythm::analysis::{largest_lyapunov, LyapunovSpec};
    let spec = |method| LyapunovSpec {
        paths: 1,
        transient: 0.0,
        length: 20.0,
        method,
        ..Default::default()
    };
    let method = PredictorCorrector::default();
    for m in [LyapunovMethod::Tangent, LyapunovMethod::TwoTrajectory] {
        let r = largest_lyapunov(&problem, &method, &spec(m), &Silent).unwrap();
        assert!(r.lle.value.is_finite(), "{m:?}: {}", r.lle.value);
    }
}

/// The Lyapunov exponent through the General kernel: the damped linear oscillator
/// Ü + cU̇ + U = F cos Ωt + η is linear, so the forcing and the noise do not enter its
/// variational equation and its exponent is −c/2, by both methods (the tangent differentiates
/// the General step, the forcing's phase held; the copy of two trajectories carries the phase).
/// A Rayleigh term that vanishes to the last bit at the path's speeds (d = 1e-300) goes through
/// the corrector's linearisation and its derivative with the same answer.
#[test]
fn the_lyapunov_exponent_of_the_forced_damped_oscillator_is_minus_half_the_damping() {
    use trirhythm::analysis::lyapunov::LyapunovMethod;
    use trirhythm::analysis::{largest_lyapunov, LyapunovSpec};
    let c = 0.1;
    let mut m = linear(1.0, c);
    m.forcing = Some(Harmonic {
        amplitude: 0.5,
        frequency: 1.3,
        phase: 0.3,
    });
    m.noise.additive = Some(NoiseTerm {
        intensity: 0.1,
        correlation_time: 0.0,
    });
    m.damping.rayleigh = vec![1e-300];
    let problem = Problem::from_model(&m).unwrap();
    for method in [LyapunovMethod::Tangent, LyapunovMethod::TwoTrajectory] {
        let spec = LyapunovSpec {
            paths: 2,
            seed: SEED,
            transient: 50.0,
            length: 1000.0,
            method,
            ..Default::default()
        };
        let r = largest_lyapunov(&problem, &PredictorCorrector::default(), &spec, &Silent).unwrap();
        let err = r.lle.value + c / 2.0;
        println!(
            "{method:?}: LLE {} against −c/2 = {} (error {err:e})",
            r.lle.value,
            -c / 2.0
        );
        assert!(
            err.abs() < 1e-3,
            "{method:?}: LLE {} (error {err:e})",
            r.lle.value
        );
    }
}

/// An ensemble's fingerprint (checkpoints, pieces) tells a General model from the paper model
/// of the same parameters, and the paper's fingerprint does not change.
#[test]
fn the_ensemble_fingerprint_names_the_general_terms() {
    use trirhythm::analysis::ensemble::{fingerprint, EnsembleSpec};
    let m = linear(1.0, 0.5);
    let paper = Problem::from_model(&m).unwrap();
    let mut duffing = m.clone();
    duffing.restoring.cubic = 0.25;
    let general = Problem::from_model(&duffing).unwrap();
    let (method, spec) = (PredictorCorrector::default(), EnsembleSpec::default());
    let (a, b) = (
        fingerprint(&paper, &method, &spec),
        fingerprint(&general, &method, &spec),
    );
    assert!(!a.contains("terms:"));
    assert!(b.starts_with(&a) && b.contains("terms: cubic=0.25"), "{b}");
}
