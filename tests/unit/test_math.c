/*
 * Tests of the freestanding math library (src/math) that run on the host and
 * on every target, without libm. References are values computed once in
 * 80-digit arithmetic and stored here correctly rounded, exact identities,
 * exact integer arithmetic, and the special cases of C99 Annex F. The dense
 * comparison against the host libm is tests/host/test_math_libm.c.
 *
 * The last test folds the bits of a few thousand results into a checksum
 * and compares it with the value the host computes: equal checksums on a
 * target mean that the target computed the same bits as the host. After a
 * deliberate change to an algorithm, run the host unit tests and copy the
 * printed checksum into MATH_CHECKSUM_F64 / MATH_CHECKSUM_F32.
 */
#include <stdbool.h>
#include <stdint.h>

#include "math/umath.h"
#include "ut.h"

void suite_math(void);

#define MATH_CHECKSUM_F64 0xf187c530609c852au
#define MATH_CHECKSUM_F32 0x84449c02bd8b8826u

/* ---- helpers -------------------------------------------------------------- */

/* A key that orders doubles like their values, with -0 and +0 equal. */
static uint64_t order_key_f64(double x) {
    uint64_t u = math_bits_f64(x);
    uint64_t mag = u & 0x7fffffffffffffffu;
    return ((u >> 63) != 0u) ? 0x8000000000000000u - mag : 0x8000000000000000u + mag;
}

static uint32_t order_key_f32(float x) {
    uint32_t u = math_bits_f32(x);
    uint32_t mag = u & 0x7fffffffu;
    return ((u >> 31) != 0u) ? 0x80000000u - mag : 0x80000000u + mag;
}

/* Distance in units in the last place; NaN is infinitely far from anything. */
static uint64_t ulps_f64(double a, double b) {
    if (math_isnan_f64(a) || math_isnan_f64(b)) {
        return UINT64_MAX;
    }
    uint64_t ka = order_key_f64(a);
    uint64_t kb = order_key_f64(b);
    return (ka > kb) ? ka - kb : kb - ka;
}

static uint32_t ulps_f32(float a, float b) {
    if (math_isnan_f32(a) || math_isnan_f32(b)) {
        return UINT32_MAX;
    }
    uint32_t ka = order_key_f32(a);
    uint32_t kb = order_key_f32(b);
    return (ka > kb) ? ka - kb : kb - ka;
}

static bool same_f64(double a, double b) { return math_bits_f64(a) == math_bits_f64(b); }
static bool same_f32(float a, float b) { return math_bits_f32(a) == math_bits_f32(b); }

/* A canonical NaN, as the library promises for every NaN it makes. */
static bool canonical_nan_f64(double x) { return math_bits_f64(x) == 0x7ff8000000000000u; }
static bool canonical_nan_f32(float x) { return math_bits_f32(x) == 0x7fc00000u; }

/* A small deterministic generator (ut.h). */
static uint64_t lcg_next(uint64_t *state) { return ut_rand_u64(state); }

/* ---- square root ---------------------------------------------------------- */

/* The 128-bit square of a < 2^63 as hi * 2^64 + lo. */
static void square_u128(uint64_t a, uint64_t *hi, uint64_t *lo) {
    uint64_t a0 = a & 0xffffffffu;
    uint64_t a1 = a >> 32;
    uint64_t low = a0 * a0;
    uint64_t mid = a0 * a1; /* counted twice */
    uint64_t high = a1 * a1;
    uint64_t mid_lo = mid << 33;
    uint64_t mid_hi = mid >> 31;
    *lo = low + mid_lo;
    *hi = high + mid_hi + ((*lo < low) ? 1u : 0u);
}

static bool less_u128(uint64_t ahi, uint64_t alo, uint64_t bhi, uint64_t blo) {
    return (ahi < bhi) || (ahi == bhi && alo < blo);
}

/*
 * True when r = sqrt(x) is correctly rounded, for x in [1, 4): with
 * x = X * 2^-52 and r = R * 2^-52, (2R - 1)^2 < X * 2^54 < (2R + 1)^2.
 */
static bool sqrt_correct_f64(double x, double r) {
    uint64_t big_x = (math_bits_f64(x) & 0x000fffffffffffffu) | 0x0010000000000000u;
    if (x >= 2.0) {
        big_x <<= 1;
    }
    uint64_t big_r = (math_bits_f64(r) & 0x000fffffffffffffu) | 0x0010000000000000u;
    uint64_t xhi = big_x >> 10; /* X * 2^54 as a 128-bit number */
    uint64_t xlo = big_x << 54;
    uint64_t lhi;
    uint64_t llo;
    uint64_t hhi;
    uint64_t hlo;
    square_u128(2u * big_r - 1u, &lhi, &llo);
    square_u128(2u * big_r + 1u, &hhi, &hlo);
    return less_u128(lhi, llo, xhi, xlo) && less_u128(xhi, xlo, hhi, hlo);
}

/* The same for float, x in [1, 4): (2R - 1)^2 < X * 2^25 < (2R + 1)^2 in 64 bits. */
static bool sqrt_correct_f32(float x, float r) {
    uint64_t big_x = (math_bits_f32(x) & 0x007fffffu) | 0x00800000u;
    if (x >= 2.0f) {
        big_x <<= 1;
    }
    uint64_t big_r = (math_bits_f32(r) & 0x007fffffu) | 0x00800000u;
    uint64_t lo = (2u * big_r - 1u) * (2u * big_r - 1u);
    uint64_t hi = (2u * big_r + 1u) * (2u * big_r + 1u);
    uint64_t mid = big_x << 25;
    return lo < mid && mid < hi;
}

/* math_isqrt_u64(x) = q with q^2 <= x < (q + 1)^2, the squares formed in 128 bits. */
static bool isqrt_ok(uint64_t x) {
    uint64_t q = math_isqrt_u64(x);
    uint64_t lhi;
    uint64_t llo;
    uint64_t hhi;
    uint64_t hlo;
    if (q > 0xffffffffu) {
        return false;
    }
    square_u128(q, &lhi, &llo);
    square_u128(q + 1u, &hhi, &hlo);
    return !less_u128(0u, x, lhi, llo) && less_u128(0u, x, hhi, hlo);
}

