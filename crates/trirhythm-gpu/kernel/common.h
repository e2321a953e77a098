/* trirhythm-gpu: what every kernel file shares.
 *
 * The kernel's source is one C99 subset that compiles twice: by NVRTC as CUDA (the GPU backend,
 * `src/cuda.rs`) and by the host's C compiler as plain C (the CPU emulation, `src/emulate.rs`,
 * built by `build.rs`): the same arithmetic, so that the emulation tests the kernel's
 * arithmetic against the CPU engine without a GPU. Both builds forbid fused multiply-add
 * contraction (NVRTC `--fmad=false`, C `-ffp-contract=off`): every +, −, ×, ÷ and √ is the
 * correctly rounded IEEE double operation, as in the Rust engine.
 *
 * Transcendental functions: the emulation calls back into the engine's own (`trirhythm::maths`,
 * the `libm` crate's), so that its paths are the engine's bit for bit; the GPU uses CUDA's
 * exp, log, expm1, pow, cos and sin (at most 1–2 ulp from the correctly rounded value). Where
 * a path meets one (the ziggurat's wedges and tail, an impact's memory weights, the forcing's
 * re-anchored phase and its value at an impact), a GPU path may differ from the CPU's in the
 * last bit from then on (docs/gpu.md). */
#ifndef TR_COMMON_H
#define TR_COMMON_H

#if defined(__CUDACC__) || defined(__CUDACC_RTC__)
#define TR_CUDA 1
#define TR_FN static __device__ __forceinline__
#define TR_NOINLINE static __device__ __noinline__
typedef unsigned long long tr_u64;
typedef unsigned int tr_u32;
typedef long long tr_i64;
#ifdef TR_ARITHMETIC_ONLY
/* a compile check only (tests/ptx.rs): the kernel's own arithmetic without CUDA's functions,
 * whose implementations use fused multiply-adds, so that the PTX shows none of ours */
#define tr_exp(x) (x)
#define tr_ln(x) (x)
#define tr_expm1(x) (x)
#define tr_pow(x, y) ((x) * (y))
#define tr_cos(x) (x)
#define tr_sin(x) (x)
#define tr_fmod(x, y) ((x) - (y))
#else
#define tr_exp(x) exp(x)
#define tr_ln(x) log(x)
#define tr_expm1(x) expm1(x)
#define tr_pow(x, y) pow(x, y)
#define tr_cos(x) cos(x)
#define tr_sin(x) sin(x)
/* exact in CUDA as in C (the remainder is representable): as Rust's `%` */
#define tr_fmod(x, y) fmod(x, y)
#endif
#define tr_sqrt(x) sqrt(x)
#define tr_fabs(x) fabs(x)
#else
#define TR_CUDA 0
#include <math.h>
#include <stdint.h>
#define TR_FN static inline
#define TR_NOINLINE static
typedef uint64_t tr_u64;
typedef uint32_t tr_u32;
typedef int64_t tr_i64;
/* the engine's functions (`trirhythm::maths`), defined in Rust (src/emulate.rs) */
double tr_host_exp(double x);
double tr_host_ln(double x);
double tr_host_expm1(double x);
double tr_host_pow(double x, double y);
double tr_host_cos(double x);
double tr_host_sin(double x);
#define tr_exp(x) tr_host_exp(x)
#define tr_ln(x) tr_host_ln(x)
#define tr_expm1(x) tr_host_expm1(x)
#define tr_pow(x, y) tr_host_pow(x, y)
#define tr_cos(x) tr_host_cos(x)
#define tr_sin(x) tr_host_sin(x)
/* fmod is exact (C99 F.9.7.1), as Rust's `%` on f64 */
#define tr_fmod(x, y) fmod(x, y)
#define tr_sqrt(x) sqrt(x)
#define tr_fabs(x) fabs(x)
#endif

/* f64 <-> bits without undefined behaviour in either build */
TR_FN double tr_from_bits(tr_u64 b) {
#if TR_CUDA
    return __longlong_as_double((long long)b);
#else
    double d;
    __builtin_memcpy(&d, &b, 8);
    return d;
#endif
}

TR_FN tr_u64 tr_to_bits(double d) {
#if TR_CUDA
    return (tr_u64)__double_as_longlong(d);
#else
    tr_u64 b;
    __builtin_memcpy(&b, &d, 8);
    return b;
#endif
}

#endif
