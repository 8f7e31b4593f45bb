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
    "usage: uuvsim [options] --scenario FILE     (or --scenario=FILE; likewise every option)\n"
    "       uuvsim derivs FILE.csv\n"
    "       uuvsim view RUN_DIR\n"
    "\n"
    "Simulates the vehicle on a scenario and prints a summary.\n"
    "\n"
    "  --scenario FILE          scenario file (see scenarios/*.scn)\n"
    "  --duration S             simulated time [s] (default: the scenario's)\n"
    "  --plant full|vessel      battery, drive and vessel (default), or the vessel\n"
    "                           alone with the shaft speed through its 0.1 s lag\n"
    "  --propulsion paper|mss   thrust law (default paper)\n"
    "  --inverter switching|averaged|event\n"
    "                           switching: six switches at the 2 us step (see\n"
    "                           --modulator);\n"
    "                           averaged: leg duty cycles, quasi-static filter, the\n"
    "                           stage and the motor at the controller's 800 us frame\n"
    "                           (no switch, leg, phase or contactor faults);\n"
    "                           event: switching instants located inside the step\n"
    "  --modulator substep|sampled\n"
    "                           the switching inverter's: substep (default): each\n"
    "                           leg's on-time located inside the step, the step's\n"
    "                           mean pole voltage applied; sampled: the switch\n"
    "                           states at the step's start held over the step\n"
    "  --dead-time T            T with its unit: --set pwm.dead_time=T (after the\n"
    "                           other --set options): both switches of a leg off\n"
    "                           for T at every edge; switching inverter, substep\n"
    "                           modulator; default the set's (none)\n"
    "  --single-rate            every segment at 2 us (the reference)\n"
    "  --deep-water             no free surface (the reference vessel of the vectors:\n"
    "                           buoyancy B wherever the vehicle is)\n"
    "  --energy-audit           count the filter's and the motor's losses and print\n"
    "                           the energy balance (slower: the general fast path)\n"
    "  --slow-to-fast zoh|foh|deriv|stagger\n"
    "                           how the motor's EMF reaches the 2 us steps\n"
    "                           (default zoh)\n"
    "  --fast-to-slow avg|filter|sample\n"
    "                           how fast signals are reduced for slower segments\n"
    "  --motor-frame T          the motor task's frame (default 100us), a whole\n"
    "                           number of 2 us fast steps\n"
    "  --control-frame T        the controller's frame (default 800us), a whole\n"
    "                           number of motor frames\n"
    "  --slow-frame T           the vessel's and the battery's frame (default 100ms),\n"
    "                           a whole number of controller frames; T with its\n"
    "                           unit: us, ms or s\n"
    "  --csv FILE               telemetry, one row per slow frame (100 ms)\n"
    "  --trace FILE             every 2 us step between --trace-from and --trace-to [s]\n"
    "                           (defaults: from 0, to 0.02 s after --trace-from; the\n"
    "                           window must start before the end of the run)\n"
    "  --realtime               pace the run to the wall clock\n"
    "  --view                   the live view: the mission page on 127.0.0.1 while\n"
    "                           the paced run (--view implies --realtime) makes its\n"
    "                           frames; the address goes to stderr, and the run\n"
    "                           starts when a browser opens it\n"
    "  --view-port N            its port (default 8026; 0: any free port)\n"
    "  --summary FILE           the summary as JSON, to a file\n"
    "  --json                   the summary as JSON on stdout\n"
    "  --quiet                  no text summary, no progress line\n"
    "  --help, --version\n"
    "\n"
    "derivs FILE.csv: reads commands and states in the layout of the reference\n"
    "derivative vectors and prints the same layout with the derivatives of the\n"
    "vessel model (MSS propulsion, actuator lag).\n"
    "\n"
    "view RUN_DIR: writes RUN_DIR/mission.html, the run of RUN_DIR/telemetry.csv\n"
    "(and summary.json) in 3-D with its plots, one page that opens from file://\n"
    "(three.js from libjs-three; UUVSIM_THREE_JS names another copy).\n";

