/*
 * uuvsim sweep and sweep-merge (see sweep.h).
 *
 * Sweep file, one statement per line, '#' starts a comment:
 *   scenario FILE              the base scenario (required)
 *   params FILE                the base parameter set (default: the compiled-in one)
 *   options WORD...            uuvsim options of every run (--plant vessel, --duration 30, ...)
 *   set KEY=VALUE              a fixed override of every run
 *   grid KEY VALUE...          a grid axis: every combination of the axes runs
 *   draws N                    Monte Carlo draws per grid point (default 1)
 *   seed S                     the draws' seed (default 1)
 *   uniform KEY LO HI          a key drawn uniformly in [LO, HI)
 *   normal KEY MEAN SD         a key drawn from a normal distribution
 *   metric NAME                a result column (see metric_value)
 * Paths in the file are as given (relative to where the sweep runs).
 */
#include "sweep.h"

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <signal.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#define MAX_WORDS 64
#define MAX_AXES 16
#define MAX_VALUES 256
#define MAX_METRICS 64
#define MAX_RUNS 1000000L
#define TEXT_MAX 4096

typedef struct {
    char *key;
    char *values[MAX_VALUES];
    int n;
} axis;

typedef struct {
    char *key;
    bool normal;
    double a, b; /* lo, hi or mean, sd */
} draw;

typedef struct {
    char *text;     /* the file, as read (the sweep's identity) */
    size_t text_len;
    const char *path;
    char *scenario, *params;
    char *options[MAX_WORDS];
    int n_options;
    char *sets[MAX_WORDS];
    int n_sets;
    axis axes[MAX_AXES];
    int n_axes;
    draw draws[MAX_AXES];
    int n_draws;
    long n_per_point;
    uint64_t seed;
    char *metrics[MAX_METRICS];
    int n_metrics;
    bool wants_csv, wants_trace;
    long n_runs;
} sweep;

static int fail2(const char *format, ...) __attribute__((format(printf, 1, 2)));

static int fail2(const char *format, ...) {
    va_list args;
    va_start(args, format);
    fputs("uuvsim: ", stderr);
    vfprintf(stderr, format, args);
    fputc('\n', stderr);
    va_end(args);
    return 2;
}

static char *read_all(const char *path, size_t *len) {
    FILE *f = fopen(path, "rb");
    if (f == NULL) {
        return NULL;
    }
    size_t cap = 4096, n = 0;
    char *buf = malloc(cap + 1u);
    while (buf != NULL) {
        size_t got = fread(buf + n, 1, cap - n, f);
        n += got;
        if (n < cap) {
            break;
        }
        cap *= 2u;
        char *bigger = (cap <= (16u << 20)) ? realloc(buf, cap + 1u) : NULL;
        if (bigger == NULL) {
            free(buf);
            buf = NULL;
        }
        buf = bigger;
    }
    bool bad = ferror(f) != 0;
    fclose(f);
    if (buf == NULL || bad) {
        free(buf);
        return NULL;
    }
    buf[n] = '\0';
    *len = n;
    return buf;
}

/* Splits at blanks in place; the number of words or MAX_WORDS + 1 when too many. */
static int words(char *p, char **w) {
    int n = 0;
    for (;;) {
        while (*p == ' ' || *p == '\t' || *p == '\r') {
            p++;
        }
        if (*p == '\0') {
            return n;
        }
        if (n == MAX_WORDS) {
            return MAX_WORDS + 1;
        }
        w[n++] = p;
        while (*p != '\0' && *p != ' ' && *p != '\t' && *p != '\r') {
            p++;
        }
        if (*p != '\0') {
            *p++ = '\0';
        }
    }
}

static bool number(const char *t, double *v) {
    char *end = NULL;
    errno = 0;
    *v = strtod(t, &end);
    return end != t && *end == '\0' && errno == 0 && isfinite(*v);
}

/* The metrics that need the run's telemetry CSV or its trace. */
static bool metric_known(const char *m, bool *csv, bool *trace) {
    static const char *const csv_ops[] = {"max:", "min:", "mean:", "last:"};
    static const char *const trace_ops[] = {"ripple:", "pp:"};
    for (size_t i = 0; i < 4u; i++) {
        if (strncmp(m, csv_ops[i], strlen(csv_ops[i])) == 0 && m[strlen(csv_ops[i])] != '\0') {
            *csv = true;
            return true;
        }
    }
    for (size_t i = 0; i < 2u; i++) {
        if (strncmp(m, trace_ops[i], strlen(trace_ops[i])) == 0 &&
            m[strlen(trace_ops[i])] != '\0') {
            *trace = true;
            return true;
        }
    }
    return strspn(m, "abcdefghijklmnopqrstuvwxyz0123456789_.") == strlen(m);
}

