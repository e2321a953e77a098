//! The lane stepper gives the scalar stepper's bits: every path stepped in lanes of 4 or 8 (in
//! any position, with any neighbours, in groups of any split) follows, step by step, exactly
//! the U, V, events and counters that [`Stepper::step`] gives it alone — over random
//! parameters with impacts, sticking, stiff steps (second pass), white, coloured and no noise,
//! λ < 1 and λ = 1, both impact memories, the direct and the SOE memory, the three systems.
//! The ensemble's statistics are identical for every lane count.

use proptest::prelude::*;
use trirhythm::analysis::ensemble::{run_ensemble, EnsembleSpec};
use trirhythm::engine::*;
use trirhythm::model::{preset, Damping, Params};
use trirhythm::monitor::Silent;
use trirhythm::{Error, Result};

/// Everything a step shows of a path, as bits.
fn snapshot(s: &Stepper) -> [u64; 8] {
    let e = s.events();
    let i = e.impact.map_or([0; 3], |i| {
        [i.time.to_bits(), i.v_minus.to_bits(), i.v_plus.to_bits()]
    });
    [
        s.u().to_bits(),
        s.v().to_bits(),
        s.eta().to_bits(),
        i[0] ^ (e.stuck as u64),
        i[1],
        i[2],
        s.impacts() * 1_000_003 + s.sticking_steps(),
        s.steps(),
    ]
}

/// Records every snapshot of a path.
#[derive(Default)]
struct Log(Vec<[u64; 8]>);

impl Observer for Log {
    fn observe(&mut self, s: &Stepper) -> Flow {
        self.0.push(snapshot(s));
        Flow::Continue
    }
}

#[derive(Debug, Clone)]
struct Case {
    lambda: f64,
    mu0: f64,
    r: f64,
    d: f64,
    tau: f64,
    system: u8,
    wall: bool,
    restart: bool,
    direct: bool,
    dt: f64,
    starts: Vec<(f64, f64)>,
}

fn problem(c: &Case) -> (Problem, PredictorCorrector) {
    let p = preset("fig13a")
        .unwrap()
        .params
        .with("lambda", c.lambda)
        .and_then(|p| p.with("mu0", c.mu0))
        .and_then(|p| p.with("r", c.r))
        .and_then(|p| p.with("D", c.d))
        .and_then(|p| p.with("tau", c.tau))
        .unwrap();
    let system = [System::Fractional, System::Equivalent, System::Zhuravlev][c.system as usize];
    let barrier = if c.wall && system != System::Zhuravlev {
        Barrier::On
    } else {
        Barrier::Off
    };
    let problem = Problem::from_params(&p)
        .and_then(|q| q.with_system(system))
        .and_then(|q| q.with_barrier(barrier))
        .and_then(|q| q.with_starts(&c.starts))
        .unwrap();
    let method = PredictorCorrector {
        dt: c.dt,
        memory: if c.direct {
            Memory::Direct
        } else {
            Memory::default()
        },
        impact_memory: if c.restart {
            ImpactMemory::Restart
        } else {
            ImpactMemory::Continuous
        },
        ..Default::default()
    };
    (problem, method)
}

/// Paths `ids` of seed 5 run for `steps`: alone by `run`, and by `run_lanes` with `lanes`.
fn logs(c: &Case, ids: &[u64], steps: u64, lanes: Lanes) -> Vec<(Result<u64>, Vec<[u64; 8]>)> {
    let (problem, method) = problem(c);
    let horizon = steps as f64 * method.dt;
    let mut paths: Vec<Stepper> = ids
        .iter()
        .map(|&i| Stepper::new(&problem, &method, (5, i), horizon).unwrap())
        .collect();
    let mut obs: Vec<Log> = ids.iter().map(|_| Log::default()).collect();
    let taken = run_lanes(&mut paths, steps, &mut obs, lanes, &Silent).unwrap();
    taken
        .into_iter()
        .zip(obs.into_iter().map(|l| l.0))
        .collect()
}

