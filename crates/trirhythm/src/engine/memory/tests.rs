//! Unit tests of the memory (see the parent module's Tests section).

use super::history::History;
use super::moments::{advance_moments, lumped_weights};
use super::*;
use crate::engine::kernel::LUMPED_TERMS;

#[test]
fn scalar_solver_at_order_one_is_the_trapezoidal_predictor_corrector() {
    // y' = −y: S_n = y0 + trapezoidal sum of corrected f; y_{n+1} = S_n + h/2 (f_n + f(S_n + h f_n))
    let h = 0.1;
    for memory in [Memory::Direct, Memory::default()] {
        let ys = solve_scalar(1.0, &|_, y| -y, 1.0, h, 40, memory).unwrap();
        let (mut s, mut y) = (1.0, 1.0);
        for (n, &got) in ys.iter().enumerate().skip(1) {
            let f = -y;
            let yp = s + h * f;
            let y1 = s + 0.5 * h * (f - yp);
            s += 0.5 * h * (f - y1);
            y = y1;
            assert!((got - y).abs() < 1e-14, "{n}: {got} vs {y}");
        }
    }
}

#[test]
fn moments_advance_exactly() {
    // pieces of lengths ℓ_j, linear from l_j to r_j; m_k = ∫ (t_m − s)ᵏ g(s) ds against
    // Simpson's rule, exact for the cubic-and-lower integrands of k ≤ 2 and, per piece,
    // for k = 3 after splitting each piece in 64
    let pieces: Vec<(f64, f64, f64)> = (0..40)
        .map(|j| {
            let j = j as f64;
            (
                0.01 + 0.005 * (j * 0.7).sin().abs(),
                (0.3 * j).cos(),
                (0.3 * j + 0.2).sin(),
            )
        })
        .collect();
    let mut m = [0.0; LUMPED_TERMS];
    for &(len, l, r) in &pieces {
        advance_moments(&mut m, false, len, l, r);
    }
    let t_m: f64 = pieces.iter().map(|p| p.0).sum();
    for (k, &mk) in m.iter().enumerate() {
        let mut exact = 0.0;
        let mut start = 0.0;
        for &(len, l, r) in &pieces {
            let n = 64;
            let f = |x: f64| (t_m - start - x).powi(k as i32) * (l + (r - l) * x / len);
            let dx = len / n as f64;
            for i in 0..n {
                let a = i as f64 * dx;
                exact += dx / 6.0 * (f(a) + 4.0 * f(a + 0.5 * dx) + f(a + dx));
            }
            start += len;
        }
        assert!(
            (mk - exact).abs() <= 1e-13 * (1.0 + exact.abs()),
            "m{k}: {mk} vs {exact}"
        );
    }
    let mut flat = [0.0; LUMPED_TERMS];
    for &(len, l, r) in &pieces {
        advance_moments(&mut flat, true, len, l, r);
    }
    assert_eq!(flat[0], m[0]);
    // the lumped polynomial moved by `back`: Σ_k p_k (back + x)ᵏ = Σ_i out_i xⁱ
    let p = [0.9, -3e-3, 2e-5, -7e-8];
    let out = lumped_weights(&p, 0.16);
    for x in [0.0_f64, 1.0, 37.5, 1e3] {
        let direct: f64 = (0..4).map(|k| p[k] * (0.16 + x).powi(k as i32)).sum();
        let moved: f64 = (0..4).map(|i| out[i] * x.powi(i as i32)).sum();
        assert!(
            (direct - moved).abs() <= 1e-14 * direct.abs().max(1.0),
            "{x}"
        );
    }
}

#[test]
fn portable_and_avx_memories_give_the_same_bits() {
    // the AVX path does the portable path's operations in the same order: same bits, so
    // results do not depend on the CPU (pieces leave the window, an impact split and the
    // odd number of mode blocks included)
    let mut a = [1e3, 1e4, 1e5, 1e6, 1e7]
        .into_iter()
        .map(|t| History::new(0.998, 0.01, t, Memory::default(), DEFAULT_WINDOW).unwrap())
        .find(|h| h.modes.y.len() % 2 == 1)
        .expect("a horizon with an odd number of mode blocks");
    if !a.avx {
        return;
    }
    let mut b = a.clone();
    b.avx = false;
    for n in 0..200 {
        let piece = Piece {
            left: (0.37 * n as f64).sin(),
            right: (0.37 * n as f64 + 0.3).cos(),
            split: (n == 50).then_some(Split {
                theta: 0.4,
                before: 3.0,
                after: -1.0,
                keep_before: true,
                mass: 0.0,
            }),
        };
        a.push(piece);
        b.push(piece);
        assert_eq!(a.value().to_bits(), b.value().to_bits(), "step {n}");
    }
}

