/*
 * The formatter (util/fmt.h) beyond the basic cases of test_harness.c:
 * long arguments, exponents of every size and rounding that carries into
 * the exponent, the precision limit of 17, %g's choice of notation, and
 * the unusual inputs (NULL string, unknown conversion, a format that ends
 * inside a conversion, a zero capacity). References are the outputs C99
 * printf gives for the same exactly representable values, or the limits
 * fmt.h states.
 */
#include <stdarg.h>
#include <stddef.h>

#include "util/fmt.h"
#include "ut.h"

void suite_fmt(void);

/* Formats into a buffer and compares with the expected text. */
static char out[96];

#define FMT_IS(expected, ...)                                           \
    do {                                                                \
        (void)fmt_format(out, sizeof out, __VA_ARGS__);                 \
        if (!UT_CHECK(ut_text_equal(out, expected))) {                     \
            ut_info("got \"%s\", expected \"%s\"", out, expected);      \
        }                                                               \
    } while (0)

static void test_integers(void) {
    UT_TEST("formatter: the l modifier for d, u and x, as C99 printf");
    FMT_IS("-5 7 ff -2147483648", "%ld %lu %lx %ld", -5L, 7UL, 255UL, -2147483647L - 1L);
}

static void test_doubles(void) {
    UT_TEST("formatter: %e of magnitudes beyond 1e16 and below 1e-16, three-digit exponents, "
            "and rounding that carries into the exponent (9.999 -> 1.00e+01), as C99 printf");
    FMT_IS("1.000000e+20 1.000000e-20", "%e %e", 1e20, 1e-20);
    FMT_IS("1.000000e+100 2.5e-300", "%e %.1e", 1e100, 2.5e-300);
    FMT_IS("1.00e+01 -1.0e+03", "%.2e %.1e", 9.999, -999.96);

    UT_TEST("formatter: the precision is limited to 17 (fmt.h): %.20e and %.17e of 1 give 17 "
            "significant digits, %.20f gives 17 decimals");
    FMT_IS("1.0000000000000000e+00", "%.20e", 1.0);
    FMT_IS("5.0000000000000000e-01", "%.17e", 0.5);
    FMT_IS("0.50000000000000000", "%.20f", 0.5);

    UT_TEST("formatter: %f beyond 17 digits falls back to the exponent form (fmt.c): 1e20, "
            "and 1e15 with 6 decimals");
    FMT_IS("1.000000e+20 1.000000e+15", "%f %.6f", 1e20, 1e15);

    UT_TEST("formatter: %g with precision 0 keeps one digit and an exponent below -4 uses "
            "the exponent form; %.f rounds to an integer; as C99 printf");
    FMT_IS("1e+02 1e-07 0.0001", "%.0g %g %g", 123.0, 1e-7, 1e-4);
    FMT_IS("3 -2", "%.f %.f", 2.75, -1.5);
}

/*
 * fmt_vformat without the printf format check: the cases below are formats
 * a compiler would rightly warn about, which the formatter must still handle.
 */
static size_t fmt_unchecked(char *buf, size_t cap, const char *format, ...) {
    va_list args;
    va_start(args, format);
    size_t n = fmt_vformat(buf, cap, format, args);
    va_end(args);
    return n;
}

static void test_unusual(void) {
    UT_TEST("formatter: a NULL string prints (null); an unknown conversion is copied; a "
            "format that ends inside a conversion stops there");
    char buf[16];
    size_t n = fmt_unchecked(buf, sizeof buf, "<%s>", (const char *)NULL);
    UT_CHECK(ut_text_equal(buf, "<(null)>"));
    UT_EQ_INT(n, 8);
    n = fmt_unchecked(buf, sizeof buf, "%q|%");
    UT_CHECK(ut_text_equal(buf, "%q|"));
    UT_EQ_INT(n, 3);
    n = fmt_unchecked(buf, sizeof buf, "50%.");
    UT_CHECK(ut_text_equal(buf, "50"));
    UT_EQ_INT(n, 2);

    UT_TEST("formatter: the '0' flag pads after a leading sign (fmt.c), for text too; an "
            "empty text is all padding");
    (void)fmt_unchecked(out, sizeof out, "[%05s][%04s][%03s]", "+12", "-x", "");
    UT_CHECK(ut_text_equal(out, "[+0012][-00x][000]"));

    UT_TEST("formatter: with capacity 0 nothing is written and the full length is returned");
    buf[0] = 'x';
    n = fmt_format(buf, 0u, "%d%s", 123, "abc");
    UT_EQ_INT(n, 6);
    UT_CHECK(buf[0] == 'x');
}

void suite_fmt(void) {
    test_integers();
    test_doubles();
    test_unusual();
}
