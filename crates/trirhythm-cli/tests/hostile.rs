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

// ---------------------------------------------------------------------------------------------
// Issue 33: nothing lost, nothing pretended. One block per class of defect; every case failed
// on main at ae3915a.

/// The sorted entries of `dir`, hidden ones included.
fn listing(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

/// Exit 2 with an `error:` naming `flag` (and each of `also`); the message.
fn refused_naming(out: &std::process::Output, flag: &str, also: &[&str], what: &str) -> String {
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(2), "{what}: {err}");
    assert!(
        err.starts_with("error:") && err.contains(flag),
        "{what}: {err}"
    );
    for a in also {
        assert!(err.contains(a), "{what}: {a} not in {err}");
    }
    err
}

/// Whether this process runs as root (permission bits do not stop root).
#[cfg(unix)]
fn is_root() -> bool {
    Command::new("id")
        .arg("-u")
        .output()
        .map(|o| String::from_utf8_lossy(&o.stdout).trim() == "0")
        .unwrap_or(false)
}

/// `dir` made unwritable for this process until the value is dropped: mode 555 for a user,
/// the immutable attribute (`chattr +i`) for root, whom modes do not stop. `None` (with the
/// reason printed) where neither can be done here.
#[cfg(unix)]
struct Unwritable(std::path::PathBuf, bool);

#[cfg(unix)]
impl Unwritable {
    fn make(dir: &Path) -> Option<Unwritable> {
        if is_root() {
            let ok = Command::new("chattr")
                .args(["+i", dir.to_str().unwrap()])
                .stderr(Stdio::null())
                .status()
                .is_ok_and(|s| s.success());
            if !ok {
                eprintln!(
                    "skipped: running as root and `chattr +i` is not available here, so no \
                     directory can be made unwritable"
                );
                return None;
            }
            Some(Unwritable(dir.to_path_buf(), true))
        } else {
            use std::os::unix::fs::PermissionsExt;
            std::fs::set_permissions(dir, std::fs::Permissions::from_mode(0o555)).unwrap();
            Some(Unwritable(dir.to_path_buf(), false))
        }
    }
}

#[cfg(unix)]
impl Drop for Unwritable {
    fn drop(&mut self) {
        if self.1 {
            let _ = Command::new("chattr")
                .args(["-i", self.0.to_str().unwrap()])
                .status();
        } else {
            use std::os::unix::fs::PermissionsExt;
            let _ = std::fs::set_permissions(&self.0, std::fs::Permissions::from_mode(0o755));
        }
    }
}

/// A small figure data directory: Fig. 8's quick data (fast to compute and to draw).
fn figure_data(scratch: &Path) -> std::path::PathBuf {
    let data = scratch.join("data");
    std::fs::create_dir_all(&data).unwrap();
    ok_stdout(&[
        "figure",
        "8",
        "--quick",
        "--data",
        "--out-dir",
        data.to_str().unwrap(),
    ]);
    data
}

/// `report --from-data DATA --out-dir OUT`.
fn report_from(data: &Path, out: &Path) -> std::process::Output {
    run(&[
        "report",
        "--from-data",
        data.to_str().unwrap(),
        "--out-dir",
        out.to_str().unwrap(),
    ])
}

/// A process that never runs here: no `/proc/PID`.
#[cfg(target_os = "linux")]
fn dead_pid() -> u32 {
    (400_000..u32::MAX)
        .find(|p| !Path::new(&format!("/proc/{p}")).exists())
        .unwrap()
}

/// A report that waits, under the test's control, while it works: its figure data is a named
/// pipe (`mkfifo`) that the test serves once for the report's first reading (before its
/// temporary directory exists) and, once [`Paused::resume`] is called, for every later one.
/// Between the two the report has made its temporary directory and waits for the data: the
/// test changes the destination meanwhile, with no race.
#[cfg(target_os = "linux")]
struct Paused {
    child: std::process::Child,
    gate: std::sync::mpsc::Sender<()>,
    done: std::sync::Arc<std::sync::atomic::AtomicBool>,
    server: Option<std::thread::JoinHandle<()>>,
}

