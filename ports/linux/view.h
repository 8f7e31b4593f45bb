/*
 * The mission page (view.c): `uuvsim view RUN_DIR` writes it from a run's
 * files; the live view (live.c) serves it while a paced run goes on.
 */
#ifndef UUV_VIEW_H
#define UUV_VIEW_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

typedef struct {
    char *data; /* malloc'd, NUL-terminated */
    size_t len;
} view_text;

/* `uuvsim view RUN_DIR`: writes RUN_DIR/mission.html; the exit status (0, or 2). */
int uuvsim_view(const char *dir);

/* Reads three.js (libjs-three, or $UUVSIM_THREE_JS); prints the error on failure. */
bool view_read_three(view_text *three);

/* The page: the template with three.js, the telemetry CSV (header and rows),
 * the summary (NULL or no data: none yet) and whether it is live. */
void view_write_page(FILE *f, const view_text *three, const view_text *csv,
                     const view_text *summary, bool live);

#endif /* UUV_VIEW_H */
