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
#include "models/drive/inverter/power_stage.h"
#include "models/drive/inverter/power_stage_nodes.h"

/* What the pieces of one step carry between them (fixed twin). */
typedef struct {
    int32_t dd[2]; /* s_a - s_c, s_b - s_c */
    int32_t t;     /* the DC-link current's sum T, formed phase by phase */
    uint32_t sat;  /* the stage's clamp count, kept in a local */
} ps_fast_q;

/* Start of a step with the held states s[x] in {0, 1}: inverter voltages. */
static inline void ps_fast_begin_q(power_stage_q *ps, const int32_t s[3], ps_fast_q *f) {
    const int32_t sc = s[2];
    /* Inverter: u_x = n_x v_dc / 3, v_dc / 3 rounded as in ps_inverter_q(). */
    const int32_t v3 = ps_hi_q(ps_mac_q(ps_acc_q(0), ps->v_dc, 0x55555555));
    ps->u[0] = (2 * s[0] - s[1] - sc) * v3;
    ps->u[1] = (2 * s[1] - s[0] - sc) * v3;
    f->dd[0] = s[0] - sc;
    f->dd[1] = s[1] - sc;
    f->t = 0;
    f->sat = ps->sat_count;
}

/*
 * Filter phase x (0 or 1) with the motor current im (Q3.28 of 256 A: the
 * general step's Q15 input times 8192); adds dd_x S_x to T, so that after
 * both phases T = dd_a S_a + dd_b S_b as the sum above.
 */
static inline void ps_fast_phase_q(power_stage_q *ps, ps_fast_q *f, int x, int32_t im) {
    const ps_coef_q *k = &ps->k;
    ps_phase_q *ph = &ps->ph[x];
    ps_hist_q h;
    const int32_t i0 = ph->i_l;
    ps_filter_history_q(k, ph, ps->u[x], &h);
    const int32_t dv = ps_filter_node_q(k, ph, &h, im);
    ps_filter_update_q(k, ph, &h, dv, im, &f->sat);
    f->t += f->dd[x] * (i0 + ph->i_l);
}

/* End of the step: the DC-link current and the DC link with the battery bat. */
static inline void ps_fast_end_q(power_stage_q *ps, const ps_battery_q *bat, const ps_fast_q *f) {
    uint32_t sat = f->sat;
    /* DC-link current: floor((T + 1) / 2), |T| <= 2^30 (see above). */
    const int32_t i_dc = fp_shr_floor_i32(f->t + 1, 1u);
    ps->v_dc = ps_dclink_step_q(ps->v_dc, bat, ps->k.neg_k_c, i_dc, &sat);
    ps->i_dc = i_dc;
    ps->sat_count = sat;
}

/*
 * One step, fixed twin: power_stage_step_q() with the duties s[x] * 32768
 * (s[x] in {0, 1}, held over the step), the motor currents im_a, im_b
 * (Q3.28 of 256 A) and the battery bat. Integer only, no division; total
 * (the stage clamps and counts as in power_stage_step_q()).
 */
static inline void ps_fast_step_q(power_stage_q *ps, const ps_battery_q *bat, const int32_t s[3],
                                  int32_t im_a, int32_t im_b) {
    ps_fast_q f;
    ps_fast_begin_q(ps, s, &f);
    ps_fast_phase_q(ps, &f, 0, im_a);
    ps_fast_phase_q(ps, &f, 1, im_b);
    ps_fast_end_q(ps, bat, &f);
}

/*
 * The float twins of the pieces and of ps_fast_step_q(): power_stage_step_f32()
 * with duties s[x] (0 or 1), its expressions rounded in its order.
 */
typedef struct {
    float dd[2];  /* s_a - s_c, s_b - s_c (exact) */
    float t;      /* the DC-link current's sum, formed phase by phase */
    uint32_t sat; /* the stage's clamp count, kept in a local */
} ps_fast_f32;

static inline void ps_fast_begin_f32(power_stage_f32 *ps, const int32_t s[3], ps_fast_f32 *f) {
    const int32_t sc = s[2];
    /* (2 d_x - d_y) - d_z with d in {0, 1} is the small integer n_x, exactly. */
    const float v3 = ps->v_dc * (1.0f / 3.0f);
    ps->u[0] = v3 * (float)(2 * s[0] - s[1] - sc);
    ps->u[1] = v3 * (float)(2 * s[1] - s[0] - sc);
    f->dd[0] = (float)(s[0] - sc);
    f->dd[1] = (float)(s[1] - sc);
    f->t = 0.0f;
    f->sat = ps->sat_count;
}

static inline void ps_fast_phase_f32(power_stage_f32 *ps, ps_fast_f32 *f, int x, float im) {
    const ps_coef_f32 *k = &ps->k;
    ps_phase_f32 *ph = &ps->ph[x];
    ps_hist_f32 h;
    const float i0 = ph->i_l;
    ps_filter_history_f32(k, ph, ps->u[x], &h);
    const float dv = ps_filter_node_f32(k, ph, &h, im);
    ps_filter_update_f32(k, ph, &h, dv, im, &f->sat);
    /* dd_a S_a, then + dd_b S_b: the general step's sum, in its order
     * (phase 0 assigns, so that no 0 + (-0) changes a zero's sign). */
    const float term = f->dd[x] * (i0 + ph->i_l);
    f->t = (x == 0) ? term : f->t + term;
}

static inline void ps_fast_end_f32(power_stage_f32 *ps, const ps_battery_f32 *bat,
                                   const ps_fast_f32 *f) {
    uint32_t sat = f->sat;
    const float i_dc = 0.5f * f->t;
    ps->v_dc = ps_dclink_step_f32(ps->v_dc, bat, ps->k.neg_k_c, i_dc, &sat);
    ps->i_dc = i_dc;
    ps->sat_count = sat;
}

static inline void ps_fast_step_f32(power_stage_f32 *ps, const ps_battery_f32 *bat,
                                    const int32_t s[3], float im_a, float im_b) {
    ps_fast_f32 f;
    ps_fast_begin_f32(ps, s, &f);
    ps_fast_phase_f32(ps, &f, 0, im_a);
    ps_fast_phase_f32(ps, &f, 1, im_b);
    ps_fast_end_f32(ps, bat, &f);
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
