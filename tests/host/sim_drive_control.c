/*
 * Closed-loop check of the drive controller on the drive's actual machine:
 * both controller twins at 800 us against the double-precision induction
 * motor (src/models/drive/motor/induction_motor.h, 100 us, 15 kW set, propeller load and
 * inertia) fed by an ideal averaged inverter (no switching ripple, no LC
 * filter): the voltage vector m Vdc / 2 turning by the controller's phase
 * increment, averaged exactly over each motor step. The controller sees the
 * phase currents and the speed averaged over its frame, as the executive's
 * default fast-to-slow transfer gives them. Prints, per scenario, the
 * figures docs/drive_control.md quotes. Host only (libc, libm); ends with
 * the "N passed, N failed" line of a host test, where each scenario passes
 * when it reaches its command within 0.5 % and the integer twin counted no
 * saturation.
 *
 * Build: make host-benches (build/tools/sim_drive_control); make test runs it.
 */
#include <math.h>
#include <stdbool.h>
#include <stdio.h>

#include "fixedpoint/fixedpoint.h"
#include "math/umath.h"
#include "models/drive/control/drive_control.h"
#include "models/drive/drive_units.h"
#include "models/drive/motor/induction_motor.h"
#include "models/propeller/propeller.h"

#define W_1500 (1500.0 * MATH_PI_F64 / 30.0)
#define MOTOR_STEP 100e-6
#define STEPS_PER_FRAME 8u
#define PWM_STEPS_PER_MOTOR_STEP 50u

typedef struct {
    bool fixed;
    drive_control_q q;
    drive_control_f32 f;
} ctl_t;

/* What the controller asked for, in SI. */
typedef struct {
    double m, freq, i_dem, slip;
    uint32_t inc, flags;
} cmd_t;

static void ctl_step(ctl_t *c, double cmd, double w, const double i[3], double vdc, cmd_t *o) {
    if (c->fixed) {
        drive_control_in_q in = {
            fp_pu_from_f64_q31(cmd, DRIVE_BASE_SPEED_RADPS),
            fp_pu_from_f64_q31(w, DRIVE_BASE_SPEED_RADPS),
            fp_pu_from_f64_q31(i[0], DRIVE_BASE_CURRENT_A),
            fp_pu_from_f64_q31(i[1], DRIVE_BASE_CURRENT_A),
            fp_pu_from_f64_q31(i[2], DRIVE_BASE_CURRENT_A),
            fp_pu_from_f64_q31(vdc, DRIVE_BASE_VOLTAGE_V)};
        drive_control_out_q out;
        drive_control_step_q(&c->q, &in, &out);
        o->m = fp_to_f64_q15(out.m);
        o->freq = fp_pu_to_f64_q31(out.freq, DRIVE_BASE_FREQ_HZ);
        o->slip = fp_pu_to_f64_q31(out.slip, DRIVE_BASE_FREQ_HZ);
        o->i_dem = fp_pu_to_f64_q31(out.i_demand, DRIVE_BASE_CURRENT_A);
        o->inc = out.phase_inc;
        o->flags = out.flags;
    } else {
        drive_control_in_f32 in = {(float)cmd, (float)w, (float)i[0], (float)i[1], (float)i[2],
                                   (float)vdc};
        drive_control_out_f32 out;
        drive_control_step_f32(&c->f, &in, &out);
        o->m = (double)out.m;
        o->freq = (double)out.freq_hz;
        o->slip = (double)out.slip_hz;
        o->i_dem = (double)out.i_demand_a;
        o->inc = out.phase_inc;
        o->flags = out.flags;
    }
}

/* Figures of one run. */
typedef struct {
    double w_max, w_min, i_peak, psi_peak, m_peak, t_in_05, w_end, i_end, slip_end, m_end;
} run_t;

typedef struct {
    induction_motor_f64 motor;
    uint32_t phase;    /* inverter voltage angle, 2^32 per turn */
    cmd_t cmd;
    double i_avg[3], w_avg;
} plant_t;

/*
 * One controller frame: 8 motor steps at the held command. The mean of the
 * vector V e^(j theta) over a step in which theta advances by d is
 * V sinc(d / 2) e^(j theta_mid).
 */
