/*
 * atan, atan2, asin and acos in double precision.
 *
 * atan(a), a >= 0, is reduced by the addition formula
 * atan(a) = atan(b) + atan((a - b) / (1 + a*b)) with b chosen by interval:
 *     a < 7/16          b = 0      (no reduction)
 *     7/16 <= a < 11/16 b = 1/2    t = (2a - 1) / (2 + a)
 *     11/16 <= a < 19/16 b = 1     t = (a - 1) / (a + 1)
 *     19/16 <= a < 39/16 b = 3/2   t = (2a - 3) / (2 + 3a)
 *     a >= 39/16        b = inf    t = -1/a
 * so that |t| <= 7/16, and atan(t) = t + t^3 * A(t^2) with A a minimax
 * polynomial of degree 10 (relative error 2^-57.7, Remez exchange in
 * 90-digit arithmetic, coefficients rounded to double one at a time with the
 * rest re-optimised). atan(b) is a two-part constant. The numerators 2a - 1,
 * a - 1 and 2a - 3 are exact; the rounding of t is damped by the reduction,
 * whose derivative is below 1 and whose result is added to a larger atan(b).
 *
 * atan2(y, x) divides the smaller by the larger after scaling both by the
 * same power of two, recovers the division's rounding error exactly
 * (two_prod) and passes it to atan as a first-order correction, then adds
 * the result to pi when x < 0 in two parts. asin and acos are
 * atan(x / sqrt(1 - x^2)) and its complement, where 1 - x^2 is formed
 * exactly and the roundings of the square root and of the division are
 * passed to atan as the same first-order correction.
 */
#include "math/math_private.h"

static const double PI_HI = 0x1.921fb54442d18p+1;
static const double PI_LO = 0x1.1a62633145c07p-53;
static const double PIO2_HI = 0x1.921fb54442d18p+0;
static const double PIO4_HI = 0x1.921fb54442d18p-1;
static const double THREE_PIO4_HI = 0x1.2d97c7f3321d2p+1;

/* atan(t) - t for |t| <= 7/16. */
static double atan_poly(double t) {
    static const double A[11] = {
        -0x1.555555555550bp-2, 0x1.999999998e7ecp-3, -0x1.2492491ff378dp-3, 0x1.c71c6fdb322e1p-4,
        -0x1.745cdba6e74e3p-4, 0x1.3b0f2082bd276p-4, -0x1.10d6030ca9db1p-4, 0x1.ddddc075a30aap-5,
        -0x1.97a0ce799ad35p-5, 0x1.2b184f0ef9e2cp-5, -0x1.0a7fddd42043dp-6,
    };
    double z = t * t;
    double p = A[10];
    for (int i = 9; i >= 0; i--) {
        p = A[i] + z * p;
    }
    return (t * z) * p;
}

/*
 * atan(a + da) for finite a >= 0 and a small correction da (|da| <= ulp(a)),
 * returned as hi + *lo with hi rounded to nearest.
 */
static double atan_core(double a, double da, double *lo) {
    static const double ATAN_B_HI[4] = {
        0x1.dac670561bb4fp-2,
        0x1.921fb54442d18p-1,
        0x1.f730bd281f69bp-1,
        0x1.921fb54442d18p+0,
    };
    static const double ATAN_B_LO[4] = {
        0x1.a2b7f222f65e2p-56,
        0x1.1a62633145c07p-55,
        0x1.007887af0cbbdp-56,
        0x1.1a62633145c07p-54,
    };
    double corr = (da != 0.0) ? da / (1.0 + a * a) : 0.0;
    double hi;
    if (a < 0.4375) {
        math_fast_two_sum_f64(a, atan_poly(a) + corr, &hi, lo);
        return hi;
    }
    int i;
    double t;
    if (a < 0.6875) {
        i = 0;
        t = (2.0 * a - 1.0) / (2.0 + a);
    } else if (a < 1.1875) {
        i = 1;
        t = (a - 1.0) / (a + 1.0);
    } else if (a < 2.4375) {
        i = 2;
        t = (2.0 * a - 3.0) / (2.0 + 3.0 * a);
    } else {
        i = 3;
        t = -1.0 / a;
    }
    double rest = ((ATAN_B_LO[i] + corr) + atan_poly(t)) + t;
    math_fast_two_sum_f64(ATAN_B_HI[i], rest, &hi, lo);
    return hi;
}

double math_atan_f64(double x) {
    if (math_isnan_f64(x)) {
        return math_nan_f64();
    }
    double ax = math_fabs_f64(x);
    if (ax < 0x1p-27) {
        return x; /* atan x = x - x^3/3 rounds to x */
    }
    if (ax > 0x1p60) {
        return math_copysign_f64(PIO2_HI, x); /* includes infinity */
    }
    double lo;
    return math_copysign_f64(atan_core(ax, 0.0, &lo), x);
}

/* floor(log2 |a|) for a finite nonzero a, subnormals included. */
static int exponent_of(double a) {
    uint64_t u = math_bits_f64(a) & 0x7fffffffffffffffu;
    int e = (int)(u >> 52);
    if (e != 0) {
        return e - 1023;
    }
    int b = 51;
    while (((u >> b) & 1u) == 0u) {
        b--;
    }
    return -1074 + b;
}

/* v * 2^k in two exact steps, for results that are normal (|k| <= 2100). */
static double scale_exact(double v, int k) {
    int k1 = k / 2;
    return (v * math_pow2i_f64(k1)) * math_pow2i_f64(k - k1);
}

