/*
 * Parameter sets on the desk (src/params.h holds the set itself): one table
 * of keys (name, unit, allowed range, source, the struct field it sets)
 * serves the printer (uuvsim params), the parser (--params FILE, --set
 * key=value) and the firmware generator (uuvsim params --emit-c), so that
 * the three cannot disagree.
 *
 * File format, one key per line, '#' starts a comment:
 *     name SET-NAME
 *     KEY VALUE... UNIT
 * UNIT is the key's unit as `uuvsim params` prints it ("-" for a
 * dimensionless key); a battery table key takes one value per breakpoint.
 * A set file lists the keys it changes: every key it does not list keeps
 * the default set's value. The controller's four gains may be given as
 * "auto"; a gain not given follows from the motor, the filter, the
 * propeller's inertia and the design targets (control.speed_crossover,
 * control.speed_zero_ratio, control.current_bandwidth) whenever the set
 * changes one of those.
 */
#ifndef UUV_PARAMSET_H
#define UUV_PARAMSET_H

#include <stdbool.h>
#include <stdio.h>

#include "params.h"

/* One override given on the command line (--set KEY=VALUE). */
#define PARAMS_MAX_SETS 64

typedef struct param_store param_store;

/* A loaded set: the models' structs the uuv_params points to. */
param_store *params_new(void);
void params_free(param_store *s);

/*
 * Loads FILE over the default set (path NULL: the default set alone), then
 * applies the overrides "KEY=VALUE[ UNIT]" in order, derives what follows
 * from them and checks the result: ranges, the models' own checks and (in
 * the fixed build) the per-unit bases. On failure prints
 * "uuvsim: FILE:LINE: KEY: what was expected, got what" and returns false.
 */
bool params_load(param_store *s, const char *path, const char *const *sets, int n_sets);

/*
 * Checks the loaded set against the run's inverter: a dead time
 * (pwm.dead_time) is modelled only by the switching inverter with sub-step
 * edges, and a set that gives one to another inverter is refused (message
 * as above, false) rather than run without it. dead_time_modelled: the run
 * has no drive, or that inverter.
 */
bool params_check_run(const param_store *s, bool dead_time_modelled);

/* The set, for exec_config.params. */
const uuv_params *params_set(const param_store *s);

/* "default", or the file's name line (or its path), and the overrides, for summaries. */
const char *params_label(const param_store *s);

/* Writes the set in the file format, every key with its unit, range and source. */
void params_print(FILE *f, const param_store *s);

/* Writes the set as C (constant param structs and `fw_params`) for a firmware image. */
void params_emit_c(FILE *f, const param_store *s, const char *source);

/*
 * uuvsim params [--params FILE] [--set KEY=VALUE]... [--emit-c FILE.c]:
 * prints the set (or writes it as C); the exit status (0, 2 bad input).
 */
int params_command(const char *path, const char *const *sets, int n_sets, const char *emit_c);

#endif /* UUV_PARAMSET_H */
