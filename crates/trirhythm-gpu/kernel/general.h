/* The General kernel's step: the engine's `Stepper::step_general` and what it calls (engine
 * `stepper::{mod, general, impact}`), the same expressions in the same order; the tangent is
 * not ported (the ensembles do not need it).
 *
 * Equation (engine `stepper::general`):
 *   D^{1+λ}U + Σ_j K_j D^{α_j}U − h(U, U̇)U̇ + k(U) = F cos(Ωt + φ) + η_a(t) + U·η_m(t),
 *   h = μ0P(U) + Σ_{k≥1} d_k U̇^{2k},  k(U) = ω0²U + k3U³ + k5U⁵,
 * with no wall, the paper's wall at U = 0 (impacts U̇₊ = −rU̇₋, sticking, either impact memory)
 * or the model's walls (engine `stepper::walls`: one at any δ keeping U above or below it, or
 * two at δ1 < δ2, each with a constant r or r(v) = r_fast + (r0 − r_fast)e^{−v/v_s}; sticking
 * at δ); in Volterra form U′ = V, V = V₀ + J^λ g, with m_j = J^{1−α_j}V (= D^{α_j}U),
 * g = h(U, V)V − k(U) − Σ_j K_j m_j + F cos ψ + η_a + Uη_m.
 *
 * Method: the engine's General kernel. Each corrector pass freezes U at its predictor U^P and
 * linearises hV in V at V_l (the first pass at V_n, the second at the first pass's V):
 *   V_{n+1} = [N + w_r(F_r − k(U^P) + (h(U^P, V_l) − a)V_l)] / (1 − w_r a),
 *   a = ∂_V(hV)(U^P, V_l) − κ, U_{n+1} as the paper kernel's with the limiter L(2w_r a).
 * The forcing's phase is per-path state: (cos ψ_n, sin ψ_n) rotated every step by the plan's
 * (cos ΩΔt, sin ΩΔt) and re-anchored from ψ = φ + (ΩΔt·n mod 2π) every 256 steps. η_m is
 * piecewise constant at its exact step mean, from a stream of its own ((seed ^ salt, path)),
 * mixed with the additive noise as it enters g: η_m = mix·side·η_a + own·η′ (correlation c).
 * At the wall at 0 the impact is located on the Hermite interpolant and the scheme's V(t*−)
 * is the root of V = N + w_s(h(0, V)V + F cos ψ* + η*) (affine without Rayleigh terms, else
 * Newton's method); the rest of the step is this kernel's step from (0, V₊). At the model's
 * walls the same with U − δ located, g at the wall h(δ, V)V − k(δ) + F cos ψ* + η* + δη_m,
 * V₋ clipped to the wall's side, V₊ = −r(|V₋|)V₋; a path stuck at δ stays clamped while its
 * free step ends beyond the wall (n(U₁ − δ) ≤ 0), and a step that meets both walls stops the
 * path with the engine's refusal of Δt (TR_TWO_WALLS).
 * Fractional terms: m_j is a memory of V of order 1 − α_j — memory.h's TrHistory with its own
 * TrPlan (the General plan's `memories`), into which each step pushes (V_n, V_{n+1});
 * m_{j,n+1} = M_j + ϖ_l^j V_n + ϖ_r^j V_{n+1} is affine in V_{n+1}, so the corrector keeps its
 * one division with a − κ (κ = Σ K_j ϖ_r^j) and −Σ K_j(M_j + ϖ_l^j V_n) in the known forcing;
 * α_j = 1 is local (m_j = V). At an impact m_j(t*) = A_j + c_j V(t*) enters the root for V(t*)
 * (κ* = Σ K_j c_j), g's split piece carries −Σ K_j m_j(t*) on both sides (V₊ for α = 1), each
 * memory of V is split at the instant as the leading memory of g is (restarted with it), and
 * the redone rest uses the split memories' κ_s and known part.
 *
 * Constants: `trirhythm::engine::GeneralPlan` (TrGeneralPlan, plan.h), copied out of the
 * engine's own `General`; the damping μ0P, ω0², the wall and the memory are the StepPlan's.
 * Per-path state is TrGeneral: a few words, with TR_MULTIPLICATIVE the second stream, and
 * TR_MAX_FRACTIONAL memories of V (the GPU build sets both from the plan: 0 where unused).
 *
 * Reference: the engine's module docs of `stepper::general` (model-class.md §2–§5;
 * Diethelm, Ford & Freed 2002 for the scheme).
 *
 * Tests: tests/emulation.rs (`general_*`, `a_step_that_meets_both_walls_*`): Duffing,
 * quintic, Rayleigh, forcing past several re-anchorings, multiplicative noise (white and OU,
 * correlated), fractional terms (α < 1 and α = 1, one or two, λ = 1 and a window of 24), with
 * no wall, with the wall at 0 and with the model's walls (two walls, offset walls above and
 * below, speed-dependent restitution, sticking at δ, both impact memories):
 * every path's statistics and the merged result bit for bit as the engine's `run_paths` and
 * `run_ensemble`; a blow-up and the two-wall refusal with the engine's messages. */
