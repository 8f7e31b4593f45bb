/*
 * Properties of the fixed-point core (src/fixedpoint/fixedpoint.h and .c):
 * saturation at both ends and its counting, rounding to nearest with the
 * documented tie rule, shifts of negative values, narrowing and widening,
 * multiply-accumulate, float conversions and per-unit helpers.
 *
 * References are independent of the code under test: exact integer
 * arithmetic in a wider type, where C's truncating division is corrected to
 * a floor, or hand-worked values.
 */
#include "fixedpoint/fixedpoint.h"
#include "ut.h"

void suite_fixedpoint(void);

/* ---- Independent references ------------------------------------------- */

/* floor(x / 2^s) for 0 <= s <= 63, from C's truncating division. */
static int64_t ref_floor_pow2(int64_t x, unsigned s) {
    int64_t d;
    int64_t q;

    if (s == 63u) {
        return (x < 0) ? -1 : 0;
    }
    d = (int64_t)1 << s;
    q = x / d;
    if (x % d != 0 && x < 0) {
        q -= 1;
    }
    return q;
}

/* round(x / 2^s), ties up: the floor plus one when the remainder is >= half. */
static int64_t ref_round_pow2(int64_t x, unsigned s) {
    int64_t q;
    uint64_t rem;

    if (s == 0u) {
        return x;
    }
    q = ref_floor_pow2(x, s);
    rem = (uint64_t)x - ((uint64_t)q << s); /* exact remainder, 0 <= rem < 2^s */
    return (rem >= ((uint64_t)1 << (s - 1u))) ? q + 1 : q;
}

static int64_t ref_clamp(int64_t x, int64_t lo, int64_t hi) {
    return (x < lo) ? lo : (x > hi) ? hi : x;
}

/* A small deterministic generator of test operands (64-bit LCG). */
static uint64_t lcg_state;

static uint64_t lcg_next(void) { return ut_rand_u64(&lcg_state); }

static const int32_t edge_i32[] = {
    INT32_MIN, INT32_MIN + 1, -1073741824, -65537, -65536, -32769, -32768, -16385, -16384, -3,
    -2, -1, 0, 1, 2, 3, 16383, 16384, 32767, 32768, 65535, 1073741824, INT32_MAX - 1, INT32_MAX,
};
#define N_EDGE_I32 (sizeof edge_i32 / sizeof edge_i32[0])

/* Operand i of a sweep: the edge values first, then pseudo-random ones. */
static int32_t operand_i32(unsigned i) {
    if (i < N_EDGE_I32) {
        return edge_i32[i];
    }
    return fp_from_u32_i32((uint32_t)(lcg_next() >> 32));
}

static int64_t operand_i64(unsigned i) {
    if (i < N_EDGE_I32) {
        return (int64_t)edge_i32[i] * (int64_t)4294967296 + (int64_t)(i & 1u) * INT32_MAX;
    }
    if (i == N_EDGE_I32) {
        return INT64_MIN;
    }
    if (i == N_EDGE_I32 + 1u) {
        return INT64_MAX;
    }
    return fp_from_u64_i64(lcg_next());
}

/* ---- Reinterpretation and shifts -------------------------------------- */

static void test_reinterpret(void) {
    UT_TEST("fp_from_u32_i32/u64_i64 read two's complement patterns, reference: hand values");
    UT_EQ_INT(fp_from_u32_i32(0u), 0);
    UT_EQ_INT(fp_from_u32_i32(0x7FFFFFFFu), INT32_MAX);
    UT_EQ_INT(fp_from_u32_i32(0x80000000u), INT32_MIN);
    UT_EQ_INT(fp_from_u32_i32(0xFFFFFFFFu), -1);
    UT_EQ_INT(fp_from_u32_i32(0xFFFF8000u), -32768);
    UT_EQ_INT(fp_from_u64_i64(0u), 0);
    UT_EQ_INT(fp_from_u64_i64(0x7FFFFFFFFFFFFFFFu), INT64_MAX);
    UT_CHECK(fp_from_u64_i64(0x8000000000000000u) == INT64_MIN);
    UT_EQ_INT(fp_from_u64_i64(0xFFFFFFFFFFFFFFFFu), -1);
}

static void test_shifts_i32(void) {
    unsigned i;
    unsigned s;
    unsigned bad_floor = 0u;
    unsigned bad_round = 0u;

    UT_TEST("fp_shr_floor_i32 = floor(x/2^s), fp_shr_round_i32 = round ties up, every s, "
            "negative x; reference: corrected integer division");
    lcg_state = 1u;
    for (i = 0u; i < 400u; i++) {
        int32_t x = operand_i32(i);
        for (s = 0u; s <= 31u; s++) {
            bad_floor += (fp_shr_floor_i32(x, s) != ref_floor_pow2(x, s)) ? 1u : 0u;
            bad_round += (fp_shr_round_i32(x, s) != ref_round_pow2(x, s)) ? 1u : 0u;
        }
    }
    UT_EQ_INT(bad_floor, 0);
    UT_EQ_INT(bad_round, 0);

    UT_TEST("rounding shifts: ties go towards plus infinity (-1.5 -> -1, -0.5 -> 0, 1.5 -> 2)");
    UT_EQ_INT(fp_shr_round_i32(-3, 1u), -1);
    UT_EQ_INT(fp_shr_round_i32(-1, 1u), 0);
    UT_EQ_INT(fp_shr_round_i32(3, 1u), 2);
    UT_EQ_INT(fp_shr_round_i32(-5, 1u), -2);
    UT_EQ_INT(fp_shr_round_i32(-49153, 15u), -2); /* -1.50003 */
    UT_EQ_INT(fp_shr_floor_i32(-1, 31u), -1);
    UT_EQ_INT(fp_shr_floor_i32(INT32_MIN, 31u), -1);
    UT_EQ_INT(fp_shr_round_i32(INT32_MIN, 31u), -1);
    UT_EQ_INT(fp_shr_round_i32(INT32_MAX, 1u), 1073741824);
    UT_EQ_INT(fp_shr_round_i32(-7, 0u), -7);
}

