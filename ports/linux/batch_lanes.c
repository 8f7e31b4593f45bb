/*
 * The fast steps of several runs in SIMD lanes (batch_lanes.h).
 *
 * The lanes are GCC vector extensions (clang has them too) of BATCH_W
 * elements, the target's widest vector of floats for the flags this file
 * is built with (the Makefile builds it alone with the host's own
 * instruction set, BATCH_LANES_FLAGS): 16 with AVX-512, 8 with AVX, 4
 * otherwise (SSE2, NEON, or scalar code where the target has no vectors:
 * the compiler lowers the operations, which stay correct at any width).
 * Every lane operation is the scalar one, elementwise: IEEE single
 * precision without contraction (-ffp-contract=off, the build's flag), the
 * integers modulo 2^32 where the scalar code's values never leave their
 * range, so each lane has the bits of its scalar run.
 *
 * The step below is drive_rt_step()'s (drive_rt_step.h, as
 * drive_fast_run.c's rt_run() takes it), piece by piece (the float build's names; the fixed
 * build's are the _q twins):
 *   lane_duties()  pwm_rt_substep() / pwm_rt_sampled() (pwm_rt.h)
 *   lane_phase()   ps_fast_phase_f32(), then the motor's fast companion
 *                  i += (v_c - e) k_l and the frame sum of v_c
 *   lane_step()    ps_fast_begin_f32(), the two phases, ps_fast_end_f32()
 *                  and the frame sum of v_dc (power_stage_fast.h and
 *                  power_stage_nodes.h's clamps and counts)
 * The sub-step modulator's edges (a leg whose comparison changes sign
 * within the step, a few legs in a hundred) take pwm_rt_edge_duty() in
 * lanes (lane_edge_duty(): its quotient in double, the same integer),
 * after a test whether any lane has one.
 *
 * The fixed build's step is the same pieces in Q3.28 (lane_acc(),
 * lane_mac(), lane_hi(): power_stage_nodes.h's 64-bit sums modulo 2^64 and
 * their high words), with 64-bit lanes for the products and the frame sums;
 * its filter update clamps every lane and takes the shunt history from the
 * clamped values, which is ps_filter_update_q()'s result whether or not a
 * value left the range.
 */
#include "batch_lanes.h"

#include <string.h>

#include "models/drive/inverter/power_stage_fast.h"
#include "models/drive/pwm/pwm_rt.h"

bool batch_lane_ready(const drive_segment *d) { return d->rt_path && d->fast_now == NULL; }

void batch_lanes_attach(exec *e) {
    if (e->desk_run == NULL && e->drive.cfg.inverter == DRIVE_INVERTER_SWITCHING) {
        pwm_rt_frames(&e->drive.rt, 0u);
    }
}

#define BATCH_PASS_MAX 4096 /* executives per pass */

/*
 * What one run does in a pass: the work before its next tick's step (a
 * latch; exec_desk_tick_begin()), the steps that only step (ahead: that
 * tick's own, when its count has no event, and those after it), the next
 * event tick's step (tick) and its event; the steps in lanes when the run
 * is on the real-time path, else all of it through exec_desk_run(). At
 * the first tick of a split motor frame that fits, the whole frame
 * (exec_desk_frame_begin()): the release's work, the frame's steps, the
 * boundary's first half, so that a frame is one run of steps in the
 * lanes, not two (the two steps to the release and the rest).
 */
typedef struct {
    uint32_t ahead; /* exec_desk_ahead()'s steps, after the begin; a whole frame's steps */
    bool tick;      /* the event tick's step follows them (in the same lanes) */
    bool lane;      /* the steps go in lanes */
    bool whole;     /* a whole frame in lanes (exec_desk_frame_end() after the steps) */
    bool taken;     /* already in a group this pass */
} batch_plan;

