/* trirhythm-gpu: a path's noise, the same bits as the CPU engine's.
 *
 * What
 *   The forcing η of one path, drawn from the path's own random stream exactly as the engine
 *   does it (`trirhythm::engine::noise`): the generator `path_rng(seed, path)`, its standard
 *   normal deviates (`trirhythm::maths::standard_normal`) and the white / Ornstein–Uhlenbeck
 *   step means of `NoiseStream::next_step`. Per thread: a TrRng (the key, the block counter,
 *   the stream, one 16-word block and its read position: 29 words) and a TrNoise (the host's
 *   constants and the running node value).
 *
 * Method
 *   1. The generator is ChaCha with 8 rounds (4 double rounds of column then diagonal
 *      quarter-rounds, rotations 16, 12, 8, 7; the output block is the rounds' result plus the
 *      input block), laid out as `rand_chacha::ChaCha8Rng` 0.9 lays it out: words 0–3 the
 *      constant "expand 32-byte k", 4–11 the key, 12–13 a 64-bit block counter (low word
 *      first), 14–15 the 64-bit stream (low word first). The key is rand_core 0.9's
 *      `seed_from_u64(seed)`: eight outputs of PCG32 (state ← state·6364136223846793005 +
 *      11634580027462260723, then output rotr32(((s >> 18) ^ s) >> 27, s >> 59)), key word k =
 *      the k-th output (little-endian bytes read back as little-endian words); the stream is
 *      `set_stream(path)` on the fresh generator, the counter starts at 0. rand_chacha computes
 *      four blocks at a time into a 64-word buffer; here one block of 16 words is computed when
 *      the previous one is used up: the same words in the same order. `next_u64` is rand_core's
 *      `BlockRng::next_u64`: the next two words w₀, w₁ as w₁·2³² + w₀; when only one word is
 *      left in the buffer it is the low half and the first word of the next block the high half
 *      (only reachable after an odd number of 32-bit reads: the engine's noise draws 64-bit words
 *      only, so the position stays even, and then the 16-word buffer meets the same case as the
 *      64-word one, never).
 *   2. A standard normal deviate is `rand_distr` 0.5's ziggurat (Doornik's ZIGNOR variant of
 *      Marsaglia & Tsang's, 256 strips), word for word as the engine's `standard_normal`: a word
 *      b gives the strip i = b & 0xff and u = (the double with the bits (b >> 12) | 1024·2⁵²)
 *      − 3 ∈ [−1, 1); x = u·x_i is returned when |x| < x_{i+1}; otherwise strip 0 samples the
 *      tail beyond R = x_1 (Marsaglia: x = ln(U₁)/R, y = ln(U₂) with two `Open01` uniforms until
 *      −2y ≥ x², then ±(R − x) on u's side), a wedge is accepted when f_{i+1} + (f_i − f_{i+1})·U
 *      < exp(−x·x/2) with U rand 0.9's `StandardUniform` f64 ((b >> 11)·2⁻⁵³), and otherwise a
 *      fresh word starts over. `Open01` f64 is (the double with the bits (b >> 12) | 1023·2⁵²)
 *      − (1 − 2⁻⁵³). The tables x and f are the engine's own (`trirhythm::maths::
 *      ziggurat_tables`), passed by pointer, never transcribed.
 *   3. The step: TrNoise holds `NoiseStream::step_constants()` (kind 0 none, 1 white, 2 OU) and
 *      the node value; tr_noise_start draws the OU start sd·ξ, tr_noise_step is `next_step`
 *      with the same operations in the same order (no fused multiply–add: both builds forbid
 *      contraction, see common.h).
 *   In the C build (the emulation) exp and ln are the engine's own, so the deviates are the
 *   engine's bit for bit; on the GPU they are CUDA's, and a wedge decision or a tail deviate
 *   can differ in the last bit (about one deviate in 10⁶ meets a transcendental function, see
 *   common.h).
 *
 * Reference
 *   D. J. Bernstein, "ChaCha, a variant of Salsa20" (2008); M. E. O'Neill, "PCG: a family of
 *   simple fast space-efficient statistically good algorithms for random number generation"
 *   (2014); G. Marsaglia & W. W. Tsang, J. Stat. Softw. 5 (2000) 8; J. A. Doornik, "An improved
 *   ziggurat method to generate normal random samples" (2005), as `rand_distr` 0.5 lays it out.
 *
 * Tests
 *   tests/noise.rs, through the C build (kernel/emulate.c, src/emulate.rs): the 64-bit words
 *   equal `path_rng(seed, path).next_u64()` over 1.2·10⁵ words for several (seed, path);
 *   10⁶ normal deviates equal `standard_normal`'s bit for bit, with the wedge and tail branches
 *   counted; white and OU step pairs and the OU start equal `NoiseStream`'s bit for bit over
 *   10⁵ steps for several (D, τ, Δt). */
