/* The step's constants: the C mirror of `trirhythm::engine::StepPlan` (#[repr(C)], field by
 * field, same order and types; tests/emulation.rs checks the sizes and offsets), and of
 * `trirhythm::engine::GeneralPlan` (TrGeneralPlan, below). TR_MAX_CAP and TR_MAX_MODES size the
 * per-path arrays: the emulation takes the plan's maxima, the GPU build the plans' own values
 * (`src/gpu.rs`: the largest over the leading memory and the fractional terms' memories), so
 * that a path's state is small. */
#ifndef TR_PLAN_H
#define TR_PLAN_H
#include "common.h"

#define TR_PLAN_MAX_MODES 128
#define TR_PLAN_MAX_CAP 63
#define TR_PLAN_MAX_DAMPING 16
#ifndef TR_MAX_CAP
#define TR_MAX_CAP TR_PLAN_MAX_CAP
#endif
#ifndef TR_MAX_MODES
#define TR_MAX_MODES TR_PLAN_MAX_MODES
#endif
/* splits live in the window at once: at most one per step of it */
#define TR_MAX_SPLITS (TR_MAX_CAP + 1)

typedef struct {
    double damping[TR_PLAN_MAX_DAMPING];
    tr_u32 damping_terms, damping_long;
    double omega2, gain, restitution, lambda, h, blow_up;
    tr_u32 wall, crossing, restart, soe;
    double scale, wl0, wr0;
    tr_u32 cap, n_exp, modes, flat, older_len;
    double wl[TR_PLAN_MAX_CAP + 1];
    double wr[TR_PLAN_MAX_CAP + 1];
    double older[2 * TR_PLAN_MAX_CAP + 4];
    double newest[2];
    double rates[TR_PLAN_MAX_MODES];
    double weights[TR_PLAN_MAX_MODES];
    double decay[TR_PLAN_MAX_MODES];
    double start[TR_PLAN_MAX_MODES];
    double end[TR_PLAN_MAX_MODES];
    double out[TR_PLAN_MAX_MODES];
    double lumped[4];
    double lumped_out[4];
    double shift[7];
    double piece[6];
    double iw_even[12];
    double iw_odd[12];
    double iw_whole[16];
    double phi_series[17];
    double psi_series[17];
} TrPlan;

/* The General kernel's constants: the C mirror of `trirhythm::engine::GeneralPlan` (the same
 * fields, order and types; `active` = 0 for the paper's family). */
#define TR_PLAN_MAX_RAYLEIGH 20
#define TR_PLAN_MAX_FRACTIONAL 2

/* `trirhythm::engine::noise::StepConstants` (TrNoise's first fields) */
typedef struct {
    tr_u32 kind;
    double rho, sigma, mean_coef, cross, rest, dt, sd;
} TrNoiseConstants;

typedef struct {
    tr_u32 active, rayleigh_terms;
    double rayleigh[TR_PLAN_MAX_RAYLEIGH];
    double cubic, quintic, kappa;
    tr_u32 forcing, multiplicative;
    double amplitude, angle, phase, rotation_cos, rotation_sin, start_cos, start_sin;
    double mix, own;
    tr_u64 salt;
    TrNoiseConstants parametric;
    /* the model's walls: [0] the lower (keeping U above it), [1] the upper */
    tr_u32 walls;
    tr_u32 wall_present[2];
    tr_u32 wall_speed_dependent[2];
    double wall_position[2], wall_r[2], wall_r_fast[2], wall_speed[2];
    /* the fractional terms K_j D^{α_j}U: K_j, ϖ_l^j, ϖ_r^j, and the memory of J^{1−α_j}V of
     * each term with α_j < 1 (its constants in a TrPlan's memory fields) */
    tr_u32 fractional_terms;
    tr_u32 fractional_memory[TR_PLAN_MAX_FRACTIONAL];
    double fractional_k[TR_PLAN_MAX_FRACTIONAL];
    double fractional_wl[TR_PLAN_MAX_FRACTIONAL];
    double fractional_wr[TR_PLAN_MAX_FRACTIONAL];
    TrPlan memories[TR_PLAN_MAX_FRACTIONAL];
} TrGeneralPlan;

#endif
