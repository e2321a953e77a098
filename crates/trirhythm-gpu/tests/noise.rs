//! The kernel's noise (`kernel/noise.h`, through the C build of `src/emulate.rs`) against the
//! engine's, bit for bit: the generator's words, the normal deviates (with the ziggurat's wedge
//! and tail branches counted), and the white and Ornstein–Uhlenbeck steps.

use rand::RngCore;
use trirhythm::engine::noise::{path_rng, Noise, NoiseStream, StepConstants};
use trirhythm::maths::{standard_normal, ziggurat_tables};
use trirhythm_gpu::emulate;

const RNG_SEED: u64 = 0x5eed_0039;

/// (seed, path) pairs: small, large and extreme, so that every key and stream word is exercised.
const STREAMS: [(u64, u64); 5] = [
    (RNG_SEED, 0),
    (RNG_SEED, 1),
    (0, 0),
    (u64::MAX, 0x0123_4567_89ab_cdef),
    (0xdead_beef, u64::MAX),
];

#[test]
fn words_are_chacha8_rng_s() {
    // 120 000 words of 64 bits per stream: 15 000 blocks of 16 words, so every position in a
    // block and the counter's carries from block to block are met
    let n = 120_000;
    for &(seed, path) in &STREAMS {
        let got = emulate::words(seed, path, n);
        let mut rng = path_rng(seed, path);
        for (k, &w) in got.iter().enumerate() {
            let want = rng.next_u64();
            assert_eq!(w, want, "seed {seed:#x}, path {path:#x}, word {k}");
        }
    }
}

#[test]
fn words_depend_on_the_seed_and_the_path() {
    let a = emulate::words(RNG_SEED, 3, 64);
    let b = emulate::words(RNG_SEED, 3, 64);
    let other_path = emulate::words(RNG_SEED, 4, 64);
    let other_seed = emulate::words(RNG_SEED + 1, 3, 64);
    assert_eq!(a, b);
    // every word differs (a coincidence has probability 2⁻⁶⁴ per word)
    for k in 0..64 {
        assert_ne!(a[k], other_path[k], "word {k}");
        assert_ne!(a[k], other_seed[k], "word {k}");
    }
}

#[test]
fn normals_are_standard_normal_s_bit_for_bit() {
    let n = 1_000_000;
    let (x, _) = ziggurat_tables();
    for &(seed, path) in &STREAMS[..2] {
        let got = emulate::normals(seed, path, n);
        let mut rng = path_rng(seed, path);
        let (mut wedges, mut tails, mut redraws) = (0usize, 0usize, 0usize);
        for (k, &z) in got.iter().enumerate() {
            // the first word's branch, read from a copy of the generator with the same tables
            let mut peek = rng.clone();
            let first = peek.next_u64();
            let i = (first & 0xff) as usize;
            let u = f64::from_bits((first >> 12) | (1024u64 << 52)) - 3.0;
            if (u * x[i]).abs() >= x[i + 1] {
                if i == 0 {
                    tails += 1;
                } else {
                    wedges += 1;
                }
            }
            let before = rng.get_word_pos();
            let want = standard_normal(&mut rng);
            // more words than the first and a wedge's uniform: the tail, or a rejection that drew again
            redraws += usize::from(rng.get_word_pos() - before > 4);
            assert_eq!(
                z.to_bits(),
                want.to_bits(),
                "seed {seed:#x}, path {path}, deviate {k}: {z} vs {want}"
            );
        }
        println!("seed {seed:#x}, path {path}: {wedges} wedges, {tails} tails, {redraws} redraws");
        // about 1.2 % of first words fall in a wedge and 1/256 of their 1 % in the base
        // strip's tail part (expected ≈ 1.2·10⁴ and ≈ 2.6·10² here)
        assert!(wedges > 5_000, "{wedges} wedges");
        assert!(tails > 100, "{tails} tails");
        assert!(redraws > 100, "{redraws} redraws");
    }
}

#[test]
fn normals_depend_on_the_stream() {
    let a = emulate::normals(RNG_SEED, 0, 1000);
    let b = emulate::normals(RNG_SEED, 1, 1000);
    assert_eq!(a.len(), 1000);
    assert!(a.iter().zip(&b).all(|(p, q)| p != q));
}

fn bits(p: (f64, f64)) -> (u64, u64) {
    (p.0.to_bits(), p.1.to_bits())
}

/// The engine's stream and the kernel's, step by step.
fn check_steps(kind: Noise, dt: f64, seed: u64, path: u64, n: usize) -> emulate::NoiseSteps {
    let mut stream = NoiseStream::new(kind, dt, seed, path).unwrap();
    let constants = stream.step_constants();
    let got = emulate::noise_steps(&constants, seed, path, n);
    assert_eq!(
        got.start.to_bits(),
        stream.current().to_bits(),
        "{kind:?}, dt {dt}: start"
    );
    assert_eq!(got.steps.len(), n);
    for (k, &pair) in got.steps.iter().enumerate() {
        let want = stream.next_step();
        assert_eq!(
            bits(pair),
            bits(want),
            "{kind:?}, dt {dt}, step {k}: {pair:?} vs {want:?}"
        );
    }
    assert_eq!(got.end.to_bits(), stream.current().to_bits());
    got
}

#[test]
fn white_steps_are_noise_stream_s_bit_for_bit() {
    for &(d, dt) in &[(0.7, 0.02), (1e-3, 1e-4), (25.0, 0.5)] {
        let kind = Noise::White { intensity: d };
        let c = NoiseStream::new(kind, dt, RNG_SEED, 0)
            .unwrap()
            .step_constants();
        assert_eq!(c.kind, StepConstants::WHITE);
        let got = check_steps(kind, dt, RNG_SEED, 5, 100_000);
        assert_eq!(got.start, 0.0);
        assert!(got.steps.iter().all(|&(a, b)| a == b && a != 0.0));
    }
}

#[test]
fn ou_steps_are_noise_stream_s_bit_for_bit() {
    // τ ≫ Δt, τ ~ Δt and τ ≪ Δt
    for &(d, tau, dt) in &[
        (0.3, 0.5, 0.01),
        (0.4, 0.01, 0.01),
        (0.4, 0.0005, 0.01),
        (2.0, 10.0, 1e-3),
    ] {
        let kind = Noise::Colored {
            intensity: d,
            correlation_time: tau,
        };
        let c = NoiseStream::new(kind, dt, RNG_SEED, 0)
            .unwrap()
            .step_constants();
        assert_eq!(c.kind, StepConstants::COLORED);
        let got = check_steps(kind, dt, RNG_SEED, 9, 100_000);
        // the start drew a deviate: the stationary start is not 0
        assert_ne!(got.start, 0.0);
    }
}

#[test]
fn no_noise_draws_nothing() {
    let got = check_steps(Noise::None, 0.01, RNG_SEED, 0, 1000);
    assert_eq!(got.start, 0.0);
    assert!(got.steps.iter().all(|&p| bits(p) == (0, 0)));
}

#[test]
fn noise_steps_depend_on_the_path() {
    let kind = Noise::Colored {
        intensity: 0.3,
        correlation_time: 0.5,
    };
    let c = NoiseStream::new(kind, 0.01, RNG_SEED, 0)
        .unwrap()
        .step_constants();
    let a = emulate::noise_steps(&c, RNG_SEED, 0, 100);
    let b = emulate::noise_steps(&c, RNG_SEED, 1, 100);
    assert_ne!(a.start, b.start);
    assert!(a.steps.iter().zip(&b.steps).all(|(p, q)| p != q));
}
