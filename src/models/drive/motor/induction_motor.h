/*
 * Three-phase squirrel-cage induction motor with its shaft: the fast-medium
 * segment of the drive (100 us). The motor section of docs/drive.md gives
 * the derivation, the parameters and their sources, the fixed-point range
 * analysis and the validation figures.
 *
 * Equations (star-equivalent per-phase parameters, rotor referred to the
 * stator, linear magnetics). Space vectors in the stationary alpha-beta frame
 * use the amplitude-invariant Clarke transform. The star point is isolated,
 * so no zero-sequence current flows and the common-mode part v0 of the
 * terminal voltages does not act on the machine:
 *
 *   v0 = (v_a + v_b + v_c) / 3,  v_alpha = v_a - v0,  v_beta = (v_b - v_c) / sqrt(3)
 *   i_a = i_alpha,  i_b = -i_alpha / 2 + (sqrt(3) / 2) i_beta,  i_c = -i_a - i_b
 *
 * The states are the stator flux psi_s and the rotor flux psi_r, both
 * expressed in stator coordinates (complex numbers x = x_alpha + j x_beta):
 *
 *   psi_s = Ls i_s + Lm i_r,  psi_r = Lm i_s + Lr i_r,  Ls = Lls + Lm,  Lr = Llr + Lm
 *   i_s = (Lr psi_s - Lm psi_r) / D,  i_r = (Ls psi_r - Lm psi_s) / D,  D = Ls Lr - Lm^2
 *   d psi_s / dt   = v_s - Rs i_s          (stator, in stator coordinates)
 *   d psi_r^r / dt = -Rr i_r^r             (rotor, in rotor coordinates x^r = e^(-j theta) x)
 *   Te = (3/2) p Im(conj(psi_s) i_s) = (3/2) p (Lm / D) (psi_s,beta psi_r,alpha
 *                                                       - psi_s,alpha psi_r,beta)
 *   J dw/dt = Te - T_load,  T_load = k_drag w |w|,  J = J_rotor + I0,  d theta/dt = p w
 *
 * with w the mechanical shaft speed [rad/s], p the pole pairs, and k_drag
 * and I0 from the propeller (src/models/propeller/propeller.h; the drag torque there is
 * -T_load). The electrical input power is v_a i_a + v_b i_b + v_c i_c =
 * (3/2) Re(v_s conj(i_s)).
 *
 * Discretisation (step h, a parameter; 100 us in the drive). Each equation is
 * integrated by the trapezoidal rule in its own coordinates, with the speed
 * held over the step at the mid-step value w_m = w_n + (w_n - w_(n-1)) / 2
 * (second-order extrapolation), so the rotor turns by phi = p h w_m. Carried
 * back to stator coordinates the rotor equation reads
 *
 *   psi_r,n+1 + (h/2) Rr i_r,n+1 = e^(j phi) (psi_r,n - (h/2) Rr i_r,n)
 *   psi_s,n+1 + (h/2) Rs i_s,n+1 = psi_s,n - (h/2) Rs i_s,n + h vbar
 *
 * where vbar is the mean terminal voltage over the step (the executive
 * averages the filter-capacitor voltages over the frame; for a smooth input
 * h vbar is the exact integral, and the trapezoidal mean of the end values is
 * a valid substitute). Because the rotation sits on the known right-hand
 * side, the implicit system is a REAL 2x2 matrix M acting on complex
 * vectors, independent of the speed: M^-1 is computed once at init and a
 * step needs no division. Writing the right-hand sides as N psi_n (plus the
 * voltage and rotation) and Q = M^-1 - I, one step is
 *
 *   b_s = psi_s + n_ss psi_s + n_sr psi_r + h vbar
 *   b_r = e^(j phi) (psi_r + n_rs psi_s + n_rr psi_r)
 *   psi_s' = b_s + q_ss b_s + q_sr b_r,  psi_r' = b_r + q_rs b_s + q_rr b_r
 *
 * (the identity is kept apart so that the small coefficients keep their
 * precision). e^(j phi) comes from its Taylor series (|phi| <= 0.25 rad,
 * truncation below 1e-9); at steps long enough for the angle at 512 rad/s
 * to exceed 0.25 rad (beyond 244 us with p = 2: the averaged layer's
 * 800 us frame) the series is taken at phi / 2^k and squared k times,
 * e^(j phi) = (e^(j phi / 2^k))^(2^k), with the least such k (0 at 100 us,
 * where the step is unchanged). Integrating the rotor in rotor coordinates keeps
 * the slip frequency exact: the steady state at stator frequency f is that
 * of the continuous machine at f (1 + O((2 pi f h)^2 / 12)) with the slip
 * unchanged, which a stationary-frame trapezoid would not give near
 * synchronous speed.
 *
 * Mechanics: trapezoidal, J (w' - w) = (h/2) (Te + Te' - T_load - T_load'),
 * with T_load' linearised about w (T_load' = T_load + 2 k |w| (w' - w), one
 * Newton step of the implicit rule) and 1 / (1 + eps) replaced by 1 - eps,
 * eps = h k |w| / J (eps <= 1e-3 in the drive, error below eps^2):
 *
 *   w' = w + (h / (2 J)) (Te + Te' - 2 T_load) (1 - eps)
 *
 * A locked shaft (induction_motor_set_speed_*, locked = true) keeps w fixed,
 * for tests at a given slip.
 *
 * Twins. _q is integer-only (per-unit Q31 signals, see below), _f32 is
 * single precision in SI units, _f64 is the same algorithm in double, the
 * reference of the tests. All three share the coefficients of
 * induction_motor_coefs_f64(). The float speed is accumulated with a
 * compensation term (Kahan), because near steady state the increment per
 * step falls below the resolution of a float speed.
 *
 * Fixed-point formats (bases of src/models/drive/drive_units.h):
 *   inputs  v_a, v_b, v_c        Q31 of 1024 V
 *   outputs i_a, i_b, i_c        Q31 of 256 A (saturated, counted)
 *           te, t_load           Q31 of 512 N m (saturated, counted)
 *           w                    Q31 of 512 rad/s (mechanical)
 *           psi_s alpha, beta    Q31 of 4 Wb (saturated, counted)
 *           n_rpm_q16            int32, shaft speed [rpm] * 2^16 (|n| < 4890 rpm)
 *   states  psi_s, psi_r         Q31 of 8 Wb (twice the flux base: headroom above
 *                                the 5.6 Wb that 256 A of magnetising current makes)
 *           w, w_prev            Q31 of 512 rad/s
 *   constants: each row of constants that multiplies one sum is an int32
 *           mantissa per constant with one shared shift, chosen at init so
 *           that the largest mantissa has 30 significant bits (29 for the
 *           speed update, whose operand is a sum of four torques); a sum of
 *           up to three products of such a mantissa with a Q31 operand stays
 *           below 2^63. The rounding shift then gives the result in the
 *           format of the row's output. Every narrowing to 32 bits saturates
 *           and counts in sat_count.
 */
