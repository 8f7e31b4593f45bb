/*
 * Exhaustive check of the table waveforms of src/fixedpoint/wavetable.h
 * against exact references, for every phase the 32-bit accumulator can
 * present. Host program: uses libc and libm (sinl, cosl in long double).
 *
 * Why checking 2^26 references covers all 2^32 phases. A lookup uses only
 * the top 25 bits of the phase (10 index + 15 fraction bits), so it returns
 * one value L for each bucket of 128 consecutive phases. Bucket edges are
 * multiples of 128, and the waveforms turn only at multiples of 2^30 (sine)
 * or 2^31 (triangle), which are bucket edges too: inside a bucket each
 * waveform is monotone. So over a bucket the exact value y runs between its
 * values at the bucket's first and last phase, and so does round(y), the
 * rounding being monotone. If L is within 1 of round(y) at both ends, it is
 * within 1 of every round(y) in between (and |L - y| is largest at an end,
 * being convex in y). The check therefore evaluates each bucket's two ends.
 *
 * Output: first the two lines
 *     sine max error: <e> LSB over <n> phases
 *     triangle max error: <e> LSB over <n> phases
 * (e = max |lookup - round(32767 w)|, the Q15 requirement being e <= 1),
 * then the float twins (max |lookup - w|, requirement 2^-15), the largest
 * unrounded deviations against the error analysis of docs/fixedpoint.md,
 * and "N passed, N failed". The exit status is 0 only if every bound holds.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>

#include "fixedpoint/wavetable.h"

#define BUCKETS (1ul << (WT_INDEX_BITS + WT_FRAC_BITS))
#define BUCKET_LAST ((1u << WT_IGNORED_BITS) - 1u)
#define NEAR_TIE 1e-9L /* a reference closer than this to a tie counts as ambiguous */

/* Bounds from the error analysis (docs/fixedpoint.md), in Q15 LSB or units. */
#define SINE_Q15_DEVIATION_BOUND 0.6663L
#define TRIANGLE_Q15_DEVIATION_BOUND 0.5079L
#define F32_BOUND (1.0L / 32768.0L)

static const long double two_pi_l = 6.283185307179586476925286766559005768L;

typedef struct {
    long double max_int_error;  /* max |L - round(y)| [LSB] (or [1] for float) */
    long double max_deviation;  /* max |L - y| */
    unsigned long ambiguous;    /* references within NEAR_TIE of a rounding tie */
} stats;

/*
 * sin(2 pi phase / 2^32) in long double after an exact integer reduction of
 * the phase to an angle of at most pi/4 (the reduction of the generator).
 */
static long double ref_sin_turn(uint32_t phase) {
    uint32_t quadrant = phase >> 30;
    uint32_t u = phase & 0x3FFFFFFFu;
    int use_cos = (quadrant & 1u) != 0u;
    long double x;
    long double s;

    if (u > 0x20000000u) {
        u = 0x40000000u - u;
        use_cos = !use_cos;
    }
    x = two_pi_l * (long double)u / 4294967296.0L;
    s = use_cos ? cosl(x) : sinl(x);
    return (quadrant >= 2u) ? -s : s;
}

/* The unit triangle, exact in long double: -1 at 0, +1 at 2^31. */
static long double ref_tri_turn(uint32_t phase) {
    long double half = 2147483648.0L;

    if (phase <= 0x80000000u) {
        return -1.0L + 2.0L * (long double)phase / half;
    }
    return 1.0L - 2.0L * (long double)(phase - 0x80000000u) / half;
}

/* Scores a Q15 lookup L against the exact y = 32767 w at one phase. */
static void score_q15(stats *st, long double lookup, long double y) {
    long double lower = floorl(y);
    long double error;

    if (fabsl((y - lower) - 0.5L) < NEAR_TIE) {
        /* Either neighbour may be the rounded value: demand both. */
        long double e_low = fabsl(lookup - lower);
        long double e_high = fabsl(lookup - (lower + 1.0L));
        error = (e_low > e_high) ? e_low : e_high;
        st->ambiguous++;
    } else {
        error = fabsl(lookup - roundl(y));
    }
    if (error > st->max_int_error) {
        st->max_int_error = error;
    }
    if (fabsl(lookup - y) > st->max_deviation) {
        st->max_deviation = fabsl(lookup - y);
    }
}