static void plant_frame(plant_t *p, double vdc, run_t *r) {
    double amp = p->cmd.m * vdc * 0.5;
    double d = (double)(int32_t)p->cmd.inc * PWM_STEPS_PER_MOTOR_STEP * (2.0 * MATH_PI_F64 / 4294967296.0);
    double sinc = (fabs(d) > 1e-12) ? sin(0.5 * d) / (0.5 * d) : 1.0;
    double acc[3] = {0.0, 0.0, 0.0};
    double w_acc = 0.0;
    for (unsigned k = 0u; k < STEPS_PER_FRAME; k++) {
        double th = (double)p->phase * (2.0 * MATH_PI_F64 / 4294967296.0) + 0.5 * d;
        p->phase += p->cmd.inc * PWM_STEPS_PER_MOTOR_STEP; /* modulo 2^32, like the PWM */
        induction_motor_in_f64 in = {amp * sinc * cos(th), amp * sinc * cos(th - 2.0 * MATH_PI_F64 / 3.0),
                                     amp * sinc * cos(th + 2.0 * MATH_PI_F64 / 3.0)};
        induction_motor_out_f64 out;
        induction_motor_step_f64(&p->motor, &in, &out);
        acc[0] += out.i_a;
        acc[1] += out.i_b;
        acc[2] += out.i_c;
        w_acc += out.w_radps;
        induction_motor_obs o;
        induction_motor_observe_f64(&p->motor, &o);
        double imag = hypot(o.i_s[0], o.i_s[1]);
        double psi = hypot(o.psi_r[0], o.psi_r[1]);
        r->i_peak = fmax(r->i_peak, imag);
        r->psi_peak = fmax(r->psi_peak, psi);
    }
    for (unsigned k = 0u; k < 3u; k++) {
        p->i_avg[k] = acc[k] / STEPS_PER_FRAME;
    }
    p->w_avg = w_acc / STEPS_PER_FRAME;
}

/* Runs the command for t seconds; figures over the run. */
static void run(ctl_t *c, plant_t *p, double cmd, double vdc, double t, run_t *r) {
    unsigned n = (unsigned)(t / 800e-6 + 0.5);
    r->w_max = -1e9;
    r->w_min = 1e9;
    r->i_peak = 0.0;
    r->psi_peak = 0.0;
    r->m_peak = 0.0;
    r->t_in_05 = 0.0;
    for (unsigned k = 0u; k < n; k++) {
        ctl_step(c, cmd, p->w_avg, p->i_avg, vdc, &p->cmd);
        r->m_peak = fmax(r->m_peak, p->cmd.m);
        plant_frame(p, vdc, r);
        double w = p->motor.w;
        r->w_max = fmax(r->w_max, w);
        r->w_min = fmin(r->w_min, w);
        double band = (fabs(cmd) > 1.0) ? 0.005 * fabs(cmd) : 0.005 * W_1500;
        if (fabs(w - cmd) > band) {
            r->t_in_05 = (double)(k + 1u) * 800e-6;
        }
    }
    r->w_end = p->motor.w;
    r->i_end = hypot(p->i_avg[0], (p->i_avg[1] - p->i_avg[2]) / sqrt(3.0));
    r->slip_end = p->cmd.slip;
    r->m_end = p->cmd.m;
}

static unsigned passed;
static unsigned failed;

static void report(const char *name, const ctl_t *c, double cmd, double from, const run_t *r,
                   bool idle_ok) {
    double span = fabs(cmd - from);
    double over = (cmd >= from) ? (r->w_max - cmd) : (cmd - r->w_min);
    bool ok = idle_ok ? (fabs(r->w_end) < 6.0) : (fabs(r->w_end - cmd) <= 0.005 * fabs(cmd));
    uint32_t sat = c->fixed ? c->q.sat_count : 0u;
    ok = ok && (sat == 0u);
    printf("%-6s %-28s within 0.5%% after %6.3f s, overshoot %5.2f %% of the step, "
           "peak |i| %5.1f A, peak psi_r %5.3f Wb, peak m %5.3f; end: %7.2f rad/s, "
           "|i| %5.1f A, slip %6.3f Hz, m %5.3f, sat %u  %s\n",
           c->fixed ? "fixed" : "float", name, r->t_in_05, (span > 0.0) ? over / span * 100.0 : 0.0,
           r->i_peak, r->psi_peak, r->m_peak, r->w_end, r->i_end, r->slip_end, r->m_end, sat,
           ok ? "ok" : "FAIL");
    if (ok) {
        passed++;
    } else {
        failed++;
    }
}