#[cfg(target_os = "linux")]
impl Paused {
    /// Start `report --from-data FIFO_DIR --out-dir out` with `fig08.json` of `data` served
    /// through a pipe in `fifo_dir`; returns once its temporary directory exists.
    fn start(data: &Path, fifo_dir: &Path, out: &Path) -> Paused {
        use std::sync::atomic::{AtomicBool, Ordering};
        std::fs::create_dir_all(fifo_dir).unwrap();
        let fifo = fifo_dir.join("fig08.json");
        let _ = std::fs::remove_file(&fifo);
        assert!(Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .unwrap()
            .success());
        let content = std::fs::read(data.join("fig08.json")).unwrap();
        let child = Command::new(env!("CARGO_BIN_EXE_trirhythm"))
            .args([
                "report",
                "--from-data",
                fifo_dir.to_str().unwrap(),
                "--out-dir",
                out.to_str().unwrap(),
            ])
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        let pid = child.id();
        let (gate, opened) = std::sync::mpsc::channel::<()>();
        let done = std::sync::Arc::new(AtomicBool::new(false));
        let stop = done.clone();
        let server = std::thread::spawn(move || {
            let mut served = 0;
            while !stop.load(Ordering::Relaxed) {
                if served == 1 && opened.recv_timeout(Duration::from_millis(20)).is_err() {
                    continue;
                }
                if serve(&fifo, &content, pid, &stop) {
                    served += 1;
                }
            }
        });
        let parent = out.parent().unwrap();
        let name = format!(".{}.partial-", out.file_name().unwrap().to_string_lossy());
        let t = Instant::now();
        while !listing(parent).iter().any(|e| e.starts_with(&name)) {
            assert!(
                t.elapsed() < Duration::from_secs(60),
                "no temporary directory"
            );
            std::thread::sleep(Duration::from_millis(10));
        }
        Paused {
            child,
            gate,
            done,
            server: Some(server),
        }
    }

    /// Let the report go on; its exit status and standard error.
    fn resume(mut self) -> (std::process::ExitStatus, String) {
        let _ = self.gate.send(());
        let (status, stderr) = wait_with_stderr(self.child);
        self.done.store(true, std::sync::atomic::Ordering::Relaxed);
        if let Some(s) = self.server.take() {
            s.join().unwrap();
        }
        (status, stderr)
    }

    /// Kill the report with SIGKILL (it leaves its temporary directory).
    fn kill(mut self) {
        self.child.kill().unwrap();
        self.child.wait().unwrap();
        self.done.store(true, std::sync::atomic::Ordering::Relaxed);
        if let Some(s) = self.server.take() {
            s.join().unwrap();
        }
    }
}

/// Serve `content` once through the pipe `fifo` to process `pid`: wait for it to open the
/// pipe, write, close, and wait until it has closed its end (so that the next serving is a
/// reading of its own). False when stopped first.
#[cfg(target_os = "linux")]
fn serve(fifo: &Path, content: &[u8], pid: u32, stop: &std::sync::atomic::AtomicBool) -> bool {
    use std::io::Write;
    use std::os::unix::fs::OpenOptionsExt;
    use std::sync::atomic::Ordering;
    const O_NONBLOCK: i32 = 0o4000;
    let mut f = loop {
        if stop.load(Ordering::Relaxed) {
            return false;
        }
        // a write end opens only while a reader has the pipe open
        match std::fs::OpenOptions::new()
            .write(true)
            .custom_flags(O_NONBLOCK)
            .open(fifo)
        {
            Ok(f) => break f,
            Err(_) => std::thread::sleep(Duration::from_millis(2)),
        }
    };
    let mut off = 0;
    while off < content.len() {
        match f.write(&content[off..]) {
            Ok(n) => off += n,
            Err(e) if e.kind() == std::io::ErrorKind::WouldBlock => {
                if stop.load(Ordering::Relaxed) {
                    return false;
                }
                std::thread::sleep(Duration::from_millis(1));
            }
            Err(_) => return false,
        }
    }
    let target = std::fs::canonicalize(fifo).unwrap();
    let holds = || {
        std::fs::read_dir(format!("/proc/{pid}/fd"))
            .map(|d| {
                d.flatten()
                    .any(|e| std::fs::read_link(e.path()).is_ok_and(|l| l == target))
            })
            .unwrap_or(false)
    };
    // the write end stays open until the reader's open has returned (it cannot see the end
    // of the data before), then the reader is waited for until it has closed its end
    while !holds() && !stop.load(Ordering::Relaxed) {
        std::thread::sleep(Duration::from_millis(1));
    }
    drop(f);
    while holds() && !stop.load(Ordering::Relaxed) {
        std::thread::sleep(Duration::from_millis(2));
    }
    true
}

