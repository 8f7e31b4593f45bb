/*
 * Set-up and the motor task's side of the real-time modulator (pwm_rt.h).
 */
#include "models/drive/pwm/pwm_rt.h"

#include <stddef.h>

#include "fixedpoint/fixedpoint.h"
#include "fixedpoint/wavetable.h"

pwm_status pwm_rt_init(pwm_rt *p, const pwm_params *pp, uint32_t step_ns) {
    pwm_q check;
    if (p == NULL || pp == NULL) {
        return PWM_ERR_NULL;
    }
    if (pp->edges != PWM_EDGES_SAMPLED) {
        return PWM_ERR_EDGES;
    }
    /* The general modulator checks the parameters and forms the carrier increment. */
    pwm_status st = pwm_init_q(&check, pp, step_ns);
    if (st != PWM_OK) {
        return st;
    }
    /* The pre-shift that brings a step's carrier change, inc_c / 2^7 in
     * Q23 (with up to 2 % of reference slope on it), below 2^16. */
    uint32_t sh = 0u;
    while (sh < 16u && ((check.inc_c >> 7) + (check.inc_c >> 12)) >> sh > 0xffffu) {
        sh++;
    }
    *p = (pwm_rt){0};
    p->inc_c = check.inc_c;
    p->den_sh = sh;
    p->fr[0].ph0 = check.ph_c;
    p->ev[0].kind = (uint8_t)PWM_RT_PER_STEP;
    p->ev[PWM_RT_EVENTS + 1u].kind = (uint8_t)PWM_RT_PER_STEP;
    return PWM_OK;
}

/* ---- Plans (pwm_rt.h) ---------------------------------------------------- */

/* The sign bit of -e as a leg state: 1 when e > 0 (|e| < 2^31). */
static inline uint32_t pos_bit(int32_t e) { return (uint32_t)-e >> 31; }

/* The sign bits (e > 0) of the three legs. */
static inline uint32_t state_bits(int32_t e0, int32_t e1, int32_t e2) {
    return pos_bit(e0) | (pos_bit(e1) << 1) | (pos_bit(e2) << 2);
}

/* A frame's legs for its plan: the carrier's start and step, each leg's reference and slope. */
typedef struct {
    uint32_t ph0;
    uint32_t inc;
    uint32_t r0[3];  /* the references at the frame's first step (Q23, as uint32_t: sums modulo 2^32) */
    uint32_t dr[3];  /* their change per step */
    uint32_t sh;     /* the duty division's pre-shift */
} rt_legs;

/* The three legs' comparisons at step j: pwm_rt_e_at()'s (the same sums modulo 2^32), their states. */
static inline uint32_t e_legs(const rt_legs *g, uint32_t j, int32_t e[3]) {
    const int32_t c = pwm_rt_carrier(g->ph0 + j * g->inc);
    e[0] = (int32_t)(g->r0[0] + j * g->dr[0]) - c;
    e[1] = (int32_t)(g->r0[1] + j * g->dr[1]) - c;
    e[2] = (int32_t)(g->r0[2] + j * g->dr[2]) - c;
    return state_bits(e[0], e[1], e[2]);
}

/*
 * The step t in [a, b) at whose ends leg x's comparison e changes sign,
 * given that it does between a and b within one half of the carrier
 * (rising or not), where e is monotone: from e_a and the change per step
 * (the carrier's inc / 2^7 less the reference's slope, on the rising half;
 * plus it, on the falling one) the estimate, then the steps checked and
 * moved until e_t and e_t+1 differ in sign; the leg's duty in that step
 * (pwm_rt_edge_duty() of its ends) in *duty. The phase and the reference
 * move with t by their steps (the same sums modulo 2^32).
 */
