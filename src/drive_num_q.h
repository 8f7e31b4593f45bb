/*
 * The drive segment's numeric adapter of the fixed-point build: what
 * drive_segment.c's one flow needs that differs between the builds (its
 * twin is drive_num_f32.h; drive_segment.h includes the build's by
 * UUV_NUMERIC). Every signal is per unit of the bases in
 * models/drive/drive_units.h: voltages and currents in the fast segment
 * Q3.28 (of 1024 V, 256 A), the motor's and the controller's Q31; integer
 * arithmetic only on the fast tick and in the motor task; the slow
 * exchange converts to SI in double.
 *
 * DRIVE_NUM(name) is the build's twin of a model's name (name_q);
 * num_val a signal, num_sum its sum over a motor frame, num_slow over a
 * slow frame; the num_*() functions are the build's arithmetic.
 */
#ifndef UUV_DRIVE_NUM_Q_H
#define UUV_DRIVE_NUM_Q_H

#include <stdbool.h>
#include <stdint.h>

#include "fixedpoint/fixedpoint.h"
#include "math/umath.h"
#include "models/drive/control/drive_control.h"
#include "models/drive/drive_units.h"
#include "models/drive/inverter/power_stage.h"
#include "models/drive/inverter/power_stage_fast.h"
#include "models/drive/motor/induction_motor.h"
#include "models/drive/pwm/pwm.h"

#define DRIVE_NUM(name) name##_q

typedef int32_t num_val;   /* Q3.28 (fast segment) or Q31 (motor, controller) */
typedef int64_t num_sum;   /* Q3.28 summed over a motor frame; the audit's A^2 2^16 */
typedef int64_t num_filt;  /* the filter coupling's state, Q3.28 << 16 */
typedef int64_t num_slow;  /* sums over a slow frame */
typedef uint32_t num_frac; /* the filter's gain per fast step (Q16), a count of steps */
typedef uint32_t num_count; /* what a frame's mean divides by: the steps, n */
typedef int64_t num_lead;  /* a count of fast steps in products */

/*
 * The fast companion's gain on the real-time path, a_ss h1 * 4 * 2^32
 * (Q3.28 current step per Q3.28 volt; 0 where it does not fit), named
 * k32 (the Thumb-2 kernel's offsets name it), and the build's other
 * constants of the companion and the EMF.
 */
#define NUM_RT_GAIN k32
typedef struct {
    int32_t k_mant;   /* the gain as mantissa and right shift, for any step */
    uint32_t k_shift;
    int32_t e_mant;   /* 1 / (k_l N) as mantissa ... */
    uint32_t e_shift; /* ... and shift: Q3.28 volts per Q31 current change */
} num_consts;

/* The controller's saturation count: after its last step, and as the motor task took it. */
#define NUM_CONTROL_SAT_FIELDS uint32_t ctl_sat, ctl_sat_taken;
#define NUM_CONTROL_STEPPED(d) ((d)->ctl_sat = (d)->ctl.sat_count)
#define NUM_CONTROL_TAKEN(d) ((d)->ctl_sat_taken = (d)->ctl_sat)
/* The saturations the build's motor and controller count. */
#define NUM_MODEL_SAT(d) ((d)->motor.sat_count + (d)->ctl_sat_taken)

#define NUM_Q31_ONE 2147483648.0
#define NUM_Q28_ONE 268435456.0
#define NUM_PWM_DUTY_ONE PWM_DUTY_ONE_Q

/* Splits a positive factor into an int32 mantissa below 2^30 and a right shift. */
static inline void num_factor_split(double f, int32_t *mant, uint32_t *shift) {
    uint32_t sh = 0u;
    double scale = 1.0; /* 2^sh, exact */
    while (sh < 62u && f * (scale * 2.0) < 1073741824.0) {
        scale *= 2.0;
        sh++;
    }
    *mant = (int32_t)(f * scale + 0.5);
    *shift = sh;
}

/*
 * The companion's constants from a_ss [1/H] at the fast step fast_s [s]
 * and n fast steps a frame: false when the gain is out of range.
 */
static inline bool num_companion_init(num_consts *k, num_val *rt_gain, double a_ss,
                                      double fast_s, uint32_t n) {
    /* a_ss h1 in Q3.28 current (256 A) per Q3.28 volt (1024 V). */
    double k_l = a_ss * fast_s * 4.0;
    if (!(k_l > 1e-7 && k_l < 8.0)) {
        return false;
    }
    num_factor_split(k_l, &k->k_mant, &k->k_shift);
    /* The real-time path's form: k_l 2^32 (below 2^31, at least 2^20 for precision). */
    *rt_gain = (k_l < 0.5 && k_l > 2.5e-4) ? (int32_t)(k_l * 4294967296.0 + 0.5) : 0;
    /* The EMF's current drop per Q31 (motor) current change: 1 / (8 k_l N). */
    num_factor_split(1.0 / (8.0 * k_l * (double)n), &k->e_mant, &k->e_shift);
    return true;
}

