/*
 * The power stage's 2 us step for the real-time modulator (pwm_rt.h), in
 * inline pieces per twin, for the executive's fast tick. It computes
 * exactly what power_stage_step_q() computes with the same duties (and the
 * same for the float twins), bit for bit; tests/unit/test_power_stage.c
 * checks that over long runs. The duties are the legs' on-times over the
 * step (Q15, 32768 = the step, in both builds: the modulator is integer),
 * so the stage applies the step-averaged pole voltages and DC-link
 * current: sub-step switching, or held states as duties of 0 or 32768.
 * Only the work is arranged for the tick, never the arithmetic:
 *
 *   - What the step takes from the duties is its legs' factors (ps_legs_*,
 *     ps_fast_legs_*): the inverter's leg sums w_x = 2 d_x - d_y - d_c
 *     and the DC-link current's d_x - d_c, for x = a, b. A run of steps
 *     with the same duties forms them once (the held states of the
 *     modulator's frame plan, drive_rt_step.h); they are the duties'
 *     arithmetic in either case, so there is one form of the step.
 *   - The inverter voltages are ps_inverter_w_q()'s; with held duties its
 *     rounded product is exactly n_x v_dc / 3.
 *   - The DC-link current's product sum is formed phase by phase as
 *     T = dd_a S_a + dd_b S_b in 64 bits (dd_x = d_x - d_c in Q15 units,
 *     S_x the sum of the old and new inductor currents) and rounded once,
 *     floor((T + 2^15) / 2^16): the high word ps_dc_current_q() takes of
 *     2^16 T + 2^31.
 *   - The motor currents come in the stage's own format (Q3.28 in the
 *     fixed twin), so nothing is narrowed or widened per step.
 *   - The filter phases and the DC link are the inline pieces of
 *     power_stage_nodes.h, unchanged.
 */
#ifndef UUV_POWER_STAGE_FAST_H
#define UUV_POWER_STAGE_FAST_H

#include <stdbool.h>
#include <stdint.h>

#include "fixedpoint/fixedpoint.h"
#include "models/drive/inverter/power_stage.h"
#include "models/drive/inverter/power_stage_nodes.h"

/*
 * The legs' factors of a step (fixed twin): what its duties give the stage,
 * in Q15 units, or, for held states (every duty 0 or 32768), in whole
 * units (whole: the duties over 32768, the small integers n_x = 2 s_x -
 * s_y - s_c and s_x - s_c). Both give the same bits: with w = 32768 n the
 * inverter's rounded product hi((8 v3) (2^14 w) + 2^31) is exactly n v3
 * (v3 = v_dc / 3 as rounded there), and with dd = 32768 m the DC-link
 * current's floor((T + 2^15) / 2^16) is floor((T' + 1) / 2) of T' = T /
 * 32768 (tests/unit/test_power_stage.c, test_held_legs); the filter's
 * history then takes u G_L2 as v3 (n G_L2) (ps_filter_history_held_q()).
 * The whole form takes about seven operations off the step's chain
 * through the DC link; a constant at each inlined use, so each use
 * compiles to one form (the firmware's tick takes the Q15 one).
 */
typedef struct {
    int32_t w[2];  /* the leg sums 2 d_x - d_y - d_c, x = a, b, in [-65536, 65536] */
    int32_t dd[2]; /* d_a - d_c, d_b - d_c */
    bool whole;    /* held states: w and dd in whole units */
} ps_legs_q;

/* What the pieces of one step carry between them (fixed twin). */
typedef struct {
    int32_t dd[2]; /* d_a - d_c, d_b - d_c, the legs' units */
    int64_t t;     /* the DC-link current's sum T, formed phase by phase */
    uint32_t sat;  /* the stage's clamp count, kept in a local */
    bool whole;    /* the legs' units whole (ps_legs_q) */
} ps_fast_q;

/* The legs' factors of the duties duty[x] (Q15, 0..32768). */
static inline void ps_fast_legs_q(const int32_t duty[3], ps_legs_q *l) {
    l->w[0] = ps_leg_sum_q(duty[0], duty[1], duty[2]);
    l->w[1] = ps_leg_sum_q(duty[1], duty[0], duty[2]);
    l->dd[0] = duty[0] - duty[2];
    l->dd[1] = duty[1] - duty[2];
    l->whole = false;
}

