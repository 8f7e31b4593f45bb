/*
 * Sine and triangle waveforms by table lookup with linear interpolation,
 * driven by a 32-bit phase accumulator: the PWM modulator's references and
 * carrier on the 2 us fast path.
 *
 * Phase. A phase is a uint32_t where a full turn is 2^32 (so 2^30 is 90
 * degrees). A generator keeps `phase += inc` every step; unsigned arithmetic
 * wraps modulo 2^32, which is exactly the wrap of the angle. The increment
 * for a frequency f and a step T is round(2^32 * f * T) (see
 * wt_phase_inc_q16() and wt_phase_inc_f32()); a negative frequency is the
 * increment's two's complement, so the phase runs backwards.
 *
 * Lookup. The top WT_INDEX_BITS bits of the phase select segment k of the
 * turn; the next WT_FRAC_BITS bits are the fraction f / 2^15 of the way
 * from knot k to knot k + 1; the lowest 7 bits are ignored. A turn has
 * WT_TABLE_SIZE + 1 knots: the last equals the first, so segment 1023
 * interpolates towards the wrap without a test. The sine's knots come from a
 * table of its first quarter turn, unfolded by symmetry. The triangle needs
 * no table: it is linear on each half turn, so its knots and their
 * differences are computed.
 *
 * Waveforms (Q15 outputs, the float twins are the same divided by 32767):
 *   sine:     32767 * sin(2 pi phase / 2^32);
 *   triangle: the PWM carrier, -32767 at phase 0 (valley), rising linearly
 *             to +32767 at phase 2^31 (peak), falling back to -32767 at
 *             2^32; it is even about phase 0: tri(-p) = tri(p).
 * Accuracy (measured exhaustively by tools/check_tables for every one of the
 * 2^32 phases, see docs/fixedpoint.md): each Q15 output is within 1 LSB of
 * the exactly rounded value round(32767 * w(phase)); each float output is
 * within 2^-15 of the exact w(phase) (w the unit waveform).
 *
 * Cost. A Q15 sine lookup is two unfolded loads (a mask, a comparison and
 * a conditional negation each), a subtraction, a multiplication, an offset
 * floor shift and a rounding shift; the float lookup is the two loads, a
 * conversion and a multiply-add. No division. The triangle replaces the
 * loads by a comparison and a multiply-add. The sine is evaluated at the
 * motor task's rate on the real-time path (pwm_rt.h), the triangle at 2 us.
 */
#ifndef UUV_WAVETABLE_H
#define UUV_WAVETABLE_H

#include <stdint.h>

#include "fixedpoint/fixedpoint.h"

#define WT_INDEX_BITS 10u                      /* segments per turn = 2^10 */
#define WT_FRAC_BITS 15u                       /* interpolation fraction bits */
#define WT_TABLE_SIZE (1u << WT_INDEX_BITS)    /* entries per turn (+1 guard stored) */
#define WT_IGNORED_BITS (32u - WT_INDEX_BITS - WT_FRAC_BITS) /* phase bits not used: 7 */
#define WT_ENTRY_EXTRA_BITS 8u                 /* fixed entries: bits below the Q15 LSB */
#define WT_AMPLITUDE_Q15 32767                 /* peak of the Q15 waveforms */

#define WT_PHASE_QUARTER 0x40000000u /* 90 degrees */
#define WT_PHASE_HALF 0x80000000u    /* 180 degrees */
#define WT_PHASE_120 1431655765u     /* round(2^32 / 3): 120 degrees, 1/3 count short */
#define WT_PHASE_240 2863311531u     /* round(2^33 / 3): 240 degrees, 1/3 count long */

/*
 * The sine's knots. Entry k of the full turn (k = 0 .. 1024, at phase
 * k * 2^22) is round(256 * 32767 * sin(2 pi k / 1024)) in Q23 of the Q15
 * waveform (|entry| <= 8388352) and sin(2 pi k / 1024) rounded to float.
 * The rounded sine keeps the sine's symmetries exactly (sin(pi - x) = sin x,
 * sin(x + pi) = -sin x; the generator checks it), so only the first quarter,
 * k = 0 .. 256, is stored (wavetable_data.c, written by
 * tools/gen_wavetables.c) and wt_sine_knot_*() unfold it: a mirror and a
 * sign, a few instructions, for 3 KiB of flash per table.
 */
