/*
 * Phase increments of the table waveforms (the lookups themselves are
 * inline in wavetable.h; the tables are in wavetable_data.c).
 */
#include "fixedpoint/wavetable.h"

/*
 * 2^32 * (freq_q16 / 2^16) * (step_ns / 10^9) = m * 2^7 / 5^9 with
 * m = |freq_q16| * step_ns < 2^31 * 2^32. Splitting m = q * 5^9 + r gives
 * q * 2^7 exactly (only its low 32 bits matter) plus r * 2^7 / 5^9 < 2^7,
 * rounded as floor((r * 2^8 + 5^9) / (2 * 5^9)). That quotient is never a
 * tie, because 5^9 is odd and r * 2^8 is even.
 */
uint32_t wt_phase_inc_q16(int32_t freq_q16, uint32_t step_ns) {
    const uint64_t five_pow_9 = 1953125u;
    uint64_t magnitude = (freq_q16 < 0) ? (uint64_t)(-(int64_t)freq_q16) : (uint64_t)freq_q16;
    uint64_t m = magnitude * (uint64_t)step_ns;
    uint64_t whole = (m / five_pow_9) << 7;
    uint64_t part = ((m % five_pow_9) * 256u + five_pow_9) / (2u * five_pow_9);
    uint32_t inc = (uint32_t)(whole + part); /* modulo 2^32: whole turns drop out */

    return (freq_q16 < 0) ? 0u - inc : inc;
}

/*
 * counts = (f * T) * 2^32 is exact after the one rounding of f * T. Every
 * float of magnitude 2^55 or more is a multiple of 2^32, so its increment
 * modulo 2^32 is 0; below that the value converts to int64_t without
 * overflow and is rounded to nearest (ties away from zero) from its exact
 * fractional part, then reduced modulo 2^32 by the unsigned conversion.
 */
uint32_t wt_phase_inc_f32(float freq_hz, float step_s) {
    float counts = (freq_hz * step_s) * 4294967296.0f;
    const float two_pow_55 = 36028797018963968.0f;
    int64_t whole;
    float frac;

    if (!(counts == counts) || counts >= two_pow_55 || counts <= -two_pow_55) {
        return 0u;
    }
    whole = (int64_t)counts;
    frac = counts - (float)whole;
    if (frac >= 0.5f) {
        whole += 1;
    } else if (frac <= -0.5f) {
        whole -= 1;
    }
    return (uint32_t)whole;
}