static void test_sqrt(void) {
    UT_TEST("sqrt: perfect squares k^2 give k exactly (k up to 2^26)");
    bool ok = true;
    for (uint32_t k = 0u; k < 1000u; k++) {
        double d = (double)k;
        double big = (double)(67108863u - 21u * k); /* near 2^26: k^2 uses all 53 bits */
        ok = ok && same_f64(math_sqrt_f64(d * d), d) && same_f64(math_sqrt_f64(big * big), big);
        float f = (float)(4u * k + 1u);
        ok = ok && same_f32(math_sqrt_f32(f * f), f);
    }
    UT_CHECK(ok);

    UT_TEST("sqrt: bit patterns of the IEEE 754 square root for known inputs");
    UT_CHECK(math_bits_f64(math_sqrt_f64(2.0)) == 0x3ff6a09e667f3bcdu);
    UT_CHECK(math_bits_f64(math_sqrt_f64(3.0)) == 0x3ffbb67ae8584caau);
    UT_CHECK(math_bits_f64(math_sqrt_f64(0.1)) == 0x3fd43d136248490fu);
    UT_CHECK(math_bits_f64(math_sqrt_f64(0x1.fffffffffffffp+1023)) == 0x5fefffffffffffffu);
    UT_CHECK(math_bits_f64(math_sqrt_f64(0x1p-1074)) == 0x1e60000000000000u);
    UT_CHECK(math_bits_f32(math_sqrt_f32(2.0f)) == 0x3fb504f3u);
    UT_CHECK(math_bits_f32(math_sqrt_f32(3.0f)) == 0x3fddb3d7u);
    UT_CHECK(math_bits_f32(math_sqrt_f32(0.1f)) == 0x3ea1e89bu);
    UT_CHECK(math_bits_f32(math_sqrt_f32(0x1.fffffep+127f)) == 0x5f7fffffu);
    UT_CHECK(math_bits_f32(math_sqrt_f32(0x1p-148f)) == 0x1a800000u);

    UT_TEST("sqrt: correctly rounded for pseudo-random x in [1, 4), by exact integer bounds");
    uint64_t state = 12345u;
    ok = true;
    for (int i = 0; i < 1000; i++) {
        uint64_t v = lcg_next(&state);
        double x = math_from_bits_f64(0x3ff0000000000000u + (v >> 11)); /* [1, 4) */
        float xf = math_from_bits_f32(0x3f800000u + (uint32_t)(v >> 40));
        ok = ok && sqrt_correct_f64(x, math_sqrt_f64(x)) && sqrt_correct_f32(xf, math_sqrt_f32(xf));
    }
    UT_CHECK(ok);

    UT_TEST("isqrt_u64: the floor root, q^2 <= x < (q + 1)^2 in exact 128-bit arithmetic, at "
            "0..4, around k^2 for pseudo-random k of every width, at 2^62, 2^63 and 2^64 - 1");
    static const uint64_t edges[] = {0u, 1u, 2u, 3u, 4u, 0x4000000000000000u,
                                     0x8000000000000000u, 0xfffffffe00000000u,
                                     0xfffffffe00000001u, 0xffffffffffffffffu};
    ok = true;
    for (unsigned i = 0u; i < sizeof edges / sizeof edges[0]; i++) {
        ok = ok && isqrt_ok(edges[i]);
    }
    for (int i = 0; i < 2000; i++) {
        uint64_t v = lcg_next(&state);
        uint64_t k = v >> (32 + (i % 32)); /* every width up to 32 bits */
        uint64_t k2 = k * k;
        ok = ok && isqrt_ok(k2) && isqrt_ok(k2 + k) && isqrt_ok(k2 + 2u * k) &&
             (k == 0u || isqrt_ok(k2 - 1u)) && isqrt_ok(v >> (i % 64));
    }
    UT_CHECK(ok);

    UT_TEST("sqrt: special values (C99 Annex F): +-0, -x, +inf, NaN");
    UT_CHECK(same_f64(math_sqrt_f64(-0.0), -0.0));
    UT_CHECK(same_f64(math_sqrt_f64(0.0), 0.0));
    UT_CHECK(canonical_nan_f64(math_sqrt_f64_soft(-1.0)));
    UT_CHECK(canonical_nan_f64(math_sqrt_f64_soft(-math_inf_f64())));
    UT_CHECK(canonical_nan_f64(math_sqrt_f64_soft(-math_nan_f64())));
    UT_CHECK(math_isnan_f64(math_sqrt_f64(-1.0)) && math_isnan_f64(math_sqrt_f64(-math_inf_f64())));
    UT_CHECK(math_sqrt_f64(math_inf_f64()) == math_inf_f64());
    UT_CHECK(same_f32(math_sqrt_f32(-0.0f), -0.0f));
    UT_CHECK(canonical_nan_f32(math_sqrt_f32_soft(-0x1p-149f)));
    UT_CHECK(math_isnan_f32(math_sqrt_f32(-0x1p-149f)));
    UT_CHECK(math_sqrt_f32(math_inf_f32()) == math_inf_f32());

    /*
     * Where the port has a square-root instruction (UUV_HW_SQRT_F64/F32,
     * src/uuv_config.h), the entry points use it; elsewhere they are the
     * integer version and these checks compare it with itself. A negative
     * input gives a NaN either way (the instruction's default NaN may
     * carry another sign), so only non-negative inputs are compared by bits.
     */
    UT_TEST("sqrt: the entry points give the integer version's bits for every kind of "
            "non-negative input: the vessel's and controller's ranges, subnormals, the "
            "extremes, pseudo-random bit patterns over every exponent");
    static const double edge64[] = {0.0, 0x1p-1074, 0x1.ffffffffffffep-1023, 0x1p-1022, 0.5, 1.0,
                                    1.5, 2.0, 1e-6, 0.36, 2.25e4, 0x1.fffffffffffffp+1023};
    ok = true;
    for (unsigned i = 0u; i < sizeof edge64 / sizeof edge64[0]; i++) {
        ok = ok && same_f64(math_sqrt_f64(edge64[i]), math_sqrt_f64_soft(edge64[i])) &&
             same_f32(math_sqrt_f32((float)edge64[i]), math_sqrt_f32_soft((float)edge64[i]));
    }
    for (int i = 0; i < 20000; i++) {
        uint64_t v = lcg_next(&state);
        double x = math_from_bits_f64((v >> 1) % 0x7ff0000000000000u); /* finite, >= 0 */
        float xf = math_from_bits_f32((uint32_t)(v >> 33) % 0x7f800000u);
        double y = (double)(v >> 40) * 1e-4; /* 0 ... 1.7e8: flows, speeds, currents */
        ok = ok && same_f64(math_sqrt_f64(x), math_sqrt_f64_soft(x)) &&
             same_f64(math_sqrt_f64(y), math_sqrt_f64_soft(y)) &&
             same_f32(math_sqrt_f32(xf), math_sqrt_f32_soft(xf)) &&
             same_f32(math_sqrt_f32((float)y), math_sqrt_f32_soft((float)y));
    }
    UT_CHECK(ok);

    UT_TEST("isqrt_u64: the entry point equals the integer version at the edges and on "
            "pseudo-random squares and neighbours of every width");
    ok = true;
    for (unsigned i = 0u; i < sizeof edges / sizeof edges[0]; i++) {
        ok = ok && math_isqrt_u64(edges[i]) == math_isqrt_u64_soft(edges[i]);
    }
    for (int i = 0; i < 20000; i++) {
        uint64_t v = lcg_next(&state);
        uint64_t k = v >> (32 + (i % 32));
        uint64_t x = (i % 3 == 0) ? k * k - 1u : ((i % 3 == 1) ? k * k : v >> (i % 64));
        ok = ok && math_isqrt_u64(x) == math_isqrt_u64_soft(x);
    }
    UT_CHECK(ok);
}

/* ---- trigonometric functions ---------------------------------------------- */

/* x, sin x, cos x, tan x, correctly rounded (80-digit arithmetic). */
static const double TRIG_REF_F64[][4] = {
    {0x1p+0, 0x1.aed548f090ceep-1, 0x1.14a280fb5068cp-1, 0x1.8eb245cbee3a6p+0},
    {0x1p-1, 0x1.eaee8744b05fp-2, 0x1.c1528065b7d5p-1, 0x1.17b4f5bf3474ap-1},
    {0x1p+1, 0x1.d18f6ead1b446p-1, -0x1.aa22657537205p-2, -0x1.17af62e0950f8p+1},
    {0x1.8p+1, 0x1.210386db6d55bp-3, -0x1.fae04be85e5d2p-1, -0x1.23ef71254b86fp-3},
    {0x1.4p+3, -0x1.1689ef5f34f52p-1, -0x1.ad9ac890c6b1fp-1, 0x1.4bf5f34be3782p-1},
    {0x1.9p+6, -0x1.03425b78c4db8p-1, 0x1.b981dbf665fdfp-1, -0x1.2ca74d62b5d38p-1},
    {0x1.86ap+16, 0x1.24daa9c527e96p-5, -0x1.ffac3841b3da7p-1, -0x1.250a9d503313dp-5},
    {0x1.0f0cf064dd592p+73, -0x1.b453ab76bf397p-1, 0x1.0be2cef01c8f4p-1, -0x1.a0f79c1b6b257p+0},
    {0x1p+1023, 0x1.205248cbdb76p-1, -0x1.a719f26c232bfp-1, -0x1.5ce6b4c0d02a3p-1},
    {0x1.921fb54442d18p+1, 0x1.1a62633145c07p-53, -0x1p+0, -0x1.1a62633145c07p-53},
    {0x1.921fb54442d18p+0, 0x1p+0, 0x1.1a62633145c07p-54, 0x1.d02967c31cdb5p+53},
    {-0x1.ep+2, -0x1.e041886fcae3p-1, 0x1.62f45e66f5c2fp-2, -0x1.5a5ea99227d5bp+1},
    {0x1p-20, 0x1.ffffffffffaabp-21, 0x1.ffffffffffp-1, 0x1.0000000000555p-20},
    /* The double closest to a multiple of pi/2 (cos is about -2^-61). */
    {0x1.6ac5b262ca1ffp+849, 0x1p+0, -0x1.14ae72e6ba22fp-61, -0x1.d9ba9a7975636p+60},
};