void batch_step_all(exec *const *e, const uint32_t *most, size_t count) {
    static drive_segment *group[BATCH_PASS_MAX];
    static batch_plan plan[BATCH_PASS_MAX];
    for (size_t i0 = 0u; i0 < count; i0 += BATCH_PASS_MAX) {
        const size_t m = (count - i0 < BATCH_PASS_MAX) ? count - i0 : BATCH_PASS_MAX;
        exec *const *x = e + i0;
        for (size_t i = 0; i < m; i++) {
            batch_plan *p = &plan[i];
            const bool begin = x[i]->fast_gate == EXEC_GATE_BEGIN;
            /* A latch may leave the real-time path (a fault, a trip): tested after it. */
            p->lane = x[i]->desk_run == NULL && batch_lane_ready(&x[i]->drive) &&
                      exec_desk_tick_begin(x[i]) && batch_lane_ready(&x[i]->drive);
            p->whole = p->lane && exec_desk_frame_whole(x[i], begin, most[i0 + i]);
            if (p->whole) {
                /*
                 * The release's tasks cannot take the drive off the real-time path: it
                 * changes only at the latch (tested above) and at a slow
                 * boundary (drive_segment.c: rt_path_set()), and the frame's
                 * steps come before the next boundary.
                 */
                p->ahead = exec_desk_frame_begin(x[i]);
                p->tick = false;
            } else {
                p->ahead = p->lane ? exec_desk_ahead(x[i], most[i0 + i]) : 0u;
                p->tick = p->lane && p->ahead < most[i0 + i];
            }
            p->taken = false;
        }
        for (size_t i = 0; i < m; i++) {
            if (!plan[i].lane || plan[i].taken) {
                continue;
            }
            const uint32_t steps = plan[i].ahead + (plan[i].tick ? 1u : 0u);
            const drive_modulator mod = x[i]->drive.cfg.modulator;
            size_t n = 0u;
            for (size_t j = i; j < m; j++) {
                const batch_plan *q = &plan[j];
                if (q->lane && !q->taken && q->ahead + (q->tick ? 1u : 0u) == steps &&
                    x[j]->drive.cfg.modulator == mod) {
                    group[n++] = &x[j]->drive;
                    plan[j].taken = true;
                }
            }
            batch_fast_run(group, n, steps, mod == DRIVE_MODULATOR_SUBSTEP);
        }
        for (size_t i = 0; i < m; i++) {
            const batch_plan *p = &plan[i];
            if (p->whole) {
                exec_desk_frame_end(x[i], p->ahead);
                continue;
            }
            if (!p->lane) {
                /* Its tick begun or not (then nothing was done), exec_desk_run() goes on from there. */
                (void)exec_desk_run(x[i], most[i0 + i]);
                continue;
            }
            x[i]->fast_phase += p->ahead;
            if (p->tick) {
                exec_desk_tick_end(x[i]);
            }
        }
    }
}

#if defined(__AVX512F__)
#define BATCH_W 16
#define BATCH_ISA "avx512"
#elif defined(__AVX__)
#define BATCH_W 8
#define BATCH_ISA "avx"
#elif defined(__SSE2__)
#define BATCH_W 4
#define BATCH_ISA "sse2"
#elif defined(__ARM_NEON)
#define BATCH_W 4
#define BATCH_ISA "neon"
#else
#define BATCH_W 4
#define BATCH_ISA "generic"
#endif

/*
 * Vectors stepped side by side in one loop (-DBATCH_G=N): independent
 * chains through the runs' DC links. 1 by default: with 16 lanes of
 * AVX-512 the step is bound by its instructions, not by that chain (two
 * vectors side by side measured 20 % slower per run-step).
 */
#ifndef BATCH_G
#define BATCH_G 1
#endif

const unsigned batch_lanes = BATCH_W * BATCH_G;
const char batch_lanes_isa[] = BATCH_ISA;

typedef float vf __attribute__((vector_size(4 * BATCH_W)));
typedef int32_t vi __attribute__((vector_size(4 * BATCH_W)));
typedef uint32_t vu __attribute__((vector_size(4 * BATCH_W)));
typedef int64_t vl __attribute__((vector_size(8 * BATCH_W)));
typedef uint64_t vul __attribute__((vector_size(8 * BATCH_W)));

