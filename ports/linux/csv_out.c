/*
 * Output files (see csv_out.h).
 */
#include "csv_out.h"

#include <errno.h>
#include <string.h>

bool out_open(out_file *o, const char *path) {
    *o = (out_file){0};
    if (strlen(path) >= sizeof o->path) {
        fprintf(stderr, "uuvsim: %s: path too long\n", path);
        return false;
    }
    strcpy(o->path, path);
    snprintf(o->partial, sizeof o->partial, "%s.partial", path);
    o->f = fopen(o->partial, "w");
    if (o->f == NULL) {
        fprintf(stderr, "uuvsim: %s: cannot write: %s\n", path, strerror(errno));
        return false;
    }
    return true;
}

bool out_close(out_file *o) {
    if (o->f == NULL) {
        return true;
    }
    bool ok = !ferror(o->f);
    ok = (fclose(o->f) == 0) && ok;
    o->f = NULL;
    if (!ok || rename(o->partial, o->path) != 0) {
        fprintf(stderr, "uuvsim: %s: cannot write: %s\n", o->path, strerror(errno));
        remove(o->partial);
        return false;
    }
    return true;
}

void out_abort(out_file *o) {
    if (o->f != NULL) {
        fclose(o->f);
        o->f = NULL;
        remove(o->partial);
    }
}

const char *const out_trip_names[OUT_TRIP_NAMES] = {"none", "leg short", "under-voltage",
                                                    "phase loss"};

static const char *const drive_columns[] = {"te_nm", "i_rms_a", "v_dc", "i_batt_a", "soc",
                                            "m_index", "f_hz", "faults", "trip"};

void csv_header(FILE *f, bool full_plant) {
    fputs("t_s", f);
    for (int i = 0; i < VESSEL_NSTATES; i++) {
        fprintf(f, ",%s", vessel_state_names[i]);
    }
    for (int i = 0; i < EXEC_NCMD; i++) {
        fprintf(f, ",%s", exec_command_names[i]);
    }
    if (full_plant) {
        for (size_t i = 0; i < sizeof drive_columns / sizeof drive_columns[0]; i++) {
            fprintf(f, ",%s", drive_columns[i]);
        }
    }
    fputc('\n', f);
}

void csv_row(FILE *f, const exec_frame *r, bool full_plant) {
    fprintf(f, "%.17g", r->t_s);
    for (int i = 0; i < VESSEL_NSTATES; i++) {
        fprintf(f, ",%.17g", r->x[i]);
    }
    for (int i = 0; i < EXEC_NCMD; i++) {
        fprintf(f, ",%.17g", r->cmd[i]);
    }
    if (full_plant) {
        fprintf(f, ",%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%u,%u", r->te_nm, r->i_rms_a,
                r->v_dc_v, r->i_batt_a, r->soc, r->m_index, r->f_hz, (unsigned)r->faults,
                (unsigned)r->trip);
    }
    fputc('\n', f);
}

void trace_header(FILE *f) {
    fputs("t_s,sa,sb,sc,m_index,f_hz,v_dc,v_an,v_bn,v_cn,vc_a,vc_b,vc_c,i_a,i_b,i_c,i_dc,"
          "n_rpm,te_nm\n",
          f);
}

void trace_row(FILE *f, double t_s, const drive_trace_row *r) {
    fprintf(f, "%.9g,%u,%u,%u,%.6g,%.6g,%.7g,%.7g,%.7g,%.7g,%.7g,%.7g,%.7g,%.7g,%.7g,%.7g,%.7g,"
               "%.7g,%.7g\n",
            t_s, r->s[0], r->s[1], r->s[2], r->m_index, r->f_hz, r->v_dc, r->v_inv[0],
            r->v_inv[1], r->v_inv[2], r->v_cap[0], r->v_cap[1], r->v_cap[2], r->i_motor[0],
            r->i_motor[1], r->i_motor[2], r->i_dc, r->n_rpm, r->te_nm);
}