/* The same in float; 0x1.2d97c8p+2 and 0x1.f9cbe2p+7 are the floats closest to k*pi/2 below 2^8. */
static const float TRIG_REF_F32[][4] = {
    {0x1p+0f, 0x1.aed548p-1f, 0x1.14a28p-1f, 0x1.8eb246p+0f},
    {0x1p-1f, 0x1.eaee88p-2f, 0x1.c1528p-1f, 0x1.17b4f6p-1f},
    {0x1p+1f, 0x1.d18f6ep-1f, -0x1.aa2266p-2f, -0x1.17af62p+1f},
    {0x1.8p+1f, 0x1.210386p-3f, -0x1.fae04cp-1f, -0x1.23ef72p-3f},
    {0x1.4p+3f, -0x1.1689fp-1f, -0x1.ad9ac8p-1f, 0x1.4bf5f4p-1f},
    {0x1.9p+6f, -0x1.03425cp-1f, 0x1.b981dcp-1f, -0x1.2ca74ep-1f},
    {0x1.86ap+16f, 0x1.24daaap-5f, -0x1.ffac38p-1f, -0x1.250a9ep-5f},
    {0x1p+100f, -0x1.be8edap-1f, 0x1.f4eb4p-2f, -0x1.c86fcp+0f},
    {0x1.921fb6p+1f, -0x1.777a5cp-24f, -0x1p+0f, 0x1.777a5cp-24f},
    {0x1.2d97c8p+2f, -0x1p+0f, 0x1.99bc5cp-27f, -0x1.3fe4dap+26f},
    {0x1.f9cbe2p+7f, 0x1p+0f, -0x1.1fa3bcp-28f, -0x1.c7ae6ep+27f},
    {-0x1.ep+2f, -0x1.e04188p-1f, 0x1.62f45ep-2f, -0x1.5a5eaap+1f},
};

static void test_trig_values(void) {
    UT_TEST("sin, cos, tan f64: within 1 ulp of correctly rounded values (to x = 2^1023)");
    for (unsigned i = 0u; i < sizeof TRIG_REF_F64 / sizeof TRIG_REF_F64[0]; i++) {
        const double *t = TRIG_REF_F64[i];
        double s;
        double c;
        math_sincos_f64(t[0], &s, &c);
        bool ok = UT_CHECK(ulps_f64(math_sin_f64(t[0]), t[1]) <= 1u);
        ok = UT_CHECK(ulps_f64(math_cos_f64(t[0]), t[2]) <= 1u) && ok;
        ok = UT_CHECK(ulps_f64(math_tan_f64(t[0]), t[3]) <= 1u) && ok;
        ok = UT_CHECK(same_f64(s, math_sin_f64(t[0])) && same_f64(c, math_cos_f64(t[0]))) && ok;
        if (!ok) {
            ut_info("x = %.17g (row %u)", t[0], i);
        }
    }

    UT_TEST("sin, cos, tan f32: within 1 ulp of correctly rounded values");
    for (unsigned i = 0u; i < sizeof TRIG_REF_F32 / sizeof TRIG_REF_F32[0]; i++) {
        const float *t = TRIG_REF_F32[i];
        float s;
        float c;
        math_sincos_f32(t[0], &s, &c);
        bool ok = UT_CHECK(ulps_f32(math_sin_f32(t[0]), t[1]) <= 1u);
        ok = UT_CHECK(ulps_f32(math_cos_f32(t[0]), t[2]) <= 1u) && ok;
        ok = UT_CHECK(ulps_f32(math_tan_f32(t[0]), t[3]) <= 1u) && ok;
        ok = UT_CHECK(same_f32(s, math_sin_f32(t[0])) && same_f32(c, math_cos_f32(t[0]))) && ok;
        if (!ok) {
            ut_info("x = %.9g (row %u)", (double)t[0], i);
        }
    }

    UT_TEST("sin, cos: pi/6, pi/3 and pi/4 give 1/2 and sqrt(2)/2 to the rounding of the argument");
    UT_NEAR(math_sin_f64(MATH_PI_F64 / 6.0), 0.5, 2e-16);
    UT_NEAR(math_cos_f64(MATH_PI_F64 / 3.0), 0.5, 2e-16);
    UT_NEAR(math_cos_f64(MATH_QUARTER_PI_F64), MATH_SQRT2_F64 / 2.0, 2e-16);
    UT_NEAR(math_sin_f32(MATH_PI_F32 / 6.0f), 0.5f, 1.2e-7f);
    UT_NEAR(math_cos_f32(MATH_PI_F32 / 3.0f), 0.5f, 1.2e-7f);
    UT_NEAR(math_tan_f32(MATH_QUARTER_PI_F32), 1.0f, 1.2e-7f);
}

static void test_trig_special(void) {
    UT_TEST("sin, cos, tan: zeros keep their sign, tiny x returns x, inf and NaN give NaN");
    UT_CHECK(same_f64(math_sin_f64(-0.0), -0.0) && same_f64(math_tan_f64(-0.0), -0.0));
    UT_CHECK(math_cos_f64(-0.0) == 1.0 && math_cos_f32(-0.0f) == 1.0f);
    UT_CHECK(same_f32(math_sin_f32(-0.0f), -0.0f) && same_f32(math_tan_f32(-0.0f), -0.0f));
    UT_CHECK(same_f64(math_sin_f64(0x1p-1074), 0x1p-1074) &&
             same_f64(math_tan_f64(-1e-300), -1e-300));
    UT_CHECK(same_f32(math_sin_f32(0x1p-149f), 0x1p-149f));
    UT_CHECK(canonical_nan_f64(math_sin_f64(math_inf_f64())));
    UT_CHECK(canonical_nan_f64(math_cos_f64(-math_inf_f64())));
    UT_CHECK(canonical_nan_f64(math_tan_f64(math_nan_f64())));
    UT_CHECK(canonical_nan_f32(math_sin_f32(-math_inf_f32())));
    UT_CHECK(canonical_nan_f32(math_cos_f32(math_nan_f32())));
    UT_CHECK(canonical_nan_f32(math_tan_f32(math_inf_f32())));
    double s;
    double c;
    math_sincos_f64(math_nan_f64(), &s, &c);
    UT_CHECK(canonical_nan_f64(s) && canonical_nan_f64(c));

    UT_TEST("sin, cos: every finite magnitude up to the largest double returns a value in [-1, 1]");
    bool ok = true;
    for (int e = 0; e < 1024; e += 3) {
        double x = math_from_bits_f64(((uint64_t)(e + 1023) << 52) | 0x5555555555555u);
        double sv = math_sin_f64(x);
        double cv = math_cos_f64(-x);
        ok = ok && sv >= -1.0 && sv <= 1.0 && cv >= -1.0 && cv <= 1.0;
        ok = ok && ulps_f64(sv * sv + cv * cv, 1.0) <= 4u;
    }
    for (int e = 0; e < 128; e++) {
        float x = math_from_bits_f32(((uint32_t)(e + 127) << 23) | 0x2aaaaau);
        float sv = math_sin_f32(x);
        float cv = math_cos_f32(x);
        ok = ok && sv >= -1.0f && sv <= 1.0f && ulps_f32(sv * sv + cv * cv, 1.0f) <= 4u;
    }
    UT_CHECK(ok);
}

