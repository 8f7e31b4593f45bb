/*
 * The vessel model's entry points: configuration, the assembled right-hand
 * side nu_dot = M^-1 tau, eta_dot = J(eta) nu, and the classical RK4 frame.
 */
#include "models/vessel/vessel.h"

#include <stddef.h>

#include "math/umath.h"
#include "models/vessel/vessel_internal.h"

const char *const vessel_state_names[VESSEL_NSTATES] = {
    "u_mps",       "v_mps",       "w_mps",        "p_radps",      "q_radps",   "r_radps",
    "x_m",         "y_m",         "z_m",          "phi_rad",      "theta_rad", "psi_rad",
    "delta_r_rad", "delta_s_rad", "delta_bp_rad", "delta_bs_rad", "n_rpm",
};

void vessel_config_default(vessel_config *cfg) {
    cfg->params = &vessel_params_npsauv2;
    cfg->propeller = &propeller_params_default;
    cfg->propulsion = VESSEL_PROP_PAPER;
    cfg->shaft = VESSEL_SHAFT_LAG;
    cfg->free_surface = true;
    cfg->step_s = 0.1;
}

/*
 * The physical fields must lie in their ranges. The many hydrodynamic
 * coefficients are checked for finiteness by vessel_probe during init.
 */
static bool vessel_params_valid(const vessel_params *p) {
    const double lims[3] = {p->fin_limit_rad, p->shaft_limit_rpm, p->actuator_tau_s};
    bool ok = (p->length_m > 0.0) && (p->gravity_mps2 > 0.0) && (p->rho_kgpm3 > 0.0) &&
              (p->weight_n > 0.0) && (p->buoyancy_n > 0.0) && (p->ix_kgm2 > 0.0) &&
              (p->iy_kgm2 > 0.0) && (p->iz_kgm2 > 0.0) && (p->cdy >= 0.0) && (p->cdz >= 0.0) &&
              (p->hx_m >= 0.0) && (p->bx_m >= 0.0) && (p->hull_radius_m > 0.0) &&
              (p->cd0 >= 0.0);
    for (int i = 0; i < 3; i++) {
        ok = ok && (lims[i] > 0.0) && math_isfinite_f64(lims[i]);
    }
    return ok;
}

/*
 * Evaluates the model once at an ordinary state. A NaN or infinite
 * coefficient anywhere makes some derivative non-finite (even a term
 * multiplied by zero), so this finds every one of them.
 */
static bool vessel_probe(const vessel_model *m) {
    static const double x0[VESSEL_NSTATES] = {1.0, 0.1, 0.1, 0.01, 0.01, 0.01, 0.0, 0.0, 1.0,
                                              0.1, 0.1, 0.1, 0.1,  0.1,  0.1,  0.1, 500.0};
    const vessel_cmd cmd = {0.0, 0.0, 0.0, 0.0, 500.0, 500.0, 0.0, 0.0};
    double dx[VESSEL_NSTATES];
    (void)vessel_derivatives(m, x0, &cmd, dx);
    bool ok = true;
    for (int i = 0; i < VESSEL_NSTATES; i++) {
        ok = ok && math_isfinite_f64(dx[i]);
    }
    return ok;
}

static bool vessel_config_valid(const vessel_config *cfg) {
    return ((cfg->propulsion == VESSEL_PROP_MSS) || (cfg->propulsion == VESSEL_PROP_PAPER)) &&
           ((cfg->shaft == VESSEL_SHAFT_LAG) || (cfg->shaft == VESSEL_SHAFT_INPUT)) &&
           (cfg->step_s > 0.0) && (cfg->step_s <= 1.0);
}

/* The prime-system scale factors, the strip stations and the wash constants. */
static void vessel_derive(vessel_model *m) {
    const vessel_params *p = &m->params;
    const double len = p->length_m;
    m->mass_kg = p->weight_n / p->gravity_mps2;
    m->r2 = 0.5 * p->rho_kgpm3 * len * len;
    m->r3 = m->r2 * len;
    m->r4 = m->r3 * len;
    m->r5 = m->r4 * len;
    m->m_prime = m->mass_kg / m->r3;
    for (int k = 0; k < 11; k++) {
        m->station_m[k] = -0.5 * len + (double)k * (len / 10.0);
    }
    /* C_t = 0.008 L^2 / 2 * eta|eta|; C_t1 is its value at eta|eta| = 1. */
    m->ct_scale = 0.008 * len * len / 2.0;
    m->eps_den = math_sqrt_f64(m->ct_scale + 1.0) - 1.0 + 1e-10;
    m->actuator_rate_hz = 1.0 / p->actuator_tau_s;
    /* ceil(step_s / VESSEL_RK4_MAX_S); the 1e-6 keeps a frame of 0.1 s or
     * 0.2 s (in binary slightly more) one or two steps. step_s <= 1. */
    const double steps = m->step_s / VESSEL_RK4_MAX_S - 1e-6;
    m->substeps = (uint32_t)steps + 1u;
    m->sub_s = m->step_s / (double)m->substeps;
}

