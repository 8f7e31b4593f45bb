/*
 * The drive controller (800 us): a scalar slip-regulated speed loop over a
 * PI loop on the motor current magnitude that sets the PWM modulation index.
 * docs/drive_control.md gives the source of the scheme, the choice of the
 * gains, the fixed-point range analysis and the measured figures.
 *
 * Scheme (Bose, "Modern Power Electronics and AC Drives", 2002, sec. 8.3:
 * scalar control with slip regulation and a flux-maintaining current
 * function generator I_s = f(w_sl)). Per frame of length T:
 *
 *   Speed reference. The command is clamped to +-speed_max and ramped at
 *   accel_max: w_ref moves towards w_cmd by at most accel_max T. The ramp
 *   bounds the rate of the stator frequency the drive asks for.
 *
 *   Speed loop (PI -> slip frequency):
 *     e_w   = w_ref - w
 *     f_sl  = clamp(kp_w e_w + x_w, +-f_sl_lim)
 *     f_s   = clamp(p w / (2 pi) + f_sl, +-f_max)     stator frequency, signed
 *     f_sl  = f_s - p w / (2 pi)                       the slip actually applied
 *     x_w  += ki_w T e_w, clamped to +-f_sl_lim, unless the slip or the
 *             frequency is at a limit in the direction of e_w (conditional
 *             integration).
 *
 *   Current demand (constant rotor flux psi_r = Lm i_mag; in steady state
 *   the rotor-flux components of the stator current are i_d = i_mag and
 *   i_q = w_sl tau_r i_mag, tau_r = Lr / Rr, and the torque is
 *   (3/2) p psi_r^2 w_sl / Rr, proportional to the slip):
 *     i_q = k_q f_sl,  k_q = 2 pi tau_r i_mag,  I* = sqrt(i_mag^2 + i_q^2)
 *   The slip limit f_sl_lim = min(slip_max, sqrt(i_max^2 - i_mag^2) / k_q)
 *   makes I* <= i_max everywhere, so the flux is never cut by the current
 *   limit.
 *
 *   Current loop (PI on the magnitude -> voltage amplitude -> m):
 *     |i|   = |i_alpha + j i_beta| of the measured phase currents
 *     e_i   = I* - |i|
 *     v_ff  = ff_gain |(Rs i_d - w_s sigma Ls i_q) + j (Rs i_q + w_s Ls i_d)|,
 *             the steady-state phase voltage amplitude of the demanded
 *             operating point (w_s = 2 pi f_s), from the equivalent circuit
 *     v*    = clamp(v_ff + kp_i e_i + x_i, 0, m_max Vdc / 2)
 *     m     = v* / (Vdc / 2)   (Vdc floored at vdc_min)
 *     x_i  += ki_i T e_i, clamped to +-m_max Vdc / 2, unless v* is at a
 *             limit in the direction of e_i, or the machine is generating.
 *   Generating (f_sl and f_s of opposite signs, power flowing back): the
 *   current lags the voltage by more than 90 degrees, the fast response of
 *   |i| to the voltage amplitude changes sign, and the PI would be
 *   unstable; there the proportional term is dropped and the integrator
 *   held, so the voltage follows the feedforward.
 *
 *   Standstill. When |w_cmd| and |w| are both at most idle_speed the drive
 *   idles: m = 0, f_s = 0, both integrators and the reference are reset (the
 *   propeller coasts). Leaving idle, the reference starts from the measured
 *   speed. Negative commands reverse the drive through the same equations.
 *
 * Measured inputs. Phase currents i_a, i_b, i_c (positive into the motor),
 * sampled at the frame boundary or averaged over the frame by the executive
 * (averaging a vector turning at f_s shortens it by sin(x)/x, x = pi f_s T:
 * 0.26 % at 50 Hz, which the loop absorbs); the shaft speed; the DC-link
 * voltage. The magnitude uses the amplitude-invariant Clarke transform,
 * |i| = sqrt((2 i_a - i_b - i_c)^2 + 3 (i_b - i_c)^2) / 3, which is exact
 * whether or not the three currents sum to zero.
 *
 * Outputs: m in [0, m_max], the signed stator frequency and the matching
 * phase increment of the PWM sine accumulator (wavetable.h) for the PWM
 * step given in the parameters, and the demands for telemetry.
 *
 * Twins. _q is integer-only in per-unit Q31 (bases of drive_units.h):
 *   inputs   speed_cmd, w          Q31 of 512 rad/s (mechanical)
 *            i_a, i_b, i_c         Q31 of 256 A
 *            vdc                   Q31 of 1024 V
 *   outputs  m                     Q15, 1.0 = full modulation
 *            freq, slip            Q31 of 128 Hz
 *            phase_inc             turns * 2^32 per PWM step
 *            i_demand, i_meas      Q31 of 256 A
 *            v_demand              Q31 of 1024 V (phase voltage amplitude)
 *            speed_ref             Q31 of 512 rad/s
 *   states   speed_ref Q31 of 512 rad/s, x_w Q31 of 128 Hz, x_i Q31 of 1024 V.
 *   Each constant is an int32 mantissa with its own shift (value =
 *   mantissa / 2^shift, 30 significant bits) applied to a Q31 operand in
 *   int64 with a rounding shift. Sums are formed in int64 and saturate
 *   (counted in sat_count) when narrowed to Q31; with the default
 *   parameters no saturation can occur in normal use (range analysis in
 *   docs/drive_control.md). Magnitudes use an integer square root of a
 *   64-bit sum of squares; m uses one 32-bit unsigned division.
 * _f32 is the same algorithm in single precision, SI units.
 */
