//! Records the git commit the binary is built from as `TRIRHYTHM_COMMIT` (for the provenance
//! of `trirhythm report`): `git rev-parse --short=12 HEAD`, or `unknown` when git or the
//! repository is absent (a source tarball, `cargo install` from a registry). Never fails the
//! build.

use std::process::Command;

fn git(args: &[&str]) -> Option<String> {
    let out = Command::new("git").args(args).output().ok()?;
    if !out.status.success() {
        return None;
    }
    let text = String::from_utf8(out.stdout).ok()?.trim().to_string();
    (!text.is_empty()).then_some(text)
}

fn main() {
    let commit = git(&["rev-parse", "--short=12", "HEAD"]).unwrap_or_else(|| "unknown".into());
    println!("cargo:rustc-env=TRIRHYTHM_COMMIT={commit}");
    // run again when HEAD moves (a commit, a checkout); the files exist only in a repository
    for what in ["HEAD", "logs/HEAD"] {
        if let Some(path) = git(&["rev-parse", "--git-path", what]) {
            let path = std::path::Path::new(&path);
            let path = if path.is_relative() {
                std::path::Path::new(&std::env::var("CARGO_MANIFEST_DIR").unwrap_or_default())
                    .join(path)
            } else {
                path.to_path_buf()
            };
            if path.exists() {
                println!("cargo:rerun-if-changed={}", path.display());
            }
        }
    }
    println!("cargo:rerun-if-changed=build.rs");
}
