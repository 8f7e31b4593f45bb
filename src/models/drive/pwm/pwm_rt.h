/*
 * The real-time modulator: the sine-triangle PWM of pwm.h with sampled
 * edges, shaped for the 2 us interrupt. Both numeric builds use it as it
 * is (integers only in the step), so the switching pattern is the same
 * function of the controller's commands in both.
 *
 * What differs from pwm.h, and why:
 *   - The references are not looked up every step. The motor task, which
 *     runs once per motor frame of N steps, evaluates them exactly at the
 *     start and the end of the next frame, r = m sin(theta) and
 *     m sin(theta + N inc), and hands over the start value and the change
 *     per step (pwm_rt_ramp_*); the step adds the change. Between the
 *     knots the reference is the chord of the sinusoid: its largest
 *     deviation is m (w N T)^2 / 8, 1.5e-4 at 55 Hz and a 100 us frame,
 *     against the 2 % of a carrier ramp that one sampled step already
 *     quantises. The step does two additions instead of two table
 *     lookups and two multiplications.
 *   - The carrier is the triangle in closed form, exact in integers: with
 *     x = phase >> 7 (25 bits) folded about the peak, y = x on the rising
 *     half and 2^25 - x on the falling one, the carrier is y - 2^23 in Q23
 *     (-1 at phase 0, +1 at half a turn), linear between, as the table
 *     triangle of fixedpoint/wavetable.h is.
 *   - Two ways to turn the comparison into the inverter's input, both in
 *     Q23, leg x on while r_x > c (r_c = -r_a - r_b, so the three
 *     references sum to zero):
 *     sub-step (pwm_rt_substep, the default): the comparison e = r - c is
 *       linear over the step (the carrier between its knots, the reference
 *       on its ramp), so from its values e0 at t_k and e1 at t_k+1 the
 *       leg's on-time is exact: the whole step or none of it without a
 *       sign change, else the positive end's share e_pos / |e1 - e0| (the
 *       crossing located inside the step). The duty (Q15, 32768 = the
 *       step) is what the power stage applies, as the step's mean pole
 *       voltage (power_stage_fast.h). A step that holds a carrier knot is
 *       taken as straight between its ends: for m below 1 - 4 f_c T (0.96
 *       at 5 kHz and 2 us) no leg switches in such a step, above it a
 *       pulse narrower than the step may be lost.
 *     sampled (pwm_rt_step): the comparison made at t_k and held over
 *       [t_k, t_k+1], the sign bit of c - r_x: fixed-step switching, the
 *       paper's baseline (pulse widths in whole steps).
 *   - Dead time t_d (pwm_rt_dead_time; 0 by default, the paper's ideal
 *     switches): at every edge both switches of a leg are off for t_d, and
 *     the pole follows the diode the phase current takes: the lower one
 *     (pole low) for i_L >= 0, out of the leg, the upper one for i_L < 0.
 *     So with i_L >= 0 a rising edge comes t_d late, with i_L < 0 a
 *     falling one. Delaying an edge of a linear comparison by t_d is
 *     shifting it by t_d/T of its change per step: pwm_rt_substep_dt()
 *     resolves it with the sub-step arithmetic above, on e0 - s and
 *     e1 - s with s = (t_d / T)(e1 - e0) for the edges the current delays
 *     and s = 0 for the others. Over a carrier period it takes
 *     t_d f_c sign(i) of the duty away: the classic mean error
 *     V_dc t_d f_c sign(i) per leg.
 *
 * Scaling: references Q23 (2^23 = 1, |r| <= 2^23 for m <= 1), the carrier
 * Q23 in [-2^23, 2^23]; |c - r_x| and |c + r_a + r_b| stay below 2^25.
 */
#ifndef UUV_PWM_RT_H
#define UUV_PWM_RT_H

#include <stdbool.h>
#include <stdint.h>

#include "fixedpoint/fixedpoint.h"
#include "models/drive/pwm/pwm.h"
#include "uuv_config.h"

#define PWM_RT_ONE 8388608 /* 2^23: 1 in the Q23 of the references and the carrier */

