/*
 * Host micro-benchmark of the induction motor step: nanoseconds per step of
 * the integer (_q), single (_f32) and double (_f64) twins, driven by the
 * drive's machine at 50.67 Hz, 234 V line to line, against the propeller.
 * The stimulus is precomputed (one period of step-mean voltages), so only
 * the step is timed. Host-only: uses libc, libm and the POSIX clock.
 *
 * Build: make host-benches (build/tools/bench_induction_motor).
 */
#include <math.h>
#include <stdio.h>
#include <time.h>

#include "math/umath.h"
#include "models/drive/drive_units.h"
#include "models/drive/motor/induction_motor.h"

#define STEP_S 100e-6
#define PERIOD_STEPS 197 /* about one period of 50.67 Hz at 10 kHz */
#define RUNS 5
#define STEPS_PER_RUN 2000000L

static double v_f64[PERIOD_STEPS][3];
static float v_f32[PERIOD_STEPS][3];
static q31_t v_q[PERIOD_STEPS][3];
static volatile double sink;

static double now_ns(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e9 + (double)ts.tv_nsec;
}

static void make_stimulus(void) {
    const double amp = 234.0 * sqrt(2.0 / 3.0);
    const double w = 2.0 * MATH_PI_F64 * 50.67;
    for (int n = 0; n < PERIOD_STEPS; n++) {
        const double th = w * ((double)n + 0.5) * STEP_S;
        for (int k = 0; k < 3; k++) {
            v_f64[n][k] = amp * cos(th - 2.0 * MATH_PI_F64 * (double)k / 3.0);
            v_f32[n][k] = (float)v_f64[n][k];
            v_q[n][k] = fp_pu_from_f64_q31(v_f64[n][k], DRIVE_BASE_VOLTAGE_V);
        }
    }
}

static double bench_q(const propeller_model *prop) {
    static induction_motor_q m;
    induction_motor_out_q out;
    double best = 1e30, acc = 0.0;
    for (int r = 0; r < RUNS; r++) {
        induction_motor_init_q(&m, &induction_motor_params_15kw_delta, prop, STEP_S);
        const double t0 = now_ns();
        for (long n = 0; n < STEPS_PER_RUN; n++) {
            const q31_t *v = v_q[n % PERIOD_STEPS];
            const induction_motor_in_q in = {v[0], v[1], v[2]};
            induction_motor_step_q(&m, &in, &out);
            acc += (double)out.i_a;
        }
        const double dt = (now_ns() - t0) / (double)STEPS_PER_RUN;
        best = (dt < best) ? dt : best;
    }
    sink = acc;
    return best;
}

static double bench_f32(const propeller_model *prop) {
    static induction_motor_f32 m;
    induction_motor_out_f32 out;
    double best = 1e30, acc = 0.0;
    for (int r = 0; r < RUNS; r++) {
        induction_motor_init_f32(&m, &induction_motor_params_15kw_delta, prop, STEP_S);
        const double t0 = now_ns();
        for (long n = 0; n < STEPS_PER_RUN; n++) {
            const float *v = v_f32[n % PERIOD_STEPS];
            const induction_motor_in_f32 in = {v[0], v[1], v[2]};
            induction_motor_step_f32(&m, &in, &out);
            acc += (double)out.i_a;
        }
        const double dt = (now_ns() - t0) / (double)STEPS_PER_RUN;
        best = (dt < best) ? dt : best;
    }
    sink = acc;
    return best;
}

static double bench_f64(const propeller_model *prop) {
    static induction_motor_f64 m;
    induction_motor_out_f64 out;
    double best = 1e30, acc = 0.0;
    for (int r = 0; r < RUNS; r++) {
        induction_motor_init_f64(&m, &induction_motor_params_15kw_delta, prop, STEP_S);
        const double t0 = now_ns();
        for (long n = 0; n < STEPS_PER_RUN; n++) {
            const double *v = v_f64[n % PERIOD_STEPS];
            const induction_motor_in_f64 in = {v[0], v[1], v[2]};
            induction_motor_step_f64(&m, &in, &out);
            acc += out.i_a;
        }
        const double dt = (now_ns() - t0) / (double)STEPS_PER_RUN;
        best = (dt < best) ? dt : best;
    }
    sink = acc;
    return best;
}

int main(void) {
    propeller_model prop;
    if (propeller_init(&prop, &propeller_params_default) != PROPELLER_OK) {
        fprintf(stderr, "bench_induction_motor: propeller_init failed\n");
        return 1;
    }
    make_stimulus();
    printf("induction motor step, best of %d runs of %ld steps (ns per step)\n", RUNS,
           STEPS_PER_RUN);
    printf("  fixed (_q):   %7.1f ns\n", bench_q(&prop));
    printf("  float (_f32): %7.1f ns\n", bench_f32(&prop));
    printf("  double (_f64):%7.1f ns\n", bench_f64(&prop));
    return 0;
}