/* The usage's second part (C99 bounds a string literal at 4095 characters). */
const char cli_usage_studies[] =
    "\n"
    "Desk speed (docs/multirate.md, \"Speed\"):\n"
    "  --fast-path exact|leap   exact (default): the firmware's 2 us step, bit for\n"
    "                           bit; leap: each stretch of steps between two\n"
    "                           switching events as one map of the same model\n"
    "                           (within float rounding of exact; float build only;\n"
    "                           paths without leaps step as exact)\n"
    "\n"
    "Parameter sets and studies (docs/studies.md):\n"
    "       uuvsim params [--params FILE] [--set KEY=VALUE]... [--emit-c FILE.c]\n"
    "       uuvsim sweep FILE --out DIR [-j N] [--shard K/N]\n"
    "       uuvsim sweep-merge --out DIR DIR1 DIR2...\n"
    "       uuvsim batch --out DIR [--list FILE] [SCENARIO...] [-- OPTION...]\n"
    "                           runs side by side, their fast steps in SIMD lanes;\n"
    "                           run NAME writes DIR/NAME.csv and DIR/NAME.json\n"
    "  --params FILE            a run's parameter set (uuvsim params prints the\n"
    "                           default one with every key's unit, range, source)\n"
    "  --set KEY=VALUE          overrides one key of the set (repeatable); the value\n"
    "                           may end in its unit: --set 'stage.l=2e-3 H'\n"
    "  --emit-c FILE.c          (params) the set as C, for make firmware PARAMS=FILE\n"
    "\n"
    "The multi-party run's slow segment (make qemu-party, docs/cosimulation.md):\n"
    "       uuvsim party --link SOCKET --scenario FILE [--duration S] [--csv FILE]\n"
    "                    [--timeout S] [--corrupt-down K] [--drop-down K] [--corrupt-up K]\n";

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

typedef enum { OPT_FLAG, OPT_PATH, OPT_SECONDS, OPT_CHOICE, OPT_FRAME, OPT_PORT, OPT_SET } opt_kind;

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
    {"--params", OPT_PATH, NULL, FIELD(params_path)},
    {"--emit-c", OPT_PATH, NULL, FIELD(emit_c_path)},
    {"--set", OPT_SET, NULL, FIELD(sets)},
    {"--duration", OPT_SECONDS, NULL, FIELD(exec.duration_s)},
    {"--trace-from", OPT_SECONDS, NULL, FIELD(trace_from_s)},
    {"--trace-to", OPT_SECONDS, NULL, FIELD(trace_to_s)},
    {"--plant", OPT_CHOICE, "vessel|full", FIELD(exec.plant)},
    {"--propulsion", OPT_CHOICE, "mss|paper", FIELD(exec.propulsion)},
    {"--inverter", OPT_CHOICE, "switching|averaged|event", FIELD(exec.inverter)},
    {"--modulator", OPT_CHOICE, "substep|sampled", FIELD(exec.modulator)},
    {"--dead-time", OPT_FRAME, NULL, FIELD(dead_time_ns)},
    {"--slow-to-fast", OPT_CHOICE, "zoh|foh|deriv|stagger", FIELD(exec.down)},
    {"--fast-to-slow", OPT_CHOICE, "avg|filter|sample", FIELD(exec.up)},
    {"--motor-frame", OPT_FRAME, NULL, FIELD(motor_frame_ns)},
    {"--control-frame", OPT_FRAME, NULL, FIELD(control_frame_ns)},
    {"--slow-frame", OPT_FRAME, NULL, FIELD(slow_frame_ns)},
    {"--fast-path", OPT_CHOICE, "exact|leap", FIELD(fast_path)},
    {"--single-rate", OPT_FLAG, NULL, FIELD(exec.single_rate)},
    {"--deep-water", OPT_FLAG, NULL, FIELD(exec.deep_water)},
    {"--energy-audit", OPT_FLAG, NULL, FIELD(exec.energy_audit)},
    {"--realtime", OPT_FLAG, NULL, FIELD(realtime)},
    {"--view", OPT_FLAG, NULL, FIELD(view)},
    {"--view-port", OPT_PORT, NULL, FIELD(view_port)},
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

#define FRAME_MAX_NS 10000000000.0 /* [ns] 10 s, the executive's longest slow frame */

