/*
 * Set-up of the power stage, both twins (power_stage.h): parameter checks,
 * the step coefficients of the trapezoidal filter and the forward-Euler DC
 * link, the battery companion in the step's form, and the outputs. All of
 * it in double: none of it runs on the 2 us path.
 */
#include "models/drive/inverter/power_stage.h"

#include <stddef.h>

#include "models/drive/drive_units.h"

#define PS_STEP_MIN_NS 100u
#define PS_STEP_MAX_NS 1000000u
#define PS_Z_BASE_OHM (DRIVE_BASE_VOLTAGE_V / DRIVE_BASE_CURRENT_A) /* [ohm] 4 */
#define PS_KG_MAX 0.4999 /* forward-Euler factor T G / C_dc, below the Q32 limit 0.5 */
#define PS_G_MAX_PU 127.9 /* Q24 limit of the battery conductance, per unit (32 S) */

/* Coefficients of one step in SI units (double), shared by both twins. */
typedef struct {
    double g_l, eps_l, r_cd, g_d, k_node, k_c;
} ps_coef_si;

static int ps_finite_pos(double x) { return x > 0.0 && x < 1.0e300; }

static ps_status ps_check(const power_stage_params *p, uint32_t step_ns, double v_dc0_v) {
    if (!ps_finite_pos(p->c_dc_f) || !ps_finite_pos(p->l_h) || !ps_finite_pos(p->c_f) ||
        !ps_finite_pos(p->r_d_ohm) || !ps_finite_pos(p->c_d_f) ||
        !(p->r_l_ohm >= 0.0 && p->r_l_ohm < 1.0e300)) {
        return PS_ERR_PARAM;
    }
    if (step_ns < PS_STEP_MIN_NS || step_ns > PS_STEP_MAX_NS) {
        return PS_ERR_STEP;
    }
    if (!(v_dc0_v >= 0.0 && v_dc0_v < DRIVE_BASE_VOLTAGE_V)) {
        return PS_ERR_VOLTAGE;
    }
    return PS_OK;
}

/*
 * Trapezoidal companions of the filter elements and the forward-Euler DC
 * link over a step T (docs/drive_power.md):
 *   inductor R_L + L:    G_L = 1 / (2L/T + R_L),  a_L = (2L/T - R_L) G_L
 *   capacitor C:         G_C = 2C / T
 *   damping R_d + C_d:   G_d = 1 / (R_d + T / (2 C_d))
 *   node:                k_node = 1 / (G_L + G_C + G_d)
 *   DC link:             k_c = T / C_dc
 */
static ps_coef_si ps_coef_from(const power_stage_params *p, uint32_t step_ns) {
    const double t = (double)step_ns * 1.0e-9;
    const double z_l = 2.0 * p->l_h / t + p->r_l_ohm;
    ps_coef_si c;
    c.g_l = 1.0 / z_l;
    c.eps_l = 2.0 * p->r_l_ohm / z_l;
    c.r_cd = t / (2.0 * p->c_d_f);
    c.g_d = 1.0 / (p->r_d_ohm + c.r_cd);
    c.k_node = 1.0 / (c.g_l + 2.0 * p->c_f / t + c.g_d);
    c.k_c = t / p->c_dc_f;
    return c;
}

/* round(x * 2^bits) into int32_t when |x * 2^bits| < 2^31 - 1; 0 and *ok = 0 otherwise. */
static int32_t ps_to_fixed(double x, unsigned bits, int *ok) {
    double s = x;
    unsigned i;
    for (i = 0u; i < bits; i++) {
        s *= 2.0;
    }
    if (!(s < 2147483647.0 && s > -2147483647.0)) {
        *ok = 0;
        return 0;
    }
    return (int32_t)((s >= 0.0) ? s + 0.5 : s - 0.5);
}

/* Q3.28 per unit of a value in its base (clamped to +-1 per unit: set-up values). */
static int32_t ps_q28_from(double value, double base) {
    double pu = value / base;
    int ok = 1;
    if (pu > 1.0) { /* LCOV_EXCL_BR_LINE: callers pass [0, 1024) V (checked v_dc0, clamped e) */
        pu = 1.0;
    } else if (pu < -1.0) { /* LCOV_EXCL_BR_LINE: no caller passes a negative value */
        pu = -1.0;
    }
    return ps_to_fixed(pu, 28u, &ok);
}

