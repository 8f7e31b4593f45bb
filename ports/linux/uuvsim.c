/*
 * uuvsim: the desk simulator. Reads a scenario, runs it, writes the
 * slow-rate telemetry as CSV and prints a summary (text or JSON).
 *
 * Exit status: 0 success, 2 bad input (options, scenario, files); 1 an
 * internal failure. Output files are written under a temporary name and
 * renamed when complete, so a failed run leaves no half-written file.
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cli.h"
#include "csv_out.h"
#include "hal_linux.h"
#include "sim.h"
#include "uuv_config.h"

#define UUVSIM_VERSION "0.1.0"
#define MAX_SCENARIO_BYTES (1u << 20)

int uuvsim_derivs(const char *path); /* derivs.c */

static double wall_seconds(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Reads the whole scenario file; prints the error and returns NULL on failure. */
static char *read_file(const char *path, size_t *len) {
    FILE *f = fopen(path, "rb");
    if (f == NULL) {
        fprintf(stderr, "uuvsim: %s: cannot open: %s\n", path, strerror(errno));
        return NULL;
    }
    char *buf = malloc(MAX_SCENARIO_BYTES + 1u);
    size_t n = buf ? fread(buf, 1, MAX_SCENARIO_BYTES + 1u, f) : 0u;
    int bad = ferror(f);
    fclose(f);
    if (buf == NULL || bad) {
        fprintf(stderr, "uuvsim: %s: cannot read\n", path);
        free(buf);
        return NULL;
    }
    if (n > MAX_SCENARIO_BYTES) {
        fprintf(stderr, "uuvsim: %s: larger than %u bytes\n", path, MAX_SCENARIO_BYTES);
        free(buf);
        return NULL;
    }
    *len = n;
    return buf;
}

static void print_summary(const cli_options *o, const sim *s, const sim_frame *last,
                          double wall_s) {
    const manoeuvre_result *m = sim_manoeuvre(s);
    double sim_s = last->t_s;
    double rtf = wall_s > 0.0 ? sim_s / wall_s : 0.0;
    static const char *const plants[] = {"vessel", "full"};
    static const char *const laws[] = {"mss", "paper"};
    if (o->json) {
        printf("{\n  \"build\": \"%s\",\n  \"mode\": \"multi-rate\",\n", UUV_NUMERIC_NAME);
        printf("  \"plant\": \"%s\",\n  \"propulsion\": \"%s\",\n", plants[o->plant],
               laws[o->propulsion]);
        printf("  \"sim_time_s\": %.6g,\n  \"wall_time_s\": %.6g,\n", sim_s, wall_s);
        printf("  \"realtime_factor\": %.6g,\n", rtf);
        printf("  \"steps\": {\"fast\": 0, \"medium\": 0, \"control\": 0, \"slow\": %u},\n",
               (unsigned)last->index);
        printf("  \"final\": {");
        for (int i = 0; i < 12; i++) {
            printf("\"%s\": %.10g, ", vessel_state_names[i], last->x[i]);
        }
        printf("\"n_rpm\": %.10g}", last->x[VESSEL_N_RPM]);
        if (m->turn_executed && !m->zigzag) {
            printf(",\n  \"turning_circle\": {\"advance_m\": %.6g, \"transfer_m\": %.6g, "
                   "\"tactical_diameter_m\": %.6g, \"steady_diameter_m\": %.6g, "
                   "\"speed_loss_pct\": %.6g}",
                   m->has_advance ? m->advance_m : 0.0, m->has_advance ? m->transfer_m : 0.0,
                   m->has_tactical ? m->tactical_diameter_m : 0.0,
                   m->has_steady ? m->steady_diameter_m : 0.0,
                   m->has_steady ? m->speed_loss_pct : 0.0);
        }
        if (m->zigzag) {
            printf(",\n  \"zigzag\": {\"overshoot_deg\": [");
            for (size_t i = 0; i < m->n_overshoots; i++) {
                printf("%s%.6g", i ? ", " : "", m->overshoot_deg[i]);
            }
            printf("], \"period_s\": %.6g}", m->period_s);
        }
        printf("\n}\n");
        return;
    }
    printf("uuvsim %s, %s build: plant %s, propulsion %s\n", UUVSIM_VERSION, UUV_NUMERIC_NAME,
           plants[o->plant], laws[o->propulsion]);
    printf("simulated %.1f s in %.3f s of wall time (%.0fx real time), %u slow frames\n",
           sim_s, wall_s, rtf, (unsigned)last->index);
    printf("final: u %.3f m/s, position N %.1f E %.1f depth %.2f m, heading %.1f deg, "
           "shaft %.0f rpm\n",
           last->x[VESSEL_U_MPS], last->x[VESSEL_X_M], last->x[VESSEL_Y_M],
           last->x[VESSEL_Z_M], last->x[VESSEL_PSI_RAD] * 57.29577951308232,
           last->x[VESSEL_N_RPM]);
    if (m->turn_executed && !m->zigzag) {
        printf("turning circle:");
        if (m->has_advance) {
            printf(" advance %.1f m, transfer %.1f m", m->advance_m, m->transfer_m);
        }
        if (m->has_tactical) {
            printf(", tactical diameter %.1f m", m->tactical_diameter_m);
        }
        if (m->has_steady) {
            printf(", steady diameter %.1f m, speed loss %.1f %%", m->steady_diameter_m,
                   m->speed_loss_pct);
        }
        if (!m->has_advance) {
            printf(" the heading did not change by 90 deg");
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
}

static int run(const cli_options *o) {
    size_t len = 0;
    char *text = read_file(o->scenario_path, &len);
    if (text == NULL) {
        return 2;
    }
    static scenario scn;
    scenario_error err;
    bool ok = scenario_parse(&scn, text, len, &err);
    free(text);
    if (!ok) {
        fprintf(stderr, "uuvsim: %s:%u: %s%s%s%s\n", o->scenario_path, err.line,
                err.field[0] ? "field '" : "", err.field, err.field[0] ? "': " : "",
                err.message);
        return 2;
    }
    if (o->duration_s <= 0.0 && scn.duration_s <= 0.0) {
        fprintf(stderr, "uuvsim: %s: no duration (give 'duration <s>' or --duration)\n",
                o->scenario_path);
        return 2;
    }
    sim_config cfg;
    sim_config_default(&cfg);
    cfg.plant = (sim_plant)o->plant;
    cfg.propulsion = (vessel_propulsion)o->propulsion;
    cfg.duration_s = o->duration_s;
    static sim s;
    sim_status st = sim_init(&s, &cfg, &scn);
    if (st == SIM_ERR_PLANT) {
        fprintf(stderr, "uuvsim: --plant full: the electric drive is not in this version\n");
        return 2;
    }
    if (st != SIM_OK) {
        fprintf(stderr, "uuvsim: the simulation refused its configuration (status %d)\n",
                (int)st);
        return 2;
    }
    csv_out csv;
    if (o->csv_path != NULL && !csv_out_open(&csv, o->csv_path)) {
        return 2;
    }
    double w0 = wall_seconds();
    sim_frame f;
    for (;;) {
        sim_frame_get(&s, &f);
        if (o->csv_path != NULL) {
            csv_out_frame(&csv, &f);
        }
        if (sim_done(&s)) {
            break;
        }
        sim_step(&s);
    }
    double wall = wall_seconds() - w0;
    if (o->csv_path != NULL && !csv_out_close(&csv)) {
        return 2;
    }
    if (!o->quiet) {
        print_summary(o, &s, &f, wall);
    }
    return 0;
}

int main(int argc, char **argv) {
    cli_options o;
    char err[256];
    if (!cli_parse(argc, argv, &o, err, sizeof err)) {
        fprintf(stderr, "uuvsim: %s\n", err);
        return 2;
    }
    switch (o.action) {
    case CLI_HELP:
        fputs(cli_usage, stdout);
        return 0;
    case CLI_VERSION:
        printf("uuvsim %s (%s build)\n", UUVSIM_VERSION, UUV_NUMERIC_NAME);
        return 0;
    case CLI_DERIVS:
        return uuvsim_derivs(o.derivs_path);
    case CLI_RUN:
        break;
    }
    return run(&o);
}
