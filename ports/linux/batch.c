/*
 * uuvsim batch: several runs side by side, their fast steps in SIMD lanes
 * (batch_lanes.h), each run's outputs those of its single run.
 *
 *   uuvsim batch --out DIR [--list FILE] [SCENARIO...] [-- OPTION...]
 *
 * Every SCENARIO given, and every line of the list FILE
 * ("SCENARIO [--name NAME] [OPTION...]", '#' starts a comment), is one run
 * with the OPTIONs after "--" (uuvsim's run options) and then the line's
 * own. Run NAME (the scenario file's name without ".scn", or the line's
 * --name) writes DIR/NAME.csv (the telemetry, as --csv) and
 * DIR/NAME.json (the summary, as --summary); a line may add --trace FILE.
 * The runs advance together, one event tick of the executive at a time:
 * the runs on the real-time path take their steps in lanes
 * (batch_step_all(), batch_fast_run()), any other run (averaged or event
 * inverter, a fault or trip that leaves the real-time path, exact leaps)
 * steps on its own as uuvsim would run it. The steps are the same
 * bits either way, so each run's files are its single run's, byte for
 * byte, except the summary's wall_time_s and realtime_factor, which are
 * timing (the batch's wall time shared equally among its runs).
 *
 * Exit status: 2 for bad input (nothing written: every run is opened and
 * checked before the first step), otherwise the largest of the runs' own
 * statuses (uuvsim.c: 0, 1 or 3).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "batch_lanes.h"
#include "leap.h"
#include "run.h"

#define BATCH_MAX_RUNS 4096
#define BATCH_MAX_WORDS 128
#define BATCH_LINE_MAX 4096

typedef struct {
    cli_options o;
    char name[256];
    char csv[4096], sum[4096];
    char *words[BATCH_MAX_WORDS + 4]; /* argv for cli_parse, into text */
    char text[BATCH_LINE_MAX];
    uuvsim_run *u;
    int status;
    bool done;
} batch_run;

static const char batch_usage[] =
    "usage: uuvsim batch --out DIR [--list FILE] [SCENARIO...] [-- OPTION...]\n";

/* The run's name: the scenario file's, without its directory and ".scn". */
static void default_name(const char *path, char *name, size_t len) {
    const char *b = strrchr(path, '/');
    b = (b != NULL) ? b + 1 : path;
    size_t n = strlen(b);
    if (n > 4u && strcmp(b + n - 4u, ".scn") == 0) {
        n -= 4u;
    }
    if (n >= len) {
        n = len - 1u;
    }
    memcpy(name, b, n);
    name[n] = '\0';
}

/* A name is a file name: not empty, no '/', not "." or "..". */
static bool name_ok(const char *name) {
    return name[0] != '\0' && strchr(name, '/') == NULL && strcmp(name, ".") != 0 &&
           strcmp(name, "..") != 0;
}

/*
 * Builds run r from the scenario path, its own words (a list line's) and
 * the common options; where names the input for messages ("FILE:LINE" or
 * "argument N"). False with a message on bad input.
 */
static bool make_run(batch_run *r, const char *dir, const char *scn_path, char **own, int n_own,
                     char **common, int n_common, const char *where) {
    int n = 0;
    r->words[n++] = "uuvsim";
    const char *name = NULL;
    if (n_own + n_common + 5 > BATCH_MAX_WORDS) {
        fprintf(stderr, "uuvsim: batch: %s: more than %d option words\n", where,
                BATCH_MAX_WORDS);
        return false;
    }
    for (int k = 0; k < n_common; k++) {
        r->words[n++] = common[k];
    }
    for (int k = 0; k < n_own; k++) {
        if (strcmp(own[k], "--name") == 0) {
            if (k + 1 >= n_own) {
                fprintf(stderr, "uuvsim: batch: %s: option --name: expected a name\n", where);
                return false;
            }
            name = own[++k];
            continue;
        }
        r->words[n++] = own[k];
    }
    r->words[n++] = "--scenario";
    r->words[n++] = (char *)scn_path;
    r->words[n] = NULL;
    char err[256];
    if (!cli_parse(n, r->words, &r->o, err, sizeof err)) {
        fprintf(stderr, "uuvsim: batch: %s: %s\n", where, err);
        return false;
    }
    const char *bad = (r->o.action != CLI_RUN) ? "a command" : r->o.csv_path ? "--csv"
                      : r->o.summary_path                  ? "--summary"
                      : r->o.json                          ? "--json"
                      : r->o.view                          ? "--view"
                      : r->o.realtime                      ? "--realtime"
                                                           : NULL;
    if (bad != NULL) {
        fprintf(stderr, "uuvsim: batch: %s: %s is not a batch run's option (its telemetry "
                "and summary go to DIR/NAME.csv and DIR/NAME.json)\n", where, bad);
        return false;
    }
    if (r->o.fast_path == CLI_FAST_LEAP && !leap_available()) {
        fprintf(stderr, "uuvsim: batch: %s: option --fast-path leap: not in the %s build\n",
                where, UUV_NUMERIC_NAME);
        return false;
    }
    if (name != NULL) {
        snprintf(r->name, sizeof r->name, "%s", name);
    } else {
        default_name(scn_path, r->name, sizeof r->name);
    }
    if (!name_ok(r->name)) {
        fprintf(stderr, "uuvsim: batch: %s: run name '%s' is not a file name\n", where, r->name);
        return false;
    }
    snprintf(r->csv, sizeof r->csv, "%s/%s.csv", dir, r->name);
    snprintf(r->sum, sizeof r->sum, "%s/%s.json", dir, r->name);
    r->o.csv_path = r->csv;
    r->o.summary_path = r->sum;
    r->o.quiet = true;
    return true;
}

