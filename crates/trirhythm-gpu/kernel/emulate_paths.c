/* The CPU emulation's entry points for whole paths: the kernel's `tr_run_path` (path.h) for
 * one path at a time, with its histograms in the path's own rows (src/paths.rs calls it from
 * several threads, one path per call). */
#include <stddef.h>
#define TR_COUNT(c, i) ((c)[i] += 1)
#include "path.h"

void tr_emulate_path(const TrPlan* plan, const TrGeneralPlan* general, const TrNoise* noise,
                     const TrRecordPlan* record, const double* zx, const double* zf, tr_u64 seed,
                     tr_u64 path, double u0, double v0, tr_u64 steps, TrBatch* batches,
                     tr_u64* wells, TrPassage* passages, tr_u64* counts, TrPathEnd* end) {
    /* a path's state is a few kilobytes at the plan's maximal sizes: on the heap of the
     * caller's thread would do as well; the stack keeps the call free of allocation */
    TrPath s;
    tr_run_path(plan, general, noise, record, zx, zf, seed, path, u0, v0, steps, &s, batches,
                wells, passages, counts, end);
}

/* sizes and offsets of the shared structures, checked against Rust's layouts in the tests */
tr_u64 tr_layout(int which) {
    switch (which) {
    case 0: return sizeof(TrPlan);
    case 1: return offsetof(TrPlan, older_len);
    case 2: return offsetof(TrPlan, psi_series);
    case 3: return sizeof(TrRecordPlan);
    case 4: return offsetof(TrRecordPlan, core_hi);
    case 5: return sizeof(TrNoise);
    case 6: return sizeof(TrBatch);
    case 7: return sizeof(TrPassage);
    case 8: return sizeof(TrPathEnd);
    case 9: return offsetof(TrPlan, omega2);
    case 10: return offsetof(TrRecordPlan, burn);
    case 11: return sizeof(TrGeneralPlan);
    case 12: return offsetof(TrGeneralPlan, cubic);
    case 13: return offsetof(TrGeneralPlan, forcing);
    case 14: return offsetof(TrGeneralPlan, amplitude);
    case 15: return offsetof(TrGeneralPlan, salt);
    case 16: return offsetof(TrGeneralPlan, parametric);
    case 17: return offsetof(TrGeneralPlan, parametric.sd);
    case 18: return offsetof(TrGeneralPlan, walls);
    case 19: return offsetof(TrGeneralPlan, wall_position);
    case 20: return offsetof(TrGeneralPlan, fractional_terms);
    case 21: return offsetof(TrGeneralPlan, fractional_k);
    case 22: return offsetof(TrGeneralPlan, memories);
    default: return 0;
    }
}