#ifndef TR_GENERAL_H
#define TR_GENERAL_H
#include "step.h"

/* the multiplicative noise's stream in a path's state (the GPU build sets it from the plan) */
#ifndef TR_MULTIPLICATIVE
#define TR_MULTIPLICATIVE 1
#endif

/* the fractional terms' memories in a path's state (the GPU build sets the plan's count) */
#ifndef TR_MAX_FRACTIONAL
#define TR_MAX_FRACTIONAL TR_PLAN_MAX_FRACTIONAL
#endif

/* steps between re-anchorings of the forcing's phase (engine `general::REANCHOR`) */
#define TR_REANCHOR 256u
/* std::f64::consts::TAU */
#define TR_TAU 6.283185307179586476925286766559

/* one path's General state (engine `General`'s per-path fields) */
typedef struct {
    /* (cos ψ_n, sin ψ_n) and n (engine `Phase`) */
    double cos_now, sin_now;
    tr_u64 n;
    /* η_m on the step in progress, −Σ K_j m_j at the node, its part known at the step's start */
    double eta_m, lag, ahead;
#if TR_MULTIPLICATIVE
    TrRng rng;
    TrNoise noise;
#endif
#if TR_MAX_FRACTIONAL > 0
    /* the memory of J^{1−α_j}V of each term with α_j < 1 (indexed by term) */
    TrHistory memories[TR_MAX_FRACTIONAL];
    /* the memories split at an impact inside the step in progress (engine `SplitMemories`):
     * V's split, the part of −Σ K_j m_{j,n+1} known after the impact, κ_s */
    int pending;
    TrSplit pending_split;
    double pending_ahead, pending_kappa;
#endif
} TrGeneral;

/* the Rayleigh parts at v (engine `General::rayleigh_at`, the tangent's parts left out) */
typedef struct {
    double h, a, rest;
} TrRayleighAt;

TR_FN TrRayleighAt tr_rayleigh_at(const TrGeneralPlan* G, double v) {
    TrRayleighAt r;
    r.h = 0.0;
    r.a = 0.0;
    r.rest = 0.0;
    if (G->rayleigh_terms == 0) {
        return r;
    }
    double x = v * v;
    double h = 0.0, a = 0.0;
    double before = 1.0;
    for (tr_u32 i = 0; i < G->rayleigh_terms; i++) {
        double d = G->rayleigh[i];
        double k = (double)(i + 1);
        double pow = before * x;
        h += d * pow;
        a += (2.0 * k + 1.0) * d * pow;
        before = pow;
    }
    r.h = h;
    r.a = a;
    r.rest = (h - a) * v;
    return r;
}

/* k(U) = ω0²U + k3U³ + k5U⁵ */
TR_FN double tr_restoring(const TrPlan* P, const TrGeneralPlan* G, double u) {
    double x = u * u;
    return u * (P->omega2 + x * (G->cubic + G->quintic * x));
}

/* ∂_V(hV) at (u, v) */
TR_FN double tr_general_a(const TrPlan* P, const TrGeneralPlan* G, double u, double v) {
    return tr_damping(P, u) + tr_rayleigh_at(G, v).a;
}

/* h(U, V)V − k(U): g without its forcing */
TR_FN double tr_general_drift(const TrPlan* P, const TrGeneralPlan* G, double u, double v) {
    return (tr_damping(P, u) + tr_rayleigh_at(G, v).h) * v - tr_restoring(P, G, u);
}

/* the drift and the predictor's weight at a node (engine `General::node`) */
TR_FN void tr_general_node(const TrPlan* P, const TrGeneralPlan* G, double h, double u1,
                           double v1, double* drift, double* pw) {
    *drift = tr_general_drift(P, G, u1, v1);
    *pw = tr_predictor_weight(h, tr_general_a(P, G, u1, v1) - G->kappa);
}

/* g at a wall U = δ without its forcing, h(δ, V)V − k(δ) (engine `General::wall_drift`) */
TR_FN double tr_wall_drift(const TrPlan* P, const TrGeneralPlan* G, double delta, double v) {
    return (tr_damping(P, delta) + tr_rayleigh_at(G, v).h) * v - tr_restoring(P, G, delta);
}

