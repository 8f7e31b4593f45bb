/*
 * Fixed-point core of uuvsim: the Q15 and Q31 types and the operations the
 * fixed-point build of the drive models is written in.
 *
 * Formats. A q15_t holds a value in [-1, 1 - 2^-15] as raw / 2^15; a q31_t
 * holds a value in [-1, 1 - 2^-31] as raw / 2^31. Physical quantities are
 * stored per unit of a documented base (see docs/fixedpoint.md).
 *
 * Rules every function follows:
 *   - No signed overflow: products and sums are formed in a wider type
 *     (int32_t for Q15, int64_t for Q31) before they are narrowed.
 *   - Saturation by comparison: a result beyond the range of its type is
 *     clamped to the nearest end of that range.
 *   - Rounding to nearest, ties towards plus infinity, wherever bits are
 *     dropped (products, narrowings, rounding shifts). The float
 *     conversions round ties away from zero, as C's round() does.
 *   - No right shift of a negative value and no left shift of a negative
 *     value: shifts go through the helpers below, which work on an
 *     offset-binary (unsigned) image of the value, where shifting is defined.
 *   - No implementation-defined conversion: unsigned results are turned back
 *     into signed ones by fp_from_u32_i32() and fp_from_u64_i64().
 *   Where the port declares the compiler's own signed shift and narrowing
 *   (UUV_NATIVE_INT_OPS, uuv_config.h), the shifts and fp_sat_cnt_q31()
 *   use them instead: the same value for every input in fewer
 *   instructions (x86-64: 19 % fewer in the fixed build's averaged
 *   mission; Cortex-M4: 8 % fewer in the motor task, Cortex-M3: 18 %).
 *
 * Saturation counting. Each saturating operation comes in two forms:
 * fp_OP_TYPE(...) clamps silently, and fp_OP_cnt_TYPE(..., sat_count) also
 * adds one to *sat_count when it clamps (the counter itself stops at
 * UINT32_MAX instead of wrapping). The silent form is the counting form with
 * a local counter that the compiler removes, so both share one definition.
 *
 * Everything on the fast path is static inline; the float conversions and
 * per-unit helpers, which are for set-up and tests, live in fixedpoint.c.
 */
#ifndef UUV_FIXEDPOINT_H
#define UUV_FIXEDPOINT_H

#include <limits.h>
#include <stdbool.h>
#include <stdint.h>

#include "uuv_config.h"

typedef int16_t q15_t; /* Q1.15: value = raw / 2^15 */
typedef int32_t q31_t; /* Q1.31: value = raw / 2^31 */

#define Q15_MAX ((q15_t)INT16_MAX)
#define Q15_MIN ((q15_t)INT16_MIN)
#define Q31_MAX ((q31_t)INT32_MAX)
#define Q31_MIN ((q31_t)INT32_MIN)

/*
 * Compile-time constants from a real number x (an arithmetic constant
 * expression, usable in static initialisers). The value is rounded to the
 * nearest step, ties away from zero, and saturated to the range of the type.
 * The sum x * 2^n +- 0.5 is evaluated in double; it is exact unless x lies
 * within 2^-53 (relative) of a tie, which no sensible constant does.
 */
#define Q15_CONST(x) ((q15_t)FP_ROUND_CONST_((double)(x) * 32768.0, 32767.0, -32768.0))
#define Q31_CONST(x) \
    ((q31_t)FP_ROUND_CONST_((double)(x) * 2147483648.0, 2147483647.0, -2147483648.0))

/*
 * Rounds the scaled value s to nearest, ties away from zero, within [lo, hi]
 * (the conversion to the integer type then truncates the +-0.5 away).
 */
#define FP_ROUND_CONST_(s, hi, lo)                                              \
    (((s) >= (hi) + 0.5) ? (hi)                                                 \
     : ((s) <= (lo) - 0.5) ? (lo)                                               \
     : ((s) >= 0.0)        ? (s) + 0.5                                          \
                           : (s) - 0.5)

/* Per-unit constants: the physical value divided by its base, as above. */
#define Q15_PU(value, base) Q15_CONST((double)(value) / (double)(base))
#define Q31_PU(value, base) Q31_CONST((double)(value) / (double)(base))

/* ---- Defined conversions and shifts ------------------------------------ */

/*
 * Reinterprets a 32-bit two's complement pattern as a signed value. Plain
 * conversion of an unsigned value above INT32_MAX is implementation-defined;
 * this one is not. Compilers turn it into a plain register move.
 */