/* The build's values and frame sums in lanes (num_val, num_sum of drive_num_q.h / _f32.h). */
#if UUV_NUMERIC == UUV_NUMERIC_FIXED
typedef vi vs; /* Q3.28 */
typedef vl vsum;
#define DRIVE_BAT_E(d) ((d)->in.battery.e)
#define DRIVE_GAIN(d) ((d)->k32)
#else
typedef vf vs; /* [A], [V] */
typedef vf vsum;
#define DRIVE_BAT_E(d) ((d)->in.battery.e_v)
#define DRIVE_GAIN(d) ((d)->k_l)
#endif

/* The lanes' state: what rt_run() keeps in locals, one element per run. */
typedef struct {
    /* Modulator (pwm_rt). */
    vu ph_c, inc_c, den_sh;
    vi r[2], dr[2];
    vi s[3];
    /* Stage (power_stage_q / _f32): phases, DC link, inverter voltages, counts. */
    vs i_l[2], v_c[2], i_d[2], j_sh[2];
    vs v_dc, u[2], i_dc;
    vu sat;  /* the stage's count of clamps before the run (it stops at UINT32_MAX) */
    vu cnt;  /* the clamps in the run: at most 7 a step, added to sat at its end (lanes_count()) */
    /* Its coefficients and the battery companion (held over the run). */
    vs neg_eps_l, g_l2, neg_g_l, g_d, a_d, neg_a_d, k_node, neg_k_c;
    vs bat_e, bat_kg;
    /* The motor's fast companion (its gain: k_l, or k32 in the fixed build) and the frame sums. */
    vs i_fast[2], e[2], gain;
    vsum sum_v_cap[2], sum_v_dc;
} lanes;

/* A lane's element of a vector, to load and store one run. */
#define LANE(v, l) (((union { __typeof__(v) w; __typeof__((v)[0]) x[BATCH_W]; } *)(void *)&(v))->x[l])

static void lanes_load(lanes *L, unsigned l, const drive_segment *d) {
    const pwm_rt *rt = &d->rt;
    LANE(L->ph_c, l) = pwm_rt_phase(rt);
    LANE(L->inc_c, l) = rt->inc_c;
    LANE(L->den_sh, l) = rt->den_sh;
    for (int x = 0; x < 2; x++) {
        LANE(L->r[x], l) = pwm_rt_ref_now(rt, x);
        LANE(L->dr[x], l) = pwm_rt_slope(rt, x);
        LANE(L->i_l[x], l) = d->ps.ph[x].i_l;
        LANE(L->v_c[x], l) = d->ps.ph[x].v_c;
        LANE(L->i_d[x], l) = d->ps.ph[x].i_d;
        LANE(L->j_sh[x], l) = d->ps.ph[x].j_sh;
        LANE(L->u[x], l) = d->ps.u[x];
        LANE(L->i_fast[x], l) = d->i_fast[x];
        LANE(L->e[x], l) = d->e[x];
        LANE(L->sum_v_cap[x], l) = d->sums.v_cap[x];
    }
    for (int x = 0; x < 3; x++) {
        LANE(L->s[x], l) = d->s[x];
    }
    LANE(L->v_dc, l) = d->ps.v_dc;
    LANE(L->i_dc, l) = d->ps.i_dc;
    LANE(L->sat, l) = d->ps.sat_count;
    LANE(L->cnt, l) = 0u;
    LANE(L->neg_eps_l, l) = d->ps.k.neg_eps_l;
    LANE(L->g_l2, l) = d->ps.k.g_l2;
    LANE(L->neg_g_l, l) = d->ps.k.neg_g_l;
    LANE(L->g_d, l) = d->ps.k.g_d;
    LANE(L->a_d, l) = d->ps.k.a_d;
    LANE(L->neg_a_d, l) = d->ps.k.neg_a_d;
    LANE(L->k_node, l) = d->ps.k.k_node;
    LANE(L->neg_k_c, l) = d->ps.k.neg_k_c;
    LANE(L->bat_e, l) = DRIVE_BAT_E(d);
    LANE(L->bat_kg, l) = d->in.battery.kg;
    LANE(L->gain, l) = DRIVE_GAIN(d);
    LANE(L->sum_v_dc, l) = d->sums.v_dc;
}

