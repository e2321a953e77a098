/* trirhythm-gpu: the CPU emulation's entry points (built by build.rs as plain C99, called by
 * src/emulate.rs). Each runs the kernel's own functions, the very source that NVRTC compiles
 * for the GPU, on the host, so that tests can compare them with the Rust engine bit for bit.
 * No state lives here: every call starts from its arguments. */
#include "noise.h"

/* n successive path_rng(seed, path).next_u64() words */
void tr_emulate_words(tr_u64 seed, tr_u64 path, tr_u64* out, tr_u64 n) {
    TrRng r;
    tr_u64 k;
    tr_rng_new(&r, seed, path);
    for (k = 0; k < n; k++) out[k] = tr_next_u64(&r);
}

/* n successive standard_normal(&mut path_rng(seed, path)) deviates, with the tables x, f */
void tr_emulate_normals(tr_u64 seed, tr_u64 path, const double* x, const double* f, double* out,
                        tr_u64 n) {
    TrRng r;
    tr_u64 k;
    tr_rng_new(&r, seed, path);
    for (k = 0; k < n; k++) out[k] = tr_standard_normal(&r, x, f);
}

/* NoiseStream::new(kind, dt, seed, path) then n next_step() pairs: *noise holds the step
 * constants on entry (its state is overwritten) and the final state on return; start gets the
 * state after the start (NoiseStream::current() before any step) */
void tr_emulate_noise(TrNoise* noise, tr_u64 seed, tr_u64 path, const double* x, const double* f,
                      double* start, double* el, double* er, tr_u64 n) {
    TrRng r;
    tr_u64 k;
    tr_rng_new(&r, seed, path);
    tr_noise_start(noise, &r, x, f);
    *start = noise->state;
    for (k = 0; k < n; k++) tr_noise_step(noise, &r, x, f, &el[k], &er[k]);
}
