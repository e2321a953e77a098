//! The CPU emulation of the kernel: its C source (`kernel/`), built as plain C99 by `build.rs`,
//! called from Rust.
//!
//! # What
//! The kernel's functions are one C99 subset compiled twice, by NVRTC for the GPU and by the
//! host's C compiler here (`-std=c99 -O2 -ffp-contract=off -fno-fast-math`: every +, −, ×, ÷
//! and √ the correctly rounded IEEE double operation, as in the Rust engine). The elementary
//! functions of the C build call back into the engine's own ([`trirhythm::maths`]: the
//! `tr_host_*` functions below), so the emulation must give the engine's bits exactly; a test
//! that compares them checks the kernel's arithmetic without a GPU.
//!
//! # Method
//! `kernel/emulate.c` holds plain entry points that run the kernel's functions over a whole
//! sequence (the words of a path's generator, its normal deviates, its noise steps); the safe
//! wrappers here allocate the outputs and pass the engine's ziggurat tables
//! ([`trirhythm::maths::ziggurat_tables`]) by pointer.
//!
//! # Reference
//! `kernel/noise.h` (ChaCha8 as `rand_chacha`, the ziggurat as `rand_distr`, the engine's
//! `NoiseStream`).
//!
//! # Tests
//! `tests/noise.rs`: the words, the deviates and the noise steps against the engine's, bit for
//! bit.

use trirhythm::engine::noise::StepConstants;
use trirhythm::maths::ziggurat_tables;

/// The kernel's `TrNoise` (`kernel/noise.h`): [`StepConstants`]' fields in the same order, then
/// the running node value.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TrNoise {
    /// [`StepConstants::kind`].
    pub kind: u32,
    /// [`StepConstants::rho`].
    pub rho: f64,
    /// [`StepConstants::sigma`].
    pub sigma: f64,
    /// [`StepConstants::mean_coef`].
    pub mean_coef: f64,
    /// [`StepConstants::cross`].
    pub cross: f64,
    /// [`StepConstants::rest`].
    pub rest: f64,
    /// [`StepConstants::dt`].
    pub dt: f64,
    /// [`StepConstants::sd`].
    pub sd: f64,
    /// The node value η_n (OU), the last white level, or 0.
    pub state: f64,
}

impl TrNoise {
    /// The kernel's noise with the host's constants, before its start (state 0).
    pub fn new(c: &StepConstants) -> Self {
        TrNoise {
            kind: c.kind,
            rho: c.rho,
            sigma: c.sigma,
            mean_coef: c.mean_coef,
            cross: c.cross,
            rest: c.rest,
            dt: c.dt,
            sd: c.sd,
            state: 0.0,
        }
    }
}

extern "C" {
    fn tr_emulate_words(seed: u64, path: u64, out: *mut u64, n: u64);
    fn tr_emulate_normals(
        seed: u64,
        path: u64,
        x: *const f64,
        f: *const f64,
        out: *mut f64,
        n: u64,
    );
    fn tr_emulate_noise(
        noise: *mut TrNoise,
        seed: u64,
        path: u64,
        x: *const f64,
        f: *const f64,
        start: *mut f64,
        el: *mut f64,
        er: *mut f64,
        n: u64,
    );
}

/// eˣ for the C build: [`trirhythm::maths::exp`].
#[no_mangle]
pub extern "C" fn tr_host_exp(x: f64) -> f64 {
    trirhythm::maths::exp(x)
}

/// ln x for the C build: [`trirhythm::maths::ln`].
#[no_mangle]
pub extern "C" fn tr_host_ln(x: f64) -> f64 {
    trirhythm::maths::ln(x)
}

/// eˣ − 1 for the C build: [`trirhythm::maths::expm1`].
#[no_mangle]
pub extern "C" fn tr_host_expm1(x: f64) -> f64 {
    trirhythm::maths::expm1(x)
}

/// xʸ for the C build: [`trirhythm::maths::pow`].
#[no_mangle]
pub extern "C" fn tr_host_pow(x: f64, y: f64) -> f64 {
    trirhythm::maths::pow(x, y)
}

/// cos x for the C build: [`trirhythm::maths::cos`].
#[no_mangle]
pub extern "C" fn tr_host_cos(x: f64) -> f64 {
    trirhythm::maths::cos(x)
}

/// sin x for the C build: [`trirhythm::maths::sin`].
#[no_mangle]
pub extern "C" fn tr_host_sin(x: f64) -> f64 {
    trirhythm::maths::sin(x)
}

/// The first `n` words `next_u64()` of the kernel's generator for path `path` of `seed`
/// (`tr_rng_new`, `tr_next_u64`), to equal `trirhythm::engine::noise::path_rng(seed, path)`'s.
pub fn words(seed: u64, path: u64, n: usize) -> Vec<u64> {
    let mut out = vec![0u64; n];
    // SAFETY: `out` holds `n` words, which the C function writes and nothing else.
    unsafe { tr_emulate_words(seed, path, out.as_mut_ptr(), n as u64) };
    out
}

/// The first `n` standard normal deviates of the kernel (`tr_standard_normal`) from path
/// `path` of `seed`, to equal `trirhythm::maths::standard_normal`'s from the same generator.
pub fn normals(seed: u64, path: u64, n: usize) -> Vec<f64> {
    let (x, f) = ziggurat_tables();
    let mut out = vec![0.0; n];
    // SAFETY: the tables hold 257 doubles each (all that the ziggurat reads: indices ≤ 256);
    // `out` holds `n`, which the C function writes and nothing else.
    unsafe {
        tr_emulate_normals(
            seed,
            path,
            x.as_ptr(),
            f.as_ptr(),
            out.as_mut_ptr(),
            n as u64,
        )
    };
    out
}

/// What the kernel's noise gives for path `path` of `seed` with the constants `c`
/// (`tr_noise_start`, then `n` times `tr_noise_step`).
#[derive(Debug, Clone, PartialEq)]
pub struct NoiseSteps {
    /// The node value after the start (`NoiseStream::current()` before any step).
    pub start: f64,
    /// The (start, end) values of the forcing on each step.
    pub steps: Vec<(f64, f64)>,
    /// The node value after the last step.
    pub end: f64,
}

/// The kernel's noise steps for path `path` of `seed` with the host's constants `c`, to equal
/// `NoiseStream::new(kind, dt, seed, path)`'s `current()` and `next_step()` pairs.
pub fn noise_steps(c: &StepConstants, seed: u64, path: u64, n: usize) -> NoiseSteps {
    let (x, f) = ziggurat_tables();
    let mut noise = TrNoise::new(c);
    let mut start = 0.0;
    let (mut el, mut er) = (vec![0.0; n], vec![0.0; n]);
    // SAFETY: `noise` is a `#[repr(C)]` copy of the C struct `TrNoise`; the tables hold 257
    // doubles each; `el` and `er` hold `n` each; the C function writes only these and `start`.
    unsafe {
        tr_emulate_noise(
            &mut noise,
            seed,
            path,
            x.as_ptr(),
            f.as_ptr(),
            &mut start,
            el.as_mut_ptr(),
            er.as_mut_ptr(),
            n as u64,
        )
    };
    NoiseSteps {
        start,
        steps: el.into_iter().zip(er).collect(),
        end: noise.state,
    }
}
