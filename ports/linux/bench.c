/*
 * bench: the accuracy/speed-up study of the multi-rate executive, for one
 * numeric build, in one run on one scenario.
 *
 *   bench SCENARIO.scn [DURATION_S [LOW_SPEED.scn]]
 *
 * Runs the scenario single-rate (every integrating segment at 2 us, the
 * reference), then multi-rate with every coupling, and the averaged
 * inverter, and with the motor task's frame from 20 us to 800 us;
 * measures process CPU time, real-time factors and the errors against the
 * reference (RMS over the run of the difference, relative to the RMS of
 * the reference signal); times each segment's step on its own. Prints a
 * table on stderr, with the line of targets (docs/multirate.md, "Speed")
 * met or not, and one JSON object on stdout.
 *
 * The averaged layer, and the single-rate run of the default (sub-step)
 * switching model, are also compared with the single-rate run of the
 * switching-event inverter (edges located inside the 2 us step by the
 * general modulator), the reference for what they model. The averaged
 * layer's real-time factor is the best of five runs (one run takes well
 * under a millisecond).
 *
 * The speed-up is the single-rate run's CPU time (best of two) over the
 * multi-rate run's (best of five), both in this one program: the same
 * compiler, flags and square roots (uuv_config.h's UUV_HW_SQRT_*, printed
 * with the figure); for the exact fast path (the firmware's bits) and, in
 * the float build, for the exact leaps (leap.h), whose figure the target
 * line judges.
 *
 * With a third argument, the switching-error study follows (study()): the
 * sampled and sub-step modulators against the single-rate switching-event
 * reference at fast steps of 1, 2, 4 and 5 us on SCENARIO and on the
 * low-speed scenario, the fundamental of v_an, and the motor coupling's
 * frame-rate artefact against the single-rate run.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "executive.h"
#include "batch_lanes.h"
#include "leap.h"
#include "fixedpoint/wavetable.h"
#include "models/drive/pwm/pwm_rt.h"
#include "uuv_config.h"

#define MAX_RECORDS 4096
#define MISSION_PATH "scenarios/default.scn" /* the default mission (make run), 240 s */
#define BENCH_PI 3.14159265358979323846

typedef struct {
    exec_frame rec[MAX_RECORDS];
    size_t n;
    double cpu_s;
    exec_state state;
} run_data;

