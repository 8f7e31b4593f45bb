/*
 * uuvsim-decode: turns the telemetry stream of a firmware run (its UART
 * output, frames of src/telemetry.h) into the desk simulator's CSV, written
 * by the same csv_header()/csv_row(), so that the two compare byte for byte,
 * and into a JSON summary of the run: steps, overruns, the instruction
 * counts of tools/qemu_insn_plugin.c when given, and the `final` block of
 * the desk simulator's summary, in its format.
 *
 *   uuvsim-decode TELEMETRY.bin [--csv OUT.csv] [--json OUT.json]
 *                 [--insn COUNTS.txt --shift N] [--scenario NAME]
 *
 * Exit status: 0 for a complete, intact stream (the run's own outcome is in
 * the summary), 3 when that run stopped at its guard (a non-finite state);
 * 2 for bad input: an unreadable file, a truncated or corrupt
 * frame, frames out of order or missing, a bad option. Output files are
 * written whole or not at all.
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "csv_out.h"
#include "telemetry.h"
#include "uuv_config.h"

#define MAX_INPUT_BYTES (256u << 20)
#define MAX_STATS 32

typedef struct {
    const char *in_path, *csv_path, *json_path, *insn_path, *scenario;
    int shift; /* -icount shift, -1 when not given */
} options;

typedef struct {
    char name[64];
    unsigned long long count, min, max, sum;
} insn_stat;

typedef struct {
    insn_stat stats[MAX_STATS];
    int n_stats;
    unsigned long long total, errors;
    bool present;
} insn_counts;

typedef struct {
    tlm_start start;
    tlm_end end;
    exec_frame last;
    unsigned long records;
} stream;

static const char *prog = "uuvsim-decode";

static int usage_error(const char *what, const char *arg) {
    fprintf(stderr, "%s: %s%s\nusage: %s TELEMETRY.bin [--csv OUT.csv] [--json OUT.json] "
                    "[--insn COUNTS.txt --shift N] [--scenario NAME]\n",
            prog, what, arg, prog);
    return 2;
}

static int parse_options(int argc, char **argv, options *o) {
    *o = (options){NULL, NULL, NULL, NULL, NULL, -1};
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        const char **slot = strcmp(a, "--csv") == 0        ? &o->csv_path
                            : strcmp(a, "--json") == 0     ? &o->json_path
                            : strcmp(a, "--insn") == 0     ? &o->insn_path
                            : strcmp(a, "--scenario") == 0 ? &o->scenario
                                                           : NULL;
        if (slot != NULL || strcmp(a, "--shift") == 0) {
            if (i + 1 >= argc || argv[i + 1][0] == '\0') {
                return usage_error("expected a value after ", a);
            }
            const char *v = argv[++i];
            if (slot != NULL) {
                *slot = v;
            } else {
                char *end = NULL;
                long s = strtol(v, &end, 10);
                if (*end != '\0' || s < 0 || s > 10) {
                    return usage_error("--shift: expected 0..10, got ", v);
                }
                o->shift = (int)s;
            }
        } else if (a[0] == '-' || o->in_path != NULL) {
            return usage_error("unexpected argument ", a);
        } else {
            o->in_path = a;
        }
    }
    return o->in_path == NULL ? usage_error("no telemetry file", "") : 0;
}

static unsigned char *read_all(const char *path, size_t *n) {
    FILE *f = fopen(path, "rb");
    if (f == NULL) {
        fprintf(stderr, "%s: %s: cannot open: %s\n", prog, path, strerror(errno));
        return NULL;
    }
    unsigned char *buf = malloc(MAX_INPUT_BYTES + 1u);
    *n = buf ? fread(buf, 1, MAX_INPUT_BYTES + 1u, f) : 0u;
    bool bad = ferror(f) != 0 || buf == NULL || *n > MAX_INPUT_BYTES;
    fclose(f);
    if (bad) {
        fprintf(stderr, "%s: %s: cannot read (or larger than 256 MiB)\n", prog, path);
        free(buf);
        return NULL;
    }
    return buf;
}

/* ---- The stream ------------------------------------------------------------- */

static bool stream_error(const char *path, size_t at, unsigned long frame, const char *what) {
    fprintf(stderr, "%s: %s: byte %zu, frame %lu: %s\n", prog, path, at, frame, what);
    return false;
}

