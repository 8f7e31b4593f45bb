/*
 * The vessel model against its references: the derivative vectors and the
 * mass matrix of the project's reference description of the NPS AUV II
 * (tests/vectors/), the first 10 s of its 1300 rpm straight run, the
 * analytic steady speed of the `paper` propulsion law, hand-computed
 * restoring forces for W != B, and the sign conventions of the reference
 * README. Runs on the host and on every target; on a Cortex-M3 with
 * software double it costs about 1.1e9 instructions, 40 % of them in the
 * 100 s run of the `paper` law.
 */
#include <stddef.h>
#include <stdint.h>

#include "math/umath.h"
#include "models/vessel/vessel.h"
#include "ut.h"

#include "test_vessel_data.h"

void suite_vessel(void);

/* Tolerances of the reference checks (relative, with an absolute floor). */
#define DERIV_REL 1e-9
#define DERIV_ABS 1e-12
#define TRAJ_REL 1e-6
#define TRAJ_ABS 1e-12

/* Tolerance for comparing with expected: rel * |expected|, at least abs_floor. */
static double tol(double expected, double rel, double abs_floor) {
    const double t = rel * math_fabs_f64(expected);
    return (t > abs_floor) ? t : abs_floor;
}

/* Relative error of got against expected (absolute error where expected is 0). */
static double rel_err(double got, double expected) {
    const double d = math_fabs_f64(got - expected);
    return (expected != 0.0) ? d / math_fabs_f64(expected) : d;
}

static vessel_cmd cmd_of(const double c[5]) {
    vessel_cmd cmd = {c[0], c[1], c[2], c[3], c[4], c[4], 0.0, 0.0};
    return cmd;
}

static void copy_state(double dst[VESSEL_NSTATES], const double src[VESSEL_NSTATES]) {
    for (int i = 0; i < VESSEL_NSTATES; i++) {
        dst[i] = src[i];
    }
}

static void zero_state(double x[VESSEL_NSTATES]) {
    for (int i = 0; i < VESSEL_NSTATES; i++) {
        x[i] = 0.0;
    }
}

static bool all_finite(const double x[VESSEL_NSTATES]) {
    bool ok = true;
    for (int i = 0; i < VESSEL_NSTATES; i++) {
        ok = ok && math_isfinite_f64(x[i]);
    }
    return ok;
}

/* Model instances in static storage: each is about 1.8 KB, too much for the stack. */
static vessel_model vm_a, vm_b;

static vessel_model *model_with(vessel_model *m, vessel_propulsion law,
                                vessel_shaft_source shaft) {
    vessel_config cfg;
    vessel_config_default(&cfg);
    cfg.propulsion = law;
    cfg.shaft = shaft;
    cfg.free_surface = false; /* deep water: the reference model of the vectors */
    UT_CHECK(vessel_init(m, &cfg) == VESSEL_OK);
    return m;
}

static void test_names_and_mass(void) {
    static const char *const header[VESSEL_NSTATES] = {
        "u_mps",       "v_mps",       "w_mps",        "p_radps",      "q_radps",   "r_radps",
        "x_m",         "y_m",         "z_m",          "phi_rad",      "theta_rad", "psi_rad",
        "delta_r_rad", "delta_s_rad", "delta_bp_rad", "delta_bs_rad", "n_rpm"};
    UT_TEST("state names: the 17 names in the order of the reference CSV header");
    for (int i = 0; i < VESSEL_NSTATES; i++) {
        UT_CHECK(ut_text_equal(vessel_state_names[i], header[i]));
    }

    UT_TEST("mass matrix: M_RB + M_A equals npsauv_mass_matrix.csv to 1e-12 relative");
    vessel_model *m = model_with(&vm_a, VESSEL_PROP_MSS, VESSEL_SHAFT_LAG);
    for (int i = 0; i < 6; i++) {
        for (int j = 0; j < 6; j++) {
            UT_NEAR(m->mass_matrix[i][j], vec_mass[i][j], tol(vec_mass[i][j], 1e-12, 1e-12));
        }
    }
    UT_TEST("mass matrix: the inverse computed at init gives M * M^-1 = I to 1e-12");
    for (int i = 0; i < 6; i++) {
        for (int j = 0; j < 6; j++) {
            double s = 0.0;
            for (int k = 0; k < 6; k++) {
                s += m->mass_matrix[i][k] * m->mass_inverse[k][j];
            }
            UT_NEAR(s, (i == j) ? 1.0 : 0.0, 1e-12);
        }
    }
}

/* Checks rows [first, first + n) of vec_derivs; returns the largest relative error. */
static double check_deriv_rows(const vessel_model *m, int first, int n) {
    double worst = 0.0;
    for (int r = first; r < first + n; r++) {
        const double *row = vec_derivs[r];
        const vessel_cmd cmd = cmd_of(&row[VEC_COL_CMD]);
        double dx[VESSEL_NSTATES];
        (void)vessel_derivatives(m, &row[VEC_COL_STATE], &cmd, dx);
        for (int i = 0; i < VESSEL_NSTATES; i++) {
            const double e = row[VEC_COL_DERIV + i];
            UT_NEAR(dx[i], e, tol(e, DERIV_REL, DERIV_ABS));
            const double re = rel_err(dx[i], e);
            worst = (re > worst) ? re : worst;
        }
    }
    return worst;
}

