/*
 * The pieces of the power-stage step as small inline functions, both twins:
 * inverter voltages, the companion (history currents) of one filter phase,
 * its node solve and state update, the DC-link current and the DC-link
 * forward-Euler step. power_stage_step_q/_f32 chain them; an executive that
 * solves the nodes itself (paper section 3) can call them one by one.
 * Equations in power_stage.h; derivation in docs/drive_power.md.
 *
 * Fixed-point conventions (module prefix ps_):
 *   - values are Q3.28 per unit (PS_Q28_ONE = 1 per unit): voltages of
 *     1024 V, currents of 256 A; the clamped states stay within +-1 per
 *     unit, so by the bounds noted at each function no intermediate leaves
 *     +-8 per unit (the int32_t range) when the coefficients are in their
 *     Q32 format (below 0.5, checked by power_stage_init_q);
 *   - a product sum is formed exactly in 64 bits and rounded once to its
 *     high word (ps_acc_q, ps_mac_q, ps_hi_q): a Q3.28 value times a Q32
 *     coefficient lands in Q3.28 with no shift but the word select.
 */
#ifndef UUV_POWER_STAGE_NODES_H
#define UUV_POWER_STAGE_NODES_H

#include <stdint.h>

#include "fixedpoint/fixedpoint.h"
#include "models/drive/inverter/power_stage.h"

/* ---- Fixed-point helpers ------------------------------------------------- */

/*
 * Product sums rounded to their high word. An accumulator starts as
 * base * 2^32 + 2^31 (a Q3.28 value in the high word and the rounding
 * half), takes products of a Q3.28 value and a Q32 coefficient (exact in
 * 64 bits), and ends as its high word: base + round(sum / 2^32), ties up,
 * in Q3.28. The arithmetic is modulo 2^64 on uint64_t, so nothing
 * overflows; the high word is the exact result whenever that result fits
 * int32_t, which the ranges noted at each function guarantee. The pattern
 * compiles to one multiply-accumulate per product (SMULL/SMLAL) plus one
 * instruction for the rounding and base.
 */
static inline uint64_t ps_acc_q(int32_t base) {
    return ((uint64_t)(uint32_t)base << 32) | 0x80000000u;
}

static inline uint64_t ps_mac_q(uint64_t acc, int32_t x, int32_t c) {
    return acc + (uint64_t)((int64_t)x * (int64_t)c); /* conversion modulo 2^64 */
}

static inline int32_t ps_hi_q(uint64_t acc) {
    return fp_from_u32_i32((uint32_t)(acc >> 32));
}

/*
 * Clamps x to [-1, 1] per unit (+-2^28) and counts a clamp. One unsigned
 * comparison in the usual case.
 */
static inline int32_t ps_clamp_q(int32_t x, uint32_t *sat_count) {
    if ((uint32_t)x + (uint32_t)PS_Q28_ONE > 2u * (uint32_t)PS_Q28_ONE) {
        fp_count_sat(sat_count);
        return (x > 0) ? PS_Q28_ONE : -PS_Q28_ONE;
    }
    return x;
}

/*
 * 1 when any of x, y, z is outside [-1, 1) per unit: bits 29 to 31 of
 * x + 2^28 (modulo 2^32) are then not all zero. One test for three values.
 */
static inline int ps_out_of_range3_q(int32_t x, int32_t y, int32_t z) {
    const uint32_t one = (uint32_t)PS_Q28_ONE;
    return ((((uint32_t)x + one) | ((uint32_t)y + one) | ((uint32_t)z + one)) >> 29) != 0u;
}

/* ---- Inverter ---------------------------------------------------------------- */

/*
 * Phase voltages a and b (Q3.28 of 1024 V) of the pole voltages with the
 * common mode removed: u_x = v_dc (2 d_x - d_y - d_z) / 3, duties Q15 with
 * 32768 = 1, from the leg sums w_x = 2 d_x - d_y - d_z in [-65536, 65536]
 * (ps_inverter_w_q; ps_inverter_q forms them from the duties). v_dc / 3 is
 * formed once (round(2^32 / 3) = 0x55555555); then (8 v_dc / 3) * (w *
 * 2^14) / 2^32: both factors below 2^31 for |v_dc| <= 1 per unit, the
 * product below 2^61. u_c = -u_a - u_b.
 */
