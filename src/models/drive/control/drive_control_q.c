/*
 * Integer twin of the drive controller (see drive_control.h): per-unit Q31
 * signals, constants as mantissa and shift, int64 sums saturated and counted
 * when narrowed. No floating point after init.
 */
#include "models/drive/control/drive_control.h"

#include <stddef.h>

#include "fixedpoint/wavetable.h"
#include "math/umath.h"
#include "models/drive/drive_units.h"

#define DC_MANT_LIMIT 1073741824.0 /* 2^30: a mantissa keeps 30 significant bits */

/* ---- Constants ------------------------------------------------------------ */

/*
 * value -> mantissa / 2^shift with the largest shift (at most 62) that keeps
 * |mantissa| <= 2^30. Scaling by a power of two is exact, so only the final
 * rounding loses precision (relative 2^-30). False when |value| >= 2^30 or
 * value is not finite.
 */
static bool dc_gain_make(drive_control_gain_q *g, double value) {
    double mag = math_fabs_f64(value);
    double scale = 1.0;
    uint32_t shift = 0u;
    if (!math_isfinite_f64(value) || !(mag < DC_MANT_LIMIT)) {
        return false;
    }
    while ((mag > 0.0) && (shift < 62u) && (mag * scale * 2.0 < DC_MANT_LIMIT)) {
        scale *= 2.0;
        shift++;
    }
    g->mant = (int32_t)math_round_f64(value * scale);
    g->shift = (mag > 0.0) ? shift : 0u;
    return true;
}

/*
 * g * x: Q31 operand times the constant, rounded to nearest (ties up) and
 * saturated to Q31 (counted). The product |x * mant| <= 2^61 is exact in
 * int64, so only the narrowing can clamp.
 */
static q31_t dc_apply(const drive_control_gain_q *g, q31_t x, uint32_t *sat) {
    return fp_sat_cnt_q31(fp_shr_round_var_i64((int64_t)x * (int64_t)g->mant, g->shift), sat);
}

/* Clamps an int64 to [lo, hi] (a control limit, not counted as saturation). */
static q31_t dc_clamp(int64_t x, q31_t lo, q31_t hi) {
    return (x > (int64_t)hi) ? hi : (x < (int64_t)lo) ? lo : (q31_t)x;
}

/* -1, 0 or +1 after the sign of x. */
static int dc_sign(int64_t x) {
    return (x > 0) ? 1 : (x < 0) ? -1 : 0;
}

/*
 * round(sqrt(x)) for every x < 2^63: the exact floor root (math_isqrt_u64,
 * a few dozen integer operations instead of up to 31 + 32 loop passes),
 * then rem = x - root^2 (below 2^33); the root rounds up when rem > root,
 * since (root + 1/2)^2 = root^2 + root + 1/4.
 */
static uint64_t dc_isqrt_round_u64(uint64_t x) {
    uint64_t root = math_isqrt_u64(x);
    uint64_t rem = x - root * root;
    return (rem > root) ? root + 1u : root;
}

/* Q31 of the value per unit of base, for set-up; false when out of range. */
static bool dc_pu_ok(q31_t *q, double value, double base) {
    if (!(math_fabs_f64(value / base) < 1.0)) {
        return false;
    }
    *q = fp_pu_from_f64_q31(value, base);
    return true;
}

