/*
 * The power stage of the drive (fast segment, 2 us): the six-switch
 * inverter with its DC-link capacitor and the three-phase LC output filter.
 * The leg duties come from the PWM modulator (pwm.h) or, in the averaged
 * layered model, from the duty cycles (inverter_avg.h); the battery is an
 * input as its companion (G, b); the motor is an input as its phase
 * currents. docs/drive_power.md derives every equation below.
 *
 * Circuit, per phase x = a, b, c:
 *
 *   inverter leg x --- R_L --- L ---+--- node x (motor terminal x)
 *                                   |        |
 *                                   C      R_d
 *                                   |        |
 *                                   |      C_d
 *                                   |        |
 *                                  filter star point (isolated)
 *
 * The motor (star, isolated neutral) draws i_m,x from node x. With every
 * star point isolated no zero-sequence current can flow: the three
 * inductor currents, capacitor voltages and motor currents each sum to zero,
 * and the filter sees the pole voltages with their common mode removed,
 *   u_x = v_dc (d_x - (d_a + d_b + d_c) / 3)            (exact for this wiring)
 * where d_x is the duty of leg x over the step (the mean of its switch
 * state s_x; 0 or 1 in a step without a switching edge). Phases a and b are
 * integrated; phase c is -a - b exactly (and the motor current of phase c is
 * not read: the motor's three currents sum to zero).
 *
 * DC link (forward Euler, explicit): the capacitor voltage v_dc is known at
 * t_k, so the bus node is solved by the battery's companion
 *   i_bat = G v_dc - b = G (v_dc - e),  e = b / G        (into the battery)
 * and the capacitor takes what the battery delivers minus the inverter's
 * input current:
 *   v_dc(k+1) = v_dc(k) + (T / C_dc) (G (e - v_dc(k)) - i_dc(k)),
 *   i_dc(k) = sum_x d_x (i_L,x(k) + i_L,x(k+1)) / 2,
 * the step mean of the switched inductor currents, which makes the energy
 * leaving the DC link equal to the energy the trapezoidal filter receives.
 *
 * Filter (trapezoidal rule, written as companion models). Over one step the
 * node voltage moves by dv = v(k+1) - v(k); each branch then carries
 *   inductor branch, into the node:   i_L(k+1)  = j_L - G_L dv
 *   shunt (C and R_d-C_d), out of it: i_sh(k+1) = G_sh dv - j_sh
 * with G_L = 1 / (2L/T + R_L), G_sh = 2C/T + 1 / (R_d + T / (2 C_d)) and
 * history currents j_L (from the state at t_k and the mean inverter voltage
 * u of the step) and j_sh (kept from the last step); power_stage_nodes.h
 * gives them. This is the paper's i = G v - b with b = G v(k) -+ j. The node
 * (KCL with the motor current i_m held over the step) then gives
 *   dv = (j_L + j_sh - i_m) / (G_L + G_sh),
 * whose reciprocal is a constant computed at init. The incremental form
 * keeps the history terms at the size of the branch currents, which is
 * what lets the fixed-point twin hold them.
 *
 * Twins. The fixed twin runs integer arithmetic only in its step: internal
 * states in Q3.28 per unit of the drive bases (drive_units.h: 1024 V,
 * 256 A), coefficients in Q32 (checked at init), Q15 per-unit outputs. The
 * float twin runs the same equations in SI units. Both clamp the inductor
 * currents, capacitor voltages, damping branch currents and the DC-link
 * voltage to +-1 per unit (1024 V, 256 A) and count the clamps.
 */
#ifndef UUV_POWER_STAGE_H
#define UUV_POWER_STAGE_H

#include <stdint.h>

#include "fixedpoint/fixedpoint.h"

typedef struct {
    double c_dc_f;    /* [F] DC-link capacitance */
    double l_h;       /* [H] filter inductance per phase */
    double r_l_ohm;   /* [ohm] series resistance of the filter inductor (>= 0) */
    double c_f;       /* [F] filter capacitor per phase (star) */
    double r_d_ohm;   /* [ohm] damping resistor, in series with c_d_f, across c_f */
    double c_d_f;     /* [F] damping capacitor */
} power_stage_params;

typedef enum {
    PS_OK = 0,
    PS_ERR_NULL,         /* a pointer argument was NULL */
    PS_ERR_PARAM,        /* a parameter not positive and finite (R_L: not >= 0) */
    PS_ERR_STEP,         /* step not in [100 ns, 1 ms] */
    PS_ERR_VOLTAGE,      /* initial DC-link voltage not in [0, 1024) V */
    PS_ERR_FIXED_RANGE   /* a coefficient does not fit its Q32 format at this step */
} ps_status;

