//! The kernel's arithmetic against the engine: the CPU emulation (the kernel's source compiled
//! as C) gives every path's statistics bit for bit as `run_paths`, and the merged result as
//! `run_ensemble`, across what the kernel holds — the wall with impacts and sticking, no wall,
//! λ < 1 and λ = 1, white and OU noise, both impact memories, Eq. 5 and Eq. 9, wells with
//! first passages, and the General kernel's terms (Duffing, quintic, Rayleigh, forcing,
//! multiplicative noise, fractional terms, the model's walls: `general_*`) — and refuses what it
//! does not hold by name. The layouts shared with C are checked field by field. Each case prints
//! its paths' impacts and sticking steps (`--nocapture`).

use std::mem::{offset_of, size_of};
use trirhythm::analysis::ensemble::{run_ensemble, run_paths, EnsembleSpec, RecordPlan, Wells};
use trirhythm::engine::noise::StepConstants;
use trirhythm::engine::{
    Barrier, GeneralPlan, ImpactMemory, Memory, PredictorCorrector, Problem, StepPlan, System,
};
use trirhythm::model::{
    preset, Fractional, Harmonic, Keep, Model, NoiseTerm, Restitution, SpeedRestitution, Wall,
};
use trirhythm::monitor::Silent;
use trirhythm::Error;
use trirhythm_gpu::{emulate_ensemble, emulate_paths, layout_of_c};

fn spec(paths: usize, seed: u64) -> EnsembleSpec {
    EnsembleSpec {
        paths,
        seed,
        burn_in: 20.0,
        length: 60.0,
        batches: 4,
        bins: 40,
        joint_bins: 8,
        sample_every: 3,
        amplitude_max: 12.0,
        ..Default::default()
    }
}

fn method(dt: f64) -> PredictorCorrector {
    PredictorCorrector {
        dt,
        ..Default::default()
    }
}

/// Every path's statistics and the merged result, emulation against engine, bit for bit;
/// returns the impacts and sticking steps of all paths.
fn same(problem: &Problem, method: &PredictorCorrector, spec: &EnsembleSpec) -> (u64, u64) {
    let all: Vec<u64> = (0..spec.paths as u64).collect();
    let engine = run_paths(problem, method, spec, &all, &Silent).unwrap();
    let emulated = emulate_paths(problem, method, spec, &all).unwrap();
    for (a, b) in engine.iter().zip(&emulated) {
        assert_eq!(a, b, "path {}", a.path);
    }
    assert_eq!(
        run_ensemble(problem, method, spec, &Silent).unwrap(),
        emulate_ensemble(problem, method, spec).unwrap()
    );
    let impacts = engine.iter().map(|p| p.impacts).sum();
    let sticking = engine.iter().map(|p| p.sticking_steps).sum();
    eprintln!(
        "{} paths bit for bit: {impacts} impacts, {sticking} sticking steps",
        spec.paths
    );
    (impacts, sticking)
}

fn fig13a(d: f64) -> Problem {
    let p = preset("fig13a").unwrap().params.with("D", d).unwrap();
    Problem::from_params(&p)
        .unwrap()
        .with_starts(&[(1.0, 0.0), (6.5, 0.0), (0.3, -0.2)])
        .unwrap()
}

#[test]
fn the_structures_shared_with_c_have_the_same_layout() {
    let plan = size_of::<StepPlan>() as u64;
    assert_eq!(layout_of_c(0), plan);
    assert_eq!(layout_of_c(1), offset_of!(StepPlan, older_len) as u64);
    assert_eq!(layout_of_c(2), offset_of!(StepPlan, psi_series) as u64);
    assert_eq!(layout_of_c(9), offset_of!(StepPlan, omega2) as u64);
    assert_eq!(layout_of_c(3), size_of::<RecordPlan>() as u64);
    assert_eq!(layout_of_c(4), offset_of!(RecordPlan, core_hi) as u64);
    assert_eq!(layout_of_c(10), offset_of!(RecordPlan, burn) as u64);
    assert_eq!(layout_of_c(5), trirhythm_gpu::noise_layout() as u64);
    assert_eq!(layout_of_c(11), size_of::<GeneralPlan>() as u64);
    assert_eq!(layout_of_c(12), offset_of!(GeneralPlan, cubic) as u64);
    assert_eq!(layout_of_c(13), offset_of!(GeneralPlan, forcing) as u64);
    assert_eq!(layout_of_c(14), offset_of!(GeneralPlan, amplitude) as u64);
    assert_eq!(layout_of_c(15), offset_of!(GeneralPlan, salt) as u64);
    assert_eq!(layout_of_c(16), offset_of!(GeneralPlan, parametric) as u64);
    assert_eq!(
        layout_of_c(17),
        (offset_of!(GeneralPlan, parametric) + offset_of!(StepConstants, sd)) as u64
    );
    assert_eq!(layout_of_c(18), offset_of!(GeneralPlan, walls) as u64);
    assert_eq!(
        layout_of_c(19),
        offset_of!(GeneralPlan, wall_position) as u64
    );
    assert_eq!(
        layout_of_c(20),
        offset_of!(GeneralPlan, fractional_terms) as u64
    );
    assert_eq!(
        layout_of_c(21),
        offset_of!(GeneralPlan, fractional_k) as u64
    );
    assert_eq!(layout_of_c(22), offset_of!(GeneralPlan, memories) as u64);
}

