//! `trirhythm ensemble --checkpoint`: a directory is bound to its run. Two runs cannot share
//! it (a lock), a path file from another run, a path file under another index and path files
//! without their `run.txt` are refused with exit 2, and a resumed run equals a fresh one.

mod common;

use common::{ok_json, run, scratch_dir};
use serde_json::Value;
use std::path::Path;

/// A small run of `seed`.
fn base(seed: &str) -> Vec<String> {
    [
        "ensemble",
        "--preset",
        "fig13a",
        "--paths",
        "4",
        "--t-end",
        "300",
        "--burn-in",
        "10",
        "--seed",
        seed,
    ]
    .iter()
    .map(|s| s.to_string())
    .collect()
}

fn with_cp(seed: &str, cp: &Path) -> Vec<String> {
    let mut a = base(seed);
    a.extend(["--checkpoint".to_string(), cp.to_str().unwrap().to_string()]);
    a
}

fn strs(a: &[String]) -> Vec<&str> {
    a.iter().map(String::as_str).collect()
}

fn without_wall_time(mut v: Value) -> Value {
    v.as_object_mut().unwrap().remove("wall_time_s");
    v
}

/// The run's JSON without the wall time.
fn result(args: &[String]) -> Value {
    without_wall_time(ok_json(&strs(args)))
}

/// Exit 2 with `needles` in the message.
fn refused(args: &[String], needles: &[&str]) {
    let out = run(&strs(args));
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
    for n in needles {
        assert!(err.contains(n), "{n:?} not in {err}");
    }
}

