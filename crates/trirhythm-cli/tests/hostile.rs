//! The CLI's promises under hostile input, one test per class of failure:
//! - bad input exits 2 naming the parameter (by the user's name) and its allowed range;
//! - exit 0 never prints a non-finite number; an overflow exits 1 saying where; nothing panics;
//! - every size is bounded before work starts;
//! - what was asked is done or refused, never silently changed (end time, step);
//! - no partial file on any path: errors, `--out` onto a directory or a device, SIGINT, SIGTERM;
//! - a closed pipe ends quietly, a full device exits 1.

mod common;

use common::{csv_rows, ok_stdout, run, scratch_dir};
use std::io::Read;
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// Keys set to extreme values on every command.
const KEYS: [&str; 12] = [
    "mu0", "omega0", "lambda", "r", "D", "tau", "alpha0", "beta0", "gamma0", "delta0", "c0", "c1",
];
const VALUES: [&str; 10] = [
    "-0", "-1", "1e-300", "1e308", "-1e308", "inf", "-inf", "nan", "1e-12", "1e6",
];

/// The promises every run keeps, whatever it was given.
fn assert_promises(args: &[&str], out: &std::process::Output) {
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    let code = out.status.code();
    assert!(
        matches!(code, Some(0..=2)),
        "{args:?}: exit {code:?} (a crash or abort)\n{stderr}"
    );
    assert!(!stderr.contains("panicked"), "{args:?}: panic\n{stderr}");
    match code {
        Some(0) => {
            // the limits U_eff(0⁺) = +∞ (D > 0) and ln p = −∞ outside the support are values
            let infinity_is_a_value = matches!(args[0], "potential" | "pdf");
            for line in stdout.lines().filter(|l| !l.starts_with('#')) {
                let cells = line.split([',', ' ', ':', '[', ']']).map(str::trim);
                for c in cells {
                    let c = c.trim_matches('"').to_ascii_lowercase();
                    let infinite = matches!(c.as_str(), "inf" | "-inf");
                    assert!(
                        !(matches!(c.as_str(), "nan" | "null") || infinite && !infinity_is_a_value),
                        "{args:?}: exit 0 with a non-finite value in {line:?}"
                    );
                }
            }
        }
        _ => assert!(
            stderr.starts_with("error:") && stdout.is_empty() || stdout.contains("# error:"),
            "{args:?}: failure without an error message, or with partial output\n{stderr}"
        ),
    }
}

/// Every command, every parameter, extreme values: no crash, no silent NaN, and a refusal
/// names the parameter the user set, by the user's name (β0, not c3) and sign.
#[test]
fn extreme_parameters_keep_every_promise() {
    let commands: [&[&str]; 9] = [
        &["equivalents", "--preset", "fig11"],
        &["cycles", "--preset", "fig11"],
        &["drift", "--preset", "fig11"],
        &["potential", "--preset", "fig11"],
        &["barriers", "--preset", "fig11"],
        &["pdf", "--preset", "fig11"],
        &["simulate", "--preset", "fig1", "--t-end", "1"],
        &[
            "map",
            "--preset",
            "fig6",
            "--x",
            "gamma0=0:0.01:3",
            "--y",
            "delta0=1e-8:6e-7:3",
        ],
        &[
            "branches", "--preset", "fig5", "--x", "r=0.9:1", "--step", "0.05",
        ],
    ];
    let mut refused = 0;
    let mut runs = 0;
    for base in commands {
        for key in KEYS {
            for value in VALUES {
                let kv = format!("{key}={value}");
                let mut args: Vec<&str> = base.to_vec();
                args.extend(["--param", &kv]);
                let out = run(&args);
                runs += 1;
                assert_promises(&args, &out);
                let stderr = String::from_utf8_lossy(&out.stderr);
                let non_finite = matches!(value, "inf" | "-inf" | "nan");
                if non_finite {
                    // never accepted, and named as given
                    assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
                    assert!(
                        stderr.contains(&format!("{key} = {}", value.replace("nan", "NaN"))),
                        "{args:?}: the message must name {key} = {value}: {stderr}"
                    );
                }
                if out.status.code() == Some(2) {
                    refused += 1;
                }
            }
        }
    }
    assert!(refused > runs / 3, "{refused} of {runs} refused");
}