static void test_trig_identities(void) {
    UT_TEST("sin, cos, tan: odd and even symmetry hold bit for bit");
    bool ok = true;
    for (int i = 0; i < 200; i++) {
        double x = -60.0 + 0.6271 * (double)i;
        x = (i % 7 == 0) ? x * 1e5 : x;
        ok = ok && same_f64(math_sin_f64(-x), -math_sin_f64(x));
        ok = ok && same_f64(math_cos_f64(-x), math_cos_f64(x));
        ok = ok && same_f64(math_tan_f64(-x), -math_tan_f64(x));
        float xf = (float)x;
        ok = ok && same_f32(math_sin_f32(-xf), -math_sin_f32(xf));
        ok = ok && same_f32(math_cos_f32(-xf), math_cos_f32(xf));
        ok = ok && same_f32(math_tan_f32(-xf), -math_tan_f32(xf));
    }
    UT_CHECK(ok);

    UT_TEST("sin^2 + cos^2 = 1 within 3 ulp and tan = sin/cos within 3 ulp, |x| up to 1e5");
    uint64_t worst_pyth = 0u;
    uint64_t worst_tan = 0u;
    uint32_t worst_pyth32 = 0u;
    uint32_t worst_tan32 = 0u;
    for (int i = 0; i < 300; i++) {
        double x = -1e5 + 666.6667 * (double)i + 0.001 * (double)(i % 13);
        double s = math_sin_f64(x);
        double c = math_cos_f64(x);
        uint64_t d = ulps_f64(s * s + c * c, 1.0);
        worst_pyth = (d > worst_pyth) ? d : worst_pyth;
        d = ulps_f64(math_tan_f64(x), s / c);
        worst_tan = (d > worst_tan) ? d : worst_tan;
        float xf = (float)x;
        float sf = math_sin_f32(xf);
        float cf = math_cos_f32(xf);
        uint32_t df = ulps_f32(sf * sf + cf * cf, 1.0f);
        worst_pyth32 = (df > worst_pyth32) ? df : worst_pyth32;
        df = ulps_f32(math_tan_f32(xf), sf / cf);
        worst_tan32 = (df > worst_tan32) ? df : worst_tan32;
    }
    UT_CHECK(worst_pyth <= 3u && worst_tan <= 3u && worst_pyth32 <= 3u && worst_tan32 <= 3u);
    ut_info("worst ulps: f64 pyth %u tan %u, f32 pyth %u tan %u", (unsigned)worst_pyth,
            (unsigned)worst_tan, (unsigned)worst_pyth32, (unsigned)worst_tan32);
}

static void test_wrap(void) {
    UT_TEST("wrap_pi: identity on [-pi, pi], result in [-pi, pi], x - wrap(x) a multiple of 2 pi");
    UT_CHECK(same_f64(math_wrap_pi_f64(3.0), 3.0) &&
             same_f64(math_wrap_pi_f64(-MATH_PI_F64), -MATH_PI_F64));
    UT_CHECK(same_f32(math_wrap_pi_f32(-3.0f), -3.0f) &&
             same_f32(math_wrap_pi_f32(MATH_PI_F32), MATH_PI_F32));
    UT_NEAR(math_wrap_pi_f64(MATH_TWO_PI_F64 + 1.0), 1.0, 1e-15);
    UT_NEAR(math_wrap_pi_f64(-7.0 * MATH_TWO_PI_F64 - 0.5), -0.5, 1e-14);
    UT_NEAR(math_wrap_pi_f32(MATH_TWO_PI_F32 + 1.0f), 1.0f, 1e-6f);
    bool ok = true;
    for (int i = 0; i < 250; i++) {
        double x = -1e6 + 8003.4 * (double)i;
        double w = math_wrap_pi_f64(x);
        double turns = (x - w) / MATH_TWO_PI_F64;
        ok = ok && w >= -MATH_PI_F64 && w <= MATH_PI_F64;
        ok = ok && math_fabs_f64(turns - math_round_f64(turns)) < 1e-9;
        ok = ok && math_fabs_f64(math_sin_f64(w) - math_sin_f64(x)) < 1e-15;
        float xf = (float)(x * 1e-3);
        float wf = math_wrap_pi_f32(xf);
        ok = ok && wf >= -MATH_PI_F32 && wf <= MATH_PI_F32;
        ok = ok && math_fabs_f32(math_sin_f32(wf) - math_sin_f32(xf)) < 4e-7f;
    }
    UT_CHECK(ok);
    UT_CHECK(canonical_nan_f64(math_wrap_pi_f64(math_inf_f64())));
    UT_CHECK(canonical_nan_f32(math_wrap_pi_f32(math_nan_f32())));
}

/* ---- inverse trigonometric functions -------------------------------------- */

static void test_atan(void) {
    UT_TEST("atan f64/f32: within 1 ulp of correctly rounded values, odd symmetry bit for bit");
    UT_CHECK(ulps_f64(math_atan_f64(0.5), 0x1.dac670561bb4fp-2) <= 1u);
    UT_CHECK(ulps_f64(math_atan_f64(1.0), 0x1.921fb54442d18p-1) <= 1u);
    UT_CHECK(ulps_f64(math_atan_f64(2.0), 0x1.1b6e192ebbe44p+0) <= 1u);
    UT_CHECK(ulps_f64(math_atan_f64(10.0), 0x1.789bd2c160054p+0) <= 1u);
    UT_CHECK(ulps_f64(math_atan_f64(0x1.0624dd2f1a9fcp-10), 0x1.0624d77516e16p-10) <= 1u);
    UT_CHECK(ulps_f32(math_atan_f32(0.5f), 0x1.dac67p-2f) <= 1u);
    UT_CHECK(ulps_f32(math_atan_f32(2.0f), 0x1.1b6e1ap+0f) <= 1u);
    UT_CHECK(ulps_f32(math_atan_f32(80.0f), 0x1.8eec8cp+0f) <= 1u);
    bool ok = true;
    for (int i = 0; i < 300; i++) {
        double x = 0.001 * (double)(i * i) - 3.0;
        ok = ok && same_f64(math_atan_f64(-x), -math_atan_f64(x));
        ok = ok && same_f32(math_atan_f32((float)-x), -math_atan_f32((float)x));
    }
    UT_CHECK(ok);
    UT_CHECK(math_atan_f64(math_inf_f64()) == MATH_HALF_PI_F64);
    UT_CHECK(math_atan_f32(-math_inf_f32()) == -MATH_HALF_PI_F32);
    UT_CHECK(same_f64(math_atan_f64(-0.0), -0.0) &&
             canonical_nan_f64(math_atan_f64(math_nan_f64())));

    UT_TEST("atan2: the four quadrants, and atan(y/x) for x > 0 within 2 ulp");
    UT_CHECK(ulps_f64(math_atan2_f64(1.0, 1.0), MATH_QUARTER_PI_F64) <= 1u);
    UT_CHECK(ulps_f64(math_atan2_f64(1.0, -1.0), 0x1.2d97c7f3321d2p+1) <= 1u);
    UT_CHECK(ulps_f64(math_atan2_f64(-1.0, -1.0), -0x1.2d97c7f3321d2p+1) <= 1u);
    UT_CHECK(ulps_f64(math_atan2_f64(-1.0, 1.0), -MATH_QUARTER_PI_F64) <= 1u);
    UT_CHECK(ulps_f64(math_atan2_f64(1.0, -3.0), 0x1.68f095fdf593cp+1) <= 1u);
    UT_CHECK(ulps_f64(math_atan2_f64(-2.0, -1e-5), -0x1.9220092718f51p+0) <= 1u);
    UT_CHECK(ulps_f32(math_atan2_f32(-1.0f, -1.0f), -0x1.2d97c8p+1f) <= 1u);
    UT_CHECK(ulps_f32(math_atan2_f32(1.0f, -1.0f), 0x1.2d97c8p+1f) <= 1u);
    ok = true;
    for (int i = 1; i < 200; i++) {
        double y = 0.37 * (double)i - 20.0;
        double x = 0.11 * (double)i;
        ok = ok && ulps_f64(math_atan2_f64(y, x), math_atan_f64(y / x)) <= 2u;
        ok = ok &&
             ulps_f32(math_atan2_f32((float)y, (float)x), math_atan_f32((float)y / (float)x)) <= 2u;
    }
    UT_CHECK(ok);

    UT_TEST("atan2: zeros and infinities as C99 Annex F");
    UT_CHECK(same_f64(math_atan2_f64(0.0, 0.0), 0.0) && same_f64(math_atan2_f64(-0.0, 0.0), -0.0));
    UT_CHECK(math_atan2_f64(0.0, -0.0) == MATH_PI_F64 &&
             math_atan2_f64(-0.0, -1.0) == -MATH_PI_F64);
    UT_CHECK(math_atan2_f64(5.0, 0.0) == MATH_HALF_PI_F64 &&
             math_atan2_f64(-5.0, -0.0) == -MATH_HALF_PI_F64);
    UT_CHECK(math_atan2_f64(math_inf_f64(), math_inf_f64()) == MATH_QUARTER_PI_F64);
    UT_CHECK(math_atan2_f64(-math_inf_f64(), -math_inf_f64()) == -0x1.2d97c7f3321d2p+1);
    UT_CHECK(same_f64(math_atan2_f64(-3.0, math_inf_f64()), -0.0));
    UT_CHECK(math_atan2_f64(3.0, -math_inf_f64()) == MATH_PI_F64);
    UT_CHECK(math_atan2_f64(1e300, 1e-300) == MATH_HALF_PI_F64);
    UT_CHECK(same_f64(math_atan2_f64(1e-300, 1e300), 0.0) &&
             math_atan2_f64(1e-300, -1e300) == MATH_PI_F64);
    UT_CHECK(canonical_nan_f64(math_atan2_f64(math_nan_f64(), 1.0)));
    UT_CHECK(same_f32(math_atan2_f32(-0.0f, 1.0f), -0.0f) &&
             math_atan2_f32(0.0f, -0.0f) == MATH_PI_F32);
    UT_CHECK(math_atan2_f32(-math_inf_f32(), 2.0f) == -MATH_HALF_PI_F32);
    UT_CHECK(canonical_nan_f32(math_atan2_f32(1.0f, math_nan_f32())));
}