#[test]
fn paths_with_the_wall_impacts_and_sticking_are_the_engines() {
    // λ = 0.998, OU noise, the wall with r = 0.99: impacts on every cycle
    let (impacts, _) = same(&fig13a(0.1), &method(0.01), &spec(6, 11));
    assert!(impacts > 50, "impacts {impacts}");
    // strong noise at a small r: the oscillator sticks at the wall
    let p = preset("fig13a")
        .unwrap()
        .params
        .with("D", 2.0)
        .unwrap()
        .with("r", 0.3)
        .unwrap();
    let problem = Problem::from_params(&p).unwrap();
    let (impacts, sticking) = same(&problem, &method(0.02), &spec(4, 5));
    assert!(
        impacts > 10 && sticking > 0,
        "impacts {impacts}, sticking {sticking}"
    );
    // the memory restarting at impacts
    let m = PredictorCorrector {
        impact_memory: ImpactMemory::Restart,
        ..method(0.01)
    };
    let (impacts, _) = same(&problem, &m, &spec(3, 8));
    assert!(impacts > 10);
}

#[test]
fn paths_without_the_wall_at_lambda_below_and_at_one_are_the_engines() {
    let off = fig13a(0.1).with_barrier(Barrier::Off).unwrap();
    let (impacts, _) = same(&off, &method(0.01), &spec(4, 3));
    assert_eq!(impacts, 0);
    // λ = 1: the flat lumped memory; white noise
    let p = preset("fig13a")
        .unwrap()
        .params
        .with("lambda", 1.0)
        .unwrap();
    let white = p.with("tau", 0.0).unwrap();
    same(
        &Problem::from_params(&p).unwrap(),
        &method(0.01),
        &spec(3, 4),
    );
    same(
        &Problem::from_params(&white).unwrap(),
        &method(0.01),
        &spec(3, 4),
    );
    // λ = 0.7 with a longer window and a finer SOE tolerance
    let frac = preset("fig13a")
        .unwrap()
        .params
        .with("lambda", 0.7)
        .unwrap();
    let m = PredictorCorrector {
        memory: Memory::SumOfExponentials { tolerance: 1e-9 },
        window: 24,
        ..method(0.02)
    };
    same(&Problem::from_params(&frac).unwrap(), &m, &spec(3, 9));
}

#[test]
fn the_equivalent_and_zhuravlev_systems_are_the_engines() {
    let p = preset("fig13a").unwrap().params.with("D", 0.2).unwrap();
    for system in [System::Equivalent, System::Zhuravlev] {
        let problem = Problem::from_params(&p)
            .unwrap()
            .with_system(system)
            .unwrap();
        let (impacts, _) = same(&problem, &method(0.01), &spec(3, 21));
        assert!(impacts > 10, "{system:?}: impacts {impacts}");
    }
}

#[test]
fn wells_and_first_passages_are_the_engines() {
    // Fig. 13(a)'s two cycles, strong noise so that paths pass between them
    let problem = fig13a(0.6);
    let s = EnsembleSpec {
        wells: Some(Wells::new(vec![2.0, 6.5], vec![4.5]).unwrap()),
        length: 300.0,
        ..spec(4, 2)
    };
    same(&problem, &method(0.02), &s);
    let stats = emulate_paths(&problem, &method(0.02), &s, &[0, 1, 2, 3]).unwrap();
    let passages: u64 = stats
        .iter()
        .flat_map(|p| &p.passages)
        .map(|c| c.count)
        .sum();
    assert!(passages > 0, "no passage between the wells");
}

