/*
 * CSV telemetry writer (see csv_out.h).
 */
#include "csv_out.h"

#include <errno.h>
#include <string.h>

bool csv_out_open(csv_out *c, const char *path) {
    *c = (csv_out){0};
    if (strlen(path) >= sizeof c->path) {
        fprintf(stderr, "uuvsim: %s: path too long\n", path);
        return false;
    }
    strcpy(c->path, path);
    snprintf(c->partial, sizeof c->partial, "%s.partial", path);
    c->f = fopen(c->partial, "w");
    if (c->f == NULL) {
        fprintf(stderr, "uuvsim: %s: cannot write: %s\n", path, strerror(errno));
        return false;
    }
    fputs("t_s", c->f);
    for (int i = 0; i < VESSEL_NSTATES; i++) {
        fprintf(c->f, ",%s", vessel_state_names[i]);
    }
    for (int i = 0; i < SIM_NCMD; i++) {
        fprintf(c->f, ",%s", sim_command_names[i]);
    }
    fputc('\n', c->f);
    return true;
}

void csv_out_frame(csv_out *c, const sim_frame *f) {
    fprintf(c->f, "%.17g", f->t_s);
    for (int i = 0; i < VESSEL_NSTATES; i++) {
        fprintf(c->f, ",%.17g", f->x[i]);
    }
    for (int i = 0; i < SIM_NCMD; i++) {
        fprintf(c->f, ",%.17g", f->cmd[i]);
    }
    fputc('\n', c->f);
}

bool csv_out_close(csv_out *c) {
    bool ok = !ferror(c->f);
    ok = (fclose(c->f) == 0) && ok;
    c->f = NULL;
    if (!ok || rename(c->partial, c->path) != 0) {
        fprintf(stderr, "uuvsim: %s: cannot write: %s\n", c->path, strerror(errno));
        remove(c->partial);
        return false;
    }
    return true;
}

void csv_out_abort(csv_out *c) {
    if (c->f != NULL) {
        fclose(c->f);
        c->f = NULL;
        remove(c->partial);
    }
}
