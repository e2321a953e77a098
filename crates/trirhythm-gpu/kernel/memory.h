/* The memory J^λ g of one path: the engine's `engine::memory::History` with the
 * sum-of-exponentials kernel (exact window of `cap` pieces, SOE modes, lumped moments, impact
 * splits), the same expressions in the same order.
 *
 * Differences of form only: the engine keeps a table of weights per live split
 * (`split_weight_table`); here the weights are recomputed where they are used — the same
 * function of the same numbers, so the same bits — to keep a path's state small on the GPU. */
#ifndef TR_MEMORY_H
#define TR_MEMORY_H
#include "plan.h"

typedef struct {
    double theta, before, after;
    int keep_before;
} TrSplit;

typedef struct {
    /* the window's ring, doubled (engine `memory::window::Window`): pairs 1 + 2·cap */
    double pairs[2 * (1 + 2 * TR_MAX_CAP)];
    tr_u32 head, len;
    tr_u64 pushed;
    double y[TR_MAX_MODES];
    double moments[4];
    double cached;
    tr_u32 nsplits;
    tr_u64 split_seq[TR_MAX_SPLITS];
    TrSplit splits[TR_MAX_SPLITS];
} TrHistory;

/* ---- interval weights (engine `kernel::IntervalWeights`) ---- */

TR_FN double tr_power(const TrPlan* P, double u) {
    if (u >= 1.0 && u < 16.0 && u - trunc(u) == 0.0) {
        return P->iw_whole[(int)u];
    }
    return tr_pow(u, P->lambda);
}

TR_FN void tr_weights_of(const TrPlan* P, double ua, double ub, double* wa, double* wb) {
    double lambda = P->lambda;
    double d = ub - ua;
    if (d <= 0.0) {
        *wa = 0.0;
        *wb = 0.0;
        return;
    }
    double c = 0.5 * (ua + ub);
    double eps = 0.5 * d / c;
    if (ua > 0.0 && eps < 0.1) {
        double e2 = eps * eps;
        double s0 = 0.0, s1 = 0.0;
        for (int k = 11; k >= 0; k--) {
            s0 = s0 * e2 + P->iw_even[k];
        }
        for (int k = 11; k >= 0; k--) {
            s1 = s1 * e2 + P->iw_odd[k];
        }
        s1 = eps * s1;
        double f = 0.5 * d * tr_pow(c, lambda - 1.0);
        *wa = 0.5 * f * (s0 - s1);
        *wb = 0.5 * f * (s0 + s1);
    } else {
        double pb = tr_power(P, ub);
        double pa = ua == 0.0 ? 0.0 : tr_power(P, ua);
        double m0 = (pb - pa) / lambda;
        double m1 = (ub * pb - ua * pa) / (lambda + 1.0);
        *wa = (ub * m0 - m1) / d;
        *wb = (m1 - ua * m0) / d;
    }
}

/* φ and ψ of z with e^{−z} given (engine `kernel::phi_psi_given`) */
TR_FN void tr_phi_psi_given(const TrPlan* P, double z, double e, double* phi, double* psi) {
    if (z < 0.5) {
        double x = -z;
        int terms = z < 1e-3 ? 6 : (z < 0.05 ? 10 : 17);
        double a = 0.0, b = 0.0;
        for (int k = terms - 1; k >= 0; k--) {
            a = a * x + P->phi_series[k];
        }
        for (int k = terms - 1; k >= 0; k--) {
            b = b * x + P->psi_series[k];
        }
        *phi = a;
        *psi = b;
    } else {
        *phi = (1.0 - e) / z;
        *psi = (1.0 - e * (1.0 + z)) / (z * z);
    }
}