/* the scheme's velocity at an impact on a wall U = δ, the root of
 * V = N + w((h(δ, V) − κ*)V + forcing) (engine `General::wall_velocity_lagged`; κ* = 0:
 * `wall_velocity`) */
TR_NOINLINE double tr_wall_velocity(const TrPlan* P, const TrGeneralPlan* G, double delta,
                                    double known, double w, double forcing, double kappa) {
    double a0 = kappa == 0.0 ? tr_damping(P, delta) : tr_damping(P, delta) - kappa;
    double v = (known + w * forcing) / (1.0 - w * a0);
    if (G->rayleigh_terms == 0) {
        return v;
    }
    for (int it = 0; it < 50; it++) {
        TrRayleighAt r = tr_rayleigh_at(G, v);
        double f = v - known - w * ((a0 + r.h) * v + forcing);
        double df = 1.0 - w * (a0 + r.a);
        double step = f / df;
        v -= step;
        /* a NaN step ends the iteration too */
        if (step != step || tr_fabs(step) <= 1e-14 * (1.0 + tr_fabs(v))) {
            break;
        }
    }
    return v;
}

/* one pass with U frozen at up, hV linearised at vl (engine `General::pass`) */
TR_FN void tr_general_pass(const TrPlan* P, const TrGeneralPlan* G, const TrGeneral* g,
                           double kappa, double len, double u, double v, double g0, double up,
                           double vl, double known, double w, double fr, double* u1,
                           double* v1) {
    double mp = tr_damping(P, up);
    TrRayleighAt r = tr_rayleigh_at(G, vl);
    double a = mp + r.a - kappa;
    double k = tr_restoring(P, G, up);
    if (G->multiplicative) {
        fr = fr + up * g->eta_m;
    }
    double inv = 1.0 / (1.0 - w * a);
    double z = 2.0 * w * a;
    double lim = 1.0 / (1.0 + z * z * (1.0 / 12.0));
    double vv = (known + w * (fr - k + r.rest)) * inv;
    double gr = (mp + tr_rayleigh_at(G, vv).h - kappa) * vv - k + fr;
    *u1 = u + 0.5 * len * (v + vv) + len * len * (1.0 / 12.0) * lim * (g0 - gr);
    *v1 = vv;
}

/* the step of length len from (u, v) where g = g0 (engine `General::advance_split`) */
TR_FN void tr_general_advance(const TrPlan* P, const TrGeneralPlan* G, const TrGeneral* g,
                              double kappa, double len, double u, double v, double g0, double pw,
                              double known, double w, double fr, double* u1, double* v1) {
    double up1, vp1;
    tr_general_pass(P, G, g, kappa, len, u, v, g0, u + len * v + pw * g0, v, known, w, fr, &up1,
                    &vp1);
    tr_general_pass(P, G, g, kappa, len, u, v, g0, up1, vp1, known, w, fr, u1, v1);
}

/* F cos ψ at the current node and at the next, the phase moved there (engine
 * `General::forces`, `Phase::advance`) */
TR_FN void tr_phase_forces(const TrGeneralPlan* G, TrGeneral* g, double* left, double* right) {
    if (!G->forcing) {
        *left = 0.0;
        *right = 0.0;
        return;
    }
    *left = G->amplitude * g->cos_now;
    g->n += 1;
    if (g->n % TR_REANCHOR == 0) {
        /* ψ = φ + (ΩΔt·n).rem_euclid(2π) */
        double r = tr_fmod(G->angle * (double)g->n, TR_TAU);
        if (r < 0.0) {
            r = r + TR_TAU;
        }
        double psi = G->phase + r;
        g->cos_now = tr_cos(psi);
        g->sin_now = tr_sin(psi);
    } else {
        double c = g->cos_now, s = g->sin_now;
        g->cos_now = c * G->rotation_cos - s * G->rotation_sin;
        g->sin_now = s * G->rotation_cos + c * G->rotation_sin;
    }
    *right = G->amplitude * g->cos_now;
}

/* F cos ψ at the current node (engine `General::force_now`) */
TR_FN double tr_force_now(const TrGeneralPlan* G, const TrGeneral* g) {
    return G->forcing ? G->amplitude * g->cos_now : 0.0;
}

/* F cos ψ at the fraction θ of the step that ends at the current node (engine
 * `General::force_at`) */
TR_FN double tr_force_at(const TrGeneralPlan* G, const TrGeneral* g, double theta) {
    if (!G->forcing) {
        return 0.0;
    }
    double back = (1.0 - theta) * G->angle;
    return G->amplitude * (g->cos_now * tr_cos(back) + g->sin_now * tr_sin(back));
}