/* Back into the drive after n steps: what rt_run() stores (the coefficients are unchanged). */
static void lanes_store(lanes *L, unsigned l, drive_segment *d, uint32_t n, bool substep) {
    if (substep) {
        pwm_rt_skip_substep(&d->rt, n);
    } else {
        pwm_rt_skip(&d->rt, n);
    }
    for (int x = 0; x < 2; x++) {
        d->ps.ph[x].i_l = LANE(L->i_l[x], l);
        d->ps.ph[x].v_c = LANE(L->v_c[x], l);
        d->ps.ph[x].i_d = LANE(L->i_d[x], l);
        d->ps.ph[x].j_sh = LANE(L->j_sh[x], l);
        d->ps.u[x] = LANE(L->u[x], l);
        d->i_fast[x] = LANE(L->i_fast[x], l);
        d->sums.v_cap[x] = LANE(L->sum_v_cap[x], l);
    }
    for (int x = 0; x < 3; x++) {
        d->s[x] = LANE(L->s[x], l);
    }
    d->ps.v_dc = LANE(L->v_dc, l);
    d->ps.i_dc = LANE(L->i_dc, l);
    d->ps.sat_count = LANE(L->sat, l);
    d->sums.v_dc = LANE(L->sum_v_dc, l);
}

/* Where the mask m is -1, a; where 0, b (bit for bit: floats through their bits). */
static inline vi sel_i(vi m, vi a, vi b) { return (a & m) | (b & ~m); }
static inline vu sel_u(vi m, vu a, vu b) { return (vu)sel_i(m, (vi)a, (vi)b); }

/* pwm_rt_carrier(): the triangle in Q23 from the phase. */
static inline vi lane_carrier(vu ph) {
    const vu x = ph >> 7;
    const vu y = sel_u((vi)((ph & 0x80000000u) != 0u), 0x2000000u - x, x);
    return (vi)y - PWM_RT_ONE;
}

/* pwm_rt_neg(): 1 where v < 0. */
static inline vi lane_neg(vi v) { return (vi)((vu)v >> 31); }

/* A clamp where the mask is -1: counted (fp_count_sat()'s stop at UINT32_MAX: lanes_count()). */
static inline void lane_count(vu *cnt, vi mask) { *cnt -= (vu)mask; }

/*
 * The run's clamps into the count: sat + cnt, UINT32_MAX where that
 * overflows, which is the count of adding one per clamp and stopping at
 * UINT32_MAX (the run's cnt is below 2^32: at most 7 a step).
 */
static inline void lanes_count(lanes *L) {
    const vu s = L->sat + L->cnt;
    L->sat = sel_u((vi)(s < L->sat), (vu){0} + UINT32_MAX, s);
    L->cnt = (vu){0};
}

/* Whether any element of the mask is nonzero: an OR of its 64-bit words. */
static inline bool lane_any(vi m) {
    union {
        vi v;
        uint64_t w[sizeof(vi) / sizeof(uint64_t)];
    } u = {m};
    uint64_t o = 0u;
    for (size_t i = 0u; i < sizeof(vi) / sizeof(uint64_t); i++) {
        o |= u.w[i];
    }
    return o != 0u;
}

/* Doubles, one per lane: the edge duty's quotient. */
typedef double vd __attribute__((vector_size(8 * BATCH_W)));

/*
 * pwm_rt_edge_duty(e0, e1, sh) in the lanes where the mask m is -1 (the
 * others: any value). Its shifts as they are; its quotient floor(n / d),
 * n = pos 2^15 < 2^31, d = den | 1 < 2^16, as the truncated double
 * quotient, which is the same integer: the double division is correctly
 * rounded, and n / d, below 2^31, is an integer or at least 1 / d >= 2^-16
 * from the next one, while its rounding error is at most 2^-22. No
 * integer division in the lanes; tests/host/test_batch_lanes.c compares
 * the two on the edge cases and on a million random edges.
 */