static inline int32_t fp_from_u32_i32(uint32_t r) {
    if (r <= (uint32_t)INT32_MAX) {
        return (int32_t)r;
    }
    return -(int32_t)(~r) - 1;
}

/* The 64-bit twin of fp_from_u32_i32(). */
static inline int64_t fp_from_u64_i64(uint64_t r) {
    if (r <= (uint64_t)INT64_MAX) {
        return (int64_t)r;
    }
    return -(int64_t)(~r) - 1;
}

/*
 * floor(x / 2^s) for 0 <= s <= 31, for every x (the arithmetic right shift,
 * defined for negative x). Works on the offset-binary image x + 2^31, which
 * is non-negative and ordered like x, then removes the shifted offset.
 * Cannot overflow.
 */
static inline int32_t fp_shr_floor_i32(int32_t x, unsigned s) {
#if UUV_NATIVE_INT_OPS
    return x >> s;
#else
    uint32_t biased = (uint32_t)x ^ 0x80000000u;
    return fp_from_u32_i32((biased >> s) - (0x80000000u >> s));
#endif
}

#if UUV_NATIVE_INT_OPS
/*
 * The rounding shift in the compiler's own arithmetic shift, for 1 <= s,
 * one definition for both widths (a 32-bit value stays in 32 bits, which
 * a 32-bit core needs): floor(x / 2^(s-1)) + 1, halved; for s >= 2 the
 * floor is at most a quarter of the type's range, so nothing carries, and
 * s = 1 adds bit 0 instead.
 */
#define FP_SHR_ROUND_NATIVE_(x, s) \
    (((s) == 1u) ? (((x) >> 1) + ((x) & 1)) : ((((x) >> ((s) - 1u)) + 1) >> 1))
#endif

/*
 * round(x / 2^s) for 0 <= s <= 31, ties towards plus infinity, for every x.
 * The half added before flooring is taken from bit s-1 of the offset image,
 * so nothing can carry out of 32 bits. For s >= 1 the result lies in
 * [-2^30, 2^30]; it cannot overflow.
 */
static inline int32_t fp_shr_round_i32(int32_t x, unsigned s) {
#if UUV_NATIVE_INT_OPS
    if (s == 0u) {
        return x;
    }
    return FP_SHR_ROUND_NATIVE_(x, s);
#else
    uint32_t biased = (uint32_t)x ^ 0x80000000u;
    if (s == 0u) {
        return x;
    }
    return fp_from_u32_i32((biased >> s) + ((biased >> (s - 1u)) & 1u) - (0x80000000u >> s));
#endif
}

/* floor(x / 2^s) for 0 <= s <= 63, for every x; as fp_shr_floor_i32(). */
static inline int64_t fp_shr_floor_i64(int64_t x, unsigned s) {
#if UUV_NATIVE_INT_OPS
    return x >> s;
#else
    uint64_t biased = (uint64_t)x ^ 0x8000000000000000u;
    return fp_from_u64_i64((biased >> s) - (0x8000000000000000u >> s));
#endif
}

/* round(x / 2^s) for 0 <= s <= 63, ties towards plus infinity; as above. */
static inline int64_t fp_shr_round_i64(int64_t x, unsigned s) {
#if UUV_NATIVE_INT_OPS
    if (s == 0u) {
        return x;
    }
    return FP_SHR_ROUND_NATIVE_(x, s);
#else
    uint64_t biased = (uint64_t)x ^ 0x8000000000000000u;
    if (s == 0u) {
        return x;
    }
    return fp_from_u64_i64((biased >> s) + ((biased >> (s - 1u)) & 1u) -
                           (0x8000000000000000u >> s));
#endif
}

/*
 * fp_shr_round_i64() for a shift that is not a compile-time constant (a
 * model's row or gain): the same value for every x and s, with one
 * variable 64-bit shift instead of three, which a 32-bit core takes as
 * several instructions each (24 instead of 34 on a Cortex-M4, 23 instead
 * of 32 at -Os on a Cortex-M3; the offset form stays the shorter one by
 * 4-5 instructions when s is a constant). With m all ones for x < 0,
 * x ^ m is non-negative and ((x ^ m) >> k) ^ m = floor(x / 2^k) (for
 * negative x, floor(x / 2^k) = -floor((-x - 1) / 2^k) - 1); with
 * y = floor(x / 2^(s-1)), the result is floor(y / 2) + (y & 1), which
 * cannot overflow (y = x when s = 1). test_fixedpoint pins the two forms
 * to one reference for every s and the edge values.
 */
