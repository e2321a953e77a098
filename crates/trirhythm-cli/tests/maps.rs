//! The bifurcation commands from the outside: `map` and `branches` outputs parse and agree with
//! `cycles` point by point, fold curves come out as JSON or a second CSV, bad input exits 2
//! naming the parameter, and the map figures write their files.

mod common;

use common::{csv_rows as rows, ok_stdout as ok, run, scratch_dir};
use serde_json::Value;

/// Stable count reported by `cycles` at one parameter point.
fn stable_count(preset: &str, extra: &[(&str, f64)]) -> u64 {
    let mut args = vec![
        "cycles".to_string(),
        "--preset".into(),
        preset.into(),
        "--format".into(),
        "json".into(),
    ];
    for (k, v) in extra {
        args.push("--param".into());
        args.push(format!("{k}={v}"));
    }
    let a: Vec<&str> = args.iter().map(String::as_str).collect();
    let v: Value = serde_json::from_str(&ok(&a)).unwrap();
    v["stable_count"].as_u64().unwrap()
}

#[test]
fn map_csv_has_every_point_and_agrees_with_cycles() {
    let text = ok(&[
        "map",
        "--preset",
        "fig2ii",
        "--x",
        "gamma0=2e-5:1e-4:9",
        "--y",
        "delta0=2e-8:4e-7:7",
        "--format",
        "csv",
    ]);
    let r = rows(&text);
    assert_eq!(r[0], ["x", "y", "count"]);
    assert_eq!(r.len() - 1, 9 * 7);
    let mut seen = std::collections::BTreeSet::new();
    for row in r.iter().skip(1).step_by(5) {
        let (x, y): (f64, f64) = (row[0].parse().unwrap(), row[1].parse().unwrap());
        let c: u64 = row[2].parse().unwrap();
        assert_eq!(
            c,
            stable_count("fig2ii", &[("gamma0", x), ("delta0", y)]),
            "{row:?}"
        );
        seen.insert(c);
    }
    assert!(
        seen.len() >= 2,
        "the sample should cross a boundary: {seen:?}"
    );
}

#[test]
fn modes_map_agrees_with_cycles_with_noise() {
    let text = ok(&[
        "map",
        "--preset",
        "fig12a",
        "--x",
        "mu0=0.005:0.1:5",
        "--y",
        "r=0.8:1:4",
        "--what",
        "modes",
        "--format",
        "csv",
    ]);
    for row in rows(&text).iter().skip(1) {
        let (x, y): (f64, f64) = (row[0].parse().unwrap(), row[1].parse().unwrap());
        let c: u64 = row[2].parse().unwrap();
        assert_eq!(
            c,
            stable_count("fig12a", &[("mu0", x), ("r", y)]),
            "{row:?}"
        );
    }
}

#[test]
fn fold_curves_in_json_end_at_the_analytic_cusp() {
    let text = ok(&[
        "map",
        "--preset",
        "fig2i",
        "--x",
        "alpha0=0.04:0.24:61",
        "--y",
        "beta0=0.0005:0.0105:61",
        "--folds",
        "--format",
        "json",
    ]);
    let v: Value = serde_json::from_str(&text).unwrap();
    assert_eq!(v["counts"].as_array().unwrap().len(), 61);
    let cusps = v["folds"]["cusps"].as_array().unwrap();
    assert_eq!(cusps.len(), 1);
    let (x, y) = (
        cusps[0]["x"].as_f64().unwrap(),
        cusps[0]["y"].as_f64().unwrap(),
    );
    assert!(
        (x - 1.0 / 6.0).abs() < 1e-7 && (y - 1.0 / 135.0).abs() < 1e-9,
        "{x} {y}"
    );
    let curves = v["folds"]["curves"].as_array().unwrap();
    assert_eq!(curves.len(), 2);
    for c in curves {
        let ends = [c["start"].as_str().unwrap(), c["end"].as_str().unwrap()];
        assert!(
            ends.contains(&"cusp") && ends.contains(&"border"),
            "{ends:?}"
        );
        // A fold point is a double root: just off the curve on one side `cycles` reports two
        // cycles close to the curve's amplitude.
        let mid = &c["points"].as_array().unwrap()[c["points"].as_array().unwrap().len() / 2];
        let (a0, b0, amp) = (
            mid["x"].as_f64().unwrap(),
            mid["y"].as_f64().unwrap(),
            mid["amplitude"].as_f64().unwrap(),
        );
        let mut near = 0;
        for shift in [1.0 + 1e-7, 1.0 - 1e-7] {
            let out = ok(&[
                "cycles",
                "--preset",
                "fig2i",
                "--param",
                &format!("alpha0={a0}"),
                "--param",
                &format!("beta0={}", b0 * shift),
                "--format",
                "json",
            ]);
            let cy: Value = serde_json::from_str(&out).unwrap();
            let n = cy["cycles"]
                .as_array()
                .unwrap()
                .iter()
                .filter(|c| (c["amplitude"].as_f64().unwrap() - amp).abs() < 2e-2 * amp)
                .count();
            near = near.max(n);
        }
        assert_eq!(near, 2, "no pair of cycles near the fold amplitude {amp}");
    }
}

