//! Known answers of the General kernel's walls (`engine::stepper::walls`): a wall at any δ
//! keeping U above or below it, two walls δ1 < δ2, a speed-dependent restitution, sticking at a
//! wall where the force is not zero. Every model is built from a [`Model`] value (the model
//! file's fields) through [`Problem::from_model`].
//!
//! - **Two walls, r = 1** (λ = 1, h ≡ 0, no noise): Ü + U = 0 between δ1 < 0 < δ2 with
//!   energy E = (U̇² + U²)/2 = A²/2 > δ²/2 moves along arcs U = A sin t, so the time from one
//!   wall to the other is asin(δ2/A) − asin(δ1/A) and the period twice that; the energy is kept.
//!   Measured: the mean time between impacts on the upper wall over t ∈ [0, 100] and the energy
//!   at t = 100, at Δt = 0.02, 0.01, 0.005, with the observed order of both errors.
//! - **An offset wall, r = 1**: U = A cos t kept above δ returns to the wall after 2acos(δ/A);
//!   kept below δ after 2acos(−δ/A); both measured as above, for δ = 0.3 and δ = −0.4.
//! - **The paper's arithmetic**: a wall at 0 keeping U ≥ 0 whose speed-dependent law is the
//!   constant r (r0 = r_fast = r) steps through this code and gives the paper kernel's bits
//!   (fig13a, OU noise, chattering and sticking, both impact memories); the mirror image — a
//!   wall at 0 keeping U ≤ 0, from −U(0) — gives the paper's path negated, bit for bit.
//! - **Speed-dependent restitution**: every impact's exit speed is r(|V₋|)·|V₋| with
//!   r(v) = r_fast + (r0 − r_fast)e^{−v/v_s} (to the last bit), the first impact's V₋ is the
//!   exact −√(A² − δ²), and the rebound's height the exact √(δ² + V₊²).
//! - **Sticking at δ**: a mass with r = 0.5 on a lower wall at δ = 0.5 (the force −k(δ) = −0.5
//!   pushes into it) chatters, settles and stays at (δ, 0); the same above an upper wall at
//!   −0.5, and at λ = 0.95; with a forcing F cos(Ωt + π), F = 1, a mass at rest on the wall stays
//!   while −0.5 + F cos ψ ≤ 0 and leaves at t = 2π/(3Ω).
//! - **Lanes and clones** give the scalar bits; both Lyapunov methods (the tangent and two
//!   trajectories) take these models.
//! - **Multiplicative noise at a wall off 0**: with W = U − s the oscillator
//!   Ü + cU̇ + U = √D_a ξ + U√D_m ξ against a wall at δ is the oscillator
//!   Ẅ + cẆ + W = −s + (√D_a + s√D_m)ξ + W√D_m ξ against a wall at δ − s, so δ·η_m acts at
//!   the wall; the two paths agree to rounding through the impacts (one lower wall moved to 0,
//!   an upper wall, two walls; white and OU noise; started above and below 0).
//! - **Lyapunov exponents by the tangent**: an elastic (r = 1) undamped linear oscillator
//!   between two walls is periodic and conservative: |λ| < 2e-3 over T = 2000 (the tangent grows
//!   at most linearly); damped (h = −0.1) with r = 0.9 the exponent is negative over the impacts
//!   (T = 20) and −c/2 over T = 500 (the decay beside the walls).
//!
//! Measured values are printed with `--nocapture`.

mod common;

use common::{chattering, linear, same_alone_as_clones_and_in_lanes, SEED};
use trirhythm::engine::{run, Flow, ImpactMemory, PredictorCorrector, Problem, Stepper};
use trirhythm::model::{Harmonic, Keep, Model, NoiseTerm, Restitution, SpeedRestitution, Wall};
use trirhythm::monitor::Silent;

