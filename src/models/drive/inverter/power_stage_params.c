/*
 * Parameters of the drive's power stage (declared in power_stage.h). The
 * sizing rules and their sources are in docs/drive_power.md ("Parameters");
 * in short:
 *   - C_dc = 470 uF: the battery pack's resistance (about 0.6 ohm, 144s2p,
 *     battery_params.c) and C_dc put the bus corner at 1/(2 pi R C) = 0.55 kHz,
 *     well below the 5 kHz carrier, so the capacitor carries the switching
 *     ripple; measured bus ripple 2 V peak-to-peak at 9.25 kW (0.35 %).
 *   - L = 1 mH, R_L = 25 mohm: ripple current about v_dc / (8 L f_c) = 15 A
 *     peak-to-peak, a third of the rated peak current; reactance 0.33 ohm at
 *     52 Hz (7 % of the motor's rated impedance).
 *   - C = 22 uF: with L an undamped corner of 1.07 kHz, twenty times the
 *     highest fundamental and a fifth of the carrier.
 *   - R_d = 8.2 ohm in series with C_d = 47 uF across C: the parallel R-C
 *     damping of Erickson and Maksimovic (Fundamentals of Power Electronics,
 *     2nd ed., ch. 10, section 10.4, "R_f-C_b parallel damping") with
 *     n = C_d / C = 2.1 and R_d near its optimum, which limits the resonant
 *     peak of the voltage transfer to 1.92 at 754 Hz (Q about 2) while
 *     keeping the high-frequency roll-off of C (|H| = 0.047 at 5 kHz).
 */
#include "models/drive/inverter/power_stage.h"

const power_stage_params power_stage_params_default = {
    .c_dc_f = 470.0e-6,
    .l_h = 1.0e-3,
    .r_l_ohm = 0.025,
    .c_f = 22.0e-6,
    .r_d_ohm = 8.2,
    .c_d_f = 47.0e-6,
};
