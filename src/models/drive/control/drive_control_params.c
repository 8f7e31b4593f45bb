/*
 * Default parameters of the drive controller: the 15 kW machine of
 * induction_motor_params.c (its star-equivalent constants are repeated here
 * because a static initialiser cannot read another object; the unit test
 * checks that they agree), with the propeller load. docs/drive_control.md
 * shows how each gain and limit was chosen.
 */
#include "models/drive/control/drive_control.h"

const drive_control_params drive_control_params_default = {
    .step_s = 800e-6,
    .pwm_step_s = 2e-6,
    .pole_pairs = 2u,
    .rs_ohm = 0.2147 / 3.0,
    .rr_ohm = 0.2205 / 3.0,
    .lls_h = (0.065181 - 0.06419) / 3.0,
    .llr_h = (0.065181 - 0.06419) / 3.0,
    .lm_h = 0.06419 / 3.0,
    /* 26 A gives psi_r = 0.556 Wb, 94 % of the flux of the rated 230 V, 50 Hz
     * supply: the 1500 rpm load point then needs m = 0.85 at the 432 V
     * cut-off bus, leaving room for the filter drop. */
    .i_mag_a = 26.0,
    /* 64 A peak is 1.3 times the 1500 rpm load current (44 A) and allows
     * the 1.2 Hz slip limit: 95 N m, 1.6 times the propeller torque. */
    .i_max_a = 64.0,
    .slip_max_hz = 1.2,
    .freq_max_hz = 80.0,
    .speed_max_radps = 180.0,
    .accel_max_radps2 = 200.0,
    .idle_speed_radps = 5.0,
    /* Speed loop crossover 28 rad/s with J = 0.113 kg m^2 and 79.4 N m per
     * slip hertz; the PI zero an eighth of it (3.6 rad/s). The controller's
     * result acts one control frame after its inputs (it runs as its own
     * task), about 1 ms of delay in all: the margin it leaves keeps the
     * start from rest at 2 % overshoot (a crossover of 20 rad/s with the
     * zero at 5 rad/s gave 6 % with that delay). */
    .kp_speed_hz_per_radps = 0.04,
    .ki_speed_hz_per_rad = 0.1424,
    /* Current loop: half of the gains at which a current-demand step on the
     * machine starts to overshoot (Kp 0.6 V/A, Ki 60 V/(A s): at most 2.2 %
     * from 0.5 Hz to 70 Hz; twice those give 20 to 38 %). */
    .kp_current_v_per_a = 0.3,
    .ki_current_v_per_as = 30.0,
    .ff_gain = 1.0,
    .m_max = 1.0,
    .vdc_min_v = 100.0,
};
