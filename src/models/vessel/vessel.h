/*
 * The vessel: the 6-DOF NPS AUV II with rudder, stern plane, port and
 * starboard bow planes, propeller and buoyancy adjustment, integrated with
 * classical fourth-order Runge-Kutta at the slow frame (docs/vessel.md).
 *
 * The model follows the project's reference description of Fossen's MSS
 * npsauv model, with its heave Coriolis and pitch gyroscopic signs
 * corrected, general restoring forces for W != B, and a choice of two
 * propulsion laws. Everything is double precision and uses only the
 * project's own math functions, so the host and the targets compute the
 * same bits. There are no ocean currents: the velocities relative to the
 * water are the body velocities (u_r = u, v_r = v, w_r = w).
 *
 * The caller owns the state vector (17 doubles, in the order of
 * vessel_state_index); the model instance holds the parameters, the
 * factorised mass matrix and counters of the guards that acted.
 */
#ifndef UUV_VESSEL_H
#define UUV_VESSEL_H

#include <stdbool.h>
#include <stdint.h>

#include "models/propeller/propeller.h"
#include "models/vessel/vessel_params.h"

/* Indices of the state vector (the reference order of the MSS model). */
typedef enum {
    VESSEL_U_MPS = 0,     /* [m/s] surge velocity, BODY */
    VESSEL_V_MPS,         /* [m/s] sway velocity, BODY */
    VESSEL_W_MPS,         /* [m/s] heave velocity, BODY */
    VESSEL_P_RADPS,       /* [rad/s] roll rate */
    VESSEL_Q_RADPS,       /* [rad/s] pitch rate */
    VESSEL_R_RADPS,       /* [rad/s] yaw rate */
    VESSEL_X_M,           /* [m] North */
    VESSEL_Y_M,           /* [m] East */
    VESSEL_Z_M,           /* [m] Down (depth) */
    VESSEL_PHI_RAD,       /* [rad] roll angle (zyx Euler) */
    VESSEL_THETA_RAD,     /* [rad] pitch angle */
    VESSEL_PSI_RAD,       /* [rad] yaw angle */
    VESSEL_DELTA_R_RAD,   /* [rad] rudder, actual (positive turns to port) */
    VESSEL_DELTA_S_RAD,   /* [rad] stern plane, actual (positive dives) */
    VESSEL_DELTA_BP_RAD,  /* [rad] port bow plane, actual */
    VESSEL_DELTA_BS_RAD,  /* [rad] starboard bow plane, actual */
    VESSEL_N_RPM,         /* [rpm] propeller shaft speed */
    VESSEL_NSTATES
} vessel_state_index;

/* Names of the states, as the reference CSV files head their columns. */
extern const char *const vessel_state_names[VESSEL_NSTATES];

/* Propulsion law (the surge force of the propeller and the hull drag). */
typedef enum {
    VESSEL_PROP_MSS = 0,  /* the MSS model's own law, used to match its vectors */
    VESSEL_PROP_PAPER     /* the seed paper's bilinear thruster (the simulator's default) */
} vessel_propulsion;

/* Where the shaft speed (state VESSEL_N_RPM) comes from. */
typedef enum {
    VESSEL_SHAFT_LAG = 0, /* follows cmd.n_rpm through the 0.1 s actuator lag, clamped */
    VESSEL_SHAFT_INPUT    /* set to cmd.shaft_rpm at each step (the motor's speed) */
} vessel_shaft_source;

/* Guards and limits that can act during an evaluation (bit i of the flags). */
typedef enum {
    VESSEL_EVENT_ETA_POLE = 0, /* |u + 1e-10| < 1e-10: the advance-ratio pole was avoided */
    VESSEL_EVENT_EPS_SQRT,     /* C_t + 1 < 0: the wash factor took its real part */
    VESSEL_EVENT_PITCH_90,     /* |cos(theta)| < 1e-12: the Euler singularity was avoided */
    VESSEL_EVENT_ACTUATOR_LIMIT, /* an actuator value was clamped to its limit */
    VESSEL_EVENT_COUNT
} vessel_event;

typedef struct {
    const vessel_params *params;       /* NULL selects vessel_params_npsauv2 */
    const propeller_params *propeller; /* NULL selects propeller_params_default */
    vessel_propulsion propulsion;
    vessel_shaft_source shaft;
    bool free_surface;                 /* buoyancy of the submerged hull only (docs/vessel.md);
                                        * false: deep water, the reference model */
    double step_s;                     /* [s] RK4 frame, in (0, 1] */
} vessel_config;