const char *cli_frame_text(uint64_t ns, char *buf, size_t len) {
    if (ns % 1000000000u == 0u) {
        snprintf(buf, len, "%llu s", (unsigned long long)(ns / 1000000000u));
    } else if (ns >= 1000000u) {
        snprintf(buf, len, "%.9g ms", (double)ns * 1e-6);
    } else {
        snprintf(buf, len, "%.9g us", (double)ns * 1e-3);
    }
    return buf;
}

/* A frame length with its unit (us, ms, s) in whole nanoseconds; 0 if malformed. */
static uint64_t frame_ns_of(const char *value) {
    double v = 0.0;
    size_t used = 0;
    if (!parse_number(value, strlen(value), &v, &used)) {
        return 0u;
    }
    const char *unit = value + used;
    double scale = (strcmp(unit, "us") == 0)   ? 1e3
                   : (strcmp(unit, "ms") == 0) ? 1e6
                   : (strcmp(unit, "s") == 0)  ? 1e9
                                               : 0.0;
    double ns = v * scale;
    if (!(ns >= 1.0 && ns <= FRAME_MAX_NS)) {
        return 0u;
    }
    uint64_t whole = (uint64_t)(ns + 0.5);
    double off = ns - (double)whole;
    return (off < 1e-3 && off > -1e-3) ? whole : 0u;
}

void cli_frames_ns(const exec_config *c, uint64_t ns[4]) {
    ns[0] = c->fast_ns;
    ns[1] = ns[0] * c->fast_per_medium;
    ns[2] = ns[1] * c->medium_per_control;
    ns[3] = ns[1] * c->medium_per_slow;
}

/* Whether the frame outer (option opt) is a whole number of inner frames (what). */
static bool frame_divides(const char *opt, const char *what, uint64_t inner, uint64_t outer,
                          bool given, char *err, size_t err_len) {
    if (outer % inner == 0u) {
        return true;
    }
    char a[32], b[32];
    return fail(err, err_len, "option %s: expected a whole number of %s (%s), got %s%s%s%s",
                opt, what, cli_frame_text(inner, b, sizeof b), cli_frame_text(outer, a, sizeof a),
                given ? "" : " (the default: give ", given ? "" : opt, given ? "" : ")");
}

/*
 * The frames the options give (each a default where not given): the motor
 * frame a whole number of fast steps, the controller's a whole number of
 * motor frames, the slow one a whole number of controller frames.
 */