#[test]
fn folds_go_to_a_second_csv_next_to_out() {
    let d = scratch_dir("folds");
    let out = d.join("m.csv");
    ok(&[
        "map",
        "--preset",
        "fig2ii",
        "--x",
        "gamma0=2e-5:1e-4:41",
        "--y",
        "delta0=2e-8:4e-7:41",
        "--folds",
        "--format",
        "csv",
        "--out",
        out.to_str().unwrap(),
    ]);
    let folds = std::fs::read_to_string(d.join("m-folds.csv")).unwrap();
    let r = rows(&folds);
    assert_eq!(r[0], ["curve", "system", "x", "y", "amplitude"]);
    assert!(r.len() > 50);
    assert!(r.iter().skip(1).all(|row| row[1] == "drift"));
    let map = rows(&std::fs::read_to_string(&out).unwrap());
    assert_eq!(map.len() - 1, 41 * 41);
    // CSV with folds on standard output has nowhere to put the curves.
    let e = run(&[
        "map",
        "--x",
        "gamma0=2e-5:1e-4:5",
        "--y",
        "delta0=2e-8:4e-7:5",
        "--folds",
        "--format",
        "csv",
    ]);
    assert_eq!(e.status.code(), Some(2));
}

#[test]
fn branches_cross_each_r_at_every_cycle() {
    let text = ok(&[
        "branches", "--preset", "fig5", "--param", "mu0=0.01", "--x", "r=0.8:1", "--format", "csv",
    ]);
    assert!(text.contains("# fold: r = "), "{text}");
    let r = rows(&text);
    assert_eq!(r[0], ["branch", "param", "amplitude", "stable"]);
    let pts: Vec<(usize, f64, f64, bool)> = r
        .iter()
        .skip(1)
        .map(|row| {
            (
                row[0].parse().unwrap(),
                row[1].parse().unwrap(),
                row[2].parse().unwrap(),
                row[3] == "1",
            )
        })
        .collect();
    for rv in [0.83, 0.9, 0.95, 0.975, 0.99] {
        let mut got = Vec::new();
        for w in pts.windows(2) {
            if w[0].0 == w[1].0 && (w[0].1 - rv) * (w[1].1 - rv) <= 0.0 && w[0].1 != w[1].1 {
                let t = (rv - w[0].1) / (w[1].1 - w[0].1);
                got.push((
                    (w[0].2.powi(2) + t * (w[1].2.powi(2) - w[0].2.powi(2))).sqrt(),
                    w[0].3,
                ));
            }
        }
        got.sort_by(|a, b| a.0.total_cmp(&b.0));
        let cy: Value = serde_json::from_str(&ok(&[
            "cycles",
            "--preset",
            "fig5",
            "--param",
            "mu0=0.01",
            "--param",
            &format!("r={rv}"),
            "--format",
            "json",
        ]))
        .unwrap();
        let want: Vec<(f64, bool)> = cy["cycles"]
            .as_array()
            .unwrap()
            .iter()
            .map(|c| {
                (
                    c["amplitude"].as_f64().unwrap(),
                    c["stable"].as_bool().unwrap(),
                )
            })
            .collect();
        assert_eq!(got.len(), want.len(), "r = {rv}: {got:?} vs {want:?}");
        for (g, w) in got.iter().zip(&want) {
            assert!(
                (g.0 - w.0).abs() < 5e-3 * w.0 && g.1 == w.1,
                "r = {rv}: {g:?} vs {w:?}"
            );
        }
    }
}

