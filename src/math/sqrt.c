/*
 * Correctly rounded square root, and the exact integer square root it is
 * built on, with integer arithmetic only.
 *
 * Write x = M * 2^(E - p) with the significand M an integer of p + 1 bits
 * (p = 52 or 23) and E even (M is doubled when E is odd), so that
 * y = M * 2^-p lies in [1, 4) and sqrt(x) = sqrt(y) * 2^(E/2). The result's
 * significand follows from Q = floor(sqrt(y) * 2^(p+1)) = floor(sqrt(N)),
 * N = M * 2^(p+2), the root with one bit more than the result needs. The
 * last bit of Q is the rounding bit. A square root is never exactly halfway
 * between two floating-point numbers (a root with p + 2 significant bits
 * would square to a number with 2p + 3 of them, more than M holds), so
 * round to nearest is "add the rounding bit". The result is the IEEE 754
 * square root bit for bit, on every port.
 *
 * How Q is found. Why not one result bit per step: that takes 54 (25)
 * passes, about 1800 instructions in double on a Cortex-M and 110 ns on the
 * desk, and the vessel's strip theory takes 44 roots per slow step. Here a
 * 32-bit estimate comes from Newton's iteration for 1/sqrt, which needs
 * products only: a seed from a 48-entry table (1.5 % at worst), three
 * passes of z' = z (3 - u z^2) / 2 in Q31 (error 1.5 %, 3.4e-4, 1.7e-7,
 * then the truncation of the Q31 products, a few units of 2^-31). Newton's
 * map for 1/sqrt never overshoots, but the truncation of z^2 can push z up
 * by a unit or two, so z is lowered by four units: z, and the root r = u z
 * taken from it, then stay at or below the exact values. For the double
 * and for the 64-bit integer root one more Newton step on the root itself,
 * r + (X - r^2) / (2 r), with the exact remainder X - r^2 and 1 / r taken
 * from z, brings the estimate within a unit of Q. Then the remainder
 * N - Q^2, formed exactly in 64-bit arithmetic modulo 2^64 (it is far below
 * 2^63 in magnitude, so its sign bit is its sign), corrects Q by whole
 * units to floor(sqrt(N)). The correction loops are bounded by four passes; the
 * estimate is at most one unit low (measured over every positive float,
 * 2e8 doubles and 2e8 64-bit integers; the 1/sqrt estimate is 3.0 to 5.5
 * units low over all 2^31 of its arguments), so they end by their test.
 */
#include "math/math_private.h"
#include "uuv_config.h"

/* 1 / sqrt(u) at the middle of [k / 16, (k + 1) / 16), Q16, for k = 16 ... 63. */
static const uint16_t sqrt_seed_q16[48] = {
    64535, 62664, 60947, 59364, 57898, 56535, 55265, 54076,
    52961, 51912, 50923, 49989, 49104, 48265, 47467, 46707,
    45983, 45292, 44630, 43997, 43390, 42808, 42248, 41710,
    41192, 40693, 40211, 39746, 39297, 38863, 38443, 38036,
    37642, 37260, 36889, 36529, 36179, 35840, 35509, 35188,
    34875, 34571, 34274, 33985, 33703, 33427, 33159, 32897,
};

/*
 * 2^31 / sqrt(u), u = a / 2^30 in [1, 4) (a in [2^30, 2^32)), from below
 * and within a few units: the result is in (2^30, 2^31]. Each product is of two
 * 32-bit factors (one UMULL on a Cortex-M): z^2 is Q62, taken as Q31 (below
 * 2^31 + 8); u z^2 is then Q61 near 2^61 (the seed keeps it below
 * 1.04 * 2^61); 3 - u z^2 is positive and below 2^62, and its Q31 form
 * times z stays below 2^64. Newton's map never overshoots; the truncation
 * of z^2 may, by a unit or two.
 */