/// Ü + U = 0 (λ = 1, h ≡ 0, ω0 = 1, no noise) with `walls`, from (u0, v0).
fn harmonic(walls: Vec<Wall>, (u0, v0): (f64, f64)) -> Model {
    let mut m = linear(1.0, 1.0);
    m.damping.coefficients = vec![0.0];
    m.walls = walls;
    m.start.u0 = u0;
    m.start.v0 = v0;
    m
}

fn wall(position: f64, keep: Keep, r: f64) -> Wall {
    Wall {
        position,
        keep,
        restitution: Restitution::Constant(r),
    }
}

/// The mean time between impacts with V₋ of sign `sign` (one wall of the pair) over
/// [0, t_end] and the relative energy error at t_end, at steps `dt`.
fn period_and_energy(problem: &Problem, dt: f64, t_end: f64, sign: f64) -> (f64, f64, usize) {
    let method = PredictorCorrector {
        dt,
        ..Default::default()
    };
    let (u0, v0) = problem.start(0);
    let e0 = 0.5 * (u0 * u0 + v0 * v0);
    let mut s = Stepper::new(problem, &method, (SEED, 0), t_end).unwrap();
    let mut times = Vec::new();
    let mut obs = |s: &Stepper| {
        if let Some(i) = s.events().impact {
            if i.v_minus * sign > 0.0 {
                times.push(i.time);
            }
        }
        Flow::Continue
    };
    run(&mut s, (t_end / dt).round() as u64, &mut obs, &Silent).unwrap();
    assert_eq!(s.sticking_steps(), 0);
    let period = (times[times.len() - 1] - times[0]) / (times.len() - 1) as f64;
    let e = 0.5 * (s.u() * s.u() + s.v() * s.v());
    (period, (e - e0) / e0, times.len())
}

/// The period's and the energy's relative errors at Δt = 0.02, 0.01, 0.005 against `exact`;
/// asserts both small at the finest step and both orders near 2.
fn converges(name: &str, problem: &Problem, exact: f64, sign: f64) {
    let t_end = 100.0;
    let rows: Vec<(f64, f64, f64, usize)> = [0.02, 0.01, 0.005]
        .iter()
        .map(|&dt| {
            let (period, de, n) = period_and_energy(problem, dt, t_end, sign);
            (dt, (period - exact) / exact, de, n)
        })
        .collect();
    let orders: Vec<(f64, f64)> = rows
        .windows(2)
        .map(|w| {
            (
                (w[0].1 / w[1].1).abs().log2(),
                (w[0].2 / w[1].2).abs().log2(),
            )
        })
        .collect();
    println!(
        "{name}: exact period {exact:.12}; (dt, relative error of the period, of the energy at \
         t = {t_end}, impacts) {rows:?}; observed orders (period, energy) {orders:?}"
    );
    let (_, e_fine, h_fine, n) = rows[2];
    assert!(n > 20, "{name}: {rows:?}");
    assert!(
        e_fine.abs() < 1e-5 && h_fine.abs() < 1e-4,
        "{name}: {rows:?}"
    );
    let (p_order, h_order) = orders[1];
    assert!((1.6..=2.6).contains(&p_order), "{name}: {orders:?}");
    assert!((1.6..=2.6).contains(&h_order), "{name}: {orders:?}");
}

#[test]
fn a_linear_oscillator_between_two_walls_keeps_the_exact_period_and_its_energy() {
    let (lower, upper) = (-0.5, 0.8);
    let m = harmonic(
        vec![wall(lower, Keep::Above, 1.0), wall(upper, Keep::Below, 1.0)],
        (0.0, 1.0),
    );
    let problem = Problem::from_model(&m).unwrap();
    assert!(!problem.wall() && problem.oscillator().terms().is_some());
    let amplitude = 1.0f64;
    let exact = 2.0 * ((upper / amplitude).asin() - (lower / amplitude).asin());
    converges("two walls at -0.5, 0.8, r = 1", &problem, exact, 1.0);
}

