/*
 * The propeller of the seed paper: a bilinear thruster for the surge force
 * and a rotating-disc drag torque for the load on the motor shaft.
 *
 *   thrust       T = Tnn*|w|*w + Tnu*|w|*u,  Tnn = rho*D^4*alpha1, Tnu = rho*D^3*alpha2
 *   surge force  X = efficiency * T
 *   load torque  T_load = -I0*dw/dt - 0.5*rho*C_D*w*|w|*R^3,  R = D/2
 *
 * w is the shaft speed in [rad/s], u the surge speed in [m/s]. The drag
 * term is written with w*|w| (not the paper's n^2) so that it opposes the
 * rotation in both directions. The inertia I0 is not part of the torque
 * functions: the motor model adds it to the rotor inertia, so the shaft
 * sees only the drag part each motor step. docs/vessel.md explains the
 * coefficients and how I0 was estimated.
 */
#ifndef UUV_PROPELLER_H
#define UUV_PROPELLER_H

typedef struct {
    double diameter_m;    /* [m] D */
    double alpha1;        /* [-] thrust coefficient of w*|w| (with w in rad/s) */
    double alpha2;        /* [-] thrust coefficient of |w|*u */
    double efficiency;    /* [-] surge force / ideal thrust */
    double rho_kgpm3;     /* [kg/m^3] water density */
    double drag_coeff;    /* [-] C_D of a disc rotating about its axis */
    double inertia_kgm2;  /* [kg m^2] I0, added to the motor's rotor inertia */
} propeller_params;

/* Coefficients derived once from the parameters, in the form each step uses. */
typedef struct {
    double tnn;            /* [N s^2/rad^2] rho*D^4*alpha1 */
    double tnu;            /* [N s^2/(rad m)] rho*D^3*alpha2 */
    double efficiency;     /* [-] */
    double k_drag;         /* [N m s^2/rad^2] 0.5*rho*C_D*R^3 */
    float k_drag_f32;      /* [N m s^2/rad^2] the same, rounded to single precision */
    double inertia_kgm2;   /* [kg m^2] I0 */
} propeller_model;

typedef enum {
    PROPELLER_OK = 0,
    PROPELLER_ERR_NULL,   /* a pointer argument was NULL */
    PROPELLER_ERR_PARAM   /* a parameter is out of its physical range */
} propeller_status;

/* D = 0.3 m, alpha1 = 0.019, alpha2 = -0.16, efficiency 0.7, rho = 1025, C_D = 1.369e-3. */
extern const propeller_params propeller_params_default;

/*
 * Checks the parameters (positive diameter, density, efficiency in (0, 1],
 * non-negative drag coefficient and inertia, all finite) and derives the
 * coefficients. On an error the model is left unchanged.
 */
propeller_status propeller_init(propeller_model *m, const propeller_params *p);

/* Ideal thrust T [N] at shaft speed w [rad/s] and surge speed u [m/s]. */
double propeller_thrust_f64(const propeller_model *m, double w_radps, double u_mps);

/* Surge force efficiency * T [N], the propulsion force of the `paper` law. */
double propeller_surge_force_f64(const propeller_model *m, double w_radps, double u_mps);

/*
 * Hydrodynamic drag torque on the shaft [N m], -k_drag*w*|w|: negative for
 * w > 0, positive for w < 0. Cheap enough for every motor step.
 */
double propeller_drag_torque_f64(const propeller_model *m, double w_radps);

/* Single-precision twin of propeller_drag_torque_f64 (same formula). */
float propeller_drag_torque_f32(const propeller_model *m, float w_radps);

/* Full load torque T_load [N m] = -I0*w_dot + drag, for reference and tests. */
double propeller_load_torque_f64(const propeller_model *m, double w_radps,
                                 double w_dot_radps2);

#endif /* UUV_PROPELLER_H */
