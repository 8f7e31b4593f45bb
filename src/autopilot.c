/*
 * Heading and depth autopilots (see autopilot.h).
 */
#include "autopilot.h"

#include "math/umath.h"

#define AP_DEG (MATH_PI_F64 / 180.0)

const autopilot_params autopilot_params_default = {
    .heading_kp = 1.0,
    .heading_kd_s = 4.0,
    .depth_kp = 0.08,
    .depth_ki = 0.005,
    .depth_band_m = 1.0,
    .pitch_max_rad = 20.0 * AP_DEG,
    .pitch_kp = 3.0,
    .pitch_kd_s = 3.0,
    .fin_limit_rad = 20.0 * AP_DEG,
    .fin_rate_radps = 15.0 * AP_DEG,
};

void autopilot_init(autopilot *a) {
    *a = (autopilot){0};
    a->p = autopilot_params_default;
}

void autopilot_set_heading(autopilot *a, double psi_ref_rad) {
    a->heading_on = true;
    a->heading_ref_rad = psi_ref_rad;
}

void autopilot_set_depth(autopilot *a, double z_ref_m) {
    a->depth_on = true;
    a->depth_ref_m = z_ref_m;
    a->depth_int_ms = 0.0;
}

/* The fin command moved from *cmd towards want, within the rate and angle limits. */
static void fin_move(const autopilot_params *p, double want, double dt, double *cmd) {
    const double step = p->fin_rate_radps * dt;
    want = math_clamp_f64(want, *cmd - step, *cmd + step);
    *cmd = math_clamp_f64(want, -p->fin_limit_rad, p->fin_limit_rad);
}

void autopilot_step(autopilot *a, const double x[VESSEL_NSTATES], double dt, double *rudder,
                    double *stern) {
    const autopilot_params *p = &a->p;
    if (a->heading_on) {
        /* The error the short way round: psi is unwrapped (it counts turns). */
        const double d = a->heading_ref_rad - x[VESSEL_PSI_RAD];
        const double e = d - (2.0 * MATH_PI_F64) * math_round_f64(d / (2.0 * MATH_PI_F64));
        fin_move(p, -p->heading_kp * e + p->heading_kd_s * x[VESSEL_R_RADPS], dt, rudder);
    }
    if (a->depth_on) {
        const double e = a->depth_ref_m - x[VESSEL_Z_M];
        const double want = p->depth_kp * e + p->depth_ki * a->depth_int_ms;
        const double theta_ref = -math_clamp_f64(want, -p->pitch_max_rad, p->pitch_max_rad);
        if (e < p->depth_band_m && e > -p->depth_band_m) {
            a->depth_int_ms += e * dt;
        }
        const double d = p->pitch_kp * (x[VESSEL_THETA_RAD] - theta_ref) +
                         p->pitch_kd_s * x[VESSEL_Q_RADPS];
        fin_move(p, d, dt, stern);
    }
}