fn same(a: &(Result<u64>, Vec<[u64; 8]>), b: &(Result<u64>, Vec<[u64; 8]>)) -> bool {
    let ok = match (&a.0, &b.0) {
        (Ok(x), Ok(y)) => x == y,
        (Err(x), Err(y)) => x.to_string() == y.to_string(),
        _ => false,
    };
    ok && a.1 == b.1
}

fn case_strategy() -> impl Strategy<Value = Case> {
    (
        (
            prop_oneof![Just(1.0), 0.6f64..1.0],
            prop_oneof![0.001f64..0.05, 0.05f64..0.8],
            0.3f64..1.0,
            prop_oneof![Just(0.0), 0.01f64..0.6],
            prop_oneof![Just(0.0), 0.05f64..1.0],
        ),
        (
            0u8..3,
            proptest::bool::weighted(0.8),
            proptest::bool::ANY,
            proptest::bool::weighted(0.15),
            prop_oneof![Just(0.01), 0.005f64..0.05],
            proptest::collection::vec((0.0f64..12.0, -3.0f64..3.0), 1..4),
        ),
    )
        .prop_map(
            |((lambda, mu0, r, d, tau), (system, wall, restart, direct, dt, starts))| Case {
                lambda,
                mu0,
                r,
                d,
                tau,
                system,
                wall,
                restart,
                direct,
                dt,
                starts,
            },
        )
}

/// Paths of the cases `cases` (path k: the first start of case k, its own Δt, memory, system
/// and parameters; noise stream k of seed 5) run for `steps`: by `run_lanes` with `lanes`.
fn mixed_logs(cases: &[Case], steps: u64, lanes: Lanes) -> Vec<(Result<u64>, Vec<[u64; 8]>)> {
    let mut paths: Vec<Stepper> = cases
        .iter()
        .enumerate()
        .map(|(k, c)| {
            let (problem, method) = problem(c);
            let horizon = steps as f64 * method.dt;
            Stepper::new(&problem, &method, (5, k as u64), horizon).unwrap()
        })
        .collect();
    let mut obs: Vec<Log> = cases.iter().map(|_| Log::default()).collect();
    let taken = run_lanes(&mut paths, steps, &mut obs, lanes, &Silent).unwrap();
    taken
        .into_iter()
        .zip(obs.into_iter().map(|l| l.0))
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(40))]

    /// Paths of different problems in one group (each lane its own polynomial, ω², Δt and
    /// weights; their own memories, systems and walls) give the scalar stepper's bits.
    #[test]
    fn lanes_of_different_problems_give_the_scalar_bits(
        cases in proptest::collection::vec(case_strategy(), 1..12)
    ) {
        let steps = if cases.iter().any(|c| c.direct) { 300 } else { 1500 };
        let scalar = mixed_logs(&cases, steps, Lanes::Width(1));
        for lanes in [4, 8] {
            let lane = mixed_logs(&cases, steps, Lanes::Width(lanes));
            for (k, (a, b)) in scalar.iter().zip(&lane).enumerate() {
                prop_assert!(same(a, b), "path {k} in lanes of {lanes} differs ({:?})", cases[k]);
            }
        }
    }

    #[test]
    fn lanes_give_the_scalar_bits(c in case_strategy(), first in 0u64..50, n in 1usize..12) {
        let ids: Vec<u64> = (first..first + n as u64).collect();
        let steps = if c.direct { 300 } else { 1500 };
        let scalar = logs(&c, &ids, steps, Lanes::Width(1));
        for lanes in [4, 8] {
            let lane = logs(&c, &ids, steps, Lanes::Width(lanes));
            for (k, (a, b)) in scalar.iter().zip(&lane).enumerate() {
                prop_assert!(same(a, b), "path {} in lanes of {lanes} differs from the scalar stepper ({:?})", ids[k], c);
            }
        }
        // another position and other neighbours: the paths reversed, in lanes of 4
        let rev: Vec<u64> = ids.iter().rev().copied().collect();
        let lane = logs(&c, &rev, steps, Lanes::Width(4));
        for (k, b) in lane.iter().enumerate() {
            prop_assert!(same(&scalar[n - 1 - k], b), "path {} reversed", rev[k]);
        }
    }
}

