/*
 * Output files of the host programs (uuvsim, uuvsim-decode), written so that
 * a run replaces nothing it should not and leaves nothing half-written:
 *
 * - out_check, before anything is written: every output must be a regular
 *   file or not exist yet (a symbolic link, a device such as /dev/stdout, a
 *   FIFO or a directory is refused), and no two of the outputs and inputs
 *   may be the same file: the same path (after resolving the directory) or,
 *   for files that exist, the same device and inode;
 * - out_open creates the temporary file FILE.partial.PID (PID: the
 *   process's id, unique among the runs) in the target's directory,
 *   exclusively (O_CREAT | O_EXCL | O_NOFOLLOW): when anything, a symbolic
 *   link included, has that name, the run is refused; it is never opened or
 *   followed;
 * - out_finish flushes, syncs and closes it, checking every error;
 * - out_commit renames it to FILE, once every output of the run is
 *   finished (a run commits all its outputs or none);
 * - out_abort removes it; so does SIGINT, SIGTERM or SIGHUP, whose handler
 *   (out_guard_signals) removes every temporary file still open and then
 *   ends the program as the signal would have.
 *
 * Messages start with the program's name, which out_program sets.
 */
#ifndef UUV_OUT_FILE_H
#define UUV_OUT_FILE_H

#include <stdbool.h>
#include <stdio.h>

typedef struct {
    FILE *f;
    char path[4096];
    char tmp[4096 + 48];
    bool finished;
} out_file;

/* The name messages start with ("uuvsim" unless set). */
void out_program(const char *name);

/* A file a run names: the option that named it (for messages) and its path (NULL: none). */
typedef struct {
    const char *option;
    const char *path;
} out_spec;

/*
 * Checks the n_out outputs against each other and against the n_in inputs
 * (entries with a NULL path are skipped); prints the first problem.
 */
bool out_check(const out_spec *outputs, int n_out, const out_spec *inputs, int n_in);

/* Creates the temporary file; prints the error on failure. */
bool out_open(out_file *o, const char *path);
/* Flushes, syncs and closes the temporary file; prints the error on failure. */
bool out_finish(out_file *o);
/* Renames a finished temporary file into place; prints the error on failure. */
bool out_commit(out_file *o);
/* Abandons the file: removes the temporary file (any state; no-op when none). */
void out_abort(out_file *o);

/* Installs the handlers that remove the temporary files on SIGINT, SIGTERM, SIGHUP. */
void out_guard_signals(void);

/* Flushes stdout; on a write error or a short write prints it and returns false. */
bool out_stdout_ok(void);

#endif /* UUV_OUT_FILE_H */
