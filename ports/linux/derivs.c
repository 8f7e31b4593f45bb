/*
 * `uuvsim derivs FILE.csv`: evaluates the vessel's state derivative for
 * each row of a file in the layout of the reference derivative vectors
 * (case, 5 commands, 17 states, optionally the 17 derivatives d_*, which
 * are read and ignored) and prints the same layout with the derivatives
 * computed by the model: MSS propulsion, shaft speed through the actuator
 * lag.
 *
 * The reader takes the whole file (a regular file of at most 64 MiB),
 * lines of any length ended by LF, CR LF or CR; every row must have the
 * header's number of columns, and every field must be a plain decimal
 * number (no spaces, no decimal comma, no hexadecimal, no inf or nan),
 * finite and inside the bounds below. Errors name the line and column.
 * Nothing is printed unless the whole file is good; a write error on
 * standard output gives exit status 2.
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "executive.h"
#include "models/vessel/vessel.h"
#include "out_file.h"

#define MAX_INPUT_BYTES (64u << 20)
#define NCOLS_IN (1 + EXEC_NCMD + VESSEL_NSTATES)
#define NCOLS_ALL (NCOLS_IN + VESSEL_NSTATES)
#define MAX_NUMBER_CHARS 64

int uuvsim_derivs(const char *path);
FILE *uuvsim_open_input(const char *path);

/*
 * The bounds of each input column, wider than a scenario's (the reference
 * rows drive the actuators beyond their limits) but such that every
 * derivative is finite: the case number, 5 commands, 17 states.
 */
static const double col_max[NCOLS_IN] = {
    1e9,                              /* case */
    3.15, 3.15, 3.15, 3.15, 1e4,      /* fins [rad], shaft [rpm] */
    100.0, 100.0, 100.0,              /* u v w [m/s] */
    100.0, 100.0, 100.0,              /* p q r [rad/s] */
    1e7, 1e7, 1e4,                    /* x y z [m] */
    3.15, 1.5707, 1e3,                /* phi theta psi [rad] */
    3.15, 3.15, 3.15, 3.15, 1e4,      /* actuator states [rad], [rpm] */
};

typedef struct {
    const char *path;
    long line;
} where;

static int row_error(const where *w, int col, const char *what, const char *text, size_t n) {
    fprintf(stderr, "uuvsim: %s:%ld: column %d: %s", w->path, w->line, col, what);
    if (text != NULL) {
        fputs(", got '", stderr);
        for (size_t i = 0; i < n && i < 40u; i++) {
            unsigned char ch = (unsigned char)text[i];
            fprintf(stderr, (ch >= 0x20u && ch < 0x7fu) ? "%c" : "\\x%02x", ch);
        }
        fputs(n > 40u ? "...'" : "'", stderr);
    }
    fputc('\n', stderr);
    return 2;
}

/* [+-] digits [. digits] [e [+-] digits], or [+-] . digits [e ...]: nothing else. */
static bool plain_decimal(const char *s, size_t n) {
    size_t i = (n > 0u && (s[0] == '+' || s[0] == '-')) ? 1u : 0u;
    size_t digits = 0;
    while (i < n && s[i] >= '0' && s[i] <= '9') {
        i++;
        digits++;
    }
    if (i < n && s[i] == '.') {
        i++;
        while (i < n && s[i] >= '0' && s[i] <= '9') {
            i++;
            digits++;
        }
    }
    if (digits == 0u) {
        return false;
    }
    if (i < n && (s[i] == 'e' || s[i] == 'E')) {
        i++;
        i += (i < n && (s[i] == '+' || s[i] == '-')) ? 1u : 0u;
        size_t e = 0;
        while (i < n && s[i] >= '0' && s[i] <= '9') {
            i++;
            e++;
        }
        if (e == 0u) {
            return false;
        }
    }
    return i == n;
}

/* One field: a plain decimal, finite, |v| <= max (max < 0: any finite value). */
static int read_field(const where *w, int col, const char *s, size_t n, double max, double *v) {
    if (!plain_decimal(s, n) || n > MAX_NUMBER_CHARS) {
        return row_error(w, col, "expected a plain decimal number", s, n);
    }
    char buf[MAX_NUMBER_CHARS + 1];
    memcpy(buf, s, n);
    buf[n] = '\0';
    errno = 0;
    *v = strtod(buf, NULL);
    if (errno == ERANGE && (*v > 1.0 || *v < -1.0)) {
        return row_error(w, col, "the number overflows a double", s, n);
    }
    if (max >= 0.0 && !(*v >= -max && *v <= max)) {
        char what[160];
        snprintf(what, sizeof what, "out of range [%g, %g]", -max, max);
        return row_error(w, col, what, s, n);
    }
    return 0;
}

