/*
 * The averaged inverter: the layered alternative of the switching power
 * stage (paper section 3), in two forms, both driven by the leg duty
 * cycles d_x = (1 + m sin(theta_x)) / 2 of the modulator's references
 * (pwm_average_*, taken at the middle of each step) instead of switching:
 * no ripple, the same fundamental.
 *   - inverter_avg_*: the same terminals, DC link and LC filter as the
 *     switching stage (power_stage.h), runnable at the motor's 100 us
 *     frame with substeps (below); the stage-level comparison with the
 *     switching model (test_power_stage.c, docs/drive_power.md).
 *   - inverter_quasi_static_*: the quasi-static stage the executive's averaged layer
 *     runs with the motor at the controller's 800 us frame (further down).
 *
 * Step. One call advances one frame of n_sub equal substeps; each substep
 * takes the duties and runs power_stage_step_* at frame / n_sub, with the
 * motor currents and the battery companion held over the frame. Why
 * substeps: the trapezoidal rule is A-stable, so the filter stays stable at
 * any step, but it maps the analogue resonance w0 to the digital one
 * (2/T) atan(w0 T / 2): at T = 100 us the 1.07 kHz corner lands 3.5 %
 * low, at 25 us (n_sub = 4) 0.24 %. The fundamental (<= 55 Hz) is within
 * 1e-4 either way; the DC link's forward Euler needs T G / C_dc < 2 (the
 * battery conversion keeps it below 0.5). docs/drive_power.md has the
 * measured comparison with the switching model.
 */
#ifndef UUV_INVERTER_AVG_H
#define UUV_INVERTER_AVG_H

#include <stdint.h>

#include "models/drive/inverter/power_stage.h"
#include "models/drive/pwm/pwm.h"

#define INVERTER_AVG_SUB_MAX 64u /* most substeps per frame */

typedef enum {
    INVERTER_AVG_OK = 0,
    INVERTER_AVG_ERR_NULL,   /* a pointer argument was NULL */
    INVERTER_AVG_ERR_SUB,    /* n_sub not in 1..INVERTER_AVG_SUB_MAX, or frame not a multiple */
    INVERTER_AVG_ERR_PWM,    /* the modulator rejected its parameters */
    INVERTER_AVG_ERR_STAGE   /* the power stage rejected its parameters */
} inverter_avg_status;

typedef struct {
    pwm_q mod;           /* references only (its carrier is not used) */
    power_stage_q stage; /* stepped at frame / n_sub */
    uint32_t n_sub;
} inverter_avg_q;

typedef struct {
    pwm_f32 mod;
    power_stage_f32 stage;
    uint32_t n_sub;
} inverter_avg_f32;

/*
 * Initialises the modulator (in mode PWM_AVERAGED whatever pp says; only
 * its reference phase is used) and the power stage at the substep
 * frame_ns / n_sub (frame_ns must be a multiple of n_sub). The power-stage
 * parameters must outlive the instance. On an error the instance may be
 * partly written.
 */
inverter_avg_status inverter_avg_init_q(inverter_avg_q *inv, const pwm_params *pp,
                                        const power_stage_params *sp, uint32_t frame_ns,
                                        uint32_t n_sub, double v_dc0_v);
inverter_avg_status inverter_avg_init_f32(inverter_avg_f32 *inv, const pwm_params *pp,
                                          const power_stage_params *sp, uint32_t frame_ns,
                                          uint32_t n_sub, double v_dc0_v);

/*
 * One frame: n_sub substeps. in->duty is ignored (the duties come from the
 * references); in->battery must come from power_stage_battery_*() of
 * inv->stage (it depends on the substep). Total; integer only in the fixed
 * twin.
 */
void inverter_avg_step_q(inverter_avg_q *inv, const power_stage_in_q *in);
void inverter_avg_step_f32(inverter_avg_f32 *inv, const power_stage_in_f32 *in);

/*
 * ---- The quasi-static averaged stage (the executive's averaged layer) ----
 *
 * For frames far longer than the filter's and the DC link's time
 * constants: the executive runs it at the controller's 800 us frame,
 * together with the motor. At such a frame the LC filter above cannot be
 * stepped (the motor current held over the frame meets the 1.07 kHz
 * resonance), and it need not be: at the fundamental (<= 55 Hz) its
 * resonance is 20 times higher, so the filter acts through its impedances
 * alone.
 *   - Series branch, R_L + j w L: 0.33 ohm at 52 Hz, 7 % of the motor's
 *     impedance, not negligible. It is in series with the motor's stator,
 *     so the caller adds it there (Rs + R_L, Lls + L: exact for this
 *     branch) and this stage's terminals are the inverter's.
 *   - Shunt branch (C, R_d + C_d): left out. Through L it raises the motor
 *     voltage by w^2 L C_total = 0.3 % at 33 Hz, which the current loop
 *     absorbs; its reactive current (about 4 A at 33 Hz) never reached
 *     the motor anyway.
 *   - DC link: C_dc dv/dt = G (e - v) - i_dc, with the battery companion
 *     (G, e = b / G) and the inverter's current i_dc = sum_x d_x i_x held
 *     over the frame, solved exactly:
 *       v' = v + alpha (e - v) - beta i_dc,
 *       alpha = 1 - exp(-T G / C_dc),  beta = alpha / G  (T / C_dc when G = 0).
 *     The time constant C_dc / G is 0.28 ms, so at T = 800 us alpha is 0.94:
 *     the bus settles within the frame, and the update is stable for any
 *     T, G and C_dc (the contactor open, G = 0: the capacitor alone).
 *   - Terminal voltages, the frame means of the inverter's phase voltages:
 *       u_x = v' (d_x - (d_a + d_b + d_c) / 3),
 *     with the duties of the references at the frame's middle (the frame
 *     mean of a sinusoid to second order: 0.12 % low in amplitude at 33 Hz
 *     and 800 us, sin(x) / x with x = pi f T) and v' the settled bus.
 *   - The currents in i_dc are the motor's at the frame's middle, where the
 *     duties are taken: those at its start turned by the references'
 *     advance over half a frame (exact for a steady rotation). With the
 *     start values the power v' i_dc lags the motor's by half a frame,
 *     4.8 degrees at 33 Hz, which at the motor's power factor put the
 *     battery's energy 14 % low over the bench start-up.
 * Energy: the stage is lossless, v' i_dc = sum_x u_x i_x (mid-frame currents).
 * Measured (docs/drive_power.md section 4, make bench): against the
 * single-rate switching-event reference the shaft speed of the bench's
 * start-up is within 0.01 % RMS.
 */

