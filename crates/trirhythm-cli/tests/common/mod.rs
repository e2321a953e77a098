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
