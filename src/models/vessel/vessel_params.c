/*
 * The NPS AUV II parameter set. The numbers are those of Healey and Lienard
 * (1993) as Fossen's MSS toolbox (npsauv.m) uses them, with rho = 1025 kg/m^3
 * and g = 9.81 m/s^2; docs/vessel.md lists them with their sources.
 */
#include "models/vessel/vessel_params.h"

#include "math/umath.h"

const vessel_params vessel_params_npsauv2 = {
    .length_m = 5.3,
    .gravity_mps2 = 9.81,
    .rho_kgpm3 = 1025.0,
    .weight_n = 53400.0,
    .buoyancy_n = 53400.0,
    .r_g_m = {0.0, 0.0, 0.061},
    .r_b_m = {0.0, 0.0, 0.0},
    .ix_kgm2 = 2038.0,
    .iy_kgm2 = 13587.0,
    .iz_kgm2 = 13587.0,
    .ixy_kgm2 = -13.58,
    .iyz_kgm2 = -13.58,
    .ixz_kgm2 = -13.58,
    .cdy = 0.5,
    .cdz = 0.6,
    .hx_m = 0.53,
    .bx_m = 0.53,
    .hull_radius_m = 0.265,
    .cd0 = 0.00385,
    .fin_limit_rad = 20.0 * MATH_DEG_TO_RAD_F64,
    .shaft_limit_rpm = 1500.0,
    .actuator_tau_s = 0.1,
    .x = {.pp = 7.0e-3, .qq = -1.5e-2, .rr = 4.0e-3, .pr = 7.5e-4, .udot = -7.6e-3,
          .wq = -2.0e-1, .vp = -3.0e-3, .vr = 2.0e-2, .q_ds = 2.5e-2, .q_db2 = -1.3e-3,
          .r_dr = -1.0e-3, .vv = 5.3e-2, .ww = 1.7e-1, .v_dr = 1.7e-3, .w_ds = 4.6e-2,
          .w_db2 = 0.5e-2, .ds_ds = -1.0e-2, .dr_dr = -1.0e-2, .q_ds_n = 2.0e-3,
          .w_ds_n = 3.5e-3, .ds_ds_n = -1.6e-3},
    .y = {.pdot = 1.2e-4, .rdot = 1.2e-3, .pq = 4.0e-3, .qr = -6.5e-3, .vdot = -5.5e-2,
          .p = 3.0e-3, .r = 3.0e-2, .vq = 2.4e-2, .wp = 2.3e-1, .wr = -1.9e-2, .v = -1.0e-1,
          .vw = 6.8e-2, .dr = 2.7e-2},
    .z = {.qdot = -6.8e-3, .pp = 1.3e-4, .pr = 6.7e-3, .rr = -7.4e-3, .wdot = -2.4e-1,
          .q = -1.4e-1, .vp = -4.8e-2, .vr = 4.5e-2, .w = -3.0e-1, .vv = -6.8e-2,
          .ds = -7.3e-2, .db2 = -1.3e-2, .q_n = -2.9e-3, .w_n = -5.1e-3, .ds_n = -1.0e-2},
    .k = {.pdot = -1.0e-3, .rdot = -3.4e-5, .pq = -6.9e-5, .qr = 1.7e-2, .vdot = 1.2e-4,
          .p = -1.1e-2, .r = -8.4e-4, .vq = -5.1e-3, .wp = -1.3e-4, .wr = 1.4e-2, .v = 3.1e-3,
          .vw = -1.9e-1, .db2 = 0.0, .p_n = -5.7e-4, .prop = 0.0},
    .m = {.qdot = -1.7e-2, .pp = 5.3e-5, .pr = 5.0e-3, .rr = 2.9e-3, .wdot = -6.8e-3,
          .uq = -6.8e-2, .vp = 1.2e-3, .vr = 1.7e-2, .uw = 1.0e-1, .vv = -2.6e-2,
          .ds = -4.1e-2, .db2 = 3.5e-3, .q_n = -1.6e-3, .w_n = -2.9e-3, .ds_n = -5.2e-3},
    .n = {.pdot = -3.4e-5, .rdot = -3.4e-3, .pq = -2.1e-2, .qr = 2.7e-3, .vdot = 1.2e-3,
          .p = -8.4e-4, .r = -1.6e-2, .vq = -1.0e-2, .wp = -1.7e-2, .wr = 7.4e-3,
          .v = -7.4e-3, .vw = -2.7e-2, .dr = -1.3e-2, .prop = 0.0},
};
