/*
 * The sine-triangle PWM modulator of the inverter (fast segment, 2 us).
 *
 * Algorithm (both twins). Two 32-bit phase accumulators, one for the
 * triangle carrier (a full turn is 2^32, see fixedpoint/wavetable.h) and
 * one for the stator frequency, advance once per step. The carrier c is the
 * table triangle (-1 at phase 0, +1 at half a turn); the three references
 * are r_a = m sin(theta), r_b = m sin(theta - 120 deg) and r_c = -r_a - r_b
 * (which is m sin(theta + 120 deg) exactly, and makes the three sum to zero
 * in both twins), with m the modulation index in [0, 1]. The upper switch
 * of leg x is on while r_x > c (s_x = 1), the lower one otherwise: six
 * ideal switches in three complementary legs.
 *
 * Each step covers [t_k, t_k+1]. The modulator evaluates e_x = r_x - c at
 * the end of the step (after advancing the phases) and reports, per leg,
 *   - state[x]: the switch state s_x at t_k+1;
 *   - duty[x]:  the fraction of the step during which s_x = 1, the quantity
 *               the inverter model integrates (it applies the mean pole
 *               voltage of the step).
 * Two edge modes give the duty:
 *   PWM_EDGES_INTERPOLATED (default): when e_x changes sign within the step,
 *     the crossing is located by linear interpolation between the two end
 *     values, so the duty is the on-time fraction; otherwise it is 0 or 1.
 *     The divisor |e(t_k) - e(t_k+1)| is taken as the carrier's change over
 *     one step, |dc| = 4 f_c T (a constant whose reciprocal is computed at
 *     init): the reference moves at most 2 pi f1 m T per step, under 2 % of
 *     |dc| at 55 Hz and 5 kHz, so the located crossing is within 2 % of a
 *     step (40 ns) of the exact one. A step that contains a carrier peak is
 *     handled as if the carrier were straight; a pulse shorter than the
 *     step that lies entirely inside it (only possible for m close to 1) is
 *     lost. Why: with the carrier period exactly 100 steps, the plain
 *     sampled comparison can only produce 50 distinct pulse widths per
 *     carrier period, a quantiser with a 0.04 step in m sin; at m = 0.2 the
 *     fundamental comes out 3.2 % low. Interpolation removes that error
 *     (docs/drive_power.md gives the figures).
 *   PWM_EDGES_SAMPLED: the comparison made at t_k is held over the whole
 *     step (duty 0 or 1): plain fixed-step switching, kept as the reference
 *     for the error of fixed-step switching.
 *
 * Averaged modulator (the layered alternative, for the averaged inverter,
 * mode PWM_AVERAGED): the leg duty cycles d_x = (1 + r_x) / 2 with the
 * references taken at the middle of the step (the mean over the step to
 * second order); only the reference phase advances, and the step may be
 * long (100 us).
 *
 * Commands. The controller sets the modulation index and the stator
 * frequency (pwm_command_*): the frequency becomes a signed phase increment
 * there, at the controller's rate, so the 2 us step only adds. A negative
 * frequency runs the phase backwards (the phase sequence a-c-b: reversal),
 * zero holds it (standstill with DC references). pwm_command_inc_*() takes
 * the increment directly.
 *
 * Fixed twin: integer arithmetic only in the step. m is Q15 ([0, 32767],
 * 32767 standing for 1: the Q15 sine and triangle tables both peak at
 * 32767, so the comparison m sin > c is scale-consistent); the comparison
 * is exact, m * sin (Q15 x Q15) against c * 2^15, with no rounding of the
 * reference; duties are Q15 fractions of the step with 32768 = the whole
 * step (held in int32_t).
 * Float twin: the same phase accumulators (integers), the float tables, m in
 * [0, 1] and duties in [0, 1].
 */
#ifndef UUV_PWM_H
#define UUV_PWM_H

#include <stdint.h>

#include "fixedpoint/fixedpoint.h"

/* How the duty of a step is formed (see above); the layered versions of the modulator. */
typedef enum {
    PWM_EDGES_INTERPOLATED = 0, /* switching, crossing located inside the step */
    PWM_EDGES_SAMPLED = 1,      /* switching, comparison at the step start, held */
    PWM_AVERAGED = 2            /* no switching: duty cycles (1 + r) / 2; carrier unused */
} pwm_edges;

typedef struct {
    double carrier_hz;        /* [Hz] triangle carrier frequency, 5000 (unused when averaged) */
    pwm_edges edges;          /* edge mode, or PWM_AVERAGED */
    uint32_t carrier_phase0;  /* initial carrier phase (2^32 = one turn); 0 = valley */
    uint32_t ref_phase0;      /* initial reference phase of leg a (2^32 = one turn) */
    uint32_t dead_time_ns;    /* [ns] both switches of a leg off at every edge (the switching
                               * inverter's sub-step edges, pwm_rt.h); 0: ideal switches */
} pwm_params;

typedef enum {
    PWM_OK = 0,
    PWM_ERR_NULL,     /* a pointer argument was NULL */
    PWM_ERR_STEP,     /* step not in [100 ns, 1 ms] */
    PWM_ERR_CARRIER,  /* switching: carrier not in (0, 32767] Hz or under 8 steps per period */
    PWM_ERR_EDGES     /* unknown edge mode */
} pwm_status;

