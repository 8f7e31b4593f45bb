/*
 * The unit-test harness (see ut.h). A test is counted once, as passed or
 * failed, when the next test begins or the run finishes; each failed check
 * prints its file, line and expression.
 */
#include "ut.h"

#include <stdarg.h>

#include "util/fmt.h"

static struct {
    const char *name;   /* current test, NULL before the first */
    unsigned failures;  /* failed checks in the current test */
    unsigned passed;    /* tests */
    unsigned failed;    /* tests */
} ut_state;

static void ut_close_test(void) {
    if (ut_state.name == NULL) {
        return;
    }
    if (ut_state.failures == 0u) {
        ut_state.passed++;
        fmt_print("  ok    %s\n", ut_state.name);
    } else {
        ut_state.failed++;
        fmt_print("  FAIL  %s\n", ut_state.name);
    }
    ut_state.name = NULL;
    ut_state.failures = 0u;
}

void ut_suite_begin(const char *name) {
    ut_close_test();
    fmt_print("suite %s\n", name);
}

void ut_test_begin(const char *name) {
    ut_close_test();
    ut_state.name = name;
}

static void ut_fail_header(const char *file, int line) {
    if (ut_state.name == NULL) {
        /* A check outside any test counts as a test of its own. */
        ut_state.name = "(check outside a test)";
    }
    ut_state.failures++;
    fmt_print("        %s:%d: ", file, line);
}

size_t ut_text_len(const char *s) {
    size_t n = 0;
    while (s[n] != '\0') {
        n++;
    }
    return n;
}

bool ut_text_equal(const char *a, const char *b) {
    size_t i = 0;
    while (a[i] != '\0' && a[i] == b[i]) {
        i++;
    }
    return a[i] == b[i];
}

uint32_t ut_rand_u32(uint32_t *state) {
    uint32_t x = *state;
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    *state = x;
    return x;
}

int32_t ut_rand_within(uint32_t *state, int32_t lim) {
    return (int32_t)(ut_rand_u32(state) % (2u * (uint32_t)lim + 1u)) - lim;
}

uint64_t ut_rand_u64(uint64_t *state) {
    *state = *state * 6364136223846793005u + 1442695040888963407u;
    return *state;
}

bool ut_check(bool ok, const char *file, int line, const char *expr) {
    if (!ok) {
        ut_fail_header(file, line);
        fmt_print("check failed: %s\n", expr);
    }
    return ok;
}

bool ut_check_near(double actual, double expected, double tolerance, const char *file, int line,
                   const char *expr) {
    double diff = actual - expected;
    if (diff < 0.0) {
        diff = -diff;
    }
    /* Written so that a NaN on either side fails. */
    bool ok = diff <= tolerance;
    if (!ok) {
        ut_fail_header(file, line);
        fmt_print("%s: got %.17g, expected %.17g (tolerance %.3g, off by %.3g)\n", expr, actual,
                  expected, tolerance, diff);
    }
    return ok;
}

bool ut_check_int(long long actual, long long expected, const char *file, int line,
                  const char *expr) {
    bool ok = actual == expected;
    if (!ok) {
        ut_fail_header(file, line);
        fmt_print("%s: got %lld, expected %lld\n", expr, actual, expected);
    }
    return ok;
}

void ut_info(const char *format, ...) {
    char text[200];
    va_list args;
    va_start(args, format);
    size_t n = fmt_vformat(text, sizeof text, format, args);
    va_end(args);
    (void)n;
    fmt_print("        %s\n", text);
}

unsigned ut_finish(void) {
    ut_close_test();
    fmt_print("%u passed, %u failed\n", ut_state.passed, ut_state.failed);
    return ut_state.failed;
}
