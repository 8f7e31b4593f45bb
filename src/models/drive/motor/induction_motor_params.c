/*
 * Published induction-machine parameter sets (motor section of docs/drive.md).
 *
 * Source of both sets: the squirrel-cage presets of the MathWorks Simscape
 * Electrical (Specialized Power Systems) "Asynchronous Machine" block, as
 * transcribed in the Modelica Buildings Library (Lawrence Berkeley National
 * Laboratory), records
 *   Buildings/Electrical/AC/ThreePhasesBalanced/Loads/MotorDrive/
 *   InductionMotors/Data/IM_20HP_400V_50Hz.mo and IM_5HP_400V_50Hz.mo
 * (4 poles, 50 Hz, 400 V, star-equivalent values per phase). Those records
 * give the self inductances Ls = Lr and the mutual inductance Lm; the
 * leakages below are Ls - Lm and Lr - Lm.
 *
 * The drive's machine is the 20 hp (15 kW) set. Its 400 V rating is for the
 * star connection, but the DC bus gives at most about 0.612 * 0.95 * 432 V =
 * 251 V line to line at battery cut-off. A 400 V star / 230 V delta machine
 * reconnected in delta keeps each winding at its rated voltage from a
 * 400 / sqrt(3) = 230.9 V supply; the star equivalent of the delta then has
 * one third of the winding impedances. Torque, speed, power and inertia are
 * unchanged; line currents are sqrt(3) times the star values.
 */
#include "models/drive/motor/induction_motor.h"

/* 20 hp preset: Rs = 0.2147 ohm, Rr = 0.2205 ohm, Ls = Lr = 0.065181 H, Lm = 0.06419 H. */
const induction_motor_params induction_motor_params_15kw_delta = {
    .rs_ohm = 0.2147 / 3.0,
    .rr_ohm = 0.2205 / 3.0,
    .lls_h = (0.065181 - 0.06419) / 3.0,
    .llr_h = (0.065181 - 0.06419) / 3.0,
    .lm_h = 0.06419 / 3.0,
    .pole_pairs = 2u,
    .j_rotor_kgm2 = 0.102,
    .v_ll_rated_v = 230.94010767585030, /* 400 / sqrt(3) */
    .f_rated_hz = 50.0,
};

/* 5 hp preset: Rs = 1.405 ohm, Rr = 1.395 ohm, Ls = Lr = 0.178039 H, Lm = 0.1722 H. */
const induction_motor_params induction_motor_params_4kw_star = {
    .rs_ohm = 1.405,
    .rr_ohm = 1.395,
    .lls_h = 0.178039 - 0.1722,
    .llr_h = 0.178039 - 0.1722,
    .lm_h = 0.1722,
    .pole_pairs = 2u,
    .j_rotor_kgm2 = 0.0131,
    .v_ll_rated_v = 400.0,
    .f_rated_hz = 50.0,
};