static void test_shifts_i64(void) {
    unsigned i;
    unsigned s;
    unsigned bad_floor = 0u;
    unsigned bad_round = 0u;
    unsigned bad_var = 0u;
    unsigned ties = 0u;

    UT_TEST("fp_shr_floor_i64, fp_shr_round_i64 and fp_shr_round_var_i64 for every s 0..63 and "
            "negative x, the ties and their neighbours, reference: corrected integer division");
    lcg_state = 2u;
    for (i = 0u; i < 300u; i++) {
        int64_t x = operand_i64(i);
        for (s = 0u; s <= 63u; s++) {
            bad_floor += (fp_shr_floor_i64(x, s) != ref_floor_pow2(x, s)) ? 1u : 0u;
            bad_round += (fp_shr_round_i64(x, s) != ref_round_pow2(x, s)) ? 1u : 0u;
            bad_var += (fp_shr_round_var_i64(x, s) != ref_round_pow2(x, s)) ? 1u : 0u;
        }
    }
    /* x = q 2^s + 2^(s-1) + d for d = -1, 0, 1: the ties and the values beside them. */
    for (s = 1u; s <= 62u; s++) {
        for (i = 0u; i < 20u; i++) {
            const int64_t q = fp_shr_floor_i64(operand_i64(i + 40u), s + 1u);
            for (int d = -1; d <= 1; d++) {
                const int64_t x = q * ((int64_t)1 << s) + ((int64_t)1 << (s - 1u)) + d;
                bad_var += (fp_shr_round_var_i64(x, s) != ref_round_pow2(x, s)) ? 1u : 0u;
                bad_round += (fp_shr_round_i64(x, s) != ref_round_pow2(x, s)) ? 1u : 0u;
                ties += (d == 0) ? 1u : 0u;
            }
        }
    }
    UT_EQ_INT(bad_floor, 0);
    UT_EQ_INT(bad_round, 0);
    UT_EQ_INT(bad_var, 0);
    UT_EQ_INT(ties, 62 * 20);
    UT_CHECK(fp_shr_round_var_i64(INT64_MAX, 1u) == (int64_t)1 << 62);
    UT_EQ_INT(fp_shr_round_var_i64(INT64_MIN, 63u), -1);
    UT_EQ_INT(fp_shr_round_var_i64(INT64_MIN, 1u), INT64_MIN / 2);
    UT_EQ_INT(fp_shr_round_var_i64(-3, 1u), -1);
    UT_EQ_INT(fp_shr_round_var_i64(-5, 0u), -5);
    UT_EQ_INT(fp_shr_round_i64(-3, 1u), -1);
    UT_CHECK(fp_shr_round_i64(INT64_MAX, 1u) == (int64_t)1 << 62);
    UT_CHECK(fp_shr_floor_i64(INT64_MIN, 0u) == INT64_MIN);
    UT_EQ_INT(fp_shr_round_i64(INT64_MIN, 63u), -1);
    UT_EQ_INT(fp_shr_round_i64(-5, 0u), -5);
}

/*
 * The division of a 64-bit value by a count (fp_udiv_u64_u16(), the three
 * 32-bit divisions, and fp_div_i64_u32(), C's truncated quotient) against
 * the compiler's 64-bit division (libgcc's on the Cortex-M images):
 * operands across the whole range and its ends, small and random values
 * (a frame's sums are small against 2^63), divisors from 1 to 2^16 - 1 and
 * beyond (where fp_div_i64_u32() takes the compiler's division).
 */
static void test_div_count(void) {
    static const uint32_t ns[] = {1u, 2u, 3u, 7u, 50u, 255u, 256u, 1000u, 40000u, 65534u,
                                  65535u, 65536u, 1000000u, UINT32_MAX};
    unsigned bad_u = 0u;
    unsigned bad_s = 0u;

    UT_TEST("fp_udiv_u64_u16 = floor(x/n) for n < 2^16 and fp_div_i64_u32 = x/n truncated, "
            "every x range end, small and random x, reference: the compiler's 64-bit division");
    lcg_state = 5u;
    for (unsigned i = 0u; i < 600u; i++) {
        int64_t x = operand_i64(i);
        if ((i % 3u) == 1u) {
            x = fp_shr_floor_i64(x, (unsigned)(lcg_next() % 60u)); /* small values too */
        }
        for (unsigned j = 0u; j < 16u; j++) {
            const uint32_t n = (j < 14u) ? ns[j] : (uint32_t)(lcg_next() % 65535u) + 1u;
            const uint64_t ux = (uint64_t)x;
            if (n <= 0xffffu) {
                bad_u += (fp_udiv_u64_u16(ux, n) != ux / n) ? 1u : 0u;
            }
            bad_s += (fp_div_i64_u32(x, n) != x / (int64_t)n) ? 1u : 0u;
        }
    }
    UT_EQ_INT(bad_u, 0);
    UT_EQ_INT(bad_s, 0);
    UT_CHECK(fp_udiv_u64_u16(UINT64_MAX, 1u) == UINT64_MAX);
    UT_CHECK(fp_udiv_u64_u16(UINT64_MAX, 65535u) == UINT64_MAX / 65535u);
    UT_CHECK(fp_div_i64_u32(INT64_MIN, 1u) == INT64_MIN);
    UT_EQ_INT(fp_div_i64_u32(-7, 2u), -3);
    UT_EQ_INT(fp_div_i64_u32(7, 2u), 3);
    UT_EQ_INT(fp_div_i64_u32(-1, 50u), 0);
}