/* Checks one frame's place in the stream: START first, records in order, END last. */
static bool frame_in_order(const char *path, size_t at, unsigned long k, const tlm_frame *f,
                           bool ended) {
    if (f->seq != (uint16_t)k) {
        return stream_error(path, at, k, "sequence number out of order (a frame was lost)");
    }
    if (ended) {
        return stream_error(path, at, k, "data after the end frame");
    }
    if ((k == 0u) != (f->type == TLM_START)) {
        return stream_error(path, at, k,
                            k == 0u ? "the stream does not begin with a start frame"
                                    : "a second start frame");
    }
    return true;
}

static bool record_finite(const exec_frame *r) {
    const double v[7] = {r->te_nm, r->i_rms_a, r->v_dc_v, r->i_batt_a, r->soc, r->m_index, r->f_hz};
    bool ok = isfinite(r->t_s);
    for (int i = 0; i < VESSEL_NSTATES; i++) {
        ok = ok && isfinite(r->x[i]);
    }
    for (int i = 0; i < EXEC_NCMD; i++) {
        ok = ok && isfinite(r->cmd[i]);
    }
    for (int i = 0; i < 7; i++) {
        ok = ok && isfinite(v[i]);
    }
    return ok;
}

/* Decodes every frame, writing the records to csv (may be NULL). */
static bool decode(const char *path, const unsigned char *buf, size_t n, FILE *csv, stream *s) {
    size_t at = 0;
    unsigned long k = 0;
    bool ended = false;
    bool full = false;
    while (at < n) {
        tlm_frame f;
        tlm_status st = tlm_frame_check(buf + at, n - at, &f);
        if (st != TLM_OK) {
            return stream_error(path, at, k, tlm_status_text(st));
        }
        if (!frame_in_order(path, at, k, &f, ended)) {
            return false;
        }
        if (f.type == TLM_START) {
            tlm_decode_start(&f, &s->start);
            if (s->start.version != TLM_VERSION || s->start.plant > EXEC_PLANT_FULL) {
                return stream_error(path, at, k, "unknown protocol version or plant");
            }
            full = s->start.plant == EXEC_PLANT_FULL;
            if (csv != NULL) {
                csv_header(csv, full);
            }
        } else if (f.type == TLM_RECORD) {
            tlm_decode_record(&f, &s->last);
            if (s->last.index != s->records) {
                return stream_error(path, at, k, "record index out of order");
            }
            if (!record_finite(&s->last)) {
                return stream_error(path, at, k, "a record holds a NaN or an infinite value "
                                                 "(the firmware's guard never sends one)");
            }
            s->records++;
            if (csv != NULL) {
                csv_row(csv, &s->last, full);
            }
        } else if (f.type != TLM_END) {
            return stream_error(path, at, k, "a frame of the multi-party link (LINK_UP or "
                                             "LINK_DOWN), not of a telemetry stream");
        } else {
            tlm_decode_end(&f, &s->end);
            if (!isfinite(s->end.e_batt_j) || !isfinite(s->end.e_mech_j)) {
                return stream_error(path, at, k, "the end frame's energies are not finite");
            }
            ended = true;
        }
        at += f.frame_len;
        k++;
    }
    if (!ended) {
        return stream_error(path, at, k,
                            k == 0u ? "empty: no frames"
                                    : "the stream ends without its end frame (truncated: the "
                                      "target stopped before finishing)");
    }
    return true;
}

/* ---- Instruction counts ---------------------------------------------------- */

static bool read_insn(const char *path, insn_counts *c) {
    FILE *f = fopen(path, "r");
    if (f == NULL) {
        fprintf(stderr, "%s: %s: cannot open: %s\n", prog, path, strerror(errno));
        return false;
    }
    char line[256];
    while (fgets(line, sizeof line, f) != NULL) {
        insn_stat s;
        if (strchr(line, '-') != NULL) { /* %llu would take "-5" as 2^64 - 5 */
            fprintf(stderr, "%s: %s: a negative count: %s", prog, path, line);
            fclose(f);
            return false;
        }
        if (sscanf(line, "stat %63s count %llu min %llu max %llu sum %llu", s.name, &s.count,
                   &s.min, &s.max, &s.sum) == 5 &&
            c->n_stats < MAX_STATS) {
            c->stats[c->n_stats++] = s;
        } else if (sscanf(line, "total %llu", &c->total) != 1 &&
                   sscanf(line, "errors %llu", &c->errors) != 1) {
            fprintf(stderr, "%s: %s: unreadable line: %s", prog, path, line);
            fclose(f);
            return false;
        }
    }
    fclose(f);
    c->present = true;
    return true;
}