static inline vi lane_edge_duty(vi m, vi e0, vi e1, vu sh) {
    const vi p0 = (vi)(e0 > 0);
    vu pos = (vu)sel_i(p0, e0, e1);
    vu den = (vu)sel_i(p0, (vi)((vu)e0 - (vu)e1), (vi)((vu)e1 - (vu)e0));
    pos >>= sh;
    den = (vu)((vi)(den >> sh) & m);
    for (vi big = (vi)(den > 0xffffu); lane_any(big); big = (vi)(den > 0xffffu)) {
        pos = sel_u(big, pos >> 1, pos);
        den = sel_u(big, den >> 1, den);
    }
    const vd q = __builtin_convertvector(pos << 15, vd) / __builtin_convertvector(den | 1u, vd);
    return (vi)__builtin_convertvector(q, vu);
}

int32_t batch_lanes_edge_duty(int32_t e0, int32_t e1, uint32_t sh) {
    const vi m = (vi){0} - 1;
    return lane_edge_duty(m, (vi){0} + e0, (vi){0} + e1, (vu){0} + sh)[0];
}

/*
 * The modulator's step: pwm_rt_substep() or pwm_rt_sampled(), then the
 * advance. A sub-step leg without a sign change of its comparison over the
 * step is held (0 or the whole step); the legs with one (a few in a
 * hundred) take pwm_rt_edge_duty() itself, lane by lane.
 */
static inline void lane_duties(lanes *L, bool substep, vi duty[3]) {
    const vi ra = L->r[0];
    const vi rb = L->r[1];
    const vi c0 = lane_carrier(L->ph_c);
    if (substep) {
        const vi c1 = lane_carrier(L->ph_c + L->inc_c);
        const vi ra1 = ra + L->dr[0];
        const vi rb1 = rb + L->dr[1];
        const vi e0[3] = {ra - c0, rb - c0, -ra - rb - c0};
        const vi e1[3] = {ra1 - c1, rb1 - c1, -ra1 - rb1 - c1};
        vi edge[3];
        vi any = {0};
        for (int x = 0; x < 3; x++) {
            const vi p1 = (vi)(e1[x] > 0);
            edge[x] = (vi)(e0[x] > 0) ^ p1;
            any |= edge[x];
            duty[x] = p1 & PWM_RT_DUTY_ONE;
            L->s[x] = lane_neg(-e1[x]);
        }
        if (lane_any(any)) {
            for (int x = 0; x < 3; x++) {
                if (lane_any(edge[x])) {
                    duty[x] = sel_i(edge[x], lane_edge_duty(edge[x], e0[x], e1[x], L->den_sh),
                                    duty[x]);
                }
            }
        }
    } else {
        L->s[0] = lane_neg(c0 - ra);
        L->s[1] = lane_neg(c0 - rb);
        L->s[2] = lane_neg(c0 + ra + rb);
        for (int x = 0; x < 3; x++) {
            duty[x] = L->s[x] * PWM_RT_DUTY_ONE;
        }
    }
    L->ph_c += L->inc_c;
    L->r[0] = ra + L->dr[0];
    L->r[1] = rb + L->dr[1];
}

#if UUV_NUMERIC == UUV_NUMERIC_FIXED

/* ps_acc_q(), ps_mac_q(), ps_hi_q() (power_stage_nodes.h): a 64-bit sum modulo 2^64. */
static inline vul lane_acc(vi base) {
    return (__builtin_convertvector((vu)base, vul) << 32) | 0x80000000u;
}

static inline vul lane_mac(vul acc, vi x, vi c) {
    return acc + (vul)(__builtin_convertvector(x, vl) * __builtin_convertvector(c, vl));
}

static inline vi lane_hi(vul acc) { return (vi)__builtin_convertvector(acc >> 32, vu); }

/* ps_clamp_q(): within +-1 per unit (Q3.28), each clamp counted. */
static inline vi lane_clamp(vi x, vu *cnt) {
    const vi out = (vi)((vu)x + (uint32_t)PS_Q28_ONE > 2u * (uint32_t)PS_Q28_ONE);
    lane_count(cnt, out);
    return sel_i(out, sel_i((vi)(x > 0), (vi){0} + PS_Q28_ONE, (vi){0} - PS_Q28_ONE), x);
}

/* ps_shunt_history_q(). */
static inline vi lane_shunt(const lanes *L, vi i_l, vi i_d, vi i_m) {
    const vu base = (vu)i_l - (vu)i_m - 2u * (vu)i_d;
    return lane_hi(lane_mac(lane_acc((vi)base), i_d, L->a_d));
}