static void test_shl(void) {
    uint32_t sat = 0u;

    UT_TEST("fp_shl_cnt_i32 multiplies by 2^s, defined for negative x, saturating and counting");
    UT_EQ_INT(fp_shl_cnt_i32(-3, 4u, &sat), -48);
    UT_EQ_INT(fp_shl_cnt_i32(5, 0u, &sat), 5);
    UT_EQ_INT(fp_shl_cnt_i32(-1, 31u, &sat), INT32_MIN);
    UT_EQ_INT(fp_shl_cnt_i32(0, 31u, &sat), 0);
    UT_EQ_INT(fp_shl_cnt_i32(-65536, 15u, &sat), INT32_MIN);
    UT_EQ_INT(fp_shl_cnt_i32(65535, 15u, &sat), 2147450880);
    UT_EQ_INT(sat, 0);
    UT_EQ_INT(fp_shl_cnt_i32(65536, 15u, &sat), INT32_MAX);
    UT_EQ_INT(fp_shl_cnt_i32(1, 31u, &sat), INT32_MAX);
    UT_EQ_INT(fp_shl_cnt_i32(-65537, 15u, &sat), INT32_MIN);
    UT_EQ_INT(fp_shl_cnt_i32(-2, 31u, &sat), INT32_MIN);
    UT_EQ_INT(sat, 4);
    UT_EQ_INT(fp_shl_i32(INT32_MIN, 1u), INT32_MIN);
    UT_EQ_INT(fp_shl_i32(-7, 2u), -28);
}

/* ---- Saturation and its counter -------------------------------------- */

static void test_saturation(void) {
    uint32_t sat = 0u;

    UT_TEST("saturation counter counts each clamp and stops at UINT32_MAX instead of wrapping");
    fp_count_sat(&sat);
    UT_EQ_INT(sat, 1);
    sat = UINT32_MAX - 1u;
    fp_count_sat(&sat);
    UT_EQ_INT(sat, UINT32_MAX);
    fp_count_sat(&sat);
    UT_EQ_INT(sat, UINT32_MAX);

    UT_TEST("fp_sat_q15/q31 clamp to the range at both ends and pass values inside unchanged");
    sat = 0u;
    UT_EQ_INT(fp_sat_cnt_q15(32767, &sat), 32767);
    UT_EQ_INT(fp_sat_cnt_q15(-32768, &sat), -32768);
    UT_EQ_INT(sat, 0);
    UT_EQ_INT(fp_sat_cnt_q15(32768, &sat), 32767);
    UT_EQ_INT(fp_sat_cnt_q15(-32769, &sat), -32768);
    UT_EQ_INT(fp_sat_cnt_q15(INT32_MIN, &sat), -32768);
    UT_EQ_INT(sat, 3);
    UT_EQ_INT(fp_sat_q15(100000), 32767);
    UT_EQ_INT(fp_sat_cnt_q31(INT32_MAX, &sat), INT32_MAX);
    UT_EQ_INT(fp_sat_cnt_q31(INT32_MIN, &sat), INT32_MIN);
    UT_EQ_INT(sat, 3);
    UT_EQ_INT(fp_sat_cnt_q31((int64_t)INT32_MAX + 1, &sat), INT32_MAX);
    UT_EQ_INT(fp_sat_cnt_q31((int64_t)INT32_MIN - 1, &sat), INT32_MIN);
    UT_EQ_INT(fp_sat_cnt_q31(INT64_MIN, &sat), INT32_MIN);
    UT_EQ_INT(sat, 6);
    UT_EQ_INT(fp_sat_q31(INT64_MAX), INT32_MAX);
    /* Values whose low 32 bits are in range (the native form's test). */
    UT_EQ_INT(fp_sat_cnt_q31((int64_t)1 << 32, &sat), INT32_MAX);
    UT_EQ_INT(fp_sat_cnt_q31(((int64_t)1 << 32) + 5, &sat), INT32_MAX);
    UT_EQ_INT(fp_sat_cnt_q31(-((int64_t)1 << 32) - 5, &sat), INT32_MIN);
    UT_EQ_INT(fp_sat_cnt_q31(((int64_t)3 << 31) - 1, &sat), INT32_MAX);
    UT_EQ_INT(fp_sat_cnt_q31(-((int64_t)3 << 31), &sat), INT32_MIN);
    UT_EQ_INT(sat, 11);
    unsigned bad = 0u;
    for (int64_t k = -64; k <= 64; k++) {
        const int64_t x = k * ((int64_t)1 << 28) + (k % 7);
        const int64_t want = (x > INT32_MAX) ? INT32_MAX : (x < INT32_MIN) ? INT32_MIN : x;
        bad += (fp_sat_q31(x) != want) ? 1u : 0u;
    }
    UT_EQ_INT(bad, 0);
}

/* ---- Q15 arithmetic ---------------------------------------------------- */