static void test_derivative_vectors(void) {
    vessel_model *m = model_with(&vm_a, VESSEL_PROP_MSS, VESSEL_SHAFT_LAG);
    UT_TEST("derivatives: the 10 random rows of npsauv_derivatives.csv to 1e-9 relative");
    ut_info("largest relative error %.3e", check_deriv_rows(m, 0, 10));
    UT_TEST("derivatives: the 8 edge rows (rest, astern, coasting, reverse, beyond limits, "
            "u = 1e-6, general) to 1e-9 relative");
    ut_info("largest relative error %.3e", check_deriv_rows(m, 10, 8));
}

/* Runs TRAJ_STEPS_PER_ROW frames per reference row and compares; returns the worst error. */
static double run_straight(vessel_model *m) {
    double x[VESSEL_NSTATES];
    double worst = 0.0;
    copy_state(x, &vec_traj[0][TRAJ_COL_STATE]);
    for (int r = 1; r < 11; r++) {
        /* The commands are constant over the run (0 rad, 1300 rpm). */
        const vessel_cmd cmd = cmd_of(&vec_traj[r - 1][TRAJ_COL_CMD]);
        for (int k = 0; k < TRAJ_STEPS_PER_ROW; k++) {
            (void)vessel_step(m, x, &cmd);
        }
        for (int i = 0; i < VESSEL_NSTATES; i++) {
            const double e = vec_traj[r][TRAJ_COL_STATE + i];
            UT_NEAR(x[i], e, tol(e, TRAJ_REL, TRAJ_ABS));
            const double re = rel_err(x[i], e);
            worst = (re > worst) ? re : worst;
        }
    }
    return worst;
}

static void test_straight_run(void) {
    UT_TEST("RK4: 100 frames of 0.1 s from u = 1e-6 m/s at 1300 rpm follow "
            "npsauv_straight_1300rpm.csv to 1e-6 relative at t = 1..10 s");
    vessel_model *m = model_with(&vm_a, VESSEL_PROP_MSS, VESSEL_SHAFT_LAG);
    UT_NEAR(m->step_s, 0.1, 0.0);
    ut_info("largest relative error %.3e", run_straight(m));

    UT_TEST("shaft from input: the same run with the shaft speed given as a 1300 rpm input");
    vessel_model *mi = model_with(&vm_b, VESSEL_PROP_MSS, VESSEL_SHAFT_INPUT);
    ut_info("largest relative error %.3e", run_straight(mi));
}

/* The derivatives of states 1..16 of two evaluations agree exactly. */
static bool same_except_shaft(const double a[VESSEL_NSTATES], const double b[VESSEL_NSTATES]) {
    bool same = true;
    for (int i = 0; i < VESSEL_N_RPM; i++) {
        same = same && (a[i] == b[i]);
    }
    return same;
}

static void test_shaft_input(void) {
    UT_TEST("shaft from input: d_n = 0, the state takes cmd.shaft_rpm, cmd.n_rpm is ignored");
    vessel_model *lag = model_with(&vm_a, VESSEL_PROP_PAPER, VESSEL_SHAFT_LAG);
    vessel_model *in = model_with(&vm_b, VESSEL_PROP_PAPER, VESSEL_SHAFT_INPUT);
    const double *row = vec_derivs[7];
    vessel_cmd cmd = cmd_of(&row[VEC_COL_CMD]);
    double dl[VESSEL_NSTATES], di[VESSEL_NSTATES], x[VESSEL_NSTATES];
    (void)vessel_derivatives(lag, &row[VEC_COL_STATE], &cmd, dl);
    (void)vessel_derivatives(in, &row[VEC_COL_STATE], &cmd, di);
    UT_CHECK(di[VESSEL_N_RPM] == 0.0);
    UT_CHECK(dl[VESSEL_N_RPM] != 0.0);
    UT_CHECK(same_except_shaft(dl, di));
    copy_state(x, &row[VEC_COL_STATE]);
    cmd.n_rpm = 0.0;
    cmd.shaft_rpm = 1234.5;
    (void)vessel_step(in, x, &cmd);
    UT_CHECK(x[VESSEL_N_RPM] == 1234.5);

    UT_TEST("shaft from input: the motor's speed is used unclamped (1600 rpm > 1500 rpm limit)");
    x[VESSEL_U_MPS] = 2.0;
    x[VESSEL_N_RPM] = 1600.0;
    const double w = 1600.0 * MATH_PI_F64 / 30.0;
    const double t_hand = 0.7 * (1025.0 * 0.0081 * 0.019 * w * w - 1025.0 * 0.027 * 0.16 * w * 2.0);
    UT_NEAR(vessel_shaft_radps(in, x), w, 1e-12 * w);
    UT_NEAR(vessel_thrust_n(in, x), t_hand, 1e-9 * t_hand);
    UT_NEAR(vessel_shaft_radps(lag, x), 1500.0 * MATH_PI_F64 / 30.0, 1e-12 * w);
}