/*
 * The plan of one frame (sub-step modulator, no dead time): the steps in
 * which the legs' states change, found once per frame by the motor task
 * (pwm_rt_prepare) from the same comparisons e = r - c at the step ends
 * that the step-by-step form makes. Between the knots of the carrier e is
 * monotone in each leg (the references change by less per step than the
 * carrier does), so each leg has at most one edge per half period of the
 * carrier, which is located exactly among the frame's knots by evaluating
 * e there; the edge's duty is pwm_rt_edge_duty() of that step's ends, as
 * the step-by-step form computes it. A step without an event applies the
 * legs' held states as whole-step duties; an event step applies its
 * duties and leaves its states. So the plan gives the step-by-step form's
 * duties and states bit for bit, with no carrier or comparison in the
 * step. A frame the plan cannot hold (more events than PWM_RT_EVENTS, a
 * reference faster than the carrier, frames above 65535 steps, or none
 * set: n = 0) continues step by step from the event that says so
 * (PWM_RT_PER_STEP). A lean image (uuv_config.h) plans nothing: it
 * computes every step on its own, without the plans' code.
 */
#define PWM_RT_EVENTS 8u   /* events a frame's plan holds; one more slot ends it */
#define PWM_RT_PER_STEP 2u /* an event's kind: every step from this one is computed on its own */

typedef struct {
    uint16_t at;      /* the step of the frame it falls in (0 = the first) */
    uint8_t s;        /* the legs' states at that step's end, bit x for leg x */
    uint8_t kind;     /* 0: whole-step duties; 1: some duty a share of the step; PWM_RT_PER_STEP */
    int32_t duty[3];  /* the legs' duties in that step, Q15 */
} pwm_rt_event;

typedef struct {
    uint32_t ph0;     /* carrier phase at the frame's first step (2^32 = one turn) */
    int32_t r0[2];    /* references of legs a and b there, Q23 */
    int32_t dr[2];    /* their change per step, Q23 */
    uint8_t s0;       /* the legs' states in the first steps, before any event */
    uint8_t s_end;    /* their states at the frame's end (after step n - 1) */
    bool ready;       /* prepared for the next pwm_rt_apply() */
} pwm_rt_frame;

typedef struct {
    uint32_t k;       /* steps of the frame in force taken */
    uint32_t next_at; /* the step of its next event (k and next_at adjacent: paired loads) */
    uint32_t next;    /* that event's index in ev */
    uint32_t cur;     /* the frame in force: fr[cur], its events from ev[cur * (PWM_RT_EVENTS + 1)] */
    uint32_t inc_c;   /* carrier increment per step */
    int32_t kd;       /* dead time over the step, t_d / T, Q16 (0: none) */
    uint32_t den_sh;  /* the duty division's pre-shift: a step's carrier change below 2^16 */
    uint32_t n;       /* steps per frame the plans cover (pwm_rt_frames; 0: step by step) */
    uint32_t dr_lim;  /* a plan takes slopes of magnitude below it (pwm_rt_frames; 0: none) */
    pwm_rt_frame fr[2];
    pwm_rt_event ev[2u * (PWM_RT_EVENTS + 1u)];
} pwm_rt;

/*
 * The frame in force, fr[pwm_rt_cur()], and the steps of it taken,
 * pwm_rt_k(). Without plans (n = 0) a frame starts again in place
 * (pwm_rt_apply()). A lean image (uuv_config.h), which plans nothing, steps
 * fr[0] only and moves its start with each step (pwm_rt_advance()), k
 * staying 0: its step forms no products.
 */
static inline uint32_t pwm_rt_cur(const pwm_rt *p) { return (UUV_LEAN_IMAGE != 0) ? 0u : p->cur; }
static inline uint32_t pwm_rt_k(const pwm_rt *p) { return (UUV_LEAN_IMAGE != 0) ? 0u : p->k; }

/* The step is taken: the carrier and the references advance to t_k+1 (see pwm_rt_k()). */
static inline void pwm_rt_advance(pwm_rt *p) __attribute__((always_inline));
static inline void pwm_rt_advance(pwm_rt *p) {
    if (UUV_LEAN_IMAGE != 0) {
        pwm_rt_frame *f = &p->fr[0];
        f->ph0 += p->inc_c;
        f->r0[0] = (int32_t)((uint32_t)f->r0[0] + (uint32_t)f->dr[0]);
        f->r0[1] = (int32_t)((uint32_t)f->r0[1] + (uint32_t)f->dr[1]);
    } else {
        p->k++;
    }
}

