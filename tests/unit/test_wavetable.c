/*
 * Properties of the table waveforms (src/fixedpoint/wavetable.h) that run on
 * every target, without libm.
 *
 * The split with the host. The exhaustive proof of the 1-LSB and 2^-15
 * bounds for all 2^32 phases is tools/check_tables (host, long double
 * libm), about 2^26 sine evaluations: far too many for a Cortex-M3 in
 * software double. Here, on every target and build:
 *   - every table entry is compared with its defining formula (the sine
 *     from a double sine written in this file, accurate to about 1e-16);
 *   - the interpolation arithmetic is checked exactly, in integers, for
 *     every fraction of selected segments and a strided set of fractions in
 *     all segments (entries + exact interpolation bound => lookup bound);
 *   - the lookups are compared with the exactly rounded waveform on a
 *     strided set of phases that exercises every bit of the phase;
 *   - the triangle, whose reference is exact in integers, on every 32nd
 *     bucket of 128 phases, both ends of each (see check_tables.c for why
 *     both ends cover the bucket).
 * Plus the phase increments, the accumulator's long-run period, symmetry
 * and the 120-degree set.
 */
#include "fixedpoint/wavetable.h"
#include "math/umath.h"
#include "ut.h"

void suite_wavetable(void);

#define GOLDEN 2654435761u /* odd multiplier: i * GOLDEN spreads i over all 32 bits */

/* Error-analysis bounds of docs/fixedpoint.md (|lookup - exact waveform|). */
#define SINE_Q15_DEVIATION_BOUND 0.6663
#define F32_BOUND (1.0 / 32768.0)

/* ---- A self-contained double sine (the reference of this file) -------- */

static const double ref_two_pi = MATH_TWO_PI_F64;

/* sin x for 0 <= x <= pi/4: Taylor series to x^19 (next term < 1e-19). */
static double ref_sin_small(double x) {
    static const double inv[10] = {
        0.0,          1.0 / 6.0,    1.0 / 20.0,   1.0 / 42.0,   1.0 / 72.0,
        1.0 / 110.0,  1.0 / 156.0,  1.0 / 210.0,  1.0 / 272.0,  1.0 / 342.0,
    };
    double x2 = x * x;
    double s = 1.0;
    unsigned k;

    for (k = 9u; k > 0u; k--) {
        s = 1.0 - s * x2 * inv[k];
    }
    return x * s;
}

/* cos x for 0 <= x <= pi/4: Taylor series to x^20 (next term < 1e-21). */
static double ref_cos_small(double x) {
    static const double inv[11] = {
        0.0,          1.0 / 2.0,    1.0 / 12.0,   1.0 / 30.0,   1.0 / 56.0,   1.0 / 90.0,
        1.0 / 132.0,  1.0 / 182.0,  1.0 / 240.0,  1.0 / 306.0,  1.0 / 380.0,
    };
    double x2 = x * x;
    double c = 1.0;
    unsigned k;

    for (k = 10u; k > 0u; k--) {
        c = 1.0 - c * x2 * inv[k];
    }
    return c;
}

/*
 * sin(2 pi phase / 2^32): the phase is reduced exactly, in integers, to a
 * quadrant and an angle of at most pi/4 from the nearer axis.
 */
static double ref_sin_turn(uint32_t phase) {
    uint32_t quadrant = phase >> 30;
    uint32_t u = phase & 0x3FFFFFFFu;
    bool use_cos = (quadrant & 1u) != 0u;
    double x;
    double s;

    if (u > 0x20000000u) {
        u = 0x40000000u - u;
        use_cos = !use_cos;
    }
    x = (double)u * (ref_two_pi / 4294967296.0);
    s = use_cos ? ref_cos_small(x) : ref_sin_small(x);
    return (quadrant >= 2u) ? -s : s;
}

/* round(v), ties away from zero, for |v| < 2^30. */
static int32_t ref_round(double v) {
    return (v >= 0.0) ? (int32_t)(v + 0.5) : -(int32_t)(0.5 - v);
}

static double ref_abs(double v) {
    return (v < 0.0) ? -v : v;
}

static int32_t abs_i32(int32_t v) {
    return (v < 0) ? -v : v;
}