#[test]
fn a_blow_up_is_reported_as_the_engine_reports_it() {
    // strong noise and the bound at 4: the paths cross it
    let problem = fig13a(3.0)
        .with_starts(&[(1.0, 0.0)])
        .unwrap()
        .with_blow_up(4.0)
        .unwrap();
    let m = method(0.01);
    let s = spec(3, 1);
    let engine = run_ensemble(&problem, &m, &s, &Silent).unwrap_err();
    let emulated = emulate_ensemble(&problem, &m, &s).unwrap_err();
    assert!(matches!(engine, Error::InPath { .. }), "{engine}");
    assert_eq!(engine.to_string(), emulated.to_string());
}

/// Fig. 13(a)'s oscillator (λ = 0.998, OU noise, the wall at 0 with r = 0.99) as a model, with
/// `d` for D and `r` for r, three starts.
fn fig13a_model(d: f64, r: f64) -> Model {
    let p = preset("fig13a")
        .unwrap()
        .params
        .with("D", d)
        .unwrap()
        .with("r", r)
        .unwrap();
    Model::from(&p)
}

fn general(m: &Model) -> Problem {
    let problem = Problem::from_model(m)
        .unwrap()
        .with_starts(&[(1.0, 0.0), (4.0, 0.5), (0.3, -0.2)])
        .unwrap();
    assert!(problem.oscillator().terms().is_some());
    problem
}

/// Stage 1's terms together: Duffing and quintic restoring, two Rayleigh terms, the harmonic
/// forcing (8000 steps: 31 re-anchorings of its phase).
fn duffing_rayleigh_forced(m: &mut Model) {
    m.restoring.cubic = 0.3;
    m.restoring.quintic = 0.002;
    m.damping.rayleigh = vec![-0.02, 0.001];
    m.forcing = Some(Harmonic {
        amplitude: 0.4,
        frequency: 1.3,
        phase: 0.2,
    });
}

#[test]
fn general_paths_without_a_wall_are_the_engines() {
    let mut m = fig13a_model(0.1, 0.99);
    m.walls.clear();
    duffing_rayleigh_forced(&mut m);
    let problem = general(&m);
    assert!(!problem.wall());
    let (impacts, _) = same(&problem, &method(0.01), &spec(4, 3));
    assert_eq!(impacts, 0);
    // each term alone, at λ = 1 (the flat memory) and white noise
    let p = preset("fig13a")
        .unwrap()
        .params
        .with("lambda", 1.0)
        .unwrap()
        .with("tau", 0.0)
        .unwrap();
    let base = {
        let mut m = Model::from(&p);
        m.walls.clear();
        m
    };
    let mut cubic = base.clone();
    cubic.restoring.cubic = 0.5;
    let mut rayleigh = base.clone();
    rayleigh.damping.rayleigh = vec![-0.05];
    let mut forced = base.clone();
    forced.forcing = Some(Harmonic {
        amplitude: 1.0,
        frequency: 0.7,
        phase: -1.0,
    });
    for m in [cubic, rayleigh, forced] {
        same(&general(&m), &method(0.02), &spec(3, 4));
    }
}

#[test]
fn general_paths_with_the_wall_impacts_and_sticking_are_the_engines() {
    let mut m = fig13a_model(0.1, 0.99);
    duffing_rayleigh_forced(&mut m);
    let problem = general(&m);
    assert!(problem.wall());
    let (impacts, _) = same(&problem, &method(0.01), &spec(4, 11));
    assert!(impacts > 50, "impacts {impacts}");
    // strong noise at a small r: sticking; both impact memories
    let mut m = fig13a_model(2.0, 0.3);
    duffing_rayleigh_forced(&mut m);
    let problem = general(&m);
    for memory in [ImpactMemory::Continuous, ImpactMemory::Restart] {
        let method = PredictorCorrector {
            impact_memory: memory,
            ..method(0.02)
        };
        let (impacts, sticking) = same(&problem, &method, &spec(4, 5));
        assert!(
            impacts > 10 && sticking > 0,
            "{memory:?}: impacts {impacts}, sticking {sticking}"
        );
    }
}