#ifndef UUV_DRIVE_CONTROL_H
#define UUV_DRIVE_CONTROL_H

#include <stdbool.h>
#include <stdint.h>

#include "fixedpoint/fixedpoint.h"

/* Bits of the flags output: which limits acted in this frame. */
#define DRIVE_CONTROL_FLAG_IDLE 0x01u       /* standstill: outputs held at zero */
#define DRIVE_CONTROL_FLAG_SLIP_LIMIT 0x02u /* slip at +-f_sl_lim */
#define DRIVE_CONTROL_FLAG_FREQ_LIMIT 0x04u /* stator frequency at +-f_max */
#define DRIVE_CONTROL_FLAG_M_MAX 0x08u      /* modulation index at m_max */
#define DRIVE_CONTROL_FLAG_M_ZERO 0x10u     /* voltage demand clipped at zero */
#define DRIVE_CONTROL_FLAG_GENERATING 0x20u /* current PI held (power flows back) */
#define DRIVE_CONTROL_FLAG_RAMP 0x40u       /* speed reference still ramping */

/* Parameters (SI). The machine constants are the motor's star equivalent. */
typedef struct {
    double step_s;            /* [s] controller frame T, (0, 10 ms] */
    double pwm_step_s;        /* [s] PWM step the phase increment is for, whole ns */
    uint32_t pole_pairs;      /* [-] p, 1..16 */
    double rs_ohm;            /* [ohm] stator resistance (feedforward) */
    double rr_ohm;            /* [ohm] rotor resistance, referred to the stator */
    double lls_h;             /* [H] stator leakage inductance */
    double llr_h;             /* [H] rotor leakage inductance */
    double lm_h;              /* [H] magnetising inductance */
    double i_mag_a;           /* [A] peak magnetising (d-axis) current: psi_r = Lm i_mag */
    double i_max_a;           /* [A] peak current demand limit, > i_mag, < 256 A */
    double slip_max_hz;       /* [Hz] slip limit (the current limit may lower it) */
    double freq_max_hz;       /* [Hz] stator frequency limit, < 128 Hz */
    double speed_max_radps;   /* [rad/s] command limit, < 256 rad/s */
    double accel_max_radps2;  /* [rad/s^2] ramp of the speed reference */
    double idle_speed_radps;  /* [rad/s] standstill band, [0, speed_max) */
    double kp_speed_hz_per_radps; /* [Hz/(rad/s)] speed PI: slip per speed error */
    double ki_speed_hz_per_rad;   /* [Hz/rad] speed PI: slip rate per speed error */
    double kp_current_v_per_a;    /* [V/A] current PI: voltage per current error */
    double ki_current_v_per_as;   /* [V/(A s)] current PI: voltage rate per error */
    double ff_gain;           /* [-] weight of the voltage feedforward, [0, 1] */
    double m_max;             /* [-] modulation index limit, (0, 1] */
    double vdc_min_v;         /* [V] floor of the DC-link voltage used to normalise m */
} drive_control_params;