/*
 * The exact Q15 triangle at a phase, 32767 * tri, as a numerator over 2^31:
 * -32767 * 2^31 + 65534 * p up to half a turn, mirrored after it.
 */
static int64_t ref_tri_num(uint32_t phase) {
    if (phase <= 0x80000000u) {
        return 65534 * (int64_t)phase - 32767 * (int64_t)0x80000000u;
    }
    return 32767 * (int64_t)0x80000000u - 65534 * (int64_t)(phase - 0x80000000u);
}

/* round(num / 2^31), ties away from zero (divisions of non-negative values). */
static int32_t ref_tri_round(int64_t num) {
    const int64_t half = 0x40000000;
    const int64_t one = 0x80000000;
    return (num >= 0) ? (int32_t)((num + half) / one) : -(int32_t)((half - num) / one);
}

static void test_reference_sine(void) {
    double worst = 0.0;
    uint32_t i;

    UT_TEST("the file's own double sine: sin(pi/4), sin(pi/2), sin(pi/6), cos(pi/6) within 2e-16, "
            "sin^2 + cos^2 = 1 within 4e-16");
    UT_NEAR(ref_sin_turn(0x20000000u), 0.70710678118654752440, 2e-16);
    UT_NEAR(ref_sin_turn(0x40000000u), 1.0, 0.0);
    UT_NEAR(ref_sin_turn(0x80000000u), 0.0, 0.0);
    UT_NEAR(ref_sin_small(ref_two_pi / 12.0), 0.5, 2e-16);
    UT_NEAR(ref_cos_small(ref_two_pi / 12.0), 0.86602540378443864676, 2e-16);
    for (i = 0u; i < 256u; i++) {
        uint32_t p = i * GOLDEN;
        double s = ref_sin_turn(p);
        double c = ref_sin_turn(p + 0x40000000u);
        double e = ref_abs(s * s + c * c - 1.0);
        worst = (e > worst) ? e : worst;
    }
    UT_NEAR(worst, 0.0, 4e-16);
}

/* ---- Tables --------------------------------------------------------------- */

/* The sine's knots of the whole turn, unfolded from the quarter tables. */
static int32_t sine_knots_q23[WT_TABLE_SIZE + 1u];
static float sine_knots_f32[WT_TABLE_SIZE + 1u];

static void build_sine_knots(void) {
    for (uint32_t k = 0u; k <= WT_TABLE_SIZE; k++) {
        sine_knots_q23[k] = wt_sine_knot_q23(k);
        sine_knots_f32[k] = wt_sine_knot_f32(k);
    }
}

/* The lookup in a table of knots: the reference the computed lookups must equal. */
static q15_t table_lookup_q15(const int32_t *table, uint32_t phase) {
    uint32_t k = phase >> (32u - WT_INDEX_BITS);
    return wt_segment_q15(table[k], table[k + 1u], phase);
}

static float table_lookup_f32(const float *table, uint32_t phase) {
    uint32_t k = phase >> (32u - WT_INDEX_BITS);
    return wt_segment_f32(table[k], table[k + 1u], phase);
}

static void test_tables(void) {
    uint32_t k;
    unsigned bad_sine = 0u;
    unsigned bad_sine_f = 0u;

    UT_TEST("tables: sine Q23 knot k = round(256*32767*sin(2 pi k/1024)) and f32 knot = "
            "(float)sin, for all 1025 knots unfolded from the quarter tables (reference: own "
            "double sine)");
    build_sine_knots();
    for (k = 0u; k <= WT_TABLE_SIZE; k++) {
        double s = ref_sin_turn(k << (32u - WT_INDEX_BITS));
        bad_sine += (sine_knots_q23[k] != ref_round(256.0 * 32767.0 * s)) ? 1u : 0u;
        bad_sine_f += (sine_knots_f32[k] != (float)s) ? 1u : 0u;
    }
    UT_EQ_INT(bad_sine, 0);
    UT_EQ_INT(bad_sine_f, 0);

    UT_TEST("tables: the sine's last knot equals knot 0, and the quarter turn's knots are "
            "0 and the peak 256*32767");
    UT_EQ_INT(wt_sine_knot_q23(WT_TABLE_SIZE), wt_sine_knot_q23(0u));
    UT_CHECK(wt_sine_knot_f32(WT_TABLE_SIZE) == wt_sine_knot_f32(0u));
    UT_EQ_INT(wt_sine_knot_q23(WT_QUARTER_SIZE), 256 * 32767);
    UT_EQ_INT(wt_sine_knot_q23(3u * WT_QUARTER_SIZE), -256 * 32767);
    UT_CHECK(wt_sine_knot_f32(WT_QUARTER_SIZE) == 1.0f);
}