/* ∫ of one piece at p steps back (engine `memory::piece_integral`; no point mass here) */
TR_FN double tr_piece_integral(const TrPlan* P, double left, double right, const TrSplit* s,
                               double p) {
    double wa, wb;
    if (!s) {
        tr_weights_of(P, p, p + 1.0, &wa, &wb);
        return wa * right + wb * left;
    }
    double mid = p + 1.0 - s->theta;
    tr_weights_of(P, p, mid, &wa, &wb);
    double v = wa * right + wb * s->after;
    if (s->keep_before) {
        tr_weights_of(P, mid, p + 1.0, &wa, &wb);
        v += wa * s->before + wb * left;
    }
    return v;
}

/* ---- moments of the lumped slow part (engine `memory::moments`) ---- */

TR_FN void tr_advance_moments(double* m, int flat, double len, double l, double r) {
    if (!flat) {
        double m0 = m[0], m1 = m[1], m2 = m[2], m3 = m[3];
        double h = len, h2 = len * len;
        double h3 = h2 * h;
        m[3] = ((m3 + 3.0 * h * m2) + (3.0 * h2 * m1 + h3 * m0)) + h3 * h * (l / 5.0 + r / 20.0);
        m[2] = (m2 + 2.0 * h * m1) + (h2 * m0 + h3 * (l / 4.0 + r / 12.0));
        m[1] = (m1 + h * m0) + h2 * (l / 3.0 + r / 6.0);
    }
    m[0] += 0.5 * len * (l + r);
}

TR_FN void tr_moment_step(const TrPlan* P, double* m, double l, double r) {
    const double* s = P->shift;
    const double* q = P->piece;
    double m0 = m[0], m1 = m[1], m2 = m[2], m3 = m[3];
    double n0 = m0 + s[6] * (l + r);
    if (P->flat) {
        m[0] = n0;
        return;
    }
    m[0] = n0;
    m[1] = (m1 + s[5] * m0) + (q[4] * l + q[5] * r);
    m[2] = (m2 + s[3] * m1) + (s[4] * m0 + (q[2] * l + q[3] * r));
    m[3] = ((m3 + s[0] * m2) + (s[1] * m1 + s[2] * m0)) + (q[0] * l + q[1] * r);
}

TR_FN double tr_dot_moments(const double* w, const double* m) {
    return (w[0] * m[0] + w[1] * m[1]) + (w[2] * m[2] + w[3] * m[3]);
}

TR_FN void tr_lumped_weights(const double* p, double b, double* w) {
    w[0] = p[0] + b * (p[1] + b * (p[2] + b * p[3]));
    w[1] = p[1] + b * (2.0 * p[2] + 3.0 * b * p[3]);
    w[2] = p[2] + 3.0 * b * p[3];
    w[3] = p[3];
}

TR_FN double tr_lumped_value(const TrPlan* P, const double* m) {
    if (P->flat) {
        return P->lumped[0] * m[0];
    }
    return tr_dot_moments(P->lumped_out, m);
}

/* ---- the window (engine `memory::window::Window`) ---- */

/* push a piece; returns 1 and the leaving piece when the window was full */
TR_FN int tr_window_push(const TrPlan* P, TrHistory* H, double left, double right, double* l0,
                         double* r0) {
    tr_u32 cap = P->cap;
    if (cap == 0) {
        *l0 = left;
        *r0 = right;
        return 1;
    }
    tr_u32 pos;
    int leaving = 0;
    if (H->len < cap) {
        H->len += 1;
        pos = H->len - 1;
    } else {
        tr_u32 h = H->head;
        H->head = h + 1 == cap ? 0 : h + 1;
        *l0 = H->pairs[2 * (1 + h)];
        *r0 = H->pairs[2 * (1 + h) + 1];
        pos = h;
        leaving = 1;
    }
    H->pairs[2 * (1 + pos)] = left;
    H->pairs[2 * (1 + pos) + 1] = right;
    H->pairs[2 * (1 + pos + cap)] = left;
    H->pairs[2 * (1 + pos + cap) + 1] = right;
    return leaving;
}

/* the held pieces: piece k (0 = oldest) is at pairs + 2·(1 + head + k) */
TR_FN const double* tr_held(const TrHistory* H) { return H->pairs + 2 * (1 + H->head); }

