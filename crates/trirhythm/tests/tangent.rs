//! Benettin's renormalisation of a perturbed copy of a path ([`Stepper::contract_toward`]):
//! it must act on the whole state, memory included.
//!
//! - Linearity (λ = 0.998, Eq. 1 with P ≡ −1, no wall, no noise): the system is linear, so a copy
//!   pulled toward the reference by c must stay exactly c times as far from it as the
//!   un-pulled copy, at every later step. Scaling (δU, δV) alone, leaving the perturbation in the
//!   memory, breaks this at once.
//! - Known exponent (λ = 1, the damped linear oscillator U″ + μU′ + ω²U = 0): Benettin's sum of
//!   logarithms of the separation growth gives −μ/2.
//! - c = 1 changes nothing and c = 0 makes the copy the reference, bit for bit, on a noisy path
//!   with the wall (impacts, sticking).

use trirhythm::engine::*;
use trirhythm::model::{preset, Params};

fn linear(lambda: f64, mu0: f64) -> Params {
    let mut p = preset("fig1").unwrap().params;
    for (k, v) in [
        ("c0", -1.0),
        ("c1", 0.0),
        ("alpha0", 0.0),
        ("beta0", 0.0),
        ("gamma0", 0.0),
        ("delta0", 0.0),
        ("D", 0.0),
        ("lambda", lambda),
        ("mu0", mu0),
        ("omega0", 1.0),
    ] {
        p = p.with(k, v).unwrap();
    }
    p
}

fn path(p: &Params, barrier: Barrier, (u0, v0): (f64, f64), steps: f64, seed: u64) -> Stepper {
    let problem = Problem::from_params(p)
        .and_then(|q| q.with_barrier(barrier))
        .and_then(|q| q.with_start(u0, v0))
        .unwrap();
    let method = PredictorCorrector {
        dt: 0.01,
        ..Default::default()
    };
    let o = Options {
        t_end: steps * 0.01,
        seed,
        ..Default::default()
    };
    o.stepper(&problem, &method).unwrap()
}

#[test]
fn contraction_is_exact_for_a_linear_fractional_system() {
    let p = linear(0.998, 0.1);
    let mut a = path(&p, Barrier::Off, (1.0, 0.0), 6000.0, 0);
    let mut b = path(&p, Barrier::Off, (1.001, 0.0005), 6000.0, 0);
    for _ in 0..3000 {
        a.step().unwrap();
        b.step().unwrap();
    }
    let c = 0.25;
    let mut pulled = b.clone();
    assert!(pulled.contract_toward(&a, c));
    let mut worst: f64 = 0.0;
    for _ in 0..3000 {
        a.step().unwrap();
        b.step().unwrap();
        pulled.step().unwrap();
        let (du, dv) = b.separation(&a);
        let (pu, pv) = pulled.separation(&a);
        let scale = du.hypot(dv);
        worst = worst.max((pu - c * du).hypot(pv - c * dv) / scale);
    }
    // rounding of differences of O(1) numbers against a separation of ~1e-3
    assert!(
        worst < 1e-9,
        "pulled copy off the linear prediction by {worst:e} (relative)"
    );
}

#[test]
fn benettin_exponent_of_the_damped_oscillator_is_minus_half_the_damping() {
    let mu = 0.1;
    let p = linear(1.0, mu);
    let steps = 200_000;
    let mut a = path(&p, Barrier::Off, (1.0, 0.0), steps as f64, 0);
    let d0 = 1e-6;
    let mut b = a.clone();
    assert!(b.contract_toward(&a, 1.0));
    // a perturbation of size d0 along U: pull a copy displaced by 1 toward a by d0
    let mut far = path(&p, Barrier::Off, (2.0, 0.0), steps as f64, 0);
    assert!(far.contract_toward(&a, d0));
    b = far;
    let mut log_sum = 0.0;
    for n in 1..=steps {
        a.step().unwrap();
        b.step().unwrap();
        if n % 100 == 0 {
            let (du, dv) = b.separation(&a);
            let d = du.hypot(dv);
            log_sum += (d / d0).ln();
            assert!(b.contract_toward(&a, d0 / d));
        }
    }
    let exponent = log_sum / (steps as f64 * 0.01);
    assert!(
        (exponent + mu / 2.0).abs() < 2e-4,
        "exponent {exponent} vs −μ/2 = {}",
        -mu / 2.0
    );
}

#[test]
fn contraction_by_zero_makes_the_copy_the_reference_bit_for_bit() {
    // a chattering noisy path with the wall: impacts and sticking steps
    let p = preset("fig13a")
        .unwrap()
        .params
        .with("r", 0.3)
        .unwrap()
        .with("D", 0.5)
        .unwrap();
    let mut a = path(&p, Barrier::On, (7.0, 0.0), 40_000.0, 7);
    let mut other = path(&p, Barrier::On, (6.5, 0.3), 40_000.0, 7);
    for _ in 0..5000 {
        a.step().unwrap();
        other.step().unwrap();
    }
    assert_ne!(other.u(), a.u());
    // at a step where both may be combined (no impact inside either exact window)
    let mut waited = 0;
    while !other.contract_toward(&a, 0.0) {
        a.step().unwrap();
        other.step().unwrap();
        waited += 1;
        assert!(waited < 10_000, "never combinable");
    }
    for _ in 0..20_000 {
        a.step().unwrap();
        other.step().unwrap();
        assert_eq!((other.u(), other.v()), (a.u(), a.v()));
    }
    assert!(a.impacts() > 50 && a.sticking_steps() > 0);
}

#[test]
fn contraction_is_refused_while_an_impact_is_inside_the_window() {
    let p = preset("fig1").unwrap().params;
    let mut a = path(&p, Barrier::On, (2.0, 0.0), 10_000.0, 0);
    let mut b = path(&p, Barrier::On, (2.001, 0.0), 10_000.0, 0);
    while a.impacts() == 0 {
        a.step().unwrap();
        b.step().unwrap();
    }
    // both have just impacted, at slightly different instants: their split pieces differ
    a.step().unwrap();
    b.step().unwrap();
    assert_eq!(b.impacts(), 1);
    let before = (b.u(), b.v());
    assert!(!b.contract_toward(&a, 0.5));
    assert_eq!((b.u(), b.v()), before);
    // and accepted once the impact has left the exact window (8 steps)
    for _ in 0..20 {
        a.step().unwrap();
        b.step().unwrap();
    }
    assert!(b.contract_toward(&a, 0.5));
}
