/*
 * Hull hydrodynamics of the vessel: the damping and Coriolis derivatives of
 * the prime system together with the rigid-body Coriolis and centripetal
 * terms, and the strip-theory cross-flow drag. The terms follow the
 * reference description of the MSS model term by term (docs/vessel.md),
 * with two signs corrected: the rigid-body heave term enters with a minus
 * sign and the pitch gyroscopic term (I_z - I_x) p r with a plus sign, as
 * Newton's and Euler's laws in the rotating body frame require.
 *
 * Without currents the velocities relative to the water are the body
 * velocities, so u, v, w below are the states themselves.
 */
#include "math/umath.h"
#include "models/vessel/vessel_internal.h"

/* Surge and sway. */
static void vessel_hydro_xy(const vessel_model *m, const double x[VESSEL_NSTATES],
                            double tau[6]) {
    const vessel_params *pa = &m->params;
    const double u = x[VESSEL_U_MPS], v = x[VESSEL_V_MPS], w = x[VESSEL_W_MPS];
    const double p = x[VESSEL_P_RADPS], q = x[VESSEL_Q_RADPS], r = x[VESSEL_R_RADPS];
    const double au = math_fabs_f64(u); /* the damping terms' flow speed, see below */
    const double xg = pa->r_g_m[0], yg = pa->r_g_m[1], zg = pa->r_g_m[2];
    const double mp = m->m_prime;
    const double len = pa->length_m;
    const vessel_coeffs_x *cx = &pa->x;
    const vessel_coeffs_y *cy = &pa->y;

    /* The m' terms are the rigid-body surge Coriolis terms in prime form. */
    tau[0] += m->r2 * (cx->vv * v * v + cx->ww * w * w) +
              m->r3 * ((mp + cx->vr) * v * r + (cx->wq - mp) * w * q + cx->vp * v * p) +
              m->r4 * ((mp * xg / len + cx->qq) * q * q + (mp * xg / len + cx->rr) * r * r -
                       (mp * yg / len) * p * q + (cx->pr - mp * zg / len) * p * r +
                       cx->pp * p * p);
    tau[1] += m->r2 * (cy->v * au * v + cy->vw * v * w) +
              m->r3 * (cy->p * au * p + cy->r * u * r + cy->vq * v * q + cy->wp * w * p +
                       cy->wr * w * r) +
              m->r4 * (cy->pq * p * q + cy->qr * q * r) -
              m->mass_kg * (u * r - w * p + xg * p * q - yg * (p * p + r * r) + zg * q * r);
}

/* Heave and roll. */
static void vessel_hydro_zk(const vessel_model *m, const double x[VESSEL_NSTATES],
                            double tau[6]) {
    const vessel_params *pa = &m->params;
    const double u = x[VESSEL_U_MPS], v = x[VESSEL_V_MPS], w = x[VESSEL_W_MPS];
    const double p = x[VESSEL_P_RADPS], q = x[VESSEL_Q_RADPS], r = x[VESSEL_R_RADPS];
    const double au = math_fabs_f64(u); /* the damping terms' flow speed, see below */
    const double xg = pa->r_g_m[0], yg = pa->r_g_m[1], zg = pa->r_g_m[2];
    const vessel_coeffs_z *cz = &pa->z;
    const vessel_coeffs_k *ck = &pa->k;

    /* Corrected sign: the centripetal term is subtracted (MSS adds it). */
    tau[2] += m->r2 * (cz->w * au * w + cz->vv * v * v) +
              m->r3 * (cz->q * u * q + cz->vp * v * p + cz->vr * v * r) +
              m->r4 * (cz->pp * p * p + cz->pr * p * r + cz->rr * r * r) -
              m->mass_kg * (v * p - u * q + xg * p * r + yg * q * r - zg * (p * p + q * q));
    tau[3] += m->r3 * (ck->v * au * v + ck->vw * v * w) +
              m->r4 * (ck->p * au * p + ck->r * u * r + ck->vq * v * q + ck->wp * w * p +
                       ck->wr * w * r) +
              m->r5 * (ck->pq * p * q + ck->qr * q * r) +
              (pa->iy_kgm2 - pa->iz_kgm2) * q * r - pa->ixy_kgm2 * p * r -
              pa->iyz_kgm2 * (r * r - q * q) + pa->ixz_kgm2 * p * q -
              m->mass_kg * (yg * (v * p - u * q) - zg * (u * r - w * p));
}