TR_FN double tr_dot4(const double* a, const double* b, tr_u32 n) {
    double acc[4] = {0.0, 0.0, 0.0, 0.0};
    tr_u32 whole = n - n % 4;
    for (tr_u32 k = 0; k < whole; k += 4) {
        for (int i = 0; i < 4; i++) {
            acc[i] += a[k + i] * b[k + i];
        }
    }
    for (tr_u32 i = 0; i < n % 4; i++) {
        acc[i] += a[whole + i] * b[whole + i];
    }
    return (acc[0] + acc[1]) + (acc[2] + acc[3]);
}

/* ---- SOE modes (engine `memory::modes`) ---- */

TR_FN double tr_advance_modes(const TrPlan* P, TrHistory* H, double l, double r) {
    double acc[2][4] = {{0.0, 0.0, 0.0, 0.0}, {0.0, 0.0, 0.0, 0.0}};
    tr_u32 blocks = P->modes / 4;
    for (tr_u32 k = 0; k < blocks; k++) {
        for (int i = 0; i < 4; i++) {
            tr_u32 j = 4 * k + i;
            double v = P->decay[j] * H->y[j] + (P->start[j] * l + P->end[j] * r);
            H->y[j] = v;
            acc[k % 2][i] += P->out[j] * v;
        }
    }
    double s[4];
    for (int i = 0; i < 4; i++) {
        s[i] = acc[0][i] + acc[1][i];
    }
    return (s[0] + s[1]) + (s[2] + s[3]);
}

TR_FN double tr_modes_dot(const TrPlan* P, const TrHistory* H) {
    double acc[4] = {0.0, 0.0, 0.0, 0.0};
    for (tr_u32 k = 0; k < P->modes / 4; k++) {
        for (int i = 0; i < 4; i++) {
            acc[i] += P->out[4 * k + i] * H->y[4 * k + i];
        }
    }
    return (acc[0] + acc[1]) + (acc[2] + acc[3]);
}

/* ---- the history ---- */

TR_FN void tr_history_new(TrHistory* H) {
    for (int k = 0; k < 2 * (1 + 2 * TR_MAX_CAP); k++) {
        H->pairs[k] = 0.0;
    }
    H->head = 0;
    H->len = 0;
    H->pushed = 0;
    for (int k = 0; k < TR_MAX_MODES; k++) {
        H->y[k] = 0.0;
    }
    for (int k = 0; k < 4; k++) {
        H->moments[k] = 0.0;
    }
    H->cached = 0.0;
    H->nsplits = 0;
}

TR_FN void tr_history_restart(const TrPlan* P, TrHistory* H) {
    H->head = 0;
    H->len = 0;
    H->nsplits = 0;
    for (tr_u32 k = 0; k < P->modes; k++) {
        H->y[k] = 0.0;
    }
    for (int k = 0; k < 4; k++) {
        H->moments[k] = 0.0;
    }
    H->cached = 0.0;
}

TR_FN void tr_remove_first_split(TrHistory* H) {
    for (tr_u32 k = 1; k < H->nsplits; k++) {
        H->split_seq[k - 1] = H->split_seq[k];
        H->splits[k - 1] = H->splits[k];
    }
    H->nsplits -= 1;
}

TR_FN int tr_split_leaves(const TrPlan* P, const TrHistory* H) {
    if (H->nsplits == 0) {
        return 0;
    }
    return H->len == P->cap && H->split_seq[0] + P->cap == H->pushed;
}

/* Σ over live splits of the split's weights minus the plain ones (engine
 * `held_split_corrections`, its table entry recomputed: `split_weight_table`) */
