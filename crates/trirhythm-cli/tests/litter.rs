//! Bad input leaves nothing behind and is refused before any work: invalid ensemble sizes with
//! `--checkpoint` create no directory, an unwritable `--out` is refused at once (before a
//! long computation), a joint density too large for memory is refused before it is computed,
//! and an amplitude range too small for finite densities is refused with its reason.

mod common;

use common::run;
use std::path::Path;
use std::process::Output;
use std::time::{Duration, Instant};

/// A fresh empty directory for one test.
fn scratch(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("trirhythm-litter-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The entries of `dir` (hidden ones included).
fn entries(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

/// Assert a refusal: exit 2 with an `error:` line naming `flag`.
fn refused(out: &Output, flag: &str, args: &[&str]) -> String {
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
    assert!(
        err.contains("error:") && err.contains(flag),
        "{args:?}: {err}"
    );
    err
}

#[test]
fn invalid_ensemble_sizes_leave_no_checkpoint_directory() {
    let dir = scratch("checkpoint");
    let ck = dir.join("ck");
    let ck = ck.to_str().unwrap();
    let cases: &[(&[&str], &str)] = &[
        (&["--paths", "0"], "--paths"),
        (&["--paths", "2000000"], "--paths"),
        (&["--bins", "1"], "--bins"),
        (&["--joint-bins", "1"], "--joint-bins"),
        (&["--sample-every", "0"], "--sample-every"),
        (&["--t-end", "0"], "--t-end"),
        (&["--t-end", "0.001"], "--t-end"),
        (&["--burn-in", "-1"], "--burn-in"),
        (&["--amplitude-max", "0"], "amplitude_max = 0"),
        (&["--amplitude-max", "1e-300"], "--amplitude-max"),
        (&["--amplitude-max", "1e7"], "--amplitude-max"),
        (&["--dt", "0"], "dt = 0"),
    ];
    for (bad, flag) in cases {
        let mut args = vec![
            "ensemble",
            "--paths",
            "2",
            "--t-end",
            "20",
            "--checkpoint",
            ck,
        ];
        args.extend_from_slice(bad);
        let out = run(&args);
        refused(&out, flag, &args);
        assert_eq!(entries(&dir), Vec::<String>::new(), "{args:?} left files");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn amplitude_max_below_its_least_is_refused_with_the_reason() {
    let args = [
        "ensemble",
        "--paths",
        "2",
        "--t-end",
        "20",
        "--amplitude-max",
        "1e-300",
    ];
    let err = refused(&run(&args), "--amplitude-max", &args);
    assert!(err.contains("1e-100") && err.contains("underflow"), "{err}");
    // the least is accepted and gives a finite document
    let args = [
        "ensemble",
        "--paths",
        "2",
        "--t-end",
        "20",
        "--burn-in",
        "0",
    ];
    let mut with = args.to_vec();
    with.extend(["--amplitude-max", "1e-100"]);
    let out = run(&with);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let doc: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!(doc.is_object());
}

/// A directory no one can write in (a file cannot be created in /proc, even by root).
#[cfg(target_os = "linux")]
const UNWRITABLE: &str = "/proc/trirhythm-litter.csv";

#[cfg(target_os = "linux")]
#[test]
fn an_unwritable_destination_is_refused_before_the_work() {
    // each of these runs for many seconds when its destination is accepted
    let cases: &[&[&str]] = &[
        &[
            "oscillation",
            "--preset",
            "fig15",
            "--param",
            "lambda=1",
            "--x",
            "r=0.5:0.95:400",
            "--y",
            "mu0=0.001:0.3",
        ],
        &["ensemble", "--paths", "64", "--t-end", "20000"],
        &["lyapunov", "--paths", "64", "--t-end", "20000"],
        &[
            "critical-noise",
            "--d-range",
            "0.01:2",
            "--paths",
            "16",
            "--t-end",
            "5000",
        ],
    ];
    for case in cases {
        let mut args = case.to_vec();
        args.extend(["--out", UNWRITABLE]);
        let t = Instant::now();
        let out = run(&args);
        let err = refused(&out, "--out", &args);
        assert!(err.contains("cannot write"), "{err}");
        assert!(
            t.elapsed() < Duration::from_secs(10),
            "{args:?}: {:?}",
            t.elapsed()
        );
    }
}

#[test]
fn a_directory_as_destination_is_refused_and_left_alone() {
    let dir = scratch("destination");
    let d = dir.to_str().unwrap();
    let args = [
        "oscillation",
        "--preset",
        "fig15",
        "--x",
        "r=0.9:0.95:2",
        "--y",
        "mu0=0.001:0.3",
        "--out",
        d,
    ];
    refused(&run(&args), "--out", &args);
    assert_eq!(entries(&dir), Vec::<String>::new());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_joint_density_too_large_for_memory_is_refused_before_any_work() {
    let dir = scratch("joint");
    let out = dir.join("x.csv");
    let args = [
        "pdf",
        "--preset",
        "fig14",
        "--kind",
        "joint",
        "--grid",
        "0:5:10000",
        "--vgrid",
        "-5:5:10000",
        "--out",
        out.to_str().unwrap(),
    ];
    let t = Instant::now();
    let err = refused(&run(&args), "--grid", &args);
    assert!(t.elapsed() < Duration::from_secs(10), "{:?}", t.elapsed());
    // the message names the largest grid that fits with this --vgrid, and the square one
    assert!(err.contains("100000000 cells"), "{err}");
    assert!(
        err.contains("at most 250 points") && err.contains("1581 × 1581"),
        "{err}"
    );
    assert_eq!(entries(&dir), Vec::<String>::new());
    // one cell fewer than the bound on one side is accepted (small grids as before)
    let ok = [
        "pdf", "--preset", "fig14", "--kind", "joint", "--grid", "0:5:11", "--vgrid", "-5:5:7",
    ];
    let o = run(&ok);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_library_error_names_the_flag_typed() {
    for (args, flag) in [
        (&["ensemble", "--dt", "0", "--paths", "2"][..], "--dt"),
        (&["ensemble", "--dt", "nan", "--paths", "2"][..], "--dt"),
        (&["simulate", "--u0", "inf", "--t-end", "1"][..], "--u0"),
        (
            &["simulate", "--tolerance", "0.5", "--t-end", "1"][..],
            "--tolerance",
        ),
    ] {
        let o = common::run(args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(
            err.contains(&format!("error: {flag}:")),
            "{args:?} should name {flag}: {err}"
        );
    }
}
