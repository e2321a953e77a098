//! The published systems of `examples/models/` (docs/published-systems.md), loaded from their
//! files and checked against what could be read of their papers, and against exact answers
//! where no published number could be read.
//!
//! - `trirhythmic-vdp.toml`, the extended van der Pol oscillator of Saha, Gangopadhyay and Ray
//!   (arXiv:2008.03499): the averaged drift against the printed amplitude equation (relative
//!   1e-12), the cycles against the roots of its printed polynomial (relative 1e-9), five of
//!   them stable-unstable-stable-unstable-stable as printed, and deterministic paths settling
//!   on the stable radii (their mean amplitude over the last 1000 time units within 0.2 %,
//!   the first-order method's O(μ0) at μ0 = 1e-3; measured −0.01 %, −0.00 %, +0.03 %).
//! - `bilateral-vibroimpact-duffing.toml`, the two-barrier vibro-impact Duffing oscillator of
//!   Yang, Xu, Gu and Huang (2016) with chosen parameters and r = 1: the ensemble's Var U and
//!   Var U̇ against the exact stationary density ∝ exp(−cH/D) on [−1, 1] (within four standard
//!   errors; measured −0.4 and −0.5); with the paper's parametric noise U·η_m added
//!   (D_m = 0.005), the exact energy balance ⟨U̇²⟩ = (D_a + D_m⟨U²⟩)/c of elastic walls
//!   (within four standard errors; measured +1.5).

mod common;
use common::{ok_json, ok_stdout, scratch_dir};

fn model(name: &str) -> String {
    format!(
        "{}/../../examples/models/{name}",
        env!("CARGO_MANIFEST_DIR")
    )
}

// the printed parameters and amplitude equation of the extended van der Pol oscillator
const ALPHA: f64 = 0.144;
const BETA: f64 = 0.005;
const GAMMA: f64 = 5.862e-5;
const DELTA: f64 = 2.13e-7;

/// The printed polynomial in x = r²: r' = (μ0 r/1024)·q(r²).
fn q(x: f64) -> f64 {
    512.0 - 128.0 * x + 64.0 * ALPHA * x.powi(2) - 40.0 * BETA * x.powi(3)
        + 28.0 * GAMMA * x.powi(4)
        - 21.0 * DELTA * x.powi(5)
}

/// The roots of q in r, by bisection on a fine grid of x (independent of the library).
fn printed_radii() -> Vec<f64> {
    let mut roots = Vec::new();
    let step = 0.01;
    for i in 1..30_000 {
        let (mut lo, mut hi) = (i as f64 * step, (i + 1) as f64 * step);
        if q(lo) * q(hi) >= 0.0 {
            continue;
        }
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if q(lo) * q(mid) <= 0.0 {
                hi = mid
            } else {
                lo = mid
            }
        }
        roots.push((0.5 * (lo + hi)).sqrt());
    }
    roots
}