TR_NOINLINE double tr_held_split_corrections(const TrPlan* P, const TrHistory* H) {
    const double* held = tr_held(H);
    tr_u64 first = H->pushed - H->len;
    double acc = 0.0;
    for (tr_u32 i = 0; i < H->nsplits; i++) {
        const TrSplit* s = &H->splits[i];
        tr_u64 seq = H->split_seq[i];
        double l = held[2 * (seq - first)], r = held[2 * (seq - first) + 1];
        tr_u32 p = (tr_u32)(H->pushed - seq);
        double pf = (double)p;
        double mid = pf + 1.0 - s->theta;
        double wa, wb, wa2 = 0.0, wb2 = 0.0;
        tr_weights_of(P, pf, mid, &wa, &wb);
        if (s->keep_before) {
            tr_weights_of(P, mid, pf + 1.0, &wa2, &wb2);
        }
        double k = P->scale;
        double c0 = k * (wb2 - P->wl[p]), c1 = k * wa2, c2 = k * wb, c3 = k * (wa - P->wr[p]);
        acc += ((c0 * l + c1 * s->before) + c2 * s->after) + c3 * r;
    }
    return acc;
}

/* the plain sum of the held pieces (an iterator's sum: from −0.0) */
TR_FN double tr_plain_sum(const TrPlan* P, const TrHistory* H) {
    const double* held = tr_held(H);
    tr_u32 n = H->len;
    double sum = -0.0;
    for (tr_u32 k = 0; k < n; k++) {
        sum = sum + (P->wl[n - k] * held[2 * k] + P->wr[n - k] * held[2 * k + 1]);
    }
    return sum;
}

TR_NOINLINE double tr_split_corrections(const TrPlan* P, const TrHistory* H) {
    if (H->nsplits == 0) {
        return 0.0;
    }
    const double* held = tr_held(H);
    tr_u32 len = H->len;
    tr_u64 first = H->pushed - len;
    double acc = 0.0;
    for (tr_u32 i = 0; i < H->nsplits; i++) {
        tr_u32 k = (tr_u32)(H->split_seq[i] - first);
        tr_u32 p = len - k;
        double left = held[2 * k], right = held[2 * k + 1];
        acc += tr_piece_integral(P, left, right, &H->splits[i], (double)p) -
               (P->wl[p] * left + P->wr[p] * right);
    }
    return acc;
}

/* a piece leaving the window into the modes and moments (engine `absorb`) */
TR_NOINLINE double tr_absorb(const TrPlan* P, TrHistory* H, double left, double right,
                             const TrSplit* s) {
    double h = P->h;
    if (!s) {
        double modes = P->modes == 0 ? 0.0 : tr_advance_modes(P, H, left, right);
        tr_advance_moments(H->moments, P->flat, h, left, right);
        return modes;
    }
    double l1 = s->theta * h;
    double l2 = h - l1;
    for (tr_u32 j = 0; j < P->n_exp; j++) {
        double rate = P->rates[j];
        double e1 = tr_exp(-rate * l1);
        double e2 = P->decay[j] / e1;
        double phi, psi;
        tr_phi_psi_given(P, rate * l1, e1, &phi, &psi);
        double v = 0.0;
        if (s->keep_before) {
            v = e1 * H->y[j] + l1 * psi * left + l1 * (phi - psi) * s->before;
        }
        tr_phi_psi_given(P, rate * l2, e2, &phi, &psi);
        v = e2 * v + l2 * psi * s->after + l2 * (phi - psi) * right;
        H->y[j] = v;
    }
    if (s->keep_before) {
        tr_advance_moments(H->moments, P->flat, l1, left, s->before);
    } else {
        for (int k = 0; k < 4; k++) {
            H->moments[k] = 0.0;
        }
    }
    tr_advance_moments(H->moments, P->flat, l2, s->after, right);
    return tr_modes_dot(P, H);
}

