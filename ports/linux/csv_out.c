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
 * Writes the P-digit decimal d[0..p) times 10^x as printf's "%.Pg" does:
 * positional when -4 <= x < p, else d.ddd e+XX; trailing zeros and a
 * trailing point dropped. neg adds the sign. Returns the length.
 */
static size_t g_text(char *out, bool neg, const char *d, int p, int x) {
    size_t n = 0u;
    int last = p - 1; /* the last digit kept: trailing zeros go */
    while (last > 0 && d[last] == '0') {
        last--;
    }
    if (neg) {
        out[n++] = '-';
    }
    if (x < -4 || x >= p) {
        out[n++] = d[0];
        if (last > 0) {
            out[n++] = '.';
            for (int i = 1; i <= last; i++) {
                out[n++] = d[i];
            }
        }
        n += (size_t)sprintf(out + n, "e%c%02d", (x < 0) ? '-' : '+', (x < 0) ? -x : x);
        return n;
    }
    if (x < 0) {
        out[n++] = '0';
        out[n++] = '.';
        for (int i = 0; i < -x - 1; i++) {
            out[n++] = '0';
        }
        for (int i = 0; i <= last; i++) {
            out[n++] = d[i];
        }
    } else {
        for (int i = 0; i <= x; i++) {
            out[n++] = d[i];
        }
        if (last > x) {
            out[n++] = '.';
            for (int i = x + 1; i <= last; i++) {
                out[n++] = d[i];
            }
        }
    }
    out[n] = '\0';
    return n;
}

/*
 * A value with the fewest significant digits that read back as the same
 * double (15, 16 or 17: %g drops trailing zeros, so 0.1 is "0.1"), and 0
 * for magnitudes below CSV_FLUSH and for -0. The text is printf's
 * "%.15g", "%.16g" or "%.17g", whichever comes first reads back; the
 * digits are printed once, to 17 places, and the 15- and 16-digit ones
 * rounded from them: exact unless the digits dropped are a half
 * ("5", "50"), where the exact value may lie on either side, so there
 * printf rounds the value itself. tests/host/test_csv_number.c compares
 * the result with the three printf calls on a million values.
 */
void csv_format_number(char *buf, size_t cap, double v) {
    if (!(fabs(v) >= CSV_FLUSH)) {
        snprintf(buf, cap, "%s", (v != v) ? "nan" : "0");
        return;
    }
    char e17[40];
    if (!isfinite(v) || cap < 32u || snprintf(e17, sizeof e17, "%.16e", fabs(v)) != 22) {
        for (int digits = 15; digits <= 17; digits++) {
            snprintf(buf, cap, "%.*g", digits, v);
            if (strtod(buf, NULL) == v) {
                break;
            }
        }
        return;
    }
    /* e17 is "d.dddddddddddddddde+XX" (22 characters; a 3-digit exponent took printf above). */
    char d17[17];
    d17[0] = e17[0];
    memcpy(d17 + 1, e17 + 2, 16u);
    const int x17 = atoi(e17 + 19);
    const bool neg = v < 0.0;
    for (int p = 15; p <= 16; p++) {
        const char *tail = d17 + p;
        const bool half = (p == 16) ? (tail[0] == '5') : (tail[0] == '5' && tail[1] == '0');
        if (half) {
            snprintf(buf, cap, "%.*g", p, v);
        } else {
            char d[17];
            int x = x17;
            memcpy(d, d17, (size_t)p);
            if (tail[0] >= '5') { /* above the half: round up, carrying */
                int i = p - 1;
                while (i >= 0 && d[i] == '9') {
                    d[i--] = '0';
                }
                if (i >= 0) {
                    d[i]++;
                } else {
                    d[0] = '1';
                    x++;
                }
            }
            (void)g_text(buf, neg, d, p, x);
        }
        if (strtod(buf, NULL) == v) {
            return;
        }
    }
    (void)g_text(buf, neg, d17, 17, x17);
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