static inline int64_t fp_shr_round_var_i64(int64_t x, unsigned s) {
    if (s == 0u) {
        return x; /* a return of its own: the form with one exit compiles 1-2 % longer */
    }
#if UUV_NATIVE_INT_OPS
    /* y = floor(x / 2^(s-1)), then floor(y / 2) + (y & 1), as below: for
     * a shift that is not a constant, FP_SHR_ROUND_NATIVE_'s test of s
     * adds 29-115 instructions to the longest motor task of the M4 and M3. */
    const int64_t y = x >> (s - 1u);
    return (y >> 1) + (y & 1);
#else
    const uint64_t m = (uint64_t)0 - ((uint64_t)x >> 63);
    const unsigned k = s - 1u;
    const uint64_t a = ((uint64_t)x ^ m) >> k;
    return fp_from_u64_i64(((a >> 1) ^ m) + ((a ^ m) & (uint64_t)1));
#endif
}

/* ---- Division by a count ----------------------------------------------- */

/*
 * floor(x / n) for a divisor 1 <= n <= 65535, exact for every x, in three
 * 32-bit divisions: the high word, then the low word in two 16-bit digits
 * (each partial dividend, the remainder so far and one digit, is below
 * n 2^16 < 2^32, so each digit of the quotient is below 2^16). About 15
 * instructions on a Cortex-M3/M4/M7, which divide 32-bit values only.
 */
static inline uint64_t fp_udiv_u64_u16(uint64_t x, uint32_t n) {
    const uint32_t hi = (uint32_t)(x >> 32);
    const uint32_t lo = (uint32_t)x;
    const uint32_t q2 = hi / n;
    const uint32_t m = ((hi - (q2 * n)) << 16) | (lo >> 16);
    const uint32_t q1 = m / n;
    const uint32_t l = ((m - (q1 * n)) << 16) | (lo & 0xffffu);
    const uint32_t q0 = l / n;
    return ((uint64_t)q2 << 32) | ((uint64_t)q1 << 16) | (uint64_t)q0;
}

/*
 * x / n as C divides (truncated toward zero) for n >= 1 and every x: the
 * compiler's division where the target has a 64-bit divide (UUV_HW_DIV_64,
 * uuv_config.h) or n >= 2^16, else fp_udiv_u64_u16() of |x| with x's sign.
 */
static inline int64_t fp_div_i64_u32(int64_t x, uint32_t n) {
    int64_t q;
    if ((UUV_HW_DIV_64 != 0) || (n > 0xffffu)) {
        q = x / (int64_t)n;
    } else {
        const bool neg = (x < 0);
        const uint64_t m = neg ? (0u - (uint64_t)x) : (uint64_t)x;
        const uint64_t u = fp_udiv_u64_u16(m, n);
        const uint64_t r = neg ? ((uint64_t)0 - u) : u;
        q = fp_from_u64_i64(r);
    }
    return q;
}

/* ---- Saturation -------------------------------------------------------- */

/* Adds one saturation event to *sat_count; the counter stops at UINT32_MAX. */
static inline void fp_count_sat(uint32_t *sat_count) {
    if (*sat_count < UINT32_MAX) {
        *sat_count += 1u;
    }
}

/* Clamps an int32_t to the Q15 range [-32768, 32767] (same scaling). */
static inline q15_t fp_sat_cnt_q15(int32_t x, uint32_t *sat_count) {
    if (x > (int32_t)INT16_MAX) {
        fp_count_sat(sat_count);
        return Q15_MAX;
    }
    if (x < (int32_t)INT16_MIN) {
        fp_count_sat(sat_count);
        return Q15_MIN;
    }
    return (q15_t)x;
}

/* Clamps an int64_t to the Q31 range [-2^31, 2^31 - 1] (same scaling). */
static inline q31_t fp_sat_cnt_q31(int64_t x, uint32_t *sat_count) {
#if UUV_NATIVE_INT_OPS
    /* x modulo 2^32 is x exactly when x is in range; beyond it, x >> 63
     * (0 or -1) turns INT32_MAX into the nearer end. */
    const q31_t t = (q31_t)x;
    if ((int64_t)t != x) {
        fp_count_sat(sat_count);
        return (q31_t)((x >> 63) ^ INT32_MAX);
    }
    return t;
#else
    if (x > (int64_t)INT32_MAX) {
        fp_count_sat(sat_count);
        return Q31_MAX;
    }
    if (x < (int64_t)INT32_MIN) {
        fp_count_sat(sat_count);
        return Q31_MIN;
    }
    return (q31_t)x;
#endif
}