/*
 * The default: gains and limits for the drive's 15 kW machine with the
 * propeller (docs/drive_control.md); 800 us frame, 2 us PWM step.
 */
extern const drive_control_params drive_control_params_default;

typedef enum {
    DRIVE_CONTROL_OK = 0,
    DRIVE_CONTROL_ERR_NULL,  /* a pointer argument was NULL */
    DRIVE_CONTROL_ERR_PARAM, /* a parameter is out of its range */
    DRIVE_CONTROL_ERR_RANGE  /* a constant does not fit its fixed-point format */
} drive_control_status;

/* Quantities derived once from the parameters (SI, double), shared by the twins. */
typedef struct {
    double step_s;            /* [s] T */
    double ls_h;              /* [H] Lls + Lm */
    double sigma_ls_h;        /* [H] Ls - Lm^2 / Lr, the transient inductance */
    double tau_r_s;           /* [s] Lr / Rr */
    double kq_a_per_hz;       /* [A/Hz] i_q per slip hertz: 2 pi tau_r i_mag */
    double kt_nm_per_hz;      /* [N m/Hz] steady torque per slip hertz at psi_r */
    double slip_lim_hz;       /* [Hz] effective slip limit */
    double fr_hz_per_radps;   /* [Hz/(rad/s)] p / (2 pi) */
    uint32_t pwm_step_ns;     /* [ns] PWM step */
} drive_control_design;

/* Checks the parameters and derives the shared quantities (d may be NULL). */
drive_control_status drive_control_design_f64(drive_control_design *d,
                                              const drive_control_params *p);

/* ---- Integer twin (per unit, Q31) --------------------------------------- */

typedef struct {
    q31_t speed_cmd;      /* Q31 of 512 rad/s: commanded shaft speed, signed */
    q31_t w;              /* Q31 of 512 rad/s: measured shaft speed */
    q31_t i_a, i_b, i_c;  /* Q31 of 256 A: phase currents, positive into the motor */
    q31_t vdc;            /* Q31 of 1024 V: DC-link voltage */
} drive_control_in_q;

typedef struct {
    q15_t m;              /* Q15: modulation index, [0, m_max] */
    q31_t freq;           /* Q31 of 128 Hz: stator frequency, signed */
    uint32_t phase_inc;   /* [2^-32 turn] sine phase increment per PWM step */
    q31_t slip;           /* Q31 of 128 Hz: slip frequency applied */
    q31_t speed_ref;      /* Q31 of 512 rad/s: ramped speed reference */
    q31_t i_demand;       /* Q31 of 256 A: current magnitude demand I* */
    q31_t i_meas;         /* Q31 of 256 A: measured current magnitude */
    q31_t v_demand;       /* Q31 of 1024 V: phase voltage amplitude demand */
    uint32_t flags;       /* DRIVE_CONTROL_FLAG_* */
} drive_control_out_q;

/* A constant of the integer twin: value = mant / 2^shift. */
typedef struct {
    int32_t mant;
    uint32_t shift;
} drive_control_gain_q;

typedef struct {
    drive_control_design d;           /* derived SI quantities */
    drive_control_gain_q kp_w, ki_w;  /* slip <- speed error (ki includes T) */
    drive_control_gain_q k_fr;        /* frequency <- speed: p / (2 pi) */
    drive_control_gain_q k_q;         /* current <- slip: k_q */
    drive_control_gain_q k_rs;        /* voltage <- current: Rs */
    drive_control_gain_q k_sls, k_ls; /* voltage <- frequency * current: 2 pi sigma Ls, 2 pi Ls */
    drive_control_gain_q k_ff;        /* voltage <- voltage: ff_gain */
    drive_control_gain_q kp_i, ki_i;  /* voltage <- current error (ki includes T) */
    drive_control_gain_q k_vmax;      /* voltage <- Vdc: m_max / 2 */
    q31_t speed_max, ramp_step, idle_speed; /* Q31 of 512 rad/s */
    q31_t slip_lim, freq_max;         /* Q31 of 128 Hz */
    q31_t i_mag;                      /* Q31 of 256 A */
    q31_t vdc_min;                    /* Q31 of 1024 V */
    q15_t m_max;                      /* Q15 */
    uint32_t inc_base;                /* phase increment at 128 Hz */
    q31_t speed_ref;                  /* state: Q31 of 512 rad/s */
    q31_t x_w;                        /* state: speed integrator, Q31 of 128 Hz */
    q31_t x_i;                        /* state: current integrator, Q31 of 1024 V */
    bool idle;                        /* state: standstill */
    uint32_t sat_count;               /* saturation events since init or reset */
} drive_control_q;

