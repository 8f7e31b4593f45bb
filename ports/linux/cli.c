/*
 * The uuvsim command line (see cli.h). Table-driven: each option names the
 * field it sets and how its value is read.
 */
#include "cli.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "util/parse.h"

const char cli_usage[] =
    "usage: uuvsim [options] --scenario FILE\n"
    "       uuvsim derivs FILE.csv\n"
    "\n"
    "Simulates the vehicle on a scenario and prints a summary.\n"
    "\n"
    "  --scenario FILE          scenario file (see scenarios/*.scn)\n"
    "  --duration S             simulated time [s] (default: the scenario's)\n"
    "  --plant full|vessel      battery, drive and vessel (default), or the vessel\n"
    "                           alone with the shaft speed through its 0.1 s lag\n"
    "  --propulsion paper|mss   thrust law (default paper)\n"
    "  --inverter switching|averaged|event\n"
    "                           switching: switch states held over each 2 us step;\n"
    "                           averaged: leg duty cycles, quasi-static filter, the\n"
    "                           stage and the motor at the controller's 800 us frame\n"
    "                           (no switch, leg, phase or contactor faults);\n"
    "                           event: switching instants located inside the step\n"
    "  --single-rate            every segment at 2 us (the reference)\n"
    "  --energy-audit           count the filter's and the motor's losses and print\n"
    "                           the energy balance (slower: the general fast path)\n"
    "  --slow-to-fast zoh|foh|deriv|stagger\n"
    "                           how the motor's currents reach the 2 us steps\n"
    "  --fast-to-slow avg|filter|sample\n"
    "                           how fast signals are reduced for slower segments\n"
    "  --csv FILE               telemetry, one row per 100 ms\n"
    "  --trace FILE             every 2 us step between --trace-from and --trace-to [s]\n"
    "  --realtime               pace the run to the wall clock\n"
    "  --summary FILE           the summary as JSON, to a file\n"
    "  --json                   the summary as JSON on stdout\n"
    "  --quiet                  no text summary, no progress line\n"
    "  --help, --version\n"
    "\n"
    "derivs FILE.csv: reads commands and states in the layout of the reference\n"
    "derivative vectors and prints the same layout with the derivatives of the\n"
    "vessel model (MSS propulsion, actuator lag).\n";

static bool fail(char *err, size_t len, const char *format, ...)
    __attribute__((format(printf, 3, 4)));

static bool fail(char *err, size_t len, const char *format, ...) {
    va_list args;
    va_start(args, format);
    (void)vsnprintf(err, len, format, args);
    va_end(args);
    /* An argument echoed in the message may hold control characters; the
     * message stays on one line, as cli.h promises. */
    for (size_t i = 0; i < len && err[i] != '\0'; i++) {
        if ((unsigned char)err[i] < 0x20u || err[i] == '\x7f') {
            err[i] = '?';
        }
    }
    return false;
}

typedef enum { OPT_FLAG, OPT_PATH, OPT_SECONDS, OPT_CHOICE } opt_kind;

typedef struct {
    const char *name;
    opt_kind kind;
    const char *choices; /* OPT_CHOICE: names separated by '|', in enum order */
    size_t offset;       /* of the field in cli_options */
} opt_spec;

#define FIELD(f) offsetof(cli_options, f)

static const opt_spec options[] = {
    {"--scenario", OPT_PATH, NULL, FIELD(scenario_path)},
    {"--csv", OPT_PATH, NULL, FIELD(csv_path)},
    {"--trace", OPT_PATH, NULL, FIELD(trace_path)},
    {"--summary", OPT_PATH, NULL, FIELD(summary_path)},
    {"--duration", OPT_SECONDS, NULL, FIELD(exec.duration_s)},
    {"--trace-from", OPT_SECONDS, NULL, FIELD(trace_from_s)},
    {"--trace-to", OPT_SECONDS, NULL, FIELD(trace_to_s)},
    {"--plant", OPT_CHOICE, "vessel|full", FIELD(exec.plant)},
    {"--propulsion", OPT_CHOICE, "mss|paper", FIELD(exec.propulsion)},
    {"--inverter", OPT_CHOICE, "switching|averaged|event", FIELD(exec.inverter)},
    {"--slow-to-fast", OPT_CHOICE, "zoh|foh|deriv|stagger", FIELD(exec.down)},
    {"--fast-to-slow", OPT_CHOICE, "avg|filter|sample", FIELD(exec.up)},
    {"--single-rate", OPT_FLAG, NULL, FIELD(exec.single_rate)},
    {"--energy-audit", OPT_FLAG, NULL, FIELD(exec.energy_audit)},
    {"--realtime", OPT_FLAG, NULL, FIELD(realtime)},
    {"--json", OPT_FLAG, NULL, FIELD(json)},
    {"--quiet", OPT_FLAG, NULL, FIELD(quiet)},
};