static void scenario(bool fixed) {
    propeller_model prop;
    (void)propeller_init(&prop, &propeller_params_default);
    ctl_t c;
    c.fixed = fixed;
    if (fixed) {
        (void)drive_control_init_q(&c.q, &drive_control_params_default);
    } else {
        (void)drive_control_init_f32(&c.f, &drive_control_params_default);
    }
    plant_t p = {0};
    (void)induction_motor_init_f64(&p.motor, &induction_motor_params_15kw_delta, &prop, MOTOR_STEP);
    run_t r;
    run(&c, &p, W_1500, 432.0, 2.0, &r);
    report("start 0->1500 rpm, 432 V", &c, W_1500, 0.0, &r, false);
    run(&c, &p, 1000.0 * MATH_PI_F64 / 30.0, 432.0, 1.5, &r);
    report("step 1500->1000 rpm", &c, 1000.0 * MATH_PI_F64 / 30.0, W_1500, &r, false);
    run(&c, &p, W_1500, 432.0, 1.5, &r);
    report("step 1000->1500 rpm", &c, W_1500, 1000.0 * MATH_PI_F64 / 30.0, &r, false);
    run(&c, &p, W_1500, 605.0, 1.0, &r);
    report("bus 432->605 V at 1500 rpm", &c, W_1500, W_1500, &r, false);
    run(&c, &p, -W_1500, 605.0, 3.0, &r);
    report("reverse 1500->-1500 rpm", &c, -W_1500, W_1500, &r, false);
    run(&c, &p, 0.0, 605.0, 2.5, &r);
    report("stop -1500->0 rpm (idle)", &c, 0.0, -W_1500, &r, true);
}

/*
 * The current loop alone on the machine with its shaft locked at the speed
 * of stator frequency f and slip f_sl, without feedforward (so the PI does
 * all the work): the demand steps 38 -> 44 A after 1 s. Returns the
 * overshoot in % of the step and the time to stay within 2 % of the step.
 * The controller is told a motoring slip whatever the machine's, so that its
 * generating hold stays off and the bare PI on a generating machine can be
 * seen. The bus is at 605 V so that 70 Hz stays within m <= 1.
 */
static void current_scan(double f, double f_sl, double kp, double ki, double *over,
                         double *t_settle) {
    drive_control_params cp = drive_control_params_default;
    cp.ff_gain = 0.0;
    cp.kp_current_v_per_a = kp;
    cp.ki_current_v_per_as = ki;
    drive_control_f32 c;
    (void)drive_control_init_f32(&c, &cp);
    plant_t p = {0};
    (void)induction_motor_init_f64(&p.motor, &induction_motor_params_15kw_delta, NULL,
                                   MOTOR_STEP);
    induction_motor_set_speed_f64(&p.motor, (f - f_sl) * 2.0 * MATH_PI_F64 / 2.0, true);
    run_t r = {0};
    double i_max = 0.0;
    *t_settle = 0.0;
    for (unsigned k = 0u; k < 2500u; k++) {
        double i_dem = (k < 1250u) ? 38.0 : 44.0;
        drive_control_in_f32 in = {0.0f, 0.0f, (float)p.i_avg[0], (float)p.i_avg[1],
                                   (float)p.i_avg[2], 605.0f};
        drive_control_out_f32 out;
        drive_control_current_step_f32(&c, (float)i_dem, (float)f, (float)fabs(f_sl), &in, &out);
        p.cmd.m = (double)out.m;
        p.cmd.inc = out.phase_inc;
        plant_frame(&p, 605.0, &r);
        double mag = hypot(p.i_avg[0], (p.i_avg[1] - p.i_avg[2]) / sqrt(3.0));
        if (k >= 1250u) {
            i_max = fmax(i_max, mag);
            if (fabs(mag - 44.0) > 0.02 * 6.0) {
                *t_settle = (double)(k + 1u - 1250u) * 800e-6;
            }
        }
    }
    *over = (i_max - 44.0) / 6.0 * 100.0;
}

static void scan(void) {
    static const double freqs[] = {0.5, 1.5, 5.0, 15.0, 35.0, 50.7, 70.0};
    static const double gains[][2] = {
        {0.3, 30.0}, {0.6, 30.0}, {1.2, 30.0}, {0.3, 60.0}, {0.3, 120.0}};
    for (unsigned g = 0u; g < 5u; g++) {
        printf("current PI Kp %.1f V/A, Ki %.0f V/(A s), no feedforward, 38 -> 44 A, "
               "slip +0.73 Hz:\n ",
               gains[g][0], gains[g][1]);
        for (unsigned k = 0u; k < sizeof freqs / sizeof freqs[0]; k++) {
            double over;
            double ts;
            current_scan(freqs[k], 0.73, gains[g][0], gains[g][1], &over, &ts);
            printf(" %4.1f Hz: %5.1f %% %5.3f s |", freqs[k], over, ts);
        }
        printf("\n");
    }
    printf("generating machine (slip -0.73 Hz), Kp 0.3, Ki 30, generating hold off:\n ");
    for (unsigned k = 0u; k < sizeof freqs / sizeof freqs[0]; k++) {
        double over;
        double ts;
        current_scan(freqs[k], -0.73, 0.3, 30.0, &over, &ts);
        printf(" %4.1f Hz: %6.0f %% %5.3f s |", freqs[k], over, ts);
    }
    printf("\n");
}

int main(void) {
    scan();
    scenario(true);
    scenario(false);
    printf("%u passed, %u failed\n", passed, failed);
    return (failed == 0u) ? 0 : 1;
}