#[test]
fn bad_input_exits_2_naming_the_parameter() {
    let cases: [(&[&str], &str); 6] = [
        (
            &["map", "--x", "lambda=0.9:1.2:10", "--y", "r=0.9:1:10"],
            "lambda",
        ),
        (
            &["map", "--x", "bogus=0:1:10", "--y", "r=0.9:1:10"],
            "bogus",
        ),
        (&["map", "--x", "gamma0", "--y", "r=0.9:1:10"], "--x"),
        (&["map", "--x", "r=0.9:1:1", "--y", "mu0=0.1:1:10"], "COUNT"),
        (
            &[
                "map",
                "--x",
                "r=0.9:1:5",
                "--y",
                "mu0=0.1:1:5",
                "--what",
                "modes",
            ],
            "D",
        ),
        (&["branches", "--x", "r=0.8:1.5"], "r"),
    ];
    for (args, name) in cases {
        let out = run(args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(name), "{args:?}: {err}");
    }
    // No partial file on failure.
    let d = scratch_dir("bad");
    let f = d.join("x.csv");
    let out = run(&[
        "map",
        "--x",
        "lambda=0.9:1.2:10",
        "--y",
        "r=0.9:1:10",
        "--out",
        f.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(std::fs::read_dir(&d).unwrap().count(), 0);
}

#[test]
fn map_figures_write_data_and_pictures() {
    let d = scratch_dir("figs");
    for n in ["2", "5", "10"] {
        let text = ok(&["figure", n, "--quick", "--out-dir", d.to_str().unwrap()]);
        let stem = format!("fig{:02}", n.parse::<u32>().unwrap());
        for ext in ["csv", "png", "svg"] {
            let p = d.join(format!("{stem}.{ext}"));
            assert!(text.contains(p.to_str().unwrap()), "{text}");
            assert!(
                std::fs::metadata(&p).unwrap().len() > 1000,
                "{}",
                p.display()
            );
        }
        let csv = std::fs::read_to_string(d.join(format!("{stem}.csv"))).unwrap();
        assert!(csv.starts_with(&format!("# trirhythm figure {n}:")));
        assert!(csv.contains("# note:"));
    }
    // The P-bifurcation figure names the printed Eq. 37 curves and the chosen r.
    let f10 = std::fs::read_to_string(d.join("fig10.csv")).unwrap();
    assert!(f10.contains("printed Eq. 36-37"));
    assert!(f10.contains("r = 0.998"));
    let folds = rows(&std::fs::read_to_string(d.join("fig10_folds.csv")).unwrap());
    assert!(folds
        .iter()
        .any(|r| r.get(2).map(String::as_str) == Some("fpk-printed")));
    assert!(folds
        .iter()
        .any(|r| r.get(2).map(String::as_str) == Some("fpk")));
}

/// `map --simulate` on Fig. 12(d)'s set at λ = 1, white noise, μ0 = 0.01, around r = 0.95,
/// D = 1: the theory has two modes there and the paths hop between them.
const SIMULATED: &[&str] = &[
    "map",
    "--simulate",
    "--preset",
    "fig12d",
    "--param",
    "lambda=1",
    "--param",
    "tau=0",
    "--param",
    "mu0=0.01",
    "--x",
    "r=0.95:0.951:2",
    "--y",
    "D=1:1.01:2",
    "--paths",
    "8",
    "--t-end",
    "20000",
    "--burn-in",
    "200",
    "--dt",
    "0.05",
    "--batches",
    "10",
    "--seed",
    "3",
];

#[test]
fn simulated_map_counts_two_modes_beside_the_theory_in_csv_and_json() {
    let mut csv_args = SIMULATED.to_vec();
    csv_args.extend(["--format", "csv"]);
    let text = ok(&csv_args);
    assert!(
        text.contains("# rule: a mode dips more than z = 3"),
        "{text}"
    );
    let r = rows(&text);
    assert_eq!(
        r[0],
        [
            "x",
            "y",
            "theory",
            "simulated",
            "low",
            "high",
            "agreement",
            "stationary",
            "beyond"
        ]
    );
    assert_eq!(r.len(), 5);
    // the theory's column is `map --what modes` at the same points
    let theory = rows(&ok(&[
        "map",
        "--preset",
        "fig12d",
        "--param",
        "lambda=1",
        "--param",
        "tau=0",
        "--param",
        "mu0=0.01",
        "--x",
        "r=0.95:0.951:2",
        "--y",
        "D=1:1.01:2",
        "--what",
        "modes",
        "--format",
        "csv",
    ]));
    let mut json_args = SIMULATED.to_vec();
    json_args.extend(["--format", "json"]);
    let doc: Value = serde_json::from_str(&ok(&json_args)).unwrap();
    let points = doc["points"].as_array().unwrap();
    assert_eq!(points.len(), 4);
    assert!(doc["method"].as_str().unwrap().contains("dt=0.05"));
    for ((row, th), p) in r.iter().skip(1).zip(theory.iter().skip(1)).zip(points) {
        assert_eq!(row[..2], th[..2]);
        assert_eq!(row[2], th[2], "theory's count");
        assert_eq!(row[2], "2");
        assert_eq!(row[3..6], ["2", "2", "2"], "{row:?}");
        let expected = if row[7] == "true" {
            "agree"
        } else {
            "non_stationary"
        };
        assert_eq!(row[6], expected);
        // the JSON holds the same numbers (the same seeds: the same bits)
        assert_eq!(p["simulated"]["count"].as_u64(), Some(2));
        assert_eq!(p["agreement"].as_str(), Some(expected));
        assert_eq!(p["stationary"].as_bool(), Some(row[7] == "true"));
        assert_eq!(p["amplitude"]["density"].as_array().unwrap().len(), 40);
    }
}

#[test]
fn simulated_map_refuses_bad_input_by_name_before_any_work() {
    let plane = ["--preset", "fig12d", "--x", "r=0.9:1:3", "--y", "D=0.1:1:3"];
    let with = |extra: &[&'static str]| {
        let mut a = vec!["map"];
        a.extend(plane);
        a.extend(extra);
        a
    };
    let cases: Vec<(Vec<&str>, &str)> = vec![
        // the simulation's options without --simulate, the folds with it
        (
            with(&["--paths", "4"]),
            "--paths applies to --simulate only",
        ),
        (with(&["--simulate", "--folds"]), "--folds applies to"),
        (
            with(&["--simulate", "--what", "rhythmicity"]),
            "--what rhythmicity",
        ),
        // the work sized first
        (
            with(&["--simulate", "--t-end", "1e6", "--paths", "1000"]),
            "--max-path-steps = 20000000000: this map takes",
        ),
        (with(&["--simulate", "--z", "1"]), "--z"),
        (with(&["--simulate", "--batches", "2"]), "--batches"),
        (
            vec![
                "map",
                "--simulate",
                "--preset",
                "fig12d",
                "--param",
                "D=0",
                "--x",
                "r=0.9:1:3",
                "--y",
                "mu0=0.01:0.02:3",
            ],
            "D = 0",
        ),
    ];
    for (args, needle) in cases {
        let out = run(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(needle), "{args:?}: {err}");
    }
}

/// A tiny simulated map for its picture: [`SIMULATED`] on 2 × 2 points around r = 0.95,
/// D = 1, two short paths each, as CSV.
fn tiny() -> Vec<&'static str> {
    let mut a = SIMULATED.to_vec();
    for (flag, value) in [
        ("--x", "r=0.95:0.96:2"),
        ("--y", "D=1:1.1:2"),
        ("--paths", "2"),
        ("--t-end", "200"),
        ("--burn-in", "20"),
        ("--batches", "4"),
    ] {
        let i = a.iter().position(|&f| f == flag).unwrap();
        a[i + 1] = value;
    }
    a.extend(["--format", "csv"]);
    a
}

/// The width and height a PNG's header gives.
fn png_size(bytes: &[u8]) -> (u32, u32) {
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "not a PNG");
    assert_eq!(&bytes[12..16], b"IHDR");
    let be = |i: usize| u32::from_be_bytes(bytes[i..i + 4].try_into().unwrap());
    (be(16), be(20))
}

