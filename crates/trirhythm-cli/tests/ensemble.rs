//! `trirhythm ensemble`: the output contract, bad input, and a checkpointed run killed with
//! SIGINT and resumed, which must equal the uninterrupted run.

mod common;

use common::{ok_json, ok_stdout, run, scratch_dir};
use serde_json::Value;

#[test]
fn json_and_csv_keep_the_contract() {
    let v = ok_json(&[
        "ensemble",
        "--preset",
        "fig13a",
        "--paths",
        "3",
        "--t-end",
        "200",
        "--burn-in",
        "10",
    ]);
    for key in [
        "params",
        "method",
        "paths",
        "mean_u",
        "stationarity",
        "warnings",
        "amplitude",
        "joint",
        "theory",
    ] {
        assert!(v.get(key).is_some(), "missing {key}");
    }
    assert_eq!(v["paths"], 3);
    assert_eq!(v["steps_per_path"], 21000);
    assert!(v["wall_time_s"].as_f64().unwrap() >= 0.0);
    for m in ["mean_u", "var_u", "mean_v", "var_v"] {
        assert!(v[m]["value"].is_number(), "{m}");
        assert!(v[m]["stderr"].is_number(), "{m}");
    }
    assert!(v["stationarity"]["stationary"].is_boolean());
    assert!(v["stationarity"]["ess"].is_number());
    let pdf = &v["amplitude"];
    let n = pdf["density"].as_array().unwrap().len();
    assert_eq!(pdf["edges"].as_array().unwrap().len(), n + 1);
    assert_eq!(pdf["stderr"].as_array().unwrap().len(), n);
    assert!(v["joint"]["density"].is_array());
    for variant in ["paper", "consistent"] {
        let t = &v["theory"][variant];
        for key in ["hellinger", "l1", "ks"] {
            assert!(t[key]["value"].is_number(), "theory.{variant}.{key}");
        }
        assert!(
            t["hellinger"]["stderr"].is_number(),
            "theory.{variant}.hellinger.stderr"
        );
        for key in ["modes_theory", "modes_mc"] {
            assert!(t[key].is_number(), "theory.{variant}.{key}");
        }
    }
    // 200 time units cannot mix fig13a's wells: the run says so
    assert_eq!(v["stationarity"]["stationary"], false);
    assert!(v["warnings"]
        .as_array()
        .unwrap()
        .iter()
        .any(|w| w.as_str().unwrap().starts_with("not stationary")));

    let csv = ok_stdout(&[
        "ensemble",
        "--preset",
        "fig13a",
        "--paths",
        "2",
        "--t-end",
        "100",
        "--burn-in",
        "0",
        "--format",
        "csv",
        "--bins",
        "40",
    ]);
    let rows: Vec<&str> = csv.lines().filter(|l| !l.starts_with('#')).collect();
    assert_eq!(rows[0], "A_lo,A_hi,density,stderr");
    assert_eq!(rows.len(), 41);
    assert!(csv.contains("# stationarity: NOT STATIONARY"));
}

#[test]
fn bad_input_names_the_flag() {
    for (args, needle) in [
        (vec!["--paths", "0"], "paths = 0"),
        (vec!["--bins", "1"], "bins = 1"),
        (vec!["--t-end", "10.005"], "t_end = 10.005"),
        (vec!["--burn-in", "-1"], "burn_in = -1"),
        (vec!["--u0", "-2"], "u0 = -2"),
        (vec!["--amplitude-max", "0"], "amplitude_max = 0"),
        (vec!["--dt", "0"], "dt = 0"),
        (vec!["--amplitude-max", "1e300"], "amplitude_max = 1e300"),
        (vec!["--t-end", "inf"], "t_end = inf"),
        (vec!["--u0", "nan"], "u0 = NaN"),
        (
            vec!["--lanes", "3"],
            "--lanes = 3: allowed range is 1, 4 or 8",
        ),
        (
            vec!["--lanes", "-4"],
            "--lanes = -4: allowed range is 1, 4 or 8",
        ),
        // the statistics of every path are held until the merge: bounded before work starts
        (
            vec!["--paths", "1000000", "--joint-bins", "1000"],
            "paths = 1000000",
        ),
    ] {
        let mut a = vec!["ensemble", "--preset", "fig13a"];
        if args[0] != "--t-end" {
            a.extend(["--t-end", "100"]);
        }
        a.extend(args.iter());
        let out = run(&a);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{a:?}: {err}");
        assert!(err.contains(needle), "{a:?}: {err}");
    }
}