/* Splits a line at commas into at most cap fields; returns their count (cap + 1: more). */
static int split_fields(const char *s, size_t n, const char **f, size_t *len, int cap) {
    int k = 0;
    size_t start = 0;
    for (size_t i = 0; i <= n; i++) {
        if (i == n || s[i] == ',') {
            if (k == cap) {
                return cap + 1;
            }
            f[k] = s + start;
            len[k] = i - start;
            k++;
            start = i + 1;
        }
    }
    return k;
}

/* Checks the header: the reference layout's 23 columns, optionally the 17 d_* after them. */
static int check_header(const where *w, const char *s, size_t n, int *ncols) {
    const char *f[NCOLS_ALL + 1];
    size_t len[NCOLS_ALL + 1];
    int k = split_fields(s, n, f, len, NCOLS_ALL);
    const int names = (k < NCOLS_IN) ? NCOLS_IN : (k > NCOLS_ALL ? NCOLS_ALL : k);
    for (int c = 0; c < names; c++) {
        char expected[64];
        const char *name = (c == 0)              ? "case"
                           : (c <= EXEC_NCMD)    ? exec_command_names[c - 1]
                           : (c < NCOLS_IN)      ? vessel_state_names[c - 1 - EXEC_NCMD]
                                                 : vessel_state_names[c - NCOLS_IN];
        snprintf(expected, sizeof expected, "%s%s", c >= NCOLS_IN ? "d_" : "", name);
        if (c >= k || strlen(expected) != len[c] || memcmp(expected, f[c], len[c]) != 0) {
            where h = {w->path, 1};
            char what[160];
            snprintf(what, sizeof what, "expected '%s'%s", expected,
                     c >= k ? ", got the end of the line" : "");
            return row_error(&h, c + 1, what, c < k ? f[c] : NULL, c < k ? len[c] : 0u);
        }
    }
    if (k != NCOLS_IN && k != NCOLS_ALL) {
        fprintf(stderr, "uuvsim: %s:1: expected %d columns (or %d with the derivatives), got %d%s\n",
                w->path, NCOLS_IN, NCOLS_ALL, k > NCOLS_ALL ? NCOLS_ALL + 1 : k,
                k > NCOLS_ALL ? " or more" : "");
        return 2;
    }
    *ncols = k;
    return 0;
}

/* Reads the whole input; NULL (with the message printed) when it cannot. */
static char *read_input(const char *path, size_t *n) {
    FILE *f = uuvsim_open_input(path);
    if (f == NULL) {
        return NULL;
    }
    char *buf = malloc(MAX_INPUT_BYTES + 1u);
    *n = (buf != NULL) ? fread(buf, 1, MAX_INPUT_BYTES + 1u, f) : 0u;
    bool bad = ferror(f) != 0;
    fclose(f);
    if (buf == NULL || bad || *n > MAX_INPUT_BYTES) {
        fprintf(stderr, "uuvsim: %s: %s\n", path,
                buf == NULL ? "out of memory" : (bad ? "cannot read" : "larger than 64 MiB"));
        free(buf);
        return NULL;
    }
    return buf;
}

/* The next line from *at: its text and length, without the LF, CR LF or CR. */
static bool next_line(const char *buf, size_t n, size_t *at, const char **s, size_t *len) {
    if (*at >= n) {
        return false;
    }
    size_t i = *at;
    while (i < n && buf[i] != '\n' && buf[i] != '\r') {
        i++;
    }
    *s = buf + *at;
    *len = i - *at;
    if (i < n && buf[i] == '\r' && i + 1u < n && buf[i + 1u] == '\n') {
        i++;
    }
    *at = i + 1u;
    return true;
}

