/*
 * Heading and depth autopilots (docs/vessel.md, section 10), run by the
 * scenario player once per reporting period (100 ms) on the vessel's state.
 *
 *   heading (rudder):       delta_r = -Kpsi e_psi + Kr r,  e_psi = psi_ref - psi wrapped to
 *                           [-pi, pi]  (a positive rudder turns to port)
 *   depth (stern plane):    theta_ref = -sat(Kz e_z + Ki integral(e_z), theta_max),
 *                           e_z = z_ref - z  (nose down to go deeper)
 *   pitch (inner loop):     delta_s = Ktheta (theta - theta_ref) + Kq q
 *                           (a positive stern plane pitches the nose down)
 *
 * Each fin command is limited in angle and in rate before it reaches the
 * fin's own 0.1 s lag. The depth error is integrated only near the
 * reference (within depth_band_m), so a long depth change winds nothing up.
 */
#ifndef UUV_AUTOPILOT_H
#define UUV_AUTOPILOT_H

#include <stdbool.h>

#include "models/vessel/vessel.h"

typedef struct {
    double heading_kp;      /* [rad/rad] rudder per heading error */
    double heading_kd_s;    /* [s] rudder per yaw rate [rad per rad/s] */
    double depth_kp;        /* [rad/m] pitch reference per depth error */
    double depth_ki;        /* [rad/(m s)] pitch reference per integrated depth error */
    double depth_band_m;    /* [m] the error is integrated only while within +-band */
    double pitch_max_rad;   /* [rad] limit of the pitch reference */
    double pitch_kp;        /* [rad/rad] stern plane per pitch error */
    double pitch_kd_s;      /* [s] stern plane per pitch rate [rad per rad/s] */
    double fin_limit_rad;   /* [rad] limit of the fin commands */
    double fin_rate_radps;  /* [rad/s] limit of their rate of change */
} autopilot_params;

/* The gains docs/vessel.md documents, with their overshoot and settling. */
extern const autopilot_params autopilot_params_default;

typedef struct {
    autopilot_params p;
    bool heading_on;
    bool depth_on;
    double heading_ref_rad; /* [rad] */
    double depth_ref_m;     /* [m] */
    double depth_int_ms;    /* [m s] integral of the depth error */
} autopilot;

/* Both axes off, with the default gains. */
void autopilot_init(autopilot *a);

/* Holds the heading psi_ref [rad] (any angle: the error is wrapped). */
void autopilot_set_heading(autopilot *a, double psi_ref_rad);

/* Holds the depth z_ref [m]; the integral restarts. */
void autopilot_set_depth(autopilot *a, double z_ref_m);

/*
 * One step of dt [s] at state x: for each axis that is on, moves *rudder
 * or *stern [rad] (the command in force) towards the control law's value,
 * within the rate and angle limits.
 */
void autopilot_step(autopilot *a, const double x[VESSEL_NSTATES], double dt, double *rudder,
                    double *stern);

#endif /* UUV_AUTOPILOT_H */
