//! Files the tool reads may be damaged or hostile: `figure N --from-data DIR` and
//! `report --from-data DIR` read `figNN.json` written by `figure N --data`. Whatever the file
//! holds, the tool either renders it (exit 0) or refuses it as bad input (exit 2, naming the
//! file), never panics, and a refused figure leaves none of its files behind.
//!
//! Method: a property test by mutation. Each figure's `--quick --data` JSON is mutated in a
//! deterministic sample of ways (every array truncated, emptied or extended, numbers replaced
//! by 0, −1, 1e308 or the string "NaN", `start`/`stop` swapped, fields dropped, another
//! version's stamp) and read back.

mod common;

use common::{ok_output, quick_data, run, scratch_dir};
use serde_json::Value;
use std::path::{Path, PathBuf};

/// Every place in a JSON value, as a path of object keys and array indices.
#[derive(Clone, Debug)]
enum Step {
    Key(String),
    Index(usize),
}

fn places(v: &Value, path: &mut Vec<Step>, out: &mut Vec<Vec<Step>>) {
    out.push(path.clone());
    match v {
        Value::Object(m) => {
            for (k, x) in m {
                path.push(Step::Key(k.clone()));
                places(x, path, out);
                path.pop();
            }
        }
        Value::Array(a) => {
            // the first, second and last element stand for the rest
            let mut idx: Vec<usize> = [0, 1, a.len().saturating_sub(1)]
                .into_iter()
                .filter(|&i| i < a.len())
                .collect();
            idx.dedup();
            for i in idx {
                path.push(Step::Index(i));
                places(&a[i], path, out);
                path.pop();
            }
        }
        _ => {}
    }
}

fn at<'a>(v: &'a mut Value, path: &[Step]) -> &'a mut Value {
    path.iter().fold(v, |v, s| match s {
        Step::Key(k) => &mut v[k.as_str()],
        Step::Index(i) => &mut v[*i],
    })
}

/// The mutations of the value at one place (each a description and the mutated document).
fn mutations(doc: &Value, path: &[Step]) -> Vec<(String, Value)> {
    let mut out = Vec::new();
    let mut with = |what: &str, f: &dyn Fn(&mut Value)| {
        let mut d = doc.clone();
        f(at(&mut d, path));
        out.push((format!("{path:?}: {what}"), d));
    };
    let here = {
        let mut d = doc.clone();
        at(&mut d, path).clone()
    };
    match &here {
        Value::Array(a) if !a.is_empty() => {
            with("truncated", &|v| {
                v.as_array_mut().unwrap().pop();
            });
            with("emptied", &|v| v.as_array_mut().unwrap().clear());
            with("extended", &|v| {
                let a = v.as_array_mut().unwrap();
                a.push(a[a.len() - 1].clone());
            });
        }
        Value::Number(_) => {
            for x in [
                Value::from(0),
                Value::from(-1),
                Value::from(1e308),
                Value::from("NaN"),
            ] {
                with(&format!("= {x}"), &|v| *v = x.clone());
            }
        }
        Value::Object(m) => {
            if m.contains_key("start") && m.contains_key("stop") {
                with("start and stop swapped", &|v| {
                    let (a, b) = (v["start"].clone(), v["stop"].clone());
                    v["start"] = b;
                    v["stop"] = a;
                });
            }
            if let Some(k) = m.keys().next().cloned() {
                with(&format!("without {k}"), &|v| {
                    v.as_object_mut().unwrap().remove(&k);
                });
            }
        }
        _ => {}
    }
    out
}

/// A deterministic sample of `n` of the items (a fixed linear congruential sequence).
fn sample<T: Clone>(items: &[T], n: usize, seed: u64) -> Vec<T> {
    let mut s = seed
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    (0..n.min(items.len()))
        .map(|_| {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            items[(s >> 33) as usize % items.len()].clone()
        })
        .collect()
}

