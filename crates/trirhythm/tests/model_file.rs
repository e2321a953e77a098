//! The model description and its file: presets → file → model bit for bit, the round trip,
//! malformed files refused with the dotted field named, terms the engine does not step refused
//! by name, and `Problem::from_params(p)` against `Problem::from_model(file of p)`: the same
//! paths, bit for bit.

use trirhythm::engine::{
    simulate, Barrier, ImpactMemory, Options, PredictorCorrector, Problem, Trajectory,
};
use trirhythm::model::{
    presets, Fractional, Harmonic, Keep, Model, NoiseTerm, Restitution, SpeedRestitution, Wall,
};
use trirhythm::Error;

include!("data/malformed_models.rs");

/// A model using every term of the class.
fn every_term() -> Model {
    let mut m = Model::from_toml_str(BASE).unwrap();
    m.leading.lambda = 0.75;
    m.damping.rayleigh = vec![-0.25, 1e-3];
    m.restoring.cubic = 0.5;
    m.restoring.quintic = -1.5e-7;
    m.fractional = vec![
        Fractional {
            coefficient: 0.1,
            order: 0.5,
        },
        Fractional {
            coefficient: 0.3,
            order: 1.0,
        },
    ];
    m.walls = vec![
        Wall {
            position: -1.25,
            keep: Keep::Above,
            restitution: Restitution::Constant(0.8),
        },
        Wall {
            position: 2.0,
            keep: Keep::Below,
            restitution: Restitution::Speed(SpeedRestitution {
                r0: 0.95,
                r_fast: 0.6,
                speed: 0.3,
            }),
        },
    ];
    m.forcing = Some(Harmonic {
        amplitude: 0.2,
        frequency: 1.1,
        phase: 0.1,
    });
    m.noise.multiplicative = Some(NoiseTerm {
        intensity: 0.01,
        correlation_time: 0.5,
    });
    m.noise.correlation = -0.3;
    m.start.u0 = 0.3;
    m.start.v0 = -0.7;
    m.validate().unwrap();
    m
}

#[test]
fn every_preset_is_a_model_file_and_back_bit_for_bit() {
    for preset in presets() {
        let model = Model::from(&preset.params);
        assert_eq!(
            model.paper_params().as_ref(),
            Some(&preset.params),
            "{}",
            preset.name
        );
        let text = model.to_toml();
        let back = Model::from_toml_str(&text).unwrap_or_else(|e| panic!("{}: {e}", preset.name));
        assert_eq!(back, model, "{}:\n{text}", preset.name);
        assert_eq!(back.to_toml(), text, "{}", preset.name);
    }
}

#[test]
fn a_model_with_every_term_round_trips() {
    let m = every_term();
    let back = Model::from_toml_str(&m.to_toml()).unwrap();
    assert_eq!(back, m, "{}", m.to_toml());
    for (i, &d) in back.damping.rayleigh.iter().enumerate() {
        assert_eq!(d.to_bits(), m.damping.rayleigh[i].to_bits());
    }
}

#[test]
fn the_base_file_reads_with_defaults() {
    let m = Model::from_toml_str(BASE).unwrap();
    assert_eq!(
        m.paper_params(),
        Some(trirhythm::model::preset("fig13a").unwrap().params)
    );
    // the least file: defaults for P(U), the terms absent, the start (1, 0)
    let least = "format = 1\nleading = { lambda = 1.0 }\ndamping = { mu0 = 0.1 }\nrestoring = { omega0 = 1.0 }\n";
    let m = Model::from_toml_str(least).unwrap();
    assert_eq!(
        m.damping.coefficients,
        trirhythm::model::terms::paper_coefficients()
    );
    assert!(m.walls.is_empty() && m.noise.additive.is_none() && m.forcing.is_none());
    assert_eq!((m.start.u0, m.start.v0), (1.0, 0.0));
    let p = Problem::from_model(&m).unwrap();
    assert_eq!(p.barrier(), Barrier::Off);
    assert_eq!(p.params().noise_intensity, 0.0);
}

