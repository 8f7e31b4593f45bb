/*
 * The small helpers of math/umath.h at their edges: minimum and maximum
 * ignore a NaN argument and keep the first of equal ones (C99 fmin/fmax, as
 * umath.h documents), clamping limits to each bound and passes a NaN through.
 * The references are those documented rules, checked by bit pattern.
 */
#include "math/umath.h"
#include "ut.h"

void suite_math_paths(void);

static void test_min_max(void) {
    const double nan64 = math_nan_f64();
    const float nan32 = math_nan_f32();

    UT_TEST("min and max, double: a NaN first or second argument gives the other one");
    UT_NEAR(math_min_f64(nan64, 2.0), 2.0, 0.0);
    UT_NEAR(math_min_f64(2.0, nan64), 2.0, 0.0);
    UT_NEAR(math_max_f64(nan64, -2.0), -2.0, 0.0);
    UT_NEAR(math_max_f64(-2.0, nan64), -2.0, 0.0);
    UT_NEAR(math_max_f64(1.0, 3.0), 3.0, 0.0);
    UT_NEAR(math_max_f64(3.0, 1.0), 3.0, 0.0);

    UT_TEST("min and max, float: the same rules, and of -0 and +0 the first is returned");
    UT_NEAR(math_min_f32(nan32, 2.0f), 2.0, 0.0);
    UT_NEAR(math_min_f32(2.0f, nan32), 2.0, 0.0);
    UT_NEAR(math_min_f32(1.0f, 3.0f), 1.0, 0.0);
    UT_NEAR(math_min_f32(3.0f, 1.0f), 1.0, 0.0);
    UT_NEAR(math_max_f32(nan32, -2.0f), -2.0, 0.0);
    UT_NEAR(math_max_f32(-2.0f, nan32), -2.0, 0.0);
    UT_NEAR(math_max_f32(1.0f, 3.0f), 3.0, 0.0);
    UT_NEAR(math_max_f32(3.0f, 1.0f), 3.0, 0.0);
    UT_CHECK(math_signbit_f32(math_min_f32(-0.0f, 0.0f)));
    UT_CHECK(!math_signbit_f32(math_max_f32(0.0f, -0.0f)));
}

static void test_clamp(void) {
    UT_TEST("clamp, float and double: below, inside and above [lo, hi]; a NaN stays NaN");
    UT_NEAR(math_clamp_f32(-5.0f, -1.0f, 1.0f), -1.0, 0.0);
    UT_NEAR(math_clamp_f32(0.25f, -1.0f, 1.0f), 0.25, 0.0);
    UT_NEAR(math_clamp_f32(5.0f, -1.0f, 1.0f), 1.0, 0.0);
    UT_CHECK(math_isnan_f32(math_clamp_f32(math_nan_f32(), -1.0f, 1.0f)));
    UT_NEAR(math_clamp_f64(-5.0, -1.0, 1.0), -1.0, 0.0);
    UT_NEAR(math_clamp_f64(5.0, -1.0, 1.0), 1.0, 0.0);
    UT_CHECK(math_isnan_f64(math_clamp_f64(math_nan_f64(), -1.0, 1.0)));
}

void suite_math_paths(void) {
    test_min_max();
    test_clamp();
}
