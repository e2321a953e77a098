//! The theory commands from the outside: outputs parse, bad input exits 2 naming the parameter,
//! no partial files.

mod common;

use common::{ok_json, ok_stdout, run, scratch_dir};
use serde_json::Value;

/// Rows of a successful run's CSV output, header first.
fn csv_rows(args: &[&str]) -> Vec<Vec<String>> {
    common::csv_rows(&ok_stdout(args))
}

/// Rows of a CSV output (comments skipped), header first.

#[test]
fn cycles_json_lists_the_five_cycles_of_fig4c_at_r1() {
    let v = ok_json(&[
        "cycles", "--preset", "fig4c", "--param", "r=1", "--format", "json",
    ]);
    let cycles = v["cycles"].as_array().unwrap();
    assert_eq!(cycles.len(), 5);
    let stable: Vec<f64> = cycles
        .iter()
        .filter(|c| c["stable"].as_bool().unwrap())
        .map(|c| c["amplitude"].as_f64().unwrap())
        .collect();
    for (got, want) in stable.iter().zip([1.90, 8.21, 12.93]) {
        assert!((got - want).abs() < 0.005, "{got} vs {want}");
    }
    assert_eq!(v["stable_count"], 3);
    assert_eq!(v["rhythmicity"], "trirhythmic");
    assert_eq!(v["variant"], "paper");
    assert_eq!(v["params"]["r"], 1.0);
    assert!(v["equivalents"]["mu1"].as_f64().unwrap() > 0.0);
}

#[test]
fn equivalents_in_every_format() {
    let v = ok_json(&["equivalents", "--param", "lambda=0.998", "--format", "json"]);
    assert!((v["equivalents"]["beta1"].as_f64().unwrap() - 0.685841251412).abs() < 1e-9);
    let rows = csv_rows(&["equivalents", "--format", "csv"]);
    assert_eq!(rows[0], ["name", "value"]);
    assert!(rows.iter().any(|r| r[0] == "omega1"));
    let out = run(&["equivalents"]);
    assert!(out.status.success() && String::from_utf8_lossy(&out.stdout).contains("beta2"));
}

#[test]
fn drift_and_potential_grids_parse_and_agree() {
    let f = csv_rows(&["drift", "--grid", "0.5:14:1351", "--format", "csv"]);
    assert_eq!(&f[0][..2], ["A", "f"]);
    assert_eq!(f.len(), 1352);
    let u = csv_rows(&["potential", "--grid", "0.5:14:1351", "--format", "csv"]);
    assert_eq!(&u[0][..2], ["A", "U_eff"]);
    // D = 0: dU_eff/dA = −f; check with a centred difference on neighbouring rows.
    let num = |r: &Vec<String>, i: usize| r[i].parse::<f64>().unwrap();
    for i in 2..1351 {
        let h = num(&u[i + 1], 0) - num(&u[i - 1], 0);
        let du = (num(&u[i + 1], 1) - num(&u[i - 1], 1)) / h;
        let f_i = num(&f[i], 1);
        // Centred-difference error h²f‴/6 ≲ 1e-5 on this grid (h = 0.01).
        assert!(
            (du + f_i).abs() < 1e-4 + 1e-3 * f_i.abs(),
            "row {i}: {du} vs {}",
            -f_i
        );
    }
}

#[test]
fn barriers_of_fig8_are_four() {
    let v = ok_json(&["barriers", "--preset", "fig8", "--format", "json"]);
    let b = v["barriers"].as_array().unwrap();
    assert_eq!(b.len(), 4);
    assert_eq!(b[0]["name"], "dU1");
    assert!(b.iter().all(|x| x["height"].as_f64().unwrap() > 0.0));
}

#[test]
fn pdf_kinds_parse() {
    let v = ok_json(&[
        "pdf",
        "--preset",
        "fig13a",
        "--kind",
        "amplitude",
        "--format",
        "json",
    ]);
    assert_eq!(v["modes"].as_array().unwrap().len(), 3);
    assert_eq!(v["antimodes"].as_array().unwrap().len(), 2);
    assert!((v["mean_amplitude"].as_f64().unwrap() - 10.4557038345).abs() < 1e-8);
    let a = v["A"].as_array().unwrap();
    let p = v["p"].as_array().unwrap();
    assert_eq!(a.len(), p.len());
    let e = csv_rows(&[
        "pdf", "--preset", "fig13a", "--kind", "energy", "--grid", "0:100:11", "--format", "csv",
    ]);
    assert_eq!(e[0], ["H", "p", "log_p"]);
    assert_eq!(e.len(), 12);
    let j = csv_rows(&[
        "pdf", "--preset", "fig14", "--kind", "joint", "--grid", "0:12:5", "--vgrid", "-12:12:7",
        "--format", "csv",
    ]);
    assert_eq!(&j[0][..3], ["U", "V", "p"]);
    assert_eq!(j.len(), 1 + 5 * 7);
}