/*
 * The triangle's knots as a table (256 tri(k) and tri(k) / 32767, exact),
 * the reference of the computed lookups.
 */
static int32_t tri_table_q23[WT_TABLE_SIZE + 1u];
static float tri_table_f32[WT_TABLE_SIZE + 1u];

static void build_tri_tables(void) {
    for (uint32_t k = 0u; k <= WT_TABLE_SIZE; k++) {
        int32_t j = (k <= WT_TABLE_SIZE / 2u) ? (int32_t)k : (int32_t)(WT_TABLE_SIZE - k);
        tri_table_q23[k] = -8388352 + 32767 * j;
        tri_table_f32[k] = -1.0f + (float)j / 256.0f;
    }
}

static void test_triangle_knots(void) {
    unsigned bad = 0u;
    unsigned bad_f = 0u;

    build_tri_tables();
    UT_TEST("triangle: the computed lookups equal the interpolation of a table of the exact "
            "knots bit for bit, Q15 and f32: every fraction of 10 segments and every 61st "
            "fraction of all 1024");
    static const uint32_t segments[] = {0u, 1u, 255u, 256u, 511u, 512u, 513u, 767u, 1022u, 1023u};
    for (uint32_t i = 0u; i < sizeof segments / sizeof segments[0]; i++) {
        for (uint32_t f = 0u; f < (1u << WT_FRAC_BITS); f++) {
            uint32_t phase = (segments[i] << (32u - WT_INDEX_BITS)) | (f << WT_IGNORED_BITS) |
                             ((f * 37u) & 127u);
            bad += (wt_tri_q15(phase) != table_lookup_q15(tri_table_q23, phase)) ? 1u : 0u;
            bad_f += (wt_tri_f32(phase) != table_lookup_f32(tri_table_f32, phase)) ? 1u : 0u;
        }
    }
    for (uint32_t k = 0u; k < WT_TABLE_SIZE; k++) {
        for (uint32_t f = (k * 7u) % 61u; f < (1u << WT_FRAC_BITS); f += 61u) {
            uint32_t phase = (k << (32u - WT_INDEX_BITS)) | (f << WT_IGNORED_BITS);
            bad += (wt_tri_q15(phase) != table_lookup_q15(tri_table_q23, phase)) ? 1u : 0u;
            bad_f += (wt_tri_f32(phase) != table_lookup_f32(tri_table_f32, phase)) ? 1u : 0u;
        }
    }
    UT_EQ_INT(bad, 0);
    UT_EQ_INT(bad_f, 0);
}

/*
 * Checks, exactly in integers, that the lookup is within 1/2 + 2^-8 LSB of
 * the linear interpolation of its two entries: with v = e0 + d f / 2^15 in
 * Q23, 2^23 L - 2^15 v must lie in (-2^22 - 2^15, 2^22]. Returns the count
 * of fractions (stepping by f_step from f_first) that do not.
 */
static unsigned interp_violations(const int32_t *table, uint32_t k, uint32_t f_first,
                                  uint32_t f_step) {
    unsigned bad = 0u;
    uint32_t f;

    for (f = f_first; f < (1u << WT_FRAC_BITS); f += f_step) {
        /* The ignored low bits vary too: they must not matter. */
        uint32_t phase = (k << (32u - WT_INDEX_BITS)) | (f << WT_IGNORED_BITS) | ((f * 37u) & 127u);
        int64_t e0 = table[k];
        int64_t num = e0 * 32768 + (table[k + 1u] - e0) * (int64_t)f;
        int64_t diff = (int64_t)table_lookup_q15(table, phase) * 8388608 - num;
        bad += (diff <= -(4194304 + 32768) || diff > 4194304) ? 1u : 0u;
    }
    return bad;
}