/* Fixed twin. */
typedef struct {
    int32_t e;        /* [V] b / G, Q3.28 of 1024 V, in [0, 1) */
    q31_t alpha;      /* [-] 1 - exp(-T G / C_dc), Q31 in [0, 1) */
    int32_t beta;     /* [ohm] alpha / G (T / C_dc when open), Q24 per unit of 4 ohm */
} inverter_quasi_static_bus_q;

typedef struct {
    pwm_q mod;          /* references only (its carrier is not used) */
    uint32_t frame_ns;  /* [ns] frame T */
    uint32_t rot_half;  /* the mod.half_inc_s that rot_c, rot_s are of */
    int32_t rot_c;      /* [-] its cosine and sine (wt_cos_q15, wt_sin_q15), Q15 */
    int32_t rot_s;
    int32_t v_dc;       /* [V] DC-link voltage at the frame's end, Q3.28 of 1024 V */
    int32_t u[2];       /* [V] terminal voltages a, b, frame means, Q3.28 of 1024 V */
    int32_t i_dc;       /* [A] inverter input current, Q3.28 of 256 A */
    uint32_t sat_count; /* DC-link voltage clamped to +-1024 V, companion values clamped */
} inverter_quasi_static_q;

/* Float twin, SI. */
typedef struct {
    float e_v;        /* [V] b / G */
    float alpha;      /* [-] */
    float beta_ohm;   /* [ohm] */
} inverter_quasi_static_bus_f32;

typedef struct {
    pwm_f32 mod;
    uint32_t frame_ns;
    uint32_t rot_half;  /* as in the fixed twin (wt_cos_f32, wt_sin_f32) */
    float rot_c;
    float rot_s;
    float v_dc;         /* [V] */
    float u[2];         /* [V] */
    float i_dc;         /* [A] */
    uint32_t sat_count; /* DC-link voltage clamped to +-1024 V */
} inverter_quasi_static_f32;

/*
 * Initialises the modulator (mode PWM_AVERAGED whatever pp says) at the
 * frame frame_ns (100 ns to 1 ms) and the bus at v_dc0_v (clamped to
 * [0, 1024) V), terminals at zero. ERR_NULL, or ERR_PWM for a frame the
 * modulator refuses.
 */
inverter_avg_status inverter_quasi_static_init_q(inverter_quasi_static_q *inv, const pwm_params *pp,
                                                 uint32_t frame_ns, double v_dc0_v);
inverter_avg_status inverter_quasi_static_init_f32(inverter_quasi_static_f32 *inv,
                                                   const pwm_params *pp, uint32_t frame_ns,
                                                   double v_dc0_v);

/*
 * The DC-link update's constants for the battery companion i = G v - b
 * (g_s [S], b_a [A], battery.h convention) and the capacitance c_dc_f [F]
 * (the fault may lower it), at this instance's frame. Background work
 * (double, math_exp_f64). G = 0, negative or not finite: open (a negative
 * or non-finite G counts one clamp). Returns the clamps: e to [0, 1024) V,
 * beta below 128 per unit (512 ohm).
 */
uint32_t inverter_quasi_static_battery_q(const inverter_quasi_static_q *inv, double c_dc_f,
                                         double g_s, double b_a, inverter_quasi_static_bus_q *out);
uint32_t inverter_quasi_static_battery_f32(const inverter_quasi_static_f32 *inv, double c_dc_f,
                                           double g_s, double b_a,
                                           inverter_quasi_static_bus_f32 *out);

/*
 * One frame: the duties (pwm_average), i_dc from the motor currents i_a,
 * i_b at the frame's start (fixed: Q3.28 of 256 A, |i| <= 1 per unit;
 * float: [A]) turned to its middle, the DC-link update and the terminal
 * voltages. Integer only,
 * no division, in the fixed twin; total (the bus clamps and counts).
 */
void inverter_quasi_static_step_q(inverter_quasi_static_q *inv,
                                  const inverter_quasi_static_bus_q *bat, int32_t i_a, int32_t i_b);
void inverter_quasi_static_step_f32(inverter_quasi_static_f32 *inv,
                                    const inverter_quasi_static_bus_f32 *bat, float i_a, float i_b);

#endif /* UUV_INVERTER_AVG_H */
