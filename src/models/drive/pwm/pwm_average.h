/*
 * The averaged modulator's references and duties (pwm_average_q/_f32,
 * pwm.h) as inline pieces, for the averaged stages that take the duties
 * alone (inverter_avg.h): each leg's reference m sin(theta_x) at the
 * middle of the step, the duty (1 + r_x) / 2, the phase advanced by a
 * step. The same operations as pwm_average_*(), which chain them.
 */
#ifndef UUV_PWM_AVERAGE_H
#define UUV_PWM_AVERAGE_H

#include <stdint.h>

#include "fixedpoint/fixedpoint.h"
#include "fixedpoint/wavetable.h"
#include "models/drive/pwm/pwm.h"

/*
 * m * sin in Q15 units, rounded (ties up), for the averaged duties. m in
 * [0, 32767] and |sin| <= 32767: the product fits int32_t.
 */
static inline int32_t pwm_ref_q(int32_t m, q15_t s) {
    return fp_shr_round_i32(m * (int32_t)s, 15u);
}

/*
 * (32768 + r + 1) / 2 floored, r in Q15 units. r_c = -r_a - r_b can reach
 * 32769 in magnitude (two table roundings), so the sum is in [0, 65538]
 * and the duty is clamped to 32768.
 */
static inline int32_t pwm_duty_avg_q(int32_t r) {
    uint32_t d = (uint32_t)(PWM_DUTY_ONE_Q + r + 1) >> 1;
    return (d > (uint32_t)PWM_DUTY_ONE_Q) ? PWM_DUTY_ONE_Q : (int32_t)d;
}

/* The references of legs a, b, c at the step's middle (Q15 units); the phase moves a step. */
static inline void pwm_average_refs_q(pwm_q *pw, int32_t r[3]) {
    const uint32_t ph_mid = pw->ph_s + pw->half_inc_s;
    r[0] = pwm_ref_q(pw->m, wt_sin_q15(ph_mid));
    r[1] = pwm_ref_q(pw->m, wt_sin_q15(ph_mid - WT_PHASE_120));
    r[2] = -r[0] - r[1];
    pw->ph_s += pw->inc_s;
}

/* (1 + r) / 2 clamped to [0, 1]. */
static inline float pwm_duty_avg_f32(float r) {
    float d = 0.5f + 0.5f * r;
    return (d > 1.0f) ? 1.0f : (d < 0.0f) ? 0.0f : d;
}

/* As pwm_average_refs_q(), in [-1, 1]. */
static inline void pwm_average_refs_f32(pwm_f32 *pw, float r[3]) {
    const uint32_t ph_mid = pw->ph_s + pw->half_inc_s;
    r[0] = pw->m * wt_sin_f32(ph_mid);
    r[1] = pw->m * wt_sin_f32(ph_mid - WT_PHASE_120);
    r[2] = -r[0] - r[1];
    pw->ph_s += pw->inc_s;
}

#endif /* UUV_PWM_AVERAGE_H */