/// Class 1: the report never deletes or overwrites a file it did not write — a folder made at
/// the destination during the run, a file added to a previous report during the run, a file
/// inside a previous report's figures/ — and refuses with exit 2 naming `--out-dir`, leaving
/// the folder as it was and no hidden copy beside it.
#[cfg(target_os = "linux")]
#[test]
fn the_report_never_deletes_a_file_it_did_not_write() {
    let scratch = scratch_dir("foreign-files");
    let data = figure_data(&scratch);
    let hidden = |name: &str| -> Vec<String> {
        listing(&scratch)
            .into_iter()
            .filter(|e| e.starts_with(&format!(".{name}.")))
            .collect()
    };

    // a folder with the user's file appears at the destination while the report works
    let r = scratch.join("R");
    let paused = Paused::start(&data, &scratch.join("fifo1"), &r);
    std::fs::create_dir(&r).unwrap();
    std::fs::write(r.join("thesis.tex"), "x").unwrap();
    let (status, err) = paused.resume();
    assert_eq!(status.code(), Some(2), "{err}");
    assert!(
        err.contains("--out-dir") && err.contains("thesis.tex"),
        "{err}"
    );
    assert_eq!(listing(&r), ["thesis.tex"]);
    assert_eq!(std::fs::read_to_string(r.join("thesis.tex")).unwrap(), "x");
    assert!(hidden("R").is_empty(), "{:?}", hidden("R"));

    // a file added to a previous report while the new one is computed
    let p = scratch.join("P");
    let out = report_from(&data, &p);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let before = listing(&p.join("figures"));
    let verdicts = std::fs::read(p.join("verdicts.json")).unwrap();
    let paused = Paused::start(&data, &scratch.join("fifo2"), &p);
    std::fs::write(p.join("figures/mine.txt"), "mine").unwrap();
    let (status, err) = paused.resume();
    assert_eq!(status.code(), Some(2), "{err}");
    assert!(
        err.contains("--out-dir") && err.contains("figures/mine.txt"),
        "{err}"
    );
    let mut expected = before.clone();
    expected.push("mine.txt".into());
    expected.sort();
    assert_eq!(listing(&p.join("figures")), expected);
    assert_eq!(std::fs::read(p.join("verdicts.json")).unwrap(), verdicts);
    assert!(hidden("P").is_empty(), "{:?}", hidden("P"));

    // the same file there from the start: refused before any work, nothing touched
    let out = report_from(&data, &p);
    refused_naming(
        &out,
        "--out-dir",
        &["figures/mine.txt"],
        "a foreign file in figures/",
    );
    assert_eq!(listing(&p.join("figures")), expected);
    assert_eq!(std::fs::read(p.join("verdicts.json")).unwrap(), verdicts);

    // without it the previous report is replaced, and nothing is left beside it
    std::fs::remove_file(p.join("figures/mine.txt")).unwrap();
    let out = report_from(&data, &p);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(listing(&p.join("figures")), before);
    assert!(hidden("P").is_empty(), "{:?}", hidden("P"));
    let _ = std::fs::remove_dir_all(&scratch);
}