/* ---- Fixed-point twin ---------------------------------------------------- */

ps_status power_stage_init_q(power_stage_q *ps, const power_stage_params *p, uint32_t step_ns,
                             double v_dc0_v) {
    ps_status st;
    ps_coef_si c;
    ps_coef_q k;
    int ok = 1;
    unsigned x;

    if (ps == NULL || p == NULL) {
        return PS_ERR_NULL;
    }
    st = ps_check(p, step_ns, v_dc0_v);
    if (st != PS_OK) {
        return st;
    }
    c = ps_coef_from(p, step_ns);
    /* Admittances per unit are G * 4 ohm, impedances R / 4 ohm. */
    k.neg_eps_l = ps_to_fixed(-c.eps_l, 32u, &ok);
    k.g_l2 = ps_to_fixed(2.0 * c.g_l * PS_Z_BASE_OHM, 32u, &ok);
    k.neg_g_l = ps_to_fixed(-c.g_l * PS_Z_BASE_OHM, 32u, &ok);
    k.g_d = ps_to_fixed(c.g_d * PS_Z_BASE_OHM, 32u, &ok);
    k.a_d = ps_to_fixed(2.0 * c.r_cd * c.g_d, 32u, &ok);
    k.neg_a_d = -k.a_d;
    k.k_node = ps_to_fixed(c.k_node / PS_Z_BASE_OHM, 32u, &ok);
    k.neg_k_c = ps_to_fixed(-c.k_c / PS_Z_BASE_OHM, 32u, &ok);
    if (!ok) {
        return PS_ERR_FIXED_RANGE;
    }
    ps->p = p;
    ps->step_ns = step_ns;
    ps->k = k;
    for (x = 0u; x < 2u; x++) {
        ps->ph[x].i_l = 0;
        ps->ph[x].v_c = 0;
        ps->ph[x].i_d = 0;
        ps->ph[x].j_sh = 0;
        ps->u[x] = 0;
    }
    ps->v_dc = ps_q28_from(v_dc0_v, DRIVE_BASE_VOLTAGE_V);
    ps->i_dc = 0;
    ps->sat_count = 0u;
    return PS_OK;
}

/*
 * Shared clamping of a battery companion: returns the number of clamps and
 * writes e [V], kg and G [S] (all zero when open).
 */
static uint32_t ps_battery_si(uint32_t step_ns, const power_stage_params *p, double g_s,
                              double b_a, double *e, double *kg, double *g) {
    const double t = (double)step_ns * 1.0e-9;
    const double g_max = PS_G_MAX_PU / PS_Z_BASE_OHM;
    uint32_t n = 0u;

    *e = 0.0;
    *kg = 0.0;
    *g = 0.0;
    if (g_s == 0.0) {
        return 0u;
    }
    if (!(g_s > 0.0 && g_s < 1.0e300) || !(b_a > -1.0e300 && b_a < 1.0e300)) {
        return 1u;
    }
    *g = g_s;
    if (*g > g_max) {
        *g = g_max;
        n++;
    }
    *e = b_a / g_s;
    if (*e < 0.0) {
        *e = 0.0;
        n++;
    } else if (*e >= DRIVE_BASE_VOLTAGE_V) {
        *e = DRIVE_BASE_VOLTAGE_V * (1.0 - 1.0e-9);
        n++;
    }
    *kg = t * *g / p->c_dc_f;
    if (*kg > PS_KG_MAX) {
        *kg = PS_KG_MAX;
        n++;
    }
    return n;
}

uint32_t power_stage_battery_q(const power_stage_q *ps, double g_s, double b_a,
                               ps_battery_q *out) {
    double e;
    double kg;
    double g;
    int ok = 1;
    uint32_t n = ps_battery_si(ps->step_ns, ps->p, g_s, b_a, &e, &kg, &g);
    out->e = ps_q28_from(e, DRIVE_BASE_VOLTAGE_V);
    out->kg = ps_to_fixed(kg, 32u, &ok);
    out->g = ps_to_fixed(g * PS_Z_BASE_OHM, 24u, &ok);
    return n;
}