fn assert_bad(args: &[&str], needles: &[&str]) {
    let out = run(args);
    assert_eq!(out.status.code(), Some(2), "{args:?}");
    let err = String::from_utf8_lossy(&out.stderr);
    for n in needles {
        assert!(err.contains(n), "{args:?}: `{err}` lacks `{n}`");
    }
}

#[test]
fn bad_input_exits_2_naming_the_parameter() {
    assert_bad(
        &["cycles", "--param", "lambda=1.5"],
        &["lambda", "1.5", "(0, 1]"],
    );
    assert_bad(&["cycles", "--param", "r=-0.1"], &["r", "-0.1", "[0, 1]"]);
    assert_bad(&["cycles", "--param", "mu0=0"], &["mu0", "0"]);
    assert_bad(&["cycles", "--param", "D=nan"], &["D", "NaN"]);
    assert_bad(&["cycles", "--param", "omega=1"], &["omega", "mu0"]);
    assert_bad(&["cycles", "--param", "lambda"], &["KEY=VALUE"]);
    assert_bad(&["cycles", "--param", "lambda=abc"], &["lambda", "abc"]);
    assert_bad(&["cycles", "--preset", "fig99"], &["fig99", "fig4c"]);
    assert_bad(&["drift", "--grid", "5:1:10"], &["--grid", "START"]);
    assert_bad(&["drift", "--grid", "-1:1:10"], &["--grid", "≥ 0"]);
    assert_bad(&["pdf", "--param", "D=0"], &["D = 0"]);
    assert_bad(
        &["cycles", "--variant", "consistent", "--param", "r=0"],
        &["r", "consistent"],
    );
    assert_bad(&["figure", "99"], &["figure 99"]);
    assert_bad(&["cycles", "--format", "xml"], &["xml"]);
}

#[test]
fn no_partial_file_on_error_and_atomic_write_on_success() {
    let d = scratch_dir("atomic");
    let target = d.join("cycles.json");
    let out = run(&[
        "cycles",
        "--param",
        "lambda=2",
        "--format",
        "json",
        "--out",
        target.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        std::fs::read_dir(&d).unwrap().next().is_none(),
        "nothing written on error"
    );
    let out = run(&[
        "cycles",
        "--format",
        "json",
        "--out",
        target.to_str().unwrap(),
    ]);
    assert!(out.status.success());
    let v: Value = serde_json::from_str(&std::fs::read_to_string(&target).unwrap()).unwrap();
    assert_eq!(v["cycles"].as_array().unwrap().len(), 5);
    assert_eq!(
        std::fs::read_dir(&d).unwrap().count(),
        1,
        "no temporary file left"
    );
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn figures_4_7_8_write_csv_png_svg() {
    let d = scratch_dir("figures");
    for n in ["4", "7", "8"] {
        let out = run(&["figure", n, "--quick", "--out-dir", d.to_str().unwrap()]);
        assert!(
            out.status.success(),
            "figure {n}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        let stem = d.join(format!("fig{:02}", n.parse::<u32>().unwrap()));
        let csv = std::fs::read_to_string(stem.with_extension("csv")).unwrap();
        assert!(csv.starts_with(&format!("# trirhythm figure {n}")));
        assert!(
            csv.lines().any(|l| l.starts_with("# panel")),
            "parameters in the header"
        );
        let png = std::fs::read(stem.with_extension("png")).unwrap();
        assert_eq!(&png[1..4], b"PNG");
        let svg = std::fs::read_to_string(stem.with_extension("svg")).unwrap();
        assert!(svg.contains("<svg") && svg.contains("A0"));
    }
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn json_writes_a_limit_as_the_library_does() {
    // U_eff(0) = +∞ with noise: the string "inf", as in every JSON document the tool writes
    // (figure data included), never `null`
    let v = ok_json(&[
        "potential",
        "--grid",
        "0:1:3",
        "--param",
        "D=0.1",
        "--format",
        "json",
    ]);
    assert_eq!(v["U_eff"][0], "inf");
    assert!(v["U_eff"][1].as_f64().unwrap().is_finite());
}