vessel_status vessel_init(vessel_model *m, const vessel_config *cfg) {
    if ((m == NULL) || (cfg == NULL)) {
        return VESSEL_ERR_NULL;
    }
    const vessel_params *p = (cfg->params != NULL) ? cfg->params : &vessel_params_npsauv2;
    const propeller_params *pp =
        (cfg->propeller != NULL) ? cfg->propeller : &propeller_params_default;
    if (!vessel_config_valid(cfg) || !vessel_params_valid(p)) {
        return VESSEL_ERR_PARAM;
    }
    /* Built in place: the instance is large for a small stack (see vessel.h). */
    if (propeller_init(&m->prop, pp) != PROPELLER_OK) {
        return VESSEL_ERR_PARAM;
    }
    m->params = *p;
    m->propulsion = cfg->propulsion;
    m->shaft = cfg->shaft;
    m->free_surface = cfg->free_surface;
    m->step_s = cfg->step_s;
    vessel_derive(m);
    if (!vessel_mass_build(m)) {
        return VESSEL_ERR_MASS_MATRIX;
    }
    if (!vessel_probe(m)) {
        return VESSEL_ERR_PARAM;
    }
    vessel_reset_counters(m);
    return VESSEL_OK;
}

void vessel_reset_counters(vessel_model *m) {
    for (int i = 0; i < (int)VESSEL_EVENT_COUNT; i++) {
        m->event_steps[i] = 0u;
    }
}

unsigned vessel_derivatives(const vessel_model *m, const double x[VESSEL_NSTATES],
                            const vessel_cmd *cmd, double dx[VESSEL_NSTATES]) {
    vessel_actuation act;
    vessel_trig trig;
    double tau[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
    unsigned ev = vessel_actuators(m, x, cmd, &act, &dx[VESSEL_DELTA_R_RAD]);
    ev |= vessel_trig_eval(x, &trig);

    vessel_tau_hydro(m, x, tau);
    vessel_tau_crossflow(m, x, tau);
    ev |= vessel_tau_control(m, x, &act, tau);
    vessel_tau_restoring(m, &trig, x, cmd->delta_b_n, tau);

    for (int i = 0; i < 6; i++) {
        double s = 0.0;
        for (int j = 0; j < 6; j++) {
            s += m->mass_inverse[i][j] * tau[j];
        }
        dx[VESSEL_U_MPS + i] = s;
    }
    vessel_kinematics(&trig, x, &dx[VESSEL_X_M]);
    return ev;
}

/* Counts each event once per step, saturating at the counter's range. */
static void vessel_count(vessel_model *m, unsigned ev) {
    for (int i = 0; i < (int)VESSEL_EVENT_COUNT; i++) {
        if (((ev & VESSEL_FLAG(i)) != 0u) && (m->event_steps[i] != UINT32_MAX)) {
            m->event_steps[i]++;
        }
    }
}

/* One classical RK4 step of length h. */
static unsigned vessel_rk4(const vessel_model *m, double x[VESSEL_NSTATES], const vessel_cmd *cmd,
                           double h) {
    double k1[VESSEL_NSTATES], k2[VESSEL_NSTATES], k3[VESSEL_NSTATES], k4[VESSEL_NSTATES];
    double xt[VESSEL_NSTATES];
    unsigned ev = vessel_derivatives(m, x, cmd, k1);
    for (int i = 0; i < VESSEL_NSTATES; i++) {
        xt[i] = x[i] + h / 2.0 * k1[i];
    }
    ev |= vessel_derivatives(m, xt, cmd, k2);
    for (int i = 0; i < VESSEL_NSTATES; i++) {
        xt[i] = x[i] + h / 2.0 * k2[i];
    }
    ev |= vessel_derivatives(m, xt, cmd, k3);
    for (int i = 0; i < VESSEL_NSTATES; i++) {
        xt[i] = x[i] + h * k3[i];
    }
    ev |= vessel_derivatives(m, xt, cmd, k4);
    for (int i = 0; i < VESSEL_NSTATES; i++) {
        x[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
    }
    return ev;
}

unsigned vessel_step(vessel_model *m, double x[VESSEL_NSTATES], const vessel_cmd *cmd) {
    unsigned ev = 0u;
    if (m->shaft == VESSEL_SHAFT_INPUT) {
        x[VESSEL_N_RPM] = cmd->shaft_rpm;
    }
    for (uint32_t k = 0u; k < m->substeps; k++) {
        ev |= vessel_rk4(m, x, cmd, m->sub_s);
    }
    vessel_count(m, ev);
    return ev;
}

double vessel_thrust_n(const vessel_model *m, const double x[VESSEL_NSTATES]) {
    vessel_prop_terms pt;
    (void)vessel_propulsion_eval(m, x[VESSEL_U_MPS], vessel_shaft_radps(m, x), &pt);
    return pt.thrust_n;
}
