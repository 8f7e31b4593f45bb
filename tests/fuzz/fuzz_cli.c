/*
 * libFuzzer harness for the desk simulator's command line (ports/linux/cli.c).
 *
 * The input is an argument vector: arguments separated by NUL bytes (at most
 * MAX_ARGS of them, each in its own heap block so that a read past an
 * argument is caught). cli_parse must never crash, and a rejected command
 * line must give a one-line, NUL-terminated, non-empty message that names
 * the option (or the missing one) at fault. An accepted one must give
 * finite trace times and a known action.
 */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

#define MAX_ARGS 64

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void broken(const char *what, const char *err) {
    fprintf(stderr, "contract broken: %s (message '%s')\n", what, err);
    abort();
}

static void check_rejected(const char *err, size_t len) {
    if (memchr(err, '\0', len) == NULL) {
        broken("an unterminated message", "");
    }
    if (err[0] == '\0') {
        broken("an empty message", err);
    }
    if (strchr(err, '\n') != NULL) {
        broken("a message on more than one line", err);
    }
    /* Each message begins with what it is about: an option, or the command. */
    if (strncmp(err, "option ", 7) != 0 && strncmp(err, "unknown option ", 15) != 0 &&
        strncmp(err, "no scenario", 11) != 0 && strncmp(err, "derivs", 6) != 0) {
        broken("a message that names no option", err);
    }
}

static void check_accepted(const cli_options *o) {
    if (o->action != CLI_RUN && o->action != CLI_DERIVS && o->action != CLI_HELP &&
        o->action != CLI_VERSION) {
        broken("an unknown action", "");
    }
    if (!isfinite(o->trace_from_s) || !isfinite(o->trace_to_s)) {
        broken("a trace window that is not finite", "");
    }
    if (o->action == CLI_RUN && o->scenario_path == NULL) {
        broken("a run without a scenario", "");
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    char *argv[MAX_ARGS + 1];
    int argc = 0;
    argv[argc++] = strdup("uuvsim");
    size_t start = 0u;
    while (start < size && argc < MAX_ARGS) {
        size_t end = start;
        while (end < size && data[end] != 0u) {
            end++;
        }
        char *arg = malloc(end - start + 1u);
        if (arg == NULL) {
            break;
        }
        memcpy(arg, data + start, end - start);
        arg[end - start] = '\0';
        argv[argc++] = arg;
        start = end + 1u;
    }
    argv[argc] = NULL;
    cli_options o;
    char err[160];
    memset(err, 'x', sizeof err);
    err[sizeof err - 1u] = '\0';
    if (cli_parse(argc, argv, &o, err, sizeof err)) {
        check_accepted(&o);
    } else {
        check_rejected(err, sizeof err);
    }
    for (int i = 0; i < argc; i++) {
        free(argv[i]);
    }
    return 0;
}