#ifndef UUV_INDUCTION_MOTOR_H
#define UUV_INDUCTION_MOTOR_H

#include <stdbool.h>
#include <stdint.h>

#include "fixedpoint/fixedpoint.h"
#include "models/propeller/propeller.h"

/* Full scale of the internal flux states of the fixed twin [Wb]: 2 * DRIVE_BASE_FLUX_WB. */
#define INDUCTION_MOTOR_PSI_FS_WB 8.0

/* Largest rotor angle per step at full-scale speed for the series of e^(j phi) [rad]. */
#define INDUCTION_MOTOR_PHI_MAX_RAD 0.25


/* Machine parameters: star-equivalent, per phase, rotor referred to the stator. */
typedef struct {
    double rs_ohm;       /* [ohm] stator resistance */
    double rr_ohm;       /* [ohm] rotor resistance */
    double lls_h;        /* [H] stator leakage inductance */
    double llr_h;        /* [H] rotor leakage inductance */
    double lm_h;         /* [H] magnetising inductance */
    uint32_t pole_pairs; /* [-] p, 1..16 */
    double j_rotor_kgm2; /* [kg m^2] rotor inertia */
    double v_ll_rated_v; /* [V] rated line-to-line rms voltage of this connection */
    double f_rated_hz;   /* [Hz] rated frequency */
} induction_motor_params;

/*
 * The drive's motor: a 15 kW (20 hp), 400 V star, 50 Hz, 4-pole machine
 * reconnected in delta for 230 V (star-equivalent values = the star values
 * / 3). Source and conversion in induction_motor_params.c.
 */
