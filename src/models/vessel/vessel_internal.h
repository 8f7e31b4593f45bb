/*
 * The pieces of the vessel model's right-hand side, shared between its
 * source files and not part of its API. Each function adds its
 * contribution to the generalised force tau = (X, Y, Z, K, M, N) [N, N m]
 * or writes its part of the state derivative; docs/vessel.md gives the
 * equations.
 */
#ifndef UUV_VESSEL_INTERNAL_H
#define UUV_VESSEL_INTERNAL_H

#include <stdbool.h>

#include "models/vessel/vessel.h"

/* Event flag of one vessel_event. */
#define VESSEL_FLAG(e) (1u << (unsigned)(e))

/* Sines and cosines of the Euler angles, computed once per evaluation. */
typedef struct {
    double sphi, cphi;
    double sth, cth;
    double spsi, cpsi;
    double inv_cth;  /* 1 / cos(theta), with |cos(theta)| kept at least 1e-12 */
    double tth;      /* tan(theta) = sin(theta) * inv_cth */
} vessel_trig;

/* Clamped actuator values the force model uses. */
typedef struct {
    double rudder_rad;
    double stern_rad;
    double bow_port_rad;
    double bow_stbd_rad;
    double shaft_radps; /* [rad/s] */
} vessel_actuation;

/* Actuator lags (states 13-17): writes their derivatives and the clamped values. */
unsigned vessel_actuators(const vessel_model *m, const double x[VESSEL_NSTATES],
                          const vessel_cmd *cmd, vessel_actuation *a,
                          double dact[VESSEL_NSTATES - VESSEL_DELTA_R_RAD]);

/* Trigonometric functions of the Euler angles, with the pitch singularity guarded. */
unsigned vessel_trig_eval(const double x[VESSEL_NSTATES], vessel_trig *t);

/* Kinematics: deta = J(eta) * nu (states 7-12). */
void vessel_kinematics(const vessel_trig *t, const double x[VESSEL_NSTATES], double deta[6]);

/*
 * Adds the restoring forces -g(eta) for weight W and buoyancy B + delta_b_n,
 * with the free surface: of the part of the hull under water (x: the state).
 */
void vessel_tau_restoring(const vessel_model *m, const vessel_trig *t,
                          const double x[VESSEL_NSTATES], double delta_b_n, double tau[6]);

/* Adds the hydrodynamic damping and the rigid-body Coriolis and centripetal terms. */
void vessel_tau_hydro(const vessel_model *m, const double x[VESSEL_NSTATES], double tau[6]);

/* Adds the strip-theory cross-flow drag. */
void vessel_tau_crossflow(const vessel_model *m, const double x[VESSEL_NSTATES], double tau[6]);

/* Adds the control-surface, propeller-wash and propulsion forces. */
unsigned vessel_tau_control(const vessel_model *m, const double x[VESSEL_NSTATES],
                            const vessel_actuation *a, double tau[6]);

/*
 * The propulsion terms at surge speed u [m/s] and shaft speed w [rad/s]:
 * the wash factor epsilon and the surge force including the hull drag [N].
 */
typedef struct {
    double eps;       /* [-] propeller-wash factor of the "n" terms */
    double thrust_n;  /* [N] propeller force (without the hull drag) */
    double surge_n;   /* [N] propeller force plus hull drag */
} vessel_prop_terms;

unsigned vessel_propulsion_eval(const vessel_model *m, double u_mps, double w_radps,
                                vessel_prop_terms *pt);

/* Builds M = M_RB + M_A and its inverse; false when M is singular. */
bool vessel_mass_build(vessel_model *m);

#endif /* UUV_VESSEL_INTERNAL_H */
