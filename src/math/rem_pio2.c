/*
 * Argument reduction for the trigonometric functions: x = n*pi/2 + r with
 * |r| <= pi/4, r returned as an unevaluated sum hi + lo.
 *
 * Two methods, chosen by |x|:
 *
 * - Moderate |x| (below 1.5*2^20 rad in double, 400 rad in float): Cody and
 *   Waite's method. n = round(x*2/pi) in floating point, then pi/2 is
 *   subtracted n times in pieces P1 + P2 + P3 + P4. P1..P3 have so few
 *   significant bits that n*Pi is exact, and x - n*P1 is exact because the
 *   two are within a factor of two of each other; the further subtractions
 *   are done with two_sum, which keeps their rounding errors exactly, and
 *   only the tiny last product n*P4 rounds. pi/2 is carried to 152 bits in
 *   double (33 + 33 + 33 + 53) and 72 bits in float (16 + 16 + 16 + 24).
 *
 * - Large |x|: Payne and Hanek's method in integer arithmetic. With
 *   x = m * 2^e (m an integer significand), the bits of 2/pi whose product
 *   with x is a multiple of 4 are skipped, and the next 192 bits of 2/pi are
 *   multiplied by m exactly. Of the product, two bits give n mod 4 and the
 *   next 128 bits the fraction of a quarter turn, which is rounded to the
 *   nearest quarter, multiplied by pi/2 (a 128-bit constant) and converted
 *   to hi + lo. The bits of 2/pi beyond the window change the fraction by
 *   less than 2^-137.
 *
 * The closest a double comes to a multiple of pi/2 is about 2^-61 (a float:
 * 2^-27.8, measured over all floats below 2^24). The errors of both methods
 * are far below that, and leave hi + lo accurate to better than 2^-59
 * (double) and 2^-40 (float) relative for every finite x. Both methods
 * use only exact integer operations and IEEE operations in a fixed order,
 * so the result is the same on every port.
 */
#include "math/math_private.h"

/*
 * 2/pi in binary, most significant word first: word i holds the bits of
 * weight 2^-(32i+1) .. 2^-(32i+32). Computed with 500-digit arithmetic as
 * floor(2/pi * 2^(32(i+1))) mod 2^32. 40 words cover the largest double.
 */
static const uint32_t TWO_OVER_PI_BITS[40] = {
    0xa2f9836eu, 0x4e441529u, 0xfc2757d1u, 0xf534ddc0u, 0xdb629599u, 0x3c439041u, 0xfe5163abu,
    0xdebbc561u, 0xb7246e3au, 0x424dd2e0u, 0x06492eeau, 0x09d1921cu, 0xfe1deb1cu, 0xb129a73eu,
    0xe88235f5u, 0x2ebb4484u, 0xe99c7026u, 0xb45f7e41u, 0x3991d639u, 0x835339f4u, 0x9c845f8bu,
    0xbdf9283bu, 0x1ff897ffu, 0xde05980fu, 0xef2f118bu, 0x5a0a6d1fu, 0x6d367ecfu, 0x27cb09b7u,
    0x4f463f66u, 0x9e5fea2du, 0x7527bac7u, 0xebe5f17bu, 0x3d0739f7u, 0x8a5292eau, 0x6bfb5fb1u,
    0x1f8d5d08u, 0x56033046u, 0xfc7b6babu, 0xf0cfbc20u, 0x9af4361du,
};

/* round(pi/2 * 2^127), least significant word first. */
static const uint32_t PIO2_Q127[4] = {0x80dc1cd1u, 0xc4c6628bu, 0x2168c234u, 0xc90fdaa2u};

/* Word (limb) w of a little-endian array of n words; zero outside it. */
static uint32_t limb_at(const uint32_t *a, int n, int w) { return (w >= 0 && w < n) ? a[w] : 0u; }

/* Bits pos .. pos+31 of the integer held in a[0..n-1] (pos may be negative). */
static uint32_t limbs_get32(const uint32_t *a, int n, int pos) {
    int w = (pos >= 0) ? pos / 32 : -((31 - pos) / 32); /* floor(pos / 32) */
    int sh = pos - 32 * w;
    uint32_t v = limb_at(a, n, w) >> sh;
    if (sh != 0) {
        v |= limb_at(a, n, w + 1) << (32 - sh);
    }
    return v;
}

