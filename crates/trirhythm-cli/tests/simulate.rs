//! `trirhythm simulate` from the outside: CSV and JSON parse, the columns and keys of the
//! contract are there, the numbers are the library's, bad input exits 2 naming the parameter
//! and leaves no file.

mod common;

use common::{ok_output as ok, run};
use serde_json::Value;
use std::process::Output;

fn csv(out: &Output) -> (Vec<String>, Vec<Vec<f64>>) {
    let text = String::from_utf8(out.stdout.clone()).unwrap();
    let mut lines = text.lines().filter(|l| !l.starts_with('#'));
    let header: Vec<String> = lines.next().unwrap().split(',').map(String::from).collect();
    let rows = lines
        .map(|l| l.split(',').map(|c| c.parse::<f64>().unwrap()).collect())
        .collect();
    (header, rows)
}

#[test]
fn csv_has_the_contract_columns_and_matches_the_exact_impact_solution() {
    // λ = 1, P ≡ 0 (c0 = 0), no noise: U = (v0/ω) r^k |sin ωt|
    let out = ok(&[
        "simulate", "--param", "lambda=1", "--param", "c0=0", "--param", "c1=0", "--param",
        "alpha0=0", "--param", "beta0=0", "--param", "gamma0=0", "--param", "delta0=0", "--param",
        "omega0=2", "--param", "r=0.5", "--u0", "0", "--v0", "2", "--t-end", "4", "--dt", "0.001",
        "--every", "10",
    ]);
    let (header, rows) = csv(&out);
    assert_eq!(header, ["t", "U", "V"]);
    assert_eq!(rows.len(), 401);
    for row in &rows {
        let (t, u) = (row[0], row[1]);
        let k = (t / (std::f64::consts::PI / 2.0)).floor();
        let exact = 0.5f64.powf(k) * (2.0 * t).sin().abs();
        assert!((u - exact).abs() < 1e-5, "t = {t}: {u} vs {exact}");
        assert!(u >= 0.0);
    }
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("impacts 2"), "{stderr}");
}

#[test]
fn eta_column_appears_with_noise_and_json_has_the_summary() {
    let out = ok(&[
        "simulate", "--preset", "fig11", "--t-end", "5", "--every", "50", "--seed", "3",
    ]);
    let (header, rows) = csv(&out);
    assert_eq!(header, ["t", "U", "V", "eta"]);
    assert_eq!(rows.len(), 11);
    let out = ok(&[
        "simulate", "--preset", "fig11", "--t-end", "5", "--every", "50", "--seed", "3",
        "--format", "json",
    ]);
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    let s = &v["summary"];
    for key in [
        "impacts",
        "final_amplitude",
        "wall_time_s",
        "steps",
        "exponentials",
    ] {
        assert!(!s[key].is_null(), "summary.{key} missing");
    }
    assert_eq!(s["steps"], 500);
    let u: Vec<f64> = v["U"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    // the same seed gives the same path in both formats (JSON parsing may round the last bit)
    for (a, row) in u.iter().zip(&rows) {
        assert!((a - row[1]).abs() <= 1e-15 * a.abs().max(1.0));
    }
    assert_eq!(v["eta"].as_array().unwrap().len(), 11);
}

#[test]
fn the_systems_and_memories_run() {
    let base = [
        "simulate", "--preset", "fig1", "--t-end", "10", "--every", "100",
    ];
    let mut finals = vec![];
    for extra in [
        &["--system", "fractional"][..],
        &["--system", "equivalent"],
        &["--system", "zhuravlev"],
        &["--memory", "direct"],
        &["--impact-memory", "restart"],
        &["--barrier", "off"],
    ] {
        let mut args = base.to_vec();
        args.extend_from_slice(extra);
        let (_, rows) = csv(&ok(&args));
        assert_eq!(rows.len(), 11, "{extra:?}");
        finals.push(rows[10][1]);
    }
    // SOE and Direct agree on the fractional system
    assert!((finals[0] - finals[3]).abs() < 1e-8, "{finals:?}");
}

#[test]
fn bad_input_exits_2_naming_the_parameter_and_leaves_no_file() {
    let dir = std::env::temp_dir().join(format!("trirhythm-sim-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let target = dir.join("out.csv");
    let t = target.to_str().unwrap();
    for (args, name) in [
        (vec!["simulate", "--dt", "-0.1", "--out", t], "dt"),
        (vec!["simulate", "--dt", "0", "--out", t], "dt"),
        (vec!["simulate", "--t-end", "-5", "--out", t], "t_end"),
        (
            vec!["simulate", "--param", "lambda=1.5", "--out", t],
            "lambda",
        ),
        (vec!["simulate", "--u0", "-1", "--out", t], "u0"),
        (vec!["simulate", "--every", "0", "--out", t], "every"),
        (
            vec!["simulate", "--tolerance", "0", "--out", t],
            "tolerance",
        ),
        (vec!["simulate", "--param", "r=2", "--out", t], "r"),
    ] {
        let out = run(&args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(name), "{args:?}: {err}");
        assert!(!target.exists(), "{args:?} left a file");
    }
    // a good run writes the file
    ok(&["simulate", "--t-end", "1", "--out", t]);
    assert!(target.exists());
    std::fs::remove_dir_all(&dir).unwrap();
}