static void test_add_sub_q15(void) {
    uint32_t sat = 0u;
    int32_t a;
    unsigned bad = 0u;

    UT_TEST("Q15 add/sub: exact inside the range, clamped and counted at both ends, "
            "reference: int32 sum clamped");
    for (a = -32768; a <= 32767; a += 127) {
        int32_t b = 32767 - (int32_t)((uint32_t)(a * 3) & 0xFFFFu);
        int64_t sum = ref_clamp((int64_t)a + b, -32768, 32767);
        int64_t diff = ref_clamp((int64_t)a - b, -32768, 32767);
        bad += (fp_add_q15((q15_t)a, (q15_t)b) != sum) ? 1u : 0u;
        bad += (fp_sub_q15((q15_t)a, (q15_t)b) != diff) ? 1u : 0u;
    }
    UT_EQ_INT(bad, 0);
    UT_EQ_INT(fp_add_cnt_q15(16384, 16383, &sat), 32767);
    UT_EQ_INT(fp_sub_cnt_q15(-16384, 16384, &sat), -32768);
    UT_EQ_INT(sat, 0);
    UT_EQ_INT(fp_add_cnt_q15(16384, 16384, &sat), 32767);
    UT_EQ_INT(fp_add_cnt_q15(-32768, -1, &sat), -32768);
    UT_EQ_INT(fp_sub_cnt_q15(32767, -1, &sat), 32767);
    UT_EQ_INT(fp_sub_cnt_q15(-32768, 1, &sat), -32768);
    UT_EQ_INT(sat, 4);
}

static void test_mul_q15(void) {
    uint32_t sat = 0u;
    int32_t a;
    int32_t b;
    unsigned bad = 0u;

    UT_TEST("Q15 mul = round(a*b / 2^15) ties up, clamped; reference: exact integer product "
            "over a 256 x 256 grid of operands including both ends");
    for (a = -32768; a <= 32767; a += 257) {
        for (b = -32768; b <= 32767; b += 257) {
            int64_t ref = ref_clamp(ref_round_pow2((int64_t)a * b, 15u), -32768, 32767);
            bad += (fp_mul_q15((q15_t)a, (q15_t)b) != ref) ? 1u : 0u;
        }
    }
    UT_EQ_INT(bad, 0);

    UT_TEST("Q15 mul ties: 0.5 LSB -> 1, -0.5 LSB -> 0, 1.5 -> 2, -1.5 -> -1 (hand values)");
    UT_EQ_INT(fp_mul_q15(1, 16384), 1);
    UT_EQ_INT(fp_mul_q15(-1, 16384), 0);
    UT_EQ_INT(fp_mul_q15(3, 16384), 2);
    UT_EQ_INT(fp_mul_q15(-3, 16384), -1);
    UT_EQ_INT(fp_mul_q15(16384, 16384), 8192);
    UT_EQ_INT(fp_mul_q15(-32768, 32767), -32767);

    UT_TEST("Q15 mul: only (-1)*(-1) leaves the range; it gives 32767 and counts once");
    UT_EQ_INT(fp_mul_cnt_q15(-32768, -32768, &sat), 32767);
    UT_EQ_INT(sat, 1);
    UT_EQ_INT(fp_mul_cnt_q15(-32768, -32767, &sat), 32767);
    UT_EQ_INT(sat, 1);
}

/*
 * Operand i < 80 of a Q15 sweep that reaches both ends of the range: the 8
 * lowest values, 64 values 1023 apart in between, the 8 highest.
 */
static int32_t operand_q15_ends(unsigned i) {
    if (i < 8u) {
        return -32768 + (int32_t)i;
    }
    if (i >= 72u) {
        return 32767 - (int32_t)(79u - i);
    }
    return -32760 + (int32_t)(i - 8u) * 1023;
}

static void test_mac_neg_abs_q15(void) {
    uint32_t sat = 0u;

    UT_TEST("Q15 mac = acc + round(a*b/2^15), only the sum saturates: -0.5 + (-1)(-1) = 0.5");
    UT_EQ_INT(fp_mac_cnt_q15(-16384, -32768, -32768, &sat), 16384);
    UT_EQ_INT(fp_mac_cnt_q15(100, 1, 16384, &sat), 101);
    UT_EQ_INT(fp_mac_cnt_q15(100, -1, 16384, &sat), 100);
    UT_EQ_INT(sat, 0);
    UT_EQ_INT(fp_mac_cnt_q15(32000, 16384, 16384, &sat), 32767);
    UT_EQ_INT(fp_mac_cnt_q15(-32000, -16384, 16384, &sat), -32768);
    UT_EQ_INT(sat, 2);
    UT_EQ_INT(fp_mac_q15(1000, 16384, -16384), -7192);

    UT_TEST("Q15 mac at the ends of the exact Q30 sum acc*2^15 + a*b (up to 2^31 - 2^15 in "
            "magnitude); reference: exact int64 sum, rounded and clamped");
    {
        static const int32_t acc_end[] = {-32768, -32767, -1, 0, 1, 32766, 32767};
        unsigned bad = 0u;
        unsigned i;
        unsigned ia;
        unsigned ib;

        for (i = 0u; i < sizeof acc_end / sizeof acc_end[0]; i++) {
            for (ia = 0u; ia < 80u; ia++) {
                for (ib = 0u; ib < 80u; ib++) {
                    int32_t a = operand_q15_ends(ia);
                    int32_t b = operand_q15_ends(ib);
                    int64_t ref = ref_clamp(acc_end[i] + ref_round_pow2((int64_t)a * b, 15u),
                                            -32768, 32767);
                    bad += (fp_mac_q15((q15_t)acc_end[i], (q15_t)a, (q15_t)b) != ref) ? 1u : 0u;
                }
            }
        }
        UT_EQ_INT(bad, 0);
    }

    UT_TEST("Q15 neg/abs: exact except -(-1) and |-1|, which give 32767 and count");
    UT_EQ_INT(fp_neg_cnt_q15(32767, &sat), -32767);
    UT_EQ_INT(fp_neg_cnt_q15(-5, &sat), 5);
    UT_EQ_INT(fp_abs_cnt_q15(-32767, &sat), 32767);
    UT_EQ_INT(fp_abs_cnt_q15(7, &sat), 7);
    UT_EQ_INT(fp_abs_cnt_q15(0, &sat), 0);
    UT_EQ_INT(sat, 2);
    UT_EQ_INT(fp_neg_cnt_q15(-32768, &sat), 32767);
    UT_EQ_INT(fp_abs_cnt_q15(-32768, &sat), 32767);
    UT_EQ_INT(sat, 4);
    UT_EQ_INT(fp_neg_q15(-32768), 32767);
    UT_EQ_INT(fp_abs_q15(-32768), 32767);
}