static uint32_t sqrt_rsqrt_q31(uint32_t a) {
    uint32_t z = (uint32_t)sqrt_seed_q16[(a >> 26) - 16u] << 15;
    for (int i = 0; i < 3; i++) {
        uint64_t uz2 = (uint64_t)a * (uint32_t)(((uint64_t)z * z) >> 31);
        uint64_t e = 0x6000000000000000u - uz2;
        z = (uint32_t)(((uint64_t)z * (e >> 30)) >> 32);
    }
    return z - 4u; /* from below: the truncations may leave z a few units high */
}

/*
 * A root of x in [2^62, 2^64) from below: r <= sqrt(x), at most a few
 * units under it, and r^2 <= x (a 32-bit r; the exact remainder x - r^2
 * is then below 2^38). z receives 2^31 / sqrt(u) of x's high word, from
 * which 1 / r = z / 2^62 (relative error near 2^-29).
 */
static uint64_t sqrt_root_u64(uint64_t x, uint32_t *z) {
    uint32_t a = (uint32_t)(x >> 32);
    *z = sqrt_rsqrt_q31(a);
    uint64_t r = ((uint64_t)a * *z) >> 30;
    if (r > 0xffffffffu) {
        r = 0xffffffffu;
    }
    for (int i = 0; i < 3 && r * r > x; i++) {
        r--;
    }
    return r;
}

uint64_t math_isqrt_u64_soft(uint64_t x) {
    if (x == 0u) {
        return 0u;
    }
    /* Normalise by an even shift 2h so that x lies in [2^62, 2^64). */
    uint64_t xn = x;
    unsigned h = 0u;
    if ((xn >> 32) == 0u) {
        xn <<= 32;
        h += 16u;
    }
    if ((xn >> 48) == 0u) {
        xn <<= 16;
        h += 8u;
    }
    if ((xn >> 56) == 0u) {
        xn <<= 8;
        h += 4u;
    }
    if ((xn >> 60) == 0u) {
        xn <<= 4;
        h += 2u;
    }
    if ((xn >> 62) == 0u) {
        xn <<= 2;
        h += 1u;
    }
    /* One Newton step on the root: r + (xn - r^2) / (2 r), 1 / (2 r) = z / 2^63. */
    uint32_t z;
    uint64_t r = sqrt_root_u64(xn, &z);
    uint64_t q = (r + ((((xn - r * r) >> 6) * z) >> 57)) >> h;
    if (q > 0xffffffffu) {
        q = 0xffffffffu; /* the root of any 64-bit value */
    }
    for (int i = 0; i < 4 && q * q > x; i++) {
        q--;
    }
    for (int i = 0; i < 4 && q < 0xffffffffu && (q + 1u) * (q + 1u) <= x; i++) {
        q++;
    }
    return q;
}

double math_sqrt_f64_soft(double x) {
    uint64_t u = math_bits_f64(x);
    uint64_t mag = u & 0x7fffffffffffffffu;
    if (mag == 0u) {
        return x; /* sqrt(+-0) = +-0 */
    }
    if (mag > 0x7ff0000000000000u || (u >> 63) != 0u) {
        return math_nan_f64(); /* NaN, or any negative number including -inf */
    }
    if (mag == 0x7ff0000000000000u) {
        return x;
    }
    int e = (int)(u >> 52);
    uint64_t m = u & 0x000fffffffffffffu;
    if (e == 0) {
        /* Subnormal: normalise so that bit 52 is set (at most 52 steps). */
        e = 1;
        while (m < 0x0010000000000000u) {
            m <<= 1;
            e -= 1;
        }
    } else {
        m |= 0x0010000000000000u;
    }
    int ex = e - 1023;
    if (ex % 2 != 0) {
        m <<= 1;
        ex -= 1;
    }
    /*
     * N = M 2^54 = X 2^44 with X = M 2^10 in [2^62, 2^64), so
     * sqrt(N) = sqrt(X) 2^22. With r = floor-ish sqrt(X) from below and
     * rem = X - r^2 (exact, below 2^38), Newton's step gives
     * Q = r 2^22 + rem 2^21 / r; 1 / r is z / 2^62. Q lands within two
     * units of floor(sqrt(N)).
     */
    uint64_t xs = m << 10;
    uint32_t z;
    uint64_t r = sqrt_root_u64(xs, &z);
    uint64_t q = (r << 22) + ((((xs - r * r) >> 6) * z) >> 35);
    /* d = N - Q^2 modulo 2^64; |d| < 2^58, so bit 63 is its sign. */
    uint64_t d = (xs << 44) - q * q;
    for (int i = 0; i < 4 && (d >> 63) != 0u; i++) {
        q--;
        d += 2u * q + 1u;
    }
    for (int i = 0; i < 4 && d >= 2u * q + 1u; i++) {
        d -= 2u * q + 1u;
        q++;
    }
    /* q has 54 bits; a carry out of the significand would step the exponent. */
    uint64_t sig = (q >> 1) + (q & 1u);
    return math_from_bits_f64(((uint64_t)(ex / 2 + 1022) << 52) + sig);
}