#define PWM_RT_DUTY_ONE 32768 /* a whole step's duty (Q15, as pwm.h's PWM_DUTY_ONE_Q) */

/*
 * The references at the end of the last frame ramped (pwm_rt_ramp_q/_f32),
 * the start of the next one when it begins there with the same modulation
 * index: its phase, the index in the build's arithmetic, the values.
 */
typedef struct {
    uint32_t ph;      /* the reference phase they are at (leg a) */
    int32_t m_q15;    /* the index they were formed with: fixed build */
    float m;          /* float build */
    int32_t r[2];     /* legs a and b, Q23 */
    bool valid;       /* false until a frame has been ramped */
} pwm_rt_knots;

/* What the motor task hands the step for one frame: the references' start and slope. */
typedef struct {
    int32_t r0[2];   /* references a, b at the frame's first step, Q23 */
    int32_t dr[2];   /* change per step, Q23 */
} pwm_rt_ramp;

/* Carrier at phase ph, Q23: -2^23 at phase 0 (valley), +2^23 at half a turn. */
static inline int32_t pwm_rt_carrier(uint32_t ph) {
    const uint32_t x = ph >> 7;
    const uint32_t y = ((ph & 0x80000000u) != 0u) ? (0x2000000u - x) : x;
    return (int32_t)y - PWM_RT_ONE;
}

/* 1 when v < 0 (|v| < 2^31): the sign bit, formed modulo 2^32. */
static inline int32_t pwm_rt_neg(int32_t v) {
    return (int32_t)((uint32_t)v >> 31);
}

/* The references of legs a and b at step k of the frame in force, Q23 (modulo 2^32 as stepped). */
static inline int32_t pwm_rt_ref(const pwm_rt_frame *f, int x, uint32_t k) {
    const uint32_t r = (uint32_t)f->r0[x] + k * (uint32_t)f->dr[x];
    return (int32_t)r;
}

/*
 * One step: the leg states held over [t_k, t_k+1] (0 or 1 each, as
 * int32_t, for the inverter's arithmetic), then the step is taken.
 * Integer only, branch-free but for the carrier's fold; total.
 */
static inline void pwm_rt_step(pwm_rt *p, int32_t s[3]) {
    const pwm_rt_frame *f = &p->fr[pwm_rt_cur(p)];
    const uint32_t k = pwm_rt_k(p);
    const int32_t c = pwm_rt_carrier(f->ph0 + k * p->inc_c);
    const int32_t ra = pwm_rt_ref(f, 0, k);
    const int32_t rb = pwm_rt_ref(f, 1, k);
    s[0] = pwm_rt_neg(c - ra);
    s[1] = pwm_rt_neg(c - rb);
    s[2] = pwm_rt_neg(c + ra + rb);
    pwm_rt_advance(p);
}

/* The comparisons e = r - c of the three legs at step j of frame f. */
static inline void pwm_rt_e_at(const pwm_rt_frame *f, uint32_t inc, uint32_t j, int32_t e[3]) {
    const int32_t c = pwm_rt_carrier(f->ph0 + j * inc);
    const int32_t ra = pwm_rt_ref(f, 0, j);
    const int32_t rb = pwm_rt_ref(f, 1, j);
    e[0] = ra - c;
    e[1] = rb - c;
    e[2] = -ra - rb - c;
}

/*
 * The comparisons e = r - c of the three legs at t_k (e0) and t_k+1 (e1),
 * Q23: pwm_rt_e_at() at k and k + 1, the second from the first's phase and
 * references by one step (the same sums modulo 2^32).
 */