/* Pitch and yaw. */
static void vessel_hydro_mn(const vessel_model *m, const double x[VESSEL_NSTATES],
                            double tau[6]) {
    const vessel_params *pa = &m->params;
    const double u = x[VESSEL_U_MPS], v = x[VESSEL_V_MPS], w = x[VESSEL_W_MPS];
    const double p = x[VESSEL_P_RADPS], q = x[VESSEL_Q_RADPS], r = x[VESSEL_R_RADPS];
    const double au = math_fabs_f64(u); /* the damping terms' flow speed, see below */
    const double xg = pa->r_g_m[0], yg = pa->r_g_m[1], zg = pa->r_g_m[2];
    const vessel_coeffs_m *cm = &pa->m;
    const vessel_coeffs_n *cn = &pa->n;

    /* Corrected sign: +(I_z - I_x) p r (MSS subtracts it). */
    tau[4] += m->r3 * (cm->uw * u * w + cm->vv * v * v) +
              m->r4 * (cm->uq * au * q + cm->vp * v * p + cm->vr * v * r) +
              m->r5 * (cm->pp * p * p + cm->pr * p * r + cm->rr * r * r) +
              (pa->iz_kgm2 - pa->ix_kgm2) * p * r + pa->ixy_kgm2 * q * r -
              pa->iyz_kgm2 * p * q - pa->ixz_kgm2 * (p * p - r * r) +
              m->mass_kg * (xg * (v * p - u * q) - zg * (w * q - v * r));
    tau[5] += m->r3 * (cn->v * u * v + cn->vw * v * w) +
              m->r4 * (cn->p * u * p + cn->r * au * r + cn->vq * v * q + cn->wp * w * p +
                       cn->wr * w * r) +
              m->r5 * (cn->pq * p * q + cn->qr * q * r) +
              (pa->ix_kgm2 - pa->iy_kgm2) * p * q + pa->ixy_kgm2 * (p * p - q * q) +
              pa->iyz_kgm2 * p * r - pa->ixz_kgm2 * q * r -
              m->mass_kg * (xg * (u * r - w * p) - yg * (w * q - v * r));
}

void vessel_tau_hydro(const vessel_model *m, const double x[VESSEL_NSTATES], double tau[6]) {
    vessel_hydro_xy(m, x, tau);
    vessel_hydro_zk(m, x, tau);
    vessel_hydro_mn(m, x, tau);
}

/*
 * Cross-flow drag by strip theory over 11 stations of box-shaped sections,
 * each weighted with the full station spacing (so the sum spans 1.1 L, as
 * in the source). The 1e-6 added to the local cross-flow speed makes a
 * station without cross flow contribute 0 instead of 0/0. The pitch moment
 * uses (w + x q) where the heave force uses (w - x q), as the source does.
 * One division per station and the spacing applied once to the sums keep the
 * cost down where double is software (a division costs ~700 instructions on
 * a Cortex-M3); the result differs from the term-by-term form by rounding only.
 */
void vessel_tau_crossflow(const vessel_model *m, const double x[VESSEL_NSTATES],
                          double tau[6]) {
    const vessel_params *pa = &m->params;
    const double v = x[VESSEL_V_MPS], w = x[VESSEL_W_MPS];
    const double q = x[VESSEL_Q_RADPS], r = x[VESSEL_R_RADPS];
    const double dx = pa->length_m / 10.0;
    const double ky = pa->cdy * pa->hx_m;
    const double kz = pa->cdz * pa->bx_m;
    double cy = 0.0, cz = 0.0, cm = 0.0, cn = 0.0;

    for (int k = 0; k < 11; k++) {
        const double xk = m->station_m[k];
        const double vk = v + xk * r;
        const double wk = w - xk * q;
        const double uk = math_sqrt_f64(vk * vk + wk * wk) + 1e-6;
        const double f = (ky * vk * vk + kz * wk * wk) / uk;
        cy += f * vk;
        cz += f * wk;
        cm += f * (w + xk * q) * xk;
        cn += f * vk * xk;
    }
    const double half_rho = 0.5 * pa->rho_kgpm3 * dx;
    tau[1] -= half_rho * cy;
    tau[2] -= half_rho * cz;
    tau[4] -= half_rho * cm;
    tau[5] -= half_rho * cn;
}
