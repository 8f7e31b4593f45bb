/*
 * Single-precision twin of the induction motor (SI units): the algorithm of
 * induction_motor.h, the same sequence of operations as
 * induction_motor_f64.c, with the speed accumulated by compensated (Kahan)
 * summation: near steady state the increment per step, h (Te - T_load) / J,
 * is far below the float resolution of the speed (1.5e-5 rad/s at 157 rad/s).
 */
#include <stddef.h>

#include "math/umath.h"
#include "models/drive/motor/induction_motor.h"

#define IM_INV_SQRT3_F32 0.577350269f    /* 1 / sqrt(3) */
#define IM_HALF_SQRT3_F32 0.866025404f   /* sqrt(3) / 2 */
#define IM_RPM_PER_RADPS_F32 MATH_RAD_TO_RPM_F32

/* e^(j phi) - 1 = c1 + j s, Taylor series as in the double twin. */
static void im_rotation_f32(float phi, float *c1, float *s) {
    const float p2 = phi * phi;
    *c1 = p2 * (-0.5f + p2 * ((1.0f / 24.0f) - p2 * (1.0f / 720.0f)));
    *s = phi + phi * p2 * ((-1.0f / 6.0f) + p2 * ((1.0f / 120.0f) - p2 * (1.0f / 5040.0f)));
}

/* Any angle of the step: halvings, the series, squarings, as in the double twin. */
static void im_rotation_long_f32(float phi, uint32_t k, float *c1, float *s) {
    float ph = phi;
    for (uint32_t i = 0u; i < k; i++) {
        ph *= 0.5f;
    }
    im_rotation_f32(ph, c1, s);
    for (uint32_t i = 0u; i < k; i++) {
        const float c = *c1;
        *c1 = 2.0f * c + (c * c - *s * *s);
        *s = 2.0f * (*s + *s * c);
    }
}

static float im_load_f32(const induction_motor_f32 *m, float w) {
    return (m->prop != NULL) ? -m->load_factor * propeller_drag_torque_f32(m->prop, w) : 0.0f;
}

induction_motor_status induction_motor_init_f32(induction_motor_f32 *m,
                                                const induction_motor_params *p,
                                                const propeller_model *prop, double step_s) {
    if (m == NULL) {
        return INDUCTION_MOTOR_ERR_NULL;
    }
    induction_motor_coefs c;
    induction_motor_status st = induction_motor_coefs_f64(&c, p, prop, step_s);
    if (st != INDUCTION_MOTOR_OK) {
        return st;
    }
    m->c = c;
    m->h = (float)c.h_s;
    m->a_ss = (float)c.a_ss;
    m->a_sr = (float)c.a_sr;
    m->n_ss = (float)c.n_ss;
    m->n_sr = (float)c.n_sr;
    m->n_rs = (float)c.n_rs;
    m->n_rr = (float)c.n_rr;
    m->q_ss = (float)c.q_ss;
    m->q_sr = (float)c.q_sr;
    m->q_rs = (float)c.q_rs;
    m->q_rr = (float)c.q_rr;
    m->phi_per_w = (float)c.phi_per_w;
    m->te_per_cross = (float)c.te_per_cross;
    m->dw_per_t = (float)c.dw_per_t;
    m->eps_per_w = (float)c.eps_per_w;
    m->prop = prop;
    m->load_factor = 1.0f;
    induction_motor_reset_f32(m);
    return INDUCTION_MOTOR_OK;
}

void induction_motor_reset_f32(induction_motor_f32 *m) {
    m->psi_s[0] = 0.0f;
    m->psi_s[1] = 0.0f;
    m->psi_r[0] = 0.0f;
    m->psi_r[1] = 0.0f;
    m->w = 0.0f;
    m->w_comp = 0.0f;
    m->w_prev = 0.0f;
    m->te = 0.0f;
    m->t_load = 0.0f;
    m->speed_locked = false;
}

void induction_motor_set_speed_f32(induction_motor_f32 *m, float w_radps, bool locked) {
    m->w = w_radps;
    m->w_comp = 0.0f;
    m->w_prev = w_radps;
    m->t_load = im_load_f32(m, w_radps);
    m->speed_locked = locked;
}

/* Trapezoidal mechanics with the linearised load; Kahan summation of the speed. */
static void im_mechanics_f32(induction_motor_f32 *m, float te_new) {
    m->w_prev = m->w;
    if (!m->speed_locked) {
        const float aw = (m->w < 0.0f) ? -m->w : m->w;
        const float dw0 = m->dw_per_t * (m->te + te_new - 2.0f * m->t_load);
        const float y = (dw0 - dw0 * (m->eps_per_w * aw)) - m->w_comp;
        const float t = m->w + y;
        m->w_comp = (t - m->w) - y;
        m->w = t;
    }
    m->te = te_new;
    m->t_load = im_load_f32(m, m->w);
}

