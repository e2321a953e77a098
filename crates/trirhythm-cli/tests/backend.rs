//! `trirhythm ensemble --backend` and `trirhythm map --simulate --backend`: `cpu` is the
//! default's bits; `gpu` without a driver or a device fails with the GPU backend's reason before
//! any output; an unknown name is refused; `map --backend` without `--simulate` is refused.

mod common;

use common::{ok_json, run, scratch_dir};
use serde_json::Value;

/// A small run of fig13a's ensemble with `extra` flags.
fn small(extra: &[&str]) -> Vec<String> {
    let mut a: Vec<String> = [
        "ensemble",
        "--preset",
        "fig13a",
        "--paths",
        "2",
        "--t-end",
        "20",
        "--burn-in",
        "5",
        "--bins",
        "20",
        "--joint-bins",
        "8",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    a.extend(extra.iter().map(|s| s.to_string()));
    a
}

fn refs(a: &[String]) -> Vec<&str> {
    a.iter().map(String::as_str).collect()
}

fn without_wall_time(mut v: Value) -> Value {
    v["wall_time_s"] = Value::Null;
    v
}

#[test]
fn the_cpu_backend_is_the_default_bit_for_bit() {
    let default = ok_json(&refs(&small(&[])));
    let cpu = ok_json(&refs(&small(&["--backend", "cpu"])));
    assert!(default.get("backend").is_none());
    assert_eq!(without_wall_time(default), without_wall_time(cpu));
}

#[test]
fn the_gpu_backend_without_a_device_fails_before_any_output() {
    let dir = scratch_dir("backend-gpu");
    let out_file = dir.join("ensemble.json");
    let out = run(&refs(&small(&[
        "--backend",
        "gpu",
        "--out",
        out_file.to_str().unwrap(),
    ])));
    let stderr = String::from_utf8_lossy(&out.stderr);
    if trirhythm_gpu::cuda::device().is_ok() && out.status.success() {
        // a machine with a GPU and the kernel: the document says where it ran
        let v: Value = serde_json::from_str(&std::fs::read_to_string(&out_file).unwrap()).unwrap();
        assert_eq!(v["backend"], "gpu");
        return;
    }
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("the GPU backend does not apply"),
        "no reason given: {stderr}"
    );
    if trirhythm_gpu::cuda::device().is_err() {
        assert!(
            stderr.contains("a CUDA driver and device") && stderr.contains("libcuda"),
            "{stderr}"
        );
    }
    assert!(out.stdout.is_empty(), "partial output on stdout");
    assert!(!out_file.exists(), "partial output in --out");
    let left: Vec<_> = std::fs::read_dir(&dir).unwrap().collect();
    assert!(left.is_empty(), "files left behind: {left:?}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn an_unknown_backend_is_refused_naming_the_choices() {
    let out = run(&refs(&small(&["--backend", "tpu"])));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("'tpu'") && stderr.contains("--backend") && stderr.contains("cpu, gpu"),
        "{stderr}"
    );
    assert!(out.stdout.is_empty());
}

#[test]
fn the_gpu_backend_refuses_what_it_does_not_do() {
    for (extra, names) in [
        (&["--method", "wells"][..], "--method direct only"),
        (
            &["--lanes", "4"][..],
            "--lanes applies to --backend cpu only",
        ),
    ] {
        let mut a = vec!["--backend", "gpu"];
        a.extend_from_slice(extra);
        let out = run(&refs(&small(&a)));
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{stderr}");
        assert!(stderr.contains(names), "{extra:?}: {stderr}");
        assert!(out.stdout.is_empty());
    }
}

/// A 2×2 simulated map of Fig. 13(a)'s set with `extra` flags.
fn small_map(extra: &[&str]) -> Vec<String> {
    let mut a: Vec<String> = [
        "map",
        "--simulate",
        "--preset",
        "fig13a",
        "--x",
        "D=0.1:0.2:2",
        "--y",
        "tau=0.5:0.6:2",
        "--paths",
        "2",
        "--t-end",
        "40",
        "--burn-in",
        "4",
        "--dt",
        "0.05",
        "--batches",
        "4",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    a.extend(extra.iter().map(|s| s.to_string()));
    a
}

#[test]
fn the_simulated_map_takes_the_backend() {
    let default = run(&refs(&small_map(&["--format", "json"])));
    let cpu = run(&refs(&small_map(&["--format", "json", "--backend", "cpu"])));
    assert!(
        default.status.success(),
        "{}",
        String::from_utf8_lossy(&default.stderr)
    );
    let strip = |o: &std::process::Output| {
        let mut v: Value = serde_json::from_slice(&o.stdout).unwrap();
        v["wall_time_s"] = Value::Null;
        v
    };
    assert_eq!(strip(&default), strip(&cpu));
    if trirhythm_gpu::cuda::device().is_err() {
        let dir = scratch_dir("backend-map");
        let out_file = dir.join("map.csv");
        let gpu = run(&refs(&small_map(&[
            "--backend",
            "gpu",
            "--out",
            out_file.to_str().unwrap(),
        ])));
        let stderr = String::from_utf8_lossy(&gpu.stderr);
        assert_eq!(gpu.status.code(), Some(2), "{stderr}");
        assert!(stderr.contains("a CUDA driver and device"), "{stderr}");
        assert!(
            gpu.stdout.is_empty() && !out_file.exists(),
            "partial output"
        );
        let _ = std::fs::remove_dir_all(&dir);
    }
    // the theory's map has no backend
    let theory = run(&[
        "map",
        "--preset",
        "fig13a",
        "--x",
        "D=0.1:0.2:2",
        "--y",
        "tau=0.5:0.6:2",
        "--backend",
        "gpu",
    ]);
    let stderr = String::from_utf8_lossy(&theory.stderr);
    assert_eq!(theory.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("--backend applies to --simulate only"),
        "{stderr}"
    );
}
