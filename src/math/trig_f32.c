/*
 * sin, cos, tan and angle wrapping in single precision, computed in float
 * only. The algorithm is the one of trig_f64.c: reduction to
 * x = n*pi/2 + y, |y| <= pi/4, with y carried as y + ylo (rem_pio2.c), then
 *     sin(y) = y + y^3 * S(y^2)          (S of degree 3, odd degree 9)
 *     cos(y) = 1 - y^2/2 + y^4 * C(y^2)  (C of degree 2, even degree 8)
 * with the low part to first order, y^2 exact in cos, and tan as a quotient
 * of the two kernels rounded once. S and C are Remez minimax approximations
 * of the relative error with coefficients rounded to float one at a time;
 * their errors are 2^-32.5 (sin) and 2^-33.0 (cos).
 *
 * Results are within one ulp (measured worst cases in docs/math.md) for
 * every finite argument; sin, cos and tan of an infinity or a NaN are NaN.
 */
#include "math/math_private.h"

static const float PIO4 = 0x1.921fb6p-1f;
static const float PIO2_HI = 0x1.921fb6p+0f;
static const float PIO2_LO = -0x1.777a5cp-25f;

/* sin(y + ylo) as a rounded value plus *tail (the error of that rounding). */
static float sin_kernel(float y, float ylo, float *tail) {
    static const float S0 = -0x1.555556p-3f;
    static const float S1 = 0x1.111174p-7f;
    static const float S2 = -0x1.a05954p-13f;
    static const float S3 = 0x1.7c2c4ep-19f;
    float z = y * y;
    float p = S0 + z * (S1 + z * (S2 + z * S3));
    float t = (y * z) * p + ylo * (1.0f - 0.5f * z);
    float s;
    math_fast_two_sum_f32(y, t, &s, tail);
    return s;
}

/* cos(y + ylo) as a rounded value plus *tail. */
static float cos_kernel(float y, float ylo, float *tail) {
    static const float C0 = 0x1.55554ap-5f;
    static const float C1 = -0x1.6c0c28p-10f;
    static const float C2 = 0x1.99e80cp-16f;
    float zh;
    float zl;
    /* y^2 = zh + zl exactly; |y| >= 2^-30 keeps zl far from underflow. */
    math_two_prod_f32(y, y, &zh, &zl);
    float hz = 0.5f * zh;
    float w = 1.0f - hz;
    float werr = (1.0f - w) - hz; /* exact: 1 - hz = w + werr */
    float p = C0 + zh * (C1 + zh * C2);
    float t = werr + ((zh * zh) * p - (0.5f * zl + y * ylo));
    float c;
    math_fast_two_sum_f32(w, t, &c, tail);
    return c;
}

/* (ah + al) / (bh + bl), rounded once after an exact residual. */
static float div_dd(float ah, float al, float bh, float bl) {
    float q = ah / bh;
    float p;
    float pe;
    math_two_prod_f32(q, bh, &p, &pe);
    /* q*bh is within two ulps of ah, so ah - p is exact. */
    float r = (((ah - p) - pe) + al - q * bl) / bh;
    return q + r;
}

/* Reduces x (finite, |x| >= 2^-12) and evaluates both kernels. */
static unsigned sincos_reduced(float x, float *s, float *st, float *c, float *ct) {
    float y = x;
    float ylo = 0.0f;
    unsigned n = 0u;
    if (math_fabs_f32(x) > PIO4) {
        n = math_rem_pio2_f32(x, &y, &ylo);
    }
    *s = sin_kernel(y, ylo, st);
    *c = cos_kernel(y, ylo, ct);
    return n;
}

void math_sincos_f32(float x, float *s, float *c) {
    if (!math_isfinite_f32(x)) {
        *s = math_nan_f32();
        *c = math_nan_f32();
        return;
    }
    if (math_fabs_f32(x) < 0x1p-12f) {
        /* sin x = x and cos x = 1 after rounding; keeps the sign of zero. */
        *s = x;
        *c = 1.0f;
        return;
    }
    float sv;
    float st;
    float cv;
    float ct;
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

float math_sin_f32(float x) {
    float s;
    float c;
    math_sincos_f32(x, &s, &c);
    return s;
}

float math_cos_f32(float x) {
    float s;
    float c;
    math_sincos_f32(x, &s, &c);
    return c;
}

float math_tan_f32(float x) {
    if (!math_isfinite_f32(x)) {
        return math_nan_f32();
    }
    if (math_fabs_f32(x) < 0x1p-12f) {
        return x; /* tan x = x + x^3/3 rounds to x */
    }
    float sv;
    float st;
    float cv;
    float ct;
    unsigned n = sincos_reduced(x, &sv, &st, &cv, &ct);
    if ((n & 1u) != 0u) {
        return div_dd(-cv, -ct, sv, st); /* tan(y + pi/2) = -cos y / sin y */
    }
    return div_dd(sv, st, cv, ct);
}

float math_wrap_pi_f32(float x) {
    if (!math_isfinite_f32(x)) {
        return math_nan_f32();
    }
    if (math_fabs_f32(x) <= 2.0f * PIO2_HI) {
        return x;
    }
    float y;
    float ylo;
    unsigned n = math_rem_pio2_f32(x, &y, &ylo);
    /* x = j*pi/2 + y (mod 2*pi) with j in {-2, -1, 0, 1, 2}, chosen so the sum is in [-pi, pi]. */
    int j = (n == 3u) ? -1 : (int)n;
    if (j == 2 && y > 0.0f) {
        j = -2;
    }
    if (j == 0) {
        return y;
    }
    float jd = (float)j;
    return jd * PIO2_HI + (y + (ylo + jd * PIO2_LO));
}