/* 32 bits of 2/pi starting at the bit of weight 2^-p (p >= 1). */
static uint32_t two_over_pi_word(int p) {
    int idx = (p - 1) / 32;
    int sh = (p - 1) % 32;
    uint32_t v = TWO_OVER_PI_BITS[idx] << sh;
    if (sh != 0) {
        v |= TWO_OVER_PI_BITS[idx + 1] >> (32 - sh);
    }
    return v;
}

/* out[0..na+nb-1] = a * b, little-endian 32-bit words, schoolbook. */
static void mul_limbs(const uint32_t *a, int na, const uint32_t *b, int nb, uint32_t *out) {
    for (int i = 0; i < na + nb; i++) {
        out[i] = 0u;
    }
    for (int j = 0; j < nb; j++) {
        uint64_t carry = 0u;
        for (int i = 0; i < na; i++) {
            /* At most (2^32-1)^2 + 2*(2^32-1) = 2^64 - 1: no overflow. */
            uint64_t t = (uint64_t)a[i] * b[j] + out[i + j] + carry;
            out[i + j] = (uint32_t)t;
            carry = t >> 32;
        }
        out[j + na] = (uint32_t)carry;
    }
}

/*
 * The Payne-Hanek core: for x = m * 2^e (m < 2^53, e <= 971), returns
 * n = round(x * 2/pi) mod 4 and sets r[0..3] to |x - n*pi/2| * 2^127
 * (at most pi/4 * 2^127) and *neg when x - n*pi/2 is negative.
 */
static unsigned reduce_wide(uint64_t m, int e, uint32_t r[4], int *neg) {
    /* Bits of 2/pi of weight 2^-i with e - i >= 2 only add multiples of 4. */
    int first = (e - 1 > 1) ? e - 1 : 1;
    uint32_t win[6];
    for (int j = 0; j < 6; j++) {
        win[5 - j] = two_over_pi_word(first + 32 * j);
    }
    uint32_t mw[2] = {(uint32_t)m, (uint32_t)(m >> 32)};
    uint32_t prod[8];
    mul_limbs(mw, 2, win, 6, prod);
    /* prod = x * 2/pi (mod 4, truncated) * 2^point. */
    int point = first + 191 - e;
    unsigned n = limbs_get32(prod, 8, point) & 3u;
    uint32_t f[4];
    for (int k = 0; k < 4; k++) {
        f[k] = limbs_get32(prod, 8, point - 128 + 32 * k);
    }
    *neg = 0;
    if ((f[3] & 0x80000000u) != 0u) {
        /* Fraction >= 1/2: round n up and take 1 - fraction (two's complement). */
        n = (n + 1u) & 3u;
        *neg = 1;
        uint32_t carry = 1u;
        for (int k = 0; k < 4; k++) {
            uint32_t v = ~f[k] + carry;
            carry = (carry != 0u && v == 0u) ? 1u : 0u;
            f[k] = v;
        }
    }
    uint32_t full[8];
    mul_limbs(f, 4, PIO2_Q127, 4, full);
    for (int k = 0; k < 4; k++) {
        r[k] = full[4 + k];
    }
    return n;
}

/* Index of the highest set bit of r[0..3], or -1 when r is zero. */
static int top_bit(const uint32_t r[4]) {
    for (int k = 3; k >= 0; k--) { /* LCOV_EXCL_BR_LINE: r is never 0 (see the callers) */
        if (r[k] != 0u) {
            int b = 31;
            while ((r[k] >> b) == 0u) {
                b--;
            }
            return 32 * k + b;
        }
    }
    return -1;
}

static unsigned rem_pio2_wide_f64(double ax, double *hi, double *lo) {
    uint64_t u = math_bits_f64(ax);
    int e = (int)(u >> 52) - 1075;
    uint64_t m = (u & 0x000fffffffffffffu) | 0x0010000000000000u;
    uint32_t r[4];
    int neg;
    unsigned n = reduce_wide(m, e, r, &neg);
    int t = top_bit(r);
    double h = 0.0;
    double l = 0.0;
    if (t >= 0) { /* LCOV_EXCL_BR_LINE: r >= 2^66: no double is within 2^-61 of k pi/2 */
        /* The 53 bits from the top and the 53 after them, converted exactly. */
        uint64_t bh =
            ((uint64_t)(limbs_get32(r, 4, t - 20) & 0x1fffffu) << 32) | limbs_get32(r, 4, t - 52);
        uint64_t bl =
            ((uint64_t)(limbs_get32(r, 4, t - 73) & 0x1fffffu) << 32) | limbs_get32(r, 4, t - 105);
        h = (double)bh * math_pow2i_f64(t - 52 - 127);
        l = (double)bl * math_pow2i_f64(t - 105 - 127);
        math_fast_two_sum_f64(h, l, &h, &l);
    }
    *hi = neg ? -h : h;
    *lo = neg ? -l : l;
    return n;
}

