/*
 * The freestanding math library of uuvsim: elementary functions in double
 * (_f64) and single (_f32) precision, written with nothing but IEEE 754
 * addition, subtraction, multiplication, division, comparisons and integer
 * operations on the bit patterns.
 *
 * Determinism is the point of this library. Each of those operations is
 * correctly rounded by IEEE 754, whether it runs on an SSE2 host, on the FPU
 * of a Cortex-M4F/M7 or in the software floating point of a Cortex-M3, so the
 * same sequence of operations gives the same bits everywhere. The build must
 * keep that sequence intact: -ffp-contract=off (no fused multiply-add),
 * -fno-builtin, no -ffast-math, no x87 and no flush-to-zero (the reset
 * default of the Cortex-M FPU is round to nearest with subnormals, which is
 * what is assumed). Float functions compute in float only and double
 * functions in double only.
 *
 * NaN results are always the canonical quiet NaN (positive sign, payload
 * zero) whatever the NaN inputs were, because the payload and sign of a NaN
 * made by arithmetic differ between an x86 host and an Arm core. Functions
 * that only move bits (fabs, copysign, trunc, floor, ceil, round, min, max,
 * clamp) return their NaN argument unchanged, which is deterministic too.
 *
 * Accuracy, algorithms and measured errors are in docs/math.md.
 */
#ifndef UUV_UMATH_H
#define UUV_UMATH_H

#include <stdbool.h>
#include <stdint.h>

/*
 * Constants, as hexadecimal literals so that every compiler reads the same
 * bits (a decimal literal may legally round either way). Each is the value
 * in the comment, correctly rounded.
 */
#define MATH_PI_F64 0x1.921fb54442d18p+1         /* 3.14159265358979323846 */
#define MATH_TWO_PI_F64 0x1.921fb54442d18p+2     /* 6.28318530717958647693 */
#define MATH_HALF_PI_F64 0x1.921fb54442d18p+0    /* 1.57079632679489661923 */
#define MATH_QUARTER_PI_F64 0x1.921fb54442d18p-1 /* 0.78539816339744830962 */
#define MATH_INV_PI_F64 0x1.45f306dc9c883p-2     /* 0.31830988618379067154 */
#define MATH_E_F64 0x1.5bf0a8b145769p+1          /* 2.71828182845904523536 */
#define MATH_LN2_F64 0x1.62e42fefa39efp-1        /* 0.69314718055994530942 */
#define MATH_LN10_F64 0x1.26bb1bbb55516p+1       /* 2.30258509299404568402 */
#define MATH_SQRT2_F64 0x1.6a09e667f3bcdp+0      /* 1.41421356237309504880 */
#define MATH_DEG_TO_RAD_F64 0x1.1df46a2529d39p-6 /* pi / 180 = 0.01745329251994329577 */
#define MATH_RAD_TO_DEG_F64 0x1.ca5dc1a63c1f8p+5 /* 180 / pi = 57.2957795130823208768 */
#define MATH_RAD_TO_RPM_F64 0x1.3193d66ed2bfap+3 /* 30 / pi = 9.54929658551372014613 */

#define MATH_PI_F32 0x1.921fb6p+1f
#define MATH_TWO_PI_F32 0x1.921fb6p+2f
#define MATH_HALF_PI_F32 0x1.921fb6p+0f
#define MATH_QUARTER_PI_F32 0x1.921fb6p-1f
#define MATH_INV_PI_F32 0x1.45f306p-2f
#define MATH_E_F32 0x1.5bf0a8p+1f
#define MATH_LN2_F32 0x1.62e430p-1f
#define MATH_LN10_F32 0x1.26bb1cp+1f
#define MATH_SQRT2_F32 0x1.6a09e6p+0f
#define MATH_DEG_TO_RAD_F32 0x1.1df46ap-6f
#define MATH_RAD_TO_DEG_F32 0x1.ca5dc2p+5f
#define MATH_RAD_TO_RPM_F32 0x1.3193d6p+3f

/* Views of a value as its bit pattern (type punning through a union is C99). */
typedef union {
    double f;
    uint64_t u;
} math_pun64_t;

typedef union {
    float f;
    uint32_t u;
} math_pun32_t;

static inline uint64_t math_bits_f64(double x) {
    math_pun64_t p;
    p.f = x;
    return p.u;
}

static inline double math_from_bits_f64(uint64_t u) {
    math_pun64_t p;
    p.u = u;
    return p.f;
}

static inline uint32_t math_bits_f32(float x) {
    math_pun32_t p;
    p.f = x;
    return p.u;
}

static inline float math_from_bits_f32(uint32_t u) {
    math_pun32_t p;
    p.u = u;
    return p.f;
}

/* Special values and classification (by bit pattern, immune to compiler flags). */
static inline double math_nan_f64(void) { return math_from_bits_f64(0x7ff8000000000000u); }
static inline double math_inf_f64(void) { return math_from_bits_f64(0x7ff0000000000000u); }
static inline float math_nan_f32(void) { return math_from_bits_f32(0x7fc00000u); }
static inline float math_inf_f32(void) { return math_from_bits_f32(0x7f800000u); }

static inline bool math_isnan_f64(double x) {
    return (math_bits_f64(x) & 0x7fffffffffffffffu) > 0x7ff0000000000000u;
}
static inline bool math_isinf_f64(double x) {
    return (math_bits_f64(x) & 0x7fffffffffffffffu) == 0x7ff0000000000000u;
}
static inline bool math_isfinite_f64(double x) {
    return (math_bits_f64(x) & 0x7fffffffffffffffu) < 0x7ff0000000000000u;
}
static inline bool math_signbit_f64(double x) { return (math_bits_f64(x) >> 63) != 0u; }