#ifndef TR_NOISE_H
#define TR_NOISE_H

#include "common.h"

/* ---- ChaCha8 as rand_chacha's ChaCha8Rng ---- */

typedef struct {
    tr_u32 key[8];
    tr_u64 counter; /* the block that the next refill computes */
    tr_u64 stream;
    tr_u32 buf[16]; /* the current block */
    tr_u32 index;   /* the next word of buf to read; 16: used up */
} TrRng;

#define TR_ROTL32(v, n) (((v) << (n)) | ((v) >> (32 - (n))))
#define TR_QUARTER(a, b, c, d)                                                                   \
    do {                                                                                         \
        a += b;                                                                                  \
        d ^= a;                                                                                  \
        d = TR_ROTL32(d, 16);                                                                    \
        c += d;                                                                                  \
        b ^= c;                                                                                  \
        b = TR_ROTL32(b, 12);                                                                    \
        a += b;                                                                                  \
        d ^= a;                                                                                  \
        d = TR_ROTL32(d, 8);                                                                     \
        c += d;                                                                                  \
        b ^= c;                                                                                  \
        b = TR_ROTL32(b, 7);                                                                     \
    } while (0)

/* the next keystream block into buf; the counter advances by one */
TR_FN void tr_chacha8_refill(TrRng* r) {
    tr_u32 in[16];
    tr_u32 x[16];
    int k;
    in[0] = 0x61707865u; /* "expa" */
    in[1] = 0x3320646eu; /* "nd 3" */
    in[2] = 0x79622d32u; /* "2-by" */
    in[3] = 0x6b206574u; /* "te k" */
    for (k = 0; k < 8; k++) in[4 + k] = r->key[k];
    in[12] = (tr_u32)r->counter;
    in[13] = (tr_u32)(r->counter >> 32);
    in[14] = (tr_u32)r->stream;
    in[15] = (tr_u32)(r->stream >> 32);
    for (k = 0; k < 16; k++) x[k] = in[k];
    for (k = 0; k < 4; k++) {
        TR_QUARTER(x[0], x[4], x[8], x[12]);
        TR_QUARTER(x[1], x[5], x[9], x[13]);
        TR_QUARTER(x[2], x[6], x[10], x[14]);
        TR_QUARTER(x[3], x[7], x[11], x[15]);
        TR_QUARTER(x[0], x[5], x[10], x[15]);
        TR_QUARTER(x[1], x[6], x[11], x[12]);
        TR_QUARTER(x[2], x[7], x[8], x[13]);
        TR_QUARTER(x[3], x[4], x[9], x[14]);
    }
    for (k = 0; k < 16; k++) r->buf[k] = x[k] + in[k];
    r->counter += 1;
    r->index = 0;
}

/* one output of rand_core's PCG32 seed expansion, advancing its state */
TR_FN tr_u32 tr_pcg32_next(tr_u64* state) {
    tr_u64 s;
    tr_u32 xorshifted, rot;
    *state = *state * 6364136223846793005ull + 11634580027462260723ull;
    s = *state;
    xorshifted = (tr_u32)(((s >> 18) ^ s) >> 27);
    rot = (tr_u32)(s >> 59);
    return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
}

/* path_rng(seed, path): ChaCha8Rng::seed_from_u64(seed), then set_stream(path) */
TR_FN void tr_rng_new(TrRng* r, tr_u64 seed, tr_u64 path) {
    tr_u64 state = seed;
    int k;
    for (k = 0; k < 8; k++) r->key[k] = tr_pcg32_next(&state);
    r->counter = 0;
    r->stream = path;
    r->index = 16;
}

/* RngCore::next_u64 of the generator (BlockRng::next_u64) */
TR_FN tr_u64 tr_next_u64(TrRng* r) {
    tr_u32 i = r->index;
    tr_u64 lo;
    if (i < 15u) {
        r->index = i + 2u;
        return ((tr_u64)r->buf[i + 1u] << 32) | (tr_u64)r->buf[i];
    }
    if (i >= 16u) {
        tr_chacha8_refill(r);
        r->index = 2u;
        return ((tr_u64)r->buf[1] << 32) | (tr_u64)r->buf[0];
    }
    lo = (tr_u64)r->buf[15];
    tr_chacha8_refill(r);
    r->index = 1u;
    return ((tr_u64)r->buf[0] << 32) | lo;
}