static inline uint32_t edge_find(const rt_legs *g, uint32_t x, uint32_t a, uint32_t b, bool rising,
                                 int32_t e_a, int32_t *duty) {
    const uint32_t pos = pos_bit(e_a);
    const uint32_t inc = g->inc;
    const uint32_t dr = g->dr[x];
    const uint32_t carrier = inc >> 7;
    const uint32_t step = rising ? carrier - dr : carrier + dr;
    const uint32_t gap = (uint32_t)e_a - pos;
    const uint32_t sg = 0u - (pos ^ 1u); /* all ones for e_a <= 0: |gap| by its complement + 1 */
    uint32_t t = a + ((gap ^ sg) - sg) / step;
    t = (t < b) ? t : b - 1u;
    uint32_t ph = g->ph0 + t * inc;
    uint32_t r = g->r0[x] + t * dr;
    int32_t e0 = (int32_t)r - pwm_rt_carrier(ph);
    while (t > a && pos_bit(e0) != pos) {
        t--;
        ph -= inc;
        r -= dr;
        e0 = (int32_t)r - pwm_rt_carrier(ph);
    }
    ph += inc;
    r += dr;
    int32_t e1 = (int32_t)r - pwm_rt_carrier(ph);
    while (pos_bit(e1) == pos) {
        t++;
        e0 = e1;
        ph += inc;
        r += dr;
        e1 = (int32_t)r - pwm_rt_carrier(ph);
    }
    *duty = pwm_rt_edge_duty(e0, e1, g->sh);
    return t;
}

/* The events of a plan being written. */
typedef struct {
    pwm_rt_event *v;    /* the next slot; NULL once handed over to single steps */
    pwm_rt_event *end;  /* the slot a full plan hands over in (the first's PWM_RT_EVENTS on) */
    uint32_t held;      /* the legs' states after the last event */
    bool need0;         /* its first step must be an event */
} rt_plan_out;

/* Writes event v: step at, kind, the states s, the duties d. */
static inline void event_set(pwm_rt_event *v, uint32_t at, uint32_t s, uint8_t kind, int32_t d0,
                             int32_t d1, int32_t d2) {
    v->at = (uint16_t)at;
    v->s = (uint8_t)s;
    v->kind = kind;
    v->duty[0] = d0;
    v->duty[1] = d1;
    v->duty[2] = d2;
}

/* Leg x's whole-step duty for the states s. */
static inline int32_t held_duty(uint32_t s, uint32_t x) {
    return (int32_t)(((s >> x) & 1u) << 15);
}

/* Writes event v at step at: kind, the states s, whole-step duties. */
static inline void event_put(pwm_rt_event *v, uint32_t at, uint32_t s, uint8_t kind) {
    event_set(v, at, s, kind, held_duty(s, 0u), held_duty(s, 1u), held_duty(s, 2u));
}

/*
 * The event of step at, where the legs of mask change (their duties duty,
 * their states to s's bits); the first step's event before it when due;
 * the hand-over to single steps when the plan is full.
 */
static inline void event_edges(rt_plan_out *o, uint32_t at, uint32_t mask, const int32_t duty[3],
                               uint32_t s) {
    pwm_rt_event *v = o->v;
    if (v != NULL) {
        if (o->need0) {
            o->need0 = false;
            if (at != 0u) {
                event_put(v, 0u, o->held, 0u);
                v = &v[1];
            }
        }
        if (v == o->end) {
            event_set(v, at, 0u, (uint8_t)PWM_RT_PER_STEP, 0, 0, 0);
            o->v = NULL;
        } else {
            const uint32_t h = (o->held & ~mask) | (s & mask);
            o->held = h;
            event_set(v, at, h, 1u, ((mask & 1u) != 0u) ? duty[0] : held_duty(h, 0u),
                      ((mask & 2u) != 0u) ? duty[1] : held_duty(h, 1u),
                      ((mask & 4u) != 0u) ? duty[2] : held_duty(h, 2u));
            o->v = &v[1];
        }
    }
}