/// The number after `name=\"` in an SVG's opening tag.
fn svg_attribute(svg: &str, name: &str) -> f64 {
    let open = &svg[svg.find("<svg").unwrap()..];
    let open = &open[..open.find('>').unwrap()];
    let at = open.find(&format!(" {name}=\"")).unwrap() + name.len() + 3;
    open[at..at + open[at..].find('"').unwrap()]
        .parse()
        .unwrap()
}

#[test]
fn simulated_map_draws_its_picture_as_png_and_svg() {
    let dir = scratch_dir("simulated-map-picture");
    let (png, svg) = (dir.join("map.png"), dir.join("map.svg"));
    let mut args = tiny();
    let (p, s) = (png.to_str().unwrap(), svg.to_str().unwrap());
    args.extend(["--png", p, "--svg", s]);
    // twice: the second run replaces the pictures the first one drew
    for _ in 0..2 {
        let text = ok(&args);
        let tally = text
            .lines()
            .find_map(|l| l.strip_prefix("# tally: "))
            .expect("a tally line");
        let svg_text = std::fs::read_to_string(&svg).unwrap();
        let bytes = std::fs::read(&png).unwrap();
        // 7 in at 300 dpi wide, the SVG's height at that scale
        let (w, h) = png_size(&bytes);
        assert_eq!(w, 2100);
        let (sw, sh) = (
            svg_attribute(&svg_text, "width"),
            svg_attribute(&svg_text, "height"),
        );
        assert_eq!(sw, 1120.0);
        assert_eq!(h, (sh * 2100.0 / sw).round() as u32);
        assert!(h > 1000 && h < 2100, "{h}");
        assert_eq!(&bytes[bytes.len() - 8..bytes.len() - 4], b"IEND");
        // both panels, and the caption's tally as the CSV's
        assert!(svg_text.contains("(a) theory (Eq. 27)"), "panel a");
        assert!(svg_text.contains("(b) simulated (Eq. 1), z = 3"), "panel b");
        let drawn = tally
            .replace("non_stationary", "non-stationary")
            .replace("outside_range", "outside the range");
        assert!(
            svg_text.contains(&format!("Tally: {drawn}.")),
            "{drawn} not in the SVG"
        );
        assert!(svg_text.contains("z = 4 … z = 2"), "the range's rule");
        // a mark's legend entry exactly where a point has that verdict
        let rows = rows(&text);
        for (verdict, entry) in [
            ("disagree", "disagree (theory outside the range)"),
            ("uncertain", "uncertain (range of several counts)"),
            ("non_stationary", "not stationary (not compared)"),
        ] {
            let any = rows.iter().skip(1).any(|r| r[6] == verdict);
            assert_eq!(svg_text.contains(entry), any, "{verdict}");
        }
    }
}

