/*
 * exp and log in single precision, computed in float only.
 *
 * exp: x = n*ln2 + r, n = round(x/ln2), |r| <= ln2/2 (ln2 in two parts, the
 * first with 15 significant bits so that n*ln2_hi is exact for |n| <= 255),
 * exp(r) = 1 + r + r^2 * E(r) with E a minimax polynomial of degree 4
 * (relative error 2^-28.2), then an exact scaling by 2^n. r is kept as
 * rh + rl and 1 + rh is formed exactly, so that the result rounds once.
 *
 * log: x = 2^k * (1 + f), 1 + f in [sqrt(1/2), sqrt(2)), s = f / (2 + f),
 *     log(1 + f) = 2 atanh(s) = f - (f^2/2 - s*(f^2/2 + R(s^2)))
 * with R(z) = z * L(z), L a minimax polynomial of degree 2 (error 2^-29.2).
 * Written that way the rounding of s only touches the small term s*(...),
 * and k*ln2 is added in two parts.
 *
 * Both polynomials come from the Remez exchange in 90-digit arithmetic with
 * coefficients rounded to float one at a time and the rest re-optimised.
 */
#include "math/math_private.h"

float math_exp_f32(float x) {
    static const float INV_LN2 = 0x1.715476p+0f;
    static const float LN2_HI = 0x1.62e4p-1f;
    static const float LN2_LO = 0x1.7f7d1cp-20f;
    static const float E0 = 0x1.fffffcp-2f;
    static const float E1 = 0x1.55548cp-3f;
    static const float E2 = 0x1.555858p-5f;
    static const float E3 = 0x1.123de0p-7f;
    static const float E4 = 0x1.6ac74ep-10f;
    if (math_isnan_f32(x)) {
        return math_nan_f32();
    }
    if (x > 0x1.62e43p+6f) {
        return math_inf_f32(); /* above 128*ln2 */
    }
    if (x < -0x1.9fe36ap+6f) {
        return 0.0f; /* below -150*ln2: rounds to zero */
    }
    float fn = (x * INV_LN2 + 0x1.8p23f) - 0x1.8p23f;
    int32_t n = (int32_t)fn;    /* |n| <= 150 */
    float rh = x - fn * LN2_HI; /* exact */
    float rl = -(fn * LN2_LO);
    float r = rh + rl;
    /* 1 + r + r^2 E(r) with 1 + rh exact as s + se, so that only the last addition rounds. */
    float s;
    float se;
    math_fast_two_sum_f32(1.0f, rh, &s, &se);
    float p = (r * r) * (E0 + r * (E1 + r * (E2 + r * (E3 + r * E4))));
    return math_scale_f32(s + ((se + rl) + p), (int)n);
}

float math_log_f32(float x) {
    static const float LN2_HI = 0x1.62e4p-1f;
    static const float LN2_LO = 0x1.7f7d1cp-20f;
    static const float L0 = 0x1.55557ap-1f;
    static const float L1 = 0x1.995ed4p-2f;
    static const float L2 = 0x1.31e0d8p-2f;
    if (x == 0.0f) {
        return -math_inf_f32();
    }
    if (math_isnan_f32(x) || x < 0.0f) {
        return math_nan_f32();
    }
    if (math_isinf_f32(x)) {
        return x;
    }
    uint32_t u = math_bits_f32(x);
    int k = 0;
    if (u < 0x00800000u) {
        u = math_bits_f32(x * 0x1p25f); /* subnormal: exact rescaling */
        k = -25;
    }
    uint32_t mant = u & 0x007fffffu;
    float m;
    if (mant >= 0x3504f3u) { /* 1.mant >= sqrt(2): use (1.mant)/2 */
        m = math_from_bits_f32(mant | (126u << 23));
        k += (int)(u >> 23) - 126;
    } else {
        m = math_from_bits_f32(mant | (127u << 23));
        k += (int)(u >> 23) - 127;
    }
    float f = m - 1.0f; /* exact */
    float s = f / (2.0f + f);
    float z = s * s;
    float rz = z * (L0 + z * (L1 + z * L2));
    float hfsq = 0.5f * f * f;
    float kf = (float)k;
    return kf * LN2_HI - ((hfsq - (s * (hfsq + rz) + kf * LN2_LO)) - f);
}