/* ---- Q31 arithmetic ---------------------------------------------------- */

static void test_add_sub_q31(void) {
    uint32_t sat = 0u;
    unsigned i;
    unsigned bad = 0u;

    UT_TEST("Q31 add/sub: exact inside the range, clamped and counted at both ends, "
            "reference: int64 sum clamped");
    lcg_state = 3u;
    for (i = 0u; i < 2000u; i++) {
        int32_t a = operand_i32(i);
        int32_t b = operand_i32(i % N_EDGE_I32);
        bad += (fp_add_q31(a, b) != ref_clamp((int64_t)a + b, INT32_MIN, INT32_MAX)) ? 1u : 0u;
        bad += (fp_sub_q31(a, b) != ref_clamp((int64_t)a - b, INT32_MIN, INT32_MAX)) ? 1u : 0u;
    }
    UT_EQ_INT(bad, 0);
    UT_EQ_INT(fp_add_cnt_q31(INT32_MAX, 1, &sat), INT32_MAX);
    UT_EQ_INT(fp_add_cnt_q31(INT32_MIN, -1, &sat), INT32_MIN);
    UT_EQ_INT(fp_sub_cnt_q31(INT32_MIN, 1, &sat), INT32_MIN);
    UT_EQ_INT(fp_sub_cnt_q31(INT32_MAX, -1, &sat), INT32_MAX);
    UT_EQ_INT(sat, 4);
    UT_EQ_INT(fp_sub_cnt_q31(-1, INT32_MAX, &sat), INT32_MIN);
    UT_EQ_INT(sat, 4);
}

static void test_mul_mac_q31(void) {
    uint32_t sat = 0u;
    unsigned i;
    unsigned bad = 0u;

    UT_TEST("Q31 mul = round(a*b / 2^31) ties up, and mac = acc + that, clamped; reference: "
            "exact int64 product over edges and random operands");
    lcg_state = 4u;
    for (i = 0u; i < 3000u; i++) {
        int32_t a = operand_i32(i);
        int32_t b = operand_i32((i * 7u) % 3000u);
        int32_t acc = operand_i32(i % N_EDGE_I32);
        int64_t p = ref_round_pow2((int64_t)a * b, 31u);
        bad += (fp_mul_q31(a, b) != ref_clamp(p, INT32_MIN, INT32_MAX)) ? 1u : 0u;
        bad += (fp_mac_q31(acc, a, b) != ref_clamp(acc + p, INT32_MIN, INT32_MAX)) ? 1u : 0u;
    }
    UT_EQ_INT(bad, 0);
    UT_EQ_INT(fp_mul_q31(1, 1073741824), 1);   /* 0.5 LSB -> 1 */
    UT_EQ_INT(fp_mul_q31(-1, 1073741824), 0);  /* -0.5 LSB -> 0 */
    UT_EQ_INT(fp_mul_q31(-3, 1073741824), -1); /* -1.5 LSB -> -1 */

    UT_TEST("Q31 mul: only (-1)*(-1) saturates; mac clamps only the final sum");
    UT_EQ_INT(fp_mul_cnt_q31(INT32_MIN, INT32_MIN, &sat), INT32_MAX);
    UT_EQ_INT(sat, 1);
    UT_EQ_INT(fp_mul_cnt_q31(INT32_MIN, INT32_MAX, &sat), -INT32_MAX);
    UT_EQ_INT(fp_mac_cnt_q31(-1073741824, INT32_MIN, INT32_MIN, &sat), 1073741824);
    UT_EQ_INT(sat, 1);
    UT_EQ_INT(fp_mac_cnt_q31(INT32_MAX, 1073741824, 1073741824, &sat), INT32_MAX);
    UT_EQ_INT(fp_mac_cnt_q31(INT32_MIN, -1073741824, 1073741824, &sat), INT32_MIN);
    UT_EQ_INT(sat, 3);

    UT_TEST("Q31 mac at the ends of the exact Q62 sum acc*2^31 + a*b (up to 2^63 - 2^31)");
    UT_EQ_INT(fp_mac_cnt_q31(INT32_MAX, INT32_MIN, INT32_MIN, &sat), INT32_MAX);
    UT_EQ_INT(fp_mac_cnt_q31(INT32_MIN, INT32_MIN, INT32_MAX, &sat), INT32_MIN);
    UT_EQ_INT(sat, 5);
    UT_EQ_INT(fp_mac_cnt_q31(INT32_MIN, INT32_MIN, INT32_MIN, &sat), 0);
    UT_EQ_INT(fp_mac_cnt_q31(INT32_MAX, INT32_MIN, INT32_MAX, &sat), 0);
    UT_EQ_INT(fp_mac_cnt_q31(-1, INT32_MAX, INT32_MAX, &sat), INT32_MAX - 2);
    UT_EQ_INT(sat, 5);
}

