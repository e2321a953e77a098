//! `trirhythm lyapunov` and `trirhythm critical-noise` from the outside: the JSON and CSV
//! contracts, the known exponent of the damped linear oscillator, "no sign change in range"
//! said plainly, both methods (`--method two-trajectory | tangent`), and bad input (exit 2 naming the flag).

mod common;

use common::{ok_json, ok_stdout as ok, run};

const LINEAR: [&str; 16] = [
    "--param",
    "c0=-1",
    "--param",
    "c1=0",
    "--param",
    "alpha0=0",
    "--param",
    "beta0=0",
    "--param",
    "gamma0=0",
    "--param",
    "delta0=0",
    "--param",
    "lambda=1",
    "--barrier",
    "off",
];

#[test]
fn json_has_the_exponent_its_error_per_path_and_running() {
    let mut args = vec![
        "lyapunov",
        "--param",
        "mu0=0.1",
        "--param",
        "omega0=1",
        "--param",
        "D=0.5",
        "--param",
        "tau=0.1",
        "--paths",
        "2",
        "--t-end",
        "500",
        "--transient",
        "50",
    ];
    args.extend(LINEAR);
    let doc = ok_json(&args);
    let v = doc["lle"]["value"].as_f64().unwrap();
    assert!((v + 0.05).abs() < 2e-3, "LLE {v} vs −μ0/2 = −0.05");
    assert!(doc["lle"]["stderr"].as_f64().unwrap() < 1e-6);
    assert_eq!(doc["per_path"].as_array().unwrap().len(), 2);
    let running = doc["running"].as_array().unwrap();
    assert_eq!(running.len(), 100);
    for key in ["t", "value", "stderr"] {
        assert!(running[0][key].is_number(), "running[0].{key}");
    }
    assert_eq!(doc["method"], "two-trajectory");
    // the tangent method: the same known exponent, and recorded as such
    args.extend(["--method", "tangent"]);
    let doc = ok_json(&args);
    let t = doc["lle"]["value"].as_f64().unwrap();
    assert!((t + 0.05).abs() < 2e-3, "tangent LLE {t} vs −μ0/2 = −0.05");
    assert!((t - v).abs() < 1e-6, "tangent {t} vs two trajectories {v}");
    assert_eq!(doc["method"], "tangent");
}

#[test]
fn sweep_writes_key_lle_stderr() {
    let text = ok(&[
        "lyapunov",
        "--preset",
        "fig17a",
        "--paths",
        "2",
        "--t-end",
        "50",
        "--transient",
        "0",
        "--sweep",
        "D=0.1:0.5:3",
    ]);
    let rows: Vec<&str> = text.lines().filter(|l| !l.starts_with('#')).collect();
    assert_eq!(rows[0], "D,lle,stderr,merged,unmerged,unmerged_stderr");
    assert_eq!(rows.len(), 4);
}

/// A realisation whose copy merges with its reference (both stuck at the wall on the same step,
/// memory restarted): −∞ said in words with the count and the others' mean, the merge time per
/// path in JSON.
#[test]
fn a_merged_realisation_is_reported_with_its_time_and_the_others_mean() {
    let out = run(&[
        "lyapunov",
        "--preset",
        "fig18b",
        "--param",
        "r=0.8",
        "--param",
        "D=0.29375",
        "--paths",
        "6",
        "--t-end",
        "380",
        "--transient",
        "20",
        "--u0",
        "1",
    ]);
    assert!(out.status.success());
    let doc: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!(doc["lle"]["value"].is_null());
    assert_eq!(doc["merged"], 1);
    let path4 = &doc["per_path"][4];
    assert_eq!(path4["exponent"], "-inf");
    let t = path4["merged_at"].as_f64().unwrap();
    assert!((t - 67.04).abs() < 1e-6, "{t}");
    assert!(doc["per_path"][0]["merged_at"].is_null());
    assert!(doc["unmerged"]["value"].as_f64().unwrap() > 0.0);
    let said = String::from_utf8_lossy(&out.stderr);
    assert!(said.contains("−∞: 1 of 6 realisations merged"), "{said}");
    assert!(said.contains("the other 5: "), "{said}");
}

#[test]
fn critical_noise_says_when_there_is_no_sign_change() {
    let mut args = vec![
        "critical-noise",
        "--param",
        "mu0=0.1",
        "--paths",
        "2",
        "--t-end",
        "100",
        "--transient",
        "10",
        "--d-range",
        "0:1",
        "--grid",
        "2",
        "--refinements",
        "0",
    ];
    args.extend(LINEAR);
    let out = run(&args);
    assert_eq!(out.status.code(), Some(0));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("no sign change in range"), "{text}");
    assert!(text.lines().any(|l| l == "D_c,D_c_lo,D_c_hi"));
    assert!(String::from_utf8_lossy(&out.stderr).contains("no sign change in range"));
}

#[test]
fn bad_input_names_the_flag() {
    for (args, needle) in [
        (vec!["lyapunov", "--paths", "0"], "--paths"),
        (vec!["lyapunov", "--dt", "1"], "--dt"),
        (vec!["lyapunov", "--separation", "0.1"], "--separation"),
        (
            vec!["lyapunov", "--lanes", "2"],
            "--lanes = 2: allowed range is 1, 4 or 8",
        ),
        (vec!["lyapunov", "--sweep", "D=1:0:3"], "--sweep"),
        (vec!["critical-noise", "--d-range", "2:1"], "--d-range"),
        (
            vec!["critical-noise", "--d-range", "0:1", "--sweep", "D=0:1:2"],
            "--sweep",
        ),
    ] {
        let out = run(&args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(stderr.contains(needle), "{args:?}: {stderr}");
    }
}

/// Both methods give the same exponents, path by path, with the paths in lanes or one after the
/// other (`--lanes`).
#[test]
fn every_lane_count_gives_the_same_exponents() {
    for method in ["two-trajectory", "tangent"] {
        let run = |lanes: &str| {
            let doc = ok_json(&[
                "lyapunov",
                "--preset",
                "fig17a",
                "--param",
                "D=0.1",
                "--paths",
                "5",
                "--t-end",
                "40",
                "--transient",
                "5",
                "--u0",
                "3",
                "--method",
                method,
                "--lanes",
                lanes,
            ]);
            (
                doc["lle"].clone(),
                doc["per_path"].clone(),
                doc["running"].clone(),
            )
        };
        let one = run("1");
        assert!(one.0["value"].is_number(), "{method}: {:?}", one.0);
        assert_eq!(one, run("4"), "{method}");
        assert_eq!(one, run("8"), "{method}");
    }
}
