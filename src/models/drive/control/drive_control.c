/*
 * Parameter check and derived quantities of the drive controller, shared by
 * the integer and the float twins (see drive_control.h).
 */
#include "models/drive/control/drive_control.h"

#include <stddef.h>

#include "math/umath.h"
#include "models/drive/drive_units.h"


/* True when every value is finite and strictly positive. */
static bool dc_all_positive(const double *v, size_t n) {
    for (size_t k = 0u; k < n; k++) {
        if (!math_isfinite_f64(v[k]) || !(v[k] > 0.0)) {
            return false;
        }
    }
    return true;
}

/* True when every value is finite and not negative. */
static bool dc_all_nonnegative(const double *v, size_t n) {
    for (size_t k = 0u; k < n; k++) {
        if (!math_isfinite_f64(v[k]) || !(v[k] >= 0.0)) {
            return false;
        }
    }
    return true;
}

/* The PWM step in whole nanoseconds, or 0 when it is not one (within 1e-6 ns). */
static uint32_t dc_step_ns(double step_s) {
    double ns = step_s * 1e9;
    double whole = math_round_f64(ns);
    if (!(whole >= 1.0) || !(whole <= 1e7) || !(math_fabs_f64(ns - whole) <= 1e-6)) {
        return 0u;
    }
    return (uint32_t)whole;
}

/* The limits and gains, checked against each other and the per-unit bases. */
static bool dc_limits_ok(const drive_control_params *p) {
    const double positive[] = {p->i_mag_a,         p->i_max_a,          p->slip_max_hz,
                               p->freq_max_hz,     p->speed_max_radps,  p->accel_max_radps2,
                               p->m_max,           p->vdc_min_v};
    const double nonneg[] = {p->idle_speed_radps,      p->kp_speed_hz_per_radps,
                             p->ki_speed_hz_per_rad,   p->kp_current_v_per_a,
                             p->ki_current_v_per_as,   p->ff_gain};
    if (!dc_all_positive(positive, sizeof positive / sizeof positive[0]) ||
        !dc_all_nonnegative(nonneg, sizeof nonneg / sizeof nonneg[0])) {
        return false;
    }
    return (p->i_max_a > p->i_mag_a) && (p->i_max_a < DRIVE_BASE_CURRENT_A) &&
           (p->freq_max_hz > p->slip_max_hz) && (p->freq_max_hz < DRIVE_BASE_FREQ_HZ) &&
           (p->speed_max_radps < 0.5 * DRIVE_BASE_SPEED_RADPS) &&
           (p->idle_speed_radps < p->speed_max_radps) && (p->m_max <= 1.0) &&
           (p->ff_gain <= 1.0) && (p->vdc_min_v < DRIVE_BASE_VOLTAGE_V);
}

drive_control_status drive_control_design_f64(drive_control_design *d,
                                              const drive_control_params *p) {
    if (p == NULL) {
        return DRIVE_CONTROL_ERR_NULL;
    }
    const double machine[] = {p->step_s, p->pwm_step_s, p->rs_ohm, p->rr_ohm,
                              p->lls_h,  p->llr_h,      p->lm_h};
    if (!dc_all_positive(machine, sizeof machine / sizeof machine[0]) || (p->step_s > 0.01) ||
        (p->pwm_step_s > p->step_s) || (p->pole_pairs < 1u) || (p->pole_pairs > 16u) ||
        !dc_limits_ok(p)) {
        return DRIVE_CONTROL_ERR_PARAM;
    }
    uint32_t pwm_ns = dc_step_ns(p->pwm_step_s);
    if (pwm_ns == 0u) {
        return DRIVE_CONTROL_ERR_PARAM;
    }
    if (d != NULL) {
        double lr = p->llr_h + p->lm_h;
        d->step_s = p->step_s;
        d->ls_h = p->lls_h + p->lm_h;
        d->sigma_ls_h = d->ls_h - p->lm_h * p->lm_h / lr;
        d->tau_r_s = lr / p->rr_ohm;
        d->kq_a_per_hz = MATH_TWO_PI_F64 * d->tau_r_s * p->i_mag_a;
        double psi_r = p->lm_h * p->i_mag_a;
        d->kt_nm_per_hz = 1.5 * (double)p->pole_pairs * psi_r * psi_r * MATH_TWO_PI_F64 / p->rr_ohm;
        double iq_max = math_sqrt_f64(p->i_max_a * p->i_max_a - p->i_mag_a * p->i_mag_a);
        d->slip_lim_hz = math_min_f64(p->slip_max_hz, iq_max / d->kq_a_per_hz);
        d->fr_hz_per_radps = (double)p->pole_pairs / MATH_TWO_PI_F64;
        d->pwm_step_ns = pwm_ns;
    }
    return DRIVE_CONTROL_OK;
}
