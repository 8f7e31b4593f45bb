/*
 * The CSV layouts of the desk simulator (the files themselves: out_file.h).
 *
 * Telemetry CSV (one row per 100 ms): t_s, the 17 vessel states of the
 * reference layout, the 5 commands, and in the full plant te_nm, i_rms_a,
 * v_dc_v, i_batt_a, soc, m_index, f_hz, faults, trip. Every value has the
 * fewest significant digits (at most 17) that read back as the same double
 * (csv_number), and magnitudes below CSV_FLUSH are written as 0: the
 * actuator lags decay geometrically towards their command and would end in
 * values such as 2.8e-108 and the subnormal 4.9e-324, which mean nothing
 * physically. The firmware's decoded telemetry goes through the same writer,
 * so the two CSV files stay byte-identical.
 *
 * Trace CSV (every fast step in a window): t_s, sa, sb, sc (switch states),
 * m_index, f_hz, v_dc_v, v_an_v, v_bn_v, v_cn_v (the inverter's phase-to-
 * neutral voltages), vc_a_v, vc_b_v, vc_c_v (filter capacitors), i_a_a,
 * i_b_a, i_c_a (motor phase currents), i_dc_a, n_rpm, te_nm; 7 significant
 * digits, no -0.
 */
#ifndef UUV_CSV_OUT_H
#define UUV_CSV_OUT_H

#include <stdbool.h>
#include <stdio.h>

#include "executive.h"
#include "out_file.h"

/* The protection's reasons, by the telemetry's trip value (drive_trip). */
#define OUT_TRIP_NAMES 4u
extern const char *const out_trip_names[OUT_TRIP_NAMES];

/* [-] magnitudes below this are written as 0 (a tenth of a femto-unit of any column). */
#define CSV_FLUSH 1e-15

void csv_number(FILE *f, double v);
/* The same text into buf (capacity cap, at least 32). */
void csv_format_number(char *buf, size_t cap, double v);
void csv_header(FILE *f, bool full_plant);
void csv_row(FILE *f, const exec_frame *r, bool full_plant);

void trace_header(FILE *f);
void trace_row(FILE *f, double t_s, const drive_trace_row *r);

#endif /* UUV_CSV_OUT_H */