/* Reads, checks and evaluates every row; rows[] then holds inputs and derivatives. */
static int read_rows(const where *w0, const char *buf, size_t n, const vessel_model *m,
                     double (**rows)[NCOLS_ALL], size_t *nrows) {
    where w = *w0;
    size_t at = 0;
    const char *s = NULL;
    size_t len = 0;
    int ncols = 0;
    const char *nul = memchr(buf, '\0', n);
    size_t nul_at = (nul != NULL) ? (size_t)(nul - buf) : n;
    if (n >= 3u && memcmp(buf, "\xEF\xBB\xBF", 3) == 0) {
        at = 3u; /* a UTF-8 byte-order mark is skipped */
    }
    if (!next_line(buf, n, &at, &s, &len) || (nul != NULL && nul_at < at)) {
        fprintf(stderr, "uuvsim: %s:1: expected the header line%s\n", w.path,
                nul != NULL ? " (the line holds a NUL byte)" : "");
        return 2;
    }
    int st = check_header(&w, s, len, &ncols);
    size_t cap = 0;
    while (st == 0 && next_line(buf, n, &at, &s, &len)) {
        w.line++;
        if (nul != NULL && nul_at < at) {
            fprintf(stderr, "uuvsim: %s:%ld: the line holds a NUL byte\n", w.path, w.line);
            return 2;
        }
        if (len == 0u) {
            continue;
        }
        const char *f[NCOLS_ALL + 1];
        size_t flen[NCOLS_ALL + 1];
        int k = split_fields(s, len, f, flen, NCOLS_ALL);
        if (k != ncols) {
            fprintf(stderr, "uuvsim: %s:%ld: expected %d columns as in the header, got %d%s\n",
                    w.path, w.line, ncols, k, k > NCOLS_ALL ? " or more" : "");
            return 2;
        }
        if (*nrows == cap) {
            cap = (cap == 0u) ? 64u : 2u * cap;
            void *grown = realloc(*rows, cap * sizeof **rows);
            if (grown == NULL) {
                fprintf(stderr, "uuvsim: out of memory\n");
                return 1;
            }
            *rows = grown;
        }
        double *r = (*rows)[*nrows];
        for (int c = 0; c < ncols && st == 0; c++) {
            double ignored = 0.0;
            st = read_field(&w, c + 1, f[c], flen[c], c < NCOLS_IN ? col_max[c] : -1.0,
                            c < NCOLS_IN ? &r[c] : &ignored);
        }
        if (st != 0) {
            return st;
        }
        vessel_cmd cmd = {0};
        cmd.rudder_rad = r[1];
        cmd.stern_rad = r[2];
        cmd.bow_port_rad = r[3];
        cmd.bow_stbd_rad = r[4];
        cmd.n_rpm = r[5];
        (void)vessel_derivatives(m, &r[1 + EXEC_NCMD], &cmd, &r[NCOLS_IN]);
        for (int c = NCOLS_IN; c < NCOLS_ALL; c++) {
            if (!(r[c] - r[c] == 0.0)) {
                fprintf(stderr, "uuvsim: %s:%ld: the derivative %s is not finite\n", w.path,
                        w.line, vessel_state_names[c - NCOLS_IN]);
                return 2;
            }
        }
        (*nrows)++;
    }
    return st;
}

static void print_rows(double (*rows)[NCOLS_ALL], size_t nrows) {
    fputs("case", stdout);
    for (int i = 0; i < EXEC_NCMD; i++) {
        printf(",%s", exec_command_names[i]);
    }
    for (int i = 0; i < VESSEL_NSTATES; i++) {
        printf(",%s", vessel_state_names[i]);
    }
    for (int i = 0; i < VESSEL_NSTATES; i++) {
        printf(",d_%s", vessel_state_names[i]);
    }
    putchar('\n');
    for (size_t k = 0; k < nrows; k++) {
        printf("%.17g", rows[k][0]);
        for (int c = 1; c < NCOLS_ALL; c++) {
            printf(",%.17g", rows[k][c]);
        }
        putchar('\n');
    }
}

int uuvsim_derivs(const char *path) {
    size_t n = 0;
    char *buf = read_input(path, &n);
    if (buf == NULL) {
        return 2;
    }
    vessel_config cfg;
    vessel_config_default(&cfg);
    cfg.propulsion = VESSEL_PROP_MSS;
    cfg.shaft = VESSEL_SHAFT_LAG;
    cfg.free_surface = false; /* the reference vectors' deep water */
    static vessel_model m;
    if (vessel_init(&m, &cfg) != VESSEL_OK) {
        fprintf(stderr, "uuvsim: the vessel model refused its parameters\n");
        free(buf);
        return 1;
    }
    double(*rows)[NCOLS_ALL] = NULL;
    size_t nrows = 0;
    const where w = {path, 1};
    int status = read_rows(&w, buf, n, &m, &rows, &nrows);
    free(buf);
    if (status == 0) {
        print_rows(rows, nrows);
        status = out_stdout_ok() ? 0 : 2;
    }
    free(rows);
    return status;
}