/* The real-time path needs the gain in its form. */
static inline bool num_rt_gain_ok(num_val rt_gain) { return rt_gain != 0; }

/* First-order filter gain per fast step: step / frame, Q16. */
static inline num_frac num_filter_gain(uint32_t n) { return (uint32_t)(65536u / n); }

/* EMF rotation per fast step per unit frequency: 2 pi 128 Hz T / sqrt 3, Q31. */
static inline num_val num_deriv_gain(double fast_s) {
    return fp_from_f64_q31(MATH_TWO_PI_F64 * DRIVE_BASE_FREQ_HZ * fast_s / 1.7320508075688772);
}

/*
 * Steps of a correction still to come at the next mark: from the latch on
 * it runs a frame, and the latch is at the boundary or, staggered, N / 2
 * steps later.
 */
static inline num_frac num_corr_pending(bool staggered, uint32_t n) {
    return staggered ? n / 2u : n;
}

/* DRIVE_UV_TRIP_V, Q3.28 of 1024 V. */
static inline num_val num_uv_trip(void) {
    return fp_from_f64_q31(DRIVE_UV_TRIP_V / DRIVE_BASE_VOLTAGE_V / 8.0);
}

/* The real-time companion step, i + round((v - e) k32 / 2^32): one multiply-accumulate. */
static inline num_val num_companion_rt(num_val i, num_val v, num_val e, num_val k32) {
    return ps_hi_q(ps_mac_q(ps_acc_q(i), v - e, k32));
}

/*
 * The companion's current step for any step, Q3.28 of 256 A: the real-time
 * form where k32 fits (so that both paths give the same currents), else
 * i + round((v - e) k_mant / 2^k_shift).
 */
static inline num_val num_companion(const num_consts *k, num_val k32, num_val i, num_val dv) {
    if (k32 != 0) {
        return ps_hi_q(ps_mac_q(ps_acc_q(i), dv, k32));
    }
    return i + (int32_t)fp_shr_round_var_i64((int64_t)dv * k->k_mant, k->k_shift);
}

/*
 * An open motor phase in the fast companion: phase a open gives
 * (0, i_b + i_a / 2), b open (i_a + i_b / 2, 0), c open ((i_a - i_b) / 2,
 * -(i_a - i_b) / 2); the sums are formed in 64 bits and saturated.
 */
static inline void num_open_phase(int32_t i[2], uint8_t phase) {
    if (phase == 1u) {
        i[1] = fp_sat_q31((int64_t)i[1] + fp_shr_round_i32(i[0], 1u));
        i[0] = 0;
    } else if (phase == 2u) {
        i[0] = fp_sat_q31((int64_t)i[0] + fp_shr_round_i32(i[1], 1u));
        i[1] = 0;
    } else {
        i[0] = (int32_t)fp_shr_round_i64((int64_t)i[0] - i[1], 1u);
        i[1] = -i[0];
    }
}

/*
 * The energy audit's fast sums: the squares of the three inductor and
 * damping currents, each rounded to A 2^8 first (Q3.28 of 256 A is A 2^20),
 * so that a slow frame of 50000 steps stays far below 2^63 (each square is
 * at most 2^32 with the states clamped to +-1 per unit).
 */
static inline void num_audit(const power_stage_q *ps, int64_t *loss_l, int64_t *loss_d) {
    int64_t l[3], r[3];
    for (int x = 0; x < 2; x++) {
        l[x] = fp_shr_round_i32(ps->ph[x].i_l, 12u);
        r[x] = fp_shr_round_i32(ps->ph[x].i_d, 12u);
    }
    l[2] = -l[0] - l[1];
    r[2] = -r[0] - r[1];
    *loss_l += l[0] * l[0] + l[1] * l[1] + l[2] * l[2];
    *loss_d += r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
}

/* The general power stage's motor currents (Q15) from the companion's (Q3.28). */
static inline void num_stage_motor_in(power_stage_in_q *in, const int32_t i_fast[2]) {
    in->i_motor[0] = fp_sat_q15(fp_shr_round_i32(i_fast[0], 13u));
    in->i_motor[1] = fp_sat_q15(fp_shr_round_i32(i_fast[1], 13u));
}

/* One step of the first-order filter coupling on a Q3.28 voltage. */
static inline int64_t num_filter(int64_t filt, int32_t v, uint32_t k) {
    return filt + ((int64_t)v * 65536 - filt) * (int64_t)k / 65536;
}

