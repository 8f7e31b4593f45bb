/*
 * The uuvsim command line (see cli.h).
 */
#include "cli.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "sim.h"
#include "util/parse.h"

const char cli_usage[] =
    "usage: uuvsim [options] --scenario FILE\n"
    "       uuvsim derivs FILE.csv\n"
    "\n"
    "Runs a scenario on the simulated vehicle and prints a summary.\n"
    "\n"
    "options:\n"
    "  --scenario FILE        scenario file (see scenarios/*.scn)\n"
    "  --duration S           simulated time [s] (default: the scenario's)\n"
    "  --plant vessel|full    vessel alone, shaft speed through its lag (default vessel)\n"
    "  --propulsion mss|paper thrust law (default paper)\n"
    "  --csv FILE             slow-rate telemetry, one row per 100 ms frame\n"
    "  --json                 summary as JSON on stdout\n"
    "  --quiet                no summary (errors only)\n"
    "  --help, --version\n"
    "\n"
    "derivs FILE.csv: reads commands and states in the layout of the reference\n"
    "derivative vectors and prints the same layout with the derivatives computed\n"
    "by the vessel model (MSS propulsion, actuator lag).\n";

static bool fail(char *err, size_t len, const char *format, ...)
    __attribute__((format(printf, 3, 4)));

static bool fail(char *err, size_t len, const char *format, ...) {
    va_list args;
    va_start(args, format);
    (void)vsnprintf(err, len, format, args);
    va_end(args);
    return false;
}

static bool choose(const char *value, const char *const *names, int count, int *out) {
    for (int i = 0; i < count; i++) {
        if (strcmp(value, names[i]) == 0) {
            *out = i;
            return true;
        }
    }
    return false;
}

bool cli_parse(int argc, char **argv, cli_options *o, char *err, size_t err_len) {
    static const char *const plants[] = {"vessel", "full"};
    static const char *const laws[] = {"mss", "paper"};
    *o = (cli_options){0};
    o->action = CLI_RUN;
    o->plant = SIM_PLANT_VESSEL;
    o->propulsion = VESSEL_PROP_PAPER;
    int i = 1;
    if (argc >= 2 && strcmp(argv[1], "derivs") == 0) {
        if (argc != 3) {
            return fail(err, err_len, "derivs: expected exactly one CSV file");
        }
        o->action = CLI_DERIVS;
        o->derivs_path = argv[2];
        return true;
    }
    for (; i < argc; i++) {
        const char *a = argv[i];
        const char *v = (i + 1 < argc) ? argv[i + 1] : NULL;
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            o->action = CLI_HELP;
            return true;
        }
        if (strcmp(a, "--version") == 0) {
            o->action = CLI_VERSION;
            return true;
        }
        if (strcmp(a, "--json") == 0) {
            o->json = true;
            continue;
        }
        if (strcmp(a, "--quiet") == 0) {
            o->quiet = true;
            continue;
        }
        bool takes_value = strcmp(a, "--scenario") == 0 || strcmp(a, "--csv") == 0 ||
                           strcmp(a, "--duration") == 0 || strcmp(a, "--plant") == 0 ||
                           strcmp(a, "--propulsion") == 0;
        if (!takes_value) {
            return fail(err, err_len, "unknown option '%s' (see --help)", a);
        }
        if (v == NULL || v[0] == '\0') {
            return fail(err, err_len, "option %s: expected a value", a);
        }
        i++;
        if (strcmp(a, "--scenario") == 0) {
            o->scenario_path = v;
        } else if (strcmp(a, "--csv") == 0) {
            o->csv_path = v;
        } else if (strcmp(a, "--duration") == 0) {
            size_t used = 0;
            size_t n = strlen(v);
            if (!parse_number(v, n, &o->duration_s, &used) || used != n ||
                !(o->duration_s > 0.0 && o->duration_s <= 1e6)) {
                return fail(err, err_len,
                            "option --duration: expected seconds in (0, 1e6], got '%s'", v);
            }
        } else if (strcmp(a, "--plant") == 0) {
            if (!choose(v, plants, 2, &o->plant)) {
                return fail(err, err_len, "option --plant: expected vessel or full, got '%s'",
                            v);
            }
        } else {
            if (!choose(v, laws, 2, &o->propulsion)) {
                return fail(err, err_len,
                            "option --propulsion: expected mss or paper, got '%s'", v);
            }
        }
    }
    if (o->scenario_path == NULL) {
        return fail(err, err_len, "no scenario: expected --scenario FILE (see --help)");
    }
    return true;
}
