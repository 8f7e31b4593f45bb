/*
 * sin, cos, tan and angle wrapping in double precision.
 *
 * The argument is reduced to x = n*pi/2 + y, |y| <= pi/4, with y carried as
 * y + ylo (rem_pio2.c; no reduction when |x| <= pi/4). On that interval
 *     sin(y) = y + y^3 * S(y^2)          (S of degree 5, odd degree 13)
 *     cos(y) = 1 - y^2/2 + y^4 * C(y^2)  (C of degree 5, even degree 14)
 * and the low part enters to first order: sin += ylo * cos(y),
 * cos -= ylo * sin(y). S and C are minimax approximations for the relative
 * error of sin and cos, computed by the Remez exchange in 90-digit
 * arithmetic, each coefficient rounded to double in turn with the remaining
 * ones re-optimised; their errors are 2^-57.9 (sin) and 2^-63.9 (cos).
 *
 * Each kernel returns its result rounded and the rounding error of the last
 * addition, so that tan can divide two values carried to about 2^-60 and
 * round once. cos computes y^2 exactly (two_prod) and 1 - y^2/2 with its
 * exact error, so that the largest term rounds only once.
 *
 * The quadrant n selects sin or cos and the sign. Results are within one
 * ulp (measured worst cases in docs/math.md) for every finite argument;
 * sin, cos and tan of an infinity or a NaN are NaN.
 */
#include "math/math_private.h"

static const double PIO4 = 0x1.921fb54442d18p-1;
static const double PIO2_HI = 0x1.921fb54442d18p+0;
static const double PIO2_LO = 0x1.1a62633145c07p-54;

/* sin(y + ylo) as a rounded value plus *tail (the error of that rounding). */
static double sin_kernel(double y, double ylo, double *tail) {
    static const double S0 = -0x1.5555555555548p-3;
    static const double S1 = 0x1.111111110f730p-7;
    static const double S2 = -0x1.a01a019be9217p-13;
    static const double S3 = 0x1.71de35552b52cp-19;
    static const double S4 = -0x1.ae5e4b83e4772p-26;
    static const double S5 = 0x1.5d8b5594a0a7cp-33;
    double z = y * y;
    double p = S0 + z * (S1 + z * (S2 + z * (S3 + z * (S4 + z * S5))));
    double t = (y * z) * p + ylo * (1.0 - 0.5 * z);
    double s;
    math_fast_two_sum_f64(y, t, &s, tail);
    return s;
}

/* cos(y + ylo) as a rounded value plus *tail. */
static double cos_kernel(double y, double ylo, double *tail) {
    static const double C0 = 0x1.555555555554bp-5;
    static const double C1 = -0x1.6c16c16c15015p-10;
    static const double C2 = 0x1.a01a019c8f254p-16;
    static const double C3 = -0x1.27e4f7f19148bp-22;
    static const double C4 = 0x1.1ee9dbcf0188fp-29;
    static const double C5 = -0x1.8fa6849520b1ap-37;
    double zh;
    double zl;
    /* y^2 = zh + zl exactly; |y| >= 2^-62 keeps zl far from underflow. */
    math_two_prod_f64(y, y, &zh, &zl);
    double hz = 0.5 * zh;
    double w = 1.0 - hz;
    double werr = (1.0 - w) - hz; /* exact: 1 - hz = w + werr */
    double p = C0 + zh * (C1 + zh * (C2 + zh * (C3 + zh * (C4 + zh * C5))));
    double t = werr + ((zh * zh) * p - (0.5 * zl + y * ylo));
    double c;
    math_fast_two_sum_f64(w, t, &c, tail);
    return c;
}

/* (ah + al) / (bh + bl), rounded once after an exact residual. */
static double div_dd(double ah, double al, double bh, double bl) {
    double q = ah / bh;
    double p;
    double pe;
    math_two_prod_f64(q, bh, &p, &pe);
    /* q*bh is within two ulps of ah, so ah - p is exact. */
    double r = (((ah - p) - pe) + al - q * bl) / bh;
    return q + r;
}

/* Reduces x (finite, |x| >= 2^-27) and evaluates both kernels. */
static unsigned sincos_reduced(double x, double *s, double *st, double *c, double *ct) {
    double y = x;
    double ylo = 0.0;
    unsigned n = 0u;
    if (math_fabs_f64(x) > PIO4) {
        n = math_rem_pio2_f64(x, &y, &ylo);
    }
    *s = sin_kernel(y, ylo, st);
    *c = cos_kernel(y, ylo, ct);
    return n;
}

void math_sincos_f64(double x, double *s, double *c) {
    if (!math_isfinite_f64(x)) {
        *s = math_nan_f64();
        *c = math_nan_f64();
        return;
    }
    if (math_fabs_f64(x) < 0x1p-27) {
        /* sin x = x and cos x = 1 after rounding; keeps the sign of zero. */
        *s = x;
        *c = 1.0;
        return;
    }
    double sv;
    double st;
    double cv;
    double ct;
    unsigned n = sincos_reduced(x, &sv, &st, &cv, &ct);
    switch (n) {
    case 0u:
        *s = sv;
        *c = cv;
        break;
    case 1u:
        *s = cv;
        *c = -sv;
        break;
    case 2u:
        *s = -sv;
        *c = -cv;
        break;
    default:
        *s = -cv;
        *c = sv;
        break;
    }
}

double math_sin_f64(double x) {
    double s;
    double c;
    math_sincos_f64(x, &s, &c);
    return s;
}

double math_cos_f64(double x) {
    double s;
    double c;
    math_sincos_f64(x, &s, &c);
    return c;
}

double math_tan_f64(double x) {
    if (!math_isfinite_f64(x)) {
        return math_nan_f64();
    }
    if (math_fabs_f64(x) < 0x1p-27) {
        return x; /* tan x = x + x^3/3 rounds to x */
    }
    double sv;
    double st;
    double cv;
    double ct;
    unsigned n = sincos_reduced(x, &sv, &st, &cv, &ct);
    if ((n & 1u) != 0u) {
        return div_dd(-cv, -ct, sv, st); /* tan(y + pi/2) = -cos y / sin y */
    }
    return div_dd(sv, st, cv, ct);
}

double math_wrap_pi_f64(double x) {
    if (!math_isfinite_f64(x)) {
        return math_nan_f64();
    }
    if (math_fabs_f64(x) <= 2.0 * PIO2_HI) {
        return x;
    }
    double y;
    double ylo;
    unsigned n = math_rem_pio2_f64(x, &y, &ylo);
    /* x = j*pi/2 + y (mod 2*pi) with j in {-2, -1, 0, 1, 2}, chosen so the sum is in [-pi, pi]. */
    int j = (n == 3u) ? -1 : (int)n;
    if (j == 2 && y > 0.0) {
        j = -2;
    }
    if (j == 0) {
        return y;
    }
    double jd = (double)j;
    return jd * PIO2_HI + (y + (ylo + jd * PIO2_LO));
}