/* The angle of (x, ay) in [0, pi], for finite nonzero ay and x. */
static double atan2_finite(double ay, double x) {
    double ax = math_fabs_f64(x);
    int ey = exponent_of(ay);
    int ex = exponent_of(ax);
    if (ey - ex > 60) {
        return PIO2_HI; /* the angle differs from pi/2 by less than 2^-59 */
    }
    if (ex - ey > 60) {
        return (x > 0.0) ? ay / ax : PI_HI; /* atan(t) rounds to t for t < 2^-59 */
    }
    /* With ax scaled into [1, 2) and ay into [2^-61, 2^62], two_prod is exact. */
    double sx = scale_exact(ax, -ex);
    double sy = scale_exact(ay, -ex);
    double q = sy / sx;
    double p;
    double pe;
    math_two_prod_f64(q, sx, &p, &pe);
    double dq = ((sy - p) - pe) / sx; /* sy - p is exact: p is within 2 ulp of sy */
    double lo;
    double a = atan_core(q, dq, &lo);
    if (x > 0.0) {
        return a;
    }
    double s;
    double e;
    math_two_sum_f64(PI_HI, -a, &s, &e);
    return s + (e + (PI_LO - lo));
}

double math_atan2_f64(double y, double x) {
    if (math_isnan_f64(x) || math_isnan_f64(y)) {
        return math_nan_f64();
    }
    double ay = math_fabs_f64(y);
    double ax = math_fabs_f64(x);
    double r;
    if (ay == 0.0) {
        r = math_signbit_f64(x) ? PI_HI : 0.0; /* x = -0 counts as negative */
    } else if (math_isinf_f64(ax)) {
        if (math_isinf_f64(ay)) {
            r = (x < 0.0) ? THREE_PIO4_HI : PIO4_HI;
        } else {
            r = (x < 0.0) ? PI_HI : 0.0;
        }
    } else if (math_isinf_f64(ay) || ax == 0.0) {
        r = PIO2_HI;
    } else {
        r = atan2_finite(ay, x);
    }
    return math_copysign_f64(r, y);
}

/*
 * c = sqrt(1 - x^2) for 2^-27 <= ax < 1, and *rel such that the exact root is
 * c * (1 + *rel) to about 2^-100: 1 - x^2 is formed exactly as h + l (with
 * 1 - ax exact when ax >= 1/2), and the rounding of the square root is
 * recovered from the exact residual h - c^2.
 */
static double cos_of_sine(double ax, double *rel) {
    double h;
    double l;
    if (ax >= 0.5) {
        double a = 1.0 - ax;
        double b;
        double bl;
        double pe;
        math_two_sum_f64(1.0, ax, &b, &bl);
        math_two_prod_f64(a, b, &h, &pe);
        l = pe + a * bl;
    } else {
        double sh;
        double sl;
        double e;
        math_two_prod_f64(ax, ax, &sh, &sl);
        math_two_sum_f64(1.0, -sh, &h, &e);
        l = e - sl;
    }
    double c = math_sqrt_f64(h);
    double cc;
    double ce;
    math_two_prod_f64(c, c, &cc, &ce);
    *rel = (((h - cc) - ce) + l) / (2.0 * h); /* h - cc is exact: cc is within an ulp of h */
    return c;
}

/* num / den, and in *corr the division's rounding error, recovered exactly (quotient < 2^60). */
static double quotient(double num, double den, double *corr) {
    double q = num / den;
    double p;
    double pe;
    math_two_prod_f64(q, den, &p, &pe);
    *corr = ((num - p) - pe) / den;
    return q;
}

/* asin x = atan(x / sqrt(1 - x^2)), with both roundings passed to atan as a correction. */
double math_asin_f64(double x) {
    double ax = math_fabs_f64(x);
    if (math_isnan_f64(x) || ax > 1.0) {
        return math_nan_f64();
    }
    if (ax < 0x1p-27) {
        return x; /* asin x = x + x^3/6 rounds to x */
    }
    if (ax == 1.0) {
        return math_copysign_f64(PIO2_HI, x);
    }
    double rel;
    double c = cos_of_sine(ax, &rel);
    double dq;
    double q = quotient(ax, c, &dq);
    double lo;
    return math_copysign_f64(atan_core(q, dq - q * rel, &lo), x);
}

/* acos x = atan(sqrt(1 - x^2) / x), from pi when x < 0. */
double math_acos_f64(double x) {
    double ax = math_fabs_f64(x);
    if (math_isnan_f64(x) || ax > 1.0) {
        return math_nan_f64();
    }
    if (ax < 0x1p-54) {
        return PIO2_HI; /* pi/2 - x rounds to pi/2 */
    }
    if (ax == 1.0) {
        return (x > 0.0) ? 0.0 : PI_HI;
    }
    double rel = -0.5 * ax * ax; /* sqrt(1 - x^2) = 1 - x^2/2 for tiny x */
    double c = 1.0;
    if (ax >= 0x1p-27) {
        c = cos_of_sine(ax, &rel);
    }
    double dq;
    double q = quotient(c, ax, &dq);
    double lo;
    double a = atan_core(q, dq + q * rel, &lo);
    if (x > 0.0) {
        return a;
    }
    double s;
    double e;
    math_two_sum_f64(PI_HI, -a, &s, &e);
    return s + (e + (PI_LO - lo));
}
