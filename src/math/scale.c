/*
 * Multiplication by a power of two with a single rounding. exp and the
 * argument reduction produce a value near 1 and a binary exponent; the
 * exponent may lie outside the range of a normal power of two, so the
 * scaling is split in two steps of which only the last can round.
 */
#include "math/math_private.h"

double math_scale_f64(double x, int k) {
    /* The first step is exact: x in [0.5, 4) stays normal and finite. */
    if (k > 1023) {
        x *= 0x1p1000;
        k -= 1000;
    } else if (k < -1022) {
        x *= 0x1p-1000;
        k += 1000;
    }
    /* Only reached outside the documented range; keeps the bit pattern valid. */
    if (k > 1023) { /* LCOV_EXCL_BR_LINE: the only caller (exp) passes k <= 1024 */
        k = 1023;
    } else if (k < -1022) { /* LCOV_EXCL_BR_LINE: exp passes k >= -1075 */
        k = -1022;
    }
    return x * math_pow2i_f64(k);
}

float math_scale_f32(float x, int k) {
    if (k > 127) {
        x *= 0x1p100f;
        k -= 100;
    } else if (k < -126) {
        x *= 0x1p-100f;
        k += 100;
    }
    /* As above; the callers (exp_f32, rem_pio2) pass -151 <= k <= 128. */
    if (k > 127) { /* LCOV_EXCL_BR_LINE: k <= 128 - 100 after the first step */
        k = 127;
    } else if (k < -126) { /* LCOV_EXCL_BR_LINE: k >= -151 + 100 after the first step */
        k = -126;
    }
    return x * math_pow2i_f32(k);
}
