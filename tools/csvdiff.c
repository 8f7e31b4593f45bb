/*
 * csvdiff: compares two CSV files column by column, by header name.
 *
 *   csvdiff [--rel R] [--abs A] [--cols a,b,...] REFERENCE.csv ACTUAL.csv
 *
 * Every column of REFERENCE (or only those named by --cols) must exist in
 * ACTUAL, and both files must have the same number of rows. A value passes
 * when |actual - reference| <= max(R * |reference|, A). Prints the largest
 * relative error per column and where it occurs, then "N passed, N failed"
 * with one check per column. Exit status 0 when all pass, 1 when a column
 * fails, 2 on unreadable or malformed input.
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_COLS 128
#define MAX_LINE 16384

typedef struct {
    char *names[MAX_COLS];
    int ncols;
    double *rows; /* nrows x ncols */
    long nrows;
} table;

static int split_header(char *line, table *t, const char *path) {
    t->ncols = 0;
    for (char *tok = strtok(line, ",\r\n"); tok != NULL; tok = strtok(NULL, ",\r\n")) {
        if (t->ncols == MAX_COLS) {
            fprintf(stderr, "%s:1: more than %d columns\n", path, MAX_COLS);
            return -1;
        }
        t->names[t->ncols++] = strdup(tok);
    }
    return t->ncols > 0 ? 0 : -1;
}

static int read_table(const char *path, table *t) {
    FILE *f = fopen(path, "r");
    if (f == NULL) {
        fprintf(stderr, "%s: cannot open: %s\n", path, strerror(errno));
        return -1;
    }
    static char line[MAX_LINE];
    if (fgets(line, sizeof line, f) == NULL || split_header(line, t, path) != 0) {
        fprintf(stderr, "%s:1: expected a header line of column names\n", path);
        fclose(f);
        return -1;
    }
    long cap = 1024;
    t->rows = malloc(sizeof(double) * (size_t)cap * (size_t)t->ncols);
    t->nrows = 0;
    long lineno = 1;
    while (fgets(line, sizeof line, f) != NULL) {
        lineno++;
        if (line[0] == '\n' || line[0] == '\0') {
            continue;
        }
        if (t->nrows == cap) {
            cap *= 2;
            t->rows = realloc(t->rows, sizeof(double) * (size_t)cap * (size_t)t->ncols);
        }
        char *p = line;
        for (int c = 0; c < t->ncols; c++) {
            char *end = NULL;
            errno = 0;
            double v = strtod(p, &end);
            if (end == p || errno != 0) {
                fprintf(stderr, "%s:%ld: column %s: expected a number\n", path, lineno,
                        t->names[c]);
                fclose(f);
                return -1;
            }
            t->rows[t->nrows * t->ncols + c] = v;
            p = end;
            if (c + 1 < t->ncols) {
                if (*p != ',') {
                    fprintf(stderr, "%s:%ld: expected %d columns\n", path, lineno, t->ncols);
                    fclose(f);
                    return -1;
                }
                p++;
            }
        }
        t->nrows++;
    }
    fclose(f);
    return 0;
}

static int find_col(const table *t, const char *name) {
    for (int c = 0; c < t->ncols; c++) {
        if (strcmp(t->names[c], name) == 0) {
            return c;
        }
    }
    return -1;
}

static int wanted(const char *cols, const char *name) {
    if (cols == NULL) {
        return 1;
    }
    size_t n = strlen(name);
    for (const char *p = cols; *p != '\0';) {
        const char *e = strchr(p, ',');
        size_t len = e ? (size_t)(e - p) : strlen(p);
        if (len == n && strncmp(p, name, n) == 0) {
            return 1;
        }
        p += len + (e ? 1 : 0);
    }
    return 0;
}

int main(int argc, char **argv) {
    double rel = 1e-9;
    double abs_tol = 1e-12;
    const char *cols = NULL;
    int i = 1;
    for (; i + 1 < argc && strncmp(argv[i], "--", 2) == 0; i += 2) {
        if (strcmp(argv[i], "--rel") == 0) {
            rel = atof(argv[i + 1]);
        } else if (strcmp(argv[i], "--abs") == 0) {
            abs_tol = atof(argv[i + 1]);
        } else if (strcmp(argv[i], "--cols") == 0) {
            cols = argv[i + 1];
        } else {
            fprintf(stderr, "csvdiff: unknown option %s\n", argv[i]);
            return 2;
        }
    }
    if (argc - i != 2) {
        fprintf(stderr, "usage: csvdiff [--rel R] [--abs A] [--cols a,b] REFERENCE ACTUAL\n");
        return 2;
    }
    table ref = {0};
    table act = {0};
    if (read_table(argv[i], &ref) != 0 || read_table(argv[i + 1], &act) != 0) {
        return 2;
    }
    if (ref.nrows != act.nrows) {
        fprintf(stderr, "csvdiff: %s has %ld rows, %s has %ld\n", argv[i], ref.nrows,
                argv[i + 1], act.nrows);
        printf("0 passed, 1 failed\n");
        return 1;
    }
    int passed = 0;
    int failed = 0;
    for (int c = 0; c < ref.ncols; c++) {
        if (!wanted(cols, ref.names[c])) {
            continue;
        }
        int a = find_col(&act, ref.names[c]);
        if (a < 0) {
            printf("%-18s missing in %s\n", ref.names[c], argv[i + 1]);
            failed++;
            continue;
        }
        double worst = 0.0;
        long worst_row = -1;
        int bad = 0;
        for (long r = 0; r < ref.nrows; r++) {
            double x = ref.rows[r * ref.ncols + c];
            double y = act.rows[r * act.ncols + a];
            double d = fabs(y - x);
            double tol = fmax(rel * fabs(x), abs_tol);
            double e = d / fmax(fabs(x), abs_tol / rel);
            if (!(d <= tol)) {
                bad = 1;
            }
            if (!(e <= worst)) {
                worst = e;
                worst_row = r;
            }
        }
        printf("%-18s max rel error %.3e (row %ld) %s\n", ref.names[c], worst, worst_row + 2,
               bad ? "FAIL" : "ok");
        if (bad) {
            failed++;
        } else {
            passed++;
        }
    }
    printf("%d passed, %d failed\n", passed, failed);
    return failed == 0 ? 0 : 1;
}
