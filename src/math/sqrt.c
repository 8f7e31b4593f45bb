/*
 * Correctly rounded square root by the digit-by-digit (restoring) method on
 * the integer significand, one result bit per step.
 *
 * Write x = M * 2^(E - p) with the significand M an integer of p + 1 bits
 * (p = 52 or 23) and E even (M is doubled when E is odd), so that
 * y = M * 2^-p lies in [1, 4) and sqrt(x) = sqrt(y) * 2^(E/2). The loop
 * builds Q = floor(sqrt(y) * 2^(p+1)), the root with one bit more than the
 * result needs, trying bits from the most significant down: with the
 * partial root Q_k, a candidate bit b is kept when (Q_k + b)^2 still fits
 * under y. The remainder y - Q_k^2 is kept scaled in `rem`, which doubles at
 * each step; the test then reads 2*Q_k + b <= rem, with s = 2*Q_k carried
 * along, so every quantity is an integer below 2^(p+5).
 *
 * The last bit of Q is the rounding bit. A square root is never exactly
 * halfway between two floating-point numbers (a root with p + 2 significant
 * bits would square to a number with 2p + 3 of them, more than M holds), so
 * round to nearest is "add the rounding bit". The result is the IEEE 754
 * square root bit for bit, on every port, with integer operations only.
 * The loop has no data-dependent branch, so its time does not depend on x.
 */
#include "math/math_private.h"

double math_sqrt_f64(double x) {
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
    uint64_t rem = m << 1; /* y * 2^53, y = m * 2^-52 in [1, 4) */
    uint64_t s = 0u;
    uint64_t q = 0u;
    for (uint64_t bit = (uint64_t)1u << 53; bit != 0u; bit >>= 1) {
        uint64_t t = s + bit;
        uint64_t keep = (uint64_t)0u - (uint64_t)(t <= rem); /* all ones when kept */
        s += (bit << 1) & keep;
        rem -= t & keep;
        q |= bit & keep;
        rem <<= 1;
    }
    /* q has 54 bits; a carry out of the significand would step the exponent. */
    uint64_t sig = (q >> 1) + (q & 1u);
    return math_from_bits_f64(((uint64_t)(ex / 2 + 1022) << 52) + sig);
}

float math_sqrt_f32(float x) {
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
    uint32_t rem = m << 1; /* y * 2^24 */
    uint32_t s = 0u;
    uint32_t q = 0u;
    for (uint32_t bit = (uint32_t)1u << 24; bit != 0u; bit >>= 1) {
        uint32_t t = s + bit;
        uint32_t keep = (uint32_t)0u - (uint32_t)(t <= rem); /* all ones when kept */
        s += (bit << 1) & keep;
        rem -= t & keep;
        q |= bit & keep;
        rem <<= 1;
    }
    uint32_t sig = (q >> 1) + (q & 1u);
    return math_from_bits_f32(((uint32_t)(ex / 2 + 126) << 23) + sig);
}