/*
 * The edges inside segment [a, b) of one carrier half of the legs of todo
 * (their signs at a and b differ; ea their comparisons at a, sb their
 * states at b) as events in step order, legs with the same step in one:
 * the legs sorted by their steps (three exchanges), then each step once.
 */
static inline void segment_edges(const rt_legs *g, rt_plan_out *o, uint32_t a, uint32_t b,
                                 bool rising, const int32_t ea[3], uint32_t todo, uint32_t sb) {
    uint32_t t[3] = {UINT32_MAX, UINT32_MAX, UINT32_MAX};
    int32_t duty[3] = {0, 0, 0};
    for (uint32_t x = 0u; x < 3u; x++) {
        if (((todo >> x) & 1u) != 0u) {
            t[x] = edge_find(g, x, a, b, rising, ea[x], &duty[x]);
        }
    }
    /* The edges in step order (the legs without one last, at UINT32_MAX): steps t and legs m. */
    uint32_t t0 = t[0];
    uint32_t t1 = t[1];
    uint32_t t2 = t[2];
    uint32_t m0 = 1u;
    uint32_t m1 = 2u;
    uint32_t m2 = 4u;
    uint32_t w;
    if (t1 < t0) {
        w = t0; t0 = t1; t1 = w;
        w = m0; m0 = m1; m1 = w;
    }
    if (t2 < t1) {
        w = t1; t1 = t2; t2 = w;
        w = m1; m1 = m2; m2 = w;
    }
    if (t1 < t0) {
        w = t0; t0 = t1; t1 = w;
        w = m0; m0 = m1; m1 = w;
    }
    /* Each distinct step once, with the mask of its legs. */
    if (t1 == t0) {
        m1 |= m0;
    } else {
        event_edges(o, t0, m0, duty, sb);
    }
    if (t1 != UINT32_MAX) {
        if (t2 == t1) {
            event_edges(o, t1, m1 | m2, duty, sb);
        } else {
            event_edges(o, t1, m1, duty, sb);
            if (t2 != UINT32_MAX) {
                event_edges(o, t2, m2, duty, sb);
            }
        }
    }
}

/*
 * The edges of frame f's n steps as events, segment by segment of the
 * carrier's halves (within one, each leg's comparison is monotone): an
 * edge inside a segment where the signs at its ends differ
 * (segment_edges()), and one in the step that crosses into the next half
 * where that step's ends differ; f's states at its first and last index.
 * False when the frame cannot be planned (a reference as fast as the
 * carrier, or out of range).
 */