static inline void pwm_rt_ends(const pwm_rt *p, int32_t e0[3], int32_t e1[3]) {
    const pwm_rt_frame *f = &p->fr[pwm_rt_cur(p)];
    const uint32_t k = pwm_rt_k(p);
    const uint32_t ph = f->ph0 + k * p->inc_c;
    const int32_t c0 = pwm_rt_carrier(ph);
    const int32_t c1 = pwm_rt_carrier(ph + p->inc_c);
    const uint32_t ra = (uint32_t)f->r0[0] + k * (uint32_t)f->dr[0];
    const uint32_t rb = (uint32_t)f->r0[1] + k * (uint32_t)f->dr[1];
    const uint32_t ra1 = ra + (uint32_t)f->dr[0];
    const uint32_t rb1 = rb + (uint32_t)f->dr[1];
    e0[0] = (int32_t)ra - c0;
    e0[1] = (int32_t)rb - c0;
    e0[2] = (int32_t)(0u - ra - rb) - c0;
    e1[0] = (int32_t)ra1 - c1;
    e1[1] = (int32_t)rb1 - c1;
    e1[2] = (int32_t)(0u - ra1 - rb1) - c1;
}

/*
 * The on-time of a leg over a step whose comparison goes linearly from e0
 * to e1 (Q23, |e0|, |e1| < 2^30), Q15 of the step, when the sign changes
 * inside it (e0 > 0 >= e1 or e0 <= 0 < e1): e_pos / (e_pos - e_neg). The
 * division is of operands below 2^16: both shifted right by sh (set-up: a
 * step's carrier change below 2^16) and, if the change is still above
 * 2^16, by more; the quotient is at most 32768 (e_pos <= the change, and
 * the divisor is rounded up by its lowest bit). Integer only; total; out
 * of line (pwm_rt.c): it runs in the few steps with an edge.
 */
int32_t pwm_rt_edge_duty(int32_t e0, int32_t e1, uint32_t sh);

/* The on-time of a leg over a step (Q15): the whole step or none without an edge. */
static inline int32_t pwm_rt_duty(int32_t e0, int32_t e1, uint32_t sh) {
    if ((e0 > 0) == (e1 > 0)) {
        return (e1 > 0) ? PWM_RT_DUTY_ONE : 0;
    }
    return pwm_rt_edge_duty(e0, e1, sh);
}

/*
 * One sampled step as duties: the held states of pwm_rt_step() in s and
 * as duties of a whole step or none (Q15) in duty.
 */
static inline void pwm_rt_sampled(pwm_rt *p, int32_t s[3], int32_t duty[3]) {
    pwm_rt_step(p, s);
    duty[0] = s[0] * PWM_RT_DUTY_ONE;
    duty[1] = s[1] * PWM_RT_DUTY_ONE;
    duty[2] = s[2] * PWM_RT_DUTY_ONE;
}

/*
 * One sub-step computed on its own (step by step): the duties of the three
 * legs over [t_k, t_k+1] (Q15) and their states at t_k+1 (0 or 1), then the
 * step is taken. No dead time (pwm_rt_substep_dt() takes it). Integer
 * only; total.
 */
static inline void pwm_rt_substep_each(pwm_rt *p, int32_t s[3], int32_t duty[3]) {
    int32_t e0[3];
    int32_t e1[3];
    pwm_rt_ends(p, e0, e1);
    for (int x = 0; x < 3; x++) {
        duty[x] = pwm_rt_duty(e0[x], e1[x], p->den_sh);
        s[x] = pwm_rt_neg(-e1[x]);
    }
    pwm_rt_advance(p);
}

/*
 * An event step of the plan (pwm_rt.c, out of line): its duties and
 * states, and the next event; a PWM_RT_PER_STEP event computes the step
 * on its own and stays the next. Takes the step.
 */
void pwm_rt_event_take(pwm_rt *p, int32_t s[3], int32_t duty[3]);

/*
 * One sub-step by the frame's plan: pwm_rt_substep_each()'s duties and
 * states bit for bit, with s holding the states of the step before (the
 * caller keeps them between steps, and nothing else may change them: the
 * faulted path takes pwm_rt_substep_each()). Outside the event steps the
 * held states are the duties. Integer only; total.
 */
static inline void pwm_rt_substep(pwm_rt *p, int32_t s[3], int32_t duty[3]) {
    const uint32_t k = p->k;
    if (UUV_LEAN_IMAGE != 0) {
        pwm_rt_substep_each(p, s, duty); /* a lean image plans nothing (uuv_config.h) */
    } else if (k != p->next_at) {
        duty[0] = s[0] * PWM_RT_DUTY_ONE;
        duty[1] = s[1] * PWM_RT_DUTY_ONE;
        duty[2] = s[2] * PWM_RT_DUTY_ONE;
        p->k = k + 1u;
    } else {
        pwm_rt_event_take(p, s, duty);
    }
}