#[test]
fn the_well_method_keeps_the_document_and_adds_its_decomposition() {
    let base = [
        "ensemble",
        "--preset",
        "fig13a",
        "--param",
        "r=0.99",
        "--param",
        "D=0.2",
        "--method",
        "wells",
        "--paths",
        "2",
        "--t-end",
        "300",
        "--burn-in",
        "20",
        "--clones",
        "8",
        "--bins",
        "20",
        "--joint-bins",
        "4",
    ];
    let v = ok_json(&base);
    // the direct document's keys for the stationary mixture …
    for key in [
        "params",
        "method",
        "paths",
        "mean_u",
        "stationarity",
        "warnings",
        "amplitude",
        "joint",
        "theory",
        "occupancy",
        "wells",
    ] {
        assert!(v.get(key).is_some(), "missing {key}");
    }
    assert!(v["method"]
        .as_str()
        .unwrap()
        .contains("estimator=wells clones=8"));
    // … and the decomposition
    assert_eq!(v["estimator"], "wells");
    let d = &v["decomposition"];
    assert_eq!(d["rate_matrix"].as_array().unwrap().len(), 2);
    assert_eq!(d["weights"].as_array().unwrap().len(), 2);
    assert_eq!(d["replicas"].as_array().unwrap().len(), 2);
    assert_eq!(d["rates"].as_array().unwrap().len(), 2);
    assert!(d["valid"].is_boolean());
    assert!(d["cores"]["bounds"].is_array());
    let n = v["amplitude"]["density"].as_array().unwrap().len();
    assert_eq!(n, 20);
    // each replica's conditional counts: 2 replicas × 2 wells × (20 bins + beyond), summing to
    // each well's samples
    let counts = d["conditional_counts"].as_array().unwrap();
    assert_eq!(counts.len(), 2);
    for r in counts {
        let wells = r.as_array().unwrap();
        assert_eq!(wells.len(), 2);
        for c in wells {
            let c = c.as_array().unwrap();
            assert_eq!(c.len(), n + 1);
            assert!(c.iter().map(|x| x.as_u64().unwrap()).sum::<u64>() > 0);
        }
    }
    assert!(d["conditional_valid"].is_boolean());
    assert_eq!(d["rate_bounds"].as_array().unwrap().len(), 2);
    assert_eq!(d["conditional_ess"].as_array().unwrap().len(), 2);

    for (args, needle) in [
        (vec!["--clones", "1"], "clones = 1"),
        (vec!["--max-excursion", "0"], "max_excursion = 0"),
        (vec!["--core-quantile", "0.5"], "core_quantile = 0.5"),
        (vec!["--paths", "1"], "paths = 1"),
    ] {
        // the flag replaces the base's value
        let mut a: Vec<&str> = Vec::new();
        let mut k = 0;
        while k < base.len() {
            if base[k] == args[0] {
                k += 2;
                continue;
            }
            a.push(base[k]);
            k += 1;
        }
        a.extend(args.iter());
        let out = run(&a);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{a:?}: {err}");
        assert!(err.contains(needle), "{a:?}: {err}");
    }
    // one well has no rates to split: the method runs and reports weight 1
    let v = ok_json(&[
        "ensemble",
        "--preset",
        "fig13a",
        "--param",
        "r=0.84",
        "--method",
        "wells",
        "--paths",
        "2",
        "--t-end",
        "200",
        "--burn-in",
        "10",
        "--bins",
        "20",
        "--joint-bins",
        "4",
    ]);
    assert_eq!(v["decomposition"]["weights"][0]["value"], 1.0);
}

fn without_wall_time(mut v: Value) -> Value {
    v["wall_time_s"] = Value::Null;
    v
}

/// Paths stepped one by one, in lanes of 4 and of 8: the same document, number for number.
#[test]
fn every_lane_count_gives_the_same_result() {
    let run = |lanes: &str| {
        without_wall_time(ok_json(&[
            "ensemble",
            "--preset",
            "fig13a",
            "--paths",
            "6",
            "--t-end",
            "100",
            "--burn-in",
            "10",
            "--lanes",
            lanes,
        ]))
    };
    let one = run("1");
    assert_eq!(one["paths"], 6);
    assert_eq!(one, run("4"));
    assert_eq!(one, run("8"));
}

#[cfg(unix)]
#[test]
fn a_killed_checkpointed_run_resumes_to_the_same_result() {
    use std::process::{Command, Stdio};
    use std::time::{Duration, Instant};
    let dir = scratch_dir("checkpoint");
    let cp = dir.join("cp");
    let base = [
        "ensemble",
        "--preset",
        "fig13a",
        "--paths",
        "6",
        "--t-end",
        "20000",
        "--burn-in",
        "0",
        "--seed",
        "3",
    ];
    let whole = without_wall_time(ok_json(&base));
    let mut with_cp: Vec<&str> = base.to_vec();
    with_cp.extend(["--checkpoint", cp.to_str().unwrap()]);
    let child = Command::new(env!("CARGO_BIN_EXE_trirhythm"))
        .args(&with_cp)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let saved = || {
        std::fs::read_dir(&cp).map_or(0, |d| {
            d.filter(|e| {
                let n = e.as_ref().unwrap().file_name();
                let n = n.to_string_lossy();
                n.starts_with("path-") && n.ends_with(".json")
            })
            .count()
        })
    };
    let t = Instant::now();
    while saved() == 0 && t.elapsed() < Duration::from_secs(60) {
        std::thread::sleep(Duration::from_millis(5));
    }
    let status = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(status.success());
    let out = child.wait_with_output().unwrap();
    let done = saved();
    assert_eq!(out.status.code(), Some(130), "interrupted run");
    assert!((1..6).contains(&done), "{done} paths saved before the kill");
    let resumed = without_wall_time(ok_json(&with_cp));
    assert_eq!(whole, resumed, "resumed after {done} saved paths");
    // a different run refuses the directory
    let mut other = with_cp.clone();
    other[8] = "4";
    let out = run(&other);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("holds another run"));
    let _ = std::fs::remove_dir_all(&dir);
}