static void test_interpolation(void) {
    static const uint32_t segments[] = {0u, 1u, 127u, 128u, 255u, 256u, 511u, 512u, 767u, 1023u};
    unsigned bad = 0u;
    unsigned bad_f = 0u;
    uint32_t i;

    build_sine_knots();
    UT_TEST("sine lookups (Q15 and f32) equal the lookup in the unfolded table of the whole "
            "turn, bit for bit: every 61st fraction of all 1024 segments");
    for (i = 0u; i < WT_TABLE_SIZE; i++) {
        for (uint32_t f = (i * 5u) % 61u; f < (1u << WT_FRAC_BITS); f += 61u) {
            uint32_t phase = (i << (32u - WT_INDEX_BITS)) | (f << WT_IGNORED_BITS) | (f & 127u);
            bad += (wt_sin_q15(phase) != table_lookup_q15(sine_knots_q23, phase)) ? 1u : 0u;
            bad_f += (wt_sin_f32(phase) != table_lookup_f32(sine_knots_f32, phase)) ? 1u : 0u;
        }
    }
    UT_EQ_INT(bad, 0);
    UT_EQ_INT(bad_f, 0);

    UT_TEST("Q15 interpolation is within 1/2 + 2^-8 LSB of the exact interpolation of its "
            "entries: every fraction of 10 segments, exact integer reference");
    for (i = 0u; i < sizeof segments / sizeof segments[0]; i++) {
        bad += interp_violations(sine_knots_q23, segments[i], 0u, 1u);
        bad += interp_violations(tri_table_q23, segments[i], 0u, 1u);
    }
    UT_EQ_INT(bad, 0);

    UT_TEST("Q15 interpolation bound holds in all 1024 segments for every 61st fraction "
            "(varying offset), exact integer reference");
    bad = 0u;
    for (i = 0u; i < WT_TABLE_SIZE; i++) {
        bad += interp_violations(sine_knots_q23, i, i % 61u, 61u);
        bad += interp_violations(tri_table_q23, i, (i * 7u) % 61u, 61u);
    }
    UT_EQ_INT(bad, 0);
}

/* ---- Lookups against the exact waveforms -------------------------------- */

static void check_sine_at(uint32_t phase, unsigned *bad, double *worst_q15, double *worst_f32) {
    double s = ref_sin_turn(phase);
    double y = 32767.0 * s;
    q15_t lookup = wt_sin_q15(phase);
    double dev = ref_abs((double)lookup - y);
    double dev_f = ref_abs((double)wt_sin_f32(phase) - s);

    *bad += (abs_i32(lookup - ref_round(y)) > 1) ? 1u : 0u;
    *worst_q15 = (dev > *worst_q15) ? dev : *worst_q15;
    *worst_f32 = (dev_f > *worst_f32) ? dev_f : *worst_f32;
}

static void test_sine_lookup(void) {
    unsigned bad = 0u;
    double worst = 0.0;
    double worst_f = 0.0;
    uint32_t i;

    UT_TEST("sine Q15 within 1 LSB of round(32767 sin) and f32 within 2^-15 of sin: strided "
            "on target (all 1024 nodes + 32768 spread phases); host check_tables: all 2^32");
    for (i = 0u; i < WT_TABLE_SIZE; i++) {
        check_sine_at(i << (32u - WT_INDEX_BITS), &bad, &worst, &worst_f);
    }
    for (i = 0u; i < 32768u; i++) {
        check_sine_at(i * GOLDEN, &bad, &worst, &worst_f);
    }
    UT_EQ_INT(bad, 0);
    UT_CHECK(worst <= SINE_Q15_DEVIATION_BOUND);
    UT_CHECK(worst_f <= F32_BOUND);
    ut_info("max |lookup - 32767 sin| = %.4f LSB (bound %.4f); f32 max error %.3e (2^-15 = %.3e)",
            worst, SINE_Q15_DEVIATION_BOUND, worst_f, F32_BOUND);
}

