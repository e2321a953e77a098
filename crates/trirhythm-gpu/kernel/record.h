/* What one path records, streamed: the engine's ensemble recorder
 * (`analysis::ensemble::recording::Recorder`) step by step — batch sums, well occupancies, the
 * histograms of A, of the energy, of the turning amplitude and of (U, U̇) per quarter of the
 * window, first passages between wells — the same samples, bins and sums in the same order.
 * The histogram counts go to `counts` through TR_COUNT: the path's own row in the emulation,
 * the block's shared rows on the GPU (integer additions: any order gives the same counts). */
#ifndef TR_RECORD_H
#define TR_RECORD_H
#include "common.h"

#define TR_QUARTERS 4
#define TR_MAX_WELLS 8
#define TR_NEVER 0xffffffffffffffffULL

/* the C mirror of `trirhythm::analysis::ensemble::RecordPlan` */
typedef struct {
    tr_u32 bins, joint_bins, batches, wells, crossing, pad;
    tr_u64 burn, every, samples;
    double a_scale, h_scale, u_lo, u_scale, v_lo, v_scale, inv_omega1_sq, omega1_sq, bins_f,
        joint_bins_f;
    double antimodes[TR_MAX_WELLS];
    double core_lo[TR_MAX_WELLS];
    double core_hi[TR_MAX_WELLS];
} TrRecordPlan;

/* one batch's sums (`BatchSums` without its wells) */
typedef struct {
    tr_u64 n;
    double u, u2, v, v2, a;
} TrBatch;

/* one first-passage cell (`PassageSums`) */
typedef struct {
    tr_u64 count;
    double time, time2;
    tr_u64 censored;
} TrPassage;

typedef struct {
    tr_u64 sample, k, until_sample, next_quarter, next_batch;
    tr_u32 quarter, batch;
    int rising, state;
    double clocks[TR_MAX_WELLS * TR_MAX_WELLS];
} TrRecorder;

TR_FN tr_u64 tr_div_ceil(tr_u64 a, tr_u64 b) { return a / b + (a % b != 0 ? 1 : 0); }

TR_FN tr_u64 tr_quarter_start(tr_u32 q, tr_u64 len) {
    if (q >= TR_QUARTERS) {
        return TR_NEVER;
    }
    return tr_div_ceil((tr_u64)q * len, TR_QUARTERS) + 1;
}

TR_FN tr_u64 tr_batch_start(tr_u32 b, tr_u32 batches, tr_u64 samples) {
    if (b >= batches) {
        return TR_NEVER;
    }
    return tr_div_ceil((tr_u64)b * samples, batches);
}

TR_FN tr_u32 tr_bin(double x, double scale, tr_u32 n, double nf) {
    double b = x * scale;
    if (b >= 0.0 && b < nf) {
        return (tr_u32)(tr_i64)b;
    }
    return n;
}

TR_FN tr_u64 tr_stride(const TrRecordPlan* L) {
    return 3 * ((tr_u64)L->bins + 1) + (tr_u64)L->joint_bins * L->joint_bins + 1;
}

TR_FN void tr_recorder_new(const TrRecordPlan* L, TrRecorder* R) {
    R->sample = 0;
    R->k = 0;
    R->until_sample = L->every;
    R->quarter = 0;
    R->next_quarter = tr_quarter_start(1, L->every * L->samples);
    R->batch = 0;
    R->next_batch = tr_batch_start(1, L->batches, L->samples);
    R->rising = 0;
    R->state = -1;
    for (int i = 0; i < TR_MAX_WELLS * TR_MAX_WELLS; i++) {
        R->clocks[i] = tr_from_bits(0x7ff8000000000000ULL);
    }
}

TR_FN tr_u32 tr_well_of(const TrRecordPlan* L, double a) {
    tr_u32 k = 0;
    while (k + 1 < L->wells && a > L->antimodes[k]) {
        k++;
    }
    return k;
}

