/*
 * The power stage's set-up and battery conversion at the edges of their
 * ranges, both twins: every parameter that is not positive and finite, a
 * step above 1 ms, NULL arguments, and each clamp of the battery companion
 * (a conductance or source that is not finite, a source voltage below zero
 * or beyond the 1024 V range, a forward-Euler factor T G / C_dc above its
 * limit). The references are power_stage.h's documented statuses and
 * clamps and the companion's own formulas, e = b / G and kg = T G / C_dc.
 */
#include <stddef.h>

#include "models/drive/inverter/power_stage.h"
#include "ut.h"

void suite_power_stage_paths(void);

#define BIG 1.0e301 /* beyond the 1e300 the checks take as "not finite" */

/* Both twins' status for one parameter set (they must agree). */
static ps_status init_both(const power_stage_params *p, uint32_t step_ns) {
    power_stage_q q;
    power_stage_f32 f;
    ps_status sq = power_stage_init_q(&q, p, step_ns, 600.0);
    ps_status sf = power_stage_init_f32(&f, p, step_ns, 600.0);
    UT_EQ_INT(sq, sf);
    return sf;
}

static void test_init(void) {
    UT_TEST("init, both twins: each capacitance, inductance and damping parameter that is "
            "zero or huge, and a series resistance that is negative or huge, is PS_ERR_PARAM");
    power_stage_params p = power_stage_params_default;
    UT_EQ_INT(init_both(&p, 2000u), PS_OK);
    double *fields[] = {&p.c_dc_f, &p.l_h, &p.c_f, &p.r_d_ohm, &p.c_d_f};
    for (int k = 0; k < 5; k++) {
        p = power_stage_params_default;
        *fields[k] = 0.0;
        UT_EQ_INT(init_both(&p, 2000u), PS_ERR_PARAM);
        p = power_stage_params_default;
        *fields[k] = BIG;
        UT_EQ_INT(init_both(&p, 2000u), PS_ERR_PARAM);
    }
    p = power_stage_params_default;
    p.r_l_ohm = BIG;
    UT_EQ_INT(init_both(&p, 2000u), PS_ERR_PARAM);
    p.r_l_ohm = 0.0; /* an ideal inductor is allowed */
    UT_EQ_INT(init_both(&p, 2000u), PS_OK);

    UT_TEST("init, both twins: a step of 1 ms is the longest accepted, one nanosecond more "
            "is PS_ERR_STEP; a NULL instance or parameter set is PS_ERR_NULL");
    power_stage_f32 f;
    power_stage_q q;
    UT_EQ_INT(power_stage_init_f32(&f, &power_stage_params_default, 1000000u, 600.0), PS_OK);
    UT_EQ_INT(power_stage_init_f32(&f, &power_stage_params_default, 1000001u, 600.0),
              PS_ERR_STEP);
    UT_EQ_INT(power_stage_init_q(&q, &power_stage_params_default, 1000001u, 600.0),
              PS_ERR_STEP);
    UT_EQ_INT(power_stage_init_q(&q, NULL, 2000u, 600.0), PS_ERR_NULL);
    UT_EQ_INT(power_stage_init_f32(NULL, &power_stage_params_default, 2000u, 600.0),
              PS_ERR_NULL);
    UT_EQ_INT(power_stage_init_f32(&f, NULL, 2000u, 600.0), PS_ERR_NULL);
}

static void test_battery(void) {
    power_stage_q q;
    power_stage_f32 f;
    ps_battery_q bq;
    ps_battery_f32 bf;
    UT_CHECK(power_stage_init_q(&q, &power_stage_params_default, 2000u, 600.0) == PS_OK);
    UT_CHECK(power_stage_init_f32(&f, &power_stage_params_default, 2000u, 600.0) == PS_OK);

    UT_TEST("battery: a conductance or source term beyond 1e300 is refused as one clamp and "
            "leaves the pack disconnected (all zero), in both twins");
    const double bad[3][2] = {{BIG, 1200.0}, {2.0, BIG}, {2.0, -BIG}};
    for (int k = 0; k < 3; k++) {
        UT_EQ_INT(power_stage_battery_q(&q, bad[k][0], bad[k][1], &bq), 1);
        UT_CHECK(bq.e == 0 && bq.kg == 0 && bq.g == 0);
        UT_EQ_INT(power_stage_battery_f32(&f, bad[k][0], bad[k][1], &bf), 1);
        UT_CHECK(bf.e_v == 0.0f && bf.kg == 0.0f && bf.g_s == 0.0f);
    }

    UT_TEST("battery: a source voltage b / G below 0 V is clamped to 0 V and one above the "
            "1024 V range to just below it, each counted once; G is kept");
    UT_EQ_INT(power_stage_battery_f32(&f, 2.0, -100.0, &bf), 1);
    UT_NEAR(bf.e_v, 0.0, 0.0);
    UT_NEAR(bf.g_s, 2.0, 0.0);
    UT_EQ_INT(power_stage_battery_q(&q, 2.0, -100.0, &bq), 1);
    UT_EQ_INT(bq.e, 0);
    UT_EQ_INT(power_stage_battery_f32(&f, 2.0, 2.0 * 1500.0, &bf), 1);
    UT_NEAR(bf.e_v, 1024.0, 1e-3);
    UT_CHECK(bf.e_v <= 1024.0f);
    UT_EQ_INT(power_stage_battery_q(&q, 2.0, 2.0 * 1500.0, &bq), 1);
    UT_NEAR((double)bq.e / (double)PS_Q28_ONE, 1.0, 1e-8);
    UT_CHECK(bq.e <= PS_Q28_ONE);

    UT_TEST("battery: at a 1 ms step, kg = T G / C_dc = 1e-3 x 2 / 470e-6 = 4.3 is beyond "
            "the forward-Euler limit and clamped to just below 0.5, counted once");
    UT_CHECK(power_stage_init_q(&q, &power_stage_params_default, 1000000u, 600.0) ==
             PS_ERR_FIXED_RANGE);
    UT_CHECK(power_stage_init_f32(&f, &power_stage_params_default, 1000000u, 600.0) == PS_OK);
    UT_EQ_INT(power_stage_battery_f32(&f, 2.0, 1200.0, &bf), 1);
    UT_NEAR(bf.kg, 0.5, 1e-3);
    UT_CHECK(bf.kg < 0.5f);
    UT_NEAR(bf.e_v, 600.0, 1e-4);
}

void suite_power_stage_paths(void) {
    test_init();
    test_battery();
}
