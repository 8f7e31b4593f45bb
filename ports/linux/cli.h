/*
 * The uuvsim command line, parsed into options. Kept apart from main so
 * that tests and fuzzers can drive it without running a simulation.
 */
#ifndef UUV_CLI_H
#define UUV_CLI_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "executive.h"

/* How the desk takes its runs of fast steps (--fast-path). */
typedef enum {
    CLI_FAST_EXACT = 0, /* the firmware's step, bit for bit */
    CLI_FAST_LEAP       /* exact leaps between switching events (float build; leap.h) */
} cli_fast_path;

typedef enum { CLI_RUN, CLI_DERIVS, CLI_VIEW, CLI_HELP, CLI_VERSION, CLI_PARAMS } cli_action;

#define CLI_MAX_SETS 64 /* --set options */

typedef struct {
    cli_action action;
    const char *scenario_path;  /* --scenario */
    const char *csv_path;       /* --csv */
    const char *trace_path;     /* --trace */
    const char *summary_path;   /* --summary: the JSON summary, to a file */
    const char *derivs_path;    /* derivs FILE */
    const char *view_dir;       /* view RUN_DIR */
    const char *params_path;    /* --params: a parameter set (ports/linux/params.h) */
    const char *emit_c_path;    /* params --emit-c: the set as C, for a firmware image */
    const char *sets[CLI_MAX_SETS]; /* --set KEY=VALUE, in order */
    int n_sets;
    double trace_from_s;        /* --trace-from */
    double trace_to_s;          /* --trace-to */
    exec_config exec;           /* plant, laws, inverter, couplings, rates, duration */
    uint64_t motor_frame_ns;    /* --motor-frame; 0: the default (exec_config_default) */
    uint64_t control_frame_ns;  /* --control-frame; 0: the default */
    uint64_t slow_frame_ns;     /* --slow-frame; 0: the default */
    uint64_t dead_time_ns;      /* --dead-time; 0: not given (the set's pwm.dead_time) */
    char dead_time_set[48];     /* --dead-time as the override "pwm.dead_time=N ns" */
    cli_fast_path fast_path;    /* --fast-path */
    bool realtime;
    bool view;                  /* --view: the live view (implies --realtime) */
    double view_port;           /* --view-port: its port on 127.0.0.1 (0: any free one) */
    bool json;                  /* the JSON summary on stdout (instead of the text one) */
    bool quiet;                 /* no text summary, no progress line */
} cli_options;

/*
 * Parses argv. Returns true on success; otherwise writes a one-line message
 * (without the program name) into err and returns false.
 */
bool cli_parse(int argc, char **argv, cli_options *o, char *err, size_t err_len);

/* The frames of a configuration [ns]: fast step, motor task, controller, slow step. */
void cli_frames_ns(const exec_config *c, uint64_t ns[4]);

/* A frame length for messages: "100 us", "0.8 ms", "2 s" (into buf, returned). */
const char *cli_frame_text(uint64_t ns, char *buf, size_t len);

extern const char cli_usage[];
extern const char cli_usage_studies[]; /* printed after cli_usage */

#endif /* UUV_CLI_H */