static inline void ps_inverter_w_q(int32_t v_dc, int32_t w_a, int32_t w_b, int32_t *u_a,
                                   int32_t *u_b) {
    const int32_t v3x8 = ps_hi_q(ps_mac_q(ps_acc_q(0), v_dc, 0x55555555)) * 8;
    *u_a = ps_hi_q(ps_mac_q(ps_acc_q(0), v3x8, w_a * 16384));
    *u_b = ps_hi_q(ps_mac_q(ps_acc_q(0), v3x8, w_b * 16384));
}

/* The leg sum 2 d_x - d_y - d_z. */
static inline int32_t ps_leg_sum_q(int32_t d_x, int32_t d_y, int32_t d_z) {
    return 2 * d_x - d_y - d_z;
}

static inline void ps_inverter_q(int32_t v_dc, const int32_t duty[3], int32_t *u_a,
                                 int32_t *u_b) {
    ps_inverter_w_q(v_dc, ps_leg_sum_q(duty[0], duty[1], duty[2]),
                    ps_leg_sum_q(duty[1], duty[0], duty[2]), u_a, u_b);
}

/*
 * DC-link current, the step mean sum_x d_x (i_L,x(k) + i_L,x(k+1)) / 2 with
 * phase c eliminated: (d_a - d_c) s_a + (d_b - d_c) s_b, where s_x =
 * i_L,x(k) + i_L,x(k+1) (|s| <= 2 per unit). Scaling: (dd * 2^15) * (2 s)
 * / 2^32 = dd s / 2^16, Q3.28; each factor at most 2^30.
 */
static inline int32_t ps_dc_current_q(const int32_t duty[3], int32_t s_a, int32_t s_b) {
    const int32_t dd_a = (duty[0] - duty[2]) * 32768;
    const int32_t dd_b = (duty[1] - duty[2]) * 32768;
    return ps_hi_q(ps_mac_q(ps_mac_q(ps_acc_q(0), dd_a, 2 * s_a), dd_b, 2 * s_b));
}

/*
 * DC-link forward Euler: v + kg (e - v) - k_c i_dc, clamped and counted.
 * |e - v| <= 2, |i_dc| <= 2 per unit; kg, k_c below 0.5 (Q32).
 */
static inline int32_t ps_dclink_step_q(int32_t v_dc, const ps_battery_q *bat, int32_t neg_k_c,
                                       int32_t i_dc, uint32_t *sat_count) {
    return ps_clamp_q(
        ps_hi_q(ps_mac_q(ps_mac_q(ps_acc_q(v_dc), bat->e - v_dc, bat->kg), i_dc, neg_k_c)),
        sat_count);
}

/* ---- Filter phase: companion, node, update ----------------------------------- */

/* History term of the inductor branch for the coming step (Q3.28). */
typedef struct {
    int32_t j_l;   /* [A] inductor branch current at t_k+1 if dv = 0, into the node */
} ps_hist_q;

/*
 * Companion of the inductor branch for a step with mean inverter voltage u:
 *   j_L = a_L i_L + 2 G_L (u - v),   a_L = 1 - eps_l.
 * The shunt's history j_sh is a state (ps_phase_q). Bounds (|i_L|, |v| <= 1
 * clamped, |u| <= 2/3, Q32 coefficients below 0.5): |u - v| <= 5/3,
 * |j_L| < 1.9 per unit.
 */
static inline void ps_filter_history_q(const ps_coef_q *k, const ps_phase_q *x, int32_t u,
                                       ps_hist_q *h) {
    h->j_l = ps_hi_q(
        ps_mac_q(ps_mac_q(ps_acc_q(x->i_l), x->i_l, k->neg_eps_l), u - x->v_c, k->g_l2));
}

/*
 * The inductor branch's history (ps_filter_history_q()) with held states:
 * its 64-bit sum takes (u - v) G_L2 as v3 (n G_L2) - v G_L2, the same
 * integer (u = n v3 and u - v are exact), so that the step's chain
 * through the DC link has one product there instead of two.
 */
