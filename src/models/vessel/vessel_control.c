/*
 * Control-surface and propulsion forces of the vessel: rudder, stern plane,
 * port and starboard bow planes, the propeller-wash corrections (the terms
 * scaled by the factor epsilon) and the surge propulsion force of the
 * selected law. docs/vessel.md states the equations and the guards.
 */
#include "math/umath.h"
#include "models/vessel/vessel_internal.h"

/* Surge speed per unit shaft speed of the MSS law's advance ratio [m/rad]. */
#define VESSEL_ETA_GAIN 0.012
/* Guard of the advance-ratio denominator u + 1e-10 [m/s], as in the source. */
#define VESSEL_ETA_GUARD 1e-10

/*
 * The advance-ratio-like quantity eta = 0.012 w / (u + 1e-10) and the wash
 * factor eps = -1 + sgn(w)/sgn(d) * (sqrt(C_t + 1) - 1) / (sqrt(C_t1 + 1) - 1 + 1e-10).
 *
 * Two guards beyond the source's own 1e-10:
 * - the denominator d = u + 1e-10 has a pole at u = -1e-10 (a division by
 *   zero there, and values that overflow a few RK4 stages later within
 *   ~1e-20 m/s of it); for |d| < 1e-10, i.e. -2e-10 < u < 0, d is taken as
 *   1e-10, the value at rest. No reachable speed other than that band sees it.
 * - C_t + 1 < 0 (eta < -2.98: the shaft turning against a slow surge) has
 *   no real square root; the source then gives complex derivatives. The
 *   argument is clamped at 0, which gives exactly the real part of the
 *   source's result, and equals it whenever the wash terms vanish.
 */
unsigned vessel_propulsion_eval(const vessel_model *m, double u_mps, double w_radps,
                                vessel_prop_terms *pt) {
    unsigned ev = 0u;
    const vessel_params *pa = &m->params;
    double d = u_mps + VESSEL_ETA_GUARD;
    if ((d > -VESSEL_ETA_GUARD) && (d < VESSEL_ETA_GUARD)) {
        d = VESSEL_ETA_GUARD;
        ev |= VESSEL_FLAG(VESSEL_EVENT_ETA_POLE);
    }
    const double eta = VESSEL_ETA_GAIN * w_radps / d;
    const double eta2 = eta * math_fabs_f64(eta);
    double arg = m->ct_scale * eta2 + 1.0;
    if (arg < 0.0) {
        arg = 0.0;
        ev |= VESSEL_FLAG(VESSEL_EVENT_EPS_SQRT);
    }
    double sgn = (w_radps > 0.0) ? 1.0 : ((w_radps < 0.0) ? -1.0 : 0.0);
    sgn = (d > 0.0) ? sgn : -sgn;
    pt->eps = -1.0 + sgn * (math_sqrt_f64(arg) - 1.0) / m->eps_den;

    const double uu = u_mps * u_mps;
    if (m->propulsion == VESSEL_PROP_MSS) {
        /* r2 u^2 X'_prop with X'_prop = C_d0 (eta |eta| - 1): thrust minus hull drag. */
        pt->thrust_n = m->r2 * uu * (pa->cd0 * eta2);
        pt->surge_n = m->r2 * uu * (pa->cd0 * (eta2 - 1.0));
    } else {
        /* The paper's thruster; the hull drag keeps its coefficient r2 C_d0. */
        pt->thrust_n = propeller_surge_force_f64(&m->prop, w_radps, u_mps);
        pt->surge_n = pt->thrust_n - m->r2 * pa->cd0 * u_mps * math_fabs_f64(u_mps);
    }
    return ev;
}

/* Surge: fin drag and lift terms, wash corrections, propulsion. */
static double vessel_control_x(const vessel_model *m, const double x[VESSEL_NSTATES],
                               const vessel_actuation *a, const vessel_prop_terms *pt) {
    const vessel_coeffs_x *c = &m->params.x;
    const double u = x[VESSEL_U_MPS], v = x[VESSEL_V_MPS], w = x[VESSEL_W_MPS];
    const double q = x[VESSEL_Q_RADPS], r = x[VESSEL_R_RADPS];
    const double dr = a->rudder_rad, ds = a->stern_rad;
    const double db = a->bow_port_rad + a->bow_stbd_rad;
    const double uu = u * math_fabs_f64(u); /* signed: fin drag opposes the flow */
    return m->r3 * (c->r_dr * u * r * dr + (c->q_ds * ds + c->q_db2 * db) * u * q) +
           m->r2 * (c->v_dr * u * v * dr + (c->w_ds * ds + c->w_db2 * db) * u * w +
                    (c->ds_ds * ds * ds + c->dr_dr * dr * dr) * uu) +
           m->r3 * c->q_ds_n * u * q * ds * pt->eps +
           m->r2 * (c->w_ds_n * u * w * ds + c->ds_ds_n * uu * ds * ds) * pt->eps + pt->surge_n;
}

unsigned vessel_tau_control(const vessel_model *m, const double x[VESSEL_NSTATES],
                            const vessel_actuation *a, double tau[6]) {
    const vessel_params *pa = &m->params;
    const double u = x[VESSEL_U_MPS], w = x[VESSEL_W_MPS];
    const double p = x[VESSEL_P_RADPS], q = x[VESSEL_Q_RADPS];
    const double dr = a->rudder_rad, ds = a->stern_rad;
    const double db = a->bow_port_rad + a->bow_stbd_rad;
    const double au = math_fabs_f64(u);
    const double uu = u * u;
    const double ua = u * au; /* signed dynamic pressure: fin lift reverses astern */
    vessel_prop_terms pt;
    const unsigned ev = vessel_propulsion_eval(m, u, a->shaft_radps, &pt);
    const double eps = pt.eps;

    tau[0] += vessel_control_x(m, x, a, &pt);
    tau[1] += m->r2 * pa->y.dr * ua * dr;
    tau[2] += m->r2 * ua * (pa->z.ds * ds + pa->z.db2 * db) + m->r3 * pa->z.q_n * u * q * eps +
              m->r2 * (pa->z.w_n * au * w + pa->z.ds_n * ua * ds) * eps;
    tau[3] += m->r4 * pa->k.p_n * au * p * eps + m->r3 * pa->k.prop * uu * u +
              m->r3 * ua * pa->k.db2 * db;
    tau[4] += m->r4 * pa->m.q_n * au * q * eps +
              m->r3 * (pa->m.w_n * u * w + pa->m.ds_n * ua * ds) * eps +
              m->r3 * ua * (pa->m.ds * ds + pa->m.db2 * db);
    tau[5] += m->r3 * pa->n.prop * uu + m->r3 * pa->n.dr * ua * dr;
    return ev;
}
