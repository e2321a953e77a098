//! The Monte Carlo figures run their panels, ensembles, paths, splittings and Lyapunov points as
//! tasks of one work-stealing pool: their data do not depend on how many threads the pool has
//! (every random stream is keyed by the seed and an index, every reduction combines in a fixed
//! order), and recording the parallel profile (`--profile`) changes nothing but stderr.

mod common;

use common::scratch_dir;
use std::path::Path;
use std::process::Command;

/// Figures whose computation is all tasks of the pool (ensembles with well decompositions
/// and their splittings, Lyapunov curves with their Δt check); Fig. 14 runs the same
/// ensemble machinery as Fig. 13.
const FIGURES: [&str; 2] = ["13", "17"];

/// The CSV files of `figure N --quick` with `threads` threads (and `--profile` when asked),
/// each with its wall-clock note ("… steps in N s") blanked.
fn csv_files(figure: &str, threads: &str, profile: bool) -> Vec<(String, String)> {
    let dir = scratch_dir(&format!("threads-{figure}-{threads}-{profile}"));
    let mut args = vec!["figure", figure, "--quick", "--out-dir"];
    let out_dir = dir.to_string_lossy().into_owned();
    args.push(&out_dir);
    if profile {
        args.push("--profile");
    }
    let out = Command::new(env!("CARGO_BIN_EXE_trirhythm"))
        .args(&args)
        .env("RAYON_NUM_THREADS", threads)
        .output()
        .expect("binary runs");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{args:?}: {stderr}");
    assert_eq!(
        profile,
        stderr.contains(&format!("figure {figure} profile: total CPU")),
        "the profile is printed when asked, and only then: {stderr}"
    );
    let files = read_csv(&dir);
    let _ = std::fs::remove_dir_all(&dir);
    files
}

fn read_csv(dir: &Path) -> Vec<(String, String)> {
    let mut files: Vec<(String, String)> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "csv"))
        .map(|p| {
            let name = p.file_name().unwrap().to_string_lossy().into_owned();
            (
                name,
                without_wall_clock(&std::fs::read_to_string(&p).unwrap()),
            )
        })
        .collect();
    files.sort();
    assert!(!files.is_empty(), "no CSV written in {}", dir.display());
    files
}

/// `text` with the seconds of every "steps in N s" (a wall-clock time) replaced by `_`.
fn without_wall_clock(text: &str) -> String {
    let mut out = String::new();
    let mut rest = text;
    while let Some(at) = rest.find("steps in ") {
        let (head, tail) = rest.split_at(at + "steps in ".len());
        out.push_str(head);
        let digits = tail
            .find(|c: char| !(c.is_ascii_digit() || c == '.'))
            .unwrap_or(tail.len());
        out.push('_');
        rest = &tail[digits..];
    }
    out.push_str(rest);
    out
}

#[test]
fn quick_figures_are_the_same_bytes_for_1_2_and_16_threads() {
    for figure in FIGURES {
        let one = csv_files(figure, "1", false);
        for (threads, profile) in [("2", false), ("16", true)] {
            let other = csv_files(figure, threads, profile);
            assert_eq!(
                one.iter().map(|f| &f.0).collect::<Vec<_>>(),
                other.iter().map(|f| &f.0).collect::<Vec<_>>()
            );
            for ((name, a), (_, b)) in one.iter().zip(&other) {
                assert!(
                    a == b,
                    "figure {figure}: {name} differs between 1 and {threads} threads"
                );
            }
        }
    }
}

#[test]
fn the_wall_clock_note_is_blanked_and_nothing_else() {
    assert_eq!(
        without_wall_clock("a; 2.01e7 steps in 4 s; b 3 steps in 12.5 s"),
        "a; 2.01e7 steps in _ s; b 3 steps in _ s"
    );
    assert_eq!(without_wall_clock("no note"), "no note");
}