/// A group whose polynomials μP are of different forms (degree ≤ 7 in U² and beyond: no
/// common lane step) is stepped path by path, with the same bits; one of equal forms but
/// different coefficients takes the lanes.
#[test]
fn lanes_of_polynomials_of_different_forms() {
    let base = preset("fig13a").unwrap().params.with("D", 0.2).unwrap();
    let mut long = base.clone();
    long.damping = Damping {
        coefficients: vec![1.0, -0.5, 0.02, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, -1e-12],
    };
    let method = PredictorCorrector::default();
    let problems: Vec<Problem> = [&base, &long, &base.with("mu0", 0.3).unwrap(), &long]
        .into_iter()
        .map(|p| {
            Problem::from_params(p)
                .unwrap()
                .with_start(2.0, 0.5)
                .unwrap()
        })
        .collect();
    let run = |lanes| {
        let mut paths: Vec<Stepper> = problems
            .iter()
            .enumerate()
            .map(|(k, q)| Stepper::new(q, &method, (2, k as u64), 30.0).unwrap())
            .collect();
        let mut obs: Vec<Log> = problems.iter().map(|_| Log::default()).collect();
        let taken = run_lanes(&mut paths, 3000, &mut obs, lanes, &Silent).unwrap();
        let impacts: u64 = paths.iter().map(|p| p.impacts()).sum();
        (
            taken.into_iter().map(|t| t.ok()).collect::<Vec<_>>(),
            obs.into_iter().map(|o| o.0).collect::<Vec<_>>(),
            impacts,
        )
    };
    let one = run(Lanes::Width(1));
    assert!(one.2 > 10, "impacts {}", one.2);
    for lanes in [4, 8] {
        assert!(run(Lanes::Width(lanes)) == one, "lanes {lanes}");
    }
}

/// Cases with every event: a frozen force pressing the oscillator against the wall (impacts
/// that shrink into sticking: OU noise with τ ≫ T) and a stiff damping (second passes), checked
/// to have them, so that the property above covers them.
#[test]
fn the_lanes_meet_impacts_sticking_and_stiff_steps() {
    for (lambda, restart) in [(0.9, false), (1.0, false), (0.95, true)] {
        let p = Params {
            mu0: 1.0,
            omega0: 3.0,
            lambda,
            restitution: 0.5,
            damping: Damping {
                coefficients: vec![-0.3, 0.0, 0.01],
            },
            noise_intensity: 1e6,
            correlation_time: 1e6,
        };
        let starts = [(1.0, 0.0), (0.2, -1.0), (13.0, 0.0)];
        let problem = Problem::from_params(&p)
            .and_then(|q| q.with_starts(&starts))
            .unwrap();
        let method = PredictorCorrector {
            impact_memory: if restart {
                ImpactMemory::Restart
            } else {
                ImpactMemory::Continuous
            },
            ..Default::default()
        };
        let run = |lanes| {
            let mut paths: Vec<Stepper> = (0..9)
                .map(|i| Stepper::new(&problem, &method, (3, i), 20.0).unwrap())
                .collect();
            let mut obs: Vec<Log> = (0..9).map(|_| Log::default()).collect();
            let taken = run_lanes(&mut paths, 2000, &mut obs, lanes, &Silent).unwrap();
            (taken, obs, paths)
        };
        let (t1, o1, p1) = run(Lanes::Width(1));
        let impacts: u64 = p1.iter().map(|s| s.impacts()).sum();
        let stuck: u64 = p1.iter().map(|s| s.sticking_steps()).sum();
        assert!(
            impacts > 20 && stuck > 100,
            "impacts {impacts}, sticking steps {stuck}"
        );
        for lanes in [4, 8] {
            let (t, o, _) = run(Lanes::Width(lanes));
            for k in 0..9 {
                assert_eq!(t[k].as_ref().ok(), t1[k].as_ref().ok());
                assert!(o[k].0 == o1[k].0, "λ = {lambda}: path {k}, lanes {lanes}");
            }
        }
    }
}

