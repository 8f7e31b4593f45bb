/*
 * atan, atan2, asin and acos in single precision, computed in float only.
 * The algorithm is the one of atan_f64.c (reduction by atan(b) with
 * b in {0, 1/2, 1, 3/2, inf}, a polynomial on |t| <= 7/16, atan2 with the
 * exact residual of its division); the polynomial A has degree 4 (relative
 * error 2^-29.6, Remez minimax with coefficients rounded to float).
 */
#include "math/math_private.h"

static const float PI_HI = 0x1.921fb6p+1f;
static const float PI_LO = -0x1.777a5cp-24f;
static const float PIO2_HI = 0x1.921fb6p+0f;
static const float PIO4_HI = 0x1.921fb6p-1f;
static const float THREE_PIO4_HI = 0x1.2d97c8p+1f;

/* atan(t) - t for |t| <= 7/16. */
static float atan_poly(float t) {
    static const float A[5] = {
        -0x1.555542p-2f, 0x1.998df8p-3f, -0x1.236f16p-3f, 0x1.add6b4p-4f, -0x1.dd3c84p-5f,
    };
    float z = t * t;
    float p = A[4];
    for (int i = 3; i >= 0; i--) {
        p = A[i] + z * p;
    }
    return (t * z) * p;
}

/*
 * atan(a + da) for finite a >= 0 and a small correction da (|da| <= ulp(a)),
 * returned as hi + *lo with hi rounded to nearest.
 */
static float atan_core(float a, float da, float *lo) {
    static const float ATAN_B_HI[4] = {0x1.dac670p-2f, 0x1.921fb6p-1f, 0x1.f730bep-1f,
                                       0x1.921fb6p+0f};
    static const float ATAN_B_LO[4] = {0x1.586ed4p-28f, -0x1.777a5cp-26f, -0x1.afc12cp-26f,
                                       -0x1.777a5cp-25f};
    float corr = (da != 0.0f) ? da / (1.0f + a * a) : 0.0f;
    float hi;
    if (a < 0.4375f) {
        math_fast_two_sum_f32(a, atan_poly(a) + corr, &hi, lo);
        return hi;
    }
    int i;
    float t;
    if (a < 0.6875f) {
        i = 0;
        t = (2.0f * a - 1.0f) / (2.0f + a);
    } else if (a < 1.1875f) {
        i = 1;
        t = (a - 1.0f) / (a + 1.0f);
    } else if (a < 2.4375f) {
        i = 2;
        t = (2.0f * a - 3.0f) / (2.0f + 3.0f * a);
    } else {
        i = 3;
        t = -1.0f / a;
    }
    float rest = ((ATAN_B_LO[i] + corr) + atan_poly(t)) + t;
    math_fast_two_sum_f32(ATAN_B_HI[i], rest, &hi, lo);
    return hi;
}

float math_atan_f32(float x) {
    if (math_isnan_f32(x)) {
        return math_nan_f32();
    }
    float ax = math_fabs_f32(x);
    if (ax < 0x1p-12f) {
        return x; /* atan x = x - x^3/3 rounds to x */
    }
    if (ax > 0x1p28f) {
        return math_copysign_f32(PIO2_HI, x); /* includes infinity */
    }
    float lo;
    return math_copysign_f32(atan_core(ax, 0.0f, &lo), x);
}

/* floor(log2 |a|) for a finite nonzero a, subnormals included. */
static int exponent_of(float a) {
    uint32_t u = math_bits_f32(a) & 0x7fffffffu;
    int e = (int)(u >> 23);
    if (e != 0) {
        return e - 127;
    }
    int b = 22;
    while (((u >> b) & 1u) == 0u) {
        b--;
    }
    return -149 + b;
}

/* v * 2^k in two exact steps, for results that are normal (|k| <= 250). */
static float scale_exact(float v, int k) {
    int k1 = k / 2;
    return (v * math_pow2i_f32(k1)) * math_pow2i_f32(k - k1);
}

/* The angle of (x, ay) in [0, pi], for finite nonzero ay and x. */
static float atan2_finite(float ay, float x) {
    float ax = math_fabs_f32(x);
    int ey = exponent_of(ay);
    int ex = exponent_of(ax);
    if (ey - ex > 30) {
        return PIO2_HI; /* the angle differs from pi/2 by less than 2^-29 */
    }
    if (ex - ey > 30) {
        return (x > 0.0f) ? ay / ax : PI_HI; /* atan(t) rounds to t for t < 2^-29 */
    }
    /* With ax scaled into [1, 2) and ay into [2^-31, 2^32], two_prod is exact. */
    float sx = scale_exact(ax, -ex);
    float sy = scale_exact(ay, -ex);
    float q = sy / sx;
    float p;
    float pe;
    math_two_prod_f32(q, sx, &p, &pe);
    float dq = ((sy - p) - pe) / sx; /* sy - p is exact: p is within 2 ulp of sy */
    float lo;
    float a = atan_core(q, dq, &lo);
    if (x > 0.0f) {
        return a;
    }
    float s;
    float e;
    math_two_sum_f32(PI_HI, -a, &s, &e);
    return s + (e + (PI_LO - lo));
}