extern const induction_motor_params induction_motor_params_15kw_delta;

/*
 * A 4 kW (5 hp), 400 V star, 50 Hz, 4-pole machine of the same published
 * family, whose direct-on-line start stays inside the 256 A current base: the
 * free-acceleration test case of both twins.
 */
extern const induction_motor_params induction_motor_params_4kw_star;

typedef enum {
    INDUCTION_MOTOR_OK = 0,
    INDUCTION_MOTOR_ERR_NULL,  /* a pointer argument was NULL */
    INDUCTION_MOTOR_ERR_PARAM, /* a parameter is out of its physical range */
    INDUCTION_MOTOR_ERR_STEP,  /* step not in (0, 1 ms] */
    INDUCTION_MOTOR_ERR_RANGE  /* a constant does not fit its fixed-point format */
} induction_motor_status;

/* The discrete coefficients derived once from the parameters (SI, double). */
typedef struct {
    double h_s; /* [s] step */
    /* [1/H] i_s = a_ss psi_s - a_sr psi_r;  i_r = a_rr psi_r - a_sr psi_s */
    double a_ss, a_sr, a_rr;
    double n_ss, n_sr, n_rs, n_rr; /* [-] N - I, right-hand side */
    double q_ss, q_sr, q_rs, q_rr; /* [-] M^-1 - I, solve */
    double phi_per_w;              /* [rad per rad/s] p h */
    uint32_t rot_squarings;        /* [-] k: the series at phi / 2^k, squared k times */
    double te_per_cross;           /* [N m / Wb^2] (3/2) p Lm / D */
    double dw_per_t;               /* [rad/s per N m] h / (2 J) */
    double eps_per_w;              /* [1 per rad/s] h k_drag / J */
    double k_drag;                 /* [N m s^2 / rad^2] 0 without a propeller */
    double j_total_kgm2;           /* [kg m^2] J_rotor + I0 */
    double rs_ohm, rr_ohm;         /* [ohm] copies, for energy accounting */
    double ls_h, lr_h, lm_h;       /* [H] self and mutual inductances */
    uint32_t pole_pairs;           /* [-] */
} induction_motor_coefs;

/*
 * Checks the parameters (finite, positive resistances, leakages, Lm and
 * rotor inertia; 1 <= p <= 16; 0 < step <= 1 ms) and derives the
 * coefficients. prop may be NULL: no load torque and no propeller inertia.
 */
induction_motor_status induction_motor_coefs_f64(induction_motor_coefs *c,
                                                 const induction_motor_params *p,
                                                 const propeller_model *prop, double step_s);

/* The state of any twin in SI units, for tests, telemetry and energy accounting. */
typedef struct {
    double psi_s[2], psi_r[2]; /* [Wb] alpha, beta */
    double i_s[2], i_r[2];     /* [A] alpha, beta */
    double w_radps;            /* [rad/s] mechanical speed */
    double te_nm;              /* [N m] electromagnetic torque of the last step */
    double t_load_nm;          /* [N m] load torque k w |w| */
} induction_motor_obs;

/*
 * Magnetic energy (3/4) (psi_s . i_s + psi_r . i_r) [J], kinetic energy
 * J w^2 / 2 [J] and copper losses (3/2) (R_s |i_s|^2 + R_r |i_r|^2) [W] of
 * an observed state.
 */
double induction_motor_magnetic_energy_f64(const induction_motor_obs *o);
double induction_motor_kinetic_energy_f64(const induction_motor_coefs *c,
                                          const induction_motor_obs *o);
double induction_motor_copper_loss_f64(const induction_motor_coefs *c,
                                       const induction_motor_obs *o);

/* ---- Double-precision reference twin (SI) --------------------------------- */

typedef struct {
    double v_a, v_b, v_c; /* [V] terminal phase voltages, mean over the step */
} induction_motor_in_f64;

typedef struct {
    double i_a, i_b, i_c;                 /* [A] phase currents, positive into the motor */
    double te_nm;                         /* [N m] electromagnetic torque */
    double t_load_nm;                     /* [N m] load torque k w |w| (opposes w) */
    double w_radps;                       /* [rad/s] shaft speed */
    double n_rpm;                         /* [rpm] shaft speed */
    double psi_s_alpha_wb, psi_s_beta_wb; /* [Wb] stator flux */
} induction_motor_out_f64;