/* ---- uniforms as rand 0.9 draws them ---- */

/* StandardUniform f64: 53 high bits times 2^-53, in [0, 1) */
TR_FN double tr_uniform_f64(TrRng* r) {
    tr_u64 b = tr_next_u64(r);
    return (1.0 / 9007199254740992.0) * (double)(b >> 11);
}

/* Open01 f64: 52 high bits as the mantissa of [1, 2), minus 1 − 2^-53: in (0, 1) */
TR_FN double tr_open01_f64(TrRng* r) {
    tr_u64 b = tr_next_u64(r);
    return tr_from_bits((b >> 12) | (1023ull << 52)) - (1.0 - 1.1102230246251565e-16);
}

/* ---- the ziggurat of trirhythm::maths::standard_normal ---- */

/* the tail beyond R = x[1] on u's side */
TR_NOINLINE double tr_normal_tail(TrRng* r, double big_r, double u) {
    double x = 1.0, y = 0.0;
    while (-2.0 * y < x * x) {
        double x_ = tr_open01_f64(r);
        double y_ = tr_open01_f64(r);
        x = tr_ln(x_) / big_r;
        y = tr_ln(y_);
    }
    if (u < 0.0) return x - big_r;
    return big_r - x;
}

/* the rest of a deviate whose first word (strip i, uniform u, x = u·x_i) fell outside its
 * strip: the tail or the wedge, then fresh words until one is accepted */
TR_NOINLINE double tr_normal_beyond(TrRng* r, const double* xt, const double* ft, tr_u32 i,
                                    double u, double x) {
    for (;;) {
        if (i == 0u) return tr_normal_tail(r, xt[1], u);
        if (ft[i + 1u] + (ft[i] - ft[i + 1u]) * tr_uniform_f64(r) < tr_exp(-x * x / 2.0)) return x;
        {
            tr_u64 b = tr_next_u64(r);
            i = (tr_u32)(b & 0xffu);
            u = tr_from_bits((b >> 12) | (1024ull << 52)) - 3.0;
            x = u * xt[i];
            if (tr_fabs(x) < xt[i + 1u]) return x;
        }
    }
}

/* a standard normal deviate: trirhythm::maths::standard_normal(rng), with its tables x, f */
TR_FN double tr_standard_normal(TrRng* r, const double* xt, const double* ft) {
    tr_u64 b = tr_next_u64(r);
    tr_u32 i = (tr_u32)(b & 0xffu);
    double u = tr_from_bits((b >> 12) | (1024ull << 52)) - 3.0;
    double x = u * xt[i];
    if (tr_fabs(x) < xt[i + 1u]) return x;
    return tr_normal_beyond(r, xt, ft, i, u, x);
}

/* ---- NoiseStream ---- */

#define TR_NOISE_NONE 0u
#define TR_NOISE_WHITE 1u
#define TR_NOISE_COLORED 2u

/* trirhythm::engine::noise::StepConstants (#[repr(C)], the same fields in the same order) and
 * the running node value */
typedef struct {
    tr_u32 kind; /* TR_NOISE_NONE, TR_NOISE_WHITE or TR_NOISE_COLORED */
    double rho;
    double sigma;
    double mean_coef;
    double cross;
    double rest;
    double dt;
    double sd;
    double state; /* η_n (OU), the last white level, or 0 */
} TrNoise;

/* what NoiseStream::new draws: the OU start η_0 = sd·ξ; white and none draw nothing */
TR_FN void tr_noise_start(TrNoise* n, TrRng* r, const double* xt, const double* ft) {
    n->state = 0.0;
    if (n->kind == TR_NOISE_COLORED) n->state = n->sd * tr_standard_normal(r, xt, ft);
}

/* NoiseStream::next_step: the forcing's (start, end) values on the next step */
TR_FN void tr_noise_step(TrNoise* n, TrRng* r, const double* xt, const double* ft, double* el,
                         double* er) {
    if (n->kind == TR_NOISE_WHITE) {
        double w = n->sigma * tr_standard_normal(r, xt, ft);
        n->state = w;
        *el = w;
        *er = w;
    } else if (n->kind == TR_NOISE_COLORED) {
        double x1 = tr_standard_normal(r, xt, ft);
        double x2 = tr_standard_normal(r, xt, ft);
        double start = n->state;
        double mean;
        n->state = n->rho * start + n->sigma * x1;
        mean = (n->mean_coef * start + n->cross * x1 + n->rest * x2) / n->dt;
        *el = mean;
        *er = mean;
    } else {
        *el = 0.0;
        *er = 0.0;
    }
}

#endif
