/*
 * pow in double precision: x^y = exp(y * log x) with log x carried in two
 * parts (about 2^-66 relative, log_f64.c) and the product y * log x formed
 * exactly as ph + pl (two_prod), so that the exponential sees an argument
 * whose error is far below its own rounding: |y log x| <= 746 whenever the
 * result is finite and nonzero, so the argument error is below 2^-56 and
 * the result is within about 0.6 ulp.
 *
 * The special cases follow C99 Annex F: pow(x, +-0) = 1 and pow(1, y) = 1
 * even for a NaN; a negative x needs an integer y (NaN otherwise) and gives
 * a negative result for odd y; zeros and infinities give zeros and
 * infinities with the sign rules of the standard. y = 1, 2, -1 and 1/2 are
 * computed directly (x, x*x, 1/x, sqrt x), correctly rounded.
 */
#include "math/math_private.h"

/* 0 when y is not an integer, 1 for an odd integer, 2 for an even one (finite y). */
static int integer_class(double y) {
    uint64_t u = math_bits_f64(y) & 0x7fffffffffffffffu;
    int e = (int)(u >> 52) - 1023;
    if (e < 0) {
        return (u == 0u) ? 2 : 0; /* LCOV_EXCL_BR_LINE: y = +-0 returns 1 before this */
    }
    if (e >= 53) {
        return 2; /* every double from 2^53 on is an even integer */
    }
    uint64_t m = (u & 0x000fffffffffffffu) | 0x0010000000000000u;
    uint64_t below_one = ((uint64_t)1u << (52 - e)) - 1u;
    if ((m & below_one) != 0u) {
        return 0;
    }
    return (((m >> (52 - e)) & 1u) != 0u) ? 1 : 2;
}

/* ax^y for finite ax > 0 and finite y != 0. */
static double pow_positive(double ax, double y) {
    if (ax == 1.0) {
        return 1.0; /* also pow(-1, y) for any even or odd integer y, however large */
    }
    if (y == 1.0) {
        return ax;
    }
    if (y == 2.0) {
        return ax * ax;
    }
    if (y == -1.0) {
        return 1.0 / ax;
    }
    if (y == 0.5) {
        return math_sqrt_f64(ax);
    }
    if (math_fabs_f64(y) > 0x1p64) {
        /* |log ax| >= 2^-53 for ax != 1, so |y log ax| > 2^11: overflow or underflow. */
        return ((ax > 1.0) == (y > 0.0)) ? math_inf_f64() : 0.0;
    }
    double ll;
    double lh = math_log_dd_f64(ax, &ll);
    double ph;
    double pl;
    math_two_prod_f64(y, lh, &ph, &pl);
    return math_exp_dd_f64(ph, pl + y * ll);
}

double math_pow_f64(double x, double y) {
    if (y == 0.0 || x == 1.0) {
        return 1.0;
    }
    if (math_isnan_f64(x) || math_isnan_f64(y)) {
        return math_nan_f64();
    }
    double ax = math_fabs_f64(x);
    if (math_isinf_f64(y)) {
        if (ax == 1.0) {
            return 1.0; /* pow(-1, +-inf) */
        }
        return ((ax < 1.0) == (y < 0.0)) ? math_inf_f64() : 0.0;
    }
    int yc = integer_class(y);
    bool negative = math_signbit_f64(x) && yc == 1;
    double r;
    if (ax == 0.0 || math_isinf_f64(ax)) {
        bool huge = (ax == 0.0) == (y < 0.0);
        r = huge ? math_inf_f64() : 0.0;
    } else if (x < 0.0 && yc == 0) {
        return math_nan_f64();
    } else {
        r = pow_positive(ax, y);
    }
    return negative ? -r : r;
}
