//! Known answers of the General kernel's fractional terms K·D^αU and multiplicative noise U·η_m
//! (`engine::stepper::general`), every model built from a [`Model`] value through
//! [`Problem::from_model`].
//!
//! - **The second memory against the exact one** (as `tests/soe.rs` checks the leading
//!   memory): D^{1+λ}U + K1·D^{α1}U + K2·D^{α2}U − μ0P(U)U̇ + U = 0 (no wall, no noise, U(0) = 2)
//!   with the sum-of-exponentials memories against [`Memory::Direct`] (the exact product
//!   integration of every piece) over 10⁴ steps: max |ΔU| ≤ 1e-8. And α = 1 is K·U̇ exactly:
//!   the term K·D¹U against the damping h ≡ −K to rounding.
//! - **The linear oscillator with fractional damping** Ü + K·D^αU + ω0²U = η under white noise
//!   (⟨ηη⟩ = 2Dδ) and OU noise (⟨ηη⟩ = (D/τ)e^{−|t−s|/τ}): the stationary ⟨U²⟩ and ⟨U̇²⟩ are
//!   (1/π)∫₀^∞ S(ω)|H(iω)|²(1, ω²) dω, H(iω) = 1/(ω0² − ω² + K(iω)^α), S = 2D or
//!   2D/(1 + τ²ω²), by quadrature here (ω = x/(1 − x), Simpson). Measured as time averages of
//!   independent paths, the standard error from their spread; tolerance four standard errors
//!   plus the discretisation bias estimated from Δt and 2Δt (as `tests/general.rs` does).
//! - **The linear oscillator with parametric white noise** Ü + 2ζω0U̇ + ω0²U = Uξ,
//!   ⟨ξξ⟩ = 2Dδ. U has finite variation, so Itô and Stratonovich (the limit of coloured noise)
//!   are the same process here, and the second moments x = (EU², EUU̇, EU̇²) obey exactly
//!   x′ = Mx, M = [[0, 2, 0], [−ω0², −2ζω0, 1], [2D, −2ω0², −4ζω0]]: det M = 4D − 8ζω0³, and
//!   Routh–Hurwitz puts the boundary of second-moment stability at D_c = 2ζω0³ (the other
//!   Hurwitz condition, 6ζω0(4ω0² + 8ζ²ω0²) > 8ζω0³ − 4D, always holds). The ensemble's
//!   EU²(T), EU̇²(T) against e^{MT}x(0) just below and just above D_c (decay, growth), within
//!   four standard errors plus the bias from Δt and 2Δt. A scheme that read U·ξ in a different
//!   calculus, or leaked the step's deviate into U's coefficient, would add a drift
//!   ∝ D·EU² to EU̇² and move the boundary.
//! - **Correlated noises**: η_m with correlation c to η_a has the sample correlation c.
//!
//! Measured values are printed with `--nocapture`; the extended (ignored) variants run longer.

mod common;

use common::{averages, linear, mean_se, same_alone_as_clones_and_in_lanes, SEED};
use trirhythm::engine::{run, Flow, Memory, PredictorCorrector, Problem, Stepper};
use trirhythm::model::{Fractional, Model, NoiseTerm};
use trirhythm::monitor::Silent;

/// `f(path)` for paths 0..paths, on every core (scoped threads), in path order.
fn each_path<T: Send>(paths: u64, f: impl Fn(u64) -> T + Sync) -> Vec<T> {
    let threads = std::thread::available_parallelism().map_or(2, |n| n.get()) as u64;
    let mut out: Vec<(u64, T)> = std::thread::scope(|s| {
        let handles: Vec<_> = (0..threads)
            .map(|t| {
                let f = &f;
                s.spawn(move || {
                    (t..paths)
                        .step_by(threads as usize)
                        .map(|i| (i, f(i)))
                        .collect::<Vec<_>>()
                })
            })
            .collect();
        handles
            .into_iter()
            .flat_map(|h| h.join().unwrap())
            .collect()
    });
    out.sort_by_key(|(i, _)| *i);
    out.into_iter().map(|(_, x)| x).collect()
}