/* the path's General state at its start (engine `General::new`'s phase and stream, `start`,
 * then the node of `Stepper::with_history`) */
TR_FN void tr_general_new(const TrPlan* P, const TrGeneralPlan* G, TrPath* s, TrGeneral* g,
                          tr_u64 seed, tr_u64 path, const double* zx, const double* zf) {
    g->cos_now = G->start_cos;
    g->sin_now = G->start_sin;
    g->n = 0;
    g->eta_m = 0.0;
    g->lag = 0.0;
    g->ahead = 0.0;
#if TR_MAX_FRACTIONAL > 0
    /* −Σ K_j m_j(0): an α = 1 term is V(0) itself, the others start at 0 */
    g->pending = 0;
    for (tr_u32 j = 0; j < G->fractional_terms; j++) {
        tr_history_new(&g->memories[j]);
        if (!G->fractional_memory[j]) {
            g->lag -= G->fractional_k[j] * s->v;
        }
    }
#endif
#if TR_MULTIPLICATIVE
    if (G->multiplicative) {
        tr_rng_new(&g->rng, seed ^ G->salt, path);
        g->noise.kind = G->parametric.kind;
        g->noise.rho = G->parametric.rho;
        g->noise.sigma = G->parametric.sigma;
        g->noise.mean_coef = G->parametric.mean_coef;
        g->noise.cross = G->parametric.cross;
        g->noise.rest = G->parametric.rest;
        g->noise.dt = G->parametric.dt;
        g->noise.sd = G->parametric.sd;
        tr_noise_start(&g->noise, &g->rng, zx, zf);
    }
#else
    (void)seed;
    (void)path;
    (void)zx;
    (void)zf;
#endif
    tr_general_node(P, G, P->h, s->u, s->v, &s->drift, &s->pw);
}

/* the start of a step from (u, v), η_a = el as it enters g (engine `General::begin_step`):
 * draws η_m; returns g's extra at the step's start and the part known of its end's */
TR_FN void tr_general_begin(const TrGeneralPlan* G, TrGeneral* g, double u, double v,
                            double el, const double* zx, const double* zf, double* xl,
                            double* xr) {
#if TR_MULTIPLICATIVE
    if (G->multiplicative) {
        double own, own_r;
        tr_noise_step(&g->noise, &g->rng, zx, zf, &own, &own_r);
        g->eta_m = G->mix * el + G->own * own;
    }
#else
    (void)el;
    (void)zx;
    (void)zf;
#endif
    double ahead = 0.0;
#if TR_MAX_FRACTIONAL > 0
    /* −Σ_j K_j(M_j + ϖ_l^j V_n) */
    for (tr_u32 j = 0; j < G->fractional_terms; j++) {
        double past = G->fractional_memory[j] ? g->memories[j].cached : 0.0;
        ahead -= G->fractional_k[j] * (past + G->fractional_wl[j] * v);
    }
#else
    (void)G;
    (void)v;
#endif
    g->ahead = ahead;
    *xl = g->lag + u * g->eta_m;
    *xr = ahead;
}

/* the end of the step from V_n = v at (u1, v1) (engine `General::end_step`, `end_split_step`):
 * V's piece into every memory (split at an impact); returns the part of g's extras there not
 * in the step's known forcing, −κV_{n+1} + u1·η_m (relative to it after a split) */
TR_FN double tr_general_end(const TrGeneralPlan* G, TrGeneral* g, double v, double v1, double u1,
                            int* status) {
#if TR_MAX_FRACTIONAL > 0
    if (g->pending) {
        g->pending = 0;
        for (tr_u32 j = 0; j < G->fractional_terms; j++) {
            if (G->fractional_memory[j]) {
                if (g->memories[j].nsplits >= TR_MAX_SPLITS) {
                    *status = TR_TOO_MANY_SPLITS;
                    return 0.0;
                }
                tr_history_push(&G->memories[j], &g->memories[j], v, v1, &g->pending_split);
            }
        }
        g->lag = g->pending_ahead - g->pending_kappa * v1;
        return (g->lag - g->ahead) + u1 * g->eta_m;
    }
    for (tr_u32 j = 0; j < G->fractional_terms; j++) {
        if (G->fractional_memory[j]) {
            tr_history_push(&G->memories[j], &g->memories[j], v, v1, 0);
        }
    }
#else
    (void)v;
#endif
    (void)status;
    double now = -G->kappa * v1;
    g->lag = g->ahead + now;
    return now + u1 * g->eta_m;
}