#[test]
fn a_linear_oscillator_against_an_offset_wall_keeps_the_exact_period_and_its_energy() {
    for delta in [0.3, -0.4] {
        // kept above δ from U = 1: the return time 2acos(δ)
        let above = Problem::from_model(&harmonic(vec![wall(delta, Keep::Above, 1.0)], (1.0, 0.0)))
            .unwrap();
        let exact = 2.0 * delta.acos();
        converges(
            &format!("wall at {delta} keeping above"),
            &above,
            exact,
            -1.0,
        );
        // kept below δ from U = −1: 2acos(−δ)
        let below =
            Problem::from_model(&harmonic(vec![wall(delta, Keep::Below, 1.0)], (-1.0, 0.0)))
                .unwrap();
        let exact = 2.0 * (-delta).acos();
        converges(
            &format!("wall at {delta} keeping below"),
            &below,
            exact,
            1.0,
        );
    }
}

#[test]
fn a_wall_at_zero_through_the_walls_code_gives_the_paper_kernels_bits_and_their_mirror() {
    let p = chattering();
    for memory in [ImpactMemory::Continuous, ImpactMemory::Restart] {
        let method = PredictorCorrector {
            impact_memory: memory,
            ..Default::default()
        };
        let paper = Problem::from_params(&p).unwrap();
        // r(v) ≡ r through the speed-dependent law: the General kernel's walls
        let mut speed = Model::from(&p);
        speed.walls[0].restitution = Restitution::Speed(SpeedRestitution {
            r0: 0.3,
            r_fast: 0.3,
            speed: 1.0,
        });
        let speed = Problem::from_model(&speed).unwrap();
        assert!(!speed.wall() && speed.oscillator().terms().is_some());
        // the mirror: a wall at 0 keeping U ≤ 0, from U(0) = −1
        let mut mirror = Model::from(&p);
        mirror.walls[0].keep = Keep::Below;
        mirror.start.u0 = -1.0;
        let mirror = Problem::from_model(&mirror).unwrap();
        let mut a = Stepper::new(&paper, &method, (7, 0), 200.0).unwrap();
        let mut b = Stepper::new(&speed, &method, (7, 0), 200.0).unwrap();
        let mut c = Stepper::new(&mirror, &method, (7, 0), 200.0).unwrap();
        for n in 0..20_000 {
            a.step().unwrap();
            b.step().unwrap();
            c.step().unwrap();
            assert_eq!(
                (a.u().to_bits(), a.v().to_bits(), a.events()),
                (b.u().to_bits(), b.v().to_bits(), b.events()),
                "{memory:?}: step {n}"
            );
            let mut negated = c.events();
            if let Some(i) = &mut negated.impact {
                (i.v_minus, i.v_plus) = (-i.v_minus, -i.v_plus);
            }
            // bit for bit but for the sign of a zero (the clamped state (0, 0) is +0 on both)
            let bits = |x: f64| (x + 0.0).to_bits();
            assert_eq!(
                (bits(a.u()), bits(a.v()), a.events()),
                (bits(-c.u()), bits(-c.v()), negated),
                "{memory:?}: mirror, step {n}"
            );
        }
        assert!(a.impacts() > 100 && a.sticking_steps() > 1000, "{memory:?}");
        for s in [&b, &c] {
            assert_eq!(
                (a.impacts(), a.sticking_steps()),
                (s.impacts(), s.sticking_steps())
            );
        }
    }
}