/* A voltage as the filter coupling's state. */
static inline int64_t num_filt_of(int32_t v) { return (int64_t)v * 65536; }

/* Counts the motor task's saturations (sat) in the drive's count. */
static inline void num_count_sat(uint32_t *count, uint32_t sat) { *count += sat; }

/* What the frame means of n fast steps take (num_count). */
static inline uint32_t num_frame_count(uint32_t n) { return n; }

/* round(sum * 8 / n) as Q31, saturating: a frame mean of Q3.28 values. */
static inline q31_t num_frame_mean(int64_t sum, uint32_t n, uint32_t *sat) {
    int64_t scaled = sum * 8;
    int64_t half = (int64_t)(n / 2u);
    int64_t q = (scaled >= 0) ? fp_div_i64_u32(scaled + half, n) : -fp_div_i64_u32(-scaled + half, n);
    return fp_sat_cnt_q31(q, sat);
}

/* A Q3.28 voltage at the boundary as the motor's Q31. */
static inline q31_t num_from_mark(int32_t v, uint32_t *sat) {
    return fp_sat_cnt_q31((int64_t)v * 8, sat);
}

/* The filter coupling's state as the motor's Q31. */
static inline q31_t num_from_filt(int64_t f, uint32_t *sat) {
    return fp_sat_cnt_q31(fp_shr_round_i64(f, 13u), sat);
}

/* The third phase, -a - b, saturated. */
static inline q31_t num_third(q31_t a, q31_t b) { return fp_sat_q31(-(int64_t)a - (int64_t)b); }

/* A motor current (Q31) in the companion's Q3.28: three bits down. */
static inline int32_t num_fast_of_motor(q31_t i) { return fp_shr_round_i32(i, 3u); }

/* What the last correction corr has still to bring after the mark: corr pending / n. */
static inline int32_t num_pending(int32_t corr, uint32_t pending, uint32_t n) {
    return (int32_t)fp_div_i64_u32((int64_t)corr * (int64_t)pending, n);
}

/* The EMF of a frame, Q3.28 of 1024 V: vbar - (i_end - i_start) / (a_ss h N). */
static inline int32_t num_emf(const num_consts *k, q31_t v_mean, q31_t i_end, q31_t i_start) {
    int64_t di = (int64_t)i_end - i_start;
    int64_t drop = fp_shr_round_var_i64(di * k->e_mant, k->e_shift);
    return (int32_t)fp_sat_q31(fp_shr_round_i64(v_mean, 3u) - drop);
}

/* Its change per fast step from the last frame's (FOH). */
static inline int32_t num_emf_slope(int32_t e, int32_t e_prev, uint32_t n) {
    return (int32_t)fp_div_i64_u32((int64_t)e - e_prev, n);
}

/*
 * Its change per fast step along its rotation (DERIV), de/dt = w_s (e_c -
 * e_b) / sqrt 3 for phase a, (e_a - e_c) / sqrt 3 for b: g = w_s T /
 * sqrt 3 from the frequency in force, then each phase's change.
 */
static inline q31_t num_emf_turn(const drive_control_out_q *cmd, q31_t k_deriv) {
    return fp_mul_q31(cmd->freq, k_deriv);
}
static inline int32_t num_emf_turn_a(q31_t g, int32_t e_a, int32_t e_b) {
    return (int32_t)fp_shr_round_i64(((int64_t)-e_a - 2 * (int64_t)e_b) * g, 31u);
}
static inline int32_t num_emf_turn_b(q31_t g, int32_t e_a, int32_t e_b) {
    return (int32_t)fp_shr_round_i64((2 * (int64_t)e_a + (int64_t)e_b) * g, 31u);
}

/* How many fast steps ahead the published EMF is: 1.5 frames less a step. */
static inline int64_t num_emf_lead(uint32_t n) { return 3 * (int64_t)n / 2 - 1; }

/*
 * The EMF published for the next frame's first step: lead steps ahead, and
 * the drift correction spread over the frame, corr / (k_l N) volts less.
 */
static inline int32_t num_emf_ahead(const num_consts *k, int32_t e, int32_t de, int32_t corr,
                                    int64_t lead) {
    int64_t steer = fp_shr_round_var_i64((int64_t)corr * 8 * k->e_mant, k->e_shift);
    return (int32_t)fp_sat_q31((int64_t)e + (int64_t)de * lead - steer);
}

/*
 * A frame's DC-link voltage into the slow sums: its sum (Q3.28), and the
 * square of its mean times n (Q3.28): the ripple's variance, about 1e-6
 * of the square, is left out of the battery's power.
 */
