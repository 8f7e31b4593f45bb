/*
 * `uuvsim view RUN_DIR`: writes RUN_DIR/mission.html, one page that shows
 * the run of RUN_DIR (telemetry.csv, and summary.json when there is one)
 * in 3-D with its plots. The page stands alone: the template
 * (ports/linux/mission.html, compiled in), three.js as Debian packages it
 * (libjs-three, read when the page is written) and the run's files are
 * all copied into it, so it opens from file:// with no network.
 *
 * The telemetry is checked before anything is written: a header of
 * column names with the columns the page draws, then rows of as many
 * finite numbers with increasing time. Columns are found by name; extra
 * columns are carried along. The page is written under .partial.PID and
 * renamed when complete (out_open, out_finish, out_commit).
 */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "csv_out.h"
#include "view.h"

/* The template, one string per line (generated from ports/linux/mission.html). */
static const char *const template_lines[] = {
#include "mission_html.inc"
};

#define THREE_DEFAULT "/usr/share/javascript/three/three.min.js"
#define FILE_MAX_BYTES ((size_t)1 << 30)   /* 1 GiB: about 60 h of telemetry */
#define SUMMARY_MAX_BYTES ((size_t)1 << 20)
#define THREE_MAX_BYTES ((size_t)64 << 20)
#define PATH_BYTES 4096

/* The columns the page cannot do without; the drive's (v_dc_v, soc, ...) are optional. */
static const char *const required_columns[] = {
    "t_s",     "u_mps",       "v_mps",       "w_mps",        "x_m",          "y_m",
    "z_m",     "phi_rad",     "theta_rad",   "psi_rad",      "delta_r_rad",  "delta_s_rad",
    "delta_bp_rad", "delta_bs_rad", "n_rpm"};
#define N_REQUIRED (sizeof required_columns / sizeof required_columns[0])

typedef view_text text;

/* Reads a whole file; returns false with errno's reason when it cannot. */
static bool read_text(const char *path, size_t max, text *t, const char **why) {
    *t = (text){NULL, 0u};
    FILE *f = fopen(path, "rb");
    if (f == NULL) {
        *why = strerror(errno);
        return false;
    }
    size_t cap = 1u << 16;
    char *buf = malloc(cap + 1u);
    size_t n = 0u;
    while (buf != NULL) {
        n += fread(buf + n, 1u, cap - n, f);
        if (n < cap || ferror(f)) {
            break;
        }
        if (cap >= max) {
            *why = "too large";
            free(buf);
            fclose(f);
            return false;
        }
        cap *= 2u;
        char *grown = realloc(buf, cap + 1u);
        if (grown == NULL) {
            free(buf);
        }
        buf = grown;
    }
    bool bad = (buf == NULL) || ferror(f);
    fclose(f);
    if (bad) {
        *why = (buf == NULL) ? "out of memory" : "cannot read";
        free(buf);
        return false;
    }
    buf[n] = '\0';
    t->data = buf;
    t->len = n;
    return true;
}

/* The length of the line at p (without its '\n' or "\r\n"), and where the next begins. */
static size_t line_at(const char *p, const char *end, const char **next) {
    const char *nl = memchr(p, '\n', (size_t)(end - p));
    const char *stop = nl ? nl : end;
    *next = nl ? nl + 1 : end;
    if (stop > p && stop[-1] == '\r') {
        stop--;
    }
    return (size_t)(stop - p);
}

/* A column name: a letter or '_', then letters, digits and '_'. */
static bool is_name(const char *s, size_t n) {
    if (n == 0u || !(isalpha((unsigned char)s[0]) || s[0] == '_')) {
        return false;
    }
    for (size_t i = 1; i < n; i++) {
        if (!(isalnum((unsigned char)s[i]) || s[i] == '_')) {
            return false;
        }
    }
    return true;
}

/* A finite number in C (and JavaScript) syntax: what strtod reads, all of it. */
static bool is_number(const char *s, size_t n, double *v) {
    char buf[64];
    if (n == 0u || n >= sizeof buf) {
        return false;
    }
    memcpy(buf, s, n);
    buf[n] = '\0';
    for (size_t i = 0; i < n; i++) {
        if (!(isdigit((unsigned char)buf[i]) || strchr("+-.eE", buf[i]) != NULL)) {
            return false; /* no "nan", "inf", hexadecimal or spaces */
        }
    }
    /* A subnormal value (strtod's ERANGE underflow, as a fin's decaying
     * deflection gives) is a number; an overflow is not finite. */
    char *end = NULL;
    *v = strtod(buf, &end);
    return end == buf + n && isfinite(*v);
}

/* Prints a field for a message: at most 40 characters, control characters as '?'. */
static void print_field(const char *s, size_t n) {
    for (size_t i = 0; i < n && i < 40u; i++) {
        unsigned char c = (unsigned char)s[i];
        fputc((c < 0x20u || c >= 0x7fu) ? '?' : (int)c, stderr);
    }
    if (n > 40u) {
        fputs("...", stderr);
    }
}