static int parse_sweep(sweep *s, const char *path) {
    *s = (sweep){0};
    s->path = path;
    s->n_per_point = 1;
    s->seed = 1u;
    s->text = read_all(path, &s->text_len);
    if (s->text == NULL) {
        return fail2("%s: cannot read: %s", path, strerror(errno));
    }
    char *copy = strdup(s->text);
    if (copy == NULL) {
        return fail2("out of memory");
    }
    unsigned line = 0;
    for (char *p = copy; p != NULL && *p != '\0';) {
        line++;
        char *nl = strchr(p, '\n');
        if (nl != NULL) {
            *nl = '\0';
        }
        char *hash = strchr(p, '#');
        if (hash != NULL) {
            *hash = '\0';
        }
        char *w[MAX_WORDS + 1];
        int n = words(p, w);
        p = (nl != NULL) ? nl + 1 : NULL;
        if (n == 0) {
            continue;
        }
        if (n > MAX_WORDS) {
            return fail2("%s:%u: more than %d words", path, line, MAX_WORDS);
        }
        const char *cmd = w[0];
        double a = 0.0, b = 0.0;
        if (strcmp(cmd, "scenario") == 0 && n == 2) {
            s->scenario = w[1];
        } else if (strcmp(cmd, "params") == 0 && n == 2) {
            s->params = w[1];
        } else if (strcmp(cmd, "options") == 0) {
            for (int i = 1; i < n; i++) {
                if (s->n_options == MAX_WORDS) {
                    return fail2("%s:%u: options: at most %d words", path, line, MAX_WORDS);
                }
                s->options[s->n_options++] = w[i];
            }
        } else if (strcmp(cmd, "set") == 0 && n == 2 && strchr(w[1], '=') != NULL) {
            if (s->n_sets == MAX_WORDS) {
                return fail2("%s:%u: set: at most %d overrides", path, line, MAX_WORDS);
            }
            s->sets[s->n_sets++] = w[1];
        } else if (strcmp(cmd, "grid") == 0 && n >= 3) {
            if (s->n_axes == MAX_AXES) {
                return fail2("%s:%u: grid: at most %d axes", path, line, MAX_AXES);
            }
            axis *x = &s->axes[s->n_axes++];
            x->key = w[1];
            for (int i = 2; i < n; i++) {
                if (!number(w[i], &a)) {
                    return fail2("%s:%u: grid %s: expected numbers, got '%s'", path, line, w[1],
                                 w[i]);
                }
                x->values[x->n++] = w[i];
            }
        } else if (strcmp(cmd, "draws") == 0 && n == 2) {
            if (!number(w[1], &a) || a < 1.0 || a > 100000.0 || a != floor(a)) {
                return fail2("%s:%u: draws: expected a whole number in [1, 100000], got '%s'",
                             path, line, w[1]);
            }
            s->n_per_point = (long)a;
        } else if (strcmp(cmd, "seed") == 0 && n == 2) {
            if (!number(w[1], &a) || a < 0.0 || a > 9007199254740992.0 || a != floor(a)) {
                return fail2("%s:%u: seed: expected a whole number in [0, 2^53], got '%s'", path,
                             line, w[1]);
            }
            s->seed = (uint64_t)a;
        } else if ((strcmp(cmd, "uniform") == 0 || strcmp(cmd, "normal") == 0) && n == 4) {
            bool normal = (cmd[0] == 'n');
            if (!number(w[2], &a) || !number(w[3], &b) || (normal ? !(b >= 0.0) : !(b > a))) {
                return fail2("%s:%u: %s %s: expected %s, got '%s %s'", path, line, cmd, w[1],
                             normal ? "MEAN SD (SD >= 0)" : "LO HI (LO < HI)", w[2], w[3]);
            }
            if (s->n_draws == MAX_AXES) {
                return fail2("%s:%u: at most %d drawn keys", path, line, MAX_AXES);
            }
            s->draws[s->n_draws++] = (draw){w[1], normal, a, b};
        } else if (strcmp(cmd, "metric") == 0 && n == 2) {
            if (!metric_known(w[1], &s->wants_csv, &s->wants_trace)) {
                return fail2("%s:%u: metric: expected a summary path (final.u_mps), "
                             "max:/min:/mean:/last:COLUMN or ripple:/pp:COLUMN, got '%s'",
                             path, line, w[1]);
            }
            if (s->n_metrics == MAX_METRICS) {
                return fail2("%s:%u: at most %d metrics", path, line, MAX_METRICS);
            }
            s->metrics[s->n_metrics++] = w[1];
        } else {
            return fail2("%s:%u: '%s': expected scenario FILE, params FILE, options WORD..., "
                         "set KEY=VALUE, grid KEY VALUE..., draws N, seed S, uniform KEY LO HI, "
                         "normal KEY MEAN SD or metric NAME", path, line, cmd);
        }
    }
    if (s->scenario == NULL) {
        return fail2("%s: no scenario (expected a line 'scenario FILE')", path);
    }
    long runs = s->n_per_point;
    for (int i = 0; i < s->n_axes; i++) {
        runs *= s->axes[i].n;
        if (runs > MAX_RUNS) {
            return fail2("%s: more than %ld runs", path, MAX_RUNS);
        }
    }
    s->n_runs = runs;
    return 0;
}

