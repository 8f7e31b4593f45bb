/*
 * The heading and depth autopilots (autopilot.h): the signs of their laws
 * against the vessel's conventions (a positive rudder turns to port, a
 * positive stern plane dives), the heading error taken the short way round,
 * and the fins' angle and rate limits. The closed loop on the vessel is
 * checked in suite exec_paths.
 */
#include "autopilot.h"
#include "math/umath.h"
#include "ut.h"

void suite_autopilot(void);

#define DEG (MATH_PI_F64 / 180.0)

static void zero(double x[VESSEL_NSTATES]) {
    for (int i = 0; i < VESSEL_NSTATES; i++) {
        x[i] = 0.0;
    }
}

static void test_signs(void) {
    autopilot a;
    double x[VESSEL_NSTATES];
    UT_TEST("autopilot: both axes start off and leave the fins alone");
    autopilot_init(&a);
    zero(x);
    double rudder = 0.1, stern = -0.1;
    autopilot_step(&a, x, 0.1, &rudder, &stern);
    UT_NEAR(rudder, 0.1, 0.0);
    UT_NEAR(stern, -0.1, 0.0);

    UT_TEST("autopilot: a heading to starboard gives a negative rudder (positive turns to "
            "port), a heading to port a positive one");
    autopilot_set_heading(&a, 30.0 * DEG);
    rudder = 0.0;
    autopilot_step(&a, x, 0.1, &rudder, &stern);
    UT_CHECK(rudder < 0.0);
    autopilot_set_heading(&a, -30.0 * DEG);
    rudder = 0.0;
    autopilot_step(&a, x, 0.1, &rudder, &stern);
    UT_CHECK(rudder > 0.0);

    UT_TEST("autopilot: the heading error goes the short way round: from psi = 350 deg "
            "(unwrapped 710 deg) to 10 deg is a turn to starboard");
    x[VESSEL_PSI_RAD] = 710.0 * DEG;
    autopilot_set_heading(&a, 10.0 * DEG);
    rudder = 0.0;
    autopilot_step(&a, x, 0.1, &rudder, &stern);
    UT_CHECK(rudder < 0.0);
    UT_NEAR(rudder, -a.p.fin_rate_radps * 0.1, 1e-15);

    UT_TEST("autopilot: deeper than the vehicle gives a positive stern plane (nose down), "
            "shallower a negative one; stern_rad unchanged by the heading axis");
    zero(x);
    x[VESSEL_Z_M] = 5.0;
    autopilot_init(&a);
    autopilot_set_depth(&a, 10.0);
    stern = 0.0;
    rudder = 0.25;
    autopilot_step(&a, x, 0.1, &rudder, &stern);
    UT_CHECK(stern > 0.0);
    UT_NEAR(rudder, 0.25, 0.0);
    autopilot_set_depth(&a, 1.0);
    stern = 0.0;
    autopilot_step(&a, x, 0.1, &rudder, &stern);
    UT_CHECK(stern < 0.0);
}

static void test_limits(void) {
    autopilot a;
    double x[VESSEL_NSTATES];
    UT_TEST("autopilot: a fin command moves by at most rate * dt per step and stops at the "
            "angle limit (15 deg/s, 20 deg)");
    autopilot_init(&a);
    zero(x);
    autopilot_set_heading(&a, 170.0 * DEG);
    double rudder = 0.0, stern = 0.0, prev = 0.0, worst_step = 0.0;
    for (int k = 0; k < 40; k++) {
        autopilot_step(&a, x, 0.1, &rudder, &stern);
        double d = prev - rudder;
        worst_step = (d > worst_step) ? d : worst_step;
        prev = rudder;
    }
    UT_NEAR(worst_step, 15.0 * DEG * 0.1, 1e-12);
    UT_NEAR(rudder, -20.0 * DEG, 1e-15);
    UT_NEAR(a.p.fin_limit_rad, 20.0 * DEG, 1e-15);

    UT_TEST("autopilot: the depth error is integrated only within 1 m of the reference");
    autopilot_set_depth(&a, 20.0);
    x[VESSEL_Z_M] = 5.0;
    autopilot_step(&a, x, 0.1, &rudder, &stern);
    UT_NEAR(a.depth_int_ms, 0.0, 0.0);
    x[VESSEL_Z_M] = 19.5;
    autopilot_step(&a, x, 0.1, &rudder, &stern);
    UT_NEAR(a.depth_int_ms, 0.05, 1e-15);
}

void suite_autopilot(void) {
    test_signs();
    test_limits();
}