/* The drive's power stage: 470 uF, 1 mH + 25 mohm, 22 uF, 8.2 ohm + 47 uF. */
extern const power_stage_params power_stage_params_default;

/* ---- Fixed-point twin ---------------------------------------------------- */

/* Q3.28 per unit: the internal format, range +-8, states clamped to +-1. */
#define PS_Q28_ONE 268435456 /* 2^28 */

/*
 * Step coefficients, from the parameters and the step at init; Q32 (value
 * times 2^32, so each must be below 0.5 in magnitude; init checks), per unit
 * of the admittance 1 / (4 ohm) or the impedance 4 ohm. Some are stored
 * negated so that every product of the step is an accumulate.
 */
typedef struct {
    int32_t neg_eps_l;  /* -(1 - a_L) = -2 R_L / (2L/T + R_L) */
    int32_t g_l2;       /* 2 G_L, G_L = 1 / (2L/T + R_L) */
    int32_t neg_g_l;    /* -G_L */
    int32_t g_d;        /* G_d = 1 / (R_d + T / (2 C_d)) */
    int32_t a_d;        /* a = 2 r_cd G_d = T / (C_d (R_d + T / (2 C_d))), r_cd = T / (2 C_d) */
    int32_t neg_a_d;    /* -a */
    int32_t k_node;     /* 1 / (G_L + 2C/T + G_d) */
    int32_t neg_k_c;    /* -T / C_dc */
} ps_coef_q;

/*
 * State of one filter phase, Q3.28 per unit. Besides the inductor current
 * and the capacitor voltage, the shunt keeps its damping branch current
 * (which with v fixes the damping capacitor's voltage, v_d = v - R_d i_d)
 * and its trapezoidal history j_sh (power_stage_nodes.h).
 */
typedef struct {
    int32_t i_l;   /* [A] inductor current, inverter towards node, of 256 A */
    int32_t v_c;   /* [V] capacitor (motor terminal) voltage to the filter star, of 1024 V */
    int32_t i_d;   /* [A] damping branch current, node to star, of 256 A */
    int32_t j_sh;  /* [A] shunt history: minus its current at t_k+1 if dv = 0, of 256 A */
} ps_phase_q;

/* The battery's companion in the form the step uses (power_stage_battery_q). */
typedef struct {
    int32_t e;   /* [V] source voltage b / G, Q3.28 of 1024 V, in [0, 1) */
    int32_t kg;  /* [-] T G / C_dc, Q32, in [0, 0.5) (forward Euler stable) */
    int32_t g;   /* [S] G, Q24 of 1 / (4 ohm) (for the battery current output) */
} ps_battery_q;

typedef struct {
    int32_t duty[3];       /* [-] leg duty over the step, Q15, 0..32768 (pwm_out_q.duty) */
    q15_t i_motor[3];      /* [A] phase currents into the motor, Q15 of 256 A; [2] not read */
    ps_battery_q battery;  /* held over the slow frame */
} power_stage_in_q;

typedef struct {
    q15_t v_dc;      /* [V] DC-link voltage, Q15 of 1024 V */
    q15_t v_inv[3];  /* [V] inverter phase voltages u_x, mean over the last step, Q15 of 1024 V */
    q15_t v_cap[3];  /* [V] filter capacitor = motor terminal voltages, Q15 of 1024 V */
    q15_t i_l[3];    /* [A] filter inductor currents, Q15 of 256 A */
    q15_t i_dc;      /* [A] DC-link current into the inverter, step mean, Q15 of 256 A */
    q15_t i_bat;     /* [A] battery current into its + terminal at v_dc, Q15 of 256 A */
} power_stage_out_q;

typedef struct {
    const power_stage_params *p;
    uint32_t step_ns;   /* [ns] step T */
    ps_coef_q k;
    ps_phase_q ph[2];   /* phases a and b */
    int32_t v_dc;       /* [V] DC-link voltage, Q3.28 of 1024 V */
    int32_t u[2];       /* [V] inverter voltages a, b of the last step, Q3.28 of 1024 V */
    int32_t i_dc;       /* [A] DC-link current of the last step, Q3.28 of 256 A */
    uint32_t sat_count; /* states clamped to +-1 per unit */
} power_stage_q;

