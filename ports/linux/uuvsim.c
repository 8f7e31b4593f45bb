/*
 * uuvsim: the desk simulator. Reads a scenario, runs the executive in
 * virtual time (as fast as it can, or paced to the wall clock), writes the
 * telemetry and trace files and prints a summary, as text or JSON.
 *
 * Exit status: 0 success; 2 bad input (options, scenario, files); 1 the
 * run stopped early (an overrun) or an internal failure; 3 the run stopped
 * because a state became non-finite (the executive's guard).
 */
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "cli.h"
#include "csv_out.h"
#include "leap.h"
#include "live.h"
#include "math/umath.h"
#include "paramset.h"
#include "run.h"
#include "party_host.h"
#include "sweep.h"
#include "uuv_config.h"
#include "view.h"

#define UUVSIM_VERSION "0.2.0"
#define MAX_SCENARIO_BYTES (1u << 20)

int uuvsim_derivs(const char *path); /* derivs.c */
FILE *uuvsim_open_input(const char *path);

static double wall_seconds(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

double uuvsim_wall_s(void) { return wall_seconds(); }

/*
 * Opens an input file for reading: a regular file only (a FIFO without a
 * writer would block the run forever, a device has no end), opened without
 * blocking before that is known.
 */
FILE *uuvsim_open_input(const char *path) {
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    struct stat st;
    if (fd < 0 || fstat(fd, &st) != 0) {
        fprintf(stderr, "uuvsim: %s: cannot open: %s\n", path, strerror(errno));
        if (fd >= 0) {
            close(fd);
        }
        return NULL;
    }
    if (!S_ISREG(st.st_mode)) {
        fprintf(stderr, "uuvsim: %s: cannot open: not a regular file\n", path);
        close(fd);
        return NULL;
    }
    FILE *f = fdopen(fd, "rb");
    if (f == NULL) {
        fprintf(stderr, "uuvsim: %s: cannot open: %s\n", path, strerror(errno));
        close(fd);
    }
    return f;
}

/* Reads and parses the scenario; prints the error (file:line: field) on failure. */
bool uuvsim_load_scenario(const char *path, scenario *scn) {
    FILE *f = uuvsim_open_input(path);
    if (f == NULL) {
        return false;
    }
    char *buf = malloc(MAX_SCENARIO_BYTES + 1u);
    size_t n = buf ? fread(buf, 1, MAX_SCENARIO_BYTES + 1u, f) : 0u;
    bool bad = ferror(f) != 0;
    fclose(f);
    if (buf == NULL || bad || n > MAX_SCENARIO_BYTES) {
        fprintf(stderr, "uuvsim: %s: %s\n", path,
                n > MAX_SCENARIO_BYTES ? "larger than 1 MiB" : "cannot read");
        free(buf);
        return false;
    }
    scenario_error err;
    bool ok = scenario_parse(scn, buf, n, &err);
    free(buf);
    if (!ok) {
        fprintf(stderr, "uuvsim: %s:%u: %s%s%s%s\n", path, err.line,
                err.field[0] ? "field '" : "", err.field, err.field[0] ? "': " : "",
                err.message);
    }
    return ok;
}

typedef struct {
    const cli_options *o;
    const char *params;        /* the parameter set's label (params_label) */
    exec *e;
    exec_frame last;
    double wall_s;
    double realtime_lag_max_s; /* [s] worst lag of the simulation behind the wall clock */
    uint32_t realtime_late;    /* reports produced after their wall-clock time */
    const scenario *scn;
} run_result;

static const char *const plant_names[] = {"vessel", "full"};
static const char *const law_names[] = {"mss", "paper"};
static const char *const inverter_names[] = {"switching", "averaged", "event"};
static const char *const down_names[] = {"zoh", "foh", "deriv", "stagger"};
static const char *const modulator_names[] = {"substep", "sampled"};
static const char *const up_names[] = {"avg", "filter", "sample"};

/* The mode: a vessel-only run has one frame, neither multi- nor single-rate. */
static const char *mode_name(const exec *e) {
    if (e->cfg.plant != EXEC_PLANT_FULL) {
        return "vessel only";
    }
    return e->cfg.single_rate ? "single-rate" : "multi-rate";
}

/* The injected faults by name, separated by sep and each quoted with q. */
static void print_faults(FILE *f_out, uint32_t mask, const char *sep, const char *q) {
    const char *s = "";
    for (int k = 0; k < SCN_COMMAND_COUNT - SCN_FIRST_FAULT; k++) {
        if ((mask & (1u << k)) != 0u) {
            fprintf(f_out, "%s%s%s%s", s, q, scenario_command_names[SCN_FIRST_FAULT + k], q);
            s = sep;
        }
    }
}

/*
 * The energy audit (--energy-audit): the battery's energy at its terminals
 * against the filter's and the motor's losses and the shaft's work; the
 * residual is what no account holds (the DC link's and the windings' stored
 * energy, the switching and coupling errors), in percent of the battery's.
 */
static void print_energy_balance(FILE *f_out, const exec *e) {
    const exec_counters *c = &e->count;
    double residual = c->e_batt_j - c->e_loss_filter_j - c->e_loss_motor_j - c->e_mech_j;
    fprintf(f_out, "  \"energy_balance\": {\"battery_wh\": %.9g, \"filter_loss_wh\": %.9g, "
            "\"motor_loss_wh\": %.9g, \"mechanical_wh\": %.9g, \"residual_wh\": %.9g, "
            "\"residual_pct\": %.6g},\n",
            c->e_batt_j / 3600.0, c->e_loss_filter_j / 3600.0, c->e_loss_motor_j / 3600.0,
            c->e_mech_j / 3600.0, residual / 3600.0,
            c->e_batt_j != 0.0 ? 100.0 * residual / c->e_batt_j : 0.0);
}

/*
 * The scenario's timed commands up to the run's end (the mission page marks
 * them along the track), in the command's unit (angles in rad), and the
 * zig-zag's start and stop.
 */
static void print_events(FILE *f_out, const scenario *scn, double end_s) {
    fprintf(f_out, "  \"events\": [");
    const char *sep = "";
    for (size_t k = 0; k < scn->n_events && scn->events[k].t_s <= end_s; k++) {
        const scenario_event *ev = &scn->events[k];
        fprintf(f_out, "%s{\"t_s\": %.9g, \"command\": \"%s\", \"value\": %.9g}", sep, ev->t_s,
                scenario_command_names[ev->command], ev->value);
        sep = ", ";
    }
    const scenario_zigzag *z = &scn->zigzag;
    if (z->enabled && z->start_s <= end_s) {
        fprintf(f_out, "%s{\"t_s\": %.9g, \"command\": \"zigzag\", \"value\": %.9g}", sep,
                z->start_s, z->rudder_rad);
        if (z->stop_s >= 0.0 && z->stop_s <= end_s) {
            fprintf(f_out, ", {\"t_s\": %.9g, \"command\": \"zigzag_stop\", \"value\": 0}",
                    z->stop_s);
        }
    }
    fprintf(f_out, "],\n");
}

static void print_json(FILE *f_out, const run_result *r) {
    const exec *e = r->e;
    const exec_frame *f = &r->last;
    const manoeuvre_result *m = exec_manoeuvre(e);
    double sim_s = f->t_s;
    fprintf(f_out, "{\n  \"build\": \"%s\",\n  \"mode\": \"%s\",\n", UUV_NUMERIC_NAME,
            mode_name(e));
    fprintf(f_out, "  \"plant\": \"%s\",\n  \"propulsion\": \"%s\",\n  \"inverter\": \"%s\",\n",
           plant_names[e->cfg.plant], law_names[e->cfg.propulsion],
           inverter_names[e->cfg.inverter]);
    if (e->desk_run != NULL) {
        /* Leap runs only: the exact path's summary keeps its bytes. */
        const leap_stats ls = leap_stats_of(e);
        fprintf(f_out, "  \"fast_path\": \"leap\",\n  \"leaps\": {\"leaps\": %llu, "
                "\"steps_in_leaps\": %llu, \"steps_in_double\": %llu, \"steps_in_runs\": %llu, "
                "\"bound_refusals\": %llu, \"table_builds\": %llu},\n",
                (unsigned long long)ls.leaps, (unsigned long long)ls.leap_steps,
                (unsigned long long)ls.dsteps, (unsigned long long)ls.steps,
                (unsigned long long)ls.bound_fails,
                (unsigned long long)ls.rebuilds);
    }
    fprintf(f_out, "  \"modulator\": \"%s\",\n  \"dead_time_s\": %.9g,\n",
            modulator_names[e->cfg.modulator], 1e-9 * (double)e->cfg.params->pwm->dead_time_ns);
    fprintf(f_out, "  \"params\": \"");
    for (const char *c = r->params; *c != '\0'; c++) {
        fprintf(f_out, (*c == '"' || *c == '\\') ? "\\%c" : "%c", *c);
    }
    fprintf(f_out, "\",\n");
    fprintf(f_out, "  \"slow_to_fast\": \"%s\",\n  \"fast_to_slow\": \"%s\",\n", down_names[e->cfg.down],
           up_names[e->cfg.up]);
    /* The frames the run used (a single-rate run steps every segment at the fast one). */
    uint64_t ns[4];
    cli_frames_ns(&e->cfg, ns);
    fprintf(f_out, "  \"frames_s\": {\"fast\": %.9g, \"motor\": %.9g, \"control\": %.9g, "
            "\"slow\": %.9g},\n  \"report_s\": %.9g,\n", 1e-9 * (double)ns[0],
            1e-9 * (double)ns[1], 1e-9 * (double)ns[2], 1e-9 * (double)ns[3], e->report_s);
    fprintf(f_out, "  \"sim_time_s\": %.9g,\n  \"wall_time_s\": %.6g,\n  \"realtime_factor\": %.6g,\n",
           sim_s, r->wall_s, r->wall_s > 0.0 ? sim_s / r->wall_s : 0.0);
    fprintf(f_out, "  \"steps\": {\"fast\": %llu, \"motor\": %llu, \"control\": %llu, \"slow\": %llu},\n",
           (unsigned long long)exec_fast_steps(e), (unsigned long long)e->count.medium,
           (unsigned long long)e->count.control, (unsigned long long)e->count.slow);
    fprintf(f_out, "  \"overruns\": %u,\n  \"saturations\": %u,\n",
           exec_overruns(e), e->count.saturations);
    fprintf(f_out, "  \"battery_energy_wh\": %.9g,\n  \"mechanical_energy_wh\": %.9g,\n",
           e->count.e_batt_j / 3600.0, e->count.e_mech_j / 3600.0);
    if (e->cfg.energy_audit) {
        print_energy_balance(f_out, e);
    }
    fprintf(f_out, "  \"faults\": [");
    print_faults(f_out, e->player.fault_mask, ", ", "\"");
    fprintf(f_out, "],\n  \"protection\": {\"tripped\": %s, \"reason\": \"%s\"",
            f->trip != 0u ? "true" : "false",
            out_trip_names[f->trip < OUT_TRIP_NAMES ? f->trip : 0u]);
    if (e->trip_t_s >= 0.0) {
        fprintf(f_out, ", \"at_s\": %.6g", e->trip_t_s);
    }
    fprintf(f_out, ", \"torque_limit_s\": %.6g},\n", e->count.limit_s);
    if (r->o->realtime) {
        fprintf(f_out, "  \"realtime_lag_max_s\": %.6g,\n  \"realtime_late_frames\": %u,\n"
                "  \"realtime_behind\": %s,\n",
                r->realtime_lag_max_s, r->realtime_late, r->realtime_late > 0u ? "true" : "false");
    }
    print_events(f_out, r->scn, sim_s);
    fprintf(f_out, "  \"final\": {");
    for (int i = 0; i < 12; i++) {
        fprintf(f_out, "\"%s\": %.10g, ", vessel_state_names[i], f->x[i]);
    }
    fprintf(f_out, "\"n_rpm\": %.10g, \"soc\": %.10g}", f->x[VESSEL_N_RPM],
           e->cfg.plant == EXEC_PLANT_FULL ? f->soc : 1.0);
    if (m->turn_executed && !m->zigzag) {
        /* Only the figures the turn reached. */
        fprintf(f_out, ",\n  \"turning_circle\": {\"executed\": true");
        if (m->has_advance) {
            fprintf(f_out, ", \"advance_m\": %.6g, \"transfer_m\": %.6g", m->advance_m,
                    m->transfer_m);
        }
        if (m->has_tactical) {
            fprintf(f_out, ", \"tactical_diameter_m\": %.6g", m->tactical_diameter_m);
        }
        if (m->has_steady) {
            fprintf(f_out, ", \"steady_diameter_m\": %.6g, \"speed_loss_pct\": %.6g",
                    m->steady_diameter_m, m->speed_loss_pct);
        }
        if (m->turn_ended) {
            fprintf(f_out, ", \"rudder_left_s\": %.6g", m->turn_end_s);
        }
        fprintf(f_out, "}");
    }
    if (m->zigzag) {
        fprintf(f_out, ",\n  \"zigzag\": {\"overshoot_deg\": [");
        for (size_t i = 0; i < m->n_overshoots; i++) {
            fprintf(f_out, "%s%.6g", i ? ", " : "", m->overshoot_deg[i]);
        }
        fprintf(f_out, "], \"period_s\": %.6g}", m->period_s);
    }
    fprintf(f_out, "\n}\n");
}

static void print_text(const run_result *r) {
    const exec *e = r->e;
    const exec_frame *f = &r->last;
    const manoeuvre_result *m = exec_manoeuvre(e);
    double rtf = r->wall_s > 0.0 ? f->t_s / r->wall_s : 0.0;
    printf("uuvsim %s, %s build, %s: plant %s, propulsion %s", UUVSIM_VERSION, UUV_NUMERIC_NAME,
           mode_name(e), plant_names[e->cfg.plant], law_names[e->cfg.propulsion]);
    if (e->cfg.plant == EXEC_PLANT_FULL) {
        printf(", inverter %s", inverter_names[e->cfg.inverter]);
        if (e->cfg.inverter == DRIVE_INVERTER_SWITCHING) {
            printf(" (modulator %s", modulator_names[e->cfg.modulator]);
            if (e->cfg.params->pwm->dead_time_ns != 0u) {
                printf(", dead time %.9g us", 1e-3 * (double)e->cfg.params->pwm->dead_time_ns);
            }
            printf(")");
        }
        printf(", couplings %s/%s", down_names[e->cfg.down], up_names[e->cfg.up]);
    }
    uint64_t ns[4];
    char t[4][32];
    cli_frames_ns(&e->cfg, ns);
    for (int k = 0; k < 4; k++) {
        (void)cli_frame_text(ns[k], t[k], sizeof t[k]);
    }
    if (e->cfg.plant != EXEC_PLANT_FULL) {
        printf("\nframe: %s", t[3]);
    } else if (e->cfg.single_rate) {
        char rep_t[32];
        (void)cli_frame_text((uint64_t)(e->report_s * 1e9 + 0.5), rep_t, sizeof rep_t);
        printf("\nframes: every segment at %s, controller %s, records every %s", t[0], t[2],
               rep_t);
    } else if (e->cfg.inverter == DRIVE_INVERTER_AVERAGED) {
        printf("\nframes: the drive at the controller's %s, slow %s", t[2], t[3]);
    } else {
        printf("\nframes: fast %s, motor %s, controller %s, slow %s", t[0], t[1], t[2], t[3]);
    }
    printf("\nparameters: %s", r->params);
    printf("\nsimulated %.1f s in %.3f s (%.*fx real time)\n", f->t_s, r->wall_s,
           rtf < 10.0 ? 2 : 0, rtf);
    if (r->o->realtime && r->realtime_late > 0u) {
        printf("paced to the wall clock: FELL BEHIND, %u of the records late, worst lag %.3f s\n",
               r->realtime_late, r->realtime_lag_max_s);
    } else if (r->o->realtime) {
        printf("paced to the wall clock: kept up (worst lag 0 s)\n");
    }
    if (e->cfg.plant == EXEC_PLANT_FULL) {
        printf("steps: %llu fast, %llu motor, %llu control, %llu slow; %u overruns, "
               "%u saturations\n",
               (unsigned long long)exec_fast_steps(e), (unsigned long long)e->count.medium,
               (unsigned long long)e->count.control, (unsigned long long)e->count.slow,
               exec_overruns(e), e->count.saturations);
        printf("battery: %.1f Wh drawn, state of charge %.4f, DC link %.1f V\n",
               e->count.e_batt_j / 3600.0, f->soc, f->v_dc_v);
        if (e->cfg.energy_audit) {
            const exec_counters *c = &e->count;
            double res = c->e_batt_j - c->e_loss_filter_j - c->e_loss_motor_j - c->e_mech_j;
            printf("energy balance: battery %.3f Wh = filter losses %.3f + motor losses %.3f + "
                   "shaft work %.3f + residual %.3f Wh (%.3f %%)\n",
                   c->e_batt_j / 3600.0, c->e_loss_filter_j / 3600.0,
                   c->e_loss_motor_j / 3600.0, c->e_mech_j / 3600.0, res / 3600.0,
                   c->e_batt_j != 0.0 ? 100.0 * res / c->e_batt_j : 0.0);
        }
        if (e->player.fault_mask != 0u || f->trip != 0u) {
            printf("faults injected: ");
            print_faults(stdout, e->player.fault_mask, ", ", "");
            printf("%s; protection: %s\n", e->player.fault_mask != 0u ? "" : "none",
                   f->trip != 0u ? out_trip_names[f->trip < OUT_TRIP_NAMES ? f->trip : 0u]
                                 : "not tripped");
        }
    }
    /* The state psi is unwrapped (it counts whole turns); the line gives the
     * compass heading in [0, 360) and psi itself beside it. */
    const double psi_deg = f->x[VESSEL_PSI_RAD] * MATH_RAD_TO_DEG_F64;
    long long tenths = llround(psi_deg * 10.0) % 3600;
    if (tenths < 0) {
        tenths += 3600;
    }
    const double heading_deg = (double)tenths / 10.0;
    printf("final: u %.3f m/s, N %.1f m, E %.1f m, depth %.2f m, heading %.1f deg "
           "(psi %.1f deg unwrapped), shaft %.0f rpm\n",
           f->x[VESSEL_U_MPS], f->x[VESSEL_X_M], f->x[VESSEL_Y_M], f->x[VESSEL_Z_M],
           heading_deg, psi_deg, f->x[VESSEL_N_RPM]);
    if (m->turn_executed && !m->zigzag) {
        printf("turning circle:");
        if (m->has_advance) {
            printf(" advance %.1f m, transfer %.1f m", m->advance_m, m->transfer_m);
        } else {
            printf(" the heading did not change by 90 deg");
        }
        if (m->has_tactical) {
            printf(", tactical diameter %.1f m", m->tactical_diameter_m);
        }
        if (m->has_steady) {
            printf(", steady diameter %.1f m, speed loss %.1f %%", m->steady_diameter_m,
                   m->speed_loss_pct);
        }
        if (m->turn_ended) {
            printf(" (the rudder left its angle at %.1f s%s)", m->turn_end_s,
                   m->has_steady ? "" : ", before a full circle: no steady diameter");
        }
        printf("\n");
    }
    if (m->zigzag) {
        printf("zig-zag: overshoots");
        for (size_t i = 0; i < m->n_overshoots; i++) {
            printf(" %.2f", m->overshoot_deg[i]);
        }
        printf(" deg; period %.1f s\n", m->period_s);
    }
    if (e->state == EXEC_STOP_OVERRUN) {
        printf("stopped early: a task overran its frame\n");
    }
}

/*
 * The guard's report: when and what became non-finite, and the state of the
 * last record (finite).
 */
static void print_nonfinite(const exec *e) {
    const double t = (double)e->frame * e->slow_s;
    fprintf(stderr, "uuvsim: at t = %.9g s the run stopped: non-finite or diverged (beyond %g)",
            t, EXEC_DIVERGED);
    for (int i = 0; i < VESSEL_NSTATES; i++) {
        if ((e->nonfinite & (1u << i)) != 0u) {
            fprintf(stderr, " %s", vessel_state_names[i]);
        }
    }
    if ((e->nonfinite & EXEC_NONFINITE_DRIVE) != 0u) {
        fprintf(stderr, " drive or battery value");
    }
    fprintf(stderr, "\nuuvsim: the state at t = %.9g s:", e->report.t_s);
    for (int i = 0; i < VESSEL_NSTATES; i++) {
        fprintf(stderr, " %s=%.9g", vessel_state_names[i], e->report.x[i]);
    }
    fprintf(stderr, "\n");
}

/*
 * exec_init's refusal, naming what to change: the duration (the option, or
 * the scenario's line and field) or the slow frame.
 */
static void print_init_error(const cli_options *o, const scenario *scn, exec_status st) {
    uint64_t ns[4];
    cli_frames_ns(&o->exec, ns);
    const double slow_s = 1e-9 * (double)ns[3];
    const double report_s = o->exec.single_rate ? 0.1 : slow_s;
    const double d = (o->exec.duration_s > 0.0) ? o->exec.duration_s : scn->duration_s;
    char where[4200];
    if (o->exec.duration_s > 0.0) {
        snprintf(where, sizeof where, "option --duration");
    } else {
        snprintf(where, sizeof where, "%s:%u: field 'duration'", o->scenario_path,
                 (unsigned)scn->duration_line);
    }
    if (st == EXEC_ERR_SLOW_FRAME) {
        fprintf(stderr, "uuvsim: option --slow-frame: %.9g s is out of range: at most 10 s%s\n",
                slow_s, o->exec.plant == EXEC_PLANT_VESSEL
                            ? ", and at least 1 ms with --plant vessel (one vessel step per frame)"
                            : "");
    } else if (st == EXEC_ERR_DURATION_SHORT) {
        fprintf(stderr, "uuvsim: %s: %.9g s is shorter than half a record period (%.9g s%s): "
                "the run would have no record\n", where, d, report_s,
                o->slow_frame_ns != 0u ? ", the --slow-frame" : "");
    } else if (st == EXEC_ERR_DURATION_LONG) {
        fprintf(stderr, "uuvsim: %s: %.9g s needs more than 2^32 - 1 %s frames: at most %.9g s\n",
                where, d, o->exec.plant == EXEC_PLANT_FULL ? "motor" : "slow",
                o->exec.plant == EXEC_PLANT_FULL ? 4294967295.0 * 1e-9 * (double)ns[1]
                                                 : 4.0e9 * report_s);
    } else {
        fprintf(stderr, "uuvsim: %s\n",
                st == EXEC_ERR_CONFIG ? "the frames, duration or options are out of range"
                                      : "a model refused its parameters at these frames");
    }
}

/* Sleeps until the wall clock reaches the simulated time t_s (from w0); the
 * live view serves its browsers in that time instead (and when late, once). */
static void pace(run_result *r, double w0, double t_s, live_server *live) {
    double ahead = t_s - (wall_seconds() - w0);
    if (live != NULL) {
        live_wait(live, ahead);
    }
    if (live != NULL && ahead > 0.0) {
        return;
    }
    if (ahead > 0.0) {
        struct timespec ts = {(time_t)ahead, (long)((ahead - (double)(time_t)ahead) * 1e9)};
        nanosleep(&ts, NULL);
    } else {
        r->realtime_late++;
        if (-ahead > r->realtime_lag_max_s) {
            r->realtime_lag_max_s = -ahead;
        }
    }
}

/* One run's state from its options to its committed outputs (run.h). */
struct uuvsim_run {
    scenario scn;
    param_store *set;
    exec e;
    out_file csv, trace, sum;
    live_server *live;
    run_result r;
    bool full, progress, tracing;
    bool leap; /* --fast-path leap: e's runs of steps are leap.c's */
    uint64_t trace_first, trace_last;
    uint64_t traced; /* the fast step of the last trace row */
    double w0, next_progress;
};

static void run_free(uuvsim_run *u) {
    if (u != NULL) {
        if (u->leap) {
            leap_detach(&u->e);
        }
        params_free(u->set);
        free(u);
    }
}

uuvsim_run *uuvsim_run_open(const cli_options *o, int *status) {
    *status = 2;
    uuvsim_run *u = calloc(1u, sizeof *u);
    if (u == NULL) {
        fprintf(stderr, "uuvsim: out of memory\n");
        return NULL;
    }
    scenario *scn = &u->scn;
    if (!uuvsim_load_scenario(o->scenario_path, scn)) {
        run_free(u);
        return NULL;
    }
    if (o->exec.duration_s <= 0.0 && scn->duration_s <= 0.0) {
        fprintf(stderr, "uuvsim: %s: no duration (give 'duration <s>' or --duration)\n",
                o->scenario_path);
        run_free(u);
        return NULL;
    }
    const double duration = (o->exec.duration_s > 0.0) ? o->exec.duration_s : scn->duration_s;
    if (o->trace_path != NULL && o->trace_from_s >= duration) {
        fprintf(stderr, "uuvsim: option --trace-from: %g s is not before the end of the run "
                "(%g s): the trace would be empty\n", o->trace_from_s, duration);
        run_free(u);
        return NULL;
    }
    scenario_error err;
    if (!exec_check_scenario(&o->exec, scn, &err)) {
        fprintf(stderr, "uuvsim: %s:%u: field '%s': %s\n", o->scenario_path, err.line, err.field,
                err.message);
        run_free(u);
        return NULL;
    }
    u->set = params_new();
    if (u->set == NULL || !params_load(u->set, o->params_path, o->sets, o->n_sets) ||
        !params_check_run(u->set, o->exec.plant != EXEC_PLANT_FULL ||
                                      (o->exec.inverter == DRIVE_INVERTER_SWITCHING &&
                                       o->exec.modulator == DRIVE_MODULATOR_SUBSTEP))) {
        run_free(u);
        return NULL;
    }
    exec_config cfg = o->exec;
    cfg.params = params_set(u->set);
    exec *e = &u->e;
    exec_status st = exec_init(e, &cfg, scn);
    if (st != EXEC_OK) {
        print_init_error(o, scn, st);
        run_free(u);
        return NULL;
    }
    if (o->fast_path == CLI_FAST_LEAP) {
        if (!leap_attach(e)) {
            fprintf(stderr, "uuvsim: option --fast-path leap: no memory for the leap tables\n");
            run_free(u);
            return NULL;
        }
        u->leap = true;
    }
    u->full = (o->exec.plant == EXEC_PLANT_FULL);
    const out_spec outs[3] = {{"--csv", o->csv_path},
                              {"--trace", o->trace_path},
                              {"--summary", o->summary_path}};
    const out_spec ins[1] = {{"--scenario", o->scenario_path}};
    if (!out_check(outs, 3, ins, 1)) {
        run_free(u);
        return NULL;
    }
    out_guard_signals();
    /* Every output is written in full before any is committed (out_file.h). */
    if ((o->csv_path != NULL && !out_open(&u->csv, o->csv_path)) ||
        (o->trace_path != NULL && !out_open(&u->trace, o->trace_path)) ||
        (o->summary_path != NULL && !out_open(&u->sum, o->summary_path))) {
        out_abort(&u->csv);
        out_abort(&u->trace);
        run_free(u);
        return NULL;
    }
    if (o->view && (u->live = live_open((unsigned)o->view_port, u->full)) == NULL) {
        uuvsim_run_abort(u);
        return NULL;
    }
    if (u->csv.f != NULL) {
        csv_header(u->csv.f, u->full);
    }
    if (u->trace.f != NULL) {
        trace_header(u->trace.f);
        double fast_s = 1e-9 * (double)e->cfg.fast_ns;
        u->trace_first = (uint64_t)(o->trace_from_s / fast_s + 0.5);
        u->trace_last = (uint64_t)(o->trace_to_s / fast_s + 0.5);
    }
    u->progress = !o->quiet && isatty(STDERR_FILENO);
    u->r = (run_result){o, params_label(u->set), e, {0}, 0.0, 0.0, 0u, scn};
    (void)exec_report_take(e, &u->r.last);
    if (u->csv.f != NULL) {
        csv_row(u->csv.f, &u->r.last, u->full);
    }
    if (u->live != NULL) {
        live_frame(u->live, &u->r.last);
        live_wait_browser(u->live); /* the run starts when someone watches */
    }
    u->w0 = wall_seconds();
    u->next_progress = u->w0 + 0.5;
    u->traced = UINT64_MAX;
    u->tracing = (u->trace.f != NULL && u->full);
    *status = 0;
    return u;
}

exec *uuvsim_run_exec(uuvsim_run *u) { return &u->e; }

uint32_t uuvsim_run_ahead(const uuvsim_run *u) {
    /* Steps in runs, but one at a time inside the trace window. */
    uint32_t max_ticks = UINT32_MAX;
    if (u->tracing) {
        uint64_t k = exec_fast_steps(&u->e);
        if (k < u->trace_first) {
            uint64_t ahead = u->trace_first - k;
            max_ticks = (ahead < UINT32_MAX) ? (uint32_t)ahead : UINT32_MAX;
        } else if (k < u->trace_last) {
            max_ticks = 1u;
        }
    }
    return max_ticks;
}

void uuvsim_run_after(uuvsim_run *u) {
    exec *e = &u->e;
    run_result *r = &u->r;
    const cli_options *o = r->o;
    if (u->tracing) {
        uint64_t k = exec_fast_steps(e);
        if (k != u->traced && k >= u->trace_first && k <= u->trace_last) {
            u->traced = k; /* a tick without a step (the run's last) adds no row */
            drive_trace_row row;
            drive_trace(&e->drive, &row);
            trace_row(u->trace.f, exec_time_s(e), &row);
        }
    }
    if (!e->report_ready) {
        return;
    }
    (void)exec_report_take(e, &r->last);
    if (u->csv.f != NULL) {
        csv_row(u->csv.f, &r->last, u->full);
    }
    if (u->live != NULL) {
        live_frame(u->live, &r->last);
    }
    if (o->realtime) {
        pace(r, u->w0, r->last.t_s, u->live);
    }
    if (u->progress && wall_seconds() >= u->next_progress) {
        u->next_progress += 0.5;
        fprintf(stderr, "\r  t = %8.1f s  u = %5.2f m/s  depth %7.2f m  shaft %5.0f rpm ",
                r->last.t_s, r->last.x[VESSEL_U_MPS], r->last.x[VESSEL_Z_M],
                r->last.x[VESSEL_N_RPM]);
    }
}

void uuvsim_run_abort(uuvsim_run *u) {
    out_abort(&u->csv);
    out_abort(&u->trace);
    out_abort(&u->sum);
    if (u->live != NULL) {
        live_close(u->live);
    }
    run_free(u);
}

int uuvsim_run_close(uuvsim_run *u, double wall_s) {
    run_result *r = &u->r;
    const cli_options *o = r->o;
    exec *e = &u->e;
    r->wall_s = (wall_s >= 0.0) ? wall_s : wall_seconds() - u->w0;
    if (u->progress) {
        fprintf(stderr, "\r%78s\r", "");
    }
    if (u->live != NULL) {
        /* The summary to the live view's browsers, then the end of their streams. */
        char *text = NULL;
        size_t len = 0u;
        FILE *m = open_memstream(&text, &len);
        if (m != NULL) {
            print_json(m, r);
            fclose(m);
        }
        live_end(u->live, text != NULL ? text : "null", text != NULL ? len : 4u);
        free(text);
        live_close(u->live);
        u->live = NULL;
    }
    if (u->sum.f != NULL) {
        print_json(u->sum.f, r);
    }
    if (o->json) {
        print_json(stdout, r);
    } else if (!o->quiet) {
        print_text(r);
    }
    bool ok = out_finish(&u->csv);
    ok = out_finish(&u->trace) && ok;
    ok = out_finish(&u->sum) && ok;
    ok = ok && out_stdout_ok();
    ok = ok && out_commit(&u->csv);
    ok = ok && out_commit(&u->trace);
    ok = ok && out_commit(&u->sum);
    if (!ok) {
        uuvsim_run_abort(u);
        return 2;
    }
    int status = e->state == EXEC_DONE ? 0 : 1;
    if (e->state == EXEC_STOP_NONFINITE) {
        print_nonfinite(e);
        status = 3;
    }
    run_free(u);
    return status;
}

static int run(const cli_options *o) {
    int status;
    uuvsim_run *u = uuvsim_run_open(o, &status);
    if (u == NULL) {
        return status;
    }
    exec *e = uuvsim_run_exec(u);
    while (e->state == EXEC_RUNNING) {
        (void)exec_desk_run(e, uuvsim_run_ahead(u));
        uuvsim_run_after(u);
    }
    return uuvsim_run_close(u, -1.0);
}

int main(int argc, char **argv) {
    static cli_options o;
    char err[256];
    if (argc >= 2 && (strcmp(argv[1], "sweep") == 0 || strcmp(argv[1], "sweep-merge") == 0)) {
        return sweep_main(argc, argv);
    }
    if (argc >= 2 && strcmp(argv[1], "party") == 0) {
        return party_main(argc, argv);
    }
    if (argc >= 2 && strcmp(argv[1], "batch") == 0) {
        return batch_main(argc, argv);
    }
    if (!cli_parse(argc, argv, &o, err, sizeof err)) {
        fprintf(stderr, "uuvsim: %s\n", err);
        return 2;
    }
    switch (o.action) {
    case CLI_HELP:
        fputs(cli_usage, stdout);
        fputs(cli_usage_studies, stdout);
        return out_stdout_ok() ? 0 : 2;
    case CLI_VERSION:
        printf("uuvsim %s (%s build)\n", UUVSIM_VERSION, UUV_NUMERIC_NAME);
        return out_stdout_ok() ? 0 : 2;
    case CLI_DERIVS:
        return uuvsim_derivs(o.derivs_path);
    case CLI_VIEW:
        return uuvsim_view(o.view_dir);
    case CLI_PARAMS:
        return params_command(o.params_path, o.sets, o.n_sets, o.emit_c_path);
    case CLI_RUN:
        break;
    }
    if (o.fast_path == CLI_FAST_LEAP && !leap_available()) {
        fprintf(stderr, "uuvsim: option --fast-path leap: not in the %s build (leaps map the "
                "float build's step only); use the float build's uuvsim, or --fast-path "
                "exact\n", UUV_NUMERIC_NAME);
        return 2;
    }
    return run(&o);
}
