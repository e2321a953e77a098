/* trirhythm-gpu: the host side's probe kernel (tests/ptx.rs): each thread copies one double's
 * bits, so that a launch, the buffers and the arguments' order are checked on a device
 * without any arithmetic. */
#include "common.h"

extern "C" __global__ void tr_probe(const double *x, tr_u64 *bits, tr_u64 n, tr_u64 offset) {
    tr_u64 i = (tr_u64)blockIdx.x * blockDim.x + threadIdx.x;
    if (i < n) {
        bits[i] = tr_to_bits(x[i]) + offset;
    }
}
