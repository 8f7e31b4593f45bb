/*
 * fmod: x - n*y with n = trunc(x/y), which is always representable, so it is
 * computed exactly by binary long division of the integer significands:
 * the remainder is doubled and reduced by the divisor's significand once per
 * bit of exponent difference (at most 2098 steps in double, 277 in float,
 * bounded and without division instructions). The result has the sign of x.
 */
#include "math/math_private.h"

/* |a| = *m * 2^*e with *m in [2^52, 2^53), for finite nonzero bits a (sign cleared). */
static void unpack_f64(uint64_t a, uint64_t *m, int *e) {
    int be = (int)(a >> 52);
    uint64_t mant = a & 0x000fffffffffffffu;
    if (be == 0) {
        int ex = -1074;
        while (mant < 0x0010000000000000u) {
            mant <<= 1;
            ex -= 1;
        }
        *m = mant;
        *e = ex;
        return;
    }
    *m = mant | 0x0010000000000000u;
    *e = be - 1075;
}

double math_fmod_f64(double x, double y) {
    uint64_t ux = math_bits_f64(x);
    uint64_t sign = ux & 0x8000000000000000u;
    uint64_t ax = ux & 0x7fffffffffffffffu;
    uint64_t ay = math_bits_f64(y) & 0x7fffffffffffffffu;
    if (ax >= 0x7ff0000000000000u || ay > 0x7ff0000000000000u || ay == 0u) {
        return math_nan_f64(); /* x infinite or NaN, y NaN or zero */
    }
    if (ax < ay) {
        return x; /* |x| < |y|, y = inf included: bit patterns order like magnitudes */
    }
    uint64_t mx;
    uint64_t my;
    int ex;
    int ey;
    unpack_f64(ax, &mx, &ex);
    unpack_f64(ay, &my, &ey);
    uint64_t rem = (mx >= my) ? mx - my : mx;
    for (int i = ex - ey; i > 0; i--) {
        rem <<= 1; /* rem < my < 2^53 before, so no overflow */
        if (rem >= my) {
            rem -= my;
        }
    }
    if (rem == 0u) {
        return math_from_bits_f64(sign);
    }
    while (rem < 0x0010000000000000u) {
        rem <<= 1;
        ey -= 1;
    }
    int be = ey + 1075;
    if (be >= 1) {
        return math_from_bits_f64(sign | ((uint64_t)be << 52) | (rem & 0x000fffffffffffffu));
    }
    /* Subnormal: the result is a multiple of 2^-1074, so only zeros are shifted out. */
    return math_from_bits_f64(sign | (rem >> (1 - be)));
}

static void unpack_f32(uint32_t a, uint32_t *m, int *e) {
    int be = (int)(a >> 23);
    uint32_t mant = a & 0x007fffffu;
    if (be == 0) {
        int ex = -149;
        while (mant < 0x00800000u) {
            mant <<= 1;
            ex -= 1;
        }
        *m = mant;
        *e = ex;
        return;
    }
    *m = mant | 0x00800000u;
    *e = be - 150;
}

float math_fmod_f32(float x, float y) {
    uint32_t ux = math_bits_f32(x);
    uint32_t sign = ux & 0x80000000u;
    uint32_t ax = ux & 0x7fffffffu;
    uint32_t ay = math_bits_f32(y) & 0x7fffffffu;
    if (ax >= 0x7f800000u || ay > 0x7f800000u || ay == 0u) {
        return math_nan_f32();
    }
    if (ax < ay) {
        return x;
    }
    uint32_t mx;
    uint32_t my;
    int ex;
    int ey;
    unpack_f32(ax, &mx, &ex);
    unpack_f32(ay, &my, &ey);
    uint32_t rem = (mx >= my) ? mx - my : mx;
    for (int i = ex - ey; i > 0; i--) {
        rem <<= 1;
        if (rem >= my) {
            rem -= my;
        }
    }
    if (rem == 0u) {
        return math_from_bits_f32(sign);
    }
    while (rem < 0x00800000u) {
        rem <<= 1;
        ey -= 1;
    }
    int be = ey + 150;
    if (be >= 1) {
        return math_from_bits_f32(sign | ((uint32_t)be << 23) | (rem & 0x007fffffu));
    }
    return math_from_bits_f32(sign | (rem >> (1 - be)));
}
