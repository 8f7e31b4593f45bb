/*
 * The CSV layouts (see csv_out.h).
 */
#include "csv_out.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

const char *const out_trip_names[OUT_TRIP_NAMES] = {"none", "leg short", "under-voltage",
                                                    "phase loss"};

static const char *const drive_columns[] = {"te_nm", "i_rms_a", "v_dc_v", "i_batt_a", "soc",
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

/*
 * A value with the fewest significant digits that read back as the same
 * double (15, 16 or 17: %g drops trailing zeros, so 0.1 is "0.1"), and 0
 * for magnitudes below CSV_FLUSH and for -0.
 */
void csv_format_number(char *buf, size_t cap, double v) {
    if (!(fabs(v) >= CSV_FLUSH)) {
        snprintf(buf, cap, "%s", (v != v) ? "nan" : "0");
        return;
    }
    for (int digits = 15; digits <= 17; digits++) {
        snprintf(buf, cap, "%.*g", digits, v);
        if (strtod(buf, NULL) == v) {
            break;
        }
    }
}

void csv_number(FILE *f, double v) {
    char buf[40];
    csv_format_number(buf, sizeof buf, v);
    fputs(buf, f);
}

void csv_row(FILE *f, const exec_frame *r, bool full_plant) {
    csv_number(f, r->t_s);
    const double *groups[2] = {r->x, r->cmd};
    const int sizes[2] = {VESSEL_NSTATES, EXEC_NCMD};
    for (int g = 0; g < 2; g++) {
        for (int i = 0; i < sizes[g]; i++) {
            fputc(',', f);
            csv_number(f, groups[g][i]);
        }
    }
    if (full_plant) {
        const double drive[7] = {r->te_nm, r->i_rms_a, r->v_dc_v, r->i_batt_a,
                                 r->soc,   r->m_index, r->f_hz};
        for (int i = 0; i < 7; i++) {
            fputc(',', f);
            csv_number(f, drive[i]);
        }
        fprintf(f, ",%u,%u", (unsigned)r->faults, (unsigned)r->trip);
    }
    fputc('\n', f);
}

void trace_header(FILE *f) {
    fputs("t_s,sa,sb,sc,m_index,f_hz,v_dc_v,v_an_v,v_bn_v,v_cn_v,vc_a_v,vc_b_v,vc_c_v,"
          "i_a_a,i_b_a,i_c_a,i_dc_a,n_rpm,te_nm\n",
          f);
}

/* Adding +0.0 turns -0 into 0 (round to nearest), so no "-0" is printed. */
void trace_row(FILE *f, double t_s, const drive_trace_row *r) {
    fprintf(f, "%.9g,%u,%u,%u,%.6g,%.6g,%.7g,%.7g,%.7g,%.7g,%.7g,%.7g,%.7g,%.7g,%.7g,%.7g,%.7g,"
               "%.7g,%.7g\n",
            t_s, r->s[0], r->s[1], r->s[2], r->m_index + 0.0, r->f_hz + 0.0, r->v_dc + 0.0,
            r->v_inv[0] + 0.0, r->v_inv[1] + 0.0, r->v_inv[2] + 0.0, r->v_cap[0] + 0.0,
            r->v_cap[1] + 0.0, r->v_cap[2] + 0.0, r->i_motor[0] + 0.0, r->i_motor[1] + 0.0,
            r->i_motor[2] + 0.0, r->i_dc + 0.0, r->n_rpm + 0.0, r->te_nm + 0.0);
}
