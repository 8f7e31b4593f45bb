/*
 * The power stage's 2 us step for switch states held over the step (the
 * real-time modulator of pwm_rt.h), in one inline function per twin, for
 * the executive's fast tick. It computes exactly what power_stage_step_q()
 * computes with duties of 0 or 1 (and the same for the float twins), bit
 * for bit; tests/unit/test_power_stage.c checks that over long runs. Only
 * the work is specialised, never the arithmetic:
 *
 *   - Held duties are 0 or 1, so the inverter voltages are n_x v_dc / 3
 *     with n_x = 2 s_x - s_y - s_z in {-2, ..., 2}: in the fixed twin the
 *     general product (8 v3) (n_x 2^29) / 2^32 rounded is exactly n_x v3,
 *     and the DC-link current's rounded product sum is floor((T + 1) / 2)
 *     with T = (s_a - s_c) S_a + (s_b - s_c) S_b (S_x the sum of the old
 *     and new inductor currents; |T| <= 2^30 with the states clamped). In
 *     the float twin the small integer factors are exact, so the general
 *     expressions round alike.
 *   - The motor currents come in the stage's own format (Q3.28 in the
 *     fixed twin), so nothing is narrowed or widened per step.
 *   - The filter phases and the DC link are the inline pieces of
 *     power_stage_nodes.h, unchanged.
 */
#ifndef UUV_POWER_STAGE_FAST_H
#define UUV_POWER_STAGE_FAST_H

#include <stdint.h>

#include "fixedpoint/fixedpoint.h"
#include "models/power_stage.h"
#include "models/power_stage_nodes.h"

/*
 * One step, fixed twin: power_stage_step_q() with the duties s[x] * 32768
 * (s[x] in {0, 1}, held over the step), the motor currents im_a, im_b
 * (Q3.28 of 256 A: the general step's Q15 inputs times 8192) and the
 * battery bat. Integer only, no division; total (the stage clamps and
 * counts as in power_stage_step_q()).
 */
static inline void ps_fast_step_q(power_stage_q *ps, const ps_battery_q *bat, const int32_t s[3],
                                  int32_t im_a, int32_t im_b) {
    const ps_coef_q *k = &ps->k;
    uint32_t sat = ps->sat_count;
    const int32_t sa = s[0];
    const int32_t sb = s[1];
    const int32_t sc = s[2];
    /* Inverter: u_x = n_x v_dc / 3, v_dc / 3 rounded as in ps_inverter_q(). */
    const int32_t v3 = ps_hi_q(ps_mac_q(ps_acc_q(0), ps->v_dc, 0x55555555));
    const int32_t u_a = (2 * sa - sb - sc) * v3;
    const int32_t u_b = (2 * sb - sa - sc) * v3;
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

/* The float twin of ps_fast_step_q(): power_stage_step_f32() with duties s[x] (0 or 1). */
static inline void ps_fast_step_f32(power_stage_f32 *ps, const ps_battery_f32 *bat,
                                    const int32_t s[3], float im_a, float im_b) {
    const ps_coef_f32 *k = &ps->k;
    uint32_t sat = ps->sat_count;
    const int32_t sa = s[0];
    const int32_t sb = s[1];
    const int32_t sc = s[2];

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

/*
 * The same steps out of line (power_stage_step.c), for callers that are not
 * the real-time path: one inlined copy there, one call everywhere else.
 */
void ps_fast_step_call_q(power_stage_q *ps, const ps_battery_q *bat, const int32_t s[3],
                         int32_t im_a, int32_t im_b);
void ps_fast_step_call_f32(power_stage_f32 *ps, const ps_battery_f32 *bat, const int32_t s[3],
                           float im_a, float im_b);

#endif /* UUV_POWER_STAGE_FAST_H */