/// Stage 2: U·η_m from its own stream, white and OU, uncorrelated and correlated with the
/// additive noise (c = ±0.6: η_m takes side·η_a, a path started below 0 too), with no wall and with the wall (impacts,
/// sticking, both impact memories), alone and with stage 1's terms.
#[test]
fn general_paths_with_multiplicative_noise_are_the_engines() {
    for (tau, c) in [(0.0, 0.0), (0.0, 0.6), (0.5, 0.0), (0.5, -0.6)] {
        let p = preset("fig13a")
            .unwrap()
            .params
            .with("D", 0.3)
            .unwrap()
            .with("tau", tau)
            .unwrap();
        let mut m = Model::from(&p);
        m.noise.multiplicative = Some(NoiseTerm {
            intensity: 0.2,
            correlation_time: tau,
        });
        m.noise.correlation = c;
        let (impacts, _) = same(&general(&m), &method(0.01), &spec(3, 7));
        assert!(impacts > 10, "τ = {tau}, c = {c}: impacts {impacts}");
        let mut off = m.clone();
        off.walls.clear();
        // a start below 0: side = −1, so η_m mixes −η_a
        let below = general(&off)
            .with_starts(&[(-1.0, 0.0), (2.0, 0.0)])
            .unwrap();
        let (impacts, _) = same(&below, &method(0.01), &spec(4, 8));
        assert_eq!(impacts, 0);
    }
    // with stage 1's terms, sticking at a small r, both impact memories
    let mut m = fig13a_model(2.0, 0.3);
    duffing_rayleigh_forced(&mut m);
    m.noise.multiplicative = Some(NoiseTerm {
        intensity: 0.05,
        correlation_time: m.noise.additive.unwrap().correlation_time,
    });
    m.noise.correlation = 0.4;
    let problem = general(&m);
    for memory in [ImpactMemory::Continuous, ImpactMemory::Restart] {
        let method = PredictorCorrector {
            impact_memory: memory,
            ..method(0.02)
        };
        let (impacts, sticking) = same(&problem, &method, &spec(4, 5));
        assert!(
            impacts > 10 && sticking > 0,
            "{memory:?}: impacts {impacts}, sticking {sticking}"
        );
    }
}

fn wall(position: f64, keep: Keep, r: f64) -> Wall {
    Wall {
        position,
        keep,
        restitution: Restitution::Constant(r),
    }
}

/// r(v) = 0.4 + 0.5·e^{−v/0.8}.
fn speed_dependent() -> Restitution {
    Restitution::Speed(SpeedRestitution {
        r0: 0.9,
        r_fast: 0.4,
        speed: 0.8,
    })
}

/// `m` with `walls` (the model's: the paper's barrier off) and `starts`.
fn walled(m: &Model, walls: Vec<Wall>, starts: &[(f64, f64)]) -> Problem {
    let mut m = m.clone();
    m.walls = walls;
    m.start.u0 = starts[0].0;
    m.start.v0 = starts[0].1;
    let problem = Problem::from_model(&m)
        .unwrap()
        .with_starts(starts)
        .unwrap();
    assert!(problem.oscillator().terms().is_some() && !problem.wall());
    problem
}

