/*
 * The fused 2 us step of the drive's switching path: the sine-triangle
 * modulator with sampled edges (pwm.h, PWM_EDGES_SAMPLED) followed by the
 * power stage (power_stage.h), in one inline function per twin, for the
 * executive's fast tick. It computes exactly what pwm_step_q() followed by
 * power_stage_step_q() computes (and the same for the float twins), bit
 * for bit; tests/unit/test_power_stage.c checks that over long runs. Only
 * the work is specialised, never the arithmetic:
 *
 *   - Carrier. The triangle table is linear between its nodes with a slope
 *     of 32767 Q23 counts per segment, so its interpolated lookup equals a
 *     closed form in the phase: with x = phase >> 7 (25 bits: segment and
 *     fraction) folded about the peak, y = x on the rising half and
 *     2^25 - x on the falling one,
 *         tri_q23 = -8388352 + y - ceil(y / 2^15),
 *     and the Q15 carrier is (tri_q23 + 2^23 + 2^7) >> 8 minus 2^15, as in
 *     wt_interp_q15(). The float table's lookup is exact too (every value
 *     is a multiple of 2^-23 below 1 in magnitude), so the float carrier is
 *     (y - 2^23) / 2^23. No table load, no multiplication.
 *   - Sampled duties are 0 or 1, so the inverter voltages are n_x v_dc / 3
 *     with n_x = 2 s_x - s_y - s_z in {-2, ..., 2}: in the fixed twin the
 *     general product (8 v3) (n_x 2^29) / 2^32 rounded is exactly n_x v3,
 *     and the DC-link current's rounded product sum is floor((T + 1) / 2)
 *     with T = (s_a - s_c) S_a + (s_b - s_c) S_b (S_x the sum of the old
 *     and new inductor currents; |T| <= 2^30 with the states clamped). In
 *     the float twin the small integer factors are exact, so the general
 *     expressions round alike.
 *   - The filter phases and the DC link are the inline pieces of
 *     power_stage_nodes.h, unchanged.
 *   - The modulator's state is read once and written once; the instance
 *     structs keep their meaning, so the general functions can continue
 *     from where the fused step stopped.
 */
#ifndef UUV_POWER_STAGE_FAST_H
#define UUV_POWER_STAGE_FAST_H

#include <stdint.h>

#include "fixedpoint/fixedpoint.h"
#include "fixedpoint/wavetable.h"
#include "models/power_stage.h"
#include "models/power_stage_nodes.h"
#include "models/pwm.h"

/*
 * The carrier's phase folded about its peak: y = x on the rising half,
 * 2^25 - x on the falling half, x = phase >> 7; y in [0, 2^24].
 */
static inline uint32_t ps_fast_fold(uint32_t ph_c) {
    const uint32_t x = ph_c >> WT_IGNORED_BITS;
    return (ph_c & WT_PHASE_HALF) ? (0x2000000u - x) : x;
}

/* wt_tri_q15(ph_c) in closed form (see above); all terms are non-negative. */
static inline int32_t ps_fast_tri_q15(uint32_t ph_c) {
    const uint32_t y = ps_fast_fold(ph_c);
    return (int32_t)((y - ((y + 32767u) >> 15) + 384u) >> 8) - 32768;
}

/* wt_tri_f32(ph_c) in closed form: (y - 2^23) / 2^23, exact. */
static inline float ps_fast_tri_f32(uint32_t ph_c) {
    return (float)((int32_t)ps_fast_fold(ph_c) - 8388608) * (1.0f / 8388608.0f);
}

/*
 * 1 when e > 0, else 0, for |e| < 2^31 (the modulator's comparison values):
 * the sign bit of -e, formed modulo 2^32. Two instructions, no branch.
 */
static inline int32_t ps_fast_pos_q(int32_t e) {
    return (int32_t)((0u - (uint32_t)e) >> 31);
}

/*
 * One fused step, fixed twin: pwm_step_q() with sampled edges (pw->edges
 * must be PWM_EDGES_SAMPLED) and power_stage_step_q() with the duties it
 * gives, the motor currents im_a, im_b (Q15 of 256 A) and the battery bat.
 * state receives the switch states held over the step (pwm_out_q.state).
 * Integer only, no division; total (the stage clamps and counts as in
 * power_stage_step_q()).
 */