/* ---- the fractional terms at an impact (engine `General::memories_at`, `split_memories`,
 * `restart_memories`, `impact::split_fractional`) ---- */

/* −Σ_j K_j m_j(t*−) at θ of the step from V_n = v: (known part, weight of V(t*) of the terms
 * with a memory, Σ K_j of the α = 1 terms) */
TR_FN void tr_memories_at(const TrGeneralPlan* G, const TrGeneral* g, double theta, double v,
                          double* known, double* weight, double* local) {
    double k = 0.0, w = 0.0, l = 0.0;
#if TR_MAX_FRACTIONAL > 0
    for (tr_u32 j = 0; j < G->fractional_terms; j++) {
        if (!G->fractional_memory[j]) {
            l += G->fractional_k[j];
        } else {
            double past, wj;
            tr_at_fraction(&G->memories[j], &g->memories[j], theta, v, &past, &wj);
            k -= G->fractional_k[j] * past;
            w += G->fractional_k[j] * wj;
        }
    }
#else
    (void)G;
    (void)g;
    (void)theta;
    (void)v;
#endif
    *known = k;
    *weight = w;
    *local = l;
}

/* split the memories at the impact (V jumps from V(t*) to V₊ at θ; restarted there when the
 * split keeps nothing before): the part of −Σ_j K_j m_{j,n+1} known now and κ_s */
TR_FN void tr_split_memories(const TrGeneralPlan* G, TrGeneral* g, double v,
                             const TrSplit* split, double* ahead, double* kappa) {
    double a = 0.0, kk = 0.0;
#if TR_MAX_FRACTIONAL > 0
    for (tr_u32 j = 0; j < G->fractional_terms; j++) {
        if (!G->fractional_memory[j]) {
            kk += G->fractional_k[j];
        } else {
            const TrPlan* M = &G->memories[j];
            TrHistory* H = &g->memories[j];
            if (!split->keep_before) {
                tr_history_restart(M, H);
            }
            double known, w;
            tr_current_split(M, v, split, &known, &w);
            a -= G->fractional_k[j] * (H->cached + known);
            kk += G->fractional_k[j] * w;
        }
    }
    g->pending = 1;
    g->pending_split = *split;
    g->pending_ahead = a;
    g->pending_kappa = kk;
#else
    (void)G;
    (void)g;
    (void)v;
    (void)split;
#endif
    *ahead = a;
    *kappa = kk;
}

/* the memories restart at the end of the step in progress (a sticking step with the memory
 * restarting) */
TR_FN void tr_restart_memories(const TrGeneralPlan* G, TrGeneral* g) {
#if TR_MAX_FRACTIONAL > 0
    for (tr_u32 j = 0; j < G->fractional_terms; j++) {
        if (G->fractional_memory[j]) {
            tr_history_restart(&G->memories[j], &g->memories[j]);
        }
    }
    g->pending = 0;
#else
    (void)G;
#endif
    g->lag = 0.0;
    g->ahead = 0.0;
}

/* g's split piece at an impact on the wall at δ of a path with fractional terms (−Σ K_j m_j(t*)
 * on both sides: continuous for α < 1, 0 after a restart, V₊ for α = 1), the memories split,
 * and the redone rest's κ_s, its known forcing's part, length and predictor weight */
TR_NOINLINE void tr_split_fractional(const TrPlan* P, const TrGeneralPlan* G, TrGeneral* g,
                                     double theta, double forcing, double lag, double weight,
                                     double local, double delta, double v_n, int keep_before,
                                     double v_at, double v_plus, TrSplit* split, double* ahead,
                                     double* kappa, double* len, double* pw) {
    double at = lag - (weight + local) * v_at;
    double kept = keep_before ? lag - weight * v_at : 0.0;
    double after = kept - local * v_plus;
    TrSplit memories;
    memories.theta = theta;
    memories.before = v_at;
    memories.after = v_plus;
    memories.keep_before = keep_before;
    tr_split_memories(G, g, v_n, &memories, ahead, kappa);
    split->theta = theta;
    split->before = tr_wall_drift(P, G, delta, v_at) + forcing + at;
    split->after = tr_wall_drift(P, G, delta, v_plus) + forcing + after;
    split->keep_before = keep_before;
    *len = (1.0 - theta) * P->h;
    *pw = tr_predictor_weight(*len, tr_general_a(P, G, delta, v_plus) - *kappa);
}

/* an impact on the wall at 0 inside the step whose free end is (u1, v1) (engine
 * `Stepper::locate` then `jump_general`): its split of g and the step's end */