#[test]
fn two_runs_on_one_directory_cannot_mix() {
    use std::process::{Command, Stdio};
    let dir = scratch_dir("ckpt-race");
    // long enough for the two runs to overlap; several trials, as the start order is chance
    let longer = |a: Vec<String>| {
        let mut a = a;
        a[6] = "3000".into();
        a
    };
    for trial in 0..4 {
        let cp = dir.join(format!("cp{trial}"));
        let spawn = |seed: &str| {
            Command::new(env!("CARGO_BIN_EXE_trirhythm"))
                .args(longer(with_cp(seed, &cp)))
                .stdout(Stdio::piped())
                .stderr(Stdio::piped())
                .spawn()
                .unwrap()
        };
        let (a, b) = (spawn("1"), spawn("2"));
        let (a, b) = (a.wait_with_output().unwrap(), b.wait_with_output().unwrap());
        let codes = (a.status.code(), b.status.code());
        let winner = match codes {
            (Some(0), Some(2)) => "1",
            (Some(2), Some(0)) => "2",
            _ => panic!(
                "trial {trial}: exactly one run must succeed, the other exit 2: {codes:?}\n{}\n{}",
                String::from_utf8_lossy(&a.stderr),
                String::from_utf8_lossy(&b.stderr)
            ),
        };
        assert!(!cp.join("lock").exists(), "the lock is removed at the end");
        let fresh = result(&longer(base(winner)));
        assert_eq!(
            result(&longer(with_cp(winner, &cp))),
            fresh,
            "trial {trial}: resume = run {winner}"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_held_lock_refuses_a_second_run() {
    let dir = scratch_dir("ckpt-lock");
    let cp = dir.join("cp");
    std::fs::create_dir_all(&cp).unwrap();
    // this test process is alive: the directory is in use
    let me = std::process::id().to_string();
    std::fs::write(cp.join("lock"), format!("pid {me}\nsomething")).unwrap();
    refused(&with_cp("1", &cp), &["in use by process", &me, "lock"]);
    assert!(cp.join("lock").exists(), "another run's lock is left alone");
    assert!(
        !cp.join("run.txt").exists(),
        "nothing written in a held directory"
    );
    std::fs::remove_file(cp.join("lock")).unwrap();
    result(&with_cp("1", &cp));
    assert!(!cp.join("lock").exists());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_foreign_path_file_is_refused() {
    let dir = scratch_dir("ckpt-foreign");
    let (a, b) = (dir.join("a"), dir.join("b"));
    result(&with_cp("1", &a));
    result(&with_cp("2", &b));
    std::fs::copy(b.join("path-1.json"), a.join("path-1.json")).unwrap();
    refused(&with_cp("1", &a), &["path-1.json", "another run"]);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_path_file_under_another_index_is_refused() {
    let dir = scratch_dir("ckpt-index");
    let cp = dir.join("cp");
    result(&with_cp("1", &cp));
    let f = cp.join("path-1.json");
    let mut v: Value = serde_json::from_str(&std::fs::read_to_string(&f).unwrap()).unwrap();
    assert_eq!(v["path"], 1);
    v["path"] = 2.into();
    std::fs::write(&f, serde_json::to_string(&v).unwrap()).unwrap();
    std::fs::remove_file(cp.join("path-2.json")).unwrap();
    refused(&with_cp("1", &cp), &["path-1.json", "holds path 2"]);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn path_files_without_their_run_are_refused() {
    let dir = scratch_dir("ckpt-orphan");
    let cp = dir.join("cp");
    result(&with_cp("2", &cp));
    std::fs::remove_file(cp.join("run.txt")).unwrap();
    refused(&with_cp("1", &cp), &["no run.txt", "path-"]);
    assert!(!cp.join("run.txt").exists(), "the directory is not adopted");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_partly_done_directory_resumes_to_the_fresh_result() {
    let dir = scratch_dir("ckpt-resume");
    let cp = dir.join("cp");
    let fresh = result(&base("3"));
    assert_eq!(result(&with_cp("3", &cp)), fresh);
    for i in [0, 2] {
        std::fs::remove_file(cp.join(format!("path-{i}.json"))).unwrap();
    }
    let out = run(&strs(&with_cp("3", &cp)));
    assert!(out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("2 of 4 paths already done"));
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(without_wall_time(v), fresh);
    assert!(!cp.join("lock").exists());
    let _ = std::fs::remove_dir_all(&dir);
}

#[cfg(unix)]
#[test]
fn an_interrupted_run_releases_the_directory() {
    use std::process::{Command, Stdio};
    use std::time::{Duration, Instant};
    let dir = scratch_dir("ckpt-signal");
    let cp = dir.join("cp");
    let mut args = with_cp("5", &cp);
    args[6] = "200000".into();
    for signal in ["-INT", "-TERM"] {
        let child = Command::new(env!("CARGO_BIN_EXE_trirhythm"))
            .args(&args)
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        let t = Instant::now();
        while !cp.join("lock").exists() && t.elapsed() < Duration::from_secs(60) {
            std::thread::sleep(Duration::from_millis(5));
        }
        assert!(cp.join("lock").exists(), "the run holds the directory");
        let status = Command::new("kill")
            .args([signal, &child.id().to_string()])
            .status()
            .unwrap();
        assert!(status.success());
        let out = child.wait_with_output().unwrap();
        assert_eq!(out.status.code(), Some(130), "{signal}");
        assert!(!cp.join("lock").exists(), "{signal} removes the lock");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_path_file_of_another_shape_is_refused() {
    let dir = scratch_dir("ckpt-shape");
    let cp = dir.join("cp");
    result(&with_cp("1", &cp));
    let f = cp.join("path-1.json");
    let mut v: Value = serde_json::from_str(&std::fs::read_to_string(&f).unwrap()).unwrap();
    let batches = v["batches"].as_array_mut().unwrap();
    assert!(batches.len() > 3);
    batches.truncate(3);
    std::fs::write(&f, serde_json::to_string(&v).unwrap()).unwrap();
    std::fs::remove_file(cp.join("path-2.json")).unwrap();
    refused(&with_cp("1", &cp), &["path-1.json", "another shape"]);
    let _ = std::fs::remove_dir_all(&dir);
}