/*
 * ps_fast_phase_q() of phase x with the companion's current, then the
 * companion and the frame sum. ps_filter_update_q() clamps and redoes the
 * shunt history only when a value leaves the range; a clamp of a value in
 * range leaves it, so clamping every lane and taking the history from the
 * clamped values is the same.
 */
static inline void lane_phase(lanes *L, int x, vi dd, vl *t) {
    const vi im = L->i_fast[x];
    const vi i0 = L->i_l[x];
    const vi j_l =
        lane_hi(lane_mac(lane_mac(lane_acc(i0), i0, L->neg_eps_l), L->u[x] - L->v_c[x], L->g_l2));
    const vi dv = lane_hi(lane_mac(lane_acc((vi){0}), j_l + L->j_sh[x] - im, L->k_node));
    const vi i_l = lane_clamp(lane_hi(lane_mac(lane_acc(j_l), dv, L->neg_g_l)), &L->cnt);
    const vi i_d = lane_clamp(
        lane_hi(lane_mac(lane_mac(lane_acc(L->i_d[x]), L->i_d[x], L->neg_a_d), dv, L->g_d)),
        &L->cnt);
    const vi v = lane_clamp(L->v_c[x] + dv, &L->cnt);
    L->j_sh[x] = lane_shunt(L, i_l, i_d, im);
    L->v_c[x] = v;
    L->i_l[x] = i_l;
    L->i_d[x] = i_d;
    *t += __builtin_convertvector(dd, vl) * __builtin_convertvector(i0 + i_l, vl);
    L->i_fast[x] = lane_hi(lane_mac(lane_acc(im), v - L->e[x], L->gain));
    L->sum_v_cap[x] += __builtin_convertvector(v, vl);
}

/* One real-time step of every lane (fixed build). */
static inline void lane_step(lanes *L, bool substep) {
    vi duty[3];
    lane_duties(L, substep, duty);
    /* ps_inverter_q(). */
    const vi v3x8 = lane_hi(lane_mac(lane_acc((vi){0}), L->v_dc, (vi){0} + 0x55555555)) * 8;
    const vi w_a = 2 * duty[0] - duty[1] - duty[2];
    const vi w_b = 2 * duty[1] - duty[0] - duty[2];
    L->u[0] = lane_hi(lane_mac(lane_acc((vi){0}), v3x8, w_a * 16384));
    L->u[1] = lane_hi(lane_mac(lane_acc((vi){0}), v3x8, w_b * 16384));
    vl t = {0};
    lane_phase(L, 0, duty[0] - duty[2], &t);
    lane_phase(L, 1, duty[1] - duty[2], &t);
    /* ps_fast_end_q(): floor((T + 2^15) / 2^16), then the DC link. */
    const vi i_dc = (vi)__builtin_convertvector((vul)((t + 32768) >> 16), vu);
    L->v_dc = lane_clamp(
        lane_hi(lane_mac(lane_mac(lane_acc(L->v_dc), L->bat_e - L->v_dc, L->bat_kg), i_dc,
                         L->neg_k_c)),
        &L->cnt);
    L->i_dc = i_dc;
    L->sum_v_dc += __builtin_convertvector(L->v_dc, vl);
}

#else /* UUV_NUMERIC_FLOAT */

static inline vf sel_f(vi m, vf a, vf b) { return (vf)sel_i(m, (vi)a, (vi)b); }

/* ps_clamp_f32(): x within +-lim, each clamp counted (fp_count_sat()). */
static inline vf lane_clamp(vf x, float lim, vu *cnt) {
    const vi hi = (vi)(x > lim);
    const vi lo = (vi)(x < -lim);
    lane_count(cnt, hi | lo);
    return sel_f(hi, (vf){0} + lim, sel_f(lo, (vf){0} - lim, x));
}