/* Index of value among the '|'-separated choices, or -1. */
static int choice_index(const char *choices, const char *value) {
    size_t n = strlen(value);
    int index = 0;
    for (const char *p = choices;; index++) {
        const char *end = strchr(p, '|');
        size_t len = end ? (size_t)(end - p) : strlen(p);
        if (len == n && strncmp(p, value, n) == 0) {
            return index;
        }
        if (end == NULL) {
            return -1;
        }
        p = end + 1;
    }
}

static bool set_option(const opt_spec *spec, const char *value, cli_options *o, char *err,
                       size_t err_len) {
    char *field = (char *)o + spec->offset;
    switch (spec->kind) {
    case OPT_FLAG:
        *(bool *)(void *)field = true;
        return true;
    case OPT_PATH:
        *(const char **)(void *)field = value;
        return true;
    case OPT_SECONDS: {
        double v = 0.0;
        size_t used = 0;
        size_t n = strlen(value);
        if (!parse_number(value, n, &v, &used) || used != n || !(v >= 0.0 && v <= 1e6)) {
            return fail(err, err_len, "option %s: expected seconds in [0, 1e6], got '%s'",
                        spec->name, value);
        }
        if (spec->offset == FIELD(exec.duration_s) && !(v > 0.0)) {
            return fail(err, err_len, "option --duration: expected seconds in (0, 1e6], got '%s'",
                        value);
        }
        *(double *)(void *)field = v;
        return true;
    }
    case OPT_CHOICE: {
        int k = choice_index(spec->choices, value);
        if (k < 0) {
            return fail(err, err_len, "option %s: expected one of %s, got '%s'", spec->name,
                        spec->choices, value);
        }
        /* Every choice field is an enum, stored as an int-sized object. */
        *(int *)(void *)field = k;
        return true;
    }
    }
    return false;
}

bool cli_parse(int argc, char **argv, cli_options *o, char *err, size_t err_len) {
    *o = (cli_options){0};
    o->action = CLI_RUN;
    exec_config_default(&o->exec);
    o->trace_to_s = -1.0;
    if (argc >= 2 && strcmp(argv[1], "derivs") == 0) {
        if (argc != 3) {
            return fail(err, err_len, "derivs: expected exactly one CSV file");
        }
        o->action = CLI_DERIVS;
        o->derivs_path = argv[2];
        return true;
    }
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            o->action = CLI_HELP;
            return true;
        }
        if (strcmp(a, "--version") == 0) {
            o->action = CLI_VERSION;
            return true;
        }
        const opt_spec *spec = NULL;
        for (size_t k = 0; k < sizeof options / sizeof options[0]; k++) {
            if (strcmp(a, options[k].name) == 0) {
                spec = &options[k];
            }
        }
        if (spec == NULL) {
            return fail(err, err_len, "unknown option '%s' (see --help)", a);
        }
        const char *value = NULL;
        if (spec->kind != OPT_FLAG) {
            if (i + 1 >= argc || argv[i + 1][0] == '\0') {
                return fail(err, err_len, "option %s: expected a value", a);
            }
            value = argv[++i];
        }
        if (!set_option(spec, value, o, err, err_len)) {
            return false;
        }
    }
    if (o->scenario_path == NULL) {
        return fail(err, err_len, "no scenario: expected --scenario FILE (see --help)");
    }
    if (o->trace_path != NULL) {
        if (o->exec.plant != EXEC_PLANT_FULL) {
            return fail(err, err_len, "option --trace: needs --plant full");
        }
        if (o->trace_to_s < 0.0) {
            o->trace_to_s = o->trace_from_s + 0.02; /* one fundamental period or so */
        }
        if (!(o->trace_to_s > o->trace_from_s)) {
            return fail(err, err_len, "option --trace-to: must come after --trace-from");
        }
        if (o->trace_to_s - o->trace_from_s > 10.0) {
            return fail(err, err_len, "option --trace-to: the trace window is at most 10 s");
        }
    }
    return true;
}
