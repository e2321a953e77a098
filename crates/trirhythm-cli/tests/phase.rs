//! `trirhythm phase-response` from the outside: the JSON and CSV contracts, white noise with
//! impacts said plainly (no number), a start that reaches rest refused (exit 2), bad flags
//! refused naming the flag.

mod common;

use common::{csv_rows, ok_json, ok_stdout as ok, run};

const FAST: [&str; 8] = [
    "--preset",
    "fig17a",
    "--param",
    "mu0=0.01",
    "--phases",
    "16",
    "--periods",
    "9",
];

#[test]
fn json_has_the_cycle_omega_and_the_coefficient() {
    let mut args = vec!["phase-response", "--format", "json"];
    args.extend(FAST);
    let j = ok_json(&args);
    assert_eq!(j["cycle"]["name"], "outer");
    assert_eq!(j["section"], "impact");
    assert_eq!(j["impact_memory"], "restart");
    let omega = j["omega"].as_f64().unwrap();
    assert!((omega - 1.776).abs() < 0.01, "{omega}");
    let c = j["coefficient"].as_f64().unwrap();
    assert!((c - 0.01304).abs() < 0.001, "{c}");
    assert!(j["uncertainty"].as_f64().unwrap() < 0.1 * c);
    assert_eq!(j["samples"].as_array().unwrap().len(), 16);
}

#[test]
fn csv_has_z_at_each_phase_and_the_summary_in_its_header() {
    let mut args = vec!["phase-response", "--format", "csv"];
    args.extend(FAST);
    let text = ok(&args);
    assert!(text.lines().any(|l| l.starts_with("# c = ")), "{text}");
    let rows = csv_rows(&text);
    assert_eq!(rows[0], ["theta", "z", "z_double", "extrapolation"]);
    assert_eq!(rows.len(), 17);
}

#[test]
fn white_noise_with_impacts_has_no_coefficient() {
    let mut args = vec!["phase-response", "--param", "tau=0"];
    args.extend(FAST);
    let text = ok(&args);
    assert!(text.contains("c undefined: white noise"), "{text}");
}

#[test]
fn a_start_at_rest_and_bad_flags_are_refused() {
    let out = run(&[
        "phase-response",
        "--preset",
        "fig18b",
        "--param",
        "r=0.9",
        "--u0",
        "1",
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("rest"));
    for (flag, value) in [("--phases", "7"), ("--periods", "2"), ("--dt", "0.5")] {
        let out = run(&["phase-response", flag, value]);
        assert_eq!(out.status.code(), Some(2), "{flag}");
        assert!(
            String::from_utf8_lossy(&out.stderr).contains(flag),
            "{flag}"
        );
    }
}
