/* One path's predictor–corrector step: the engine's `Stepper::step` for the paper's family (the
 * `Affine` kernel: Eq. 1, 5, 9; the wall at U = 0 with impacts and sticking, or the Zhuravlev
 * crossing), the same expressions in the same order (engine `stepper::{mod, affine, impact}`).
 * Method and reference: the engine's `stepper` module docs (the linearly implicit PECE step of
 * Diethelm–Ford–Freed with the product-trapezoidal weights; impacts located on the Hermite
 * interpolant, the rest of the step redone). */
#ifndef TR_STEP_H
#define TR_STEP_H
#include "memory.h"
#include "noise.h"

/* what ended a path early */
#define TR_OK 0
#define TR_BLOW_UP 1
#define TR_TOO_MANY_SPLITS 2
#define TR_TWO_WALLS 3

typedef struct {
    double u, v, drift, pw, side, base;
    int stuck;
    tr_u64 steps, impacts, sticking_steps;
    TrHistory history;
    TrRng rng;
    TrNoise noise;
    /* the blow-up's report: the state before the failing step */
    double from_u, from_v;
} TrPath;

TR_FN double tr_damping(const TrPlan* P, double u) {
    double x = u * u;
    const double* c = P->damping;
    if (!P->damping_long) {
        double x2 = x * x;
        double x4 = x2 * x2;
        double p01 = c[0] + c[1] * x;
        double p23 = c[2] + c[3] * x;
        double p45 = c[4] + c[5] * x;
        double p67 = c[6] + c[7] * x;
        return (p01 + p23 * x2) + (p45 + p67 * x2) * x4;
    }
    double acc = 0.0;
    for (int k = (int)P->damping_terms - 1; k >= 0; k--) {
        acc = acc * x + c[k];
    }
    return acc;
}

TR_FN double tr_forcing(const TrPlan* P, double eta, double side) { return P->gain * side * eta; }

TR_FN double tr_predictor_weight(double len, double a) {
    return 0.5 * len * len / (1.0 + len * tr_fabs(a));
}

/* one pass of the corrector with U frozen at `up`; returns V and U at the end */
TR_FN void tr_pass(const TrPlan* P, double len, double u, double v, double g0, double up,
                   double known, double w, double fr, double* u1, double* v1) {
    double a = tr_damping(P, up);
    double inv = 1.0 / (1.0 - w * a);
    double z = 2.0 * w * a;
    double lim = 1.0 / (1.0 + z * z * (1.0 / 12.0));
    double vv = (known + w * (fr - P->omega2 * up)) * inv;
    double gr = a * vv - P->omega2 * up + fr;
    *u1 = u + 0.5 * len * (v + vv) + len * len * (1.0 / 12.0) * lim * (g0 - gr);
    *v1 = vv;
}

TR_FN void tr_advance(const TrPlan* P, double len, double u, double v, double g0, double pw,
                      double known, double w, double fr, double* u1, double* v1) {
    double up1, vp1;
    tr_pass(P, len, u, v, g0, u + len * v + pw * g0, known, w, fr, &up1, &vp1);
    tr_pass(P, len, u, v, g0, up1, known, w, fr, u1, v1);
}

/* the crossing θ of U = 0 on the cubic Hermite interpolant (engine `impact::hermite_root`) */
TR_NOINLINE double tr_hermite_root(double u0, double v0, double u1, double v1, double h) {
    double hv0 = h * v0, hv1 = h * v1;
    double a = 0.0, b = 1.0;
    int fa_pos = u0 > 0.0 || (u0 == 0.0 && u1 < 0.0);
    double secant = u0 != u1 ? u0 / (u0 - u1) : 0.5;
    double t = secant > 0.0 && secant < 1.0 ? secant : 0.5;
    for (int it = 0; it < 100; it++) {
        double t2 = t * t;
        double t3 = t2 * t;
        double ft = (2.0 * t3 - 3.0 * t2 + 1.0) * u0 + (t3 - 2.0 * t2 + t) * hv0 +
                    (-2.0 * t3 + 3.0 * t2) * u1 + (t3 - t2) * hv1;
        if (ft == 0.0) {
            return t;
        }
        if ((ft > 0.0) == fa_pos) {
            a = t;
        } else {
            b = t;
        }
        double d = (6.0 * t2 - 6.0 * t) * (u0 - u1) + (3.0 * t2 - 4.0 * t + 1.0) * hv0 +
                   (3.0 * t2 - 2.0 * t) * hv1;
        double next = t - ft / d;
        if (!(next > a && next < b)) {
            next = 0.5 * (a + b);
        }
        int done = tr_fabs(next - t) <= 1e-15 || b - a <= 1e-15;
        t = next;
        if (done) {
            break;
        }
    }
    return t;
}

TR_FN void tr_path_new(const TrPlan* P, const TrNoise* noise, TrPath* s, double u0, double v0,
                       tr_u64 seed, tr_u64 path, const double* zx, const double* zf) {
    tr_history_new(&s->history);
    tr_rng_new(&s->rng, seed, path);
    s->noise = *noise;
    tr_noise_start(&s->noise, &s->rng, zx, zf);
    s->u = u0;
    s->v = v0;
    double a = tr_damping(P, u0);
    s->drift = a * v0 - P->omega2 * u0;
    s->pw = tr_predictor_weight(P->h, a);
    s->side = u0 < 0.0 ? -1.0 : 1.0;
    s->base = v0;
    s->stuck = 0;
    s->steps = 0;
    s->impacts = 0;
    s->sticking_steps = 0;
    s->from_u = 0.0;
    s->from_v = 0.0;
}

