/*
 * Internal helpers of the math library, shared by its source files and not
 * part of the public API: error-free transformations (sums and products that
 * return their rounding error), exact powers of two, and the argument
 * reduction modulo pi/2.
 *
 * The error-free transformations are the classical ones of Knuth (two_sum),
 * Dekker (fast_two_sum) and Veltkamp/Dekker (split, two_prod). They are exact
 * in round-to-nearest IEEE arithmetic as long as nothing overflows and the
 * products stay clear of the subnormal range; every caller documents why its
 * operands satisfy that. They use only +, - and *, so they give the same bits
 * on every port.
 */
#ifndef UUV_MATH_PRIVATE_H
#define UUV_MATH_PRIVATE_H

#include <stdint.h>

#include "math/umath.h"

/* s + e == a + b exactly, s = fl(a + b); any a, b without overflow. */
static inline void math_two_sum_f64(double a, double b, double *s, double *e) {
    double sum = a + b;
    double bv = sum - a;
    double av = sum - bv;
    *s = sum;
    *e = (a - av) + (b - bv);
}

/* The same when |a| >= |b| (or a == 0): three operations instead of six. */
static inline void math_fast_two_sum_f64(double a, double b, double *s, double *e) {
    double sum = a + b;
    *s = sum;
    *e = b - (sum - a);
}

/* hi + lo == a, each with at most 26 significant bits; |a| < 2^995. */
static inline void math_split_f64(double a, double *hi, double *lo) {
    double t = 0x1.0000002p27 * a; /* 2^27 + 1 */
    double h = t - (t - a);
    *hi = h;
    *lo = a - h;
}

/* p + e == a * b exactly, p = fl(a * b); no overflow, |a*b| well above 2^-969. */
static inline void math_two_prod_f64(double a, double b, double *p, double *e) {
    double ah;
    double al;
    double bh;
    double bl;
    double prod = a * b;
    math_split_f64(a, &ah, &al);
    math_split_f64(b, &bh, &bl);
    *p = prod;
    *e = ((ah * bh - prod) + ah * bl + al * bh) + al * bl;
}

static inline void math_two_sum_f32(float a, float b, float *s, float *e) {
    float sum = a + b;
    float bv = sum - a;
    float av = sum - bv;
    *s = sum;
    *e = (a - av) + (b - bv);
}

static inline void math_fast_two_sum_f32(float a, float b, float *s, float *e) {
    float sum = a + b;
    *s = sum;
    *e = b - (sum - a);
}

/* hi + lo == a, each with at most 12 significant bits; |a| < 2^114. */
static inline void math_split_f32(float a, float *hi, float *lo) {
    float t = 0x1.001p12f * a; /* 2^12 + 1 */
    float h = t - (t - a);
    *hi = h;
    *lo = a - h;
}

static inline void math_two_prod_f32(float a, float b, float *p, float *e) {
    float ah;
    float al;
    float bh;
    float bl;
    float prod = a * b;
    math_split_f32(a, &ah, &al);
    math_split_f32(b, &bh, &bl);
    *p = prod;
    *e = ((ah * bh - prod) + ah * bl + al * bh) + al * bl;
}

/* 2^k for -1022 <= k <= 1023 (a normal number), built from its bits. */
static inline double math_pow2i_f64(int k) {
    return math_from_bits_f64((uint64_t)(k + 1023) << 52);
}

/* 2^k for -126 <= k <= 127. */
static inline float math_pow2i_f32(int k) { return math_from_bits_f32((uint32_t)(k + 127) << 23); }

/*
 * x * 2^k for x in [0.5, 4) and -1100 <= k <= 1100, rounded once: the result
 * overflows to infinity or becomes subnormal or zero as IEEE multiplication
 * by a power of two would (src/math/scale.c).
 */
double math_scale_f64(double x, int k);
float math_scale_f32(float x, int k);

/*
 * Argument reduction: x = n*pi/2 + (hi + lo) with |hi + lo| <= pi/4 (plus a
 * relative 2^-14 when n is rounded in floating point), |lo| <= ulp(hi), and
 * hi + lo within 2^-59 (double) or 2^-40 (float) relative of the exact
 * remainder for every finite x. Returns n mod 4. x must be finite
 * (src/math/rem_pio2.c).
 */
unsigned math_rem_pio2_f64(double x, double *hi, double *lo);
unsigned math_rem_pio2_f32(float x, float *hi, float *lo);

/* Natural logarithm of a positive finite x as hi + *lo, |lo| <= ulp(hi)/2 (log_f64.c). */
double math_log_dd_f64(double x, double *lo);

/* exp(x + xlo) for |xlo| <= ulp(x) and any x but a NaN (exp_f64.c). */
double math_exp_dd_f64(double x, double xlo);

#endif /* UUV_MATH_PRIVATE_H */
