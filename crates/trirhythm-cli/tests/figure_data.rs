//! A figure's data is a value of its own: `figure N --data` writes it as `figNN.json`, and
//! `figure N --from-data DIR` renders it again without computing. Reading the data back loses
//! nothing (the JSON written again is the same bytes) and rendering is a function of the data
//! alone (the CSV, PNG and SVG drawn from the data read back are the same bytes as those drawn
//! from the computed value).

mod common;

use common::{csv_rows, ok_output, quick_data, run, scratch_dir};
use serde_json::Value;
use std::collections::BTreeMap;
use std::path::Path;

/// The files of a directory by name, with their bytes.
fn files(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| {
            let p = e.unwrap().path();
            let name = p.file_name().unwrap().to_string_lossy().into_owned();
            (name, std::fs::read(&p).unwrap())
        })
        .collect()
}

#[test]
fn figures_render_identically_from_their_data_read_back() {
    let dir = scratch_dir("figure-data");
    // `figure all --quick --data`, computed once for the CLI's tests
    let (computed, rendered) = (quick_data().to_path_buf(), dir.join("rendered"));
    let (c, r) = (computed.to_str().unwrap(), rendered.to_str().unwrap());
    ok_output(&["figure", "all", "--from-data", c, "--data", "--out-dir", r]);
    let (a, b) = (files(&computed), files(&rendered));
    let figures = [1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 12];
    for n in figures {
        for ext in ["json", "csv", "png", "svg"] {
            let name = format!("fig{n:02}.{ext}");
            assert!(a.contains_key(&name), "{name} not written");
        }
        let json: Value = serde_json::from_slice(&a[&format!("fig{n:02}.json")]).unwrap();
        assert_eq!(json["figure"], n, "fig{n:02}.json: figure number");
        assert_eq!(json["variant"], "paper", "fig{n:02}.json: variant");
        assert_eq!(json["quick"], true, "fig{n:02}.json: quality");
        assert!(json["data"].is_object(), "fig{n:02}.json: no data");
    }
    for n in [2, 3, 6, 10, 12] {
        assert!(a.contains_key(&format!("fig{n:02}_folds.csv")));
    }
    // every CSV of every figure parses with a CSV parser, every record with the header's
    // column count (panel names holding commas are quoted)
    let mut tables = 0;
    for (name, bytes) in a.iter().filter(|(n, _)| n.ends_with(".csv")) {
        let rows = csv_rows(std::str::from_utf8(bytes).unwrap());
        assert!(rows.len() > 1, "{name}: no rows");
        let width = rows[0].len();
        assert!(
            rows.iter().all(|r| r.len() == width),
            "{name}: a record's field count differs from the header's ({width})"
        );
        tables += 1;
    }
    assert!(tables >= 19, "{tables} CSV files");
    assert_eq!(
        a.keys().collect::<Vec<_>>(),
        b.keys().collect::<Vec<_>>(),
        "the same files"
    );
    for (name, bytes) in &a {
        assert!(
            bytes == &b[name],
            "{name} differs when rendered from the data read back"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn data_is_written_only_when_asked() {
    let dir = scratch_dir("figure-no-data");
    ok_output(&["figure", "8", "--quick", "--out-dir", dir.to_str().unwrap()]);
    let names: Vec<String> = files(&dir).into_keys().collect();
    assert_eq!(names, ["fig08.csv", "fig08.png", "fig08.svg"]);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn unusable_data_is_bad_input() {
    let dir = scratch_dir("figure-bad-data");
    let d = dir.to_str().unwrap();
    let out = dir.join("out");
    let o = out.to_str().unwrap();
    let refused = |args: &[&str], says: &str| {
        let res = run(args);
        let err = String::from_utf8_lossy(&res.stderr);
        assert_eq!(res.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(says), "{args:?}: {err}");
    };
    // nothing there
    refused(
        &["figure", "4", "--from-data", d, "--out-dir", o],
        "fig04.json",
    );
    // another figure's data under this figure's name
    ok_output(&["figure", "8", "--quick", "--data", "--out-dir", d]);
    std::fs::copy(dir.join("fig08.json"), dir.join("fig04.json")).unwrap();
    refused(
        &["figure", "4", "--from-data", d, "--out-dir", o],
        "holds the data of figure 8",
    );
    // not JSON; JSON of the right number but not the figure's shape
    std::fs::write(dir.join("fig04.json"), "not json").unwrap();
    refused(
        &["figure", "4", "--from-data", d, "--out-dir", o],
        "is not figure data",
    );
    std::fs::write(dir.join("fig04.json"), r#"{"figure": 4, "data": {}}"#).unwrap();
    refused(
        &["figure", "4", "--from-data", d, "--out-dir", o],
        "is not the data of figure 4",
    );
    // the quality and the variant are the data's
    refused(
        &["figure", "8", "--from-data", d, "--quick", "--out-dir", o],
        "--quick",
    );
    refused(
        &[
            "figure",
            "8",
            "--from-data",
            d,
            "--variant",
            "consistent",
            "--out-dir",
            o,
        ],
        "--variant",
    );
    assert!(!out.exists(), "nothing written for refused requests");
    let _ = std::fs::remove_dir_all(&dir);
}