float math_atan2_f32(float y, float x) {
    if (math_isnan_f32(x) || math_isnan_f32(y)) {
        return math_nan_f32();
    }
    float ay = math_fabs_f32(y);
    float ax = math_fabs_f32(x);
    float r;
    if (ay == 0.0f) {
        r = math_signbit_f32(x) ? PI_HI : 0.0f; /* x = -0 counts as negative */
    } else if (math_isinf_f32(ax)) {
        if (math_isinf_f32(ay)) {
            r = (x < 0.0f) ? THREE_PIO4_HI : PIO4_HI;
        } else {
            r = (x < 0.0f) ? PI_HI : 0.0f;
        }
    } else if (math_isinf_f32(ay) || ax == 0.0f) {
        r = PIO2_HI;
    } else {
        r = atan2_finite(ay, x);
    }
    return math_copysign_f32(r, y);
}

/*
 * c = sqrt(1 - x^2) for 2^-12 <= ax < 1, and *rel such that the exact root is
 * c * (1 + *rel) to about 2^-44: 1 - x^2 is formed exactly as h + l (with
 * 1 - ax exact when ax >= 1/2), and the rounding of the square root is
 * recovered from the exact residual h - c^2.
 */
static float cos_of_sine(float ax, float *rel) {
    float h;
    float l;
    if (ax >= 0.5f) {
        float a = 1.0f - ax;
        float b;
        float bl;
        float pe;
        math_two_sum_f32(1.0f, ax, &b, &bl);
        math_two_prod_f32(a, b, &h, &pe);
        l = pe + a * bl;
    } else {
        float sh;
        float sl;
        float e;
        math_two_prod_f32(ax, ax, &sh, &sl);
        math_two_sum_f32(1.0f, -sh, &h, &e);
        l = e - sl;
    }
    float c = math_sqrt_f32(h);
    float cc;
    float ce;
    math_two_prod_f32(c, c, &cc, &ce);
    *rel = (((h - cc) - ce) + l) / (2.0f * h); /* h - cc is exact: cc is within an ulp of h */
    return c;
}

/* num / den, and in *corr the division's rounding error, recovered exactly (quotient < 2^30). */
static float quotient(float num, float den, float *corr) {
    float q = num / den;
    float p;
    float pe;
    math_two_prod_f32(q, den, &p, &pe);
    *corr = ((num - p) - pe) / den;
    return q;
}

/* asin x = atan(x / sqrt(1 - x^2)), with both roundings passed to atan as a correction. */
float math_asin_f32(float x) {
    float ax = math_fabs_f32(x);
    if (math_isnan_f32(x) || ax > 1.0f) {
        return math_nan_f32();
    }
    if (ax < 0x1p-12f) {
        return x; /* asin x = x + x^3/6 rounds to x */
    }
    if (ax == 1.0f) {
        return math_copysign_f32(PIO2_HI, x);
    }
    float rel;
    float c = cos_of_sine(ax, &rel);
    float dq;
    float q = quotient(ax, c, &dq);
    float lo;
    return math_copysign_f32(atan_core(q, dq - q * rel, &lo), x);
}

/* acos x = atan(sqrt(1 - x^2) / x), from pi when x < 0. */
float math_acos_f32(float x) {
    float ax = math_fabs_f32(x);
    if (math_isnan_f32(x) || ax > 1.0f) {
        return math_nan_f32();
    }
    if (ax < 0x1p-26f) {
        return PIO2_HI; /* pi/2 - x rounds to pi/2 */
    }
    if (ax == 1.0f) {
        return (x > 0.0f) ? 0.0f : PI_HI;
    }
    float rel = -0.5f * ax * ax; /* sqrt(1 - x^2) = 1 - x^2/2 for tiny x */
    float c = 1.0f;
    if (ax >= 0x1p-12f) {
        c = cos_of_sine(ax, &rel);
    }
    float dq;
    float q = quotient(c, ax, &dq);
    float lo;
    float a = atan_core(q, dq + q * rel, &lo);
    if (x > 0.0f) {
        return a;
    }
    float s;
    float e;
    math_two_sum_f32(PI_HI, -a, &s, &e);
    return s + (e + (PI_LO - lo));
}