/// Flags with extreme or malformed values: refused naming the flag, never a crash.
#[test]
fn extreme_flags_keep_every_promise() {
    // (arguments, the flag a refusal must name)
    let mut cases: Vec<(Vec<String>, &str)> = Vec::new();
    let v = |s: &[&str]| s.iter().map(|x| x.to_string()).collect::<Vec<_>>();
    for value in ["0", "-0", "-1", "1e-300", "1e308", "inf", "nan", "abc", ""] {
        for flag in ["--dt", "--u0", "--v0", "--tolerance", "--every", "--seed"] {
            let args = v(&["simulate", "--preset", "fig1", "--t-end", "1", flag, value]);
            // the message names the flag, or the engine's parameter (dt, u0, v0, tolerance)
            cases.push((args, flag.trim_start_matches("--")));
        }
        cases.push((
            v(&["simulate", "--preset", "fig1", "--t-end", value]),
            "t-end",
        ));
        for cmd in ["drift", "potential", "pdf"] {
            for grid in [
                format!("0:{value}:5"),
                format!("{value}:10:5"),
                format!("0:10:{value}"),
            ] {
                cases.push((v(&[cmd, "--preset", "fig11", "--grid", &grid]), "--grid"));
            }
        }
        cases.push((
            v(&[
                "branches", "--preset", "fig5", "--x", "r=0.9:1", "--step", value,
            ]),
            "--step",
        ));
        cases.push((
            v(&[
                "map",
                "--preset",
                "fig6",
                "--x",
                &format!("gamma0=0:1:{value}"),
                "--y",
                "delta0=1e-8:6e-7:3",
            ]),
            "--x",
        ));
    }
    for (args, flag) in &cases {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let out = run(&args);
        assert_promises(&args, &out);
        if out.status.code() == Some(2) {
            let stderr = String::from_utf8_lossy(&out.stderr);
            assert!(
                stderr.contains(flag) || stderr.contains(&flag.replace('-', "_")),
                "{args:?}: the message must name {flag}: {stderr}"
            );
        }
    }
}