static const insn_stat *find_stat(const insn_counts *c, const char *name) {
    for (int i = 0; i < c->n_stats; i++) {
        if (strcmp(c->stats[i].name, name) == 0) {
            return &c->stats[i];
        }
    }
    return NULL;
}

/* The JSON members of the instruction counts: what the firmware names what. */
static const struct {
    const char *json, *stat;
} insn_names[] = {
    {"fast_tick", "fast"},
    {"drive_fast", "drive_fast"},
    {"motor_tick", "medium"},
    {"control_tick", "control"},
    {"controller", "controller"},
    {"background_step", "background"},
};

static void json_insn(FILE *f, const insn_counts *c) {
    fprintf(f, "  \"insn\": {");
    for (size_t i = 0; i < sizeof insn_names / sizeof insn_names[0]; i++) {
        const insn_stat *s = find_stat(c, insn_names[i].stat);
        if (s == NULL || s->count == 0) {
            fprintf(f, "\n    \"%s\": null,", insn_names[i].json);
            continue;
        }
        fprintf(f, "\n    \"%s\": {\"count\": %llu, \"min\": %llu, \"mean\": %.1f, \"max\": %llu},",
                insn_names[i].json, s->count, s->min, (double)s->sum / (double)s->count,
                s->max);
    }
    fprintf(f, "\n    \"total\": %llu, \"errors\": %llu\n  },\n", c->total, c->errors);
}

/* Share of the simulated time each rate's instructions take at 2^shift ns each. */
static void json_load(FILE *f, const insn_counts *c, const stream *s, int shift) {
    double span_ns = (double)s->end.fast * (double)s->start.fast_ns;
    static const char *const rates[4] = {"fast", "medium", "control", "background"};
    double total = 0.0;
    fprintf(f, "  \"cpu_load\": {");
    bool all = true;
    for (int i = 0; i < 4; i++) {
        const insn_stat *st = find_stat(c, rates[i]);
        if (st == NULL || !(span_ns > 0.0)) {
            fprintf(f, "\"%s\": null, ", rates[i]);
            all = false;
            continue;
        }
        double load = (double)st->sum * (double)(1u << shift) / span_ns;
        total += load;
        fprintf(f, "\"%s\": %.4f, ", rates[i], load);
    }
    if (all) {
        fprintf(f, "\"total\": %.4f},\n", total);
    } else {
        fprintf(f, "\"total\": null},\n");
    }
}

/* ---- The summary -------------------------------------------------------------- */

static const char *state_name(const tlm_end *e) {
    if ((e->overruns_fast | e->overruns_medium | e->overruns_control | e->overruns_slow) != 0u) {
        return "overrun";
    }
    return e->state == EXEC_DONE           ? "done"
           : e->state == EXEC_STOP_NONFINITE ? "non-finite"
                                              : "stopped";
}

static void json_final(FILE *f, const stream *s) {
    const exec_frame *r = &s->last;
    fprintf(f, "  \"final\": {");
    for (int i = 0; i < 12; i++) {
        fprintf(f, "\"%s\": %.10g, ", vessel_state_names[i], r->x[i]);
    }
    fprintf(f, "\"n_rpm\": %.10g, \"soc\": %.10g}\n", r->x[VESSEL_N_RPM],
            s->start.plant == EXEC_PLANT_FULL ? r->soc : 1.0);
}

/* A JSON string of at most n bytes of s (to its NUL): quotes, backslashes and controls escaped. */
static void json_string(FILE *f, const char *s, size_t n) {
    fputc('"', f);
    for (size_t i = 0; i < n && s[i] != '\0'; i++) {
        const unsigned char ch = (unsigned char)s[i];
        if (ch == '"' || ch == '\\') {
            fprintf(f, "\\%c", ch);
        } else if (ch < 0x20u || ch == 0x7fu) {
            fprintf(f, "\\u%04x", ch);
        } else {
            fputc(ch, f);
        }
    }
    fputc('"', f);
}