/* ---- Q15 arithmetic ---------------------------------------------------- */

/* a + b, Q15 in and out; saturates at both ends. */
static inline q15_t fp_add_cnt_q15(q15_t a, q15_t b, uint32_t *sat_count) {
    return fp_sat_cnt_q15((int32_t)a + (int32_t)b, sat_count);
}

/* a - b, Q15 in and out; saturates at both ends. */
static inline q15_t fp_sub_cnt_q15(q15_t a, q15_t b, uint32_t *sat_count) {
    return fp_sat_cnt_q15((int32_t)a - (int32_t)b, sat_count);
}

/*
 * a * b, Q15 x Q15 -> Q15, rounded to nearest (ties up). The Q30 product
 * fits int32_t; the only result out of range is (-1) * (-1) = +1, which
 * saturates to 32767.
 */
static inline q15_t fp_mul_cnt_q15(q15_t a, q15_t b, uint32_t *sat_count) {
    return fp_sat_cnt_q15(fp_shr_round_i32((int32_t)a * (int32_t)b, 15u), sat_count);
}

/*
 * acc + a * b, all Q15: acc + round(a * b / 2^15), the product rounded to
 * Q15 (ties up); only the final sum saturates, so an intermediate +1 from
 * (-1) * (-1) is not clamped when acc brings the sum back into range. It is
 * formed as the rounding of the exact Q30 sum acc * 2^15 + a * b, which
 * gives the same value because acc * 2^15 is a whole number of Q15 steps;
 * that sum lies in [-2^31 + 2^15, 2^31 - 2^15], so it fits int32_t.
 */
static inline q15_t fp_mac_cnt_q15(q15_t acc, q15_t a, q15_t b, uint32_t *sat_count) {
    int32_t sum_q30 = (int32_t)acc * 32768 + (int32_t)a * (int32_t)b;
    return fp_sat_cnt_q15(fp_shr_round_i32(sum_q30, 15u), sat_count);
}

/* -x, Q15; -(-1) saturates to 32767. */
static inline q15_t fp_neg_cnt_q15(q15_t x, uint32_t *sat_count) {
    return fp_sat_cnt_q15(-(int32_t)x, sat_count);
}

/* |x|, Q15; |-1| saturates to 32767. */
static inline q15_t fp_abs_cnt_q15(q15_t x, uint32_t *sat_count) {
    return fp_sat_cnt_q15((x < 0) ? -(int32_t)x : (int32_t)x, sat_count);
}

/* ---- Q31 arithmetic ---------------------------------------------------- */

/* a + b, Q31 in and out; formed in int64_t, saturates at both ends. */
static inline q31_t fp_add_cnt_q31(q31_t a, q31_t b, uint32_t *sat_count) {
    return fp_sat_cnt_q31((int64_t)a + (int64_t)b, sat_count);
}

/* a - b, Q31 in and out; formed in int64_t, saturates at both ends. */
static inline q31_t fp_sub_cnt_q31(q31_t a, q31_t b, uint32_t *sat_count) {
    return fp_sat_cnt_q31((int64_t)a - (int64_t)b, sat_count);
}

/*
 * a * b, Q31 x Q31 -> Q31, rounded to nearest (ties up). The Q62 product
 * fits int64_t; only (-1) * (-1) = +1 is out of range and saturates.
 */
static inline q31_t fp_mul_cnt_q31(q31_t a, q31_t b, uint32_t *sat_count) {
    return fp_sat_cnt_q31(fp_shr_round_i64((int64_t)a * (int64_t)b, 31u), sat_count);
}

/*
 * acc + a * b, all Q31: acc + round(a * b / 2^31), the product rounded to
 * Q31 (ties up); only the sum saturates. As fp_mac_cnt_q15(), it is the
 * rounding of the exact Q62 sum acc * 2^31 + a * b, which lies in
 * [-2^63 + 2^31, 2^63 - 2^31] and so fits int64_t.
 */