/*
 * Checks the telemetry (see the file's comment); prints the first problem
 * as file:line: field 'name': what was expected, got what.
 */
static bool check_telemetry(const char *path, const text *t) {
    const char *p = t->data;
    const char *end = t->data + t->len;
    if (memchr(p, '\0', t->len) != NULL) {
        fprintf(stderr, "uuvsim: %s: a binary file, expected the telemetry CSV\n", path);
        return false;
    }
    const char *next = NULL;
    size_t n = line_at(p, end, &next);
    size_t ncols = 0u;
    bool seen[N_REQUIRED] = {false};
    size_t t_col = 0u;
    /* The header: names, and each required one present. */
    static const char *names[512];
    static size_t name_len[512];
    for (size_t i = 0u; i <= n;) {
        size_t j = i;
        while (j < n && p[j] != ',') {
            j++;
        }
        if (!is_name(p + i, j - i) || ncols == 512u) {
            fprintf(stderr, "uuvsim: %s:1: column %zu: expected a column name, got '", path,
                    ncols + 1u);
            print_field(p + i, j - i);
            fprintf(stderr, "'%s\n", ncols == 512u ? " (more than 512 columns)" : "");
            return false;
        }
        for (size_t k = 0; k < N_REQUIRED; k++) {
            if (strlen(required_columns[k]) == j - i &&
                memcmp(required_columns[k], p + i, j - i) == 0) {
                seen[k] = true;
                if (k == 0u) {
                    t_col = ncols;
                }
            }
        }
        names[ncols] = p + i;
        name_len[ncols] = j - i;
        ncols++;
        i = j + 1u;
    }
    for (size_t k = 0; k < N_REQUIRED; k++) {
        if (!seen[k]) {
            fprintf(stderr, "uuvsim: %s:1: expected a column '%s' (a uuvsim telemetry file)\n",
                    path, required_columns[k]);
            return false;
        }
    }
    /* The rows: ncols finite numbers each, the time increasing. */
    size_t line = 1u;
    size_t rows = 0u;
    double t_prev = -HUGE_VAL;
    for (p = next; p < end; p = next) {
        line++;
        n = line_at(p, end, &next);
        if (n == 0u && next == end) {
            break; /* the final newline */
        }
        size_t col = 0u;
        for (size_t i = 0u; i <= n; col++) {
            size_t j = i;
            while (j < n && p[j] != ',') {
                j++;
            }
            double v = 0.0;
            if (col >= ncols) {
                fprintf(stderr, "uuvsim: %s:%zu: expected %zu fields, got more\n", path, line,
                        ncols);
                return false;
            }
            if (!is_number(p + i, j - i, &v)) {
                fprintf(stderr, "uuvsim: %s:%zu: field '", path, line);
                print_field(names[col], name_len[col]);
                fprintf(stderr, "': expected a finite number, got '");
                print_field(p + i, j - i);
                fprintf(stderr, "'\n");
                return false;
            }
            if (col == t_col) {
                if (!(v > t_prev)) {
                    fprintf(stderr, "uuvsim: %s:%zu: field 't_s': expected a time after %.9g s, "
                            "got %.9g\n", path, line, t_prev, v);
                    return false;
                }
                t_prev = v;
            }
            i = j + 1u;
        }
        if (col != ncols) {
            fprintf(stderr, "uuvsim: %s:%zu: expected %zu fields, got %zu\n", path, line, ncols,
                    col);
            return false;
        }
        rows++;
    }
    if (rows == 0u) {
        fprintf(stderr, "uuvsim: %s: expected rows of telemetry after the header, got none\n",
                path);
        return false;
    }
    return true;
}

/* The summary: a JSON object (the page parses it); "</" is written as "<\/". */
static bool check_summary(const char *path, const text *s) {
    size_t i = 0u;
    while (i < s->len && isspace((unsigned char)s->data[i])) {
        i++;
    }
    if (i == s->len || s->data[i] != '{' || memchr(s->data, '\0', s->len) != NULL) {
        fprintf(stderr, "uuvsim: %s:1: expected a JSON object (the summary of uuvsim --summary)\n",
                path);
        return false;
    }
    return true;
}

static void write_summary(FILE *f, const text *s) {
    for (size_t i = 0; i < s->len; i++) {
        if (s->data[i] == '/' && i > 0u && s->data[i - 1u] == '<') {
            fputc('\\', f);
        }
        fputc(s->data[i], f);
    }
}

/* Whether the text holds "</script" in any case (it would end the page's script). */
static bool has_script_end(const text *t) {
    static const char tag[] = "</script";
    for (const char *p = t->data; (p = memchr(p, '<', t->len - (size_t)(p - t->data))) != NULL;
         p++) {
        size_t left = t->len - (size_t)(p - t->data);
        size_t k = 0u;
        while (k < sizeof tag - 1u && k < left && tolower((unsigned char)p[k]) == tag[k]) {
            k++;
        }
        if (k == sizeof tag - 1u) {
            return true;
        }
    }
    return false;
}