#[test]
fn the_trirhythmic_van_der_pol_oscillator_has_the_printed_amplitude_equation_and_cycles() {
    let file = model("trirhythmic-vdp.toml");
    let text = std::fs::read_to_string(&file).unwrap();
    let m = trirhythm::model::Model::from_toml_str(&text).unwrap();
    let mu0 = m.damping.mu0;
    assert_eq!(
        m.damping.coefficients,
        vec![1.0, -1.0, ALPHA, -BETA, GAMMA, -DELTA]
    );
    // the drift against the printed amplitude equation, on the command's whole grid
    let csv = ok_stdout(&["drift", "--model", &file, "--format", "csv"]);
    let rows = common::csv_rows(&csv);
    assert_eq!(rows[0][..2], ["A", "f"]);
    let pairs: Vec<(f64, f64)> = rows[1..]
        .iter()
        .map(|r| (r[0].parse().unwrap(), r[1].parse().unwrap()))
        .collect();
    assert!(pairs.len() > 100 && pairs.last().unwrap().0 > 13.0);
    let printed = |a: f64| mu0 * a / 1024.0 * q(a * a);
    let scale = pairs
        .iter()
        .map(|&(a, _)| printed(a).abs())
        .fold(0.0, f64::max);
    for &(a, f) in &pairs {
        assert!(
            (f - printed(a)).abs() <= 1e-12 * scale,
            "A = {a}: {f} vs {}",
            printed(a)
        );
    }
    // the cycles: five, S-U-S-U-S, at the printed polynomial's roots
    let doc = ok_json(&["cycles", "--model", &file, "--format", "json"]);
    let cycles = doc["cycles"].as_array().unwrap();
    let radii = printed_radii();
    assert_eq!(radii.len(), 5);
    assert_eq!(cycles.len(), 5);
    for (i, (c, r)) in cycles.iter().zip(&radii).enumerate() {
        let a = c["amplitude"].as_f64().unwrap();
        assert!((a - r).abs() <= 1e-9 * r, "cycle {i}: {a} vs {r}");
        assert_eq!(c["stable"].as_bool().unwrap(), i % 2 == 0, "cycle {i}");
    }
    // deterministic paths, one in each stable cycle's basin, settle on the averaged radii
    let dir = scratch_dir("published-tri");
    for (start, radius) in [(2.4, radii[0]), (8.0, radii[2]), (12.5, radii[4])] {
        let path = dir.join(format!("start-{start}.toml"));
        std::fs::write(&path, text.replace("u0 = 2.4", &format!("u0 = {start}"))).unwrap();
        let csv = ok_stdout(&[
            "simulate",
            "--model",
            path.to_str().unwrap(),
            "--t-end",
            "20000",
            "--every",
            "20",
        ]);
        let rows = common::csv_rows(&csv);
        let late: Vec<f64> = rows[1..]
            .iter()
            .filter(|r| r[0].parse::<f64>().unwrap() >= 19_000.0)
            .map(|r| r[1].parse::<f64>().unwrap().hypot(r[2].parse().unwrap()))
            .collect();
        let mean = late.iter().sum::<f64>() / late.len() as f64;
        assert!(
            (mean / radius - 1.0).abs() < 2e-3,
            "U(0) = {start}: mean amplitude {mean} vs {radius}"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// ⟨U^k⟩ of p(U) ∝ exp(−(c/D)(U²/2 + k3U⁴/4)) on [−1, 1] (Simpson, 4000 intervals).
fn exact_moment(k: i32, c_over_d: f64, k3: f64) -> f64 {
    let n = 4000;
    let (mut num, mut den) = (0.0, 0.0);
    for i in 0..=n {
        let u = -1.0 + 2.0 * i as f64 / n as f64;
        let w = if i == 0 || i == n {
            1.0
        } else if i % 2 == 1 {
            4.0
        } else {
            2.0
        };
        let p = (-c_over_d * (u * u / 2.0 + k3 * u.powi(4) / 4.0)).exp();
        num += w * u.powi(k) * p;
        den += w * p;
    }
    num / den
}

/// `ensemble --model FILE` over 8 paths of T = 20000 after a burn-in of 200 (the docs' table),
/// as JSON.
fn stationary_ensemble(file: &str) -> serde_json::Value {
    ok_json(&[
        "ensemble",
        "--model",
        file,
        "--paths",
        "8",
        "--t-end",
        "20000",
        "--burn-in",
        "200",
        "--amplitude-max",
        "3",
        "--format",
        "json",
    ])
}

#[test]
fn the_two_barrier_vibro_impact_duffing_oscillator_has_the_exact_density_at_r_1() {
    let file = model("bilateral-vibroimpact-duffing.toml");
    let text = std::fs::read_to_string(&file).unwrap();
    let m = trirhythm::model::Model::from_toml_str(&text).unwrap();
    assert_eq!(m.walls.len(), 2);
    let (c, k3) = (
        -m.damping.mu0 * m.damping.coefficients[0],
        m.restoring.cubic,
    );
    let d = m.noise.additive.as_ref().unwrap().intensity;
    assert_eq!((c, k3, d), (0.05, 0.5, 0.02));
    let doc = stationary_ensemble(&file);
    assert_eq!(doc["stationarity"]["stationary"], true);
    let exact_u = exact_moment(2, c / d, k3);
    assert!((exact_u - 0.222053).abs() < 1e-6, "{exact_u}");
    for (key, exact) in [("var_u", exact_u), ("var_v", d / c)] {
        let value = doc[key]["value"].as_f64().unwrap();
        let se = doc[key]["stderr"].as_f64().unwrap();
        assert!(
            (value - exact).abs() < 4.0 * se,
            "{key}: {value} ± {se} vs {exact}"
        );
    }
    // the paper's second excitation, parametric noise U·η_m beside the additive one: with
    // elastic walls the energy H = U̇²/2 + Φ(U) balances exactly, d⟨H⟩/dt = −c⟨U̇²⟩ + D_a +
    // D_m⟨U²⟩ = 0 (Itô's term of each noise; impacts at r = 1 keep H), so
    // ⟨U̇²⟩ = (D_a + D_m⟨U²⟩)/c whatever k(U) and the walls
    let dir = scratch_dir("published-vi");
    let path = dir.join("parametric.toml");
    let dm = 0.005;
    std::fs::write(
        &path,
        format!("{text}\n[noise.multiplicative]\nintensity = {dm}\n"),
    )
    .unwrap();
    let doc = stationary_ensemble(path.to_str().unwrap());
    assert_eq!(doc["stationarity"]["stationary"], true);
    let [(u2, se_u), (v2, se_v)] = ["var_u", "var_v"].map(|key| {
        (
            doc[key]["value"].as_f64().unwrap(),
            doc[key]["stderr"].as_f64().unwrap(),
        )
    });
    let balance = (d + dm * u2) / c;
    let se = se_v.hypot(dm / c * se_u);
    eprintln!("parametric: ⟨U̇²⟩ = {v2} ± {se_v}, (D_a + D_m⟨U²⟩)/c = {balance}");
    assert!((v2 - balance).abs() < 4.0 * se, "{v2} ± {se} vs {balance}");
    let _ = std::fs::remove_dir_all(&dir);
}
