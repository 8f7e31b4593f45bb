/*
 * What depends on the vessel's attitude: the zyx Euler kinematics
 * deta = J(eta) nu and the restoring forces of weight and buoyancy.
 * Both use the same sines and cosines, computed once per evaluation.
 */
#include "math/umath.h"
#include "models/vessel/vessel_internal.h"

/* Below this |cos(theta)| the Euler rates are computed with +-1e-12 instead. */
#define VESSEL_COS_THETA_MIN 1e-12

/*
 * The Euler-angle rates divide by cos(theta), which vanishes at theta =
 * +-90 degrees. No double is exactly pi/2, but an approximate cosine may
 * still return 0 or a denormal there; keeping the divisor at least 1e-12 in
 * magnitude keeps the rates finite (the attitude is then meaningless for a
 * moment, as in any Euler-angle model, but the run continues).
 */
unsigned vessel_trig_eval(const double x[VESSEL_NSTATES], vessel_trig *t) {
    unsigned ev = 0u;
    math_sincos_f64(x[VESSEL_PHI_RAD], &t->sphi, &t->cphi);
    math_sincos_f64(x[VESSEL_THETA_RAD], &t->sth, &t->cth);
    math_sincos_f64(x[VESSEL_PSI_RAD], &t->spsi, &t->cpsi);
    double c = t->cth;
    if ((c < VESSEL_COS_THETA_MIN) && (c > -VESSEL_COS_THETA_MIN)) {
        c = (c < 0.0) ? -VESSEL_COS_THETA_MIN : VESSEL_COS_THETA_MIN;
        ev |= VESSEL_FLAG(VESSEL_EVENT_PITCH_90);
    }
    t->inv_cth = 1.0 / c;
    t->tth = t->sth * t->inv_cth;
    return ev;
}

void vessel_kinematics(const vessel_trig *t, const double x[VESSEL_NSTATES], double deta[6]) {
    const double u = x[VESSEL_U_MPS], v = x[VESSEL_V_MPS], w = x[VESSEL_W_MPS];
    const double p = x[VESSEL_P_RADPS], q = x[VESSEL_Q_RADPS], r = x[VESSEL_R_RADPS];
    const double sf = t->sphi, cf = t->cphi, st = t->sth, ct = t->cth;
    const double ss = t->spsi, cs = t->cpsi;

    /* Linear velocity: R = Rz(psi) Ry(theta) Rx(phi) maps BODY to NED. */
    deta[0] = cs * ct * u + (-ss * cf + cs * st * sf) * v + (ss * sf + cs * cf * st) * w;
    deta[1] = ss * ct * u + (cs * cf + sf * st * ss) * v + (-cs * sf + st * ss * cf) * w;
    deta[2] = -st * u + ct * sf * v + ct * cf * w;
    /* Angular velocity: the Euler-angle rates. */
    deta[3] = p + sf * t->tth * q + cf * t->tth * r;
    deta[4] = cf * q - sf * r;
    deta[5] = sf * t->inv_cth * q + cf * t->inv_cth * r;
}

/*
 * Restoring forces tau = -g(eta) for weight W at r_G and buoyancy B at r_B,
 * in the general form that holds for W != B. B is the nominal buoyancy plus
 * the command delta_B, which models a variable-displacement device: it
 * changes B only, not the mass. With z positive down, B > W gives a
 * negative heave force: the vehicle rises.
 */
void vessel_tau_restoring(const vessel_model *m, const vessel_trig *t, double delta_b_n,
                          double tau[6]) {
    const vessel_params *pa = &m->params;
    const double wt = pa->weight_n;
    const double b = pa->buoyancy_n + delta_b_n;
    const double wb = wt - b;
    const double mx = pa->r_g_m[0] * wt - pa->r_b_m[0] * b;
    const double my = pa->r_g_m[1] * wt - pa->r_b_m[1] * b;
    const double mz = pa->r_g_m[2] * wt - pa->r_b_m[2] * b;
    const double sf = t->sphi, cf = t->cphi, st = t->sth, ct = t->cth;

    tau[0] -= wb * st;
    tau[1] -= -wb * ct * sf;
    tau[2] -= -wb * ct * cf;
    tau[3] -= -my * ct * cf + mz * ct * sf;
    tau[4] -= mz * st + mx * ct * cf;
    tau[5] -= -mx * ct * sf - my * st;
}