TR_NOINLINE void tr_general_impact(const TrPlan* P, const TrGeneralPlan* G, TrPath* s,
                                   TrGeneral* g, double gl, double el, double er, double* u1,
                                   double* v1, TrSplit* split) {
    double h = P->h;
    double theta = tr_hermite_root(s->u, s->v, *u1, *v1, h);
    double eta_star = el + theta * (er - el);
    double hs, ws;
    tr_at_fraction(P, &s->history, theta, gl, &hs, &ws);
    double forcing = tr_forcing(P, eta_star, s->side);
    forcing += tr_force_at(G, g, theta);
    int fractional = G->fractional_terms != 0;
    double lag = 0.0, weight = 0.0, local = 0.0;
    double v_at;
    if (fractional) {
        /* and −Σ K_j m_j(t*), affine in V(t*) */
        tr_memories_at(G, g, theta, s->v, &lag, &weight, &local);
        v_at = tr_wall_velocity(P, G, 0.0, s->base + hs, ws, forcing + lag, weight + local);
    } else {
        v_at = tr_wall_velocity(P, G, 0.0, s->base + hs, ws, forcing, 0.0);
    }
    double v_minus = v_at < 0.0 ? v_at : 0.0;
    double v_plus = -P->restitution * v_minus;
    s->impacts += 1;
    if (P->restart) {
        tr_history_restart(P, &s->history);
        s->base = v_plus;
    } else {
        s->base += v_plus - v_at;
    }
    if (fractional) {
        double ahead, kappa, len, pw, known_s, wr_s;
        tr_split_fractional(P, G, g, theta, forcing, lag, weight, local, 0.0, s->v, !P->restart,
                            v_at, v_plus, split, &ahead, &kappa, &len, &pw);
        tr_current_split(P, gl, split, &known_s, &wr_s);
        double known = s->base + s->history.cached + known_s;
        double fr = tr_forcing(P, er, s->side) + tr_force_now(G, g) + ahead;
        tr_general_advance(P, G, g, kappa, len, 0.0, v_plus, split->after, pw, known, wr_s, fr,
                           u1, v1);
        return;
    }
    split->theta = theta;
    split->before = tr_wall_drift(P, G, 0.0, v_at) + forcing;
    split->after = tr_wall_drift(P, G, 0.0, v_plus) + forcing;
    split->keep_before = !P->restart;
    double known_s, wr_s;
    tr_current_split(P, gl, split, &known_s, &wr_s);
    double known = s->base + s->history.cached + known_s;
    double hh = (1.0 - theta) * h;
    double fr = tr_forcing(P, er, s->side) + tr_force_now(G, g);
    double pw = tr_predictor_weight(hh, tr_general_a(P, G, 0.0, v_plus));
    tr_general_advance(P, G, g, G->kappa, hh, 0.0, v_plus, split->after, pw, known, wr_s, fr, u1,
                       v1);
}

/* ---- the model's walls (engine `stepper::walls`) ---- */

/* r(|V₋|) of wall i (engine `Restitution::at`) */
TR_FN double tr_restitution_at(const TrGeneralPlan* G, int i, double speed) {
    if (!G->wall_speed_dependent[i]) {
        return G->wall_r[i];
    }
    return G->wall_r_fast[i] +
           (G->wall_r[i] - G->wall_r_fast[i]) * tr_exp(-tr_fabs(speed) / G->wall_speed[i]);
}

/* the wall that u lies beyond: 0 the lower, 1 the upper, −1 none (engine `Walls::beyond`) */
TR_FN int tr_beyond(const TrGeneralPlan* G, double u) {
    if (G->wall_present[0] && u < G->wall_position[0]) {
        return 0;
    }
    if (G->wall_present[1] && u > G->wall_position[1]) {
        return 1;
    }
    return -1;
}

/* the wall that u sits on exactly, or −1 (engine `Walls::at`) */
TR_FN int tr_on_wall(const TrGeneralPlan* G, double u) {
    if (G->wall_present[0] && u == G->wall_position[0]) {
        return 0;
    }
    if (G->wall_present[1] && u == G->wall_position[1]) {
        return 1;
    }
    return -1;
}

/* the impact on wall `side` inside the step whose free end is (u1, v1): located, the jump by
 * its restitution law, the rest of the step redone from the wall (engine
 * `Stepper::impact_wall`) */
