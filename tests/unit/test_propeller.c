/*
 * The propeller against hand-computed values of the seed paper's formulas
 * (reference README items 2 and 3): thrust T = Tnn |w| w + Tnu |w| u and the
 * shaft load torque -I0 dw/dt - 0.5 rho C_D w |w| R^3, about 44 N m at
 * 1300 rpm and 58 N m at 1500 rpm.
 */
#include <stddef.h>

#include "math/umath.h"
#include "models/propeller/propeller.h"
#include "ut.h"

void suite_propeller(void);

#define RAD_PER_RPM (MATH_PI_F64 / 30.0)

static propeller_model default_model(void) {
    propeller_model m;
    UT_CHECK(propeller_init(&m, &propeller_params_default) == PROPELLER_OK);
    return m;
}

static void test_thrust(void) {
    UT_TEST("thrust: Tnn = rho D^4 alpha1 = 0.1577475, Tnu = rho D^3 alpha2 = -4.428 "
            "(hand values), T = Tnn |w| w + Tnu |w| u");
    propeller_model m = default_model();
    UT_NEAR(m.tnn, 0.1577475, 1e-12);
    UT_NEAR(m.tnu, -4.428, 1e-12);
    const double w = 1000.0 * RAD_PER_RPM;
    /* 1000 rpm at rest: 0.1577475 * 104.72^2 = 1729.9 N. */
    UT_NEAR(propeller_thrust_f64(&m, w, 0.0), 0.1577475 * w * w, 1e-9);
    UT_NEAR(propeller_thrust_f64(&m, w, 2.0), 0.1577475 * w * w - 4.428 * w * 2.0, 1e-9);
    UT_NEAR(propeller_surge_force_f64(&m, w, 2.0), 0.7 * (0.1577475 * w * w - 4.428 * w * 2.0),
            1e-9);
    UT_TEST("thrust: reversed shaft pushes astern (T(-w, 0) = -T(w, 0))");
    UT_NEAR(propeller_thrust_f64(&m, -w, 0.0), -0.1577475 * w * w, 1e-9);
    UT_CHECK(propeller_thrust_f64(&m, -w, 1.0) < propeller_thrust_f64(&m, -w, 0.0));
}

static void test_torque(void) {
    propeller_model m = default_model();
    UT_TEST("load torque: 0.5 rho C_D R^3 w^2 = 43.885 N m (5.97 kW) at 1300 rpm, "
            "58.427 N m (9.18 kW) at 1500 rpm");
    const double w13 = 1300.0 * RAD_PER_RPM;
    const double w15 = 1500.0 * RAD_PER_RPM;
    const double q13 = propeller_drag_torque_f64(&m, w13);
    const double q15 = propeller_drag_torque_f64(&m, w15);
    UT_NEAR(q13, -43.88489217068335, 1e-9);
    UT_NEAR(q15, -58.4266315881879, 1e-9);
    ut_info("drag torque %.4f N m at 1300 rpm (%.1f W), %.4f N m at 1500 rpm (%.1f W)", -q13,
            -q13 * w13, -q15, -q15 * w15);

    UT_TEST("load torque: opposes the rotation in reverse too (odd in w)");
    UT_NEAR(propeller_drag_torque_f64(&m, -w13), 43.88489217068335, 1e-9);
    UT_CHECK(propeller_drag_torque_f64(&m, 0.0) == 0.0);

    UT_TEST("load torque: -I0 w_dot adds the inertia (I0 = 0.011 kg m^2)");
    UT_NEAR(m.inertia_kgm2, 0.011, 0.0);
    UT_NEAR(propeller_load_torque_f64(&m, w13, 100.0), -0.011 * 100.0 - 43.88489217068335,
            1e-9);

    UT_TEST("load torque: the float twin agrees with the double version to 1e-6 relative");
    const float wf = 136.135681655558f; /* 1300 rpm */
    const float qf = propeller_drag_torque_f32(&m, wf);
    const double qd = propeller_drag_torque_f64(&m, (double)wf);
    UT_NEAR((double)qf, qd, 1e-6 * 43.9);
    UT_NEAR((double)propeller_drag_torque_f32(&m, -wf), -qd, 1e-6 * 43.9);
}

static void test_init(void) {
    UT_TEST("init: refuses NULL, a non-positive diameter, an efficiency above 1, a negative "
            "inertia and a NaN");
    propeller_model m;
    propeller_params p = propeller_params_default;
    UT_CHECK(propeller_init(NULL, &p) == PROPELLER_ERR_NULL);
    UT_CHECK(propeller_init(&m, NULL) == PROPELLER_ERR_NULL);
    p.diameter_m = 0.0;
    UT_CHECK(propeller_init(&m, &p) == PROPELLER_ERR_PARAM);
    p = propeller_params_default;
    p.efficiency = 1.5;
    UT_CHECK(propeller_init(&m, &p) == PROPELLER_ERR_PARAM);
    p = propeller_params_default;
    p.inertia_kgm2 = -1.0;
    UT_CHECK(propeller_init(&m, &p) == PROPELLER_ERR_PARAM);
    volatile double zero = 0.0;
    p = propeller_params_default;
    p.alpha2 = zero / zero;
    UT_CHECK(propeller_init(&m, &p) == PROPELLER_ERR_PARAM);

    UT_TEST("init: refuses a non-positive density and efficiency and a negative drag "
            "coefficient; accepts efficiency 1, C_D 0 and I0 0 (inclusive bounds), giving "
            "k_drag = 0");
    p = propeller_params_default;
    p.rho_kgpm3 = -1025.0;
    UT_CHECK(propeller_init(&m, &p) == PROPELLER_ERR_PARAM);
    p = propeller_params_default;
    p.efficiency = 0.0;
    UT_CHECK(propeller_init(&m, &p) == PROPELLER_ERR_PARAM);
    p = propeller_params_default;
    p.drag_coeff = -1e-3;
    UT_CHECK(propeller_init(&m, &p) == PROPELLER_ERR_PARAM);
    p = propeller_params_default;
    p.efficiency = 1.0;
    p.drag_coeff = 0.0;
    p.inertia_kgm2 = 0.0;
    UT_CHECK(propeller_init(&m, &p) == PROPELLER_OK);
    UT_NEAR(m.k_drag, 0.0, 0.0);
    UT_NEAR(propeller_drag_torque_f64(&m, 150.0), 0.0, 0.0);
}

void suite_propeller(void) {
    test_thrust();
    test_torque();
    test_init();
}
