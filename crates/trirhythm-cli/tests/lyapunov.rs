//! `trirhythm lyapunov` and `trirhythm critical-noise` from the outside: the JSON and CSV
//! contracts, the known exponent of the damped linear oscillator, both methods (`--method
//! two-trajectory | tangent`), the critical noise by regime (a stable cycle at small D called
//! not chaotic with D_c above the range, a rest-regime parameter set giving a rest curve, the
//! CSV's decisions the JSON's, the same bits on any thread count), and bad input (exit 2 naming
//! the flag).

mod common;

use common::{csv_rows, ok_json, ok_stdout as ok, run};

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

/// Fig. 17(a)'s parameters at μ0 = 0.05 (three stable cycles, the rest state unstable) at
/// small D, quick sizes.
const CYCLES: [&str; 13] = [
    "critical-noise",
    "--preset",
    "fig17a",
    "--param",
    "mu0=0.05",
    "--noises",
    "0.001,0.003",
    "--paths",
    "4",
    "--t-end",
    "100",
    "--transient",
    "20",
];

/// On a stable cycle weak noise synchronises (λ ≈ −c·D): every point of every cycle curve is
/// called not chaotic against δ = 1/W, and D_c lies above the range, one-sided.
#[test]
fn a_stable_cycle_at_small_noise_is_not_chaotic_and_its_d_c_lies_above() {
    let mut args = CYCLES.to_vec();
    args.extend(["--format", "json"]);
    let doc = ok_json(&args);
    assert_eq!(doc["margin"], 0.01);
    assert!(doc["sweep"].is_null() && doc["dt"].is_null());
    let results = doc["results"].as_array().unwrap();
    assert_eq!(results.len(), 1);
    assert!(results[0]["value"].is_null());
    let curves = results[0]["curves"].as_array().unwrap();
    let names: Vec<&str> = curves
        .iter()
        .map(|c| c["attractor"].as_str().unwrap())
        .collect();
    assert_eq!(names.len(), 3, "{names:?}");
    for (c, name) in curves.iter().zip(["inner", "middle", "outer"]) {
        let attractor = c["attractor"].as_str().unwrap();
        assert!(
            attractor.starts_with(&format!("{name} cycle (A = ")),
            "{attractor}"
        );
        assert_eq!(c["regime"], "cycle");
        // the figures' step rule: τ = 0.06, Δt = 0.005
        assert_eq!(c["dt"], 0.005);
        for q in c["points"].as_array().unwrap() {
            assert_eq!(q["call"], "not-chaotic", "{attractor}: {q}");
            assert_eq!(q["n"], 4);
            assert!(q["lle"].as_f64().unwrap() < 0.01);
        }
        assert_eq!(
            c["bracket"],
            serde_json::json!({"kind": "above", "lo": 0.003, "hi": null}),
            "{attractor}"
        );
        // on a cycle: the phase-reduction coefficient, no rest-regime statistics
        assert!(c["coefficient"].as_f64().unwrap() > 0.0, "{attractor}");
        assert!(c["rest"].is_null());
        assert!(c["decision"]
            .as_str()
            .unwrap()
            .starts_with("not chaotic up to the largest D = 0.003: D_c > 0.003"));
    }
}

/// Fig. 18(b)'s r = 0.8: the noise-free path from every start comes to rest on the wall, so
/// there is one curve, of the rest regime, with its pooled exponent and slope over D ≤ 1e-2.
#[test]
fn a_rest_regime_parameter_set_gives_a_rest_curve() {
    let doc = ok_json(&[
        "critical-noise",
        "--preset",
        "fig18b",
        "--param",
        "r=0.8",
        "--noises",
        "1e-6,1e-4,1e-2",
        "--paths",
        "3",
        "--t-end",
        "50",
        "--transient",
        "10",
        "--format",
        "json",
    ]);
    let curves = doc["results"][0]["curves"].as_array().unwrap();
    assert_eq!(curves.len(), 1, "{curves:?}");
    let c = &curves[0];
    assert_eq!(
        (&c["attractor"], &c["regime"]),
        (&"rest".into(), &"rest".into())
    );
    // τ = 0.025: Δt = 0.0025
    assert_eq!(c["dt"], 0.0025);
    let rest = &c["rest"];
    assert_eq!(rest["decades"], 4.0);
    for key in ["pooled", "pooled_se", "slope", "slope_se"] {
        assert!(rest[key].is_number(), "{key}: {rest}");
    }
    assert!(rest["d_c_zero"].is_boolean());
    assert!(c["coefficient"].is_null());
    let points = c["points"].as_array().unwrap();
    assert_eq!(points.len(), 3);
    assert!(points.iter().all(|q| q["agrees"].is_null()));
}