typedef struct {
    induction_motor_coefs c;
    const propeller_model *prop; /* NULL: no load */
    double psi_s[2], psi_r[2];   /* [Wb] */
    double w, w_prev;            /* [rad/s] */
    double te, t_load;           /* [N m] at the end of the last step */
    bool speed_locked;
} induction_motor_f64;

induction_motor_status induction_motor_init_f64(induction_motor_f64 *m,
                                                const induction_motor_params *p,
                                                const propeller_model *prop, double step_s);
/* Zero flux, at rest, shaft free. */
void induction_motor_reset_f64(induction_motor_f64 *m);
/* Sets the shaft speed [rad/s]; locked = true holds it there (no mechanics). */
void induction_motor_set_speed_f64(induction_motor_f64 *m, double w_radps, bool locked);
void induction_motor_step_f64(induction_motor_f64 *m, const induction_motor_in_f64 *in,
                              induction_motor_out_f64 *out);
void induction_motor_observe_f64(const induction_motor_f64 *m, induction_motor_obs *o);

/* ---- Single-precision twin (SI) ------------------------------------------- */

typedef struct {
    float v_a, v_b, v_c; /* [V] terminal phase voltages, mean over the step */
} induction_motor_in_f32;

typedef struct {
    float i_a, i_b, i_c;                 /* [A] phase currents, positive into the motor */
    float te_nm;                         /* [N m] electromagnetic torque */
    float t_load_nm;                     /* [N m] load torque k w |w| (opposes w) */
    float w_radps;                       /* [rad/s] shaft speed */
    float n_rpm;                         /* [rpm] shaft speed */
    float psi_s_alpha_wb, psi_s_beta_wb; /* [Wb] stator flux */
} induction_motor_out_f32;

typedef struct {
    induction_motor_coefs c; /* double originals (observation, energy) */
    float h, a_ss, a_sr;     /* [s], [1/H] */
    float n_ss, n_sr, n_rs, n_rr, q_ss, q_sr, q_rs, q_rr; /* [-] */
    float phi_per_w, te_per_cross, dw_per_t, eps_per_w;   /* as in the coefficients */
    const propeller_model *prop;                          /* NULL: no load */
    float psi_s[2], psi_r[2];                             /* [Wb] */
    float w, w_comp, w_prev; /* [rad/s] speed, its Kahan compensation, last speed */
    float te, t_load;        /* [N m] at the end of the last step */
    float load_factor;       /* [-] on the propeller's torque (fouling), 1 when clean */
    bool speed_locked;
} induction_motor_f32;

induction_motor_status induction_motor_init_f32(induction_motor_f32 *m,
                                                const induction_motor_params *p,
                                                const propeller_model *prop, double step_s);
void induction_motor_reset_f32(induction_motor_f32 *m);
void induction_motor_set_speed_f32(induction_motor_f32 *m, float w_radps, bool locked);
void induction_motor_step_f32(induction_motor_f32 *m, const induction_motor_in_f32 *in,
                              induction_motor_out_f32 *out);
void induction_motor_observe_f32(const induction_motor_f32 *m, induction_motor_obs *o);

/*
 * Faults (docs/reliability.md). A fouled propeller: its load torque times
 * factor (>= 1, finite), computed by induction_motor_load_*() in the
 * background and put in force by induction_motor_set_load_*() at a frame
 * boundary (a few copies). An open phase (0, 1, 2: a, b, c): right after a
 * step, with out holding that step's outputs, the stator flux loses the
 * component that drives current in that phase, so its current is zero and
 * the other two carry one current in series; out is recomputed.
 */
typedef struct {
    float eps_per_w; /* [1 per rad/s] the drag's linearisation, times the factor */
    float factor;    /* [-] */
} induction_motor_drag_f32;

induction_motor_status induction_motor_load_f32(const induction_motor_f32 *m, double factor,
                                                induction_motor_drag_f32 *l);
void induction_motor_set_load_f32(induction_motor_f32 *m, const induction_motor_drag_f32 *l);
void induction_motor_open_phase_f32(induction_motor_f32 *m, uint32_t phase,
                                    induction_motor_out_f32 *out);

