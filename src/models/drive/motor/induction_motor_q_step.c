/*
 * One step of the induction motor's integer twin: integer arithmetic only,
 * no division. Formats and algorithm in induction_motor.h; every narrowing
 * to 32 bits saturates and counts in m->sat_count.
 */
#include "models/drive/motor/induction_motor.h"
#include "models/drive/motor/induction_motor_q_internal.h"

#define IM_Q31_THIRD 715827883          /* round(2^31 / 3) */
#define IM_Q31_INV_SQRT3 1239850262     /* round(2^31 / sqrt(3)) */
#define IM_Q31_HALF_SQRT3 1859775393    /* round(2^31 * sqrt(3) / 2) */
#define IM_Q31_HALF ((q31_t)1073741824) /* 1/2 */
#define IM_Q31_SIXTH Q31_CONST(1.0 / 6.0)
#define IM_Q31_1_24 Q31_CONST(1.0 / 24.0)
#define IM_Q31_1_120 Q31_CONST(1.0 / 120.0)
#define IM_Q31_1_720 Q31_CONST(1.0 / 720.0)
#define IM_Q31_1_5040 Q31_CONST(1.0 / 5040.0)

/*
 * Clarke transform without the common mode. In: Q31 of 1024 V. Out: Q31 of
 * 1024 V. v0 = round(sum * round(2^31/3) / 2^31): |sum| <= 3 * 2^31 and the
 * constant is below 2^30, so the product is below 2^63. (v_b - v_c) is at
 * most 2^32 and 2^31/sqrt(3) below 2^31: product below 2^63. v_alpha
 * saturates (counted) only for a common mode no inverter makes.
 */
static void im_clarke_q(induction_motor_q *m, const induction_motor_in_q *in, q31_t v[2]) {
    const int64_t sum = (int64_t)in->v_a + (int64_t)in->v_b + (int64_t)in->v_c;
    const int64_t v0 = fp_shr_round_i64(sum * IM_Q31_THIRD, 31u);
    v[0] = fp_sat_cnt_q31((int64_t)in->v_a - v0, &m->sat_count);
    v[1] = fp_sat_cnt_q31(
        fp_shr_round_i64(((int64_t)in->v_b - (int64_t)in->v_c) * IM_Q31_INV_SQRT3, 31u),
        &m->sat_count);
}

/*
 * e^(j phi) - 1 = c1 + j s in Q31 for phi in Q31 [rad], |phi| <= 0.25
 * (after the halvings of im_rotation_long_q): Horner forms of the Taylor
 * series as in the float twins. Every intermediate stays below 0.51 in
 * magnitude, so nothing saturates;
 * the rounding errors total a few LSB of Q31.
 */
static void im_rotation_q(q31_t phi, q31_t *c1, q31_t *s) {
    const q31_t p2 = fp_mul_q31(phi, phi);
    q31_t t = fp_sub_q31(IM_Q31_1_24, fp_mul_q31(p2, IM_Q31_1_720));
    t = fp_sub_q31(fp_mul_q31(p2, t), IM_Q31_HALF);
    *c1 = fp_mul_q31(p2, t);
    q31_t u = fp_sub_q31(IM_Q31_1_120, fp_mul_q31(p2, IM_Q31_1_5040));
    u = fp_sub_q31(fp_mul_q31(p2, u), IM_Q31_SIXTH);
    *s = fp_add_q31(phi, fp_mul_q31(fp_mul_q31(phi, p2), u));
}

/*
 * Any angle of the step (|phi| < 1 rad, the init check): the series at
 * phi / 2^k (rounding shift), then k squarings in Q31,
 * c1' = 2 c1 + c1^2 - s^2, s' = 2 (s + s c1). |c1| <= 1 - cos 1 < 0.46 and
 * |s| <= sin 1 < 0.85 at every stage, so nothing saturates (counted if it
 * did). k = 0 at the drive's 100 us: the series alone.
 */
static void im_rotation_long_q(induction_motor_q *m, q31_t phi, q31_t *c1, q31_t *s) {
    const uint32_t k = m->c.rot_squarings;
    im_rotation_q(fp_shr_round_i32(phi, k), c1, s);
    for (uint32_t i = 0u; i < k; i++) {
        const int64_t cc = fp_shr_round_i64((int64_t)*c1 * *c1 - (int64_t)*s * *s, 31u);
        const int64_t sc = fp_shr_round_i64((int64_t)*s * *c1, 31u);
        *c1 = fp_sat_cnt_q31(2 * (int64_t)*c1 + cc, &m->sat_count);
        *s = fp_sat_cnt_q31(2 * ((int64_t)*s + sc), &m->sat_count);
    }
}