static inline void ps_filter_history_held_q(const ps_coef_q *k, const ps_phase_q *x, int32_t v3,
                                            int64_t ng, ps_hist_q *h) {
    const uint64_t acc = ps_mac_q(ps_acc_q(x->i_l), x->i_l, k->neg_eps_l) -
                         (uint64_t)((int64_t)x->v_c * (int64_t)k->g_l2);
    h->j_l = ps_hi_q(acc + (uint64_t)(v3 * ng)); /* |v3 ng| < 2^61 */
}

/*
 * Node solve: dv = (j_L + j_sh - i_m) / (G_L + G_sh) = k_node (j_L + j_sh - i_m).
 * |j_sh| <= 4 (below), so the sum is below 6.9 per unit; dv below 3.5.
 */
static inline int32_t ps_filter_node_q(const ps_coef_q *k, const ps_phase_q *x,
                                       const ps_hist_q *h, int32_t i_m) {
    return ps_hi_q(ps_mac_q(ps_acc_q(0), h->j_l + x->j_sh - i_m, k->k_node));
}

/*
 * Branch currents and states at t_k+1 from the node's dv; i_L, v and i_d
 * clamped to +-1 per unit and counted:
 *   v(k+1)    = v + dv
 *   i_L(k+1)  = j_L - G_L dv
 *   i_d(k+1)  = (1 - a) i_d + G_d dv,           a = 2 r_cd G_d
 *   j_sh(k+1) = i_L(k+1) - i_m - (2 - a) i_d(k+1)
 * The last is i_C(k+1) - G_d (v - h_d)(k+1), with the capacitor current by
 * KCL and h_d = v_d + r_cd i_d the damping capacitor's trapezoidal history,
 * for which v - h_d = (R_d - r_cd) i_d. Bounds: |j_sh| <= 1 + 1 + 2 = 4.
 * The three states are tested together; j_sh is formed first from the
 * unclamped values (in range, the usual case, they are the same) and only
 * formed again after a clamp. Before the clamp |i_L| < 3.8, |i_d| < 3.4
 * and |v| < 4.7 per unit, and j_sh's sum may then leave the int32_t range;
 * it is computed modulo 2^32 and 2^64 (defined) and replaced.
 */
static inline int32_t ps_shunt_history_q(const ps_coef_q *k, int32_t i_l, int32_t i_d,
                                         int32_t i_m) {
    /* Modulo 2^32: exact in range, defined (and then replaced) out of it. */
    const uint32_t base = (uint32_t)i_l - (uint32_t)i_m - 2u * (uint32_t)i_d;
    return ps_hi_q(ps_mac_q(ps_acc_q(fp_from_u32_i32(base)), i_d, k->a_d));
}

static inline void ps_filter_update_q(const ps_coef_q *k, ps_phase_q *x, const ps_hist_q *h,
                                      int32_t dv, int32_t i_m, uint32_t *sat_count) {
    int32_t i_l = ps_hi_q(ps_mac_q(ps_acc_q(h->j_l), dv, k->neg_g_l));
    int32_t i_d = ps_hi_q(ps_mac_q(ps_mac_q(ps_acc_q(x->i_d), x->i_d, k->neg_a_d), dv, k->g_d));
    int32_t v = x->v_c + dv;
    int32_t j_sh = ps_shunt_history_q(k, i_l, i_d, i_m);
    if (ps_out_of_range3_q(i_l, i_d, v)) { /* rare: clamp and count each, redo j_sh */
        i_l = ps_clamp_q(i_l, sat_count);
        i_d = ps_clamp_q(i_d, sat_count);
        v = ps_clamp_q(v, sat_count);
        j_sh = ps_shunt_history_q(k, i_l, i_d, i_m);
    }
    x->j_sh = j_sh;
    x->v_c = v;
    x->i_l = i_l;
    x->i_d = i_d;
}

/* ---- Float twin ---------------------------------------------------------------- */

/*
 * Clamps x to [-lim, lim] and counts a clamp; NaN passes. lim is a power
 * of two (the ranges below), so |x| > lim is one product and one
 * comparison, x^2 > lim^2, rounded or not: lim^2 is exact, |x| <= lim
 * gives x^2 <= lim^2, which rounds to at most lim^2, and the next float
 * above lim, lim (1 + 2^-23), gives lim^2 (1 + 2^-22 + 2^-46), which
 * rounds to at least lim^2 (1 + 2^-22), the float after lim^2;
 * infinities compare above, NaN does not.
 */