static void test_asin_acos(void) {
    UT_TEST("asin, acos: known values within 1 ulp, asin + acos = pi/2, sin(asin x) = x");
    UT_CHECK(ulps_f64(math_asin_f64(0.5), 0x1.0c152382d7366p-1) <= 1u);
    UT_CHECK(ulps_f64(math_acos_f64(0.5), 0x1.0c152382d7366p+0) <= 1u);
    UT_CHECK(ulps_f64(math_acos_f64(-0.999), 0x1.8c66280ae928ep+1) <= 1u);
    UT_CHECK(ulps_f64(math_asin_f64(0.999), 0x1.86ac9ad18f803p+0) <= 1u);
    UT_CHECK(math_asin_f64(1.0) == MATH_HALF_PI_F64 && math_asin_f64(-1.0) == -MATH_HALF_PI_F64);
    UT_CHECK(math_acos_f64(-1.0) == MATH_PI_F64 && same_f64(math_acos_f64(1.0), 0.0));
    UT_CHECK(math_asin_f32(1.0f) == MATH_HALF_PI_F32 && math_acos_f32(-1.0f) == MATH_PI_F32);
    UT_CHECK(same_f64(math_asin_f64(-0.0), -0.0) && same_f32(math_asin_f32(-0.0f), -0.0f));
    bool ok = true;
    for (int i = 0; i <= 200; i++) {
        double x = -1.0 + 0.01 * (double)i;
        ok = ok && math_fabs_f64(math_asin_f64(x) + math_acos_f64(x) - MATH_HALF_PI_F64) < 1e-15;
        ok = ok && math_fabs_f64(math_sin_f64(math_asin_f64(x)) - x) < 5e-16;
        float xf = (float)x;
        ok = ok && math_fabs_f32(math_asin_f32(xf) + math_acos_f32(xf) - MATH_HALF_PI_F32) < 6e-7f;
        ok = ok && math_fabs_f32(math_cos_f32(math_acos_f32(xf)) - xf) < 3e-7f;
    }
    UT_CHECK(ok);
    UT_CHECK(canonical_nan_f64(math_asin_f64(1.0000000000000002)));
    UT_CHECK(canonical_nan_f64(math_acos_f64(-math_inf_f64())));
    UT_CHECK(canonical_nan_f32(math_acos_f32(1.0000001f)) &&
             canonical_nan_f32(math_asin_f32(math_nan_f32())));
}

/* ---- exponential, logarithm, power ---------------------------------------- */

/* x, exp x, log x (0 when undefined), correctly rounded. */
static const double EXP_LOG_REF_F64[][3] = {
    {0x1p-1, 0x1.a61298e1e069cp+0, -0x1.62e42fefa39efp-1},
    {0x1p+0, 0x1.5bf0a8b145769p+1, 0.0},
    {0x1p+1, 0x1.d8e64b8d4ddaep+2, 0x1.62e42fefa39efp-1},
    {0x1.4p+3, 0x1.5829dcf95056p+14, 0x1.26bb1bbb55516p+1},
    {0x1p-30, 0x1.00000004p+0, -0x1.4cb5ecf0a965p+4},
    {0x1.9p+6, 0x1.3494a9b171bf5p+144, 0x1.26bb1bbb55516p+2},
    {-0x1.4p+4, 0x1.1b48655f37267p-29, 0.0},
    {0x1.5ep+9, 0x1.d945df4f8ec8ep+1009, 0x1.a344e6741ebabp+2},
    {-0x1.5ep+9, 0x1.14f2b0fb9307fp-1010, 0.0},
    {0x1.0624dd2f1a9fcp-10, 0x1.0041919b7ee34p+0, -0x1.ba18a998fffap+2},
};

static const float EXP_LOG_REF_F32[][3] = {
    {0x1p-1f, 0x1.a61298p+0f, -0x1.62e43p-1f},
    {0x1p+1f, 0x1.d8e64cp+2f, 0x1.62e43p-1f},
    {0x1.4p+3f, 0x1.5829dcp+14f, 0x1.26bb1cp+1f},
    {0x1p-20f, 0x1.00001p+0f, -0x1.bb9d3cp+3f},
    {-0x1.4p+4f, 0x1.1b4866p-29f, 0.0f},
    {0x1.4p+6f, 0x1.55779cp+115f, 0x1.18732p+2f},
    {-0x1.4p+6f, 0x1.7fd974p-116f, 0.0f},
    {0x1.0624dep-10f, 0x1.004192p+0f, -0x1.ba18aap+2f},
};

static void test_exp_log_values(void) {
    UT_TEST("exp, log f64: within 1 ulp of correctly rounded values");
    for (unsigned i = 0u; i < sizeof EXP_LOG_REF_F64 / sizeof EXP_LOG_REF_F64[0]; i++) {
        const double *t = EXP_LOG_REF_F64[i];
        bool ok = UT_CHECK(ulps_f64(math_exp_f64(t[0]), t[1]) <= 1u);
        if (t[0] > 0.0) {
            ok = UT_CHECK(ulps_f64(math_log_f64(t[0]), t[2]) <= 1u) && ok;
        }
        if (!ok) {
            ut_info("x = %.17g (row %u)", t[0], i);
        }
    }

    UT_TEST("exp, log f32: within 1 ulp of correctly rounded values");
    for (unsigned i = 0u; i < sizeof EXP_LOG_REF_F32 / sizeof EXP_LOG_REF_F32[0]; i++) {
        const float *t = EXP_LOG_REF_F32[i];
        bool ok = UT_CHECK(ulps_f32(math_exp_f32(t[0]), t[1]) <= 1u);
        if (t[0] > 0.0f) {
            ok = UT_CHECK(ulps_f32(math_log_f32(t[0]), t[2]) <= 1u) && ok;
        }
        if (!ok) {
            ut_info("x = %.9g (row %u)", (double)t[0], i);
        }
    }

    UT_TEST("exp, log: exact cases and subnormal results");
    UT_CHECK(math_exp_f64(0.0) == 1.0 && math_exp_f64(-0.0) == 1.0 && math_exp_f32(0.0f) == 1.0f);
    UT_CHECK(same_f64(math_log_f64(1.0), 0.0) && same_f32(math_log_f32(1.0f), 0.0f));
    UT_CHECK(math_log_f64(0x1p-1074) < -744.4 && math_log_f64(0x1p-1074) > -744.5);
    UT_CHECK(math_exp_f64(-745.0) == 0x1p-1074 && math_exp_f64(-740.0) == 0x55p-1074);
    UT_CHECK(math_exp_f64(709.7) < math_inf_f64() && math_exp_f64(709.8) == math_inf_f64());
    UT_CHECK(math_exp_f32(88.7f) < math_inf_f32() && math_exp_f32(88.8f) == math_inf_f32());
    UT_CHECK(math_exp_f32(-103.9f) > 0.0f && same_f32(math_exp_f32(-104.0f), 0.0f));
}

