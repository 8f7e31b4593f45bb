/*
 * Checks of the harness and the formatter it prints with. The failing test
 * is compiled only into the "must fail" build (UT_PROVE_FAILURE), which the
 * test run uses to show that a failing check fails the whole run.
 */
#include <stddef.h>

#include "util/fmt.h"
#include "ut.h"

static int text_equal(const char *a, const char *b) {
    size_t i = 0;
    for (; a[i] != '\0' && a[i] == b[i]; i++) {
    }
    return a[i] == b[i];
}

#define FMT_IS(expected, ...)                                \
    do {                                                     \
        char out_[96];                                       \
        (void)fmt_format(out_, sizeof out_, __VA_ARGS__);    \
        if (!UT_CHECK(text_equal(out_, expected))) {         \
            ut_info("got \"%s\", expected \"%s\"", out_, expected); \
        }                                                    \
    } while (0)

void suite_harness(void);

void suite_harness(void) {
    UT_TEST("formatter: integers, widths and flags as C99 printf");
    FMT_IS("42 -7 4294967295 ff FF", "%d %i %u %x %X", 42, -7, 4294967295u, 255u, 255u);
    FMT_IS("-9223372036854775807 18446744073709551615", "%lld %llu", -9223372036854775807LL,
           18446744073709551615ULL);
    FMT_IS("[  12][12  ][0012][-012]", "[%4d][%-4d][%04d][%04d]", 12, 12, 12, -12);
    FMT_IS("ab|x|%|abc", "%.2s|%c|%%|%.*s", "abc", 'x', 3, "abcdef");

    UT_TEST("formatter: doubles as C99 printf for exactly representable values");
    FMT_IS("1.5 -0.25 100 1e+20 0.001", "%g %g %g %g %g", 1.5, -0.25, 100.0, 1e20, 0.001);
    FMT_IS("3.140 2.5e-03 -0", "%.3f %.1e %g", 3.14, 0.0025, -0.0);
    FMT_IS("0.333333333333333", "%.15g", 1.0 / 3.0);
    FMT_IS("nan inf -inf", "%g %g %g", 0.0 / 0.0 + 0.0, 1e308 * 10.0, -1e308 * 10.0);

    UT_TEST("formatter: output is cut to the buffer and NUL-terminated");
    char small[5];
    size_t n = fmt_format(small, sizeof small, "%s", "abcdefgh");
    UT_EQ_INT(n, 8);
    UT_CHECK(text_equal(small, "abcd"));

    UT_TEST("harness: passing checks return true");
    UT_CHECK(UT_NEAR(1.0, 1.0 + 1e-12, 1e-9));
    UT_CHECK(UT_EQ_INT(3, 3));

#ifdef UT_PROVE_FAILURE
    UT_TEST("harness: this test fails on purpose (the must-fail build)");
    UT_CHECK(1 + 1 == 3);
#endif
}
