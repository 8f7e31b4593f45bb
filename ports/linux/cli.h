/*
 * The uuvsim command line, parsed into options. Kept apart from main so
 * that tests and fuzzers can drive it without running a simulation.
 */
#ifndef UUV_CLI_H
#define UUV_CLI_H

#include <stdbool.h>
#include <stddef.h>

#include "executive.h"

typedef enum { CLI_RUN, CLI_DERIVS, CLI_HELP, CLI_VERSION } cli_action;

typedef struct {
    cli_action action;
    const char *scenario_path;  /* --scenario */
    const char *csv_path;       /* --csv */
    const char *trace_path;     /* --trace */
    const char *summary_path;   /* --summary: the JSON summary, to a file */
    const char *derivs_path;    /* derivs FILE */
    double trace_from_s;        /* --trace-from */
    double trace_to_s;          /* --trace-to */
    exec_config exec;           /* plant, laws, inverter, couplings, rates, duration */
    bool realtime;
    bool json;                  /* the JSON summary on stdout (instead of the text one) */
    bool quiet;                 /* no text summary, no progress line */
} cli_options;

/*
 * Parses argv. Returns true on success; otherwise writes a one-line message
 * (without the program name) into err and returns false.
 */
bool cli_parse(int argc, char **argv, cli_options *o, char *err, size_t err_len);

extern const char cli_usage[];

#endif /* UUV_CLI_H */