#[test]
fn a_speed_dependent_restitution_gives_the_documented_exit_speed() {
    let law = SpeedRestitution {
        r0: 0.9,
        r_fast: 0.4,
        speed: 0.5,
    };
    let delta = 0.2;
    let mut m = harmonic(
        vec![Wall {
            position: delta,
            keep: Keep::Above,
            restitution: Restitution::Speed(law),
        }],
        (1.0, 0.0),
    );
    m.damping.mu0 = 1.0;
    let problem = Problem::from_model(&m).unwrap();
    let dt = 0.001;
    let method = PredictorCorrector {
        dt,
        ..Default::default()
    };
    let mut s = Stepper::new(&problem, &method, (SEED, 0), 20.0).unwrap();
    let mut impacts = Vec::new();
    let mut top = f64::NEG_INFINITY;
    let mut obs = |s: &Stepper| {
        if let Some(i) = s.events().impact {
            impacts.push(i);
        }
        if impacts.len() == 1 {
            top = top.max(s.u());
        }
        Flow::Continue
    };
    run(&mut s, 20_000, &mut obs, &Silent).unwrap();
    assert!(impacts.len() >= 3, "{impacts:?}");
    // the documented form, and the library's r(v) (its own exp) to the last bit
    let r = |v: f64| Restitution::Speed(law).at(v);
    let documented = |v: f64| law.r_fast + (law.r0 - law.r_fast) * (-v / law.speed).exp();
    for i in &impacts {
        let speed = i.v_minus.abs();
        assert!(i.v_minus < 0.0);
        assert!((r(speed) - documented(speed)).abs() <= 1e-15, "{i:?}");
        assert_eq!(i.v_plus, r(speed) * speed, "{i:?}");
    }
    let first = impacts[0];
    let exact_in = (1.0f64 - delta * delta).sqrt();
    let exact_top = (delta * delta + first.v_plus * first.v_plus).sqrt();
    println!(
        "speed-dependent r at δ = {delta}, dt = {dt}: V₋ = {} (exact {}), V₊ = {} = r(|V₋|)|V₋| \
         with r = {}; rebound height {top} (exact {exact_top}); impacts {}",
        first.v_minus,
        -exact_in,
        first.v_plus,
        r(first.v_minus.abs()),
        impacts.len()
    );
    assert!((first.v_minus + exact_in).abs() < 1e-6, "{first:?}");
    assert!((top - exact_top).abs() < 1e-6, "{top} vs {exact_top}");
    // slower impacts rebound with more of their speed: r0 > r_fast
    let ratios: Vec<f64> = impacts.iter().map(|i| i.v_plus / i.v_minus.abs()).collect();
    assert!(ratios.windows(2).all(|w| w[1] > w[0]), "{ratios:?}");
}

/// Steps until t_end from (u0, 0) with `walls`; returns the stepper.
fn settle(lambda: f64, walls: Vec<Wall>, u0: f64, t_end: f64, dt: f64) -> Stepper {
    let mut m = harmonic(walls, (u0, 0.0));
    m.leading.lambda = lambda;
    let problem = Problem::from_model(&m).unwrap();
    let method = PredictorCorrector {
        dt,
        ..Default::default()
    };
    let mut s = Stepper::new(&problem, &method, (SEED, 0), t_end).unwrap();
    for _ in 0..(t_end / dt).round() as u64 {
        s.step().unwrap();
    }
    s
}

#[test]
fn a_mass_settles_onto_a_wall_where_the_force_pushes_into_it_and_stays() {
    let dt = 0.01;
    for lambda in [1.0, 0.95] {
        let lower = settle(lambda, vec![wall(0.5, Keep::Above, 0.5)], 1.0, 60.0, dt);
        let upper = settle(lambda, vec![wall(-0.5, Keep::Below, 0.5)], -1.0, 60.0, dt);
        println!(
            "λ = {lambda}: on the lower wall at 0.5 after {} impacts, {} sticking steps; on the \
             upper wall at −0.5 after {} impacts, {} sticking steps",
            lower.impacts(),
            lower.sticking_steps(),
            upper.impacts(),
            upper.sticking_steps()
        );
        for (s, delta) in [(&lower, 0.5), (&upper, -0.5)] {
            assert_eq!((s.u(), s.v()), (delta, 0.0), "λ = {lambda}");
            assert!(s.events().stuck, "λ = {lambda}");
            assert!(s.impacts() > 3, "λ = {lambda}: it chattered first");
            // it stays: the last half of the run stuck
            assert!(s.sticking_steps() as f64 * dt > 30.0, "λ = {lambda}");
        }
        assert_eq!(lower.impacts(), upper.impacts());
        assert_eq!(lower.sticking_steps(), upper.sticking_steps());
    }
}