/// The CSV holds the JSON's numbers and decisions: a row per point, the curve's bracket, rest
/// statistics and coefficient repeated on its rows; with --sweep the parameter's column first.
/// One thread or three: the same bits.
#[test]
fn the_csv_says_what_the_json_says_on_any_thread_count() {
    let mut args = CYCLES.to_vec();
    args.extend(["--sweep", "mu0=0.05:0.06:2"]);
    let run_with = |threads: &str, format: &str| {
        let mut a = args.clone();
        a.extend(["--format", format]);
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_trirhythm"))
            .args(&a)
            .env("RAYON_NUM_THREADS", threads)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        String::from_utf8(out.stdout).unwrap()
    };
    let json = run_with("1", "json");
    assert_eq!(
        json,
        run_with("3", "json"),
        "the thread count changed the result"
    );
    let doc: serde_json::Value = serde_json::from_str(&json).unwrap();
    let csv = run_with("2", "csv");
    let rows = csv_rows(&csv);
    assert_eq!(
        rows[0].join(","),
        "mu0,attractor,regime,u0,dt,D,lle,se,n,merged,call,agrees,bracket,D_c_lo,D_c_hi,\
         D_c_zero,rest_pooled,rest_pooled_se,rest_slope,rest_slope_se,rest_decades,c,c_uncertainty"
    );
    let col = |name: &str| rows[0].iter().position(|c| c == name).unwrap();
    let number = |cell: &str| -> Option<f64> { (!cell.is_empty()).then(|| cell.parse().unwrap()) };
    let mut body = rows[1..].iter();
    let mut curves = 0;
    for r in doc["results"].as_array().unwrap() {
        for c in r["curves"].as_array().unwrap() {
            curves += 1;
            for q in c["points"].as_array().unwrap() {
                let row = body.next().expect("a row per point");
                assert_eq!(number(&row[col("mu0")]), r["value"].as_f64());
                assert_eq!(row[col("attractor")], c["attractor"].as_str().unwrap());
                assert_eq!(number(&row[col("D")]), q["d"].as_f64());
                assert_eq!(number(&row[col("lle")]), q["lle"].as_f64());
                assert_eq!(number(&row[col("se")]), q["se"].as_f64());
                assert_eq!(row[col("call")], q["call"].as_str().unwrap());
                assert_eq!(row[col("bracket")], c["bracket"]["kind"].as_str().unwrap());
                assert_eq!(number(&row[col("D_c_lo")]), c["bracket"]["lo"].as_f64());
                assert_eq!(number(&row[col("D_c_hi")]), c["bracket"]["hi"].as_f64());
                assert_eq!(number(&row[col("c")]), c["coefficient"].as_f64());
                let agrees = q["agrees"]
                    .as_bool()
                    .map(|a| a.to_string())
                    .unwrap_or_default();
                assert_eq!(row[col("agrees")], agrees);
            }
            // each curve's decision in words in the header
            let line = format!(
                "# mu0 = {}: {} (U(0) = ",
                r["value"].as_f64().unwrap(),
                c["attractor"].as_str().unwrap()
            );
            assert!(csv.contains(&line), "{line}");
            assert!(csv.contains(c["decision"].as_str().unwrap()));
        }
    }
    assert!(body.next().is_none());
    assert_eq!(curves, 6);
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
        (
            vec!["critical-noise", "--d-range", "2:1"],
            "--d-range: invalid parameter d_range = 1: allowed range is a high end in (2, ∞)",
        ),
        (
            vec!["critical-noise", "--d-range", "0:1"],
            "--d-range: invalid parameter d_range = 0: allowed range is a low end in (0, ∞)",
        ),
        (vec!["critical-noise", "--d-range", "0.1:x"], "--d-range"),
        (
            vec!["critical-noise", "--d-range", "0.1:1", "--points", "1"],
            "--points: invalid parameter points = 1: allowed range is 2 to 1000",
        ),
        (
            vec!["critical-noise", "--d-range", "0.1:1", "--points", "1.5"],
            "--points = 1.5: allowed range is 2 to 1000",
        ),
        (
            vec!["critical-noise", "--d-range", "1:1.001", "--points", "100"],
            "--points: invalid parameter points = 100: allowed range is fewer here",
        ),
        (
            vec!["critical-noise", "--noises", "0.1,0.05"],
            "--noises = 0.05: allowed range is above 0.1",
        ),
        (
            vec!["critical-noise", "--noises", "0,0.1"],
            "--noises = 0: allowed range is (0, ∞)",
        ),
        (vec!["critical-noise", "--noises", "0.1,abc"], "--noises"),
        (
            vec!["critical-noise", "--noises", "0.1", "--d-range", "0.1:1"],
            "--noises",
        ),
        (vec!["critical-noise"], "--d-range"),
        (
            vec!["critical-noise", "--noises", "0.1", "--points", "5"],
            "--points",
        ),
        (
            vec!["critical-noise", "--noises", "0.1", "--dt", "1"],
            "--dt",
        ),
        (
            vec!["critical-noise", "--noises", "0.1", "--paths", "0"],
            "--paths",
        ),
        (
            vec!["critical-noise", "--noises", "0.1", "--t-end", "100.003"],
            "--t-end",
        ),
        (
            vec!["critical-noise", "--d-range", "0.1:1", "--sweep", "D=0:1:2"],
            "--sweep",
        ),
        // the work is bounded before it starts: D values × parameter values × paths
        (
            vec![
                "critical-noise",
                "--d-range",
                "1e-6:10",
                "--points",
                "500",
                "--sweep",
                "mu0=0.01:0.02:1000",
                "--paths",
                "3",
            ],
            "--paths: invalid parameter paths = 3: allowed range is 1 to 2 here",
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