/* a turning point of |U| at amplitude a, time t (engine `Recorder::turning_point`) */
TR_FN void tr_turning_point(const TrRecordPlan* L, TrRecorder* R, TrPassage* passages,
                            tr_u64* counts, double a, double t) {
    tr_u64 row = (tr_u64)R->quarter * tr_stride(L) + 2 * ((tr_u64)L->bins + 1);
    TR_COUNT(counts, row + tr_bin(a, L->a_scale, L->bins, L->bins_f));
    if (L->wells == 0) {
        return;
    }
    tr_u32 k = tr_well_of(L, a);
    if (!(a >= L->core_lo[k] && a <= L->core_hi[k])) {
        return;
    }
    if (R->state == (int)k) {
        return;
    }
    tr_u32 n = L->wells;
    for (tr_u32 i = 0; i < n; i++) {
        double c = R->clocks[i * n + k];
        if (!(c != c)) {
            double dt = t - c;
            TrPassage* p = &passages[i * n + k];
            p->count += 1;
            p->time += dt;
            p->time2 += dt * dt;
            R->clocks[i * n + k] = tr_from_bits(0x7ff8000000000000ULL);
        }
    }
    for (tr_u32 j = 0; j < n; j++) {
        double c = R->clocks[k * n + j];
        if (j != k && c != c) {
            R->clocks[k * n + j] = t;
        }
    }
    R->state = (int)k;
}

/* after step n of a path at (u, v), time t (engine `Recorder::observe`) */
TR_FN void tr_observe(const TrRecordPlan* L, TrRecorder* R, TrBatch* batches, tr_u64* wells,
                      TrPassage* passages, tr_u64* counts, tr_u64 n, double u, double v,
                      double t) {
    if (n <= L->burn) {
        if (n == L->burn) {
            double sg = u > 0.0 ? 1.0 : (u < 0.0 ? -1.0 : (tr_to_bits(u) >> 63 ? -1.0 : 1.0));
            R->rising = sg * v > 0.0;
        }
        return;
    }
    R->k += 1;
    if (R->k >= R->next_quarter) {
        R->quarter += 1;
        R->next_quarter = tr_quarter_start(R->quarter + 1, L->every * L->samples);
    }
    double side = 1.0;
    if (L->crossing) {
        side = u > 0.0 ? 1.0 : (u < 0.0 ? -1.0 : (tr_to_bits(u) >> 63 ? -1.0 : 1.0));
    }
    int rising = side * v > 0.0;
    if (R->rising && !rising) {
        tr_turning_point(L, R, passages, counts, tr_fabs(u), t);
    }
    R->rising = rising;
    R->until_sample -= 1;
    if (R->until_sample != 0) {
        return;
    }
    R->until_sample = L->every;
    if (R->sample >= L->samples) {
        return;
    }
    if (R->sample >= R->next_batch) {
        R->batch += 1;
        R->next_batch = tr_batch_start(R->batch + 1, L->batches, L->samples);
    }
    tr_u32 b = R->batch;
    R->sample += 1;
    double a2 = u * u + v * v * L->inv_omega1_sq;
    double a = tr_sqrt(a2);
    TrBatch* batch = &batches[b];
    batch->n += 1;
    batch->u += u;
    batch->u2 += u * u;
    batch->v += v;
    batch->v2 += v * v;
    batch->a += a;
    if (L->wells > 0) {
        wells[(tr_u64)b * L->wells + tr_well_of(L, a)] += 1;
    }
    tr_u64 row = (tr_u64)R->quarter * tr_stride(L);
    tr_u64 brow = (tr_u64)L->bins + 1;
    TR_COUNT(counts, row + tr_bin(a, L->a_scale, L->bins, L->bins_f));
    TR_COUNT(counts, row + brow + tr_bin(0.5 * L->omega1_sq * a2, L->h_scale, L->bins, L->bins_f));
    tr_u32 jb = L->joint_bins;
    tr_u32 iu = tr_bin(u - L->u_lo, L->u_scale, jb, L->joint_bins_f);
    tr_u32 iv = tr_bin(v - L->v_lo, L->v_scale, jb, L->joint_bins_f);
    tr_u64 cell = iu < jb && iv < jb ? (tr_u64)iu * jb + iv : (tr_u64)jb * jb;
    TR_COUNT(counts, row + 2 * brow + brow + cell);
}

/* the end of the window: passages still running are censored (engine `finish_counted`) */
TR_FN void tr_recorder_finish(const TrRecordPlan* L, const TrRecorder* R, TrPassage* passages) {
    tr_u32 n = L->wells;
    for (tr_u32 i = 0; i < n * n; i++) {
        double c = R->clocks[i];
        if (!(c != c)) {
            passages[i].censored += 1;
        }
    }
}

#endif
