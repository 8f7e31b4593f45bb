/*
 * The discrete coefficients of the induction motor, shared by the three
 * twins (see induction_motor.h for the equations). Set-up code: double
 * precision, divisions allowed.
 */
#include <stddef.h>

#include "models/drive/drive_units.h"
#include "models/drive/motor/induction_motor.h"

/* True for a finite value: x - x is 0 for finite x and NaN for an infinity or a NaN. */
static bool im_is_finite(double x) { return (x - x) == 0.0; }

static bool im_positive(double x) { return im_is_finite(x) && (x > 0.0); }

static induction_motor_status im_check(const induction_motor_params *p, const propeller_model *prop,
                                       double step_s) {
    if (!im_positive(p->rs_ohm) || !im_positive(p->rr_ohm) || !im_positive(p->lls_h) ||
        !im_positive(p->llr_h) || !im_positive(p->lm_h) || !im_positive(p->j_rotor_kgm2) ||
        !im_positive(p->v_ll_rated_v) || !im_positive(p->f_rated_hz) || (p->pole_pairs < 1u) ||
        (p->pole_pairs > 16u)) {
        return INDUCTION_MOTOR_ERR_PARAM;
    }
    if ((prop != NULL) && (!im_is_finite(prop->k_drag) || (prop->k_drag < 0.0) ||
                           !im_is_finite(prop->inertia_kgm2) || (prop->inertia_kgm2 < 0.0))) {
        return INDUCTION_MOTOR_ERR_PARAM;
    }
    if (!im_positive(step_s) || (step_s > 1e-3)) {
        return INDUCTION_MOTOR_ERR_STEP;
    }
    return INDUCTION_MOTOR_OK;
}

/*
 * The implicit system M = [[1 + x, -a Rs a_sr], [-a Rr a_sr, 1 + y]] with
 * a = h/2, x = a Rs a_ss, y = a Rr a_rr, and Q = M^-1 - I written without
 * the cancellation of (1 + y) / det - 1.
 */
static void im_solve_coefs(induction_motor_coefs *c) {
    const double a = 0.5 * c->h_s;
    const double x = a * c->rs_ohm * c->a_ss;
    const double y = a * c->rr_ohm * c->a_rr;
    const double us = a * c->rs_ohm * c->a_sr;
    const double ur = a * c->rr_ohm * c->a_sr;
    const double det = 1.0 + x + y + x * y - us * ur;
    c->n_ss = -x;
    c->n_sr = us;
    c->n_rs = ur;
    c->n_rr = -y;
    c->q_ss = (us * ur - x - x * y) / det;
    c->q_rr = (us * ur - y - x * y) / det;
    c->q_sr = us / det;
    c->q_rs = ur / det;
}

induction_motor_status induction_motor_coefs_f64(induction_motor_coefs *c,
                                                 const induction_motor_params *p,
                                                 const propeller_model *prop, double step_s) {
    if ((c == NULL) || (p == NULL)) {
        return INDUCTION_MOTOR_ERR_NULL;
    }
    induction_motor_status st = im_check(p, prop, step_s);
    if (st != INDUCTION_MOTOR_OK) {
        return st;
    }
    const double ls = p->lls_h + p->lm_h;
    const double lr = p->llr_h + p->lm_h;
    /* D = Lls Llr + Lm (Lls + Llr): the same value as Ls Lr - Lm^2 without cancellation. */
    const double d = p->lls_h * p->llr_h + p->lm_h * (p->lls_h + p->llr_h);
    const double pp = (double)p->pole_pairs;
    c->h_s = step_s;
    c->rs_ohm = p->rs_ohm;
    c->rr_ohm = p->rr_ohm;
    c->ls_h = ls;
    c->lr_h = lr;
    c->lm_h = p->lm_h;
    c->pole_pairs = p->pole_pairs;
    c->a_ss = lr / d;
    c->a_sr = p->lm_h / d;
    c->a_rr = ls / d;
    im_solve_coefs(c);
    c->phi_per_w = pp * step_s;
    /* The least k with the angle at the fixed twin's full-scale speed (every
     * twin's bound) / 2^k within the series' range. */
    double range = INDUCTION_MOTOR_PHI_MAX_RAD;
    c->rot_squarings = 0u;
    while ((c->rot_squarings < 8u) && (c->phi_per_w * DRIVE_BASE_SPEED_RADPS > range)) {
        range *= 2.0;
        c->rot_squarings++;
    }
    c->te_per_cross = 1.5 * pp * c->a_sr;
    c->k_drag = (prop != NULL) ? prop->k_drag : 0.0;
    c->j_total_kgm2 = p->j_rotor_kgm2 + ((prop != NULL) ? prop->inertia_kgm2 : 0.0);
    c->dw_per_t = step_s / (2.0 * c->j_total_kgm2);
    c->eps_per_w = step_s * c->k_drag / c->j_total_kgm2;
    return INDUCTION_MOTOR_OK;
}

double induction_motor_magnetic_energy_f64(const induction_motor_obs *o) {
    return 0.75 * (o->psi_s[0] * o->i_s[0] + o->psi_s[1] * o->i_s[1] + o->psi_r[0] * o->i_r[0] +
                   o->psi_r[1] * o->i_r[1]);
}

double induction_motor_kinetic_energy_f64(const induction_motor_coefs *c,
                                          const induction_motor_obs *o) {
    return 0.5 * c->j_total_kgm2 * o->w_radps * o->w_radps;
}

double induction_motor_copper_loss_f64(const induction_motor_coefs *c,
                                       const induction_motor_obs *o) {
    const double is2 = o->i_s[0] * o->i_s[0] + o->i_s[1] * o->i_s[1];
    const double ir2 = o->i_r[0] * o->i_r[0] + o->i_r[1] * o->i_r[1];
    return 1.5 * (c->rs_ohm * is2 + c->rr_ohm * ir2);
}