fn files_in(dir: &Path) -> Vec<PathBuf> {
    std::fs::read_dir(dir)
        .map(|r| r.map(|e| e.unwrap().path()).collect())
        .unwrap_or_default()
}

/// Run `args` on a mutated `figNN.json`; exit 0 or 2, no panic, nothing written on exit 2.
fn read_back(n: u32, what: &str, doc: &Value, dir: &Path, args: &[&str]) -> i32 {
    let (data, out) = (dir.join("data"), dir.join("out"));
    let _ = std::fs::remove_dir_all(dir);
    std::fs::create_dir_all(&data).unwrap();
    std::fs::write(
        data.join(format!("fig{n:02}.json")),
        serde_json::to_string(doc).unwrap(),
    )
    .unwrap();
    let mut all: Vec<&str> = args.to_vec();
    all.extend(["--from-data", data.to_str().unwrap(), "--out-dir"]);
    all.push(out.to_str().unwrap());
    let o = run(&all);
    let err = String::from_utf8_lossy(&o.stderr);
    let code = o.status.code().unwrap_or(-1);
    assert!(
        !err.contains("panicked"),
        "figure {n}, {what}: panicked: {err}"
    );
    assert!(
        code == 0 || code == 2,
        "figure {n}, {what}: exit {code}: {err}"
    );
    if code == 2 {
        assert!(
            err.contains(&format!("fig{n:02}.json")),
            "figure {n}, {what}: the error does not name the file: {err}"
        );
        let left: Vec<_> = files_in(&out)
            .into_iter()
            .filter(|p| p.to_string_lossy().contains(&format!("fig{n:02}")))
            .collect();
        assert!(
            left.is_empty(),
            "figure {n}, {what}: refused but left {left:?}"
        );
    }
    code
}

/// The figures whose quick data is computed and mutated (a second or two each).
const FIGURES: [u32; 19] = [
    1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19,
];

/// Five mutations of figure `n`'s quick data (from `computed`), each read back in a case
/// directory under `dir`: (refused, total).
fn mutate_and_read_back(n: u32, computed: &Path, dir: &Path) -> (usize, usize) {
    let (mut refused, mut total) = (0, 0);
    let text = std::fs::read_to_string(computed.join(format!("fig{n:02}.json"))).unwrap();
    let doc: Value = serde_json::from_str(&text).unwrap();
    let mut ps = Vec::new();
    places(&doc, &mut Vec::new(), &mut ps);
    let all: Vec<(String, Value)> = ps.iter().flat_map(|p| mutations(&doc, p)).collect();
    // grid shapes first: every `counts`, `wells`, `density`, `edges`, `start`/`stop`
    let named: Vec<_> = all
        .iter()
        .filter(|(w, _)| {
            [
                "counts", "wells", "density", "edges", "start", "stop", "count",
            ]
            .iter()
            .any(|k| w.contains(&format!("\"{k}\"")))
        })
        .cloned()
        .collect();
    let mut chosen = sample(&named, 3, n as u64);
    chosen.extend(sample(&all, 2, 1000 + n as u64));
    let case = dir.join(format!("case-{n}"));
    let args = ["figure", &n.to_string()];
    // the data as written renders
    assert_eq!(read_back(n, "intact", &doc, &case, &args), 0, "figure {n}");
    for (what, m) in &chosen {
        if read_back(n, what, m, &case, &args) == 2 {
            refused += 1;
        }
        total += 1;
    }
    (refused, total)
}