static void test_paper_law(void) {
    UT_TEST("paper law: from rest at 1000 rpm the speed settles within 1 % of the root of "
            "0.7 (Tnn w^2 + Tnu w u) = r2 C_d0 u^2");
    vessel_model *m = model_with(&vm_a, VESSEL_PROP_PAPER, VESSEL_SHAFT_LAG);
    const double w = 1000.0 * MATH_PI_F64 / 30.0;
    const double tnn = 1025.0 * (0.3 * 0.3 * 0.3 * 0.3) * 0.019;
    const double tnu = 1025.0 * (0.3 * 0.3 * 0.3) * -0.16;
    const double kd = 0.5 * 1025.0 * 5.3 * 5.3 * 0.00385; /* 55.4251 N s^2/m^2 */
    const double b = -0.7 * tnu * w;
    const double c = -0.7 * tnn * w * w;
    const double u_ss = (-b + math_sqrt_f64(b * b - 4.0 * kd * c)) / (2.0 * kd);
    double x[VESSEL_NSTATES];
    zero_state(x);
    const vessel_cmd cmd = {0.0, 0.0, 0.0, 0.0, 1000.0, 0.0, 0.0, 0.0};
    double u_10s = 0.0, u_90s = 0.0;
    for (int k = 1; k <= 1000; k++) {
        (void)vessel_step(m, x, &cmd);
        u_10s = (k == 100) ? x[VESSEL_U_MPS] : u_10s;
        u_90s = (k == 900) ? x[VESSEL_U_MPS] : u_90s;
    }
    const double u = x[VESSEL_U_MPS];
    UT_CHECK(u_10s > 0.5 * u_ss);
    UT_NEAR(u, u_ss, 0.01 * u_ss);
    UT_NEAR(u, u_90s, 1e-3 * u_ss);
    UT_CHECK(all_finite(x));
    ut_info("analytic %.9f m/s; simulated at 10 s %.6f, 90 s %.9f, 100 s %.9f (rel %.2e)",
            u_ss, u_10s, u_90s, u, (u - u_ss) / u_ss);
}

/* At rest, M nu_dot equals the restoring force: everything else vanishes. */
static void test_restoring(void) {
    UT_TEST("restoring forces: M nu_dot at rest equals -g(eta) for W != B, r_G and r_B off "
            "the axes (hand values)");
    vessel_params p = vessel_params_npsauv2;
    p.r_g_m[0] = 0.02;
    p.r_g_m[1] = -0.01;
    p.r_b_m[0] = 0.01;
    p.r_b_m[1] = 0.005;
    p.r_b_m[2] = -0.02;
    vessel_config cfg;
    vessel_model *m = &vm_a;
    vessel_config_default(&cfg);
    cfg.params = &p;
    cfg.free_surface = false;
    UT_CHECK(vessel_init(m, &cfg) == VESSEL_OK);
    double x[VESSEL_NSTATES], dx[VESSEL_NSTATES];
    zero_state(x);
    x[VESSEL_PHI_RAD] = 0.2;
    x[VESSEL_THETA_RAD] = 0.3;
    x[VESSEL_PSI_RAD] = 1.0;
    const vessel_cmd cmd = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 800.0, 0.0};
    (void)vessel_derivatives(m, x, &cmd, dx);
    /*
     * W = 53400 N, B = 54200 N; x_G W - x_B B = 526, y_G W - y_B B = -805,
     * z_G W - z_B B = 4341.4 [N m]; phi = 0.2, theta = 0.3 rad:
     * -g = (-(W-B) s_th, (W-B) c_th s_phi, (W-B) c_th c_phi,
     *       -805 c_th c_phi - 4341.4 c_th s_phi, -4341.4 s_th - 526 c_th c_phi,
     *       526 c_th s_phi - 805 s_th).
     */
    static const double hand[6] = {236.41616532907165,  -151.83684878294991, -749.03469086735936,
                                   -1577.6967768181539, -1775.4617344448282, -138.06103828758876};
    for (int i = 0; i < 6; i++) {
        double s = 0.0;
        for (int j = 0; j < 6; j++) {
            s += m->mass_matrix[i][j] * dx[j];
        }
        UT_NEAR(s, hand[i], 1e-9 * 1800.0);
    }
}

/* Runs n frames from x with cmd. */
static void run(vessel_model *m, double x[VESSEL_NSTATES], const vessel_cmd *cmd, int n) {
    for (int k = 0; k < n; k++) {
        (void)vessel_step(m, x, cmd);
    }
}

static void test_buoyancy(void) {
    UT_TEST("buoyancy: delta_B = +500 N raises the vehicle from rest (z < 0), -500 N sinks it");
    vessel_model *m = model_with(&vm_a, VESSEL_PROP_PAPER, VESSEL_SHAFT_LAG);
    double x[VESSEL_NSTATES];
    vessel_cmd cmd = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 500.0, 0.0};
    zero_state(x);
    run(m, x, &cmd, 50);
    UT_CHECK(x[VESSEL_Z_M] < -0.1);
    UT_CHECK(x[VESSEL_W_MPS] < 0.0);
    ut_info("+500 N: z = %.4f m after 5 s", x[VESSEL_Z_M]);
    zero_state(x);
    cmd.delta_b_n = -500.0;
    run(m, x, &cmd, 50);
    UT_CHECK(x[VESSEL_Z_M] > 0.1);
    ut_info("-500 N: z = %.4f m after 5 s", x[VESSEL_Z_M]);
}

/* The paper law's cruise at 1000 rpm, all else zero. */
static void cruise_state(double x[VESSEL_NSTATES]) {
    zero_state(x);
    x[VESSEL_U_MPS] = 2.5874540539237803;
    x[VESSEL_N_RPM] = 1000.0;
}

