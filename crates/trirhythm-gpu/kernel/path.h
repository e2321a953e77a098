/* One path of an ensemble from its start to the end of the window: the engine's stepper and
 * recorder together (what `run_paths` does for one path), shared by the GPU kernel's thread
 * (`ensemble.cu`) and the CPU emulation (`emulate.c`). */
#ifndef TR_PATH_H
#define TR_PATH_H
#include "general.h"
#include "record.h"

/* which step the build holds: 0 the paper kernel's only, 1 the General kernel's only (the GPU
 * build, from the plan), 2 both, chosen per run by the General plan's `active` (the
 * emulation) */
#ifndef TR_GENERAL
#define TR_GENERAL 2
#endif

/* how a path ended, and what a blow-up reports */
typedef struct {
    tr_u64 status, steps, impacts, sticking_steps;
    double u, v, from_u, from_v;
} TrPathEnd;

TR_FN void tr_run_path(const TrPlan* P, const TrGeneralPlan* G, const TrNoise* noise,
                       const TrRecordPlan* L, const double* zx, const double* zf, tr_u64 seed,
                       tr_u64 path, double u0, double v0, tr_u64 steps, TrPath* s,
                       TrBatch* batches, tr_u64* wells, TrPassage* passages, tr_u64* counts,
                       TrPathEnd* end) {
    TrRecorder R;
    tr_recorder_new(L, &R);
    tr_path_new(P, noise, s, u0, v0, seed, path, zx, zf);
#if TR_GENERAL == 0
    (void)G;
#else
    TrGeneral g;
#if TR_GENERAL == 1
    int general = 1;
#else
    int general = G->active != 0;
#endif
    if (general) {
        tr_general_new(P, G, s, &g, seed, path, zx, zf);
    }
#endif
    tr_observe(L, &R, batches, wells, passages, counts, 0, u0, v0, 0.0);
    int status = TR_OK;
    for (tr_u64 n = 1; n <= steps; n++) {
#if TR_GENERAL == 0
        status = tr_step(P, s, zx, zf);
#elif TR_GENERAL == 1
        status = tr_step_general(P, G, s, &g, zx, zf);
#else
        status = general ? tr_step_general(P, G, s, &g, zx, zf) : tr_step(P, s, zx, zf);
#endif
        if (status != TR_OK) {
            break;
        }
        tr_observe(L, &R, batches, wells, passages, counts, s->steps, s->u, s->v,
                   (double)s->steps * P->h);
    }
    tr_recorder_finish(L, &R, passages);
    end->status = (tr_u64)status;
    end->steps = s->steps;
    end->impacts = s->impacts;
    end->sticking_steps = s->sticking_steps;
    end->u = s->u;
    end->v = s->v;
    end->from_u = s->from_u;
    end->from_v = s->from_v;
}

#endif