/// Work is bounded before it starts: each of these would take hours or gigabytes, and is
/// refused in well under a second naming the flag that set the size.
#[test]
fn sizes_are_refused_before_work_starts() {
    let cases: [(&[&str], &str); 6] = [
        (
            &[
                "simulate", "--preset", "fig1", "--t-end", "1e9", "--format", "json",
            ],
            "--every",
        ),
        (
            &["simulate", "--preset", "fig1", "--t-end", "1e12"],
            "t_end",
        ),
        (
            &[
                "map",
                "--preset",
                "fig6",
                "--x",
                "gamma0=0:1e-4:10000000",
                "--y",
                "delta0=1e-8:6e-7:10000000",
            ],
            "points",
        ),
        (
            &["cycles", "--preset", "fig11", "--param", "c100000000000=0"],
            "c100000000000",
        ),
        (
            &["cycles", "--preset", "fig11", "--param", "c100000000=0"],
            "c100000000",
        ),
        (
            &[
                "branches", "--preset", "fig5", "--x", "r=0.9:1", "--step", "1e-12",
            ],
            "--step",
        ),
    ];
    for (args, name) in cases {
        let t = Instant::now();
        let out = run(args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(stderr.contains(name), "{args:?} must name {name}: {stderr}");
        assert!(
            t.elapsed() < Duration::from_secs(5),
            "{args:?} took {:?} to refuse",
            t.elapsed()
        );
    }
}

/// The end time is kept exactly, or the request is refused: never integrated to another time.
#[test]
fn end_time_is_kept_or_refused() {
    for dt in ["0.3", "1.9", "0.7"] {
        let args = ["simulate", "--preset", "fig1", "--t-end", "1", "--dt", dt];
        let out = run(&args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(
            stderr.contains("dt") && stderr.contains("t_end"),
            "{stderr}"
        );
        // the suggested end times are printed as people write them
        assert!(
            !stderr.contains("99999") && !stderr.contains("00000"),
            "{stderr}"
        );
    }
    let text = ok_stdout(&[
        "simulate", "--preset", "fig1", "--t-end", "1", "--dt", "0.25", "--format", "csv",
    ]);
    let rows = csv_rows(&text);
    let last: f64 = rows.last().unwrap()[0].parse().unwrap();
    assert_eq!(last, 1.0, "the last row is at t_end");
    assert_eq!(rows.len(), 1 + 5, "header and t = 0, 0.25, …, 1");
}

/// A step that cannot resolve the problem is refused before any work, naming `--dt` and the
/// largest step the guard allows; a coarse one runs with its warning in the output.
#[test]
fn a_step_that_cannot_be_right_is_refused() {
    for args in [
        &[
            "ensemble", "--preset", "fig13a", "--paths", "2", "--t-end", "100", "--dt", "1",
        ][..],
        &[
            "simulate", "--preset", "fig13b", "--u0", "14.9", "--t-end", "3", "--dt", "0.3",
        ],
        &[
            "lyapunov", "--preset", "fig17a", "--t-end", "10", "--dt", "0.1", "--param", "omega0=7",
        ],
    ] {
        let out = run(args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(stderr.starts_with("error: --dt"), "{args:?}: {stderr}");
        assert!(
            stderr.contains("allowed range is") && stderr.contains("here"),
            "{stderr}"
        );
        assert!(out.stdout.is_empty(), "{args:?}");
    }
    // coarse but not wrong: the run goes on and says so, in JSON and in the CSV header
    let doc = common::ok_json(&[
        "ensemble",
        "--preset",
        "fig2i",
        "--paths",
        "2",
        "--t-end",
        "100",
        "--burn-in",
        "10",
        "--dt",
        "0.5",
        "--param",
        "D=0.1",
        "--param",
        "tau=1",
        "--format",
        "json",
    ]);
    let w = doc["step_warnings"].as_array().unwrap();
    assert_eq!(w.len(), 2, "{w:?}");
    assert!(w[0].as_str().unwrap().contains("halving the step"), "{w:?}");
    assert!(
        w[1].as_str().unwrap().contains("2.000 steps per noise"),
        "{w:?}"
    );
    let text = ok_stdout(&[
        "simulate", "--preset", "fig13a", "--param", "tau=0.05", "--t-end", "1",
    ]);
    assert!(text
        .lines()
        .any(|l| l.starts_with("# warning: dt = 0.01: 5.000 steps per noise")));
    // the default step on the paper's set carries no warning
    let doc = common::ok_json(&[
        "simulate", "--preset", "fig13a", "--t-end", "1", "--format", "json",
    ]);
    assert_eq!(doc["step_warnings"], serde_json::json!([]));
}

/// Messages use the user's names and signs, and negative numbers reach the flag's own check.
#[test]
fn messages_name_what_the_user_typed() {
    let cases: [(&[&str], &[&str]); 5] = [
        (
            &["cycles", "--preset", "fig11", "--param", "beta0=-inf"],
            &["beta0 = -inf"],
        ),
        (
            &["cycles", "--preset", "fig11", "--param", "delta0=1e308"],
            &["delta0 = 1e308", "[-1e20, 1e20]"],
        ),
        (
            &[
                "simulate", "--preset", "fig1", "--t-end", "1", "--every", "-0",
            ],
            &["--every"],
        ),
        (
            &[
                "simulate", "--preset", "fig1", "--t-end", "1", "--seed", "-1",
            ],
            &["--seed"],
        ),
        (
            &[
                "branches", "--preset", "fig5", "--x", "r=0.9:1", "--step", "-1",
            ],
            &["--step", "-1"],
        ),
    ];
    for (args, needles) in cases {
        let out = run(args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
        for n in needles {
            assert!(stderr.contains(n), "{args:?}: missing {n:?} in {stderr}");
        }
        assert!(
            stderr.len() < 600,
            "a readable message, not a dump: {stderr}"
        );
    }
    // figures: every one of the paper's 19 exists; others do not
    let out = run(&["figure", "20"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("no such figure"));
}

/// Values that are defined at the edge of the domain are printed as such (U_eff(0) = 0 with
/// D = 0), and a density with a very narrow peak still shows it on the default grid.
#[test]
fn edge_values_and_narrow_peaks_are_shown() {
    let text = ok_stdout(&["potential", "--format", "csv"]);
    let first = &csv_rows(&text)[1];
    assert_eq!(first[0], "0");
    assert_eq!(
        first[1].parse::<f64>().unwrap(),
        0.0,
        "U_eff(0) = 0: {first:?}"
    );
    for extra in ["D=1e-12", "tau=1e6"] {
        let text = ok_stdout(&[
            "pdf", "--preset", "fig11", "--param", extra, "--format", "csv",
        ]);
        let rows = csv_rows(&text);
        let nonzero = rows[1..]
            .iter()
            .filter(|r| r[1].parse::<f64>().unwrap() > 0.0)
            .count();
        assert!(nonzero >= 50, "{extra}: {nonzero} rows with p > 0");
    }
}

/// `--out` onto a directory, into a missing directory, or onto a device: refused before work,
/// and nothing is left behind.
#[test]
fn output_onto_odd_places_is_refused_and_leaves_nothing() {
    let dir = scratch_dir("odd-places");
    let sub = dir.join("sub");
    std::fs::create_dir(&sub).unwrap();
    let missing = dir.join("missing").join("x.csv");
    let targets = [
        sub.to_str().unwrap().to_string(),
        missing.to_str().unwrap().to_string(),
        String::new(),
    ];
    let mut targets = targets.to_vec();
    if Path::new("/dev/null").exists() {
        targets.push("/dev/null".into());
    }
    for t in &targets {
        for cmd in [
            &["simulate", "--preset", "fig1", "--t-end", "1", "--out"][..],
            &["cycles", "--preset", "fig11", "--out"][..],
            &[
                "map",
                "--preset",
                "fig6",
                "--x",
                "gamma0=0:0.01:3",
                "--y",
                "delta0=1e-8:6e-7:3",
                "--out",
            ][..],
        ] {
            let mut args = cmd.to_vec();
            args.push(t);
            let out = run(&args);
            let stderr = String::from_utf8_lossy(&out.stderr);
            assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
            assert!(stderr.contains("--out"), "{args:?}: {stderr}");
        }
    }
    let left: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(
        left,
        vec![std::ffi::OsString::from("sub")],
        "litter: {left:?}"
    );
    assert_eq!(std::fs::read_dir(&sub).unwrap().count(), 0);
    // the folds file is not written when the main output is refused
    let folds = dir.join("f.csv");
    let out = run(&[
        "map",
        "--preset",
        "fig6",
        "--x",
        "gamma0=0:0.01:3",
        "--y",
        "delta0=1e-8:6e-7:3",
        "--folds-out",
        folds.to_str().unwrap(),
        "--out",
        sub.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(!folds.exists());
    let _ = std::fs::remove_dir_all(&dir);
}

/// Wait for `child` and read its standard error.
#[cfg(unix)]
fn wait_with_stderr(mut child: std::process::Child) -> (std::process::ExitStatus, String) {
    let status = child.wait().unwrap();
    let mut stderr = String::new();
    child
        .stderr
        .take()
        .unwrap()
        .read_to_string(&mut stderr)
        .unwrap();
    (status, stderr)
}

/// Send `signal` to a long run writing into `dir` once its temporary exists: exit 130 and an
/// empty directory.
#[cfg(unix)]
fn interrupt_leaves_nothing(signal: &str, args: &[&str], dir: &Path) {
    let child = Command::new(env!("CARGO_BIN_EXE_trirhythm"))
        .args(args)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let t = Instant::now();
    // wait for the temporary (or at most 20 s: then signal anyway)
    while std::fs::read_dir(dir).unwrap().count() == 0 && t.elapsed() < Duration::from_secs(20) {
        std::thread::sleep(Duration::from_millis(20));
    }
    std::thread::sleep(Duration::from_millis(100));
    let status = Command::new("kill")
        .args([signal, &child.id().to_string()])
        .status()
        .unwrap();
    assert!(status.success());
    let (status, stderr) = wait_with_stderr(child);
    assert_eq!(status.code(), Some(130), "{signal} {args:?}: {stderr}");
    let left: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert!(left.is_empty(), "{signal} {args:?} left {left:?}");
}

#[cfg(unix)]
#[test]
fn interrupted_runs_leave_no_file() {
    let dir = scratch_dir("signals");
    let out = dir.join("path.csv");
    let out = out.to_str().unwrap();
    // 10⁸ steps streamed to CSV: minutes of work, its temporary grows from the start
    let simulate = [
        "simulate", "--preset", "fig1", "--t-end", "5e5", "--format", "csv", "--out", out,
    ];
    for signal in ["-INT", "-TERM"] {
        interrupt_leaves_nothing(signal, &simulate, &dir);
    }
    let map_out = dir.join("map.csv");
    let map = [
        "map",
        "--preset",
        "fig6",
        "--x",
        "gamma0=0:0.5:2000",
        "--y",
        "delta0=1e-8:6e-7:2000",
        "--out",
        map_out.to_str().unwrap(),
    ];
    interrupt_leaves_nothing("-TERM", &map, &dir);
    let _ = std::fs::remove_dir_all(&dir);
}

/// A reader that goes away ends the command quietly; a full device is an error, not a panic.
#[cfg(unix)]
#[test]
fn closed_and_full_standard_output() {
    let mut child = Command::new(env!("CARGO_BIN_EXE_trirhythm"))
        .args([
            "simulate", "--preset", "fig1", "--t-end", "1e5", "--format", "csv",
        ])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut head = [0u8; 4096];
    child
        .stdout
        .as_mut()
        .unwrap()
        .read_exact(&mut head)
        .unwrap();
    drop(child.stdout.take());
    let (status, stderr) = wait_with_stderr(child);
    assert_eq!(status.code(), Some(0), "broken pipe: {stderr}");
    assert!(stderr.is_empty(), "a closed pipe ends quietly: {stderr}");

    if Path::new("/dev/full").exists() {
        for args in [
            &["presets"][..],
            &["cycles", "--preset", "fig11"][..],
            &["simulate", "--preset", "fig1", "--t-end", "10"][..],
        ] {
            let full = std::fs::OpenOptions::new()
                .write(true)
                .open("/dev/full")
                .unwrap();
            let out = Command::new(env!("CARGO_BIN_EXE_trirhythm"))
                .args(args)
                .stdout(full)
                .output()
                .unwrap();
            let stderr = String::from_utf8_lossy(&out.stderr);
            assert_eq!(out.status.code(), Some(1), "{args:?}: {stderr}");
            assert!(!stderr.contains("panicked"), "{args:?}: {stderr}");
            assert!(stderr.contains("standard output"), "{args:?}: {stderr}");
        }
    }
}