static void test_signs(void) {
    vessel_model *m = model_with(&vm_a, VESSEL_PROP_PAPER, VESSEL_SHAFT_LAG);
    double x[VESSEL_NSTATES];
    UT_TEST("signs: a positive rudder turns to port (r < 0, psi decreasing)");
    vessel_cmd cmd = {0.1, 0.0, 0.0, 0.0, 1000.0, 0.0, 0.0, 0.0};
    cruise_state(x);
    run(m, x, &cmd, 100);
    UT_CHECK(x[VESSEL_R_RADPS] < 0.0);
    UT_CHECK(x[VESSEL_PSI_RAD] < -0.1);
    ut_info("rudder +0.1 rad for 10 s: psi = %.4f rad, y = %.3f m", x[VESSEL_PSI_RAD],
            x[VESSEL_Y_M]);

    UT_TEST("signs: a positive stern plane dives (nose down, z increasing)");
    cmd.rudder_rad = 0.0;
    cmd.stern_rad = 0.1;
    cruise_state(x);
    run(m, x, &cmd, 100);
    UT_CHECK(x[VESSEL_THETA_RAD] < 0.0);
    UT_CHECK(x[VESSEL_Z_M] > 0.5);
    ut_info("stern +0.1 rad for 10 s: theta = %.4f rad, z = %.3f m", x[VESSEL_THETA_RAD],
            x[VESSEL_Z_M]);
}

static void test_guards(void) {
    vessel_model *m = model_with(&vm_a, VESSEL_PROP_MSS, VESSEL_SHAFT_LAG);
    double x[VESSEL_NSTATES], dx[VESSEL_NSTATES];
    const vessel_cmd cmd = {0.0, 0.1, 0.0, 0.0, 1300.0, 0.0, 0.0, 0.0};
    unsigned ev;

    UT_TEST("guards: u = -1e-10 (pole of the advance ratio) gives finite derivatives");
    cruise_state(x);
    x[VESSEL_U_MPS] = -1e-10;
    x[VESSEL_Q_RADPS] = 0.05;
    x[VESSEL_N_RPM] = 1300.0;
    ev = vessel_derivatives(m, x, &cmd, dx);
    UT_CHECK(all_finite(dx));
    UT_CHECK((ev & (1u << VESSEL_EVENT_ETA_POLE)) != 0u);

    UT_TEST("guards: eta < -2.98 with active wash terms (u = -0.5 m/s, q != 0) stays finite");
    x[VESSEL_U_MPS] = -0.5;
    ev = vessel_derivatives(m, x, &cmd, dx);
    UT_CHECK(all_finite(dx));
    UT_CHECK((ev & (1u << VESSEL_EVENT_EPS_SQRT)) != 0u);
    UT_CHECK((ev & (1u << VESSEL_EVENT_ETA_POLE)) == 0u);

    UT_TEST("guards: theta = pi/2 (Euler singularity) gives finite derivatives");
    x[VESSEL_U_MPS] = 1.0;
    x[VESSEL_THETA_RAD] = MATH_HALF_PI_F64;
    ev = vessel_derivatives(m, x, &cmd, dx);
    UT_CHECK(all_finite(dx));
    UT_CHECK((ev & (1u << VESSEL_EVENT_PITCH_90)) != 0u);

    UT_TEST("trap kept from the source: under `mss` a vehicle at rest stays at rest at 1300 rpm");
    zero_state(x);
    x[VESSEL_N_RPM] = 1300.0;
    const vessel_cmd fwd = {0.0, 0.0, 0.0, 0.0, 1300.0, 0.0, 0.0, 0.0};
    run(m, x, &fwd, 10);
    UT_CHECK(x[VESSEL_U_MPS] == 0.0);
    UT_CHECK(x[VESSEL_X_M] == 0.0);
}

/* Runs n frames and checks that every state stays finite. */
static bool run_finite(vessel_model *m, double x[VESSEL_NSTATES], const vessel_cmd *cmd, int n) {
    bool ok = true;
    for (int k = 0; k < n; k++) {
        (void)vessel_step(m, x, cmd);
        ok = ok && all_finite(x);
    }
    return ok;
}

