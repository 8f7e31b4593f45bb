/*
 * Integer twin of the induction motor: set-up (the constants in their
 * formats), reset, speed setting and observation. The step is in
 * induction_motor_q_step.c; formats and algorithm in induction_motor.h.
 */
#include <stddef.h>

#include "math/umath.h"
#include "models/drive/drive_units.h"
#include "models/drive/motor/induction_motor.h"
#include "models/drive/motor/induction_motor_q_internal.h"

/*
 * Fills a row with round(v_k * 2^shift), the largest shift <= 62 for which
 * the largest |v_k| * 2^shift stays below 2^bits - 1/2 (so its rounded
 * mantissa has at most `bits` bits). False when even shift 0 does not fit.
 * The products are exact powers of two, the rounding is half away from zero.
 */
static bool im_row_from_f64(induction_motor_row_q *r, double v0, double v1, double v2,
                            unsigned bits) {
    const double v[3] = {v0, v1, v2};
    const double limit = (double)(1UL << bits) - 0.5;
    double vmax = 0.0;
    double scale = 1.0;
    unsigned shift = 0u;
    for (int k = 0; k < 3; k++) {
        const double a = (v[k] < 0.0) ? -v[k] : v[k];
        if (!((a - a) == 0.0)) {
            return false;
        }
        vmax = (a > vmax) ? a : vmax;
    }
    if (!(vmax < limit)) {
        return false;
    }
    while ((shift < 62u) && (vmax * scale * 2.0 < limit)) {
        scale *= 2.0;
        shift++;
    }
    for (int k = 0; k < 3; k++) {
        const double x = v[k] * scale;
        r->c[k] = (int32_t)((x >= 0.0) ? (x + 0.5) : (x - 0.5));
    }
    r->shift = shift;
    return true;
}

/* Scale factors between SI and the raw integers (value per LSB). */
#define IM_Q_PSI (INDUCTION_MOTOR_PSI_FS_WB / 2147483648.0) /* [Wb] */
#define IM_Q_V (DRIVE_BASE_VOLTAGE_V / 2147483648.0)        /* [V] */
#define IM_Q_I (DRIVE_BASE_CURRENT_A / 2147483648.0)        /* [A] */
#define IM_Q_W (DRIVE_BASE_SPEED_RADPS / 2147483648.0)      /* [rad/s] */
#define IM_Q_T (DRIVE_BASE_TORQUE_NM / 2147483648.0)        /* [N m] */
#define IM_RPM_PER_RADPS MATH_RAD_TO_RPM_F64

/*
 * Each constant expressed as (output LSB per operand LSB). The cross
 * product of two raw fluxes is taken / 2^32, so one of its LSB is
 * 2^32 * IM_Q_PSI^2 Wb^2; w|w| is taken / 2^31.
 */
static bool im_rows_q(induction_motor_q *m) {
    const induction_motor_coefs *c = &m->c;
    const double cross_lsb = 4294967296.0 * IM_Q_PSI * IM_Q_PSI;
    const double w2_lsb = 2147483648.0 * IM_Q_W * IM_Q_W;
    bool ok = true;
    ok = ok && im_row_from_f64(&m->row_bs, c->n_ss, c->n_sr, c->h_s * IM_Q_V / IM_Q_PSI, 30u);
    ok = ok && im_row_from_f64(&m->row_br, c->n_rs, c->n_rr, 0.0, 30u);
    ok = ok && im_row_from_f64(&m->row_qs, c->q_ss, c->q_sr, 0.0, 30u);
    ok = ok && im_row_from_f64(&m->row_qr, c->q_rs, c->q_rr, 0.0, 30u);
    ok = ok && im_row_from_f64(&m->row_is, c->a_ss * IM_Q_PSI / IM_Q_I,
                               -c->a_sr * IM_Q_PSI / IM_Q_I, 0.0, 30u);
    ok = ok && im_row_from_f64(&m->k_phi, c->phi_per_w * IM_Q_W * 2147483648.0, 0.0, 0.0, 30u);
    ok = ok && im_row_from_f64(&m->k_te, c->te_per_cross * cross_lsb / IM_Q_T, 0.0, 0.0, 30u);
    ok = ok && im_row_from_f64(&m->k_dw, c->dw_per_t * IM_Q_T / IM_Q_W, 0.0, 0.0, 29u);
    ok = ok && im_row_from_f64(&m->k_eps, c->eps_per_w * IM_Q_W * 2147483648.0, 0.0, 0.0, 30u);
    ok = ok && im_row_from_f64(&m->k_load, c->k_drag * w2_lsb / IM_Q_T, 0.0, 0.0, 30u);
    ok = ok && im_row_from_f64(&m->k_rpm, IM_RPM_PER_RADPS * 65536.0 * IM_Q_W, 0.0, 0.0, 30u);
    ok = ok && im_row_from_f64(&m->k_open, IM_Q_I / (c->a_ss * IM_Q_PSI), 0.0, 0.0, 30u);
    return ok;
}