/* Scores a float lookup against the exact unit waveform w at one phase. */
static void score_f32(stats *st, long double lookup, long double w) {
    if (fabsl(lookup - w) > st->max_deviation) {
        st->max_deviation = fabsl(lookup - w);
    }
}

static unsigned passed;
static unsigned failed;

static void verdict(int ok, const char *what) {
    if (ok) {
        passed++;
    } else {
        failed++;
        printf("FAIL: %s\n", what);
    }
}

int main(void) {
    stats sine = {0.0L, 0.0L, 0u}, tri = {0.0L, 0.0L, 0u};
    stats sine_f = {0.0L, 0.0L, 0u}, tri_f = {0.0L, 0.0L, 0u};
    unsigned long b;
    unsigned long long phases = (unsigned long long)BUCKETS << WT_IGNORED_BITS;

    for (b = 0u; b < BUCKETS; b++) {
        uint32_t ends[2];
        int e;

        ends[0] = (uint32_t)b << WT_IGNORED_BITS;
        ends[1] = ends[0] + BUCKET_LAST;
        for (e = 0; e < 2; e++) {
            long double s = ref_sin_turn(ends[e]);
            long double t = ref_tri_turn(ends[e]);

            /* The lookup at either end is the bucket's one value. */
            score_q15(&sine, (long double)wt_sin_q15(ends[e]), 32767.0L * s);
            score_q15(&tri, (long double)wt_tri_q15(ends[e]), 32767.0L * t);
            score_f32(&sine_f, (long double)wt_sin_f32(ends[e]), s);
            score_f32(&tri_f, (long double)wt_tri_f32(ends[e]), t);
        }
    }

    printf("sine max error: %.0Lf LSB over %llu phases\n", sine.max_int_error, phases);
    printf("triangle max error: %.0Lf LSB over %llu phases\n", tri.max_int_error, phases);
    printf("sine f32 max error: %.3Le (2^-15 = %.3Le) over %llu phases\n",
           sine_f.max_deviation, F32_BOUND, phases);
    printf("triangle f32 max error: %.3Le (2^-15 = %.3Le) over %llu phases\n",
           tri_f.max_deviation, F32_BOUND, phases);
    printf("sine q15 max |lookup - 32767 sin|: %.4Lf LSB (analysis bound %.4Lf)\n",
           sine.max_deviation, SINE_Q15_DEVIATION_BOUND);
    printf("triangle q15 max |lookup - 32767 tri|: %.4Lf LSB (analysis bound %.4Lf)\n",
           tri.max_deviation, TRIANGLE_Q15_DEVIATION_BOUND);
    printf("references within %.0Le of a rounding tie (both neighbours demanded): "
           "sine %lu, triangle %lu\n", NEAR_TIE, sine.ambiguous, tri.ambiguous);
    printf("method: %lu lookup inputs (%u index + %u fraction bits), each scored at both "
           "ends of its bucket of %u phases, inside which the waveforms are monotone\n",
           (unsigned long)BUCKETS, WT_INDEX_BITS, WT_FRAC_BITS, BUCKET_LAST + 1u);

    verdict(sine.max_int_error <= 1.0L, "sine Q15 within 1 LSB of the rounded sine");
    verdict(tri.max_int_error <= 1.0L, "triangle Q15 within 1 LSB of the rounded triangle");
    verdict(sine_f.max_deviation <= F32_BOUND, "sine f32 within 2^-15 of sin");
    verdict(tri_f.max_deviation <= F32_BOUND, "triangle f32 within 2^-15 of the triangle");
    verdict(sine.max_deviation <= SINE_Q15_DEVIATION_BOUND, "sine Q15 within its analysis bound");
    verdict(tri.max_deviation <= TRIANGLE_Q15_DEVIATION_BOUND,
            "triangle Q15 within its analysis bound");
    printf("%u passed, %u failed\n", passed, failed);
    return failed == 0u ? 0 : 1;
}