static void test_triangle_lookup(void) {
    unsigned bad = 0u;
    unsigned bad_dev = 0u;
    double worst_f = 0.0;
    uint32_t b;
    /* 2^31 * (1/2 + 2^-8 + 127 * 65534 / 2^31): rounding, floor and the ignored bits. */
    const int64_t dev_bound = 1073741824 + 8388608 + 127 * 65534;

    UT_TEST("triangle Q15 within 1 LSB of the exactly rounded triangle and within its "
            "analysis bound: both ends of every 32nd bucket (2^20 buckets, integer reference)");
    for (b = 0u; b < (1u << 25); b += 32u) {
        uint32_t p0 = b << WT_IGNORED_BITS;
        uint32_t p1 = p0 + 127u;
        int32_t lookup = wt_tri_q15(p0);
        int64_t d0 = (int64_t)lookup * 2147483648 - ref_tri_num(p0);
        int64_t d1 = (int64_t)lookup * 2147483648 - ref_tri_num(p1);

        bad += (abs_i32(lookup - ref_tri_round(ref_tri_num(p0))) > 1) ? 1u : 0u;
        bad += (abs_i32(lookup - ref_tri_round(ref_tri_num(p1))) > 1) ? 1u : 0u;
        bad_dev += (d0 > dev_bound || -d0 > dev_bound || d1 > dev_bound || -d1 > dev_bound)
                       ? 1u
                       : 0u;
    }
    UT_EQ_INT(bad, 0);
    UT_EQ_INT(bad_dev, 0);

    UT_TEST("triangle f32 within 2^-15 of the exact triangle on 16384 spread phases");
    for (b = 0u; b < 16384u; b++) {
        uint32_t p = b * GOLDEN;
        double exact = (double)ref_tri_num(p) / (32767.0 * 2147483648.0);
        double dev = ref_abs((double)wt_tri_f32(p) - exact);
        worst_f = (dev > worst_f) ? dev : worst_f;
    }
    UT_CHECK(worst_f <= F32_BOUND);
    ut_info("triangle f32 max error %.3e", worst_f);
}

static void test_landmarks(void) {
    UT_TEST("landmarks: sin 0/90/180/270 deg = 0, 32767, 0, -32767; cos 0 = 32767; carrier "
            "valley -32767 at 0, 0 at 90 deg, peak 32767 at 180 deg (and in f32)");
    UT_EQ_INT(wt_sin_q15(0u), 0);
    UT_EQ_INT(wt_sin_q15(WT_PHASE_QUARTER), 32767);
    UT_EQ_INT(wt_sin_q15(WT_PHASE_HALF), 0);
    UT_EQ_INT(wt_sin_q15(3u * WT_PHASE_QUARTER), -32767);
    UT_EQ_INT(wt_cos_q15(0u), 32767);
    UT_EQ_INT(wt_cos_q15(WT_PHASE_HALF), -32767);
    UT_EQ_INT(wt_tri_q15(0u), -32767);
    UT_EQ_INT(wt_tri_q15(WT_PHASE_QUARTER), 0);
    UT_EQ_INT(wt_tri_q15(WT_PHASE_HALF), 32767);
    UT_EQ_INT(wt_tri_q15(0xFFFFFFFFu), -32767);
    UT_CHECK(wt_sin_f32(WT_PHASE_QUARTER) == 1.0f);
    UT_CHECK(wt_cos_f32(WT_PHASE_HALF) == -1.0f);
    UT_CHECK(wt_tri_f32(0u) == -1.0f);
    UT_CHECK(wt_tri_f32(WT_PHASE_HALF) == 1.0f);
}

static void test_symmetry(void) {
    unsigned bad_even = 0u;
    int32_t worst_odd = 0;
    int32_t worst_half = 0;
    int32_t worst_even = 0;
    uint32_t i;

    UT_TEST("symmetry: triangle even about 0 exactly on bucket starts and within 1 LSB "
            "elsewhere; sine odd and half-wave antisymmetric within 1 LSB");
    for (i = 0u; i < 16384u; i++) {
        uint32_t p = i * GOLDEN;
        uint32_t aligned = p & ~127u;
        int32_t odd = abs_i32(wt_sin_q15(p) + wt_sin_q15(0u - p));
        int32_t half = abs_i32(wt_sin_q15(p) + wt_sin_q15(p + WT_PHASE_HALF));
        int32_t tri_half = abs_i32(wt_tri_q15(p) + wt_tri_q15(p + WT_PHASE_HALF));
        int32_t even = abs_i32(wt_tri_q15(p) - wt_tri_q15(0u - p));

        bad_even += (wt_tri_q15(aligned) != wt_tri_q15(0u - aligned)) ? 1u : 0u;
        worst_odd = (odd > worst_odd) ? odd : worst_odd;
        worst_half = (half > worst_half) ? half : worst_half;
        worst_half = (tri_half > worst_half) ? tri_half : worst_half;
        worst_even = (even > worst_even) ? even : worst_even;
    }
    UT_EQ_INT(bad_even, 0);
    UT_CHECK(worst_odd <= 1);
    UT_CHECK(worst_half <= 1);
    UT_CHECK(worst_even <= 1);
}

