/*
 * Single-bin DFT for the power-stage tests (test_pwm.c, test_power_stage.c):
 * X = (2 / N) sum_n x_n exp(-j theta_n), with theta_n from a 32-bit phase
 * accumulator (2^32 = one turn) and the basis from the Q15 wavetables
 * (32767 cos and 32767 sin within 1 LSB; the scale is divided out at the
 * end). Over a window of whole periods of the analysed frequency, a signal
 * A sin(theta + phi) gives X = A exp(j(phi - 90 deg)), so |X| is the
 * amplitude. Sums in double; integer basis values keep the cost low on a
 * core without an FPU.
 */
#ifndef UUV_POWER_TEST_DFT_H
#define UUV_POWER_TEST_DFT_H

#include <stdint.h>

#include "fixedpoint/wavetable.h"
#include "math/umath.h"

typedef struct {
    uint32_t ph;   /* phase of the next sample */
    uint32_t inc;  /* phase increment per sample */
    double re;
    double im;
    uint32_t n;
} tdft;

static inline void tdft_init(tdft *d, uint32_t inc, uint32_t ph0) {
    d->ph = ph0;
    d->inc = inc;
    d->re = 0.0;
    d->im = 0.0;
    d->n = 0u;
}

static inline void tdft_add(tdft *d, double x) {
    d->re += x * (double)wt_cos_q15(d->ph);
    d->im -= x * (double)wt_sin_q15(d->ph);
    d->ph += d->inc;
    d->n++;
}

/* Amplitude 2 |X| / N (the basis amplitude 32767 divided out). */
static inline double tdft_amp(const tdft *d) {
    if (d->n == 0u) {
        return 0.0;
    }
    return 2.0 * math_sqrt_f64(d->re * d->re + d->im * d->im) / ((double)d->n * 32767.0);
}

/* Phase of X [deg]. */
static inline double tdft_phase_deg(const tdft *d) {
    return math_atan2_f64(d->im, d->re) * MATH_RAD_TO_DEG_F64;
}

/* An angle [deg] wrapped into [-180, 180). */
static inline double tdft_wrap_deg(double a) {
    while (a >= 180.0) {
        a -= 360.0;
    }
    while (a < -180.0) {
        a += 360.0;
    }
    return a;
}

#endif /* UUV_POWER_TEST_DFT_H */
