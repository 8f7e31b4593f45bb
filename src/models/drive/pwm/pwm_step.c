/*
 * The 2 us steps of the PWM modulator, both twins (algorithm in pwm.h).
 * Per step: two phase additions, three table lookups (carrier and two
 * references; the third reference is minus the sum of the other two), two
 * multiplications by m, and per leg a sign test, plus one multiplication in
 * a step where that leg switches.
 */
#include "models/drive/pwm/pwm.h"

#include "fixedpoint/wavetable.h"
#include "models/drive/pwm/pwm_average.h"

/* The three switch states of a step. */
static inline void pwm_states(uint8_t state[3], int a, int b, int c) {
    state[0] = (uint8_t)a;
    state[1] = (uint8_t)b;
    state[2] = (uint8_t)c;
}

/* ---- Fixed-point twin ---------------------------------------------------- */

/*
 * Duty of one leg over a step whose comparison went from e0 (start) to e1
 * (end), both in Q30 units (m sin * 2^15 against c * 2^15). Without a sign
 * change the leg did not switch (0 or 32768). Otherwise the on-time is the
 * positive end value over the change of e, taken as dc_abs * 2^15: pos is
 * brought to Q15 units (pos / 2^15, pos > 0 so the shift is of a positive
 * value), clamped to dc_abs, and scaled by recip = 2^31 / dc_abs, which
 * bounds the unsigned product by 2^31 + dc_abs / 2 and the duty by 32768.
 */
static inline int32_t pwm_duty_interp_q(int32_t e0, int32_t e1, int32_t dc_abs, uint32_t recip) {
    uint32_t pos;
    if (e1 > 0) {
        if (e0 > 0) {
            return PWM_DUTY_ONE_Q;
        }
        pos = (uint32_t)e1 >> 15;
    } else {
        if (e0 <= 0) {
            return 0;
        }
        pos = (uint32_t)e0 >> 15;
    }
    if (pos > (uint32_t)dc_abs) {
        pos = (uint32_t)dc_abs;
    }
    return (int32_t)((pos * recip + 0x8000u) >> 16);
}

/*
 * One switching step. The comparison m sin > c is made exactly in Q30
 * units: m * sin (both Q15, |product| <= 32767^2) against c * 2^15. With
 * |sin_a + sin_b| <= 32769 (two table values within 1 LSB each), every e
 * is below 32767 * 32769 + 32767 * 32768 < 2^31 in magnitude: no overflow.
 */
static void pwm_switch_q(pwm_q *pw, pwm_out_q *out) {
    const uint32_t ph_c = pw->ph_c + pw->inc_c; /* unsigned: wraps with the turn */
    const uint32_t ph_s = pw->ph_s + pw->inc_s;
    const int32_t c = (int32_t)wt_tri_q15(ph_c) * 32768;
    const int32_t pa = pw->m * (int32_t)wt_sin_q15(ph_s);
    const int32_t pb = pw->m * (int32_t)wt_sin_q15(ph_s - WT_PHASE_120);
    const int32_t ea = pa - c;
    const int32_t eb = pb - c;
    const int32_t ec = -pa - pb - c;

    if (pw->edges == PWM_EDGES_INTERPOLATED) {
        out->duty[0] = pwm_duty_interp_q(pw->e[0], ea, pw->dc_abs, pw->recip);
        out->duty[1] = pwm_duty_interp_q(pw->e[1], eb, pw->dc_abs, pw->recip);
        out->duty[2] = pwm_duty_interp_q(pw->e[2], ec, pw->dc_abs, pw->recip);
        pwm_states(out->state, ea > 0, eb > 0, ec > 0);
    } else {
        out->duty[0] = (pw->e[0] > 0) ? PWM_DUTY_ONE_Q : 0;
        out->duty[1] = (pw->e[1] > 0) ? PWM_DUTY_ONE_Q : 0;
        out->duty[2] = (pw->e[2] > 0) ? PWM_DUTY_ONE_Q : 0;
        pwm_states(out->state, pw->e[0] > 0, pw->e[1] > 0, pw->e[2] > 0);
    }
    pw->e[0] = ea;
    pw->e[1] = eb;
    pw->e[2] = ec;
    pw->ph_c = ph_c;
    pw->ph_s = ph_s;
}

