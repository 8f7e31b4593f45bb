/*
 * Output files of the desk simulator, written under FILE.partial and
 * renamed to FILE when complete, so that a failed run leaves nothing
 * half-written.
 *
 * Telemetry CSV (one row per 100 ms): t_s, the 17 vessel states of the
 * reference layout, the 5 commands, and in the full plant te_nm, i_rms_a,
 * v_dc, i_batt_a, soc, m_index, f_hz. Every value has 17 significant
 * digits, so it reads back as the same double; the firmware's decoded
 * telemetry goes through the same writer.
 *
 * Trace CSV (every fast step in a window): t_s, sa, sb, sc, m_index, f_hz,
 * v_dc, v_an, v_bn, v_cn, vc_a, vc_b, vc_c, i_a, i_b, i_c, i_dc, n_rpm,
 * te_nm.
 */
#ifndef UUV_CSV_OUT_H
#define UUV_CSV_OUT_H

#include <stdbool.h>
#include <stdio.h>

#include "executive.h"

typedef struct {
    FILE *f;
    char path[4096];
    char partial[4096 + 16];
} out_file;

/* Opens the partial file; prints the error on failure. */
bool out_open(out_file *o, const char *path);
/* Completes the file (renames it into place); prints the error on failure. */
bool out_close(out_file *o);
/* Abandons the file: removes the partial output. */
void out_abort(out_file *o);

/* The protection's reasons, by the telemetry's trip value (drive_trip). */
#define OUT_TRIP_NAMES 4u
extern const char *const out_trip_names[OUT_TRIP_NAMES];

void csv_header(FILE *f, bool full_plant);
void csv_row(FILE *f, const exec_frame *r, bool full_plant);

void trace_header(FILE *f);
void trace_row(FILE *f, double t_s, const drive_trace_row *r);

#endif /* UUV_CSV_OUT_H */
