//! `trirhythm ensemble --backend`: `cpu` is the default's bits; `gpu` without a driver or a
//! device fails with the GPU backend's reason before any output; an unknown name is refused.

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