TR_NOINLINE void tr_wall_impact(const TrPlan* P, const TrGeneralPlan* G, TrPath* s,
                                TrGeneral* g, int side, double gl, double el, double er,
                                double fr, double* u1, double* v1, TrSplit* split) {
    double h = P->h;
    double delta = G->wall_position[side];
    double theta = tr_hermite_root(s->u - delta, s->v, *u1 - delta, *v1, h);
    double eta_star = el + theta * (er - el);
    double hs, ws;
    tr_at_fraction(P, &s->history, theta, gl, &hs, &ws);
    /* the forcing at the instant (noise, harmonic and δ·η_m) and the wall's force −k(δ) */
    double forcing = tr_forcing(P, eta_star, s->side) + tr_force_at(G, g, theta);
    if (G->multiplicative) {
        forcing = forcing + (delta != 0.0 ? delta * g->eta_m : 0.0);
    }
    double at_wall = forcing - tr_restoring(P, G, delta);
    int fractional = G->fractional_terms != 0;
    double lag = 0.0, weight = 0.0, local = 0.0;
    double v_at;
    if (fractional) {
        /* and the fractional terms' −Σ K_j m_j(t*), affine in V(t*) */
        tr_memories_at(G, g, theta, s->v, &lag, &weight, &local);
        v_at = tr_wall_velocity(P, G, delta, s->base + hs, ws, at_wall + lag, weight + local);
    } else {
        v_at = tr_wall_velocity(P, G, delta, s->base + hs, ws, at_wall, 0.0);
    }
    /* at a grazing impact the scheme's V(t*−) may point away from the wall: then V₋ = 0 */
    double v_minus;
    if (side == 0) {
        v_minus = v_at < 0.0 ? v_at : 0.0;
    } else {
        v_minus = v_at > 0.0 ? v_at : 0.0;
    }
    double v_plus = -tr_restitution_at(G, side, tr_fabs(v_minus)) * v_minus;
    if (fractional) {
        /* engine `Stepper::impact_wall_fractional` */
        s->impacts += 1;
        if (P->restart) {
            tr_history_restart(P, &s->history);
            s->base = v_plus;
        } else {
            s->base += v_plus - v_at;
        }
        double ahead, kappa, len, pw, known_s, wr_s;
        tr_split_fractional(P, G, g, theta, forcing, lag, weight, local, delta, s->v,
                            !P->restart, v_at, v_plus, split, &ahead, &kappa, &len, &pw);
        tr_current_split(P, gl, split, &known_s, &wr_s);
        double known = s->base + s->history.cached + known_s;
        double fr_s = tr_forcing(P, er, s->side) + tr_force_now(G, g) + ahead;
        tr_general_advance(P, G, g, kappa, len, delta, v_plus, split->after, pw, known, wr_s,
                           fr_s, u1, v1);
        return;
    }
    split->theta = theta;
    split->before = tr_wall_drift(P, G, delta, v_at) + forcing;
    split->after = tr_wall_drift(P, G, delta, v_plus) + forcing;
    split->keep_before = !P->restart;
    double pw = tr_predictor_weight((1.0 - theta) * h, tr_general_a(P, G, delta, v_plus));
    s->impacts += 1;
    if (P->restart) {
        tr_history_restart(P, &s->history);
        s->base = v_plus;
    } else {
        s->base += v_plus - v_at;
    }
    double known_s, wr_s;
    tr_current_split(P, gl, split, &known_s, &wr_s);
    double known = s->base + s->history.cached + known_s;
    tr_general_advance(P, G, g, G->kappa, (1.0 - theta) * h, delta, v_plus, split->after, pw,
                       known, wr_s, fr, u1, v1);
}

/* the end of a General step from (u, v) at (u1, v1) after its events (engine `end_general`,
 * the tail of `step_general` at the wall at 0 and `end_wall_step`): the blow-up check, the node,
 * the fractional terms' pieces and U·η_m at the end, g's piece pushed (`push`; `split` at an
 * impact), the state. Without those terms the engine's step at the wall at 0 adds their absent
 * part as 0.0 and its walls' step leaves it out (`zero_extra` 1 or 0): the two forms differ only
 * in the sign of a zero, kept so that the bits are the engine's. */
TR_FN int tr_general_finish(const TrPlan* P, const TrGeneralPlan* G, TrPath* s, TrGeneral* g,
                            double u, double v, double gl, double fr, double u1, double v1,
                            int push, const TrSplit* split, int zero_extra) {
    if (tr_count_step(P, s, u, v, u1, v1) != TR_OK) {
        return TR_BLOW_UP;
    }
    tr_general_node(P, G, P->h, u1, v1, &s->drift, &s->pw);
    double right;
    if (G->multiplicative || G->fractional_terms) {
        /* a step that sticks with the memory restarting pushes nothing: the fractional
         * memories restart too */
        double extra = 0.0;
        int status = TR_OK;
        if (!push && G->fractional_terms) {
            tr_restart_memories(G, g);
        } else {
            extra = tr_general_end(G, g, v, v1, u1, &status);
        }
        if (status != TR_OK) {
            return status;
        }
        right = s->drift + fr + extra;
    } else if (zero_extra) {
        right = s->drift + fr + 0.0;
    } else {
        right = s->drift + fr;
    }
    if (push) {
        if (split && s->history.nsplits >= TR_MAX_SPLITS) {
            return TR_TOO_MANY_SPLITS;
        }
        tr_history_push(P, &s->history, gl, right, split);
    }
    s->u = u1;
    s->v = v1;
    return TR_OK;
}