/// Five mutations of every figure's quick data, each rendered or refused, never a panic:
/// three that change a grid's shape and two of any kind (a fixed sample of the few hundred
/// that `mutations` finds).
#[test]
fn mutated_figure_data_is_rendered_or_refused_never_panics() {
    let dir = scratch_dir("malformed");
    // every figure's `--quick --data`, computed once for the CLI's tests
    let computed = quick_data();
    // the figures on every core (each read-back is a process of its own): (refused, total)
    let next = std::sync::atomic::AtomicUsize::new(0);
    let workers = std::thread::available_parallelism().map_or(2, |n| n.get().min(4));
    let counts: Vec<(usize, usize)> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..workers)
            .map(|_| {
                scope.spawn(|| {
                    let (mut refused, mut total) = (0, 0);
                    while let Some(&n) =
                        FIGURES.get(next.fetch_add(1, std::sync::atomic::Ordering::Relaxed))
                    {
                        let (r, t) = mutate_and_read_back(n, computed, &dir);
                        refused += r;
                        total += t;
                    }
                    (refused, total)
                })
            })
            .collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    let refused: usize = counts.iter().map(|c| c.0).sum();
    let total: usize = counts.iter().map(|c| c.1).sum();
    // most of the mutations break the data's shape or range, and are refused
    assert!(
        refused * 2 > total,
        "only {refused} of {total} mutations refused"
    );
}

#[test]
fn data_of_another_version_is_refused_naming_the_field() {
    let dir = scratch_dir("malformed-version");
    let computed = dir.join("computed");
    ok_output(&[
        "figure",
        "4",
        "--quick",
        "--data",
        "--out-dir",
        computed.to_str().unwrap(),
    ]);
    let text = std::fs::read_to_string(computed.join("fig04.json")).unwrap();
    let mut doc: Value = serde_json::from_str(&text).unwrap();
    doc["trirhythm"] = Value::from("0.0.1");
    let case = dir.join("case");
    for args in [&["figure", "4"][..], &["report"][..]] {
        let code = read_back(4, "another version", &doc, &case, args);
        assert_eq!(code, 2, "{args:?}: data of another version accepted");
    }
    let o = run(&[
        "figure",
        "4",
        "--from-data",
        case.join("data").to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("trirhythm"), "the field is not named: {err}");
    // a truncated grid is refused by `report --from-data` too
    let mut bad = doc.clone();
    bad["trirhythm"] = serde_json::from_str::<Value>(&text).unwrap()["trirhythm"].clone();
    assert_eq!(read_back(4, "intact", &bad, &case, &["report"]), 0);
}

/// `lyapunov --format csv` writes what the JSON does: an undefined running estimate (JSON
/// `"NaN"` or `null`) is an empty `lle` cell, never a refusal. Without a transient the first
/// renormalisations have no estimate yet, so the run has undefined rows to write.
#[test]
fn lyapunov_csv_writes_every_row_the_json_has() {
    let base = [
        "lyapunov",
        "--t-end",
        "5",
        "--paths",
        "2",
        "--transient",
        "0",
    ];
    let json: Value = serde_json::from_slice(&ok_output(&base).stdout).unwrap();
    let running = json["running"].as_array().expect("running estimate");
    let mut csv_args = base.to_vec();
    csv_args.extend(["--format", "csv"]);
    let text = String::from_utf8(ok_output(&csv_args).stdout).unwrap();
    let rows = common::csv_rows(&text);
    assert_eq!(rows[0], ["t", "lle", "stderr"]);
    assert_eq!(rows.len() - 1, running.len(), "one CSV row per JSON entry");
    let mut undefined = 0;
    for (row, entry) in rows[1..].iter().zip(running) {
        let v = &entry["value"];
        if v.is_null() || v == "NaN" {
            assert_eq!(row[1], "", "undefined estimate at t = {}", row[0]);
            undefined += 1;
        } else if let Some(x) = v.as_f64() {
            assert_eq!(row[1].parse::<f64>().unwrap(), x);
        } else {
            panic!("running value {v} at t = {}", row[0]);
        }
    }
    assert!(
        undefined > 0,
        "the case was meant to have undefined estimates"
    );
}

/// D is what critical-noise searches: a value given for it is refused, naming it.
#[test]
fn critical_noise_refuses_a_value_for_d() {
    let o = run(&["critical-noise", "--d-range", "0:1", "--param", "D=0.5"]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("--param D=0.5") && err.contains("--d-range"),
        "{err}"
    );
    assert!(o.stdout.is_empty());
}