static void json_summary(FILE *f, const options *o, const stream *s, const insn_counts *c) {
    const tlm_end *e = &s->end;
    fputs("{\n  \"machine\": ", f);
    json_string(f, s->start.machine, sizeof s->start.machine);
    fprintf(f, ",\n  \"build\": \"%s\",\n",
            s->start.numeric == UUV_NUMERIC_FLOAT ? "float" : "fixed");
    if (o->scenario != NULL) {
        fputs("  \"scenario\": ", f);
        json_string(f, o->scenario, strlen(o->scenario));
        fputs(",\n", f);
    }
    if (o->shift >= 0) {
        fprintf(f, "  \"icount_shift\": %d,\n  \"ns_per_insn\": %u,\n", o->shift,
                1u << o->shift);
    }
    fprintf(f, "  \"state\": \"%s\",\n  \"exit_status\": %u,\n", state_name(e), e->exit_status);
    fprintf(f, "  \"sim_time_s\": %.9g,\n  \"records\": %lu,\n", s->last.t_s, s->records);
    fprintf(f, "  \"steps\": {\"fast\": %llu, \"motor\": %llu, \"control\": %llu, "
               "\"slow\": %llu},\n",
            (unsigned long long)e->fast, (unsigned long long)e->medium,
            (unsigned long long)e->control, (unsigned long long)e->slow);
    fprintf(f, "  \"overruns\": %llu,\n", /* summed in 64 bits: it cannot wrap */
            (unsigned long long)e->overruns_fast + e->overruns_medium + e->overruns_control +
                e->overruns_slow);
    fprintf(f, "  \"overruns_by_rate\": {\"fast\": %u, \"motor\": %u, \"control\": %u, "
               "\"slow\": %u},\n",
            e->overruns_fast, e->overruns_medium, e->overruns_control, e->overruns_slow);
    fprintf(f, "  \"saturations\": %u,\n", e->saturations);
    fprintf(f, "  \"battery_energy_wh\": %.9g,\n  \"mechanical_energy_wh\": %.9g,\n", e->e_batt_j / 3600.0,
            e->e_mech_j / 3600.0);
    fprintf(f, "  \"stack_used_bytes\": %u,\n", e->stack_used_bytes);
    if (c->present) {
        json_insn(f, c);
        if (o->shift >= 0) {
            json_load(f, c, s, o->shift);
        }
    }
    json_final(f, s);
    fprintf(f, "}\n");
}

int main(int argc, char **argv) {
    out_program(prog);
    options o;
    if (parse_options(argc, argv, &o) != 0) {
        return 2;
    }
    static insn_counts counts;
    if (o.insn_path != NULL && !read_insn(o.insn_path, &counts)) {
        return 2;
    }
    size_t n = 0;
    unsigned char *buf = read_all(o.in_path, &n);
    if (buf == NULL) {
        return 2;
    }
    static out_file csv, json;
    static stream s;
    const out_spec outs[2] = {{"--csv", o.csv_path}, {"--json", o.json_path}};
    const out_spec ins[2] = {{"the telemetry", o.in_path}, {"--insn", o.insn_path}};
    bool ok = out_check(outs, 2, ins, 2);
    if (ok) {
        out_guard_signals();
    }
    ok = ok && (o.csv_path == NULL || out_open(&csv, o.csv_path)) &&
         (o.json_path == NULL || out_open(&json, o.json_path)) &&
         decode(o.in_path, buf, n, csv.f, &s);
    free(buf);
    if (ok && json.f != NULL) {
        json_summary(json.f, &o, &s, &counts);
    }
    ok = ok && out_finish(&csv);
    ok = ok && out_finish(&json);
    ok = ok && out_commit(&csv) && out_commit(&json);
    if (!ok) {
        out_abort(&csv);
        out_abort(&json);
        return 2;
    }
    if (s.end.state == EXEC_STOP_NONFINITE) {
        fprintf(stderr, "%s: %s: the run stopped: a state became non-finite in slow frame %llu; "
                        "the last record is at t = %.9g s\n",
                prog, o.in_path, (unsigned long long)s.end.slow + 1u, s.last.t_s);
        return 3;
    }
    return 0;
}