static void test_no_nan(void) {
    double x[VESSEL_NSTATES];
    UT_TEST("no NaN: 60 s of reversed shaft (-800 rpm) from 1 m/s under `mss` stay finite");
    vessel_model *m = model_with(&vm_a, VESSEL_PROP_MSS, VESSEL_SHAFT_LAG);
    const vessel_cmd rev = {0.05, 0.05, 0.0, 0.0, -800.0, 0.0, 0.0, 0.0};
    zero_state(x);
    x[VESSEL_U_MPS] = 1.0;
    UT_CHECK(run_finite(m, x, &rev, 600));
    ut_info("u = %.3e m/s; steps with the square-root guard: %u", x[VESSEL_U_MPS],
            (unsigned)m->event_steps[VESSEL_EVENT_EPS_SQRT]);

    UT_TEST("no NaN: 60 s with every command beyond its limit (`paper`) stay finite; the "
            "actuator states wind up at (command - limit) / T_a");
    vessel_model *mp = model_with(&vm_b, VESSEL_PROP_PAPER, VESSEL_SHAFT_LAG);
    const vessel_cmd big = {0.6, 0.6, 0.6, -0.6, 2000.0, 0.0, 0.0, 0.0};
    double dx[VESSEL_NSTATES];
    zero_state(x);
    UT_CHECK(run_finite(mp, x, &big, 600));
    UT_CHECK(mp->event_steps[VESSEL_EVENT_ACTUATOR_LIMIT] >= 590u);
    (void)vessel_derivatives(mp, x, &big, dx);
    const double lim = vessel_params_npsauv2.fin_limit_rad;
    UT_NEAR(dx[VESSEL_DELTA_R_RAD], (0.6 - lim) / 0.1, 1e-12);
    UT_NEAR(dx[VESSEL_DELTA_BS_RAD], (-0.6 + lim) / 0.1, 1e-12);
    UT_NEAR(dx[VESSEL_N_RPM], (2000.0 - 1500.0) / 0.1, 1e-9);
    ut_info("after 60 s: u = %.3f m/s, z = %.1f m, theta = %.3f rad, delta_r state %.2f rad",
            x[VESSEL_U_MPS], x[VESSEL_Z_M], x[VESSEL_THETA_RAD], x[VESSEL_DELTA_R_RAD]);
}

/*
 * Four-quadrant operation (docs/vessel.md, section 3): astern at full
 * reverse under `paper` reaches minus the forward steady speed and damps
 * a pitch disturbance; with only the surge speed, the fins and no shaft
 * speed, the body accelerations are odd in u (fin lift and drag reverse
 * with the flow); a frame longer than 0.1 s is integrated in equal steps.
 */
static void test_four_quadrant(void) {
    double x[VESSEL_NSTATES];
    UT_TEST("astern (`paper`, -1500 rpm, 60 s from rest with a 0.3 rad/s pitch rate): "
            "finite, u -> -3.881 m/s (minus the forward steady speed), the pitch rate damped below 0.01 rad/s");
    vessel_model *m = model_with(&vm_a, VESSEL_PROP_PAPER, VESSEL_SHAFT_LAG);
    const vessel_cmd rev = {0.0, 0.0, 0.0, 0.0, -1500.0, 0.0, 0.0, 0.0};
    zero_state(x);
    x[VESSEL_Q_RADPS] = 0.3;
    UT_CHECK(run_finite(m, x, &rev, 600));
    UT_NEAR(x[VESSEL_U_MPS], -3.8806, 2e-3);
    UT_CHECK(math_fabs_f64(x[VESSEL_Q_RADPS]) < 0.01 && math_fabs_f64(x[VESSEL_THETA_RAD]) < 0.3);
    ut_info("after 60 s: u = %.4f m/s, q = %.2e rad/s, theta = %.4f rad", x[VESSEL_U_MPS],
            x[VESSEL_Q_RADPS], x[VESSEL_THETA_RAD]);

    UT_TEST("four quadrants: with u, the fins and n = 0 only, du..dr at -u are minus those at u");
    double xa[VESSEL_NSTATES], da[VESSEL_NSTATES], db[VESSEL_NSTATES];
    const vessel_cmd fins = {0.1, -0.15, 0.05, 0.1, 0.0, 0.0, 0.0, 0.0};
    zero_state(xa);
    xa[VESSEL_U_MPS] = 2.0;
    xa[VESSEL_DELTA_R_RAD] = 0.1;
    xa[VESSEL_DELTA_S_RAD] = -0.15;
    xa[VESSEL_DELTA_BP_RAD] = 0.05;
    xa[VESSEL_DELTA_BS_RAD] = 0.1;
    (void)vessel_derivatives(m, xa, &fins, da);
    xa[VESSEL_U_MPS] = -2.0;
    (void)vessel_derivatives(m, xa, &fins, db);
    bool odd = true;
    for (int i = VESSEL_U_MPS; i <= VESSEL_R_RADPS; i++) {
        odd = odd && math_fabs_f64(da[i] + db[i]) <= 1e-15 * math_fabs_f64(da[i]) + 1e-300;
    }
    UT_CHECK(odd && da[VESSEL_R_RADPS] != 0.0 && da[VESSEL_Q_RADPS] != 0.0);

    UT_TEST("a 0.5 s frame is 5 RK4 steps of 0.1 s: the bits of five 0.1 s frames");
    vessel_config cfg;
    vessel_config_default(&cfg);
    cfg.step_s = 0.5;
    cfg.free_surface = false;
    UT_CHECK(vessel_init(&vm_b, &cfg) == VESSEL_OK);
    UT_EQ_INT(vm_b.substeps, 5);
    const vessel_cmd cmd = {0.1, -0.05, 0.0, 0.0, 1200.0, 0.0, 0.0, 0.0};
    cruise_state(x);
    copy_state(xa, x);
    (void)vessel_step(&vm_b, x, &cmd);
    run(model_with(&vm_a, VESSEL_PROP_PAPER, VESSEL_SHAFT_LAG), xa, &cmd, 5);
    bool same = true;
    for (int i = 0; i < VESSEL_NSTATES; i++) {
        same = same && (math_bits_f64(x[i]) == math_bits_f64(xa[i]));
    }
    UT_CHECK(same);
}