/* ps_fast_phase_f32() of phase x with the companion's current, then the companion and sum. */
static inline void lane_phase(lanes *L, int x, vf dd, vf *t) {
    const vf im = L->i_fast[x];
    const vf i0 = L->i_l[x];
    const vf j_l = (i0 + L->neg_eps_l * i0) + L->g_l2 * (L->u[x] - L->v_c[x]);
    const vf dv = L->k_node * ((j_l + L->j_sh[x]) - im);
    const vf i_l = lane_clamp(j_l + L->neg_g_l * dv, PS_I_LIM_F32, &L->cnt);
    const vf i_d =
        lane_clamp((L->i_d[x] + L->neg_a_d * L->i_d[x]) + L->g_d * dv, PS_I_LIM_F32, &L->cnt);
    L->j_sh[x] = ((i_l - im) - 2.0f * i_d) + L->a_d * i_d;
    L->v_c[x] = lane_clamp(L->v_c[x] + dv, PS_V_LIM_F32, &L->cnt);
    L->i_l[x] = i_l;
    L->i_d[x] = i_d;
    const vf term = dd * (i0 + i_l);
    *t = (x == 0) ? term : *t + term;
    const vf v = L->v_c[x];
    L->i_fast[x] = im + (v - L->e[x]) * L->gain;
    L->sum_v_cap[x] += v;
}

/* One real-time step of every lane. */
static inline void lane_step(lanes *L, bool substep) {
    vi duty[3];
    lane_duties(L, substep, duty);
    const float q = 1.0f / 32768.0f;
    const vf dq[3] = {__builtin_convertvector(duty[0], vf) * q,
                      __builtin_convertvector(duty[1], vf) * q,
                      __builtin_convertvector(duty[2], vf) * q};
    const vf v3 = L->v_dc * (1.0f / 3.0f);
    L->u[0] = v3 * ((2.0f * dq[0] - dq[1]) - dq[2]);
    L->u[1] = v3 * ((2.0f * dq[1] - dq[0]) - dq[2]);
    vf t = {0};
    lane_phase(L, 0, dq[0] - dq[2], &t);
    lane_phase(L, 1, dq[1] - dq[2], &t);
    const vf i_dc = 0.5f * t;
    L->v_dc = lane_clamp(L->v_dc + (L->bat_kg * (L->bat_e - L->v_dc) + L->neg_k_c * t),
                         PS_V_LIM_F32, &L->cnt);
    L->i_dc = i_dc;
    L->sum_v_dc += L->v_dc;
}

#endif

/*
 * n steps on a copy of the lanes in locals (so that the compiler keeps
 * them in registers between the steps), stored back after the last.
 */
static inline void lanes_run_on(lanes *L, uint32_t n, const bool substep) {
    lanes w[BATCH_G];
    for (int g = 0; g < BATCH_G; g++) {
        w[g] = L[g];
    }
    for (uint32_t k = 0u; k < n; k++) {
        for (int g = 0; g < BATCH_G; g++) {
            lane_step(&w[g], substep);
        }
    }
    for (int g = 0; g < BATCH_G; g++) {
        lanes_count(&w[g]);
        L[g] = w[g];
    }
}

static void lanes_run(lanes *L, uint32_t n, bool substep) {
    if (substep) {
        lanes_run_on(L, n, true);
    } else {
        lanes_run_on(L, n, false);
    }
}

void batch_fast_run(drive_segment *const *d, size_t count, uint32_t n, bool substep) {
    static lanes L[BATCH_G];
    const size_t width = (size_t)BATCH_W * BATCH_G;
    for (size_t i0 = 0u; i0 < count; i0 += width) {
        const size_t m = (count - i0 < width) ? count - i0 : width;
        if (m == 1u) {
            drive_fast_run(d[i0], n); /* one run: its own loop */
            continue;
        }
        for (size_t l = 0u; l < width; l++) {
            /* Lanes beyond the runs repeat the last one; their results are dropped. */
            lanes_load(&L[l / BATCH_W], (unsigned)(l % BATCH_W), d[i0 + ((l < m) ? l : m - 1u)]);
        }
        lanes_run(L, n, substep);
        for (size_t l = 0u; l < m; l++) {
            lanes_store(&L[l / BATCH_W], (unsigned)(l % BATCH_W), d[i0 + l], n, substep);
        }
    }
}