static void test_three_phase(void) {
    int32_t worst = 0;
    uint32_t i;

    UT_TEST("120-degree offsets: WT_PHASE_120/240 are round(2^32/3), round(2^33/3), and three "
            "Q15 sines 120 deg apart sum to within 2 LSB of zero on 16384 phases");
    UT_EQ_INT(WT_PHASE_120 * 3u, 0xFFFFFFFFu);
    UT_EQ_INT(WT_PHASE_240, 2u * WT_PHASE_120 + 1u);
    UT_EQ_INT(WT_PHASE_240 * 3u, 1u);
    for (i = 0u; i < 16384u; i++) {
        uint32_t p = i * GOLDEN;
        int32_t sum = wt_sin_q15(p) + wt_sin_q15(p + WT_PHASE_120) + wt_sin_q15(p + WT_PHASE_240);
        worst = (abs_i32(sum) > worst) ? abs_i32(sum) : worst;
    }
    UT_CHECK(worst <= 2);
    ut_info("max |sum of three phases| = %d LSB", (int)worst);
}

/* ---- Phase increments and the accumulator ------------------------------- */

static void test_phase_inc_q16(void) {
    unsigned bad = 0u;
    uint32_t i;

    UT_TEST("wt_phase_inc_q16 = round(2^32 f T) mod 2^32; hand-worked values (5 kHz at 2 us: "
            "42949672.96 -> 42949673)");
    UT_EQ_INT(wt_phase_inc_q16(5000 << 16, 2000u), 42949673);
    UT_EQ_INT(wt_phase_inc_q16(50 << 16, 2000u), 429497);
    UT_EQ_INT(wt_phase_inc_q16(1 << 16, 2000u), 8590);
    UT_EQ_INT(wt_phase_inc_q16(50 << 16, 100000u), 21474836);
    UT_EQ_INT(wt_phase_inc_q16(32768, 2000u), 4295);
    UT_EQ_INT(wt_phase_inc_q16(-(50 << 16), 2000u), 4294537799u);
    UT_EQ_INT(wt_phase_inc_q16(0, 2000u), 0);
    UT_EQ_INT(wt_phase_inc_q16(10000 << 16, 50000u), 2147483648u);
    UT_EQ_INT(wt_phase_inc_q16(20000 << 16, 100000u), 0);
    UT_EQ_INT(wt_phase_inc_q16(INT32_MAX, 1000u), 140737488);
    UT_EQ_INT(wt_phase_inc_q16(INT32_MIN, UINT32_MAX), 2197637871u);
    UT_EQ_INT(wt_phase_inc_q16(INT32_MAX, UINT32_MAX), 2097047950u);

    UT_TEST("wt_phase_inc_q16 meets |inc * 5^9 - 2^7 f_q16 T_ns| < 5^9 / 2 (the definition of "
            "rounding to nearest), 2000 random frequencies and steps below one turn");
    for (i = 0u; i < 2000u; i++) {
        uint64_t r = (uint64_t)(i + 1u) * 0x9E3779B97F4A7C15u;
        int32_t f = (int32_t)(r >> 33);
        /* Steps below one turn: f / 2^16 * step / 10^9 < 1. */
        uint64_t limit = (f > 0) ? (65536u * (uint64_t)1000000000u) / (uint64_t)f : 1u;
        uint32_t step = (uint32_t)((r & 0xFFFFFFFFu) % (limit < 0xFFFFFFFFu ? limit : 0xFFFFFFFFu));
        int64_t err = (int64_t)wt_phase_inc_q16(f, step) * 1953125 -
                      (int64_t)f * (int64_t)step * 128;
        bad += (err > 976562 || err < -976562) ? 1u : 0u;
    }
    UT_EQ_INT(bad, 0);
}