static void test_exp_log_special(void) {
    UT_TEST("exp, log: infinities, zeros, negative and NaN arguments as C99 Annex F");
    UT_CHECK(same_f64(math_exp_f64(-math_inf_f64()), 0.0) &&
             math_exp_f64(math_inf_f64()) == math_inf_f64());
    UT_CHECK(same_f64(math_exp_f64(-1000.0), 0.0) && math_exp_f64(1000.0) == math_inf_f64());
    UT_CHECK(canonical_nan_f64(math_exp_f64(math_nan_f64())));
    UT_CHECK(math_log_f64(0.0) == -math_inf_f64() && math_log_f64(-0.0) == -math_inf_f64());
    UT_CHECK(canonical_nan_f64(math_log_f64(-1.0)) &&
             canonical_nan_f64(math_log_f64(-math_inf_f64())));
    UT_CHECK(math_log_f64(math_inf_f64()) == math_inf_f64());
    UT_CHECK(same_f32(math_exp_f32(-math_inf_f32()), 0.0f) &&
             math_exp_f32(1000.0f) == math_inf_f32());
    UT_CHECK(math_log_f32(-0.0f) == -math_inf_f32() && canonical_nan_f32(math_log_f32(-1e-30f)));
    UT_CHECK(canonical_nan_f32(math_exp_f32(math_nan_f32())) &&
             math_log_f32(math_inf_f32()) == math_inf_f32());

    UT_TEST("exp(log x) = x within (|log x| + 2) ulp and log(exp x) = x within 2 ulp");
    bool ok = true;
    for (int i = -300; i <= 300; i += 3) {
        double x = 1.2345 * math_pow_f64(10.0, (double)i);
        double err = math_fabs_f64(math_exp_f64(math_log_f64(x)) / x - 1.0);
        ok = ok && err <= (math_fabs_f64(math_log_f64(x)) + 2.0) * 0x1p-52;
        double y = 0.0731 * (double)i;
        ok = ok && ulps_f64(math_log_f64(math_exp_f64(y)), y) <= 2u;
        float xf = 1.2345f * math_exp_f32((float)i * 0.25f);
        float errf = math_fabs_f32(math_exp_f32(math_log_f32(xf)) / xf - 1.0f);
        ok = ok && errf <= (math_fabs_f32(math_log_f32(xf)) + 2.0f) * 0x1p-23f;
    }
    UT_CHECK(ok);
}

static void test_pow(void) {
    UT_TEST("pow: exact integer powers, known values within 1 ulp");
    UT_CHECK(math_pow_f64(2.0, 10.0) == 1024.0 && math_pow_f64(-2.0, 3.0) == -8.0);
    UT_CHECK(math_pow_f64(10.0, 15.0) == 1e15 &&
             ulps_f64(math_pow_f64(3.0, -2.0), 1.0 / 9.0) <= 1u);
    UT_CHECK(math_pow_f64(2.0, 0.5) == math_sqrt_f64(2.0) &&
             math_pow_f64(2.0, -1074.0) == 0x1p-1074);
    UT_CHECK(ulps_f64(math_pow_f64(10.0, -2.0), 0x1.47ae147ae147bp-7) <= 1u);
    UT_CHECK(ulps_f64(math_pow_f64(1.0001, 1e5), 0x1.57fdd2fe62a3dp+14) <= 1u);
    UT_CHECK(ulps_f64(math_pow_f64(2.5, -3.5), 0x1.4b96be9c2da2cp-5) <= 1u);
    UT_CHECK(ulps_f64(math_pow_f64(1e-300, 1.01), 0x1.5f1ca8205119ep-1007) <= 1u);
    UT_CHECK(ulps_f64(math_pow_f64(0.9, 7000.5), 0x3bdp-1074) <= 1u);

    UT_TEST("pow: special cases as C99 Annex F");
    UT_CHECK(math_pow_f64(math_nan_f64(), 0.0) == 1.0 && math_pow_f64(1.0, math_nan_f64()) == 1.0);
    UT_CHECK(math_pow_f64(-1.0, math_inf_f64()) == 1.0 &&
             math_pow_f64(-1.0, -math_inf_f64()) == 1.0);
    UT_CHECK(canonical_nan_f64(math_pow_f64(-8.0, 1.0 / 3.0)));
    UT_CHECK(canonical_nan_f64(math_pow_f64(math_nan_f64(), 1.0)));
    UT_CHECK(math_pow_f64(0.0, -1.0) == math_inf_f64() &&
             math_pow_f64(-0.0, -1.0) == -math_inf_f64());
    UT_CHECK(math_pow_f64(-0.0, -2.0) == math_inf_f64() && same_f64(math_pow_f64(-0.0, 3.0), -0.0));
    UT_CHECK(same_f64(math_pow_f64(-0.0, 2.5), 0.0) && same_f64(math_pow_f64(0.0, 4.0), 0.0));
    UT_CHECK(math_pow_f64(0.5, -math_inf_f64()) == math_inf_f64() &&
             same_f64(math_pow_f64(2.0, -math_inf_f64()), 0.0));
    UT_CHECK(same_f64(math_pow_f64(0.5, math_inf_f64()), 0.0) &&
             math_pow_f64(-2.0, math_inf_f64()) == math_inf_f64());
    UT_CHECK(math_pow_f64(-math_inf_f64(), 3.0) == -math_inf_f64() &&
             same_f64(math_pow_f64(-math_inf_f64(), -3.0), -0.0));
    UT_CHECK(math_pow_f64(-math_inf_f64(), 2.0) == math_inf_f64() &&
             same_f64(math_pow_f64(math_inf_f64(), -0.5), 0.0));
    UT_CHECK(math_pow_f64(10.0, 400.0) == math_inf_f64() &&
             same_f64(math_pow_f64(10.0, -400.0), 0.0));
    UT_CHECK(math_pow_f64(-10.0, 309.0) == -math_inf_f64() &&
             math_pow_f64(1.0000001, 1e300) == math_inf_f64());
}

/* ---- rounding and remainders ---------------------------------------------- */

