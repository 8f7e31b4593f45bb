/*
 * The compiled-in parameter set (params.h): each model's default struct.
 */
#include "params.h"

const uuv_params uuv_params_default = {
    .vessel = &vessel_params_npsauv2,
    .autopilot = &autopilot_params_default,
    .propeller = &propeller_params_default,
    .battery = &battery_params_uuv,
    .stage = &power_stage_params_default,
    .pwm = &pwm_params_default,
    .motor = &induction_motor_params_15kw_delta,
    .control = &drive_control_params_default,
};