static inline void num_vdc_sums(int64_t *v_dc, int64_t *v_dc_sq, int64_t v_dc_sum, uint32_t n) {
    *v_dc += v_dc_sum;
    int64_t vdc_mean = fp_div_i64_u32(v_dc_sum, n);
    *v_dc_sq += fp_shr_floor_i64(vdc_mean * vdc_mean, 28u) * (int64_t)n;
}

/* A motor current's square for the rms sums, Q15 squared. */
static inline int64_t num_i_sq(q31_t i) {
    q15_t i15 = fp_narrow_q15(i);
    return (int64_t)i15 * i15;
}

/* The mechanical power te w, Q31 of 512 N m * 512 rad/s. */
static inline int64_t num_power(q31_t te, q31_t w) {
    return fp_shr_round_i64((int64_t)te * (int64_t)w, 31u);
}

/* One step of the speed's first-order filter with n steps' time constant. */
static inline q31_t num_lowpass(q31_t filt, q31_t w, uint32_t n) {
    return filt + (q31_t)fp_div_i64_u32((int64_t)w - filt, n);
}

static inline q31_t num_motor_w(const induction_motor_out_q *o) { return o->w; }
static inline q31_t num_motor_te(const induction_motor_out_q *o) { return o->te; }
static inline double num_motor_rpm(const induction_motor_out_q *o) {
    return (double)o->n_rpm_q16 / 65536.0;
}

/* The controller's inputs (the phase-a measurement with the sensor's offset, the frame's
 * mean DC-link voltage). */
static inline void num_control_in(drive_control_in_q *in, q31_t speed_cmd,
                                  const induction_motor_out_q *o, const q31_t i_end[2],
                                  q31_t i_offset, int64_t v_dc_sum, uint32_t n, uint32_t *sat) {
    in->speed_cmd = speed_cmd;
    in->w = o->w;
    in->i_a = fp_sat_q31((int64_t)i_end[0] + i_offset);
    in->i_b = i_end[1];
    in->i_c = o->i_c;
    in->vdc = num_frame_mean(v_dc_sum, n, sat);
}

/* Under-voltage: the frame's mean DC-link voltage below uv. */
static inline bool num_undervoltage(int64_t v_dc_sum, uint32_t n, int32_t uv) {
    return v_dc_sum < (int64_t)uv * (int64_t)n;
}

/* SI from the slow segment's sums and the signals (in double, off the fast path). */
static inline double num_si_volts(double x) {
    return x / NUM_Q28_ONE * DRIVE_BASE_VOLTAGE_V;
}
static inline double num_si_volts_sq(double x) {
    return x / NUM_Q28_ONE * DRIVE_BASE_VOLTAGE_V * DRIVE_BASE_VOLTAGE_V;
}
static inline double num_si_speed(double x) { return x / NUM_Q31_ONE * DRIVE_BASE_SPEED_RADPS; }
static inline double num_si_torque(double x) { return x / NUM_Q31_ONE * DRIVE_BASE_TORQUE_NM; }
static inline double num_si_power(double x) {
    return x / NUM_Q31_ONE * DRIVE_BASE_TORQUE_NM * DRIVE_BASE_SPEED_RADPS;
}
/* The rms sums' mean square per unit, and a per-unit rms current in A. */
static inline double num_si_i_sq_pu(double x) { return x / (32768.0 * 32768.0); }
static inline double num_si_rms_amps(double x) { return x * DRIVE_BASE_CURRENT_A; }
/* The audit's sums of A^2 2^16 in A^2. */
static inline double num_si_audit(double x) { return x / 65536.0; }
/* A Q3.28 current in A, and the same through the premultiplied scale (the averaged trace's). */
static inline double num_si_amps(double x) { return x / NUM_Q28_ONE * DRIVE_BASE_CURRENT_A; }
static inline double num_si_amps_scaled(num_val x) {
    return (double)x * (DRIVE_BASE_CURRENT_A / NUM_Q28_ONE);
}
/* A Q3.28 voltage in V through the premultiplied scale (the trace's). */
static inline double num_trace_volts(num_val x) {
    return (double)x * (DRIVE_BASE_VOLTAGE_V / NUM_Q28_ONE);
}
static inline double num_si_m(const drive_control_out_q *c) { return (double)c->m / 32768.0; }
static inline double num_si_f(const drive_control_out_q *c) {
    return (double)c->freq / NUM_Q31_ONE * DRIVE_BASE_FREQ_HZ;
}

/* SI to the build's units (the slow segment's requests). */
static inline q31_t num_from_amps(double a) { return fp_from_f64_q31(a / DRIVE_BASE_CURRENT_A); }
static inline q31_t num_from_speed(double w) {
    return fp_from_f64_q31(w / DRIVE_BASE_SPEED_RADPS);
}

#endif /* UUV_DRIVE_NUM_Q_H */
