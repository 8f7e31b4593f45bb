/*
 * The averaged inverter, both twins (inverter_avg.h): the modulator's
 * averaged duties feeding the power stage, n_sub substeps per frame; and
 * the quasi-static stage of the executive's averaged layer.
 */
#include "models/drive/inverter/inverter_avg.h"

#include <stdbool.h>
#include <stddef.h>

#include "fixedpoint/wavetable.h"
#include "math/umath.h"
#include "models/drive/inverter/power_stage_nodes.h"
#include "models/drive/pwm/pwm_average.h"

#define QS_INV_SQRT3_Q31 1239850262   /* round(2^31 / sqrt 3) */
#define QS_HALF_SQRT3_Q31 1859775393  /* round(2^31 sqrt(3) / 2) */

static int inverter_avg_sub_ok(uint32_t frame_ns, uint32_t n_sub) {
    return n_sub >= 1u && n_sub <= INVERTER_AVG_SUB_MAX && (frame_ns % n_sub) == 0u;
}

inverter_avg_status inverter_avg_init_q(inverter_avg_q *inv, const pwm_params *pp,
                                        const power_stage_params *sp, uint32_t frame_ns,
                                        uint32_t n_sub, double v_dc0_v) {
    pwm_params mode;
    if (inv == NULL || pp == NULL || sp == NULL) {
        return INVERTER_AVG_ERR_NULL;
    }
    if (!inverter_avg_sub_ok(frame_ns, n_sub)) {
        return INVERTER_AVG_ERR_SUB;
    }
    mode = *pp;
    mode.edges = PWM_AVERAGED;
    if (pwm_init_q(&inv->mod, &mode, frame_ns / n_sub) != PWM_OK) {
        return INVERTER_AVG_ERR_PWM;
    }
    if (power_stage_init_q(&inv->stage, sp, frame_ns / n_sub, v_dc0_v) != PS_OK) {
        return INVERTER_AVG_ERR_STAGE;
    }
    inv->n_sub = n_sub;
    return INVERTER_AVG_OK;
}

inverter_avg_status inverter_avg_init_f32(inverter_avg_f32 *inv, const pwm_params *pp,
                                          const power_stage_params *sp, uint32_t frame_ns,
                                          uint32_t n_sub, double v_dc0_v) {
    pwm_params mode;
    if (inv == NULL || pp == NULL || sp == NULL) {
        return INVERTER_AVG_ERR_NULL;
    }
    if (!inverter_avg_sub_ok(frame_ns, n_sub)) {
        return INVERTER_AVG_ERR_SUB;
    }
    mode = *pp;
    mode.edges = PWM_AVERAGED;
    if (pwm_init_f32(&inv->mod, &mode, frame_ns / n_sub) != PWM_OK) {
        return INVERTER_AVG_ERR_PWM;
    }
    if (power_stage_init_f32(&inv->stage, sp, frame_ns / n_sub, v_dc0_v) != PS_OK) {
        return INVERTER_AVG_ERR_STAGE;
    }
    inv->n_sub = n_sub;
    return INVERTER_AVG_OK;
}

void inverter_avg_step_q(inverter_avg_q *inv, const power_stage_in_q *in) {
    power_stage_in_q sub = *in;
    pwm_out_q d;
    uint32_t i;
    for (i = 0u; i < inv->n_sub; i++) {
        pwm_average_q(&inv->mod, &d);
        sub.duty[0] = d.duty[0];
        sub.duty[1] = d.duty[1];
        sub.duty[2] = d.duty[2];
        power_stage_step_q(&inv->stage, &sub);
    }
}

void inverter_avg_step_f32(inverter_avg_f32 *inv, const power_stage_in_f32 *in) {
    power_stage_in_f32 sub = *in;
    pwm_out_f32 d;
    uint32_t i;
    for (i = 0u; i < inv->n_sub; i++) {
        pwm_average_f32(&inv->mod, &d);
        sub.duty[0] = d.duty[0];
        sub.duty[1] = d.duty[1];
        sub.duty[2] = d.duty[2];
        power_stage_step_f32(&inv->stage, &sub);
    }
}

/* ---- The quasi-static stage --------------------------------------------- */

/* [0, 1024) V: the fixed twin's range for the bus, on both twins. */
static double inverter_quasi_static_clamp_v0(double v) {
    return (v > 0.0) ? ((v < 1023.0) ? v : 1023.0) : 0.0;
}

inverter_avg_status inverter_quasi_static_init_q(inverter_quasi_static_q *inv, const pwm_params *pp,
                                                 uint32_t frame_ns, double v_dc0_v) {
    pwm_params mode;
    if (inv == NULL || pp == NULL) {
        return INVERTER_AVG_ERR_NULL;
    }
    mode = *pp;
    mode.edges = PWM_AVERAGED;
    if (pwm_init_q(&inv->mod, &mode, frame_ns) != PWM_OK) {
        return INVERTER_AVG_ERR_PWM;
    }
    const double v_q28 = inverter_quasi_static_clamp_v0(v_dc0_v) / 1024.0 * 268435456.0 + 0.5;
    inv->frame_ns = frame_ns;
    inv->rot_half = inv->mod.half_inc_s;
    inv->rot_c = wt_cos_q15(inv->rot_half);
    inv->rot_s = wt_sin_q15(inv->rot_half);
    inv->v_dc = (int32_t)v_q28;
    inv->u[0] = 0;
    inv->u[1] = 0;
    inv->i_dc = 0;
    inv->sat_count = 0u;
    return INVERTER_AVG_OK;
}