/*
 * The rotor angle of this step, Q31 [rad], from the mid-step speed
 * w + (w - w_prev) / 2 (Q31 of 512 rad/s, saturated, counted) and the
 * constant p h 512 rad/s < 1.
 */
static q31_t im_phi_q(induction_motor_q *m) {
    const int64_t dw = (int64_t)m->w - (int64_t)m->w_prev;
    const q31_t w_mid = fp_sat_cnt_q31((int64_t)m->w + fp_shr_round_i64(dw, 1u), &m->sat_count);
    return fp_sat_cnt_q31(im_mul1_q(&m->k_phi, w_mid), &m->sat_count);
}

/*
 * The flux update: histories, rotation, solve. Fluxes are Q31 of 8 Wb; the
 * rotation products c1 x, s x are below 2^61 each (|c1|, |s| < 0.85 of
 * Q31), their sums below 2^62.
 */
static void im_flux_q(induction_motor_q *m, const q31_t v[2]) {
    uint32_t *sat = &m->sat_count;
    q31_t bs[2], rr[2], br[2], c1, s;
    for (int k = 0; k < 2; k++) {
        const int64_t ds = im_dot_q(&m->row_bs, m->psi_s[k], m->psi_r[k], v[k]);
        const int64_t dr = im_dot2_q(&m->row_br, m->psi_s[k], m->psi_r[k]);
        bs[k] = fp_sat_cnt_q31((int64_t)m->psi_s[k] + ds, sat);
        rr[k] = fp_sat_cnt_q31((int64_t)m->psi_r[k] + dr, sat);
    }
    im_rotation_long_q(m, im_phi_q(m), &c1, &s);
    br[0] = fp_sat_cnt_q31(
        (int64_t)rr[0] + fp_shr_round_i64((int64_t)c1 * rr[0] - (int64_t)s * rr[1], 31u), sat);
    br[1] = fp_sat_cnt_q31(
        (int64_t)rr[1] + fp_shr_round_i64((int64_t)c1 * rr[1] + (int64_t)s * rr[0], 31u), sat);
    for (int k = 0; k < 2; k++) {
        const int64_t ds = im_dot2_q(&m->row_qs, bs[k], br[k]);
        const int64_t dr = im_dot2_q(&m->row_qr, bs[k], br[k]);
        m->psi_s[k] = fp_sat_cnt_q31((int64_t)bs[k] + ds, sat);
        m->psi_r[k] = fp_sat_cnt_q31((int64_t)br[k] + dr, sat);
    }
}

/*
 * Te = (3/2) p (Lm/D) (psi_s,b psi_r,a - psi_s,a psi_r,b), Q31 of 512 N m.
 * Each product of raw fluxes is below 2^62 and is rounded / 2^32 before the
 * difference, which is then at most 2^31 (saturated, counted, only with
 * both fluxes at full scale): Q30 of 64 Wb^2.
 */
static q31_t im_torque_q(induction_motor_q *m) {
    const int64_t p1 = fp_shr_round_i64((int64_t)m->psi_s[1] * m->psi_r[0], 32u);
    const int64_t p2 = fp_shr_round_i64((int64_t)m->psi_s[0] * m->psi_r[1], 32u);
    const q31_t cross = fp_sat_cnt_q31(p1 - p2, &m->sat_count);
    return fp_sat_cnt_q31(im_mul1_q(&m->k_te, cross), &m->sat_count);
}

/*
 * Mechanics (induction_motor.h): w' = w + (h/2J) (Te + Te' - 2 T_load)(1 - eps).
 * The torque sum is at most 2^33 and the mantissa of k_dw below 2^29. eps
 * is Q31 (about 1e-3 at full speed in the drive); |w| is formed in 64 bits
 * so that w = -2^31 has a magnitude.
 */
