/*
 * Sweeps and Monte Carlo studies of the desk simulator (docs/studies.md):
 *
 *   uuvsim sweep FILE --out DIR [-j N] [--shard K/N]
 *   uuvsim sweep-merge --out DIR PART_DIR...
 *
 * A sweep file names the base scenario and parameter set, a grid over keys
 * and/or Monte Carlo draws (uniform, normal, seeded: the same draws on
 * every machine and in every shard), the uuvsim options of every run and
 * the metrics to collect. Each variant runs as its own uuvsim process, at
 * most N at a time; each finished run leaves its row in DIR/runs/ (written
 * whole, then renamed), so an interrupted sweep resumes where it stopped
 * without losing or repeating a row. A run that fails is a row with its
 * exit status and its error. DIR/results.csv and DIR/results.json hold
 * one row per run, in run order; a shard holds its part (runs K-1, K-1+N,
 * ...) and sweep-merge joins the parts into the single-process result.
 */
#ifndef UUV_SWEEP_H
#define UUV_SWEEP_H

/* argv[0] is the program, argv[1] "sweep" or "sweep-merge"; the exit status. */
int sweep_main(int argc, char **argv);

#endif /* UUV_SWEEP_H */