/* Duty value of a whole step in the fixed twin (Q15 with 1.0 representable). */
#define PWM_DUTY_ONE_Q 32768

/* Default parameters: 5 kHz carrier, interpolated edges, both phases at 0, no dead time. */
extern const pwm_params pwm_params_default;

/* The same with sampled edges, as the real-time step (pwm_rt.h) takes them. */
extern const pwm_params pwm_params_sampled;

/* ---- Fixed-point twin ---------------------------------------------------- */

typedef struct {
    q15_t m_index;  /* [-] modulation index, Q15, clamped to [0, 32767] */
    q31_t freq;     /* [Hz] stator frequency, Q31 of 128 Hz (signed); a Q15 value widens exactly */
} pwm_cmd_q;

typedef struct {
    int32_t duty[3];   /* [-] on-time fraction of the step, Q15, 0..32768 */
    uint8_t state[3];  /* [-] switch state s_x at the end of the step, 0 or 1 */
} pwm_out_q;

typedef struct {
    uint32_t step_ns;     /* [ns] step T */
    pwm_edges edges;
    uint32_t ph_c;        /* carrier phase at the end of the last step */
    uint32_t inc_c;       /* carrier increment per step */
    uint32_t ph_s;        /* reference phase of leg a at the end of the last step */
    uint32_t inc_s;       /* reference increment per step (two's complement when negative) */
    uint32_t half_inc_s;  /* inc_s / 2 (signed, floored): the middle of a step, averaged use */
    int32_t m;            /* [-] modulation index, Q15 in [0, 32767] */
    int32_t e[3];         /* m sin - c at the end of the last step, Q30 units (|e| < 2^31) */
    int32_t dc_abs;       /* |carrier change per step|, Q15 units (1311 for 5 kHz, 2 us) */
    uint32_t recip;       /* round(2^31 / dc_abs): Q16 of 2^15 / dc_abs */
    uint32_t sat_count;   /* commands clamped (m outside [0, 1]) */
} pwm_q;

/*
 * Checks the parameters and the step T = step_ns (the carrier only for the
 * switching modes), starts both phases at their initial values with m = 0
 * and f = 0. The parameters are read here only. Returns PWM_OK, or an error
 * and leaves the instance unchanged. Set-up code: it divides.
 */
pwm_status pwm_init_q(pwm_q *pw, const pwm_params *p, uint32_t step_ns);

/*
 * Sets m and the stator frequency (controller rate, 800 us). m below 0 is
 * clamped to 0 and counted. The increment is round(2^32 f T) with f rounded
 * to 2^-16 Hz (wt_phase_inc_q16: a 64-bit division, not for the 2 us step).
 */
void pwm_command_q(pwm_q *pw, const pwm_cmd_q *cmd);

/* Sets m (clamped as above) and the reference increment per step directly. */
void pwm_command_inc_q(pwm_q *pw, q15_t m_index, uint32_t inc);

/*
 * One step [t_k, t_k+1] in the instance's mode: switching (advances both
 * phases, compares, writes the duties and states) or, for PWM_AVERAGED,
 * pwm_average_q(). Integer only, no division; total.
 */
void pwm_step_q(pwm_q *pw, pwm_out_q *out);

/*
 * One averaged step (whatever the mode): duty[x] = (32768 + r_x) / 2
 * rounded, r_x taken at the middle of the step; state[x] = 1 when r_x > 0.
 * Advances the reference phase only. Integer only; total.
 */
void pwm_average_q(pwm_q *pw, pwm_out_q *out);

/* ---- Float twin ------------------------------------------------------------ */

typedef struct {
    float m_index;  /* [-] modulation index, clamped to [0, 1] */
    float freq_hz;  /* [Hz] stator frequency (signed) */
} pwm_cmd_f32;

typedef struct {
    float duty[3];     /* [-] on-time fraction of the step, [0, 1] */
    uint8_t state[3];  /* [-] switch state s_x at the end of the step, 0 or 1 */
} pwm_out_f32;

typedef struct {
    uint32_t step_ns;
    pwm_edges edges;
    uint32_t ph_c, inc_c, ph_s, inc_s, half_inc_s; /* as in pwm_q */
    float m;            /* [-] modulation index in [0, 1] */
    float e[3];         /* r_x - c at the end of the last step */
    float recip;        /* 1 / |carrier change per step| */
    uint32_t sat_count; /* commands clamped (m outside [0, 1] or NaN) */
} pwm_f32;

/* As pwm_init_q(). */
pwm_status pwm_init_f32(pwm_f32 *pw, const pwm_params *p, uint32_t step_ns);

/* As pwm_command_q(): m clamped to [0, 1] (a NaN gives 0), counted. */
void pwm_command_f32(pwm_f32 *pw, const pwm_cmd_f32 *cmd);

/* As pwm_command_inc_q(). */
void pwm_command_inc_f32(pwm_f32 *pw, float m_index, uint32_t inc);

/* As pwm_step_q(), in single precision. */
void pwm_step_f32(pwm_f32 *pw, pwm_out_f32 *out);

/* As pwm_average_q(): duty = (1 + r_x) / 2 at the middle of the step. */
void pwm_average_f32(pwm_f32 *pw, pwm_out_f32 *out);

#endif /* UUV_PWM_H */