/// The trajectory's U at every step, from `problem` with `memory`.
fn trajectory(problem: &Problem, dt: f64, steps: u64, memory: Memory) -> Vec<f64> {
    let method = PredictorCorrector {
        dt,
        memory,
        ..Default::default()
    };
    let mut s = Stepper::new(problem, &method, (SEED, 0), steps as f64 * dt).unwrap();
    let mut u = Vec::with_capacity(steps as usize);
    let mut obs = |s: &Stepper| {
        u.push(s.u());
        Flow::Continue
    };
    run(&mut s, steps, &mut obs, &Silent).unwrap();
    u
}

#[test]
fn the_fractional_terms_memories_match_the_direct_memory() {
    // two fractional terms beside a fractional leading term, and beside Ü
    for (lambda, terms) in [
        (0.9, vec![(0.4, 0.5), (0.2, 0.8)]),
        (1.0, vec![(0.5, 0.3)]),
        (0.998, vec![(0.3, 0.7), (0.1, 1.0)]),
    ] {
        let mut m = linear(lambda, 0.1);
        m.damping.coefficients = vec![1.0, -0.1];
        m.start.u0 = 2.0;
        m.fractional = terms
            .iter()
            .map(|&(coefficient, order)| Fractional { coefficient, order })
            .collect();
        let problem = Problem::from_model(&m).unwrap();
        assert!(problem.oscillator().terms().is_some());
        let (dt, steps) = (0.01, 10_000);
        let direct = trajectory(&problem, dt, steps, Memory::Direct);
        let soe = trajectory(
            &problem,
            dt,
            steps,
            Memory::SumOfExponentials { tolerance: 1e-11 },
        );
        let du = direct
            .iter()
            .zip(&soe)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        let scale = direct.iter().fold(0.0f64, |a, b| a.max(b.abs()));
        println!("λ = {lambda}, terms {terms:?}: max|U| = {scale:.3}, max |ΔU| = {du:.2e}");
        assert!(scale > 0.1, "the path moves");
        assert!(du <= 1e-8, "λ = {lambda}, {terms:?}: max |ΔU| = {du:e}");
    }
}

#[test]
fn a_fractional_term_of_order_one_is_plain_damping() {
    let k = 0.35;
    let mut fractional = linear(0.95, 1.0);
    fractional.damping.coefficients = vec![0.0];
    fractional.start.u0 = 1.5;
    fractional.noise.additive = Some(NoiseTerm {
        intensity: 0.02,
        correlation_time: 0.0,
    });
    fractional.restoring.cubic = 0.2;
    let mut damped = fractional.clone();
    fractional.fractional = vec![Fractional {
        coefficient: k,
        order: 1.0,
    }];
    damped.damping.mu0 = k;
    damped.damping.coefficients = vec![-1.0];
    let a = trajectory(
        &Problem::from_model(&fractional).unwrap(),
        0.01,
        5000,
        Memory::default(),
    );
    let b = trajectory(
        &Problem::from_model(&damped).unwrap(),
        0.01,
        5000,
        Memory::default(),
    );
    let du = a
        .iter()
        .zip(&b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max);
    println!("K·D¹U against h ≡ −K: max |ΔU| = {du:.2e}");
    assert!(du <= 1e-12, "{du:e}");
}