/* One step by the modulator in force: sampled, or sub-step by the plan (no dead time). */
static inline void pwm_rt_duties(pwm_rt *p, bool sampled, int32_t s[3], int32_t duty[3])
    __attribute__((always_inline));
static inline void pwm_rt_duties(pwm_rt *p, bool sampled, int32_t s[3], int32_t duty[3]) {
    if (sampled) {
        pwm_rt_sampled(p, s, duty);
    } else {
        pwm_rt_substep(p, s, duty);
    }
}

/* The same with each step computed on its own (the faulted path's: s may be forced). */
static inline void pwm_rt_duties_each(pwm_rt *p, bool sampled, int32_t s[3], int32_t duty[3]) {
    if (sampled) {
        pwm_rt_sampled(p, s, duty);
    } else {
        pwm_rt_substep_each(p, s, duty);
    }
}

/*
 * The same with the dead time p->kd and the phase currents that decide
 * which edges it delays: neg[x] nonzero when leg x's current flows into
 * the leg (i_L < 0). The comparison of a leg whose delayed edges go its
 * way (rising with neg[x] == 0, falling with neg[x] != 0) is shifted by
 * s = kd (e1 - e0) / 2^16 before its duty and state are formed.
 */
static inline void pwm_rt_substep_dt(pwm_rt *p, const int32_t neg[3], int32_t s[3],
                                     int32_t duty[3]) {
    int32_t e0[3];
    int32_t e1[3];
    pwm_rt_ends(p, e0, e1);
    for (int x = 0; x < 3; x++) {
        const int32_t de = e1[x] - e0[x];
        const bool delayed = (neg[x] != 0) ? (de < 0) : (de > 0);
        const int32_t sft =
            delayed ? (int32_t)fp_shr_floor_i64((int64_t)de * p->kd, 16u) : 0;
        duty[x] = pwm_rt_duty(e0[x] - sft, e1[x] - sft, p->den_sh);
        s[x] = pwm_rt_neg(sft - e1[x]);
    }
    pwm_rt_advance(p);
}

/*
 * The dead time of the real-time modulator: t_d = dead_ns against the
 * step step_ns, at most 10 us and at most 8 steps (PWM_ERR_STEP
 * otherwise, the instance unchanged). Set-up code: divides.
 */
pwm_status pwm_rt_dead_time(pwm_rt *p, uint32_t dead_ns, uint32_t step_ns);

/*
 * Set-up from the parameters of pwm.h (edges must be PWM_EDGES_SAMPLED;
 * the carrier frequency, its increment and initial phase as pwm_init_q()
 * checks and computes them), references at zero, no plans (every step
 * computed on its own). Returns PWM_OK, or the error of pwm.h and leaves
 * the instance unchanged. Set-up code: divides.
 */
pwm_status pwm_rt_init(pwm_rt *p, const pwm_params *pp, uint32_t step_ns);

/*
 * Frames of n steps planned (n = 0: none, every step computed on its own;
 * the sub-step modulator without dead time uses them): plans the frame in
 * force from its start, its first step an event. Set-up code.
 */
void pwm_rt_frames(pwm_rt *p, uint32_t n);

/*
 * The motor task's side: plans the frame that the next pwm_rt_apply() starts
 * n steps after the start of the frame in force, which must be given the
 * same ramp. Integer only; a few divisions per edge.
 */
void pwm_rt_prepare(pwm_rt *p, const pwm_rt_ramp *ramp);

/* Plans frame c from carrier phase ph with the ramp, its first step an event (pwm_rt.c). */
void pwm_rt_plan(pwm_rt *p, uint32_t c, uint32_t ph, const pwm_rt_ramp *ramp);

/*
 * Starts a frame with the ramp (the boundary's work): the frame prepared
 * for it when it starts where the frame in force ends, else planned here.
 */