/// A path that blows up in a lane fails as it fails alone; its neighbours go on unchanged.
#[test]
fn a_failing_lane_leaves_its_neighbours_alone() {
    let c = Case {
        lambda: 1.0,
        mu0: 0.01,
        r: 0.9,
        d: 0.3,
        tau: 0.0,
        system: 0,
        wall: true,
        restart: false,
        direct: false,
        dt: 0.01,
        starts: vec![(5.0, 0.0)],
    };
    let (problem, method) = problem(&c);
    let small = problem
        .clone()
        .with_start(0.9, 0.0)
        .and_then(|q| q.with_blow_up(1.0))
        .unwrap();
    let mut paths: Vec<Stepper> = (0..4)
        .map(|i| {
            let p = if i == 2 { &small } else { &problem };
            Stepper::new(p, &method, (5, i), 100.0).unwrap()
        })
        .collect();
    // the blow-up bound is the problem's, not the equation's: the lanes accept both
    let mut obs: Vec<Log> = (0..4).map(|_| Log::default()).collect();
    let taken = run_lanes(&mut paths, 10_000, &mut obs, Lanes::Width(4), &Silent).unwrap();
    let alone = logs(&c, &[0, 1, 3], 10_000, Lanes::Width(1));
    assert!(
        matches!(taken[2], Err(Error::BlowUp { .. })),
        "{:?}",
        taken[2]
    );
    for (k, i) in [0usize, 1, 3].into_iter().enumerate() {
        assert_eq!(taken[i].as_ref().ok(), Some(&10_000));
        assert!(obs[i].0 == alone[k].1, "path {i}");
    }
}

#[test]
fn lane_counts_are_checked() {
    assert!(Lanes::Width(3).width().is_err());
    assert!(Lanes::Width(0).width().is_err());
    for w in LANE_WIDTHS {
        assert_eq!(Lanes::Width(w).width().unwrap(), w);
    }
    assert!([4, 8].contains(&Lanes::Auto.width().unwrap()));
    assert_eq!(Lanes::Auto.width().unwrap(), detected_lanes());
}

/// The fig13a ensemble (8 paths, impacts every few hundred steps) gives the same statistics
/// for every lane count.
#[test]
fn the_ensemble_is_the_same_for_every_lane_count() {
    let p = preset("fig13a").unwrap().params;
    let problem = Problem::from_params(&p)
        .and_then(|q| q.with_starts(&[(4.0, 0.0), (8.0, 0.0), (12.0, 0.0)]))
        .unwrap();
    let run = |lanes| {
        let spec = EnsembleSpec {
            paths: 11,
            burn_in: 5.0,
            length: 60.0,
            bins: 20,
            joint_bins: 8,
            batches: 4,
            lanes,
            ..Default::default()
        };
        run_ensemble(&problem, &PredictorCorrector::default(), &spec, &Silent).unwrap()
    };
    let one = run(Lanes::Width(1));
    assert!(one.paths == 11);
    for lanes in [Lanes::Width(4), Lanes::Width(8), Lanes::Auto] {
        assert!(run(lanes) == one, "{lanes:?}");
    }
}

/// Lyapunov realisations in lanes — two trajectories (reference and copy side by side, several
/// realisations a group) and the tangent method (each path with its tangent in a lane) — give
/// the exponents, the running estimates and the counts of the scalar stepper, bit for bit,
/// with impacts (the wall) and without.
#[test]
fn lyapunov_realisations_are_the_same_for_every_lane_count() {
    use trirhythm::analysis::lyapunov::{largest_lyapunov, LyapunovMethod, LyapunovSpec};
    for (preset_name, barrier) in [("fig13a", Barrier::On), ("fig1", Barrier::Off)] {
        let p = preset(preset_name).unwrap().params.with("D", 0.05).unwrap();
        let problem = Problem::from_params(&p)
            .and_then(|q| q.with_barrier(barrier))
            .and_then(|q| q.with_starts(&[(3.0, 0.0), (7.0, 0.0)]))
            .unwrap();
        for method in [LyapunovMethod::TwoTrajectory, LyapunovMethod::Tangent] {
            let run = |lanes| {
                let spec = LyapunovSpec {
                    paths: 7,
                    seed: 3,
                    transient: 5.0,
                    length: 60.0,
                    renormalise_every: 37,
                    running_points: 10,
                    method,
                    lanes,
                    ..Default::default()
                };
                largest_lyapunov(&problem, &PredictorCorrector::default(), &spec, &Silent).unwrap()
            };
            let one = run(Lanes::Width(1));
            assert!(one.lle.value.is_finite(), "{preset_name} {method:?}");
            for lanes in [Lanes::Width(4), Lanes::Width(8), Lanes::Auto] {
                let r = run(lanes);
                assert!(
                    format!("{r:?}") == format!("{one:?}"),
                    "{preset_name} {method:?} {lanes:?}"
                );
            }
        }
    }
}