/* Inputs, held constant over a step. */
typedef struct {
    double rudder_rad;   /* [rad] rudder command */
    double stern_rad;    /* [rad] stern plane command */
    double bow_port_rad; /* [rad] port bow plane command */
    double bow_stbd_rad; /* [rad] starboard bow plane command */
    double n_rpm;        /* [rpm] shaft speed command (VESSEL_SHAFT_LAG) */
    double shaft_rpm;    /* [rpm] measured shaft speed at the step start (VESSEL_SHAFT_INPUT) */
    double delta_b_n;    /* [N] buoyancy change: B = B_nominal + delta_b_n, > 0 rises */
    double shaft_rate_rpmps; /* [rpm/s] its rate over the step (VESSEL_SHAFT_INPUT; 0 holds it) */
} vessel_cmd;

typedef struct {
    vessel_params params;
    propeller_model prop;
    vessel_propulsion propulsion;
    vessel_shaft_source shaft;
    bool free_surface;         /* see vessel_config */
    double step_s;             /* [s] */
    double sub_s;              /* [s] RK4 step: step_s / substeps, at most VESSEL_RK4_MAX_S */
    uint32_t substeps;         /* RK4 steps per frame */
    double mass_kg;            /* [kg] W / g */
    double r2, r3, r4, r5;     /* 0.5*rho*L^k, the prime-system scale factors (SI) */
    double m_prime;            /* [-] mass / r3 */
    double mass_matrix[6][6];  /* M = M_RB + M_A (SI) */
    double mass_inverse[6][6]; /* M^-1, computed at init */
    double station_m[11];      /* [m] strip-theory stations along the hull */
    double ct_scale;           /* [-] 0.008*L^2/2 */
    double eps_den;            /* [-] sqrt(ct_scale + 1) - 1 + 1e-10 */
    double actuator_rate_hz;   /* [1/s] 1 / T_a */
    uint32_t event_steps[VESSEL_EVENT_COUNT]; /* steps in which each event occurred */
} vessel_model;

typedef enum {
    VESSEL_OK = 0,
    VESSEL_ERR_NULL,        /* a pointer argument was NULL */
    VESSEL_ERR_PARAM,       /* a parameter or option is out of range */
    VESSEL_ERR_MASS_MATRIX  /* the mass matrix is singular */
} vessel_status;

/* Default configuration: NPS AUV II, `paper` law, shaft through the lag, free surface, 0.1 s. */
void vessel_config_default(vessel_config *cfg);

/*
 * Checks the configuration, builds and inverts the mass matrix. The
 * instance (about 1.8 KB) is best given static storage. After an error
 * other than VESSEL_ERR_NULL the instance is not usable until a
 * successful init.
 */
vessel_status vessel_init(vessel_model *m, const vessel_config *cfg);

/* Clears the event counters. */
void vessel_reset_counters(vessel_model *m);

/*
 * The state derivative dx = f(x, cmd). Returns the events that occurred as
 * bit flags (1u << vessel_event). In VESSEL_SHAFT_INPUT mode the shaft
 * speed is x[VESSEL_N_RPM] as it stands and its derivative is
 * cmd->shaft_rate_rpmps.
 */
unsigned vessel_derivatives(const vessel_model *m, const double x[VESSEL_NSTATES],
                            const vessel_cmd *cmd, double dx[VESSEL_NSTATES]);

/*
 * The longest RK4 step [s]. Within the states the scenario accepts, the
 * explicit RK4 is stable at 0.1 s (docs/vessel.md, section 6), not at
 * 0.2 s: a longer frame is integrated in equal steps of at most this.
 */
#define VESSEL_RK4_MAX_S 0.1

/*
 * One frame of length step_s with the commands held: classical RK4 in
 * `substeps` equal steps (one when step_s <= VESSEL_RK4_MAX_S). In
 * VESSEL_SHAFT_INPUT mode x[VESSEL_N_RPM] is first set to cmd->shaft_rpm.
 * Counts the events; returns their flags.
 */
unsigned vessel_step(vessel_model *m, double x[VESSEL_NSTATES], const vessel_cmd *cmd);

/*
 * The propeller's surge force at state x [N] (without the hull drag):
 * r2*C_d0*u^2*eta*|eta| under `mss`, efficiency * T under `paper`. For
 * telemetry.
 */
double vessel_thrust_n(const vessel_model *m, const double x[VESSEL_NSTATES]);

/* The shaft speed the force model uses [rad/s] (clamped in VESSEL_SHAFT_LAG mode). */
double vessel_shaft_radps(const vessel_model *m, const double x[VESSEL_NSTATES]);

#endif /* UUV_VESSEL_H */