static void test_phase_inc_f32_pu(void) {
    volatile float zero = 0.0f;
    uint32_t base = wt_phase_inc_q16(50 << 16, 2000u);

    UT_TEST("wt_phase_inc_f32 = round(2^32 * (f*T rounded to float)) mod 2^32: 5 kHz at 2 us "
            "within 8 counts (float resolution), small ones exact, reverse = two's complement");
    UT_CHECK(wt_phase_inc_f32(5000.0f, 2e-6f) - 42949665u <= 16u);
    UT_EQ_INT(wt_phase_inc_f32(1.0f, 2e-6f), 8590);
    UT_EQ_INT(wt_phase_inc_f32(-1.0f, 2e-6f), 4294967296u - 8590u);
    UT_EQ_INT(wt_phase_inc_f32(50.0f, 1e-4f), 21474836);
    UT_EQ_INT(wt_phase_inc_f32(0.75f, 1.0f), 3221225472u);
    UT_EQ_INT(wt_phase_inc_f32(-0.75f, 1.0f), 1073741824u);
    UT_EQ_INT(wt_phase_inc_f32(1e6f, 1.0f), 0); /* whole turns drop out */

    UT_TEST("wt_phase_inc_f32 gives 0 for NaN and for magnitudes whose increment is a whole "
            "number of turns (>= 2^55 counts)");
    UT_EQ_INT(wt_phase_inc_f32(zero / zero, 2e-6f), 0);
    UT_EQ_INT(wt_phase_inc_f32(1e30f, 1.0f), 0);
    UT_EQ_INT(wt_phase_inc_f32(-1e30f, 1.0f), 0);

    UT_TEST("wt_phase_inc_pu_q31 = round(f_pu * inc_base / 2^31): 0.5 pu halves, -1 pu "
            "negates modulo 2^32, 0 pu stops; reference: hand values");
    UT_EQ_INT(base, 429497);
    UT_EQ_INT(wt_phase_inc_pu_q31(Q31_CONST(0.5), base), 214749); /* 214748.5 -> up */
    UT_EQ_INT(wt_phase_inc_pu_q31(Q31_MIN, base), 4294967296u - 429497u);
    UT_EQ_INT(wt_phase_inc_pu_q31(0, base), 0);
    UT_EQ_INT(wt_phase_inc_pu_q31(Q31_MAX, 0xFFFFFFFFu), 0xFFFFFFFDu);
}

static void test_accumulator(void) {
    uint32_t phase = 0u;
    uint32_t wraps = 0u;
    uint32_t inc = wt_phase_inc_q16(5000 << 16, 2000u);
    uint32_t i;

    UT_TEST("a 5 kHz carrier at 2 us wraps exactly 5000 times in 500000 steps (1 s) and ends "
            "20000 counts (4.7e-6 turn) past its start: the increment's 0.04-count excess");
    for (i = 0u; i < 500000u; i++) {
        uint32_t next = phase + inc;
        wraps += (next < phase) ? 1u : 0u;
        phase = next;
    }
    UT_EQ_INT(wraps, 5000);
    UT_EQ_INT(phase, 20000);

    UT_TEST("a 50 Hz reference at 2 us: 50 turns in 1 s, ending 135200 counts (0.011 deg) "
            "ahead, within the bound steps * 1/2 count");
    phase = 0u;
    wraps = 0u;
    inc = wt_phase_inc_q16(50 << 16, 2000u);
    for (i = 0u; i < 500000u; i++) {
        uint32_t next = phase + inc;
        wraps += (next < phase) ? 1u : 0u;
        phase = next;
    }
    UT_EQ_INT(wraps, 50);
    UT_EQ_INT(phase, 135200);
    UT_CHECK(phase <= 500000u / 2u);
}

void suite_wavetable(void) {
    test_reference_sine();
    test_tables();
    test_triangle_knots();
    test_interpolation();
    test_sine_lookup();
    test_triangle_lookup();
    test_landmarks();
    test_symmetry();
    test_three_phase();
    test_phase_inc_q16();
    test_phase_inc_f32_pu();
    test_accumulator();
}