#[test]
fn simulated_map_picture_destinations_are_refused_before_any_work() {
    let dir = scratch_dir("simulated-map-picture-refused");
    std::fs::create_dir_all(dir.join("folder.png")).unwrap();
    let foreign = dir.join("theirs.svg");
    std::fs::write(&foreign, "<svg>someone else's</svg>").unwrap();
    let path = |name: &str| dir.join(name).to_str().unwrap().to_string();
    let cases: Vec<(&str, String, &str)> = vec![
        ("--png", path("folder.png"), "is a directory"),
        ("--png", path("missing/map.png"), "does not exist"),
        ("--png", path("map.svg"), "give a file name ending in .png"),
        ("--svg", path("map"), "give a file name ending in .svg"),
        (
            "--svg",
            path("theirs.svg"),
            "is not a picture trirhythm drew",
        ),
    ];
    for (flag, dest, needle) in &cases {
        let mut args = tiny();
        args.extend([*flag, dest.as_str()]);
        let out = run(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{flag} {dest}: {err}");
        assert!(err.contains(needle), "{flag} {dest}: {err}");
        // refused before the work: the sizing note that opens it never came, nor any data
        assert!(!err.contains("path-steps on the"), "{err}");
        assert!(out.stdout.is_empty());
    }
    assert_eq!(
        std::fs::read_to_string(&foreign).unwrap(),
        "<svg>someone else's</svg>"
    );
    // the picture's options belong to --simulate
    let out = run(&[
        "map",
        "--preset",
        "fig12d",
        "--x",
        "r=0.9:1:3",
        "--y",
        "D=0.1:1:3",
        "--png",
        "m.png",
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--png applies to --simulate only"));
}