static inline bool edges_find(const pwm_rt *p, pwm_rt_frame *f, rt_plan_out *o, bool force0,
                              uint32_t prev) {
    const uint32_t n = p->n;
    const uint32_t inc = p->inc_c;
    const uint32_t lim = p->dr_lim;
    const rt_legs g = {f->ph0, inc,
                       {(uint32_t)f->r0[0], (uint32_t)f->r0[1], (uint32_t)(-f->r0[0] - f->r0[1])},
                       {(uint32_t)f->dr[0], (uint32_t)f->dr[1], (uint32_t)(-f->dr[0] - f->dr[1])},
                       p->den_sh};
    if (f->r0[0] >= 0x1000000 || f->r0[0] <= -0x1000000 || f->r0[1] >= 0x1000000 ||
        f->r0[1] <= -0x1000000) {
        return false;
    }
    for (uint32_t x = 0u; x < 3u; x++) {
        const uint32_t mag = ((int32_t)g.dr[x] < 0) ? 0u - g.dr[x] : g.dr[x];
        if (mag >= lim) {
            return false; /* as fast as the carrier, or beyond the frame's range (dr_lim) */
        }
    }
    int32_t ea[3];
    uint32_t sa = e_legs(&g, 0u, ea);
    f->s0 = (uint8_t)sa;
    o->held = sa;
    o->need0 = force0 || sa != prev;
    uint32_t a = 0u;
    for (;;) {
        const uint32_t pa = f->ph0 + a * inc;
        const uint32_t to_half = 0x80000000u - (pa & 0x7fffffffu);
        const uint32_t steps = (to_half - 1u) / inc + 1u;
        const uint32_t b = (steps - 1u < n - a) ? a + steps - 1u : n;
        int32_t eb[3];
        uint32_t sb = sa;
        if (b > a) {
            sb = e_legs(&g, b, eb);
        } else {
            eb[0] = ea[0];
            eb[1] = ea[1];
            eb[2] = ea[2];
        }
        /* Inside the segment: each leg's edge, in step order. */
        if ((sa ^ sb) != 0u) {
            segment_edges(&g, o, a, b, (pa & 0x80000000u) == 0u, ea, sa ^ sb, sb);
        }
        if (b == n) {
            f->s_end = (uint8_t)sb;
            return true;
        }
        /* The step from this half into the next. */
        sa = e_legs(&g, b + 1u, ea);
        const uint32_t mask = sb ^ sa;
        if (mask != 0u) {
            int32_t duty[3] = {0, 0, 0};
            for (uint32_t x = 0u; x < 3u; x++) {
                if (((mask >> x) & 1u) != 0u) {
                    duty[x] = pwm_rt_edge_duty(eb[x], ea[x], p->den_sh);
                }
            }
            event_edges(o, b, mask, duty, sa);
        }
        if (b + 1u == n) {
            f->s_end = (uint8_t)sa;
            return true;
        }
        a = b + 1u;
    }
}

/*
 * Frame c from phase ph with the ramp: the frame's start and its events;
 * an event at its first step when force0 or its first states differ from
 * prev (the states the steps before it leave).
 */
static void plan_build(pwm_rt *p, uint32_t c, uint32_t ph, const pwm_rt_ramp *ramp, bool force0,
                       uint32_t prev) {
    pwm_rt_frame *f = &p->fr[c];
    pwm_rt_event *ev = &p->ev[(size_t)c * (PWM_RT_EVENTS + 1u)];
    rt_plan_out o = {ev, &ev[PWM_RT_EVENTS], 0u, false};
    f->ph0 = ph;
    for (int x = 0; x < 2; x++) {
        f->r0[x] = ramp->r0[x];
        f->dr[x] = ramp->dr[x];
    }
    if (UUV_LEAN_IMAGE != 0 || !edges_find(p, f, &o, force0, prev)) {
        int32_t e[3];
        pwm_rt_e_at(f, p->inc_c, 0u, e);
        f->s0 = (uint8_t)state_bits(e[0], e[1], e[2]);
        pwm_rt_e_at(f, p->inc_c, p->n, e);
        f->s_end = (uint8_t)state_bits(e[0], e[1], e[2]);
        event_put(ev, 0u, 0u, (uint8_t)PWM_RT_PER_STEP);
    } else if (o.v != NULL) {
        pwm_rt_event *v = o.v;
        if (o.need0) {
            event_put(v, 0u, o.held, 0u);
            v = &v[1];
        }
        event_set(v, p->n, 0u, (uint8_t)PWM_RT_PER_STEP, 0, 0, 0);
    } else {
        /* full: the plan ends in its hand-over event */
    }
}

void pwm_rt_plan(pwm_rt *p, uint32_t c, uint32_t ph, const pwm_rt_ramp *ramp) {
    plan_build(p, c, ph, ramp, true, 0u);
}

void pwm_rt_prepare(pwm_rt *p, const pwm_rt_ramp *ramp) {
    if (UUV_LEAN_IMAGE != 0 || p->n == 0u) {
        return;
    }
    const uint32_t c = p->cur ^ 1u;
    const pwm_rt_frame *now = &p->fr[p->cur];
    plan_build(p, c, now->ph0 + p->n * p->inc_c, ramp, false, now->s_end);
    p->fr[c].ready = true;
}