/// `run_lanes` refuses a missing observer and a bad lane count (naming the argument), and
/// takes no paths as no work.
#[test]
fn run_lanes_checks_its_arguments() {
    let p = preset("fig13a").unwrap().params;
    let method = PredictorCorrector::default();
    let a = Problem::from_params(&p).unwrap();
    let stepper = |q: &Problem, i| Stepper::new(q, &method, (1, i), 1.0).unwrap();
    let message = |r: Result<Vec<Result<u64>>>| r.unwrap_err().to_string();
    let two: Vec<Log> = vec![Log::default(), Log::default()];
    let mut two = two;
    let mut same = vec![stepper(&a, 0), stepper(&a, 1)];
    let mut one: Vec<Log> = vec![Log::default()];
    let e = message(run_lanes(&mut same, 10, &mut one, Lanes::Width(4), &Silent));
    assert!(e.contains("observers"), "{e}");
    let e = message(run_lanes(&mut same, 10, &mut two, Lanes::Width(2), &Silent));
    assert!(e.contains("lanes") && e.contains("1, 4 or 8"), "{e}");
    let mut none: Vec<Stepper> = vec![];
    let mut no_obs: Vec<Log> = vec![];
    assert!(run_lanes(&mut none, 10, &mut no_obs, Lanes::Auto, &Silent)
        .unwrap()
        .is_empty());
    // an observer that stops its path early: the others go on, the counts are the steps taken
    let mut paths = vec![stepper(&a, 0), stepper(&a, 1), stepper(&a, 2)];
    let mut stops: Vec<_> = [3u64, 100, 0]
        .iter()
        .map(|&at| {
            move |s: &Stepper| {
                if s.steps() >= at {
                    Flow::Stop
                } else {
                    Flow::Continue
                }
            }
        })
        .collect();
    let taken = run_lanes(&mut paths, 50, &mut stops, Lanes::Width(8), &Silent).unwrap();
    let taken: Vec<u64> = taken.into_iter().map(|t| t.unwrap()).collect();
    assert_eq!(taken, vec![3, 50, 0]);
    assert_eq!(
        paths.iter().map(|p| p.steps()).collect::<Vec<_>>(),
        vec![3, 50, 0]
    );
}

/// `simulate_ensemble` (paths in lanes) gives every path's trajectory exactly as `simulate`
/// gives it alone.
#[test]
fn simulate_ensemble_in_lanes_equals_the_paths_alone() {
    let p = preset("fig13a").unwrap().params.with("D", 0.3).unwrap();
    let problem = Problem::from_params(&p)
        .and_then(|q| q.with_starts(&[(3.0, 0.0), (9.0, -1.0)]))
        .unwrap();
    let method = PredictorCorrector::default();
    let options = Options {
        t_end: 40.0,
        seed: 9,
        record_every: 7,
        record_impacts: true,
        ..Default::default()
    };
    let all = simulate_ensemble(&problem, &method, &options, 11).unwrap();
    assert_eq!(all.len(), 11);
    assert!(all.iter().map(|t| t.impacts).sum::<usize>() > 0);
    for (i, t) in all.iter().enumerate() {
        let alone = simulate(
            &problem,
            &method,
            &Options {
                path: i as u64,
                ..options.clone()
            },
        )
        .unwrap();
        assert!(*t == alone, "path {i}");
    }
}
