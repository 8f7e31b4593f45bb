/*
 * The live view of a paced run (uuvsim --view, live.c): the mission page
 * on a local port while the run makes its 100 ms frames.
 */
#ifndef UUV_LIVE_H
#define UUV_LIVE_H

#include <stdbool.h>
#include <stddef.h>

#include "executive.h"

typedef struct live_server live_server;

/* Listens on 127.0.0.1:port (0: any free port) and prints the address on
 * stderr; NULL (the error printed) when it cannot. */
live_server *live_open(unsigned port, bool full_plant);
/* Keeps the frame and sends it to the browsers that stream. */
void live_frame(live_server *l, const exec_frame *f);
/* Serves requests for the given time [s] (at least once, also when <= 0). */
void live_wait(live_server *l, double seconds);
/* Serves until a browser has opened the page and its stream. */
void live_wait_browser(live_server *l);
/* Sends the summary (JSON text) and the end to the streams and closes them. */
void live_end(live_server *l, const char *summary, size_t len);
void live_close(live_server *l);

#endif /* UUV_LIVE_H */
