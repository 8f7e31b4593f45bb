/*
 * Slow-rate telemetry as CSV: the reference trajectory layout (t_s, the 17
 * vessel states, the 5 commands), every value with 17 significant digits so
 * that it reads back as the same double. Written to FILE.partial and renamed
 * to FILE when complete.
 */
#ifndef UUV_CSV_OUT_H
#define UUV_CSV_OUT_H

#include <stdbool.h>
#include <stdio.h>

#include "sim.h"

typedef struct {
    FILE *f;
    char path[4096];
    char partial[4096 + 16];
} csv_out;

/* Opens the partial file and writes the header; prints the error on failure. */
bool csv_out_open(csv_out *c, const char *path);
void csv_out_frame(csv_out *c, const sim_frame *f);
/* Completes the file (renames it into place); prints the error on failure. */
bool csv_out_close(csv_out *c);
/* Abandons the file: removes the partial output. */
void csv_out_abort(csv_out *c);

#endif /* UUV_CSV_OUT_H */