unsigned math_rem_pio2_f64(double x, double *hi, double *lo) {
    static const double TWO_OVER_PI = 0x1.45f306dc9c883p-1;
    static const double P1 = 0x1.921fb544p+0;
    static const double P2 = 0x1.0b4611a6p-34;
    static const double P3 = 0x1.3198a2ep-69;
    static const double P4 = 0x1.b839a252049c1p-104;
    double ax = math_fabs_f64(x);
    if (ax < 0x1.8p20) {
        /* |n| < 2^20: n*P1, n*P2, n*P3 are exact (20 + 33 bits). */
        double fn = (x * TWO_OVER_PI + 0x1.8p52) - 0x1.8p52;
        int32_t n = (int32_t)fn;
        double r = x - fn * P1;
        double a;
        double ae;
        double b;
        double be;
        math_two_sum_f64(r, -(fn * P2), &a, &ae);
        math_two_sum_f64(a, -(fn * P3), &b, &be);
        math_fast_two_sum_f64(b, (ae + be) - fn * P4, hi, lo);
        return (uint32_t)n & 3u;
    }
    double h;
    double l;
    unsigned n = rem_pio2_wide_f64(ax, &h, &l);
    if (x < 0.0) {
        *hi = -h;
        *lo = -l;
        return (4u - n) & 3u;
    }
    *hi = h;
    *lo = l;
    return n;
}

static unsigned rem_pio2_wide_f32(float ax, float *hi, float *lo) {
    uint32_t u = math_bits_f32(ax);
    int e = (int)(u >> 23) - 150;
    uint64_t m = (uint64_t)((u & 0x007fffffu) | 0x00800000u);
    uint32_t r[4];
    int neg;
    unsigned n = reduce_wide(m, e, r, &neg);
    int t = top_bit(r);
    float h = 0.0f;
    float l = 0.0f;
    if (t >= 0) { /* LCOV_EXCL_BR_LINE: r >= 2^66: no double is within 2^-61 of k pi/2 */
        /* 24 + 24 bits, each converted exactly and scaled into place. */
        float bh = (float)(limbs_get32(r, 4, t - 23) & 0xffffffu) * 0x1p-23f;
        float bl = (float)(limbs_get32(r, 4, t - 47) & 0xffffffu) * 0x1p-23f;
        h = math_scale_f32(bh, t - 127);
        l = math_scale_f32(bl, t - 24 - 127);
        math_fast_two_sum_f32(h, l, &h, &l);
    }
    *hi = neg ? -h : h;
    *lo = neg ? -l : l;
    return n;
}

unsigned math_rem_pio2_f32(float x, float *hi, float *lo) {
    static const float TWO_OVER_PI = 0x1.45f306p-1f;
    static const float P1 = 0x1.922p+0f;
    static const float P2 = -0x1.2aeep-18f;
    static const float P3 = -0x1.e974p-35f;
    static const float P4 = 0x1.1a6264p-54f;
    float ax = math_fabs_f32(x);
    if (ax < 400.0f) {
        /* |n| <= 255: n*P1, n*P2, n*P3 are exact (8 + 16 bits). */
        float fn = (x * TWO_OVER_PI + 0x1.8p23f) - 0x1.8p23f;
        int32_t n = (int32_t)fn;
        float r = x - fn * P1;
        float a;
        float ae;
        float b;
        float be;
        math_two_sum_f32(r, -(fn * P2), &a, &ae);
        math_two_sum_f32(a, -(fn * P3), &b, &be);
        math_fast_two_sum_f32(b, (ae + be) - fn * P4, hi, lo);
        return (uint32_t)n & 3u;
    }
    float h;
    float l;
    unsigned n = rem_pio2_wide_f32(ax, &h, &l);
    if (x < 0.0f) {
        *hi = -h;
        *lo = -l;
        return (4u - n) & 3u;
    }
    *hi = h;
    *lo = l;
    return n;
}
