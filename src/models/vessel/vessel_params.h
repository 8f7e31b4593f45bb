/*
 * Parameters of the 6-DOF vessel model: the NPS AUV II of Healey and Lienard
 * (1993) as Fossen's MSS toolbox gives it. Every value and its source is
 * listed in docs/vessel.md. The hydrodynamic derivatives are non-dimensional
 * ("prime system", scaled with the hull length L and the water density);
 * the other fields are in SI units, as their comments say.
 *
 * Subscript "b2" marks a coefficient applied to each of the two bow planes
 * (port and starboard) separately.
 */
#ifndef UUV_VESSEL_PARAMS_H
#define UUV_VESSEL_PARAMS_H

/* Surge (X) derivatives, prime system. */
typedef struct {
    double pp, qq, rr, pr, udot, wq, vp, vr;
    double q_ds, q_db2, r_dr, vv, ww, v_dr, w_ds, w_db2;
    double ds_ds, dr_dr, q_ds_n, w_ds_n, ds_ds_n;
} vessel_coeffs_x;

/* Sway (Y) derivatives, prime system. */
typedef struct {
    double pdot, rdot, pq, qr, vdot, p, r, vq, wp, wr, v, vw, dr;
} vessel_coeffs_y;

/* Heave (Z) derivatives, prime system. */
typedef struct {
    double qdot, pp, pr, rr, wdot, q, vp, vr, w, vv, ds, db2, q_n, w_n, ds_n;
} vessel_coeffs_z;

/* Roll (K) derivatives, prime system. */
typedef struct {
    double pdot, rdot, pq, qr, vdot, p, r, vq, wp, wr, v, vw, db2, p_n, prop;
} vessel_coeffs_k;

/* Pitch (M) derivatives, prime system. */
typedef struct {
    double qdot, pp, pr, rr, wdot, uq, vp, vr, uw, vv, ds, db2, q_n, w_n, ds_n;
} vessel_coeffs_m;

/* Yaw (N) derivatives, prime system. */
typedef struct {
    double pdot, rdot, pq, qr, vdot, p, r, vq, wp, wr, v, vw, dr, prop;
} vessel_coeffs_n;

typedef struct {
    double length_m;          /* [m] hull length L, also the prime-system length */
    double gravity_mps2;      /* [m/s^2] */
    double rho_kgpm3;         /* [kg/m^3] water density */
    double weight_n;          /* [N] W; the mass is W / g */
    double buoyancy_n;        /* [N] nominal B; the command delta_B adds to it */
    double r_g_m[3];          /* [m] centre of gravity (x, y, z) in BODY, origin at the CB */
    double r_b_m[3];          /* [m] centre of buoyancy (x, y, z) in BODY */
    double ix_kgm2;           /* [kg m^2] moments of inertia about the body axes */
    double iy_kgm2;
    double iz_kgm2;
    double ixy_kgm2;          /* [kg m^2] products of inertia, entered with a minus sign */
    double iyz_kgm2;
    double ixz_kgm2;
    double cdy;               /* [-] cross-flow drag coefficient, sway */
    double cdz;               /* [-] cross-flow drag coefficient, heave */
    double hx_m;              /* [m] average height of the hull sections */
    double bx_m;              /* [m] average width of the hull sections */
    double hull_radius_m;     /* [m] radius of the hull's circular sections (free surface) */
    double cd0;               /* [-] surge drag / propulsion coefficient */
    double fin_limit_rad;     /* [rad] clamp of the four fin deflections */
    double shaft_limit_rpm;   /* [rpm] clamp of the commanded shaft speed */
    double actuator_tau_s;    /* [s] time constant of the five actuator lags */
    vessel_coeffs_x x;
    vessel_coeffs_y y;
    vessel_coeffs_z z;
    vessel_coeffs_k k;
    vessel_coeffs_m m;
    vessel_coeffs_n n;
} vessel_params;

/* The NPS AUV II (rho = 1025 kg/m^3, neutrally buoyant, CG 61 mm below the CB). */
extern const vessel_params vessel_params_npsauv2;

#endif /* UUV_VESSEL_PARAMS_H */