static inline q31_t fp_mac_cnt_q31(q31_t acc, q31_t a, q31_t b, uint32_t *sat_count) {
    int64_t sum_q62 = (int64_t)acc * (int64_t)2147483648 + (int64_t)a * (int64_t)b;
    return fp_sat_cnt_q31(fp_shr_round_i64(sum_q62, 31u), sat_count);
}

/* -x, Q31; -(-1) saturates to 2^31 - 1. */
static inline q31_t fp_neg_cnt_q31(q31_t x, uint32_t *sat_count) {
    return fp_sat_cnt_q31(-(int64_t)x, sat_count);
}

/* |x|, Q31; |-1| saturates to 2^31 - 1. */
static inline q31_t fp_abs_cnt_q31(q31_t x, uint32_t *sat_count) {
    return fp_sat_cnt_q31((x < 0) ? -(int64_t)x : (int64_t)x, sat_count);
}

/*
 * round(a * b / 2^shift) saturated to int32_t, for 0 <= shift <= 63: the
 * general product of two Q formats (Qm.n x Qp.q -> Qr.s with
 * shift = n + q - s). The product is exact in int64_t (|a * b| <= 2^62);
 * the rounding is to nearest, ties up.
 */
static inline int32_t fp_mulshift_cnt_i32(int32_t a, int32_t b, unsigned shift,
                                          uint32_t *sat_count) {
    return fp_sat_cnt_q31(fp_shr_round_i64((int64_t)a * (int64_t)b, shift), sat_count);
}

/* ---- Narrowing, widening and shifts ------------------------------------ */

/*
 * Q31 -> Q15: round(x / 2^16), ties up. Only x >= 2^31 - 2^15 rounds to
 * 32768, which saturates to 32767.
 */
static inline q15_t fp_narrow_cnt_q15(q31_t x, uint32_t *sat_count) {
    return fp_sat_cnt_q15(fp_shr_round_i32(x, 16u), sat_count);
}

/*
 * int64_t -> Q31: round(x / 2^shift) for 0 <= shift <= 63, ties up,
 * saturated to the Q31 range. Narrows a wide accumulator (for example a sum
 * of Q62 products with shift = 31).
 */
static inline q31_t fp_narrow_cnt_q31(int64_t x, unsigned shift, uint32_t *sat_count) {
    return fp_sat_cnt_q31(fp_shr_round_i64(x, shift), sat_count);
}

/* Q15 -> Q31: exact (x * 2^16); the product of a negative value is defined. */
static inline q31_t fp_widen_q31(q15_t x) {
    return (q31_t)x * 65536;
}

/*
 * x * 2^s for 0 <= s <= 31, saturated to int32_t: the left shift, defined
 * for negative x and for results out of range. In range, the shift is done
 * on the unsigned image, whose low 32 bits are the exact result.
 */
static inline int32_t fp_shl_cnt_i32(int32_t x, unsigned s, uint32_t *sat_count) {
    int32_t limit = (int32_t)(0x7FFFFFFFu >> s);
    if (x > limit) {
        fp_count_sat(sat_count);
        return INT32_MAX;
    }
    if (x < -limit - 1) {
        fp_count_sat(sat_count);
        return INT32_MIN;
    }
    return fp_from_u32_i32((uint32_t)x << s);
}

/* ---- Silent forms (clamp without counting) ----------------------------- */

static inline q15_t fp_sat_q15(int32_t x) {
    uint32_t unused = 0u;
    return fp_sat_cnt_q15(x, &unused);
}

static inline q31_t fp_sat_q31(int64_t x) {
    uint32_t unused = 0u;
    return fp_sat_cnt_q31(x, &unused);
}

static inline q15_t fp_add_q15(q15_t a, q15_t b) {
    uint32_t unused = 0u;
    return fp_add_cnt_q15(a, b, &unused);
}

static inline q15_t fp_sub_q15(q15_t a, q15_t b) {
    uint32_t unused = 0u;
    return fp_sub_cnt_q15(a, b, &unused);
}

static inline q15_t fp_mul_q15(q15_t a, q15_t b) {
    uint32_t unused = 0u;
    return fp_mul_cnt_q15(a, b, &unused);
}

static inline q15_t fp_mac_q15(q15_t acc, q15_t a, q15_t b) {
    uint32_t unused = 0u;
    return fp_mac_cnt_q15(acc, a, b, &unused);
}