/* The drag's rows for a load factor; false when one does not fit. */
static bool im_load_rows_q(const induction_motor_coefs *c, double factor,
                           induction_motor_drag_q *l) {
    const double w2_lsb = 2147483648.0 * IM_Q_W * IM_Q_W;
    return im_row_from_f64(&l->k_eps, factor * c->eps_per_w * IM_Q_W * 2147483648.0, 0.0, 0.0,
                           30u) &&
           im_row_from_f64(&l->k_load, factor * c->k_drag * w2_lsb / IM_Q_T, 0.0, 0.0, 30u);
}

induction_motor_status induction_motor_load_q(const induction_motor_q *m, double factor,
                                              induction_motor_drag_q *l) {
    if (m == NULL || l == NULL) {
        return INDUCTION_MOTOR_ERR_NULL;
    }
    if (!(factor >= 1.0 && factor <= 1e3)) {
        return INDUCTION_MOTOR_ERR_PARAM;
    }
    return im_load_rows_q(&m->c, factor, l) ? INDUCTION_MOTOR_OK : INDUCTION_MOTOR_ERR_RANGE;
}

void induction_motor_set_load_q(induction_motor_q *m, const induction_motor_drag_q *l) {
    m->k_eps = l->k_eps;
    m->k_load = l->k_load;
}

induction_motor_status induction_motor_init_q(induction_motor_q *m, const induction_motor_params *p,
                                              const propeller_model *prop, double step_s) {
    if (m == NULL) {
        return INDUCTION_MOTOR_ERR_NULL;
    }
    induction_motor_q t;
    induction_motor_status st = induction_motor_coefs_f64(&t.c, p, prop, step_s);
    if (st != INDUCTION_MOTOR_OK) {
        return st;
    }
    /* The Q31 angle holds |phi| < 1 rad; the squarings take it to any such angle. */
    if (!(t.c.phi_per_w * DRIVE_BASE_SPEED_RADPS < 1.0) || !im_rows_q(&t)) {
        return INDUCTION_MOTOR_ERR_RANGE;
    }
    induction_motor_reset_q(&t);
    *m = t;
    return INDUCTION_MOTOR_OK;
}

void induction_motor_reset_q(induction_motor_q *m) {
    m->psi_s[0] = 0;
    m->psi_s[1] = 0;
    m->psi_r[0] = 0;
    m->psi_r[1] = 0;
    m->w = 0;
    m->w_prev = 0;
    m->te = 0;
    m->t_load = 0;
    m->speed_locked = false;
    m->sat_count = 0u;
}

void induction_motor_set_speed_q(induction_motor_q *m, q31_t w, bool locked) {
    m->w = w;
    m->w_prev = w;
    m->t_load = im_load_q(m, w);
    m->speed_locked = locked;
}

void induction_motor_observe_q(const induction_motor_q *m, induction_motor_obs *o) {
    const induction_motor_coefs *c = &m->c;
    for (int k = 0; k < 2; k++) {
        o->psi_s[k] = (double)m->psi_s[k] * IM_Q_PSI;
        o->psi_r[k] = (double)m->psi_r[k] * IM_Q_PSI;
        o->i_s[k] = c->a_ss * o->psi_s[k] - c->a_sr * o->psi_r[k];
        o->i_r[k] = c->a_rr * o->psi_r[k] - c->a_sr * o->psi_s[k];
    }
    o->w_radps = (double)m->w * IM_Q_W;
    o->te_nm = (double)m->te * IM_Q_T;
    o->t_load_nm = (double)m->t_load * IM_Q_T;
}