/* The per-unit constants; false when one does not fit its format. */
static bool dc_make_constants(drive_control_q *c, const drive_control_params *p) {
    const double t = p->step_s;
    const double sw = DRIVE_BASE_SPEED_RADPS / DRIVE_BASE_FREQ_HZ;    /* slip <- speed */
    const double vi = DRIVE_BASE_CURRENT_A / DRIVE_BASE_VOLTAGE_V;    /* voltage <- current */
    const double fi = DRIVE_BASE_FREQ_HZ * vi;                        /* voltage <- f * i */
    bool ok = dc_gain_make(&c->kp_w, p->kp_speed_hz_per_radps * sw) &&
              dc_gain_make(&c->ki_w, p->ki_speed_hz_per_rad * t * sw) &&
              dc_gain_make(&c->k_fr, c->d.fr_hz_per_radps * sw) &&
              dc_gain_make(&c->k_q, c->d.kq_a_per_hz * DRIVE_BASE_FREQ_HZ / DRIVE_BASE_CURRENT_A) &&
              dc_gain_make(&c->k_rs, p->rs_ohm * vi) &&
              dc_gain_make(&c->k_sls, MATH_TWO_PI_F64 * c->d.sigma_ls_h * fi) &&
              dc_gain_make(&c->k_ls, MATH_TWO_PI_F64 * c->d.ls_h * fi) &&
              dc_gain_make(&c->k_ff, p->ff_gain) &&
              dc_gain_make(&c->kp_i, p->kp_current_v_per_a * vi) &&
              dc_gain_make(&c->ki_i, p->ki_current_v_per_as * t * vi) &&
              dc_gain_make(&c->k_vmax, 0.5 * p->m_max);
    ok = ok && dc_pu_ok(&c->speed_max, p->speed_max_radps, DRIVE_BASE_SPEED_RADPS) &&
         dc_pu_ok(&c->ramp_step, p->accel_max_radps2 * t, DRIVE_BASE_SPEED_RADPS) &&
         dc_pu_ok(&c->idle_speed, p->idle_speed_radps, DRIVE_BASE_SPEED_RADPS) &&
         dc_pu_ok(&c->slip_lim, c->d.slip_lim_hz, DRIVE_BASE_FREQ_HZ) &&
         dc_pu_ok(&c->freq_max, p->freq_max_hz, DRIVE_BASE_FREQ_HZ) &&
         dc_pu_ok(&c->i_mag, p->i_mag_a, DRIVE_BASE_CURRENT_A) &&
         dc_pu_ok(&c->vdc_min, p->vdc_min_v, DRIVE_BASE_VOLTAGE_V);
    /* A ramp step below one LSB would never move the reference. */
    return ok && (c->ramp_step > 0) && (c->vdc_min >= (1 << 16));
}

drive_control_status drive_control_init_q(drive_control_q *c, const drive_control_params *p) {
    drive_control_q tmp;
    if ((c == NULL) || (p == NULL)) {
        return DRIVE_CONTROL_ERR_NULL;
    }
    drive_control_status st = drive_control_design_f64(&tmp.d, p);
    if (st != DRIVE_CONTROL_OK) {
        return st;
    }
    if (!dc_make_constants(&tmp, p)) {
        return DRIVE_CONTROL_ERR_RANGE;
    }
    tmp.m_max = fp_from_f64_q15(p->m_max);
    tmp.inc_base = wt_phase_inc_q16((int32_t)(DRIVE_BASE_FREQ_HZ * 65536.0), tmp.d.pwm_step_ns);
    *c = tmp;
    drive_control_reset_q(c);
    return DRIVE_CONTROL_OK;
}

void drive_control_reset_q(drive_control_q *c) {
    c->speed_ref = 0;
    c->x_w = 0;
    c->x_i = 0;
    c->idle = true;
    c->sat_count = 0u;
}

/* ---- Measurement -------------------------------------------------------- */

/*
 * |i| = sqrt((2 i_a - i_b - i_c)^2 + 3 (i_b - i_c)^2) / 3, Q31 of 256 A.
 * The currents are first rounded to Q23 (LSB 3e-5 A), so that the sum of
 * squares, at most 7 * 2^48, fits in 64 bits; the root of it is 3 |i| in
 * Q23, divided by 3 with rounding and shifted back to Q31. A magnitude of
 * 256 A or more (impossible for a balanced set inside the base) saturates
 * and counts.
 */
static q31_t dc_magnitude_q(const drive_control_in_q *in, uint32_t *sat) {
    int64_t a = fp_shr_round_i32(in->i_a, 8u);
    int64_t b = fp_shr_round_i32(in->i_b, 8u);
    int64_t cc = fp_shr_round_i32(in->i_c, 8u);
    int64_t x = 2 * a - b - cc;
    int64_t y = b - cc;
    uint64_t sum = (uint64_t)(x * x) + 3u * (uint64_t)(y * y);
    uint64_t root3 = dc_isqrt_round_u64(sum);
    int32_t mag23 = (int32_t)((2u * root3 + 3u) / 6u); /* round(root3 / 3), ties up */
    return fp_shl_cnt_i32(mag23, 8u, sat);
}

/* ---- Current loop ------------------------------------------------------- */

/*
 * Steady-state voltage amplitude of the demand (Q31 of 1024 V), weighted by
 * ff_gain: |(Rs i_d - w_s sigma Ls i_q) + j (Rs i_q + w_s Ls i_d)|. The
 * frequency-current products are Q31 per-unit products; each component is
 * below 0.5 pu with the default machine at 80 Hz, so the sum of squares is
 * below 2^63 and its root below 2^31.5 (saturated and counted beyond Q31).
 */