#[test]
fn a_mass_at_rest_on_a_wall_leaves_when_the_force_pulls_away() {
    // the net force at the wall δ = 0.5 is −k(δ) + F cos(Ωt + π) = −0.5 − cos(Ωt): it pushes
    // into the wall until Ωt = 2π/3
    let (delta, omega, dt) = (0.5, 0.2, 0.01);
    let mut m = harmonic(vec![wall(delta, Keep::Above, 0.0)], (delta, 0.0));
    m.forcing = Some(Harmonic {
        amplitude: 1.0,
        frequency: omega,
        phase: std::f64::consts::PI,
    });
    let problem = Problem::from_model(&m).unwrap();
    let method = PredictorCorrector {
        dt,
        ..Default::default()
    };
    let mut s = Stepper::new(&problem, &method, (SEED, 0), 20.0).unwrap();
    let mut left = None;
    for _ in 0..2000 {
        s.step().unwrap();
        if s.u() > delta && left.is_none() {
            left = Some(s.time());
        }
        if left.is_none() {
            assert_eq!((s.u(), s.v()), (delta, 0.0), "t = {}", s.time());
        }
    }
    let exact = 2.0 * std::f64::consts::PI / (3.0 * omega);
    let left = left.expect("it leaves");
    println!("leaves the wall at t = {left} (exact {exact}, dt = {dt})");
    assert!((left - exact).abs() <= 2.0 * dt, "{left} vs {exact}");
}