static void test_neg_abs_q31(void) {
    uint32_t sat = 0u;

    UT_TEST("Q31 neg/abs: exact except -(-1) and |-1|, which give 2^31-1 and count");
    UT_EQ_INT(fp_neg_cnt_q31(INT32_MAX, &sat), -INT32_MAX);
    UT_EQ_INT(fp_neg_cnt_q31(-9, &sat), 9);
    UT_EQ_INT(fp_abs_cnt_q31(-INT32_MAX, &sat), INT32_MAX);
    UT_EQ_INT(fp_abs_cnt_q31(12, &sat), 12);
    UT_EQ_INT(sat, 0);
    UT_EQ_INT(fp_neg_cnt_q31(INT32_MIN, &sat), INT32_MAX);
    UT_EQ_INT(fp_abs_cnt_q31(INT32_MIN, &sat), INT32_MAX);
    UT_EQ_INT(sat, 2);
    UT_EQ_INT(fp_neg_q31(INT32_MIN), INT32_MAX);
    UT_EQ_INT(fp_abs_q31(INT32_MIN), INT32_MAX);
}

/* ---- Mixed formats, narrowing, widening -------------------------------- */

static void test_mulshift(void) {
    uint32_t sat = 0u;

    UT_TEST("fp_mulshift_i32: Q16.16 x Q16.16 >> 16 = Q16.16 rounded; any shift 0..63, clamped");
    UT_EQ_INT(fp_mulshift_i32(98304, 147456, 16u), 221184);   /* 1.5 * 2.25 = 3.375 */
    UT_EQ_INT(fp_mulshift_i32(-98304, 147456, 16u), -221184);
    UT_EQ_INT(fp_mulshift_i32(-3, 1, 1u), -1);                /* -1.5 -> -1 */
    UT_EQ_INT(fp_mulshift_i32(-7, 3, 0u), -21);
    UT_EQ_INT(fp_mulshift_i32(INT32_MIN, INT32_MIN, 63u), 1); /* 2^62 / 2^63 = 0.5 -> 1 */
    UT_EQ_INT(fp_mulshift_cnt_i32(65536, 65536, 0u, &sat), INT32_MAX);
    UT_EQ_INT(fp_mulshift_cnt_i32(-65536, 65536, 0u, &sat), INT32_MIN);
    UT_EQ_INT(sat, 2);
    UT_EQ_INT(fp_mulshift_cnt_i32(-65536, 65536, 1u, &sat), INT32_MIN);
    UT_EQ_INT(fp_mulshift_cnt_i32(-65536, 32768, 0u, &sat), INT32_MIN);
    UT_EQ_INT(sat, 2);
}

static void test_narrow_widen(void) {
    uint32_t sat = 0u;
    unsigned i;
    unsigned bad = 0u;

    UT_TEST("Q31 -> Q15 narrowing = round(x / 2^16) ties up; only x >= 2^31 - 2^15 saturates");
    lcg_state = 5u;
    for (i = 0u; i < 2000u; i++) {
        int32_t x = operand_i32(i);
        bad += (fp_narrow_q15(x) != ref_clamp(ref_round_pow2(x, 16u), -32768, 32767)) ? 1u : 0u;
    }
    UT_EQ_INT(bad, 0);
    UT_EQ_INT(fp_narrow_cnt_q15(0x7FFF7FFF, &sat), 32767);
    UT_EQ_INT(fp_narrow_cnt_q15(INT32_MIN, &sat), -32768);
    UT_EQ_INT(fp_narrow_cnt_q15(-98304, &sat), -1); /* -1.5 -> -1 */
    UT_EQ_INT(fp_narrow_cnt_q15(-32768, &sat), 0);  /* -0.5 -> 0 */
    UT_EQ_INT(sat, 0);
    UT_EQ_INT(fp_narrow_cnt_q15(0x7FFF8000, &sat), 32767);
    UT_EQ_INT(sat, 1);

    UT_TEST("int64 -> Q31 narrowing = round(x / 2^shift) ties up, saturating at both ends");
    sat = 0u;
    UT_EQ_INT(fp_narrow_cnt_q31((int64_t)3 << 30, 31u, &sat), 2);      /* 1.5 -> 2 */
    UT_EQ_INT(fp_narrow_cnt_q31(-((int64_t)3 << 30), 31u, &sat), -1);  /* -1.5 -> -1 */
    UT_EQ_INT(fp_narrow_cnt_q31(INT32_MIN, 0u, &sat), INT32_MIN);
    UT_EQ_INT(sat, 0);
    UT_EQ_INT(fp_narrow_cnt_q31((int64_t)1 << 62, 31u, &sat), INT32_MAX);
    UT_EQ_INT(fp_narrow_cnt_q31(INT64_MIN, 31u, &sat), INT32_MIN);
    UT_EQ_INT(fp_narrow_cnt_q31((int64_t)INT32_MAX + 1, 0u, &sat), INT32_MAX);
    UT_EQ_INT(sat, 3);
    UT_EQ_INT(fp_narrow_q31(INT64_MAX, 63u), 1);

    UT_TEST("Q15 -> Q31 widening is exact (x * 2^16) at both ends and for negative values");
    UT_EQ_INT(fp_widen_q31(-32768), INT32_MIN);
    UT_EQ_INT(fp_widen_q31(32767), 2147418112);
    UT_EQ_INT(fp_widen_q31(-1), -65536);
    UT_EQ_INT(fp_narrow_q15(fp_widen_q31(-12345)), -12345);
}

/* ---- Constants and conversions ------------------------------------------ */