/*
 * The bound a plan's slopes must stay below, |dr| < it: below the
 * carrier's change per step, inc / 2^7 (each leg's comparison then
 * monotone in each half), and with |dr| n below 2^24 (the references stay
 * in range over the frame); 0, no plan, for frames of none or more than
 * 65535 steps and for increments of none or half a turn or more.
 */
static uint32_t pwm_rt_slope_limit(uint32_t n, uint32_t inc) {
    uint32_t lim = 0u;
    if (n != 0u && n <= 65535u && inc != 0u && inc < 0x80000000u) {
        const uint32_t range = (0xffffffu / n) + 1u;
        lim = inc >> 7;
        lim = (range < lim) ? range : lim;
    }
    return lim;
}

void pwm_rt_frames(pwm_rt *p, uint32_t n) {
    const pwm_rt_frame *now = &p->fr[p->cur];
    const pwm_rt_ramp ramp = {{now->r0[0], now->r0[1]}, {now->dr[0], now->dr[1]}};
    p->n = (UUV_LEAN_IMAGE != 0) ? 0u : n; /* a lean image plans nothing */
    p->dr_lim = pwm_rt_slope_limit(p->n, p->inc_c);
    pwm_rt_plan(p, p->cur, now->ph0, &ramp);
    p->k = 0u;
    p->next = p->cur * (PWM_RT_EVENTS + 1u);
    p->next_at = p->ev[p->next].at;
}

void pwm_rt_skip(pwm_rt *p, uint32_t n) {
    if (UUV_LEAN_IMAGE != 0) {
        for (uint32_t j = 0u; j < n; j++) {
            pwm_rt_advance(p); /* the frame's start moves (pwm_rt_k()) */
        }
        return;
    }
    const uint32_t k = p->k + n;
    p->k = k;
    if (p->n == 0u) {
        return; /* no plans: the steps use no events (as pwm_rt_sampled()) */
    }
    while (p->ev[p->next].kind != (uint8_t)PWM_RT_PER_STEP && p->ev[p->next].at < k) {
        p->next++;
    }
    const uint32_t at = p->ev[p->next].at;
    p->next_at = (at < k) ? k : at;
}

void pwm_rt_event_take(pwm_rt *p, int32_t s[3], int32_t duty[3]) {
    const pwm_rt_event *v = &p->ev[p->next];
    if (v->kind == (uint8_t)PWM_RT_PER_STEP) {
        pwm_rt_substep_each(p, s, duty);
        p->next_at = p->k;
        return;
    }
    for (uint32_t x = 0u; x < 3u; x++) {
        duty[x] = v->duty[x];
        s[x] = pwm_rt_bit(v->s, x);
    }
    p->next++;
    p->next_at = p->ev[p->next].at;
    p->k++;
}

int32_t pwm_rt_edge_duty(int32_t e0, int32_t e1, uint32_t sh) {
    uint32_t pos;
    uint32_t den;
    if (e0 > 0) {
        pos = (uint32_t)e0;
        den = (uint32_t)e0 - (uint32_t)e1;
    } else {
        pos = (uint32_t)e1;
        den = (uint32_t)e1 - (uint32_t)e0;
    }
    pos >>= sh;
    den >>= sh;
    while (den > 0xffffu) {
        pos >>= 1;
        den >>= 1;
    }
    const uint32_t q = (pos << 15) / (den | 1u);
    return (int32_t)q;
}

pwm_status pwm_rt_dead_time(pwm_rt *p, uint32_t dead_ns, uint32_t step_ns) {
    if (p == NULL) {
        return PWM_ERR_NULL;
    }
    if (step_ns == 0u || dead_ns > 10000u || dead_ns > 8u * step_ns) {
        return PWM_ERR_STEP;
    }
    /* t_d / T in Q16, rounded: below 2^19. */
    const uint32_t half = step_ns / 2u;
    const uint64_t num = ((uint64_t)dead_ns << 16) + (uint64_t)half;
    const uint64_t kd = num / (uint64_t)step_ns;
    p->kd = (int32_t)kd;
    return PWM_OK;
}

