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
    *p = (pwm_rt){check.ph_c, check.inc_c, {0, 0}, {0, 0}, 0, sh};
    return PWM_OK;
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
