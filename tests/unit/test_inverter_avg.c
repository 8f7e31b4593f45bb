/*
 * Set-up of the averaged inverter (inverter_avg.h), both twins: each error
 * the header lists, in the order it is checked (NULL pointers, the substep
 * count, the modulator's step range of [100 ns, 1 ms], the power stage's
 * initial DC-link voltage range [0, 1024) V), and the accepted limits. Its
 * step is tested against the switching path in test_power_stage.c.
 * The quasi-static stage: set-up, the DC-link constants against their
 * closed forms, and its step against the exponential bus, the settled bus
 * and the lossless power balance, both twins.
 */
#include <stddef.h>

#include "math/umath.h"
#include "models/drive/inverter/inverter_avg.h"
#include "ut.h"

void suite_inverter_avg(void);
static void suite_inverter_quasi_static(void);

/* Static: the instances hold a whole power stage, kept off the small target stacks. */
static inverter_avg_q inv_q;
static inverter_avg_f32 inv_f;

/* The status of both twins' init for the same arguments; -1 when they differ. */
static int init_both(bool null_inv, const pwm_params *pp, const power_stage_params *sp,
                     uint32_t frame_ns, uint32_t n_sub, double v_dc0_v) {
    inverter_avg_status q = inverter_avg_init_q(null_inv ? NULL : &inv_q, pp, sp, frame_ns, n_sub,
                                                v_dc0_v);
    inverter_avg_status f = inverter_avg_init_f32(null_inv ? NULL : &inv_f, pp, sp, frame_ns,
                                                  n_sub, v_dc0_v);
    return (q == f) ? (int)q : -1;
}

void suite_inverter_avg(void) {
    const pwm_params *pp = &pwm_params_default;
    const power_stage_params *sp = &power_stage_params_default;

    UT_TEST("init, both twins: a NULL instance, modulator or stage parameter set is ERR_NULL");
    UT_EQ_INT(init_both(true, pp, sp, 100000u, 50u, 500.0), INVERTER_AVG_ERR_NULL);
    UT_EQ_INT(init_both(false, NULL, sp, 100000u, 50u, 500.0), INVERTER_AVG_ERR_NULL);
    UT_EQ_INT(init_both(false, pp, NULL, 100000u, 50u, 500.0), INVERTER_AVG_ERR_NULL);

    UT_TEST("init, both twins: n_sub outside 1..64, or a frame it does not divide, is ERR_SUB");
    UT_EQ_INT(init_both(false, pp, sp, 100000u, 0u, 500.0), INVERTER_AVG_ERR_SUB);
    UT_EQ_INT(init_both(false, pp, sp, 130000u, INVERTER_AVG_SUB_MAX + 1u, 500.0),
              INVERTER_AVG_ERR_SUB);
    UT_EQ_INT(init_both(false, pp, sp, 100000u, 3u, 500.0), INVERTER_AVG_ERR_SUB);

    UT_TEST("init, both twins: a substep the modulator refuses (50 ns, below 100 ns) is "
            "ERR_PWM; an initial DC-link voltage the stage refuses (-1 V) is ERR_STAGE");
    UT_EQ_INT(init_both(false, pp, sp, 50u, 1u, 500.0), INVERTER_AVG_ERR_PWM);
    UT_EQ_INT(init_both(false, pp, sp, 100000u, 50u, -1.0), INVERTER_AVG_ERR_STAGE);

    UT_TEST("init, both twins: 50 substeps of 2 us in 100 us and 64 substeps (the most) of "
            "2 us in 128 us are accepted and kept");
    UT_EQ_INT(init_both(false, pp, sp, 100000u, 50u, 500.0), INVERTER_AVG_OK);
    UT_EQ_INT(inv_q.n_sub, 50);
    UT_EQ_INT(inv_f.n_sub, 50);
    UT_EQ_INT(init_both(false, pp, sp, 128000u, INVERTER_AVG_SUB_MAX, 0.0), INVERTER_AVG_OK);
    UT_EQ_INT(inv_q.n_sub, 64);
    UT_EQ_INT(inv_f.n_sub, 64);
    suite_inverter_quasi_static();
}