/*
 * Checks the parameters, the step (step_ns) and the initial DC-link voltage
 * v_dc0_v, derives the coefficients and starts with the filter at rest.
 * Returns PS_ERR_FIXED_RANGE when a coefficient does not fit its format at
 * this step (for example a step far beyond 100 us). The instance keeps p.
 * On an error the instance is left unchanged. Set-up code (double).
 */
ps_status power_stage_init_q(power_stage_q *ps, const power_stage_params *p, uint32_t step_ns,
                             double v_dc0_v);

/*
 * The battery's companion i = G v - b (g_s [S], b_a [A], battery.h sign
 * convention) for this instance's step: e = b / G, kg = T G / C_dc, G. For
 * the slow frame (double arithmetic, not the fast path). G = 0 (contactor
 * open) gives all zero. Returns the number of values clamped: e to
 * [0, 1024) V, kg below 0.5 (G < C_dc / (2T): the explicit update then
 * stays stable), G below 32 S; a negative or non-finite G counts as open.
 */
uint32_t power_stage_battery_q(const power_stage_q *ps, double g_s, double b_a,
                               ps_battery_q *out);

/*
 * One step [t_k, t_k+1]: inverter voltages from the duties and v_dc(k),
 * trapezoidal filter step with the held motor currents, forward-Euler
 * DC-link step. Integer only, no division; total (clamps and counts).
 */
void power_stage_step_q(power_stage_q *ps, const power_stage_in_q *in);

/* Outputs in Q15 per unit; bat is the battery input of the last step. */
void power_stage_output_q(const power_stage_q *ps, const ps_battery_q *bat,
                          power_stage_out_q *out);

/* ---- Float twin ------------------------------------------------------------ */

typedef struct {
    float neg_eps_l, g_l2, neg_g_l; /* [-] -(1 - a_L), [S] 2 G_L, [S] -G_L */
    float g_d;                      /* [S] 1 / (R_d + T / (2 C_d)) */
    float a_d, neg_a_d;             /* [-] 2 r_cd G_d and its negative */
    float k_node;                   /* [ohm] 1 / (G_L + 2C/T + G_d) */
    float neg_k_c;                  /* [ohm] -T / (2 C_dc): of the DC-link current's sum 2 i_dc
                                       (ps_dclink_step_f32; volts per ampere and step) */
} ps_coef_f32;

typedef struct {
    float i_l;   /* [A] */
    float v_c;   /* [V] */
    float i_d;   /* [A] */
    float j_sh;  /* [A] */
} ps_phase_f32;

typedef struct {
    float e_v;  /* [V] b / G */
    float kg;   /* [-] T G / C_dc, in [0, 0.5) */
    float g_s;  /* [S] G */
} ps_battery_f32;

typedef struct {
    float duty[3];       /* [-] leg duty over the step, [0, 1] */
    float i_motor_a[3];  /* [A] phase currents into the motor; [2] not read */
    ps_battery_f32 battery;
} power_stage_in_f32;

typedef struct {
    float v_dc_v;       /* [V] */
    float v_inv_v[3];   /* [V] mean over the last step */
    float v_cap_v[3];   /* [V] */
    float i_l_a[3];     /* [A] */
    float i_dc_a;       /* [A] mean over the last step */
    float i_bat_a;      /* [A] into the battery's + terminal */
} power_stage_out_f32;

typedef struct {
    const power_stage_params *p;
    uint32_t step_ns;
    ps_coef_f32 k;
    ps_phase_f32 ph[2];
    float v_dc;         /* [V] */
    float u[2];         /* [V] */
    float i_dc;         /* [A] */
    uint32_t sat_count; /* states clamped to +-1024 V / +-256 A */
} power_stage_f32;

/* As power_stage_init_q() (PS_ERR_FIXED_RANGE does not occur). */
ps_status power_stage_init_f32(power_stage_f32 *ps, const power_stage_params *p,
                               uint32_t step_ns, double v_dc0_v);

/* As power_stage_battery_q(), with the same clamps. */
uint32_t power_stage_battery_f32(const power_stage_f32 *ps, double g_s, double b_a,
                                 ps_battery_f32 *out);

/* As power_stage_step_q(), in single precision. */
void power_stage_step_f32(power_stage_f32 *ps, const power_stage_in_f32 *in);

/* As power_stage_output_q(), in SI units. */
void power_stage_output_f32(const power_stage_f32 *ps, const ps_battery_f32 *bat,
                            power_stage_out_f32 *out);

#endif /* UUV_POWER_STAGE_H */
