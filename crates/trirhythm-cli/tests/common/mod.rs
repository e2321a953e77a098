//! Helpers shared by the CLI tests: run the built binary, check success, parse its output.
// Each test crate uses a different subset.
#![allow(dead_code)]

use serde_json::Value;
use std::path::PathBuf;
use std::process::{Command, Output};

/// Run `trirhythm` with `args`.
pub fn run(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_trirhythm"))
        .args(args)
        .output()
        .expect("binary runs")
}

/// Run and assert success (stderr in the message otherwise).
pub fn ok_output(args: &[&str]) -> Output {
    let out = run(args);
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

/// Standard output of a successful run.
pub fn ok_stdout(args: &[&str]) -> String {
    String::from_utf8(ok_output(args).stdout).expect("UTF-8 output")
}

/// Standard output of a successful run, parsed as JSON.
pub fn ok_json(args: &[&str]) -> Value {
    serde_json::from_str(&ok_stdout(args)).expect("valid JSON")
}

/// Rows of a CSV document (`#` comment lines skipped), header first.
pub fn csv_rows(text: &str) -> Vec<Vec<String>> {
    // a real CSV parser (quoted fields, `#` comment lines), which refuses a record whose field
    // count differs from the header's
    csv::ReaderBuilder::new()
        .has_headers(false)
        .comment(Some(b'#'))
        .from_reader(text.as_bytes())
        .records()
        .map(|r| {
            r.unwrap_or_else(|e| panic!("not CSV: {e}"))
                .iter()
                .map(str::to_string)
                .collect()
        })
        .collect()
}

/// A fresh, empty directory under the system's temporary directory.
pub fn scratch_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("trirhythm-cli-test-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// `figure all --quick --data` of this build's binary (the paper's variant: each figure's
/// `figNN.json`, its SVG and PNG, the contact sheet), computed once and read by every test
/// binary that needs it (cargo runs them one after the other): a directory under Cargo's
/// target tmp named by the binary's size and modification time, so that a rebuilt binary
/// computes it afresh (older ones are removed). Tests read it and never write into it.
pub fn quick_data() -> &'static std::path::Path {
    static DIR: std::sync::OnceLock<PathBuf> = std::sync::OnceLock::new();
    DIR.get_or_init(|| {
        let bin = std::fs::metadata(env!("CARGO_BIN_EXE_trirhythm")).expect("the binary");
        let stamp = bin
            .modified()
            .expect("a modification time")
            .duration_since(std::time::UNIX_EPOCH)
            .expect("after 1970")
            .as_nanos();
        let root = PathBuf::from(env!("CARGO_TARGET_TMPDIR"));
        let name = format!("quick-data-{}-{stamp}", bin.len());
        let dir = root.join(&name);
        // the marker beside the directory: written once the directory is whole
        let marker = root.join(format!("{name}.complete"));
        if marker.exists() {
            return dir;
        }
        let _ = std::fs::remove_dir_all(&dir);
        ok_output(&[
            "figure",
            "all",
            "--quick",
            "--data",
            "--out-dir",
            dir.to_str().unwrap(),
        ]);
        std::fs::write(&marker, b"").unwrap();
        for entry in std::fs::read_dir(&root).unwrap().flatten() {
            let other = entry.file_name().to_string_lossy().into_owned();
            if other.starts_with("quick-data-") && !other.starts_with(&name) {
                let _ = std::fs::remove_dir_all(entry.path());
                let _ = std::fs::remove_file(entry.path());
            }
        }
        dir
    })
}
