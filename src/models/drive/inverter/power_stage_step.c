/*
 * The 2 us step of the power stage, both twins: inverter, trapezoidal
 * filter (phases a and b; c = -a - b) and forward-Euler DC link, in that
 * order, from the pieces in power_stage_nodes.h. The DC link uses v_dc(k)
 * for the inverter voltages and the step-mean inductor currents for i_dc,
 * so the step is explicit in v_dc and implicit (trapezoidal) in the filter.
 */
#include "models/drive/inverter/power_stage.h"

#include "models/drive/inverter/power_stage_fast.h"
#include "models/drive/inverter/power_stage_nodes.h"

void power_stage_step_q(power_stage_q *ps, const power_stage_in_q *in) {
    const ps_coef_q *k = &ps->k;
    uint32_t sat = ps->sat_count; /* counted locally, stored once */
    const int32_t i0_a = ps->ph[0].i_l;
    const int32_t i0_b = ps->ph[1].i_l;
    /* Q15 of 256 A to Q3.28: exact. */
    const int32_t im_a = (int32_t)in->i_motor[0] * 8192;
    const int32_t im_b = (int32_t)in->i_motor[1] * 8192;
    int32_t u_a;
    int32_t u_b;
    int32_t dv;
    int32_t i_dc;
    ps_hist_q h;

    ps_inverter_q(ps->v_dc, in->duty, &u_a, &u_b);

    ps_filter_history_q(k, &ps->ph[0], u_a, &h);
    dv = ps_filter_node_q(k, &ps->ph[0], &h, im_a);
    ps_filter_update_q(k, &ps->ph[0], &h, dv, im_a, &sat);

    ps_filter_history_q(k, &ps->ph[1], u_b, &h);
    dv = ps_filter_node_q(k, &ps->ph[1], &h, im_b);
    ps_filter_update_q(k, &ps->ph[1], &h, dv, im_b, &sat);

    i_dc = ps_dc_current_q(in->duty, i0_a + ps->ph[0].i_l, i0_b + ps->ph[1].i_l);
    ps->v_dc = ps_dclink_step_q(ps->v_dc, &in->battery, k->neg_k_c, i_dc, &sat);
    ps->u[0] = u_a;
    ps->u[1] = u_b;
    ps->i_dc = i_dc;
    ps->sat_count = sat;
}

void power_stage_step_f32(power_stage_f32 *ps, const power_stage_in_f32 *in) {
    const ps_coef_f32 *k = &ps->k;
    const float i0_a = ps->ph[0].i_l;
    const float i0_b = ps->ph[1].i_l;
    float u_a;
    float u_b;
    float dv;
    float i_dc;
    ps_hist_f32 h;

    ps_inverter_f32(ps->v_dc, in->duty, &u_a, &u_b);

    ps_filter_history_f32(k, &ps->ph[0], u_a, &h);
    dv = ps_filter_node_f32(k, &ps->ph[0], &h, in->i_motor_a[0]);
    ps_filter_update_f32(k, &ps->ph[0], &h, dv, in->i_motor_a[0], &ps->sat_count);

    ps_filter_history_f32(k, &ps->ph[1], u_b, &h);
    dv = ps_filter_node_f32(k, &ps->ph[1], &h, in->i_motor_a[1]);
    ps_filter_update_f32(k, &ps->ph[1], &h, dv, in->i_motor_a[1], &ps->sat_count);

    const float t = ps_dc_sum_f32(in->duty, i0_a + ps->ph[0].i_l, i0_b + ps->ph[1].i_l);
    i_dc = 0.5f * t;
    ps->v_dc = ps_dclink_step_f32(ps->v_dc, &in->battery, k->neg_k_c, t, &ps->sat_count);
    ps->u[0] = u_a;
    ps->u[1] = u_b;
    ps->i_dc = i_dc;
}

void ps_fast_step_call_q(power_stage_q *ps, const ps_battery_q *bat, const int32_t duty[3],
                         int32_t im_a, int32_t im_b) {
    ps_fast_step_q(ps, bat, duty, im_a, im_b);
}

void ps_fast_step_call_f32(power_stage_f32 *ps, const ps_battery_f32 *bat,
                           const int32_t duty[3], float im_a, float im_b) {
    ps_fast_step_f32(ps, bat, duty, im_a, im_b);
}
