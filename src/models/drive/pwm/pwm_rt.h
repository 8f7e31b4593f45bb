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
 *   - The comparison is made at t_k and held over [t_k, t_k+1] (sampled
 *     edges), in Q23: leg x is on when r_x > c, the sign bit of c - r_x.
 *     r_c = -r_a - r_b, so the three references sum to zero.
 *
 * Scaling: references Q23 (2^23 = 1, |r| <= 2^23 for m <= 1), the carrier
 * Q23 in [-2^23, 2^23]; |c - r_x| and |c + r_a + r_b| stay below 2^25.
 */
#ifndef UUV_PWM_RT_H
#define UUV_PWM_RT_H

#include <stdint.h>

#include "models/drive/pwm/pwm.h"

#define PWM_RT_ONE 8388608 /* 2^23: 1 in the Q23 of the references and the carrier */

typedef struct {
    uint32_t ph_c;   /* carrier phase at t_k (2^32 = one turn) */
    uint32_t inc_c;  /* carrier increment per step */
    int32_t r[2];    /* references of legs a and b at t_k, Q23 */
    int32_t dr[2];   /* their change per step, Q23 */
} pwm_rt;

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

/*
 * One step: the leg states held over [t_k, t_k+1] (0 or 1 each, as
 * int32_t, for the inverter's arithmetic), then the carrier and the
 * references advance to t_k+1. Integer only, branch-free but for the
 * carrier's fold; total.
 */
static inline void pwm_rt_step(pwm_rt *p, int32_t s[3]) {
    const int32_t c = pwm_rt_carrier(p->ph_c);
    const int32_t ra = p->r[0];
    const int32_t rb = p->r[1];
    s[0] = pwm_rt_neg(c - ra);
    s[1] = pwm_rt_neg(c - rb);
    s[2] = pwm_rt_neg(c + ra + rb);
    p->ph_c += p->inc_c;
    p->r[0] = ra + p->dr[0];
    p->r[1] = rb + p->dr[1];
}

/*
 * Set-up from the parameters of pwm.h (edges must be PWM_EDGES_SAMPLED;
 * the carrier frequency, its increment and initial phase as pwm_init_q()
 * checks and computes them), references at zero. Returns PWM_OK, or the
 * error of pwm.h and leaves the instance unchanged. Set-up code: divides.
 */
pwm_status pwm_rt_init(pwm_rt *p, const pwm_params *pp, uint32_t step_ns);

/* Applies a frame's ramp (the boundary's work: four copies). */
static inline void pwm_rt_apply(pwm_rt *p, const pwm_rt_ramp *ramp) {
    p->r[0] = ramp->r0[0];
    p->r[1] = ramp->r0[1];
    p->dr[0] = ramp->dr[0];
    p->dr[1] = ramp->dr[1];
}

/*
 * The ramp of a frame of n steps (n >= 1) whose first step starts at the
 * reference phase ph (leg a; 2^32 = one turn) with increment inc per step
 * and modulation index m: r0 = m sin(ph), r1 = m sin(ph + n inc), slope
 * round((r1 - r0) / n), for both legs (b lags by 120 degrees). Fixed:
 * m Q15 in [0, 32767] (table sine Q15, product floored to Q23). Float: m
 * in [0, 1] (rounded to Q23). Motor-task work: one division per leg.
 */
void pwm_rt_ramp_q(pwm_rt_ramp *out, int32_t m_q15, uint32_t ph, uint32_t inc, uint32_t n);
void pwm_rt_ramp_f32(pwm_rt_ramp *out, float m, uint32_t ph, uint32_t inc, uint32_t n);

#endif /* UUV_PWM_RT_H */
