/*
 * property: no value the desk simulator reports is ever NaN or infinite,
 * over random in-range inputs (docs/reliability.md), in one numeric build.
 *
 *   property CASES SEED [MAX_DURATION_S]
 *
 * Each case is a random scenario, written as text and read by the scenario
 * parser: every one of the 17 vessel states drawn inside the range the
 * parser accepts, two random sets of commands (fins, shaft speed,
 * buoyancy, a third of them with heading and depth set points for the
 * autopilots) at t = 0 and half-way, a random propulsion law; the vessel
 * plant for up to MAX_DURATION_S (default 20 s), one case in 16 with the
 * full plant for 0.3 s. The parser must accept it; the run must end with
 * EXEC_DONE, or, under `mss` only, at the guard (EXEC_STOP_NONFINITE): the
 * reference law accelerates a vehicle moving astern without bound
 * (docs/vessel.md). Every record, the counters and the manoeuvre results
 * (what the CSV and the summary are made of) must be finite.
 * Prints the counts, then "N passed, N failed".
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "executive.h"
#include "uuv_config.h"

static uint64_t rng_state;

/* xorshift64*: a uniform double in [-1, 1). */
static double rnd(void) {
    rng_state ^= rng_state >> 12;
    rng_state ^= rng_state << 25;
    rng_state ^= rng_state >> 27;
    uint64_t r = rng_state * 2685821657736338717ull;
    return (double)(r >> 11) * (2.0 / 9007199254740992.0) - 1.0;
}

/* The half-widths of the ranges the scenario parser accepts (src/scenario.c). */
static const double state_lim[VESSEL_NSTATES] = {
    5.0,  3.0,  3.0,   5.0,    3.0,    3.0,    1000.0, 1000.0, 100.0,
    3.14, 1.39, 6.283, 0.785, 0.785, 0.785, 0.785, 1500.0};

static size_t make_case(char *buf, size_t cap, double dur, bool full) {
    size_t n = (size_t)snprintf(buf, cap, "duration %.1f\ninit", dur);
    for (int i = 0; i < VESSEL_NSTATES; i++) {
        double v = rnd() * state_lim[i];
        if (i == VESSEL_Z_M) {
            v = fabs(v);
        }
        if (i != VESSEL_N_RPM || !full) { /* the full plant's motor starts at rest */
            n += (size_t)snprintf(buf + n, cap - n, " %s=%.6g", vessel_state_names[i], v);
        }
    }
    for (int j = 0; j < 2; j++) {
        n += (size_t)snprintf(buf + n, cap - n,
                              "\nat %.1f rudder=%.4f stern=%.4f bow_port=%.4f bow_stbd=%.4f "
                              "n_rpm=%.1f buoyancy=%.1f",
                              j * floor(dur * 5.0) / 10.0, rnd() * 0.785, rnd() * 0.785,
                              rnd() * 0.785, rnd() * 0.785, rnd() * 1500.0, rnd() * 5340.0);
        if (rnd() > 0.3) { /* the autopilots, in a third of the command sets */
            n += (size_t)snprintf(buf + n, cap - n, " heading=%.4f depth=%.2f", rnd() * 6.28,
                                  (rnd() + 1.0) * 100.0);
        }
    }
    n += (size_t)snprintf(buf + n, cap - n, "\n");
    return n;
}

static bool frame_finite(const exec_frame *f) {
    const double v[8] = {f->t_s, f->te_nm, f->i_rms_a, f->v_dc_v,
                         f->i_batt_a, f->soc, f->m_index, f->f_hz};
    bool ok = true;
    for (int i = 0; i < VESSEL_NSTATES; i++) {
        ok = ok && isfinite(f->x[i]);
    }
    for (int i = 0; i < EXEC_NCMD; i++) {
        ok = ok && isfinite(f->cmd[i]);
    }
    for (int i = 0; i < 8; i++) {
        ok = ok && isfinite(v[i]);
    }
    return ok;
}

static bool results_finite(const exec *e) {
    const exec_counters *c = &e->count;
    const manoeuvre_result *m = exec_manoeuvre(e);
    const double v[10] = {c->e_batt_j,    c->e_mech_j,       c->e_loss_filter_j,
                          c->e_loss_motor_j, c->limit_s,     m->advance_m,
                          m->transfer_m,  m->tactical_diameter_m, m->steady_diameter_m,
                          m->speed_loss_pct};
    bool ok = isfinite(m->period_s);
    for (int i = 0; i < 10; i++) {
        ok = ok && isfinite(v[i]);
    }
    for (size_t i = 0; i < m->n_overshoots; i++) {
        ok = ok && isfinite(m->overshoot_deg[i]);
    }
    return ok;
}

static scenario scn;
static exec ex;

int main(int argc, char **argv) {
    if (argc < 3) {
        fprintf(stderr, "usage: property CASES SEED [MAX_DURATION_S]\n");
        return 2;
    }
    const long cases = strtol(argv[1], NULL, 10);
    rng_state = 0x9E3779B97F4A7C15ull ^ (uint64_t)strtoull(argv[2], NULL, 10);
    const double maxdur = (argc > 3) ? strtod(argv[3], NULL) : 20.0;
    long pass = 0, fail = 0, guard = 0, full_cases = 0, frames = 0;
    for (long k = 0; k < cases; k++) {
        const bool full = (k % 16) == 15;
        exec_config cfg;
        exec_config_default(&cfg);
        cfg.plant = full ? EXEC_PLANT_FULL : EXEC_PLANT_VESSEL;
        cfg.propulsion = (rnd() < 0.0) ? VESSEL_PROP_PAPER : VESSEL_PROP_MSS;
        const double dur = full ? 0.3 : 0.1 * floor(1.0 + (rnd() + 1.0) * 5.0 * maxdur);
        static char text[2048];
        size_t len = make_case(text, sizeof text, dur, full);
        scenario_error err;
        const char *why = NULL;
        if (!scenario_parse(&scn, text, len, &err)) {
            why = err.message;
        } else if (exec_init(&ex, &cfg, &scn) != EXEC_OK) {
            why = "exec_init refused the case";
        } else {
            exec_frame f;
            bool finite = true;
            while (ex.state == EXEC_RUNNING) {
                (void)exec_desk_run(&ex, UINT32_MAX);
                if (exec_report_take(&ex, &f)) {
                    finite = finite && frame_finite(&f);
                }
            }
            frames += (long)ex.frame;
            const bool guarded =
                ex.state == EXEC_STOP_NONFINITE && cfg.propulsion == VESSEL_PROP_MSS;
            guard += guarded ? 1 : 0;
            if (ex.state != EXEC_DONE && !guarded) {
                why = (ex.state == EXEC_STOP_NONFINITE) ? "the guard stopped a `paper` run"
                                                        : "the run stopped early";
            } else if (!finite || !results_finite(&ex)) {
                why = "a non-finite value reached the results";
            }
        }
        full_cases += full ? 1 : 0;
        if (why == NULL) {
            pass++;
        } else {
            fail++;
            if (fail <= 5) {
                printf("  FAIL  case %ld (%s, %s): %s\n%s", k, full ? "full" : "vessel",
                       cfg.propulsion == VESSEL_PROP_MSS ? "mss" : "paper", why, text);
            }
        }
    }
    printf("  %s build: %ld random cases (seed %s, %ld with the full plant, %ld slow frames): "
           "%ld finite, %ld of them (mss) stopped at the guard\n",
           UUV_NUMERIC_NAME, cases, argv[2], full_cases, frames, pass, guard);
    printf("%ld passed, %ld failed\n", pass, fail);
    return fail == 0 ? 0 : 1;
}