static void test_init(void) {
    UT_TEST("init: refuses NULL, a bad frame, an unknown law or shaft source, a NaN "
            "coefficient, a non-physical field and a singular mass matrix");
    vessel_config cfg;
    vessel_model *m = &vm_a;
    vessel_config_default(&cfg);
    UT_CHECK(cfg.propulsion == VESSEL_PROP_PAPER);
    UT_CHECK(vessel_init(NULL, &cfg) == VESSEL_ERR_NULL);
    UT_CHECK(vessel_init(m, NULL) == VESSEL_ERR_NULL);
    cfg.step_s = 0.0;
    UT_CHECK(vessel_init(m, &cfg) == VESSEL_ERR_PARAM);
    cfg.step_s = 0.1;
    cfg.propulsion = (vessel_propulsion)7;
    UT_CHECK(vessel_init(m, &cfg) == VESSEL_ERR_PARAM);
    cfg.propulsion = VESSEL_PROP_MSS;
    cfg.shaft = (vessel_shaft_source)7;
    UT_CHECK(vessel_init(m, &cfg) == VESSEL_ERR_PARAM);
    cfg.shaft = VESSEL_SHAFT_LAG;

    volatile double zero = 0.0;
    vessel_params p = vessel_params_npsauv2;
    cfg.params = &p;
    p.n.vw = zero / zero;
    UT_CHECK(vessel_init(m, &cfg) == VESSEL_ERR_PARAM);
    p = vessel_params_npsauv2;
    p.actuator_tau_s = 0.0;
    UT_CHECK(vessel_init(m, &cfg) == VESSEL_ERR_PARAM);
    /* A roll row of zeros: no roll inertia, no added roll inertia, no coupling. */
    p = vessel_params_npsauv2;
    p.ix_kgm2 = 1e-30;
    p.ixy_kgm2 = 0.0;
    p.ixz_kgm2 = 0.0;
    p.r_g_m[2] = 0.0;
    p.k.vdot = 0.0;
    p.k.pdot = 0.0;
    p.k.rdot = 0.0;
    UT_CHECK(vessel_init(m, &cfg) == VESSEL_ERR_MASS_MATRIX);
    cfg.params = NULL;
    UT_CHECK(vessel_init(m, &cfg) == VESSEL_OK);
}

/*
 * Each range check of vessel_init (vessel.h and vessel_params.h: positive
 * length, g, rho, W, B, inertias and hull radius; non-negative drag and hull sizes;
 * positive finite limits and lag; frame in (0, 1]; a valid propeller).
 */
static void test_init_fields(void) {
    UT_TEST("init: each physical field out of its range, a limit that is not finite, a "
            "frame above 1 s and an invalid propeller are refused; NULL propeller selects "
            "the default");
    vessel_config cfg;
    vessel_model *m = &vm_a;
    vessel_params p;
    vessel_config_default(&cfg);
    cfg.params = &p;
    for (unsigned k = 0u; k < 17u; k++) {
        p = vessel_params_npsauv2;
        switch (k) {
        case 0u: p.length_m = 0.0; break;
        case 1u: p.gravity_mps2 = -9.81; break;
        case 2u: p.rho_kgpm3 = 0.0; break;
        case 3u: p.weight_n = 0.0; break;
        case 4u: p.buoyancy_n = -1.0; break;
        case 5u: p.ix_kgm2 = 0.0; break;
        case 6u: p.iy_kgm2 = 0.0; break;
        case 7u: p.iz_kgm2 = -1.0; break;
        case 8u: p.cdy = -0.1; break;
        case 9u: p.cdz = -0.1; break;
        case 10u: p.hx_m = -0.1; break;
        case 11u: p.bx_m = -0.1; break;
        case 12u: p.cd0 = -0.1; break;
        case 13u: p.fin_limit_rad = math_inf_f64(); break;
        case 14u: p.shaft_limit_rpm = -1500.0; break;
        case 15u: p.hull_radius_m = 0.0; break;
        default: p.actuator_tau_s = math_nan_f64(); break;
        }
        if (!UT_CHECK(vessel_init(m, &cfg) == VESSEL_ERR_PARAM)) {
            ut_info("field case %u", k);
        }
    }
    cfg.params = NULL;
    cfg.step_s = 1.5;
    UT_CHECK(vessel_init(m, &cfg) == VESSEL_ERR_PARAM);
    cfg.step_s = 1.0;
    propeller_params pp = propeller_params_default;
    pp.diameter_m = 0.0;
    cfg.propeller = &pp;
    UT_CHECK(vessel_init(m, &cfg) == VESSEL_ERR_PARAM);
    cfg.propeller = NULL;
    UT_CHECK(vessel_init(m, &cfg) == VESSEL_OK);
    propeller_model def;
    UT_CHECK(propeller_init(&def, &propeller_params_default) == PROPELLER_OK);
    UT_NEAR(m->prop.k_drag, def.k_drag, 0.0);
    UT_NEAR(m->step_s, 1.0, 0.0);
}