static const q15_t const_q15[] = {
    Q15_CONST(0.5), Q15_CONST(-0.5), Q15_CONST(1.0), Q15_CONST(-1.0), Q15_CONST(-2.0),
    Q15_CONST(0.5 / 32768.0), Q15_CONST(-0.5 / 32768.0), Q15_CONST(1.5 / 32768.0),
    Q15_CONST(0.49 / 32768.0), Q15_CONST(32767.49 / 32768.0), Q15_PU(200.0, 400.0),
    Q15_CONST(0.25f),
};
static const q31_t const_q31[] = {
    Q31_CONST(0.5), Q31_CONST(-0.25), Q31_CONST(1.0), Q31_CONST(-1.0), Q31_CONST(3.0),
    Q31_CONST(-0.5 / 2147483648.0), Q31_PU(-100.0, 400.0),
};

static void test_constants(void) {
    UT_TEST("Q15_CONST/Q31_CONST/_PU in static initialisers round to nearest (ties away from "
            "zero) and saturate; reference: hand values");
    UT_EQ_INT(const_q15[0], 16384);
    UT_EQ_INT(const_q15[1], -16384);
    UT_EQ_INT(const_q15[2], 32767);
    UT_EQ_INT(const_q15[3], -32768);
    UT_EQ_INT(const_q15[4], -32768);
    UT_EQ_INT(const_q15[5], 1);
    UT_EQ_INT(const_q15[6], -1);
    UT_EQ_INT(const_q15[7], 2);
    UT_EQ_INT(const_q15[8], 0);
    UT_EQ_INT(const_q15[9], 32767);
    UT_EQ_INT(const_q15[10], 16384);
    UT_EQ_INT(const_q15[11], 8192);
    UT_EQ_INT(const_q31[0], 1073741824);
    UT_EQ_INT(const_q31[1], -536870912);
    UT_EQ_INT(const_q31[2], INT32_MAX);
    UT_EQ_INT(const_q31[3], INT32_MIN);
    UT_EQ_INT(const_q31[4], INT32_MAX);
    UT_EQ_INT(const_q31[5], -1);
    UT_EQ_INT(const_q31[6], -536870912);
}

static void test_from_f64(void) {
    volatile double zero = 0.0;
    double nan = zero / zero;
    double inf = 1.0 / zero;
    uint32_t sat = 0u;

    UT_TEST("double -> Q15: round(x*2^15) ties away from zero, exact at the range ends, "
            "saturating and counting beyond them and for NaN (-> 0)");
    UT_EQ_INT(fp_from_f64_cnt_q15(0.5 / 32768.0, &sat), 1);
    UT_EQ_INT(fp_from_f64_cnt_q15(-0.5 / 32768.0, &sat), -1);
    UT_EQ_INT(fp_from_f64_cnt_q15(2.5 / 32768.0, &sat), 3);
    UT_EQ_INT(fp_from_f64_cnt_q15(-2.4999 / 32768.0, &sat), -2);
    UT_EQ_INT(fp_from_f64_cnt_q15(0.49999 / 32768.0, &sat), 0);
    UT_EQ_INT(fp_from_f64_cnt_q15(32767.49 / 32768.0, &sat), 32767);
    UT_EQ_INT(fp_from_f64_cnt_q15(-32768.49 / 32768.0, &sat), -32768);
    UT_EQ_INT(sat, 0);
    UT_EQ_INT(fp_from_f64_cnt_q15(32767.5 / 32768.0, &sat), 32767);
    UT_EQ_INT(fp_from_f64_cnt_q15(-32768.5 / 32768.0, &sat), -32768);
    UT_EQ_INT(fp_from_f64_cnt_q15(inf, &sat), 32767);
    UT_EQ_INT(fp_from_f64_cnt_q15(-inf, &sat), -32768);
    UT_EQ_INT(fp_from_f64_cnt_q15(nan, &sat), 0);
    UT_EQ_INT(sat, 5);
    UT_EQ_INT(fp_from_f64_q15(-0.75), -24576);
    sat = UINT32_MAX;
    UT_EQ_INT(fp_from_f64_cnt_q15(2.0, &sat), 32767);
    UT_EQ_INT(sat, UINT32_MAX); /* the counter stops, it does not wrap */

    UT_TEST("double -> Q31: round(x*2^31) ties away from zero, saturating, NaN -> 0");
    sat = 0u;
    UT_EQ_INT(fp_from_f64_cnt_q31(0.5 / 2147483648.0, &sat), 1);
    UT_EQ_INT(fp_from_f64_cnt_q31(-1.5 / 2147483648.0, &sat), -2);
    UT_EQ_INT(fp_from_f64_cnt_q31(0.4 / 2147483648.0, &sat), 0);
    UT_EQ_INT(fp_from_f64_cnt_q31(2147483647.49 / 2147483648.0, &sat), INT32_MAX);
    UT_EQ_INT(fp_from_f64_cnt_q31(-1.0, &sat), INT32_MIN);
    UT_EQ_INT(sat, 0);
    UT_EQ_INT(fp_from_f64_cnt_q31(2147483647.5 / 2147483648.0, &sat), INT32_MAX);
    UT_EQ_INT(fp_from_f64_cnt_q31(-2147483648.5 / 2147483648.0, &sat), INT32_MIN);
    UT_EQ_INT(fp_from_f64_cnt_q31(nan, &sat), 0);
    UT_EQ_INT(sat, 3);
    UT_EQ_INT(fp_from_f64_q31(0.25), 536870912);
}

