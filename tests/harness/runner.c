/*
 * The test program's entry point, the same on every port: runs every suite
 * the build found (suites.inc is generated from tests/unit/test_*.c) and
 * exits with the number of failed tests as its status (capped at 255 by the
 * emulator's exit code, so it is reported as 0 or 1).
 */
#include "hal/hal.h"
#include "util/fmt.h"
#include "uuv_config.h"
#include "ut.h"

#define UT_SUITE(name) void suite_##name(void);
#include "suites.inc"
#undef UT_SUITE

int main(void);

int main(void) {
    fmt_print("uuvsim unit tests, %s build\n", UUV_NUMERIC_NAME);
#define UT_SUITE(name)   \
    ut_suite_begin(#name); \
    suite_##name();
#include "suites.inc"
#undef UT_SUITE
    unsigned failed = ut_finish();
    hal_exit(failed == 0u ? 0 : 1);
}