/// Stage 3: the model's walls — two walls (a constant and a speed-dependent restitution), an
/// offset wall keeping above and one keeping below, with stage 1's and 2's terms, both impact
/// memories; sticking at δ ≠ 0 where k(δ) pushes into the wall.
#[test]
fn general_paths_with_the_models_walls_are_the_engines() {
    let mut m = fig13a_model(0.3, 0.99);
    duffing_rayleigh_forced(&mut m);
    m.noise.multiplicative = Some(NoiseTerm {
        intensity: 0.05,
        correlation_time: m.noise.additive.unwrap().correlation_time,
    });
    m.noise.correlation = 0.3;
    let two = vec![
        wall(-0.6, Keep::Above, 0.7),
        Wall {
            position: 0.9,
            keep: Keep::Below,
            restitution: speed_dependent(),
        },
    ];
    let starts = [(0.2, 0.0), (-0.5, 1.0), (0.85, -0.3)];
    for memory in [ImpactMemory::Continuous, ImpactMemory::Restart] {
        let method = PredictorCorrector {
            impact_memory: memory,
            ..method(0.01)
        };
        let (impacts, _) = same(&walled(&m, two.clone(), &starts), &method, &spec(3, 2));
        assert!(impacts > 50, "{memory:?}: impacts {impacts}");
    }
    // an offset wall keeping above, one keeping below (speed-dependent), without η_m
    let mut plain = fig13a_model(0.3, 0.99);
    duffing_rayleigh_forced(&mut plain);
    let above = walled(
        &plain,
        vec![wall(0.5, Keep::Above, 0.8)],
        &[(1.0, 0.0), (3.0, 1.0)],
    );
    let (impacts, _) = same(&above, &method(0.01), &spec(3, 4));
    assert!(impacts > 10, "above: impacts {impacts}");
    let below = Wall {
        position: 2.0,
        keep: Keep::Below,
        restitution: speed_dependent(),
    };
    let below = walled(&plain, vec![below], &[(1.0, 0.0), (-3.0, 1.0)]);
    let (impacts, _) = same(&below, &method(0.01), &spec(3, 5));
    assert!(impacts > 10, "below: impacts {impacts}");
    // sticking at δ = 0.5: k(δ) > 0 pushes into the lower wall, strong noise pulls away;
    let mut sticky = fig13a_model(1.0, 0.3);
    sticky.restoring.cubic = 0.5;
    sticky.noise.multiplicative = Some(NoiseTerm {
        intensity: 0.1,
        correlation_time: sticky.noise.additive.unwrap().correlation_time,
    });
    // and its mirror at an upper wall at δ = −0.5
    let lower = walled(&sticky, vec![wall(0.5, Keep::Above, 0.3)], &[(1.0, 0.0)]);
    let upper = walled(&sticky, vec![wall(-0.5, Keep::Below, 0.3)], &[(-1.0, 0.0)]);
    for memory in [ImpactMemory::Continuous, ImpactMemory::Restart] {
        let method = PredictorCorrector {
            impact_memory: memory,
            ..method(0.02)
        };
        for problem in [&lower, &upper] {
            let (impacts, sticking) = same(problem, &method, &spec(3, 6));
            assert!(
                impacts > 10 && sticking > 0,
                "{memory:?}: impacts {impacts}, sticking {sticking}"
            );
        }
    }
}

/// A step that meets both walls is the engine's refusal of Δt, with the same message.
#[test]
fn a_step_that_meets_both_walls_is_refused_as_the_engine_refuses_it() {
    let m = fig13a_model(3.0, 0.99);
    let problem = walled(
        &m,
        vec![wall(-0.02, Keep::Above, 1.0), wall(0.02, Keep::Below, 1.0)],
        &[(0.0, 0.0)],
    );
    let (m, s) = (method(0.05), spec(3, 1));
    let engine = run_ensemble(&problem, &m, &s, &Silent).unwrap_err();
    let emulated = emulate_ensemble(&problem, &m, &s).unwrap_err();
    assert!(engine.to_string().contains("both walls"), "{engine}");
    assert_eq!(engine.to_string(), emulated.to_string());
}

fn fractional(terms: &[(f64, f64)]) -> Vec<Fractional> {
    terms
        .iter()
        .map(|&(coefficient, order)| Fractional { coefficient, order })
        .collect()
}

