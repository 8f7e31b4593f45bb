/*
 * Default parameters of the PWM modulator (declared in pwm.h). The 5 kHz
 * carrier is the paper's (section 2); docs/drive_power.md explains the edge
 * mode and the phase origins.
 */
#include "models/drive/pwm/pwm.h"

#define PWM_CARRIER_HZ 5000.0 /* [Hz] the paper's carrier, the drive's one home for it */

const pwm_params pwm_params_default = {
    .carrier_hz = PWM_CARRIER_HZ,
    .edges = PWM_EDGES_INTERPOLATED,
    .carrier_phase0 = 0u,
    .ref_phase0 = 0u,
    .dead_time_ns = 0u, /* the paper's ideal switches */
};

const pwm_params pwm_params_sampled = {
    .carrier_hz = PWM_CARRIER_HZ,
    .edges = PWM_EDGES_SAMPLED,
    .carrier_phase0 = 0u,
    .ref_phase0 = 0u,
    .dead_time_ns = 0u, /* the paper's ideal switches */
};