static void test_rounding(void) {
    UT_TEST("trunc, floor, ceil, round: exact, signs of zero as C99, large values unchanged");
    UT_CHECK(math_floor_f64(-2.5) == -3.0 && math_ceil_f64(-2.5) == -2.0 &&
             math_trunc_f64(-2.5) == -2.0);
    UT_CHECK(math_round_f64(-2.5) == -3.0 && math_round_f64(2.5) == 3.0 &&
             math_round_f64(0.49999999999999994) == 0.0);
    UT_CHECK(same_f64(math_floor_f64(-0.0), -0.0) && math_floor_f64(-0.5) == -1.0);
    UT_CHECK(same_f64(math_ceil_f64(-0.5), -0.0) && same_f64(math_trunc_f64(-0.7), -0.0));
    UT_CHECK(same_f64(math_round_f64(-0.4), -0.0) && math_round_f64(-0.5) == -1.0);
    UT_CHECK(math_floor_f64(4503599627370495.5) == 4503599627370495.0);
    UT_CHECK(math_ceil_f64(0x1p60) == 0x1p60 &&
             math_round_f64(4503599627370495.5) == 4503599627370496.0);
    UT_CHECK(math_floor_f64(-math_inf_f64()) == -math_inf_f64() &&
             math_isnan_f64(math_round_f64(math_nan_f64())));
    UT_CHECK(math_floor_f32(-2.5f) == -3.0f && math_ceil_f32(-2.5f) == -2.0f &&
             math_round_f32(2.5f) == 3.0f);
    UT_CHECK(same_f32(math_ceil_f32(-0.5f), -0.0f) && math_trunc_f32(8388607.5f) == 8388607.0f);
    UT_CHECK(math_round_f32(8388607.5f) == 8388608.0f && math_floor_f32(0x1p30f) == 0x1p30f);

    UT_TEST("fmod: exact, sign of x, special cases as C99 Annex F");
    UT_CHECK(math_fmod_f64(5.5, 2.0) == 1.5 && math_fmod_f64(-5.5, 2.0) == -1.5 &&
             math_fmod_f64(5.5, -2.0) == 1.5);
    UT_CHECK(math_fmod_f64(1e300, 7.0) == 1.0 &&
             math_fmod_f64(-1e300, 0.1) == -0x1.d66e81bc378p-14);
    UT_CHECK(math_fmod_f64(0x1p1000, 0x1.8p-1000) == 0x1p-1000);
    UT_CHECK(math_fmod_f64(7.0 * 0x1p-1074, 2.0 * 0x1p-1074) == 0x1p-1074);
    UT_CHECK(math_fmod_f64(0x1p-1000, 0x1.5p-1070) == 0x4p-1074);
    UT_CHECK(same_f64(math_fmod_f64(-6.0, 3.0), -0.0) && same_f64(math_fmod_f64(-0.0, 3.0), -0.0));
    UT_CHECK(math_fmod_f64(2.0, math_inf_f64()) == 2.0);
    UT_CHECK(canonical_nan_f64(math_fmod_f64(math_inf_f64(), 2.0)) &&
             canonical_nan_f64(math_fmod_f64(1.0, 0.0)));
    UT_CHECK(math_fmod_f32(0x1.93e594p+99f, 7.0f) == 1.0f &&
             math_fmod_f32(-0x1.93e594p+99f, 0.1f) == -0x1.93e594p-5f);
    UT_CHECK(same_f32(math_fmod_f32(-4.0f, 2.0f), -0.0f) &&
             canonical_nan_f32(math_fmod_f32(1.0f, -0.0f)));

    UT_TEST("fabs, copysign, min, max, clamp: exact, NaN rules as documented");
    UT_CHECK(same_f64(math_fabs_f64(-0.0), 0.0) && same_f64(math_copysign_f64(3.0, -0.0), -3.0));
    UT_CHECK(same_f32(math_fabs_f32(-2.0f), 2.0f) &&
             same_f32(math_copysign_f32(-3.0f, 1.0f), 3.0f));
    UT_CHECK(math_min_f64(math_nan_f64(), 2.0) == 2.0 && math_max_f64(1.0, math_nan_f64()) == 1.0);
    UT_CHECK(math_min_f32(-1.0f, 2.0f) == -1.0f && math_max_f32(-1.0f, 2.0f) == 2.0f);
    UT_CHECK(math_clamp_f64(5.0, -1.0, 1.0) == 1.0 && math_clamp_f64(-5.0, -1.0, 1.0) == -1.0);
    UT_CHECK(math_isnan_f64(math_clamp_f64(math_nan_f64(), -1.0, 1.0)) &&
             math_clamp_f32(0.5f, 0.0f, 1.0f) == 0.5f);
}

/* ---- special paths ------------------------------------------------------- */

/*
 * The paths that the value tables above do not reach: NaN and infinite
 * operands, the tiny and huge ranges where a function returns its argument
 * or a constant, subnormal operands, and the exact shortcuts of pow.
 * References: C99 Annex F, and values computed once in 300-bit arithmetic,
 * stored correctly rounded.
 */
static void test_inverse_trig_special_f32(void) {
    UT_TEST("atan, atan2 f32: NaN, tiny x (atan x = x), ratios beyond 2^30, infinities and "
            "zeros as C99 Annex F, subnormal operands (atan2(3 2^-149, 2^-148) = atan 1.5)");
    UT_CHECK(canonical_nan_f32(math_atan_f32(math_nan_f32())));
    UT_CHECK(same_f32(math_atan_f32(1e-5f), 1e-5f) && same_f32(math_atan_f32(-1e-5f), -1e-5f));
    UT_CHECK(canonical_nan_f32(math_atan2_f32(math_nan_f32(), 1.0f)));
    UT_CHECK(math_atan2_f32(math_inf_f32(), math_inf_f32()) == MATH_QUARTER_PI_F32);
    UT_CHECK(math_atan2_f32(-math_inf_f32(), -math_inf_f32()) == -0x1.2d97c8p+1f);
    UT_CHECK(same_f32(math_atan2_f32(3.0f, math_inf_f32()), 0.0f));
    UT_CHECK(math_atan2_f32(-3.0f, -math_inf_f32()) == -MATH_PI_F32);
    UT_CHECK(math_atan2_f32(math_inf_f32(), -2.0f) == MATH_HALF_PI_F32);
    UT_CHECK(math_atan2_f32(5.0f, 0.0f) == MATH_HALF_PI_F32 &&
             math_atan2_f32(-5.0f, -0.0f) == -MATH_HALF_PI_F32);
    /* pi/2 - 1e-10 rounds to pi/2, pi - 1e-10 to pi, atan(1e-10) to 1e-10 (in float). */
    UT_CHECK(math_atan2_f32(1.0f, 1e-10f) == MATH_HALF_PI_F32);
    UT_CHECK(ulps_f32(math_atan2_f32(1e-10f, 1.0f), 0x1.b7cdfep-34f) <= 1u);
    UT_CHECK(math_atan2_f32(1e-10f, -1.0f) == MATH_PI_F32 &&
             math_atan2_f32(-1e-10f, -1.0f) == -MATH_PI_F32);
    UT_CHECK(ulps_f32(math_atan2_f32(0x3p-149f, 0x1p-148f), 0x1.f730bep-1f) <= 1u);
    /* In the second quadrant the angle is pi - atan 1.5. */
    UT_CHECK(ulps_f32(math_atan2_f32(0x3p-149f, -0x1p-148f), 0x1.145386p+1f) <= 1u);

    UT_TEST("asin, acos f32: NaN outside [-1, 1] and for NaN; acos of +-1e-5 (below 2^-12, "
            "where sqrt(1 - x^2) = 1 - x^2/2) within 1 ulp of the reference");
    UT_CHECK(canonical_nan_f32(math_asin_f32(2.0f)) &&
             canonical_nan_f32(math_acos_f32(math_nan_f32())));
    UT_CHECK(ulps_f32(math_acos_f32(1e-5f), 0x1.921f0ep+0f) <= 1u);
    UT_CHECK(ulps_f32(math_acos_f32(-1e-5f), 0x1.92205ep+0f) <= 1u);
}

