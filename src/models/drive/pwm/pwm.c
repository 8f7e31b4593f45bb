/*
 * Set-up and commands of the PWM modulator, both twins (pwm.h). Nothing here
 * runs at the 2 us rate: init divides, and the commands turn a frequency
 * into a phase increment at the controller's rate.
 */
#include "models/drive/pwm/pwm.h"

#include <stddef.h>

#include "fixedpoint/wavetable.h"

#define PWM_STEP_MIN_NS 100u
#define PWM_STEP_MAX_NS 1000000u
#define PWM_MIN_STEPS_PER_CARRIER 8.0
#define PWM_FREQ_LIMIT_HZ 32767.0 /* wt_phase_inc_q16 takes |f| < 32768 Hz */

/* Checks what both twins require of the parameters and the step. */
static pwm_status pwm_check(const pwm_params *p, uint32_t step_ns) {
    double steps_per_carrier;

    if (p->edges != PWM_EDGES_INTERPOLATED && p->edges != PWM_EDGES_SAMPLED &&
        p->edges != PWM_AVERAGED) {
        return PWM_ERR_EDGES;
    }
    if (step_ns < PWM_STEP_MIN_NS || step_ns > PWM_STEP_MAX_NS) {
        return PWM_ERR_STEP;
    }
    if (p->edges == PWM_AVERAGED) {
        return PWM_OK;
    }
    /* Written so that a NaN carrier fails. */
    if (!(p->carrier_hz > 0.0) || !(p->carrier_hz <= PWM_FREQ_LIMIT_HZ)) {
        return PWM_ERR_CARRIER;
    }
    steps_per_carrier = 1.0e9 / (p->carrier_hz * (double)step_ns);
    if (steps_per_carrier < PWM_MIN_STEPS_PER_CARRIER) {
        return PWM_ERR_CARRIER;
    }
    return PWM_OK;
}

/*
 * Carrier increment per step: the carrier frequency rounded to 2^-16 Hz;
 * 0 for the averaged modulator, which has no carrier.
 */
static uint32_t pwm_carrier_inc(const pwm_params *p, uint32_t step_ns) {
    if (p->edges == PWM_AVERAGED) {
        return 0u;
    }
    return wt_phase_inc_q16((int32_t)(p->carrier_hz * 65536.0 + 0.5), step_ns);
}

/*
 * The signed half of an increment, floored: the phase offset of the middle
 * of a step. The conversion back to unsigned is modulo 2^32 (defined).
 */
static uint32_t pwm_half_inc(uint32_t inc) {
    return (uint32_t)fp_shr_floor_i32(fp_from_u32_i32(inc), 1u);
}

/* ---- Fixed-point twin ---------------------------------------------------- */

pwm_status pwm_init_q(pwm_q *pw, const pwm_params *p, uint32_t step_ns) {
    pwm_status st;
    uint64_t dc;
    int32_t c0;

    if (pw == NULL || p == NULL) {
        return PWM_ERR_NULL;
    }
    st = pwm_check(p, step_ns);
    if (st != PWM_OK) {
        return st;
    }
    pw->step_ns = step_ns;
    pw->edges = p->edges;
    pw->inc_c = pwm_carrier_inc(p, step_ns);
    pw->ph_c = p->carrier_phase0;
    pw->ph_s = p->ref_phase0;
    pw->inc_s = 0u;
    pw->half_inc_s = 0u;
    pw->m = 0;
    /* |dc| = 4 * 32767 * inc_c / 2^32, rounded; at least 8 steps per period keep it <= 16384. */
    dc = ((uint64_t)4u * 32767u * (uint64_t)pw->inc_c + 0x80000000u) >> 32;
    pw->dc_abs = (dc < 1u) ? 1 : (int32_t)dc;
    pw->recip = (uint32_t)((0x80000000u + (uint32_t)pw->dc_abs / 2u) / (uint32_t)pw->dc_abs);
    c0 = (int32_t)wt_tri_q15(pw->ph_c) * 32768; /* Q30 units, as the step */
    pw->e[0] = -c0;
    pw->e[1] = -c0;
    pw->e[2] = -c0;
    pw->sat_count = 0u;
    return PWM_OK;
}

void pwm_command_inc_q(pwm_q *pw, q15_t m_index, uint32_t inc) {
    int32_t m = m_index;
    if (m < 0) {
        fp_count_sat(&pw->sat_count);
        m = 0;
    }
    pw->m = m;
    pw->inc_s = inc;
    pw->half_inc_s = pwm_half_inc(inc);
}

void pwm_command_q(pwm_q *pw, const pwm_cmd_q *cmd) {
    /* Q31 of 128 Hz is f * 2^24 / 1 Hz; Q16.16 hertz is that divided by 2^8. */
    int32_t f_q16 = fp_shr_round_i32(cmd->freq, 8u);
    pwm_command_inc_q(pw, cmd->m_index, wt_phase_inc_q16(f_q16, pw->step_ns));
}

/* ---- Float twin ------------------------------------------------------------ */

pwm_status pwm_init_f32(pwm_f32 *pw, const pwm_params *p, uint32_t step_ns) {
    pwm_status st;
    float c0;

    if (pw == NULL || p == NULL) {
        return PWM_ERR_NULL;
    }
    st = pwm_check(p, step_ns);
    if (st != PWM_OK) {
        return st;
    }
    pw->step_ns = step_ns;
    pw->edges = p->edges;
    pw->inc_c = pwm_carrier_inc(p, step_ns);
    pw->ph_c = p->carrier_phase0;
    pw->ph_s = p->ref_phase0;
    pw->inc_s = 0u;
    pw->half_inc_s = 0u;
    pw->m = 0.0f;
    /* The carrier changes by 4 inc_c / 2^32 (amplitude 1) per step. */
    pw->recip = (pw->inc_c == 0u) ? 1.0f : (float)(4294967296.0 / (4.0 * (double)pw->inc_c));
    c0 = wt_tri_f32(pw->ph_c);
    pw->e[0] = -c0;
    pw->e[1] = -c0;
    pw->e[2] = -c0;
    pw->sat_count = 0u;
    return PWM_OK;
}

void pwm_command_inc_f32(pwm_f32 *pw, float m_index, uint32_t inc) {
    float m = m_index;
    if (!(m >= 0.0f)) { /* negative or NaN */
        fp_count_sat(&pw->sat_count);
        m = 0.0f;
    } else if (m > 1.0f) {
        fp_count_sat(&pw->sat_count);
        m = 1.0f;
    }
    pw->m = m;
    pw->inc_s = inc;
    pw->half_inc_s = pwm_half_inc(inc);
}

/*
 * The frequency is rounded to 2^-16 Hz and turned into an increment by the
 * same exact integer function as the fixed twin, so equal frequencies give
 * equal phases in both twins. A NaN frequency gives 0 Hz.
 */
void pwm_command_f32(pwm_f32 *pw, const pwm_cmd_f32 *cmd) {
    float f = cmd->freq_hz;
    int64_t f_q16 = 0;
    if (f == f) {
        float scaled = f * 65536.0f;
        if (scaled > 2147418112.0f) {
            scaled = 2147418112.0f;
        } else if (scaled < -2147418112.0f) {
            scaled = -2147418112.0f;
        }
        f_q16 = (int64_t)((scaled >= 0.0f) ? scaled + 0.5f : scaled - 0.5f);
    }
    pwm_command_inc_f32(pw, cmd->m_index, wt_phase_inc_q16((int32_t)f_q16, pw->step_ns));
}