/* The legs' factors of the held states s[x] (0 or 1), in whole units: the same sums of s. */
static inline void ps_fast_held_legs_q(const int32_t s[3], ps_legs_q *l) {
    ps_fast_legs_q(s, l);
    l->whole = true;
}

/* Start of a step with the legs' factors l: inverter voltages. */
static inline void ps_fast_begin_q(power_stage_q *ps, const ps_legs_q *l, ps_fast_q *f) {
    if (l->whole) {
        const int32_t v3 = ps_hi_q(ps_mac_q(ps_acc_q(0), ps->v_dc, 0x55555555));
        ps->u[0] = l->w[0] * v3;
        ps->u[1] = l->w[1] * v3;
    } else {
        ps_inverter_w_q(ps->v_dc, l->w[0], l->w[1], &ps->u[0], &ps->u[1]);
    }
    f->dd[0] = l->dd[0];
    f->dd[1] = l->dd[1];
    f->t = 0;
    f->sat = ps->sat_count;
    f->whole = l->whole;
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
    f->t += (int64_t)f->dd[x] * (i0 + ph->i_l);
}

/*
 * The same phase after a begin with the held legs l (whole units), its
 * history by ps_filter_history_held_q(): the same bits. v3 is the begin's
 * (the DC link moves at the end), n G_L2 the same in every step of a
 * held run, so that inlined in a run's loop both are formed once. A
 * function of its own, so that the tick's phase (ps_fast_phase_q(), out
 * of line where the compiler takes it so) carries no test of the form.
 */
static inline void ps_fast_phase_held_q(power_stage_q *ps, ps_fast_q *f, const ps_legs_q *l, int x,
                                        int32_t im) {
    const ps_coef_q *k = &ps->k;
    ps_phase_q *ph = &ps->ph[x];
    ps_hist_q h;
    const int32_t i0 = ph->i_l;
    const int32_t v3 = ps_hi_q(ps_mac_q(ps_acc_q(0), ps->v_dc, 0x55555555));
    ps_filter_history_held_q(k, ph, v3, (int64_t)l->w[x] * k->g_l2, &h);
    const int32_t dv = ps_filter_node_q(k, ph, &h, im);
    ps_filter_update_q(k, ph, &h, dv, im, &f->sat);
    f->t += (int64_t)f->dd[x] * (i0 + ph->i_l);
}

/* End of the step: the DC-link current and the DC link with the battery bat. */
static inline void ps_fast_end_q(power_stage_q *ps, const ps_battery_q *bat, const ps_fast_q *f) {
    uint32_t sat = f->sat;
    /* DC-link current: floor((T + 2^15) / 2^16), |T| <= 2^46 (see above), or
     * in whole units floor((T + 1) / 2), |T| <= 2^30. */
    const int32_t i_dc = f->whole ? (int32_t)fp_shr_floor_i64(f->t + 1, 1u)
                                  : (int32_t)fp_shr_floor_i64(f->t + 32768, 16u);
    ps->v_dc = ps_dclink_step_q(ps->v_dc, bat, ps->k.neg_k_c, i_dc, &sat);
    ps->i_dc = i_dc;
    ps->sat_count = sat;
}

/*
 * One step, fixed twin: power_stage_step_q() with the duties duty[x] (Q15),
 * the motor currents im_a, im_b
 * (Q3.28 of 256 A) and the battery bat. Integer only, no division; total
 * (the stage clamps and counts as in power_stage_step_q()).
 */
static inline void ps_fast_step_q(power_stage_q *ps, const ps_battery_q *bat, const int32_t duty[3],
                                  int32_t im_a, int32_t im_b) {
    ps_legs_q l;
    ps_fast_q f;
    ps_fast_legs_q(duty, &l);
    ps_fast_begin_q(ps, &l, &f);
    ps_fast_phase_q(ps, &f, 0, im_a);
    ps_fast_phase_q(ps, &f, 1, im_b);
    ps_fast_end_q(ps, bat, &f);
}