#[test]
fn histories_coincide_after_the_same_restart_whatever_their_stale_slots() {
    // two paths with different pasts that restart on the same step and then see the same
    // pieces hold the same history, although the ring's unused slots still differ
    let mut a = History::new(0.998, 0.01, 100.0, Memory::default(), DEFAULT_WINDOW).unwrap();
    let mut b = a.clone();
    let piece = |x: f64| Piece {
        left: x,
        right: x + 0.5,
        split: None,
    };
    for n in 0..20 {
        a.push(piece(n as f64));
        b.push(piece(n as f64 + 1e-8));
    }
    assert!(!a.coincides(&b));
    a.restart();
    b.restart();
    assert!(a.coincides(&b) && a.is_zero() && b.is_zero());
    for n in 0..3 {
        a.push(piece(-(n as f64)));
        b.push(piece(-(n as f64)));
    }
    assert!(a.coincides(&b));
    assert!(!a.is_zero());
    b.push(piece(1.0));
    assert!(!a.coincides(&b));
}

#[test]
fn every_window_size_agrees_with_the_direct_memory() {
    // the fast path reads the window's older pieces as one run whose length is rounded up
    // to a multiple of four, zero-weighted values in front (a padding of two doubles when
    // the window holds an odd number of older pieces): against the exact O(N) memory, for
    // windows of 2 … 10 steps, through the fill, the steady state and a restart
    let g = |n: usize| (0.37 * n as f64).sin() + 0.02 * n as f64;
    for lambda in [0.6, 0.998] {
        for window in 2..=10 {
            let soe = Memory::SumOfExponentials { tolerance: 1e-12 };
            let mut fast = History::new(lambda, 0.01, 4.0, soe, window).unwrap();
            let mut exact = History::new(lambda, 0.01, 4.0, Memory::Direct, window).unwrap();
            let mut worst: f64 = 0.0;
            for n in 0..400 {
                if n == 250 {
                    fast.restart();
                    exact.restart();
                }
                let piece = Piece {
                    left: g(n),
                    right: g(n + 1) + 0.01,
                    split: None,
                };
                fast.push(piece);
                exact.push(piece);
                let scale = exact.value().abs().max(1e-3);
                worst = worst.max((fast.value() - exact.value()).abs() / scale);
            }
            assert!(worst < 1e-10, "λ = {lambda}, window {window}: {worst:e}");
        }
    }
}

#[test]
fn scaling_the_history_equals_the_history_of_the_scaled_g() {
    // J^λ is linear: scale(c) after pieces of g = pieces of c·g, for every memory, through
    // the window, the modes and a split (impact) piece
    let c = 2.5;
    for memory in [Memory::Direct, Memory::default()] {
        for lambda in [0.9, 0.998, 1.0] {
            let mut a = History::new(lambda, 0.01, 10.0, memory, DEFAULT_WINDOW).unwrap();
            let mut b = a.clone();
            let g = |n: usize| (0.37 * n as f64).sin() + 0.1 * n as f64;
            let piece = |n: usize, k: f64| Piece {
                left: k * g(n),
                right: k * g(n + 1),
                split: (n == 5).then_some(Split {
                    theta: 0.4,
                    before: k * 3.0,
                    after: -k,
                    keep_before: true,
                    mass: 0.0,
                }),
            };
            for n in 0..40 {
                a.push(piece(n, 1.0));
                b.push(piece(n, c));
            }
            a.scale(c);
            for n in 40..80 {
                let (va, vb) = (a.value(), b.value());
                assert!(
                    (va - vb).abs() <= 1e-13 * vb.abs().max(1.0),
                    "{memory:?} λ={lambda} n={n}: {va} vs {vb}"
                );
                let (fa, fb) = (a.at_fraction(0.3, 1.0).0, b.at_fraction(0.3, 1.0).0);
                assert!((fa - fb).abs() <= 1e-13 * fb.abs().max(1.0));
                a.push(piece(n, c));
                b.push(piece(n, c));
            }
        }
    }
}

/// The history of a smooth g with one split piece at step `at`, split at `theta` with jump
/// values (before, after) and `mass`, `n` pieces pushed.
fn split_history(
    lambda: f64,
    memory: Memory,
    (at, theta, keep): (usize, f64, bool),
    (before, after, mass): (f64, f64, f64),
    g: &dyn Fn(usize) -> f64,
    n: usize,
) -> History {
    let mut h = History::new(lambda, 0.01, 10.0, memory, DEFAULT_WINDOW).unwrap();
    for k in 0..n {
        h.push(Piece {
            left: g(k),
            right: g(k + 1),
            split: (k == at).then_some(Split {
                theta,
                before,
                after,
                keep_before: keep,
                mass,
            }),
        });
    }
    h
}