drive_control_status drive_control_init_q(drive_control_q *c, const drive_control_params *p);
/* Idle, integrators and reference zero, saturation count cleared. */
void drive_control_reset_q(drive_control_q *c);
/* One controller frame: speed loop, current demand, current loop. Total. */
void drive_control_step_q(drive_control_q *c, const drive_control_in_q *in,
                          drive_control_out_q *out);
/*
 * The current loop alone, for a given demand (Q31 of 256 A), stator
 * frequency and slip (Q31 of 128 Hz; they set the feedforward and the
 * generating test): fills m, phase_inc, freq, slip, i_demand, i_meas,
 * v_demand and flags; speed_cmd and w of the input are not used. Leaves the
 * speed loop and the idle state untouched.
 */
void drive_control_current_step_q(drive_control_q *c, q31_t i_demand, q31_t freq, q31_t slip,
                                  const drive_control_in_q *in, drive_control_out_q *out);

/* ---- Single-precision twin (SI) ----------------------------------------- */

typedef struct {
    float speed_cmd_radps;   /* [rad/s] commanded shaft speed, signed */
    float w_radps;           /* [rad/s] measured shaft speed */
    float i_a, i_b, i_c;     /* [A] phase currents, positive into the motor */
    float vdc_v;             /* [V] DC-link voltage */
} drive_control_in_f32;

typedef struct {
    float m;                 /* [-] modulation index, [0, m_max] */
    float freq_hz;           /* [Hz] stator frequency, signed */
    uint32_t phase_inc;      /* [2^-32 turn] sine phase increment per PWM step */
    float slip_hz;           /* [Hz] slip frequency applied */
    float speed_ref_radps;   /* [rad/s] ramped speed reference */
    float i_demand_a;        /* [A] current magnitude demand I* */
    float i_meas_a;          /* [A] measured current magnitude */
    float v_demand_v;        /* [V] phase voltage amplitude demand */
    uint32_t flags;          /* DRIVE_CONTROL_FLAG_* */
} drive_control_out_f32;

typedef struct {
    drive_control_design d;  /* derived SI quantities */
    float kp_w, ki_w_t;      /* [Hz/(rad/s)], [Hz/(rad/s)] per frame */
    float fr_per_w;          /* [Hz/(rad/s)] */
    float kq;                /* [A/Hz] */
    float rs, w_sls, w_ls;   /* [ohm], [ohm/Hz] 2 pi sigma Ls, [ohm/Hz] 2 pi Ls */
    float ff_gain;           /* [-] */
    float kp_i, ki_i_t;      /* [V/A], [V/A] per frame */
    float half_m_max;        /* [-] m_max / 2 */
    float speed_max, ramp_step, idle_speed; /* [rad/s] */
    float slip_lim, freq_max;               /* [Hz] */
    float i_mag;             /* [A] */
    float vdc_min;           /* [V] */
    float m_max;             /* [-] */
    float pwm_step;          /* [s] */
    float speed_ref;         /* state: [rad/s] */
    float x_w;               /* state: [Hz] speed integrator */
    float x_i;               /* state: [V] current integrator */
    bool idle;               /* state: standstill */
} drive_control_f32;

drive_control_status drive_control_init_f32(drive_control_f32 *c,
                                            const drive_control_params *p);
void drive_control_reset_f32(drive_control_f32 *c);
void drive_control_step_f32(drive_control_f32 *c, const drive_control_in_f32 *in,
                            drive_control_out_f32 *out);
void drive_control_current_step_f32(drive_control_f32 *c, float i_demand_a, float freq_hz,
                                    float slip_hz, const drive_control_in_f32 *in,
                                    drive_control_out_f32 *out);

#endif /* UUV_DRIVE_CONTROL_H */