static void im_mechanics_q(induction_motor_q *m, q31_t te_new) {
    uint32_t *sat = &m->sat_count;
    m->w_prev = m->w;
    if (!m->speed_locked) {
        const int64_t tsum = (int64_t)m->te + (int64_t)te_new - 2 * (int64_t)m->t_load;
        const q31_t dw0 = fp_sat_cnt_q31(im_mul1_q(&m->k_dw, tsum), sat);
        const int64_t aw = (m->w < 0) ? -(int64_t)m->w : (int64_t)m->w;
        const q31_t eps = fp_sat_cnt_q31(im_mul1_q(&m->k_eps, aw), sat);
        const int64_t dw = (int64_t)dw0 - fp_shr_round_i64((int64_t)dw0 * eps, 31u);
        m->w = fp_sat_cnt_q31((int64_t)m->w + dw, sat);
    }
    m->te = te_new;
    m->t_load = im_load_q(m, m->w);
}

/*
 * Outputs. i_s from the fluxes (Q31 of 256 A, saturated, counted); the phase
 * currents i_b = -i_alpha/2 + (sqrt(3)/2) i_beta (two products below 2^61)
 * and i_c = -i_a - i_b; the stator flux from 8 Wb to the 4 Wb base (a left
 * shift, saturated, counted); the speed in rpm * 2^16 (below 2^29).
 */
static void im_outputs_q(induction_motor_q *m, induction_motor_out_q *out) {
    uint32_t *sat = &m->sat_count;
    const q31_t i_al = fp_sat_cnt_q31(im_dot2_q(&m->row_is, m->psi_s[0], m->psi_r[0]), sat);
    const q31_t i_be = fp_sat_cnt_q31(im_dot2_q(&m->row_is, m->psi_s[1], m->psi_r[1]), sat);
    const int64_t ib = (int64_t)i_be * IM_Q31_HALF_SQRT3 - (int64_t)i_al * 1073741824;
    out->i_a = i_al;
    out->i_b = fp_sat_cnt_q31(fp_shr_round_i64(ib, 31u), sat);
    out->i_c = fp_sat_cnt_q31(-(int64_t)out->i_a - (int64_t)out->i_b, sat);
    out->te = m->te;
    out->t_load = m->t_load;
    out->w = m->w;
    out->n_rpm_q16 = fp_sat_cnt_q31(im_mul1_q(&m->k_rpm, m->w), sat);
    out->psi_s_alpha = fp_shl_cnt_i32(m->psi_s[0], 1u, sat);
    out->psi_s_beta = fp_shl_cnt_i32(m->psi_s[1], 1u, sat);
}

void induction_motor_step_q(induction_motor_q *m, const induction_motor_in_q *in,
                            induction_motor_out_q *out) {
    q31_t v[2];
    im_clarke_q(m, in, v);
    im_flux_q(m, v);
    im_mechanics_q(m, im_torque_q(m));
    im_outputs_q(m, out);
}

/*
 * An open phase (induction_motor.h): with u the phase's unit vector in the
 * alpha-beta plane ((1, 0), (-1/2, sqrt(3)/2), (-1/2, -sqrt(3)/2)) and i_x
 * its current, the stator flux moves by -u i_x / a_ss (row k_open), which
 * takes i_x out of the stator current and leaves the rotor flux alone.
 * k_open is 32 / a_ss raw flux per raw current (about 0.1 for the drive's
 * motor), so |d| < 2^31 and d sqrt(3)/2 2^31 < 2^62; the new fluxes are
 * saturated and counted.
 */
void induction_motor_open_phase_q(induction_motor_q *m, uint32_t phase,
                                  induction_motor_out_q *out) {
    uint32_t *sat = &m->sat_count;
    const q31_t i_x = (phase == 0u) ? out->i_a : (phase == 1u) ? out->i_b : out->i_c;
    const int64_t d = im_mul1_q(&m->k_open, i_x);
    int64_t d_al = d;
    int64_t d_be = 0;
    if (phase != 0u) {
        d_al = -fp_shr_round_i64(d, 1u);
        d_be = fp_shr_round_i64(d * IM_Q31_HALF_SQRT3, 31u);
        d_be = (phase == 1u) ? d_be : -d_be;
    }
    m->psi_s[0] = fp_sat_cnt_q31((int64_t)m->psi_s[0] - d_al, sat);
    m->psi_s[1] = fp_sat_cnt_q31((int64_t)m->psi_s[1] - d_be, sat);
    im_outputs_q(m, out);
}