static inline bool math_isnan_f32(float x) {
    return (math_bits_f32(x) & 0x7fffffffu) > 0x7f800000u;
}
static inline bool math_isinf_f32(float x) {
    return (math_bits_f32(x) & 0x7fffffffu) == 0x7f800000u;
}
static inline bool math_isfinite_f32(float x) {
    return (math_bits_f32(x) & 0x7fffffffu) < 0x7f800000u;
}
static inline bool math_signbit_f32(float x) { return (math_bits_f32(x) >> 31) != 0u; }

/* |x|, exact; clears the sign bit of any value, NaN included. */
static inline double math_fabs_f64(double x) {
    return math_from_bits_f64(math_bits_f64(x) & 0x7fffffffffffffffu);
}
static inline float math_fabs_f32(float x) {
    return math_from_bits_f32(math_bits_f32(x) & 0x7fffffffu);
}

/* The magnitude of mag with the sign bit of sgn, exact. */
static inline double math_copysign_f64(double mag, double sgn) {
    return math_from_bits_f64((math_bits_f64(mag) & 0x7fffffffffffffffu) |
                              (math_bits_f64(sgn) & 0x8000000000000000u));
}
static inline float math_copysign_f32(float mag, float sgn) {
    return math_from_bits_f32((math_bits_f32(mag) & 0x7fffffffu) |
                              (math_bits_f32(sgn) & 0x80000000u));
}

/*
 * Minimum and maximum. As C99 fmin/fmax, a NaN argument is ignored (the other
 * one is returned); between -0 and +0 the first argument is returned.
 */
static inline double math_min_f64(double a, double b) {
    return (math_isnan_f64(a) || b < a) ? b : a;
}
static inline double math_max_f64(double a, double b) {
    return (math_isnan_f64(a) || b > a) ? b : a;
}
static inline float math_min_f32(float a, float b) { return (math_isnan_f32(a) || b < a) ? b : a; }
static inline float math_max_f32(float a, float b) { return (math_isnan_f32(a) || b > a) ? b : a; }

/*
 * x limited to [lo, hi] (the caller guarantees lo <= hi). A NaN x is returned
 * unchanged: saturating it to a bound would hide the fault that made it.
 */
static inline double math_clamp_f64(double x, double lo, double hi) {
    return (x < lo) ? lo : ((x > hi) ? hi : x);
}
static inline float math_clamp_f32(float x, float lo, float hi) {
    return (x < lo) ? lo : ((x > hi) ? hi : x);
}

/* Rounding to an integral value, exact (src/math/round.c). round: half away from zero. */
double math_trunc_f64(double x);
double math_floor_f64(double x);
double math_ceil_f64(double x);
double math_round_f64(double x);
float math_trunc_f32(float x);
float math_floor_f32(float x);
float math_ceil_f32(float x);
float math_round_f32(float x);

/*
 * x - n*y with n = trunc(x/y), exact, with the sign of x (C99 fmod).
 * NaN when x is infinite or y is zero; x when y is infinite.
 */
double math_fmod_f64(double x, double y);
float math_fmod_f32(float x, float y);

/* Square root, correctly rounded (bit-identical to IEEE sqrt); sqrt(-0) = -0. */
double math_sqrt_f64(double x);
float math_sqrt_f32(float x);

/* floor(sqrt(x)) for every 64-bit x, exact. */
uint64_t math_isqrt_u64(uint64_t x);

/*
 * The same three in integer arithmetic only, always built: the entry points
 * above use the target's square-root instruction instead where the port
 * sets UUV_HW_SQRT_F64 / UUV_HW_SQRT_F32 (uuv_config.h), with the same bits.
 */
double math_sqrt_f64_soft(double x);
float math_sqrt_f32_soft(float x);
uint64_t math_isqrt_u64_soft(uint64_t x);

/*
 * Trigonometric functions of an angle in radians. Accurate for every finite
 * argument (exact argument reduction); NaN for an infinite or NaN argument.
 */
double math_sin_f64(double x);
double math_cos_f64(double x);
double math_tan_f64(double x);
void math_sincos_f64(double x, double *s, double *c);
float math_sin_f32(float x);
float math_cos_f32(float x);
float math_tan_f32(float x);
void math_sincos_f32(float x, float *s, float *c);

/*
 * The angle x - 2*pi*n wrapped into [-pi, pi] [rad], for headings and
 * electrical angles; x itself when |x| <= pi. NaN for an infinite or NaN x.
 */
double math_wrap_pi_f64(double x);
float math_wrap_pi_f32(float x);

/* Inverse trigonometric functions [rad]; atan2 follows C99 Annex F for zeros and infinities. */
double math_atan_f64(double x);
double math_atan2_f64(double y, double x);
double math_asin_f64(double x);
double math_acos_f64(double x);
float math_atan_f32(float x);
float math_atan2_f32(float y, float x);
float math_asin_f32(float x);
float math_acos_f32(float x);

/* Exponential and natural logarithm; log(0) = -inf, log(x < 0) = NaN. */
double math_exp_f64(double x);
double math_log_f64(double x);
float math_exp_f32(float x);
float math_log_f32(float x);

/* x raised to the power y, with the special cases of C99 Annex F (pow). */
double math_pow_f64(double x, double y);

#endif /* UUV_UMATH_H */