/// Class 2: every destination that cannot be written is refused before any work, exit 2
/// naming its flag — `--checkpoint`, `report --out-dir`, `figure --out-dir`, `--folds-out` —
/// under a regular file, in `/proc` (which takes no file, even from root), and in a directory
/// made unwritable (mode 555, or for root the immutable attribute).
#[cfg(target_os = "linux")]
#[test]
fn unwritable_destinations_are_refused_naming_the_flag() {
    let scratch = scratch_dir("unwritable");
    let file = scratch.join("file");
    std::fs::write(&file, "x").unwrap();
    let under_file = file.join("x");
    let s = |p: &Path| p.to_str().unwrap().to_string();
    // minutes of work when the destination is accepted
    let ensemble = ["ensemble", "--paths", "64", "--t-end", "20000"];
    let map = [
        "map",
        "--preset",
        "fig6",
        "--x",
        "gamma0=0:0.01:3",
        "--y",
        "delta0=1e-8:6e-7:3",
    ];
    let mut cases: Vec<(Vec<String>, &str)> = Vec::new();
    for bad in [s(&under_file), "/proc/trirhythm-x".to_string()] {
        let mut a: Vec<String> = ensemble.iter().map(|x| x.to_string()).collect();
        a.extend(["--checkpoint".into(), bad.clone()]);
        cases.push((a, "--checkpoint"));
        cases.push((
            vec![
                "figure".into(),
                "8".into(),
                "--quick".into(),
                "--out-dir".into(),
                bad.clone(),
            ],
            "--out-dir",
        ));
        let mut a: Vec<String> = map.iter().map(|x| x.to_string()).collect();
        a.extend(["--folds-out".into(), format!("{bad}.csv")]);
        cases.push((a, "--folds-out"));
    }
    cases.push((
        vec![
            "report".into(),
            "--quick".into(),
            "--out-dir".into(),
            "/proc/trirhythm-report".into(),
        ],
        "--out-dir",
    ));
    let ro = scratch.join("ro");
    std::fs::create_dir(&ro).unwrap();
    let guard = Unwritable::make(&ro);
    if guard.is_some() {
        for dest in [ro.clone(), ro.join("new")] {
            let mut a: Vec<String> = ensemble.iter().map(|x| x.to_string()).collect();
            a.extend(["--checkpoint".into(), s(&dest)]);
            cases.push((a, "--checkpoint"));
            cases.push((
                vec![
                    "figure".into(),
                    "8".into(),
                    "--quick".into(),
                    "--out-dir".into(),
                    s(&dest),
                ],
                "--out-dir",
            ));
        }
        cases.push((
            vec![
                "report".into(),
                "--quick".into(),
                "--out-dir".into(),
                s(&ro.join("report")),
            ],
            "--out-dir",
        ));
    }
    for (args, flag) in &cases {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let t = Instant::now();
        let out = run(&args);
        refused_naming(&out, flag, &[], &format!("{args:?}"));
        assert!(
            t.elapsed() < Duration::from_secs(10),
            "{args:?}: refused only after {:?}",
            t.elapsed()
        );
    }
    drop(guard);
    assert_eq!(listing(&ro), Vec::<String>::new());
    assert_eq!(listing(&scratch), ["file", "ro"]);
    let _ = std::fs::remove_dir_all(&scratch);
}

/// Class 3: no hidden copy is left. A temporary of a killed run (SIGKILL) is removed by the
/// next run on the same destination — a report's folder, an `--out` file — unless its process
/// still runs; a previous report whose files cannot be removed is an error naming the path.
#[cfg(target_os = "linux")]
#[test]
fn hidden_copies_are_cleaned_up_or_named() {
    let scratch = scratch_dir("hidden-copies");
    let data = figure_data(&scratch);
    let hidden = |name: &str| -> Vec<String> {
        listing(&scratch)
            .into_iter()
            .filter(|e| e.starts_with(&format!(".{name}.")))
            .collect()
    };

    // a report killed while it works leaves its temporary: the next run removes it
    let r = scratch.join("R");
    Paused::start(&data, &scratch.join("fifo"), &r).kill();
    assert_eq!(hidden("R").len(), 1, "{:?}", listing(&scratch));
    // and a live process's temporary (this test's own id) is left alone
    let live = scratch.join(format!(".R.partial-{}", std::process::id()));
    std::fs::create_dir(&live).unwrap();
    let out = report_from(&data, &r);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(
        hidden("R"),
        [format!(".R.partial-{}", std::process::id())],
        "the killed run's temporary is removed, the live one kept"
    );
    std::fs::remove_dir(&live).unwrap();

    // an --out file's temporary of a killed run
    let dead = dead_pid();
    let csv = scratch.join("c.csv");
    let stale = scratch.join(format!(".c.csv.partial-{dead}.csv"));
    std::fs::write(&stale, "half a file").unwrap();
    ok_stdout(&[
        "cycles",
        "--preset",
        "fig11",
        "--format",
        "csv",
        "--out",
        csv.to_str().unwrap(),
    ]);
    assert!(!stale.exists(), "{:?}", listing(&scratch));
    assert!(csv.exists());

    // a previous report whose files cannot be removed
    let blocked = r.join("figures");
    let guard = if is_root() {
        let f = blocked.join("fig08.csv");
        Command::new("chattr")
            .args(["+i", f.to_str().unwrap()])
            .stderr(Stdio::null())
            .status()
            .is_ok_and(|s| s.success())
            .then(|| Unwritable(f, true))
    } else {
        Unwritable::make(&blocked)
    };
    match guard {
        None => eprintln!(
            "skipped: a file that cannot be removed (running as root without `chattr +i`)"
        ),
        Some(guard) => {
            let out = report_from(&data, &r);
            let err = String::from_utf8_lossy(&out.stderr).into_owned();
            assert_ne!(out.status.code(), Some(0), "{err}");
            if is_root() {
                // found only when removing: the new report is in place, the old one named
                assert_eq!(out.status.code(), Some(1), "{err}");
                let aside = hidden("R");
                assert_eq!(aside.len(), 1, "{:?}", listing(&scratch));
                assert!(aside[0].starts_with(".R.replaced-"), "{aside:?}");
                assert!(err.contains(&aside[0]) && err.contains("by hand"), "{err}");
                // the file moved with the previous report
                drop(guard);
                let moved = scratch.join(&aside[0]).join("figures/fig08.csv");
                drop(Unwritable(moved, true));
                std::fs::remove_dir_all(scratch.join(&aside[0])).unwrap();
            } else {
                // found before any work
                refused_naming(
                    &out,
                    "--out-dir",
                    &["cannot be replaced"],
                    "read-only report",
                );
                drop(guard);
            }
        }
    }
    assert!(hidden("R").is_empty(), "{:?}", listing(&scratch));
    let _ = std::fs::remove_dir_all(&scratch);
}