static inline void ps_fast_step_q(pwm_q *pw, power_stage_q *ps, const ps_battery_q *bat,
                                  q15_t im_a15, q15_t im_b15, uint8_t state[3]) {
    const ps_coef_q *k = &ps->k;
    uint32_t sat = ps->sat_count;
    /* The comparison made at t_k is held over the step. */
    const int32_t sa = ps_fast_pos_q(pw->e[0]);
    const int32_t sb = ps_fast_pos_q(pw->e[1]);
    const int32_t sc = ps_fast_pos_q(pw->e[2]);
    /* The comparison at t_k+1 for the next step: m sin against c, Q30 units (pwm_step.c). */
    const uint32_t ph_c = pw->ph_c + pw->inc_c;
    const uint32_t ph_s = pw->ph_s + pw->inc_s;
    const int32_t c = ps_fast_tri_q15(ph_c) * 32768;
    const int32_t pa = pw->m * (int32_t)wt_sin_q15(ph_s);
    const int32_t pb = pw->m * (int32_t)wt_sin_q15(ph_s - WT_PHASE_120);
    pw->e[0] = pa - c;
    pw->e[1] = pb - c;
    pw->e[2] = -pa - pb - c;
    pw->ph_c = ph_c;
    pw->ph_s = ph_s;
    state[0] = (uint8_t)sa;
    state[1] = (uint8_t)sb;
    state[2] = (uint8_t)sc;

    /* Inverter: u_x = n_x v_dc / 3, v_dc / 3 rounded as in ps_inverter_q(). */
    const int32_t v3 = ps_hi_q(ps_mac_q(ps_acc_q(0), ps->v_dc, 0x55555555));
    const int32_t u_a = (2 * sa - sb - sc) * v3;
    const int32_t u_b = (2 * sb - sa - sc) * v3;
    /* Q15 of 256 A to Q3.28: exact. */
    const int32_t im_a = (int32_t)im_a15 * 8192;
    const int32_t im_b = (int32_t)im_b15 * 8192;
    const int32_t i0_a = ps->ph[0].i_l;
    const int32_t i0_b = ps->ph[1].i_l;
    ps_hist_q h;
    int32_t dv;

    ps_filter_history_q(k, &ps->ph[0], u_a, &h);
    dv = ps_filter_node_q(k, &ps->ph[0], &h, im_a);
    ps_filter_update_q(k, &ps->ph[0], &h, dv, im_a, &sat);
    ps_filter_history_q(k, &ps->ph[1], u_b, &h);
    dv = ps_filter_node_q(k, &ps->ph[1], &h, im_b);
    ps_filter_update_q(k, &ps->ph[1], &h, dv, im_b, &sat);

    /* DC-link current: floor((T + 1) / 2), |T| <= 2^30 (see above). */
    const int32_t t = (sa - sc) * (i0_a + ps->ph[0].i_l) + (sb - sc) * (i0_b + ps->ph[1].i_l);
    const int32_t i_dc = fp_shr_floor_i32(t + 1, 1u);
    ps->v_dc = ps_dclink_step_q(ps->v_dc, bat, k->neg_k_c, i_dc, &sat);
    ps->u[0] = u_a;
    ps->u[1] = u_b;
    ps->i_dc = i_dc;
    ps->sat_count = sat;
}

/* The float twin of ps_fast_step_q(): pwm_step_f32() (sampled) and power_stage_step_f32(). */
static inline void ps_fast_step_f32(pwm_f32 *pw, power_stage_f32 *ps, const ps_battery_f32 *bat,
                                    float im_a, float im_b, uint8_t state[3]) {
    const ps_coef_f32 *k = &ps->k;
    uint32_t sat = ps->sat_count;
    const int32_t sa = pw->e[0] > 0.0f;
    const int32_t sb = pw->e[1] > 0.0f;
    const int32_t sc = pw->e[2] > 0.0f;
    const uint32_t ph_c = pw->ph_c + pw->inc_c;
    const uint32_t ph_s = pw->ph_s + pw->inc_s;
    const float c = ps_fast_tri_f32(ph_c);
    const float ra = pw->m * wt_sin_f32(ph_s);
    const float rb = pw->m * wt_sin_f32(ph_s - WT_PHASE_120);
    pw->e[0] = ra - c;
    pw->e[1] = rb - c;
    pw->e[2] = (-ra - rb) - c;
    pw->ph_c = ph_c;
    pw->ph_s = ph_s;
    state[0] = (uint8_t)sa;
    state[1] = (uint8_t)sb;
    state[2] = (uint8_t)sc;

    /* (2 d_x - d_y) - d_z with d in {0, 1} is the small integer n_x, exactly. */
    const float v3 = ps->v_dc * (1.0f / 3.0f);
    const float u_a = v3 * (float)(2 * sa - sb - sc);
    const float u_b = v3 * (float)(2 * sb - sa - sc);
    const float i0_a = ps->ph[0].i_l;
    const float i0_b = ps->ph[1].i_l;
    ps_hist_f32 h;
    float dv;

    ps_filter_history_f32(k, &ps->ph[0], u_a, &h);
    dv = ps_filter_node_f32(k, &ps->ph[0], &h, im_a);
    ps_filter_update_f32(k, &ps->ph[0], &h, dv, im_a, &sat);
    ps_filter_history_f32(k, &ps->ph[1], u_b, &h);
    dv = ps_filter_node_f32(k, &ps->ph[1], &h, im_b);
    ps_filter_update_f32(k, &ps->ph[1], &h, dv, im_b, &sat);

    const float i_dc = 0.5f * ((float)(sa - sc) * (i0_a + ps->ph[0].i_l) +
                               (float)(sb - sc) * (i0_b + ps->ph[1].i_l));
    ps->v_dc = ps_dclink_step_f32(ps->v_dc, bat, k->neg_k_c, i_dc, &sat);
    ps->u[0] = u_a;
    ps->u[1] = u_b;
    ps->i_dc = i_dc;
    ps->sat_count = sat;
}

#endif /* UUV_POWER_STAGE_FAST_H */