static void test_special_f64(void) {
    UT_TEST("atan2, asin, acos f64: NaN x, infinite y, subnormal operands; acos(+-1e-10) "
            "within 1 ulp of the reference");
    UT_CHECK(canonical_nan_f64(math_atan2_f64(1.0, math_nan_f64())));
    UT_CHECK(math_atan2_f64(math_inf_f64(), 1.0) == MATH_HALF_PI_F64);
    UT_CHECK(ulps_f64(math_atan2_f64(0x3p-1074, 0x1p-1073), 0x1.f730bd281f69bp-1) <= 1u);
    UT_CHECK(canonical_nan_f64(math_asin_f64(math_nan_f64())) &&
             canonical_nan_f64(math_acos_f64(math_nan_f64())));
    UT_CHECK(ulps_f64(math_acos_f64(1e-10), 0x1.921fb543d4de0p+0) <= 1u);
    UT_CHECK(ulps_f64(math_acos_f64(-1e-10), 0x1.921fb544b0c50p+0) <= 1u);

    UT_TEST("sin, cos of 0x1.ffe3e803c947ap+92, whose fraction of a quarter turn is above 1/2 "
            "with its lowest 32 of 128 bits zero (the carry of 1 - fraction runs through "
            "that word): within 1 ulp of the reference");
    UT_CHECK(ulps_f64(math_sin_f64(0x1.ffe3e803c947ap+92), 0x1.e5fcbf2e3b649p-2) <= 1u);
    UT_CHECK(ulps_f64(math_cos_f64(0x1.ffe3e803c947ap+92), -0x1.c2a9ff537231ap-1) <= 1u);

    UT_TEST("sqrt, log, exp: NaN gives the canonical NaN; log f32 of the subnormal 2^-140 "
            "= -140 ln 2 within 1 ulp; exp(709.78) (2^1024 times a value just below 1) "
            "within 1 ulp");
    UT_CHECK(canonical_nan_f32(math_sqrt_f32(math_nan_f32())));
    UT_CHECK(canonical_nan_f64(math_log_f64(math_nan_f64())) &&
             canonical_nan_f32(math_log_f32(math_nan_f32())));
    UT_CHECK(ulps_f32(math_log_f32(0x1p-140f), -0x1.842994p+6f) <= 1u);
    UT_CHECK(ulps_f64(math_exp_f64(709.78), 0x1.fe9ce5c4c52b4p+1023) <= 1u);

    UT_TEST("pow: the exact shortcuts y = 1, 2, -1 and |x| = 1; |y| > 2^64 underflows to +0 "
            "when x^y -> 0; a NaN y gives NaN");
    UT_CHECK(math_pow_f64(-1.0, 3.0) == -1.0 && math_pow_f64(-1.0, 1e20) == 1.0);
    UT_CHECK(math_pow_f64(3.7, 1.0) == 3.7 && math_pow_f64(-3.7, 1.0) == -3.7);
    UT_CHECK(math_pow_f64(1.5, 2.0) == 2.25 && math_pow_f64(-0.1, 2.0) == 0.1 * 0.1);
    UT_CHECK(math_pow_f64(4.0, -1.0) == 0.25 && math_pow_f64(-8.0, -1.0) == -0.125);
    UT_CHECK(same_f64(math_pow_f64(2.0, -1e20), 0.0) && same_f64(math_pow_f64(0.5, 1e20), 0.0));
    UT_CHECK(canonical_nan_f64(math_pow_f64(2.0, math_nan_f64())));

    UT_TEST("ceil, round f32, fmod: the remaining cases (C99 Annex F; fmod of subnormals "
            "2^-120 mod 21 2^-144 = 2^-144 since 2^24 = 1 mod 21)");
    UT_CHECK(math_ceil_f64(2.5) == 3.0 && math_ceil_f32(2.5f) == 3.0f);
    UT_CHECK(math_round_f32(1e10f) == 1e10f && math_round_f32(-math_inf_f32()) == -math_inf_f32());
    UT_CHECK(same_f32(math_round_f32(0.3f), 0.0f) && same_f32(math_round_f32(-0.3f), -0.0f));
    UT_CHECK(math_round_f32(-0.7f) == -1.0f && math_round_f32(0.5f) == 1.0f);
    UT_CHECK(canonical_nan_f64(math_fmod_f64(1.0, math_nan_f64())));
    UT_CHECK(canonical_nan_f32(math_fmod_f32(math_inf_f32(), 2.0f)) &&
             canonical_nan_f32(math_fmod_f32(1.0f, math_nan_f32())));
    UT_CHECK(math_fmod_f32(1.5f, 4.0f) == 1.5f && math_fmod_f32(-2.0f, math_inf_f32()) == -2.0f);
    UT_CHECK(math_fmod_f32(0x7p-149f, 0x2p-149f) == 0x1p-149f);
    UT_CHECK(math_fmod_f32(0x1p-120f, 0x15p-144f) == 0x1p-144f &&
             math_fmod_f32(-0x1p-120f, 0x15p-144f) == -0x1p-144f);
}

/* ---- determinism ---------------------------------------------------------- */

static uint64_t fnv_mix(uint64_t h, uint64_t v) {
    for (int i = 0; i < 8; i++) {
        h ^= (v >> (8 * i)) & 0xffu;
        h *= 1099511628211u; /* FNV-1a 64-bit prime */
    }
    return h;
}

static uint64_t checksum_f64(void) {
    uint64_t h = 14695981039346656037u; /* FNV offset basis */
    uint64_t state = 2024u;
    for (int i = 0; i < 160; i++) {
        uint64_t v = lcg_next(&state);
        double x = (double)((int64_t)(v >> 32) - 0x80000000) * 0x1p-21; /* |x| < 1024, exact */
        double w = (double)(uint32_t)(v & 0xfffffu) * 0x1p-20;          /* [0, 1) */
        double big = x * 0x1p40;
        double s;
        double c;
        math_sincos_f64(x, &s, &c);
        h = fnv_mix(h, math_bits_f64(s));
        h = fnv_mix(h, math_bits_f64(c));
        h = fnv_mix(h, math_bits_f64(math_tan_f64(big)));
        h = fnv_mix(h, math_bits_f64(math_sin_f64(big)));
        h = fnv_mix(h, math_bits_f64(math_wrap_pi_f64(big)));
        h = fnv_mix(h, math_bits_f64(math_atan2_f64(x, w - 0.5)));
        h = fnv_mix(h, math_bits_f64(math_asin_f64(2.0 * w - 1.0)));
        h = fnv_mix(h, math_bits_f64(math_acos_f64(w)));
        h = fnv_mix(h, math_bits_f64(math_exp_f64(x * 0.7)));
        h = fnv_mix(h, math_bits_f64(math_log_f64(math_fabs_f64(big) + w)));
        h = fnv_mix(h, math_bits_f64(math_pow_f64(w * 10.0, x * 0.1)));
        h = fnv_mix(h, math_bits_f64(math_sqrt_f64(math_fabs_f64(big))));
        h = fnv_mix(h, math_bits_f64(math_fmod_f64(big, w + 0.001)));
    }
    return h;
}

static uint64_t checksum_f32(void) {
    uint64_t h = 14695981039346656037u;
    uint64_t state = 4048u;
    for (int i = 0; i < 160; i++) {
        uint64_t v = lcg_next(&state);
        float x = (float)((int32_t)(v >> 40) - 0x800000) * 0x1p-13f; /* |x| < 1024, exact */
        float w = (float)(uint32_t)(v & 0xfffffu) * 0x1p-20f;
        float big = x * 0x1p20f;
        float s;
        float c;
        math_sincos_f32(x, &s, &c);
        h = fnv_mix(h, math_bits_f32(s));
        h = fnv_mix(h, math_bits_f32(c));
        h = fnv_mix(h, math_bits_f32(math_tan_f32(big)));
        h = fnv_mix(h, math_bits_f32(math_sin_f32(big)));
        h = fnv_mix(h, math_bits_f32(math_wrap_pi_f32(x)));
        h = fnv_mix(h, math_bits_f32(math_atan2_f32(x, w - 0.5f)));
        h = fnv_mix(h, math_bits_f32(math_asin_f32(2.0f * w - 1.0f)));
        h = fnv_mix(h, math_bits_f32(math_acos_f32(w)));
        h = fnv_mix(h, math_bits_f32(math_exp_f32(x * 0.08f)));
        h = fnv_mix(h, math_bits_f32(math_log_f32(math_fabs_f32(big) + w)));
        h = fnv_mix(h, math_bits_f32(math_sqrt_f32(math_fabs_f32(big))));
        h = fnv_mix(h, math_bits_f32(math_fmod_f32(big, w + 0.001f)));
    }
    return h;
}

static void test_determinism(void) {
    UT_TEST("determinism: checksum of 2080 f64 results equals the host's");
    uint64_t h = checksum_f64();
    if (!UT_CHECK(h == MATH_CHECKSUM_F64)) {
        ut_info("checksum 0x%016llx", (unsigned long long)h);
    }

    UT_TEST("determinism: checksum of 1920 f32 results equals the host's");
    h = checksum_f32();
    if (!UT_CHECK(h == MATH_CHECKSUM_F32)) {
        ut_info("checksum 0x%016llx", (unsigned long long)h);
    }
}

void suite_math(void) {
    test_sqrt();
    test_trig_values();
    test_trig_special();
    test_trig_identities();
    test_wrap();
    test_atan();
    test_asin_acos();
    test_exp_log_values();
    test_exp_log_special();
    test_pow();
    test_rounding();
    test_inverse_trig_special_f32();
    test_special_f64();
    test_determinism();
}
