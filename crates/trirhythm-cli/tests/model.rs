//! `trirhythm model show/check` and `--model FILE`: the show → check round trip for every
//! preset, the same output as `--preset` for every command that takes a model, and malformed
//! files each refused (exit 2, the dotted field named, no output file written).

mod common;
use common::{ok_stdout, run, scratch_dir};

include!("../../trirhythm/tests/data/malformed_models.rs");

fn write(dir: &std::path::Path, name: &str, text: &str) -> String {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path.to_str().unwrap().to_string()
}

#[test]
fn show_then_check_is_a_round_trip_for_every_preset() {
    let dir = scratch_dir("model-show");
    for preset in trirhythm::model::presets() {
        let text = ok_stdout(&["model", "show", "--preset", preset.name]);
        assert!(text.contains("format = 1"), "{}", preset.name);
        let file = write(&dir, &format!("{}.toml", preset.name), &text);
        let said = ok_stdout(&["model", "check", &file]);
        assert!(
            said.contains("the engine steps it"),
            "{}: {said}",
            preset.name
        );
        // the printed file is the preset's model, bit for bit, and prints back the same
        let model = trirhythm::model::Model::from_toml_str(&text).unwrap();
        assert_eq!(model.paper_params().as_ref(), Some(&preset.params));
        assert!(text.ends_with(&model.to_toml()), "{}", preset.name);
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn model_files_give_the_presets_output() {
    let dir = scratch_dir("model-same");
    let file = write(
        &dir,
        "fig13a.toml",
        &ok_stdout(&["model", "show", "--preset", "fig13a"]),
    );
    let common = ["--t-end", "20"];
    let by_preset = ok_stdout(&[&["simulate", "--preset", "fig13a"][..], &common].concat());
    let by_model = ok_stdout(&[&["simulate", "--model", file.as_str()][..], &common].concat());
    assert!(by_preset == by_model, "the outputs differ");
    // the wall and the start come from the file
    let off = write(
        &dir,
        "off.toml",
        &BASE
            .replace(
                "[[wall]]\nposition = 0.0\nkeep = \"above\"\nrestitution = 0.99\n",
                "",
            )
            .replace("u0 = 1.0", "u0 = -0.5"),
    );
    let by_flags = ok_stdout(
        &[
            &[
                "simulate",
                "--preset",
                "fig13a",
                "--barrier",
                "off",
                "--u0",
                "-0.5",
            ][..],
            &common,
        ]
        .concat(),
    );
    let by_model = ok_stdout(&[&["simulate", "--model", off.as_str()][..], &common].concat());
    // no wall: the parameters' r is 1 (unused), the preset's 0.99 — the path is the same
    let rows = |s: &str| -> Vec<String> {
        s.lines()
            .filter(|l| !l.starts_with('#'))
            .map(str::to_string)
            .collect()
    };
    assert!(rows(&by_flags) == rows(&by_model), "the paths differ");
    assert!(by_model.contains("barrier=off") && by_model.contains("u0=-0.5"));
    // every other command takes the file (small runs; the wall-clock fields differ)
    for args in [
        &[
            "ensemble",
            "--paths",
            "2",
            "--t-end",
            "10",
            "--burn-in",
            "2",
        ][..],
        &[
            "lyapunov",
            "--paths",
            "1",
            "--t-end",
            "10",
            "--transient",
            "2",
        ],
    ] {
        let a = ok_stdout(&[args, &["--model", file.as_str(), "--format", "json"]].concat());
        let b = ok_stdout(
            &[
                args,
                &["--preset", "fig13a", "--u0", "1", "--format", "json"],
            ]
            .concat(),
        );
        let strip = |s: &str| {
            let mut v: serde_json::Value = serde_json::from_str(s).unwrap();
            v.as_object_mut()
                .unwrap()
                .retain(|k, _| !k.contains("time"));
            v
        };
        assert_eq!(strip(&a), strip(&b), "{args:?}");
    }
    // phase-response starts from the file's start: Fig. 17(a)'s outer cycle from U(0) = 12
    let outer = write(
        &dir,
        "fig17a.toml",
        &ok_stdout(&["model", "show", "--preset", "fig17a"]).replace("u0 = 1.0", "u0 = 12.0"),
    );
    let args = [
        "phase-response",
        "--phases",
        "8",
        "--periods",
        "6",
        "--format",
        "json",
    ];
    let a = ok_stdout(&[&args[..], &["--model", outer.as_str()]].concat());
    let b = ok_stdout(&[&args[..], &["--preset", "fig17a", "--u0", "12"]].concat());
    let strip = |s: &str| {
        let mut v: serde_json::Value = serde_json::from_str(s).unwrap();
        v.as_object_mut()
            .unwrap()
            .retain(|k, _| !k.contains("time"));
        v
    };
    assert_eq!(strip(&a), strip(&b));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn malformed_model_files_are_refused_with_the_field_named_and_no_output() {
    let dir = scratch_dir("model-malformed");
    assert!(MALFORMED.len() >= 20);
    for (i, (field, _, _)) in MALFORMED.iter().enumerate() {
        let file = write(&dir, &format!("bad{i}.toml"), &malformed(i));
        for command in ["simulate", "ensemble", "lyapunov"] {
            let out_path = dir.join(format!("out{i}-{command}"));
            let out = run(&[
                command,
                "--model",
                &file,
                "--out",
                out_path.to_str().unwrap(),
            ]);
            let stderr = String::from_utf8_lossy(&out.stderr);
            assert_eq!(out.status.code(), Some(2), "case {i} {command}: {stderr}");
            assert!(stderr.contains(field), "case {i} {command}: {stderr}");
            assert!(!out_path.exists(), "case {i} {command}: output written");
        }
        let out = run(&["model", "check", &file]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "case {i} check: {stderr}");
        assert!(stderr.contains(field), "case {i} check: {stderr}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn multiplicative_noise_at_the_model_walls_is_stepped() {
    let dir = scratch_dir("model-parametric");
    for (case, text) in [
        (
            "an upper wall at 3",
            format!(
                "{BASE}[[wall]]\nposition = 3.0\nkeep = \"below\"\nrestitution = 0.9\n\
                 [noise.multiplicative]\nintensity = 0.01\n"
            ),
        ),
        (
            "a lower wall at -0.5",
            format!(
                "{}[noise.multiplicative]\nintensity = 0.01\n",
                BASE.replace("position = 0.0", "position = -0.5")
            ),
        ),
    ] {
        let file = write(&dir, "term.toml", &text);
        let said = ok_stdout(&["model", "check", &file]);
        assert!(!said.contains("not stepped yet"), "{case}: {said}");
        let out_path = dir.join("out.csv");
        let out = run(&[
            "simulate",
            "--model",
            &file,
            "--t-end",
            "20",
            "--out",
            out_path.to_str().unwrap(),
        ]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(0), "{case}: {stderr}");
        assert!(out_path.exists(), "{case}");
        let _ = std::fs::remove_file(&out_path);
    }
    // the wall and the start are the file's: the flags are refused beside it
    let file = write(&dir, "base.toml", BASE);
    for flags in [
        &["--barrier", "off"][..],
        &["--u0", "2"],
        &["--preset", "fig1"],
    ] {
        let out = run(&[&["simulate", "--model", file.as_str()][..], flags].concat());
        assert_eq!(out.status.code(), Some(2), "{flags:?}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A Rayleigh–van der Pol oscillator with fractional damping under OU noise, no wall: outside
/// the paper's family, inside the averaged theory's.
const RAYLEIGH: &str = r#"format = 1
[leading]
lambda = 0.98
[damping]
mu0 = 0.1
coefficients = [1.0]
rayleigh = [-0.1]
[restoring]
omega0 = 1.0
[[fractional]]
coefficient = 0.02
order = 0.5
[noise.additive]
intensity = 0.01
correlation_time = 0.2
"#;

#[test]
fn theory_commands_take_a_model_the_theory_covers() {
    let dir = scratch_dir("model-theory");
    let file = write(&dir, "rayleigh.toml", RAYLEIGH);
    let model = trirhythm::model::Model::from_toml_str(RAYLEIGH).unwrap();
    let th = trirhythm::theory::averaging::Theory::from_model(
        &model,
        trirhythm::theory::averaging::Variant::Consistent,
    )
    .unwrap();
    let flags = ["--model", file.as_str(), "--variant", "consistent"];
    let doc = common::ok_json(&[&["cycles"][..], &flags, &["--format", "json"]].concat());
    let cycles = doc["cycles"].as_array().unwrap();
    assert_eq!(cycles.len(), th.cycles().len());
    assert_eq!(
        cycles[0]["amplitude"].as_f64().unwrap(),
        th.cycles()[0].amplitude
    );
    assert!(doc["model"]["damping"]["rayleigh"][0].as_f64() == Some(-0.1));
    assert!(doc.get("params").is_none());
    assert!(doc["assumptions"].as_array().unwrap().len() >= 4);
    let said = ok_stdout(&["model", "check", &file]);
    assert!(
        said.contains("the averaged theory applies (--variant consistent)"),
        "{said}"
    );
    // without --variant a model outside Eq. (1) with its wall gets the consistent variant,
    // said on standard error; the paper's variant, asked for, is refused with the reason
    let out = run(&["cycles", "--model", &file, "--format", "json"]);
    assert_eq!(out.status.code(), Some(0));
    let doc: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(doc["variant"], "consistent");
    assert_eq!(doc["cycles"].as_array().unwrap(), cycles);
    assert!(String::from_utf8_lossy(&out.stderr).contains("--variant consistent"));
    let out = run(&["cycles", "--model", &file, "--variant", "paper"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("use the consistent variant"));
    // every theory command runs on it; the CSV header names the model and the assumptions
    for command in [
        &["equivalents"][..],
        &["drift", "--grid", "0:2:5"],
        &["potential", "--grid", "0:2:5"],
        &["barriers"],
        &["pdf"],
    ] {
        let text = ok_stdout(&[command, &flags, &["--format", "csv"]].concat());
        assert!(
            text.contains("rayleigh = [-0.1]") && text.contains("assumption: 1 − λ"),
            "{command:?}: {text}"
        );
    }
    // a file of the paper's family gives the preset's cycles, bit for bit
    let paper = write(
        &dir,
        "fig13a.toml",
        &ok_stdout(&["model", "show", "--preset", "fig13a"]),
    );
    for variant in ["paper", "consistent"] {
        let by_model = common::ok_json(&[
            "cycles",
            "--model",
            &paper,
            "--variant",
            variant,
            "--format",
            "json",
        ]);
        let by_preset = common::ok_json(&[
            "cycles",
            "--preset",
            "fig13a",
            "--variant",
            variant,
            "--format",
            "json",
        ]);
        assert_eq!(by_model["cycles"], by_preset["cycles"], "{variant}");
        assert_eq!(by_model["params"], by_preset["params"], "{variant}");
    }
    // the balance at ω1(ω1): by quadrature, for a preset too; not for the paper variant
    let natural = common::ok_json(&[&["equivalents"][..], &flags, &["--format", "json"]].concat());
    let balanced = common::ok_json(
        &[
            &["equivalents"][..],
            &flags,
            &["--balance", "self-consistent", "--format", "json"],
        ]
        .concat(),
    );
    let gap = |d: &serde_json::Value| d["assumptions"][1]["value"].as_f64().unwrap();
    assert!(gap(&balanced) < 1e-14 && gap(&natural) > 1e-3);
    let preset = [
        "cycles",
        "--preset",
        "fig13a",
        "--balance",
        "self-consistent",
    ];
    let _ = ok_stdout(&[&preset[..], &["--variant", "consistent"]].concat());
    assert_eq!(run(&preset).status.code(), Some(2));
    // --param overrides a paper-family file, as it does a preset
    let by_model = common::ok_json(&[
        "cycles", "--model", &paper, "--param", "r=0.95", "--format", "json",
    ]);
    let by_preset = common::ok_json(&[
        "cycles", "--preset", "fig13a", "--param", "r=0.95", "--format", "json",
    ]);
    assert_eq!(by_model["cycles"], by_preset["cycles"]);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn theory_commands_refuse_a_model_the_theory_does_not_cover() {
    let dir = scratch_dir("model-theory-refused");
    let forced = RAYLEIGH.replace(
        "[noise.additive]",
        "[forcing]\namplitude = 0.3\nfrequency = 1.1\n[noise.additive]",
    );
    let offset = BASE
        .replace("position = 0.0", "position = 0.5")
        .replace("u0 = 1.0", "u0 = 1.5");
    for (field, text, variant) in [
        ("forcing.amplitude = 0.3", forced, "consistent"),
        ("wall.0.position = 0.5", offset, "consistent"),
        // the paper variant's κ and σ1 are printed for Eq. (1), not derived
        ("damping.rayleigh.0 = -0.1", RAYLEIGH.to_string(), "paper"),
    ] {
        let file = write(&dir, "refused.toml", &text);
        if variant == "consistent" {
            let said = ok_stdout(&["model", "check", &file]);
            assert!(
                said.contains("the averaged theory does not apply") && said.contains(field),
                "{said}"
            );
        }
        for command in [
            &["cycles"][..],
            &["equivalents"],
            &["drift"],
            &["potential"],
            &["barriers"],
            &["pdf"],
            &["map", "--x", "mu0=0.01:0.1:3", "--y", "r=0.9:1:3"],
            &["branches", "--x", "mu0=0.01:0.1"],
        ] {
            let out_path = dir.join("out.csv");
            let out = run(&[
                command,
                &["--model", &file, "--variant", variant],
                &["--out", out_path.to_str().unwrap()],
            ]
            .concat());
            let stderr = String::from_utf8_lossy(&out.stderr);
            assert_eq!(out.status.code(), Some(2), "{field} {command:?}: {stderr}");
            assert!(
                stderr.contains(field) && stderr.contains("does not apply"),
                "{command:?}: {stderr}"
            );
            assert!(!out_path.exists(), "{command:?}: output written");
        }
    }
    // a model the theory covers but that map cannot sweep: refused naming the term, pointing
    // at the theory commands
    let file = write(&dir, "rayleigh.toml", RAYLEIGH);
    let out = run(&[
        "map",
        "--model",
        &file,
        "--variant",
        "consistent",
        "--x",
        "mu0=0.01:0.1:3",
        "--y",
        "r=0.9:1:3",
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("damping.rayleigh.0") && stderr.contains("cycles"),
        "{stderr}"
    );
    // --param does not edit a model outside the paper's family
    let out = run(&[
        "cycles",
        "--model",
        &file,
        "--variant",
        "consistent",
        "--param",
        "mu0=0.2",
    ]);
    assert_eq!(out.status.code(), Some(2));
    let _ = std::fs::remove_dir_all(&dir);
}

/// The Rayleigh oscillator Ü − μ0(1 − U̇²)U̇ + U = η (h = μ0 + d1U̇², d1 = −μ0) under weak
/// white noise, stepped by the General kernel, without and with fractional damping
/// 0.01·D^0.5U: each ensemble is compared with the model's own averaged theory (phase
/// quadrature, the fractional term by harmonic balance, consistent variant), which chose its
/// range and well.
#[test]
fn a_rayleigh_ensemble_agrees_with_its_averaged_theory() {
    let dir = scratch_dir("model-rayleigh-mc");
    for (name, fractional) in [
        ("rayleigh", ""),
        (
            "rayleigh-fractional",
            "fractional = [{ coefficient = 0.01, order = 0.5 }]\n",
        ),
    ] {
        let text = format!(
            "format = 1\nleading = {{ lambda = 1.0 }}\n\
             damping = {{ mu0 = 0.05, coefficients = [1.0], rayleigh = [-0.05] }}\n\
             restoring = {{ omega0 = 1.0 }}\n{fractional}\
             noise.additive = {{ intensity = 0.0005 }}\nstart = {{ u0 = 1.0 }}\n"
        );
        let file = write(&dir, &format!("{name}.toml"), &text);
        let doc = common::ok_json(&[
            "ensemble",
            "--model",
            &file,
            "--paths",
            "8",
            "--t-end",
            "5000",
            "--burn-in",
            "500",
            "--format",
            "json",
        ]);
        assert_eq!(doc["stationarity"]["stationary"], true, "{name}");
        let theory = &doc["theory"]["consistent"];
        let mc = doc["mean_amplitude"]["value"].as_f64().unwrap();
        let se = doc["mean_amplitude"]["stderr"].as_f64().unwrap();
        let th = theory["mean_amplitude"].as_f64().unwrap();
        // without the fractional term the cycle of averaging is 2/√3 = 1.1547 (1.1590 with
        // the noise's drift); the mean amplitude within four standard errors and the
        // first-order method's O(μ0) = 0.5 %
        assert!(
            (mc - th).abs() < 4.0 * se + 0.005 * th,
            "{name}: {mc} ± {se} vs {th}"
        );
        let h = theory["hellinger"]["value"].as_f64().unwrap();
        assert!(h < 0.08, "{name}: Hellinger {h}");
        assert!(doc["theory"]["paper"]["error"]
            .as_str()
            .unwrap()
            .contains("Rayleigh"));
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A Duffing oscillator under white noise, no wall: the General kernel's terms run end to end
/// through `simulate --model` and `ensemble --model`, and the ensemble says that the averaged
/// theory does not apply instead of comparing with the paper's formulas.
#[test]
fn a_duffing_model_runs_through_simulate_and_ensemble_without_the_papers_theory() {
    let dir = scratch_dir("model-duffing");
    let text = "format = 1\nleading = { lambda = 1.0 }\n\
                damping = { mu0 = 0.5, coefficients = [-1.0] }\n\
                restoring = { omega0 = 1.0, cubic = 1.0 }\n\
                noise.additive = { intensity = 0.5 }\nstart = { u0 = 0.5 }\n";
    let file = write(&dir, "duffing.toml", text);
    let said = ok_stdout(&["model", "check", &file]);
    assert!(
        said.contains("the engine steps it (the General kernel"),
        "{said}"
    );
    let csv = ok_stdout(&["simulate", "--model", &file, "--t-end", "5"]);
    assert!(csv.contains("# terms: cubic=1 quintic=0"), "{csv}");
    assert_eq!(csv.lines().filter(|l| !l.starts_with('#')).count(), 502);
    let ensemble = [
        "ensemble",
        "--model",
        &file,
        "--t-end",
        "50",
        "--burn-in",
        "10",
        "--paths",
        "2",
    ];
    // no theory to choose the histogram's range from: refused, naming it
    let out = run(&ensemble);
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("amplitude_max") && stderr.contains("restoring.cubic"),
        "{stderr}"
    );
    let json = ok_stdout(&[&ensemble[..], &["--amplitude-max", "4", "--format", "json"]].concat());
    let doc: serde_json::Value = serde_json::from_str(&json).unwrap();
    assert!(doc["terms"].as_str().unwrap().contains("cubic=1"));
    for variant in ["paper", "consistent"] {
        let error = doc["theory"][variant]["error"].as_str().unwrap();
        assert!(error.contains("does not apply"), "{variant}: {error}");
    }
    // the well method and the commands built on the theory refuse it, saying why
    for args in [
        &[
            &ensemble[..],
            &["--amplitude-max", "4", "--method", "wells"],
        ]
        .concat()[..],
        &["critical-noise", "--model", &file, "--noises", "0.1,0.2"],
        &[
            "oscillation",
            "--model",
            &file,
            "--x",
            "mu0=0.01:0.1:3",
            "--y",
            "lambda=0.9:1",
        ],
    ] {
        let out = run(args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(
            stderr.contains("the averaged theory does not apply"),
            "{args:?}: {stderr}"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_two_wall_model_runs_through_simulate_and_ensemble_without_the_papers_theory() {
    let dir = scratch_dir("model-walls");
    // a linear oscillator between a wall at −1 (r = 0.8) and one at 1 (speed-dependent r)
    let text = "format = 1\nleading = { lambda = 1.0 }\n\
                damping = { mu0 = 0.05, coefficients = [-1.0] }\n\
                restoring = { omega0 = 1.0 }\n\
                wall = [{ position = -1.0, keep = \"above\", restitution = 0.8 }, \
                { position = 1.0, keep = \"below\", restitution = { r0 = 0.9, r_fast = 0.6, \
                speed = 1.0 } }]\n\
                noise.additive = { intensity = 0.3 }\nstart = { u0 = 0.5 }\n";
    let file = write(&dir, "walls.toml", text);
    let said = ok_stdout(&["model", "check", &file]);
    assert!(
        said.contains("the engine steps it (the General kernel") && said.contains("two walls"),
        "{said}"
    );
    let out_path = dir.join("sim.csv");
    let out = run(&[
        "simulate",
        "--model",
        &file,
        "--t-end",
        "100",
        "--out",
        out_path.to_str().unwrap(),
    ]);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let csv = std::fs::read_to_string(&out_path).unwrap();
    assert!(
        csv.contains("walls: position=-1 keep=above restitution=0.8; position=1 keep=below"),
        "{csv}"
    );
    let us: Vec<f64> = csv
        .lines()
        .filter(|l| !l.starts_with('#') && !l.starts_with('t'))
        .map(|l| l.split(',').nth(1).unwrap().parse().unwrap())
        .collect();
    assert_eq!(us.len(), 10_001);
    assert!(
        us.iter().all(|u| (-1.0..=1.0).contains(u)),
        "between the walls"
    );
    // it meets both walls
    assert!(us.iter().any(|&u| u < -0.95) && us.iter().any(|&u| u > 0.95));
    let ensemble = [
        "ensemble",
        "--model",
        &file,
        "--t-end",
        "50",
        "--burn-in",
        "10",
        "--paths",
        "2",
    ];
    // no theory to choose the histogram's range from: refused, naming the walls
    let out = run(&ensemble);
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("amplitude_max") && stderr.contains("two walls"),
        "{stderr}"
    );
    let json = ok_stdout(&[&ensemble[..], &["--amplitude-max", "3", "--format", "json"]].concat());
    let doc: serde_json::Value = serde_json::from_str(&json).unwrap();
    assert!(doc["terms"]
        .as_str()
        .unwrap()
        .contains("walls: position=-1"));
    for variant in ["paper", "consistent"] {
        let error = doc["theory"][variant]["error"].as_str().unwrap();
        assert!(error.contains("does not apply"), "{variant}: {error}");
    }
    // the tangent method takes it (through the impact steps on both walls)
    let json = ok_stdout(&[
        "lyapunov",
        "--model",
        &file,
        "--method",
        "tangent",
        "--paths",
        "1",
        "--t-end",
        "20",
        "--transient",
        "2",
        "--format",
        "json",
    ]);
    let doc: serde_json::Value = serde_json::from_str(&json).unwrap();
    assert_eq!(doc["method"], "tangent");
    assert!(doc["lle"]["value"].as_f64().unwrap().is_finite(), "{json}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// A linear oscillator with fractional damping and multiplicative noise (correlated with the
/// additive noise), no wall: simulate and ensemble run it end to end through the General
/// kernel; the tangent method runs on it (and agrees with two trajectories), with the wall too.
#[test]
fn a_fractional_model_with_multiplicative_noise_runs_through_simulate_and_ensemble() {
    let dir = scratch_dir("model-fractional");
    let text = "format = 1\nleading = { lambda = 1.0 }\n\
                damping = { mu0 = 0.1, coefficients = [-1.0] }\n\
                restoring = { omega0 = 1.0 }\n\
                [[fractional]]\ncoefficient = 0.4\norder = 0.5\n\
                [[fractional]]\ncoefficient = 0.1\norder = 0.8\n\
                [noise]\ncorrelation = 0.5\n\
                [noise.additive]\nintensity = 0.1\n\
                [noise.multiplicative]\nintensity = 0.02\n\
                [start]\nu0 = 0.5\n";
    let file = write(&dir, "fractional.toml", text);
    let said = ok_stdout(&["model", "check", &file]);
    assert!(
        said.contains("the engine steps it (the General kernel"),
        "{said}"
    );
    let csv = ok_stdout(&["simulate", "--model", &file, "--t-end", "5"]);
    assert!(
        csv.contains("fractional=[0.4@0.5,0.1@0.8]")
            && csv.contains("multiplicative: intensity=0.02 correlation_time=0 correlation=0.5"),
        "{csv}"
    );
    assert_eq!(csv.lines().filter(|l| !l.starts_with('#')).count(), 502);
    let ensemble = [
        "ensemble",
        "--model",
        &file,
        "--t-end",
        "50",
        "--burn-in",
        "10",
        "--paths",
        "2",
        "--amplitude-max",
        "4",
        "--format",
        "json",
    ];
    let doc: serde_json::Value = serde_json::from_str(&ok_stdout(&ensemble)).unwrap();
    assert!(doc["terms"].as_str().unwrap().contains("fractional="));
    // the paper's printed formulas do not cover it; the model's own averaged theory does
    // (the fractional terms by harmonic balance, U·η_m by its spectral terms): compared
    let error = doc["theory"]["paper"]["error"].as_str().unwrap();
    assert!(error.contains("does not apply"), "{error}");
    assert!(
        doc["theory"]["consistent"]["hellinger"]["value"].is_number(),
        "{}",
        doc["theory"]["consistent"]
    );
    // fractional terms with the wall: stepped, U kept above it
    let walled = write(
        &dir,
        "walled.toml",
        &format!("{text}[[wall]]\nposition = 0.0\nkeep = \"above\"\nrestitution = 0.9\n"),
    );
    let csv = ok_stdout(&["simulate", "--model", &walled, "--t-end", "20"]);
    let u: Vec<f64> = csv
        .lines()
        .filter(|l| !l.starts_with('#') && !l.starts_with('t'))
        .map(|l| l.split(',').nth(1).unwrap().parse().unwrap())
        .collect();
    assert_eq!(u.len(), 2001);
    assert!(u.iter().all(|&u| u >= 0.0), "{csv}");
    assert!(u.iter().any(|&u| u < 0.05), "the wall is met: {csv}");
    // the Lyapunov exponent by the tangent (fractional terms and U·η_m differentiated) and by
    // two trajectories, the same path: no wall, so the tangent is the step's exact derivative
    let lle = |model: &str, method: &str| {
        vec![
            "lyapunov".to_string(),
            "--model".into(),
            model.into(),
            "--method".into(),
            method.into(),
            "--paths".into(),
            "1".into(),
            "--t-end".into(),
            "60".into(),
            "--transient".into(),
            "10".into(),
            "--format".into(),
            "json".into(),
        ]
    };
    let mut values = vec![];
    for method in ["tangent", "two-trajectory"] {
        let args = lle(&file, method);
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let doc: serde_json::Value = serde_json::from_str(&ok_stdout(&args)).unwrap();
        assert_eq!(doc["method"], method);
        values.push(doc["lle"]["value"].as_f64().unwrap());
    }
    assert!(
        values[0].is_finite() && (values[0] - values[1]).abs() < 1e-3,
        "tangent {} against two trajectories {}",
        values[0],
        values[1]
    );
    // with the wall too (the memories of δV split at the impacts)
    let args = lle(&walled, "tangent");
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let doc: serde_json::Value = serde_json::from_str(&ok_stdout(&args)).unwrap();
    assert!(doc["lle"]["value"].as_f64().unwrap().is_finite(), "{doc}");
    assert!(doc["per_path"][0]["impacts"].as_u64().unwrap() > 0, "{doc}");
    let _ = std::fs::remove_dir_all(&dir);
}
