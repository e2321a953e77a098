//! `trirhythm oscillation` from the outside: the CSV and JSON contracts, the exact boundary
//! inside the simulated bracket, `--grid`, and bad input (exit 2 naming the flag and its range).

mod common;

use common::{ok_stdout as ok, run};
use serde_json::Value;

#[test]
fn csv_rows_are_method_x_y_bracket_and_the_exact_boundary_is_bracketed() {
    let text = ok(&[
        "oscillation",
        "--preset",
        "fig15",
        "--param",
        "lambda=1",
        "--x",
        "r=0.9:0.95:2",
        "--y",
        "mu0=0.001:0.3",
    ]);
    let rows: Vec<Vec<&str>> = text
        .lines()
        .filter(|l| !l.starts_with('#'))
        .map(|l| l.split(',').collect())
        .collect();
    assert_eq!(rows[0], ["method", "x", "y", "y_lo", "y_hi"]);
    let get = |m: &str, x: &str| -> Vec<f64> {
        let r = rows.iter().find(|r| r[0] == m && r[1] == x).unwrap();
        r[2..].iter().map(|v| v.parse().unwrap()).collect()
    };
    for x in ["0.9", "0.95"] {
        let sim = get("simulation", x);
        let exact = get("exact", x);
        let avg = get("averaging", x);
        assert!(sim[1] <= sim[0] && sim[0] <= sim[2]);
        assert!((sim[2] - sim[1]) <= 1e-3 * sim[0] * 1.000001);
        assert!(sim[1] - 2e-4 * exact[0] <= exact[0] && exact[0] <= sim[2] + 2e-4 * exact[0]);
        assert_eq!(avg[1], avg[0]);
        assert_eq!(avg[2], avg[0]);
    }
    assert!(text.contains("# simulations: "));
}

#[test]
fn json_has_parameters_simulations_and_sides() {
    let text = ok(&[
        "oscillation",
        "--preset",
        "fig16",
        "--x",
        "lambda=0.99:0.99:1",
        "--y",
        "mu0=0.001:0.2",
        "--format",
        "json",
    ]);
    let v: Value = serde_json::from_str(&text).unwrap();
    assert_eq!(v["params"]["r"], 0.99);
    assert!(v["simulations"].as_u64().unwrap() >= 3);
    let b = v["boundaries"].as_array().unwrap();
    assert_eq!(b.len(), 3);
    assert_eq!(b[0]["method"], "simulation");
    assert_eq!(b[0]["points"][0]["side"], "boundary");
    // the exact linearisation with the wall is known at λ = 1 only
    assert_eq!(b[2]["points"][0]["side"], "unavailable");
    assert_eq!(b[2]["points"][0]["y"], "NaN");
}

#[test]
fn grid_mode_classifies_the_plane() {
    let text = ok(&[
        "oscillation",
        "--preset",
        "fig15",
        "--param",
        "lambda=1",
        "--x",
        "r=0.9:0.95:2",
        "--y",
        "mu0=0.01:0.1:4",
        "--grid",
    ]);
    let rows: Vec<&str> = text.lines().filter(|l| !l.starts_with('#')).collect();
    assert_eq!(rows[0], "x,y,oscillates");
    assert_eq!(rows.len(), 1 + 8);
    // r = 0.9: exact boundary 0.0603; μ0 = 0.01 rests, 0.1 oscillates
    assert!(rows.contains(&"0.9,0.01,0") && rows.contains(&"0.9,0.1,1"));
}

#[test]
fn bad_input_exits_2_naming_the_flag_and_its_range() {
    for (args, needle) in [
        (
            vec!["--tolerance", "0"],
            "--tolerance = 0: allowed range is (0, 0.1]",
        ),
        (vec!["--dt", "1"], "--dt = 1: allowed range is [1e-4, 0.1]"),
        (
            vec!["--lanes", "0"],
            "--lanes = 0: allowed range is 1, 4 or 8",
        ),
        (vec!["--x", "r=0.9:0.95:0"], "--x: COUNT"),
        (
            vec!["--x", "r=0.9:0.95:1"],
            "START = 0.9 and STOP = 0.95 must be equal",
        ),
        (vec!["--y", "mu0=0.3:0.001"], "--y"),
        (vec!["--y", "r=0.1:0.5"], "same parameter"),
        (vec!["--param", "D=0.1"], "D = 0"),
        (vec!["--x", "lambda=0.5:1.5:3"], "lambda"),
        (
            vec!["--grid", "--method", "all", "--y", "mu0=0.01:0.1:3"],
            "--method all",
        ),
    ] {
        let mut full = vec!["oscillation", "--preset", "fig15"];
        if !args.contains(&"--x") {
            full.extend(["--x", "r=0.9:0.95:2"]);
        }
        if !args.contains(&"--y") {
            full.extend(["--y", "mu0=0.001:0.3"]);
        }
        full.extend(args.iter().copied());
        let out = run(&full);
        assert_eq!(out.status.code(), Some(2), "{full:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(needle), "{full:?}: {err}");
    }
}

/// The simulated boundary and the classified grid are the same with the simulations in lanes
/// and one after the other (`--lanes`).
#[test]
fn every_lane_count_gives_the_same_output() {
    for grid in [false, true] {
        let run = |lanes: &str| {
            let mut args = vec![
                "oscillation",
                "--preset",
                "fig15",
                "--x",
                "lambda=0.95:1:3",
                "--method",
                "simulation",
                "--lanes",
                lanes,
            ];
            if grid {
                args.extend(["--grid", "--y", "mu0=0.001:0.1:6"]);
            } else {
                args.extend(["--y", "mu0=0.001:0.3"]);
            }
            ok(&args)
        };
        let one = run("1");
        assert!(
            one.lines().filter(|l| !l.starts_with('#')).count() > 3,
            "{one}"
        );
        assert_eq!(one, run("4"), "grid {grid}");
        assert_eq!(one, run("8"), "grid {grid}");
    }
}