/* ---- Integer twin (per unit, Q31) ----------------------------------------- */

typedef struct {
    q31_t v_a, v_b, v_c; /* Q31 of 1024 V: terminal phase voltages, mean over the step */
} induction_motor_in_q;

typedef struct {
    q31_t i_a, i_b, i_c;           /* Q31 of 256 A: phase currents, positive into the motor */
    q31_t te;                      /* Q31 of 512 N m: electromagnetic torque */
    q31_t t_load;                  /* Q31 of 512 N m: load torque k w |w| */
    q31_t w;                       /* Q31 of 512 rad/s: shaft speed */
    int32_t n_rpm_q16;             /* [rpm * 2^16] shaft speed */
    q31_t psi_s_alpha, psi_s_beta; /* Q31 of 4 Wb: stator flux */
} induction_motor_out_q;

/* Constants that share one binary point: value_k = c[k] / 2^shift. */
typedef struct {
    int32_t c[3];
    uint32_t shift;
} induction_motor_row_q;

typedef struct {
    induction_motor_coefs c;      /* double originals (observation, energy) */
    induction_motor_row_q row_bs; /* n_ss, n_sr, h vbar: flux <- flux, flux, voltage */
    induction_motor_row_q row_br; /* n_rs, n_rr */
    induction_motor_row_q row_qs; /* q_ss, q_sr */
    induction_motor_row_q row_qr; /* q_rs, q_rr */
    induction_motor_row_q row_is; /* a_ss, -a_sr: current <- flux, flux */
    induction_motor_row_q k_phi;  /* Q31 rad <- speed */
    induction_motor_row_q k_te;   /* torque <- flux cross product (Q30 of 64 Wb^2) */
    induction_motor_row_q k_dw;   /* speed step <- sum of four torques */
    induction_motor_row_q k_eps;  /* Q31 eps <- |speed| */
    induction_motor_row_q k_load; /* torque <- Q31 w|w| */
    induction_motor_row_q k_rpm;  /* rpm * 2^16 <- speed */
    induction_motor_row_q k_open; /* stator flux <- stator current, 1 / a_ss (open phase) */
    q31_t psi_s[2], psi_r[2];     /* Q31 of 8 Wb */
    q31_t w, w_prev;              /* Q31 of 512 rad/s */
    q31_t te, t_load;             /* Q31 of 512 N m, end of the last step */
    bool speed_locked;
    uint32_t sat_count; /* saturation events since init or reset */
} induction_motor_q;

/*
 * As the float init, plus INDUCTION_MOTOR_ERR_RANGE when a constant does not
 * fit its format (a rotor angle per step of 1 rad or more at 512 rad/s,
 * beyond the Q31 angle: h >= 977 us with p = 2; or a coefficient of 2^30 or
 * more).
 */
induction_motor_status induction_motor_init_q(induction_motor_q *m, const induction_motor_params *p,
                                              const propeller_model *prop, double step_s);
/* Zero flux, at rest, shaft free, saturation count cleared. */
void induction_motor_reset_q(induction_motor_q *m);
void induction_motor_set_speed_q(induction_motor_q *m, q31_t w, bool locked);
/*
 * One step, integer arithmetic only. Total: every narrowing to 32 bits
 * saturates and adds to m->sat_count. Cost: about 50 products of 32 x 32
 * bits into 64 bits and no division (measured figures in docs/drive.md).
 */
void induction_motor_step_q(induction_motor_q *m, const induction_motor_in_q *in,
                            induction_motor_out_q *out);
void induction_motor_observe_q(const induction_motor_q *m, induction_motor_obs *o);

/* The faults of the float twin (above), in the integer formats; the same errors as init. */
typedef struct {
    induction_motor_row_q k_eps, k_load; /* the rows of the drag, times the factor */
} induction_motor_drag_q;

induction_motor_status induction_motor_load_q(const induction_motor_q *m, double factor,
                                              induction_motor_drag_q *l);
void induction_motor_set_load_q(induction_motor_q *m, const induction_motor_drag_q *l);
void induction_motor_open_phase_q(induction_motor_q *m, uint32_t phase,
                                  induction_motor_out_q *out);

#endif /* UUV_INDUCTION_MOTOR_H */