/* Q3.28 -> Q15: round(x / 2^13), saturated (+1 per unit becomes 32767). */
static q15_t ps_q15(int32_t x) { return fp_sat_q15(fp_shr_round_i32(x, 13u)); }

void power_stage_output_q(const power_stage_q *ps, const ps_battery_q *bat,
                          power_stage_out_q *out) {
    unsigned x;
    /* G (v - e): Q24 times Q3.28 is Q52 of the per-unit current; Q15 is 37 bits down. */
    const int64_t i_bat = (int64_t)bat->g * (int64_t)(ps->v_dc - bat->e);

    out->v_dc = ps_q15(ps->v_dc);
    for (x = 0u; x < 2u; x++) {
        out->v_inv[x] = ps_q15(ps->u[x]);
        out->v_cap[x] = ps_q15(ps->ph[x].v_c);
        out->i_l[x] = ps_q15(ps->ph[x].i_l);
    }
    out->v_inv[2] = ps_q15(-ps->u[0] - ps->u[1]);
    out->v_cap[2] = ps_q15(-ps->ph[0].v_c - ps->ph[1].v_c);
    out->i_l[2] = ps_q15(-ps->ph[0].i_l - ps->ph[1].i_l);
    out->i_dc = ps_q15(ps->i_dc);
    out->i_bat = fp_sat_q15((int32_t)fp_sat_q31(fp_shr_round_i64(i_bat, 37u)));
}

/* ---- Float twin ------------------------------------------------------------ */

ps_status power_stage_init_f32(power_stage_f32 *ps, const power_stage_params *p,
                               uint32_t step_ns, double v_dc0_v) {
    ps_status st;
    ps_coef_si c;
    unsigned x;

    if (ps == NULL || p == NULL) {
        return PS_ERR_NULL;
    }
    st = ps_check(p, step_ns, v_dc0_v);
    if (st != PS_OK) {
        return st;
    }
    c = ps_coef_from(p, step_ns);
    ps->p = p;
    ps->step_ns = step_ns;
    ps->k.neg_eps_l = (float)(-c.eps_l);
    ps->k.g_l2 = (float)(2.0 * c.g_l);
    ps->k.neg_g_l = (float)(-c.g_l);
    ps->k.g_d = (float)c.g_d;
    ps->k.a_d = (float)(2.0 * c.r_cd * c.g_d);
    ps->k.neg_a_d = -ps->k.a_d;
    ps->k.k_node = (float)c.k_node;
    ps->k.neg_k_c = (float)(-0.5 * c.k_c); /* of the sum 2 i_dc (ps_dclink_step_f32) */
    for (x = 0u; x < 2u; x++) {
        ps->ph[x].i_l = 0.0f;
        ps->ph[x].v_c = 0.0f;
        ps->ph[x].i_d = 0.0f;
        ps->ph[x].j_sh = 0.0f;
        ps->u[x] = 0.0f;
    }
    ps->v_dc = (float)v_dc0_v;
    ps->i_dc = 0.0f;
    ps->sat_count = 0u;
    return PS_OK;
}

uint32_t power_stage_battery_f32(const power_stage_f32 *ps, double g_s, double b_a,
                                 ps_battery_f32 *out) {
    double e;
    double kg;
    double g;
    uint32_t n = ps_battery_si(ps->step_ns, ps->p, g_s, b_a, &e, &kg, &g);
    out->e_v = (float)e;
    out->kg = (float)kg;
    out->g_s = (float)g;
    return n;
}

void power_stage_output_f32(const power_stage_f32 *ps, const ps_battery_f32 *bat,
                            power_stage_out_f32 *out) {
    unsigned x;
    out->v_dc_v = ps->v_dc;
    for (x = 0u; x < 2u; x++) {
        out->v_inv_v[x] = ps->u[x];
        out->v_cap_v[x] = ps->ph[x].v_c;
        out->i_l_a[x] = ps->ph[x].i_l;
    }
    out->v_inv_v[2] = -ps->u[0] - ps->u[1];
    out->v_cap_v[2] = -ps->ph[0].v_c - ps->ph[1].v_c;
    out->i_l_a[2] = -ps->ph[0].i_l - ps->ph[1].i_l;
    out->i_dc_a = ps->i_dc;
    out->i_bat_a = bat->g_s * (ps->v_dc - bat->e_v);
}