/* ---- The quasi-static stage ---------------------------------------------- */

#define QS_FRAME_NS 800000u
#define QS_C_DC 470e-6
#define QS_G 1.67    /* [S] about the pack's companion */
#define QS_B 1008.0  /* [A] e = b / G = 603.6 V */

static inverter_quasi_static_q qs_q;
static inverter_quasi_static_f32 qs_f;

static double qs_v_q(int32_t x) { return (double)x / 268435456.0 * 1024.0; }

/* The DC references of a zero frequency at phase 0: r = (0, -0.866, 0.866) m. */
static void qs_command(float m) {
    pwm_command_inc_q(&qs_q.mod, (q15_t)(m * 32767.0f), 0u);
    pwm_command_inc_f32(&qs_f.mod, m, 0u);
}

static void suite_inverter_quasi_static(void) {
    const pwm_params *pp = &pwm_params_default;
    inverter_quasi_static_bus_q bq;
    inverter_quasi_static_bus_f32 bf;

    UT_TEST("quasi-static init, both twins: NULL is ERR_NULL, a 50 ns frame ERR_PWM; the bus "
            "starts clamped to [0, 1023] V");
    UT_EQ_INT(inverter_quasi_static_init_q(NULL, pp, QS_FRAME_NS, 600.0), INVERTER_AVG_ERR_NULL);
    UT_EQ_INT(inverter_quasi_static_init_f32(&qs_f, NULL, QS_FRAME_NS, 600.0),
              INVERTER_AVG_ERR_NULL);
    UT_EQ_INT(inverter_quasi_static_init_q(&qs_q, pp, 50u, 600.0), INVERTER_AVG_ERR_PWM);
    UT_EQ_INT(inverter_quasi_static_init_f32(&qs_f, pp, 50u, 600.0), INVERTER_AVG_ERR_PWM);
    UT_EQ_INT(inverter_quasi_static_init_q(&qs_q, pp, QS_FRAME_NS, -5.0), INVERTER_AVG_OK);
    UT_EQ_INT(qs_q.v_dc, 0);
    UT_EQ_INT(inverter_quasi_static_init_f32(&qs_f, pp, QS_FRAME_NS, 2000.0), INVERTER_AVG_OK);
    UT_NEAR((double)qs_f.v_dc, 1023.0, 0.0);

    UT_TEST("bus constants, both twins: alpha = 1 - exp(-T G / C), beta = alpha / G, e = b / G "
            "at 800 us; open (G = 0): alpha 0, beta T / C; a negative G and e above 1023 V count");
    UT_EQ_INT(inverter_quasi_static_battery_q(&qs_q, QS_C_DC, QS_G, QS_B, &bq), 0);
    UT_EQ_INT(inverter_quasi_static_battery_f32(&qs_f, QS_C_DC, QS_G, QS_B, &bf), 0);
    const double alpha = 1.0 - math_exp_f64(-800e-6 * QS_G / QS_C_DC);
    UT_NEAR((double)bq.alpha / 2147483648.0, alpha, 1e-9);
    UT_NEAR((double)bf.alpha, alpha, 1e-7);
    UT_NEAR((double)bq.beta / 16777216.0 * 4.0, alpha / QS_G, 1e-6);
    UT_NEAR((double)bf.beta_ohm, alpha / QS_G, 1e-6);
    UT_NEAR(qs_v_q(bq.e), QS_B / QS_G, 1e-5);
    UT_EQ_INT(inverter_quasi_static_battery_f32(&qs_f, QS_C_DC, 0.0, 0.0, &bf), 0);
    UT_NEAR((double)bf.alpha, 0.0, 0.0);
    UT_NEAR((double)bf.beta_ohm, 800e-6 / QS_C_DC, 1e-6);
    UT_EQ_INT(inverter_quasi_static_battery_q(&qs_q, QS_C_DC, -1.0, 0.0, &bq), 1);
    UT_EQ_INT(bq.alpha, 0);
    UT_EQ_INT(inverter_quasi_static_battery_q(&qs_q, QS_C_DC, 1.0, 2000.0, &bq), 1);
    UT_NEAR(qs_v_q(bq.e), 1023.0, 1e-5);

    UT_TEST("step, both twins, with no load current: the bus approaches e by (1 - alpha) per "
            "frame from 500 V; m = 0 gives zero terminal voltages");
    UT_EQ_INT(inverter_quasi_static_init_q(&qs_q, pp, QS_FRAME_NS, 500.0), INVERTER_AVG_OK);
    UT_EQ_INT(inverter_quasi_static_init_f32(&qs_f, pp, QS_FRAME_NS, 500.0), INVERTER_AVG_OK);
    (void)inverter_quasi_static_battery_q(&qs_q, QS_C_DC, QS_G, QS_B, &bq);
    (void)inverter_quasi_static_battery_f32(&qs_f, QS_C_DC, QS_G, QS_B, &bf);
    double v_ref = 500.0;
    for (int k = 0; k < 3; k++) {
        inverter_quasi_static_step_q(&qs_q, &bq, 0, 0);
        inverter_quasi_static_step_f32(&qs_f, &bf, 0.0f, 0.0f);
        v_ref += alpha * (QS_B / QS_G - v_ref);
        UT_NEAR(qs_v_q(qs_q.v_dc), v_ref, 1e-4);
        UT_NEAR((double)qs_f.v_dc, v_ref, 1e-3);
    }
    UT_EQ_INT(qs_q.u[0], 0);
    UT_NEAR((double)qs_f.u[1], 0.0, 0.0);

    UT_TEST("step, both twins, m = 1 at zero frequency, currents (0, -50, 50) A held: i_dc = "
            "43.3 A, the bus settles at e - i_dc / G, u_b = -0.433 v_dc, v_dc i_dc = sum u i; "
            "open, the capacitor loses T i_dc / C in one frame");
    qs_command(1.0f);
    const int32_t i50 = (int32_t)(50.0 / 256.0 * 268435456.0);
    for (int k = 0; k < 40; k++) {
        inverter_quasi_static_step_q(&qs_q, &bq, 0, -i50);
        inverter_quasi_static_step_f32(&qs_f, &bf, 0.0f, -50.0f);
    }
    const double i_dc = 25.0 * 1.7320508075688772;
    const double v_set = QS_B / QS_G - i_dc / QS_G;
    UT_NEAR(qs_v_q(qs_q.i_dc) / 4.0, i_dc, 1e-2); /* m = 32767 / 32768, table sine */
    UT_NEAR((double)qs_f.i_dc, i_dc, 2e-3);
    UT_NEAR(qs_v_q(qs_q.v_dc), v_set, 5e-3); /* Q15 cos 0 = 1 - 2^-15 in the turn */
    UT_NEAR((double)qs_f.v_dc, v_set, 2e-3);
    UT_NEAR((double)qs_f.u[1], -0.25 * 1.7320508075688772 * (double)qs_f.v_dc, 2e-3);
    UT_NEAR((double)qs_f.v_dc * (double)qs_f.i_dc, (double)qs_f.u[1] * -50.0 +
            (double)(-qs_f.u[0] - qs_f.u[1]) * 50.0, 0.05);
    (void)inverter_quasi_static_battery_q(&qs_q, QS_C_DC, 0.0, 0.0, &bq);
    (void)inverter_quasi_static_battery_f32(&qs_f, QS_C_DC, 0.0, 0.0, &bf);
    const double v0 = (double)qs_f.v_dc;
    inverter_quasi_static_step_q(&qs_q, &bq, 0, -i50);
    inverter_quasi_static_step_f32(&qs_f, &bf, 0.0f, -50.0f);
    UT_NEAR((double)qs_f.v_dc, v0 - 800e-6 * i_dc / QS_C_DC, 2e-3);
    UT_NEAR(qs_v_q(qs_q.v_dc), v0 - 800e-6 * i_dc / QS_C_DC, 2e-2);
    UT_EQ_INT(qs_q.sat_count, 0);
    UT_EQ_INT(qs_f.sat_count, 0);
}
