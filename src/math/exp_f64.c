/*
 * exp in double precision, table driven.
 *
 * x = (32k + j) * ln2/32 + r with n = 32k + j = round(x * 32/ln2),
 * 0 <= j < 32 and |r| <= ln2/64 (ln2/32 in two parts L1 + L2, L1 with 36
 * significant bits so that n*L1 is exact and x - n*L1 too). Then
 *     exp(x) = 2^k * 2^(j/32) * exp(r),  exp(r) = 1 + r + r^2 * E(r),
 * E a minimax polynomial of degree 4 (relative error 2^-63.3 over
 * |r| <= ln2/64; Remez exchange in 90-digit arithmetic, coefficients rounded
 * to double one at a time with the rest re-optimised). 2^(j/32) is a
 * two-part table entry T_hi + T_lo, correctly rounded and computed in
 * 500-digit arithmetic. The sum T_hi + (T_lo + T_hi*p) rounds once, so the
 * result is within about 0.51 ulp before the exact scaling by 2^k; only a
 * subnormal result can be rounded a second time (up to 1 ulp then).
 */
#include "math/math_private.h"

/* 2^(j/32) = hi + lo, j = 0..31. */
static const double EXP2_J32[32][2] = {
    {0x1p+0, 0.0},
    {0x1.059b0d3158574p+0, 0x1.d73e2a475b465p-55},
    {0x1.0b5586cf9890fp+0, 0x1.8a62e4adc610bp-54},
    {0x1.11301d0125b51p+0, -0x1.6c51039449b3ap-54},
    {0x1.172b83c7d517bp+0, -0x1.19041b9d78a76p-55},
    {0x1.1d4873168b9aap+0, 0x1.e016e00a2643cp-54},
    {0x1.2387a6e756238p+0, 0x1.9b07eb6c70573p-54},
    {0x1.29e9df51fdee1p+0, 0x1.612e8afad1255p-55},
    {0x1.306fe0a31b715p+0, 0x1.6f46ad23182e4p-55},
    {0x1.371a7373aa9cbp+0, -0x1.63aeabf42eae2p-54},
    {0x1.3dea64c123422p+0, 0x1.ada0911f09ebcp-55},
    {0x1.44e086061892dp+0, 0x1.89b7a04ef80dp-59},
    {0x1.4bfdad5362a27p+0, 0x1.d4397afec42e2p-56},
    {0x1.5342b569d4f82p+0, -0x1.07abe1db13cadp-55},
    {0x1.5ab07dd485429p+0, 0x1.6324c054647adp-54},
    {0x1.6247eb03a5585p+0, -0x1.383c17e40b497p-54},
    {0x1.6a09e667f3bcdp+0, -0x1.bdd3413b26456p-54},
    {0x1.71f75e8ec5f74p+0, -0x1.16e4786887a99p-55},
    {0x1.7a11473eb0187p+0, -0x1.41577ee04992fp-55},
    {0x1.82589994cce13p+0, -0x1.d4c1dd41532d8p-54},
    {0x1.8ace5422aa0dbp+0, 0x1.6e9f156864b27p-54},
    {0x1.93737b0cdc5e5p+0, -0x1.75fc781b57ebcp-57},
    {0x1.9c49182a3f09p+0, 0x1.c7c46b071f2bep-56},
    {0x1.a5503b23e255dp+0, -0x1.d2f6edb8d41e1p-54},
    {0x1.ae89f995ad3adp+0, 0x1.7a1cd345dcc81p-54},
    {0x1.b7f76f2fb5e47p+0, -0x1.5584f7e54ac3bp-56},
    {0x1.c199bdd85529cp+0, 0x1.11065895048ddp-55},
    {0x1.cb720dcef9069p+0, 0x1.503cbd1e949dbp-56},
    {0x1.d5818dcfba487p+0, 0x1.2ed02d75b3707p-55},
    {0x1.dfc97337b9b5fp+0, -0x1.1a5cd4f184b5cp-54},
    {0x1.ea4afa2a490dap+0, -0x1.e9c23179c2893p-54},
    {0x1.f50765b6e454p+0, 0x1.9d3e12dd8a18bp-54},
};

/* exp(x) overflows above 1024*ln2 and rounds to zero below -1075*ln2. */
static const double EXP_OVERFLOW = 0x1.62e42fefa39efp+9;
static const double EXP_UNDERFLOW = -0x1.74910d52d3052p+9;

double math_exp_dd_f64(double x, double xlo) {
    static const double INV_L = 0x1.71547652b82fep+5; /* 32/ln2 */
    static const double L1 = 0x1.62e42fefap-6;
    static const double L2 = 0x1.cf79abc9e3b3ap-45;
    static const double E0 = 0x1.fffffffffffffp-2;
    static const double E1 = 0x1.5555555548f6bp-3;
    static const double E2 = 0x1.5555555586a1dp-5;
    static const double E3 = 0x1.11115b7df3c1bp-7;
    static const double E4 = 0x1.6c1666bcb7c82p-10;
    if (x > EXP_OVERFLOW) {
        return math_inf_f64();
    }
    if (x < EXP_UNDERFLOW) {
        return 0.0;
    }
    /* |n| <= 34393 < 2^16, so n*L1 is exact and (int32_t)fn is in range. */
    double fn = (x * INV_L + 0x1.8p52) - 0x1.8p52;
    int32_t n = (int32_t)fn;
    double r = ((x - fn * L1) - fn * L2) + xlo;
    uint32_t j = (uint32_t)n & 31u;
    int32_t k = (n - (int32_t)j) / 32; /* exact: n - j is a multiple of 32 */
    double p = r + (r * r) * (E0 + r * (E1 + r * (E2 + r * (E3 + r * E4))));
    double v = EXP2_J32[j][0] + (EXP2_J32[j][1] + EXP2_J32[j][0] * p);
    return math_scale_f64(v, (int)k);
}

double math_exp_f64(double x) {
    if (math_isnan_f64(x)) {
        return math_nan_f64();
    }
    return math_exp_dd_f64(x, 0.0);
}