static bool apply_frames(cli_options *o, char *err, size_t err_len) {
    exec_config *c = &o->exec;
    uint64_t ns[4];
    cli_frames_ns(c, ns); /* the defaults (exec_config_default) */
    const uint64_t fast = ns[0];
    const uint64_t motor = (o->motor_frame_ns != 0u) ? o->motor_frame_ns : ns[1];
    const uint64_t control = (o->control_frame_ns != 0u) ? o->control_frame_ns : ns[2];
    const uint64_t slow = (o->slow_frame_ns != 0u) ? o->slow_frame_ns : ns[3];
    if (!frame_divides("--motor-frame", "fast steps", fast, motor, true, err, err_len) ||
        !frame_divides("--control-frame", "motor frames", motor, control,
                       o->control_frame_ns != 0u, err, err_len) ||
        !frame_divides("--slow-frame", "controller frames", control, slow,
                       o->slow_frame_ns != 0u, err, err_len)) {
        return false;
    }
    if (motor / fast > 100000u) {
        return fail(err, err_len, "option --motor-frame: expected at most 100000 fast steps, got %llu",
                    (unsigned long long)(motor / fast));
    }
    c->fast_per_medium = (uint32_t)(motor / fast);
    c->medium_per_control = (uint32_t)(control / motor);
    c->medium_per_slow = (uint32_t)(slow / motor); /* below 2^32: slow <= 10 s, motor >= 2 us */
    return true;
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
    case OPT_SET:
        if (o->n_sets >= CLI_MAX_SETS) {
            return fail(err, err_len, "option --set: at most %d overrides", CLI_MAX_SETS);
        }
        o->sets[o->n_sets++] = value;
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
    case OPT_PORT: {
        double v = 0.0;
        size_t used = 0;
        size_t n = strlen(value);
        if (!parse_number(value, n, &v, &used) || used != n || !(v >= 0.0 && v <= 65535.0) ||
            v != (double)(unsigned)v) {
            return fail(err, err_len, "option %s: expected a port number in [0, 65535], got '%s'",
                        spec->name, value);
        }
        *(double *)(void *)field = v;
        return true;
    }
    case OPT_FRAME: {
        uint64_t ns = frame_ns_of(value);
        if (ns == 0u) {
            return fail(err, err_len,
                        "option %s: expected a time with its unit (us, ms or s) up to 10 s, "
                        "such as 200us or 50ms, got '%s'",
                        spec->name, value);
        }
        *(uint64_t *)(void *)field = ns;
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
    o->view_port = 8026.0;
    if (argc >= 2 && strcmp(argv[1], "derivs") == 0) {
        if (argc != 3) {
            return fail(err, err_len, "derivs: expected exactly one CSV file");
        }
        o->action = CLI_DERIVS;
        o->derivs_path = argv[2];
        return true;
    }
    if (argc >= 2 && strcmp(argv[1], "view") == 0) {
        if (argc != 3 || argv[2][0] == '\0') {
            return fail(err, err_len, "view: expected exactly one folder, the run's (such as out)");
        }
        o->action = CLI_VIEW;
        o->view_dir = argv[2];
        return true;
    }
    int first = 1;
    if (argc >= 2 && strcmp(argv[1], "params") == 0) {
        o->action = CLI_PARAMS;
        first = 2;
    }
    for (int i = first; i < argc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            o->action = CLI_HELP;
            return true;
        }
        if (strcmp(a, "--version") == 0) {
            o->action = CLI_VERSION;
            return true;
        }
        if (a[0] != '-') {
            return fail(err, err_len, "unexpected argument '%s': options start with --; a "
                        "scenario file is given as --scenario %s", a, a);
        }
        /* --name=value is --name value. */
        const char *eq = strchr(a, '=');
        size_t name_len = (eq != NULL) ? (size_t)(eq - a) : strlen(a);
        const opt_spec *spec = NULL;
        for (size_t k = 0; k < sizeof options / sizeof options[0]; k++) {
            if (strlen(options[k].name) == name_len && strncmp(a, options[k].name, name_len) == 0) {
                spec = &options[k];
            }
        }
        if (spec == NULL) {
            return fail(err, err_len, "unknown option '%.*s' (see --help)", (int)name_len, a);
        }
        const char *value = NULL;
        if (eq != NULL) {
            if (spec->kind == OPT_FLAG || eq[1] == '\0') {
                return fail(err, err_len, "option %s: %s", spec->name,
                            spec->kind == OPT_FLAG ? "takes no value" : "expected a value");
            }
            value = eq + 1;
        } else if (spec->kind != OPT_FLAG) {
            if (i + 1 >= argc || argv[i + 1][0] == '\0') {
                return fail(err, err_len, "option %s: expected a value", a);
            }
            value = argv[++i];
        }
        if (!set_option(spec, value, o, err, err_len)) {
            return false;
        }
    }
    /* --dead-time is an override of the set's key, the last one. */
    if (o->dead_time_ns != 0u) {
        if (o->n_sets >= CLI_MAX_SETS) {
            return fail(err, err_len, "option --set: at most %d overrides", CLI_MAX_SETS - 1);
        }
        snprintf(o->dead_time_set, sizeof o->dead_time_set, "pwm.dead_time=%llu ns",
                 (unsigned long long)o->dead_time_ns);
        o->sets[o->n_sets++] = o->dead_time_set;
    }
    if (o->action == CLI_PARAMS) {
        return true;
    }
    if (o->emit_c_path != NULL) {
        return fail(err, err_len, "option --emit-c: only with uuvsim params");
    }
    if (o->scenario_path == NULL) {
        return fail(err, err_len, "no scenario: expected --scenario FILE (see --help)");
    }
    if (!apply_frames(o, err, err_len)) {
        return false;
    }
    if (o->view) {
        o->realtime = true;
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