static void test_from_f32(void) {
    volatile float zero = 0.0f;
    float nan = zero / zero;
    uint32_t sat = 0u;

    UT_TEST("float -> Q15: round(x*2^15) ties away from zero in single precision, "
            "saturating, NaN -> 0");
    UT_EQ_INT(fp_from_f32_cnt_q15(1.5f / 32768.0f, &sat), 2);
    UT_EQ_INT(fp_from_f32_cnt_q15(-1.5f / 32768.0f, &sat), -2);
    UT_EQ_INT(fp_from_f32_cnt_q15(0.25f / 32768.0f, &sat), 0);
    UT_EQ_INT(fp_from_f32_cnt_q15(32767.25f / 32768.0f, &sat), 32767);
    UT_EQ_INT(sat, 0);
    UT_EQ_INT(fp_from_f32_cnt_q15(32767.5f / 32768.0f, &sat), 32767);
    UT_EQ_INT(fp_from_f32_cnt_q15(-32768.5f / 32768.0f, &sat), -32768);
    UT_EQ_INT(fp_from_f32_cnt_q15(nan, &sat), 0);
    UT_EQ_INT(sat, 3);
    UT_EQ_INT(fp_from_f32_q15(0.5f), 16384);

    UT_TEST("float -> Q31: round(x*2^31) ties away from zero, -1 exact, +1 and beyond "
            "saturate, NaN -> 0");
    sat = 0u;
    UT_EQ_INT(fp_from_f32_cnt_q31(2.5f / 2147483648.0f, &sat), 3);
    UT_EQ_INT(fp_from_f32_cnt_q31(-2.5f / 2147483648.0f, &sat), -3);
    UT_EQ_INT(fp_from_f32_cnt_q31(0.375f / 2147483648.0f, &sat), 0);
    UT_EQ_INT(fp_from_f32_cnt_q31(-1.0f, &sat), INT32_MIN);
    UT_EQ_INT(fp_from_f32_cnt_q31(0.99999994f, &sat), 2147483520);
    UT_EQ_INT(sat, 0);
    UT_EQ_INT(fp_from_f32_cnt_q31(1.0f, &sat), INT32_MAX);
    UT_EQ_INT(fp_from_f32_cnt_q31(-1.0000001f, &sat), INT32_MIN);
    UT_EQ_INT(fp_from_f32_cnt_q31(nan, &sat), 0);
    UT_EQ_INT(sat, 3);
    UT_EQ_INT(fp_from_f32_q31(-0.5f), -1073741824);

    UT_TEST("float -> Q31 around 2^23 LSB, where floats stop having fractional parts");
    sat = 0u;
    UT_EQ_INT(fp_from_f32_cnt_q31(8388606.5f / 2147483648.0f, &sat), 8388607);
    UT_EQ_INT(fp_from_f32_cnt_q31(8388607.5f / 2147483648.0f, &sat), 8388608);
    UT_EQ_INT(fp_from_f32_cnt_q31(8388608.0f / 2147483648.0f, &sat), 8388608);
    UT_EQ_INT(fp_from_f32_cnt_q31(8388610.0f / 2147483648.0f, &sat), 8388610);
    UT_EQ_INT(fp_from_f32_cnt_q31(-8388606.5f / 2147483648.0f, &sat), -8388607);
    UT_EQ_INT(fp_from_f32_cnt_q31(-8388607.5f / 2147483648.0f, &sat), -8388608);
    UT_EQ_INT(fp_from_f32_cnt_q31(-8388608.0f / 2147483648.0f, &sat), -8388608);
    UT_EQ_INT(fp_from_f32_cnt_q31(-8388610.0f / 2147483648.0f, &sat), -8388610);
    UT_EQ_INT(sat, 0);
}

static void test_to_float_and_pu(void) {
    UT_TEST("Q15/Q31 -> float/double are raw/2^n (exact except Q31 -> float, rounded)");
    UT_CHECK(fp_to_f32_q15(-32768) == -1.0f);
    UT_CHECK(fp_to_f32_q15(1) == 1.0f / 32768.0f);
    UT_CHECK(fp_to_f64_q15(32767) == 32767.0 / 32768.0);
    UT_CHECK(fp_to_f64_q31(INT32_MIN) == -1.0);
    UT_CHECK(fp_to_f64_q31(INT32_MAX) == 2147483647.0 / 2147483648.0);
    UT_CHECK(fp_to_f32_q31(INT32_MAX) == 1.0f);
    UT_CHECK(fp_to_f32_q31(-1073741824) == -0.5f);

    UT_TEST("per unit: value/base rounds to Q15/Q31 and back to value within half a step");
    UT_EQ_INT(fp_pu_from_f64_q15(200.0, 400.0), 16384);
    UT_EQ_INT(fp_pu_from_f64_q15(-500.0, 400.0), -32768);
    UT_EQ_INT(fp_pu_from_f64_q31(100.0, 400.0), 536870912);
    UT_NEAR(fp_pu_to_f64_q15(16384, 400.0), 200.0, 0.0);
    UT_NEAR(fp_pu_to_f64_q15(fp_pu_from_f64_q15(123.4, 400.0), 400.0), 123.4,
            0.5 * 400.0 / 32768.0);
    UT_NEAR(fp_pu_to_f64_q31(fp_pu_from_f64_q31(-321.0, 400.0), 400.0), -321.0,
            0.5 * 400.0 / 2147483648.0);
}

void suite_fixedpoint(void) {
    test_reinterpret();
    test_shifts_i32();
    test_shifts_i64();
    test_div_count();
    test_shl();
    test_saturation();
    test_add_sub_q15();
    test_mul_q15();
    test_mac_neg_abs_q15();
    test_add_sub_q31();
    test_mul_mac_q31();
    test_neg_abs_q31();
    test_mulshift();
    test_narrow_widen();
    test_constants();
    test_from_f64();
    test_from_f32();
    test_to_float_and_pu();
}
