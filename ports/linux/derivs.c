/*
 * `uuvsim derivs FILE.csv`: evaluates the vessel's state derivative for
 * each row of a file in the layout of the reference derivative vectors
 * (case, 5 commands, 17 states, optionally 17 derivatives, which are
 * ignored) and prints the same layout with the derivatives computed by the
 * model: MSS propulsion, shaft speed through the actuator lag.
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "models/vessel/vessel.h"
#include "executive.h"

#define LINE_MAX_BYTES 8192
#define NCOLS_IN (1 + EXEC_NCMD + VESSEL_NSTATES)

int uuvsim_derivs(const char *path);

/* Checks the header names the columns of the reference layout, in order. */
static int check_header(const char *path, char *line) {
    const char *expected[NCOLS_IN];
    expected[0] = "case";
    for (int i = 0; i < EXEC_NCMD; i++) {
        expected[1 + i] = exec_command_names[i];
    }
    for (int i = 0; i < VESSEL_NSTATES; i++) {
        expected[1 + EXEC_NCMD + i] = vessel_state_names[i];
    }
    char *save = NULL;
    char *tok = strtok_r(line, ",\r\n", &save);
    for (int c = 0; c < NCOLS_IN; c++, tok = strtok_r(NULL, ",\r\n", &save)) {
        if (tok == NULL || strcmp(tok, expected[c]) != 0) {
            fprintf(stderr, "uuvsim: %s:1: column %d: expected '%s', got '%s'\n", path, c + 1,
                    expected[c], tok ? tok : "(end of line)");
            return -1;
        }
    }
    return 0;
}

int uuvsim_derivs(const char *path) {
    FILE *f = fopen(path, "r");
    if (f == NULL) {
        fprintf(stderr, "uuvsim: %s: cannot open: %s\n", path, strerror(errno));
        return 2;
    }
    static char line[LINE_MAX_BYTES];
    if (fgets(line, sizeof line, f) == NULL || check_header(path, line) != 0) {
        if (ferror(f) || feof(f)) {
            fprintf(stderr, "uuvsim: %s:1: expected the header line\n", path);
        }
        fclose(f);
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
        fclose(f);
        return 1;
    }
    /* Rows are computed and kept until the whole file has been read, so a
     * bad row late in the file prints nothing but the error. */
    size_t cap = 64;
    size_t nrows = 0;
    double(*rows)[NCOLS_IN + VESSEL_NSTATES] = malloc(cap * sizeof *rows);
    long lineno = 1;
    int status = 0;
    while (rows != NULL && fgets(line, sizeof line, f) != NULL) {
        lineno++;
        if (line[0] == '\n' || (line[0] == '\r' && line[1] == '\n')) {
            continue;
        }
        if (nrows == cap) {
            cap *= 2;
            void *grown = realloc(rows, cap * sizeof *rows);
            if (grown == NULL) {
                break;
            }
            rows = grown;
        }
        double *r = rows[nrows];
        char *p = line;
        for (int c = 0; c < NCOLS_IN; c++) {
            char *end = NULL;
            errno = 0;
            r[c] = strtod(p, &end);
            if (end == p || errno == ERANGE || (*end != ',' && c + 1 < NCOLS_IN) ||
                r[c] != r[c]) {
                fprintf(stderr, "uuvsim: %s:%ld: column %d: expected a number\n", path, lineno,
                        c + 1);
                status = 2;
                break;
            }
            p = end + 1;
        }
        if (status != 0) {
            break;
        }
        vessel_cmd cmd = {0};
        cmd.rudder_rad = r[1];
        cmd.stern_rad = r[2];
        cmd.bow_port_rad = r[3];
        cmd.bow_stbd_rad = r[4];
        cmd.n_rpm = r[5];
        (void)vessel_derivatives(&m, &r[1 + EXEC_NCMD], &cmd, &r[NCOLS_IN]);
        nrows++;
    }
    fclose(f);
    if (rows == NULL) {
        fprintf(stderr, "uuvsim: out of memory\n");
        return 1;
    }
    if (status == 0) {
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
            for (int c = 1; c < NCOLS_IN + VESSEL_NSTATES; c++) {
                printf(",%.17g", rows[k][c]);
            }
            putchar('\n');
        }
    }
    free(rows);
    return status;
}
