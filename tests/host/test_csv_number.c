/*
 * Host test of the desk's number text (csv_format_number, ports/linux/
 * csv_out.c) against its definition: the first of printf's "%.15g",
 * "%.16g" and "%.17g" that reads back as the same double, 0 below
 * CSV_FLUSH and for -0, "nan" for a NaN. The values: random doubles over
 * the magnitudes the columns take and beyond (1e-15 to 1e22, both signs),
 * short decimals (k / 10^j), values whose 17-digit form ends in a half at
 * the 15th or 16th digit (the case the formatter hands back to printf),
 * carries (9.99...), the edges of %g's positional range (1e-4, 1e-5,
 * 1e15, 1e16, 1e17) and the specials.
 *
 * Usage: test_csv_number [N]   (N random values per class, default 100000)
 * The last line is "N passed, N failed"; the exit status is 1 on a failure.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "csv_out.h"

static unsigned passed;
static unsigned failed;
static unsigned long long compared;
static unsigned long long mismatched;
static uint64_t lcg = 88172645463325252u;

static uint64_t next_u64(void) {
    lcg ^= lcg << 13;
    lcg ^= lcg >> 7;
    lcg ^= lcg << 17;
    return lcg;
}

/* The definition the formatter must meet. */
static void reference(char *buf, size_t cap, double v) {
    if (!(fabs(v) >= CSV_FLUSH)) {
        snprintf(buf, cap, "%s", (v != v) ? "nan" : "0");
        return;
    }
    for (int digits = 15; digits <= 17; digits++) {
        snprintf(buf, cap, "%.*g", digits, v);
        if (strtod(buf, NULL) == v) {
            break;
        }
    }
}

static void compare(double v) {
    char a[40];
    char b[40];
    csv_format_number(a, sizeof a, v);
    reference(b, sizeof b, v);
    compared++;
    if (strcmp(a, b) != 0) {
        if (mismatched < 10u) {
            fprintf(stderr, "  %.17g: \"%s\", expected \"%s\"\n", v, a, b);
        }
        mismatched++;
    }
}

static void check(const char *what, unsigned long long before_mismatch) {
    const bool ok = mismatched == before_mismatch;
    printf("  %s  %s\n", ok ? "ok  " : "FAIL", what);
    if (ok) {
        passed++;
    } else {
        failed++;
    }
}

int main(int argc, char **argv) {
    const long n = (argc > 1) ? strtol(argv[1], NULL, 10) : 100000L;
    if (n <= 0) {
        fprintf(stderr, "test_csv_number: N must be a positive count\n");
        return 2;
    }
    unsigned long long m0 = mismatched;
    for (long i = 0; i < n; i++) {
        /* A random significand at a random decimal magnitude 1e-16 .. 1e22. */
        const double mant = (double)(next_u64() >> 11) / 9007199254740992.0;
        const int e = (int)(next_u64() % 39u) - 16;
        const double v = mant * pow(10.0, e);
        compare((next_u64() & 1u) ? -v : v);
    }
    check("random doubles, 1e-16 to 1e22, both signs", m0);

    m0 = mismatched;
    for (long i = 0; i < n; i++) {
        /* Random bit patterns of finite doubles with binary exponents -60 .. 80. */
        const uint64_t bits = (next_u64() & 0x800fffffffffffffu) |
                              ((uint64_t)(1023 - 60 + (int)(next_u64() % 141u)) << 52);
        double v;
        memcpy(&v, &bits, sizeof v);
        compare(v);
    }
    check("random bit patterns, binary exponents -60 to 80", m0);

    m0 = mismatched;
    for (long i = 0; i < n; i++) {
        const double k = (double)(int64_t)(next_u64() % 2000000001u) - 1e9;
        compare(k / pow(10.0, (int)(next_u64() % 12u)));
    }
    check("short decimals k / 10^j", m0);

    m0 = mismatched;
    unsigned long long tried = 0u;
    for (long found = 0; found < n; tried++) {
        /* Doubles whose 17 digits end in a half at the 15th or 16th digit ("50", "5"):
         * where both neighbours of 16 digits can read back, and printf's choice between
         * them is the exact value's, which the 17 digits do not show. */
        const uint64_t bits = (next_u64() & 0x800fffffffffffffu) |
                              ((uint64_t)(1023 - 50 + (int)(next_u64() % 120u)) << 52);
        double v;
        memcpy(&v, &bits, sizeof v);
        char e17[40];
        snprintf(e17, sizeof e17, "%.16e", fabs(v));
        if (e17[17] == '5' || (e17[16] == '5' && e17[17] == '0')) {
            compare(v);
            found++;
        }
    }
    check("halves at the 15th and 16th digit", m0);
    printf("  (%ld halves in %llu random doubles)\n", n, tried);

    m0 = mismatched;
    static const double edges[] = {
        1e-4, 1e-5, 9.9999999999999995e-5, 0.00010000000000000001, 1e15, 1e16, 1e17, 1e21,
        999999999999999.9, 9999999999999998.0, 99999999999999984.0, 9.9999999999999999e14,
        0.99999999999999989, 0.999999999999999, 9.9999999999999982, 1.0, 0.1, 0.2, 0.3,
        1.0 / 3.0, 2.0 / 3.0, 123456789012345678.0, 1e-15, 1.0000000000000001e-15, 1e99,
        1e100, 1.7976931348623157e308, 4.9e-324, 0.0, -0.0, 5e-16, INFINITY, -INFINITY, NAN,
        299.99999999999997, 299.99999999999994, 0.5, 2.5, 1e23, 8.41e21, 5e-324};
    for (size_t i = 0; i < sizeof edges / sizeof edges[0]; i++) {
        compare(edges[i]);
        compare(-edges[i]);
        compare(nextafter(edges[i], 0.0));
        compare(nextafter(edges[i], INFINITY));
    }
    check("edges of the positional range, carries, extremes and specials", m0);

    printf("  %llu values compared, %llu differ\n", compared, mismatched);
    printf("%u passed, %u failed\n", passed, failed);
    return failed == 0u ? 0 : 1;
}