#[test]
fn a_point_mass_and_two_lines_are_the_theta_derivative_of_a_split_piece() {
    // moving a split piece's impact by δθ (values held) changes J^λ as a point mass
    // (g₋ − g₊)δθ at the impact (−g₊δθ when the part before is forgotten) and two lines that
    // vanish at the piece's ends: the central difference in θ of the history (values at every
    // later node: in the window, then in the modes and lumped moments) against the history of
    // that derivative alone, for both memories and at λ = 1
    let g = |k: usize| (0.37 * k as f64).sin() + 0.05 * k as f64;
    let (at, theta, before, after) = (12, 0.37, 2.5, -1.3);
    let (left, right) = (g(at), g(at + 1));
    // the differences err by O(ε²) and by rounding, 1e-16/ε of values of order 1 against
    // derivatives of order 10⁻³: 1e-10 at ε = 1e-4 (1e-8 at ε = 1e-6, so rounding)
    let eps = 1e-4;
    for memory in [
        Memory::Direct,
        Memory::SumOfExponentials { tolerance: 1e-12 },
    ] {
        for lambda in [0.95, 0.998, 1.0] {
            for keep in [true, false] {
                let mass = if keep { before - after } else { -after };
                let db = -(before - left) / theta;
                let da = -(right - after) / (1.0 - theta);
                let zero = |_: usize| 0.0;
                let mut worst: f64 = 0.0;
                for n in at + 1..at + 40 {
                    let at_theta = |th: f64| {
                        split_history(lambda, memory, (at, th, keep), (before, after, 0.0), &g, n)
                    };
                    let (plus, minus) = (at_theta(theta + eps), at_theta(theta - eps));
                    let d =
                        split_history(lambda, memory, (at, theta, keep), (db, da, mass), &zero, n);
                    let fd = (plus.value() - minus.value()) / (2.0 * eps);
                    worst = worst.max((d.value() - fd).abs() / fd.abs().max(1e-3));
                    let fd = (plus.at_fraction(0.3, 1.0).0 - minus.at_fraction(0.3, 1.0).0)
                        / (2.0 * eps);
                    let got = d.at_fraction(0.3, 0.0).0;
                    worst = worst.max((got - fd).abs() / fd.abs().max(1e-3));
                }
                assert!(
                    worst < 1e-8,
                    "{memory:?} λ = {lambda} keep {keep}: {worst:e}"
                );
            }
        }
    }
}

#[test]
fn the_rates_in_theta_are_the_derivatives_of_the_weights() {
    // at_fraction_rate and current_split_rate against central differences in θ of
    // at_fraction and current_split, with held split pieces in the window, both memories
    let g = |k: usize| (0.37 * k as f64).sin() + 0.05 * k as f64;
    let eps = 1e-6;
    for memory in [
        Memory::Direct,
        Memory::SumOfExponentials { tolerance: 1e-12 },
    ] {
        for lambda in [0.6, 0.95, 0.998, 1.0] {
            for n in [3, 30] {
                let h = split_history(lambda, memory, (n - 2, 0.4, true), (2.0, -1.0, 0.0), &g, n);
                for theta in [0.01, 0.3, 0.9] {
                    let (left, star) = (0.7, -0.4);
                    let j = |th: f64| {
                        let (hs, ws) = h.at_fraction(th, left);
                        (hs + ws * star, ws)
                    };
                    let (rate, rate_w) = h.at_fraction_rate(theta, left);
                    let (p, m) = (j(theta + eps), j(theta - eps));
                    let fd = ((p.0 - m.0) / (2.0 * eps), (p.1 - m.1) / (2.0 * eps));
                    let got = (rate + rate_w * star, rate_w);
                    for (a, b) in [(got.0, fd.0), (got.1, fd.1)] {
                        assert!(
                            (a - b).abs() <= 1e-7 * b.abs().max(1.0),
                            "{memory:?} λ = {lambda} n = {n} θ = {theta}: {a} vs {b}"
                        );
                    }
                    for keep in [true, false] {
                        let split = |th: f64| Split {
                            theta: th,
                            before: 1.5,
                            after: -0.8,
                            keep_before: keep,
                            mass: 0.0,
                        };
                        let (rk, rw) = h.current_split_rate(left, &split(theta));
                        let p = h.current_split(left, &split(theta + eps));
                        let m = h.current_split(left, &split(theta - eps));
                        let fd = ((p.0 - m.0) / (2.0 * eps), (p.1 - m.1) / (2.0 * eps));
                        for (a, b) in [(rk, fd.0), (rw, fd.1)] {
                            assert!(
                                (a - b).abs() <= 1e-7 * b.abs().max(1.0),
                                "split {keep} λ = {lambda} θ = {theta}: {a} vs {b}"
                            );
                        }
                    }
                }
            }
        }
    }
}
