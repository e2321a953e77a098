/* The ensemble kernel: one thread per path, the engine's step and recorder (path.h) with the
 * path's state in registers and local memory, the run's constants (plan, recorder, noise,
 * ziggurat tables) read-only and shared by every thread, each path's statistics written to its
 * own rows of global memory (the same units as the CPU engine's PathStats; the host merges
 * them with the engine's `merge`). Compiled at run time by NVRTC (src/cuda.rs) with
 * --fmad=false and TR_MAX_CAP / TR_MAX_MODES set to the plan's window and modes, TR_GENERAL
 * (the paper's step or the General kernel's, general.h) and TR_MULTIPLICATIVE from the General
 * plan. */
#define TR_COUNT(c, i) ((c)[i] += 1)
#include "path.h"

extern "C" __global__ void tr_ensemble(const TrPlan* __restrict__ plan,
                                       const TrGeneralPlan* __restrict__ general,
                                       const TrNoise* __restrict__ noise,
                                       const TrRecordPlan* __restrict__ record,
                                       const double* __restrict__ zx,
                                       const double* __restrict__ zf, tr_u64 seed, tr_u64 first,
                                       tr_u64 count, tr_u64 steps,
                                       const double* __restrict__ starts, tr_u64 nstarts,
                                       TrBatch* batches, tr_u64* wells, TrPassage* passages,
                                       tr_u64* counts, TrPathEnd* ends) {
    tr_u64 i = (tr_u64)blockIdx.x * blockDim.x + threadIdx.x;
    if (i >= count) {
        return;
    }
    tr_u64 path = first + i;
    tr_u64 k = path % nstarts;
    tr_u64 nb = record->batches, nw = record->wells;
    tr_u64 nc = 4 * (3 * ((tr_u64)record->bins + 1) +
                     (tr_u64)record->joint_bins * record->joint_bins + 1);
    TrPath s;
    tr_run_path(plan, general, noise, record, zx, zf, seed, path, starts[2 * k],
                starts[2 * k + 1], steps, &s, batches + i * nb, wells + i * nb * nw,
                passages + i * nw * nw, counts + i * nc, ends + i);
}