/* ---- The variants ----------------------------------------------------------- */

static uint64_t splitmix(uint64_t *x) {
    uint64_t z = (*x += 0x9E3779B97F4A7C15u);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9u;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBu;
    return z ^ (z >> 31);
}

/* A uniform number in (0, 1), 53 bits. */
static double uniform01(uint64_t *x) {
    return ((double)(splitmix(x) >> 11) + 0.5) * (1.0 / 9007199254740992.0);
}

/*
 * The value of parameter column c of run r, as text: a grid axis's value as
 * written, or a draw made from the seed, the run and the key alone (so that
 * any shard draws the same).
 */
static void variant_value(const sweep *s, long r, int c, char *buf, size_t len) {
    if (c < s->n_axes) {
        long g = r / s->n_per_point;
        for (int i = s->n_axes - 1; i > c; i--) {
            g /= s->axes[i].n;
        }
        snprintf(buf, len, "%s", s->axes[c].values[g % s->axes[c].n]);
        return;
    }
    const draw *d = &s->draws[c - s->n_axes];
    uint64_t x = s->seed * 0xD1B54A32D192ED03u + (uint64_t)r * 0x8CB92BA72F3D8DD7u +
                 (uint64_t)(c + 1) * 0x9E3779B97F4A7C15u;
    (void)splitmix(&x);
    double v;
    if (d->normal) {
        double u1 = uniform01(&x), u2 = uniform01(&x);
        v = d->a + d->b * sqrt(-2.0 * log(u1)) * cos(2.0 * 3.141592653589793 * u2);
    } else {
        v = d->a + (d->b - d->a) * uniform01(&x);
    }
    snprintf(buf, len, "%.17g", v);
}

static const char *param_key_of(const sweep *s, int c) {
    return (c < s->n_axes) ? s->axes[c].key : s->draws[c - s->n_axes].key;
}

/* ---- Metrics ---------------------------------------------------------------- */

typedef struct {
    char path[128];
    double v;
} jvalue;

typedef struct {
    jvalue *v;
    size_t n, cap;
} jflat;

static void jskip(const char **p) {
    while (**p == ' ' || **p == '\n' || **p == '\t' || **p == '\r') {
        (*p)++;
    }
}

static void jput(jflat *f, const char *path, double v) {
    if (f->n == f->cap) {
        f->cap = f->cap ? 2u * f->cap : 64u;
        jvalue *bigger = realloc(f->v, f->cap * sizeof *f->v);
        if (bigger == NULL) {
            return;
        }
        f->v = bigger;
    }
    snprintf(f->v[f->n].path, sizeof f->v[f->n].path, "%s", path);
    f->v[f->n++].v = v;
}

/* Flattens a JSON value into path = number pairs (objects "a.b", arrays "a.0"). */
static bool jparse(const char **p, const char *path, jflat *f, int depth) {
    jskip(p);
    char sub[128];
    if (depth > 16) {
        return false;
    }
    if (**p == '{' || **p == '[') {
        bool obj = (**p == '{');
        char close = obj ? '}' : ']';
        (*p)++;
        jskip(p);
        for (int i = 0; **p != close; i++) {
            char name[64];
            if (obj) {
                if (**p != '"') {
                    return false;
                }
                const char *end = strchr(*p + 1, '"');
                if (end == NULL || (size_t)(end - *p - 1) >= sizeof name) {
                    return false;
                }
                snprintf(name, sizeof name, "%.*s", (int)(end - *p - 1), *p + 1);
                *p = end + 1;
                jskip(p);
                if (**p != ':') {
                    return false;
                }
                (*p)++;
            } else {
                snprintf(name, sizeof name, "%d", i);
            }
            int k = snprintf(sub, sizeof sub, "%s%s%s", path, path[0] ? "." : "", name);
            if (k < 0 || (size_t)k >= sizeof sub || !jparse(p, sub, f, depth + 1)) {
                return false;
            }
            jskip(p);
            if (**p == ',') {
                (*p)++;
                jskip(p);
            } else if (**p != close) {
                return false;
            }
        }
        (*p)++;
        return true;
    }
    if (**p == '"') {
        const char *q = *p + 1;
        while (*q != '\0' && *q != '"') {
            q += (*q == '\\' && q[1] != '\0') ? 2 : 1;
        }
        if (*q != '"') {
            return false;
        }
        *p = q + 1;
        return true;
    }
    if (strncmp(*p, "true", 4) == 0 || strncmp(*p, "false", 5) == 0) {
        jput(f, path, (**p == 't') ? 1.0 : 0.0);
        *p += (**p == 't') ? 4 : 5;
        return true;
    }
    char *end = NULL;
    double v = strtod(*p, &end);
    if (end == *p) {
        return false;
    }
    jput(f, path, v);
    *p = end;
    return true;
}

