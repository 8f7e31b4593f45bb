/*
 * Double-precision twin of the induction motor: the reference the tests
 * compare the other twins with. The algorithm is described in
 * induction_motor.h; this file and induction_motor_f32.c are the same
 * sequence of operations in two precisions.
 */
#include <stddef.h>

#include "math/umath.h"
#include "models/drive/motor/induction_motor.h"

#define IM_INV_SQRT3_F64 0.57735026918962576451  /* 1 / sqrt(3) */
#define IM_HALF_SQRT3_F64 0.86602540378443864676 /* sqrt(3) / 2 */

/*
 * e^(j phi) - 1 = c1 + j s by the Taylor series of cos - 1 to phi^6 and of
 * sin to phi^7; for |phi| <= 0.25 the truncation is below 4e-10, and below
 * 3e-13 at the 0.1 rad of the drive at 512 rad/s.
 */
static void im_rotation_f64(double phi, double *c1, double *s) {
    const double p2 = phi * phi;
    *c1 = p2 * (-0.5 + p2 * ((1.0 / 24.0) - p2 * (1.0 / 720.0)));
    *s = phi + phi * p2 * ((-1.0 / 6.0) + p2 * ((1.0 / 120.0) - p2 * (1.0 / 5040.0)));
}

/*
 * e^(j phi) - 1 for any angle of the step: the series at phi / 2^k (exact
 * halvings), then k squarings, (1 + c1 + j s)^2 = 1 + (2 c1 + c1^2 - s^2)
 * + j 2 s (1 + c1). k = 0 at the drive's 100 us: the series alone.
 */
static void im_rotation_long_f64(double phi, uint32_t k, double *c1, double *s) {
    double ph = phi;
    for (uint32_t i = 0u; i < k; i++) {
        ph *= 0.5;
    }
    im_rotation_f64(ph, c1, s);
    for (uint32_t i = 0u; i < k; i++) {
        const double c = *c1;
        *c1 = 2.0 * c + (c * c - *s * *s);
        *s = 2.0 * (*s + *s * c);
    }
}

static double im_load_f64(const induction_motor_f64 *m, double w) {
    return (m->prop != NULL) ? -propeller_drag_torque_f64(m->prop, w) : 0.0;
}

induction_motor_status induction_motor_init_f64(induction_motor_f64 *m,
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
    m->prop = prop;
    induction_motor_reset_f64(m);
    return INDUCTION_MOTOR_OK;
}

void induction_motor_reset_f64(induction_motor_f64 *m) {
    m->psi_s[0] = 0.0;
    m->psi_s[1] = 0.0;
    m->psi_r[0] = 0.0;
    m->psi_r[1] = 0.0;
    m->w = 0.0;
    m->w_prev = 0.0;
    m->te = 0.0;
    m->t_load = 0.0;
    m->speed_locked = false;
}

void induction_motor_set_speed_f64(induction_motor_f64 *m, double w_radps, bool locked) {
    m->w = w_radps;
    m->w_prev = w_radps;
    m->t_load = im_load_f64(m, w_radps);
    m->speed_locked = locked;
}

/* Trapezoidal mechanics with the linearised load (induction_motor.h). */
static void im_mechanics_f64(induction_motor_f64 *m, double te_new) {
    m->w_prev = m->w;
    if (!m->speed_locked) {
        const double aw = (m->w < 0.0) ? -m->w : m->w;
        const double dw0 = m->c.dw_per_t * (m->te + te_new - 2.0 * m->t_load);
        m->w = m->w + (dw0 - dw0 * (m->c.eps_per_w * aw));
    }
    m->te = te_new;
    m->t_load = im_load_f64(m, m->w);
}

void induction_motor_step_f64(induction_motor_f64 *m, const induction_motor_in_f64 *in,
                              induction_motor_out_f64 *out) {
    const induction_motor_coefs *c = &m->c;
    const double v0 = (in->v_a + in->v_b + in->v_c) * (1.0 / 3.0);
    const double v[2] = {in->v_a - v0, (in->v_b - in->v_c) * IM_INV_SQRT3_F64};
    double bs[2], rr[2], br[2], c1, s;

    for (int k = 0; k < 2; k++) {
        bs[k] = m->psi_s[k] + (c->n_ss * m->psi_s[k] + c->n_sr * m->psi_r[k] + c->h_s * v[k]);
        rr[k] = m->psi_r[k] + (c->n_rs * m->psi_s[k] + c->n_rr * m->psi_r[k]);
    }
    im_rotation_long_f64(c->phi_per_w * (m->w + 0.5 * (m->w - m->w_prev)), c->rot_squarings,
                         &c1, &s);
    br[0] = rr[0] + (c1 * rr[0] - s * rr[1]);
    br[1] = rr[1] + (c1 * rr[1] + s * rr[0]);
    for (int k = 0; k < 2; k++) {
        m->psi_s[k] = bs[k] + (c->q_ss * bs[k] + c->q_sr * br[k]);
        m->psi_r[k] = br[k] + (c->q_rs * bs[k] + c->q_rr * br[k]);
    }
    im_mechanics_f64(m, c->te_per_cross * (m->psi_s[1] * m->psi_r[0] - m->psi_s[0] * m->psi_r[1]));

    const double i_al = c->a_ss * m->psi_s[0] - c->a_sr * m->psi_r[0];
    const double i_be = c->a_ss * m->psi_s[1] - c->a_sr * m->psi_r[1];
    out->i_a = i_al;
    out->i_b = -0.5 * i_al + IM_HALF_SQRT3_F64 * i_be;
    out->i_c = -out->i_a - out->i_b;
    out->te_nm = m->te;
    out->t_load_nm = m->t_load;
    out->w_radps = m->w;
    out->n_rpm = m->w * (30.0 / MATH_PI_F64);
    out->psi_s_alpha_wb = m->psi_s[0];
    out->psi_s_beta_wb = m->psi_s[1];
}

void induction_motor_observe_f64(const induction_motor_f64 *m, induction_motor_obs *o) {
    const induction_motor_coefs *c = &m->c;
    for (int k = 0; k < 2; k++) {
        o->psi_s[k] = m->psi_s[k];
        o->psi_r[k] = m->psi_r[k];
        o->i_s[k] = c->a_ss * m->psi_s[k] - c->a_sr * m->psi_r[k];
        o->i_r[k] = c->a_rr * m->psi_r[k] - c->a_sr * m->psi_s[k];
    }
    o->w_radps = m->w;
    o->te_nm = m->te;
    o->t_load_nm = m->t_load;
}
