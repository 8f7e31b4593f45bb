/*
 * Rounding to an integral value (trunc, floor, ceil, round) on the bit
 * pattern: exact, with the sign of zero kept as C99 specifies (floor(-0.5)
 * is -1, ceil(-0.5) is -0). Values of 2^52 (2^23 in float) and more are
 * already integers and are returned unchanged, as are infinities and NaNs.
 */
#include "math/math_private.h"

double math_trunc_f64(double x) {
    uint64_t u = math_bits_f64(x);
    int e = (int)((u >> 52) & 0x7ffu) - 1023;
    if (e >= 52) {
        return x;
    }
    if (e < 0) {
        return math_from_bits_f64(u & 0x8000000000000000u);
    }
    return math_from_bits_f64(u & ~(0x000fffffffffffffu >> e));
}

double math_floor_f64(double x) {
    double t = math_trunc_f64(x);
    /* Only a negative non-integer truncates upwards; t - 1 is exact below 2^52. */
    return (t > x) ? t - 1.0 : t;
}

double math_ceil_f64(double x) {
    double t = math_trunc_f64(x);
    return (t < x) ? t + 1.0 : t;
}

double math_round_f64(double x) {
    uint64_t u = math_bits_f64(x);
    int e = (int)((u >> 52) & 0x7ffu) - 1023;
    if (e >= 52) {
        return x;
    }
    if (e < -1) {
        return math_from_bits_f64(u & 0x8000000000000000u); /* |x| < 1/2 */
    }
    if (e == -1) {
        return math_copysign_f64(1.0, x); /* 1/2 <= |x| < 1 */
    }
    /* Add one half to the magnitude, then truncate; a carry into the exponent is fine. */
    u += (uint64_t)1u << (51 - e);
    return math_from_bits_f64(u & ~(0x000fffffffffffffu >> e));
}

float math_trunc_f32(float x) {
    uint32_t u = math_bits_f32(x);
    int e = (int)((u >> 23) & 0xffu) - 127;
    if (e >= 23) {
        return x;
    }
    if (e < 0) {
        return math_from_bits_f32(u & 0x80000000u);
    }
    return math_from_bits_f32(u & ~(0x007fffffu >> e));
}

float math_floor_f32(float x) {
    float t = math_trunc_f32(x);
    return (t > x) ? t - 1.0f : t;
}

float math_ceil_f32(float x) {
    float t = math_trunc_f32(x);
    return (t < x) ? t + 1.0f : t;
}

float math_round_f32(float x) {
    uint32_t u = math_bits_f32(x);
    int e = (int)((u >> 23) & 0xffu) - 127;
    if (e >= 23) {
        return x;
    }
    if (e < -1) {
        return math_from_bits_f32(u & 0x80000000u);
    }
    if (e == -1) {
        return math_copysign_f32(1.0f, x);
    }
    u += (uint32_t)1u << (22 - e);
    return math_from_bits_f32(u & ~(0x007fffffu >> e));
}
