/*
 * Integer helpers shared by the set-up and the step of the induction
 * motor's integer twin. Not part of the model's interface.
 */
#ifndef UUV_INDUCTION_MOTOR_Q_INTERNAL_H
#define UUV_INDUCTION_MOTOR_Q_INTERNAL_H

#include <stdint.h>

#include "fixedpoint/fixedpoint.h"
#include "models/drive/motor/induction_motor.h"

/*
 * round((c0 x0 + c1 x1 + c2 x2) / 2^shift) for a row of constants.
 * Overflow: none. Each mantissa is below 2^30 and each operand at most 2^31
 * in magnitude, so each product is below 2^61 and the sum below 2^63. The
 * result is returned wide; the caller narrows it with saturation.
 */
static inline int64_t im_dot_q(const induction_motor_row_q *r, int32_t x0, int32_t x1, int32_t x2) {
    const int64_t s = (int64_t)r->c[0] * x0 + (int64_t)r->c[1] * x1 + (int64_t)r->c[2] * x2;
    return fp_shr_round_var_i64(s, r->shift);
}

/* The two-term form of im_dot_q() (c2 unused); the same bounds. */
static inline int64_t im_dot2_q(const induction_motor_row_q *r, int32_t x0, int32_t x1) {
    const int64_t s = (int64_t)r->c[0] * x0 + (int64_t)r->c[1] * x1;
    return fp_shr_round_var_i64(s, r->shift);
}

/*
 * round(c0 x / 2^shift) for a single constant; the caller guarantees
 * |c0| |x| < 2^63 (a Q31 operand, or k_dw: mantissa below 2^29, |x| <= 2^33).
 */
static inline int64_t im_mul1_q(const induction_motor_row_q *r, int64_t x) {
    return fp_shr_round_var_i64((int64_t)r->c[0] * x, r->shift);
}

/*
 * Load torque k w |w| [Q31 of 512 N m] from the speed [Q31 of 512 rad/s]:
 * the same formula as propeller_drag_torque_*, with k converted at init
 * (row k_load). w|w| / 2^31 is Q31 of (512 rad/s)^2 and reaches 2^31 only
 * at w = -2^31, where it saturates; the torque saturates (counted) from
 * 512 N m, at 465 rad/s with the drive's propeller.
 */
static inline q31_t im_load_q(induction_motor_q *m, q31_t w) {
    const int64_t aw = (w < 0) ? -(int64_t)w : (int64_t)w;
    const q31_t w2 = fp_sat_cnt_q31(fp_shr_round_i64((int64_t)w * aw, 31u), &m->sat_count);
    return fp_sat_cnt_q31(im_mul1_q(&m->k_load, w2), &m->sat_count);
}

#endif /* UUV_INDUCTION_MOTOR_Q_INTERNAL_H */