TR_NOINLINE void tr_push_general(const TrPlan* P, TrHistory* H, double left, double right,
                                 const TrSplit* split) {
    tr_u64 seq = H->pushed;
    H->pushed += 1;
    if (split) {
        H->split_seq[H->nsplits] = seq;
        H->splits[H->nsplits] = *split;
        H->nsplits += 1;
    }
    double l0 = 0.0, r0 = 0.0;
    int leaving = tr_window_push(P, H, left, right, &l0, &r0);
    double modes = 0.0;
    if (leaving) {
        tr_u64 gone = seq - H->len;
        TrSplit leaving_split;
        const TrSplit* sp = 0;
        if (H->nsplits > 0 && H->split_seq[0] == gone) {
            leaving_split = H->splits[0];
            sp = &leaving_split;
            tr_remove_first_split(H);
        }
        modes = tr_absorb(P, H, l0, r0, sp);
    }
    modes += tr_lumped_value(P, H->moments);
    double local = tr_plain_sum(P, H) + tr_split_corrections(P, H);
    H->cached = modes + P->scale * local;
}

/* the engine's `History::push` */
TR_FN void tr_history_push(const TrPlan* P, TrHistory* H, double left, double right,
                           const TrSplit* split) {
    if (P->cap == 0 && !split && P->flat) {
        H->pushed += 1;
        H->moments[0] += 0.5 * P->h * (left + right);
        H->cached = P->lumped[0] * H->moments[0];
        return;
    }
    if (P->cap > 0 && H->len + 1 >= P->cap && !split && !tr_split_leaves(P, H)) {
        H->pushed += 1;
        double l0 = 0.0, r0 = 0.0;
        int leaving = tr_window_push(P, H, left, right, &l0, &r0);
        double off = 0.0;
        if (leaving) {
            if (P->modes > 0) {
                off = tr_advance_modes(P, H, l0, r0);
            }
            tr_moment_step(P, H->moments, l0, r0);
        }
        off += tr_lumped_value(P, H->moments);
        /* the older pieces' run ends at 2·(head + cap) in the flattened pairs */
        tr_u32 end = 2 * (H->head + P->cap);
        off += tr_dot4(H->pairs + end - P->older_len, P->older, P->older_len);
        H->cached = off + (P->newest[0] * left + P->newest[1] * right);
        if (H->nsplits > 0) {
            H->cached += tr_held_split_corrections(P, H);
        }
        return;
    }
    tr_push_general(P, H, left, right, split);
}

/* J^λ g at t_n + θΔt and the weight of g there (engine `History::at_fraction`) */
TR_NOINLINE void tr_at_fraction(const TrPlan* P, const TrHistory* H, double theta, double left,
                                double* value, double* weight) {
    double shift = 1.0 - theta;
    tr_u32 len = H->len;
    const double* held = tr_held(H);
    tr_u64 first = H->pushed - len;
    double sum = 0.0;
    for (tr_u32 k = 0; k < len; k++) {
        const TrSplit* s = 0;
        for (tr_u32 i = 0; i < H->nsplits; i++) {
            if (H->split_seq[i] == first + k) {
                s = &H->splits[i];
                break;
            }
        }
        sum += tr_piece_integral(P, held[2 * k], held[2 * k + 1], s, (double)(len - k) - shift);
    }
    double total = P->scale * sum;
    if (P->soe) {
        double back = ((double)(P->cap + 1) - shift) * P->h;
        for (tr_u32 j = 0; j < P->n_exp; j++) {
            total += P->weights[j] * tr_exp(-P->rates[j] * back) * H->y[j];
        }
        double w[4];
        tr_lumped_weights(P->lumped, back, w);
        total += tr_dot_moments(w, H->moments);
    }
    double wa, wb;
    tr_weights_of(P, 0.0, theta, &wa, &wb);
    *value = total + P->scale * wb * left;
    *weight = P->scale * wa;
}

/* the known part and the weight of g at the step's end after a split (engine `current_split`) */
TR_FN void tr_current_split(const TrPlan* P, double left, const TrSplit* s, double* known,
                            double* weight) {
    double mid = 1.0 - s->theta;
    double wa, wb;
    tr_weights_of(P, 0.0, mid, &wa, &wb);
    double k = wb * s->after;
    if (s->keep_before) {
        double wa2, wb2;
        tr_weights_of(P, mid, 1.0, &wa2, &wb2);
        k += wa2 * s->before + wb2 * left;
    }
    *known = P->scale * k;
    *weight = P->scale * wa;
}

#endif