#define WT_QUARTER_SIZE (WT_TABLE_SIZE / 4u) /* segments per quarter turn: 256 */

extern const int32_t wt_sine_quarter_q23[WT_QUARTER_SIZE + 1u];
extern const float wt_sine_quarter_f32[WT_QUARTER_SIZE + 1u];

/* The quarter-table index of full-turn knot k: k folded into [0, 256]. */
static inline uint32_t wt_quarter_index(uint32_t k) {
    uint32_t h = k & (WT_TABLE_SIZE / 2u - 1u); /* position in the half turn */
    return (h <= WT_QUARTER_SIZE) ? h : WT_TABLE_SIZE / 2u - h;
}

/* Knot k (0 .. 1024) of the full-turn sine, Q23. */
static inline int32_t wt_sine_knot_q23(uint32_t k) {
    int32_t e = wt_sine_quarter_q23[wt_quarter_index(k)];
    return ((k & (WT_TABLE_SIZE / 2u)) != 0u) ? -e : e;
}

/* Knot k (0 .. 1024) of the full-turn sine, float. */
static inline float wt_sine_knot_f32(uint32_t k) {
    float e = wt_sine_quarter_f32[wt_quarter_index(k)];
    return ((k & (WT_TABLE_SIZE / 2u)) != 0u) ? -e : e;
}

/*
 * The triangle's knots, k = 0 .. 1024 (entry k at phase k 2^22):
 * 256 tri(k) = -8388352 + 32767 k for k <= 512 and 8388352 - 32767 (k - 512)
 * above (exact integers, |value| <= 8388352); tri(k) / 32767 = -1 + k / 256
 * and 3 - k / 256 (exact floats).
 */
#define WT_TRI_KNOT_Q23 8388352 /* 256 * 32767 */
#define WT_TRI_SLOPE_Q23 32767  /* change per segment, Q23 */

/*
 * Linear interpolation between two Q23 knots, rounded to Q15.
 *
 * Scaling: entries e0, e1 are Q23; the fraction f is in [0, 2^15). The
 * interpolated value is e0 + floor((e1 - e0) * f / 2^15), Q23, then rounded
 * to Q15 (ties up). Overflow: none. |e1 - e0| <= 51472 (the steepest sine
 * segment, 256 * 32767 * 2 pi / 1024) so the product is below 2^31 in
 * magnitude; the interpolated value lies between e0 and e1 (floor can take
 * it at most 1 below), in [-8388353, 8388352], so adding 2^23 + 2^7 makes it
 * positive before the rounding shift, and the result is in [-32767, 32767].
 */
static inline q15_t wt_segment_q15(int32_t e0, int32_t e1, uint32_t phase) {
    int32_t frac = (int32_t)((phase >> WT_IGNORED_BITS) & ((1u << WT_FRAC_BITS) - 1u));
    int32_t step = fp_shr_floor_i32((e1 - e0) * frac, WT_FRAC_BITS);
    uint32_t offset = (uint32_t)(e0 + step + (32768 << WT_ENTRY_EXTRA_BITS) +
                                 (1 << (WT_ENTRY_EXTRA_BITS - 1u)));
    return (q15_t)((int32_t)(offset >> WT_ENTRY_EXTRA_BITS) - 32768);
}

/*
 * The float twin of wt_segment_q15(): the same segment and the same 15-bit
 * fraction (converted exactly to float), e0 + (e1 - e0) * f in single
 * precision. With -ffp-contract=off every target rounds it alike.
 */
static inline float wt_segment_f32(float e0, float e1, uint32_t phase) {
    float frac = (float)((phase >> WT_IGNORED_BITS) & ((1u << WT_FRAC_BITS) - 1u)) *
                 (1.0f / 32768.0f);
    return e0 + (e1 - e0) * frac;
}

/* 32767 * sin(2 pi phase / 2^32), Q15, within 1 LSB of the rounded value. */
static inline q15_t wt_sin_q15(uint32_t phase) {
    uint32_t k = phase >> (32u - WT_INDEX_BITS);
    return wt_segment_q15(wt_sine_knot_q23(k), wt_sine_knot_q23(k + 1u), phase);
}