/* the wall holds the oscillator at rest (engine `Stepper::stick`); returns whether the step's
 * piece still enters the memory */
TR_FN int tr_stick(const TrPlan* P, TrPath* s, double v1) {
    s->sticking_steps += 1;
    if (P->restart) {
        tr_history_restart(P, &s->history);
        s->base = 0.0;
        return 0;
    }
    s->base -= v1;
    return 1;
}

/* an impact inside the step whose free end is (u1, v1): its split of g and the step's end
 * (engine `Stepper::impact`: `locate` then `jump`) */
TR_NOINLINE void tr_impact(const TrPlan* P, TrPath* s, double gl, double el, double er,
                           double* u1, double* v1, TrSplit* split) {
    double h = P->h;
    double theta = tr_hermite_root(s->u, s->v, *u1, *v1, h);
    double eta_star = el + theta * (er - el);
    double a0 = tr_damping(P, 0.0);
    double hs, ws;
    tr_at_fraction(P, &s->history, theta, gl, &hs, &ws);
    double forcing = tr_forcing(P, eta_star, s->side);
    double v_at = (s->base + hs + ws * forcing) / (1.0 - ws * a0);
    double v_minus, v_plus, new_side;
    if (P->crossing) {
        v_minus = v_at;
        v_plus = P->restitution * v_at;
        new_side = -s->side;
    } else {
        v_minus = v_at < 0.0 ? v_at : 0.0;
        v_plus = -P->restitution * v_minus;
        new_side = s->side;
    }
    (void)v_minus;
    s->impacts += 1;
    s->side = new_side;
    double after_forcing = tr_forcing(P, eta_star, new_side);
    split->theta = theta;
    split->before = a0 * v_at + forcing;
    split->after = a0 * v_plus + after_forcing;
    split->keep_before = !P->restart;
    if (P->restart) {
        tr_history_restart(P, &s->history);
        s->base = v_plus;
    } else {
        s->base += v_plus - v_at;
    }
    double known_s, wr_s;
    tr_current_split(P, gl, split, &known_s, &wr_s);
    double known = s->base + s->history.cached + known_s;
    double hh = (1.0 - theta) * h;
    tr_advance(P, hh, 0.0, v_plus, split->after, tr_predictor_weight(hh, a0), known, wr_s,
               tr_forcing(P, er, new_side), u1, v1);
}

/* the end of a step from (u, v) at (u1, v1), counted (engine `check_blow_up`): beyond the
 * blow-up bound, or not finite, the path stops with the step's start kept for the report */
TR_FN int tr_count_step(const TrPlan* P, TrPath* s, double u, double v, double u1, double v1) {
    s->steps += 1;
    if (tr_fabs(u1) <= P->blow_up && tr_fabs(v1) <= P->blow_up) {
        return TR_OK;
    }
    s->from_u = u;
    s->from_v = v;
    s->u = u1;
    s->v = v1;
    return TR_BLOW_UP;
}

/* one step Δt (engine `Stepper::step`); returns TR_OK or why the path stops */
TR_FN int tr_step(const TrPlan* P, TrPath* s, const double* zx, const double* zf) {
    double el, er;
    tr_noise_step(&s->noise, &s->rng, zx, zf, &el, &er);
    double u = s->u, v = s->v;
    double gl = s->drift + tr_forcing(P, el, s->side);
    double known = s->base + s->history.cached + P->wl0 * gl;
    double fr = tr_forcing(P, er, s->side);
    double u1, v1;
    tr_advance(P, P->h, u, v, gl, s->pw, known, P->wr0, fr, &u1, &v1);
    /* the events (engine `end_events`) */
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
    } else if ((P->wall && u1 < 0.0) || (P->crossing && u * u1 < 0.0)) {
        tr_impact(P, s, gl, el, er, &u1, &v1, &split);
        has_split = 1;
        if (P->wall && u1 < 0.0) {
            push = tr_stick(P, s, v1);
            u1 = 0.0;
            v1 = 0.0;
            s->stuck = 1;
        }
    }
    if (tr_count_step(P, s, u, v, u1, v1) != TR_OK) {
        return TR_BLOW_UP;
    }
    if (P->crossing && u1 != 0.0) {
        s->side = u1 > 0.0 ? 1.0 : -1.0;
    }
    /* the node (engine `set_node`) and the piece of g (engine `complete`) */
    double a1 = tr_damping(P, u1);
    s->drift = a1 * v1 - P->omega2 * u1;
    s->pw = tr_predictor_weight(P->h, a1);
    if (push) {
        if (has_split && s->history.nsplits >= TR_MAX_SPLITS) {
            return TR_TOO_MANY_SPLITS;
        }
        double right = s->drift + tr_forcing(P, er, s->side);
        tr_history_push(P, &s->history, gl, right, has_split ? &split : 0);
    }
    s->u = u1;
    s->v = v1;
    return TR_OK;
}

#endif
