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

/* A frame's legs for its plan: the carrier's start and step, each leg's reference and slope. */
typedef struct {
    uint32_t ph0;
    uint32_t inc;
    int32_t r0[3];
    int32_t dr[3];
} rt_legs;

/* Leg x's comparison at step j: pwm_rt_e_at()'s, for one leg (the same sums modulo 2^32). */
static inline int32_t e_leg(const rt_legs *g, uint32_t j, uint32_t x) {
    const int32_t c = pwm_rt_carrier(g->ph0 + j * g->inc);
    const uint32_t r = (uint32_t)g->r0[x] + j * (uint32_t)g->dr[x];
    return (int32_t)r - c;
}

/* The three legs' comparisons at step j. */
static inline void e_legs(const rt_legs *g, uint32_t j, int32_t e[3]) {
    const int32_t c = pwm_rt_carrier(g->ph0 + j * g->inc);
    for (uint32_t x = 0u; x < 3u; x++) {
        const uint32_t r = (uint32_t)g->r0[x] + j * (uint32_t)g->dr[x];
        e[x] = (int32_t)r - c;
    }
}

/*
 * The step t in [a, b) at whose ends leg x's comparison e changes sign,
 * given that it does between a and b within one half of the carrier
 * (rising or not), where e is monotone: from e_a and the change per step
 * (the carrier's inc / 2^7 less the reference's slope, on the rising half;
 * plus it, on the falling one) the estimate, then the steps checked and
 * moved until e_t and e_t+1 (returned in e) differ in sign.
 */
static uint32_t edge_find(const rt_legs *g, uint32_t x, uint32_t a, uint32_t b, bool rising,
                          int32_t e_a, int32_t e[2]) {
    const bool pos = e_a > 0;
    const int32_t carrier = (int32_t)(g->inc >> 7);
    const uint32_t step = (uint32_t)(rising ? carrier - g->dr[x] : carrier + g->dr[x]);
    const uint32_t gap = pos ? (uint32_t)e_a - 1u : 0u - (uint32_t)e_a;
    uint32_t t = a + gap / step;
    t = (t < b) ? t : b - 1u;
    e[0] = e_leg(g, t, x);
    while (t > a && (e[0] > 0) != pos) {
        t--;
        e[0] = e_leg(g, t, x);
    }
    e[1] = e_leg(g, t + 1u, x);
    while ((e[1] > 0) == pos) {
        t++;
        e[0] = e[1];
        e[1] = e_leg(g, t + 1u, x);
    }
    return t;
}

/* The sign bits (e > 0) of the three legs (|e| < 2^31). */
static uint32_t state_bits(const int32_t e[3]) {
    return ((uint32_t)-e[0] >> 31) | (((uint32_t)-e[1] >> 31) << 1) | (((uint32_t)-e[2] >> 31) << 2);
}

/* The events of a plan being written. */
typedef struct {
    pwm_rt_event *ev;
    uint32_t n;      /* written */
    uint32_t held;   /* the legs' states after the last */
    bool need0;      /* its first step must be an event */
    bool full;       /* handed over to single steps */
} rt_plan_out;

/* Writes an event at step at: kind, the states s, whole-step duties. */
static pwm_rt_event *event_put(rt_plan_out *o, uint32_t at, uint32_t s, uint8_t kind) {
    pwm_rt_event *v = &o->ev[o->n++];
    v->at = (uint16_t)at;
    v->s = (uint8_t)s;
    v->kind = kind;
    v->duty[0] = ((s & 1u) != 0u) ? PWM_RT_DUTY_ONE : 0;
    v->duty[1] = ((s & 2u) != 0u) ? PWM_RT_DUTY_ONE : 0;
    v->duty[2] = ((s & 4u) != 0u) ? PWM_RT_DUTY_ONE : 0;
    return v;
}

/*
 * The event of step at, where the legs of mask change (their duties duty,
 * their states to s's bits); the first step's event before it when due;
 * the hand-over to single steps when the plan is full.
 */