/* Splits a list line into words at blanks, in place; returns their count or -1 (too many). */
static int split_words(char *s, char **w, int most) {
    int n = 0;
    for (;;) {
        while (*s == ' ' || *s == '\t' || *s == '\r' || *s == '\n') {
            s++;
        }
        if (*s == '\0' || *s == '#') {
            return n;
        }
        if (n == most) {
            return -1;
        }
        w[n++] = s;
        while (*s != '\0' && *s != ' ' && *s != '\t' && *s != '\r' && *s != '\n') {
            s++;
        }
        if (*s != '\0') {
            *s++ = '\0';
        }
    }
}

static batch_run *runs[BATCH_MAX_RUNS];
static size_t n_runs;

static batch_run *new_run(void) {
    if (n_runs == BATCH_MAX_RUNS) {
        fprintf(stderr, "uuvsim: batch: more than %d runs\n", BATCH_MAX_RUNS);
        return NULL;
    }
    batch_run *r = calloc(1u, sizeof *r);
    if (r == NULL) {
        fprintf(stderr, "uuvsim: batch: out of memory\n");
        return NULL;
    }
    runs[n_runs++] = r;
    return r;
}

/* The runs of a list file. */
static bool read_list(const char *path, const char *dir, char **common, int n_common) {
    FILE *f = fopen(path, "r");
    if (f == NULL) {
        fprintf(stderr, "uuvsim: batch: option --list: %s: cannot open\n", path);
        return false;
    }
    char line[BATCH_LINE_MAX];
    unsigned no = 0u;
    bool ok = true;
    while (ok && fgets(line, sizeof line, f) != NULL) {
        no++;
        char where[4200];
        snprintf(where, sizeof where, "%s:%u", path, no);
        if (strchr(line, '\n') == NULL && !feof(f)) {
            fprintf(stderr, "uuvsim: batch: %s: line longer than %d characters\n", where,
                    BATCH_LINE_MAX - 2);
            ok = false;
            break;
        }
        char copy[BATCH_LINE_MAX];
        memcpy(copy, line, sizeof copy);
        char *w[BATCH_MAX_WORDS];
        int n = split_words(copy, w, BATCH_MAX_WORDS);
        if (n == 0) {
            continue;
        }
        if (n < 0) {
            fprintf(stderr, "uuvsim: batch: %s: more than %d words\n", where, BATCH_MAX_WORDS);
            ok = false;
            break;
        }
        batch_run *r = new_run();
        if (r == NULL) {
            ok = false;
            break;
        }
        /* The words live in the run's own text. */
        memcpy(r->text, line, sizeof r->text);
        n = split_words(r->text, w, BATCH_MAX_WORDS);
        if (w[0][0] == '-') {
            fprintf(stderr, "uuvsim: batch: %s: expected a scenario file first, found '%s'\n",
                    where, w[0]);
            ok = false;
            break;
        }
        ok = make_run(r, dir, w[0], w + 1, n - 1, common, n_common, where);
    }
    if (ok && ferror(f)) {
        fprintf(stderr, "uuvsim: batch: option --list: %s: cannot read\n", path);
        ok = false;
    }
    fclose(f);
    if (ok && no == 0u) {
        /* An empty list is caught with the count of runs below. */
    }
    return ok;
}