/* 32767 * cos(2 pi phase / 2^32): the sine a quarter turn ahead. */
static inline q15_t wt_cos_q15(uint32_t phase) {
    return wt_sin_q15(phase + WT_PHASE_QUARTER);
}

/*
 * The PWM carrier in Q15: -32767 at phase 0, +32767 at phase 2^31. The
 * interpolation of wt_segment_q15() between the knots above, which differ
 * by +-32767 (within its bound of 51472).
 */
static inline q15_t wt_tri_q15(uint32_t phase) {
    int32_t k = (int32_t)(phase >> (32u - WT_INDEX_BITS));
    int32_t e0;
    int32_t d;
    if (k < (int32_t)(WT_TABLE_SIZE / 2u)) {
        e0 = -WT_TRI_KNOT_Q23 + WT_TRI_SLOPE_Q23 * k;
        d = WT_TRI_SLOPE_Q23;
    } else {
        e0 = WT_TRI_KNOT_Q23 - WT_TRI_SLOPE_Q23 * (k - (int32_t)(WT_TABLE_SIZE / 2u));
        d = -WT_TRI_SLOPE_Q23;
    }
    return wt_segment_q15(e0, e0 + d, phase);
}

/* sin(2 pi phase / 2^32), within 2^-15 of the exact value. */
static inline float wt_sin_f32(uint32_t phase) {
    uint32_t k = phase >> (32u - WT_INDEX_BITS);
    return wt_segment_f32(wt_sine_knot_f32(k), wt_sine_knot_f32(k + 1u), phase);
}

/* cos(2 pi phase / 2^32), within 2^-15 of the exact value. */
static inline float wt_cos_f32(uint32_t phase) {
    return wt_sin_f32(phase + WT_PHASE_QUARTER);
}

/*
 * The PWM carrier in [-1, 1]: -1 at phase 0, +1 at phase 2^31. The
 * interpolation of wt_segment_f32() between the knots above, whose
 * difference is exactly +-1/256 in float.
 */
static inline float wt_tri_f32(uint32_t phase) {
    uint32_t k = phase >> (32u - WT_INDEX_BITS);
    float frac = (float)((phase >> WT_IGNORED_BITS) & ((1u << WT_FRAC_BITS) - 1u)) *
                 (1.0f / 32768.0f);
    if (k < WT_TABLE_SIZE / 2u) {
        return (-1.0f + (float)k / 256.0f) + (1.0f / 256.0f) * frac;
    }
    return (3.0f - (float)k / 256.0f) + (-1.0f / 256.0f) * frac;
}

/*
 * Phase increment round(2^32 * f * T) modulo 2^32 for a frequency
 * freq_q16 in Q16.16 hertz (signed, |f| < 32768 Hz, resolution 2^-16 Hz)
 * and a step step_ns in nanoseconds. Integer arithmetic only, exact: the
 * rounding is to nearest (no ties can occur). Whole turns per step drop out
 * of the modulo; a negative frequency gives the negated increment. For
 * 5 kHz and 2 us: 42949673 (exact value 42949672.96). Set-up or 800 us
 * rate: it divides (64-bit, by a constant).
 */
uint32_t wt_phase_inc_q16(int32_t freq_q16, uint32_t step_ns);

/*
 * Phase increment for a frequency in float hertz and a step in seconds:
 * round(2^32 * (f * T)) modulo 2^32, where only the product f * T is rounded
 * (to float, relative error 2^-24: at most a few counts of a carrier's
 * increment). A NaN gives 0.
 */
uint32_t wt_phase_inc_f32(float freq_hz, float step_s);

/*
 * Phase increment for a per-unit frequency: round(freq_pu * inc_base / 2^31)
 * modulo 2^32, where inc_base is the increment at the base frequency (from
 * wt_phase_inc_q16()) and freq_pu is Q31 of that base (negative runs the
 * phase backwards). The product is exact in int64_t; the rounding is to
 * nearest, ties up; no overflow. Cheap enough for the controller's rate.
 */
static inline uint32_t wt_phase_inc_pu_q31(q31_t freq_pu, uint32_t inc_base) {
    int64_t scaled = fp_shr_round_i64((int64_t)freq_pu * (int64_t)inc_base, 31u);
    return (uint32_t)scaled; /* conversion to unsigned is modulo 2^32 */
}

#endif /* UUV_WAVETABLE_H */