float math_sqrt_f32_soft(float x) {
    uint32_t u = math_bits_f32(x);
    uint32_t mag = u & 0x7fffffffu;
    if (mag == 0u) {
        return x;
    }
    if (mag > 0x7f800000u || (u >> 31) != 0u) {
        return math_nan_f32();
    }
    if (mag == 0x7f800000u) {
        return x;
    }
    int e = (int)(u >> 23);
    uint32_t m = u & 0x007fffffu;
    if (e == 0) {
        e = 1;
        while (m < 0x00800000u) {
            m <<= 1;
            e -= 1;
        }
    } else {
        m |= 0x00800000u;
    }
    int ex = e - 127;
    if (ex % 2 != 0) {
        m <<= 1;
        ex -= 1;
    }
    /*
     * N = M 2^25 = a 2^18 with a = M 2^7 in [2^30, 2^32): sqrt(N) is
     * sqrt(a 2^32) / 2^7, whose estimate (a few units low) gives Q within
     * one unit; the exact remainder N - Q^2 (below 2^50) settles it.
     */
    uint64_t n = (uint64_t)m << 25;
    uint32_t a = m << 7;
    uint64_t q = (((uint64_t)a * sqrt_rsqrt_q31(a)) >> 30) >> 7;
    for (int i = 0; i < 4 && q * q > n; i++) {
        q--;
    }
    for (int i = 0; i < 4 && (q + 1u) * (q + 1u) <= n; i++) {
        q++;
    }
    uint32_t sig = (uint32_t)((q >> 1) + (q & 1u));
    return math_from_bits_f32(((uint32_t)(ex / 2 + 126) << 23) + sig);
}

/*
 * The entry points: the port's square-root instruction where uuv_config.h
 * says it has one (every IEEE 754 square-root instruction is correctly
 * rounded, so it gives the bits of the integer version above for every
 * non-negative input; test_math holds them together), the integer version
 * otherwise. The instruction needs -fno-math-errno, which the port passes
 * with the option: without it the compiler would call a libm sqrt on the
 * error path, and the freestanding link would fail.
 */
double math_sqrt_f64(double x) {
#if UUV_HW_SQRT_F64
    return __builtin_sqrt(x);
#else
    return math_sqrt_f64_soft(x);
#endif
}

float math_sqrt_f32(float x) {
#if UUV_HW_SQRT_F32
    return __builtin_sqrtf(x);
#else
    return math_sqrt_f32_soft(x);
#endif
}

/*
 * With a double-precision square root: x rounded to double is within 2^11
 * of x, so the root of it is within one unit of floor(sqrt(x)); the exact
 * integer comparisons below settle that unit (the squares below 2^64: the
 * root is capped at 2^32 - 1).
 */
uint64_t math_isqrt_u64(uint64_t x) {
#if UUV_HW_SQRT_F64
    uint64_t q = (uint64_t)__builtin_sqrt((double)x);
    if (q > 0xffffffffu) {
        q = 0xffffffffu;
    }
    while (q * q > x) {
        q--;
    }
    while (q < 0xffffffffu && (q + 1u) * (q + 1u) <= x) {
        q++;
    }
    return q;
#else
    return math_isqrt_u64_soft(x);
#endif
}