static void test_counters_and_pitch(void) {
    vessel_model *m = model_with(&vm_a, VESSEL_PROP_PAPER, VESSEL_SHAFT_LAG);
    double x[VESSEL_NSTATES], dx[VESSEL_NSTATES];

    UT_TEST("event counters saturate at UINT32_MAX instead of wrapping to 0");
    const vessel_cmd big = {0.6, 0.0, 0.0, 0.0, 1000.0, 0.0, 0.0, 0.0};
    cruise_state(x);
    m->event_steps[VESSEL_EVENT_ACTUATOR_LIMIT] = UINT32_MAX - 1u;
    (void)vessel_step(m, x, &big);
    UT_CHECK(m->event_steps[VESSEL_EVENT_ACTUATOR_LIMIT] == UINT32_MAX);
    (void)vessel_step(m, x, &big);
    UT_CHECK(m->event_steps[VESSEL_EVENT_ACTUATOR_LIMIT] == UINT32_MAX);
    vessel_reset_counters(m);
    UT_EQ_INT(m->event_steps[VESSEL_EVENT_ACTUATOR_LIMIT], 0);

    UT_TEST("Euler rates near theta = 90 deg: the divisor cos(theta) is held at 1e-12 with "
            "its sign, psi_dot = (q sin(phi) + r cos(phi)) / (+-1e-12) on either side; at "
            "theta = 180 deg (cos = -1) no guard acts and psi_dot = -(q sin(phi) + r cos(phi))");
    const vessel_cmd cmd = {0.0, 0.0, 0.0, 0.0, 1000.0, 0.0, 0.0, 0.0};
    cruise_state(x);
    x[VESSEL_PHI_RAD] = 0.1;
    x[VESSEL_Q_RADPS] = 0.01;
    x[VESSEL_R_RADPS] = 0.02;
    const double rate = 0.01 * math_sin_f64(0.1) + 0.02 * math_cos_f64(0.1);
    for (int k = 0; k < 2; k++) {
        double side = (k == 0) ? 1.0 : -1.0;
        x[VESSEL_THETA_RAD] = MATH_HALF_PI_F64 + side * 1e-13;
        unsigned ev = vessel_derivatives(m, x, &cmd, dx);
        UT_CHECK((ev & (1u << VESSEL_EVENT_PITCH_90)) != 0u);
        UT_CHECK(all_finite(dx));
        UT_NEAR(dx[VESSEL_PSI_RAD], -side * rate * 1e12, 1e-9 * rate * 1e12);
    }
    x[VESSEL_THETA_RAD] = MATH_PI_F64;
    unsigned ev = vessel_derivatives(m, x, &cmd, dx);
    UT_CHECK((ev & (1u << VESSEL_EVENT_PITCH_90)) == 0u);
    UT_NEAR(dx[VESSEL_PSI_RAD], -rate, 1e-15);
}

/* FNV-1a over the bits of the state, to compare host and target runs. */
/* ---- Free surface ---------------------------------------------------------- */

/*
 * The axis depth at which a cylinder of radius r floats when the fraction
 * `frac` of its volume is under water, from the segment's central angle a:
 * the submerged area is (a - sin a) / (2 pi) of the circle's, and the axis
 * lies r cos(a/2) below the water line when a > pi. Bisection on a, so the
 * figure does not come from the model's own formula.
 */
static double float_depth(double frac, double r) {
    double lo = 0.0, hi = 2.0 * MATH_PI_F64;
    for (int k = 0; k < 80; k++) {
        const double a = 0.5 * (lo + hi);
        if ((a - math_sin_f64(a)) / (2.0 * MATH_PI_F64) < frac) {
            lo = a;
        } else {
            hi = a;
        }
    }
    return -r * math_cos_f64(0.25 * (lo + hi));
}

static vessel_model *model_surface(vessel_model *m) {
    vessel_config cfg;
    vessel_config_default(&cfg);
    UT_CHECK(cfg.free_surface);
    UT_CHECK(vessel_init(m, &cfg) == VESSEL_OK);
    return m;
}