/// (1/π)∫₀^∞ S(ω)|H(iω)|²(1, ω²) dω for H(iω) = 1/(ω0² − ω² + K(iω)^α), S(ω) = 2D/(1 + τ²ω²),
/// by Simpson's rule in x = ω/(1 + ω) on [0, 1].
fn spectral_variances(k: f64, alpha: f64, omega0: f64, d: f64, tau: f64) -> (f64, f64) {
    let n = 400_000;
    let h = 1.0 / n as f64;
    let (c, s) = (
        (std::f64::consts::FRAC_PI_2 * alpha).cos(),
        (std::f64::consts::FRAC_PI_2 * alpha).sin(),
    );
    let f = |x: f64| -> (f64, f64) {
        if x <= 0.0 {
            let g = 2.0 * d / omega0.powi(4);
            return (g, 0.0);
        }
        if x >= 1.0 {
            // ω → ∞: |H|² ~ ω⁻⁴, dω/dx = (1 + ω)²: U²'s integrand → 0, U̇²'s → S(∞)
            return (0.0, if tau == 0.0 { 2.0 * d } else { 0.0 });
        }
        let w = x / (1.0 - x);
        let jac = 1.0 / ((1.0 - x) * (1.0 - x));
        let wa = w.powf(alpha);
        let re = omega0 * omega0 - w * w + k * wa * c;
        let im = k * wa * s;
        let spectrum = 2.0 * d / (1.0 + tau * tau * w * w);
        let g = spectrum / (re * re + im * im) * jac;
        (g, g * w * w)
    };
    let (mut a, mut b) = (0.0, 0.0);
    for i in 0..=n {
        let x = i as f64 * h;
        let wt = if i == 0 || i == n {
            1.0
        } else if i % 2 == 1 {
            4.0
        } else {
            2.0
        };
        let (p, q) = f(x);
        a += wt * p;
        b += wt * q;
    }
    let scale = h / 3.0 / std::f64::consts::PI;
    (a * scale, b * scale)
}

/// Measured (mean, se) at 2Δt and Δt against `exact`: within four standard errors at Δt plus
/// the bias estimated from the change beyond two standard errors of it.
fn check(label: &str, name: &str, coarse: (f64, f64), fine: (f64, f64), exact: f64) {
    let noise = 2.0 * coarse.1.hypot(fine.1);
    let bias = ((coarse.0 - fine.0).abs() - noise).max(0.0);
    let tol = 4.0 * fine.1 + bias;
    println!(
        "{label}: {name} exact {exact:.5}; 2dt: {:.5} ± {:.5}; dt: {:.5} ± {:.5} (error {:+.5}, \
         {:+.2} se; tolerance {tol:.5})",
        coarse.0,
        coarse.1,
        fine.0,
        fine.1,
        fine.0 - exact,
        (fine.0 - exact) / fine.1
    );
    assert!(
        (fine.0 - exact).abs() <= tol,
        "{label}: {name} {:.5} ± {:.5} against the exact {exact:.5} (bias estimate {bias:.5})",
        fine.0,
        fine.1
    );
}

/// The fractionally damped linear oscillator's stationary variances, `paths` paths of
/// `length` time units, at Δt = `dt` and 2Δt.
fn fractional_variances(tau: f64, paths: u64, length: f64, dt: f64) {
    let (k, alpha, d) = (0.4, 0.5, 0.1);
    let mut m = linear(1.0, 1.0);
    m.start.u0 = 0.0;
    m.damping.coefficients = vec![0.0];
    m.fractional = vec![Fractional {
        coefficient: k,
        order: alpha,
    }];
    m.noise.additive = Some(NoiseTerm {
        intensity: d,
        correlation_time: tau,
    });
    let problem = Problem::from_model(&m).unwrap();
    let (u2_exact, v2_exact) = spectral_variances(k, alpha, 1.0, d, tau);
    let mut at = Vec::new();
    for step in [2.0 * dt, dt] {
        let (u2, v2): (Vec<f64>, Vec<f64>) =
            each_path(paths, |i| averages(&problem, step, i, (100.0, length)))
                .into_iter()
                .unzip();
        at.push((mean_se(&u2), mean_se(&v2)));
    }
    let label = format!(
        "Ü + {k}·D^{alpha}U + U = η, D = {d}, τ = {tau}, {paths} paths × {length}, dt = {dt}"
    );
    check(&label, "<U^2>", at[0].0, at[1].0, u2_exact);
    check(&label, "<V^2>", at[0].1, at[1].1, v2_exact);
}