static bool jget(const jflat *f, const char *path, double *v) {
    for (size_t i = 0; i < f->n; i++) {
        if (strcmp(f->v[i].path, path) == 0) {
            *v = f->v[i].v;
            return true;
        }
    }
    return false;
}

/* A CSV's column statistics: max, min, mean, last (op), or over one carrier period windows. */
static bool csv_metric(const char *path, const char *op, const char *col, double *out) {
    FILE *f = fopen(path, "r");
    if (f == NULL) {
        return false;
    }
    static char row[1 << 16];
    int index = -1;
    if (fgets(row, sizeof row, f) != NULL) {
        int i = 0;
        for (char *t = strtok(row, ",\n"); t != NULL; t = strtok(NULL, ",\n"), i++) {
            if (strcmp(t, col) == 0) {
                index = i;
            }
        }
    }
    double mx = -HUGE_VAL, mn = HUGE_VAL, sum = 0.0, last = 0.0;
    double *vals = NULL;
    size_t n = 0, cap = 0;
    while (index >= 0 && fgets(row, sizeof row, f) != NULL) {
        int i = 0;
        char *t = row;
        while (i < index && t != NULL) {
            t = strchr(t, ',');
            t = (t != NULL) ? t + 1 : NULL;
            i++;
        }
        if (t == NULL) {
            continue;
        }
        double v = strtod(t, NULL);
        mx = fmax(mx, v);
        mn = fmin(mn, v);
        sum += v;
        last = v;
        if (n == cap) {
            cap = cap ? 2u * cap : 1024u;
            double *bigger = realloc(vals, cap * sizeof *vals);
            if (bigger == NULL) {
                break;
            }
            vals = bigger;
        }
        vals[n++] = v;
    }
    fclose(f);
    bool ok = (index >= 0 && n > 0u);
    if (ok) {
        if (strcmp(op, "max") == 0) {
            *out = mx;
        } else if (strcmp(op, "min") == 0) {
            *out = mn;
        } else if (strcmp(op, "mean") == 0) {
            *out = sum / (double)n;
        } else if (strcmp(op, "last") == 0) {
            *out = last;
        } else if (strcmp(op, "pp") == 0) {
            *out = mx - mn;
        } else {
            /* ripple: the rms of the signal less its mean over a centred window of
             * 100 steps (one 5 kHz carrier period at 2 us). */
            const size_t w = 100u;
            double acc = 0.0;
            size_t m = 0;
            for (size_t k = w / 2u; k + w / 2u < n; k++) {
                double mean = 0.0;
                for (size_t j = k - w / 2u; j < k + w / 2u; j++) {
                    mean += vals[j];
                }
                mean /= (double)w;
                acc += (vals[k] - mean) * (vals[k] - mean);
                m++;
            }
            ok = (m > 0u);
            *out = ok ? sqrt(acc / (double)m) : 0.0;
        }
    }
    free(vals);
    return ok;
}

/*
 * A metric of a finished run: a number of the JSON summary by its path
 * (energy_wh, final.u_mps, turning_circle.tactical_diameter_m,
 * zigzag.overshoot_deg.0, protection.tripped, energy_balance.filter_loss_wh),
 * endurance_h (the time to empty the battery at the run's mean rate of
 * discharge: sim_time / (1 - final.soc)), a telemetry column's max, min,
 * mean or last value, or over the trace window a column's ripple (rms about
 * its mean over a carrier period) or peak-to-peak.
 */
static bool metric_value(const char *m, const jflat *j, const char *csv, const char *trace,
                         double *v) {
    const char *colon = strchr(m, ':');
    if (colon != NULL) {
        char op[16];
        snprintf(op, sizeof op, "%.*s", (int)(colon - m), m);
        bool on_trace = strcmp(op, "ripple") == 0 || strcmp(op, "pp") == 0;
        return csv_metric(on_trace ? trace : csv, op, colon + 1, v);
    }
    if (strcmp(m, "endurance_h") == 0) {
        double t, soc;
        if (!jget(j, "sim_time_s", &t) || !jget(j, "final.soc", &soc) || !(soc < 1.0)) {
            return false;
        }
        *v = t / 3600.0 / (1.0 - soc);
        return true;
    }
    return jget(j, m, v);
}

/* ---- Rows --------------------------------------------------------------------- */

typedef struct {
    char *csv;  /* the row of results.csv, without the newline */
    char *json; /* the run's object in results.json */
} row;

static void csv_text(FILE *f, const char *t) {
    if (strpbrk(t, ",\"\n") == NULL) {
        fputs(t, f);
        return;
    }
    fputc('"', f);
    for (; *t != '\0'; t++) {
        if (*t == '"') {
            fputc('"', f);
        }
        fputc(*t == '\n' ? ' ' : *t, f);
    }
    fputc('"', f);
}