static inline void pwm_rt_apply(pwm_rt *p, const pwm_rt_ramp *ramp) {
    if (UUV_LEAN_IMAGE != 0 || p->n == 0u) {
        /* No plans: the frame in force starts again here (its event the one that hands every
         * step over). */
        pwm_rt_frame *f = &p->fr[pwm_rt_cur(p)];
        f->ph0 += pwm_rt_k(p) * p->inc_c;
        f->r0[0] = ramp->r0[0];
        f->r0[1] = ramp->r0[1];
        f->dr[0] = ramp->dr[0];
        f->dr[1] = ramp->dr[1];
        p->k = 0u;
        if (UUV_LEAN_IMAGE == 0) {
            p->next_at = 0u;
        }
        return;
    }
    const uint32_t c = p->cur ^ 1u;
    const uint32_t ph = p->fr[p->cur].ph0 + p->k * p->inc_c;
    pwm_rt_frame *f = &p->fr[c];
    if (!f->ready || f->ph0 != ph) {
        pwm_rt_plan(p, c, ph, ramp);
    }
    f->ready = false;
    p->cur = c;
    p->k = 0u;
    p->next = c * (PWM_RT_EVENTS + 1u);
    p->next_at = p->ev[p->next].at;
}

/* The carrier phase at the frame's step k now (the step-by-step form's state). */
static inline uint32_t pwm_rt_phase(const pwm_rt *p) {
    return p->fr[pwm_rt_cur(p)].ph0 + pwm_rt_k(p) * p->inc_c;
}

/* The reference of leg x (a or b) now, and its change per step. */
static inline int32_t pwm_rt_ref_now(const pwm_rt *p, int x) {
    return pwm_rt_ref(&p->fr[pwm_rt_cur(p)], x, pwm_rt_k(p));
}
static inline int32_t pwm_rt_slope(const pwm_rt *p, int x) { return p->fr[pwm_rt_cur(p)].dr[x]; }

/*
 * n steps taken by a port's own stepping of the same model (the desk's
 * leaps and lanes): the frame's count moves on, and its next event past
 * them (unplanned frames: the count only, as the sampled steps leave them).
 * The caller sets the legs' states after them.
 */
void pwm_rt_skip(pwm_rt *p, uint32_t n);

/*
 * The same for n sub-step modulator steps: in an unplanned frame (n = 0
 * frames, pwm_rt_frames()) the next step is then computed on its own, as
 * pwm_rt_substep()'s steps one by one leave it (their per-step event).
 * Desk only (exact leaps, the batch's lanes).
 */
static inline void pwm_rt_skip_substep(pwm_rt *p, uint32_t n) {
    pwm_rt_skip(p, n);
    if (p->n == 0u) {
        p->next_at = p->k;
    }
}

/* Bit x of b as a leg state, 0 or 1. */
static inline int32_t pwm_rt_bit(uint32_t b, uint32_t x) {
    int32_t v = 0;
    if (((b >> x) & 1u) != 0u) {
        v = 1;
    }
    return v;
}

/* The states for the first step of the frame in force, before any event (a path's start). */
static inline void pwm_rt_states(const pwm_rt *p, int32_t s[3]) {
    const uint32_t b = p->fr[pwm_rt_cur(p)].s0;
    s[0] = pwm_rt_bit(b, 0u);
    s[1] = pwm_rt_bit(b, 1u);
    s[2] = pwm_rt_bit(b, 2u);
}

/*
 * The ramp of a frame of n steps (n >= 1) whose first step starts at the
 * reference phase ph (leg a; 2^32 = one turn) with increment inc per step
 * and modulation index m: r0 = m sin(ph), r1 = m sin(ph + n inc), slope
 * round((r1 - r0) / n), for both legs (b lags by 120 degrees). Fixed:
 * m Q15 in [0, 32767] (table sine Q15, product floored to Q23). Float: m
 * in [0, 1] (rounded to Q23). Motor-task work: one division per leg.
 * With end (NULL: none), the references at the frame's end are kept there,
 * and a frame that starts where the last one ramped ended, with the same
 * index, takes them as its start instead of forming them again: the same
 * values, two table sines fewer in the frames between the controller's
 * commands.
 */
void pwm_rt_ramp_q(pwm_rt_ramp *out, pwm_rt_knots *end, int32_t m_q15, uint32_t ph, uint32_t inc,
                   uint32_t n);
void pwm_rt_ramp_f32(pwm_rt_ramp *out, pwm_rt_knots *end, float m, uint32_t ph, uint32_t inc,
                     uint32_t n);

#endif /* UUV_PWM_RT_H */
