/*
 * One desk run in pieces, for uuvsim's own run and for uuvsim batch
 * (batch.c), which runs several side by side with their fast steps in
 * lanes: the same code opens, steps, records and closes every run, so a
 * run in a batch writes what it writes alone.
 *
 *   u = uuvsim_run_open(o, &status);         scenario, parameters, outputs
 *   while (uuvsim_run_exec(u)->state == EXEC_RUNNING) {
 *       ticks = uuvsim_run_ahead(u);         at most this many ticks next
 *       ... exec_desk_run(uuvsim_run_exec(u), ticks), or the same ticks
 *       ... run another way with the same results (batch_lanes.h)
 *       uuvsim_run_after(u);                 trace row, record, pacing
 *   }
 *   status = uuvsim_run_close(u, wall_s);    summary, commit, exit status
 */
#ifndef UUV_RUN_H
#define UUV_RUN_H

#include <stdint.h>

#include "cli.h"
#include "executive.h"

typedef struct uuvsim_run uuvsim_run;

/*
 * Opens a run of the options o (which must outlive it): loads and checks
 * the scenario and the parameter set, initialises the executive, opens the
 * outputs (temporary files until the close) and writes the first record.
 * On bad input it prints why and returns NULL with *status 2.
 */
uuvsim_run *uuvsim_run_open(const cli_options *o, int *status);

exec *uuvsim_run_exec(uuvsim_run *u);

/* The most ticks the next exec_desk_run() may take (one at a time in a trace window). */
uint32_t uuvsim_run_ahead(const uuvsim_run *u);

/* After the ticks: the trace row, the record (CSV, live view), the pacing. */
void uuvsim_run_after(uuvsim_run *u);

/*
 * Ends the run: the summaries with wall_s as the run's time (a negative
 * wall_s: the wall clock since the open), commits the outputs and frees
 * the run. Returns the exit status (uuvsim.c's: 0, 1, 2 or 3).
 */
int uuvsim_run_close(uuvsim_run *u, double wall_s);

/* Removes the run's outputs and frees it (a batch that stops before running). */
void uuvsim_run_abort(uuvsim_run *u);

/* The wall clock [s] (monotonic) the runs' timing uses. */
double uuvsim_wall_s(void);

/* uuvsim batch (batch.c). */
int batch_main(int argc, char **argv);

#endif /* UUV_RUN_H */