/* the events of a step with the model's walls whose free end is (u1, v1), and its end
 * (engine `Stepper::step_walls`, `pressed`, `beyond_again`, `end_wall_step`) */
TR_NOINLINE int tr_walls_end(const TrPlan* P, const TrGeneralPlan* G, TrPath* s, TrGeneral* g,
                             double u, double v, double gl, double el, double er, double fr,
                             double u1, double v1) {
    TrSplit split;
    int has_split = 0;
    int push = 1;
    /* still pressed against the wall it is stuck on (n(U₁ − δ) ≤ 0)? */
    int on = tr_on_wall(G, s->u);
    int pressed = 0;
    double delta = 0.0;
    if (on >= 0 && s->stuck) {
        delta = G->wall_position[on];
        double normal = on == 0 ? 1.0 : -1.0;
        pressed = normal * (u1 - delta) <= 0.0;
    }
    if (!pressed) {
        s->stuck = 0;
    }
    if (pressed) {
        push = tr_stick(P, s, v1);
        u1 = delta;
        v1 = 0.0;
    } else {
        int side = tr_beyond(G, u1);
        if (side >= 0) {
            tr_wall_impact(P, G, s, g, side, gl, el, er, fr, &u1, &v1, &split);
            has_split = 1;
            int again = tr_beyond(G, u1);
            if (again == side) {
                /* the next impact would come within this step: stick */
                push = tr_stick(P, s, v1);
                u1 = G->wall_position[side];
                v1 = 0.0;
                s->stuck = 1;
            } else if (again >= 0) {
                /* the step meets both walls: the engine refuses Δt */
                return TR_TWO_WALLS;
            }
        }
    }
    return tr_general_finish(P, G, s, g, u, v, gl, fr, u1, v1, push, has_split ? &split : 0, 0);
}

/* one step Δt of the General kernel (engine `Stepper::step_general` with `begin_general`,
 * `end_events` and `end_general`, or `step_walls`); returns TR_OK or why the path stops */
TR_FN int tr_step_general(const TrPlan* P, const TrGeneralPlan* G, TrPath* s, TrGeneral* g,
                          const double* zx, const double* zf) {
    double el, er;
    tr_noise_step(&s->noise, &s->rng, zx, zf, &el, &er);
    double fl, fh;
    tr_phase_forces(G, g, &fl, &fh);
    double u = s->u, v = s->v;
    double gl = s->drift + tr_forcing(P, el, s->side) + fl;
    double fr = tr_forcing(P, er, s->side) + fh;
    int extras = G->multiplicative != 0 || G->fractional_terms != 0;
    if (extras) {
        /* −Σ K_j m_j and U·η_m; η_m takes the additive noise as it enters g, side·η_a */
        double xl, xr;
        tr_general_begin(G, g, u, v, s->side * el, zx, zf, &xl, &xr);
        gl += xl;
        fr += xr;
    }
    double known = s->base + s->history.cached + P->wl0 * gl;
    double u1, v1;
    tr_general_advance(P, G, g, G->kappa, P->h, u, v, gl, s->pw, known, P->wr0, fr, &u1, &v1);
    if (G->walls) {
        return tr_walls_end(P, G, s, g, u, v, gl, el, er, fr, u1, v1);
    }
    /* the events at the paper's wall at 0 */
    TrSplit split;
    int has_split = 0;
    int push = 1;
    if (P->wall && s->stuck) {
        if (u1 <= 0.0) {
            push = tr_stick(P, s, v1);
            u1 = 0.0;
            v1 = 0.0;
        } else {
            s->stuck = 0;
        }
    } else if (P->wall && u1 < 0.0) {
        tr_general_impact(P, G, s, g, gl, el, er, &u1, &v1, &split);
        has_split = 1;
        if (u1 < 0.0) {
            push = tr_stick(P, s, v1);
            u1 = 0.0;
            v1 = 0.0;
            s->stuck = 1;
        }
    }
    return tr_general_finish(P, G, s, g, u, v, gl, fr, u1, v1, push, has_split ? &split : 0, 1);
}

#endif