static void json_text(FILE *f, const char *t) {
    fputc('"', f);
    for (; *t != '\0'; t++) {
        if (*t == '"' || *t == '\\') {
            fprintf(f, "\\%c", *t);
        } else if ((unsigned char)*t < 0x20u) {
            fprintf(f, "\\u%04x", (unsigned)(unsigned char)*t);
        } else {
            fputc(*t, f);
        }
    }
    fputc('"', f);
}

static void header(FILE *f, const sweep *s) {
    fputs("run,status,error", f);
    for (int c = 0; c < s->n_axes + s->n_draws; c++) {
        fprintf(f, ",%s", param_key_of(s, c));
    }
    for (int k = 0; k < s->n_metrics; k++) {
        fprintf(f, ",%s", s->metrics[k]);
    }
    fputc('\n', f);
}

/* Writes run r's row file (CSV line, then JSON line) whole, then renames it into place. */
static bool write_row(const sweep *s, const char *dir, long r, int status, const char *error,
                      const jflat *j, const char *csv, const char *trace) {
    char tmp[TEXT_MAX + 32], final[TEXT_MAX];
    snprintf(final, sizeof final, "%s/runs/%06ld.row", dir, r);
    snprintf(tmp, sizeof tmp, "%s.%ld.tmp", final, (long)getpid());
    FILE *f = fopen(tmp, "w");
    if (f == NULL) {
        return false;
    }
    char val[64];
    fprintf(f, "%ld,%d,", r, status);
    csv_text(f, error);
    for (int c = 0; c < s->n_axes + s->n_draws; c++) {
        variant_value(s, r, c, val, sizeof val);
        fprintf(f, ",%s", val);
    }
    double v = 0.0;
    for (int k = 0; k < s->n_metrics; k++) {
        if (status == 0 && metric_value(s->metrics[k], j, csv, trace, &v)) {
            fprintf(f, ",%.10g", v);
        } else {
            fputc(',', f);
        }
    }
    fprintf(f, "\n{\"run\": %ld, \"status\": %d, \"error\": ", r, status);
    json_text(f, error);
    fputs(", \"params\": {", f);
    for (int c = 0; c < s->n_axes + s->n_draws; c++) {
        variant_value(s, r, c, val, sizeof val);
        fprintf(f, "%s\"%s\": %.17g", c ? ", " : "", param_key_of(s, c), strtod(val, NULL));
    }
    fputs("}, \"metrics\": {", f);
    for (int k = 0; k < s->n_metrics; k++) {
        fprintf(f, "%s\"%s\": ", k ? ", " : "", s->metrics[k]);
        if (status == 0 && metric_value(s->metrics[k], j, csv, trace, &v) && isfinite(v)) {
            fprintf(f, "%.10g", v);
        } else {
            fputs("null", f);
        }
    }
    fputs("}}\n", f);
    bool ok = (ferror(f) == 0);
    ok = (fclose(f) == 0) && ok;
    if (!ok || rename(tmp, final) != 0) {
        remove(tmp);
        return false;
    }
    return true;
}

static bool read_row(const char *dir, long r, row *out) {
    char path[TEXT_MAX];
    snprintf(path, sizeof path, "%s/runs/%06ld.row", dir, r);
    size_t len = 0;
    char *text = read_all(path, &len);
    if (text == NULL) {
        return false;
    }
    char *nl = strchr(text, '\n');
    if (nl == NULL || len == 0u || text[len - 1u] != '\n') {
        free(text);
        return false;
    }
    *nl = '\0';
    text[len - 1u] = '\0';
    out->csv = text;
    out->json = nl + 1;
    return true;
}

/* results.csv and results.json of the rows present, in run order, whole or not at all. */
static int write_results(const sweep *s, const char *dir, const char *const *dirs, int n_dirs,
                         long *missing) {
    char path[TEXT_MAX], tmp[TEXT_MAX + 16];
    FILE *fc, *fj;
    snprintf(path, sizeof path, "%s/results.csv", dir);
    snprintf(tmp, sizeof tmp, "%s.partial", path);
    fc = fopen(tmp, "w");
    snprintf(path, sizeof path, "%s/results.json", dir);
    snprintf(tmp, sizeof tmp, "%s.partial", path);
    fj = fopen(tmp, "w");
    if (fc == NULL || fj == NULL) {
        if (fc) fclose(fc);
        if (fj) fclose(fj);
        return fail2("%s: cannot write the results: %s", dir, strerror(errno));
    }
    header(fc, s);
    fputs("{\"sweep\": ", fj);
    json_text(fj, s->text);
    fputs(",\n \"runs\": [", fj);
    *missing = 0;
    bool first = true;
    for (long r = 0; r < s->n_runs; r++) {
        row w;
        bool found = false;
        for (int d = 0; d < n_dirs && !found; d++) {
            found = read_row(dirs[d], r, &w);
        }
        if (!found) {
            (*missing)++;
            continue;
        }
        fprintf(fc, "%s\n", w.csv);
        fprintf(fj, "%s\n  %s", first ? "" : ",", w.json);
        first = false;
        free(w.csv);
    }
    fputs("]}\n", fj);
    bool ok = ferror(fc) == 0 && ferror(fj) == 0;
    ok = (fclose(fc) == 0) && ok;
    ok = (fclose(fj) == 0) && ok;
    const char *names[] = {"results.csv", "results.json"};
    for (int i = 0; i < 2 && ok; i++) {
        snprintf(path, sizeof path, "%s/%s", dir, names[i]);
        snprintf(tmp, sizeof tmp, "%s.partial", path);
        ok = rename(tmp, path) == 0;
    }
    return ok ? 0 : fail2("%s: cannot write the results: %s", dir, strerror(errno));
}