static void event_edges(rt_plan_out *o, uint32_t at, uint32_t mask, const int32_t duty[3],
                        uint32_t s) {
    if (o->full) {
        return;
    }
    if (o->need0 && at != 0u) {
        (void)event_put(o, 0u, o->held, 0u);
    }
    o->need0 = false;
    if (o->n == PWM_RT_EVENTS) {
        (void)event_put(o, at, 0u, (uint8_t)PWM_RT_PER_STEP);
        o->full = true;
        return;
    }
    o->held = (o->held & ~mask) | (s & mask);
    pwm_rt_event *v = event_put(o, at, o->held, 1u);
    for (uint32_t x = 0u; x < 3u; x++) {
        if (((mask >> x) & 1u) != 0u) {
            v->duty[x] = duty[x];
        }
    }
}

/*
 * The edges of frame f's n steps as events, segment by segment of the
 * carrier's halves (within one, each leg's comparison is monotone): an
 * edge inside a segment where the signs at its ends differ (edge_find()),
 * in step order, and one in the step that crosses into the next half
 * where that step's ends differ; f's states at its first and last index.
 * False when the frame cannot be planned (a reference as fast as the
 * carrier, or out of range).
 */
static bool edges_find(const pwm_rt *p, pwm_rt_frame *f, rt_plan_out *o, bool force0,
                       uint32_t prev) {
    const uint32_t n = p->n;
    const uint32_t inc = p->inc_c;
    const int32_t lim = (int32_t)(inc >> 7);
    const rt_legs g = {f->ph0, inc, {f->r0[0], f->r0[1], -f->r0[0] - f->r0[1]},
                       {f->dr[0], f->dr[1], -f->dr[0] - f->dr[1]}};
    if (n == 0u || n > 65535u || inc == 0u || inc >= 0x80000000u || f->r0[0] >= 0x1000000 ||
        f->r0[0] <= -0x1000000 || f->r0[1] >= 0x1000000 || f->r0[1] <= -0x1000000) {
        return false;
    }
    for (uint32_t x = 0u; x < 3u; x++) {
        const uint32_t mag = (g.dr[x] < 0) ? 0u - (uint32_t)g.dr[x] : (uint32_t)g.dr[x];
        if ((int32_t)mag >= lim || (uint64_t)mag * n >= 0x1000000u) {
            return false;
        }
    }
    int32_t ea[3];
    e_legs(&g, 0u, ea);
    uint32_t sa = state_bits(ea);
    f->s0 = (uint8_t)sa;
    o->held = sa;
    o->need0 = force0 || sa != prev;
    uint32_t a = 0u;
    for (;;) {
        const uint32_t pa = f->ph0 + a * inc;
        const uint32_t to_half = 0x80000000u - (pa & 0x7fffffffu);
        const uint32_t steps = (to_half - 1u) / inc + 1u;
        const uint32_t b = (steps - 1u < n - a) ? a + steps - 1u : n;
        int32_t eb[3] = {ea[0], ea[1], ea[2]};
        if (b > a) {
            e_legs(&g, b, eb);
        }
        const uint32_t sb = state_bits(eb);
        /* Inside the segment: each leg's edge, in step order. */
        uint32_t todo = sa ^ sb;
        if (todo != 0u) {
            uint32_t t[3] = {UINT32_MAX, UINT32_MAX, UINT32_MAX};
            int32_t duty[3] = {0, 0, 0};
            for (uint32_t x = 0u; x < 3u; x++) {
                if (((todo >> x) & 1u) != 0u) {
                    int32_t e[2];
                    t[x] = edge_find(&g, x, a, b, (pa & 0x80000000u) == 0u, ea[x], e);
                    duty[x] = pwm_rt_edge_duty(e[0], e[1], p->den_sh);
                }
            }
            while (todo != 0u) {
                const uint32_t at = (t[0] < t[1]) ? ((t[0] < t[2]) ? t[0] : t[2])
                                                  : ((t[1] < t[2]) ? t[1] : t[2]);
                uint32_t mask = 0u;
                for (uint32_t x = 0u; x < 3u; x++) {
                    if (t[x] == at) {
                        mask |= 1u << x;
                    }
                }
                event_edges(o, at, mask, duty, sb);
                for (uint32_t x = 0u; x < 3u; x++) {
                    t[x] = (((mask >> x) & 1u) != 0u) ? UINT32_MAX : t[x];
                }
                todo &= ~mask;
            }
        }
        if (b == n) {
            f->s_end = (uint8_t)sb;
            return true;
        }
        /* The step from this half into the next. */
        e_legs(&g, b + 1u, ea);
        sa = state_bits(ea);
        const uint32_t mask = sb ^ sa;
        if (mask != 0u) {
            int32_t duty[3];
            for (uint32_t x = 0u; x < 3u; x++) {
                duty[x] = (((mask >> x) & 1u) != 0u) ? pwm_rt_edge_duty(eb[x], ea[x], p->den_sh)
                                                    : 0;
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
    rt_plan_out o = {&p->ev[(size_t)c * (PWM_RT_EVENTS + 1u)], 0u, 0u, false, false};
    f->ph0 = ph;
    for (int x = 0; x < 2; x++) {
        f->r0[x] = ramp->r0[x];
        f->dr[x] = ramp->dr[x];
    }
    if (UUV_LEAN_IMAGE != 0 || !edges_find(p, f, &o, force0, prev)) {
        int32_t e[3];
        pwm_rt_e_at(f, p->inc_c, 0u, e);
        f->s0 = (uint8_t)state_bits(e);
        pwm_rt_e_at(f, p->inc_c, p->n, e);
        f->s_end = (uint8_t)state_bits(e);
        o.n = 0u;
        (void)event_put(&o, 0u, 0u, (uint8_t)PWM_RT_PER_STEP);
        return;
    }
    if (o.need0) {
        (void)event_put(&o, 0u, o.held, 0u);
    }
    if (!o.full) {
        (void)event_put(&o, p->n, 0u, (uint8_t)PWM_RT_PER_STEP);
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

void pwm_rt_frames(pwm_rt *p, uint32_t n) {
    const pwm_rt_frame *now = &p->fr[p->cur];
    const pwm_rt_ramp ramp = {{now->r0[0], now->r0[1]}, {now->dr[0], now->dr[1]}};
    p->n = (UUV_LEAN_IMAGE != 0) ? 0u : n; /* a lean image plans nothing */
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

void pwm_rt_ramp_q(pwm_rt_ramp *out, int32_t m_q15, uint32_t ph, uint32_t inc, uint32_t n) {
    const uint32_t ph1 = ph + inc * n; /* modulo 2^32: whole turns drop out */
    const int32_t r0[2] = {ref_q(m_q15, ph), ref_q(m_q15, ph - WT_PHASE_120)};
    const int32_t r1[2] = {ref_q(m_q15, ph1), ref_q(m_q15, ph1 - WT_PHASE_120)};
    ramp_from_knots(out, r0, r1, n);
}

/* m sin(ph) in Q23, rounded: the Q31 conversion (saturating at +-1) rounded by 8 bits. */
static int32_t ref_f32(float m, uint32_t ph) {
    return fp_shr_round_i32(fp_from_f32_q31(m * wt_sin_f32(ph)), 8u);
}

void pwm_rt_ramp_f32(pwm_rt_ramp *out, float m, uint32_t ph, uint32_t inc, uint32_t n) {
    const uint32_t ph1 = ph + inc * n;
    const int32_t r0[2] = {ref_f32(m, ph), ref_f32(m, ph - WT_PHASE_120)};
    const int32_t r1[2] = {ref_f32(m, ph1), ref_f32(m, ph1 - WT_PHASE_120)};
    ramp_from_knots(out, r0, r1, n);
}