/* round(num / n) for |num| < 2^31 - n, n >= 1, ties away from zero. */
static int32_t div_round(int32_t num, uint32_t n) {
    const int32_t d = (int32_t)((n > 0x7fffffffu) ? 0x7fffffffu : n);
    const int32_t half = d / 2;
    return (num >= 0) ? (num + half) / d : -((half - num) / d);
}

static void ramp_from_knots(pwm_rt_ramp *out, const int32_t r0[2], const int32_t r1[2],
                            uint32_t n) {
    for (int x = 0; x < 2; x++) {
        out->r0[x] = r0[x];
        out->dr[x] = div_round(r1[x] - r0[x], n);
    }
}

/* m sin(ph) in Q23: the Q30 product floored by 7 bits. */
static int32_t ref_q(int32_t m_q15, uint32_t ph) {
    return fp_shr_floor_i32(m_q15 * (int32_t)wt_sin_q15(ph), 7u);
}

/* m sin(ph) in Q23, rounded: the Q31 conversion (saturating at +-1) rounded by 8 bits. */
static int32_t ref_f32(float m, uint32_t ph) {
    return fp_shr_round_i32(fp_from_f32_q31(m * wt_sin_f32(ph)), 8u);
}

/*
 * A frame's start from the knots kept at the last one's end (same: formed
 * with the same index), when it starts at their phase; false otherwise.
 */
static bool knots_start(const pwm_rt_knots *end, bool same, uint32_t ph, int32_t r0[2]) {
    const bool hit = (end != NULL) && end->valid && same && (end->ph == ph);
    if (hit) {
        r0[0] = end->r[0];
        r0[1] = end->r[1];
    }
    return hit;
}

/* Keeps a frame's end (phase ph1, references r1) for the next. */
static void knots_keep(pwm_rt_knots *end, uint32_t ph1, const int32_t r1[2]) {
    if (end != NULL) {
        end->valid = true;
        end->ph = ph1;
        end->r[0] = r1[0];
        end->r[1] = r1[1];
    }
}

void pwm_rt_ramp_q(pwm_rt_ramp *out, pwm_rt_knots *end, int32_t m_q15, uint32_t ph, uint32_t inc,
                   uint32_t n) {
    const uint32_t ph1 = ph + inc * n; /* modulo 2^32: whole turns drop out */
    int32_t r0[2];
    if (!knots_start(end, (end != NULL) && (end->m_q15 == m_q15), ph, r0)) {
        r0[0] = ref_q(m_q15, ph);
        r0[1] = ref_q(m_q15, ph - WT_PHASE_120);
    }
    const int32_t r1[2] = {ref_q(m_q15, ph1), ref_q(m_q15, ph1 - WT_PHASE_120)};
    ramp_from_knots(out, r0, r1, n);
    knots_keep(end, ph1, r1);
    if (end != NULL) {
        end->m_q15 = m_q15;
    }
}

void pwm_rt_ramp_f32(pwm_rt_ramp *out, pwm_rt_knots *end, float m, uint32_t ph, uint32_t inc,
                     uint32_t n) {
    const uint32_t ph1 = ph + inc * n;
    int32_t r0[2];
    if (!knots_start(end, (end != NULL) && (end->m == m), ph, r0)) {
        r0[0] = ref_f32(m, ph);
        r0[1] = ref_f32(m, ph - WT_PHASE_120);
    }
    const int32_t r1[2] = {ref_f32(m, ph1), ref_f32(m, ph1 - WT_PHASE_120)};
    ramp_from_knots(out, r0, r1, n);
    knots_keep(end, ph1, r1);
    if (end != NULL) {
        end->m = m;
    }
}