static inline float ps_clamp_f32(float x, float lim, uint32_t *sat_count) {
    if ((x * x) > (lim * lim)) {
        fp_count_sat(sat_count);
        return (x > 0.0f) ? lim : -lim;
    }
    return x;
}

#define PS_V_LIM_F32 1024.0f /* [V] the fixed twin's range */
#define PS_I_LIM_F32 256.0f  /* [A] */

/* The fixed twin's, with the leg sums w_x = (2 d_x - d_y) - d_z rounded in that order. */
static inline void ps_inverter_w_f32(float v_dc, float w_a, float w_b, float *u_a, float *u_b) {
    const float v3 = v_dc * (1.0f / 3.0f);
    *u_a = v3 * w_a;
    *u_b = v3 * w_b;
}

static inline float ps_leg_sum_f32(float d_x, float d_y, float d_z) {
    return (2.0f * d_x - d_y) - d_z;
}

static inline void ps_inverter_f32(float v_dc, const float duty[3], float *u_a, float *u_b) {
    ps_inverter_w_f32(v_dc, ps_leg_sum_f32(duty[0], duty[1], duty[2]),
                      ps_leg_sum_f32(duty[1], duty[0], duty[2]), u_a, u_b);
}

/* The DC-link current's sum T = (d_a - d_c) s_a + (d_b - d_c) s_b; the current is T / 2. */
static inline float ps_dc_sum_f32(const float duty[3], float s_a, float s_b) {
    return ((duty[0] - duty[2]) * s_a) + ((duty[1] - duty[2]) * s_b);
}

static inline float ps_dc_current_f32(const float duty[3], float s_a, float s_b) {
    return 0.5f * ps_dc_sum_f32(duty, s_a, s_b);
}

/*
 * DC-link forward Euler on the current's sum t = 2 i_dc:
 * v + (kg (e - v) + (-k_c / 2) t), with neg_k_c2 = -k_c / 2 (ps_coef_f32).
 * That is the fixed twin's v + kg (e - v) - k_c i_dc: halving is exact in
 * binary floating point, so (k_c / 2) t and k_c (t / 2) are the same
 * rounded product whenever t / 2 is exact, that is unless |t| < 2^-125 A
 * (a subnormal half, which the stage's currents never come near while a
 * leg conducts), and the half is formed once at set-up instead of on the
 * step's chain through the DC link. The increment is formed before it is
 * added, so that the state (about 600 V, a float step of 61 uV) is rounded
 * once per step.
 */
static inline float ps_dclink_step_f32(float v_dc, const ps_battery_f32 *bat, float neg_k_c2,
                                       float t, uint32_t *sat_count) {
    return ps_clamp_f32(v_dc + (bat->kg * (bat->e_v - v_dc) + neg_k_c2 * t), PS_V_LIM_F32,
                        sat_count);
}

typedef struct {
    float j_l;   /* [A] */
} ps_hist_f32;

static inline void ps_filter_history_f32(const ps_coef_f32 *k, const ps_phase_f32 *x, float u,
                                         ps_hist_f32 *h) {
    h->j_l = (x->i_l + k->neg_eps_l * x->i_l) + k->g_l2 * (u - x->v_c);
}

static inline float ps_filter_node_f32(const ps_coef_f32 *k, const ps_phase_f32 *x,
                                       const ps_hist_f32 *h, float i_m) {
    return k->k_node * ((h->j_l + x->j_sh) - i_m);
}

static inline void ps_filter_update_f32(const ps_coef_f32 *k, ps_phase_f32 *x,
                                        const ps_hist_f32 *h, float dv, float i_m,
                                        uint32_t *sat_count) {
    const float i_l = ps_clamp_f32(h->j_l + k->neg_g_l * dv, PS_I_LIM_F32, sat_count);
    const float i_d =
        ps_clamp_f32((x->i_d + k->neg_a_d * x->i_d) + k->g_d * dv, PS_I_LIM_F32, sat_count);
    x->j_sh = ((i_l - i_m) - 2.0f * i_d) + k->a_d * i_d;
    x->v_c = ps_clamp_f32(x->v_c + dv, PS_V_LIM_F32, sat_count);
    x->i_l = i_l;
    x->i_d = i_d;
}

#endif /* UUV_POWER_STAGE_NODES_H */
