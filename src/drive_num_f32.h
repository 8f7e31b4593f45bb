/*
 * The drive segment's numeric adapter of the float build (the twin of
 * drive_num_q.h, which says what each function is): single precision and
 * SI units. Sums over a motor frame (at most a few hundred fast steps) are
 * float; the motor task adds them into double sums for the slow frame.
 */
#ifndef UUV_DRIVE_NUM_F32_H
#define UUV_DRIVE_NUM_F32_H

#include <stdbool.h>
#include <stdint.h>

#include "math/umath.h"
#include "models/drive/control/drive_control.h"
#include "models/drive/inverter/power_stage.h"
#include "models/drive/inverter/power_stage_fast.h"
#include "models/drive/motor/induction_motor.h"
#include "models/drive/pwm/pwm.h"

#define DRIVE_NUM(name) name##_f32

typedef float num_val;   /* [V], [A], [rad/s] */
typedef float num_sum;   /* [V] summed; the audit's [A^2] */
typedef float num_filt;  /* [V] */
typedef double num_slow; /* in double: one slow frame holds up to 50000 fast steps */
typedef float num_frac;  /* [-] */
typedef float num_count; /* what a frame's mean multiplies by: 1 / n */
typedef float num_lead;  /* [-] a count of fast steps */

/* The companion's gain [A/V per fast step], a_ss h1, and 1 / (a_ss h2) [V/A]. */
#define NUM_RT_GAIN k_l
typedef struct {
    float e_per_di;
} num_consts;

/* The float controller and motor count no saturations. */
#define NUM_CONTROL_SAT_FIELDS
#define NUM_CONTROL_STEPPED(d) ((void)(d))
#define NUM_CONTROL_TAKEN(d) ((void)(d))
#define NUM_MODEL_SAT(d) 0u

#define NUM_PWM_DUTY_ONE 1.0f

static inline bool num_companion_init(num_consts *k, num_val *rt_gain, double a_ss,
                                      double fast_s, uint32_t n) {
    double k_l = a_ss * fast_s;
    if (!(k_l > 1e-6 / 32.0 && k_l < 2.0)) {
        return false;
    }
    *rt_gain = (float)k_l;
    k->e_per_di = (float)(1.0 / (k_l * (double)n));
    return true;
}

static inline bool num_rt_gain_ok(num_val rt_gain) {
    (void)rt_gain;
    return true;
}

static inline num_frac num_filter_gain(uint32_t n) { return 1.0f / (float)n; }

/* [1/Hz] 2 pi T / sqrt 3 */
static inline num_val num_deriv_gain(double fast_s) {
    return (float)(MATH_TWO_PI_F64 * fast_s / 1.7320508075688772);
}

/* The share of a correction still to come at the next mark. */
static inline num_frac num_corr_pending(bool staggered, uint32_t n) {
    const uint32_t half = n / 2u;
    return staggered ? (float)half / (float)n : 1.0f;
}

static inline num_val num_uv_trip(void) { return (float)DRIVE_UV_TRIP_V; }

static inline num_val num_companion_rt(num_val i, num_val v, num_val e, num_val k_l) {
    return i + (v - e) * k_l;
}

static inline num_val num_companion(const num_consts *k, num_val k_l, num_val i, num_val dv) {
    (void)k;
    return i + dv * k_l;
}

static inline void num_open_phase(float i[2], uint8_t phase) {
    if (phase == 1u) {
        i[1] += 0.5f * i[0];
        i[0] = 0.0f;
    } else if (phase == 2u) {
        i[0] += 0.5f * i[1];
        i[1] = 0.0f;
    } else {
        i[0] = 0.5f * (i[0] - i[1]);
        i[1] = -i[0];
    }
}

/* [A^2] */
static inline void num_audit(const power_stage_f32 *ps, float *loss_l, float *loss_d) {
    const float l2 = -ps->ph[0].i_l - ps->ph[1].i_l;
    const float r2 = -ps->ph[0].i_d - ps->ph[1].i_d;
    *loss_l += ps->ph[0].i_l * ps->ph[0].i_l + ps->ph[1].i_l * ps->ph[1].i_l + l2 * l2;
    *loss_d += ps->ph[0].i_d * ps->ph[0].i_d + ps->ph[1].i_d * ps->ph[1].i_d + r2 * r2;
}

static inline void num_stage_motor_in(power_stage_in_f32 *in, const float i_fast[2]) {
    in->i_motor_a[0] = i_fast[0];
    in->i_motor_a[1] = i_fast[1];
}

static inline float num_filter(float filt, float v, float k) { return filt + (v - filt) * k; }

