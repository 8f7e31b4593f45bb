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

/* Stations of the buoyancy integral: midpoints of equal slices of the hull. */
#define VESSEL_HS_STATIONS 10

/*
 * asin(a) for 0 <= a <= 1, given s1 = sqrt(1 - a): Abramowitz and Stegun
 * 4.4.46, pi/2 - s1 (a0 + a1 a + ... + a7 a^7), absolute error below
 * 2.2e-8 rad (a submerged fraction off by less than 7e-9). A polynomial
 * costs a tenth of the exact math_asin_f64 on a core without a double FPU.
 */
static double vessel_asin_pos(double a, double s1) {
    static const double c[8] = {1.5707963050,  -0.2145988016, 0.0889789874, -0.0501743046,
                                0.0308918810,  -0.0170881256, 0.0066700901, -0.0012624911};
    double p = c[7];
    for (int k = 6; k >= 0; k--) {
        p = p * a + c[k];
    }
    return 0.5 * MATH_PI_F64 - s1 * p;
}

/*
 * The buoyancy of the part of the hull under water, with the free surface at
 * z = 0. The hull is a cylinder of length L and radius R whose displacement
 * is B; it is cut into VESSEL_HS_STATIONS slices, each a circle centred on
 * the body x axis at x_k. The axis lies at depth z_k = z - x_k sin(theta)
 * and the section reaches R cos(theta) above and below it, so the water line
 * cuts it at t_k = z_k / (R cos(theta)) of the radius above the axis. The
 * submerged part of the circle is the fraction
 *   f(t) = 1/2 + (asin t + t sqrt(1 - t^2)) / pi      (1 for t >= 1, 0 for t <= -1)
 * (asin by vessel_asin_pos)
 * and its centroid lies s(t) = 2 R (1 - t^2)^(3/2) / (3 pi f) below the axis,
 * along the section's downward direction (0, sin(phi), cos(phi)) in BODY.
 * Returns false when every slice is under water: the caller then keeps B and
 * r_B as they are, so the deep-water model is reproduced bit for bit.
 * Otherwise writes the buoyancy *b and its moment arm products rb[i] = B r_B,i.
 */
static bool vessel_submerged(const vessel_model *m, const vessel_trig *t,
                             const double x[VESSEL_NSTATES], double *b, double rb[3]) {
    const vessel_params *pa = &m->params;
    const double len = pa->length_m;
    const double rc = pa->hull_radius_m * math_fabs_f64(t->cth);
    const double z = x[VESSEL_Z_M];
    const double end = 0.5 * len * (1.0 - 1.0 / (double)VESSEL_HS_STATIONS);
    if (!m->free_surface || ((z - end * t->sth >= rc) && (z + end * t->sth >= rc))) {
        return false;
    }
    double sf = 0.0, sfx = 0.0, sm = 0.0;
    for (int k = 0; k < VESSEL_HS_STATIONS; k++) {
        const double xk = len * (((double)k + 0.5) / (double)VESSEL_HS_STATIONS - 0.5);
        const double zk = z - xk * t->sth;
        double f = (zk > 0.0) ? 1.0 : 0.0;
        if ((zk < rc) && (zk > -rc)) {
            const double tk = zk / rc;
            const double ta = math_fabs_f64(tk);
            const double s1 = math_sqrt_f64(1.0 - ta);
            const double c = s1 * math_sqrt_f64(1.0 + ta);
            f = 0.5 + (math_copysign_f64(vessel_asin_pos(ta, s1), tk) + tk * c) / MATH_PI_F64;
            sm += c * c * c;
        }
        sf += f;
        sfx += f * xk;
    }
    const double per = *b / (double)VESSEL_HS_STATIONS;
    const double arm = sm * (2.0 * pa->hull_radius_m / (3.0 * MATH_PI_F64));
    *b = per * sf;
    rb[0] = pa->r_b_m[0] * *b + per * sfx;
    rb[1] = pa->r_b_m[1] * *b + per * arm * t->sphi;
    rb[2] = pa->r_b_m[2] * *b + per * arm * t->cphi;
    return true;
}

/*
 * Restoring forces tau = -g(eta) for weight W at r_G and buoyancy B at r_B,
 * in the general form that holds for W != B. B is the nominal buoyancy plus
 * the command delta_B, which models a variable-displacement device: it
 * changes B only, not the mass. With z positive down, B > W gives a
 * negative heave force: the vehicle rises. Near the surface B and r_B are
 * those of the submerged part of the hull (vessel_submerged).
 */
void vessel_tau_restoring(const vessel_model *m, const vessel_trig *t,
                          const double x[VESSEL_NSTATES], double delta_b_n, double tau[6]) {
    const vessel_params *pa = &m->params;
    const double wt = pa->weight_n;
    double b = pa->buoyancy_n + delta_b_n;
    double rb[3] = {pa->r_b_m[0] * b, pa->r_b_m[1] * b, pa->r_b_m[2] * b};
    (void)vessel_submerged(m, t, x, &b, rb);
    const double wb = wt - b;
    const double mx = pa->r_g_m[0] * wt - rb[0];
    const double my = pa->r_g_m[1] * wt - rb[1];
    const double mz = pa->r_g_m[2] * wt - rb[2];
    const double sf = t->sphi, cf = t->cphi, st = t->sth, ct = t->cth;

    tau[0] -= wb * st;
    tau[1] -= -wb * ct * sf;
    tau[2] -= -wb * ct * cf;
    tau[3] -= -my * ct * cf + mz * ct * sf;
    tau[4] -= mz * st + mx * ct * cf;
    tau[5] -= -mx * ct * sf - my * st;
}
