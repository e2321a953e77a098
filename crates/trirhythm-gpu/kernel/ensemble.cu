/* trirhythm-gpu: the ensemble kernel (a placeholder: the kernel's author replaces it).
 *
 * Compiled at run time by NVRTC (src/cuda.rs, `compile_ptx`) with the headers of this folder;
 * tests/ptx.rs compiles it to PTX in CI and checks that every `extern "C" __global__` entry
 * below is in the PTX. */
#include "common.h"

extern "C" __global__ void tr_ensemble(const double *u0, tr_u64 *bits, int paths) {
    int i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i < paths) {
        bits[i] = tr_to_bits(u0[i]);
    }
}