inverter_avg_status inverter_quasi_static_init_f32(inverter_quasi_static_f32 *inv,
                                                   const pwm_params *pp, uint32_t frame_ns,
                                                   double v_dc0_v) {
    pwm_params mode;
    if (inv == NULL || pp == NULL) {
        return INVERTER_AVG_ERR_NULL;
    }
    mode = *pp;
    mode.edges = PWM_AVERAGED;
    if (pwm_init_f32(&inv->mod, &mode, frame_ns) != PWM_OK) {
        return INVERTER_AVG_ERR_PWM;
    }
    inv->frame_ns = frame_ns;
    inv->rot_half = inv->mod.half_inc_s;
    inv->rot_c = wt_cos_f32(inv->rot_half);
    inv->rot_s = wt_sin_f32(inv->rot_half);
    inv->v_dc = (float)inverter_quasi_static_clamp_v0(v_dc0_v);
    inv->u[0] = 0.0f;
    inv->u[1] = 0.0f;
    inv->i_dc = 0.0f;
    inv->sat_count = 0u;
    return INVERTER_AVG_OK;
}

/*
 * The update's constants in SI for both twins: e [V] (clamped to
 * [0, 1023] V), alpha, beta [ohm]; returns the clamps. A capacitance that
 * is not positive and finite gives the settled bus (alpha 1, beta 1 / G).
 */
static uint32_t inverter_quasi_static_battery_si(uint32_t frame_ns, double c_dc_f, double g_s,
                                                 double b_a, double *e, double *alpha,
                                                 double *beta) {
    const double t = 1e-9 * (double)frame_ns;
    const bool cap = (c_dc_f > 0.0) && (c_dc_f < 1e300);
    uint32_t n = 0u;
    if (!(g_s > 0.0 && g_s < 1e300) || !(b_a > -1e300 && b_a < 1e300)) {
        /* Open (or a value no battery gives, counted): the capacitor alone. */
        if (g_s != 0.0) {
            n = 1u;
        }
        *e = 0.0;
        *alpha = 0.0;
        *beta = cap ? t / c_dc_f : 0.0;
        return n;
    }
    *alpha = cap ? 1.0 - math_exp_f64(-t * g_s / c_dc_f) : 1.0;
    *beta = *alpha / g_s;
    *e = b_a / g_s;
    if (!(*e >= 0.0)) {
        *e = 0.0;
        n++;
    }
    if (*e > 1023.0) {
        *e = 1023.0;
        n++;
    }
    return n;
}

uint32_t inverter_quasi_static_battery_q(const inverter_quasi_static_q *inv, double c_dc_f,
                                         double g_s, double b_a, inverter_quasi_static_bus_q *out) {
    double e;
    double alpha;
    double beta;
    uint32_t n =
        inverter_quasi_static_battery_si(inv->frame_ns, c_dc_f, g_s, b_a, &e, &alpha, &beta);
    /* Per unit: volts of 1024 V per ampere of 256 A is ohms / 4; Q24 below 128. */
    double beta_pu = beta * 0.25 * 16777216.0;
    if (beta_pu > 2147483520.0) {
        beta_pu = 2147483520.0;
        n++;
    }
    const double e_q28 = e / 1024.0 * 268435456.0 + 0.5;
    const double alpha_q31 = alpha * 2147483648.0 + 0.5;
    const double beta_q24 = beta_pu + 0.5;
    out->e = (int32_t)e_q28;
    out->alpha = (alpha_q31 < 2147483647.0) ? (q31_t)alpha_q31 : 2147483647; /* 1: just below */
    out->beta = (int32_t)beta_q24;
    return n;
}

uint32_t inverter_quasi_static_battery_f32(const inverter_quasi_static_f32 *inv, double c_dc_f,
                                           double g_s, double b_a,
                                           inverter_quasi_static_bus_f32 *out) {
    double e;
    double alpha;
    double beta;
    uint32_t n =
        inverter_quasi_static_battery_si(inv->frame_ns, c_dc_f, g_s, b_a, &e, &alpha, &beta);
    if (beta > 512.0) {
        beta = 512.0;
        n++;
    }
    out->e_v = (float)e;
    out->alpha = (float)alpha;
    out->beta_ohm = (float)beta;
    return n;
}

/*
 * The turn of the currents below, the references' advance over half a
 * frame (the modulator's half_inc_s): its cosine and sine, formed again
 * only when the command changed it (most frames keep it).
 */
