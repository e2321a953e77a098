//! Paths are the same bits on every platform: the library's sources call no platform
//! elementary function outside the averaged theory, and a short noisy path with impacts is
//! pinned by a hash of its bits.
//!
//! Why the pinned constant holds on every platform by construction: a path is computed from its
//! parameters by IEEE 754 operations that are correctly rounded (+, −, ×, ÷, √; no fused
//! multiply–add is ever emitted by rustc unless written), integer arithmetic (ChaCha8, the
//! ziggurat's strip), and the functions of `trirhythm::maths`, which are the pure-Rust `libm`
//! crate's: the same operations in the same order on x86-64 and aarch64, whatever the C library.
//! The AVX and portable mode sums give the same bits (the memory's unit tests). So the hash
//! below changes only when the engine's results change: a change of the scheme, the noise
//! stream or the maths. (Built with the feature `std-maths`, the platform's functions are used
//! and the pin is skipped.)

use std::path::{Path, PathBuf};
use trirhythm::engine::{simulate, Options, PredictorCorrector, Problem};
use trirhythm::model::preset;

/// Method calls and paths that reach the platform's maths library or an unspecified precision.
const FORBIDDEN: &[&str] = &[
    ".exp()",
    ".exp_m1()",
    ".exp2()",
    ".ln()",
    ".ln_1p()",
    ".log(",
    ".log2()",
    ".log10()",
    ".powf(",
    ".powi(",
    ".sin()",
    ".cos()",
    ".tan()",
    ".sin_cos()",
    ".asin()",
    ".acos()",
    ".atan()",
    ".atan2(",
    ".sinh()",
    ".cosh()",
    ".tanh()",
    ".cbrt()",
    ".hypot(",
    ".mul_add(",
    "f64::exp",
    "f64::ln",
    "f64::pow",
    "f64::sin",
    "f64::cos",
    "StandardNormal",
];

/// Sources allowed to call the platform's functions: the averaged theory, the exact solutions
/// of the tests, the maths module itself (its `std-maths` variant) and the error messages'
/// digit count.
fn exempt(rel: &str) -> bool {
    rel.starts_with("theory/")
        || rel.starts_with("maths")
        || rel == "known_answers.rs"
        || rel == "error.rs"
        || rel.ends_with("/tests.rs")
}

/// The lines of `text` outside `#[cfg(test)]` items, without `//` comments.
fn non_test_code(text: &str) -> Vec<(usize, String)> {
    let lines: Vec<&str> = text.lines().collect();
    let mut out = vec![];
    let mut i = 0;
    while i < lines.len() {
        let line = lines[i];
        if line.trim() == "#[cfg(test)]" {
            let indent = &line[..line.len() - line.trim_start().len()];
            let close = format!("{indent}}}");
            // a one-line item (`use …;`) or a block up to its closing brace at the same indent
            if lines
                .get(i + 1)
                .is_some_and(|l| l.trim_end().ends_with(';'))
            {
                i += 2;
            } else {
                while i < lines.len() && lines[i].trim_end() != close {
                    i += 1;
                }
                i += 1;
            }
            continue;
        }
        let code = line.split("//").next().unwrap_or("");
        out.push((i + 1, code.to_string()));
        i += 1;
    }
    out
}

/// Every forbidden call in `text`, as "line: pattern".
fn forbidden_calls(text: &str) -> Vec<String> {
    non_test_code(text)
        .into_iter()
        .flat_map(|(n, code)| {
            FORBIDDEN
                .iter()
                .filter(move |p| code.contains(*p))
                .map(move |p| format!("{n}: {p}"))
        })
        .collect()
}

fn sources(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            sources(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

#[test]
fn the_scan_finds_calls_and_skips_tests_and_comments() {
    let text = "fn f(x: f64) -> f64 {\n    x.exp() // e^x\n}\n// y.ln()\n#[cfg(test)]\nuse std::f64::consts::PI;\nfn g(x: f64) -> f64 { x.powi(2) }\n#[cfg(test)]\nmod tests {\n    fn h(x: f64) -> f64 {\n        x.sin()\n    }\n}\nfn k(x: f64) -> f64 { x.hypot(1.0) }\n    #[cfg(test)]\n    fn inner(x: f64) -> f64 {\n        x.cos()\n    }\n";
    assert_eq!(
        forbidden_calls(text),
        vec!["2: .exp()", "7: .powi(", "14: .hypot("]
    );
}

#[test]
fn no_platform_maths_outside_the_averaged_theory() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = vec![];
    sources(&root, &mut files);
    assert!(files.len() > 50, "{} source files found", files.len());
    let mut found = vec![];
    let mut scanned = 0;
    for file in files {
        let rel = file
            .strip_prefix(&root)
            .unwrap()
            .to_string_lossy()
            .replace('\\', "/");
        if exempt(&rel) {
            continue;
        }
        scanned += 1;
        let text = std::fs::read_to_string(&file).unwrap();
        found.extend(
            forbidden_calls(&text)
                .into_iter()
                .map(|c| format!("{rel}:{c}")),
        );
    }
    assert!(scanned > 40, "{scanned} files scanned");
    assert!(
        found.is_empty(),
        "platform maths outside the averaged theory (use trirhythm::maths): {found:#?}"
    );
}

/// FNV-1a over the bits of every recorded U and V.
fn hash(u: &[f64], v: &[f64]) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for x in u.iter().chain(v) {
        for b in x.to_bits().to_le_bytes() {
            h ^= b as u64;
            h = h.wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
    h
}

/// Case: `trirhythm simulate --preset fig13a --param r=0.3 --param D=0.5 --t-end 100 --seed 7
/// --tolerance 1e-10` (λ = 0.998, OU noise τ = 0.5, wall on, Δt = 0.01: 10⁴ steps, every node
/// recorded; the memory the bits were recorded with, the default before `Memory::Auto`).
#[test]
fn a_noisy_path_with_impacts_is_pinned_to_the_bit() {
    let p = preset("fig13a")
        .unwrap()
        .params
        .with("r", 0.3)
        .unwrap()
        .with("D", 0.5)
        .unwrap();
    let o = Options {
        t_end: 100.0,
        seed: 7,
        record_every: 1,
        ..Default::default()
    };
    let problem = Problem::from_params(&p).unwrap();
    let m = PredictorCorrector {
        memory: trirhythm::engine::Memory::SumOfExponentials {
            tolerance: trirhythm::engine::PREVIOUS_DEFAULT_TOLERANCE,
        },
        ..Default::default()
    };
    let tr = simulate(&problem, &m, &o).unwrap();
    assert_eq!((tr.steps, tr.u.len()), (10_000, 10_001));
    let h = hash(&tr.u, &tr.v);
    println!(
        "impacts {}, sticking steps {}, hash {h:#018x}",
        tr.impacts, tr.sticking_steps
    );
    if trirhythm::maths::PLATFORM_MATHS {
        return;
    }
    assert_eq!((tr.impacts, tr.sticking_steps), (83, 551));
    assert_eq!(h, 0x63c1_48bb_4454_2221, "the bits of the path changed");
}