static void test_free_surface(void) {
    UT_TEST("free surface: with the hull under water (each reference row 10 m deeper), the "
            "derivatives equal the deep-water model's bit for bit");
    vessel_model *deep = model_with(&vm_a, VESSEL_PROP_MSS, VESSEL_SHAFT_LAG);
    vessel_config cfg;
    vessel_config_default(&cfg);
    cfg.propulsion = VESSEL_PROP_MSS;
    vessel_model *sea = &vm_b;
    UT_CHECK(vessel_init(sea, &cfg) == VESSEL_OK);
    bool same = true;
    for (int r = 0; r < 18; r++) {
        const double *row = vec_derivs[r];
        const vessel_cmd cmd = cmd_of(&row[VEC_COL_CMD]);
        double x[VESSEL_NSTATES], d1[VESSEL_NSTATES], d2[VESSEL_NSTATES];
        copy_state(x, &row[VEC_COL_STATE]);
        x[VESSEL_Z_M] += 10.0;
        (void)vessel_derivatives(deep, x, &cmd, d1);
        (void)vessel_derivatives(sea, x, &cmd, d2);
        for (int i = 0; i < VESSEL_NSTATES; i++) {
            same = same && math_bits_f64(d1[i]) == math_bits_f64(d2[i]);
        }
    }
    UT_CHECK(same);

    UT_TEST("free surface: dry, the hull has no buoyancy (W pulls it down at g); half out, "
            "half of B acts (to 1e-3 N)");
    sea = model_surface(&vm_b);
    double x[VESSEL_NSTATES], dx[VESSEL_NSTATES];
    const vessel_cmd rest = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
    zero_state(x);
    x[VESSEL_Z_M] = -1.0;
    (void)vessel_derivatives(sea, x, &rest, dx);
    UT_NEAR(sea->mass_matrix[2][2] * dx[VESSEL_W_MPS] +
                sea->mass_matrix[2][4] * dx[VESSEL_Q_RADPS],
            53400.0, 1e-9);
    x[VESSEL_Z_M] = 0.0;
    (void)vessel_derivatives(sea, x, &rest, dx);
    UT_NEAR(sea->mass_matrix[2][2] * dx[VESSEL_W_MPS] +
                sea->mass_matrix[2][4] * dx[VESSEL_Q_RADPS],
            26700.0, 1e-3); /* the asin polynomial: 7e-9 of B */

    /* Delta B = +2000 N: 96.4 % of the hull under water at equilibrium. */
    const double r_hull = vessel_params_npsauv2.hull_radius_m;
    const double z_eq = float_depth(53400.0 / 55400.0, r_hull);
    const vessel_cmd up = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 2000.0, 0.0};
    UT_TEST("free surface: a vehicle 2000 N positively buoyant, at rest at the analytic "
            "floating depth, level, stays there (within 1 mm for 60 s)");
    zero_state(x);
    x[VESSEL_Z_M] = z_eq;
    double dev = 0.0;
    for (int k = 0; k < 600; k++) {
        (void)vessel_step(sea, x, &up);
        const double d = math_fabs_f64(x[VESSEL_Z_M] - z_eq);
        dev = (d > dev) ? d : dev;
    }
    UT_CHECK(dev < 1e-3);
    UT_NEAR(x[VESSEL_THETA_RAD], 0.0, 1e-6);
    ut_info("analytic axis depth %.4f m (draft %.4f m); largest deviation %.2e m", z_eq,
            z_eq + r_hull, dev);

    UT_TEST("free surface: released from rest at 10 m it rises, never has its centre more "
            "than the hull radius above the water, and settles at the analytic draft "
            "(mean of the last 60 s of 300 s within 1 cm, the oscillation decaying)");
    zero_state(x);
    x[VESSEL_Z_M] = 10.0;
    double top = 10.0, sum = 0.0, early = 0.0, late = 0.0;
    for (int k = 0; k < 3000; k++) {
        (void)vessel_step(sea, x, &up);
        const double z = x[VESSEL_Z_M];
        top = (z < top) ? z : top;
        const double d = math_fabs_f64(z - z_eq);
        if (k >= 2400) {
            sum += z;
            late = (d > late) ? d : late;
        } else if (k >= 600 && k < 1200) {
            early = (d > early) ? d : early;
        }
    }
    const double mean = sum / 600.0;
    UT_CHECK(top > -r_hull);
    UT_NEAR(mean, z_eq, 0.01);
    UT_CHECK(late < early);
    ut_info("highest centre %.3f m; mean depth %.4f m (analytic %.4f); swing %.3f m at "
            "60-120 s, %.3f m at 240-300 s", top, mean, z_eq, early, late);

    UT_TEST("free surface: the CG 5 cm forward of the CB trims the floating vehicle by the "
            "bow (theta < 0), level with the CG under the CB");
    vessel_params p = vessel_params_npsauv2;
    p.r_g_m[0] = 0.05;
    cfg.params = &p;
    cfg.propulsion = VESSEL_PROP_PAPER;
    UT_CHECK(vessel_init(&vm_a, &cfg) == VESSEL_OK);
    zero_state(x);
    x[VESSEL_Z_M] = z_eq;
    run(&vm_a, x, &up, 300);
    UT_CHECK(x[VESSEL_THETA_RAD] < -0.005);
    ut_info("trim after 30 s: %.2f deg", x[VESSEL_THETA_RAD] * MATH_RAD_TO_DEG_F64);
}

static uint64_t state_hash(const double x[VESSEL_NSTATES]) {
    uint64_t h = 14695981039346656037ull;
    for (int i = 0; i < VESSEL_NSTATES; i++) {
        const uint64_t bits = math_bits_f64(x[i]);
        for (int b = 0; b < 8; b++) {
            h ^= (bits >> (8 * b)) & 0xffu;
            h *= 1099511628211ull;
        }
    }
    return h;
}

static void test_determinism(void) {
    UT_TEST("determinism: the state after a 10 s manoeuvre, hashed for comparing the ports' "
            "logs (docs/vessel.md lists the value every port printed)");
    vessel_model *m = model_with(&vm_a, VESSEL_PROP_PAPER, VESSEL_SHAFT_LAG);
    double x[VESSEL_NSTATES];
    const vessel_cmd cmd = {0.2, -0.1, 0.05, 0.1, 1200.0, 0.0, 150.0, 0.0};
    cruise_state(x);
    x[VESSEL_PHI_RAD] = 0.1;
    run(m, x, &cmd, 100);
    UT_CHECK(all_finite(x));
    ut_info("state hash %016llx", (unsigned long long)state_hash(x));
}

void suite_vessel(void) {
    test_names_and_mass();
    test_derivative_vectors();
    test_straight_run();
    test_shaft_input();
    test_paper_law();
    test_restoring();
    test_buoyancy();
    test_signs();
    test_guards();
    test_no_nan();
    test_four_quadrant();
    test_init();
    test_init_fields();
    test_counters_and_pitch();
    test_free_surface();
    test_determinism();
}