#[test]
fn malformed_files_are_refused_with_the_field_named() {
    assert!(MALFORMED.len() >= 20);
    for (i, (field, _, _)) in MALFORMED.iter().enumerate() {
        let text = malformed(i);
        let e = Model::from_toml_str(&text).expect_err(&format!("case {i} ({field}) accepted"));
        let named = match &e {
            Error::InvalidParameter { name, .. } => name.clone(),
            Error::Malformed { field, .. } => field.clone(),
            other => panic!("case {i}: {other}"),
        };
        assert_eq!(&named, field, "case {i}: {e}");
        assert!(e.to_string().contains(field), "case {i}: {e}");
    }
}

#[test]
fn every_term_of_the_class_is_stepped() {
    let base = Model::from_toml_str(BASE).unwrap();
    // multiplicative noise at a wall off 0 (δ·η_m in g at the wall)
    let mut m = base.clone();
    m.walls[0].position = -0.5;
    m.noise.multiplicative = Some(NoiseTerm {
        intensity: 0.1,
        correlation_time: 0.0,
    });
    m.validate().unwrap();
    assert!(Problem::from_model(&m)
        .unwrap()
        .oscillator()
        .terms()
        .is_some());
    assert_eq!(m.paper_params(), None);
    // the General kernel's terms (Duffing, Rayleigh, forcing) are stepped, with the wall at 0
    // and without it
    type General = Box<dyn Fn(&mut Model)>;
    let general: Vec<(&str, General)> = vec![
        (
            "rayleigh",
            Box::new(|m| m.damping.rayleigh = vec![0.0, 0.1]),
        ),
        ("cubic", Box::new(|m| m.restoring.cubic = 0.5)),
        ("quintic", Box::new(|m| m.restoring.quintic = 0.5)),
        (
            "forcing",
            Box::new(|m| {
                m.forcing = Some(Harmonic {
                    amplitude: 0.1,
                    frequency: 1.0,
                    phase: 0.0,
                })
            }),
        ),
        (
            "fractional",
            Box::new(|m| {
                m.fractional = vec![Fractional {
                    coefficient: 0.1,
                    order: 0.5,
                }]
            }),
        ),
        (
            "multiplicative",
            Box::new(|m| {
                m.noise.multiplicative = Some(NoiseTerm {
                    intensity: 0.1,
                    correlation_time: 0.0,
                })
            }),
        ),
    ];
    for (name, change) in general {
        for wall in [true, false] {
            let mut m = base.clone();
            change(&mut m);
            if !wall {
                m.walls.clear();
            }
            let p = Problem::from_model(&m).unwrap_or_else(|e| panic!("{name}: {e}"));
            assert!(p.oscillator().terms().is_some(), "{name}");
            assert_eq!(p.wall(), wall, "{name}");
            assert_eq!(m.paper_params(), None, "{name}");
        }
    }
    // walls other than the paper's (off 0, keeping below, two, speed-dependent r) are the
    // General kernel's: stepped, the paper's barrier off
    let walls: Vec<(&str, General)> = vec![
        ("wall.0.position", Box::new(|m| m.walls[0].position = -0.5)),
        (
            "wall.0.keep",
            Box::new(|m| {
                m.walls[0].keep = Keep::Below;
                m.start.u0 = -1.0;
            }),
        ),
        (
            "wall.0.restitution",
            Box::new(|m| {
                m.walls[0].restitution = Restitution::Speed(SpeedRestitution {
                    r0: 0.9,
                    r_fast: 0.5,
                    speed: 1.0,
                })
            }),
        ),
        (
            "two walls",
            Box::new(|m| {
                m.walls.push(Wall {
                    position: 3.0,
                    keep: Keep::Below,
                    restitution: Restitution::Constant(0.9),
                })
            }),
        ),
    ];
    for (name, change) in walls {
        let mut m = base.clone();
        change(&mut m);
        let p = Problem::from_model(&m).unwrap_or_else(|e| panic!("{name}: {e}"));
        let terms = p.oscillator().terms().expect("the General kernel");
        assert_eq!(terms.walls, m.walls, "{name}");
        assert!(!p.wall(), "{name}");
        assert_eq!(m.paper_params(), None, "{name}");
    }
    // fractional terms are stepped with the model's walls too
    let mut fractional = base.clone();
    fractional.walls[0].position = -0.5;
    fractional.fractional = vec![Fractional {
        coefficient: 0.1,
        order: 0.5,
    }];
    let p = Problem::from_model(&fractional).unwrap();
    assert_eq!(p.oscillator().terms().unwrap().fractional.len(), 1);
    assert_eq!(p.oscillator().terms().unwrap().walls, fractional.walls);
    assert_eq!(fractional.paper_params(), None);
    // present with a zero coefficient is absent: the same problem
    let mut zero = base.clone();
    zero.damping.rayleigh = vec![0.0];
    zero.restoring.cubic = 0.0;
    zero.fractional = vec![Fractional {
        coefficient: 0.0,
        order: 0.5,
    }];
    assert_eq!(
        Problem::from_model(&zero).unwrap(),
        Problem::from_model(&base).unwrap()
    );
}