#[test]
fn paths_with_walls_are_the_same_in_lanes_and_clones_and_take_both_lyapunov_methods() {
    let mut m = harmonic(
        vec![wall(-0.6, Keep::Above, 0.7), wall(0.9, Keep::Below, 0.95)],
        (0.2, 0.0),
    );
    m.leading.lambda = 0.95;
    m.damping.mu0 = 0.1;
    m.damping.coefficients = vec![1.0, -1.0];
    m.restoring.cubic = 0.5;
    m.noise.additive = Some(NoiseTerm {
        intensity: 0.3,
        correlation_time: 0.5,
    });
    let problem = Problem::from_model(&m).unwrap();
    for memory in [ImpactMemory::Continuous, ImpactMemory::Restart] {
        let method = PredictorCorrector {
            impact_memory: memory,
            ..Default::default()
        };
        let bits = |s: &Stepper| (s.u().to_bits(), s.v().to_bits(), s.impacts());
        let between = |s: &Stepper| assert!((-0.6..=0.9).contains(&s.u()), "between the walls");
        let label = format!("{memory:?}: ");
        let alone =
            same_alone_as_clones_and_in_lanes(&problem, &method, 3000, bits, between, &label);
        assert!(alone.iter().all(|b| b.2 > 5), "{alone:?}");
    }
    // both Lyapunov methods take the model (the tangent through the impact steps)
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

/// The largest exponent by the tangent method of `model` over [transient, transient + length],
/// one path.
fn tangent_lle(model: &Model, transient: f64, length: f64) -> f64 {
    use trirhythm::analysis::lyapunov::LyapunovMethod;
    use trirhythm::analysis::{largest_lyapunov, LyapunovSpec};
    let problem = Problem::from_model(model).unwrap();
    let spec = LyapunovSpec {
        paths: 1,
        seed: SEED,
        transient,
        length,
        method: LyapunovMethod::Tangent,
        ..Default::default()
    };
    let method = PredictorCorrector::default();
    largest_lyapunov(&problem, &method, &spec, &Silent)
        .unwrap()
        .lle
        .value
}

#[test]
fn tangent_exponents_between_two_walls() {
    // Ü + U = 0 between walls at −0.5 and 0.7, r = 1, from (0, 1): periodic and conservative;
    // the period depends on the energy, so a perturbation grows at most linearly (a phase
    // drift) and the exponent over T is O(ln T/T): |λ| < 2e-3 over T = 2000
    let elastic = harmonic(
        vec![wall(-0.5, Keep::Above, 1.0), wall(0.7, Keep::Below, 1.0)],
        (0.0, 1.0),
    );
    let lle = tangent_lle(&elastic, 0.0, 2000.0);
    println!("elastic linear oscillator between two walls: tangent LLE {lle:e} over T = 2000");
    assert!(lle.abs() < 2e-3, "{lle}");
    // damped, h = −c (c = 0.1), r = 0.9 at both walls: negative; it stops reaching the walls
    // (10 impacts, by t ≈ 40) and decays as the damped linear oscillator, at −c/2. Over
    // T = 500 only: the impacts leave the tangent's Volterra constant at the size of its state
    // then, which its memory cancels as the state decays, so beyond a decay of about 2⁵³
    // (|λ|T ≈ 37) the exponent meets rounding (measured −0.018 over T = 2000, two trajectories
    // −0.023)
    let mut damped = harmonic(
        vec![wall(-0.5, Keep::Above, 0.9), wall(0.7, Keep::Below, 0.9)],
        (0.0, 3.0),
    );
    damped.damping.mu0 = 0.1;
    damped.damping.coefficients = vec![-1.0];
    let impacts_over = |t_end: f64| {
        let problem = Problem::from_model(&damped).unwrap();
        let method = PredictorCorrector::default();
        let mut s = Stepper::new(&problem, &method, (SEED, 0), t_end).unwrap();
        let mut obs = |_: &Stepper| Flow::Continue;
        run(
            &mut s,
            (t_end / method.dt).round() as u64,
            &mut obs,
            &Silent,
        )
        .unwrap();
        s.impacts()
    };
    // the transient's impacts (the exponent over it), then the decay beside the walls
    let short = tangent_lle(&damped, 0.0, 20.0);
    let long = tangent_lle(&damped, 0.0, 500.0);
    println!(
        "damped (c = 0.1, r = 0.9) between two walls: {} impacts over [0, 20]; tangent LLE \
         {short} over T = 20, {long} over T = 500 (−c/2 = −0.05)",
        impacts_over(20.0)
    );
    assert!(impacts_over(20.0) > 5);
    assert!(short < 0.0 && long < 0.0, "{short}, {long}");
    assert!((long + 0.05).abs() < 5e-3, "{long}");
}

#[test]
fn starts_beyond_the_walls_and_walls_with_the_paper_barrier_are_refused() {
    let m = harmonic(
        vec![wall(-0.5, Keep::Above, 1.0), wall(0.8, Keep::Below, 1.0)],
        (0.0, 1.0),
    );
    let problem = Problem::from_model(&m).unwrap();
    for u0 in [-0.6, 0.81] {
        match problem.clone().with_start(u0, 0.0) {
            Err(trirhythm::Error::InvalidParameter { name, .. }) => assert_eq!(name, "u0"),
            other => panic!("u0 = {u0}: {other:?}"),
        }
    }
    assert!(problem.clone().with_start(0.8, 0.0).is_ok());
    assert!(matches!(
        problem.with_barrier(trirhythm::engine::Barrier::On),
        Err(trirhythm::Error::NotApplicable { .. })
    ));
}

/// Ü + cU̇ + U = √D_a·ξ + U·√D_m·ξ (one deviate stream: correlation c = 1; c = 0.05,
/// D_a = 0.01, D_m = 0.04, r = 0.95) against `walls`, from (u0, 1); `shift` moves the whole
/// problem by W = U − s: walls at δ − s, the static force −s as F cos(Ωt + φ) with Ω = 1e-9
/// (cos ψ = ∓1 to 2e-14 over T = 20), the additive noise's gain √D_a + s√D_m.
fn parametric(walls: &[(f64, Keep)], u0: f64, tau: f64, shift: f64) -> Problem {
    let (da, dm, c) = (0.01f64, 0.04f64, 0.05);
    let mut m = linear(1.0, c);
    m.walls = walls
        .iter()
        .map(|&(position, keep)| wall(position - shift, keep, 0.95))
        .collect();
    m.start.u0 = u0 - shift;
    m.start.v0 = 1.0;
    let gain = da.sqrt() + shift * dm.sqrt();
    m.noise.additive = Some(NoiseTerm {
        intensity: gain * gain,
        correlation_time: tau,
    });
    m.noise.multiplicative = Some(NoiseTerm {
        intensity: dm,
        correlation_time: tau,
    });
    m.noise.correlation = 1.0;
    if shift != 0.0 {
        m.forcing = Some(Harmonic {
            amplitude: shift.abs(),
            frequency: 1e-9,
            phase: if shift > 0.0 {
                std::f64::consts::PI
            } else {
                0.0
            },
        });
    }
    Problem::from_model(&m).unwrap()
}

#[test]
fn multiplicative_noise_at_a_moved_wall_is_the_moved_oscillator() {
    // With W = U − s, Ü + cU̇ + U = √D_a ξ + U√D_m ξ against a wall at δ is
    // Ẅ + cẆ + W = −s + (√D_a + s√D_m)ξ + W√D_m ξ against a wall at δ − s: the force of the
    // multiplicative noise at the wall, δ√D_m ξ, becomes part of the additive noise. The paths
    // agree to rounding over the impacts, for a lower wall moved to 0 (the paper's wall: the
    // impact code of `stepper::impact`, where U·η_m = 0), an upper wall and two walls (the
    // walls' code at other positions), white and OU noise, paths started above and below 0
    // (the additive noise enters as side·η_a, side = −1 below 0: η_m follows it). Measured
    // (`--nocapture`): 5–8 impacts each over T = 20, differences 5e-15 … 4e-10 (the two walls'
    // grows with the impacts, as it does without U·η_m); without δ·η_m at the wall 5e-3.
    let method = PredictorCorrector {
        dt: 0.005,
        ..Default::default()
    };
    let steps = 4_000u64; // T = 20
    for (name, walls, u0, tau, shift) in [
        (
            "lower wall at -0.3, white",
            vec![(-0.3, Keep::Above)],
            1.2,
            0.0,
            -0.3,
        ),
        ("no wall OU", vec![], -1.2, 0.5, 0.4),
        (
            "upper wall at 0.4, white",
            vec![(0.4, Keep::Below)],
            -1.2,
            0.0,
            0.4,
        ),
        (
            "upper wall at 0.4, OU",
            vec![(0.4, Keep::Below)],
            -1.2,
            0.5,
            0.4,
        ),
        (
            "walls at -0.7 and 0.6, white",
            vec![(-0.7, Keep::Above), (0.6, Keep::Below)],
            0.5,
            0.0,
            0.25,
        ),
    ] {
        let path = |shift: f64| {
            let problem = parametric(&walls, u0, tau, shift);
            let mut s = Stepper::new(&problem, &method, (SEED, 0), steps as f64 * 0.005).unwrap();
            let mut out = Vec::with_capacity(steps as usize);
            let mut impacts = 0usize;
            let mut obs = |s: &Stepper| {
                impacts += usize::from(s.events().impact.is_some());
                out.push((s.u() + shift, s.v()));
                Flow::Continue
            };
            run(&mut s, steps, &mut obs, &Silent).unwrap();
            (out, impacts, s.sticking_steps())
        };
        let (at, impacts, sticking) = path(0.0);
        let (moved, impacts_moved, sticking_moved) = path(shift);
        let worst = at
            .iter()
            .zip(&moved)
            .map(|(a, b)| (a.0 - b.0).abs().max((a.1 - b.1).abs()))
            .fold(0.0f64, f64::max);
        eprintln!(
            "{name}: {impacts} impacts, {sticking} sticking steps, largest difference {worst:e}"
        );
        assert!(
            walls.is_empty() || impacts >= 3,
            "{name}: {impacts} impacts"
        );
        assert_eq!(
            (impacts, sticking),
            (impacts_moved, sticking_moved),
            "{name}"
        );
        assert!(worst <= 1e-8, "{name}: {worst:e}");
    }
}
