/*
 * Host micro-benchmark of the drive controller: nanoseconds per controller
 * frame for the integer and the float twin, full frame (speed loop, current
 * demand, current loop) and current loop alone. The inputs are recorded
 * first from a closed loop on a simple shaft (torque proportional to slip,
 * propeller load) so that the timed calls see the branches of a real run;
 * the timing loop then replays them.
 *
 * Build: make host-benches (build/tools/bench_drive_control).
 */
#include <math.h>
#include <stdio.h>
#include <time.h>

#include "fixedpoint/fixedpoint.h"
#include "math/umath.h"
#include "models/drive/control/drive_control.h"
#include "models/drive/drive_units.h"

#define N_REC 4096u  /* recorded frames (3.3 s: start, run, reversal) */
#define N_REP 200u   /* replays of the record per measurement */

static drive_control_in_q rec_q[N_REC];
static drive_control_in_f32 rec_f[N_REC];

static double now_ns(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e9 + (double)ts.tv_nsec;
}

/* Records inputs from a float-twin closed loop on a shaft with J = 0.113 kg m^2. */
static void record(void) {
    drive_control_f32 c;
    drive_control_design d;
    drive_control_out_f32 o = {0};
    (void)drive_control_init_f32(&c, &drive_control_params_default);
    (void)drive_control_design_f64(&d, &drive_control_params_default);
    double w = 0.0;
    double th = 0.0;
    for (unsigned k = 0u; k < N_REC; k++) {
        double cmd = (k < 2000u) ? 157.08 : -120.0;
        double amp = (double)o.i_demand_a * 0.97;
        drive_control_in_f32 in = {(float)cmd, (float)w, (float)(amp * cos(th)),
                                   (float)(amp * cos(th - 2.0943951023931953)),
                                   (float)(amp * cos(th + 2.0943951023931953)), 432.0f};
        rec_f[k] = in;
        rec_q[k].speed_cmd = fp_pu_from_f64_q31(cmd, DRIVE_BASE_SPEED_RADPS);
        rec_q[k].w = fp_pu_from_f64_q31(w, DRIVE_BASE_SPEED_RADPS);
        rec_q[k].i_a = fp_pu_from_f64_q31((double)in.i_a, DRIVE_BASE_CURRENT_A);
        rec_q[k].i_b = fp_pu_from_f64_q31((double)in.i_b, DRIVE_BASE_CURRENT_A);
        rec_q[k].i_c = fp_pu_from_f64_q31((double)in.i_c, DRIVE_BASE_CURRENT_A);
        rec_q[k].vdc = fp_pu_from_f64_q31(432.0, DRIVE_BASE_VOLTAGE_V);
        drive_control_step_f32(&c, &in, &o);
        double torque = d.kt_nm_per_hz * ((double)o.freq_hz - d.fr_hz_per_radps * w);
        w += 800e-6 * (torque - 0.0023681 * w * fabs(w)) / 0.113;
        th += MATH_TWO_PI_F64 * (double)o.freq_hz * 800e-6;
    }
}

static double bench_q(int current_only, unsigned *sink) {
    drive_control_q c;
    drive_control_out_q o;
    (void)drive_control_init_q(&c, &drive_control_params_default);
    q31_t i_dem = fp_pu_from_f64_q31(40.0, DRIVE_BASE_CURRENT_A);
    q31_t f = fp_pu_from_f64_q31(50.0, DRIVE_BASE_FREQ_HZ);
    q31_t s = fp_pu_from_f64_q31(0.7, DRIVE_BASE_FREQ_HZ);
    double t0 = now_ns();
    for (unsigned r = 0u; r < N_REP; r++) {
        for (unsigned k = 0u; k < N_REC; k++) {
            if (current_only) {
                drive_control_current_step_q(&c, i_dem, f, s, &rec_q[k], &o);
            } else {
                drive_control_step_q(&c, &rec_q[k], &o);
            }
            *sink += (unsigned)o.m + o.phase_inc;
        }
    }
    return (now_ns() - t0) / ((double)N_REP * (double)N_REC);
}

static double bench_f(int current_only, unsigned *sink) {
    drive_control_f32 c;
    drive_control_out_f32 o;
    (void)drive_control_init_f32(&c, &drive_control_params_default);
    double t0 = now_ns();
    for (unsigned r = 0u; r < N_REP; r++) {
        for (unsigned k = 0u; k < N_REC; k++) {
            if (current_only) {
                drive_control_current_step_f32(&c, 40.0f, 50.0f, 0.7f, &rec_f[k], &o);
            } else {
                drive_control_step_f32(&c, &rec_f[k], &o);
            }
            *sink += (unsigned)(o.m * 1000.0f) + o.phase_inc;
        }
    }
    return (now_ns() - t0) / ((double)N_REP * (double)N_REC);
}

int main(void) {
    unsigned sink = 0u;
    record();
    /* Best of five runs of each, to keep scheduling noise out. */
    double best[4] = {1e30, 1e30, 1e30, 1e30};
    for (unsigned run = 0u; run < 5u; run++) {
        double t[4] = {bench_q(0, &sink), bench_f(0, &sink), bench_q(1, &sink),
                       bench_f(1, &sink)};
        for (unsigned i = 0u; i < 4u; i++) {
            best[i] = (t[i] < best[i]) ? t[i] : best[i];
        }
    }
    printf("drive_control_step_q          %7.1f ns per 800 us frame\n", best[0]);
    printf("drive_control_step_f32        %7.1f ns per 800 us frame\n", best[1]);
    printf("drive_control_current_step_q  %7.1f ns (current loop alone)\n", best[2]);
    printf("drive_control_current_step_f32 %6.1f ns (current loop alone)\n", best[3]);
    printf("(%u frames x %u replays each, best of 5; checksum %u)\n", N_REC, N_REP, sink & 0xffu);
    return 0;
}