/// Class 4: an option typed for another method or mode is refused, naming it and what it
/// applies to; left at its default it is not.
#[test]
fn options_that_would_be_ignored_are_refused() {
    let ens = [
        "ensemble", "--preset", "fig11", "--paths", "2", "--t-end", "10",
    ];
    let cases: &[(&[&str], &str, &str)] = &[
        (
            &["--max-excursion", "-1"],
            "--max-excursion",
            "--method wells",
        ),
        (&["--clones", "3"], "--clones", "--method wells"),
        (
            &["--core-quantile", "0.7"],
            "--core-quantile",
            "--method wells",
        ),
        (&["--separation", "nan"], "--separation", "--method wells"),
        (
            &["--max-iterations", "0"],
            "--max-iterations",
            "--method wells",
        ),
        (
            &["--method", "wells", "--u0", "1,2"],
            "--u0",
            "--method direct",
        ),
        (
            &["--method", "wells", "--lanes", "4"],
            "--lanes",
            "--method direct",
        ),
    ];
    for (extra, flag, applies) in cases {
        let mut args = ens.to_vec();
        args.extend(extra.iter());
        refused_naming(&run(&args), flag, &[applies], &format!("{args:?}"));
    }
    let others: &[(&[&str], &str, &str)] = &[
        (
            &[
                "oscillation",
                "--preset",
                "fig15",
                "--x",
                "r=0.9:0.95:2",
                "--y",
                "mu0=0.001:0.3",
                "--method",
                "exact",
                "--dt",
                "0.02",
            ],
            "--dt",
            "--method simulation",
        ),
        (
            &[
                "oscillation",
                "--preset",
                "fig15",
                "--x",
                "r=0.9:0.95:2",
                "--y",
                "mu0=0.01:0.1:3",
                "--grid",
                "--tolerance",
                "0.01",
            ],
            "--tolerance",
            "without --grid",
        ),
        (
            &["lyapunov", "--method", "tangent", "--separation", "1e-6"],
            "--separation",
            "--method two-trajectory",
        ),
    ];
    for (args, flag, applies) in others {
        refused_naming(&run(args), flag, &[applies], &format!("{args:?}"));
    }
    // defaults are not "typed": the direct method runs with the wells' sizes at theirs
    ok_stdout(&ens);
}