/* Process CPU time [s]: what a run costs, whatever else shares the core. */
static double now_s(void) {
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static scenario scn;
static exec ex;
static bool run_leaps; /* run() takes the exact leaps (--fast-path leap, leap.h) */
static leap_stats run_leap_stats;

static int run(const exec_config *cfg, run_data *out) {
    if (exec_init(&ex, cfg, &scn) != EXEC_OK) {
        fprintf(stderr, "bench: the executive refused the configuration\n");
        return -1;
    }
    if (run_leaps && !leap_attach(&ex)) {
        fprintf(stderr, "bench: no leaps in this build, or no memory for their tables\n");
        return -1;
    }
    out->n = 0;
    (void)exec_report_take(&ex, &out->rec[out->n++]);
    double t0 = now_s();
    while (ex.state == EXEC_RUNNING) {
        (void)exec_desk_run(&ex, UINT32_MAX);
        if (ex.report_ready && out->n < MAX_RECORDS) {
            (void)exec_report_take(&ex, &out->rec[out->n++]);
        }
    }
    out->cpu_s = now_s() - t0;
    out->state = ex.state;
    run_leap_stats = leap_stats_of(&ex);
    leap_detach(&ex);
    return 0;
}

/* RMS of (a - b) relative to the RMS of b, in per cent, for one field. */
static double rel_rms(const run_data *a, const run_data *b, size_t offset) {
    double se = 0.0;
    double sr = 0.0;
    size_t n = (a->n < b->n) ? a->n : b->n;
    for (size_t i = 0; i < n; i++) {
        double x = *(const double *)(const void *)((const char *)&a->rec[i] + offset);
        double y = *(const double *)(const void *)((const char *)&b->rec[i] + offset);
        se += (x - y) * (x - y);
        sr += y * y;
    }
    return sr > 0.0 ? 100.0 * sqrt(se / sr) : 0.0;
}

/* Horizontal position error relative to the RMS distance travelled, per cent. */
static double pos_rms(const run_data *a, const run_data *b) {
    double se = 0.0;
    double sr = 0.0;
    size_t n = (a->n < b->n) ? a->n : b->n;
    for (size_t i = 0; i < n; i++) {
        double dx = a->rec[i].x[VESSEL_X_M] - b->rec[i].x[VESSEL_X_M];
        double dy = a->rec[i].x[VESSEL_Y_M] - b->rec[i].x[VESSEL_Y_M];
        se += dx * dx + dy * dy;
        sr += b->rec[i].x[VESSEL_X_M] * b->rec[i].x[VESSEL_X_M] +
              b->rec[i].x[VESSEL_Y_M] * b->rec[i].x[VESSEL_Y_M];
    }
    return sr > 0.0 ? 100.0 * sqrt(se / sr) : 0.0;
}

#define FIELD_X(i) (offsetof(exec_frame, x) + (size_t)(i) * sizeof(double))

typedef struct {
    double shaft, current, surge, position;
} errors;

/* How the bench reports a target: met or not. */
static const char *met(bool ok) {
    return ok ? "met" : "not met";
}

static errors compare(const run_data *a, const run_data *ref) {
    errors e;
    e.shaft = rel_rms(a, ref, FIELD_X(VESSEL_N_RPM));
    e.current = rel_rms(a, ref, offsetof(exec_frame, i_rms_a));
    e.surge = rel_rms(a, ref, FIELD_X(VESSEL_U_MPS));
    e.position = pos_rms(a, ref);
    return e;
}

/*
 * Per-step cost of each segment, timed in isolation on a running plant
 * [ns]: the fast step as a tick (drive_fast_tick) and in the desk's runs
 * (ns[4]), the motor, the controller, the slow segment.
 */
static void segment_costs(const exec_config *base, double ns[5]) {
    exec_config cfg = *base;
    cfg.duration_s = 10.0;
    exec_init(&ex, &cfg, &scn);
    /* Bring the drive to a running state first. */
    for (int i = 0; i < 250000 && ex.state == EXEC_RUNNING; i++) {
        exec_desk_step(&ex);
    }
    /*
     * The fast step, as ticks and in the desk's runs (a frame's steps less
     * one): frames of it on the running drive, each from the modulator's
     * state at the frame's start, so that the references stay those the
     * motor task set (without it they would ramp on past their range).
     */
    static drive_segment d;
    const pwm_rt rt0 = ex.drive.rt;
    const uint32_t run_n = (cfg.fast_per_medium > 1u) ? cfg.fast_per_medium - 1u : 1u;
    const int n_frames = 2000000 / (int)run_n;
    const double n_fast = (double)n_frames * run_n;
    d = ex.drive;
    double t0 = now_s();
    for (int i = 0; i < n_frames; i++) {
        d.rt = rt0;
        for (uint32_t k = 0u; k < run_n; k++) {
            drive_fast_tick(&d);
        }
    }
    ns[0] = 1e9 * (now_s() - t0) / n_fast;
    d = ex.drive;
    t0 = now_s();
    for (int i = 0; i < n_frames; i++) {
        d.rt = rt0;
        drive_fast_run(&d, run_n);
    }
    ns[4] = 1e9 * (now_s() - t0) / n_fast;
    d = ex.drive;
    const int n_med = 100000;
    t0 = now_s();
    for (int i = 0; i < n_med; i++) {
        drive_medium_task(&d, false, false);
    }
    ns[1] = 1e9 * (now_s() - t0) / n_med;
    d = ex.drive;
    const int n_ctl = 20000;
    t0 = now_s();
    for (int i = 0; i < n_ctl; i++) {
        drive_control_task(&d);
    }
    ns[2] = 1e9 * (now_s() - t0) / n_ctl;
    static vessel_model v;
    v = ex.vessel;
    double x[VESSEL_NSTATES];
    memcpy(x, ex.x, sizeof x);
    battery b = ex.bat;
    battery_frame_meas bm = {-5.0, 25.0, -3000.0};
    const int n_slow = 20000;
    t0 = now_s();
    for (int i = 0; i < n_slow; i++) {
        (void)vessel_step(&v, x, &ex.cmd);
        battery_step_f64(&b, &bm);
        (void)battery_companion_f64(&b);
    }
    ns[3] = 1e9 * (now_s() - t0) / n_slow;
}

/*
 * The exact leaps on the default mission (float build): the real-time
 * factor (best of three leap runs, interleaved with two exact ones) and the
 * largest RMS deviation of a telemetry column from the exact run's,
 * relative to that column's RMS. The fixed build has none (null).
 */
static int leap_mission(const exec_config *base) {
    static run_data exact, leap;
    if (!leap_available()) {
        fprintf(stderr, "  exact leaps: not in the %s build\n", UUV_NUMERIC_NAME);
        printf(", \"rtf_leap\": null, \"leap_dev_rel\": null");
        return 0;
    }
    exec_config c = *base;
    c.duration_s = 0.0;
    double cpu_exact = 1e300;
    double cpu_leap = 1e300;
    for (int k = 0; k < 5; k++) {
        run_leaps = (k % 2 == 0);
        run_data *r = run_leaps ? &leap : &exact;
        if (run(&c, r) != 0) {
            run_leaps = false;
            return -1;
        }
        double *best = run_leaps ? &cpu_leap : &cpu_exact;
        *best = (r->cpu_s < *best) ? r->cpu_s : *best;
    }
    run_leaps = false;
    const leap_stats st = run_leap_stats;
    double dev = 0.0;
    const char *worst = "none";
    static const char *const extra[] = {"te_nm", "i_rms_a", "v_dc_v", "i_batt_a", "soc",
                                        "m_index", "f_hz"};
    for (size_t i = 0; i < VESSEL_NSTATES + EXEC_NCMD + 7u; i++) {
        const size_t off = offsetof(exec_frame, x) + i * sizeof(double);
        const double d = 0.01 * rel_rms(&leap, &exact, off);
        if (d > dev) {
            dev = d;
            worst = (i < VESSEL_NSTATES)               ? vessel_state_names[i]
                    : (i < VESSEL_NSTATES + EXEC_NCMD) ? exec_command_names[i - VESSEL_NSTATES]
                                                       : extra[i - VESSEL_NSTATES - EXEC_NCMD];
        }
    }
    const double sim = leap.rec[leap.n - 1].t_s;
    fprintf(stderr, "  exact leaps on %s (%.0f s): real-time factor %.0f against %.0f exact "
                    "(x%.2f, CPU time, best of 3 and 2); largest deviation %.2g of its RMS "
                    "(%s; target <= 1e-5: %s); %.1f steps per leap, %.1f %% of the steps in "
                    "leaps\n",
            MISSION_PATH, sim, sim / cpu_leap, sim / cpu_exact, cpu_exact / cpu_leap, dev, worst,
            met(dev <= 1e-5), (double)st.leap_steps / (double)(st.leaps > 0u ? st.leaps : 1u),
            100.0 * (double)st.leap_steps / (sim / (1e-9 * (double)c.fast_ns)));
    printf(", \"rtf_leap\": %.6g, \"rtf_exact_mission\": %.6g, \"leap_dev_rel\": %.6g",
           sim / cpu_leap, sim / cpu_exact, dev);
    return 0;
}

/*
 * Batched runs (uuvsim batch, batch_lanes.h) on the default mission:
 * a vector's runs (batch_lanes; 16 without lanes) of its first tenth
 * (24 s) side by side, against one
 * such run alone; in whole missions (240 s) per second of CPU time.
 */
#define BATCH_BENCH_RUNS 64

static int batch_mission(const exec_config *base) {
    static exec *x[BATCH_BENCH_RUNS];
    static uint32_t most[BATCH_BENCH_RUNS];
    static run_data one;
    /* A vector's runs; 16 where the build has no lanes (its runs step one after another). */
    const size_t lanes = (batch_lanes > 1u) ? batch_lanes : 16u;
    const size_t n = (lanes < BATCH_BENCH_RUNS) ? lanes : BATCH_BENCH_RUNS;
    exec_config c = *base;
    c.duration_s = 0.1 * scn.duration_s;
    if (run(&c, &one) != 0) {
        return -1;
    }
    for (size_t i = 0; i < n; i++) {
        x[i] = (x[i] != NULL) ? x[i] : malloc(sizeof *x[i]);
        if (x[i] == NULL || exec_init(x[i], &c, &scn) != EXEC_OK) {
            fprintf(stderr, "bench: the batch's runs could not start\n");
            return -1;
        }
        most[i] = UINT32_MAX;
        batch_lanes_attach(x[i]);
    }
    const double t0 = now_s();
    for (bool running = true; running;) {
        batch_step_all(x, most, n);
        running = false;
        for (size_t i = 0; i < n; i++) {
            exec_frame f;
            (void)exec_report_take(x[i], &f);
            running = running || x[i]->state == EXEC_RUNNING;
        }
    }
    const double cpu = now_s() - t0;
    const double per_s = (double)n * 0.1 / cpu;
    const double one_per_s = 0.1 / one.cpu_s;
    fprintf(stderr, "  batched runs (%zu runs, lanes %s): %.2f default missions per second of CPU "
                    "time against %.2f one at a time (x%.2f; target >= 2.5: %s)\n",
            n, batch_lanes_isa, per_s, one_per_s, per_s / one_per_s, met(per_s >= 2.5));
    printf(", \"batch_runs_per_s\": %.6g, \"batch_runs\": %zu, \"single_runs_per_s\": %.6g",
           per_s, n, one_per_s);
    return 0;
}

static const char *const down_names[] = {"zoh", "foh", "deriv", "stagger"};
static const char *const up_names[] = {"avg", "filter", "sample"};

static int load(const char *path) {
    FILE *f = fopen(path, "rb");
    if (f == NULL) {
        fprintf(stderr, "bench: %s: cannot open\n", path);
        return -1;
    }
    static char buf[1 << 16];
    size_t n = fread(buf, 1, sizeof buf, f);
    fclose(f);
    scenario_error err;
    if (!scenario_parse(&scn, buf, n, &err)) {
        fprintf(stderr, "bench: %s:%u: %s: %s\n", path, err.line, err.field, err.message);
        return -1;
    }
    return 0;
}

/* ---- The switching-error study (docs/multirate.md, "Switching error") ---- */

/*
 * The fast-step window of a run: the phase-a capacitor voltage and the
 * motor-side current the filter sees (the fast companion's, the trace's
 * i_motor) after each of n fast steps from step k0 on (k0 a whole number of
 * motor frames).
 */
static int run_window(const exec_config *cfg, uint64_t k0, uint32_t n, double *vc, double *ia) {
    if (exec_init(&ex, cfg, &scn) != EXEC_OK) {
        fprintf(stderr, "bench: the executive refused the configuration\n");
        return -1;
    }
    uint32_t i = 0u;
    uint64_t last = UINT64_MAX;
    while (ex.state == EXEC_RUNNING && i < n) {
        uint64_t k = exec_fast_steps(&ex);
        uint64_t ahead = (k < k0) ? k0 - k : 1u;
        (void)exec_desk_run(&ex, (ahead < UINT32_MAX) ? (uint32_t)ahead : UINT32_MAX);
        k = exec_fast_steps(&ex);
        if (k > k0 && k != last) {
            last = k;
            drive_trace_row row;
            drive_trace(&ex.drive, &row);
            vc[i] = row.v_cap[0];
            ia[i] = row.i_motor[0];
            i++;
        }
        if (ex.report_ready) {
            exec_frame f;
            (void)exec_report_take(&ex, &f);
        }
    }
    return (i == n) ? 0 : -1;
}

/* RMS [units of x] of x's content from f_lo to f_hi (single-bin DFTs over the window). */
static double band_rms(const double *x, uint32_t n, double dt, double f_lo, double f_hi) {
    const double df = 1.0 / ((double)n * dt);
    double sum = 0.0;
    for (long b = (long)ceil(f_lo / df); (double)b * df <= f_hi; b++) {
        const double w = -2.0 * BENCH_PI * (double)b * df * dt;
        const double cr = cos(w);
        const double ci = sin(w);
        double zr = 1.0, zi = 0.0, re = 0.0, im = 0.0;
        for (uint32_t k = 0u; k < n; k++) {
            re += x[k] * zr;
            im += x[k] * zi;
            const double t = zr * cr - zi * ci;
            zi = zr * ci + zi * cr;
            zr = t;
        }
        const double amp = 2.0 * sqrt(re * re + im * im) / (double)n;
        sum += 0.5 * amp * amp;
    }
    return sqrt(sum);
}

/* The motor-frame jump: mean |di| at each frame's first step and at the others. */
static void frame_jump(const double *ia, uint32_t n, uint32_t frame, double *jump, double *step) {
    double sj = 0.0, ss = 0.0;
    uint32_t nj = 0u, ns = 0u;
    for (uint32_t k = 1u; k < n; k++) {
        const double d = fabs(ia[k] - ia[k - 1u]);
        if (k % frame == 0u) {
            sj += d;
            nj++;
        } else {
            ss += d;
            ns++;
        }
    }
    *jump = (nj > 0u) ? sj / nj : 0.0;
    *step = (ns > 0u) ? ss / ns : 0.0;
}

/*
 * v_an = Vdc (d_a - 1/2) of the real-time modulator over one 50 Hz period
 * at the fast step step_ns (the motor task's ramps over 100 us frames, of
 * this build): its fundamental against m Vdc / 2, in per cent.
 */
static double van_error_pct(uint32_t step_ns, bool substep, double m) {
    static const pwm_params sampled = {5000.0, PWM_EDGES_SAMPLED, 0u, 0u, 0u};
    const uint32_t inc = wt_phase_inc_q16(50 * 65536, step_ns);
    const uint32_t frame = 100000u / step_ns;
    const uint32_t steps = 20000000u / step_ns;
    pwm_rt rt;
    if (pwm_rt_init(&rt, &sampled, step_ns) != PWM_OK) {
        return NAN;
    }
    uint32_t ph = 0u;
    double re = 0.0, im = 0.0;
    for (uint32_t k = 0u; k < steps; k++) {
        if (k % frame == 0u) {
            pwm_rt_ramp ramp;
#if UUV_NUMERIC == UUV_NUMERIC_FIXED
            pwm_rt_ramp_q(&ramp, NULL, (int32_t)(m * 32768.0 + 0.5), ph, inc, frame);
#else
            pwm_rt_ramp_f32(&ramp, NULL, (float)m, ph, inc, frame);
#endif
            pwm_rt_apply(&rt, &ramp);
            ph += frame * inc;
        }
        int32_t s[3], duty[3];
        if (substep) {
            pwm_rt_substep_each(&rt, s, duty);
        } else {
            pwm_rt_sampled(&rt, s, duty);
        }
        /* The step's mean against the fundamental at the step's middle. */
        const double th = 2.0 * BENCH_PI * ((double)k + 0.5) / (double)steps;
        const double v = (double)duty[0] / 32768.0 - 0.5;
        re += v * sin(th);
        im += v * cos(th);
    }
    const double amp = 2.0 * sqrt(re * re + im * im) / (double)steps;
    return 100.0 * (amp / (m / 2.0) - 1.0);
}

static const uint32_t study_steps_ns[] = {1000u, 2000u, 4000u, 5000u};

/* The study's errors against the event reference ref, for one scenario (already loaded). */
static int switching_study(const exec_config *base, const run_data *ref, const char *what,
                           bool *first) {
    static run_data sw;
    for (size_t h = 0; h < sizeof study_steps_ns / sizeof study_steps_ns[0]; h++) {
        for (int sub = 1; sub >= 0; sub--) {
            exec_config c = *base;
            c.fast_ns = study_steps_ns[h];
            c.fast_per_medium = base->fast_ns * base->fast_per_medium / c.fast_ns;
            c.modulator = sub ? DRIVE_MODULATOR_SUBSTEP : DRIVE_MODULATOR_SAMPLED;
            if (run(&c, &sw) != 0) {
                return -1;
            }
            errors e = compare(&sw, ref);
            double worst = 0.0;
            size_t n = (sw.n < ref->n) ? sw.n : ref->n;
            for (size_t i = 0; i < n; i++) {
                worst = fmax(worst, fabs(sw.rec[i].x[VESSEL_N_RPM] - ref->rec[i].x[VESSEL_N_RPM]));
            }
            fprintf(stderr, "    %-9s %u us %-8s %8.3f %8.3f %8.3f %8.3f %8.1f%s\n", what,
                    (unsigned)(c.fast_ns / 1000u), sub ? "substep" : "sampled", e.shaft,
                    e.current, e.surge, e.position, worst,
                    sw.state == EXEC_DONE ? "" : "  (stopped)");
            printf("%s{\"scenario\": \"%s\", \"fast_step_us\": %u, \"modulator\": \"%s\", "
                   "\"err_shaft_speed_pct\": %.6g, \"err_current_pct\": %.6g, "
                   "\"err_surge_speed_pct\": %.6g, \"err_position_pct\": %.6g, "
                   "\"worst_shaft_rpm\": %.6g}",
                   *first ? "" : ", ", what, (unsigned)(c.fast_ns / 1000u),
                   sub ? "substep" : "sampled", e.shaft, e.current, e.surge, e.position, worst);
            *first = false;
        }
    }
    return 0;
}

/*
 * The whole study (after the main tables): the errors of both modulators
 * at four fast steps on the bench scenario and the low-speed one, the
 * fundamental of v_an, and the motor coupling's frame-rate artefact at a
 * steady 1000 rpm against the single-rate run (the motor at 2 us: the
 * physical motor at the filter's terminals).
 */
static int study(const exec_config *cfg, const run_data *ref_ev, const char *low_path) {
    fprintf(stderr, "  switching error against the single-rate switching-event reference "
                    "(2 us), carrier 5 kHz, motor frame 100 us:\n");
    fprintf(stderr, "    %-9s %4s %-8s %8s %8s %8s %8s %8s\n", "scenario", "step", "model",
            "shaft", "current", "surge", "position", "worst rpm");
    printf(", \"switching_study\": [");
    bool first = true;
    if (switching_study(cfg, ref_ev, "bench", &first) != 0) {
        return -1;
    }
    if (load(low_path) != 0) {
        return -1;
    }
    static run_data ref_low;
    exec_config c = *cfg;
    c.single_rate = true;
    c.inverter = DRIVE_INVERTER_EVENT;
    if (run(&c, &ref_low) != 0 || switching_study(cfg, &ref_low, "low-speed", &first) != 0) {
        return -1;
    }
    printf("], \"van_fundamental\": [");
    fprintf(stderr, "  v_an fundamental against m Vdc/2 (%%), 50 Hz, sampled / substep:\n");
    fprintf(stderr, "    %-6s", "step");
    static const double m_list[] = {0.1, 0.2, 0.5, 0.9};
    for (size_t j = 0; j < 4u; j++) {
        fprintf(stderr, "      m = %.1f    ", m_list[j]);
    }
    fprintf(stderr, "\n");
    first = true;
    for (size_t h = 0; h < sizeof study_steps_ns / sizeof study_steps_ns[0]; h++) {
        fprintf(stderr, "    %u us  ", (unsigned)(study_steps_ns[h] / 1000u));
        for (size_t j = 0; j < 4u; j++) {
            const double es = van_error_pct(study_steps_ns[h], false, m_list[j]);
            const double eu = van_error_pct(study_steps_ns[h], true, m_list[j]);
            fprintf(stderr, " %7.3f / %7.4f", es, eu);
            printf("%s{\"fast_step_us\": %u, \"m\": %.2g, \"sampled_pct\": %.6g, "
                   "\"substep_pct\": %.6g}",
                   first ? "" : ", ", (unsigned)(study_steps_ns[h] / 1000u), m_list[j], es, eu);
            first = false;
        }
        fprintf(stderr, "\n");
    }
    /* The frame-rate artefact: 2 s to 3 s of the bench scenario (1000 rpm held). */
    printf("], \"motor_coupling\": [");
    fprintf(stderr, "  motor coupling at 1000 rpm (2 s to 3 s of the bench scenario; band "
                    "7-13 kHz over 2.0 to 2.1 s, A and V rms):\n");
    fprintf(stderr, "    %-18s %9s %9s %7s %9s %9s %9s %9s\n", "run", "jump [A]", "step [A]",
            "ratio", "i_a band", "vc_a band", "di band", "dvc band");
    static const char *const bench_path = "scenarios/bench_2s.scn";
    if (load(bench_path) != 0) {
        return -1;
    }
    const uint32_t n = 500000u;
    const uint32_t nb = 50000u;
    static double vc_ref[500000], ia_ref[500000], vc[500000], ia[500000], dv[50000], di[50000];
    c = *cfg;
    c.duration_s = 3.0;
    c.single_rate = true;
    const uint64_t k0 = (uint64_t)(2.0e9 / (double)cfg->fast_ns + 0.5);
    if (run_window(&c, k0, n, vc_ref, ia_ref) != 0) {
        return -1;
    }
    static const coupling_down downs[] = {COUPLE_ZOH, COUPLE_FOH, COUPLE_DERIV, COUPLE_STAGGER};
    first = true;
    for (int r = -1; r < 4; r++) {
        const double *v = vc_ref;
        const double *i = ia_ref;
        char name[32];
        if (r < 0) {
            snprintf(name, sizeof name, "single-rate");
        } else {
            c = *cfg;
            c.duration_s = 3.0;
            c.down = downs[r];
            if (run_window(&c, k0, n, vc, ia) != 0) {
                return -1;
            }
            v = vc;
            i = ia;
            snprintf(name, sizeof name, "%s%s", down_names[downs[r]],
                     downs[r] == cfg->down ? " (default)" : "");
        }
        double jump, step;
        frame_jump(i, n, cfg->fast_per_medium, &jump, &step);
        for (uint32_t k = 0u; k < nb; k++) {
            dv[k] = v[k] - vc_ref[k];
            di[k] = i[k] - ia_ref[k];
        }
        const double dt = 1e-9 * (double)cfg->fast_ns;
        const double bi = band_rms(i, nb, dt, 7000.0, 13000.0);
        const double bv = band_rms(v, nb, dt, 7000.0, 13000.0);
        const double bdi = (r < 0) ? 0.0 : band_rms(di, nb, dt, 7000.0, 13000.0);
        const double bdv = (r < 0) ? 0.0 : band_rms(dv, nb, dt, 7000.0, 13000.0);
        fprintf(stderr, "    %-18s %9.4f %9.4f %7.2f %9.4f %9.4f %9.4f %9.4f\n", name, jump,
                step, jump / step, bi, bv, bdi, bdv);
        printf("%s{\"run\": \"%s\", \"jump_a\": %.6g, \"step_a\": %.6g, \"band_i_a\": %.6g, "
               "\"band_vc_v\": %.6g, \"band_di_a\": %.6g, \"band_dvc_v\": %.6g}",
               first ? "" : ", ", name, jump, step, bi, bv, bdi, bdv);
        first = false;
    }
    printf("]");
    return 0;
}

int main(int argc, char **argv) {
    if (argc < 2 || argc > 4) {
        fprintf(stderr, "usage: bench SCENARIO.scn [DURATION_S [LOW_SPEED.scn]]\n");
        return 2;
    }
    if (load(argv[1]) != 0) {
        return 2;
    }
    exec_config cfg;
    exec_config_default(&cfg);
    cfg.duration_s = (argc == 3) ? atof(argv[2]) : 2.0;
    static run_data ref, ref_ev, mr, avg, cpl;
    exec_config c = cfg;
    c.single_rate = true;
    double ref_cpu = 1e300; /* best of two: the speed-ups' reference */
    for (int k = 0; k < 2; k++) {
        if (run(&c, &ref) != 0) {
            return 1;
        }
        ref_cpu = (ref.cpu_s < ref_cpu) ? ref.cpu_s : ref_cpu;
    }
    ref.cpu_s = ref_cpu;
    c.inverter = DRIVE_INVERTER_EVENT;
    if (run(&c, &ref_ev) != 0) {
        return 1;
    }
    /* The multi-rate run on the exact path and, where the build has them, with the exact
     * leaps (leap.h): best of five each (a leap run takes some 6 ms), interleaved; mr keeps
     * an exact run's records. */
    static run_data lp;
    const bool have_leap = leap_available();
    double mr_cpu = 1e300;
    double lp_cpu = 1e300;
    for (int k = 0; k < (have_leap ? 10 : 5); k++) {
        run_leaps = have_leap && (k % 2 == 1);
        run_data *r = run_leaps ? &lp : &mr;
        double *best = run_leaps ? &lp_cpu : &mr_cpu;
        if (run(&cfg, r) != 0) {
            return 1;
        }
        *best = (r->cpu_s < *best) ? r->cpu_s : *best;
    }
    run_leaps = false;
    mr.cpu_s = mr_cpu;
    c = cfg;
    c.inverter = DRIVE_INVERTER_AVERAGED;
    double avg_cpu = 1e300;
    for (int k = 0; k < 5; k++) {
        if (run(&c, &avg) != 0) {
            return 1;
        }
        avg_cpu = (avg.cpu_s < avg_cpu) ? avg.cpu_s : avg_cpu;
    }
    double sim_s = mr.rec[mr.n - 1].t_s;
    errors e = compare(&mr, &ref);
    double ns[5];
    segment_costs(&cfg, ns);
    const double rtf_sw = sim_s / mr.cpu_s;
    const double rtf_avg = sim_s / avg_cpu;
    const double speedup = ref.cpu_s / mr.cpu_s;
    const double speedup_leap = have_leap ? ref.cpu_s / lp_cpu : 0.0;
    const errors le = have_leap ? compare(&lp, &ref) : e;
    /* The target's figure: the leaps' where the build has them (the desk path). */
    const double speedup_best = have_leap ? speedup_leap : speedup;
    /* The single-rate reference's square roots are the multi-rate run's (one program). */
    const char *const sqrt_kind = (UUV_HW_SQRT_F64 != 0 && UUV_HW_SQRT_F32 != 0) ? "hardware"
                                  : (UUV_HW_SQRT_F64 != 0 || UUV_HW_SQRT_F32 != 0) ? "mixed"
                                                                                 : "software";
    const double err_ex = (e.shaft > e.surge) ? e.shaft : e.surge;
    const double err_lp = (le.shaft > le.surge) ? le.shaft : le.surge;
    const double err_max = (err_ex > err_lp) ? err_ex : err_lp;

    fprintf(stderr, "%s build, %.1f s of %s\n", UUV_NUMERIC_NAME, sim_s, argv[1]);
    fprintf(stderr, "  real-time factor: switching %.0f, averaged %.0f\n", rtf_sw, rtf_avg);
    fprintf(stderr, "  cost per step: fast %.1f ns (%.1f ns in runs), motor %.1f ns, "
                    "controller %.1f ns, slow %.0f ns\n",
            ns[0], ns[4], ns[1], ns[2], ns[3]);
    fprintf(stderr, "  single-rate %.2f s, multi-rate %.4f s (CPU, best of 5): speed-up %.0fx "
                    "(exact path; both runs this program's, square roots %s)\n",
            ref.cpu_s, mr.cpu_s, speedup, sqrt_kind);
    if (have_leap) {
        fprintf(stderr, "  with the exact leaps %.4f s (best of 5): speed-up %.0fx; errors vs "
                        "single-rate: shaft %.3f %%, surge %.3f %% (exact path %.3f %%, %.3f %%)\n",
                lp_cpu, speedup_leap, le.shaft, le.surge, e.shaft, e.surge);
    }
    fprintf(stderr,
            "  targets: real-time factor >= 100 switching (%s), >= 10000 averaged (%s); "
            "speed-up >= 300 (%s, %s) at shaft and surge errors <= 0.5 %% (%s)\n",
            met(rtf_sw >= 100.0), met(rtf_avg >= 10000.0), have_leap ? "leaps" : "exact path",
            met(speedup_best >= 300.0), met(err_max <= 0.5));
    fprintf(stderr, "  errors vs single-rate (RMS, %% of reference RMS):\n");
    fprintf(stderr, "    %-16s %8s %8s %8s %8s\n", "coupling", "shaft", "current", "surge",
            "position");
    printf("{\"build\": \"%s\", \"sim_time_s\": %.6g, \"rtf_switching\": %.6g, "
           "\"rtf_averaged\": %.6g, \"speedup_vs_single_rate\": %.6g, \"speedup_sqrt\": \"%s\", "
           "\"cpu_single_rate_s\": %.6g, \"cpu_multi_rate_s\": %.6g, "
           "\"err_shaft_speed_pct\": %.6g, \"err_current_pct\": %.6g, "
           "\"err_surge_speed_pct\": %.6g, \"err_position_pct\": %.6g, "
           "\"ns_per_step\": {\"fast\": %.4g, \"fast_in_runs\": %.4g, \"medium\": %.4g, "
           "\"control\": %.4g, \"slow\": %.4g}, ",
           UUV_NUMERIC_NAME, sim_s, rtf_sw, rtf_avg, speedup, sqrt_kind, ref.cpu_s, mr.cpu_s, e.shaft,
           e.current, e.surge, e.position, ns[0], ns[4], ns[1], ns[2], ns[3]);
    if (have_leap) {
        printf("\"speedup_leap\": %.6g, \"cpu_leap_s\": %.6g, \"leap_err_shaft_speed_pct\": %.6g, "
               "\"leap_err_surge_speed_pct\": %.6g, ",
               speedup_leap, lp_cpu, le.shaft, le.surge);
    } else {
        printf("\"speedup_leap\": null, \"cpu_leap_s\": null, \"leap_err_shaft_speed_pct\": null, "
               "\"leap_err_surge_speed_pct\": null, ");
    }
    printf("\"couplings\": [");
    bool first = true;
    for (int dn = 0; dn < 4; dn++) {
        for (int up = 0; up < 3; up++) {
            c = cfg;
            c.down = (coupling_down)dn;
            c.up = (coupling_up)up;
            if (run(&c, &cpl) != 0) {
                return 1;
            }
            errors ce = compare(&cpl, &ref);
            char name[32];
            snprintf(name, sizeof name, "%s/%s", down_names[dn], up_names[up]);
            fprintf(stderr, "    %-16s %8.3f %8.3f %8.3f %8.3f%s\n", name, ce.shaft, ce.current,
                    ce.surge, ce.position, cpl.state == EXEC_DONE ? "" : "  (stopped)");
            printf("%s{\"coupling\": \"%s\", \"err_shaft_speed_pct\": %.6g, "
                   "\"err_current_pct\": %.6g, \"err_surge_speed_pct\": %.6g, "
                   "\"err_position_pct\": %.6g}",
                   first ? "" : ", ", name, ce.shaft, ce.current, ce.surge, ce.position);
            first = false;
        }
    }
    errors ae = compare(&avg, &ref);
    errors ee = compare(&avg, &ref_ev);
    errors rr = compare(&ref, &ref_ev);
    fprintf(stderr, "    %-16s %8.3f %8.3f %8.3f %8.3f\n", "averaged", ae.shaft, ae.current,
            ae.surge, ae.position);
    /* The motor task's frame, the controller's kept at 800 us (default couplings). */
    static const uint32_t motor_us[] = {20u, 50u, 100u, 200u, 400u, 800u};
    fprintf(stderr, "  motor frame (controller 800 us; real-time factor: best of three runs):\n");
    fprintf(stderr, "    %-16s %8s %8s %8s %8s %8s\n", "frame", "shaft", "current", "surge",
            "position", "rtf");
    printf("], \"motor_frames\": [");
    for (size_t k = 0; k < sizeof motor_us / sizeof motor_us[0]; k++) {
        c = cfg;
        const uint64_t motor_ns = (uint64_t)motor_us[k] * 1000u;
        const uint64_t default_ns = (uint64_t)cfg.fast_ns * cfg.fast_per_medium;
        c.fast_per_medium = (uint32_t)(motor_ns / cfg.fast_ns);
        c.medium_per_control = (uint32_t)(default_ns * cfg.medium_per_control / motor_ns);
        c.medium_per_slow = (uint32_t)(default_ns * cfg.medium_per_slow / motor_ns);
        double wall = 1e300;
        for (int r = 0; r < 3; r++) {
            if (run(&c, &cpl) != 0) {
                return 1;
            }
            wall = (cpl.cpu_s < wall) ? cpl.cpu_s : wall;
        }
        errors fe = compare(&cpl, &ref);
        char name[32];
        snprintf(name, sizeof name, "%u us", (unsigned)motor_us[k]);
        fprintf(stderr, "    %-16s %8.3f %8.3f %8.3f %8.3f %8.0f%s\n", name, fe.shaft, fe.current,
                fe.surge, fe.position, sim_s / wall,
                cpl.state == EXEC_DONE ? "" : "  (stopped)");
        printf("%s{\"motor_frame_us\": %u, \"rtf\": %.6g, \"err_shaft_speed_pct\": %.6g, "
               "\"err_current_pct\": %.6g, \"err_surge_speed_pct\": %.6g, "
               "\"err_position_pct\": %.6g}",
               (k == 0u) ? "" : ", ", (unsigned)motor_us[k], sim_s / wall, fe.shaft,
               fe.current, fe.surge, fe.position);
    }
    fprintf(stderr, "  against the single-rate switching-event reference:\n");
    fprintf(stderr, "    %-16s %8.3f %8.3f %8.3f %8.3f\n", "averaged", ee.shaft, ee.current,
            ee.surge, ee.position);
    fprintf(stderr, "    %-16s %8.3f %8.3f %8.3f %8.3f\n", "single-rate dflt", rr.shaft,
            rr.current, rr.surge, rr.position);
    printf("], \"averaged\": {\"err_shaft_speed_pct\": %.6g, \"err_current_pct\": %.6g, "
           "\"err_surge_speed_pct\": %.6g, \"err_position_pct\": %.6g}, "
           "\"averaged_vs_event_reference\": {\"err_shaft_speed_pct\": %.6g, "
           "\"err_current_pct\": %.6g, \"err_surge_speed_pct\": %.6g, "
           "\"err_position_pct\": %.6g}, "
           "\"reference_vs_event_reference\": {\"err_shaft_speed_pct\": %.6g, "
           "\"err_current_pct\": %.6g, \"err_surge_speed_pct\": %.6g, "
           "\"err_position_pct\": %.6g}",
           ae.shaft, ae.current, ae.surge, ae.position, ee.shaft, ee.current, ee.surge,
           ee.position, rr.shaft, rr.current, rr.surge, rr.position);
    /* The averaged layer on the default mission (its target's run), best of five. */
    if (load(MISSION_PATH) != 0) {
        return 1;
    }
    c = cfg;
    c.duration_s = 0.0;
    c.inverter = DRIVE_INVERTER_AVERAGED;
    double mission_cpu = 1e300;
    for (int k = 0; k < 5; k++) {
        if (run(&c, &avg) != 0) {
            return 1;
        }
        mission_cpu = (avg.cpu_s < mission_cpu) ? avg.cpu_s : mission_cpu;
    }
    const double rtf_mission = avg.rec[avg.n - 1].t_s / mission_cpu;
    const double rtf_mission_target = (UUV_NUMERIC == UUV_NUMERIC_FIXED) ? 5000.0 : 10000.0;
    fprintf(stderr, "  averaged layer on %s (%.0f s): real-time factor %.0f (target >= %.0f: %s)\n",
            MISSION_PATH, avg.rec[avg.n - 1].t_s, rtf_mission, rtf_mission_target,
            met(rtf_mission >= rtf_mission_target));
    printf(", \"rtf_averaged_mission\": %.6g", rtf_mission);
    if (leap_mission(&cfg) != 0 || batch_mission(&cfg) != 0) {
        return 1;
    }
    if (load(argv[1]) != 0) {
        return 1;
    }
    if (argc == 4 && study(&cfg, &ref_ev, argv[3]) != 0) {
        return 1;
    }
    printf("}\n");
    return 0;
}
