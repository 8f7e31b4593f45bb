/*
 * Conversions between floating point and the Q formats, and the per-unit
 * helpers. These run at set-up and in tests, not on the fast path, so they
 * favour exactness over speed.
 *
 * Method, shared by every from_* function: scale by 2^15 or 2^31 (exact, a
 * power of two), clamp by comparison with the half-step beyond each end of
 * the range, truncate towards zero (defined, because the value is then in
 * range), and correct the truncation by the fractional part, which is
 * computed exactly (it is the low bits of the scaled value). The result is
 * round-to-nearest with ties away from zero and no double rounding.
 */
#include "fixedpoint/fixedpoint.h"

q15_t fp_from_f64_cnt_q15(double x, uint32_t *sat_count) {
    double scaled = x * 32768.0;
    int32_t t;
    double frac;

    if (!(scaled == scaled)) { /* NaN */
        fp_count_sat(sat_count);
        return 0;
    }
    if (scaled >= 32767.5) {
        fp_count_sat(sat_count);
        return Q15_MAX;
    }
    if (scaled <= -32768.5) {
        fp_count_sat(sat_count);
        return Q15_MIN;
    }
    t = (int32_t)scaled;
    frac = scaled - (double)t;
    if (frac >= 0.5) {
        t += 1;
    } else if (frac <= -0.5) {
        t -= 1;
    }
    return (q15_t)t;
}

q31_t fp_from_f64_cnt_q31(double x, uint32_t *sat_count) {
    double scaled = x * 2147483648.0;
    int64_t t;
    double frac;

    if (!(scaled == scaled)) { /* NaN */
        fp_count_sat(sat_count);
        return 0;
    }
    if (scaled >= 2147483647.5) {
        fp_count_sat(sat_count);
        return Q31_MAX;
    }
    if (scaled <= -2147483648.5) {
        fp_count_sat(sat_count);
        return Q31_MIN;
    }
    t = (int64_t)scaled;
    frac = scaled - (double)t;
    if (frac >= 0.5) {
        t += 1;
    } else if (frac <= -0.5) {
        t -= 1;
    }
    return (q31_t)t;
}

/*
 * The float forms work in float: the scaled value, the bounds 32767.5 and
 * -32768.5, and the fractional part are all exact in single precision.
 */
q15_t fp_from_f32_cnt_q15(float x, uint32_t *sat_count) {
    float scaled = x * 32768.0f;
    int32_t t;
    float frac;

    if (!(scaled == scaled)) { /* NaN */
        fp_count_sat(sat_count);
        return 0;
    }
    if (scaled >= 32767.5f) {
        fp_count_sat(sat_count);
        return Q15_MAX;
    }
    if (scaled <= -32768.5f) {
        fp_count_sat(sat_count);
        return Q15_MIN;
    }
    t = (int32_t)scaled;
    frac = scaled - (float)t;
    if (frac >= 0.5f) {
        t += 1;
    } else if (frac <= -0.5f) {
        t -= 1;
    }
    return (q15_t)t;
}

/*
 * In single precision every float of magnitude 2^23 or more is an integer,
 * so no float lies in (2^31 - 1, 2^31) and the upper clamp is at 2^31
 * itself; -2^31 is in range and exact. Those integers convert exactly and
 * are returned before the rounding step, which thus sees |t| < 2^23 and
 * cannot overflow when it corrects t by one (the early return changes no
 * result: their fractional part is 0).
 */
q31_t fp_from_f32_cnt_q31(float x, uint32_t *sat_count) {
    float scaled = x * 2147483648.0f;
    int32_t t;
    float frac;

    if (!(scaled == scaled)) { /* NaN */
        fp_count_sat(sat_count);
        return 0;
    }
    if (scaled >= 2147483648.0f) {
        fp_count_sat(sat_count);
        return Q31_MAX;
    }
    if (scaled < -2147483648.0f) {
        fp_count_sat(sat_count);
        return Q31_MIN;
    }
    if (scaled >= 8388608.0f || scaled <= -8388608.0f) {
        return (int32_t)scaled;
    }
    t = (int32_t)scaled;
    frac = scaled - (float)t;
    if (frac >= 0.5f) {
        t += 1;
    } else if (frac <= -0.5f) {
        t -= 1;
    }
    return t;
}

q15_t fp_from_f32_q15(float x) {
    uint32_t unused = 0u;
    return fp_from_f32_cnt_q15(x, &unused);
}

q31_t fp_from_f32_q31(float x) {
    uint32_t unused = 0u;
    return fp_from_f32_cnt_q31(x, &unused);
}

q15_t fp_from_f64_q15(double x) {
    uint32_t unused = 0u;
    return fp_from_f64_cnt_q15(x, &unused);
}

q31_t fp_from_f64_q31(double x) {
    uint32_t unused = 0u;
    return fp_from_f64_cnt_q31(x, &unused);
}

q15_t fp_pu_from_f64_q15(double value, double base) {
    return fp_from_f64_q15(value / base);
}

q31_t fp_pu_from_f64_q31(double value, double base) {
    return fp_from_f64_q31(value / base);
}

double fp_pu_to_f64_q15(q15_t pu, double base) {
    return base * fp_to_f64_q15(pu);
}

double fp_pu_to_f64_q31(q31_t pu, double base) {
    return base * fp_to_f64_q31(pu);
}