static q31_t dc_feedforward_q(drive_control_q *c, q31_t freq, q31_t iq) {
    uint32_t *sat = &c->sat_count;
    q31_t f_iq = fp_mul_cnt_q31(freq, iq, sat);
    q31_t f_id = fp_mul_cnt_q31(freq, c->i_mag, sat);
    q31_t vd = fp_sat_cnt_q31((int64_t)dc_apply(&c->k_rs, c->i_mag, sat) -
                                  (int64_t)dc_apply(&c->k_sls, f_iq, sat),
                              sat);
    q31_t vq = fp_sat_cnt_q31((int64_t)dc_apply(&c->k_rs, iq, sat) +
                                  (int64_t)dc_apply(&c->k_ls, f_id, sat),
                              sat);
    uint64_t sum = (uint64_t)((int64_t)vd * vd) + (uint64_t)((int64_t)vq * vq);
    q31_t mag = fp_sat_cnt_q31((int64_t)dc_isqrt_round_u64(sum), sat);
    return dc_apply(&c->k_ff, mag, sat);
}

/*
 * m = v / (Vdc / 2) in Q15: v is Q31 and Vdc is taken in Q15 of the same
 * base, so m * 2^15 = v_q31 / vdc_q15, one 32-bit unsigned division
 * (rounded). vdc_q15 >= 32 (vdc_min >= 2^16 in Q31) and v < 2^31, so the
 * quotient fits; it is clamped to m_max.
 */
static q15_t dc_modulation_q(const drive_control_q *c, q31_t v, q31_t vdc) {
    uint32_t vdc15 = (uint32_t)fp_shr_round_i32(vdc, 16u);
    uint32_t m = ((uint32_t)v + vdc15 / 2u) / vdc15;
    if (m > (uint32_t)c->m_max) {
        return c->m_max;
    }
    return (q15_t)m;
}

/* The current loop proper; the measured magnitude is already in out. */
static void dc_current_loop_q(drive_control_q *c, q31_t i_dem, q31_t freq, q31_t slip,
                              q31_t vdc_in, drive_control_out_q *out) {
    uint32_t *sat = &c->sat_count;
    q31_t e = fp_sat_cnt_q31((int64_t)i_dem - (int64_t)out->i_meas, sat);
    q31_t iq = dc_apply(&c->k_q, slip, sat);
    q31_t vff = dc_feedforward_q(c, freq, iq);
    q31_t vdc = (vdc_in > c->vdc_min) ? vdc_in : c->vdc_min;
    q31_t vmax = dc_apply(&c->k_vmax, vdc, sat);
    bool gen = ((slip > 0) && (freq < 0)) || ((slip < 0) && (freq > 0));
    int64_t u = (int64_t)vff + (int64_t)c->x_i;
    if (!gen) {
        u += (int64_t)dc_apply(&c->kp_i, e, sat);
    }
    q31_t v = dc_clamp(u, 0, vmax);
    int dir = (u > (int64_t)vmax) ? 1 : (u < 0) ? -1 : 0;
    if (!gen && !((dir > 0) && (e > 0)) && !((dir < 0) && (e < 0))) {
        int64_t x = (int64_t)c->x_i + (int64_t)dc_apply(&c->ki_i, e, sat);
        c->x_i = dc_clamp(x, -vmax, vmax);
    }
    out->m = dc_modulation_q(c, v, vdc);
    out->v_demand = v;
    out->i_demand = i_dem;
    out->freq = freq;
    out->slip = slip;
    out->phase_inc = wt_phase_inc_pu_q31(freq, c->inc_base);
    out->flags |= (dir > 0) ? DRIVE_CONTROL_FLAG_M_MAX : 0u;
    out->flags |= (dir < 0) ? DRIVE_CONTROL_FLAG_M_ZERO : 0u;
    out->flags |= gen ? DRIVE_CONTROL_FLAG_GENERATING : 0u;
}

void drive_control_current_step_q(drive_control_q *c, q31_t i_demand, q31_t freq, q31_t slip,
                                  const drive_control_in_q *in, drive_control_out_q *out) {
    out->flags = 0u;
    out->speed_ref = c->speed_ref;
    out->i_meas = dc_magnitude_q(in, &c->sat_count);
    dc_current_loop_q(c, (i_demand > 0) ? i_demand : 0, freq, slip, in->vdc, out);
}

/* ---- Speed loop and the full frame ------------------------------------- */