#[test]
fn fractional_damping_under_white_noise_has_the_spectral_variances() {
    fractional_variances(0.0, 32, 1500.0, 0.02);
}

#[test]
fn fractional_damping_under_ou_noise_has_the_spectral_variances() {
    fractional_variances(0.5, 32, 1500.0, 0.02);
}

#[test]
#[ignore = "extended: 8 times the path-time of the quick checks, Δt halved"]
fn fractional_damping_has_the_spectral_variances_extended() {
    fractional_variances(0.0, 64, 6000.0, 0.01);
    fractional_variances(0.5, 64, 6000.0, 0.01);
}

/// The exact moments E U^{n−b}U̇^b(T), b = 0…n, of Ü + cU̇ + ω0²U = Uξ (Itô = Stratonovich
/// here) from (1, 0): the generator on U^aV^b gives the closed system
/// m_b′ = (n − b)m_{b+1} − bc·m_b − bω0²m_{b−1} + Db(b − 1)m_{b−2} (n = 2: the matrix M of
/// the module docs), integrated by RK4 with 10⁵ steps (exact to ~1e-12 here).
fn exact_moments(n: usize, c: f64, omega0: f64, d: f64, t: f64) -> Vec<f64> {
    let w2 = omega0 * omega0;
    let f = |m: &[f64]| -> Vec<f64> {
        (0..=n)
            .map(|b| {
                let bf = b as f64;
                let mut y = -bf * c * m[b];
                if b < n {
                    y += (n - b) as f64 * m[b + 1];
                }
                if b >= 1 {
                    y -= bf * w2 * m[b - 1];
                }
                if b >= 2 {
                    y += d * bf * (bf - 1.0) * m[b - 2];
                }
                y
            })
            .collect()
    };
    let steps = 100_000;
    let h = t / steps as f64;
    let mut x = vec![0.0; n + 1];
    x[0] = 1.0;
    let add = |a: &[f64], b: &[f64], s: f64| -> Vec<f64> {
        a.iter().zip(b).map(|(x, y)| x + s * y).collect()
    };
    for _ in 0..steps {
        let k1 = f(&x);
        let k2 = f(&add(&x, &k1, h / 2.0));
        let k3 = f(&add(&x, &k2, h / 2.0));
        let k4 = f(&add(&x, &k3, h));
        for i in 0..=n {
            x[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
        }
    }
    x
}

/// (U(T)², U̇(T)²) of path `path`.
fn end_squares(problem: &Problem, dt: f64, t: f64, path: u64) -> (f64, f64) {
    let method = PredictorCorrector {
        dt,
        ..Default::default()
    };
    let steps = (t / dt).round() as u64;
    let mut s = Stepper::new(problem, &method, (SEED, path), t).unwrap();
    for _ in 0..steps {
        s.step().unwrap();
    }
    (s.u() * s.u(), s.v() * s.v())
}

/// Ü + 2ζU̇ + U = Uξ from (1, 0): EU²(T), EU̇²(T) at D = `factor`·D_c against the moment
/// system's exact values; with `tau` > 0 the noise is OU of that correlation time (τ ≪ 1/ω0:
/// its white limit, the same exact values up to O(τ²ω0²), which the tolerance does not need). The second moments of a multiplicative-noise system are carried by
/// rare large paths: the standard error taken is the larger of the sample's and the exact one
/// (√((EU⁴ − (EU²)²)/N), from the fourth moments), and ζ, D, T keep it at a few per cent.
fn parametric(factor: f64, paths: u64, t: f64, dt: f64) {
    parametric_with(factor, 0.0, paths, t, dt)
}

fn parametric_with(factor: f64, tau: f64, paths: u64, t: f64, dt: f64) {
    let (zeta, omega0): (f64, f64) = (0.05, 1.0);
    let critical = 2.0 * zeta * omega0.powi(3);
    let d = factor * critical;
    let c = 2.0 * zeta * omega0;
    let mut m = linear(1.0, c);
    m.start.u0 = 1.0;
    m.noise.multiplicative = Some(NoiseTerm {
        intensity: d,
        correlation_time: tau,
    });
    let problem = Problem::from_model(&m).unwrap();
    let second = exact_moments(2, c, omega0, d, t);
    let fourth = exact_moments(4, c, omega0, d, t);
    let n = paths as f64;
    let exact_se = [
        ((fourth[0] - second[0] * second[0]) / n).sqrt(),
        ((fourth[4] - second[2] * second[2]) / n).sqrt(),
    ];
    let mut at = Vec::new();
    for step in [2.0 * dt, dt] {
        let (u2, v2): (Vec<f64>, Vec<f64>) =
            each_path(paths, |i| end_squares(&problem, step, t, i))
                .into_iter()
                .unzip();
        let (u2, v2) = (mean_se(&u2), mean_se(&v2));
        at.push(((u2.0, u2.1.max(exact_se[0])), (v2.0, v2.1.max(exact_se[1]))));
    }
    let label = format!(
        "Ü + {c}U̇ + U = Uξ, D = {factor}·D_c = {d:.4} (D_c = 2ζω0³ = {critical}), τ = {tau}, \
         {paths} paths, T = {t}, dt = {dt}"
    );
    check(&label, "E U^2(T)", at[0].0, at[1].0, second[0]);
    check(&label, "E V^2(T)", at[0].1, at[1].1, second[2]);
    // the energy-like moment decays below the boundary and grows above it
    let end = at[1].0 .0 + at[1].1 .0;
    let exact_end = second[0] + second[2];
    println!("{label}: E(U² + U̇²)(T) = {end:.4} (exact {exact_end:.4}, from 1)");
    if factor < 1.0 {
        assert!(exact_end < 1.0 && end < 1.0);
    } else {
        assert!(exact_end > 1.0 && end > 1.0);
    }
}

#[test]
fn parametric_white_noise_has_the_exact_second_moments_below_the_boundary() {
    parametric(0.8, 16_000, 20.0, 0.01);
}

#[test]
fn parametric_white_noise_has_the_exact_second_moments_above_the_boundary() {
    parametric(1.25, 16_000, 20.0, 0.01);
}

/// The τ → 0 limit of OU multiplicative noise is the white noise of the same D (Stratonovich's,
/// here Itô's too): at τ = 0.01 the ensemble meets the white-noise exact moments.
#[test]
fn parametric_ou_noise_of_short_correlation_time_has_the_white_second_moments() {
    parametric_with(0.8, 0.01, 16_000, 20.0, 0.01);
}

#[test]
#[ignore = "extended: four times the paths, Δt halved"]
fn parametric_white_noise_has_the_exact_second_moments_extended() {
    parametric(0.8, 64_000, 20.0, 0.005);
    parametric(1.25, 64_000, 20.0, 0.005);
}

/// A model with two fractional terms, correlated multiplicative OU noise and a Duffing term:
/// lanes of 4 and 8 give the scalar bits (path by path), a clone continues as its original
/// (memories and η_m's stream carried), and the Lyapunov exponent by the tangent (the
/// fractional terms' memories of δV and U·η_m differentiated) agrees with two trajectories
/// path by path (no wall: the tangent is the step's exact derivative).
#[test]
fn fractional_paths_are_the_same_in_lanes_and_clones() {
    use trirhythm::analysis::lyapunov::LyapunovMethod;
    use trirhythm::analysis::{largest_lyapunov, LyapunovSpec};
    let mut m = linear(0.95, 0.1);
    m.restoring.cubic = 0.3;
    m.start.u0 = 0.7;
    m.fractional = vec![
        Fractional {
            coefficient: 0.3,
            order: 0.4,
        },
        Fractional {
            coefficient: 0.1,
            order: 1.0,
        },
    ];
    m.noise.additive = Some(NoiseTerm {
        intensity: 0.05,
        correlation_time: 0.5,
    });
    m.noise.multiplicative = Some(NoiseTerm {
        intensity: 0.02,
        correlation_time: 0.5,
    });
    m.noise.correlation = -0.4;
    let problem = Problem::from_model(&m).unwrap();
    let method = PredictorCorrector::default();
    let steps = 3000u64;
    let horizon = steps as f64 * method.dt;
    let bits = |s: &Stepper| (s.u().to_bits(), s.v().to_bits());
    let alone = same_alone_as_clones_and_in_lanes(&problem, &method, steps, bits, |_| {}, "");
    // the multiplicative noise moves the path: not the bits without it
    let mut quiet = m.clone();
    quiet.noise.multiplicative = None;
    quiet.noise.correlation = 0.0;
    let mut q = Stepper::new(
        &Problem::from_model(&quiet).unwrap(),
        &method,
        (SEED, 0),
        horizon,
    )
    .unwrap();
    for _ in 0..steps {
        q.step().unwrap();
    }
    assert_ne!(bits(&q), alone[0]);
    let spec = |method| LyapunovSpec {
        paths: 2,
        transient: 20.0,
        length: 200.0,
        method,
        ..Default::default()
    };
    let two = largest_lyapunov(
        &problem,
        &method,
        &spec(LyapunovMethod::TwoTrajectory),
        &Silent,
    )
    .unwrap();
    println!(
        "two-trajectory exponent: {} ± {}",
        two.lle.value, two.lle.stderr
    );
    // the fractional memory relaxes algebraically: an exponent near 0 from below
    assert!(two.lle.value.is_finite() && two.lle.value.abs() < 0.1);
    let tangent =
        largest_lyapunov(&problem, &method, &spec(LyapunovMethod::Tangent), &Silent).unwrap();
    for (a, b) in tangent.per_path.iter().zip(&two.per_path) {
        println!(
            "path {}: tangent {}, two trajectories {}",
            a.path, a.exponent, b.exponent
        );
        assert!((a.exponent - b.exponent).abs() < 1e-5, "path {}", a.path);
    }
}

/// Multiplicative noise with the wall at 0 (U·η_m vanishes at the wall, so the impact's
/// V₋ is the General kernel's as without it): paths bounce and stick, keep U ≥ 0, and give the
/// same bits in lanes.
#[test]
fn multiplicative_noise_steps_with_the_wall() {
    use trirhythm::engine::Lanes;
    let mut m = Model::from(&trirhythm::model::preset("fig13a").unwrap().params);
    m.noise.multiplicative = Some(NoiseTerm {
        intensity: 0.3,
        correlation_time: 0.0,
    });
    m.noise.additive = Some(NoiseTerm {
        intensity: 0.2,
        correlation_time: 0.0,
    });
    m.noise.correlation = 0.5;
    let problem = Problem::from_model(&m).unwrap();
    assert!(problem.wall());
    let method = PredictorCorrector::default();
    let steps = 4000u64;
    let horizon = steps as f64 * method.dt;
    let mut impacts = 0;
    let alone: Vec<_> = (0..4)
        .map(|i| {
            let mut s = Stepper::new(&problem, &method, (SEED, i), horizon).unwrap();
            for _ in 0..steps {
                s.step().unwrap();
                assert!(s.u() >= 0.0);
            }
            impacts += s.impacts();
            (s.u().to_bits(), s.v().to_bits())
        })
        .collect();
    println!("{impacts} impacts on 4 paths");
    assert!(impacts > 10);
    let mut paths: Vec<Stepper> = (0..4)
        .map(|i| Stepper::new(&problem, &method, (SEED, i), horizon).unwrap())
        .collect();
    let mut obs: Vec<_> = (0..4).map(|_| |_: &Stepper| Flow::Continue).collect();
    trirhythm::engine::run_lanes(&mut paths, steps, &mut obs, Lanes::Width(4), &Silent).unwrap();
    let got: Vec<_> = paths
        .iter()
        .map(|s| (s.u().to_bits(), s.v().to_bits()))
        .collect();
    assert_eq!(got, alone);
}