static inline q15_t fp_neg_q15(q15_t x) {
    uint32_t unused = 0u;
    return fp_neg_cnt_q15(x, &unused);
}

static inline q15_t fp_abs_q15(q15_t x) {
    uint32_t unused = 0u;
    return fp_abs_cnt_q15(x, &unused);
}

static inline q31_t fp_add_q31(q31_t a, q31_t b) {
    uint32_t unused = 0u;
    return fp_add_cnt_q31(a, b, &unused);
}

static inline q31_t fp_sub_q31(q31_t a, q31_t b) {
    uint32_t unused = 0u;
    return fp_sub_cnt_q31(a, b, &unused);
}

static inline q31_t fp_mul_q31(q31_t a, q31_t b) {
    uint32_t unused = 0u;
    return fp_mul_cnt_q31(a, b, &unused);
}

static inline q31_t fp_mac_q31(q31_t acc, q31_t a, q31_t b) {
    uint32_t unused = 0u;
    return fp_mac_cnt_q31(acc, a, b, &unused);
}

static inline q31_t fp_neg_q31(q31_t x) {
    uint32_t unused = 0u;
    return fp_neg_cnt_q31(x, &unused);
}

static inline q31_t fp_abs_q31(q31_t x) {
    uint32_t unused = 0u;
    return fp_abs_cnt_q31(x, &unused);
}

static inline int32_t fp_mulshift_i32(int32_t a, int32_t b, unsigned shift) {
    uint32_t unused = 0u;
    return fp_mulshift_cnt_i32(a, b, shift, &unused);
}

static inline q15_t fp_narrow_q15(q31_t x) {
    uint32_t unused = 0u;
    return fp_narrow_cnt_q15(x, &unused);
}

static inline q31_t fp_narrow_q31(int64_t x, unsigned shift) {
    uint32_t unused = 0u;
    return fp_narrow_cnt_q31(x, shift, &unused);
}

static inline int32_t fp_shl_i32(int32_t x, unsigned s) {
    uint32_t unused = 0u;
    return fp_shl_cnt_i32(x, s, &unused);
}

/* ---- Conversions to floating point (exact or correctly rounded) -------- */

/* Q15 -> float: raw / 2^15, exact. */
static inline float fp_to_f32_q15(q15_t x) {
    return (float)x * (1.0f / 32768.0f);
}

/* Q31 -> float: raw / 2^31, rounded to nearest float (24-bit significand). */
static inline float fp_to_f32_q31(q31_t x) {
    return (float)x * (1.0f / 2147483648.0f);
}

/* Q15 -> double: raw / 2^15, exact. */
static inline double fp_to_f64_q15(q15_t x) {
    return (double)x * (1.0 / 32768.0);
}

/* Q31 -> double: raw / 2^31, exact. */
static inline double fp_to_f64_q31(q31_t x) {
    return (double)x * (1.0 / 2147483648.0);
}

/* ---- Conversions from floating point and per-unit helpers (set-up) ----- */

/*
 * x -> Q15 / Q31: round(x * 2^15) or round(x * 2^31), ties away from zero,
 * saturated to the range of the type; a NaN gives 0. The scaling by a power
 * of two and the rounding are exact (no double rounding). The _cnt forms
 * count a clamp or a NaN as one saturation.
 */
q15_t fp_from_f32_cnt_q15(float x, uint32_t *sat_count);
q31_t fp_from_f32_cnt_q31(float x, uint32_t *sat_count);
q15_t fp_from_f64_cnt_q15(double x, uint32_t *sat_count);
q31_t fp_from_f64_cnt_q31(double x, uint32_t *sat_count);
q15_t fp_from_f32_q15(float x);
q31_t fp_from_f32_q31(float x);
q15_t fp_from_f64_q15(double x);
q31_t fp_from_f64_q31(double x);

/*
 * A physical value -> per unit of a base (base > 0, in the value's unit):
 * fp_from_f64_q15(value / base), so it rounds and saturates the same way.
 * The division is in double: these run at set-up, never on the fast path.
 */
q15_t fp_pu_from_f64_q15(double value, double base);
q31_t fp_pu_from_f64_q31(double value, double base);

/* Per unit -> physical value: base * raw / 2^15 (or 2^31), in double. */
double fp_pu_to_f64_q15(q15_t pu, double base);
double fp_pu_to_f64_q31(q31_t pu, double base);

#endif /* UUV_FIXEDPOINT_H */