/// Stage 4: fractional terms K_j D^{α_j}U (a memory of V each; α = 1 local) with no wall, the
/// wall at 0 and the model's walls, both impact memories, with sticking, with the other terms;
/// at λ = 1 (the flat leading memory) and with a longer window and a finer SOE tolerance.
#[test]
fn general_paths_with_fractional_terms_are_the_engines() {
    // no wall: two terms (α = 0.5 and α = 1), Duffing, forcing, η_m
    let mut m = fig13a_model(0.3, 0.99);
    m.walls.clear();
    duffing_rayleigh_forced(&mut m);
    m.fractional = fractional(&[(0.3, 0.5), (0.2, 1.0)]);
    m.noise.multiplicative = Some(NoiseTerm {
        intensity: 0.05,
        correlation_time: m.noise.additive.unwrap().correlation_time,
    });
    let (impacts, _) = same(&general(&m), &method(0.01), &spec(3, 3));
    assert_eq!(impacts, 0);
    // the wall at 0: impacts, and sticking at a small r; both impact memories
    let mut m = fig13a_model(0.1, 0.99);
    m.fractional = fractional(&[(0.3, 0.6)]);
    let (impacts, _) = same(&general(&m), &method(0.01), &spec(3, 11));
    assert!(impacts > 50, "impacts {impacts}");
    let mut m = fig13a_model(2.0, 0.3);
    duffing_rayleigh_forced(&mut m);
    m.fractional = fractional(&[(0.2, 0.4), (0.1, 1.0)]);
    for memory in [ImpactMemory::Continuous, ImpactMemory::Restart] {
        let method = PredictorCorrector {
            impact_memory: memory,
            ..method(0.02)
        };
        let (impacts, sticking) = same(&general(&m), &method, &spec(3, 5));
        assert!(
            impacts > 10 && sticking > 0,
            "{memory:?}: impacts {impacts}, sticking {sticking}"
        );
    }
    // the model's walls: two walls, and sticking at δ = 0.5; both impact memories
    let mut m = fig13a_model(0.3, 0.99);
    m.fractional = fractional(&[(0.2, 0.4), (0.1, 1.0)]);
    m.noise.multiplicative = Some(NoiseTerm {
        intensity: 0.05,
        correlation_time: m.noise.additive.unwrap().correlation_time,
    });
    let two = vec![
        wall(-0.6, Keep::Above, 0.7),
        Wall {
            position: 0.9,
            keep: Keep::Below,
            restitution: speed_dependent(),
        },
    ];
    let two = walled(&m, two, &[(0.2, 0.0), (-0.5, 1.0), (0.85, -0.3)]);
    let mut sticky = fig13a_model(1.0, 0.3);
    sticky.restoring.cubic = 0.5;
    sticky.fractional = fractional(&[(0.3, 0.7)]);
    let sticky = walled(&sticky, vec![wall(0.5, Keep::Above, 0.3)], &[(1.0, 0.0)]);
    for memory in [ImpactMemory::Continuous, ImpactMemory::Restart] {
        let method = PredictorCorrector {
            impact_memory: memory,
            ..method(0.01)
        };
        let (impacts, _) = same(&two, &method, &spec(3, 2));
        assert!(impacts > 50, "{memory:?}: impacts {impacts}");
        let (impacts, sticking) = same(&sticky, &method, &spec(3, 6));
        assert!(
            impacts > 10 && sticking > 0,
            "{memory:?}: impacts {impacts}, sticking {sticking}"
        );
    }
    // λ = 1 (the leading memory flat, the fractional one not); a window of 24 at 1e-9
    let p = preset("fig13a")
        .unwrap()
        .params
        .with("lambda", 1.0)
        .unwrap();
    let mut m = Model::from(&p);
    m.fractional = fractional(&[(0.4, 0.3)]);
    let (impacts, _) = same(&general(&m), &method(0.01), &spec(3, 4));
    assert!(impacts > 10, "λ = 1: impacts {impacts}");
    let window = PredictorCorrector {
        memory: Memory::SumOfExponentials { tolerance: 1e-9 },
        window: 24,
        ..method(0.02)
    };
    let mut m = fig13a_model(0.3, 0.99);
    m.fractional = fractional(&[(0.3, 0.5)]);
    let (impacts, _) = same(&general(&m), &window, &spec(3, 9));
    assert!(impacts > 10, "window 24: impacts {impacts}");
}

#[test]
fn a_general_blow_up_is_reported_as_the_engine_reports_it() {
    // negative Rayleigh damping pumps the amplitude past the bound
    let mut m = fig13a_model(0.5, 0.99);
    m.walls.clear();
    m.damping.rayleigh = vec![0.5];
    let problem = general(&m).with_blow_up(20.0).unwrap();
    let (m, s) = (method(0.01), spec(3, 1));
    let engine = run_ensemble(&problem, &m, &s, &Silent).unwrap_err();
    let emulated = emulate_ensemble(&problem, &m, &s).unwrap_err();
    assert!(matches!(engine, Error::InPath { .. }), "{engine}");
    assert_eq!(engine.to_string(), emulated.to_string());
}

#[test]
fn what_the_kernel_does_not_hold_is_refused_by_name() {
    let s = spec(2, 1);
    let direct = PredictorCorrector {
        memory: Memory::Direct,
        ..method(0.01)
    };
    let e = emulate_ensemble(&fig13a(0.1), &direct, &s).unwrap_err();
    assert!(e.to_string().contains("memory"), "{e}");
    // a window beyond the plan's size
    let wide = PredictorCorrector {
        window: 100,
        ..method(0.01)
    };
    let e = emulate_ensemble(&fig13a(0.1), &wide, &s).unwrap_err();
    assert!(e.to_string().contains("window"), "{e}");
    // bad input is the engine's error, before any work
    let bad = EnsembleSpec { bins: 0, ..s };
    let e = emulate_ensemble(&fig13a(0.1), &method(0.01), &bad).unwrap_err();
    assert!(e.to_string().contains("bins"), "{e}");
}