/* The names of the fault commands (by bit of the faults column) and of the
 * trips; live: the page came from the live view's server (live.c). */
static void write_names(FILE *f, bool live) {
    fputs("{\"faults\": [", f);
    for (int k = SCN_FIRST_FAULT; k < SCN_COMMAND_COUNT; k++) {
        fprintf(f, "%s\"%s\"", k > SCN_FIRST_FAULT ? ", " : "", scenario_command_names[k]);
    }
    fputs("], \"trips\": [", f);
    for (unsigned k = 0u; k < OUT_TRIP_NAMES; k++) {
        fprintf(f, "%s\"%s\"", k > 0u ? ", " : "", out_trip_names[k]);
    }
    fprintf(f, "], \"live\": %s}\n", live ? "true" : "false");
}

void view_write_page(FILE *f, const view_text *three, const view_text *csv,
                     const view_text *summary, bool live) {
    for (size_t i = 0; i < sizeof template_lines / sizeof template_lines[0]; i++) {
        const char *l = template_lines[i];
        if (strcmp(l, "@THREE_JS@\n") == 0) {
            fwrite(three->data, 1u, three->len, f);
            fputc('\n', f);
        } else if (strcmp(l, "@TELEMETRY_CSV@\n") == 0) {
            fwrite(csv->data, 1u, csv->len, f);
            if (csv->len > 0u && csv->data[csv->len - 1u] != '\n') {
                fputc('\n', f);
            }
        } else if (strcmp(l, "@SUMMARY_JSON@\n") == 0) {
            if (summary != NULL && summary->data != NULL) {
                write_summary(f, summary);
            } else {
                fputs("null", f);
            }
            fputc('\n', f);
        } else if (strcmp(l, "@NAMES_JSON@\n") == 0) {
            write_names(f, live);
        } else {
            fputs(l, f);
        }
    }
}

bool view_read_three(view_text *three) {
    const char *path = getenv("UUVSIM_THREE_JS");
    if (path == NULL || path[0] == '\0') {
        path = THREE_DEFAULT;
    }
    const char *why = "";
    if (!read_text(path, THREE_MAX_BYTES, three, &why)) {
        fprintf(stderr, "uuvsim: view: %s: %s (three.js: install it with "
                "'apt-get install libjs-three', or name the file in UUVSIM_THREE_JS)\n",
                path, why);
        return false;
    }
    if (has_script_end(three)) {
        fprintf(stderr, "uuvsim: view: %s: holds '</script', cannot be put into a page\n", path);
        free(three->data);
        three->data = NULL;
        return false;
    }
    return true;
}

int uuvsim_view(const char *dir) {
    struct stat st;
    if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode)) {
        fprintf(stderr, "uuvsim: view: %s: %s (expected the folder of a run, such as out/)\n",
                dir, errno == ENOENT ? "no such folder" : "not a folder");
        return 2;
    }
    char csv_path[PATH_BYTES], sum_path[PATH_BYTES], page_path[PATH_BYTES];
    if (snprintf(csv_path, sizeof csv_path, "%s/telemetry.csv", dir) >= PATH_BYTES ||
        snprintf(sum_path, sizeof sum_path, "%s/summary.json", dir) >= PATH_BYTES ||
        snprintf(page_path, sizeof page_path, "%s/mission.html", dir) >= PATH_BYTES) {
        fprintf(stderr, "uuvsim: view: %s: path too long\n", dir);
        return 2;
    }
    const char *why = "";
    text csv, summary = {NULL, 0u}, three;
    if (!read_text(csv_path, FILE_MAX_BYTES, &csv, &why)) {
        fprintf(stderr, "uuvsim: view: %s: %s (expected the telemetry of uuvsim --csv)\n",
                csv_path, why);
        return 2;
    }
    int status = 2;
    if (!check_telemetry(csv_path, &csv)) {
        free(csv.data);
        return 2;
    }
    if (access(sum_path, F_OK) == 0) {
        if (!read_text(sum_path, SUMMARY_MAX_BYTES, &summary, &why)) {
            fprintf(stderr, "uuvsim: view: %s: %s\n", sum_path, why);
            free(csv.data);
            return 2;
        }
        if (!check_summary(sum_path, &summary)) {
            free(csv.data);
            free(summary.data);
            return 2;
        }
    }
    if (view_read_three(&three)) {
        out_file page;
        if (out_open(&page, page_path)) {
            view_write_page(page.f, &three, &csv, &summary, false);
            if (out_finish(&page) && out_commit(&page)) {
                printf("written %s\n", page_path);
                status = out_stdout_ok() ? 0 : 2;
            }
        }
        free(three.data);
    }
    free(csv.data);
    free(summary.data);
    return status;
}
