/*
 * The unit-test harness: one header, no dependencies beyond src/. The same
 * test files compile for the host and for the firmware images; results go to
 * the HAL console, and the runner ends with the HAL exit status (0 when every
 * check passed), which QEMU turns into its own exit code.
 *
 * A test file tests/unit/test_NAME.c defines `void suite_NAME(void)`; the
 * build finds the files and generates the list of suites. Inside a suite,
 * UT_TEST("what property, against what reference") opens a test; every check
 * after it counts towards that test, which passes when all its checks pass.
 */
#ifndef UUV_UT_H
#define UUV_UT_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

void ut_suite_begin(const char *name);
void ut_test_begin(const char *name);
bool ut_check(bool ok, const char *file, int line, const char *expr);
bool ut_check_near(double actual, double expected, double tolerance, const char *file,
                   int line, const char *expr);
bool ut_check_int(long long actual, long long expected, const char *file, int line,
                  const char *expr);
/* Prints an informational line, indented under the current test. */
void ut_info(const char *format, ...) __attribute__((format(printf, 1, 2)));

/* Length of a NUL-terminated text, and whether two texts are equal (no libc on targets). */
size_t ut_text_len(const char *s);
bool ut_text_equal(const char *a, const char *b);

/*
 * Deterministic test operands, the same on every host and target: a 32-bit
 * xorshift (13, 17, 5; state must not be 0), a draw uniform in [-lim, lim]
 * from it (0 <= lim < 2^31), and a 64-bit LCG (Knuth's MMIX constants).
 */
uint32_t ut_rand_u32(uint32_t *state);
int32_t ut_rand_within(uint32_t *state, int32_t lim);
uint64_t ut_rand_u64(uint64_t *state);

/* Ends the run: prints "N passed, N failed" and returns the failed count. */
unsigned ut_finish(void);

#define UT_TEST(name) ut_test_begin(name)
#define UT_CHECK(cond) ut_check((cond), __FILE__, __LINE__, #cond)
#define UT_NEAR(actual, expected, tol)                                                   \
    ut_check_near((double)(actual), (double)(expected), (double)(tol), __FILE__, __LINE__, \
                  #actual " ~ " #expected)
#define UT_EQ_INT(actual, expected)                                                      \
    ut_check_int((long long)(actual), (long long)(expected), __FILE__, __LINE__,          \
                 #actual " == " #expected)

#endif /* UUV_UT_H */