/* ---- Running -------------------------------------------------------------------- */

static volatile sig_atomic_t stop_signal;

static void on_signal(int sig) { stop_signal = sig; }

typedef struct {
    pid_t pid;
    long run;
} child;

static void run_files(const char *dir, long r, pid_t owner, char json[TEXT_MAX], char csv[TEXT_MAX],
                      char trace[TEXT_MAX], char err[TEXT_MAX]) {
    snprintf(json, TEXT_MAX, "%s/runs/%06ld.%ld.json", dir, r, (long)owner);
    snprintf(csv, TEXT_MAX, "%s/runs/%06ld.%ld.csv", dir, r, (long)owner);
    snprintf(trace, TEXT_MAX, "%s/runs/%06ld.%ld.trace.csv", dir, r, (long)owner);
    snprintf(err, TEXT_MAX, "%s/runs/%06ld.%ld.err", dir, r, (long)owner);
}

static pid_t start_run(const sweep *s, const char *self, const char *dir, long r) {
    char json[TEXT_MAX], csv[TEXT_MAX], trace[TEXT_MAX], err[TEXT_MAX];
    pid_t pid = fork();
    if (pid != 0) {
        return pid;
    }
    run_files(dir, r, getpid(), json, csv, trace, err);
    char *argv[4 * MAX_WORDS + 3 * MAX_AXES + 16];
    char sets[2 * MAX_AXES][160];
    int n = 0;
    argv[n++] = (char *)(uintptr_t)self;
    for (int i = 0; i < s->n_options; i++) {
        argv[n++] = s->options[i];
    }
    argv[n++] = (char *)(uintptr_t)"--scenario";
    argv[n++] = s->scenario;
    if (s->params != NULL) {
        argv[n++] = (char *)(uintptr_t)"--params";
        argv[n++] = s->params;
    }
    for (int i = 0; i < s->n_sets; i++) {
        argv[n++] = (char *)(uintptr_t)"--set";
        argv[n++] = s->sets[i];
    }
    for (int c = 0; c < s->n_axes + s->n_draws; c++) {
        char val[64];
        variant_value(s, r, c, val, sizeof val);
        snprintf(sets[c], sizeof sets[c], "%s=%s", param_key_of(s, c), val);
        argv[n++] = (char *)(uintptr_t)"--set";
        argv[n++] = sets[c];
    }
    argv[n++] = (char *)(uintptr_t)"--quiet";
    argv[n++] = (char *)(uintptr_t)"--summary";
    argv[n++] = json;
    if (s->wants_csv) {
        argv[n++] = (char *)(uintptr_t)"--csv";
        argv[n++] = csv;
    }
    if (s->wants_trace) {
        argv[n++] = (char *)(uintptr_t)"--trace";
        argv[n++] = trace;
    }
    argv[n] = NULL;
    int fd = open(err, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    int null = open("/dev/null", O_RDWR);
    if (fd < 0 || null < 0) {
        _exit(126);
    }
    dup2(null, 0);
    dup2(null, 1);
    dup2(fd, 2);
    execv(self, argv);
    fprintf(stderr, "cannot run %s: %s\n", self, strerror(errno));
    _exit(127);
}

/* Collects a finished run's results into its row; removes its scratch files. */
static bool finish_run(const sweep *s, const char *dir, long r, pid_t pid, int wstatus) {
    char json[TEXT_MAX], csv[TEXT_MAX], trace[TEXT_MAX], err[TEXT_MAX];
    run_files(dir, r, pid, json, csv, trace, err);
    int status = WIFEXITED(wstatus) ? WEXITSTATUS(wstatus) : 128 + WTERMSIG(wstatus);
    char error[512] = "";
    size_t len = 0;
    char *text = read_all(err, &len);
    if (text != NULL) {
        /* The last line the run printed on stderr. */
        while (len > 0u && (text[len - 1u] == '\n' || text[len - 1u] == '\r')) {
            text[--len] = '\0';
        }
        char *last = strrchr(text, '\n');
        const char *msg = (last != NULL) ? last + 1 : text;
        if (strncmp(msg, "uuvsim: ", 8) == 0) {
            msg += 8;
        }
        snprintf(error, sizeof error, "%s", msg);
        free(text);
    }
    if (status != 0 && error[0] == '\0') {
        snprintf(error, sizeof error, "%s %d", WIFEXITED(wstatus) ? "exit status" : "signal",
                 WIFEXITED(wstatus) ? status : WTERMSIG(wstatus));
    }
    jflat j = {0};
    char *summary = read_all(json, &len);
    if (summary != NULL) {
        const char *p = summary;
        if (!jparse(&p, "", &j, 0)) {
            j.n = 0;
        }
        free(summary);
    } else if (status == 0) {
        status = 1;
        snprintf(error, sizeof error, "the run wrote no summary");
    }
    bool ok = write_row(s, dir, r, status, error, &j, csv, trace);
    free(j.v);
    remove(json);
    remove(csv);
    remove(trace);
    remove(err);
    return ok;
}

static bool row_done(const char *dir, long r) {
    char path[TEXT_MAX];
    snprintf(path, sizeof path, "%s/runs/%06ld.row", dir, r);
    return access(path, F_OK) == 0;
}

static int usage(void) {
    return fail2("sweep: expected uuvsim sweep FILE --out DIR [-j N] [--shard K/N], or "
                 "uuvsim sweep-merge --out DIR PART_DIR...");
}

/* DIR/sweep.txt: the sweep the directory holds; a different one is refused. */
static int claim_dir(const sweep *s, const char *dir) {
    char path[TEXT_MAX];
    if (mkdir(dir, 0755) != 0 && errno != EEXIST) {
        return fail2("%s: cannot create: %s", dir, strerror(errno));
    }
    snprintf(path, sizeof path, "%s/runs", dir);
    if (mkdir(path, 0755) != 0 && errno != EEXIST) {
        return fail2("%s: cannot create: %s", path, strerror(errno));
    }
    snprintf(path, sizeof path, "%s/sweep.txt", dir);
    size_t len = 0;
    char *held = read_all(path, &len);
    if (held != NULL) {
        bool same = (len == s->text_len && memcmp(held, s->text, len) == 0);
        free(held);
        if (!same) {
            return fail2("%s: holds another sweep (its sweep.txt differs from %s): give another "
                         "--out", dir, s->path);
        }
        return 0;
    }
    char tmp[TEXT_MAX + 16];
    snprintf(tmp, sizeof tmp, "%s.partial", path);
    FILE *f = fopen(tmp, "wb");
    bool ok = f != NULL && fwrite(s->text, 1, s->text_len, f) == s->text_len;
    ok = (f != NULL && fclose(f) == 0) && ok;
    if (!ok || rename(tmp, path) != 0) {
        return fail2("%s: cannot write: %s", path, strerror(errno));
    }
    return 0;
}

static int sweep_run(int argc, char **argv) {
    const char *file = NULL, *dir = NULL;
    long jobs = 1, shard_k = 1, shard_n = 1;
    for (int i = 2; i < argc; i++) {
        if ((strcmp(argv[i], "--out") == 0 || strcmp(argv[i], "-j") == 0 ||
             strcmp(argv[i], "--shard") == 0) && i + 1 < argc) {
            const char *v = argv[++i];
            char *end = NULL;
            if (argv[i - 1][1] == 'j') {
                jobs = strtol(v, &end, 10);
                if (*v == '\0' || *end != '\0' || jobs < 1 || jobs > 1024) {
                    return fail2("sweep: -j: expected a whole number in [1, 1024], got '%s'", v);
                }
            } else if (argv[i - 1][2] == 's') {
                shard_k = strtol(v, &end, 10);
                shard_n = (*end == '/') ? strtol(end + 1, &end, 10) : 0;
                if (*end != '\0' || shard_n < 1 || shard_n > 100000 || shard_k < 1 ||
                    shard_k > shard_n) {
                    return fail2("sweep: --shard: expected K/N with 1 <= K <= N, got '%s'", v);
                }
            } else {
                dir = v;
            }
        } else if (argv[i][0] != '-' && file == NULL) {
            file = argv[i];
        } else {
            return usage();
        }
    }
    if (file == NULL || dir == NULL) {
        return usage();
    }
    sweep s;
    int st = parse_sweep(&s, file);
    if (st != 0) {
        return st;
    }
    st = claim_dir(&s, dir);
    if (st != 0) {
        return st;
    }
    char self[TEXT_MAX];
    ssize_t sl = readlink("/proc/self/exe", self, sizeof self - 1u);
    if (sl <= 0) {
        return fail2("sweep: cannot find the uuvsim program: %s", strerror(errno));
    }
    self[sl] = '\0';
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    long mine = 0, done = 0, failed = 0, todo = 0;
    for (long r = shard_k - 1; r < s.n_runs; r += shard_n) {
        mine++;
        todo += row_done(dir, r) ? 0 : 1;
    }
    fprintf(stderr, "sweep %s: %ld runs%s, %ld to run (%ld done before), %ld at a time\n", file,
            mine, shard_n > 1 ? " in this shard" : "", todo, mine - todo, jobs);
    child *kids = calloc((size_t)jobs, sizeof *kids);
    if (kids == NULL) {
        return fail2("out of memory");
    }
    long next = shard_k - 1;
    long running = 0;
    bool write_failed = false;
    for (;;) {
        while (stop_signal == 0 && running < jobs && next < s.n_runs) {
            long r = next;
            next += shard_n;
            if (row_done(dir, r)) {
                continue;
            }
            pid_t pid = start_run(&s, self, dir, r);
            if (pid < 0) {
                fail2("sweep: cannot start a run: %s", strerror(errno));
                stop_signal = SIGTERM;
                break;
            }
            for (long k = 0; k < jobs; k++) {
                if (kids[k].pid == 0) {
                    kids[k] = (child){pid, r};
                    break;
                }
            }
            running++;
        }
        if (running == 0) {
            break;
        }
        int wstatus = 0;
        pid_t pid = waitpid(-1, &wstatus, 0);
        if (pid < 0) {
            if (errno == EINTR) {
                if (stop_signal != 0) {
                    for (long k = 0; k < jobs; k++) {
                        if (kids[k].pid != 0) {
                            kill(kids[k].pid, SIGTERM);
                        }
                    }
                }
                continue;
            }
            break;
        }
        for (long k = 0; k < jobs; k++) {
            if (kids[k].pid == pid) {
                running--;
                kids[k].pid = 0;
                if (stop_signal != 0) {
                    /* Stopped, not finished: no row, so the resumed sweep runs it again. */
                    char a[TEXT_MAX], b[TEXT_MAX], c[TEXT_MAX], d[TEXT_MAX];
                    run_files(dir, kids[k].run, pid, a, b, c, d);
                    remove(a);
                    remove(b);
                    remove(c);
                    remove(d);
                    break;
                }
                write_failed = !finish_run(&s, dir, kids[k].run, pid, wstatus) || write_failed;
                done++;
                bool bad = !(WIFEXITED(wstatus) && WEXITSTATUS(wstatus) == 0);
                failed += bad ? 1 : 0;
                fprintf(stderr, "  [%ld/%ld] run %ld %s\n", done + mine - todo, mine,
                        kids[k].run, bad ? "failed" : "done");
                break;
            }
        }
    }
    free(kids);
    if (stop_signal != 0) {
        fprintf(stderr, "sweep: stopped by signal %d after %ld runs; run the same command to "
                "resume\n", (int)stop_signal, done);
        return 128 + (int)stop_signal;
    }
    if (write_failed) {
        return fail2("%s: cannot write a row", dir);
    }
    long missing = 0;
    const char *dirs[1] = {dir};
    st = write_results(&s, dir, dirs, 1, &missing);
    if (st != 0) {
        return st;
    }
    fprintf(stderr, "sweep: %ld runs, %ld failed: %s/results.csv, %s/results.json\n", mine,
            failed, dir, dir);
    return 0;
}

static int sweep_merge(int argc, char **argv) {
    const char *dir = NULL;
    const char *parts[1024];
    int n_parts = 0;
    for (int i = 2; i < argc; i++) {
        if (strcmp(argv[i], "--out") == 0 && i + 1 < argc) {
            dir = argv[++i];
        } else if (argv[i][0] != '-' && n_parts < 1024) {
            parts[n_parts++] = argv[i];
        } else {
            return usage();
        }
    }
    if (dir == NULL || n_parts == 0) {
        return usage();
    }
    char path[TEXT_MAX];
    snprintf(path, sizeof path, "%s/sweep.txt", parts[0]);
    sweep s;
    int st = parse_sweep(&s, path);
    if (st != 0) {
        return st;
    }
    for (int d = 1; d < n_parts; d++) {
        snprintf(path, sizeof path, "%s/sweep.txt", parts[d]);
        size_t len = 0;
        char *text = read_all(path, &len);
        bool same = text != NULL && len == s.text_len && memcmp(text, s.text, len) == 0;
        free(text);
        if (!same) {
            return fail2("sweep-merge: %s holds another sweep than %s", parts[d], parts[0]);
        }
    }
    st = claim_dir(&s, dir);
    if (st != 0) {
        return st;
    }
    long missing = 0;
    st = write_results(&s, dir, parts, n_parts, &missing);
    if (st != 0) {
        return st;
    }
    if (missing > 0) {
        fprintf(stderr, "sweep-merge: %ld of %ld runs are missing (a shard not run or not "
                "finished): %s/results.csv has the others\n", missing, s.n_runs, dir);
        return 1;
    }
    fprintf(stderr, "sweep-merge: %ld runs from %d parts: %s/results.csv, %s/results.json\n",
            s.n_runs, n_parts, dir, dir);
    return 0;
}

int sweep_main(int argc, char **argv) {
    return (strcmp(argv[1], "sweep") == 0) ? sweep_run(argc, argv) : sweep_merge(argc, argv);
}