/* Two runs writing one file would leave only one of them. */
static bool names_distinct(void) {
    for (size_t i = 0; i < n_runs; i++) {
        for (size_t j = 0; j < i; j++) {
            if (strcmp(runs[i]->name, runs[j]->name) == 0) {
                fprintf(stderr, "uuvsim: batch: runs %zu and %zu are both named '%s' (both "
                        "would write %s): give a list line --name NAME\n", j + 1u, i + 1u,
                        runs[i]->name, runs[i]->csv);
                return false;
            }
        }
    }
    return true;
}

static void free_runs(void) {
    for (size_t i = 0; i < n_runs; i++) {
        free(runs[i]);
    }
    n_runs = 0u;
}

/* One pass: every running run to its next event tick (batch_step_all()), then its records. */
static size_t batch_pass(void) {
    static exec *e[BATCH_MAX_RUNS];
    static uint32_t most[BATCH_MAX_RUNS];
    size_t n = 0u;
    for (size_t i = 0; i < n_runs; i++) {
        if (!runs[i]->done) {
            e[n] = uuvsim_run_exec(runs[i]->u);
            most[n++] = uuvsim_run_ahead(runs[i]->u);
        }
    }
    batch_step_all(e, most, n);
    for (size_t i = 0; i < n_runs; i++) {
        batch_run *r = runs[i];
        if (!r->done) {
            uuvsim_run_after(r->u);
            r->done = uuvsim_run_exec(r->u)->state != EXEC_RUNNING;
        }
    }
    return n;
}

int batch_main(int argc, char **argv) {
    const char *dir = NULL;
    const char *list = NULL;
    char *scenarios[BATCH_MAX_RUNS];
    int n_scn = 0;
    char **common = NULL;
    int n_common = 0;
    for (int k = 2; k < argc; k++) {
        const char *a = argv[k];
        if (strcmp(a, "--") == 0) {
            common = argv + k + 1;
            n_common = argc - k - 1;
            break;
        }
        if (strcmp(a, "--out") == 0 || strcmp(a, "--list") == 0) {
            if (k + 1 >= argc) {
                fprintf(stderr, "uuvsim: batch: option %s: expected a %s\n%s", a,
                        a[2] == 'o' ? "directory" : "file", batch_usage);
                return 2;
            }
            *(a[2] == 'o' ? &dir : &list) = argv[++k];
        } else if (strcmp(a, "--help") == 0) {
            fputs(batch_usage, stdout);
            return 0;
        } else if (a[0] == '-') {
            fprintf(stderr, "uuvsim: batch: unknown option '%s' (the runs' options go after "
                    "\"--\")\n%s", a, batch_usage);
            return 2;
        } else if (n_scn == BATCH_MAX_RUNS) {
            fprintf(stderr, "uuvsim: batch: more than %d runs\n", BATCH_MAX_RUNS);
            return 2;
        } else {
            scenarios[n_scn++] = argv[k];
        }
    }
    if (dir == NULL) {
        fprintf(stderr, "uuvsim: batch: option --out: expected the output directory\n%s",
                batch_usage);
        return 2;
    }
    struct stat st;
    if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode)) {
        fprintf(stderr, "uuvsim: batch: option --out: %s: not a directory\n", dir);
        return 2;
    }
    bool ok = true;
    for (int k = 0; ok && k < n_scn; k++) {
        batch_run *r = new_run();
        char where[4200];
        snprintf(where, sizeof where, "%s", scenarios[k]);
        ok = r != NULL && make_run(r, dir, scenarios[k], NULL, 0, common, n_common, where);
    }
    if (ok && list != NULL) {
        ok = read_list(list, dir, common, n_common);
    }
    if (ok && n_runs == 0u) {
        fprintf(stderr, "uuvsim: batch: no runs: give scenario files or --list FILE\n%s",
                batch_usage);
        ok = false;
    }
    ok = ok && names_distinct();
    /* Every run opened (and checked) before any steps. */
    for (size_t i = 0; ok && i < n_runs; i++) {
        runs[i]->u = uuvsim_run_open(&runs[i]->o, &runs[i]->status);
        ok = runs[i]->u != NULL;
        if (ok) {
            batch_lanes_attach(uuvsim_run_exec(runs[i]->u));
        }
    }
    if (!ok) {
        for (size_t i = 0; i < n_runs; i++) {
            if (runs[i]->u != NULL) {
                uuvsim_run_abort(runs[i]->u);
            }
        }
        free_runs();
        return 2;
    }
    const double w0 = uuvsim_wall_s();
    while (batch_pass() > 0u) {
    }
    const double share = (uuvsim_wall_s() - w0) / (double)n_runs;
    int status = 0;
    for (size_t i = 0; i < n_runs; i++) {
        const int s = uuvsim_run_close(runs[i]->u, share);
        status = (s > status) ? s : status;
    }
    free_runs();
    return status;
}