static inline void inverter_quasi_static_rot_q(inverter_quasi_static_q *inv) {
    if (inv->mod.half_inc_s != inv->rot_half) {
        inv->rot_half = inv->mod.half_inc_s;
        inv->rot_c = wt_cos_q15(inv->rot_half);
        inv->rot_s = wt_sin_q15(inv->rot_half);
    }
}

static inline void inverter_quasi_static_rot_f32(inverter_quasi_static_f32 *inv) {
    if (inv->mod.half_inc_s != inv->rot_half) {
        inv->rot_half = inv->mod.half_inc_s;
        inv->rot_c = wt_cos_f32(inv->rot_half);
        inv->rot_s = wt_sin_f32(inv->rot_half);
    }
}

/*
 * The motor currents at the frame's middle: those at its start, as the
 * vector i_alpha + j i_beta (i_beta = (i_a + 2 i_b) / sqrt 3), turned by
 * the references' advance over half a frame (cosine and sine in Q15;
 * exact for a steady rotation). Q3.28 currents of at most 1 per unit
 * times Q15 or Q31 constants stay far inside 64 bits.
 */
static inline void inverter_quasi_static_mid_q(int64_t c, int64_t s, int32_t *i_a, int32_t *i_b) {
    const int64_t a = *i_a;
    const int64_t beta = fp_shr_round_i64((a + 2 * (int64_t)*i_b) * QS_INV_SQRT3_Q31, 31u);
    const int64_t a2 = fp_shr_round_i64(a * c - beta * s, 15u);
    const int64_t beta2 = fp_shr_round_i64(beta * c + a * s, 15u);
    *i_a = (int32_t)a2;
    *i_b = (int32_t)(fp_shr_round_i64(beta2 * QS_HALF_SQRT3_Q31, 31u) - fp_shr_round_i64(a2, 1u));
}

/*
 * Fixed: i_dc by the stage's DC-current piece (held currents: s_x = 2 i_x,
 * |s| <= 2 per unit); alpha (e - v) below 2 per unit and beta i_dc below
 * 2^36 before the Q24 shift, both in 64 bits; the sum saturates to 32 bits
 * and the bus clamps to +-1 per unit (counted); then the phase voltages
 * from the settled bus.
 */
void inverter_quasi_static_step_q(inverter_quasi_static_q *inv,
                                  const inverter_quasi_static_bus_q *bat, int32_t i_a,
                                  int32_t i_b) {
    int32_t r[3];
    int32_t duty[3];
    int32_t u_a;
    int32_t u_b;
    uint32_t sat = inv->sat_count;
    int32_t m_a = i_a;
    int32_t m_b = i_b;
    inverter_quasi_static_rot_q(inv);
    inverter_quasi_static_mid_q(inv->rot_c, inv->rot_s, &m_a, &m_b);
    /* The duties of pwm_average_q(), without its states. */
    pwm_average_refs_q(&inv->mod, r);
    for (int x = 0; x < 3; x++) {
        duty[x] = pwm_duty_avg_q(r[x]);
    }
    const int32_t i_dc = ps_dc_current_q(duty, 2 * m_a, 2 * m_b);
    const int64_t dv = fp_shr_round_i64((int64_t)(bat->e - inv->v_dc) * bat->alpha, 31u) -
                       fp_shr_round_i64((int64_t)i_dc * bat->beta, 24u);
    const int32_t v = ps_clamp_q(fp_sat_q31((int64_t)inv->v_dc + dv), &sat);
    ps_inverter_q(v, duty, &u_a, &u_b);
    inv->v_dc = v;
    inv->u[0] = u_a;
    inv->u[1] = u_b;
    inv->i_dc = i_dc;
    inv->sat_count = sat;
}

void inverter_quasi_static_step_f32(inverter_quasi_static_f32 *inv,
                                    const inverter_quasi_static_bus_f32 *bat, float i_a,
                                    float i_b) {
    float r[3];
    float duty[3];
    float u_a;
    float u_b;
    /* The currents at the frame's middle, as in the fixed twin. */
    inverter_quasi_static_rot_f32(inv);
    const float c = inv->rot_c;
    const float s = inv->rot_s;
    const float beta = (i_a + 2.0f * i_b) * 0.577350269f;
    const float m_a = i_a * c - beta * s;
    const float m_b = 0.866025404f * (beta * c + i_a * s) - 0.5f * m_a;
    pwm_average_refs_f32(&inv->mod, r);
    for (int x = 0; x < 3; x++) {
        duty[x] = pwm_duty_avg_f32(r[x]);
    }
    const float i_dc = ps_dc_current_f32(duty, 2.0f * m_a, 2.0f * m_b);
    const float v = ps_clamp_f32(
        inv->v_dc + (bat->alpha * (bat->e_v - inv->v_dc) - bat->beta_ohm * i_dc), PS_V_LIM_F32,
        &inv->sat_count);
    ps_inverter_f32(v, duty, &u_a, &u_b);
    inv->v_dc = v;
    inv->u[0] = u_a;
    inv->u[1] = u_b;
    inv->i_dc = i_dc;
}
