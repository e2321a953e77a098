//! Impact invariants (proptest): |V₊| = r|V₋| with V₋ ≤ 0, U ≥ 0 always, chattering ends in
//! sticking without hanging, no energy gain from impacts.

use proptest::prelude::*;
use trirhythm::engine::Memory;
use trirhythm::engine::*;
use trirhythm::model::{preset, Damping, Params};

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    #[test]
    fn impact_law_and_positivity(
        r in 0.0f64..1.0,
        lambda in 0.85f64..=1.0,
        u0 in 0.0f64..3.0,
        v0 in -3.0f64..3.0,
        noise in 0.0f64..0.5,
        restart in proptest::bool::ANY,
    ) {
        let mut p = preset("fig1").unwrap().params;
        p.restitution = r;
        p.lambda = lambda;
        p.mu0 = 0.05;
        p.noise_intensity = noise;
        p.correlation_time = 0.3;
        let problem = Problem::from_params(&p).unwrap().with_start(u0, v0).unwrap();
        let m = PredictorCorrector {
            dt: 0.01,
            impact_memory: if restart { ImpactMemory::Restart } else { ImpactMemory::Continuous },
            ..Default::default()
        };
        let o = Options { t_end: 30.0, seed: 11, record_impacts: true, ..Default::default() };
        let tr = simulate(&problem, &m, &o).unwrap();
        prop_assert_eq!(tr.impacts, tr.impact_events.len());
        for i in &tr.impact_events {
            prop_assert!(i.v_minus <= 0.0);
            prop_assert!((i.v_plus.abs() - r * i.v_minus.abs()).abs() <= 1e-12 * (1.0 + i.v_minus.abs()));
        }
        prop_assert!(tr.u.iter().all(|&u| u >= 0.0), "U < 0");
        prop_assert_eq!(tr.steps, 3000);
    }
}

/// Ü + 0.3U̇ + 9U = η with η a frozen negative force (OU noise with τ = 1e6 ≫ T, D/τ = 1,
/// the first seed whose η is negative), r = 0.5: pressed against the wall, the bounces shrink
/// geometrically and their spacing with them (chattering: infinitely many impacts in finite
/// time); the scheme must stick at U = 0 and stay, with finitely many impacts and U ≥ 0.
#[test]
fn chattering_ends_in_sticking() {
    let p = Params {
        mu0: 1.0,
        omega0: 3.0,
        lambda: 1.0,
        restitution: 0.5,
        damping: Damping {
            coefficients: vec![-0.3], // positive damping (P < 0): energy decays too
        },
        noise_intensity: 1e6,
        correlation_time: 1e6,
    };
    let problem = Problem::from_params(&p).unwrap();
    let seed = (0..100u64)
        .find(|&seed| {
            let probe = Options {
                t_end: 0.01,
                seed,
                ..Default::default()
            };
            simulate(&problem, &PredictorCorrector::default(), &probe)
                .unwrap()
                .eta[0]
                < -0.5
        })
        .unwrap();
    for memory in [Memory::Direct, Memory::default()] {
        for im in [ImpactMemory::Continuous, ImpactMemory::Restart] {
            let m = PredictorCorrector {
                dt: 0.01,
                memory,
                impact_memory: im,
                ..Default::default()
            };
            let o = Options {
                t_end: 20.0,
                seed,
                ..Default::default()
            };
            let problem = problem.clone().with_start(0.0, 2.0).unwrap();
            let tr = simulate(&problem, &m, &o).unwrap();
            assert!(
                tr.impacts >= 3 && tr.impacts < 200,
                "{} impacts",
                tr.impacts
            );
            assert!(tr.sticking_steps > 0, "chattering must end in sticking");
            assert!(tr.u.iter().all(|&u| u >= 0.0));
            let e_end = tr.u.last().unwrap().powi(2) * 9.0 + tr.v.last().unwrap().powi(2);
            assert!(e_end < 1e-6, "should come to rest at the wall: E = {e_end}");
        }
    }
}

/// The fractional oscillator pressed against the wall by its memory: a fractional system
/// started downwards at λ = 0.9 with r = 0 sticks at the first impact and must leave when g
/// pushes away (the restoring force is zero at U = 0, so it leaves only through memory);
/// whatever happens, the run ends and U ≥ 0.
#[test]
fn plastic_impacts_do_not_hang() {
    let mut p = preset("fig1").unwrap().params;
    p.restitution = 0.0;
    p.lambda = 0.9;
    let problem = Problem::from_params(&p)
        .unwrap()
        .with_start(1.0, -1.0)
        .unwrap();
    let o = Options {
        t_end: 50.0,
        ..Default::default()
    };
    let tr = simulate(&problem, &PredictorCorrector::default(), &o).unwrap();
    assert!(tr.impacts >= 1);
    assert!(tr.u.iter().all(|&u| u >= 0.0));
}
