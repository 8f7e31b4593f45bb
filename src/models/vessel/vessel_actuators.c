/*
 * The actuator lags of the vessel (states 13-17): one first-order lag of
 * time constant T_a for each of the four fins and the shaft speed,
 *
 *   da/dt = (command - sat(a)) / T_a,
 *
 * where sat clamps the state's value to the actuator's limit. The clamp acts
 * on the value only, as in the source: while a command lies beyond the
 * limit, the state keeps drifting at (command - limit) / T_a but the force
 * model sees the limit. That wind-up is part of the reference behaviour.
 *
 * With the shaft speed taken from the motor (VESSEL_SHAFT_INPUT) the shaft
 * is not an actuator of the vessel: its state is the measured speed, used
 * as it is (no clamp, the motor's speed is physical), and its derivative is
 * the rate the command gives (the motor's speed change over the frame, so
 * that the step sees the speed ramp linearly between the frame's ends).
 */
#include "math/umath.h"
#include "models/vessel/vessel_internal.h"

/* [rad/s] per [rpm]: 2 pi / 60. */
#define VESSEL_RADPS_PER_RPM (MATH_PI_F64 / 30.0)

/* Clamps a to [-limit, limit]; sets *hit when it had to. */
static double vessel_sat(double a, double limit, unsigned *hit) {
    if (a > limit) {
        *hit = 1u;
        return limit;
    }
    if (a < -limit) {
        *hit = 1u;
        return -limit;
    }
    return a;
}

double vessel_shaft_radps(const vessel_model *m, const double x[VESSEL_NSTATES]) {
    unsigned hit = 0u;
    double n = x[VESSEL_N_RPM];
    if (m->shaft == VESSEL_SHAFT_LAG) {
        n = vessel_sat(n, m->params.shaft_limit_rpm, &hit);
    }
    return n * VESSEL_RADPS_PER_RPM;
}

unsigned vessel_actuators(const vessel_model *m, const double x[VESSEL_NSTATES],
                          const vessel_cmd *cmd, vessel_actuation *a,
                          double dact[VESSEL_NSTATES - VESSEL_DELTA_R_RAD]) {
    const double lim = m->params.fin_limit_rad;
    const double rate = m->actuator_rate_hz; /* 1 / T_a, a multiplication is cheaper */
    unsigned hit = 0u;

    a->rudder_rad = vessel_sat(x[VESSEL_DELTA_R_RAD], lim, &hit);
    a->stern_rad = vessel_sat(x[VESSEL_DELTA_S_RAD], lim, &hit);
    a->bow_port_rad = vessel_sat(x[VESSEL_DELTA_BP_RAD], lim, &hit);
    a->bow_stbd_rad = vessel_sat(x[VESSEL_DELTA_BS_RAD], lim, &hit);
    dact[0] = (cmd->rudder_rad - a->rudder_rad) * rate;
    dact[1] = (cmd->stern_rad - a->stern_rad) * rate;
    dact[2] = (cmd->bow_port_rad - a->bow_port_rad) * rate;
    dact[3] = (cmd->bow_stbd_rad - a->bow_stbd_rad) * rate;

    if (m->shaft == VESSEL_SHAFT_LAG) {
        const double n = vessel_sat(x[VESSEL_N_RPM], m->params.shaft_limit_rpm, &hit);
        a->shaft_radps = n * VESSEL_RADPS_PER_RPM;
        dact[4] = (cmd->n_rpm - n) * rate;
    } else {
        a->shaft_radps = x[VESSEL_N_RPM] * VESSEL_RADPS_PER_RPM;
        dact[4] = cmd->shaft_rate_rpmps;
    }
    return (hit != 0u) ? VESSEL_FLAG(VESSEL_EVENT_ACTUATOR_LIMIT) : 0u;
}