/*
 * The float twins of the pieces and of ps_fast_step_q(): power_stage_step_f32()
 * with the duties duty[x] / 32768, its expressions rounded in its order.
 */
typedef struct {
    float w[2];  /* the leg sums (2 d_x - d_y) - d_c, x = a, b */
    float dd[2]; /* d_a - d_c, d_b - d_c */
    bool whole;  /* of held states (the float step has one form for both) */
} ps_legs_f32;

typedef struct {
    float dd[2];  /* d_a - d_c, d_b - d_c */
    float t;      /* the DC-link current's sum, formed phase by phase */
    uint32_t sat; /* the stage's clamp count, kept in a local */
} ps_fast_f32;

/*
 * The legs' factors of the duties duty[x] (the modulator's Q15, 0..32768),
 * as power_stage_step_f32() forms them of duty[x] / 32768 (exact in
 * single precision).
 */
static inline void ps_fast_legs_f32(const int32_t duty[3], ps_legs_f32 *l) {
    const float dq[3] = {(float)duty[0] * (1.0f / 32768.0f), (float)duty[1] * (1.0f / 32768.0f),
                         (float)duty[2] * (1.0f / 32768.0f)};
    l->w[0] = ps_leg_sum_f32(dq[0], dq[1], dq[2]);
    l->w[1] = ps_leg_sum_f32(dq[1], dq[0], dq[2]);
    l->dd[0] = dq[0] - dq[2];
    l->dd[1] = dq[1] - dq[2];
    l->whole = false;
}

/* The legs' factors of the held states s[x] (0 or 1): those of their duties. */
static inline void ps_fast_held_legs_f32(const int32_t s[3], ps_legs_f32 *l) {
    const int32_t duty[3] = {s[0] * 32768, s[1] * 32768, s[2] * 32768};
    ps_fast_legs_f32(duty, l);
    l->whole = true;
}

static inline void ps_fast_begin_f32(power_stage_f32 *ps, const ps_legs_f32 *l, ps_fast_f32 *f) {
    ps_inverter_w_f32(ps->v_dc, l->w[0], l->w[1], &ps->u[0], &ps->u[1]);
    f->dd[0] = l->dd[0];
    f->dd[1] = l->dd[1];
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

/* The phase after held legs: the float step's one form. */
static inline void ps_fast_phase_held_f32(power_stage_f32 *ps, ps_fast_f32 *f,
                                          const ps_legs_f32 *l, int x, float im) {
    (void)l;
    ps_fast_phase_f32(ps, f, x, im);
}

static inline void ps_fast_end_f32(power_stage_f32 *ps, const ps_battery_f32 *bat,
                                   const ps_fast_f32 *f) {
    uint32_t sat = f->sat;
    const float i_dc = 0.5f * f->t;
    ps->v_dc = ps_dclink_step_f32(ps->v_dc, bat, ps->k.neg_k_c, f->t, &sat);
    ps->i_dc = i_dc;
    ps->sat_count = sat;
}

static inline void ps_fast_step_f32(power_stage_f32 *ps, const ps_battery_f32 *bat,
                                    const int32_t duty[3], float im_a, float im_b) {
    ps_legs_f32 l;
    ps_fast_f32 f;
    ps_fast_legs_f32(duty, &l);
    ps_fast_begin_f32(ps, &l, &f);
    ps_fast_phase_f32(ps, &f, 0, im_a);
    ps_fast_phase_f32(ps, &f, 1, im_b);
    ps_fast_end_f32(ps, bat, &f);
}

/*
 * The same steps out of line (power_stage_step.c), for callers that are not
 * the real-time path: one inlined copy there, one call everywhere else.
 */
void ps_fast_step_call_q(power_stage_q *ps, const ps_battery_q *bat, const int32_t duty[3],
                         int32_t im_a, int32_t im_b);
void ps_fast_step_call_f32(power_stage_f32 *ps, const ps_battery_f32 *bat,
                           const int32_t duty[3], float im_a, float im_b);

#endif /* UUV_POWER_STAGE_FAST_H */