static void im_outputs_f32(const induction_motor_f32 *m, induction_motor_out_f32 *out) {
    const float i_al = m->a_ss * m->psi_s[0] - m->a_sr * m->psi_r[0];
    const float i_be = m->a_ss * m->psi_s[1] - m->a_sr * m->psi_r[1];
    out->i_a = i_al;
    out->i_b = -0.5f * i_al + IM_HALF_SQRT3_F32 * i_be;
    out->i_c = -out->i_a - out->i_b;
    out->te_nm = m->te;
    out->t_load_nm = m->t_load;
    out->w_radps = m->w;
    out->n_rpm = m->w * IM_RPM_PER_RADPS_F32;
    out->psi_s_alpha_wb = m->psi_s[0];
    out->psi_s_beta_wb = m->psi_s[1];
}

void induction_motor_step_f32(induction_motor_f32 *m, const induction_motor_in_f32 *in,
                              induction_motor_out_f32 *out) {
    const float v0 = (in->v_a + in->v_b + in->v_c) * (1.0f / 3.0f);
    const float v[2] = {in->v_a - v0, (in->v_b - in->v_c) * IM_INV_SQRT3_F32};
    float bs[2], rr[2], br[2], c1, s;

    for (int k = 0; k < 2; k++) {
        bs[k] = m->psi_s[k] + (m->n_ss * m->psi_s[k] + m->n_sr * m->psi_r[k] + m->h * v[k]);
        rr[k] = m->psi_r[k] + (m->n_rs * m->psi_s[k] + m->n_rr * m->psi_r[k]);
    }
    im_rotation_long_f32(m->phi_per_w * (m->w + 0.5f * (m->w - m->w_prev)), m->c.rot_squarings,
                         &c1, &s);
    br[0] = rr[0] + (c1 * rr[0] - s * rr[1]);
    br[1] = rr[1] + (c1 * rr[1] + s * rr[0]);
    for (int k = 0; k < 2; k++) {
        m->psi_s[k] = bs[k] + (m->q_ss * bs[k] + m->q_sr * br[k]);
        m->psi_r[k] = br[k] + (m->q_rs * bs[k] + m->q_rr * br[k]);
    }
    im_mechanics_f32(m, m->te_per_cross * (m->psi_s[1] * m->psi_r[0] - m->psi_s[0] * m->psi_r[1]));

    im_outputs_f32(m, out);
}

void induction_motor_observe_f32(const induction_motor_f32 *m, induction_motor_obs *o) {
    const induction_motor_coefs *c = &m->c;
    for (int k = 0; k < 2; k++) {
        o->psi_s[k] = (double)m->psi_s[k];
        o->psi_r[k] = (double)m->psi_r[k];
        o->i_s[k] = c->a_ss * o->psi_s[k] - c->a_sr * o->psi_r[k];
        o->i_r[k] = c->a_rr * o->psi_r[k] - c->a_sr * o->psi_s[k];
    }
    o->w_radps = (double)m->w;
    o->te_nm = (double)m->te;
    o->t_load_nm = (double)m->t_load;
}

induction_motor_status induction_motor_load_f32(const induction_motor_f32 *m, double factor,
                                                induction_motor_drag_f32 *l) {
    if (m == NULL || l == NULL) {
        return INDUCTION_MOTOR_ERR_NULL;
    }
    if (!(factor >= 1.0 && factor <= 1e3)) {
        return INDUCTION_MOTOR_ERR_PARAM;
    }
    l->eps_per_w = (float)(m->c.eps_per_w * factor);
    l->factor = (float)factor;
    return INDUCTION_MOTOR_OK;
}

void induction_motor_set_load_f32(induction_motor_f32 *m, const induction_motor_drag_f32 *l) {
    m->eps_per_w = l->eps_per_w;
    m->load_factor = l->factor;
}

/* The open phase of induction_motor.h: the stator flux moves by -u i_x / a_ss. */
void induction_motor_open_phase_f32(induction_motor_f32 *m, uint32_t phase,
                                    induction_motor_out_f32 *out) {
    const float i_x = (phase == 0u) ? out->i_a : (phase == 1u) ? out->i_b : out->i_c;
    const float d = i_x / m->a_ss;
    float d_al = d;
    float d_be = 0.0f;
    if (phase != 0u) {
        d_al = -0.5f * d;
        d_be = (phase == 1u) ? IM_HALF_SQRT3_F32 * d : -IM_HALF_SQRT3_F32 * d;
    }
    m->psi_s[0] -= d_al;
    m->psi_s[1] -= d_be;
    im_outputs_f32(m, out);
}