void pwm_average_q(pwm_q *pw, pwm_out_q *out) {
    int32_t r[3];
    pwm_average_refs_q(pw, r);
    out->duty[0] = pwm_duty_avg_q(r[0]);
    out->duty[1] = pwm_duty_avg_q(r[1]);
    out->duty[2] = pwm_duty_avg_q(r[2]);
    pwm_states(out->state, r[0] > 0, r[1] > 0, r[2] > 0);
}

/* ---- Float twin ------------------------------------------------------------ */

/* As pwm_duty_interp_q(): the positive end value times 1 / |dc|, at most 1. */
static inline float pwm_duty_interp_f32(float e0, float e1, float recip) {
    float pos;
    float d;
    if (e1 > 0.0f) {
        if (e0 > 0.0f) {
            return 1.0f;
        }
        pos = e1;
    } else {
        if (!(e0 > 0.0f)) {
            return 0.0f;
        }
        pos = e0;
    }
    d = pos * recip;
    return (d > 1.0f) ? 1.0f : d;
}

static void pwm_switch_f32(pwm_f32 *pw, pwm_out_f32 *out) {
    const uint32_t ph_c = pw->ph_c + pw->inc_c;
    const uint32_t ph_s = pw->ph_s + pw->inc_s;
    const float c = wt_tri_f32(ph_c);
    const float ra = pw->m * wt_sin_f32(ph_s);
    const float rb = pw->m * wt_sin_f32(ph_s - WT_PHASE_120);
    const float ea = ra - c;
    const float eb = rb - c;
    const float ec = (-ra - rb) - c;

    if (pw->edges == PWM_EDGES_INTERPOLATED) {
        out->duty[0] = pwm_duty_interp_f32(pw->e[0], ea, pw->recip);
        out->duty[1] = pwm_duty_interp_f32(pw->e[1], eb, pw->recip);
        out->duty[2] = pwm_duty_interp_f32(pw->e[2], ec, pw->recip);
        pwm_states(out->state, ea > 0.0f, eb > 0.0f, ec > 0.0f);
    } else {
        out->duty[0] = (pw->e[0] > 0.0f) ? 1.0f : 0.0f;
        out->duty[1] = (pw->e[1] > 0.0f) ? 1.0f : 0.0f;
        out->duty[2] = (pw->e[2] > 0.0f) ? 1.0f : 0.0f;
        pwm_states(out->state, pw->e[0] > 0.0f, pw->e[1] > 0.0f, pw->e[2] > 0.0f);
    }
    pw->e[0] = ea;
    pw->e[1] = eb;
    pw->e[2] = ec;
    pw->ph_c = ph_c;
    pw->ph_s = ph_s;
}

void pwm_average_f32(pwm_f32 *pw, pwm_out_f32 *out) {
    float r[3];
    pwm_average_refs_f32(pw, r);
    out->duty[0] = pwm_duty_avg_f32(r[0]);
    out->duty[1] = pwm_duty_avg_f32(r[1]);
    out->duty[2] = pwm_duty_avg_f32(r[2]);
    pwm_states(out->state, r[0] > 0.0f, r[1] > 0.0f, r[2] > 0.0f);
}

/* ---- Dispatch on the mode ---------------------------------------------------- */

void pwm_step_q(pwm_q *pw, pwm_out_q *out) {
    if (pw->edges == PWM_AVERAGED) {
        pwm_average_q(pw, out);
        return;
    }
    pwm_switch_q(pw, out);
}

void pwm_step_f32(pwm_f32 *pw, pwm_out_f32 *out) {
    if (pw->edges == PWM_AVERAGED) {
        pwm_average_f32(pw, out);
        return;
    }
    pwm_switch_f32(pw, out);
}