/* Standstill: zero outputs, states cleared for the next start. */
static void dc_idle_q(drive_control_q *c, drive_control_out_q *out) {
    c->idle = true;
    c->speed_ref = 0;
    c->x_w = 0;
    c->x_i = 0;
    out->m = 0;
    out->freq = 0;
    out->phase_inc = 0u;
    out->slip = 0;
    out->speed_ref = 0;
    out->i_demand = 0;
    out->v_demand = 0;
    out->flags = DRIVE_CONTROL_FLAG_IDLE;
}

/* Moves the reference towards the clamped command by at most one ramp step. */
static uint32_t dc_ramp_q(drive_control_q *c, q31_t cmd) {
    int64_t d = (int64_t)cmd - (int64_t)c->speed_ref;
    if (d > (int64_t)c->ramp_step) {
        c->speed_ref += c->ramp_step;
        return DRIVE_CONTROL_FLAG_RAMP;
    }
    if (d < -(int64_t)c->ramp_step) {
        c->speed_ref -= c->ramp_step;
        return DRIVE_CONTROL_FLAG_RAMP;
    }
    c->speed_ref = cmd;
    return 0u;
}

/*
 * Speed PI -> slip -> stator frequency (see drive_control.h); writes the
 * applied slip and frequency and returns the limit flags.
 */
static uint32_t dc_speed_loop_q(drive_control_q *c, q31_t w, q31_t *freq, q31_t *slip) {
    uint32_t *sat = &c->sat_count;
    uint32_t flags = 0u;
    q31_t e = fp_sat_cnt_q31((int64_t)c->speed_ref - (int64_t)w, sat);
    int64_t u = (int64_t)dc_apply(&c->kp_w, e, sat) + (int64_t)c->x_w;
    q31_t slip_cmd = dc_clamp(u, -c->slip_lim, c->slip_lim);
    int dir = dc_sign(u - (int64_t)slip_cmd);
    flags |= (dir != 0) ? DRIVE_CONTROL_FLAG_SLIP_LIMIT : 0u;
    q31_t fr = dc_apply(&c->k_fr, w, sat);
    int64_t fs = (int64_t)fr + (int64_t)slip_cmd;
    *freq = dc_clamp(fs, -c->freq_max, c->freq_max);
    if (fs != (int64_t)*freq) {
        dir = dc_sign(fs - (int64_t)*freq);
        flags |= DRIVE_CONTROL_FLAG_FREQ_LIMIT;
    }
    *slip = dc_clamp((int64_t)*freq - (int64_t)fr, -c->slip_lim, c->slip_lim);
    if (!((dir > 0) && (e > 0)) && !((dir < 0) && (e < 0))) {
        int64_t x = (int64_t)c->x_w + (int64_t)dc_apply(&c->ki_w, e, sat);
        c->x_w = dc_clamp(x, -c->slip_lim, c->slip_lim);
    }
    return flags;
}

/*
 * I* = sqrt(i_mag^2 + (k_q slip)^2), Q31 of 256 A. Both terms are below
 * 0.25 pu, so the sum of squares is far below 2^63 and the root below 2^31.
 */
static q31_t dc_current_demand_q(drive_control_q *c, q31_t slip) {
    q31_t iq = dc_apply(&c->k_q, slip, &c->sat_count);
    uint64_t sum = (uint64_t)((int64_t)c->i_mag * c->i_mag) + (uint64_t)((int64_t)iq * iq);
    return fp_sat_cnt_q31((int64_t)dc_isqrt_round_u64(sum), &c->sat_count);
}

void drive_control_step_q(drive_control_q *c, const drive_control_in_q *in,
                          drive_control_out_q *out) {
    q31_t cmd = dc_clamp((int64_t)in->speed_cmd, -c->speed_max, c->speed_max);
    out->i_meas = dc_magnitude_q(in, &c->sat_count);
    if ((cmd <= c->idle_speed) && (cmd >= -c->idle_speed) && (in->w <= c->idle_speed) &&
        (in->w >= -c->idle_speed)) {
        dc_idle_q(c, out);
        return;
    }
    if (c->idle) {
        /* Leaving standstill: start the reference where the shaft is. */
        c->idle = false;
        c->speed_ref = dc_clamp((int64_t)in->w, -c->speed_max, c->speed_max);
        c->x_w = 0;
        c->x_i = 0;
    }
    q31_t freq;
    q31_t slip;
    uint32_t flags = dc_ramp_q(c, cmd);
    flags |= dc_speed_loop_q(c, in->w, &freq, &slip);
    out->flags = flags;
    out->speed_ref = c->speed_ref;
    dc_current_loop_q(c, dc_current_demand_q(c, slip), freq, slip, in->vdc, out);
}
