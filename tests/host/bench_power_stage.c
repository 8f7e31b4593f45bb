/*
 * Host micro-benchmark of the power stage: nanoseconds per 2 us fast step
 * (PWM, then the inverter, DC link and filter) for the fixed and the float
 * twins, each part alone and the two chained as the executive will chain
 * them, and per 100 us frame of the averaged inverter (four substeps).
 * Host-only: it uses libc's clock_gettime and printf.
 *
 * Each figure is the best of several repetitions of a run long enough to
 * dwarf the clock's resolution; the drive runs at m = 0.8, 50 Hz with a
 * constant load current, from a bus precharged to 600 V.
 */
#include <stdint.h>
#include <stdio.h>
#include <time.h>

#include "fixedpoint/wavetable.h"
#include "models/drive/inverter/inverter_avg.h"
#include "models/drive/inverter/power_stage.h"
#include "models/drive/pwm/pwm.h"

#define STEPS 2000000u
#define FRAMES 100000u
#define REPEATS 5u

static double now_ns(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e9 + (double)ts.tv_nsec;
}

/* The parts under test, one instance each. */
static pwm_q pq;
static power_stage_q sq;
static power_stage_in_q iq;
static pwm_out_q oq;
static pwm_f32 pf;
static power_stage_f32 sf;
static power_stage_in_f32 inf;
static pwm_out_f32 of;
static inverter_avg_q aq;
static inverter_avg_f32 af;

static void setup(void) {
    const uint32_t inc = wt_phase_inc_q16(50 << 16, 2000u);
    pwm_init_q(&pq, &pwm_params_default, 2000u);
    pwm_command_inc_q(&pq, Q15_CONST(0.8), inc);
    power_stage_init_q(&sq, &power_stage_params_default, 2000u, 600.0);
    power_stage_battery_q(&sq, 1.63, 1.63 * 603.0, &iq.battery);
    iq.i_motor[0] = Q15_CONST(20.0 / 256.0);
    iq.i_motor[1] = Q15_CONST(-10.0 / 256.0);
    iq.i_motor[2] = Q15_CONST(-10.0 / 256.0);

    pwm_init_f32(&pf, &pwm_params_default, 2000u);
    pwm_command_inc_f32(&pf, 0.8f, inc);
    power_stage_init_f32(&sf, &power_stage_params_default, 2000u, 600.0);
    power_stage_battery_f32(&sf, 1.63, 1.63 * 603.0, &inf.battery);
    inf.i_motor_a[0] = 20.0f;
    inf.i_motor_a[1] = -10.0f;
    inf.i_motor_a[2] = -10.0f;

    inverter_avg_init_q(&aq, &pwm_params_default, &power_stage_params_default, 100000u, 4u, 600.0);
    pwm_command_inc_q(&aq.mod, Q15_CONST(0.8), wt_phase_inc_q16(50 << 16, 25000u));
    inverter_avg_init_f32(&af, &pwm_params_default, &power_stage_params_default, 100000u, 4u,
                          600.0);
    pwm_command_inc_f32(&af.mod, 0.8f, wt_phase_inc_q16(50 << 16, 25000u));
}

typedef void (*bench_fn)(uint32_t n);

static void run_pwm_q(uint32_t n) {
    for (uint32_t k = 0; k < n; k++) {
        pwm_step_q(&pq, &oq);
    }
}

static void run_stage_q(uint32_t n) {
    for (uint32_t k = 0; k < n; k++) {
        power_stage_step_q(&sq, &iq);
    }
}

static void run_tick_q(uint32_t n) {
    for (uint32_t k = 0; k < n; k++) {
        pwm_step_q(&pq, &oq);
        iq.duty[0] = oq.duty[0];
        iq.duty[1] = oq.duty[1];
        iq.duty[2] = oq.duty[2];
        power_stage_step_q(&sq, &iq);
    }
}

static void run_pwm_f(uint32_t n) {
    for (uint32_t k = 0; k < n; k++) {
        pwm_step_f32(&pf, &of);
    }
}

static void run_stage_f(uint32_t n) {
    for (uint32_t k = 0; k < n; k++) {
        power_stage_step_f32(&sf, &inf);
    }
}

static void run_tick_f(uint32_t n) {
    for (uint32_t k = 0; k < n; k++) {
        pwm_step_f32(&pf, &of);
        inf.duty[0] = of.duty[0];
        inf.duty[1] = of.duty[1];
        inf.duty[2] = of.duty[2];
        power_stage_step_f32(&sf, &inf);
    }
}

static void run_avg_q(uint32_t n) {
    for (uint32_t k = 0; k < n; k++) {
        inverter_avg_step_q(&aq, &iq);
    }
}

static void run_avg_f(uint32_t n) {
    for (uint32_t k = 0; k < n; k++) {
        inverter_avg_step_f32(&af, &inf);
    }
}

/* Best of REPEATS runs of n calls, in ns per call. */
static double bench(bench_fn fn, uint32_t n) {
    double best = 1e300;
    for (uint32_t r = 0; r < REPEATS; r++) {
        double t0 = now_ns();
        fn(n);
        double t = (now_ns() - t0) / (double)n;
        best = (t < best) ? t : best;
    }
    return best;
}

int main(void) {
    setup();
    printf("power stage, host ns per call (best of %u runs of %u steps)\n", REPEATS, STEPS);
    printf("  fixed  pwm_step_q            %7.2f ns\n", bench(run_pwm_q, STEPS));
    printf("  fixed  power_stage_step_q    %7.2f ns\n", bench(run_stage_q, STEPS));
    printf("  fixed  fast tick (both)      %7.2f ns\n", bench(run_tick_q, STEPS));
    printf("  float  pwm_step_f32          %7.2f ns\n", bench(run_pwm_f, STEPS));
    printf("  float  power_stage_step_f32  %7.2f ns\n", bench(run_stage_f, STEPS));
    printf("  float  fast tick (both)      %7.2f ns\n", bench(run_tick_f, STEPS));
    printf("  fixed  averaged, 100 us frame (4 substeps)  %7.2f ns\n", bench(run_avg_q, FRAMES));
    printf("  float  averaged, 100 us frame (4 substeps)  %7.2f ns\n", bench(run_avg_f, FRAMES));
    /* Uses the states, so that nothing above is optimised away; all should be 0. */
    printf("  saturation counts: %u %u %u %u\n", (unsigned)sq.sat_count, (unsigned)sf.sat_count,
           (unsigned)aq.stage.sat_count, (unsigned)af.stage.sat_count);
    return 0;
}