static inline float num_filt_of(float v) { return v; }

/* The float means do not saturate: sat stays 0. */
static inline void num_count_sat(uint32_t *count, uint32_t sat) {
    (void)count;
    (void)sat;
}

static inline float num_frame_count(uint32_t n) { return 1.0f / (float)n; }

static inline float num_frame_mean(float sum, float inv_n, uint32_t *sat) {
    (void)sat;
    return sum * inv_n;
}

static inline float num_from_mark(float v, uint32_t *sat) {
    (void)sat;
    return v;
}

static inline float num_from_filt(float f, uint32_t *sat) {
    (void)sat;
    return f;
}

static inline float num_third(float a, float b) { return -a - b; }

static inline float num_fast_of_motor(float i) { return i; }

static inline float num_pending(float corr, float pending, uint32_t n) {
    (void)n;
    return corr * pending;
}

static inline float num_emf(const num_consts *k, float v_mean, float i_end, float i_start) {
    return v_mean - (i_end - i_start) * k->e_per_di;
}

static inline float num_emf_slope(float e, float e_prev, uint32_t n) {
    return (e - e_prev) * (1.0f / (float)n);
}

static inline float num_emf_turn(const drive_control_out_f32 *cmd, float k_deriv) {
    return cmd->freq_hz * k_deriv;
}
static inline float num_emf_turn_a(float g, float e_a, float e_b) {
    return (-e_a - 2.0f * e_b) * g;
}
static inline float num_emf_turn_b(float g, float e_a, float e_b) {
    return (2.0f * e_a + e_b) * g;
}

static inline float num_emf_lead(uint32_t n) { return 1.5f * (float)n - 1.0f; }

static inline float num_emf_ahead(const num_consts *k, float e, float de, float corr, float lead) {
    return (e + de * lead) - corr * k->e_per_di;
}

static inline void num_vdc_sums(double *v_dc, double *v_dc_sq, float v_dc_sum, uint32_t n) {
    float nf = (float)n;
    double vdc_mean = (double)(v_dc_sum / nf);
    *v_dc += (double)v_dc_sum;
    *v_dc_sq += vdc_mean * vdc_mean * (double)nf;
}

static inline double num_i_sq(float i) {
    const float sq = i * i;
    return (double)sq;
}

static inline double num_power(float te, float w) { return (double)(te * w); }

static inline float num_lowpass(float filt, float w, uint32_t n) {
    return filt + (w - filt) / (float)n;
}

static inline float num_motor_w(const induction_motor_out_f32 *o) { return o->w_radps; }
static inline float num_motor_te(const induction_motor_out_f32 *o) { return o->te_nm; }
static inline double num_motor_rpm(const induction_motor_out_f32 *o) { return (double)o->n_rpm; }

static inline void num_control_in(drive_control_in_f32 *in, float speed_cmd,
                                  const induction_motor_out_f32 *o, const float i_end[2],
                                  float i_offset, float v_dc_sum, float inv_n, uint32_t *sat) {
    in->speed_cmd_radps = speed_cmd;
    in->w_radps = o->w_radps;
    in->i_a = i_end[0] + i_offset;
    in->i_b = i_end[1];
    in->i_c = o->i_c;
    in->vdc_v = num_frame_mean(v_dc_sum, inv_n, sat);
}

static inline bool num_undervoltage(float v_dc_sum, float inv_n, float uv) {
    (void)uv; /* num_uv_trip(), compared as the constant it is */
    return v_dc_sum * inv_n < num_uv_trip();
}

/* The build's units are SI: the conversions are the identity. */
static inline double num_si_volts(double x) { return x; }
static inline double num_si_volts_sq(double x) { return x; }
static inline double num_si_speed(double x) { return x; }
static inline double num_si_torque(double x) { return x; }
static inline double num_si_power(double x) { return x; }
static inline double num_si_i_sq_pu(double x) { return x; }
static inline double num_si_rms_amps(double x) { return x; }
static inline double num_si_audit(double x) { return x; }
static inline double num_si_amps(double x) { return x; }
static inline double num_si_amps_scaled(num_val x) { return (double)x; }
static inline double num_trace_volts(num_val x) { return (double)x; }
static inline double num_si_m(const drive_control_out_f32 *c) { return (double)c->m; }
static inline double num_si_f(const drive_control_out_f32 *c) { return (double)c->freq_hz; }

static inline float num_from_amps(double a) { return (float)a; }
static inline float num_from_speed(double w) { return (float)w; }

#endif /* UUV_DRIVE_NUM_F32_H */