/// Class 5: where the well decomposition's weights are undetermined, no statistic of the
/// mixture is computed from substituted weights: the distances and the simulated mode count
/// are null like the density, and the CSV writes empty cells where the JSON has null (exit 0,
/// not 1).
#[test]
fn undefined_stays_undefined() {
    let args = [
        "ensemble",
        "--preset",
        "fig11",
        "--param",
        "lambda=0.998",
        "--method",
        "wells",
        "--paths",
        "2",
        "--t-end",
        "200",
        "--clones",
        "10",
        "--max-iterations",
        "50",
    ];
    let doc: serde_json::Value = serde_json::from_str(&ok_stdout(&args)).unwrap();
    let refusals = doc["decomposition"]["refusals"].to_string();
    assert!(refusals.contains("weights are undetermined"), "{refusals}");
    assert!(doc["amplitude"]["density"][0].is_null());
    assert_eq!(doc["per_path_amplitude"], serde_json::json!([]));
    for variant in ["paper", "consistent"] {
        let t = &doc["theory"][variant];
        for key in ["hellinger", "l1", "ks"] {
            assert!(t[key]["value"].is_null(), "{variant} {key}: {}", t[key]);
            assert!(t[key]["stderr"].is_null(), "{variant} {key}: {}", t[key]);
        }
        assert!(t["modes_mc"].is_null(), "{variant}: {}", t["modes_mc"]);
        // the theory's own numbers stand
        assert!(t["modes_theory"].is_u64() && t["mean_amplitude"].is_number());
    }
    let mut csv = args.to_vec();
    csv.extend(["--format", "csv"]);
    let text = ok_stdout(&csv);
    assert!(text.contains("does not exist (JSON null)"), "{text}");
    let rows = csv_rows(&text);
    assert_eq!(rows[0], ["A_lo", "A_hi", "density", "stderr"]);
    assert!(rows[1..].iter().all(|r| r[2].is_empty() && r[3].is_empty()));
    assert!(
        !text.contains("Hellinger"),
        "a distance from substituted weights"
    );
}

/// Run `command` on a pseudo-terminal (`script`) for `seconds`, then SIGINT: what the terminal
/// showed. `None` where `script` or `timeout` is missing.
#[cfg(target_os = "linux")]
fn on_a_terminal(args: &[&str], seconds: f64) -> Option<String> {
    let have = |tool: &str| {
        Command::new("sh")
            .args(["-c", &format!("command -v {tool}")])
            .stdout(Stdio::null())
            .status()
            .is_ok_and(|s| s.success())
    };
    if !have("script") || !have("timeout") {
        eprintln!("skipped: `script` (util-linux) and `timeout` are needed for a pseudo-terminal");
        return None;
    }
    let line = std::iter::once(env!("CARGO_BIN_EXE_trirhythm"))
        .chain(args.iter().copied())
        .map(|a| format!("'{a}'"))
        .collect::<Vec<_>>()
        .join(" ");
    let out = Command::new("script")
        .args([
            "-qfec",
            &format!("timeout -s INT {seconds} {line}"),
            "/dev/null",
        ])
        .env("TERM", "xterm")
        .stdin(Stdio::null())
        .stderr(Stdio::null())
        .output()
        .unwrap();
    Some(String::from_utf8_lossy(&out.stdout).into_owned())
}

/// Classes 6 and 7: on a terminal the elapsed time moves at least once a second, from the
/// first second — while no unit of work has finished, and during the set-up checks before the
/// first bar — with a rate; on a pipe nothing is drawn.
#[cfg(target_os = "linux")]
#[test]
fn progress_moves_on_a_terminal_from_the_first_second() {
    // the first unit of work takes far longer than the 3.5 s watched
    let critical = [
        "critical-noise",
        "--d-range",
        "0.01:1",
        "--paths",
        "100000",
        "--t-end",
        "1e8",
    ];
    // 1000 points' step checks before any bar (about 15 s)
    let sweep = [
        "lyapunov",
        "--paths",
        "100000",
        "--t-end",
        "1e8",
        "--sweep",
        "D=0:1:1000",
    ];
    for (args, needles) in [
        (&critical[..], &["none done yet"][..]),
        (&sweep[..], &["preparing"][..]),
    ] {
        let Some(shown) = on_a_terminal(args, 3.5) else {
            return;
        };
        for s in ["1s elapsed", "2s elapsed"] {
            assert!(shown.contains(s), "{args:?}: never showed {s}:\n{shown}");
        }
        for n in needles {
            assert!(shown.contains(n), "{args:?}: {n} not shown:\n{shown}");
        }
    }
    // on a pipe: nothing drawn
    let child = Command::new(env!("CARGO_BIN_EXE_trirhythm"))
        .args(sweep)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(Duration::from_millis(1500));
    Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    let (_, stderr) = wait_with_stderr(child);
    assert!(!stderr.contains("elapsed"), "{stderr}");
}