fn bits(t: &Trajectory) -> Vec<u64> {
    t.t.iter()
        .chain(&t.u)
        .chain(&t.v)
        .chain(&t.eta)
        .map(|x| x.to_bits())
        .collect()
}

/// `Problem::from_params(p)` and `Problem::from_model(file of p)` step the same paths, bit for
/// bit: with the wall and OU noise (Fig. 13(a)), white noise, and without the wall.
#[test]
fn the_model_file_steps_the_same_bits_as_the_preset() {
    let method = PredictorCorrector {
        dt: 0.01,
        ..Default::default()
    };
    let options = Options {
        t_end: 50.0,
        seed: 7,
        record_impacts: true,
        ..Default::default()
    };
    for (name, tau, barrier) in [
        ("fig13a", None, Barrier::On),
        ("fig17a", Some(0.0), Barrier::On),
        ("fig13b", None, Barrier::Off),
    ] {
        let mut p = trirhythm::model::preset(name).unwrap().params;
        if let Some(tau) = tau {
            p.correlation_time = tau;
        }
        let mut model = Model::from(&p);
        if barrier == Barrier::Off {
            model.walls.clear();
        }
        model.start.u0 = 1.5;
        let file = model.to_toml();
        let from_file = Problem::from_model(&Model::from_toml_str(&file).unwrap()).unwrap();
        let direct = Problem::from_params(&p)
            .unwrap()
            .with_barrier(barrier)
            .unwrap()
            .with_start(1.5, 0.0)
            .unwrap();
        for impact_memory in [ImpactMemory::Continuous, ImpactMemory::Restart] {
            let method = PredictorCorrector {
                impact_memory,
                ..method
            };
            let a = simulate(&direct, &method, &options).unwrap();
            let b = simulate(&from_file, &method, &options).unwrap();
            assert!(!a.eta.is_empty(), "{name}: noise recorded");
            assert_eq!(bits(&a), bits(&b), "{name}");
            assert_eq!(a.impacts, b.impacts, "{name}");
            if barrier == Barrier::On && impact_memory == ImpactMemory::Continuous {
                assert!(a.impacts > 0, "{name}: the wall is hit");
            }
        }
    }
}

/// r(v) = r_fast + (r0 − r_fast)e^{−v/speed}: r0 at grazing, r_fast at fast impacts, r0 − (r0 −
/// r_fast)(1 − 1/e) at v = speed; a constant r is constant.
#[test]
fn the_speed_dependent_restitution_is_its_documented_form() {
    let law = Restitution::Speed(SpeedRestitution {
        r0: 0.9,
        r_fast: 0.5,
        speed: 2.0,
    });
    assert_eq!(law.at(0.0), 0.9);
    assert!((law.at(2.0) - (0.5 + 0.4 / std::f64::consts::E)).abs() < 1e-15);
    assert_eq!(law.at(-2.0), law.at(2.0));
    assert!((law.at(1e3) - 0.5).abs() < 1e-15);
    assert_eq!(Restitution::Constant(0.7).at(5.0), 0.7);
}
